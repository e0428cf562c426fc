//! Kinematic chains: screw axes in the base frame, the home pose of the tip, joint kinds
//! and limits; rigid forward kinematics and the PPOE.

use crate::error::Error;
use crate::linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
use crate::scalar::Real;
use crate::se3::{self, mirror_lower, Congruence, Pack, Transform};
use crate::so3;
use crate::uncertainty::{check_covariance, concat_globally, Order};

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
    /// The constants of [`Joint::displacement`] derived from `screw`, if computed:
    /// [`Joint::prepared`], [`Joint::from_f64`] and `ppoe-build`'s tables have them;
    /// [`Joint::new`] (a `const fn`, which cannot compute them) has `None`, and then each
    /// call derives them again (BENCHMARKS.md: `ppoe_seed/ours_joint_new`). Recompute
    /// them after changing `screw`; [`ChainRef::check`] verifies them.
    pub constants: Option<JointConstants<T>>,
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
    /// division by t, so no series branch. Accuracy: a few ε absolute in R and
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
    fn matches(&self, screw: &Vec6<T>, tol: T) -> bool {
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
    /// this, with [`JointConstants::of`] of the screw).
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

    /// The joint with its displacement constants computed ([`JointConstants::of`] of the
    /// screw; `None` for a joint that does not rotate): the fast path of
    /// [`Joint::displacement`] for chains built at run time.
    ///
    /// Non-finite constants (from a screw so large or small that v/‖ω‖ overflows) are not
    /// kept: such a joint stays on the per-call path, whose result is the same.
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

/// A serial kinematic chain of `N` moving joints from a base link to a tip link.
///
/// The forward kinematics is the product of exponentials
/// `T(θ) = Exp(S₁θ₁)·…·Exp(Sₙθₙ)·M` with screw axes Sᵢ in the base frame (rotation first)
/// and the home pose M (tip to base at θ = 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chain<T, const N: usize> {
    /// Name of the base link.
    pub base: &'static str,
    /// Name of the tip link.
    pub tip: &'static str,
    /// The moving joints from base to tip.
    pub joints: [Joint<T>; N],
    /// The home pose M: tip to base at θ = 0.
    pub home: Transform<T>,
}

impl<T: Real, const N: usize> Chain<T, N> {
    /// A chain; usable in `const` items (this is what `ppoe-build` emits).
    #[inline]
    pub const fn new(
        base: &'static str,
        tip: &'static str,
        joints: [Joint<T>; N],
        home: Transform<T>,
    ) -> Self {
        Self {
            base,
            tip,
            joints,
            home,
        }
    }
}

/// Which covariance the PPOE returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Convention {
    /// Right (local) perturbation of the returned pose: `T = T̄·Exp(η)`, η ~ N(0, Σ),
    /// η in the tip frame. `Σ = Ad(M⁻¹)·C·Ad(M⁻¹)ᵀ`. The default: Monte Carlo puts it
    /// within 1.4–5.6 % of the true distribution at the seed's noise (MATH.md §8).
    #[default]
    Right,
    /// Left (global) perturbation: `T = Exp(η)·T̄`, η in the base frame,
    /// `Σ_left = Ad(T̄)·Σ_right·Ad(T̄)ᵀ` — the convention of the rest of
    /// pytransform3d's `uncertainty` module.
    Left,
    /// pytransform3d's example, reproduced exactly: `Ad(M)·C·Ad(M)ᵀ` in the last step,
    /// and continuous joints clipped to their stated limits. For migration and
    /// comparison only: it is the covariance of neither perturbation (164 % median error
    /// on the seed robot, MATH.md §8).
    Pytransform3d,
}

impl<T: Real> UncertainPose<T> {
    /// A pose without uncertainty (zero covariance).
    #[inline]
    pub fn certain(pose: Transform<T>) -> Self {
        Self {
            pose,
            cov: Mat6::zeros(),
        }
    }
}

/// A pose and the covariance of its exponential-coordinate perturbation (rotation
/// first); the [`Convention`] that produced it says which perturbation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UncertainPose<T> {
    /// The mean pose T̄ (tip to base).
    pub pose: Transform<T>,
    /// The 6×6 covariance.
    pub cov: Mat6<T>,
}

crate::linalg::approx_fields!([T: Real] UncertainPose<T> { pose, cov });

/// A chain whose joints live in a slice: the runtime-sized counterpart of [`Chain`]
/// (used by host tools that load a URDF at run time). Same algorithms, same code path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainRef<'a, T> {
    /// The moving joints from base to tip.
    pub joints: &'a [Joint<T>],
    /// The home pose M: tip to base at θ = 0.
    pub home: Transform<T>,
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
    /// and a ω whose 1/‖ω‖ overflows goes through [`se3::exp`]. ≈ 40 % fewer operations
    /// than [`se3::exp`] with the constants derived, ≈ 60 % with them given.
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

