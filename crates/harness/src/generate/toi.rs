//! `toi` scenes: a sphere moving linearly against a sphere, a plane, a triangle
//! or a small mesh, each possibly moving too, over `[0, t_max]`.
//!
//! The uniform families place and move everything at random in a small box
//! (displacements over the interval of the box's size, so hits and misses are
//! both common). The biased ones sit where time-of-impact methods break:
//! impacts built exactly (short dyadic inputs, the touching time a dyadic
//! `t*` with the sphere approaching, so the referee's answer is exactly `t*`) at
//! a face, an edge or a vertex; impacts exactly at `t_max` and a few ULPs
//! either side of it (an edge walker on the interval's end); grazing passes at
//! a closest approach `R (1 ± g)`, `|g|` from `2^-60` to `2^-3`; near-parallel
//! approaches to a plane; shapes already touching or overlapping at `t = 0`;
//! tunneling (a small fast sphere through a thin target within one interval,
//! clear of it at the end); no relative motion, receding and sideways motion;
//! small meshes hit at their vertices and edges; far from the origin; tiny and
//! huge sizes.

use super::build::*;
use super::family::{Family, Params, Posed};
use crate::case::{MeshSpec, Shape};
use crashtest_core::vec3::{add, dot, norm_sqrt_dot, scale, sub};
use oracle::geom::P3;
use proptest::prelude::*;

/// Radii of uniform scenes.
const RADIUS: std::ops::Range<f64> = 0.05..2.0;

/// Velocity components of uniform scenes: over the default interval `[0, 1]`
/// a shape moves up to about twice the box's half-width.
const SPEED: f64 = 8.0;

/// `shape` moving at `v` (spheres, planes, triangles, meshes and boxes move; other
/// shapes are returned as they are).
pub(super) fn moving(shape: Shape, v: P3) -> Shape {
    match shape {
        Shape::Sphere(mut s) => {
            s.velocity = Some(v);
            Shape::Sphere(s)
        }
        Shape::Plane(mut p) => {
            p.velocity = Some(v);
            Shape::Plane(p)
        }
        Shape::Triangle(mut t) => {
            t.velocity = Some(v);
            Shape::Triangle(t)
        }
        Shape::Mesh(mut m) => {
            m.velocity = Some(v);
            Shape::Mesh(m)
        }
        Shape::Box(mut b) => {
            b.velocity = Some(v);
            Shape::Box(b)
        }
        other => other,
    }
}

/// The velocity a shape carries, if any.
fn velocity_of(shape: &Shape) -> Option<P3> {
    match shape {
        Shape::Sphere(s) => s.velocity,
        Shape::Plane(p) => p.velocity,
        Shape::Triangle(t) => t.velocity,
        Shape::Mesh(m) => m.velocity,
        Shape::Box(b) => b.velocity,
        _ => None,
    }
}

/// An inline mesh.
fn mesh(vertices: Vec<P3>, triangles: Vec<[usize; 3]>) -> Shape {
    Shape::Mesh(MeshSpec { vertices: Some(vertices), triangles: Some(triangles), file: None, velocity: None })
}

/// A `toi` scene: `a` moving at `va`, `b` at `vb`, over `[0, t_max]`.
fn posed(a: Shape, va: P3, b: Shape, vb: P3, t_max: Option<f64>) -> Posed {
    ((moving(a, va), Some(moving(b, vb))), Params { t_max, restitution: None })
}

/// The interval's end: the format's default (1) half the time, else from 1/4 to 4.
fn t_max() -> impl Strategy<Value = Option<f64>> + Clone {
    prop_oneof![Just(None), (0.25..4.0f64).prop_map(Some)]
}

/// A velocity of a uniform scene.
fn velocity() -> impl Strategy<Value = P3> + Clone {
    vec3(SPEED)
}

/// The image of a moving scene under a similarity: positions and shapes as
/// [`Similarity::scene`] maps them (meshes too: their inline vertices), and
/// velocities rotated and scaled with them (`v' = s R v`), so every time is
/// unchanged.
fn transformed(sim: &Similarity, ((a, b), p): &Posed) -> Posed {
    let map = |shape: &Shape| -> Shape {
        let moved = match shape {
            Shape::Mesh(m) => Shape::Mesh(MeshSpec {
                vertices: m.vertices.as_ref().map(|vs| vs.iter().map(|&x| sim.point(x)).collect()),
                ..m.clone()
            }),
            other => sim.shape(other),
        };
        match velocity_of(shape) {
            Some(u) => moving(moved, scale([dot(sim.rot[0], u), dot(sim.rot[1], u), dot(sim.rot[2], u)], sim.scale)),
            None => moved,
        }
    };
    ((map(a), b.as_ref().map(map)), *p)
}

