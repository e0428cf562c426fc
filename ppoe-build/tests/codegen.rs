//! Generated source: deterministic, documented, and accepted by `rustfmt --check` as it is
//! (the items are `#[rustfmt::skip]`; checked when rustfmt is installed, skipped otherwise).

use ppoe_build::codegen::{self, Source};
use ppoe_build::{ChainJoint, Config, ErrorKind, JointKind, RobotChain, Scalar};

mod common;
use common::{rustfmt_available, rustfmt_check, urdf_path};

/// The requests of the golden files, plus a few more.
const CHAINS: &[(&str, &str, &str)] = &[
    ("seed.urdf", "linkmount", "tcp"),
    ("continuous.urdf", "base", "ee"),
    ("fixed_between.urdf", "world", "tool_tip"),
    ("prismatic.urdf", "base_link", "tool0"),
    ("rpy_everywhere.urdf", "base", "tool"),
    ("rpy_everywhere.urdf", "link2", "tool"),
    ("tree.urdf", "base_footprint", "left_tip"),
    ("tree.urdf", "base_footprint", "right_tip"),
];

/// `None` if rustfmt accepts `source` unchanged, else its diff.
fn rustfmt_diff(source: &str, tag: &str) -> Option<String> {
    rustfmt_check(source, "ppoe-build-fmt", tag)
}

#[test]
fn generated_tables_are_rustfmt_clean() {
    if !rustfmt_available() {
        eprintln!("note: rustfmt not found, skipping the formatting check");
        return;
    }
    // The check is not vacuous: rustfmt does flag unformatted code.
    assert!(rustfmt_diff("pub const X: u8=1;\n", "unformatted").is_some());
    for (file, base, tip) in CHAINS {
        let path = urdf_path(file);
        if !path.exists() {
            continue;
        }
        let source = Config::new(&path)
            .base(*base)
            .tip(*tip)
            .scalar(Scalar::Both)
            .name("ROBOT")
            .generate()
            .unwrap();
        if let Some(diff) = rustfmt_diff(&source, &format!("{base}_{tip}")) {
            panic!("{file} {base}->{tip}: not rustfmt-clean:\n{diff}");
        }
    }
}

/// A small deterministic generator (xorshift) for synthetic chains.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    /// Values whose printed form has very different lengths.
    fn value(&mut self) -> f64 {
        let u = (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        match self.below(8) {
            0 => 0.0,
            1 => 1.0,
            2 => -0.5,
            3 => (u * 1000.0).round() / 1000.0,
            4 => -(u * 1e8).round() / 1e8,
            5 => u * 1e-20,
            6 => -u * 1e20,
            _ => u - 0.5,
        }
    }
    fn limit(&mut self, lower: bool) -> f64 {
        match self.below(4) {
            0 if lower => f64::NEG_INFINITY,
            0 => f64::INFINITY,
            // Beyond f32 on the unbounded side (a huge lower bound would leave no finite
            // f32 position, an InvalidLimits error).
            1 if lower => -1e300,
            1 => 1e300,
            _ => self.value(),
        }
    }
}

fn synthetic(rng: &mut Rng, n: usize, name_len: usize) -> RobotChain {
    let name = |rng: &mut Rng, len: usize| -> String {
        (0..len.max(1))
            .map(|_| (b'a' + rng.below(26) as u8) as char)
            .collect()
    };
    let joints = (0..n)
        .map(|_| {
            let kind = match rng.below(3) {
                0 => JointKind::Revolute,
                1 => JointKind::Continuous,
                _ => JointKind::Prismatic,
            };
            let mut screw = [0.0; 6];
            for x in &mut screw {
                *x = rng.value();
            }
            let len = 1 + rng.below(name_len as u64 + 1) as usize;
            ChainJoint {
                name: name(rng, len),
                kind,
                screw,
                lower: rng.limit(true),
                upper: rng.limit(false),
                // Not part of a table.
                home_frame: [[0.0; 4]; 4],
            }
        })
        .collect();
    let mut home = [[0.0; 4]; 4];
    for row in &mut home[..3] {
        for x in row.iter_mut() {
            *x = rng.value();
        }
    }
    home[3][3] = 1.0;
    RobotChain {
        robot: "synthetic".into(),
        base: name(rng, name_len),
        tip: name(rng, name_len),
        joints,
        home,
        coupling: None,
    }
}

