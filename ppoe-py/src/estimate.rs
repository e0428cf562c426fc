//! The Gaussian estimators from samples: the core's (right update, converges at any
//! angle) and pytransform3d 3.17.0's, reproduced with the core's Fréchet mean through a
//! group whose update is on the left.
//!
//! pytransform3d takes right differences `Log(mean⁻¹·Xᵢ)` but updates
//! `mean ← Exp(avg)·mean` for exactly 20 iterations, and returns the covariance of the
//! differences of the last iteration, taken *before* its update. Reproduced here: 19
//! iterations of the core's `frechet_mean` on [`LeftUpdate`] (no stopping tolerance; the
//! covariance it returns is that of the differences at the 19th mean), then the 20th
//! update.

use crate::convert::{elements, mat3s, matrix_array, transform, transform_array, Pair};
use crate::core_err;
use numpy::PyReadonlyArrayDyn;
use ppoe::uncertainty::{self, frechet_mean, Estimate, IterationOptions, LieGroup};
use ppoe::{se3, so3, Error, Mat3, Matrix, Transform, Vector};
use pyo3::prelude::*;

/// pytransform3d's fixed number of Fréchet iterations.
const PT3D_ITERATIONS: usize = 20;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(estimate_gaussian_transform, m)?)?;
    m.add_function(wrap_pyfunction!(estimate_gaussian_rotation, m)?)?;
    Ok(())
}

/// A group element whose update is the *left* one, `Exp(d)·self`, while its difference
/// stays the right one: pytransform3d's Fréchet iteration.
#[derive(Clone, Copy)]
struct LeftUpdate<G>(G);

impl LieGroup<f64, 6> for LeftUpdate<Transform<f64>> {
    fn right_difference(&self, x: &Self) -> Vector<f64, 6> {
        self.0.right_difference(&x.0)
    }
    fn right_update(&self, d: &Vector<f64, 6>) -> Self {
        LeftUpdate(se3::exp(d) * self.0)
    }
    fn is_finite(&self) -> bool {
        LieGroup::<f64, 6>::is_finite(&self.0)
    }
    fn check(&self) -> Result<(), Error> {
        LieGroup::<f64, 6>::check(&self.0)
    }
    fn magnitude(&self) -> f64 {
        LieGroup::<f64, 6>::magnitude(&self.0)
    }
}

impl LieGroup<f64, 3> for LeftUpdate<Mat3<f64>> {
    fn right_difference(&self, x: &Self) -> Vector<f64, 3> {
        self.0.right_difference(&x.0)
    }
    fn right_update(&self, d: &Vector<f64, 3>) -> Self {
        LeftUpdate(so3::exp(d) * self.0)
    }
    fn is_finite(&self) -> bool {
        LieGroup::<f64, 3>::is_finite(&self.0)
    }
    fn check(&self) -> Result<(), Error> {
        LieGroup::<f64, 3>::check(&self.0)
    }
}

/// pytransform3d's estimate: 19 left-updated iterations, the covariance there, then the
/// 20th update.
fn pytransform3d_estimate<G: LieGroup<f64, D>, const D: usize>(
    samples: &[G],
) -> Result<(G, Matrix<f64, D, D>), Error> {
    let options = IterationOptions {
        max_iterations: PT3D_ITERATIONS - 1,
        step_tolerance: 0.0,
        converged_tolerance: 0.0,
    };
    let Estimate { mean, cov, .. } = frechet_mean(samples, &options)?;
    let mut sum = Vector::<f64, D>::zeros();
    for s in samples {
        sum += mean.right_difference(s);
    }
    let last = mean.right_update(&sum.scale(1.0 / samples.len() as f64));
    if !last.is_finite() {
        return Err(Error::Overflow);
    }
    Ok((last, cov))
}

/// Gaussian on SE(3) from samples (N, 4, 4): pytransform3d's iteration if `compat`,
/// else the core's `estimate_gaussian_transform`.
#[pyfunction]
fn estimate_gaussian_transform<'py>(
    py: Python<'py>,
    samples: PyReadonlyArrayDyn<'py, f64>,
    compat: bool,
) -> PyResult<Pair<'py>> {
    let x = elements(&samples, "samples", &[usize::MAX, 4, 4])?;
    let poses: Vec<Transform<f64>> = (0..x.len() / 16).map(|i| transform(x, 16 * i)).collect();
    let (mean, cov) = if compat {
        let wrapped: Vec<_> = poses.iter().map(|p| LeftUpdate(*p)).collect();
        let (m, c) = pytransform3d_estimate(&wrapped).map_err(core_err)?;
        (m.0, c)
    } else {
        let e = uncertainty::estimate_gaussian_transform(&poses).map_err(core_err)?;
        (e.mean, e.cov)
    };
    Ok((transform_array(py, &mean)?, matrix_array(py, &cov)?))
}

/// Gaussian on SO(3) from samples (N, 3, 3): pytransform3d's iteration if `compat`,
/// else the core's `estimate_gaussian_rotation`.
#[pyfunction]
fn estimate_gaussian_rotation<'py>(
    py: Python<'py>,
    samples: PyReadonlyArrayDyn<'py, f64>,
    compat: bool,
) -> PyResult<Pair<'py>> {
    let rotations = mat3s(elements(&samples, "samples", &[usize::MAX, 3, 3])?);
    let (mean, cov) = if compat {
        let wrapped: Vec<_> = rotations.iter().map(|r| LeftUpdate(*r)).collect();
        let (m, c) = pytransform3d_estimate(&wrapped).map_err(core_err)?;
        (m.0, c)
    } else {
        let e = uncertainty::estimate_gaussian_rotation(&rotations).map_err(core_err)?;
        (e.mean, e.cov)
    };
    Ok((matrix_array(py, &mean)?, matrix_array(py, &cov)?))
}
