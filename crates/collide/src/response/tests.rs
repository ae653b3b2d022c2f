//! Tests of the collision response: hand-derived impulses (derivation beside
//! each), separating and degenerate input, and the conservation properties —
//! momentum always, kinetic energy at `e = 1`, no normal relative velocity left
//! at `e = 0`. Every body runs for `f32` and `f64`.

use super::*;
use crate::real::{Real, Vec3};
use crate::shapes::Sphere;
use crate::test_support::{both, eps, prop_both, same_bits, v};
use proptest::prelude::*;

/// Hand-derived answers are short rational expressions of values ≤ 4: a few
/// roundings each. Units: ε, absolute on values of order 1.
const HAND_TOL_EPS: f64 = 16.0;

/// Conservation checks (momentum, energy, the restitution law) compare sums of
/// products of inputs up to ~10 in size: each of the handful of roundings is at
/// most ε/2 of the largest term, so 64 ε of that term bounds the error.
/// Units: ε times the largest term of the conserved quantity.
const CONSERVE_TOL_EPS: f64 = 64.0;

fn close_v<T: Real>(got: &Vec3<T>, want: [f64; 3], what: &str) {
    for (k, w) in want.iter().enumerate() {
        let g = got[k].wide();
        assert!((g - w).abs() <= HAND_TOL_EPS * eps::<T>(), "{what}[{k}]: got {got:?}, want {want:?}");
    }
}

fn equal_masses_head_on<T: Real>() {
    // a at (−1,0,0) moving +1, b at (1,0,0) moving −1, masses 1: the normal from b
    // toward a is −x, v_rel·n = (2,0,0)·(−1,0,0) = −2.
    // e = 1: j = −2·(−2)/2 = 2, va' = (1,0,0) + 2(−1,0,0) = (−1,0,0), vb' = (1,0,0):
    // the velocities swap. e = 0: j = 1, both stop.
    let a = Sphere::new(v::<T>(-1.0, 0.0, 0.0), T::one());
    let b = Sphere::new(v::<T>(1.0, 0.0, 0.0), T::one());
    let (va, vb) = (v::<T>(1.0, 0.0, 0.0), v::<T>(-1.0, 0.0, 0.0));
    let r = respond_sphere_sphere_contact(&a, &va, T::one(), &b, &vb, T::one(), T::one());
    close_v(&r.velocity_a, [-1.0, 0.0, 0.0], "e = 1, a");
    close_v(&r.velocity_b, [1.0, 0.0, 0.0], "e = 1, b");
    assert!((r.impulse.wide() - 2.0).abs() <= HAND_TOL_EPS * eps::<T>() && !r.degenerate);
    let r = respond_sphere_sphere_contact(&a, &va, T::one(), &b, &vb, T::one(), T::zero());
    close_v(&r.velocity_a, [0.0; 3], "e = 0, a");
    close_v(&r.velocity_b, [0.0; 3], "e = 0, b");
}
both!(equal_masses_head_on_case, equal_masses_head_on);

fn unequal_masses<T: Real>() {
    // ma = 1 at 4 into mb = 3 at rest, e = 1: v_n = −4, j = 2·4/(1 + 1/3) = 6,
    // va' = 4 − 6 = −2, vb' = 6/3 = 2 — the 1-D elastic formulas
    // (ma − mb)/(ma + mb)·4 = −2 and 2 ma/(ma + mb)·4 = 2.
    let r = respond_sphere_sphere(
        &v::<T>(4.0, 0.0, 0.0),
        T::one(),
        &Vec3::zeros(),
        T::of(3.0),
        &v(-1.0, 0.0, 0.0),
        T::one(),
    );
    close_v(&r.velocity_a, [-2.0, 0.0, 0.0], "a");
    close_v(&r.velocity_b, [2.0, 0.0, 0.0], "b");
    // An infinite mass is a static body: a bounces back with −e·4 (e = 1/2).
    let inf = T::one() / T::zero();
    let r =
        respond_sphere_sphere(&v::<T>(4.0, 0.0, 0.0), T::one(), &Vec3::zeros(), inf, &v(-1.0, 0.0, 0.0), T::of(0.5));
    close_v(&r.velocity_a, [-2.0, 0.0, 0.0], "static b, a");
    close_v(&r.velocity_b, [0.0; 3], "static b, b");
}
both!(unequal_masses_case, unequal_masses);

