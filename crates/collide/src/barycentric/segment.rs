//! Signed barycentric coordinates on a segment, of the point's projection.

use super::coords::Barycentric;
use super::local::scaled_differences;
use crate::real::Real;
use crate::real::Vec3;
use crate::shapes::Segment;

/// Signed barycentric coordinates `[1 − t, t]` of the orthogonal projection of `p`
/// onto the line through `seg`, with `a = seg.start`, `b = seg.end`:
///
/// ```text
/// t = (p − a)·(b − a) / ‖b − a‖²
/// ```
///
/// Derivation: the projection `q = a + t (b − a)` is the point of the line whose
/// offset `p − q` is orthogonal to the direction: `(p − a − t (b − a))·(b − a) = 0`
/// gives `t` above, and `q = (1 − t) a + t b`. `t < 0` before `a`, `t > 1` past
/// `b`, so the coordinates are negative outside the segment (the robust
/// counterpart of the lecture's unsigned length ratios,
/// [`barycentric_segment_lecture`](super::barycentric_segment_lecture)). Source:
/// Ericson, *Real-Time Collision Detection*, §5.1.2 (the unclamped `t`).
///
/// Numerics: `b − a` and `p − a` are formed in one frame scaled by an exact power
/// of two (halved first if a difference overflows), so `‖b − a‖²` can neither
/// overflow nor underflow; the coordinates are the same as in exact scaling. They
/// sum to 1 to one rounding of `1 − t`.
///
/// Degenerate input: a zero-length segment (`a == b` exactly; any non-zero length
/// is usable after scaling) has no direction: `degenerate` is set and the
/// fallback is `[1, 0]` (the point is attributed to `a`). A `t` beyond the type's
/// range (`p` farther from `a` than `‖b − a‖` times the largest finite value) is
/// also answered as degenerate, with the endpoint on `p`'s side: `[0, 1]` for
/// `t = +∞`, `[1, 0]` otherwise. Never NaN for finite input.
pub fn barycentric_segment<T: Real>(p: &Vec3<T>, seg: &Segment<T>) -> Barycentric<T, 2> {
    let (a, b) = (&seg.start, &seg.end);
    let fallback = |coords| Barycentric { coords, degenerate: true };
    let Some([d, q]) = scaled_differences([(b, a), (p, a)], 1) else {
        return fallback([T::one(), T::zero()]);
    };
    let t = q.dot(&d) / d.norm_squared();
    if !t.finite() {
        return if t > T::zero() { fallback([T::zero(), T::one()]) } else { fallback([T::one(), T::zero()]) };
    }
    Barycentric { coords: [T::one() - t, t], degenerate: false }
}
