//! The `core_f64` / `core_f32` oracle: one generic body.

use crate::*;
use arbitrary::Arbitrary;
use ppoe::chain::{ChainView, Convention, Joint, JointKind};
use ppoe::linalg::SymmetricEigen;
use ppoe::uncertainty::{self, check_covariance, IterationOptions, Order};
use ppoe::{se3, Error};
use std::hint::black_box;

/// One joint of the fuzzed chain.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub struct JointIn {
    /// 0 revolute, 1 continuous, 2 prismatic (mod 3).
    pub kind: u8,
    /// The axis direction (normalised here; a raw screw if `raw`).
    pub axis: [FVal; 3],
    /// A point on the axis.
    pub q: [FVal; 3],
    /// Limits.
    pub lower: FVal,
    /// Limits.
    pub upper: FVal,
    /// Use the six values `axis ++ q` as the screw as they are.
    pub raw: bool,
}

/// The whole `core_*` input.
#[derive(Arbitrary, Debug)]
pub struct CoreInput {
    /// A transform for `Transform::check`, exp/log, concatenation, inversion.
    pub t1: TransformIn,
    /// A second transform.
    pub t2: TransformIn,
    /// Covariances.
    pub c1: CovIn,
    /// Covariances.
    pub c2: CovIn,
    /// A twist for the unchecked exp / Jacobians.
    pub xi: [FVal; 6],
    /// The chain: 1 to 3 joints (count = 1 + n % 3).
    pub n_joints: u8,
    /// The joints.
    pub joints: [JointIn; 3],
    /// The home pose.
    pub home: TransformIn,
    /// Joint values.
    pub thetas: [FVal; 3],
    /// Joint covariances: index into (c1, c2, c3) per joint.
    pub cov_pick: [u8; 3],
    /// A third covariance.
    pub c3: CovIn,
    /// Fusion / estimation samples (count = n % 5).
    pub n_samples: u8,
    /// Samples: transforms (exp of a twist, or raw).
    pub samples: [TransformIn; 4],
}

fn bounded<T: Fz>(x: T) -> bool {
    x.is_finite() && x.abs().to_f64() <= T::BOUND
}

fn vec_bounded<T: Fz, const N: usize>(v: &Vector<T, N>) -> bool {
    v.0.iter().all(|&x| bounded(x))
}

/// Covariance entries are bounded by BOUND² (a variance of BOUND).
/// and, unless zero, not below √MIN_POSITIVE (so that the rounding of the transport does
/// not reach the subnormal range, where relative accuracy is lost).
fn cov_bounded<T: Fz>(c: &Mat6<T>) -> bool {
    let s = mat_amax(c);
    c.is_finite()
        && s.to_f64() <= T::BOUND * T::BOUND
        && (s == T::ZERO || s >= T::min_positive_value().sqrt())
}

/// A transform in the valid domain: passes `check`, translation bounded.
fn transform_valid<T: Fz>(t: &Transform<T>) -> bool {
    t.check().is_ok() && vec_bounded(&t.translation)
}

/// Checks `Transform::check` against the independent computation.
fn check_transform<T: Fz>(t: &Transform<T>) {
    let r = t.check();
    if !transform_finite(t) {
        assert_eq!(
            r,
            Err(Error::NonFinite),
            "Transform::check ({}) of {t:?}",
            T::NAME
        );
    }
    if r.is_ok() {
        assert_rigid("Transform::check accepted", t, T::TOL);
    }
}

/// Checks `check_covariance` against the eigenvalues.
fn check_cov_input<T: Fz>(c: &Mat6<T>) {
    let r = check_covariance(c);
    if !c.is_finite() {
        assert_eq!(
            r,
            Err(Error::NonFinite),
            "check_covariance ({}) of {c:?}",
            T::NAME
        );
        return;
    }
    if r.is_ok() {
        let s = mat_amax(c);
        assert!(
            c.asymmetry() <= T::TOL * s,
            "check_covariance ({}) accepted an asymmetric matrix {c:?}",
            T::NAME
        );
        // Eigenvalues (of the symmetric part) no lower than −tol·s, up to the rounding of
        // the Cholesky test and of the eigen-solver.
        if s.to_f64() < T::max_value().to_f64() / 64.0 {
            let eig = SymmetricEigen::new(&c.symmetrize()).expect("finite");
            let floor = -(T::TOL * s * T::lit(2.0)
                + T::lit(256.0) * T::EPS * s
                + T::lit(4.0) * T::min_positive_value());
            assert!(
                eig.min_value() >= floor,
                "check_covariance ({}) accepted λ_min = {:e} < {:e}: {c:?}",
                T::NAME,
                eig.min_value().to_f64(),
                floor.to_f64()
            );
        }
    }
}

