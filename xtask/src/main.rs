//! The project's task index: `cargo xtask <task> [args…]` (the alias is in
//! `.cargo/config.toml`). Each task is a thin wrapper over a script of `scripts/`, `.ci/run`,
//! a generator of `test_data/reference/` or a cargo command, run from the workspace root;
//! extra arguments go to that command and its exit status is the task's. The scripts stay
//! the single definition of each task (CI calls them directly); this file only names them.
//! Needs nothing beyond cargo (no `just`).
#![forbid(unsafe_code)]
#![deny(missing_docs)]

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

mod layers;
mod rust_paths;

/// One entry point: its name, what it runs and what it is for.
struct Task {
    name: &'static str,
    /// The program and its fixed arguments; paths are relative to the workspace root.
    command: &'static [&'static str],
    help: &'static str,
}

const TASKS: &[Task] = &[
    Task {
        name: "ci",
        command: &["bash", ".ci/run"],
        help: "the whole CI (fmt, clippy, tests, docs, dependency rule, thumb, demo, \
               firmware, fuzz smoke); CI_FAIL_FAST=1 stops at the first failure",
    },
    Task {
        name: "test",
        command: &["cargo", "test", "--workspace"],
        help:
            "every test of the workspace (CI's test step); e.g. `cargo xtask test -- --nocapture`",
    },
    Task {
        name: "thumb",
        command: &["bash", "scripts/thumb-check.sh"],
        help: "build the core crate for the four Cortex-M targets (installs the toolchain \
               if missing); --no-setup, --host-nostd, TARGET…",
    },
    Task {
        name: "firmware",
        command: &["bash", "scripts/firmware.sh"],
        help: "build examples/firmware for four Cortex-M cores, run it in QEMU, M4F \
               instruction count; --no-setup",
    },
    Task {
        name: "template",
        command: &["bash", "scripts/template-check.sh"],
        help: "build the firmware template (rustup's toolchain if it can add the target, \
               else Debian's), run it in QEMU, compare with the host; --no-setup",
    },
    Task {
        name: "setup-thumb",
        command: &["bash", "scripts/setup-thumb.sh"],
        help: "install what the bare-metal builds need (Debian's rustc-web, QEMU, Arm GCC, \
               cbindgen); --env, --no-install, --rustup TARGET",
    },
    Task {
        name: "deps-rule",
        command: &["bash", "scripts/deps-rule.sh"],
        help: "the core crate's direct normal dependencies are exactly approx, heapless, \
               libm and num-traits",
    },
    Task {
        name: "msrv",
        command: &["bash", "scripts/msrv.sh"],
        help: "build and test with the declared minimum Rust version (rust-version)",
    },
    Task {
        name: "publish-check",
        command: &["bash", "scripts/publish-check.sh"],
        help: "package every publishable crate and run the packaged core crate's tests",
    },
    Task {
        name: "features",
        command: &["bash", "scripts/features-check.sh"],
        help: "each optional feature of the core crate on its own, its tests, and the \
               no_std ones for thumbv7em",
    },
    Task {
        name: "demo",
        command: &["bash", "scripts/demo-check.sh"],
        help: "the README's main command (the seed example) end to end; its pictures exist",
    },
    Task {
        name: "html-check",
        command: &["bash", "scripts/html-check.sh"],
        help: "the HTML views in headless Chromium: the robot and the surface are drawn \
               (installs Chromium if missing)",
    },
    Task {
        name: "python",
        command: &["bash", "scripts/python-check.sh"],
        help: "the Python package: fresh venv, maturin wheel, its pytest suite and \
               pytransform3d 3.17.0's own uncertainty tests against it (needs PyPI)",
    },
    Task {
        name: "fuzz-smoke",
        command: &["bash", "scripts/fuzz-smoke.sh"],
        help: "every fuzz target from the seed corpus, 30 s each (FUZZ_SECONDS, \
               FUZZ_TARGETS, FUZZ_SEED, FUZZ_RUNS); CI runs it with FUZZ_SEED=1 \
               FUZZ_RUNS=100000",
    },
    Task {
        name: "fuzz-long",
        command: &["bash", "scripts/fuzz-long.sh"],
        help: "long fuzzing (1 h per target by default) with a line per target appended \
               to FUZZING.md",
    },
    Task {
        name: "bench-report",
        command: &["bash", "scripts/bench-report.sh"],
        help: "regenerate BENCHMARKS.md (criterion, pytransform3d baselines, callgrind, \
               firmware counts; 10-20 min; needs a quiet machine)",
    },
    Task {
        name: "bench-report-selftest",
        command: &["python3", "scripts/bench_report.py", "selftest"],
        help: "the bench report's parsers and renderers on made-up lines (a CI step; \
               no benchmark is run)",
    },
    Task {
        name: "accuracy",
        command: &["bash", "scripts/accuracy.sh"],
        help: "regenerate ACCURACY.md (Monte Carlo and f32-vs-f64 tables; --samples N)",
    },
    Task {
        name: "golden-core",
        command: &["bash", "test_data/reference/generate_core.sh"],
        help: "regenerate test_data/golden/core with pytransform3d 3.17.0 (venv in \
               /tmp/venv-oracle; needs PyPI)",
    },
    Task {
        name: "golden-ppoe",
        command: &[
            "bash",
            "-c",
            "set -e; python3 -m venv /tmp/venv-ppoe; \
             /tmp/venv-ppoe/bin/pip install -q -r test_data/reference/requirements-ppoe.txt; \
             /tmp/venv-ppoe/bin/python test_data/reference/generate_ppoe.py \"$@\"",
            "golden-ppoe",
        ],
        help: "regenerate test_data/golden/ppoe with pytransform3d 3.17.0 (venv in \
               /tmp/venv-ppoe; needs PyPI); --random N for smaller files",
    },
];

