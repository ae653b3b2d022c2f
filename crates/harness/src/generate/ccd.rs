//! `ccd` scenes: a point moving against a moving triangle (vertex–face) and two
//! moving segments (edge–edge), every position moving linearly from its place
//! at time 0 to its place at time 1.
//!
//! The uniform families place everything at random in a small box and move it
//! by up to the box's size, so impacts and misses are both common. The biased
//! ones sit where CCD methods break: impacts built exactly (short dyadic
//! inputs, the point reaching a dyadic point of the triangle, inside or exactly
//! on an edge or a vertex, at a dyadic time `t*`, so the coplanarity cubic has
//! the exact root `t*`); coplanar motion (every position in one plane: the
//! cubic is identically zero); parallel and collinear edges; touching exactly
//! at `t = 0` and at `t = t_max`; zero-area triangles and zero-length edges;
//! far from the origin; tiny and huge sizes.

use super::build::*;
use super::family::{Family, Params, Posed};
use crashtest_core::vec3::{add, scale, sub};
use oracle::geom::P3;
use proptest::prelude::*;

/// How far a uniform scene's positions move over `[0, 1]`, per component.
const MOTION: f64 = 4.0;

/// `t_max` for a posed family: the default (1) half the time, else a dyadic in
/// `(0, 1)` or exactly 0.
fn t_max() -> impl Strategy<Value = Option<f64>> + Clone {
    prop_oneof![
        2 => Just(None),
        1 => (1..16i64).prop_map(|k| Some(k as f64 / 16.0)),
        1 => Just(Some(0.0)),
    ]
}

fn posed(scene: Scene, t_max: Option<f64>) -> Posed {
    (scene, Params { t_max, restitution: None })
}

fn uniform_vertex_face() -> SBoxedStrategy<Posed> {
    (vec3(BOX), vec3(MOTION), random_triangle(), prop::array::uniform3(vec3(MOTION)), t_max())
        .prop_map(|(p0, dp, v0, dv, tm)| {
            let v1 = [0, 1, 2].map(|i| add(v0[i], dv[i]));
            posed((moving_point(p0, add(p0, dp)), Some(moving_triangle(v0, v1))), tm)
        })
        .sboxed()
}

fn uniform_edge_edge() -> SBoxedStrategy<Posed> {
    (prop::array::uniform4(vec3(BOX)), prop::array::uniform4(vec3(MOTION)), t_max())
        .prop_map(|(e, d, tm)| {
            let a = moving_segment([e[0], e[1]], [add(e[0], d[0]), add(e[1], d[1])]);
            let b = moving_segment([e[2], e[3]], [add(e[2], d[2]), add(e[3], d[3])]);
            posed((a, Some(b)), tm)
        })
        .sboxed()
}

/// A dyadic time in `[0, 1]`, multiples of 1/16.
fn dyadic_time() -> impl Strategy<Value = f64> + Clone {
    (0..=16i64).prop_map(|k| k as f64 / 16.0)
}

/// Barycentric weights `(s, u)` in multiples of 1/8 with `s, u ≥ 0`, `s + u ≤ 1`;
/// `boundary` puts the point on an edge or a vertex.
fn weights(boundary: bool) -> impl Strategy<Value = (f64, f64)> + Clone {
    (0..=8i64, 0..=8i64, 0..3usize).prop_map(move |(i, j, side)| {
        let (i, j) = if i + j > 8 { (8 - i, 8 - j) } else { (i, j) };
        let (s, u) = (i as f64 / 8.0, j as f64 / 8.0);
        if !boundary {
            return (s, u);
        }
        match side {
            0 => (0.0, u),
            1 => (s, 0.0),
            _ => (s, 1.0 - s),
        }
    })
}

/// A grid displacement: multiples of 1/16 in `[-4, 4]`.
fn grid_motion() -> impl Strategy<Value = P3> + Clone {
    prop::array::uniform3(dyadic(64, 4))
}

