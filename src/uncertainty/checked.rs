//! Checked concatenation and inversion: the inputs validated before, the result after.
//!
//! [`concat_globally`], [`concat_locally`] and [`invert`] are the reference's unchecked
//! ports: given a scaled "rotation", a non-symmetric covariance or NaN they compute
//! something, and finite inputs whose products exceed the scalar's range (a translation
//! of 10²⁰⁰ m moving a covariance) come back as ±∞ or NaN. The `_checked` variants are
//! the same computation (the same bits where they return `Ok`) between the crate's one
//! transform check ([`Transform::check`]) and one covariance check ([`check_covariance`])
//! on the way in, and a finiteness check on the way out.

use super::{check_covariance, concat_globally, concat_locally, invert, Order};
use crate::error::Error;
use crate::linalg::Mat6;
use crate::scalar::Real;
use crate::se3::Transform;

/// An uncertain transform: its mean and covariance.
type Uncertain<T> = (Transform<T>, Mat6<T>);

/// [`concat_globally`] (left perturbations, covariance in frame C) with its inputs and
/// result checked. Same accuracy and cost, plus two 6×6 Cholesky factorisations.
///
/// ```
/// use ppoe::uncertainty::{concat_globally, concat_globally_checked, Order};
/// use ppoe::{Error, Mat6, Transform, Vector};
/// let cov = Mat6::from_diagonal(&Vector([1e-4, 1e-4, 1e-4, 1e-6, 1e-6, 1e-6]));
/// let b2c = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [0., 0., 1.]);
/// let a2b = Transform::identity();
/// let checked = concat_globally_checked(&a2b, &cov, &b2c, &cov, Order::Second)?;
/// assert_eq!(checked, concat_globally(&a2b, &cov, &b2c, &cov, Order::Second));
/// // A translation so long that moving the covariance overflows: an error, not ∞.
/// let far = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1e200, 0., 0.]);
/// let r = concat_globally_checked(&a2b, &cov, &far, &cov, Order::Second);
/// assert_eq!(r, Err(Error::Overflow));
/// # Ok::<(), Error>(())
/// ```
///
/// # Errors
///
/// [`Error::NonFinite`] or [`Error::NotARotation`] for a mean, [`Error::NonFinite`],
/// [`Error::NotSymmetric`] or [`Error::NotPositiveSemidefinite`] for a covariance
/// ([`check_covariance`]), [`Error::Overflow`] if the result is not finite.
pub fn concat_globally_checked<T: Real>(
    mean_a2b: &Transform<T>,
    cov_a2b: &Mat6<T>,
    mean_b2c: &Transform<T>,
    cov_b2c: &Mat6<T>,
    order: Order,
) -> Result<Uncertain<T>, Error> {
    check_inputs(&[mean_a2b, mean_b2c], &[cov_a2b, cov_b2c])?;
    validated(concat_globally(mean_a2b, cov_a2b, mean_b2c, cov_b2c, order))
}

/// [`concat_locally`] (right perturbations, covariance in frame A) with its inputs and
/// result checked. Same accuracy and cost, plus two 6×6 Cholesky factorisations.
///
/// ```
/// use ppoe::uncertainty::concat_locally_checked;
/// use ppoe::{Error, Mat6, Transform, Vector};
/// let cov = Mat6::from_diagonal(&Vector([0.0, 0.0, 0.01, 0.0, 0.0, 0.0]));
/// // A "rotation" scaled by 2 is rejected, not used.
/// let scaled = Transform::from_parts([[2., 0., 0.], [0., 2., 0.], [0., 0., 2.]], [0.; 3]);
/// let r = concat_locally_checked(&scaled, &Transform::identity(), &cov, &cov);
/// assert_eq!(r, Err(Error::NotARotation));
/// ```
///
/// # Errors
///
/// As [`concat_globally_checked`].
pub fn concat_locally_checked<T: Real>(
    mean_a2b: &Transform<T>,
    mean_b2c: &Transform<T>,
    cov_a: &Mat6<T>,
    cov_b: &Mat6<T>,
) -> Result<Uncertain<T>, Error> {
    check_inputs(&[mean_a2b, mean_b2c], &[cov_a, cov_b])?;
    validated(concat_locally(mean_a2b, mean_b2c, cov_a, cov_b))
}

/// [`invert`] (left perturbation) with its input and result checked. Same accuracy and
/// cost, plus one 6×6 Cholesky factorisation.
///
/// ```
/// use ppoe::uncertainty::invert_checked;
/// use ppoe::{Error, Mat6, Transform};
/// let mut cov = Mat6::<f64>::zeros();
/// cov.0[0][1] = 1e-3; // not symmetric
/// assert_eq!(invert_checked(&Transform::identity(), &cov), Err(Error::NotSymmetric));
/// ```
///
/// # Errors
///
/// As [`concat_globally_checked`].
pub fn invert_checked<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> Result<Uncertain<T>, Error> {
    check_inputs(&[mean], &[cov])?;
    validated(invert(mean, cov))
}

