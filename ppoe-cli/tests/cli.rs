//! End-to-end tests of the `ppoe` command.

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::repo;

fn seed_urdf() -> PathBuf {
    common::urdf("seed.urdf")
}

fn tmp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("ppoe-cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn run(args: &[&str], stdin: Option<&str>) -> Output {
    common::run_bytes(args, stdin.unwrap_or("").as_bytes())
}

/// Asserts failure (status 1) with exactly one stderr line `error: ...`; returns it.
fn assert_one_line_error(out: &Output) -> String {
    common::one_line_error(out, 1)
}

/// Asserts success, with standard error (after `context`) as the failure message.
fn assert_success(out: &Output, context: &str) {
    assert!(
        out.status.success(),
        "{context}{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Runs `ppoe <cmd> --urdf seed.urdf --base linkmount --tip tcp <extra>`.
fn run_seed(cmd: &str, extra: &[&str], stdin: Option<&str>) -> Output {
    let urdf = seed_urdf();
    let mut args = vec![
        cmd,
        "--urdf",
        urdf.to_str().unwrap(),
        "--base",
        "linkmount",
        "--tip",
        "tcp",
    ];
    args.extend_from_slice(extra);
    run(&args, stdin)
}

/// Asserts a one-line error (see [`assert_one_line_error`]) that contains every one of
/// `mentions`.
fn assert_error_mentions(out: &Output, mentions: &[&str]) {
    let line = assert_one_line_error(out);
    for m in mentions {
        assert!(line.contains(m), "{line}");
    }
}

fn golden() -> Value {
    let text =
        std::fs::read_to_string(repo().join("test_data/golden/ppoe/seed_linkmount_tcp.json"))
            .unwrap();
    serde_json::from_str(&text).unwrap()
}

fn golden_case(label: &str) -> Value {
    golden()["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["label"] == label)
        .unwrap_or_else(|| panic!("no case {label}"))
        .clone()
}

fn matrix(v: &Value) -> Vec<Vec<f64>> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect()
}

/// Max |a − b| relative to the largest entry of b (at least 1e-300).
fn rel_err(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()))
        .max(1e-300);
    a.iter()
        .zip(b)
        .flat_map(|(ra, rb)| {
            assert_eq!(ra.len(), rb.len());
            ra.iter().zip(rb).map(|(x, y)| (x - y).abs())
        })
        .fold(0.0, f64::max)
        / scale
}

fn seed_input(case: &Value) -> String {
    json!({"cases": [{"thetas": case["thetas"], "covs": case["covs"]}]}).to_string()
}

fn eval_seed(extra: &[&str], input: &str) -> Value {
    let out = run_seed("eval", extra, Some(input));
    assert_success(&out, "");
    serde_json::from_slice(&out.stdout).unwrap()
}

/// `rel_err` of two JSON matrices is at most `tol`.
fn close(a: &Value, b: &Value, tol: f64) -> bool {
    rel_err(&matrix(a), &matrix(b)) <= tol
}

#[test]
fn eval_seed_initial_matches_golden_right() {
    let case = golden_case("seed_initial");
    let out = eval_seed(&["--convention", "ppoe"], &seed_input(&case));
    let r = &out["results"][0];
    assert!(close(&r["pose"], &case["pose"], 1e-12));
    assert!(close(&r["cov"], &case["cov_right"], 1e-12));
    // The default convention is the right perturbation.
    let out2 = eval_seed(&[], &seed_input(&case));
    assert_eq!(out, out2);
}

#[test]
fn eval_seed_initial_matches_golden_pytransform3d() {
    let case = golden_case("seed_initial");
    let path = tmp("seed_initial.json");
    std::fs::write(&path, seed_input(&case)).unwrap();
    let out = eval_seed(
        &[
            "--convention",
            "pytransform3d",
            "--input",
            path.to_str().unwrap(),
        ],
        "",
    );
    let r = &out["results"][0];
    assert!(close(&r["pose"], &case["pose"], 1e-12));
    assert!(close(&r["cov"], &case["cov_pytransform3d"], 1e-12));
    assert_eq!(r["thetas_clipped"], case["thetas_clipped"]);
}

#[test]
fn eval_left_convention_matches_golden() {
    let case = golden_case("seed_initial");
    let out = eval_seed(&["--convention", "left"], &seed_input(&case));
    let r = &out["results"][0];
    assert!(close(&r["cov"], &case["cov_left"], 1e-12));
}

#[test]
fn eval_chain_matches_golden() {
    let g = golden();
    let case = golden_case("seed_initial");
    let out = eval_seed(&[], &seed_input(&case));
    let c = &out["chain"];
    assert_eq!(c["base"], "linkmount");
    assert_eq!(c["tip"], "tcp");
    assert_eq!(c["joints"], g["joints"]);
    assert!(close(&c["screw_axes"], &g["screw_axes"], 1e-12));
    assert!(close(&c["home"], &g["home"], 1e-12));
    // Infinite limits are null.
    assert_eq!(
        c["limits"],
        json!([
            [-1.0, 1.0],
            [-1.0, null],
            [null, 1.0],
            [null, null],
            [null, null],
            [null, null]
        ])
    );
}

