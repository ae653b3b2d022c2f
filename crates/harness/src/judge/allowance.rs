//! The verdict's second stage: what each field may be off by, from its sizes
//! ([`super::sizes`]) and the engine's tolerances ([`super::tolerance`]) —
//! the allowance of the verdict, and beside it the conditioning alone and one
//! ulp of each field's magnitude, which the accuracy in ulps is measured by.

use super::sizes::Local;
use super::tolerance::Tolerance;
use crate::case::Shape;
use crate::engine::Answer;
use crate::load::LoadedCase;
use serde::Serialize;

/// What each field of one case's answer is allowed to be off by, for one
/// engine: from the sizes that decide the field ([`super::sizes`]) and the
/// engine's tolerances. Every entry is finite and positive for every finite
/// input (a property test says so): at least the floor of the engine's
/// precision ([`Tolerance::floor`]), at most `f64::MAX` (π for a normal).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Allowed {
    /// The point (largest coordinate error), a length.
    pub point: f64,
    /// The depth or bounding radius, a length.
    pub depth: f64,
    /// The normal, radians.
    pub normal: f64,
    /// The segment parameter or the time.
    pub t: f64,
    /// Each barycentric coordinate.
    pub barycentric: f64,
    /// Each velocity component.
    pub velocity: f64,
    /// The band around a decision boundary inside which a classification
    /// difference is borderline, a length.
    pub margin: f64,
}

/// The allowances of one case's answer for one engine: the verdict's, the
/// conditioning and the floor alone (an error within it is 0 ulps), and one
/// ulp of each field's magnitude (the fixed part alone, every entry `ε`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Allowances {
    /// What each field may be off by.
    pub verdict: Allowed,
    /// What conditioning and the floor allow.
    pub conditioned: Allowed,
    /// One ulp of each field's magnitude.
    pub one: Allowed,
}

impl Allowances {
    /// The allowances of the case `lc`'s answer, from the referee's `truth`
    /// and the case's sizes `l`.
    pub fn of(lc: &LoadedCase, truth: &Answer, tol: &Tolerance, l: &Local) -> Self {
        Allowances {
            verdict: allowed_from(lc, truth, tol, l, Parts::ALL),
            conditioned: allowed_from(lc, truth, &tol.fixed(0.0), l, Parts::ALL),
            one: allowed_from(lc, truth, &tol.fixed(tol.eps), l, Parts::FIXED),
        }
    }
}

/// Which parts of an allowance to add up: the fixed part (`tol`'s relative,
/// angle and unitless entries times each field's magnitude), the
/// conditioning part (`K · ε` times each field's condition, and a time of
/// impact's conditioning), and the precision's floor. A verdict counts all
/// three ([`Parts::ALL`]); the accuracy in ulps
/// ([`Errors::ulps`]) divides what exceeds the conditioning and the floor by
/// one ulp of the magnitude (the fixed part alone, with every entry `ε`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Parts {
    condition: bool,
    floor: bool,
}

impl Parts {
    const ALL: Parts = Parts { condition: true, floor: true };
    const FIXED: Parts = Parts { condition: false, floor: false };
}

/// The allowance of one field: the fixed part times the size's magnitude, the
/// conditioning part (`ulps · ε`) times its condition, at least the precision's
/// floor, at most `cap` (the parts `parts` names).
fn allowance(size: super::sizes::Size, fixed: f64, ulps: f64, tol: &Tolerance, cap: f64, parts: Parts) -> f64 {
    let condition = if parts.condition { ulps * tol.eps * size.condition } else { 0.0 };
    let x = fixed * size.magnitude + condition;
    let floor = if parts.floor { tol.floor() } else { 0.0 };
    if x.is_nan() { cap } else { x.clamp(floor, cap) }
}

/// The allowances of every field of the case's answer (see [`Allowed`]), from
/// the referee's answer `truth`.
pub fn allowed(lc: &LoadedCase, truth: &Answer, tol: &Tolerance) -> Allowed {
    allowed_from(lc, truth, tol, &super::sizes::local(lc, truth), Parts::ALL)
}

/// [`allowed`] from the case's sizes `l`, already taken, counting `parts`.
fn allowed_from(lc: &LoadedCase, truth: &Answer, tol: &Tolerance, l: &Local, parts: Parts) -> Allowed {
    use super::tolerance::{BARY_CONDITION_ULPS, LENGTH_CONDITION_ULPS, NORMAL_CONDITION_ULPS};
    let big = f64::MAX;
    let floor = if parts.floor { tol.floor() } else { 0.0 };
    let f = |size, fixed, ulps, cap| allowance(size, fixed, ulps, tol, cap, parts);
    let mut a = Allowed {
        point: f(l.point, tol.rel, LENGTH_CONDITION_ULPS, big),
        depth: f(l.depth, tol.rel, LENGTH_CONDITION_ULPS, big),
        normal: f(l.normal, tol.normal_rad, NORMAL_CONDITION_ULPS, std::f64::consts::PI),
        // A segment parameter lies in [0, 1]: an allowance of 1 already admits
        // every value (a time's is capped by t_max below).
        t: f(l.t, tol.unitless, LENGTH_CONDITION_ULPS, 1.0),
        barycentric: f(l.barycentric, tol.unitless, BARY_CONDITION_ULPS, big),
        velocity: f(l.velocity, tol.rel, LENGTH_CONDITION_ULPS, big),
        margin: f(l.margin, tol.rel, LENGTH_CONDITION_ULPS, big),
    };
    if let (Answer::Toi(w), Some(b)) = (truth, lc.case.b.as_ref())
        && let Some(wt) = &w.toi
    {
        let extra =
            if parts.condition { toi_allowance(lc, wt, b, tol, l.point.magnitude) } else { ToiAllowance::default() };
        // A time is judged relative to the interval: t_max plays the
        // scene's scale for the time axis.
        let t_max = lc.case.t_max();
        a.t = (tol.rel * t_max + extra.t).clamp(floor, t_max.max(floor));
        a.point = (a.point + extra.point).clamp(floor, big);
        a.normal = (a.normal + extra.normal).clamp(floor, std::f64::consts::PI);
    }
    if let Answer::Ccd(_) = truth {
        // A ccd time lies in [0, t_max]: t_max already admits every value.
        let t_max = lc.case.t_max();
        a.t = a.t.min(t_max.max(floor));
    }
    a
}

