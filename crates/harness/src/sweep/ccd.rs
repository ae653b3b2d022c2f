//! `ccd-edge` and `ccd-parallel`: continuous collision of linearly moving
//! points, swept toward its two degeneracies.
//!
//! - `ccd-edge` (vertex–face): a point crosses a moving triangle's plane at the
//!   time `t*` in `[1/4, 3/4]`, at the distance δ from one of its edges, δ from
//!   1 down to 1e-30, outside the triangle (probe `vertex–face outside`) or
//!   inside it (`vertex–face inside`), and exactly through the edge. The
//!   referee's answer: outside, no impact for every δ > 0; inside, an impact at
//!   `t*`; exactly on the edge, an impact at `t*` (the closed triangle holds
//!   its edges) — so the outside probe's classification flips at δ = 0.
//! - `ccd-parallel` (edge–edge): two edges cross each other (each at an
//!   interior point) at the time `t*` in `[1/4, 3/4]`, the angle θ between
//!   them from 1 rad down to 1e-30; the referee's answer is an impact at `t*`,
//!   not degenerate. Exactly parallel (θ = 0), the two edges are collinear at
//!   `t*` and overlap there: an impact at `t*` still, but flagged degenerate —
//!   two parallel edges lie in one plane at every time, so the coplanarity
//!   cubic is identically zero (the problem is planar), and the impact is
//!   between parallel edges.
//!
//! Canonical scenes are built at the crossing time in the plane `z = h`; each
//! position is then placed at times 0 and 1 by its velocity, `p − t*·v` and
//! `p + (1 − t*)·v`, and the pose maps both.
//!
//! Exactness (the construction holds down to 1e-300; the grids stop at 1e-30,
//! past every f64 method's rounding, to keep the report's stability section
//! to seconds with the peers). A parameter of 1e-300 survives only in a coordinate whose value
//! is of that size, with nothing of size 1 added to it:
//! - `ccd-edge`: as in the `edge` sweep, the edge runs through the origin with
//!   exact ends (a direction on a 1/64 grid times multiples of 1/8), the third
//!   vertex 4–6 away on one side, and the crossing point is `X = ±δ·m` (`m` the
//!   in-plane unit normal to the edge, rounded once: δ holds to an ulp of
//!   itself). In an exact pose nothing moves in the plane: the point moves
//!   along the normal and the triangle moves along it too, so `X`'s in-plane
//!   coordinates are the same at every time and the point passes exactly δ
//!   from the edge. In a rotated pose the triangle translates at a random
//!   velocity and the point crosses at up to 35° from the normal, the scene
//!   turned and moved: every coordinate rounds at about 1e-16 of the scene,
//!   so a δ below that is a rounding and the referee judges what it rounded
//!   to.
//! - `ccd-parallel`: edge `a` lies on the `x` axis from `−a₁` to `a₂`, edge `b`
//!   from `−b₁(cos θ, sin θ)` to `b₂(cos θ, sin θ)` (multiples of 1/8), so
//!   `b`'s `y` coordinates are `∓b·sin θ` exactly and the angle is θ to an ulp
//!   of itself down to 1e-300 (cos θ rounds to 1 below 1e-8; the line through
//!   `b`'s rounded ends then still crosses `a` at the origin). In an exact
//!   pose the edges move along `z` (their relative speed 1–3) and slide along
//!   `x` by dyadic amounts, never along `y`. In a rotated pose each edge
//!   translates at a random velocity (their relative velocity at least 1
//!   along the normal), the scene is turned and moved, and θ below about
//!   1e-16 is a rounding: the nearly parallel edges may then cross elsewhere,
//!   later or not at all, and the referee judges the rounded scene.
//!
//! Relative motion with a component along the plane's normal makes `t*` the
//! only time the shapes share a point: before and after it they are in
//! parallel planes apart (the Minkowski difference of the two shapes at `t*`
//! lies in the plane, and the relative displacement `(t − t*)·r` leaves it).

use super::grid::{Pose, PoseKind, Rng, sin_cos};
use super::scene::reorder;
use crate::generate::build::{Scene, moving_point, moving_segment, moving_triangle, normalize_or};
use crashtest_core::vec3::{add, scale, sub};
use oracle::geom::P3;

/// A unit direction in `z = 0` snapped to multiples of 1/64 (as the `edge`
/// sweep's).
fn snapped_unit_xy(rng: &mut Rng) -> P3 {
    let u = rng.unit_xy();
    [(u[0] * 64.0).round() / 64.0, (u[1] * 64.0).round() / 64.0, 0.0]
}

/// The in-plane perpendicular `(−u_y, u_x)`, normalized.
fn perp_unit(u: P3) -> P3 {
    normalize_or([-u[1], u[0], 0.0], [0.0, 1.0, 0.0])
}

/// A position at the crossing time `ts` as its places at times 0 and 1 under
/// the velocity `v`.
fn ends(p: P3, v: P3, ts: f64) -> (P3, P3) {
    (sub(p, scale(v, ts)), add(p, scale(v, 1.0 - ts)))
}

