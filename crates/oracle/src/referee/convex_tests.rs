//! Hand-derived cases of box–box, box–triangle, capsule–box and
//! capsule–triangle contact, and cross-checks against the sphere pairs (a
//! capsule with a zero-length axis is a sphere, answered by other code).
//!
//! Every expected number is exact in `f64` by construction (dyadic inputs,
//! 3-4-5 rotations whose entries cancel), so answers are compared bit for bit.

use super::*;
use crate::geom::Sphere;
use crate::referee::boxes::tests::{close, close_v};
use crate::referee::exact::within_ulps;

/// The referee's numbers are correctly rounded and these cases' exact
/// values are doubles: 0 ulps apart.
const EXACT_ULPS: u64 = 0;

fn close_region(got: &[P3], want: &[P3]) {
    assert_eq!(got.len(), want.len(), "{got:?} against {want:?}");
    for (g, w) in got.iter().zip(want) {
        close_v(*g, *w, "region");
    }
}
use proptest::prelude::*;

fn bx(center: P3, h: f64, rotation: [f64; 4]) -> OrientedBox {
    OrientedBox { center, half_extents: [h, h, h], rotation }
}

const ID: [f64; 4] = [1.0, 0.0, 0.0, 0.0];
/// The 3-4-5 rotation about z: columns (3/5, 4/5, 0), (−4/5, 3/5, 0), z.
const Z345: [f64; 4] = [2.0, 0.0, 0.0, 1.0];
/// The 3-4-5 rotation about x: columns x, (0, 3/5, 4/5), (0, −4/5, 3/5).
const X345: [f64; 4] = [2.0, 1.0, 0.0, 0.0];

fn contact(a: ContactAnswer) -> (Contact, bool) {
    (a.contact.expect("a contact"), a.degenerate)
}

#[test]
fn boxes_face_on_face() {
    let (a, b) = (bx([1.5, 0.0, 0.0], 1.0, ID), bx([0.0; 3], 1.0, ID));
    let (c, degenerate) = contact(contact_box_box(&a, &b).unwrap());
    close_v(c.point, [1.0, 0.0, 0.0], "c.point");
    close_v(c.normal, [1.0, 0.0, 0.0], "c.normal");
    close(c.depth, 0.5, "c.depth");
    assert!(!degenerate);
    let region = contact_region_box_box(&a, &b).unwrap().unwrap();
    assert_eq!(region.len(), 4, "the face x = 1: {region:?}");
    assert!(region.iter().all(|p| within_ulps(p[0], 1.0, EXACT_ULPS)
        && within_ulps(p[1].abs(), 1.0, EXACT_ULPS)
        && within_ulps(p[2].abs(), 1.0, EXACT_ULPS)));
    close(contact_margin_box_box(&a, &b).unwrap(), 0.5, "margin");
}

#[test]
fn boxes_touching_and_apart() {
    let b = bx([0.0; 3], 1.0, ID);
    let touching = bx([2.0, 0.0, 0.0], 1.0, ID);
    let (c, _) = contact(contact_box_box(&touching, &b).unwrap());
    close_v(c.point, [1.0, 0.0, 0.0], "c.point");
    close(c.depth, 0.0, "c.depth");
    let apart = bx([2.5, 0.0, 0.0], 1.0, ID);
    assert_eq!(contact_box_box(&apart, &b).unwrap(), ContactAnswer { contact: None, degenerate: false });
    close(contact_margin_box_box(&apart, &b).unwrap(), -0.5, "margin");
    assert_eq!(contact_region_box_box(&apart, &b).unwrap(), None);
}

#[test]
fn concentric_boxes_are_degenerate_with_the_first_axis() {
    let (a, b) = (bx([0.0; 3], 1.0, ID), bx([0.0; 3], 1.0, ID));
    let (c, degenerate) = contact(contact_box_box(&a, &b).unwrap());
    assert!(degenerate);
    close_v(c.normal, [1.0, 0.0, 0.0], "c.normal");
    close(c.depth, 2.0, "c.depth");
    close_v(c.point, [1.0, 0.0, 0.0], "c.point");
}

#[test]
fn a_box_on_a_turned_box_rests_on_an_octagon() {
    // b turned by the 3-4-5 rotation about z; a 0.25 into its top face.
    let (a, b) = (bx([0.0, 0.0, 1.75], 1.0, ID), bx([0.0; 3], 1.0, Z345));
    let (c, degenerate) = contact(contact_box_box(&a, &b).unwrap());
    close_v(c.normal, [0.0, 0.0, 1.0], "c.normal");
    close(c.depth, 0.25, "c.depth");
    assert!(!degenerate);
    let region = contact_region_box_box(&a, &b).unwrap().unwrap();
    assert_eq!(region.len(), 8, "two squares turned against each other: {region:?}");
    assert!(region.iter().all(|p| within_ulps(p[2], 1.0, EXACT_ULPS)));
    // Symmetric under a half turn: the middle is the centre of the face.
    close_v(c.point, [0.0, 0.0, 1.0], "c.point");
}

