//! The rank-one PPOE (`ppoe_rank1`, joint-value noise) against the dense PPOE with
//! `screw_noise` covariances, which the golden tests tie to pytransform3d: every golden
//! chain, every case, all three conventions, f64 and f32; plus random joint values and
//! variances (proptest), and the checked variant's errors.
//!
//! Error measure `max|a − b| / max|b|` over the covariance (the pose must match to 1e-12 in
//! f64): f64 ≤ 1e-14, f32 ≤ 1e-6.

mod common;
use common::*;
use ppoe::chain::{screw_noise, Chain, ChainView, Convention, Joint, JointKind};
use ppoe::{Error, Mat6, Real, Transform};
use proptest::prelude::*;

const CONVENTIONS: [Convention; 3] = [
    Convention::Right,
    Convention::Left,
    Convention::Pytransform3d,
];

/// The f32 chain's values, exactly, in f64.
fn widen(c: &Chain<f32, 6>) -> Chain<f64, 6> {
    let joints = c.joints.map(|j| {
        Joint::new(
            j.name,
            j.kind,
            j.screw.0.map(f64::from),
            f64::from(j.lower),
            f64::from(j.upper),
        )
    });
    let m = c.home.to_matrix4();
    Chain::new(
        "base",
        "tip",
        joints,
        Transform::from_matrix4(&m.map(|r| r.map(f64::from))),
    )
}

/// max|a − b| / max|b| with `a` in f32 and the oracle `b` in f64.
fn max_rel_to(a: &Mat6<f32>, b: &Mat6<f64>) -> f64 {
    let scale = b.0.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff =
        a.0.iter()
            .flatten()
            .zip(b.0.iter().flatten())
            .fold(0.0f64, |m, (x, y)| m.max((f64::from(*x) - y).abs()));
    if scale == 0.0 {
        diff
    } else {
        diff / scale
    }
}

fn max_rel<T: Real>(a: &Mat6<T>, b: &Mat6<T>) -> f64 {
    let scale =
        b.0.iter()
            .flatten()
            .fold(0.0f64, |m, x| m.max(Real::to_f64(*x).abs()));
    let diff =
        a.0.iter()
            .flatten()
            .zip(b.0.iter().flatten())
            .fold(0.0f64, |m, (x, y)| {
                m.max((Real::to_f64(*x) - Real::to_f64(*y)).abs())
            });
    if scale == 0.0 {
        diff
    } else {
        diff / scale
    }
}

/// The rank-one and dense paths on one chain at one θ: (covariance error, pose error).
fn compare<T: Real>(chain: &ChainView<'_, T>, thetas: &[T], s2: &[T], c: Convention) -> (f64, f64) {
    let covs: Vec<Mat6<T>> = chain
        .joints
        .iter()
        .zip(s2)
        .map(|(j, s)| screw_noise(&j.screw, *s))
        .collect();
    let dense = chain.ppoe(thetas, &covs, c).unwrap();
    let fast = chain.ppoe_rank1(thetas, s2, c).unwrap();
    let pose = rel_err(&flat_t(&up_t(&fast.pose)), &flat_t(&up_t(&dense.pose)));
    (max_rel(&fast.cov, &dense.cov), pose)
}

fn golden_chains<T: Real>(bound: f64) {
    let mut worst = 0.0f64;
    for file in PPOE_FILES {
        let g = golden(&format!("ppoe/{file}.json"));
        for prepared in [false, true] {
            let (mut joints, home) = chain_from_golden::<T>(&g);
            if prepared {
                joints = joints.into_iter().map(Joint::prepared).collect();
            }
            let chain = ChainView {
                joints: &joints,
                home,
            };
            let n = joints.len();
            for (k, case) in g["cases"].as_array().unwrap().iter().enumerate() {
                let thetas = vecf(&case["thetas"]);
                if Real::to_f64(T::EPS) > 1e-10 && thetas.iter().any(|t| t.abs() > 10.0) {
                    continue; // f32 rounds a 1000-rad angle by 6e-5: an input error
                }
                let th: Vec<T> = thetas.iter().map(|x| T::lit(*x)).collect();
                let s2: Vec<T> = (0..n)
                    .map(|i| T::lit(1e-4 * (1.0 + (i + k) as f64 % 3.0)))
                    .collect();
                for c in CONVENTIONS {
                    let (e, p) = compare(&chain, &th, &s2, c);
                    assert!(e <= bound, "{file} case {k} {c:?}: covariance error {e:e}");
                    assert!(p <= bound.max(1e-12), "{file} case {k} {c:?}: pose {p:e}");
                    worst = worst.max(e);
                }
            }
        }
    }
    eprintln!(
        "{}: worst rank-1 vs dense {worst:.2e}",
        core::any::type_name::<T>()
    );
}

