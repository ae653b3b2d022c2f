//! Tests of box–box, box–triangle, capsule–box and capsule–triangle contact:
//! hand-derived cases (the derivation beside each) for both methods in `f32`
//! and `f64`, every degenerate case and its fallback, the robust forms at
//! `2^±997`, exact touching against the 3-4-5 rotation, a property check of
//! the robust box–box depth against the exact overlap test, no NaN anywhere,
//! and the cases where the lecture's form is known wrong, asserted as they
//! are.

use crate::boxes::*;
use crate::contact::Contact;
use crate::real::{Real, Vec3};
use crate::shapes::Triangle;
use crate::test_support::{both, eps, v};

/// Hand-derived answers on small inputs (coordinates ≤ 8): exact or a few
/// roundings in the type under test (the lecture's normalized rotation, the
/// robust form's rounded `R̃`, `3/5` and `4/5` not being binary, square roots
/// of 2). Units: ε of the type times `1 + |expected|`.
const HAND_EPS: f64 = 16.0;

/// The lecture's box–box depths carry [`OBB_EPSILON`] (`1e-6`) on every
/// rotation entry, times the half-extents (≤ 1 here, three per box) and over
/// `‖L‖ ≥ 1/√2`: within `1e-5` of the exact depth, by design.
const LECTURE_EPS: f64 = 1e-5;

/// The robust forms at `2^±997`: the unit scene scaled, answered to a few
/// ulps of its own size. Units: `f64` ε, relative to the scene's scale.
const SCALED_EPS: f64 = 16.0;

/// The extreme scales: `2^±997` (about `1.3e300` and `7.5e-301`), powers of
/// two so that a scaled scene touches exactly where the unit one does.
const EXTREMES: [f64; 2] = [f64::from_bits((1023 + 997) << 52), f64::from_bits((1023 - 997) << 52)];

fn close<T: Real>(got: T, want: f64, tol: f64) -> bool {
    (got.wide() - want).abs() <= tol * (1.0 + want.abs())
}

fn hand<T: Real>() -> f64 {
    HAND_EPS * eps::<T>()
}

fn close3<T: Real>(got: &Vec3<T>, want: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| close(got[i], want[i], tol))
}

/// Whether `p` lies in the axis-aligned set `[lo, hi]` (a face, an edge or a
/// point of the touching set) within `tol` (times `1 + |coordinate|`).
fn within<T: Real>(p: &Vec3<T>, lo: [f64; 3], hi: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| {
        let x = p[i].wide();
        x >= lo[i] - tol * (1.0 + lo[i].abs()) && x <= hi[i] + tol * (1.0 + hi[i].abs())
    })
}

fn cube<T: Real>(c: [f64; 3], h: [f64; 3]) -> OrientedBox<T> {
    OrientedBox::axis_aligned(v(c[0], c[1], c[2]), v(h[0], h[1], h[2]))
}

fn turned<T: Real>(c: [f64; 3], h: [f64; 3], q: [f64; 4]) -> OrientedBox<T> {
    OrientedBox::new(v(c[0], c[1], c[2]), v(h[0], h[1], h[2]), q.map(T::of))
}

/// The 3-4-5 rotation about z: `q = [2, 0, 0, 1]`, axes `(3/5, 4/5, 0)`,
/// `(−4/5, 3/5, 0)`, `(0, 0, 1)`.
const Q345: [f64; 4] = [2.0, 0.0, 0.0, 1.0];

fn capsule<T: Real>(a: [f64; 3], b: [f64; 3], r: f64) -> Capsule<T> {
    Capsule::new(v(a[0], a[1], a[2]), v(b[0], b[1], b[2]), T::of(r))
}

