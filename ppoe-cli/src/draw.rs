//! What `demo`, `render` and `mesh` draw: for each state of the arm, the PPOE, the joint
//! frames along the chain, the equiprobable surface of the tool position and the
//! second-order mean, as a [`picture::Frame`].

use crate::args::{Precision, SurfaceArg, SurfaceArgs};
use crate::exaggerate::{self, Exaggeration};
use crate::output::println;
use crate::picture::{self, Frame};
use crate::seed;
use crate::visuals::Visuals;
use anyhow::{bail, Context};
use ppoe::chain::{ChainView, Convention};
use ppoe::surface::{self, Surface};
use ppoe::{Mat6, Transform, Vec3};
use std::io::{IsTerminal, Write};

/// A row-major 4×4 homogeneous transform.
type Mat4 = [[f64; 4]; 4];
use std::path::Path;
use std::time::Instant;

/// The surface radius k (Mahalanobis, 3D) and a label for it.
pub fn level(args: &SurfaceArgs) -> anyhow::Result<(f64, String)> {
    let (k, p) = match (args.level.sigma, args.level.probability) {
        (_, Some(p)) => {
            if !(p > 0.0 && p < 1.0) {
                bail!("--probability {p}: expected a probability strictly between 0 and 1");
            }
            let k = surface::chi2_3_radius(p)
                .with_context(|| format!("--probability {p}: no radius"))?;
            (k, p)
        }
        (k, None) => {
            let k = k.unwrap_or(1.0);
            if !(k.is_finite() && k > 0.0) {
                bail!("--sigma {k}: expected a positive number of standard deviations");
            }
            (k, surface::chi2_3_probability(k))
        }
    };
    let what = match args.surface {
        SurfaceArg::Lift => "lift surface",
        SurfaceArg::Marginal => "linear marginal ellipsoid",
        SurfaceArg::Pytransform3d => "pytransform3d projected ellipsoid",
    };
    let label = if args.surface == SurfaceArg::Pytransform3d {
        format!("{what}, factor {k:.3} (not equiprobable)")
    } else {
        format!("{what}, k = {k:.3} σ ({:.1} % of a 3D Gaussian)", 100.0 * p)
    };
    Ok((k, label))
}

/// Everything computed for one state of the arm.
pub struct State {
    /// The picture's content.
    pub frame: Frame,
    /// The mean pose.
    pub pose: Transform<f64>,
    /// The covariance of the right perturbation.
    pub cov_right: Mat6<f64>,
    /// The pytransform3d-compatible covariance.
    pub cov_compat: Mat6<f64>,
}

/// The PPOE and the picture content for one state.
#[allow(clippy::too_many_arguments)]
pub fn state(
    title: String,
    chain: &ChainView<'_, f64>,
    home_frames: &[Mat4],
    thetas: &[f64],
    covs: &[Mat6<f64>],
    surface: SurfaceArg,
    k: f64,
    grid: usize,
    label: &str,
    visuals: &Visuals,
) -> anyhow::Result<State> {
    let right = chain
        .ppoe_checked(thetas, covs, Convention::Right)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let compat = chain
        .ppoe_checked(thetas, covs, Convention::Pytransform3d)
        .map_err(|e| anyhow::anyhow!("{e}"))?;

    // Joint frames along the chain: T_base←child_i(θ) = D₁…Dᵢ·L_i.
    let mut frames_out = vec![Transform::<f64>::identity().to_matrix4()];
    let mut points = vec![[0.0, 0.0, 0.0]];
    let mut p = Transform::identity();
    // prefix[k] = Exp(S₁θ₁)·…·Exp(S_kθ_k): places the links below joint k.
    let mut prefix = vec![picture::geom::IDENTITY];
    for ((j, theta), l) in chain.joints.iter().zip(thetas).zip(home_frames) {
        p = p * j.displacement(j.clip(*theta, false));
        prefix.push(p.to_matrix4());
        let f = (p * Transform::from_matrix4(l)).to_matrix4();
        points.push([f[0][3], f[1][3], f[2][3]]);
        frames_out.push(f);
    }
    let tool = right.pose.to_matrix4();
    points.push(right.pose.translation.0);
    frames_out.push(tool);

    let mut grid_pts = vec![Vec3::zeros(); grid * grid];
    let (s, mean, cov) = match surface {
        SurfaceArg::Lift => (Surface::Lift, right.pose, right.cov),
        SurfaceArg::Marginal => (Surface::Marginal, right.pose, right.cov),
        SurfaceArg::Pytransform3d => (Surface::Pytransform3d, compat.pose, compat.cov),
    };
    surface::surface_grid(s, &mean, &cov, k, grid, &mut grid_pts)
        .map_err(|e| anyhow::anyhow!("the surface: {e}"))?;
    let surface_rows = grid_pts
        .chunks(grid)
        .map(|row| row.iter().map(|v| v.0).collect())
        .collect();
    let mean2 = surface::position_mean_second_order(&right.pose, &right.cov).0;
    Ok(State {
        frame: Frame {
            title,
            joints: points,
            frames: frames_out,
            tool,
            surface: surface_rows,
            mean2,
            sigma_label: label.to_string(),
            bodies: visuals.place(&prefix),
        },
        pose: right.pose,
        cov_right: right.cov,
        cov_compat: compat.cov,
    })
}