#[test]
fn boxes_edge_on_edge() {
    // a turned about x (its lowest edge runs along x at z = −1/5), b about z
    // (its highest edge along z at x = −1/5); along y they overlap by
    // 14/5 − 11/4 = 1/20, the least push, on the axis a_x × b_z = −y.
    let (a, b) = (bx([0.0, 2.75, 0.0], 1.0, X345), bx([0.0; 3], 1.0, Z345));
    let (c, degenerate) = contact(contact_box_box(&a, &b).unwrap());
    close_v(c.normal, [0.0, 1.0, 0.0], "c.normal");
    close(c.depth, 0.05, "c.depth");
    assert!(!degenerate);
    close_v(c.point, [-0.2, 1.4, -0.2], "c.point");
    assert_eq!(contact_region_box_box(&a, &b).unwrap().unwrap().len(), 1);
}

#[test]
fn flat_boxes_in_one_plane_touch_without_a_normal() {
    let flat = |c: P3| OrientedBox { center: c, half_extents: [1.0, 1.0, 0.0], rotation: ID };
    let (c, degenerate) = contact(contact_box_box(&flat([1.0, 0.0, 0.0]), &flat([0.0; 3])).unwrap());
    assert!(degenerate, "±z both push them apart by 0");
    close(c.depth, 0.0, "c.depth");
    close_v(c.normal, [0.0, 0.0, 1.0], "c.normal");
}

#[test]
fn a_box_into_a_triangle() {
    let t = Triangle { vertices: [[-4.0, -4.0, 0.0], [4.0, -4.0, 0.0], [0.0, 4.0, 0.0]] };
    let a = bx([0.0, 0.0, 0.75], 1.0, ID);
    let (c, degenerate) = contact(contact_box_triangle(&a, &t).unwrap());
    close_v(c.normal, [0.0, 0.0, 1.0], "c.normal");
    close(c.depth, 0.25, "c.depth");
    close_v(c.point, [0.0, 0.0, 0.0], "c.point");
    assert!(!degenerate);
    assert_eq!(contact_region_box_triangle(&a, &t).unwrap().unwrap().len(), 4);
    let above = bx([0.0, 0.0, 1.5], 1.0, ID);
    assert_eq!(contact_box_triangle(&above, &t).unwrap().contact, None);
    close(contact_margin_box_triangle(&above, &t).unwrap(), -0.5, "margin");
}

fn capsule(start: P3, end: P3, radius: f64) -> Capsule {
    Capsule { start, end, radius }
}

#[test]
fn a_capsule_along_a_box_face() {
    let b = bx([0.0; 3], 1.0, ID);
    let a = capsule([-0.5, 0.0, 1.5], [0.5, 0.0, 1.5], 1.0);
    let (c, degenerate) = contact(contact_capsule_box(&a, &b).unwrap());
    close_v(c.normal, [0.0, 0.0, 1.0], "c.normal");
    close(c.depth, 0.5, "c.depth");
    close_v(c.point, [0.0, 0.0, 1.0], "c.point");
    assert!(!degenerate);
    let region = contact_region_capsule_box(&a, &b).unwrap().unwrap();
    close_region(&region, &[[-0.5, 0.0, 1.0], [0.5, 0.0, 1.0]]);
    let far = capsule([-0.5, 0.0, 3.0], [0.5, 0.0, 3.0], 1.0);
    assert_eq!(contact_capsule_box(&far, &b).unwrap().contact, None);
    close(contact_margin_capsule_box(&far, &b).unwrap(), -1.0, "margin");
}

#[test]
fn a_capsule_through_a_box() {
    // The axis through the centre along x: pushed out along ±y or ±z by 1,
    // four ways at once; the first is +y (the box's axes in order, +L first).
    let b = bx([0.0; 3], 1.0, ID);
    let a = capsule([-3.0, 0.0, 0.0], [3.0, 0.0, 0.0], 0.5);
    let (c, degenerate) = contact(contact_capsule_box(&a, &b).unwrap());
    assert!(degenerate);
    close_v(c.normal, [0.0, 1.0, 0.0], "c.normal");
    close(c.depth, 1.5, "c.depth");
    close_v(c.point, [0.0, 1.0, 0.0], "c.point");
    close_region(&contact_region_capsule_box(&a, &b).unwrap().unwrap(), &[[-1.0, 1.0, 0.0], [1.0, 1.0, 0.0]]);
    close(contact_margin_capsule_box(&a, &b).unwrap(), 1.5, "margin");
}

