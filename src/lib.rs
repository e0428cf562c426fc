//! # ppoe — the Probabilistic Product of Exponentials, for microcontrollers
//!
//! Given the joint coordinates of a serial robot and a 6×6 covariance per joint, ppoe
//! returns the end-effector pose **and its 6×6 covariance** in the tangent space of
//! SE(3) (Meyer, Strobl & Triebel, IROS 2022), plus the uncertainty algebra of
//! pytransform3d's `uncertainty` module it is built on.
//!
//! * `#![no_std]`, no allocator, fixed-size types, no `unsafe`. No function is meant to
//!   panic. A link-time check on Cortex-M4F (run by the repository's CI, see the README)
//!   *proves* the public
//!   entry points of `so3`, `se3`, `uncertainty`, `chain` (the PPOE included) and the
//!   eigen-decomposition panic-free in f32 and f64; the surface grids (`lift_surface`,
//!   `marginal_surface`, `surface_grid`, `to_projected_ellipsoid*`, `LiftSurface::grid`)
//!   keep bounds checks the compiler cannot remove and are only fuzzed (FUZZING.md,
//!   shipped with this package),
//!   which finds panics but proves their absence for none.
//!   Checked functions return an [`Error`] for bad input and for results that are not
//!   finite.
//! * Generic over `f32` and `f64` through one trait, [`Real`].
//! * Exponential coordinates and covariances are **rotation first**: ξ = (ω, v).
//!
//! | module | concept |
//! |---|---|
//! | [`scalar`] | the [`Real`] trait and its precision-dependent constants |
//! | [`linalg`] | fixed-size vectors and matrices, Cholesky, the symmetric eigen-solver |
//! | [`so3`] | rotations: hat/vee, exp, log, Jacobians |
//! | [`rotation_forms`] | quaternions `[w, x, y, z]` and URDF roll-pitch-yaw to and from rotations |
//! | [`se3`] | rigid transforms: exp, log, adjoint, Jacobians, screw axes |
//! | [`uncertainty`] | uncertain transforms: concatenation, inversion, fusion, estimation |
//! | [`chain`] | the joint model, kinematic chains (forward kinematics, Jacobians, checks) and the PPOE |
//! | [`surface`] | equiprobable surfaces of an uncertain tool position, for drawing |
//! | [`error`] | the error type of the checked entry points |
//! | [`interop`] | ROS covariance order; optional `mint`, `nalgebra`, `serde`, `defmt`, `arbitrary` support |
//!
//! The PPOE of a two-joint arm held in a `const` item (what `ppoe-build` generates from
//! a URDF): the tip pose and the covariance of its right perturbation `T = T̄·Exp(η)`,
//! η in the tip frame, rotation first.
//!
//! ```
//! use ppoe::chain::{screw_noise, Chain, Convention, Joint, JointKind};
//! use ppoe::Transform;
//!
//! const INF: f64 = f64::INFINITY;
//! // A planar arm: joints about z through x = 0 and x = 0.5 (screw axes in the base
//! // frame, rotation first), tip at x = 1 at the home pose.
//! const ARM: Chain<f64, 2> = Chain::new(
//!     "base",
//!     "tip",
//!     [
//!         Joint::new("shoulder", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
//!         Joint::new("elbow", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
//!     ],
//!     Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]),
//! );
//! // Joint-value noise: σ = 0.01 rad on each joint.
//! let covs = ARM.joints.map(|j| screw_noise(&j.screw, 1e-4));
//! let tip = ARM.ppoe_checked(&[0.3, -0.2], &covs, Convention::Right)?;
//! // The mean is the rigid forward kinematics: links of 0.5 at angles 0.3 and 0.1.
//! let x = 0.5 * 0.3f64.cos() + 0.5 * 0.1f64.cos();
//! assert!((tip.pose.translation.0[0] - x).abs() < 1e-12);
//! // Both joints turn the tip about parallel z axes: their yaw variances add up.
//! assert!((tip.cov.0[2][2] - 2e-4).abs() < 1e-18);
//! # Ok::<(), ppoe::Error>(())
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod calibration;
pub mod chain;
mod checks;
pub mod error;
pub mod interop;
mod joint;
mod kinematics;
pub mod linalg;
mod mimic;
mod ppoe;
pub mod rotation_forms;
pub mod scalar;
pub mod se3;
pub mod so3;
pub mod surface;
pub mod uncertainty;

// The types nearly every call names, also at the root. The rest of `linalg` (the
// eigen-solver, Cholesky) has one door, `ppoe::linalg`.
pub use error::Error;
pub use linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
pub use scalar::Real;
pub use se3::Transform;

/// The format of the robot tables `ppoe-build` generates for this crate (the items and
/// constructors they call: `Chain::new`, `Joint::…`, the noise items). It is raised when
/// that form changes; every generated Rust table starts with
/// `const _: () = assert!(ppoe::TABLE_FORMAT == N, "…");`, `N` the format of the `ppoe`
/// that `ppoe-build` was built with, so a table compiled against a `ppoe` of another
/// format fails to build with a message saying so instead of compiling into something
/// else.
///
/// ```compile_fail
/// // What a table generated for another format does (here: one format ahead).
/// const _: () = assert!(ppoe::TABLE_FORMAT == ppoe::TABLE_FORMAT + 1, "mismatched ppoe");
/// ```
pub const TABLE_FORMAT: u32 = 1;

/// The README's code blocks, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
