//! The `eigen` oracle: `SymmetricEigen` and the ellipsoid surfaces.

use crate::*;
use arbitrary::Arbitrary;
use ppoe::linalg::SymmetricEigen;
use ppoe::surface;
use ppoe::uncertainty::check_covariance;
use ppoe::Error;
use std::hint::black_box;

/// The `eigen` input.
#[derive(Arbitrary, Debug)]
pub struct EigenInput {
    /// A 6×6 matrix (also used for its leading 3×3 block).
    pub m: CovIn,
    /// A 3×3 matrix: lower triangle, or raw.
    pub m3: [FVal; 9],
    /// Use `m3` raw (not mirrored).
    pub m3_raw: bool,
    /// The mean pose of the surfaces.
    pub mean: TransformIn,
    /// Radius k / factor.
    pub k: FVal,
    /// Grid steps (mod 13).
    pub n_steps: u8,
    /// Output buffer length (mod 170).
    pub buf: u8,
}

/// Checks one decomposition.
fn check_eigen<T: Fz, const N: usize>(a: &Matrix<T, N, N>) {
    let r = SymmetricEigen::new(a);
    if !a.is_finite() {
        assert_eq!(
            r.err(),
            Some(Error::NonFinite),
            "SymmetricEigen ({}) of {a:?}",
            T::NAME
        );
        return;
    }
    let e = r.unwrap_or_else(|e| panic!("SymmetricEigen ({}) of finite {a:?}: {e:?}", T::NAME));
    let s = mat_amax(a);
    // Eigenvalues of a finite matrix can exceed the range (e.g. every entry MAX): only
    // within max/(4N) are they guaranteed representable.
    if s.to_f64() > T::max_value().to_f64() / (4.0 * N as f64) {
        black_box(e.reconstruct());
        return;
    }
    assert!(
        e.converged,
        "SymmetricEigen ({}) did not converge in {} sweeps: {a:?}",
        T::NAME,
        e.sweeps
    );
    assert!(
        e.values.is_finite(),
        "SymmetricEigen ({}) values {:?} of {a:?}",
        T::NAME,
        e.values
    );
    for k in 1..N {
        assert!(
            e.values.0[k - 1] >= e.values.0[k],
            "SymmetricEigen ({}) values not descending: {:?}",
            T::NAME,
            e.values
        );
    }
    // Orthonormal vectors.
    let nn = T::from_usize(N);
    let vt_v = e.vectors.transpose() * e.vectors;
    let ortho = mat_amax(&(vt_v - Matrix::identity()));
    let otol = T::lit(64.0) * nn * T::EPS;
    assert!(
        ortho <= otol,
        "SymmetricEigen ({}) ‖VᵀV − I‖ = {:e} of {a:?}",
        T::NAME,
        ortho.to_f64()
    );
    // Reconstruction of the symmetric part, relative to max|A| (plus the subnormal grain).
    let sym = a.symmetrize();
    let rec = e.reconstruct();
    let err = mat_amax(&(rec - sym));
    let rtol = T::lit(64.0) * nn * T::EPS * s + T::lit(64.0) * nn * T::denorm_min();
    assert!(
        err <= rtol,
        "SymmetricEigen ({}) reconstruction error {:e} > {:e} (max|A| = {:e}) of {a:?}; {e:?}",
        T::NAME,
        err.to_f64(),
        rtol.to_f64(),
        s.to_f64()
    );
    // Derived matrices: finite.
    for (what, m) in [
        ("sqrt", e.sqrt()),
        ("pinv_sqrt", e.pinv_sqrt()),
        ("clamped", e.clamped().reconstruct()),
    ] {
        assert!(
            m.is_finite(),
            "SymmetricEigen::{what} ({}) of {a:?}: {m:?}",
            T::NAME
        );
    }
}

