//! The deterministic parameters of a measurement campaign and what they do to the model:
//! `T_meas = X·D₁'(θ₁)···Dₙ'(θₙ)·M'·Y` (noise aside), with X the robot base in the
//! tracker's frame, Y the marker in the tip frame (position-only: a point, Y = (I, m)),
//! and the calibrated kinematics `Dᵢ' = Exp(Sᵢ''·(θᵢ + δᵢ))`, `Sᵢ'' = Ad(Exp(κᵢ))·Sᵢ`,
//! `M' = M·Exp(μ)`, folded into the chain by `ppoe::chain::fold_calibration`.
//!
//! Every parameter is a perturbation of a reference [`Point`]: X ← X₀·Exp(x), Y ← Y₀·Exp(y)
//! (right, in the base and marker frames; position-only m ← m₀ + y), δ ← δ₀ + d, κᵢ ← κᵢ₀ +
//! Bᵢ·c (Bᵢ: the axis corrections that move joint i's axis — for a revolute joint the two
//! rotations about lines through the axis point perpendicular to it and the two
//! translations perpendicular to it; for a prismatic one the two rotations of its
//! direction — so rotation about, or sliding along, the axis itself, which change nothing,
//! are not parameters), μ ← μ₀ + u. The home correction is a parameter only where the
//! marker is not estimated: M'·Y is all the data see, so with Y estimated μ is exactly
//! redundant and fixed at zero (the gauge: the URDF's tip frame stays the tool frame).

use nalgebra::{DMatrix, DVector, Vector6};
use ppoe::chain::{fold_calibration, Joint, JointKind};
use ppoe::{se3, Transform, Vec3, Vec6};

/// Which deterministic parameters are estimated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Estimate {
    /// X: the robot base in the tracker's frame.
    pub base: bool,
    /// Y: the marker in the tip frame (a point for position-only data).
    pub tip: bool,
    /// δᵢ: every joint's zero offset.
    pub offsets: bool,
    /// κᵢ and μ: every joint's axis and the home pose (product-of-exponentials kinematic
    /// calibration).
    pub kinematics: bool,
}

impl Estimate {
    /// Nothing: the data are in the base frame, the marker is at the tip frame, the
    /// kinematics are the nominal ones.
    pub const NONE: Estimate = Estimate {
        base: false,
        tip: false,
        offsets: false,
        kinematics: false,
    };

    /// Everything.
    pub const ALL: Estimate = Estimate {
        base: true,
        tip: true,
        offsets: true,
        kinematics: true,
    };

    /// Whether nothing is estimated.
    pub fn is_none(&self) -> bool {
        *self == Self::NONE
    }

    /// The names of the estimated groups (`base`, `tip`, `offsets`, `kinematics`).
    pub fn names(&self) -> Vec<&'static str> {
        [
            (self.base, "base"),
            (self.tip, "tip"),
            (self.offsets, "offsets"),
            (self.kinematics, "kinematics"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect()
    }
}

/// A complete set of deterministic parameters: the reference every perturbation is
/// applied to.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Point {
    pub x: Transform<f64>,
    pub y: Transform<f64>,
    pub offsets: Vec<f64>,
    pub kappa: Vec<Vec6<f64>>,
    pub mu: Vec6<f64>,
}

impl Point {
    /// The nominal kinematics with X and Y given.
    pub fn nominal(n: usize, x: Transform<f64>, y: Transform<f64>) -> Self {
        Self {
            x,
            y,
            offsets: vec![0.0; n],
            kappa: vec![Vec6::zeros(); n],
            mu: Vec6::zeros(),
        }
    }

    /// The folded (calibrated) chain and its home pose, without Y.
    pub fn chain(
        &self,
        joints: &[Joint<f64>],
        home: &Transform<f64>,
    ) -> Option<(Vec<Joint<f64>>, Transform<f64>)> {
        let mut j = joints.to_vec();
        let mut h = *home;
        fold_calibration(&mut j, &mut h, &self.offsets, &self.kappa, &self.mu).ok()?;
        Some((j, h))
    }
}

