//! Tests of the oriented-box referee: hand-derived cases (each derivation
//! beside it), every degeneracy and refusal, extreme scales, and loops against
//! direct `f64` formulas and sampling.
//!
//! Most expected values are rationals whose correct rounding is the decimal
//! literal written (Rust parses literals correctly rounded: `0.6` is the
//! rounding of 3/5), or exact small dyadic numbers; the 3-4-5 rotation
//! (`q = [2, 0, 0, 1]`, axes `(3/5, 4/5, 0)`, `(−4/5, 3/5, 0)`, `(0, 0, 1)`)
//! keeps rotated boxes rational. Since the referee rounds correctly, those
//! are compared with no ulp of slack.

use super::*;
use crate::referee::exact::{Q, within_ulps};
use crate::referee::stage::exact_only;

/// The referee is correctly rounded and the expectations are correctly
/// rounded literals or exact values: no ulp of slack. (The capsule tests use
/// these helpers too.)
const EXACT_ULPS: u64 = 0;

/// The 3-4-5 rotation about z: `R = [[3/5, −4/5, 0], [4/5, 3/5, 0], [0, 0, 1]]`.
const Q345: [f64; 4] = [2.0, 0.0, 0.0, 1.0];
const IDENTITY: [f64; 4] = [1.0, 0.0, 0.0, 0.0];

fn obb(center: P3, half_extents: P3, rotation: [f64; 4]) -> OrientedBox {
    OrientedBox { center, half_extents, rotation }
}

fn unit_box() -> OrientedBox {
    obb([0.0; 3], [1.0; 3], IDENTITY)
}

pub(crate) fn sphere(center: P3, radius: f64) -> Sphere {
    Sphere { center, radius }
}

pub(crate) fn close(got: f64, want: f64, what: &str) {
    assert!(within_ulps(got, want, EXACT_ULPS), "{what}: got {got:e}, want {want:e}");
}

pub(crate) fn close_v(got: P3, want: P3, what: &str) {
    for k in 0..3 {
        assert!(within_ulps(got[k], want[k], EXACT_ULPS), "{what}[{k}]: got {got:?}, want {want:?}");
    }
}

pub(crate) fn contact(answer: Result<ContactAnswer, RefereeError>, what: &str) -> (Contact, bool) {
    let a = answer.unwrap_or_else(|e| panic!("{what}: refused: {e}"));
    (a.contact.unwrap_or_else(|| panic!("{what}: expected contact")), a.degenerate)
}

/// A margin's sign bit is the decision: `+0.0` on the boundary.
pub(crate) fn positive(m: f64) -> bool {
    !m.is_sign_negative()
}

#[test]
fn referee_box_rotation_is_exact_and_orthonormal() {
    // The 3-4-5 rotation at several lengths of q: the same exact columns.
    for k in [1.0, 0.5, 3.0, 1e-300, 5e-324, 1e300] {
        let bx = exact_box(&obb([0.0; 3], [1.0; 3], [2.0 * k, 0.0, 0.0, k]), BOX_A).unwrap();
        let f = |n: i32, d: u32| Q::from_parts(n.into(), d.into());
        assert_eq!(bx.axes[0], [f(3, 5), f(4, 5), Q::ZERO], "scale {k}");
        assert_eq!(bx.axes[1], [f(-4, 5), f(3, 5), Q::ZERO], "scale {k}");
        assert_eq!(bx.axes[2], [Q::ZERO, Q::ZERO, Q::ONE], "scale {k}");
    }
    // Any quaternion: columns exactly unit and pairwise orthogonal, and a
    // right-handed frame (A0 × A1 = A2).
    for qr in [[1.0, 2.0, 3.0, 4.0], [0.1, -0.7, 1e-3, 5.0], [0.0, 0.0, 0.0, 5e-324], [-3.0, 1e10, 1e-10, 2.0]] {
        let bx = exact_box(&obb([0.0; 3], [1.0; 3], qr), BOX_A).unwrap();
        for i in 0..3 {
            for j in 0..3 {
                let want = if i == j { Q::ONE } else { Q::ZERO };
                assert_eq!(dot(&bx.axes[i], &bx.axes[j]), want, "{qr:?}: axes {i}, {j}");
            }
        }
        assert_eq!(crate::referee::exact::cross(&bx.axes[0], &bx.axes[1]), bx.axes[2], "{qr:?}: handedness");
    }
}

