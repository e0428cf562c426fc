//! `ppoe demo`: the seed example, from the table generated at build time.

use crate::args::{precision, Precision, SurfaceArgs};
use crate::{draw, noise, output};
use clap::Args;
use std::path::PathBuf;

/// The arguments of `ppoe demo`.
#[derive(Args, Debug)]
pub struct DemoArgs {
    /// The directory to write ppoe-seed.png, ppoe-seed.gif and ppoe-seed.html into.
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    #[command(flatten)]
    surface: SurfaceArgs,
    /// Use the joint covariances of a noise model written by `ppoe fit` for the seed
    /// robot instead of the example's; if the fit estimated a calibration, the seed's
    /// chain is calibrated with it (at run time) too.
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
    /// Use a noise model whose fit was rejected by its goodness-of-fit test
    /// (goodness_of_fit.fits false) anyway; without it, such a model is an error.
    #[arg(long, requires = "noise")]
    allow_rejected_noise: bool,
    /// Use a datasheet's noise instead: six σ, one per joint of the seed robot, base to
    /// tip, comma-separated (radians; σ, not σ²): joint i's covariance is σᵢ²·SᵢSᵢᵀ.
    /// Not with --noise.
    #[arg(
        long,
        value_name = "S1,...,S6",
        value_delimiter = ',',
        allow_negative_numbers = true,
        conflicts_with = "noise"
    )]
    joint_sigma: Option<Vec<f64>>,
    /// The number of animation frames, 1 to 10000 (angle = 0.5·cos(2π(0.5 + step/N))).
    /// The frames are streamed to the files (memory does not grow with N); each is
    /// computed three times (to fit the view, for the page, for the GIF).
    #[arg(long, value_name = "N", default_value_t = 200,
          value_parser = clap::value_parser!(u32).range(1..=10000))]
    frames: u32,
    /// Significant digits of the printed pose and covariances: a number from 1 to 17, or
    /// `full` (17: every value reads back exactly).
    #[arg(long, value_name = "DIGITS|full", default_value = "6", value_parser = precision,
          allow_negative_numbers = true)]
    precision: Precision,
}

/// `ppoe demo`: outputs checked before any computation.
pub fn run(a: &DemoArgs) -> anyhow::Result<()> {
    let names = ["ppoe-seed.png", "ppoe-seed.gif", "ppoe-seed.html"].map(String::from);
    output::check_targets(&a.out, &names)?;
    let seed = match (&a.noise, &a.joint_sigma) {
        (Some(p), _) => noise::seed(p, a.allow_rejected_noise)?,
        (None, Some(sigmas)) => noise::seed_sigmas(sigmas)?,
        (None, None) => noise::Seed::example(),
    };
    draw::demo(&a.out, &a.surface, a.frames as usize, seed, a.precision)
}