fn glancing<T: Real>() {
    // b at 0, a at (−3, 4, 0) (normal (−0.6, 0.8, 0), a 3-4-5 direction), a
    // moving +x at 1, masses 1, e = 1: v_n = −0.6, j = 2·0.6/2 = 0.6,
    // va' = (1,0,0) + 0.6(−0.6, 0.8, 0) = (0.64, 0.48, 0), vb' = (0.36, −0.48, 0).
    // Momentum (1,0,0) and energy 1/2 are kept.
    let a = Sphere::new(v::<T>(-3.0, 4.0, 0.0), T::of(2.5));
    let b = Sphere::new(Vec3::zeros(), T::of(2.5));
    let r = respond_sphere_sphere_contact(&a, &v(1.0, 0.0, 0.0), T::one(), &b, &Vec3::zeros(), T::one(), T::one());
    close_v(&r.velocity_a, [0.64, 0.48, 0.0], "a");
    close_v(&r.velocity_b, [0.36, -0.48, 0.0], "b");
}
both!(glancing_case, glancing);

fn separating_keep_their_velocities<T: Real>() {
    // a at (−1,0,0) moving −x, away from b: v_rel·n = (−1,0,0)·(−1,0,0) = 1 ≥ 0.
    // Sliding (v_rel ⟂ n) is not approaching either.
    let a = Sphere::new(v::<T>(-1.0, 0.0, 0.0), T::one());
    let b = Sphere::new(v::<T>(1.0, 0.0, 0.0), T::one());
    for (va, vb) in [(v::<T>(-1.0, 0.0, 0.0), Vec3::zeros()), (v(0.0, 3.0, 0.0), v(0.0, -1.0, 2.0))] {
        let r = respond_sphere_sphere_contact(&a, &va, T::one(), &b, &vb, T::of(2.0), T::one());
        assert!(same_bits(&r.velocity_a, &va) && same_bits(&r.velocity_b, &vb), "{r:?}");
        assert!(r.impulse <= T::zero() && !r.degenerate);
    }
}
both!(separating_keep_their_velocities_case, separating_keep_their_velocities);

fn plane_reflection<T: Real>() {
    // Ground normal (0,0,2) (any length), velocity (1,0,−2), e = 1/2: the normal
    // component −2 becomes +1, the tangential 1 is kept: (1, 0, 1).
    let r = respond_sphere_plane(&v::<T>(1.0, 0.0, -2.0), &v(0.0, 0.0, 2.0), T::of(0.5));
    close_v(&r.velocity_a, [1.0, 0.0, 1.0], "e = 1/2");
    close_v(&r.velocity_b, [0.0; 3], "static plane");
    // e = 1 keeps the speed; e = 0 leaves only the tangential part.
    let r = respond_sphere_plane(&v::<T>(1.0, 0.0, -2.0), &v(0.0, 0.0, 1.0), T::one());
    close_v(&r.velocity_a, [1.0, 0.0, 2.0], "e = 1");
    let r = respond_sphere_plane(&v::<T>(1.0, 0.0, -2.0), &v(0.0, 0.0, 1.0), T::zero());
    close_v(&r.velocity_a, [1.0, 0.0, 0.0], "e = 0");
    // Leaving the plane: unchanged.
    let va = v::<T>(1.0, 0.0, 2.0);
    assert!(same_bits(&respond_sphere_plane(&va, &v(0.0, 0.0, 1.0), T::one()).velocity_a, &va));
}
both!(plane_reflection_case, plane_reflection);

fn degenerate_input<T: Real>() {
    let va = v::<T>(1.0, 0.0, 0.0);
    let vb = v::<T>(-1.0, 0.0, 0.0);
    // Concentric spheres: the fallback normal +z, flagged. The velocities are
    // along x, perpendicular to it: no impulse.
    let s = Sphere::new(Vec3::zeros(), T::one());
    let r = respond_sphere_sphere_contact(&s, &va, T::one(), &s, &vb, T::one(), T::one());
    assert!(r.degenerate && same_bits(&r.velocity_a, &va));
    // Along the fallback normal they are approaching: the impulse acts along +z.
    let r = respond_sphere_sphere_contact(&s, &v(0.0, 0.0, -1.0), T::one(), &s, &Vec3::zeros(), T::one(), T::one());
    assert!(r.degenerate);
    close_v(&r.velocity_a, [0.0; 3], "fallback normal, a");
    close_v(&r.velocity_b, [0.0, 0.0, -1.0], "fallback normal, b");
    // Zero normal, a non-positive mass, two infinite masses, a NaN restitution:
    // unchanged and flagged.
    let n = v::<T>(-1.0, 0.0, 0.0);
    let inf = T::one() / T::zero();
    for (ma, mb, normal, e, what) in [
        (T::one(), T::one(), Vec3::zeros(), T::one(), "zero normal"),
        (T::zero(), T::one(), n, T::one(), "zero mass"),
        (T::one(), -T::one(), n, T::one(), "negative mass"),
        (inf, inf, n, T::one(), "two static bodies"),
        (T::one(), T::one(), n, T::zero() / T::zero(), "NaN restitution"),
    ] {
        let r = respond_sphere_sphere(&va, ma, &vb, mb, &normal, e);
        assert!(r.degenerate && same_bits(&r.velocity_a, &va) && same_bits(&r.velocity_b, &vb), "{what}");
    }
}
both!(degenerate_input_case, degenerate_input);

