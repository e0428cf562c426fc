//! Property-based tests of the SO(3)/SE(3) algebra and the uncertainty operations, for
//! both scalars: every property is written once, generically, and run for f32 and f64.

use approx::assert_relative_eq;
use ppoe::chain::{bending_noise, screw_noise, Chain, ChainView, Convention, Joint, JointKind};
use ppoe::uncertainty::{self, Order};
use ppoe::{se3, so3, Error, Mat3, Mat6, Real, Transform, Vec3, Vec6, Vector};
use proptest::prelude::*;

/// Tolerance for an operation chain of a few dozen flops on values of order 1.
fn tol<T: Real>() -> T {
    T::EPS * T::lit(512.0)
}

fn v3<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vector(a.map(T::lit))
}

fn v6<T: Real>(a: [f64; 6]) -> Vec6<T> {
    Vector(a.map(T::lit))
}

/// Rotation vectors with angle in [0, π − 0.1] (away from the log's branch cut).
fn rotvec() -> impl Strategy<Value = [f64; 3]> {
    (
        prop::array::uniform3(-1.0..1.0f64),
        0.0..(std::f64::consts::PI - 0.1),
    )
        .prop_map(|(a, angle)| {
            let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            if n < 1e-3 {
                [angle, 0.0, 0.0]
            } else {
                a.map(|x| x / n * angle)
            }
        })
}

fn twist() -> impl Strategy<Value = [f64; 6]> {
    (rotvec(), prop::array::uniform3(-2.0..2.0f64))
        .prop_map(|(w, v)| [w[0], w[1], w[2], v[0], v[1], v[2]])
}

/// A random covariance L·Lᵀ of rank 1..=6 and scale up to 1.
fn covariance() -> impl Strategy<Value = [[f64; 6]; 6]> {
    (
        prop::array::uniform6(prop::array::uniform6(-0.3..0.3f64)),
        1usize..=6,
    )
        .prop_map(|(l, rank)| {
            let mut c = [[0.0; 6]; 6];
            for (i, row) in c.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x = (0..rank).map(|k| l[i][k] * l[j][k]).sum();
                }
            }
            c
        })
}

fn mat6<T: Real>(a: [[f64; 6]; 6]) -> Mat6<T> {
    ppoe::Matrix(a.map(|r| r.map(T::lit)))
}

fn assert_sym_psd<T: Real>(c: &Mat6<T>) {
    assert_eq!(c.asymmetry(), T::ZERO, "not exactly symmetric");
    uncertainty::check_covariance(c).expect("not PSD within tolerance");
}

fn exp_log_round_trips<T: Real>(w: [f64; 3], xi: [f64; 6]) {
    let w = v3::<T>(w);
    assert_relative_eq!(so3::log(&so3::exp(&w)), w, epsilon = tol::<T>());
    let r = so3::exp(&w);
    assert_relative_eq!(so3::exp(&so3::log(&r)), r, epsilon = tol::<T>());
    let xi = v6::<T>(xi);
    assert_relative_eq!(
        se3::log(&se3::exp(&xi)),
        xi,
        epsilon = tol::<T>() * T::lit(4.0)
    );
    let t = se3::exp(&xi);
    assert_relative_eq!(
        se3::exp(&se3::log(&t)),
        t,
        epsilon = tol::<T>() * T::lit(4.0)
    );
    assert!(so3::is_rotation(&t.rotation, tol::<T>()));
}

fn adjoint_identities<T: Real>(a: [f64; 6], b: [f64; 6], c: [f64; 6]) {
    let (t1, t2, xi) = (se3::exp(&v6::<T>(a)), se3::exp(&v6::<T>(b)), v6::<T>(c));
    let e = tol::<T>() * T::lit(8.0);
    assert_relative_eq!(
        (t1 * t2).adjoint(),
        t1.adjoint() * t2.adjoint(),
        epsilon = e
    );
    assert_relative_eq!(
        t1.adjoint() * t1.inverse().adjoint(),
        Mat6::identity(),
        epsilon = e
    );
    let lhs = t1 * se3::exp(&xi) * t1.inverse();
    let rhs = se3::exp(&(t1.adjoint() * xi));
    assert_relative_eq!(lhs, rhs, epsilon = e);
}

