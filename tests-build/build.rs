//! Generates the robot tables this crate includes, exactly as a firmware's build script
//! would.

use ppoe_build::{Config, Scalar};

fn main() -> Result<(), ppoe_build::Error> {
    // The seed robot of pytransform3d's PPOE example, both scalar types.
    Config::new("../test_data/urdf/seed.urdf")
        .base("linkmount")
        .tip("tcp")
        .joints(["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"])
        .scalar(Scalar::Both)
        .name("SEED")
        .write_to_out_dir("seed_table.rs")?;

    // A gantry with prismatic joints and an oblique slide, f32 only, default joint list.
    Config::new("../test_data/urdf/prismatic.urdf")
        .base("base_link")
        .tip("tool0")
        .scalar(Scalar::F32)
        .name("GANTRY")
        .write_to_out_dir("gantry_table.rs")?;

    // One joint of a branch of the tree (a single-joint table).
    Config::new("../test_data/urdf/tree.urdf")
        .base("base_footprint")
        .tip("torso")
        .name("TORSO")
        .write_to_out_dir("torso_table.rs")?;
    Ok(())
}
