//! Closed-form starting values of the base X (robot base in the tracker's frame) and the
//! marker Y (in the tip frame) from the data and the nominal kinematics `Fₖ = T̄(θₖ)`:
//!
//! * poses, both estimated: `Tₖ = X·Fₖ·Y` gives, for pairs of samples,
//!   `(Fⱼ⁻¹Fₖ)·Y = Y·(Tⱼ⁻¹Tₖ)` (AX = XB, hand–eye calibration). The rotation of Y aligns
//!   the rotation vectors of the pairs' relative motions (α = R_Y·β, solved by the
//!   orthogonal Procrustes problem, Park & Martin 1994), its translation solves the
//!   stacked `(R_A − I)·t_Y = R_Y·t_B − t_A` by least squares; then X is the average of
//!   `Tₖ·Y⁻¹·Fₖ⁻¹` (rotations projected back onto SO(3), translations meaned);
//! * poses, one estimated: the average of `Tₖ·Fₖ⁻¹` (X) or `Fₖ⁻¹·Tₖ` (Y);
//! * positions: the marker point m in the tip frame and X together by alternating a
//!   point-set registration (Kabsch/Umeyama without scale) of the predicted points
//!   `Fₖ·m` onto the measured ones with the least-squares m for that X, from m = 0.
//!
//! These are starting values for the maximum-likelihood refinement, not estimates: they
//! ignore the noise model and the kinematic errors.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use ppoe::{Mat3, Transform, Vec3};

fn na3(m: &Mat3<f64>) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| m.0[r][c])
}

fn v3(v: &Vec3<f64>) -> Vector3<f64> {
    Vector3::new(v.0[0], v.0[1], v.0[2])
}

fn transform(r: &Matrix3<f64>, t: &Vector3<f64>) -> Transform<f64> {
    Transform {
        rotation: Mat3::from(std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)]))),
        translation: Vec3::from([t[0], t[1], t[2]]),
    }
}

/// The rotation nearest `m` in the Frobenius norm (U·diag(1, 1, det)·Vᵀ).
fn nearest_rotation(m: &Matrix3<f64>) -> Matrix3<f64> {
    let svd = m.svd(true, true);
    let (u, vt) = (svd.u.unwrap_or_default(), svd.v_t.unwrap_or_default());
    let d = (u * vt).determinant().signum();
    u * Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, d)) * vt
}

/// The mean of transforms: rotations averaged and projected onto SO(3), translations
/// meaned.
fn mean(ts: impl Iterator<Item = Transform<f64>>) -> Transform<f64> {
    let (mut r, mut t, mut k) = (Matrix3::zeros(), Vector3::zeros(), 0.0f64);
    for x in ts {
        r += na3(&x.rotation);
        t += v3(&x.translation);
        k += 1.0;
    }
    transform(&nearest_rotation(&r), &(t / k.max(1.0)))
}

/// The rotation vector of `r` (axis·angle): the core's `so3::log`, exact up to a half turn.
fn rotation_vector(r: &Mat3<f64>) -> Vector3<f64> {
    v3(&ppoe::so3::log(r))
}

/// Y from `Tₖ = X·Fₖ·Y` (both unknown), pairs (k, k + K/2).
fn hand_eye(f: &[Transform<f64>], t: &[Transform<f64>]) -> Transform<f64> {
    let half = f.len() / 2;
    let pairs: Vec<(Transform<f64>, Transform<f64>)> = (0..half)
        .map(|k| {
            let (j, k) = (k, k + half);
            (f[j].inverse() * f[k], t[j].inverse() * t[k])
        })
        .collect();
    // α = R_Y·β: R_Y maximises Σ αᵀ·R·β, the Procrustes problem on H = Σ α·βᵀ.
    let mut h = Matrix3::zeros();
    for (a, b) in &pairs {
        h += rotation_vector(&a.rotation) * rotation_vector(&b.rotation).transpose();
    }
    let ry = nearest_rotation(&h);
    // (R_A − I)·t_Y = R_Y·t_B − t_A, stacked.
    let mut m = DMatrix::zeros(3 * pairs.len(), 3);
    let mut rhs = DVector::zeros(3 * pairs.len());
    for (p, (a, b)) in pairs.iter().enumerate() {
        let ra = na3(&a.rotation) - Matrix3::identity();
        let r = ry * v3(&b.translation) - v3(&a.translation);
        for i in 0..3 {
            for j in 0..3 {
                m[(3 * p + i, j)] = ra[(i, j)];
            }
            rhs[3 * p + i] = r[i];
        }
    }
    let ty = m
        .svd(true, true)
        .solve(&rhs, 1e-12)
        .map_or(Vector3::zeros(), |x| Vector3::new(x[0], x[1], x[2]));
    transform(&ry, &ty)
}

/// Starting X and Y from measured poses `t` and nominal tip poses `f`.
pub(crate) fn poses(
    f: &[Transform<f64>],
    t: &[Transform<f64>],
    base: bool,
    tip: bool,
) -> (Transform<f64>, Transform<f64>) {
    let id = Transform::identity();
    match (base, tip) {
        (false, false) => (id, id),
        (true, false) => (mean(f.iter().zip(t).map(|(f, t)| *t * f.inverse())), id),
        (false, true) => (id, mean(f.iter().zip(t).map(|(f, t)| f.inverse() * *t))),
        (true, true) => {
            let y = hand_eye(f, t);
            let x = mean(f.iter().zip(t).map(|(f, t)| *t * y.inverse() * f.inverse()));
            (x, y)
        }
    }
}

/// The rigid motion (R, t) that best maps points `a` onto `b` (Kabsch, no scale).
fn kabsch(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> Transform<f64> {
    let k = a.len().max(1) as f64;
    let ca = a.iter().sum::<Vector3<f64>>() / k;
    let cb = b.iter().sum::<Vector3<f64>>() / k;
    let mut h = Matrix3::zeros();
    for (p, q) in a.iter().zip(b) {
        h += (q - cb) * (p - ca).transpose();
    }
    let r = nearest_rotation(&h);
    transform(&r, &(cb - r * ca))
}

/// The least-squares marker point m (tip frame) for X: `Rₖ·m + tₖ = X⁻¹·pₖ`.
fn marker_point(x: &Transform<f64>, f: &[Transform<f64>], p: &[Vector3<f64>]) -> Vector3<f64> {
    let xi = x.inverse();
    let k = f.len().max(1) as f64;
    f.iter()
        .zip(p)
        .map(|(f, p)| {
            let local = v3(&xi.transform_point(&Vec3::from([p[0], p[1], p[2]])));
            na3(&f.rotation).transpose() * (local - v3(&f.translation))
        })
        .sum::<Vector3<f64>>()
        / k
}

/// Starting X and the marker point (as Y = (I, m)) from measured positions `p`.
pub(crate) fn positions(
    f: &[Transform<f64>],
    p: &[Vector3<f64>],
    base: bool,
    tip: bool,
) -> (Transform<f64>, Transform<f64>) {
    let id = Transform::identity();
    let mut x = id;
    let mut m = Vector3::zeros();
    for _ in 0..if base && tip { 20 } else { 1 } {
        if base {
            let pred: Vec<Vector3<f64>> = f
                .iter()
                .map(|f| na3(&f.rotation) * m + v3(&f.translation))
                .collect();
            x = kabsch(&pred, p);
        }
        if tip {
            m = marker_point(&x, f, p);
        }
    }
    (x, transform(&Matrix3::identity(), &m))
}
