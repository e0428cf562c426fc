//! ROS's `geometry_msgs/PoseWithCovariance` (`ppoe::interop::ros`): translation first,
//! the covariance in the parent frame.

use crate::convert::{elements, matrix, matrix_array, transform, Array};
use crate::core_err;
use numpy::PyReadonlyArrayDyn;
use ppoe::interop::ros;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(ros_pose_with_covariance, m)?)?;
    Ok(())
}

/// The quaternion `[w, x, y, z]` of the pose's rotation and the ROS covariance (6, 6,
/// translation first, parent frame) of a `right` or `left` covariance.
#[pyfunction]
fn ros_pose_with_covariance<'py>(
    py: Python<'py>,
    mean: PyReadonlyArrayDyn<'py, f64>,
    cov: PyReadonlyArrayDyn<'py, f64>,
    convention: &str,
) -> PyResult<([f64; 4], Array<'py>)> {
    let mean = transform(elements(&mean, "pose", &[4, 4])?, 0);
    let cov = matrix(elements(&cov, "cov", &[6, 6])?, 0);
    let out = match convention {
        "right" => ros::ros_from_right(&mean, &cov),
        "left" => ros::ros_from_left(&mean, &cov),
        _ => {
            return Err(PyValueError::new_err(format!(
                "convention must be 'right' or 'left' (pytransform3d's covariance is neither \
                 perturbation), not {convention:?}"
            )))
        }
    };
    let q = mean.quaternion().map_err(core_err)?;
    Ok((q, matrix_array(py, &out)?))
}