#[test]
fn golden_chains_f64() {
    golden_chains::<f64>(1e-14);
}

#[test]
fn golden_chains_f32() {
    golden_chains::<f32>(1e-6);
}

/// Independent of both PPOE loops: Σ_right = J_b·diag(σ²)·J_bᵀ with the body Jacobian,
/// Σ_left = J_s·diag(σ²)·J_sᵀ with the space Jacobian.
#[test]
fn jacobian_identity() {
    let g = golden("ppoe/seed_linkmount_tcp.json");
    let (joints, home) = chain_from_golden::<f64>(&g);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let th = [0.3, -0.4, 0.2, 0.5, -0.1, 0.7];
    let s2 = [1e-4, 2e-4, 3e-4, 4e-4, 5e-4, 6e-4];
    for (c, body) in [(Convention::Right, true), (Convention::Left, false)] {
        let mut cols = [ppoe::Vec6::zeros(); 6];
        if body {
            chain.body_jacobian(&th, &mut cols).unwrap();
        } else {
            chain.space_jacobian(&th, &mut cols).unwrap();
        }
        let mut want = Mat6::<f64>::zeros();
        for (u, s) in cols.iter().zip(s2) {
            want += u.outer(u).scale(s);
        }
        let got = chain.ppoe_rank1(&th, &s2, c).unwrap().cov;
        assert!(max_rel(&got, &want) < 1e-14, "{c:?}");
    }
}

const INF: f64 = f64::INFINITY;
/// A 6-joint arm with a prismatic joint, offsets and tilted axes (not a golden chain).
const ARM: Chain<f64, 6> = Chain::new(
    "base",
    "tip",
    [
        Joint::new("a", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -3., 3.),
        Joint::new(
            "b",
            JointKind::Revolute,
            [0., 1., 0., -0.4, 0., 0.1],
            -2.,
            2.,
        ),
        Joint::new(
            "c",
            JointKind::Prismatic,
            [0., 0., 0., 0.6, 0., 0.8],
            0.,
            0.5,
        ),
        Joint::new(
            "d",
            JointKind::Continuous,
            [1., 0., 0., 0., 0.9, -0.2],
            -1.,
            1.,
        ),
        Joint::new(
            "e",
            JointKind::Revolute,
            [0., 0.6, 0.8, 0.3, -0.8, 0.6],
            -INF,
            INF,
        ),
        Joint::new(
            "f",
            JointKind::Revolute,
            [0., 0., 1., 0.2, -1.1, 0.],
            -3.,
            3.,
        ),
    ],
    Transform::from_parts([[0., -1., 0.], [1., 0., 0.], [0., 0., 1.]], [1.1, 0.2, 0.9]),
);

