//! `ppoe table`: the Rust (or C) source of a robot table generated from a URDF.

use crate::args::ChainArgs;
use crate::{load, noise, output};
use clap::{Args, ValueEnum};
use ppoe_build::noise::NoiseModel;
use std::path::PathBuf;

/// The arguments of `ppoe table`.
#[derive(Args, Debug)]
pub struct TableArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// Which tables to emit: NAME (f64), NAME_F32 (f32) or both.
    #[arg(long, value_enum, default_value_t = TableScalar::F64)]
    scalar: TableScalar,
    /// The const's name (default: the URDF file's stem in upper case).
    #[arg(long)]
    name: Option<String>,
    /// Also emit NAME_NOISE (and NAME_SIGMA2 for the joint model) from a noise model
    /// written by `ppoe fit`. If the fit estimated a calibration, the table is the
    /// calibrated chain's (offsets and corrections folded into the screw axes and the home
    /// pose; its header names the noise file and its sha256), in Rust and in C (a C table
    /// takes only the calibration: the C API takes the covariances as arguments).
    #[arg(long, value_name = "FILE")]
    noise: Option<PathBuf>,
    /// Use a noise model whose fit was rejected by its goodness-of-fit test
    /// (goodness_of_fit.fits false) anyway; without it, such a model is an error.
    #[arg(long, requires = "noise")]
    allow_rejected_noise: bool,
    /// Emit NAME_NOISE and NAME_SIGMA2 from a datasheet instead: one σ per moving joint,
    /// base to tip, comma-separated (radians or metres; σ, not σ²): NAME_NOISE[i] =
    /// σᵢ²·SᵢSᵢᵀ. Not with --noise; Rust tables only.
    #[arg(
        long,
        value_name = "S1,S2,...",
        value_delimiter = ',',
        allow_negative_numbers = true,
        conflicts_with = "noise"
    )]
    joint_sigma: Option<Vec<f64>>,
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

/// `ppoe table`: the generated source on standard output.
pub fn run(a: &TableArgs) -> anyhow::Result<()> {
    load::check_one_stdin(&[
        load::urdf_input(&a.chain.urdf),
        load::noise_input(a.noise.as_deref()),
    ])?;
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
    let model = match (&a.noise, &a.joint_sigma) {
        (Some(p), _) => Some(noise::read(p, a.allow_rejected_noise)?),
        (None, Some(sigmas)) => Some((
            NoiseModel::from_sigmas(&robot.chain, sigmas)
                .map_err(|e| anyhow::anyhow!("--joint-sigma: {e}"))?,
            PathBuf::from("--joint-sigma"),
        )),
        (None, None) => None,
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
