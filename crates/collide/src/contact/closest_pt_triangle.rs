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
    let found = closest_pt_point_triangle_region_with_area(p, tri);
    (found.point, found.region)
}

/// What [`closest_pt_point_triangle_region_with_area`] found: the closest
/// point, its region, and the book's three edge tests with the magnitudes that
/// bound their rounding.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Closest<T: Real> {
    /// The closest point.
    pub point: Vec3<T>,
    /// The feature it lies on.
    pub region: Region,
    /// The book's `[va, vb, vc]` as computed. Exactly (by the Binet–Cauchy
    /// identity `(ab·ap)(ac·bp) − (ab·bp)(ac·ap) = (ab × ac)·(ap × bp)`),
    /// `va = n · ((b − p) × (c − p))`, `vb = n · ((c − p) × (a − p))`,
    /// `vc = n · ((a − p) × (b − p))` with `n = (b − a) × (c − a)`: `‖n‖²`
    /// times the barycentric coordinates of `p`'s projection onto the plane,
    /// positive when the projection is strictly inside the edge opposite
    /// `a`, `b`, `c` respectively.
    pub edge_tests: [T; 3],
    /// `E`: the largest component magnitude of the computed edges `b − a`
    /// and `c − a`; infinite when the branching fallback answered (then
    /// `edge_tests` are not computed).
    pub edge_extent: T,
    /// `Q`: the largest component magnitude of the computed offsets `p − a`,
    /// `p − b`, `p − c`.
    pub offset_extent: T,
}

/// Bound on the rounding of [`Closest::edge_tests`] in units of `u` and of
/// `(E Q)²` ([`Closest::edge_extent`], [`Closest::offset_extent`]): each
/// computed test is within `217 u (E Q)²` of its exact value on the given
/// inputs (`u` the unit roundoff, in `f64` when no product underflows or
/// overflows). Derivation: the differences round once (`|fl(x) − x| ≤
/// u |fl(x)|`), so each dot product `d_i` is within `(γ3 + 2u + u²) Σ |e_k|
/// |o_k| ≤ 15.01 u E Q` of the exact one, and both are at most `3.001 E Q`
/// in magnitude; a test `d_i d_j − d_k d_l` is then within
/// `2 · 15.01 · 3.001 · 2 u (E Q)²` (the factors' errors) plus
/// `γ2 · 2 · 3.001² (E Q)²` (its own two roundings), `216.2 u (E Q)²` in all.
pub(crate) const EDGE_TEST_ROUNDING: f64 = 217.0;

