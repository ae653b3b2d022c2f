//! `box-turn`, `box-tie`, `capsule-parallel` and `kissing`: oriented boxes and
//! capsules swept toward their degeneracies.
//!
//! - `box-turn` (overlap box–box, and their contact): box `b` turned by θ from `a`'s orientation
//!   about a random axis, θ from 1 down to 1e-16, and exactly 0 (the same
//!   rotation). Every edge of `b` is then nearly parallel to one of `a`'s, and
//!   the separating axes built from their cross products nearly vanish — the
//!   case a test with an epsilon on those axes decides by it. Both boxes have
//!   half-extents 0.5–1.5 on the 1/32 grid, `a` with an integer quaternion;
//!   `b`'s centre is `a`'s moved along one of `a`'s face normals by the sum of
//!   the half-extents there, less 0.05–0.2 (probe `overlapping`) or plus it
//!   (`apart`): well inside its classification at θ = 0, and for small θ too
//!   (turning by θ moves a corner by at most θ times the half-diagonal).
//!   `b`'s quaternion is `a`'s times `(cos θ/2, sin θ/2 · axis)` in f64 (its
//!   box is exactly that quaternion's, which the referee reads exactly).
//! - `box-tie` (contact sphere–box): a sphere whose centre is inside a box, at
//!   `a` from the face `+x` and `a + δ` from the face `+y` (in the box's own
//!   frame; the box turned by a quarter turn, whose matrix is a signed
//!   permutation, so the tie is exact), δ from 1 down to 1e-16,
//!   and exactly equidistant: the nearest face swaps at δ = 0, where the answer
//!   is flagged (two faces tie) and the normal is a right angle from its
//!   neighbour's. Probe `inside`; probe `onto the edge` puts the centre outside
//!   the face `+x` at `a`, δ short of the edge `+x +y` along `y` (δ = 0: exactly
//!   over the edge's line, where the closest point is the edge).
//! - `capsule-parallel` (contact capsule–capsule): capsule `b` along `x`,
//!   capsule `a` above it at the height `h < r_a + r_b` (overlapping), its axis
//!   turned by θ in the plane `z = h` about the point over `b`'s middle, θ from 1
//!   down to 1e-16, and exactly parallel (the contact region is then a
//!   segment: any of its points is right). The closest points slide along the
//!   axes as θ → 0.
//! - `kissing` (contact of spheres, boxes, capsules and planes):
//!   the gap between the surfaces from 1 down to 1e-16, apart, and exactly
//!   touching: a sphere beside a box's face (in the face region), two crossing
//!   capsules, a box face down on a box, a capsule across a box's face. Radii
//!   and
//!   half-extents on the 1/32 grid, the box's quaternion an integer one with a
//!   dyadic rotation (the quarter turns), so that exactly touching is exact.
//!
//! An exact pose permutes the axes (no translation); a rotated pose turns and
//! moves the scene, rounding every coordinate at the scene's scale, below which
//! a small parameter is a rounding.

use super::grid::{Pose, Rng, sin_cos};
use super::scene::{moving_sphere, posed_with_velocity};
use crate::generate::build::{Scene, aabb, capsule, hamilton, oriented_box, plane, segment, sphere, triangle};
use crashtest_core::vec3::{add, scale};
use oracle::geom::{P3, rotation_matrix};

/// A quaternion of small integers, not all zero (an exact rational rotation).
fn integer_quaternion(rng: &mut Rng) -> [f64; 4] {
    let q = [0; 4].map(|_| rng.int(-2, 2) as f64);
    if q.iter().all(|x| *x == 0.0) { [1.0, 0.0, 0.0, 0.0] } else { q }
}

/// A grid value in `[lo, hi]` on the 1/32 grid.
fn grid(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    rng.int((lo * 32.0) as i64, (hi * 32.0) as i64) as f64 / 32.0
}

/// `R·l` for the rotation `q`.
fn turn(q: [f64; 4], l: P3) -> P3 {
    let r = rotation_matrix(q);
    [0, 1, 2].map(|i| r[i][0] * l[0] + r[i][1] * l[1] + r[i][2] * l[2])
}

fn turned_boxes(rng: &mut Rng, theta: f64, pose: &Pose, gap_sign: f64) -> Scene {
    let qa = integer_quaternion(rng);
    let (ha, hb) = ([0; 3].map(|_| grid(rng, 0.5, 1.5)), [0; 3].map(|_| grid(rng, 0.5, 1.5)));
    let face = rng.int(0, 2) as usize;
    let gap = grid(rng, 0.0625, 0.1875);
    let mut l = [0.0; 3];
    l[face] = ha[face] + hb[face] + gap_sign * gap;
    let cb = turn(qa, l);
    let axis = rng.unit();
    let (s, c) = sin_cos(theta / 2.0);
    let qb = hamilton(qa, [c, s * axis[0], s * axis[1], s * axis[2]]);
    pose.scene(&(oriented_box([0.0; 3], ha, qa), Some(oriented_box(cb, hb, qb))))
}

