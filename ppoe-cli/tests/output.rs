//! Output robustness (issue class: output): a closed or full standard output, files
//! written atomically, outputs checked before any computation. (Bounded animation
//! memory: tests/stream_memory.rs.)

mod common;
use common::*;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Runs `ppoe args` with standard output closed by its reader before the command writes.
fn run_with_closed_stdout(args: &[&str], stdin: &[u8]) -> std::process::Output {
    use std::io::Write;
    let mut child = Command::new(BIN)
        .args(args)
        .current_dir(repo())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader goes away, as `| head -0` does
    let mut i = child.stdin.take().unwrap();
    let _ = i.write_all(stdin);
    drop(i);
    child.wait_with_output().unwrap()
}

#[test]
fn every_command_survives_a_closed_stdout() {
    let dir = fresh_dir("closed-stdout");
    let out = dir.to_str().unwrap();
    let input = seed_cases(2);
    let commands: Vec<Vec<String>> = vec![
        vec!["demo", "--frames", "2", "--grid", "4", "--out", out]
            .into_iter()
            .map(String::from)
            .collect(),
        seed_args("render", &["--grid", "4", "--out", out]),
        seed_args("render", &["--grid", "4", "--format", "svg", "--out", out]),
        seed_args("mesh", &["--grid", "4", "--out", out]),
        seed_args("eval", &[]),
        seed_args("table", &[]),
        vec![
            "links".into(),
            "--urdf".into(),
            urdf("tree.urdf").display().to_string(),
        ],
        vec!["completions".into(), "bash".into()],
    ];
    for args in &commands {
        let o = run_with_closed_stdout(&refs(args), input.as_bytes());
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        // Progress lines may go to stderr; an error or a panic may not.
        let e = stderr(&o);
        let only_progress = e.lines().all(|l| l.starts_with("rendering "));
        assert!(only_progress, "{args:?}: {e}");
    }
    // The files are still written: standard output only carried the log.
    for f in [
        "ppoe-seed.png",
        "ppoe-seed.gif",
        "ppoe-render-1.png",
        "ppoe-render-1.svg",
    ] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    assert!(dir.join("ppoe-mesh-1.obj").is_file());
}

#[test]
fn a_full_stdout_is_an_error_naming_it() {
    let Ok(full) = std::fs::File::create("/dev/full") else {
        return; // no /dev/full on this system
    };
    let o = Command::new(BIN)
        .args(refs(&seed_args("table", &[])))
        .current_dir(repo())
        .stdout(full)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    let line = one_line_error(&o, 1);
    assert!(
        line.contains("cannot write to standard output: No space left on device"),
        "{line}"
    );
}

#[test]
fn an_interrupted_write_keeps_the_previous_file() {
    let dir = fresh_dir("interrupted");
    let target = dir.join("ppoe-render.gif");
    std::fs::write(&target, b"the previous good file").unwrap();
    let a = seed_args(
        "render",
        &[
            "--format",
            "gif",
            "--grid",
            "30",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    let mut child = Command::new(BIN)
        .args(refs(&a))
        .current_dir(repo())
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    {
        use std::io::Write;
        let mut i = child.stdin.take().unwrap();
        i.write_all(seed_cases(60).as_bytes()).unwrap();
    }
    // Kill the command (as Ctrl-C would) once the GIF is being written: a temporary file
    // has content, or (a writer in place) the target changed.
    let previous = b"the previous good file".len() as u64;
    let start = Instant::now();
    loop {
        let writing = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(Result::ok)
            .any(|e| e.metadata().is_ok_and(|m| m.len() > 0) && e.path() != target);
        let changed = std::fs::metadata(&target).map_or(true, |m| m.len() != previous);
        if writing || changed {
            break;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "finished before it was interrupted"
        );
        assert!(start.elapsed() < Duration::from_secs(600));
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    // Only hidden temporaries besides the target.
    for e in std::fs::read_dir(&dir).unwrap().filter_map(Result::ok) {
        let name = e.file_name().into_string().unwrap();
        assert!(
            name == "ppoe-render.gif" || name.starts_with(".ppoe-tmp-"),
            "{name}"
        );
    }
    assert_eq!(std::fs::read(&target).unwrap(), b"the previous good file");
}

#[test]
fn outputs_are_checked_before_any_computation() {
    let dir = fresh_dir("checked-first");
    // A regular file as the output directory.
    let file = dir.join("not-a-dir");
    std::fs::write(&file, b"x").unwrap();
    // Case 0 is invalid (a negative variance): an error about it would mean the cases
    // were computed before the outputs were checked.
    let mut bad = seed_cases(1).replace("0.01", "-1");
    for (cmd, extra) in [
        ("render", vec![]),
        ("render", vec!["--format", "gif"]),
        ("mesh", vec![]),
    ] {
        let mut e = extra.clone();
        e.extend(["--out", file.to_str().unwrap()]);
        let o = run_bytes(&refs(&seed_args(cmd, &e)), bad.as_bytes());
        let line = one_line_error(&o, 1);
        assert!(
            line.contains("not-a-dir") && line.contains("not a directory"),
            "{line}"
        );
    }
    // A directory where an output file goes.
    std::fs::create_dir_all(dir.join("ppoe-mesh-0.obj")).unwrap();
    let o = run_bytes(
        &refs(&seed_args("mesh", &["--out", dir.to_str().unwrap()])),
        bad.as_bytes(),
    );
    let line = one_line_error(&o, 1);
    assert!(
        line.contains("ppoe-mesh-0.obj: it is a directory"),
        "{line}"
    );
    bad.clear();
    let o = run(&["demo", "--out", file.to_str().unwrap()]);
    assert!(one_line_error(&o, 1).contains("not a directory"));
}
