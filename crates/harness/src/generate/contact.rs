//! `contact` scenes: sphere against sphere, plane or triangle, in both orders.
//!
//! The uniform families place shapes at random in a small box. The biased ones
//! sit where contact methods break: exactly touching (built exactly: dyadic
//! centres along axes or Pythagorean directions, so the gap is exactly 0),
//! grazing (the gap a tiny fraction of the radii), near-concentric spheres (no
//! direction to speak of), centres on or near a triangle's plane and near the
//! borders of its edge and vertex regions, slivers, far from the origin, tiny
//! and huge, and an edge walker that steps a few ULPs either side of exact touching.

use super::build::*;
use super::family::Family;
use crashtest_core::vec3::{add, dot, norm_sqrt_dot, scale, sub};
use oracle::geom::P3;
use proptest::prelude::*;

/// Radii of uniform scenes: comparable to the box, so contact is common.
const RADIUS: std::ops::Range<f64> = 0.05..BOX;

fn uniform_sphere_sphere() -> SBoxedStrategy<Scene> {
    (vec3(BOX), RADIUS, vec3(BOX), RADIUS).prop_map(|(ca, ra, cb, rb)| (sphere(ca, ra), Some(sphere(cb, rb)))).sboxed()
}

fn uniform_sphere_plane() -> SBoxedStrategy<Scene> {
    (vec3(BOX), RADIUS, random_plane()).prop_map(|(c, r, (n, d))| (sphere(c, r), Some(plane(n, d)))).sboxed()
}

fn uniform_plane_sphere() -> SBoxedStrategy<Scene> {
    uniform_sphere_plane().prop_map(swap).sboxed()
}

fn uniform_sphere_triangle() -> SBoxedStrategy<Scene> {
    (vec3(BOX), RADIUS, random_triangle()).prop_map(|(c, r, v)| (sphere(c, r), Some(triangle(v)))).sboxed()
}

fn uniform_triangle_sphere() -> SBoxedStrategy<Scene> {
    uniform_sphere_triangle().prop_map(swap).sboxed()
}

/// `(a, b)` → `(b, a)`.
fn swap((a, b): Scene) -> Scene {
    match b {
        Some(b) => (b, Some(a)),
        None => (a, None),
    }
}

/// `(a, b)`, or `(b, a)` when `flip`.
fn order(scene: Scene, flip: bool) -> Scene {
    if flip { swap(scene) } else { scene }
}

/// Two spheres touching exactly: `cb` on the 1/64 grid, `ca = cb + k v` with `v` a
/// Pythagorean vector of integer length `d` and `k` a multiple of 1/64, radii
/// `ra = j k d / 16` and `rb = k d − ra`. Every value is a short dyadic, so
/// `‖ca − cb‖ = k d = ra + rb` holds exactly in the inputs.
fn touching_spheres() -> SBoxedStrategy<Scene> {
    (grid_point(), pythagorean(), 1..=256i64, 1..=15i64)
        .prop_map(|(cb, (v, d), k, j)| {
            let k = k as f64 / 64.0;
            let total = k * d;
            let ra = total * j as f64 / 16.0;
            (sphere(add(cb, scale(v, k)), ra), Some(sphere(cb, total - ra)))
        })
        .sboxed()
}

/// Spheres whose centre distance is `(ra + rb)(1 + g)`, `|g|` from `2^-60` to
/// `2^-3`, either side of touching.
fn grazing_spheres() -> SBoxedStrategy<Scene> {
    (vec3(BOX), unit(), RADIUS, RADIUS, signed_magnitude(-60, -3))
        .prop_map(|(cb, u, ra, rb, g)| {
            let dist = (ra + rb) * (1.0 + g);
            (sphere(add(cb, scale(u, dist)), ra), Some(sphere(cb, rb)))
        })
        .sboxed()
}

/// Centres `rb · m` apart with `m` from `2^-60` to 1, and exactly concentric one
/// time in eight (the degenerate case).
fn near_concentric_spheres() -> SBoxedStrategy<Scene> {
    (vec3(BOX), unit(), RADIUS, RADIUS, magnitude(-60, 0), 0..8u8)
        .prop_map(|(cb, u, ra, rb, m, pick)| {
            let ca = if pick == 0 { cb } else { add(cb, scale(u, rb * m)) };
            (sphere(ca, ra), Some(sphere(cb, rb)))
        })
        .sboxed()
}

