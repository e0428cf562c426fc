//! Robustness of the covariance results and of the checked entry points, by class of
//! input, for f32 and f64 through the same generic code (issue "nothing silently wrong",
//! items 3, 5, 6):
//! * fourth-order compounding: `Order::Fourth` (pytransform3d's numbers) is indefinite on
//!   ordinary PSD inputs; `Order::FourthPsd` is PSD and is exactly the nearest PSD matrix
//!   (checked with nalgebra's eigen-solver, independent of ours);
//! * the fourth-order PPOE is PSD;
//! * `check_covariance` at every magnitude, `ppoe_checked` when the result overflows,
//!   estimators whose differences overflow, and the error a non-unit axis gets.

mod common;
use common::{chain_from_golden, golden, seed_covs, seed_frame, PPOE_FILES};
use ppoe::chain::{ChainView, Convention, Joint, JointKind};
use ppoe::uncertainty::{self, check_covariance, Order};
use ppoe::{se3, Error, Mat6, Matrix, Real, Transform, Vec6, Vector};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};

fn m6<T: Real>(m: &Mat6<f64>) -> Mat6<T> {
    Matrix(m.0.map(|r| r.map(T::lit)))
}

/// Eigenvalues (ascending) of the symmetric part of `m`, by nalgebra, in f64.
fn eigenvalues<T: Real>(m: &Mat6<T>) -> Vec<f64> {
    let a = nalgebra::Matrix6::from_fn(|i, j| 0.5 * (m.0[i][j].to_f64() + m.0[j][i].to_f64()));
    let mut v: Vec<f64> = a.symmetric_eigenvalues().iter().copied().collect();
    v.sort_by(f64::total_cmp);
    v
}

/// A random covariance like the reference's test distribution: `A·Aᵀ·scale` with A 6×r
/// Gaussian (rank r from 1 to 6), scale 10^[−3, 0].
fn random_psd(rng: &mut impl Rng) -> Mat6<f64> {
    let r = rng.gen_range(1..=6);
    let scale = 10f64.powf(rng.gen_range(-3.0..0.0));
    let mut a = Mat6::<f64>::zeros();
    for row in a.0.iter_mut() {
        for x in row.iter_mut().take(r) {
            *x = rng.gen_range(-1.0..1.0);
        }
    }
    a.mul_tr(&a).scale(scale / r as f64)
}

/// Random poses: rotation up to π, translation up to 2 m.
fn random_pose(rng: &mut impl Rng) -> Transform<f64> {
    let xi: [f64; 6] = std::array::from_fn(|i| {
        if i < 3 {
            rng.gen_range(-1.8..1.8)
        } else {
            rng.gen_range(-2.0..2.0)
        }
    });
    se3::exp(&Vector(xi))
}

/// The relative PSD tolerance of a computed covariance: its rounding, a few dozen ε of
/// its largest eigenvalue (the eigenvalues of a rounded symmetric matrix move by at
/// most ‖E‖₂ ≤ 6·max|Eᵢⱼ|, Weyl).
fn psd_tol<T: Real>() -> f64 {
    64.0 * T::EPS.to_f64()
}

