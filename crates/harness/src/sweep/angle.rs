//! `angle`: a segment at the angle θ to a plane or a triangle, θ from 1 rad down
//! to 1e-16, and exactly parallel.
//!
//! Canonical scene: the surface is the plane `z = 0` (normal `(0, 0, ν)`, `ν`
//! in `[0.5, 2)`, so a normal need not be unit) or a triangle of size 1–3 in it
//! round the crossing point `X`; the segment runs from `X − a·d` to `X + b·d`,
//! `d = (cos θ · e, sin θ)` over an in-plane unit `e`, so it crosses at
//! `t = a/(a + b) ∈ (1/4, 3/4)`. Exactly parallel (θ = 0): the segment lies in
//! the plane one time in two, else at a dyadic height above it.
//!
//! In an exact pose the out-of-plane coordinates are `−a sin θ` and `b sin θ`
//! themselves (no shift is added to them), so the angle is the nominal one to
//! within two roundings even at 1e-16; in a rotated pose every coordinate is
//! rounded at the scene's scale, and below about 1e-15 the angle is as near
//! to θ as `f64` coordinates of a generic orientation can put it.

use super::grid::{Pose, PoseKind, Rng};
use super::scene::{through, tilted, triangle_round};
use crate::generate::build::{Scene, plane, triangle};
use crashtest_core::vec3::add;
use oracle::geom::P3;

struct Draws {
    e: P3,
    nu: f64,
    a: f64,
    b: f64,
    x: P3,
    tri: [P3; 3],
    height: f64,
}

fn draw(rng: &mut Rng) -> Draws {
    let e = rng.unit_xy();
    let nu = rng.uniform(0.5, 2.0);
    let (a, b) = (rng.uniform(1.0, 3.0), rng.uniform(1.0, 3.0));
    let x = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.0];
    let tri = triangle_round(rng, x, 1.0, 3.0);
    // Exactly parallel: in the plane, or at a dyadic height k/8, k = ±1 … ±8.
    let k = rng.int(1, 8) as f64 / 8.0;
    let height = if rng.coin() {
        0.0
    } else if rng.coin() {
        k
    } else {
        -k
    };
    Draws { e, nu, a, b, x, tri, height }
}

/// The segment (and the in-plane shift of an exact pose, applied to the
/// surface too).
fn segment_and_shift(d: &Draws, theta: f64, pose: &Pose, rng_shift: [f64; 2]) -> (crate::case::Shape, P3) {
    let shift = match pose.kind {
        PoseKind::Exact => [rng_shift[0], rng_shift[1], 0.0],
        PoseKind::Rotated => [0.0; 3],
    };
    let x = add(d.x, shift);
    let seg = if theta == 0.0 {
        let lift = [x[0], x[1], d.height];
        through(lift, d.e, d.a, d.b)
    } else {
        through(x, tilted(d.e, theta), d.a, d.b)
    };
    (seg, shift)
}

/// Segment against the plane.
pub(super) fn segment_plane(rng: &mut Rng, theta: f64, pose: &Pose) -> Scene {
    let d = draw(rng);
    let s = [rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)];
    let (seg, _) = segment_and_shift(&d, theta, pose, s);
    pose.scene(&(seg, Some(plane([0.0, 0.0, d.nu], 0.0))))
}

/// Segment against a triangle round the crossing point.
pub(super) fn segment_triangle(rng: &mut Rng, theta: f64, pose: &Pose) -> Scene {
    let d = draw(rng);
    let s = [rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)];
    let (seg, shift) = segment_and_shift(&d, theta, pose, s);
    let tri = d.tri.map(|v| add(v, shift));
    pose.scene(&(seg, Some(triangle(tri))))
}
