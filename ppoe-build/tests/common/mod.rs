//! Shared helpers of the ppoe-build integration tests: the test URDFs and rustfmt.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// Path of a file below `test_data/urdf/`.
pub fn urdf_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../test_data/urdf")
        .join(name)
}

pub fn rustfmt_available() -> bool {
    Command::new("rustfmt")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// `None` if `rustfmt --check --edition 2021` accepts `source` unchanged (which needs it to
/// parse), else its output. The file `{tag}.rs` is written to a temporary directory named
/// `{dir_prefix}-{pid}`, outside the workspace, so that no rustfmt.toml of ours applies: the
/// output is meant for rustfmt's defaults.
pub fn rustfmt_check(source: &str, dir_prefix: &str, tag: &str) -> Option<String> {
    let dir = std::env::temp_dir().join(format!("{dir_prefix}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{tag}.rs"));
    std::fs::write(&file, source).unwrap();
    let out = Command::new("rustfmt")
        .args(["--check", "--edition", "2021"])
        .arg(&file)
        .output()
        .expect("rustfmt runs");
    let _ = std::fs::remove_file(&file);
    (!out.status.success()).then(|| {
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    })
}

/// `Ok` if `cc -std={std} -Wall -Wextra -Werror -pedantic -fsyntax-only` accepts a C file
/// that includes `header` (with ppoe-ffi's `ppoe.h` on the include path) and `main_c`, else
/// the compiler's messages. The files go to a temporary directory `{tag}-{pid}`.
pub fn cc_syntax_check(header: &str, main_c: &str, std: &str, tag: &str) -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let dir = std::env::temp_dir().join(format!("{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("table.h"), header).unwrap();
    std::fs::write(dir.join("t.c"), format!("#include \"table.h\"\n{main_c}")).unwrap();
    let out = Command::new("cc")
        .arg(format!("-std={std}"))
        .args(["-Wall", "-Wextra", "-Werror", "-pedantic", "-fsyntax-only"])
        .arg(format!("-I{}", root.join("ppoe-ffi/include").display()))
        .arg(dir.join("t.c"))
        .output()
        .expect("a C compiler (cc) on the PATH");
    let _ = std::fs::remove_dir_all(&dir);
    if out.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&out.stderr).into_owned())
    }
}
