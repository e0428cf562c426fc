//! The robot's visual geometry from a URDF's `<visual>` elements, for the pictures:
//! cylinders, boxes and spheres with their `<origin>` and material colours, and meshes
//! (STL, OBJ, COLLADA `.dae`) loaded from the URDF's directory or the `--package-dir`
//! of their `package://` package; a mesh that cannot be found, is of another format or
//! cannot be read is skipped with a notice saying which and why.
//! The `<visual>`s are read by ppoe-build with the rest of the URDF (`Link::visuals`, the
//! link/joint tree); this file turns them into shapes and places them, and reads no XML.
//!
//! Each visual is placed with the product of exponentials: a link below the `k`-th chain
//! joint is at `T_base←link(θ) = Exp(S₁θ₁)·…·Exp(S_kθ_k)·T_base←link(0)`, where
//! `T_base←link(0)` is the product of the joint origins from the base down to the link.

use crate::meshfile::{self, Limits};
use crate::picture::geom::{mul4, Mat4, IDENTITY};
use crate::picture::{Body, Shape};
use anyhow::anyhow;
use ppoe_build::urdf::{Geometry, Material, Tree, Visual};
use ppoe_build::Urdf;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The colour of a visual without a material colour.
const DEFAULT_RGB: [u8; 3] = [160, 160, 170];

/// One visual of one link, at the home pose.
#[derive(Clone, Debug)]
struct Part {
    /// How many chain joints (from the base) move this link.
    prefix: usize,
    /// `T_base←visual` with every joint at zero.
    home: Mat4,
    shape: Arc<Shape>,
    rgb: [u8; 3],
}

/// The visuals of the links at or below a chain's base.
#[derive(Clone, Debug, Default)]
pub struct Visuals {
    parts: Vec<Part>,
}

/// A URDF item's error (ppoe-build's, with its line and column) as the command's error.
fn item_error(e: &ppoe_build::Error) -> anyhow::Error {
    anyhow!("{e}")
}

/// The sRGB of a material's `rgba` (components clamped to [0, 1]).
fn colour(material: &Material) -> Option<[u8; 3]> {
    let v = material.rgba?;
    Some([0, 1, 2].map(|k| (v[k].clamp(0.0, 1.0) * 255.0).round() as u8))
}

/// The named materials declared at the robot's top level (a later one of the same name
/// wins).
fn materials(urdf: &Urdf) -> anyhow::Result<HashMap<&str, [u8; 3]>> {
    let mut out = HashMap::new();
    for m in &urdf.materials {
        let m = m.as_ref().map_err(item_error)?;
        if let (Some(name), Some(rgb)) = (&m.name, colour(m)) {
            out.insert(name.as_str(), rgb);
        }
    }
    Ok(out)
}

/// A visual's colour: its material's own colour, else that of the named material.
fn visual_rgb(v: &Visual, named: &HashMap<&str, [u8; 3]>) -> Option<[u8; 3]> {
    let m = v.material.as_ref()?;
    colour(m).or_else(|| m.name.as_deref().and_then(|n| named.get(n).copied()))
}

/// Where mesh files are looked for: the URDF's directory (none for standard input or a
/// pipe), the package directories of `--package-dir NAME=PATH`, and the bounds on a file.
#[derive(Clone, Debug, Default)]
pub struct MeshSearch {
    /// The URDF's directory: relative names are resolved there.
    pub dir: Option<PathBuf>,
    /// `package://NAME/rest` is `PATH/rest` for each `(NAME, PATH)`.
    pub packages: Vec<(String, PathBuf)>,
    /// The bounds on each mesh file.
    pub limits: Limits,
}

/// The mesh formats read, by file extension (case-insensitive).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum MeshFormat {
    File(meshfile::Format),
    Collada,
}

fn mesh_format(filename: &str) -> Result<MeshFormat, String> {
    let path = Path::new(filename);
    if let Some(f) = meshfile::Format::of(path) {
        return Ok(MeshFormat::File(f));
    }
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("dae") => Ok(MeshFormat::Collada),
        e => Err(format!(
            "mesh '{filename}': unsupported format{} (STL, OBJ and COLLADA .dae are read)",
            e.map_or(String::from(" (no extension)"), |e| format!(" '.{e}'"))
        )),
    }
}