/// The generic body of the `core_f64` and `core_f32` targets.
pub fn run<T: Fz>(inp: &CoreInput) {
    let t1: Transform<T> = inp.t1.get();
    let t2: Transform<T> = inp.t2.get();
    let c1: Mat6<T> = inp.c1.get();
    let c2: Mat6<T> = inp.c2.get();
    let c3: Mat6<T> = inp.c3.get();
    let xi: Vec6<T> = vals(&inp.xi);

    // --- Input checks --------------------------------------------------------------
    for t in [&t1, &t2] {
        check_transform(t);
    }
    for c in [&c1, &c2, &c3] {
        check_cov_input(c);
    }
    unchecked_never_panic(&t1, &t2, &c1, &c2, &xi);
    unchecked_valid_domain(&t1, &t2, &c1, &c2, &xi);
    checked_uncertain(&t1, &t2, &c1, &c2);
    let pool = [c1, c2, c3];
    check_chain(inp, &pool);
    check_fusion_and_estimation(inp, &pool);
}

/// A covariance in the valid domain: passes `check_covariance`, entries bounded.
fn cov_ok<T: Fz>(c: &Mat6<T>) -> bool {
    check_covariance(c).is_ok() && cov_bounded(c)
}

/// Unchecked operations: must not panic on anything.
fn unchecked_never_panic<T: Fz>(
    t1: &Transform<T>,
    t2: &Transform<T>,
    c1: &Mat6<T>,
    c2: &Mat6<T>,
    xi: &Vec6<T>,
) {
    black_box(se3::exp(xi));
    black_box(se3::log(t1));
    black_box(so3::exp(&xi.rotation()));
    black_box(so3::log(&t1.rotation));
    black_box(so3::log_axis_angle(&t2.rotation));
    black_box(se3::left_jacobian(xi));
    black_box(se3::left_jacobian_inv(xi));
    black_box(so3::left_jacobian_inv(&xi.rotation()));
    black_box(se3::curly_hat(xi));
    black_box(t1.adjoint());
    black_box(t1.inverse());
    black_box(t1.transport_covariance(c1));
    for order in [Order::Second, Order::Fourth] {
        black_box(uncertainty::concat_globally(t1, c1, t2, c2, order));
    }
    black_box(uncertainty::concat_locally(t1, t2, c1, c2));
    black_box(uncertainty::invert(t1, c1));
    black_box(uncertainty::left_to_right(t1, c1));
    black_box(ppoe::surface::position_mean_second_order(t1, c1));
    black_box(se3::screw_axis(&xi.rotation(), &xi.translation(), c1.0[0][0]).ok());
    black_box(ppoe::chain::screw_noise(xi, c1.0[1][1]));
    black_box(ppoe::chain::bending_noise(
        &xi.translation(),
        &c1.block(0, 0),
    ));
}

