//! ppoe on a microcontroller core: the seed robot's PPOE in f64 and f32, dense and rank-one
//! (`ppoe_rank1`), against expectations computed on the host at build time (see build.rs;
//! the rank-one cases are expected from the dense PPOE of their screw-noise covariances).
//! Prints a summary over semihosting and exits QEMU with status 0 if every case matches, 1
//! otherwise (a panic exits with 1 too). Cortex-M (src/arm.rs) and RISC-V (src/riscv.rs)
//! share this file.
//!
//! Tolerances (`max|a−b| / max(1, max|b|)` over the pose's 4×4 and, separately, the 6×6
//! covariance): f64 ≤ 1e-12, f32 ≤ 1e-5 (the project's documented bounds, README
//! "Accuracy").

#![no_std]
#![no_main]

#[cfg(target_arch = "arm")]
#[path = "arm.rs"]
mod platform;
#[cfg(target_arch = "riscv32")]
#[path = "riscv.rs"]
mod platform;

use core::hint::black_box;
use ppoe::chain::{Convention, UncertainPose};
use ppoe::{se3, uncertainty, Mat6, Matrix, Real, Transform, Vec6, Vector};

/// `hprintln!` on every platform.
macro_rules! hprintln {
    ($($arg:tt)*) => { platform::println(format_args!($($arg)*)) };
}

// SEED: Chain<f64, 6> and SEED_F32: Chain<f32, 6>, generated from the URDF by ppoe-build.
include!(concat!(env!("OUT_DIR"), "/seed_table.rs"));

/// One test case and its host-computed PPOE (right convention).
pub struct Case {
    name: &'static str,
    thetas: [f64; 6],
    covs: [[[f64; 6]; 6]; 6],
    pose: [[f64; 4]; 4],
    cov: [[f64; 6]; 6],
}

// EXPECTED: [Case; K]
include!(concat!(env!("OUT_DIR"), "/expected.rs"));

/// One rank-one case (a variance per joint value) and its expected PPOE (right convention):
/// the dense PPOE of the covariances `σᵢ²·SᵢSᵢᵀ` on the host.
pub struct Rank1Case {
    name: &'static str,
    thetas: [f64; 6],
    sigma2: [f64; 6],
    pose: [[f64; 4]; 4],
    cov: [[f64; 6]; 6],
}

// EXPECTED_RANK1: [Rank1Case; K]
include!(concat!(env!("OUT_DIR"), "/expected_rank1.rs"));

const TOL_F64: f64 = 1e-12;
const TOL_F32: f64 = 1e-5;

/// The f64 PPOE as a symbol of its own (nm, instruction counts).
#[inline(never)]
#[no_mangle]
pub fn ppoe_seed_f64(thetas: &[f64; 6], covs: &[Mat6<f64>; 6]) -> UncertainPose<f64> {
    SEED.ppoe(thetas, covs, Convention::Right)
}

/// The f32 PPOE as a symbol of its own (nm, instruction counts).
#[inline(never)]
#[no_mangle]
pub fn ppoe_seed_f32(thetas: &[f32; 6], covs: &[Mat6<f32>; 6]) -> UncertainPose<f32> {
    SEED_F32.ppoe(thetas, covs, Convention::Right)
}

/// The f64 rank-one PPOE as a symbol of its own (nm, instruction counts, code size).
#[inline(never)]
#[no_mangle]
pub fn ppoe_seed_rank1_f64(thetas: &[f64; 6], sigma2: &[f64; 6]) -> UncertainPose<f64> {
    SEED.ppoe_rank1(thetas, sigma2, Convention::Right)
}

/// The f32 rank-one PPOE as a symbol of its own (nm, instruction counts, code size).
#[inline(never)]
#[no_mangle]
pub fn ppoe_seed_rank1_f32(thetas: &[f32; 6], sigma2: &[f32; 6]) -> UncertainPose<f32> {
    SEED_F32.ppoe_rank1(thetas, sigma2, Convention::Right)
}

/// `se3::exp` in f64 / f32 as symbols of their own (instruction counts only).
#[inline(never)]
#[no_mangle]
pub fn ppoe_exp_f64(xi: &Vec6<f64>) -> Transform<f64> {
    se3::exp(xi)
}

#[inline(never)]
#[no_mangle]
pub fn ppoe_exp_f32(xi: &Vec6<f32>) -> Transform<f32> {
    se3::exp(xi)
}

/// `se3::log` in f64 / f32 (instruction counts only).
#[inline(never)]
#[no_mangle]
pub fn ppoe_log_f64(t: &Transform<f64>) -> Vec6<f64> {
    se3::log(t)
}