/// The workspace root: this crate's parent directory.
fn root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().unwrap_or(manifest).to_path_buf()
}

/// The tasks this crate runs itself (no script): name and help.
const BUILT_IN: &[(&str, &str)] = &[(
    "layers",
    "the core crate's module graph against ARCHITECTURE.md's layer table: no import \
     cycle, no layer using one below it; [SRC_DIR [ARCHITECTURE_MD]]",
)];

fn usage() -> String {
    let mut s = String::from("usage: cargo xtask <task> [args…]\n\ntasks:\n");
    for (name, help) in BUILT_IN {
        s += &format!("  {name:<13} {help}\n");
        s += &format!("  {:<13}   runs: built in (xtask/src/{name}.rs)\n", "");
    }
    for t in TASKS {
        s += &format!("  {:<13} {}\n", t.name, t.help);
        s += &format!("  {:<13}   runs: {}\n", "", t.command.join(" "));
    }
    s
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(name) = args.first() else {
        eprint!("{}", usage());
        return ExitCode::from(2);
    };
    if matches!(name.as_str(), "help" | "-h" | "--help" | "list") {
        print!("{}", usage());
        return ExitCode::SUCCESS;
    }
    if name == "layers" {
        return layers::run(&root(), &args[1..]);
    }
    let Some(task) = TASKS.iter().find(|t| t.name == name) else {
        eprint!("error: unknown task {name:?}\n\n{}", usage());
        return ExitCode::from(2);
    };
    let Some((program, fixed)) = task.command.split_first() else {
        eprintln!("xtask {name}: the task has no command");
        return ExitCode::FAILURE;
    };
    let status = Command::new(program)
        .args(fixed)
        .args(&args[1..])
        .current_dir(root())
        .status();
    match status {
        Ok(s) if s.success() => ExitCode::SUCCESS,
        Ok(s) => {
            eprintln!("xtask {name}: {} failed ({s})", task.command.join(" "));
            ExitCode::from(u8::try_from(s.code().unwrap_or(1)).unwrap_or(1).max(1))
        }
        Err(e) => {
            eprintln!("xtask {name}: cannot run {program}: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every script a task names exists, so a renamed script breaks this test, not a
    /// release day.
    #[test]
    fn every_task_runs_an_existing_file() {
        let root = root();
        let mut names = std::collections::HashSet::new();
        for t in TASKS {
            assert!(names.insert(t.name), "task {} listed twice", t.name);
            let files: Vec<&str> = t
                .command
                .iter()
                .flat_map(|a| a.split([' ', ';', '"']))
                .filter(|a| {
                    a.starts_with("scripts/")
                        || a.starts_with(".ci/")
                        || a.starts_with("test_data/")
                })
                .collect();
            assert!(
                !files.is_empty() || t.command[0] == "cargo",
                "task {} names no file",
                t.name
            );
            for f in files {
                assert!(
                    root.join(f).is_file(),
                    "task {}: {f} does not exist",
                    t.name
                );
            }
        }
        for wanted in [
            "ci",
            "test",
            "thumb",
            "firmware",
            "fuzz-smoke",
            "fuzz-long",
            "bench-report",
            "accuracy",
            "golden-core",
            "golden-ppoe",
        ] {
            assert!(names.contains(wanted), "no task {wanted}");
        }
    }

    /// Every script `.ci/run` calls is a task too, so what CI runs can be run alone by name.
    #[test]
    fn every_ci_script_is_a_task() {
        let ci = std::fs::read_to_string(root().join(".ci/run")).expect(".ci/run");
        let tasks: Vec<String> = TASKS.iter().map(|t| t.command.join(" ")).collect();
        let mut seen = 0;
        for word in ci.split(|c: char| c.is_whitespace() || c == '"') {
            let Some(script) = word.strip_prefix("$ROOT/") else {
                continue;
            };
            seen += 1;
            assert!(
                tasks.iter().any(|c| c.contains(script)),
                ".ci/run calls {script}, which no xtask task runs"
            );
        }
        assert!(
            seen >= 5,
            ".ci/run names only {seen} scripts: the parse is wrong"
        );
    }
}
