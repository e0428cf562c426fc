//! Joints: the joint model of a chain (kind, screw axis, limits), its displacement
//! `Exp(S·θ)` from precomputed constants, and joint noise models (covariances of the
//! joint's right perturbation, base-frame screw coordinates, rotation first).
//!
//! ```
//! use ppoe::chain::{Joint, JointKind};
//! use ppoe::Vec3;
//! // Revolute about z through (1, 0, 0): screw axis (ŝ, q × ŝ) = (0, 0, 1, 0, −1, 0).
//! let j = Joint::new("j", JointKind::Revolute, [0., 0., 1., 0., -1., 0.], -4.0, 4.0);
//! // A half turn carries the base origin around the axis to (2, 0, 0).
//! let d = j.displacement(core::f64::consts::PI);
//! approx::assert_abs_diff_eq!(d.translation, Vec3::new(2.0, 0.0, 0.0), epsilon = 1e-15);
//! ```

use crate::linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
use crate::scalar::Real;
use crate::se3::{self, Transform};
use crate::so3;

/// The kind of a moving joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// Rotation about the screw axis; the value is an angle in radians, clipped to the
    /// limits.
    Revolute,
    /// Rotation without limits (URDF `continuous`). The stored limits are only used by the
    /// pytransform3d-compatible mode, which clips continuous joints like revolute ones.
    Continuous,
    /// Translation along the screw axis; the value is a distance in metres, clipped to the
    /// limits.
    Prismatic,
}

/// One moving joint of a chain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joint<T> {
    /// The joint's name (from the URDF).
    pub name: &'static str,
    /// The joint's kind.
    pub kind: JointKind,
    /// The screw axis S = (ω, v) in the base frame at the home pose, rotation first:
    /// `(ŝ, q × ŝ)` for revolute joints, `(0, ŝ)` for prismatic ones.
    pub screw: Vec6<T>,
    /// Lower limit (may be −∞).
    pub lower: T,
    /// Upper limit (may be +∞).
    pub upper: T,
    /// The constants of [`Joint::displacement`] derived from `screw`, if computed
    /// (private so that they cannot drift from `screw` unnoticed; read them with
    /// [`Joint::constants`]).
    constants: Option<JointConstants<T>>,
}

/// The constants of a joint's displacement `Exp(S·θ)` derived from its screw axis
/// S = (ω, v), rotation first, base frame: with ŵ = ω/‖ω‖ and v̂ = v/‖ω‖, Rodrigues'
/// rotation needs ŵ and the entries of `[ŵ]×²`, and the screw translation
/// `sin t·v̂ + (1 − cos t)·ŵ×v̂ + (t − sin t)·(ŵ·v̂)·ŵ` (t = θ·‖ω‖) needs v̂, ŵ×v̂ and
/// (ŵ·v̂)·ŵ. Computed once ([`JointConstants::of`]), they leave a sin/cos, 19
/// multiplications and 17 additions per joint and call. Only for joints that rotate
/// (ω ≠ 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointConstants<T> {
    /// ‖ω‖, the angle per unit of joint value (1 for URDF joints).
    pub scale: T,
    /// ŵ = ω/‖ω‖.
    pub axis: [T; 3],
    /// (ŵy² + ŵz², ŵx² + ŵz², ŵx² + ŵy²): the diagonal of `−[ŵ]×²`.
    pub axis_sq: [T; 3],
    /// (ŵx·ŵy, ŵx·ŵz, ŵy·ŵz): the off-diagonal entries of `[ŵ]×²`.
    pub axis_prod: [T; 3],
    /// v̂ = v/‖ω‖.
    pub v: [T; 3],
    /// ŵ × v̂.
    pub axis_cross_v: [T; 3],
    /// (ŵ·v̂)·ŵ: the axial part of v̂ (zero for a pure rotation).
    pub axial_v: [T; 3],
}

impl<T: Real> JointConstants<T> {
    /// The constants from their parts; usable in `const` items (`ppoe-build` emits this,
    /// with values from [`JointConstants::of`]).
    #[inline]
    pub const fn new(
        scale: T,
        axis: [T; 3],
        axis_sq: [T; 3],
        axis_prod: [T; 3],
        v: [T; 3],
        axis_cross_v: [T; 3],
        axial_v: [T; 3],
    ) -> Self {
        Self {
            scale,
            axis,
            axis_sq,
            axis_prod,
            v,
            axis_cross_v,
            axial_v,
        }
    }

