//! Sphere–triangle time of impact by conservative advancement.

use super::feature_roots::{FirstContact, first_contact};
use super::time_of_impact::{Toi, ToiStatus, approach_fallback, clamp_t_max};
use crate::contact::{closest_pt_point_triangle, contact_sphere_triangle};
use crate::real::{Real, Vec3, c, scale2, scale2v, stable_norm, try_normalize_stable, unit_scale};
use crate::shapes::{Sphere, Triangle};

/// The default gap tolerance of conservative advancement, in units of the
/// type's ε times the scene's scale (the largest of the radius and the largest
/// coordinate of the centre and of the vertices at `t = 0`).
///
/// The gap `‖M(t) − q(t)‖ − r` is computed with an error of a few ulps of that
/// scale (the closest point is a handful of dot products and one division), so a
/// tolerance below ~10 ε·scale could not be reached reliably; 64 leaves room and
/// is still ~1.4e-14 of the scale in `f64` (7.6e-6 in `f32`). Units: ε·scale.
pub const ADVANCE_TOL_EPS: f64 = 64.0;

/// The default cap on advancement steps. A head-on approach to the face
/// converges in one step (the distance is linear in time there); the slowest
/// case, a grazing contact at an edge or a vertex, quarters the gap per step
/// (see [`toi_sphere_triangle`]), so reaching [`ADVANCE_TOL_EPS`] from a gap of
/// the scene's size takes about `log₄(1 / (64 ε))` ≈ 23 steps in `f64`. 64 is
/// well above that; hitting it is reported, not hidden.
pub const MAX_ADVANCE_STEPS: u32 = 64;

/// The stopping rule of conservative advancement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Advancement {
    /// Stop when the gap is at most this many ε times the scene's scale (see
    /// [`ADVANCE_TOL_EPS`]).
    pub tol_eps: f64,
    /// Give up after this many steps, with [`ToiStatus::OutOfIterations`].
    pub max_steps: u32,
}

impl Default for Advancement {
    /// [`ADVANCE_TOL_EPS`] and [`MAX_ADVANCE_STEPS`].
    fn default() -> Self {
        Self { tol_eps: ADVANCE_TOL_EPS, max_steps: MAX_ADVANCE_STEPS }
    }
}

