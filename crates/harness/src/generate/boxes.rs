//! Scenes of boxes that may be rotated and of capsules, for `contact`,
//! `intersect`, `bounds` and `overlap`.
//!
//! The uniform families place shapes at random in a small box, with random
//! rotations (a quaternion of random doubles) or exact ones (a quaternion of
//! small integers, whose rotation matrix is rational). The biased ones sit where
//! methods break: a box resting on a plane face or edge down (exactly, with the
//! 3-4-5 rotation about the plane's normal), a sphere centre exactly on or a few
//! ulps from a box's edge or corner, a centre inside a box equidistant from faces,
//! capsules side by side (parallel axes) and with meeting axes, a capsule lying
//! along a plane, segments entering a box through an edge or starting inside it,
//! boxes touching face to face under a shared exact rotation, rotations near the
//! identity (the separating axes' cross products nearly vanish), flat boxes, and
//! the same scenes far from the origin and at tiny and huge sizes.

use super::build::*;
use super::family::Family;
use crate::case::Shape;
use crashtest_core::vec3::{add, scale, sub};
use oracle::geom::P3;
use proptest::prelude::*;

/// Half-extents of uniform boxes, per axis.
const HALF: std::ops::Range<f64> = 0.05..2.0;

/// Radii of uniform capsules.
const RADIUS: std::ops::Range<f64> = 0.05..1.5;

/// A quaternion of small integers, not all zero: its rotation matrix is
/// rational (the referee's box is exact; an engine's is rounded).
fn integer_quaternion() -> impl Strategy<Value = [f64; 4]> + Clone {
    prop::array::uniform4(-3i32..=3).prop_map(|q| if q == [0; 4] { [1.0, 0.0, 0.0, 0.0] } else { q.map(f64::from) })
}

/// A quaternion of random doubles (any length, as the format allows).
pub(super) fn random_quaternion() -> impl Strategy<Value = [f64; 4]> + Clone {
    prop::array::uniform4(-1.0..1.0f64).prop_map(|q| if q.iter().all(|x| *x == 0.0) { [1.0, 0.0, 0.0, 0.0] } else { q })
}

/// Either kind of rotation.
fn any_rotation() -> impl Strategy<Value = [f64; 4]> + Clone {
    prop_oneof![integer_quaternion(), random_quaternion()]
}

pub(super) fn random_box() -> impl Strategy<Value = Shape> + Clone {
    (vec3(BOX), prop::array::uniform3(HALF), any_rotation()).prop_map(|(c, h, q)| oriented_box(c, h, q))
}

pub(super) fn random_capsule() -> impl Strategy<Value = Shape> + Clone {
    (vec3(BOX), vec3(1.5), RADIUS).prop_map(|(c, d, r)| capsule(sub(c, d), add(c, d), r))
}

fn uniform_sphere_box() -> SBoxedStrategy<Scene> {
    (vec3(BOX), RADIUS, random_box()).prop_map(|(c, r, b)| (sphere(c, r), Some(b))).sboxed()
}

fn uniform_box_plane() -> SBoxedStrategy<Scene> {
    (random_box(), random_plane()).prop_map(|(b, (n, d))| (b, Some(plane(n, d)))).sboxed()
}

fn uniform_sphere_capsule() -> SBoxedStrategy<Scene> {
    (vec3(BOX), RADIUS, random_capsule()).prop_map(|(c, r, k)| (sphere(c, r), Some(k))).sboxed()
}

fn uniform_capsule_capsule() -> SBoxedStrategy<Scene> {
    (random_capsule(), random_capsule()).prop_map(|(a, b)| (a, Some(b))).sboxed()
}

fn uniform_capsule_plane() -> SBoxedStrategy<Scene> {
    (random_capsule(), random_plane()).prop_map(|(k, (n, d))| (k, Some(plane(n, d)))).sboxed()
}

/// The 3-4-5 rotation about `z` (`R = [[3,−4,0],[4,3,0],[0,0,5]]/5`) and its
/// quarter turns: exact rational rotations whose boxes have corners on the
/// grid when the half-extents are multiples of 5/64.
const ABOUT_Z: [[f64; 4]; 4] =
    [[1.0, 0.0, 0.0, 0.0], [2.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, -2.0]];