impl<'a, T: Real> ChainRef<'a, T> {
    /// Clips joint values to the limits into `out` (see [`Joint::clip`]).
    pub fn clip(&self, thetas: &[T], out: &mut [T], clip_continuous: bool) -> Result<(), Error> {
        if thetas.len() != self.joints.len() || out.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        for ((o, t), j) in out.iter_mut().zip(thetas).zip(self.joints) {
            *o = j.clip(*t, clip_continuous);
        }
        Ok(())
    }

    /// Rigid forward kinematics `Exp(S₁θ₁)·…·Exp(Sₙθₙ)·M` after clipping θ to the limits.
    pub fn forward_kinematics(&self, thetas: &[T]) -> Result<Transform<T>, Error> {
        if thetas.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        let mut t = Transform::identity();
        for (j, theta) in self.joints.iter().zip(thetas) {
            t = t * j.displacement(j.clip(*theta, false));
        }
        Ok(t * self.home)
    }

    /// Space Jacobian (columns `Ad(D₁…Dᵢ₋₁)·Sᵢ`, twists in the base frame, rotation
    /// first) at the clipped θ, written into `out` (one column per joint).
    pub fn space_jacobian(&self, thetas: &[T], out: &mut [Vec6<T>]) -> Result<(), Error> {
        if thetas.len() != self.joints.len() || out.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        let mut t = Transform::identity();
        for ((col, j), theta) in out.iter_mut().zip(self.joints).zip(thetas) {
            *col = t.adjoint() * j.screw;
            t = t * j.displacement(j.clip(*theta, false));
        }
        Ok(())
    }

    /// Body Jacobian (columns `Ad(T(θ)⁻¹)·Jₛ,ᵢ`, twists in the tip frame, rotation first)
    /// at the clipped θ, written into `out`.
    pub fn body_jacobian(&self, thetas: &[T], out: &mut [Vec6<T>]) -> Result<(), Error> {
        self.space_jacobian(thetas, out)?;
        let ad = self.forward_kinematics(thetas)?.inverse().adjoint();
        for col in out.iter_mut() {
            *col = ad * *col;
        }
        Ok(())
    }

    /// The PPOE, unchecked: tip pose and covariance for joint values `thetas` (clipped to
    /// the limits first) and per-joint covariances `covs` of the model
    /// `T = D₁·Exp(ξ₁)·D₂·Exp(ξ₂)·…·Dₙ·Exp(ξₙ)·M`, `Dᵢ = Exp(Sᵢθᵢ)`, ξᵢ ~ N(0, covsᵢ)
    /// (rotation first, base-frame screw coordinates).
    ///
    /// Method: Meyer, Strobl & Triebel, *The Probabilistic Robot Kinematics Model*, IROS
    /// 2022: `C ← Ad(Dᵢ⁻¹)·C·Ad(Dᵢ⁻¹)ᵀ + covsᵢ` per joint (second order), then the last
    /// step chosen by `convention`. Computed unrolled, one structured transport per joint
    /// ([`Transform::transport_covariance`]) and none at the end: Right sums
    /// `Ad(Gᵢ⁻¹)·covsᵢ·Ad(Gᵢ⁻¹)ᵀ`, `Gᵢ = Dᵢ₊₁…Dₙ·M`, from the tip backwards (lever arms
    /// from each joint to the tip); Left sums `Ad(Pᵢ)·covsᵢ·Ad(Pᵢ)ᵀ`, `Pᵢ = D₁…Dᵢ`.
    /// Only one triangle is accumulated; the result is exactly symmetric. Non-finite or
    /// non-PSD inputs give meaningless (possibly NaN) output but never panic; see
    /// [`ChainRef::ppoe_checked`].
    pub fn ppoe(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        if thetas.len() != self.joints.len() || covs.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        // The lane count is a constant of T: only one arm is compiled in.
        Ok(match T::TRANSPORT_LANES {
            2 => self.ppoe_lanes::<2>(thetas, covs, convention),
            _ => self.ppoe_lanes::<1>(thetas, covs, convention),
        })
    }