/// Valid-domain properties of the unchecked operations.
fn unchecked_valid_domain<T: Fz>(
    t1: &Transform<T>,
    t2: &Transform<T>,
    c1: &Mat6<T>,
    c2: &Mat6<T>,
    xi: &Vec6<T>,
) {
    if vec_bounded(xi) {
        let e = se3::exp(xi);
        assert_rigid("se3::exp of a bounded twist", &e, T::TOL);
        let l = se3::log(&e);
        assert!(
            l.is_finite(),
            "se3::log ({}) of exp({xi:?}) = {l:?}",
            T::NAME
        );
    }
    if !transform_valid(t1) {
        return;
    }
    let l = se3::log(t1);
    assert!(
        l.is_finite(),
        "se3::log ({}) of valid {t1:?} = {l:?}",
        T::NAME
    );
    if cov_ok(c1) {
        let (inv, ic) = uncertainty::invert(t1, c1);
        assert_rigid("invert mean", &inv, T::TOL * T::lit(2.0));
        assert_sym("invert cov", &ic);
    }
    if transform_valid(t2) && cov_ok(c1) && cov_ok(c2) {
        for order in [Order::Second, Order::Fourth] {
            let (m, c) = uncertainty::concat_globally(t1, c1, t2, c2, order);
            assert_rigid("concat_globally mean", &m, T::TOL * T::lit(3.0));
            assert_sym("concat_globally cov", &c);
        }
        let (m, c) = uncertainty::concat_locally(t1, t2, c1, c2);
        assert_rigid("concat_locally mean", &m, T::TOL * T::lit(3.0));
        assert_sym("concat_locally cov", &c);
    }
}

/// The checked concatenations and inversion: `Ok` exactly when every input passes its
/// check and the unchecked result is finite, and then with the unchecked result's bits.
fn checked_uncertain<T: Fz>(t1: &Transform<T>, t2: &Transform<T>, c1: &Mat6<T>, c2: &Mat6<T>) {
    let inputs_ok = t1.check().is_ok()
        && t2.check().is_ok()
        && check_covariance(c1).is_ok()
        && check_covariance(c2).is_ok();
    let expect =
        |name: &str, got: Result<(Transform<T>, Mat6<T>), Error>, want: (Transform<T>, Mat6<T>)| {
            let finite = transform_finite(&want.0) && want.1.is_finite();
            match got {
                Ok(r) => {
                    assert!(
                        inputs_ok && finite,
                        "{name} ({}) accepted {t1:?} {t2:?} {c1:?} {c2:?}",
                        T::NAME
                    );
                    assert_eq!(r, want, "{name} ({}): not the unchecked result", T::NAME);
                }
                Err(Error::Overflow) => assert!(
                    inputs_ok && !finite,
                    "{name} ({}): overflow of a finite result",
                    T::NAME
                ),
                Err(e) => assert!(
                    !inputs_ok,
                    "{name} ({}) rejected valid inputs: {e:?}",
                    T::NAME
                ),
            }
        };
    let order = Order::FourthPsd;
    let g = uncertainty::concat_globally_checked(t1, c1, t2, c2, order);
    expect(
        "concat_globally_checked",
        g,
        uncertainty::concat_globally(t1, c1, t2, c2, order),
    );
    let l = uncertainty::concat_locally_checked(t1, t2, c1, c2);
    expect(
        "concat_locally_checked",
        l,
        uncertainty::concat_locally(t1, t2, c1, c2),
    );
    // invert_checked sees one mean and one covariance: valid ones of the pair may fail it.
    if inputs_ok {
        expect(
            "invert_checked",
            uncertainty::invert_checked(t1, c1),
            uncertainty::invert(t1, c1),
        );
    }
}

/// One fuzzed joint, and whether it lies in the valid domain.
fn build_joint<T: Fz>(ji: &JointIn) -> (Joint<T>, bool) {
    let kind = match ji.kind % 3 {
        0 => JointKind::Revolute,
        1 => JointKind::Continuous,
        _ => JointKind::Prismatic,
    };
    let a: Vec3<T> = vals(&ji.axis);
    let q: Vec3<T> = vals(&ji.q);
    let mut valid = true;
    let screw = if ji.raw {
        valid &= vec_bounded(&a) && vec_bounded(&q);
        Vec6::from_parts(a, q)
    } else {
        let norm = a.norm();
        valid &= vec_bounded(&q) && norm.is_finite() && norm > T::ZERO;
        let s = a.scale(T::ONE / norm);
        valid &= s.is_finite();
        if kind == JointKind::Prismatic {
            Vec6::from_parts(Vec3::zeros(), s)
        } else {
            Vec6::from_parts(s, q.cross(&s))
        }
    };
    valid &= vec_bounded(&screw);
    // Limits clip θ: a finite limit beyond BOUND can move θ out of the valid domain.
    // Unbounded limits must point outwards (lower −∞, upper +∞).
    let (lo, up): (T, T) = (ji.lower.get(), ji.upper.get());
    valid &= lo.is_nan() || lo == T::neg_infinity() || bounded(lo);
    valid &= up.is_nan() || up == T::infinity() || bounded(up);
    // Half the joints with their displacement constants (the tables' fast path),
    // half without (derived per call).
    let joint = Joint::new("", kind, screw.0, ji.lower.get(), ji.upper.get());
    (
        if ji.kind % 2 == 0 {
            joint.prepared()
        } else {
            joint
        },
        valid,
    )
}

