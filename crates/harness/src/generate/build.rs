//! The pieces every generator is built from: shape constructors, a little vector
//! arithmetic beyond [`crashtest_core::vec3`]'s, exact number tools (powers of
//! two, dyadic grids, ULP steps, Pythagorean directions) and whole-scene
//! transforms.
//!
//! Portability: nothing here calls a transcendental function (`powf`, `sin`,
//! `exp`), whose last bit differs between C libraries. Magnitudes are drawn as
//! `m · 2^k` (mantissa uniform in `[1, 2)`, exponent uniform), which is
//! log-uniform to within a factor of 2 and reproducible on every platform: a case
//! is the same everywhere for the same `(seed, index)`.

use crate::case::{AabbSpec, BoxSpec, PlaneSpec, PointSpec, PointsSpec, SegmentSpec, Shape, SphereSpec, TriangleSpec};
use crashtest_core::vec3::{add, cross, dot, norm_sqrt_dot, scale, sub};
use oracle::geom::P3;
use oracle::geom::{Capsule, MovingPoint, MovingSegment, MovingTriangle};
use proptest::prelude::*;

/// A generated scene: `a`, and `b` for every query but `bounds`.
pub(crate) type Scene = (Shape, Option<Shape>);

/// A solid ball.
pub(crate) fn sphere(center: P3, radius: f64) -> Shape {
    Shape::Sphere(SphereSpec { center, radius, velocity: None, mass: None })
}

/// The plane `normal · x = offset`.
pub(crate) fn plane(normal: P3, offset: f64) -> Shape {
    Shape::Plane(PlaneSpec { normal, offset, velocity: None })
}

/// A segment.
pub(crate) fn segment(start: P3, end: P3) -> Shape {
    Shape::Segment(SegmentSpec { start, end })
}

/// A triangle.
pub(crate) fn triangle(vertices: [P3; 3]) -> Shape {
    Shape::Triangle(TriangleSpec { vertices, velocity: None })
}

/// A point.
pub(crate) fn point(at: P3) -> Shape {
    Shape::Point(PointSpec { at })
}

/// A point cloud.
pub(crate) fn points(points: Vec<P3>) -> Shape {
    Shape::Points(PointsSpec { points })
}

/// An axis-aligned box.
pub(crate) fn aabb(min: P3, max: P3) -> Shape {
    Shape::Aabb(AabbSpec { min, max })
}

/// A box that may be rotated: `rotation` the quaternion `[w, x, y, z]`.
pub(crate) fn oriented_box(center: P3, half_extents: P3, rotation: [f64; 4]) -> Shape {
    Shape::Box(BoxSpec { center, half_extents, rotation: Some(rotation), velocity: None })
}

/// A capsule.
pub(crate) fn convex(points: Vec<P3>) -> Shape {
    Shape::Convex(oracle::geom::Convex { points })
}

pub(crate) fn capsule(start: P3, end: P3, radius: f64) -> Shape {
    Shape::Capsule(Capsule { start, end, radius })
}

/// A quaternion `[w, x, y, z]` (not normalized) of the rotation with rows
/// `r`: Shepperd's choice of the largest of `1 + tr`, `1 + 2rᵢᵢ − tr`, each
/// quaternion scaled by four times that component, so that every entry is a
/// sum of `r`'s entries (no square root: a quaternion of any length is a
/// box's rotation).
pub(crate) fn quaternion_of(r: [P3; 3]) -> [f64; 4] {
    let tr = r[0][0] + r[1][1] + r[2][2];
    let cand = [1.0 + tr, 1.0 + 2.0 * r[0][0] - tr, 1.0 + 2.0 * r[1][1] - tr, 1.0 + 2.0 * r[2][2] - tr];
    let k = (0..4).fold(0, |k, i| if cand[i] > cand[k] { i } else { k });
    let (a, b, c) = (r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]);
    let (d, e, f) = (r[0][1] + r[1][0], r[0][2] + r[2][0], r[1][2] + r[2][1]);
    match k {
        0 => [cand[0], a, b, c],
        1 => [a, cand[1], d, e],
        2 => [b, d, cand[2], f],
        _ => [c, e, f, cand[3]],
    }
}

