//! COLLADA (`.dae`) meshes, the visuals of most ROS-Industrial URDFs, read into triangles
//! for the pictures (ppoe-build is the one XML reader of the workspace).
//!
//! What is read: every `<geometry>`'s `<mesh>` (`<triangles>`, `<polylist>` and
//! `<polygons>`; polygons are split into fans), placed by the `<node>`s of the scene's
//! `<visual_scene>` that instance it (`<matrix>`, `<translate>`, `<rotate>`, `<scale>`,
//! composed in document order as COLLADA specifies); a document without a scene node
//! instancing a geometry draws every geometry once, untransformed. Then the two asset
//! settings that change where a vertex is:
//!
//! * `<unit meter="m">`: every coordinate is multiplied by `m` (a file in millimetres has
//!   `meter="0.001"`), so the result is in metres before the URDF's own `scale`;
//! * `<up_axis>`: `Y_UP` and `X_UP` documents are rotated so that their up axis is +Z,
//!   as the COLLADA specification's axis table defines (`Y_UP`: (x, y, z) → (x, −z, y);
//!   `X_UP`: (x, y, z) → (−y, −z, x)); `Z_UP` (the URDF convention) is unchanged.
//!
//! Not read: materials and textures (the URDF's material colours the mesh), lines,
//! `<tristrips>`/`<trifans>`, `<instance_node>`, controllers and animations. A document
//! type declaration is refused (no entity expansion to bound).

use crate::error::{Error, ErrorKind, Result};
use roxmltree::{Document, Node};
use std::collections::HashMap;

/// A COLLADA document's triangles, in metres, Z up.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// The vertices (finite).
    pub vertices: Vec<[f64; 3]>,
    /// Triangles: three indices into `vertices` each.
    pub triangles: Vec<[u32; 3]>,
}

/// The most triangles a document may make. A geometry instanced by many nodes is copied
/// once per instance, so a small file could otherwise ask for any number; 8 million is
/// six times a 64 MiB binary STL's, and the pictures reduce meshes far below it.
pub const MAX_TRIANGLES: usize = 8_000_000;

/// The most `<instance_geometry>` elements, and the deepest `<node>` nesting, read: a
/// bound on the work of placing them (each instance multiplies its ancestors' transforms).
pub const MAX_INSTANCES: usize = 100_000;

/// See [`MAX_INSTANCES`].
pub const MAX_NODE_DEPTH: usize = 1_000;

type M4 = [[f64; 4]; 4];

const IDENTITY: M4 = [
    [1., 0., 0., 0.],
    [0., 1., 0., 0.],
    [0., 0., 1., 0.],
    [0., 0., 0., 1.],
];

fn mul(a: &M4, b: &M4) -> M4 {
    let mut c = [[0.0; 4]; 4];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn apply(m: &M4, p: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3])
}

fn err(node: Node<'_, '_>, message: String) -> Error {
    let p = node.document().text_pos_at(node.range().start);
    Error::new(ErrorKind::Xml, message).at(Some(crate::error::Position {
        line: p.row,
        column: p.col,
    }))
}

/// Parses a COLLADA document's bytes (UTF-8).
///
/// # Errors
/// Malformed XML, a document type declaration, a number that is not finite, an index
/// past its source, a reference to a missing element, or no triangles at all; the
/// message names the element and its line.
pub fn parse(bytes: &[u8]) -> Result<Mesh> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| Error::new(ErrorKind::Xml, format!("not UTF-8 ({e})")))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let doc = Document::parse(text)
        .map_err(|e| Error::new(ErrorKind::Xml, format!("malformed XML: {e}")))?;
    let root = doc.root_element();
    if root.tag_name().name() != "COLLADA" {
        return Err(err(root, "the root element is not <COLLADA>".into()));
    }
    let geometries: HashMap<&str, Node<'_, '_>> = root
        .descendants()
        .filter(|n| is(n, "geometry"))
        .filter_map(|n| Some((n.attribute("id")?, n)))
        .collect();
    let mut mesh = Mesh::default();
    let placed = instances(root)?;
    if placed.is_empty() {
        for g in root.descendants().filter(|n| is(n, "geometry")) {
            add_geometry(g, &IDENTITY, &mut mesh)?;
        }
    }
    for (url, m) in &placed {
        let g = geometries.get(url.as_str()).ok_or_else(|| {
            Error::new(
                ErrorKind::Xml,
                format!("<instance_geometry url=\"#{url}\">: no such <geometry>"),
            )
        })?;
        add_geometry(*g, m, &mut mesh)?;
    }
    let asset = asset_transform(root)?;
    for v in &mut mesh.vertices {
        *v = apply(&asset, *v);
    }
    if mesh.triangles.is_empty() {
        return Err(Error::new(ErrorKind::Xml, "no triangles".to_string()));
    }
    Ok(mesh)
}

