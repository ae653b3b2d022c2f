//! Scenes for `distance`: convex hulls, spheres, capsules, boxes, triangles
//! and planes, apart, touching and overlapping.
//!
//! The uniform families place each pair of the table at random in a small
//! box. The biased ones sit where GJK and EPA break: hulls of many points,
//! boxes given as hulls of their corners (the same solid two ways), flat and
//! needle hulls, nearly coplanar points, parallel faces kissing at gaps down
//! to zero, a vertex exactly on a face or a few ulps off it, edges crossing
//! edges, deep penetration, and the same scenes far from the origin and at
//! tiny and huge sizes.
//!
//! **The referee's cost.** Overlapping hulls are decided by the separating
//! axes, whose count is the product of the two hulls' edge counts; hulls of
//! more than [`PENETRATING_POINTS`] points are therefore placed apart, where
//! the exact GJK costs a few passes over the points (`docs/FORMAT.md`,
//! "Distance").

use super::boxes::{random_box, random_capsule, random_quaternion};
use super::build::*;
use super::family::Family;
use crate::case::Shape;
use crashtest_core::vec3::{add, scale, sub};
use oracle::geom::P3;
use proptest::prelude::*;

/// Radii of spheres and capsules.
const RADIUS: std::ops::Range<f64> = 0.05..1.5;

/// The most points of a hull that may overlap its partner (see the module
/// docs).
const PENETRATING_POINTS: usize = 24;

/// The largest hull of the many-points family.
const MOST_POINTS: usize = 1000;

/// `n` points in a ball of radius `spread` about `c`.
fn hull_points(n: std::ops::Range<usize>, spread: f64) -> impl Strategy<Value = Vec<P3>> + Clone {
    (vec3(BOX), prop::collection::vec(vec3(spread), n)).prop_map(|(c, ps)| ps.into_iter().map(|p| add(c, p)).collect())
}

fn random_hull() -> impl Strategy<Value = Shape> + Clone {
    hull_points(4..13, 1.5).prop_map(convex)
}

fn random_sphere() -> impl Strategy<Value = Shape> + Clone {
    (vec3(BOX), RADIUS).prop_map(|(c, r)| sphere(c, r))
}

fn random_plane_shape() -> impl Strategy<Value = Shape> + Clone {
    random_plane().prop_map(|(n, d)| plane(n, d))
}

fn random_triangle_shape() -> impl Strategy<Value = Shape> + Clone {
    random_triangle().prop_map(triangle)
}

fn uniform_sphere_solid() -> SBoxedStrategy<Scene> {
    (
        random_sphere(),
        prop_oneof![
            random_sphere(),
            random_plane_shape(),
            random_triangle_shape(),
            random_box(),
            random_capsule(),
            random_hull()
        ],
    )
        .prop_map(|(a, b)| (a, Some(b)))
        .sboxed()
}

fn uniform_capsule_solid() -> SBoxedStrategy<Scene> {
    (
        random_capsule(),
        prop_oneof![random_capsule(), random_plane_shape(), random_box(), random_triangle_shape(), random_hull()],
    )
        .prop_map(|(a, b)| (a, Some(b)))
        .sboxed()
}

fn uniform_box_solid() -> SBoxedStrategy<Scene> {
    (random_box(), prop_oneof![random_plane_shape(), random_box(), random_triangle_shape()])
        .prop_map(|(a, b)| (a, Some(b)))
        .sboxed()
}

fn uniform_convex_solid() -> SBoxedStrategy<Scene> {
    (random_hull(), prop_oneof![random_hull(), random_plane_shape(), random_box(), random_triangle_shape()])
        .prop_map(|(a, b)| (a, Some(b)))
        .sboxed()
}

/// Hulls of 4 to [`MOST_POINTS`] points (log-uniform counts); past
/// [`PENETRATING_POINTS`] the second is moved clear of the first along a
/// random direction, by their bounding radii and a gap.
fn many_point_hulls() -> SBoxedStrategy<Scene> {
    let count = (2.0f64..(MOST_POINTS as f64).log2()).prop_map(|e| 2f64.powf(e) as usize);
    (count.clone(), count, unit(), 0.0..2.0f64)
        .prop_flat_map(|(n, m, u, gap)| (hull_points(n..n + 1, 1.5), hull_points(m..m + 1, 1.5), Just((u, gap))))
        .prop_map(|(pa, pb, (u, gap))| {
            if pa.len().max(pb.len()) <= PENETRATING_POINTS {
                return (convex(pa), Some(convex(pb)));
            }
            let centre = |ps: &[P3]| scale(ps.iter().fold([0.0; 3], |s, p| add(s, *p)), 1.0 / ps.len() as f64);
            let radius = |ps: &[P3], c: P3| ps.iter().map(|p| norm(sub(*p, c))).fold(0.0, f64::max);
            let (ca, cb) = (centre(&pa), centre(&pb));
            let reach = radius(&pa, ca) + radius(&pb, cb) + gap;
            let shift = sub(add(ca, scale(u, reach)), cb);
            (convex(pa), Some(convex(pb.into_iter().map(|p| add(p, shift)).collect())))
        })
        .sboxed()
}