/// A sphere touching a plane exactly: the plane's normal is `s v` (`v`
/// Pythagorean, `s` ∈ {1/2, 1, 2, 3}) through the grid point `q`, so
/// `offset = s v · q` is exact; the centre is `q + k v` and the radius `k ‖v‖`.
/// Either order.
fn touching_sphere_plane() -> SBoxedStrategy<Scene> {
    (grid_point(), pythagorean(), 1..=256i64, 0..4usize, any::<bool>())
        .prop_map(|(q, (v, d), k, s, flip)| {
            let s = [0.5, 1.0, 2.0, 3.0][s];
            let k = k as f64 / 64.0;
            let n = scale(v, s);
            order((sphere(add(q, scale(v, k)), k * d), Some(plane(n, dot(n, q)))), flip)
        })
        .sboxed()
}

/// A sphere whose centre is `r (1 + g)` above a random plane, `|g|` from `2^-60`
/// to `2^-3`. Either order.
fn grazing_sphere_plane() -> SBoxedStrategy<Scene> {
    (random_plane(), vec3(BOX), RADIUS, signed_magnitude(-60, -3), any::<bool>())
        .prop_map(|((n, d), w, r, g, flip)| {
            let len = norm_sqrt_dot(n);
            let u = scale(n, 1.0 / len);
            // The foot: the plane's point nearest the origin, moved in the plane.
            let foot = add(scale(u, d / len), sub(w, scale(u, dot(u, w))));
            let c = add(foot, scale(u, r * (1.0 + g)));
            order((sphere(c, r), Some(plane(n, d))), flip)
        })
        .sboxed()
}

/// Which feature of a triangle a constructed contact is at.
#[derive(Clone, Copy, Debug)]
enum Feature {
    Face,
    Edge,
    Vertex,
}

/// A canonical triangle in `z = 0` and a point `q` on the given feature, all
/// exact (short dyadics):
///
/// - face: any grid triangle, `q` the convex combination of its vertices with
///   weights `(16 − i − j, i, j) / 16`, all positive;
/// - edge: `v0 = (x0, 0, 0)`, `v1 = (x0 + len, 0, 0)`, `v2` above `y = 0`, `q` a
///   dyadic point strictly inside the edge `v0 v1`; the edge's region lies at
///   `y < 0`, and its border with the face's region is the plane `y = 0`;
/// - vertex: `v0` at the origin, `v1 = (len, 0, 0)`, `v2` in the open first
///   quadrant, `q = v0`; the vertex's region is `{w : w · v1 ≤ 0, w · v2 ≤ 0}`,
///   and its border with edge `v0 v1`'s region is the plane `x = 0`.
fn canonical_feature(features: &'static [Feature]) -> impl Strategy<Value = (Feature, [P3; 3], P3)> + Clone {
    let grid = || dyadic(64, 4);
    let positive = || (1..=64i64).prop_map(|m| m as f64 / 16.0);
    (
        prop::sample::select(features),
        flat_grid_triangle(),
        (grid(), positive(), positive(), positive()),
        (1..=15i64, 1..=14i64),
    )
        .prop_map(move |(f, tri, (x0, len, x2, y2), (i, j))| match f {
            Feature::Face => {
                let i = i.min(15 - j);
                (f, tri, at_barycentric(&tri, i as f64 / 16.0, j as f64 / 16.0))
            }
            Feature::Edge => {
                let v = [[x0, 0.0, 0.0], [x0 + len, 0.0, 0.0], [x0 + x2 - 2.0, y2, 0.0]];
                (f, v, [x0 + len * i as f64 / 16.0, 0.0, 0.0])
            }
            Feature::Vertex => (f, [[0.0; 3], [len, 0.0, 0.0], [x2 * i as f64 / 16.0, y2, 0.0]], [0.0; 3]),
        })
}

/// Every feature of [`canonical_feature`].
const ALL_FEATURES: &[Feature] = &[Feature::Face, Feature::Edge, Feature::Vertex];