// ------------------------------------------------------------------ uniform

fn uniform_sphere_sphere() -> SBoxedStrategy<Posed> {
    (vec3(BOX), RADIUS, velocity(), vec3(BOX), RADIUS, velocity(), t_max())
        .prop_map(|(ca, ra, va, cb, rb, vb, tm)| posed(sphere(ca, ra), va, sphere(cb, rb), vb, tm))
        .sboxed()
}

fn uniform_sphere_plane() -> SBoxedStrategy<Posed> {
    (vec3(BOX), RADIUS, velocity(), random_plane(), velocity(), t_max())
        .prop_map(|(c, r, va, (n, d), vb, tm)| posed(sphere(c, r), va, plane(n, d), vb, tm))
        .sboxed()
}

fn uniform_sphere_triangle() -> SBoxedStrategy<Posed> {
    (vec3(BOX), RADIUS, velocity(), random_triangle(), velocity(), t_max())
        .prop_map(|(c, r, va, v, vb, tm)| posed(sphere(c, r), va, triangle(v), vb, tm))
        .sboxed()
}

/// The faces of an octahedron with vertices `+x, −x, +y, −y, +z, −z` (in that
/// order), oriented outward.
const OCTAHEDRON: [[usize; 3]; 8] =
    [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];

/// The faces of a tetrahedron, oriented outward when its fourth vertex is on
/// the positive side of the first three's plane.
const TETRAHEDRON: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

/// A small closed mesh near the origin: an octahedron around a random centre
/// with half-axes from 1/4 to 2, or a random tetrahedron (its faces oriented as
/// the table says, whatever the vertices' order: a mesh is two-sided).
fn small_mesh() -> impl Strategy<Value = Shape> + Clone {
    let octahedron = (vec3(BOX / 2.0), prop::array::uniform6(0.25..2.0f64)).prop_map(|(c, s)| {
        let mut vs = Vec::with_capacity(6);
        for k in 0..3 {
            for (j, sign) in [1.0, -1.0].into_iter().enumerate() {
                let mut p = c;
                p[k] += sign * s[2 * k + j];
                vs.push(p);
            }
        }
        mesh(vs, OCTAHEDRON.to_vec())
    });
    let tetrahedron = prop::array::uniform4(vec3(BOX / 2.0)).prop_map(|v| mesh(v.to_vec(), TETRAHEDRON.to_vec()));
    prop_oneof![octahedron, tetrahedron]
}

fn uniform_sphere_mesh() -> SBoxedStrategy<Posed> {
    (vec3(BOX), RADIUS, velocity(), small_mesh(), velocity(), t_max())
        .prop_map(|(c, r, va, m, vb, tm)| posed(sphere(c, r), va, m, vb, tm))
        .sboxed()
}

// ------------------------------------------------------ exact constructions

/// A dyadic velocity: components multiples of 1/8 in `[-8, 8]`.
fn dyadic_velocity() -> impl Strategy<Value = P3> + Clone {
    prop::array::uniform3(dyadic(64, 3))
}

/// A relative velocity that approaches along `−w` (`v · w < 0`), dyadic: `v`
/// itself, `−v`, or `−w` when `v` is perpendicular to `w`.
fn approaching(v: P3, w: P3) -> P3 {
    let d = dot(v, w);
    if d < 0.0 {
        v
    } else if d > 0.0 {
        scale(v, -1.0)
    } else {
        scale(w, -1.0)
    }
}

/// The impact time `t*` of an exact construction: a multiple of 1/16 in
/// `(0, 2]`.
fn impact_time() -> impl Strategy<Value = f64> + Clone {
    (1..=32i64).prop_map(|m| m as f64 / 16.0)
}

/// Where the interval ends against an exact impact at `t*`: exactly at `t*` one
/// time in four, after it (by a multiple of 1/16 up to 2) one time in two,
/// before it (the impact comes too late: no impact) one time in four.
fn end_around(t_star: f64, pick: u8, m: i64) -> f64 {
    match pick {
        0 => t_star,
        1 => (t_star - m as f64 / 64.0).max(0.0),
        _ => t_star + m as f64 / 16.0,
    }
}

