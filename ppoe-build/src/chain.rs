//! Chain extraction: from a base link to a tip link through the URDF tree, the screw axes of
//! the moving joints in the base frame at the home pose, the home pose M of the tip, and the
//! limits — computed as pytransform3d's probabilistic-kinematics example does (see the
//! crate docs, "What is computed").

use crate::error::{Error, ErrorKind, Result};
use crate::math::{self, Mat4, IDENTITY};
use crate::mimic::MimicCoupling;
use crate::urdf::{Joint as UrdfJoint, JointType, Urdf};
use ppoe::chain::{Joint, JointKind};
use ppoe::se3::Transform;
use std::collections::HashMap;

/// One moving joint of a [`RobotChain`].
#[derive(Clone, Debug, PartialEq)]
pub struct ChainJoint {
    /// The joint's name in the URDF.
    pub name: String,
    /// Revolute, continuous or prismatic.
    pub kind: JointKind,
    /// The screw axis S = (ω, v) in the base frame at the home pose, rotation first:
    /// `(ŝ, q × ŝ)` for revolute and continuous joints, `(0, ŝ)` for prismatic ones.
    pub screw: [f64; 6],
    /// The lower limit as written in the URDF (−∞ if absent). Continuous joints keep the
    /// limits the file gives them; whether to clip them is the core's decision.
    pub lower: f64,
    /// The upper limit as written in the URDF (+∞ if absent).
    pub upper: f64,
    /// The joint's home frame `L = T_base←child`: the pose of its child link in the base
    /// frame at the home pose (every joint at 0), row-major 4×4. The joint's axis passes
    /// through its origin; the screw axis is computed from it (`ŝ = R(L)·axis`, `q = p(L)`),
    /// with the same products, so it agrees with pytransform3d bit for bit like the screw.
    /// Finite whenever the screw is (a chain whose frames overflow is an error).
    pub home_frame: [[f64; 4]; 4],
}

/// A serial chain extracted from a URDF, host side (owned strings, any number of joints).
/// The generated `const` tables hold exactly these values.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotChain {
    /// The `<robot name>`.
    pub robot: String,
    /// The base link.
    pub base: String,
    /// The tip link.
    pub tip: String,
    /// The moving joints, base to tip.
    pub joints: Vec<ChainJoint>,
    /// The home pose M (tip to base at θ = 0), row-major 4×4.
    pub home: [[f64; 4]; 4],
    /// `None` if no joint of the chain is a mimic joint (the chain then takes one value per
    /// joint); otherwise how the joints' values follow from the independent values callers
    /// give ([`MimicCoupling`]; mimic joints keep their own screw, limits and noise).
    pub coupling: Option<MimicCoupling>,
}

impl RobotChain {
    /// The joints as the core's [`ppoe::chain::Joint`]s ([`Joint::from_f64`]: screw
    /// elements below ε²·max of ω or of v are zero, as in the tables).
    ///
    /// `Joint` holds its name as `&'static str`, so that generated chains can be `const`
    /// items with no allocation. To build one at run time, each name is copied into a
    /// leaked `Box<str>`: a few bytes per joint and call, never freed. That is meant for
    /// build scripts, command-line tools and tests that build a handful of chains; do not
    /// call it in a loop.
    pub fn to_core_joints(&self) -> Vec<Joint<f64>> {
        self.joints
            .iter()
            .map(|j| {
                let name: &'static str = Box::leak(j.name.clone().into_boxed_str());
                Joint::from_f64(&Joint::new(name, j.kind, j.screw, j.lower, j.upper))
            })
            .collect()
    }

    /// The home pose M as the core's [`Transform`] ([`Transform::from_f64`]: elements below
    /// ε²·max of the rotation or of the translation are zero, as in the tables).
    pub fn home_transform(&self) -> Transform<f64> {
        Transform::from_f64(&Transform::from_matrix4(&self.home))
    }

    /// The chain as the core's [`ppoe::chain::Chain`] with `N` joints, the same values a
    /// generated `const` holds. Leaks the link and joint names like
    /// [`RobotChain::to_core_joints`]. Error ([`ErrorKind::Config`]) if the chain does not
    /// have exactly `N` joints.
    pub fn to_core_chain<const N: usize>(&self) -> Result<ppoe::chain::Chain<f64, N>> {
        let joints: [Joint<f64>; N] = self.to_core_joints().try_into().map_err(|v: Vec<_>| {
            Error::new(
                ErrorKind::Config,
                format!("the chain has {} joints, not {N}", v.len()),
            )
        })?;
        let base: &'static str = Box::leak(self.base.clone().into_boxed_str());
        let tip: &'static str = Box::leak(self.tip.clone().into_boxed_str());
        Ok(ppoe::chain::Chain::new(
            base,
            tip,
            joints,
            self.home_transform(),
        ))
    }

