//! The noise model fitted by `ppoe fit`, read back and baked into a table: the per-joint
//! covariances as a `const` next to the chain, so firmware calls the PPOE with the table's
//! own noise model.
//!
//! The file is the JSON `ppoe fit` writes: `{"model": "joint"|"full", "joints": [{"name":
//! ..., "cov": 6×6 row-major, "sigma2": ..., "offset": δ, "axis_correction": [6]}, ...],
//! "calibration": {"estimated": [...], "home_correction": [6], ...}, "goodness_of_fit":
//! {"fits": bool, ...}, ...}`; other fields are ignored here. Every joint's `cov` must be
//! finite, symmetric and positive semi-definite, and the joints must be the chain's, by
//! name and in order.
//!
//! **From a datasheet.** A joint may give `"sigma2"` (its joint-value variance σ², rad²
//! or m²) and no `"cov"`: its covariance is then `σ²·SᵢSᵢᵀ`
//! ([`ppoe::chain::screw_noise`]), Sᵢ the joint's screw axis in the base frame of the
//! chain the model is used with (the calibrated one if the model has a calibration),
//! filled in by [`NoiseModel::resolve`] once the chain is known. When a joint gives both,
//! **`cov` wins** and `sigma2` is kept only for `NAME_SIGMA2` (that is what `ppoe fit`
//! writes: the two agree there). [`NoiseModel::from_sigmas`] builds such a model from
//! one σ per joint (`--joint-sigma`, [`crate::Config::joint_sigmas`]).
//!
//! The calibration fields are optional (hand-written and older files have none) and read
//! strictly ([`Calibration`]): a fit that estimated a calibration wrote covariances of the
//! *calibrated* chain, so [`NoiseModel::calibrated_chain`] folds it into the chain and a
//! table with such a model is the calibrated chain's ([`crate::Table::generate`]: its
//! header says so and names the file and its [`NoiseModel::sha256`]). A model without a
//! calibration (or with every value zero) changes nothing, byte for byte.
//!
//! `goodness_of_fit.fits` false means the fit was rejected by its goodness-of-fit test:
//! [`NoiseModel::check_accepted`] refuses it unless forced (`Config::allow_rejected_noise`,
//! `--allow-rejected-noise`); a file without `goodness_of_fit` is accepted.
//!
//! For a table `NAME` the generated items are `NAME_NOISE: [ppoe::Mat6<T>; N]` (what
//! `Chain::ppoe` takes as `covs`) and, for the joint model, `NAME_SIGMA2: [T; N]` (the
//! joint-value variances `Chain::ppoe_rank1` takes); with `_F32` suffixes for f32 tables.

pub use crate::calibration::Calibration;
use crate::chain::RobotChain;
use crate::codegen::Scalar;
use crate::error::{Error, ErrorKind, Result};
use crate::literal::comment_text;
use std::fmt::Write as _;
use std::path::Path;

/// One joint's noise in a fitted model.
#[derive(Clone, Debug, PartialEq)]
pub struct NoiseJoint {
    /// The joint's name.
    pub name: String,
    /// Its covariance: base-frame screw coordinates, rotation first, row-major.
    pub cov: [[f64; 6]; 6],
    /// The joint-value variance (joint model only).
    pub sigma2: Option<f64>,
}

/// A noise model as `ppoe fit` writes it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NoiseModel {
    /// `"joint"` or `"full"`.
    pub model: String,
    /// Per joint, base to tip.
    pub joints: Vec<NoiseJoint>,
    /// The calibration the fit estimated with the noise (all zeros if none): the
    /// covariances belong to the chain it calibrates ([`NoiseModel::calibrated_chain`]).
    pub calibration: Calibration,
    /// `goodness_of_fit.fits`: `Some(false)` if the fit was rejected by its
    /// goodness-of-fit test ([`NoiseModel::check_accepted`]); `None` for a file without it
    /// (hand-written).
    pub fits: Option<bool>,
    /// The lowercase hex SHA-256 of the file's text ([`NoiseModel::parse`]'s argument), so
    /// a table can name the exact file it was calibrated with.
    pub sha256: String,
    /// The joints (indices) that gave `sigma2` and no `cov`: their `cov` is zero until
    /// [`NoiseModel::resolve`] computes it from the chain's screw axes.
    pub from_sigma2: Vec<usize>,
}

fn config(msg: String) -> Error {
    Error::new(ErrorKind::Config, msg)
}