#[test]
fn referee_sphere_box_outside_face_edge_and_rotated() {
    // (sphere, box, point, normal, depth, what): derived by hand.
    let cases = [
        // Face region: u = (2.5, 0, 0), p = (1, 0, 0), distance 1.5; r 2 → 0.5.
        (sphere([2.5, 0.0, 0.0], 2.0), unit_box(), [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.5, "face +x"),
        // Edge region: u = (4, 5, 0), p = (1, 1, 0), u − p = (3, 4, 0), distance 5;
        // r 6 → depth 1, normal (3/5, 4/5, 0).
        (sphere([4.0, 5.0, 0.0], 6.0), unit_box(), [1.0, 1.0, 0.0], [0.6, 0.8, 0.0], 1.0, "edge"),
        // Corner region: u = (−3, −5, 5) against h = (1, 1, 1)… p = (−1, −1, 1),
        // u − p = (−2, −4, 4), distance 6; r 6.5 → 0.5, normal (−1/3, −2/3, 2/3).
        (
            sphere([-3.0, -5.0, 5.0], 6.5),
            unit_box(),
            [-1.0, -1.0, 1.0],
            [-1.0 / 3.0, -2.0 / 3.0, 2.0 / 3.0],
            0.5,
            "corner",
        ),
        // The 3-4-5 box: M = (3, 4, 0) is u = Rᵀ M = (5, 0, 0); p = (1, 0, 0),
        // distance 4; r 5 → depth 1, normal R·x = (3/5, 4/5, 0), point R·p.
        (sphere([3.0, 4.0, 0.0], 5.0), obb([0.0; 3], [1.0; 3], Q345), [0.6, 0.8, 0.0], [0.6, 0.8, 0.0], 1.0, "rotated"),
        // Moved centre: the same, shifted by (10, −20, 30).
        (
            sphere([13.0, -16.0, 30.0], 5.0),
            obb([10.0, -20.0, 30.0], [1.0; 3], Q345),
            [10.6, -19.2, 30.0],
            [0.6, 0.8, 0.0],
            1.0,
            "rotated, moved",
        ),
    ];
    for (s, b, point, normal, depth, what) in cases {
        let (k, deg) = contact(contact_sphere_box(&s, &b), what);
        assert!(!deg, "{what}");
        close_v(k.point, point, what);
        close_v(k.normal, normal, what);
        close(k.depth, depth, what);
        close(contact_margin_sphere_box(&s, &b).unwrap(), depth, what);
    }
    // 1/3 and 2/3 above are IEEE quotients, correctly rounded by definition.
}

#[test]
fn referee_sphere_box_touching_and_one_ulp_apart() {
    // Centre 2 from the face x = 1, r 1: depth exactly 0 is contact, margin +0.
    let (k, _) = contact(contact_sphere_box(&sphere([2.0, 0.0, 0.0], 1.0), &unit_box()), "touching");
    close(k.depth, 0.0, "depth");
    assert!(positive(contact_margin_sphere_box(&sphere([2.0, 0.0, 0.0], 1.0), &unit_box()).unwrap()));
    // One ulp further (2 + 2⁻⁵¹): apart, margin exactly −2⁻⁵¹ (representable).
    let far = f64::from_bits(2f64.to_bits() + 1);
    let s = sphere([far, 0.0, 0.0], 1.0);
    assert_eq!(contact_sphere_box(&s, &unit_box()).unwrap().contact, None);
    close(contact_margin_sphere_box(&s, &unit_box()).unwrap(), -(far - 2.0), "margin");
    // A point sphere (r = 0) on the face: contact, depth 0, the face's normal.
    let (k, deg) = contact(contact_sphere_box(&sphere([1.0, 0.5, 0.0], 0.0), &unit_box()), "point on face");
    assert!(!deg);
    close_v(k.normal, [1.0, 0.0, 0.0], "normal");
    close(k.depth, 0.0, "depth");
}

#[test]
fn referee_sphere_box_centre_inside() {
    // (centre, r, point, normal, depth, degenerate, what).
    let cases = [
        // Nearest face +x at 0.5 (+y at 0.75, z at 1): point (1, 0.25, 0), depth 1.5.
        ([0.5, 0.25, 0.0], 1.0, [1.0, 0.25, 0.0], [1.0, 0.0, 0.0], 1.5, false, "+x"),
        ([0.0, -0.75, 0.25], 1.0, [0.0, -1.0, 0.25], [0.0, -1.0, 0.0], 1.25, false, "−y"),
        ([0.0, 0.0, -0.5], 2.0, [0.0, 0.0, -1.0], [0.0, 0.0, -1.0], 2.5, false, "−z"),
        // The centre: every face at 1, a tie: +x first, depth r + 1.
        ([0.0, 0.0, 0.0], 1.0, [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 2.0, true, "centre"),
        // Equidistant from +y and −z (0.5 each): +y comes first.
        ([0.0, 0.5, -0.5], 1.0, [0.0, 1.0, -0.5], [0.0, 1.0, 0.0], 1.5, true, "+y/−z tie"),
        // On the edge x = −1, z = 1: faces −x and +z at 0; −x first.
        ([-1.0, 0.0, 1.0], 0.5, [-1.0, 0.0, 1.0], [-1.0, 0.0, 0.0], 0.5, true, "edge"),
        // On a corner, r 0: depth 0, contact, degenerate.
        ([1.0, -1.0, 1.0], 0.0, [1.0, -1.0, 1.0], [1.0, 0.0, 0.0], 0.0, true, "corner"),
    ];
    for (c, r, point, normal, depth, degenerate, what) in cases {
        let (k, deg) = contact(contact_sphere_box(&sphere(c, r), &unit_box()), what);
        assert_eq!(deg, degenerate, "{what}");
        close_v(k.point, point, what);
        close_v(k.normal, normal, what);
        close(k.depth, depth, what);
        close(contact_margin_sphere_box(&sphere(c, r), &unit_box()).unwrap(), depth, what);
    }
    // Inside the 3-4-5 box: M = (3/8, 1/2, 0) is u = Rᵀ M = (5/8, 0, 0): nearest
    // face +x (3/8 away), normal R·x = (3/5, 4/5, 0), point R·(1, 0, 0),
    // depth 1 + 3/8.
    let b = obb([0.0; 3], [1.0; 3], Q345);
    let (k, deg) = contact(contact_sphere_box(&sphere([0.375, 0.5, 0.0], 1.0), &b), "rotated inside");
    assert!(!deg);
    close_v(k.normal, [0.6, 0.8, 0.0], "normal");
    close_v(k.point, [0.6, 0.8, 0.0], "point");
    close(k.depth, 1.375, "depth");
}

#[test]
fn referee_sphere_box_flat_box() {
    // A square of half-side 1 in z = 0 (h_z = 0).
    let flat = obb([0.0; 3], [1.0, 1.0, 0.0], IDENTITY);
    // Above it: u = (0.25, 0, 2), p = (0.25, 0, 0): normal +z, depth 3 − 2.
    let (k, deg) = contact(contact_sphere_box(&sphere([0.25, 0.0, 2.0], 3.0), &flat), "above");
    assert!(!deg);
    close_v(k.point, [0.25, 0.0, 0.0], "point");
    close_v(k.normal, [0.0, 0.0, 1.0], "normal");
    close(k.depth, 1.0, "depth");
    // Below it: normal −z.
    let (k, _) = contact(contact_sphere_box(&sphere([0.25, 0.0, -2.0], 3.0), &flat), "below");
    close_v(k.normal, [0.0, 0.0, -1.0], "normal");
    // In its plane: faces +z and −z both at 0 — degenerate, +z, depth r.
    let (k, deg) = contact(contact_sphere_box(&sphere([0.25, 0.0, 0.0], 3.0), &flat), "in the plane");
    assert!(deg);
    close_v(k.normal, [0.0, 0.0, 1.0], "normal");
    close_v(k.point, [0.25, 0.0, 0.0], "point");
    close(k.depth, 3.0, "depth");
    // A point box (all h = 0): the sphere–sphere contact with a zero radius.
    let dot_box = obb([1.0, 2.0, 3.0], [0.0; 3], Q345);
    let (k, deg) = contact(contact_sphere_box(&sphere([4.0, 6.0, 3.0], 6.0), &dot_box), "point box");
    assert!(!deg);
    close_v(k.normal, [0.6, 0.8, 0.0], "normal");
    close_v(k.point, [1.0, 2.0, 3.0], "point");
    close(k.depth, 1.0, "depth");
}

#[test]
fn referee_box_plane_resting_sunk_and_apart() {
    let ground = Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 };
    // Resting face down: lowest face z = 0, depth 0, point the face centre's
    // projection (0, 0, 0), region the face's four corners in order.
    let resting = obb([0.0, 0.0, 1.0], [1.0; 3], IDENTITY);
    let (k, deg) = contact(contact_box_plane(&resting, &ground), "resting");
    assert!(!deg);
    close_v(k.point, [0.0; 3], "point");
    close_v(k.normal, [0.0, 0.0, 1.0], "normal");
    close(k.depth, 0.0, "depth");
    assert!(positive(contact_margin_box_plane(&resting, &ground).unwrap()));
    let region = contact_region_box_plane(&resting, &ground).unwrap().unwrap();
    let want = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]];
    assert_eq!(region.len(), 4);
    for (got, want) in region.iter().zip(want) {
        close_v(*got, want, "face region");
    }
    // Sunk half a unit, the plane's normal of length 2 (the same plane).
    let sunk = obb([0.0, 0.0, 0.5], [1.0; 3], IDENTITY);
    let twice = Plane { normal: [0.0, 0.0, 2.0], offset: 0.0 };
    let (k, _) = contact(contact_box_plane(&sunk, &twice), "sunk");
    close(k.depth, 0.5, "depth");
    close_v(k.normal, [0.0, 0.0, 1.0], "normal");
    // One ulp above the ground: apart, margin −2⁻⁵² (exact).
    let up = obb([0.0, 0.0, f64::from_bits(1f64.to_bits() + 1)], [1.0; 3], IDENTITY);
    assert_eq!(contact_box_plane(&up, &ground).unwrap().contact, None);
    assert_eq!(contact_region_box_plane(&up, &ground).unwrap(), None);
    close(contact_margin_box_plane(&up, &ground).unwrap(), -f64::EPSILON, "margin");
    // The 3-4-5 box on the ground (its z axis vertical): the face's corners
    // c ± R·x ± R·y, e.g. −(3/5, 4/5) − (−4/5, 3/5) = (1/5, −7/5).
    let turned = obb([0.0, 0.0, 1.0], [1.0; 3], Q345);
    let region = contact_region_box_plane(&turned, &ground).unwrap().unwrap();
    let want = [[0.2, -1.4, 0.0], [1.4, 0.2, 0.0], [-0.2, 1.4, 0.0], [-1.4, -0.2, 0.0]];
    for (got, want) in region.iter().zip(want) {
        close_v(*got, want, "turned face region");
    }
}

