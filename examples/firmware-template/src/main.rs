//! The PPOE on a Cortex-M core: the tool pose of the arm in `robot.urdf` and its 6×6
//! covariance, for joint angles read with 0.01 rad of noise (1σ), printed over semihosting.
//!
//! Replace the fixed angles with your encoder readings and the noise with your joints'
//! (see `ppoe::chain::screw_noise` for encoder noise, `bending_noise` for a link that
//! bends); keep `ppoe_checked` (it reports bad input instead of returning garbage).

#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;
use ppoe::chain::{screw_noise, Convention};

// ARM_F32: ppoe::chain::Chain<f32, 3>, generated from robot.urdf by build.rs.
include!(concat!(env!("OUT_DIR"), "/arm.rs"));

/// Encoder noise of every joint: variance of the joint angle, rad² (σ = 0.01 rad).
const ENCODER_VARIANCE: f32 = 1e-4;

#[entry]
fn main() -> ! {
    let thetas = [0.3f32, -0.6, 0.9];
    let covs = ARM_F32
        .joints
        .map(|j| screw_noise(&j.screw, ENCODER_VARIANCE));

    // Right convention: T = T̄·Exp(η), η ~ N(0, Σ), η = (rotation, translation) in the tool
    // frame.
    match ARM_F32.ppoe_checked(&thetas, &covs, Convention::Right) {
        Ok(tool) => {
            hprintln!("thetas: {:?}", thetas);
            for row in tool.pose.to_matrix4() {
                hprintln!("pose: {:e} {:e} {:e} {:e}", row[0], row[1], row[2], row[3]);
            }
            for row in tool.cov.0 {
                hprintln!(
                    "cov: {:e} {:e} {:e} {:e} {:e} {:e}",
                    row[0],
                    row[1],
                    row[2],
                    row[3],
                    row[4],
                    row[5]
                );
            }
            hprintln!("ppoe-firmware-template: ok");
            debug::exit(debug::EXIT_SUCCESS);
        }
        Err(e) => {
            hprintln!("ppoe-firmware-template: error: {:?}", e);
            debug::exit(debug::EXIT_FAILURE);
        }
    }
    loop {}
}
