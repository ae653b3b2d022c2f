//! Private helpers shared by the barycentric queries (and the bounding-volume
//! constructions): an overflow-free, exactly scaled frame, the flat-triangle test
//! and the degenerate-triangle fallback.

use crate::real::{Real, Vec3, c, finite3};

/// Flatness threshold of a triangle, in units of the type's machine epsilon ε:
/// a triangle is treated as zero-area when `‖(v1 − v0) × (v2 − v0)‖ ≤
/// FLAT_TRIANGLE_EPS · ε · L²`, `L` its longest edge (a scale-free test: both
/// sides scale with the square of the scene's size).
///
/// Reason: for three exactly collinear (or coincident) vertices the computed cross
/// product is pure rounding noise, bounded by about `3.6 ε L²` (each component is
/// `fl(fl(a·d) − fl(b·c))` of rounded differences, relative error ≤ 2.5ε on each
/// product, and `Σ (|a d| + |b c|)² ≤ 2 L⁴`). 16 leaves a margin of four, so every
/// exactly zero-area triangle is flagged; a genuine triangle this thin (smallest
/// height below about `16 ε L`) is flagged too, since its computed normal carries
/// at least a quarter of its length in rounding error.
pub(crate) const FLAT_TRIANGLE_EPS: f64 = 16.0;

/// The exponent `k` with `m · 2^k ∈ [1, 2)`, for a finite `m > 0`: read from
/// the bits of `m`'s `f64` value (exact; a subnormal is first scaled by
/// `2^64`).
#[inline]
pub(crate) fn unit_exponent<T: Real>(m: T) -> i32 {
    let m = m.wide();
    let biased = |x: f64| ((x.to_bits() >> 52) & 0x7ff) as i32;
    if m >= f64::MIN_POSITIVE { 1023 - biased(m) } else { 64 + 1023 - biased(m * TWO_TO_64) }
}

/// `2^64`, exactly.
const TWO_TO_64: f64 = 18446744073709551616.0;

/// `2^k` for `|k| ≤ 1022`, from its bits.
#[inline(always)]
fn pow2(k: i32) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// `v · 2^k`, applied as two power-of-two factors `2^⌊k/2⌋` and `2^(k − ⌊k/2⌋)` so
/// that neither factor overflows the type (|k| ≤ 1075 for `f64`, ≤ 150 for `f32`,
/// halves ≤ 538 and 75). Exact unless a result is subnormal or overflows.
#[inline]
pub(crate) fn mul_pow2<T: Real>(v: &Vec3<T>, k: i32) -> Vec3<T> {
    let k1 = k / 2;
    let k2 = k - k1;
    v * c::<T>(pow2(k1)) * c::<T>(pow2(k2))
}

/// The largest absolute component of `v`.
#[inline]
pub(crate) fn max_abs<T: Real>(v: &Vec3<T>) -> T {
    v.x.abs().max(v.y.abs()).max(v.z.abs())
}

/// The differences `x − y` of the given pairs, in one common frame: if any
/// difference overflows, every pair is first halved (`x/2 − y/2`, exact for all
/// but subnormal inputs); then all are multiplied by the same power of two `2^k`
/// (exact) chosen so that the largest component among the first `lead`
/// differences lies in `[1, 2)`. Ratios of lengths, areas and volumes, and so
/// barycentric coordinates, are unchanged by this uniform scaling, and no product
/// of two lead differences can overflow or underflow afterwards.
///
/// Returns `None` when the first `lead` differences are all exactly zero (no
/// scale to normalize by). Differences beyond `lead` may still overflow to ±∞
/// after scaling when they exceed the lead ones by more than the type's range.
pub(crate) fn scaled_differences<T: Real, const N: usize>(
    pairs: [(&Vec3<T>, &Vec3<T>); N],
    lead: usize,
) -> Option<[Vec3<T>; N]> {
    let mut d = pairs.map(|(x, y)| x - y);
    if !d.iter().all(finite3) {
        let half = c::<T>(0.5);
        d = pairs.map(|(x, y)| x * half - y * half);
    }
    let m = d[..lead].iter().map(max_abs).fold(T::zero(), |a, b| a.max(b));
    if m == T::zero() {
        return None;
    }
    let k = unit_exponent(m);
    Some(d.map(|v| mul_pow2(&v, k)))
}

/// Whether the triangle with edge vectors `e0 = v1 − v0`, `e1 = v2 − v0` (in a
/// scaled frame, see [`scaled_differences`]) and face normal `n = e0 × e1` is flat
/// by the scale-relative test of [`FLAT_TRIANGLE_EPS`].
pub(crate) fn is_flat_triangle<T: Real>(e0: &Vec3<T>, e1: &Vec3<T>, n: &Vec3<T>) -> bool {
    let e2 = e1 - e0;
    let l2 = e0.norm_squared().max(e1.norm_squared()).max(e2.norm_squared());
    let tol = c::<T>(FLAT_TRIANGLE_EPS) * T::EPSILON * l2;
    n.norm_squared() <= tol * tol
}

/// The fallback coordinates for a triangle without a usable plane: the closest
/// point to `p` on the triangle's longest edge, written as barycentric
/// coordinates (`1 − t` and `t` on that edge's endpoints, 0 on the third vertex,
/// `t ∈ [0, 1]`); `[1, 0, 0]` when all three vertices coincide. Non-negative and
/// summing to 1 (to one rounding of `1 − t`).
///
/// The clamped parameter is `t = clamp((p − u)·(w − u) / ‖w − u‖², 0, 1)` for the
/// longest edge `u → w`, computed in a scaled frame so it cannot overflow; a
/// non-finite quotient (a point beyond the type's range relative to the edge)
/// clamps by its sign, and an undefined one gives `t = 0`.
pub(crate) fn longest_edge_fallback<T: Real>(p: &Vec3<T>, v: &[Vec3<T>; 3]) -> [T; 3] {
    // Edge k joins vertex k to vertex (k + 1) % 3; all three in one scaled frame.
    let mut out = [T::zero(); 3];
    let Some(edges) = scaled_differences([(&v[1], &v[0]), (&v[2], &v[1]), (&v[0], &v[2])], 3) else {
        out[0] = T::one();
        return out;
    };
    let mut k = 0;
    for j in 1..3 {
        if edges[j].norm_squared() > edges[k].norm_squared() {
            k = j;
        }
    }
    let (i, j) = (k, (k + 1) % 3);
    let Some([d, q]) = scaled_differences([(&v[j], &v[i]), (p, &v[i])], 1) else {
        // Unreachable in exact terms (the longest edge is non-zero); kept total.
        out[0] = T::one();
        return out;
    };
    let t = q.dot(&d) / d.norm_squared();
    let t = if t > T::zero() { t.min(T::one()) } else { T::zero() };
    out[i] = T::one() - t;
    out[j] = t;
    out
}
