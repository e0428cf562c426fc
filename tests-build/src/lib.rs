//! End-to-end check of `ppoe-build`: `build.rs` generates robot tables from URDF files in
//! `test_data/urdf/`, this `#![no_std]` crate includes them exactly as a firmware would, and
//! the tests (`tests/table.rs`) compare the `const` items with the chains `ppoe-build`
//! computes at run time.
//!
//! Tables: [`SEED`] and [`SEED_F32`] (the seed robot of pytransform3d's PPOE example,
//! `linkmount` → `tcp`), [`GANTRY_F32`] (prismatic joints), [`TORSO`] (a single joint).
#![no_std]
#![forbid(unsafe_code)]

include!(concat!(env!("OUT_DIR"), "/seed_table.rs"));
include!(concat!(env!("OUT_DIR"), "/gantry_table.rs"));
include!(concat!(env!("OUT_DIR"), "/torso_table.rs"));

/// The tables are usable in constant expressions (no parsing, no allocation).
const _: () = {
    assert!(SEED.joints.len() == 6);
    assert!(SEED_F32.joints.len() == 6);
    assert!(TORSO.joints.len() == 1);
};

/// A `static` built from a table, as firmware might place it in flash.
pub static SEED_IN_FLASH: ppoe::chain::Chain<f32, 6> = SEED_F32;
