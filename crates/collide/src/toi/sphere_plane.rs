//! Sphere–plane time of impact in closed form.

use super::time_of_impact::{Toi, ToiStatus, clamp_t_max};
use crate::contact::{Contact, clearly_apart, contact_sphere_plane, contact_sphere_plane_parts, normal_parts};
use crate::exact::norm::safe_squared_range;
use crate::real::{Real, Vec3};
use crate::shapes::{Plane, Sphere};

/// Time of impact of sphere `a` (centre `M`, radius `r`, velocity `va`) and the
/// solid half-space `n·x ≤ d` bounded by plane `b` (velocity `vb`) over
/// `[0, t_max]`, **in closed form**.
///
/// **Formula.** With `n̂ = n/‖n‖`, the plane translated by `t·vb` is
/// `n̂·x = d/‖n‖ + t n̂·vb`, so the centre's signed distance from it is linear in
/// time:
///
/// ```text
/// s(t) = s0 − t·k,   s0 = n̂·M − d/‖n‖,   k = −n̂·(va − vb)  (the closing speed)
/// ```
///
/// The sphere reaches the half-space when `s(t) = r`: `t = (s0 − r)/k`, one
/// subtraction and one division, nothing to cancel but `s0 − r` itself (which is
/// the data's own conditioning). The contact then is the plane's: normal `n̂`
/// (from `b` toward `a`), point `M + t va − r n̂` (the sphere's lowest point, on
/// the plane at time `t`).
///
/// **Cost.** Where `n · n` lies in the range in which its plain square root
/// loses nothing (`[2^−918, 2^920]` in `f64`): `t = (s' − r‖n‖)/k'` with
/// `s' = n·M − d` and `k' = −n·(va − vb)` (the normal's length cancels), one
/// root and one division for `t`, one division for the unit normal beside it;
/// the static contact test only for a sphere that may already be within `r`
/// (decided from the squares, without the root, by the static test's own
/// "clearly apart" test, so the two agree on every start; squares below the
/// plain range always ask it). Other normals, a
/// signed distance that overflows, and a closing speed `k'` that overflows
/// (a normal of length 8 and a speed of `2.8e307`) or falls below the plain
/// range, take a scaled path: the unit normal from the scaled norm, `s0 − r`
/// at a quarter scale and the relative velocity at its own power-of-two
/// scale, so no intermediate overflows or underflows.
///
/// **Cases.** Already in contact at `t = 0` ([`contact_sphere_plane`]: `s0 ≤ r`,
/// a centre inside the solid included): `t = 0`, [`ToiStatus::Penetrating`],
/// the static contact. No closing speed (`k ≤ 0`: parallel motion or moving
/// away) or touching after `t_max`: `None`. Otherwise
/// [`ToiStatus::Converged`].
///
/// **Degenerate input.** A zero or non-finite normal defines no plane: `None`,
/// as for [`contact_sphere_plane`] (the fixture format refuses such planes). A
/// scene whose intermediate values overflow is answered `None`, never NaN. A
/// negative or NaN `t_max` is read as 0.
pub fn toi_sphere_plane<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &Plane<T>, vb: &Vec3<T>, t_max: T) -> Option<Toi<T>> {
    let t_max = clamp_t_max(t_max);
    let nn = b.normal.norm_squared();
    let (lo, hi) = safe_squared_range::<T>();
    if !(nn >= lo && nn <= hi) {
        return toi_sphere_plane_scaled(a, va, b, vb, t_max);
    }
    // s' = s0 ‖n‖ and k' = closing ‖n‖: the normal's length cancels in t.
    let sp = b.normal.dot(&a.center) - b.offset;
    // A signed distance below the plain range may be a sum of products
    // flushed to 0 (a normal of 5e-67 against a centre at 1.2e-308: the
    // gap reads 0 and the sphere, moving at `MAX`, is answered where it
    // starts): the scaled path forms it at its own scale.
    if !(sp.finite() && sp.abs() >= lo) {
        return toi_sphere_plane_scaled(a, va, b, vb, t_max);
    }
    // Within r (up to rounding), or squares too small to tell: the static
    // test decides, whenever its own root-free test does not say apart.
    let r = a.radius;
    if !clearly_apart(sp, r, nn) {
        if let Some(k) = contact_sphere_plane(a, b) {
            return Some(penetrating(a, b, &k));
        }
        if let Some(k) = tiny_scene(a, va, b, vb) {
            return scaled_up(a, va, b, vb, t_max, k);
        }
    }
    // A closing speed that overflowed (`8 · 2.8e307` for a normal of length
    // 8) or fell below the plain range (its products may have underflowed)
    // takes the scaled path, which forms it from the unit normal and the
    // relative velocity at its own scale.
    let kp = -b.normal.dot(&(va - vb));
    if !(kp.abs() >= lo && kp.finite()) {
        return toi_sphere_plane_scaled(a, va, b, vb, t_max);
    }
    if !(kp > T::zero()) {
        return None;
    }
    let len = nn.sqrt();
    let gap = sp - r * len;
    let t = (gap / kp).max(T::zero());
    if !(t <= t_max) {
        return None;
    }
    // A time below the normal range (or flushed to 0) has lost its bits,
    // and the point moves by it: at a high closing speed the motion
    // `va t` is of the scene's size (a centre at 1e-300 meeting a plane at
    // 1e300 per unit time). The scaled path moves the point by the
    // unrounded time.
    if gap > T::zero() && t < smallest_normal::<T>() {
        return toi_sphere_plane_scaled(a, va, b, vb, t_max);
    }
    let n = b.normal * (T::one() / len);
    Some(Toi {
        t,
        point: a.center + va * t - n * r,
        normal: n,
        status: ToiStatus::Converged,
        iterations: 0,
        degenerate: false,
    })
}