    /// [`ChainRef::ppoe`] after the length check, W transports at a time: the joints
    /// go in groups of W, each group's W congruences and covariances are built as locals
    /// and transported in the W lanes together; the group at the far end is padded with
    /// zero covariances. (Queuing them in a buffer until W were pending made the lane
    /// gathers load what had just been stored field by field: store-forwarding stalls.)
    #[inline(always)]
    fn ppoe_lanes<const W: usize>(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
    ) -> UncertainPose<T> {
        let clip_continuous = convention == Convention::Pytransform3d;
        let n = self.joints.len();
        let zero = Mat6::zeros();
        let mut acc = [[Pack([T::ZERO; W]); 6]; 6];
        // Explicit loops over the lanes, no closures: `core::array::from_fn` and closures
        // were left as calls here, each spilling every register.
        let pose = if convention == Convention::Left {
            // Base frame: Σ_left = Σᵢ Ad(Pᵢ)·covᵢ·Ad(Pᵢ)ᵀ, Pᵢ = D₁…Dᵢ (the reference's sum
            // moved by Ad(Pₙ)); one transport per joint and none at the end.
            let mut p = Transform::identity();
            for m in 0..n.div_ceil(W) {
                let mut group = [(Congruence::of(&p), &zero); W];
                for (k, slot) in group.iter_mut().enumerate() {
                    let i = m * W + k;
                    if let (Some(j), Some(t), Some(cov)) =
                        (self.joints.get(i), thetas.get(i), covs.get(i))
                    {
                        p = p.compose(&j.displacement(j.clip(*t, clip_continuous)));
                        *slot = (Congruence::of(&p), cov);
                    }
                }
                Congruence::add_lower_packed(&group, &mut acc);
            }
            p * self.home
        } else {
            // Tip frame, from the tip backwards: Σ_right = Σᵢ Ad(Gᵢ⁻¹)·covᵢ·Ad(Gᵢ⁻¹)ᵀ with
            // Gᵢ = Dᵢ₊₁…Dₙ·M (the reference's recursion unrolled, then moved by Ad(M⁻¹)).
            // One transport per joint and none at the end, and each uses the lever arm
            // from joint i to the tip, not through the base and back. The reference's
            // variant starts from Gₙ = I and moves the sum by Ad(M) instead.
            let mut g = if convention == Convention::Right {
                self.home
            } else {
                Transform::identity()
            };
            for m in 0..n.div_ceil(W) {
                let mut group = [(Congruence::of_inverse(&g), &zero); W];
                for (k, slot) in group.iter_mut().enumerate() {
                    // Joint n − 1 − (m·W + k); none below 0 (padding lanes).
                    let i = n.wrapping_sub(m * W + k + 1);
                    if let (Some(j), Some(t), Some(cov)) =
                        (self.joints.get(i), thetas.get(i), covs.get(i))
                    {
                        *slot = (Congruence::of_inverse(&g), cov);
                        g = j.displacement(j.clip(*t, clip_continuous)).compose(&g);
                    }
                }
                Congruence::add_lower_packed(&group, &mut acc);
            }
            if convention == Convention::Right {
                g
            } else {
                g * self.home
            }
        };
        let cov = sum_lanes(&acc);
        let cov = if convention == Convention::Pytransform3d {
            self.home.transport_covariance(&cov)
        } else {
            cov
        };
        UncertainPose { pose, cov }
    }

    /// Checks the chain itself: finite screw axes with a unit rotation part (revolute) or
    /// zero rotation and unit translation part (prismatic) within [`Real::TOL`], limits not
    /// NaN, displacement constants (where given) those of the screw within [`Real::TOL`],
    /// and a valid home pose ([`Transform::check`]). A non-unit axis is
    /// [`Error::ZeroAxis`] if its relevant part is exactly zero, else
    /// [`Error::NotUnitAxis`].
    pub fn check(&self) -> Result<(), Error> {
        self.home.check()?;
        for j in self.joints {
            if !j.screw.is_finite() || j.lower.is_nan() || j.upper.is_nan() {
                return Err(Error::NonFinite);
            }
            let (w, v) = (j.screw.rotation().norm(), j.screw.translation().norm());
            let unit = match j.kind {
                JointKind::Prismatic => w == T::ZERO && (v - T::ONE).abs() <= T::TOL,
                _ => (w - T::ONE).abs() <= T::TOL,
            };
            if !unit {
                let length = if j.kind == JointKind::Prismatic { v } else { w };
                return Err(crate::checks::axis_length_error(length));
            }
            if let Some(k) = &j.constants {
                if !k.matches(&j.screw, T::TOL) {
                    return Err(Error::InconsistentConstants);
                }
            }
        }
        Ok(())
    }