    /// The home frame of each moving joint, base to tip: [`ChainJoint::home_frame`], the
    /// pose of the joint's child link in the base frame with every joint at 0 (row-major
    /// 4×4; the axis passes through its origin). At joint values θ the frame of joint i is
    /// `Exp(S₁θ₁)·…·Exp(Sᵢθᵢ)·Lᵢ` (space-frame product of exponentials).
    pub fn home_frames(&self) -> Vec<[[f64; 4]; 4]> {
        self.joints.iter().map(|j| j.home_frame).collect()
    }

    /// The names of the moving joints, base to tip.
    pub fn joint_names(&self) -> Vec<&str> {
        self.joints.iter().map(|j| j.name.as_str()).collect()
    }

    /// The names of the independent joint values the chain takes, in order: the joint
    /// names if no joint is a mimic joint, else [`MimicCoupling::inputs`].
    pub fn input_names(&self) -> Vec<&str> {
        match &self.coupling {
            Some(c) => c.inputs.iter().map(String::as_str).collect(),
            None => self.joint_names(),
        }
    }

    /// The full joint vector (one value per joint, base to tip) from the independent
    /// values ([`RobotChain::input_names`]): copied if no joint is a mimic joint, else
    /// expanded by [`MimicCoupling::expand`].
    ///
    /// # Errors
    ///
    /// [`ErrorKind::Config`] naming the inputs if there is not one value per input; for a
    /// mimic joint, a non-finite value or one that overflows.
    pub fn expand_thetas(&self, inputs: &[f64]) -> Result<Vec<f64>> {
        match &self.coupling {
            Some(c) => c.expand(inputs),
            None if inputs.len() == self.joints.len() => Ok(inputs.to_vec()),
            None => Err(Error::new(
                ErrorKind::Config,
                format!(
                    "{} joint values given, the chain has {} joints ({})",
                    inputs.len(),
                    self.joints.len(),
                    self.joint_names().join(", ")
                ),
            )),
        }
    }
}

impl Urdf {
    /// Extracts the chain from `base` to `tip`.
    ///
    /// `joints`: `None` takes every moving joint on the path, base to tip. An explicit list
    /// must name joints on the path, moving, each once, in path order (base to tip). Moving
    /// joints on the path that are left out are frozen at their home position (0): they
    /// only contribute their fixed `<origin>` transform, like fixed joints.
    ///
    /// Fixed joints on the path (before, between and after the moving ones) are folded into
    /// the screw axes and the home pose.
    ///
    /// Mimic joints (`<mimic joint multiplier offset>`) are joints of the chain like any
    /// other — their own screw, limits and noise — whose values follow their masters';
    /// [`RobotChain::coupling`] says how, and which independent values the chain takes
    /// (a master off the path, or left out of an explicit list, is one of them though it
    /// has no screw). A mimic of a mimic is followed to its root, composing the couplings.
    ///
    /// # Errors
    ///
    /// [`ErrorKind::UnknownLink`], [`ErrorKind::TipNotBelowBase`],
    /// [`ErrorKind::UnsupportedJointType`], [`ErrorKind::NotMovable`], for the chain's mimic
    /// joints [`ErrorKind::UnknownJoint`] (no such master) and [`ErrorKind::Mimic`] (a
    /// master that does not move, a cycle of mimic joints),
    /// the errors of an explicit list ([`ErrorKind::UnknownJoint`],
    /// [`ErrorKind::DuplicateName`], [`ErrorKind::NotOnPath`]), and for the chain's moving
    /// joints [`ErrorKind::InvalidLimits`], [`ErrorKind::ZeroAxis`] and
    /// [`ErrorKind::NonFinite`] (a product that overflows).
    pub fn chain<S: AsRef<str>>(
        &self,
        base: &str,
        tip: &str,
        joints: Option<&[S]>,
    ) -> Result<RobotChain> {
        self.check_ends(base, tip)?;
        let path = self.path(base, tip)?;
        check_path(&path, base, tip)?;
        let selected: Vec<usize> = match joints {
            None => self.moving_on_path(&path, base, tip)?,
            Some(list) => self.select(list, &path, base, tip)?,
        };
        let moving: Vec<&UrdfJoint> = selected.iter().map(|&i| path[i]).collect();
        let coupling = crate::mimic::couple(self, &moving)?;
        let frames = HomeFrames::new(&path);
        let mut out = Vec::with_capacity(selected.len());
        for &i in &selected {
            out.push(chain_joint(path[i], frames.link2base(i), &path[..=i])?);
        }
        let home = frames.link2base(path.len() - 1);
        if home.iter().flatten().any(|x| !x.is_finite()) {
            return Err(overflow_error(
                &path,
                &format!("the home pose of '{tip}' in '{base}'"),
            ));
        }
        Ok(RobotChain {
            robot: self.name.clone(),
            base: base.to_string(),
            tip: tip.to_string(),
            joints: out,
            home,
            coupling,
        })
    }

