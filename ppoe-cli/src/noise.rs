//! `--noise FILE`: a noise model written by `ppoe fit`, read back by `eval`, `render`,
//! `mesh`, `demo` and `table`. Read once like every input (a file, `-` for standard input,
//! or a pipe), decoded by [`input::text`] (a byte-order mark is accepted), then parsed and
//! its covariances checked by `ppoe-build`'s [`NoiseModel::parse`], the one reader of the
//! format (the same the build scripts use).
//!
//! A fit rejected by its goodness-of-fit test (`goodness_of_fit.fits` false) is refused
//! unless `--allow-rejected-noise`. If the fit estimated a calibration, the model's
//! covariances belong to the calibrated chain, so every command uses that chain
//! ([`NoiseModel::calibrated_chain`]: offsets and corrections folded into the screws and
//! the home pose) and places the links with its folds (see [`Applied`]).
//!
//! `--joint-sigma S1,S2,...` is the datasheet's noise model instead
//! ([`NoiseModel::from_sigmas`]: σᵢ²·SᵢSᵢᵀ per joint), as is a noise file whose joints
//! give `sigma2` and no `cov` ([`NoiseModel::resolve`]); the two flags exclude each other.

use crate::args::NoiseArgs;
use crate::{input, load};
use anyhow::{anyhow, bail};
use ppoe_build::noise::NoiseModel;
use ppoe_build::RobotChain;
use std::path::{Path, PathBuf};

/// What messages call the input.
const WHAT: &str = "noise model";

/// A row-major 4×4 homogeneous transform.
type Mat4 = [[f64; 4]; 4];

/// Reads and parses the noise model at `path` (`-`: standard input) and refuses a rejected
/// fit unless `allow_rejected`; returns it with the path that names it in generated sources
/// and in errors (`stdin` for standard input). The model's `sha256` is that of the bytes
/// read (a byte-order mark included), what `sha256sum` prints for the file.
///
/// # Errors
/// Unreadable, not UTF-8, malformed, a covariance that is not a covariance, or a rejected
/// fit; each naming the file.
pub fn read(path: &Path, allow_rejected: bool) -> anyhow::Result<(NoiseModel, PathBuf)> {
    let source = load::read(path, WHAT)?;
    let text = input::text(&source.bytes).map_err(|e| {
        anyhow!(
            "{}: the {WHAT} is not UTF-8 (invalid byte at offset {})",
            source.name,
            e.valid_up_to()
        )
    })?;
    let mut model = NoiseModel::parse(text).map_err(|e| anyhow!("{}: {e}", source.name))?;
    model.sha256 = ppoe_build::codegen::sha256_hex(&source.bytes);
    // The message names the file itself ("the fit in FILE …").
    model
        .check_accepted(allow_rejected, &source.name, "pass --allow-rejected-noise")
        .map_err(|e| anyhow!("{e}"))?;
    let named = if load::is_stdin(path) {
        PathBuf::from(&source.file_name)
    } else {
        path.to_path_buf()
    };
    Ok((model, named))
}

/// A noise model applied to a robot's chain.
pub struct Applied {
    /// The per-joint covariances.
    pub covs: Vec<[[f64; 6]; 6]>,
    /// `Fᵢ = E₁···Eᵢ` per joint ([`ppoe_build::calibration::Calibration::link_folds`]):
    /// a link below joint i is placed by the folded chain's prefix times `Fᵢ`; empty
    /// without a calibration.
    pub folds: Vec<Mat4>,
}

/// Reads the noise model at `path`, checks it against `robot` and replaces `robot` by the
/// calibrated chain if the model has a calibration.
///
/// # Errors
/// As [`read`], a model for other joints, or a calibration that cannot be folded.
pub fn apply(path: &Path, allow_rejected: bool, robot: &mut RobotChain) -> anyhow::Result<Applied> {
    let (model, named) = read(path, allow_rejected)?;
    let in_file = |e: ppoe_build::Error| anyhow!("{}: {e}", named.display());
    let calibrated = model.calibrated_chain(robot).map_err(in_file)?;
    let folds = if model.is_calibrated() {
        model.calibration.link_folds(robot).map_err(in_file)?
    } else {
        Vec::new()
    };
    let mut model = model;
    // Joints given by sigma2 alone take the screws of the chain the covariances belong to.
    model.resolve(&calibrated).map_err(in_file)?;
    *robot = calibrated;
    Ok(Applied {
        covs: model.joints.iter().map(|j| j.cov).collect(),
        folds,
    })
}

