//! `--noise FILE`: a noise model written by `ppoe fit`, read back by `eval`, `render`,
//! `mesh`, `demo` and `table`. Read once like every input (a file, `-` for standard input,
//! or a pipe), decoded by [`input::text`] (a byte-order mark is accepted), then parsed and
//! its covariances checked by `ppoe-build`'s [`NoiseModel::parse`], the one reader of the
//! format (the same the build scripts use).

use crate::{input, load};
use anyhow::{anyhow, bail};
use ppoe_build::noise::NoiseModel;
use ppoe_build::RobotChain;
use std::path::{Path, PathBuf};

/// What messages call the input.
const WHAT: &str = "noise model";

/// Reads and parses the noise model at `path` (`-`: standard input); returns it with the
/// path that names it in generated sources and in errors (`stdin` for standard input).
///
/// # Errors
/// Unreadable, not UTF-8, malformed, or a covariance that is not a covariance; each
/// naming the file.
pub fn read(path: &Path) -> anyhow::Result<(NoiseModel, PathBuf)> {
    let source = load::read(path, WHAT)?;
    let text = input::text(&source.bytes).map_err(|e| {
        anyhow!(
            "{}: the {WHAT} is not UTF-8 (invalid byte at offset {})",
            source.name,
            e.valid_up_to()
        )
    })?;
    let model = NoiseModel::parse(text).map_err(|e| anyhow!("{}: {e}", source.name))?;
    let named = if load::is_stdin(path) {
        PathBuf::from(&source.file_name)
    } else {
        path.to_path_buf()
    };
    Ok((model, named))
}

/// The per-joint covariances of the noise model at `path`, checked against the chain.
///
/// # Errors
/// As [`read`], or a model for other joints.
pub fn covs_for(path: &Path, robot: &RobotChain) -> anyhow::Result<Vec<[[f64; 6]; 6]>> {
    let (model, named) = read(path)?;
    model
        .check_against(robot)
        .map_err(|e| anyhow!("{}: {e}", named.display()))?;
    Ok(model.joints.iter().map(|j| j.cov).collect())
}

/// The seed robot's covariances from a noise model (`demo --noise`), checked against the
/// seed table's joint names.
///
/// # Errors
/// As [`read`], or a model for other joints than the seed robot's.
pub fn seed_covs(path: &Path) -> anyhow::Result<[ppoe::Mat6<f64>; 6]> {
    let (model, named) = read(path)?;
    let names: Vec<&str> = crate::seed::SEED.joints.iter().map(|j| j.name).collect();
    let mine: Vec<&str> = model.joints.iter().map(|j| j.name.as_str()).collect();
    if names != mine {
        bail!(
            "{}: the noise model's joints [{}] are not the seed robot's [{}]",
            named.display(),
            mine.join(", "),
            names.join(", ")
        );
    }
    let covs = model.covs();
    Ok(std::array::from_fn(|i| covs[i]))
}
