//! Coverage of the default equiprobable surface (the lift surface, `Surface::Lift`):
//! sample the PPOE model `T = D₁Exp(ξ₁)…DₙExp(ξₙ)·M` (fixed seed, 10⁵ samples), and count
//! the fraction of sampled tool positions inside the triangulated surface drawn at
//! k = 1, 2, 3. It must be within 0.03 of the probability the surface is drawn for,
//! `chi2_3_probability(k)` = 0.199 / 0.739 / 0.971 (the surface's claim in the
//! `ppoe::surface` module docs, "Which surface to draw").
//!
//! # The inside test
//!
//! The test of record is the **generalized winding number** of the closed triangle mesh
//! (the sum of the signed solid angles of its triangles seen from the point, Van Oosterom
//! & Strackee 1983, divided by 4π; inside if |w| > ½), checked on a unit sphere below. It
//! is exact for any closed, consistently oriented mesh, but costs one `atan2` per triangle:
//! 10⁵ samples × 3 radii × ~7000 triangles is too slow for a test. So each sample is first
//! classified cheaply by its **lift coordinate**:
//!
//! The surface at radius k is `F(k·S²)` for the smooth map `F(s) = t̄ + R̄·p(Exp(B·s))`
//! (`LiftSurface::point`, `F(0) = t̄`, `dF(0) = R̄·Σ_vv^½`, orientation preserving). For a
//! sampled tool position y we solve `F(s) = y` by Newton's method (started from the linear
//! solution). Wherever F is a diffeomorphism of a neighbourhood of the ball `|s| ≤ k`,
//! winding numbers are preserved by F, and the mesh is `F(M')` for a closed surface `M'`
//! in s-space whose vertices lie exactly on the sphere `|s| = k` (the mesh vertices are
//! surface points). If `M'` stays within the shell `k − δ < |s| < k + δ`, it is homotopic
//! to the sphere inside the shell (radial projection, degree 1), so every point with
//! `|s| ≤ k − δ` has winding number 1 and every point with `|s| ≥ k + δ` has 0: those
//! samples are classified without the mesh. δ is measured per mesh: the lift coordinates
//! of all triangle-edge midpoints and centroids deviate from k by at most e, and the
//! deviation over a small triangle is (to second order) a quadratic function vanishing at
//! the vertices, whose maximum is at most the sum of its three edge-midpoint values
//! (≤ 3e); δ = 4e + 10⁻⁶·k. Samples inside the shell, and samples whose Newton iteration
//! does not converge, get the full winding number.
//!
//! As a guard against any flaw in this argument (a non-injective F, a wrong preimage),
//! the first `N_CHECK` samples of every case are also classified by the full winding
//! number at every k and must agree with the fast classification.
//!
//! The winding number itself is summed block by block (8 × 8 grid quads); a block whose
//! bounding sphere does not contain the point contributes the solid angle of the fan over
//! its boundary loop instead of its own triangles, which is exact (see [`Block`]; checked
//! against the plain sum in `winding_number_on_unit_sphere_mesh`) and ~3× cheaper.
//!
//! Run time (test profile, opt-level 2): about 0.5 s of CPU per case (10⁵ samples, 3
//! radii), under 2 s of CPU for the whole file.