/// `box-turn`, probe `overlapping`.
pub(super) fn turned_overlapping(rng: &mut Rng, theta: f64, pose: &Pose) -> Scene {
    turned_boxes(rng, theta, pose, -1.0)
}

/// `box-turn`, probe `apart`.
pub(super) fn turned_apart(rng: &mut Rng, theta: f64, pose: &Pose) -> Scene {
    turned_boxes(rng, theta, pose, 1.0)
}

/// `box-tie`, probe `inside`.
pub(super) fn tie_inside(rng: &mut Rng, delta: f64, pose: &Pose) -> Scene {
    let q = QUARTER_TURNS[rng.int(0, 3) as usize];
    let h = [grid(rng, 1.5, 2.5), grid(rng, 1.5, 2.5), grid(rng, 1.5, 2.5)];
    let a = grid(rng, 0.25, 0.75);
    let r = grid(rng, 0.25, 1.0);
    // a from +x, a + δ from +y (the local coordinates are exact: h − a is on
    // the grid and h − a − δ rounds at most at δ's own ulp).
    let local = [h[0] - a, h[1] - a - delta, 0.0];
    pose.scene(&(sphere(turn(q, local), r), Some(oriented_box([0.0; 3], h, q))))
}

/// `box-tie`, probe `onto the edge`.
pub(super) fn tie_onto_edge(rng: &mut Rng, delta: f64, pose: &Pose) -> Scene {
    let q = QUARTER_TURNS[rng.int(0, 3) as usize];
    let h = [grid(rng, 1.0, 2.0), grid(rng, 1.0, 2.0), grid(rng, 1.0, 2.0)];
    let a = grid(rng, 0.25, 0.75);
    let r = a + grid(rng, 0.125, 0.5);
    let local = [h[0] + a, h[1] - delta, 0.0];
    pose.scene(&(sphere(turn(q, local), r), Some(oriented_box([0.0; 3], h, q))))
}

/// `capsule-parallel`.
pub(super) fn capsules_turning(rng: &mut Rng, theta: f64, pose: &Pose) -> Scene {
    let (ra, rb) = (grid(rng, 0.25, 1.0), grid(rng, 0.25, 1.0));
    let h = (ra + rb) * 0.75;
    let (la, lb) = (grid(rng, 1.0, 2.0), grid(rng, 1.5, 3.0));
    let (s, c) = sin_cos(theta);
    let dir = [c, s, 0.0];
    let mid = [0.0, 0.0, h];
    let a = capsule(add(mid, scale(dir, -la)), add(mid, scale(dir, la)), ra);
    pose.scene(&(a, Some(capsule([-lb, 0.0, 0.0], [lb, 0.0, 0.0], rb))))
}

/// The quarter turns about the axes: quaternions whose rotation matrices are
/// signed permutations (dyadic, so a face's position is exact).
const QUARTER_TURNS: [[f64; 4]; 4] =
    [[1.0, 0.0, 0.0, 0.0], [1.0, 1.0, 0.0, 0.0], [1.0, 0.0, 1.0, 0.0], [1.0, 0.0, 0.0, 1.0]];

/// `kissing`, probe `sphere–box`: the sphere beside the face `+x`, `g` away.
pub(super) fn kissing_sphere_box(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let q = QUARTER_TURNS[rng.int(0, 3) as usize];
    let h = [grid(rng, 0.5, 1.5), grid(rng, 0.5, 1.5), grid(rng, 0.5, 1.5)];
    let r = grid(rng, 0.25, 1.0);
    let along = [grid(rng, -0.4, 0.4) * h[1], grid(rng, -0.4, 0.4) * h[2]];
    let local = [h[0] + r + g, along[0], along[1]];
    pose.scene(&(sphere(turn(q, local), r), Some(oriented_box([0.0; 3], h, q))))
}