fn matrix6(v: &serde_json::Value, what: &str) -> Result<[[f64; 6]; 6]> {
    let bad = || config(format!("{what}: expected 6 rows of 6 finite numbers"));
    let rows = v.as_array().filter(|r| r.len() == 6).ok_or_else(bad)?;
    let mut m = [[0.0; 6]; 6];
    for (out, row) in m.iter_mut().zip(rows) {
        let row = row.as_array().filter(|r| r.len() == 6).ok_or_else(bad)?;
        for (o, x) in out.iter_mut().zip(row) {
            *o = x.as_f64().filter(|x| x.is_finite()).ok_or_else(bad)?;
        }
    }
    Ok(m)
}

impl NoiseModel {
    /// Parses the JSON text of a fit result (strict JSON, [`crate::json::parse`]: one
    /// leading BOM skipped, duplicate keys refused) and checks every covariance.
    ///
    /// # Errors
    /// [`ErrorKind::Json`] with a position for text that is not strict JSON;
    /// [`ErrorKind::Config`] naming the joint for a missing field or a covariance that is
    /// not finite, symmetric and PSD within tolerance.
    pub fn parse(text: &str) -> Result<Self> {
        let v = crate::json::parse(text).map_err(|e| {
            let message = format!("noise model: {}", e.message());
            Error::new(e.kind(), message).at(e.position())
        })?;
        let model = v["model"].as_str().unwrap_or("full").to_string();
        let list = v["joints"]
            .as_array()
            .ok_or_else(|| config("noise model: no \"joints\" array".into()))?;
        let mut joints = Vec::with_capacity(list.len());
        let mut from_sigma2 = Vec::new();
        for (i, j) in list.iter().enumerate() {
            let name = j["name"]
                .as_str()
                .ok_or_else(|| config(format!("noise model: joint {i} has no \"name\"")))?;
            let joint = if j.get("cov").is_none() {
                from_sigma2.push(i);
                sigma2_joint(i, name, &j["sigma2"])?
            } else {
                let what = format!("noise model: joint {i} ('{name}') cov");
                let cov = matrix6(&j["cov"], &what)?;
                ppoe::uncertainty::check_covariance(&ppoe::Mat6::from(cov))
                    .map_err(|e| config(format!("{what}: {e}")))?;
                NoiseJoint {
                    name: name.to_string(),
                    cov,
                    sigma2: j["sigma2"].as_f64().filter(|s| s.is_finite() && *s >= 0.0),
                }
            };
            joints.push(joint);
        }
        let names: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
        let calibration = Calibration::parse(&v, list, &names)?;
        Ok(Self {
            model,
            joints,
            calibration,
            fits: fits(&v)?,
            sha256: crate::codegen::sha256_hex(text.as_bytes()),
            from_sigma2,
        })
    }

    /// The joint model of a datasheet: joint i's covariance is `σᵢ²·SᵢSᵢᵀ` (Sᵢ its screw
    /// axis in `chain`'s base frame), one σ per joint of `chain`, base to tip (radians for
    /// revolute and continuous joints, metres for prismatic ones; σ, not σ²). `model` is
    /// `"joint"`, so a table also gets `NAME_SIGMA2`; there is no calibration.
    ///
    /// # Errors
    /// [`ErrorKind::Config`] for another number of σ than the chain has joints (naming
    /// them), or a σ that is negative or not finite (naming its joint).
    pub fn from_sigmas(chain: &RobotChain, sigmas: &[f64]) -> Result<Self> {
        let names = chain.joint_names();
        if sigmas.len() != names.len() {
            return Err(config(format!(
                "{} joint sigmas given, the chain from '{}' to '{}' has {} moving joints ({})",
                sigmas.len(),
                chain.base,
                chain.tip,
                names.len(),
                names.join(", ")
            )));
        }
        let mut joints = Vec::with_capacity(sigmas.len());
        for (i, (&sigma, joint)) in sigmas.iter().zip(&chain.joints).enumerate() {
            if !(sigma.is_finite() && sigma >= 0.0) {
                return Err(config(format!(
                    "joint sigma {i} ('{}') is {sigma}: expected a finite σ ≥ 0 (radians or metres)",
                    joint.name
                )));
            }
            let sigma2 = sigma * sigma;
            joints.push(NoiseJoint {
                name: joint.name.clone(),
                cov: screw_cov(&joint.screw, sigma2),
                sigma2: Some(sigma2),
            });
        }
        Ok(Self {
            model: "joint".into(),
            joints,
            ..Self::default()
        })
    }

