//! Noise from a datasheet: a noise-file joint with `sigma2` and no `cov`, and
//! `Config::joint_sigmas`, both mean `σ²·SᵢSᵢᵀ` with Sᵢ the joint's screw axis in the base
//! frame. The screws are derived here by hand from the URDF's origins and axes.

use ppoe_build::noise::NoiseModel;
use ppoe_build::{Config, ErrorKind, Urdf};

/// A revolute joint about y, 0.5 m up; a prismatic joint along z, 1 m out in x.
const URDF: &str = r#"<robot name="two">
  <link name="base"/><link name="upper"/><link name="tool"/>
  <joint name="pitch" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="lift" type="prismatic"><parent link="upper"/><child link="tool"/>
    <origin xyz="1 0 0"/><axis xyz="0 0 1"/><limit lower="0" upper="0.2" effort="1" velocity="1"/></joint>
</robot>"#;

/// The screw axes by hand: revolute (ω, q × ω) with q the joint's position at home,
/// prismatic (0, axis).
fn screws() -> [[f64; 6]; 2] {
    // ω = (0, 1, 0), q = (0, 0, 0.5): q × ω = (0·0 − 0.5·1, 0.5·0 − 0·0, 0·1 − 0·0).
    let pitch = [0.0, 1.0, 0.0, -0.5, 0.0, 0.0];
    let lift = [0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    [pitch, lift]
}

/// `σ²·S·Sᵀ` element by element.
fn outer(s: &[f64; 6], sigma2: f64) -> [[f64; 6]; 6] {
    let mut m = [[0.0; 6]; 6];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = sigma2 * s[i] * s[j];
        }
    }
    m
}

fn chain() -> ppoe_build::RobotChain {
    Urdf::parse(URDF)
        .unwrap()
        .chain::<&str>("base", "tool", None)
        .unwrap()
}

#[test]
fn sigma2_only_joints_are_screw_noise_of_the_chain() {
    let text = r#"{"model": "joint", "joints": [
        {"name": "pitch", "sigma2": 4e-8},
        {"name": "lift", "sigma2": 9e-10, "cov": [[0,0,0,0,0,0],[0,0,0,0,0,0],[0,0,0,0,0,0],
                                                   [0,0,0,0,0,0],[0,0,0,0,0,0],[0,0,0,0,0,1e-6]]}]}"#;
    let mut m = NoiseModel::parse(text).unwrap();
    assert_eq!(m.from_sigma2, vec![0]);
    m.resolve(&chain()).unwrap();
    let s = screws();
    assert_eq!(m.joints[0].cov, outer(&s[0], 4e-8));
    // Both given: cov wins (1e-6, not 9e-10), sigma2 is kept.
    assert_eq!(m.joints[1].cov[5][5], 1e-6);
    assert_eq!(m.joints[1].sigma2, Some(9e-10));
    // A second resolve changes nothing.
    let before = m.clone();
    m.resolve(&chain()).unwrap();
    assert_eq!(m, before);
}

#[test]
fn from_sigmas_squares_sigma() {
    let m = NoiseModel::from_sigmas(&chain(), &[2e-4, 3e-5]).unwrap();
    let s = screws();
    assert_eq!(m.model, "joint");
    assert_eq!(m.joints[0].cov, outer(&s[0], 2e-4 * 2e-4));
    assert_eq!(m.joints[1].cov, outer(&s[1], 3e-5 * 3e-5));
    assert_eq!(m.joints[1].sigma2, Some(3e-5 * 3e-5));
}

#[test]
fn bad_sigmas_are_errors_naming_the_joints() {
    let e = NoiseModel::from_sigmas(&chain(), &[1e-4]).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("1 joint sigmas") && msg.contains("2 moving joints (pitch, lift)"),
        "{msg}"
    );
    for bad in [-1e-4, f64::NAN, f64::INFINITY] {
        let msg = NoiseModel::from_sigmas(&chain(), &[1e-4, bad])
            .unwrap_err()
            .to_string();
        assert!(msg.contains("joint sigma 1 ('lift')"), "{msg}");
    }
    for (sigma2, what) in [
        ("-1e-8", "sigma2"),
        ("\"x\"", "sigma2"),
        ("null", "neither"),
    ] {
        let text = format!(r#"{{"joints": [{{"name": "pitch", "sigma2": {sigma2}}}]}}"#);
        let e = NoiseModel::parse(&text).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::Config);
        assert!(
            e.to_string().contains("joint 0 ('pitch')") && e.to_string().contains(what),
            "{e}"
        );
    }
}

#[test]
fn config_joint_sigmas_bakes_the_same_table_as_a_sigma2_file() {
    let dir = std::env::temp_dir().join(format!("ppoe-datasheet-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let urdf = dir.join("two.urdf");
    std::fs::write(&urdf, URDF).unwrap();
    let noise = dir.join("noise.json");
    std::fs::write(
        &noise,
        r#"{"model": "joint", "joints": [{"name": "pitch", "sigma2": 4e-8}, {"name": "lift", "sigma2": 9e-10}]}"#,
    )
    .unwrap();
    let from_file = Config::new(&urdf)
        .base("base")
        .tip("tool")
        .noise(&noise)
        .generate()
        .unwrap();
    let from_sigmas = Config::new(&urdf)
        .base("base")
        .tip("tool")
        .joint_sigmas(&[2e-4, 3e-5])
        .generate()
        .unwrap();
    // Pitch's row 3 is σ²·S₃·S = 4e-8·(−0.5)·(0, 1, 0, −0.5, 0, 0) (−0.5·0 is −0.0).
    let items = |src: &str| src[src.find("pub const TWO_NOISE").unwrap()..].to_string();
    let file_items = items(&from_file);
    assert!(
        file_items.contains("[-0.0, -2e-8, -0.0, 1e-8, -0.0, -0.0]"),
        "{file_items}"
    );
    assert!(
        file_items.contains("pub const TWO_SIGMA2: [f64; 2] = [4e-8, 9e-10];"),
        "{file_items}"
    );
    // (2e-4)² and (3e-5)² round to the same doubles as 4e-8 and 9e-10.
    assert_eq!(file_items, items(&from_sigmas));
    let both = Config::new(&urdf)
        .base("base")
        .tip("tool")
        .noise(&noise)
        .joint_sigmas(&[1e-4, 1e-4])
        .generate()
        .unwrap_err();
    assert!(
        both.to_string().contains("give the noise one way"),
        "{both}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_overflowing_sigma2_is_an_error_naming_the_joint() {
    let mut far = chain();
    // The pitch axis 10 m up: v = q × ω = (−10, 0, 0), so σ²·v₀² = 1e307·100 overflows.
    far.joints[0].screw = [0.0, 1.0, 0.0, -10.0, 0.0, 0.0];
    let text = r#"{"joints": [{"name": "pitch", "sigma2": 1e307}, {"name": "lift", "sigma2": 0}]}"#;
    let mut m = NoiseModel::parse(text).unwrap();
    let e = m.resolve(&far).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert!(e.to_string().contains("joint 0 ('pitch')"), "{e}");
}
