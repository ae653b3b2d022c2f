//! Tests of the capsule referee: hand-derived cases (each derivation beside
//! it), every degeneracy and refusal, extreme scales, and loops against
//! brute-force sampling in `f64`.
//!
//! Expected values are exact small numbers or rationals whose correct
//! rounding is the decimal literal written (Rust parses literals correctly
//! rounded); Pythagorean triples keep the distances rational. The referee
//! rounds correctly, so they are compared with no ulp of slack.

use super::*;
use crate::referee::boxes::tests::{close, close_v, contact, positive, sphere};
use crate::referee::contact::contact_sphere_sphere;

fn cap(start: P3, end: P3, radius: f64) -> Capsule {
    Capsule { start, end, radius }
}

/// The axis from the origin to (4, 0, 0).
fn rod(radius: f64) -> Capsule {
    cap([0.0; 3], [4.0, 0.0, 0.0], radius)
}

#[test]
fn referee_sphere_capsule_side_cap_touching_and_apart() {
    // (sphere, point, normal, depth, what).
    let cases = [
        // Beside the axis: q = (2, 0, 0), M − q = (0, 3, 0); r 2.5 + 1 − 3.
        (sphere([2.0, 3.0, 0.0], 2.5), [2.0, 1.0, 0.0], [0.0, 1.0, 0.0], 0.5, "side"),
        // Past the end: q = (4, 0, 0), M − q = (3, 4, 0), 5 away; 5 + 1 − 5 = 1,
        // normal (3/5, 4/5, 0), point q + 1·normal = (23/5, 4/5, 0).
        (sphere([7.0, 4.0, 0.0], 5.0), [4.6, 0.8, 0.0], [0.6, 0.8, 0.0], 1.0, "end cap"),
        // Before the start: q = (0, 0, 0), M − q = (−2, 0, 0); touching.
        (sphere([-2.0, 0.0, 0.0], 1.0), [-1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], 0.0, "touching the start cap"),
    ];
    for (s, point, normal, depth, what) in cases {
        let (k, deg) = contact(contact_sphere_capsule(&s, &rod(1.0)), what);
        assert!(!deg, "{what}");
        close_v(k.point, point, what);
        close_v(k.normal, normal, what);
        close(k.depth, depth, what);
        close(contact_margin_sphere_capsule(&s, &rod(1.0)).unwrap(), depth, what);
    }
    assert!(positive(contact_margin_sphere_capsule(&sphere([-2.0, 0.0, 0.0], 1.0), &rod(1.0)).unwrap()));
    // Apart: 3 away with radii 1 + 1, margin −1; one ulp past touching.
    let s = sphere([2.0, 3.0, 0.0], 1.0);
    assert_eq!(contact_sphere_capsule(&s, &rod(1.0)).unwrap().contact, None);
    close(contact_margin_sphere_capsule(&s, &rod(1.0)).unwrap(), -1.0, "margin");
    let past = f64::from_bits(2f64.to_bits() + 1);
    let s = sphere([-past, 0.0, 0.0], 1.0);
    assert_eq!(contact_sphere_capsule(&s, &rod(1.0)).unwrap().contact, None);
    close(contact_margin_sphere_capsule(&s, &rod(1.0)).unwrap(), -(past - 2.0), "one ulp");
}

