//! `ppoe.fit`: the noise fit of `ppoe fit` (ppoe-fit's `fit_campaign`) on numpy arrays.
//! The result is the command's output JSON, built by the same function
//! (`ppoe_fit::json::campaign`; the package's test_fit.py also compares the two on
//! datasets), then converted to Python: numeric arrays
//! become float64 numpy arrays of their shape (a `null` entry NaN), everything else dicts,
//! lists, str, int, float, bool and None.

use crate::convert::{array, elements};
use crate::robot::Robot;
use crate::PpoeError;
use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use ppoe::chain::Joint;
use ppoe_fit::{CampaignSample, Estimate, Measurement, MeasurementCov, Model};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pyo3::IntoPyObjectExt;
use serde_json::{json, Value};
use std::collections::BTreeSet;
use std::sync::{Mutex, PoisonError};

/// The name as `&'static str`, which ppoe's `Joint` holds (the fit's messages and
/// parameter names use it): each distinct name is leaked once, not once per fit.
fn intern(name: &str) -> &'static str {
    static NAMES: Mutex<BTreeSet<&'static str>> = Mutex::new(BTreeSet::new());
    let mut set = NAMES.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some(n) = set.get(name) {
        return n;
    }
    let n: &'static str = Box::leak(name.into());
    set.insert(n);
    n
}

/// `"joint"` or `"full"`, as `ppoe fit --model`.
fn model_of(name: &str) -> PyResult<Model> {
    match name {
        "joint" => Ok(Model::Joint),
        "full" => Ok(Model::Full),
        _ => Err(PyValueError::new_err(format!(
            "model must be 'joint' or 'full', not {name:?}"
        ))),
    }
}

/// The groups of `ppoe fit --estimate`: `base`, `tip`, `offsets`, `kinematics`, `all`.
fn estimate_of(names: &[String]) -> PyResult<Estimate> {
    let mut e = Estimate::NONE;
    for item in names {
        match item.as_str() {
            "base" => e.base = true,
            "tip" => e.tip = true,
            "offsets" => e.offsets = true,
            "kinematics" => e.kinematics = true,
            "all" => e = Estimate::ALL,
            other => {
                return Err(PyValueError::new_err(format!(
                    "estimate: unknown group {other:?} (expected base, tip, offsets, \
                     kinematics or all)"
                )))
            }
        }
    }
    Ok(e)
}

/// The samples from joint values (N, n) and measured poses (N, 4, 4) or positions (N, 3).
fn samples(
    thetas: &PyReadonlyArrayDyn<'_, f64>,
    measured: &PyReadonlyArrayDyn<'_, f64>,
    n: usize,
) -> PyResult<Vec<CampaignSample>> {
    let t = elements(thetas, "thetas", &[usize::MAX, n])?;
    let count = thetas.shape()[0];
    let pose = measured.ndim() == 3;
    let shape: &[usize] = if pose { &[count, 4, 4] } else { &[count, 3] };
    let m = elements(measured, "measurements", shape)?;
    let at = |x: &[f64], k: usize, w: usize| x[k * w..(k + 1) * w].to_vec();
    Ok((0..count)
        .map(|k| CampaignSample {
            thetas: at(t, k, n),
            measurement: if pose {
                let v = at(m, k, 16);
                Measurement::Pose(std::array::from_fn(|r| {
                    std::array::from_fn(|c| v[4 * r + c])
                }))
            } else {
                let v = at(m, k, 3);
                Measurement::Position([v[0], v[1], v[2]])
            },
        })
        .collect())
}

/// The tracker's noise: (6, 6) for poses, (3, 3) for positions.
fn measurement_cov(
    r: Option<&PyReadonlyArrayDyn<'_, f64>>,
    pose: bool,
) -> PyResult<Option<MeasurementCov>> {
    let Some(r) = r else { return Ok(None) };
    let d = if pose { 6 } else { 3 };
    let x = elements(r, "measurement_cov", &[d, d])?;
    Ok(Some(if pose {
        MeasurementCov::Pose(std::array::from_fn(|i| {
            std::array::from_fn(|j| x[6 * i + j])
        }))
    } else {
        MeasurementCov::Position(std::array::from_fn(|i| {
            std::array::from_fn(|j| x[3 * i + j])
        }))
    }))
}

