//! Collision response, exactly: velocities after one frictionless impulse with
//! restitution along the contact normal (fixture format, `response`).
//!
//! **Exact in rationals.** The impulse needs the unit normal `n̂ = n/‖n‖` only
//! through `n̂ n̂ᵀ = n nᵀ/‖n‖²` — the velocity change is `(j/m) n̂` with
//! `j ∝ v_rel·n̂`, so `‖n‖` appears squared — and `n nᵀ/‖n‖²` is rational for a
//! rational `n` (the line of centres, a plane's normal). So every output is an
//! exact rational, correctly rounded once; no square root is taken.
//!
//! There is no margin: the rule "already separating keeps its velocities"
//! switches at `v_rel·n = 0`, where the impulse `j` is 0 anyway, so the answer is
//! continuous across it and no case is borderline.

use super::error::RefereeError;
use super::exact::{Q, V3, add, check, check_radius, check_v3, dot, is_zero, q, round_v, scale, sub, v3};
use crate::geom::{P3, Plane, ResponseAnswer, Sphere};

/// The floating-point stage's answer ([`super::response_fast`]), counted.
fn staged<T>(fast: impl FnOnce() -> Option<T>) -> Option<T> {
    super::stage::fast_stage(super::stage::Stage::Response, fast)
}

fn unchanged(va: &P3, vb: &P3, degenerate: bool) -> ResponseAnswer {
    ResponseAnswer { velocity_a: *va, velocity_b: *vb, degenerate }
}

/// The velocities after the impulse along `n` (any non-zero length, from `b`
/// toward `a`), with inverse masses `wa`, `wb` (`wa + wb > 0`):
/// `va + (j'·wa) n`, `vb − (j'·wb) n` with `j' = −(1 + e)(v_rel·n)/((wa + wb)‖n‖²)`,
/// or `None` when separating (`v_rel·n ≥ 0`).
fn impulse(va: &V3, wa: &Q, vb: &V3, wb: &Q, n: &V3, e: &Q) -> Option<(V3, V3)> {
    let vn = dot(&sub(va, vb), n);
    if vn >= Q::ZERO {
        return None;
    }
    let j = -((Q::ONE + e) * vn) / ((wa + wb) * dot(n, n));
    Some((add(va, &scale(n, &(&j * wa))), sub(vb, &scale(n, &(&j * wb)))))
}

/// Velocities of spheres `a` (velocity `va`, mass `ma`) and `b` (`vb`, `mb`) after
/// one frictionless impulse with restitution `e` along their contact normal.
///
/// **Definition** (the lecture's rigid collision, no friction, no spin): the
/// contact normal of two spheres is the line of centres, `n = Ma − Mb` (from `b`
/// toward `a`, not normalized); with `v_rel = va − vb`,
///
/// ```text
/// j  = −(1 + e)(v_rel·n̂)/(1/ma + 1/mb)          (Newton's law: v_rel'·n̂ = −e v_rel·n̂)
/// va' = va + (j/ma) n̂ = va − (1 + e)(v_rel·n)/((1/ma + 1/mb)‖n‖²) · n/ma
/// vb' = vb − (j/mb) n̂
/// ```
///
/// all rational (see the module docs), each component correctly rounded. Bodies
/// already separating or sliding (`v_rel·n ≥ 0`) keep their velocities. The
/// normal is taken from the centres whether the spheres touch, overlap or are
/// apart. Source: the lecture; Hecker, *Collision Response* (1997), linear part.
///
/// **Degenerate input.** Concentric spheres have no line of centres: the normal
/// is `+z` (the contact fallback, [`super::contact::CONCENTRIC_FALLBACK_NORMAL`]), the
/// impulse is applied along it, flagged. A mass that is not positive defines no
/// impulse: velocities unchanged, flagged (the fixture format refuses it). `e` is
/// used as given. Non-finite numbers and negative radii are refused.
pub fn response_sphere_sphere(
    a: &Sphere,
    va: &P3,
    ma: f64,
    b: &Sphere,
    vb: &P3,
    mb: f64,
    e: f64,
) -> Result<ResponseAnswer, RefereeError> {
    // The checks first, the stage next, the rationals last ([`check`]).
    check_v3(&a.center, "a.center")?;
    check_radius(a.radius, "a.radius")?;
    check_v3(&b.center, "b.center")?;
    check_radius(b.radius, "b.radius")?;
    check_v3(va, "a.velocity")?;
    check_v3(vb, "b.velocity")?;
    check(ma, "a.mass")?;
    check(mb, "b.mass")?;
    check(e, "restitution")?;
    // f64 order is the rationals' order.
    if ma <= 0.0 || mb <= 0.0 {
        return Ok(unchanged(va, vb, true));
    }
    if let Some(answer) = staged(|| super::response_fast::sphere_sphere(a, va, ma, b, vb, mb, e)) {
        return Ok(answer);
    }
    let (ca, cb) = (v3(&a.center, "a.center")?, v3(&b.center, "b.center")?);
    let (va_q, vb_q) = (v3(va, "a.velocity")?, v3(vb, "b.velocity")?);
    let (ma, mb) = (q(ma, "a.mass")?, q(mb, "b.mass")?);
    let e = q(e, "restitution")?;
    let mut n = sub(&ca, &cb);
    let concentric = is_zero(&n);
    if concentric {
        n = [Q::ZERO, Q::ZERO, Q::ONE];
    }
    let (wa, wb) = (Q::ONE / ma, Q::ONE / mb);
    Ok(match impulse(&va_q, &wa, &vb_q, &wb, &n, &e) {
        Some((a2, b2)) => ResponseAnswer { velocity_a: round_v(&a2), velocity_b: round_v(&b2), degenerate: concentric },
        None => unchanged(va, vb, concentric),
    })
}

