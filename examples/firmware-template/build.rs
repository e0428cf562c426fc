//! Build script (runs on the host): generates the robot's kinematic table from `robot.urdf`
//! with ppoe-build, and puts `memory.x` where cortex-m-rt's `link.x` finds it.

use std::error::Error;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn Error>> {
    // ARM_F32: ppoe::chain::Chain<f32, 3>, a const: the device never parses URDF.
    // Scalar::F64 (ARM) or Scalar::Both for f64 tables; f32 suits cores with an f32 FPU.
    ppoe_build::Config::new("robot.urdf")
        .base("base_link")
        .tip("tool0")
        .scalar(ppoe_build::Scalar::F32)
        .name("ARM")
        .write_to_out_dir("arm.rs")?; // also prints cargo:rerun-if-changed=robot.urdf

    let out = PathBuf::from(std::env::var_os("OUT_DIR").ok_or("OUT_DIR is not set")?);
    std::fs::write(out.join("memory.x"), include_bytes!("memory.x"))?;
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    Ok(())
}
