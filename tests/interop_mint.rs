//! mint (feature `mint`): layouts against mint's documented field meanings, exact round
//! trips, and validation of what comes in.
#![cfg(feature = "mint")]

use ppoe::{so3, Error, Mat3, Transform, Vec3, Vector};

fn pose() -> Transform<f64> {
    Transform::from_rpy(&[0.4, -0.3, 2.0], [1.0, -2.0, 3.5]).unwrap()
}

#[test]
fn vectors_and_matrices_exact() {
    let v = Vector([1.0f32, 2.0, 3.0]);
    let m: mint::Vector3<f32> = v.into();
    assert_eq!((m.x, m.y, m.z), (1.0, 2.0, 3.0));
    assert_eq!(Vec3::from(m), v);
    let p: mint::Point3<f32> = v.into();
    assert_eq!(Vec3::from(p), v);
    let v4 = Vector([1.0, 2.0, 3.0, 4.0]);
    let m4: mint::Vector4<f64> = v4.into();
    assert_eq!(m4.w, 4.0);
    assert_eq!(Vector::from(m4), v4);
    let r = Mat3::from([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]]);
    let rows: mint::RowMatrix3<f64> = r.into();
    assert_eq!(rows.y.x, 4.0); // row 1, column 0
    let cols: mint::ColumnMatrix3<f64> = r.into();
    assert_eq!(cols.y.x, 2.0); // column 1, row 0
    assert_eq!(Mat3::from(rows), r);
    assert_eq!(Mat3::from(cols), r);
}

#[test]
fn transforms_round_trip_and_are_validated() {
    let t = pose();
    let rows: mint::RowMatrix4<f64> = t.into();
    let cols: mint::ColumnMatrix4<f64> = t.into();
    // Homogeneous: translation in the last column, (0, 0, 0, 1) last row.
    assert_eq!((rows.x.w, rows.y.w, rows.z.w), (1.0, -2.0, 3.5));
    assert_eq!(
        (cols.w.x, cols.w.y, cols.w.z, cols.w.w),
        (1.0, -2.0, 3.5, 1.0)
    );
    assert_eq!(
        (rows.w.x, rows.w.y, rows.w.z, rows.w.w),
        (0.0, 0.0, 0.0, 1.0)
    );
    assert_eq!(Transform::try_from(rows), Ok(t));
    assert_eq!(Transform::try_from(cols), Ok(t));
    let mut bad = rows;
    bad.w.x = 0.5;
    assert_eq!(Transform::try_from(bad), Err(Error::NotARotation));
    let mut bad = rows;
    bad.x.x = 2.0;
    assert_eq!(Transform::try_from(bad), Err(Error::NotARotation));
    let mut bad = cols;
    bad.w.y = f64::NAN;
    assert_eq!(Transform::try_from(bad), Err(Error::NonFinite));
}

#[test]
fn quaternions_follow_hamilton_axis_angle() {
    // 0.7 rad about a unit axis u: q = (cos 0.35, sin 0.35 u), s = w.
    let u = [2.0f64 / 7.0, 3.0 / 7.0, 6.0 / 7.0];
    let (s, c) = 0.35f64.sin_cos();
    let q = mint::Quaternion {
        v: mint::Vector3::from(u.map(|x| s * x)),
        s: c,
    };
    let oracle = so3::exp(&Vector(u.map(|x| 0.7 * x)));
    let r = Mat3::try_from(q).unwrap();
    assert!((r - oracle).amax() < 1e-15);
    let back = mint::Quaternion::try_from(oracle).unwrap();
    assert!((back.s - c).abs() < 1e-15 && (back.v.z - s * u[2]).abs() < 1e-15);
    let zero = mint::Quaternion {
        v: mint::Vector3::from([0.0f32; 3]),
        s: 0.0,
    };
    assert_eq!(Mat3::try_from(zero), Err(Error::NotARotation));
    let shear = Mat3::from([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    assert_eq!(mint::Quaternion::try_from(shear), Err(Error::NotARotation));
}
