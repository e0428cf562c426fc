//! Mesh files a URDF's `<visual>` names (STL binary or ASCII, Wavefront OBJ), read with
//! bounded cost: the file must be a regular file within a size cap, is read once, and a
//! mesh with more triangles than the cap is reduced by vertex clustering.
//!
//! Self-contained (std only, nothing from the rest of the crate), so that the fuzz target
//! `mesh` compiles this very file.
//!
//! Why not the `stl_io` / `tobj` crates: `tobj` opens every `mtllib` the OBJ names
//! itself (a `/dev/zero` or a FIFO there is read without bound), `stl_io` takes any file
//! starting with `solid` for ASCII (binary STLs whose 80-byte header starts so are
//! common), and neither bounds the mesh's size. The pictures need positions and faces only;
//! materials come from the URDF, so `mtllib`, normals and texture coordinates are ignored.
//!
//! Vertex clustering (Rossignac & Borrel's method): vertices are snapped to a uniform grid
//! over the mesh's bounding box and each occupied cell becomes one vertex (the mean of
//! its members); triangles whose corners fall into fewer than three cells vanish. The
//! grid is made coarser until the triangle count is within the cap. The shape's error is
//! at most one cell's diagonal, which the notice states.

use std::collections::HashMap;
use std::fs::File;
use std::io::Read;
use std::path::Path;

/// The bounds on a mesh file's cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Largest file read, in bytes; a larger file is skipped.
    pub max_bytes: u64,
    /// Most triangles kept per mesh; a mesh with more is reduced by vertex clustering.
    pub max_triangles: usize,
}

impl Default for Limits {
    /// 64 MiB per file (a binary STL of 1.3 million triangles) and 20 000 triangles per
    /// mesh: a picture of a few hundred pixels shows no more, and the drawing's cost grows
    /// with the triangle count.
    fn default() -> Self {
        Limits {
            max_bytes: 64 << 20,
            max_triangles: 20_000,
        }
    }
}

/// A triangle mesh: vertices (in the file's units times the scale) and 0-based triangles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// The vertices, every coordinate finite.
    pub vertices: Vec<[f64; 3]>,
    /// Triangles, each three distinct valid vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Set when the mesh was reduced: what was done, for the user.
    pub reduced: Option<String>,
}

/// The formats read, by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// STL, binary or ASCII (told apart by the file's size, not its first word).
    Stl,
    /// Wavefront OBJ (`v` and `f` statements).
    Obj,
}

impl Format {
    /// The format of a path's extension (case-insensitive), if read.
    pub fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "stl" => Some(Format::Stl),
            "obj" => Some(Format::Obj),
            _ => None,
        }
    }
}

/// Reads a mesh file once: it must be a regular file (symlinks followed) of at most
/// `limits.max_bytes`. Checked before opening, since opening a FIFO blocks until a writer
/// comes, and again on the opened handle, in case the path was replaced in between.
///
/// # Errors
/// A message naming what is wrong (not a regular file, too large, unreadable).
pub fn read(path: &Path, limits: &Limits) -> Result<Vec<u8>, String> {
    if !std::fs::metadata(path)
        .map_err(|e| e.to_string())?
        .is_file()
    {
        return Err("not a regular file".into());
    }
    let file = File::open(path).map_err(|e| e.to_string())?;
    let meta = file.metadata().map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    if meta.len() > limits.max_bytes {
        return Err(format!(
            "{} bytes, more than the {} read",
            meta.len(),
            limits.max_bytes
        ));
    }
    let mut bytes = Vec::new();
    // `take` bounds the read even if the file grows after the size check.
    file.take(limits.max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > limits.max_bytes {
        return Err(format!("grew past the {} bytes read", limits.max_bytes));
    }
    Ok(bytes)
}

/// Parses a mesh file's bytes, scales it per axis and bounds its triangle count.
///
/// # Errors
/// A message naming the place (line, or triangle for binary STL) of malformed data, a
/// face naming a missing vertex, no triangles, or a vertex that is not finite after
/// scaling.
pub fn parse(
    bytes: &[u8],
    format: Format,
    scale: [f64; 3],
    limits: &Limits,
) -> Result<Mesh, String> {
    let (vertices, triangles) = match format {
        Format::Stl => stl(bytes)?,
        Format::Obj => obj(bytes)?,
    };
    from_triangles(vertices, triangles, scale, limits)
}

/// A mesh read by another parser (COLLADA), scaled per axis and bounded as [`parse`]
/// does: every triangle index must be below `vertices.len()`.
///
/// # Errors
/// No proper triangles, or a vertex that is not finite after scaling.
pub fn from_triangles(
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
    scale: [f64; 3],
    limits: &Limits,
) -> Result<Mesh, String> {
    let vertices: Vec<[f64; 3]> = vertices
        .into_iter()
        .map(|p| [0, 1, 2].map(|k| p[k] * scale[k]))
        .collect();
    // After scaling: finite vertices and a finite scale can still overflow.
    if let Some(i) = vertices
        .iter()
        .position(|p| p.iter().any(|x| !x.is_finite()))
    {
        return Err(format!("vertex {} is not finite after scaling", i + 1));
    }
    let triangles = proper(triangles);
    if triangles.is_empty() {
        return Err("no triangles".into());
    }
    let mut mesh = Mesh {
        vertices,
        triangles,
        reduced: None,
    };
    if mesh.triangles.len() > limits.max_triangles {
        reduce(&mut mesh, limits.max_triangles);
        if mesh.triangles.is_empty() {
            return Err("no triangles left after reduction to the bound".into());
        }
    }
    Ok(mesh)
}

/// Triangles with three distinct corners (a degenerate one draws nothing).
fn proper(triangles: Vec<[u32; 3]>) -> Vec<[u32; 3]> {
    triangles
        .into_iter()
        .filter(|[a, b, c]| a != b && b != c && a != c)
        .collect()
}

type Raw = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// Binary if the size is exactly that of the triangle count in the header, else ASCII if it
/// starts with `solid`.
fn stl(bytes: &[u8]) -> Result<Raw, String> {
    let count = bytes
        .get(80..84)
        .map(|b| u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])));
    if count.is_some_and(|n| 84 + 50 * n == bytes.len() as u64) {
        return Ok(stl_binary(&bytes[84..]));
    }
    match (std::str::from_utf8(bytes).ok(), count) {
        (Some(t), _) if t.trim_start().starts_with("solid") => stl_ascii(t),
        (_, Some(n)) => Err(format!(
            "neither ASCII STL nor binary STL (the header counts {n} triangles, which need {} \
             bytes; the file has {})",
            84 + 50 * n,
            bytes.len()
        )),
        (_, None) => Err("too short for binary STL and not ASCII STL".into()),
    }
}

