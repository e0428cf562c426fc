//! nalgebra (feature `nalgebra`): element (i, j) maps to element (i, j), products agree
//! with nalgebra's, transforms act on points as nalgebra's isometries do.
#![cfg(feature = "nalgebra")]

use nalgebra::{
    Isometry3, IsometryMatrix3, Point3, Quaternion, SMatrix, SVector, Translation3, UnitQuaternion,
};
use ppoe::{Error, Matrix, Real, Transform, Vector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

#[test]
fn matrices_map_elementwise_and_products_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let a = Matrix([[0.0; 4]; 3].map(|r| r.map(|_: f64| rng.gen_range(-1.0..1.0))));
    let b = Matrix([[0.0; 2]; 4].map(|r| r.map(|_: f64| rng.gen_range(-1.0..1.0))));
    let na: SMatrix<f64, 3, 4> = a.into();
    assert_eq!(na[(1, 2)], a.0[1][2]);
    assert_eq!(Matrix::from(na), a);
    let prod = Matrix::from(na * SMatrix::<f64, 4, 2>::from(b));
    assert!((prod - a.mul_mat(&b)).amax() < 1e-15);
    let v = Vector([1.0f32, -2.0, 3.5, 0.25, 8.0, -1.0]);
    let nv: SVector<f32, 6> = v.into();
    assert_eq!(nv[4], 8.0);
    assert_eq!(Vector::from(nv), v);
}

fn transforms_agree<T: Real + nalgebra::RealField>(tol_eps: f64) {
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let eps = <T as Real>::EPS.to_f64();
    for _ in 0..200 {
        let rpy = [0; 3].map(|_| T::lit(rng.gen_range(-3.0..3.0)));
        let p = [0; 3].map(|_| T::lit(rng.gen_range(-2.0..2.0)));
        let t = Transform::from_rpy(&rpy, p).unwrap();
        let x = Vector([0; 3].map(|_| T::lit(rng.gen_range(-1.0..1.0))));
        let ours = t.transform_point(&x);
        let exact: IsometryMatrix3<T> = t.into();
        assert_eq!(Transform::try_from(exact), Ok(t));
        let iso: Isometry3<T> = t.into();
        let theirs = iso.transform_point(&Point3::from(SVector::from(x)));
        for k in 0..3 {
            let d = (ours.0[k] - theirs[k]).to_f64().abs();
            assert!(d <= tol_eps * eps, "{d}");
        }
        let back = Transform::try_from(iso).unwrap();
        assert!((back.rotation - t.rotation).amax().to_f64() <= tol_eps * eps);
        assert_eq!(back.translation, t.translation);
    }
}

#[test]
fn transforms_agree_f64() {
    transforms_agree::<f64>(16.0);
}

#[test]
fn transforms_agree_f32() {
    transforms_agree::<f32>(16.0);
}

#[test]
fn invalid_isometries_are_errors() {
    let q = UnitQuaternion::new_unchecked(Quaternion::new(2.0, 0.0, 0.0, 0.0));
    let iso = Isometry3::from_parts(Translation3::new(0.0, 0.0, 0.0), q);
    assert_eq!(Transform::try_from(iso), Err(Error::NotARotation));
    let mut m = IsometryMatrix3::<f64>::identity();
    m.translation.vector.x = f64::NAN;
    assert_eq!(Transform::try_from(m), Err(Error::NonFinite));
}
