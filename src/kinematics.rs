//! Kinematic chains: [`Chain`] (N joints, a `const` table) and its borrowed view
//! [`ChainView`]; rigid forward kinematics, Jacobians and the checks of the chain itself.
//! Below the PPOE, which adds its methods to both types; users reach both through
//! `ppoe::chain`.

use crate::error::Error;
use crate::linalg::{Matrix, Vec6};
use crate::scalar::Real;
use crate::se3::Transform;

use crate::joint::{Joint, JointKind};

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

/// A view of a chain whose joints live in a slice: the runtime-sized counterpart of
/// [`Chain`] (used by host tools that load a URDF at run time, and by [`Chain`] itself
/// through [`Chain::as_ref`]). Same algorithms, same code path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainView<'a, T> {
    /// The moving joints from base to tip.
    pub joints: &'a [Joint<T>],
    /// The home pose M: tip to base at θ = 0.
    pub home: Transform<T>,
}

impl<'a, T: Real> ChainView<'a, T> {
    /// Clips joint values to the limits into `out` (see [`Joint::clip`]).
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `thetas` and `out` have one element per joint.
    pub fn clip(&self, thetas: &[T], out: &mut [T], clip_continuous: bool) -> Result<(), Error> {
        if thetas.len() != self.joints.len() || out.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        for ((o, t), j) in out.iter_mut().zip(thetas).zip(self.joints) {
            *o = j.clip(*t, clip_continuous);
        }
        Ok(())
    }

    /// Rigid forward kinematics `Exp(S₁θ₁)·…·Exp(Sₙθₙ)·M` (tip to base) after clipping θ
    /// to the limits.
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `thetas` have one element per joint.
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
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `thetas` and `out` have one element per joint.
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
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `thetas` and `out` have one element per joint.
    pub fn body_jacobian(&self, thetas: &[T], out: &mut [Vec6<T>]) -> Result<(), Error> {
        self.space_jacobian(thetas, out)?;
        let ad = self.forward_kinematics(thetas)?.inverse().adjoint();
        for col in out.iter_mut() {
            *col = ad * *col;
        }
        Ok(())
    }

    /// Checks the chain itself: finite screw axes with a unit rotation part (revolute) or
    /// zero rotation and unit translation part (prismatic) within [`Real::TOL`], limits not
    /// NaN, displacement constants (where given) those of the screw within [`Real::TOL`],
    /// and a valid home pose ([`Transform::check`]).
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a non-finite screw or NaN limit, [`Error::ZeroAxis`] for a
    /// screw axis whose relevant part (rotation; translation for a prismatic joint) is
    /// exactly zero, [`Error::NotUnitAxis`] for one of another non-unit length, [`Error::InconsistentConstants`] for
    /// displacement constants that are not those of the screw, and the errors of
    /// [`Transform::check`] for the home pose.
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
            if let Some(k) = &j.constants() {
                if !k.matches(&j.screw, T::TOL) {
                    return Err(Error::InconsistentConstants);
                }
            }
        }
        Ok(())
    }
}

impl<T: Real, const N: usize> Chain<T, N> {
    /// The slice view of this chain (same algorithms).
    #[inline]
    pub fn as_ref(&self) -> ChainView<'_, T> {
        ChainView {
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
    ///
    /// ```
    /// use ppoe::chain::{Chain, Joint, JointKind};
    /// use ppoe::Transform;
    /// const INF: f64 = f64::INFINITY;
    /// // A planar arm: joints about z through x = 0 and x = 0.5, tip at x = 1 at home.
    /// const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
    ///     Joint::new("shoulder", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
    ///     Joint::new("elbow", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
    /// ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
    /// let t = ARM.forward_kinematics(&[0.3, -0.2]);
    /// let (x, y) = (0.5 * (0.3_f64.cos() + 0.1_f64.cos()), 0.5 * (0.3_f64.sin() + 0.1_f64.sin()));
    /// approx::assert_abs_diff_eq!(t.translation, ppoe::Vec3::new(x, y, 0.0), epsilon = 1e-15);
    /// assert!((t.rotation.0[1][0] - 0.1_f64.sin()).abs() < 1e-15); // tip yaw 0.3 − 0.2
    /// assert_eq!(ARM.forward_kinematics(&[0.0, 0.0]), ARM.home); // θ = 0: the home pose
    /// ```
    pub fn forward_kinematics(&self, thetas: &[T; N]) -> Transform<T> {
        self.as_ref()
            .forward_kinematics(thetas)
            .unwrap_or_else(|_| Transform::identity())
    }

    /// Space Jacobian at the clipped θ: 6×N, column i = `Ad(D₁…Dᵢ₋₁)·Sᵢ` (base frame,
    /// rotation first).
    ///
    /// ```
    /// use ppoe::chain::{Chain, Joint, JointKind};
    /// use ppoe::Transform;
    /// const INF: f64 = f64::INFINITY;
    /// // A planar arm: joints about z through x = 0 and x = 0.5, tip at x = 1 at home.
    /// const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
    ///     Joint::new("shoulder", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
    ///     Joint::new("elbow", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
    /// ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
    /// let js = ARM.space_jacobian(&[0.3, -0.2]);
    /// // Column 1 is S₁; column 2 is the elbow's axis where the shoulder moved it: about z
    /// // through q = 0.5·(cos 0.3, sin 0.3, 0), i.e. (0, 0, 1, q_y, −q_x, 0).
    /// let q = [0.5 * 0.3_f64.cos(), 0.5 * 0.3_f64.sin()];
    /// assert_eq!(js.column(0), ARM.joints[0].screw);
    /// let expected = ppoe::Vector([0.0, 0.0, 1.0, q[1], -q[0], 0.0]);
    /// approx::assert_abs_diff_eq!(js.column(1), expected, epsilon = 1e-15);
    /// ```
    pub fn space_jacobian(&self, thetas: &[T; N]) -> Matrix<T, 6, N> {
        let mut cols = [Vec6::zeros(); N];
        let _ = self.as_ref().space_jacobian(thetas, &mut cols);
        columns_to_matrix(&cols)
    }

    /// Body Jacobian at the clipped θ: 6×N, column i = `Ad(T⁻¹)·Jₛ,ᵢ` (tip frame,
    /// rotation first).
    ///
    /// ```
    /// use ppoe::chain::{Chain, Joint, JointKind};
    /// use ppoe::Transform;
    /// const INF: f64 = f64::INFINITY;
    /// // A planar arm: joints about z through x = 0 and x = 0.5, tip at x = 1 at home.
    /// const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
    ///     Joint::new("shoulder", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
    ///     Joint::new("elbow", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
    /// ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
    /// let jb = ARM.body_jacobian(&[0.3, -0.2]);
    /// // Seen from the tip, the elbow is 0.5 behind it on the tip's x axis: turning the
    /// // elbow moves the tip along its own y axis at 0.5 m/rad.
    /// let expected = ppoe::Vector([0.0, 0.0, 1.0, 0.0, 0.5, 0.0]);
    /// approx::assert_abs_diff_eq!(jb.column(1), expected, epsilon = 1e-15);
    /// ```
    pub fn body_jacobian(&self, thetas: &[T; N]) -> Matrix<T, 6, N> {
        let mut cols = [Vec6::zeros(); N];
        let _ = self.as_ref().body_jacobian(thetas, &mut cols);
        columns_to_matrix(&cols)
    }
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
