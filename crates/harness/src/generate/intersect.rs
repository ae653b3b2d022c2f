//! `intersect` scenes: a segment against a plane or a triangle.
//!
//! The uniform families place both at random in a small box. The biased ones sit
//! where intersection methods break: near-parallel segments (angles from about
//! 1e-1 down to 1e-16, and exactly parallel or coplanar), endpoints on or near
//! the surface, crossings near a triangle's edges and vertices (by distances
//! from about 1e-1 down to 1e-17, and exactly on them), slivers, far from the
//! origin, tiny and huge, and an edge walker that steps an endpoint on the plane,
//! or a segment through an edge, `k ∈ [-8, 8]` ULPs either way.

use super::build::*;
use super::family::Family;
use crashtest_core::vec3::{add, cross, dot, norm_sqrt_dot, scale, sub};
use oracle::geom::P3;
use proptest::prelude::*;

fn uniform_segment_plane() -> SBoxedStrategy<Scene> {
    (vec3(BOX), vec3(BOX), random_plane()).prop_map(|(p0, p1, (n, d))| (segment(p0, p1), Some(plane(n, d)))).sboxed()
}

fn uniform_segment_triangle() -> SBoxedStrategy<Scene> {
    (vec3(BOX), vec3(BOX), random_triangle()).prop_map(|(p0, p1, v)| (segment(p0, p1), Some(triangle(v)))).sboxed()
}

/// A direction at a small angle `θ` to a surface with unit normal `u`: a unit
/// in-plane vector `e` (from `w`) plus `θ u`.
fn tilted(u: P3, w: P3, theta: f64) -> P3 {
    let e = normalize_or(sub(w, scale(u, dot(u, w))), perpendicular(u));
    add(e, scale(u, theta))
}

/// The segment of length `len` along `d` that passes through `x` at parameter
/// `tau` (so it crosses there when `tau ∈ [0, 1]`, and misses otherwise).
fn through(x: P3, d: P3, len: f64, tau: f64) -> (P3, P3) {
    let p0 = sub(x, scale(d, len * tau));
    (p0, add(p0, scale(d, len)))
}

/// The angle of a near-parallel segment: `|θ|` from `2^-54 ≈ 6e-17` to `2^-3`.
fn angle() -> impl Strategy<Value = f64> + Clone {
    signed_magnitude(-54, -3)
}

/// Where along a near-parallel segment the surface is met: mostly inside
/// `[0, 1]`, sometimes beyond either end.
const TAU: std::ops::Range<f64> = -0.25..1.25;

/// An exactly parallel segment: both endpoints at the same height `z0 + dz` over
/// the plane `z = z0` (normal `s e_i`), `dz = 0` (coplanar) one time in three.
fn exactly_parallel_to_plane() -> impl Strategy<Value = Scene> + Clone {
    (grid_point(), grid_point(), (0..3usize, dyadic(12, 2), dyadic(64, 4)), 0..3u8).prop_map(
        |(p0, p1, (axis, s, dz), pick)| {
            let s = if s == 0.0 { 1.0 } else { s };
            let (mut p0, mut p1) = (p0, p1);
            let z0 = p0[axis];
            let height = if pick == 0 { z0 } else { z0 + dz };
            p0[axis] = height;
            p1[axis] = height;
            let mut n = [0.0; 3];
            n[axis] = s;
            (segment(p0, p1), Some(plane(n, s * z0)))
        },
    )
}

/// A segment at a small angle to a random plane, through a point of the plane at
/// parameter `τ`; one time in eight exactly parallel or coplanar instead.
fn near_parallel_plane() -> SBoxedStrategy<Scene> {
    (random_plane(), vec3(BOX), unit(), angle(), 0.1..8.0f64, TAU, exactly_parallel_to_plane(), 0..8u8)
        .prop_map(|((n, d), w, dir, theta, len, tau, exact, pick)| {
            if pick == 0 {
                return exact;
            }
            let u = scale(n, 1.0 / norm_sqrt_dot(n));
            let foot = add(scale(u, d / norm_sqrt_dot(n)), sub(w, scale(u, dot(u, w))));
            let (p0, p1) = through(foot, tilted(u, dir, theta), len, tau);
            (segment(p0, p1), Some(plane(n, d)))
        })
        .sboxed()
}