    /// Fills in the covariances of the joints that gave only `sigma2`
    /// ([`NoiseModel::from_sigma2`]) from `chain`'s screw axes: `σ²·SᵢSᵢᵀ`. `chain` is the
    /// one the covariances belong to ([`NoiseModel::calibrated_chain`]). Joints that gave a
    /// `cov` are not touched; a second call changes nothing.
    ///
    /// # Errors
    /// As [`NoiseModel::check_against`]; [`ErrorKind::NonFinite`] naming the joint if
    /// `σ²·SᵢSᵢᵀ` overflows.
    pub fn resolve(&mut self, chain: &RobotChain) -> Result<()> {
        self.check_against(chain)?;
        for &i in &self.from_sigma2 {
            let j = &mut self.joints[i];
            let cov = screw_cov(&chain.joints[i].screw, j.sigma2.unwrap_or(0.0));
            // A huge σ² on a screw far from the origin overflows: an error, not a table of inf.
            if cov.iter().flatten().any(|x| !x.is_finite()) {
                return Err(Error::new(
                    ErrorKind::NonFinite,
                    format!(
                        "noise model: joint {i} ('{}'): σ²·SSᵀ is not finite (sigma2 {})",
                        j.name,
                        j.sigma2.unwrap_or(0.0)
                    ),
                ));
            }
            j.cov = cov;
        }
        self.from_sigma2.clear();
        Ok(())
    }

    /// Reads and parses a fit result file.
    ///
    /// # Errors
    /// [`ErrorKind::Io`] if the file cannot be read, else as [`NoiseModel::parse`].
    pub fn read(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| {
            Error::new(ErrorKind::Io, format!("cannot read the noise model: {e}")).in_file(path)
        })?;
        Self::parse(&text).map_err(|e| e.in_file(path))
    }

    /// Checks that the model's joints are the chain's (same names, same order).
    ///
    /// # Errors
    /// [`ErrorKind::Config`] naming the first mismatch.
    pub fn check_against(&self, chain: &RobotChain) -> Result<()> {
        let names: Vec<&str> = chain.joint_names();
        let mine: Vec<&str> = self.joints.iter().map(|j| j.name.as_str()).collect();
        if names != mine {
            return Err(config(format!(
                "the noise model's joints [{}] are not the chain's [{}]",
                mine.join(", "),
                names.join(", ")
            )));
        }
        Ok(())
    }

    /// `true` if the model carries a calibration that changes the chain (not all zero).
    pub fn is_calibrated(&self) -> bool {
        !self.calibration.is_identity()
    }

    /// The chain the model's covariances belong to: `chain` checked against the model
    /// ([`NoiseModel::check_against`]) with the calibration folded in
    /// ([`Calibration::apply`]); `chain` itself, bit for bit, if there is no calibration.
    ///
    /// # Errors
    /// As [`NoiseModel::check_against`] and [`Calibration::apply`].
    pub fn calibrated_chain(&self, chain: &RobotChain) -> Result<RobotChain> {
        self.check_against(chain)?;
        self.calibration.apply(chain)
    }

    /// Refuses a model whose fit was rejected by its goodness-of-fit test
    /// (`goodness_of_fit.fits` false) unless `allow`; `file` names the model and `force`
    /// says how to use it anyway (`"pass --allow-rejected-noise"`,
    /// `"call Config::allow_rejected_noise(true)"`).
    ///
    /// # Errors
    /// [`ErrorKind::Config`] for a rejected fit that is not allowed.
    pub fn check_accepted(&self, allow: bool, file: &str, force: &str) -> Result<()> {
        if allow || self.fits != Some(false) {
            return Ok(());
        }
        Err(config(format!(
            "the fit in {file} was rejected by its goodness-of-fit test (goodness_of_fit.fits \
             is false: its noise model does not explain the residuals, often because the \
             kinematics are off); re-fit with `ppoe fit --estimate ...` (calibration), or \
             {force} to use it anyway"
        )))
    }

    /// The per-joint covariances as core matrices.
    pub fn covs(&self) -> Vec<ppoe::Mat6<f64>> {
        self.joints
            .iter()
            .map(|j| ppoe::Mat6::from(j.cov))
            .collect()
    }
}

