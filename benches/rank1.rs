//! The rank-one PPOE (`ppoe_rank1`, one variance per joint along its screw axis) against
//! the dense PPOE with the same covariances (`screw_noise`), f64 and f32, on the seed robot
//! (6 joints, from the oracle's golden file) and on the 7-joint arm of
//! test_data/urdf/arm7.urdf.

#[path = "pinocchio/robots.rs"]
mod robots;

use criterion::{criterion_group, criterion_main, Criterion};
use ppoe::chain::{screw_noise, ChainView, Convention, Joint, JointKind};
use ppoe::{Mat6, Real, Transform};
use serde_json::Value;
use std::hint::black_box;

fn num(v: &Value) -> f64 {
    match v {
        Value::String(s) if s == "inf" => f64::INFINITY,
        Value::String(s) if s == "-inf" => f64::NEG_INFINITY,
        _ => v.as_f64().expect("number"),
    }
}

/// The seed chain from the golden file, converted as `ppoe-build`'s tables are
/// (`Joint::from_f64`, `Transform::from_f64`).
fn seed_chain<T: Real>() -> (Vec<Joint<T>>, Transform<T>) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/test_data/golden/ppoe/seed_linkmount_tcp.json"
    );
    let g: Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("golden seed")).expect("json");
    let arr = |v: &Value| -> Vec<f64> { v.as_array().unwrap().iter().map(num).collect() };
    let joints: Vec<Joint<f64>> = g["screw_axes"]
        .as_array()
        .unwrap()
        .iter()
        .zip(g["limits"].as_array().unwrap())
        .map(|(s, l)| {
            let (s, l) = (arr(s), arr(l));
            let s: [f64; 6] = std::array::from_fn(|i| s[i]);
            Joint::new("j", JointKind::Revolute, s, l[0], l[1]).prepared()
        })
        .collect();
    let h = g["home"].as_array().unwrap();
    let m: [[f64; 4]; 4] = std::array::from_fn(|r| {
        let row = arr(&h[r]);
        std::array::from_fn(|c| row[c])
    });
    let home = Transform::from_matrix4(&m);
    (
        joints.iter().map(Joint::from_f64).collect(),
        Transform::from_f64(&home),
    )
}

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