/// Two spheres touching exactly at `t*`: `cb` on the 1/64 grid moving at a
/// dyadic `vb`; at `t*` the centres differ by `k w` (`w` Pythagorean of
/// integer length `d`, `k` a multiple of 1/64), the radii sum to `k d`; the
/// relative velocity is dyadic and approaches along `w`, so `t*` is the first
/// touch. Every input is a short dyadic: the referee's `t` is exactly `t*`.
fn exact_spheres() -> impl Strategy<Value = (Posed, f64)> + Clone {
    (
        (grid_point(), pythagorean(), 1..=256i64, 1..=15i64),
        (dyadic_velocity(), dyadic_velocity(), impact_time()),
        (0..4u8, 1..=32i64),
    )
        .prop_map(|((cb, (w, d), k, j), (vb, v, ts), (pick, m))| {
            let k = k as f64 / 64.0;
            let total = k * d;
            let ra = total * j as f64 / 16.0;
            let v = approaching(v, w);
            let va = add(vb, v);
            // a's centre at t*: cb + vb t* + k w; at 0: that minus va t*.
            let ca = sub(add(add(cb, scale(vb, ts)), scale(w, k)), scale(va, ts));
            (posed(sphere(ca, ra), va, sphere(cb, total - ra), vb, Some(end_around(ts, pick, m))), ts)
        })
}

/// A sphere touching a plane exactly at `t*`: the plane's normal `s w` (`w`
/// Pythagorean, `s ∈ {1/2, 1, 2, 3}`) through the grid point `q`, moving at a
/// dyadic `vb`; the sphere of radius `k d` centred at `q + vb t* + k w` at `t*`,
/// approaching along `−w`. Exact as [`exact_spheres`].
fn exact_sphere_plane() -> impl Strategy<Value = (Posed, f64)> + Clone {
    (
        (grid_point(), pythagorean(), 1..=256i64, 0..4usize),
        (dyadic_velocity(), dyadic_velocity(), impact_time()),
        (0..4u8, 1..=32i64),
    )
        .prop_map(|((q, (w, d), k, s), (vb, v, ts), (pick, m))| {
            let s = [0.5, 1.0, 2.0, 3.0][s];
            let k = k as f64 / 64.0;
            let n = scale(w, s);
            let va = add(vb, approaching(v, w));
            let c = sub(add(add(q, scale(vb, ts)), scale(w, k)), scale(va, ts));
            let scene = posed(sphere(c, k * d), va, plane(n, dot(n, q)), vb, Some(end_around(ts, pick, m)));
            (scene, ts)
        })
}

/// Which feature of a triangle an exact impact is at.
#[derive(Clone, Copy, Debug)]
enum Feature {
    Face,
    Edge,
    Vertex,
}

/// A sphere touching a triangle exactly at `t*` at its face, an edge or a
/// vertex. The triangle in `z = 0`: `v0 = (x0, y0, 0)`, `v1 = v0 + (len, 0, 0)`,
/// `v2 = v0 + (x2, y2, 0)` with `x2 ≥ 0`, `y2 > 0` (area > 0), all on the 1/16
/// grid. The touching point `q` and the outward direction `w` into the
/// feature's region: the face — `q` at weights `(16 − i − j, i, j)/16`,
/// `w = (0, 0, ±1)`; the edge `v0 v1` — `q` strictly inside it,
/// `w = (0, −a, ±b)` with `a² + b² = c²`; the vertex `v0` — `w` a Pythagorean
/// vector turned to `(−|x|, −|y|, ±|z|)`, inside the vertex's region since
/// `x2 ≥ 0`. At `t*` the centre is `q + vb t* + k w`, the radius `k ‖w‖`, the
/// relative velocity dyadic and approaching along `−w`. Then an exact signed
/// permutation and grid shift (velocities permuted too).
fn exact_sphere_triangle() -> impl Strategy<Value = (Posed, f64)> + Clone {
    (
        (
            prop::sample::select(&[Feature::Face, Feature::Edge, Feature::Vertex][..]),
            (dyadic(64, 4), dyadic(64, 4)),
            ((1..=64i64), (0..=64i64), (1..=64i64)),
            (1..=14i64, 1..=14i64),
        ),
        ((pythagorean_pair(), pythagorean()), 1..=256i64, any::<bool>()),
        (dyadic_velocity(), dyadic_velocity(), impact_time()),
        (signed_perm(), grid_point(), 0..4u8, 1..=32i64),
    )
        .prop_map(
            |(
                (f, (x0, y0), (len, x2, y2), (i, j)),
                (((a, b, c), (pv, d)), k, down),
                (vb, v, ts),
                (sp, shift, pick, m),
            )| {
                let (len, x2, y2) = (len as f64 / 16.0, x2 as f64 / 16.0, y2 as f64 / 16.0);
                let v0 = [x0, y0, 0.0];
                let tri = [v0, add(v0, [len, 0.0, 0.0]), add(v0, [x2, y2, 0.0])];
                let z = if down { -1.0 } else { 1.0 };
                let (q, w, wl) = match f {
                    Feature::Face => {
                        let i = i.min(15 - j);
                        (at_barycentric(&tri, i as f64 / 16.0, j as f64 / 16.0), [0.0, 0.0, z], 1.0)
                    }
                    Feature::Edge => (add(v0, [len * i as f64 / 16.0, 0.0, 0.0]), [0.0, -a, z * b], c),
                    Feature::Vertex => (v0, [-pv[0].abs(), -pv[1].abs(), z * pv[2].abs()], d),
                };
                let k = k as f64 / 64.0;
                let va = add(vb, approaching(v, w));
                let c0 = sub(add(add(q, scale(vb, ts)), scale(w, k)), scale(va, ts));
                let scene = posed(sphere(c0, k * wl), va, triangle(tri), vb, Some(end_around(ts, pick, m)));
                (transformed(&Similarity::perm_shift(&sp, shift), &scene), ts)
            },
        )
}

