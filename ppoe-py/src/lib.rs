//! The native half of the Python package `ppoe` (`ppoe._ppoe`): thin wrappers of the
//! core crate's functions on contiguous float64 numpy arrays. The Python half
//! (`python/ppoe/`) converts and validates the user's arrays, and gives the functions
//! pytransform3d's names, argument order and defaults.
//!
//! Every core error becomes `ppoe.PpoeError`, a subclass of `ValueError`, with the core's
//! message.
#![deny(missing_docs)]

use pyo3::prelude::*;

mod batch;
mod convert;
mod estimate;
mod fit;
mod robot;
mod ros;
mod surface;
mod uncertainty;

pyo3::create_exception!(
    _ppoe,
    PpoeError,
    pyo3::exceptions::PyValueError,
    "An error of the ppoe core (invalid input or a result that overflowed)."
);

/// The core's error as a Python `PpoeError` (a `ValueError`) with the core's message.
pub(crate) fn core_err(e: ppoe::Error) -> PyErr {
    PpoeError::new_err(e.to_string())
}

/// The module `ppoe._ppoe`.
#[pymodule]
fn _ppoe(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("PpoeError", m.py().get_type::<PpoeError>())?;
    uncertainty::register(m)?;
    estimate::register(m)?;
    fit::register(m)?;
    surface::register(m)?;
    ros::register(m)?;
    m.add_class::<robot::Robot>()?;
    Ok(())
}
