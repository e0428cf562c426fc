//! The PPOE and forward kinematics of a batch of configurations on a chain, in f64 or
//! f32, with the GIL released. The PPOE is the core's batch call, whose result for a
//! configuration does not depend on the batch it is in: a batch's results equal the
//! single calls' (batches of one) bit for bit.

use crate::convert::{array, elements, elements_mut, mat6s, push_transform};
use crate::{core_err, PpoeError};
use numpy::{Element, PyArrayDyn, PyReadonlyArrayDyn, PyReadwriteArrayDyn, PyUntypedArrayMethods};
use ppoe::chain::{ChainView, Convention, UncertainPose};
use ppoe::{Error, Mat6, Real, Transform};
use pyo3::exceptions::PyMemoryError;
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
        let mut out = reserved::<T>(16, count)?;
        for i in 0..count {
            let t = view.forward_kinematics(&th[i * n..(i + 1) * n]);
            push_transform(&mut out, &t.map_err(|e| batch_err(i, e))?);
        }
        Ok(out)
    })?;
    array(py, out, &[count, 4, 4])
}

/// The inputs of a PPOE batch call, checked: `thetas` (N, n) and covariances (n, 6, 6)
/// shared by all or (N, n, 6, 6); the configuration count N.
fn ppoe_inputs<'a, T: Real + Element>(
    n: usize,
    thetas: &'a PyReadonlyArrayDyn<'_, T>,
    covs: &'a PyReadonlyArrayDyn<'_, T>,
) -> PyResult<(&'a [T], &'a [T], bool, usize)> {
    let th = elements(thetas, "thetas", &[usize::MAX, n])?;
    let count = thetas.shape()[0];
    let shared = covs.ndim() == 3;
    let c = if shared {
        elements(covs, "covs", &[n, 6, 6])?
    } else {
        elements(covs, "covs", &[count, n, 6, 6])?
    };
    Ok((th, c, shared, count))
}

/// The PPOE of N configurations `thetas` (N, n) with covariances (n, 6, 6) shared by all
/// or (N, n, 6, 6) → poses (N, 4, 4), covariances (N, 6, 6).
pub(crate) fn ppoe<'py, T: Real + Element + Send + Sync>(
    py: Python<'py>,
    view: ChainView<'_, T>,
    thetas: &PyReadonlyArrayDyn<'py, T>,
    covs: &PyReadonlyArrayDyn<'py, T>,
    convention: Convention,
    threads: usize,
) -> PyResult<(ArrayOf<'py, T>, ArrayOf<'py, T>)> {
    let (th, c, shared, count) = ppoe_inputs(view.joints.len(), thetas, covs)?;
    let (poses, out_covs) = py.detach(|| -> Result<_, PyErr> {
        let (mut poses, mut out_covs) = (zeroed(16, count)?, zeroed(36, count)?);
        Batch::new(view, th, c, shared, convention).run(threads, &mut poses, &mut out_covs)?;
        Ok((poses, out_covs))
    })?;
    Ok((
        array(py, poses, &[count, 4, 4])?,
        array(py, out_covs, &[count, 6, 6])?,
    ))
}

/// [`ppoe`] writing into the caller's arrays `poses_out` (N, 4, 4) and `covs_out`
/// (N, 6, 6), C-contiguous (rust-numpy's borrow check has already refused arrays that
/// overlap each other or the inputs). On an error their contents are unspecified.
#[allow(clippy::too_many_arguments)]
pub(crate) fn ppoe_into<'py, T: Real + Element + Send + Sync>(
    py: Python<'py>,
    view: ChainView<'_, T>,
    thetas: &PyReadonlyArrayDyn<'py, T>,
    covs: &PyReadonlyArrayDyn<'py, T>,
    convention: Convention,
    threads: usize,
    poses_out: &mut PyReadwriteArrayDyn<'py, T>,
    covs_out: &mut PyReadwriteArrayDyn<'py, T>,
) -> PyResult<()> {
    let (th, c, shared, count) = ppoe_inputs(view.joints.len(), thetas, covs)?;
    let poses = elements_mut(poses_out, "out[0]", &[count, 4, 4])?;
    let out_covs = elements_mut(covs_out, "out[1]", &[count, 6, 6])?;
    py.detach(|| Batch::new(view, th, c, shared, convention).run(threads, poses, out_covs))
}

/// An empty vector with room for `per·count` values, or a `MemoryError` where they do
/// not fit (the global allocator would abort the interpreter instead of failing the call).
fn reserved<T>(per: usize, count: usize) -> Result<Vec<T>, PyErr> {
    let too_big =
        || PyMemoryError::new_err(format!("no memory for {count} configurations' results"));
    let len = per.checked_mul(count).ok_or_else(too_big)?;
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| too_big())?;
    Ok(v)
}

/// `per·count` zeros, or a `MemoryError` ([`reserved`]). The reservation only probes:
/// `vec!` then takes zeroed pages from the system (calloc) without writing them, which
/// filling the reserved vector with zeros would.
fn zeroed<T: Real>(per: usize, count: usize) -> Result<Vec<T>, PyErr> {
    drop(reserved::<T>(per, count)?);
    Ok(vec![T::ZERO; per * count])
}

