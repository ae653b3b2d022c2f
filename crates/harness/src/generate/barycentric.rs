//! `barycentric` scenes: a point and a triangle.
//!
//! The uniform family places both at random in a small box. The biased ones sit
//! where barycentric methods break: points on and near edges and vertices,
//! points exactly in the triangle's plane and off it (the format asks for the
//! projection's coordinates), slivers down to an aspect ratio of 1e-15 and
//! triangles of exactly zero area (degenerate), far from the origin, tiny and
//! huge, and an edge walker stepping a point on an edge `k ∈ [-8, 8]` ULPs.

use super::build::*;
use super::family::Family;
use crashtest_core::vec3::{add, scale, sub};
use proptest::prelude::*;

fn uniform_point_triangle() -> SBoxedStrategy<Scene> {
    (vec3(BOX), random_triangle()).prop_map(|(p, v)| (point(p), Some(triangle(v)))).sboxed()
}

/// A point on an edge or a vertex of a grid triangle in `z = 0` (exactly: a
/// dyadic point of the edge), moved in the plane by `|δ|` from `2^-57` to `2^-3`
/// three times in four, and lifted off the plane by `h` (`|h|` from `2^-20` to 4)
/// one time in two; then an exact signed permutation and grid shift, or (one time
/// in four) a random rotation.
fn near_edge_or_vertex() -> SBoxedStrategy<Scene> {
    (
        (flat_grid_triangle(), 0..3usize, 0..=16i64),
        (unit(), signed_magnitude(-57, -3), 0..4u8),
        (signed_magnitude(-20, 2), any::<bool>()),
        (signed_perm(), grid_point(), rotation(), 0..4u8),
    )
        .prop_map(|((v, edge, j), (w, delta, exact), (h, lift), (sp, shift, rot, rotate))| {
            let (a, b) = (v[edge], v[(edge + 1) % 3]);
            let x = add(a, scale(sub(b, a), j as f64 / 16.0));
            let x = if exact == 0 { x } else { add(x, scale(normalize_or([w[0], w[1], 0.0], [1.0, 0.0, 0.0]), delta)) };
            let x = if lift { [x[0], x[1], h] } else { x };
            let scene = (point(x), Some(triangle(v)));
            if rotate == 0 {
                Similarity::rotate_shift(rot, shift).scene(&scene)
            } else {
                Similarity::perm_shift(&sp, shift).scene(&scene)
            }
        })
        .sboxed()
}

/// A triangle with vertices on the 1/64 grid in any orientation, and the point
/// at barycentric `(1 − s − t, s, t)` with `s, t` multiples of 1/32 in
/// `[−1/2, 3/2]`: exactly in the triangle's plane (every product and sum is exact).
/// One time in two it is lifted off the plane along the unit normal by `h`
/// (`|h|` from `2^-40` to 8).
fn in_and_off_plane() -> SBoxedStrategy<Scene> {
    (prop::array::uniform3(grid_point()), dyadic(32, 4), dyadic(32, 4), signed_magnitude(-40, 2), any::<bool>())
        .prop_map(|(v, s, t, h, lift)| {
            let (s, t) = (s / 2.0 + 0.5, t / 2.0 + 0.5);
            let x = at_barycentric(&v, s, t);
            let x = if lift { add(x, scale(unit_normal(&v), h)) } else { x };
            (point(x), Some(triangle(v)))
        })
        .sboxed()
}

/// A point near a sliver (height down to `2^-50` of the length, or zero area),
/// at barycentric `(1 − s − t, s, t)`, `s, t ∈ [−1/4, 5/4)`, in its plane or
/// lifted off it.
fn point_and_sliver() -> SBoxedStrategy<Scene> {
    (sliver_triangle(), -0.25..1.25f64, -0.25..1.25f64, signed_magnitude(-30, 1), any::<bool>())
        .prop_map(|(v, s, t, h, lift)| {
            let x = at_barycentric(&v, s, t);
            let x = if lift { add(x, scale(unit_normal(&v), h)) } else { x };
            (point(x), Some(triangle(v)))
        })
        .sboxed()
}

/// A point and a triangle of exactly zero area (collinear or repeated vertices):
/// the degenerate case.
fn zero_area() -> SBoxedStrategy<Scene> {
    (vec3(BOX), zero_area_triangle()).prop_map(|(p, v)| (point(p), Some(triangle(v)))).sboxed()
}

/// What the far and resized families move.
fn moved_base() -> SBoxedStrategy<Scene> {
    prop_oneof![uniform_point_triangle(), near_edge_or_vertex(), in_and_off_plane()].sboxed()
}

/// A point exactly on an edge: the canonical edge on the line `y = y0, z = 0`,
/// the point at `(x, y0, h)` with `x` strictly inside the edge and `h` zero (one
/// time in two) or a dyadic height; after an exact signed permutation and grid
/// shift, its coordinate along the image of the `y` axis is stepped
/// `k ∈ [-8, 8]` ULPs.
fn walk_point_on_edge() -> SBoxedStrategy<Scene> {
    (
        (dyadic(64, 4), dyadic(64, 4), (1..=64i64, 1..=64i64, 1..=15i64)),
        (dyadic(64, 4), dyadic(64, 4), any::<bool>()),
        (signed_perm(), grid_point(), ulps()),
    )
        .prop_map(|((x0, y0, (len, hgt, i)), (x2, h, lift), (sp, shift, k))| {
            let (len, hgt) = (len as f64 / 16.0, hgt as f64 / 16.0);
            let v = [[x0, y0, 0.0], [x0 + len, y0, 0.0], [x2, y0 + hgt, 0.0]];
            let p = [x0 + len * i as f64 / 16.0, y0, if lift { h } else { 0.0 }];
            let sim = Similarity::perm_shift(&sp, shift);
            let mut p = sim.point(p);
            let (axis, _) = sp.image_of_axis(1);
            p[axis] = step_ulps(p[axis], k);
            (point(p), Some(sim.shape(&triangle(v))))
        })
        .sboxed()
}

/// The barycentric families: uniform first, then biased.
pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform("uniform point and triangle", uniform_point_triangle),
        Family::biased("point on or near a triangle's edge or vertex", near_edge_or_vertex),
        Family::biased("point exactly in and off the triangle's plane", in_and_off_plane),
        Family::biased("point and sliver triangle", point_and_sliver),
        Family::biased("point and zero-area triangle", zero_area),
        Family::biased("barycentric far from the origin", || far_from_origin(moved_base())),
        Family::biased("barycentric at tiny and huge sizes", || resized(moved_base())),
        Family::biased("edge walker: point on an edge ± k ulps", walk_point_on_edge),
    ]
}