/// The three grids of `mean`, `m6` at radius `k`: the errors their arguments call for,
/// `n_steps²` finite points on valid input, and no `Ok` with a point that is not finite.
fn check_surfaces<T: Fz>(mean: &Transform<T>, m6: &Mat6<T>, k: T, n_steps: usize, buf_len: usize) {
    let mut buf = vec![Vec3::<T>::zeros(); buf_len];
    let needed = n_steps * n_steps;
    let grid_ok = n_steps >= 2 && needed <= buf.len();

    // Valid domain: a valid pose with a bounded translation, a covariance that passes
    // check_covariance with bounded entries, |k| ≤ 100.
    let valid = mean.check().is_ok()
        && vec_amax(&mean.translation).to_f64() <= T::BOUND
        && check_covariance(m6).is_ok()
        && mat_amax(m6).to_f64() <= T::BOUND * T::BOUND
        && k.abs().to_f64() <= 100.0;

    type Surf<T> = fn(&Transform<T>, &Mat6<T>, T, usize, &mut [Vec3<T>]) -> Result<usize, Error>;
    let surfaces: [(&str, Surf<T>); 3] = [
        ("to_projected_ellipsoid", surface::to_projected_ellipsoid),
        ("lift_surface", surface::lift_surface),
        ("marginal_surface", surface::marginal_surface),
    ];
    for (what, f) in surfaces {
        buf.iter_mut().for_each(|p| *p = Vec3::zeros());
        let r = f(mean, m6, k, n_steps, &mut buf);
        let inputs_finite = transform_finite(mean) && m6.is_finite() && k.is_finite();
        if !grid_ok || !inputs_finite {
            assert!(r.is_err(), "{what} ({}): Ok for bad arguments", T::NAME);
        }
        if inputs_finite && n_steps < 2 {
            assert_eq!(r, Err(Error::GridSize), "{what} ({})", T::NAME);
        } else if inputs_finite && needed > buf.len() {
            assert_eq!(r, Err(Error::BufferTooSmall), "{what} ({})", T::NAME);
        } else if grid_ok && !inputs_finite {
            assert_eq!(r, Err(Error::NonFinite), "{what} ({})", T::NAME);
        }
        if grid_ok && valid {
            assert_eq!(r, Ok(needed), "{what} ({}) on valid input", T::NAME);
            for (i, p) in buf[..needed].iter().enumerate() {
                assert!(
                    p.is_finite(),
                    "{what} ({}): point {i} = {p:?} for valid input mean {mean:?} cov {m6:?} k {k:?}",
                    T::NAME
                );
            }
        } else if let Ok(n) = r {
            // Outside the valid domain huge values may overflow, which is
            // `Err(Overflow)`: an `Ok` grid is finite, and never more points than asked.
            assert_eq!(n, needed);
            assert!(
                buf[..n].iter().all(|p| p.is_finite()),
                "{what} ({}): Ok with a point that is not finite",
                T::NAME
            );
        }
    }
}

/// The generic body of the `eigen` target (run for f32 and f64).
pub fn run<T: Fz>(inp: &EigenInput) {
    let m6: Mat6<T> = inp.m.get();
    let v3: [T; 9] = inp.m3.map(|x| x.get());
    let m3: Mat3<T> = if inp.m3_raw {
        Mat3::from_rows([
            [v3[0], v3[1], v3[2]],
            [v3[3], v3[4], v3[5]],
            [v3[6], v3[7], v3[8]],
        ])
    } else {
        mirror::<T, 3>(&v3)
    };
    check_eigen(&m6);
    check_eigen(&m3);
    check_eigen(&m6.block(0, 0));
    check_eigen(&m6.block(1, 1));

    let mean: Transform<T> = inp.mean.get();
    let k: T = inp.k.get();
    check_surfaces(
        &mean,
        &m6,
        k,
        (inp.n_steps % 13) as usize,
        (inp.buf % 170) as usize,
    );
    let mean3: Vec3<T> = mean.translation;
    match surface::to_ellipsoid(&mean3, &m3) {
        Ok((t, radii)) => {
            assert!(mean3.is_finite() && m3.is_finite());
            if mat_amax(&m3).to_f64() <= T::BOUND * T::BOUND {
                assert!(
                    radii.is_finite(),
                    "to_ellipsoid ({}) radii {radii:?}",
                    T::NAME
                );
                assert_rigid("to_ellipsoid rotation", &t, T::lit(256.0) * T::EPS);
            }
        }
        Err(e) => assert!(
            !(mean3.is_finite() && m3.is_finite()),
            "to_ellipsoid ({}) of finite input: {e:?}",
            T::NAME
        ),
    }
    black_box(surface::position_ellipsoid(&mean, &m6).ok());
    black_box(surface::chi2_3_probability(k));
    black_box(surface::chi2_3_radius(k));
}