/// Creates the output directory if needed.
pub fn ensure_dir(dir: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("cannot create the output directory {}", dir.display()))
}

/// The URDF visuals of `robot` (from the URDF already parsed), meshes looked up beside
/// `urdf_path` when the URDF is a regular file and in `surface.package_dirs`, at most
/// `surface.mesh_triangles` triangles per mesh; what is skipped or reduced is noted on
/// stderr (the picture is drawn without it).
///
/// # Errors
/// A `<visual>` element is malformed, or a `--package-dir` is not a directory.
pub fn robot_visuals(
    robot: &crate::load::Robot,
    urdf_path: &Path,
    surface: &SurfaceArgs,
) -> anyhow::Result<Visuals> {
    let name = &robot.source.name;
    for (package, path) in &surface.package_dirs {
        if !path.is_dir() {
            anyhow::bail!(
                "--package-dir {package}={}: not a directory",
                path.display()
            );
        }
    }
    let search = crate::visuals::MeshSearch {
        dir: if robot.source.regular {
            urdf_path.parent().map(Path::to_path_buf)
        } else {
            None
        },
        packages: surface.package_dirs.clone(),
        limits: crate::meshfile::Limits {
            max_triangles: surface.mesh_triangles,
            ..Default::default()
        },
    };
    let (visuals, notices) = Visuals::from_urdf_with(
        &robot.urdf,
        &robot.chain.base,
        &robot.chain.joint_names(),
        &search,
    )
    .with_context(|| name.clone())?;
    for n in notices {
        eprintln!("note: {n}");
    }
    Ok(visuals)
}

fn print_matrix<const C: usize>(title: &str, m: &[[f64; C]], precision: Precision) {
    println!("{title}");
    for row in m {
        let cells: Vec<String> = row.iter().map(|x| precision.format(*x)).collect();
        println!("  [{}]", cells.join(","));
    }
}

/// Progress on stderr: a bar redrawn in place on a terminal, otherwise a line at every
/// quarter (so logs show that a long render is alive without flooding them).
struct Progress {
    tty: bool,
    total: usize,
    what: String,
}

impl Progress {
    fn new(what: String, total: usize) -> Self {
        let tty = std::io::stderr().is_terminal();
        Self { tty, total, what }
    }

    fn set(&self, done: usize) {
        let mut e = std::io::stderr().lock();
        if !self.tty {
            let quarter = self.total.div_ceil(4).max(1);
            if done > 0 && (done.is_multiple_of(quarter) || done == self.total) {
                let _ = writeln!(e, "{}: {done}/{}", self.what, self.total);
            }
            return;
        }
        let width = 30;
        let filled = (width * done)
            .checked_div(self.total)
            .unwrap_or(width)
            .min(width);
        let _ = write!(
            e,
            "\r{} [{}{}] {done}/{}",
            self.what,
            "#".repeat(filled),
            "-".repeat(width - filled),
            self.total
        );
        let _ = e.flush();
    }

    fn finish(&self) {
        if self.tty {
            eprintln!();
        }
    }
}

/// Writes an animated GIF with progress on stderr (see [`picture::write_gif_with_progress`]).
///
/// # Errors
/// As [`picture::write_gif_with_progress`].
pub fn write_gif(
    path: &Path,
    frames: &picture::Frames<'_>,
    survey: &picture::Survey,
) -> anyhow::Result<()> {
    let name = path
        .file_name()
        .unwrap_or(path.as_os_str())
        .to_string_lossy();
    let progress = Progress::new(format!("rendering {name}"), frames.n);
    progress.set(0);
    picture::write_gif_with_progress(path, frames, survey, &mut |i| progress.set(i + 1))?;
    progress.finish();
    Ok(())
}

