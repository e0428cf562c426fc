//! COLLADA meshes (issue #30, point 2): the hand-written files of
//! `test_data/packages/ppoe_ur_style/meshes/visual/`, whose triangle counts and bounding
//! boxes their comments derive by hand, and malformed documents as errors.

use ppoe_build::collada::{parse, Mesh};
use std::path::PathBuf;

fn file(name: &str) -> Vec<u8> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../test_data/packages/ppoe_ur_style/meshes/visual");
    std::fs::read(dir.join(name)).unwrap()
}

fn bounds(m: &Mesh) -> [[f64; 2]; 3] {
    let mut b = [[f64::INFINITY, f64::NEG_INFINITY]; 3];
    for t in &m.triangles {
        for &i in t {
            for (k, x) in m.vertices[i as usize].iter().enumerate() {
                b[k] = [b[k][0].min(*x), b[k][1].max(*x)];
            }
        }
    }
    b
}

fn assert_bounds(m: &Mesh, expected: [[f64; 2]; 3]) {
    let b = bounds(m);
    for k in 0..3 {
        for e in 0..2 {
            assert!(
                (b[k][e] - expected[k][e]).abs() < 1e-15,
                "{b:?} vs {expected:?}"
            );
        }
    }
}

#[test]
fn a_cube_of_quads_placed_by_its_scene_node() {
    let m = parse(&file("base.dae")).unwrap();
    assert_eq!(m.triangles.len(), 12);
    assert_bounds(&m, [[-0.05, 0.05], [-0.05, 0.05], [0.0, 0.1]]);
}

#[test]
fn millimetres_and_y_up_are_converted_to_metres_and_z_up() {
    let m = parse(&file("shoulder_mm.dae")).unwrap();
    assert_eq!(m.triangles.len(), 4);
    assert_bounds(&m, [[0.0, 0.1], [-0.1, 0.0], [0.0, 0.1]]);
    // The corner (0, 100, 0) mm, Y up, is 0.1 m straight up.
    assert!(
        m.vertices.iter().any(|p| p == &[0.0, 0.0, 0.1]),
        "{:?}",
        m.vertices
    );
}

/// A one-triangle document with `body` as its `<triangles>`' content and `asset` as its
/// `<asset>`'s.
fn triangle(asset: &str, positions: &str, p: &str) -> String {
    format!(
        r##"<COLLADA><asset>{asset}</asset><library_geometries><geometry id="g"><mesh>
        <source id="s"><float_array count="9">{positions}</float_array></source>
        <vertices id="v"><input semantic="POSITION" source="#s"/></vertices>
        <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>{p}</p></triangles>
        </mesh></geometry></library_geometries></COLLADA>"##
    )
}

#[test]
fn x_up_and_node_transforms() {
    // X up: the document's +x is up (+z), its -y is +x (the specification's axis table).
    let doc = triangle("<up_axis>X_UP</up_axis>", "1 0 0 0 -1 0 0 0 1", "0 1 2");
    let m = parse(doc.as_bytes()).unwrap();
    assert_eq!(
        m.vertices,
        vec![[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]
    );
    // Transforms compose in document order: translate, then rotate 90° about z, so the
    // point (1, 0, 0) goes to (0, 1, 0) and then up by 2.
    let doc = triangle("", "1 0 0 0 1 0 0 0 1", "0 1 2").replace(
        "</library_geometries>",
        r##"</library_geometries><library_visual_scenes><visual_scene id="S">
        <node><translate>0 0 2</translate><rotate>0 0 1 90</rotate>
        <instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
        <scene><instance_visual_scene url="#S"/></scene>"##,
    );
    let m = parse(doc.as_bytes()).unwrap();
    let p = m.vertices[0];
    assert!(
        (p[0]).abs() < 1e-15 && (p[1] - 1.0).abs() < 1e-15 && p[2] == 2.0,
        "{p:?}"
    );
}

#[test]
fn malformed_documents_are_errors_naming_the_problem() {
    for (doc, expected) in [
        (
            String::from_utf8(file("broken.dae")).unwrap(),
            "malformed XML",
        ),
        (
            triangle("", "0 0 0 1 0 0 0 1 0", "0 1 3"),
            "vertex index 3 past the 3 positions",
        ),
        (
            triangle("", "0 0 0 1 0 0 0 1 nan", "0 1 2"),
            "'nan' is not a finite number",
        ),
        (
            triangle("", "0 0 0 1 0 0 0 1 0", "0 1 x"),
            "'x' is not an index",
        ),
        (
            triangle("<unit meter=\"-1\"/>", "0 0 0 1 0 0 0 1 0", "0 1 2"),
            "not a positive number",
        ),
        (
            triangle("<up_axis>W_UP</up_axis>", "0 0 0 1 0 0 0 1 0", "0 1 2"),
            "W_UP",
        ),
        (triangle("", "0 0 0 1 0 0 0 1 0", ""), "no triangles"),
        ("<mesh/>".to_string(), "not <COLLADA>"),
        (
            "<!DOCTYPE COLLADA [<!ENTITY a \"aa\">]><COLLADA/>".to_string(),
            "malformed XML",
        ),
    ] {
        let e = parse(doc.as_bytes()).unwrap_err().to_string();
        assert!(e.contains(expected), "{expected}: {e}");
    }
    assert!(parse(&[0xff, 0xfe])
        .unwrap_err()
        .to_string()
        .contains("not UTF-8"));
}

/// A small file cannot ask for unbounded work: a geometry instanced more often than
/// `MAX_INSTANCES`, or under nodes nested deeper than `MAX_NODE_DEPTH`, is an error.
#[test]
fn instancing_is_bounded() {
    use ppoe_build::collada::{MAX_INSTANCES, MAX_NODE_DEPTH};
    let scene = |nodes: &str| {
        triangle("", "0 0 0 1 0 0 0 1 0", "0 1 2").replace(
            "</library_geometries>",
            &format!(
                "</library_geometries><library_visual_scenes><visual_scene id=\"S\">{nodes}\
                 </visual_scene></library_visual_scenes>"
            ),
        )
    };
    let one = "<node><instance_geometry url=\"#g\"/></node>";
    let m = parse(scene(&one.repeat(3)).as_bytes()).unwrap();
    assert_eq!(m.triangles.len(), 3);
    let e = parse(scene(&one.repeat(MAX_INSTANCES + 1)).as_bytes()).unwrap_err();
    assert!(
        e.to_string()
            .contains("more than 100000 <instance_geometry>"),
        "{e}"
    );
    let deep = format!(
        "{}<instance_geometry url=\"#g\"/>{}",
        "<node>".repeat(MAX_NODE_DEPTH + 1),
        "</node>".repeat(MAX_NODE_DEPTH + 1)
    );
    let e = parse(scene(&deep).as_bytes()).unwrap_err();
    assert!(e.to_string().contains("nested deeper than 1000"), "{e}");
    // 100 triangles instanced 90 000 times would be 9 million triangles.
    let many = triangle("", "0 0 0 1 0 0 0 1 0", &"0 1 2 ".repeat(100))
        .replace("count=\"1\"", "count=\"100\"")
        .replace(
            "</library_geometries>",
            &format!(
                "</library_geometries><library_visual_scenes><visual_scene id=\"S\">{}\
                 </visual_scene></library_visual_scenes>",
                one.repeat(90_000)
            ),
        );
    let e = parse(many.as_bytes()).unwrap_err();
    assert!(e.to_string().contains("more than 8000000 triangles"), "{e}");
}
