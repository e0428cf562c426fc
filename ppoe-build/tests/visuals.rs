//! The visual model (`<visual>`, `<material>`) and the link/joint tree of a parsed URDF:
//! values as written in the file, a malformed visual kept as that visual's error (the URDF
//! and its chain still usable), and the tree's walks.

use ppoe_build::urdf::{Geometry, Material};
use ppoe_build::{ErrorKind, Urdf};

const URDF: &str = r#"<robot name="r">
  <material name="blue"><color rgba="0.1 0.2 1 1"/></material>
  <material name="plain"/>
  <link name="base">
    <visual><origin xyz="0 0 0.05"/><geometry><box size="0.3 0.2 0.1"/></geometry>
      <material name="blue"/></visual>
    <visual><geometry><cylinder radius="0.04" length="0.2"/></geometry></visual>
  </link>
  <link name="arm">
    <visual><origin xyz="1 2 3" rpy="0.3 -1.2 2.5"/><geometry><sphere radius="0.08"/></geometry>
      <material><color rgba="0 0.8 0 0.5"/></material></visual>
    <visual><geometry><mesh filename="package://p/m.stl" scale="0.001 0.001 0.002"/></geometry></visual>
    <visual><geometry><mesh filename="m.obj"/></geometry></visual>
    <visual><geometry/></visual>
    <visual><geometry><capsule radius="1" length="2"/></geometry></visual>
    <visual/>
  </link>
  <link name="tool"/>
  <link name="side"/>
  <joint name="yaw" type="revolute">
    <origin xyz="1 2 3" rpy="0.3 -1.2 2.5"/><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/>
  </joint>
  <joint name="mount" type="fixed"><parent link="arm"/><child link="tool"/></joint>
  <joint name="cam" type="fixed"><parent link="base"/><child link="side"/></joint>
</robot>"#;

#[test]
fn visuals_and_materials_as_written() {
    let urdf = Urdf::parse(URDF).unwrap();
    let ok = |link: usize| -> Vec<_> {
        urdf.links[link]
            .visuals
            .iter()
            .map(|v| v.clone().unwrap())
            .collect()
    };
    let base = ok(0);
    assert_eq!(base.len(), 2);
    assert_eq!(
        base[0].geometry,
        Some(Geometry::Box {
            size: [0.3, 0.2, 0.1]
        })
    );
    assert_eq!(base[0].origin[2][3], 0.05);
    assert_eq!(
        base[0].material,
        Some(Material {
            name: Some("blue".into()),
            rgba: None
        })
    );
    assert_eq!(
        base[1].geometry,
        Some(Geometry::Cylinder {
            radius: 0.04,
            length: 0.2
        })
    );
    assert_eq!(base[1].material, None);
    let arm = ok(1);
    assert_eq!(arm[0].geometry, Some(Geometry::Sphere { radius: 0.08 }));
    assert_eq!(
        arm[0].material.as_ref().unwrap().rgba,
        Some([0.0, 0.8, 0.0, 0.5])
    );
    assert_eq!(
        arm[1].geometry,
        Some(Geometry::Mesh {
            filename: "package://p/m.stl".into(),
            scale: [0.001, 0.001, 0.002]
        })
    );
    assert_eq!(
        arm[2].geometry,
        Some(Geometry::Mesh {
            filename: "m.obj".into(),
            scale: [1.0; 3]
        })
    );
    assert_eq!(arm[3].geometry, Some(Geometry::Empty));
    assert_eq!(
        arm[4].geometry,
        Some(Geometry::Other {
            element: "capsule".into()
        })
    );
    assert_eq!(arm[5].geometry, None);
    assert!(urdf.links[2].visuals.is_empty());
    let materials: Vec<Material> = urdf.materials.iter().map(|m| m.clone().unwrap()).collect();
    assert_eq!(
        materials,
        [
            Material {
                name: Some("blue".into()),
                rgba: Some([0.1, 0.2, 1.0, 1.0])
            },
            Material {
                name: Some("plain".into()),
                rgba: None
            }
        ]
    );
}

