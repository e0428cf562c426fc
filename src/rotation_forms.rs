//! Rotation forms people have: unit quaternions and URDF roll-pitch-yaw angles, to and
//! from a rotation matrix ([`Transform`]'s `rotation`).
//!
//! Conventions, stated once for the whole module:
//! * A rotation matrix R maps vectors of the rotated frame into the reference frame
//!   (`x_ref = R·x_rot`), as everywhere in ppoe.
//! * **Quaternions are Hamilton quaternions in the order `[w, x, y, z]`** (scalar first),
//!   active, with `R(q)·v = q·v·q*`. Other libraries store them differently: `mint` as
//!   `{ v: [x, y, z], s: w }`, nalgebra's `Quaternion::new(w, x, y, z)` stores
//!   `[x, y, z, w]`, ROS `geometry_msgs/Quaternion` has fields `x, y, z, w`, Eigen's
//!   constructor takes `(w, x, y, z)` but `coeffs()` is `[x, y, z, w]`. q and −q are the
//!   same rotation; the quaternions returned here have `w ≥ 0`.
//! * **Roll-pitch-yaw are URDF's fixed-axis angles `[roll, pitch, yaw]`**:
//!   `R = Rz(yaw)·Ry(pitch)·Rx(roll)` (rotate about the fixed x axis by roll, then about the
//!   fixed y axis by pitch, then about the fixed z axis by yaw; the same matrix as the
//!   intrinsic z-y'-x'' sequence). Returned angles: roll and yaw in [−π, π], pitch in
//!   [−π/2, π/2].
//!
//! All functions are generic over [`Real`], `no_std`, and allocate nothing.
//!
//! ```
//! use ppoe::rotation_forms::{matrix_from_rpy, quaternion_from_matrix, rpy_from_matrix};
//! // A URDF yaw of 90°: the quaternion [cos 45°, 0, 0, sin 45°], and back to the angles.
//! let r = matrix_from_rpy(&[0.0, 0.0, core::f64::consts::FRAC_PI_2])?;
//! let h = core::f64::consts::FRAC_1_SQRT_2;
//! let q = quaternion_from_matrix(&r)?;
//! approx::assert_abs_diff_eq!(q[..], [h, 0.0, 0.0, h][..], epsilon = 1e-15);
//! let rpy = rpy_from_matrix(&r)?;
//! assert!((rpy[2] - core::f64::consts::FRAC_PI_2).abs() < 1e-15 && rpy[0].abs() < 1e-15);
//! # Ok::<(), ppoe::Error>(())
//! ```

use crate::error::Error;
use crate::linalg::{Mat3, Matrix, Vec3};
use crate::scalar::Real;
use crate::se3::Transform;
use crate::so3;

/// The rotation matrix of a Hamilton quaternion `[w, x, y, z]`, normalised first (any
/// finite non-zero quaternion is accepted, so that a quaternion rounded to f32 or read
/// from text need not have unit norm to the last bit).
///
/// # Errors
/// [`Error::NonFinite`] if an element is NaN or infinite, [`Error::NotARotation`] if the
/// norm is zero or underflows (no rotation is defined), or if the result is not finite.
///
/// # Accuracy
/// The result is orthonormal to a few ε of T (the tests check `‖RᵀR − I‖_max ≤ 8ε` and
/// agreement with [`so3::exp`] of the same axis-angle within `8ε`).
///
/// ```
/// use ppoe::rotation_forms::{matrix_from_quaternion, quaternion_from_matrix};
/// // 90° about z: w = cos 45°, z = sin 45°.
/// let h = core::f64::consts::FRAC_1_SQRT_2;
/// let r = matrix_from_quaternion(&[h, 0.0, 0.0, h])?;
/// assert!((r.0[1][0] - 1.0).abs() < 1e-15); // x axis -> y axis
/// let q = quaternion_from_matrix(&r)?;
/// assert!((q[0] - h).abs() < 1e-15 && (q[3] - h).abs() < 1e-15);
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn matrix_from_quaternion<T: Real>(q: &[T; 4]) -> Result<Mat3<T>, Error> {
    if q.iter().any(|v| !v.is_finite()) {
        return Err(Error::NonFinite);
    }
    // Scale by the largest element before the norm so that neither squares overflow nor
    // tiny quaternions underflow.
    let m = q.iter().fold(T::ZERO, |a, v| a.max(v.abs()));
    if m <= T::min_positive_value() {
        return Err(Error::NotARotation);
    }
    let s = q.map(|v| v / m);
    let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + s[3] * s[3]).sqrt();
    let [w, x, y, z] = s.map(|v| v / n);
    let one = T::ONE;
    let two = T::TWO;
    let r = Matrix([
        [
            one - two * (y * y + z * z),
            two * (x * y - w * z),
            two * (x * z + w * y),
        ],
        [
            two * (x * y + w * z),
            one - two * (x * x + z * z),
            two * (y * z - w * x),
        ],
        [
            two * (x * z - w * y),
            two * (y * z + w * x),
            one - two * (x * x + y * y),
        ],
    ]);
    if r.is_finite() {
        Ok(r)
    } else {
        Err(Error::NotARotation)
    }
}

