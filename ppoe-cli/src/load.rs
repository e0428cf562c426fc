//! Reading the command's inputs, each exactly once: the URDF, the JSON cases and the noise
//! model, from a path, `-` for standard input (one input at most), or a pipe (`--urdf
//! <(xacro robot.urdf.xacro)`), which can be read only once.

use crate::args::ChainArgs;
use crate::names::{self, shown};
use crate::output::io_sentence;
use anyhow::bail;
use ppoe_build::{RobotChain, Urdf};
use std::io::Read;
use std::path::Path;

/// The bytes of one input and the name messages give it.
pub struct Input {
    /// Everything the input held.
    pub bytes: Vec<u8>,
    /// The path as given, or "standard input".
    pub name: String,
    /// The file name (no directory) for generated sources; "stdin" for standard input,
    /// "pipe" for a pipe or another file that is not a regular file.
    pub file_name: String,
    /// `true` for a regular file (its name can name a table; a pipe's `63` cannot).
    pub regular: bool,
}

/// `true` if `path` means standard input.
pub fn is_stdin(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// Reads `path` (`-`: standard input) whole; `what` names the input in errors.
///
/// # Errors
/// A sentence naming the input and the reason.
pub fn read(path: &Path, what: &str) -> anyhow::Result<Input> {
    if is_stdin(path) {
        let mut bytes = Vec::new();
        std::io::stdin()
            .lock()
            .read_to_end(&mut bytes)
            .map_err(|e| {
                anyhow::anyhow!(
                    "cannot read the {what} from standard input: {}",
                    io_sentence(&e)
                )
            })?;
        return Ok(Input {
            bytes,
            name: "standard input".to_string(),
            file_name: "stdin".to_string(),
            regular: false,
        });
    }
    if path.is_dir() {
        bail!(
            "cannot read the {what} {}: it is a directory",
            path.display()
        );
    }
    let bytes = std::fs::read(path).map_err(|e| {
        anyhow::anyhow!(
            "cannot read the {what} {}: {}",
            path.display(),
            io_sentence(&e)
        )
    })?;
    let regular = std::fs::metadata(path).is_ok_and(|m| m.is_file());
    Ok(Input {
        bytes,
        name: path.display().to_string(),
        file_name: match path.file_name() {
            Some(s) if regular => s.to_string_lossy().into_owned(),
            _ => "pipe".to_string(),
        },
        regular,
    })
}

/// One input of a command line that may come from standard input, for
/// [`check_one_stdin`].
pub struct StdinUse {
    /// What messages call it ("the URDF").
    what: &'static str,
    /// Its flag ("--urdf").
    flag: &'static str,
    /// Whether it reads standard input.
    stdin: bool,
}

/// `--urdf FILE`.
pub fn urdf_input(path: &Path) -> StdinUse {
    StdinUse {
        what: "the URDF",
        flag: "--urdf",
        stdin: is_stdin(path),
    }
}

/// `--input FILE` of the cases (`None`: standard input).
pub fn cases_input(path: Option<&Path>) -> StdinUse {
    StdinUse {
        what: "the input cases",
        flag: "--input",
        stdin: path.is_none_or(is_stdin),
    }
}

/// `--noise FILE` (`None`: no noise model).
pub fn noise_input(path: Option<&Path>) -> StdinUse {
    StdinUse {
        what: "the noise model",
        flag: "--noise",
        stdin: path.is_some_and(is_stdin),
    }
}

/// Refuses two inputs from standard input (`--urdf -` with the cases on standard input),
/// before anything is read: standard input can be read only once.
///
/// # Errors
/// When two of `inputs` read standard input, naming both.
pub fn check_one_stdin(inputs: &[StdinUse]) -> anyhow::Result<()> {
    let on_stdin: Vec<&StdinUse> = inputs.iter().filter(|i| i.stdin).collect();
    if let [a, b, ..] = on_stdin[..] {
        bail!(
            "{} and {} cannot both come from standard input: give one of them as a file \
             ({} FILE or {} FILE)",
            a.what,
            b.what,
            a.flag,
            b.flag
        );
    }
    Ok(())
}

/// A URDF and the chain the command line selects from it.
pub struct Robot {
    /// The URDF's bytes and name.
    pub source: Input,
    /// The parsed URDF.
    pub urdf: Urdf,
    /// The chain from `--base` to `--tip`.
    pub chain: RobotChain,
}

/// A `ppoe-build` error prefixed with the input's name (`file:line:column: message`).
pub fn in_input(name: &str, e: &ppoe_build::Error) -> anyhow::Error {
    if e.position().is_some() {
        anyhow::anyhow!("{name}:{e}")
    } else {
        anyhow::anyhow!("{name}: {e}")
    }
}

/// Reads and parses the URDF once.
///
/// # Errors
/// Unreadable or malformed input, naming it (and the line and column).
pub fn urdf(path: &Path) -> anyhow::Result<(Input, Urdf)> {
    let source = read(path, "URDF file")?;
    let urdf = Urdf::parse_bytes(&source.bytes).map_err(|e| in_input(&source.name, &e));
    let urdf = urdf.map_err(|e| xacro_hinted(&source, e))?;
    Ok((source, urdf))
}

/// `e` with ppoe-build's hint to run xacro first, when the URDF input looks like xacro.
fn xacro_hinted(source: &Input, e: anyhow::Error) -> anyhow::Error {
    match ppoe_build::error::xacro_hint(&source.name, &source.bytes) {
        Some(hint) => anyhow::anyhow!("{e}; {hint}"),
        None => e,
    }
}

/// Reads the URDF once and extracts the chain; unknown link and joint names are reported
/// with the nearest names of the file.
///
/// # Errors
/// As [`urdf`], and every chain error of `ppoe-build` (named links not connected, no
/// moving joint, ...), naming the file.
pub fn robot(args: &ChainArgs) -> anyhow::Result<Robot> {
    let (source, urdf) = urdf(&args.urdf)?;
    // A xacro file that parses as XML still lacks the links its macros would make.
    match chain_of(&source, &urdf, args) {
        Ok(chain) => Ok(Robot {
            source,
            urdf,
            chain,
        }),
        Err(e) => Err(xacro_hinted(&source, e)),
    }
}

/// The chain `args` names in the parsed URDF, with the nearest names for unknown ones.
fn chain_of(source: &Input, urdf: &Urdf, args: &ChainArgs) -> anyhow::Result<RobotChain> {
    for (what, name) in [("base", &args.base), ("tip", &args.tip)] {
        if urdf.link(name).is_none() {
            bail!(
                "{}: {what} link '{}' does not exist in robot '{}'; {}",
                source.name,
                shown(name),
                shown(&urdf.name),
                names::hint(name, urdf.links.iter().map(|l| l.name.as_str()))
            );
        }
    }
    for name in args.joints.iter().flatten() {
        if urdf.joint(name).is_none() {
            let near = names::nearest(name, urdf.joints.iter().map(|j| j.name.as_str()));
            let near: Vec<String> = near.iter().map(|n| format!("'{}'", shown(n))).collect();
            bail!(
                "{}: joint '{}' (listed in --joints) does not exist in robot '{}'{}",
                source.name,
                shown(name),
                shown(&urdf.name),
                if near.is_empty() {
                    String::new()
                } else {
                    format!("; did you mean {}?", near.join(", "))
                }
            );
        }
    }
    urdf.chain(&args.base, &args.tip, args.joints.as_deref())
        .map_err(|e| in_input(&source.name, &e))
}
