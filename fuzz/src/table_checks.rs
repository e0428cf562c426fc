//! The `table` oracle: an arbitrary chain with arbitrary names, file names and noise
//! strings → `Table::generate` in Rust and C. Never a panic; for every `Ok` output, the
//! escaping holds by an oracle that shares no code with ppoe-build (the skeleton of the
//! source without comment and literal text, `ppoe_test_robots::skeleton`, equals that of the
//! same table with plain names), no raw character that could break or reorder a line, C
//! printable ASCII only, and the identifiers it defines valid and distinct.

use crate::FVal;
use arbitrary::Arbitrary;
use ppoe_build::chain::{ChainJoint, RobotChain};
use ppoe_build::literal::needs_escape;
use ppoe_build::noise::{NoiseJoint, NoiseModel};
use ppoe_build::table::{Lang, Noise, Table};
use ppoe_build::{JointKind, Scalar};
use ppoe_test_robots::skeleton::{c_skeleton, rust_skeleton};
use std::path::Path;

/// Joints per input (the C API's maximum is 16: one more reaches the refusal). Bounded, as
/// are the strings ([`MAX_CHARS`]), to keep the smoke run's 10⁵ executions within its
/// time cap under AddressSanitizer; longer inputs add no new way to escape.
pub const MAX_JOINTS: usize = 17;

/// Characters kept of each fuzzed string.
pub const MAX_CHARS: usize = 40;

fn clip(s: &str) -> String {
    s.chars().take(MAX_CHARS).collect()
}

/// One fuzzed joint.
#[derive(Arbitrary, Debug)]
pub struct JointIn {
    name: String,
    kind: u8,
    screw: [FVal; 6],
    lower: FVal,
    upper: FVal,
}

/// One fuzzed table request.
#[derive(Arbitrary, Debug)]
pub struct TableIn {
    robot: String,
    base: String,
    tip: String,
    file_name: String,
    /// Index into [`NAMES`] or, past it, the string `raw_name`.
    name: u8,
    raw_name: String,
    joints: Vec<JointIn>,
    home: [FVal; 12],
    scalar: u8,
    c: bool,
    noise: Option<(String, String, u8)>,
}

/// Table names: ordinary ones and ones C or Rust must refuse.
const NAMES: &[&str] = &[
    "R", "SEED", "robot_1", "NULL", "_Bool", "int", "fn", "async", "PPOE_OK", "sin", "A_",
    "size_t", "INFINITY", "INT8_MAX", "_x", "1A", "",
];

fn chain(t: &TableIn, plain: bool) -> RobotChain {
    let name = |s: &str, i: usize| {
        if plain {
            format!("p{i}")
        } else {
            s.to_string()
        }
    };
    let h: Vec<f64> = t.home.iter().map(|x| x.get::<f64>()).collect();
    let home = [
        [h[0], h[1], h[2], h[9]],
        [h[3], h[4], h[5], h[10]],
        [h[6], h[7], h[8], h[11]],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let joints = t
        .joints
        .iter()
        .take(MAX_JOINTS)
        .enumerate()
        .map(|(i, j)| ChainJoint {
            name: name(&j.name, i),
            kind: [
                JointKind::Revolute,
                JointKind::Continuous,
                JointKind::Prismatic,
            ][j.kind as usize % 3],
            screw: j.screw.map(|x| x.get::<f64>()),
            lower: j.lower.get(),
            upper: j.upper.get(),
            home_frame: home,
        });
    RobotChain {
        robot: name(&t.robot, 100),
        base: name(&t.base, 101),
        tip: name(&t.tip, 102),
        joints: joints.collect(),
        home,
        coupling: None,
    }
}

/// The body of the `table` target.
pub fn run(t: &TableIn) {
    let name = NAMES
        .get(t.name as usize)
        .map_or(t.raw_name.as_str(), |s| s);
    let lang = if t.c { Lang::C } else { Lang::Rust };
    let scalar = [Scalar::F64, Scalar::F32, Scalar::Both][t.scalar as usize % 3];
    let Some(hostile) = generate(t, false, name, lang, scalar) else {
        return;
    };
    let plain = generate(t, true, name, lang, scalar)
        .expect("the same table with plain names is generated too");
    match lang {
        Lang::Rust => {
            assert_eq!(
                rust_skeleton(&hostile),
                rust_skeleton(&plain),
                "escaping: {hostile}"
            );
            let raw = hostile.chars().find(|&c| c != '\n' && needs_escape(c));
            assert_eq!(raw, None, "a raw character in {hostile}");
        }
        Lang::C => {
            assert_eq!(
                c_skeleton(&hostile),
                c_skeleton(&plain),
                "escaping: {hostile}"
            );
            let bad = hostile
                .bytes()
                .find(|&b| b != b'\n' && !(b' '..=b'~').contains(&b));
            assert_eq!(bad, None, "not printable ASCII: {hostile}");
            assert!(t.joints.len().min(MAX_JOINTS) <= ppoe_build::codegen_c::C_API_MAX_JOINTS);
        }
    }
    check_identifiers(&plain, lang);
}

fn generate(t: &TableIn, plain: bool, name: &str, lang: Lang, scalar: Scalar) -> Option<String> {
    let chain = chain(t, plain);
    let model = t.noise.as_ref().map(|(model, _, cov)| NoiseModel {
        model: if plain {
            plain_model(model)
        } else {
            model.clone()
        },
        joints: chain
            .joints
            .iter()
            .map(|j| NoiseJoint {
                name: j.name.clone(),
                cov: [[f64::from(*cov) * 1e-6; 6]; 6],
                sigma2: Some(1e-4),
            })
            .collect(),
        ..Default::default()
    });
    let path = t
        .noise
        .as_ref()
        .map(|(_, file, _)| Path::new("/fits").join(if plain { "p.json" } else { file.as_str() }));
    let noise = model
        .as_ref()
        .zip(path.as_deref())
        .map(|(model, path)| Noise { model, path });
    let file_name = if plain {
        "p.urdf".into()
    } else {
        clip(&t.file_name)
    };
    Table {
        chain: &chain,
        urdf: b"",
        file_name: &file_name,
        name,
        scalar,
        lang,
        noise,
    }
    .generate()
    .ok()
}

/// A plain model name that generates the same items as `model` (only "joint" adds σ²).
fn plain_model(model: &str) -> String {
    if clip(model) == "joint" {
        "joint"
    } else {
        "full"
    }
    .to_string()
}

/// The identifiers the source defines (`pub const X`, `static const T X`, `#define X`) are
/// valid ASCII identifiers and distinct.
fn check_identifiers(src: &str, lang: Lang) {
    let skeleton = match lang {
        Lang::Rust => rust_skeleton(src),
        Lang::C => c_skeleton(src),
    };
    let mut ids: Vec<&str> = Vec::new();
    for line in skeleton.lines() {
        let id = if let Some(rest) = line.strip_prefix("pub const ") {
            rest.split(':').next()
        } else if let Some(rest) = line.strip_prefix("static const ") {
            rest.split_whitespace()
                .nth(1)
                .map(|s| s.split('[').next().unwrap_or(s))
        } else if let Some(rest) = line.strip_prefix("#define ") {
            rest.split_whitespace().next()
        } else {
            None
        };
        if let Some(id) = id {
            let valid = id.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
                && id.bytes().next().is_some_and(|b| !b.is_ascii_digit());
            assert!(valid, "invalid identifier {id:?} in {src}");
            assert!(!ids.contains(&id), "{id} defined twice in {src}");
            ids.push(id);
        }
    }
    assert!(!ids.is_empty(), "no identifier found in {src}");
}