/// The file a mesh name means. `package://NAME/rest` is `PATH/rest` when `--package-dir
/// NAME=PATH` names the package; otherwise it is looked up as `rest` and `NAME/rest` in
/// the URDF's directory and its parent (a package beside its URDF); other names are
/// relative to the URDF's directory.
fn mesh_path(filename: &str, search: &MeshSearch) -> Result<PathBuf, String> {
    let not_found = |looked: &Path| {
        format!(
            "mesh '{filename}' not found (looked for {})",
            looked.display()
        )
    };
    if let Some(rest) = filename.strip_prefix("package://") {
        let (package, after_pkg) = rest.split_once('/').unwrap_or((rest, ""));
        if let Some((_, root)) = search.packages.iter().rev().find(|(n, _)| n == package) {
            let path = root.join(after_pkg);
            // Any existing path: a device, FIFO or directory is then refused by name.
            return if path.exists() {
                Ok(path)
            } else {
                Err(not_found(&path))
            };
        }
        let found = search.dir.as_deref().and_then(|dir| {
            let parent = dir.parent().unwrap_or(dir);
            [
                dir.join(after_pkg),
                parent.join(after_pkg),
                dir.join(rest),
                parent.join(rest),
            ]
            .into_iter()
            .find(|p| p.exists())
        });
        return found.ok_or_else(|| {
            format!(
                "mesh '{filename}': unknown package '{package}' (give --package-dir \
                 {package}=PATH)"
            )
        });
    }
    let name = Path::new(filename.strip_prefix("file://").unwrap_or(filename));
    let path = match &search.dir {
        _ if name.is_absolute() => name.to_path_buf(),
        Some(dir) => dir.join(name),
        None => {
            return Err(format!(
                "mesh '{filename}': a relative name and the URDF has no directory (standard \
                 input or a pipe)"
            ))
        }
    };
    if path.exists() {
        Ok(path)
    } else {
        Err(not_found(&path))
    }
}

/// Loads an STL, OBJ or COLLADA mesh, scaled, within `limits`; with the notice of its
/// reduction, if it was reduced.
fn load_mesh(
    path: &Path,
    format: MeshFormat,
    scale: [f64; 3],
    limits: &Limits,
) -> Result<(Shape, Option<String>), String> {
    let bytes = meshfile::read(path, limits)?;
    let mesh = match format {
        MeshFormat::File(format) => meshfile::parse(&bytes, format, scale, limits)?,
        MeshFormat::Collada => {
            let dae = ppoe_build::collada::parse(&bytes).map_err(|e| e.to_string())?;
            meshfile::from_triangles(dae.vertices, dae.triangles, scale, limits)?
        }
    };
    let shape = Shape {
        vertices: mesh.vertices,
        faces: mesh.triangles.iter().map(|t| t.to_vec()).collect(),
        closed: false,
    };
    Ok((shape, mesh.reduced))
}

/// The shape of a geometry (with a notice if a mesh was reduced), or a notice why it is
/// skipped.
fn shape(geometry: &Geometry, search: &MeshSearch) -> Result<(Shape, Option<String>), String> {
    Ok((
        match geometry {
            Geometry::Cylinder { radius, length } => Shape::cylinder(*radius, *length),
            Geometry::Sphere { radius } => Shape::sphere(*radius),
            Geometry::Box { size } => Shape::cuboid(*size),
            Geometry::Mesh { filename, scale } => {
                let format = mesh_format(filename)?;
                let path = mesh_path(filename, search)?;
                let named = |e: String| format!("mesh '{}': {e}", path.display());
                let loaded = load_mesh(&path, format, *scale, &search.limits);
                let (shape, reduced) = loaded.map_err(named)?;
                return Ok((shape, reduced.map(named)));
            }
            Geometry::Empty => return Err("an empty <geometry>".into()),
            Geometry::Other { element } => return Err(format!("unknown geometry <{element}>")),
        },
        None,
    ))
}

/// `T_base←link(0)` and the number of chain joints above `link`, or `None` when the link is
/// not at or below `base`.
fn link_home(tree: &Tree<'_>, base: &str, chain: &[&str], link: &str) -> Option<(Mat4, usize)> {
    let mut t = IDENTITY;
    let mut prefix = 0;
    for j in tree.joints_above(link, base)? {
        t = mul4(&j.child2parent, &t);
        if let Some(i) = chain.iter().position(|n| *n == j.name) {
            prefix = prefix.max(i + 1);
        }
    }
    Some((t, prefix))
}

impl Visuals {
    /// The visuals of `urdf`'s links at or below `base`, for the chain through `joints`
    /// (moving joints, base to tip); meshes are looked up around `dir`. Returns the visuals
    /// and the notices of what was skipped.
    ///
    /// # Errors
    /// A malformed `<visual>` of a link at or below `base`, or a malformed top-level
    /// `<material>` (ppoe-build keeps these as the items' errors).
    pub fn from_urdf(
        urdf: &Urdf,
        base: &str,
        joints: &[&str],
        dir: Option<&Path>,
    ) -> anyhow::Result<(Visuals, Vec<String>)> {
        let search = MeshSearch {
            dir: dir.map(Path::to_path_buf),
            ..MeshSearch::default()
        };
        Self::from_urdf_with(urdf, base, joints, &search)
    }