fn exact_impacts() -> SBoxedStrategy<Posed> {
    prop_oneof![exact_spheres(), exact_sphere_plane(), exact_sphere_triangle(), exact_sphere_box()]
        .prop_map(|(s, _)| s)
        .sboxed()
}

/// An exact impact (sphere, plane or triangle) with the interval ending exactly
/// at the impact and then stepped `k ∈ [-8, 8]` ULPs: a touch at the very end,
/// or one a few ULPs too late.
fn walk_t_max() -> SBoxedStrategy<Posed> {
    (prop_oneof![exact_spheres(), exact_sphere_plane(), exact_sphere_triangle(), exact_sphere_box()], ulps())
        .prop_map(|(((shapes, p), ts), k)| (shapes, Params { t_max: Some(step_ulps(ts, k)), ..p }))
        .sboxed()
}

// ---------------------------------------------------------------- grazing

/// A sphere passing another at a closest approach `(ra + rb)(1 + g)`, `|g|`
/// from `2^-60` to `2^-3` either side: it grazes (touches once, or cuts a
/// sliver) or misses by a hair, at a time `t_c` inside the interval, along a
/// random direction (not exact: a generic orientation).
fn grazing_spheres() -> SBoxedStrategy<Posed> {
    (vec3(BOX), unit(), unit(), (RADIUS, RADIUS), signed_magnitude(-60, -3), (0.5..8.0f64, 0.1..0.9f64), velocity())
        .prop_map(|(cb, u, w, (ra, rb), g, (speed, tc), vb)| {
            let across = normalize_or(sub(w, scale(u, dot(u, w))), perpendicular(u));
            let h = (ra + rb) * (1.0 + g);
            let v = scale(u, speed);
            let ca = sub(add(cb, scale(across, h)), scale(v, tc));
            posed(sphere(ca, ra), add(vb, v), sphere(cb, rb), vb, None)
        })
        .sboxed()
}

/// A sphere passing a triangle's edge or vertex at a closest approach
/// `r (1 + g)`, `|g|` from `2^-60` to `2^-3` either side, crossing the
/// triangle's plane outside it: the canonical triangle of
/// [`exact_sphere_triangle`], the path perpendicular to its plane through the
/// point `h = r (1 + g)` beyond the edge `v0 v1` (at `−y`) or beyond the vertex
/// `v0` (at `−x`), crossing the plane at `t_c`; then a random rotation and shift.
fn grazing_triangle() -> SBoxedStrategy<Posed> {
    (
        ((dyadic(64, 4), dyadic(64, 4)), (1..=64i64, 0..=64i64, 1..=64i64), 1..=15i64, any::<bool>()),
        (RADIUS, signed_magnitude(-60, -3), (0.5..8.0f64, 0.1..0.9f64), any::<bool>()),
        (rotation(), vec3(BOX), velocity()),
    )
        .prop_map(|(((x0, y0), (len, x2, y2), i, edge), (r, g, (speed, tc), up), (rot, shift, vb))| {
            let (len, x2, y2) = (len as f64 / 16.0, x2 as f64 / 16.0, y2 as f64 / 16.0);
            let v0 = [x0, y0, 0.0];
            let tri = [v0, add(v0, [len, 0.0, 0.0]), add(v0, [x2, y2, 0.0])];
            let h = r * (1.0 + g);
            let at = if edge { [x0 + len * i as f64 / 16.0, y0 - h, 0.0] } else { [x0 - h, y0, 0.0] };
            let v = [0.0, 0.0, if up { speed } else { -speed }];
            let c = sub(at, scale(v, tc));
            let scene = posed(sphere(c, r), add(vb, v), triangle(tri), vb, None);
            transformed(&Similarity::rotate_shift(rot, shift), &scene)
        })
        .sboxed()
}