#[test]
fn synthetic_tables_are_rustfmt_clean() {
    if !rustfmt_available() {
        eprintln!("note: rustfmt not found, skipping the formatting check");
        return;
    }
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let source = Source {
        file_name: "synthetic.urdf".into(),
        sha256: codegen::sha256_hex(b"synthetic"),
    };
    // Batch many items into a few files (rustfmt runs are slow).
    let const_names = [
        "A",
        "SEED",
        "A_RATHER_LONG_CONST_NAME_FOR_THE_TABLE",
        &"N".repeat(48),
    ];
    for batch in 0..6 {
        let mut all = String::new();
        let mut k = 0;
        for n in [0usize, 1, 1, 2, 3, 6, 7] {
            for name_len in [1usize, 8, 30, 70] {
                let chain = synthetic(&mut rng, n, name_len);
                let stem = const_names[(k + batch) % const_names.len()];
                let const_name: String = format!("T{k}_{stem}").chars().take(48).collect();
                let text = codegen::generate(&chain, &const_name, Scalar::Both, &source).unwrap();
                if !all.is_empty() {
                    all.push('\n');
                }
                all.push_str(&text);
                k += 1;
            }
        }
        // Each table alone and the concatenation are formatted.
        if let Some(diff) = rustfmt_diff(&all, &format!("synthetic{batch}")) {
            panic!("synthetic batch {batch}: not rustfmt-clean:\n{diff}");
        }
    }
}

#[test]
fn output_is_deterministic_documented_and_portable() {
    let path = urdf_path("seed.urdf");
    let mut config = Config::new(&path);
    config.base("linkmount").tip("tcp").scalar(Scalar::Both);
    let a = config.generate().unwrap();
    let b = config.generate().unwrap();
    assert_eq!(a, b);
    // The format guard, once, right after the header line, naming the core's format.
    let guard = format!(
        "const _: () = assert!(ppoe::TABLE_FORMAT == {}, ",
        ppoe::TABLE_FORMAT
    );
    assert!(a.lines().nth(1).unwrap().starts_with(&guard), "{a}");
    assert_eq!(a.matches("ppoe::TABLE_FORMAT").count(), 1);
    // Default name from the file stem; the f32 table is NAME_F32.
    assert!(a.contains("pub const SEED: ppoe::chain::Chain<f64, 6> = ppoe::chain::Chain::new("));
    assert!(a.contains("pub const SEED_F32: ppoe::chain::Chain<f32, 6> = ppoe::chain::Chain::new("));
    // The doc comment: file name, sha256, base, tip, joints.
    let sha = codegen::sha256_hex(&std::fs::read(&path).unwrap());
    assert!(a.contains(&format!("/// sha256 `{sha}`.")));
    assert!(a.contains("from `seed.urdf`"));
    assert!(a.contains("/// * base: `linkmount`"));
    assert!(a.contains("/// * tip: `tcp`"));
    for j in 1..=6 {
        assert!(a.contains(&format!("`joint{j}` (revolute")));
    }
    // No directory in the output (it must not depend on the checkout location).
    let dir = path.parent().unwrap().to_string_lossy().into_owned();
    assert!(!a.contains(&dir));
    // Unbounded limits.
    assert!(a.contains("f64::INFINITY") && a.contains("f64::NEG_INFINITY"));
    assert!(a.contains("f32::INFINITY") && a.contains("f32::NEG_INFINITY"));

    // Only the requested tables.
    let f64_only = Config::new(&path)
        .base("linkmount")
        .tip("tcp")
        .name("ARM")
        .generate()
        .unwrap();
    assert!(f64_only.contains("pub const ARM: ppoe::chain::Chain<f64, 6>"));
    assert!(!f64_only.contains("f32"));
    let f32_only = Config::new(&path)
        .base("linkmount")
        .tip("tcp")
        .name("ARM")
        .scalar(Scalar::F32)
        .generate()
        .unwrap();
    assert!(f32_only.contains("pub const ARM_F32: ppoe::chain::Chain<f32, 6>"));
    assert!(!f32_only.contains("Chain<f64"));
}

