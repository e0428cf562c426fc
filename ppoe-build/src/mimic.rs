//! Mimic joints of a chain: each one's master resolved through the URDF (a mimic of a
//! mimic is followed to the first joint that mimics nothing, composing the couplings), and
//! the independent joint values the chain takes ([`MimicCoupling`]).
//!
//! The independent values — the *inputs* — are, in this order: the chain's joints that
//! mimic nothing, base to tip; then every master that is not one of the chain's joints
//! (off the path, or on it but left out of an explicit joint list), in the order of the
//! first chain joint that follows it. Such a master contributes no screw: its value only
//! moves the joints that mimic it.

use crate::error::{Error, ErrorKind, Result};
use crate::urdf::{Joint as UrdfJoint, Urdf};
use ppoe::chain::{Coupling, JointSource, Mimic};
use std::collections::{HashMap, HashSet};

/// How the values of a chain's joints follow from the independent values a caller gives,
/// for a chain with at least one mimic joint.
#[derive(Clone, Debug, PartialEq)]
pub struct MimicCoupling {
    /// The names of the independent values, in the order they are given (see the module
    /// docs): the chain's joints that mimic nothing, base to tip, then the masters that are
    /// not chain joints.
    pub inputs: Vec<String>,
    /// One source per chain joint, base to tip: [`JointSource::Input`] with the index into
    /// `inputs`, or [`JointSource::Mimic`] with the master's index into `inputs` and the
    /// composed multiplier and offset.
    pub sources: Vec<JointSource<f64>>,
}

impl MimicCoupling {
    /// The core's [`Coupling`] over these sources.
    pub fn core(&self) -> Coupling<'_, f64> {
        Coupling::new(self.inputs.len(), &self.sources)
    }

    /// The full joint vector (one value per chain joint) from the independent values
    /// ([`Coupling::expand`]). Error ([`ErrorKind::Config`]) naming the inputs if their
    /// number is wrong, and for a non-finite or overflowing value.
    pub fn expand(&self, inputs: &[f64]) -> Result<Vec<f64>> {
        if inputs.len() != self.inputs.len() {
            return Err(Error::new(
                ErrorKind::Config,
                format!(
                    "{} joint values given, the chain takes {} independent ones ({})",
                    inputs.len(),
                    self.inputs.len(),
                    self.inputs.join(", ")
                ),
            ));
        }
        let mut full = vec![0.0; self.sources.len()];
        self.core().expand(inputs, &mut full).map_err(|e| {
            Error::new(
                ErrorKind::Config,
                format!("the mimic joints' values from the independent ones: {e}"),
            )
        })?;
        Ok(full)
    }
}

/// The couplings of the chain joints `chain` (moving joints of `urdf`, base to tip);
/// `None` if none of them mimics another joint.
///
/// # Errors
///
/// [`ErrorKind::UnknownJoint`] for a master that does not exist, [`ErrorKind::Mimic`] for a
/// master that does not move (fixed, planar, floating), for a cycle of mimic joints and for
/// a composed coupling that is not finite.
pub(crate) fn couple(urdf: &Urdf, chain: &[&UrdfJoint]) -> Result<Option<MimicCoupling>> {
    if chain.iter().all(|j| j.mimic.is_none()) {
        return Ok(None);
    }
    let mut resolver = Resolver {
        by_name: urdf.joints.iter().map(|j| (j.name.as_str(), j)).collect(),
        memo: HashMap::new(),
    };
    let mut inputs: Vec<String> = chain
        .iter()
        .filter(|j| j.mimic.is_none())
        .map(|j| j.name.clone())
        .collect();
    let mut index: HashMap<String, usize> = inputs
        .iter()
        .enumerate()
        .map(|(i, n)| (n.clone(), i))
        .collect();
    let mut sources = Vec::with_capacity(chain.len());
    for j in chain {
        let source = match j.mimic {
            None => JointSource::Input(index.get(&j.name).copied().unwrap_or(0)),
            Some(_) => {
                let (master, multiplier, offset) = resolver.resolve(j)?;
                if !(multiplier.is_finite() && offset.is_finite()) {
                    return Err(Error::new(
                        ErrorKind::Mimic,
                        format!(
                            "joint '{}' follows joint '{master}' through a chain of mimic \
                             joints whose composed multiplier {multiplier} or offset {offset} \
                             is not finite",
                            j.name
                        ),
                    )
                    .at(j.mimic_position.or(j.position)));
                }
                let k = *index.entry(master.to_string()).or_insert_with(|| {
                    inputs.push(master.to_string());
                    inputs.len() - 1
                });
                JointSource::Mimic(Mimic::new(k, multiplier, offset))
            }
        };
        sources.push(source);
    }
    Ok(Some(MimicCoupling { inputs, sources }))
}