fn is(n: &Node<'_, '_>, name: &str) -> bool {
    n.is_element() && n.tag_name().name() == name
}

fn child<'a, 'i>(n: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| is(c, name))
}

/// The `<unit>` scale and the `<up_axis>` rotation of the root `<asset>`, as one matrix.
fn asset_transform(root: Node<'_, '_>) -> Result<M4> {
    let Some(asset) = child(root, "asset") else {
        return Ok(IDENTITY);
    };
    let meter = match child(asset, "unit").and_then(|u| u.attribute("meter")) {
        None => 1.0,
        Some(s) => match s.trim().parse::<f64>() {
            Ok(m) if m.is_finite() && m > 0.0 => m,
            _ => {
                let unit = child(asset, "unit").unwrap_or(asset);
                return Err(err(
                    unit,
                    format!("<unit meter=\"{s}\">: not a positive number"),
                ));
            }
        },
    };
    let up = child(asset, "up_axis")
        .and_then(|u| u.text())
        .map(str::trim);
    // Columns: where the document's x, y and z axes go (the specification's axis table).
    let r: [[f64; 3]; 3] = match up {
        None | Some("Z_UP") => [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
        Some("Y_UP") => [[1., 0., 0.], [0., 0., -1.], [0., 1., 0.]],
        Some("X_UP") => [[0., -1., 0.], [0., 0., -1.], [1., 0., 0.]],
        Some(other) => {
            let node = child(asset, "up_axis").unwrap_or(asset);
            return Err(err(
                node,
                format!("<up_axis>{other}</up_axis>: not X_UP, Y_UP or Z_UP"),
            ));
        }
    };
    let mut m = IDENTITY;
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = meter * r[i][j];
        }
    }
    Ok(m)
}

/// Every `<instance_geometry>` under the scene's visual scene, with its node's transform
/// (the product of its ancestors' transforms, outermost first).
fn instances(root: Node<'_, '_>) -> Result<Vec<(String, M4)>> {
    let scene_url = child(root, "scene")
        .and_then(|s| child(s, "instance_visual_scene"))
        .and_then(|i| i.attribute("url"))
        .and_then(|u| u.strip_prefix('#'));
    let Some(scene) = root
        .descendants()
        .filter(|n| is(n, "visual_scene"))
        .find(|n| scene_url.is_none() || n.attribute("id") == scene_url)
    else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for inst in scene.descendants().filter(|n| is(n, "instance_geometry")) {
        if out.len() == MAX_INSTANCES {
            return Err(err(
                inst,
                format!("more than {MAX_INSTANCES} <instance_geometry>"),
            ));
        }
        let mut m = IDENTITY;
        for (depth, node) in inst.ancestors().filter(|n| is(n, "node")).enumerate() {
            if depth == MAX_NODE_DEPTH {
                return Err(err(
                    inst,
                    format!("<node>s nested deeper than {MAX_NODE_DEPTH}"),
                ));
            }
            m = mul(&node_transform(node)?, &m);
        }
        let url = inst.attribute("url").unwrap_or("");
        let id = url.strip_prefix('#').ok_or_else(|| {
            err(
                inst,
                format!("<instance_geometry url=\"{url}\">: not a local #id"),
            )
        })?;
        out.push((id.to_string(), m));
    }
    Ok(out)
}