fn jacobian_inverses<T: Real>(xi: [f64; 6]) {
    let xi = v6::<T>(xi);
    let w = xi.rotation();
    let e = tol::<T>() * T::lit(8.0);
    assert_relative_eq!(
        so3::left_jacobian(&w) * so3::left_jacobian_inv(&w),
        Mat3::identity(),
        epsilon = e
    );
    assert_relative_eq!(
        se3::left_jacobian(&xi) * se3::left_jacobian_inv(&xi),
        Mat6::identity(),
        epsilon = e
    );
    // Left Jacobian: Exp(ξ + δ) ≈ Exp(J δ) Exp(ξ) to first order.
    let d = T::lit(1e-3) * T::EPS.sqrt().sqrt();
    let delta = Vector([d, -d, d, d, d, -d]);
    let lhs = se3::exp(&(xi + delta));
    let rhs = se3::exp(&(se3::left_jacobian(&xi) * delta)) * se3::exp(&xi);
    assert_relative_eq!(lhs, rhs, epsilon = d * d * T::lit(50.0) + e);
}

fn covariances_symmetric_psd<T: Real>(
    a: [f64; 6],
    b: [f64; 6],
    c1: [[f64; 6]; 6],
    c2: [[f64; 6]; 6],
) {
    let (t1, t2) = (se3::exp(&v6::<T>(a)), se3::exp(&v6::<T>(b)));
    let (s1, s2) = (mat6::<T>(c1), mat6::<T>(c2));
    for order in [Order::Second, Order::Fourth] {
        let (_, c) = uncertainty::concat_globally(&t1, &s1, &t2, &s2, order);
        assert_eq!(c.asymmetry(), T::ZERO);
        if order == Order::Second {
            assert_sym_psd(&c);
        }
    }
    let (_, c) = uncertainty::concat_locally(&t1, &t2, &s1, &s2);
    assert_sym_psd(&c);
    let (_, c) = uncertainty::invert(&t1, &s1);
    assert_sym_psd(&c);
}

/// Changing the output frame with an exact transform commutes with concatenation.
fn frame_invariance<T: Real>(
    a: [f64; 6],
    b: [f64; 6],
    z: [f64; 6],
    c1: [[f64; 6]; 6],
    c2: [[f64; 6]; 6],
) {
    let (a2b, b2c, c2d) = (
        se3::exp(&v6::<T>(a)),
        se3::exp(&v6::<T>(b)),
        se3::exp(&v6::<T>(z)),
    );
    let (s1, s2) = (mat6::<T>(c1), mat6::<T>(c2));
    let e = tol::<T>() * T::lit(16.0);
    for order in [Order::Second, Order::Fourth] {
        let (m, c) = uncertainty::concat_globally(&a2b, &s1, &b2c, &s2, order);
        let moved = c.congruence(&c2d.adjoint());
        let s2d = s2.congruence(&c2d.adjoint());
        let (m2, c2) = uncertainty::concat_globally(&a2b, &s1, &(c2d * b2c), &s2d, order);
        assert_relative_eq!(c2d * m, m2, epsilon = e);
        assert_relative_eq!(moved, c2, epsilon = e * moved.amax().max(T::ONE));
    }
    // Local: prepend an exact transform Z→A.
    let z2a = c2d;
    let (m1, k1) = uncertainty::concat_locally(&a2b, &b2c, &s1, &s2);
    let (m2, k2) = uncertainty::concat_locally(&z2a, &m1, &Mat6::zeros(), &k1);
    let s1z = s1.congruence(&z2a.inverse().adjoint());
    let (m3, k3) = uncertainty::concat_locally(&(a2b * z2a), &b2c, &s1z, &s2);
    assert_relative_eq!(m2, m3, epsilon = e);
    assert_relative_eq!(k2, k3, epsilon = e * k2.amax().max(T::ONE));
}