/// Merges bit-equal vertices, as STL repeats each corner per triangle.
#[derive(Default)]
struct Welder {
    index: HashMap<[u64; 3], u32>,
    vertices: Vec<[f64; 3]>,
}

impl Welder {
    fn add(&mut self, p: [f64; 3]) -> u32 {
        let next = self.vertices.len() as u32;
        let key = p.map(|x| (x + 0.0).to_bits()); // +0.0: −0 and 0 weld
        *self.index.entry(key).or_insert_with(|| {
            self.vertices.push(p);
            next
        })
    }
}

fn stl_binary(body: &[u8]) -> Raw {
    let mut weld = Welder::default();
    let mut triangles = Vec::with_capacity(body.len() / 50);
    for record in body.chunks_exact(50) {
        // 12 bytes of normal (ignored), three corners of 12 bytes, 2 attribute bytes.
        let corner = |k: usize| {
            let at = 12 + 12 * k;
            [0, 1, 2].map(|c| {
                let b = &record[at + 4 * c..at + 4 * c + 4];
                f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            })
        };
        triangles.push([0, 1, 2].map(|k| weld.add(corner(k))));
    }
    (weld.vertices, triangles)
}

/// `facet … outer loop vertex x y z … endloop endfacet`; a loop of more than three
/// vertices is a convex polygon, split into a fan.
fn stl_ascii(text: &str) -> Result<Raw, String> {
    let mut weld = Welder::default();
    let mut triangles = Vec::new();
    let mut polygon: Vec<u32> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vertex") => {
                let p = three(&mut words)
                    .ok_or_else(|| format!("line {}: expected `vertex x y z`", i + 1))?;
                polygon.push(weld.add(p));
            }
            Some("endloop") => {
                if polygon.len() < 3 {
                    return Err(format!("line {}: a loop of fewer than 3 vertices", i + 1));
                }
                fan(&polygon, &mut triangles);
                polygon.clear();
            }
            _ => {}
        }
    }
    Ok((weld.vertices, triangles))
}

/// Three finite numbers, the rest of the statement ignored.
fn three<'a>(words: &mut impl Iterator<Item = &'a str>) -> Option<[f64; 3]> {
    let mut p = [0.0; 3];
    for x in &mut p {
        *x = words
            .next()?
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())?;
    }
    Some(p)
}

fn fan(polygon: &[u32], out: &mut Vec<[u32; 3]>) {
    for k in 1..polygon.len().saturating_sub(1) {
        out.push([polygon[0], polygon[k], polygon[k + 1]]);
    }
}

