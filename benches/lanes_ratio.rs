//! f32/f64 time ratios of the PPOE measured in one process: f32 and f64 batches
//! interleaved round by round, so that load from other processes hits both alike; the
//! median over rounds of each round's ratio is printed. Also the time of the 7th joint
//! relative to 6 (the marginal cost of one joint), and every lane width the schedule has
//! (`ChainView::ppoe_with_lanes`: 1, 2, 4).
//!
//! `cargo bench --bench lanes_ratio` (optional args: rounds, calls per batch).
//! `LANES_RATIO_CALLGRIND=<case>/<f32|f64>/<lanes> valgrind --tool=callgrind
//! --collect-atstart=no --toggle-collect='*callgrind_region*' <binary>` counts the
//! instructions of 1000 calls of one case (`LANES_RATIO_CALLGRIND=list` lists them;
//! lanes 0 = the target's own choice, `ChainView::ppoe`). `LANES_RATIO_FTZ=1` sets
//! flush-to-zero first (x86-64), which shows what subnormal values cost.

use ppoe::chain::{ChainView, Convention, Joint, JointKind};
use ppoe::{se3, Mat6, Real, Transform, Vec3, Vector};
use serde_json::Value;
use std::hint::black_box;
use std::time::Instant;

/// Joints, home pose, joint values and joint covariances of one case.
type Case<T> = (Vec<Joint<T>>, Transform<T>, Vec<T>, Vec<Mat6<T>>);

fn num(v: &Value) -> f64 {
    match v {
        Value::String(s) if s == "inf" => f64::INFINITY,
        Value::String(s) if s == "-inf" => f64::NEG_INFINITY,
        _ => v.as_f64().expect("number"),
    }
}

/// The seed robot (its golden file) at the example's initial state, converted as
/// ppoe-build converts its tables (`Joint::from_f64`, `Transform::from_f64`).
fn seed<T: Real>() -> Case<T> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/test_data/golden/ppoe/seed_linkmount_tcp.json"
    );
    let g: Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("golden seed")).expect("json");
    let joints: Vec<Joint<f64>> = g["screw_axes"]
        .as_array()
        .unwrap()
        .iter()
        .zip(g["limits"].as_array().unwrap())
        .map(|(s, l)| {
            let s: Vec<f64> = s.as_array().unwrap().iter().map(num).collect();
            let l: Vec<f64> = l.as_array().unwrap().iter().map(num).collect();
            let screw = std::array::from_fn(|i| s[i]);
            Joint::new("j", JointKind::Revolute, screw, l[0], l[1])
        })
        .collect();
    let h: Vec<Vec<f64>> = g["home"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_array().unwrap().iter().map(num).collect())
        .collect();
    let home = Transform::from_matrix4(&std::array::from_fn(|i| std::array::from_fn(|j| h[i][j])));
    let mut covs = vec![Mat6::zeros(); 6];
    covs[0].0[2][2] = T::lit(0.05);
    for i in [1, 2, 4] {
        covs[i].0[1][1] = T::lit(0.05);
    }
    (
        joints.iter().map(Joint::from_f64).collect(),
        Transform::from_f64(&home),
        [-0.5, -0.5, -0.5, 0.0, -0.5, 0.0].map(T::lit).to_vec(),
        covs,
    )
}

/// A chain of n revolute joints with varied axes and a full-rank covariance each (the
/// synthetic chains of benches/ops.rs).
fn synthetic<T: Real>(n: usize) -> Case<T> {
    let joints = (0..n)
        .map(|i| {
            let a = i as f64 * 0.7;
            let s = Vec3::<f64>::new(a.sin() * 0.3, a.cos() * 0.4, 0.866);
            let q = Vec3::new(0.1 * i as f64, 0.05, 0.2 * i as f64);
            let screw = se3::screw_axis(&q, &s, 0.0).unwrap();
            let j = Joint::new("j", JointKind::Revolute, screw.0, -3.0, 3.0);
            Joint::from_f64(&j)
        })
        .collect();
    let home = Transform::from_parts(
        [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]].map(|r| r.map(T::lit)),
        [0.1, 0.0, 0.2 * n as f64].map(T::lit),
    );
    let thetas = (0..n).map(|i| T::lit(0.3 + 0.1 * i as f64)).collect();
    let cov = Mat6::from_diagonal(&Vector([1e-4, 2e-4, 1e-4, 1e-6, 2e-6, 1e-6].map(T::lit)));
    (joints, home, thetas, vec![cov; n])
}

fn case<T: Real>(name: &str) -> Case<T> {
    match name {
        "seed" => seed(),
        n => synthetic(n.trim_start_matches("chain").parse().expect("chainN")),
    }
}

/// One PPOE call with `lanes` (0: the target's choice).
#[inline(always)]
fn call<T: Real>(c: &Case<T>, lanes: usize) -> ppoe::chain::UncertainPose<T> {
    let chain = ChainView {
        joints: &c.0,
        home: c.1,
    };
    let th = black_box(&c.2[..]);
    let r = if lanes == 0 {
        chain.ppoe(th, &c.3, Convention::Right)
    } else {
        chain.ppoe_with_lanes(th, &c.3, Convention::Right, lanes)
    };
    r.expect("lengths")
}

