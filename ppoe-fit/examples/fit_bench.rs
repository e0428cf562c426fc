//! The fit's speed: 2000 samples of the exact model (fixed seeds, `ppoe_fit::simulate`) on
//! the seed robot (6 joints) and `prismatic.urdf` (7 joints), fitted with the joint and the
//! full model (the 7-joint full model with and without tracker noise), each fit repeated
//! five times; the median wall time per fit.
//!
//! `cargo run --release -p ppoe-fit --example fit_bench`: stdout has one line per case and
//! nothing else,
//! `fit_bench robot=<file> joints=<n> model=<joint|full> tracker=<yes|no> samples=2000 median_s=<f> iters=<k> converged=<true|false>`;
//! stderr names the CPU (the figures mean nothing without it, nor on a loaded machine).
//!
//! Then the calibration cases: a campaign of 2000 pose samples with every systematic error
//! at once (`tests/common/campaign.rs`: tracker metres away, marker centimetres off, joint
//! zeros and axes off) on the 7-joint arm, fitted by `fit_campaign` with the joint model
//! and `--estimate base,tip,offsets` and `all`, three repeats each; one line per case,
//! `fit_calibration_bench robot=arm7.urdf joints=7 model=joint estimate=<list> samples=2000 median_s=<f> rounds=<k> fits=<true|false>`.

#[path = "../tests/common/mod.rs"]
mod common;
use common::campaign::{run, Setup, BASE};
use common::*;
use ppoe_fit::{fit, simulate, Model};
use std::time::Instant;

const SAMPLES: usize = 2000;
const REPEATS: usize = 5;

/// (robot index in `ROBOTS`, model, tracker noise)
const CASES: [(usize, Model, bool); 5] = [
    (0, Model::Joint, false),
    (0, Model::Full, false),
    (1, Model::Joint, false),
    (1, Model::Full, false),
    (1, Model::Full, true),
];

fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown (no /proc/cpuinfo)".into())
}

fn case(robot_index: usize, model: Model, tracker_noise: bool, repeats: usize) -> String {
    let (file, base, tip) = ROBOTS[robot_index];
    let (joints, home) = robot(file, base, tip);
    let truth = match model {
        Model::Joint => joint_covs(&joints, &joint_truth(&joints, 1.0)),
        Model::Full => full_truth(&joints, 1.0),
    };
    let r = tracker();
    let meas = tracker_noise.then_some(&r);
    // The seeds of ACCURACY.md section 4 (1 + the robot's index).
    let seed = 1 + robot_index as u64;
    let samples = simulate::samples(&joints, &home, &truth, meas, SAMPLES, seed);
    let mut times = Vec::with_capacity(repeats);
    let mut last = None;
    for _ in 0..repeats {
        let start = Instant::now();
        let f = fit(
            &joints,
            &home,
            &samples,
            meas.map(|m| &m.0),
            model,
            &mut |_, _| {},
        )
        .unwrap_or_else(|e| panic!("{file}: {e}"));
        times.push(start.elapsed().as_secs_f64());
        last = Some(f);
    }
    times.sort_by(f64::total_cmp);
    let f = last.expect("at least one repeat");
    format!(
        "fit_bench robot={file} joints={} model={} tracker={} samples={SAMPLES} median_s={:.4} iters={} converged={}",
        joints.len(),
        model.name(),
        if tracker_noise { "yes" } else { "no" },
        times[repeats / 2],
        f.iterations,
        f.converged
    )
}

/// A calibration case: the median wall time of `repeats` fits of one campaign.
fn calibration_case(estimate: ppoe_fit::Estimate, repeats: usize) -> String {
    let setup = Setup {
        robot: 5,
        estimate,
        ..BASE
    };
    let mut runs: Vec<_> = (0..repeats).map(|_| run(setup)).collect();
    runs.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
    let r = &runs[repeats / 2];
    format!(
        "fit_calibration_bench robot={} joints={} model=joint estimate={} samples={} median_s={:.4} rounds={} fits={}",
        ROBOTS[5].0,
        r.out.fit.joints.len(),
        estimate.names().join(","),
        setup.samples,
        r.seconds,
        r.out.calibration.rounds,
        r.out.fit.goodness_of_fit.fits
    )
}

/// `fit_bench [CASE [REPEATS]]`: one case (index into `CASES`) and fewer repeats, for
/// profiling; no argument runs every case five times.
fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("usage: fit_bench [CASE [REPEATS]]"))
        .collect();
    let repeats = args.get(1).copied().unwrap_or(REPEATS).max(1);
    eprintln!("cpu: {}", cpu_model());
    for (k, (robot_index, model, tracker_noise)) in CASES.into_iter().enumerate() {
        if args.first().is_none_or(|&only| only == k) {
            println!("{}", case(robot_index, model, tracker_noise, repeats));
        }
    }
    let calibrations = [
        ppoe_fit::Estimate {
            kinematics: false,
            ..ppoe_fit::Estimate::ALL
        },
        ppoe_fit::Estimate::ALL,
    ];
    for (k, estimate) in calibrations.into_iter().enumerate() {
        if args.first().is_none_or(|&only| only == CASES.len() + k) {
            println!("{}", calibration_case(estimate, repeats.min(3)));
        }
    }
}
