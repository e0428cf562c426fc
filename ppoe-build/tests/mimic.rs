//! Mimic joints in chain extraction: the couplings of `test_data/urdf/gripper.urdf` (a
//! master off the path, one on it), URDF's defaults, a mimic of a mimic resolved to its
//! root with the couplings composed by hand, a master left out of an explicit joint list,
//! the generated table, and the errors (no such master, a fixed master, a cycle, a
//! non-finite multiplier).

use ppoe::chain::{JointSource, Mimic};
use ppoe_build::{ErrorKind, Scalar, Source, Urdf};

fn gripper() -> Urdf {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../test_data/urdf/gripper.urdf"
    );
    Urdf::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A serial robot a → b → c → d with revolute joints j1, j2, j3 (each `<inner>` added).
fn serial(inner: [&str; 3]) -> String {
    let mut s = String::from(
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\
         <link name=\"d\"/><link name=\"x\"/>",
    );
    for (i, (p, c)) in [("a", "b"), ("b", "c"), ("c", "d")].iter().enumerate() {
        s.push_str(&format!(
            "<joint name=\"j{}\" type=\"revolute\"><parent link=\"{p}\"/><child link=\"{c}\"/>\
             <axis xyz=\"0 0 1\"/>{}</joint>",
            i + 1,
            inner[i]
        ));
    }
    // Off the path: an independent joint `free` and a fixed joint `still`.
    s.push_str(
        "<joint name=\"free\" type=\"revolute\"><parent link=\"a\"/><child link=\"x\"/></joint>\
         <link name=\"y\"/><joint name=\"still\" type=\"fixed\"><parent link=\"x\"/>\
         <child link=\"y\"/></joint></robot>",
    );
    s
}

#[test]
fn gripper_couplings() {
    let c = gripper()
        .chain("base", "left_tip", None::<&[&str]>)
        .unwrap();
    assert_eq!(
        c.joint_names(),
        ["shoulder", "elbow", "left_finger", "curl"]
    );
    assert_eq!(c.input_names(), ["shoulder", "elbow", "right_finger"]);
    let coupling = c.coupling.as_ref().unwrap();
    assert_eq!(
        coupling.sources,
        [
            JointSource::Input(0),
            JointSource::Input(1),
            JointSource::Mimic(Mimic::new(2, 0.8, 0.005)),
            JointSource::Mimic(Mimic::new(1, -0.5, 0.1)),
        ]
    );
    // 0.8·0.025 + 0.005 = 0.025 and −0.5·0.5 + 0.1 = −0.15 (not clipped here).
    let full = c.expand_thetas(&[0.25, 0.5, 0.025]).unwrap();
    assert_eq!(full[..2], [0.25, 0.5]);
    assert!((full[2] - 0.025).abs() < 1e-17 && (full[3] + 0.15).abs() < 1e-16);
    let e = c.expand_thetas(&[0.0; 4]).unwrap_err();
    assert!(
        e.to_string().contains("shoulder, elbow, right_finger"),
        "{e}"
    );
    // The other finger's chain holds the master, and nothing mimics on it.
    let r = gripper()
        .chain("base", "right_tip", None::<&[&str]>)
        .unwrap();
    assert!(r.coupling.is_none());
    assert_eq!(r.input_names(), r.joint_names());
}

#[test]
fn defaults_and_a_mimic_of_a_mimic() {
    // j2 = 1·j1 + 0 (defaults); j3 = 2·j2 + 0.5 = 2·j1 + 0.5; then j3 of a mimic of a
    // mimic: j3 = 3·j2 − 1 with j2 = −0.5·free + 0.25 is −1.5·free − 0.25.
    let text = serial([
        "",
        "<mimic joint=\"j1\"/>",
        "<mimic joint=\"j2\" multiplier=\"2\" offset=\"0.5\"/>",
    ]);
    let c = Urdf::parse(&text)
        .unwrap()
        .chain("a", "d", None::<&[&str]>)
        .unwrap();
    assert_eq!(c.input_names(), ["j1"]);
    assert_eq!(
        c.coupling.unwrap().sources,
        [
            JointSource::Input(0),
            JointSource::Mimic(Mimic::new(0, 1.0, 0.0)),
            JointSource::Mimic(Mimic::new(0, 2.0, 0.5)),
        ]
    );
    let text = serial([
        "",
        "<mimic joint=\"free\" multiplier=\"-0.5\" offset=\"0.25\"/>",
        "<mimic joint=\"j2\" multiplier=\"3\" offset=\"-1\"/>",
    ]);
    let c = Urdf::parse(&text)
        .unwrap()
        .chain("a", "d", None::<&[&str]>)
        .unwrap();
    assert_eq!(c.input_names(), ["j1", "free"]);
    assert_eq!(
        c.coupling.unwrap().sources,
        [
            JointSource::Input(0),
            JointSource::Mimic(Mimic::new(1, -0.5, 0.25)),
            JointSource::Mimic(Mimic::new(1, -1.5, -0.25)),
        ]
    );
}

