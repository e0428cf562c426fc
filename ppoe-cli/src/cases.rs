//! The cases of `eval`, `render` and `mesh`,
//! `{"cases":[{"thetas":[N numbers],"covs":[N 6×6 row-major]}]}`: read once (a file,
//! `-` or a pipe), decoded once ([`input::text`]) and parsed once into typed cases. With a
//! noise model (`--noise`) the cases give joint values only and each gets the model's
//! covariances; the JSON is not edited and parsed again. For a chain with mimic joints the
//! cases give the independent joint values ([`expand_mimic`]).

use crate::{input, load};
use anyhow::{anyhow, bail};
use ppoe_build::RobotChain;
use serde::de::{DeserializeOwned, IgnoredAny};
use serde::{Deserialize, Deserializer};
use std::path::Path;

/// The input: `{"cases":[{"thetas":[N numbers],"covs":[N 6×6 row-major]}]}`. Unknown
/// fields (e.g. a case `label`) are ignored.
#[derive(Deserialize, Debug, Clone)]
pub struct Input {
    /// The cases, evaluated in order.
    pub cases: Vec<Case>,
}

/// One case: joint values and per-joint 6×6 covariances (rotation first, base-frame
/// screw coordinates).
#[derive(Deserialize, Debug, Clone)]
pub struct Case {
    /// One value per joint (radians or metres).
    pub thetas: Vec<f64>,
    /// One 6×6 covariance per joint, row-major.
    pub covs: Vec<[[f64; 6]; 6]>,
}

/// The input when a noise model gives the covariances (messages name it as [`Input`]).
#[derive(Deserialize)]
#[serde(expecting = "struct Input")]
struct ThetasInput {
    cases: Vec<ThetasCase>,
}

/// A case when a noise model gives the covariances (messages name it as [`Case`]).
#[derive(Deserialize)]
#[serde(expecting = "struct Case")]
struct ThetasCase {
    thetas: Vec<f64>,
    /// Whether the case gives "covs" (any value, `null` too): then the covariances
    /// would come two ways.
    #[serde(default, deserialize_with = "given")]
    covs: bool,
}

/// `true` for any value that is there.
fn given<'de, D: Deserializer<'de>>(d: D) -> Result<bool, D::Error> {
    IgnoredAny::deserialize(d).map(|_| true)
}

/// The input's shape, named in messages about a wrong one.
const SHAPE: &str = "(expected {\"cases\":[{\"thetas\":[N numbers],\"covs\":[N 6×6 arrays]}]})";

/// Parses `text` as `T`; a wrong shape names the expected one (`with_syntax`: a JSON
/// syntax error too).
fn parse<T: DeserializeOwned>(text: &str, with_syntax: bool) -> anyhow::Result<T> {
    input::parse_json(text).map_err(|e| {
        if input::is_shape_error(&e) || with_syntax {
            anyhow!("{e} {SHAPE}")
        } else {
            e
        }
    })
}

/// Reads, decodes and parses the cases once from `path` (`None` or `-`: standard input);
/// with the covariances of a noise model (`--noise`, read first: [`crate::noise::apply`]),
/// every case gets them, and a case that gives its own is an error (one source of
/// covariances).
///
/// # Errors
/// Unreadable or malformed input, naming it; a case with its own covs.
pub fn load(path: Option<&Path>, covs: Option<Vec<[[f64; 6]; 6]>>) -> anyhow::Result<Input> {
    let input = load::read(path.unwrap_or(Path::new("-")), "input file")?;
    let malformed = |e: anyhow::Error| anyhow!("{}: malformed input JSON: {e:#}", input.name);
    let text = input::text(&input.bytes).map_err(|e| {
        malformed(anyhow!(
            "the input is not UTF-8 (invalid byte at offset {})",
            e.valid_up_to()
        ))
    })?;
    let Some(covs) = covs else {
        return parse::<Input>(text, true).map_err(malformed);
    };
    let given: ThetasInput = parse(text, false).map_err(malformed)?;
    let mut cases = Vec::with_capacity(given.cases.len());
    for (i, c) in given.cases.into_iter().enumerate() {
        if c.covs {
            bail!(
                "case {i} gives \"covs\" and --noise or --joint-sigma is set: give the \
                 covariances one way"
            );
        }
        cases.push(Case {
            thetas: c.thetas,
            covs: covs.clone(),
        });
    }
    Ok(Input { cases })
}

/// For a chain with mimic joints, replaces every case's `thetas` — the independent values,
/// [`RobotChain::input_names`] — by the full joint vector the PPOE takes (a mimic joint's
/// value is `multiplier·master + offset`, then clipped to its own limits like any joint's
/// by the PPOE). Called where the cases are read, before [`check_counts`]; a chain without
/// mimic joints leaves the cases as they are.
///
/// # Errors
/// The first case with another number of independent values (naming them), or whose mimic
/// values overflow.
pub fn expand_mimic(robot: &RobotChain, input: &mut Input) -> anyhow::Result<()> {
    if robot.coupling.is_none() {
        return Ok(());
    }
    for (i, c) in input.cases.iter_mut().enumerate() {
        c.thetas = robot.expand_thetas(&c.thetas).map_err(|e| {
            anyhow!(
                "case {i}: {e} (the chain from '{}' to '{}' has mimic joints, whose values \
                 follow their masters')",
                robot.base,
                robot.tip
            )
        })?;
    }
    Ok(())
}

/// Checks the joint counts of every case against the chain.
///
/// # Errors
/// The first case with another number of joint values or covariances, naming the chain.
pub fn check_counts(robot: &RobotChain, input: &Input) -> anyhow::Result<()> {
    let n = robot.joints.len();
    for (i, c) in input.cases.iter().enumerate() {
        for (given, what) in [
            (c.thetas.len(), "joint values"),
            (c.covs.len(), "covariances"),
        ] {
            if given != n {
                bail!(
                    "case {i}: {given} {what} given, the chain from '{}' to '{}' has {n} joints ({})",
                    robot.base,
                    robot.tip,
                    robot.joint_names().join(", ")
                );
            }
        }
    }
    Ok(())
}