/// The largest and a subnormal mass of the test's precision: `1e300` and
/// `1e-310` in `f64`, `1e38` and `1e-40` in `f32` (the sums `1e38 + 1e38`
/// and inverses `1/1e-40` overflow `f32` as `1e300`'s products and
/// `1/1e-310` overflow `f64`).
fn huge_and_subnormal<T: Real>() -> (T, T) {
    if eps::<T>() > 1e-10 { (T::of(1e38), T::of(1e-40)) } else { (T::of(1e300), T::of(1e-310)) }
}

/// The smallest positive subnormal of the test's precision.
fn least<T: Real>() -> T {
    if eps::<T>() > 1e-10 { T::of(f64::from(f32::from_bits(1))) } else { T::of(f64::from_bits(1)) }
}

fn huge_masses<T: Real>() {
    // Masses 1e300 (f64) at ±1e10 head on, normal −x: v_n = −2e10, each
    // mass fraction 1/2, so e = 1 swaps the velocities and e = 0 stops both,
    // exactly. Before the fractions, 1/ma + 1/mb = 2e-300 and
    // j = 4e10/2e-300 overflowed: velocities ∞ and NaN.
    let (big, _) = huge_and_subnormal::<T>();
    let (va, vb, n) = (v::<T>(1e10, 0.0, 0.0), v::<T>(-1e10, 0.0, 0.0), v::<T>(-1.0, 0.0, 0.0));
    let speed = 1e10;
    let close = |got: &Vec3<T>, want: [f64; 3], what: &str| {
        for k in 0..3 {
            let g = got[k].wide();
            assert!((g - want[k]).abs() <= HAND_TOL_EPS * eps::<T>() * speed, "{what}: {got:?}, want {want:?}");
        }
    };
    let r = respond_sphere_sphere(&va, big, &vb, big, &n, T::one());
    close(&r.velocity_a, [-1e10, 0.0, 0.0], "e = 1, a");
    close(&r.velocity_b, [1e10, 0.0, 0.0], "e = 1, b");
    assert!(!r.degenerate, "{r:?}");
    let r = respond_sphere_sphere(&va, big, &vb, big, &n, T::zero());
    close(&r.velocity_a, [0.0; 3], "e = 0, a");
    close(&r.velocity_b, [0.0; 3], "e = 0, b");
    // One huge and one unit mass, e = 1: the light body bounces back with
    // 3e10 (the 1-D elastic formula 2 mb/(ma + mb) · 1e10 − (ma − mb)/(ma + mb) · 1e10,
    // to within 1/big), the heavy one keeps its velocity.
    let r = respond_sphere_sphere(&va, T::one(), &vb, big, &n, T::one());
    close(&r.velocity_a, [-3e10, 0.0, 0.0], "light a");
    close(&r.velocity_b, [-1e10, 0.0, 0.0], "heavy b");
    // Velocities whose difference overflows (±0.9e308 in f64, exact at a
    // quarter scale): equal unit masses swap them.
    if eps::<T>() < 1e-10 {
        let (va, vb) = (v::<T>(0.9e308, 1.0, 0.0), v::<T>(-0.9e308, 0.0, 0.0));
        let r = respond_sphere_sphere(&va, T::one(), &vb, T::one(), &n, T::one());
        let tol = HAND_TOL_EPS * eps::<T>() * 0.9e308;
        assert!(
            (r.velocity_a.x.wide() + 0.9e308).abs() <= tol && (r.velocity_b.x.wide() - 0.9e308).abs() <= tol,
            "{r:?}"
        );
        assert!((r.velocity_a.y.wide() - 1.0).abs() <= tol && !r.degenerate, "{r:?}");
    }
}
both!(huge_masses_case, huge_masses);