/// A 3-joint chain with one prismatic joint, written generically.
fn chain<T: Real>() -> Chain<T, 3> {
    let l = T::lit;
    let inf = T::infinity();
    Chain::new(
        "base",
        "tip",
        [
            Joint::new(
                "a",
                JointKind::Revolute,
                [0., 0., 1., 0., 0., 0.].map(l),
                l(-2.0),
                l(2.0),
            ),
            Joint::new(
                "b",
                JointKind::Prismatic,
                [0., 0., 0., 0.6, 0., 0.8].map(l),
                l(-0.5),
                l(0.5),
            ),
            Joint::new(
                "c",
                JointKind::Continuous,
                [1., 0., 0., 0., 0.4, -0.1].map(l),
                -inf,
                inf,
            ),
        ],
        Transform::from_parts(
            [[0., -1., 0.], [1., 0., 0.], [0., 0., 1.]].map(|r| r.map(l)),
            [0.3, 0.1, 0.5].map(l),
        ),
    )
}

fn ppoe_properties<T: Real>(thetas: [f64; 3], c1: [[f64; 6]; 6], sigma: f64) {
    let ch = chain::<T>();
    let th = thetas.map(T::lit);
    let covs = [
        mat6::<T>(c1),
        screw_noise(&ch.joints[1].screw, T::lit(sigma * sigma)),
        bending_noise(
            &v3::<T>([0.1, 0.2, 0.3]),
            &Mat3::identity().scale(T::lit(sigma)),
        ),
    ];
    let r = ch.ppoe(&th, &covs, Convention::Right);
    let l = ch.ppoe(&th, &covs, Convention::Left);
    assert_sym_psd(&r.cov);
    assert_sym_psd(&l.cov);
    let e = tol::<T>() * T::lit(16.0) * l.cov.amax().max(T::ONE);
    assert_relative_eq!(
        uncertainty::right_to_left(&r.pose, &r.cov),
        l.cov,
        epsilon = e
    );
    assert_relative_eq!(r.pose, ch.forward_kinematics(&th), epsilon = tol::<T>());
    // Space Jacobian columns are the base-frame twists: first-order FK check.
    let js = ch.space_jacobian(&th);
    // Central differences, h = ε^⅓: truncation h² and rounding ε/h balance at ε^⅔.
    let h = T::EPS.cbrt();
    let fk0_inv = ch.forward_kinematics(&th).inverse();
    for i in 0..3 {
        let (mut tp, mut tm) = (th, th);
        tp[i] += h;
        tm[i] -= h;
        if ch.clip(&tp) != tp || ch.clip(&tm) != tm {
            continue;
        }
        let dp = se3::log(&(ch.forward_kinematics(&tp) * fk0_inv));
        let dm = se3::log(&(ch.forward_kinematics(&tm) * fk0_inv));
        let numeric = (dp - dm).scale(T::ONE / (h + h));
        assert_relative_eq!(numeric, js.column(i), epsilon = T::lit(50.0) * h * h);
    }
    let fourth = ch.ppoe_fourth_order(&th, &covs, Convention::Right);
    assert_eq!(fourth.cov.asymmetry(), T::ZERO);
}