#[inline(never)]
#[no_mangle]
pub fn ppoe_log_f32(t: &Transform<f32>) -> Vec6<f32> {
    se3::log(t)
}

/// `uncertainty::concat_globally`, second order, f64 / f32 (instruction counts only).
#[inline(never)]
#[no_mangle]
pub fn ppoe_concat_f64(
    a: &Transform<f64>,
    ca: &Mat6<f64>,
    b: &Transform<f64>,
    cb: &Mat6<f64>,
) -> (Transform<f64>, Mat6<f64>) {
    uncertainty::concat_globally(a, ca, b, cb, uncertainty::Order::Second)
}

#[inline(never)]
#[no_mangle]
pub fn ppoe_concat_f32(
    a: &Transform<f32>,
    ca: &Mat6<f32>,
    b: &Transform<f32>,
    cb: &Mat6<f32>,
) -> (Transform<f32>, Mat6<f32>) {
    uncertainty::concat_globally(a, ca, b, cb, uncertainty::Order::Second)
}

/// Cost of the small ops (exp, log, second-order concat) in one scalar type: counter ticks
/// for `REPS` = 64 calls each, `[exp, log, concat]`; under -icount shift=0, instructions
/// per call = ticks × [`platform::INSNS_PER_TICK`] / 64 (see [`ticks_per_call`]).
fn op_ticks<T: Real>(
    exp: fn(&Vec6<T>) -> Transform<T>,
    log: fn(&Transform<T>) -> Vec6<T>,
    concat: fn(&Transform<T>, &Mat6<T>, &Transform<T>, &Mat6<T>) -> (Transform<T>, Mat6<T>),
) -> [u32; 3] {
    const REPS: u32 = 64;
    let xi = Vector([0.3, -0.2, 0.5, 0.4, 0.1, -0.3].map(T::lit));
    let xi2 = Vector([-0.6, 0.1, 0.2, 0.0, 0.7, 0.2].map(T::lit));
    let (a, b) = (se3::exp(&xi), se3::exp(&xi2));
    let cov = Mat6::from_diagonal(&Vector([1e-3, 2e-3, 5e-4, 1e-3, 3e-3, 2e-3].map(T::lit)));
    [
        ticks_total(REPS, || {
            black_box(exp(black_box(&xi)));
        }),
        ticks_total(REPS, || {
            black_box(log(black_box(&a)));
        }),
        ticks_total(REPS, || {
            black_box(concat(
                black_box(&a),
                black_box(&cov),
                black_box(&b),
                black_box(&cov),
            ));
        }),
    ]
}

fn abs(x: f64) -> f64 {
    if x < 0.0 {
        -x
    } else {
        x
    }
}

/// `max|a−b| / max(1, max|b|)`; +∞ if anything is NaN.
fn rel_err<const R: usize, const C: usize>(a: &[[f64; C]; R], b: &[[f64; C]; R]) -> f64 {
    let (mut num, mut den) = (0.0f64, 1.0f64);
    for (ra, rb) in a.iter().zip(b) {
        for (&x, &y) in ra.iter().zip(rb) {
            let d = abs(x - y);
            if d.is_nan() {
                return f64::INFINITY;
            }
            if d > num {
                num = d;
            }
            if abs(y) > den {
                den = abs(y);
            }
        }
    }
    num / den
}

fn to_f64<const R: usize, const C: usize>(m: &[[f32; C]; R]) -> [[f64; C]; R] {
    m.map(|row| row.map(f64::from))
}

/// Error of a result (`pose`, `cov`) against an expectation (`want`): the worse of pose
/// and covariance.
fn case_err(
    pose: &[[f64; 4]; 4],
    cov: &[[f64; 6]; 6],
    want: (&[[f64; 4]; 4], &[[f64; 6]; 6]),
) -> f64 {
    let (ep, ec) = (rel_err(pose, want.0), rel_err(cov, want.1));
    if ep > ec || ep.is_nan() {
        ep
    } else {
        ec
    }
}

/// Counter ticks per call of `f`, averaged over `reps` calls; instructions =
/// ticks × [`platform::INSNS_PER_TICK`] under `qemu -icount shift=0` (meaningless without).
fn ticks_per_call(reps: u32, f: impl FnMut()) -> u32 {
    platform::ticks_total(reps, f) / reps
}

/// Counter ticks for `reps` calls of `f` (see [`ticks_per_call`]).
fn ticks_total(reps: u32, f: impl FnMut()) -> u32 {
    platform::ticks_total(reps, f)
}

const PAINT: u32 = 0x5AFE_C0DE;

