//! Generates the robot tables this crate includes, exactly as a firmware's build script
//! would.

use ppoe_build::codegen::{self, Scalar as S, Source};
use ppoe_build::literal::str_lit;
use ppoe_build::{Config, Scalar, Urdf};
use ppoe_test_robots as robots;
use std::fmt::Write as _;

/// Random robots whose tables are generated and compiled (see the `ppoe-test-robots` crate).
const RANDOM_ROBOTS: usize = 40;

fn main() -> Result<(), ppoe_build::Error> {
    println!("cargo:rerun-if-changed=build.rs");
    random_tables();
    hostile_tables()?;
    // The seed robot of pytransform3d's PPOE example, both scalar types.
    Config::new("../test_data/urdf/seed.urdf")
        .base("linkmount")
        .tip("tcp")
        .joints(["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"])
        .scalar(Scalar::Both)
        .name("SEED")
        .write_to_out_dir("seed_table.rs")?;

    // The seed robot calibrated by a noise file (issue #27): the table of the folded chain.
    let noise = seed_calibrated_noise();
    Config::new("../test_data/urdf/seed.urdf")
        .base("linkmount")
        .tip("tcp")
        .scalar(Scalar::Both)
        .name("SEED_CALIBRATED")
        .noise(&noise)
        .write_to_out_dir("seed_calibrated_table.rs")?;

    // A gantry with prismatic joints and an oblique slide, f32 only, default joint list.
    Config::new("../test_data/urdf/prismatic.urdf")
        .base("base_link")
        .tip("tool0")
        .scalar(Scalar::F32)
        .name("GANTRY")
        .write_to_out_dir("gantry_table.rs")?;

    // One joint of a branch of the tree (a single-joint table).
    Config::new("../test_data/urdf/tree.urdf")
        .base("base_footprint")
        .tip("torso")
        .name("TORSO")
        .write_to_out_dir("torso_table.rs")?;

    // A gripper whose chain has mimic joints (issue #30): the table and its coupling.
    Config::new("../test_data/urdf/gripper.urdf")
        .base("base")
        .tip("left_tip")
        .scalar(Scalar::Both)
        .name("GRIPPER")
        .write_to_out_dir("gripper_table.rs")?;
    Ok(())
}

/// Writes `random_tables.rs`: for every random robot whose chain ppoe-build accepts, its
/// table(s) exactly as `Config::write_to_out_dir` would generate them, and a `RANDOM` list
/// pairing each table with its URDF text; robots it rejects go to `RANDOM_REJECTED` with
/// the error kind, so the test can check that the run-time parse rejects them the same way.
fn random_tables() {
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR"));
    let mut rng = robots::Rng::new(0x5eed_1234_abcd_0042);
    let (mut src, mut list, mut rejected) = (String::new(), String::new(), String::new());
    for k in 0..RANDOM_ROBOTS {
        let (text, base, tip) = robots::robot(&mut rng, k);
        let suffix = robots::FILE_SUFFIXES[k % robots::FILE_SUFFIXES.len()];
        let file = format!("random_{k}{suffix}.urdf");
        // The text of a `&'static str` holding the URDF, and the link names, as literals
        // (`{:?}` would leave some format characters raw).
        let urdf_lit = format!(
            "include_str!(concat!(env!(\"OUT_DIR\"), {}))",
            str_lit(&format!("/{file}"))
        );
        let (base_lit, tip_lit) = (str_lit(&base), str_lit(&tip));
        std::fs::write(out_dir.join(&file), &text).expect("write a random URDF");
        let chain = match Urdf::parse(&text).and_then(|u| u.chain::<&str>(&base, &tip, None)) {
            Ok(c) => c,
            Err(e) => {
                let _ = writeln!(
                    rejected,
                    "    ({urdf_lit}, {base_lit}, {tip_lit}, {:?}),",
                    e.kind().name()
                );
                continue;
            }
        };
        let source = Source {
            file_name: file.clone(),
            sha256: codegen::sha256_hex(text.as_bytes()),
        };
        let name = format!("RANDOM_{k}");
        // Both scalar types when every value fits in f32, else the f64 table alone.
        let (code, has_f32) = match codegen::generate(&chain, &name, S::Both, &source) {
            Ok(c) => (c, true),
            Err(_) => (
                codegen::generate(&chain, &name, S::F64, &source).expect("f64 table"),
                false,
            ),
        };
        src += &code;
        let f32_ref = if has_f32 {
            format!("Some(ppoe::chain::ChainView {{ joints: &{name}_F32.joints, home: {name}_F32.home }})")
        } else {
            "None".to_string()
        };
        let _ = writeln!(
            list,
            "    RandomTable {{ urdf: {urdf_lit}, base: {base_lit}, tip: {tip_lit}, f64: ppoe::chain::ChainView {{ joints: &{name}.joints, home: {name}.home }}, f32: {f32_ref} }},"
        );
    }
    src += &format!("\n/// The random robots' tables with their URDF text.\npub static RANDOM: &[RandomTable] = &[\n{list}];\n");
    src += &format!("\n/// The random robots ppoe-build rejects: (URDF text, base, tip, error kind).\npub static RANDOM_REJECTED: &[(&str, &str, &str, &str)] = &[\n{rejected}];\n");
    std::fs::write(out_dir.join("random_tables.rs"), src).expect("write random_tables.rs");
}

