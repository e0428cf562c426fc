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
//! error, 1 for anything else (see [`EXIT_CODES`]).

mod cases;
mod draw;
mod eval;
mod fit;
mod links;
mod load;
mod mesh;
mod names;
mod output;
mod picture;
mod seed;
mod visuals;

use clap::{Args, CommandFactory, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;

/// The exit statuses, as `--help` states them.
const EXIT_CODES: &str = "Exit status: 0 on success (also when the reader of standard output \
closes it early, as `ppoe eval ... | head` does); 1 when an input is unreadable or wrong, a \
computation fails or a file cannot be written (one line on standard error, `error: ...`); 2 \
for a usage error (unknown subcommand or flag, missing or out-of-range value). FILE \
arguments (--urdf, --input) accept `-` for standard input and pipes such as `<(xacro \
robot.urdf.xacro)`; each input is read once. Output files are written to a temporary file \
and renamed, so an interrupted run never leaves a partial file under the final name.";

/// The exit statuses, in short, for each subcommand's `--help`.
const EXIT_CODES_SHORT: &str = "Exit status: 0 success; 1 bad input, failed computation or \
write; 2 usage error. FILE may be `-` (standard input) or a pipe.";

/// Exit status of a usage error (clap's convention).
const USAGE_ERROR: u8 = 2;

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
    Table(TableArgs),
    /// Evaluate the PPOE (tool pose and 6×6 covariance) for the cases of a JSON file.
    ///
    /// Input (file or stdin): {"cases":[{"thetas":[N numbers],"covs":[N 6×6 row-major]}]}
    /// (covariances rotation first, in the base frame, right perturbation of each joint).
    /// Output (stdout): {"chain":{"base","tip","joints","screw_axes","home","limits"},
    /// "results":[{"thetas_clipped","pose","cov"}]}; infinite limits are null.
    #[command(after_help = EXIT_CODES_SHORT)]
    Eval(EvalArgs),
    /// The seed example: the seed robot (its table generated at build time), its initial
    /// pose and covariance, and the 200-frame animation as ppoe-seed.png, ppoe-seed.gif and
    /// the interactive ppoe-seed.html.
    #[command(after_help = EXIT_CODES_SHORT)]
    Demo(DemoArgs),
    /// Draw any robot and its tool-pose distribution for the cases of a JSON file (the
    /// input of `ppoe eval`): one picture per case (png, svg), one animation (gif) or one
    /// interactive view (html).
    #[command(after_help = EXIT_CODES_SHORT)]
    Render(RenderArgs),
    /// Write the equiprobable surface (and the skeleton as lines) of each case of a JSON
    /// file (the input of `ppoe eval`) as a mesh for Blender or MeshLab.
    #[command(after_help = EXIT_CODES_SHORT)]
    Mesh(MeshArgs),
    /// Fit the per-joint noise covariances to joint values recorded with tool poses
    /// measured by an external tracker (maximum likelihood of the PPOE's model).
    ///
    /// Input: {"samples":[{"thetas":[N numbers],"pose":[[4×4 row-major, tip in base]]}],
    /// "measurement_cov": optional 6×6, the tracker's noise in the tip frame (rotation
    /// first)}. Output (stdout, or --out written atomically): {"model","joints":[{"name",
    /// "cov" (6×6, what `eval` takes as covs[i]),"cov_se","sigma2","sigma2_se"}],
    /// "log_likelihood","samples","converged","identifiability","goodness_of_fit",
    /// "prediction_error" (relative standard error of the predicted tool covariance),
    /// "warnings",...}; a summary (estimate ± standard error per joint) on stderr.
    #[command(after_help = EXIT_CODES_SHORT)]
    Fit(FitArgs),
    /// List the links and joints of a URDF as a tree (joint type, axis, limits), to find
    /// the names for --base, --tip and --joints.
    #[command(after_help = EXIT_CODES_SHORT)]
    Links(LinksArgs),
    /// Print a shell completion script (e.g. `ppoe completions bash >
    /// ~/.local/share/bash-completion/completions/ppoe`).
    #[command(after_help = EXIT_CODES_SHORT)]
    Completions(CompletionsArgs),
}