#[test]
fn every_f64_value_is_written_in_round_trip_form() {
    let chain = Config::new(urdf_path("rpy_everywhere.urdf"))
        .base("base")
        .tip("tool")
        .chain()
        .unwrap();
    let source = Source {
        file_name: "x.urdf".into(),
        sha256: "0".repeat(64),
    };
    let text = codegen::generate(&chain, "X", Scalar::F64, &source).unwrap();
    // The literals, in order, parse back to the chain's values bit for bit (after the
    // header comment and the format guard, whose number is the format's).
    assert_eq!(text.lines().nth(1), Some(codegen::format_guard().as_str()));
    let code: String = text
        .lines()
        .skip(2)
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n");
    let mut values = Vec::new();
    for token in code.split(|c: char| c == ',' || c == '[' || c == ']' || c.is_whitespace()) {
        let t = token.trim_end_matches([')', ';', '>']);
        if t == "f64::INFINITY" {
            values.push(f64::INFINITY);
        } else if t == "f64::NEG_INFINITY" {
            values.push(f64::NEG_INFINITY);
        } else if t.starts_with(|c: char| c.is_ascii_digit() || c == '-') {
            values.push(t.parse::<f64>().unwrap_or_else(|_| panic!("{t}")));
        }
    }
    let mut expected = Vec::new();
    for j in &chain.joints {
        expected.extend_from_slice(&j.screw);
        expected.push(j.lower);
        expected.push(j.upper);
        // The displacement constants, as `Joint::from_f64` computes them at run time.
        let raw = ppoe::chain::Joint::new("", j.kind, j.screw, j.lower, j.upper);
        if let Some(k) = ppoe::chain::Joint::<f64>::from_f64(&raw).constants() {
            expected.push(k.scale);
            for a in [
                k.axis,
                k.axis_sq,
                k.axis_prod,
                k.v,
                k.axis_cross_v,
                k.axial_v,
            ] {
                expected.extend_from_slice(&a);
            }
        }
    }
    for row in &chain.home[..3] {
        expected.extend_from_slice(&row[..3]);
    }
    for row in &chain.home[..3] {
        expected.push(row[3]);
    }
    // The `N` of `Chain<f64, N>` comes first.
    assert_eq!(values[0], chain.joints.len() as f64);
    let values = &values[1..];
    assert_eq!(values.len(), expected.len());
    for (a, b) in values.iter().zip(&expected) {
        assert_eq!(a.to_bits(), b.to_bits(), "{a:?} vs {b:?}");
    }
}

#[test]
fn bad_names_and_missing_links_are_config_errors() {
    let path = urdf_path("seed.urdf");
    let err = Config::new(&path)
        .base("linkmount")
        .tip("tcp")
        .name("not-an-ident")
        .generate()
        .unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Config);
    let err = Config::new(&path).base("linkmount").chain().unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Config);
    let err = Config::new(urdf_path("no_such_file.urdf"))
        .base("a")
        .tip("b")
        .chain()
        .unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Io);
    assert!(err.to_string().contains("no_such_file.urdf"));
    assert_eq!("f32".parse::<Scalar>().unwrap(), Scalar::F32);
    assert_eq!("both".parse::<Scalar>().unwrap(), Scalar::Both);
    assert_eq!(
        "f16".parse::<Scalar>().unwrap_err().kind(),
        ErrorKind::Config
    );
}

