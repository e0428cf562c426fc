//! The one error type of `ppoe-build`: a kind to match on, a message naming the element, the
//! attribute and the problem, and the position in the URDF file where there is one.

use std::fmt;
use std::path::PathBuf;

/// What went wrong. Match on this (through [`Error::kind`]); the message says the rest.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The file is not well-formed XML (or not UTF-8). The error has a position.
    Xml,
    /// The root element is not `<robot>`.
    NotARobot,
    /// A required attribute or element is missing or empty (a link or joint `name`, a joint
    /// `type`, `<parent link>`/`<child link>`, the robot's `name`).
    MissingAttribute,
    /// A number could not be parsed, or a vector attribute does not hold exactly three.
    InvalidNumber,
    /// NaN or ±∞ where a finite number is needed (origins, axes; NaN in limits), or a
    /// product of transforms that overflowed (finite but huge origins whose screw axis or
    /// home pose is no longer finite).
    NonFinite,
    /// A link named by a joint, or the base or tip link, does not exist.
    UnknownLink,
    /// A joint named in the joint list does not exist.
    UnknownJoint,
    /// Two links or two joints have the same name, or a joint is listed twice.
    DuplicateName,
    /// A link is the child of more than one joint.
    MultipleParents,
    /// The parent relation has a cycle (including a joint whose parent is its child).
    Cycle,
    /// The tip link is not below the base link in the tree (or is the base itself).
    TipNotBelowBase,
    /// A fixed joint was listed as a moving joint, or the path from base to tip has no
    /// moving joint at all.
    NotMovable,
    /// A joint type this crate cannot turn into a screw axis: `planar` or `floating` on the
    /// path from base to tip, or a type string that URDF does not define (anywhere).
    UnsupportedJointType,
    /// A moving joint of the chain has the axis (0, 0, 0).
    ZeroAxis,
    /// A moving joint of the chain has limits that admit no finite position: `lower >
    /// upper`, `lower = +∞` or `upper = −∞`. Checked, like [`ErrorKind::ZeroAxis`], only for
    /// the chain's own moving joints (other joints keep their limits as written).
    InvalidLimits,
    /// A mimic joint of the chain cannot be coupled: its master does not move (fixed,
    /// planar, floating), the mimic joints form a cycle, or their composed coupling is not
    /// finite. (A master that does not exist is [`ErrorKind::UnknownJoint`].)
    Mimic,
    /// A listed joint exists but is not on the path from base to tip, or the list is not in
    /// path order.
    NotOnPath,
    /// Reading the URDF or writing the generated file failed.
    Io,
    /// A JSON file (a noise model) is not strict JSON ([`crate::json::parse`]): a syntax
    /// error, a duplicate key, nesting too deep. The error has a position.
    Json,
    /// The builder was misused: no base/tip given, `OUT_DIR` unset, an invalid const name.
    Config,
}

impl ErrorKind {
    /// The variant's name, e.g. `"ZeroAxis"` (what `test_data/urdf/malformed/expected.json`
    /// uses).
    pub fn name(self) -> &'static str {
        match self {
            ErrorKind::Xml => "Xml",
            ErrorKind::NotARobot => "NotARobot",
            ErrorKind::MissingAttribute => "MissingAttribute",
            ErrorKind::InvalidNumber => "InvalidNumber",
            ErrorKind::NonFinite => "NonFinite",
            ErrorKind::UnknownLink => "UnknownLink",
            ErrorKind::UnknownJoint => "UnknownJoint",
            ErrorKind::DuplicateName => "DuplicateName",
            ErrorKind::MultipleParents => "MultipleParents",
            ErrorKind::Cycle => "Cycle",
            ErrorKind::TipNotBelowBase => "TipNotBelowBase",
            ErrorKind::NotMovable => "NotMovable",
            ErrorKind::UnsupportedJointType => "UnsupportedJointType",
            ErrorKind::ZeroAxis => "ZeroAxis",
            ErrorKind::InvalidLimits => "InvalidLimits",
            ErrorKind::Mimic => "Mimic",
            ErrorKind::NotOnPath => "NotOnPath",
            ErrorKind::Io => "Io",
            ErrorKind::Json => "Json",
            ErrorKind::Config => "Config",
        }
    }
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A position in the URDF (or JSON) text: 1-based line and column (in characters).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Position {
    /// Line, starting at 1.
    pub line: u32,
    /// Column, starting at 1.
    pub column: u32,
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// An error of `ppoe-build`. Displayed as `file:line:column: message` (the parts that are
/// known).
#[derive(Clone, Debug, PartialEq)]
pub struct Error {
    kind: ErrorKind,
    message: String,
    position: Option<Position>,
    file: Option<PathBuf>,
}

/// `Result<T, ppoe_build::Error>`.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// An error of `kind` with `message` and no position.
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Self {
            kind,
            message: message.into(),
            position: None,
            file: None,
        }
    }

    pub(crate) fn at(mut self, position: Option<Position>) -> Self {
        self.position = position;
        self
    }

    pub(crate) fn in_file(mut self, file: impl Into<PathBuf>) -> Self {
        if self.file.is_none() {
            self.file = Some(file.into());
        }
        self
    }

    /// What went wrong.
    pub fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// The message (without file and position).
    pub fn message(&self) -> &str {
        &self.message
    }

    /// Line and column in the URDF text, where known.
    pub fn position(&self) -> Option<Position> {
        self.position
    }

    /// The URDF file, where known (errors of [`crate::Config`]).
    pub fn file(&self) -> Option<&std::path::Path> {
        self.file.as_deref()
    }
}

/// The hint added to the errors of a URDF input that looks like xacro, or `None`. Xacro
/// files are macro sources that `xacro` expands into a URDF; read as URDF they fail (or
/// lack the links the macros would make), so the error says how to expand them first.
/// `name` is the input's path or name as shown in messages; it looks like xacro when it
/// ends in `.xacro`, or when the text declares `xmlns:xacro` or has an `<xacro:` element.
pub fn xacro_hint(name: &str, text: &[u8]) -> Option<String> {
    let contains = |needle: &[u8]| text.windows(needle.len()).any(|w| w == needle);
    let by_name = name.to_ascii_lowercase().ends_with(".xacro");
    if !(by_name || contains(b"xmlns:xacro") || contains(b"<xacro:")) {
        return None;
    }
    Some(format!(
        "the file looks like xacro, not URDF: expand it first (run: xacro {} > {})",
        if by_name { name } else { "robot.urdf.xacro" },
        if by_name {
            // The last six bytes are the ASCII `.xacro`: a character boundary.
            name.get(..name.len() - ".xacro".len()).unwrap_or(name)
        } else {
            "robot.urdf"
        }
    ))
}

impl Error {
    /// This error with [`xacro_hint`]'s hint appended to its message when the input
    /// `name` holding `text` looks like xacro; otherwise unchanged.
    pub fn with_xacro_hint(mut self, name: &str, text: &[u8]) -> Self {
        if let Some(hint) = xacro_hint(name, text) {
            self.message = format!("{}; {hint}", self.message);
        }
        self
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.file, self.position) {
            (Some(file), Some(p)) => write!(f, "{}:{}: ", file.display(), p)?,
            (Some(file), None) => write!(f, "{}: ", file.display())?,
            (None, Some(p)) => write!(f, "{}: ", p)?,
            (None, None) => {}
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for Error {}
