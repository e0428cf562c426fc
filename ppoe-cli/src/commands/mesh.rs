//! `ppoe mesh`: the equiprobable surface and the skeleton of each case as a mesh file.

use crate::args::{ChainArgs, NoiseArgs, SurfaceArgs};
use crate::frames::{self, Sink};
use crate::{mesh, picture};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum MeshFormat {
    Obj,
    Ply,
}

/// The arguments of `ppoe mesh`.
#[derive(Args, Debug)]
pub struct MeshArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The input JSON file (the input of `ppoe eval`; default or `-`: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    #[command(flatten)]
    noise: NoiseArgs,
    /// One file per case: ppoe-mesh-<i>.obj or ppoe-mesh-<i>.ply.
    #[arg(long, value_enum, default_value_t = MeshFormat::Obj)]
    format: MeshFormat,
    /// The output directory.
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    #[command(flatten)]
    surface: SurfaceArgs,
}

/// `ppoe mesh`: one mesh file per case.
pub fn run(a: &MeshArgs) -> anyhow::Result<()> {
    let fmt = a.format;
    let name = move |i: usize| match fmt {
        MeshFormat::Obj => format!("ppoe-mesh-{i}.obj"),
        MeshFormat::Ply => format!("ppoe-mesh-{i}.ply"),
    };
    let write = move |p: &Path, f: &picture::Frame| match fmt {
        MeshFormat::Obj => mesh::write_obj(p, f),
        MeshFormat::Ply => mesh::write_ply(p, f),
    };
    let sink = Sink::Each {
        dir: &a.out,
        name: &name,
        write: &write,
    };
    frames::run(
        &a.chain,
        a.input.as_deref(),
        &a.noise,
        &a.surface,
        &sink,
        crate::exaggerate::Exaggeration::Factor(1.0),
    )
}
