//! From the C types to the core crate's: chains, joint values, covariances, and results
//! back into caller-owned arrays. Every pointer is checked for NULL and every length
//! against the others and against `PPOE_MAX_JOINTS` before anything is read.

use crate::*;
use heapless::Vec;
use ppoe::chain::{ChainView, Convention, Joint, JointConstants, JointKind, UncertainPose};
use ppoe::{Mat6, Matrix, Real, Transform};

/// The joints of a chain, copied for the core crate's `ChainView`.
pub(crate) type Joints<T> = Vec<Joint<T>, { PPOE_MAX_JOINTS as usize }>;
/// The joint covariances, copied into the core crate's matrices.
pub(crate) type Covs<T> = Vec<Mat6<T>, { PPOE_MAX_JOINTS as usize }>;

/// A C chain as a core `ChainView` over `joints` (filled here).
///
/// # Safety
/// `chain` is NULL or points to a valid `ppoe_chain<T>` whose `joints` points to
/// `n_joints` valid joints (or is NULL).
pub(crate) unsafe fn chain<'a, T: Real>(
    chain: *const ppoe_chain<T>,
    joints: &'a mut Joints<T>,
) -> Result<ChainView<'a, T>, ppoe_status> {
    // SAFETY: NULL checked here; otherwise valid by the caller's contract.
    let c = unsafe { chain.as_ref() }.ok_or(PPOE_ERR_NULL_POINTER)?;
    if c.n_joints > PPOE_MAX_JOINTS {
        return Err(PPOE_ERR_TOO_MANY_JOINTS);
    }
    let n = c.n_joints as usize;
    if n > 0 && c.joints.is_null() {
        return Err(PPOE_ERR_NULL_POINTER);
    }
    joints.clear();
    for i in 0..n {
        // SAFETY: i < n_joints and joints is not NULL: within the caller's array.
        let j = unsafe { &*c.joints.add(i) };
        joints
            .push(joint(j)?)
            .map_err(|_| PPOE_ERR_TOO_MANY_JOINTS)?;
    }
    Ok(ChainView {
        joints: joints.as_slice(),
        home: Transform::from_matrix4(&c.home),
    })
}

fn joint<T: Real>(j: &ppoe_joint<T>) -> Result<Joint<T>, ppoe_status> {
    let kind = match j.kind {
        PPOE_JOINT_REVOLUTE => JointKind::Revolute,
        PPOE_JOINT_CONTINUOUS => JointKind::Continuous,
        PPOE_JOINT_PRISMATIC => JointKind::Prismatic,
        _ => return Err(PPOE_ERR_BAD_ENUM),
    };
    let out = if j.has_constants != 0 {
        let k = JointConstants::new(
            j.scale,
            j.axis,
            j.axis_sq,
            j.axis_prod,
            j.v,
            j.axis_cross_v,
            j.axial_v,
        );
        Joint::with_constants("", kind, j.screw, j.lower, j.upper, k)
    } else {
        Joint::new("", kind, j.screw, j.lower, j.upper)
    };
    Ok(out)
}

/// The convention of a `PPOE_CONVENTION_*` value.
pub(crate) fn convention(c: i32) -> Result<Convention, ppoe_status> {
    match c {
        PPOE_CONVENTION_RIGHT => Ok(Convention::Right),
        PPOE_CONVENTION_LEFT => Ok(Convention::Left),
        PPOE_CONVENTION_PYTRANSFORM3D => Ok(Convention::Pytransform3d),
        _ => Err(PPOE_ERR_BAD_ENUM),
    }
}

/// `n` joint values.
///
/// # Safety
/// `thetas` is NULL or points to `n` values.
pub(crate) unsafe fn thetas<'a, T>(thetas: *const T, n: usize) -> Result<&'a [T], ppoe_status> {
    if n > PPOE_MAX_JOINTS as usize {
        return Err(PPOE_ERR_TOO_MANY_JOINTS);
    }
    if n == 0 {
        return Ok(&[]);
    }
    if thetas.is_null() {
        return Err(PPOE_ERR_NULL_POINTER);
    }
    // SAFETY: not NULL, `n` values by the caller's contract.
    Ok(unsafe { core::slice::from_raw_parts(thetas, n) })
}

/// `n` row-major 6×6 covariances, copied into `out`.
///
/// # Safety
/// `covs` is NULL or points to `36·n` values.
pub(crate) unsafe fn covs<T: Real>(
    covs: *const T,
    n: usize,
    out: &mut Covs<T>,
) -> Result<(), ppoe_status> {
    if n > PPOE_MAX_JOINTS as usize {
        return Err(PPOE_ERR_TOO_MANY_JOINTS);
    }
    if n > 0 && covs.is_null() {
        return Err(PPOE_ERR_NULL_POINTER);
    }
    let flat: &[T] = if n == 0 {
        &[]
    } else {
        // SAFETY: not NULL, 36·n values by the caller's contract (n bounded: no overflow).
        unsafe { core::slice::from_raw_parts(covs, 36 * n) }
    };
    out.clear();
    for m in flat.chunks_exact(36) {
        let mut c = [[T::ZERO; 6]; 6];
        for (row, src) in c.iter_mut().zip(m.chunks_exact(6)) {
            row.copy_from_slice(src);
        }
        out.push(Matrix(c)).map_err(|_| PPOE_ERR_TOO_MANY_JOINTS)?;
    }
    Ok(())
}

/// Writes a pose (4×4 row-major) if it is finite.
///
/// # Safety
/// `out` is NULL or points to 16 writable values.
pub(crate) unsafe fn write_pose<T: Real>(
    pose: &Transform<T>,
    out: *mut T,
) -> Result<(), ppoe_status> {
    if out.is_null() {
        return Err(PPOE_ERR_NULL_POINTER);
    }
    let m = pose.to_matrix4();
    if !m.iter().flatten().all(|x| x.is_finite()) {
        return Err(PPOE_ERR_NON_FINITE);
    }
    for (i, x) in m.iter().flatten().enumerate() {
        // SAFETY: i < 16, within the caller's array.
        unsafe { out.add(i).write(*x) };
    }
    Ok(())
}

/// Writes a PPOE result (pose 16, covariance 36) if both are finite; nothing otherwise.
///
/// # Safety
/// `pose` and `cov` are NULL or point to 16 and 36 writable values.
pub(crate) unsafe fn write_result<T: Real>(
    r: &UncertainPose<T>,
    pose: *mut T,
    cov: *mut T,
) -> Result<(), ppoe_status> {
    if cov.is_null() || pose.is_null() {
        return Err(PPOE_ERR_NULL_POINTER);
    }
    if !r.cov.is_finite() {
        return Err(PPOE_ERR_NON_FINITE);
    }
    // SAFETY: forwarded contract.
    unsafe { write_pose(&r.pose, pose) }?;
    for (i, x) in r.cov.0.iter().flatten().enumerate() {
        // SAFETY: i < 36, within the caller's array.
        unsafe { cov.add(i).write(*x) };
    }
    Ok(())
}
