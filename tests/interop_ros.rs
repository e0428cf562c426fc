//! ROS covariance order and frame: the permutation against its definition, and the
//! right/left-to-ROS maps against finite differences of the perturbed pose
//! (`p = p̄ + δp`, `R = Exp(δθ)·R̄` in the parent frame).

use ppoe::interop::ros::{
    from_ros_order, left_from_ros, right_from_ros, ros_from_left, ros_from_right, to_ros_order,
};
use ppoe::{se3, so3, Mat6, Matrix, Transform, Vector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_pose(rng: &mut ChaCha8Rng) -> Transform<f64> {
    let rpy = [
        rng.gen_range(-3.0..3.0),
        rng.gen_range(-1.5..1.5),
        rng.gen_range(-3.0..3.0),
    ];
    let p = [0; 3].map(|_| rng.gen_range(-2.0..2.0));
    Transform::from_rpy(&rpy, p).unwrap()
}

fn random_cov(rng: &mut ChaCha8Rng) -> Mat6<f64> {
    let a = Matrix([[0.0; 6]; 6].map(|r| r.map(|_: f64| rng.gen_range(-1.0..1.0))));
    a.mul_tr(&a)
}

/// (δp, δθ) of `t` relative to `mean`, ROS order.
fn ros_delta(mean: &Transform<f64>, t: &Transform<f64>) -> [f64; 6] {
    let dp = t.translation - mean.translation;
    let dth = so3::log(&(t.rotation * mean.rotation.transpose()));
    [dp.0[0], dp.0[1], dp.0[2], dth.0[0], dth.0[1], dth.0[2]]
}

/// The Jacobian d(δp, δθ)/dη by central differences.
fn numeric_jacobian(mean: &Transform<f64>, right: bool) -> Mat6<f64> {
    let h = 1e-6;
    let mut jac = Mat6::zeros();
    for k in 0..6 {
        let mut e = [0.0; 6];
        let mut col = [[0.0; 6]; 2];
        for (s, sign) in [1.0, -1.0].iter().enumerate() {
            e[k] = sign * h;
            let d = se3::exp(&Vector(e));
            let t = if right { *mean * d } else { d * *mean };
            col[s] = ros_delta(mean, &t);
        }
        for (row, (a, b)) in jac.0.iter_mut().zip(col[0].iter().zip(&col[1])) {
            row[k] = (a - b) / (2.0 * h);
        }
    }
    jac
}

#[test]
fn order_is_the_block_swap() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let cov = random_cov(&mut rng);
    let ros = to_ros_order(&cov);
    // ROS (x, y, z, rotX, rotY, rotZ) = ppoe indices (3, 4, 5, 0, 1, 2).
    let idx = [3, 4, 5, 0, 1, 2];
    for i in 0..6 {
        for j in 0..6 {
            assert_eq!(ros.0[i][j], cov.0[idx[i]][idx[j]]);
        }
    }
    assert_eq!(from_ros_order(&ros), cov);
}

#[test]
fn frame_maps_match_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..50 {
        let mean = random_pose(&mut rng);
        let cov = random_cov(&mut rng);
        for right in [true, false] {
            let jac = numeric_jacobian(&mean, right);
            let oracle = cov.congruence(&jac);
            let ours = if right {
                ros_from_right(&mean, &cov)
            } else {
                ros_from_left(&mean, &cov)
            };
            let err = (ours - oracle).amax() / oracle.amax();
            assert!(err < 1e-8, "right={right}: relative error {err}");
            let back = if right {
                right_from_ros(&mean, &ours)
            } else {
                left_from_ros(&mean, &ours)
            };
            assert!((back - cov).amax() < 1e-13 * cov.amax().max(1.0) * 100.0);
        }
    }
}

#[test]
fn right_and_left_agree_through_the_adjoint() {
    // Σ_left = Ad(T̄)·Σ_right·Ad(T̄)ᵀ: both must give the same ROS covariance.
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    for _ in 0..20 {
        let mean = random_pose(&mut rng);
        let cov = random_cov(&mut rng);
        let left = ppoe::uncertainty::right_to_left(&mean, &cov);
        let a = ros_from_right(&mean, &cov);
        let b = ros_from_left(&mean, &left);
        assert!(
            (a - b).amax() < 1e-12 * a.amax().max(1.0),
            "{}",
            (a - b).amax()
        );
    }
}