/// A segment at a small angle to a random triangle, through a point of its plane
/// at barycentric `(1 − s − t, s, t)` (`s, t ∈ [−1/4, 5/4)`: inside or near) at
/// parameter `τ`; one time in eight exactly parallel to a grid triangle in
/// `z = 0` (coplanar one time in three), moved by a signed permutation.
fn near_parallel_triangle() -> SBoxedStrategy<Scene> {
    (
        (random_triangle(), -0.25..1.25f64, -0.25..1.25f64, unit(), angle(), 0.1..8.0f64, TAU),
        (flat_grid_triangle(), prop::array::uniform2(prop::array::uniform2(dyadic(96, 4))), dyadic(64, 4), 0..3u8),
        (signed_perm(), grid_point(), 0..8u8),
    )
        .prop_map(|((v, s, t, dir, theta, len, tau), (gt, [a, b], dz, cop), (sp, shift, pick))| {
            if pick == 0 {
                let z = if cop == 0 { 0.0 } else { dz };
                let scene = (segment([a[0], a[1], z], [b[0], b[1], z]), Some(triangle(gt)));
                return Similarity::perm_shift(&sp, shift).scene(&scene);
            }
            let x = at_barycentric(&v, s, t);
            let (p0, p1) = through(x, tilted(unit_normal(&v), dir, theta), len, tau);
            (segment(p0, p1), Some(triangle(v)))
        })
        .sboxed()
}

/// An integer vector perpendicular to `v` (its cross product with the axis of
/// `v`'s smallest component, never zero for a non-zero integer `v`).
fn integer_perpendicular(v: P3) -> P3 {
    let i = (0..3).min_by(|&i, &j| v[i].abs().total_cmp(&v[j].abs())).unwrap_or(0);
    let mut e = [0.0; 3];
    e[i] = 1.0;
    cross(v, e)
}

/// One endpoint exactly on a plane, or `h` off it (`|h|` from `2^-60` to `2^-2`),
/// the other anywhere in the box. The plane's normal is `s v` (`v` Pythagorean)
/// through the grid point `q`, offset `s v · q`, and the endpoint is `q` plus a
/// dyadic multiple of an integer vector perpendicular to `v`: exactly on the
/// plane. Either endpoint.
fn endpoint_on_or_near_plane() -> SBoxedStrategy<Scene> {
    (
        grid_point(),
        pythagorean(),
        (dyadic(64, 4), 0..4usize),
        vec3(BOX),
        (signed_magnitude(-60, -2), 0..4u8),
        any::<bool>(),
    )
        .prop_map(|(q, (v, d), (k, s), other, (h, pick), flip)| {
            let s = [0.5, 1.0, 2.0, 3.0][s];
            let n = scale(v, s);
            let on = add(q, scale(integer_perpendicular(v), k));
            let end = if pick == 0 { on } else { add(on, scale(v, h / d)) };
            let (p0, p1) = if flip { (other, end) } else { (end, other) };
            (segment(p0, p1), Some(plane(n, dot(n, q))))
        })
        .sboxed()
}

/// A segment through a point near an edge or a vertex of a grid triangle in
/// `z = 0`: the point on the feature exactly (a dyadic point of an edge, or a
/// vertex), moved in the plane by `|δ|` from `2^-57` to `2^-3` (exactly not at
/// all one time in four); the segment `X + σ0 D … X − σ1 D` with `D` a dyadic
/// direction out of the plane, so `X` is exactly on it. Then either an exact
/// signed permutation and grid shift, or (one time in four) a random rotation.
fn crossing_near_edge_or_vertex() -> SBoxedStrategy<Scene> {
    (
        (flat_grid_triangle(), 0..3usize, 0..=16i64),
        (unit(), signed_magnitude(-57, -3), 0..4u8),
        (prop::array::uniform2(dyadic(64, 4)), (1..=64i64).prop_map(|m| m as f64 / 16.0), any::<bool>()),
        ((1..=64i64, 1..=64i64), signed_perm(), grid_point(), (rotation(), 0..4u8)),
    )
        .prop_map(|((v, edge, j), (w, delta, exact), ([dx, dy], dz, down), ((s0, s1), sp, shift, (rot, rotate)))| {
            // j = 0 or 16 is a vertex, else a point inside the edge.
            let (a, b) = (v[edge], v[(edge + 1) % 3]);
            let x = add(a, scale(sub(b, a), j as f64 / 16.0));
            let x = if exact == 0 { x } else { add(x, scale(normalize_or([w[0], w[1], 0.0], [1.0, 0.0, 0.0]), delta)) };
            let dir = [dx, dy, if down { -dz } else { dz }];
            let p0 = add(x, scale(dir, s0 as f64 / 16.0));
            let p1 = sub(x, scale(dir, s1 as f64 / 16.0));
            let scene = (segment(p0, p1), Some(triangle(v)));
            if rotate == 0 {
                Similarity::rotate_shift(rot, shift).scene(&scene)
            } else {
                Similarity::perm_shift(&sp, shift).scene(&scene)
            }
        })
        .sboxed()
}