fn norm(v: P3) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The quarter turns about `z` (the identity and 90°, 180°, 270°): their
/// rotation matrices are exact, so a box's corners are too.
const QUARTER_TURNS: [[f64; 4]; 4] =
    [[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, -1.0]];

/// A box under a quarter turn and its eight corners, exactly.
fn box_and_corners() -> impl Strategy<Value = (Shape, Vec<P3>)> + Clone {
    (grid_point(), prop::array::uniform3(1i32..16), 0..4usize).prop_map(|(c, h, k)| {
        let h = h.map(|x| f64::from(x) / 8.0);
        // A quarter turn about z swaps the x and y extents (and signs).
        let world = if k % 2 == 1 { [h[1], h[0], h[2]] } else { h };
        let corners =
            (0..8).map(|s| [0, 1, 2].map(|i| c[i] + if s >> i & 1 == 1 { world[i] } else { -world[i] })).collect();
        (oriented_box(c, h, QUARTER_TURNS[k]), corners)
    })
}

/// A box given as the hull of its corners, against a box, a sphere, a
/// capsule or that same box: engines see one solid two ways.
fn boxes_as_hulls() -> SBoxedStrategy<Scene> {
    (box_and_corners(), random_box(), prop_oneof![random_sphere(), random_capsule()], 0..3usize)
        .prop_map(|((bx, corners), other_box, round, which)| match which {
            0 => (convex(corners), Some(bx)),
            1 => (convex(corners), Some(other_box)),
            // The table puts spheres and capsules first.
            _ => (round, Some(convex(corners))),
        })
        .sboxed()
}

/// Flat hulls (points in one plane) and needles (points on one line), with
/// repeats, against a hull or a box.
fn flat_and_needle_hulls() -> SBoxedStrategy<Scene> {
    (
        prop::collection::vec((dyadic(16, 3), dyadic(16, 3)), 3..10),
        grid_point(),
        any::<bool>(),
        prop_oneof![random_hull(), random_box()],
    )
        .prop_map(|(uv, c, needle, other)| {
            let pts =
                uv.iter().map(|&(u, v)| if needle { add(c, [u, u / 2.0, 0.0]) } else { add(c, [u, v, 0.0]) }).collect();
            (convex(pts), Some(other))
        })
        .sboxed()
}

/// Points on a plane, each moved off it by a few ulps: a hull whose faces
/// are nearly coplanar.
fn nearly_coplanar() -> SBoxedStrategy<Scene> {
    (prop::collection::vec((dyadic(16, 3), dyadic(16, 3), ulps()), 4..12), 0.5..3.0f64, random_box())
        .prop_map(|(uvk, z, other)| {
            let pts = uvk.iter().map(|&(u, v, k)| [u, v, step_ulps(z, k)]).collect();
            (convex(pts), Some(other))
        })
        .sboxed()
}

/// Two hull cubes with parallel faces at gap `2^−k` (k up to 60), exactly 0,
/// or overlapping by `2^−k`; their cross-sections offset.
fn kissing_faces() -> SBoxedStrategy<Scene> {
    (grid_point(), 1i32..16, 1i32..16, (0i32..61), -1i32..=1, prop::array::uniform2(-8i32..8))
        .prop_map(|(c, ha, hb, k, sign, off)| {
            let (ha, hb) = (f64::from(ha) / 8.0, f64::from(hb) / 8.0);
            let gap = f64::from(sign) * pow2(-k);
            let cube = |c: P3, h: f64| -> Vec<P3> {
                (0..8).map(|s| [0, 1, 2].map(|i| c[i] + if s >> i & 1 == 1 { h } else { -h })).collect()
            };
            let cb = c;
            let ca = [c[0] + f64::from(off[0]) / 16.0, c[1] + f64::from(off[1]) / 16.0, c[2] + ha + hb + gap];
            (convex(cube(ca, ha)), Some(convex(cube(cb, hb))))
        })
        .sboxed()
}