/// Time of impact of sphere `a` (centre `M`, radius `r`, velocity `va`) and
/// triangle `b` (velocity `vb`) over `[0, t_max]`, by **conservative
/// advancement** (Mirtich, *Impulse-based dynamic simulation*, 1996; Ericson
/// §9.5.4 for the distance-bound formulation).
///
/// **Method.** Work in `b`'s frame: the centre moves as `M(t) = M + t v` with
/// `v = va − vb` past the triangle at its time-0 position. Starting at `t = 0`,
/// repeat:
///
/// ```text
/// q = closest_pt_point_triangle(M(t), b),   d = ‖M(t) − q‖,   gap = d − r
/// stop (converged) when gap ≤ tol
/// n = (M(t) − q)/d,   closing = −v·n          (the speed toward q)
/// no impact when closing ≤ 0;  otherwise  t ← t + gap/closing
/// no impact when t > t_max
/// ```
///
/// **Why the step is safe.** The distance from a moving point to a convex set,
/// `D(t) = dist(M(t), b)`, is a convex function of `t` for linear motion, and
/// its slope at `t` is `v·n = −closing`. A convex function lies above its
/// tangent, so `D(t + τ) ≥ D(t) − τ·closing`, and the gap cannot close before
/// `τ = gap/closing`: the step never passes the first contact. The classic bound
/// divides by the full relative speed `‖v‖` instead; `closing ≤ ‖v‖`, so the step
/// here is never shorter than that one, and it is exact (one step) for a face
/// hit, where `D` is linear. For the same reason `closing ≤ 0` means `D` never
/// decreases again: the sphere is moving away and there is no impact.
///
/// **Stopping rule.** `tol = tol_eps · ε · scale` ([`ADVANCE_TOL_EPS`] by
/// default, scale as described there): the gap is then below what the distance
/// computation can resolve; a few last steps of the same rule are taken from
/// there (see `POLISH_STEPS`), which land on a face contact up to rounding and
/// take the gap at an edge or a vertex down to the distance's rounding, so the
/// reported `t` is at the first contact up to that rounding over the closing
/// speed. A last step that would end after `t_max` means the contact is after
/// it: no impact. Near grazing (an edge or vertex
/// met tangentially) `D` is flat at the contact, each step halves the time left
/// and quarters the gap, and `t`'s error is about `√(2 r tol)/‖v‖` when the gap
/// first falls below the tolerance (halved by each last step): the
/// distance's own resolution, seen through a flat minimum. The loop also stops, converged, when a step no longer
/// changes `t` in the type. After `max_steps` steps without converging the
/// answer is [`ToiStatus::OutOfIterations`] with `t` the last (safe) time and
/// the closest points then.
///
/// **Answer.** Already in contact at `t = 0` ([`contact_sphere_triangle`],
/// touching counts): `t = 0`, [`ToiStatus::Penetrating`], the static contact.
/// Converged: the normal `n` (from the triangle toward the sphere) and the point
/// `q + t vb` on the triangle at time `t`.
///
/// **Degenerate input.** A zero-area triangle is the segment or point it
/// collapsed to ([`closest_pt_point_triangle`]'s fallback): its distance is still
/// convex, so the method is unchanged. A sphere of zero radius meets the triangle
/// at a point with no direction: the normal is the direction it came from,
/// `−v/‖v‖`, flagged. A centre on the triangle at `t = 0` gets the static test's
/// fallback (flagged). Non-finite intermediate values end the search with `None`,
/// never NaN. A negative or NaN `t_max` is read as 0.
///
/// **Scenes of widely mixed magnitudes.** Where the triangle's coordinates
/// reach beyond [`EXACT_RANGE_RATIO`] (2^20) times the sphere's own scale
/// (its radius, its centre, its distance from the triangle's box), the
/// rounding of advancement's distances, at the vertices' scale, can exceed
/// the sphere and its gap, and the steps pass the first contact or stop at
/// once. Such a scene is answered by [`toi_exact`] instead: the first contact
/// solved from the face's, edges' and vertices' equations with exact
/// coefficients, the time within a few roundings, `iterations` 0.
///
/// **Beyond the range.** A contact whose point, moved with `b` to time `t`,
/// lies beyond the type's range (the shapes have travelled past `MAX` by
/// then) has no answer in the type: `None`, never an infinity. (Such an
/// impact, if real, has no representable answer at all; in practice it is an
/// advancement that converged on a distance its scene's rounding could not
/// resolve — a huge `t_max` in a scene of wildly mixed magnitudes.)
pub fn toi_sphere_triangle<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Triangle<T>,
    vb: &Vec3<T>,
    t_max: T,
    rule: &Advancement,
) -> Option<Toi<T>> {
    let t_max = clamp_t_max(t_max);
    // The static contact on the scene as given: it scales its own scene
    // where that is safe, while the advancement's scaling below may push the
    // smallest coordinates beside a huge sphere into the subnormals or to
    // zero — a centre just off the triangle's plane would land in it.
    if let Some(k) = contact_sphere_triangle(a, b) {
        return Some(Toi::penetrating(&k));
    }
    let [p, q, s] = b.vertices;
    if beyond_advancement(a, &p.inf(&q).inf(&s), &p.sup(&q).sup(&s)) {
        return toi_exact(a, va, b, vb, t_max).filter(Toi::in_range);
    }
    toi_clear(a, va, b, vb, t_max, rule).filter(Toi::in_range)
}

/// How far a triangle's (or a mesh's) coordinates may reach beyond the
/// sphere's own scale before its time of impact is solved from the
/// features' exact equations ([`toi_exact`]) instead of by advancement:
/// 2^20.
///
/// Reason: advancement's distances, closest points and gap tolerance carry
/// rounding of a few ε (and its tolerance 64 ε) of the largest coordinate
/// they are formed from — the triangle's vertices, and for a mesh its whole
/// box — while the first contact happens at the sphere's own scale: its
/// radius, its centre, and how far it must travel to the triangle (at least
/// its distance from the triangle's box). Within 2^20 of that scale the
/// rounding stays below 2^20 · 64 ε ≈ 1.5e-8 of it and the polishing steps
/// take the answer down to the distance's own rounding (every ordinary scene
/// and nearly every full-range one); beyond it the rounding can exceed the
/// sphere and the gap itself, and advancement stepped past the first contact
/// or stopped at once: a sphere of radius 1e43 under a triangle with
/// vertices of 1e265 answered a contact 10^18 times too late, one of radius
/// 5e15 beside a mesh of 1e291 answered at t ≈ 1e-137 instead of 0.013. The
/// exact solve is right at every scale but costs a few hundred exact
/// products — measured at 10–18 µs on a unit scene, where advancement takes
/// 0.4 µs, and 0.25–0.6 ms on the full-range scenes above, whose exact values
/// span thousands of bits — so it answers only these scenes (crashtest's
/// ordinary toi cases are answered exactly as before).
pub(crate) const EXACT_RANGE_RATIO: f64 = 1_048_576.0;