/// A box resting on the plane `z = d` from above (`b` the solid below it,
/// normal `+z`): face down, rotated about `z` exactly, sunk by `k/64` (0:
/// touching), or tipped onto an edge by the quarter turn about `x`
/// (`[1, 1, 0, 0]`, exact: `R` has entries 0 and ±1).
fn box_resting_on_plane() -> SBoxedStrategy<Scene> {
    (
        grid_point(),
        prop::array::uniform3((1..=16i64).prop_map(|m| m as f64 * 5.0 / 64.0)),
        0..ABOUT_Z.len(),
        0..=8i64,
        any::<bool>(),
    )
        .prop_map(|(c, h, q, sink, edge_down)| {
            let d = c[2] - h[2] + sink as f64 / 64.0;
            let rotation = if edge_down { [1.0, 1.0, 0.0, 0.0] } else { ABOUT_Z[q] };
            // A quarter turn about x swaps y and z: the lowest point is then
            // at c − h₁ along z.
            let d = if edge_down { c[2] - h[1] + sink as f64 / 64.0 } else { d };
            (oriented_box(c, h, rotation), Some(plane([0.0, 0.0, 1.0], d)))
        })
        .sboxed()
}

/// A sphere whose centre lies exactly on the line of a box's edge or at a
/// corner's diagonal, outside at the radius (touching) or a few ulps off, for
/// the 3-4-5 rotation about `z`: the box's corners are on the grid.
fn sphere_at_box_edge_or_corner() -> SBoxedStrategy<Scene> {
    (grid_point(), 1..=8i64, 0..ABOUT_Z.len(), 0..3usize, ulps(), 1..=16i64)
        .prop_map(|(c, m, q, feature, k, r)| {
            let h = m as f64 * 5.0 / 64.0;
            let b = oriented_box(c, [h, h, h], ABOUT_Z[q]);
            let rot = oracle::geom::rotation_matrix(ABOUT_Z[q]);
            // In the box's frame: a face centre's outward point, an edge's
            // midpoint or a corner, moved out along the face normal by r.
            let r = r as f64 / 16.0;
            let local = match feature {
                0 => [h + r, 0.0, 0.0],
                1 => [h + r, h, 0.0],
                _ => [h + r, h, h],
            };
            let world = add(c, [0, 1, 2].map(|i| rot[i][0] * local[0] + rot[i][1] * local[1] + rot[i][2] * local[2]));
            (sphere(world.map(|x| step_ulps(x, k)), r), Some(b))
        })
        .sboxed()
}

/// A sphere centred inside a box: at its centre (every face pair ties), on a
/// plane of symmetry, or anywhere inside.
fn sphere_inside_box() -> SBoxedStrategy<Scene> {
    (grid_point(), prop::array::uniform3(1..=32i64), integer_quaternion(), 0..3usize, -15..=15i64, RADIUS)
        .prop_map(|(c, h, q, kind, t, r)| {
            let h = h.map(|m| m as f64 / 16.0);
            let rot = oracle::geom::rotation_matrix(q);
            let local = match kind {
                0 => [0.0; 3],
                1 => [h[0] * t as f64 / 16.0, 0.0, 0.0],
                _ => [h[0] * t as f64 / 16.0, h[1] * (t / 2) as f64 / 16.0, h[2] * (t / 3) as f64 / 16.0],
            };
            let world = add(c, [0, 1, 2].map(|i| rot[i][0] * local[0] + rot[i][1] * local[1] + rot[i][2] * local[2]));
            (sphere(world, r), Some(oriented_box(c, h, q)))
        })
        .sboxed()
}

/// Capsules with parallel axes side by side (touching exactly when the gap
/// is 0), their axes overlapping in part, along an axis or a Pythagorean
/// direction.
fn parallel_capsules() -> SBoxedStrategy<Scene> {
    (grid_point(), pythagorean(), 1..=32i64, -16..=16i64, 1..=16i64, 1..=16i64, 0..=4i64)
        .prop_map(|(p, (v, _), len, shift, ra, rb, gap)| {
            let dir = scale(v, len as f64 / 64.0);
            // A direction across the axis: z when v has no z component,
            // x when v is along z, else v's turn in the xy plane.
            let across = if v[2] == 0.0 {
                [0.0, 0.0, 1.0]
            } else if v[0] == 0.0 && v[1] == 0.0 {
                [1.0, 0.0, 0.0]
            } else {
                [v[1], -v[0], 0.0]
            };
            let (ra, rb) = (ra as f64 / 32.0, rb as f64 / 32.0);
            let offset = scale(across, (ra + rb) / crashtest_core::vec3::norm(across) + gap as f64 / 64.0);
            let q = add(add(p, offset), scale(dir, shift as f64 / 32.0));
            (capsule(p, add(p, dir), ra), Some(capsule(q, add(q, dir), rb)))
        })
        .sboxed()
}