/// `v x y z` and `f i j k …` (each corner `i`, `i/t`, `i//n` or `i/t/n`; 1-based, or
/// negative counting back from the latest vertex); everything else is ignored.
fn obj(bytes: &[u8]) -> Result<Raw, String> {
    let text = std::str::from_utf8(bytes).map_err(|e| format!("not UTF-8 text ({e})"))?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let mut polygon = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let at = |what: &str| format!("line {}: {what}", i + 1);
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => vertices.push(three(&mut words).ok_or_else(|| at("expected `v x y z`"))?),
            Some("f") => {
                polygon.clear();
                for w in words {
                    polygon
                        .push(obj_corner(w, vertices.len()).ok_or_else(|| {
                            at("a face corner names no vertex defined before it")
                        })?);
                }
                if polygon.len() < 3 {
                    return Err(at("a face of fewer than 3 corners"));
                }
                fan(&polygon, &mut triangles);
            }
            _ => {}
        }
    }
    Ok((vertices, triangles))
}

/// The 0-based vertex of an OBJ face corner, given `n` vertices so far.
fn obj_corner(word: &str, n: usize) -> Option<u32> {
    let i: i64 = word.split('/').next()?.parse().ok()?;
    let n = i64::try_from(n).ok()?;
    let zero_based = if (1..=n).contains(&i) {
        i - 1
    } else if (-n..=-1).contains(&i) {
        n + i
    } else {
        return None;
    };
    u32::try_from(zero_based).ok()
}

/// Vertex clustering on ever coarser grids until at most `max` triangles remain.
fn reduce(mesh: &mut Mesh, max: usize) {
    let before = mesh.triangles.len();
    let (lo, hi) = bounds(&mesh.vertices);
    let half_extent = (0..3)
        .map(|k| hi[k] / 2.0 - lo[k] / 2.0)
        .fold(0.0, f64::max);
    // A surface of T triangles over r² cells keeps about 2·r² of them.
    let mut cells = ((max as f64 / 2.0).sqrt().ceil() as usize).max(1);
    loop {
        let (v, t) = cluster(mesh, lo, half_extent, cells);
        if t.len() <= max || cells == 1 {
            let cell = 2.0 * half_extent / cells as f64;
            mesh.reduced = Some(format!(
                "{before} triangles reduced to {} by vertex clustering (grid cell {cell:.3e}, \
                 the shape's error at most {:.3e}); the bound is {max} per mesh \
                 (--mesh-triangles)",
                t.len(),
                cell * 3f64.sqrt()
            ));
            (mesh.vertices, mesh.triangles) = (v, t);
            return;
        }
        cells = (cells * 3 / 4).max(1);
    }
}

