//! The robot's visual geometry from a URDF's `<visual>` elements, for the pictures:
//! cylinders, boxes and spheres with their `<origin>` and material colours, and meshes
//! (STL, OBJ) loaded from the URDF's directory (`package://` or relative paths); a mesh
//! that cannot be found or read (or a COLLADA `.dae`) is skipped with a notice.
//! Kinematic tables (`ppoe-build`) ignore visuals; only the drawing tools read them.
//!
//! Each visual is placed with the product of exponentials: a link below the `k`-th chain
//! joint is at `T_base←link(θ) = Exp(S₁θ₁)·…·Exp(S_kθ_k)·T_base←link(0)`, where
//! `T_base←link(0)` is the product of the joint origins from the base down to the link.

use crate::picture::geom::{mul4, Mat4, IDENTITY};
use crate::picture::{Body, Shape};
use anyhow::{anyhow, bail, Context};
use ppoe_build::Urdf;
use roxmltree::Node;
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

fn attr_numbers(node: Node<'_, '_>, name: &str, n: usize) -> anyhow::Result<Option<Vec<f64>>> {
    let Some(text) = node.attribute(name) else {
        return Ok(None);
    };
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| {
            anyhow!(
                "<{}> {name}=\"{text}\": expected numbers",
                node.tag_name().name()
            )
        })?;
    if v.len() != n || !v.iter().all(|x| x.is_finite()) {
        bail!(
            "<{}> {name}=\"{text}\": expected {n} finite numbers",
            node.tag_name().name()
        );
    }
    Ok(Some(v))
}

fn child<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.has_tag_name(name))
}