#[test]
fn referee_box_plane_edge_and_corner_down() {
    let ground = Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 };
    // q = [2, 1, 0, 0]: rotation about x with cos 3/5, sin 4/5, so
    // R·y = (0, 3/5, 4/5), R·z = (0, −4/5, 3/5). With h = (1, 5, 5), s = n·Rᵢ =
    // (0, 4/5, 3/5): the lowest points are u = (±1, −5, −5), at
    // z = c_z − 4 − 3. Centre (0, 0, 6): depth 1, the lowest edge
    // c + R·(±1, −5, −5) = (±1, 1, −1), projected (±1, 1, 0); the answer's
    // point its centre (0, 1, 0).
    let edge_down = obb([0.0, 0.0, 6.0], [1.0, 5.0, 5.0], [2.0, 1.0, 0.0, 0.0]);
    let (k, deg) = contact(contact_box_plane(&edge_down, &ground), "edge down");
    assert!(!deg);
    close(k.depth, 1.0, "depth");
    close_v(k.point, [0.0, 1.0, 0.0], "point");
    let region = contact_region_box_plane(&edge_down, &ground).unwrap().unwrap();
    assert_eq!(region.len(), 2);
    close_v(region[0], [-1.0, 1.0, 0.0], "edge start");
    close_v(region[1], [1.0, 1.0, 0.0], "edge end");
    // Corner down: a plane with normal (3, 4, 12) (length 13) against the
    // unit box: s = (3, 4, 12), lowest corner (−1, −1, −1) at n·x = −19.
    // Offset −6: depth (−6 + 19)/13 = 1, the corner's projection
    // (−1, −1, −1) + (13/169)·(3, 4, 12) = (−10/13, −9/13, −1/13).
    let tilted = Plane { normal: [3.0, 4.0, 12.0], offset: -6.0 };
    let (k, deg) = contact(contact_box_plane(&unit_box(), &tilted), "corner down");
    assert!(!deg);
    close(k.depth, 1.0, "depth");
    close_v(k.normal, [3.0 / 13.0, 4.0 / 13.0, 12.0 / 13.0], "normal");
    close_v(k.point, [-10.0 / 13.0, -9.0 / 13.0, -1.0 / 13.0], "point");
    let region = contact_region_box_plane(&unit_box(), &tilted).unwrap().unwrap();
    // The same rational rounded by the same code: equal bits.
    assert_eq!(region, vec![k.point], "a unique point is the answer's");
    // (IEEE quotients of exact integers are the correctly rounded rationals.)
    // A flat box standing on its zero-thickness edge (h_x = 0, free axis y):
    // the region is a segment, not a degenerate rectangle.
    let card = obb([0.0, 0.0, 2.0], [0.0, 1.0, 2.0], IDENTITY);
    let region = contact_region_box_plane(&card, &ground).unwrap().unwrap();
    assert_eq!(region.len(), 2);
    close_v(region[0], [0.0, -1.0, 0.0], "card start");
    close_v(region[1], [0.0, 1.0, 0.0], "card end");
}

#[test]
fn referee_segment_box_hits() {
    let b = unit_box();
    let seg = |start: P3, end: P3| Segment { start, end };
    // (segment, t, point, normal, degenerate, what).
    let cases = [
        // Along x from −3 to 3: enters x = −1 at t = 2/6.
        (seg([-3.0, 0.0, 0.0], [3.0, 0.0, 0.0]), 1.0 / 3.0, [-1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], false, "face −x"),
        // Downward onto the top: t = (4 − 1)/8.
        (seg([0.5, 0.5, 4.0], [0.5, 0.5, -4.0]), 0.375, [0.5, 0.5, 1.0], [0.0, 0.0, 1.0], false, "face +z"),
        // Ending exactly on the face: t = 1 counts.
        (seg([-3.0, 0.0, 0.0], [-1.0, 0.0, 0.0]), 1.0, [-1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], false, "ends on face"),
        // Through the corner (−1, −1, −1): all three slabs at t = 1/4: −x first.
        (seg([-2.0, -2.0, -2.0], [2.0, 2.0, 2.0]), 0.25, [-1.0; 3], [-1.0, 0.0, 0.0], true, "corner"),
        // Through the edge x = 1, y = −1 (moving −x, +y): slabs x and y both at
        // 1/2; faces +x and −y: +x first.
        (seg([2.0, -2.0, 0.0], [0.0, 0.0, 0.0]), 0.5, [1.0, -1.0, 0.0], [1.0, 0.0, 0.0], true, "edge"),
        // Sliding in the plane of face +y (y = 1 throughout): enters through −x,
        // the only slab it crosses; not degenerate.
        (seg([-3.0, 1.0, 0.0], [3.0, 1.0, 0.0]), 1.0 / 3.0, [-1.0, 1.0, 0.0], [-1.0, 0.0, 0.0], false, "sliding"),
        // Starting inside: t = 0 at the start, nearest face +x (0.5 away).
        (seg([0.5, 0.0, 0.0], [5.0, 0.0, 0.0]), 0.0, [0.5, 0.0, 0.0], [1.0, 0.0, 0.0], false, "inside"),
        // Starting at the centre: six faces tie, +x.
        (seg([0.0; 3], [0.0, 0.0, 5.0]), 0.0, [0.0; 3], [1.0, 0.0, 0.0], true, "centre"),
        // Starting on face −y and leaving: in the closed box at t = 0.
        (seg([0.0, -1.0, 0.0], [0.0, -3.0, 0.0]), 0.0, [0.0, -1.0, 0.0], [0.0, -1.0, 0.0], false, "start on face"),
    ];
    for (s, t, point, normal, degenerate, what) in cases {
        let a = intersect_segment_box(&s, &b).unwrap();
        let hit = a.hit.unwrap_or_else(|| panic!("{what}: expected a hit"));
        assert_eq!(a.degenerate, degenerate, "{what}");
        assert!(!a.parallel, "{what}");
        assert_eq!((hit.barycentric, hit.triangle), (None, None), "{what}");
        // 1/3 and 3/8 are IEEE quotients (correctly rounded) or exact.
        close(hit.t, t, what);
        close_v(hit.point, point, what);
        close_v(hit.normal, normal, what);
    }
}