/// Velocity of a sphere (velocity `va`) after one frictionless impulse with
/// restitution `e` against the static plane `b` (`n·x = d`, outward normal `n`).
///
/// **Definition.** The plane has infinite mass (`1/mb = 0`), so the sphere's
/// mass cancels:
///
/// ```text
/// va' = va − (1 + e)(va·n)/‖n‖² · n        when va·n < 0 (approaching)
/// ```
///
/// the lecture's reflection with restitution, rational and correctly rounded;
/// a sphere leaving or sliding keeps its velocity. `velocity_b` is `[0, 0, 0]`.
///
/// **Degenerate input.** None; a zero normal is refused
/// ([`RefereeError::ZeroNormal`]), as are non-finite numbers.
pub fn response_sphere_plane(va: &P3, b: &Plane, e: f64) -> Result<ResponseAnswer, RefereeError> {
    check_v3(va, "a.velocity")?;
    check_v3(&b.normal, "b.normal")?;
    check(b.offset, "b.offset")?;
    check(e, "restitution")?;
    if b.normal.iter().all(|x| *x == 0.0) {
        return Err(RefereeError::ZeroNormal { field: "b.normal" });
    }
    if let Some(answer) = staged(|| super::response_fast::sphere_plane(va, b, e)) {
        return Ok(answer);
    }
    let (va_q, n) = (v3(va, "a.velocity")?, v3(&b.normal, "b.normal")?);
    let e = q(e, "restitution")?;
    let zero: V3 = [Q::ZERO, Q::ZERO, Q::ZERO];
    Ok(match impulse(&va_q, &Q::ONE, &zero, &Q::ZERO, &n, &e) {
        Some((a2, _)) => ResponseAnswer { velocity_a: round_v(&a2), velocity_b: [0.0; 3], degenerate: false },
        None => unchanged(va, &[0.0; 3], false),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::within_ulps;

    /// The answers below are exact rationals whose correct roundings are the
    /// literals (decimal fractions with exact binary expansions or their
    /// nearest floats, derived by hand): no ulp of slack.
    const EXACT_ULPS: u64 = 0;

    fn close_v(got: P3, want: P3, what: &str) {
        for k in 0..3 {
            assert!(within_ulps(got[k], want[k], EXACT_ULPS), "{what}[{k}]: got {got:?}, want {want:?}");
        }
    }

    fn sphere(center: P3) -> Sphere {
        Sphere { center, radius: 1.0 }
    }

    #[test]
    fn referee_response_head_on_equal_and_unequal_masses() {
        // Equal masses head-on, e = 1: the velocities swap; e = 0: both stop.
        let (a, b) = (sphere([-1.0, 0.0, 0.0]), sphere([1.0, 0.0, 0.0]));
        let (va, vb) = ([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]);
        let r = response_sphere_sphere(&a, &va, 1.0, &b, &vb, 1.0, 1.0).unwrap();
        close_v(r.velocity_a, [-1.0, 0.0, 0.0], "e = 1, a");
        close_v(r.velocity_b, [1.0, 0.0, 0.0], "e = 1, b");
        assert!(!r.degenerate);
        let r = response_sphere_sphere(&a, &va, 1.0, &b, &vb, 1.0, 0.0).unwrap();
        close_v(r.velocity_a, [0.0; 3], "e = 0, a");
        close_v(r.velocity_b, [0.0; 3], "e = 0, b");
        // ma = 1 at 4 into mb = 3 at rest, e = 1: −2 and 2 (1-D elastic formulas).
        // The centres 7 apart: n = (−7,0,0) is not unit, which must not matter.
        let r =
            response_sphere_sphere(&a, &[4.0, 0.0, 0.0], 1.0, &sphere([6.0, 0.0, 0.0]), &[0.0; 3], 3.0, 1.0).unwrap();
        close_v(r.velocity_a, [-2.0, 0.0, 0.0], "a");
        close_v(r.velocity_b, [2.0, 0.0, 0.0], "b");
    }

    #[test]
    fn referee_response_glancing_is_rational() {
        // a at (−3,4,0), b at 0 (n = (−3,4,0), ‖n‖² = 25), a moving +x, masses 1,
        // e = 1: v_rel·n = −3, va' = (1,0,0) − 2·(−3)/(2·25)·(−3,4,0) = (16/25, 12/25, 0),
        // vb' = (9/25, −12/25, 0). The literals are the nearest floats to those
        // fractions (0.64 = 16/25 rounded, and so on).
        let r = response_sphere_sphere(
            &sphere([-3.0, 4.0, 0.0]),
            &[1.0, 0.0, 0.0],
            1.0,
            &sphere([0.0; 3]),
            &[0.0; 3],
            1.0,
            1.0,
        )
        .unwrap();
        close_v(r.velocity_a, [0.64, 0.48, 0.0], "a");
        close_v(r.velocity_b, [0.36, -0.48, 0.0], "b");
    }

    #[test]
    fn referee_response_separating_and_degenerate() {
        // Moving apart or sliding: unchanged (the inputs, bit for bit).
        let (a, b) = (sphere([-1.0, 0.0, 0.0]), sphere([1.0, 0.0, 0.0]));
        for (va, vb) in [([-1.0, 0.0, 0.0], [0.0; 3]), ([0.0, 3.0, 0.0], [0.0, -1.0, 2.0])] {
            let r = response_sphere_sphere(&a, &va, 1.0, &b, &vb, 2.0, 1.0).unwrap();
            assert_eq!(r, ResponseAnswer { velocity_a: va, velocity_b: vb, degenerate: false });
        }
        // Concentric: the +z fallback, flagged; approaching along it, the impulse
        // acts (equal masses, e = 1: velocities swap along z).
        let r = response_sphere_sphere(&a, &[0.0, 0.0, -1.0], 1.0, &a, &[0.0; 3], 1.0, 1.0).unwrap();
        assert!(r.degenerate);
        close_v(r.velocity_a, [0.0; 3], "a");
        close_v(r.velocity_b, [0.0, 0.0, -1.0], "b");
        // A mass that is not positive: unchanged, flagged.
        let r = response_sphere_sphere(&a, &[1.0, 0.0, 0.0], 0.0, &b, &[0.0; 3], 1.0, 1.0).unwrap();
        assert!(r.degenerate);
        close_v(r.velocity_a, [1.0, 0.0, 0.0], "unchanged");
        assert_eq!(
            response_sphere_sphere(&a, &[1.0, 0.0, 0.0], 1.0, &b, &[0.0; 3], f64::NAN, 1.0),
            Err(RefereeError::NonFinite { field: "b.mass" })
        );
        assert_eq!(
            response_sphere_sphere(&a, &[1.0, 0.0, 0.0], 1.0, &b, &[0.0; 3], 1.0, f64::INFINITY),
            Err(RefereeError::NonFinite { field: "restitution" })
        );
    }

    #[test]
    fn referee_response_sphere_plane() {
        // Normal (0,0,2), velocity (1,0,−2), e = 1/2: (1, 0, 1). Tilted normal
        // (1,1,0), velocity (−1,0,0), e = 1: va·n = −1, ‖n‖² = 2,
        // va' = (−1,0,0) + 2·(1/2)(1,1,0) = (0, 1, 0).
        let ground = Plane { normal: [0.0, 0.0, 2.0], offset: 0.0 };
        let r = response_sphere_plane(&[1.0, 0.0, -2.0], &ground, 0.5).unwrap();
        close_v(r.velocity_a, [1.0, 0.0, 1.0], "ground");
        close_v(r.velocity_b, [0.0; 3], "static");
        let tilted = Plane { normal: [1.0, 1.0, 0.0], offset: 3.0 };
        let r = response_sphere_plane(&[-1.0, 0.0, 0.0], &tilted, 1.0).unwrap();
        close_v(r.velocity_a, [0.0, 1.0, 0.0], "tilted");
        // Leaving: unchanged. Zero normal: refused.
        let r = response_sphere_plane(&[1.0, 0.0, 2.0], &ground, 1.0).unwrap();
        close_v(r.velocity_a, [1.0, 0.0, 2.0], "leaving");
        let zero = Plane { normal: [0.0; 3], offset: 0.0 };
        assert_eq!(response_sphere_plane(&[1.0; 3], &zero, 1.0), Err(RefereeError::ZeroNormal { field: "b.normal" }));
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use proptest::prelude::*;

    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![(-3i8..=3).prop_map(f64::from), -4.0..4.0f64]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coord(), coord(), coord()]
    }

    fn mass() -> impl Strategy<Value = f64> {
        prop_oneof![(1u8..=4).prop_map(f64::from), 0.1..10.0f64]
    }

    fn restitution() -> impl Strategy<Value = f64> {
        prop_oneof![Just(0.0), Just(1.0), 0.0..=1.0f64]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn referee_response_conserves_momentum_and_energy_exactly(ca in point(), va in point(), ma in mass(), cb in point(), vb in point(), mb in mass(), e in restitution()) {
            // Re-derived from the rounded outputs is not exact, so the identities
            // are checked on the exact values the referee rounds: recompute them
            // here through the same rational path and test them exactly.
            let (a, b) = (Sphere { center: ca, radius: 1.0 }, Sphere { center: cb, radius: 1.0 });
            let got = response_sphere_sphere(&a, &va, ma, &b, &vb, mb, e).unwrap();
            let n = sub(&v3(&ca, "ca").unwrap(), &v3(&cb, "cb").unwrap());
            prop_assume!(!is_zero(&n));
            let (va_q, vb_q) = (v3(&va, "va").unwrap(), v3(&vb, "vb").unwrap());
            let (mq_a, mq_b, eq) = (q(ma, "ma").unwrap(), q(mb, "mb").unwrap(), q(e, "e").unwrap());
            let (wa, wb) = (Q::ONE / &mq_a, Q::ONE / &mq_b);
            match impulse(&va_q, &wa, &vb_q, &wb, &n, &eq) {
                None => prop_assert_eq!((got.velocity_a, got.velocity_b), (va, vb), "separating keeps velocities"),
                Some((a2, b2)) => {
                    prop_assert_eq!((got.velocity_a, got.velocity_b), (round_v(&a2), round_v(&b2)), "rounded once");
                    let p0 = add(&scale(&va_q, &mq_a), &scale(&vb_q, &mq_b));
                    let p1 = add(&scale(&a2, &mq_a), &scale(&b2, &mq_b));
                    prop_assert_eq!(p0, p1, "momentum, exactly");
                    // v_rel'·n = −e v_rel·n exactly; energy exactly kept at e = 1.
                    let n0 = dot(&sub(&va_q, &vb_q), &n);
                    let n1 = dot(&sub(&a2, &b2), &n);
                    prop_assert_eq!(n1, -(&eq * &n0), "restitution law, exactly");
                    let ke = |x: &V3, y: &V3| &mq_a * dot(x, x) + &mq_b * dot(y, y);
                    if eq == Q::ONE {
                        prop_assert_eq!(ke(&va_q, &vb_q), ke(&a2, &b2), "energy at e = 1, exactly");
                    } else {
                        prop_assert!(ke(&a2, &b2) <= ke(&va_q, &vb_q), "no energy gained");
                    }
                }
            }
        }
    }
}
