//! Hostile input that is not a small file of `test_data/urdf/malformed`: non-ASCII names
//! (a valid robot), trees and cycles of 10⁴ links (generated here), deeply nested XML,
//! huge but finite numbers, and limits that only matter on the chain.

use ppoe_build::{Config, ErrorKind, JointKind, Scalar, Urdf};
use std::time::{Duration, Instant};

mod common;
use common::{rustfmt_available, rustfmt_check, urdf_path};

/// Generous: these take milliseconds; the bound catches quadratic (or worse) behaviour.
const TIME_LIMIT: Duration = Duration::from_secs(2);

const N: usize = 10_000;

// ---------------------------------------------------------------------------------------
// Non-ASCII names

const NON_ASCII_JOINTS: [&str; 4] = ["gelenk_ä", "関節1", "e\u{301}paule", "🦾_wrist"];
const NON_ASCII_BASE: &str = "basis_ä";
const NON_ASCII_TIP: &str = "\"spitze\" \\ 🔧";

/// `None` if rustfmt accepts `source` unchanged (which needs it to parse), else its output;
/// `Some("")`-free: skipped (None) when rustfmt is not installed.
fn rustfmt_complaint(source: &str, tag: &str) -> Option<String> {
    if !rustfmt_available() {
        eprintln!("note: rustfmt not found, skipping the parse check");
        return None;
    }
    rustfmt_check(source, "ppoe-build-hostile", tag)
}

