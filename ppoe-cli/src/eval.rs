//! `ppoe eval`: the PPOE for the cases of a JSON file, through the runtime path a host
//! tool gets (`ChainRef` over the joints `ppoe-build` computes, `ppoe_checked`).

use crate::EvalScalar;
use anyhow::{bail, Context};
use ppoe::chain::{ChainRef, Convention, Joint};
use ppoe::{Mat6, Real, Transform};
use ppoe_build::RobotChain;
use serde::{Deserialize, Serialize};
use std::io::Read;
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

/// The output of `ppoe eval`.
#[derive(Serialize, Debug)]
pub struct Output {
    /// The chain the cases were evaluated on.
    pub chain: ChainOut,
    /// One result per case.
    pub results: Vec<CaseOut>,
}

/// The chain in the output.
#[derive(Serialize, Debug)]
pub struct ChainOut {
    /// The base link.
    pub base: String,
    /// The tip link.
    pub tip: String,
    /// The moving joints, base to tip.
    pub joints: Vec<String>,
    /// The screw axes (base frame, home pose, rotation first).
    pub screw_axes: Vec<[f64; 6]>,
    /// The home pose M (4×4 row-major).
    pub home: [[f64; 4]; 4],
    /// `[lower, upper]` per joint; null for an infinite limit.
    pub limits: Vec<[Option<f64>; 2]>,
}

/// One result.
#[derive(Serialize, Debug)]
pub struct CaseOut {
    /// The joint values after clipping to the limits, as the convention clips them.
    pub thetas_clipped: Vec<f64>,
    /// The mean tool pose (4×4 row-major).
    pub pose: [[f64; 4]; 4],
    /// The 6×6 covariance in the requested convention.
    pub cov: [[f64; 6]; 6],
}

/// Reads and parses the input from `path`, or stdin for `None`.
pub fn read_input(path: Option<&Path>) -> anyhow::Result<Input> {
    let (text, name) = match path {
        Some(p) => (
            std::fs::read_to_string(p)
                .with_context(|| format!("cannot read the input file {}", p.display()))?,
            p.display().to_string(),
        ),
        None => {
            let mut s = String::new();
            std::io::stdin()
                .read_to_string(&mut s)
                .context("cannot read the input from standard input")?;
            (s, "standard input".to_string())
        }
    };
    parse_input(&text).with_context(|| format!("{name}: malformed input JSON"))
}

/// Parses the input JSON.
pub fn parse_input(text: &str) -> anyhow::Result<Input> {
    let input: Input = serde_json::from_str(text).map_err(|e| {
        anyhow::anyhow!(
            "{e} (expected {{\"cases\":[{{\"thetas\":[N numbers],\"covs\":[N 6×6 arrays]}}]}})"
        )
    })?;
    Ok(input)
}

/// Checks the joint counts of every case against the chain.
pub fn check_counts(robot: &RobotChain, input: &Input) -> anyhow::Result<()> {
    let n = robot.joints.len();
    for (i, c) in input.cases.iter().enumerate() {
        if c.thetas.len() != n {
            bail!(
                "case {i}: {} joint values given, the chain from '{}' to '{}' has {n} joints ({})",
                c.thetas.len(),
                robot.base,
                robot.tip,
                robot.joint_names().join(", ")
            );
        }
        if c.covs.len() != n {
            bail!(
                "case {i}: {} covariances given, the chain from '{}' to '{}' has {n} joints ({})",
                c.covs.len(),
                robot.base,
                robot.tip,
                robot.joint_names().join(", ")
            );
        }
    }
    Ok(())
}

/// The chain part of the output.
pub fn chain_out(robot: &RobotChain) -> ChainOut {
    let fin = |x: f64| if x.is_finite() { Some(x) } else { None };
    ChainOut {
        base: robot.base.clone(),
        tip: robot.tip.clone(),
        joints: robot.joints.iter().map(|j| j.name.clone()).collect(),
        screw_axes: robot.joints.iter().map(|j| j.screw).collect(),
        home: robot.home,
        limits: robot
            .joints
            .iter()
            .map(|j| [fin(j.lower), fin(j.upper)])
            .collect(),
    }
}

/// The PPOE of every case, in f64 or f32.
pub fn eval(
    robot: &RobotChain,
    input: &Input,
    scalar: EvalScalar,
    convention: Convention,
) -> anyhow::Result<Output> {
    let results = match scalar {
        EvalScalar::F64 => eval_cases::<f64>(robot, input, convention)?,
        EvalScalar::F32 => eval_cases::<f32>(robot, input, convention)?,
    };
    Ok(Output {
        chain: chain_out(robot),
        results,
    })
}

/// The runtime chain in scalar T: the joints `ppoe-build` computes, converted like its
/// tables ([`Joint::from_f64`], [`Transform::from_f64`]).
pub fn core_joints<T: Real>(robot: &RobotChain) -> (Vec<Joint<T>>, Transform<T>) {
    let joints = robot.to_core_joints().iter().map(Joint::from_f64).collect();
    (joints, Transform::from_f64(&robot.home_transform()))
}

/// The mean pose and covariance of one case (already count-checked), in scalar T, with
/// the clipped joint values; errors name the case and the joint.
pub fn eval_case<T: Real>(
    chain: &ChainRef<'_, T>,
    index: usize,
    case: &Case,
    convention: Convention,
) -> anyhow::Result<(Vec<T>, Transform<T>, Mat6<T>)> {
    let thetas: Vec<T> = case.thetas.iter().map(|&x| T::lit(x)).collect();
    for (j, t) in thetas.iter().enumerate() {
        if !t.is_finite() {
            bail!(
                "case {index}, joint {j}: the joint value {} is not finite{}",
                case.thetas[j],
                if case.thetas[j].is_finite() {
                    " in f32"
                } else {
                    ""
                }
            );
        }
    }
    let covs: Vec<Mat6<T>> = case
        .covs
        .iter()
        .map(|c| Mat6::from(c.map(|r| r.map(T::lit))))
        .collect();
    for (j, c) in covs.iter().enumerate() {
        ppoe::uncertainty::check_covariance(c).map_err(|e| {
            let name = chain.joints.get(j).map(|jt| jt.name).unwrap_or("?");
            anyhow::anyhow!("case {index}, joint {j} ('{name}'): {e}")
        })?;
    }
    let tip = chain
        .ppoe_checked(&thetas, &covs, convention)
        .map_err(|e| anyhow::anyhow!("case {index}: {e}"))?;
    let mut clipped = vec![T::ZERO; thetas.len()];
    chain
        .clip(
            &thetas,
            &mut clipped,
            convention == Convention::Pytransform3d,
        )
        .map_err(|e| anyhow::anyhow!("case {index}: {e}"))?;
    Ok((clipped, tip.pose, tip.cov))
}

fn eval_cases<T: Real>(
    robot: &RobotChain,
    input: &Input,
    convention: Convention,
) -> anyhow::Result<Vec<CaseOut>> {
    check_counts(robot, input)?;
    let (joints, home) = core_joints::<T>(robot);
    let chain = ChainRef {
        joints: &joints,
        home,
    };
    let mut out = Vec::with_capacity(input.cases.len());
    for (i, case) in input.cases.iter().enumerate() {
        let (clipped, pose, cov) = eval_case(&chain, i, case, convention)?;
        out.push(CaseOut {
            thetas_clipped: clipped.iter().map(|x| Real::to_f64(*x)).collect(),
            pose: pose.to_matrix4().map(|r| r.map(<T as Real>::to_f64)),
            cov: cov.0.map(|r| r.map(<T as Real>::to_f64)),
        });
    }
    Ok(out)
}