/// Stack bytes used by `f` (high-water mark): paints the free stack below the current
/// stack pointer, runs `f`, and finds the lowest word that changed.
#[inline(never)]
fn stack_used(f: impl FnOnce()) -> usize {
    let lo = platform::stack_floor();
    let sp = platform::stack_pointer();
    let hi = sp - 256; // leave this function's own frame and the painting loop alone
    let mut p = (lo + 3) & !3;
    while p < hi {
        // SAFETY: [stack floor, sp - 256) is free stack memory, word aligned.
        unsafe { (p as *mut u32).write_volatile(PAINT) };
        p += 4;
    }
    f();
    let mut p = (lo + 3) & !3;
    // SAFETY: as above; reads only.
    while p < hi && unsafe { (p as *const u32).read_volatile() } == PAINT {
        p += 4;
    }
    sp - p
}

/// One line with the bits of an f32 result (pose 4×4 then covariance 6×6, row-major, as
/// hex words): scripts/firmware.sh compares these lines between the soft- and hard-float
/// builds of the same core.
fn print_f32_bits(prefix: &str, name: &str, r: &UncertainPose<f32>) {
    let mut words = [0u32; 52];
    let pose = r.pose.to_matrix4();
    let flat = pose.iter().flatten().chain(r.cov.0.iter().flatten());
    for (w, x) in words.iter_mut().zip(flat) {
        *w = x.to_bits();
    }
    hprintln!("f32 bits {}{}: {:08x?}", prefix, name, words);
}

/// Pass count and worst errors (f64, f32) of a group of cases.
#[derive(Default)]
struct Tally {
    passed: usize,
    worst64: f64,
    worst32: f64,
}

impl Tally {
    /// Counts one case with errors `e64`, `e32` and prints its line.
    fn add(&mut self, label: &str, name: &str, e64: f64, e32: f64) {
        let ok = e64 <= TOL_F64 && e32 <= TOL_F32;
        self.passed += usize::from(ok);
        // `!(x <= worst)`: a NaN error becomes the worst.
        if !(e64 <= self.worst64) {
            self.worst64 = e64;
        }
        if !(e32 <= self.worst32) {
            self.worst32 = e32;
        }
        hprintln!(
            "  {}{:<8} f64 {:.2e}  f32 {:.2e}  {}",
            label,
            name,
            e64,
            e32,
            if ok { "ok" } else { "MISMATCH" }
        );
    }
}

/// The dense PPOE of every case in f64 and f32 against its expectation.
fn check_dense() -> Tally {
    let mut t = Tally::default();
    for c in EXPECTED.iter() {
        // f64: the table SEED, inputs as they are.
        let covs64: [Mat6<f64>; 6] = c.covs.map(Matrix);
        let r64 = ppoe_seed_f64(black_box(&c.thetas), black_box(&covs64));
        let e64 = case_err(&r64.pose.to_matrix4(), &r64.cov.0, (&c.pose, &c.cov));
        // f32: the table SEED_F32, inputs converted to f32.
        let th32 = c.thetas.map(|t| t as f32);
        let covs32: [Mat6<f32>; 6] = c.covs.map(|m| Matrix(m.map(|r| r.map(|x| x as f32))));
        let r32 = ppoe_seed_f32(black_box(&th32), black_box(&covs32));
        let want = (&c.pose, &c.cov);
        let e32 = case_err(&to_f64(&r32.pose.to_matrix4()), &to_f64(&r32.cov.0), want);
        print_f32_bits("", c.name, &r32);
        t.add("", c.name, e64, e32);
    }
    t
}

/// The rank-one PPOE of every rank-one case in f64 and f32 against its expectation.
fn check_rank1() -> Tally {
    let mut t = Tally::default();
    for c in EXPECTED_RANK1.iter() {
        let r64 = ppoe_seed_rank1_f64(black_box(&c.thetas), black_box(&c.sigma2));
        let e64 = case_err(&r64.pose.to_matrix4(), &r64.cov.0, (&c.pose, &c.cov));
        let (th32, s32) = (c.thetas.map(|t| t as f32), c.sigma2.map(|s| s as f32));
        let r32 = ppoe_seed_rank1_f32(black_box(&th32), black_box(&s32));
        let want = (&c.pose, &c.cov);
        let e32 = case_err(&to_f64(&r32.pose.to_matrix4()), &to_f64(&r32.cov.0), want);
        print_f32_bits("rank1_", c.name, &r32);
        t.add("rank-1 ", c.name, e64, e32);
    }
    t
}