#[test]
fn a_capsule_over_and_through_a_triangle() {
    let t = Triangle { vertices: [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]] };
    let over = capsule([1.0, 1.0, 1.0], [1.0, 1.0, 3.0], 2.0);
    let (c, degenerate) = contact(contact_capsule_triangle(&over, &t).unwrap());
    close_v(c.normal, [0.0, 0.0, 1.0], "c.normal");
    close(c.depth, 1.0, "c.depth");
    close_v(c.point, [1.0, 1.0, 0.0], "c.point");
    assert!(!degenerate);
    let thin = capsule([1.0, 1.0, 1.0], [1.0, 1.0, 3.0], 0.5);
    assert_eq!(contact_capsule_triangle(&thin, &t).unwrap().contact, None);
    close(contact_margin_capsule_triangle(&thin, &t).unwrap(), -0.5, "margin");
    // Through the face, 0.5 below it: pushed up by 0.5 (the edges' axes push
    // by 1 and √2).
    let through = capsule([1.0, 1.0, -0.5], [1.0, 1.0, 2.0], 0.25);
    let (c, degenerate) = contact(contact_capsule_triangle(&through, &t).unwrap());
    close_v(c.normal, [0.0, 0.0, 1.0], "c.normal");
    close(c.depth, 0.75, "c.depth");
    close_v(c.point, [1.0, 1.0, 0.0], "c.point");
    assert!(!degenerate);
}

#[test]
fn an_axis_along_a_collapsed_triangle_has_no_normal() {
    let t = Triangle { vertices: [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [4.0, 0.0, 0.0]] };
    let a = capsule([1.0, 0.0, 0.0], [3.0, 0.0, 0.0], 0.5);
    let (c, degenerate) = contact(contact_capsule_triangle(&a, &t).unwrap());
    assert!(degenerate);
    close_v(c.normal, [0.0, 0.0, 1.0], "c.normal");
    close(c.depth, 0.5, "c.depth");
}

#[test]
fn refusals_name_the_field() {
    let b = OrientedBox { center: [0.0; 3], half_extents: [1.0, -1.0, 1.0], rotation: ID };
    let a = capsule([0.0; 3], [1.0, 0.0, 0.0], 1.0);
    assert_eq!(contact_capsule_box(&a, &b), Err(RefereeError::NegativeHalfExtent { field: "b.half_extents" }));
    let t = Triangle { vertices: [[0.0; 3], [f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]] };
    assert_eq!(contact_capsule_triangle(&a, &t), Err(RefereeError::NonFinite { field: "b.vertices" }));
    let bad = capsule([0.0; 3], [f64::INFINITY, 0.0, 0.0], 1.0);
    assert_eq!(contact_box_triangle(&bx([0.0; 3], 1.0, ID), &t), Err(RefereeError::NonFinite { field: "b.vertices" }));
    assert_eq!(contact_capsule_box(&bad, &bx([0.0; 3], 1.0, ID)), Err(RefereeError::NonFinite { field: "a.end" }));
}

/// Small integer coordinates (halves), so contacts, touching and ties are
/// common.
fn coord() -> impl Strategy<Value = f64> {
    (-8i32..=8).prop_map(|k| f64::from(k) / 2.0)
}

fn point() -> impl Strategy<Value = P3> {
    [coord(), coord(), coord()]
}

fn quaternion() -> impl Strategy<Value = [f64; 4]> {
    prop_oneof![Just(ID), Just(Z345), Just(X345), Just([2.0, 1.0, 2.0, 4.0]), Just([1.0, 1.0, 1.0, 1.0])]
}