/// A node's own transform: its transform elements composed in document order.
fn node_transform(node: Node<'_, '_>) -> Result<M4> {
    let mut m = IDENTITY;
    for t in node.children().filter(Node::is_element) {
        let name = t.tag_name().name();
        let step = match name {
            "matrix" => {
                let v = numbers::<16>(t)?;
                let mut a = IDENTITY;
                for (i, row) in a.iter_mut().enumerate() {
                    row.copy_from_slice(&v[4 * i..4 * i + 4]);
                }
                a
            }
            "translate" => {
                let v = numbers::<3>(t)?;
                let mut a = IDENTITY;
                (a[0][3], a[1][3], a[2][3]) = (v[0], v[1], v[2]);
                a
            }
            "scale" => {
                let v = numbers::<3>(t)?;
                let mut a = IDENTITY;
                (a[0][0], a[1][1], a[2][2]) = (v[0], v[1], v[2]);
                a
            }
            "rotate" => rotation(t, numbers::<4>(t)?)?,
            _ => continue,
        };
        m = mul(&m, &step);
    }
    Ok(m)
}

/// `<rotate>x y z degrees</rotate>`: Rodrigues' formula about the normalised axis.
fn rotation(t: Node<'_, '_>, v: [f64; 4]) -> Result<M4> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n == 0.0 || !n.is_finite() {
        return Err(err(t, "<rotate>: the axis is zero".into()));
    }
    let (x, y, z) = (v[0] / n, v[1] / n, v[2] / n);
    let (s, c) = v[3].to_radians().sin_cos();
    let k = 1.0 - c;
    Ok([
        [c + x * x * k, x * y * k - z * s, x * z * k + y * s, 0.],
        [y * x * k + z * s, c + y * y * k, y * z * k - x * s, 0.],
        [z * x * k - y * s, z * y * k + x * s, c + z * z * k, 0.],
        [0., 0., 0., 1.],
    ])
}

/// Exactly `N` finite numbers of an element's text.
fn numbers<const N: usize>(t: Node<'_, '_>) -> Result<[f64; N]> {
    let v = floats(t)?;
    <[f64; N]>::try_from(v.as_slice()).map_err(|_| {
        let name = t.tag_name().name();
        err(
            t,
            format!("<{name}>: expected {N} numbers, found {}", v.len()),
        )
    })
}

/// The finite numbers of an element's text.
fn floats(t: Node<'_, '_>) -> Result<Vec<f64>> {
    let name = t.tag_name().name();
    t.text()
        .unwrap_or("")
        .split_ascii_whitespace()
        .map(|w| match w.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(err(t, format!("<{name}>: '{w}' is not a finite number"))),
        })
        .collect()
}

/// The integers of a `<p>` or `<vcount>` element.
fn indices(t: Node<'_, '_>) -> Result<Vec<usize>> {
    let name = t.tag_name().name();
    t.text()
        .unwrap_or("")
        .split_ascii_whitespace()
        .map(|w| {
            w.parse::<usize>()
                .map_err(|_| err(t, format!("<{name}>: '{w}' is not an index")))
        })
        .collect()
}

/// Adds a `<geometry>`'s triangles, every vertex moved by `m`.
fn add_geometry(g: Node<'_, '_>, m: &M4, out: &mut Mesh) -> Result<()> {
    let Some(mesh) = child(g, "mesh") else {
        return Ok(()); // splines and other non-mesh geometry draw nothing
    };
    let positions = positions(mesh)?;
    let first = out.vertices.len();
    out.vertices.extend(positions.iter().map(|p| apply(m, *p)));
    // Every index is below the vertex count, so a count that fits a u32 makes the
    // `as u32` below exact.
    u32::try_from(out.vertices.len()).map_err(|_| err(g, "more than 2^32 vertices".into()))?;
    for prim in mesh.children().filter(Node::is_element) {
        let polygons = match prim.tag_name().name() {
            "triangles" | "polylist" | "polygons" => polygons(prim)?,
            _ => continue,
        };
        for poly in polygons {
            if let Some(&bad) = poly.iter().find(|&&i| i >= positions.len()) {
                return Err(err(
                    prim,
                    format!("vertex index {bad} past the {} positions", positions.len()),
                ));
            }
            let index = |k: usize| (first + poly[k]) as u32;
            if out.triangles.len() + poly.len().saturating_sub(2) > MAX_TRIANGLES {
                return Err(err(prim, format!("more than {MAX_TRIANGLES} triangles")));
            }
            for k in 1..poly.len().saturating_sub(1) {
                out.triangles.push([index(0), index(k), index(k + 1)]);
            }
        }
    }
    Ok(())
}