/// The unit Hamilton quaternion `[w, x, y, z]` (with `w ≥ 0`) of the rotation `r`, by
/// Shepperd's method: the largest of `1 + tr R`, `1 + 2R₀₀ − tr R`, … is the one taken
/// under the square root, so no division by a small number happens for any rotation
/// (including 180° turns). The result is normalised.
///
/// # Errors
/// [`Error::NonFinite`] if an element is NaN or infinite, [`Error::NotARotation`] if `r`
/// is not a rotation within [`Real::TOL`] ([`so3::is_rotation`]).
///
/// # Accuracy
/// For a rotation orthonormal to a few ε, the quaternion's rotation matrix reproduces `r`
/// within `8ε` (max-element; tested over random rotations including 180° turns, f32 and
/// f64); for an input off orthonormal by δ, the error is O(δ).
///
/// ```
/// use ppoe::rotation_forms::quaternion_from_matrix;
/// use ppoe::Mat3;
/// // 180° about x: w = 0, x = 1.
/// let r = Mat3::from([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]]);
/// assert_eq!(quaternion_from_matrix(&r)?, [0.0, 1.0, 0.0, 0.0]);
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn quaternion_from_matrix<T: Real>(r: &Mat3<T>) -> Result<[T; 4], Error> {
    if !r.is_finite() {
        return Err(Error::NonFinite);
    }
    if !so3::is_rotation(r, T::TOL) {
        return Err(Error::NotARotation);
    }
    Ok(shepperd(&r.0))
}

/// Shepperd's method on a rotation matrix (see [`quaternion_from_matrix`]).
fn shepperd<T: Real>(a: &[[T; 3]; 3]) -> [T; 4] {
    let tr = a[0][0] + a[1][1] + a[2][2];
    let quarter = T::HALF * T::HALF;
    // 4·q_k² for the four candidates; the largest is at least 1 for a rotation.
    let cand = [
        T::ONE + tr,
        T::ONE + a[0][0] - a[1][1] - a[2][2],
        T::ONE - a[0][0] + a[1][1] - a[2][2],
        T::ONE - a[0][0] - a[1][1] + a[2][2],
    ];
    let mut k = 0;
    for i in 1..4 {
        if cand[i] > cand[k] {
            k = i;
        }
    }
    let big = cand[k].sqrt() * T::HALF; // |q_k|
    let f = quarter / big; // 1 / (4·|q_k|)
    let q = match k {
        0 => [
            big,
            (a[2][1] - a[1][2]) * f,
            (a[0][2] - a[2][0]) * f,
            (a[1][0] - a[0][1]) * f,
        ],
        1 => [
            (a[2][1] - a[1][2]) * f,
            big,
            (a[0][1] + a[1][0]) * f,
            (a[0][2] + a[2][0]) * f,
        ],
        2 => [
            (a[0][2] - a[2][0]) * f,
            (a[0][1] + a[1][0]) * f,
            big,
            (a[1][2] + a[2][1]) * f,
        ],
        _ => [
            (a[1][0] - a[0][1]) * f,
            (a[0][2] + a[2][0]) * f,
            (a[1][2] + a[2][1]) * f,
            big,
        ],
    };
    let n = q.iter().fold(T::ZERO, |s, v| s + *v * *v).sqrt();
    let sign = if q[0] < T::ZERO { -T::ONE } else { T::ONE };
    q.map(|v| sign * v / n)
}