/// The PPOE on a small chain: 1 to 3 fuzzed joints.
fn check_chain<T: Fz>(inp: &CoreInput, pool: &[Mat6<T>; 3]) {
    let n = 1 + inp.n_joints as usize % 3;
    let mut joints = [Joint::new("", JointKind::Revolute, [T::ZERO; 6], T::ZERO, T::ZERO); 3];
    let mut chain_valid = true;
    for (j, ji) in joints.iter_mut().zip(&inp.joints).take(n) {
        let (joint, valid) = build_joint(ji);
        *j = joint;
        chain_valid &= valid;
    }
    let home: Transform<T> = inp.home.get();
    chain_valid &= transform_valid(&home);
    let chain = ChainView {
        joints: &joints[..n],
        home,
    };
    let covs: Vec<Mat6<T>> = (0..n).map(|i| pool[inp.cov_pick[i] as usize % 3]).collect();
    let pool_psd = [&inp.c1, &inp.c2, &inp.c3].map(|c| c.psd_by_construction::<T>());
    let covs_psd = (0..n).all(|i| pool_psd[inp.cov_pick[i] as usize % 3]);
    let thetas: Vec<T> = inp.thetas[..n].iter().map(|x| x.get()).collect();
    let inputs_finite = thetas.iter().all(|t| t.is_finite()) && covs.iter().all(|c| c.is_finite());
    let inputs_pass =
        thetas.iter().all(|t| t.is_finite()) && covs.iter().all(|c| check_covariance(c).is_ok());
    // Revolute joints take any finite angle; the translation a prismatic joint adds is
    // θ·|s| and must stay within BOUND like the rest of the geometry.
    let inputs_valid = inputs_pass
        && thetas.iter().all(|&t| bounded(t))
        && thetas
            .iter()
            .zip(&joints[..n])
            .all(|(&t, j)| bounded(t * vec_amax(&j.screw)))
        && covs.iter().all(cov_bounded);
    let domain = Domain {
        inputs_finite,
        inputs_pass,
        valid: chain_valid && inputs_valid,
        covs_psd,
    };
    for conv in [
        Convention::Right,
        Convention::Left,
        Convention::Pytransform3d,
    ] {
        check_ppoe(&chain, &thetas, &covs, conv, &domain);
    }
    black_box(chain.forward_kinematics(&thetas).ok());
    let mut cols = [Vec6::zeros(); 3];
    black_box(chain.body_jacobian(&thetas, &mut cols[..n]).ok());
    // Length mismatches are errors, not panics.
    assert!(chain
        .ppoe_checked(&thetas[..n - 1], &covs, Convention::Right)
        .is_err());
    assert!(chain
        .ppoe(&thetas, &covs[..n - 1], Convention::Left)
        .is_err());
}

/// What the oracle knows of the PPOE's inputs.
struct Domain {
    /// Every θ and covariance is finite.
    inputs_finite: bool,
    /// Every θ is finite and every covariance passes `check_covariance`.
    inputs_pass: bool,
    /// Chain and inputs lie in the valid domain (bounded, see `bounded`).
    valid: bool,
    /// Every joint covariance is PSD by construction.
    covs_psd: bool,
}

