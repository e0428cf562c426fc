//! The chains of `test_data/golden/ppoe/*.json` (produced by pytransform3d 3.17.0): joint
//! names and kinds, screw axes, home pose and limits.
//!
//! The values agree bit for bit: `ppoe-build` evaluates the products in the order and with
//! the fused multiply-adds of the numpy/OpenBLAS build that produced the files (see
//! `src/math.rs`). Should the files be regenerated with a BLAS without FMA, expect
//! differences in the last bit or two; the 1e-15 bound below is the contract, bit-exactness
//! the bonus.

#![allow(clippy::needless_range_loop)] // index loops read best for matrices

use ppoe_build::{Config, JointKind};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn num(v: &Value) -> f64 {
    match v {
        Value::String(s) => match s.as_str() {
            "inf" => f64::INFINITY,
            "-inf" => f64::NEG_INFINITY,
            _ => f64::NAN,
        },
        _ => v.as_f64().expect("number"),
    }
}

fn golden_files() -> Vec<PathBuf> {
    let dir = root().join("test_data/golden/ppoe");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    files.retain(|p| p.extension().is_some_and(|e| e == "json"));
    files.sort();
    files
}

#[test]
fn chains_match_pytransform3d() {
    let files = golden_files();
    if files.is_empty() {
        eprintln!("note: no golden files in test_data/golden/ppoe");
        return;
    }
    let mut not_bit_exact = Vec::new();
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        let g: Value = serde_json::from_str(&text).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let urdf = root().join(g["urdf"].as_str().unwrap());
        let names: Vec<&str> = g["joints"]
            .as_array()
            .unwrap()
            .iter()
            .map(|j| j.as_str().unwrap())
            .collect();
        let base = g["base"].as_str().unwrap();
        let tip = g["tip"].as_str().unwrap();

        // Default joint list = the moving joints on the path, which is what the files use;
        // the explicit list gives the same chain.
        let chain = Config::new(&urdf).base(base).tip(tip).chain().unwrap();
        let explicit = Config::new(&urdf)
            .base(base)
            .tip(tip)
            .joints(&names)
            .chain()
            .unwrap();
        assert_eq!(chain, explicit, "{name}");
        assert_eq!(chain.joint_names(), names, "{name}");
        assert_eq!(chain.base, base);
        assert_eq!(chain.tip, tip);

        let mut check = |what: String, ours: f64, golden: f64| {
            assert!(
                ours == golden || (ours - golden).abs() <= 1e-15,
                "{name}: {what}: ours {ours:?}, pytransform3d {golden:?}"
            );
            if ours.to_bits() != golden.to_bits() {
                not_bit_exact.push(format!("{name}: {what}: {ours:?} vs {golden:?}"));
            }
        };
        for (i, j) in chain.joints.iter().enumerate() {
            let kind = match j.kind {
                JointKind::Revolute => "revolute",
                JointKind::Continuous => "continuous",
                JointKind::Prismatic => "prismatic",
            };
            assert_eq!(
                kind,
                g["joint_types"][i].as_str().unwrap(),
                "{name}: {}",
                j.name
            );
            for k in 0..6 {
                check(
                    format!("screw {} [{k}]", j.name),
                    j.screw[k],
                    num(&g["screw_axes"][i][k]),
                );
            }
            check(
                format!("lower {}", j.name),
                j.lower,
                num(&g["limits"][i][0]),
            );
            check(
                format!("upper {}", j.name),
                j.upper,
                num(&g["limits"][i][1]),
            );
        }
        for r in 0..4 {
            for c in 0..4 {
                check(
                    format!("home [{r}][{c}]"),
                    chain.home[r][c],
                    num(&g["home"][r][c]),
                );
            }
        }
    }
    assert!(
        not_bit_exact.is_empty(),
        "within 1e-15 but not bit-exact (golden files regenerated with another BLAS?):\n{}",
        not_bit_exact.join("\n")
    );
}
