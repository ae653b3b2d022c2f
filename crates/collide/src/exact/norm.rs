//! Norms without spurious overflow or underflow, fast where the plain formula
//! is already exact enough: the queries' hot paths use the plain `√(v · v)`
//! inside [`safe_squared_range`] and the scaled forms of [`crate::real`]
//! outside it.

use crate::real::{Real, Vec3, try_normalize_stable};

/// `n / ‖n‖`: the plain square root of `n · n` where that cannot lose
/// precision (`n · n` within `[m/ε², M ε²]` of the type's normal range, `ε`
/// its epsilon), [`try_normalize_stable`] otherwise.
#[inline]
pub(crate) fn normalize<T: Real>(n: &Vec3<T>) -> Option<Vec3<T>> {
    let nn = n.norm_squared();
    let (lo, hi) = safe_squared_range::<T>();
    if nn >= lo && nn <= hi { Some(n * (T::one() / nn.sqrt())) } else { try_normalize_stable(n) }
}

/// The range of a sum of three squares `s` in which `√s` is as accurate as the
/// type allows: its largest term is normal with `2p` bits to spare (`s ≥ m/ε²`,
/// `m` the smallest normal) and nothing overflowed (`s ≤ M ε²`, `M` the largest
/// finite value): `[2^−918, 2^920]` in `f64`, `[2^−80, 2^82]` in `f32`.
#[inline(always)]
pub(crate) fn safe_squared_range<T: Real>() -> (T, T) {
    if T::EPSILON.wide() < 1e-10 {
        (T::of(f64::MIN_POSITIVE / (f64::EPSILON * f64::EPSILON)), T::of(f64::MAX * (f64::EPSILON * f64::EPSILON)))
    } else {
        let (e, m, big) = (f64::from(f32::EPSILON), f64::from(f32::MIN_POSITIVE), f64::from(f32::MAX));
        (T::of(m / (e * e)), T::of(big * (e * e)))
    }
}

/// `1 + 8u` (`u` the unit roundoff of `T`), the margin of a root-free "apart"
/// test between spheres: a computed `‖Δ‖²` above `fl(fl(reach²) · (1 + 8u))`
/// exceeds `reach² (1 + 5u)` exactly, so `fl(√‖Δ‖²) > reach (1 + 2u) > reach`:
/// the test `dist > reach` would say "apart" too, and the square root can be
/// skipped. Shared by the sphere–sphere contact and the batch API, which must
/// make the same decisions.
#[inline(always)]
pub(crate) fn clear_miss_factor<T: Real>() -> T {
    T::one() + T::of(4.0) * T::EPSILON
}