/// The rotation `Rz(yaw)·Ry(pitch)·Rx(roll)` of URDF's `rpy="roll pitch yaw"`.
///
/// # Errors
/// [`Error::NonFinite`] if an angle is NaN or infinite.
///
/// # Accuracy
/// Each element within 8ε of the product of the three elementary rotations
/// (tested against `so3::exp` of each angle, f32 and f64; the sines and cosines are
/// [`Real::sin_cos_r`]).
///
/// ```
/// use ppoe::rotation_forms::matrix_from_rpy;
/// // yaw = 90°: x axis -> y axis.
/// let r = matrix_from_rpy(&[0.0, 0.0, core::f64::consts::FRAC_PI_2])?;
/// assert!((r.0[1][0] - 1.0).abs() < 1e-15 && r.0[0][0].abs() < 1e-15);
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn matrix_from_rpy<T: Real>(rpy: &[T; 3]) -> Result<Mat3<T>, Error> {
    if rpy.iter().any(|v| !v.is_finite()) {
        return Err(Error::NonFinite);
    }
    let (sr, cr) = rpy[0].sin_cos_r();
    let (sp, cp) = rpy[1].sin_cos_r();
    let (sy, cy) = rpy[2].sin_cos_r();
    Ok(Matrix([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]))
}

/// URDF roll-pitch-yaw `[roll, pitch, yaw]` of the rotation `r` (see the module
/// conventions), robust at and near gimbal lock (pitch = ±90°).
///
/// Method: yaw = atan2(R₁₀, R₀₀); then, with `M = Rz(−yaw)·R = Ry(pitch)·Rx(roll)`,
/// pitch = atan2(−R₂₀, M₀₀) and roll = atan2(−M₁₂, M₁₁). Every angle comes from entries
/// of order 1, so the angles reproduce `r` to a few ε even where roll and yaw are
/// not separately determined. At gimbal lock (`hypot(R₀₀, R₁₀) ≤ ε`) yaw is set to 0 and
/// roll carries the whole rotation about the vertical axis.
///
/// # Errors
/// [`Error::NonFinite`] if an element is NaN or infinite, [`Error::NotARotation`] if `r`
/// is not a rotation within [`Real::TOL`].
///
/// # Accuracy
/// `matrix_from_rpy(rpy_from_matrix(r))` reproduces `r` within `8ε` (max-element; tested
/// over random rotations and rotations within 1e-9 rad of gimbal lock, f32 and f64).
///
/// ```
/// use ppoe::rotation_forms::{matrix_from_rpy, rpy_from_matrix};
/// let rpy = [0.1f64, -0.2, 0.3];
/// let back = rpy_from_matrix(&matrix_from_rpy(&rpy)?)?;
/// assert!(back.iter().zip(&rpy).all(|(a, b)| (a - b).abs() < 1e-15));
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn rpy_from_matrix<T: Real>(r: &Mat3<T>) -> Result<[T; 3], Error> {
    if !r.is_finite() {
        return Err(Error::NonFinite);
    }
    if !so3::is_rotation(r, T::TOL) {
        return Err(Error::NotARotation);
    }
    let a = &r.0;
    let locked = a[0][0].hypot(a[1][0]) <= T::EPS;
    let yaw = if locked {
        T::ZERO
    } else {
        a[1][0].atan2(a[0][0])
    };
    let (sy, cy) = yaw.sin_cos_r();
    // Rows 0 and 1 of Rz(−yaw)·R; row 2 is R's.
    let m00 = cy * a[0][0] + sy * a[1][0];
    let m11 = -sy * a[0][1] + cy * a[1][1];
    let m12 = -sy * a[0][2] + cy * a[1][2];
    let pitch = (-a[2][0]).atan2(m00);
    let roll = (-m12).atan2(m11);
    Ok([roll, pitch, yaw])
}

