//! A robot loaded from URDF (ppoe-build's chain extraction) and the core's PPOE and
//! forward kinematics on it, one configuration or a batch, with the GIL released.

use crate::convert::{array, elements, matrix, push_matrix, push_transform, transform_array, Pair};
use crate::{core_err, PpoeError};
use numpy::{PyArrayDyn, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use ppoe::chain::{ChainView, Convention, Joint, JointKind};
use ppoe::uncertainty::check_covariance;
use ppoe::{Error, Mat6, Transform};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A serial chain from a URDF: the joints (base to tip) and the home pose of the tip.
#[pyclass(frozen, module = "ppoe._ppoe")]
pub(crate) struct Robot {
    joints: Vec<Joint<f64>>,
    home: Transform<f64>,
}

fn convention(name: &str) -> PyResult<Convention> {
    match name {
        "right" => Ok(Convention::Right),
        "left" => Ok(Convention::Left),
        "pytransform3d" => Ok(Convention::Pytransform3d),
        _ => Err(PyValueError::new_err(format!(
            "convention must be 'right', 'left' or 'pytransform3d', not {name:?}"
        ))),
    }
}

fn kind_name(kind: JointKind) -> &'static str {
    match kind {
        JointKind::Revolute => "revolute",
        JointKind::Continuous => "continuous",
        JointKind::Prismatic => "prismatic",
    }
}

/// The error of configuration `i` of a batch: the core's message, and which one.
fn batch_err(i: usize, e: Error) -> PyErr {
    PpoeError::new_err(format!("configuration {i}: {e}"))
}

impl Robot {
    fn view(&self) -> ChainView<'_, f64> {
        ChainView {
            joints: &self.joints,
            home: self.home,
        }
    }

    /// The PPOE of every configuration: `covs` holds n covariances shared by all, or n
    /// per configuration. Writes 16 + 36 values per configuration.
    fn ppoe_all(
        &self,
        count: usize,
        thetas: &[f64],
        covs: &[f64],
        shared: bool,
        convention: Convention,
    ) -> Result<(Vec<f64>, Vec<f64>), PyErr> {
        let n = self.joints.len();
        let mut per = vec![Mat6::zeros(); n];
        if shared {
            per = crate::convert::mat6s(covs);
            for c in &per {
                check_covariance(c).map_err(core_err)?;
            }
        }
        let (mut poses, mut out_covs) = (
            Vec::with_capacity(16 * count),
            Vec::with_capacity(36 * count),
        );
        let view = self.view();
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
            if !(r.cov.is_finite() && r.pose.rotation.is_finite() && r.pose.translation.is_finite())
            {
                return Err(batch_err(i, Error::Overflow));
            }
            push_transform(&mut poses, &r.pose);
            push_matrix(&mut out_covs, &r.cov);
        }
        Ok((poses, out_covs))
    }
}

#[pymethods]
impl Robot {
    /// Loads the chain from `base` to `tip` of the URDF text `urdf`; `joints` names the
    /// moving joints (base to tip), `None` takes every moving joint on the path.
    #[new]
    #[pyo3(signature = (urdf, base, tip, joints=None))]
    fn new(urdf: &str, base: &str, tip: &str, joints: Option<Vec<String>>) -> PyResult<Self> {
        let err = |e: ppoe_build::Error| PpoeError::new_err(e.to_string());
        let robot = ppoe_build::Urdf::parse(urdf).map_err(err)?;
        let chain = robot.chain(base, tip, joints.as_deref()).map_err(err)?;
        // As RobotChain::to_core_joints, without leaking the names (the math needs none).
        let joints = chain
            .joints
            .iter()
            .map(|j| Joint::from_f64(&Joint::new("", j.kind, j.screw, j.lower, j.upper)))
            .collect();
        let robot = Robot {
            joints,
            home: chain.home_transform(),
        };
        robot.view().check().map_err(core_err)?;
        Ok(robot)
    }

    /// The number of moving joints.
    #[getter]
    fn n_joints(&self) -> usize {
        self.joints.len()
    }

    /// The joint kinds, base to tip ('revolute', 'continuous' or 'prismatic').
    #[getter]
    fn kinds(&self) -> Vec<&'static str> {
        self.joints.iter().map(|j| kind_name(j.kind)).collect()
    }

    /// The screw axes (n, 6), base frame, rotation first.
    fn screw_axes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let v = self.joints.iter().flat_map(|j| j.screw.0).collect();
        array(py, v, &[self.joints.len(), 6])
    }

    /// The joint limits (n, 2): lower, upper.
    fn limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let v = self
            .joints
            .iter()
            .flat_map(|j| [j.lower, j.upper])
            .collect();
        array(py, v, &[self.joints.len(), 2])
    }

    /// The home pose M of the tip (4, 4).
    fn home<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        transform_array(py, &self.home)
    }

    /// Forward kinematics of N configurations `thetas` (N, n) → (N, 4, 4).
    fn forward_kinematics<'py>(
        &self,
        py: Python<'py>,
        thetas: PyReadonlyArrayDyn<'py, f64>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let n = self.joints.len();
        let th = elements(&thetas, "thetas", &[usize::MAX, n])?;
        let count = thetas.shape()[0];
        let out = py.detach(|| -> Result<Vec<f64>, PyErr> {
            let mut out = Vec::with_capacity(16 * count);
            for i in 0..count {
                let t = self.view().forward_kinematics(&th[i * n..(i + 1) * n]);
                push_transform(&mut out, &t.map_err(|e| batch_err(i, e))?);
            }
            Ok(out)
        })?;
        array(py, out, &[count, 4, 4])
    }

    /// The PPOE of N configurations `thetas` (N, n) with covariances (n, 6, 6) shared by
    /// all or (N, n, 6, 6), in `convention` → poses (N, 4, 4), covariances (N, 6, 6).
    fn ppoe<'py>(
        &self,
        py: Python<'py>,
        thetas: PyReadonlyArrayDyn<'py, f64>,
        covs: PyReadonlyArrayDyn<'py, f64>,
        convention_name: &str,
    ) -> PyResult<Pair<'py>> {
        let n = self.joints.len();
        let conv = convention(convention_name)?;
        let th = elements(&thetas, "thetas", &[usize::MAX, n])?;
        let count = thetas.shape()[0];
        let shared = covs.ndim() == 3;
        let c = if shared {
            elements(&covs, "covs", &[n, 6, 6])?
        } else {
            elements(&covs, "covs", &[count, n, 6, 6])?
        };
        let (poses, out_covs) = py.detach(|| self.ppoe_all(count, th, c, shared, conv))?;
        Ok((
            array(py, poses, &[count, 4, 4])?,
            array(py, out_covs, &[count, 6, 6])?,
        ))
    }
}
