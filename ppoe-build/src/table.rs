//! The one table pipeline: a chain and the URDF bytes it came from → the source of a
//! table, in Rust or C, with the noise model appended. [`Config`](crate::Config), the `ppoe
//! table` command and any other front end call [`Table::generate`], so the const name, the
//! source hash, the language and the noise items are assembled in this one place.

use crate::chain::RobotChain;
use crate::codegen::{self, Scalar, Source};
use crate::error::{Error, ErrorKind, Result};
use crate::literal::{c_comment_text, comment_text, CommentText};
use crate::noise::{self, NoiseModel};
use std::path::Path;

/// The language of a generated table.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Lang {
    /// `pub const` items of the `ppoe` crate ([`codegen::generate`]), the default.
    #[default]
    Rust,
    /// A C99 header of `static const` data for ppoe-ffi's C API
    /// ([`crate::codegen_c::generate`]).
    C,
}

/// A noise model to bake into a table, and the file it was read from.
#[derive(Clone, Copy, Debug)]
pub struct Noise<'a> {
    /// The model ([`NoiseModel::read`] or [`NoiseModel::parse`]).
    pub model: &'a NoiseModel,
    /// Its file: names it in errors, and its file name (no directory) goes into the items'
    /// doc comment.
    pub path: &'a Path,
}

/// One table to generate.
#[derive(Clone, Copy, Debug)]
pub struct Table<'a> {
    /// The chain ([`Urdf::chain`](crate::Urdf::chain) of the URDF in `urdf`).
    pub chain: &'a RobotChain,
    /// The URDF's bytes: their SHA-256 goes into the doc comment.
    pub urdf: &'a [u8],
    /// The URDF's file name (no directory, so the output does not depend on where the
    /// workspace lives), for the doc comment.
    pub file_name: &'a str,
    /// The const's name ([`const_name`] maps a file stem to the default one).
    pub name: &'a str,
    /// Which scalar types to emit.
    pub scalar: Scalar,
    /// Rust or C.
    pub lang: Lang,
    /// The noise model to append as `NAME_NOISE` (and `NAME_SIGMA2`), Rust only; its
    /// calibration, if it has one, makes the table (Rust or C) the calibrated chain's.
    pub noise: Option<Noise<'a>>,
}

/// The const name: `name` if given, else `stem` in upper case with every character that
/// cannot be in a Rust identifier replaced ([`codegen::const_name_from`]).
pub fn const_name(name: Option<&str>, stem: &str) -> String {
    name.map_or_else(|| codegen::const_name_from(stem), str::to_string)
}

impl Table<'_> {
    /// The table's source: the chain's items, then the noise model's.
    ///
    /// With a noise model that carries a calibration ([`NoiseModel::is_calibrated`]) the
    /// table is that of the calibrated chain ([`NoiseModel::calibrated_chain`]: screws and
    /// home pose folded), in Rust and in C, and its header comment says so, naming the
    /// noise file and its SHA-256. A model without one leaves the chain's table as it is,
    /// byte for byte.
    ///
    /// # Errors
    /// Those of [`codegen::generate`] or [`crate::codegen_c::generate`]; a noise model for
    /// another chain ([`NoiseModel::check_against`]) or whose calibration cannot be folded,
    /// naming its file; with [`Lang::C`], a noise model without a calibration
    /// ([`ErrorKind::Config`]: the C API takes the covariances as arguments, so nothing of
    /// it would go in).
    pub fn generate(&self) -> Result<String> {
        let source = Source {
            file_name: self.file_name.to_string(),
            sha256: codegen::sha256_hex(self.urdf),
        };
        let calibrated = match self.noise {
            Some(n) if n.model.is_calibrated() => Some(
                n.model
                    .calibrated_chain(self.chain)
                    .map_err(|e| e.in_file(n.path))?,
            ),
            _ => None,
        };
        if let (Some(n), None, Lang::C) = (self.noise, &calibrated, self.lang) {
            return Err(Error::new(
                ErrorKind::Config,
                "a noise model cannot be baked into a C table yet: the C API takes the \
                 covariances as arguments (only a calibration would go in, and this model has \
                 none)",
            )
            .in_file(n.path));
        }
        let chain = calibrated.as_ref().unwrap_or(self.chain);
        let mut src = match self.lang {
            Lang::Rust => codegen::generate(chain, self.name, self.scalar, &source),
            Lang::C => crate::codegen_c::generate(chain, self.name, self.scalar, &source),
        }?;
        let Some(n) = self.noise else {
            return Ok(src);
        };
        let file = n.path.file_name().map(|s| s.to_string_lossy().into_owned());
        let file = file.unwrap_or_default();
        if calibrated.is_some() {
            src = with_calibration_note(&src, self.lang, n.model, &file);
        }
        if self.lang == Lang::Rust {
            n.model
                .check_against(self.chain)
                .map_err(|e| e.in_file(n.path))?;
            // Joints given by sigma2 alone take the screw axes of the chain the table holds.
            let mut model = n.model.clone();
            model.resolve(chain).map_err(|e| e.in_file(n.path))?;
            src += &noise::generate(&model, self.name, self.scalar, &file);
        }
        Ok(src)
    }
}

/// `src` with a line after its first (the generated header's) saying that the table is the
/// calibrated chain of noise file `file`: a `//` line in Rust, a ` * ` line of the header's
/// block comment in C. The file name and the model's strings go through the comment
/// escaping of each language, so they cannot end the comment.
fn with_calibration_note(src: &str, lang: Lang, model: &NoiseModel, file: &str) -> String {
    let (lead, esc): (&str, fn(&str) -> CommentText) = match lang {
        Lang::Rust => ("//", comment_text),
        Lang::C => (" *", c_comment_text),
    };
    let estimated: Vec<String> = model
        .calibration
        .estimated
        .iter()
        .map(|e| esc(e).to_string())
        .collect();
    let estimated = if estimated.is_empty() {
        String::new()
    } else {
        format!(" (estimated: {})", estimated.join(", "))
    };
    let note = format!(
        "{lead} Calibrated: the screw axes and home pose have the calibration{estimated} of \
         the noise file\n{lead} `{}`, sha256 {}, folded in (what its covariances belong to).\n",
        esc(file),
        esc(&model.sha256)
    );
    let split = src.find('\n').map_or(src.len(), |i| i + 1);
    format!("{}{note}{}", &src[..split], &src[split..])
}