    /// The constants of the screw S = (ω, v) (rotation first); `None` when 1/‖ω‖ is not
    /// finite (ω = 0: a prismatic joint; a subnormal ω; NaN).
    ///
    /// ‖ω‖ and 1/‖ω‖ of a unit-length ω (every URDF axis): with d = ‖ω‖² − 1, √(1+d) ≈
    /// 1 + d/2 and 1/√(1+d) ≈ 1 − d/2 leave out d²/8 and 3d²/8, below ε/2 for |d| < √ε
    /// ([`Real::TOL`]); otherwise a square root and a division.
    pub fn of(screw: &Vec6<T>) -> Option<Self> {
        let (w, v) = (screw.rotation(), screw.translation());
        let d = w.norm_squared() - T::ONE;
        let (n, inv) = if d.abs() < T::TOL {
            let h = d * T::HALF;
            (T::ONE + h, T::ONE - h)
        } else {
            let n = w.norm();
            (n, T::ONE / n)
        };
        if !inv.is_finite() {
            return None;
        }
        let (x, vh) = (w.scale(inv), v.scale(inv));
        let [a, b, c] = x.0;
        Some(Self {
            scale: n,
            axis: x.0,
            axis_sq: [b * b + c * c, a * a + c * c, a * a + b * b],
            axis_prod: [a * b, a * c, b * c],
            v: vh.0,
            axis_cross_v: x.cross(&vh).0,
            axial_v: x.scale(x.dot(&vh)).0,
        })
    }

    /// `Exp(S·θ)` (no clipping): `R = I + sin t·[ŵ]× + (1 − cos t)·[ŵ]×²` (Rodrigues) and
    /// `p = sin t·v̂ + (1 − cos t)·ŵ×v̂ + (t − sin t)·(ŵ·v̂)·ŵ` with t = θ·‖ω‖ (Lynch &
    /// Park, *Modern Robotics*, §3.3.3, with `ŵ×(ŵ×v̂) = (ŵ·v̂)ŵ − v̂` folded in): no
    /// division by t, so no series branch.
    ///
    /// # Accuracy
    ///
    /// A few ε absolute in R and
    /// ε·‖v̂‖·max(1, |t|) in p, like [`se3::exp`].
    #[inline(always)]
    pub fn displacement(&self, theta: T) -> Transform<T> {
        let t = theta * self.scale;
        let (s, c) = t.sin_cos_r();
        let omc = T::ONE - c;
        let ([x, y, z], [dx, dy, dz], [xy, xz, yz]) = (self.axis, self.axis_sq, self.axis_prod);
        let rotation = Matrix([
            [T::ONE - omc * dx, omc * xy - s * z, omc * xz + s * y],
            [omc * xy + s * z, T::ONE - omc * dy, omc * yz - s * x],
            [omc * xz - s * y, omc * yz + s * x, T::ONE - omc * dz],
        ]);
        let tms = t - s;
        let (v, cv, av) = (self.v, self.axis_cross_v, self.axial_v);
        let translation = Vector([
            s * v[0] + omc * cv[0] + tms * av[0],
            s * v[1] + omc * cv[1] + tms * av[1],
            s * v[2] + omc * cv[2] + tms * av[2],
        ]);
        Transform {
            rotation,
            translation,
        }
    }

    /// Whether every constant is finite.
    pub fn is_finite(&self) -> bool {
        self.scale.is_finite() && self.arrays().iter().flatten().all(|x| x.is_finite())
    }

    /// The six 3-arrays, in the order of [`JointConstants::new`].
    fn arrays(&self) -> [[T; 3]; 6] {
        [
            self.axis,
            self.axis_sq,
            self.axis_prod,
            self.v,
            self.axis_cross_v,
            self.axial_v,
        ]
    }

    /// Whether `self` equals [`JointConstants::of`] of `screw` within `tol` (relative to
    /// max(1, |value|), element-wise).
    pub(crate) fn matches(&self, screw: &Vec6<T>, tol: T) -> bool {
        let Some(k) = Self::of(screw) else {
            return false;
        };
        let near = |a: T, b: T| (a - b).abs() <= tol * T::ONE.max(b.abs());
        near(self.scale, k.scale)
            && self
                .arrays()
                .iter()
                .flatten()
                .zip(k.arrays().iter().flatten())
                .all(|(a, b)| near(*a, *b))
    }
}

