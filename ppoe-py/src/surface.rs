//! pytransform3d's ellipsoids of an uncertainty (`ppoe::surface`).

use crate::convert::{
    array, elements, matrix, matrix_array, transform, transform_array, vec3, vec3_array, Array,
    Pair,
};
use crate::core_err;
use numpy::{PyArrayDyn, PyReadonlyArrayDyn};
use ppoe::linalg::SymmetricEigen;
use ppoe::surface;
use ppoe::{Mat6, Vec3, Vector};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The largest `n_steps` of a projected ellipsoid: n² points are allocated, and a grid of
/// 2000² (4·10⁶ points, 96 MB) is far beyond what a plot needs.
const MAX_STEPS: usize = 2000;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(to_ellipsoid, m)?)?;
    m.add_function(wrap_pyfunction!(to_projected_ellipsoid, m)?)?;
    m.add_function(wrap_pyfunction!(symmetric_eigen6, m)?)?;
    m.add_function(wrap_pyfunction!(surface_grid, m)?)?;
    m.add_function(wrap_pyfunction!(chi2_3_radius, m)?)?;
    m.add_function(wrap_pyfunction!(chi2_3_probability, m)?)?;
    Ok(())
}

/// `ppoe::surface::to_ellipsoid`: (ellipsoid2origin (4, 4), radii (3,)).
#[pyfunction]
fn to_ellipsoid<'py>(
    py: Python<'py>,
    mean: PyReadonlyArrayDyn<'py, f64>,
    cov: PyReadonlyArrayDyn<'py, f64>,
) -> PyResult<Pair<'py>> {
    let (frame, radii) = surface::to_ellipsoid(
        &vec3(elements(&mean, "mean", &[3])?),
        &matrix(elements(&cov, "cov", &[3, 3])?, 0),
    )
    .map_err(core_err)?;
    Ok((transform_array(py, &frame)?, vec3_array(py, &radii)?))
}

/// `ppoe::surface::to_projected_ellipsoid` as an (n_steps², 3) array, row-major over the
/// grid; with `eigen = (values (6,) descending, vectors (6, 6) as columns)` the given
/// basis is used (`to_projected_ellipsoid_from_eigen`).
#[pyfunction]
#[pyo3(signature = (mean, cov, factor, n_steps, eigen=None))]
fn to_projected_ellipsoid<'py>(
    py: Python<'py>,
    mean: PyReadonlyArrayDyn<'py, f64>,
    cov: PyReadonlyArrayDyn<'py, f64>,
    factor: f64,
    n_steps: usize,
    eigen: Option<(PyReadonlyArrayDyn<'py, f64>, PyReadonlyArrayDyn<'py, f64>)>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    if n_steps > MAX_STEPS {
        return Err(PyValueError::new_err(format!(
            "n_steps must be at most {MAX_STEPS}, got {n_steps}"
        )));
    }
    let mean = transform(elements(&mean, "mean", &[4, 4])?, 0);
    let cov = matrix(elements(&cov, "cov", &[6, 6])?, 0);
    let mut out = vec![Vec3::zeros(); n_steps * n_steps];
    let n = match eigen {
        None => surface::to_projected_ellipsoid(&mean, &cov, factor, n_steps, &mut out),
        Some((values, vectors)) => {
            let v = elements(&values, "eigenvalues", &[6])?;
            let values = Vector(core::array::from_fn(|i| v[i]));
            let vectors = matrix(elements(&vectors, "eigenvectors", &[6, 6])?, 0);
            surface::to_projected_ellipsoid_from_eigen(
                &mean, &values, &vectors, factor, n_steps, &mut out,
            )
        }
    }
    .map_err(core_err)?;
    let flat: Vec<f64> = out[..n].iter().flat_map(|p| p.0).collect();
    array(py, flat, &[n, 3])
}

/// The core's eigen-decomposition of a symmetric 6×6 matrix: values (6,) descending and
/// the eigenvectors as the columns of a (6, 6) array.
#[pyfunction]
fn symmetric_eigen6<'py>(py: Python<'py>, a: PyReadonlyArrayDyn<'py, f64>) -> PyResult<Pair<'py>> {
    let m: Mat6<f64> = matrix(elements(&a, "cov", &[6, 6])?, 0);
    let e = SymmetricEigen::new(&m).map_err(core_err)?;
    Ok((
        array(py, e.values.0.to_vec(), &[6])?,
        matrix_array(py, &e.vectors)?,
    ))
}

/// `ppoe::surface::surface_grid` of `kind` ('lift', 'marginal' or 'pytransform3d') at
/// radius `k`: an (n_steps², 3) array, row-major over the grid.
#[pyfunction]
fn surface_grid<'py>(
    py: Python<'py>,
    kind: &str,
    mean: PyReadonlyArrayDyn<'py, f64>,
    cov: PyReadonlyArrayDyn<'py, f64>,
    k: f64,
    n_steps: usize,
) -> PyResult<Array<'py>> {
    let kind = match kind {
        "lift" => surface::Surface::Lift,
        "marginal" => surface::Surface::Marginal,
        "pytransform3d" => surface::Surface::Pytransform3d,
        _ => {
            return Err(PyValueError::new_err(format!(
                "kind must be 'lift', 'marginal' or 'pytransform3d', not {kind:?}"
            )))
        }
    };
    if n_steps > MAX_STEPS {
        return Err(PyValueError::new_err(format!(
            "n_steps must be at most {MAX_STEPS}, got {n_steps}"
        )));
    }
    let mean = transform(elements(&mean, "pose", &[4, 4])?, 0);
    let cov = matrix(elements(&cov, "cov", &[6, 6])?, 0);
    let mut out = vec![Vec3::zeros(); n_steps * n_steps];
    let n = surface::surface_grid(kind, &mean, &cov, k, n_steps, &mut out).map_err(core_err)?;
    let flat: Vec<f64> = out[..n].iter().flat_map(|p| p.0).collect();
    array(py, flat, &[n, 3])
}

/// The radius k whose 3D Gaussian ball holds probability `p` (χ²₃), or an error for p
/// outside [0, 1).
#[pyfunction]
fn chi2_3_radius(p: f64) -> PyResult<f64> {
    surface::chi2_3_radius(p)
        .ok_or_else(|| PyValueError::new_err(format!("probability must be in [0, 1), got {p}")))
}

/// The probability that a 3D standard normal vector has norm at most k.
#[pyfunction]
fn chi2_3_probability(k: f64) -> PyResult<f64> {
    if k.is_nan() {
        return Err(PyValueError::new_err("k must be a number, got NaN"));
    }
    Ok(surface::chi2_3_probability(k))
}