/// Capsules whose axes meet (at an interior point, at an end, or collinear):
/// no unique normal.
fn meeting_capsules() -> SBoxedStrategy<Scene> {
    (grid_point(), pythagorean(), pythagorean(), 1..=16i64, 0..=16i64, RADIUS, RADIUS)
        .prop_map(|(p, (u, _), (v, _), a, b, ra, rb)| {
            let (a, b) = (a as f64 / 64.0, b as f64 / 64.0);
            (capsule(sub(p, scale(u, a)), add(p, scale(u, a)), ra), Some(capsule(p, add(p, scale(v, b)), rb)))
        })
        .sboxed()
}

/// A capsule along a plane (its axis parallel, at its radius or sunk) or
/// tipped by a Pythagorean slope.
fn capsule_on_plane() -> SBoxedStrategy<Scene> {
    (grid_point(), pythagorean_pair(), 1..=32i64, 1..=16i64, 0..=8i64, any::<bool>())
        .prop_map(|(p, (x, y, _), len, r, sink, tipped)| {
            let r = r as f64 / 32.0;
            let dir = if tipped { [x, 0.0, y] } else { [x, y, 0.0] };
            let end = add(p, scale(dir, len as f64 / 64.0));
            let lowest = p[2].min(end[2]);
            (capsule(p, end, r), Some(plane([0.0, 0.0, 1.0], lowest - r + sink as f64 / 64.0)))
        })
        .sboxed()
}

fn uniform_segment_capsule() -> SBoxedStrategy<Scene> {
    (vec3(BOX), vec3(BOX), random_capsule()).prop_map(|(s, e, c)| (segment(s, e), Some(c))).sboxed()
}

/// Segments at a capsule along a Pythagorean direction (its axis exact):
/// grazing its side at the radius (± ulps), through an end cap along the
/// axis, starting inside (on the axis too), or ending on its surface.
fn segment_at_capsule() -> SBoxedStrategy<Scene> {
    (grid_point(), pythagorean(), 1..=16i64, 1..=16i64, 0..4usize, ulps(), -16..=16i64)
        .prop_map(|(p, (v, _), len, r, kind, k, along)| {
            let r = r as f64 / 32.0;
            let dir = scale(v, len as f64 / 64.0);
            let across = if v[2] == 0.0 {
                [0.0, 0.0, 1.0]
            } else if v[0] == 0.0 && v[1] == 0.0 {
                [1.0, 0.0, 0.0]
            } else {
                [v[1], -v[0], 0.0]
            };
            let across = scale(across, 1.0 / crashtest_core::vec3::norm(across));
            let mid = add(p, scale(dir, 0.5 + along as f64 / 64.0));
            let (s, e) = match kind {
                0 => {
                    let side = add(mid, scale(across, r));
                    (sub(side, scale(dir, 2.0)), add(side, scale(dir, 2.0)).map(|x| step_ulps(x, k)))
                }
                1 => (sub(p, scale(dir, 1.0)), add(p, scale(dir, 2.0))),
                2 => (mid, add(mid, scale(across, 4.0 * r))),
                _ => (add(mid, scale(across, 4.0 * r)), add(mid, scale(across, r))),
            };
            (segment(s, e), Some(capsule(p, add(p, dir), r)))
        })
        .sboxed()
}

fn uniform_segment_box() -> SBoxedStrategy<Scene> {
    (vec3(BOX), vec3(BOX), random_box()).prop_map(|(s, e, b)| (segment(s, e), Some(b))).sboxed()
}