/// `σ²·S·Sᵀ`: the core's [`ppoe::chain::screw_noise`], so tables and the runtime agree.
fn screw_cov(screw: &[f64; 6], sigma2: f64) -> [[f64; 6]; 6] {
    ppoe::chain::screw_noise(&ppoe::Vector(*screw), sigma2).0
}

/// A joint that gives `sigma2` and no `cov` (its `cov` is filled in by
/// [`NoiseModel::resolve`]).
fn sigma2_joint(i: usize, name: &str, sigma2: &serde_json::Value) -> Result<NoiseJoint> {
    let at = format!("noise model: joint {i} ('{name}')");
    if sigma2.is_null() {
        return Err(config(format!(
            "{at} has neither \"cov\" (6×6) nor \"sigma2\" (its joint-value variance)"
        )));
    }
    let s = sigma2
        .as_f64()
        .filter(|s| s.is_finite() && *s >= 0.0)
        .ok_or_else(|| {
            config(format!(
                "{at} sigma2: expected a finite variance ≥ 0 (rad² or m²), got {sigma2}"
            ))
        })?;
    Ok(NoiseJoint {
        name: name.to_string(),
        cov: [[0.0; 6]; 6],
        sigma2: Some(s),
    })
}

/// `goodness_of_fit.fits`: absent (a hand-written file) is `None`; present, it must be a
/// boolean in an object.
fn fits(v: &serde_json::Value) -> Result<Option<bool>> {
    let Some(g) = v.get("goodness_of_fit") else {
        return Ok(None);
    };
    let g = g
        .as_object()
        .ok_or_else(|| config("noise model: \"goodness_of_fit\" is not an object".into()))?;
    match g.get("fits") {
        None => Ok(None),
        Some(f) => f.as_bool().map(Some).ok_or_else(|| {
            config("noise model: goodness_of_fit.fits: expected true or false".into())
        }),
    }
}