/// Whether a triangle or mesh with the box `[lo, hi]` reaches beyond
/// [`EXACT_RANGE_RATIO`] times the sphere's own scale: the largest of its
/// radius, its centre's largest coordinate and its distance from the box
/// (the largest per-axis gap, a lower bound on how far it travels to any
/// contact). In `f64`, so no difference overflows in a narrower type. A
/// non-finite input (a coordinate beyond a narrower type's range, rounded to
/// an infinity) answers `false`: the exact solve has no answer for it, and
/// advancement keeps its own handling.
pub(crate) fn beyond_advancement<T: Real>(a: &Sphere<T>, lo: &Vec3<T>, hi: &Vec3<T>) -> bool {
    let w = |p: &Vec3<T>| [p.x.wide(), p.y.wide(), p.z.wide()];
    let (m, lo, hi) = (w(&a.center), w(lo), w(hi));
    if !(a.radius.finite() && m.iter().chain(&lo).chain(&hi).all(|x| x.is_finite())) {
        return false;
    }
    let mut own = a.radius.wide().abs();
    let mut big = 0.0_f64;
    for k in 0..3 {
        own = own.max(m[k].abs()).max(lo[k] - m[k]).max(m[k] - hi[k]);
        big = big.max(lo[k].abs()).max(hi[k].abs());
    }
    big > EXACT_RANGE_RATIO * own
}

/// [`toi_sphere_triangle`] for a sphere clear of the triangle at `t = 0`
/// (by the static test), from the features' exact equations
/// ([`first_contact`]): the time within a few roundings of the exact first
/// contact, the normal and the point on the triangle (world frame) from exact
/// components at that time. No power-of-two scaling: exact
/// arithmetic has no range to keep within.
pub(crate) fn toi_exact<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Triangle<T>,
    vb: &Vec3<T>,
    t_max: T,
) -> Option<Toi<T>> {
    first_contact(a, va, b, vb, t_max).map(|hit| exact_answer(a, va, vb, &hit))
}

/// The answer of an exact solve in the format's convention: `t` rounded to
/// the type (never above `t_max`, which is a value of the type), the normal
/// rounded from its exact direction — for a zero radius or no direction the
/// approach direction `−v/‖v‖`, flagged, as for advancement — and the point
/// on `b`'s surface at the contact, rounded from its exact value. A sphere found touching at
/// `t = 0` (the static test is accurate to 2^−38 of the distance, so it can
/// call such a sphere clear by a hair) is [`ToiStatus::Penetrating`].
pub(crate) fn exact_answer<T: Real>(a: &Sphere<T>, va: &Vec3<T>, vb: &Vec3<T>, hit: &FirstContact) -> Toi<T> {
    let t = T::of(hit.t);
    let (normal, degenerate) = match hit.normal {
        Some([x, y, z]) if a.radius > T::zero() => (Vec3::new(T::of(x), T::of(y), T::of(z)), false),
        _ => (approach_fallback(&(va - vb)), true),
    };
    let status = if hit.at_start { ToiStatus::Penetrating } else { ToiStatus::Converged };
    let [x, y, z] = hit.point;
    Toi { t, point: Vec3::new(T::of(x), T::of(y), T::of(z)), normal, status, iterations: 0, degenerate }
}

