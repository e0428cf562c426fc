//! Panic-freedom proof for the public entry points of the core crate (the technique of the
//! `panic-never` crate).
//!
//! This firmware calls every public function and method of `so3`, `se3`, `uncertainty`,
//! `linalg` (the eigen-decomposition), `surface` (ellipsoids, surface points) and `chain`
//! (the compile-time [`Chain`], the slice view, the dense and rank-one PPOE), in f32 and f64, on opaque
//! inputs (`black_box`: the optimiser may assume nothing about values, slice lengths or
//! enum variants). Its panic handler calls a function that does not exist, so the link
//! fails ("undefined symbol: ppoe_panic_path_survived_optimisation") if any panic path of
//! these functions survives optimisation (release profile: opt-level 3, LTO). Built only
//! with `--features panic-never` (scripts/firmware.sh does it for the M4F); running it
//! exits QEMU with 0.
//!
//! Not proven: the surface grids (`to_projected_ellipsoid*`, `lift_surface`,
//! `marginal_surface`, `surface_grid`, `LiftSurface::grid`): their bounds checks survive
//! (build with `PN_GROUPS=G` to see the link fail). Not called: the `linalg` helpers
//! (reached through their callers) and closures a caller passes in (`map`).

#![no_std]
#![no_main]

use core::hint::black_box as bb;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug;
use ppoe::chain::{self, Chain, ChainView, Convention, Joint, JointConstants};
use ppoe::linalg::SymmetricEigen;
use ppoe::surface::{self, LiftSurface, Surface};
use ppoe::uncertainty::{self, IterationOptions, Order};
use ppoe::{se3, so3, Mat3, Mat6, Matrix, Real, Transform, Vec3, Vec6, Vector};

include!(concat!(env!("OUT_DIR"), "/seed_table.rs"));

extern "C" {
    /// Deliberately undefined: referenced only from the panic handler.
    fn ppoe_panic_path_survived_optimisation() -> !;
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: never defined, so never called: the link fails if this handler is reachable.
    unsafe { ppoe_panic_path_survived_optimisation() }
}

/// Consumes a result opaquely (a `Result` too: its error path must be kept).
fn sink<X>(x: X) {
    let _ = bb(x);
}

fn v3<T: Real>() -> Vec3<T> {
    bb(Vector([0.3, -0.2, 0.5].map(T::lit)))
}

fn v6<T: Real>() -> Vec6<T> {
    bb(Vector([0.3, -0.2, 0.5, 0.4, 0.1, -0.3].map(T::lit)))
}

fn m3<T: Real>() -> Mat3<T> {
    bb(so3::exp(&v3()))
}

fn m6<T: Real>() -> Mat6<T> {
    bb(Mat6::from_diagonal(&Vector(
        [1e-3, 2e-3, 5e-4, 1e-3, 3e-3, 2e-3].map(T::lit),
    )))
}

fn pose<T: Real>() -> Transform<T> {
    bb(se3::exp(&v6()))
}

/// so3 and se3: the group operations, Jacobians, hat/vee, checks.
fn lie<T: Real>() {
    let (w, xi, r, t) = (v3::<T>(), v6::<T>(), m3::<T>(), pose::<T>());
    sink(so3::hat(&w));
    sink(so3::vee(&r));
    sink(so3::exp(&w));
    sink(so3::log_axis_angle(&r));
    sink(so3::log(&r));
    sink(so3::left_jacobian(&w));
    sink(so3::left_jacobian_inv(&w));
    sink(so3::is_rotation(&r, bb(T::TOL)));
    sink(Transform::<T>::identity());
    sink(Transform::from_matrix4(&bb(t.to_matrix4())));
    sink(Transform::<T>::from_f64(&pose::<f64>()));
    sink(t.inverse());
    sink(t.transform_point(&w));
    sink(t.transform_vector(&w));
    sink(t.adjoint());
    sink(t.transport_covariance(&m6()));
    sink(Transform::exp(&xi));
    sink(t.log());
    sink(t.is_valid(bb(T::TOL)));
    sink(t.check());
    sink(se3::hat(&xi));
    sink(se3::vee(&bb(se3::hat(&xi))));
    sink(se3::curly_hat(&xi));
    sink(se3::exp(&xi));
    sink(se3::exp_translation(&xi));
    sink(se3::log(&t));
    sink(se3::q_matrix(&xi));
    sink(se3::left_jacobian(&xi));
    sink(se3::left_jacobian_inv(&xi));
    sink(se3::screw_axis(&w, &v3(), bb(T::HALF)));
}

