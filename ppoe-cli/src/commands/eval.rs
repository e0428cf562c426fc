//! `ppoe eval`: the PPOE (tool pose and 6×6 covariance) for the cases of a JSON file.

use crate::args::{ChainArgs, ConventionArg, EvalScalar, NoiseArgs};
use crate::{cases, eval, load, noise, output};
use clap::Args;
use std::path::PathBuf;

/// The arguments of `ppoe eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The scalar type to compute in.
    #[arg(long, value_enum, default_value_t = EvalScalar::F64)]
    scalar: EvalScalar,
    /// Which covariance to return.
    #[arg(long, value_enum, default_value_t = ConventionArg::Ppoe)]
    convention: ConventionArg,
    /// The input JSON file (default or `-`: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// Indent the output JSON.
    #[arg(long)]
    pretty: bool,
    #[command(flatten)]
    noise: NoiseArgs,
}

/// `ppoe eval`: the results as JSON on standard output.
pub fn run(a: &EvalArgs) -> anyhow::Result<()> {
    load::check_one_stdin(&[
        load::urdf_input(&a.chain.urdf),
        load::cases_input(a.input.as_deref()),
        load::noise_input(a.noise.noise.as_deref()),
    ])?;
    let mut robot = load::robot(&a.chain)?;
    // The noise model first: a calibration replaces the chain the cases are checked against.
    let covs = match &a.noise.noise {
        Some(p) => Some(noise::apply(p, a.noise.allow_rejected_noise, &mut robot.chain)?.covs),
        None => None,
    };
    let mut input = cases::load(a.input.as_deref(), covs)?;
    cases::expand_mimic(&robot.chain, &mut input)?;
    let out = eval::eval(&robot.chain, &input, a.scalar, a.convention.core())?;
    let mut text = if a.pretty {
        serde_json::to_string_pretty(&out)?
    } else {
        serde_json::to_string(&out)?
    };
    text.push('\n');
    output::print(text.as_bytes())
}
