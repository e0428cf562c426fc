//! Mimic joints: joints whose value follows another joint's, `θ = multiplier·θ_master +
//! offset` (URDF `<mimic joint multiplier offset>`), and the expansion of the independent
//! joint values a caller gives into the full joint vector of a chain.
//!
//! A mimic joint is an ordinary joint of the chain — its own screw, its own limits, its own
//! 6×6 covariance slot — whose value is computed instead of given. So the PPOE is unchanged:
//! [`Coupling::expand`] turns the independent values into one value per chain joint, and
//! those go to `ppoe`/`ppoe_checked`, which clip each joint to its own limits as always.
//!
//! The independent values (the *inputs*) need not all be chain joints: a gripper finger on
//! the path may mimic the other finger, which is not on the path. That finger's value is
//! still an input (it moves the mimic joint) but contributes no screw.
//!
//! ```
//! use ppoe::chain::{Coupling, JointSource, Mimic};
//! // Three chain joints, two inputs: joint 2 follows input 1 (not a chain joint here) as
//! // θ₂ = −0.5·q₁ + 0.1.
//! const GRIPPER: Coupling<'static, f64> = Coupling::new(
//!     2,
//!     &[JointSource::Input(0), JointSource::Input(0), JointSource::Mimic(Mimic::new(1, -0.5, 0.1))],
//! );
//! let mut full = [0.0; 3];
//! GRIPPER.expand(&[0.3, 0.4], &mut full)?;
//! assert_eq!(full, [0.3, 0.3, -0.5 * 0.4 + 0.1]);
//! # Ok::<(), ppoe::Error>(())
//! ```

use crate::error::Error;
use crate::scalar::Real;

/// The coupling of a mimic joint to its master: `θ = multiplier·q[master] + offset`, where
/// `q` are the independent joint values ([`Coupling`]'s inputs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mimic<T> {
    /// The index of the master's value among the inputs.
    pub master: usize,
    /// The factor on the master's value (URDF's `multiplier`, default 1).
    pub multiplier: T,
    /// Added after the multiplication (URDF's `offset`, default 0; radians or metres).
    pub offset: T,
}

impl<T> Mimic<T> {
    /// A coupling to input `master`; usable in `const` items (`ppoe-build` emits this).
    #[inline]
    pub const fn new(master: usize, multiplier: T, offset: T) -> Self {
        Self {
            master,
            multiplier,
            offset,
        }
    }
}

/// Where one joint of a chain takes its value from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointSource<T> {
    /// An independent value: `θ = q[index]`, copied unchanged.
    Input(usize),
    /// A mimic joint: `θ = multiplier·q[master] + offset`.
    Mimic(Mimic<T>),
}

/// How the joint values of a chain follow from its independent inputs: one
/// [`JointSource`] per chain joint, base to tip, and the number of inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coupling<'a, T> {
    /// The number of independent values [`Coupling::expand`] takes.
    pub inputs: usize,
    /// One source per chain joint, base to tip.
    pub joints: &'a [JointSource<T>],
}

impl<'a, T: Real> Coupling<'a, T> {
    /// A coupling of `joints.len()` chain joints to `inputs` independent values; usable in
    /// `const` items (`ppoe-build` emits this for chains with mimic joints).
    #[inline]
    pub const fn new(inputs: usize, joints: &'a [JointSource<T>]) -> Self {
        Self { inputs, joints }
    }

    /// Checks the coupling itself: every index below [`Coupling::inputs`], every
    /// multiplier and offset finite.
    ///
    /// # Errors
    ///
    /// [`Error::IndexOutOfRange`] for an index (an input's or a master's) that is not
    /// below `inputs`, [`Error::NonFinite`] for a non-finite multiplier or offset.
    pub fn check(&self) -> Result<(), Error> {
        for source in self.joints {
            let index = match source {
                JointSource::Input(k) => *k,
                JointSource::Mimic(m) => {
                    if !m.multiplier.is_finite() || !m.offset.is_finite() {
                        return Err(Error::NonFinite);
                    }
                    m.master
                }
            };
            if index >= self.inputs {
                return Err(Error::IndexOutOfRange);
            }
        }
        Ok(())
    }

    /// The full joint vector, one value per chain joint, from the independent values
    /// `inputs`, into `full`: an input joint's value is copied, a mimic joint's is
    /// `multiplier·q[master] + offset`. Nothing is clipped here: the PPOE and the
    /// kinematics clip each joint, mimic ones included, to its own limits.
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `inputs` has [`Coupling::inputs`] values and `full`
    /// one per chain joint; the errors of [`Coupling::check`]; [`Error::NonFinite`] for a
    /// non-finite input; [`Error::Overflow`] if a mimic joint's value overflows. `full` is
    /// unspecified after an error.
    pub fn expand(&self, inputs: &[T], full: &mut [T]) -> Result<(), Error> {
        if inputs.len() != self.inputs || full.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        self.check()?;
        if inputs.iter().any(|q| !q.is_finite()) {
            return Err(Error::NonFinite);
        }
        for (out, source) in full.iter_mut().zip(self.joints) {
            // Indices were checked above; `get` keeps the panic path out anyway.
            *out = match source {
                JointSource::Input(k) => *inputs.get(*k).ok_or(Error::IndexOutOfRange)?,
                JointSource::Mimic(m) => {
                    let q = *inputs.get(m.master).ok_or(Error::IndexOutOfRange)?;
                    let theta = m.multiplier * q + m.offset;
                    if !theta.is_finite() {
                        return Err(Error::Overflow);
                    }
                    theta
                }
            };
        }
        Ok(())
    }
}
