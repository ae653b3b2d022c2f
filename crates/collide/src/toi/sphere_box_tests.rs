//! Tests of the sphere–box time of impact, both forms: hand-derived cases
//! (derivation beside each), the lecture's halving shown missing what it
//! misses, power-of-two scalings of one scene, and properties of the robust
//! form on random scenes (no contact before the reported time, touching at
//! it, never later than halving's impact). Hand-derived bodies run for `f32`
//! and `f64`.

use super::*;
use crate::boxes::{contact_sphere_box, contact_sphere_box_lecture};
use crate::real::{Real, Vec3};
use crate::shapes::{OrientedBox, Sphere};
use crate::test_support::{both, eps, prop_both, v};
use proptest::prelude::*;

/// Hand-derived scenes have coordinates of at most 10 and answers reached by a
/// few roundings, one rotation and at most one square root: 32 ε of the
/// scene's scale covers them with room. Units: ε times [`HAND_SCALE`].
const HAND_TOL_EPS: f64 = 32.0;

/// The scale of the hand-derived scenes: their largest coordinate or
/// displacement. Units: length (and time, for speeds of order 1).
const HAND_SCALE: f64 = 10.0;

/// Bisections asked of the lecture's halving in the hand-derived cases: 50,
/// so that its bracket `t_max / 2^50` (below 1e-14 for `t_max ≤ 10`) is within
/// the hand tolerance in `f64`; in `f32` the bracket stops at the type's
/// resolution first.
const HALVING_STEPS: u32 = 50;

/// Relative agreement asked of the robust answer on one scene scaled by a
/// power of two: the scaling is exact and the method scales the scene back
/// to its own size by powers of two, so the answers should agree bit for bit;
/// 4 ε leaves room for a last rounding taken on another path (the world
/// point's sum). Units: ε times the compared value's magnitude.
const SCALED_REL_EPS: f64 = 4.0;

fn hand_tol<T: Real>() -> f64 {
    HAND_TOL_EPS * eps::<T>() * HAND_SCALE
}

/// What halving's answer may be off by over `[0, t_max]`: its bracket after
/// [`HALVING_STEPS`] bisections, the type's resolution of `t` (a bracket
/// stops when its midpoint rounds to an end: a few ε of `t_max`), and the
/// hand tolerance for the static tests' rounding.
fn halving_tol<T: Real>(t_max: f64) -> f64 {
    t_max / 2f64.powi(HALVING_STEPS as i32) + 4.0 * eps::<T>() * t_max + hand_tol::<T>()
}

fn close<T: Real>(got: T, want: f64, tol: f64, what: &str) {
    let g = got.wide();
    assert!((g - want).abs() <= tol, "{what}: got {g}, want {want} (tol {tol:e})");
}

fn close_v<T: Real>(got: &Vec3<T>, want: [f64; 3], tol: f64, what: &str) {
    for (k, w) in want.iter().enumerate() {
        let g = got[k].wide();
        assert!((g - w).abs() <= tol, "{what}[{k}]: got {got:?}, want {want:?} (tol {tol:e})");
    }
}

fn ball<T: Real>(x: f64, y: f64, z: f64, r: f64) -> Sphere<T> {
    Sphere::new(v(x, y, z), T::of(r))
}

/// The unit box: centre 0, half-extents 1, unrotated.
fn unit_box<T: Real>() -> OrientedBox<T> {
    OrientedBox::axis_aligned(Vec3::zeros(), v(1.0, 1.0, 1.0))
}

fn still<T: Real>() -> Vec3<T> {
    Vec3::zeros()
}

fn robust<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &OrientedBox<T>, vb: &Vec3<T>, t_max: f64) -> Option<Toi<T>> {
    toi_sphere_box(a, va, b, vb, T::of(t_max))
}

fn halving<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &OrientedBox<T>, vb: &Vec3<T>, t_max: f64) -> Option<Toi<T>> {
    toi_sphere_box_halving(a, va, b, vb, T::of(t_max), Halving::Steps(HALVING_STEPS))
}

