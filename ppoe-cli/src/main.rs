//! `ppoe`: robot tables from URDF, the Probabilistic Product of Exponentials on them, and
//! pictures of the result.
//!
//! ```text
//! ppoe table --urdf robot.urdf --base base_link --tip tool0 [--scalar f32|f64|both]
//! ppoe eval  --urdf robot.urdf --base base_link --tip tool0 --input cases.json
//! ppoe demo  [--out DIR] [--sigma K | --probability P] [--surface lift|marginal|pytransform3d]
//! ppoe render --urdf robot.urdf --base base_link --tip tool0 --input cases.json --format png
//! ppoe mesh   --urdf robot.urdf --base base_link --tip tool0 --input cases.json --format obj
//! ppoe fit    --urdf robot.urdf --base base_link --tip tool0 --input data.json --model joint
//! ```
//!
//! Errors are reported as one line on stderr (`error: ...`) with exit status 1.

mod draw;
mod eval;
mod fit;
mod frames;
mod mesh;
mod picture;
mod seed;

use anyhow::Context;
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;

/// Probabilistic Product of Exponentials: robot tables from URDF, tool pose and its 6×6
/// covariance, and pictures of the tool's uncertainty.
#[derive(Parser, Debug)]
#[command(name = "ppoe", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Print the Rust source of a robot table (`pub const NAME: ppoe::chain::Chain<..>`)
    /// generated from a URDF, as `ppoe-build` writes it from a build script.
    Table(TableArgs),
    /// Evaluate the PPOE (tool pose and 6×6 covariance) for the cases of a JSON file.
    ///
    /// Input (file or stdin): {"cases":[{"thetas":[N numbers],"covs":[N 6×6 row-major]}]}
    /// (covariances rotation first, in the base frame, right perturbation of each joint).
    /// Output (stdout): {"chain":{"base","tip","joints","screw_axes","home","limits"},
    /// "results":[{"thetas_clipped","pose","cov"}]}; infinite limits are null.
    Eval(EvalArgs),
    /// The seed example: the seed robot (its table generated at build time), its initial
    /// pose and covariance, and the 200-frame animation as ppoe-seed.png and ppoe-seed.gif.
    Demo(DemoArgs),
    /// Draw any robot and its tool-pose distribution for the cases of a JSON file (the
    /// input of `ppoe eval`): one picture per case (png, svg) or one animation (gif).
    Render(RenderArgs),
    /// Write the equiprobable surface (and the skeleton as lines) of each case of a JSON
    /// file (the input of `ppoe eval`) as a mesh for Blender or MeshLab.
    Mesh(MeshArgs),
    /// Fit the per-joint noise covariances to joint values recorded with tool poses
    /// measured by an external tracker (maximum likelihood of the PPOE's model).
    ///
    /// Input: {"samples":[{"thetas":[N numbers],"pose":[[4×4 row-major, tip in base]]}],
    /// "measurement_cov": optional 6×6, the tracker's noise in the tip frame (rotation
    /// first)}. Output (stdout, or --out written atomically): {"model","joints":[{"name",
    /// "cov" (6×6, what `eval` takes as covs[i]),"cov_se","sigma2","sigma2_se"}],
    /// "log_likelihood","samples","converged","identifiability","goodness_of_fit",
    /// "warnings",...}; a summary (estimate ± standard error per joint) on stderr.
    Fit(FitArgs),
}

/// Which per-joint noise `fit` estimates.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum FitModel {
    /// One variance per joint along its screw axis (encoder noise, backlash).
    Joint,
    /// Any 6×6 PSD covariance per joint (flexible links).
    Full,
}

#[derive(Args, Debug)]
struct FitArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The input JSON file (default: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// The noise model to fit.
    #[arg(long, value_enum)]
    model: FitModel,
    /// Write the result to FILE (atomically) instead of standard output.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
}

/// Which chain of which URDF.
#[derive(Args, Debug, Clone)]
struct ChainArgs {
    /// The URDF file.
    #[arg(long, value_name = "FILE")]
    urdf: PathBuf,
    /// The base link: screw axes and poses are expressed in its frame.
    #[arg(long, value_name = "LINK")]
    base: String,
    /// The tip link (e.g. the tool centre point).
    #[arg(long, value_name = "LINK")]
    tip: String,
    /// The moving joints, base to tip, comma-separated (default: every moving joint on
    /// the path; moving joints left out are frozen at 0).
    #[arg(long, value_name = "A,B,...", value_delimiter = ',')]
    joints: Option<Vec<String>>,
}

impl ChainArgs {
    fn config(&self) -> ppoe_build::Config {
        let mut c = ppoe_build::Config::new(&self.urdf);
        c.base(&self.base).tip(&self.tip);
        if let Some(j) = &self.joints {
            c.joints(j);
        }
        c
    }
}

