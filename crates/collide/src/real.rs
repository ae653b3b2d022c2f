//! The scalar type collide is generic over.
//!
//! Every query is written once for [`Real`] and run in `f32` and `f64`, so precision
//! is one more axis on crashtest's accuracy–speed chart. Exact predicates are
//! evaluated on the `f64` value of each input: every `f32` is exactly an `f64`, so
//! the conversion loses nothing and one exact code path serves both precisions.

use nalgebra::RealField;

/// A floating-point scalar: `f32` or `f64`.
pub trait Real: RealField + Copy + Default + core::fmt::Debug {
    /// The value as an `f64` (exact for both implementors).
    fn wide(self) -> f64;
    /// The nearest value of this type to `x` (rounds for `f32`).
    fn of(x: f64) -> Self;
    /// Machine epsilon of this type (the gap between 1 and the next value).
    const EPSILON: Self;
    /// Whether the value is neither infinite nor NaN.
    fn finite(self) -> bool;
    /// Whether the value is NaN.
    fn is_nan(self) -> bool;
}

impl Real for f64 {
    #[inline(always)]
    fn wide(self) -> f64 {
        self
    }
    #[inline(always)]
    fn of(x: f64) -> Self {
        x
    }
    const EPSILON: Self = f64::EPSILON;
    #[inline(always)]
    fn finite(self) -> bool {
        self.is_finite()
    }
    #[inline(always)]
    fn is_nan(self) -> bool {
        <f64>::is_nan(self)
    }
}

impl Real for f32 {
    #[inline(always)]
    fn wide(self) -> f64 {
        f64::from(self)
    }
    #[inline(always)]
    fn of(x: f64) -> Self {
        x as f32
    }
    const EPSILON: Self = f32::EPSILON;
    #[inline(always)]
    fn finite(self) -> bool {
        self.is_finite()
    }
    #[inline(always)]
    fn is_nan(self) -> bool {
        <f32>::is_nan(self)
    }
}

/// A 3-vector; collide uses it for points and directions alike.
pub type Vec3<T> = nalgebra::Vector3<T>;

/// Shorthand for a literal constant in generic code.
#[inline(always)]
pub(crate) fn c<T: Real>(x: f64) -> T {
    T::of(x)
}

/// Whether every component of `v` is finite.
#[inline(always)]
pub(crate) fn finite3<T: Real>(v: &Vec3<T>) -> bool {
    v.x.finite() && v.y.finite() && v.z.finite()
}

/// The components of `v` as `f64`.
#[inline(always)]
pub(crate) fn to_f64_3<T: Real>(v: &Vec3<T>) -> [f64; 3] {
    [v.x.wide(), v.y.wide(), v.z.wide()]
}

/// Euclidean norm computed without spurious overflow or underflow: the vector is
/// scaled by its largest component first. The naive `sqrt(x² + y² + z²)` returns
/// 0 for components below about 1e-154 (f64) and infinity above about 1e154.
#[inline]
pub fn stable_norm<T: Real>(v: &Vec3<T>) -> T {
    let m = v.x.abs().max(v.y.abs()).max(v.z.abs());
    if m == T::zero() || !m.finite() {
        return m;
    }
    let s = v / m;
    m * s.norm()
}

/// `v / ‖v‖` with the norm from [`stable_norm`]; `None` for a zero or
/// non-finite vector.
#[inline]
pub fn try_normalize_stable<T: Real>(v: &Vec3<T>) -> Option<Vec3<T>> {
    let m = v.x.abs().max(v.y.abs()).max(v.z.abs());
    if m == T::zero() || !m.finite() {
        return None;
    }
    let s = v / m;
    let n = s.norm();
    Some(s / n)
}

/// The power of two `2^k` that brings a scene whose largest magnitude is `m`
/// to about 1, when `m` lies outside the type's plain range `[2^-e, 2^e]`
/// (`e` = 200 for `f64`, 25 for `f32`: there the fourth powers of such
/// magnitudes, the highest a query forms, neither overflow nor underflow);
/// `None` inside it, and for a zero or non-finite `m`.
///
/// Scaling a scene by `2^k` is exact (apart from numbers so much smaller than
/// the largest that they fall into the subnormals, whose loss is far below
/// the answer's rounding), and every query's answer scales with it (lengths
/// by `2^k`, times and directions not at all), so a query outside the range
/// can be answered on the scaled scene and its lengths scaled back.
pub(crate) fn unit_scale<T: Real>(m: T) -> Option<i32> {
    // 2^±200 and 2^±25 (exponent fields 1023 ± e).
    const F64_RANGE: (f64, f64) = (f64::from_bits((1023 - 200) << 52), f64::from_bits((1023 + 200) << 52));
    const F32_RANGE: (f64, f64) = (f64::from_bits((1023 - 25) << 52), f64::from_bits((1023 + 25) << 52));
    let m = m.wide();
    let (lo, hi) = if T::EPSILON.wide() < 1e-10 { F64_RANGE } else { F32_RANGE };
    if !(m > 0.0 && m.is_finite()) || (m >= lo && m <= hi) {
        return None;
    }
    Some(-(m.log2().round() as i32))
}

/// `x · 2^k`, in steps of at most `2^±60` (each exact in both types unless the
/// result under- or overflows).
pub(crate) fn scale2<T: Real>(mut x: T, mut k: i32) -> T {
    while k != 0 {
        let step = k.clamp(-60, 60);
        x *= T::of(2f64.powi(step));
        k -= step;
    }
    x
}

/// A vector times `2^k` (see [`scale2`]).
pub(crate) fn scale2v<T: Real>(v: &Vec3<T>, k: i32) -> Vec3<T> {
    Vec3::new(scale2(v.x, k), scale2(v.y, k), scale2(v.z, k))
}

#[cfg(test)]
mod unit_scale_tests {
    use super::*;

    #[test]
    fn unit_scale_leaves_the_plain_range_alone_and_brings_the_rest_near_1() {
        for m in [1.0, 2f64.powi(-200), 2f64.powi(200), 3.5e-60, 7.0e59] {
            assert_eq!(unit_scale::<f64>(m), None, "{m:e} is in the plain range");
        }
        assert_eq!(unit_scale::<f64>(0.0), None);
        assert_eq!(unit_scale::<f64>(f64::INFINITY), None);
        for m in [f64::from_bits(1), 1e-300, 2f64.powi(-201), 2f64.powi(201), 1e300, f64::MAX] {
            let k = unit_scale::<f64>(m).expect("outside the plain range");
            let scaled = scale2(m, k);
            assert!((0.5..=2.0).contains(&scaled), "{m:e} scaled by 2^{k} is {scaled:e}");
        }
        assert_eq!(unit_scale::<f32>(1e7), None);
        let k = unit_scale::<f32>(1e-40).expect("an f32 subnormal");
        assert!((0.5..=2.0).contains(&scale2(1e-40f32, k)));
    }
}
