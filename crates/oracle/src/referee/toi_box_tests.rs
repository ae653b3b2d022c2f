//! Hand-derived cases of a sphere's time of impact with a box, and its margin.
//!
//! Faces give rational times, exact in `f64` here (dyadic inputs, 3-4-5
//! rotations), compared bit for bit; edges and corners give `2 − 1/√k`,
//! compared within [`ROOT_ULPS`].

use super::*;
use crate::referee::exact::within_ulps;
use crate::referee::stage::exact_only;

/// The referee's numbers are correctly rounded and these exact values are
/// doubles: 0 ulps apart.
const EXACT_ULPS: u64 = 0;

/// An expected `2 − 1/√k` or `1/√k` computed in `f64` from a correctly
/// rounded `1/√k` (`FRAC_1_SQRT_2`, or `1/√3` with two roundings) and one
/// subtraction is within 1 ulp of the correctly rounded value the referee
/// gives.
const ROOT_ULPS: u64 = 1;

fn unit_box(center: P3, h: [f64; 3], rotation: [f64; 4]) -> OrientedBox {
    OrientedBox { center, half_extents: h, rotation }
}

const ID: [f64; 4] = [1.0, 0.0, 0.0, 0.0];
/// The 3-4-5 rotation about z: columns (3/5, 4/5, 0), (−4/5, 3/5, 0), z.
const Z345: [f64; 4] = [2.0, 0.0, 0.0, 1.0];
const STILL: P3 = [0.0; 3];

fn sphere(center: P3, radius: f64) -> Sphere {
    Sphere { center, radius }
}

fn near(got: f64, want: f64, ulps: u64, what: &str) {
    assert!(within_ulps(got, want, ulps), "{what}: got {got:e}, want {want:e}");
}

fn near_v(got: P3, want: P3, ulps: u64, what: &str) {
    for i in 0..3 {
        near(got[i], want[i], ulps, what);
    }
}

fn hit(a: &Sphere, va: P3, b: &OrientedBox, vb: P3, t_max: f64) -> (crate::geom::Toi, bool) {
    let answer = toi_sphere_box(a, &va, b, &vb, t_max).unwrap();
    let staged_exact = exact_only(|| toi_sphere_box(a, &va, b, &vb, t_max).unwrap());
    assert_eq!(answer, staged_exact, "the stages agree bit for bit");
    (answer.toi.expect("an impact"), answer.degenerate)
}

fn miss(a: &Sphere, va: P3, b: &OrientedBox, vb: P3, t_max: f64) {
    let answer = toi_sphere_box(a, &va, b, &vb, t_max).unwrap();
    assert_eq!(answer, exact_only(|| toi_sphere_box(a, &va, b, &vb, t_max).unwrap()));
    assert_eq!(answer.toi, None, "no impact");
}

fn margin(a: &Sphere, va: P3, b: &OrientedBox, vb: P3, t_max: f64) -> f64 {
    toi_margin_sphere_box(a, &va, b, &vb, t_max).unwrap()
}

#[test]
fn head_on_onto_a_face() {
    let b = unit_box(STILL, [1.0; 3], ID);
    let a = sphere([3.0, 0.0, 0.0], 0.5);
    let (k, degenerate) = hit(&a, [-1.0, 0.0, 0.0], &b, STILL, 2.0);
    near(k.t, 1.5, EXACT_ULPS, "t");
    near_v(k.point, [1.0, 0.0, 0.0], EXACT_ULPS, "point");
    near_v(k.normal, [1.0, 0.0, 0.0], EXACT_ULPS, "normal");
    assert!(!degenerate);
    // The path reaches the box: the gap is the whole radius.
    near(margin(&a, [-1.0, 0.0, 0.0], &b, STILL, 2.0), 0.5, EXACT_ULPS, "margin");
}

#[test]
fn onto_an_edge_and_a_corner() {
    let b = unit_box(STILL, [1.0; 3], ID);
    // Centre (3 − t, 3 − t, 0): √2 (2 − t) = 1 from the edge x = y = 1.
    let (k, _) = hit(&sphere([3.0, 3.0, 0.0], 1.0), [-1.0, -1.0, 0.0], &b, STILL, 2.0);
    near(k.t, 2.0 - std::f64::consts::FRAC_1_SQRT_2, ROOT_ULPS, "edge t");
    near_v(k.point, [1.0, 1.0, 0.0], EXACT_ULPS, "edge point");
    let s = std::f64::consts::FRAC_1_SQRT_2;
    near_v(k.normal, [s, s, 0.0], EXACT_ULPS, "edge normal");
    // Centre (3 − t)(1, 1, 1): √3 (2 − t) = 1 from the corner (1, 1, 1).
    let (k, _) = hit(&sphere([3.0; 3], 1.0), [-1.0; 3], &b, STILL, 2.0);
    let r3 = 1.0 / 3f64.sqrt();
    near(k.t, 2.0 - r3, ROOT_ULPS, "corner t");
    near_v(k.point, [1.0; 3], EXACT_ULPS, "corner point");
    near_v(k.normal, [r3; 3], ROOT_ULPS, "corner normal");
}

#[test]
fn a_rotated_box_is_met_on_its_own_face() {
    // Axis 0 is (3/5, 4/5, 0): the centre (3, 4, 0) is 5 along it, moving
    // back at speed 5; the face +x (at 1, plus r = 1) is reached at t = 3/5.
    let b = unit_box(STILL, [1.0; 3], Z345);
    let (k, _) = hit(&sphere([3.0, 4.0, 0.0], 1.0), [-3.0, -4.0, 0.0], &b, STILL, 1.0);
    near(k.t, 0.6, EXACT_ULPS, "t");
    near_v(k.point, [0.6, 0.8, 0.0], EXACT_ULPS, "point");
    near_v(k.normal, [0.6, 0.8, 0.0], EXACT_ULPS, "normal");
}

