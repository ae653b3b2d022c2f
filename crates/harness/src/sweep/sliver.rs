//! `sliver`: a triangle of height ρ times its base, ρ from 1 down to 1e-15, and
//! exactly flat (zero area); asked for barycentrics, a segment crossing and a
//! sphere contact at a point inside it.
//!
//! Canonical scene: the base runs from `(−a, 0, 0)` to `(b, 0, 0)` (`a`, `b` in
//! `[1, 2)`, base `L = a + b`), the apex is at `(−a + αL, ρL, 0)` with `α` in
//! `[0.15, 0.85]`; the point inside is at barycentric weights of at least 1/11
//! each, so its `y` is a fraction of `ρL` and held in full relative precision.
//! - `barycentric`: that point, in the triangle's plane.
//! - `segment–triangle`: a segment through it (perpendicular to the plane in an
//!   exact pose, tilted up to 35° in a rotated one).
//! - `sphere–triangle contact`: a sphere centred `H` above it (`H` in
//!   `[0.5, 1.5)`) and sunk 5–30 % of `H` into the face.
//!
//! An exact pose shifts the scene along `x` and `z` only (never along `y`,
//! which carries the height) and permutes the axes; a rotated pose turns and
//! moves it, so below about 1e-16 of the scene the height is a rounding.

use super::grid::{Pose, PoseKind, Rng};
use super::scene::{combine, inside_weights, reorder, through};
use crate::generate::build::{Scene, normalize_or, point, segment, sphere, triangle};
use oracle::geom::P3;

struct Draws {
    tri: [P3; 3],
    p: P3,
    shift: P3,
    z0: f64,
    z1: f64,
    tilt: P3,
    h: f64,
    sink: f64,
}

fn draw(rng: &mut Rng, rho: f64, pose: &Pose) -> Draws {
    let (a, b) = (rng.uniform(1.0, 2.0), rng.uniform(1.0, 2.0));
    let l = a + b;
    let alpha = rng.uniform(0.15, 0.85);
    let weights = inside_weights(rng);
    let shift = [rng.uniform(-2.0, 2.0), 0.0, rng.uniform(-2.0, 2.0)];
    let (z0, z1) = (rng.uniform(0.5, 3.0), rng.uniform(0.5, 3.0));
    let tilt = normalize_or([rng.uniform(-0.7, 0.7), rng.uniform(-0.7, 0.7), 1.0], [0.0, 0.0, 1.0]);
    let (h, sink) = (rng.uniform(0.5, 1.5), rng.uniform(0.05, 0.3));
    let canonical = [[-a, 0.0, 0.0], [b, 0.0, 0.0], [-a + alpha * l, rho * l, 0.0]];
    let p = combine(&canonical, weights);
    // The interior point's y is λ2 ρ L: computed as such, not as a sum that
    // would round it against the base's zeros.
    let p = [p[0], weights[2] * (rho * l), 0.0];
    let shift = if pose.kind == PoseKind::Exact { shift } else { [0.0; 3] };
    let moved = |q: P3| [q[0] + shift[0], q[1], q[2] + shift[2]];
    let tri = reorder(rng, canonical.map(moved));
    Draws { tri, p: moved(p), shift, z0, z1, tilt, h, sink }
}

/// Barycentric coordinates of a point inside the sliver.
pub(super) fn barycentric(rng: &mut Rng, rho: f64, pose: &Pose) -> Scene {
    let d = draw(rng, rho, pose);
    pose.scene(&(point(d.p), Some(triangle(d.tri))))
}

/// A segment through a point inside the sliver.
pub(super) fn segment_triangle(rng: &mut Rng, rho: f64, pose: &Pose) -> Scene {
    let d = draw(rng, rho, pose);
    let seg = match pose.kind {
        PoseKind::Exact => segment([d.p[0], d.p[1], d.shift[2] + d.z0], [d.p[0], d.p[1], d.shift[2] - d.z1]),
        PoseKind::Rotated => through(d.p, d.tilt, d.z0, d.z1),
    };
    pose.scene(&(seg, Some(triangle(d.tri))))
}

/// A sphere sunk into the sliver's face over a point inside it.
pub(super) fn contact_sphere_triangle(rng: &mut Rng, rho: f64, pose: &Pose) -> Scene {
    let d = draw(rng, rho, pose);
    let center = [d.p[0], d.p[1], d.p[2] + d.h];
    pose.scene(&(sphere(center, d.h * (1.0 + d.sink)), Some(triangle(d.tri))))
}
