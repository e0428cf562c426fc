//! Kinematic chains: the joints from a base link to a tip link and the home pose of the
//! tip; rigid forward kinematics, Jacobians, the checks of the chain itself, and the PPOE
//! (the methods `ppoe`, `ppoe_checked`, `ppoe_fourth_order` and `ppoe_rank1*` of
//! [`Chain`] and [`ChainView`], with [`Convention`] and [`UncertainPose`]), and the joint
//! model ([`Joint`], [`JointKind`], the noise models [`screw_noise`] and
//! [`bending_noise`]), and calibrated kinematics folded into a chain
//! ([`fold_calibration`]), and mimic joints, whose values follow other joints'
//! ([`Coupling`], [`JointSource`], [`Mimic`]). They are defined in private modules, one per concept (the joint,
//! the chain's kinematics, the PPOE); this module is their one public door.
//!
//! Frames: screw axes and the space Jacobian are in the base frame, the body Jacobian and
//! the PPOE's default ([`Convention::Right`]) covariance in the tip frame; everything is
//! rotation first. The crate-level example and [`Chain::ppoe`] show the PPOE.
//!
//! ```
//! use ppoe::chain::{Chain, Joint, JointKind};
//! use ppoe::Transform;
//! const INF: f64 = f64::INFINITY;
//! // A planar arm: joints about z through x = 0 and x = 0.5, tip at x = 1 at home.
//! const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
//!     Joint::new("shoulder", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
//!     Joint::new("elbow", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
//! ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
//! // The tip pose at θ = (0.3, −0.2): links of 0.5 at angles 0.3 and 0.1.
//! let tip = ARM.forward_kinematics(&[0.3, -0.2]);
//! let x = 0.5 * 0.3_f64.cos() + 0.5 * 0.1_f64.cos();
//! assert!((tip.translation.0[0] - x).abs() < 1e-15);
//! assert!(ARM.as_ref().check().is_ok()); // unit axes, valid home pose
//! ```

pub use crate::calibration::fold_calibration;
pub use crate::joint::{bending_noise, screw_noise, Joint, JointConstants, JointKind};
pub use crate::kinematics::{Chain, ChainView};
pub use crate::mimic::{Coupling, JointSource, Mimic};
pub use crate::ppoe::{dense_covariances, BatchError, Convention, UncertainPose};