/// [`closest_pt_point_triangle_region`] for a triangle already known not to
/// have exactly zero area (the caller decided it): Ericson's region tests,
/// evaluated without branches, with the edge tests they were decided by
/// ([`Closest`]).
///
/// Every quantity of the book's tests (`d1 … d6`, `va`, `vb`, `vc`) is
/// computed, the seven regions' conditions are evaluated, and the region is
/// selected as the book's early returns would select it — the first in the
/// order vertex A, vertex B, edge AB, vertex C, edge AC, edge BC, face whose
/// condition holds (an edge region only when its parameter is finite, as in
/// [`closest_pt_point_triangle`]). The point is then formed once as
/// `base + s e + t (c − a)` with the region's base vertex, edge `e` and
/// parameters (`0` for a vertex), which gives the book's expressions
/// bit for bit (`a + ab v`, `a + ac w`, `b + (c − b) w`, `a + ab v + ac w`,
/// the vertex itself). For random queries this replaces three or four
/// unpredictable branches by a few selects and two divisions; answers are
/// unchanged. A non-finite point (coordinates near the overflow threshold)
/// falls back to the branching form.
///
/// **Rounding.** The region is the book's, decided on rounded values: the
/// edge tests `va`, `vb`, `vc` are degree-4 polynomials whose rounding
/// ([`EDGE_TEST_ROUNDING`]) is relative to `(E Q)²`, while their values are
/// `‖n‖ · ‖edge‖ · (distance of the projection from that edge)`: on a sliver
/// (`‖n‖` tiny) or for a projection within rounding of an edge the computed
/// signs, hence the region, can be wrong. The caller that needs the region
/// certified compares them with that bound.
///
/// Always inlined: its caller usually builds the triangle just before (in a
/// translated frame), and a call would reload those fresh stores through
/// memory in wider loads than they were written with, which stalls.
#[inline(always)]
pub(crate) fn closest_pt_point_triangle_region_with_area<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Closest<T> {
    let [a, b, c] = tri.vertices;
    let (zero, one) = (T::zero(), T::one());
    let (ab, ac, bc) = (b - a, c - a, c - b);
    let (ap, bp, cp) = (p - a, p - b, p - c);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    let vc = d1 * d4 - d3 * d2;
    let vb = d5 * d2 - d1 * d6;
    let va = d3 * d6 - d5 * d4;
    // An edge parameter num / den with 0 ≤ num ≤ den is finite exactly when
    // den > 0 (not NaN) and num is finite.
    let finite_quotient = |num: T, den: T| den > zero && num.finite();
    let (bc_num, bc_rest) = (d4 - d3, d5 - d6);
    let bc_den = bc_num + bc_rest;
    let denom = va + vb + vc;
    // (base, edge, s numerator, t numerator, denominator, region), the
    // book's regions from last to first: each that holds overrides the ones
    // after it in the book's order.
    let mut sel = (a, ab, vb, vc, denom, Region::Face);
    if va <= zero && bc_num >= zero && bc_rest >= zero && finite_quotient(bc_num, bc_den) {
        sel = (b, bc, bc_num, zero, bc_den, Region::Boundary);
    }
    if vb <= zero && d2 >= zero && d6 <= zero && finite_quotient(d2, d2 - d6) {
        sel = (a, ab, zero, d2, d2 - d6, Region::Boundary);
    }
    if d6 >= zero && d5 <= d6 {
        sel = (c, ab, zero, zero, one, Region::Boundary);
    }
    if vc <= zero && d1 >= zero && d3 <= zero && finite_quotient(d1, d1 - d3) {
        sel = (a, ab, d1, zero, d1 - d3, Region::Boundary);
    }
    if d3 >= zero && d4 <= d3 {
        sel = (b, ab, zero, zero, one, Region::Boundary);
    }
    if d1 <= zero && d2 <= zero {
        sel = (a, ab, zero, zero, one, Region::Boundary);
    }
    let (base, edge, s_num, t_num, den, region) = sel;
    let x = base + edge * (s_num / den) + ac * (t_num / den);
    let face_ok = region == Region::Boundary || (denom > zero && denom.finite());
    if face_ok && crate::real::finite3(&x) {
        return Closest {
            point: x,
            region,
            edge_tests: [va, vb, vc],
            edge_extent: ab.amax().max(ac.amax()),
            offset_extent: ap.amax().max(bp.amax()).max(cp.amax()),
        };
    }
    let (point, region) = closest_pt_point_triangle_region_branching(p, tri);
    let unknown = T::of(f64::INFINITY);
    Closest { point, region, edge_tests: [unknown; 3], edge_extent: unknown, offset_extent: unknown }
}

/// Ericson's region tests with the book's early returns (the fallback of
/// [`closest_pt_point_triangle_region_with_area`] near the overflow
/// threshold, where its selected point is not finite).
#[cold]
fn closest_pt_point_triangle_region_branching<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> (Vec3<T>, Region) {
    let [a, b, c] = tri.vertices;
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
    segment_foot(p, a, b).0
}

/// [`closest_pt_point_segment`], and whether the foot of `p` on the
/// segment's line fell strictly inside it (`0 < t < 1` as computed), i.e.
/// was not clamped to an end.
///
/// The foot is formed from the nearer end: `a + (b − a) t` for `t ≤ 1/2`,
/// else `b + (a − b) t_b` with `t_b` computed from `b` (not `1 − t`), so its
/// rounding is relative to its distance from that end, not to the
/// segment's length: a foot 3.5 from the end of an edge of length `1e15` is
/// placed to a few ulps of 3.5, where `b + (a − b)(1 − t)` would be off by
/// `ε · 1e15`; and it is clamped at `b` by `t_b ≤ 0`, not by `t ≥ 1`
/// (which rounds a foot `1e-16` of the length inside to the end). A segment whose squared length is outside the plain range
/// (huge or tiny edges) takes [`segment_foot_scaled`].
fn segment_foot<T: Real>(p: &Vec3<T>, a: &Vec3<T>, b: &Vec3<T>) -> (Vec3<T>, bool) {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let (lo, hi) = crate::exact::norm::safe_squared_range::<T>();
    if !(len2 >= lo && len2 <= hi) {
        return segment_foot_scaled(p, a, b);
    }
    // Numerators below the plain range may have lost their products to
    // underflow (a tiny scene): the scaled path.
    let num = (p - a).dot(&ab);
    if num.abs() < lo && num != T::zero() {
        return segment_foot_scaled(p, a, b);
    }
    let raw = num / len2;
    let half: T = crate::real::c(0.5);
    if !(raw > T::zero()) {
        // A positive numerator whose parameter underflowed: the foot is
        // still off `a` by `num / ‖ab‖`, which the scaled path forms.
        if num > T::zero() {
            return segment_foot_scaled(p, a, b);
        }
        return (*a, false);
    }
    if raw <= half {
        return (a + ab * raw, true);
    }
    // Clamped at `b` by its own parameter: `raw` near 1 has lost what
    // separates a foot a little inside from `b`.
    let num_b = (p - b).dot(&(-ab));
    if num_b.abs() < lo && num_b != T::zero() {
        return segment_foot_scaled(p, a, b);
    }
    let from_b = num_b / len2;
    if !(from_b > T::zero()) {
        if num_b > T::zero() {
            return segment_foot_scaled(p, a, b);
        }
        return (*b, false);
    }
    (b - ab * from_b, true)
}

