//! How a person meets the command (issue class: usage): a bare `ppoe` prints help, usage
//! errors exit 2 and input errors 1, `--help` states exit codes and value ranges,
//! negative numbers reach the range checks, shell completions.

mod common;
use common::*;

#[test]
fn bare_ppoe_prints_help_with_status_2() {
    let o = run(&[]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(err.contains("Usage: ppoe <COMMAND>"), "{err}");
    assert!(
        err.contains("links") && err.contains("completions"),
        "{err}"
    );
}

#[test]
fn usage_errors_exit_2_on_one_line() {
    for args in [
        vec!["frobnicate"],
        vec!["eval"],
        vec![
            "eval", "--urdf", "x", "--base", "a", "--tip", "b", "--scalar", "f16",
        ],
        vec!["demo", "--sigma", "1", "--probability", "0.5"],
        vec!["demo", "--probability", "1.5"],
        vec!["demo", "--frames", "0"],
        vec!["demo", "--grid", "401"],
        vec!["completions", "tcsh"],
    ] {
        let line = one_line_error(&run(&args), 2);
        assert!(line.ends_with("(see --help)"), "{args:?}: {line}");
    }
}

#[test]
fn negative_values_reach_the_range_check() {
    for (args, says) in [
        (vec!["demo", "--sigma", "-1"], "positive finite number"),
        (vec!["demo", "--sigma=-0.5"], "positive finite number"),
        (
            vec!["demo", "--probability", "-0.1"],
            "strictly between 0 and 1",
        ),
        (vec!["demo", "--sigma", "nan"], "positive finite number"),
    ] {
        let line = one_line_error(&run(&args), 2);
        assert!(line.contains(says), "{args:?}: {line}");
        assert!(!line.contains("unexpected argument"), "{line}");
    }
}

#[test]
fn input_errors_exit_1() {
    let line = one_line_error(&run(&refs(&seed_args("eval", &[]))), 1);
    assert!(line.contains("standard input"), "{line}");
    let line = one_line_error(&run(&["links", "--urdf", "no/such.urdf"]), 1);
    assert!(line.contains("no/such.urdf"), "{line}");
}

#[test]
fn help_states_exit_codes_and_ranges() {
    let o = run(&["--help"]);
    success(&o);
    let top = String::from_utf8_lossy(&o.stdout);
    assert!(
        top.contains("Exit status: 0") && top.contains("2 for a usage error"),
        "{top}"
    );
    for cmd in [
        "table",
        "eval",
        "demo",
        "render",
        "mesh",
        "links",
        "completions",
    ] {
        let o = run(&[cmd, "--help"]);
        success(&o);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains("Exit status: 0 success; 1 "), "{cmd}: {text}");
    }
    let demo = String::from_utf8_lossy(&run(&["demo", "--help"]).stdout).into_owned();
    for range in ["(2 to 400)", "1 to 10000", "0 < P < 1", "positive"] {
        assert!(demo.contains(range), "{range}: {demo}");
    }
}

#[test]
fn completions_for_every_shell() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let o = run(&["completions", shell]);
        success(&o);
        let script = String::from_utf8_lossy(&o.stdout);
        for word in ["ppoe", "links", "urdf", "probability"] {
            assert!(script.contains(word), "{shell}: {word}");
        }
    }
}

#[test]
fn bash_accepts_the_bash_completion() {
    let o = run(&["completions", "bash"]);
    success(&o);
    let Ok(check) = std::process::Command::new("bash")
        .arg("-n")
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::null())
        .spawn()
    else {
        return; // no bash here
    };
    let mut check = check;
    {
        use std::io::Write;
        check.stdin.take().unwrap().write_all(&o.stdout).unwrap();
    }
    assert!(
        check.wait().unwrap().success(),
        "bash -n rejects the script"
    );
}
