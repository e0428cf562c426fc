//! `--noise FILE` with a calibration (issue #27): `eval`, `mesh` and `demo` use the
//! calibrated chain, checked against the unfolded calibrated product
//! `Π Exp(κᵢ)·Exp(Sᵢ(θᵢ+δᵢ))·Exp(κᵢ)⁻¹ · M · Exp(μ)` computed here with this file's own
//! 4×4 exponential; `table --noise` bakes it (Rust and C) and names the file's sha256; a
//! rejected fit is refused by every `--noise` unless `--allow-rejected-noise`.

mod common;
use common::*;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

use ppoe_test_robots::matrix4::{exp, inv, mul, I4, M4};

/// The seed's calibration of this file: δ, κ per joint and μ.
struct Cal {
    offsets: [f64; 6],
    kappas: [[f64; 6]; 6],
    mu: [f64; 6],
}

fn cal() -> Cal {
    Cal {
        offsets: [0.03, -0.02, 0.05, -0.04, 0.01, 0.02],
        kappas: std::array::from_fn(|i| {
            let a = 0.01 * (i as f64 + 1.0);
            [a, -0.5 * a, 0.3 * a, 0.2 * a, a, -a]
        }),
        mu: [0.01, -0.02, 0.015, 0.004, -0.003, 0.005],
    }
}

/// The nominal seed chain, from ppoe-build (its screws, home frames and home pose).
fn nominal() -> ppoe_build::RobotChain {
    ppoe_build::Config::new(urdf("seed.urdf"))
        .base("linkmount")
        .tip("tcp")
        .chain()
        .unwrap()
}

/// The calibrated frames along the chain: `Π_{k≤i} Exp(κ)·Exp(S(θ+δ))·Exp(κ)⁻¹ · Lᵢ` for
/// each joint i, then the tool `… · M · Exp(μ)`.
fn calibrated_frames(c: &Cal, thetas: &[f64]) -> Vec<M4> {
    let chain = nominal();
    let mut t = I4;
    let mut out = Vec::new();
    for (i, (j, th)) in chain.joints.iter().zip(thetas).enumerate() {
        let k = exp(&c.kappas[i]);
        let e = exp(&j.screw.map(|s| s * (th + c.offsets[i])));
        t = mul(&t, &mul(&mul(&k, &e), &inv(&k)));
        out.push(mul(&t, &j.home_frame));
    }
    out.push(mul(&mul(&t, &chain.home), &exp(&c.mu)));
    out
}