/// The smallest positive normal number of `T`: below it a time keeps fewer
/// than the type's digits.
fn smallest_normal<T: Real>() -> T {
    T::of(if T::EPSILON.wide() < 1e-10 { f64::MIN_POSITIVE } else { f64::from(f32::MIN_POSITIVE) })
}

/// The answer of a sphere in contact with the half-space at `t = 0`: the
/// static contact, flagged only when its point lies beyond the type's range
/// (a plane's normal is never a fallback; the static contact's flag also
/// marks a depth beyond the range, which a time of impact does not report:
/// a sphere of radius `MAX` whose centre is `1e300` inside).
fn penetrating<T: Real>(a: &Sphere<T>, b: &Plane<T>, k: &Contact<T>) -> Toi<T> {
    let beyond = k.degenerate && contact_sphere_plane_parts(a, b).is_none_or(|(_, beyond)| beyond);
    Toi::penetrating_flagged(k, beyond)
}

/// The scaled path of [`toi_sphere_plane`]: a normal whose squared length would
/// underflow or overflow, or a signed distance that overflows.
#[inline(never)]
fn toi_sphere_plane_scaled<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Plane<T>,
    vb: &Vec3<T>,
    t_max: T,
) -> Option<Toi<T>> {
    // The unit normal from the normal's parts: its length may overflow or
    // round in the subnormals (see `normal_parts`).
    let (_, _, n) = normal_parts(&b.normal)?;
    if let Some(k) = contact_sphere_plane(a, b) {
        return Some(penetrating(a, b, &k));
    }
    if let Some(k) = tiny_scene(a, va, b, vb) {
        return scaled_up(a, va, b, vb, t_max, k);
    }
    let (t, point) = scaled_time(a, va, b, vb)?;
    let t = T::of(t);
    if t.is_nan() || t > t_max {
        return None;
    }
    // s0 > r up to the static test's rescue of overflowing scenes; never before 0.
    let t = t.max(T::zero());
    Some(Toi {
        t,
        point: Vec3::new(T::of(point[0]), T::of(point[1]), T::of(point[2])),
        normal: n,
        status: ToiStatus::Converged,
        iterations: 0,
        degenerate: false,
    })
}

/// The power of two `2^k` (`k > 0`) that brings a scene whose lengths (the
/// centre, the radius, the plane's offset and both velocities; the normal is
/// a direction) all lie below the plain range (see
/// [`unit_scale`](crate::real::unit_scale)) to about 1; `None` otherwise.
/// In such a scene the signed distance, the closing speed and their
/// quotient are formed from subnormal products with a few bits each (a `t`
/// of `1.6249995` for `1.625`, from coordinates near `1e-317`).
fn tiny_scene<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &Plane<T>, vb: &Vec3<T>) -> Option<i32> {
    let amax = |p: &Vec3<T>| p.x.abs().max(p.y.abs()).max(p.z.abs());
    let size = amax(&a.center).max(a.radius.abs()).max(b.offset.abs()).max(amax(va)).max(amax(vb));
    crate::real::unit_scale(size).filter(|k| *k > 0)
}