/// `(root, multiplier, offset)` of a joint: `θ = multiplier·θ_root + offset`, where the
/// root mimics nothing (a joint that mimics nothing is its own root, `(1, 0)`).
type Resolved<'u> = (&'u str, f64, f64);

/// Resolves mimic joints to their roots, remembering every joint it has resolved, so that
/// a chain of n joints each mimicking the next costs O(n), not O(n²).
struct Resolver<'u> {
    by_name: HashMap<&'u str, &'u UrdfJoint>,
    memo: HashMap<&'u str, Resolved<'u>>,
}

impl<'u> Resolver<'u> {
    /// The root `j` follows and the composed coupling: for `x` mimicking `y` as
    /// `θ_x = m·θ_y + o` and `θ_y = m_y·θ_r + o_y`, `θ_x = (m·m_y)·θ_r + (m·o_y + o)`.
    fn resolve(&mut self, j: &'u UrdfJoint) -> Result<Resolved<'u>> {
        // Walk up to a joint already resolved or one that mimics nothing.
        let mut walk: Vec<&'u UrdfJoint> = Vec::new();
        let mut on_walk: HashSet<&str> = HashSet::new();
        let mut cur = j;
        let mut known = loop {
            if let Some(&r) = self.memo.get(cur.name.as_str()) {
                break r;
            }
            let Some(m) = &cur.mimic else {
                break (cur.name.as_str(), 1.0, 0.0);
            };
            walk.push(cur);
            on_walk.insert(cur.name.as_str());
            let Some(&master) = self.by_name.get(m.joint.as_str()) else {
                return Err(Error::new(
                    ErrorKind::UnknownJoint,
                    format!(
                        "joint '{}' mimics joint '{}', which does not exist",
                        cur.name, m.joint
                    ),
                )
                .at(cur.mimic_position.or(cur.position)));
            };
            if on_walk.contains(master.name.as_str()) {
                return Err(cycle_error(&walk, master));
            }
            check_master(cur, master)?;
            cur = master;
        };
        // Back down the walk, composing each joint's own coupling onto its master's.
        for x in walk.iter().rev() {
            if let Some(m) = &x.mimic {
                known = (
                    known.0,
                    m.multiplier * known.1,
                    m.multiplier * known.2 + m.offset,
                );
            }
            self.memo.insert(x.name.as_str(), known);
        }
        Ok(known)
    }
}

/// The error for a cycle of mimic joints: `walk` ends with a joint mimicking `back`,
/// which is on the walk already.
fn cycle_error(walk: &[&UrdfJoint], back: &UrdfJoint) -> Error {
    let start = walk.iter().position(|j| j.name == back.name).unwrap_or(0);
    let mut names: Vec<String> = walk[start..]
        .iter()
        .map(|j| format!("'{}'", j.name))
        .collect();
    names.push(format!("'{}'", back.name));
    Error::new(
        ErrorKind::Mimic,
        format!(
            "the mimic joints form a cycle (each mimics the next): {}; one of them must be \
             independent",
            names.join(" → ")
        ),
    )
    .at(back.mimic_position.or(back.position))
}

/// A master must move: a fixed joint has no value to follow, planar and floating ones
/// have more than one.
fn check_master(follower: &UrdfJoint, master: &UrdfJoint) -> Result<()> {
    if master.joint_type.is_moving() {
        return Ok(());
    }
    Err(Error::new(
        ErrorKind::Mimic,
        format!(
            "joint '{}' mimics joint '{}', which is {}: a master must be revolute, continuous \
             or prismatic",
            follower.name,
            master.name,
            master.joint_type.as_str()
        ),
    )
    .at(follower.mimic_position.or(follower.position)))
}
