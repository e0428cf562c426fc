//! The C API of ppoe: the Probabilistic Product of Exponentials (all three conventions),
//! rigid forward kinematics and the chain check, in f32 and f64, on plain C types.
//!
//! The header is `include/ppoe.h` (generated from this file by cbindgen, see
//! `cbindgen.toml`; `examples/c-firmware/build.sh` fails if the committed header differs from what
//! cbindgen produces). Robot tables for it: `ppoe table --lang c` or
//! `ppoe_build::Config::generate_c`.
//!
//! Conventions (also stated in the header):
//! - every array is caller-owned; nothing is allocated, nothing is kept after a call;
//! - matrices are row-major: a pose is 16 numbers (the 4×4 homogeneous matrix, tip to
//!   base), a covariance 36 (6×6, rotation first); `covs` holds `n_covs` of them back to back;
//! - every function returns a status: `PPOE_OK` (0) or an error code, never panics and never
//!   aborts; on an error the outputs are left unwritten;
//! - results are validated: a non-finite pose or covariance is `PPOE_ERR_NON_FINITE`.
//!
//! A chain holds at most [`PPOE_MAX_JOINTS`] joints: the joints and covariances are copied
//! onto the stack for the core crate's types (about 530 B per joint in f64, half in f32).

#![no_std]
#![deny(missing_docs)]
#![allow(non_camel_case_types)]

use core::ffi::c_char;
use ppoe::Error;

/// A status code: `PPOE_OK` or one of the `PPOE_ERR_*` codes.
pub type ppoe_status = i32;

/// Success.
pub const PPOE_OK: ppoe_status = 0;
/// A required pointer is NULL.
pub const PPOE_ERR_NULL_POINTER: ppoe_status = 1;
/// An input contains NaN or ±∞, or a result is not finite.
pub const PPOE_ERR_NON_FINITE: ppoe_status = 2;
/// A covariance is not symmetric within tolerance.
pub const PPOE_ERR_NOT_SYMMETRIC: ppoe_status = 3;
/// A covariance has a negative eigenvalue beyond tolerance.
pub const PPOE_ERR_NOT_POSITIVE_SEMIDEFINITE: ppoe_status = 4;
/// A matrix that must be inverted is singular or not positive definite.
pub const PPOE_ERR_SINGULAR: ppoe_status = 5;
/// A rotation part (the home pose's) is not orthonormal with determinant +1.
pub const PPOE_ERR_NOT_A_ROTATION: ppoe_status = 6;
/// A screw axis whose relevant part (rotation; translation for a prismatic joint) is
/// exactly zero.
pub const PPOE_ERR_ZERO_AXIS: ppoe_status = 7;
/// A collection input is empty.
pub const PPOE_ERR_EMPTY: ppoe_status = 8;
/// Too few samples.
pub const PPOE_ERR_TOO_FEW_SAMPLES: ppoe_status = 9;
/// An output buffer is too small.
pub const PPOE_ERR_BUFFER_TOO_SMALL: ppoe_status = 10;
/// Inputs of mismatched lengths (joint values, covariances and the chain's joints).
pub const PPOE_ERR_LENGTH_MISMATCH: ppoe_status = 11;
/// A joint's displacement constants are not those of its screw axis.
pub const PPOE_ERR_INCONSISTENT_CONSTANTS: ppoe_status = 12;
/// More than `PPOE_MAX_JOINTS` joints.
pub const PPOE_ERR_TOO_MANY_JOINTS: ppoe_status = 13;
/// An enumeration argument (convention, joint kind) has no defined value.
pub const PPOE_ERR_BAD_ENUM: ppoe_status = 14;
/// An error of the core crate this version of the C API does not know.
pub const PPOE_ERR_OTHER: ppoe_status = 15;
/// A result overflowed to infinity or NaN although the inputs were finite (e.g. huge link
/// lengths times large covariances).
pub const PPOE_ERR_OVERFLOW: ppoe_status = 16;
/// A screw axis of nonzero, non-unit length.
pub const PPOE_ERR_NOT_UNIT_AXIS: ppoe_status = 17;
/// A surface grid with fewer than two steps.
pub const PPOE_ERR_GRID_SIZE: ppoe_status = 18;

/// The most joints a chain may have.
pub const PPOE_MAX_JOINTS: u32 = 16;

/// The layout of `ppoe_joint_*` and `ppoe_chain_*` that tables of `ppoe table --lang c` are
/// written for: a table checks it with `#if` and stops the compile with `#error` when the
/// `ppoe.h` it includes has another (or none), so a table and a header from different
/// releases cannot be compiled together.
pub const PPOE_C_TABLE_FORMAT: u32 = 1;

/// Right (local) perturbation of the returned pose, in the tip frame (the default).
pub const PPOE_CONVENTION_RIGHT: i32 = 0;
/// Left (global) perturbation, in the base frame.
pub const PPOE_CONVENTION_LEFT: i32 = 1;
/// pytransform3d's example reproduced exactly (for comparison only: the covariance of
/// neither perturbation).
pub const PPOE_CONVENTION_PYTRANSFORM3D: i32 = 2;

