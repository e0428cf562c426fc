//! The argument groups and value types several commands share: the chain of a URDF, the
//! scalar and convention of the PPOE, and what surface to draw at which level. Each
//! command's own arguments are beside it in [`crate::commands`].

use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// Which chain of which URDF.
#[derive(Args, Debug, Clone)]
pub struct ChainArgs {
    /// The URDF file (`-`: standard input).
    #[arg(long, value_name = "FILE")]
    pub urdf: PathBuf,
    /// The base link: screw axes and poses are expressed in its frame.
    #[arg(long, value_name = "LINK")]
    pub base: String,
    /// The tip link (e.g. the tool centre point).
    #[arg(long, value_name = "LINK")]
    pub tip: String,
    /// The moving joints, base to tip, comma-separated (default: every moving joint on
    /// the path; moving joints left out are frozen at 0, a mimic joint too even if its
    /// master is listed: list it to have it follow).
    #[arg(long, value_name = "A,B,...", value_delimiter = ',')]
    pub joints: Option<Vec<String>>,
}

/// The noise model of `eval`, `render` and `mesh`.
#[derive(Args, Debug, Clone)]
pub struct NoiseArgs {
    /// Take every case's covariances from a noise model written by `ppoe fit` (the cases
    /// then give no "covs"). If the fit estimated a calibration, the chain is the
    /// calibrated one (offsets and corrections folded in), which the covariances belong to.
    #[arg(long, value_name = "FILE")]
    pub noise: Option<PathBuf>,
    /// Use a noise model whose fit was rejected by its goodness-of-fit test
    /// (goodness_of_fit.fits false) anyway; without it, such a model is an error.
    #[arg(long, requires = "noise")]
    pub allow_rejected_noise: bool,
    /// Take every case's covariances from a datasheet instead: one σ per moving joint of
    /// the chain, base to tip, comma-separated (radians for revolute and continuous
    /// joints, metres for prismatic ones; σ, not σ²); joint i's covariance is σᵢ²·SᵢSᵢᵀ,
    /// Sᵢ its screw axis in the base frame. Not with --noise (a noise file does the same
    /// with "sigma2" and no "cov" per joint).
    #[arg(
        long,
        value_name = "S1,S2,...",
        value_delimiter = ',',
        allow_negative_numbers = true,
        conflicts_with = "noise"
    )]
    pub joint_sigma: Option<Vec<f64>>,
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
    /// The core's convention.
    pub fn core(self) -> ppoe::chain::Convention {
        match self {
            ConventionArg::Ppoe => ppoe::chain::Convention::Right,
            ConventionArg::Left => ppoe::chain::Convention::Left,
            ConventionArg::Pytransform3d => ppoe::chain::Convention::Pytransform3d,
        }
    }
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
    pub sigma: Option<f64>,
    /// Draw the surface holding probability P of the tool positions, 0 < P < 1 (k from
    /// χ²₃, e.g. 0.95 → k = 2.80).
    #[arg(long, value_name = "P", allow_negative_numbers = true, value_parser = open_unit)]
    pub probability: Option<f64>,
}

/// What to draw and how.
#[derive(Args, Debug, Clone)]
pub struct SurfaceArgs {
    #[command(flatten)]
    pub level: LevelArgs,
    /// Which surface to draw.
    #[arg(long, value_enum, default_value_t = SurfaceArg::Lift)]
    pub surface: SurfaceArg,
    /// Grid points per side of the surface (2 to 400).
    #[arg(long, default_value_t = 40, value_parser = clap::value_parser!(u16).range(2..=400))]
    pub grid: u16,
    /// Most triangles drawn per URDF mesh; a mesh with more is reduced by vertex
    /// clustering, with a notice (the drawing's time and the HTML view's size grow with it).
    #[arg(long, value_name = "N", default_value_t = crate::meshfile::Limits::default().max_triangles,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=100_000_000))]
    pub mesh_triangles: usize,
    /// Scale the drawn surface by K about the mean tool position, so that a small
    /// noise can be seen; the legend then says "surface drawn ×K" (1: true scale).
    /// Default for pictures: auto (a surface under 1/40 of the arm's extent is scaled by
    /// the smallest 1, 2 or 5 × 10ⁿ that makes it 1/10 of it; an animation keeps its first
    /// frame's factor); for `mesh`: 1.
    #[arg(long, value_name = "auto|K", value_parser = crate::exaggerate::parse)]
    pub exaggerate: Option<crate::exaggerate::Exaggeration>,
    /// Where the ROS package NAME is: a URDF mesh `package://NAME/rest` is read from
    /// PATH/rest (repeatable, one per package; the last one of a NAME wins). Without it a
    /// package is looked for beside the URDF (its directory and the parent).
    #[arg(long = "package-dir", value_name = "NAME=PATH", value_parser = package_dir)]
    pub package_dirs: Vec<(String, PathBuf)>,
}

/// `--package-dir NAME=PATH`: a non-empty package name without `/`, and a path.
fn package_dir(s: &str) -> Result<(String, PathBuf), String> {
    match s.split_once('=') {
        Some((name, path)) if !name.is_empty() && !name.contains('/') && !path.is_empty() => {
            Ok((name.to_string(), PathBuf::from(path)))
        }
        _ => Err("expected NAME=PATH (a package name without '/', then its directory)".into()),
    }
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

/// How many significant digits numbers printed for people get (`--precision`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// This many significant digits, 1 to 17.
    Digits(u8),
    /// 17 significant digits: every f64 reads back exactly.
    Full,
}

impl Precision {
    /// `x` in scientific notation with the precision's significant digits.
    pub fn format(self, x: f64) -> String {
        let digits = match self {
            Precision::Digits(d) => usize::from(d),
            Precision::Full => 17,
        };
        // Sign, one digit, point, the other digits, and an exponent of up to `e-308`.
        format!("{x:>width$.prec$e}", width = digits + 7, prec = digits - 1)
    }
}

/// `--precision`: `full` or a number of significant digits from 1 to 17 (a usage error
/// otherwise, exit status 2).
pub fn precision(s: &str) -> Result<Precision, String> {
    if s == "full" {
        return Ok(Precision::Full);
    }
    match s.parse::<u8>() {
        Ok(d) if (1..=17).contains(&d) => Ok(Precision::Digits(d)),
        _ => Err("expected `full` or a number of significant digits from 1 to 17".to_string()),
    }
}