/// A tetrahedron whose apex is on a box's (or a hull cube's) top face, or a
/// few ulps above or below it.
fn vertex_on_face() -> SBoxedStrategy<Scene> {
    (grid_point(), prop::array::uniform2(-7i32..8), 1i32..16, ulps(), any::<bool>(), 0.25..2.0f64)
        .prop_map(|(c, uv, h, k, as_box, spread)| {
            let h = f64::from(h) / 8.0;
            let top = step_ulps(c[2] + h, k);
            let apex = [c[0] + f64::from(uv[0]) * h / 8.0, c[1] + f64::from(uv[1]) * h / 8.0, top];
            let up = |dx: f64, dy: f64| [apex[0] + dx, apex[1] + dy, apex[2] + spread];
            let tet = vec![apex, up(-1.0, -1.0), up(1.0, -1.0), up(0.0, 1.0)];
            let b = if as_box {
                oriented_box(c, [h; 3], [1.0, 0.0, 0.0, 0.0])
            } else {
                convex((0..8).map(|s| [0, 1, 2].map(|i| c[i] + if s >> i & 1 == 1 { h } else { -h })).collect())
            };
            (convex(tet), Some(b))
        })
        .sboxed()
}

/// Two needle hulls (segments) crossing at right angles or at a 3-4-5 angle,
/// at an exact gap, 0, or a few ulps.
fn edge_crossing_edge() -> SBoxedStrategy<Scene> {
    (grid_point(), prop_oneof![Just(0.0), (0i32..40).prop_map(|k| pow2(-k))], any::<bool>(), ulps(), 1i32..16)
        .prop_map(|(c, gap, pythagorean, k, len)| {
            let len = f64::from(len) / 4.0;
            let dir = if pythagorean { [0.6 * len, 0.8 * len, 0.0] } else { [0.0, len, 0.0] };
            let a = vec![sub(c, [len, 0.0, 0.0]), add(c, [len, 0.0, 0.0])];
            let z = step_ulps(c[2] + gap, k);
            let cb = [c[0], c[1], z];
            let b = vec![sub(cb, dir), add(cb, dir), cb];
            (convex(b), Some(convex(a)))
        })
        .sboxed()
}

/// A hull deep inside a box or another hull: the penetration is the nearest
/// face's distance, far larger than the hull.
fn deep_penetration() -> SBoxedStrategy<Scene> {
    (hull_points(4..10, 0.25), vec3(1.0), prop::array::uniform3(1.5..4.0f64), any::<bool>(), random_quaternion())
        .prop_map(|(pts, c, h, as_box, q)| {
            let centre = pts[0];
            let other = if as_box {
                oriented_box(add(centre, scale(c, 0.5)), h, q)
            } else {
                let big: Vec<P3> = (0..8)
                    .map(|s| [0, 1, 2].map(|i| centre[i] + c[i] * 0.5 + if s >> i & 1 == 1 { h[i] } else { -h[i] }))
                    .collect();
                convex(big)
            };
            (convex(pts), Some(other))
        })
        .sboxed()
}

/// Every scene of the families above but the many-point hulls, for the
/// moved and resized variants.
fn base() -> SBoxedStrategy<Scene> {
    prop_oneof![
        uniform_sphere_solid(),
        uniform_capsule_solid(),
        uniform_box_solid(),
        uniform_convex_solid(),
        boxes_as_hulls(),
        flat_and_needle_hulls(),
        // Nested: `prop_oneof!` of more than ten is a union that is not `Sync`.
        prop_oneof![nearly_coplanar(), kissing_faces(), vertex_on_face(), edge_crossing_edge(), deep_penetration()]
            .sboxed(),
    ]
    .sboxed()
}

/// The full-range scene: a base scene scaled by a power of two from `2^−1000`
/// to `2^1000` and moved off the origin by up to `2^40` of its size.
pub(super) fn full_range_scene() -> SBoxedStrategy<Scene> {
    (base(), magnitude(-1000, 1000), unit(), magnitude(-8, 40))
        .prop_map(|(s, f, u, off)| Similarity::scale_shift(f, scale(u, off * f)).scene(&s))
        .sboxed()
}

pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform("uniform sphere–solid", uniform_sphere_solid),
        Family::uniform("uniform capsule–solid", uniform_capsule_solid),
        Family::uniform("uniform box–solid", uniform_box_solid),
        Family::uniform("uniform convex–solid", uniform_convex_solid),
        Family::biased("hulls of 4 to 1,000 points", many_point_hulls),
        Family::biased("boxes given as hulls of their corners", boxes_as_hulls),
        Family::biased("flat and needle hulls", flat_and_needle_hulls),
        Family::biased("nearly coplanar points", nearly_coplanar),
        Family::biased("parallel faces kissing at gaps to 0", kissing_faces),
        Family::biased("vertex on a face ± k ulps", vertex_on_face),
        Family::biased("edge crossing an edge", edge_crossing_edge),
        Family::biased("deep penetration", deep_penetration),
        Family::biased("distance far from the origin", || far_from_origin(base())),
        Family::biased("distance at tiny and huge sizes", || resized(base())),
    ]
}