/// A sphere approaching a plane at a small angle: the normal component of the
/// relative velocity `θ` times the tangential one, `|θ|` from `2^-50` to `2^-3`
/// (toward the plane), from the height that closes at a time from 0.05 to 1.5
/// (inside the interval or beyond it); or one time in four moving
/// exactly parallel to an axis plane at a height `r (1 + g)` (touching or
/// overlapping at `t = 0` when `g ≤ 0`, never otherwise).
fn near_parallel_plane() -> SBoxedStrategy<Posed> {
    (
        (random_plane(), vec3(BOX), unit(), RADIUS),
        (magnitude(-50, -3), 0.5..8.0f64, 0.05..1.5f64, t_max()),
        (grid_point(), (0..3usize, 1..=64i64), signed_magnitude(-60, -3), dyadic_velocity(), 0..4u8),
        velocity(),
    )
        .prop_map(|(((n, d), w, dir, r), (theta, speed, tc, tm), (q, (axis, rr), g, slide, pick), vb)| {
            if pick == 0 {
                let r = rr as f64 / 16.0;
                let mut normal = [0.0; 3];
                normal[axis] = 1.0;
                let mut c = q;
                c[axis] += r * (1.0 + g);
                let mut slide = slide;
                slide[axis] = 0.0;
                return posed(sphere(c, r), add(vb, slide), plane(normal, q[axis]), vb, tm);
            }
            let len = norm_sqrt_dot(n);
            let u = scale(n, 1.0 / len);
            let foot = add(scale(u, d / len), sub(w, scale(u, dot(u, w))));
            // The gap closes at θ·speed: at tc, inside or beyond the interval.
            let c = add(foot, scale(u, r + theta * speed * tc));
            let along = normalize_or(sub(dir, scale(u, dot(u, dir))), perpendicular(u));
            let v = scale(sub(along, scale(u, theta)), speed);
            posed(sphere(c, r), add(vb, v), plane(n, d), vb, tm)
        })
        .sboxed()
}

// ------------------------------------------------------------ other biases

/// Shapes already touching or overlapping at `t = 0` (depth from 0, exactly,
/// to the radius), moving any way: the answer is `t = 0` and the static
/// contact.
fn overlapping_at_start() -> SBoxedStrategy<Posed> {
    (
        (vec3(BOX), unit(), RADIUS, RADIUS, 0.0..1.0f64, 0..4u8),
        (random_triangle(), 0.1..0.9f64, 0.05..0.9f64),
        (random_plane(), velocity(), velocity(), 0..3u8),
    )
        .prop_map(|((cb, u, ra, rb, depth, exact), (tri, s, tt), ((n, d), va, vb, which))| {
            let sink = if exact == 0 { 0.0 } else { depth };
            match which {
                0 => {
                    let ca = add(cb, scale(u, (ra + rb) * (1.0 - sink)));
                    posed(sphere(ca, ra), va, sphere(cb, rb), vb, None)
                }
                1 => {
                    let len = norm_sqrt_dot(n);
                    let un = scale(n, 1.0 / len);
                    let c = add(scale(un, d / len + ra * (1.0 - sink)), sub(cb, scale(un, dot(un, cb))));
                    posed(sphere(c, ra), va, plane(n, d), vb, None)
                }
                _ => {
                    let p = at_barycentric(&tri, s * (1.0 - tt), tt * (1.0 - s));
                    let c = add(p, scale(unit_normal(&tri), ra * (1.0 - sink)));
                    posed(sphere(c, ra), va, triangle(tri), vb, None)
                }
            }
        })
        .sboxed()
}