proptest! {
    /// A capsule whose axis is one point is a sphere: the same answer, bit
    /// for bit, as the sphere–box referee's (outside: the clamp; inside: the
    /// nearest face, which is the least push along the box's axes).
    #[test]
    fn a_zero_length_capsule_is_a_sphere_on_a_box(c in point(), r in 1u8..4, center in point(), h in point(), q in quaternion()) {
        let r = f64::from(r) / 2.0;
        let b = OrientedBox { center, half_extents: h.map(f64::abs), rotation: q };
        let cap = contact_capsule_box(&capsule(c, c, r), &b).unwrap();
        let sph = super::super::contact_sphere_box(&Sphere { center: c, radius: r }, &b).unwrap();
        prop_assert_eq!(cap, sph);
    }

    /// The same against a triangle where the centre is off the triangle
    /// (on it, sphere–triangle's fallback normal is its own).
    #[test]
    fn a_zero_length_capsule_is_a_sphere_on_a_triangle(c in point(), r in 1u8..4, v in [point(), point(), point()]) {
        let r = f64::from(r) / 2.0;
        let t = Triangle { vertices: v };
        let sph = super::super::contact_sphere_triangle(&Sphere { center: c, radius: r }, &t).unwrap();
        prop_assume!(!sph.degenerate);
        let cap = contact_capsule_triangle(&capsule(c, c, r), &t).unwrap();
        prop_assert_eq!(cap, sph);
    }

    /// The floating-point "apart" stages give the answers of the exact stage
    /// alone, on scenes where touching and near misses are common.
    #[test]
    fn the_apart_stages_change_no_answer(c0 in point(), c1 in point(), r in 1u8..4, center in point(), h in point(), q in quaternion(), v in [point(), point(), point()]) {
        let r = f64::from(r) / 4.0;
        let b = OrientedBox { center, half_extents: h.map(f64::abs), rotation: q };
        let t = Triangle { vertices: v };
        let cap = capsule(c0, c1, r);
        use super::super::exact_only;
        prop_assert_eq!(contact_capsule_box(&cap, &b), exact_only(|| contact_capsule_box(&cap, &b)));
        prop_assert_eq!(contact_capsule_triangle(&cap, &t), exact_only(|| contact_capsule_triangle(&cap, &t)));
        prop_assert_eq!(contact_box_triangle(&b, &t), exact_only(|| contact_box_triangle(&b, &t)));
    }

    /// Moved by its depth along its normal (exactly), `a` touches `b`: the
    /// least push is then exactly 0; and the margin's sign is the decision.
    #[test]
    fn the_depth_moves_a_box_clear(ca in point(), cb in point(), ha in point(), hb in point(), qa in quaternion(), qb in quaternion()) {
        let a = OrientedBox { center: ca, half_extents: ha.map(f64::abs), rotation: qa };
        let b = OrientedBox { center: cb, half_extents: hb.map(f64::abs), rotation: qb };
        let answer = contact_box_box(&a, &b).unwrap();
        let margin = contact_margin_box_box(&a, &b).unwrap();
        // The floating-point stage's certified axis gives the same bits as
        // all fifteen axes in rationals.
        let exact = super::super::exact_only(|| contact_box_box(&a, &b).unwrap());
        prop_assert_eq!(answer, exact);
        let exact_margin = super::super::exact_only(|| contact_margin_box_box(&a, &b).unwrap());
        prop_assert_eq!(margin.to_bits(), exact_margin.to_bits());
        let region = contact_region_box_box(&a, &b).unwrap();
        prop_assert_eq!(region, super::super::exact_only(|| contact_region_box_box(&a, &b).unwrap()));
        prop_assert_eq!(answer.contact.is_some(), margin.is_sign_positive());
        let (ea, eb) = (exact_box(&a, BOX_A).unwrap(), exact_box(&b, BOX_B).unwrap());
        let (pa, pb) = (Convex::of_box(&ea), Convex::of_box(&eb));
        if let Some(least) = least_push(&pa, &pb).filter(|l| l.push.amount >= Q::ZERO) {
            let t = least.push.translation();
            let moved = Convex { vertices: pa.vertices.iter().map(|v| add(v, &t)).collect(), ..pa };
            let after = least_push(&moved, &pb).unwrap();
            prop_assert!(after.push.amount.is_zero(), "touching after the push");
        }
    }
}

/// The last box pair is remembered on its thread (a case's answer, margin and
/// region share it): asked again, it gives the same bits and counts the same
/// stages as computing it the first time did.
#[test]
fn a_remembered_box_pair_counts_its_stages_again() {
    use crate::referee::stage::stage_counts_on_this_thread as counts;
    let (a, b) = (bx([1.5, 0.25, 0.0], 1.0, Z345), bx([0.0; 3], 1.0, ID));
    let delta = |x: &[(crate::referee::Stage, u64, u64)], y: &[(crate::referee::Stage, u64, u64)]| {
        x.iter().zip(y).map(|(p, q)| (q.1 - p.1, q.2 - p.2)).collect::<Vec<_>>()
    };
    let before = counts();
    let first = contact_margin_box_box(&a, &b).unwrap();
    let mid = counts();
    let again = contact_margin_box_box(&a, &b).unwrap();
    let after = counts();
    assert_eq!(first.to_bits(), again.to_bits());
    let (d1, d2) = (delta(&before, &mid), delta(&mid, &after));
    assert!(d1.iter().any(|&(f, e)| f + e > 0), "the first computation counts a stage: {d1:?}");
    assert_eq!(d1, d2, "the remembered pair counts what computing it counted");
}
