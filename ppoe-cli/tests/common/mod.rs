//! Helpers shared by the command's test files: run the built `ppoe`, paths, the seed's
//! inputs.
#![allow(dead_code)] // each test file uses a part

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// The built command.
pub const BIN: &str = env!("CARGO_BIN_EXE_ppoe");

/// The repository root (the commands run there).
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A URDF of `test_data/urdf`.
pub fn urdf(name: &str) -> PathBuf {
    repo().join("test_data/urdf").join(name)
}

/// A fresh (emptied) directory for one test.
pub fn fresh_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("ppoe-cli-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `ppoe args` with `stdin` (bytes) and collects its output.
pub fn run_bytes(args: &[&str], stdin: &[u8]) -> Output {
    let mut child = Command::new(BIN)
        .args(args)
        .current_dir(repo())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut i = child.stdin.take().unwrap();
    // A command that fails before reading its input may exit first.
    match i.write_all(stdin) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        r => r.unwrap(),
    }
    drop(i);
    child.wait_with_output().unwrap()
}

/// Runs `ppoe args` with an empty standard input.
pub fn run(args: &[&str]) -> Output {
    run_bytes(args, b"")
}

/// Standard error as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts exit status `code` with exactly one stderr line `error: ...` (no panic);
/// returns that line.
pub fn one_line_error(out: &Output, code: i32) -> String {
    let text = stderr(out);
    assert_eq!(out.status.code(), Some(code), "stderr: {text}");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 1, "expected one stderr line, got: {text:?}");
    assert!(lines[0].starts_with("error: "), "{text:?}");
    assert!(!text.contains("panicked"), "{text:?}");
    lines[0].to_string()
}

/// Asserts success.
pub fn success(out: &Output) {
    assert!(out.status.success(), "stderr: {}", stderr(out));
    assert!(!stderr(out).contains("panicked"));
}

/// A 6×6 matrix with `d` on the diagonal.
pub fn diag(d: f64) -> serde_json::Value {
    let rows: Vec<Vec<f64>> = (0..6)
        .map(|i| (0..6).map(|j| if i == j { d } else { 0.0 }).collect())
        .collect();
    serde_json::json!(rows)
}

/// `n` seed cases (6 joints), joint values `0.1·k`, covariance `0.01·I` per joint.
pub fn seed_cases(n: usize) -> String {
    let cases: Vec<serde_json::Value> = (0..n)
        .map(
            |k| serde_json::json!({"thetas": vec![0.1 * k as f64; 6], "covs": vec![diag(0.01); 6]}),
        )
        .collect();
    serde_json::json!({ "cases": cases }).to_string()
}

/// The seed chain's arguments: `--urdf seed.urdf --base linkmount --tip tcp`.
pub fn seed_chain() -> Vec<String> {
    [
        "--urdf",
        urdf("seed.urdf").to_str().unwrap(),
        "--base",
        "linkmount",
        "--tip",
        "tcp",
    ]
    .map(String::from)
    .to_vec()
}

/// `ppoe cmd <seed chain> extra...` as owned arguments.
pub fn seed_args(cmd: &str, extra: &[&str]) -> Vec<String> {
    let mut a = vec![cmd.to_string()];
    a.extend(seed_chain());
    a.extend(extra.iter().map(|s| s.to_string()));
    a
}

/// Borrowed view of owned arguments.
pub fn refs(a: &[String]) -> Vec<&str> {
    a.iter().map(String::as_str).collect()
}
