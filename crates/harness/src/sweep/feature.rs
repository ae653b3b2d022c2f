//! `edge` and `vertex`: a segment crossing a triangle at the distance δ from an
//! edge or a vertex, δ from 1 down to 1e-17, and exactly on it.
//!
//! Canonical scene, in the plane `z = 0`: the feature passes through the origin,
//! so the crossing point `X` (δ times a unit direction) carries δ in full
//! relative precision however small it is.
//! - `edge`: the edge runs from `−a·u` to `b·u`, with `u` a unit direction
//!   snapped to multiples of 1/64 and `a`, `b` multiples of 1/8 in `[1, 2]`, so
//!   both ends are exact and the origin is exactly on the edge; the third
//!   vertex is 4–6 away on one side. `X` is δ off the edge's line toward the
//!   third vertex or away from it (inside or outside: one pose in two each).
//! - `vertex`: the vertex is the origin; the other two are 2–4 away in
//!   directions 30°–150° apart; `X` is δ from the vertex in a random in-plane
//!   direction (inside the corner or outside it, as it falls).
//!
//! In an exact pose the segment is perpendicular to the plane, from
//! `(X, h + z0)` to `(X, h − z1)` (the plane at height `h`): its `x` and `y`
//! are `X`'s own, so it crosses exactly at `X`. In a rotated pose the segment
//! is tilted up to 35° from the normal and the whole scene turned and moved, so
//! `X` is where it is to within an ulp of the coordinates (about 1e-16 of the
//! scene): the generic case, where a distance below that is a rounding.

use super::grid::{Pose, PoseKind, Rng};
use super::scene::{reorder, through};
use crate::generate::build::{Scene, normalize_or, segment, triangle};
use crashtest_core::vec3::{add, scale};
use oracle::geom::P3;

/// A unit direction in `z = 0` snapped to multiples of 1/64 (length within 2 %
/// of 1; never zero, since one component of a unit vector is at least 0.7).
fn snapped_unit_xy(rng: &mut Rng) -> P3 {
    let u = rng.unit_xy();
    [(u[0] * 64.0).round() / 64.0, (u[1] * 64.0).round() / 64.0, 0.0]
}

/// The in-plane perpendicular `(−u_y, u_x)`, normalized.
fn perp_unit(u: P3) -> P3 {
    normalize_or([-u[1], u[0], 0.0], [0.0, 1.0, 0.0])
}

struct Segment {
    z0: f64,
    z1: f64,
    h: f64,
    tilt: P3,
}

fn draw_segment(rng: &mut Rng) -> Segment {
    let z0 = rng.uniform(0.5, 3.0);
    let z1 = rng.uniform(0.5, 3.0);
    let h = rng.uniform(-2.0, 2.0);
    let tilt = normalize_or([rng.uniform(-0.7, 0.7), rng.uniform(-0.7, 0.7), 1.0], [0.0, 0.0, 1.0]);
    Segment { z0, z1, h, tilt }
}

/// The scene for the crossing point `x` on the canonical triangle `tri`.
fn crossing(tri: [P3; 3], x: P3, s: &Segment, pose: &Pose) -> Scene {
    match pose.kind {
        PoseKind::Exact => {
            let lift = |p: P3| [p[0], p[1], p[2] + s.h];
            let seg = segment([x[0], x[1], s.h + s.z0], [x[0], x[1], s.h - s.z1]);
            pose.scene(&(seg, Some(triangle(tri.map(lift)))))
        }
        PoseKind::Rotated => pose.scene(&(through(x, s.tilt, s.z0, s.z1), Some(triangle(tri)))),
    }
}

/// Crossing δ from an edge (inside or outside).
pub(super) fn near_edge(rng: &mut Rng, delta: f64, pose: &Pose) -> Scene {
    let u = snapped_unit_xy(rng);
    let m = perp_unit(u);
    let a = rng.int(8, 16) as f64 / 8.0;
    let b = rng.int(8, 16) as f64 / 8.0;
    let w = rng.uniform(-a / 2.0, b / 2.0);
    let c = rng.uniform(4.0, 6.0);
    let inside = rng.coin();
    let s = draw_segment(rng);
    let tri = reorder(rng, [scale(u, -a), scale(u, b), add(scale(u, w), scale(m, c))]);
    let x = scale(m, if inside { delta } else { -delta });
    crossing(tri, x, &s, pose)
}

/// Crossing δ from a vertex (in a random direction).
pub(super) fn near_vertex(rng: &mut Rng, delta: f64, pose: &Pose) -> Scene {
    let u = snapped_unit_xy(rng);
    let (alpha, beta) = (rng.uniform(-0.8, 0.8), rng.uniform(0.5, 1.0));
    let v = normalize_or(add(scale(u, alpha), scale(perp_unit(u), beta)), perp_unit(u));
    let (b, c) = (rng.uniform(2.0, 4.0), rng.uniform(2.0, 4.0));
    let dir = rng.unit_xy();
    let s = draw_segment(rng);
    let tri = reorder(rng, [[0.0; 3], scale(u, b), scale(v, c)]);
    crossing(tri, scale(dir, delta), &s, pose)
}