/// A segment against a sliver (height down to `2^-50` of the length, or zero),
/// through a point of the sliver's plane near it.
fn segment_and_sliver() -> SBoxedStrategy<Scene> {
    (sliver_triangle(), -0.25..1.25f64, -0.25..1.25f64, unit(), 0.1..8.0f64, 0.0..1.0f64)
        .prop_map(|(v, s, t, d, len, tau)| {
            let (p0, p1) = through(at_barycentric(&v, s, t), d, len, tau);
            (segment(p0, p1), Some(triangle(v)))
        })
        .sboxed()
}

/// What the far and resized families move.
fn moved_base() -> SBoxedStrategy<Scene> {
    prop_oneof![
        uniform_segment_plane(),
        uniform_segment_triangle(),
        near_parallel_plane(),
        near_parallel_triangle(),
        endpoint_on_or_near_plane(),
        crossing_near_edge_or_vertex(),
    ]
    .sboxed()
}

/// A segment with one endpoint exactly on an axis plane (normal `s e_i`, `s` a
/// small non-zero dyadic, offset `s z0`), the other a dyadic distance to either
/// side; then that endpoint's coordinate along the axis stepped `k ∈ [-8, 8]`
/// ULPs. Either endpoint.
fn walk_endpoint_on_plane() -> SBoxedStrategy<Scene> {
    (grid_point(), grid_point(), (0..3usize, dyadic(12, 2)), (dyadic(256, 4), ulps()), any::<bool>())
        .prop_map(|(e, f, (axis, s), (dz, k), flip)| {
            let s = if s == 0.0 { 1.0 } else { s };
            let z0 = e[axis];
            let (mut e, mut f) = (e, f);
            e[axis] = step_ulps(z0, k);
            f[axis] = z0 + if dz == 0.0 { 1.0 } else { dz };
            let mut n = [0.0; 3];
            n[axis] = s;
            let (p0, p1) = if flip { (f, e) } else { (e, f) };
            (segment(p0, p1), Some(plane(n, s * z0)))
        })
        .sboxed()
}

/// A segment crossing exactly through an edge: the canonical edge `v0 v1` on the
/// line `y = y0, z = 0`, `v2` above it; the segment runs from height `+a` to `−b`
/// in the plane `y = y0` at `x` strictly inside the edge. After an exact signed
/// permutation and grid shift, both endpoints' coordinate along the image of the
/// `y` axis is stepped `k ∈ [-8, 8]` ULPs: into the triangle, or out of it.
fn walk_through_edge() -> SBoxedStrategy<Scene> {
    (
        (dyadic(64, 4), dyadic(64, 4), (1..=64i64, 1..=64i64, 1..=15i64)),
        (dyadic(64, 4), (1..=64i64, 1..=64i64)),
        (signed_perm(), grid_point(), ulps()),
    )
        .prop_map(|((x0, y0, (len, hgt, i)), (x2, (a, b)), (sp, shift, k))| {
            let (len, hgt) = (len as f64 / 16.0, hgt as f64 / 16.0);
            let v = [[x0, y0, 0.0], [x0 + len, y0, 0.0], [x2, y0 + hgt, 0.0]];
            let x = x0 + len * i as f64 / 16.0;
            let scene = (segment([x, y0, a as f64 / 16.0], [x, y0, -(b as f64) / 16.0]), Some(triangle(v)));
            let (seg, tri) = Similarity::perm_shift(&sp, shift).scene(&scene);
            let (axis, _) = sp.image_of_axis(1);
            let seg = match seg {
                crate::case::Shape::Segment(mut s) => {
                    s.start[axis] = step_ulps(s.start[axis], k);
                    s.end[axis] = step_ulps(s.end[axis], k);
                    crate::case::Shape::Segment(s)
                }
                other => other,
            };
            (seg, tri)
        })
        .sboxed()
}

/// The intersect families: uniform first, then biased.
pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform("uniform segment–plane", uniform_segment_plane),
        Family::uniform("uniform segment–triangle", uniform_segment_triangle),
        Family::biased("near-parallel segment and plane", near_parallel_plane),
        Family::biased("near-parallel segment and triangle", near_parallel_triangle),
        Family::biased("segment endpoint on or near a plane", endpoint_on_or_near_plane),
        Family::biased("segment crossing near a triangle's edge or vertex", crossing_near_edge_or_vertex),
        Family::biased("segment and sliver triangle", segment_and_sliver),
        Family::biased("intersect far from the origin", || far_from_origin(moved_base())),
        Family::biased("intersect at tiny and huge sizes", || resized(moved_base())),
        Family::biased("edge walker: segment endpoint on a plane ± k ulps", walk_endpoint_on_plane),
        Family::biased("edge walker: segment through a triangle's edge ± k ulps", walk_through_edge),
    ]
}