/// `ppoe_checked` (and `ppoe_fourth_order`, which must not panic) in one convention.
fn check_ppoe<T: Fz>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &[Mat6<T>],
    conv: Convention,
    d: &Domain,
) {
    let r = chain.ppoe_checked(thetas, covs, conv);
    black_box(chain.ppoe_fourth_order(thetas, covs, conv).ok());
    if !d.inputs_finite {
        assert!(
            r.is_err(),
            "ppoe_checked ({}) accepted non-finite input",
            T::NAME
        );
    }
    // The checked entry point also checks the chain (unit screw axes, rigid home pose).
    // Valid input: Ok, or Overflow if the result is not finite in T (never Ok(±∞/NaN)).
    if d.inputs_pass && chain.check().is_ok() {
        let ok = matches!(r, Ok(_) | Err(Error::Overflow));
        assert!(ok, "ppoe_checked ({}) rejected valid input: {r:?}", T::NAME);
    }
    if let Ok(out) = &r {
        let finite = out.cov.is_finite() && transform_finite(&out.pose);
        assert!(
            finite,
            "ppoe_checked ({}) returned Ok with a non-finite result",
            T::NAME
        );
    }
    if chain.check().is_err() {
        assert!(
            r.is_err(),
            "ppoe_checked ({}) accepted an invalid chain",
            T::NAME
        );
    }
    if d.valid && chain.check().is_ok() {
        let out = r.expect("valid");
        let tol = T::TOL * T::from_usize(thetas.len() + 2);
        assert_rigid("ppoe_checked pose", &out.pose, tol);
        // PSD is promised for PSD inputs only: an input indefinite within
        // check_covariance's tolerance stays indefinite through the congruences
        // Ad·Σ·Adᵀ (Sylvester's law of inertia) and its negative eigenvalue can grow
        // relative to ‖Σ‖ by up to κ(Ad)², however small it was (FUZZING.md, "Bugs
        // found"). Symmetry always.
        if d.covs_psd {
            assert_cov("ppoe_checked cov", &out.cov);
        } else {
            assert_sym("ppoe_checked cov", &out.cov);
        }
    }
}

/// Pose fusion and Gaussian estimation on 0 to 4 samples.
fn check_fusion_and_estimation<T: Fz>(inp: &CoreInput, pool: &[Mat6<T>; 3]) {
    let k = inp.n_samples as usize % 5;
    let samples: Vec<Transform<T>> = inp.samples[..k].iter().map(|s| s.get()).collect();
    let scovs: Vec<Mat6<T>> = (0..k).map(|i| pool[i % 3]).collect();
    let all_finite = samples.iter().all(transform_finite) && scovs.iter().all(|c| c.is_finite());
    let fusion = uncertainty::pose_fusion(&samples, &scovs, &IterationOptions::default());
    if k == 0 {
        assert_eq!(fusion.err(), Some(Error::Empty));
    } else if !all_finite {
        assert!(
            fusion.is_err(),
            "pose_fusion ({}) accepted non-finite input",
            T::NAME
        );
    }
    if let Ok(f) = &fusion {
        assert_sym_bits("pose_fusion cov", &f.cov);
        let valid = samples.iter().all(transform_valid) && scovs.iter().all(cov_ok);
        if valid {
            assert_sym("pose_fusion cov", &f.cov);
            let tol = T::TOL * T::lit(8.0);
            assert_rigid("pose_fusion mean", &f.mean, tol);
        }
    }
    check_estimation(&samples, k);
}

/// The Gaussian estimators on the same samples.
fn check_estimation<T: Fz>(samples: &[Transform<T>], k: usize) {
    let est = uncertainty::estimate_gaussian_transform(samples);
    match k {
        0 => assert_eq!(est.err(), Some(Error::Empty)),
        1 => assert_eq!(est.err(), Some(Error::TooFewSamples)),
        _ if samples.iter().any(|s| !transform_finite(s)) => {
            assert_eq!(
                est.err(),
                Some(Error::NonFinite),
                "estimate_gaussian_transform ({})",
                T::NAME
            )
        }
        _ => {}
    }
    if let Ok(e) = &est {
        assert_sym_bits("estimate_gaussian_transform cov", &e.cov);
        if samples.iter().all(transform_valid) {
            assert_rigid(
                "estimate_gaussian_transform mean",
                &e.mean,
                T::TOL * T::lit(8.0),
            );
            assert_cov("estimate_gaussian_transform cov", &e.cov);
        }
    }
    let rots: Vec<Mat3<T>> = samples.iter().map(|s| s.rotation).collect();
    if let Ok(e) = uncertainty::estimate_gaussian_rotation(&rots) {
        assert_sym_bits("estimate_gaussian_rotation cov", &e.cov);
    }
}