#[test]
fn referee_sphere_capsule_centre_on_the_axis_and_point_capsule() {
    // M = q = (1, 0, 0): degenerate, normal +z, point q + r_b·z, depth r_a + r_b.
    let (k, deg) = contact(contact_sphere_capsule(&sphere([1.0, 0.0, 0.0], 0.5), &rod(1.0)), "on the axis");
    assert!(deg);
    close_v(k.normal, CONCENTRIC_FALLBACK_NORMAL_F64, "normal");
    close_v(k.point, [1.0, 0.0, 1.0], "point");
    close(k.depth, 1.5, "depth");
    // A capsule with start = end is a sphere: the same bits as sphere–sphere
    // (the same exact values rounded once by the same code).
    for (c, r) in [([3.0, 4.0, 0.0], 2.0), ([0.1, 0.2, 0.3], 0.5), ([1.0, 2.0, 3.0], 7.0), ([9.0, 9.0, 9.0], 1.0)] {
        let s = sphere(c, r);
        let ball = cap([1.0, 2.0, 3.0], [1.0, 2.0, 3.0], 1.5);
        let got = contact_sphere_capsule(&s, &ball).unwrap();
        let want = contact_sphere_sphere(&s, &sphere([1.0, 2.0, 3.0], 1.5)).unwrap();
        assert_eq!(got, want, "{c:?}");
    }
}

/// `+z`, the fallback normal, as `f64`.
const CONCENTRIC_FALLBACK_NORMAL_F64: P3 = crate::referee::CONCENTRIC_FALLBACK_NORMAL;