/// The demo's report of the seed robot and its initial state on stdout.
fn print_initial(initial: &State, precision: Precision) {
    println!(
        "seed robot: '{}' → '{}', joints {} (table generated at build time from seed.urdf)",
        seed::SEED.base,
        seed::SEED.tip,
        seed::SEED
            .joints
            .iter()
            .map(|j| j.name)
            .collect::<Vec<_>>()
            .join(", ")
    );
    println!("initial joint values: {:?}", seed::initial_thetas());
    print_matrix(
        "initial pose (tcp in linkmount):",
        &initial.pose.to_matrix4(),
        precision,
    );
    print_matrix(
        "initial covariance, right perturbation T = T̄·Exp(η) (rotation first):",
        &initial.cov_right.0,
        precision,
    );
    print_matrix(
        "initial covariance, pytransform3d-compatible (Ad(M), for comparison):",
        &initial.cov_compat.0,
        precision,
    );
    let m2 = initial.frame.mean2;
    println!(
        "second-order mean of the tool position: [{:.6}, {:.6}, {:.6}] (t̄ = [{:.6}, {:.6}, {:.6}])",
        m2[0],
        m2[1],
        m2[2],
        initial.pose.translation.0[0],
        initial.pose.translation.0[1],
        initial.pose.translation.0[2]
    );
}

/// `ppoe demo`: the seed example from the build-time table with the covariances (and
/// the calibration, folded in at run time) of `seed` ([`crate::noise::seed`]); the pose
/// and covariances printed with `precision`.
pub fn demo(
    out: &Path,
    surface: &SurfaceArgs,
    n_frames: usize,
    seed: crate::noise::Seed,
    precision: Precision,
) -> anyhow::Result<()> {
    let start = Instant::now();
    let (k, label) = level(surface)?;
    let (chain, covs) = (seed.chain.as_ref(), seed.covs);
    let grid = surface.grid as usize;
    let mut visuals = seed::visuals()?;
    visuals.fold(&seed.folds);

    let exaggeration = surface.exaggerate.unwrap_or(Exaggeration::Auto);
    let mut initial = state(
        format!("ppoe seed: frame 0/{n_frames}"),
        &chain,
        &seed.home_frames,
        &seed::initial_thetas(),
        &covs,
        surface.surface,
        k,
        grid,
        &label,
        &visuals,
    )?;
    // The initial frame's factor for every picture of the demo (see `frames::run`).
    let factor = exaggerate::factor(exaggeration, &initial.frame);
    crate::frames::note_auto(exaggeration, factor, &mut false);
    exaggerate::apply(&mut initial.frame, factor);
    print_initial(&initial, precision);
    println!("surface: {}", initial.frame.sigma_label);

    ensure_dir(out)?;
    let png = out.join("ppoe-seed.png");
    picture::write_png(&png, &initial.frame)?;

    let make = |step: usize| {
        let s = state(
            format!("ppoe seed: frame {step}/{n_frames}"),
            &chain,
            &seed.home_frames,
            &seed::thetas_at(step, n_frames),
            &covs,
            surface.surface,
            k,
            grid,
            &label,
            &visuals,
        );
        let mut frame = s.with_context(|| format!("frame {step}"))?.frame;
        exaggerate::apply(&mut frame, factor);
        Ok(frame)
    };
    println!("wrote {} (initial state)", png.display());
    write_demo_animation(out, n_frames, &make)?;
    println!("done in {:.1} s", start.elapsed().as_secs_f64());
    Ok(())
}

/// The demo's page and GIF of the `n_frames` frames `make` computes, in `out`.
fn write_demo_animation(
    out: &Path,
    n_frames: usize,
    make: &(dyn Fn(usize) -> anyhow::Result<Frame> + Sync),
) -> anyhow::Result<()> {
    let frames = picture::Frames { n: n_frames, make };
    let survey = picture::Survey::of(&frames)?;
    let html = out.join("ppoe-seed.html");
    picture::write_html(&html, &frames, &survey)?;
    let gif = out.join("ppoe-seed.gif");
    write_gif(&gif, &frames, &survey)?;
    println!("wrote {} ({n_frames} frames)", gif.display());
    println!(
        "wrote {} (interactive view, {n_frames} frames)",
        html.display()
    );
    Ok(())
}