/// The worst f32 error of both paths against the f64 oracle over 20,000 random states of
/// `ARM`, per convention: the figures the `random_f32` bounds and the rank-one PPOE's docs cite.
/// `cargo test --release -p ppoe --test ppoe_rank1 -- --ignored --nocapture`
#[test]
#[ignore = "a measurement (20,000 states), not a check"]
fn worst_f32_error_over_random_states() {
    let arm32 = Chain::new(
        "base",
        "tip",
        ARM.joints.map(|j| Joint::from_f64(&j)),
        Transform::<f32>::from_f64(&ARM.home),
    );
    let arm64 = widen(&arm32);
    let mut state = 12345u64;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for c in CONVENTIONS {
        let (mut fast_worst, mut dense_worst) = (0.0f64, 0.0f64);
        for _ in 0..20_000 {
            let th: [f32; 6] = std::array::from_fn(|_| (uniform() * 8.0 - 4.0) as f32);
            let s2: [f32; 6] = std::array::from_fn(|_| (uniform() * 1e-2) as f32);
            let (th64, s64) = (th.map(f64::from), s2.map(f64::from));
            let truth = arm64.ppoe(&th64, &ppoe::chain::dense_covariances(&arm64, &s64), c);
            let dense = arm32.ppoe(&th, &ppoe::chain::dense_covariances(&arm32, &s2), c);
            let fast = arm32.ppoe_rank1(&th, &s2, c);
            fast_worst = fast_worst.max(max_rel_to(&fast.cov, &truth.cov));
            dense_worst = dense_worst.max(max_rel_to(&dense.cov, &truth.cov));
        }
        println!("{c:?}: rank-one worst {fast_worst:.2e}, dense worst {dense_worst:.2e}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    #[test]
    fn random_f64(th in proptest::array::uniform6(-4.0f64..4.0),
                  s2 in proptest::array::uniform6(0.0f64..1e-2)) {
        for c in CONVENTIONS {
            let dense = ARM.ppoe(&th, &ppoe::chain::dense_covariances(&ARM, &s2), c);
            let fast = ARM.ppoe_rank1(&th, &s2, c);
            prop_assert!(max_rel(&fast.cov, &dense.cov) <= 1e-14);
            prop_assert!(rel_err(&flat_t(&fast.pose), &flat_t(&dense.pose)) <= 1e-14);
            prop_assert_eq!(fast.cov, fast.cov.transpose());
        }
    }

    #[test]
    fn random_f32(th in proptest::array::uniform6(-4.0f32..4.0),
                  s2 in proptest::array::uniform6(0.0f32..1e-2)) {
        let arm32 = Chain::new("base", "tip", ARM.joints.map(|j| Joint::from_f64(&j)),
                               Transform::<f32>::from_f64(&ARM.home));
        // The oracle is the f64 computation of the same (f32-rounded) inputs: the dense f32
        // path itself can be off by more than 1e-6 relative (the Left convention's extra
        // congruence with the tool pose's lever arm: 1.2e-6 in the shrunk case that showed
        // it), so comparing the two f32 paths with each other would test the dense path.
        let th64 = th.map(f64::from);
        let s64 = s2.map(f64::from);
        let arm64 = widen(&arm32);
        for c in CONVENTIONS {
            let truth = arm64.ppoe(&th64, &ppoe::chain::dense_covariances(&arm64, &s64), c);
            let dense = arm32.ppoe(&th, &ppoe::chain::dense_covariances(&arm32, &s2), c);
            let fast = arm32.ppoe_rank1(&th, &s2, c);
            // Left sums the transports in the base frame, where lever arms from the base
            // to each joint cancel: over 20,000 random states of this arm
            // (`worst_f32_error_over_random_states`) the f32 rank-one
            // path's worst error is 1.1e-6 there (the dense path's 1.7e-6), 8.3e-7 in the
            // tip frame (dense 7.5e-7). Bounds: 16ε (Left) and 8ε (the tip frame).
            let bound = if c == Convention::Left { 16.0 } else { 8.0 } * f64::from(f32::EPSILON);
            prop_assert!(max_rel_to(&fast.cov, &truth.cov) <= bound);
            prop_assert!(max_rel_to(&dense.cov, &truth.cov) <= 1e-5);
        }
    }
}

#[test]
fn checked_errors() {
    let th = [0.1; 6];
    let ok = [1e-4; 6];
    assert!(ARM.ppoe_rank1_checked(&th, &ok, Convention::Right).is_ok());
    let mut bad = ok;
    bad[2] = f64::NAN;
    assert_eq!(
        ARM.ppoe_rank1_checked(&th, &bad, Convention::Right),
        Err(Error::NonFinite)
    );
    bad[2] = -1e-6;
    assert_eq!(
        ARM.ppoe_rank1_checked(&th, &bad, Convention::Right),
        Err(Error::NotPositiveSemidefinite)
    );
    let mut th_bad = th;
    th_bad[0] = f64::INFINITY;
    assert_eq!(
        ARM.ppoe_rank1_checked(&th_bad, &ok, Convention::Left),
        Err(Error::NonFinite)
    );
    // Finite inputs whose product overflows: the output check catches it.
    assert_eq!(
        ARM.ppoe_rank1_checked(&th, &[1e308; 6], Convention::Right),
        Err(Error::Overflow)
    );
    let r = ARM.as_ref();
    assert_eq!(
        r.ppoe_rank1(&th[..5], &ok, Convention::Right),
        Err(Error::LengthMismatch)
    );
    assert_eq!(
        r.ppoe_rank1_checked(&th, &ok[..5], Convention::Right),
        Err(Error::LengthMismatch)
    );
    let mut broken = ARM;
    broken.joints[1].screw.0[1] = 2.0; // not a unit axis
    assert_eq!(
        broken.ppoe_rank1_checked(&th, &ok, Convention::Right),
        Err(Error::NotUnitAxis)
    );
}