#[test]
fn referee_capsule_capsule_skew_ends_and_perpendicular() {
    // (a, b, point, normal, depth, what).
    let cases = [
        // Crossing skew axes 2 apart: p_a = (0, 0, 2), p_b = (0, 0, 0);
        // radii 1 + 1.5 − 2 = 0.5, point p_b + 1.5·z.
        (
            cap([-1.0, 0.0, 2.0], [1.0, 0.0, 2.0], 1.0),
            cap([0.0, -1.0, 0.0], [0.0, 1.0, 0.0], 1.5),
            [0.0, 0.0, 1.5],
            [0.0, 0.0, 1.0],
            0.5,
            "skew",
        ),
        // Perpendicular, b starting past a's end: Ericson's t < 0 branch: p_a =
        // a's end (2, 0, 0), p_b = b's start (5, 4, 0); p_a − p_b = (−3, −4, 0),
        // 5 apart; 2 + 3.5 − 5 = 0.5; point (5, 4, 0) + 3.5·(−3/5, −4/5, 0).
        (
            cap([0.0; 3], [2.0, 0.0, 0.0], 2.0),
            cap([5.0, 4.0, 0.0], [5.0, 9.0, 0.0], 3.5),
            [2.9, 1.2, 0.0],
            [-0.6, -0.8, 0.0],
            0.5,
            "perpendicular, past the end",
        ),
        // The same with b reversed: the t > 1 branch, the same pair.
        (
            cap([0.0; 3], [2.0, 0.0, 0.0], 2.0),
            cap([5.0, 9.0, 0.0], [5.0, 4.0, 0.0], 3.5),
            [2.9, 1.2, 0.0],
            [-0.6, -0.8, 0.0],
            0.5,
            "perpendicular, reversed",
        ),
        // Parallel, disjoint along the axis: a's end (1, 0, 0) and b's start
        // (4, 4, 0), 5 apart: the same numbers.
        (
            cap([0.0; 3], [1.0, 0.0, 0.0], 2.0),
            cap([4.0, 4.0, 0.0], [8.0, 4.0, 0.0], 3.5),
            [1.9, 1.2, 0.0],
            [-0.6, -0.8, 0.0],
            0.5,
            "parallel, end to end",
        ),
        // A point capsule (a sphere) beside b: the sphere–capsule answer.
        (
            cap([2.0, 3.0, 0.0], [2.0, 3.0, 0.0], 2.5),
            rod(1.0),
            [2.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            0.5,
            "point capsule a",
        ),
    ];
    for (a, b, point, normal, depth, what) in cases {
        let (k, deg) = contact(contact_capsule_capsule(&a, &b), what);
        assert!(!deg, "{what}");
        close_v(k.point, point, what);
        close_v(k.normal, normal, what);
        close(k.depth, depth, what);
        close(contact_margin_capsule_capsule(&a, &b).unwrap(), depth, what);
        close(contact_margin_capsule_capsule(&b, &a).unwrap(), depth, what);
        let region = contact_region_capsule_capsule(&a, &b).unwrap().unwrap();
        // The same exact value rounded by the same code: equal bits.
        assert_eq!(region, vec![k.point], "{what}: a unique point is the answer's");
    }
}

#[test]
fn referee_capsule_capsule_parallel_side_by_side() {
    // a along y = 1 from x = 0 to 4, b along y = 0 from x = 2 to 6: the axial
    // ranges share [2, 4]; every pair there is 1 apart. Radii 0.75 + 0.5 − 1.
    // The pair with the least parameter on a: s = 1/2, p_a = (2, 1, 0),
    // p_b = (2, 0, 0); point p_b + 0.5·y; the region runs to x = 4.
    let a = cap([0.0, 1.0, 0.0], [4.0, 1.0, 0.0], 0.75);
    for b in [cap([2.0, 0.0, 0.0], [6.0, 0.0, 0.0], 0.5), cap([6.0, 0.0, 0.0], [2.0, 0.0, 0.0], 0.5)] {
        let (k, deg) = contact(contact_capsule_capsule(&a, &b), "parallel");
        assert!(!deg);
        close_v(k.point, [2.0, 0.5, 0.0], "point");
        close_v(k.normal, [0.0, 1.0, 0.0], "normal");
        close(k.depth, 0.25, "depth");
        let region = contact_region_capsule_capsule(&a, &b).unwrap().unwrap();
        assert_eq!(region.len(), 2);
        close_v(region[0], [2.0, 0.5, 0.0], "region start");
        close_v(region[1], [4.0, 0.5, 0.0], "region end");
    }
    // a reversed (from x = 4 to 0): its least parameter is at x = 4 now.
    let a_rev = cap([4.0, 1.0, 0.0], [0.0, 1.0, 0.0], 0.75);
    let b = cap([2.0, 0.0, 0.0], [6.0, 0.0, 0.0], 0.5);
    let (k, _) = contact(contact_capsule_capsule(&a_rev, &b), "reversed a");
    close_v(k.point, [4.0, 0.5, 0.0], "point");
    // Apart side by side: no region.
    let far = cap([2.0, -2.0, 0.0], [6.0, -2.0, 0.0], 0.5);
    assert_eq!(contact_capsule_capsule(&a, &far).unwrap().contact, None);
    assert_eq!(contact_region_capsule_capsule(&a, &far).unwrap(), None);
    close(contact_margin_capsule_capsule(&a, &far).unwrap(), -1.75, "margin");
}

#[test]
fn referee_capsule_capsule_axes_that_meet_are_degenerate() {
    // Crossing at the origin: normal +z, point p_b + r_b·z, depth r_a + r_b.
    let a = cap([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.5);
    let b = cap([0.0, -1.0, 0.0], [0.0, 1.0, 0.0], 0.25);
    let (k, deg) = contact(contact_capsule_capsule(&a, &b), "crossing");
    assert!(deg);
    close_v(k.normal, [0.0, 0.0, 1.0], "normal");
    close_v(k.point, [0.0, 0.0, 0.25], "point");
    close(k.depth, 0.75, "depth");
    // Collinear and overlapping on [1, 2]: degenerate; the region spans it.
    let a = cap([0.0; 3], [2.0, 0.0, 0.0], 1.0);
    let b = cap([1.0, 0.0, 0.0], [3.0, 0.0, 0.0], 1.0);
    let (k, deg) = contact(contact_capsule_capsule(&a, &b), "collinear");
    assert!(deg);
    close_v(k.point, [1.0, 0.0, 1.0], "point");
    close(k.depth, 2.0, "depth");
    let region = contact_region_capsule_capsule(&a, &b).unwrap().unwrap();
    assert_eq!(region.len(), 2);
    close_v(region[1], [2.0, 0.0, 1.0], "region end");
    // Two equal point capsules: concentric spheres, the same bits.
    let p = cap([1.0, 2.0, 3.0], [1.0, 2.0, 3.0], 1.0);
    let s = sphere([1.0, 2.0, 3.0], 1.0);
    assert_eq!(contact_capsule_capsule(&p, &p).unwrap(), contact_sphere_sphere(&s, &s).unwrap());
}

#[test]
fn referee_capsule_plane_cases() {
    let ground = Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 };
    // Tilted, its start lowest at z = 1 with r 1: touching, point (0, 0, 0).
    let a = cap([0.0, 0.0, 1.0], [4.0, 0.0, 3.0], 1.0);
    let (k, deg) = contact(contact_capsule_plane(&a, &ground), "touching");
    assert!(!deg);
    close(k.depth, 0.0, "depth");
    close_v(k.point, [0.0; 3], "point");
    close_v(k.normal, [0.0, 0.0, 1.0], "normal");
    assert!(positive(contact_margin_capsule_plane(&a, &ground).unwrap()));
    assert_eq!(contact_region_capsule_plane(&a, &ground).unwrap().unwrap(), vec![k.point]);
    // The end lowest: (4, 0, −1) is 1 deep, depth 1 + 1.
    let a = cap([0.0, 0.0, 1.0], [4.0, 0.0, -1.0], 1.0);
    let (k, _) = contact(contact_capsule_plane(&a, &ground), "end lowest");
    close(k.depth, 2.0, "depth");
    close_v(k.point, [4.0, 0.0, 0.0], "point");
    // Lying along the plane, sunk by a half: the region is the axis's projection.
    let a = cap([0.0, 0.0, 0.5], [4.0, 0.0, 0.5], 1.0);
    let (k, _) = contact(contact_capsule_plane(&a, &ground), "lying");
    close(k.depth, 0.5, "depth");
    close_v(k.point, [0.0; 3], "point: start's projection");
    let region = contact_region_capsule_plane(&a, &ground).unwrap().unwrap();
    assert_eq!(region.len(), 2);
    close_v(region[0], [0.0; 3], "region start");
    close_v(region[1], [4.0, 0.0, 0.0], "region end");
    // A plane 3y + 4z ≤ 5 (‖n‖ = 5): the end (0, 3, 4) has n·x = 25, the start
    // (0, 0, 0) has 0: start lowest, (5 − 0)/5 + 1 = 2, point
    // 0 + (5/25)·(0, 3, 4) = (0, 3/5, 4/5).
    let tilted = Plane { normal: [0.0, 3.0, 4.0], offset: 5.0 };
    let a = cap([0.0; 3], [0.0, 3.0, 4.0], 1.0);
    let (k, _) = contact(contact_capsule_plane(&a, &tilted), "tilted");
    close(k.depth, 2.0, "depth");
    close_v(k.point, [0.0, 0.6, 0.8], "point");
    close_v(k.normal, [0.0, 0.6, 0.8], "normal");
    // Apart: start 3 above the ground with r 1, margin −2; one ulp apart.
    let a = cap([0.0, 0.0, 3.0], [1.0, 0.0, 5.0], 1.0);
    assert_eq!(contact_capsule_plane(&a, &ground).unwrap().contact, None);
    assert_eq!(contact_region_capsule_plane(&a, &ground).unwrap(), None);
    close(contact_margin_capsule_plane(&a, &ground).unwrap(), -2.0, "margin");
    let a = cap([0.0, 0.0, f64::from_bits(1f64.to_bits() + 1)], [0.0, 0.0, 2.0], 1.0);
    assert_eq!(contact_capsule_plane(&a, &ground).unwrap().contact, None);
    close(contact_margin_capsule_plane(&a, &ground).unwrap(), -f64::EPSILON, "one ulp");
    // A point capsule is a sphere: the sphere–plane answer's numbers.
    let a = cap([5.0, 6.0, -3.0], [5.0, 6.0, -3.0], 1.0);
    let (k, _) = contact(contact_capsule_plane(&a, &ground), "point capsule");
    close(k.depth, 4.0, "depth");
    close_v(k.point, [5.0, 6.0, 0.0], "point");
    assert_eq!(contact_region_capsule_plane(&a, &ground).unwrap().unwrap().len(), 1);
}

#[test]
fn referee_capsules_refuse_malformed_input() {
    let ground = Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 };
    let good = rod(1.0);
    assert_eq!(
        contact_sphere_capsule(&sphere([0.0; 3], 1.0), &cap([0.0; 3], [1.0; 3], -1.0)),
        Err(RefereeError::NegativeRadius { field: "b.radius" })
    );
    assert_eq!(
        contact_capsule_capsule(&cap([f64::NAN, 0.0, 0.0], [1.0; 3], 1.0), &good),
        Err(RefereeError::NonFinite { field: "a.start" })
    );
    assert_eq!(
        contact_margin_capsule_capsule(&good, &cap([0.0; 3], [f64::INFINITY, 0.0, 0.0], 1.0)),
        Err(RefereeError::NonFinite { field: "b.end" })
    );
    assert_eq!(
        contact_capsule_plane(&good, &Plane { normal: [0.0; 3], offset: 0.0 }),
        Err(RefereeError::ZeroNormal { field: "b.normal" })
    );
    assert_eq!(
        contact_region_capsule_plane(&cap([0.0; 3], [1.0; 3], f64::NAN), &ground),
        Err(RefereeError::NonFinite { field: "a.radius" })
    );
    assert_eq!(
        contact_sphere_capsule(&sphere([0.0; 3], -0.5), &good),
        Err(RefereeError::NegativeRadius { field: "a.radius" })
    );
    // A zero radius is what the sphere check allows: the capsule is its axis.
    let (k, _) = contact(contact_sphere_capsule(&sphere([2.0, 1.0, 0.0], 1.0), &rod(0.0)), "zero radius");
    close(k.depth, 0.0, "depth");
}