    /// [`Visuals::from_urdf`] with meshes looked up as `search` says, within its bounds
    /// (a mesh beyond them is skipped or reduced, with a notice).
    ///
    /// # Errors
    /// As [`Visuals::from_urdf`].
    pub fn from_urdf_with(
        urdf: &Urdf,
        base: &str,
        joints: &[&str],
        search: &MeshSearch,
    ) -> anyhow::Result<(Visuals, Vec<String>)> {
        let named = materials(urdf)?;
        let tree = urdf.tree();
        // Equal geometries share one shape (a mesh is loaded once); the key is the
        // geometry's `Debug` text, which round-trips every number.
        let mut shapes: HashMap<String, Arc<Shape>> = HashMap::new();
        let (mut parts, mut notices) = (Vec::new(), Vec::new());
        for link in &urdf.links {
            let name = &link.name;
            let Some((home, prefix)) = link_home(&tree, base, joints, name) else {
                continue;
            };
            for v in &link.visuals {
                let v = v.as_ref().map_err(item_error)?;
                let Some(g) = &v.geometry else {
                    notices.push(format!("link '{name}': a <visual> without <geometry>"));
                    continue;
                };
                let key = format!("{g:?}");
                let shape = match shapes.get(&key) {
                    Some(s) => s.clone(),
                    None => match shape(g, search) {
                        Ok((s, reduced)) => {
                            if let Some(why) = reduced {
                                notices.push(format!("link '{name}': {why}"));
                            }
                            shapes.entry(key).or_insert(Arc::new(s)).clone()
                        }
                        Err(why) => {
                            notices.push(format!("link '{name}': {why}, skipped"));
                            continue;
                        }
                    },
                };
                parts.push(Part {
                    prefix,
                    home: mul4(&home, &v.origin),
                    shape,
                    rgb: visual_rgb(v, &named).unwrap_or(DEFAULT_RGB),
                });
            }
        }
        Ok((Visuals { parts }, notices))
    }

    /// The visuals of the calibrated robot: a link below the `k`-th chain joint moved by
    /// `folds[k - 1]` (`Fₖ = E₁···Eₖ`, see [`crate::noise::Applied::folds`]), so that
    /// [`Visuals::place`] with the folded chain's prefixes puts it where the calibrated
    /// product `Exp(S₁''(θ₁+δ₁))···Exp(Sₖ''(θₖ+δₖ))` does. The home correction μ is not a
    /// joint's: it moves the tool frame only, not the drawn links. No folds: unchanged.
    pub fn fold(&mut self, folds: &[Mat4]) {
        for p in &mut self.parts {
            if let Some(f) = p.prefix.checked_sub(1).and_then(|k| folds.get(k)) {
                p.home = mul4(f, &p.home);
            }
        }
    }

