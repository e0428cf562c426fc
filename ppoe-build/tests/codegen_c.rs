//! The C tables (`ppoe_build::codegen_c`) compile: an integration test, because it needs the
//! repository's `test_data/` and `ppoe-ffi/include/ppoe.h`, which the packaged crate does
//! not ship.

use ppoe_build::{Config, Scalar};

#[test]
fn compiles_as_c99() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let dir = std::env::temp_dir().join(format!("ppoe-codegen-c-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let robots = [
        ("seed", "linkmount", "tcp"),
        ("prismatic", "base_link", "tool0"),
        ("continuous", "base", "ee"),
        ("non_ascii", "basis_\u{e4}", "\"spitze\" \\ \u{1f527}"),
    ];
    for (file, base, tip) in robots {
        let mut cfg = Config::new(root.join(format!("test_data/urdf/{file}.urdf")));
        cfg.base(base).tip(tip).scalar(Scalar::Both).name("R");
        let header = cfg.generate_c().unwrap();
        std::fs::write(dir.join("table.h"), header).unwrap();
        let main = "#include \"table.h\"\nint f(void);\nint f(void) { return (int)R.n_joints \
                    + (int)R_F32.n_joints + (int)R_N_JOINTS; }\n";
        std::fs::write(dir.join("t.c"), main).unwrap();
        let out = std::process::Command::new("cc")
            .args([
                "-std=c99",
                "-Wall",
                "-Wextra",
                "-Werror",
                "-pedantic",
                "-fsyntax-only",
            ])
            .arg(format!("-I{}", root.join("ppoe-ffi/include").display()))
            .arg(dir.join("t.c"))
            .output()
            .expect("a C compiler (cc) on the PATH");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{file}: C99 compile failed:\n{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