/// Checks one expected impact on both forms: the robust answer within the
/// hand tolerance, halving's time within its bracket (never before the
/// impact, up to rounding) and its point and normal within what its time's
/// error moves them by (`speed` the relative speed, `r` the radius).
#[allow(clippy::too_many_arguments)]
fn impact_both<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &OrientedBox<T>,
    vb: &Vec3<T>,
    t_max: f64,
    want: (f64, [f64; 3], [f64; 3]),
    speed: f64,
    what: &str,
) {
    let (t, point, normal) = want;
    let k = robust(a, va, b, vb, t_max).unwrap_or_else(|| panic!("{what}: robust finds the impact"));
    assert_eq!(k.status, ToiStatus::Converged, "{what}");
    assert!(!k.degenerate, "{what}");
    close(k.t, t, hand_tol::<T>(), &format!("{what}: robust t"));
    close_v(&k.point, point, hand_tol::<T>(), &format!("{what}: robust point"));
    close_v(&k.normal, normal, hand_tol::<T>(), &format!("{what}: robust normal"));
    let h = halving(a, va, b, vb, t_max).unwrap_or_else(|| panic!("{what}: halving finds the impact"));
    let tol = halving_tol::<T>(t_max);
    assert!(h.t.wide() >= t - hand_tol::<T>(), "{what}: halving's t {:?} is before {t}", h.t);
    close(h.t, t, tol, &format!("{what}: halving t"));
    // The point moves with the box by |vb| δt; the normal turns by at most
    // speed δt / r (the overlap at the bracket's end over the radius).
    let vb_speed = vb.iter().map(|x| x.wide().abs()).fold(0.0, f64::max) * 3f64.sqrt();
    close_v(&h.point, point, tol * (1.0 + vb_speed), &format!("{what}: halving point"));
    let turn = speed * tol / a.radius.wide().max(f64::MIN_POSITIVE);
    close_v(&h.normal, normal, 4.0 * turn + hand_tol::<T>(), &format!("{what}: halving normal"));
}

// ------------------------------------------------------------------ impacts