impl<T: Real> Joint<T> {
    /// A joint; usable in `const` items (this is what `ppoe-build` emits).
    ///
    /// `screw` is S = (ω, v) in the base frame at the home pose, rotation first: `(ŝ, q × ŝ)`
    /// for a revolute or continuous joint about the unit axis ŝ through q, `(0, ŝ)` for a
    /// prismatic one ([`se3::screw_axis`] computes it). Nothing is checked here
    /// ([`ChainView::check`](crate::chain::ChainView::check) does).
    ///
    /// ```
    /// use ppoe::chain::{Joint, JointKind};
    /// // A prismatic joint along y with a 0.3 m stroke.
    /// const SLIDE: Joint<f64> =
    ///     Joint::new("slide", JointKind::Prismatic, [0., 0., 0., 0., 1., 0.], 0.0, 0.3);
    /// assert_eq!(SLIDE.clip(0.5, false), 0.3); // values are clipped to the limits
    /// assert_eq!(SLIDE.displacement(0.2).translation.0, [0.0, 0.2, 0.0]);
    /// ```
    #[inline]
    pub const fn new(
        name: &'static str,
        kind: JointKind,
        screw: [T; 6],
        lower: T,
        upper: T,
    ) -> Self {
        Self {
            name,
            kind,
            screw: crate::linalg::Vector(screw),
            lower,
            upper,
            constants: None,
        }
    }

    /// [`Joint::new`] with the displacement constants given (`const`; `ppoe-build` emits
    /// this, with [`JointConstants::of`] of the screw). For generated tables: the
    /// constants are not checked here ([`ChainView::check`](crate::chain::ChainView::check) does).
    #[doc(hidden)]
    #[inline]
    pub const fn with_constants(
        name: &'static str,
        kind: JointKind,
        screw: [T; 6],
        lower: T,
        upper: T,
        constants: JointConstants<T>,
    ) -> Self {
        Self {
            constants: Some(constants),
            ..Self::new(name, kind, screw, lower, upper)
        }
    }

    /// The constants of [`Joint::displacement`] derived from the screw, if computed:
    /// [`Joint::prepared`], [`Joint::from_f64`] and `ppoe-build`'s tables have them;
    /// [`Joint::new`] (a `const fn`, which cannot compute them) has `None`, and then each
    /// call derives them again (BENCHMARKS.md, shipped with this package:
    /// `ppoe_seed/ours_joint_new`). They are
    /// those of the screw when the joint was built: call [`Joint::prepared`] again after
    /// changing `screw`; [`ChainView::check`](crate::chain::ChainView::check) verifies them.
    #[inline]
    pub fn constants(&self) -> Option<JointConstants<T>> {
        self.constants
    }

    /// [`Joint::constants`] by reference: the batch PPOE reads them in place (a copy of the
    /// whole `Option`, written field by field, made its vector reads wait on the writes).
    #[inline(always)]
    pub(crate) fn constants_ref(&self) -> Option<&JointConstants<T>> {
        self.constants.as_ref()
    }

    /// The joint with its displacement constants computed ([`JointConstants::of`] of the
    /// screw; `None` for a joint that does not rotate): the fast path of
    /// [`Joint::displacement`] for chains built at run time.
    ///
    /// Non-finite constants (from a screw so large or small that v/‖ω‖ overflows) are not
    /// kept: such a joint stays on the per-call path, whose result is the same.
    ///
    /// ```
    /// use ppoe::chain::{Joint, JointKind};
    /// let j = Joint::new("j", JointKind::Revolute, [0., 1., 0., 0., 0., 0.5], -3.0, 3.0);
    /// assert!(j.constants().is_none()); // `new` is `const`: it cannot compute them
    /// let p = j.prepared();
    /// assert_eq!(p.constants().map(|k| k.axis), Some([0.0, 1.0, 0.0]));
    /// assert_eq!(p.displacement(0.4), j.displacement(0.4)); // the same result, faster
    /// ```
    #[must_use]
    pub fn prepared(mut self) -> Self {
        self.constants = JointConstants::of(&self.screw).filter(JointConstants::is_finite);
        self
    }

    /// The joint `j`, computed in f64 (as `ppoe-build` does), in scalar T: every value
    /// rounded to T, then in ω and in v separately the elements below ε²·max (ε of T) set
    /// to zero ([`Vector::without_negligible`]). That keeps T's products out of the slow
    /// subnormal range and changes no result by more than ε² relative. Then the
    /// displacement constants are computed in T ([`Joint::prepared`]). `ppoe-build`'s
    /// tables and run-time chains are built this way.
    pub fn from_f64(j: &Joint<f64>) -> Self {
        let s = j.screw.0.map(T::lit);
        let w = Vector([s[0], s[1], s[2]]).without_negligible().0;
        let v = Vector([s[3], s[4], s[5]]).without_negligible().0;
        Self::new(
            j.name,
            j.kind,
            [w[0], w[1], w[2], v[0], v[1], v[2]],
            T::lit(j.lower),
            T::lit(j.upper),
        )
        .prepared()
    }
}

/// `np.clip` semantics: `min(max(θ, lower), upper)`; NaN stays NaN, lower > upper gives
/// upper.
#[inline]
fn clip<T: Real>(theta: T, lower: T, upper: T) -> T {
    let x = if theta < lower { lower } else { theta };
    if x > upper {
        upper
    } else {
        x
    }
}