/// The point reaches the triangle's dyadic point `(s, u)` at the dyadic time
/// `t*`: the triangle translates by `d`, the point moves by `w`; with grid
/// inputs every position is exact, so the cubic has the exact root `t*` (an
/// earlier impact, if the motion makes one, is the referee's to find).
fn exact_vertex_face(boundary: bool) -> SBoxedStrategy<Posed> {
    (prop::array::uniform3(grid_point()), weights(boundary), grid_motion(), grid_motion(), dyadic_time(), t_max())
        .prop_map(|(v0, (s, u), d, w, ts, tm)| {
            let q = at_barycentric(&v0, s, u);
            let p0 = sub(add(q, scale(d, ts)), scale(w, ts));
            let v1 = v0.map(|v| add(v, d));
            posed((moving_point(p0, add(p0, w)), Some(moving_triangle(v0, v1))), tm)
        })
        .sboxed()
}

/// Two grid edges that cross at the dyadic time `t*`: edge `b` translates by
/// `d`, edge `a` by `w`, positioned so that their points at parameters `s` and
/// `u` (multiples of 1/8; 0 and 1 give an endpoint) meet at `t*`.
fn exact_edge_edge() -> SBoxedStrategy<Posed> {
    (prop::array::uniform4(grid_point()), (0..=8i64, 0..=8i64), grid_motion(), grid_motion(), dyadic_time(), t_max())
        .prop_map(|(e, (i, j), d, w, ts, tm)| {
            let (s, u) = (i as f64 / 8.0, j as f64 / 8.0);
            let on = |p: P3, q: P3, f: f64| add(p, scale(sub(q, p), f));
            // b's point at u, at time t*.
            let meet = add(on(e[2], e[3], u), scale(d, ts));
            // a placed at t* so that its point at s is `meet`.
            let a_at = sub(meet, on(e[0], e[1], s));
            let a0 = [add(e[0], sub(a_at, scale(w, ts))), add(e[1], sub(a_at, scale(w, ts)))];
            let a = moving_segment(a0, a0.map(|p| add(p, w)));
            let b = moving_segment([e[2], e[3]], [add(e[2], d), add(e[3], d)]);
            posed((a, Some(b)), tm)
        })
        .sboxed()
}

/// Every position in the plane `z = 0`: the coplanarity cubic is identically
/// zero and the problem is planar.
fn coplanar() -> SBoxedStrategy<Posed> {
    let flat = || prop::array::uniform2(dyadic(64, 4)).prop_map(|[x, y]| [x, y, 0.0]);
    (prop::array::uniform4(flat()), prop::array::uniform4(flat()), any::<bool>(), t_max())
        .prop_map(|(s, e, vf, tm)| {
            if vf {
                let tri = moving_triangle([s[1], s[2], s[3]], [e[1], e[2], e[3]]);
                posed((moving_point(s[0], e[0]), Some(tri)), tm)
            } else {
                posed(
                    (moving_segment([s[0], s[1]], [e[0], e[1]]), Some(moving_segment([s[2], s[3]], [e[2], e[3]]))),
                    tm,
                )
            }
        })
        .sboxed()
}

/// Parallel edges (the same direction, possibly scaled or reversed) and
/// collinear ones, sliding along or toward each other.
fn parallel_edges() -> SBoxedStrategy<Posed> {
    (grid_point(), grid_motion(), grid_point(), (-4..=4i64), grid_motion(), grid_motion(), any::<bool>(), t_max())
        .prop_map(|(a0, dir, b0, k, wa, wb, collinear, tm)| {
            let f = if k == 0 { 0.5 } else { k as f64 / 2.0 };
            let b0 = if collinear { add(a0, scale(dir, 0.75)) } else { b0 };
            let a = [a0, add(a0, dir)];
            let b = [b0, add(b0, scale(dir, f))];
            // Collinear edges stay on one line when b's motion is a's plus a
            // step along the line; parallel ones move freely.
            let wb = if collinear { add(wa, scale(dir, 0.25)) } else { wb };
            posed((moving_segment(a, a.map(|p| add(p, wa))), Some(moving_segment(b, b.map(|p| add(p, wb))))), tm)
        })
        .sboxed()
}