#[test]
fn referee_segment_box_misses_rotated_flat_and_zero_length() {
    let b = unit_box();
    let seg = |start: P3, end: P3| Segment { start, end };
    for (s, what) in [
        (seg([-3.0, 2.0, 0.0], [3.0, 2.0, 0.0]), "parallel to slab y, outside it"),
        (seg([-3.0, 0.0, 0.0], [-2.0, 0.0, 0.0]), "stops short"),
        (seg([-3.0, 0.0, 0.0], [-f64::from_bits(1f64.to_bits() + 1), 0.0, 0.0]), "one ulp short"),
        (seg([2.0, 0.0, 0.0], [5.0, 0.0, 0.0]), "moving away"),
        (seg([-3.0, 3.0, 0.0], [3.0, 3.5, 0.0]), "passes above"),
    ] {
        let a = intersect_segment_box(&s, &b).unwrap();
        assert_eq!(a, IntersectAnswer { hit: None, parallel: false, degenerate: false }, "{what}");
    }
    // The 3-4-5 box: from u = (−5, 0, 0) to (5, 0, 0), i.e. (−3, −4, 0) to
    // (3, 4, 0): enters face −x at t = 4/10, point R·(−1, 0, 0).
    let r = intersect_segment_box(&seg([-3.0, -4.0, 0.0], [3.0, 4.0, 0.0]), &obb([0.0; 3], [1.0; 3], Q345)).unwrap();
    let hit = r.hit.expect("rotated hit");
    close(hit.t, 0.4, "t");
    close_v(hit.point, [-0.6, -0.8, 0.0], "point");
    close_v(hit.normal, [-0.6, -0.8, 0.0], "normal");
    assert!(!r.degenerate);
    // A flat box (the square z = 0): crossing it at t = 1/2 through face −z.
    let flat = obb([0.0; 3], [1.0, 1.0, 0.0], IDENTITY);
    let r = intersect_segment_box(&seg([0.0, 0.0, -1.0], [0.0, 0.0, 1.0]), &flat).unwrap();
    let hit = r.hit.expect("flat hit");
    close(hit.t, 0.5, "t");
    close_v(hit.normal, [0.0, 0.0, -1.0], "normal");
    assert!(!r.degenerate);
    // Zero-length segments are degenerate: inside, a hit at t = 0 with the
    // nearest face; outside, no hit.
    let r = intersect_segment_box(&seg([0.5, 0.0, 0.0], [0.5, 0.0, 0.0]), &b).unwrap();
    assert!(r.degenerate);
    close_v(r.hit.expect("point inside").normal, [1.0, 0.0, 0.0], "normal");
    let r = intersect_segment_box(&seg([5.0, 0.0, 0.0], [5.0, 0.0, 0.0]), &b).unwrap();
    assert_eq!(r, IntersectAnswer { hit: None, parallel: false, degenerate: true });
}

#[test]
fn referee_bounds_box() {
    // The 3-4-5 box with h = (1, 2, 3): reach x = 3/5 + 2·4/5 = 11/5,
    // y = 4/5 + 2·3/5 = 2, z = 3; radius √14 (IEEE sqrt is correctly rounded).
    let b = obb([1.0, -1.0, 0.5], [1.0, 2.0, 3.0], Q345);
    let a = bounds_box(&b).unwrap();
    let aabb = a.aabb.unwrap();
    // 1 − 11/5 = −6/5 and 1 + 11/5 = 16/5: correctly rounded literals.
    close_v(aabb.min, [-1.2, -3.0, -2.5], "min");
    close_v(aabb.max, [3.2, 1.0, 3.5], "max");
    let ball = a.sphere.unwrap();
    close_v(ball.center, [1.0, -1.0, 0.5], "centre");
    close(ball.radius, 14f64.sqrt(), "radius");
    // A point box: min = max = centre, radius 0.
    // (The corners are the centre itself, exact inputs: compared bit for bit.)
    let a = bounds_box(&obb([1.0, 2.0, 3.0], [0.0; 3], [0.3, 0.1, 0.2, 0.7])).unwrap();
    assert_eq!(a.aabb.unwrap(), Aabb { min: [1.0, 2.0, 3.0], max: [1.0, 2.0, 3.0] });
    close(a.sphere.unwrap().radius, 0.0, "radius");
}

/// `−√41/82`, correctly rounded: `float(-Decimal(41).sqrt()/82)` at 80 digits
/// in CPython (its Decimal → float conversion is correctly rounded).
const MINUS_SQRT41_OVER_82: f64 = -0.07808688094430304;

#[test]
fn referee_overlap_box_box_faces_touching_and_gaps() {
    let a = unit_box();
    // (b, overlaps, margin, what): margins by hand along the tightest axis.
    let cases = [
        (obb([1.5, 0.0, 0.0], [1.0; 3], IDENTITY), true, 0.5, "sunk half a unit on x"),
        (obb([2.0, 0.0, 0.0], [1.0; 3], IDENTITY), true, 0.0, "touching faces"),
        (obb([2.0, 2.0, 2.0], [1.0; 3], IDENTITY), true, 0.0, "touching corners"),
        (obb([2.25, 0.0, 0.0], [1.0; 3], IDENTITY), false, -0.25, "a quarter apart on x"),
        // The 3-4-5 box centred at (3, 4, 0)·(4/5)… its axis R·x points at a's
        // centre; a's projection on R·x is 7/5, b's 1: centre distance 3
        // (centre (9/5, 12/5) is not exact, so (3, 4, 0) at distance 5): gap
        // 5 − 1 − 7/5 = 13/5 along R·x; along x: 3 − 1 − (3/5 + 4/5) = 3/5,
        // along y: 4 − 1 − 7/5 = 8/5. The widest gap is 13/5.
        (obb([3.0, 4.0, 0.0], [1.0; 3], Q345), false, -2.6, "rotated, apart"),
        // Nested: the inner box's depth is its distance out: 1 + 0.25 on x.
        (obb([0.0; 3], [0.25, 0.5, 0.75], IDENTITY), true, 1.25, "nested"),
    ];
    for (b, want, margin, what) in cases {
        assert_eq!(overlap_box_box(&a, &b).unwrap(), want, "{what}");
        assert_eq!(overlap_box_box(&b, &a).unwrap(), want, "{what}, swapped");
        close(overlap_margin_box_box(&a, &b).unwrap(), margin, what);
        close(overlap_margin_box_box(&b, &a).unwrap(), margin, what);
    }
    assert!(positive(overlap_margin_box_box(&a, &obb([2.0, 0.0, 0.0], [1.0; 3], IDENTITY)).unwrap()));
}