/// [`toi_sphere_triangle`] for a sphere known to be clear of the triangle at
/// `t = 0`.
fn toi_clear<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Triangle<T>,
    vb: &Vec3<T>,
    t_max: T,
    rule: &Advancement,
) -> Option<Toi<T>> {
    // Outside the plain range (huge, tiny or subnormal scenes, displacements
    // near the type's limits) the scene is answered scaled by a power of two
    // to about 1, where no square or distance under- or overflows and the
    // tolerance is not lost in the subnormals; its point is scaled back.
    // The sphere and the motion decide: a small sphere beside a huge triangle
    // is answered as it is (the closest point is exact enough at any size,
    // and the tolerance is the sphere's), since scaling the triangle to 1
    // would push the sphere into the subnormals.
    if let Some(k) = unit_scale(a.radius.abs().max(amax(&a.center)).max(amax(va)).max(amax(vb))) {
        let a2 = Sphere { center: scale2v(&a.center, k), radius: scale2(a.radius, k) };
        let b2 = Triangle { vertices: b.vertices.map(|p| scale2v(&p, k)) };
        return toi_clear(&a2, &scale2v(va, k), &b2, &scale2v(vb, k), t_max, rule).map(|mut r| {
            r.point = scale2v(&r.point, -k);
            r
        });
    }
    let v = va - vb;
    // The tolerance is the problem's own scale, not the triangle's: the
    // sphere's (its radius and centre), grown at each step to the closest
    // point's size. A small sphere beside a triangle with legs of 1e300 has a
    // distance that resolves to its own ulps, and a tolerance of the legs'
    // size would stop the advancement at once.
    let per_size = c::<T>(rule.tol_eps) * T::EPSILON;
    let tol = per_size * a.radius.abs().max(amax(&a.center));
    advance(a, &v, b, t_max, tol, per_size, rule.max_steps).map(|s| s.answer(a, &v, vb))
}

/// Where conservative advancement against one triangle stopped.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Advanced<T: Real> {
    /// The time reached.
    pub t: T,
    /// The triangle's closest point to the centre then (in `b`'s frame at time 0).
    pub q: Vec3<T>,
    /// The centre then, minus `q`.
    pub delta: Vec3<T>,
    /// [`ToiStatus::Converged`] or [`ToiStatus::OutOfIterations`].
    pub status: ToiStatus,
    /// Steps taken.
    pub steps: u32,
}

impl<T: Real> Advanced<T> {
    /// The answer in the format's convention: the normal from the triangle toward
    /// the centre (the approach direction `−v/‖v‖` when there is none, flagged),
    /// the point `q` moved with `b` to time `t`.
    pub(crate) fn answer(&self, a: &Sphere<T>, v: &Vec3<T>, vb: &Vec3<T>) -> Toi<T> {
        let (normal, degenerate) = match try_normalize_stable(&self.delta) {
            Some(n) if a.radius > T::zero() => (n, false),
            _ => (approach_fallback(v), true),
        };
        Toi { t: self.t, point: self.q + vb * self.t, normal, status: self.status, iterations: self.steps, degenerate }
    }
}

/// The advancement loop of [`toi_sphere_triangle`] in `b`'s frame: the centre
/// moves as `a.center + t v` past the triangle `b` at its time-0 position; the
/// sphere is known to be clear of it at `t = 0`. `None`: no impact in
/// `[0, t_max]` (moving away, passing by, arriving late, or a non-finite value).
/// Its answers do not depend on `t_max` other than through that cut: the steps
/// are the same whatever the limit, so an answer at `t ≤ t_max` is the same for
/// every `t_max ≥ t`.
///
/// The gap tolerance is `tol`, or `per_size` times the size of the centre and
/// of the closest point at that step when that is larger (0 keeps `tol`
/// fixed, as the mesh query does, whose `tol` is of the whole mesh's scale).
#[allow(clippy::too_many_arguments)]
pub(crate) fn advance<T: Real>(
    a: &Sphere<T>,
    v: &Vec3<T>,
    b: &Triangle<T>,
    t_max: T,
    tol: T,
    per_size: T,
    max_steps: u32,
) -> Option<Advanced<T>> {
    let mut t = T::zero();
    let mut steps = 0u32;
    let fixed = tol;
    let closest = closest_for(a, v, b, t_max);
    loop {
        let p = a.center + v * t;
        let q = closest(&p);
        let tol = fixed.max(per_size * amax(&p).max(amax(&q)));
        let delta = p - q;
        let dist = stable_norm(&delta);
        let gap = dist - a.radius;
        if !gap.finite() {
            return None;
        }
        let stop = |status| Some(Advanced { t, q, delta, status, steps });
        if gap <= tol {
            let polished =
                polish(a, v, &closest, t_max, Advanced { t, q, delta, status: ToiStatus::Converged, steps })?;
            return Some(grazing_root(a, v, b, &closest, t_max, tol, polished));
        }
        if steps >= max_steps {
            return stop(ToiStatus::OutOfIterations);
        }
        // gap > tol ≥ 0, so dist > 0 and the direction exists.
        let closing = -v.dot(&(delta / dist));
        if closing.is_nan() || closing <= T::zero() {
            return None;
        }
        let next = t + gap / closing;
        if next.is_nan() || next > t_max {
            return None;
        }
        if next <= t {
            // The time left is below t's resolution: as close as the type gets.
            return stop(ToiStatus::Converged);
        }
        t = next;
        steps += 1;
    }
}