/// The fit of `ppoe fit` for `robot`: joint values `thetas` (N, n), measured poses
/// (N, 4, 4) or positions (N, 3), the tracker's noise, the model and the calibration
/// groups; `progress(step, log_likelihood)` after each step. The GIL is released while
/// fitting (the callback takes it back); an exception of the callback is raised once the
/// fit has finished (the fit cannot be stopped), and no later step calls it again.
#[pyfunction]
#[pyo3(signature = (robot, thetas, measured, measurement_cov, model, estimate, progress=None))]
#[allow(clippy::too_many_arguments)]
fn fit<'py>(
    py: Python<'py>,
    robot: &Bound<'py, Robot>,
    thetas: PyReadonlyArrayDyn<'py, f64>,
    measured: PyReadonlyArrayDyn<'py, f64>,
    measurement_cov: Option<PyReadonlyArrayDyn<'py, f64>>,
    model: &str,
    estimate: Vec<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let robot = robot.get();
    let (joints, home) = robot.chain();
    let (base, tip, names) = robot.names();
    let samples = samples(&thetas, &measured, joints.len())?;
    let r = self::measurement_cov(measurement_cov.as_ref(), measured.ndim() == 3)?;
    let (model, estimate) = (model_of(model)?, estimate_of(&estimate)?);
    let joints: Vec<Joint<f64>> = joints
        .iter()
        .zip(names)
        .map(|(j, n)| {
            let mut j = *j;
            j.name = intern(n);
            j
        })
        .collect();
    let home = *home;
    let mut raised: Option<PyErr> = None;
    let out = py.detach(|| {
        let mut step = |it: usize, l: f64| {
            if let (Some(cb), None) = (&progress, &raised) {
                raised = Python::attach(|py| cb.call1(py, (it, l)).err());
            }
        };
        ppoe_fit::fit_campaign(
            &joints,
            &home,
            &samples,
            r.as_ref(),
            model,
            estimate,
            &mut step,
        )
    });
    if let Some(e) = raised {
        return Err(e);
    }
    let out = out.map_err(|e| PpoeError::new_err(e.to_string()))?;
    let chain = json!({"base": base, "tip": tip, "joints": names});
    to_python(py, &ppoe_fit::json::campaign(chain, &out, r.as_ref()))
}

/// The shape of `v` if it is a non-empty array of numbers or nulls, or of such arrays
/// of one shape (a vector or matrix of the output); `None` otherwise.
fn numeric_shape(v: &Value) -> Option<Vec<usize>> {
    let Value::Array(items) = v else { return None };
    let mut inner: Option<Vec<usize>> = None;
    for item in items {
        let s = match item {
            Value::Number(_) | Value::Null => Vec::new(),
            Value::Array(_) => numeric_shape(item)?,
            _ => return None,
        };
        if inner.get_or_insert_with(|| s.clone()) != &s {
            return None;
        }
    }
    let mut shape = vec![items.len()];
    shape.extend(inner?);
    Some(shape)
}

/// The numbers of a numeric array, row-major, `null` as NaN.
fn flatten(v: &Value, out: &mut Vec<f64>) {
    match v {
        Value::Array(items) => items.iter().for_each(|x| flatten(x, out)),
        x => out.push(x.as_f64().unwrap_or(f64::NAN)),
    }
}

/// The JSON tree as Python objects: numeric arrays as float64 numpy arrays, integers as
/// int, other numbers as float, `null` as None.
fn to_python<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    match v {
        Value::Null => Ok(py.None().into_bound(py)),
        Value::Bool(b) => b.into_bound_py_any(py),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => u.into_bound_py_any(py),
            (None, Some(i)) => i.into_bound_py_any(py),
            _ => n.as_f64().unwrap_or(f64::NAN).into_bound_py_any(py),
        },
        Value::String(s) => s.into_bound_py_any(py),
        Value::Array(items) => match numeric_shape(v) {
            Some(shape) => {
                let mut data = Vec::new();
                flatten(v, &mut data);
                Ok(array(py, data, &shape)?.into_any())
            }
            None => {
                let list = PyList::empty(py);
                for x in items {
                    list.append(to_python(py, x)?)?;
                }
                Ok(list.into_any())
            }
        },
        Value::Object(m) => {
            let d = PyDict::new(py);
            for (k, x) in m {
                d.set_item(k, to_python(py, x)?)?;
            }
            Ok(d.into_any())
        }
    }
}

/// Adds `fit` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fit, m)?)
}
