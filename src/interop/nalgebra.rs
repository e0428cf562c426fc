//! nalgebra conversions (feature `nalgebra`, built with nalgebra's `libm` feature and
//! without its default `std`). nalgebra 0.34 needs Rust 1.87, below ppoe's own minimum
//! (`rust-version`, 1.95), so the feature raises no requirement.
//!
//! | ppoe | nalgebra | direction |
//! |---|---|---|
//! | [`Vector<T, N>`] | `SVector<T, N>` | both, exact |
//! | [`Matrix<T, R, C>`] (row-major) | `SMatrix<T, R, C>` (column-major storage) | both, exact: element `(i, j)` is element `(i, j)` |
//! | [`Transform<T>`] | `IsometryMatrix3<T>` (rotation matrix) | `From` to nalgebra, exact; `TryFrom` back, validated |
//! | [`Transform<T>`] | `Isometry3<T>` (unit quaternion) | `From` to nalgebra; `TryFrom` back, validated |
//!
//! Through `Isometry3` the rotation passes through a quaternion: a round trip
//! reproduces the rotation within 16ε of T (max-element, tested for f32 and f64), not
//! bit for bit; use
//! `IsometryMatrix3` for exact round trips. nalgebra's `Quaternion::new(w, x, y, z)` takes
//! the scalar first like ppoe's `[w, x, y, z]`, but stores `[x, y, z, w]`.
//!
//! ```
//! use ppoe::Transform;
//! let t = Transform::<f64>::from_rpy(&[0.1, 0.2, 0.3], [1.0, 2.0, 3.0])?;
//! let iso: nalgebra::Isometry3<f64> = t.into();
//! let p = iso.transform_point(&nalgebra::Point3::new(1.0, 0.0, 0.0));
//! let q = t.transform_point(&[1.0, 0.0, 0.0].into());
//! assert!((p.x - q.0[0]).abs() < 1e-15);
//! let exact: nalgebra::IsometryMatrix3<f64> = t.into();
//! assert_eq!(Transform::try_from(exact)?, t);
//! # Ok::<(), ppoe::Error>(())
//! ```

use nalgebra::{
    Isometry3, IsometryMatrix3, RealField, Rotation3, SMatrix, SVector, Scalar, Translation3,
    UnitQuaternion,
};

use crate::error::Error;
use crate::linalg::{Mat3, Matrix, Vector};
use crate::scalar::Real;
use crate::se3::Transform;

impl<T: Real + Scalar, const N: usize> From<Vector<T, N>> for SVector<T, N> {
    fn from(v: Vector<T, N>) -> Self {
        SVector::from_fn(|i, _| v.0[i])
    }
}

impl<T: Real + Scalar, const N: usize> From<SVector<T, N>> for Vector<T, N> {
    fn from(v: SVector<T, N>) -> Self {
        Vector(core::array::from_fn(|i| v[i]))
    }
}

impl<T: Real + Scalar, const R: usize, const C: usize> From<Matrix<T, R, C>> for SMatrix<T, R, C> {
    fn from(m: Matrix<T, R, C>) -> Self {
        SMatrix::from_fn(|i, j| m.0[i][j])
    }
}

impl<T: Real + Scalar, const R: usize, const C: usize> From<SMatrix<T, R, C>> for Matrix<T, R, C> {
    fn from(m: SMatrix<T, R, C>) -> Self {
        Matrix(core::array::from_fn(|i| {
            core::array::from_fn(|j| m[(i, j)])
        }))
    }
}

impl<T: Real + RealField> From<Transform<T>> for IsometryMatrix3<T> {
    fn from(t: Transform<T>) -> Self {
        let r = Rotation3::from_matrix_unchecked(SMatrix::from(t.rotation));
        let p = Translation3::from(SVector::from(t.translation));
        IsometryMatrix3::from_parts(p, r)
    }
}

impl<T: Real + RealField> From<Transform<T>> for Isometry3<T> {
    fn from(t: Transform<T>) -> Self {
        let r = Rotation3::from_matrix_unchecked(SMatrix::from(t.rotation));
        let p = Translation3::from(SVector::from(t.translation));
        Isometry3::from_parts(p, UnitQuaternion::from_rotation_matrix(&r))
    }
}

/// A checked transform from nalgebra's rotation matrix and translation.
fn checked<T: Real + RealField>(
    r: &Rotation3<T>,
    p: &Translation3<T>,
) -> Result<Transform<T>, Error> {
    let t = Transform {
        rotation: Mat3::from(*r.matrix()),
        translation: Vector::from(p.vector),
    };
    t.check()?;
    Ok(t)
}

impl<T: Real + RealField> TryFrom<IsometryMatrix3<T>> for Transform<T> {
    type Error = Error;
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::NotARotation`] ([`Transform::check`]): an
    /// `IsometryMatrix3` can hold any matrix.
    fn try_from(iso: IsometryMatrix3<T>) -> Result<Self, Error> {
        checked(&iso.rotation, &iso.translation)
    }
}

impl<T: Real + RealField> TryFrom<Isometry3<T>> for Transform<T> {
    type Error = Error;
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::NotARotation`] ([`Transform::check`]): a
    /// `UnitQuaternion` built with `new_unchecked` need not have unit norm.
    fn try_from(iso: Isometry3<T>) -> Result<Self, Error> {
        checked(&iso.rotation.to_rotation_matrix(), &iso.translation)
    }
}
