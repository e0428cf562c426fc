//! Runs every request of `test_data/urdf/malformed/expected.json` and checks the error kind,
//! the substrings the message must contain, and (for XML errors) the line.

use ppoe_build::Config;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn malformed_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../test_data/urdf/malformed")
}

#[test]
fn every_malformed_request_fails_as_expected() {
    let dir = malformed_dir();
    let text = std::fs::read_to_string(dir.join("expected.json")).expect("expected.json");
    let cases: Vec<Value> = serde_json::from_str(&text).expect("expected.json is JSON");
    assert!(!cases.is_empty());

    let mut failures = Vec::new();
    let mut checked = 0;
    let mut missing = Vec::new();
    for case in &cases {
        let file = case["file"].as_str().expect("file");
        let path = dir.join(file);
        if !path.exists() {
            missing.push(file.to_string());
            continue;
        }
        let base = case["base"].as_str().expect("base");
        let tip = case["tip"].as_str().expect("tip");
        let mut config = Config::new(&path);
        config.base(base).tip(tip);
        if let Some(joints) = case["joints"].as_array() {
            config.joints(joints.iter().map(|j| j.as_str().expect("joint name")));
        }
        let label = format!("{file} ({base} -> {tip}, joints {})", case["joints"]);
        checked += 1;
        let err = match config.chain() {
            Ok(chain) => {
                failures.push(format!(
                    "{label}: accepted, chain {:?}",
                    chain.joint_names()
                ));
                continue;
            }
            Err(e) => e,
        };
        // Generating source must fail the same way.
        match config.generate() {
            Ok(_) => failures.push(format!("{label}: generate() accepted")),
            Err(g) if g.kind() != err.kind() => failures.push(format!(
                "{label}: generate() gave {:?}, chain() {:?}",
                g.kind(),
                err.kind()
            )),
            Err(_) => {}
        }
        let shown = err.to_string();
        let expected_kind = case["error"].as_str().expect("error");
        if err.kind().name() != expected_kind {
            failures.push(format!(
                "{label}: kind {:?}, expected {expected_kind}: {shown}",
                err.kind()
            ));
            continue;
        }
        for m in case["mentions"].as_array().expect("mentions") {
            let m = m.as_str().expect("mention");
            if !shown.contains(m) {
                failures.push(format!("{label}: message does not mention {m:?}: {shown}"));
            }
        }
        if let Some(line) = case.get("line").and_then(Value::as_u64) {
            match err.position() {
                Some(p) if u64::from(p.line) == line => {}
                other => failures.push(format!(
                    "{label}: position {other:?}, expected line {line}: {shown}"
                )),
            }
            if !shown.contains(&line.to_string()) {
                failures.push(format!("{label}: message lacks line {line}: {shown}"));
            }
        }
        // The file is named in the message.
        if !shown.contains(file) {
            failures.push(format!("{label}: message does not name the file: {shown}"));
        }
    }
    if !missing.is_empty() {
        eprintln!(
            "note: {} file(s) of expected.json not present yet: {}",
            missing.len(),
            missing.join(", ")
        );
    }
    assert!(
        failures.is_empty(),
        "{} of {checked} requests failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(checked >= 20, "only {checked} malformed requests checked");
}

/// `valid_tree.urdf` is valid: its two documented chains load.
#[test]
fn the_valid_tree_of_the_malformed_set_loads() {
    let path = malformed_dir().join("valid_tree.urdf");
    if !path.exists() {
        return;
    }
    let left = Config::new(&path)
        .base("base")
        .tip("l_tip")
        .chain()
        .unwrap();
    assert_eq!(left.joint_names(), ["l_j1", "l_j2", "l_j3"]);
    let right = Config::new(&path)
        .base("base")
        .tip("r_tip")
        .chain()
        .unwrap();
    assert_eq!(right.joint_names(), ["r_j1", "r_j2"]);
}

/// No input makes the parser panic: every malformed file, cut at every length, and with a
/// byte flipped, gives `Ok` or an `Err`.
#[test]
fn truncated_and_corrupted_files_never_panic() {
    let dir = malformed_dir();
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    files.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("../test_data/urdf/seed.urdf"));
    files.retain(|p| p.extension().is_some_and(|e| e == "urdf"));
    files.sort();
    for path in files {
        let bytes = std::fs::read(&path).unwrap();
        let step = (bytes.len() / 200).max(1);
        for cut in (0..bytes.len()).step_by(step) {
            let mut b = bytes[..cut].to_vec();
            let _ = ppoe_build::Urdf::parse_bytes(&b).and_then(|u| {
                u.chain("linkmount", "tcp", None::<&[&str]>)?;
                u.chain("base", "tip", None::<&[&str]>)
            });
            if let Some(x) = b.last_mut() {
                *x ^= 0x5a;
            }
            let _ = ppoe_build::Urdf::parse_bytes(&b);
        }
    }
}
