//! The PPOE and forward kinematics of a batch of configurations on a chain, in f64 or
//! f32, with the GIL released. Each configuration is one call of the core, so a batch's
//! results equal the single calls' bit for bit.

use crate::convert::{array, elements, mat6s, matrix, push_matrix, push_transform};
use crate::{core_err, PpoeError};
use numpy::{Element, PyArrayDyn, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use ppoe::chain::{ChainView, Convention};
use ppoe::uncertainty::check_covariance;
use ppoe::{Error, Mat6, Real};
use pyo3::prelude::*;

/// An array of the chain's scalar.
type ArrayOf<'py, T> = Bound<'py, PyArrayDyn<T>>;

/// The error of configuration `i` of a batch: the core's message, and which one.
fn batch_err(i: usize, e: Error) -> PyErr {
    PpoeError::new_err(format!("configuration {i}: {e}"))
}

/// Forward kinematics of N configurations `thetas` (N, n) → (N, 4, 4).
pub(crate) fn forward_kinematics<'py, T: Real + Element + Send + Sync>(
    py: Python<'py>,
    view: ChainView<'_, T>,
    thetas: &PyReadonlyArrayDyn<'py, T>,
) -> PyResult<ArrayOf<'py, T>> {
    let n = view.joints.len();
    let th = elements(thetas, "thetas", &[usize::MAX, n])?;
    let count = thetas.shape()[0];
    let out = py.detach(|| -> Result<Vec<T>, PyErr> {
        let mut out = Vec::with_capacity(16 * count);
        for i in 0..count {
            let t = view.forward_kinematics(&th[i * n..(i + 1) * n]);
            push_transform(&mut out, &t.map_err(|e| batch_err(i, e))?);
        }
        Ok(out)
    })?;
    array(py, out, &[count, 4, 4])
}

/// The PPOE of N configurations `thetas` (N, n) with covariances (n, 6, 6) shared by all
/// or (N, n, 6, 6) → poses (N, 4, 4), covariances (N, 6, 6).
pub(crate) fn ppoe<'py, T: Real + Element + Send + Sync>(
    py: Python<'py>,
    view: ChainView<'_, T>,
    thetas: &PyReadonlyArrayDyn<'py, T>,
    covs: &PyReadonlyArrayDyn<'py, T>,
    convention: Convention,
) -> PyResult<(ArrayOf<'py, T>, ArrayOf<'py, T>)> {
    let n = view.joints.len();
    let th = elements(thetas, "thetas", &[usize::MAX, n])?;
    let count = thetas.shape()[0];
    let shared = covs.ndim() == 3;
    let c = if shared {
        elements(covs, "covs", &[n, 6, 6])?
    } else {
        elements(covs, "covs", &[count, n, 6, 6])?
    };
    let (poses, out_covs) = py.detach(|| ppoe_all(view, count, th, c, shared, convention))?;
    Ok((
        array(py, poses, &[count, 4, 4])?,
        array(py, out_covs, &[count, 6, 6])?,
    ))
}

/// The PPOE of every configuration: `covs` holds n covariances shared by all (checked
/// once), or n per configuration. Writes 16 + 36 values per configuration.
fn ppoe_all<T: Real>(
    view: ChainView<'_, T>,
    count: usize,
    thetas: &[T],
    covs: &[T],
    shared: bool,
    convention: Convention,
) -> Result<(Vec<T>, Vec<T>), PyErr> {
    let n = view.joints.len();
    let mut per = vec![Mat6::zeros(); n];
    if shared {
        per = mat6s(covs);
        for c in &per {
            check_covariance(c).map_err(core_err)?;
        }
    }
    let (mut poses, mut out_covs) = (
        Vec::with_capacity(16 * count),
        Vec::with_capacity(36 * count),
    );
    for i in 0..count {
        if !shared {
            for (k, c) in per.iter_mut().enumerate() {
                *c = matrix(covs, 36 * (i * n + k));
                check_covariance(c).map_err(|e| batch_err(i, e))?;
            }
        }
        let th = &thetas[i * n..(i + 1) * n];
        if !th.iter().all(|t| t.is_finite()) {
            return Err(batch_err(i, Error::NonFinite));
        }
        let r = view
            .ppoe(th, &per, convention)
            .map_err(|e| batch_err(i, e))?;
        if !(r.cov.is_finite() && r.pose.rotation.is_finite() && r.pose.translation.is_finite()) {
            return Err(batch_err(i, Error::Overflow));
        }
        push_transform(&mut poses, &r.pose);
        push_matrix(&mut out_covs, &r.cov);
    }
    Ok((poses, out_covs))
}
