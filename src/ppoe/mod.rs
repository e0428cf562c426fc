//! The Probabilistic Product of Exponentials: the tip pose of a chain and the covariance
//! of its perturbation, from joint values and per-joint covariances. Its types
//! ([`Convention`], [`UncertainPose`]) and dense entry points (methods of [`ChainView`]
//! and [`Chain`]) are here; the instruction schedule of the dense loop in `schedule.rs`,
//! the variant for one variance per joint in `rank1.rs`. Users reach all of it through
//! `ppoe::chain`, which re-exports the types.

use crate::error::Error;
use crate::kinematics::{Chain, ChainView};
use crate::linalg::Mat6;
use crate::scalar::Real;
use crate::se3::Transform;
use crate::uncertainty::{check_covariance, concat_globally, Order};

mod batch;
#[cfg(test)]
mod batch_tests;
#[cfg(test)]
mod lane_tests;
mod packed;
mod rank1;
mod schedule;

pub use batch::BatchError;
pub use rank1::dense_covariances;

/// Test-only door to the schedules of other targets, for the `lanes_ratio` benchmark.
#[cfg(ppoe_bench_lanes)]
impl<T: Real> ChainView<'_, T> {
    /// [`ChainView::ppoe`] with `lanes` transports side by side (1, 2 or 4; any other
    /// value gives 1). Exists only in builds with `--cfg ppoe_bench_lanes`.
    ///
    /// # Errors
    ///
    /// As [`ChainView::ppoe`].
    #[doc(hidden)]
    pub fn ppoe_with_lanes(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
        lanes: usize,
    ) -> Result<UncertainPose<T>, Error> {
        if thetas.len() != self.joints.len() || covs.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        Ok(schedule::with_lanes(self, thetas, covs, convention, lanes))
    }
}

/// Which covariance the PPOE returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Convention {
    /// Right (local) perturbation of the returned pose: `T = T̄·Exp(η)`, η ~ N(0, Σ),
    /// η in the tip frame. `Σ = Ad(M⁻¹)·C·Ad(M⁻¹)ᵀ`. The default: the covariance of the
    /// sampled perturbation to second order (Monte Carlo: within a few % at the seed
    /// robot's noise; by noise level in ACCURACY.md, shipped with this package).
    #[default]
    Right,
    /// Left (global) perturbation: `T = Exp(η)·T̄`, η in the base frame,
    /// `Σ_left = Ad(T̄)·Σ_right·Ad(T̄)ᵀ` — the convention of the rest of
    /// pytransform3d's `uncertainty` module.
    Left,
    /// pytransform3d's example, reproduced exactly: `Ad(M)·C·Ad(M)ᵀ` in the last step,
    /// and continuous joints clipped to their stated limits. For migration and
    /// comparison only: it is the covariance of neither perturbation (Monte Carlo: more
    /// than 30 % off on the seed robot; ACCURACY.md).
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

impl<'a, T: Real> ChainView<'a, T> {
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
    /// [`ChainView::ppoe_checked`].
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `thetas` and `covs` have one element per joint.
    pub fn ppoe(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        if thetas.len() != self.joints.len() || covs.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        Ok(schedule::ppoe(self, thetas, covs, convention))
    }