#[test]
fn referee_overlap_box_box_only_an_edge_axis_separates() {
    // b: a segment (h = (5/2, 0, 0)) along R·x = (3/5, 12/25, 16/25), R of
    // q = [4, 2, −1, 2] (n² = 25; q is [2,1,0,0]·[2,0,0,1]), centred at
    // (−1/2, 3/2, 0); a: the unit cube. On a's axes the projections overlap
    // (x: 2, y: 7/10, z: 13/5 of overlap), on b's too (19/5, 7/10, 1/5), and on
    // every cross axis but L = z × R·x = (−12/25, 3/5, 0): a's radius
    // 12/25 + 3/5 = 27/25, b's 0, |L·c| = 6/25 + 9/10 = 57/50: a gap of 3/50,
    // over ‖L‖ = √369/25: 3/(2√369) = 1/(2√41) = √41/82. (Every axis checked
    // with Python's fractions.)
    let a = unit_box();
    let b = obb([-0.5, 1.5, 0.0], [2.5, 0.0, 0.0], [4.0, 2.0, -1.0, 2.0]);
    assert!(!overlap_box_box(&a, &b).unwrap());
    close(overlap_margin_box_box(&a, &b).unwrap(), MINUS_SQRT41_OVER_82, "margin");
    // Moved toward the cube by 1/2 on y, the gap 3/50 turns into an overlap
    // along L (|L·c| = 57/50 − 3/10 < 27/25), and it still overlaps on every
    // other axis (their overlaps only change by at most 1/2·|L_y|).
    let b2 = obb([-0.5, 1.0, 0.0], [2.5, 0.0, 0.0], [4.0, 2.0, -1.0, 2.0]);
    assert!(overlap_box_box(&a, &b2).unwrap());
    assert!(positive(overlap_margin_box_box(&a, &b2).unwrap()));
}

#[test]
fn referee_overlap_box_aabb() {
    let cube = Aabb { min: [-1.0; 3], max: [1.0; 3] };
    // The same as against the unit box: touching, sunk, apart.
    let cases = [
        (obb([2.0, 0.0, 0.0], [1.0; 3], IDENTITY), true, 0.0, "touching"),
        (obb([1.5, 0.0, 0.0], [1.0; 3], IDENTITY), true, 0.5, "sunk"),
        (obb([3.0, 4.0, 0.0], [1.0; 3], Q345), false, -2.6, "rotated, apart"),
    ];
    for (b, want, margin, what) in cases {
        assert_eq!(overlap_box_aabb(&b, &cube).unwrap(), want, "{what}");
        close(overlap_margin_box_aabb(&b, &cube).unwrap(), margin, what);
    }
    // A flat aabb (z from 0 to 0) under a box resting on it.
    let sheet = Aabb { min: [-1.0, -1.0, 0.0], max: [1.0, 1.0, 0.0] };
    assert!(overlap_box_aabb(&obb([0.0, 0.0, 1.0], [1.0; 3], Q345), &sheet).unwrap());
    let above = obb([0.0, 0.0, f64::from_bits(1f64.to_bits() + 1)], [1.0; 3], Q345);
    assert!(!overlap_box_aabb(&above, &sheet).unwrap());
    close(overlap_margin_box_aabb(&above, &sheet).unwrap(), -f64::EPSILON, "one ulp above");
    // Refusals of the aabb.
    let inverted = Aabb { min: [1.0, 0.0, 0.0], max: [0.0, 1.0, 1.0] };
    assert_eq!(overlap_box_aabb(&unit_box(), &inverted), Err(RefereeError::InvertedAabb { field: "b.min" }));
    let nan = Aabb { min: [0.0; 3], max: [f64::NAN, 1.0, 1.0] };
    assert_eq!(overlap_box_aabb(&unit_box(), &nan), Err(RefereeError::NonFinite { field: "b.max" }));
}

#[test]
fn referee_boxes_refuse_malformed_input() {
    let s = sphere([0.0; 3], 1.0);
    let ground = Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 };
    let bad_h = obb([0.0; 3], [1.0, -1.0, 1.0], IDENTITY);
    let zero_q = obb([0.0; 3], [1.0; 3], [0.0, -0.0, 0.0, 0.0]);
    let nan_c = obb([0.0, f64::NAN, 0.0], [1.0; 3], IDENTITY);
    let inf_q = obb([0.0; 3], [1.0; 3], [1.0, f64::INFINITY, 0.0, 0.0]);
    let inf_h = obb([0.0; 3], [f64::INFINITY, 1.0, 1.0], IDENTITY);
    assert_eq!(contact_sphere_box(&s, &bad_h), Err(RefereeError::NegativeHalfExtent { field: "b.half_extents" }));
    assert_eq!(contact_sphere_box(&s, &zero_q), Err(RefereeError::ZeroRotation { field: "b.rotation" }));
    assert_eq!(contact_sphere_box(&s, &nan_c), Err(RefereeError::NonFinite { field: "b.center" }));
    assert_eq!(contact_margin_sphere_box(&s, &inf_q), Err(RefereeError::NonFinite { field: "b.rotation" }));
    assert_eq!(contact_box_plane(&inf_h, &ground), Err(RefereeError::NonFinite { field: "a.half_extents" }));
    assert_eq!(contact_box_plane(&bad_h, &ground), Err(RefereeError::NegativeHalfExtent { field: "a.half_extents" }));
    assert_eq!(contact_region_box_plane(&zero_q, &ground), Err(RefereeError::ZeroRotation { field: "a.rotation" }));
    let zero_n = Plane { normal: [0.0; 3], offset: 1.0 };
    assert_eq!(contact_box_plane(&unit_box(), &zero_n), Err(RefereeError::ZeroNormal { field: "b.normal" }));
    assert_eq!(
        contact_sphere_box(&sphere([0.0; 3], -1.0), &unit_box()),
        Err(RefereeError::NegativeRadius { field: "a.radius" })
    );
    let seg = Segment { start: [0.0; 3], end: [f64::NAN, 0.0, 0.0] };
    assert_eq!(intersect_segment_box(&seg, &unit_box()), Err(RefereeError::NonFinite { field: "a.end" }));
    assert_eq!(
        intersect_segment_box(&Segment { start: [0.0; 3], end: [1.0; 3] }, &zero_q),
        Err(RefereeError::ZeroRotation { field: "b.rotation" })
    );
    assert_eq!(bounds_box(&bad_h), Err(RefereeError::NegativeHalfExtent { field: "a.half_extents" }));
    assert_eq!(overlap_box_box(&unit_box(), &zero_q), Err(RefereeError::ZeroRotation { field: "b.rotation" }));
    assert_eq!(overlap_margin_box_box(&nan_c, &unit_box()), Err(RefereeError::NonFinite { field: "a.center" }));
    let refused = overlap_margin_box_aabb(&bad_h, &Aabb { min: [0.0; 3], max: [1.0; 3] }).unwrap_err();
    assert_eq!(refused.to_string(), "a.half_extents: negative half-extent");
    // −0.0 is a zero half-extent, not a negative one: a flat box.
    assert!(contact_sphere_box(&s, &obb([0.0; 3], [1.0, 1.0, -0.0], IDENTITY)).is_ok());
}