/// Which groups are parameters, for a chain of these joint kinds, in the order base (6),
/// tip (6, or 3 position-only), offsets (n), axis corrections (per joint 4 or 2), home
/// correction (6).
#[derive(Clone, Debug)]
pub(crate) struct Layout {
    pub estimate: Estimate,
    pub position: bool,
    /// With kinematics and offsets: consecutive joints (i − 1, i) with parallel axes, whose
    /// offsets' difference is a link length along the arm (the gauge puts it in the
    /// offsets; reported as undetermined).
    pub parallel_pairs: Vec<(usize, usize)>,
    /// The joints whose offsets are parameters (see `offset_joints`).
    offset_joints: Vec<usize>,
    /// Per joint: its axis-correction basis (4 or 2 twists), empty without kinematics.
    bases: Vec<Vec<Vec6<f64>>>,
}

/// Two unit vectors perpendicular to `w` and to each other.
fn perpendicular(w: &Vec3<f64>) -> (Vec3<f64>, Vec3<f64>) {
    let a = w.0.map(f64::abs);
    let e = if a[0] <= a[1] && a[0] <= a[2] {
        Vec3::from([1., 0., 0.])
    } else if a[1] <= a[2] {
        Vec3::from([0., 1., 0.])
    } else {
        Vec3::from([0., 0., 1.])
    };
    let u = w.cross(&e);
    let u = u * (1.0 / u.norm());
    (u, w.cross(&u))
}

/// The twists that move joint `j`'s axis (see the module docs), each tagged with whether
/// it changes the axis's direction.
fn axis_basis(j: &Joint<f64>) -> Vec<(Vec6<f64>, bool)> {
    let (w, v) = (j.screw.rotation(), j.screw.translation());
    let zero = Vec3::from([0.0; 3]);
    if j.kind == JointKind::Prismatic {
        let (u1, u2) = perpendicular(&(v * (1.0 / v.norm())));
        return vec![
            (Vec6::from_parts(u1, zero), true),
            (Vec6::from_parts(u2, zero), true),
        ];
    }
    // The axis point nearest the origin, q = ω × v (unit ω); a rotation about the line
    // through q along u is the twist (u, q × u).
    let q = w.cross(&v);
    let (u1, u2) = perpendicular(&w);
    vec![
        (Vec6::from_parts(u1, q.cross(&u1)), true),
        (Vec6::from_parts(u2, q.cross(&u2)), true),
        (Vec6::from_parts(zero, u1), false),
        (Vec6::from_parts(zero, u2), false),
    ]
}

/// The Lie bracket `ad(a)·b` (the core's `se3::curly_hat`): how screw b changes when
/// twist a moves it.
fn bracket(a: &Vec6<f64>, b: &Vec6<f64>) -> Vector6<f64> {
    Vector6::from(se3::curly_hat(a).mul_vec(b).0)
}

/// Consecutive revolute joints with parallel axes (see `Layout::parallel_pairs`).
fn parallel_pairs(joints: &[Joint<f64>], e: &Estimate) -> Vec<(usize, usize)> {
    if !(e.kinematics && e.offsets) {
        return Vec::new();
    }
    let revolute = |j: &Joint<f64>| j.kind != JointKind::Prismatic;
    (1..joints.len())
        .filter(|&i| revolute(&joints[i - 1]) && revolute(&joints[i]))
        .filter(|&i| {
            let (a, b) = (joints[i - 1].screw.rotation(), joints[i].screw.rotation());
            a.cross(&b).norm() < 1e-6
        })
        .map(|i| (i - 1, i))
        .collect()
}

/// The joints whose zero offsets are parameters when offsets are estimated: all but the
/// first with the base estimated (its offset is X's rotation about — or, prismatic,
/// translation along — the first axis) and all but the last with the marker or the home
/// correction estimated (its offset is a motion of the tip frame): those are the gauge,
/// held at zero and reported as such.
fn offset_joints(n: usize, e: &Estimate) -> Vec<usize> {
    if !e.offsets {
        return Vec::new();
    }
    let last_free = e.tip || e.kinematics;
    (0..n)
        .filter(|&i| !((i == 0 && e.base) || (i + 1 == n && last_free)))
        .collect()
}