    /// The visuals at a state of the arm: `prefix[k] = Exp(S₁θ₁)·…·Exp(S_kθ_k)`
    /// (`prefix[0]` the identity), one entry per chain joint plus one.
    pub fn place(&self, prefix: &[Mat4]) -> Vec<Body> {
        self.parts
            .iter()
            .filter_map(|p| {
                Some(Body {
                    shape: p.shape.clone(),
                    pose: mul4(prefix.get(p.prefix)?, &p.home),
                    rgb: p.rgb,
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::picture::geom::origin as translation;
    use ppoe::chain::Convention;

    #[test]
    fn bad_visual_numbers_are_errors() {
        for geometry in [
            r#"<cylinder radius="-1" length="0.1"/>"#,
            r#"<cylinder radius="inf" length="0.1"/>"#,
            r#"<box size="0.1 0.2"/>"#,
            r#"<box size="0.1 -0.2 0.3"/>"#,
            r#"<sphere/>"#,
        ] {
            let text = format!(
                r#"<robot name="r"><link name="a"><visual><geometry>{geometry}</geometry></visual></link></robot>"#
            );
            let urdf = Urdf::parse(&text).unwrap();
            let err = Visuals::from_urdf(&urdf, "a", &[], None).unwrap_err();
            assert!(
                format!("{err:#}").contains("link 'a'"),
                "{geometry}: {err:#}"
            );
            // Only the links drawn count: below another base the bad visual is not read.
            let text = format!(
                r#"<robot name="r"><link name="a"><visual><geometry>{geometry}</geometry></visual></link>
                <link name="b"/><joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>"#
            );
            let urdf = Urdf::parse(&text).unwrap();
            let (v, notices) = Visuals::from_urdf(&urdf, "b", &[], None).unwrap();
            assert!(v.parts.is_empty() && notices.is_empty(), "{geometry}");
        }
    }

    /// The seed's flange cylinder (link6, origin z 0.025) sits 0.025 m behind the tool
    /// along the tool's z axis (the tool is link6 moved 0.05 m along z), with the tool's
    /// orientation: checked against the core library's tool pose at the seed's frame 100.
    #[test]
    fn visuals_follow_the_core_forward_kinematics() {
        let chain = crate::seed::SEED.as_ref();
        let thetas = crate::seed::thetas_at(100, 200);
        let covs = crate::seed::covs();
        let pose = chain
            .ppoe_checked(&thetas, &covs, Convention::Right)
            .unwrap()
            .pose
            .to_matrix4();
        let mut p = ppoe::Transform::identity();
        let mut prefix = vec![IDENTITY];
        for (j, t) in chain.joints.iter().zip(&thetas) {
            p = p * j.displacement(j.clip(*t, false));
            prefix.push(p.to_matrix4());
        }
        let bodies = crate::seed::visuals().unwrap().place(&prefix);
        let flange = bodies.last().unwrap();
        let o = translation(&flange.pose);
        for k in 0..3 {
            assert!((o[k] - (pose[k][3] - 0.025 * pose[k][2])).abs() < 1e-12);
            for (a, b) in flange.pose[k][..3].iter().zip(&pose[k][..3]) {
                assert!((a - b).abs() < 1e-12);
            }
        }
    }

    fn bounds(shape: &Shape) -> [[f64; 2]; 3] {
        let mut b = [[f64::INFINITY, f64::NEG_INFINITY]; 3];
        for f in &shape.faces {
            for &i in f {
                for (k, x) in shape.vertices[i as usize].iter().enumerate() {
                    b[k] = [b[k][0].min(*x), b[k][1].max(*x)];
                }
            }
        }
        b
    }

    /// The UR-style test robot's COLLADA meshes from its `--package-dir`: the cube (12
    /// triangles) and the millimetre, Y-up tetrahedron (4 triangles, scaled by the URDF's
    /// `scale` here) have the bounding boxes their files' comments derive by hand; each
    /// other visual is skipped with its reason.
    #[test]
    fn collada_meshes_from_a_package_dir() {
        let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let urdf_path = repo.join("test_data/urdf/ur_style.urdf");
        if !urdf_path.exists() {
            // The published package has no repository test data (scripts/publish-check.sh
            // tests the unpacked crate); the repository's `cargo test` runs this test.
            eprintln!(
                "skipped: {} is not here (not a repository checkout)",
                urdf_path.display()
            );
            return;
        }
        let text = std::fs::read_to_string(&urdf_path).unwrap();
        let text = text.replace("shoulder_mm.dae\"/>", "shoulder_mm.dae\" scale=\"2 1 1\"/>");
        let urdf = Urdf::parse(&text).unwrap();
        let joints = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"];
        let search = MeshSearch {
            dir: Some(repo.join("test_data/urdf")),
            packages: vec![(
                "ppoe_ur_style".into(),
                repo.join("test_data/packages/ppoe_ur_style"),
            )],
            ..MeshSearch::default()
        };
        let (v, notices) = Visuals::from_urdf_with(&urdf, "base_link", &joints, &search).unwrap();
        assert_eq!(v.parts.len(), 2, "{notices:?}");
        let cube = &v.parts[0].shape;
        assert_eq!(cube.faces.len(), 12);
        let want = [[-0.05, 0.05], [-0.05, 0.05], [0.0, 0.1]];
        assert_eq!(bounds(cube), want);
        let tetra = &v.parts[1].shape;
        assert_eq!(tetra.faces.len(), 4);
        let b = bounds(tetra);
        let want = [[0.0, 0.2], [-0.1, 0.0], [0.0, 0.1]];
        for k in 0..3 {
            for e in 0..2 {
                assert!((b[k][e] - want[k][e]).abs() < 1e-15, "{b:?}");
            }
        }
        // The tetrahedron's link is one joint down, at its visual's origin 0.1 m up.
        assert_eq!(v.parts[1].prefix, 1);
        assert_eq!(translation(&v.parts[1].home), [0.0, 0.0, 0.2]);
        let expected = [
            "unknown package 'ppoe_missing_description' (give --package-dir",
            "forearm.dae' not found (looked for ",
            "unsupported format '.3ds'",
            "broken.dae': malformed XML",
        ];
        assert_eq!(notices.len(), expected.len(), "{notices:?}");
        for (n, e) in notices.iter().zip(expected) {
            assert!(n.contains(e) && n.ends_with(", skipped"), "{n}");
        }
    }
}