/// A small fast sphere through a thin target within one interval: radius from
/// `2^-10` to `2^-3`, speed from 16 to about 16,000 (the box crossed in a tiny
/// fraction of the interval), aimed through a point of a random triangle, of a
/// small sphere (radius `2^-8` to `2^-3`) or of a small mesh, at a time inside
/// the interval `[0, 1]`: at the end it is far past, clear of the target.
fn tunneling() -> SBoxedStrategy<Posed> {
    (
        (magnitude(-10, -4), magnitude(4, 13), unit(), 0.05..0.95f64),
        (random_triangle(), 0.05..0.9f64, 0.05..0.9f64, magnitude(-8, -4), vec3(BOX / 2.0)),
        (small_mesh(), 0..3u8),
    )
        .prop_map(|((r, speed, u, th), (tri, s, t, rb, cb), (m, which))| {
            let v = scale(u, speed);
            let through = |x: P3| sub(x, scale(v, th));
            match which {
                0 => {
                    let x = at_barycentric(&tri, s * (1.0 - t), t * (1.0 - s));
                    posed(sphere(through(x), r), v, triangle(tri), [0.0; 3], None)
                }
                1 => posed(sphere(through(cb), r), v, sphere(cb, rb), [0.0; 3], None),
                _ => {
                    let x = match &m {
                        Shape::Mesh(spec) => spec.vertices.as_ref().map_or([0.0; 3], |vs| {
                            let n = vs.len() as f64;
                            vs.iter().fold([0.0; 3], |acc, &p| add(acc, scale(p, 1.0 / n)))
                        }),
                        _ => [0.0; 3],
                    };
                    posed(sphere(through(x), r), v, m, [0.0; 3], None)
                }
            }
        })
        .sboxed()
}

/// Motions that never close the gap: both shapes moving together (no relative
/// motion), `a` receding from `b` (along the line from `b`'s nearest point), or
/// sliding sideways past a plane; from a small gap (from `2^-40` to 1 of the
/// radius) so a method that drifts would touch.
fn not_closing() -> SBoxedStrategy<Posed> {
    ((vec3(BOX), unit(), RADIUS, RADIUS, magnitude(-40, 0)), (velocity(), 0.1..8.0f64, random_plane(), unit(), 0..3u8))
        .prop_map(|((cb, u, ra, rb, gap), (vb, speed, (n, d), dir, which))| match which {
            0 => {
                let ca = add(cb, scale(u, (ra + rb) * (1.0 + gap)));
                posed(sphere(ca, ra), vb, sphere(cb, rb), vb, None)
            }
            1 => {
                let ca = add(cb, scale(u, (ra + rb) * (1.0 + gap)));
                posed(sphere(ca, ra), add(vb, scale(u, speed)), sphere(cb, rb), vb, None)
            }
            _ => {
                let len = norm_sqrt_dot(n);
                let un = scale(n, 1.0 / len);
                let c = add(scale(un, d / len + ra * (1.0 + gap)), sub(cb, scale(un, dot(un, cb))));
                let side = scale(normalize_or(sub(dir, scale(un, dot(un, dir))), perpendicular(un)), speed);
                posed(sphere(c, ra), add(vb, side), plane(n, d), vb, None)
            }
        })
        .sboxed()
}

/// A sphere aimed at a vertex or an edge's midpoint of a small mesh (its
/// features shared by two or three faces), with a little jitter, arriving
/// within the interval; the mesh may move.
fn mesh_features() -> SBoxedStrategy<Posed> {
    (small_mesh(), (0..12usize, any::<bool>()), (vec3(BOX), RADIUS, 0.2..0.9f64), (vec3(0.05), velocity()))
        .prop_map(|(m, (pick, edge), (c, r, th), (jitter, vb))| {
            let target = match &m {
                Shape::Mesh(MeshSpec { vertices: Some(vs), triangles: Some(ts), .. }) => {
                    let f = ts[pick % ts.len()];
                    if edge { scale(add(vs[f[0]], vs[f[1]]), 0.5) } else { vs[f[pick % 3]] }
                }
                _ => [0.0; 3],
            };
            let aim = add(target, jitter);
            // Relative velocity reaching the target at th (the centre would be
            // on it): the first touch is earlier, within the interval.
            let v = scale(sub(aim, c), 1.0 / th);
            posed(sphere(c, r), add(vb, v), m, vb, None)
        })
        .sboxed()
}

/// What the far and resized families move: the uniform scenes and the exact
/// impacts.
fn moved_base() -> SBoxedStrategy<Posed> {
    prop_oneof![
        uniform_sphere_sphere(),
        uniform_sphere_plane(),
        uniform_sphere_triangle(),
        uniform_sphere_mesh(),
        uniform_sphere_box(),
        exact_impacts(),
    ]
    .sboxed()
}

