//! Concatenation, inversion and fusion of uncertain transforms
//! (`ppoe::uncertainty`), in pytransform3d's argument order.

use crate::convert::{elements, finite_pair, mat6s, matrix, transform, Pair};
use crate::core_err;
use numpy::{PyArrayDyn, PyReadonlyArrayDyn};
use ppoe::uncertainty::{self, IterationOptions, Order};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(concat_globally, m)?)?;
    m.add_function(wrap_pyfunction!(concat_locally, m)?)?;
    m.add_function(wrap_pyfunction!(invert, m)?)?;
    m.add_function(wrap_pyfunction!(pose_fusion, m)?)?;
    Ok(())
}

fn order(name: &str) -> PyResult<Order> {
    match name {
        "second" => Ok(Order::Second),
        "fourth" => Ok(Order::Fourth),
        "fourth_psd" => Ok(Order::FourthPsd),
        _ => Err(PyValueError::new_err(format!(
            "order must be 'second', 'fourth' or 'fourth_psd', not {name:?}"
        ))),
    }
}

/// `ppoe::uncertainty::concat_globally` (left perturbations).
#[pyfunction]
fn concat_globally<'py>(
    py: Python<'py>,
    mean_a2b: PyReadonlyArrayDyn<'py, f64>,
    cov_a2b: PyReadonlyArrayDyn<'py, f64>,
    mean_b2c: PyReadonlyArrayDyn<'py, f64>,
    cov_b2c: PyReadonlyArrayDyn<'py, f64>,
    order_name: &str,
) -> PyResult<Pair<'py>> {
    let (t, c) = uncertainty::concat_globally(
        &transform(elements(&mean_a2b, "mean_A2B", &[4, 4])?, 0),
        &matrix(elements(&cov_a2b, "cov_A2B", &[6, 6])?, 0),
        &transform(elements(&mean_b2c, "mean_B2C", &[4, 4])?, 0),
        &matrix(elements(&cov_b2c, "cov_B2C", &[6, 6])?, 0),
        order(order_name)?,
    );
    finite_pair(py, &t, &c)
}

/// `ppoe::uncertainty::concat_locally` (right perturbations).
#[pyfunction]
fn concat_locally<'py>(
    py: Python<'py>,
    mean_a2b: PyReadonlyArrayDyn<'py, f64>,
    mean_b2c: PyReadonlyArrayDyn<'py, f64>,
    cov_a: PyReadonlyArrayDyn<'py, f64>,
    cov_b: PyReadonlyArrayDyn<'py, f64>,
) -> PyResult<Pair<'py>> {
    let (t, c) = uncertainty::concat_locally(
        &transform(elements(&mean_a2b, "mean_A2B", &[4, 4])?, 0),
        &transform(elements(&mean_b2c, "mean_B2C", &[4, 4])?, 0),
        &matrix(elements(&cov_a, "cov_A", &[6, 6])?, 0),
        &matrix(elements(&cov_b, "cov_B", &[6, 6])?, 0),
    );
    finite_pair(py, &t, &c)
}

/// `ppoe::uncertainty::invert` (left perturbation).
#[pyfunction]
fn invert<'py>(
    py: Python<'py>,
    mean: PyReadonlyArrayDyn<'py, f64>,
    cov: PyReadonlyArrayDyn<'py, f64>,
) -> PyResult<Pair<'py>> {
    let (t, c) = uncertainty::invert(
        &transform(elements(&mean, "mean", &[4, 4])?, 0),
        &matrix(elements(&cov, "cov", &[6, 6])?, 0),
    );
    finite_pair(py, &t, &c)
}

/// `ppoe::uncertainty::pose_fusion`: (mean, cov, cost V, iterations, converged).
#[pyfunction]
#[allow(clippy::type_complexity)]
fn pose_fusion<'py>(
    py: Python<'py>,
    means: PyReadonlyArrayDyn<'py, f64>,
    covs: PyReadonlyArrayDyn<'py, f64>,
) -> PyResult<(
    Bound<'py, PyArrayDyn<f64>>,
    Bound<'py, PyArrayDyn<f64>>,
    f64,
    usize,
    bool,
)> {
    let m = elements(&means, "means", &[usize::MAX, 4, 4])?;
    let k = m.len() / 16;
    let c = elements(&covs, "covs", &[k, 6, 6])?;
    let means: Vec<_> = (0..k).map(|i| transform(m, 16 * i)).collect();
    let fused = uncertainty::pose_fusion(&means, &mat6s(c), &IterationOptions::default())
        .map_err(core_err)?;
    let (mean, cov) = finite_pair(py, &fused.mean, &fused.cov)?;
    Ok((mean, cov, fused.cost, fused.iterations, fused.converged))
}
