//! `ppoe links`: the links and joints of a URDF as a tree, to find the `--base`, `--tip`
//! and `--joints` names.
//!
//! ```text
//! robot 'arm': 4 links, 3 joints (2 moving)
//! base_link
//!   j1: revolute, axis (0, 0, 1), limits [-3, 3] → l1
//!   ├─ j2: prismatic, axis (1, 0, 0), limits [0, 0.5] → l2
//!   └─ cam: fixed → camera
//! ```
//!
//! A mimic joint says whose value it follows: `finger_l: prismatic, axis (0, 1, 0), limits
//! [0, 0.03], mimic of finger_r: 0.8·finger_r + 0.005 → pad_l`.
//!
//! A link's only child joint stays at its parent's indentation, so a serial chain of any
//! length is printed in lines of bounded width; branches are drawn with `├─`/`└─`.

use crate::names::shown;
use ppoe_build::urdf::Joint;
use ppoe_build::Urdf;
use std::fmt::Write as _;

/// One joint's line (without the tree's prefix).
fn joint_line(j: &Joint) -> String {
    let mut s = format!("{}: {}", shown(&j.name), j.joint_type.as_str());
    if j.joint_type.is_moving() || j.joint_type.as_str() == "planar" {
        let [x, y, z] = j.axis;
        let _ = write!(s, ", axis ({x}, {y}, {z})");
    }
    if j.joint_type.is_moving() {
        if j.lower.is_finite() || j.upper.is_finite() {
            let _ = write!(s, ", limits [{}, {}]", j.lower, j.upper);
        } else {
            s.push_str(", no limits");
        }
    }
    if let (Some(m), true) = (&j.mimic, j.joint_type.is_moving()) {
        let _ = write!(
            s,
            ", mimic of {}: {}·{} + {}",
            shown(&m.joint),
            m.multiplier,
            shown(&m.joint),
            m.offset
        );
    }
    let _ = write!(s, " → {}", shown(&j.child));
    s
}

/// The tree as text: a header line, then each root link (a link no joint has as child)
/// with the joints below it, depth first in document order. Iterative, so chains of any
/// depth are fine.
pub fn tree(urdf: &Urdf) -> String {
    let tree = urdf.tree();
    let moving = urdf
        .joints
        .iter()
        .filter(|j| j.joint_type.is_moving())
        .count();
    let mut out = format!(
        "robot '{}': {} links, {} joints ({moving} moving)\n",
        shown(&urdf.name),
        urdf.links.len(),
        urdf.joints.len()
    );
    for root in tree.roots() {
        let _ = writeln!(out, "{}", shown(&root.name));
        // (joint, prefix of its line, connector, prefix of its children)
        let mut stack: Vec<(&Joint, String, &str, String)> = Vec::new();
        push_children(&mut stack, tree.children(&root.name), "  ");
        while let Some((j, prefix, connector, below)) = stack.pop() {
            let _ = writeln!(out, "{prefix}{connector}{}", joint_line(j));
            push_children(&mut stack, tree.children(&j.child), &below);
        }
    }
    out
}

/// Pushes the child joints `kids` of a link (reversed, so they pop in document order).
fn push_children<'a>(
    stack: &mut Vec<(&'a Joint, String, &'static str, String)>,
    kids: &[&'a Joint],
    prefix: &str,
) {
    if let [only] = kids {
        stack.push((only, prefix.to_string(), "", prefix.to_string()));
        return;
    }
    for (i, j) in kids.iter().enumerate().rev() {
        let last = i + 1 == kids.len();
        let (connector, more) = if last {
            ("└─ ", "   ")
        } else {
            ("├─ ", "│  ")
        };
        stack.push((j, prefix.to_string(), connector, format!("{prefix}{more}")));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn branches_and_serial_chains() {
        let urdf = Urdf::parse(
            r#"<robot name="r"><link name="b"/><link name="l1"/><link name="l2"/>
            <link name="c"/><link name="l3"/>
            <joint name="j1" type="revolute"><parent link="b"/><child link="l1"/>
              <axis xyz="0 0 1"/><limit lower="-1" upper="1"/></joint>
            <joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/>
              <axis xyz="1 0 0"/><limit lower="0" upper="0.5"/></joint>
            <joint name="cam" type="fixed"><parent link="l1"/><child link="c"/></joint>
            <joint name="j3" type="continuous"><parent link="l2"/><child link="l3"/></joint>
            </robot>"#,
        )
        .unwrap();
        let expected = "robot 'r': 5 links, 4 joints (3 moving)\n\
                        b\n  \
                        j1: revolute, axis (0, 0, 1), limits [-1, 1] → l1\n  \
                        ├─ j2: prismatic, axis (1, 0, 0), limits [0, 0.5] → l2\n  \
                        │  j3: continuous, axis (1, 0, 0), no limits → l3\n  \
                        └─ cam: fixed → c\n";
        assert_eq!(tree(&urdf), expected);
    }

    #[test]
    fn mimic_joints_name_their_master() {
        let urdf = Urdf::parse(
            r#"<robot name="g"><link name="p"/><link name="a"/><link name="b"/>
            <joint name="r" type="prismatic"><parent link="p"/><child link="a"/>
              <axis xyz="0 1 0"/><limit lower="0" upper="0.04"/></joint>
            <joint name="l" type="prismatic"><parent link="p"/><child link="b"/>
              <axis xyz="0 1 0"/><limit lower="0" upper="0.03"/>
              <mimic joint="r" multiplier="-0.8" offset="0.005"/></joint>
            </robot>"#,
        )
        .unwrap();
        let expected = "robot 'g': 3 links, 2 joints (2 moving)\n\
                        p\n  \
                        ├─ r: prismatic, axis (0, 1, 0), limits [0, 0.04] → a\n  \
                        └─ l: prismatic, axis (0, 1, 0), limits [0, 0.03], mimic of r: \
                        -0.8·r + 0.005 → b\n";
        assert_eq!(tree(&urdf), expected);
    }
}