/// The Hamilton product `p ⊗ q`, whose rotation is `R(p)·R(q)`.
pub(crate) fn hamilton(p: [f64; 4], q: [f64; 4]) -> [f64; 4] {
    let ([a1, b1, c1, d1], [a2, b2, c2, d2]) = (p, q);
    [
        a1 * a2 - b1 * b2 - c1 * c2 - d1 * d2,
        a1 * b2 + b1 * a2 + c1 * d2 - d1 * c2,
        a1 * c2 - b1 * d2 + c1 * a2 + d1 * b2,
        a1 * d2 + b1 * c2 - c1 * b2 + d1 * a2,
    ]
}

/// The determinant of a row matrix.
fn det3(m: [P3; 3]) -> f64 {
    dot(m[0], cross(m[1], m[2]))
}

/// A point moving linearly from `t0` (time 0) to `t1` (time 1).
pub(crate) fn moving_point(t0: P3, t1: P3) -> Shape {
    Shape::MovingPoint(MovingPoint { t0, t1 })
}

/// A segment whose ends move linearly from `t0` to `t1`.
pub(crate) fn moving_segment(t0: [P3; 2], t1: [P3; 2]) -> Shape {
    Shape::MovingSegment(MovingSegment { t0, t1 })
}

/// A triangle whose vertices move linearly from `t0` to `t1`.
pub(crate) fn moving_triangle(t0: [P3; 3], t1: [P3; 3]) -> Shape {
    Shape::MovingTriangle(MovingTriangle { t0, t1 })
}

/// Below this length a random vector is too short to give a direction (its
/// normalization would amplify rounding); the fallback direction is used instead.
const SHORTEST_DIRECTION: f64 = 1e-3;

/// `a / ‖a‖`, or `fallback` when `a` is shorter than [`SHORTEST_DIRECTION`].
pub(crate) fn normalize_or(a: P3, fallback: P3) -> P3 {
    let n = norm_sqrt_dot(a);
    if n >= SHORTEST_DIRECTION { scale(a, 1.0 / n) } else { fallback }
}

/// A unit vector perpendicular to the unit vector `u` (the cross product with the
/// coordinate axis least aligned with `u`, normalized).
pub(crate) fn perpendicular(u: P3) -> P3 {
    let axis = if u[0].abs() <= u[1].abs() && u[0].abs() <= u[2].abs() {
        [1.0, 0.0, 0.0]
    } else if u[1].abs() <= u[2].abs() {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    };
    let c = cross(u, axis);
    scale(c, 1.0 / norm_sqrt_dot(c))
}

/// `2^k`, exactly, for `k` in the normal range `[-1022, 1023]` (clamped to it).
pub(crate) fn pow2(k: i32) -> f64 {
    let k = k.clamp(-1022, 1023);
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// `x` moved `k` ULPs (up for `k > 0`, down for `k < 0`; 0 leaves it).
pub(crate) fn step_ulps(mut x: f64, k: i32) -> f64 {
    for _ in 0..k.unsigned_abs() {
        x = if k > 0 { x.next_up() } else { x.next_down() };
    }
    x
}

/// Coordinates of uniform scenes lie in `[-BOX, BOX]`.
pub(crate) const BOX: f64 = 4.0;

/// A coordinate, uniform in `[-lim, lim)`.
pub(crate) fn coord(lim: f64) -> impl Strategy<Value = f64> + Clone {
    -lim..lim
}

/// A point, uniform in the cube `[-lim, lim)³`.
pub(crate) fn vec3(lim: f64) -> impl Strategy<Value = P3> + Clone {
    prop::array::uniform3(coord(lim))
}

/// A unit vector (a normalized point of the cube; a direction is all a
/// generator needs, not a uniform one).
pub(crate) fn unit() -> impl Strategy<Value = P3> + Clone {
    vec3(1.0).prop_map(|v| normalize_or(v, [0.0, 0.0, 1.0]))
}

/// `m · 2^k` with `m` uniform in `[1, 2)` and `k` uniform in `[lo, hi]`: a
/// magnitude spread evenly over the binades `2^lo … 2^(hi+1)`.
pub(crate) fn magnitude(lo: i32, hi: i32) -> impl Strategy<Value = f64> + Clone {
    (lo..=hi, 1.0..2.0f64).prop_map(|(k, m)| m * pow2(k))
}

/// [`magnitude`] with a random sign.
pub(crate) fn signed_magnitude(lo: i32, hi: i32) -> impl Strategy<Value = f64> + Clone {
    (magnitude(lo, hi), any::<bool>()).prop_map(|(m, neg)| if neg { -m } else { m })
}

/// A ULP step count in `[-8, 8]`, the edge walker's range.
pub(crate) fn ulps() -> impl Strategy<Value = i32> + Clone {
    -8i32..=8
}

/// A multiple of `2^-frac_bits` in `[-lim, lim] · 2^-frac_bits`: exactly
/// representable, and sums and small multiples of such values stay exact.
pub(crate) fn dyadic(lim: i64, frac_bits: i32) -> impl Strategy<Value = f64> + Clone {
    (-lim..=lim).prop_map(move |m| m as f64 * pow2(-frac_bits))
}

/// A point of the grid of multiples of 1/64 in `[-16, 16]³`: sums of such points
/// and small integer multiples of them are exact.
pub(crate) fn grid_point() -> impl Strategy<Value = P3> + Clone {
    prop::array::uniform3(dyadic(1024, 6))
}

/// Integer vectors `(x, y, z)` with integer length `d`: `x² + y² + z² = d²`.
/// Scaled by a dyadic `k`, the vector `k (x, y, z)` has the exact length `k d`,
/// so exact contact can be built in directions other than the axes.
const PYTHAGOREAN: [([f64; 3], f64); 9] = [
    ([1.0, 0.0, 0.0], 1.0),
    ([3.0, 4.0, 0.0], 5.0),
    ([1.0, 2.0, 2.0], 3.0),
    ([2.0, 3.0, 6.0], 7.0),
    ([1.0, 4.0, 8.0], 9.0),
    ([4.0, 4.0, 7.0], 9.0),
    ([2.0, 6.0, 9.0], 11.0),
    ([6.0, 6.0, 7.0], 11.0),
    ([2.0, 10.0, 11.0], 15.0),
];

/// The six permutations of three axes.
const PERMUTATIONS: [[usize; 3]; 6] = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];