fn subnormal_masses<T: Real>() {
    // A positive subnormal mass is a mass: its inverse overflows, its
    // fraction does not. ma = 1e-310 (f64) against mb = 1, head on at ±1,
    // e = 1: a bounces back at 1 − 4 · mb/(ma + mb) = −3 (to within 1e-310),
    // b's change 4 · ma/(ma + mb) is subnormal: −1 to the last bit. Equal
    // subnormal masses swap the velocities. Before, both were flagged
    // degenerate and left unchanged.
    let (_, tiny) = huge_and_subnormal::<T>();
    let (va, vb, n) = (v::<T>(1.0, 0.0, 0.0), v::<T>(-1.0, 0.0, 0.0), v::<T>(-1.0, 0.0, 0.0));
    for ma in [tiny, least::<T>()] {
        let r = respond_sphere_sphere(&va, ma, &vb, T::one(), &n, T::one());
        assert!(!r.degenerate, "{r:?}");
        close_v(&r.velocity_a, [-3.0, 0.0, 0.0], "subnormal a");
        close_v(&r.velocity_b, [-1.0, 0.0, 0.0], "unit b");
    }
    let r = respond_sphere_sphere(&va, tiny, &vb, tiny, &n, T::one());
    assert!(!r.degenerate, "{r:?}");
    close_v(&r.velocity_a, [-1.0, 0.0, 0.0], "equal subnormal a");
    close_v(&r.velocity_b, [1.0, 0.0, 0.0], "equal subnormal b");
    // Its impulse is 4 μ, μ = ma mb/(ma + mb) = ma/2: 2 · tiny, to a rounding
    // of the subnormal range.
    let want = 2.0 * tiny.wide();
    assert!((r.impulse.wide() - want).abs() <= HAND_TOL_EPS * eps::<T>() * want + least::<T>().wide(), "{r:?}");
}
both!(subnormal_masses_case, subnormal_masses);

// --------------------------------------------------------------- properties

#[derive(Clone, Debug)]
struct Bodies {
    va: [f64; 3],
    ma: f64,
    vb: [f64; 3],
    mb: f64,
    n: [f64; 3],
    e: f64,
}

fn bodies() -> impl Strategy<Value = Bodies> {
    let p = || [-5.0..5.0f64, -5.0..5.0f64, -5.0..5.0f64];
    (p(), 0.1..10.0f64, p(), 0.1..10.0f64, p(), 0.0..=1.0f64).prop_map(|(va, ma, vb, mb, n, e)| Bodies {
        va,
        ma,
        vb,
        mb,
        n,
        e,
    })
}

fn vt<T: Real>(p: &[f64; 3]) -> Vec3<T> {
    v(p[0], p[1], p[2])
}

fn wide3<T: Real>(p: &Vec3<T>) -> Vec3<f64> {
    Vec3::new(p.x.wide(), p.y.wide(), p.z.wide())
}