    fn link_position(&self, name: &str) -> Option<crate::error::Position> {
        self.link(name).and_then(|l| l.position)
    }

    /// Both links exist and differ.
    fn check_ends(&self, base: &str, tip: &str) -> Result<()> {
        for (what, name) in [("base", base), ("tip", tip)] {
            if self.link(name).is_none() {
                return Err(Error::new(
                    ErrorKind::UnknownLink,
                    format!(
                        "{what} link '{name}' does not exist in robot '{}'",
                        self.name
                    ),
                ));
            }
        }
        if base == tip {
            return Err(Error::new(
                ErrorKind::TipNotBelowBase,
                format!("the tip link '{tip}' is the base link itself: the chain is empty"),
            )
            .at(self.link_position(tip)));
        }
        Ok(())
    }

    /// The joints from `base` down to `tip`, base to tip, found by walking up from the tip.
    /// The tree was checked at parse time (one parent per link, no cycle), so the walk
    /// ends; the step bound makes that certain anyway.
    fn path(&self, base: &str, tip: &str) -> Result<Vec<&UrdfJoint>> {
        let parent_joint: HashMap<&str, &UrdfJoint> =
            self.joints.iter().map(|j| (j.child.as_str(), j)).collect();
        let mut path: Vec<&UrdfJoint> = Vec::new();
        let mut cur = tip;
        while cur != base {
            match parent_joint.get(cur) {
                Some(j) if path.len() <= self.joints.len() => {
                    path.push(j);
                    cur = j.parent.as_str();
                }
                _ => {
                    return Err(Error::new(
                        ErrorKind::TipNotBelowBase,
                        format!(
                            "the tip link '{tip}' is not below the base link '{base}': going \
                             up from '{tip}' reaches the root link '{cur}' without passing \
                             '{base}'"
                        ),
                    )
                    .at(self.link_position(tip)));
                }
            }
        }
        path.reverse();
        Ok(path)
    }

    /// The default selection: every moving joint on the path (indices into `path`).
    fn moving_on_path(&self, path: &[&UrdfJoint], base: &str, tip: &str) -> Result<Vec<usize>> {
        let moving: Vec<usize> = (0..path.len())
            .filter(|&i| path[i].joint_type.is_moving())
            .collect();
        if moving.is_empty() {
            return Err(Error::new(
                ErrorKind::NotMovable,
                format!(
                    "the path from '{base}' to '{tip}' has no moving joint (only fixed \
                     joints: {})",
                    names(path)
                ),
            )
            .at(self.link_position(tip)));
        }
        Ok(moving)
    }

