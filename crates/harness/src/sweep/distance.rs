//! The `distance` sweeps: every distance pair with its surfaces `g` apart
//! (`distance-kissing`), most of them parallel faces or a face and an edge
//! lying on it as `g` goes to 0; and hulls of more and more points, each
//! given in shuffled orders (`distance-points`).
//!
//! The scenes are the `kissing` sweep's (`super::boxes`, `super::spheres`):
//! boxes under a quarter turn with half-extents on a 1/32 grid, so every
//! corner is exact, and a box's hull is the convex shape of its eight
//! corners — the same solid, given as points. Each scene is built unposed,
//! its boxes turned into hulls where the pair asks for one, then posed.

use super::boxes;
use super::grid::{Pose, Rng};
use super::spheres;
use crate::case::Shape;
use crate::generate::build::{Scene, capsule, convex, plane, sphere, triangle};
use crashtest_core::geom::rotation_matrix;
use oracle::geom::P3;

/// A multiple of 1/32 in `[lo, hi]`, as the `kissing` scenes draw them.
fn grid(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    rng.int((lo * 32.0) as i64, (hi * 32.0) as i64) as f64 / 32.0
}

/// The identity pose: the builders' scenes as they are made.
fn unposed() -> Pose {
    Pose {
        kind: super::grid::PoseKind::Exact,
        rot: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        shift: [0.0; 3],
    }
}

/// A box's eight corners as a convex shape. The box generators use quarter
/// turns (signed permutations) and grid half-extents, so each corner
/// `c + R·(±h)` is exact.
fn hull_of(s: &Shape) -> Shape {
    let Shape::Box(b) = s else { return s.clone() };
    let r = rotation_matrix(b.rotation.unwrap_or(crate::case::IDENTITY_ROTATION));
    let corners: Vec<P3> = (0..8usize)
        .map(|k| {
            let u: P3 = std::array::from_fn(|j| if k >> j & 1 == 1 { b.half_extents[j] } else { -b.half_extents[j] });
            std::array::from_fn(|i| b.center[i] + (0..3).map(|j| r[i][j] * u[j]).sum::<f64>())
        })
        .collect();
    convex(corners)
}

/// `build`'s scene with `a` (when `ha`) and `b` (when `hb`) turned into hulls,
/// then posed.
fn hulled(build: fn(&mut Rng, f64, &Pose) -> Scene, rng: &mut Rng, g: f64, pose: &Pose, ha: bool, hb: bool) -> Scene {
    let (a, b) = build(rng, g, &unposed());
    let a = if ha { hull_of(&a) } else { a };
    let b = b.map(|b| if hb { hull_of(&b) } else { b });
    pose.scene(&(a, b))
}

/// The `kissing` sphere–box scene with its box as a hull.
pub(super) fn sphere_convex(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    hulled(boxes::kissing_sphere_box, rng, g, pose, false, true)
}

pub(super) fn capsule_convex(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    hulled(boxes::kissing_capsule_box, rng, g, pose, false, true)
}

pub(super) fn convex_convex(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    hulled(boxes::kissing_box_box, rng, g, pose, true, true)
}

pub(super) fn convex_box(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    hulled(boxes::kissing_box_box, rng, g, pose, true, false)
}

pub(super) fn convex_plane(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    hulled(boxes::kissing_box_plane, rng, g, pose, true, false)
}

pub(super) fn convex_triangle(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    hulled(boxes::kissing_box_triangle, rng, g, pose, true, false)
}

pub(super) fn sphere_sphere(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    spheres::apart(rng, g, pose)
}

/// A sphere over the plane `z = 0`, its surface `g` above it.
pub(super) fn sphere_plane(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let r = grid(rng, 0.25, 1.0);
    let (x, y) = (grid(rng, -1.0, 1.0), grid(rng, -1.0, 1.0));
    pose.scene(&(sphere([x, y, r + g], r), Some(plane([0.0, 0.0, 1.0], 0.0))))
}

/// A sphere over a triangle in `z = 0` (legs 1 to 2 about the origin), its
/// surface `g` above the face.
pub(super) fn sphere_triangle(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let (a, b, c) = (grid(rng, 1.0, 2.0), grid(rng, 1.0, 2.0), grid(rng, 1.0, 2.0));
    let t = triangle([[-a, -b, 0.0], [c, -b, 0.0], [0.0, a + b, 0.0]]);
    let r = grid(rng, 0.25, 1.0);
    pose.scene(&(sphere([0.0, 0.0, r + g], r), Some(t)))
}

/// The `distance-points` scene of `n` points, its points in the order of
/// shuffle `k` (the report's cost-growth cases, `crate::report::growth`).
pub(crate) fn growth_scene(seed: u64, n: usize, k: u64) -> Scene {
    let mut rng = Rng::keyed(seed, &[0x6772_6f77_7468, n as u64, k]);
    shuffled_hull(&mut rng, n as f64, &unposed())
}