/// A sphere touching a triangle exactly at its face, an edge or a vertex: the
/// canonical construction, the centre `q + k w` with `w` an integer vector of
/// integer length pointing into the feature's region (`(0, 0, ±1)` for the face;
/// `(0, −a, ±b)` with `a² + b² = c²` for the edge; `(−|x|, −|y|, ±|z|)` of a
/// Pythagorean vector for the vertex), radius `k ‖w‖`; then an exact signed
/// permutation and a shift on the 1/64 grid. Either order.
fn touching_sphere_triangle() -> SBoxedStrategy<Scene> {
    (
        canonical_feature(ALL_FEATURES),
        (pythagorean_pair(), pythagorean()),
        (1..=256i64, any::<bool>()),
        signed_perm(),
        grid_point(),
        any::<bool>(),
    )
        .prop_map(|((f, tri, q), ((a, b, c), (v, d)), (k, down), sp, shift, flip)| {
            let k = k as f64 / 64.0;
            let z = if down { -1.0 } else { 1.0 };
            let (w, len) = match f {
                Feature::Face => ([0.0, 0.0, z], 1.0),
                Feature::Edge => ([0.0, -a, z * b], c),
                Feature::Vertex => ([-v[0].abs(), -v[1].abs(), z * v[2].abs()], d),
            };
            let scene = (sphere(add(q, scale(w, k)), k * len), Some(triangle(tri)));
            order(Similarity::perm_shift(&sp, shift).scene(&scene), flip)
        })
        .sboxed()
}

/// A sphere whose centre is near the border of an edge's or a vertex's region:
/// the canonical edge or vertex, the centre at height `h` (from `2^-4` to 4) above
/// the plane and `δ h` across the border (`|δ|` from `2^-57` to `2^-3`, either
/// side: in the face's or the edge's region by a hair, or just out of it), radius
/// `‖c − q‖ (1 + g)` with `|g|` from `2^-55` to `2^-2`; then a random rotation
/// and shift, so the border is in no special position. Either order.
fn sphere_near_triangle_border() -> SBoxedStrategy<Scene> {
    (
        canonical_feature(&[Feature::Edge, Feature::Vertex]),
        (magnitude(-4, 1), signed_magnitude(-57, -3), signed_magnitude(-55, -2)),
        rotation(),
        vec3(BOX),
        any::<bool>(),
    )
        .prop_map(|((f, tri, q), (h, delta, g), rot, shift, flip)| {
            let c = match f {
                Feature::Vertex => [delta * h, -h / 2.0, h],
                _ => [q[0], delta * h, h],
            };
            let r = norm_sqrt_dot(sub(c, q)) * (1.0 + g);
            let scene = (sphere(c, r), Some(triangle(tri)));
            order(Similarity::rotate_shift(rot, shift).scene(&scene), flip)
        })
        .sboxed()
}

/// A centre on a triangle's plane or a height `h` off it (`|h|` from `2^-60` to
/// 2, or exactly 0 one time in four). Exactly on: the canonical grid triangle in
/// `z = 0` and a dyadic centre in that plane — one time in two strictly inside
/// the triangle (weights `(16 − i − j, i, j) / 16`, all positive: the degenerate
/// case, no direction to push along), else anywhere in the plane — moved by a
/// signed permutation and a grid shift. Off: a random triangle, the centre at
/// barycentric `(1 − s − t, s, t)`, `s, t ∈ [−1/2, 3/2)`, plus `h` along the
/// normal.
fn centre_on_or_near_plane() -> SBoxedStrategy<Scene> {
    (
        (
            flat_grid_triangle(),
            prop::array::uniform2(dyadic(96, 4)),
            (1..=14i64, 1..=14i64, any::<bool>()),
            signed_perm(),
            grid_point(),
        ),
        (random_triangle(), -0.5..1.5f64, -0.5..1.5f64, signed_magnitude(-60, 1)),
        (RADIUS, 0..4u8, any::<bool>()),
    )
        .prop_map(|((gt, [x, y], (i, j, inside), sp, shift), (rt, s, t, h), (r, pick, flip))| {
            let scene = if pick == 0 {
                let c = if inside {
                    let i = i.min(15 - j);
                    at_barycentric(&gt, i as f64 / 16.0, j as f64 / 16.0)
                } else {
                    [x, y, 0.0]
                };
                let scene = (sphere(c, r), Some(triangle(gt)));
                Similarity::perm_shift(&sp, shift).scene(&scene)
            } else {
                let c = add(at_barycentric(&rt, s, t), scale(unit_normal(&rt), h));
                (sphere(c, r), Some(triangle(rt)))
            };
            order(scene, flip)
        })
        .sboxed()
}