fn face_head_on<T: Real>() {
    // Unit box at the origin; sphere r 0.5 at (3,0,0) moving −x at speed 1:
    // its leading point 2.5 reaches the face x = 1 after 1.5. Normal +x,
    // point (1,0,0).
    let a = ball::<T>(3.0, 0.0, 0.0, 0.5);
    let va = v::<T>(-1.0, 0.0, 0.0);
    let want = (1.5, [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    impact_both(&a, &va, &unit_box(), &still(), 2.0, want, 1.0, "face");
}
both!(face_head_on_case, face_head_on);

fn onto_an_edge<T: Real>() {
    // Sphere r 1 at (5, 1.6, 0) moving −x at speed 1. The face +x would be met
    // at x = 2 with its foot at y = 1.6, off the face; the +y face is never
    // approached. The edge along z at (x, y) = (1, 1): (x − 1)² + 0.6² = 1
    // gives x = 1.8, so t = 5 − 1.8 = 3.2, with the foot at z = 0 on the
    // edge. Normal (0.8, 0.6, 0), point (1, 1, 0).
    let a = ball::<T>(5.0, 1.6, 0.0, 1.0);
    let va = v::<T>(-1.0, 0.0, 0.0);
    let want = (3.2, [1.0, 1.0, 0.0], [0.8, 0.6, 0.0]);
    impact_both(&a, &va, &unit_box(), &still(), 4.0, want, 1.0, "edge");
}
both!(onto_an_edge_case, onto_an_edge);

fn onto_a_corner<T: Real>() {
    // Sphere r 1 at (5, 1.48, 1.64) moving −x at speed 1. Offsets from the
    // corner (1,1,1) across the motion: 0.48² + 0.64² = 0.64, so the corner is
    // met when (x − 1)² = 1 − 0.64 = 0.36: x = 1.6, t = 3.4. The +x face's
    // foot (1.48, 1.64) is off it; the edge along y at (x, z) = (1, 1) is met
    // at (x − 1)² = 1 − 0.64² with its foot at y = 1.48, off it; the edge
    // along z at (1, 1) likewise (foot z = 1.64); the edge along x is
    // parallel to the motion. Normal (0.6, 0.48, 0.64), point (1, 1, 1).
    let a = ball::<T>(5.0, 1.48, 1.64, 1.0);
    let va = v::<T>(-1.0, 0.0, 0.0);
    let want = (3.4, [1.0, 1.0, 1.0], [0.6, 0.48, 0.64]);
    impact_both(&a, &va, &unit_box(), &still(), 4.0, want, 1.0, "corner");
}
both!(onto_a_corner_case, onto_a_corner);

fn rotated_box_345<T: Real>() {
    // Quaternion [2,0,0,1] (not unit) is the 3-4-5 rotation about z:
    // R = [[3/5, −4/5, 0], [4/5, 3/5, 0], [0, 0, 1]]. The unit box's +x face
    // has the normal R e_x = (3/5, 4/5, 0); its centre is at that point.
    // The sphere (r 1) starts 5 out along the normal and half a unit along
    // the box's y axis R e_y = (−4/5, 3/5, 0): (3, 4, 0) + (−0.4, 0.3, 0) =
    // (2.6, 4.3, 0), moving −5 along the normal, (−3, −4, 0). It has
    // 5 − 1 − 1 = 3 to close at speed 5: t = 0.6. The point is the face's
    // centre plus the half unit: (0.6, 0.8, 0) + (−0.4, 0.3, 0) =
    // (0.2, 1.1, 0).
    let b = OrientedBox::new(Vec3::zeros(), v(1.0, 1.0, 1.0), [T::of(2.0), T::zero(), T::zero(), T::one()]);
    let a = ball::<T>(2.6, 4.3, 0.0, 1.0);
    let va = v::<T>(-3.0, -4.0, 0.0);
    let want = (0.6, [0.2, 1.1, 0.0], [0.6, 0.8, 0.0]);
    impact_both(&a, &va, &b, &still(), 1.0, want, 5.0, "3-4-5 face");
    // Onto the box's corner R (1, 1, 1) = (−1/5, 7/5, 1), along the diagonal
    // direction d = R (1, 1, 1)/√3 from 1 + 2√3 out: the sphere's surface
    // has 2√3 to go at speed 1, t = 2√3; the normal is d.
    let s3 = 3f64.sqrt();
    let d = [-0.2 / s3, 1.4 / s3, 1.0 / s3];
    let corner = [-0.2, 1.4, 1.0];
    let start = [0, 1, 2].map(|k| corner[k] + (1.0 + 2.0 * s3) * d[k]);
    let a = ball::<T>(start[0], start[1], start[2], 1.0);
    let va = v::<T>(-d[0], -d[1], -d[2]);
    impact_both(&a, &va, &b, &still(), 4.0, (2.0 * s3, corner, d), 1.0, "3-4-5 corner");
}
both!(rotated_box_345_case, rotated_box_345);

fn both_moving<T: Real>() {
    // The box moves +x at 1, the sphere (r 0.5, at (5,0,0)) −x at 1: the gap
    // 5 − 1 − 0.5 = 3.5 closes at 2, t = 1.75. The box's centre is then at
    // 1.75, so the point is (2.75, 0, 0); normal +x.
    let a = ball::<T>(5.0, 0.0, 0.0, 0.5);
    let (va, vb) = (v::<T>(-1.0, 0.0, 0.0), v::<T>(1.0, 0.0, 0.0));
    impact_both(&a, &va, &unit_box(), &vb, 2.0, (1.75, [2.75, 0.0, 0.0], [1.0, 0.0, 0.0]), 2.0, "both moving");
}
both!(both_moving_case, both_moving);

fn flat_box<T: Real>() {
    // A square in z = 0 (half-extents (1, 1, 0)). Sphere r 0.5 at
    // (0.2, 0.3, 3) moving −z at 1: t = 3 − 0.5 = 2.5, point (0.2, 0.3, 0),
    // normal +z; from below, mirrored, the normal is −z.
    let b = OrientedBox::axis_aligned(Vec3::zeros(), v::<T>(1.0, 1.0, 0.0));
    let a = ball::<T>(0.2, 0.3, 3.0, 0.5);
    let want = (2.5, [0.2, 0.3, 0.0], [0.0, 0.0, 1.0]);
    impact_both(&a, &v(0.0, 0.0, -1.0), &b, &still(), 3.0, want, 1.0, "flat from above");
    let a = ball::<T>(0.2, 0.3, -3.0, 0.5);
    let want = (2.5, [0.2, 0.3, 0.0], [0.0, 0.0, -1.0]);
    impact_both(&a, &v(0.0, 0.0, 1.0), &b, &still(), 3.0, want, 1.0, "flat from below");
}
both!(flat_box_case, flat_box);

// ------------------------------------------------------------ no impact

fn no_impact<T: Real>() {
    let b = unit_box::<T>();
    // Passing wide: centre at y = 3 with r 1 stays 1 clear of the +y face.
    let a = ball::<T>(5.0, 3.0, 0.0, 1.0);
    assert!(robust(&a, &v(-1.0, 0.0, 0.0), &b, &still(), 10.0).is_none(), "wide, robust");
    assert!(halving(&a, &v(-1.0, 0.0, 0.0), &b, &still(), 10.0).is_none(), "wide, halving");
    // Passing the corner region diagonally, just wide: the path (5, y, y) at
    // y = 1 + 1/√2 + 0.01 keeps its distance to the edge along x at
    // √2 (1/√2 + 0.01) > 1 = r.
    let y = 1.0 + 0.5f64.sqrt() + 0.01;
    let a = ball::<T>(5.0, y, y, 1.0);
    assert!(robust(&a, &v(-1.0, 0.0, 0.0), &b, &still(), 10.0).is_none(), "diagonal, robust");
    assert!(halving(&a, &v(-1.0, 0.0, 0.0), &b, &still(), 10.0).is_none(), "diagonal, halving");
    // Moving away.
    let a = ball::<T>(3.0, 0.0, 0.0, 0.5);
    assert!(robust(&a, &v(1.0, 0.0, 0.0), &b, &still(), 10.0).is_none(), "away, robust");
    assert!(halving(&a, &v(1.0, 0.0, 0.0), &b, &still(), 10.0).is_none(), "away, halving");
    // The head-on impact at 1.5 lies after t_max = 1 (and after 1.49).
    let va = v::<T>(-1.0, 0.0, 0.0);
    assert!(robust(&a, &va, &b, &still(), 1.0).is_none(), "late, robust");
    assert!(robust(&a, &va, &b, &still(), 1.49).is_none(), "late by 0.01, robust");
    assert!(halving(&a, &va, &b, &still(), 1.0).is_none(), "late, halving");
    // No relative motion: both move alike.
    assert!(robust(&a, &va, &b, &va, 10.0).is_none(), "no relative motion");
    // A negative or NaN t_max is 0: only a contact at t = 0 is found.
    assert!(robust(&a, &va, &b, &still(), -1.0).is_none(), "negative t_max");
    assert!(toi_sphere_box(&a, &va, &b, &still(), T::of(f64::NAN)).is_none(), "NaN t_max");
    // A non-finite input is no impact.
    assert!(robust(&a, &v(f64::NAN, 0.0, 0.0), &b, &still(), 10.0).is_none(), "NaN velocity");
}
both!(no_impact_case, no_impact);

// ------------------------------------------------------- contact at t = 0

fn touching_at_start<T: Real>() {
    // Sphere r 0.5 at (1.5, 0, 0) touches the face x = 1 (touching counts):
    // t = 0, Penetrating, the static contact (point (1,0,0), normal +x), even
    // moving away.
    let a = ball::<T>(1.5, 0.0, 0.0, 0.5);
    let b = unit_box::<T>();
    for va in [v::<T>(-1.0, 0.0, 0.0), v(1.0, 0.0, 0.0)] {
        let k = robust(&a, &va, &b, &still(), 2.0).expect("touching");
        assert_eq!(k.status, ToiStatus::Penetrating);
        close(k.t, 0.0, 0.0, "t is exactly 0");
        let s = contact_sphere_box(&a, &b).expect("static contact");
        close_v(&k.point, [s.point.x.wide(), s.point.y.wide(), s.point.z.wide()], 0.0, "the static point");
        close_v(&k.normal, [1.0, 0.0, 0.0], hand_tol::<T>(), "normal");
        let h = halving(&a, &va, &b, &still(), 2.0).expect("touching");
        assert_eq!(h.status, ToiStatus::Penetrating);
        close(h.t, 0.0, 0.0, "halving t is exactly 0");
        let s = contact_sphere_box_lecture(&a, &b).expect("static contact");
        close_v(&h.point, [s.point.x.wide(), s.point.y.wide(), s.point.z.wide()], 0.0, "the lecture's point");
    }
    // Overlapping deeper, the centre inside: the static contact's nearest face.
    let a = ball::<T>(0.75, 0.0, 0.0, 0.5);
    let k = robust(&a, &v(-1.0, 0.0, 0.0), &b, &still(), 2.0).expect("inside");
    assert_eq!(k.status, ToiStatus::Penetrating);
    close_v(&k.point, [1.0, 0.0, 0.0], hand_tol::<T>(), "nearest face's point");
    close_v(&k.normal, [1.0, 0.0, 0.0], hand_tol::<T>(), "nearest face's normal");
}
both!(touching_at_start_case, touching_at_start);

// ----------------------------------------------------- degenerate inputs

fn zero_radius<T: Real>() {
    // A point at (3, 0.5, 0) moving (−2, −1, 0) meets the face x = 1 at t = 1
    // at (1, −0.5, 0). With no radius there is no normal: −v/‖v‖ =
    // (2, 1, 0)/√5, flagged.
    let a = ball::<T>(3.0, 0.5, 0.0, 0.0);
    let va = v::<T>(-2.0, -1.0, 0.0);
    let k = robust(&a, &va, &unit_box(), &still(), 2.0).expect("met");
    assert!(k.degenerate);
    close(k.t, 1.0, hand_tol::<T>(), "t");
    close_v(&k.point, [1.0, -0.5, 0.0], hand_tol::<T>(), "point");
    let s5 = 5f64.sqrt();
    close_v(&k.normal, [2.0 / s5, 1.0 / s5, 0.0], hand_tol::<T>(), "normal");
    // The lecture's static test with no radius is "the centre in the box":
    // halving finds the same time (its normal is the nearest face's, +x)
    // when the step ends with the point inside, at (0.6, −0.7, 0) for
    // t_max = 1.2; at t_max = 2 the point has left through the −y face
    // (tunneling: no impact seen).
    let h = halving(&a, &va, &unit_box(), &still(), 1.2).expect("met");
    assert!(h.t.wide() >= 1.0 - hand_tol::<T>());
    close(h.t, 1.0, halving_tol::<T>(1.2), "halving t");
    assert!(halving(&a, &va, &unit_box(), &still(), 2.0).is_none(), "passed through by t_max = 2");
    close_v(&h.normal, [1.0, 0.0, 0.0], hand_tol::<T>(), "halving normal");
    // Aimed exactly at the corner (1, 1, 1) along the diagonal: t = 2, point
    // the corner, normal the approach direction.
    let a = ball::<T>(3.0, 3.0, 3.0, 0.0);
    let k = robust(&a, &v(-1.0, -1.0, -1.0), &unit_box(), &still(), 4.0).expect("met");
    assert!(k.degenerate);
    close(k.t, 2.0, hand_tol::<T>(), "corner t");
    close_v(&k.point, [1.0, 1.0, 1.0], hand_tol::<T>(), "corner point");
    let s3 = 1.0 / 3f64.sqrt();
    close_v(&k.normal, [s3, s3, s3], hand_tol::<T>(), "corner normal");
}
both!(zero_radius_case, zero_radius);

fn tunneling<T: Real>() {
    // A small fast sphere (r 0.1, speed 10) through the flat square within
    // one step: t = (5 − 0.1)/10 = 0.49, and at t_max = 1 it is 5 below. The
    // robust form finds it; halving reports none (asserted as it is: the
    // lecture's method tests only the end of the step).
    let b = OrientedBox::axis_aligned(Vec3::zeros(), v::<T>(1.0, 1.0, 0.0));
    let a = ball::<T>(0.0, 0.0, 5.0, 0.1);
    let va = v::<T>(0.0, 0.0, -10.0);
    let k = robust(&a, &va, &b, &still(), 1.0).expect("seen");
    close(k.t, 0.49, hand_tol::<T>(), "t");
    close_v(&k.normal, [0.0, 0.0, 1.0], hand_tol::<T>(), "normal");
    assert!(halving(&a, &va, &b, &still(), 1.0).is_none(), "the lecture's halving misses it");
    // A glancing pass by a corner, also missed by halving: the path
    // (x, 1.5, 1.5) at r 0.8 passes the edge along x at √0.5 ≈ 0.707 < 0.8.
    // It meets the corner (1, 1, 1) when (x − 1)² = 0.64 − 0.5: x = 1 + √0.14,
    // from x = 5 at speed 10: t = (4 − √0.14)/10.
    let a = ball::<T>(5.0, 1.5, 1.5, 0.8);
    let va = v::<T>(-10.0, 0.0, 0.0);
    let k = robust(&a, &va, &unit_box(), &still(), 1.0).expect("seen");
    close(k.t, (4.0 - 0.14f64.sqrt()) / 10.0, hand_tol::<T>(), "glancing t");
    close_v(&k.point, [1.0, 1.0, 1.0], hand_tol::<T>(), "glancing point");
    assert!(halving(&a, &va, &unit_box(), &still(), 1.0).is_none(), "the lecture's halving misses it");
}
both!(tunneling_case, tunneling);

// ---------------------------------------------------------------- scale

/// The 3-4-5 corner scene of [`rotated_box_345`] plus box motion, in `f64`,
/// with lengths times `2^kl` and speeds times `2^kv`.
fn scaled_scene(kl: i32, kv: i32) -> (Sphere<f64>, Vec3<f64>, OrientedBox<f64>, Vec3<f64>) {
    let (l, s) = (2f64.powi(kl), 2f64.powi(kv));
    let b = OrientedBox::new(v(0.5 * l, -0.25 * l, 0.125 * l), v(l, 0.5 * l, 2.0 * l), [2.0, 0.0, 0.0, 1.0]);
    let a = Sphere::new(v(3.0 * l, 4.5 * l, 1.0 * l), 0.75 * l);
    (a, v(-2.0 * s, -3.0 * s, -0.25 * s), b, v(0.5 * s, 0.25 * s, 0.0))
}

#[test]
fn scaled_scenes_scale_their_answers() {
    let (a, va, b, vb) = scaled_scene(0, 0);
    let base = robust(&a, &va, &b, &vb, 4.0).expect("the unit scene has an impact");
    assert!(base.t > 0.0 && !base.degenerate);
    let rel = |got: f64, want: f64, what: &str| {
        let tol = SCALED_REL_EPS * f64::EPSILON * want.abs();
        assert!((got - want).abs() <= tol, "{what}: got {got:e}, want {want:e}");
    };
    // Lengths and speeds alike: t unchanged, the point scaled.
    for k in [500, -500] {
        let (a, va, b, vb) = scaled_scene(k, k);
        let got = robust(&a, &va, &b, &vb, 4.0).unwrap_or_else(|| panic!("2^{k}: impact"));
        rel(got.t, base.t, &format!("2^{k}: t"));
        for i in 0..3 {
            rel(got.point[i] * 2f64.powi(-k), base.point[i], &format!("2^{k}: point[{i}]"));
            rel(got.normal[i], base.normal[i], &format!("2^{k}: normal[{i}]"));
        }
    }
    // Lengths by 2^−500, speeds by 2^500: t scaled by 2^−1000 (about 1e-301),
    // still representable.
    let (a, va, b, vb) = scaled_scene(-500, 500);
    let got = robust(&a, &va, &b, &vb, 4.0).expect("tiny scene, fast motion");
    rel(got.t * 2f64.powi(1000), base.t, "mixed: t");
    for i in 0..3 {
        rel(got.point[i] * 2f64.powi(500), base.point[i], &format!("mixed: point[{i}]"));
    }
}

#[test]
fn huge_t_max_stays_finite() {
    // parry's "no limit": the head-on impact at 1.5 is found as it is.
    let a = Sphere::new(v::<f64>(3.0, 0.0, 0.0), 0.5);
    let k = robust(&a, &v(-1.0, 0.0, 0.0), &unit_box(), &still(), f64::MAX).expect("impact");
    close(k.t, 1.5, hand_tol::<f64>(), "t");
    // A far sphere creeping toward the box: its impact at about 1e600 is
    // beyond the range, so no answer (never an infinity).
    let a = Sphere::new(v::<f64>(1e300, 0.0, 0.0), 1.0);
    assert!(robust(&a, &v(-1e-300, 0.0, 0.0), &unit_box(), &still(), f64::MAX).is_none());
    // A box of half-extent 1e300 rushing at 1e300 against a sphere far
    // beyond: t = (1.5e308 − 1e300 − 1)/(2e300) ≈ 7.5e7, and the point lies
    // near 1.5e308, within the range.
    let a = Sphere::new(v::<f64>(1.5e308, 0.0, 0.0), 1.0);
    let b = OrientedBox::axis_aligned(Vec3::zeros(), v(1e300, 1e300, 1e300));
    let k = robust(&a, &v(-1e300, 0.0, 0.0), &b, &v(1e300, 0.0, 0.0), f64::MAX).expect("impact");
    let want = (1.5e308 - 1e300) / 2e300;
    assert!((k.t - want).abs() <= hand_tol::<f64>() * want, "t {} want {want}", k.t);
    assert!(k.point.iter().all(|x| x.is_finite()));
}

/// A sphere of radius `s = 2^−600` at an edge of a needle (half-extents
/// `(1, s, s)`): the edge's offsets and radius, squared, would underflow
/// without the per-feature scaling (the scene's own scale is 1). The edge
/// scene of [`onto_an_edge`] across the needle, in units of `s`: centre
/// `(0.5, 5s, 1.6s)` moving −y at speed 1 meets the edge along x at
/// `(y, z) = (s, s)` when `(y − s)² + (0.6 s)² = s²`: `y = 1.8 s`,
/// `t = 3.2 s`; normal `(0, 0.8, 0.6)`, point `(0.5, s, s)`. (A tiny sphere
/// at a corner of a unit box is not representable: `1 + 2^−600` is 1.)
#[test]
fn tiny_sphere_at_an_edge_of_a_needle() {
    let s = 2f64.powi(-600);
    let b = OrientedBox::axis_aligned(Vec3::zeros(), v(1.0, s, s));
    let a = Sphere::new(v::<f64>(0.5, 5.0 * s, 1.6 * s), s);
    let k = robust(&a, &v(0.0, -1.0, 0.0), &b, &still(), 1.0).expect("impact");
    let rel = |got: f64, want: f64| (got - want).abs() <= HAND_TOL_EPS * f64::EPSILON * want.abs();
    assert!(rel(k.t, 3.2 * s), "t {:e}", k.t);
    assert!(rel(k.point.x, 0.5) && rel(k.point.y, s) && rel(k.point.z, s), "point {:?}", k.point);
    close_v(&k.normal, [0.0, 0.8, 0.6], hand_tol::<f64>(), "normal");
}

// ------------------------------------------------------------- properties

/// Agreement, in the random scenes, between the robust answer and the static
/// tests around it: the sampled times before `t` may be in contact by at most
/// this much of the scene's scale (the static test is exact, the time a few
/// roundings of the scene over the closing speed, so a sample just before a
/// grazing contact may touch by a rounding), and the centre at `t` is at `r`
/// from the reported point to within it. Units: ε times the scene's scale.
const PROP_TOL_EPS: f64 = 256.0;

/// Samples of `[0, t)` checked for no contact.
const SAMPLES: u32 = 64;

#[derive(Clone, Debug)]
struct Scene {
    m: [f64; 3],
    r: f64,
    va: [f64; 3],
    c: [f64; 3],
    h: [f64; 3],
    q: [f64; 4],
    vb: [f64; 3],
}

/// Random scenes aimed near the box: the sphere's centre heads for a point
/// within 3 of the box's centre (box half-extents up to 2, radius up to 2),
/// reached at a time in `[0.25, 3]` against the step's 2 — so that hits on
/// faces, edges and corners, grazes, misses and late impacts are all common.
fn scene() -> impl Strategy<Value = Scene> {
    let p = || [-6.0..6.0f64, -6.0..6.0f64, -6.0..6.0f64];
    let off = || [-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64];
    let s = || [-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64];
    let q = [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64];
    let h = [0.0..2.0f64, 0.0..2.0f64, 0.0..2.0f64];
    ((p(), 0.0..2.0f64, off(), 0.25..3.0f64), (p(), h, q, s())).prop_map(|((m, r, aim, when), (c, h, q, vb))| {
        let va = [0, 1, 2].map(|k| (c[k] + aim[k] + vb[k] * when - m[k]) / when);
        Scene { m, r, va, c, h, q, vb }
    })
}

fn robust_agrees_with_static_tests<T: Real>(s: &Scene) -> Result<(), TestCaseError> {
    let p = |x: [f64; 3]| v::<T>(x[0], x[1], x[2]);
    let a = Sphere::new(p(s.m), T::of(s.r));
    let b = OrientedBox::new(p(s.c), p(s.h), s.q.map(T::of));
    let (va, vb) = (p(s.va), p(s.vb));
    let t_max = T::of(2.0);
    let scale = 40.0;
    let tol = PROP_TOL_EPS * eps::<T>() * scale;
    let at = |t: f64, grow: f64| {
        let t = T::of(t);
        let moved = OrientedBox { center: b.center + vb * t, ..b };
        contact_sphere_box(&Sphere::new(a.center + va * t, a.radius + T::of(grow)), &moved)
    };
    let got = toi_sphere_box(&a, &va, &b, &vb, t_max);
    let lecture = toi_sphere_box_halving(&a, &va, &b, &vb, t_max, Halving::Steps(60));
    match got {
        None => {
            // No impact: halving (which sees less) sees none either, and the
            // end of the step is clear.
            prop_assert!(lecture.is_none(), "halving found {lecture:?}");
            for i in 0..=SAMPLES {
                let ti = 2.0 * f64::from(i) / f64::from(SAMPLES);
                prop_assert!(at(ti, -tol).is_none(), "contact at {ti}, none reported");
            }
        }
        Some(k) => {
            let t = k.t.wide();
            prop_assert!((0.0..=2.0).contains(&t));
            prop_assert!(k.normal.iter().all(|x| x.finite()) && k.point.iter().all(|x| x.finite()));
            let len = (k.normal.norm().wide() - 1.0).abs();
            prop_assert!(len <= 4.0 * eps::<T>(), "normal length off by {len:e}");
            if k.status == ToiStatus::Penetrating {
                prop_assert!(t == 0.0 && at(0.0, 0.0).is_some());
                return Ok(());
            }
            prop_assert_eq!(k.status, ToiStatus::Converged);
            // Touching at t, within tolerance: the centre then is r from the
            // point, along the normal.
            let centre = a.center + va * k.t;
            let off = (centre - k.point).map(|x| x.wide());
            let gap = off.norm() - s.r;
            prop_assert!(gap.abs() <= tol, "gap at t {gap:e}");
            if s.r > 0.0 {
                let along = off.dot(&k.normal.map(|x| x.wide()));
                prop_assert!((along - s.r).abs() <= tol, "the normal is off: {along} for r {}", s.r);
            }
            // Not in contact before t (shrunk by the tolerance).
            for i in 0..SAMPLES {
                let ti = t * f64::from(i) / f64::from(SAMPLES);
                prop_assert!(at(ti, -tol).is_none(), "contact at {ti} before {t}");
            }
            // Halving's time is never before the first contact.
            if let Some(h) = lecture {
                prop_assert!(h.t.wide() >= t - tol, "halving at {:?} before {t}", h.t);
            }
        }
    }
    Ok(())
}

prop_both!(512, robust_random_scenes, scene(), robust_agrees_with_static_tests);
