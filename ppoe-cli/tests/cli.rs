//! End-to-end tests of the `ppoe` command.

use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_ppoe");

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn seed_urdf() -> PathBuf {
    repo().join("test_data/urdf/seed.urdf")
}

fn tmp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("ppoe-cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn run(args: &[&str], stdin: Option<&str>) -> Output {
    let mut child = Command::new(BIN)
        .args(args)
        .current_dir(repo())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    {
        let mut i = child.stdin.take().unwrap();
        if let Some(s) = stdin {
            i.write_all(s.as_bytes()).unwrap();
        }
    }
    child.wait_with_output().unwrap()
}

/// Asserts failure with exactly one stderr line `error: ...`; returns that line.
fn assert_one_line_error(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "expected failure, stderr: {stderr}");
    assert_eq!(out.status.code(), Some(1), "stderr: {stderr}");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "expected one stderr line, got: {stderr:?}");
    assert!(lines[0].starts_with("error: "), "{stderr:?}");
    assert!(!stderr.contains("panicked"), "{stderr:?}");
    lines[0].to_string()
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
    let urdf = seed_urdf();
    let mut args = vec![
        "eval",
        "--urdf",
        urdf.to_str().unwrap(),
        "--base",
        "linkmount",
        "--tip",
        "tcp",
    ];
    args.extend_from_slice(extra);
    let out = run(&args, Some(input));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn eval_seed_initial_matches_golden_right() {
    let case = golden_case("seed_initial");
    let out = eval_seed(&["--convention", "ppoe"], &seed_input(&case));
    let r = &out["results"][0];
    assert!(rel_err(&matrix(&r["pose"]), &matrix(&case["pose"])) <= 1e-12);
    assert!(rel_err(&matrix(&r["cov"]), &matrix(&case["cov_right"])) <= 1e-12);
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
    assert!(rel_err(&matrix(&r["pose"]), &matrix(&case["pose"])) <= 1e-12);
    assert!(rel_err(&matrix(&r["cov"]), &matrix(&case["cov_pytransform3d"])) <= 1e-12);
    assert_eq!(r["thetas_clipped"], case["thetas_clipped"]);
}

#[test]
fn eval_left_convention_matches_golden() {
    let case = golden_case("seed_initial");
    let out = eval_seed(&["--convention", "left"], &seed_input(&case));
    let r = &out["results"][0];
    assert!(rel_err(&matrix(&r["cov"]), &matrix(&case["cov_left"])) <= 1e-12);
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
    assert!(rel_err(&matrix(&c["screw_axes"]), &matrix(&g["screw_axes"])) <= 1e-12);
    assert!(rel_err(&matrix(&c["home"]), &matrix(&g["home"])) <= 1e-12);
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
            assert!(
                rel_err(&matrix(&r["pose"]), &matrix(&c["pose"])) <= 1e-12,
                "{}",
                c["label"]
            );
            assert!(
                rel_err(&matrix(&r["cov"]), &matrix(&c[key])) <= 1e-12,
                "{} {conv}",
                c["label"]
            );
            if conv == "pytransform3d" {
                assert_eq!(r["thetas_clipped"], c["thetas_clipped"], "{}", c["label"]);
            }
        }
    }
}

#[test]
fn eval_f32_is_close() {
    let case = golden_case("seed_initial");
    let out = eval_seed(&["--scalar", "f32"], &seed_input(&case));
    let r = &out["results"][0];
    assert!(rel_err(&matrix(&r["pose"]), &matrix(&case["pose"])) <= 1e-5);
    assert!(rel_err(&matrix(&r["cov"]), &matrix(&case["cov_right"])) <= 1e-4);
}

#[test]
fn table_prints_const_and_sha256() {
    use sha2::Digest;
    let urdf = seed_urdf();
    let sha = sha2::Sha256::digest(std::fs::read(&urdf).unwrap());
    let sha: String = sha.iter().map(|b| format!("{b:02x}")).collect();
    let out = run(
        &[
            "table",
            "--urdf",
            urdf.to_str().unwrap(),
            "--base",
            "linkmount",
            "--tip",
            "tcp",
            "--scalar",
            "both",
            "--name",
            "ARM",
        ],
        None,
    );
    assert!(out.status.success());
    let src = String::from_utf8(out.stdout).unwrap();
    assert!(
        src.contains("pub const ARM: ppoe::chain::Chain<f64, 6>"),
        "{src}"
    );
    assert!(
        src.contains("pub const ARM_F32: ppoe::chain::Chain<f32, 6>"),
        "{src}"
    );
    assert!(src.contains(&sha), "{src}");
}

#[test]
fn table_with_explicit_joints() {
    let urdf = seed_urdf();
    let out = run(
        &[
            "table",
            "--urdf",
            urdf.to_str().unwrap(),
            "--base",
            "linkmount",
            "--tip",
            "tcp",
            "--joints",
            "joint1,joint2,joint3",
        ],
        None,
    );
    assert!(out.status.success());
    let src = String::from_utf8(out.stdout).unwrap();
    assert!(
        src.contains("pub const SEED: ppoe::chain::Chain<f64, 3>"),
        "{src}"
    );
}

