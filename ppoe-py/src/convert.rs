//! numpy arrays ↔ the core's fixed-size types. The Python wrappers pass C-contiguous
//! float64 arrays; the shapes are checked here again so that a direct call of
//! `ppoe._ppoe` with a wrong array is an error, never a wrong answer.

use numpy::{
    Element, PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyReadwriteArrayDyn,
    PyUntypedArrayMethods,
};
use ppoe::{Mat3, Mat6, Matrix, Real, Transform, Vec3, Vector};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A float64 numpy array of any shape.
pub(crate) type Array<'py> = Bound<'py, PyArrayDyn<f64>>;

/// Two arrays (a mean and a covariance, mostly).
pub(crate) type Pair<'py> = (Array<'py>, Array<'py>);

/// The elements of `a` if its shape is `shape` (`usize::MAX` matches any length).
pub(crate) fn elements<'a, T: Element>(
    a: &'a PyReadonlyArrayDyn<'_, T>,
    name: &str,
    shape: &[usize],
) -> PyResult<&'a [T]> {
    check_layout(name, a.shape(), a.is_c_contiguous(), shape)?;
    a.as_slice().map_err(|_| not_c_contiguous(name))
}

/// The elements of the writeable array `a`, for results, if its shape is `shape` (as
/// [`elements`]).
pub(crate) fn elements_mut<'a, T: Element>(
    a: &'a mut PyReadwriteArrayDyn<'_, T>,
    name: &str,
    shape: &[usize],
) -> PyResult<&'a mut [T]> {
    check_layout(name, a.shape(), a.is_c_contiguous(), shape)?;
    a.as_slice_mut().map_err(|_| not_c_contiguous(name))
}

/// Refuses an array of shape `got` unless it matches `shape` (`usize::MAX` matches any
/// length) and is C-contiguous: a slice of a Fortran-ordered array would be read (or
/// written) transposed.
fn check_layout(name: &str, got: &[usize], c_contiguous: bool, shape: &[usize]) -> PyResult<()> {
    let ok = got.len() == shape.len()
        && got
            .iter()
            .zip(shape)
            .all(|(g, s)| *s == usize::MAX || g == s);
    if !ok {
        return Err(PyValueError::new_err(format!(
            "{name}: expected shape {}, got {got:?}",
            shape_text(shape)
        )));
    }
    if !c_contiguous {
        return Err(not_c_contiguous(name));
    }
    Ok(())
}

fn not_c_contiguous(name: &str) -> PyErr {
    PyValueError::new_err(format!("{name}: array is not C-contiguous"))
}

fn shape_text(shape: &[usize]) -> String {
    let parts: Vec<String> = shape
        .iter()
        .map(|s| {
            if *s == usize::MAX {
                "N".to_string()
            } else {
                s.to_string()
            }
        })
        .collect();
    format!("({})", parts.join(", "))
}

/// A row-major `R×C` block of `x` starting at element `at`.
pub(crate) fn matrix<T: Copy, const R: usize, const C: usize>(
    x: &[T],
    at: usize,
) -> Matrix<T, R, C> {
    Matrix(core::array::from_fn(|r| {
        core::array::from_fn(|c| x[at + r * C + c])
    }))
}

/// The 4×4 row-major transform at element `at` (the last row is not read).
pub(crate) fn transform<T: Real>(x: &[T], at: usize) -> Transform<T> {
    let m: Matrix<T, 4, 4> = matrix(x, at);
    Transform::from_matrix4(&m.0)
}

/// The 6×6 matrices of `x`, one per 36 elements.
pub(crate) fn mat6s<T: Copy>(x: &[T]) -> Vec<Mat6<T>> {
    (0..x.len() / 36).map(|k| matrix(x, 36 * k)).collect()
}

/// Appends a transform as a 4×4 row-major matrix.
pub(crate) fn push_transform<T: Real>(out: &mut Vec<T>, t: &Transform<T>) {
    for row in t.to_matrix4() {
        out.extend_from_slice(&row);
    }
}

/// Appends a matrix row-major.
pub(crate) fn push_matrix<T: Copy, const R: usize, const C: usize>(
    out: &mut Vec<T>,
    m: &Matrix<T, R, C>,
) {
    for row in &m.0 {
        out.extend_from_slice(row);
    }
}

/// `data` as a numpy array of shape `shape`.
pub(crate) fn array<'py, T: Element>(
    py: Python<'py>,
    data: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    PyArray1::from_vec(py, data).reshape(shape.to_vec())
}

/// A transform and a covariance as (4, 4) and (6, 6) arrays, or the core's overflow error
/// if either is not finite: a result computed from finite inputs (the wrappers reject the
/// others) is never handed back as ±∞ or NaN.
pub(crate) fn finite_pair<'py>(
    py: Python<'py>,
    t: &Transform<f64>,
    cov: &Mat6<f64>,
) -> PyResult<Pair<'py>> {
    if !(t.rotation.is_finite() && t.translation.is_finite() && cov.is_finite()) {
        return Err(crate::core_err(ppoe::Error::Overflow));
    }
    Ok((transform_array(py, t)?, matrix_array(py, cov)?))
}

/// A transform as a (4, 4) array.
pub(crate) fn transform_array<'py>(
    py: Python<'py>,
    t: &Transform<f64>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let mut v = Vec::with_capacity(16);
    push_transform(&mut v, t);
    array(py, v, &[4, 4])
}

/// A matrix as an (R, C) array.
pub(crate) fn matrix_array<'py, const R: usize, const C: usize>(
    py: Python<'py>,
    m: &Matrix<f64, R, C>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let mut v = Vec::with_capacity(R * C);
    push_matrix(&mut v, m);
    array(py, v, &[R, C])
}

/// A 3-vector as a (3,) array.
pub(crate) fn vec3_array<'py>(
    py: Python<'py>,
    v: &Vec3<f64>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    array(py, v.0.to_vec(), &[3])
}

/// The 3×3 matrices of `x`, one per 9 elements.
pub(crate) fn mat3s(x: &[f64]) -> Vec<Mat3<f64>> {
    (0..x.len() / 9).map(|k| matrix(x, 9 * k)).collect()
}

/// The 3-vector of `x`.
pub(crate) fn vec3(x: &[f64]) -> Vec3<f64> {
    Vector([x[0], x[1], x[2]])
}
