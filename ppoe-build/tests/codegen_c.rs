//! The C tables (`ppoe_build::codegen_c`) compile: an integration test, because it needs the
//! repository's `test_data/` and `ppoe-ffi/include/ppoe.h`, which the packaged crate does
//! not ship.

mod common;

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

/// The chain of the seed robot with its joints repeated to `n` joints (names made unique).
fn seed_with_joints(n: usize) -> ppoe_build::RobotChain {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let bytes = std::fs::read(root.join("test_data/urdf/seed.urdf")).unwrap();
    let mut chain = ppoe_build::Urdf::parse_bytes(&bytes)
        .unwrap()
        .chain::<&str>("linkmount", "tcp", None)
        .unwrap();
    let joints = chain.joints.clone();
    chain.joints = (0..n)
        .map(|i| {
            let mut j = joints[i % joints.len()].clone();
            j.name = format!("j{i}");
            j
        })
        .collect();
    chain
}

fn source() -> ppoe_build::Source {
    ppoe_build::Source {
        file_name: "seed.urdf".into(),
        sha256: "0".repeat(64),
    }
}

#[test]
fn c_api_max_joints_is_the_headers() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let header = std::fs::read_to_string(root.join("ppoe-ffi/include/ppoe.h")).unwrap();
    let value = header
        .lines()
        .find_map(|l| l.strip_prefix("#define PPOE_MAX_JOINTS "))
        .expect("ppoe.h defines PPOE_MAX_JOINTS");
    assert_eq!(
        value.trim().parse::<usize>().unwrap(),
        ppoe_build::codegen_c::C_API_MAX_JOINTS
    );
    // No identifier of ppoe.h is in the table's include-guard namespace, and every one is
    // in the namespace c_names refuses.
    assert!(!header.contains("PPOE_TABLE_"));
    for word in header.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')) {
        if word.to_ascii_lowercase().starts_with("ppoe") && word.len() > 5 {
            assert!(word.to_ascii_lowercase().starts_with("ppoe_"), "{word}");
        }
    }
}

#[test]
fn c_table_format_is_the_headers() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let header = std::fs::read_to_string(root.join("ppoe-ffi/include/ppoe.h")).unwrap();
    let value = header
        .lines()
        .find_map(|l| l.strip_prefix("#define PPOE_C_TABLE_FORMAT "))
        .expect("ppoe.h defines PPOE_C_TABLE_FORMAT");
    assert_eq!(
        value.trim().parse::<u32>().unwrap(),
        ppoe_build::codegen_c::C_TABLE_FORMAT
    );
}

/// A table compiled against a ppoe.h of another table format, or one without the macro,
/// stops at its `#error`, which names the cause; the repository's header compiles
/// (`compiles_as_c99`).
#[test]
fn a_table_refuses_a_header_of_another_format() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let real = std::fs::read_to_string(root.join("ppoe-ffi/include/ppoe.h")).unwrap();
    let want = ppoe_build::codegen_c::C_TABLE_FORMAT;
    let line = format!("#define PPOE_C_TABLE_FORMAT {want}");
    assert!(real.contains(&line));
    let dir = std::env::temp_dir().join(format!("ppoe-codegen-c-fmt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut cfg = Config::new(root.join("test_data/urdf/seed.urdf"));
    cfg.base("linkmount").tip("tcp").name("R");
    std::fs::write(dir.join("table.h"), cfg.generate_c().unwrap()).unwrap();
    std::fs::write(dir.join("t.c"), "#include \"table.h\"\nint x;\n").unwrap();
    let other = format!("#define PPOE_C_TABLE_FORMAT {}", want + 1);
    for header in [real.replace(&line, &other), real.replace(&line, "")] {
        std::fs::write(dir.join("ppoe.h"), header).unwrap();
        let out = std::process::Command::new("cc")
            .args(["-std=c99", "-fsyntax-only"])
            .arg(format!("-I{}", dir.display()))
            .arg(dir.join("t.c"))
            .output()
            .expect("a C compiler (cc) on the PATH");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "compiled against another format");
        assert!(
            err.contains("generated by ppoe-build for C table format"),
            "{err}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn chains_longer_than_the_c_api_takes_are_refused() {
    use ppoe_build::codegen_c::{generate, C_API_MAX_JOINTS};
    let max = C_API_MAX_JOINTS;
    let ok = generate(&seed_with_joints(max), "R", Scalar::Both, &source()).unwrap();
    let main = "int f(void);\nint f(void) { return (int)R.n_joints; }\n";
    common::cc_syntax_check(&ok, main, "c99", "ppoe-max-joints").unwrap();
    let e = generate(&seed_with_joints(max + 1), "R", Scalar::F64, &source()).unwrap_err();
    assert_eq!(e.kind(), ppoe_build::ErrorKind::Config);
    let m = e.message();
    assert!(m.contains(&format!("has {} moving joints", max + 1)), "{m}");
    assert!(m.contains(&format!("at most {max}")), "{m}");
    // The Rust core has no maximum: the same chain is a Rust table.
    let rust =
        ppoe_build::codegen::generate(&seed_with_joints(max + 4), "R", Scalar::F64, &source());
    assert!(rust.is_ok());
}

#[test]
fn names_that_collide_in_c_are_refused_naming_them() {
    let chain = seed_with_joints(2);
    for bad in [
        "_Bool", "bool", "NULL", "PPOE_OK", "offsetof", "INFINITY", "sin", "int8_t", "A_", "__x",
    ] {
        let e = ppoe_build::codegen_c::generate(&chain, bad, Scalar::F64, &source()).unwrap_err();
        assert_eq!(e.kind(), ppoe_build::ErrorKind::Config, "{bad}");
        assert!(e.message().contains(&format!("{bad:?}")), "{bad}: {e}");
        // The same names are fine in Rust, where they do not collide.
        if !bad.starts_with('_') && bad != "bool" {
            assert!(
                ppoe_build::codegen::generate(&chain, bad, Scalar::F64, &source()).is_ok(),
                "{bad}"
            );
        }
    }
}