/// Joint `i`'s axis-correction basis with the gauge directions removed: the motions of
/// its axis that other estimated parameters make exactly too. Moving joint i−1's zero
/// rotates every later axis about axis i−1, so with offsets estimated that motion of axis
/// i is dropped and the offset carries it, as a Denavit–Hartenberg θ offset does; with the
/// base estimated, the first axis defines the base frame (no correction of its own) and
/// sliding the base along the first axis moves the second axis (dropped too). Each drop
/// removes a *direction* change where the motion has one (so axis positions — link
/// lengths — stay parameters), else a position change (parallel axes, where a pair of
/// offsets and a link length along the arm are the same motion).
fn gauged_basis(joints: &[Joint<f64>], i: usize, estimate: &Estimate) -> Vec<Vec6<f64>> {
    if i == 0 && estimate.base {
        return Vec::new();
    }
    let mut basis = axis_basis(&joints[i]);
    let mut gauges = Vec::new();
    // Joint i−1's offset, or for the second joint X's rotation about the first axis.
    if i > 0 && (estimate.offsets || (i == 1 && estimate.base)) {
        gauges.push(joints[i - 1].screw);
    }
    if i == 1 && estimate.base && joints[0].kind != JointKind::Prismatic {
        gauges.push(Vec6::from_parts(
            Vec3::from([0.0; 3]),
            joints[0].screw.rotation(),
        ));
    }
    for g in gauges {
        basis = without_motion(&basis, &joints[i].screw, &g);
    }
    basis.into_iter().map(|(b, _)| b).collect()
}

/// `basis` (twists tagged: moves the axis's direction) without the combination that
/// moves `screw` as twist `g` does (least squares in the coefficients; nothing removed if
/// `g` does not move it): among the direction-moving elements if the motion has a part
/// there, else among the position-moving ones.
fn without_motion(
    basis: &[(Vec6<f64>, bool)],
    screw: &Vec6<f64>,
    g: &Vec6<f64>,
) -> Vec<(Vec6<f64>, bool)> {
    let m = basis.len();
    let e = DMatrix::from_fn(6, m, |r, k| bracket(&basis[k].0, screw)[r]);
    let t = DVector::from_column_slice(bracket(g, screw).as_slice());
    if m == 0 || t.norm() < 1e-9 * e.norm().max(1e-300) {
        return basis.to_vec();
    }
    let Ok(c) = e.svd(true, true).solve(&t, 1e-12) else {
        return basis.to_vec();
    };
    let part = |rot: bool| -> f64 {
        (0..m)
            .filter(|&k| basis[k].1 == rot)
            .map(|k| c[k] * c[k])
            .sum::<f64>()
            .sqrt()
    };
    let rot = part(true) > 1e-6 * c.norm();
    if part(rot) < 1e-12 {
        return basis.to_vec();
    }
    let group: Vec<usize> = (0..m).filter(|&k| basis[k].1 == rot).collect();
    let mut out: Vec<(Vec6<f64>, bool)> = basis.iter().filter(|b| b.1 != rot).copied().collect();
    // The group's elements orthogonal to c's part in it: eigenvectors of I − ĉĉᵀ with
    // eigenvalue 1.
    let cg = DVector::from_iterator(group.len(), group.iter().map(|&k| c[k]));
    let cg = &cg / cg.norm();
    let p = DMatrix::identity(group.len(), group.len()) - &cg * cg.transpose();
    let eig = p.symmetric_eigen();
    for k in (0..group.len()).filter(|&k| eig.eigenvalues[k] > 0.5) {
        let mut b = Vec6::zeros();
        for (&g, coef) in group.iter().zip(eig.eigenvectors.column(k).iter()) {
            b += basis[g].0 * *coef;
        }
        out.push((b, rot));
    }
    out
}

impl Layout {
    /// The layout of `estimate` for `joints` (the nominal chain: the axis bases are its
    /// axes').
    pub fn new(estimate: Estimate, position: bool, joints: &[Joint<f64>]) -> Self {
        let bases = if estimate.kinematics {
            (0..joints.len())
                .map(|i| gauged_basis(joints, i, &estimate))
                .collect()
        } else {
            Vec::new()
        };
        Self {
            estimate,
            position,
            parallel_pairs: parallel_pairs(joints, &estimate),
            offset_joints: offset_joints(joints.len(), &estimate),
            bases,
        }
    }

    fn tip_len(&self) -> usize {
        if self.position {
            3
        } else {
            6
        }
    }

    fn home_correction(&self) -> bool {
        self.estimate.kinematics && !self.estimate.tip
    }

    /// The parameter blocks: (group, start, length).
    fn blocks(&self) -> Vec<(&'static str, usize, usize)> {
        let e = &self.estimate;
        let sizes = [
            ("base", if e.base { 6 } else { 0 }),
            ("tip", if e.tip { self.tip_len() } else { 0 }),
            ("offsets", self.offset_joints.len()),
            ("kinematics", self.bases.iter().map(Vec::len).sum()),
            ("home", if self.home_correction() { 6 } else { 0 }),
        ];
        let mut start = 0;
        sizes
            .into_iter()
            .map(|(g, len)| {
                let b = (g, start, len);
                start += len;
                b
            })
            .collect()
    }

