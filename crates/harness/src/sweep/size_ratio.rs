//! `size-ratio`: one shape of size about 1, the other `ρ` times as large, `ρ`
//! from 1e-8 to 1e8; benign at 1, and walked toward both ends.
//!
//! Canonical scenes (then turned at random and moved up to 4 from the origin):
//! - `sphere–sphere`: radii `s1` and `ρ·s2` (`s` in `[0.5, 1)`), overlapping by
//!   a quarter of the smaller radius;
//! - `sphere–plane`: a sphere of radius `ρ·s` sunk a quarter of its radius into
//!   a plane, over a point 0–1.4 from the plane's foot at the origin;
//! - `sphere–triangle`: a triangle of size 1–2 and a sphere of radius `ρ·s`
//!   over a point inside it, sunk a quarter of the smaller of its radius and 1;
//! - `segment–triangle`: a triangle of size 1–2 and a segment of length `ρ·ℓ`
//!   (`ℓ` in `[1, 2)`) through a point inside it at an angle of 0.3–1.2 rad,
//!   crossing at `t` in `(1/4, 3/4)`.

use super::grid::{Pose, Rng};
use super::scene::{combine, inside_weights, through, tilted, triangle_round};
use crate::generate::build::{Scene, plane, sphere, triangle};
use crashtest_core::vec3::{add, scale};

/// Spheres of radii about 1 and ρ.
pub(super) fn sphere_sphere(rng: &mut Rng, rho: f64, pose: &Pose) -> Scene {
    let r1 = rng.uniform(0.5, 1.0);
    let r2 = rho * rng.uniform(0.5, 1.0);
    let u = rng.unit();
    let d = r1 + r2 - 0.25 * r1.min(r2);
    pose.scene(&(sphere([0.0; 3], r1), Some(sphere(scale(u, d), r2))))
}

/// A sphere of radius about ρ on a plane.
pub(super) fn sphere_plane(rng: &mut Rng, rho: f64, pose: &Pose) -> Scene {
    let nu = rng.uniform(0.5, 2.0);
    let r = rho * rng.uniform(0.5, 1.0);
    let (x, y) = (rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    pose.scene(&(sphere([x, y, 0.75 * r], r), Some(plane([0.0, 0.0, nu], 0.0))))
}

/// A sphere of radius about ρ on a triangle of size about 1.
pub(super) fn sphere_triangle(rng: &mut Rng, rho: f64, pose: &Pose) -> Scene {
    let tri = triangle_round(rng, [0.0; 3], 1.0, 2.0);
    let p = combine(&tri, inside_weights(rng));
    let r = rho * rng.uniform(0.5, 1.0);
    let c = add(p, [0.0, 0.0, r - 0.25 * r.min(1.0)]);
    pose.scene(&(sphere(c, r), Some(triangle(tri))))
}

/// A segment of length about ρ through a triangle of size about 1.
pub(super) fn segment_triangle(rng: &mut Rng, rho: f64, pose: &Pose) -> Scene {
    let tri = triangle_round(rng, [0.0; 3], 1.0, 2.0);
    let x = combine(&tri, inside_weights(rng));
    let e = rng.unit_xy();
    let theta = rng.uniform(0.3, 1.2);
    let len = rho * rng.uniform(1.0, 2.0);
    let tau = rng.uniform(0.25, 0.75);
    pose.scene(&(through(x, tilted(e, theta), tau * len, (1.0 - tau) * len), Some(triangle(tri))))
}