#[test]
fn referee_capsules_huge_and_tiny_scales() {
    // The end-to-end case scaled by 2^±1000 and into the subnormals (exact
    // scalings): depth 0.5·s, normal (−3/5, −4/5, 0).
    for s in [2f64.powi(1000), 2f64.powi(-1000), 2f64.powi(-1060)] {
        let a = cap([0.0; 3], [s, 0.0, 0.0], 2.0 * s);
        let b = cap([4.0 * s, 4.0 * s, 0.0], [8.0 * s, 4.0 * s, 0.0], 3.5 * s);
        let (k, _) = contact(contact_capsule_capsule(&a, &b), "scaled");
        close(k.depth, 0.5 * s, "depth");
        close_v(k.normal, [-0.6, -0.8, 0.0], "normal");
        let (k, _) = contact(contact_sphere_capsule(&sphere([9.0 * s, 4.0 * s, 0.0], 5.0 * s), &b), "sphere");
        // Past b's end: M − q = (9s, 4s) − (8s, 4s) = (s, 0, 0): depth 5s + 3.5s − s.
        close(k.depth, 7.5 * s, "sphere depth");
        close_v(k.normal, [1.0, 0.0, 0.0], "sphere normal");
    }
    // Near f64's edge: finite answers, or ±∞ where the exact value is beyond
    // the range (the referee's documented rounding).
    let a = cap([-1e308, 0.0, 0.0], [1e308, 0.0, 0.0], 1e308);
    let b = cap([0.0, -1e308, 1e308], [0.0, 1e308, 1e308], 1e308);
    let (k, deg) = contact(contact_capsule_capsule(&a, &b), "huge");
    assert!(!deg);
    close(k.depth, 1e308, "depth: 2e308 − 1e308 is exact");
    close_v(k.normal, [0.0, 0.0, -1.0], "normal");
    let (k, _) = contact(contact_sphere_capsule(&sphere([0.0; 3], f64::MAX), &a), "beyond");
    assert!(k.depth.is_infinite() && k.depth > 0.0, "MAX + 1e308 overflows: {}", k.depth);
    // A tiny plane normal: d − n·e ≈ 1 over ‖n‖ ≈ 1e-300, a margin near 1e300.
    let c = cap([-1e300, 0.0, 0.0], [1e300, 0.0, 0.0], 1.0);
    let p = Plane { normal: [1e-300, 0.0, 5e-324], offset: 1e-300 };
    let m = contact_margin_capsule_plane(&c, &p).unwrap();
    assert!(m.is_finite() && m > 1e299, "{m}");
}