    /// The PPOE with input checks: the chain ([`ChainRef::check`]), every θ finite, every
    /// covariance finite, symmetric and positive semi-definite within tolerance
    /// ([`check_covariance`]); then [`ChainRef::ppoe`], whose result is validated too:
    /// [`Error::Overflow`] if it is not finite (e.g. huge link lengths times large
    /// covariances overflow inside).
    ///
    /// The output is exactly symmetric. It is positive semi-definite within rounding when
    /// the input covariances are PSD. An input that is *indefinite within the tolerance*
    /// (accepted by [`check_covariance`], smallest eigenvalue down to −[`Real::TOL`]·‖Σ‖)
    /// stays indefinite through the congruences `Ad·Σ·Adᵀ` (Sylvester's law of inertia),
    /// and its negative eigenvalue can grow relative to ‖Σ‖ by up to κ(Ad)², i.e. with the
    /// square of the lever arms: the output may then fail [`check_covariance`] although
    /// it is the exact propagation of the input (found by fuzzing: an f32 input with
    /// λ_min = −4·10⁻⁵·‖Σ‖ gave −6·10⁻⁴·λ_max, the same in f64). Give PSD inputs, e.g. from
    /// [`screw_noise`], [`bending_noise`] or a factor `L·Lᵀ`.
    pub fn ppoe_checked(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        self.check()?;
        if !thetas.iter().all(|t| t.is_finite()) {
            return Err(Error::NonFinite);
        }
        for c in covs {
            check_covariance(c)?;
        }
        let out = self.ppoe(thetas, covs, convention)?;
        crate::checks::validate_uncertain_pose(&out.pose, &out.cov)?;
        Ok(out)
    }

    /// Higher-order PPOE: the Barfoot & Furgale fourth-order compounding
    /// ([`concat_globally`] with [`Order::FourthPsd`], so the result is PSD for PSD
    /// inputs; with the raw [`Order::Fourth`] the seed robot with random PSD joint
    /// covariances reached λmin = −0.08·λmax) applied once per joint in the global
    /// form, factor i = `(Dᵢ, Ad(Dᵢ)·covsᵢ·Ad(Dᵢ)ᵀ)`, then converted to `convention`
    /// (Right or Left; Pytransform3d is treated as Right). Closer to Monte Carlo at large
    /// noise (MATH.md §8); several times the cost of [`ChainRef::ppoe`] (`BENCHMARKS.md`).
    /// Unchecked.
    pub fn ppoe_fourth_order(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        if thetas.len() != self.joints.len() || covs.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        let mut p = Transform::identity();
        let mut c = Mat6::zeros();
        for ((j, theta), cov) in self.joints.iter().zip(thetas).zip(covs) {
            let d = j.displacement(j.clip(*theta, false));
            let global = d.transport_covariance(cov);
            (p, c) = concat_globally(&d, &global, &p, &c, Order::FourthPsd);
        }
        let pose = p * self.home;
        let cov = match convention {
            Convention::Left => c,
            _ => pose.inverse().transport_covariance(&c),
        };
        Ok(UncertainPose { pose, cov })
    }
}