/// Momentum is conserved; with `e = 1` so is kinetic energy; after the impulse
/// the normal relative velocity is `−e` times what it was (0 at `e = 0`); the
/// tangential relative velocity is untouched. All evaluated in `f64` on the
/// type's inputs and outputs.
fn check_conservation<T: Real>(s: &Bodies) -> Result<(), TestCaseError> {
    let (va, vb, n) = (vt::<T>(&s.va), vt::<T>(&s.vb), vt::<T>(&s.n));
    let (ma, mb) = (T::of(s.ma), T::of(s.mb));
    prop_assume!(n.norm().wide() > 0.1);
    let scaled_e = T::of(s.e);
    let r = respond_sphere_sphere(&va, ma, &vb, mb, &n, scaled_e);
    prop_assert!(!r.degenerate, "{r:?}");
    let (ma, mb, e) = (ma.wide(), mb.wide(), scaled_e.wide());
    let (va, vb, n) = (wide3(&va), wide3(&vb), wide3(&n).normalize());
    let (va2, vb2) = (wide3(&r.velocity_a), wide3(&r.velocity_b));
    let eps = eps::<T>();
    // Momentum.
    let p0 = va * ma + vb * mb;
    let p1 = va2 * ma + vb2 * mb;
    let size = (va * ma).amax().max((vb * mb).amax()).max((va2 * ma).amax()).max((vb2 * mb).amax());
    prop_assert!((p1 - p0).amax() <= CONSERVE_TOL_EPS * eps * size, "momentum {p0:?} → {p1:?}");
    // Restitution law along the normal, tangential part kept.
    let (u0, u1) = (va - vb, va2 - vb2);
    let speed = u0.amax().max(u1.amax());
    let (n0, n1) = (u0.dot(&n), u1.dot(&n));
    let want = if n0 < 0.0 { -e * n0 } else { n0 };
    prop_assert!((n1 - want).abs() <= CONSERVE_TOL_EPS * eps * speed, "normal {n0} → {n1}, want {want}");
    let (t0, t1) = (u0 - n * n0, u1 - n * n1);
    prop_assert!((t1 - t0).amax() <= CONSERVE_TOL_EPS * eps * speed, "tangential {t0:?} → {t1:?}");
    // Energy: kept at e = 1, never gained.
    let ke = |a: &Vec3<f64>, b: &Vec3<f64>| 0.5 * (ma * a.norm_squared() + mb * b.norm_squared());
    let (k0, k1) = (ke(&va, &vb), ke(&va2, &vb2));
    let ke_tol = CONSERVE_TOL_EPS * eps * k0.max(k1);
    prop_assert!(k1 <= k0 + ke_tol, "energy gained: {k0} → {k1}");
    if e >= 1.0 {
        prop_assert!((k1 - k0).abs() <= ke_tol, "e = 1: energy {k0} → {k1}");
    }
    Ok(())
}

/// The same at the two ends of the restitution range, where the claims are
/// sharpest: `e = 1` conserves kinetic energy, `e = 0` leaves no normal relative
/// velocity (for approaching bodies).
fn check_extremes<T: Real>(s: &Bodies) -> Result<(), TestCaseError> {
    for e in [0.0, 1.0] {
        check_conservation::<T>(&Bodies { e, ..s.clone() })?;
    }
    Ok(())
}

/// Against a static plane: the speed is kept at `e = 1`, the normal component
/// is `−e` times what it was when approaching, and the tangential one is kept.
fn check_plane<T: Real>(s: &Bodies) -> Result<(), TestCaseError> {
    let (va, n) = (vt::<T>(&s.va), vt::<T>(&s.n));
    prop_assume!(n.norm().wide() > 0.1);
    let e = T::of(s.e);
    let r = respond_sphere_plane(&va, &n, e);
    let (va, n, e) = (wide3(&va), wide3(&n).normalize(), e.wide());
    let va2 = wide3(&r.velocity_a);
    let tol = CONSERVE_TOL_EPS * eps::<T>() * va.amax().max(va2.amax());
    let (n0, n1) = (va.dot(&n), va2.dot(&n));
    let want = if n0 < 0.0 { -e * n0 } else { n0 };
    prop_assert!((n1 - want).abs() <= tol, "normal {n0} → {n1}, want {want}");
    prop_assert!(((va2 - n * n1) - (va - n * n0)).amax() <= tol, "tangential changed");
    prop_assert!(wide3(&r.velocity_b).amax() <= 0.0, "the plane is static");
    Ok(())
}

prop_both!(1000, response_conserves_momentum_and_obeys_restitution, bodies(), check_conservation);
prop_both!(1000, response_elastic_keeps_energy_and_plastic_stops_normal_motion, bodies(), check_extremes);
prop_both!(1000, response_plane_reflects_with_restitution, bodies(), check_plane);

/// Bodies over the whole range: masses from subnormal to the top of the
/// type (`1e-310 … 1e300` in `f64`, `1e-40 … 1e38` in `f32`, as decimal
/// exponents drawn as fractions of the range), velocity components of
/// magnitude `10^j` (`j` from −300 to 300 in `f64`, −36 to 36 in `f32`).
#[derive(Clone, Debug)]
struct WideBodies {
    /// Fractions of the mass range (decimal exponents).
    ka: f64,
    kb: f64,
    va: [(f64, f64); 3],
    vb: [(f64, f64); 3],
    n: [f64; 3],
    e: f64,
}

fn wide_bodies() -> impl Strategy<Value = WideBodies> {
    let c = || (-1.0..1.0f64, 0.0..1.0f64);
    let p = || [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64];
    (0.0..1.0f64, 0.0..1.0f64, [c(), c(), c()], [c(), c(), c()], p(), 0.0..=1.0f64)
        .prop_map(|(ka, kb, va, vb, n, e)| WideBodies { ka, kb, va, vb, n, e })
}