/// Steps taken after the gap first falls within the tolerance, at most: 6.
/// Reason: each of them lands on a face contact up to rounding, and at an edge
/// or a vertex (a flat minimum of the distance) halves the time left and
/// quarters the gap, so six take a gap of `tol` down to `tol / 4096`, below the
/// distance's own rounding (a few ε·scale) from the default tolerance — also
/// far from the origin, where the tolerance may exceed the radius.
const POLISH_STEPS: u32 = 6;

/// The last steps of a converged advancement: from a gap within the tolerance,
/// up to [`POLISH_STEPS`] more steps `gap / closing` (safe, as every step), so
/// that the answer is at the contact up to rounding rather than up to the
/// tolerance. They stop at a gap of 0 or below (touching, up to rounding), at no
/// closing speed, or at a step below `t`'s resolution; a step that would end
/// after `t_max` means the contact is after it: no impact, as for any other
/// step.
fn polish<T: Real>(
    a: &Sphere<T>,
    v: &Vec3<T>,
    closest: &impl Fn(&Vec3<T>) -> Vec3<T>,
    t_max: T,
    at: Advanced<T>,
) -> Option<Advanced<T>> {
    let mut at = at;
    for _ in 0..POLISH_STEPS {
        let dist = stable_norm(&at.delta);
        let gap = dist - a.radius;
        if !(gap > T::zero()) {
            break;
        }
        let closing = -v.dot(&(at.delta / dist));
        if !(closing > T::zero()) {
            break;
        }
        let next = at.t + gap / closing;
        if !next.finite() || next > t_max {
            return None;
        }
        if next <= at.t {
            break;
        }
        let p = a.center + v * next;
        let q = closest(&p);
        at = Advanced { t: next, q, delta: p - q, steps: at.steps + 1, ..at };
    }
    Some(at)
}

/// The scene's length scale for the tolerance: the largest of `r` and the
/// largest coordinate of the centre and of the vertices at `t = 0`.
///
/// The displacement is left out on purpose: up to the first contact the centre
/// stays within `‖M‖ + ‖q‖ + r` of the origin, so the rounding of `M + t v`
/// there is already of this scale, and a huge `t_max` (parry's "no limit",
/// `f64::MAX`) would otherwise make the tolerance infinite.
pub(crate) fn scale<T: Real>(a: &Sphere<T>, vertices: &[Vec3<T>]) -> T {
    let mut s = a.radius.abs().max(amax(&a.center));
    for p in vertices {
        s = s.max(amax(p));
    }
    s
}

/// The largest absolute coordinate.
pub(crate) fn amax<T: Real>(p: &Vec3<T>) -> T {
    p.x.abs().max(p.y.abs()).max(p.z.abs())
}

/// How far beyond the sphere's own size (its radius, centre and motion) a
/// triangle's vertices must reach before the advancement takes its closest
/// points from the static contact's certified path: 2^20. Reason: below it the
/// plain closest point's rounding, relative to the vertices' size, stays within
/// the gap tolerance's few hundred ulps of the sphere's size; above it the
/// small coordinates beside the huge ones are lost (a sphere near the small
/// vertex of a triangle with legs of 1e70 missed its impact).
const MULTI_SCALE_RATIO: f64 = 1_048_576.0;

/// Growth of the nearest vertex's distance for the fallback probe of
/// [`closest_for`]: `1 + 2^−20`, far above that distance's rounding, so the
/// probe reaches the vertex (the triangle's distance is at most its).
const PROBE_GROWTH: f64 = 1.0 + 1.0 / 1_048_576.0;