/// Nanoseconds per call of a batch of `k` calls.
fn batch<T: Real>(c: &Case<T>, lanes: usize, k: usize) -> f64 {
    let t = Instant::now();
    for _ in 0..k {
        black_box(call(c, lanes));
    }
    t.elapsed().as_nanos() as f64 / k as f64
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

const CASES: [&str; 4] = ["seed", "chain6", "chain7", "chain8"];
const LANES: [usize; 4] = [0, 1, 2, 4];

/// Interleaved rounds: every (case, scalar, lanes) batch once per round, then medians.
fn ratios(rounds: usize, k: usize) {
    let c64: Vec<Case<f64>> = CASES.iter().map(|n| case(n)).collect();
    let c32: Vec<Case<f32>> = CASES.iter().map(|n| case(n)).collect();
    // ns[case][lanes][0 = f64, 1 = f32] per round.
    let mut ns = vec![vec![[Vec::new(), Vec::new()]; LANES.len()]; CASES.len()];
    for _ in 0..rounds {
        for (ci, (a, b)) in c64.iter().zip(&c32).enumerate() {
            for (li, &l) in LANES.iter().enumerate() {
                ns[ci][li][0].push(batch(a, l, k));
                ns[ci][li][1].push(batch(b, l, k));
            }
        }
    }
    println!("case lanes | f64 ns | f32 ns | median of per-round f32/f64");
    for (ci, name) in CASES.iter().enumerate() {
        for (li, l) in LANES.iter().enumerate() {
            let [a, b] = &ns[ci][li];
            let mut r: Vec<f64> = a.iter().zip(b).map(|(x, y)| y / x).collect();
            let (mut a, mut b) = (a.clone(), b.clone());
            println!(
                "{name:6} {l} | {:7.1} | {:7.1} | {:.3}",
                median(&mut a),
                median(&mut b),
                median(&mut r)
            );
        }
    }
    // The 7th and 8th joints' marginal cost, target lanes, per round.
    for (ti, t) in ["f64", "f32"].iter().enumerate() {
        let s6 = &ns[1][0][ti];
        let mut m7: Vec<f64> = ns[2][0][ti].iter().zip(s6).map(|(x, y)| x - y).collect();
        let mut m8: Vec<f64> = ns[3][0][ti]
            .iter()
            .zip(&ns[2][0][ti])
            .map(|(x, y)| x - y)
            .collect();
        let mut per6: Vec<f64> = s6.iter().map(|x| x / 6.0).collect();
        println!(
            "{t}: chain7 - chain6 = {:.1} ns, chain8 - chain7 = {:.1} ns, chain6 / 6 = {:.1} ns",
            median(&mut m7),
            median(&mut m8),
            median(&mut per6)
        );
    }
}

#[inline(never)]
fn callgrind_region(reps: usize, f: &mut dyn FnMut()) {
    for _ in 0..reps {
        f();
    }
}

fn callgrind(which: &str) {
    let mut names = Vec::new();
    for c in CASES {
        for t in ["f64", "f32"] {
            for l in LANES {
                names.push(format!("{c}/{t}/{l}"));
            }
        }
    }
    if which == "list" {
        names.iter().for_each(|n| println!("{n}"));
        return;
    }
    let parts: Vec<&str> = which.split('/').collect();
    let [c, t, l] = parts[..] else {
        panic!("LANES_RATIO_CALLGRIND=<case>/<f32|f64>/<lanes>");
    };
    let l: usize = l.parse().expect("lanes");
    let mut f: Box<dyn FnMut()> = if t == "f32" {
        let c = case::<f32>(c);
        Box::new(move || {
            black_box(call(&c, l));
        })
    } else {
        let c = case::<f64>(c);
        Box::new(move || {
            black_box(call(&c, l));
        })
    };
    f();
    callgrind_region(1000, f.as_mut());
}

/// With `LANES_RATIO_FTZ` set (x86-64 only): flush subnormal results to zero and treat
/// subnormal operands as zero (MXCSR FTZ and DAZ), to see what subnormals cost.
#[cfg(target_arch = "x86_64")]
#[allow(deprecated)] // _mm_setcsr: the one way to set MXCSR from Rust
fn flush_to_zero() {
    use std::arch::x86_64::{_mm_getcsr, _mm_setcsr};
    if std::env::var_os("LANES_RATIO_FTZ").is_some() {
        // SAFETY: SSE is baseline on x86-64; FTZ/DAZ change rounding of tiny values only.
        unsafe { _mm_setcsr(_mm_getcsr() | 0x8040) };
        println!("MXCSR: flush-to-zero and denormals-are-zero set");
    }
}

#[cfg(not(target_arch = "x86_64"))]
fn flush_to_zero() {}

fn main() {
    flush_to_zero();
    if let Ok(which) = std::env::var("LANES_RATIO_CALLGRIND") {
        return callgrind(&which);
    }
    // Positional numbers only (cargo bench passes `--bench`).
    let args: Vec<usize> = std::env::args().filter_map(|a| a.parse().ok()).collect();
    let rounds = args.first().copied().unwrap_or(201);
    let k = args.get(1).copied().unwrap_or(2000);
    ratios(rounds, k);
}