/// Writes `hostile_tables.rs`: the seed robot's table once per string of
/// `ppoe_test_robots::hostile::HOSTILE_STRINGS`, that string in every name (robot, links,
/// joints), the URDF's file name, and the name and file name of a noise model baked in,
/// through `Table::generate` as `ppoe table` does. A string that escaped its comment would
/// inject `compile_error!` and fail this build. `HOSTILE` lists (string, table) for the
/// test that the names arrive intact.
fn hostile_tables() -> Result<(), ppoe_build::Error> {
    use ppoe_build::noise::NoiseModel;
    use ppoe_build::table::{Lang, Noise, Table};
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR"));
    let bytes = std::fs::read("../test_data/urdf/seed.urdf").expect("read seed.urdf");
    let seed = Urdf::parse_bytes(&bytes)?.chain::<&str>("linkmount", "tcp", None)?;
    let (mut src, mut list) = (String::new(), String::new());
    for (k, s) in robots::hostile::HOSTILE_STRINGS.iter().enumerate() {
        let mut chain = seed.clone();
        (chain.robot, chain.base, chain.tip) = (s.to_string(), format!("{s}b"), format!("{s}t"));
        for (i, j) in chain.joints.iter_mut().enumerate() {
            j.name = format!("{s}{i}");
        }
        let cov: Vec<Vec<f64>> = (0..6)
            .map(|i| (0..6).map(|j| if i == j { 1e-4 } else { 0.0 }).collect())
            .collect();
        let joints: Vec<String> = chain
            .joint_names()
            .iter()
            .map(|n| {
                format!(
                    "{{\"name\": {}, \"cov\": {cov:?}, \"sigma2\": 1e-4}}",
                    json_str(n)
                )
            })
            .collect();
        let text = format!(
            "{{\"model\": {}, \"joints\": [{}]}}",
            json_str(s),
            joints.join(", ")
        );
        let model = NoiseModel::parse(&text)?;
        let path = std::path::Path::new("/fits").join(format!("{s}.json"));
        let name = format!("HOSTILE_{k}");
        src += &Table {
            chain: &chain,
            urdf: &bytes,
            file_name: &format!("{s}.urdf"),
            name: &name,
            scalar: S::Both,
            lang: Lang::Rust,
            noise: Some(Noise {
                model: &model,
                path: &path,
            }),
        }
        .generate()?;
        let _ = writeln!(list, "    ({}, &{name}, &{name}_NOISE_F32),", str_lit(s));
    }
    src += &format!("\n/// The hostile strings with their tables.\npub static HOSTILE: &[(&str, &ppoe::chain::Chain<f64, 6>, &[ppoe::Mat6<f32>; 6])] = &[\n{list}];\n");
    std::fs::write(out_dir.join("hostile_tables.rs"), src).expect("write hostile_tables.rs");
    Ok(())
}

/// Writes `seed_calibrated.json` to `OUT_DIR`: a noise file for the seed robot with a
/// calibration (joint offsets, axis corrections, a home correction) as `ppoe fit
/// --estimate` writes it; returns its path (the test reads it back).
fn seed_calibrated_noise() -> std::path::PathBuf {
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR"));
    let joints: Vec<String> = (0..6)
        .map(|i| {
            let (d, k) = (0.01 * (i as f64 + 1.0), 0.004 * (i as f64 - 2.5));
            format!(
                "{{\"name\": \"joint{}\", \"cov\": [[1e-6,0,0,0,0,0],[0,1e-6,0,0,0,0],[0,0,1e-6,0,0,0],\
                 [0,0,0,1e-6,0,0],[0,0,0,0,1e-6,0],[0,0,0,0,0,1e-6]], \"sigma2\": 1e-6, \"offset\": {d}, \
                 \"offset_se\": 1e-5, \"axis_correction\": [{k}, {}, 0, 0, {k}, {}]}}",
                i + 1,
                -k,
                0.5 * k
            )
        })
        .collect();
    let text = format!(
        "{{\"model\": \"joint\", \"joints\": [{}],\n \"calibration\": {{\"estimated\": [\"base\", \
         \"tip\", \"offsets\", \"kinematics\"], \"home_correction\": [0.01, -0.02, 0.005, 0.001, \
         0.002, -0.003]}},\n \"goodness_of_fit\": {{\"fits\": true}}}}\n",
        joints.join(",\n ")
    );
    let path = out_dir.join("seed_calibrated.json");
    std::fs::write(&path, text).expect("write seed_calibrated.json");
    path
}

/// A JSON string literal (`{:?}` is not JSON for every character).
fn json_str(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            _ => {
                for u in c.encode_utf16(&mut [0; 2]) {
                    let _ = write!(out, "\\u{u:04x}");
                }
            }
        }
    }
    out.push('"');
    out
}