#[derive(Args, Debug)]
struct TableArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// Which tables to emit: NAME (f64), NAME_F32 (f32) or both.
    #[arg(long, value_enum, default_value_t = TableScalar::F64)]
    scalar: TableScalar,
    /// The const's name (default: the URDF file's stem in upper case).
    #[arg(long)]
    name: Option<String>,
    /// Also emit NAME_NOISE (and NAME_SIGMA2 for the joint model) from a noise model
    /// written by `ppoe fit`.
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum TableScalar {
    F32,
    F64,
    Both,
}

/// The scalar type the PPOE is computed in.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum EvalScalar {
    /// Double precision.
    F64,
    /// Single precision: the chain and the inputs are rounded to f32, the outputs
    /// converted back to f64.
    F32,
}

/// Which covariance `eval` returns.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConventionArg {
    /// The right (local) perturbation of the returned pose, T = T̄·Exp(η), η ~ N(0, Σ)
    /// in the tip frame (the correct covariance; the default).
    Ppoe,
    /// The left (global) perturbation, T = Exp(η)·T̄, η in the base frame.
    Left,
    /// pytransform3d's example reproduced exactly (Ad(M) in the last step, continuous
    /// joints clipped to their limits): for comparison and migration only.
    Pytransform3d,
}

impl ConventionArg {
    fn core(self) -> ppoe::chain::Convention {
        match self {
            ConventionArg::Ppoe => ppoe::chain::Convention::Right,
            ConventionArg::Left => ppoe::chain::Convention::Left,
            ConventionArg::Pytransform3d => ppoe::chain::Convention::Pytransform3d,
        }
    }
}

#[derive(Args, Debug)]
struct EvalArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The scalar type to compute in.
    #[arg(long, value_enum, default_value_t = EvalScalar::F64)]
    scalar: EvalScalar,
    /// Which covariance to return.
    #[arg(long, value_enum, default_value_t = ConventionArg::Ppoe)]
    convention: ConventionArg,
    /// The input JSON file (default: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// Indent the output JSON.
    #[arg(long)]
    pretty: bool,
    /// Take every case's covariances from a noise model written by `ppoe fit` (the cases
    /// then give no "covs").
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
}

/// Which equiprobable surface of the tool position to draw.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SurfaceArg {
    /// The lift surface ξ(s) = Σ[:,v]·Σ_vv^(−½)·s, |s| = k, through T̄·Exp(ξ): right
    /// coverage, bends like the sampled cloud (the default).
    Lift,
    /// The linear marginal ellipsoid of the tool position.
    Marginal,
    /// pytransform3d's to_projected_ellipsoid of the compatible covariance, factor k (not
    /// an equiprobable surface; for comparison with the reference).
    Pytransform3d,
}

/// The probability level of the surface.
#[derive(Args, Debug, Clone)]
#[group(multiple = false)]
pub struct LevelArgs {
    /// Draw the surface at K standard deviations (Mahalanobis radius in 3D; default 1).
    #[arg(long, value_name = "K")]
    sigma: Option<f64>,
    /// Draw the surface holding probability P of the tool positions (k from χ²₃, e.g.
    /// 0.95 → k = 2.80).
    #[arg(long, value_name = "P")]
    probability: Option<f64>,
}

/// What to draw and how.
#[derive(Args, Debug, Clone)]
pub struct SurfaceArgs {
    #[command(flatten)]
    level: LevelArgs,
    /// Which surface to draw.
    #[arg(long, value_enum, default_value_t = SurfaceArg::Lift)]
    surface: SurfaceArg,
    /// Grid points per side of the surface.
    #[arg(long, default_value_t = 40, value_parser = clap::value_parser!(u16).range(2..=400))]
    grid: u16,
}

#[derive(Args, Debug)]
struct DemoArgs {
    /// The directory to write ppoe-seed.png and ppoe-seed.gif into.
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    #[command(flatten)]
    surface: SurfaceArgs,
    /// Use the joint covariances of a noise model written by `ppoe fit` for the seed
    /// robot instead of the example's.
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
    /// The number of animation frames (angle = 0.5·cos(2π(0.5 + step/N))).
    #[arg(long, value_name = "N", default_value_t = 200,
          value_parser = clap::value_parser!(u32).range(1..=10000))]
    frames: u32,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum ImageFormat {
    Png,
    Svg,
    Gif,
}

#[derive(Args, Debug)]
struct RenderArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The input JSON file (the input of `ppoe eval`; default: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// Take every case's covariances from a noise model written by `ppoe fit`.
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
    /// png or svg: one picture per case (ppoe-render-<i>.<ext>); gif: one animation of
    /// all cases (ppoe-render.gif).
    #[arg(long, value_enum, default_value_t = ImageFormat::Png)]
    format: ImageFormat,
    /// The output directory.
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    #[command(flatten)]
    surface: SurfaceArgs,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum MeshFormat {
    Obj,
    Ply,
}

#[derive(Args, Debug)]
struct MeshArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The input JSON file (the input of `ppoe eval`; default: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// Take every case's covariances from a noise model written by `ppoe fit`.
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
    /// One file per case: ppoe-mesh-<i>.obj or ppoe-mesh-<i>.ply.
    #[arg(long, value_enum, default_value_t = MeshFormat::Obj)]
    format: MeshFormat,
    /// The output directory.
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    #[command(flatten)]
    surface: SurfaceArgs,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            return match e.kind() {
                ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
                    let _ = e.print();
                    ExitCode::SUCCESS
                }
                ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => report(
                    "a subcommand or argument is missing (see 'ppoe --help' or \
                     'ppoe <command> --help')",
                ),
                _ => report(&format!("{} (see --help)", clap_message(&e))),
            };
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => report(&format!("{e:#}")),
    }
}