#[test]
fn eval_many_golden_cases_and_clipping() {
    // Every golden case of the seed robot (inside, outside and at limits), both
    // conventions, in one call each.
    let g = golden();
    let cases: Vec<&Value> = g["cases"].as_array().unwrap().iter().collect();
    let input = json!({"cases": cases.iter().map(|c| json!({"thetas": c["thetas"], "covs": c["covs"]})).collect::<Vec<_>>()}).to_string();
    for (conv, key) in [
        ("ppoe", "cov_right"),
        ("pytransform3d", "cov_pytransform3d"),
    ] {
        let out = eval_seed(&["--convention", conv], &input);
        let results = out["results"].as_array().unwrap();
        assert_eq!(results.len(), cases.len());
        for (r, c) in results.iter().zip(&cases) {
            let label = &c["label"];
            assert!(close(&r["pose"], &c["pose"], 1e-12), "{label}");
            assert!(close(&r["cov"], &c[key], 1e-12), "{label} {conv}");
            if conv == "pytransform3d" {
                assert_eq!(r["thetas_clipped"], c["thetas_clipped"], "{label}");
            }
        }
    }
}

#[test]
fn eval_f32_is_close() {
    let case = golden_case("seed_initial");
    let out = eval_seed(&["--scalar", "f32"], &seed_input(&case));
    let r = &out["results"][0];
    assert!(close(&r["pose"], &case["pose"], 1e-5));
    assert!(close(&r["cov"], &case["cov_right"], 1e-4));
}

#[test]
fn table_prints_const_and_sha256() {
    use sha2::Digest;
    let sha = sha2::Sha256::digest(std::fs::read(seed_urdf()).unwrap());
    let sha: String = sha.iter().map(|b| format!("{b:02x}")).collect();
    let src = seed_table(&["--scalar", "both", "--name", "ARM"]);
    for expected in [
        "pub const ARM: ppoe::chain::Chain<f64, 6>",
        "pub const ARM_F32: ppoe::chain::Chain<f32, 6>",
        &sha,
    ] {
        assert!(src.contains(expected), "{src}");
    }
}

