//! The exported functions: one thin `extern "C"` wrapper per scalar around one generic
//! body each.

use crate::convert::{self, Covs, Joints};
use crate::*;
use core::ffi::c_char;
use ppoe::Real;

/// Runs `f`; its error or `PPOE_OK`.
fn run(f: impl FnOnce() -> Result<(), ppoe_status>) -> ppoe_status {
    match f() {
        Ok(()) => PPOE_OK,
        Err(s) => s,
    }
}

unsafe fn check<T: Real>(chain: *const ppoe_chain<T>) -> ppoe_status {
    let mut joints = Joints::new();
    run(|| {
        // SAFETY: forwarded contract of the exported function.
        let c = unsafe { convert::chain(chain, &mut joints) }?;
        c.check().map_err(status)
    })
}

unsafe fn forward_kinematics<T: Real>(
    chain: *const ppoe_chain<T>,
    thetas: *const T,
    n_thetas: usize,
    pose: *mut T,
) -> ppoe_status {
    let mut joints = Joints::new();
    run(|| {
        // SAFETY (all three): forwarded contract of the exported function.
        let c = unsafe { convert::chain(chain, &mut joints) }?;
        let th = unsafe { convert::thetas(thetas, n_thetas) }?;
        let t = c.forward_kinematics(th).map_err(status)?;
        unsafe { convert::write_pose(&t, pose) }
    })
}

/// The arguments of both PPOE entry points.
struct PpoeArgs<T> {
    chain: *const ppoe_chain<T>,
    thetas: *const T,
    n_thetas: usize,
    covs: *const T,
    n_covs: usize,
    convention: i32,
    pose: *mut T,
    cov: *mut T,
}

/// `CHECKED` a constant: each entry point links only its own path.
unsafe fn ppoe<T: Real, const CHECKED: bool>(a: PpoeArgs<T>) -> ppoe_status {
    let mut joints = Joints::new();
    let mut covs = Covs::new();
    run(|| {
        // SAFETY (all): forwarded contract of the exported function.
        let c = unsafe { convert::chain(a.chain, &mut joints) }?;
        let th = unsafe { convert::thetas(a.thetas, a.n_thetas) }?;
        unsafe { convert::covs(a.covs, a.n_covs, &mut covs) }?;
        let conv = convert::convention(a.convention)?;
        let r = if CHECKED {
            c.ppoe_checked(th, &covs, conv)
        } else {
            c.ppoe(th, &covs, conv)
        };
        unsafe { convert::write_result(&r.map_err(status)?, a.pose, a.cov) }
    })
}

/// Checks a chain: finite unit screw axes (zero rotation and unit translation for a
/// prismatic joint) within the scalar's tolerance, limits not NaN, displacement constants
/// (where given) those of the screw, a valid home pose (orthonormal rotation, det +1).
///
/// # Safety
/// `chain` is NULL or points to a valid chain whose `joints` holds `n_joints` joints.
#[no_mangle]
pub unsafe extern "C" fn ppoe_chain_check_f32(chain: *const ppoe_chain_f32) -> ppoe_status {
    // SAFETY: the caller's contract.
    unsafe { check(chain) }
}

/// `ppoe_chain_check_f32` in double precision.
///
/// # Safety
/// As `ppoe_chain_check_f32`.
#[no_mangle]
pub unsafe extern "C" fn ppoe_chain_check_f64(chain: *const ppoe_chain_f64) -> ppoe_status {
    // SAFETY: the caller's contract.
    unsafe { check(chain) }
}