/// Fourth order on one input pair: `FourthPsd` is PSD; equals `Fourth` bit for bit when
/// that is positive definite; otherwise differs from it by exactly its negative part
/// (‖FourthPsd − Fourth‖_F = √Σ λ₋², the Frobenius distance to the PSD cone). Returns
/// whether `Fourth` was indefinite beyond rounding.
fn fourth_case<T: Real>(
    a: &Transform<f64>,
    ca: &Mat6<f64>,
    b: &Transform<f64>,
    cb: &Mat6<f64>,
) -> bool {
    let (a, b) = (Transform::<T>::from_f64(a), Transform::<T>::from_f64(b));
    let (ca, cb) = (m6::<T>(ca), m6::<T>(cb));
    let (_, raw) = uncertainty::concat_globally(&a, &ca, &b, &cb, Order::Fourth);
    let (_, psd) = uncertainty::concat_globally(&a, &ca, &b, &cb, Order::FourthPsd);
    let lr = eigenvalues(&raw);
    let lp = eigenvalues(&psd);
    let top = lr[5].abs().max(lp[5].abs());
    let name = std::any::type_name::<T>();
    assert!(
        lp[0] >= -psd_tol::<T>() * top,
        "{name}: FourthPsd λmin = {:e}·λmax",
        lp[0] / top
    );
    assert_eq!(psd.asymmetry(), T::ZERO);
    if raw.cholesky().is_some() {
        assert_eq!(
            raw, psd,
            "{name}: a positive definite Fourth must be returned as is"
        );
    }
    let neg: f64 = lr
        .iter()
        .filter(|l| **l < 0.0)
        .map(|l| l * l)
        .sum::<f64>()
        .sqrt();
    let dist = {
        let d = psd - raw;
        d.0.iter()
            .flatten()
            .map(|x| Real::to_f64(*x).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    assert!(
        (dist - neg).abs() <= psd_tol::<T>() * top,
        "{name}: moved by {dist:e}, the negative part is {neg:e}"
    );
    lr[0] < -psd_tol::<T>() * top
}

/// Over 400 random pairs from the reference's kind of distribution, `FourthPsd` is always
/// PSD and minimal; the class is exercised (some `Fourth` results are indefinite).
#[test]
fn fourth_order_psd_random() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(16);
    let mut indefinite = [0usize; 2];
    for _ in 0..400 {
        let (a, b) = (random_pose(&mut rng), random_pose(&mut rng));
        let (ca, cb) = (random_psd(&mut rng), random_psd(&mut rng));
        indefinite[0] += usize::from(fourth_case::<f64>(&a, &ca, &b, &cb));
        indefinite[1] += usize::from(fourth_case::<f32>(&a, &ca, &b, &cb));
    }
    println!("Order::Fourth indefinite in {indefinite:?} of 400 (f64, f32)");
    assert!(indefinite[0] > 0 && indefinite[1] > 0);
}

/// Two single-axis rotation variances of 0.05 rad² (the seed example's) between 100
/// random poses: `Fourth` is indefinite for almost all of them (beyond f32's rounding
/// for fewer), `FourthPsd` for none.
#[test]
fn fourth_order_single_axis() {
    fn case<T: Real>() -> usize {
        let z = Mat6::from_diagonal(&Vector([0.0, 0.0, 0.05, 0.0, 0.0, 0.0]));
        let y = Mat6::from_diagonal(&Vector([0.0, 0.05, 0.0, 0.0, 0.0, 0.0]));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        (0..100)
            .filter(|_| {
                let (a, b) = (random_pose(&mut rng), random_pose(&mut rng));
                fourth_case::<T>(&a, &z, &b, &y)
            })
            .count()
    }
    let (n64, n32) = (case::<f64>(), case::<f32>());
    println!("Order::Fourth indefinite in {n64} (f64), {n32} (f32) of 100");
    assert!(n64 >= 90 && n32 > 0);
}

/// The fourth-order PPOE of every test chain (the seed robot, prismatic, fixed-between,
/// continuous, RPY and tree chains) at 30 random joint vectors, with the seed example's
/// single-axis covariances (seed robot) or random PSD covariances of the reference's
/// distribution, scaled up to 10× (large noise, where the fourth-order terms matter): PSD.
#[test]
fn fourth_order_ppoe_is_psd() {
    fn case<T: Real>() -> f64 {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut worst = 0.0f64;
        for file in PPOE_FILES {
            let g = golden(&format!("ppoe/{file}.json"));
            let (joints, home) = chain_from_golden::<T>(&g);
            let chain = ChainView {
                joints: &joints,
                home,
            };
            for k in 0..30 {
                let th: Vec<T> = if file.starts_with("seed") && k < 10 {
                    seed_frame(k * 20).iter().map(|x| T::lit(*x)).collect()
                } else {
                    joints
                        .iter()
                        .map(|_| T::lit(rng.gen_range(-1.5..1.5)))
                        .collect()
                };
                let covs: Vec<Mat6<T>> = if file.starts_with("seed") && k < 10 {
                    seed_covs(1.0).iter().map(m6).collect()
                } else {
                    let s = 10f64.powf(rng.gen_range(-1.0..1.0));
                    (0..joints.len())
                        .map(|_| m6(&random_psd(&mut rng).scale(s)))
                        .collect()
                };
                for conv in [Convention::Right, Convention::Left] {
                    let out = chain.ppoe_fourth_order(&th, &covs, conv).unwrap();
                    let l = eigenvalues(&out.cov);
                    worst = worst.min(l[0] / l[5]);
                    assert!(
                        l[0] >= -psd_tol::<T>() * l[5],
                        "{}: {file} #{k} {conv:?}: λmin = {:e}·λmax",
                        std::any::type_name::<T>(),
                        l[0] / l[5]
                    );
                }
            }
        }
        worst
    }
    println!(
        "ppoe_fourth_order worst λmin/λmax: {:e} (f64), {:e} (f32)",
        case::<f64>(),
        case::<f32>()
    );
}

/// A covariance with the given eigenvalues in a random orthonormal basis (from the QR of
/// a random matrix, by nalgebra), in f64.
fn with_eigenvalues(rng: &mut impl Rng, l: [f64; 6]) -> Mat6<f64> {
    let a = nalgebra::Matrix6::<f64>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    let q = a.qr().q();
    let m = q * nalgebra::Matrix6::from_diagonal(&nalgebra::Vector6::from(l)) * q.transpose();
    let mut out = Mat6::zeros();
    for i in 0..6 {
        for j in 0..6 {
            out.0[i][j] = 0.5 * (m[(i, j)] + m[(j, i)]);
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A PSD covariance (smallest eigenvalue 0 or tiny) passes at any magnitude, an
    /// indefinite one (λmin = −10⁻²·λmax, far beyond the √ε tolerance) fails at any
    /// magnitude: the check works on Σ/‖Σ‖_max, so no square overflows or underflows.
    #[test]
    fn check_covariance_any_magnitude(
        seed in any::<u64>(),
        e64 in -1000..1000i32,
        e32 in -120..120i32,
        l in prop::array::uniform5(0.01..1.0f64),
    ) {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let psd = with_eigenvalues(&mut rng, [l[0], l[1], l[2], l[3], l[4], 0.0]);
        let bad = with_eigenvalues(&mut rng, [1.0, l[1], l[2], l[3], l[4], -0.01]);
        magnitude_case::<f64>(&psd, &bad, e64);
        magnitude_case::<f32>(&psd, &bad, e32);
    }

    /// `ppoe_checked` on finite, valid inputs whose result may overflow (a lever arm
    /// of 2^k m, covariances of 2^j): either `Ok` with a finite result or
    /// `Err(Overflow)`, never `Ok` with ±∞/NaN and never "input contains NaN".
    #[test]
    fn ppoe_checked_overflow(k in 0..700i32, j in -10..700i32, theta in -3.0..3.0f64) {
        overflow_case::<f64>(k, j, theta);
        overflow_case::<f32>(k / 5, j / 5, theta);
    }
}

fn magnitude_case<T: Real>(psd: &Mat6<f64>, bad: &Mat6<f64>, e: i32) {
    let s = 2f64.powi(e);
    let psd = m6::<T>(&psd.scale(s)).symmetrize();
    let bad = m6::<T>(&bad.scale(s)).symmetrize();
    // Only where the scaled matrix is still a faithful copy (no underflow to zero or
    // subnormal loss of the eigenvalue structure): the largest element is normal/ε.
    if psd.amax() < T::min_positive_value() / T::EPS || !psd.is_finite() || !bad.is_finite() {
        return;
    }
    let name = std::any::type_name::<T>();
    assert_eq!(check_covariance(&psd), Ok(()), "{name}: PSD at 2^{e}");
    assert_eq!(
        check_covariance(&bad),
        Err(Error::NotPositiveSemidefinite),
        "{name}: indefinite at 2^{e}"
    );
}

fn overflow_case<T: Real>(k: i32, j: i32, theta: f64) {
    let lever = T::lit(2f64.powi(k));
    let var = T::lit(2f64.powi(j));
    if !lever.is_finite() || !var.is_finite() || var == T::ZERO {
        return;
    }
    // Two revolute joints about z, the second at x = lever; the tip at x = 2·lever.
    let joints = [
        Joint::new(
            "a",
            JointKind::Revolute,
            [T::ZERO, T::ZERO, T::ONE, T::ZERO, T::ZERO, T::ZERO],
            -T::infinity(),
            T::infinity(),
        ),
        Joint::new(
            "b",
            JointKind::Revolute,
            [T::ZERO, T::ZERO, T::ONE, T::ZERO, -lever, T::ZERO],
            -T::infinity(),
            T::infinity(),
        ),
    ];
    let mut home = Transform::identity();
    home.translation.0[0] = lever + lever;
    if !home.translation.is_finite() {
        return;
    }
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let cov = Mat6::<T>::identity().scale(var);
    let th = [T::lit(theta), T::lit(-theta)];
    for conv in [
        Convention::Right,
        Convention::Left,
        Convention::Pytransform3d,
    ] {
        match chain.ppoe_checked(&th, &[cov, cov], conv) {
            Ok(out) => assert!(
                out.cov.is_finite() && out.pose.translation.is_finite(),
                "{}: Ok with a non-finite result",
                std::any::type_name::<T>()
            ),
            Err(e) => assert_eq!(e, Error::Overflow, "lever 2^{k}, variance 2^{j}"),
        }
    }
}

/// Lever arms beyond √max with unit variances do overflow: the error class is reached.
#[test]
fn ppoe_checked_overflow_is_reported() {
    fn case<T: Real>() {
        let lever = T::max_value().sqrt() * T::lit(4.0);
        let joints = [Joint::new(
            "a",
            JointKind::Revolute,
            [T::ZERO, T::ZERO, T::ONE, T::ZERO, -lever, T::ZERO],
            -T::infinity(),
            T::infinity(),
        )];
        let mut home = Transform::identity();
        home.translation.0[0] = lever;
        let chain = ChainView {
            joints: &joints,
            home,
        };
        let out = chain.ppoe_checked(&[T::ONE], &[Mat6::identity()], Convention::Left);
        assert_eq!(out.err(), Some(Error::Overflow));
        assert!(Error::Overflow.to_string().contains("overflow"));
    }
    case::<f64>();
    case::<f32>();
}

/// An axis of length 2 is `NotUnitAxis` ("not a unit vector"), a zero one `ZeroAxis`;
/// for revolute (rotation part) and prismatic (translation part) joints.
#[test]
fn chain_axis_errors() {
    fn case<T: Real>() {
        let l = |x: f64| T::lit(x);
        let cases = [
            (
                JointKind::Revolute,
                [l(0.0), l(0.0), l(2.0), l(0.0), l(0.0), l(0.0)],
                Error::NotUnitAxis,
            ),
            (
                JointKind::Revolute,
                [l(0.0), l(0.0), l(1e-20), l(0.0), l(0.0), l(0.0)],
                Error::NotUnitAxis,
            ),
            (JointKind::Revolute, [l(0.0); 6], Error::ZeroAxis),
            (
                JointKind::Prismatic,
                [l(0.0), l(0.0), l(0.0), l(0.0), l(2.0), l(0.0)],
                Error::NotUnitAxis,
            ),
            (JointKind::Prismatic, [l(0.0); 6], Error::ZeroAxis),
        ];
        for (kind, screw, err) in cases {
            let joints = [Joint::new("j", kind, screw, -T::infinity(), T::infinity())];
            let chain = ChainView {
                joints: &joints,
                home: Transform::identity(),
            };
            assert_eq!(chain.check(), Err(err), "{kind:?} {screw:?}");
        }
        assert!(Error::NotUnitAxis.to_string().contains("not a unit vector"));
    }
    case::<f64>();
    case::<f32>();
}

/// Finite samples whose differences overflow: `Overflow`, not "input contains NaN".
#[test]
fn estimator_overflow() {
    fn case<T: Real>() {
        let mut a = Transform::<T>::identity();
        let mut b = a;
        a.translation.0[0] = T::max_value() * T::lit(0.75);
        b.translation.0[0] = -T::max_value() * T::lit(0.75);
        let e = uncertainty::estimate_gaussian_transform(&[a, b]);
        assert_eq!(e.err(), Some(Error::Overflow));
        let _ = Vec6::<T>::zeros();
    }
    case::<f64>();
    case::<f32>();
}

/// Issue #26 item 4's matrix at scale s: diagonal s, Σ₀₁ = s/2 and Σ₁₀ = −s/2, so its
/// asymmetry is s itself, 100 % of its scale. Its symmetric part, s·I, is PSD: only the
/// symmetry check can reject it.
fn antisymmetric_by_its_scale<T: Real>(s: f64) -> Mat6<T> {
    let mut m = Mat6::<f64>::identity().scale(s);
    m.0[0][1] = 0.5 * s;
    m.0[1][0] = -0.5 * s;
    m6(&m)
}

/// A PSD covariance of scale s whose only asymmetry is `rel`·s in Σ₂₄ (Σ₄₂ unchanged).
fn symmetric_but<T: Real>(s: f64, rel: f64) -> Mat6<T> {
    let mut m = Mat6::<f64>::zeros();
    for (i, row) in m.0.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = if i == j {
                1.0
            } else {
                0.1 / (1 + i + j) as f64
            };
        }
    }
    let mut m: Mat6<T> = m6(&m.scale(s));
    m.0[2][4] += T::lit(rel * s);
    m
}

/// The symmetry check is relative to the matrix's scale (`max|Σᵢⱼ − Σⱼᵢ| ≤ TOL·‖Σ‖_max`,
/// the documented rule): at every scale from 10⁻⁸ to 10⁴, in f32 and f64, the issue's
/// matrix is rejected, so is an asymmetry of 2·TOL of the scale; a symmetric covariance,
/// one with rounding-level asymmetry (4 ulps of its scale) and one with 0.5·TOL are
/// accepted. Before, the tolerance was TOL·max(1, ‖Σ‖_max): absolute below 1, so every
/// matrix of these with scale ≤ 10⁻⁸ passed.
fn symmetry_is_relative<T: Real>() {
    let name = std::any::type_name::<T>();
    let tol = T::TOL.to_f64();
    for e in -8..=4 {
        let s = 10f64.powi(e);
        let cases = [
            (
                antisymmetric_by_its_scale::<T>(s),
                false,
                "issue #26's matrix",
            ),
            (symmetric_but::<T>(s, 2.0 * tol), false, "2·TOL asymmetric"),
            (symmetric_but::<T>(s, 0.5 * tol), true, "0.5·TOL asymmetric"),
            (
                symmetric_but::<T>(s, 4.0 * T::EPS.to_f64()),
                true,
                "4 ulps asymmetric",
            ),
            (symmetric_but::<T>(s, 0.0), true, "symmetric"),
        ];
        for (m, ok, what) in cases {
            let want = if ok { Ok(()) } else { Err(Error::NotSymmetric) };
            assert_eq!(check_covariance(&m), want, "{name} {what} at 1e{e}");
        }
    }
}

#[test]
fn symmetry_is_relative_f64() {
    symmetry_is_relative::<f64>();
}

#[test]
fn symmetry_is_relative_f32() {
    symmetry_is_relative::<f32>();
}

/// `ppoe_checked` (also what the C API's checked PPOE calls) rejects a joint covariance
/// that is antisymmetric by its own small scale, at every scale, in f32 and f64.
fn ppoe_checked_rejects_small_asymmetry<T: Real>() {
    let g = golden("ppoe/seed_linkmount_tcp.json");
    let (joints, home) = chain_from_golden::<T>(&g);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let th = vec![T::lit(0.1); joints.len()];
    for e in -8..=4 {
        let s = 10f64.powi(e);
        let mut covs = vec![Mat6::<T>::identity().scale(T::lit(s)); joints.len()];
        assert!(chain.ppoe_checked(&th, &covs, Convention::Right).is_ok());
        covs[1] = antisymmetric_by_its_scale(s);
        assert_eq!(
            chain.ppoe_checked(&th, &covs, Convention::Right),
            Err(Error::NotSymmetric),
            "{} at 1e{e}",
            std::any::type_name::<T>()
        );
    }
}

#[test]
fn ppoe_checked_rejects_small_asymmetry_f64() {
    ppoe_checked_rejects_small_asymmetry::<f64>();
}

#[test]
fn ppoe_checked_rejects_small_asymmetry_f32() {
    ppoe_checked_rejects_small_asymmetry::<f32>();
}
