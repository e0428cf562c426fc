//! End-to-end check of `ppoe-build`: `build.rs` generates robot tables from URDF files in
//! `test_data/urdf/`, this `#![no_std]` crate includes them exactly as a firmware would, and
//! the tests (`tests/table.rs`) compare the `const` items with the chains `ppoe-build`
//! computes at run time.
//!
//! Tables: [`SEED`] and [`SEED_F32`] (the seed robot of pytransform3d's PPOE example,
//! `linkmount` → `tcp`), [`GANTRY_F32`] (prismatic joints), [`TORSO`] (a single joint),
//! [`GRIPPER`] with [`GRIPPER_COUPLING`] (mimic joints), and
//! [`RANDOM`]: 40 random robots (the `ppoe-test-robots` crate, `robots/`: every joint type, fixed joints between
//! moving ones, rpy everywhere, unnormalised axes, hostile names, extreme finite numbers).
#![no_std]
#![forbid(unsafe_code)]

include!(concat!(env!("OUT_DIR"), "/seed_table.rs"));
include!(concat!(env!("OUT_DIR"), "/gantry_table.rs"));
include!(concat!(env!("OUT_DIR"), "/torso_table.rs"));
// A chain with mimic joints: `GRIPPER`, `GRIPPER_F32` and their `GRIPPER_COUPLING[_F32]`.
include!(concat!(env!("OUT_DIR"), "/gripper_table.rs"));
// The seed robot calibrated by `OUT_DIR/seed_calibrated.json` (issue #27): the folded chain,
// with its noise items.
include!(concat!(env!("OUT_DIR"), "/seed_calibrated_table.rs"));

/// A table generated from a random URDF robot (the `ppoe-test-robots` crate, `robots/`) with the URDF text it came
/// from: the tests parse the text at run time and compare.
pub struct RandomTable {
    /// The URDF text.
    pub urdf: &'static str,
    /// The base link.
    pub base: &'static str,
    /// The tip link.
    pub tip: &'static str,
    /// The f64 table.
    pub f64: ppoe::chain::ChainView<'static, f64>,
    /// The f32 table, when every value fits in f32.
    pub f32: Option<ppoe::chain::ChainView<'static, f32>>,
}

#[allow(missing_docs, clippy::all)] // generated: every table has its own doc comment
mod random {
    use super::RandomTable;
    include!(concat!(env!("OUT_DIR"), "/random_tables.rs"));
}
pub use random::{RANDOM, RANDOM_REJECTED};

// Generated; only HOSTILE is used (the other items are there to be compiled).
#[allow(missing_docs, dead_code, clippy::all)]
mod hostile {
    include!(concat!(env!("OUT_DIR"), "/hostile_tables.rs"));
}
/// The seed robot's table once per hostile string of `ppoe_test_robots::hostile` (in every
/// name and file name, and in a noise model baked in): (string, table, f32 noise).
pub use hostile::HOSTILE;

/// The tables are usable in constant expressions (no parsing, no allocation).
const _: () = {
    assert!(SEED.joints.len() == 6);
    assert!(SEED_F32.joints.len() == 6);
    assert!(TORSO.joints.len() == 1);
};

/// A `static` built from a table, as firmware might place it in flash.
pub static SEED_IN_FLASH: ppoe::chain::Chain<f32, 6> = SEED_F32;
