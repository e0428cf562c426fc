//! Meshes of the equiprobable surface and the skeleton (Wavefront OBJ, ASCII PLY), for
//! Blender or MeshLab.
//!
//! Vertex order, in both formats: first the surface's grid points row by row (rows = φ,
//! columns = θ; `n_rows · n_cols` vertices, exactly the frame's surface points), then the
//! skeleton's points (base, joints, tool), then the second-order mean of the tool
//! position. Faces: two triangles per grid cell, leaving out the degenerate ones at the
//! poles and cells with non-finite points. The skeleton is a polyline (OBJ `l`, PLY
//! `edge` elements). Coordinates are metres in the robot's base frame, written with
//! Rust's shortest round-trip formatting, so reading them back gives the same `f64`s.

use crate::output;
use crate::picture::Frame;
use anyhow::{bail, Context};
use std::fmt::Write as _;
use std::path::Path;

/// The mesh of a frame: vertices, triangles and skeleton edges (0-based indices).
struct Mesh {
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[usize; 3]>,
    edges: Vec<[usize; 2]>,
    /// Index of the first skeleton vertex.
    skeleton_start: usize,
    /// Index of the second-order mean's vertex.
    mean2: usize,
}

fn finite(p: &[f64; 3]) -> bool {
    p.iter().all(|c| c.is_finite())
}

fn mesh_of(frame: &Frame) -> Mesh {
    let mut vertices = Vec::new();
    let mut index = Vec::with_capacity(frame.surface.len());
    for row in &frame.surface {
        let mut idx = Vec::with_capacity(row.len());
        for p in row {
            idx.push(vertices.len());
            vertices.push(*p);
        }
        index.push(idx);
    }
    let mut triangles = Vec::new();
    for i in 0..frame.surface.len().saturating_sub(1) {
        let m = index[i].len().min(index[i + 1].len());
        for j in 0..m.saturating_sub(1) {
            let (a, b, c, d) = (
                index[i][j],
                index[i + 1][j],
                index[i + 1][j + 1],
                index[i][j + 1],
            );
            for t in [[a, b, c], [a, c, d]] {
                let [p, q, r] = t.map(|k| vertices[k]);
                if finite(&p) && finite(&q) && finite(&r) && p != q && q != r && p != r {
                    triangles.push(t);
                }
            }
        }
    }
    let skeleton_start = vertices.len();
    vertices.extend_from_slice(&frame.joints);
    let edges = (1..frame.joints.len())
        .map(|k| [skeleton_start + k - 1, skeleton_start + k])
        .collect();
    let mean2 = vertices.len();
    vertices.push(frame.mean2);
    Mesh {
        vertices,
        triangles,
        edges,
        skeleton_start,
        mean2,
    }
}

/// A coordinate as text: shortest round-trip form; NaN and infinities as `nan`, `inf`,
/// `-inf` (which Blender and MeshLab read as such or reject, rather than misread).
fn num(x: f64) -> String {
    if x.is_nan() {
        "nan".to_string()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.to_string()
    } else {
        format!("{x:?}")
    }
}

/// The OBJ text of a frame (see the module documentation for the layout).
fn obj_text(frame: &Frame) -> String {
    let m = mesh_of(frame);
    let mut s = String::new();
    let rows = frame.surface.len();
    let cols = frame.surface.first().map_or(0, Vec::len);
    let _ = writeln!(s, "# ppoe: {}", frame.title.replace('\n', " "));
    let _ = writeln!(
        s,
        "# surface: {} ({rows}x{cols} grid, rows = phi, columns = theta)",
        frame.sigma_label.replace('\n', " ")
    );
    let _ = writeln!(s, "# units: metres, robot base frame");
    let _ = writeln!(s, "o surface");
    for (k, p) in m.vertices.iter().enumerate() {
        if k == m.skeleton_start {
            let _ = writeln!(s, "o skeleton");
        }
        if k == m.mean2 {
            let _ = writeln!(s, "o second_order_mean");
        }
        let _ = writeln!(s, "v {} {} {}", num(p[0]), num(p[1]), num(p[2]));
        if k + 1 == m.skeleton_start {
            for t in &m.triangles {
                let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
            }
        }
        if k + 1 == m.mean2 && !m.edges.is_empty() {
            let mut line = String::from("l");
            for v in m.skeleton_start..m.mean2 {
                let _ = write!(line, " {}", v + 1);
            }
            let _ = writeln!(s, "{line}");
        }
    }
    let _ = writeln!(s, "p {}", m.mean2 + 1);
    s
}

