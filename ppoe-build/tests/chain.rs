//! Chain extraction: the seed robot against an independent computation, the lenient parts of
//! URDF parsing, and every error kind on small inline files.

#![allow(clippy::needless_range_loop)] // index loops read best for matrices

use ppoe_build::{ErrorKind, JointKind, RobotChain, Urdf};

const NONE: Option<&[&str]> = None;

fn chain(text: &str, base: &str, tip: &str) -> RobotChain {
    Urdf::parse(text).unwrap().chain(base, tip, NONE).unwrap()
}

fn chain_with(text: &str, base: &str, tip: &str, joints: &[&str]) -> RobotChain {
    Urdf::parse(text)
        .unwrap()
        .chain(base, tip, Some(joints))
        .unwrap()
}

fn error(text: &str, base: &str, tip: &str, joints: Option<&[&str]>) -> ppoe_build::Error {
    match Urdf::parse(text).and_then(|u| u.chain(base, tip, joints)) {
        Ok(c) => panic!("accepted: {:?}", c.joint_names()),
        Err(e) => e,
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    a == b || (a - b).abs() <= tol
}

// ---------------------------------------------------------------------------------------
// An independent home-pose computation: the closed-form URDF rpy matrix and plain products.

type M4 = [[f64; 4]; 4];

fn origin(xyz: [f64; 3], rpy: [f64; 3]) -> M4 {
    let (sr, cr) = rpy[0].sin_cos();
    let (sp, cp) = rpy[1].sin_cos();
    let (sy, cy) = rpy[2].sin_cos();
    [
        [
            cy * cp,
            cy * sp * sr - sy * cr,
            cy * sp * cr + sy * sr,
            xyz[0],
        ],
        [
            sy * cp,
            sy * sp * sr + cy * cr,
            sy * sp * cr - cy * sr,
            xyz[1],
        ],
        [-sp, cp * sr, cp * cr, xyz[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn mul(a: &M4, b: &M4) -> M4 {
    let mut c = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            c[i][j] = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

const SEED: &str = include_str!("../../test_data/urdf/seed.urdf");

/// The seed's roll angle: 1.570796, deliberately not π/2.
#[allow(clippy::approx_constant)]
const SEED_ROLL: f64 = 1.570796;

/// The pose of each link of the seed chain in the base frame (`link2base[0]` is joint1's
/// child, the last one the tip): the product of the URDF origins, tip to base, computed
/// independently of ppoe-build.
fn seed_link2base() -> Vec<[[f64; 4]; 4]> {
    let a = SEED_ROLL;
    let origins = [
        origin([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        origin([0.0, 0.0, 0.158], [a, 0.0, 0.0]),
        origin([0.0, 0.28, 0.0], [0.0, 0.0, 0.0]),
        origin([0.0, 0.0, 0.0], [-a, 0.0, 0.0]),
        origin([0.0, 0.0, 0.34], [a, 0.0, 0.0]),
        origin([0.0, 0.346, 0.0], [-a, 0.0, 0.0]),
        origin([0.0, 0.0, 0.05], [0.0, 0.0, 0.0]),
    ];
    let mut link2base = Vec::new();
    let mut t = origins[0];
    link2base.push(t);
    for o in &origins[1..] {
        t = mul(&t, o);
        link2base.push(t);
    }
    link2base
}

#[test]
fn seed_screw_axes_in_closed_form() {
    let c = chain(SEED, "linkmount", "tcp");
    assert_eq!(c.robot, "seed_arm");
    assert_eq!(
        c.joint_names(),
        ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"]
    );
    assert!(c.joints.iter().all(|j| j.kind == JointKind::Revolute));

    // Joint 1: axis z through the origin, exactly.
    assert_eq!(c.joints[0].screw, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);

    // Joints 2 and 3: axis −z of a frame rolled by a = 1.570796 (not π/2): direction
    // s = (0, sin a, −cos a). Joint 2 passes through q = (0, 0, 0.158): v = q × s =
    // (−0.158 sin a, 0, 0); joint 3 through q + 0.28·(0, cos a, sin a):
    // v_x = −0.28 (cos²a + sin²a) − 0.158 sin a.
    let a = SEED_ROLL;
    let expect2 = [0.0, a.sin(), -a.cos(), -0.158 * a.sin(), 0.0, 0.0];
    let expect3 = [0.0, a.sin(), -a.cos(), -0.28 - 0.158 * a.sin(), 0.0, 0.0];
    for (i, expect) in [(1, expect2), (2, expect3)] {
        let s = c.joints[i].screw;
        for k in 0..6 {
            assert!(close(s[k], expect[k], 1e-15), "joint{} [{k}]: {s:?}", i + 1);
        }
    }
    // The small non-zero entries the roll of 1.570796 instead of π/2 leaves.
    assert_eq!(c.joints[1].screw[2], -3.2679489653813835e-7);
    assert!(close(c.joints[3].screw[3], 9.15e-8, 1e-10));
}

#[test]
fn seed_home_pose_axes_and_frames_from_the_origins() {
    let c = chain(SEED, "linkmount", "tcp");
    let link2base = seed_link2base();
    let t = link2base[link2base.len() - 1];
    for r in 0..4 {
        for k in 0..4 {
            assert!(close(c.home[r][k], t[r][k], 1e-15), "M[{r}][{k}]");
        }
    }
    assert!(close(c.home[2][3], 1.174, 1e-12));
    // Each screw axis: s = R(L)·axis, v = p(L) × s.
    let axes = [1.0, -1.0, -1.0, 1.0, -1.0, 1.0];
    for (i, j) in c.joints.iter().enumerate() {
        let l = &link2base[i];
        let s = [l[0][2] * axes[i], l[1][2] * axes[i], l[2][2] * axes[i]];
        let q = [l[0][3], l[1][3], l[2][3]];
        let v = [
            q[1] * s[2] - q[2] * s[1],
            q[2] * s[0] - q[0] * s[2],
            q[0] * s[1] - q[1] * s[0],
        ];
        for k in 0..3 {
            assert!(close(j.screw[k], s[k], 1e-15), "{} ω[{k}]", j.name);
            assert!(close(j.screw[3 + k], v[k], 1e-15), "{} v[{k}]", j.name);
        }
    }

    // The home frames are those products: the pose of each joint's child link.
    let frames = c.home_frames();
    assert_eq!(frames.len(), 6);
    for (i, f) in frames.iter().enumerate() {
        assert_eq!(*f, c.joints[i].home_frame);
        for r in 0..4 {
            for k in 0..4 {
                assert!(
                    close(f[r][k], link2base[i][r][k], 1e-15),
                    "frame {i} [{r}][{k}]: {} vs {}",
                    f[r][k],
                    link2base[i][r][k]
                );
            }
        }
    }
}

#[test]
fn seed_limits_and_core_types() {
    let c = chain(SEED, "linkmount", "tcp");
    // Limits as written: joint2 has only `lower`, joint3 only `upper`, 4-6 no <limit>.
    let inf = f64::INFINITY;
    let limits: Vec<(f64, f64)> = c.joints.iter().map(|j| (j.lower, j.upper)).collect();
    assert_eq!(
        limits,
        [
            (-1.0, 1.0),
            (-1.0, inf),
            (-inf, 1.0),
            (-inf, inf),
            (-inf, inf),
            (-inf, inf)
        ]
    );

    // The core types.
    let joints = c.to_core_joints();
    assert_eq!(joints[2].name, "joint3");
    assert_eq!(joints[2].screw.0, c.joints[2].screw);
    let core: ppoe::chain::Chain<f64, 6> = c.to_core_chain().unwrap();
    assert_eq!(core.home.to_matrix4(), c.home);
    assert_eq!(
        c.to_core_chain::<5>().unwrap_err().kind(),
        ErrorKind::Config
    );
}

fn robot(body: &str) -> String {
    format!("<?xml version=\"1.0\"?>\n<robot name=\"r\">\n{body}\n</robot>\n")
}

fn links(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("<link name=\"{n}\"/>"))
        .collect::<Vec<_>>()
        .join("\n")
}

fn joint(name: &str, ty: &str, parent: &str, child: &str, inner: &str) -> String {
    format!(
        "<joint name=\"{name}\" type=\"{ty}\"><parent link=\"{parent}\"/>\
         <child link=\"{child}\"/>{inner}</joint>"
    )
}

/// A robot of the given links and joints (each from `joint`).
fn robot_of(names: &[&str], joints: &[String]) -> String {
    robot(&format!("{}{}", links(names), joints.concat()))
}

// ---------------------------------------------------------------------------------------
// Leniency.

#[test]
fn whitespace_between_numbers_is_any_whitespace() {
    let plain = two_links("<origin xyz=\"0.1 0.2 0.3\" rpy=\"0.4 0.5 0.6\"/><axis xyz=\"0 1 0\"/>");
    let spaced = two_links(
        "<origin xyz=\"  0.1\t0.2\n\n 0.3 \" rpy=\"\n0.4&#9;0.5&#10;0.6\"/>\
         <axis xyz=\"\t0 1e0   +0.0 \"/>",
    );
    assert_eq!(chain(&plain, "a", "b"), chain(&spaced, "a", "b"));
}

#[test]
fn missing_origin_axis_and_limit_take_the_defaults() {
    let j2 = "<origin xyz=\"1 0 0\"/><axis/><limit effort=\"1\"/>";
    let j3 = "<origin rpy=\"0 0 0\"/><limit lower=\"-0.5\"/>";
    let text = robot_of(
        &["a", "b", "c", "d"],
        &[
            bare("j1", "revolute", "a", "b"),
            joint("j2", "continuous", "b", "c", j2),
            joint("j3", "prismatic", "c", "d", j3),
        ],
    );
    let c = chain(&text, "a", "d");
    let inf = f64::INFINITY;
    // Axis (1, 0, 0) everywhere.
    assert_eq!(c.joints[0].screw, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    assert_eq!(c.joints[1].screw, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    assert_eq!(c.joints[2].screw, [0.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
    assert_eq!(c.joints[1].kind, JointKind::Continuous);
    assert_eq!(c.joints[2].kind, JointKind::Prismatic);
    assert_eq!((c.joints[0].lower, c.joints[0].upper), (-inf, inf));
    assert_eq!((c.joints[1].lower, c.joints[1].upper), (-inf, inf));
    assert_eq!((c.joints[2].lower, c.joints[2].upper), (-0.5, inf));
    assert_eq!(c.home[0][3], 1.0);
}

#[test]
fn axes_are_normalised_and_continuous_limits_are_kept() {
    let j1 = "<origin xyz=\"0 0 1\"/><axis xyz=\"0 -3 4\"/>\
              <limit lower=\" -6.5 \" upper=\"inf\"/>";
    let text = robot_of(
        &["a", "b", "c"],
        &[
            joint("j1", "continuous", "a", "b", j1),
            joint("j2", "prismatic", "b", "c", "<axis xyz=\"0 0 2\"/>"),
        ],
    );
    let c = chain(&text, "a", "c");
    let s = c.joints[0].screw;
    assert_eq!(&s[..3], &[0.0, -0.6, 0.8]);
    // q = (0, 0, 1): v = q × s = (0·0.8 − 1·(−0.6), 1·0 − 0·0.8, 0) = (0.6, 0, 0).
    assert_eq!(&s[3..], &[0.6, 0.0, 0.0]);
    assert_eq!(
        (c.joints[0].lower, c.joints[0].upper),
        (-6.5, f64::INFINITY)
    );
    assert_eq!(c.joints[1].screw, [0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
}

#[test]
fn namespaces_comments_and_unknown_elements_are_ignored() {
    let text = r#"<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE robot>
<!-- a comment -->
<robot name="ns" xmlns="http://example.org/urdf" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="len" value="0.5"/>
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="a">
    <visual><origin xyz="9 9 9"/><geometry><box size="1 1 1"/></geometry></visual>
    <collision><geometry><mesh filename="package://x.stl"/></geometry></collision>
    <inertial><origin xyz="5 5 5"/><mass value="1"/></inertial>
  </link>
  <link name="b"/>
  <!-- <joint name="commented_out" type="planar"/> -->
  <joint name="j" type="revolute">
    <?processing instruction?>
    <origin xyz="0 0 0.5"/>
    <parent link="a"/>
    <child link="b"/>
    <axis xyz="0 0 1"/>
    <dynamics damping="0.1"/>
    <safety_controller k_velocity="1"/>
    <calibration rising="0"/>
  </joint>
  <transmission name="t"><joint name="j"/></transmission>
  <gazebo reference="a"><material>Gazebo/Blue</material></gazebo>
</robot>"#;
    let c = chain(text, "a", "b");
    assert_eq!(c.joints[0].screw, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    assert_eq!(c.home[2][3], 0.5);
    // A byte-order mark is fine too.
    let with_bom = format!("\u{feff}{text}");
    assert_eq!(chain(&with_bom, "a", "b"), c);
    assert_eq!(Urdf::parse_bytes(with_bom.as_bytes()).unwrap().name, "ns");
}

#[test]
fn fixed_joints_are_folded_in_and_off_path_problems_do_not_matter() {
    let mount = "<origin xyz=\"0 0 1\" rpy=\"0 0 1.5707963267948966\"/><axis xyz=\"0 0 0\"/>";
    let x = "<axis xyz=\"1 0 0\"/>";
    let text = robot_of(
        &["w", "a", "b", "c", "tip", "side", "side2"],
        &[
            joint("mount", "fixed", "w", "a", mount),
            joint("j1", "revolute", "a", "b", x),
            joint("between", "fixed", "b", "c", "<origin xyz=\"2 0 0\"/>"),
            joint("j2", "prismatic", "c", "tip", x),
            // Off the path: a planar joint and a mimic joint with a zero axis.
            bare("plane", "planar", "w", "side"),
            joint(
                "follower",
                "revolute",
                "side",
                "side2",
                "<axis xyz=\"0 0 0\"/><mimic joint=\"j1\"/>",
            ),
        ],
    );
    let u = Urdf::parse(&text).unwrap();
    let fixed = u.joint("mount").unwrap();
    assert_eq!((fixed.lower, fixed.upper), (0.0, 0.0));
    let c = u.chain("w", "tip", NONE).unwrap();
    assert_eq!(c.joint_names(), ["j1", "j2"]);
    // The yaw of the mount turns x into y.
    let s1 = c.joints[0].screw;
    assert!(close(s1[0], 0.0, 1e-15) && close(s1[1], 1.0, 1e-15) && s1[2] == 0.0);
    // j1 passes through (0, 0, 1): v = q × s = (0, 0, 1) × (0, 1, 0) = (−1, 0, 0).
    assert!(close(s1[3], -1.0, 1e-15) && close(s1[4], 0.0, 1e-15));
    let s2 = c.joints[1].screw;
    assert!(close(s2[4], 1.0, 1e-15) && s2[..3] == [0.0; 3]);
    // The tip is 2 along the mount's y... i.e. along base y.
    assert!(close(c.home[1][3], 2.0, 1e-15) && close(c.home[2][3], 1.0, 1e-15));
    // Home frames fold the fixed joints in: j1's child at (0, 0, 1) turned by the yaw, j2's
    // child (a prismatic joint with no origin) at the tip.
    let f = c.home_frames();
    let yaw = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    for (frame, p) in f.iter().zip([[0.0, 0.0, 1.0], [0.0, 2.0, 1.0]]) {
        for r in 0..3 {
            for k in 0..3 {
                assert!(close(frame[r][k], yaw[r][k], 1e-15), "{frame:?}");
            }
            assert!(close(frame[r][3], p[r], 1e-15), "{frame:?}");
        }
        assert_eq!(frame[3], [0.0, 0.0, 0.0, 1.0]);
    }
}

#[test]
fn an_explicit_list_may_freeze_moving_joints() {
    let hinge = |name, parent, child, axis| {
        let inner = format!("<origin xyz=\"1 0 0\"/><axis xyz=\"{axis}\"/>");
        joint(name, "revolute", parent, child, &inner)
    };
    let text = robot_of(
        &["a", "b", "c", "d"],
        &[
            hinge("j1", "a", "b", "0 0 1"),
            // Frozen at 0: even a zero axis does not matter.
            hinge("j2", "b", "c", "0 0 0"),
            hinge("j3", "c", "d", "0 0 1"),
        ],
    );
    let all = error(&text, "a", "d", None);
    assert_eq!(all.kind(), ErrorKind::ZeroAxis);
    let c = chain_with(&text, "a", "d", &["j1", "j3"]);
    assert_eq!(c.joint_names(), ["j1", "j3"]);
    assert_eq!(c.joints[1].screw, [0.0, 0.0, 1.0, 0.0, -3.0, 0.0]);
    assert_eq!(c.home[0][3], 3.0);
    // The frozen joint's origin is in j3's home frame; j2 has none.
    let origins: Vec<f64> = c.home_frames().iter().map(|f| f[0][3]).collect();
    assert_eq!(origins, [1.0, 3.0]);
}

#[test]
fn unbounded_limits_may_be_written_out() {
    let text = two_links("<limit lower=\"-inf\" upper=\"Infinity\"/>");
    let c = chain(&text, "a", "b");
    assert_eq!(
        (c.joints[0].lower, c.joints[0].upper),
        (f64::NEG_INFINITY, f64::INFINITY)
    );
}

// ---------------------------------------------------------------------------------------
// Every error kind.

/// A robot of links `a` and `b` and one joint `j` of type `ty` from `a` to `b`.
fn one_joint(ty: &str, inner: &str) -> String {
    robot_of(&["a", "b"], &[joint("j", ty, "a", "b", inner)])
}

fn two_links(inner: &str) -> String {
    one_joint("revolute", inner)
}

/// A joint without origin, axis or limit.
fn bare(name: &str, ty: &str, parent: &str, child: &str) -> String {
    joint(name, ty, parent, child, "")
}

/// Links `a`, `b`, `c` and fixed joints `j1` and `j2` from parent to child.
fn fixed_pair(j1: [&str; 2], j2: [&str; 2]) -> String {
    let joints = [
        bare("j1", "fixed", j1[0], j1[1]),
        bare("j2", "fixed", j2[0], j2[1]),
    ];
    robot_of(&["a", "b", "c"], &joints)
}

/// `text` with a link `c` and the joint `extra` added at the end.
fn with_c(text: &str, extra: String) -> String {
    text.replace("</robot>", &format!("{}{}</robot>", links(&["c"]), extra))
}

/// A request that must fail: the error kind and what its message must mention.
struct Case {
    kind: ErrorKind,
    text: String,
    base: &'static str,
    tip: &'static str,
    joints: Option<&'static [&'static str]>,
    mentions: &'static [&'static str],
}

/// A request from `a` to `b`, all moving joints.
fn case(kind: ErrorKind, text: impl Into<String>, mentions: &'static [&'static str]) -> Case {
    Case {
        kind,
        text: text.into(),
        base: "a",
        tip: "b",
        joints: None,
        mentions,
    }
}

impl Case {
    fn path(self, base: &'static str, tip: &'static str) -> Self {
        Case { base, tip, ..self }
    }

    fn joints(self, joints: &'static [&'static str]) -> Self {
        let joints = Some(joints);
        Case { joints, ..self }
    }
}

/// Malformed documents and values: one case per way of getting them wrong.
fn document_error_cases() -> Vec<Case> {
    use ErrorKind as K;
    let far = "<origin xyz=\"1e308 0 0\"/>";
    let orphan = "<joint name=\"j\" type=\"fixed\"><child link=\"b\"/></joint>".to_string();
    vec![
        case(
            K::Xml,
            "<robot name=\"r\"><link name=\"a\"></robot>",
            &["1:"],
        ),
        case(K::Xml, "", &["1:1"]),
        case(K::NotARobot, "<model name=\"x\"/>", &["model", "robot"]),
        case(K::MissingAttribute, "<robot/>", &["robot", "name"]),
        case(K::MissingAttribute, robot("<link/>"), &["link", "name"]),
        case(
            K::MissingAttribute,
            robot("<link name=\"\"/>"),
            &["name", "empty"],
        ),
        case(
            K::MissingAttribute,
            robot_of(&["a", "b"], &[orphan]),
            &["'j'", "parent"],
        ),
        case(
            K::InvalidNumber,
            two_links("<origin xyz=\"0 0 x\"/>"),
            &["'j'", "origin", "xyz", "\"x\""],
        ),
        case(
            K::InvalidNumber,
            two_links("<origin rpy=\"0 0\"/>"),
            &["rpy", "expected 3 numbers, found 2"],
        ),
        case(
            K::InvalidNumber,
            two_links("<axis xyz=\"1,0,0\"/>"),
            &["axis", "xyz"],
        ),
        case(
            K::InvalidNumber,
            two_links("<limit upper=\"1.5rad\"/>"),
            &["limit", "upper"],
        ),
        case(
            K::NonFinite,
            two_links("<origin xyz=\"0 NaN 0\"/>"),
            &["origin", "xyz", "NaN"],
        ),
        case(
            K::NonFinite,
            two_links("<axis xyz=\"0 0 1e400\"/>"),
            &["axis", "inf"],
        ),
        case(
            K::NonFinite,
            two_links("<limit lower=\"nan\"/>"),
            &["limit", "lower"],
        ),
        case(
            K::NonFinite,
            with_c(&two_links(far), joint("k", "fixed", "b", "c", far)),
            &["home", "not finite"],
        )
        .path("a", "c"),
    ]
}

/// Well-formed documents whose tree or request is wrong.
fn tree_error_cases() -> Vec<Case> {
    use ErrorKind as K;
    let ok = two_links("");
    vec![
        case(
            K::UnknownLink,
            robot_of(&["a"], &[bare("j", "fixed", "a", "nowhere")]),
            &["nowhere", "'j'"],
        ),
        case(K::UnknownLink, ok.clone(), &["zz", "tip"]).path("a", "zz"),
        case(K::UnknownJoint, ok.clone(), &["nope"]).joints(&["nope"]),
        case(
            K::DuplicateName,
            robot_of(&["a", "a"], &[]),
            &["link 'a'", "twice"],
        ),
        case(
            K::DuplicateName,
            with_c(&ok, bare("j", "fixed", "b", "c")),
            &["joint 'j'", "twice"],
        )
        .path("a", "c"),
        case(K::DuplicateName, ok.clone(), &["'j'", "twice"]).joints(&["j", "j"]),
        case(
            K::MultipleParents,
            fixed_pair(["a", "c"], ["b", "c"]),
            &["'c'", "j1", "j2"],
        )
        .path("a", "c"),
        case(
            K::Cycle,
            fixed_pair(["b", "c"], ["c", "b"]),
            &["b", "c", "cycle"],
        )
        .path("a", "c"),
        case(
            K::Cycle,
            robot_of(&["a"], &[bare("j", "fixed", "a", "a")]),
            &["'a'", "own parent"],
        )
        .path("a", "a"),
        case(K::TipNotBelowBase, ok.clone(), &["'a'", "'b'"]).path("b", "a"),
        case(K::TipNotBelowBase, ok.clone(), &["'a'", "base"]).path("a", "a"),
        case(K::NotMovable, one_joint("fixed", ""), &["'j'", "fixed"]).joints(&["j"]),
        case(K::NotMovable, one_joint("fixed", ""), &["no moving joint"]),
        case(
            K::UnsupportedJointType,
            one_joint("floating", ""),
            &["'j'", "floating"],
        ),
        case(
            K::UnsupportedJointType,
            one_joint("ball", ""),
            &["'j'", "ball"],
        ),
        case(
            K::ZeroAxis,
            two_links("<axis xyz=\"0 0 0\"/>"),
            &["'j'", "axis"],
        ),
        case(
            K::InvalidLimits,
            two_links("<limit lower=\"1\" upper=\"-1\"/>"),
            &["'j'", "lower=\"1\"", "upper=\"-1\""],
        ),
        case(
            K::UnknownJoint,
            two_links("<mimic joint=\"other\" multiplier=\"2\"/>"),
            &["'j'", "mimics", "'other'"],
        ),
        case(
            K::Mimic,
            robot_of(
                &["a", "b"],
                &[joint("j", "revolute", "a", "b", "<mimic joint=\"j\"/>")],
            ),
            &["'j'", "cycle"],
        ),
        case(
            K::NotOnPath,
            with_c(&ok, bare("k", "revolute", "a", "c")),
            &["'k'", "path"],
        )
        .joints(&["k"]),
        case(
            K::NotOnPath,
            with_c(&ok, bare("k", "revolute", "b", "c")),
            &["'j'", "'k'", "order"],
        )
        .path("a", "c")
        .joints(&["k", "j"]),
    ]
}

#[test]
fn every_error_kind() {
    use ErrorKind as K;
    let mut cases = document_error_cases();
    cases.extend(tree_error_cases());
    let mut seen = std::collections::HashSet::new();
    for c in &cases {
        let e = error(&c.text, c.base, c.tip, c.joints);
        let shown = e.to_string();
        let (kind, text) = (c.kind, &c.text);
        assert_eq!(e.kind(), kind, "{shown}\n{text}");
        for m in c.mentions {
            assert!(shown.contains(m), "{kind:?}: {shown:?} lacks {m:?}");
        }
        seen.insert(e.kind());
    }
    for kind in [
        K::Xml,
        K::NotARobot,
        K::MissingAttribute,
        K::InvalidNumber,
        K::NonFinite,
        K::UnknownLink,
        K::UnknownJoint,
        K::DuplicateName,
        K::MultipleParents,
        K::Cycle,
        K::TipNotBelowBase,
        K::NotMovable,
        K::UnsupportedJointType,
        K::ZeroAxis,
        K::InvalidLimits,
        K::Mimic,
        K::NotOnPath,
    ] {
        assert!(seen.contains(&kind), "{kind:?} not covered");
    }
}

#[test]
fn errors_point_at_the_attribute() {
    let text = "<robot name=\"r\">\n  <link name=\"a\"/>\n  <link name=\"b\"/>\n  \
                <joint name=\"j\" type=\"revolute\">\n    <parent link=\"a\"/>\n    \
                <child link=\"b\"/>\n    <origin xyz=\"0 0 oops\"/>\n  </joint>\n</robot>\n";
    let e = Urdf::parse(text).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidNumber);
    let p = e.position().unwrap();
    assert_eq!((p.line, p.column), (7, 18));
    assert!(e
        .to_string()
        .starts_with("7:18: joint 'j': <origin xyz=\"0 0 oops\">"));
    assert_eq!(ErrorKind::InvalidNumber.to_string(), "InvalidNumber");
}