/// Loops against brute-force sampling in `f64`, for sanity.
mod sampled {
    use super::*;
    use proptest::prelude::*;

    /// Parameters sampled on each axis for the brute-force distance.
    const SAMPLES: usize = 400;

    /// Agreement asked of the exact margin with the brute-force one. The
    /// distance to b is 1-Lipschitz along a, so the sampled least distance
    /// exceeds the true one by at most half a step of a's axis (≤ 14/800 ≈
    /// 0.018 for coordinates within ±4); checked one-sided (exact ≥ sampled,
    /// up to rounding) and two-sided with this slack.
    const SAMPLING_TOL: f64 = 0.05;

    /// Rounding slack of an `f64` evaluation on inputs of size ≤ 8.
    const F64_TOL: f64 = 1e-9;

    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![(-3i8..=3).prop_map(f64::from), -4.0..4.0f64]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coord(), coord(), coord()]
    }

    fn radius() -> impl Strategy<Value = f64> {
        prop_oneof![(0u8..=2).prop_map(f64::from), 0.0..2.0f64]
    }

    fn capsule() -> impl Strategy<Value = Capsule> {
        (point(), point(), radius(), any::<bool>())
            .prop_map(|(s, e, r, point)| if point { cap(s, s, r) } else { cap(s, e, r) })
    }

    fn at(c: &Capsule, t: f64) -> P3 {
        std::array::from_fn(|i| c.start[i] + t * (c.end[i] - c.start[i]))
    }

    fn dist(x: P3, y: P3) -> f64 {
        ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
    }

    /// The least sampled distance between the axes: a's samples against b's
    /// closest point (exact projection in f64), so only a is sampled.
    fn sampled_distance(a: &Capsule, b: &Capsule) -> f64 {
        let d: P3 = std::array::from_fn(|i| b.end[i] - b.start[i]);
        let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        (0..=SAMPLES)
            .map(|k| {
                let p = at(a, k as f64 / SAMPLES as f64);
                let t = if len2 > 0.0 {
                    (((p[0] - b.start[0]) * d[0] + (p[1] - b.start[1]) * d[1] + (p[2] - b.start[2]) * d[2]) / len2)
                        .clamp(0.0, 1.0)
                } else {
                    0.0
                };
                dist(p, at(b, t))
            })
            .fold(f64::INFINITY, f64::min)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn referee_capsule_capsule_matches_sampling(a in capsule(), b in capsule()) {
            let m = contact_margin_capsule_capsule(&a, &b).unwrap();
            let sampled = a.radius + b.radius - sampled_distance(&a, &b);
            // Sampling finds no pair closer than the closest: the exact margin
            // is at least the sampled one.
            prop_assert!(m >= sampled - F64_TOL, "margin {} below sampled {}", m, sampled);
            prop_assert!(m <= sampled + SAMPLING_TOL, "margin {} far above sampled {}", m, sampled);
            // Symmetric, to the bit (the same exact distance).
            prop_assert_eq!(m.to_bits(), contact_margin_capsule_capsule(&b, &a).unwrap().to_bits());
            let answer = contact_capsule_capsule(&a, &b).unwrap();
            prop_assert_eq!(answer.contact.is_some(), positive(m), "the margin's sign is the decision");
            let region = contact_region_capsule_capsule(&a, &b).unwrap();
            prop_assert_eq!(region.is_some(), answer.contact.is_some());
            if let (Some(k), Some(region)) = (answer.contact, region) {
                prop_assert_eq!(k.depth.to_bits(), m.to_bits());
                prop_assert!(matches!(region.len(), 1 | 2));
                // The region's first vertex is the answer's point (same value,
                // same rounding); every vertex is on b's surface, unless the
                // normal is the fallback +z (axes that meet), whose point
                // p_b + r_b·z the format fixes wherever it falls.
                prop_assert_eq!(region[0].map(f64::to_bits), k.point.map(f64::to_bits));
                for v in region.iter().filter(|_| !answer.degenerate) {
                    let on = sampled_distance(&cap(*v, *v, 0.0), &b) - b.radius;
                    prop_assert!(on.abs() <= F64_TOL, "vertex {:?} off b's surface by {}", v, on);
                }
            }
        }

        #[test]
        fn referee_sphere_capsule_is_capsule_capsule_with_a_point(c in point(), r in radius(), b in capsule()) {
            // The same exact closest point, the same rounding: equal answers.
            let s = Sphere { center: c, radius: r };
            prop_assert_eq!(contact_sphere_capsule(&s, &b).unwrap(), contact_capsule_capsule(&cap(c, c, r), &b).unwrap());
            prop_assert_eq!(
                contact_margin_sphere_capsule(&s, &b).unwrap().to_bits(),
                contact_margin_capsule_capsule(&cap(c, c, r), &b).unwrap().to_bits()
            );
        }

        #[test]
        fn referee_capsule_plane_matches_its_ends(a in capsule(), n in point(), d in coord()) {
            prop_assume!(n.iter().any(|x| *x != 0.0));
            let p = Plane { normal: n, offset: d };
            let len = dist(n, [0.0; 3]);
            let h = |x: P3| (n[0] * x[0] + n[1] * x[1] + n[2] * x[2]) / len;
            let want = a.radius + d / len - h(a.start).min(h(a.end));
            let m = contact_margin_capsule_plane(&a, &p).unwrap();
            prop_assert!((m - want).abs() <= F64_TOL, "margin {} vs f64 {}", m, want);
            let answer = contact_capsule_plane(&a, &p).unwrap();
            prop_assert_eq!(answer.contact.is_some(), positive(m));
            if let (Some(k), Some(region)) = (answer.contact, contact_region_capsule_plane(&a, &p).unwrap()) {
                prop_assert_eq!(region[0].map(f64::to_bits), k.point.map(f64::to_bits), "the answer's point opens the region");
                for v in &region {
                    prop_assert!((h(*v) - d / len).abs() <= F64_TOL, "vertex on the plane");
                }
            }
        }
    }
}

