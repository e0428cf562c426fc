//! No subnormal values in the SIMD lanes the PPOE leaves unused (x86-64 only).
//!
//! The single-call PPOE runs its transports in SIMD lanes; f32 uses two lanes of 4-lane
//! SSE registers, whose other two lanes the program does not define (src/ppoe/schedule.rs
//! says why this is safe and what it cost when it was not). If a value left in an unused
//! lane is tiny, products of it are subnormal, which x86 cores compute on a slow path:
//! the results stay right, only the time is lost, so no result test can see it.
//!
//! Oracle: the CPU's own sticky exception flags (MXCSR): `DE`, an operand was subnormal,
//! and `UE`, a result underflowed; both count every lane of every SSE instruction, used
//! or not. The inputs here have no subnormal value and produce none in the quantities
//! the PPOE computes (robot-sized chains, covariances from 10⁻⁶ to 10⁻², joint values
//! away from zero), so any flag raised comes from a lane that holds no input value. The
//! single call, the batch (whose lanes are configurations, all defined), f32 and f64,
//! every convention, on the seed chain and synthetic chains of 1 to 9 joints, each at 64
//! configurations.
//!
//! Whether unused lanes hold leftovers is a matter of code generation, so CI (`.ci/run`)
//! runs this file in release too. Checked once by hand, not repeatable by a command here:
//! ported to the API of commit bad27c7~1 (two f32 lanes gathered from registers, the code
//! that had subnormals), this test failed in release (`DE` raised, f32 only) and passed
//! at the test profile's opt-level.
#![cfg(target_arch = "x86_64")]
#![allow(deprecated)] // _mm_getcsr/_mm_setcsr: the one way to read MXCSR from Rust

use core::arch::x86_64::{_mm_getcsr, _mm_setcsr};
use ppoe::chain::{ChainView, Convention, UncertainPose};
use ppoe::{Mat6, Matrix, Real, Transform};
use ppoe_test_support::fixtures::{seed_case, synthetic_case, Case};

const CONVENTIONS: [Convention; 3] = [
    Convention::Right,
    Convention::Left,
    Convention::Pytransform3d,
];

/// MXCSR's denormal-operand flag (DE).
const DE: u32 = 0x02;
/// MXCSR's underflow flag (UE).
const UE: u32 = 0x10;
/// The flags [`raised`] reports.
const SUBNORMAL_FLAGS: u32 = DE | UE;

/// The MXCSR flags among [`SUBNORMAL_FLAGS`] that `f` raised.
fn raised(f: impl FnOnce()) -> u32 {
    // SAFETY: clearing MXCSR's sticky exception flags changes no result (the rounding
    // and masking bits are kept).
    unsafe { _mm_setcsr(_mm_getcsr() & !0x3f) };
    f();
    // SAFETY: reading MXCSR has no effect.
    let csr = unsafe { _mm_getcsr() };
    csr & SUBNORMAL_FLAGS
}

/// A dense symmetric positive definite covariance: `L·Lᵀ` for a lower-triangular L with
/// entries of 10⁻³ to 10⁻¹ (variances of 10⁻⁶ to 10⁻²), different for each `seed`.
fn dense_cov<T: Real>(seed: usize) -> Mat6<T> {
    let mut l = [[0.0f64; 6]; 6];
    for (i, row) in l.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate().take(i + 1) {
            let k = (seed * 36 + i * 6 + j) as f64;
            *x = if i == j {
                0.05 + 0.04 * (0.7 * k).sin()
            } else {
                0.01 * (1.3 * k).cos()
            };
        }
    }
    let mut c = [[T::ZERO; 6]; 6];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            let s: f64 = (0..6).map(|k| l[i][k] * l[j][k]).sum();
            *x = T::lit(s);
        }
    }
    Matrix(c)
}

/// The cases: the seed example (two joints without covariance), the seed chain with
/// dense covariances, and synthetic chains of 1 to 9 joints with dense covariances.
fn cases<T: Real>() -> Vec<Case<T>> {
    let mut out = vec![seed_case()];
    let (joints, home, thetas, _) = seed_case::<T>();
    let dense = (0..joints.len()).map(dense_cov).collect();
    out.push((joints, home, thetas, dense));
    for n in 1..=9 {
        let (joints, home, thetas, _) = synthetic_case::<T>(n);
        out.push((joints, home, thetas, (0..n).map(dense_cov).collect()));
    }
    out
}

/// 64 configurations of `n` joints, row-major, spread over ±2.9 rad and away from zero.
fn configurations<T: Real>(n: usize, first: &[T]) -> Vec<T> {
    let mut rows: Vec<T> = first.to_vec();
    for k in 1..64 {
        rows.extend((0..n).map(|i| {
            let x = ((k * 7 + i * 3) % 29) as f64 * 0.2 - 2.8 + 0.013 * i as f64;
            T::lit(if x.abs() < 0.05 { 0.3 } else { x })
        }));
    }
    rows
}

fn no_subnormals<T: Real>() {
    for (ci, (joints, home, thetas, covs)) in cases::<T>().into_iter().enumerate() {
        let chain = ChainView {
            joints: &joints,
            home,
        };
        let n = joints.len();
        let rows = configurations(n, &thetas);
        for convention in CONVENTIONS {
            let mut out = vec![UncertainPose::certain(Transform::identity()); 64];
            let flags = raised(|| {
                for row in rows.chunks(n) {
                    std::hint::black_box(chain.ppoe(std::hint::black_box(row), &covs, convention))
                        .expect("lengths");
                }
            });
            assert_eq!(
                flags, 0,
                "single call, case {ci}, {convention:?}: MXCSR {flags:#x}"
            );
            let flags = raised(|| {
                chain
                    .ppoe_batch(std::hint::black_box(&rows), &covs, convention, &mut out)
                    .expect("lengths");
            });
            assert_eq!(
                flags, 0,
                "batch, case {ci}, {convention:?}: MXCSR {flags:#x}"
            );
        }
    }
}

#[test]
fn no_subnormals_f32() {
    no_subnormals::<f32>();
}

#[test]
fn no_subnormals_f64() {
    no_subnormals::<f64>();
}

/// The oracle can fail: a product that underflows raises UE here.
#[test]
fn an_underflow_is_seen() {
    let flags = raised(|| {
        std::hint::black_box(std::hint::black_box(1e-30f32) * std::hint::black_box(1e-10f32));
    });
    assert_ne!(flags & UE, 0);
}