/// The ASCII PLY text of a frame (see the module documentation for the layout).
fn ply_text(frame: &Frame) -> String {
    let m = mesh_of(frame);
    let mut s = String::new();
    let _ = writeln!(s, "ply");
    let _ = writeln!(s, "format ascii 1.0");
    let _ = writeln!(s, "comment ppoe: {}", frame.title.replace('\n', " "));
    let _ = writeln!(
        s,
        "comment surface: {}",
        frame.sigma_label.replace('\n', " ")
    );
    let _ = writeln!(
        s,
        "comment vertices: {} surface points, then {} skeleton points, then the second-order mean",
        m.skeleton_start,
        m.mean2 - m.skeleton_start
    );
    let _ = writeln!(s, "comment units: metres, robot base frame");
    let _ = writeln!(s, "element vertex {}", m.vertices.len());
    let _ = writeln!(s, "property double x");
    let _ = writeln!(s, "property double y");
    let _ = writeln!(s, "property double z");
    let _ = writeln!(s, "element face {}", m.triangles.len());
    let _ = writeln!(s, "property list uchar int vertex_indices");
    let _ = writeln!(s, "element edge {}", m.edges.len());
    let _ = writeln!(s, "property int vertex1");
    let _ = writeln!(s, "property int vertex2");
    let _ = writeln!(s, "end_header");
    for p in &m.vertices {
        let _ = writeln!(s, "{} {} {}", num(p[0]), num(p[1]), num(p[2]));
    }
    for t in &m.triangles {
        let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
    }
    for e in &m.edges {
        let _ = writeln!(s, "{} {}", e[0], e[1]);
    }
    s
}

/// Writes the frame's surface (and the skeleton as lines) as a Wavefront OBJ file,
/// atomically (see [`output::write_atomic`]).
///
/// # Errors
/// A sentence naming `path`; the previous file, if any, is left as it was.
pub fn write_obj(path: &Path, frame: &Frame) -> anyhow::Result<()> {
    output::write_atomic(path, |w| w.write_all(obj_text(frame).as_bytes()))
}

/// Writes the frame's surface (and the skeleton as edges) as an ASCII PLY file,
/// atomically (see [`output::write_atomic`]).
///
/// # Errors
/// A sentence naming `path`; the previous file, if any, is left as it was.
pub fn write_ply(path: &Path, frame: &Frame) -> anyhow::Result<()> {
    output::write_atomic(path, |w| w.write_all(ply_text(frame).as_bytes()))
}

fn parse_xyz<'a>(
    mut it: impl Iterator<Item = &'a str>,
    line_no: usize,
) -> anyhow::Result<[f64; 3]> {
    let mut p = [0.0; 3];
    for c in &mut p {
        let t = it
            .next()
            .with_context(|| format!("line {line_no}: fewer than 3 coordinates"))?;
        *c = t
            .parse()
            .with_context(|| format!("line {line_no}: bad coordinate '{t}'"))?;
    }
    Ok(p)
}

/// The vertices (`v x y z` lines, in order) of an OBJ file's text.
#[cfg_attr(not(test), allow(dead_code))] // used by the tests
pub fn read_obj_vertices(text: &str) -> anyhow::Result<Vec<[f64; 3]>> {
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let mut it = line.split_whitespace();
        if it.next() == Some("v") {
            out.push(parse_xyz(it, k + 1)?);
        }
    }
    Ok(out)
}