/// [`toi_sphere_plane`] of the scene with every length scaled by `2^k`
/// (exact, scaling up: the plane `n·x = d` becomes `n·x = 2^k d`), the
/// contact point scaled back; the time and the normal do not scale. For a
/// sphere the static test called apart at the original scale (the static
/// test decides the start, so the time of impact and the contact agree on
/// it): a contact of the scaled scene at `t = 0` is a touch at 0, within
/// the roundings of the original one, not a penetration.
#[cold]
#[inline(never)]
fn scaled_up<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &Plane<T>, vb: &Vec3<T>, t_max: T, k: i32) -> Option<Toi<T>> {
    use crate::real::{scale2, scale2v};
    let a2 = Sphere::new(scale2v(&a.center, k), scale2(a.radius, k));
    let b2 = Plane::new(b.normal, scale2(b.offset, k));
    toi_sphere_plane(&a2, &scale2v(va, k), &b2, &scale2v(vb, k), t_max).map(|mut r| {
        r.point = scale2v(&r.point, -k);
        r.status = ToiStatus::Converged;
        r
    })
}

/// `(s0 − r)/k` of [`toi_sphere_plane_scaled`] (`s0` the centre's signed
/// distance, `k` the closing speed), in `f64` on the widened inputs, with no
/// intermediate overflow or underflow, and with it the contact point at that
/// time. `None` for no closing speed (or none defined: NaN).
///
/// - The unit normal `n̂` from the scaled norm.
/// - The relative velocity at the scale `2^−e` that brings the largest
///   component of `va` and `vb` to `[1/2, 1)` (exact, except for components
///   far below that one, whose roundings are below it by the same factor), so
///   neither `va − vb` nor `n̂ · (va − vb)` overflows or underflows.
/// - The gap `s0 − r` at the scale `2^−g` of its largest term (`‖M‖∞`, `r`
///   and the plane's distance `d/‖n‖`, the last from the mantissas and
///   exponents of `d` and `‖n‖`): `d/‖n‖` alone can exceed `f64` (an offset
///   of 3e109 over a normal of length 3.6e-209) while the time is finite.
/// - The time from the mantissas of gap and closing speed, scaled back once
///   (their quotient can overflow where the time does not: a gap of 1e302
///   over a closing speed of 1e-39 at its scale is a time of 8e57).
fn scaled_time<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &Plane<T>, vb: &Vec3<T>) -> Option<(f64, [f64; 3])> {
    use crate::exact::{frexp, ldexp};
    let w = crate::real::to_f64_3::<T>;
    let (nw, m, pa, pb) = (w(&b.normal), w(&a.center), w(va), w(vb));
    let (offset, radius) = (b.offset.wide(), a.radius.wide());
    let (nm, nl, unit) = normal_parts(&Vec3::from(nw))?;
    let n = [unit.x, unit.y, unit.z];
    let dot = |x: [f64; 3]| (n[0] * x[0] + n[1] * x[1]) + n[2] * x[2];
    let top = pa.iter().chain(pb.iter()).fold(0.0f64, |t, x| t.max(x.abs()));
    if !(top > 0.0 && top.is_finite()) {
        return None;
    }
    let (_, e) = frexp(top);
    let closing = -dot([0, 1, 2].map(|i| ldexp(pa[i], -e) - ldexp(pb[i], -e)));
    if !(closing > 0.0) {
        return None;
    }
    // The exponent of each length: `|x| < 2^exp(x)` (zero: far below all).
    let exp = |x: f64| if x == 0.0 { i64::MIN / 4 } else { frexp(x.abs()).1 };
    // ‖n‖ = nm · nl as a mantissa in [1/2, √3) and an exponent (never formed:
    // it overflows or rounds, see `normal_parts`).
    let (om, oe) = frexp(offset.abs());
    let (lm, le) = {
        let (mm, me) = frexp(nm);
        (mm * nl, me)
    };
    let plane_exp = if offset == 0.0 { i64::MIN / 4 } else { oe - le + 1 };
    let mmax = m.iter().fold(0.0f64, |t, x| t.max(x.abs()));
    // 2 more: n̂ · M is at most √3 ‖M‖∞, and three terms are summed.
    let g = exp(mmax).max(exp(radius)).max(plane_exp) + 2;
    let plane = offset.signum() * ldexp(om / lm, oe - le - g);
    let mg = m.map(|x| ldexp(x, -g));
    let gap = (dot(mg) - plane) - ldexp(radius, -g);
    let ((gm, ge), (cm, ce)) = (frexp(gap.max(0.0)), frexp(closing));
    // The time as a mantissa and an exponent: the contact point moves by
    // the unrounded time, which may lie below f64's range or in its
    // subnormals (a gap of 3.6e-59 closed at 1.2e308: t = 3e-367 rounds to
    // 0, while the plane, moving at `MAX`, travels 5e-59 by then).
    let (tm, te) = if gap > 0.0 {
        let (qm, qe) = frexp(gm / cm);
        (qm, qe + ge + g - ce - e)
    } else {
        (0.0, 0)
    };
    let t = ldexp(tm, te);
    // The point, in one of two forms that agree at the touch, whichever
    // sums the smaller terms (the other cancels):
    // - the centre's projection onto the plane at t = 0, moved by the
    //   centre's motion with its normal part replaced by the plane's,
    //   `va + n̂ k` (k the closing speed); the foot is
    //   `M − n̂ (n̂ · M) + n̂ d/‖n‖`, whose part along `n̂` is the plane's
    //   offset itself. Its normal part sums `d/‖n‖` and `t n̂·vb`: right for
    //   a sphere that moves fast onto a still plane (`M + va t − n̂ r`
    //   cancels there: at speed 2.8e307 the rounding of `t` alone is 1e284);
    // - the sphere's lowest point `M + va t − n̂ r`, whose normal part sums
    //   `n̂·M`, `r` and `t n̂·va`: right for a plane that comes from afar to a
    //   slow sphere (a plane 2^1100 away: the foot is beyond `f64`).
    // Both at one scale `2^−h` that holds every term (the foot and the
    // motion may each exceed `f64` where their sum does not).
    let along = [0, 1, 2].map(|i| ldexp(pa[i], -e) + n[i] * closing);
    let va_s = pa.map(|x| ldexp(x, -e));
    let vb_s = pb.map(|x| ldexp(x, -e));
    // The exponent of a velocity component's motion `x 2^e t` (`x` at the
    // scale 2^−e): below `2^(exp(x) + e + te)`.
    let motion = |x: f64| if tm > 0.0 && x != 0.0 { exp(x) + e + te } else { i64::MIN / 4 };
    // Which form sums the smaller terms along the normal (as exponents):
    // the plane's `d/‖n‖` and `t n̂·vb`, or the sphere's `n̂·M`, `r` and
    // `t n̂·va` (`n̂·M` at a quarter scale, which cannot overflow).
    let plane_cost = plane_exp.max(motion(dot(vb_s)));
    let sphere_cost = (exp(dot(m.map(|x| x * 0.25))) + 2).max(exp(radius)).max(motion(dot(va_s)));
    let vmax = |v: &[f64; 3]| v.iter().fold(0.0f64, |x, y| x.max(y.abs()));
    // Each form at the scale `2^−h` of its largest term, 2 more for the sums.
    let (velocity, h) = if sphere_cost < plane_cost {
        (va_s, exp(mmax).max(exp(radius)).max(motion(vmax(&va_s))) + 2)
    } else {
        (along, (g - 2).max(motion(vmax(&along))) + 2)
    };
    // `x · t · 2^(e − h)` for a velocity component `x` at the scale 2^−e;
    // a zero moves nothing however long the time.
    let tscale = ldexp(tm, e + te - h);
    let moved = |x: f64| if x == 0.0 { 0.0 } else { x * tscale };
    let (mh, ph, rh) = (m.map(|x| ldexp(x, -h)), offset.signum() * ldexp(om / lm, oe - le - h), ldexp(radius, -h));
    let point = if sphere_cost < plane_cost {
        [0, 1, 2].map(|i| ldexp((mh[i] - n[i] * rh) + moved(velocity[i]), h))
    } else {
        let mn = dot(mh);
        [0, 1, 2].map(|i| ldexp(((mh[i] - n[i] * mn) + n[i] * ph) + moved(velocity[i]), h))
    };
    Some((t, point))
}
