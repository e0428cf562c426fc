//! Inputs read once (issue class: inputs): a URDF or the cases from standard input (`-`)
//! or a pipe that can be read only once, a byte-order mark in JSON, I/O errors as
//! sentences naming the path.

mod common;
use common::*;
use std::path::Path;

/// `ppoe <cmd> --urdf /dev/stdin ...` with the URDF piped in: `/dev/stdin` is a pipe
/// here, so a second read of it finds nothing.
fn with_urdf_on_pipe(cmd: &str, urdf_arg: &str, extra: &[&str]) -> std::process::Output {
    let seed = std::fs::read(urdf("seed.urdf")).unwrap();
    let mut a = vec![
        cmd,
        "--urdf",
        urdf_arg,
        "--base",
        "linkmount",
        "--tip",
        "tcp",
    ];
    a.extend_from_slice(extra);
    run_bytes(&a, &seed)
}

#[test]
fn urdf_from_a_pipe_is_read_once_by_every_command() {
    let dir = fresh_dir("urdf-pipe");
    let cases = dir.join("cases.json");
    std::fs::write(&cases, seed_cases(2)).unwrap();
    let (c, d) = (cases.to_str().unwrap(), dir.to_str().unwrap());
    for urdf_arg in ["/dev/stdin", "-"] {
        for (cmd, extra) in [
            ("render", vec!["--input", c, "--grid", "4", "--out", d]),
            ("mesh", vec!["--input", c, "--grid", "4", "--out", d]),
            ("eval", vec!["--input", c]),
            ("table", vec![]),
        ] {
            let o = with_urdf_on_pipe(cmd, urdf_arg, &extra);
            success(&o);
        }
    }
    assert!(dir.join("ppoe-render-1.png").is_file());
    assert!(dir.join("ppoe-mesh-1.obj").is_file());
    // The same table as from the file (the sha256 of the same bytes).
    let from_file = run(&refs(&seed_args("table", &[])));
    let from_pipe = with_urdf_on_pipe("table", "/dev/stdin", &[]);
    let (f, p) = (
        String::from_utf8_lossy(&from_file.stdout),
        String::from_utf8_lossy(&from_pipe.stdout),
    );
    let sha = |s: &str| {
        s.lines()
            .find(|l| l.contains("SHA-256") || l.contains("sha256"))
            .map(str::to_string)
    };
    assert!(sha(&f).is_some(), "{f}");
    assert_eq!(sha(&f), sha(&p));
    // A pipe has no file name to name the table: the robot's name does.
    assert!(f.contains("pub const SEED: "), "{f}");
    assert!(
        p.contains("pub const SEED_ARM: ") && p.contains("from `pipe`"),
        "{p}"
    );
    // `links` too.
    let seed = std::fs::read(urdf("seed.urdf")).unwrap();
    let o = run_bytes(&["links", "--urdf", "-"], &seed);
    success(&o);
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("robot 'seed_arm'"));
}

#[test]
fn cases_from_standard_input_or_dash() {
    let input = seed_cases(1);
    let a = run_bytes(&refs(&seed_args("eval", &[])), input.as_bytes());
    let b = run_bytes(
        &refs(&seed_args("eval", &["--input", "-"])),
        input.as_bytes(),
    );
    success(&a);
    assert_eq!(a.stdout, b.stdout);
}

#[test]
fn two_inputs_on_standard_input_is_a_clear_error() {
    let line = one_line_error(
        &run(&["eval", "--urdf", "-", "--base", "a", "--tip", "b"]),
        1,
    );
    assert!(
        line.contains("cannot both come from standard input"),
        "{line}"
    );
}

#[test]
fn a_byte_order_mark_in_json_is_accepted() {
    let input = seed_cases(2);
    let plain = run_bytes(&refs(&seed_args("eval", &[])), input.as_bytes());
    let mut bom = "\u{feff}".as_bytes().to_vec();
    bom.extend_from_slice(input.as_bytes());
    let marked = run_bytes(&refs(&seed_args("eval", &[])), &bom);
    success(&plain);
    success(&marked);
    assert_eq!(plain.stdout, marked.stdout);
    // Not UTF-8 at all: an error with the offset, not a panic.
    let line = one_line_error(&run_bytes(&refs(&seed_args("eval", &[])), b"{\xff}"), 1);
    assert!(
        line.contains("not UTF-8") && line.contains("offset 1"),
        "{line}"
    );
}

#[test]
fn io_errors_are_sentences_with_the_path() {
    let dir = fresh_dir("io-errors");
    let d = dir.to_str().unwrap();
    for (args, says) in [
        (
            vec!["links", "--urdf", "no/such.urdf"],
            "cannot read the URDF file no/such.urdf: No such file or directory",
        ),
        (vec!["links", "--urdf", d], "it is a directory"),
        (
            vec![
                "table",
                "--urdf",
                "no/such.urdf",
                "--base",
                "a",
                "--tip",
                "b",
            ],
            "no/such.urdf: No such",
        ),
    ] {
        let line = one_line_error(&run(&args), 1);
        assert!(line.contains(says), "{line}");
        for debug in ["Os {", "kind:", "code:", "os error"] {
            assert!(!line.contains(debug), "{line}");
        }
    }
    let a = seed_args("eval", &["--input", "no/cases.json"]);
    let line = one_line_error(&run(&refs(&a)), 1);
    assert!(
        line.contains("cannot read the input file no/cases.json: No such file or directory"),
        "{line}"
    );
    // An unwritable output directory (a file in the way of its parent).
    std::fs::write(dir.join("file"), b"x").unwrap();
    let out = dir.join("file/sub");
    let a = seed_args("mesh", &["--out", out.to_str().unwrap()]);
    let line = one_line_error(&run_bytes(&refs(&a), seed_cases(1).as_bytes()), 1);
    assert!(
        line.contains("cannot create the output directory") && line.contains("file/sub"),
        "{line}"
    );
    assert!(!line.contains("os error"), "{line}");
}

