//! Calibrated noise files (issue #27): the table and the runtime chain of a noise file with
//! a calibration are the calibrated robot's — checked against the unfolded calibrated
//! product `Exp(S₁''(θ₁+δ₁))···Exp(Sₙ''(θₙ+δₙ))·M·Exp(μ)`, `Sᵢ'' = Ad(Exp(κᵢ))·Sᵢ`,
//! computed here with this file's own 4×4 exponential (no code of ppoe or ppoe-build) —;
//! a zero calibration changes no byte; rejected fits are refused unless allowed; bad
//! calibration fields are errors naming the joint and the field.

mod common;

use ppoe_build::codegen::{self, sha256_hex, Source};
use ppoe_build::noise::NoiseModel;
use ppoe_build::{Config, ErrorKind, RobotChain};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

use ppoe_test_robots::matrix4::{exp, inv, mul, M4};
use ppoe_test_robots::Rng;

/// The chains of `tests/codegen.rs` (revolute, continuous, prismatic, fixed joints between).
const CHAINS: &[(&str, &str, &str)] = &[
    ("seed.urdf", "linkmount", "tcp"),
    ("continuous.urdf", "base", "ee"),
    ("fixed_between.urdf", "world", "tool_tip"),
    ("prismatic.urdf", "base_link", "tool0"),
    ("rpy_everywhere.urdf", "base", "tool"),
    ("tree.urdf", "base_footprint", "left_tip"),
];

/// Six uniform values in [−scale, scale].
fn vec6(rng: &mut Rng, scale: f64) -> [f64; 6] {
    std::array::from_fn(|_| rng.uniform(scale))
}

/// A calibration: δ per joint, κ per joint, μ.
struct Cal {
    offsets: Vec<f64>,
    kappas: Vec<[f64; 6]>,
    mu: [f64; 6],
}

fn random_cal(n: usize, rng: &mut Rng) -> Cal {
    Cal {
        offsets: (0..n).map(|_| rng.uniform(0.05)).collect(),
        kappas: (0..n).map(|_| vec6(rng, 0.02)).collect(),
        mu: vec6(rng, 0.02),
    }
}

/// The noise file's JSON for `chain` with calibration `cal` (its fields absent if `None`)
/// and `goodness_of_fit.fits` = `fits` (absent if `None`).
fn noise_json(chain: &RobotChain, cal: Option<&Cal>, fits: Option<bool>) -> String {
    let cov: Vec<Vec<f64>> = (0..6)
        .map(|i| (0..6).map(|j| if i == j { 1e-6 } else { 0.0 }).collect())
        .collect();
    let joints: Vec<Value> = chain
        .joint_names()
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let mut j = json!({"name": n, "cov": cov, "sigma2": 1e-6});
            if let Some(c) = cal {
                j["offset"] = json!(c.offsets[i]);
                j["offset_se"] = json!(1e-6);
                j["axis_correction"] = json!(c.kappas[i]);
            }
            j
        })
        .collect();
    let mut v = json!({"model": "joint", "joints": joints});
    if let Some(c) = cal {
        v["calibration"] = json!({
            "estimated": ["base", "tip", "offsets", "kinematics"],
            "home_correction": c.mu,
            "residual_rms": {"before": 1e-3, "after": 1e-5},
        });
    }
    if let Some(f) = fits {
        v["goodness_of_fit"] = json!({"fits": f, "p_value": 0.5});
    }
    serde_json::to_string_pretty(&v).unwrap()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn tmp(tag: &str) -> PathBuf {
    std::env::temp_dir().join(format!(
        "ppoe-build-calibration-{tag}-{}",
        std::process::id()
    ))
}

fn config(file: &str, base: &str, tip: &str) -> Config {
    let mut c = Config::new(common::urdf_path(file));
    c.base(base).tip(tip);
    c
}

/// `Exp(S₁θ₁)···Exp(Sₙθₙ)·M` of a host chain, with this file's exponential.
fn product(chain: &RobotChain, thetas: &[f64]) -> M4 {
    let mut t = exp(&[0.0; 6]);
    for (j, th) in chain.joints.iter().zip(thetas) {
        t = mul(&t, &exp(&j.screw.map(|s| s * th)));
    }
    mul(&t, &chain.home)
}

/// The unfolded calibrated product of the nominal chain:
/// `Π Exp(κᵢ)·Exp(Sᵢ(θᵢ+δᵢ))·Exp(κᵢ)⁻¹ · M · Exp(μ)` (`Exp(Ad(K)·S·t) = K·Exp(S·t)·K⁻¹`).
fn calibrated_product(nominal: &RobotChain, cal: &Cal, thetas: &[f64]) -> M4 {
    let mut t = exp(&[0.0; 6]);
    for (i, (j, th)) in nominal.joints.iter().zip(thetas).enumerate() {
        let k = exp(&cal.kappas[i]);
        let e = exp(&j.screw.map(|s| s * (th + cal.offsets[i])));
        t = mul(&t, &mul(&mul(&k, &e), &inv(&k)));
    }
    mul(&mul(&t, &nominal.home), &exp(&cal.mu))
}

