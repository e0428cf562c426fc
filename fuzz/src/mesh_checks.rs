//! The `mesh` oracle: the mesh-file readers of the pictures (ppoe-cli's `meshfile.rs`,
//! compiled here from its source) on arbitrary bytes, as STL or OBJ, with arbitrary scales
//! and small triangle bounds (so that reduction runs often).

#[path = "../../ppoe-cli/src/meshfile.rs"]
#[allow(dead_code)]
mod meshfile;

use meshfile::{parse, Format, Limits};

/// Scales tried: ordinary, tiny, huge (overflow after scaling), negative, zero.
const SCALES: [f64; 8] = [1.0, 1e-3, 1e300, -1.0, 0.0, 1e-300, 2.5, f64::MAX];

/// The body of the `mesh` target: byte 0 picks the format (bit 7 set: COLLADA, read by
/// ppoe-build, else bit 0: STL or OBJ) and the scale, byte 1 the triangle bound
/// (1..=256, or the default), the rest is the file.
pub fn run(data: &[u8]) {
    let [a, b, file @ ..] = data else {
        return;
    };
    let format = if a & 1 == 0 { Format::Stl } else { Format::Obj };
    let s = SCALES[(a >> 1) as usize % SCALES.len()];
    let scale = [s, SCALES[(a >> 4) as usize % SCALES.len()], 1.0];
    let limits = match b {
        0 => Limits::default(),
        n => Limits {
            max_triangles: *n as usize,
            ..Limits::default()
        },
    };
    let mesh = if a & 0x80 != 0 {
        collada(file, scale, &limits)
    } else {
        parse(file, format, scale, &limits).ok()
    };
    let Some(mesh) = mesh else {
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
        assert!(
            t.iter().all(|&i| (i as usize) < mesh.vertices.len()),
            "bad index {t:?}"
        );
        assert!(
            t[0] != t[1] && t[1] != t[2] && t[0] != t[2],
            "degenerate {t:?}"
        );
    }
}

/// A COLLADA document as the pictures read it: ppoe-build's parser (whose triangles must
/// index its vertices, all finite), then the same bounds as the other formats.
fn collada(file: &[u8], scale: [f64; 3], limits: &Limits) -> Option<meshfile::Mesh> {
    let dae = ppoe_build::collada::parse(file).ok()?;
    assert!(!dae.triangles.is_empty(), "COLLADA Ok without triangles");
    for t in &dae.triangles {
        assert!(
            t.iter().all(|&i| (i as usize) < dae.vertices.len()),
            "bad index {t:?}"
        );
    }
    assert!(dae.triangles.len() <= ppoe_build::collada::MAX_TRIANGLES);
    meshfile::from_triangles(dae.vertices, dae.triangles, scale, limits).ok()
}