/// `distance-points`: a hull of `n` points (`n` the parameter rounded, 4 to
/// 10⁴) on the unit sphere (the Fibonacci lattice: the same points for the
/// same `n`, each a vertex), 2.25 above a unit cube given as a hull. Every
/// pose shuffles the points: one solid, many orders.
pub(super) fn shuffled_hull(rng: &mut Rng, n: f64, pose: &Pose) -> Scene {
    let count = (n.round() as usize).clamp(4, 10_000);
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut points: Vec<P3> = (0..count)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).sqrt();
            let (s, c) = (golden * i as f64).sin_cos();
            [r * c, r * s, z]
        })
        .collect();
    for i in (1..points.len()).rev() {
        let j = rng.int(0, i as i64) as usize;
        points.swap(i, j);
    }
    let lifted: Vec<P3> = points.iter().map(|p| [p[0], p[1], p[2] + 2.25]).collect();
    let b = hull_of(&crate::generate::build::oriented_box([0.0; 3], [1.0; 3], [1.0, 0.0, 0.0, 0.0]));
    pose.scene(&(convex(lifted), Some(b)))
}

/// An axis-aligned box's eight corners as a convex shape.
fn box_hull(center: P3, h: P3) -> Shape {
    convex(
        (0..8usize).map(|k| std::array::from_fn(|i| center[i] + if k >> i & 1 == 1 { h[i] } else { -h[i] })).collect(),
    )
}

/// The unit cube at the origin as a hull.
fn unit_cube() -> Shape {
    box_hull([0.0; 3], [1.0; 3])
}

/// `distance-aspect`: a slab `aspect` times wider than it is thick (half
/// thickness `1/aspect`), its face a grid gap above a unit cube's top face:
/// parallel faces, witnesses any pair of their overlap.
pub(super) fn slab_over_cube(rng: &mut Rng, aspect: f64, pose: &Pose) -> Scene {
    let t = 1.0 / aspect;
    let (w, gap) = (grid(rng, 0.5, 1.0), grid(rng, 0.125, 0.5));
    let (x, y) = (grid(rng, -0.5, 0.5), grid(rng, -0.5, 0.5));
    pose.scene(&(box_hull([x, y, 1.0 + gap + t], [w, w, t]), Some(unit_cube())))
}

/// A needle (half-extents `(w, 1/aspect, 1/aspect)`) lying a grid gap above
/// the cube, turned in the plane by the 3-4-5 rotation: its lower edges run
/// parallel to the top face, across it.
pub(super) fn needle_over_cube(rng: &mut Rng, aspect: f64, pose: &Pose) -> Scene {
    let t = 1.0 / aspect;
    let (w, gap) = (grid(rng, 0.5, 1.0), grid(rng, 0.125, 0.5));
    let c = [0.0, 0.0, 1.0 + gap + t];
    let r = rotation_matrix([2.0, 0.0, 0.0, 1.0]);
    let needle: Vec<P3> = (0..8usize)
        .map(|k| {
            let h = [w, t, t];
            let u: P3 = std::array::from_fn(|i| if k >> i & 1 == 1 { h[i] } else { -h[i] });
            std::array::from_fn(|i| c[i] + (0..3).map(|j| r[i][j] * u[j]).sum::<f64>())
        })
        .collect();
    pose.scene(&(convex(needle), Some(unit_cube())))
}

/// A needle standing through the cube's top face, its lower end at the
/// cube's centre height: the hulls meet (EPA), the least push sideways or
/// up, whichever is shorter.
pub(super) fn needle_through_cube(rng: &mut Rng, aspect: f64, pose: &Pose) -> Scene {
    let t = 1.0 / aspect;
    let (x, y) = (grid(rng, -0.75, 0.75), grid(rng, -0.75, 0.75));
    pose.scene(&(box_hull([x, y, 1.0], [t, t, 1.0]), Some(unit_cube())))
}

/// A capsule of radius `1/aspect` lying a grid gap above a box's top face,
/// its axis parallel to the face.
pub(super) fn thin_capsule_over_box(rng: &mut Rng, aspect: f64, pose: &Pose) -> Scene {
    let r = 1.0 / aspect;
    let (w, gap) = (grid(rng, 0.5, 1.0), grid(rng, 0.125, 0.5));
    let z = 1.0 + gap + r;
    let a = capsule([-w, grid(rng, -0.5, 0.5), z], [w, grid(rng, -0.5, 0.5), z], r);
    pose.scene(&(a, Some(crate::generate::build::oriented_box([0.0; 3], [1.0; 3], [1.0, 0.0, 0.0, 0.0]))))
}

/// A flat box (half-extents `(w, w, 1/aspect)`) face down a grid gap above
/// another box.
pub(super) fn flat_box_over_box(rng: &mut Rng, aspect: f64, pose: &Pose) -> Scene {
    let t = 1.0 / aspect;
    let (w, gap) = (grid(rng, 0.5, 1.0), grid(rng, 0.125, 0.5));
    let a = crate::generate::build::oriented_box([0.0, 0.0, 1.0 + gap + t], [w, w, t], [1.0, 0.0, 0.0, 0.0]);
    pose.scene(&(a, Some(crate::generate::build::oriented_box([0.0; 3], [1.0; 3], [1.0, 0.0, 0.0, 0.0]))))
}
