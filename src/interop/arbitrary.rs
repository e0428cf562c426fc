//! `arbitrary::Arbitrary` (feature `arbitrary`; the `arbitrary` crate needs `std`, so
//! this is for host-side fuzzing and property tests): generators of **valid** values, so
//! that a fuzz target or a property test exercises ppoe's algorithms rather than its
//! input checks.
//!
//! | type | what is generated | guaranteed |
//! |---|---|---|
//! | [`Rotation<T>`] | the rotation of a unit quaternion with elements drawn in [−1, 1] (identity if all ≈ 0) | orthonormal, det +1 ([`so3::is_rotation`] within [`Real::TOL`]) |
//! | [`Transform<T>`] | a [`Rotation`] and a translation in [−10, 10]³ | [`Transform::check`] passes |
//! | [`Covariance<T, N>`] | `s·A·Aᵀ`, A with entries in [−1, 1] and rank 0 to N (columns beyond the rank zero), scale s = 10⁻ᵏ, k in 0..=8 | symmetric (exactly) and positive semi-definite ([`check_covariance`] passes) |
//! | [`JointKind`], [`Convention`] | any variant | |
//! | [`Joint<T>`] | revolute/continuous: unit axis ŝ through a point q in [−1, 1]³, screw `(ŝ, q × ŝ)`; prismatic: `(0, ŝ)`; limits in [−π, 0] and [0, π] (prismatic [−1, 0], [0, 1]), continuous unbounded; constants computed ([`Joint::prepared`]) | the joint alone passes [`ChainView::check`] |
//! | [`Chain<T, N>`] | N arbitrary joints (named `j0`, `j1`, … from a fixed list), base `base`, tip `tip`, an arbitrary home pose | [`ChainView::check`] passes |
//! | [`UncertainPose<T>`] | an arbitrary pose and 6×6 covariance | both of the above |
//!
//! Every value is built from the bytes without rejection sampling, so any byte string
//! (including an empty one) gives a valid value.
//!
//! ```
//! use arbitrary::{Arbitrary, Unstructured};
//! use ppoe::chain::Chain;
//! use ppoe::interop::arbitrary::Covariance;
//! let bytes = [7u8; 512];
//! let mut u = Unstructured::new(&bytes);
//! let chain = Chain::<f64, 6>::arbitrary(&mut u).unwrap();
//! assert!(chain.as_ref().check().is_ok());
//! let cov = Covariance::<f64, 6>::arbitrary(&mut u).unwrap();
//! assert!(ppoe::uncertainty::check_covariance(&cov.0).is_ok());
//! ```

use arbitrary::{Arbitrary, Result, Unstructured};

use crate::chain::{Chain, Convention, Joint, JointKind, UncertainPose};
use crate::linalg::{Mat3, Matrix, Vec3, Vector};
use crate::rotation_forms::matrix_from_quaternion;
use crate::scalar::Real;
use crate::se3::Transform;
#[cfg(doc)]
use crate::{chain::ChainView, so3, uncertainty::check_covariance};

/// A rotation matrix (orthonormal, det +1) whose `Arbitrary` implementation generates
/// only valid rotations (see the module table).
///
/// ```
/// use arbitrary::{Arbitrary, Unstructured};
/// use ppoe::interop::arbitrary::Rotation;
/// let r = Rotation::<f32>::arbitrary(&mut Unstructured::new(&[1, 2, 3, 4, 5, 6, 7, 8])).unwrap();
/// assert!(ppoe::so3::is_rotation(&r.0, 1e-6));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rotation<T>(pub Mat3<T>);

/// An N×N covariance (symmetric, positive semi-definite) whose `Arbitrary`
/// implementation generates only valid covariances, of every rank (see the module table).
///
/// ```
/// use arbitrary::{Arbitrary, Unstructured};
/// use ppoe::interop::arbitrary::Covariance;
/// let c = Covariance::<f64, 3>::arbitrary(&mut Unstructured::new(&[9; 64])).unwrap();
/// assert_eq!(c.0, c.0.transpose());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Covariance<T, const N: usize>(pub Matrix<T, N, N>);

/// A number in [−1, 1] from 4 bytes (0 when the bytes run out).
fn unit<T: Real>(u: &mut Unstructured<'_>) -> Result<T> {
    let x = u32::arbitrary(u)?;
    Ok(T::lit(f64::from(x) / f64::from(u32::MAX) * 2.0 - 1.0))
}

