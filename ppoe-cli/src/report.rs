//! How the command ends: help and usage errors from clap, and every other error as one
//! safe line on standard error, with the exit statuses `--help` states.

use std::process::ExitCode;

/// The exit statuses, as `--help` states them.
pub const EXIT_CODES: &str = "Exit status: 0 on success (also when the reader of standard output \
closes it early, as `ppoe eval ... | head` does); 1 when an input is unreadable or wrong, a \
computation fails or a file cannot be written (one line on standard error, `error: ...`); 2 \
for a usage error (unknown subcommand or flag, missing or out-of-range value); 3 when `ppoe \
fit` wrote its result but its goodness-of-fit test rejects the noise model \
(`goodness_of_fit.fits` false; `ppoe table --noise` refuses such a file unless \
--allow-rejected-noise). FILE \
arguments (--urdf, --input, --noise) accept `-` for standard input (one of them at most) \
and pipes such as `<(xacro robot.urdf.xacro)`; each input is read once. Output files are \
written to a temporary file and renamed, so an interrupted run never leaves a partial file \
under the final name; a device or FIFO (`--out /dev/stdout`) is written through, and a \
symbolic link is kept (the file it points to is replaced).";

/// The exit statuses, in short, for each subcommand's `--help`.
pub const EXIT_CODES_SHORT: &str = "Exit status: 0 success; 1 bad input, failed computation or \
write; 2 usage error; 3 (`fit` only) result written, model rejected by the goodness-of-fit \
test. FILE may be `-` (standard input) or a pipe.";

/// Exit status of a fit whose result was written but is rejected (see [`EXIT_CODES`]).
const REJECTED: u8 = 3;

/// The error of a `ppoe fit` whose result was written but is rejected by its
/// goodness-of-fit test: exit status 3, not 1 (the output is valid).
#[derive(Debug)]
pub struct Rejected(pub String);

impl std::fmt::Display for Rejected {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Rejected {}

/// How an error ends the command: a [`Rejected`] fit with status 3 (its message as
/// `fit: ...`), any other error as [`report`].
pub fn error(e: &anyhow::Error) -> ExitCode {
    match e.downcast_ref::<Rejected>() {
        Some(r) => {
            eprintln!("fit: {} (exit status {REJECTED})", one_line(&r.0));
            ExitCode::from(REJECTED)
        }
        None => report(&format!("{e:#}")),
    }
}

/// Exit status of a usage error (clap's convention).
const USAGE_ERROR: u8 = 2;

/// Help and version on standard output (status 0); a bare `ppoe` prints the help on
/// standard error (status 2); any other usage error is one line (status 2).
pub fn usage_error(e: &clap::Error) -> ExitCode {
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
pub fn report(message: &str) -> ExitCode {
    eprintln!("error: {}", one_line(message));
    ExitCode::FAILURE
}