/// Segments at a box with the 3-4-5 rotation (corners on the grid): through
/// an edge or a corner exactly, starting inside, or ending on a face.
fn segment_at_box_edge() -> SBoxedStrategy<Scene> {
    (grid_point(), 1..=8i64, 0..ABOUT_Z.len(), 0..4usize, grid_point(), ulps())
        .prop_map(|(c, m, q, kind, far, k)| {
            let h = m as f64 * 5.0 / 64.0;
            let rot = oracle::geom::rotation_matrix(ABOUT_Z[q]);
            let world = |l: P3| add(c, [0, 1, 2].map(|i| rot[i][0] * l[0] + rot[i][1] * l[1] + rot[i][2] * l[2]));
            let target = match kind {
                0 => world([h, h, 0.0]),
                1 => world([h, h, h]),
                2 => c,
                _ => world([h, 0.0, 0.0]),
            };
            let start = if kind == 2 { c } else { add(target, far) };
            let end = if kind == 3 { target } else { sub(target, far) };
            (segment(start, end.map(|x| step_ulps(x, k))), Some(oriented_box(c, [h, h, h], ABOUT_Z[q])))
        })
        .sboxed()
}

fn uniform_box_bounds() -> SBoxedStrategy<Scene> {
    random_box().prop_map(|b| (b, None)).sboxed()
}

/// Flat boxes (a zero half-extent) and exact rotations.
fn flat_box_bounds() -> SBoxedStrategy<Scene> {
    (vec3(BOX), prop::array::uniform3(HALF), 0..3usize, integer_quaternion())
        .prop_map(|(c, mut h, flat, q)| {
            h[flat] = 0.0;
            (oriented_box(c, h, q), None)
        })
        .sboxed()
}

fn uniform_box_box() -> SBoxedStrategy<Scene> {
    (random_box(), random_box()).prop_map(|(a, b)| (a, Some(b))).sboxed()
}

fn uniform_box_aabb() -> SBoxedStrategy<Scene> {
    (random_box(), vec3(BOX), prop::array::uniform3(0.0..BOX))
        .prop_map(|(a, lo, e)| (a, Some(aabb(lo, add(lo, e)))))
        .sboxed()
}

/// Two boxes under one exact rotation, touching face to face, edge to edge
/// or corner to corner, or a few grid steps apart or sunk: in the shared
/// frame they are touching axis-aligned boxes.
fn touching_boxes() -> SBoxedStrategy<Scene> {
    (
        grid_point(),
        prop::array::uniform3(1..=8i64),
        prop::array::uniform3(1..=8i64),
        0..ABOUT_Z.len(),
        1..=7u8,
        -2..=2i64,
    )
        .prop_map(|(c, ha, hb, q, axes, gap)| {
            let ha = ha.map(|m| m as f64 * 5.0 / 64.0);
            let hb = hb.map(|m| m as f64 * 5.0 / 64.0);
            let rot = oracle::geom::rotation_matrix(ABOUT_Z[q]);
            // Along each chosen axis, b's centre sits at the sum of the
            // half-extents (touching), moved by `gap` 64ths (×5: on the grid).
            let local: P3 =
                std::array::from_fn(|i| if axes >> i & 1 == 1 { ha[i] + hb[i] + gap as f64 * 5.0 / 64.0 } else { 0.0 });
            let cb = add(c, [0, 1, 2].map(|i| rot[i][0] * local[0] + rot[i][1] * local[1] + rot[i][2] * local[2]));
            (oriented_box(c, ha, ABOUT_Z[q]), Some(oriented_box(cb, hb, ABOUT_Z[q])))
        })
        .sboxed()
}

/// Two boxes whose rotations differ by a tiny angle: the cross products of
/// their edges nearly vanish (a separating-axis test's epsilon decides).
fn nearly_aligned_boxes() -> SBoxedStrategy<Scene> {
    (random_box(), prop::array::uniform3(HALF), vec3(1.0), -40..=-4i32, unit())
        .prop_map(|(a, hb, offset, k, axis)| {
            let Shape::Box(spec) = &a else { unreachable!("random_box makes boxes") };
            let q = spec.rotation.unwrap_or(crate::case::IDENTITY_ROTATION);
            // q ⊗ (1, ε·axis): the same rotation turned by about 2ε.
            let e = pow2(k);
            let (w, v) = (q[0], [q[1], q[2], q[3]]);
            let turned = [
                w - e * (v[0] * axis[0] + v[1] * axis[1] + v[2] * axis[2]),
                v[0] + e * (w * axis[0] + v[1] * axis[2] - v[2] * axis[1]),
                v[1] + e * (w * axis[1] + v[2] * axis[0] - v[0] * axis[2]),
                v[2] + e * (w * axis[2] + v[0] * axis[1] - v[1] * axis[0]),
            ];
            let b = oriented_box(add(spec.center, offset), hb, turned);
            (a, Some(b))
        })
        .sboxed()
}

