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
