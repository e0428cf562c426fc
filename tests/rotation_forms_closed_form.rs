//! Quaternion and roll-pitch-yaw forms against independent oracles: the closed-form
//! quaternion of an axis-angle (cos θ/2, sin θ/2·u) against `so3::exp`, and URDF's
//! `Rz(yaw)·Ry(pitch)·Rx(roll)` as a product of three `so3::exp` rotations.

use ppoe::rotation_forms::{
    matrix_from_quaternion, matrix_from_rpy, quaternion_from_matrix, rpy_from_matrix,
};
use ppoe::{so3, Error, Mat3, Real, Transform, Vector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn max_diff<T: Real>(a: &Mat3<T>, b: &Mat3<T>) -> f64 {
    (*a - *b).amax().to_f64()
}

/// A random unit axis and an angle in [0, π], including exact 0, π/2 and π.
fn axis_angle(rng: &mut ChaCha8Rng, i: usize) -> ([f64; 3], f64) {
    let mut u = [0.0f64; 3];
    loop {
        u = u.map(|_| rng.gen_range(-1.0..1.0));
        let n = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
        if n > 0.1 {
            u = u.map(|v| v / n);
            break;
        }
    }
    let angle = match i % 5 {
        0 => core::f64::consts::PI,
        1 => core::f64::consts::PI * (1.0 - 1e-9),
        2 => 1e-9,
        _ => rng.gen_range(0.0..core::f64::consts::PI),
    };
    (u, angle)
}

fn quaternion_oracle<T: Real>(scale: f64) {
    let eps = T::EPS.to_f64();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for i in 0..2000 {
        let (u, a) = axis_angle(&mut rng, i);
        let (s, c) = (a / 2.0).sin_cos();
        let q64 = [c, s * u[0], s * u[1], s * u[2]];
        let q = q64.map(T::lit);
        let w = Vector(u.map(|v| T::lit(v * a)));
        let oracle = so3::exp(&w);
        let r = matrix_from_quaternion(&q).unwrap();
        assert!(
            max_diff(&r, &oracle) <= scale * eps,
            "{i}: R(q) vs exp: {}",
            max_diff(&r, &oracle)
        );
        assert!(max_diff(&(r.transpose() * r), &Mat3::identity()) <= 8.0 * eps);
        // Shepperd back to the quaternion: the same up to sign, w >= 0.
        let back = quaternion_from_matrix(&oracle).unwrap();
        assert!(back[0] >= T::ZERO);
        let dot: f64 = (0..4).map(|k| back[k].to_f64() * q64[k]).sum();
        let sign = dot.signum();
        for k in 0..4 {
            let d = (back[k].to_f64() - sign * q64[k]).abs();
            assert!(d <= scale * eps, "{i}: q[{k}] off by {d}");
        }
        // Round trip through the matrix of the returned quaternion.
        let rr = matrix_from_quaternion(&back).unwrap();
        assert!(
            max_diff(&rr, &oracle) <= 8.0 * eps,
            "{i}: {}",
            max_diff(&rr, &oracle)
        );
    }
}

#[test]
fn quaternion_matches_axis_angle_f64() {
    quaternion_oracle::<f64>(8.0);
}

#[test]
fn quaternion_matches_axis_angle_f32() {
    quaternion_oracle::<f32>(8.0);
}

#[test]
fn quaternion_known_values() {
    let h = core::f64::consts::FRAC_1_SQRT_2;
    // 90° about x, y, z; 180° about each axis.
    let rx = Mat3::from([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]);
    assert!(max_diff(&matrix_from_quaternion(&[h, h, 0.0, 0.0]).unwrap(), &rx) < 1e-15);
    for (k, q) in [
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
    .iter()
    .enumerate()
    {
        let mut d = [-1.0; 3];
        d[k] = 1.0;
        let r = Mat3::from_diagonal(&Vector(d));
        assert_eq!(quaternion_from_matrix(&r).unwrap(), *q);
        assert_eq!(matrix_from_quaternion(q).unwrap(), r);
    }
    // Not normalised: scaled by 1e-30 and 1e30 it is the same rotation.
    let r = matrix_from_quaternion(&[h, h, 0.0, 0.0]).unwrap();
    for s in [1e-30, 3.0, 1e30] {
        let rs = matrix_from_quaternion(&[h * s, h * s, 0.0, 0.0]).unwrap();
        assert!(max_diff(&r, &rs) < 1e-15);
    }
}

#[test]
fn quaternion_bad_input_is_an_error() {
    assert_eq!(
        matrix_from_quaternion(&[0.0f64; 4]),
        Err(Error::NotARotation)
    );
    assert_eq!(
        matrix_from_quaternion(&[f64::NAN, 0.0, 0.0, 1.0]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        matrix_from_quaternion(&[f32::INFINITY, 0.0, 0.0, 1.0]),
        Err(Error::NonFinite)
    );
    let not_rot = Mat3::from([[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    assert_eq!(quaternion_from_matrix(&not_rot), Err(Error::NotARotation));
    let reflection = Mat3::from_diagonal(&Vector([1.0, 1.0, -1.0]));
    assert_eq!(
        quaternion_from_matrix(&reflection),
        Err(Error::NotARotation)
    );
    let mut nan = Mat3::<f64>::identity();
    nan.0[1][2] = f64::NAN;
    assert_eq!(quaternion_from_matrix(&nan), Err(Error::NonFinite));
    assert_eq!(rpy_from_matrix(&nan), Err(Error::NonFinite));
    assert_eq!(rpy_from_matrix(&reflection), Err(Error::NotARotation));
    assert_eq!(
        matrix_from_rpy(&[0.0, f64::NAN, 0.0]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        Transform::from_rpy(&[0.0; 3], [0.0, f64::INFINITY, 0.0]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        Transform::from_quaternion(&[1.0, 0.0, 0.0, 0.0], [f64::NAN, 0.0, 0.0]),
        Err(Error::NonFinite)
    );
}

/// URDF's rpy as three elementary rotations about the fixed axes.
fn rpy_oracle<T: Real>(rpy: &[T; 3]) -> Mat3<T> {
    let z = T::ZERO;
    let rx = so3::exp(&Vector([rpy[0], z, z]));
    let ry = so3::exp(&Vector([z, rpy[1], z]));
    let rz = so3::exp(&Vector([z, z, rpy[2]]));
    rz * ry * rx
}

fn rpy_round_trips<T: Real>() {
    let eps = T::EPS.to_f64();
    let half_pi = core::f64::consts::FRAC_PI_2;
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let pi = core::f64::consts::PI;
    for i in 0..3000 {
        let pitch = match i % 6 {
            0 => half_pi,
            1 => -half_pi,
            2 => half_pi - 1e-9,
            3 => -half_pi + 1e-9 * rng.gen_range(0.0..1.0),
            _ => rng.gen_range(-half_pi..half_pi),
        };
        let rpy64 = [rng.gen_range(-pi..pi), pitch, rng.gen_range(-pi..pi)];
        let rpy = rpy64.map(T::lit);
        let oracle = rpy_oracle(&rpy);
        let r = matrix_from_rpy(&rpy).unwrap();
        assert!(
            max_diff(&r, &oracle) <= 8.0 * eps,
            "{i}: {}",
            max_diff(&r, &oracle)
        );
        let back = rpy_from_matrix(&r).unwrap();
        assert!(back[1].abs().to_f64() <= half_pi + eps, "pitch range");
        assert!(back[0].abs().to_f64() <= pi + eps && back[2].abs().to_f64() <= pi + eps);
        let rr = matrix_from_rpy(&back).unwrap();
        assert!(
            max_diff(&rr, &r) <= 8.0 * eps,
            "{i}: {rpy64:?} -> {back:?}: {}",
            max_diff(&rr, &r)
        );
        // Away from gimbal lock the angles themselves come back.
        if (pitch.abs() - half_pi).abs() > 1e-3 {
            for k in 0..3 {
                let d = (back[k].to_f64() - rpy64[k]).abs();
                assert!(d <= 1e4 * eps, "{i}: angle {k} off by {d}");
            }
        }
    }
}

#[test]
fn rpy_round_trip_f64() {
    rpy_round_trips::<f64>();
}

#[test]
fn rpy_round_trip_f32() {
    rpy_round_trips::<f32>();
}

#[test]
fn rpy_known_values_and_gimbal_lock() {
    let half_pi = core::f64::consts::FRAC_PI_2;
    // URDF order: roll first about x, then pitch about y, then yaw about z (fixed axes).
    let r = matrix_from_rpy(&[half_pi, 0.0, half_pi]).unwrap();
    // Rz(90)·Rx(90): z axis -> (Rx: -y) -> (Rz: +x).
    let z_img = r.column(2);
    assert!((z_img.0[0] - 1.0).abs() < 1e-15, "{z_img:?}");
    // Exactly at gimbal lock: yaw = 0, roll carries the rotation about the vertical.
    let locked = matrix_from_rpy(&[0.3, half_pi, 0.5]).unwrap();
    let rpy = rpy_from_matrix(&locked).unwrap();
    assert_eq!(rpy[2], 0.0);
    assert!((rpy[1] - half_pi).abs() < 1e-7);
    assert!((rpy[0] - (0.3 - 0.5)).abs() < 1e-7, "{rpy:?}");
    let t = Transform::<f64>::from_rpy(&[0.1, 0.2, 0.3], [1.0, 2.0, 3.0]).unwrap();
    let q = t.quaternion().unwrap();
    let t2 = Transform::from_quaternion(&q, [1.0, 2.0, 3.0]).unwrap();
    assert!(max_diff(&t.rotation, &t2.rotation) < 1e-15);
    let back = t2.rpy().unwrap();
    assert!(
        (back[0] - 0.1).abs() < 1e-15
            && (back[1] - 0.2).abs() < 1e-15
            && (back[2] - 0.3).abs() < 1e-15
    );
}