fn max_diff(a: &M4, b: &M4) -> f64 {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn calibrated_chain_is_the_unfolded_calibrated_product() {
    let dir = tmp("product");
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    for (file, base, tip) in CHAINS {
        let nominal = config(file, base, tip).chain().unwrap();
        let n = nominal.joints.len();
        for round in 0..3 {
            let cal = random_cal(n, &mut rng);
            let path = write(
                &dir,
                "fit.json",
                &noise_json(&nominal, Some(&cal), Some(true)),
            );
            let folded = config(file, base, tip).noise(&path).chain().unwrap();
            assert_ne!(folded, nominal, "{file}: the calibration changed nothing");
            for _ in 0..10 {
                let thetas: Vec<f64> = (0..n).map(|_| rng.uniform(2.0)).collect();
                let (a, b) = (
                    product(&folded, &thetas),
                    calibrated_product(&nominal, &cal, &thetas),
                );
                let d = max_diff(&a, &b);
                assert!(d < 1e-12, "{file} round {round}: {d:e} at {thetas:?}");
                // The test can fail: the nominal chain is far from the calibrated product.
                assert!(max_diff(&product(&nominal, &thetas), &b) > 1e-4, "{file}");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The generated table holds exactly the calibrated runtime chain, in Rust and C: its source
/// is the chain's table with the calibration note (naming the file and its sha256) after
/// the first line, then the noise items.
#[test]
fn calibrated_table_is_the_calibrated_chains_and_says_so() {
    let dir = tmp("table");
    let mut rng = Rng::new(42);
    for (file, base, tip) in CHAINS {
        let nominal = config(file, base, tip).chain().unwrap();
        let cal = random_cal(nominal.joints.len(), &mut rng);
        let text = noise_json(&nominal, Some(&cal), None);
        let path = write(&dir, "cal fit.json", &text);
        let folded = config(file, base, tip).noise(&path).chain().unwrap();
        let mut cfg = config(file, base, tip);
        cfg.noise(&path).name("T");
        let src = cfg.generate().unwrap();
        let source = Source {
            file_name: file.to_string(),
            sha256: sha256_hex(&std::fs::read(common::urdf_path(file)).unwrap()),
        };
        let table = codegen::generate(&folded, "T", Default::default(), &source).unwrap();
        let (first, rest) = table.split_once('\n').unwrap();
        let lines: Vec<&str> = src.lines().collect();
        assert_eq!(lines[0], first, "{file}");
        assert!(lines[1].starts_with("// Calibrated: "), "{file}:\n{src}");
        assert!(
            lines[1].contains("(estimated: base, tip, offsets, kinematics)"),
            "{src}"
        );
        assert!(lines[2].contains("`cal fit.json`"), "{file}:\n{src}");
        assert!(
            lines[2].contains(&sha256_hex(text.as_bytes())),
            "{file}:\n{src}"
        );
        let after = lines[3..].join("\n");
        assert!(after.starts_with(rest.trim_end()), "{file}:\n{src}");
        assert!(after.contains("pub const T_NOISE: "), "{file}");
        // C: the same calibrated values (the C generator's own test ties them to Rust's).
        let c = cfg.generate_c().unwrap();
        let c_table = ppoe_build::codegen_c::generate(&folded, "T", Default::default(), &source);
        let c_table = c_table.unwrap();
        let (c_first, c_rest) = c_table.split_once('\n').unwrap();
        let c_lines: Vec<&str> = c.lines().collect();
        assert_eq!(c_lines[0], c_first, "{file}");
        assert!(c_lines[1].starts_with(" * Calibrated: "), "{file}:\n{c}");
        assert!(c_lines[2].contains(&sha256_hex(text.as_bytes())), "{c}");
        assert_eq!(c_lines[3..].join("\n"), c_rest.trim_end(), "{file}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A noise file without calibration, or with every calibration value zero, gives the
/// table of today byte for byte: the chain's table without noise, then the noise items;
/// the C table and the runtime chain are those without a noise file.
#[test]
fn zero_calibration_changes_no_byte() {
    let dir = tmp("zero");
    for (file, base, tip) in CHAINS {
        let plain = config(file, base, tip).chain().unwrap();
        let n = plain.joints.len();
        let zero = Cal {
            offsets: vec![0.0; n],
            kappas: vec![[0.0; 6]; n],
            mu: [0.0; 6],
        };
        let without = write(&dir, "plain.json", &noise_json(&plain, None, None));
        let zeros = write(
            &dir,
            "zeros.json",
            &noise_json(&plain, Some(&zero), Some(true)),
        );
        let no_noise = config(file, base, tip).generate().unwrap();
        let bare = config(file, base, tip).generate_c().unwrap();
        let mut reference = None;
        for path in [&without, &zeros] {
            let mut c = config(file, base, tip);
            c.noise(path);
            assert_eq!(c.chain().unwrap(), plain, "{file}");
            assert_eq!(c.generate_c().unwrap(), bare, "{file}");
            let src = c.generate().unwrap();
            assert!(src.starts_with(&no_noise), "{file}: {src}");
            assert!(!src.contains("Calibrated"), "{file}");
            // The noise items name the file; with the same name the sources are equal.
            let src = src.replace("zeros.json", "plain.json");
            assert_eq!(reference.get_or_insert_with(|| src.clone()), &src, "{file}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn rejected_fits_are_refused_unless_allowed() {
    let dir = tmp("rejected");
    let chain = config("seed.urdf", "linkmount", "tcp").chain().unwrap();
    let cal = random_cal(6, &mut Rng::new(7));
    let rejected = write(
        &dir,
        "rejected.json",
        &noise_json(&chain, Some(&cal), Some(false)),
    );
    let mut c = config("seed.urdf", "linkmount", "tcp");
    c.noise(&rejected);
    for e in [
        c.generate().unwrap_err(),
        c.generate_c().unwrap_err(),
        c.chain().unwrap_err(),
    ] {
        let m = e.to_string();
        assert_eq!(e.kind(), ErrorKind::Config, "{m}");
        assert!(
            m.contains("rejected.json") && m.contains("was rejected by its goodness-of-fit test"),
            "{m}"
        );
        assert!(
            m.contains("ppoe fit --estimate") && m.contains("allow_rejected_noise(true)"),
            "{m}"
        );
    }
    c.allow_rejected_noise(true);
    assert!(c.generate().unwrap().contains("// Calibrated: "));
    assert!(c.generate_c().is_ok() && c.chain().is_ok());
    // Accepted fits and hand-written files (no goodness_of_fit) are used without the flag.
    for fits in [Some(true), None] {
        let p = write(&dir, "ok.json", &noise_json(&chain, Some(&cal), fits));
        assert!(config("seed.urdf", "linkmount", "tcp")
            .noise(&p)
            .generate()
            .is_ok());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// (JSON pointer of a field, a bad value, what the error must say.)
fn bad_fields() -> Vec<(&'static str, Value, &'static str)> {
    vec![
        (
            "/joints/1/offset",
            json!("0.1"),
            "joint 1 ('joint2') offset: expected a finite number",
        ),
        (
            "/joints/2/offset",
            Value::Null,
            "joint 2 ('joint3') offset: expected a finite number",
        ),
        (
            "/joints/0/axis_correction",
            json!([0, 0, 0, 0, 0]),
            "joint 0 ('joint1') axis_correction: expected an array of 6",
        ),
        (
            "/joints/5/axis_correction",
            json!([0, 0, 0, 0, 0, "x"]),
            "joint 5 ('joint6') axis_correction: expected an array of 6",
        ),
        (
            "/joints/3/axis_correction",
            json!({"w": 1}),
            "joint 3 ('joint4') axis_correction",
        ),
        (
            "/calibration",
            json!([1]),
            "\"calibration\" is not an object",
        ),
        (
            "/calibration",
            json!({"home_correction": [0, 0, 0, 0, 0, 0, 0]}),
            "calibration.home_correction: expected an array of 6",
        ),
        (
            "/calibration",
            json!({"estimated": [1]}),
            "calibration.estimated: expected an array of strings",
        ),
        (
            "/goodness_of_fit",
            json!({"fits": "yes"}),
            "goodness_of_fit.fits: expected true or false",
        ),
        (
            "/goodness_of_fit",
            json!(true),
            "\"goodness_of_fit\" is not an object",
        ),
    ]
}

/// Each bad calibration field is an error naming the joint (or the field) and the shape.
#[test]
fn bad_calibration_fields_name_the_joint() {
    let chain = config("seed.urdf", "linkmount", "tcp").chain().unwrap();
    let good: Value = serde_json::from_str(&noise_json(&chain, None, None)).unwrap();
    for (pointer, value, expected) in &bad_fields() {
        let mut v = good.clone();
        let (parent, key) = pointer.rsplit_once('/').unwrap();
        v.pointer_mut(parent)
            .unwrap()
            .as_object_mut()
            .unwrap()
            .insert(key.to_string(), value.clone());
        let e = NoiseModel::parse(&v.to_string()).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::Config, "{pointer}: {e}");
        assert!(e.to_string().contains(expected), "{pointer}: {e}");
    }
    // A calibration built by hand for another number of joints is an error, not a panic.
    let mut model = NoiseModel::parse(&good.to_string()).unwrap();
    model.calibration.offsets = vec![0.1; 5];
    let e = model.calibrated_chain(&chain).unwrap_err();
    assert!(
        e.to_string().contains("5 offsets, the chain has 6 joints"),
        "{e}"
    );
}