/// A noise model for the seed robot's six joints (`0.001·k·I` for joint k), as `ppoe fit`
/// writes it.
fn seed_noise() -> String {
    let joints: Vec<serde_json::Value> = (1..=6)
        .map(|k| serde_json::json!({"name": format!("joint{k}"), "cov": diag(1e-3 * k as f64)}))
        .collect();
    serde_json::json!({"model": "full", "joints": joints}).to_string()
}

/// `{"cases":[{"thetas":…}]}` of two seed cases, without covariances.
fn seed_thetas() -> String {
    serde_json::json!({"cases": [{"thetas": vec![0.1; 6]}, {"thetas": vec![-0.3; 6]}]}).to_string()
}

#[test]
fn noise_from_standard_input_or_with_a_byte_order_mark() {
    let dir = fresh_dir("noise-stdin");
    let (noise, marked, cases) = (dir.join("n.json"), dir.join("bom.json"), dir.join("c.json"));
    std::fs::write(&noise, seed_noise()).unwrap();
    std::fs::write(&marked, format!("\u{feff}{}", seed_noise())).unwrap();
    std::fs::write(&cases, seed_thetas()).unwrap();
    let eval = |noise: &Path, stdin: &[u8]| {
        let extra = [
            "--input",
            cases.to_str().unwrap(),
            "--noise",
            noise.to_str().unwrap(),
        ];
        run_bytes(&refs(&seed_args("eval", &extra)), stdin)
    };
    let from_file = eval(&noise, b"");
    success(&from_file);
    let from_stdin = eval(Path::new("-"), seed_noise().as_bytes());
    success(&from_stdin);
    let from_marked = eval(&marked, b"");
    success(&from_marked);
    assert_eq!(from_stdin.stdout, from_file.stdout);
    assert_eq!(from_marked.stdout, from_file.stdout);
    // The covariances are the model's, not none: the tool covariance is not zero.
    let v: serde_json::Value = serde_json::from_slice(&from_file.stdout).unwrap();
    assert_eq!(v["results"].as_array().unwrap().len(), 2);
    assert!(v["results"][0]["cov"][0][0].as_f64().unwrap() > 0.0, "{v}");
    // `table --noise -` too.
    let table = |noise: &str, stdin: &[u8]| {
        run_bytes(&refs(&seed_args("table", &["--noise", noise])), stdin)
    };
    let t_file = table(noise.to_str().unwrap(), b"");
    let t_stdin = table("-", seed_noise().as_bytes());
    success(&t_file);
    success(&t_stdin);
    let text = String::from_utf8(t_stdin.stdout).unwrap();
    assert!(text.contains("SEED_NOISE"), "{text}");
    // The same items; only the file name in the doc comment says where they came from.
    let file_text = String::from_utf8(t_file.stdout).unwrap();
    assert!(file_text.contains("n.json"), "{file_text}");
    assert_eq!(text.replace("stdin", "n.json"), file_text);
}

#[test]
fn noise_and_another_input_on_standard_input_is_a_clear_error() {
    let line = one_line_error(&run(&refs(&seed_args("eval", &["--noise", "-"]))), 1);
    assert!(
        line.contains("the input cases and the noise model cannot both come from standard input"),
        "{line}"
    );
    let chain = [
        "--base",
        "linkmount",
        "--tip",
        "tcp",
        "--noise",
        "-",
        "--urdf",
        "-",
    ];
    for cmd in ["table", "render", "mesh"] {
        let mut args = vec![cmd];
        args.extend(chain);
        if cmd != "table" {
            args.extend(["--input", "cases.json"]);
        }
        let line = one_line_error(&run(&args), 1);
        assert!(
            line.contains("the URDF and the noise model cannot both come from standard input"),
            "{cmd}: {line}"
        );
    }
}

/// A xacro file given as `--urdf` (issue #30): the one error line ends with the command
/// that expands it, by file name, by content, and from standard input.
#[test]
fn a_xacro_input_gets_the_hint_to_expand_it() {
    let dir = fresh_dir("xacro-input");
    let text = "<robot name=\"arm\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\
                <xacro:include filename=\"arm.xacro\"/></robot>";
    let file = dir.join("arm.urdf.xacro");
    std::fs::write(&file, text).unwrap();
    let f = file.to_str().unwrap();
    let args = [
        "table",
        "--urdf",
        f,
        "--base",
        "base_link",
        "--tip",
        "tool0",
    ];
    let e = one_line_error(&run(&args), 1);
    let expanded = dir.join("arm.urdf");
    assert!(e.contains("base link 'base_link' does not exist"), "{e}");
    assert!(
        e.ends_with(&format!("(run: xacro {f} > {})", expanded.display())),
        "{e}"
    );
    let args = [
        "table",
        "--urdf",
        "-",
        "--base",
        "base_link",
        "--tip",
        "tool0",
    ];
    let e = one_line_error(&run_bytes(&args, text.as_bytes()), 1);
    assert!(
        e.ends_with("(run: xacro robot.urdf.xacro > robot.urdf)"),
        "{e}"
    );
    // An ordinary unknown link: no hint.
    let seed = urdf("seed.urdf");
    let args = [
        "table",
        "--urdf",
        seed.to_str().unwrap(),
        "--base",
        "nope",
        "--tip",
        "tcp",
    ];
    assert!(!one_line_error(&run(&args), 1).contains("xacro"));
}
