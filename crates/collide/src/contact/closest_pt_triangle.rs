//! Closest point of a triangle to a point.

use crate::real::{Real, Vec3};
use crate::shapes::Triangle;

/// The point of triangle `tri` closest to `p`.
///
/// **Method** (Ericson, *Real-Time Collision Detection*, §5.1.5): classify `p`
/// against the Voronoi regions of the vertices, then of the edges, using the dot
/// products `d1 … d6` of `p − v` with the edge vectors; the face region is last,
/// where the point is `v0 + v·ab + w·ac` with `v = vb / (va + vb + vc)` and
/// `w = vc / (va + vb + vc)`. Only dot products: no normal is formed, so the
/// result is accurate to a few ulps of the triangle's scale.
///
/// **Degenerate input.** For a zero-area triangle the face region's denominator
/// `va + vb + vc` vanishes. The book divides by it anyway; here a non-positive or
/// non-finite denominator falls back to the nearest of the three edges (each a
/// closest point on a segment, a zero-length edge being its endpoint), which is
/// the exact answer for a triangle collapsed onto a segment or a point.
pub fn closest_pt_point_triangle<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Vec3<T> {
    closest_pt_point_triangle_region(p, tri).0
}

/// Which feature of a triangle a closest point lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Region {
    /// A vertex or an edge (or a zero-area triangle's segment).
    Boundary,
    /// The open face.
    Face,
}

/// [`closest_pt_point_triangle`], with the region the point was found in. A
/// triangle whose vertices are exactly collinear (decided exactly) goes straight
/// to its edges: Ericson's region tests assume a non-zero area, and on a
/// zero-area triangle they can pick an edge region whose point is not the
/// nearest.
pub(crate) fn closest_pt_point_triangle_region<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> (Vec3<T>, Region) {
    let w = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let [a, b, c] = tri.vertices;
    if crate::exact::collinear(w(&a), w(&b), w(&c)) {
        return (nearest_on_edges(p, tri), Region::Boundary);
    }
    let q = |x: Vec3<T>| (x, Region::Boundary);
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(&ap);
    let d2 = ac.dot(&ap);
    if d1 <= T::zero() && d2 <= T::zero() {
        return q(a);
    }
    let bp = p - b;
    let d3 = ab.dot(&bp);
    let d4 = ac.dot(&bp);
    if d3 >= T::zero() && d4 <= d3 {
        return q(b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= T::zero() && d1 >= T::zero() && d3 <= T::zero() {
        let v = d1 / (d1 - d3);
        if v.finite() {
            return q(a + ab * v);
        }
    }
    let cp = p - c;
    let d5 = ab.dot(&cp);
    let d6 = ac.dot(&cp);
    if d6 >= T::zero() && d5 <= d6 {
        return q(c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= T::zero() && d2 >= T::zero() && d6 <= T::zero() {
        let w = d2 / (d2 - d6);
        if w.finite() {
            return q(a + ac * w);
        }
    }
    let va = d3 * d6 - d5 * d4;
    if va <= T::zero() && (d4 - d3) >= T::zero() && (d5 - d6) >= T::zero() {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        if w.finite() {
            return q(b + (c - b) * w);
        }
    }
    let denom = va + vb + vc;
    if denom > T::zero() && denom.finite() {
        let v = vb / denom;
        let w = vc / denom;
        let x = a + ab * v + ac * w;
        if crate::real::finite3(&x) {
            return (x, Region::Face);
        }
    }
    (nearest_on_edges(p, tri), Region::Boundary)
}

/// The closest point of segment `[a, b]` to `p` (a zero-length segment is `a`).
pub fn closest_pt_point_segment<T: Real>(p: &Vec3<T>, a: &Vec3<T>, b: &Vec3<T>) -> Vec3<T> {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 <= T::zero() || !len2.finite() {
        return *a;
    }
    let t = ((p - a).dot(&ab) / len2).max(T::zero()).min(T::one());
    if !t.finite() {
        return *a;
    }
    a + ab * t
}

pub(crate) fn nearest_on_edges<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Vec3<T> {
    let [a, b, c] = tri.vertices;
    let candidates =
        [closest_pt_point_segment(p, &a, &b), closest_pt_point_segment(p, &b, &c), closest_pt_point_segment(p, &c, &a)];
    let mut best = candidates[0];
    let mut best_d = crate::real::stable_norm(&(p - best));
    for q in &candidates[1..] {
        let d = crate::real::stable_norm(&(p - q));
        if d < best_d {
            best = *q;
            best_d = d;
        }
    }
    best
}