#[cfg_attr(target_arch = "arm", platform::entry)]
#[cfg_attr(target_arch = "riscv32", export_name = "main")]
fn main() -> ! {
    hprintln!(
        "ppoe firmware: seed robot, {} cases, f64 and f32; {} rank-one cases",
        EXPECTED.len(),
        EXPECTED_RANK1.len()
    );
    let dense = check_dense();
    let rank1 = check_rank1();
    let all = dense.passed == EXPECTED.len() && rank1.passed == EXPECTED_RANK1.len();
    hprintln!(
        "summary: {}/{} cases passed, rank-1 {}/{}; worst rel. error f64 {:.2e}, rank-1 {:.2e} (tol {:.0e}), f32 {:.2e}, rank-1 {:.2e} (tol {:.0e})",
        dense.passed,
        EXPECTED.len(),
        rank1.passed,
        EXPECTED_RANK1.len(),
        dense.worst64,
        rank1.worst64,
        TOL_F64,
        dense.worst32,
        rank1.worst32,
        TOL_F32
    );

    measure(&EXPECTED[0]);
    measure_rank1(&EXPECTED_RANK1[0]);
    hprintln!("RESULT: {}", if all { "PASS" } else { "FAIL" });
    platform::exit(all)
}

/// Prints the cost of one 6-DOF PPOE call on case `c` (instructions: meaningful under
/// -icount shift=0 only, see [`ticks_per_call`]), of the small ops, and the stack of one
/// PPOE call.
fn measure(c: &Case) {
    // Cost of one 6-DOF PPOE call (meaningful under -icount shift=0 only, see above).
    let covs64: [Mat6<f64>; 6] = c.covs.map(Matrix);
    let th32 = c.thetas.map(|t| t as f32);
    let covs32: [Mat6<f32>; 6] = c.covs.map(|m| Matrix(m.map(|r| r.map(|x| x as f32))));
    let t32 = ticks_per_call(16, || {
        black_box(ppoe_seed_f32(black_box(&th32), black_box(&covs32)));
    });
    let t64 = ticks_per_call(4, || {
        black_box(ppoe_seed_f64(black_box(&c.thetas), black_box(&covs64)));
    });
    hprintln!(
        "{} per PPOE call: f32 {} f64 {} (x{} = instructions under qemu -icount shift=0 on mps2 boards and riscv virt; meaningless otherwise)",
        platform::COUNTER,
        t32,
        t64,
        platform::INSNS_PER_TICK
    );

    // Instructions of the small ops (same meaning as the PPOE line above).
    let o32 = op_ticks::<f32>(ppoe_exp_f32, ppoe_log_f32, ppoe_concat_f32);
    let o64 = op_ticks::<f64>(ppoe_exp_f64, ppoe_log_f64, ppoe_concat_f64);
    for (i, name) in ["se3_exp", "se3_log", "concat_globally_2nd"]
        .iter()
        .enumerate()
    {
        hprintln!(
            "{} per 64 calls of {}: f32 {} f64 {} (x{}/64 = instructions per call under qemu -icount shift=0; meaningless otherwise)",
            platform::COUNTER,
            name,
            o32[i],
            o64[i],
            platform::INSNS_PER_TICK
        );
    }

    let s32 = stack_used(|| {
        black_box(ppoe_seed_f32(black_box(&th32), black_box(&covs32)));
    });
    let s64 = stack_used(|| {
        black_box(ppoe_seed_f64(black_box(&c.thetas), black_box(&covs64)));
    });
    hprintln!(
        "stack per PPOE call (high-water below the caller, inputs excluded): f32 {} B, f64 {} B",
        s32,
        s64
    );
}

/// Prints the cost of one rank-one PPOE call on case `c` (instructions: meaningful under
/// -icount shift=0 only, see [`ticks_per_call`]) and its stack, like [`measure`].
fn measure_rank1(c: &Rank1Case) {
    let (th32, s32) = (c.thetas.map(|t| t as f32), c.sigma2.map(|s| s as f32));
    let t32 = ticks_per_call(16, || {
        black_box(ppoe_seed_rank1_f32(black_box(&th32), black_box(&s32)));
    });
    let t64 = ticks_per_call(4, || {
        black_box(ppoe_seed_rank1_f64(
            black_box(&c.thetas),
            black_box(&c.sigma2),
        ));
    });
    hprintln!(
        "{} per rank-1 PPOE call: f32 {} f64 {} (x{} = instructions, as for the PPOE)",
        platform::COUNTER,
        t32,
        t64,
        platform::INSNS_PER_TICK
    );
    let k32 = stack_used(|| {
        black_box(ppoe_seed_rank1_f32(black_box(&th32), black_box(&s32)));
    });
    let k64 = stack_used(|| {
        black_box(ppoe_seed_rank1_f64(
            black_box(&c.thetas),
            black_box(&c.sigma2),
        ));
    });
    hprintln!(
        "stack per rank-1 PPOE call (as for the PPOE): f32 {} B, f64 {} B",
        k32,
        k64
    );
}
