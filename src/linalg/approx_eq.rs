//! The `approx` traits (approximate equality, element-wise) for vectors and matrices, and
//! the macro that derives them field by field for the crate's structs.

use super::{Matrix, Vector};
use crate::scalar::Real;

/// Element-wise approximate equality (`approx`), for vectors and matrices.
macro_rules! approx_impls {
    ($ty:ident < $($c:ident),+ >, $iter:expr) => {
        impl<T: Real, $(const $c: usize),+> approx::AbsDiffEq for $ty<T, $($c),+> {
            type Epsilon = T;
            fn default_epsilon() -> T {
                T::default_epsilon()
            }
            fn abs_diff_eq(&self, other: &Self, epsilon: T) -> bool {
                $iter(self).zip($iter(other)).all(|(a, b)| T::abs_diff_eq(a, b, epsilon))
            }
        }
        impl<T: Real, $(const $c: usize),+> approx::RelativeEq for $ty<T, $($c),+> {
            fn default_max_relative() -> T {
                T::default_max_relative()
            }
            fn relative_eq(&self, other: &Self, epsilon: T, max_relative: T) -> bool {
                $iter(self)
                    .zip($iter(other))
                    .all(|(a, b)| T::relative_eq(a, b, epsilon, max_relative))
            }
        }
        impl<T: Real, $(const $c: usize),+> approx::UlpsEq for $ty<T, $($c),+> {
            fn default_max_ulps() -> u32 {
                T::default_max_ulps()
            }
            fn ulps_eq(&self, other: &Self, epsilon: T, max_ulps: u32) -> bool {
                $iter(self).zip($iter(other)).all(|(a, b)| T::ulps_eq(a, b, epsilon, max_ulps))
            }
        }
    };
}

/// `approx` traits for a struct compared field by field (each field already implements
/// them with `Epsilon = T`).
macro_rules! approx_fields {
    ([$($gen:tt)*] $ty:ty { $($f:ident),+ }) => {
        impl<$($gen)*> approx::AbsDiffEq for $ty {
            type Epsilon = T;
            fn default_epsilon() -> T {
                T::default_epsilon()
            }
            fn abs_diff_eq(&self, other: &Self, epsilon: T) -> bool {
                true $(&& self.$f.abs_diff_eq(&other.$f, epsilon))+
            }
        }
        impl<$($gen)*> approx::RelativeEq for $ty {
            fn default_max_relative() -> T {
                T::default_max_relative()
            }
            fn relative_eq(&self, other: &Self, epsilon: T, max_relative: T) -> bool {
                true $(&& self.$f.relative_eq(&other.$f, epsilon, max_relative))+
            }
        }
        impl<$($gen)*> approx::UlpsEq for $ty {
            fn default_max_ulps() -> u32 {
                T::default_max_ulps()
            }
            fn ulps_eq(&self, other: &Self, epsilon: T, max_ulps: u32) -> bool {
                true $(&& self.$f.ulps_eq(&other.$f, epsilon, max_ulps))+
            }
        }
    };
}
pub(crate) use approx_fields;

fn vec_iter<T, const N: usize>(v: &Vector<T, N>) -> core::slice::Iter<'_, T> {
    v.0.iter()
}

fn mat_iter<T, const R: usize, const C: usize>(
    m: &Matrix<T, R, C>,
) -> core::iter::Flatten<core::slice::Iter<'_, [T; C]>> {
    m.0.iter().flatten()
}

approx_impls!(Vector<N>, vec_iter);
approx_impls!(Matrix<R, C>, mat_iter);
