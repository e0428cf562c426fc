//! The PPOE and forward kinematics of a batch of configurations on a chain, in f64 or
//! f32, with the GIL released. The PPOE is the core's batch call, whose result for a
//! configuration does not depend on the batch it is in: a batch's results equal the
//! single calls' (batches of one) bit for bit.

use crate::convert::{array, elements, mat6s, push_matrix, push_transform};
use crate::{core_err, PpoeError};
use numpy::{Element, PyArrayDyn, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use ppoe::chain::{ChainView, Convention, UncertainPose};
use ppoe::{Error, Real, Transform};
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

/// Configurations per call of the core: the results of one call sit in a buffer on the
/// stack before they are written to the output arrays, which are touched once.
const CHUNK: usize = 64;

/// The PPOE of every configuration through the core's checked batch calls
/// (`ppoe_batch_checked`, or `ppoe_batch_per_config_checked` when `covs` holds n
/// covariances per configuration rather than n shared by all), `CHUNK` configurations at a
/// time: a configuration's result does not depend on the batch it is in, so a single
/// configuration (a batch of one) and the same configuration in any batch agree bit for
/// bit. Writes 16 + 36 values per configuration.
fn ppoe_all<T: Real>(
    view: ChainView<'_, T>,
    count: usize,
    thetas: &[T],
    covs: &[T],
    shared: bool,
    convention: Convention,
) -> Result<(Vec<T>, Vec<T>), PyErr> {
    let n = view.joints.len();
    let per = mat6s(covs);
    let (mut poses, mut out_covs) = (
        Vec::with_capacity(16 * count),
        Vec::with_capacity(36 * count),
    );
    let mut buf = [UncertainPose::certain(Transform::identity()); CHUNK];
    for first in (0..count).step_by(CHUNK) {
        let rows = CHUNK.min(count - first);
        let (th, out) = (&thetas[first * n..(first + rows) * n], &mut buf[..rows]);
        let done = if shared {
            view.ppoe_batch_checked(th, &per, convention, out)
        } else {
            let c = &per[first * n..(first + rows) * n];
            view.ppoe_batch_per_config_checked(th, c, convention, out)
        };
        done.map_err(|e| match e.config {
            Some(i) => batch_err(first + i, e.error),
            None => core_err(e.error),
        })?;
        for r in out.iter() {
            push_transform(&mut poses, &r.pose);
            push_matrix(&mut out_covs, &r.cov);
        }
    }
    Ok((poses, out_covs))
}