/// An error in units of the engine's ulp at the field's magnitude, beyond
/// what conditioning and the floor allow: `(err − conditioned) / one`, 0 when
/// the error is within `conditioned`, `∞` when the field has no magnitude to
/// measure an ulp of.
pub fn ulps_of(err: f64, conditioned: f64, one: f64) -> f64 {
    if err <= conditioned {
        0.0
    } else if one > 0.0 {
        ((err - conditioned) / one).min(f64::MAX)
    } else {
        f64::INFINITY
    }
}

/// What a time of impact's conditioning adds to the allowances of its time,
/// point and normal (see `tolerance::TIME_CONDITION_ULPS`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct ToiAllowance {
    t: f64,
    point: f64,
    normal: f64,
}

/// The conditioning allowance of a time of impact, from the referee's answer
/// `w`, the case's motion and `reach`, the sizes at the impact (the local
/// scale of [`super::sizes`]: the sphere's centre and radius, `b`'s own size
/// at the impact point, the point, and how far both move until then).
///
/// Perturbing the inputs by `δ = TIME_CONDITION_ULPS · ε · reach` (what any
/// method in the engine's precision commits in the distance it tests) moves the
/// first touch by `δ / closing`, `closing = −v_rel · n` the speed at which the
/// gap closes at the impact (`n` the referee's normal, `v_rel = va − vb`). A
/// near-parallel approach or a grazing pass makes `closing` small; where the
/// surfaces are curved (radius of curvature `R`: the sum of the radii for two
/// spheres, the sphere's radius against a triangle's edge or vertex or a mesh)
/// the shift is also at most `√(2 R δ)/‖v_rel‖`, the time a path at distance
/// `δ` inside the grazing one spends closer than it. The smaller of the two is
/// the time's allowance; a plane has no curvature (the first only).
///
/// The point then moves by the speeds of both shapes and of the motion
/// between them over that time, plus `δ`; the normal turns by the relative
/// displacement over the distance `R_n` between the points it joins (the sum of
/// the radii, or the sphere's radius; a plane's normal is an input and does
/// not turn). Shapes in contact at `t = 0` answer a static contact at `t = 0`
/// exactly; their normal gets the same `δ / R_n` as
/// `tolerance::NORMAL_CONDITION_ULPS` gives a static contact. Every norm is
/// scaled before it squares and every product of a speed and a time skips a
/// zero factor, so no allowance is NaN for any finite input.
fn toi_allowance(lc: &LoadedCase, w: &oracle::geom::Toi, b: &Shape, tol: &Tolerance, reach: f64) -> ToiAllowance {
    use super::sizes::norm;
    let va = lc.case.a.velocity();
    let vb = b.velocity();
    // The relative velocity, halved where its difference would overflow (and
    // its norm doubled back).
    let (v, k) = super::sizes::diff(&va, &vb);
    let speed = norm(&v) * k;
    let closing = -(v[0] * w.normal[0] + v[1] * w.normal[1] + v[2] * w.normal[2]) * k;
    // `δ` itself underflows for a reach near the subnormals (64 ε · 1e-313 is
    // below the smallest f64): every quotient by a speed or a length is
    // formed from `reach` first, then multiplied by `64 ε`.
    let c_eps = super::tolerance::TIME_CONDITION_ULPS * tol.eps;
    let delta = c_eps * reach;
    let radius = |s: &Shape| if let Shape::Sphere(s) = s { s.radius } else { 0.0 };
    let ra = radius(&lc.case.a);
    // (radius of curvature, distance the normal spans)
    let (curvature, span) = match b {
        Shape::Sphere(b) => (ra + b.radius, ra + b.radius),
        Shape::Plane(_) => (f64::INFINITY, f64::INFINITY),
        _ => (ra, ra),
    };
    let first = if closing > 0.0 { c_eps * (reach / closing) } else { f64::INFINITY };
    let second = if curvature.is_finite() && speed > 0.0 {
        (2.0 * curvature).sqrt() * (c_eps.sqrt() * reach.sqrt()) / speed
    } else {
        f64::INFINITY
    };
    let t = first.min(second);
    // A speed of 0 moves nothing, however long the time (no 0 · ∞).
    let moved = |speed: f64| if speed > 0.0 && t > 0.0 { speed * t } else { 0.0 };
    // A contact at t = 0 has the static contact's sizes (`super::sizes`), whose
    // conditioning covers the distance the time is decided by: only what the
    // motion adds over the time's allowance is added here.
    let at_start = w.t == 0.0;
    let point = moved(norm(&va) + norm(&vb) + 2.0 * speed) + if at_start { 0.0 } else { delta };
    let normal = if span.is_finite() {
        let still = if at_start { 0.0 } else { c_eps * (reach / span) };
        if span > 0.0 { moved(speed) / span + still } else { f64::INFINITY }
    } else {
        0.0
    };
    let finite = |x: f64| if x.is_nan() { f64::MAX } else { x.min(f64::MAX) };
    ToiAllowance { t: finite(t), point: finite(point), normal: finite(normal) }
}
