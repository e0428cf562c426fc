//! `ppoe eval`: the PPOE (tool pose and 6×6 covariance) for the cases of a JSON file.

use crate::args::{ChainArgs, ConventionArg, EvalScalar, NoiseArgs};
use crate::{cases, eval, load, noise, output, pretty, ros};
use clap::{Args, ValueEnum};
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
    /// Indent the output JSON (each matrix row, each vector on one line).
    #[arg(long)]
    pretty: bool,
    /// The shape of each result: json (`{"thetas_clipped", "pose": 4×4, "cov": 6×6}`,
    /// rotation first; reads back as the core's `UncertainPose`) or ros (a
    /// geometry_msgs/PoseWithCovariance: position, quaternion x, y, z, w, and 36
    /// covariance numbers translation first in the base frame; needs --convention ppoe or
    /// left).
    #[arg(long, value_enum, default_value_t = EvalFormat::Json)]
    format: EvalFormat,
    #[command(flatten)]
    noise: NoiseArgs,
}

/// The shape of `eval`'s results.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum EvalFormat {
    /// ppoe's: 4×4 pose, 6×6 covariance rotation first.
    Json,
    /// ROS's geometry_msgs/PoseWithCovariance.
    Ros,
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
    let covs = noise::from_args(&a.noise, &mut robot.chain)?.map(|n| n.covs);
    let mut input = cases::load(a.input.as_deref(), covs)?;
    cases::expand_mimic(&robot.chain, &mut input)?;
    let out = eval::eval(&robot.chain, &input, a.scalar, a.convention.core())?;
    let mut text = match a.format {
        EvalFormat::Json => to_json(&out, a.pretty)?,
        EvalFormat::Ros => to_json(&ros::ros_output(out, a.convention)?, a.pretty)?,
    };
    text.push('\n');
    output::print(text.as_bytes())
}

/// Compact JSON, or indented with each row on one line ([`pretty`]).
fn to_json<T: serde::Serialize>(value: &T, pretty: bool) -> serde_json::Result<String> {
    if pretty {
        pretty::to_string(value)
    } else {
        serde_json::to_string(value)
    }
}