/// A visual's `<origin>` is read exactly as a joint's: the same attributes give the same
/// bits.
#[test]
fn visual_origins_are_joint_origins() {
    let urdf = Urdf::parse(URDF).unwrap();
    let visual = urdf.links[1].visuals[0].as_ref().unwrap().origin;
    let joint = urdf.joint("yaw").unwrap().child2parent;
    let bits = |m: [[f64; 4]; 4]| m.map(|r| r.map(f64::to_bits));
    assert_eq!(bits(visual), bits(joint));
    assert_ne!(visual[0][0], 1.0, "the rotation is not the identity");
}

#[test]
fn a_malformed_visual_is_its_own_error() {
    for (geometry, kind) in [
        (
            r#"<cylinder radius="-1" length="0.1"/>"#,
            ErrorKind::InvalidNumber,
        ),
        (
            r#"<cylinder radius="inf" length="0.1"/>"#,
            ErrorKind::NonFinite,
        ),
        (r#"<box size="0.1 0.2"/>"#, ErrorKind::InvalidNumber),
        (r#"<box size="0.1 -0.2 0.3"/>"#, ErrorKind::InvalidNumber),
        (r#"<sphere/>"#, ErrorKind::MissingAttribute),
        (
            r#"<mesh filename="m.stl" scale="1 x 1"/>"#,
            ErrorKind::InvalidNumber,
        ),
    ] {
        let text = format!(
            r#"<robot name="r"><link name="a"><visual><geometry>{geometry}</geometry>
            </visual><visual><geometry><sphere radius="1"/></geometry></visual></link>
            <link name="b"/><joint name="j" type="revolute"><parent link="a"/>
            <child link="b"/></joint></robot>"#
        );
        let urdf = Urdf::parse(&text).unwrap();
        let err = urdf.links[0].visuals[0].clone().unwrap_err();
        assert_eq!(err.kind(), kind, "{geometry}: {err}");
        assert!(err.message().contains("link 'a'"), "{geometry}: {err}");
        assert_eq!(err.position().map(|p| p.line), Some(1), "{geometry}: {err}");
        assert!(urdf.links[0].visuals[1].is_ok(), "{geometry}");
        assert_eq!(urdf.chain::<&str>("a", "b", None).unwrap().joints.len(), 1);
    }
}

#[test]
fn malformed_colours_and_origins() {
    let urdf = Urdf::parse(
        r#"<robot name="r"><material name="m"><color rgba="1 0 0"/></material>
        <link name="a"><visual><origin rpy="0 nan 0"/><geometry><sphere radius="1"/></geometry></visual>
        <visual><geometry><sphere radius="1"/></geometry><material><color rgba="1 0 0 1 0"/></material></visual>
        </link></robot>"#,
    )
    .unwrap();
    let m = urdf.materials[0].clone().unwrap_err();
    assert_eq!(m.kind(), ErrorKind::InvalidNumber, "{m}");
    let o = urdf.links[0].visuals[0].clone().unwrap_err();
    assert_eq!(o.kind(), ErrorKind::NonFinite, "{o}");
    let c = urdf.links[0].visuals[1].clone().unwrap_err();
    assert!(c.message().contains("expected 4 numbers, found 5"), "{c}");
}

#[test]
fn tree_walks() {
    let urdf = Urdf::parse(URDF).unwrap();
    let tree = urdf.tree();
    let roots: Vec<&str> = tree.roots().map(|l| l.name.as_str()).collect();
    assert_eq!(roots, ["base"]);
    let names = |js: &[&ppoe_build::urdf::Joint]| -> Vec<String> {
        js.iter().map(|j| j.name.clone()).collect()
    };
    assert_eq!(names(tree.children("base")), ["yaw", "cam"]);
    assert!(tree.children("tool").is_empty());
    assert_eq!(tree.parent("tool").unwrap().name, "mount");
    assert!(tree.parent("base").is_none());
    assert_eq!(
        names(&tree.joints_above("tool", "base").unwrap()),
        ["mount", "yaw"]
    );
    assert_eq!(tree.joints_above("base", "base").unwrap().len(), 0);
    assert!(tree.joints_above("side", "arm").is_none());
    assert!(tree.joints_above("nowhere", "base").is_none());
}