/// `<origin xyz rpy>` as a transform: `[Rz(yaw)·Ry(pitch)·Rx(roll), xyz]` (URDF's fixed-axis
/// roll-pitch-yaw).
fn origin(node: Option<Node<'_, '_>>) -> anyhow::Result<Mat4> {
    let Some(node) = node else {
        return Ok(IDENTITY);
    };
    let xyz = attr_numbers(node, "xyz", 3)?.unwrap_or(vec![0.0; 3]);
    let rpy = attr_numbers(node, "rpy", 3)?.unwrap_or(vec![0.0; 3]);
    let (sr, cr) = rpy[0].sin_cos();
    let (sp, cp) = rpy[1].sin_cos();
    let (sy, cy) = rpy[2].sin_cos();
    Ok([
        [
            cy * cp,
            cy * sp * sr - sy * cr,
            cy * sp * cr + sy * sr,
            xyz[0],
        ],
        [
            sy * cp,
            sy * sp * sr + cy * cr,
            sy * sp * cr - cy * sr,
            xyz[1],
        ],
        [-sp, cp * sr, cp * cr, xyz[2]],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// The sRGB of `<color rgba>` (components clamped to [0, 1]).
fn colour(node: Node<'_, '_>) -> anyhow::Result<Option<[u8; 3]>> {
    let Some(c) = child(node, "color") else {
        return Ok(None);
    };
    Ok(attr_numbers(c, "rgba", 4)?
        .map(|v| [0, 1, 2].map(|k| (v[k].clamp(0.0, 1.0) * 255.0).round() as u8)))
}

/// The named materials declared at the robot's top level.
fn materials(robot: Node<'_, '_>) -> anyhow::Result<HashMap<String, [u8; 3]>> {
    let mut out = HashMap::new();
    for m in robot.children().filter(|c| c.has_tag_name("material")) {
        if let (Some(name), Some(rgb)) = (m.attribute("name"), colour(m)?) {
            out.insert(name.to_string(), rgb);
        }
    }
    Ok(out)
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

/// The shape of a `<geometry>`, or a notice why it is skipped.
fn geometry(node: Node<'_, '_>, dir: Option<&Path>) -> anyhow::Result<Result<Shape, String>> {
    let Some(g) = node.children().find(|c| c.is_element()) else {
        return Ok(Err("an empty <geometry>".into()));
    };
    let num = |name: &str| -> anyhow::Result<f64> {
        let v = attr_numbers(g, name, 1)?
            .ok_or_else(|| anyhow!("<{}> has no {name}", g.tag_name().name()))?;
        if v[0] < 0.0 {
            bail!("<{}> {name} is negative", g.tag_name().name());
        }
        Ok(v[0])
    };
    Ok(Ok(match g.tag_name().name() {
        "cylinder" => Shape::cylinder(num("radius")?, num("length")?),
        "sphere" => Shape::sphere(num("radius")?),
        "box" => {
            let s = attr_numbers(g, "size", 3)?.ok_or_else(|| anyhow!("<box> has no size"))?;
            if s.iter().any(|&x| x < 0.0) {
                bail!("<box> size has a negative side");
            }
            Shape::cuboid([s[0], s[1], s[2]])
        }
        "mesh" => {
            let name = g.attribute("filename").unwrap_or_default();
            let scale = attr_numbers(g, "scale", 3)?.map_or([1.0; 3], |s| [s[0], s[1], s[2]]);
            let Some(dir) = dir else {
                return Ok(Err(format!("mesh '{name}': no directory to look in")));
            };
            let Some(path) = mesh_candidates(name, dir).into_iter().find(|p| p.is_file()) else {
                return Ok(Err(format!("mesh '{name}' not found")));
            };
            match load_mesh(&path, scale) {
                Ok(s) => s,
                Err(e) => return Ok(Err(format!("mesh '{}': {e}", path.display()))),
            }
        }
        other => return Ok(Err(format!("unknown geometry <{other}>"))),
    }))
}

/// `T_base←link(0)` and the number of chain joints above `link`, or `None` when the link is
/// not at or below `base`.
fn link_home(urdf: &Urdf, base: &str, chain: &[&str], link: &str) -> Option<(Mat4, usize)> {
    let mut t = IDENTITY;
    let mut prefix = 0;
    let mut cur = link;
    for _ in 0..=urdf.joints.len() {
        if cur == base {
            return Some((t, prefix));
        }
        let j = urdf.joints.iter().find(|j| j.child == cur)?;
        t = mul4(&j.child2parent, &t);
        if let Some(i) = chain.iter().position(|n| *n == j.name) {
            prefix = prefix.max(i + 1);
        }
        cur = j.parent.as_str();
    }
    None
}

impl Visuals {
    /// Reads the `<visual>`s of `text` (the URDF already parsed as `urdf`) for the chain
    /// from `base` through `joints` (moving joints, base to tip); meshes are looked up
    /// around `dir`. Returns the visuals and the notices of what was skipped.
    ///
    /// # Errors
    /// Malformed XML, or a malformed number, size or colour in a `<visual>` or `<material>`.
    pub fn from_urdf(
        text: &str,
        urdf: &Urdf,
        base: &str,
        joints: &[&str],
        dir: Option<&Path>,
    ) -> anyhow::Result<(Visuals, Vec<String>)> {
        let doc = roxmltree::Document::parse(text).context("the URDF's visuals")?;
        let robot = doc.root_element();
        let named = materials(robot)?;
        let mut shapes: HashMap<String, Arc<Shape>> = HashMap::new();
        let (mut parts, mut notices) = (Vec::new(), Vec::new());
        for link in robot.children().filter(|c| c.has_tag_name("link")) {
            let name = link.attribute("name").unwrap_or_default();
            for v in link.children().filter(|c| c.has_tag_name("visual")) {
                let Some((home, prefix)) = link_home(urdf, base, joints, name) else {
                    continue;
                };
                let Some(g) = child(v, "geometry") else {
                    notices.push(format!("link '{name}': a <visual> without <geometry>"));
                    continue;
                };
                let key = doc.input_text()[g.range()].to_string();
                let shape = match shapes.get(&key) {
                    Some(s) => s.clone(),
                    None => match geometry(g, dir).with_context(|| format!("link '{name}'"))? {
                        Ok(s) => shapes.entry(key).or_insert(Arc::new(s)).clone(),
                        Err(why) => {
                            notices.push(format!("link '{name}': {why}, skipped"));
                            continue;
                        }
                    },
                };
                let material = child(v, "material");
                let rgb = match material {
                    Some(m) => colour(m)?
                        .or_else(|| m.attribute("name").and_then(|n| named.get(n).copied())),
                    None => None,
                };
                let local = origin(child(v, "origin")).with_context(|| format!("link '{name}'"))?;
                parts.push(Part {
                    prefix,
                    home: mul4(&home, &local),
                    shape,
                    rgb: rgb.unwrap_or(DEFAULT_RGB),
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

    /// `<origin>` as `ppoe-build` reads it for a joint, the independent reference.
    fn build_origin(xyz: &str, rpy: &str) -> Mat4 {
        let text = format!(
            r#"<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="fixed">
               <origin xyz="{xyz}" rpy="{rpy}"/><parent link="a"/><child link="b"/></joint></robot>"#
        );
        Urdf::parse(&text).unwrap().joints[0].child2parent
    }

    #[test]
    fn origins_match_ppoe_build() {
        for (xyz, rpy) in [
            ("0 0 0", "0 0 0"),
            ("0.1 -0.2 0.3", "0.3 -1.2 2.5"),
            ("1 2 3", "1.570796 0 -1.570796"),
        ] {
            let text = format!(r#"<origin xyz="{xyz}" rpy="{rpy}"/>"#);
            let doc = roxmltree::Document::parse(&text).unwrap();
            let ours = origin(Some(doc.root_element())).unwrap();
            let want = build_origin(xyz, rpy);
            for i in 0..4 {
                for j in 0..4 {
                    assert!(
                        (ours[i][j] - want[i][j]).abs() < 1e-15,
                        "{xyz} {rpy}: {ours:?} vs {want:?}"
                    );
                }
            }
        }
    }

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
            let err = Visuals::from_urdf(&text, &urdf, "a", &[], None).unwrap_err();
            assert!(
                format!("{err:#}").contains("link 'a'"),
                "{geometry}: {err:#}"
            );
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
