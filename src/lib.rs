//! # ppoe — the Probabilistic Product of Exponentials, for microcontrollers
//!
//! Given the joint coordinates of a serial robot and a 6×6 covariance per joint, ppoe
//! returns the end-effector pose **and its 6×6 covariance** in the tangent space of
//! SE(3) (Meyer, Strobl & Triebel, IROS 2022), plus the uncertainty algebra of
//! pytransform3d's `uncertainty` module it is built on.
//!
//! * `#![no_std]`, no allocator, fixed-size types, no panics on any input.
//! * Generic over `f32` and `f64` through one trait, [`Real`].
//! * Exponential coordinates and covariances are **rotation first**: ξ = (ω, v).
//!
//! | module | concept |
//! |---|---|
//! | [`scalar`] | the [`Real`] trait and its precision-dependent constants |
//! | [`linalg`] | fixed-size vectors and matrices |
//! | [`so3`] | rotations: hat/vee, exp, log, Jacobians |
//! | [`se3`] | rigid transforms: exp, log, adjoint, Jacobians, screw axes |
//! | [`uncertainty`] | uncertain transforms: concatenation, inversion, fusion, estimation |
//! | [`ellipsoid`] | symmetric eigen-decomposition and equiprobable ellipsoids |
//!
//! ```
//! use ppoe::{se3, Mat6, Transform, Vec6};
//! use ppoe::uncertainty::{concat_globally, Order};
//!
//! let a2b: Transform<f64> = se3::exp(&Vec6::from([0.1, 0.0, 0.3, 1.0, 0.0, 0.0]));
//! let b2c: Transform<f64> = se3::exp(&Vec6::from([0.0, 0.2, 0.0, 0.0, 0.5, 0.0]));
//! let cov = Mat6::<f64>::identity() * 1e-3;
//! // Left (global) perturbation: T = Exp(ξ)·T̄, ξ ~ N(0, Σ) in the output frame.
//! let (a2c, cov_a2c) = concat_globally(&a2b, &cov, &b2c, &cov, Order::Fourth);
//! assert!((a2c.translation.0[1] - (b2c * a2b).translation.0[1]).abs() < 1e-15);
//! assert!(cov_a2c.0[0][0] > 1.9e-3); // both rotation variances add up
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod chain;
pub mod ellipsoid;
pub mod error;
pub mod linalg;
pub mod rank1;
pub mod scalar;
pub mod se3;
pub mod so3;
pub mod uncertainty;

pub use error::Error;
pub use linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
pub use scalar::Real;
pub use se3::Transform;

/// The README's code blocks, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
