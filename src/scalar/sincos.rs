//! Sine and cosine for the two scalars: libm's `sincos` for f64 with its common branches
//! inlined, and an f32-native implementation (no f64 arithmetic, which Cortex-M4F cores
//! emulate in software).

/// Whether libm's branches for π/4 < |x| ≲ 5π/4 are inlined: where floats live in 128-bit
/// SIMD registers (SSE2, NEON, wasm simd128), every one of which a call clobbers in the
/// PPOE's loops. Elsewhere (Cortex-M, RISC-V: f64 in software or in scalar registers)
/// they stay in the call, whose cost is small there against a copy of the reduction and
/// its kernels in every caller (the firmware budgets measure the code and the stack).
const INLINE_NEAR: bool = cfg!(any(
    target_feature = "sse2",
    target_feature = "neon",
    target_feature = "simd128"
));

/// `libm::sincos` bit for bit (see [`Real::sin_cos_r`](crate::Real::sin_cos_r) for `f64`): its
/// branches for |x| ≤ π/4 inlined, and for |x| ≲ 5π/4 (a revolute joint's angles within
/// ±225°) where [`INLINE_NEAR`]; the rest a call.
#[inline(always)]
pub(super) fn sin_cos_f64(x: f64) -> (f64, f64) {
    // libm's own tests on the high word: |x| ≲ π/4 goes to the kernels, and below
    // 2⁻²⁷·√2 libm returns (x, 1) (both exact to rounding; θ = 0 is common).
    let ix = ((x.to_bits() >> 32) as u32) & 0x7fff_ffff;
    if ix <= 0x3fe9_21fb {
        if ix < 0x3e46_a09e {
            (x, 1.0)
        } else {
            sin_cos_f64_kernel(x)
        }
    } else if INLINE_NEAR && ix <= 0x400f_6a7a && (ix & 0xf_ffff) != 0x9_21fb {
        sin_cos_f64_near(x, ix)
    } else {
        sin_cos_f64_libm(x)
    }
}