/// Rigid forward kinematics `Exp(S1·θ1)···Exp(Sn·θn)·M` (tip to base) after clipping θ to
/// the limits, into `pose_out` (4×4 row-major). `n_thetas` must equal the chain's
/// `n_joints`. Unchecked chain (see `ppoe_chain_check_f32`); a non-finite pose is
/// `PPOE_ERR_NON_FINITE`. Accuracy: a few ulps of the scalar per joint.
///
/// # Safety
/// Pointers NULL or valid: `chain` as in `ppoe_chain_check_f32`, `thetas` `n_thetas`
/// values, `pose_out` 16 writable values.
#[no_mangle]
pub unsafe extern "C" fn ppoe_forward_kinematics_f32(
    chain: *const ppoe_chain_f32,
    thetas: *const f32,
    n_thetas: usize,
    pose_out: *mut f32,
) -> ppoe_status {
    // SAFETY: the caller's contract.
    unsafe { forward_kinematics(chain, thetas, n_thetas, pose_out) }
}

/// `ppoe_forward_kinematics_f32` in double precision.
///
/// # Safety
/// As `ppoe_forward_kinematics_f32`.
#[no_mangle]
pub unsafe extern "C" fn ppoe_forward_kinematics_f64(
    chain: *const ppoe_chain_f64,
    thetas: *const f64,
    n_thetas: usize,
    pose_out: *mut f64,
) -> ppoe_status {
    // SAFETY: the caller's contract.
    unsafe { forward_kinematics(chain, thetas, n_thetas, pose_out) }
}

/// The PPOE, inputs unchecked: the tip pose (4×4 row-major, tip to base) and its 6×6
/// covariance (rotation first) for joint values `thetas` (clipped to the limits) and
/// per-joint covariances `covs` (`n_covs` row-major 6×6 matrices, base-frame screw
/// coordinates, right perturbation of each joint's displacement). `convention`:
/// `PPOE_CONVENTION_RIGHT` (perturbation in the tip frame), `_LEFT` (base frame) or
/// `_PYTRANSFORM3D`. `n_thetas` and `n_covs` must equal the chain's `n_joints`. Non-PSD
/// or non-finite inputs give a meaningless result or `PPOE_ERR_NON_FINITE` (the outputs
/// are checked to be finite); use `ppoe_ppoe_checked_f32` to validate the inputs.
/// Accuracy: second-order propagation; f32 within 1e-5 relative of the f64 result on the
/// seed robot's test cases.
///
/// # Safety
/// Pointers NULL or valid: `chain` as in `ppoe_chain_check_f32`, `thetas` `n_thetas`
/// values, `covs` 36·`n_covs` values, `pose_out` 16 and `cov_out` 36 writable values.
#[no_mangle]
pub unsafe extern "C" fn ppoe_ppoe_f32(
    chain: *const ppoe_chain_f32,
    thetas: *const f32,
    n_thetas: usize,
    covs: *const f32,
    n_covs: usize,
    convention: i32,
    pose_out: *mut f32,
    cov_out: *mut f32,
) -> ppoe_status {
    let a = PpoeArgs {
        chain,
        thetas,
        n_thetas,
        covs,
        n_covs,
        convention,
        pose: pose_out,
        cov: cov_out,
    };
    // SAFETY: the caller's contract.
    unsafe { ppoe::<_, false>(a) }
}

/// `ppoe_ppoe_f32` in double precision (f64 within 1e-12 relative of the host's result).
///
/// # Safety
/// As `ppoe_ppoe_f32`.
#[no_mangle]
pub unsafe extern "C" fn ppoe_ppoe_f64(
    chain: *const ppoe_chain_f64,
    thetas: *const f64,
    n_thetas: usize,
    covs: *const f64,
    n_covs: usize,
    convention: i32,
    pose_out: *mut f64,
    cov_out: *mut f64,
) -> ppoe_status {
    let a = PpoeArgs {
        chain,
        thetas,
        n_thetas,
        covs,
        n_covs,
        convention,
        pose: pose_out,
        cov: cov_out,
    };
    // SAFETY: the caller's contract.
    unsafe { ppoe::<_, false>(a) }
}