impl<T: Real, const N: usize> Chain<T, N> {
    /// The slice view of this chain (same algorithms).
    #[inline]
    pub fn as_ref(&self) -> ChainRef<'_, T> {
        ChainRef {
            joints: &self.joints,
            home: self.home,
        }
    }

    /// Joint values clipped to the limits (`np.clip` semantics; continuous joints are not
    /// clipped).
    pub fn clip(&self, thetas: &[T; N]) -> [T; N] {
        let mut out = *thetas;
        for (o, j) in out.iter_mut().zip(&self.joints) {
            *o = j.clip(*o, false);
        }
        out
    }

    /// Rigid forward kinematics `Exp(S₁θ₁)·…·Exp(Sₙθₙ)·M` (tip to base) at the clipped θ.
    pub fn forward_kinematics(&self, thetas: &[T; N]) -> Transform<T> {
        self.as_ref()
            .forward_kinematics(thetas)
            .unwrap_or_else(|_| Transform::identity())
    }

    /// Space Jacobian at the clipped θ: 6×N, column i = `Ad(D₁…Dᵢ₋₁)·Sᵢ` (base frame,
    /// rotation first).
    pub fn space_jacobian(&self, thetas: &[T; N]) -> Matrix<T, 6, N> {
        let mut cols = [Vec6::zeros(); N];
        let _ = self.as_ref().space_jacobian(thetas, &mut cols);
        columns_to_matrix(&cols)
    }

    /// Body Jacobian at the clipped θ: 6×N, column i = `Ad(T⁻¹)·Jₛ,ᵢ` (tip frame,
    /// rotation first).
    pub fn body_jacobian(&self, thetas: &[T; N]) -> Matrix<T, 6, N> {
        let mut cols = [Vec6::zeros(); N];
        let _ = self.as_ref().body_jacobian(thetas, &mut cols);
        columns_to_matrix(&cols)
    }

    /// The PPOE (unchecked): pose and covariance in the given convention. See
    /// [`ChainRef::ppoe`] for the model and method.
    ///
    /// ```
    /// use ppoe::chain::{Chain, Convention, Joint, JointKind};
    /// use ppoe::{Mat6, Transform};
    /// const INF: f64 = f64::INFINITY;
    /// // A planar 2-link arm: joints about z at x = 0 and x = 0.5, tip at x = 1.
    /// const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
    ///     Joint::new("j1", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
    ///     Joint::new("j2", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
    /// ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
    /// let covs = [ppoe::chain::screw_noise(&ARM.joints[0].screw, 1e-4),
    ///             ppoe::chain::screw_noise(&ARM.joints[1].screw, 1e-4)];
    /// let tip = ARM.ppoe(&[0.3, -0.2], &covs, Convention::Right);
    /// assert!(tip.cov.0[2][2] > 1e-4); // yaw variance of the tip: both joints add up
    /// ```
    pub fn ppoe(
        &self,
        thetas: &[T; N],
        covs: &[Mat6<T>; N],
        convention: Convention,
    ) -> UncertainPose<T> {
        self.as_ref()
            .ppoe(thetas, covs, convention)
            .unwrap_or_else(|_| UncertainPose::certain(Transform::identity()))
    }

    /// The PPOE with input checks (see [`ChainRef::ppoe_checked`]).
    pub fn ppoe_checked(
        &self,
        thetas: &[T; N],
        covs: &[Mat6<T>; N],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        self.as_ref().ppoe_checked(thetas, covs, convention)
    }

    /// The fourth-order PPOE (see [`ChainRef::ppoe_fourth_order`]).
    pub fn ppoe_fourth_order(
        &self,
        thetas: &[T; N],
        covs: &[Mat6<T>; N],
        convention: Convention,
    ) -> UncertainPose<T> {
        self.as_ref()
            .ppoe_fourth_order(thetas, covs, convention)
            .unwrap_or_else(|_| UncertainPose::certain(Transform::identity()))
    }
}

/// The sum over the W lanes of the lower triangle accumulated by
/// [`Congruence::add_lower_packed`], mirrored: exactly symmetric.
#[inline(always)]
fn sum_lanes<T: Real, const W: usize>(lanes: &[[Pack<T, W>; 6]; 6]) -> Mat6<T> {
    let mut acc = [[T::ZERO; 6]; 6];
    for (arow, lrow) in acc.iter_mut().zip(lanes) {
        for (a, l) in arow.iter_mut().zip(lrow) {
            // Lane 0 plus the others (all 36, only the lower triangle is kept).
            *a = l.0.iter().skip(1).fold(l.0[0], |s, x| s + *x);
        }
    }
    mirror_lower(acc)
}

/// Joint-value noise as a joint covariance: `σ²·S·Sᵀ` for screw axis S (base frame,
/// rotation first). Exact for the model: `Exp(S(θ+δ)) = Exp(Sθ)·Exp(Sδ)`, so δ ~ N(0, σ²)
/// is the right perturbation ξ = S·δ of the joint's displacement.
#[inline]
pub fn screw_noise<T: Real>(screw: &Vec6<T>, sigma2: T) -> Mat6<T> {
    screw.outer(screw).scale(sigma2)
}

/// Link bending as a joint covariance: a small rotation ω ~ N(0, `cov_omega`) (base-frame
/// axes) about the point `pivot` (base frame), i.e. ξ = (ω, pivot × ω) and
/// `Σ = G·cov_omega·Gᵀ`, `G = [I; [pivot]×]`. The seed example's covariances are this
/// with `pivot = 0` and `cov_omega = 0.05·e eᵀ` for a base axis e.
#[inline]
pub fn bending_noise<T: Real>(pivot: &Vec3<T>, cov_omega: &Mat3<T>) -> Mat6<T> {
    let c = *cov_omega;
    let p = so3::hat(pivot);
    let pc = p * c;
    Mat6::from_blocks(&c, &pc.transpose(), &pc, &c.congruence(&p))
}

/// Stacks N 6-vectors as the columns of a 6×N matrix.
fn columns_to_matrix<T: Real, const N: usize>(cols: &[Vec6<T>; N]) -> Matrix<T, 6, N> {
    let mut m = Matrix::zeros();
    for (j, c) in cols.iter().enumerate() {
        for (row, x) in m.0.iter_mut().zip(c.0.iter()) {
            if let Some(slot) = row.get_mut(j) {
                *slot = *x;
            }
        }
    }
    m
}