    /// The PPOE with input checks: the chain ([`ChainView::check`]), every θ finite, every
    /// covariance finite, symmetric and positive semi-definite within tolerance
    /// ([`check_covariance`]); then [`ChainView::ppoe`], whose result is validated too:
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
    /// [`screw_noise`](crate::chain::screw_noise),
    /// [`bending_noise`](crate::chain::bending_noise) or a factor `L·Lᵀ`.
    ///
    /// # Errors
    ///
    /// Those of [`ChainView::check`] for the chain, [`Error::NonFinite`] for a non-finite
    /// θ, those of [`check_covariance`] for a covariance, then those of [`ChainView::ppoe`],
    /// and [`Error::Overflow`] for a non-finite result.
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
    /// noise (ACCURACY.md, section 1); several times the cost of [`ChainView::ppoe`] (`BENCHMARKS.md`).
    /// Unchecked.
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `thetas` and `covs` have one element per joint.
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
    /// The PPOE (unchecked): pose and covariance in the given convention. See
    /// [`ChainView::ppoe`] for the model and method.
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
    /// // Right convention: η in the tip frame, Σ = σ²·J_b·J_bᵀ for joint-value noise. The
    /// // yaw variances of both joints add up; along the tip's y axis the elbow (0.5 m
    /// // away) and the shoulder (0.5 + 0.5·cos 0.2 m along the link direction) add theirs.
    /// assert!((tip.cov.0[2][2] - 2e-4).abs() < 1e-18);
    /// let var_y = 1e-4 * (0.25 + (0.5 + 0.5 * 0.2_f64.cos()).powi(2));
    /// assert!((tip.cov.0[4][4] - var_y).abs() < 1e-18);
    /// let fk = ARM.forward_kinematics(&[0.3, -0.2]);
    /// approx::assert_abs_diff_eq!(tip.pose, fk, epsilon = 1e-15); // the mean: rigid FK
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

    /// The PPOE with input checks (see [`ChainView::ppoe_checked`]).
    ///
    /// # Errors
    ///
    /// As [`ChainView::ppoe_checked`] (the lengths always match).
    ///
    /// # Example
    ///
    /// ```
    /// # use ppoe::chain::{screw_noise, Chain, Convention, Joint, JointKind};
    /// # use ppoe::Transform;
    /// # const INF: f64 = f64::INFINITY;
    /// # // The planar arm of [`Chain::ppoe`].
    /// # const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
    /// #     Joint::new("j1", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
    /// #     Joint::new("j2", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
    /// # ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
    /// let covs = ARM.joints.map(|j| screw_noise(&j.screw, 1e-4));
    /// let tip = ARM.ppoe_checked(&[0.3, -0.2], &covs, Convention::Right)?;
    /// assert_eq!(tip, ARM.ppoe(&[0.3, -0.2], &covs, Convention::Right)); // valid input
    /// // A negative variance is not a covariance; a NaN joint value is not a position.
    /// let bad = ARM.joints.map(|j| screw_noise(&j.screw, -1e-4));
    /// let err = ARM.ppoe_checked(&[0.3, -0.2], &bad, Convention::Right);
    /// assert_eq!(err, Err(ppoe::Error::NotPositiveSemidefinite));
    /// let err = ARM.ppoe_checked(&[f64::NAN, 0.0], &covs, Convention::Right);
    /// assert_eq!(err, Err(ppoe::Error::NonFinite));
    /// # Ok::<(), ppoe::Error>(())
    /// ```
    pub fn ppoe_checked(
        &self,
        thetas: &[T; N],
        covs: &[Mat6<T>; N],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        self.as_ref().ppoe_checked(thetas, covs, convention)
    }

    /// The fourth-order PPOE (see [`ChainView::ppoe_fourth_order`]).
    ///
    /// ```
    /// # use ppoe::chain::{screw_noise, Chain, Convention, Joint, JointKind};
    /// # use ppoe::Transform;
    /// # const INF: f64 = f64::INFINITY;
    /// # // The planar arm of [`Chain::ppoe`].
    /// # const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
    /// #     Joint::new("j1", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
    /// #     Joint::new("j2", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
    /// # ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
    /// let covs = ARM.joints.map(|j| screw_noise(&j.screw, 1e-4));
    /// let second = ARM.ppoe(&[0.3, -0.2], &covs, Convention::Right);
    /// let fourth = ARM.ppoe_fourth_order(&[0.3, -0.2], &covs, Convention::Right);
    /// approx::assert_abs_diff_eq!(fourth.pose, second.pose, epsilon = 1e-15); // same mean
    /// // The fourth-order terms are products of two covariances: relative to Σ they are
    /// // of the order of the variances (here 10⁻⁴ rad²), so at small noise both agree.
    /// let rel = (fourth.cov - second.cov).amax() / second.cov.amax();
    /// assert!(rel > 0.0 && rel < 1e-3);
    /// ```
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