/// msun's `__rem_pio2` for π/4 ≲ |x| ≲ 5π/4 away from π/2 and π (libm's `rem_pio2` with
/// its high word `ix` in (0x3fe921fb, 0x400f6a7a], low 20 bits not 0x921fb; the cases
/// near π/2 and π, where one round of reduction cancels, stay with libm):
/// x = k·π/2 + y₀ + y₁ with k = ±1 below 3π/4, ±2 above, in one round of the two-part
/// π/2 (85 bits), then the kernels with the tail y₁ and k's quadrant. The same
/// operations as libm's branches (x − (−a) is x + a exactly, and k·PIO2_1, k·PIO2_1T
/// are exact for |k| ≤ 2), so the same bits (tested); error < 1 ulp.
#[inline(always)]
fn sin_cos_f64_near(x: f64, ix: u32) -> (f64, f64) {
    const PIO2_1: f64 = f64::from_bits(0x3ff9_21fb_5440_0000); // first 33 bits of π/2
    const PIO2_1T: f64 = f64::from_bits(0x3dd0_b461_1a62_6331); // π/2 − PIO2_1
    let k = if ix <= 0x4002_d97c { 1.0 } else { 2.0 };
    let k = if x.is_sign_negative() { -k } else { k };
    let z = x - k * PIO2_1;
    let y0 = z - k * PIO2_1T;
    let y1 = (z - y0) - k * PIO2_1T;
    let (s, c) = sin_cos_f64_kernel_tail(y0, y1);
    // k mod 4: 1, 2, 2 (k = −2) or 3 (k = −1).
    match k as i32 & 3 {
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// msun's `__kernel_sin(x, y, 1)` and `__kernel_cos(x, y)` for a reduced argument x + y
/// (|x + y| ≲ π/4 + ε): [`sin_cos_f64_kernel`]'s polynomials with the tail's terms, in
/// libm's operation order.
#[inline(always)]
fn sin_cos_f64_kernel_tail(x: f64, y: f64) -> (f64, f64) {
    let z = x * x;
    let w = z * z;
    let rs = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let v = z * x;
    let s = x - ((z * (0.5 * y - v * rs) - y) - v * S1);
    let rc = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let one_m = 1.0 - hz;
    let c = one_m + (((1.0 - one_m) - hz) + (z * rc - x * y));
    (s, c)
}

/// msun's sin and cos polynomial coefficients (libm's `k_sin` and `k_cos`).
#[allow(clippy::excessive_precision)] // digit for digit as published
mod msun {
    pub(super) const S1: f64 = -1.666_666_666_666_663_243_48e-1;
    pub(super) const S2: f64 = 8.333_333_333_322_489_461_24e-3;
    pub(super) const S3: f64 = -1.984_126_982_985_794_931_34e-4;
    pub(super) const S4: f64 = 2.755_731_370_707_006_767_89e-6;
    pub(super) const S5: f64 = -2.505_076_025_340_686_341_95e-8;
    pub(super) const S6: f64 = 1.589_690_995_211_550_102_21e-10;
    pub(super) const C1: f64 = 4.166_666_666_666_660_190_37e-2;
    pub(super) const C2: f64 = -1.388_888_888_887_410_957_49e-3;
    pub(super) const C3: f64 = 2.480_158_728_947_672_941_78e-5;
    pub(super) const C4: f64 = -2.755_731_435_139_066_330_35e-7;
    pub(super) const C5: f64 = 2.087_572_321_298_174_827_90e-9;
    pub(super) const C6: f64 = -1.135_964_755_778_819_482_65e-11;
}
use msun::{C1, C2, C3, C4, C5, C6, S1, S2, S3, S4, S5, S6};

/// msun's `__kernel_sin(x, 0, 0)` and `__kernel_cos(x, 0)` (Sun Microsystems, 1993, as in
/// libm's `k_sin`/`k_cos`): the same coefficients and operation order, so the same bits
/// as `libm::sincos` for 2⁻²⁷·√2 ≤ |x| ≤ π/4 (tested); error < 1 ulp there.
#[inline(always)]
fn sin_cos_f64_kernel(x: f64) -> (f64, f64) {
    let z = x * x;
    let w = z * z;
    let rs = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let s = x + z * x * (S1 + z * rs);
    let rc = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let one_m = 1.0 - hz;
    let c = one_m + (((1.0 - one_m) - hz) + z * rc);
    (s, c)
}

/// `libm::sincos` out of line: the arguments beyond 5π/4, near π/2 and π (see
/// [`sin_cos_f64_near`]) and the non-finite ones of
/// [`Real::sin_cos_r`](crate::Real::sin_cos_r) for `f64`.
#[inline(never)]
fn sin_cos_f64_libm(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// The Cephes sin and cos polynomials of [`sin_cos_f32`], for |r| ≤ π/4, evaluated by
/// Estrin's scheme: `sin r = r + r·z·((S1 + z·S2) + z²·S3)` and
/// `cos r = (z²·((C1 + z·C2) + z²·C3) − z/2) + 1` with z = r², z and z² side by side.
/// Why not Horner's rule: a joint's sin/cos heads the chain of its displacement, and in the
/// PPOE's loops this chain, not the arithmetic, sets the pace; Estrin's form has the same
/// ten multiplies and seven additions, two fewer of them one after the other (five after z
/// instead of seven for the sine, six instead of eight for the cosine). Accuracy: see
/// [`Real::sin_cos_r`](crate::Real::sin_cos_r) for `f32`.
#[inline(always)]
fn sin_cos_f32_kernel(r: f32) -> (f32, f32) {
    let z = r * r;
    let z2 = z * z;
    let ps = (-1.666_665_5e-1 + z * 8.332_161e-3) + z2 * -1.951_529_6e-4;
    let s = r * z * ps + r;
    let pc = (4.166_664_6e-2 + z * -1.388_731_6e-3) + z2 * 2.443_315_7e-5;
    let c = (pc * z2 - 0.5 * z) + 1.0;
    (s, c)
}

/// 2⁻¹²: at and below it [`sin_cos_f32_kernel`] gives `(x, 1)` (`(+0, 1)` for ±0), the
/// terms beyond x and 1 being under half an ulp of them (checked for every f32 up to it by
/// `f32_tiny_shortcut_is_the_kernel_exhaustive`; the next f32 up gives another cosine).
const TINY_F32: f32 = 1.0 / 4096.0;

/// See [`Real::sin_cos_r`](crate::Real::sin_cos_r) for `f32`. Inlined into its callers (a call would clobber
/// every SSE register of the PPOE loop); only libm's fallback stays a call.
#[inline(always)]
pub(super) fn sin_cos_f32(x: f32) -> (f32, f32) {
    // |x| ≤ π/4 (most joint angles): k = 0, so r = x and quadrant 0 exactly; skipping the
    // reduction gives the same bits with a shorter dependency chain, and this one test
    // (false for NaN) is all such an angle pays.
    if x.abs() <= core::f32::consts::FRAC_PI_4 {
        // The kernel's own bits (`x + 0` makes −0 the kernel's +0). Like libm's branch
        // for tiny f64 arguments, it takes the polynomials' latency off the chain of a
        // joint at θ = 0, a common value (a home pose, a joint at rest).
        if x.abs() <= TINY_F32 {
            return (x + 0.0, 1.0);
        }
        return sin_cos_f32_kernel(x);
    }
    if x.is_nan() || x.abs() > 1.0e4 {
        return sin_cos_f32_large(x);
    }
    // π/2 = P1 + P2 + P3, P1 and P2 with few significant bits so k·P1, k·P2 are exact.
    const P1: f32 = 1.570_312_5;
    const P2: f32 = 4.837_513e-4;
    const P3: f32 = 7.549_79e-8;
    // Round to nearest with the 1.5·2²³ trick (exact for |y| < 2²²; here |y| ≤ 6367): two
    // additions instead of a software rintf on cores without a rounding instruction.
    const MAGIC: f32 = 12_582_912.0;
    let k = (x * core::f32::consts::FRAC_2_PI + MAGIC) - MAGIC;
    let r = ((x - k * P1) - k * P2) - k * P3;
    // k is an integer-valued float with |k| ≤ 6367, so the cast is exact.
    sin_cos_f32_quadrant(k as i32 as u32, r)
}

/// `(sin x, cos x)` from the quadrant `k` (mod 4) and the reduced `r` of x = k·π/2 + r.
#[inline(always)]
fn sin_cos_f32_quadrant(k: u32, r: f32) -> (f32, f32) {
    let (s, c) = sin_cos_f32_kernel(r);
    match k & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// The bits of 2/π after the binary point, 32 a word (2/π = Σ Fᵢ·2^(−32i) for i ≥ 1),
/// behind a zero word for the integer part: 224 bits, enough for the largest f32.
const TWO_OVER_PI: [u32; 8] = [
    0,
    0xa2f9_836e,
    0x4e44_1529,
    0xfc27_57d1,
    0xf534_ddc0,
    0xdb62_9599,
    0x3c43_9041,
    0xfe51_63ab,
];

/// ⌊a·b / 2⁶⁴⌋ from 32-bit halves (no 128-bit multiply, which is a library call on
/// Cortex-M).
#[inline(always)]
fn mul_hi_u64(a: u64, b: u64) -> u64 {
    let (a1, a0) = (a >> 32, a & 0xffff_ffff);
    let (b1, b0) = (b >> 32, b & 0xffff_ffff);
    let (p00, p01, p10) = (a0 * b0, a0 * b1, a1 * b0);
    let mid = (p00 >> 32) + (p01 & 0xffff_ffff) + (p10 & 0xffff_ffff);
    a1 * b1 + (p01 >> 32) + (p10 >> 32) + (mid >> 32)
}

/// Payne–Hanek reduction for finite x > 10⁴ (f32): `(k mod 4, r)` with
/// x = k·π/2 + r, |r| ≤ π/4, in integer arithmetic only.
///
/// Method: x = m·2ᵉ (m < 2²⁴) times the 96 bits of 2/π from weight 2^(1−e) on, as an
/// exact 120-bit fixed-point product; the bits of 2/π above that window add multiples of
/// 4 and those below it less than 2⁻⁷⁰ of a quadrant. The fraction rounded to the
/// nearest quadrant, kept to 64 bits, times π/2 (64-bit fixed point) is r, rounded once
/// to f32. Error: ½ ulp of r plus 2⁻⁶¹ absolute, far below the kernel's (Payne & Hanek,
/// *Radian reduction for trigonometric functions*, SIGNUM Newsletter 18, 1983; the
/// fixed-point layout is ours).
#[inline(always)]
fn reduce_pio2_f32(x: f32) -> (u32, f32) {
    /// π/2·2⁶², rounded to nearest.
    const PIO2_Q62: u64 = 0x6487_ed51_10b4_611a;
    let bits = x.to_bits();
    let m = u64::from((bits & 0x7f_ffff) | 0x80_0000);
    // x = m·2ᵉ with e = exponent − 150 ∈ [−10, 104] for 10⁴ < x < 2¹²⁸. The window
    // starts at bit j = e − 1 of 2/π (weight 2⁻ʲ), which is bit p = j + 31 of the table
    // counted from the top of its zero word.
    let p = ((bits >> 23) & 0xff).wrapping_sub(150 - 30);
    let (k, sh) = ((p >> 5) as usize, p & 31);
    let word = |i: usize| -> u64 {
        let at = |n: usize| u64::from(TWO_OVER_PI.get(n).copied().unwrap_or(0));
        ((((at(k + i) << 32) | at(k + i + 1)) << sh) >> 32) & 0xffff_ffff
    };
    // m·(w₂·2⁶⁴ + w₁·2³² + w₀) = hi·2⁶⁴ + lo, in units of 2⁻⁹⁴ quadrants.
    let (p2, p1, p0) = (m * word(0), m * word(1), m * word(2));
    let (lo, carry) = p0.overflowing_add(p1 << 32);
    let hi = p2 + (p1 >> 32) + u64::from(carry);
    // Quadrant count: bits 94 and up; the fraction below it, to 64 bits (units 2⁻⁶⁴).
    let frac = ((hi & 0x3fff_ffff) << 34) | (lo >> 30);
    let half = frac >> 63; // fraction ≥ ½: round the quadrant up, r negative
    let k = ((hi >> 30) + half) as u32;
    let f = frac as i64; // frac − 2⁶⁴·half: the signed fraction of a quadrant
    let r = mul_hi_u64(f.unsigned_abs(), PIO2_Q62) as f32 * f32::from_bits(0x2080_0000); // ·2⁻⁶²
    (k, if f < 0 { -r } else { r })
}

/// sin and cos of NaN, ±∞ and |x| > 10⁴ (f32): [`reduce_pio2_f32`], then the same
/// kernel. Out of line: no joint angle gets here.
#[cold]
#[inline(never)]
fn sin_cos_f32_large(x: f32) -> (f32, f32) {
    if !x.is_finite() {
        return (f32::NAN, f32::NAN);
    }
    let (k, r) = reduce_pio2_f32(x.abs());
    let (s, c) = sin_cos_f32_quadrant(k, r);
    (if x < 0.0 { -s } else { s }, c)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::scalar::Real;
    use std::println;

    #[test]
    fn f32_sin_cos_accuracy() {
        // Every f32 in [-4π, 4π] at a fine stride, plus a coarse sweep to 1e4 and beyond.
        let mut worst = 0.0f64;
        let mut check = |x: f32| {
            let (s, c) = super::sin_cos_f32(x);
            let xd = x as f64;
            worst = worst
                .max((s as f64 - xd.sin()).abs())
                .max((c as f64 - xd.cos()).abs());
        };
        let mut x = -4.0 * core::f32::consts::PI;
        while x < 4.0 * core::f32::consts::PI {
            check(x);
            x += 1.0e-4;
        }
        for i in -1_000_000..=1_000_000 {
            check(i as f32 * 1.0e-2);
        }
        for x in [
            1.0e4f32,
            -1.0e4,
            1.0e4 + 1.0,
            3.0e7,
            f32::MIN_POSITIVE,
            1e-30,
            0.0,
            -0.0,
        ] {
            check(x);
        }
        println!("f32 sin_cos worst abs error {worst:e}");
        assert!(worst <= 1.0e-7, "worst abs error {worst:e}");
        assert!(super::sin_cos_f32(f32::NAN).0.is_nan());
        assert!(super::sin_cos_f32(f32::INFINITY).1.is_nan());
    }

    /// Every `stride`-th f32 from 0 up to [`super::TINY_F32`] and the two at the top, both
    /// signs: the shortcut there gives the kernel's bits; and just above it the kernel
    /// no longer gives `(x, 1)`, so the threshold is the largest that can be.
    fn check_tiny_shortcut(stride: usize) {
        let top = super::TINY_F32.to_bits();
        let same = |x: f32| {
            let (s, c) = super::sin_cos_f32(x);
            let (ks, kc) = super::sin_cos_f32_kernel(x);
            s.to_bits() == ks.to_bits() && c.to_bits() == kc.to_bits()
        };
        for b in (0..=top).step_by(stride).chain([top - 1, top]) {
            let x = f32::from_bits(b);
            assert!(same(x) && same(-x), "{x:e}");
        }
        let above = f32::from_bits(top + 1);
        assert_ne!(super::sin_cos_f32_kernel(above), (above, 1.0));
    }

    #[test]
    fn f32_tiny_shortcut_is_the_kernel() {
        check_tiny_shortcut(97);
    }

    /// Every f32 up to the threshold (about 2·10⁹ values with the signs; seconds in
    /// release): `cargo test --release -p ppoe --lib f32_tiny -- --ignored`.
    #[test]
    #[ignore]
    fn f32_tiny_shortcut_is_the_kernel_exhaustive() {
        check_tiny_shortcut(1);
    }

    /// |error| of the f32 sin and cos at x against f64 (x is exact in f64).
    fn f32_error(x: f32) -> f64 {
        let (s, c) = super::sin_cos_f32(x);
        let xd = x as f64;
        (s as f64 - xd.sin()).abs().max((c as f64 - xd.cos()).abs())
    }

    #[test]
    fn f32_sin_cos_large_arguments() {
        // The Payne–Hanek path: every binade from 2^13 to the largest f32, 4096 mantissas
        // each (a fixed LCG), both signs; the extremes; and the f32 closest to a multiple
        // of π/2 above 10⁴ (found by `f32_sin_cos_exhaustive_large`), where the reduction
        // cancels the most.
        let mut worst = 0.0f64;
        let mut state = 0x2545_f491_u32;
        for exponent in 140u32..=254 {
            for _ in 0..4096 {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let x = f32::from_bits((exponent << 23) | (state >> 9));
                if x > 1.0e4 {
                    worst = worst.max(f32_error(x)).max(f32_error(-x));
                }
            }
        }
        let closest = f32::from_bits(0x6f79_be45); // 7.73e28: |r| = 1.6e-9
        let worst_seen = f32::from_bits(0x76b6_06bf); // 1.85e33: the exhaustive run's worst
        for x in [
            1.0e4f32 + 0.001,
            3.0e7,
            f32::MAX,
            -f32::MAX,
            closest,
            worst_seen,
        ] {
            worst = worst.max(f32_error(x));
        }
        println!("f32 sin_cos, |x| > 1e4: worst abs error {worst:e}");
        assert!(worst <= 1.0e-7, "worst abs error {worst:e}");
        for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            let (s, c) = super::sin_cos_f32(x);
            assert!(s.is_nan() && c.is_nan());
        }
    }

    /// Every f32 above 10⁴ (about 10⁹ values; a minute in release): the worst error and
    /// the argument closest to a multiple of π/2. `cargo test --release -p ppoe --lib
    /// f32_sin_cos_exhaustive_large -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn f32_sin_cos_exhaustive_large() {
        let (mut worst, mut worst_at) = (0.0f64, 0.0f32);
        let (mut closest, mut closest_at) = (f64::INFINITY, 0.0f32);
        for bits in 1.0e4f32.to_bits() + 1..f32::INFINITY.to_bits() {
            let x = f32::from_bits(bits);
            let e = f32_error(x);
            if e > worst {
                (worst, worst_at) = (e, x);
            }
            let r = super::reduce_pio2_f32(x).1.abs() as f64;
            if r < closest {
                (closest, closest_at) = (r, x);
            }
        }
        println!(
            "worst abs error {worst:e} at {worst_at:e} ({:#x})",
            worst_at.to_bits()
        );
        println!(
            "smallest |r| {closest:e} at {closest_at:e} ({:#x})",
            closest_at.to_bits()
        );
        assert!(worst <= 1.0e-7);
    }

    #[test]
    fn f64_sin_cos_is_libm_bit_for_bit() {
        // Across the inlined branches' ranges, their edges (2^-27·√2, π/4, 3π/4 where k
        // goes from 1 to 2, 5π/4 where the libm call takes over) and the high words near
        // π/2 and π that libm reduces in more rounds, every ulp around each edge, and
        // beyond, both signs.
        let edges = [
            0x3e46_a09e_0000_0000u64,
            0x3fe9_21fc_0000_0000,
            0x4002_d97d_0000_0000,
            0x400f_6a7b_0000_0000,
            0x3ff9_21fb_0000_0000,
            0x3ff9_21fc_0000_0000,
            0x4009_21fb_0000_0000,
            0x4009_21fc_0000_0000,
            core::f64::consts::FRAC_PI_4.to_bits(),
            core::f64::consts::FRAC_PI_2.to_bits(),
            core::f64::consts::PI.to_bits(),
            (3.0 * core::f64::consts::FRAC_PI_4).to_bits(),
            (5.0 * core::f64::consts::FRAC_PI_4).to_bits(),
        ]
        .into_iter()
        .flat_map(|b| (b - 2_000..b + 2_000).map(f64::from_bits));
        let special = [
            0.0,
            1e-300,
            f64::MIN_POSITIVE / 4.0,
            f64::INFINITY,
            f64::NAN,
        ];
        let sweep = (0..=2_000_000).map(|i| (i as f64 - 1_000_000.0) * 5e-6);
        let logs = (0..2_000).map(|i| 10f64.powf(-10.0 + i as f64 * 0.005));
        for x in edges.chain(special).chain(sweep).chain(logs) {
            for x in [x, -x] {
                let (s, c) = x.sin_cos_r();
                let (ls, lc) = libm::sincos(x);
                assert_eq!(s.to_bits(), ls.to_bits(), "sin({x:e})");
                assert_eq!(c.to_bits(), lc.to_bits(), "cos({x:e})");
            }
        }
    }
}