/// The message of a clap error without its usage lines, on one line.
fn clap_message(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let mut parts = Vec::new();
    for line in text.lines().map(str::trim) {
        if line.starts_with("Usage:") || line.starts_with("For more information") {
            break;
        }
        if !line.is_empty() {
            parts.push(line.strip_prefix("error: ").unwrap_or(line));
        }
    }
    parts.join(" ")
}

/// Prints `error: <message>` as one line on stderr; exit status 1.
fn report(message: &str) -> ExitCode {
    let one_line = message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    eprintln!("error: {one_line}");
    ExitCode::FAILURE
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Table(a) => {
            let mut c = a.chain.config();
            c.scalar(match a.scalar {
                TableScalar::F32 => ppoe_build::Scalar::F32,
                TableScalar::F64 => ppoe_build::Scalar::F64,
                TableScalar::Both => ppoe_build::Scalar::Both,
            });
            if let Some(n) = &a.name {
                c.name(n);
            }
            if let Some(p) = &a.noise {
                c.noise(p);
            }
            let src = c.generate()?;
            write_stdout(src.as_bytes())
        }
        Command::Eval(a) => {
            let robot = a.chain.config().chain()?;
            let input = fit::read_cases(a.input.as_deref(), a.noise.as_deref(), &robot)?;
            let out = eval::eval(&robot, &input, a.scalar, a.convention.core())?;
            let mut text = if a.pretty {
                serde_json::to_string_pretty(&out)?
            } else {
                serde_json::to_string(&out)?
            };
            text.push('\n');
            write_stdout(text.as_bytes())
        }
        Command::Demo(a) => draw::demo(&a.out, &a.surface, a.frames as usize, a.noise.as_deref()),
        Command::Render(a) => {
            let frames = draw::frames_for_cases(
                &a.chain,
                a.input.as_deref(),
                &a.surface,
                a.noise.as_deref(),
            )?;
            draw::ensure_dir(&a.out)?;
            let mut written = Vec::new();
            match a.format {
                ImageFormat::Gif => {
                    let p = a.out.join("ppoe-render.gif");
                    picture::write_gif(&p, &frames)?;
                    written.push(p);
                }
                f => {
                    for (i, frame) in frames.iter().enumerate() {
                        let p = if f == ImageFormat::Png {
                            a.out.join(format!("ppoe-render-{i}.png"))
                        } else {
                            a.out.join(format!("ppoe-render-{i}.svg"))
                        };
                        if f == ImageFormat::Png {
                            picture::write_png(&p, frame)?;
                        } else {
                            picture::write_svg(&p, frame)?;
                        }
                        written.push(p);
                    }
                }
            }
            for p in written {
                println!("wrote {}", p.display());
            }
            Ok(())
        }
        Command::Fit(a) => {
            let robot = a.chain.config().chain()?;
            let text = match &a.input {
                Some(p) => std::fs::read_to_string(p)
                    .with_context(|| format!("cannot read the input file {}", p.display()))?,
                None => std::io::read_to_string(std::io::stdin())
                    .context("cannot read the input from standard input")?,
            };
            let model = match a.model {
                FitModel::Joint => ppoe_fit::Model::Joint,
                FitModel::Full => ppoe_fit::Model::Full,
            };
            let mut text = serde_json::to_string_pretty(&fit::run(&robot, &text, model)?)?;
            text.push('\n');
            match &a.out {
                Some(p) => fit::write_atomic(p, text.as_bytes()),
                None => write_stdout(text.as_bytes()),
            }
        }
        Command::Mesh(a) => {
            let frames = draw::frames_for_cases(
                &a.chain,
                a.input.as_deref(),
                &a.surface,
                a.noise.as_deref(),
            )?;
            draw::ensure_dir(&a.out)?;
            for (i, frame) in frames.iter().enumerate() {
                let p = match a.format {
                    MeshFormat::Obj => {
                        let p = a.out.join(format!("ppoe-mesh-{i}.obj"));
                        mesh::write_obj(&p, frame)?;
                        p
                    }
                    MeshFormat::Ply => {
                        let p = a.out.join(format!("ppoe-mesh-{i}.ply"));
                        mesh::write_ply(&p, frame)?;
                        p
                    }
                };
                println!("wrote {}", p.display());
            }
            Ok(())
        }
    }
}

/// Writes to stdout; a closed pipe (`ppoe table ... | head`) is not an error.
fn write_stdout(bytes: &[u8]) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        r => Ok(r?),
    }
}
