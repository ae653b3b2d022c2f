//! Helpers shared by collide's unit tests: literals in either precision, and one
//! test body run for `f32` and `f64`.

use crate::real::{Real, Vec3};

/// A vector of the test's precision from `f64` literals.
pub(crate) fn v<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::new(T::of(x), T::of(y), T::of(z))
}

/// The test precision's machine epsilon, as `f64`.
pub(crate) fn eps<T: Real>() -> f64 {
    T::EPSILON.wide()
}

/// Whether two vectors are the same bits, component by component: for claims
/// that a value is passed through or shared, not recomputed close to it.
pub(crate) fn same_bits<T: Real>(got: &Vec3<T>, want: &Vec3<T>) -> bool {
    got.iter().zip(want.iter()).all(|(g, w)| g.wide().to_bits() == w.wide().to_bits())
}

/// `both!(name, body)`: a module `name` with tests `f32` and `f64` running the
/// generic function `body` in each precision.
macro_rules! both {
    ($name:ident, $body:ident) => {
        mod $name {
            #[test]
            fn f32() {
                super::$body::<f32>();
            }
            #[test]
            fn f64() {
                super::$body::<f64>();
            }
        }
    };
}
pub(crate) use both;

/// `prop_both!(cases, name, strategy, check)`: a module `name` with proptests
/// `f32` and `f64`, each running `check::<T>(&case)` on `cases` cases drawn from
/// `strategy`. The expansion site must have proptest's prelude in scope.
macro_rules! prop_both {
    ($cases:expr, $name:ident, $strat:expr, $check:ident) => {
        mod $name {
            use super::*;
            proptest! {
                #![proptest_config(ProptestConfig::with_cases($cases))]
                #[test]
                fn f32(s in $strat) { $check::<f32>(&s)?; }
                #[test]
                fn f64(s in $strat) { $check::<f64>(&s)?; }
            }
        }
    };
}
pub(crate) use prop_both;
