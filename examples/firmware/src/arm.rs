//! Cortex-M glue of the test firmware: semihosting output and exit, the SysTick counter,
//! the stack pointer. Startup and the panic handler come from cortex-m-rt and
//! panic-semihosting (a panic exits QEMU with status 1).

use cortex_m::peripheral::{syst::SystClkSource, SYST};
use panic_semihosting as _;

pub use cortex_m_rt::entry;

/// Instructions per counter tick under `qemu -icount shift=0` on the mps2 boards: one
/// instruction is 1 ns of guest time and SysTick runs on the 25 MHz core clock. Other
/// boards (microbit, lm3s6965evb) clock SysTick differently: their counts are not reported.
pub const INSNS_PER_TICK: u32 = 40;

/// The counter's name in the firmware's output (the report parses it).
pub const COUNTER: &str = "systick ticks";

/// Prints one line over semihosting.
pub fn println(args: core::fmt::Arguments<'_>) {
    cortex_m_semihosting::hprintln!("{}", args);
}

/// Exits QEMU: status 0 if `ok`, 1 otherwise.
pub fn exit(ok: bool) -> ! {
    use cortex_m_semihosting::debug;
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    #[allow(clippy::empty_loop)]
    loop {}
}

/// SysTick ticks (core clock) for `reps` calls of `f`; 24 bits, so at most 16.7 M ticks.
pub fn ticks_total(reps: u32, mut f: impl FnMut()) -> u32 {
    // SAFETY: single-threaded firmware, no interrupt handlers use SysTick.
    let mut cp = unsafe { cortex_m::Peripherals::steal() };
    cp.SYST.set_clock_source(SystClkSource::Core);
    cp.SYST.set_reload(0x00FF_FFFF);
    cp.SYST.clear_current();
    cp.SYST.enable_counter();
    let s0 = SYST::get_current();
    for _ in 0..reps {
        f();
    }
    let s1 = SYST::get_current();
    cp.SYST.disable_counter();
    s0.wrapping_sub(s1) & 0x00FF_FFFF
}

/// The current stack pointer.
#[inline(always)]
pub fn stack_pointer() -> usize {
    cortex_m::register::msp::read() as usize
}

extern "C" {
    /// End of .bss/.uninit (cortex-m-rt's linker script): the stack grows down towards it.
    static mut __sheap: u32;
}

/// The lowest address the stack may grow to.
pub fn stack_floor() -> usize {
    core::ptr::addr_of_mut!(__sheap) as usize
}
