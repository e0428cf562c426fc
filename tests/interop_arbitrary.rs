//! arbitrary (feature `arbitrary`): every generated value is valid, for random byte
//! strings of every length (including empty), in f32 and f64.
#![cfg(feature = "arbitrary")]

use arbitrary::{Arbitrary, Unstructured};
use ppoe::chain::{Chain, ChainView, Convention, Joint, JointKind, UncertainPose};
use ppoe::interop::arbitrary::{Covariance, Rotation};
use ppoe::uncertainty::check_covariance;
use ppoe::{Mat3, Real, Transform};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Random byte strings: lengths 0..600, some all-zero or all-0xff.
fn byte_strings(seed: u64, n: usize) -> Vec<Vec<u8>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = vec![vec![], vec![0; 600], vec![0xff; 600]];
    for _ in 0..n {
        let len = rng.gen_range(0..600);
        out.push((0..len).map(|_| rng.gen()).collect());
    }
    out
}

fn orthonormal<T: Real>(r: &Mat3<T>) {
    let eps = T::EPS.to_f64();
    let err = (r.transpose() * *r - Mat3::identity()).amax().to_f64();
    assert!(err <= 8.0 * eps, "RᵀR − I: {err}");
    assert!((r.determinant().to_f64() - 1.0).abs() <= 8.0 * eps);
}

fn psd<T: Real, const N: usize>(c: &Covariance<T, N>) {
    assert_eq!(c.0, c.0.transpose());
    check_covariance(&c.0).unwrap();
}

fn all_valid<T: Real>(seed: u64) {
    let mut ranks = [0usize; 7];
    for bytes in byte_strings(seed, 500) {
        let mut u = Unstructured::new(&bytes);
        orthonormal(&Rotation::<T>::arbitrary(&mut u).unwrap().0);
        let t = Transform::<T>::arbitrary(&mut u).unwrap();
        t.check().unwrap();
        orthonormal(&t.rotation);
        let c6 = Covariance::<T, 6>::arbitrary(&mut u).unwrap();
        psd(&c6);
        // Independent PSD check: nalgebra's eigenvalues, in f64.
        let values = nalgebra::SMatrix::<f64, 6, 6>::from_fn(|i, j| c6.0 .0[i][j].to_f64())
            .symmetric_eigenvalues();
        let scale = c6.0.amax().to_f64().max(f64::MIN_POSITIVE);
        assert!(values.iter().all(|&l| l >= -1e-6 * scale), "{:?}", values);
        ranks[values.iter().filter(|&&l| l > 1e-6 * scale).count()] += 1;
        psd(&Covariance::<T, 3>::arbitrary(&mut u).unwrap());
        let chain = Chain::<T, 6>::arbitrary(&mut u).unwrap();
        chain.as_ref().check().unwrap();
        let j = Joint::<T>::arbitrary(&mut u).unwrap();
        // Constants computed for every joint that rotates (prismatic joints have none).
        assert_eq!(j.constants().is_some(), j.kind != JointKind::Prismatic);
        let alone = ChainView {
            joints: core::slice::from_ref(&j),
            home: Transform::identity(),
        };
        alone.check().unwrap();
        let p = UncertainPose::<T>::arbitrary(&mut u).unwrap();
        p.pose.check().unwrap();
        check_covariance(&p.cov).unwrap();
        let _ = Convention::arbitrary(&mut u).unwrap();
        // What the generators are for: the checked PPOE accepts them.
        let covs = [0; 6].map(|_| Covariance::<T, 6>::arbitrary(&mut u).unwrap().0);
        let thetas = chain.clip(&[0; 6].map(|_| T::lit(0.3)));
        chain
            .ppoe_checked(&thetas, &covs, Convention::Right)
            .unwrap();
    }
    // Every rank from 0 to 6 occurs.
    assert!(ranks.iter().all(|&n| n > 0), "{ranks:?}");
}

#[test]
fn generated_values_are_valid_f64() {
    all_valid::<f64>(1);
}

#[test]
fn generated_values_are_valid_f32() {
    all_valid::<f32>(2);
}