/// uncertainty: conversions, compounding, inversion, fusion, estimators, checks.
fn uncertain<T: Real>() {
    let (t, c) = (pose::<T>(), m6::<T>());
    sink(uncertainty::right_to_left(&t, &c));
    sink(uncertainty::left_to_right(&t, &c));
    for order in [Order::Second, Order::Fourth] {
        sink(uncertainty::concat_globally(
            &t,
            &c,
            &pose(),
            &m6(),
            bb(order),
        ));
    }
    sink(uncertainty::concat_locally(&t, &pose(), &c, &m6()));
    sink(uncertainty::invert(&t, &c));
    sink(uncertainty::concat_globally_checked(
        &t,
        &c,
        &pose(),
        &m6(),
        bb(Order::FourthPsd),
    ));
    sink(uncertainty::concat_locally_checked(&t, &pose(), &c, &m6()));
    sink(uncertainty::invert_checked(&t, &c));
    let opts = bb(IterationOptions::<T>::default());
    let means = [pose::<T>(), pose(), pose()];
    let covs = [m6::<T>(), m6(), m6()];
    let means: &[Transform<T>] = bb(&means);
    let covs: &[Mat6<T>] = bb(&covs);
    sink(uncertainty::pose_fusion(means, covs, &opts));
    sink(uncertainty::frechet_mean(means, &opts));
    sink(uncertainty::estimate_gaussian_transform(means));
    let rots = [m3::<T>(), m3(), m3()];
    let rots: &[Mat3<T>] = bb(&rots);
    sink(uncertainty::estimate_gaussian_rotation(rots));
    sink(uncertainty::check_covariance(&c));
    sink(uncertainty::check_covariance(&m3::<T>()));
}

/// ellipsoid: eigen-decomposition, ellipsoids, the surface map (one point), chi² helpers.
fn ellipsoids<T: Real>() {
    let (t, c) = (pose::<T>(), m6::<T>());
    let k = bb(T::lit(2.0));
    if let Ok(e) = SymmetricEigen::new(&c) {
        sink(e.max_value());
        sink(e.min_value());
        sink(e.clamped());
        sink(e.is_psd(bb(T::TOL)));
        sink(e.rank_threshold());
        sink(e.rank());
        sink(e.reconstruct());
        sink(e.sqrt());
        sink(e.pinv_sqrt());
    }
    sink(SymmetricEigen::new(&m3::<T>()));
    sink(surface::unit_sphere_point::<T>(bb(6), bb(2), bb(3)));
    sink(surface::to_ellipsoid(&v3(), &bb(c.block(1, 1))));
    sink(surface::position_covariance(&t, &c));
    sink(surface::position_ellipsoid(&t, &c));
    sink(surface::position_mean_second_order(&t, &c));
    if let Ok(s) = LiftSurface::new(&t, &c) {
        sink(s.perturbation(&v3()));
        sink(s.point(&v3()));
    }
    sink(surface::chi2_3_probability(k));
    sink(surface::chi2_3_radius(bb(T::HALF)));
}

/// ellipsoid: the surface grids into a caller's buffer. Not panic-free yet: with an
/// opaque `n_steps` and buffer the bounds checks of the grid filling (`fill_grid`,
/// `marginal_surface`, `LiftSurface::grid`) survive. Built only with `PN_GROUPS`
/// containing `G` (see the module docs).
fn grids<T: Real>() {
    let (t, c) = (pose::<T>(), m6::<T>());
    let mut buf = [Vec3::<T>::zeros(); 64];
    let out: &mut [Vec3<T>] = bb(&mut buf);
    let (n, k) = (bb(6usize), bb(T::lit(2.0)));
    if let Ok(e) = SymmetricEigen::new(&c) {
        sink(surface::to_projected_ellipsoid_from_eigen(
            &t, &e.values, &e.vectors, k, n, out,
        ));
    }
    sink(surface::to_projected_ellipsoid(&t, &c, k, n, out));
    if let Ok(s) = LiftSurface::new(&t, &c) {
        sink(s.grid(k, n, out));
    }
    sink(surface::lift_surface(&t, &c, k, n, out));
    sink(surface::marginal_surface(&t, &c, k, n, out));
    for surface in [Surface::Lift, Surface::Marginal, Surface::Pytransform3d] {
        sink(surface::surface_grid(bb(surface), &t, &c, k, n, out));
    }
}

