//! An independent 4×4 oracle for rigid transforms — the matrix product, the rigid inverse
//! and the matrix exponential of a twist — sharing no code with ppoe: the calibration
//! tests of ppoe-build and ppoe-cli compute the unfolded calibrated product with it.

/// A 4×4 matrix, row-major.
pub type M4 = [[f64; 4]; 4];

/// The identity.
pub const I4: M4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// The product a·b.
pub fn mul(a: &M4, b: &M4) -> M4 {
    let mut c = [[0.0; 4]; 4];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

/// The inverse of a rigid transform.
pub fn inv(a: &M4) -> M4 {
    let mut b = I4;
    for i in 0..3 {
        for j in 0..3 {
            b[i][j] = a[j][i];
        }
        b[i][3] = -(0..3).map(|k| a[k][i] * a[k][3]).sum::<f64>();
    }
    b
}

/// `Exp(ξ)`, ξ = (ω, v) rotation first: the 4×4 matrix exponential by scaling, 30 terms
/// of the series and squaring.
pub fn exp(xi: &[f64; 6]) -> M4 {
    let [wx, wy, wz, vx, vy, vz] = *xi;
    let norm = xi.iter().map(|a| a.abs()).fold(0.0, f64::max);
    let squarings = (norm.log2().ceil() as i32).saturating_add(4).clamp(0, 60);
    let s = 0.5f64.powi(squarings);
    let x = [
        [0.0, -wz, wy, vx],
        [wz, 0.0, -wx, vy],
        [-wy, wx, 0.0, vz],
        [0.0; 4],
    ]
    .map(|r| r.map(|a| a * s));
    let (mut out, mut term) = (I4, I4);
    for k in 1..30 {
        term = mul(&term, &x).map(|r| r.map(|a| a / k as f64));
        for (o, t) in out.iter_mut().zip(&term) {
            for (a, b) in o.iter_mut().zip(t) {
                *a += b;
            }
        }
    }
    for _ in 0..squarings {
        out = mul(&out, &out);
    }
    out
}