    /// Checks an explicit joint list against the path; returns indices into `path`.
    fn select<S: AsRef<str>>(
        &self,
        list: &[S],
        path: &[&UrdfJoint],
        base: &str,
        tip: &str,
    ) -> Result<Vec<usize>> {
        // Hash lookups, so that a list of 10⁴ joints is not quadratic.
        let by_name: HashMap<&str, &UrdfJoint> =
            self.joints.iter().map(|j| (j.name.as_str(), j)).collect();
        let on_path: HashMap<&str, usize> = path
            .iter()
            .enumerate()
            .map(|(i, j)| (j.name.as_str(), i))
            .collect();
        let mut seen: std::collections::HashSet<&str> = std::collections::HashSet::new();
        let mut out: Vec<usize> = Vec::with_capacity(list.len());
        for name in list {
            let name = name.as_ref();
            let Some(&joint) = by_name.get(name) else {
                return Err(Error::new(
                    ErrorKind::UnknownJoint,
                    format!(
                        "joint '{name}' (listed) does not exist in robot '{}'",
                        self.name
                    ),
                ));
            };
            if !seen.insert(name) {
                return Err(Error::new(
                    ErrorKind::DuplicateName,
                    format!("joint '{name}' is listed twice"),
                ));
            }
            let Some(&i) = on_path.get(name) else {
                return Err(Error::new(
                    ErrorKind::NotOnPath,
                    format!(
                        "joint '{name}' (listed) is not on the path from '{base}' to '{tip}' \
                         (the path: {})",
                        names(path)
                    ),
                )
                .at(joint.position));
            };
            check_listed(joint, i, out.last().copied(), path, base, tip)?;
            out.push(i);
        }
        Ok(out)
    }
}

/// Every joint on the path can be part of a chain: no planar or floating joint.
fn check_path(path: &[&UrdfJoint], base: &str, tip: &str) -> Result<()> {
    for j in path {
        if matches!(j.joint_type, JointType::Planar | JointType::Floating) {
            return Err(Error::new(
                ErrorKind::UnsupportedJointType,
                format!(
                    "joint '{}' on the path from '{base}' to '{tip}' is {}; only revolute, \
                     continuous, prismatic and fixed joints can form a chain",
                    j.name,
                    j.joint_type.as_str()
                ),
            )
            .at(j.position));
        }
    }
    Ok(())
}

/// `T_base←child` for every joint on a path, as pytransform3d's `get_transform` computes
/// it: the direct edge for a child of the base, otherwise the identity, then `T ← C_k·T`
/// from the link up. That costs O(i) products per joint, O(n²) per chain; beyond
/// [`EXACT_ORDER_MAX_PATH`] joints the products are accumulated base to tip instead (O(n);
/// equal up to rounding, ~1e-16 relative).
struct HomeFrames<'a, 'u> {
    path: &'a [&'u UrdfJoint],
    prefix: Option<Vec<Mat4>>,
}

impl<'a, 'u> HomeFrames<'a, 'u> {
    fn new(path: &'a [&'u UrdfJoint]) -> Self {
        let prefix = (path.len() > EXACT_ORDER_MAX_PATH).then(|| prefix_products(path));
        Self { path, prefix }
    }

    /// `T_base←child` of joint `i` of the path.
    fn link2base(&self, i: usize) -> Mat4 {
        if let Some(prefix) = &self.prefix {
            return prefix[i];
        }
        if i == 0 {
            return self.path[0].child2parent;
        }
        let mut t = IDENTITY;
        for j in self.path[..=i].iter().rev() {
            t = math::mul4(&j.child2parent, &t);
        }
        t
    }
}

/// The chain joint of the moving joint `j` whose child frame is `l` (`T_base←child`);
/// `path` runs from the base to `j`, for the overflow error.
fn chain_joint(j: &UrdfJoint, l: Mat4, path: &[&UrdfJoint]) -> Result<ChainJoint> {
    check_limits(j)?;
    let s = math::rotate(&l, j.axis);
    let n = math::norm(s);
    if n == 0.0 {
        return Err(Error::new(
            ErrorKind::ZeroAxis,
            format!(
                "joint '{}' ({}): the axis ({:?}, {:?}, {:?}) is zero; a moving joint needs a \
                 direction",
                j.name,
                j.joint_type.as_str(),
                j.axis[0],
                j.axis[1],
                j.axis[2]
            ),
        )
        .at(j.axis_position.or(j.position)));
    }
    let s = [s[0] / n, s[1] / n, s[2] / n];
    let (kind, screw) = match j.joint_type {
        JointType::Prismatic => (JointKind::Prismatic, [0.0, 0.0, 0.0, s[0], s[1], s[2]]),
        t => {
            let q = [l[0][3], l[1][3], l[2][3]];
            let c = math::cross(q, s);
            // pytransform3d adds h·ŝ with h = 0.0 (this only affects signed zeros).
            let v = [c[0] + 0.0 * s[0], c[1] + 0.0 * s[1], c[2] + 0.0 * s[2]];
            let kind = if t == JointType::Continuous {
                JointKind::Continuous
            } else {
                JointKind::Revolute
            };
            (kind, [s[0], s[1], s[2], v[0], v[1], v[2]])
        }
    };
    if screw.iter().any(|x| !x.is_finite()) {
        return Err(overflow_error(
            path,
            &format!("the screw axis of joint '{}'", j.name),
        ));
    }
    Ok(ChainJoint {
        name: j.name.clone(),
        kind,
        screw,
        lower: j.lower,
        upper: j.upper,
        home_frame: l,
    })
}

