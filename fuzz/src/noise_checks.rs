//! The `noise` oracle: arbitrary bytes → `json::parse` (strict) and `NoiseModel::parse`,
//! then the noise items generated for a chain of the model's joints. Never a panic;
//! strict JSON agrees with serde_json wherever it accepts, refuses only for a reason it
//! names (duplicate key, depth, BOM handling aside), and every error has a position inside
//! the text; the generated items keep every name in its comment (skeleton oracle).

use ppoe_build::chain::{ChainJoint, RobotChain};
use ppoe_build::literal::needs_escape;
use ppoe_build::noise::NoiseModel;
use ppoe_build::table::{Lang, Noise, Table};
use ppoe_build::{ErrorKind, JointKind, Scalar};
use ppoe_test_robots::skeleton::rust_skeleton;
use std::path::Path;

/// The body of the `noise` target.
pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    check_json(text);
    let Ok(model) = NoiseModel::parse(text) else {
        return;
    };
    if model.joints.len() > 64 {
        return;
    }
    // A calibration that folds beyond finite (or f32) numbers is an error, not a table.
    let (Some(hostile), Some(plain)) = (items(&model, false), items(&model, true)) else {
        return;
    };
    assert_eq!(
        rust_skeleton(&hostile),
        rust_skeleton(&plain),
        "escaping: {hostile}"
    );
    let raw = hostile.chars().find(|&c| c != '\n' && needs_escape(c));
    assert_eq!(raw, None, "a raw character in {hostile}");
}

fn check_json(text: &str) {
    let strict = ppoe_build::json::parse(text);
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    let lenient = serde_json::from_str::<serde_json::Value>(body);
    match (&strict, &lenient) {
        (Ok(a), Ok(b)) => assert_eq!(a, b, "strict and lenient parse differ"),
        (Ok(a), Err(e)) => panic!("strict accepts what serde_json refuses ({e}): {a:?}"),
        (Err(e), Ok(_)) => {
            let m = e.message();
            assert!(
                m.contains("duplicate key") || m.contains("nested deeper"),
                "{e}"
            );
        }
        (Err(_), Err(_)) => {}
    }
    if let Err(e) = strict {
        assert_eq!(e.kind(), ErrorKind::Json);
        let p = e.position().expect("a JSON error has a position");
        let lines = body.split('\n').count();
        assert!(
            p.line >= 1 && p.line as usize <= lines,
            "{e} ({lines} lines)"
        );
        let line = body.split('\n').nth(p.line as usize - 1).unwrap_or("");
        assert!(
            p.column >= 1 && p.column as usize <= line.chars().count() + 1,
            "{e}"
        );
    }
}

/// The seed-like table of `model`'s joints with the noise items; `plain`: every string
/// replaced by a plain one. `None` only for a calibration whose folded chain is not finite
/// in f64 or f32 ([`ErrorKind::NonFinite`]).
fn items(model: &NoiseModel, plain: bool) -> Option<String> {
    let mut model = model.clone();
    if plain {
        model.model = if model.model == "joint" {
            "joint"
        } else {
            "full"
        }
        .to_string();
        for (i, j) in model.joints.iter_mut().enumerate() {
            j.name = format!("p{i}");
        }
        for e in &mut model.calibration.estimated {
            *e = "p".to_string();
        }
    }
    let id = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let chain = RobotChain {
        robot: "r".into(),
        base: "b".into(),
        tip: "t".into(),
        joints: model
            .joints
            .iter()
            .map(|j| ChainJoint {
                name: j.name.clone(),
                kind: JointKind::Revolute,
                screw: [0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
                lower: -1.0,
                upper: 1.0,
                home_frame: id,
            })
            .collect(),
        home: id,
        coupling: None,
    };
    let path = Path::new("/fits/fit.json");
    let noise = Some(Noise {
        model: &model,
        path,
    });
    let src = Table {
        chain: &chain,
        urdf: b"",
        file_name: "r.urdf",
        name: "R",
        scalar: Scalar::Both,
        lang: Lang::Rust,
        noise,
    }
    .generate();
    match src {
        Err(e) if model.is_calibrated() && e.kind() == ErrorKind::NonFinite => None,
        src => Some(src.expect("a checked model for its own chain generates")),
    }
}
