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
    /// Calibrate together with the noise: a comma-separated list of `base` (the robot base
    /// in the tracker's frame), `tip` (the marker in the tip frame), `offsets` (joint zero
    /// offsets), `kinematics` (each joint's axis and the home pose), or `all`. Without it
    /// the samples must be in the robot's base frame with the marker at the tip frame, and
    /// the fit only tests for systematic errors.
    #[arg(long, value_name = "LIST", value_parser = parse_estimate)]
    estimate: Option<ppoe_fit::Estimate>,
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
    let estimate = a.estimate.unwrap_or(ppoe_fit::Estimate::NONE);
    let result = fit::run(&robot.chain, text, model, estimate)
        .map_err(|e| anyhow::anyhow!("{}: {e:#}", input.name))?;
    let mut text = crate::pretty::to_string(&result)?;
    text.push('\n');
    match &a.out {
        Some(p) => output::write_atomic(p, |w| w.write_all(text.as_bytes()))?,
        None => output::print(text.as_bytes())?,
    }
    match verdict(&result) {
        Some(why) => Err(crate::report::Rejected(why).into()),
        None => Ok(()),
    }
}

/// Why a written fit is not to be used, if it is not: its goodness-of-fit test rejects the
/// noise model (the output's `goodness_of_fit.fits`), the test `ppoe table --noise` also
/// applies. A fit that did not converge is only a warning (in the output and on stderr):
/// its estimates can still be good.
fn verdict(result: &serde_json::Value) -> Option<String> {
    if result["goodness_of_fit"]["fits"] == serde_json::Value::Bool(true) {
        return None;
    }
    Some(
        "the goodness-of-fit test rejects the noise model (see the warnings above); the \
         result is written, `ppoe table --noise` refuses it unless --allow-rejected-noise"
            .into(),
    )
}

/// `--estimate`'s list: `base`, `tip`, `offsets`, `kinematics` (any subset), or `all`.
fn parse_estimate(s: &str) -> Result<ppoe_fit::Estimate, String> {
    let mut e = ppoe_fit::Estimate::NONE;
    for item in s.split(',').map(str::trim) {
        match item {
            "base" => e.base = true,
            "tip" => e.tip = true,
            "offsets" => e.offsets = true,
            "kinematics" => e.kinematics = true,
            "all" => e = ppoe_fit::Estimate::ALL,
            other => {
                return Err(format!(
                    "unknown group '{other}' (expected base, tip, offsets, kinematics or all, \
                     comma-separated)"
                ))
            }
        }
    }
    Ok(e)
}
