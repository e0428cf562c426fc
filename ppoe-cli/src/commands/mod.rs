//! One module per subcommand: its clap arguments beside its body. `main` parses the
//! command line and calls the one `run` it names.

pub mod completions;
pub mod demo;
pub mod eval;
pub mod fit;
pub mod links;
pub mod mesh;
pub mod render;
pub mod table;
