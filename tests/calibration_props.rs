//! `fold_calibration` against the unfolded calibrated product
//! `Exp(S₁''·(θ₁+δ₁))···Exp(Sₙ''·(θₙ+δₙ))·M·Exp(μ)`, `Sᵢ'' = Ad(Exp(κᵢ))·Sᵢ`, computed
//! directly with `se3::exp` (proptest: random chains of 1–8 revolute and prismatic joints,
//! offsets and corrections up to 0.1, random configurations); f64 to 1e-13, f32 to 1e-5
//! (relative to the pose's scale), and the error cases leave the chain unchanged.

use ppoe::chain::{fold_calibration, Joint, JointKind};
use ppoe::{se3, Error, Real, Transform, Vec6};
use proptest::prelude::*;

/// Joint i: revolute about a unit axis through a point, or prismatic along a unit axis.
fn joint<T: Real>(kind: JointKind, axis: [f64; 3], point: [f64; 3]) -> Joint<T> {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let w = axis.map(|a| a / n);
    let s = match kind {
        JointKind::Prismatic => [0., 0., 0., w[0], w[1], w[2]],
        _ => {
            // v = q × ω (= −ω × q).
            let q = point;
            [
                w[0],
                w[1],
                w[2],
                q[1] * w[2] - q[2] * w[1],
                q[2] * w[0] - q[0] * w[2],
                q[0] * w[1] - q[1] * w[0],
            ]
        }
    };
    Joint::new("j", kind, s.map(T::lit), -T::lit(1e9), T::lit(1e9))
}

fn vec6<T: Real>(v: [f64; 6]) -> Vec6<T> {
    Vec6::from(v.map(T::lit))
}

/// The unfolded calibrated product at θ.
fn unfolded<T: Real>(
    joints: &[Joint<T>],
    home: &Transform<T>,
    cal: (&[T], &[Vec6<T>], &Vec6<T>),
    theta: &[T],
) -> Transform<T> {
    let (offsets, kappa, mu) = cal;
    let mut t = Transform::identity();
    for (i, j) in joints.iter().enumerate() {
        let s = se3::exp(&kappa[i]).adjoint().mul_vec(&j.screw);
        t = t * se3::exp(&(s * (theta[i] + offsets[i])));
    }
    t * *home * se3::exp(mu)
}

/// The folded chain's forward kinematics (its own displacements) at θ.
fn folded_fk<T: Real>(joints: &[Joint<T>], home: &Transform<T>, theta: &[T]) -> Transform<T> {
    let mut t = Transform::identity();
    for (j, th) in joints.iter().zip(theta) {
        t = t * j.displacement(*th);
    }
    t * *home
}

type Case = (
    Vec<(bool, [f64; 3], [f64; 3], f64, [f64; 6], f64)>,
    [f64; 6],
    [f64; 6],
);

fn case() -> impl Strategy<Value = Case> {
    let j = (
        any::<bool>(),
        prop::array::uniform3(-1.0..1.0f64),
        prop::array::uniform3(-0.8..0.8f64),
        -0.1..0.1f64,
        prop::array::uniform6(-0.1..0.1f64),
        -3.0..3.0f64,
    );
    (
        prop::collection::vec(j, 1..9),
        prop::array::uniform6(-0.5..0.5f64),
        prop::array::uniform6(-0.1..0.1f64),
    )
}