#[test]
fn error_missing_urdf() {
    let line = assert_one_line_error(&run(
        &[
            "eval",
            "--urdf",
            "no/such.urdf",
            "--base",
            "a",
            "--tip",
            "b",
        ],
        Some("{}"),
    ));
    assert!(line.contains("no/such.urdf"), "{line}");
}

#[test]
fn error_missing_input_file() {
    let urdf = seed_urdf();
    let line = assert_one_line_error(&run(
        &[
            "eval",
            "--urdf",
            urdf.to_str().unwrap(),
            "--base",
            "linkmount",
            "--tip",
            "tcp",
            "--input",
            "no/such/cases.json",
        ],
        None,
    ));
    assert!(line.contains("cases.json"), "{line}");
}

fn eval_seed_err(input: &str) -> String {
    let urdf = seed_urdf();
    assert_one_line_error(&run(
        &[
            "eval",
            "--urdf",
            urdf.to_str().unwrap(),
            "--base",
            "linkmount",
            "--tip",
            "tcp",
        ],
        Some(input),
    ))
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
        let line = eval_seed_err(bad);
        assert!(line.contains("malformed input JSON"), "{bad}: {line}");
    }
    // A covariance that is not 6×6.
    let mut case = golden_case("seed_initial");
    case["covs"][1] = json!(vec![vec![0.0; 5]; 6]);
    let line = eval_seed_err(&seed_input(&case));
    assert!(line.contains("malformed input JSON"), "{line}");
}

#[test]
fn error_wrong_joint_count() {
    let line = eval_seed_err(r#"{"cases":[{"thetas":[0,0],"covs":[]}]}"#);
    assert!(
        line.contains("case 0") && line.contains("6 joints"),
        "{line}"
    );
    let mut case = golden_case("seed_initial");
    case["covs"].as_array_mut().unwrap().pop();
    let line = eval_seed_err(&seed_input(&case));
    assert!(line.contains("5 covariances"), "{line}");
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
    let line = eval_seed_err(&input);
    assert!(
        line.contains("case 3, joint 2") && line.contains("not positive semi-definite"),
        "{line}"
    );
    // Not symmetric.
    let mut asym = case.clone();
    asym["covs"][0][0][1] = json!(0.01);
    let line = eval_seed_err(&seed_input(&asym));
    assert!(
        line.contains("case 0, joint 0") && line.contains("symmetric"),
        "{line}"
    );
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
fn error_bad_command_lines_are_one_line() {
    for args in [
        vec![],
        vec!["frobnicate"],
        vec!["eval"],
        vec![
            "eval", "--urdf", "x", "--base", "a", "--tip", "b", "--scalar", "f16",
        ],
        vec!["demo", "--sigma", "1", "--probability", "0.5"],
        vec!["demo", "--probability", "1.5"],
        vec!["demo", "--sigma", "-1"],
        vec!["demo", "--frames", "0"],
    ] {
        assert_one_line_error(&run(&args, None));
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
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("ppoe-seed.png"), "{stdout}");
    assert!(stdout.contains("ppoe-seed.gif"), "{stdout}");
    assert!(stdout.contains("initial pose"), "{stdout}");
    // The printed initial pose is the golden one (to the printed precision).
    let t = golden_case("seed_initial")["pose"][0][3].as_f64().unwrap();
    assert!(stdout.contains(&format!("{t:.10e}")[..10]), "{stdout}");
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
        let out = run(&args, None);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn render_and_mesh_run() {
    let case = golden_case("seed_initial");
    let input = tmp("render-input.json");
    std::fs::write(&input, seed_input(&case)).unwrap();
    let urdf = seed_urdf();
    for (cmd, format) in [
        ("render", "png"),
        ("render", "svg"),
        ("render", "gif"),
        ("mesh", "obj"),
        ("mesh", "ply"),
    ] {
        let dir = tmp(&format!("{cmd}-{format}"));
        let out = run(
            &[
                cmd,
                "--urdf",
                urdf.to_str().unwrap(),
                "--base",
                "linkmount",
                "--tip",
                "tcp",
                "--input",
                input.to_str().unwrap(),
                "--format",
                format,
                "--out",
                dir.to_str().unwrap(),
            ],
            None,
        );
        assert!(
            out.status.success(),
            "{cmd} {format}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(String::from_utf8_lossy(&out.stdout).contains(&format!(".{format}")));
    }
}

#[test]
fn render_reports_bad_cases() {
    let mut case = golden_case("seed_initial");
    case["covs"][4][1][1] = json!(-1.0);
    let urdf = seed_urdf();
    let line = assert_one_line_error(&run(
        &[
            "render",
            "--urdf",
            urdf.to_str().unwrap(),
            "--base",
            "linkmount",
            "--tip",
            "tcp",
            "--out",
            tmp("render-bad").to_str().unwrap(),
        ],
        Some(&seed_input(&case)),
    ));
    assert!(line.contains("case 0, joint 4"), "{line}");
}