#[test]
fn write_to_out_dir_writes_the_generated_file() {
    let dir = std::env::temp_dir().join(format!("ppoe-build-out-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut config = Config::new(urdf_path("seed.urdf"));
    config.base("linkmount").tip("tcp").scalar(Scalar::F32);
    let target = dir.join("seed_table.rs");
    config.write_to(&target).unwrap();
    assert_eq!(
        std::fs::read_to_string(&target).unwrap(),
        config.generate().unwrap()
    );
    // Unchanged content: the file is left alone (its mtime would not change).
    config.write_to(&target).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
}

/// Names holding characters rustc rejects or that could end a comment line never reach the
/// generated source raw: string literals are printable ASCII, comments hold `\u{..}`.
/// (tests-build compiles tables of such robots.)
#[test]
fn odd_characters_in_names_are_escaped_everywhere() {
    let odd = "\u{202a}\u{202b}\u{202c}\u{202d}\u{202e}\u{2066}\u{2067}\u{2068}\u{2069}\
               \u{200e}\u{200f}\u{61c}\u{85}\u{2028}\u{2029}\u{feff}\u{ad}\u{200b}\u{a0}\u{e000}";
    let xml_odd = format!("{odd}&#10;&#13;&#9;");
    let text = format!(
        "<robot name=\"r{xml_odd}\"><link name=\"a{xml_odd}\"/><link name=\"b{xml_odd}\"/>\
         <joint name=\"j{xml_odd}*/\" type=\"revolute\"><parent link=\"a{xml_odd}\"/>\
         <child link=\"b{xml_odd}\"/></joint></robot>"
    );
    let urdf = ppoe_build::Urdf::parse(&text).unwrap();
    let (base, tip) = (&urdf.links[0].name, &urdf.links[1].name);
    assert!(base.contains('\n') && base.contains('\u{202e}'));
    let chain = urdf.chain::<&str>(base, tip, None).unwrap();
    let source = Source {
        file_name: format!("odd{odd}\n.urdf"),
        sha256: codegen::sha256_hex(text.as_bytes()),
    };
    let out = codegen::generate(&chain, "ODD", Scalar::Both, &source).unwrap();
    let forbidden = |c: char| {
        (c.is_control() && c != '\n')
            || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
            || matches!(
                c,
                '\u{200e}' | '\u{200f}' | '\u{61c}' | '\u{2028}' | '\u{2029}'
            )
            || matches!(
                c,
                '\u{feff}' | '\u{ad}' | '\u{200b}' | '\u{a0}' | '\u{e000}'
            )
    };
    let raw: Vec<String> = out
        .chars()
        .filter(|&c| forbidden(c))
        .map(|c| format!("U+{:04X}", c as u32))
        .collect();
    assert!(raw.is_empty(), "raw in the output: {raw:?}\n{out}");
    // Every comment line is one line: the escapes are there, in the doc and the code.
    assert!(out.contains("/// * base: `a\\u{202a}\\u{202b}"));
    assert!(out.contains("\"a\\u{202a}\\u{202b}"));
    assert!(out.contains("// Generated by ppoe-build from `odd\\u{202a}"));
    assert!(out.contains("\\u{a}\\u{d}\\u{9}"));
    // `*/` is broken up in comments (safe in a C block comment too), kept in literals.
    assert!(out.contains("*\\/") && out.contains("*/\""));
    // The names are still all there, as string literals holding exactly them.
    for name in [base, tip, &chain.joints[0].name] {
        assert!(out.contains(&ppoe_build::literal::str_lit(name)));
    }
}

/// The format guard of a generated table, compiled by rustc against a stand-in `ppoe`
/// holding only `TABLE_FORMAT`: it compiles with the format ppoe-build wrote, and fails
/// with its message with any other (a table from another ppoe-build).
#[test]
fn a_table_for_another_ppoe_format_fails_to_compile() {
    let table = Config::new(urdf_path("seed.urdf"))
        .base("linkmount")
        .tip("tcp")
        .generate()
        .unwrap();
    let guard: Vec<&str> = table
        .lines()
        .filter(|l| l.contains("ppoe::TABLE_FORMAT"))
        .collect();
    assert_eq!(guard.len(), 1, "{table}");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("format-guard");
    std::fs::create_dir_all(&dir).unwrap();
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let compile = |format: u32| {
        let src = dir.join(format!("guard_{format}.rs"));
        let text = format!(
            "mod ppoe {{ pub const TABLE_FORMAT: u32 = {format}; }}\n{}\n",
            guard[0]
        );
        std::fs::write(&src, text).unwrap();
        std::process::Command::new(&rustc)
            .args([
                "--edition",
                "2021",
                "--crate-type",
                "lib",
                "--emit",
                "metadata",
                "-o",
            ])
            .arg(dir.join(format!("libguard_{format}.rmeta")))
            .arg(&src)
            .output()
            .unwrap()
    };
    let ok = compile(ppoe::TABLE_FORMAT);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let bad = compile(ppoe::TABLE_FORMAT + 1);
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(!bad.status.success());
    assert!(
        stderr.contains(&format!(
            "this table was generated by ppoe-build for ppoe table format {}",
            ppoe::TABLE_FORMAT
        )),
        "{stderr}"
    );
}