/// chain: joints, the compile-time chain and its slice view, noise models.
fn chains<T: Real>(seed: &Chain<T, 6>) {
    let seed = bb(seed);
    let th: [T; 6] = bb([0.5, -0.3, 1.2, 0.1, -2.0, 3.0].map(T::lit));
    let covs: [Mat6<T>; 6] = bb([m6(); 6]);
    let conv = bb(Convention::Right);
    let j = bb(seed.joints[0]);
    sink(JointConstants::of(&j.screw));
    sink(j.clip(th[0], bb(false)));
    sink(j.displacement(th[1]));
    sink(j.prepared());
    sink(Joint::<T>::from_f64(&bb(SEED.joints[1])));
    sink(seed.clip(&th));
    sink(seed.forward_kinematics(&th));
    sink(seed.space_jacobian(&th));
    sink(seed.body_jacobian(&th));
    sink(seed.ppoe(&th, &covs, conv));
    sink(seed.ppoe_checked(&th, &covs, conv));
    sink(seed.ppoe_fourth_order(&th, &covs, conv));
    let s2: [T; 6] = bb([1e-4, 0.0, 4e-4, 1e-3, 2e-4, 0.05].map(T::lit));
    sink(seed.ppoe_rank1(&th, &s2, conv));
    sink(seed.ppoe_rank1_checked(&th, &s2, conv));
    sink(chain::dense_covariances(seed, &s2));
    // The slice view with opaque lengths.
    let view: ChainView<'_, T> = bb(seed.as_ref());
    let ths: &[T] = bb(&th);
    let cs: &[Mat6<T>] = bb(&covs);
    let mut out = [T::ZERO; 6];
    let mut cols = [Vec6::<T>::zeros(); 6];
    sink(view.check());
    sink(view.clip(ths, bb(&mut out), bb(true)));
    sink(view.forward_kinematics(ths));
    sink(view.space_jacobian(ths, bb(&mut cols)));
    sink(view.body_jacobian(ths, bb(&mut cols)));
    sink(view.ppoe(ths, cs, conv));
    sink(view.ppoe_checked(ths, cs, conv));
    sink(view.ppoe_fourth_order(ths, cs, conv));
    let s2s: &[T] = bb(&s2);
    sink(view.ppoe_rank1(ths, s2s, conv));
    sink(view.ppoe_rank1_checked(ths, s2s, conv));
    // The batch calls on two configurations (opaque lengths).
    let rows: [T; 12] = bb(core::array::from_fn(|i| th[i % 6]));
    let each: [Mat6<T>; 12] = bb(core::array::from_fn(|i| covs[i % 6]));
    let rs: &[T] = bb(&rows);
    let es: &[Mat6<T>] = bb(&each);
    let mut poses = [chain::UncertainPose::certain(Transform::identity()); 2];
    let ps: &mut [chain::UncertainPose<T>] = bb(&mut poses);
    sink(view.ppoe_batch(rs, cs, conv, ps));
    sink(view.ppoe_batch_checked(rs, cs, conv, ps));
    sink(view.ppoe_batch_per_config(rs, es, conv, ps));
    sink(view.ppoe_batch_per_config_checked(rs, es, conv, ps));
    sink(view.ppoe_rank1_batch(rs, s2s, conv, ps));
    sink(view.ppoe_rank1_batch_checked(rs, s2s, conv, ps));
    sink(poses);
    sink(chain::screw_noise(&j.screw, bb(T::HALF)));
    sink(chain::bending_noise(&v3::<T>(), &m3()));
    sink(Matrix::<T, 6, 6>::identity().cholesky());
}

#[entry]
fn main() -> ! {
    // Groups (build-time `PN_GROUPS`, default all proven ones): L lie, U uncertainty,
    // E ellipsoid, C chain, G surface grids (not proven, see `grids`).
    let g = option_env!("PN_GROUPS").unwrap_or("LUEC");
    if g.contains('L') {
        lie::<f32>();
        lie::<f64>();
    }
    if g.contains('U') {
        uncertain::<f32>();
        uncertain::<f64>();
    }
    if g.contains('E') {
        ellipsoids::<f32>();
        ellipsoids::<f64>();
    }
    if g.contains('C') {
        chains::<f32>(&SEED_F32);
        chains::<f64>(&SEED);
    }
    if g.contains('G') {
        grids::<f32>();
        grids::<f64>();
    }
    debug::exit(debug::EXIT_SUCCESS);
    #[allow(clippy::empty_loop)]
    loop {}
}