/// The scene moved far from the origin (velocities unchanged).
fn far() -> SBoxedStrategy<Posed> {
    (moved_base(), far_shift()).prop_map(|(s, t)| transformed(&Similarity::scale_shift(1.0, t), &s)).sboxed()
}

/// The scene scaled to tiny or huge size, velocities with it (times unchanged).
fn resized_scene() -> SBoxedStrategy<Posed> {
    (moved_base(), size_factor()).prop_map(|(s, f)| transformed(&Similarity::scale_shift(f, [0.0; 3]), &s)).sboxed()
}

// ------------------------------------------------------------------- boxes

fn uniform_sphere_box() -> SBoxedStrategy<Posed> {
    (vec3(BOX), RADIUS, velocity(), super::boxes::random_box(), velocity(), t_max())
        .prop_map(|(c, r, va, b, vb, tm)| posed(sphere(c, r), va, b, vb, tm))
        .sboxed()
}

/// Exact rotations of a box, each with its matrix as small integers `M` over a
/// denominator `k` (`R = M/k`, rows): the identity, the 3-4-5 turn about `z`,
/// the quarter turns about `z` and about `x`. A point of the box's frame on the
/// `5/64` grid lands on the `1/64` grid in the world, exactly.
const EXACT_TURNS: [([f64; 4], [[f64; 3]; 3], f64); 4] = [
    ([1.0, 0.0, 0.0, 0.0], [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], 1.0),
    ([2.0, 0.0, 0.0, 1.0], [[3.0, -4.0, 0.0], [4.0, 3.0, 0.0], [0.0, 0.0, 5.0]], 5.0),
    ([1.0, 0.0, 0.0, 1.0], [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], 1.0),
    ([1.0, 1.0, 0.0, 0.0], [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]], 1.0),
];

/// `M x` for a row matrix of small integers.
fn times(m: &[[f64; 3]; 3], x: P3) -> P3 {
    [dot(m[0], x), dot(m[1], x), dot(m[2], x)]
}

/// A sphere touching a box's face, edge or corner exactly at `t*`, approaching:
/// the box turned exactly ([`EXACT_TURNS`]), half-extents multiples of 5/64;
/// in its frame the contact point `p` on the feature and the outward unit
/// normal `n` — `(1, 0, 0)` on a face, `(3, 4, 0)/5` at an edge along `z`,
/// `(2, 3, 6)/7` at a corner, mirrored to any of the feature's copies — with
/// the radius a multiple of `5·d/64` (`d` the normal's denominator), so the
/// centre `p + r n` at `t*` is on the 5/64 grid. The relative velocity closes
/// along the normal (the distance, convex in time, falls through `r` at `t*`:
/// the first contact), every input exact; the interval ends at, after or
/// before `t*` ([`end_around`]).
fn exact_sphere_box() -> impl Strategy<Value = (Posed, f64)> + Clone {
    (
        (0..3u8, prop::array::uniform3(1..=16i64), (-16..=16i64, -16..=16i64), 1..=8i64),
        (0..EXACT_TURNS.len(), prop::array::uniform3(any::<bool>()), grid_point()),
        (dyadic_velocity(), dyadic_velocity(), impact_time()),
        (0..4u8, 1..=32i64),
    )
        .prop_map(|((feature, m, (jy, jz), j), (turn, flip, c0), (vb, v, ts), (pick, mm))| {
            let unit = 5.0 / 64.0;
            let h = m.map(|k| k as f64 * unit);
            let (p, n_int, d) = match feature {
                0 => {
                    let y = jy.clamp(-m[1], m[1]) as f64 * unit;
                    let z = jz.clamp(-m[2], m[2]) as f64 * unit;
                    ([h[0], y, z], [1.0, 0.0, 0.0], 1.0)
                }
                1 => ([h[0], h[1], jz.clamp(-m[2], m[2]) as f64 * unit], [3.0, 4.0, 0.0], 5.0),
                _ => (h, [2.0, 3.0, 6.0], 7.0),
            };
            let s = flip.map(|f| if f { -1.0 } else { 1.0 });
            let (p, n_int) = ([0, 1, 2].map(|i| s[i] * p[i]), [0, 1, 2].map(|i| s[i] * n_int[i]));
            let r = j as f64 * 5.0 * d / 64.0;
            let local = add(p, scale(n_int, r / d));
            let (q, mat, k) = EXACT_TURNS[turn];
            let centre_star = add(c0, scale(vb, ts));
            let c_star = add(centre_star, scale(times(&mat, local), 1.0 / k));
            let v = approaching(v, times(&mat, n_int));
            let va = add(vb, v);
            let c_start = sub(c_star, scale(va, ts));
            let scene = posed(sphere(c_start, r), va, oriented_box(c0, h, q), vb, Some(end_around(ts, pick, mm)));
            (scene, ts)
        })
}