fn tri<T: Real>(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Triangle<T> {
    Triangle::new(v(a[0], a[1], a[2]), v(b[0], b[1], b[2]), v(c[0], c[1], c[2]))
}

fn got<T: Real>(k: Option<Contact<T>>, what: &str) -> Contact<T> {
    k.unwrap_or_else(|| panic!("{what}: no contact"))
}

/// Normal, depth and flag of a contact.
fn check<T: Real>(k: &Contact<T>, normal: [f64; 3], depth: f64, degen: bool, tol: f64, what: &str) {
    assert!(close3(&k.normal, normal, hand::<T>()), "{what}: normal {:?}, want {normal:?}", k.normal);
    assert!(close(k.depth, depth, tol), "{what}: depth {:?}, want {depth}", k.depth);
    assert_eq!(k.degenerate, degen, "{what}: degenerate ({k:?})");
}

type BoxBox<T> = fn(&OrientedBox<T>, &OrientedBox<T>) -> Option<Contact<T>>;
type BoxTri<T> = fn(&OrientedBox<T>, &Triangle<T>) -> Option<Contact<T>>;
type CapBox<T> = fn(&Capsule<T>, &OrientedBox<T>) -> Option<Contact<T>>;
type CapTri<T> = fn(&Capsule<T>, &Triangle<T>) -> Option<Contact<T>>;

fn box_box<T: Real>() -> [(&'static str, BoxBox<T>, f64); 2] {
    [("lecture", contact_box_box_lecture, LECTURE_EPS), ("robust", contact_box_box, hand::<T>())]
}
fn box_tri<T: Real>() -> [(&'static str, BoxTri<T>); 2] {
    [("lecture", contact_box_triangle_lecture), ("robust", contact_box_triangle)]
}
fn cap_box<T: Real>() -> [(&'static str, CapBox<T>); 2] {
    [("lecture", contact_capsule_box_lecture), ("robust", contact_capsule_box)]
}
fn cap_tri<T: Real>() -> [(&'static str, CapTri<T>); 2] {
    [("lecture", contact_capsule_triangle_lecture), ("robust", contact_capsule_triangle)]
}

// ---------------------------------------------------------------------------
// Box–box
// ---------------------------------------------------------------------------

fn box_box_hand<T: Real>() {
    let b = cube::<T>([0.0; 3], [1.0; 3]);
    for (name, f, tol) in box_box::<T>() {
        // Resting partly on b's top: a spans z ∈ [0.75, 1.75], b's top is at
        // 1: push +z = 1 − 0.75 = 0.25 (x: 1 + 0.25 = 1.25 at least; y: 1.5).
        // The touching set: a's bottom face lifted to z = 1, x ∈ [−0.25,
        // 0.75], y ∈ [−0.5, 0.5], inside b's top.
        let a = cube::<T>([0.25, 0.0, 1.25], [0.5; 3]);
        let k = got(f(&a, &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.25, false, tol, name);
        assert!(within(&k.point, [-0.25, -0.5, 1.0], [0.75, 0.5, 1.0], tol), "{name}: {k:?}");
        if name == "robust" {
            // The average of the set's corners is its centre.
            assert!(close3(&k.point, [0.25, 0.0, 1.0], tol), "{name}: {k:?}");
        }
        // Touching face on face (depth 0) is contact.
        let a = cube::<T>([0.0, 0.0, 1.5], [0.5; 3]);
        let k = got(f(&a, &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.0, false, tol, name);
        assert!(within(&k.point, [-0.5, -0.5, 1.0], [0.5, 0.5, 1.0], tol), "{name}: {k:?}");
        // Apart by 0.25: none.
        assert!(f(&cube([0.0, 0.0, 1.75], [0.5; 3]), &b).is_none(), "{name}: apart");
        // Below, pushed down: normal −z.
        let k = got(f(&cube([0.0, 0.0, -1.25], [0.5; 3]), &b), name);
        check(&k, [0.0, 0.0, -1.0], 0.25, false, tol, name);
        assert!(within(&k.point, [-0.5, -0.5, -1.0], [0.5, 0.5, -1.0], tol), "{name}: {k:?}");
    }
}
both!(box_box_hand_derived, box_box_hand);

fn box_box_rotated<T: Real>() {
    // b turned 3-4-5 about z (B_x = (0.6, 0.8, 0)); a an unturned cube of
    // half-extent 0.5 at c = 1.25 B_x = (0.75, 1, 0). Along B_x a reaches down
    // to 1.25 − 0.5 (0.6 + 0.8) = 0.55: push 1 − 0.55 = 0.45. The others are
    // longer: x 1.4 − 0.25 = 1.15, y 1.4 − 0.5 = 0.9, B_y 1 + 0.7 = 1.7, z 1.5;
    // A_z × B_y = −B_x gives the same push along the same direction (no
    // tie). The touching set: a's edge {(0.25, 0.5, z)} moved by 0.45 B_x =
    // (0.27, 0.36, 0): {(0.52, 0.86, z), |z| ≤ 0.5}, on b's face (B_x · p = 1,
    // B_y · p = 0.1).
    let b = turned::<T>([0.0; 3], [1.0; 3], Q345);
    let a = cube::<T>([0.75, 1.0, 0.0], [0.5; 3]);
    for (name, f, tol) in box_box::<T>() {
        let k = got(f(&a, &b), name);
        check(&k, [0.6, 0.8, 0.0], 0.45, false, tol, name);
        assert!(within(&k.point, [0.52, 0.86, -0.5], [0.52, 0.86, 0.5], tol), "{name}: {k:?}");
        // Swapped: the normal flips, the depth stays, and the touching set is
        // the cube's edge {(0.25, 0.5, z)}. (The lecture's point is the
        // turned box's deepest vertex moved out, off that edge: not asserted.)
        let k = got(f(&b, &a), name);
        check(&k, [-0.6, -0.8, 0.0], 0.45, false, tol, name);
        if name == "robust" {
            assert!(within(&k.point, [0.25, 0.5, -0.5], [0.25, 0.5, 0.5], tol), "{name}: swapped {k:?}");
        }
    }
}
both!(box_box_rotated_3_4_5, box_box_rotated);

fn box_box_edge_edge<T: Real>() {
    // a turned 45° about y (its lowest edge along y, at z = z_a − √2), b
    // turned 45° about x (its highest edge along x, at z = √2): crossing
    // edges. With z_a = 2√2 − 0.25 the push along z is 0.25; every face axis
    // pushes 1 + (1 + √2)/2 − (2 − 0.25/√2) ≈ 0.88. The edges touch at
    // (0, 0, √2) after the push.
    let (c, s) = (22.5f64.to_radians().cos(), 22.5f64.to_radians().sin());
    let r2 = 2f64.sqrt();
    let a = turned::<T>([0.0, 0.0, 2.0 * r2 - 0.25], [1.0; 3], [c, 0.0, s, 0.0]);
    let b = turned::<T>([0.0; 3], [1.0; 3], [c, s, 0.0, 0.0]);
    for (name, f, tol) in box_box::<T>() {
        let k = got(f(&a, &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.25, false, tol.max(4.0 * hand::<T>()), name);
        assert!(close3(&k.point, [0.0, 0.0, r2], 4.0 * tol), "{name}: {k:?}");
    }
}
both!(box_box_edge_against_edge, box_box_edge_edge);

fn box_box_degenerate<T: Real>() {
    let b = cube::<T>([0.0; 3], [1.0; 3]);
    for (name, f, tol) in box_box::<T>() {
        // Concentric: every face pushes 2 both ways; the first in the order,
        // +A_x: normal (1, 0, 0), depth 2, the set the face x = 1.
        let k = got(f(&b, &b), name);
        check(&k, [1.0, 0.0, 0.0], 2.0, true, tol, name);
        if name == "robust" {
            assert!(within(&k.point, [1.0, -1.0, -1.0], [1.0, 1.0, 1.0], tol), "{name}: {k:?}");
        }
        // Over a corner: pushes 0.5 along +x and along +y tie; +A_x answers.
        // The set: x = 1, y ∈ [0.5, 1], |z| ≤ 1.
        let k = got(f(&cube([1.5, 1.5, 0.0], [1.0; 3]), &b), name);
        check(&k, [1.0, 0.0, 0.0], 0.5, true, tol, name);
        if name == "robust" {
            assert!(close3(&k.point, [1.0, 0.75, 0.0], tol), "{name}: {k:?}");
        }
        // Flat plate lying on the top face (h_z = 0): depth 0 along +z, the
        // set the plate.
        let k = got(f(&cube([0.0, 0.0, 1.0], [0.5, 0.5, 0.0]), &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.0, false, tol, name);
        assert!(within(&k.point, [-0.5, -0.5, 1.0], [0.5, 0.5, 1.0], tol), "{name}: {k:?}");
        // A plate sunk to z = 0.75: push 0.25 up.
        let k = got(f(&cube([0.0, 0.0, 0.75], [0.5, 0.5, 0.0]), &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.25, false, tol, name);
        // Two concentric plates: the least push is 0 along ±z, a tie both
        // ways; +A_z answers (A_x, A_y push 2).
        let p = cube::<T>([0.0; 3], [1.0, 1.0, 0.0]);
        let k = got(f(&p, &p), name);
        check(&k, [0.0, 0.0, 1.0], 0.0, true, tol, name);
        assert!(within(&k.point, [-1.0, -1.0, 0.0], [1.0, 1.0, 0.0], tol), "{name}: {k:?}");
        // A zero quaternion is the identity.
        let z = OrientedBox::new(v(0.0, 0.0, 1.25), v(0.5, 0.5, 0.5), [T::zero(); 4]);
        check(&got(f(&z, &b), name), [0.0, 0.0, 1.0], 0.25, false, tol, name);
    }
}
both!(box_box_degenerate_cases, box_box_degenerate);

/// a touching the 3-4-5 box's face `B_x · x = 1` exactly: a's lowest edge
/// along `B_x` is at `0.6·0.5 + 0.8·1.75 − 0.5·1.4 = 1` (every term binary
/// but the rotation's), so the push is exactly 0; one ulp further out it is
/// apart. The touching set is a's edge `{(0, 1.25, z)}`.
fn box_box_exact_345<T: Real>() {
    let b = turned::<T>([0.0; 3], [1.0; 3], Q345);
    let k = got(contact_box_box(&cube([0.5, 1.75, 0.0], [0.5; 3]), &b), "touching");
    check(&k, [0.6, 0.8, 0.0], 0.0, false, hand::<T>(), "touching");
    assert!(within(&k.point, [0.0, 1.25, -0.5], [0.0, 1.25, 0.5], hand::<T>()), "{k:?}");
    let y = T::of(1.75);
    let apart = OrientedBox::axis_aligned(Vec3::new(T::of(0.5), y + y * T::EPSILON, T::zero()), v(0.5, 0.5, 0.5));
    assert!(contact_box_box(&apart, &b).is_none(), "an ulp apart");
    // The same quaternion at another length ([6, 0, 0, 3]) is the same box.
    let b3 = turned::<T>([0.0; 3], [1.0; 3], [6.0, 0.0, 0.0, 3.0]);
    assert!(contact_box_box(&apart, &b3).is_none());
    assert!(contact_box_box(&cube([0.5, 1.75, 0.0], [0.5; 3]), &b3).is_some_and(|k| k.depth == T::zero()));
}
both!(box_box_robust_is_exact_for_the_quaternions_rotation, box_box_exact_345);

#[test]
fn box_box_robust_at_extreme_scales() {
    for s in EXTREMES {
        let b = OrientedBox::new(Vec3::zeros(), Vec3::new(s, s, s), Q345);
        let a = OrientedBox::axis_aligned(Vec3::new(0.75 * s, s, 0.0), Vec3::new(0.5 * s, 0.5 * s, 0.5 * s));
        let k = contact_box_box(&a, &b).expect("rotated");
        let tol = SCALED_EPS * f64::EPSILON;
        assert!(close(k.depth / s, 0.45, tol) && close3(&k.normal, [0.6, 0.8, 0.0], tol), "{s:e}: {k:?}");
        assert!(within(&(k.point / s), [0.52, 0.86, -0.5], [0.52, 0.86, 0.5], tol), "{s:e}: {k:?}");
        // Exactly touching, and an ulp apart.
        let a = OrientedBox::axis_aligned(Vec3::new(0.5 * s, 1.75 * s, 0.0), Vec3::new(0.5 * s, 0.5 * s, 0.5 * s));
        assert!(contact_box_box(&a, &b).is_some_and(|k| k.depth == 0.0 && !k.degenerate), "{s:e}");
        let a = OrientedBox { center: Vec3::new(0.5 * s, (1.75 * s).next_up(), 0.0), ..a };
        assert!(contact_box_box(&a, &b).is_none(), "{s:e}: an ulp apart");
        // Concentric at scale: degenerate, depth 2s.
        let k = contact_box_box(&b, &b).expect("concentric");
        assert!(k.degenerate && close(k.depth / s, 2.0, tol), "{s:e}: {k:?}");
    }
}

#[test]
fn box_box_far_from_the_origin() {
    // The resting case moved by 2^40 in x: the robust form keeps the depth
    // exact (it comes from the exact polynomials), the point to the scene's
    // rounding.
    let o = 2f64.powi(40);
    let b = OrientedBox::axis_aligned(Vec3::new(o, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let a = OrientedBox::axis_aligned(Vec3::new(o + 0.25, 0.0, 1.25), Vec3::new(0.5, 0.5, 0.5));
    let k = contact_box_box(&a, &b).expect("resting");
    // Exact by construction: the push is 0.25 exactly, ‖L‖ = ‖q‖² = 1, and the
    // point lies in b's top face z = 1 (its plane's basis has no z part).
    assert_eq!(k.depth.to_bits(), 0.25f64.to_bits(), "{k:?}");
    assert!(!k.degenerate, "{k:?}");
    assert!((k.point.x - (o + 0.25)).abs() <= 1e-3 && k.point.z.to_bits() == 1f64.to_bits(), "{k:?}");
}

#[test]
fn box_box_lecture_is_wrong_within_its_epsilon() {
    // Known wrong, asserted as it is: 1e-7 apart along z, the lecture's
    // widened projections (OBB_EPSILON on every |R_ij|) overlap; the robust
    // form sees the gap.
    let b = cube::<f64>([0.0; 3], [1.0; 3]);
    let a = cube::<f64>([0.0, 0.0, 1.5 + 1e-7], [0.5; 3]);
    assert!(contact_box_box_lecture(&a, &b).is_some(), "the lecture's epsilon");
    assert!(contact_box_box(&a, &b).is_none());
    // And its depth of the resting case is too deep by the epsilon's share.
    let a = cube::<f64>([0.0, 0.0, 1.25], [0.5; 3]);
    let k = contact_box_box_lecture(&a, &b).expect("resting");
    assert!(k.depth > 0.25 && k.depth < 0.25 + LECTURE_EPS, "{k:?}");
}

/// A small deterministic generator (xorshift), as in tests.rs.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn real(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }
    /// Quarters in [−2, 2]: exact, so ties and touching happen.
    fn quarter(&mut self) -> f64 {
        (self.next() % 17) as f64 / 4.0 - 2.0
    }
    fn quaternion(&mut self) -> [f64; 4] {
        const EXACT: [[f64; 4]; 6] = [
            [1.0, 0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0, 1.0],
            [2.0, 1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0, 1.0],
        ];
        if self.next().is_multiple_of(2) {
            EXACT[(self.next() % 6) as usize]
        } else {
            [0; 4].map(|_| self.real(-1.0, 1.0))
        }
    }
}

/// Cases of the depth property check: each a pair of random boxes, half of
/// them on a grid of quarters with exact rotations (touching and ties).
const DEPTH_CASES: usize = 2000;

/// The relative step beyond the depth that must separate the boxes: the
/// depth is accurate to `2^−40` relative, the translation by it rounded to
/// the scene's ulps, so `2^−30` of the scene (plus that of the depth) is far
/// beyond both.
const DEPTH_STEP: f64 = 1.0 / (1u64 << 30) as f64;

#[test]
fn box_box_robust_depth_is_the_least_separating_translation() {
    // The depth along the normal is the exact penetration depth: moving a by
    // (depth − step)·n leaves the boxes overlapping, by (depth + step)·n
    // separates them (decided by the exact overlap test, test_box_box). And
    // the point lies on b and on the moved a (each within the tolerance).
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut contacts = 0;
    for i in 0..DEPTH_CASES {
        let grid = i % 2 == 0;
        let x: [f64; 12] = std::array::from_fn(|_| if grid { rng.quarter() } else { rng.real(-2.0, 2.0) });
        let (ca, cb) = (Vec3::new(x[0], x[1], x[2]), Vec3::new(x[3], x[4], x[5]));
        let (ha, hb) = (Vec3::new(x[6], x[7], x[8]).abs(), Vec3::new(x[9], x[10], x[11]).abs());
        let a = OrientedBox::new(ca, ha, rng.quaternion());
        let b = OrientedBox::new(cb, hb, rng.quaternion());
        let overlap = test_box_box(&a, &b);
        let k = contact_box_box(&a, &b);
        assert_eq!(overlap, k.is_some(), "case {i}: contact iff overlap: {a:?} {b:?} {k:?}");
        let Some(k) = k else { continue };
        contacts += 1;
        assert!(k.depth >= 0.0 && (k.normal.norm() - 1.0).abs() < 1e-12, "case {i}: {k:?}");
        let step = DEPTH_STEP * (8.0 + k.depth);
        let moved = |d: f64| OrientedBox { center: a.center + k.normal * d, ..a };
        assert!(!test_box_box(&moved(k.depth + step), &b), "case {i}: depth too short: {a:?} {b:?} {k:?}");
        if k.depth > step {
            assert!(test_box_box(&moved(k.depth - step), &b), "case {i}: depth too long: {a:?} {b:?} {k:?}");
        }
        // The point is on b and on the moved a: a small box there overlaps both.
        let dot = OrientedBox::axis_aligned(k.point, Vec3::new(step, step, step));
        assert!(test_box_box(&dot, &b) && test_box_box(&dot, &moved(k.depth)), "case {i}: point {a:?} {b:?} {k:?}");
    }
    assert!(contacts > DEPTH_CASES / 10, "too few contacts: {contacts}");
}

// ---------------------------------------------------------------------------
// Box–triangle
// ---------------------------------------------------------------------------

fn box_triangle_hand<T: Real>() {
    // The triangle (−2, −2, 0), (4, −2, 0), (−2, 4, 0): normal +z (36 z).
    let t = tri::<T>([-2.0, -2.0, 0.0], [4.0, -2.0, 0.0], [-2.0, 4.0, 0.0]);
    for (name, f) in box_tri::<T>() {
        // A cube of half-extent 0.5 at z = 0.25 sunk 0.25 below the plane:
        // push +z 0.25 (−z 0.75; x, y and the edges' normals ≥ 1.5). The set:
        // its bottom face lifted to z = 0, inside the triangle.
        let k = got(f(&cube([0.0, 0.0, 0.25], [0.5; 3]), &t), name);
        check(&k, [0.0, 0.0, 1.0], 0.25, false, hand::<T>(), name);
        assert!(within(&k.point, [-0.5, -0.5, 0.0], [0.5, 0.5, 0.0], hand::<T>()), "{name}: {k:?}");
        // From below, pushed down.
        let k = got(f(&cube([0.0, 0.0, -0.25], [0.5; 3]), &t), name);
        check(&k, [0.0, 0.0, -1.0], 0.25, false, hand::<T>(), name);
        // Touching from above: depth 0; apart: none.
        let k = got(f(&cube([0.0, 0.0, 0.5], [0.5; 3]), &t), name);
        check(&k, [0.0, 0.0, 1.0], 0.0, false, hand::<T>(), name);
        assert!(f(&cube([0.0, 0.0, 0.75], [0.5; 3]), &t).is_none(), "{name}: apart");
        // Beside the triangle's hypotenuse x + y = 2: a cube at (2, 2, 0)
        // reaches x + y ≥ 3 > 2: apart along the edge's normal (1, 1, 0)/√2.
        assert!(f(&cube([2.0, 2.0, 0.0], [0.5; 3]), &t).is_none(), "{name}: beyond the hypotenuse");
        // Across the hypotenuse: the cube at (1.25, 1.25, 0) spans
        // x + y ∈ [1.5, 3.5], the triangle x + y ≤ 2: along (1, 1)/√2 the
        // push is (2 − 1.5)/√2 = √2/4 (z: 0.5 both ways; x, y: over 3), the
        // edge's normal (A_z × E_1 = (−6, −6, 0), along −L). The set: a's
        // edge {(0.75, 0.75, z)} moved onto the hypotenuse: {(1, 1, z)},
        // |z| ≤ 0.5.
        let k = got(f(&cube([1.25, 1.25, 0.0], [0.5; 3]), &t), name);
        let s = 0.5f64.sqrt();
        check(&k, [s, s, 0.0], 0.5 * s, false, hand::<T>(), name);
        assert!(within(&k.point, [1.0, 1.0, -0.5], [1.0, 1.0, 0.5], hand::<T>()), "{name}: {k:?}");
    }
}
both!(box_triangle_hand_derived, box_triangle_hand);

fn box_triangle_tilted<T: Real>() {
    // The triangle (−4, −5, 3), (4, −5, −3), (0, 5, 0): normal 20 (3, 0, 4),
    // plane 3x + 4z = 0. A cube of half-extent 0.5 at (0.3, 0, 0.4) = 0.5 n
    // reaches down to 0.5 − 0.7 = −0.2: push 0.2 along n = (0.6, 0, 0.8).
    // The set: its edge {(−0.2, y, −0.1)} moved by 0.2 n: {(−0.08, y, 0.06)},
    // |y| ≤ 0.5.
    let t = tri::<T>([-4.0, -5.0, 3.0], [4.0, -5.0, -3.0], [0.0, 5.0, 0.0]);
    for (name, f) in box_tri::<T>() {
        let k = got(f(&cube([0.3, 0.0, 0.4], [0.5; 3]), &t), name);
        check(&k, [0.6, 0.0, 0.8], 0.2, false, hand::<T>(), name);
        assert!(within(&k.point, [-0.08, -0.5, 0.06], [-0.08, 0.5, 0.06], hand::<T>()), "{name}: {k:?}");
    }
}
both!(box_triangle_tilted_3_4_5, box_triangle_tilted);

fn box_triangle_degenerate<T: Real>() {
    let t = tri::<T>([-2.0, -2.0, 0.0], [4.0, -2.0, 0.0], [-2.0, 4.0, 0.0]);
    for (name, f) in box_tri::<T>() {
        // The cube's centre on the plane: ±z push 0.5 both ways, a tie; +A_z
        // (before the triangle's normal) answers.
        let k = got(f(&cube([0.0; 3], [0.5; 3]), &t), name);
        check(&k, [0.0, 0.0, 1.0], 0.5, true, hand::<T>(), name);
        assert!(within(&k.point, [-0.5, -0.5, 0.0], [0.5, 0.5, 0.0], hand::<T>()), "{name}: {k:?}");
        // A zero-area triangle (a segment on the x axis) under a cube at
        // z = 0.25: no normal; +z by 0.25 (A_y pushes 0.5 both ways, the
        // edge crosses ∥ z or y). The set: the segment x ∈ [−0.5, 0.5].
        let seg = tri::<T>([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]);
        let k = got(f(&cube([0.0, 0.0, 0.25], [0.5; 3]), &seg), name);
        check(&k, [0.0, 0.0, 1.0], 0.25, false, hand::<T>(), name);
        assert!(within(&k.point, [-0.5, 0.0, 0.0], [0.5, 0.0, 0.0], hand::<T>()), "{name}: {k:?}");
        // A flat box (a plate, h_z = 0) lying in the triangle's plane: 0
        // both ways along z, a tie; +A_z answers with depth 0.
        let k = got(f(&cube([0.0; 3], [0.5, 0.5, 0.0]), &t), name);
        check(&k, [0.0, 0.0, 1.0], 0.0, true, hand::<T>(), name);
    }
}
both!(box_triangle_degenerate_cases, box_triangle_degenerate);

#[test]
fn box_triangle_robust_at_extreme_scales_and_exactly_touching() {
    // The 3-4-5 box's face B_x · x = 1 and a triangle whose nearest vertex
    // v = (1, 0.5, 0) has B_x · v = 0.6 + 0.4 = 1 exactly (B_y · v = −0.5,
    // inside the face; the others at B_x · v = 3.4): touching at v; an ulp
    // further out, apart.
    for s in [1.0, EXTREMES[0], EXTREMES[1]] {
        let b = OrientedBox::new(Vec3::zeros(), Vec3::new(s, s, s), Q345);
        let t =
            Triangle::new(Vec3::new(s, 0.5 * s, 0.0), Vec3::new(3.0 * s, 2.0 * s, s), Vec3::new(3.0 * s, 2.0 * s, -s));
        let k = contact_box_triangle(&b, &t).expect("touching");
        let tol = SCALED_EPS * f64::EPSILON;
        // The normal from the triangle toward the box: −B_x.
        assert!(k.depth == 0.0 && close3(&k.normal, [-0.6, -0.8, 0.0], tol) && !k.degenerate, "{s:e}: {k:?}");
        assert!(close3(&(k.point / s), [1.0, 0.5, 0.0], tol), "{s:e}: {k:?}");
        let t = Triangle { vertices: [Vec3::new(s.next_up(), 0.5 * s, 0.0), t.vertices[1], t.vertices[2]] };
        assert!(contact_box_triangle(&b, &t).is_none(), "{s:e}: an ulp apart");
        // The tilted case at scale.
        let t = Triangle::new(
            Vec3::new(-4.0 * s, -5.0 * s, 3.0 * s),
            Vec3::new(4.0 * s, -5.0 * s, -3.0 * s),
            Vec3::new(0.0, 5.0 * s, 0.0),
        );
        let a = OrientedBox::axis_aligned(Vec3::new(0.3 * s, 0.0, 0.4 * s), Vec3::new(0.5 * s, 0.5 * s, 0.5 * s));
        let k = contact_box_triangle(&a, &t).expect("tilted");
        assert!(close(k.depth / s, 0.2, tol) && close3(&k.normal, [0.6, 0.0, 0.8], tol), "{s:e}: {k:?}");
    }
}

// ---------------------------------------------------------------------------
// Capsule–box
// ---------------------------------------------------------------------------

fn capsule_box_hand<T: Real>() {
    let b = cube::<T>([0.0; 3], [1.0; 3]);
    for (name, f) in cap_box::<T>() {
        // Parallel to the top face, 1 above it: d = 1, depth 1.5 − 1, normal
        // +z, the set the axis's shadow {(x, 0, 1)}, |x| ≤ 1.
        let k = got(f(&capsule([-1.0, 0.0, 2.0], [1.0, 0.0, 2.0], 1.5), &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.5, false, hand::<T>(), name);
        assert!(within(&k.point, [-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], hand::<T>()), "{name}: {k:?}");
        // Beside the edge (1, y, 1): d = √2, normal (1, 0, 1)/√2.
        let k = got(f(&capsule([2.0, -1.0, 2.0], [2.0, 1.0, 2.0], 2.0), &b), name);
        let s = 0.5f64.sqrt();
        check(&k, [s, 0.0, s], 2.0 - 2f64.sqrt(), false, hand::<T>(), name);
        assert!(within(&k.point, [1.0, -1.0, 1.0], [1.0, 1.0, 1.0], hand::<T>()), "{name}: {k:?}");
        // End on: the end (0, 0, 3) is 2 above the top.
        let k = got(f(&capsule([0.0, 0.0, 3.0], [0.0, 0.0, 5.0], 2.5), &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.5, false, hand::<T>(), name);
        assert!(close3(&k.point, [0.0, 0.0, 1.0], hand::<T>()), "{name}: {k:?}");
        // Touching (d = r) and apart.
        assert!(f(&capsule([0.0, 0.0, 3.0], [0.0, 0.0, 5.0], 2.0), &b).is_some_and(|k| close(
            k.depth,
            0.0,
            hand::<T>()
        )));
        assert!(f(&capsule([0.0, 0.0, 3.0], [0.0, 0.0, 5.0], 1.75), &b).is_none(), "{name}: apart");
        // The axis inside under the top face (d = 0): its own push is 0.25 up
        // (x: 1.5, y: 1 both ways; D × B_y ∥ z, D × B_z ∥ y); depth r + 0.25,
        // the set the axis lifted onto the top face.
        let k = got(f(&capsule([-0.5, 0.0, 0.75], [0.5, 0.0, 0.75], 0.5), &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.75, false, hand::<T>(), name);
        if name == "robust" {
            assert!(close3(&k.point, [0.0, 0.0, 1.0], hand::<T>()), "{name}: {k:?}");
        }
        assert!(within(&k.point, [-0.5, 0.0, 1.0], [0.5, 0.0, 1.0], hand::<T>()), "{name}: {k:?}");
    }
}
both!(capsule_box_hand_derived, capsule_box_hand);

fn capsule_box_degenerate<T: Real>() {
    let b = cube::<T>([0.0; 3], [1.0; 3]);
    for (name, f) in cap_box::<T>() {
        // Piercing up through the bottom, ending inside: ±x and ±y push 1
        // (z: 1.5 down, 4 up): a tie; +B_x answers, depth r + 1. The set: the
        // axis moved to x = 1: {(1, 0, z)}, z ∈ [−1, 0.5].
        let k = got(f(&capsule([0.0, 0.0, -3.0], [0.0, 0.0, 0.5], 0.5), &b), name);
        check(&k, [1.0, 0.0, 0.0], 1.5, true, hand::<T>(), name);
        if name == "robust" {
            assert!(close3(&k.point, [1.0, 0.0, -0.25], hand::<T>()), "{name}: {k:?}");
        }
        // A zero-length axis (a sphere) at the centre: every face 1 away, a
        // tie; +B_x. The set is the point (1, 0, 0).
        let k = got(f(&capsule([0.0; 3], [0.0; 3], 0.5), &b), name);
        check(&k, [1.0, 0.0, 0.0], 1.5, true, hand::<T>(), name);
        assert!(close3(&k.point, [1.0, 0.0, 0.0], hand::<T>()), "{name}: {k:?}");
        // A zero-length axis outside: the sphere–box answer.
        let k = got(f(&capsule([0.0, 0.0, 1.5], [0.0, 0.0, 1.5], 1.0), &b), name);
        check(&k, [0.0, 0.0, 1.0], 0.5, false, hand::<T>(), name);
        // A flat box (a plate, h_z = 0) and an axis crossing it upright: the
        // push 0.5 up or down... the axis spans z ∈ [−0.5, 0.25]: up 0.5,
        // down 0.25: −z by 0.25, depth r + 0.25.
        let plate = cube::<T>([0.0; 3], [1.0, 1.0, 0.0]);
        let k = got(f(&capsule([0.0, 0.0, -0.5], [0.0, 0.0, 0.25], 0.5), &plate), name);
        check(&k, [0.0, 0.0, -1.0], 0.75, false, hand::<T>(), name);
    }
}
both!(capsule_box_degenerate_cases, capsule_box_degenerate);

/// A capsule whose end sphere touches the 3-4-5 box's face `B_x · x = 1`
/// exactly: end `(0.5, 1.5, 0)`, `B_x · e = 0.3 + 1.2 = 1.5 = 1 + r`
/// (`B_y · e = 0.5`, inside the face), axis going out along `(3, 4, 0)`.
fn capsule_box_exact_345<T: Real>() {
    let b = turned::<T>([0.0; 3], [1.0; 3], Q345);
    let k = got(contact_capsule_box(&capsule([0.5, 1.5, 0.0], [1.25, 2.5, 0.0], 0.5), &b), "touching");
    check(&k, [0.6, 0.8, 0.0], 0.0, false, hand::<T>(), "touching");
    assert!(close3(&k.point, [0.2, 1.1, 0.0], hand::<T>()), "{k:?}");
    let r = T::of(0.5);
    let short = Capsule::new(v(0.5, 1.5, 0.0), v(1.25, 2.5, 0.0), r - r * T::EPSILON);
    assert!(contact_capsule_box(&short, &b).is_none(), "an ulp short");
}
both!(capsule_box_robust_is_exact_for_the_quaternions_rotation, capsule_box_exact_345);

#[test]
fn capsule_box_robust_at_extreme_scales() {
    let tol = SCALED_EPS * f64::EPSILON;
    for s in EXTREMES {
        let b = OrientedBox::new(Vec3::zeros(), Vec3::new(s, s, s), Q345);
        let c = Capsule::new(Vec3::new(0.5 * s, 1.5 * s, 0.0), Vec3::new(1.25 * s, 2.5 * s, 0.0), 0.5 * s);
        let k = contact_capsule_box(&c, &b).expect("touching");
        assert!(close(k.depth / s, 0.0, tol) && close3(&k.normal, [0.6, 0.8, 0.0], tol), "{s:e}: {k:?}");
        assert!(close3(&(k.point / s), [0.2, 1.1, 0.0], tol), "{s:e}: {k:?}");
        let c = Capsule { radius: (0.5 * s).next_down(), ..c };
        assert!(contact_capsule_box(&c, &b).is_none(), "{s:e}");
        // Inside under the top face of an unturned box.
        let b = OrientedBox::axis_aligned(Vec3::zeros(), Vec3::new(s, s, s));
        let c = Capsule::new(Vec3::new(-0.5 * s, 0.0, 0.75 * s), Vec3::new(0.5 * s, 0.0, 0.75 * s), 0.5 * s);
        let k = contact_capsule_box(&c, &b).expect("inside");
        assert!(close(k.depth / s, 0.75, tol) && close3(&k.normal, [0.0, 0.0, 1.0], tol), "{s:e}: {k:?}");
        assert!(close3(&(k.point / s), [0.0, 0.0, 1.0], tol) && !k.degenerate, "{s:e}: {k:?}");
        // Beside an edge.
        let c = Capsule::new(Vec3::new(2.0 * s, -s, 2.0 * s), Vec3::new(2.0 * s, s, 2.0 * s), 2.0 * s);
        let k = contact_capsule_box(&c, &b).expect("edge");
        assert!(close(k.depth / s, 2.0 - 2f64.sqrt(), tol), "{s:e}: {k:?}");
    }
}

/// An edge contact's values come from the box's corners rounded to `f64`
/// (a few ulps of the box's size) and, where the exact test says touching
/// but the rounded corners miss by an ulp, from closest points of the rounded
/// segments: within `1e-9` of the scene's scale, far below any wrong answer.
const CORNER_EPS: f64 = 1e-9;

#[test]
fn capsule_box_robust_touches_an_exact_corner_at_every_scale() {
    // The 3-4-5 box (centre (1, −0.5, 2), half-extents (0.5, 1.5, 2)) has the
    // corner c + R(−0.5, 1.5, −2) = (−0.5, 0, 0) (R's 3/5, 4/5 not binary,
    // the corner exact); the axis from (1, 1.5, −2) to (−2, 0, −1) passes at
    // exactly 1.5 from it (the referee's answer: normal (−3, 2, −6)/7). So a
    // capsule of radius 1.5 touches (depth 0), one an ulp thinner does not —
    // decided on the corner as a polynomial of q, never the rounded one.
    let tol = SCALED_EPS * f64::EPSILON;
    for s in [1.0, EXTREMES[0], EXTREMES[1]] {
        let b = OrientedBox::new(Vec3::new(s, -0.5 * s, 2.0 * s), Vec3::new(0.5 * s, 1.5 * s, 2.0 * s), Q345);
        let c = Capsule::new(Vec3::new(s, 1.5 * s, -2.0 * s), Vec3::new(-2.0 * s, 0.0, -s), 1.5 * s);
        let k = contact_capsule_box(&c, &b).expect("touching the corner");
        assert!(close(k.depth / s, 0.0, tol) && !k.degenerate, "{s:e}: {k:?}");
        assert!(close3(&k.normal, [-3.0 / 7.0, 2.0 / 7.0, -6.0 / 7.0], CORNER_EPS), "{s:e}: {k:?}");
        assert!(close3(&(k.point / s), [-0.5, 0.0, 0.0], CORNER_EPS), "{s:e}: {k:?}");
        let c = Capsule { radius: (1.5 * s).next_down(), ..c };
        assert!(contact_capsule_box(&c, &b).is_none(), "{s:e}: an ulp thinner");
    }
}

#[test]
fn capsule_box_lecture_underflows_at_tiny_scales() {
    // Known wrong, asserted as it is: at 2^−997 the lecture's plain norm of
    // the closest pair's offset (0, 0, 2^−997) squares to 0: distance 0, so
    // normal +z flagged and depth r; the robust form answers d = s, depth
    // r − d = 0.5 s.
    let s = EXTREMES[1];
    let b = OrientedBox::axis_aligned(Vec3::zeros(), Vec3::new(s, s, s));
    let c = Capsule::new(Vec3::new(-s, 0.0, 2.0 * s), Vec3::new(s, 0.0, 2.0 * s), 1.5 * s);
    let l = contact_capsule_box_lecture(&c, &b).expect("lecture");
    // Exact: the lecture's depth is r itself (r − 0).
    assert!(l.degenerate && l.depth.to_bits() == (1.5 * s).to_bits(), "{l:?}");
    let k = contact_capsule_box(&c, &b).expect("robust");
    assert!(!k.degenerate && close(k.depth / s, 0.5, SCALED_EPS * f64::EPSILON), "{k:?}");
}

// ---------------------------------------------------------------------------
// Capsule–triangle
// ---------------------------------------------------------------------------

fn capsule_triangle_hand<T: Real>() {
    let t = tri::<T>([-2.0, -2.0, 0.0], [4.0, -2.0, 0.0], [-2.0, 4.0, 0.0]);
    for (name, f) in cap_tri::<T>() {
        // End on, 1 above the face.
        let k = got(f(&capsule([0.0, 0.0, 1.0], [0.0, 0.0, 3.0], 1.5), &t), name);
        check(&k, [0.0, 0.0, 1.0], 0.5, false, hand::<T>(), name);
        assert!(close3(&k.point, [0.0; 3], hand::<T>()), "{name}: {k:?}");
        // Lying parallel 1 above: the set {(x, 0, 0)}, |x| ≤ 1.
        let k = got(f(&capsule([-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], 1.25), &t), name);
        check(&k, [0.0, 0.0, 1.0], 0.25, false, hand::<T>(), name);
        assert!(within(&k.point, [-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], hand::<T>()), "{name}: {k:?}");
        // Upright beside the edge y = −2: d = 1 to (0, −2, 0).
        let k = got(f(&capsule([0.0, -3.0, -1.0], [0.0, -3.0, 1.0], 1.5), &t), name);
        check(&k, [0.0, -1.0, 0.0], 0.5, false, hand::<T>(), name);
        assert!(close3(&k.point, [0.0, -2.0, 0.0], hand::<T>()), "{name}: {k:?}");
        assert!(f(&capsule([0.0, -3.0, -1.0], [0.0, -3.0, 1.0], 0.75), &t).is_none(), "{name}: apart");
        // Piercing the face: the axis's push is 1 up (N; down 3; the edges'
        // D × E_k: 2, √2, 2): depth r + 1, the set the point (0, 0, 0).
        let k = got(f(&capsule([0.0, 0.0, -1.0], [0.0, 0.0, 3.0], 0.5), &t), name);
        check(&k, [0.0, 0.0, 1.0], 1.5, false, hand::<T>(), name);
        if name == "robust" {
            assert!(close3(&k.point, [0.0; 3], hand::<T>()), "{name}: {k:?}");
        }
    }
}
both!(capsule_triangle_hand_derived, capsule_triangle_hand);

fn capsule_triangle_degenerate<T: Real>() {
    let t = tri::<T>([-2.0, -2.0, 0.0], [4.0, -2.0, 0.0], [-2.0, 4.0, 0.0]);
    let seg = tri::<T>([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]);
    let f = contact_capsule_triangle::<T>;
    // The axis lying in the triangle's plane across it: N pushes 0 both
    // ways, a tie; +N answers, depth r. The set: the axis, x ∈ [−1, 1].
    let k = got(f(&capsule([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.5), &t), "coplanar");
    check(&k, [0.0, 0.0, 1.0], 0.5, true, hand::<T>(), "coplanar");
    assert!(close3(&k.point, [0.0; 3], hand::<T>()), "{k:?}");
    // A zero-length axis on the face: N pushes 0 both ways; +N, flagged.
    let k = got(f(&capsule([0.0; 3], [0.0; 3], 0.5), &t), "point on the face");
    check(&k, [0.0, 0.0, 1.0], 0.5, true, hand::<T>(), "point on the face");
    // No axis at all: a zero-length axis on a zero-area triangle, and an axis
    // along the line the triangle collapsed to: (0, 0, 1), depth r, a common
    // point, flagged.
    let k = got(f(&capsule([0.5, 0.0, 0.0], [0.5, 0.0, 0.0], 1.0), &seg), "point on the segment");
    check(&k, [0.0, 0.0, 1.0], 1.0, true, hand::<T>(), "point on the segment");
    assert!(close3(&k.point, [0.5, 0.0, 0.0], hand::<T>()), "{k:?}");
    let k = got(f(&capsule([-3.0, 0.0, 0.0], [-0.5, 0.0, 0.0], 1.0), &seg), "along the line");
    check(&k, [0.0, 0.0, 1.0], 1.0, true, hand::<T>(), "along the line");
    assert!(within(&k.point, [-1.0, 0.0, 0.0], [-0.5, 0.0, 0.0], hand::<T>()), "{k:?}");
    // Along the line but apart: d = 1 from the end (−2, 0, 0) to (−1, 0, 0).
    let k = got(f(&capsule([-3.0, 0.0, 0.0], [-2.0, 0.0, 0.0], 1.5), &seg), "in line, apart");
    check(&k, [-1.0, 0.0, 0.0], 0.5, false, hand::<T>(), "in line, apart");
    assert!(close3(&k.point, [-1.0, 0.0, 0.0], hand::<T>()), "{k:?}");
    // A parallel line beside it: apart by 1 in y.
    let k = got(f(&capsule([-3.0, 1.0, 0.0], [3.0, 1.0, 0.0], 1.5), &seg), "parallel");
    check(&k, [0.0, 1.0, 0.0], 0.5, false, hand::<T>(), "parallel");
    // Crossing the zero-area triangle's segment upright: only D × E exists
    // (∥ y): 0 both ways... the segment x ∈ [−1, 1] and the axis at x = 0.25
    // along z: D × E ∥ y, pushes 0 both ways: +L first, flagged, depth r.
    let k = got(f(&capsule([0.25, 0.0, -1.0], [0.25, 0.0, 1.0], 0.5), &seg), "crossing");
    assert!(k.degenerate && close(k.depth, 0.5, hand::<T>()) && close(k.normal.y.abs(), 1.0, hand::<T>()), "{k:?}");
    assert!(close3(&k.point, [0.25, 0.0, 0.0], hand::<T>()), "{k:?}");
    // A triangle collapsed to a point, on the axis: no axis.
    let dot = tri::<T>([0.0; 3], [0.0; 3], [0.0; 3]);
    let k = got(f(&capsule([0.0, 0.0, -1.0], [0.0, 0.0, 1.0], 0.5), &dot), "collapsed to a point");
    check(&k, [0.0, 0.0, 1.0], 0.5, true, hand::<T>(), "collapsed to a point");
    assert!(close3(&k.point, [0.0; 3], hand::<T>()), "{k:?}");
}
both!(capsule_triangle_degenerate_cases, capsule_triangle_degenerate);

#[test]
fn capsule_triangle_robust_at_extreme_scales() {
    let tol = SCALED_EPS * f64::EPSILON;
    for s in EXTREMES {
        let t = Triangle::new(
            Vec3::new(-2.0 * s, -2.0 * s, 0.0),
            Vec3::new(4.0 * s, -2.0 * s, 0.0),
            Vec3::new(-2.0 * s, 4.0 * s, 0.0),
        );
        let c = Capsule::new(Vec3::new(0.0, 0.0, -s), Vec3::new(0.0, 0.0, 3.0 * s), 0.5 * s);
        let k = contact_capsule_triangle(&c, &t).expect("piercing");
        assert!(
            close(k.depth / s, 1.5, tol) && close3(&k.normal, [0.0, 0.0, 1.0], tol) && !k.degenerate,
            "{s:e}: {k:?}"
        );
        assert!(close3(&(k.point / s), [0.0; 3], tol), "{s:e}: {k:?}");
        let c = Capsule::new(Vec3::new(0.0, -3.0 * s, -s), Vec3::new(0.0, -3.0 * s, s), s);
        let k = contact_capsule_triangle(&c, &t).expect("touching the edge");
        assert!(close(k.depth / s, 0.0, tol) && close3(&k.normal, [0.0, -1.0, 0.0], tol), "{s:e}: {k:?}");
        let c = Capsule { radius: s.next_down(), ..c };
        assert!(contact_capsule_triangle(&c, &t).is_none(), "{s:e}");
    }
}

#[test]
fn capsule_triangle_lecture_misses_an_axis_in_the_plane() {
    // Known wrong, asserted as it is: an axis lying across the triangle in
    // its plane is not "crossing" to the textbook test (both ends at distance
    // 0); its closest points are then at distance 0: normal +z flagged, depth
    // r. The robust form pushes it out along +N by the least push, 0: the
    // same numbers here, but from the format's rule.
    let t = tri::<f64>([-2.0, -2.0, 0.0], [4.0, -2.0, 0.0], [-2.0, 4.0, 0.0]);
    let c = capsule::<f64>([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.5);
    let k = contact_capsule_triangle_lecture(&c, &t).expect("in the plane");
    // Exact: r − 0.
    assert!(k.degenerate && k.depth.to_bits() == 0.5f64.to_bits(), "{k:?}");
}

// ---------------------------------------------------------------------------
// No NaN anywhere
// ---------------------------------------------------------------------------

fn finite<T: Real>(k: &Option<Contact<T>>) -> bool {
    k.as_ref().is_none_or(|k| {
        crate::real::finite3(&k.point) && crate::real::finite3(&k.normal) && k.depth.finite() && !(k.depth < T::zero())
    })
}

/// Cases of the NaN sweep: coordinates across the whole range.
const NAN_CASES: usize = 400;

fn no_nan<T: Real>() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let x = |rng: &mut Rng| match rng.next() % 6 {
        0 => 0.0,
        1 => rng.real(-4.0, 4.0),
        2 => rng.real(-1.0, 1.0) * 10f64.powi((rng.next() % 600) as i32 - 300),
        3 => [1.0, -1.0, 0.5, 2.0, 1e-310, f64::MAX / 4.0][(rng.next() % 6) as usize],
        _ => rng.quarter(),
    };
    for i in 0..NAN_CASES {
        let p: [[f64; 3]; 6] = std::array::from_fn(|_| [x(&mut rng), x(&mut rng), x(&mut rng)]);
        let q = [x(&mut rng), x(&mut rng), x(&mut rng), x(&mut rng)];
        let r = x(&mut rng).abs();
        let a = turned::<T>(p[0], p[1].map(f64::abs), q);
        let b = turned::<T>(p[2], p[3].map(f64::abs), [q[2], q[0], q[3], q[1]]);
        let t = tri::<T>(p[3], p[4], p[5]);
        let c = capsule::<T>(p[4], p[5], r);
        for (name, k) in [
            ("box–box lecture", contact_box_box_lecture(&a, &b)),
            ("box–box", contact_box_box(&a, &b)),
            ("box–triangle lecture", contact_box_triangle_lecture(&a, &t)),
            ("box–triangle", contact_box_triangle(&a, &t)),
            ("capsule–box lecture", contact_capsule_box_lecture(&c, &a)),
            ("capsule–box", contact_capsule_box(&c, &a)),
            ("capsule–triangle lecture", contact_capsule_triangle_lecture(&c, &t)),
            ("capsule–triangle", contact_capsule_triangle(&c, &t)),
        ] {
            assert!(finite(&k), "case {i}, {name}: {k:?}");
        }
    }
}
both!(no_query_answers_nan, no_nan);

// ---------------------------------------------------------------------------
// Robust against lecture on ordinary scenes
// ---------------------------------------------------------------------------

/// Cases of the agreement sweep.
const AGREE_CASES: usize = 1500;

/// Away from ties and touching, on unit scenes, the two forms agree on
/// contact, normal and depth to the lecture's epsilon (its `OBB_EPSILON`
/// widening, `1e-6` on rotation entries, times the sizes ≤ 2, over axes no
/// shorter than `1e-2`): `1e-3` is far beyond that and far below the
/// differences of a wrong answer.
const AGREE_TOL: f64 = 1e-3;

#[test]
fn the_two_forms_agree_on_ordinary_scenes() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let mut compared = 0;
    for i in 0..AGREE_CASES {
        let mut p3 = |lo: f64, hi: f64| Vec3::new(rng.real(lo, hi), rng.real(lo, hi), rng.real(lo, hi));
        let (ca, cb, ha, hb) = (p3(-1.0, 1.0), p3(-1.0, 1.0), p3(0.2, 1.0), p3(0.2, 1.0));
        let (v0, v1, v2) = (p3(-2.0, 2.0), p3(-2.0, 2.0), p3(-2.0, 2.0));
        let (qa, qb) = (rng.quaternion(), rng.quaternion());
        let r = rng.real(0.1, 1.0);
        let a = OrientedBox::new(ca, ha, qa);
        let b = OrientedBox::new(cb, hb, qb);
        let t = Triangle::new(v0, v1, v2);
        let c = Capsule::new(v0, v1, r);
        let pairs = [
            ("box–box", contact_box_box_lecture(&a, &b), contact_box_box(&a, &b)),
            ("box–triangle", contact_box_triangle_lecture(&a, &t), contact_box_triangle(&a, &t)),
            ("capsule–box", contact_capsule_box_lecture(&c, &b), contact_capsule_box(&c, &b)),
            ("capsule–triangle", contact_capsule_triangle_lecture(&c, &t), contact_capsule_triangle(&c, &t)),
        ];
        for (name, l, k) in pairs {
            match (l, k) {
                (Some(l), Some(k)) if !l.degenerate && !k.degenerate => {
                    // Two nearly tied axes may give different normals: the
                    // depth is what must agree.
                    compared += 1;
                    assert!((l.depth - k.depth).abs() <= AGREE_TOL, "case {i} {name}: {l:?} {k:?}");
                }
                (None, Some(k)) => assert!(k.depth <= AGREE_TOL, "case {i} {name}: lecture none, robust {k:?}"),
                (Some(l), None) => assert!(l.depth <= AGREE_TOL, "case {i} {name}: robust none, lecture {l:?}"),
                _ => {}
            }
        }
    }
    assert!(compared > AGREE_CASES / 2, "too few compared: {compared}");
}