/// The seed's noise file with calibration `c` (absent if `None`) and
/// `goodness_of_fit.fits` = `fits` (absent if `None`).
fn noise_file(dir: &Path, name: &str, c: Option<&Cal>, fits: Option<bool>) -> PathBuf {
    let joints: Vec<Value> = (0..6)
        .map(|i| {
            let mut j =
                json!({"name": format!("joint{}", i + 1), "cov": diag(1e-6), "sigma2": 1e-6});
            if let Some(c) = c {
                j["offset"] = json!(c.offsets[i]);
                j["offset_se"] = json!(null);
                j["axis_correction"] = json!(c.kappas[i]);
            }
            j
        })
        .collect();
    let mut v = json!({"model": "full", "joints": joints});
    if let Some(c) = c {
        v["calibration"] = json!({"estimated": ["offsets", "kinematics"], "home_correction": c.mu});
    }
    if let Some(f) = fits {
        v["goodness_of_fit"] = json!({"fits": f});
    }
    let p = dir.join(name);
    std::fs::write(&p, v.to_string()).unwrap();
    p
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

const THETAS: [[f64; 6]; 3] = [
    [0.0; 6],
    [0.3, -0.7, 0.5, 1.2, -0.4, 2.0],
    [-0.8, 0.6, -0.2, -2.5, 0.9, -1.0],
];

#[test]
fn eval_uses_the_calibrated_chain() {
    let dir = fresh_dir("calibration-eval");
    let c = cal();
    let noise = noise_file(&dir, "cal.json", Some(&c), Some(true));
    let cases = json!({"cases": THETAS.iter().map(|t| json!({"thetas": t})).collect::<Vec<_>>()});
    let input = dir.join("cases.json");
    std::fs::write(&input, cases.to_string()).unwrap();
    let (n, i) = (noise.to_str().unwrap(), input.to_str().unwrap());
    let o = run(&refs(&seed_args("eval", &["--noise", n, "--input", i])));
    success(&o);
    let out: Value = serde_json::from_slice(&o.stdout).unwrap();
    for (k, t) in THETAS.iter().enumerate() {
        let pose: Vec<f64> = out["results"][k]["pose"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
            .collect();
        let expected = calibrated_frames(&c, t);
        let expected: Vec<f64> = expected.last().unwrap().iter().flatten().copied().collect();
        let d = max_diff(&pose, &expected);
        assert!(d < 1e-12, "case {k}: {d:e}");
    }
    // Without the calibration the poses differ (the check can fail).
    let plain = noise_file(&dir, "plain.json", None, None);
    let o = run(&refs(&seed_args(
        "eval",
        &["--noise", plain.to_str().unwrap(), "--input", i],
    )));
    success(&o);
    let out: Value = serde_json::from_slice(&o.stdout).unwrap();
    let p = out["results"][1]["pose"][0][3].as_f64().unwrap();
    assert!((p - calibrated_frames(&c, &THETAS[1])[6][0][3]).abs() > 1e-3);
}

/// `mesh`'s skeleton: the joint frames and the tool of the calibrated robot.
#[test]
fn mesh_skeleton_is_the_calibrated_robots() {
    let dir = fresh_dir("calibration-mesh");
    let c = cal();
    let noise = noise_file(&dir, "cal.json", Some(&c), None);
    let input = dir.join("cases.json");
    std::fs::write(
        &input,
        json!({"cases": [{"thetas": THETAS[1]}]}).to_string(),
    )
    .unwrap();
    let (n, i, d) = (
        noise.to_str().unwrap(),
        input.to_str().unwrap(),
        dir.to_str().unwrap(),
    );
    let o = run(&refs(&seed_args(
        "mesh",
        &["--noise", n, "--input", i, "--grid", "2", "--out", d],
    )));
    success(&o);
    let obj = std::fs::read_to_string(dir.join("ppoe-mesh-0.obj")).unwrap();
    let v: Vec<[f64; 3]> = obj
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|s| s.parse().unwrap()).collect();
            [x[0], x[1], x[2]]
        })
        .collect();
    // 2×2 surface points, then the base origin, the six joint frames and the tool.
    let skeleton = &v[4..12];
    assert_eq!(skeleton[0], [0.0; 3]);
    for (k, f) in calibrated_frames(&c, &THETAS[1]).iter().enumerate() {
        let p = [f[0][3], f[1][3], f[2][3]];
        let d = max_diff(&skeleton[k + 1], &p);
        assert!(d < 1e-12, "point {}: {d:e}", k + 1);
    }
}

/// `demo --noise`: the seed table folded at run time; its printed initial pose.
#[test]
fn demo_folds_the_seed_table() {
    let dir = fresh_dir("calibration-demo");
    let c = cal();
    let noise = noise_file(&dir, "cal.json", Some(&c), Some(true));
    let d = dir.join("out");
    let a = [
        "demo",
        "--noise",
        noise.to_str().unwrap(),
        "--frames",
        "1",
        "--grid",
        "4",
        "--precision",
        "full",
    ];
    let o = run(&[&a[..], &["--out", d.to_str().unwrap()]].concat());
    success(&o);
    let text = String::from_utf8_lossy(&o.stdout);
    let rows: Vec<f64> = text
        .lines()
        .skip_while(|l| !l.starts_with("initial pose"))
        .skip(1)
        .take(4)
        .flat_map(|l| {
            l.trim()
                .trim_matches(['[', ']'])
                .split(',')
                .map(|x| x.trim().parse::<f64>().unwrap())
                .collect::<Vec<_>>()
        })
        .collect();
    let initial = [-0.5, -0.5, -0.5, 0.0, -0.5, 0.0];
    let tool = calibrated_frames(&c, &initial)[6];
    let dist = max_diff(&rows, &tool.iter().flatten().copied().collect::<Vec<_>>());
    // Printed with 17 significant digits (--precision full).
    assert!(dist < 1e-14, "{dist:e}\n{text}");
}