#[test]
fn referee_boxes_huge_and_tiny_scales() {
    // The rotated sphere–box case scaled by 2^±1000 (exact scalings): point and
    // normal scale, depth s. And box–plane and overlap the same way.
    for s in [2f64.powi(1000), 2f64.powi(-1000), 2f64.powi(-1070)] {
        let b = obb([0.0; 3], [s; 3], Q345);
        let (k, deg) = contact(contact_sphere_box(&sphere([3.0 * s, 4.0 * s, 0.0], 5.0 * s), &b), "scaled");
        assert!(!deg);
        close(k.depth, s, "depth");
        close_v(k.normal, [0.6, 0.8, 0.0], "normal");
        let ground = Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 };
        let (k, _) = contact(contact_box_plane(&obb([0.0, 0.0, 0.5 * s], [s; 3], Q345), &ground), "plane");
        close(k.depth, 0.5 * s, "plane depth");
        let other = obb([2.25 * s, 0.0, 0.0], [s; 3], IDENTITY);
        assert!(!overlap_box_box(&obb([0.0; 3], [s; 3], IDENTITY), &other).unwrap());
        close(overlap_margin_box_box(&obb([0.0; 3], [s; 3], IDENTITY), &other).unwrap(), -0.25 * s, "gap");
    }
    // Coordinates near 1e300 and a subnormal quaternion: finite answers.
    let big = obb([1e300, -1e300, 1e300], [1e300, 2e300, 5e299], [5e-324, 1e-320, 0.0, 3e-322]);
    let k = contact_sphere_box(&sphere([3e300, 0.0, 0.0], 1e300), &big).unwrap();
    if let Some(k) = k.contact {
        assert!(k.depth.is_finite() && k.point.iter().chain(&k.normal).all(|x| x.is_finite()));
    }
    assert!(contact_margin_sphere_box(&sphere([3e300, 0.0, 0.0], 1e300), &big).unwrap().is_finite());
    let seg = Segment { start: [-1e308, -1e308, 1e300], end: [1e308, 1e308, 1e300] };
    let r = intersect_segment_box(&seg, &big).unwrap();
    if let Some(h) = r.hit {
        assert!(h.t.is_finite() && h.point.iter().all(|x| x.is_finite()));
    }
    // An exact answer beyond f64's range rounds to ±∞ (the referee's documented
    // behaviour, as IEEE rounding): a box reaching 1.5e308 + 1e308.
    let huge = obb([1.5e308, 0.0, 0.0], [1e308, 1.0, 1.0], IDENTITY);
    let aabb = bounds_box(&huge).unwrap().aabb.unwrap();
    assert!(aabb.max[0].is_infinite() && aabb.max[0] > 0.0, "{aabb:?}");
    // 1.5e308 − 1e308 is exact in f64 (Sterbenz), so it is the correct rounding.
    close(aabb.min[0], 1.5e308 - 1e308, "min");
    // ‖h‖ of the largest half-extents: √3·MAX overflows, the radius is +∞.
    let ball = bounds_box(&obb([0.0; 3], [f64::MAX; 3], IDENTITY)).unwrap().sphere.unwrap();
    assert!(ball.radius.is_infinite() && ball.radius > 0.0, "{ball:?}");
    // Tiny: a subnormal box touching a subnormal sphere.
    let t = 5e-324;
    let (k, _) = contact(contact_sphere_box(&sphere([2.0 * t, 0.0, 0.0], t), &obb([0.0; 3], [t; 3], IDENTITY)), "tiny");
    close(k.depth, 0.0, "tiny depth");
    close_v(k.point, [t, 0.0, 0.0], "tiny point");
}

/// Loops against independent `f64` evaluations and sampling, for sanity.
mod sampled {
    use super::*;
    use crate::geom::Capsule;
    use crate::referee::capsule::{contact_capsule_capsule, contact_capsule_plane, contact_sphere_capsule};
    use crashtest_core::geom::rotation_matrix;
    use proptest::prelude::*;

    /// Absolute agreement asked of the referee's answers with a direct `f64`
    /// evaluation of the same formula on inputs of size ≤ 8 (so every
    /// intermediate is ≤ ~100): a few dozen roundings of ≤ 100·2⁻⁵³ each is
    /// ~1e-12; 1e-9 leaves room and is still far below any definitional error
    /// (which shows at the size of the inputs). Cases whose `f64` decision is
    /// within this of its boundary are not compared.
    const F64_TOL: f64 = 1e-9;

    /// Iterations of alternating projections between two boxes (each pass
    /// projects onto one box then the other; the distance they reach
    /// converges linearly to the boxes' distance, at a rate set by the angle
    /// between them: two flat boxes meeting at a shallow angle were still
    /// 7e-6 apart after 2,000 passes and 1.5e-15 after 10,000 — the saved
    /// regression case). The passes stop early once the gap is below
    /// [`CONVERGED_GAP`].
    const PROJECTIONS: usize = 20_000;

