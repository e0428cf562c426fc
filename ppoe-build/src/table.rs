//! The one table pipeline: a chain and the URDF bytes it came from → the source of a
//! table, in Rust or C, with the noise model appended. [`Config`](crate::Config), the `ppoe
//! table` command and any other front end call [`Table::generate`], so the const name, the
//! source hash, the language and the noise items are assembled in this one place.

use crate::chain::RobotChain;
use crate::codegen::{self, Scalar, Source};
use crate::error::{Error, ErrorKind, Result};
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
    /// The noise model to append as `NAME_NOISE` (and `NAME_SIGMA2`), Rust only.
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
    /// # Errors
    /// Those of [`codegen::generate`] or [`crate::codegen_c::generate`]; a noise model with
    /// [`Lang::C`] ([`ErrorKind::Config`]: the C API takes the covariances as arguments);
    /// a noise model for another chain ([`NoiseModel::check_against`], naming its file).
    pub fn generate(&self) -> Result<String> {
        let source = Source {
            file_name: self.file_name.to_string(),
            sha256: codegen::sha256_hex(self.urdf),
        };
        let mut src = match self.lang {
            Lang::Rust => codegen::generate(self.chain, self.name, self.scalar, &source),
            Lang::C => crate::codegen_c::generate(self.chain, self.name, self.scalar, &source),
        }?;
        if let Some(n) = self.noise {
            if self.lang == Lang::C {
                return Err(Error::new(
                    ErrorKind::Config,
                    "a noise model cannot be baked into a C table yet: the C API takes the \
                     covariances as arguments",
                )
                .in_file(n.path));
            }
            n.model
                .check_against(self.chain)
                .map_err(|e| e.in_file(n.path))?;
            let file = n.path.file_name().map(|s| s.to_string_lossy().into_owned());
            src += &noise::generate(n.model, self.name, self.scalar, &file.unwrap_or_default());
        }
        Ok(src)
    }
}