/// The vertices of an ASCII PLY file's text (the `vertex` element, x y z first).
#[cfg_attr(not(test), allow(dead_code))] // used by the tests
pub fn read_ply_vertices(text: &str) -> anyhow::Result<Vec<[f64; 3]>> {
    let mut lines = text.lines().enumerate();
    if lines.next().map(|(_, l)| l.trim()) != Some("ply") {
        bail!("not a PLY file");
    }
    let mut n_vertex = None;
    let mut before_vertex = 0usize;
    let mut seen_vertex = false;
    for (_, line) in lines.by_ref() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["format", f, ..] if *f != "ascii" => bail!("not an ASCII PLY file"),
            ["element", "vertex", n] => {
                n_vertex = Some(n.parse::<usize>()?);
                seen_vertex = true;
            }
            ["element", _, n] if !seen_vertex => before_vertex += n.parse::<usize>()?,
            ["end_header"] => break,
            _ => {}
        }
    }
    if before_vertex > 0 {
        bail!("elements before the vertices are not supported");
    }
    let n = n_vertex.context("no vertex element")?;
    let mut out = Vec::with_capacity(n);
    for (k, line) in lines.take(n) {
        out.push(parse_xyz(line.split_whitespace(), k + 1)?);
    }
    if out.len() != n {
        bail!("{} vertices announced, {} found", n, out.len());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::picture::tests::{synthetic_frame, temp_path};

    fn expected_vertices(frame: &Frame) -> Vec<[f64; 3]> {
        let mut v: Vec<[f64; 3]> = frame.surface.iter().flatten().copied().collect();
        v.extend_from_slice(&frame.joints);
        v.push(frame.mean2);
        v
    }

    #[test]
    fn obj_parses_back_to_the_surface_and_skeleton() {
        let frame = synthetic_frame("obj test", 0.0);
        let path = temp_path("mesh.obj");
        write_obj(&path, &frame).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let v = read_obj_vertices(&text).unwrap();
        assert_eq!(v, expected_vertices(&frame)); // bit-for-bit
        let n_surface = 20 * 20;
        // Faces index the surface only; the skeleton is one polyline.
        let faces: Vec<&str> = text.lines().filter(|l| l.starts_with("f ")).collect();
        assert!(faces.len() >= 2 * 19 * 17, "{} faces", faces.len());
        for f in &faces {
            for i in f.split_whitespace().skip(1) {
                let i: usize = i.parse().unwrap();
                assert!((1..=n_surface).contains(&i));
            }
        }
        let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("l ")).collect();
        assert_eq!(
            lines,
            vec![format!(
                "l {} {} {} {}",
                n_surface + 1,
                n_surface + 2,
                n_surface + 3,
                n_surface + 4
            )]
        );
    }

    #[test]
    fn ply_parses_back_to_the_surface_and_skeleton() {
        let frame = synthetic_frame("ply test", 0.2);
        let path = temp_path("mesh.ply");
        write_ply(&path, &frame).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let v = read_ply_vertices(&text).unwrap();
        assert_eq!(v, expected_vertices(&frame));
        // Header counts match the body.
        let count = |name: &str| -> usize {
            text.lines()
                .find_map(|l| l.strip_prefix(&format!("element {name} ")))
                .unwrap()
                .parse()
                .unwrap()
        };
        let body: Vec<&str> = text
            .lines()
            .skip_while(|l| *l != "end_header")
            .skip(1)
            .collect();
        assert_eq!(body.len(), count("vertex") + count("face") + count("edge"));
        assert_eq!(count("edge"), frame.joints.len() - 1);
        let faces = &body[count("vertex")..count("vertex") + count("face")];
        assert!(faces.iter().all(|l| l.starts_with("3 ")));
        let edges = &body[count("vertex") + count("face")..];
        assert_eq!(edges[0], "400 401");
    }

    #[test]
    fn no_degenerate_or_non_finite_faces() {
        let mut frame = synthetic_frame("nan", 0.0);
        frame.surface[5][5] = [f64::NAN; 3];
        let m = mesh_of(&frame);
        for t in &m.triangles {
            let [p, q, r] = t.map(|k| m.vertices[k]);
            assert!(finite(&p) && finite(&q) && finite(&r));
            assert!(p != q && q != r && p != r);
        }
        // The NaN vertex is still written (vertex order is the grid order).
        let text = obj_text(&frame);
        let v = read_obj_vertices(&text).unwrap();
        assert!(v[5 * 20 + 5].iter().all(|c| c.is_nan()));
    }
}
