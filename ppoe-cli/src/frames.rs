//! `render` and `mesh`: one frame per case of the input, each computed, written and dropped
//! in turn (so memory does not grow with the number of cases), after the inputs were read
//! once and the output files checked. A GIF or an HTML view of all cases makes each frame
//! twice: once to fit the shared view, once to stream it out (see [`picture::Survey`]).

use crate::args::{ChainArgs, NoiseArgs, SurfaceArgs};
use crate::draw::{self, level};
use crate::exaggerate::{self, Exaggeration};
use crate::names::shown;
use crate::picture::{self, Frame};
use crate::{cases, eval, load, noise, output};
use anyhow::bail;
use ppoe::chain::ChainView;
use ppoe::Mat6;
use std::path::Path;

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
    /// One animation of every frame at `dir/name`, streamed (see [`picture::Survey`]).
    Gif {
        /// The output directory.
        dir: &'a Path,
        /// The file name.
        name: &'a str,
    },
    /// One interactive HTML view of every frame at `dir/name`, streamed.
    Html {
        /// The output directory.
        dir: &'a Path,
        /// The file name.
        name: &'a str,
    },
}

/// Reads the URDF, the noise model and the cases once and checks them and the outputs, all
/// before any computation; with a calibrated noise model the robot's chain is the
/// calibrated one, and the link folds ([`noise::Applied::folds`]) are returned.
fn prepare(
    chain_args: &ChainArgs,
    input: Option<&Path>,
    noise: &NoiseArgs,
    sink: &Sink<'_>,
) -> anyhow::Result<(load::Robot, cases::Input, Vec<picture::geom::Mat4>)> {
    load::check_one_stdin(&[
        load::urdf_input(&chain_args.urdf),
        load::cases_input(input),
        load::noise_input(noise.noise.as_deref()),
    ])?;
    let mut robot = load::robot(chain_args)?;
    let (covs, folds) = match noise::from_args(noise, &mut robot.chain)? {
        Some(applied) => (Some(applied.covs), applied.folds),
        None => (None, Vec::new()),
    };
    let mut cases = cases::load(input, covs)?;
    if cases.cases.is_empty() {
        bail!("the input has no cases");
    }
    cases::expand_mimic(&robot.chain, &mut cases)?;
    cases::check_counts(&robot.chain, &cases)?;
    let n = cases.cases.len();
    match sink {
        Sink::Each { dir, name, .. } => {
            output::check_targets(dir, &(0..n).map(name).collect::<Vec<_>>())?
        }
        Sink::Gif { dir, name } | Sink::Html { dir, name } => {
            output::check_targets(dir, &[name.to_string()])?
        }
    }
    Ok((robot, cases, folds))
}

/// Reads the URDF and the cases once, checks the outputs, then computes and writes each
/// case's frame; prints `wrote <path>` for each file.
///
/// # Errors
/// Input errors (naming the file, case and joint), unwritable outputs (before any
/// computation), and failures of a case (naming it).
/// `default` is the command's exaggeration of the surface when `--exaggerate` is not
/// given (automatic for pictures, none for meshes).
pub fn run(
    chain_args: &ChainArgs,
    input: Option<&Path>,
    noise: &NoiseArgs,
    surface: &SurfaceArgs,
    sink: &Sink<'_>,
    default: Exaggeration,
) -> anyhow::Result<()> {
    let exaggeration = surface.exaggerate.unwrap_or(default);
    let (k, label) = level(surface)?;
    let grid = surface.grid as usize;
    let (robot, cases, folds) = prepare(chain_args, input, noise, sink)?;
    let home_frames = robot.chain.home_frames();
    let mut visuals = draw::robot_visuals(&robot, &chain_args.urdf, surface)?;
    visuals.fold(&folds);
    let (joints, home) = eval::core_joints::<f64>(&robot.chain);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let (base, tip) = (shown(&robot.chain.base), shown(&robot.chain.tip));
    let n = cases.cases.len();
    let make = |i: usize| -> anyhow::Result<Frame> {
        let case = &cases.cases[i];
        let covs: Vec<Mat6<f64>> = case.covs.iter().map(|c| Mat6::from(*c)).collect();
        let title = format!("{base} → {tip}: case {}/{n}", i + 1);
        let s = draw::state(
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
        );
        // The PPOE checks the inputs; a bad covariance is named as `eval` names it.
        match s {
            Ok(s) => Ok(s.frame),
            Err(e) => Err(eval::named_covariance_error(&chain, i, &covs)
                .unwrap_or_else(|| e.context(format!("case {i}")))),
        }
    };
    write_frames(sink, n, &make, exaggeration)
}

/// Writes the `n` frames `make` computes into `sink`, the surface exaggerated as `e` says:
/// per picture for one file per case, with the first frame's factor for an animation.
fn write_frames(
    sink: &Sink<'_>,
    n: usize,
    make: &(dyn Fn(usize) -> anyhow::Result<Frame> + Sync),
    e: Exaggeration,
) -> anyhow::Result<()> {
    let (p, gif) = match sink {
        Sink::Each { dir, name, write } => {
            let mut noted = false;
            for i in 0..n {
                let p = dir.join(name(i));
                let mut frame = make(i)?;
                let k = exaggerate::factor(e, &frame);
                note_auto(e, k, &mut noted);
                exaggerate::apply(&mut frame, k);
                write(&p, &frame)?;
                output::print(format!("wrote {}\n", p.display()).as_bytes())?;
            }
            return Ok(());
        }
        Sink::Gif { dir, name } => (dir.join(name), true),
        Sink::Html { dir, name } => (dir.join(name), false),
    };
    // One factor for the whole animation, so the surface does not jump and the one
    // label of the page or GIF is true of every frame.
    let k = match e {
        Exaggeration::Auto => exaggerate::auto_factor(&make(0)?),
        Exaggeration::Factor(k) => k,
    };
    note_auto(e, k, &mut false);
    let scaled = |i: usize| -> anyhow::Result<Frame> {
        let mut frame = make(i)?;
        exaggerate::apply(&mut frame, k);
        Ok(frame)
    };
    let frames = picture::Frames { n, make: &scaled };
    let survey = picture::Survey::of(&frames)?;
    if gif {
        draw::write_gif(&p, &frames, &survey)?;
    } else {
        picture::write_html(&p, &frames, &survey)?;
    }
    output::print(format!("wrote {}\n", p.display()).as_bytes())?;
    Ok(())
}

/// Says once on stderr that an automatic factor enlarged the surface (the legend says
/// by how much in each picture).
pub fn note_auto(e: Exaggeration, k: f64, noted: &mut bool) {
    if e == Exaggeration::Auto && k != 1.0 && !*noted {
        *noted = true;
        eprintln!(
            "note: the surface is too small to see at the picture's scale: drawn ×{} about \
             the tool, as the legend says (--exaggerate 1: true scale)",
            exaggerate::shown(k)
        );
    }
}