/// Configurations per call of the core: the results of one call sit in a buffer (98 KB in
/// f64, within a core's L2 cache) before they are written to the output arrays, which are
/// touched once; the shared covariances' checks (a Cholesky factorisation each) are then
/// paid once per 256 configurations.
const CHUNK: usize = 256;

/// Configurations below which a batch runs on one thread whatever `threads` says: a
/// thread's start costs about as much as a few hundred configurations.
const PER_THREAD: usize = 2048;

/// How many threads a batch of `count` configurations runs on: `threads` (0: every core
/// the operating system offers), at most one per [`PER_THREAD`] configurations.
pub(crate) fn thread_count(count: usize, threads: usize) -> usize {
    let most = count / PER_THREAD;
    if most <= 1 {
        return 1;
    }
    let want = match threads {
        0 => cores(),
        t => t,
    };
    want.min(most).max(1)
}

/// The cores the operating system offers this process, asked once: on Linux the answer
/// reads the cgroup's quota files, which costs far more than a small batch.
fn cores() -> usize {
    static CORES: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// One batch's inputs, shared by its threads.
struct Batch<'a, T> {
    view: ChainView<'a, T>,
    thetas: &'a [T],
    /// The covariances as 6×6 matrices (n, or n per configuration).
    covs: Vec<Mat6<T>>,
    shared: bool,
    convention: Convention,
}

impl<'a, T: Real> Batch<'a, T> {
    /// The batch of `thetas` (row-major, n per configuration) with the covariances `covs`
    /// (36 values each: n shared by all if `shared`, else n per configuration).
    fn new(
        view: ChainView<'a, T>,
        thetas: &'a [T],
        covs: &[T],
        shared: bool,
        convention: Convention,
    ) -> Self {
        Self {
            view,
            thetas,
            covs: mat6s(covs),
            shared,
            convention,
        }
    }

    /// The PPOE of every configuration into `poses` (16 values each) and `covs` (36), on
    /// `threads` threads ([`thread_count`]) each given a contiguous range of
    /// configurations ([`Batch::range`]), the first on the caller's. A configuration's
    /// result does not depend on the batch it is in, so the results are the same bits
    /// whatever the thread count; the error reported is that of the first failing range.
    fn run(&self, threads: usize, poses: &mut [T], covs: &mut [T]) -> Result<(), PyErr> {
        let count = poses.len() / 16;
        let threads = thread_count(count, threads);
        let size = count.div_ceil(threads).max(1);
        let mut ranges = poses.chunks_mut(16 * size).zip(covs.chunks_mut(36 * size));
        // The first range runs on the caller's thread, whose core is awake and holds the
        // inputs in its caches; only the others start threads (none for one range).
        let Some((p0, c0)) = ranges.next() else {
            return Ok(());
        };
        let results: Vec<Result<(), PyErr>> = std::thread::scope(|s| {
            let handles: Vec<_> = ranges
                .enumerate()
                .map(|(k, (p, c))| s.spawn(move || self.range((k + 1) * size, p, c)))
                .collect();
            let first = self.range(0, p0, c0);
            let rest = handles.into_iter().map(|h| {
                h.join()
                    .unwrap_or_else(|_| Err(PpoeError::new_err("a batch thread panicked")))
            });
            core::iter::once(first).chain(rest).collect()
        });
        results.into_iter().collect()
    }

    /// The configurations from `first` on, as many as `poses` has room for (16 values
    /// each; `covs` 36 each), through the core's checked batch calls (`ppoe_batch_checked`,
    /// or `ppoe_batch_per_config_checked` when `covs` holds n covariances per
    /// configuration rather than n shared by all), `CHUNK` configurations at a time.
    fn range(&self, first: usize, poses: &mut [T], covs: &mut [T]) -> Result<(), PyErr> {
        let n = self.view.joints.len();
        let count = poses.len() / 16;
        let mut buf = vec![UncertainPose::certain(Transform::identity()); CHUNK.min(count)];
        let dst = poses
            .chunks_mut(16 * CHUNK)
            .zip(covs.chunks_mut(36 * CHUNK));
        for (k, (pdst, cdst)) in dst.enumerate() {
            let (at, rows) = (first + k * CHUNK, pdst.len() / 16);
            let (th, out) = (&self.thetas[at * n..(at + rows) * n], &mut buf[..rows]);
            let done = if self.shared {
                self.view
                    .ppoe_batch_checked(th, &self.covs, self.convention, out)
            } else {
                let c = &self.covs[at * n..(at + rows) * n];
                self.view
                    .ppoe_batch_per_config_checked(th, c, self.convention, out)
            };
            done.map_err(|e| match e.config {
                Some(i) => batch_err(at + i, e.error),
                None => core_err(e.error),
            })?;
            // Whole rows of 16 and 36 values (a flattening iterator copied them one
            // bounds-checked element at a time).
            let rows = out
                .iter()
                .zip(pdst.chunks_exact_mut(16).zip(cdst.chunks_exact_mut(36)));
            for (r, (p, c)) in rows {
                p.copy_from_slice(r.pose.to_matrix4().as_flattened());
                c.copy_from_slice(r.cov.0.as_flattened());
            }
        }
        Ok(())
    }
}