/// [`segment_foot`] for a segment whose squared length leaves the plain
/// range, in `f64` on the widened inputs: the edge at half scale
/// (`b/2 − a/2`, which cannot overflow) divided by the power of two `s` of
/// its largest component, the offsets `p − a` and `p − b` at a quarter
/// scale, the parameter scaled back once; the foot from the nearer end. A
/// zero-length segment is `a`.
#[cold]
#[inline(never)]
fn segment_foot_scaled<T: Real>(p: &Vec3<T>, a: &Vec3<T>, b: &Vec3<T>) -> (Vec3<T>, bool) {
    use crate::exact::{frexp, ldexp};
    let w = crate::real::to_f64_3::<T>;
    let (pw, aw, bw) = (w(p), w(a), w(b));
    let half = [0, 1, 2].map(|i| bw[i] * 0.5 - aw[i] * 0.5);
    let top = half.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(top > 0.0 && top.is_finite()) {
        return (*a, false);
    }
    let (_, k) = frexp(top);
    let u = half.map(|x| ldexp(x, -k));
    let uu = (u[0] * u[0] + u[1] * u[1]) + u[2] * u[2];
    let dot = |x: [f64; 3], y: [f64; 3]| (x[0] * y[0] + x[1] * y[1]) + x[2] * y[2];
    // ab = 2 · 2^k u and p − a = 4 q: t = (q · u)/(u · u) · 2^(1 − k), and
    // the foot's offset from the end is ab · t = 4 u (q · u)/(u · u), formed
    // from `c = (q · u)/(u · u)` directly: the parameter itself underflows
    // for a foot near the end of an edge of 1e298 (an offset of 1e-63 is a
    // parameter of 1e-361), and a foot formed through it landed on the end.
    let param = |from: [f64; 3], dir: [f64; 3]| {
        let q = [0, 1, 2].map(|i| pw[i] * 0.25 - from[i] * 0.25);
        let c = dot(q, dir) / uu;
        (c, ldexp(c, 1 - k))
    };
    let (c, raw) = param(aw, u);
    if !(c > 0.0) {
        return (*a, false);
    }
    let back = |x: [f64; 3]| Vec3::new(T::of(x[0]), T::of(x[1]), T::of(x[2]));
    if raw <= 0.5 {
        return (back([0, 1, 2].map(|i| aw[i] + u[i] * (4.0 * c))), true);
    }
    let (c_b, _) = param(bw, u.map(|x| -x));
    if !(c_b > 0.0) {
        return (*b, false);
    }
    (back([0, 1, 2].map(|i| bw[i] - u[i] * (4.0 * c_b))), true)
}

/// The point of the triangle's three edges nearest to `p` (each edge's
/// closest point, the nearest by distance, the first on a tie): the closest
/// point of a zero-area triangle, and of any triangle when `p`'s projection
/// is outside it.
pub(crate) fn nearest_on_edges<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Vec3<T> {
    nearest_of_edges(p, tri, [true; 3], false)
}