/// The motion of a scene, drawn the same way for both pose kinds (common random
/// numbers): the crossing time, the plane's height at it, and per pose kind
/// the velocity of the reference shape (the triangle, edge `a`) and the
/// relative velocity of the other.
struct Motion {
    ts: f64,
    h: f64,
    /// Exact poses: the reference shape's velocity along `z` and along `x`
    /// (dyadic, for `ccd-parallel` only), the relative speed along `z`.
    z_ref: f64,
    x_ref: f64,
    x_rel: f64,
    z_rel: f64,
    /// Rotated poses: the reference shape's velocity and the relative one.
    v_ref: P3,
    v_rel: P3,
}

fn draw_motion(rng: &mut Rng) -> Motion {
    let ts = rng.uniform(0.25, 0.75);
    let h = rng.uniform(-2.0, 2.0);
    let z_ref = rng.uniform(-1.0, 1.0);
    let x_ref = rng.int(-16, 16) as f64 / 16.0;
    let x_rel = rng.int(-16, 16) as f64 / 16.0;
    let speed = rng.uniform(1.0, 3.0);
    let z_rel = if rng.coin() { speed } else { -speed };
    let v_ref = rng.point(1.0);
    let tilt = [rng.uniform(-0.7, 0.7) * speed, rng.uniform(-0.7, 0.7) * speed, z_rel];
    Motion { ts, h, z_ref, x_ref, x_rel, z_rel, v_ref, v_rel: tilt }
}

/// The velocities of the reference shape and of the other one for `pose`:
/// along `z` only in an exact pose (and along `x` when `slide`), generic in a
/// rotated one.
fn velocities(m: &Motion, pose: &Pose, slide: bool) -> (P3, P3) {
    match pose.kind {
        PoseKind::Exact => {
            let (x0, x1) = if slide { (m.x_ref, m.x_ref + m.x_rel) } else { (0.0, 0.0) };
            ([x0, 0.0, m.z_ref], [x1, 0.0, m.z_ref + m.z_rel])
        }
        PoseKind::Rotated => (m.v_ref, add(m.v_ref, m.v_rel)),
    }
}

/// The point crossing the triangle's plane δ outside one of its edges (or
/// inside when `inside`).
fn vertex_face(rng: &mut Rng, delta: f64, pose: &Pose, inside: bool) -> Scene {
    let u = snapped_unit_xy(rng);
    let n = perp_unit(u);
    let a = rng.int(8, 16) as f64 / 8.0;
    let b = rng.int(8, 16) as f64 / 8.0;
    let w = rng.uniform(-a / 2.0, b / 2.0);
    let c = rng.uniform(4.0, 6.0);
    let m = draw_motion(rng);
    let lift = |p: P3| [p[0], p[1], p[2] + m.h];
    let tri = reorder(rng, [scale(u, -a), scale(u, b), add(scale(u, w), scale(n, c))]).map(lift);
    let x = lift(scale(n, if inside { delta } else { -delta }));
    let (v_tri, v_point) = velocities(&m, pose, false);
    let (p0, p1) = ends(x, v_point, m.ts);
    let t0 = tri.map(|v| ends(v, v_tri, m.ts).0);
    let t1 = tri.map(|v| ends(v, v_tri, m.ts).1);
    pose.scene(&(moving_point(p0, p1), Some(moving_triangle(t0, t1))))
}

/// `ccd-edge`, the point passing outside the edge.
pub(super) fn vertex_face_outside(rng: &mut Rng, delta: f64, pose: &Pose) -> Scene {
    vertex_face(rng, delta, pose, false)
}

/// `ccd-edge`, the point passing inside the edge.
pub(super) fn vertex_face_inside(rng: &mut Rng, delta: f64, pose: &Pose) -> Scene {
    vertex_face(rng, delta, pose, true)
}

/// `ccd-parallel`: two edges crossing at the angle θ at the time `t*`.
pub(super) fn edge_edge(rng: &mut Rng, theta: f64, pose: &Pose) -> Scene {
    let a = [rng.int(8, 16) as f64 / 8.0, rng.int(8, 16) as f64 / 8.0];
    let b = [rng.int(8, 16) as f64 / 8.0, rng.int(8, 16) as f64 / 8.0];
    // Which end of each edge comes first, and whether b turns clockwise.
    let (flip_a, flip_b, turn) = (rng.coin(), rng.coin(), rng.coin());
    let m = draw_motion(rng);
    let (s, c) = sin_cos(theta);
    let s = if turn { -s } else { s };
    let ea = [[-a[0], 0.0, m.h], [a[1], 0.0, m.h]];
    let eb = [[-b[0] * c, -b[0] * s, m.h], [b[1] * c, b[1] * s, m.h]];
    let order = |e: [P3; 2], flip: bool| if flip { [e[1], e[0]] } else { e };
    let (ea, eb) = (order(ea, flip_a), order(eb, flip_b));
    let (va, vb) = velocities(&m, pose, true);
    let seg = |e: [P3; 2], v: P3| {
        let (p, q) = (ends(e[0], v, m.ts), ends(e[1], v, m.ts));
        moving_segment([p.0, q.0], [p.1, q.1])
    };
    pose.scene(&(seg(ea, va), Some(seg(eb, vb))))
}