/// A revolute joint (clipped to its limits).
pub const PPOE_JOINT_REVOLUTE: i32 = 0;
/// A continuous joint (not clipped, except by the pytransform3d convention).
pub const PPOE_JOINT_CONTINUOUS: i32 = 1;
/// A prismatic joint.
pub const PPOE_JOINT_PRISMATIC: i32 = 2;

/// One moving joint: `ppoe_joint_f32` in float, `ppoe_joint_f64` in double.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct ppoe_joint<T> {
    /// The joint's name (NUL-terminated; may be NULL; not read by the library).
    pub name: *const c_char,
    /// `PPOE_JOINT_REVOLUTE`, `PPOE_JOINT_CONTINUOUS` or `PPOE_JOINT_PRISMATIC`.
    pub kind: i32,
    /// The screw axis S = (ω, v) in the base frame at the home pose, rotation first.
    pub screw: [T; 6],
    /// The lower limit (may be -INFINITY).
    pub lower: T,
    /// The upper limit (may be INFINITY).
    pub upper: T,
    /// Nonzero: the displacement constants below are given (they must be those of
    /// `screw`, which `ppoe_chain_check_*` verifies); zero: computed at each call.
    pub has_constants: i32,
    /// ‖ω‖.
    pub scale: T,
    /// ω/‖ω‖.
    pub axis: [T; 3],
    /// (ŵy² + ŵz², ŵx² + ŵz², ŵx² + ŵy²).
    pub axis_sq: [T; 3],
    /// (ŵx·ŵy, ŵx·ŵz, ŵy·ŵz).
    pub axis_prod: [T; 3],
    /// v/‖ω‖.
    pub v: [T; 3],
    /// ŵ × v̂.
    pub axis_cross_v: [T; 3],
    /// (ŵ·v̂)·ŵ.
    pub axial_v: [T; 3],
}

/// A serial chain of moving joints, base to tip: `ppoe_chain_f32` in float,
/// `ppoe_chain_f64` in double.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct ppoe_chain<T> {
    /// The base link's name (may be NULL; not read by the library).
    pub base: *const c_char,
    /// The tip link's name (may be NULL; not read by the library).
    pub tip: *const c_char,
    /// `n_joints` joints, base to tip (may be NULL if `n_joints` is 0).
    pub joints: *const ppoe_joint<T>,
    /// The number of moving joints, at most `PPOE_MAX_JOINTS`.
    pub n_joints: u32,
    /// The home pose M (tip to base at θ = 0), row-major 4×4.
    pub home: [[T; 4]; 4],
}

/// A joint in single precision.
pub type ppoe_joint_f32 = ppoe_joint<f32>;
/// A joint in double precision.
pub type ppoe_joint_f64 = ppoe_joint<f64>;
/// A chain in single precision.
pub type ppoe_chain_f32 = ppoe_chain<f32>;
/// A chain in double precision.
pub type ppoe_chain_f64 = ppoe_chain<f64>;

mod api;
mod convert;
pub use api::*;

/// The status of a core error.
fn status(e: Error) -> ppoe_status {
    match e {
        Error::NonFinite => PPOE_ERR_NON_FINITE,
        Error::NotSymmetric => PPOE_ERR_NOT_SYMMETRIC,
        Error::NotPositiveSemidefinite => PPOE_ERR_NOT_POSITIVE_SEMIDEFINITE,
        Error::Singular => PPOE_ERR_SINGULAR,
        Error::NotARotation => PPOE_ERR_NOT_A_ROTATION,
        Error::ZeroAxis => PPOE_ERR_ZERO_AXIS,
        Error::Empty => PPOE_ERR_EMPTY,
        Error::TooFewSamples => PPOE_ERR_TOO_FEW_SAMPLES,
        Error::BufferTooSmall => PPOE_ERR_BUFFER_TOO_SMALL,
        Error::LengthMismatch => PPOE_ERR_LENGTH_MISMATCH,
        Error::InconsistentConstants => PPOE_ERR_INCONSISTENT_CONSTANTS,
        Error::Overflow => PPOE_ERR_OVERFLOW,
        Error::NotUnitAxis => PPOE_ERR_NOT_UNIT_AXIS,
        Error::GridSize => PPOE_ERR_GRID_SIZE,
        _ => PPOE_ERR_OTHER,
    }
}

/// A panic handler for builds that link no other Rust code (feature `panic-handler`).
/// Unreachable in practice: every path of this library returns a status.
#[cfg(feature = "panic-handler")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    #[allow(clippy::empty_loop)]
    loop {}
}

/// The unwinder's personality routine, which the host's precompiled `core` refers to even
/// when this library is built with `panic = "abort"` (its profiles). Nothing here unwinds,
/// so it is never called; defining it lets a C program link the static library with a
/// plain `cc main.c libppoe_ffi.a -lm`, without `--gc-sections`. Bare-metal targets build
/// `core` with `panic = "abort"` and have no such reference.
#[cfg(all(feature = "panic-handler", not(target_os = "none")))]
#[no_mangle]
pub extern "C" fn rust_eh_personality() {}