/// The closest point of the triangle to `p` when `p`'s projection onto its
/// plane is outside it (or within rounding of an edge): among the edges
/// `ab`, `bc`, `ca` for which `edges` is set — at least one, and every edge
/// the projection may be outside of — the closest point of the one whose
/// foot falls strictly inside it, or if none does, the nearest of their
/// (clamped) closest points by distance (the first on a tie).
///
/// Why not [`nearest_on_edges`]: for `p` off the plane by `d`, two candidates
/// at in-plane distances `h1 < h2` from the projection are at distances whose
/// squares differ by `h2² − h1²`, which the rounding of `d² + h²` (a few
/// `ε (d² + h²)`) hides when the candidates are within `√ε d` of each other:
/// a first-order point error of `1e-8 d` from a second-order difference. Two
/// such candidates lie on two nearly parallel edges (the long edges of a
/// sliver), or are a foot inside one edge and the vertex it shares with
/// another, on which the foot was clamped. The first case is removed by the
/// edges passed: the closest point of a triangle is inside an edge only for
/// points on that edge's outer side, and is a vertex only for points outside
/// one of the vertex's two edges (inside both, `p − v` is a non-negative
/// combination of the edges from `v`, whose dot products with `p − v` cannot
/// both be `≤ 0` unless `p = v`). The second by preferring a foot inside its
/// edge: for a projection outside that edge, the foot is the closest point
/// (the edges' Voronoi regions are disjoint). A foot taken for inside by
/// rounding is within that rounding of its end; a projection within
/// rounding of an edge's line, on its inner side, is within that rounding
/// (over the sine of the angle between the edges, times that edge's height
/// at most) of the answer.
pub(crate) fn closest_on_outer_edges<T: Real>(p: &Vec3<T>, tri: &Triangle<T>, edges: [bool; 3]) -> Vec3<T> {
    nearest_of_edges(p, tri, edges, true)
}

/// The nearest to `p` of the closest points of the edges `ab`, `bc`, `ca`
/// for which `edges` is set, by distance; with `prefer_inside`, a foot
/// strictly inside its edge before any clamped one.
fn nearest_of_edges<T: Real>(p: &Vec3<T>, tri: &Triangle<T>, edges: [bool; 3], prefer_inside: bool) -> Vec3<T> {
    let [a, b, c] = tri.vertices;
    let ends = [(a, b), (b, c), (c, a)];
    // (point, distance, foot inside its edge)
    let mut best: Option<(Vec3<T>, T, bool)> = None;
    for (&(u, w), _) in ends.iter().zip(edges).filter(|(_, on)| *on) {
        let (q, inside) = segment_foot(p, &u, &w);
        let inside = inside && prefer_inside;
        let d = crate::real::stable_norm(&(p - q));
        let better = match best {
            None => true,
            Some((_, best_d, best_inside)) => (inside && !best_inside) || (inside == best_inside && d < best_d),
        };
        if better {
            best = Some((q, d, inside));
        }
    }
    best.map_or(a, |(q, _, _)| q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn v(p: [f64; 3]) -> Vec3<f64> {
        Vec3::new(p[0], p[1], p[2])
    }

    /// Coordinates on a coarse grid (so that region borders are hit exactly:
    /// `d_i = 0`, `va = 0`, …) or anywhere in a box.
    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![(-8i32..=8).prop_map(|k| f64::from(k) / 4.0), -3.0..3.0f64]
    }

    fn point() -> impl Strategy<Value = [f64; 3]> {
        [coord(), coord(), coord()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// The branch-free selection gives the book's region and the book's
        /// point, to the bit (`==` also equates `−0.0` and `0.0`, the one
        /// difference the final `+ 0` may make).
        #[test]
        fn branch_free_regions_are_the_books(p in point(), a in point(), b in point(), c in point()) {
            let tri = Triangle::new(v(a), v(b), v(c));
            prop_assume!(!crate::exact::collinear(a, b, c));
            let found = closest_pt_point_triangle_region_with_area(&v(p), &tri);
            let (x, rx) = (found.point, found.region);
            let (y, ry) = closest_pt_point_triangle_region_branching(&v(p), &tri);
            prop_assert_eq!(rx, ry, "region");
            #[expect(clippy::float_cmp, reason = "two evaluations of the same expressions: identity is the claim")]
            let same = x.x == y.x && x.y == y.y && x.z == y.z;
            prop_assert!(same, "{:?} vs {:?}", x, y);
        }
    }
}

#[cfg(test)]
mod foot_tests {
    use super::*;

    /// The foot is formed once from the nearer end: within a few ulps of its
    /// own offset (4 ε relative).
    const FOOT_REL: f64 = 4.0 * f64::EPSILON;

    #[test]
    fn foot_near_the_end_of_a_huge_edge_is_not_the_end() {
        // Edge from the origin to (0, 0, −3e298); the point (1, 0, −5e-63):
        // the foot (0, 0, −5e-63) has the parameter 1.7e-361, below f64's.
        let (a, b) = (Vec3::<f64>::new(0.0, 0.0, 0.0), Vec3::<f64>::new(0.0, 0.0, -3e298));
        let q = closest_pt_point_segment(&Vec3::new(1.0, 0.0, -5e-63), &a, &b);
        assert!((q.z / -5e-63 - 1.0).abs() <= FOOT_REL && q.x.abs() <= FOOT_REL * 5e-63, "{q:?}");
    }
}