fn literal(x: f64, f32: bool) -> String {
    let s = if f32 {
        format!("{:?}", x as f32)
    } else {
        format!("{x:?}")
    };
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

/// The Rust source of the noise items for table `name` (appended after the chain; `name`
/// is a checked const name). The model's name, its joints' names and `file_name` go into
/// comments through [`comment_text`], so they cannot end the comment.
pub fn generate(model: &NoiseModel, name: &str, scalar: Scalar, file_name: &str) -> String {
    let mut out = String::new();
    let (model_name, file_name) = (comment_text(&model.model), comment_text(file_name));
    let variants: &[(bool, &str)] = match scalar {
        Scalar::F64 => &[(false, "")],
        Scalar::F32 => &[(true, "_F32")],
        Scalar::Both => &[(false, ""), (true, "_F32")],
    };
    let n = model.joints.len();
    for &(f32, suffix) in variants {
        let ty = if f32 { "f32" } else { "f64" };
        let _ = write!(
            out,
            "\n/// Per-joint noise of `{name}{suffix}` fitted by `ppoe fit` (model `{}`), from \
             `{file_name}`:\n/// `{name}_NOISE{suffix}[i]` is joint i's covariance (base-frame \
             screw coordinates, rotation\n/// first), what `Chain::ppoe` takes as `covs`.\n\
             #[allow(clippy::excessive_precision)]\npub const {name}_NOISE{suffix}: \
             [ppoe::Mat6<{ty}>; {n}] = [\n",
            model_name
        );
        for j in &model.joints {
            let _ = writeln!(out, "    // {}\n    ppoe::Matrix([", comment_text(&j.name));
            for row in &j.cov {
                let items: Vec<String> = row.iter().map(|x| literal(*x, f32)).collect();
                let _ = writeln!(out, "        [{}],", items.join(", "));
            }
            out.push_str("    ]),\n");
        }
        out.push_str("];\n");
        let sig: Option<Vec<String>> = (model.model == "joint")
            .then(|| {
                model
                    .joints
                    .iter()
                    .map(|j| j.sigma2.map(|s| literal(s, f32)))
                    .collect()
            })
            .flatten();
        if let Some(sig) = sig {
            let _ = write!(
                out,
                "\n/// Joint-value variances (rad² or m²) of `{name}{suffix}` fitted by `ppoe fit`: \
                 what\n/// `Chain::ppoe_rank1` takes (`{name}_NOISE{suffix}[i] = σᵢ²·SᵢSᵢᵀ`).\n\
                 #[allow(clippy::excessive_precision)]\npub const {name}_SIGMA2{suffix}: \
                 [{ty}; {n}] = [{}];\n",
                sig.join(", ")
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(cov00: f64) -> String {
        let mut c = [[0.0; 6]; 6];
        c[0][0] = cov00;
        c[2][2] = 1e-4;
        serde_json::json!({"model": "joint", "joints": [
            {"name": "a", "cov": c, "sigma2": 1e-4},
            {"name": "b", "cov": c, "sigma2": 2e-4},
        ]})
        .to_string()
    }

    #[test]
    fn parse_and_generate() {
        let m = NoiseModel::parse(&model(1e-4)).unwrap();
        assert_eq!(m.joints.len(), 2);
        let src = generate(&m, "ARM", Scalar::Both, "noise.json");
        assert!(src.contains("pub const ARM_NOISE: [ppoe::Mat6<f64>; 2] = ["));
        assert!(src.contains("pub const ARM_NOISE_F32: [ppoe::Mat6<f32>; 2] = ["));
        assert!(src.contains("pub const ARM_SIGMA2: [f64; 2] = [0.0001, 0.0002];"));
        assert!(src.contains("pub const ARM_SIGMA2_F32: [f32; 2] = [0.0001, 0.0002];"));
    }

    #[test]
    fn rejects_bad_covariances() {
        let e = NoiseModel::parse(&model(-1.0)).unwrap_err();
        assert!(e.to_string().contains("joint 0 ('a') cov"), "{e}");
        let e = NoiseModel::parse("{\"joints\": [{\"name\": \"a\", \"cov\": [[1]]}]}").unwrap_err();
        assert!(e.to_string().contains("6 rows of 6"), "{e}");
        assert!(NoiseModel::parse("{}").is_err());
    }

    #[test]
    fn strict_json_bom_and_duplicate_keys() {
        let m = NoiseModel::parse(&format!("\u{feff}{}", model(1e-4))).unwrap();
        assert_eq!(m.joints.len(), 2);
        let e = NoiseModel::parse("{\"joints\": [],\n \"joints\": []}").unwrap_err();
        assert_eq!(e.kind(), ErrorKind::Json);
        assert!(e.message().contains("duplicate key \"joints\""), "{e}");
        assert_eq!(e.position().map(|p| p.line), Some(2), "{e}");
        let e = NoiseModel::parse("{\"joints\": [}").unwrap_err();
        assert_eq!(
            (e.kind(), e.position().map(|p| p.line)),
            (ErrorKind::Json, Some(1))
        );
    }

    #[test]
    fn hostile_model_and_joint_names_stay_in_their_comments() {
        let text = model(1e-4)
            .replace("\"joint\"", "\"joint\\nfn injected() {}\"")
            .replace("\"a\"", "\"a\\r\\nfn injected2() {}\"");
        let m = NoiseModel::parse(&text).unwrap();
        assert!(m.model.contains('\n') && m.joints[0].name.contains('\n'));
        let src = generate(&m, "ARM", Scalar::F64, "x\ny.json");
        for line in src.lines() {
            let code = line.trim_start();
            assert!(
                !code.starts_with("fn") && !code.starts_with("y.json"),
                "{src}"
            );
        }
        assert!(src.contains("\\u{a}fn injected() {}"), "{src}");
    }

    /// Issue #26 item 4's matrix, antisymmetric by its own scale of 10⁻⁸ (which an
    /// absolute tolerance of 1.5·10⁻⁸ let through), is rejected, naming the joint.
    #[test]
    fn rejects_asymmetry_relative_to_scale() {
        let mut c = [[0.0; 6]; 6];
        for (i, row) in c.iter_mut().enumerate() {
            row[i] = 1e-8;
        }
        c[0][1] = 5e-9;
        c[1][0] = -5e-9;
        let text = serde_json::json!({"joints": [{"name": "a", "cov": c}]}).to_string();
        let e = NoiseModel::parse(&text).unwrap_err().to_string();
        assert!(
            e.contains("joint 0 ('a') cov") && e.contains("not symmetric"),
            "{e}"
        );
        c[1][0] = 5e-9;
        let text = serde_json::json!({"joints": [{"name": "a", "cov": c}]}).to_string();
        assert!(NoiseModel::parse(&text).is_ok());
    }
}