#[derive(Args, Debug)]
struct LinksArgs {
    /// The URDF file (`-`: standard input).
    #[arg(long, value_name = "FILE")]
    urdf: PathBuf,
}

#[derive(Args, Debug)]
struct CompletionsArgs {
    /// The shell.
    #[arg(value_enum)]
    shell: clap_complete::Shell,
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
    /// The input JSON file (default or `-`: standard input).
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
    /// The URDF file (`-`: standard input).
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
    /// The language: rust (`pub const` items) or c (a C99 header of `static const` data
    /// for ppoe-ffi's C API, `ppoe.h`).
    #[arg(long, value_enum, default_value_t = TableLang::Rust)]
    lang: TableLang,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum TableLang {
    Rust,
    C,
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
    /// The input JSON file (default or `-`: standard input).
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
    /// Draw the surface at K standard deviations (Mahalanobis radius in 3D; a positive
    /// finite number; default 1).
    #[arg(long, value_name = "K", allow_negative_numbers = true, value_parser = positive_finite)]
    sigma: Option<f64>,
    /// Draw the surface holding probability P of the tool positions, 0 < P < 1 (k from
    /// χ²₃, e.g. 0.95 → k = 2.80).
    #[arg(long, value_name = "P", allow_negative_numbers = true, value_parser = open_unit)]
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
    /// Grid points per side of the surface (2 to 400).
    #[arg(long, default_value_t = 40, value_parser = clap::value_parser!(u16).range(2..=400))]
    grid: u16,
}

#[derive(Args, Debug)]
struct DemoArgs {
    /// The directory to write ppoe-seed.png, ppoe-seed.gif and ppoe-seed.html into.
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    #[command(flatten)]
    surface: SurfaceArgs,
    /// Use the joint covariances of a noise model written by `ppoe fit` for the seed
    /// robot instead of the example's.
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
    /// The number of animation frames, 1 to 10000 (angle = 0.5·cos(2π(0.5 + step/N))).
    /// The frames are streamed to the files (memory does not grow with N); each is
    /// computed three times (to fit the view, for the page, for the GIF).
    #[arg(long, value_name = "N", default_value_t = 200,
          value_parser = clap::value_parser!(u32).range(1..=10000))]
    frames: u32,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum ImageFormat {
    Png,
    Svg,
    Gif,
    Html,
}

#[derive(Args, Debug)]
struct RenderArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The input JSON file (the input of `ppoe eval`; default or `-`: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// Take every case's covariances from a noise model written by `ppoe fit`.
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
    /// png or svg: one picture per case (ppoe-render-<i>.<ext>), each written as it is
    /// computed; gif: one animation of all cases (ppoe-render.gif); html: one interactive
    /// view of all cases (ppoe-render.html). gif and html are streamed (memory does not
    /// grow with the number of cases); each case is computed twice (to fit the view, to
    /// write it).
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
    /// The input JSON file (the input of `ppoe eval`; default or `-`: standard input).
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

/// `--sigma`: a positive finite number (a usage error otherwise, exit status 2).
fn positive_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(k) if k.is_finite() && k > 0.0 => Ok(k),
        Ok(_) => Err("expected a positive finite number of standard deviations".to_string()),
        Err(e) => Err(format!("not a number ({e})")),
    }
}

/// `--probability`: strictly between 0 and 1 (a usage error otherwise, exit status 2).
fn open_unit(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(p) if p > 0.0 && p < 1.0 => Ok(p),
        Ok(_) => Err("expected a probability strictly between 0 and 1".to_string()),
        Err(e) => Err(format!("not a number ({e})")),
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(&e),
    };
    let result = run(cli);
    let stdout_error = output::take_stdout_error();
    match (result, stdout_error) {
        (Err(e), _) => report(&format!("{e:#}")),
        (Ok(()), Some(e)) => report(&e),
        (Ok(()), None) => ExitCode::SUCCESS,
    }
}