fn check<T: Real>(c: &Case, tol: f64) -> Result<(), TestCaseError> {
    let (js, home_xi, mu) = c;
    prop_assume!(js
        .iter()
        .all(|j| j.1.iter().map(|a| a * a).sum::<f64>() > 0.01));
    let mut joints: Vec<Joint<T>> = js
        .iter()
        .map(|(p, a, q, ..)| {
            let kind = if *p {
                JointKind::Prismatic
            } else {
                JointKind::Revolute
            };
            joint::<T>(kind, *a, *q)
        })
        .collect();
    let nominal = joints.clone();
    let offsets: Vec<T> = js.iter().map(|j| T::lit(j.3)).collect();
    let kappa: Vec<Vec6<T>> = js.iter().map(|j| vec6::<T>(j.4)).collect();
    let theta: Vec<T> = js.iter().map(|j| T::lit(j.5)).collect();
    let home0 = se3::exp(&vec6::<T>(*home_xi));
    let mu = vec6::<T>(*mu);
    let mut home = home0;
    fold_calibration(&mut joints, &mut home, &offsets, &kappa, &mu).unwrap();
    let want = unfolded(&nominal, &home0, (&offsets, &kappa, &mu), &theta);
    let got = folded_fk(&joints, &home, &theta);
    let (a, b) = (got.to_matrix4(), want.to_matrix4());
    for r in 0..3 {
        for k in 0..4 {
            let d = (a[r][k].to_f64() - b[r][k].to_f64()).abs();
            prop_assert!(d < tol * (1.0 + js.len() as f64), "({r}, {k}): {d}");
        }
    }
    for j in &joints {
        prop_assert!(j.constants().is_some() || j.kind == JointKind::Prismatic);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn folded_chain_is_the_calibrated_product_f64(c in case()) {
        check::<f64>(&c, 1e-13)?;
    }

    #[test]
    fn folded_chain_is_the_calibrated_product_f32(c in case()) {
        check::<f32>(&c, 1e-5)?;
    }
}

/// Offsets alone (no corrections): the folded chain at θ is the nominal one at θ + δ.
#[test]
fn offsets_alone_shift_the_joint_values() {
    let mut joints = vec![
        joint::<f64>(JointKind::Revolute, [0., 0., 1.], [0., 0., 0.]),
        joint::<f64>(JointKind::Revolute, [0., 1., 0.], [0.3, 0., 0.2]),
        joint::<f64>(JointKind::Prismatic, [1., 0., 0.], [0., 0., 0.]),
        joint::<f64>(JointKind::Revolute, [1., 0., 0.], [0.5, 0.1, 0.]),
    ];
    let nominal = joints.clone();
    let home0 = se3::exp(&vec6::<f64>([0.1, 0.2, -0.3, 0.6, 0.1, 0.4]));
    let mut home = home0;
    let offsets = [2e-3, -5e-3, 1e-3, 4e-3];
    fold_calibration(&mut joints, &mut home, &offsets, &[], &Vec6::zeros()).unwrap();
    let theta = [0.4, -1.1, 0.2, 2.0];
    let shifted: Vec<f64> = theta.iter().zip(&offsets).map(|(t, d)| t + d).collect();
    let want = folded_fk(&nominal, &home0, &shifted).to_matrix4();
    let got = folded_fk(&joints, &home, &theta).to_matrix4();
    for r in 0..3 {
        for k in 0..4 {
            assert!((got[r][k] - want[r][k]).abs() < 1e-14, "({r}, {k})");
        }
    }
}

/// Offsets, axis corrections, home correction and the error expected.
type BadCase<'a> = (&'a [f64], &'a [Vec6<f64>], Vec6<f64>, Error);

/// Wrong lengths and non-finite inputs are errors and change nothing.
#[test]
fn bad_inputs_are_errors_and_change_nothing() {
    let mut joints = vec![joint::<f64>(JointKind::Revolute, [0., 0., 1.], [0.1, 0., 0.]); 2];
    let before = joints.clone();
    let mut home = Transform::identity();
    let z = Vec6::zeros();
    let cases: [BadCase; 4] = [
        (&[0.0], &[], z, Error::LengthMismatch),
        (&[0.0, 0.0], &[z], z, Error::LengthMismatch),
        (&[0.0, f64::NAN], &[], z, Error::NonFinite),
        (
            &[0.0, 0.0],
            &[],
            Vec6::from([0., 0., 0., f64::INFINITY, 0., 0.]),
            Error::NonFinite,
        ),
    ];
    for (offsets, kappa, mu, err) in cases {
        assert_eq!(
            fold_calibration(&mut joints, &mut home, offsets, kappa, &mu),
            Err(err)
        );
        assert_eq!(joints, before);
        assert_eq!(home, Transform::identity());
    }
    // A correction so large that the folded screw overflows.
    let huge = [Vec6::from([0., 0., 0., 1e300, 1e300, 0.]); 2];
    assert_eq!(
        fold_calibration(&mut joints, &mut home, &[1e10, 1e10], &huge, &z),
        Err(Error::NonFinite)
    );
    assert_eq!(joints, before);
}