/// `kissing`, probe `toi sphere–box`: the sphere's centre passing over the
/// face `+y`, `r + g` above it, across the whole face within the interval
/// (the box turned by a quarter turn, so the height is exact): at `g = 0` it
/// first touches where it reaches the edge `x = −h₀`, then slides along the face.
pub(super) fn kissing_toi_sphere_box(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let q = QUARTER_TURNS[rng.int(0, 3) as usize];
    let h = [grid(rng, 0.5, 1.5), grid(rng, 0.5, 1.5), grid(rng, 0.5, 1.5)];
    let r = grid(rng, 0.25, 1.0);
    let z = grid(rng, -0.4, 0.4) * h[2];
    let start = [-(h[0] + r + 1.0), h[1] + r + g, z];
    let speed = 2.0 * (h[0] + r + 1.0);
    let v = turn(q, [speed, 0.0, 0.0]);
    posed_with_velocity(pose, (moving_sphere(turn(q, start), r, v), Some(oriented_box([0.0; 3], h, q))), v)
}

/// `kissing`, probe `capsule–capsule`: crossing axes, surfaces `g` apart.
pub(super) fn kissing_capsules(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let (ra, rb) = (grid(rng, 0.25, 1.0), grid(rng, 0.25, 1.0));
    let (la, lb) = (grid(rng, 0.5, 2.0), grid(rng, 0.5, 2.0));
    let z = ra + rb + g;
    pose.scene(&(capsule([-la, 0.0, z], [la, 0.0, z], ra), Some(capsule([0.0, -lb, 0.0], [0.0, lb, 0.0], rb))))
}

fn turned_box_aabb(rng: &mut Rng, theta: f64, pose: &Pose, gap_sign: f64) -> Scene {
    let (ha, hb) = ([0; 3].map(|_| grid(rng, 0.5, 1.5)), [0; 3].map(|_| grid(rng, 0.5, 1.5)));
    let face = rng.int(0, 2) as usize;
    let gap = grid(rng, 0.0625, 0.1875);
    let mut c = [0.0; 3];
    c[face] = ha[face] + hb[face] + gap_sign * gap;
    let axis = rng.unit();
    let (s, co) = sin_cos(theta / 2.0);
    let q = [co, s * axis[0], s * axis[1], s * axis[2]];
    let b = aabb([0, 1, 2].map(|i| c[i] - hb[i]), [0, 1, 2].map(|i| c[i] + hb[i]));
    // The AABB stays axis-aligned: only an exact pose (a signed permutation,
    // no translation) keeps it one, so rotated poses move the box alone.
    let a = oriented_box([0.0; 3], ha, q);
    match pose.kind {
        super::grid::PoseKind::Exact => pose.scene(&(a, Some(b))),
        super::grid::PoseKind::Rotated => (a, Some(b)),
    }
}

/// `box-turn`, probe `box–aabb overlapping`: a box turned by θ from the axes
/// against an AABB.
pub(super) fn turned_box_aabb_overlapping(rng: &mut Rng, theta: f64, pose: &Pose) -> Scene {
    turned_box_aabb(rng, theta, pose, -1.0)
}

/// `box-tie`, probe `segment–box onto the edge`: a segment along `−x` entering
/// the face `+x` δ short of the edge `+x +y`.
pub(super) fn segment_onto_edge(rng: &mut Rng, delta: f64, pose: &Pose) -> Scene {
    let q = QUARTER_TURNS[rng.int(0, 3) as usize];
    let h = [grid(rng, 1.0, 2.0), grid(rng, 1.0, 2.0), grid(rng, 1.0, 2.0)];
    let z = grid(rng, -0.5, 0.5) * h[2];
    let (s, e) = ([h[0] + grid(rng, 0.5, 2.0), h[1] - delta, z], [-h[0] - grid(rng, 0.5, 2.0), h[1] - delta, z]);
    pose.scene(&(segment(turn(q, s), turn(q, e)), Some(oriented_box([0.0; 3], h, q))))
}

/// `kissing`, probe `box–plane`: a box turned by a quarter turn, face down
/// `g` above the plane `z = 0`.
pub(super) fn kissing_box_plane(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let q = QUARTER_TURNS[rng.int(0, 3) as usize];
    let h = [grid(rng, 0.5, 1.5), grid(rng, 0.5, 1.5), grid(rng, 0.5, 1.5)];
    // The box's extent along z after the quarter turn: the half-extent its
    // rotation puts there.
    let r = rotation_matrix(q);
    let down = (0..3).map(|j| r[2][j].abs() * h[j]).sum::<f64>();
    pose.scene(&(oriented_box([0.0, 0.0, down + g], h, q), Some(plane([0.0, 0.0, 1.0], 0.0))))
}

