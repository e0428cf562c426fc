//! The one table pipeline (`ppoe_build::Table`): the source label and hash, the const
//! name, Rust and C, and the noise model appended or refused.

use ppoe_build::noise::NoiseModel;
use ppoe_build::table::{const_name, Noise};
use ppoe_build::{ErrorKind, Lang, Scalar, Table, Urdf};
use std::path::Path;

fn seed() -> (Vec<u8>, ppoe_build::RobotChain) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let bytes = std::fs::read(root.join("test_data/urdf/seed.urdf")).unwrap();
    let chain = Urdf::parse_bytes(&bytes)
        .unwrap()
        .chain::<&str>("linkmount", "tcp", None)
        .unwrap();
    (bytes, chain)
}

/// A joint model for the seed's six joints, `sigma2` 1e-4 each.
fn noise(names: &[&str]) -> NoiseModel {
    let cov: Vec<Vec<f64>> = (0..6)
        .map(|i| (0..6).map(|j| if i == j { 1e-4 } else { 0.0 }).collect())
        .collect();
    let joints: Vec<serde_json::Value> = names
        .iter()
        .map(|n| serde_json::json!({"name": n, "cov": cov, "sigma2": 1e-4}))
        .collect();
    NoiseModel::parse(&serde_json::json!({"model": "joint", "joints": joints}).to_string()).unwrap()
}

const SEED_JOINTS: [&str; 6] = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"];

#[test]
fn names_and_hash() {
    assert_eq!(const_name(None, "seed"), "SEED");
    assert_eq!(const_name(None, "my-robot.v2"), "MY_ROBOT_V2");
    assert_eq!(const_name(Some("Arm"), "seed"), "Arm");
    let (bytes, chain) = seed();
    for lang in [Lang::Rust, Lang::C] {
        let src = Table {
            chain: &chain,
            urdf: &bytes,
            file_name: "label.urdf",
            name: "ARM",
            scalar: Scalar::F64,
            lang,
            noise: None,
        }
        .generate()
        .unwrap();
        // sha256sum test_data/urdf/seed.urdf
        assert!(
            src.contains("8114fc13aa5afd0c943d9c37aeb475cd388640bbdc0315b6967565b59ae7c493"),
            "{lang:?}"
        );
        assert!(src.contains("`label.urdf`"), "{lang:?}");
    }
}

#[test]
fn noise_is_appended_to_rust_tables_only() {
    let (bytes, chain) = seed();
    let model = noise(&SEED_JOINTS);
    let path = Path::new("/some/dir/fit.json");
    let table = |lang, model| Table {
        chain: &chain,
        urdf: &bytes,
        file_name: "seed.urdf",
        name: "ARM",
        scalar: Scalar::Both,
        lang,
        noise: Some(Noise { model, path }),
    };
    let src = table(Lang::Rust, &model).generate().unwrap();
    assert!(
        src.contains("pub const ARM_NOISE: [ppoe::Mat6<f64>; 6]"),
        "{src}"
    );
    assert!(src.contains("pub const ARM_SIGMA2_F32: [f32; 6]"), "{src}");
    assert!(
        src.contains("fit.json") && !src.contains("/some/dir"),
        "{src}"
    );

    let c = table(Lang::C, &model).generate().unwrap_err();
    assert_eq!(c.kind(), ErrorKind::Config, "{c}");
    assert_eq!(c.file(), Some(path), "{c}");

    let other = noise(&SEED_JOINTS[..5]);
    let e = table(Lang::Rust, &other).generate().unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Config, "{e}");
    assert_eq!(e.file(), Some(path), "{e}");
}