/// A sphere passing a box's edge (along its own axis `z`) at a closest
/// approach `r (1 + g)`, `|g|` from `2^-60` to `2^-3` either side, moving
/// parallel to the edge from beyond its end: it touches the rounded edge
/// (first at a corner's sphere) or misses by a hair. The box has a random
/// rotation (the world path is rounded: a generic orientation).
fn grazing_box() -> SBoxedStrategy<Posed> {
    (
        (vec3(BOX), prop::array::uniform3(0.25..1.5f64), super::boxes::random_quaternion()),
        (RADIUS, signed_magnitude(-60, -3), 0.5..8.0f64, velocity()),
    )
        .prop_map(|((c, h, q), (r, g, speed, vb))| {
            let rot = oracle::geom::rotation_matrix(q);
            let world = |u: P3| add(c, [dot(rot[0], u), dot(rot[1], u), dot(rot[2], u)]);
            let reach = r * (1.0 + g);
            // Beside the edge (h₀, h₁, ·) along (3, 4)/5, from below −h₂ − r
            // to beyond +h₂ + r over the interval.
            let off = [h[0] + 0.6 * reach, h[1] + 0.8 * reach, -(h[2] + r) - 0.25 * speed];
            let along = rot.map(|row| row[2] * speed);
            let along = [along[0], along[1], along[2]];
            posed(sphere(world(off), r), add(vb, along), oriented_box(c, h, q), vb, None)
        })
        .sboxed()
}

/// A small fast sphere through a thin box (one half-extent from `2^-12` to
/// `2^-6`) within one interval, clear of it at the end.
fn tunneling_box() -> SBoxedStrategy<Posed> {
    (
        (magnitude(-10, -4), magnitude(4, 13), unit(), 0.05..0.95f64),
        (vec3(BOX / 2.0), (0.25..2.0f64, 0.25..2.0f64, magnitude(-12, -6)), super::boxes::random_quaternion()),
    )
        .prop_map(|((r, speed, u, th), (c, (hx, hy, hz), q))| {
            let v = scale(u, speed);
            posed(sphere(sub(c, scale(v, th)), r), v, oriented_box(c, [hx, hy, hz], q), [0.0; 3], None)
        })
        .sboxed()
}

/// The toi families: uniform first, then biased.
pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform_posed("uniform sphere–sphere", uniform_sphere_sphere),
        Family::uniform_posed("uniform sphere–plane", uniform_sphere_plane),
        Family::uniform_posed("uniform sphere–triangle", uniform_sphere_triangle),
        Family::uniform_posed("uniform sphere–mesh", uniform_sphere_mesh),
        Family::uniform_posed("uniform sphere–box", uniform_sphere_box),
        Family::biased_posed("impact built exactly: spheres", || exact_spheres().prop_map(|(s, _)| s).sboxed()),
        Family::biased_posed("impact built exactly: sphere–plane", || {
            exact_sphere_plane().prop_map(|(s, _)| s).sboxed()
        }),
        Family::biased_posed("impact built exactly: a triangle's face, edge or vertex", || {
            exact_sphere_triangle().prop_map(|(s, _)| s).sboxed()
        }),
        Family::biased_posed("impact built exactly: a box's face, edge or corner", || {
            exact_sphere_box().prop_map(|(s, _)| s).sboxed()
        }),
        Family::biased_posed("sphere grazing a box's edge", grazing_box),
        Family::biased_posed("tunneling: small fast sphere through a thin box", tunneling_box),
        Family::biased_posed("edge walker: impact at t_max ± k ulps", walk_t_max),
        Family::biased_posed("grazing spheres", grazing_spheres),
        Family::biased_posed("sphere grazing a triangle's edge or vertex", grazing_triangle),
        Family::biased_posed("near-parallel approach to a plane", near_parallel_plane),
        Family::biased_posed("touching or overlapping at t = 0", overlapping_at_start),
        Family::biased_posed("tunneling: small fast sphere through a thin target", tunneling),
        Family::biased_posed("no relative motion, receding or sliding", not_closing),
        Family::biased_posed("sphere aimed at a mesh's vertices and edges", mesh_features),
        Family::biased_posed("toi far from the origin", far),
        Family::biased_posed("toi at tiny and huge sizes", resized_scene),
    ]
}