#[test]
fn misses_wide_away_and_late() {
    let b = unit_box(STILL, [1.0; 3], ID);
    let wide = sphere([3.0, 3.0, 0.0], 0.5);
    miss(&wide, [0.0, 0.0, 1.0], &b, STILL, 4.0);
    // 0.5 − 2√2, the gap at the start and throughout.
    near(margin(&wide, [0.0, 0.0, 1.0], &b, STILL, 4.0), 0.5 - 2.0 * 2f64.sqrt(), ROOT_ULPS, "wide margin");
    miss(&sphere([3.0, 0.0, 0.0], 0.5), [1.0, 0.0, 0.0], &b, STILL, 4.0);
    // Reached at 1.5, after t_max = 1: the path ends 1 from the face.
    let late = sphere([3.0, 0.0, 0.0], 0.5);
    miss(&late, [-1.0, 0.0, 0.0], &b, STILL, 1.0);
    near(margin(&late, [-1.0, 0.0, 0.0], &b, STILL, 1.0), -0.5, EXACT_ULPS, "late margin");
}

#[test]
fn touching_at_the_start_is_time_zero() {
    let b = unit_box(STILL, [1.0; 3], ID);
    let (k, _) = hit(&sphere([1.5, 0.0, 0.0], 0.5), [1.0, 0.0, 0.0], &b, STILL, 1.0);
    near(k.t, 0.0, EXACT_ULPS, "t");
    near_v(k.point, [1.0, 0.0, 0.0], EXACT_ULPS, "point");
}

#[test]
fn both_moving_the_point_moves_with_the_box() {
    let b = unit_box(STILL, [1.0; 3], ID);
    let (k, _) = hit(&sphere([3.0, 0.0, 0.0], 0.5), [-1.0, 0.0, 0.0], &b, [1.0, 0.0, 0.0], 1.0);
    near(k.t, 0.75, EXACT_ULPS, "t");
    near_v(k.point, [1.75, 0.0, 0.0], EXACT_ULPS, "point");
    near_v(k.normal, [1.0, 0.0, 0.0], EXACT_ULPS, "normal");
}

#[test]
fn through_the_box_within_the_interval() {
    // A fast sphere passes through the whole box between 0 and t_max: the
    // first contact is on the near face.
    let b = unit_box(STILL, [1.0; 3], ID);
    let (k, _) = hit(&sphere([-3.0, 0.0, 0.0], 0.5), [10.0, 0.0, 0.0], &b, STILL, 1.0);
    near(k.t, 0.15, EXACT_ULPS, "t");
    near_v(k.point, [-1.0, 0.0, 0.0], EXACT_ULPS, "point");
    near_v(k.normal, [-1.0, 0.0, 0.0], EXACT_ULPS, "normal");
}

#[test]
fn a_point_is_flagged_with_the_direction_it_came_from() {
    let b = unit_box(STILL, [1.0; 3], ID);
    let (k, degenerate) = hit(&sphere([3.0, 0.0, 0.0], 0.0), [-2.0, 0.0, 0.0], &b, STILL, 2.0);
    near(k.t, 1.0, EXACT_ULPS, "t");
    near_v(k.normal, [1.0, 0.0, 0.0], EXACT_ULPS, "normal");
    assert!(degenerate, "no radius, no direction of its own");
}

#[test]
fn a_flat_box_is_its_rectangle() {
    let b = unit_box(STILL, [0.0, 1.0, 1.0], ID);
    let (k, degenerate) = hit(&sphere([3.0, 0.0, 0.0], 0.5), [-1.0, 0.0, 0.0], &b, STILL, 4.0);
    near(k.t, 2.5, EXACT_ULPS, "t");
    near_v(k.point, [0.0, 0.0, 0.0], EXACT_ULPS, "point");
    near_v(k.normal, [1.0, 0.0, 0.0], EXACT_ULPS, "normal");
    assert!(!degenerate);
}

#[test]
fn a_grazing_path_touches_once_and_counts() {
    // The centre passes at exactly r above the face y = 1: it touches along
    // the whole face, first where it reaches the edge x = −1.
    let b = unit_box(STILL, [1.0; 3], ID);
    let a = sphere([-3.0, 1.5, 0.0], 0.5);
    let (k, _) = hit(&a, [1.0, 0.0, 0.0], &b, STILL, 4.0);
    near(k.t, 2.0, EXACT_ULPS, "t");
    near_v(k.point, [-1.0, 1.0, 0.0], EXACT_ULPS, "point");
    near_v(k.normal, [0.0, 1.0, 0.0], EXACT_ULPS, "normal");
    near(margin(&a, [1.0, 0.0, 0.0], &b, STILL, 4.0), 0.0, EXACT_ULPS, "margin");
}

#[test]
fn bad_input_names_its_field() {
    let b = unit_box(STILL, [1.0; 3], ID);
    let bad = unit_box(STILL, [1.0, -1.0, 1.0], ID);
    let a = sphere([3.0, 0.0, 0.0], 0.5);
    let e = toi_sphere_box(&a, &[-1.0, 0.0, 0.0], &bad, &STILL, 1.0).unwrap_err();
    assert!(e.to_string().contains("b.half_extents"), "{e}");
    let e = toi_sphere_box(&a, &[f64::NAN, 0.0, 0.0], &b, &STILL, 1.0).unwrap_err();
    assert!(e.to_string().contains("a.velocity"), "{e}");
    let e = toi_margin_sphere_box(&a, &[-1.0, 0.0, 0.0], &b, &[0.0, f64::INFINITY, 0.0], 1.0).unwrap_err();
    assert!(e.to_string().contains("b.velocity"), "{e}");
}