    /// Where group `g` starts and how long it is.
    pub fn block(&self, g: &str) -> (usize, usize) {
        let b = self.blocks().into_iter().find(|b| b.0 == g);
        b.map_or((0, 0), |(_, s, l)| (s, l))
    }

    /// Number of parameters.
    pub fn len(&self) -> usize {
        self.blocks().iter().map(|b| b.2).sum()
    }

    /// The point perturbed by `p` from `at`.
    pub fn apply(&self, p: &[f64], at: &Point) -> Point {
        let mut out = at.clone();
        let v6 = |s: usize| Vec6::from(std::array::from_fn(|i| p[s + i]));
        let (s, l) = self.block("base");
        if l > 0 {
            out.x = at.x * se3::exp(&v6(s));
        }
        let (s, l) = self.block("tip");
        if l == 6 {
            out.y = at.y * se3::exp(&v6(s));
        } else if l == 3 {
            out.y.translation =
                Vec3::from(std::array::from_fn(|i| at.y.translation.0[i] + p[s + i]));
        }
        let (s, _) = self.block("offsets");
        for (k, &i) in self.offset_joints.iter().enumerate() {
            out.offsets[i] += p[s + k];
        }
        let (mut s, _) = self.block("kinematics");
        for (i, basis) in self.bases.iter().enumerate() {
            for b in basis {
                out.kappa[i] += *b * p[s];
                s += 1;
            }
        }
        let (s, l) = self.block("home");
        if l > 0 {
            out.mu = at.mu + v6(s);
        }
        out
    }

    /// The parameters' names.
    pub fn names(&self, joints: &[Joint<f64>]) -> Vec<String> {
        const AXES: [&str; 6] = ["rx", "ry", "rz", "x", "y", "z"];
        let mut out = Vec::with_capacity(self.len());
        let (_, l) = self.block("base");
        out.extend((0..l).map(|k| format!("base_in_tracker.{}", AXES[k])));
        let (_, l) = self.block("tip");
        let tip = if l == 3 { &AXES[3..] } else { &AXES[..l] };
        out.extend(tip.iter().map(|a| format!("marker_in_tip.{a}")));
        out.extend(
            self.offset_joints
                .iter()
                .map(|&i| format!("offset of joint '{}'", joints[i].name)),
        );
        for (i, basis) in self.bases.iter().enumerate() {
            out.extend(
                (0..basis.len()).map(|k| format!("axis of joint '{}' [{k}]", joints[i].name)),
            );
        }
        let (_, l) = self.block("home");
        out.extend((0..l).map(|k| format!("home.{}", AXES[k])));
        out
    }

    /// The covariance of joint `i`'s axis correction κᵢ (6×6) from the parameters'
    /// covariance `cov`, and of the home correction.
    pub fn kappa_cov(&self, cov: &nalgebra::DMatrix<f64>, i: usize) -> nalgebra::Matrix6<f64> {
        let (mut s, _) = self.block("kinematics");
        s += self.bases[..i].iter().map(Vec::len).sum::<usize>();
        let b = &self.bases[i];
        let bm = nalgebra::DMatrix::from_fn(6, b.len(), |r, c| b[c].0[r]);
        let c = cov.view((s, s), (b.len(), b.len()));
        let out = &bm * c * bm.transpose();
        nalgebra::Matrix6::from_fn(|r, c| out[(r, c)])
    }

    /// The parameter index of joint `i`'s offset, if it is one.
    pub fn offset_index(&self, i: usize) -> Option<usize> {
        let (s, _) = self.block("offsets");
        self.offset_joints
            .iter()
            .position(|&j| j == i)
            .map(|k| s + k)
    }

    /// Where joint `i`'s axis-correction parameters start and how many there are.
    pub fn joint_block(&self, i: usize) -> (usize, usize) {
        let (s, _) = self.block("kinematics");
        let start = s + self.bases[..i].iter().map(Vec::len).sum::<usize>();
        (start, self.bases[i].len())
    }

    /// Whether joint axis corrections are parameters.
    pub fn has_kinematics(&self) -> bool {
        !self.bases.is_empty()
    }
}
