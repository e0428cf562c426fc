//! Interoperability with the rest of the ecosystem.
//!
//! Always available: [`ros`], ROS's `PoseWithCovariance` covariance order and frame.
//! Behind optional features, all off by default (the default build depends on
//! num-traits, libm, heapless and approx only):
//!
//! | feature | what it adds |
//! |---|---|
//! | `mint` | `From`/`TryFrom` conversions with the `mint` interchange types (`mint` module) |
//! | `nalgebra` | conversions with nalgebra's `SVector`, `SMatrix` and `Isometry3` (`nalgebra` module) |
//! | `serde` | hand-written `Serialize`/`Deserialize` that validate what they read (`serde` module) |
//! | `defmt` | `defmt::Format` for firmware logging without `core::fmt` (`defmt` module) |
//! | `arbitrary` | `arbitrary::Arbitrary` producing *valid* rotations, transforms, covariances and chains (`arbitrary` module) |
//!
//! The trait implementations live in these modules; they add no item to the types' own
//! modules, so the types read the same with or without the features.
//!
//! ```
//! use ppoe::interop::ros::{from_ros_order, to_ros_order};
//! use ppoe::{Mat6, Vector};
//! // ppoe's rotation-first variances (rot x, y, z, then x, y, z) in ROS's order.
//! let cov = Mat6::from_diagonal(&Vector([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]));
//! let ros = to_ros_order(&cov);
//! assert_eq!(ros.diagonal(), Vector([4.0, 5.0, 6.0, 1.0, 2.0, 3.0]));
//! assert_eq!(from_ros_order(&ros), cov); // a permutation: exact both ways
//! ```

#[cfg(feature = "arbitrary")]
pub mod arbitrary;
#[cfg(feature = "defmt")]
pub mod defmt;
#[cfg(feature = "mint")]
pub mod mint;
#[cfg(feature = "nalgebra")]
pub mod nalgebra;
pub mod ros;
#[cfg(feature = "serde")]
pub mod serde;
