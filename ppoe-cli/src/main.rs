//! `ppoe`: robot tables from URDF, the Probabilistic Product of Exponentials on them, and
//! pictures of the result.
//!
//! ```text
//! ppoe table --urdf robot.urdf --base base_link --tip tool0 [--scalar f32|f64|both] [--lang rust|c]
//! ppoe eval  --urdf robot.urdf --base base_link --tip tool0 --input cases.json
//! ppoe demo  [--out DIR] [--sigma K | --probability P] [--surface lift|marginal|pytransform3d]
//! ppoe render --urdf robot.urdf --base base_link --tip tool0 --input cases.json --format png
//! ppoe mesh   --urdf robot.urdf --base base_link --tip tool0 --input cases.json --format obj
//! ppoe links  --urdf robot.urdf
//! ppoe completions bash
//! ppoe fit    --urdf robot.urdf --base base_link --tip tool0 --input data.json --model joint
//! ```
//!
//! Errors are reported as one line on stderr (`error: ...`); exit status 2 for a usage
//! error, 3 for a fit written but rejected, 1 for anything else (see
//! [`report::EXIT_CODES`]).

mod args;
mod calibration;
mod cases;
mod commands;
mod draw;
mod eval;
mod exaggerate;
mod fit;
mod frames;
mod input;
mod links;
mod load;
mod mesh;
mod meshfile;
mod names;
mod noise;
mod output;
mod picture;
mod pretty;
mod report;
mod ros;
mod seed;
mod visuals;

use clap::{CommandFactory, Parser, Subcommand};
use report::{EXIT_CODES, EXIT_CODES_SHORT};
use std::process::ExitCode;

/// Probabilistic Product of Exponentials: robot tables from URDF, tool pose and its 6×6
/// covariance, and pictures of the tool's uncertainty.
#[derive(Parser, Debug)]
#[command(name = "ppoe", version, about, long_about = None,
          arg_required_else_help = true, after_help = EXIT_CODES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Print the Rust source of a robot table (`pub const NAME: ppoe::chain::Chain<..>`)
    /// generated from a URDF, as `ppoe-build` writes it from a build script.
    #[command(after_help = EXIT_CODES_SHORT)]
    Table(commands::table::TableArgs),
    /// Evaluate the PPOE (tool pose and 6×6 covariance) for the cases of a JSON file.
    ///
    /// Input (file or stdin): {"cases":[{"thetas":[N numbers],"covs":[N 6×6 row-major]}]}
    /// (covariances rotation first, in the base frame, right perturbation of each joint).
    /// Output (stdout): {"chain":{"base","tip","joints","screw_axes","home","limits"},
    /// "results":[{"thetas_clipped","pose","cov"}]}; infinite limits are null. For a chain
    /// with mimic joints, "thetas" are its independent values (`chain.inputs` of the output;
    /// `ppoe links` shows each mimic joint's master), "covs" one per chain joint.
    #[command(after_help = EXIT_CODES_SHORT)]
    Eval(commands::eval::EvalArgs),
    /// The seed example: the seed robot (its table generated at build time), its initial
    /// pose and covariance, and the 200-frame animation as ppoe-seed.png, ppoe-seed.gif and
    /// the interactive ppoe-seed.html.
    #[command(after_help = EXIT_CODES_SHORT)]
    Demo(commands::demo::DemoArgs),
    /// Draw any robot and its tool-pose distribution for the cases of a JSON file (the
    /// input of `ppoe eval`): one picture per case (png, svg), one animation (gif) or one
    /// interactive view (html).
    #[command(after_help = EXIT_CODES_SHORT)]
    Render(commands::render::RenderArgs),
    /// Write the equiprobable surface (and the skeleton as lines) of each case of a JSON
    /// file (the input of `ppoe eval`) as a mesh for Blender or MeshLab.
    #[command(after_help = EXIT_CODES_SHORT)]
    Mesh(commands::mesh::MeshArgs),
    /// Fit the per-joint noise covariances to joint values recorded with tool poses or
    /// positions measured by an external tracker (maximum likelihood of the PPOE's model),
    /// calibrating the tracker's registration, the marker and the kinematics with
    /// --estimate.
    ///
    /// Input: {"samples":[{"thetas":[N numbers],"pose":[[4×4 row-major, marker in the
    /// tracker's frame]]} or {"thetas":[N],"position":[x,y,z]} (all samples one kind)],
    /// "measurement_cov": optional, the tracker's noise: 6×6 in the marker frame
    /// (rotation first) for poses, 3×3 (m²) for positions}. Output (stdout, or --out
    /// written atomically): {"model","joints":[{"name","cov" (6×6, what `eval` takes as
    /// covs[i], of the calibrated chain),"cov_se","sigma2","sigma2_se","offset",
    /// "offset_se","axis_correction","axis_correction_se"}],"log_likelihood","samples",
    /// "converged","identifiability","goodness_of_fit" (with "mean_test" and
    /// "calibration_test"),"prediction_error","calibration" ("base_in_tracker",
    /// "marker_in_tip" as {"pose","cov"}, "home_correction", "residual_rms" before and
    /// after, "undetermined"),"warnings",...}; on stderr the residuals before and after
    /// calibration, then estimate ± standard error per joint.
    #[command(after_help = EXIT_CODES_SHORT)]
    Fit(commands::fit::FitArgs),
    /// List the links and joints of a URDF as a tree (joint type, axis, limits), to find
    /// the names for --base, --tip and --joints.
    #[command(after_help = EXIT_CODES_SHORT)]
    Links(commands::links::LinksArgs),
    /// Print a shell completion script (e.g. `ppoe completions bash >
    /// ~/.local/share/bash-completion/completions/ppoe`).
    #[command(after_help = EXIT_CODES_SHORT)]
    Completions(commands::completions::CompletionsArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return report::usage_error(&e),
    };
    let result = run(cli);
    let stdout_error = output::take_stdout_error();
    match (result, stdout_error) {
        (Err(e), _) => report::error(&e),
        (Ok(()), Some(e)) => report::report(&e),
        (Ok(()), None) => ExitCode::SUCCESS,
    }
}

/// Runs the subcommand.
fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Fit(a) => commands::fit::run(&a),
        Command::Table(a) => commands::table::run(&a),
        Command::Eval(a) => commands::eval::run(&a),
        Command::Demo(a) => commands::demo::run(&a),
        Command::Render(a) => commands::render::run(&a),
        Command::Mesh(a) => commands::mesh::run(&a),
        Command::Links(a) => commands::links::run(&a),
        Command::Completions(a) => commands::completions::run(&a, &mut Cli::command()),
    }
}