/// `kissing`, probe `capsule–plane`: a capsule tipped by a Pythagorean slope,
/// its lower end's sphere `g` above the plane `z = 0`.
pub(super) fn kissing_capsule_plane(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let r = grid(rng, 0.25, 1.0);
    let len = grid(rng, 0.5, 2.0);
    let end = [0.6 * len, 0.0, 0.8 * len];
    let start = [0.0, 0.0, r + g];
    pose.scene(&(capsule(start, add(start, end), r), Some(plane([0.0, 0.0, 1.0], 0.0))))
}

/// `kissing`, probe `sphere–capsule`: a sphere beside a capsule's side.
pub(super) fn kissing_sphere_capsule(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let (ra, rb) = (grid(rng, 0.25, 1.0), grid(rng, 0.25, 1.0));
    let l = grid(rng, 0.5, 2.0);
    let x = grid(rng, -0.5, 0.5) * l;
    pose.scene(&(sphere([x, 0.0, ra + rb + g], ra), Some(capsule([-l, 0.0, 0.0], [l, 0.0, 0.0], rb))))
}

/// A box under a quarter turn at the origin, with its extent along `z`.
fn quarter_turned_box(rng: &mut Rng) -> (crate::case::Shape, f64) {
    let q = QUARTER_TURNS[rng.int(0, 3) as usize];
    let h = [grid(rng, 0.5, 1.5), grid(rng, 0.5, 1.5), grid(rng, 0.5, 1.5)];
    let r = rotation_matrix(q);
    let up = (0..3).map(|j| r[2][j].abs() * h[j]).sum::<f64>();
    (oriented_box([0.0; 3], h, q), up)
}

/// `kissing`, probe `box–box`: box `a` face down over box `b`'s top face
/// (each under a quarter turn), `g` above it.
pub(super) fn kissing_box_box(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let (b, up_b) = quarter_turned_box(rng);
    let (a, down_a) = quarter_turned_box(rng);
    let crate::case::Shape::Box(mut a) = a else { unreachable!("a box") };
    a.center = [grid(rng, -0.25, 0.25), grid(rng, -0.25, 0.25), up_b + down_a + g];
    pose.scene(&(crate::case::Shape::Box(a), Some(b)))
}

/// `kissing`, probe `capsule–box`: a capsule across box `b`'s top face, its
/// surface `g` above it.
pub(super) fn kissing_capsule_box(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let (b, up) = quarter_turned_box(rng);
    let (r, l) = (grid(rng, 0.25, 1.0), grid(rng, 0.25, 1.0));
    let z = up + r + g;
    pose.scene(&(capsule([-l, 0.25, z], [l, -0.25, z], r), Some(b)))
}

/// A triangle in the plane `z = 0` around the origin, its corners on the grid
/// (legs from 1 to 2), so that a shape just above the origin is over its face.
fn floor_triangle(rng: &mut Rng) -> crate::case::Shape {
    let (a, b, c) = (grid(rng, 1.0, 2.0), grid(rng, 1.0, 2.0), grid(rng, 1.0, 2.0));
    triangle([[-a, -b, 0.0], [c, -b, 0.0], [0.0, a + b, 0.0]])
}

/// `kissing`, probe `box–triangle`: a box under a quarter turn face down over
/// a triangle in `z = 0`, `g` above it.
pub(super) fn kissing_box_triangle(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let t = floor_triangle(rng);
    let (a, down) = quarter_turned_box(rng);
    let crate::case::Shape::Box(mut a) = a else { unreachable!("a box") };
    a.center = [grid(rng, -0.25, 0.25), grid(rng, -0.25, 0.25), down + g];
    pose.scene(&(crate::case::Shape::Box(a), Some(t)))
}

/// `kissing`, probe `capsule–triangle`: a capsule lying across a triangle in
/// `z = 0`, its surface `g` above it.
pub(super) fn kissing_capsule_triangle(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let t = floor_triangle(rng);
    let (r, l) = (grid(rng, 0.25, 1.0), grid(rng, 0.25, 0.75));
    let z = r + g;
    pose.scene(&(capsule([-l, 0.25, z], [l, -0.25, z], r), Some(t)))
}

/// `kissing`, probe `segment–capsule`: a segment across a capsule's side at
/// `r + g` from its axis (`g = 0`: it grazes the surface, a hit).
pub(super) fn kissing_segment_capsule(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let (r, l) = (grid(rng, 0.25, 1.0), grid(rng, 0.5, 2.0));
    let (x, reach) = (grid(rng, -0.5, 0.5) * l, grid(rng, 1.0, 2.0));
    let z = r + g;
    pose.scene(&(segment([x, -reach, z], [x, reach, z]), Some(capsule([-l, 0.0, 0.0], [l, 0.0, 0.0], r))))
}