/// A sphere against a sliver (height down to `2^-50` of the length, or zero).
fn sphere_and_sliver() -> SBoxedStrategy<Scene> {
    (sliver_triangle(), vec3(BOX / 2.0), RADIUS, any::<bool>())
        .prop_map(|(v, c, r, flip)| order((sphere(c, r), Some(triangle(v))), flip))
        .sboxed()
}

/// What the far and resized families move: the uniform and the exactly touching
/// scenes.
fn moved_base() -> SBoxedStrategy<Scene> {
    prop_oneof![
        uniform_sphere_sphere(),
        uniform_sphere_plane(),
        uniform_plane_sphere(),
        uniform_sphere_triangle(),
        uniform_triangle_sphere(),
        touching_spheres(),
        touching_sphere_plane(),
        touching_sphere_triangle(),
    ]
    .sboxed()
}

/// Spheres touching exactly along a coordinate axis (`cb` on the grid,
/// `ca = cb ± (ra + rb) e_i`, radii multiples of 1/64), then one coordinate of
/// `ca` along that axis, or one radius, stepped `k ∈ [-8, 8]` ULPs.
fn walk_touching_spheres() -> SBoxedStrategy<Scene> {
    (grid_point(), (1..=256i64, 1..=256i64), (0..3usize, any::<bool>()), ulps(), any::<bool>())
        .prop_map(|(cb, (ra, rb), (axis, neg), k, radius)| {
            let (mut ra, rb) = (ra as f64 / 64.0, rb as f64 / 64.0);
            let mut ca = cb;
            ca[axis] += if neg { -(ra + rb) } else { ra + rb };
            if radius {
                ra = step_ulps(ra, k);
            } else {
                ca[axis] = step_ulps(ca[axis], k);
            }
            (sphere(ca, ra), Some(sphere(cb, rb)))
        })
        .sboxed()
}

/// A sphere touching an axis plane exactly (normal `s e_i`, `s` a small dyadic of
/// either sign, offset `s z0`, centre `z0 + r` along the axis), then the centre's
/// coordinate stepped `k ∈ [-8, 8]` ULPs. Either order.
fn walk_touching_sphere_plane() -> SBoxedStrategy<Scene> {
    (grid_point(), 1..=256i64, (0..3usize, dyadic(12, 2)), ulps(), any::<bool>())
        .prop_map(|(q, r, (axis, s), k, flip)| {
            let r = r as f64 / 64.0;
            let s = if s == 0.0 { 1.0 } else { s };
            let mut n = [0.0; 3];
            n[axis] = s;
            let mut c = q;
            // The outside of n·x ≤ s q_i is the side n points to.
            c[axis] = step_ulps(q[axis] + r.copysign(s), k);
            order((sphere(c, r), Some(plane(n, s * q[axis]))), flip)
        })
        .sboxed()
}

/// The contact families: uniform first, then biased.
pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform("uniform sphere–sphere", uniform_sphere_sphere),
        Family::uniform("uniform sphere–plane", uniform_sphere_plane),
        Family::uniform("uniform plane–sphere", uniform_plane_sphere),
        Family::uniform("uniform sphere–triangle", uniform_sphere_triangle),
        Family::uniform("uniform triangle–sphere", uniform_triangle_sphere),
        Family::biased("exactly touching spheres", touching_spheres),
        Family::biased("grazing spheres", grazing_spheres),
        Family::biased("near-concentric spheres", near_concentric_spheres),
        Family::biased("sphere exactly touching a plane", touching_sphere_plane),
        Family::biased("sphere grazing a plane", grazing_sphere_plane),
        Family::biased("sphere exactly touching a triangle's face, edge or vertex", touching_sphere_triangle),
        Family::biased("sphere near the border of a triangle's edge or vertex region", sphere_near_triangle_border),
        Family::biased("sphere centre on or near a triangle's plane", centre_on_or_near_plane),
        Family::biased("sphere and sliver triangle", sphere_and_sliver),
        Family::biased("contact far from the origin", || far_from_origin(moved_base())),
        Family::biased("contact at tiny and huge sizes", || resized(moved_base())),
        Family::biased("edge walker: touching spheres ± k ulps", walk_touching_spheres),
        Family::biased("edge walker: sphere touching a plane ± k ulps", walk_touching_sphere_plane),
    ]
}
