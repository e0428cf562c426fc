//! Solid geometry drawn with the arm: URDF visual primitives (cylinder, box, sphere) and
//! loaded meshes as polygon meshes in their own frame, and a [`Body`] = a shape placed in
//! the base frame with a colour.

use super::geom::{cross, dot, sub, Mat4};
use std::sync::Arc;

/// Sides of a cylinder's polygon approximation: enough for a smooth silhouette at the
/// picture's size (a 5 cm radius spans about 30 pixels).
const CYLINDER_SIDES: usize = 24;
/// Latitude bands of a sphere (twice as many longitude sectors).
const SPHERE_BANDS: usize = 10;

/// A polygon mesh in its own frame (metres): convex planar faces given as vertex indices.
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// The vertices.
    pub vertices: Vec<[f64; 3]>,
    /// The faces, each a convex polygon of at least three vertex indices.
    pub faces: Vec<Vec<u32>>,
    /// `true` when the mesh is closed and every face is wound counter-clockwise seen from
    /// outside, so faces turned away from the viewer can be skipped; `false` for loaded
    /// meshes, whose winding is not trusted (both sides are drawn).
    pub closed: bool,
}

impl Shape {
    /// A cylinder along its z axis, centred on its origin (the URDF convention).
    pub fn cylinder(radius: f64, length: f64) -> Shape {
        let n = CYLINDER_SIDES;
        let h = length / 2.0;
        let mut vertices = Vec::with_capacity(2 * n);
        for z in [-h, h] {
            for i in 0..n {
                let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                vertices.push([radius * a.cos(), radius * a.sin(), z]);
            }
        }
        let n32 = n as u32;
        let mut faces: Vec<Vec<u32>> = (0..n32)
            .map(|i| {
                let j = (i + 1) % n32;
                vec![i, j, n32 + j, n32 + i]
            })
            .collect();
        faces.push((0..n32).rev().collect());
        faces.push((n32..2 * n32).collect());
        Shape {
            vertices,
            faces,
            closed: true,
        }
    }

    /// A box of the given side lengths, centred on its origin.
    pub fn cuboid(size: [f64; 3]) -> Shape {
        let h = size.map(|s| s / 2.0);
        let vertices = (0..8)
            .map(|i| {
                let s = |bit: usize, k: usize| if i >> bit & 1 == 1 { h[k] } else { -h[k] };
                [s(0, 0), s(1, 1), s(2, 2)]
            })
            .collect();
        let faces = vec![
            vec![0, 2, 3, 1],
            vec![4, 5, 7, 6],
            vec![0, 1, 5, 4],
            vec![2, 6, 7, 3],
            vec![0, 4, 6, 2],
            vec![1, 3, 7, 5],
        ];
        Shape {
            vertices,
            faces,
            closed: true,
        }
    }

    /// A sphere centred on its origin.
    pub fn sphere(radius: f64) -> Shape {
        let (bands, sectors) = (SPHERE_BANDS, 2 * SPHERE_BANDS);
        let mut vertices = vec![[0.0, 0.0, -radius]];
        for b in 1..bands {
            let phi = std::f64::consts::PI * b as f64 / bands as f64;
            for s in 0..sectors {
                let th = 2.0 * std::f64::consts::PI * s as f64 / sectors as f64;
                let r = radius * phi.sin();
                vertices.push([r * th.cos(), r * th.sin(), -radius * phi.cos()]);
            }
        }
        vertices.push([0.0, 0.0, radius]);
        let top = vertices.len() as u32 - 1;
        let ring = |b: usize, s: usize| (1 + (b - 1) * sectors + s % sectors) as u32;
        let mut faces = Vec::new();
        for s in 0..sectors {
            faces.push(vec![0, ring(1, s + 1), ring(1, s)]);
            for b in 1..bands - 1 {
                faces.push(vec![
                    ring(b, s),
                    ring(b, s + 1),
                    ring(b + 1, s + 1),
                    ring(b + 1, s),
                ]);
            }
            faces.push(vec![ring(bands - 1, s), ring(bands - 1, s + 1), top]);
        }
        Shape {
            vertices,
            faces,
            closed: true,
        }
    }

    /// Whether the mesh is wound outwards: the normals of a closed mesh point away from its
    /// vertices' centroid (used by the tests).
    #[cfg_attr(not(test), allow(dead_code))]
    pub fn winds_outwards(&self) -> bool {
        let c = self
            .vertices
            .iter()
            .fold([0.0; 3], |s, v| [s[0] + v[0], s[1] + v[1], s[2] + v[2]]);
        let c = c.map(|x| x / self.vertices.len() as f64);
        self.faces.iter().all(|f| {
            let pts: Vec<[f64; 3]> = f.iter().map(|&i| self.vertices[i as usize]).collect();
            let m = pts
                .iter()
                .fold([0.0; 3], |s, v| [s[0] + v[0], s[1] + v[1], s[2] + v[2]]);
            let m = m.map(|x| x / pts.len() as f64);
            dot(polygon_normal(&pts), sub(m, c)) > 0.0
        })
    }
}

/// The unnormalised normal of a planar polygon, counter-clockwise = towards the viewer
/// (Newell's method: robust for any vertex count).
pub fn polygon_normal(points: &[[f64; 3]]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for (i, a) in points.iter().enumerate() {
        let c = cross(*a, points[(i + 1) % points.len()]);
        for k in 0..3 {
            n[k] += c[k];
        }
    }
    n
}

/// A shape placed in the base frame, with its colour.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// The geometry, in its own frame; shared by every frame of an animation.
    pub shape: Arc<Shape>,
    /// `T_base←shape` at this frame.
    pub pose: Mat4,
    /// The colour (sRGB).
    pub rgb: [u8; 3],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitives_are_closed_and_wound_outwards() {
        for s in [
            Shape::cylinder(0.05, 0.3),
            Shape::cuboid([0.1, 0.2, 0.3]),
            Shape::sphere(0.07),
        ] {
            assert!(s.closed && s.winds_outwards(), "{s:?}");
            for f in &s.faces {
                assert!(f.len() >= 3 && f.iter().all(|&i| (i as usize) < s.vertices.len()));
            }
        }
    }

    #[test]
    fn primitives_have_the_stated_size() {
        let ext = |s: &Shape, k: usize| {
            let (lo, hi) = s.vertices.iter().fold((f64::MAX, f64::MIN), |(lo, hi), v| {
                (lo.min(v[k]), hi.max(v[k]))
            });
            hi - lo
        };
        let c = Shape::cylinder(0.05, 0.3);
        assert!((ext(&c, 2) - 0.3).abs() < 1e-12 && (ext(&c, 0) - 0.1).abs() < 1e-12);
        let b = Shape::cuboid([0.1, 0.2, 0.3]);
        for (k, e) in [0.1, 0.2, 0.3].iter().enumerate() {
            assert!((ext(&b, k) - e).abs() < 1e-12);
        }
        let s = Shape::sphere(0.07);
        assert!((ext(&s, 2) - 0.14).abs() < 1e-12);
    }
}
