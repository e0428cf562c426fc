//! f32/f64 time ratios of the PPOE measured in one process: f32 and f64 batches
//! interleaved round by round, so that load from other processes hits both alike; the
//! median over rounds of each round's ratio is printed. Also the time of the 7th joint
//! relative to 6 (the marginal cost of one joint), and every lane width the schedule has
//! (1, 2, 4) when built with `--cfg ppoe_bench_lanes`, which alone has the door
//! `ChainView::ppoe_with_lanes` (the schedule is private; without the cfg only the
//! target's own width, lanes 0, is timed).
//!
//! The dense cases are also timed in f64 against the two nalgebra ports of
//! benches/baseline_nalgebra.rs (4×4 inverses and the closed form; benches/ops.rs checks
//! that they give ppoe's numbers), the three round by round: the `ports` lines, the medians
//! of each round's port/ppoe ratio.
//!
//! `RUSTFLAGS="--cfg ppoe_bench_lanes" cargo bench --bench lanes_ratio` (optional args:
//! rounds, calls per batch).
//! `LANES_RATIO_CALLGRIND=<case>/<f32|f64>/<lanes> valgrind --tool=callgrind
//! --collect-atstart=no --toggle-collect='*callgrind_region*' <binary>` counts the
//! instructions of 1000 calls of one case (`LANES_RATIO_CALLGRIND=list` lists them;
//! lanes 0 = the target's own choice, `ChainView::ppoe`). `LANES_RATIO_FTZ=1` sets
//! flush-to-zero first (x86-64), which shows what subnormal values cost;
//! `LANES_RATIO_FLAGS=1` prints instead which cases and widths raise x86-64's subnormal
//! flags (tests/subnormal_lanes.rs asserts none for the target's width).

#[path = "baseline_nalgebra.rs"]
mod baseline_nalgebra;
#[path = "pinocchio/robots.rs"]
mod robots;

use ppoe::chain::{ChainView, Convention};
use ppoe::Real;
use ppoe_test_support::fixtures::{seed_case, synthetic_case, Case};
use std::hint::black_box;
use std::time::Instant;

