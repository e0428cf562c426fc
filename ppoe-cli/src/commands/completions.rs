//! `ppoe completions`: a shell completion script.

use crate::output;
use clap::Args;

/// The arguments of `ppoe completions`.
#[derive(Args, Debug)]
pub struct CompletionsArgs {
    /// The shell.
    #[arg(value_enum)]
    shell: clap_complete::Shell,
}

/// `ppoe completions`: the script for `command` (the whole command line's schema, which
/// `main` owns) on standard output.
pub fn run(a: &CompletionsArgs, command: &mut clap::Command) -> anyhow::Result<()> {
    let mut text = Vec::new();
    clap_complete::generate(a.shell, command, "ppoe", &mut text);
    output::print(&text)
}