fn uniform_box_box_contact() -> SBoxedStrategy<Scene> {
    (random_box(), random_box()).prop_map(|(a, b)| (a, Some(b))).sboxed()
}

fn uniform_box_triangle() -> SBoxedStrategy<Scene> {
    (random_box(), random_triangle()).prop_map(|(a, t)| (a, Some(triangle(t)))).sboxed()
}

fn uniform_capsule_box() -> SBoxedStrategy<Scene> {
    (random_capsule(), random_box()).prop_map(|(a, b)| (a, Some(b))).sboxed()
}

fn uniform_capsule_triangle() -> SBoxedStrategy<Scene> {
    (random_capsule(), random_triangle()).prop_map(|(a, t)| (a, Some(triangle(t)))).sboxed()
}

/// `c + R·l` for the exact rotation `q` rounded to `f64` (exact for the
/// 3-4-5 rotations about `z` on grid points: their entries times 5/64 steps
/// are dyadic).
fn placed(c: P3, q: [f64; 4], l: P3) -> P3 {
    let rot = oracle::geom::rotation_matrix(q);
    add(c, [0, 1, 2].map(|i| rot[i][0] * l[0] + rot[i][1] * l[1] + rot[i][2] * l[2]))
}

/// A box with the 3-4-5 rotation about `z` (or a quarter turn about `x`,
/// edge down) resting on a triangle in the plane `z = d`, sunk by `k/64`
/// (0: touching): the triangle holds the box's footprint, cuts it, or lies
/// under a corner.
fn box_on_triangle() -> SBoxedStrategy<Scene> {
    (grid_point(), prop::array::uniform3(1..=16i64), 0..ABOUT_Z.len(), 0..=8i64, any::<bool>(), 0..3usize)
        .prop_map(|(c, h, q, sink, edge_down, cover)| {
            let h = h.map(|m| m as f64 * 5.0 / 64.0);
            let (rotation, low) = if edge_down { ([1.0, 1.0, 0.0, 0.0], h[1]) } else { (ABOUT_Z[q], h[2]) };
            let d = c[2] - low + sink as f64 / 64.0;
            let reach = h[0] + h[1] + h[2];
            let span = [4.0, 1.0, 0.25][cover] * reach;
            let t = [
                [c[0] - span, c[1] - span, d],
                [c[0] + 2.0 * span, c[1] - span, d],
                [c[0] - span, c[1] + 2.0 * span, d],
            ];
            (oriented_box(c, h, rotation), Some(triangle(t)))
        })
        .sboxed()
}

/// A capsule at a box with the 3-4-5 rotation about `z`: its axis along a
/// face at the radius (± grid steps), through the box's centre (four ways
/// out at once), or from a corner outward.
fn capsule_at_box() -> SBoxedStrategy<Scene> {
    (grid_point(), 1..=8i64, 0..ABOUT_Z.len(), 0..3usize, 1..=16i64, -2..=2i64, 1..=16i64)
        .prop_map(|(c, m, q, kind, r, gap, len)| {
            let h = m as f64 * 5.0 / 64.0;
            let r = r as f64 / 32.0;
            let len = len as f64 * 5.0 / 64.0;
            let (s, e) = match kind {
                0 => {
                    let z = h + r + gap as f64 * 5.0 / 64.0;
                    ([-len, 0.0, z], [len, 0.0, z])
                }
                1 => ([-h - len, 0.0, 0.0], [h + len, 0.0, 0.0]),
                _ => ([h, h, h], [h + len, h + len, h + len]),
            };
            (
                capsule(placed(c, ABOUT_Z[q], s), placed(c, ABOUT_Z[q], e), r),
                Some(oriented_box(c, [h, h, h], ABOUT_Z[q])),
            )
        })
        .sboxed()
}