/// A case by name: the seed example (`seed`, two of its joints without covariance), the
/// seed chain and the 7-joint arm with a full-rank covariance on every joint as the batch
/// benchmarks of benches/ops.rs give them (`seed_dense` with the seed example's joint
/// values, `arm7` with the arm's benchmark configuration; `seed_batch`, `arm7_batch` with
/// the configuration of benches/ops.rs's `batch_*/single`), or a synthetic chain of N
/// joints (`chainN`).
fn case<T: Real>(name: &str) -> Case<T> {
    let dense = |joints: Vec<ppoe::chain::Joint<T>>, home, thetas| {
        let covs = robots::arm7_covs(joints.len());
        (joints, home, thetas, covs)
    };
    let arm7 = || robots::core_chain(&robots::robot_chain(&robots::ARM7));
    match name {
        "seed" => seed_case(),
        "seed_dense" => {
            let (joints, home, thetas, _) = seed_case();
            dense(joints, home, thetas)
        }
        "seed_batch" => {
            let (joints, home, _, _) = seed_case();
            let thetas = robots::batch_thetas(1, joints.len());
            dense(joints, home, thetas)
        }
        "arm7" => {
            let (joints, home) = arm7();
            dense(joints, home, robots::arm7_thetas())
        }
        "arm7_batch" => {
            let (joints, home) = arm7();
            let thetas = robots::batch_thetas(1, joints.len());
            dense(joints, home, thetas)
        }
        n => synthetic_case(n.trim_start_matches("chain").parse().expect("chainN")),
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
    #[cfg(ppoe_bench_lanes)]
    let r = if lanes == 0 {
        chain.ppoe(th, &c.3, Convention::Right)
    } else {
        chain.ppoe_with_lanes(th, &c.3, Convention::Right, lanes)
    };
    #[cfg(not(ppoe_bench_lanes))]
    let r = {
        assert_eq!(lanes, 0, "other widths need --cfg ppoe_bench_lanes");
        chain.ppoe(th, &c.3, Convention::Right)
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

/// Nanoseconds per call of a batch of `k` calls of a nalgebra port (`closed`: the
/// closed-form inverse) on `c`'s joint values.
fn port_batch(c: &Case<f64>, p: &Port, closed: bool, k: usize) -> f64 {
    let ((na, covs), th) = (p, &c.2);
    let t = Instant::now();
    for _ in 0..k {
        let th = black_box(&th[..]);
        black_box(if closed {
            baseline_nalgebra::ppoe_closed_form(na, th, covs)
        } else {
            baseline_nalgebra::ppoe(na, th, covs)
        });
    }
    t.elapsed().as_nanos() as f64 / k as f64
}

/// A case's chain and covariances as the nalgebra ports take them.
type Port = (baseline_nalgebra::NaChain<f64>, Vec<nalgebra::Matrix6<f64>>);

/// The dense cases timed against the nalgebra ports.
const PORT_CASES: [&str; 4] = ["seed_dense", "arm7", "seed_batch", "arm7_batch"];

/// Interleaved rounds of ppoe (f64, the target's lanes) and the two nalgebra ports on
/// [`PORT_CASES`]; prints per case the median ns of each and the medians of the rounds'
/// port/ppoe ratios.
fn port_ratios(rounds: usize, k: usize) {
    let cases: Vec<(Case<f64>, Port)> = PORT_CASES
        .iter()
        .map(|n| {
            let c: Case<f64> = case(n);
            let port = baseline_nalgebra::inputs(&c.0, c.1, &c.3);
            (c, port)
        })
        .collect();
    // ns[case][0 = ppoe, 1 = 4×4 port, 2 = closed-form port] per round.
    let mut ns = vec![[Vec::new(), Vec::new(), Vec::new()]; cases.len()];
    for _ in 0..rounds {
        for (ci, (c, p)) in cases.iter().enumerate() {
            ns[ci][0].push(batch(c, 0, k));
            ns[ci][1].push(port_batch(c, p, false, k));
            ns[ci][2].push(port_batch(c, p, true, k));
        }
    }
    println!("ports case | ppoe f64 ns | 4x4 port ns | closed port ns | median 4x4/ppoe | median closed/ppoe");
    for (name, [a, b, c]) in PORT_CASES.iter().zip(&ns) {
        let mut rb: Vec<f64> = b.iter().zip(a).map(|(x, y)| x / y).collect();
        let mut rc: Vec<f64> = c.iter().zip(a).map(|(x, y)| x / y).collect();
        let (mut a, mut b, mut c) = (a.clone(), b.clone(), c.clone());
        println!(
            "ports {name:10} | {:7.1} | {:7.1} | {:7.1} | {:.3} | {:.3}",
            median(&mut a),
            median(&mut b),
            median(&mut c),
            median(&mut rb),
            median(&mut rc)
        );
    }
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The marginal-cost lines below read `chain6`, `chain7`, `chain8` at indices 1, 2, 3.
const CASES: [&str; 8] = [
    "seed",
    "chain6",
    "chain7",
    "chain8",
    "seed_dense",
    "arm7",
    "seed_batch",
    "arm7_batch",
];
/// Lane widths timed: 0 = the target's choice (`ChainView::ppoe`).
#[cfg(ppoe_bench_lanes)]
const LANES: [usize; 4] = [0, 1, 2, 4];
#[cfg(not(ppoe_bench_lanes))]
const LANES: [usize; 1] = [0];

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
                "{name:10} {l} | {:7.1} | {:7.1} | {:.3}",
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

/// With `LANES_RATIO_FLAGS` set (x86-64 only): per case, scalar and lane width, the
/// MXCSR exception flags a call raised: `D` a subnormal operand, `U` an underflow (a
/// subnormal or zero result of a nonzero product), in any lane of the SSE registers,
/// the lanes a width leaves unused included.
#[cfg(target_arch = "x86_64")]
#[allow(deprecated)] // _mm_getcsr/_mm_setcsr: the one way to read MXCSR from Rust
fn subnormal_flags() -> bool {
    use std::arch::x86_64::{_mm_getcsr, _mm_setcsr};
    if std::env::var_os("LANES_RATIO_FLAGS").is_none() {
        return false;
    }
    fn raised<T: Real>(c: &Case<T>, l: usize) -> String {
        let mut c = c.clone();
        // SAFETY: clearing MXCSR's sticky exception flags changes no result.
        unsafe { _mm_setcsr(_mm_getcsr() & !0x3f) };
        // The case's joint values, then 200 others spread over the joints' ranges.
        for _ in 0..=200 {
            black_box(call(&c, l));
            for (i, t) in c.2.iter_mut().enumerate() {
                *t += T::lit(0.37 + 0.11 * i as f64);
                if *t > T::lit(3.0) {
                    *t -= T::lit(6.0);
                }
            }
        }
        // SAFETY: reading MXCSR has no effect.
        let m = unsafe { _mm_getcsr() };
        let d = if m & 0x02 != 0 { "D" } else { "-" };
        let u = if m & 0x10 != 0 { "U" } else { "-" };
        format!("{d}{u}")
    }
    println!("case lanes | f64 flags | f32 flags (D: subnormal operand, U: underflow)");
    for n in CASES {
        let (a, b) = (case::<f64>(n), case::<f32>(n));
        for l in LANES {
            let (fa, fb) = (raised(&a, l), raised(&b, l));
            println!("{n:10} {l} | {fa} | {fb}");
        }
    }
    true
}

#[cfg(not(target_arch = "x86_64"))]
fn subnormal_flags() -> bool {
    false
}

fn main() {
    flush_to_zero();
    if subnormal_flags() {
        return;
    }
    if let Ok(which) = std::env::var("LANES_RATIO_CALLGRIND") {
        return callgrind(&which);
    }
    // Positional numbers only (cargo bench passes `--bench`).
    let args: Vec<usize> = std::env::args().filter_map(|a| a.parse().ok()).collect();
    let rounds = args.first().copied().unwrap_or(201);
    let k = args.get(1).copied().unwrap_or(2000);
    ratios(rounds, k);
    port_ratios(rounds, k);
}