/// A listed joint `joint`, at index `i` of the path, must be moving and come after the
/// previous listed one (at `prev`).
fn check_listed(
    joint: &UrdfJoint,
    i: usize,
    prev: Option<usize>,
    path: &[&UrdfJoint],
    base: &str,
    tip: &str,
) -> Result<()> {
    let name = &joint.name;
    if !joint.joint_type.is_moving() {
        return Err(Error::new(
            ErrorKind::NotMovable,
            format!(
                "joint '{name}' is {}, it cannot be listed as a moving joint",
                joint.joint_type.as_str()
            ),
        )
        .at(joint.position));
    }
    match prev {
        Some(prev) if i < prev => Err(Error::new(
            ErrorKind::NotOnPath,
            format!(
                "joint '{name}' is listed after '{}' but comes before it on the path from \
                 '{base}' to '{tip}': list the joints in path order, base to tip (the path: \
                 {})",
                path[prev].name,
                names(path)
            ),
        )
        .at(joint.position)),
        _ => Ok(()),
    }
}

/// Paths with at most this many joints get pytransform3d's evaluation order, bit for bit
/// (O(n²) matrix products per chain); longer ones are accumulated base to tip (O(n)).
const EXACT_ORDER_MAX_PATH: usize = 256;

/// `P_i = C_0·C_1·…·C_i`, accumulated base to tip.
fn prefix_products(path: &[&UrdfJoint]) -> Vec<Mat4> {
    let mut out: Vec<Mat4> = Vec::with_capacity(path.len());
    for j in path {
        let t = match out.last() {
            Some(prev) => math::mul4(prev, &j.child2parent),
            None => j.child2parent,
        };
        out.push(t);
    }
    out
}

/// A moving joint of the chain must have limits that admit a finite position.
fn check_limits(j: &UrdfJoint) -> Result<()> {
    let problem = if j.lower > j.upper {
        "the lower limit is above the upper limit"
    } else if j.lower == f64::INFINITY {
        "the lower limit is +inf"
    } else if j.upper == f64::NEG_INFINITY {
        "the upper limit is -inf"
    } else {
        return Ok(());
    };
    Err(Error::new(
        ErrorKind::InvalidLimits,
        format!(
            "joint '{}' ({}): <limit lower=\"{}\" upper=\"{}\">: {problem}, so no position \
             is allowed; write lower <= upper (swap them if they are reversed), or leave \
             out a bound for no limit",
            j.name,
            j.joint_type.as_str(),
            num(j.lower),
            num(j.upper)
        ),
    )
    .at(j.limit_position.or(j.position)))
}

/// The error for a non-finite `what` (a screw axis or the home pose) computed from the finite
/// origins of `path`: names the first joint whose origin makes the product overflow.
fn overflow_error(path: &[&UrdfJoint], what: &str) -> Error {
    let prefix = prefix_products(path);
    let k = prefix
        .iter()
        .position(|t| t.iter().flatten().any(|x| !x.is_finite()))
        .unwrap_or(path.len() - 1);
    let j = path[k];
    let c = &j.child2parent;
    Error::new(
        ErrorKind::NonFinite,
        format!(
            "{what} is not finite: the transforms along the path overflow f64 at joint \
             '{}' (<origin xyz=\"{} {} {}\">), where link '{}' ends up at an infinite \
             distance from the base; the origins are finite but too large — use realistic \
             lengths (metres)",
            j.name,
            num(c[0][3]),
            num(c[1][3]),
            num(c[2][3]),
            j.child
        ),
    )
    .at(j.position)
}

/// A number for a message: plain for ordinary magnitudes, `1e308` for huge or tiny ones.
fn num(x: f64) -> String {
    if x.is_finite() && x != 0.0 && !(1e-6..1e16).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

fn names(path: &[&UrdfJoint]) -> String {
    path.iter()
        .map(|j| format!("{} ({})", j.name, j.joint_type.as_str()))
        .collect::<Vec<_>>()
        .join(", ")
}