#[test]
fn non_ascii_names_parse_chain_and_generate() {
    let path = urdf_path("non_ascii.urdf");
    let urdf = Urdf::parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(urdf.name, "roboter_ü");
    assert!(urdf.link("ذراع").is_some());
    assert!(urdf.link(NON_ASCII_TIP).is_some());
    assert!(urdf.joint("werkzeug_ß").is_some());

    let mut config = Config::new(&path);
    config.base(NON_ASCII_BASE).tip(NON_ASCII_TIP);
    let chain = config.chain().unwrap();
    assert_eq!(chain.joint_names(), NON_ASCII_JOINTS);
    assert_eq!(chain.robot, "roboter_ü");
    assert_eq!(chain.base, NON_ASCII_BASE);
    assert_eq!(chain.tip, NON_ASCII_TIP);
    let kinds: Vec<JointKind> = chain.joints.iter().map(|j| j.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKind::Revolute,
            JointKind::Revolute,
            JointKind::Prismatic,
            JointKind::Continuous
        ]
    );
    // The names reach the core chain unchanged.
    let core = chain.to_core_chain::<4>().unwrap();
    assert_eq!(core.joints[1].name, "関節1");
    assert_eq!(core.tip, NON_ASCII_TIP);

    // The generated source names every joint: as escaped string literals (printable ASCII
    // only) in the code, as written in the doc comment.
    config.scalar(Scalar::Both);
    let source = config.generate().unwrap();
    for (name, literal) in [
        ("gelenk_ä", r#""gelenk_\u{e4}""#),
        ("関節1", r#""\u{95a2}\u{7bc0}1""#),
        ("e\u{301}paule", r#""e\u{301}paule""#),
        ("🦾_wrist", r#""\u{1f9be}_wrist""#),
        (NON_ASCII_BASE, r#""basis_\u{e4}""#),
        (NON_ASCII_TIP, r#""\"spitze\" \\ \u{1f527}""#),
    ] {
        assert_eq!(
            source.matches(literal).count(),
            2,
            "{literal} once per table in:\n{source}"
        );
        assert!(
            source.contains(name),
            "{name} in the doc comment:\n{source}"
        );
    }
    // Every line of code (not comments) is ASCII.
    for line in source.lines() {
        let code = line.trim_start();
        assert!(
            code.starts_with("//") || code.is_ascii(),
            "non-ASCII code: {line}"
        );
    }
    // The source parses and is formatted (rustfmt fails on a parse error).
    if let Some(complaint) = rustfmt_complaint(&source, "non_ascii") {
        panic!("generated source rejected by rustfmt:\n{complaint}\n{source}");
    }
}

// ---------------------------------------------------------------------------------------
// Large trees and cycles

/// A `<robot>` with links `l0 … l{links-1}` and the given joints (name, type, parent,
/// child, origin xyz, origin rpy).
fn robot(links: usize, joints: &[(String, &str, String, String, String, String)]) -> String {
    let mut s = String::with_capacity(200 * (links + joints.len()));
    s.push_str("<?xml version=\"1.0\"?>\n<robot name=\"big\">\n");
    for i in 0..links {
        s.push_str(&format!("  <link name=\"l{i}\"/>\n"));
    }
    for (name, ty, parent, child, xyz, rpy) in joints {
        s.push_str(&format!(
            "  <joint name=\"{name}\" type=\"{ty}\">\n    <origin xyz=\"{xyz}\" rpy=\"{rpy}\"/>\n    \
             <parent link=\"{parent}\"/>\n    <child link=\"{child}\"/>\n    \
             <axis xyz=\"0 0 1\"/>\n    <limit lower=\"-1\" upper=\"1\"/>\n  </joint>\n"
        ));
    }
    s.push_str("</robot>\n");
    s
}

/// A serial chain l0 → l1 → … → l{n}: revolute joints about z, 1 mm apart along x, with
/// the given rpy.
fn serial(n: usize, rpy: impl Fn(usize) -> String) -> String {
    let joints: Vec<_> = (0..n)
        .map(|i| {
            (
                format!("j{}", i + 1),
                "revolute",
                format!("l{i}"),
                format!("l{}", i + 1),
                "0.001 0 0".to_string(),
                rpy(i),
            )
        })
        .collect();
    robot(n + 1, &joints)
}

#[test]
fn a_serial_chain_of_ten_thousand_links() {
    let text = serial(N, |_| "0 0 0".to_string());
    let start = Instant::now();
    let urdf = Urdf::parse(&text).unwrap();
    let chain = urdf.chain("l0", &format!("l{N}"), None::<&[&str]>).unwrap();
    let elapsed = start.elapsed();
    assert!(elapsed < TIME_LIMIT, "{elapsed:?}");
    assert_eq!(chain.joints.len(), N);
    assert_eq!(chain.joints[0].name, "j1");
    assert_eq!(chain.joints[N - 1].name, format!("j{N}"));
    // Joint i sits at x = i mm, axis z: S = (0, 0, 1, 0, −x, 0).
    for (i, j) in chain.joints.iter().enumerate() {
        let x = (i + 1) as f64 * 0.001;
        let expect = [0.0, 0.0, 1.0, 0.0, -x, 0.0];
        for (got, want) in j.screw.iter().zip(expect) {
            assert!((got - want).abs() < 1e-9, "{}: {:?}", j.name, j.screw);
        }
    }
    assert!((chain.home[0][3] - N as f64 * 0.001).abs() < 1e-9);

    // An explicit list of all 10⁴ joints gives the same chain.
    let names: Vec<String> = (1..=N).map(|i| format!("j{i}")).collect();
    let start = Instant::now();
    let explicit = urdf.chain("l0", &format!("l{N}"), Some(&names)).unwrap();
    assert!(start.elapsed() < TIME_LIMIT, "{:?}", start.elapsed());
    assert_eq!(explicit, chain);

    // A sub-chain deep inside.
    let mid = urdf.chain("l5000", "l5003", None::<&[&str]>).unwrap();
    assert_eq!(mid.joint_names(), ["j5001", "j5002", "j5003"]);
}

/// Paths longer than the exact-order bound (256 joints) are accumulated base to tip; the
/// results agree with the exact evaluation to rounding.
#[test]
fn long_paths_agree_with_the_exact_evaluation_order() {
    let rpy = |i: usize| {
        let a = (i as f64 * 0.37).sin();
        let b = (i as f64 * 0.11).cos() * 0.5;
        format!("{a} {b} 0.2")
    };
    let text = serial(300, rpy);
    let urdf = Urdf::parse(&text).unwrap();
    let long = urdf.chain("l0", "l300", None::<&[&str]>).unwrap(); // 300 joints: base to tip
    let short = urdf.chain("l0", "l256", None::<&[&str]>).unwrap(); // 256: exact order
    for (a, b) in short.joints.iter().zip(&long.joints) {
        assert_eq!(a.name, b.name);
        for k in 0..6 {
            assert!((a.screw[k] - b.screw[k]).abs() < 1e-12, "{}", a.name);
        }
    }
}

#[test]
fn a_star_and_a_comb_of_ten_thousand_links() {
    // Star: l0 with 10⁴ children.
    let joints: Vec<_> = (1..=N)
        .map(|i| {
            (
                format!("j{i}"),
                "revolute",
                "l0".to_string(),
                format!("l{i}"),
                format!("{} 0 0", i as f64 * 1e-3),
                "0 0 0".to_string(),
            )
        })
        .collect();
    let text = robot(N + 1, &joints);
    let start = Instant::now();
    let urdf = Urdf::parse(&text).unwrap();
    let last = urdf.chain("l0", &format!("l{N}"), None::<&[&str]>).unwrap();
    assert!(start.elapsed() < TIME_LIMIT, "{:?}", start.elapsed());
    assert_eq!(last.joint_names(), [format!("j{N}")]);
    assert_eq!(
        urdf.chain("l1", "l2", None::<&[&str]>).unwrap_err().kind(),
        ErrorKind::TipNotBelowBase
    );

    // Comb: a spine l0 → l2 → l4 → … of 5000 joints, each spine link with one leaf.
    let half = N / 2;
    let mut joints = Vec::with_capacity(N);
    for k in 0..half {
        let (spine, next, leaf) = (2 * k, 2 * k + 2, 2 * k + 1);
        joints.push((
            format!("s{k}"),
            "revolute",
            format!("l{spine}"),
            format!("l{next}"),
            "0 0 0.001".to_string(),
            "0 0 0".to_string(),
        ));
        joints.push((
            format!("t{k}"),
            "prismatic",
            format!("l{spine}"),
            format!("l{leaf}"),
            "0.01 0 0".to_string(),
            "0 0 0".to_string(),
        ));
    }
    let text = robot(N + 1, &joints);
    let start = Instant::now();
    let urdf = Urdf::parse(&text).unwrap();
    let spine = urdf.chain("l0", &format!("l{N}"), None::<&[&str]>).unwrap();
    let leaf = urdf.chain("l0", "l4001", None::<&[&str]>).unwrap();
    assert!(start.elapsed() < TIME_LIMIT, "{:?}", start.elapsed());
    assert_eq!(spine.joints.len(), half);
    assert_eq!(leaf.joints.len(), 2001);
    assert_eq!(leaf.joints[2000].name, "t2000");
    assert_eq!(leaf.joints[2000].kind, JointKind::Prismatic);
}

#[test]
fn a_cycle_of_ten_thousand_links() {
    // A base with one child, and a separate ring l1 → l2 → … → l{N} → l1.
    let mut joints: Vec<_> = (1..=N)
        .map(|i| {
            (
                format!("r{i}"),
                "revolute",
                format!("l{i}"),
                format!("l{}", i % N + 1),
                "0.001 0 0".to_string(),
                "0 0 0".to_string(),
            )
        })
        .collect();
    joints.push((
        "stem".to_string(),
        "revolute",
        "l0".to_string(),
        format!("l{}", N + 1),
        "0 0 0".to_string(),
        "0 0 0".to_string(),
    ));
    let text = robot(N + 2, &joints);
    let start = Instant::now();
    let err = Urdf::parse(&text).unwrap_err();
    assert!(start.elapsed() < TIME_LIMIT, "{:?}", start.elapsed());
    assert_eq!(err.kind(), ErrorKind::Cycle, "{err}");
    let message = err.to_string();
    assert!(
        message.contains("cycle") && message.contains("more links"),
        "{message}"
    );
    assert!(message.len() < 400, "the message stays short: {message}");
    assert!(err.position().is_some());
}

/// 10⁵ nested elements inside `<robot>` (ignored, or an error): no stack overflow.
#[test]
fn deeply_nested_xml_does_not_overflow_the_stack() {
    let depth = 100_000;
    let mut text = String::from("<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>");
    text.push_str(&"<visual>".repeat(depth));
    text.push_str(&"</visual>".repeat(depth));
    text.push_str(
        "<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/></joint>\
         </robot>",
    );
    let start = Instant::now();
    // Ok (the nesting is ignored) or an Xml error; run on a thread with the default test
    // stack size, like every test.
    match Urdf::parse(&text) {
        Ok(urdf) => assert_eq!(urdf.joints.len(), 1),
        Err(e) => assert_eq!(e.kind(), ErrorKind::Xml, "{e}"),
    }
    assert!(start.elapsed() < TIME_LIMIT, "{:?}", start.elapsed());
}

// ---------------------------------------------------------------------------------------
// Limits and huge numbers

/// base → l1 (`a`) → l2 (`b`) → tip (`c`), revolute about z; `limits_b` goes into `b`.
fn three_joints(limits_b: &str, origin_b: &str) -> String {
    format!(
        r#"<robot name="r">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="tip"/><link name="side"/>
  <joint name="a" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/></joint>
  <joint name="b" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="{origin_b}"/><axis xyz="0 0 1"/>{limits_b}</joint>
  <joint name="c" type="revolute"><parent link="l2"/><child link="tip"/>
    <origin xyz="0 0.1 0"/><axis xyz="0 0 1"/></joint>
  <joint name="off" type="prismatic"><parent link="base"/><child link="side"/>
    <limit lower="2" upper="-2"/></joint>
</robot>"#
    )
}

#[test]
fn limits_are_checked_only_for_the_moving_joints_of_the_chain() {
    let reversed = Urdf::parse(&three_joints(r#"<limit lower="1" upper="-1"/>"#, "0.2 0 0"))
        .expect("reversed limits are kept at parse time");
    // `off` (reversed) is not on the path: fine.
    let err = reversed.chain("base", "tip", None::<&[&str]>).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::InvalidLimits, "{err}");
    assert!(err.to_string().contains("'b'"), "{err}");
    assert!(err.position().is_some());
    // `b` left out of the list (frozen at 0): its limits do not matter.
    let frozen = reversed.chain("base", "tip", Some(&["a", "c"])).unwrap();
    assert_eq!(frozen.joint_names(), ["a", "c"]);
    // A chain that ends above `b`.
    assert!(reversed.chain("base", "l1", None::<&[&str]>).is_ok());
    // The off-path joint itself, as a chain.
    assert_eq!(
        reversed
            .chain("base", "side", None::<&[&str]>)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLimits
    );

    // lower == upper is a (degenerate) valid range; so are one-sided and infinite ones.
    for ok in [
        r#"<limit lower="0.5" upper="0.5"/>"#,
        r#"<limit lower="-inf" upper="inf"/>"#,
        r#"<limit upper="-3"/>"#,
        r#"<limit lower="3"/>"#,
        "",
    ] {
        let urdf = Urdf::parse(&three_joints(ok, "0.2 0 0")).unwrap();
        urdf.chain("base", "tip", None::<&[&str]>)
            .unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
    for bad in [
        r#"<limit lower="inf"/>"#,
        r#"<limit upper="-inf"/>"#,
        r#"<limit lower="inf" upper="inf"/>"#,
        r#"<limit lower="1e-300" upper="0"/>"#,
    ] {
        let urdf = Urdf::parse(&three_joints(bad, "0.2 0 0")).unwrap();
        let err = urdf.chain("base", "tip", None::<&[&str]>).unwrap_err();
        assert_eq!(err.kind(), ErrorKind::InvalidLimits, "{bad}: {err}");
    }
}

#[test]
fn huge_finite_numbers_are_accepted_until_they_overflow() {
    // 1e300 is finite and so is everything computed from it: an f64 table.
    let urdf = Urdf::parse(&three_joints("", "1e300 0 0")).unwrap();
    let chain = urdf.chain("base", "tip", None::<&[&str]>).unwrap();
    assert!(chain
        .joints
        .iter()
        .flat_map(|j| j.screw)
        .chain(chain.home.into_iter().flatten())
        .all(f64::is_finite));
    assert_eq!(chain.home[0][3], 1e300);
    let dir = std::env::temp_dir().join(format!("ppoe-build-huge-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("huge.urdf");
    std::fs::write(&file, three_joints("", "1e300 0 0")).unwrap();
    let mut config = Config::new(&file);
    config.base("base").tip("tip");
    let source = config.generate().unwrap();
    assert!(source.contains("1e300"), "{source}");
    // An f32 table cannot hold 1e300: NonFinite, naming the joint.
    let err = config.scalar(Scalar::F32).generate().unwrap_err();
    assert_eq!(err.kind(), ErrorKind::NonFinite, "{err}");
    assert!(err.to_string().contains("'b'"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);

    // 1.5e308 + 1.5e308 overflows: NonFinite naming the joint, never a table with inf.
    let text = three_joints("", "1.5e308 0 0").replace(
        r#"<origin xyz="0 0.1 0"/>"#,
        r#"<origin xyz="1.5e308 0 0"/>"#,
    );
    let urdf = Urdf::parse(&text).unwrap();
    let err = urdf.chain("base", "tip", None::<&[&str]>).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::NonFinite, "{err}");
    let message = err.to_string();
    // Joint c's own origin overflows, so its screw axis (and the home pose) would be inf.
    assert!(
        message.contains("screw axis of joint 'c'") && message.contains("at joint 'c'"),
        "{message}"
    );
    // The chain that stops before the overflow is fine.
    assert!(urdf.chain("base", "l2", None::<&[&str]>).is_ok());
}
