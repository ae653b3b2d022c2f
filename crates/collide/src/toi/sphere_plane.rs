//! Sphere–plane time of impact in closed form.

use super::time_of_impact::{Toi, ToiStatus, clamp_t_max};
use crate::contact::{clearly_apart, contact_sphere_plane};
use crate::exact::norm::safe_squared_range;
use crate::real::{Real, Vec3, stable_norm};
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
    if !sp.finite() {
        return toi_sphere_plane_scaled(a, va, b, vb, t_max);
    }
    // Within r (up to rounding), or squares too small to tell: the static
    // test decides, whenever its own root-free test does not say apart.
    let r = a.radius;
    if !clearly_apart(sp, r, nn)
        && let Some(k) = contact_sphere_plane(a, b)
    {
        return Some(Toi::penetrating(&k));
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
    let t = ((sp - r * len) / kp).max(T::zero());
    if !(t <= t_max) {
        return None;
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
    let len = stable_norm(&b.normal);
    if !(len > T::zero() && len.finite()) {
        return None;
    }
    if let Some(k) = contact_sphere_plane(a, b) {
        return Some(Toi::penetrating(&k));
    }
    let n = b.normal / len;
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

/// `(s0 − r)/k` of [`toi_sphere_plane_scaled`] (`s0` the centre's signed
/// distance, `k` the closing speed), in `f64` on the widened inputs, with no
/// intermediate overflow or underflow: the unit normal `n̂` from the scaled
/// norm; `s0 − r` at a quarter of its scale (`n̂ · (M/4)` cannot overflow,
/// and quartering is exact for normal numbers); the relative velocity at
/// the scale `2^−e` that brings the largest component of `va` and `vb` to
/// `[1/2, 1)` (exact, except for components far below that one, whose
/// roundings are below it by the same factor), so neither `va − vb` nor
/// `n̂ · (va − vb)` overflows or underflows; the quotient scaled back once.
/// `None` for no closing speed (or none defined: NaN). With it, the contact
/// point at that time (see the body).
fn scaled_time<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &Plane<T>, vb: &Vec3<T>) -> Option<(f64, [f64; 3])> {
    use crate::exact::{frexp, ldexp};
    let w = crate::real::to_f64_3::<T>;
    let (nw, m, pa, pb) = (w(&b.normal), w(&a.center), w(va), w(vb));
    let len = stable_norm(&Vec3::from(nw));
    let n = nw.map(|x| x / len);
    let dot = |x: [f64; 3]| (n[0] * x[0] + n[1] * x[1]) + n[2] * x[2];
    let gap_quarter = (dot(m.map(|x| x * 0.25)) - (b.offset.wide() / len) * 0.25) - a.radius.wide() * 0.25;
    let top = pa.iter().chain(pb.iter()).fold(0.0f64, |t, x| t.max(x.abs()));
    if !(top > 0.0 && top.is_finite()) {
        return None;
    }
    let (_, e) = frexp(top);
    let closing = -dot([0, 1, 2].map(|i| ldexp(pa[i], -e) - ldexp(pb[i], -e)));
    if !(closing > 0.0) {
        return None;
    }
    let t = ldexp((gap_quarter / closing).max(0.0), 2 - e);
    // The point: the centre's projection onto the plane at t = 0, moved by
    // the centre's motion with its normal part replaced by the plane's,
    // `va + n̂ k` (k the closing speed) — not `M + va t − n̂ r`, whose terms
    // cancel: at speed 2.8e307 the rounding of `t` alone is 1e284 there.
    // The foot is `M − n̂ (n̂ · M) + n̂ d/‖n‖`: its part along `n̂` is the
    // plane's offset itself, not `n̂ · M − s0` (which cancels).
    let (mq, offset) = (m.map(|x| x * 0.25), b.offset.wide() / len);
    let mn = dot(mq);
    let along = [0, 1, 2].map(|i| ldexp(pa[i], -e) + n[i] * closing);
    let point = [0, 1, 2].map(|i| ((mq[i] - n[i] * mn) * 4.0 + n[i] * offset) + ldexp(along[i] * t, e));
    Some((t, point))
}
