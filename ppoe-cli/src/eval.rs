//! `ppoe eval`: the PPOE for the cases of a JSON file, through the runtime path a host
//! tool gets (`ChainView` over the joints `ppoe-build` computes, `ppoe_checked`).

use crate::args::EvalScalar;
use crate::cases::{check_counts, Case, Input};
use anyhow::bail;
use ppoe::chain::{ChainView, Convention, Joint, JointSource, UncertainPose};
use ppoe::{Mat6, Real, Transform};
use ppoe_build::RobotChain;
use serde::Serialize;

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
    /// Only for a chain with mimic joints: the independent values the cases give, in order.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inputs: Option<Vec<String>>,
    /// Only for a chain with mimic joints: per joint, null or how it follows its master.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mimic: Option<Vec<Option<MimicOut>>>,
}

/// How a mimic joint follows its master: `θ = multiplier·master + offset`.
#[derive(Serialize, Debug)]
pub struct MimicOut {
    /// The master's name (one of the `inputs`).
    pub master: String,
    /// The factor on the master's value.
    pub multiplier: f64,
    /// Added after the multiplication.
    pub offset: f64,
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
        inputs: robot.coupling.as_ref().map(|c| c.inputs.clone()),
        mimic: robot.coupling.as_ref().map(mimic_out),
    }
}

/// Per joint of a coupled chain: null, or its master and coupling.
fn mimic_out(c: &ppoe_build::MimicCoupling) -> Vec<Option<MimicOut>> {
    c.sources
        .iter()
        .map(|s| match s {
            JointSource::Input(_) => None,
            JointSource::Mimic(m) => Some(MimicOut {
                master: c.inputs.get(m.master).cloned().unwrap_or_default(),
                multiplier: m.multiplier,
                offset: m.offset,
            }),
        })
        .collect()
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
///
/// The covariances are checked once, by [`ChainView::ppoe_checked`]; only when it fails
/// are they looked at again, to name the joint ([`named_covariance_error`]).
pub fn eval_case<T: Real>(
    chain: &ChainView<'_, T>,
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
    let tip = chain
        .ppoe_checked(&thetas, &covs, convention)
        .map_err(|e| {
            named_covariance_error(chain, index, &covs)
                .unwrap_or_else(|| anyhow::anyhow!("case {index}: {e}"))
        })?;
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

/// The first covariance of case `index` that is not valid, as an error naming the case
/// and the joint; `None` if all are valid. For the error path of a PPOE that failed: a
/// bad covariance is reported with its joint, before any other failure.
pub fn named_covariance_error<T: Real>(
    chain: &ChainView<'_, T>,
    index: usize,
    covs: &[Mat6<T>],
) -> Option<anyhow::Error> {
    covs.iter().enumerate().find_map(|(j, c)| {
        let e = ppoe::uncertainty::check_covariance(c).err()?;
        let name = chain.joints.get(j).map(|jt| jt.name).unwrap_or("?");
        Some(anyhow::anyhow!("case {index}, joint {j} ('{name}'): {e}"))
    })
}

/// Every case in one batch call of the core (`ppoe_batch_per_config_checked`: each case has
/// its own covariances); a case whose result it rejects is evaluated again alone
/// ([`eval_case`]) for an error that names the case and the joint. The batch's result for a
/// case does not depend on the other cases (the core's batch docs).
fn eval_cases<T: Real>(
    robot: &RobotChain,
    input: &Input,
    convention: Convention,
) -> anyhow::Result<Vec<CaseOut>> {
    check_counts(robot, input)?;
    let (joints, home) = core_joints::<T>(robot);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let lit = |x: &f64| T::lit(*x);
    let thetas: Vec<T> = input
        .cases
        .iter()
        .flat_map(|c| c.thetas.iter().map(lit))
        .collect();
    let covs: Vec<Mat6<T>> = input
        .cases
        .iter()
        .flat_map(|c| c.covs.iter().map(|m| Mat6::from(m.map(|r| r.map(T::lit)))))
        .collect();
    let mut tips = vec![UncertainPose::certain(Transform::identity()); input.cases.len()];
    if let Err(e) = chain.ppoe_batch_per_config_checked(&thetas, &covs, convention, &mut tips) {
        let i = e.config.unwrap_or(0);
        return Err(match input.cases.get(i) {
            Some(case) => eval_case(&chain, i, case, convention)
                .err()
                .unwrap_or_else(|| anyhow::anyhow!("case {i}: {}", e.error)),
            None => anyhow::anyhow!("{e}"),
        });
    }
    let n = joints.len();
    let clip_continuous = convention == Convention::Pytransform3d;
    let mut out = Vec::with_capacity(input.cases.len());
    for (i, tip) in tips.iter().enumerate() {
        let mut clipped = vec![T::ZERO; n];
        let row = thetas.get(i * n..(i + 1) * n).unwrap_or_default();
        chain
            .clip(row, &mut clipped, clip_continuous)
            .map_err(|e| anyhow::anyhow!("case {i}: {e}"))?;
        let result = CaseOut {
            thetas_clipped: clipped.iter().map(|x| Real::to_f64(*x)).collect(),
            pose: tip.pose.to_matrix4().map(|r| r.map(<T as Real>::to_f64)),
            cov: tip.cov.0.map(|r| r.map(<T as Real>::to_f64)),
        };
        check_finite(i, &result)?;
        out.push(result);
    }
    Ok(out)
}

/// JSON has no infinity or NaN (serde writes `null`, which the output uses for an infinite
/// limit), so a non-finite result is an error rather than a silent `null`.
fn check_finite(index: usize, r: &CaseOut) -> anyhow::Result<()> {
    let parts: [(&str, Vec<f64>); 3] = [
        ("the clipped joint values", r.thetas_clipped.clone()),
        ("the pose", r.pose.iter().flatten().copied().collect()),
        ("the covariance", r.cov.iter().flatten().copied().collect()),
    ];
    for (what, values) in parts {
        if let Some(x) = values.iter().find(|x| !x.is_finite()) {
            bail!(
                "case {index}: {what} is not finite ({x}): the computation overflowed; \
                 nothing is written for such a case (JSON has no infinity)"
            );
        }
    }
    Ok(())
}
