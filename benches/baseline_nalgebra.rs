//! The baseline: the same PPOE written with nalgebra's dense 4×4 and 6×6 matrices, the way
//! a Rust user would port pytransform3d's example (`probabilistic_forward_kinematics`:
//! per joint `T ← T·Dᵢ` and `C ← Ad(Dᵢ⁻¹)·C·Ad(Dᵢ⁻¹)ᵀ + Σᵢ` with dense matrices, then the
//! home pose).
//!
//! Two ports, differing only in how they invert a transform: [`ppoe`] with nalgebra's
//! general 4×4 inverse, as pytransform3d's `invert_transform` does (LU), and
//! [`ppoe_closed_form`] with the rigid transform's closed form `(Rᵀ, −Rᵀp)`, which a port
//! may equally use (it agrees to about 1 ulp) and which costs far less.

use nalgebra::{Matrix3, Matrix4, Matrix6, RealField, Vector3, Vector6};
use ppoe::chain::Joint;
use ppoe::{Mat6, Real, Transform};

/// Screw axes (rotation first), home pose and limits, as dense nalgebra types.
#[derive(Clone)]
pub struct NaChain<T: RealField + Copy> {
    pub screws: Vec<Vector6<T>>,
    pub home: Matrix4<T>,
    pub lower: Vec<T>,
    pub upper: Vec<T>,
}

/// The chain `joints`, `home` and the covariances `covs` as nalgebra types, for the ports.
pub fn inputs<T: Real + RealField>(
    joints: &[Joint<T>],
    home: Transform<T>,
    covs: &[Mat6<T>],
) -> (NaChain<T>, Vec<Matrix6<T>>) {
    let na = NaChain {
        screws: joints
            .iter()
            .map(|j| Vector6::from_column_slice(&j.screw.0))
            .collect(),
        home: Matrix4::from_fn(|i, j| home.to_matrix4()[i][j]),
        lower: joints.iter().map(|j| j.lower).collect(),
        upper: joints.iter().map(|j| j.upper).collect(),
    };
    let na_covs = covs
        .iter()
        .map(|m| Matrix6::from_fn(|i, j| m.0[i][j]))
        .collect();
    (na, na_covs)
}

fn skew<T: RealField + Copy>(w: &Vector3<T>) -> Matrix3<T> {
    Matrix3::new(
        T::zero(),
        -w.z,
        w.y,
        w.z,
        T::zero(),
        -w.x,
        -w.y,
        w.x,
        T::zero(),
    )
}

/// SE(3) exponential as a dense 4×4 (Rodrigues + left Jacobian).
pub fn exp<T: RealField + Copy>(xi: &Vector6<T>) -> Matrix4<T> {
    let w = Vector3::new(xi[0], xi[1], xi[2]);
    let v = Vector3::new(xi[3], xi[4], xi[5]);
    let t = w.norm();
    let mut m = Matrix4::identity();
    if t == T::zero() {
        m.fixed_view_mut::<3, 1>(0, 3).copy_from(&v);
        return m;
    }
    let k = skew(&w);
    let k2 = k * k;
    let (s, c) = t.sin_cos();
    let t2 = t * t;
    let r = Matrix3::identity() + k * (s / t) + k2 * ((T::one() - c) / t2);
    let j = Matrix3::identity() + k * ((T::one() - c) / t2) + k2 * ((t - s) / (t2 * t));
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
    m.fixed_view_mut::<3, 1>(0, 3).copy_from(&(j * v));
    m
}

/// Dense 6×6 adjoint of a 4×4 transform.
pub fn adjoint<T: RealField + Copy>(m: &Matrix4<T>) -> Matrix6<T> {
    let r: Matrix3<T> = m.fixed_view::<3, 3>(0, 0).into();
    let p: Vector3<T> = m.fixed_view::<3, 1>(0, 3).into();
    let mut a = Matrix6::zeros();
    a.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
    a.fixed_view_mut::<3, 3>(3, 3).copy_from(&r);
    a.fixed_view_mut::<3, 3>(3, 0).copy_from(&(skew(&p) * r));
    a
}

/// The PPOE with the right-perturbation last step `Ad(M⁻¹)`, transforms inverted as
/// general 4×4 matrices.
pub fn ppoe<T: RealField + Copy>(
    chain: &NaChain<T>,
    thetas: &[T],
    covs: &[Matrix6<T>],
) -> (Matrix4<T>, Matrix6<T>) {
    ppoe_with(chain, thetas, covs, |m| {
        m.try_inverse().unwrap_or_else(Matrix4::identity)
    })
}

/// [`ppoe`] with the transforms inverted by the closed form `(Rᵀ, −Rᵀp)`.
pub fn ppoe_closed_form<T: RealField + Copy>(
    chain: &NaChain<T>,
    thetas: &[T],
    covs: &[Matrix6<T>],
) -> (Matrix4<T>, Matrix6<T>) {
    ppoe_with(chain, thetas, covs, rigid_inverse)
}

/// The PPOE with `inverse` for the inverse transforms.
#[inline(always)]
fn ppoe_with<T: RealField + Copy>(
    chain: &NaChain<T>,
    thetas: &[T],
    covs: &[Matrix6<T>],
    inverse: impl Fn(&Matrix4<T>) -> Matrix4<T>,
) -> (Matrix4<T>, Matrix6<T>) {
    let mut t: Matrix4<T> = Matrix4::identity();
    let mut c: Matrix6<T> = Matrix6::zeros();
    for i in 0..chain.screws.len() {
        let th = thetas[i].clamp(chain.lower[i], chain.upper[i]);
        let d = exp(&(chain.screws[i] * th));
        t *= d;
        let g = adjoint(&inverse(&d));
        c = g * c * g.transpose() + covs[i];
    }
    let g = adjoint(&inverse(&chain.home));
    (t * chain.home, g * c * g.transpose())
}

/// The inverse of a rigid transform by its closed form: rotation Rᵀ, translation −Rᵀp.
fn rigid_inverse<T: RealField + Copy>(m: &Matrix4<T>) -> Matrix4<T> {
    let rt: Matrix3<T> = m.fixed_view::<3, 3>(0, 0).transpose();
    let p: Vector3<T> = m.fixed_view::<3, 1>(0, 3).into();
    let mut inv = Matrix4::identity();
    inv.fixed_view_mut::<3, 3>(0, 0).copy_from(&rt);
    inv.fixed_view_mut::<3, 1>(0, 3).copy_from(&(-(rt * p)));
    inv
}
