//! `ppoe fit`: per-joint noise covariances fitted to joint values recorded with tool poses
//! measured by an external tracker.

use crate::args::ChainArgs;
use crate::{fit, input, load, output};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};

/// Which per-joint noise `fit` estimates.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum FitModel {
    /// One variance per joint along its screw axis (encoder noise, backlash).
    Joint,
    /// Any 6×6 PSD covariance per joint (flexible links).
    Full,
}

/// The arguments of `ppoe fit`.
#[derive(Args, Debug)]
pub struct FitArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The input JSON file (default or `-`: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// The noise model to fit.
    #[arg(long, value_enum)]
    model: FitModel,
    /// Write the result to FILE instead of standard output (atomically; a device or a FIFO
    /// such as /dev/stdout is written through).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
}

/// `ppoe fit`: the noise model fitted to the samples, on standard output or `--out`.
pub fn run(a: &FitArgs) -> anyhow::Result<()> {
    load::check_one_stdin(&[
        load::urdf_input(&a.chain.urdf),
        load::cases_input(a.input.as_deref()),
    ])?;
    if let Some(out) = &a.out {
        if out.file_name().is_none() {
            anyhow::bail!("--out {} has no file name", out.display());
        }
        output::check_file(out)?;
    }
    let robot = load::robot(&a.chain)?;
    let input = load::read(a.input.as_deref().unwrap_or(Path::new("-")), "input file")?;
    let text = input::text(&input.bytes)
        .map_err(|_| anyhow::anyhow!("{}: the input is not UTF-8", input.name))?;
    let model = match a.model {
        FitModel::Joint => ppoe_fit::Model::Joint,
        FitModel::Full => ppoe_fit::Model::Full,
    };
    let result = fit::run(&robot.chain, text, model)
        .map_err(|e| anyhow::anyhow!("{}: {e:#}", input.name))?;
    let mut text = serde_json::to_string_pretty(&result)?;
    text.push('\n');
    match &a.out {
        Some(p) => output::write_atomic(p, |w| w.write_all(text.as_bytes())),
        None => output::print(text.as_bytes()),
    }
}
