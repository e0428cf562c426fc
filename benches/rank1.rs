//! The rank-one PPOE (`ppoe_rank1`, one variance per joint along its screw axis) against
//! the dense PPOE with the same covariances (`screw_noise`), f64 and f32, on the seed robot
//! (6 joints, from the oracle's golden file) and on the 7-joint arm of
//! test_data/urdf/arm7.urdf.

#[path = "pinocchio/robots.rs"]
mod robots;

use criterion::{criterion_group, criterion_main, Criterion};
use ppoe::chain::{screw_noise, ChainView, Convention, Joint};
use ppoe::{Mat6, Real, Transform};
use ppoe_test_support::fixtures::seed_chain;
use std::hint::black_box;

fn bench_chain<T: Real>(c: &mut Criterion, label: &str, joints: &[Joint<T>], home: Transform<T>) {
    let chain = ChainView { joints, home };
    let n = joints.len();
    let thetas: Vec<T> = (0..n).map(|i| T::lit(0.3 - 0.1 * i as f64)).collect();
    let s2: Vec<T> = (0..n).map(|i| T::lit(1e-4 * (1 + i) as f64)).collect();
    let covs: Vec<Mat6<T>> = joints
        .iter()
        .zip(&s2)
        .map(|(j, s)| screw_noise(&j.screw, *s))
        .collect();
    let t = core::any::type_name::<T>();
    c.bench_function(&format!("rank1_{label}/dense/{t}"), |b| {
        b.iter(|| chain.ppoe(black_box(&thetas), black_box(&covs), Convention::Right))
    });
    c.bench_function(&format!("rank1_{label}/rank1/{t}"), |b| {
        b.iter(|| chain.ppoe_rank1(black_box(&thetas), black_box(&s2), Convention::Right))
    });
    c.bench_function(&format!("rank1_{label}/rank1_checked/{t}"), |b| {
        b.iter(|| chain.ppoe_rank1_checked(black_box(&thetas), black_box(&s2), Convention::Right))
    });
}

fn benches<T: Real>(c: &mut Criterion) {
    let (joints, home) = seed_chain::<T>();
    bench_chain(c, "seed", &joints, home);
    // The 7-joint arm of test_data/urdf/arm7.urdf, as benches/ops.rs runs it.
    let (arm, arm_home) = robots::core_chain::<T>(&robots::robot_chain(&robots::ARM7));
    bench_chain(c, "7dof", &arm, arm_home);
}

fn all(c: &mut Criterion) {
    benches::<f64>(c);
    benches::<f32>(c);
}

criterion_group!(group, all);
criterion_main!(group);