    /// A gap at which alternating projections have shown two boxes to meet,
    /// far below the overlap test's 1e-6: no further pass is needed.
    const CONVERGED_GAP: f64 = 1e-12;

    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![(-3i8..=3).prop_map(f64::from), -4.0..4.0f64]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coord(), coord(), coord()]
    }

    fn half() -> impl Strategy<Value = f64> {
        prop_oneof![(0u8..=2).prop_map(f64::from), 0.0..2.0f64]
    }

    fn quaternion() -> impl Strategy<Value = [f64; 4]> {
        prop_oneof![
            Just(IDENTITY),
            Just(Q345),
            [
                (-2i8..=2).prop_map(f64::from),
                (-2i8..=2).prop_map(f64::from),
                (-2i8..=2).prop_map(f64::from),
                (-2i8..=2).prop_map(f64::from)
            ],
            [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64],
        ]
        .prop_filter("non-zero", |q| q.iter().any(|x| *x != 0.0))
    }

    fn oriented() -> impl Strategy<Value = OrientedBox> {
        (point(), [half(), half(), half()], quaternion()).prop_map(|(c, h, q)| obb(c, h, q))
    }

    fn local(b: &OrientedBox, x: P3) -> P3 {
        let r = rotation_matrix(b.rotation);
        let d = [x[0] - b.center[0], x[1] - b.center[1], x[2] - b.center[2]];
        std::array::from_fn(|i| (0..3).map(|k| r[k][i] * d[k]).sum())
    }

    fn world(b: &OrientedBox, u: P3) -> P3 {
        let r = rotation_matrix(b.rotation);
        std::array::from_fn(|i| b.center[i] + (0..3).map(|k| r[i][k] * u[k]).sum::<f64>())
    }

    fn project(b: &OrientedBox, x: P3) -> P3 {
        let u = local(b, x);
        world(b, std::array::from_fn(|i| u[i].clamp(-b.half_extents[i], b.half_extents[i])))
    }

    fn dist(x: P3, y: P3) -> f64 {
        ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
    }

    /// The sphere–box signed depth in `f64`, straight from the format's words.
    fn depth_f64(s: &Sphere, b: &OrientedBox) -> f64 {
        let u = local(b, s.center);
        let h = b.half_extents;
        if (0..3).all(|i| u[i].abs() <= h[i]) {
            s.radius + (0..3).map(|i| h[i] - u[i].abs()).fold(f64::INFINITY, f64::min)
        } else {
            let w: P3 = std::array::from_fn(|i| u[i] - u[i].clamp(-h[i], h[i]));
            s.radius - (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt()
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn referee_sphere_box_matches_the_f64_formula(c in point(), r in half(), b in oriented()) {
            let s = Sphere { center: c, radius: r };
            let m = contact_margin_sphere_box(&s, &b).unwrap();
            let want = depth_f64(&s, &b);
            prop_assert!((m - want).abs() <= F64_TOL, "margin {} vs f64 {}", m, want);
            let a = contact_sphere_box(&s, &b).unwrap();
            prop_assert_eq!(a.contact.is_some(), positive(m), "sign of the margin is the decision");
            if let Some(k) = a.contact {
                prop_assert_eq!(k.depth.to_bits(), m.to_bits(), "depth is the margin");
                let n2 = k.normal.iter().map(|x| x * x).sum::<f64>();
                prop_assert!((n2 - 1.0).abs() <= F64_TOL, "unit normal");
                // The point lies on the box's surface (in the closed box, on a face).
                let u = local(&b, k.point);
                prop_assert!((0..3).all(|i| u[i].abs() <= b.half_extents[i] + F64_TOL), "point in the box");
                prop_assert!((0..3).any(|i| (u[i].abs() - b.half_extents[i]).abs() <= F64_TOL), "point on a face");
            }
        }

        #[test]
        fn referee_box_plane_matches_corner_sampling(b in oriented(), n in point(), d in coord()) {
            prop_assume!(n.iter().any(|x| *x != 0.0));
            let p = Plane { normal: n, offset: d };
            let len = dist(n, [0.0; 3]);
            // The lowest of the eight corners, in f64.
            let lowest = (0..8).map(|k| {
                let u = std::array::from_fn(|i| if k >> i & 1 == 1 { b.half_extents[i] } else { -b.half_extents[i] });
                let x = world(&b, u);
                (n[0] * x[0] + n[1] * x[1] + n[2] * x[2]) / len
            }).fold(f64::INFINITY, f64::min);
            let want = d / len - lowest;
            let m = contact_margin_box_plane(&b, &p).unwrap();
            prop_assert!((m - want).abs() <= F64_TOL, "margin {} vs f64 {}", m, want);
            let a = contact_box_plane(&b, &p).unwrap();
            prop_assert_eq!(a.contact.is_some(), positive(m));
            let region = contact_region_box_plane(&b, &p).unwrap();
            prop_assert_eq!(region.is_some(), a.contact.is_some());
            if let (Some(k), Some(region)) = (a.contact, region) {
                prop_assert!(matches!(region.len(), 1 | 2 | 4));
                if region.len() == 1 {
                    // The same rational rounded by the same code: equal bits.
                    prop_assert_eq!(region[0].map(f64::to_bits), k.point.map(f64::to_bits), "a unique point is the answer's");
                }
                for v in &region {
                    let on = (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) / len - d / len;
                    prop_assert!(on.abs() <= F64_TOL, "region vertex on the plane: {}", on);
                }
            }
        }

        #[test]
        fn referee_overlap_box_box_matches_alternating_projections(a in oriented(), b in oriented()) {
            // x ∈ a, y ∈ b always, so ‖x − y‖ bounds the distance from above;
            // it converges to the distance.
            let mut y = b.center;
            let mut x = a.center;
            for _ in 0..PROJECTIONS {
                x = project(&a, y);
                y = project(&b, x);
                if dist(x, y) <= CONVERGED_GAP {
                    break;
                }
            }
            let gap = dist(x, y);
            let overlap = overlap_box_box(&a, &b).unwrap();
            let m = overlap_margin_box_box(&a, &b).unwrap();
            prop_assert_eq!(overlap, positive(m), "sign of the margin is the decision");
            prop_assert_eq!(overlap, overlap_box_box(&b, &a).unwrap(), "symmetric");
            if overlap {
                // Alternating projections crawl where a flat box meets another
                // at a shallow angle (a fresh-clone run met one 2.1e-6 apart
                // after every pass): there the exact signed distance — another
                // method, GJK and separating axes on the exact corners — decides.
                let touching = || {
                    crate::referee::distance::distance(crate::geom::Solid::Box(&a), crate::geom::Solid::Box(&b))
                        .is_ok_and(|d| d.distance <= 0.0)
                };
                prop_assert!(gap <= 1e-6 || touching(), "overlapping boxes {} apart", gap);
            } else {
                // The margin is minus a lower bound of the distance.
                prop_assert!(-m <= gap + F64_TOL, "margin {} beyond the distance {}", m, gap);
            }
            // A sampled point of a deep inside b proves overlap.
            for k in 0..27 {
                let u = std::array::from_fn(|i| f64::from((k / 3i32.pow(i as u32)) % 3 - 1) * a.half_extents[i]);
                let v = local(&b, world(&a, u));
                if (0..3).all(|i| v[i].abs() < b.half_extents[i] - F64_TOL) {
                    prop_assert!(overlap, "a's sample point {:?} is inside b", u);
                }
            }
        }

        #[test]
        fn referee_segment_box_matches_f64_slabs(p0 in point(), p1 in point(), b in oriented()) {
            let s = Segment { start: p0, end: p1 };
            let a = intersect_segment_box(&s, &b).unwrap();
            let u0 = local(&b, p0);
            let u1 = local(&b, p1);
            let h = b.half_extents;
            let e: P3 = std::array::from_fn(|i| u1[i] - u0[i]);
            // f64 slabs: entering and leaving times of each slab.
            let (mut t_in, mut t_out) = (0.0f64, 1.0f64);
            let mut clear = true;
            for i in 0..3 {
                if e[i].abs() < F64_TOL {
                    clear &= (u0[i].abs() - h[i]).abs() > F64_TOL;
                    if u0[i].abs() > h[i] { t_in = f64::INFINITY; }
                    continue;
                }
                let (lo, hi) = ((-h[i] - u0[i]) / e[i], (h[i] - u0[i]) / e[i]);
                t_in = t_in.max(lo.min(hi));
                t_out = t_out.min(lo.max(hi));
            }
            if clear && (t_in - t_out).abs() > F64_TOL && t_in.abs() > F64_TOL {
                prop_assert_eq!(a.hit.is_some(), t_in <= t_out, "decision: f64 t_in {} t_out {}", t_in, t_out);
                if let Some(hit) = a.hit {
                    prop_assert!((hit.t - t_in).abs() <= F64_TOL, "t {} vs f64 {}", hit.t, t_in);
                }
            }
            if let Some(hit) = a.hit {
                let v = local(&b, hit.point);
                prop_assert!((0..3).all(|i| v[i].abs() <= h[i] + F64_TOL), "hit point in the box");
            }
        }
    }

    /// Random cases in the stage-agreement test.
    const STAGE_CASES: usize = 600;

    /// The share of generic random pairs the floating-point stage must settle
    /// alone (decision and margin): it is meant to take nearly all clear
    /// cases; a stage that certifies nothing would still be correct but
    /// useless.
    const FAST_SHARE: f64 = 0.5;

    /// A deterministic generator (SplitMix64) for the stage test.
    struct Mix(u64);

    impl Mix {
        fn next(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        }

        /// In `[−s, s)`, on a grid of `1/4` half the time (touching and
        /// parallel cases), else any double.
        fn coord(&mut self, s: f64) -> f64 {
            let x = (self.next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
            if self.next().is_multiple_of(2) { (x * s * 4.0).round() / 4.0 } else { x * s }
        }

        fn rotation(&mut self) -> [f64; 4] {
            match self.next() % 4 {
                0 => IDENTITY,
                1 => Q345,
                _ => loop {
                    let q = [self.coord(1.0), self.coord(1.0), self.coord(1.0), self.coord(1.0)];
                    if q.iter().any(|x| *x != 0.0) {
                        break q;
                    }
                },
            }
        }

        fn oriented(&mut self, scale: f64) -> OrientedBox {
            let h = std::array::from_fn(|_| if self.next().is_multiple_of(8) { 0.0 } else { self.coord(scale).abs() });
            obb(std::array::from_fn(|_| self.coord(2.0 * scale)), h, self.rotation())
        }
    }

    #[test]
    fn referee_box_overlap_stage_agrees_with_the_exact_stage() {
        use crate::referee::stage::{Stage, stage_counts_on_this_thread};
        let counts = || {
            let c = stage_counts_on_this_thread();
            let (_, fast, exact) = c.into_iter().find(|(s, _, _)| *s == Stage::BoxOverlap).unwrap();
            (fast, exact)
        };
        let mut mix = Mix(20261205);
        let before = counts();
        for case in 0..STAGE_CASES {
            let scale = [1.0, 1e-300, 1e300, 3.0][case % 4];
            let (a, b) = (mix.oriented(scale), mix.oriented(scale));
            let aabb = {
                let (p, q) = (mix.oriented(scale).center, mix.oriented(scale).center);
                Aabb { min: std::array::from_fn(|i| p[i].min(q[i])), max: std::array::from_fn(|i| p[i].max(q[i])) }
            };
            let staged = (
                overlap_box_box(&a, &b).unwrap(),
                overlap_margin_box_box(&a, &b).unwrap().to_bits(),
                overlap_box_aabb(&a, &aabb).unwrap(),
                overlap_margin_box_aabb(&a, &aabb).unwrap().to_bits(),
            );
            let exact = exact_only(|| {
                (
                    overlap_box_box(&a, &b).unwrap(),
                    overlap_margin_box_box(&a, &b).unwrap().to_bits(),
                    overlap_box_aabb(&a, &aabb).unwrap(),
                    overlap_margin_box_aabb(&a, &aabb).unwrap().to_bits(),
                )
            });
            assert_eq!(staged, exact, "case {case}: {a:?} {b:?} {aabb:?}");
        }
        let after = counts();
        let (fast, exact) = (after.0 - before.0, after.1 - before.1);
        let share = fast as f64 / (fast + exact) as f64;
        assert!(share >= FAST_SHARE, "the fast stage settled {fast} of {}", fast + exact);
        // Touching boxes, identical boxes and exactly parallel edges reach the
        // exact stage or are certified; either way the same answers.
        for (a, b) in [
            (unit_box(), obb([2.0, 0.0, 0.0], [1.0; 3], IDENTITY)),
            (unit_box(), unit_box()),
            (obb([0.0; 3], [1.0; 3], Q345), obb([0.0, 0.0, 2.0], [1.0; 3], Q345)),
            (unit_box(), obb([-0.5, 1.5, 0.0], [2.5, 0.0, 0.0], [4.0, 2.0, -1.0, 2.0])),
        ] {
            let staged = (overlap_box_box(&a, &b).unwrap(), overlap_margin_box_box(&a, &b).unwrap().to_bits());
            let exact =
                exact_only(|| (overlap_box_box(&a, &b).unwrap(), overlap_margin_box_box(&a, &b).unwrap().to_bits()));
            assert_eq!(staged, exact, "{a:?} {b:?}");
        }
    }

    /// The share of the random separated pairs (the exact stage says apart)
    /// that the apart stage must certify alone: the shapes are spread over
    /// four times their size, so most separated pairs are clearly apart, and a
    /// stage that certified none would be correct but useless.
    const APART_SHARE: f64 = 0.5;

    #[test]
    fn referee_apart_stage_agrees_with_the_exact_stage() {
        use crate::referee::stage::{Stage, stage_counts_on_this_thread};
        let fast_count = || {
            let c = stage_counts_on_this_thread();
            c.into_iter().find(|(s, _, _)| *s == Stage::ShapesApart).unwrap().1
        };
        let mut mix = Mix(20261206);
        let (mut separated, before) = (0u64, fast_count());
        for case in 0..STAGE_CASES {
            let scale = [1.0, 1e-300, 1e300, 3.0][case % 4];
            let b = mix.oriented(scale);
            let mut point = || std::array::from_fn::<f64, 3, _>(|_| mix.coord(2.0 * scale));
            let (p0, p1, p2, p3, p4) = (point(), point(), point(), point(), point());
            let r = (mix.coord(scale) / 2.0).abs();
            let s = sphere(p0, r);
            let ca = Capsule { start: p1, end: if case % 5 == 0 { p1 } else { p2 }, radius: r };
            let cb = Capsule { start: p3, end: p4, radius: (mix.coord(scale) / 2.0).abs() };
            let plane = Plane { normal: [mix.coord(1.0), mix.coord(1.0), 1.0], offset: mix.coord(scale) };
            let seg = Segment { start: p1, end: if case % 7 == 0 { p1 } else { p3 } };
            let all = || {
                (
                    contact_sphere_box(&s, &b).unwrap(),
                    contact_box_plane(&b, &plane).unwrap(),
                    contact_sphere_capsule(&s, &ca).unwrap(),
                    contact_capsule_capsule(&ca, &cb).unwrap(),
                    contact_capsule_plane(&ca, &plane).unwrap(),
                    intersect_segment_box(&seg, &b).unwrap(),
                )
            };
            let staged = all();
            let exact = exact_only(all);
            assert_eq!(staged, exact, "case {case}: {s:?} {b:?} {ca:?} {cb:?} {plane:?} {seg:?}");
            separated +=
                [&exact.0, &exact.1, &exact.2, &exact.3, &exact.4].iter().filter(|a| a.contact.is_none()).count()
                    as u64
                    + u64::from(exact.5.hit.is_none());
        }
        let fast = fast_count() - before;
        assert!(
            fast as f64 >= APART_SHARE * separated as f64,
            "the apart stage certified {fast} of {separated} separated pairs"
        );
        // Touching shapes reach the exact stage: the same answers.
        let touching = || {
            (
                contact_sphere_box(&sphere([2.0, 0.0, 0.0], 1.0), &unit_box()).unwrap(),
                contact_box_plane(&unit_box(), &Plane { normal: [0.0, 0.0, 1.0], offset: -1.0 }).unwrap(),
                intersect_segment_box(&Segment { start: [1.0, 2.0, 0.0], end: [1.0, -2.0, 0.0] }, &unit_box()).unwrap(),
                contact_capsule_capsule(
                    &Capsule { start: [0.0; 3], end: [1.0, 0.0, 0.0], radius: 0.5 },
                    &Capsule { start: [0.0, 1.0, 0.0], end: [1.0, 1.0, 0.0], radius: 0.5 },
                )
                .unwrap(),
            )
        };
        let staged = touching();
        assert_eq!(staged, exact_only(touching));
        assert!(staged.0.contact.is_some() && staged.1.contact.is_some() && staged.2.hit.is_some());
        assert!(staged.3.contact.is_some());
    }

    #[test]
    fn referee_boxes_answer_the_same_with_the_stages_off() {
        // Contact has a floating-point stage for apart shapes and overlap one
        // for its decision: the switch must not change a bit.
        let b = obb([0.25, -0.5, 1.0], [1.0, 0.5, 2.0], [0.9, 0.1, -0.3, 0.2]);
        let s = sphere([1.5, 0.5, 2.5], 1.0);
        let both =
            || (contact_sphere_box(&s, &b), contact_margin_sphere_box(&s, &b), overlap_margin_box_box(&b, &unit_box()));
        assert_eq!(both(), exact_only(both));
    }
}