/// f32 results stay within the documented bound of the f64 ones.
fn f32_matches_f64(xi: [f64; 6], c1: [[f64; 6]; 6], thetas: [f64; 3]) {
    let t64 = se3::exp(&v6::<f64>(xi));
    let t32 = se3::exp(&v6::<f32>(xi));
    for (a, b) in t64
        .to_matrix4()
        .iter()
        .flatten()
        .zip(t32.to_matrix4().iter().flatten())
    {
        assert!((a - *b as f64).abs() <= 4e-6, "exp: {a} vs {b}");
    }
    let l64 = se3::log(&t64);
    let l32 = se3::log(&t32);
    for (a, b) in l64.0.iter().zip(l32.0.iter()) {
        assert!((a - *b as f64).abs() <= 1e-5, "log: {a} vs {b}");
    }
    let covs64 = [mat6::<f64>(c1); 3];
    let covs32 = [mat6::<f32>(c1); 3];
    let r64 = chain::<f64>().ppoe(&thetas, &covs64, Convention::Right);
    let r32 = chain::<f32>().ppoe(&thetas.map(|x| x as f32), &covs32, Convention::Right);
    let scale = r64.cov.amax().max(1.0);
    for (a, b) in r64.cov.0.iter().flatten().zip(r32.cov.0.iter().flatten()) {
        assert!(
            (a - *b as f64).abs() <= 1e-5 * scale,
            "ppoe cov: {a} vs {b}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn exp_log(w in rotvec(), xi in twist()) {
        exp_log_round_trips::<f32>(w, xi);
        exp_log_round_trips::<f64>(w, xi);
    }

    #[test]
    fn adjoint(a in twist(), b in twist(), c in twist()) {
        adjoint_identities::<f32>(a, b, c);
        adjoint_identities::<f64>(a, b, c);
    }

    #[test]
    fn jacobians(xi in twist()) {
        jacobian_inverses::<f32>(xi);
        jacobian_inverses::<f64>(xi);
    }

    #[test]
    fn covariances(a in twist(), b in twist(), c1 in covariance(), c2 in covariance()) {
        covariances_symmetric_psd::<f32>(a, b, c1, c2);
        covariances_symmetric_psd::<f64>(a, b, c1, c2);
    }

    #[test]
    fn change_of_frame(a in twist(), b in twist(), z in twist(), c1 in covariance(), c2 in covariance()) {
        frame_invariance::<f32>(a, b, z, c1, c2);
        frame_invariance::<f64>(a, b, z, c1, c2);
    }

    #[test]
    fn ppoe(th in prop::array::uniform3(-3.0..3.0f64), c1 in covariance(), s in 0.0..0.3f64) {
        ppoe_properties::<f32>(th, c1, s);
        ppoe_properties::<f64>(th, c1, s);
    }

    #[test]
    fn f32_vs_f64(xi in twist(), c1 in covariance(), th in prop::array::uniform3(-3.0..3.0f64)) {
        f32_matches_f64(xi, c1, th);
    }
}

fn transport_matches_dense<T: Real>(a: [f64; 6], c1: [[f64; 6]; 6]) {
    let t = se3::exp(&v6::<T>(a));
    let c = mat6::<T>(c1);
    let dense = c.congruence(&t.adjoint());
    let fast = t.transport_covariance(&c);
    assert_eq!(fast.asymmetry(), T::ZERO);
    assert_relative_eq!(fast, dense, epsilon = tol::<T>() * T::lit(4.0));
}

/// `Joint::displacement` (closed-form screw motion, with the √/÷-free path for ‖ω‖² within
/// √ε of 1) against `se3::exp(S·θ)` evaluated in f64 on the same T-rounded inputs.
fn displacement_matches_exp<T: Real>(u: [f64; 3], norm: f64, v: [f64; 3], theta: f64) {
    let l = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt().max(1e-3);
    let s = [
        u[0] / l * norm,
        u[1] / l * norm,
        u[2] / l * norm,
        v[0],
        v[1],
        v[2],
    ]
    .map(T::lit);
    let j = Joint::new("j", JointKind::Revolute, s, T::lit(-1e9), T::lit(1e9));
    let got = j.displacement(T::lit(theta));
    // With the constants computed once (`prepared`, what tables hold): the same bits.
    let prepared = j.prepared();
    assert!(prepared.constants().is_some());
    assert_eq!(
        prepared.displacement(T::lit(theta)),
        got,
        "prepared joint differs"
    );
    // And the checked path accepts them, but not constants of another screw.
    let chain = ChainView {
        joints: core::slice::from_ref(&prepared),
        home: Transform::identity(),
    };
    if (norm - 1.0).abs() < 1e-9 {
        chain.check().unwrap();
        let mut stale = prepared;
        stale.screw.0[3] += T::ONE;
        let bad = ChainView {
            joints: core::slice::from_ref(&stale),
            home: Transform::identity(),
        };
        assert_eq!(bad.check(), Err(Error::InconsistentConstants));
    }
    let s64 = Vector(s.map(|x| x.to_f64()));
    let want = se3::exp(&s64.scale(T::lit(theta).to_f64()));
    let n = s64.rotation().norm();
    let t = (theta * n).abs();
    let lever = s64.translation().norm() / n;
    let tol = tol::<T>().to_f64();
    for i in 0..3 {
        for k in 0..3 {
            let e = (got.rotation.0[i][k].to_f64() - want.rotation.0[i][k]).abs();
            assert!(
                e <= tol * (1.0 + t),
                "R[{i}][{k}] off by {e:e}, norm {norm}"
            );
        }
        let e = (got.translation.0[i].to_f64() - want.translation.0[i]).abs();
        assert!(
            e <= tol * (1.0 + lever) * (1.0 + t),
            "p[{i}] off by {e:e}, norm {norm}"
        );
    }
}

/// Axis norms: within 10⁻¹⁶…10⁻² of 1 (either side of the √ε cut) or anywhere in
/// 10⁻²…10².
fn axis_norm() -> impl Strategy<Value = f64> {
    prop_oneof![
        (-16.0..-2.0f64, any::<bool>()).prop_map(|(e, up)| {
            let d = 10f64.powf(e);
            if up {
                1.0 + d
            } else {
                1.0 - d
            }
        }),
        (-2.0..2.0f64).prop_map(|e| 10f64.powf(e)),
        Just(1.0),
    ]
}

proptest! {
    #[test]
    fn displacement(
        u in prop::array::uniform3(-1.0..1.0f64),
        norm in axis_norm(),
        v in prop::array::uniform3(-2.0..2.0f64),
        theta in -4.0..4.0f64,
    ) {
        displacement_matches_exp::<f32>(u, norm, v, theta);
        displacement_matches_exp::<f64>(u, norm, v, theta);
    }
}

proptest! {
    #[test]
    fn structured_transport(a in twist(), c1 in covariance()) {
        transport_matches_dense::<f32>(a, c1);
        transport_matches_dense::<f64>(a, c1);
    }
}

/// Found by fuzzing (fuzz/artifacts-found): a rotation with a subnormal skew part made the
/// axis 1/‖r‖ overflow; huge f32 angles overflowed t² in exp.
#[test]
fn extreme_but_finite_inputs_give_finite_results() {
    let xi = Vec6::<f64>::from([5e-324, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let log = se3::log(&se3::exp(&xi));
    assert!(log.is_finite(), "{log:?}");
    let w = Vec3::<f32>::new(1e-45, 0.0, 0.0);
    assert!(so3::log(&so3::exp(&w)).is_finite());
    for t in [1e19f32, 1e30, 3e38] {
        let xi = Vec6::<f32>::from([t, 0.0, 0.0, 0.0, 1.0, 0.0]);
        let e = se3::exp(&xi);
        assert!(
            e.rotation.is_finite() && e.translation.is_finite(),
            "exp({t})"
        );
        assert!(so3::left_jacobian_inv(&xi.rotation()).is_finite() || t > 1e38);
    }
}

/// Mismatched lengths are `LengthMismatch`, no poses `Empty`, for pose fusion.
#[test]
fn pose_fusion_length_errors() {
    let opts = uncertainty::IterationOptions::default();
    let means = [Transform::<f64>::identity(); 2];
    let covs = [Mat6::<f64>::identity(); 3];
    for (m, c) in [
        (&means[..], &covs[..1]),
        (&means[..], &covs[..]),
        (&[][..], &covs[..1]),
    ] {
        assert_eq!(
            uncertainty::pose_fusion(m, c, &opts).err(),
            Some(Error::LengthMismatch)
        );
    }
    assert_eq!(
        uncertainty::pose_fusion::<f64>(&[], &[], &opts).err(),
        Some(Error::Empty)
    );
    assert!(uncertainty::pose_fusion(&means, &covs[..2], &opts).is_ok());
}