/// The closest point of `b` to a point on the sphere's path: the plain one,
/// or, for a small sphere beside a huge triangle (see [`MULTI_SCALE_RATIO`]),
/// the static contact's, which is exact to the sphere's size there (asked of a
/// sphere at that point large enough to touch the triangle: twice the plain
/// point's distance, or when the plain point's rounding put it nearer than
/// the triangle — a sphere beside the small vertex of a triangle with legs
/// of 1e100 got the origin — the nearest vertex's distance).
fn closest_for<'a, T: Real>(
    a: &Sphere<T>,
    v: &Vec3<T>,
    b: &'a Triangle<T>,
    t_max: T,
) -> impl Fn(&Vec3<T>) -> Vec3<T> + 'a {
    let reach = a.radius.abs().max(amax(&a.center)).max(amax(v) * t_max.min(T::one()));
    let huge = b.vertices.iter().map(amax).fold(T::zero(), |m, x| m.max(x));
    let multi = huge.wide() > MULTI_SCALE_RATIO * reach.wide();
    move |p: &Vec3<T>| {
        let q = closest_pt_point_triangle(p, b);
        if !multi {
            return q;
        }
        let d = crate::real::stable_norm(&(p - q));
        let probe = Sphere::new(*p, d + d + T::of(f64::MIN_POSITIVE));
        if let Some(k) = contact_sphere_triangle(&probe, b) {
            return k.point;
        }
        // The plain point is nearer than the triangle (its rounding put it
        // there): a probe reaching the nearest vertex certainly touches.
        let reach = b.vertices.iter().map(|x| stable_norm(&(p - x))).fold(T::of(f64::MAX), |m, x| m.min(x));
        let probe = Sphere::new(*p, reach * c::<T>(PROBE_GROWTH) + T::of(f64::MIN_POSITIVE));
        contact_sphere_triangle(&probe, b).map_or(q, |k| k.point)
    }
}

/// Closing speed, relative to the relative speed, below which a converged
/// advancement is taken as grazing and its time re-solved by
/// [`grazing_root`]: `2^−8`. A head-on or oblique approach converges in a
/// few steps to rounding; a grazing one (an edge or vertex met nearly
/// tangentially) only to about the square root of the tolerance.
const GRAZING_CLOSING: f64 = 1.0 / 256.0;

/// For a grazing contact (see [`GRAZING_CLOSING`]), the time re-solved from
/// the features' own equations, whose coefficients are computed exactly:
/// the first root of `‖w + t v‖² = r²` for each vertex (`w = M − V`) and of
/// `‖u × (w + t v)‖² = r² ‖u‖²` for each edge (`w = M − P0`, `u = P1 − P0`,
/// kept when the foot's parameter at the root is in `[0, 1]`), the earliest
/// of them. Every feature is a part of the triangle, so none is met before
/// the triangle is, and the one met first is; the face's contact is linear
/// and already exact from the advancement. Where the distance is flat (a
/// double root, or nearly) the advancement's time is off by the square root
/// of its tolerance; the root is off by a rounding of the coefficients'
/// estimates.
///
/// The root replaces the advancement's time only within the window a
/// grazing advancement can be early by (four times `√(2 r tol)/‖v‖`), and at
/// or before `t_max`; the point and direction are recomputed there.
fn grazing_root<T: Real>(
    a: &Sphere<T>,
    v: &Vec3<T>,
    b: &Triangle<T>,
    closest: &impl Fn(&Vec3<T>) -> Vec3<T>,
    t_max: T,
    tol: T,
    at: Advanced<T>,
) -> Advanced<T> {
    let speed = stable_norm(v);
    let dist = stable_norm(&at.delta);
    if !(dist > T::zero() && speed > T::zero()) {
        return at;
    }
    let closing = -v.dot(&(at.delta / dist));
    if !(closing.wide() < GRAZING_CLOSING * speed.wide()) {
        return at;
    }
    let Some(root) = super::feature_roots::first_root_of_features(a, v, b) else {
        return at;
    };
    let (r, tol, speed) = (a.radius.wide().max(0.0), tol.wide().max(0.0), speed.wide());
    let window = 4.0 * (2.0 * r * tol).sqrt() / speed;
    let t_adv = at.t.wide();
    if !(root <= t_adv + window && root >= 0.0 && root <= t_max.wide()) {
        return at;
    }
    let t = T::of(root);
    let p = a.center + v * t;
    let q = closest(&p);
    Advanced { t, q, delta: p - q, ..at }
}