/// Touching exactly at `t = 0` (the point on the triangle, edges crossing), or
/// exactly at `t = t_max`.
fn touching_at_ends() -> SBoxedStrategy<Posed> {
    (prop::array::uniform3(grid_point()), weights(false), grid_motion(), grid_motion(), any::<bool>(), 1..=16i64)
        .prop_map(|(v0, (s, u), d, w, at_start, k)| {
            let tm = k as f64 / 16.0;
            let ts = if at_start { 0.0 } else { tm };
            let q = at_barycentric(&v0, s, u);
            let p0 = sub(add(q, scale(d, ts)), scale(w, ts));
            let v1 = v0.map(|v| add(v, d));
            posed((moving_point(p0, add(p0, w)), Some(moving_triangle(v0, v1))), if k == 16 { None } else { Some(tm) })
        })
        .sboxed()
}

/// A zero-area triangle (collinear or coincident vertices) or a zero-length
/// edge, crossed by a moving point or edge.
fn zero_size() -> SBoxedStrategy<Posed> {
    (zero_area_triangle(), grid_motion(), vec3(BOX), vec3(MOTION), any::<bool>(), t_max())
        .prop_map(|(v0, d, p0, dp, vf, tm)| {
            let v1 = v0.map(|v| add(v, d));
            if vf {
                posed((moving_point(p0, add(p0, dp)), Some(moving_triangle(v0, v1))), tm)
            } else {
                // An edge of zero length (the triangle's first vertex twice)
                // against the triangle's first edge.
                let a = moving_segment([v0[0], v0[0]], [v1[0], v1[0]]);
                posed((moving_segment([p0, v0[1]], [add(p0, dp), v1[1]]), Some(a)), tm)
            }
        })
        .sboxed()
}

fn far() -> SBoxedStrategy<Posed> {
    (prop_oneof![exact_vertex_face(false), exact_edge_edge(), uniform_vertex_face()], far_shift())
        .prop_map(|((s, p), t)| (Similarity::scale_shift(1.0, t).scene(&s), p))
        .sboxed()
}

fn resized_scene() -> SBoxedStrategy<Posed> {
    (prop_oneof![exact_vertex_face(true), exact_edge_edge(), uniform_edge_edge()], size_factor())
        .prop_map(|((s, p), f)| (Similarity::scale_shift(f, [0.0; 3]).scene(&s), p))
        .sboxed()
}

/// For the full-range family: an exactly built impact (or a uniform scene)
/// scaled by `2^k`, `k ∈ [−1000, 1000]`, and moved off the origin by up to
/// `2^40` times its own size, so that its coordinates span most of f64's range
/// and round where they land.
pub(super) fn full_range_scene() -> SBoxedStrategy<Posed> {
    (
        prop_oneof![exact_vertex_face(false), exact_vertex_face(true), exact_edge_edge(), uniform_vertex_face()],
        magnitude(-1000, 1000),
        unit(),
        magnitude(-8, 40),
    )
        .prop_map(|((s, p), f, u, off)| (Similarity::scale_shift(f, scale(u, off * f)).scene(&s), p))
        .sboxed()
}

pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform_posed("uniform vertex–face", uniform_vertex_face),
        Family::uniform_posed("uniform edge–edge", uniform_edge_edge),
        Family::biased_posed("impact built exactly: a point through a face", || exact_vertex_face(false)),
        Family::biased_posed("impact built exactly: a point through an edge or a vertex", || exact_vertex_face(true)),
        Family::biased_posed("impact built exactly: edges crossing, ends included", exact_edge_edge),
        Family::biased_posed("coplanar motion", coplanar),
        Family::biased_posed("parallel and collinear edges", parallel_edges),
        Family::biased_posed("touching exactly at t = 0 or at t_max", touching_at_ends),
        Family::biased_posed("zero-area triangles and zero-length edges", zero_size),
        Family::biased_posed("ccd far from the origin", far),
        Family::biased_posed("ccd at tiny and huge sizes", resized_scene),
    ]
}
