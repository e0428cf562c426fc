//! Panic-freedom proof for the PPOE path (the technique of the `panic-never` crate).
//!
//! This firmware calls the seed robot's 6-DOF PPOE in f32 and f64 on opaque inputs
//! (`black_box`) and nothing else that could panic. Its panic handler calls a function that
//! does not exist, so the link fails ("undefined symbol:
//! ppoe_panic_path_survived_optimisation") if any panic path of the PPOE survives
//! optimisation (release profile: opt-level s, LTO). Built only with `--features
//! panic-never` (scripts/firmware.sh does it for the M4F); running it exits QEMU with 0.

#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug;
use ppoe::chain::Convention;
use ppoe::{Mat6, Matrix};

include!(concat!(env!("OUT_DIR"), "/seed_table.rs"));

extern "C" {
    /// Deliberately undefined: referenced only from the panic handler.
    fn ppoe_panic_path_survived_optimisation() -> !;
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: never defined, so never called: the link fails if this handler is reachable.
    unsafe { ppoe_panic_path_survived_optimisation() }
}

#[entry]
fn main() -> ! {
    let th64: [f64; 6] = black_box([0.5, -0.3, 1.2, 0.1, -2.0, 3.0]);
    let covs64: [Mat6<f64>; 6] = black_box([Matrix([[1e-3; 6]; 6]); 6]);
    let th32: [f32; 6] = black_box([0.5, -0.3, 1.2, 0.1, -2.0, 3.0]);
    let covs32: [Mat6<f32>; 6] = black_box([Matrix([[1e-3; 6]; 6]); 6]);
    black_box(SEED.ppoe(&th64, &covs64, Convention::Right));
    black_box(SEED.ppoe(&th64, &covs64, black_box(Convention::Left)));
    black_box(SEED_F32.ppoe(&th32, &covs32, Convention::Right));
    black_box(SEED_F32.ppoe(&th32, &covs32, black_box(Convention::Left)));
    debug::exit(debug::EXIT_SUCCESS);
    #[allow(clippy::empty_loop)]
    loop {}
}