/// A capsule at a triangle in a grid plane: its axis along the face at the
/// radius (± grid steps), through the face, or along an edge's line.
fn capsule_at_triangle() -> SBoxedStrategy<Scene> {
    (flat_grid_triangle(), 0..3usize, 1..=16i64, -2..=2i64, 0.0..1.0f64, 0.0..1.0f64)
        .prop_map(|(t, kind, r, gap, s, u)| {
            let r = r as f64 / 32.0;
            let n = unit_normal(&t);
            let inside = at_barycentric(&t, s * 0.5, u * 0.5);
            let (start, end) = match kind {
                0 => {
                    let lift = scale(n, r + gap as f64 / 64.0);
                    (add(t[0], lift), add(inside, lift))
                }
                1 => (add(inside, scale(n, -r)), add(inside, scale(n, 2.0 * r))),
                _ => (t[0], add(t[0], scale(sub(t[1], t[0]), 0.5 + s))),
            };
            (capsule(start, end, r), Some(triangle(t)))
        })
        .sboxed()
}

/// Every scene of this file's contact families, for the moved and resized
/// variants.
fn contact_base() -> SBoxedStrategy<Scene> {
    prop_oneof![
        uniform_sphere_box(),
        uniform_box_plane(),
        uniform_sphere_capsule(),
        uniform_capsule_capsule(),
        uniform_capsule_plane(),
        box_resting_on_plane(),
        parallel_capsules(),
        // Nested: `prop_oneof!` of more than ten is a union that is not `Sync`.
        prop_oneof![
            uniform_box_box_contact(),
            uniform_box_triangle(),
            uniform_capsule_box(),
            uniform_capsule_triangle()
        ]
        .sboxed(),
    ]
    .sboxed()
}

/// The contact families of boxes and capsules.
pub(super) fn contact_families() -> Vec<Family> {
    vec![
        Family::uniform("uniform sphere–box", uniform_sphere_box),
        Family::uniform("uniform box–plane", uniform_box_plane),
        Family::uniform("uniform sphere–capsule", uniform_sphere_capsule),
        Family::uniform("uniform capsule–capsule", uniform_capsule_capsule),
        Family::uniform("uniform capsule–plane", uniform_capsule_plane),
        Family::biased("box resting on a plane, face or edge down", box_resting_on_plane),
        Family::biased("sphere at a box's face, edge or corner ± k ulps", sphere_at_box_edge_or_corner),
        Family::biased("sphere centre inside a box", sphere_inside_box),
        Family::biased("parallel capsules side by side", parallel_capsules),
        Family::biased("capsules whose axes meet", meeting_capsules),
        Family::biased("capsule along or tipped onto a plane", capsule_on_plane),
        Family::uniform("uniform box–box", uniform_box_box_contact),
        Family::uniform("uniform box–triangle", uniform_box_triangle),
        Family::uniform("uniform capsule–box", uniform_capsule_box),
        Family::uniform("uniform capsule–triangle", uniform_capsule_triangle),
        Family::biased("boxes resting face, edge or corner on each other under one exact rotation", touching_boxes),
        Family::biased("boxes turned against each other by a tiny angle", nearly_aligned_boxes),
        Family::biased("box resting on a triangle, face or edge down", box_on_triangle),
        Family::biased("capsule along a box's face, through it, or off a corner", capsule_at_box),
        Family::biased("capsule along a triangle, through it, or along an edge", capsule_at_triangle),
        Family::biased("boxes and capsules far from the origin", || far_from_origin(contact_base())),
        Family::biased("boxes and capsules at tiny and huge sizes", || resized(contact_base())),
    ]
}

/// The intersect families of boxes.
pub(super) fn intersect_families() -> Vec<Family> {
    vec![
        Family::uniform("uniform segment–box", uniform_segment_box),
        Family::biased("segment through a box's edge or corner, from inside, or ending on a face", segment_at_box_edge),
        Family::uniform("uniform segment–capsule", uniform_segment_capsule),
        Family::biased("segment grazing a capsule, through its cap, from inside, or ending on it", segment_at_capsule),
    ]
}

/// The bounds families of boxes.
pub(super) fn bounds_families() -> Vec<Family> {
    vec![
        Family::uniform("uniform box", uniform_box_bounds),
        Family::biased("flat box with an exact rotation", flat_box_bounds),
    ]
}

/// The overlap families of boxes.
pub(super) fn overlap_families() -> Vec<Family> {
    vec![
        Family::uniform("uniform box–box", uniform_box_box),
        Family::uniform("uniform box–aabb", uniform_box_aabb),
        Family::biased("boxes touching under one exact rotation", touching_boxes),
        Family::biased("boxes turned by a tiny angle", nearly_aligned_boxes),
    ]
}
