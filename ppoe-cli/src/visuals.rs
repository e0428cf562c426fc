//! The robot's visual geometry from a URDF's `<visual>` elements, for the pictures:
//! cylinders, boxes and spheres with their `<origin>` and material colours, and meshes
//! (STL, OBJ) loaded from the URDF's directory (`package://` or relative paths); a mesh
//! that cannot be found or read (or a COLLADA `.dae`) is skipped with a notice.
//! The `<visual>`s are read by ppoe-build with the rest of the URDF (`Link::visuals`, the
//! link/joint tree); this file turns them into shapes and places them, and reads no XML.
//!
//! Each visual is placed with the product of exponentials: a link below the `k`-th chain
//! joint is at `T_base←link(θ) = Exp(S₁θ₁)·…·Exp(S_kθ_k)·T_base←link(0)`, where
//! `T_base←link(0)` is the product of the joint origins from the base down to the link.

use crate::picture::geom::{mul4, Mat4, IDENTITY};
use crate::picture::{Body, Shape};
use anyhow::{anyhow, bail};
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

/// Where a mesh file named in the URDF may be: `package://pkg/rest` is looked up as `rest`
/// and `pkg/rest` in the URDF's directory and its parent; other names relative to the
/// URDF's directory.
fn mesh_candidates(filename: &str, dir: &Path) -> Vec<PathBuf> {
    if let Some(rest) = filename.strip_prefix("package://") {
        let after_pkg = rest.split_once('/').map_or(rest, |(_, r)| r);
        let parent = dir.parent().unwrap_or(dir);
        return vec![
            dir.join(after_pkg),
            parent.join(after_pkg),
            dir.join(rest),
            parent.join(rest),
        ];
    }
    let name = filename.strip_prefix("file://").unwrap_or(filename);
    vec![dir.join(name)]
}

/// Loads an STL or OBJ mesh, scaled.
fn load_mesh(path: &Path, scale: [f64; 3]) -> anyhow::Result<Shape> {
    let ext = path.extension().map(|e| e.to_ascii_lowercase());
    let (vertices, faces): (Vec<[f64; 3]>, Vec<Vec<u32>>) =
        match ext.as_ref().and_then(|e| e.to_str()) {
            Some("stl") => {
                let mut f = std::fs::File::open(path)?;
                let m = stl_io::read_stl(&mut f)?;
                let v = m
                    .vertices
                    .iter()
                    .map(|v| [0, 1, 2].map(|k| v[k] as f64))
                    .collect();
                let f = m
                    .faces
                    .iter()
                    .map(|t| t.vertices.iter().map(|&i| i as u32).collect())
                    .collect();
                (v, f)
            }
            Some("obj") => {
                let (models, _) = tobj::load_obj(path, &tobj::GPU_LOAD_OPTIONS)?;
                let mut v = Vec::new();
                let mut f = Vec::new();
                for m in models {
                    let base = v.len() as u32;
                    v.extend(
                        m.mesh
                            .positions
                            .chunks_exact(3)
                            .map(|p| [0, 1, 2].map(|k| p[k] as f64)),
                    );
                    f.extend(
                        m.mesh
                            .indices
                            .chunks_exact(3)
                            .map(|t| t.iter().map(|&i| base + i).collect()),
                    );
                }
                (v, f)
            }
            _ => bail!("only STL and OBJ meshes are read"),
        };
    if vertices.is_empty() || vertices.iter().flatten().any(|x| !x.is_finite()) {
        bail!("no finite vertices");
    }
    let n = vertices.len();
    if faces
        .iter()
        .any(|f: &Vec<u32>| f.len() < 3 || f.iter().any(|&i| i as usize >= n))
    {
        bail!("a face with a missing vertex");
    }
    let vertices = vertices
        .into_iter()
        .map(|p| [0, 1, 2].map(|k| p[k] * scale[k]))
        .collect();
    Ok(Shape {
        vertices,
        faces,
        closed: false,
    })
}

/// The shape of a geometry, or a notice why it is skipped.
fn shape(geometry: &Geometry, dir: Option<&Path>) -> Result<Shape, String> {
    Ok(match geometry {
        Geometry::Cylinder { radius, length } => Shape::cylinder(*radius, *length),
        Geometry::Sphere { radius } => Shape::sphere(*radius),
        Geometry::Box { size } => Shape::cuboid(*size),
        Geometry::Mesh { filename, scale } => {
            let Some(dir) = dir else {
                return Err(format!("mesh '{filename}': no directory to look in"));
            };
            let Some(path) = mesh_candidates(filename, dir)
                .into_iter()
                .find(|p| p.is_file())
            else {
                return Err(format!("mesh '{filename}' not found"));
            };
            load_mesh(&path, *scale).map_err(|e| format!("mesh '{}': {e}", path.display()))?
        }
        Geometry::Empty => return Err("an empty <geometry>".into()),
        Geometry::Other { element } => return Err(format!("unknown geometry <{element}>")),
    })
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
                    None => match shape(g, dir) {
                        Ok(s) => shapes.entry(key).or_insert(Arc::new(s)).clone(),
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
}
