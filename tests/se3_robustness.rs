//! Robustness of the SO(3)/SE(3) primitives, by class of input, for f32 and f64 through the
//! same generic code (issue "nothing silently wrong", items 4–6):
//! * the SO(3) logarithm from π/2 to π, against the exact axis of the generating rotation
//!   vector, and below π/2 within its conditioning;
//! * the left Jacobian and `se3::exp` just above the series cut-off, against the Maclaurin
//!   series of their coefficients evaluated in f64 (an independent closed form);
//! * `se3::screw_axis` for directions of any magnitude, tiny (subnormal) to huge.
//!
//! Every threshold is a small multiple of the scalar's ε, derived in place.

use ppoe::{se3, so3, Error, Real, Vec3, Vec6, Vector};
use proptest::prelude::*;
use std::f64::consts::PI;

fn cast3<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vector(a.map(T::lit))
}

fn up3<T: Real>(v: &Vec3<T>) -> [f64; 3] {
    v.0.map(|x| x.to_f64())
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn max_diff(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// Unit axes, a third of them with one component exactly 0 and a third with one of
/// 10⁻⁹ (where pytransform3d's near-π formula `√((Sᵢᵢ + 1)/2)` is off by up to δ/2).
fn axis() -> impl Strategy<Value = [f64; 3]> {
    (prop::array::uniform3(-1.0..1.0f64), 0usize..3, 0usize..3).prop_filter_map(
        "degenerate",
        |(mut a, kind, i)| {
            match kind {
                0 => a[i] = 0.0,
                1 => a[i] = 1e-9,
                _ => {}
            }
            let n = norm(a);
            (n > 0.1).then(|| a.map(|x| x / n))
        },
    )
}

/// The rotation vector as T, and the exact (f64) axis and angle of that T vector folded
/// into [0, π] (an angle rounded above π is the rotation by 2π − angle about −u).
fn near_pi_input<T: Real>(u: [f64; 3], delta: f64) -> (Vec3<T>, [f64; 3], f64) {
    let w = cast3::<T>(u.map(|x| x * (PI - delta)));
    let wf = up3(&w);
    let t = norm(wf);
    let axis = wf.map(|x| x / t);
    if t > PI {
        (w, axis.map(|x| -x), 2.0 * PI - t)
    } else {
        (w, axis, t)
    }
}

/// Axis error of `so3::log_axis_angle(so3::exp(ω))` for ω = (π − δ)·u in T.
fn log_axis_error<T: Real>(u: [f64; 3], delta: f64) -> (f64, f64) {
    let (w, axis, angle) = near_pi_input::<T>(u, delta);
    let (got_axis, got_angle) = so3::log_axis_angle(&so3::exp(&w));
    let mut e = max_diff(up3(&got_axis), axis);
    if PI - angle < 4.0 * T::EPS.to_f64() {
        // At π (to rounding) the sign is a convention.
        e = e.min(max_diff(up3(&got_axis), axis.map(|x| -x)));
    }
    (e, (got_angle.to_f64() - angle).abs())
}

/// From π/2 to π the axis comes from the symmetric part `cos θ·I + (1 − cos θ)·uuᵀ` of
/// R: R's elements carry a few ε from `so3::exp`, the row used has norm
/// (1 − cos θ)·|u_k| ≥ 1/√3, so the axis is good to ≈ √3·√3·(element error) ≈ 3 ε per
/// unit of element error: 16 ε allows 5 ε in the elements. The angle, atan2 of
/// sin θ (absolute error a few ε) and cos θ, is good to a few ε as well.
fn check_near_pi<T: Real>(u: [f64; 3], delta: f64) {
    let eps = T::EPS.to_f64();
    let (e_axis, e_angle) = log_axis_error::<T>(u, delta);
    assert!(
        e_axis <= 16.0 * eps,
        "{}: axis error {e_axis:.3e} = {:.1} ε at δ = {delta:.3e}, u = {u:?}",
        std::any::type_name::<T>(),
        e_axis / eps
    );
    assert!(
        e_angle <= 16.0 * eps,
        "{}: angle error {e_angle:.3e} at δ = {delta:.3e}",
        std::any::type_name::<T>()
    );
}

/// Below π/2 the axis is the normalised skew part 2 sin θ·u: element errors of a few ε
/// become ≈ ε/sin θ in the axis; 4·ε/sin θ allows 4 ε in the skew elements.
fn check_skew_branch<T: Real>(u: [f64; 3], theta: f64) {
    let eps = T::EPS.to_f64();
    let (e_axis, _) = log_axis_error::<T>(u, PI - theta);
    assert!(
        e_axis <= 4.0 * eps / theta.sin(),
        "{}: axis error {e_axis:.3e} > 4 ε/sin θ at θ = {theta:.3e}, u = {u:?}",
        std::any::type_name::<T>(),
    );
}

/// `(1 − cos t)/t²` and `(t − sin t)/t³` from their Maclaurin series (30 terms, exact to
/// f64 rounding for t ≤ 2: the terms alternate and fall by ≥ 3× from the second on).
fn jacobian_coefficients(t: f64) -> (f64, f64) {
    let t2 = t * t;
    let (mut a, mut b) = (0.0, 0.0);
    let (mut ta, mut tb) = (0.5, 1.0 / 6.0);
    for k in 0..30 {
        a += ta;
        b += tb;
        let k = k as f64;
        ta *= -t2 / ((2.0 * k + 3.0) * (2.0 * k + 4.0));
        tb *= -t2 / ((2.0 * k + 4.0) * (2.0 * k + 5.0));
    }
    (a, b)
}

/// `J(ω)·x = x + a·ω×x + b·ω×(ω×x)` in f64 with the series coefficients.
fn jacobian_apply(w: [f64; 3], x: [f64; 3]) -> [f64; 3] {
    let cross = |p: [f64; 3], q: [f64; 3]| {
        [
            p[1] * q[2] - p[2] * q[1],
            p[2] * q[0] - p[0] * q[2],
            p[0] * q[1] - p[1] * q[0],
        ]
    };
    let (a, b) = jacobian_coefficients(norm(w));
    let wx = cross(w, x);
    let wwx = cross(w, wx);
    [0, 1, 2].map(|i| x[i] + a * wx[i] + b * wwx[i])
}

/// Just above the series cut-off, ‖ω‖ = t ∈ [SERIES, 64·SERIES]: every column of the left
/// Jacobian (elements ≤ 1) and the translation J(ω)·v of `se3::exp` within 8 ε (·‖v‖)
/// of the series oracle. With `1 − cos t` computed by subtraction the coefficient
/// (1 − cos t)/t carried an error ε/t, i.e. 8000 ε at the f64 cut-off and 64 ε at f32's.
fn check_jacobian_above_cutoff<T: Real>(u: [f64; 3], factor: f64, v: [f64; 3]) {
    let t = T::SERIES.to_f64() * factor;
    let w = cast3::<T>(u.map(|x| x * t));
    let wf = up3(&w);
    let eps = T::EPS.to_f64();
    let j = so3::left_jacobian(&w);
    for c in 0..3 {
        let mut e = [0.0; 3];
        e[c] = 1.0;
        let expected = jacobian_apply(wf, e);
        let got = [0, 1, 2].map(|r| j.0[r][c].to_f64());
        let err = max_diff(got, expected);
        assert!(
            err <= 8.0 * eps,
            "{}: J column {c} error {:.1} ε at t = {t:.4e}",
            std::any::type_name::<T>(),
            err / eps
        );
    }
    let vt = cast3::<T>(v);
    let vf = up3(&vt);
    let xi = Vec6::from_parts(w, vt);
    let p = up3(&se3::exp(&xi).translation);
    let err = max_diff(p, jacobian_apply(wf, vf));
    assert!(
        err <= 8.0 * eps * norm(vf),
        "{}: se3::exp translation error {:.1} ε·‖v‖ at t = {t:.4e}",
        std::any::type_name::<T>(),
        err / (eps * norm(vf))
    );
}

/// Directions of any magnitude give the unit axis of the direction: the same as for the
/// direction scaled to O(1) (exactly representable: a power of 2), within 2 ε per
/// component (two roundings of a division by a norm in [1, √3]).
fn check_screw_scale<T: Real>(s: [f64; 3], exp2: i32, q: [f64; 3], h: f64) {
    let scale = T::lit(2f64.powi(exp2));
    let s1 = cast3::<T>(s);
    let big = s1.scale(scale);
    if !big.is_finite() || big.0.iter().all(|x| *x == T::ZERO) {
        return;
    }
    // Only where scaling lost no bits (subnormal results round): compare with the exact
    // axis of the scaled vector.
    let exact = up3(&big);
    let n = norm(exact.map(|x| x * 2f64.powi(-exp2)));
    let expected = exact.map(|x| x * 2f64.powi(-exp2) / n);
    let qt = cast3::<T>(q);
    let got = se3::screw_axis(&qt, &big, T::lit(h)).expect("a nonzero finite direction");
    let got_axis = up3(&got.rotation());
    let eps = T::EPS.to_f64();
    let err = max_diff(got_axis, expected);
    // Subnormal directions keep fewer bits: their own rounding (relative 2^-1074·…) is in
    // `expected` already, since it is taken from the stored T values.
    assert!(
        err <= 4.0 * eps,
        "{}: screw axis error {:.1} ε at scale 2^{exp2}",
        std::any::type_name::<T>(),
        err / eps
    );
    assert!(got.is_finite());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn so3_log_near_pi_is_accurate(u in axis(), delta in 0.0..(PI / 2.0)) {
        check_near_pi::<f64>(u, delta);
        check_near_pi::<f32>(u, delta);
    }

    #[test]
    fn so3_log_near_pi_tiny_delta(u in axis(), e in -16.0..-2.0f64) {
        check_near_pi::<f64>(u, 10f64.powf(e));
        check_near_pi::<f32>(u, 10f64.powf(e));
    }

    #[test]
    fn so3_log_skew_branch_bound(u in axis(), theta in 1e-3..(PI / 2.0)) {
        check_skew_branch::<f64>(u, theta);
        check_skew_branch::<f32>(u, theta);
    }

    #[test]
    fn jacobian_and_exp_above_series_cutoff(
        u in axis(),
        factor in 1.0..64.0f64,
        v in prop::array::uniform3(-10.0..10.0f64),
    ) {
        check_jacobian_above_cutoff::<f64>(u, factor, v);
        check_jacobian_above_cutoff::<f32>(u, factor, v);
    }

    #[test]
    fn screw_axis_any_magnitude(
        s in prop::array::uniform3(-1.0..1.0f64),
        e64 in -1070..1020i32,
        e32 in -145..125i32,
        q in prop::array::uniform3(-2.0..2.0f64),
        h in -1.0..1.0f64,
    ) {
        prop_assume!(norm(s) > 0.1);
        check_screw_scale::<f64>(s, e64, q, h);
        check_screw_scale::<f32>(s, e32, q, h);
    }
}

/// Exactly at π, from the exactly symmetric `2uuᵀ − I`: the largest component positive.
#[test]
fn so3_log_at_pi_convention() {
    for u in [[1.0, 0.0, 0.0], [0.6, -0.8, 0.0], [0.0, -0.6, 0.8]] {
        let mut m = ppoe::Mat3::<f64>::zeros();
        for i in 0..3 {
            for j in 0..3 {
                m.0[i][j] = 2.0 * u[i] * u[j] - if i == j { 1.0 } else { 0.0 };
            }
        }
        let (axis, angle) = so3::log_axis_angle(&m);
        assert_eq!(angle, PI);
        let k = (0..3)
            .max_by(|&a, &b| u[a].abs().total_cmp(&u[b].abs()))
            .unwrap();
        let sign = u[k].signum();
        assert!(max_diff(axis.0, u.map(|x| x * sign)) <= 4.0 * f64::EPSILON);
    }
}

/// A zero direction is the only `ZeroAxis`; overflow of `q × ŝ + h·ŝ` is an error, not ∞.
#[test]
fn screw_axis_errors() {
    fn case<T: Real>() {
        let z = Vec3::<T>::zeros();
        assert_eq!(se3::screw_axis(&z, &z, T::ZERO), Err(Error::ZeroAxis));
        let tiny = Vec3::<T>::from([T::ZERO, T::min_positive_value() * T::EPS, T::ZERO]);
        let s = se3::screw_axis(&z, &tiny, T::ZERO).expect("subnormal direction");
        assert_eq!(s.rotation().0, [T::ZERO, T::ONE, T::ZERO]);
        let huge = T::max_value();
        // q × ŝ = (M/√2, 0, −M/√2) and h·ŝ = (M/√2, 0, M/√2): the first sums to √2·M.
        let q = Vec3::from([T::ZERO, huge, T::ZERO]);
        let s = Vec3::from([T::ONE, T::ZERO, T::ONE]);
        assert_eq!(se3::screw_axis(&q, &s, huge), Err(Error::Overflow));
        assert!(se3::screw_axis(&q, &s, T::ZERO).is_ok());
    }
    case::<f32>();
    case::<f64>();
}