impl<T: Real> Joint<T> {
    /// The joint value clipped to the limits (`np.clip` semantics: NaN stays NaN).
    /// Continuous joints are not clipped unless `clip_continuous` (pytransform3d does).
    #[inline]
    pub fn clip(&self, theta: T, clip_continuous: bool) -> T {
        if self.kind == JointKind::Continuous && !clip_continuous {
            theta
        } else {
            clip(theta, self.lower, self.upper)
        }
    }

    /// The joint's displacement `Exp(S·θ)` (no clipping), S = (ω, v) rotation first:
    /// [`JointConstants::displacement`] with the joint's constants (derived here when
    /// `constants` is `None`, the result is the same); ω = 0 (prismatic) gives `(I, θ·v)`,
    /// and a ω whose 1/‖ω‖ overflows goes through [`se3::exp`]. Fewer operations than
    /// [`se3::exp`] (no series branch, no division), fewest with the constants given.
    #[inline(always)]
    pub fn displacement(&self, theta: T) -> Transform<T> {
        match &self.constants {
            Some(k) => k.displacement(theta),
            None => match JointConstants::of(&self.screw) {
                Some(k) => k.displacement(theta),
                None => self.displacement_degenerate(theta),
            },
        }
    }

    /// [`Joint::displacement`] when 1/‖ω‖ is not finite: ω = 0 (prismatic) gives
    /// `(I, θ·v)`, a tiny nonzero ω (or NaN) goes through [`se3::exp`]. Out of line: the
    /// loops of the PPOE inline the common path.
    #[cold]
    #[inline(never)]
    fn displacement_degenerate(&self, theta: T) -> Transform<T> {
        if self.screw.rotation().norm() == T::ZERO {
            return Transform {
                rotation: Mat3::identity(),
                translation: self.screw.translation().scale(theta),
            };
        }
        se3::exp(&self.screw.scale(theta))
    }
}

/// Joint-value noise as a joint covariance: `σ²·S·Sᵀ` for screw axis S (base frame,
/// rotation first). Exact for the model: `Exp(S(θ+δ)) = Exp(Sθ)·Exp(Sδ)`, so δ ~ N(0, σ²)
/// is the right perturbation ξ = S·δ of the joint's displacement.
///
/// ```
/// use ppoe::{chain::screw_noise, Vector};
/// // σ = 0.01 rad on a joint about z through (1, 0, 0): S = (0, 0, 1, 0, −1, 0).
/// let c = screw_noise(&Vector([0., 0., 1., 0., -1., 0.]), 1e-4);
/// assert_eq!(c.0[2][2], 1e-4); // yaw variance σ²
/// assert_eq!(c.0[4][4], 1e-4); // the origin, 1 m from the axis, moves along −y ...
/// assert_eq!(c.0[2][4], -1e-4); // ... fully correlated with the yaw
/// ```
#[inline]
pub fn screw_noise<T: Real>(screw: &Vec6<T>, sigma2: T) -> Mat6<T> {
    screw.outer(screw).scale(sigma2)
}

/// Link bending as a joint covariance: a small rotation ω ~ N(0, `cov_omega`) (base-frame
/// axes) about the point `pivot` (base frame), i.e. ξ = (ω, pivot × ω) and
/// `Σ = G·cov_omega·Gᵀ`, `G = [I; [pivot]×]`. The seed example's covariances are this
/// with `pivot = 0` and `cov_omega = 0.05·e eᵀ` for a base axis e.
///
/// ```
/// use ppoe::{chain::bending_noise, Mat3, Vec3};
/// // Bending about the base x axis (0.05 rad²) at a pivot 1 m up the z axis: a rotation
/// // ω about x there is the twist (ω, pivot × ω) = (ω, 0, 0, 0, ω, 0).
/// let cov_omega = Mat3::from_rows([[0.05, 0.0, 0.0], [0.0; 3], [0.0; 3]]);
/// let c = bending_noise(&Vec3::new(0.0, 0.0, 1.0), &cov_omega);
/// assert_eq!((c.0[0][0], c.0[4][4], c.0[0][4]), (0.05, 0.05, 0.05));
/// assert_eq!(c.0[3][3] + c.0[5][5], 0.0);
/// ```
#[inline]
pub fn bending_noise<T: Real>(pivot: &Vec3<T>, cov_omega: &Mat3<T>) -> Mat6<T> {
    let c = *cov_omega;
    let p = so3::hat(pivot);
    let pc = p * c;
    Mat6::from_blocks(&c, &pc.transpose(), &pc, &c.congruence(&p))
}
