//! Hostile strings (`ppoe_test_robots::hostile::HOSTILE_STRINGS`) in every place a string
//! reaches a generated table — robot, link and joint names, the URDF's file name, the noise
//! model's name, its file name — cannot change the code: the table's skeleton (its source
//! without comment and literal text, `ppoe_test_robots::skeleton`, which shares no code
//! with ppoe-build) is that of the same table with plain names, and the C tables compile
//! as C99 and C11 with every warning an error. (tests-build compiles the Rust ones.)

mod common;

use ppoe_build::literal::needs_escape;
use ppoe_build::noise::NoiseModel;
use ppoe_build::table::Noise;
use ppoe_build::{Lang, RobotChain, Scalar, Table, Urdf};
use ppoe_test_robots::hostile::HOSTILE_STRINGS;
use ppoe_test_robots::skeleton::{c_skeleton, rust_skeleton};
use std::path::Path;

fn seed() -> (Vec<u8>, RobotChain) {
    let bytes = std::fs::read(common::urdf_path("seed.urdf")).unwrap();
    let chain = Urdf::parse_bytes(&bytes)
        .unwrap()
        .chain::<&str>("linkmount", "tcp", None)
        .unwrap();
    (bytes, chain)
}

/// The seed chain with every name made from `s`.
fn renamed(chain: &RobotChain, s: &str) -> RobotChain {
    let mut c = chain.clone();
    c.robot = s.to_string();
    c.base = format!("{s}b");
    c.tip = format!("{s}t");
    for (i, j) in c.joints.iter_mut().enumerate() {
        j.name = format!("{s}{i}");
    }
    c
}

/// A noise model called `model` for `chain`'s joints.
fn noise_for(chain: &RobotChain, model: &str) -> NoiseModel {
    let cov: Vec<Vec<f64>> = (0..6)
        .map(|i| (0..6).map(|j| if i == j { 1e-4 } else { 0.0 }).collect())
        .collect();
    let joints: Vec<_> = chain
        .joint_names()
        .iter()
        .map(|n| serde_json::json!({"name": n, "cov": cov, "sigma2": 1e-4}))
        .collect();
    let text = serde_json::json!({"model": model, "joints": joints}).to_string();
    NoiseModel::parse(&text).unwrap()
}

/// The table of `chain` named `name` in `lang` (with a noise model called `s` from a file
/// named after `s` for Rust), everything else from `s`.
fn table(chain: &RobotChain, urdf: &[u8], name: &str, lang: Lang, s: &str) -> String {
    let model = noise_for(chain, s);
    let path = Path::new("/fits").join(format!("{s}.json"));
    let noise = (lang == Lang::Rust).then(|| Noise {
        model: &model,
        path: &path,
    });
    let file_name = format!("{s}.urdf");
    Table {
        chain,
        urdf,
        file_name: &file_name,
        name,
        scalar: Scalar::Both,
        lang,
        noise,
    }
    .generate()
    .unwrap_or_else(|e| panic!("{s:?}: {e}"))
}

#[test]
fn hostile_strings_leave_the_rust_code_unchanged() {
    let (bytes, seed) = seed();
    let plain = rust_skeleton(&table(&renamed(&seed, "p"), &bytes, "R", Lang::Rust, "p"));
    for s in HOSTILE_STRINGS {
        let src = table(&renamed(&seed, s), &bytes, "R", Lang::Rust, s);
        assert_eq!(rust_skeleton(&src), plain, "{s:?}:\n{src}");
        let raw = src.chars().find(|&c| c != '\n' && needs_escape(c));
        assert_eq!(raw, None, "{s:?}: a raw character in\n{src}");
    }
}

#[test]
fn hostile_strings_leave_the_c_code_unchanged_and_ascii() {
    let (bytes, seed) = seed();
    let plain = c_skeleton(&table(&renamed(&seed, "p"), &bytes, "R", Lang::C, "p"));
    for s in HOSTILE_STRINGS {
        let src = table(&renamed(&seed, s), &bytes, "R", Lang::C, s);
        assert_eq!(c_skeleton(&src), plain, "{s:?}:\n{src}");
        let bad = src
            .bytes()
            .find(|&b| b != b'\n' && !(b' '..=b'~').contains(&b));
        assert_eq!(bad, None, "{s:?}: not printable ASCII in\n{src}");
    }
}

