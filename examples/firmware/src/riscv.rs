//! RISC-V glue of the test firmware (QEMU `virt`, machine mode, `-bios none`): startup,
//! semihosting output and exit, the instruction counter, the stack pointer, the panic
//! handler. Written out here rather than taken from riscv-rt / riscv-semihosting: the
//! firmware needs only these few lines, and the linker script (memory/riscv-virt.x) is
//! ours too.

use core::fmt::Write;

// Startup: QEMU's reset vector jumps to the start of RAM (0x8000_0000), where the linker
// script puts `.text.start`. Set gp and sp, zero .bss (.data is loaded with the ELF image,
// everything lives in RAM), turn the FPU on (mstatus.FS = initial; harmless on a soft-float
// build), call `main`.
core::arch::global_asm!(
    ".section .text.start, \"ax\"",
    ".globl _start",
    "_start:",
    ".option push",
    ".option norelax",
    "la gp, __global_pointer$",
    ".option pop",
    "la sp, __stack_top",
    "la t0, __sbss",
    "la t1, __ebss",
    "1: bgeu t0, t1, 2f",
    "sw zero, 0(t0)",
    "addi t0, t0, 4",
    "j 1b",
    "2: li t0, 0x2000",
    "csrs mstatus, t0",
    "call main",
    "3: j 3b",
);

/// Instructions per counter tick: `instret` counts instructions (under `-icount` QEMU
/// derives it from the instruction count).
pub const INSNS_PER_TICK: u32 = 1;

/// The counter's name in the firmware's output (the report parses it).
pub const COUNTER: &str = "instret";

const SYS_WRITE0: usize = 0x04;
const SYS_EXIT: usize = 0x18;
const ADP_STOPPED_APPLICATION_EXIT: usize = 0x2_0026;
const ADP_STOPPED_RUNTIME_ERROR_UNKNOWN: usize = 0x2_0023;

/// A semihosting call: the `slli`/`ebreak`/`srai` sequence QEMU recognises, uncompressed
/// and within one 16-byte block.
fn semihost(op: usize, arg: usize) -> usize {
    let r: usize;
    // SAFETY: the sequence traps to QEMU, which reads a0/a1 and the memory `arg` points
    // to (a NUL-terminated string for SYS_WRITE0), and writes a0.
    unsafe {
        core::arch::asm!(
            ".balign 16",
            ".option push",
            ".option norvc",
            "slli x0, x0, 0x1f",
            "ebreak",
            "srai x0, x0, 7",
            ".option pop",
            inout("a0") op => r,
            in("a1") arg,
            options(nostack),
        );
    }
    r
}

/// Output through a buffer: SYS_WRITE0 per 127 bytes.
struct Out {
    buf: [u8; 128],
    len: usize,
}

impl Out {
    fn flush(&mut self) {
        if self.len > 0 {
            self.buf[self.len] = 0;
            semihost(SYS_WRITE0, self.buf.as_ptr() as usize);
            self.len = 0;
        }
    }
}

impl Write for Out {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        for &b in s.as_bytes() {
            if self.len == self.buf.len() - 1 {
                self.flush();
            }
            self.buf[self.len] = b;
            self.len += 1;
        }
        Ok(())
    }
}

/// Prints one line over semihosting.
pub fn println(args: core::fmt::Arguments<'_>) {
    let mut out = Out {
        buf: [0; 128],
        len: 0,
    };
    let _ = out.write_fmt(args);
    let _ = out.write_str("\n");
    out.flush();
}

/// Exits QEMU: status 0 if `ok`, 1 otherwise (32-bit semihosting passes only the reason).
pub fn exit(ok: bool) -> ! {
    let reason = if ok {
        ADP_STOPPED_APPLICATION_EXIT
    } else {
        ADP_STOPPED_RUNTIME_ERROR_UNKNOWN
    };
    semihost(SYS_EXIT, reason);
    #[allow(clippy::empty_loop)]
    loop {}
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    println(format_args!("panic: {}", info));
    exit(false)
}

/// `instret` for `reps` calls of `f` (low 32 bits).
pub fn ticks_total(reps: u32, mut f: impl FnMut()) -> u32 {
    let s0 = instret();
    for _ in 0..reps {
        f();
    }
    instret().wrapping_sub(s0)
}

#[inline(always)]
fn instret() -> u32 {
    let r: u32;
    // SAFETY: reads a counter CSR, no side effects.
    unsafe { core::arch::asm!("csrr {}, minstret", out(reg) r, options(nomem, nostack)) };
    r
}

/// The current stack pointer.
#[inline(always)]
pub fn stack_pointer() -> usize {
    let sp: usize;
    // SAFETY: reads sp.
    unsafe { core::arch::asm!("mv {}, sp", out(reg) sp, options(nomem, nostack)) };
    sp
}

extern "C" {
    /// End of .bss (memory/riscv-virt.x): the stack grows down towards it.
    static mut __sheap: u32;
}

/// The lowest address the stack may grow to.
pub fn stack_floor() -> usize {
    core::ptr::addr_of_mut!(__sheap) as usize
}