impl<T: Real> Transform<T> {
    /// A transform from a Hamilton quaternion `[w, x, y, z]` (normalised first; see
    /// [`matrix_from_quaternion`]) and a translation.
    ///
    /// # Errors
    /// Those of [`matrix_from_quaternion`]; [`Error::NonFinite`] for a non-finite
    /// translation.
    ///
    /// ```
    /// use ppoe::Transform;
    /// let t = Transform::from_quaternion(&[1.0, 0.0, 0.0, 0.0], [1.0, 2.0, 3.0])?;
    /// assert_eq!(t, Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 2., 3.]));
    /// # Ok::<(), ppoe::Error>(())
    /// ```
    pub fn from_quaternion(q: &[T; 4], translation: [T; 3]) -> Result<Self, Error> {
        let rotation = matrix_from_quaternion(q)?;
        from_rotation(rotation, translation)
    }

    /// A transform from URDF roll-pitch-yaw `[roll, pitch, yaw]` (`Rz(yaw)·Ry(pitch)·
    /// Rx(roll)`) and a translation: a URDF `<origin xyz=".." rpy=".."/>`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite angle or translation.
    ///
    /// ```
    /// use ppoe::Transform;
    /// let t = Transform::from_rpy(&[0.0, 0.0, core::f64::consts::PI], [0.5, 0.0, 0.0])?;
    /// let p = t.transform_point(&[1.0, 0.0, 0.0].into());
    /// assert!((p.0[0] + 0.5).abs() < 1e-15);
    /// # Ok::<(), ppoe::Error>(())
    /// ```
    pub fn from_rpy(rpy: &[T; 3], translation: [T; 3]) -> Result<Self, Error> {
        let rotation = matrix_from_rpy(rpy)?;
        from_rotation(rotation, translation)
    }

    /// The rotation as a Hamilton quaternion `[w, x, y, z]`, `w ≥ 0`
    /// ([`quaternion_from_matrix`]).
    ///
    /// # Errors
    /// Those of [`quaternion_from_matrix`] (the rotation is validated).
    ///
    /// ```
    /// use ppoe::Transform;
    /// assert_eq!(Transform::<f32>::identity().quaternion()?, [1.0, 0.0, 0.0, 0.0]);
    /// # Ok::<(), ppoe::Error>(())
    /// ```
    pub fn quaternion(&self) -> Result<[T; 4], Error> {
        quaternion_from_matrix(&self.rotation)
    }

    /// The rotation as URDF roll-pitch-yaw `[roll, pitch, yaw]` ([`rpy_from_matrix`]).
    ///
    /// # Errors
    /// Those of [`rpy_from_matrix`] (the rotation is validated).
    ///
    /// ```
    /// use ppoe::Transform;
    /// let t = Transform::from_rpy(&[0.3, 0.2, 0.1], [0.0; 3])?;
    /// let rpy = t.rpy()?;
    /// assert!((rpy[0] - 0.3f64).abs() < 1e-15);
    /// # Ok::<(), ppoe::Error>(())
    /// ```
    pub fn rpy(&self) -> Result<[T; 3], Error> {
        rpy_from_matrix(&self.rotation)
    }
}

/// A transform from a rotation known to be valid and a translation to be checked.
fn from_rotation<T: Real>(rotation: Mat3<T>, translation: [T; 3]) -> Result<Transform<T>, Error> {
    let translation = Vec3::from(translation);
    if !translation.is_finite() {
        return Err(Error::NonFinite);
    }
    Ok(Transform {
        rotation,
        translation,
    })
}