fn seg(start: P3, end: P3) -> Segment {
    Segment { start, end }
}

fn hit(a: IntersectAnswer) -> (SegmentHit, bool) {
    (a.hit.expect("a hit"), a.degenerate)
}

/// The rod from (−1,0,0) to (1,0,0) of radius 1: every expected value below
/// is exact in `f64` but `t = 1/3`, its correct rounding.
#[test]
fn referee_segment_capsule_side_end_and_grazing() {
    let c = cap([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0);
    let (h, degenerate) = hit(intersect_segment_capsule(&seg([0.0, 3.0, 0.0], [0.0, -3.0, 0.0]), &c).unwrap());
    close(h.t, 1.0 / 3.0, "h.t");
    close_v(h.point, [0.0, 1.0, 0.0], "h.point");
    close_v(h.normal, [0.0, 1.0, 0.0], "h.normal");
    assert!(!degenerate);
    let (h, _) = hit(intersect_segment_capsule(&seg([-5.0, 0.0, 0.0], [5.0, 0.0, 0.0]), &c).unwrap());
    close(h.t, 0.3, "h.t");
    close_v(h.point, [-2.0, 0.0, 0.0], "h.point");
    close_v(h.normal, [-1.0, 0.0, 0.0], "h.normal");
    // Along the side at the radius: it touches from the start cap's rim on.
    let (h, _) = hit(intersect_segment_capsule(&seg([-5.0, 1.0, 0.0], [5.0, 1.0, 0.0]), &c).unwrap());
    close(h.t, 0.4, "h.t");
    close_v(h.point, [-1.0, 1.0, 0.0], "h.point");
    close_v(h.normal, [0.0, 1.0, 0.0], "h.normal");
    // Ending on the surface: t = 1 counts.
    let (h, _) = hit(intersect_segment_capsule(&seg([0.0, 3.0, 0.0], [0.0, 1.0, 0.0]), &c).unwrap());
    close(h.t, 1.0, "h.t");
    close_v(h.point, [0.0, 1.0, 0.0], "h.point");
    let miss = seg([0.0, 3.0, 0.0], [5.0, 3.0, 0.0]);
    assert_eq!(intersect_segment_capsule(&miss, &c).unwrap().hit, None);
    close(intersect_margin_segment_capsule(&miss, &c).unwrap(), -2.0, "margin");
}

#[test]
fn referee_segment_capsule_from_inside() {
    let c = cap([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0);
    let (h, degenerate) = hit(intersect_segment_capsule(&seg([0.5, 0.5, 0.0], [0.5, 5.0, 0.0]), &c).unwrap());
    close(h.t, 0.0, "h.t");
    close_v(h.point, [0.5, 0.5, 0.0], "h.point");
    close_v(h.normal, [0.0, 1.0, 0.0], "h.normal");
    assert!(!degenerate);
    let (h, degenerate) = hit(intersect_segment_capsule(&seg([0.0; 3], [0.0, 5.0, 0.0]), &c).unwrap());
    assert!(degenerate, "a start on the axis has no outward direction");
    close(h.t, 0.0, "h.t");
    close_v(h.normal, [0.0, 0.0, 1.0], "h.normal");
    let point = seg([1.5, 0.0, 0.0], [1.5, 0.0, 0.0]);
    let (h, degenerate) = hit(intersect_segment_capsule(&point, &c).unwrap());
    assert!(degenerate, "a zero-length segment is flagged");
    close(h.t, 0.0, "h.t");
    close_v(h.normal, [1.0, 0.0, 0.0], "h.normal");
}

/// How far from the surface a correctly rounded hit point may lie in these
/// scenes (coordinates below 16): each coordinate within half an ulp of 16
/// (2⁻⁴⁹), so the point within √3·2⁻⁴⁹ of the exact one, and the distance
/// rounded once more; 2⁻⁴⁵ is that with room.
const ON_SURFACE: f64 = 1.0 / 35_184_372_088_832.0;

proptest::proptest! {
    /// The hit's point is on the capsule's surface (its distance from the
    /// axis within a few ulps of r), and the margin's sign is the decision.
    #[test]
    fn referee_segment_capsule_hits_the_surface(
        s in proptest::array::uniform3(-8i32..=8), e in proptest::array::uniform3(-8i32..=8),
        p in proptest::array::uniform3(-4i32..=4), q in proptest::array::uniform3(-4i32..=4), r in 1i32..=6,
    ) {
        let (s, e, p, q) = (s.map(f64::from), e.map(f64::from), p.map(f64::from), q.map(f64::from));
        let c = cap(p, q, f64::from(r) / 2.0);
        let answer = intersect_segment_capsule(&seg(s, e), &c).unwrap();
        let margin = intersect_margin_segment_capsule(&seg(s, e), &c).unwrap();
        proptest::prop_assert_eq!(answer.hit.is_some(), margin.is_sign_positive());
        if let Some(h) = answer.hit.filter(|h| h.t > 0.0) {
            let point = v3(&h.point, "point").unwrap();
            let foot = closest_on_segment(&point, &v3(&p, "p").unwrap(), &v3(&q, "q").unwrap());
            let gap = sub(&point, &foot);
            let dist = Root::new(dot(&gap, &gap)).round_sqrt();
            proptest::prop_assert!((dist - c.radius).abs() <= ON_SURFACE, "{dist} against {}", c.radius);
        }
    }
}
