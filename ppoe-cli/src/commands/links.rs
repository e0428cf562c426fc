//! `ppoe links`: the links and joints of a URDF as a tree.

use crate::{links, load, output};
use clap::Args;
use std::path::PathBuf;

/// The arguments of `ppoe links`.
#[derive(Args, Debug)]
pub struct LinksArgs {
    /// The URDF file (`-`: standard input).
    #[arg(long, value_name = "FILE")]
    urdf: PathBuf,
}

/// `ppoe links`: the tree on standard output.
pub fn run(a: &LinksArgs) -> anyhow::Result<()> {
    let (_, urdf) = load::urdf(&a.urdf)?;
    output::print(links::tree(&urdf).as_bytes())
}
