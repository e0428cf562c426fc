//! The few matrix operations the URDF → chain conversion needs, evaluated in the order and
//! with the roundings of the numpy/OpenBLAS build that produced the golden files, so that the
//! results agree with pytransform3d bit for bit (checked on every chain of
//! `test_data/golden/ppoe`):
//!
//! * matrix products (`numpy.dot` of 3×3 and 4×4 arrays → OpenBLAS `dgemm`, whose x86-64
//!   kernels accumulate with fused multiply-adds): `c = a₀b₀`, then `c = fma(aₖ, bₖ, c)` for
//!   k = 1, 2, …;
//! * matrix times vector (`numpy.dot` of a 3×3 view and a 3-vector → `dgemv`, the 3-row
//!   remainder loop as GCC contracts it): `fma(a₂, x₂, fma(a₀, x₀, a₁x₁))`;
//! * norms, cross products and divisions: plain IEEE operations, left to right.
//!
//! On a machine whose BLAS does not use FMA, pytransform3d's results differ from these in
//! the last bit or two (≤ 3.4e-16 on the test robots); the chain is the same to ~1e-16
//! either way. `f64::mul_add` is correctly rounded on every platform (in software where the
//! CPU has no FMA), so these results do not depend on the build machine.

/// A row-major homogeneous 4×4 transform.
pub type Mat4 = [[f64; 4]; 4];
type Mat3 = [[f64; 3]; 3];

/// The 4×4 identity.
pub const IDENTITY: Mat4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// `a · b` for 3×3 matrices (numpy `a.dot(b)`, FMA accumulation).
fn mul3(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = a[i][2].mul_add(b[2][j], a[i][1].mul_add(b[1][j], a[i][0] * b[0][j]));
        }
    }
    out
}

/// `a · b` for 4×4 matrices (numpy `a.dot(b)`, FMA accumulation), including the homogeneous
/// row and column (the `a[i][3]·0` terms only matter for the sign of zeros).
pub fn mul4(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut out = [[0.0; 4]; 4];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            let acc = a[i][1].mul_add(b[1][j], a[i][0] * b[0][j]);
            *x = a[i][3].mul_add(b[3][j], a[i][2].mul_add(b[2][j], acc));
        }
    }
    out
}

/// The rotation of a URDF `rpy`: extrinsic roll-pitch-yaw, `R = (Rz(yaw)·Ry(pitch))·Rx(roll)`
/// (pytransform3d's `active_matrix_from_extrinsic_roll_pitch_yaw`).
pub fn rotation_from_rpy(rpy: [f64; 3]) -> Mat3 {
    let (sa, ca) = rpy[0].sin_cos();
    let (sb, cb) = rpy[1].sin_cos();
    let (sg, cg) = rpy[2].sin_cos();
    let rx = [[1.0, 0.0, 0.0], [0.0, ca, -sa], [0.0, sa, ca]];
    let ry = [[cb, 0.0, sb], [0.0, 1.0, 0.0], [-sb, 0.0, cb]];
    let rz = [[cg, -sg, 0.0], [sg, cg, 0.0], [0.0, 0.0, 1.0]];
    mul3(&mul3(&rz, &ry), &rx)
}