#[test]
fn a_master_left_out_of_the_list_is_still_an_input() {
    // j1 is frozen (not listed) but j3 follows it: j1's value is an input after j2's.
    let text = serial(["", "", "<mimic joint=\"j1\" multiplier=\"-1\"/>"]);
    let c = Urdf::parse(&text)
        .unwrap()
        .chain("a", "d", Some(&["j2", "j3"][..]))
        .unwrap();
    assert_eq!(c.joint_names(), ["j2", "j3"]);
    assert_eq!(c.input_names(), ["j2", "j1"]);
}

#[test]
fn the_rust_table_holds_the_coupling_in_both_scalars() {
    let c = gripper()
        .chain("base", "left_tip", None::<&[&str]>)
        .unwrap();
    let source = Source {
        file_name: "gripper.urdf".into(),
        sha256: "0".repeat(64),
    };
    let src = ppoe_build::codegen::generate(&c, "ARM", Scalar::Both, &source).unwrap();
    for line in [
        "pub const ARM_COUPLING: ppoe::chain::Coupling<'static, f64> = ppoe::chain::Coupling::new(",
        "pub const ARM_COUPLING_F32: ppoe::chain::Coupling<'static, f32> = ppoe::chain::Coupling::new(",
        "        ppoe::chain::JointSource::Mimic(ppoe::chain::Mimic::new(1, -0.5, 0.1)), // curl",
        "/// * `right_finger`",
    ] {
        assert!(src.lines().any(|l| l == line), "no {line:?} in\n{src}");
    }
    let e = ppoe_build::codegen_c::generate(&c, "ARM", Scalar::F64, &source).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Mimic);
}

#[test]
fn errors() {
    let cases: [(&str, ErrorKind, &[&str]); 4] = [
        (
            "<mimic joint=\"nobody\"/>",
            ErrorKind::UnknownJoint,
            &["'j2'", "'nobody'"],
        ),
        (
            "<mimic joint=\"still\"/>",
            ErrorKind::Mimic,
            &["'j2'", "'still'", "fixed"],
        ),
        (
            "<mimic joint=\"j3\"/>",
            ErrorKind::Mimic,
            &["cycle", "'j2' → 'j3' → 'j2'"],
        ),
        (
            "<mimic joint=\"j1\" multiplier=\"nan\"/>",
            ErrorKind::NonFinite,
            &["multiplier", "NaN"],
        ),
    ];
    for (inner, kind, mentions) in cases {
        let text = serial(["", inner, "<mimic joint=\"j2\"/>"]);
        let e = match Urdf::parse(&text).and_then(|u| u.chain("a", "d", None::<&[&str]>)) {
            Ok(_) => panic!("{inner}: accepted"),
            Err(e) => e,
        };
        assert_eq!(e.kind(), kind, "{e}");
        for m in mentions {
            assert!(e.to_string().contains(m), "{e} lacks {m:?}");
        }
    }
    // An overflowing composition: 1e200·1e200 is not finite.
    let text = serial([
        "",
        "<mimic joint=\"j1\" multiplier=\"1e200\"/>",
        "<mimic joint=\"j2\" multiplier=\"1e200\"/>",
    ]);
    let e = Urdf::parse(&text)
        .unwrap()
        .chain("a", "d", None::<&[&str]>)
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Mimic, "{e}");
    // Off the path, a broken mimic does not matter.
    let text = serial(["", "", ""]).replace(
        "<joint name=\"free\" type=\"revolute\"><parent link=\"a\"/><child link=\"x\"/>",
        "<joint name=\"free\" type=\"revolute\"><parent link=\"a\"/><child link=\"x\"/><mimic joint=\"nobody\"/>",
    );
    assert!(Urdf::parse(&text)
        .unwrap()
        .chain("a", "d", None::<&[&str]>)
        .is_ok());
}

#[test]
fn a_long_chain_of_mimics_is_resolved() {
    // j0 ← j1 ← … ← j4999, each mimicking the one before with offset 0.001: joint k is
    // j0 + 0.001·k (each joint's resolution is remembered, so this is O(n) work; speed
    // itself is for benchmarks, not tests).
    let n = 5000;
    let mut s = String::from("<robot name=\"long\"><link name=\"l0\"/>");
    for k in 0..n {
        let mimic = if k == 0 {
            String::new()
        } else {
            format!("<mimic joint=\"j{}\" offset=\"0.001\"/>", k - 1)
        };
        s.push_str(&format!(
            "<link name=\"l{}\"/><joint name=\"j{k}\" type=\"revolute\"><parent link=\"l{k}\"/>\
             <child link=\"l{}\"/><axis xyz=\"0 0 1\"/>{mimic}</joint>",
            k + 1,
            k + 1
        ));
    }
    s.push_str("</robot>");
    let c = Urdf::parse(&s)
        .unwrap()
        .chain("l0", &format!("l{n}"), None::<&[&str]>)
        .unwrap();
    let sources = c.coupling.unwrap().sources;
    assert_eq!(sources.len(), n);
    for (k, source) in sources.iter().enumerate().skip(1) {
        let JointSource::Mimic(m) = source else {
            panic!("joint {k} is not a mimic joint");
        };
        assert_eq!((m.master, m.multiplier), (0, 1.0));
        assert!(
            (m.offset - 0.001 * k as f64).abs() < 1e-12,
            "{k}: {}",
            m.offset
        );
    }
}
