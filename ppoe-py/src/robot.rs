//! A robot loaded from URDF (ppoe-build's chain extraction), in f64 and f32; its batch
//! PPOE and forward kinematics are in `batch`.

use crate::batch;
use crate::convert::{array, transform_array, Array, Pair};
use crate::{core_err, PpoeError};
use numpy::{PyArrayDyn, PyReadonlyArrayDyn, PyReadwriteArrayDyn};
use ppoe::chain::{ChainView, Convention, Joint, JointKind};
use ppoe::Transform;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A serial chain from a URDF: the joints (base to tip) and the home pose of the tip.
#[pyclass(frozen, module = "ppoe._ppoe")]
pub(crate) struct Robot {
    joints: Vec<Joint<f64>>,
    home: Transform<f64>,
    /// The same chain in f32 (`Joint::from_f64`, `Transform::from_f64`), for float32 input.
    joints32: Vec<Joint<f32>>,
    home32: Transform<f32>,
    /// The base and tip links and the joint names (base to tip), for the fit's report.
    base: String,
    tip: String,
    names: Vec<String>,
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

impl Robot {
    fn view(&self) -> ChainView<'_, f64> {
        ChainView {
            joints: &self.joints,
            home: self.home,
        }
    }

    /// The f64 chain and the home pose (the fit's input).
    pub(crate) fn chain(&self) -> (&[Joint<f64>], &Transform<f64>) {
        (&self.joints, &self.home)
    }

    /// The base link, the tip link and the joint names, base to tip.
    pub(crate) fn names(&self) -> (&str, &str, &[String]) {
        (&self.base, &self.tip, &self.names)
    }

    fn view32(&self) -> ChainView<'_, f32> {
        ChainView {
            joints: &self.joints32,
            home: self.home32,
        }
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
        if chain.coupling.is_some() {
            // Every call here takes one value per chain joint; a mimic joint's value follows
            // its master, which this package does not expand yet: refused, not ignored.
            return Err(PpoeError::new_err(format!(
                "the chain from '{base}' to '{tip}' has mimic joints, which ppoe's Python \
                 package does not support yet (ppoe eval and ppoe-build's tables do)"
            )));
        }
        // As RobotChain::to_core_joints, without leaking the names (the math needs none).
        let exact: Vec<Joint<f64>> = chain
            .joints
            .iter()
            .map(|j| Joint::new("", j.kind, j.screw, j.lower, j.upper))
            .collect();
        let home = chain.home_transform();
        let robot = Robot {
            joints: exact.iter().map(Joint::from_f64).collect(),
            home,
            joints32: exact.iter().map(Joint::from_f64).collect(),
            home32: Transform::from_f64(&home),
            base: chain.base.clone(),
            tip: chain.tip.clone(),
            names: chain.joints.iter().map(|j| j.name.clone()).collect(),
        };
        robot.view().check().map_err(core_err)?;
        robot.view32().check().map_err(core_err)?;
        Ok(robot)
    }

    /// The number of moving joints.
    #[getter]
    fn n_joints(&self) -> usize {
        self.joints.len()
    }

    /// The names of the moving joints, base to tip.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.names.clone()
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

    /// Forward kinematics of N configurations `thetas` (N, n) → (N, 4, 4), float64.
    fn forward_kinematics<'py>(
        &self,
        py: Python<'py>,
        thetas: PyReadonlyArrayDyn<'py, f64>,
    ) -> PyResult<Array<'py>> {
        batch::forward_kinematics(py, self.view(), &thetas)
    }

    /// [`Robot::forward_kinematics`] in float32 (the chain rounded to f32).
    fn forward_kinematics_f32<'py>(
        &self,
        py: Python<'py>,
        thetas: PyReadonlyArrayDyn<'py, f32>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        batch::forward_kinematics(py, self.view32(), &thetas)
    }

    /// The PPOE of N configurations `thetas` (N, n) with covariances (n, 6, 6) shared by
    /// all or (N, n, 6, 6), in `convention` → poses (N, 4, 4), covariances (N, 6, 6), on
    /// `threads` threads (0: every core; see `batch::thread_count`).
    fn ppoe<'py>(
        &self,
        py: Python<'py>,
        thetas: PyReadonlyArrayDyn<'py, f64>,
        covs: PyReadonlyArrayDyn<'py, f64>,
        convention_name: &str,
        threads: usize,
    ) -> PyResult<Pair<'py>> {
        batch::ppoe(
            py,
            self.view(),
            &thetas,
            &covs,
            convention(convention_name)?,
            threads,
        )
    }

    /// [`Robot::ppoe`] writing into `poses_out` (N, 4, 4) and `covs_out` (N, 6, 6),
    /// C-contiguous, writeable, not overlapping the inputs or each other.
    #[allow(clippy::too_many_arguments)]
    fn ppoe_into<'py>(
        &self,
        py: Python<'py>,
        thetas: PyReadonlyArrayDyn<'py, f64>,
        covs: PyReadonlyArrayDyn<'py, f64>,
        convention_name: &str,
        threads: usize,
        mut poses_out: PyReadwriteArrayDyn<'py, f64>,
        mut covs_out: PyReadwriteArrayDyn<'py, f64>,
    ) -> PyResult<()> {
        let c = convention(convention_name)?;
        let (p, o) = (&mut poses_out, &mut covs_out);
        batch::ppoe_into(py, self.view(), &thetas, &covs, c, threads, p, o)
    }

    /// [`Robot::ppoe_into`] in float32 (the chain rounded to f32).
    #[allow(clippy::too_many_arguments)]
    fn ppoe_into_f32<'py>(
        &self,
        py: Python<'py>,
        thetas: PyReadonlyArrayDyn<'py, f32>,
        covs: PyReadonlyArrayDyn<'py, f32>,
        convention_name: &str,
        threads: usize,
        mut poses_out: PyReadwriteArrayDyn<'py, f32>,
        mut covs_out: PyReadwriteArrayDyn<'py, f32>,
    ) -> PyResult<()> {
        let c = convention(convention_name)?;
        let (p, o) = (&mut poses_out, &mut covs_out);
        batch::ppoe_into(py, self.view32(), &thetas, &covs, c, threads, p, o)
    }

    /// [`Robot::ppoe`] in float32 (the chain rounded to f32).
    #[allow(clippy::type_complexity)]
    fn ppoe_f32<'py>(
        &self,
        py: Python<'py>,
        thetas: PyReadonlyArrayDyn<'py, f32>,
        covs: PyReadonlyArrayDyn<'py, f32>,
        convention_name: &str,
        threads: usize,
    ) -> PyResult<(Bound<'py, PyArrayDyn<f32>>, Bound<'py, PyArrayDyn<f32>>)> {
        batch::ppoe(
            py,
            self.view32(),
            &thetas,
            &covs,
            convention(convention_name)?,
            threads,
        )
    }
}