/// Help and version on standard output (status 0); a bare `ppoe` prints the help on
/// standard error (status 2); any other usage error is one line (status 2).
fn usage_error(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            ExitCode::from(USAGE_ERROR)
        }
        _ => {
            eprintln!("error: {} (see --help)", one_line(&clap_message(e)));
            ExitCode::from(USAGE_ERROR)
        }
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

/// Messages longer than this many characters are cut (a name of megabytes must not be
/// echoed whole).
const MAX_MESSAGE: usize = 2000;

/// A message as one safe line: lines joined with "; ", control characters escaped, cut
/// after [`MAX_MESSAGE`] characters with the full length.
fn one_line(message: &str) -> String {
    let joined = message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    let mut out = String::new();
    for (count, c) in joined.chars().enumerate() {
        if count == MAX_MESSAGE {
            out.push_str(&format!("… (message of {} bytes cut)", joined.len()));
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// Prints `error: <message>` as one line on stderr; exit status 1.
fn report(message: &str) -> ExitCode {
    eprintln!("error: {}", one_line(message));
    ExitCode::FAILURE
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Fit(a) => fit_command(&a),
        Command::Table(a) => table(&a),
        Command::Eval(a) => eval_command(&a),
        Command::Demo(a) => demo(&a),
        Command::Render(a) => render(&a),
        Command::Mesh(a) => mesh_command(&a),
        Command::Links(a) => {
            let (_, urdf) = load::urdf(&a.urdf)?;
            output::print(links::tree(&urdf).as_bytes())
        }
        Command::Completions(a) => {
            let mut text = Vec::new();
            clap_complete::generate(a.shell, &mut Cli::command(), "ppoe", &mut text);
            output::print(&text)
        }
    }
}

/// `ppoe demo`: outputs checked before any computation.
fn demo(a: &DemoArgs) -> anyhow::Result<()> {
    let names = ["ppoe-seed.png", "ppoe-seed.gif", "ppoe-seed.html"].map(String::from);
    output::check_targets(&a.out, &names)?;
    draw::demo(&a.out, &a.surface, a.frames as usize, a.noise.as_deref())
}

/// `ppoe render`: one picture per case, or one animation.
fn render(a: &RenderArgs) -> anyhow::Result<()> {
    let fmt = a.format;
    let name = move |i: usize| match fmt {
        ImageFormat::Svg => format!("ppoe-render-{i}.svg"),
        _ => format!("ppoe-render-{i}.png"),
    };
    // The picture writers write atomically themselves.
    let write = move |p: &std::path::Path, f: &picture::Frame| match fmt {
        ImageFormat::Svg => picture::write_svg(p, f),
        _ => picture::write_png(p, f),
    };
    let sink = match fmt {
        ImageFormat::Gif => cases::Sink::Gif {
            dir: &a.out,
            name: "ppoe-render.gif",
        },
        ImageFormat::Html => cases::Sink::Html {
            dir: &a.out,
            name: "ppoe-render.html",
        },
        _ => cases::Sink::Each {
            dir: &a.out,
            name: &name,
            write: &write,
        },
    };
    cases::run(
        &a.chain,
        a.input.as_deref(),
        a.noise.as_deref(),
        &a.surface,
        &sink,
    )
}

/// `ppoe mesh`: one mesh file per case.
fn mesh_command(a: &MeshArgs) -> anyhow::Result<()> {
    let fmt = a.format;
    let name = move |i: usize| match fmt {
        MeshFormat::Obj => format!("ppoe-mesh-{i}.obj"),
        MeshFormat::Ply => format!("ppoe-mesh-{i}.ply"),
    };
    let write = move |p: &std::path::Path, f: &picture::Frame| match fmt {
        MeshFormat::Obj => mesh::write_obj(p, f),
        MeshFormat::Ply => mesh::write_ply(p, f),
    };
    let sink = cases::Sink::Each {
        dir: &a.out,
        name: &name,
        write: &write,
    };
    cases::run(
        &a.chain,
        a.input.as_deref(),
        a.noise.as_deref(),
        &a.surface,
        &sink,
    )
}

/// `ppoe fit`: the noise model fitted to the samples, on standard output or `--out`.
fn fit_command(a: &FitArgs) -> anyhow::Result<()> {
    load::check_one_stdin(&a.chain.urdf, a.input.as_deref())?;
    if let Some(out) = &a.out {
        let dir = out.parent().filter(|d| !d.as_os_str().is_empty());
        let name = out.file_name().map(|n| n.to_string_lossy().into_owned());
        let Some(name) = name else {
            anyhow::bail!("--out {} has no file name", out.display());
        };
        output::check_targets(dir.unwrap_or(std::path::Path::new(".")), &[name])?;
    }
    let robot = load::robot(&a.chain)?;
    let input = load::read(
        a.input.as_deref().unwrap_or(std::path::Path::new("-")),
        "input file",
    )?;
    let text = std::str::from_utf8(&input.bytes)
        .map_err(|_| anyhow::anyhow!("{}: the input is not UTF-8", input.name))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
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

/// `ppoe table`: the generated source on standard output.
fn table(a: &TableArgs) -> anyhow::Result<()> {
    let robot = load::robot(&a.chain)?;
    // The file's stem names the table; a pipe's (`/dev/fd/63`) cannot, the robot can.
    let stem = match &a.chain.urdf.file_stem() {
        Some(s) if robot.source.regular => s.to_string_lossy().into_owned(),
        _ => robot.urdf.name.clone(),
    };
    let scalar = match a.scalar {
        TableScalar::F32 => ppoe_build::Scalar::F32,
        TableScalar::F64 => ppoe_build::Scalar::F64,
        TableScalar::Both => ppoe_build::Scalar::Both,
    };
    let lang = match a.lang {
        TableLang::Rust => ppoe_build::Lang::Rust,
        TableLang::C => ppoe_build::Lang::C,
    };
    if a.noise.is_some() && lang == ppoe_build::Lang::C {
        anyhow::bail!("--noise is not supported with --lang c yet: the C API takes the covariances as arguments");
    }
    let model = match &a.noise {
        Some(p) => Some((
            ppoe_build::noise::NoiseModel::read(p)
                .map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))?,
            p,
        )),
        None => None,
    };
    let src = ppoe_build::Table {
        chain: &robot.chain,
        urdf: &robot.source.bytes,
        file_name: &robot.source.file_name,
        name: &ppoe_build::table::const_name(a.name.as_deref(), &stem),
        scalar,
        lang,
        noise: model
            .as_ref()
            .map(|(model, path)| ppoe_build::table::Noise { model, path }),
    }
    .generate()
    // Errors of the noise model name its file; the others are the URDF's.
    .map_err(|e| match e.file() {
        Some(_) => anyhow::anyhow!("{e}"),
        None => load::in_input(&robot.source.name, &e),
    })?;
    output::print(src.as_bytes())
}

/// `ppoe eval`: the results as JSON on standard output.
fn eval_command(a: &EvalArgs) -> anyhow::Result<()> {
    load::check_one_stdin(&a.chain.urdf, a.input.as_deref())?;
    let robot = load::robot(&a.chain)?;
    let input = fit::cases(a.input.as_deref(), a.noise.as_deref(), &robot.chain)?;
    let out = eval::eval(&robot.chain, &input, a.scalar, a.convention.core())?;
    let mut text = if a.pretty {
        serde_json::to_string_pretty(&out)?
    } else {
        serde_json::to_string(&out)?
    };
    text.push('\n');
    output::print(text.as_bytes())
}