/// Full range: every velocity finite (the exact ones are: each is at most
/// `(1 + e) · 2 √3` times the largest input speed, far below the top), the
/// restitution law along the normal and the tangential part as in
/// [`check_conservation`], and momentum with the masses divided by the
/// exact products (they leave the range).
fn check_wide<T: Real>(s: &WideBodies) -> Result<(), TestCaseError> {
    let f64_type = eps::<T>() < 1e-10;
    let (mlo, mhi, vhi) = if f64_type { (-310.0, 300.0, 300.0) } else { (-40.0, 38.0, 36.0) };
    let mass = |k: f64| T::of(10f64.powf(mlo + k * (mhi - mlo)));
    let vel = |c: &[(f64, f64); 3]| {
        v::<T>(
            c[0].0 * 10f64.powf((2.0 * c[0].1 - 1.0) * vhi),
            c[1].0 * 10f64.powf((2.0 * c[1].1 - 1.0) * vhi),
            c[2].0 * 10f64.powf((2.0 * c[2].1 - 1.0) * vhi),
        )
    };
    let (ma, mb, va, vb, n) = (mass(s.ka), mass(s.kb), vel(&s.va), vel(&s.vb), vt::<T>(&s.n));
    prop_assume!(ma > T::zero() && mb > T::zero() && n.norm().wide() > 0.1);
    let e = T::of(s.e);
    let r = respond_sphere_sphere(&va, ma, &vb, mb, &n, e);
    prop_assert!(!r.degenerate, "{r:?}");
    let finite = |x: &Vec3<T>| x.iter().all(|c| c.wide().is_finite());
    prop_assert!(finite(&r.velocity_a) && finite(&r.velocity_b), "{r:?}");
    prop_assert!(!r.impulse.wide().is_nan() && r.impulse >= T::zero(), "{r:?}");
    let (va, vb, n) = (wide3(&va), wide3(&vb), wide3(&n).normalize());
    let (va2, vb2) = (wide3(&r.velocity_a), wide3(&r.velocity_b));
    let eps = eps::<T>();
    let (u0, u1) = (va - vb, va2 - vb2);
    let speed = u0.amax().max(u1.amax()).max(va.amax()).max(vb.amax());
    let (n0, n1) = (u0.dot(&n), u1.dot(&n));
    let want = if n0 < 0.0 { -e.wide() * n0 } else { n0 };
    prop_assert!((n1 - want).abs() <= CONSERVE_TOL_EPS * eps * speed, "normal {n0:e} → {n1:e}, want {want:e}");
    let (t0, t1) = (u0 - n * n0, u1 - n * n1);
    prop_assert!((t1 - t0).amax() <= CONSERVE_TOL_EPS * eps * speed, "tangential {t0:?} → {t1:?}");
    // Momentum exactly (the products of masses and velocities leave the
    // range): per component, |Σ m v' − Σ m v| within the tolerance of the
    // largest term, plus each mass times the least subnormal (a velocity
    // change below the range rounds to 0 or a subnormal, whatever the mass:
    // a heavy body's change `μ Δ/ma` may be `1e-460`).
    use crate::exact::{BigFloat, Sign};
    let big = BigFloat::from_f64;
    let abs = |x: BigFloat| if x.sign() == Sign::Negative { -x } else { x };
    let (ma, mb) = (big(ma.wide()), big(mb.wide()));
    for k in 0..3 {
        let terms = [&ma * &big(va[k]), &mb * &big(vb[k]), &ma * &big(va2[k]), &mb * &big(vb2[k])];
        let diff = abs(&(&terms[2] + &terms[3]) - &(&terms[0] + &terms[1]));
        let size = terms.into_iter().map(abs).max().expect("four terms");
        let floor = &(&ma + &mb) * &big(2.0 * least::<T>().wide());
        let bound = &(&big(CONSERVE_TOL_EPS * eps) * &size) + &floor;
        prop_assert!(
            diff.cmp_value(&bound) != core::cmp::Ordering::Greater,
            "momentum [{k}]: off by {:e} of {:e}",
            diff.to_f64(),
            size.to_f64()
        );
    }
    Ok(())
}

prop_both!(256, response_over_the_whole_range, wide_bodies(), check_wide);