/// Every mean and covariance checked, the means first.
fn check_inputs<T: Real>(means: &[&Transform<T>], covs: &[&Mat6<T>]) -> Result<(), Error> {
    means.iter().try_for_each(|m| m.check())?;
    covs.iter().try_for_each(|c| check_covariance(*c))
}

/// `result`, if its mean and covariance are finite. Not a rotation check of the mean: a
/// product of rotations each within tolerance may lie just outside it, and is as good as
/// its factors.
fn validated<T: Real>(result: Uncertain<T>) -> Result<Uncertain<T>, Error> {
    let (mean, cov) = &result;
    if mean.rotation.is_finite() && mean.translation.is_finite() && cov.is_finite() {
        Ok(result)
    } else {
        Err(Error::Overflow)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::Vector;
    use crate::se3;

    fn mean(xi: [f64; 6]) -> Transform<f64> {
        se3::exp(&Vector(xi))
    }

    fn cov(d: [f64; 6]) -> Mat6<f64> {
        let mut c = Mat6::from_diagonal(&Vector(d));
        c.0[0][3] = 0.3 * (d[0] * d[3]).sqrt();
        c.0[3][0] = c.0[0][3];
        c
    }

    #[test]
    fn valid_inputs_give_the_unchecked_bits() {
        let (a, b) = (
            mean([0.3, -0.2, 0.5, 1.0, -2.0, 0.5]),
            mean([-0.6, 0.1, 0.2, 0.0, 0.7, 0.2]),
        );
        let (ca, cb) = (
            cov([1e-3, 2e-3, 5e-4, 1e-3, 3e-3, 2e-3]),
            cov([4e-4, 1e-4, 1e-4, 2e-3, 1e-3, 5e-3]),
        );
        for order in [Order::Second, Order::Fourth, Order::FourthPsd] {
            let checked = concat_globally_checked(&a, &ca, &b, &cb, order);
            assert_eq!(checked, Ok(concat_globally(&a, &ca, &b, &cb, order)));
        }
        assert_eq!(
            concat_locally_checked(&a, &b, &ca, &cb),
            Ok(concat_locally(&a, &b, &ca, &cb))
        );
        assert_eq!(invert_checked(&a, &ca), Ok(invert(&a, &ca)));
    }

    #[test]
    fn invalid_inputs_are_named() {
        let (a, c) = (mean([0.3, -0.2, 0.5, 1.0, -2.0, 0.5]), cov([1e-3; 6]));
        let mut nan = a;
        nan.translation.0[1] = f64::NAN;
        let mut skew = a;
        skew.rotation.0[0][1] += 1e-3;
        let mut asym = c;
        asym.0[1][2] = 1e-4;
        let neg = cov([1e-3, -1e-3, 1e-3, 1e-3, 1e-3, 1e-3]);
        let mut inf = c;
        inf.0[5][5] = f64::INFINITY;
        assert_eq!(invert_checked(&nan, &c), Err(Error::NonFinite));
        assert_eq!(invert_checked(&skew, &c), Err(Error::NotARotation));
        assert_eq!(invert_checked(&a, &asym), Err(Error::NotSymmetric));
        assert_eq!(
            invert_checked(&a, &neg),
            Err(Error::NotPositiveSemidefinite)
        );
        assert_eq!(invert_checked(&a, &inf), Err(Error::NonFinite));
        // Each position of each function is checked.
        assert_eq!(
            concat_locally_checked(&a, &skew, &c, &c),
            Err(Error::NotARotation)
        );
        assert_eq!(
            concat_locally_checked(&a, &a, &c, &neg),
            Err(Error::NotPositiveSemidefinite)
        );
        assert_eq!(
            concat_locally_checked(&a, &a, &asym, &c),
            Err(Error::NotSymmetric)
        );
        let g = |m1: &Transform<f64>, c1: &Mat6<f64>, m2: &Transform<f64>, c2: &Mat6<f64>| {
            concat_globally_checked(m1, c1, m2, c2, Order::FourthPsd)
        };
        assert_eq!(g(&nan, &c, &a, &c), Err(Error::NonFinite));
        assert_eq!(g(&a, &c, &skew, &c), Err(Error::NotARotation));
        assert_eq!(g(&a, &inf, &a, &c), Err(Error::NonFinite));
        assert_eq!(g(&a, &c, &a, &neg), Err(Error::NotPositiveSemidefinite));
    }

    #[test]
    fn overflow_is_an_error_in_both_scalars() {
        fn far<T: Real>(x: f64) -> Result<(), Error> {
            let c = Mat6::<T>::from_diagonal(&Vector([T::lit(1e-2); 6]));
            let id = Transform::<T>::identity();
            let mut far = id;
            far.translation.0[0] = T::lit(x);
            // The lever arm's square times the covariance is beyond the scalar's range.
            concat_globally_checked(&id, &c, &far, &c, Order::Second)?;
            concat_locally_checked(&far, &id, &c, &c)?;
            invert_checked(&far, &c).map(|_| ())
        }
        assert_eq!(far::<f64>(1e200), Err(Error::Overflow));
        assert_eq!(far::<f32>(1e25), Err(Error::Overflow));
        assert_eq!(far::<f64>(1e100), Ok(()));
        assert_eq!(far::<f32>(1e15), Ok(()));
    }
}