/// A signed permutation of the axes: `x'[i] = sign[i] · x[perm[i]]`. Exact, and
/// it maps boxes to boxes, so it moves a canonical construction to any of 48
/// orientations without losing its exactness.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SignedPerm {
    perm: [usize; 3],
    sign: [f64; 3],
}

impl SignedPerm {
    /// Applies the map to a point or vector.
    pub(crate) fn apply(&self, p: P3) -> P3 {
        [0, 1, 2].map(|i| self.sign[i] * p[self.perm[i]])
    }

    /// The output axis that input axis `j` lands on, and its sign.
    pub(crate) fn image_of_axis(&self, j: usize) -> (usize, f64) {
        let i = self.perm.iter().position(|&p| p == j).unwrap_or(j);
        (i, self.sign[i])
    }
}

/// A random [`SignedPerm`].
pub(crate) fn signed_perm() -> impl Strategy<Value = SignedPerm> + Clone {
    (0..6usize, prop::array::uniform3(any::<bool>()))
        .prop_map(|(p, s)| SignedPerm { perm: PERMUTATIONS[p], sign: s.map(|neg| if neg { -1.0 } else { 1.0 }) })
}

/// An integer vector with integer length (`(v, ‖v‖)`), in any of the 48
/// orientations of the table's entries.
pub(crate) fn pythagorean() -> impl Strategy<Value = (P3, f64)> + Clone {
    (0..PYTHAGOREAN.len(), signed_perm()).prop_map(|(i, sp)| {
        let (v, d) = PYTHAGOREAN[i];
        (sp.apply(v), d)
    })
}

/// A Pythagorean pair `(a, b, c)` with `a² + b² = c²` and `a, b ≥ 0`, for exact
/// directions inside a coordinate plane.
pub(crate) fn pythagorean_pair() -> impl Strategy<Value = (f64, f64, f64)> + Clone {
    const PAIRS: [(f64, f64, f64); 8] = [
        (0.0, 1.0, 1.0),
        (1.0, 0.0, 1.0),
        (3.0, 4.0, 5.0),
        (4.0, 3.0, 5.0),
        (5.0, 12.0, 13.0),
        (12.0, 5.0, 13.0),
        (8.0, 15.0, 17.0),
        (15.0, 8.0, 17.0),
    ];
    (0..PAIRS.len()).prop_map(|i| PAIRS[i])
}

/// A rotation (rows of an orthonormal matrix, up to rounding) from two random
/// directions, by Gram–Schmidt. Not exact: a rotated scene's exact relations
/// (touching, on an edge) hold only to rounding, which is what a generic
/// orientation of a near-degenerate scene is for.
pub(crate) fn rotation() -> impl Strategy<Value = [P3; 3]> + Clone {
    (unit(), unit()).prop_map(|(u, w)| {
        let v = normalize_or(sub(w, scale(u, dot(u, w))), perpendicular(u));
        [u, v, cross(u, v)]
    })
}