/// The source `ppoe table` prints for the seed robot with the `extra` arguments.
fn seed_table(extra: &[&str]) -> String {
    let out = run_seed("table", extra, None);
    assert_success(&out, "");
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn table_with_explicit_joints() {
    let src = seed_table(&["--joints", "joint1,joint2,joint3"]);
    assert!(
        src.contains("pub const SEED: ppoe::chain::Chain<f64, 3>"),
        "{src}"
    );
}

#[test]
fn error_missing_urdf() {
    let args = [
        "eval",
        "--urdf",
        "no/such.urdf",
        "--base",
        "a",
        "--tip",
        "b",
    ];
    assert_error_mentions(&run(&args, Some("{}")), &["no/such.urdf"]);
}

#[test]
fn error_missing_input_file() {
    let out = run_seed("eval", &["--input", "no/such/cases.json"], None);
    assert_error_mentions(&out, &["cases.json"]);
}

/// Asserts that `ppoe eval` of the seed robot fails on `input` with one line mentioning
/// each of `mentions`.
fn eval_seed_err(input: &str, mentions: &[&str]) {
    assert_error_mentions(&run_seed("eval", &[], Some(input)), mentions)
}

#[test]
fn error_malformed_json() {
    for bad in [
        "",
        "{\"cases\": [",
        "[1, 2]",
        "{\"cases\": [{\"thetas\": [1, 2, 3, 4, 5, 6]}]}",
        "{\"cases\": [{\"thetas\": \"x\", \"covs\": []}]}",
    ] {
        let line = assert_one_line_error(&run_seed("eval", &[], Some(bad)));
        assert!(line.contains("malformed input JSON"), "{bad}: {line}");
    }
    // A covariance that is not 6×6.
    let mut case = golden_case("seed_initial");
    case["covs"][1] = json!(vec![vec![0.0; 5]; 6]);
    eval_seed_err(&seed_input(&case), &["malformed input JSON"]);
}

#[test]
fn error_wrong_joint_count() {
    let input = r#"{"cases":[{"thetas":[0,0],"covs":[]}]}"#;
    eval_seed_err(input, &["case 0", "6 joints"]);
    let mut case = golden_case("seed_initial");
    case["covs"].as_array_mut().unwrap().pop();
    eval_seed_err(&seed_input(&case), &["5 covariances"]);
}

#[test]
fn error_not_psd_names_case_and_joint() {
    let case = golden_case("seed_initial");
    let mut bad = case.clone();
    bad["covs"][2][1][1] = json!(-0.05);
    let input = json!({"cases": [
        {"thetas": case["thetas"], "covs": case["covs"]},
        {"thetas": case["thetas"], "covs": case["covs"]},
        {"thetas": case["thetas"], "covs": case["covs"]},
        {"thetas": bad["thetas"], "covs": bad["covs"]},
    ]})
    .to_string();
    eval_seed_err(&input, &["case 3, joint 2", "not positive semi-definite"]);
    // Not symmetric.
    let mut asym = case.clone();
    asym["covs"][0][0][1] = json!(0.01);
    eval_seed_err(&seed_input(&asym), &["case 0, joint 0", "symmetric"]);
    // Issue #26 item 4: antisymmetric by its own scale of 1e-8 (an absolute tolerance of
    // 1.5e-8 let it through).
    let mut small = case.clone();
    for i in 0..6 {
        for j in 0..6 {
            small["covs"][4][i][j] = json!(if i == j { 1e-8 } else { 0.0 });
        }
    }
    small["covs"][4][0][1] = json!(5e-9);
    small["covs"][4][1][0] = json!(-5e-9);
    eval_seed_err(&seed_input(&small), &["case 0, joint 4", "not symmetric"]);
}

#[test]
fn error_malformed_urdfs() {
    let dir = repo().join("test_data/urdf/malformed");
    let expected: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    let entries = expected.as_array().unwrap();
    assert!(entries.len() >= 20);
    for e in entries {
        let file = dir.join(e["file"].as_str().unwrap());
        let mut args: Vec<String> = vec![
            "table".into(),
            "--urdf".into(),
            file.to_str().unwrap().into(),
            "--base".into(),
            e["base"].as_str().unwrap().into(),
            "--tip".into(),
            e["tip"].as_str().unwrap().into(),
        ];
        if let Some(j) = e["joints"].as_array() {
            let names: Vec<&str> = j.iter().map(|x| x.as_str().unwrap()).collect();
            args.push("--joints".into());
            args.push(names.join(","));
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let line = assert_one_line_error(&run(&args, None));
        for m in e["mentions"].as_array().unwrap() {
            assert!(
                line.contains(m.as_str().unwrap()),
                "{}: {line} lacks {m}",
                e["file"]
            );
        }
        if let Some(l) = e["line"].as_u64() {
            assert!(line.contains(&format!(":{l}:")), "{}: {line}", e["file"]);
        }
    }
}

#[test]
fn help_works_everywhere() {
    for cmd in ["table", "eval", "demo", "render", "mesh"] {
        let out = run(&[cmd, "--help"], None);
        assert!(out.status.success(), "{cmd}");
        assert!(
            String::from_utf8_lossy(&out.stdout).contains("Usage"),
            "{cmd}"
        );
    }
    assert!(run(&["--help"], None).status.success());
}

fn is_stub_picture() -> bool {
    let src = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/picture.rs"))
        .unwrap_or_default();
    src.contains("STUB")
}

#[test]
fn demo_runs() {
    let dir = tmp("demo");
    let _ = std::fs::remove_dir_all(&dir);
    let out = run(
        &["demo", "--frames", "3", "--out", dir.to_str().unwrap()],
        None,
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_success(&out, "");
    for expected in ["ppoe-seed.png", "ppoe-seed.gif", "initial pose"] {
        assert!(stdout.contains(expected), "{stdout}");
    }
    // The printed initial pose is the golden one (to the printed precision: 6 significant
    // digits by default).
    let t = golden_case("seed_initial")["pose"][0][3].as_f64().unwrap();
    assert!(stdout.contains(&format!("{t:.5e}")), "{stdout}");
    if is_stub_picture() {
        eprintln!("picture.rs is still a stub: image checks skipped");
        return;
    }
    let png = std::fs::read(dir.join("ppoe-seed.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
    let gif = std::fs::read(dir.join("ppoe-seed.gif")).unwrap();
    assert!(gif.starts_with(b"GIF8"));
}

#[test]
fn demo_other_surfaces_run() {
    for (i, extra) in [
        vec!["--surface", "pytransform3d"],
        vec!["--surface", "marginal", "--probability", "0.95"],
    ]
    .into_iter()
    .enumerate()
    {
        let dir = tmp(&format!("demo-surface-{i}"));
        let mut args = vec!["demo", "--frames", "2", "--out", dir.to_str().unwrap()];
        args.extend(extra);
        assert_success(&run(&args, None), "");
    }
}

#[test]
fn render_and_mesh_run() {
    let case = golden_case("seed_initial");
    let input = tmp("render-input.json");
    std::fs::write(&input, seed_input(&case)).unwrap();
    for (cmd, format) in [
        ("render", "png"),
        ("render", "svg"),
        ("render", "gif"),
        ("mesh", "obj"),
        ("mesh", "ply"),
    ] {
        let dir = tmp(&format!("{cmd}-{format}"));
        let extra = [
            "--input",
            input.to_str().unwrap(),
            "--format",
            format,
            "--out",
            dir.to_str().unwrap(),
        ];
        let out = run_seed(cmd, &extra, None);
        assert_success(&out, &format!("{cmd} {format}: "));
        assert!(String::from_utf8_lossy(&out.stdout).contains(&format!(".{format}")));
    }
}

#[test]
fn render_reports_bad_cases() {
    let mut case = golden_case("seed_initial");
    case["covs"][4][1][1] = json!(-1.0);
    let dir = tmp("render-bad");
    let out = run_seed(
        "render",
        &["--out", dir.to_str().unwrap()],
        Some(&seed_input(&case)),
    );
    assert_error_mentions(&out, &["case 0, joint 4"]);
}