mod common;
use common::*;
use ppoe::chain::{screw_noise, ChainView, Convention, Joint};
use ppoe::surface::{chi2_3_probability, unit_sphere_point, LiftSurface};
use ppoe::{se3, Mat3, Mat6, Matrix, Transform, Vec3, Vector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

/// Number of sampled tool positions per case.
const N_SAMPLES: usize = 100_000;
/// Grid size of the surface mesh (`n_steps`): 59 × 59 quads, 6844 non-degenerate triangles.
const N_STEPS: usize = 60;
/// Samples per case that are also classified by the full winding number.
const N_CHECK: usize = 1000;
/// Allowed |fraction − χ²₃ probability|.
const TOL: f64 = 0.03;

type P3 = [f64; 3];

fn sub(a: &P3, b: &P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: &P3, b: &P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: &P3, b: &P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Quads per side of a block of the mesh (see [`Block`]).
const BLOCK: usize = 8;

/// A patch of the mesh (up to `BLOCK × BLOCK` grid quads) with what the exact far-field
/// shortcut needs. Seen from a point q outside the convex hull of the patch, the patch
/// subtends the same signed solid angle as any other surface spanning the same oriented
/// boundary loop inside that hull (the two together form a closed surface inside the
/// hull, whose winding number at q is 0). The fan from the first loop vertex is such a
/// surface, with 4·BLOCK − 2 triangles instead of 2·BLOCK². The hull is tested by the
/// bounding sphere (centre = vertex mean, radius = largest vertex distance).
struct Block {
    center: P3,
    radius: f64,
    tris: Vec<[u32; 3]>,
    fan: Vec<[u32; 3]>,
}

/// A closed triangle mesh: vertices and triangles (vertex indices), consistently
/// oriented, grouped into blocks.
struct Mesh {
    verts: Vec<P3>,
    blocks: Vec<Block>,
}

fn non_degenerate(t: &[u32; 3]) -> bool {
    t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
}

/// The signed solid angle of triangle t seen from the query point, by the formula of
/// Van Oosterom & Strackee (IEEE Trans. Biomed. Eng. 30, 1983), with a = A − q etc.:
/// `tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|)`, evaluated with
/// atan2 (correct for |Ω| up to 2π). `rel` holds each vertex minus q and its length.
fn solid_angle(rel: &[(P3, f64)], t: &[u32; 3]) -> f64 {
    let (a, la) = rel[t[0] as usize];
    let (b, lb) = rel[t[1] as usize];
    let (c, lc) = rel[t[2] as usize];
    let num = dot(&a, &cross(&b, &c));
    let den = la * lb * lc + dot(&a, &b) * lc + dot(&a, &c) * lb + dot(&b, &c) * la;
    2.0 * num.atan2(den)
}

impl Mesh {
    /// The closed mesh of a row-major `n × n` unit-sphere grid (the layout of
    /// `lift_surface`, see the `surface` module docs): rows i = φ from the north pole
    /// (i = 0) to the south pole (i = n − 1), columns j = θ with column n − 1 repeating
    /// column 0. Each quad `(i, j), (i+1, j), (i+1, j+1), (i, j+1)` gives the triangles
    /// `(a, b, c)` and `(a, c, d)`; on the unit sphere `∂u/∂φ × ∂u/∂θ = u`, so they face
    /// outwards, and F (orientation preserving) keeps that.
    ///
    /// To make the mesh watertight bit for bit, the last column is identified with
    /// column 0 and each pole row with its first point (the grid's repeated points differ
    /// by rounding of sin(2π), sin(π), ~10⁻¹⁶); the pole triangles that degenerate to a
    /// segment are dropped (their solid angle is 0 anyway).
    fn from_grid(grid: &[Vec3<f64>], n: usize) -> Self {
        assert!(n >= 3 && grid.len() >= n * n);
        // Vertex numbering: 0 = north pole, rows 1..n−1 with m columns each, then south.
        let m = n - 1;
        let south = 1 + (n - 2) * m;
        let idx = |i: usize, j: usize| -> u32 {
            let j = j % m;
            let k = if i == 0 {
                0
            } else if i == n - 1 {
                south
            } else {
                1 + (i - 1) * m + j
            };
            k as u32
        };
        let mut verts = vec![[0.0; 3]; south + 1];
        for i in 0..n {
            for j in 0..m {
                verts[idx(i, j) as usize] = grid[i * n + j].0;
            }
        }
        let mut blocks = Vec::new();
        for i0 in (0..m).step_by(BLOCK) {
            for j0 in (0..m).step_by(BLOCK) {
                let (i1, j1) = ((i0 + BLOCK).min(m), (j0 + BLOCK).min(m));
                let mut tris = Vec::new();
                for i in i0..i1 {
                    for j in j0..j1 {
                        let (a, b) = (idx(i, j), idx(i + 1, j));
                        let (c, d) = (idx(i + 1, j + 1), idx(i, j + 1));
                        tris.extend([[a, b, c], [a, c, d]].into_iter().filter(non_degenerate));
                    }
                }
                // The boundary loop, oriented like the triangles' edges (a → b → c → d
                // for one quad): down column j0, along row i1, up column j1, back along
                // row i0.
                let mut lp: Vec<u32> = Vec::new();
                let path = (i0..i1)
                    .map(|i| idx(i, j0))
                    .chain((j0..j1).map(|j| idx(i1, j)))
                    .chain((i0 + 1..=i1).rev().map(|i| idx(i, j1)))
                    .chain((j0 + 1..=j1).rev().map(|j| idx(i0, j)));
                for v in path {
                    if lp.last() != Some(&v) {
                        lp.push(v);
                    }
                }
                while lp.len() > 1 && lp.first() == lp.last() {
                    lp.pop();
                }
                let fan = (1..lp.len().saturating_sub(1))
                    .map(|k| [lp[0], lp[k], lp[k + 1]])
                    .filter(non_degenerate)
                    .collect();
                let bverts: Vec<P3> = tris.iter().flatten().map(|&v| verts[v as usize]).collect();
                let count = bverts.len().max(1) as f64;
                let center: P3 =
                    std::array::from_fn(|k| bverts.iter().map(|v| v[k]).sum::<f64>() / count);
                let radius = bverts
                    .iter()
                    .map(|v| dot(&sub(v, &center), &sub(v, &center)).sqrt())
                    .fold(0.0, f64::max);
                blocks.push(Block {
                    center,
                    radius,
                    tris,
                    fan,
                });
            }
        }
        Self { verts, blocks }
    }

    /// Number of triangles.
    fn n_tris(&self) -> usize {
        self.blocks.iter().map(|b| b.tris.len()).sum()
    }

    /// The generalized winding number of the mesh around `q`: Σ Ω_t / 4π over all the
    /// triangles ([`solid_angle`]); 1 inside a closed outward-oriented mesh, 0 outside, up
    /// to rounding (far from the surface). With `far_field`, blocks whose bounding sphere
    /// does not contain q contribute the solid angle of their boundary fan (exact, see
    /// [`Block`]).
    fn winding_number_with(&self, q: &P3, rel: &mut Vec<(P3, f64)>, far_field: bool) -> f64 {
        rel.clear();
        rel.extend(self.verts.iter().map(|v| {
            let d = sub(v, q);
            (d, dot(&d, &d).sqrt())
        }));
        let mut sum = 0.0;
        for b in &self.blocks {
            let dc = sub(q, &b.center);
            let far = far_field && dot(&dc, &dc).sqrt() > b.radius * (1.0 + 1e-9) + 1e-12;
            let tris = if far { &b.fan } else { &b.tris };
            sum += tris.iter().map(|t| solid_angle(rel, t)).sum::<f64>();
        }
        sum / (4.0 * std::f64::consts::PI)
    }

    fn winding_number(&self, q: &P3, rel: &mut Vec<(P3, f64)>) -> f64 {
        self.winding_number_with(q, rel, true)
    }

    fn inside(&self, q: &P3, rel: &mut Vec<(P3, f64)>) -> bool {
        self.winding_number(q, rel).abs() > 0.5
    }
}

/// Solves the 3×3 system `a·x = b` by Cramer's rule; `None` if `a` is (nearly) singular.
fn solve3(a: &Mat3<f64>, b: &Vec3<f64>) -> Option<Vec3<f64>> {
    let det = a.determinant();
    let scale = a.amax().powi(3);
    if det.is_nan() || det.abs() <= 1e-14 * scale {
        return None;
    }
    let mut x = Vec3::zeros();
    for (k, xk) in x.0.iter_mut().enumerate() {
        let mut ak = *a;
        for (row, bi) in ak.0.iter_mut().zip(b.0) {
            row[k] = bi;
        }
        *xk = ak.determinant() / det;
    }
    Some(x)
}

/// The lift map of one uncertain pose and its inverse by Newton's method.
struct LiftInverse {
    surf: LiftSurface<f64>,
    inv_mean: Transform<f64>,
    /// Inverse of the linear part `Σ_vv^½` (lower block of B): the Newton start.
    lin_inv: Mat3<f64>,
}

impl LiftInverse {
    fn new(mean: &Transform<f64>, cov: &Mat6<f64>) -> Self {
        let surf = LiftSurface::new(mean, cov).expect("finite pose and covariance");
        let lin = Matrix([surf.basis.0[3], surf.basis.0[4], surf.basis.0[5]]);
        let mut lin_inv = Mat3::zeros();
        for k in 0..3 {
            let mut e = Vec3::zeros();
            e.0[k] = 1.0;
            let col = solve3(&lin, &e).expect("full-rank position covariance");
            for (row, x) in lin_inv.0.iter_mut().zip(col.0) {
                row[k] = x;
            }
        }
        Self {
            surf,
            inv_mean: mean.inverse(),
            lin_inv,
        }
    }

    /// `p(Exp(B·s))`: the surface map in the tool frame.
    fn g(&self, s: &Vec3<f64>) -> Vec3<f64> {
        se3::exp(&self.surf.perturbation(s)).translation
    }

    /// The lift coordinate s with `F(s) = y` (Newton with a forward-difference Jacobian
    /// and step halving), or `None` if the iteration does not converge to a residual
    /// below 10⁻⁹ in whitened units.
    fn coordinate(&self, y: &Vec3<f64>) -> Option<Vec3<f64>> {
        let z = self.inv_mean.transform_point(y);
        let mut s = self.lin_inv.mul_vec(&z);
        let mut gs = self.g(&s);
        let whitened = |r: &Vec3<f64>| self.lin_inv.mul_vec(r).norm();
        let mut res = whitened(&(z - gs));
        for _ in 0..40 {
            if res < 1e-9 {
                return Some(s);
            }
            let h = 1e-7 * (1.0 + s.norm());
            let mut jac = Mat3::zeros();
            for k in 0..3 {
                let mut e = s;
                e.0[k] += h;
                let col = (self.g(&e) - gs).scale(1.0 / h);
                for (row, x) in jac.0.iter_mut().zip(col.0) {
                    row[k] = x;
                }
            }
            let step = solve3(&jac, &(z - gs))?;
            let mut t = 1.0;
            loop {
                let s_new = s + step.scale(t);
                let g_new = self.g(&s_new);
                let res_new = whitened(&(z - g_new));
                if res_new < res || t < 1e-4 {
                    s = s_new;
                    gs = g_new;
                    res = res_new;
                    break;
                }
                t *= 0.5;
            }
        }
        (res < 1e-9).then_some(s)
    }
}

/// A chain from a golden file, and the file.
fn golden_chain(file: &str) -> (Vec<Joint<f64>>, Transform<f64>, serde_json::Value) {
    let g = golden(file);
    let (joints, home) = chain_from_golden(&g);
    (joints, home, g)
}

/// Tool positions of `N_SAMPLES` draws of the model `T = D₁Exp(ξ₁)…DₙExp(ξₙ)·M`.
fn sample_tool_positions(
    chain: &ChainView<f64>,
    thetas: &[f64],
    covs: &[Mat6<f64>],
    seed: u64,
) -> Vec<Vec3<f64>> {
    sample_chain_poses(chain, thetas, covs, seed, N_SAMPLES)
        .iter()
        .map(|t| t.translation)
        .collect()
}

/// The largest distance, in lift coordinates, of the mesh's edge midpoints and centroids
/// from the surface at `k`: the half-width of the shell where the mesh and the true
/// surface may disagree.
fn shell_half_width(name: &str, lift: &LiftInverse, mesh: &Mesh, k: f64) -> f64 {
    let mut e = 0.0_f64;
    for t in mesh.blocks.iter().flat_map(|b| &b.tris) {
        let [a, b, c] = t.map(|i| mesh.verts[i as usize]);
        let mid = |p: &P3, q: &P3, w: f64| -> Vec3<f64> {
            Vector(std::array::from_fn(|i| p[i] + w * (q[i] - p[i])))
        };
        let centroid: Vec3<f64> = Vector(std::array::from_fn(|i| (a[i] + b[i] + c[i]) / 3.0));
        for p in [
            mid(&a, &b, 0.5),
            mid(&b, &c, 0.5),
            mid(&a, &c, 0.5),
            centroid,
        ] {
            let s = lift
                .coordinate(&p)
                .unwrap_or_else(|| panic!("{name} k={k}: no lift coordinate for {p:?}"));
            e = e.max((s.norm() - k).abs());
        }
    }
    e
}

/// How many samples lie inside the mesh at `k`, and how many needed the winding number:
/// a sample's lift radius decides outside the shell `k ± delta` (checked against the
/// winding number for the first `N_CHECK` samples), the winding number inside it.
fn count_inside(
    name: &str,
    k: f64,
    delta: f64,
    ys: &[Vec3<f64>],
    radii: &[Option<f64>],
    mesh: &Mesh,
    scratch: &mut Vec<([f64; 3], f64)>,
) -> (usize, usize) {
    let mut inside = 0usize;
    let mut n_winding = 0usize;
    for (idx, (y, r)) in ys.iter().zip(radii).enumerate() {
        let fast = match r {
            Some(r) if *r <= k - delta => Some(true),
            Some(r) if *r >= k + delta => Some(false),
            _ => None,
        };
        let is_inside = match fast {
            Some(b) if idx >= N_CHECK => b,
            _ => {
                n_winding += 1;
                let w = mesh.inside(&y.0, scratch);
                if let Some(b) = fast {
                    assert_eq!(
                        b, w,
                        "{name} k={k}: sample {idx} (lift radius {r:?}) classified \
                         {b} by its lift coordinate, {w} by the winding number"
                    );
                }
                w
            }
        };
        inside += usize::from(is_inside);
    }
    (inside, n_winding)
}

/// Samples one case, checks the coverage at k = 1, 2, 3 and returns the fractions.
fn check_case(
    name: &str,
    chain: &ChainView<f64>,
    thetas: &[f64],
    covs: &[Mat6<f64>],
    seed: u64,
) -> [f64; 3] {
    let start = Instant::now();
    let up = chain.ppoe(thetas, covs, Convention::Right).unwrap();
    let lift = LiftInverse::new(&up.pose, &up.cov);
    let ys = sample_tool_positions(chain, thetas, covs, seed);
    let t_sample = start.elapsed();
    let radii: Vec<Option<f64>> = ys
        .iter()
        .map(|y| lift.coordinate(y).map(|s| s.norm()))
        .collect();
    let n_failed = radii.iter().filter(|r| r.is_none()).count();
    let t_newton = start.elapsed() - t_sample;

    let mut grid = vec![Vec3::zeros(); N_STEPS * N_STEPS];
    let mut scratch = Vec::new();
    let mut fractions = [0.0; 3];
    let mut failures = Vec::new();
    for (slot, k) in fractions.iter_mut().zip([1.0_f64, 2.0, 3.0]) {
        lift.surf.grid(k, N_STEPS, &mut grid).unwrap();
        let mesh = Mesh::from_grid(&grid, N_STEPS);
        let e = shell_half_width(name, &lift, &mesh, k);
        assert!(
            e < 0.01 * k,
            "{name} k={k}: mesh deviates {e} from the surface"
        );
        let delta = 4.0 * e + 1e-6 * k;

        let (inside, n_winding) = count_inside(name, k, delta, &ys, &radii, &mesh, &mut scratch);
        let frac = inside as f64 / N_SAMPLES as f64;
        let p = chi2_3_probability(k);
        println!(
            "{name:<28} k={k}: inside {frac:.4}, chi2_3 {p:.4}, diff {:+.4} \
             (mesh shell e = {e:.1e}, winding-number tests {n_winding})",
            frac - p
        );
        if (frac - p).abs() > TOL {
            failures.push(format!("k={k}: {frac:.4} vs {p:.4}"));
        }
        *slot = frac;
    }
    println!(
        "{name:<28} {N_SAMPLES} samples: sampling {:.2} s, lift coordinates {:.2} s \
         ({n_failed} not converged), total {:.2} s",
        t_sample.as_secs_f64(),
        t_newton.as_secs_f64(),
        start.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{name}: coverage off by more than {TOL}: {failures:?}"
    );
    fractions
}

#[test]
fn winding_number_on_unit_sphere_mesh() {
    let n = 40;
    let mut grid = vec![Vec3::zeros(); n * n];
    for i in 0..n {
        for j in 0..n {
            grid[i * n + j] = unit_sphere_point(n, i, j);
        }
    }
    let mesh = Mesh::from_grid(&grid, n);
    assert_eq!(mesh.n_tris(), 2 * 39 * 39 - 2 * 39);
    let mut scratch = Vec::new();
    // Inside: the centre, off-centre points, near both poles, next to the seam θ = 0.
    for q in [
        [0.0, 0.0, 0.0],
        [0.3, -0.4, 0.5],
        [0.0, 0.0, 0.99],
        [0.01, -0.02, -0.99],
        [0.95, 0.0, 0.1],
        [0.95, -1e-9, -0.1],
    ] {
        let w = mesh.winding_number(&q, &mut scratch);
        assert!((w - 1.0).abs() < 1e-9, "{q:?}: {w}");
        assert!(mesh.inside(&q, &mut scratch));
    }
    // Outside: beyond the sphere (the mesh lies inside it), across the seam, far away.
    for q in [
        [1.01, 0.0, 0.0],
        [1.2, 0.0, 0.0],
        [0.0, 0.0, 1.01],
        [0.0, 0.0, -1.5],
        [0.6, 0.6, 0.6],
        [50.0, -20.0, 3.0],
    ] {
        let w = mesh.winding_number(&q, &mut scratch);
        assert!(w.abs() < 1e-9, "{q:?}: {w}");
        assert!(!mesh.inside(&q, &mut scratch));
    }
    // Reversed orientation: −1 inside, still "inside" by |w| > ½.
    let flip = |ts: &Vec<[u32; 3]>| ts.iter().map(|t| [t[0], t[2], t[1]]).collect();
    let reversed = Mesh {
        verts: mesh.verts.clone(),
        blocks: mesh
            .blocks
            .iter()
            .map(|b| Block {
                center: b.center,
                radius: b.radius,
                tris: flip(&b.tris),
                fan: flip(&b.fan),
            })
            .collect(),
    };
    let w = reversed.winding_number(&[0.1, 0.2, 0.3], &mut scratch);
    assert!((w + 1.0).abs() < 1e-9, "{w}");
    assert!(reversed.inside(&[0.1, 0.2, 0.3], &mut scratch));
    // The far-field shortcut agrees with the plain sum, also close to the surface.
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..300 {
        let u: P3 = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let r = rng.gen_range(0.0..1.6) / dot(&u, &u).sqrt().max(1e-3);
        let q = u.map(|x| x * r);
        let fast = mesh.winding_number(&q, &mut scratch);
        let plain = mesh.winding_number_with(&q, &mut scratch, false);
        assert!((fast - plain).abs() < 1e-9, "{q:?}: {fast} vs {plain}");
        assert!(
            fast.abs() < 1e-6 || (fast - 1.0).abs() < 1e-6,
            "{q:?}: {fast}"
        );
    }
    // An anisotropic, shifted ellipsoid (the shape of a covariance surface).
    let ell: Vec<Vec3<f64>> = grid
        .iter()
        .map(|u| Vec3::new(0.5 + 0.3 * u.0[0], -1.0 + 0.02 * u.0[1], 2.0 + 0.1 * u.0[2]))
        .collect();
    let ell = Mesh::from_grid(&ell, n);
    assert!(ell.inside(&[0.5, -1.0, 2.0], &mut scratch));
    assert!(ell.inside(&[0.75, -1.0, 2.0], &mut scratch));
    assert!(ell.inside(&[0.5, -1.015, 2.0], &mut scratch));
    assert!(!ell.inside(&[0.5, -0.975, 2.0], &mut scratch));
    assert!(!ell.inside(&[0.5, -1.0, 2.11], &mut scratch));
    assert!(!ell.inside(&[0.0, 0.0, 0.0], &mut scratch));
}

#[test]
fn lift_coordinate_inverts_the_surface_map() {
    let (joints, home, _) = golden_chain("ppoe/seed_linkmount_tcp.json");
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let up = chain
        .ppoe(&seed_frame(0), &seed_covs(1.0), Convention::Right)
        .unwrap();
    let lift = LiftInverse::new(&up.pose, &up.cov);
    for s in [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.5, -0.2, 0.1),
        Vec3::new(-2.0, 1.0, 1.5),
        Vec3::new(0.0, 0.0, -3.0),
    ] {
        let back = lift.coordinate(&lift.surf.point(&s)).unwrap();
        assert!((back - s).norm() < 1e-7, "{s:?} -> {back:?}");
    }
}

#[test]
fn lift_surface_coverage_seed_robot_frame_0() {
    let (joints, home, _) = golden_chain("ppoe/seed_linkmount_tcp.json");
    let chain = ChainView {
        joints: &joints,
        home,
    };
    check_case("seed, frame 0", &chain, &seed_frame(0), &seed_covs(1.0), 40);
}

#[test]
fn lift_surface_coverage_seed_robot_frame_100() {
    let (joints, home, _) = golden_chain("ppoe/seed_linkmount_tcp.json");
    let chain = ChainView {
        joints: &joints,
        home,
    };
    check_case(
        "seed, frame 100",
        &chain,
        &seed_frame(100),
        &seed_covs(1.0),
        41,
    );
}

/// Another robot: `rpy_everywhere` (7 revolute joints, rotated frames everywhere), with
/// joint-angle noise σ = 0.05 rad on every joint (`screw_noise`), at two joint
/// configurations taken from the golden file's random `inside` cases.
#[test]
fn lift_surface_coverage_rpy_everywhere() {
    let (joints, home, g) = golden_chain("ppoe/rpy_everywhere_base_tool.json");
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let sigma = 0.05_f64;
    let covs: Vec<Mat6<f64>> = joints
        .iter()
        .map(|j| screw_noise(&j.screw, sigma * sigma))
        .collect();
    for (label, seed) in [
        ("random_000_inside_zero", 42),
        ("random_012_inside_diag", 43),
    ] {
        let case = g["cases"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["label"] == label)
            .unwrap();
        let thetas = vecf(&case["thetas"]);
        check_case(
            &format!("rpy_everywhere, {}", &label[..10]),
            &chain,
            &thetas,
            &covs,
            seed,
        );
    }
}