/// A similarity `x ↦ s · R x + t` applied to whole scenes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Similarity {
    /// Rows of the rotation (or signed permutation) `R`.
    pub rot: [P3; 3],
    /// Scale factor `s > 0`.
    pub scale: f64,
    /// Translation `t`.
    pub shift: P3,
}

impl Similarity {
    /// The identity rotation with scale `s` and shift `t`.
    pub(crate) fn scale_shift(scale: f64, shift: P3) -> Self {
        Self { rot: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], scale, shift }
    }

    /// A signed permutation followed by the shift `t` (exact on exact grids).
    pub(crate) fn perm_shift(sp: &SignedPerm, shift: P3) -> Self {
        let rows = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].map(|e| sp.apply(e));
        // rows above are the images of the axes (columns of R); transpose them.
        let rot = [0, 1, 2].map(|i| [rows[0][i], rows[1][i], rows[2][i]]);
        Self { rot, scale: 1.0, shift }
    }

    /// A rotation followed by the shift `t`.
    pub(crate) fn rotate_shift(rot: [P3; 3], shift: P3) -> Self {
        Self { rot, scale: 1.0, shift }
    }

    fn linear(&self, v: P3) -> P3 {
        [dot(self.rot[0], v), dot(self.rot[1], v), dot(self.rot[2], v)]
    }

    /// The image of a point (`s · R p + t`; a scale of 1 multiplies exactly).
    pub(crate) fn point(&self, p: P3) -> P3 {
        add(scale(self.linear(p), self.scale), self.shift)
    }

    /// The image of a shape. A plane `n · x = d` becomes `n' · x = s d + n' · t`
    /// with `n' = R n` (same length); radii scale by `s`; a box's corners are
    /// mapped and re-sorted per axis, which is its image only when `R` is a signed
    /// permutation (the only maps the box generators use).
    pub(crate) fn shape(&self, shape: &Shape) -> Shape {
        match shape {
            Shape::Sphere(s) => sphere(self.point(s.center), s.radius * self.scale),
            Shape::Plane(p) => {
                let n = self.linear(p.normal);
                plane(n, p.offset * self.scale + dot(n, self.shift))
            }
            Shape::Segment(s) => segment(self.point(s.start), self.point(s.end)),
            Shape::Triangle(t) => triangle(t.vertices.map(|v| self.point(v))),
            Shape::Point(p) => point(self.point(p.at)),
            Shape::Points(p) => points(p.points.iter().map(|&v| self.point(v)).collect()),
            Shape::Aabb(b) => {
                let (lo, hi) = (self.point(b.min), self.point(b.max));
                aabb([0, 1, 2].map(|i| lo[i].min(hi[i])), [0, 1, 2].map(|i| lo[i].max(hi[i])))
            }
            Shape::Mesh(m) => Shape::Mesh(m.clone()),
            Shape::MovingPoint(p) => moving_point(self.point(p.t0), self.point(p.t1)),
            Shape::MovingSegment(s) => moving_segment(s.t0.map(|v| self.point(v)), s.t1.map(|v| self.point(v))),
            Shape::MovingTriangle(t) => moving_triangle(t.t0.map(|v| self.point(v)), t.t1.map(|v| self.point(v))),
            Shape::Box(b) => {
                let q = b.rotation.unwrap_or(crate::case::IDENTITY_ROTATION);
                let half = scale(b.half_extents, self.scale);
                let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
                #[allow(clippy::float_cmp, reason = "exactly the identity keeps the box's own quaternion")]
                let rotation = if self.rot == identity {
                    q
                } else {
                    // A reflection M is −P with P a rotation, and a box is
                    // symmetric about its centre: M·R·u = P·R·(−u) is the
                    // same box turned by P. The product of quaternions is
                    // exact for a signed permutation and an integer q.
                    let m = if det3(self.rot) < 0.0 { self.rot.map(|row| row.map(|x| -x)) } else { self.rot };
                    hamilton(quaternion_of(m), q)
                };
                oriented_box(self.point(b.center), half, rotation)
            }
            Shape::Convex(c) => convex(c.points.iter().map(|&v| self.point(v)).collect()),
            Shape::Capsule(c) => capsule(self.point(c.start), self.point(c.end), c.radius * self.scale),
        }
    }

    /// The image of a scene.
    pub(crate) fn scene(&self, (a, b): &Scene) -> Scene {
        (self.shape(a), b.as_ref().map(|b| self.shape(b)))
    }
}

