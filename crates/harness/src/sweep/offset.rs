//! `offset`: a scene of size about 1, turned at random and moved a distance `o`
//! from the origin, `o` from 1 up to 1e15, for every query kind.
//!
//! Far from the origin every coordinate rounds at the ulp of `o` (0.125 at
//! 1e15): the shapes the engines see are the rounded ones, and the referee
//! judges exactly those. What breaks is arithmetic that forms large values and
//! subtracts them (a plane's offset `n · p` against `n · q`), not the inputs.
//! The canonical scenes, each well inside its classification:
//! - `sphere–sphere`, `sphere–plane`, `sphere–triangle` contact: spheres of
//!   radius 0.5–1 overlapping by 5–50 % (sphere–plane: centre 0.2–0.8 radii
//!   above the plane; sphere–triangle: over a point inside the face);
//! - `segment–plane`, `segment–triangle`: a segment of length 1–3 crossing at
//!   an angle of 0.3–1.2 rad, at `t` in `(1/4, 3/4)`;
//! - `barycentric`: a point inside a triangle, in its plane;
//! - `bounds`: 6–16 points in `[-1, 1)³`;
//! - `overlap`: two boxes of half-sides 0.5–1.5, overlapping on every axis or
//!   apart by 0.1–0.5 on one (one pose in two each); boxes are moved, not
//!   turned (a turned box is no longer axis-aligned);
//! - `toi`: a sphere 0.2–0.6 from a plane or another sphere, moving toward it
//!   at 0.8–1.5 per unit time (it touches within `t_max` = 1).

use super::grid::{Pose, Rng};
use super::scene::{combine, inside_weights, moving_sphere, posed_with_velocity, through, tilted, triangle_round};
use crate::generate::build::{Scene, aabb, plane, point, points, sphere, triangle};
use crashtest_core::vec3::{add, dot, scale, sub};
use oracle::geom::P3;

/// The pose moved `o` along a random direction (drawn first).
fn far(rng: &mut Rng, o: f64, pose: &Pose) -> Pose {
    let dir = rng.unit();
    pose.shifted(scale(dir, o))
}

/// Sphere–sphere contact.
pub(super) fn contact_sphere_sphere(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let (r1, r2) = (rng.uniform(0.5, 1.0), rng.uniform(0.5, 1.0));
    let d = (r1 + r2) * rng.uniform(0.5, 0.95);
    let u = rng.unit();
    pose.scene(&(sphere(scale(u, -d / 2.0), r1), Some(sphere(scale(u, d / 2.0), r2))))
}

/// Sphere–plane contact.
pub(super) fn contact_sphere_plane(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let nu = rng.uniform(0.5, 2.0);
    let r = rng.uniform(0.5, 1.0);
    let c = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), r * rng.uniform(0.2, 0.8)];
    pose.scene(&(sphere(c, r), Some(plane([0.0, 0.0, nu], 0.0))))
}

/// Sphere–triangle contact over a point inside the face.
pub(super) fn contact_sphere_triangle(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let tri = triangle_round(rng, [0.0; 3], 1.0, 2.0);
    let p = combine(&tri, inside_weights(rng));
    let r = rng.uniform(0.5, 1.0);
    let c = add(p, [0.0, 0.0, r * rng.uniform(0.5, 0.95)]);
    pose.scene(&(sphere(c, r), Some(triangle(tri))))
}

/// A crossing segment: through `x` at an angle of 0.3–1.2 rad to `z = 0`.
fn crossing_segment(rng: &mut Rng, x: P3) -> crate::case::Shape {
    let e = rng.unit_xy();
    let theta = rng.uniform(0.3, 1.2);
    let (a, b) = (rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5));
    through(x, tilted(e, theta), a, b)
}

/// Segment–plane intersection.
pub(super) fn intersect_segment_plane(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let nu = rng.uniform(0.5, 2.0);
    let x = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.0];
    let seg = crossing_segment(rng, x);
    pose.scene(&(seg, Some(plane([0.0, 0.0, nu], 0.0))))
}

/// Segment–triangle intersection through a point inside the face.
pub(super) fn intersect_segment_triangle(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let tri = triangle_round(rng, [0.0; 3], 1.0, 2.0);
    let x = combine(&tri, inside_weights(rng));
    let seg = crossing_segment(rng, x);
    pose.scene(&(seg, Some(triangle(tri))))
}

/// Barycentric coordinates of a point inside a triangle.
pub(super) fn barycentric(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let tri = triangle_round(rng, [0.0; 3], 1.0, 2.0);
    let p = combine(&tri, inside_weights(rng));
    pose.scene(&(point(p), Some(triangle(tri))))
}

/// Bounds of a small cloud.
pub(super) fn bounds(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let n = rng.int(6, 16) as usize;
    let cloud: Vec<P3> = (0..n).map(|_| rng.point(1.0)).collect();
    pose.scene(&(points(cloud), None))
}

/// Two boxes, overlapping or apart on one axis; moved, not turned.
pub(super) fn overlap(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let ha = [rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5)];
    let hb = [rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5)];
    let apart_axis = if rng.coin() { Some(rng.int(0, 2) as usize) } else { None };
    let gap = rng.uniform(0.1, 0.5);
    let mut cb = [0.0; 3];
    for i in 0..3 {
        let reach = ha[i] + hb[i];
        cb[i] = match apart_axis {
            Some(k) if k == i => reach + gap,
            _ => reach * rng.uniform(-0.8, 0.8),
        };
    }
    let t = pose.shift;
    let boxed = |c: P3, h: P3| aabb(add(sub(c, h), t), add(add(c, h), t));
    (boxed([0.0; 3], ha), Some(boxed(cb, hb)))
}

/// A sphere moving toward a plane.
pub(super) fn toi_sphere_plane(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let nu = rng.uniform(0.5, 2.0);
    let r = rng.uniform(0.5, 1.0);
    let gap = rng.uniform(0.2, 0.6);
    let c = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), r + gap];
    let v = [rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), -rng.uniform(0.8, 1.5)];
    posed_with_velocity(&pose, (moving_sphere(c, r, v), Some(plane([0.0, 0.0, nu], 0.0))), v)
}

/// A sphere moving toward another.
pub(super) fn toi_sphere_sphere(rng: &mut Rng, o: f64, pose: &Pose) -> Scene {
    let pose = far(rng, o, pose);
    let (r1, r2) = (rng.uniform(0.5, 1.0), rng.uniform(0.5, 1.0));
    let gap = rng.uniform(0.2, 0.6);
    let u = rng.unit();
    let speed = rng.uniform(0.8, 1.5);
    let side = scale(rng.unit(), 0.2 * speed);
    let v = add(scale(u, speed), sub(side, scale(u, dot(side, u))));
    let a = moving_sphere([0.0; 3], r1, v);
    posed_with_velocity(&pose, (a, Some(sphere(scale(u, r1 + r2 + gap), r2))), v)
}