/// A unit 3-vector (z when the drawn vector is too short to normalise reliably).
fn unit_axis<T: Real>(u: &mut Unstructured<'_>) -> Result<Vec3<T>> {
    let v = Vector([unit(u)?, unit(u)?, unit(u)?]);
    let n = v.norm();
    Ok(if n > T::lit(1e-3) {
        v.scale(T::ONE / n)
    } else {
        Vector([T::ZERO, T::ZERO, T::ONE])
    })
}

impl<'a, T: Real> Arbitrary<'a> for Rotation<T> {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let q: [T; 4] = [unit(u)?, unit(u)?, unit(u)?, unit(u)?];
        let small = q.iter().all(|v| v.abs() < T::lit(1e-3));
        let r = if small {
            Ok(Mat3::identity())
        } else {
            matrix_from_quaternion(&q)
        };
        // Finite and non-zero by construction; identity is the fallback nonetheless.
        Ok(Rotation(r.unwrap_or_else(|_| Mat3::identity())))
    }
}

impl<'a, T: Real> Arbitrary<'a> for Transform<T> {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let rotation = Rotation::arbitrary(u)?.0;
        let ten = T::lit(10.0);
        let mut translation = Vec3::zeros();
        for v in translation.0.iter_mut() {
            *v = unit::<T>(u)? * ten;
        }
        Ok(Transform {
            rotation,
            translation,
        })
    }
}

impl<'a, T: Real, const N: usize> Arbitrary<'a> for Covariance<T, N> {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let rank = usize::from(u8::arbitrary(u)?) % (N + 1);
        let k = u8::arbitrary(u)? % 9;
        let scale = T::lit(libm::pow(10.0, -f64::from(k)));
        let mut a = Matrix::<T, N, N>::zeros();
        for row in a.0.iter_mut() {
            for v in row.iter_mut().take(rank) {
                *v = unit(u)?;
            }
        }
        Ok(Covariance(Matrix::identity().scale(scale).congruence(&a)))
    }
}

impl<'a> Arbitrary<'a> for JointKind {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        Ok(match u8::arbitrary(u)? % 3 {
            0 => JointKind::Revolute,
            1 => JointKind::Continuous,
            _ => JointKind::Prismatic,
        })
    }
}

impl<'a> Arbitrary<'a> for Convention {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        Ok(match u8::arbitrary(u)? % 3 {
            0 => Convention::Right,
            1 => Convention::Left,
            _ => Convention::Pytransform3d,
        })
    }
}

/// Joint names of generated chains (`&'static str`: generated values cannot borrow
/// names from the input bytes for `'static`).
const NAMES: [&str; 16] = [
    "j0", "j1", "j2", "j3", "j4", "j5", "j6", "j7", "j8", "j9", "j10", "j11", "j12", "j13", "j14",
    "j15",
];

/// An arbitrary valid joint named `name`.
fn joint<T: Real>(u: &mut Unstructured<'_>, name: &'static str) -> Result<Joint<T>> {
    let kind = JointKind::arbitrary(u)?;
    let s = unit_axis::<T>(u)?;
    let (screw, range) = match kind {
        JointKind::Prismatic => (Vector::from_parts(Vec3::zeros(), s), T::ONE),
        _ => {
            let q = Vector([unit(u)?, unit(u)?, unit(u)?]);
            (Vector::from_parts(s, q.cross(&s)), T::PI())
        }
    };
    let (lower, upper) = match kind {
        JointKind::Continuous => (T::neg_infinity(), T::infinity()),
        _ => (-unit::<T>(u)?.abs() * range, unit::<T>(u)?.abs() * range),
    };
    Ok(Joint::new(name, kind, screw.0, lower, upper).prepared())
}

impl<'a, T: Real> Arbitrary<'a> for Joint<T> {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let i = usize::from(u8::arbitrary(u)?) % NAMES.len();
        joint(u, NAMES[i])
    }
}

impl<'a, T: Real, const N: usize> Arbitrary<'a> for Chain<T, N> {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let mut joints = [Joint::new("", JointKind::Revolute, [T::ZERO; 6], T::ZERO, T::ZERO); N];
        for (i, j) in joints.iter_mut().enumerate() {
            *j = joint(u, NAMES[i % NAMES.len()])?;
        }
        let home = Transform::arbitrary(u)?;
        Ok(Chain::new("base", "tip", joints, home))
    }
}

impl<'a, T: Real> Arbitrary<'a> for UncertainPose<T> {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        Ok(UncertainPose {
            pose: Transform::arbitrary(u)?,
            cov: Covariance::<T, 6>::arbitrary(u)?.0,
        })
    }
}