/// The `<mesh>`'s positions: the `POSITION` input of its `<vertices>`, read through the
/// source's accessor (its stride; the first three values of each element).
fn positions(mesh: Node<'_, '_>) -> Result<Vec<[f64; 3]>> {
    let vertices =
        child(mesh, "vertices").ok_or_else(|| err(mesh, "<mesh> without <vertices>".into()))?;
    let src = vertices
        .children()
        .find(|i| is(i, "input") && i.attribute("semantic") == Some("POSITION"))
        .and_then(|i| i.attribute("source"))
        .and_then(|s| s.strip_prefix('#'))
        .ok_or_else(|| err(vertices, "<vertices> without a POSITION input".into()))?;
    let source = mesh
        .children()
        .find(|s| is(s, "source") && s.attribute("id") == Some(src))
        .ok_or_else(|| err(vertices, format!("no <source id=\"{src}\"> in the <mesh>")))?;
    let array = child(source, "float_array")
        .ok_or_else(|| err(source, "<source> without <float_array>".into()))?;
    let values = floats(array)?;
    let stride = child(source, "technique_common")
        .and_then(|t| child(t, "accessor"))
        .and_then(|a| a.attribute("stride"))
        .map_or(Ok(3), |s| s.parse::<usize>())
        .ok()
        .filter(|&s| s >= 3)
        .ok_or_else(|| err(source, "the accessor's stride is not a number ≥ 3".into()))?;
    Ok(values
        .chunks_exact(stride)
        .map(|c| [c[0], c[1], c[2]])
        .collect())
}

/// A primitive's polygons as position indices: the `VERTEX` input's offset within each
/// corner's `max offset + 1` indices; `<triangles>` in threes, `<polylist>` by its
/// `<vcount>`, `<polygons>` one `<p>` each.
fn polygons(prim: Node<'_, '_>) -> Result<Vec<Vec<usize>>> {
    let inputs: Vec<Node<'_, '_>> = prim.children().filter(|c| is(c, "input")).collect();
    let offset_of = |i: &Node<'_, '_>| i.attribute("offset").unwrap_or("0").parse::<usize>();
    let mut stride = 1;
    for i in &inputs {
        let o = offset_of(i).map_err(|_| err(*i, "<input offset>: not an index".into()))?;
        stride = stride.max(o.saturating_add(1));
    }
    let vertex = inputs
        .iter()
        .find(|i| i.attribute("semantic") == Some("VERTEX"))
        .ok_or_else(|| err(prim, "a primitive without a VERTEX input".into()))?;
    let offset = offset_of(vertex).unwrap_or(0);
    let corners = |p: Node<'_, '_>| -> Result<Vec<usize>> {
        let v = indices(p)?;
        if v.len() % stride != 0 {
            return Err(err(
                p,
                format!("<p>: {} indices, not a multiple of {stride}", v.len()),
            ));
        }
        Ok(v.chunks_exact(stride).map(|c| c[offset]).collect())
    };
    let ps: Vec<Node<'_, '_>> = prim.children().filter(|c| is(c, "p")).collect();
    match prim.tag_name().name() {
        "polygons" => ps.into_iter().map(corners).collect(),
        name => {
            let all = match ps.first() {
                Some(p) => corners(*p)?,
                None => Vec::new(),
            };
            let counts = match child(prim, "vcount") {
                Some(vc) if name == "polylist" => indices(vc)?,
                _ => vec![3; all.len() / 3],
            };
            split(prim, &all, &counts)
        }
    }
}

/// `all` cut into polygons of `counts` corners.
fn split(prim: Node<'_, '_>, all: &[usize], counts: &[usize]) -> Result<Vec<Vec<usize>>> {
    let mut out = Vec::with_capacity(counts.len());
    let mut at = 0usize;
    for &n in counts {
        let poly = at.checked_add(n).and_then(|end| all.get(at..end));
        let poly = poly.ok_or_else(|| {
            err(
                prim,
                format!(
                    "the polygon counts need more than the {} corners given",
                    all.len()
                ),
            )
        })?;
        out.push(poly.to_vec());
        at += n; // at + n ≤ all.len(), checked above
    }
    Ok(out)
}
