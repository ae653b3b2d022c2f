//! Shared pieces of the sweeps' canonical scenes: a triangle round a point, an
//! interior point, a segment through a point, and a sphere that keeps its
//! velocity through a pose.

use super::grid::{Pose, Rng, sin_cos};
use crate::case::{Shape, SphereSpec};
use crashtest_core::vec3::{add, scale, sub};

use oracle::geom::P3;

/// `√3 / 2`, for the directions 120° apart (IEEE square root: the same bits
/// everywhere).
fn half_sqrt3() -> f64 {
    3f64.sqrt() / 2.0
}

/// A triangle in the plane `z = 0` round `c`: vertices at distances in
/// `[rmin, rmax)` from `c` in three directions 120° apart, turned by a random
/// angle. `c` is strictly inside (a positive combination of the three
/// directions is zero). The vertex order starts at a random vertex and, one
/// time in two, runs the other way round, so no edge or winding is favoured.
pub fn triangle_round(rng: &mut Rng, c: P3, rmin: f64, rmax: f64) -> [P3; 3] {
    let turn = rng.unit_xy();
    let h = half_sqrt3();
    let dirs = [[1.0, 0.0], [-0.5, h], [-0.5, -h]];
    let radii = [rng.uniform(rmin, rmax), rng.uniform(rmin, rmax), rng.uniform(rmin, rmax)];
    let v = [0, 1, 2].map(|k| {
        let [dx, dy] = dirs[k];
        let d = [turn[0] * dx - turn[1] * dy, turn[1] * dx + turn[0] * dy, 0.0];
        add(c, scale(d, radii[k]))
    });
    reorder(rng, v)
}

/// The vertices starting at a random one, one time in two in reverse order.
pub fn reorder(rng: &mut Rng, v: [P3; 3]) -> [P3; 3] {
    let start = rng.int(0, 2) as usize;
    let reverse = rng.coin();
    let v = [v[start], v[(start + 1) % 3], v[(start + 2) % 3]];
    if reverse { [v[0], v[2], v[1]] } else { v }
}

/// Barycentric weights with each weight at least `1/11` of the sum (well inside).
pub fn inside_weights(rng: &mut Rng) -> [f64; 3] {
    let u = [rng.uniform(0.2, 1.0), rng.uniform(0.2, 1.0), rng.uniform(0.2, 1.0)];
    let s = u[0] + u[1] + u[2];
    u.map(|x| x / s)
}

/// `λ0 v0 + λ1 v1 + λ2 v2`.
pub fn combine(v: &[P3; 3], l: [f64; 3]) -> P3 {
    add(add(scale(v[0], l[0]), scale(v[1], l[1])), scale(v[2], l[2]))
}

/// A direction at the angle `theta` (radians, `|theta| ≤ 2`) above the plane
/// `z = 0`, over the in-plane unit direction `e`.
pub fn tilted(e: P3, theta: f64) -> P3 {
    let (s, c) = sin_cos(theta);
    [e[0] * c, e[1] * c, s]
}

/// The segment from `x − a·d` to `x + b·d`: it passes through `x` at
/// `t = a / (a + b)`.
pub fn through(x: P3, d: P3, a: f64, b: f64) -> Shape {
    crate::generate::build::segment(sub(x, scale(d, a)), add(x, scale(d, b)))
}

/// A sphere with a velocity (the generators' `sphere` has none).
pub fn moving_sphere(center: P3, radius: f64, velocity: P3) -> Shape {
    Shape::Sphere(SphereSpec { center, radius, velocity: Some(velocity), mass: None })
}

/// `pose` applied to a scene whose first shape is a sphere moving at `velocity`
/// (in the canonical frame): the velocity turns with the scene.
pub fn posed_with_velocity(pose: &Pose, scene: (Shape, Option<Shape>), velocity: P3) -> (Shape, Option<Shape>) {
    let (a, b) = pose.scene(&scene);
    let a = match a {
        Shape::Sphere(s) => moving_sphere(s.center, s.radius, pose.vector(velocity)),
        other => other,
    };
    (a, b)
}