/// A translation far from the origin: a random direction times `2^k`,
/// `k ∈ [10, 49]` — offsets from about 1e3 up to about 1.1e15.
pub(crate) fn far_shift() -> impl Strategy<Value = P3> + Clone {
    (unit(), magnitude(10, 49)).prop_map(|(u, m)| scale(u, m))
}

/// A scale factor from about 1e-6 to 1e6 (`2^-20 … 2^20`).
pub(crate) fn size_factor() -> impl Strategy<Value = f64> + Clone {
    magnitude(-20, 19)
}

/// The scene moved far from the origin (every coordinate rounds there, so exact
/// relations of the base scene hold only to rounding, at the new scale).
pub(crate) fn far_from_origin(base: SBoxedStrategy<Scene>) -> SBoxedStrategy<Scene> {
    (base, far_shift()).prop_map(|(s, t)| Similarity::scale_shift(1.0, t).scene(&s)).sboxed()
}

/// The scene scaled to tiny or huge size.
pub(crate) fn resized(base: SBoxedStrategy<Scene>) -> SBoxedStrategy<Scene> {
    (base, size_factor()).prop_map(|(s, f)| Similarity::scale_shift(f, [0.0; 3]).scene(&s)).sboxed()
}

/// A non-zero normal of length in `[1/4, 4)` and an offset that puts the plane
/// within `BOX` of the origin.
pub(crate) fn random_plane() -> impl Strategy<Value = (P3, f64)> + Clone {
    (unit(), 0.25..4.0f64, coord(BOX)).prop_map(|(u, len, d)| (scale(u, len), d * len))
}

/// Three vertices in the cube `[-BOX, BOX)³`.
pub(crate) fn random_triangle() -> impl Strategy<Value = [P3; 3]> + Clone {
    prop::array::uniform3(vec3(BOX))
}

/// A triangle in the plane `z = 0` with vertices on the grid of multiples of 1/16
/// in `[-4, 4]²`: its edges and dyadic points on them are exact.
pub(crate) fn flat_grid_triangle() -> impl Strategy<Value = [P3; 3]> + Clone {
    prop::array::uniform3(prop::array::uniform2(dyadic(64, 4))).prop_map(|v| v.map(|[x, y]| [x, y, 0.0]))
}

/// A triangle of exactly zero area: `v0`, `v1` on the 1/64 grid and
/// `v2 = v0 + (v1 − v0) j / 16` (collinear; `j = 0` or 16 repeats a vertex), all
/// exact.
pub(crate) fn zero_area_triangle() -> impl Strategy<Value = [P3; 3]> + Clone {
    (grid_point(), grid_point(), -8..=24i64, any::<bool>()).prop_map(|(v0, v1, j, all_same)| {
        let v1 = if all_same { v0 } else { v1 };
        [v0, v1, add(v0, scale(sub(v1, v0), j as f64 / 16.0))]
    })
}

/// A sliver: a triangle of longest side about `len` and height `aspect · len`
/// (`aspect` from `2^-50 ≈ 1e-15` up to `2^-3`) in a random orientation near the
/// origin; one time in eight a triangle of exactly zero area
/// ([`zero_area_triangle`]) instead.
pub(crate) fn sliver_triangle() -> impl Strategy<Value = [P3; 3]> + Clone {
    ((vec3(BOX / 2.0), unit(), unit(), 0.5..4.0f64, 0.05..0.95f64, magnitude(-50, -3)), zero_area_triangle(), 0..8u8)
        .prop_map(|((v0, e, w, len, along, aspect), flat, pick)| {
            if pick == 0 {
                return flat;
            }
            let f = normalize_or(sub(w, scale(e, dot(e, w))), perpendicular(e));
            let v1 = add(v0, scale(e, len));
            let v2 = add(add(v0, scale(e, along * len)), scale(f, aspect * len));
            [v0, v1, v2]
        })
}

/// A point of the triangle from barycentric weights `(1 − s − t, s, t)`.
pub(crate) fn at_barycentric(v: &[P3; 3], s: f64, t: f64) -> P3 {
    add(v[0], add(scale(sub(v[1], v[0]), s), scale(sub(v[2], v[0]), t)))
}