/// `ppoe_ppoe_f32` with input checks: the chain (`ppoe_chain_check_f32`), every θ finite,
/// every covariance finite, symmetric and positive semi-definite within the scalar's
/// tolerance; errors `PPOE_ERR_NON_FINITE`, `_NOT_SYMMETRIC`,
/// `_NOT_POSITIVE_SEMIDEFINITE`, `_ZERO_AXIS`, `_NOT_A_ROTATION`,
/// `_INCONSISTENT_CONSTANTS`, `_LENGTH_MISMATCH`.
///
/// # Safety
/// As `ppoe_ppoe_f32`.
#[no_mangle]
pub unsafe extern "C" fn ppoe_ppoe_checked_f32(
    chain: *const ppoe_chain_f32,
    thetas: *const f32,
    n_thetas: usize,
    covs: *const f32,
    n_covs: usize,
    convention: i32,
    pose_out: *mut f32,
    cov_out: *mut f32,
) -> ppoe_status {
    let a = PpoeArgs {
        chain,
        thetas,
        n_thetas,
        covs,
        n_covs,
        convention,
        pose: pose_out,
        cov: cov_out,
    };
    // SAFETY: the caller's contract.
    unsafe { ppoe::<_, true>(a) }
}

/// `ppoe_ppoe_checked_f32` in double precision.
///
/// # Safety
/// As `ppoe_ppoe_f32`.
#[no_mangle]
pub unsafe extern "C" fn ppoe_ppoe_checked_f64(
    chain: *const ppoe_chain_f64,
    thetas: *const f64,
    n_thetas: usize,
    covs: *const f64,
    n_covs: usize,
    convention: i32,
    pose_out: *mut f64,
    cov_out: *mut f64,
) -> ppoe_status {
    let a = PpoeArgs {
        chain,
        thetas,
        n_thetas,
        covs,
        n_covs,
        convention,
        pose: pose_out,
        cov: cov_out,
    };
    // SAFETY: the caller's contract.
    unsafe { ppoe::<_, true>(a) }
}

/// A static NUL-terminated English description of a status ("unknown status" for a
/// value that is none).
#[no_mangle]
pub extern "C" fn ppoe_status_message(status: ppoe_status) -> *const c_char {
    let s: &core::ffi::CStr = match status {
        PPOE_OK => c"ok",
        PPOE_ERR_NULL_POINTER => c"a required pointer is NULL",
        PPOE_ERR_NON_FINITE => c"input or result contains NaN or infinity",
        PPOE_ERR_NOT_SYMMETRIC => c"covariance is not symmetric",
        PPOE_ERR_NOT_POSITIVE_SEMIDEFINITE => c"covariance is not positive semi-definite",
        PPOE_ERR_SINGULAR => c"matrix is singular or not positive definite",
        PPOE_ERR_NOT_A_ROTATION => c"rotation part is not orthonormal with determinant +1",
        PPOE_ERR_ZERO_AXIS => c"screw axis is zero",
        PPOE_ERR_EMPTY => c"no input elements",
        PPOE_ERR_TOO_FEW_SAMPLES => c"too few samples",
        PPOE_ERR_BUFFER_TOO_SMALL => c"output buffer too small",
        PPOE_ERR_LENGTH_MISMATCH => c"inputs have mismatched lengths",
        PPOE_ERR_INCONSISTENT_CONSTANTS => c"joint constants do not match its screw axis",
        PPOE_ERR_TOO_MANY_JOINTS => c"more than PPOE_MAX_JOINTS joints",
        PPOE_ERR_BAD_ENUM => c"convention or joint kind out of range",
        PPOE_ERR_OTHER => c"other error",
        PPOE_ERR_OVERFLOW => c"a result overflowed although the inputs were finite",
        PPOE_ERR_NOT_UNIT_AXIS => c"screw axis does not have unit length",
        PPOE_ERR_GRID_SIZE => c"surface grid needs at least two steps",
        _ => c"unknown status",
    };
    s.as_ptr()
}