#[test]
fn table_bakes_the_calibration_and_names_the_file() {
    let dir = fresh_dir("calibration-table");
    let noise = noise_file(&dir, "cal.json", Some(&cal()), Some(true));
    let sha = {
        use sha2::Digest;
        let d = sha2::Sha256::digest(std::fs::read(&noise).unwrap());
        d.iter().map(|b| format!("{b:02x}")).collect::<String>()
    };
    let n = noise.to_str().unwrap();
    for lang in ["rust", "c"] {
        let o = run(&refs(&seed_args("table", &["--noise", n, "--lang", lang])));
        success(&o);
        let src = String::from_utf8_lossy(&o.stdout);
        let head: Vec<&str> = src.lines().take(3).collect();
        assert!(head[1].contains("Calibrated: "), "{lang}:\n{src}");
        assert!(
            head[2].contains("`cal.json`") && head[2].contains(&sha),
            "{lang}:\n{src}"
        );
        let plain = run(&refs(&seed_args("table", &["--lang", lang])));
        assert_ne!(plain.stdout, o.stdout);
    }
    // Without a calibration a C table takes nothing of a noise model: still refused.
    let plain = noise_file(&dir, "plain.json", None, None);
    let o = run(&refs(&seed_args(
        "table",
        &["--noise", plain.to_str().unwrap(), "--lang", "c"],
    )));
    assert!(one_line_error(&o, 1).contains("cannot be baked into a C table"));
}

/// Every `--noise` refuses a rejected fit with the same sentence, and takes it with
/// `--allow-rejected-noise`.
#[test]
fn rejected_fits_are_refused_by_every_noise_flag() {
    let dir = fresh_dir("calibration-rejected");
    let noise = noise_file(&dir, "rejected.json", Some(&cal()), Some(false));
    let input = dir.join("cases.json");
    std::fs::write(
        &input,
        json!({"cases": [{"thetas": THETAS[1]}]}).to_string(),
    )
    .unwrap();
    let (n, i, d) = (
        noise.to_str().unwrap(),
        input.to_str().unwrap(),
        dir.to_str().unwrap(),
    );
    let runs: Vec<Vec<String>> = vec![
        seed_args("eval", &["--noise", n, "--input", i]),
        seed_args("table", &["--noise", n]),
        seed_args(
            "render",
            &["--noise", n, "--input", i, "--grid", "2", "--out", d],
        ),
        seed_args(
            "mesh",
            &["--noise", n, "--input", i, "--grid", "2", "--out", d],
        ),
        [
            "demo", "--noise", n, "--frames", "1", "--grid", "2", "--out", d,
        ]
        .map(String::from)
        .to_vec(),
    ];
    for args in &runs {
        let line = one_line_error(&run(&refs(args)), 1);
        for part in [
            "rejected.json",
            "was rejected by its goodness-of-fit test",
            "ppoe fit --estimate",
            "--allow-rejected-noise",
        ] {
            assert!(line.contains(part), "{}: {line}", args[0]);
        }
        let mut forced = args.clone();
        forced.push("--allow-rejected-noise".into());
        success(&run(&refs(&forced)));
    }
    // The flag needs --noise.
    let o = run(&refs(&seed_args(
        "eval",
        &["--allow-rejected-noise", "--input", i],
    )));
    assert_eq!(o.status.code(), Some(2));
}
