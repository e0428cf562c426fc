//! `render` and `mesh`: one frame per case of the input, each computed, written and dropped
//! in turn (so memory does not grow with the number of cases), after the inputs were read
//! once and the output files checked.

use crate::draw::{self, level};
use crate::names::shown;
use crate::picture::Frame;
use crate::{eval, load, output, ChainArgs, SurfaceArgs};
use anyhow::{bail, Context};
use ppoe::chain::{ChainView, Convention};
use ppoe::Mat6;
use std::path::Path;

/// A GIF holds all its frames in memory before the first is encoded (one view is fitted
/// to all of them); beyond this many bytes of frames the command refuses up front.
pub const GIF_MEMORY_LIMIT: usize = 1 << 30;

/// The approximate memory of one frame: the surface grid and the skeleton's points and
/// frames.
pub fn frame_bytes(grid: usize, joints: usize) -> usize {
    let point = std::mem::size_of::<[f64; 3]>();
    let mat = std::mem::size_of::<[[f64; 4]; 4]>();
    grid * grid * point + grid * std::mem::size_of::<Vec<[f64; 3]>>() + (joints + 2) * (point + mat)
}

/// Refuses, before any computation, an animation whose frames would not fit in
/// [`GIF_MEMORY_LIMIT`].
///
/// # Errors
/// The estimate and what to change.
pub fn check_gif_memory(n_frames: usize, grid: usize, joints: usize) -> anyhow::Result<()> {
    let total = n_frames.saturating_mul(frame_bytes(grid, joints));
    if total > GIF_MEMORY_LIMIT {
        bail!(
            "a GIF of {n_frames} frames at --grid {grid} holds about {} MB of frames in \
             memory (the limit is {} MB): use fewer frames or cases, a smaller --grid, or \
             png/svg pictures (written one at a time)",
            total / 1_000_000,
            GIF_MEMORY_LIMIT / 1_000_000
        );
    }
    Ok(())
}

/// What to do with each frame.
pub enum Sink<'a> {
    /// Write frame `i` to `dir/name(i)` with `write`, atomically.
    Each {
        /// The output directory.
        dir: &'a Path,
        /// The file name of frame `i`.
        name: &'a dyn Fn(usize) -> String,
        /// The writer; it writes atomically (see [`output`]).
        write: &'a dyn Fn(&Path, &Frame) -> anyhow::Result<()>,
    },
    /// Collect every frame into one animation at `dir/name`.
    Gif {
        /// The output directory.
        dir: &'a Path,
        /// The file name.
        name: &'a str,
    },
    /// Collect every frame into one interactive HTML view at `dir/name`.
    Html {
        /// The output directory.
        dir: &'a Path,
        /// The file name.
        name: &'a str,
    },
}

/// Reads the URDF and the cases once and checks them and the outputs, all before any
/// computation.
fn prepare(
    chain_args: &ChainArgs,
    input: Option<&Path>,
    noise: Option<&Path>,
    grid: usize,
    sink: &Sink<'_>,
) -> anyhow::Result<(load::Robot, eval::Input)> {
    load::check_one_stdin(&chain_args.urdf, input)?;
    let robot = load::robot(chain_args)?;
    let cases = crate::fit::cases(input, noise, &robot.chain)?;
    if cases.cases.is_empty() {
        bail!("the input has no cases");
    }
    eval::check_counts(&robot.chain, &cases)?;
    let n = cases.cases.len();
    match sink {
        Sink::Each { dir, name, .. } => {
            output::check_targets(dir, &(0..n).map(name).collect::<Vec<_>>())?
        }
        Sink::Gif { dir, name } | Sink::Html { dir, name } => {
            check_gif_memory(n, grid, robot.chain.joints.len())?;
            output::check_targets(dir, &[name.to_string()])?
        }
    }
    Ok((robot, cases))
}

/// Reads the URDF and the cases once, checks the outputs, then computes and writes each
/// case's frame; prints `wrote <path>` for each file.
///
/// # Errors
/// Input errors (naming the file, case and joint), unwritable outputs (before any
/// computation), and failures of a case (naming it).
pub fn run(
    chain_args: &ChainArgs,
    input: Option<&Path>,
    noise: Option<&Path>,
    surface: &SurfaceArgs,
    sink: &Sink<'_>,
) -> anyhow::Result<()> {
    let (k, label) = level(surface)?;
    let grid = surface.grid as usize;
    let (robot, cases) = prepare(chain_args, input, noise, grid, sink)?;
    let home_frames = robot.chain.home_frames();
    let visuals = draw::robot_visuals(&robot, &chain_args.urdf)?;
    let (joints, home) = eval::core_joints::<f64>(&robot.chain);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let (base, tip) = (shown(&robot.chain.base), shown(&robot.chain.tip));
    let n = cases.cases.len();
    let mut gif_frames = Vec::new();
    for (i, case) in cases.cases.iter().enumerate() {
        // Same checks and messages as `eval`.
        eval::eval_case(&chain, i, case, Convention::Right)?;
        let covs: Vec<Mat6<f64>> = case.covs.iter().map(|c| Mat6::from(*c)).collect();
        let title = format!("{base} → {tip}: case {}/{n}", i + 1);
        let frame = draw::state(
            title,
            &chain,
            &home_frames,
            &case.thetas,
            &covs,
            surface.surface,
            k,
            grid,
            &label,
            &visuals,
        )
        .with_context(|| format!("case {i}"))?
        .frame;
        match sink {
            Sink::Each { dir, name, write } => {
                let p = dir.join(name(i));
                write(&p, &frame)?;
                output::print(format!("wrote {}\n", p.display()).as_bytes())?;
            }
            Sink::Gif { .. } | Sink::Html { .. } => gif_frames.push(frame),
        }
    }
    let (p, gif) = match sink {
        Sink::Gif { dir, name } => (dir.join(name), true),
        Sink::Html { dir, name } => (dir.join(name), false),
        Sink::Each { .. } => return Ok(()),
    };
    if gif {
        draw::write_gif(&p, &gif_frames)?;
    } else {
        crate::picture::write_html(&p, &gif_frames)?;
    }
    output::print(format!("wrote {}\n", p.display()).as_bytes())?;
    Ok(())
}
