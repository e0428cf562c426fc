//! The `mesh` oracle: the mesh-file readers of the pictures (ppoe-cli's `meshfile.rs`,
//! compiled here from its source) on arbitrary bytes, as STL or OBJ, with arbitrary scales
//! and small triangle bounds (so that reduction runs often).

#[path = "../../ppoe-cli/src/meshfile.rs"]
#[allow(dead_code)]
mod meshfile;

use meshfile::{parse, Format, Limits};

/// Scales tried: ordinary, tiny, huge (overflow after scaling), negative, zero.
const SCALES: [f64; 8] = [1.0, 1e-3, 1e300, -1.0, 0.0, 1e-300, 2.5, f64::MAX];

/// The body of the `mesh` target: byte 0 picks the format and the scale, byte 1 the
/// triangle bound (1..=256, or the default), the rest is the file.
pub fn run(data: &[u8]) {
    let [a, b, file @ ..] = data else {
        return;
    };
    let format = if a & 1 == 0 { Format::Stl } else { Format::Obj };
    let s = SCALES[(a >> 1) as usize % SCALES.len()];
    let scale = [s, SCALES[(a >> 4) as usize % SCALES.len()], 1.0];
    let limits = match b {
        0 => Limits::default(),
        n => Limits { max_triangles: *n as usize, ..Limits::default() },
    };
    let Ok(mesh) = parse(file, format, scale, &limits) else {
        return;
    };
    assert!(!mesh.triangles.is_empty(), "Ok without triangles");
    assert!(
        mesh.triangles.len() <= limits.max_triangles,
        "{} triangles over the bound {}",
        mesh.triangles.len(),
        limits.max_triangles
    );
    for p in &mesh.vertices {
        assert!(p.iter().all(|x| x.is_finite()), "vertex not finite: {p:?}");
    }
    for t in &mesh.triangles {
        assert!(t.iter().all(|&i| (i as usize) < mesh.vertices.len()), "bad index {t:?}");
        assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "degenerate {t:?}");
    }
}