/// The covariances of `--noise` or `--joint-sigma` for `robot` (replaced by the calibrated
/// chain for a calibrated noise model); `None` if neither is given.
///
/// # Errors
/// As [`apply`]; for `--joint-sigma`, another count than the chain's joints (naming them)
/// or a σ that is negative or not finite.
pub fn from_args(a: &NoiseArgs, robot: &mut RobotChain) -> anyhow::Result<Option<Applied>> {
    if let Some(p) = &a.noise {
        return apply(p, a.allow_rejected_noise, robot).map(Some);
    }
    let Some(sigmas) = &a.joint_sigma else {
        return Ok(None);
    };
    let model =
        NoiseModel::from_sigmas(robot, sigmas).map_err(|e| anyhow!("--joint-sigma: {e}"))?;
    Ok(Some(Applied {
        covs: model.joints.iter().map(|j| j.cov).collect(),
        folds: Vec::new(),
    }))
}

/// The seed robot with a noise model (`demo --noise`): the covariances, the chain (the
/// seed table's, calibrated at run time if the model has a calibration), its joints'
/// home frames and the link folds (as [`Applied::folds`]).
pub struct Seed {
    /// The joint covariances.
    pub covs: [ppoe::Mat6<f64>; 6],
    /// The (calibrated) chain.
    pub chain: ppoe::chain::Chain<f64, 6>,
    /// Its joints' home frames.
    pub home_frames: [Mat4; 6],
    /// The link folds; empty without a calibration.
    pub folds: Vec<Mat4>,
}

impl Seed {
    /// The seed example as it is: its covariances, the seed table, no calibration.
    pub fn example() -> Self {
        Seed {
            covs: crate::seed::covs(),
            chain: crate::seed::SEED,
            home_frames: crate::seed::SEED_JOINT_FRAMES,
            folds: Vec::new(),
        }
    }
}

/// The seed robot's covariances and chain from a noise model, checked against the seed
/// table's joint names.
///
/// # Errors
/// As [`read`], a model for other joints than the seed robot's, or a calibration that
/// cannot be folded.
pub fn seed(path: &Path, allow_rejected: bool) -> anyhow::Result<Seed> {
    let (model, named) = read(path, allow_rejected)?;
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
    let in_file = |e: ppoe_build::Error| anyhow!("{}: {e}", named.display());
    let mut model = model;
    let mut out = Seed::example();
    let nominal = crate::seed::robot_chain();
    if model.is_calibrated() {
        let folded = model.calibration.apply(&nominal).map_err(in_file)?;
        out.folds = model.calibration.link_folds(&nominal).map_err(in_file)?;
        out.chain = folded.to_core_chain().map_err(in_file)?;
        out.home_frames = std::array::from_fn(|i| folded.joints[i].home_frame);
        model.resolve(&folded).map_err(in_file)?;
    } else {
        model.resolve(&nominal).map_err(in_file)?;
    }
    let covs = model.covs();
    out.covs = std::array::from_fn(|i| covs[i]);
    Ok(out)
}

/// The seed robot with the datasheet noise of `--joint-sigma` (six σ, base to tip).
///
/// # Errors
/// Not six σ (naming the seed's joints), or a σ that is negative or not finite.
pub fn seed_sigmas(sigmas: &[f64]) -> anyhow::Result<Seed> {
    let model = NoiseModel::from_sigmas(&crate::seed::robot_chain(), sigmas)
        .map_err(|e| anyhow!("--joint-sigma: {e}"))?;
    let covs = model.covs();
    Ok(Seed {
        covs: std::array::from_fn(|i| covs[i]),
        ..Seed::example()
    })
}