fn bounds(vertices: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// One clustering pass: `cells` per axis over the bounding box from `lo` of side
/// `extent`. Computed on halved coordinates, whose differences cannot overflow; each
/// cell's vertex is its first member (a mean of members could overflow near the largest
/// finite number, and the shape's error stays within one cell either way).
fn cluster(mesh: &Mesh, lo: [f64; 3], half_extent: f64, cells: usize) -> Raw {
    let half_cell = half_extent / cells as f64;
    let mut of_cell: HashMap<[usize; 3], u32> = HashMap::new();
    let mut vertices = Vec::new();
    let index: Vec<u32> = mesh
        .vertices
        .iter()
        .map(|p| {
            let key = [0, 1, 2].map(|k| {
                let c = if half_cell > 0.0 {
                    (p[k] / 2.0 - lo[k] / 2.0) / half_cell
                } else {
                    0.0
                };
                (c as usize).min(cells - 1)
            });
            *of_cell.entry(key).or_insert_with(|| {
                vertices.push(*p);
                (vertices.len() - 1) as u32
            })
        })
        .collect();
    let mut seen = std::collections::HashSet::new();
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| index[i as usize]))
        .filter(|&[a, b, c]| a != b && b != c && a != c)
        .filter(|t| {
            let mut key = *t;
            key.sort_unstable();
            seen.insert(key)
        })
        .collect();
    (vertices, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    const UNIT: [f64; 3] = [1.0; 3];

    fn binary_stl(header: &[u8], triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut out = header.to_vec();
        out.resize(80, b' ');
        out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
        for t in triangles {
            out.extend_from_slice(&[0u8; 12]);
            for c in t.iter().flatten() {
                out.extend_from_slice(&c.to_le_bytes());
            }
            out.extend_from_slice(&[0u8; 2]);
        }
        out
    }

    const TRI: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    const TRI2: [[f32; 3]; 3] = [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];

    #[test]
    fn binary_stl_with_a_solid_header_is_binary() {
        let bytes = binary_stl(b"solid exported by a CAD tool", &[TRI, TRI2]);
        let m = parse(&bytes, Format::Stl, UNIT, &Limits::default()).unwrap();
        // Two triangles sharing an edge: four welded vertices.
        assert_eq!((m.vertices.len(), m.triangles.len()), (4, 2));
        assert_eq!(m.vertices[1], [1.0, 0.0, 0.0]);
    }

    #[test]
    fn ascii_stl_and_its_errors() {
        let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 2 0 0\n\
                    vertex 0 2 0\nendloop\nendfacet\nendsolid t\n";
        let m = parse(
            text.as_bytes(),
            Format::Stl,
            [1.0, 1.0, 0.5],
            &Limits::default(),
        )
        .unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        assert_eq!(m.vertices[2], [0.0, 2.0, 0.0]);
        let bad = text.replace("vertex 2 0 0", "vertex 2 nan 0");
        let e = parse(bad.as_bytes(), Format::Stl, UNIT, &Limits::default()).unwrap_err();
        assert!(e.contains("line 5"), "{e}");
        let e = parse(&[7u8; 100], Format::Stl, UNIT, &Limits::default()).unwrap_err();
        assert!(e.contains("header counts"), "{e}");
    }

    #[test]
    fn obj_faces_polygons_negative_indices_and_ignored_statements() {
        let text = "mtllib /dev/zero\nusemtl m\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
                    vn 0 0 1\nf 1//1 2//1 3//1 4//1\nf -4 -2 -1\n";
        let m = parse(text.as_bytes(), Format::Obj, UNIT, &Limits::default()).unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 2, 3]]);
        for bad in [
            "v 0 0 0\nf 1 2 3\n",
            "v 0 0 0\nf 0 1 1\n",
            "v 1 2\n",
            "f 1 2\n",
        ] {
            let e = parse(bad.as_bytes(), Format::Obj, UNIT, &Limits::default()).unwrap_err();
            assert!(e.starts_with("line "), "{bad:?}: {e}");
        }
    }

    #[test]
    fn vertices_are_checked_after_scaling() {
        let bytes = binary_stl(b"", &[[[1e30, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]]);
        let e = parse(&bytes, Format::Stl, [1e300, 1.0, 1.0], &Limits::default()).unwrap_err();
        assert!(e.contains("not finite after scaling"), "{e}");
        assert!(parse(&bytes, Format::Stl, [1.0; 3], &Limits::default()).is_ok());
    }

    /// A 200×200 grid of squares (80 000 triangles) reduced to at most 5 000: every
    /// vertex kept is an input vertex, every triangle proper and unique.
    #[test]
    fn a_large_mesh_is_reduced_within_the_bound() {
        let n = 200;
        let mut text = String::new();
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
                text += &format!("v {x} {y} {}\n", (x * 3.0).sin() * 0.1);
            }
        }
        let at = |i: usize, j: usize| i * (n + 1) + j + 1;
        for i in 0..n {
            for j in 0..n {
                text += &format!(
                    "f {} {} {} {}\n",
                    at(i, j),
                    at(i + 1, j),
                    at(i + 1, j + 1),
                    at(i, j + 1)
                );
            }
        }
        let limits = Limits {
            max_triangles: 5_000,
            ..Limits::default()
        };
        let unbounded = Limits {
            max_triangles: usize::MAX,
            ..Limits::default()
        };
        let full = parse(text.as_bytes(), Format::Obj, UNIT, &unbounded).unwrap();
        assert_eq!(full.triangles.len(), 2 * n * n);
        let m = parse(text.as_bytes(), Format::Obj, UNIT, &limits).unwrap();
        assert!(
            m.triangles.len() <= 5_000 && m.triangles.len() > 1_000,
            "{}",
            m.triangles.len()
        );
        assert!(m
            .reduced
            .as_deref()
            .unwrap()
            .contains("80000 triangles reduced"));
        for v in &m.vertices {
            assert!(full.vertices.contains(v));
        }
        let mut seen = std::collections::HashSet::new();
        for t in &m.triangles {
            assert!(t.iter().all(|&i| (i as usize) < m.vertices.len()));
            assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
            let mut k = *t;
            k.sort_unstable();
            assert!(seen.insert(k));
        }
    }

    #[test]
    fn only_regular_files_within_the_cap_are_read() {
        let limits = Limits {
            max_bytes: 1000,
            ..Limits::default()
        };
        for dev in ["/dev/zero", "/dev/null"] {
            if Path::new(dev).exists() {
                let e = read(Path::new(dev), &limits).unwrap_err();
                assert!(e.contains("not a regular file"), "{dev}: {e}");
            }
        }
        let dir = std::env::temp_dir().join(format!("ppoe-meshfile-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let big = dir.join("big.stl");
        std::fs::write(&big, vec![0u8; 1001]).unwrap();
        let e = read(&big, &limits).unwrap_err();
        assert!(e.contains("1001 bytes"), "{e}");
        std::fs::write(&big, vec![0u8; 1000]).unwrap();
        assert_eq!(read(&big, &limits).unwrap().len(), 1000);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
