//! `mint` conversions (feature `mint`): the interchange types that most Rust math crates
//! (nalgebra, glam, cgmath, euclid, …) convert to and from.
//!
//! | ppoe | mint | direction |
//! |---|---|---|
//! | [`Vec3<T>`] | `Vector3<T>`, `Point3<T>` | both, exact |
//! | [`Vector<T, 4>`] | `Vector4<T>` | both, exact |
//! | [`Mat3<T>`] | `RowMatrix3<T>`, `ColumnMatrix3<T>` | both, exact |
//! | [`Transform<T>`] | `RowMatrix4<T>`, `ColumnMatrix4<T>` (homogeneous) | `From` to mint; `TryFrom` from mint (validated) |
//! | rotation [`Mat3<T>`] | `Quaternion<T>` | `TryFrom` both ways (validated) |
//!
//! mint's `Quaternion { v: [x, y, z], s: w }` is a Hamilton quaternion; the conversions
//! go through [`rotation_forms`](crate::rotation_forms), whose array order is
//! `[w, x, y, z]`.
//!
//! ```
//! use ppoe::{Mat3, Transform};
//! let t = Transform::<f64>::from_rpy(&[0.0, 0.0, 0.5], [1.0, 2.0, 3.0])?;
//! let m: mint::ColumnMatrix4<f64> = t.into();
//! assert_eq!(m.w.x, 1.0); // the translation is the fourth column
//! assert_eq!(Transform::try_from(m)?, t);
//! let q = mint::Quaternion::try_from(t.rotation)?;
//! assert!((Mat3::try_from(q)? - t.rotation).amax() < 1e-15);
//! # Ok::<(), ppoe::Error>(())
//! ```

use crate::error::Error;
use crate::linalg::{Mat3, Matrix, Vec3, Vector};
use crate::rotation_forms::{matrix_from_quaternion, quaternion_from_matrix};
use crate::scalar::Real;
use crate::se3::Transform;

impl<T> From<mint::Vector3<T>> for Vec3<T> {
    fn from(v: mint::Vector3<T>) -> Self {
        Vector([v.x, v.y, v.z])
    }
}

impl<T> From<Vec3<T>> for mint::Vector3<T> {
    fn from(v: Vec3<T>) -> Self {
        let [x, y, z] = v.0;
        mint::Vector3 { x, y, z }
    }
}

impl<T> From<mint::Point3<T>> for Vec3<T> {
    fn from(v: mint::Point3<T>) -> Self {
        Vector([v.x, v.y, v.z])
    }
}

impl<T> From<Vec3<T>> for mint::Point3<T> {
    fn from(v: Vec3<T>) -> Self {
        let [x, y, z] = v.0;
        mint::Point3 { x, y, z }
    }
}

impl<T> From<mint::Vector4<T>> for Vector<T, 4> {
    fn from(v: mint::Vector4<T>) -> Self {
        Vector([v.x, v.y, v.z, v.w])
    }
}

impl<T> From<Vector<T, 4>> for mint::Vector4<T> {
    fn from(v: Vector<T, 4>) -> Self {
        let [x, y, z, w] = v.0;
        mint::Vector4 { x, y, z, w }
    }
}

impl<T> From<mint::RowMatrix3<T>> for Mat3<T> {
    fn from(m: mint::RowMatrix3<T>) -> Self {
        Matrix([m.x.into(), m.y.into(), m.z.into()])
    }
}

impl<T> From<Mat3<T>> for mint::RowMatrix3<T> {
    fn from(m: Mat3<T>) -> Self {
        let [x, y, z] = m.0;
        mint::RowMatrix3 {
            x: x.into(),
            y: y.into(),
            z: z.into(),
        }
    }
}

impl<T: Copy> From<mint::ColumnMatrix3<T>> for Mat3<T> {
    fn from(m: mint::ColumnMatrix3<T>) -> Self {
        let c: [[T; 3]; 3] = [m.x.into(), m.y.into(), m.z.into()];
        Matrix(core::array::from_fn(|i| core::array::from_fn(|j| c[j][i])))
    }
}

impl<T: Copy> From<Mat3<T>> for mint::ColumnMatrix3<T> {
    fn from(m: Mat3<T>) -> Self {
        let col = |j: usize| mint::Vector3::from([m.0[0][j], m.0[1][j], m.0[2][j]]);
        mint::ColumnMatrix3 {
            x: col(0),
            y: col(1),
            z: col(2),
        }
    }
}

impl<T: Real> From<Transform<T>> for mint::RowMatrix4<T> {
    fn from(t: Transform<T>) -> Self {
        t.to_matrix4().into()
    }
}

impl<T: Real> From<Transform<T>> for mint::ColumnMatrix4<T> {
    fn from(t: Transform<T>) -> Self {
        let m = t.to_matrix4();
        let col = |j: usize| mint::Vector4::from([m[0][j], m[1][j], m[2][j], m[3][j]]);
        mint::ColumnMatrix4 {
            x: col(0),
            y: col(1),
            z: col(2),
            w: col(3),
        }
    }
}

/// A transform from a row-major homogeneous matrix, checked: the last row must be
/// exactly `(0, 0, 0, 1)` and the rest pass [`Transform::check`].
fn transform_from_rows<T: Real>(m: [[T; 4]; 4]) -> Result<Transform<T>, Error> {
    if m.iter().flatten().any(|v| !v.is_finite()) {
        return Err(Error::NonFinite);
    }
    let (o, l) = (T::ZERO, T::ONE);
    if m[3] != [o, o, o, l] {
        return Err(Error::NotARotation);
    }
    let t = Transform::from_matrix4(&m);
    t.check()?;
    Ok(t)
}

impl<T: Real> TryFrom<mint::RowMatrix4<T>> for Transform<T> {
    type Error = Error;
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite element, [`Error::NotARotation`] if the last
    /// row is not exactly `(0, 0, 0, 1)` or the rotation block fails
    /// [`Transform::check`].
    fn try_from(m: mint::RowMatrix4<T>) -> Result<Self, Error> {
        transform_from_rows(m.into())
    }
}

impl<T: Real> TryFrom<mint::ColumnMatrix4<T>> for Transform<T> {
    type Error = Error;
    /// # Errors
    /// As for `mint::RowMatrix4`.
    fn try_from(m: mint::ColumnMatrix4<T>) -> Result<Self, Error> {
        let c: [[T; 4]; 4] = [m.x.into(), m.y.into(), m.z.into(), m.w.into()];
        transform_from_rows(core::array::from_fn(|i| core::array::from_fn(|j| c[j][i])))
    }
}

impl<T: Real> TryFrom<mint::Quaternion<T>> for Mat3<T> {
    type Error = Error;
    /// The rotation of a Hamilton quaternion, normalised first
    /// ([`matrix_from_quaternion`]).
    ///
    /// # Errors
    /// Those of [`matrix_from_quaternion`].
    fn try_from(q: mint::Quaternion<T>) -> Result<Self, Error> {
        matrix_from_quaternion(&[q.s, q.v.x, q.v.y, q.v.z])
    }
}

impl<T: Real> TryFrom<Mat3<T>> for mint::Quaternion<T> {
    type Error = Error;
    /// The unit quaternion (s = w ≥ 0) of a rotation ([`quaternion_from_matrix`]).
    ///
    /// # Errors
    /// Those of [`quaternion_from_matrix`]: the rotation is validated.
    fn try_from(r: Mat3<T>) -> Result<Self, Error> {
        let [w, x, y, z] = quaternion_from_matrix(&r)?;
        Ok(mint::Quaternion {
            v: mint::Vector3 { x, y, z },
            s: w,
        })
    }
}