/// The triangle's unit normal, or `+z` for a zero-area triangle.
pub(crate) fn unit_normal(v: &[P3; 3]) -> P3 {
    let n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
    let len = norm_sqrt_dot(n);
    if len > 0.0 && len.is_finite() { scale(n, 1.0 / len) } else { [0.0, 0.0, 1.0] }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pow2_is_exact_across_the_normal_range() {
        let mut x = 1.0f64;
        for k in 0..=1023 {
            assert_eq!(pow2(k).to_bits(), x.to_bits(), "2^{k}");
            x *= 2.0;
        }
        let mut x = 1.0f64;
        for k in 0..=1022 {
            assert_eq!(pow2(-k).to_bits(), x.to_bits(), "2^-{k}");
            x /= 2.0;
        }
    }

    #[test]
    fn step_ulps_walks_representable_neighbours() {
        assert_eq!(step_ulps(1.0, 1).to_bits(), 1.0f64.next_up().to_bits());
        assert_eq!(step_ulps(1.0, -2).to_bits(), 1.0f64.next_down().next_down().to_bits());
        assert_eq!(step_ulps(1.0, 0).to_bits(), 1.0f64.to_bits());
        assert_eq!(step_ulps(0.0, 1).to_bits(), f64::from_bits(1).to_bits(), "the smallest subnormal");
    }

    #[test]
    fn pythagorean_vectors_have_their_integer_length() {
        for (v, d) in PYTHAGOREAN {
            let sq = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            assert_eq!(sq.to_bits(), (d * d).to_bits(), "{v:?} has length {d}");
        }
    }

    #[test]
    fn a_signed_permutation_as_a_similarity_maps_points_as_itself() {
        let sp = SignedPerm { perm: [2, 0, 1], sign: [-1.0, 1.0, -1.0] };
        let sim = Similarity::perm_shift(&sp, [0.0; 3]);
        let p = [1.0, 2.0, 3.0];
        assert_eq!(sim.point(p).map(f64::to_bits), sp.apply(p).map(f64::to_bits));
        let (axis, sign) = sp.image_of_axis(0);
        assert_eq!((axis, sign.to_bits()), (1, 1.0f64.to_bits()), "x lands on y, positive");
    }

    /// A corner of a box moved by a similarity is the similarity's image of
    /// the corner to a few roundings of the box's size: the rotation matrices
    /// are rounded, each entry within a few ulps of 1.
    const CORNER_TOL: f64 = 64.0 * f64::EPSILON;

    #[test]
    fn a_box_under_a_similarity_is_the_image_of_the_box() {
        let q = [2.0, 0.0, 0.0, 1.0];
        let b = crate::case::BoxSpec {
            center: [1.0, -2.0, 0.5],
            half_extents: [1.0, 2.0, 3.0],
            rotation: Some(q),
            velocity: None,
        };
        let corners = crate::load::box_corners(&b.to_geom());
        let rotations = [
            // A reflection (a signed permutation of determinant −1) and a rotation.
            Similarity::perm_shift(&SignedPerm { perm: [1, 0, 2], sign: [1.0, 1.0, 1.0] }, [3.0, 0.0, -1.0]),
            Similarity::perm_shift(&SignedPerm { perm: [2, 0, 1], sign: [-1.0, 1.0, -1.0] }, [0.0; 3]),
            Similarity::rotate_shift([[0.36, 0.48, -0.8], [-0.8, 0.6, 0.0], [0.48, 0.64, 0.6]], [0.25, 0.5, 1.0]),
        ];
        for sim in rotations {
            let Shape::Box(moved) = sim.shape(&Shape::Box(b.clone())) else { panic!("a box maps to a box") };
            let got = crate::load::box_corners(&moved.to_geom());
            // The same set of corners, in some order.
            for c in corners.map(|c| sim.point(c)) {
                let near = got.iter().any(|g| (0..3).all(|i| (g[i] - c[i]).abs() <= CORNER_TOL * 8.0));
                assert!(near, "corner {c:?} of the image is not a corner of {got:?}");
            }
        }
    }

    #[test]
    fn quaternion_of_inverts_the_rotation_matrix() {
        for q in [[2.0, 0.0, 0.0, 1.0], [1.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0], [1.0, -2.0, 3.0, -1.0]] {
            let r = oracle::geom::rotation_matrix(q);
            let back = oracle::geom::rotation_matrix(quaternion_of(r));
            for i in 0..3 {
                for j in 0..3 {
                    assert!((back[i][j] - r[i][j]).abs() <= CORNER_TOL, "{q:?}: {back:?} vs {r:?}");
                }
            }
        }
    }
}