/// `[[R, p], [0, 1]]`.
pub fn transform_from(r: &Mat3, p: [f64; 3]) -> Mat4 {
    [
        [r[0][0], r[0][1], r[0][2], p[0]],
        [r[1][0], r[1][1], r[1][2], p[1]],
        [r[2][0], r[2][1], r[2][2], p[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// `R(t) · v` for the rotation block of a 4×4 transform (numpy `t[:3, :3].dot(v)`):
/// `fma(r₂, v₂, fma(r₀, v₀, r₁v₁))` per row.
pub fn rotate(t: &Mat4, v: [f64; 3]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (i, x) in out.iter_mut().enumerate() {
        *x = t[i][2].mul_add(v[2], t[i][0].mul_add(v[0], t[i][1] * v[1]));
    }
    out
}

/// Below this the plain sum of squares has lost bits to underflow (its squares are
/// subnormal or flushed to zero): √(f64::MIN_POSITIVE / ε) ≈ 1.5·10⁻¹⁴⁶.
const PLAIN_NORM_MIN: f64 = 1.5e-146;

/// Euclidean norm: `sqrt(x·x)` summed left to right (numpy's, so that pytransform3d's
/// results are matched bit for bit) wherever that is exact to rounding; for vectors whose
/// squares underflow (‖v‖ < 1.5·10⁻¹⁴⁶) or overflow (‖v‖ > ~1.3·10¹⁵⁴) the vector is first
/// divided by its largest |component|, so any finite non-zero vector has a finite, non-zero
/// norm. 0 for the zero vector; not finite if a component is not.
pub fn norm(v: [f64; 3]) -> f64 {
    let plain = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if plain.is_finite() && plain >= PLAIN_NORM_MIN {
        return plain;
    }
    let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return plain;
    }
    // Divided, not multiplied by 1/m (which overflows for a subnormal m): the largest
    // component becomes ±1, so the scaled sum of squares is in [1, 3].
    let s = [v[0] / m, v[1] / m, v[2] / m];
    m * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt()
}

/// `v / ‖v‖`, or `v` unchanged if `‖v‖ = 0` (pytransform3d's `norm_vector`: a division, not
/// a multiplication by the reciprocal). A tiny or huge finite `v` gives its unit vector:
/// where ‖v‖ itself under- or overflows, `v` is first divided by its largest |component|.
pub fn normalized(v: [f64; 3]) -> [f64; 3] {
    let n = norm(v);
    if n == 0.0 {
        return v;
    }
    if n.is_finite() && n >= PLAIN_NORM_MIN {
        return [v[0] / n, v[1] / n, v[2] / n];
    }
    let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !m.is_finite() {
        return [v[0] / n, v[1] / n, v[2] / n];
    }
    let s = [v[0] / m, v[1] / m, v[2] / m];
    let n = norm(s);
    [s[0] / n, s[1] / n, s[2] / n]
}

/// `a × b` (numpy `cross`).
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rpy_quarter_turns() {
        let h = core::f64::consts::FRAC_PI_2;
        // Roll about x maps y to z.
        let r = rotation_from_rpy([h, 0.0, 0.0]);
        assert!((r[2][1] - 1.0).abs() < 1e-15 && r[1][1].abs() < 1e-15);
        // Yaw about z maps x to y.
        let r = rotation_from_rpy([0.0, 0.0, h]);
        assert!((r[1][0] - 1.0).abs() < 1e-15);
        // Extrinsic order: roll first, then pitch, then yaw: R = Rz·Ry·Rx.
        let (a, b, g) = (0.3, -0.2, 0.7);
        let r = rotation_from_rpy([a, b, g]);
        let rx = rotation_from_rpy([a, 0.0, 0.0]);
        let ry = rotation_from_rpy([0.0, b, 0.0]);
        let rz = rotation_from_rpy([0.0, 0.0, g]);
        let expect = mul3(&rz, &mul3(&ry, &rx));
        for i in 0..3 {
            for j in 0..3 {
                assert!((r[i][j] - expect[i][j]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn identity_products_and_normalisation() {
        let t = transform_from(&rotation_from_rpy([0.1, 0.2, 0.3]), [1.0, -2.0, 3.0]);
        assert_eq!(mul4(&t, &IDENTITY), t);
        assert_eq!(mul4(&IDENTITY, &t), t);
        assert_eq!(normalized([0.0, 0.0, 2.0]), [0.0, 0.0, 1.0]);
        assert_eq!(normalized([0.0, 0.0, 0.0]), [0.0, 0.0, 0.0]);
        assert_eq!(normalized([0.0, -3.0, 4.0]), [0.0, -0.6, 0.8]);
        assert_eq!(cross([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
    }

    #[test]
    fn norm_does_not_under_or_overflow() {
        // Closed forms: ‖(3, 4, 0)·k‖ = 5k, exact in binary for these k up to one rounding.
        for k in [1e-300, 1e-200, 1e150, 1e300, 1e-310] {
            let n = norm([3.0 * k, 4.0 * k, 0.0]);
            assert!(
                (n - 5.0 * k).abs() <= 4.0 * f64::EPSILON * 5.0 * k,
                "{k}: {n}"
            );
        }
        assert_eq!(
            norm([f64::MIN_POSITIVE / 4.0, 0.0, 0.0]),
            f64::MIN_POSITIVE / 4.0
        );
        assert_eq!(norm([0.0, -0.0, 0.0]), 0.0);
        assert_eq!(normalized([0.0, -1e300, 0.0]), [0.0, -1.0, 0.0]);
        assert_eq!(normalized([0.0, 0.0, 5e-324]), [0.0, 0.0, 1.0]);
    }
}
