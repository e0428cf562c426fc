//! `ppoe links` (issue class: discovery): the tree of a URDF, checked against the file's
//! own text (written by hand from test_data/urdf/tree.urdf).

mod common;
use common::*;

#[test]
fn the_tree_of_tree_urdf() {
    let o = run(&["links", "--urdf", urdf("tree.urdf").to_str().unwrap()]);
    success(&o);
    let text = String::from_utf8(o.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "robot 'two_arm_torso': 21 links, 19 joints (12 moving)"
    );
    assert_eq!(lines[1], "base_footprint");
    assert_eq!(lines[2], "  base_joint: fixed → base_link");
    assert_eq!(
        lines[3],
        "  torso_yaw: revolute, axis (0, 0, 1), limits [-1.57, 1.57] → torso"
    );
    // The torso branches into two arms and a mast.
    assert_eq!(lines[5], "  ├─ left_mount: fixed → left_shoulder_mount");
    assert_eq!(
        lines[6],
        "  │  left_j1: revolute, axis (0, 0, 1), limits [-2.5, 2.5] → left_link1"
    );
    assert!(
        lines.contains(&"  │  right_j4: prismatic, axis (0, 0, 1), limits [0, 0.1] → right_link4")
    );
    assert!(lines.contains(&"  └─ mast_joint: fixed → mast"));
    // A link that no joint connects is a root of its own.
    assert_eq!(*lines.last().unwrap(), "calibration_board");
    // Every joint of the file appears exactly once.
    let file = std::fs::read_to_string(urdf("tree.urdf")).unwrap();
    let joints = file.matches("<joint ").count();
    let listed = lines.iter().filter(|l| l.contains(" → ")).count();
    assert_eq!(listed, joints);
}

#[test]
fn a_long_serial_chain_stays_narrow() {
    // 2000 joints in series: one line each, none wider than the widest joint line.
    let n = 2000;
    let mut u = String::from(r#"<robot name="long"><link name="l0"/>"#);
    for i in 1..=n {
        u.push_str(&format!(
            r#"<link name="l{i}"/><joint name="j{i}" type="continuous"><parent link="l{}"/><child link="l{i}"/><axis xyz="0 0 1"/></joint>"#,
            i - 1
        ));
    }
    u.push_str("</robot>");
    let o = run_bytes(&["links", "--urdf", "-"], u.as_bytes());
    success(&o);
    let text = String::from_utf8(o.stdout).unwrap();
    assert_eq!(text.lines().count(), n + 2);
    assert!(text.lines().all(|l| l.chars().count() < 80));
    assert!(text.contains("\n  j2000: continuous, axis (0, 0, 1), no limits → l2000\n"));
}
