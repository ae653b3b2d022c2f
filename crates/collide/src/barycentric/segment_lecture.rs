//! The lecture's barycentric coordinates on a segment: ratios of unsigned lengths.

use super::coords::Barycentric;
use super::local::scaled_differences;
use crate::real::{Real, Vec3, stable_norm};
use crate::shapes::Segment;

/// The lecture's barycentric coordinates of `p` on `seg` (`a = seg.start`,
/// `b = seg.end`): each vertex's coordinate is the length of the opposite part
/// divided by the whole length,
///
/// ```text
/// α = ‖p − b‖ / ‖b − a‖,   β = ‖p − a‖ / ‖b − a‖,   coords = [α, β]
/// ```
///
/// Derivation: for `p = (1 − t) a + t b` on the segment, `‖p − a‖ = t ‖b − a‖` and
/// `‖p − b‖ = (1 − t) ‖b − a‖`, so `β = t`, `α = 1 − t`: the 1-D analogue of the
/// lecture's area ratios (each coordinate is the measure of the sub-simplex
/// opposite its vertex over the measure of the whole).
///
/// Returned exactly as the lecture defines them, raw: the lengths are unsigned,
/// so the coordinates are never negative, and they sum to 1 only for `p` on the
/// segment. Before `a` or past `b` they sum to more than 1 (`p` at `a − (b − a)`
/// gives `[2, 1]`, where the signed coordinates are `[2, −1]`), and off the line
/// they describe no point of the line at all. That is the method's limitation,
/// shown as it is; [`barycentric_segment`](super::barycentric_segment) is the
/// signed, projected counterpart.
///
/// Numerics: the three differences are formed in one frame scaled by an exact
/// power of two (halved first if one overflows), and the lengths use
/// [`stable_norm`], so no intermediate overflows or underflows.
///
/// Degenerate input: a zero-length segment (`a == b` exactly) sets `degenerate`
/// with the fallback `[1, 0]`. Ratios beyond the type's range (`p` farther than
/// `‖b − a‖` times the largest finite value) are answered as degenerate with the
/// nearer endpoint: `[1, 0]` when `‖p − a‖ ≤ ‖p − b‖`, else `[0, 1]`. Never NaN
/// for finite input.
pub fn barycentric_segment_lecture<T: Real>(p: &Vec3<T>, seg: &Segment<T>) -> Barycentric<T, 2> {
    let (a, b) = (&seg.start, &seg.end);
    let Some([d, pa, pb]) = scaled_differences([(b, a), (p, a), (p, b)], 1) else {
        return Barycentric { coords: [T::one(), T::zero()], degenerate: true };
    };
    let len = stable_norm(&d);
    let (to_a, to_b) = (stable_norm(&pa), stable_norm(&pb));
    let coords = [to_b / len, to_a / len];
    if !(coords[0].finite() && coords[1].finite()) {
        let near_a = to_a <= to_b;
        let coords = if near_a { [T::one(), T::zero()] } else { [T::zero(), T::one()] };
        return Barycentric { coords, degenerate: true };
    }
    Barycentric { coords, degenerate: false }
}