#[test]
fn hostile_c_tables_compile_as_c99_and_c11() {
    let (bytes, seed) = seed();
    let mut header = String::new();
    let mut uses = Vec::new();
    for (k, s) in HOSTILE_STRINGS.iter().enumerate() {
        header += &table(&renamed(&seed, s), &bytes, &format!("H{k}"), Lang::C, s);
        uses.push(format!("(int)H{k}.n_joints + (int)H{k}_F32.n_joints"));
    }
    let main = format!(
        "int f(void);\nint f(void) {{ return {}; }}\n",
        uses.join(" + ")
    );
    for std in ["c99", "c11"] {
        let r = common::cc_syntax_check(&header, &main, std, "ppoe-hostile-c");
        assert!(r.is_ok(), "-std={std}:\n{}", r.unwrap_err());
    }
}

/// `noise_for` with a calibration (offsets, axis corrections, a home correction), `s` in
/// its `estimated` list: the table is the calibrated chain's, with a note naming the file.
fn calibrated_noise_for(chain: &RobotChain, s: &str) -> NoiseModel {
    let mut v = noise_json(chain, s);
    for (i, j) in v["joints"].as_array_mut().unwrap().iter_mut().enumerate() {
        j["offset"] = serde_json::json!(1e-3 * (i as f64 + 1.0));
        j["axis_correction"] = serde_json::json!([1e-3, 0, 0, 0, 2e-3, 0]);
    }
    v["calibration"] = serde_json::json!({"estimated": [s, "offsets"], "home_correction": [0, 1e-3, 0, 0, 0, 1e-3]});
    v["goodness_of_fit"] = serde_json::json!({"fits": true});
    NoiseModel::parse(&v.to_string()).unwrap()
}

/// The JSON of `noise_for`.
fn noise_json(chain: &RobotChain, model: &str) -> serde_json::Value {
    let cov: Vec<Vec<f64>> = (0..6)
        .map(|i| (0..6).map(|j| if i == j { 1e-4 } else { 0.0 }).collect())
        .collect();
    let joints: Vec<_> = chain
        .joint_names()
        .iter()
        .map(|n| serde_json::json!({"name": n, "cov": cov, "sigma2": 1e-4}))
        .collect();
    serde_json::json!({"model": model, "joints": joints})
}

/// The calibrated table of `chain` in `lang`, every string from `s` (the noise file's name
/// too, so it reaches the calibration note).
fn calibrated_table(chain: &RobotChain, urdf: &[u8], name: &str, lang: Lang, s: &str) -> String {
    let model = calibrated_noise_for(chain, s);
    let path = Path::new("/fits").join(format!("{s}.json"));
    let file_name = format!("{s}.urdf");
    let src = Table {
        chain,
        urdf,
        file_name: &file_name,
        name,
        scalar: Scalar::Both,
        lang,
        noise: Some(Noise {
            model: &model,
            path: &path,
        }),
    }
    .generate()
    .unwrap_or_else(|e| panic!("{s:?}: {e}"));
    assert!(src.contains("Calibrated: "), "{s:?}:\n{src}");
    src
}

#[test]
fn hostile_strings_leave_calibrated_tables_unchanged() {
    let (bytes, seed) = seed();
    let rust = |s: &str| calibrated_table(&renamed(&seed, s), &bytes, "R", Lang::Rust, s);
    let c = |s: &str| calibrated_table(&renamed(&seed, s), &bytes, "R", Lang::C, s);
    let (plain_rust, plain_c) = (rust_skeleton(&rust("p")), c_skeleton(&c("p")));
    let mut header = String::new();
    let mut uses = Vec::new();
    for (k, s) in HOSTILE_STRINGS.iter().enumerate() {
        let src = rust(s);
        assert_eq!(rust_skeleton(&src), plain_rust, "{s:?}:\n{src}");
        let raw = src.chars().find(|&c| c != '\n' && needs_escape(c));
        assert_eq!(raw, None, "{s:?}: a raw character in\n{src}");
        let src = c(s);
        assert_eq!(c_skeleton(&src), plain_c, "{s:?}:\n{src}");
        let bad = src
            .bytes()
            .find(|&b| b != b'\n' && !(b' '..=b'~').contains(&b));
        assert_eq!(bad, None, "{s:?}: not printable ASCII in\n{src}");
        let name = format!("H{k}");
        header += &calibrated_table(&renamed(&seed, s), &bytes, &name, Lang::C, s);
        uses.push(format!("(int){name}.n_joints"));
    }
    let main = format!(
        "int f(void);\nint f(void) {{ return {}; }}\n",
        uses.join(" + ")
    );
    let r = common::cc_syntax_check(&header, &main, "c99", "ppoe-hostile-calibrated-c");
    assert!(r.is_ok(), "{}", r.unwrap_err());
}
