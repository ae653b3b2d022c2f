//! The verdict's second stage: what each field may be off by, from its sizes
//! ([`super::sizes`]) and the engine's tolerances ([`super::tolerance`]) —
//! the allowance of the verdict, and beside it the conditioning alone and one
//! ulp of each field's magnitude, which the accuracy in ulps is measured by.

use super::sizes::Local;
use super::tolerance::Tolerance;
use crate::case::Shape;
use crate::engine::Answer;
use crate::load::LoadedCase;
use oracle::geom::P3;
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
/// the time's allowance; a plane has no curvature (the first only). A box's
/// surface is curved only at its edges and corners (the rounded box of radius
/// `r`): on a face the first only, at an edge the second with the speed across
/// the edge alone (a path along an edge's cylinder never leaves it: a grazing
/// pass parallel to an edge has a time no perturbation pins down), at a
/// corner the whole speed (see [`box_curved_speed`]).
///
/// The point then moves by the speeds of both shapes and of the motion
/// between them over that time, plus `δ`; the normal turns by the relative
/// displacement across the curved directions (for a box, the speed of
/// [`box_curved_speed`]: a face's normal does not turn, an edge's only with
/// motion across it) over the distance `R_n` between the points it joins (the sum of
/// the radii, or the sphere's radius; a plane's normal is an input and does
/// not turn). Shapes in contact at `t = 0` answer a static contact at `t = 0`
/// exactly; their normal gets the same `δ / R_n` as
/// `tolerance::NORMAL_CONDITION_ULPS` gives a static contact. Every norm is
/// scaled before it squares and every product of a speed and a time skips a
/// zero factor, so no allowance is NaN for any finite input.
/// How close to a box's edge, relative to the box's size (the largest
/// coordinate of its centre plus its half-extents), the referee's contact
/// point counts as on it when the judge reads which feature an impact is on:
/// far above the `f64` rounding of the point taken to the box's frame (a few
/// ε of that size), so an edge or corner contact is never read as a face's.
/// Reading a face contact near an edge as the edge's is the strict side: the
/// edge's allowance is never larger than the face's.
const BOX_FEATURE_SLACK: f64 = 1.0 / (1u64 << 26) as f64;

/// The relative speed across the curved directions of box `bx`'s surface at
/// the referee's impact `w` (what makes a grazing time's second-order term;
/// `v·k` the relative velocity, `vb` the box's): the contact point, taken back
/// to time 0 and into the box's frame, lies on a face (every coordinate but
/// one inside by more than [`BOX_FEATURE_SLACK`]: no curvature, 0), an edge
/// (one coordinate inside: the speed across the edge's direction) or a
/// corner (the whole speed).
fn box_curved_speed(bx: &crate::case::BoxSpec, w: &oracle::geom::Toi, vb: &P3, v: &P3, k: f64) -> f64 {
    use super::sizes::norm;
    let rot = oracle::geom::rotation_matrix(bx.rotation.unwrap_or(crate::case::IDENTITY_ROTATION));
    let at: P3 = std::array::from_fn(|i| w.point[i] - vb[i] * w.t - bx.center[i]);
    let u: [f64; 3] = std::array::from_fn(|j| (0..3).map(|i| rot[i][j] * at[i]).sum());
    let size = bx.center.iter().fold(0.0f64, |m, x| m.max(x.abs())) + bx.half_extents.iter().sum::<f64>();
    let slack = BOX_FEATURE_SLACK * size;
    let inside: Vec<usize> = (0..3).filter(|&j| bx.half_extents[j] - u[j].abs() > slack).collect();
    match inside.as_slice() {
        [_, _, ..] => 0.0,
        [j] => {
            // The edge runs along axis j: the speed without its component there.
            let e: P3 = [rot[0][*j], rot[1][*j], rot[2][*j]];
            let along = v[0] * e[0] + v[1] * e[1] + v[2] * e[2];
            norm(&[v[0] - along * e[0], v[1] - along * e[1], v[2] - along * e[2]]) * k
        }
        [] => norm(v) * k,
    }
}

/// `x·2^e` in two exact steps (one alone overflows for `|e|` past 1023).
fn times_pow2(x: f64, e: i32) -> f64 {
    x * 2f64.powi(e / 2) * 2f64.powi(e - e / 2)
}

/// The most steps of the searches of [`box_time_window`]: each halves (or
/// cuts by a third) an interval of `f64` times, and 2,200 such steps take any
/// interval in `[0, f64::MAX]` down to adjacent doubles (2,098 binades of
/// doubles, 52 bits each way). A search stops as soon as its interval no
/// longer shrinks, which ordinary intervals reach in about 60.
const WINDOW_STEPS: u32 = 2200;

/// The time allowance of a sphere's impact on a box, from the window around
/// the referee's time `t*` in which the path is within `δ` of touching: the
/// distance `D(t)` from the centre to the box (convex in `t`: a moving point
/// and a convex set), taken in `f64` in the box's frame on the scene scaled
/// by a power of two, is at most `r + δ` from `t₁` on; a perturbation of the
/// inputs by `δ` can move the first touch as early as `t₁`, and as late as the
/// first time `D ≤ r − δ` (where the path sinks that far), or, where it never
/// does, the last time `D ≤ r + δ`. The allowance is the larger side. On a
/// face hit this is `δ/closing` either side; on a path that glides along an
/// edge or a face within `δ` of touching it is the whole glide (no
/// perturbation pins the touch down). `None` (the caller's estimate stands)
/// when the scaled motion leaves `f64`'s range or the referee's time is not
/// where `D = r` in `f64`.
fn box_time_window(
    lc: &LoadedCase,
    bx: &crate::case::BoxSpec,
    w: &oracle::geom::Toi,
    v: &P3,
    k: f64,
    delta: f64,
) -> Option<f64> {
    let Shape::Sphere(a) = &lc.case.a else { return None };
    let big = [a.radius, delta]
        .into_iter()
        .chain(a.center.iter().chain(&bx.center).chain(&bx.half_extents).map(|x| x.abs()))
        .fold(0.0f64, f64::max);
    if !(big > 0.0 && big.is_finite()) {
        return None;
    }
    let e = -(big.log2().floor() as i32);
    let sc = |x: f64| times_pow2(x, e);
    let rot = oracle::geom::rotation_matrix(bx.rotation.unwrap_or(crate::case::IDENTITY_ROTATION));
    let rel: P3 = std::array::from_fn(|i| sc(a.center[i]) - sc(bx.center[i]));
    let vel: P3 = std::array::from_fn(|i| times_pow2(v[i] * k, e));
    let local = |p: &P3| -> P3 { std::array::from_fn(|j| (0..3).map(|i| rot[i][j] * p[i]).sum()) };
    let (u0, wl) = (local(&rel), local(&vel));
    let h = bx.half_extents.map(sc);
    let (r, d) = (sc(a.radius), sc(delta));
    if !u0.iter().chain(&wl).chain(&h).all(|x| x.is_finite()) {
        return None;
    }
    let dist = |t: f64| -> f64 {
        let u: P3 = std::array::from_fn(|j| if t > 0.0 { u0[j] + t * wl[j] } else { u0[j] });
        let g: P3 = std::array::from_fn(|j| u[j] - u[j].clamp(-h[j], h[j]));
        super::sizes::norm(&g)
    };
    // The first time in [lo, hi] at which `near(D)` holds, `near(D(hi))` true.
    let first_near = |lo: f64, hi: f64, near: &dyn Fn(f64) -> bool| -> f64 {
        let (mut lo, mut hi) = (lo, hi);
        if near(dist(lo)) {
            return lo;
        }
        for _ in 0..WINDOW_STEPS {
            let mid = lo + (hi - lo) / 2.0;
            if mid <= lo || mid >= hi {
                break;
            }
            if near(dist(mid)) { hi = mid } else { lo = mid }
        }
        hi
    };
    let (ts, t_max) = (w.t, lc.case.t_max().max(w.t));
    if !(dist(ts) <= r + d) {
        return None;
    }
    let early = ts - first_near(0.0, ts, &|x| x <= r + d);
    // The least D on [t*, t_max] (convex: a ternary search).
    let (mut lo, mut hi) = (ts, t_max);
    for _ in 0..WINDOW_STEPS {
        let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if !(m1 > lo && m2 < hi) {
            break;
        }
        if dist(m1) <= dist(m2) { hi = m2 } else { lo = m1 }
    }
    let tm = lo;
    let late = if dist(tm) <= r - d {
        first_near(ts, tm, &|x| x <= r - d) - ts
    } else if dist(t_max) <= r + d {
        t_max - ts
    } else {
        // The last time within r + δ: the first past tm at which D exceeds it.
        first_near(tm, t_max, &|x| x > r + d) - ts
    };
    let out = early.max(late);
    out.is_finite().then_some(out)
}

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
    let curved = match b {
        Shape::Box(bx) => box_curved_speed(bx, w, &vb, &v, k),
        _ => speed,
    };
    let second = if curvature.is_finite() && curved > 0.0 {
        (2.0 * curvature).sqrt() * (c_eps.sqrt() * reach.sqrt()) / curved
    } else {
        f64::INFINITY
    };
    let t = match b {
        Shape::Box(bx) if w.t > 0.0 => box_time_window(lc, bx, w, &v, k, delta).unwrap_or(first.min(second)),
        _ => first.min(second),
    };
    // A speed of 0 moves nothing, however long the time (no 0 · ∞).
    let moved = |speed: f64| if speed > 0.0 && t > 0.0 { speed * t } else { 0.0 };
    // A contact at t = 0 has the static contact's sizes (`super::sizes`), whose
    // conditioning covers the distance the time is decided by: only what the
    // motion adds over the time's allowance is added here.
    let at_start = w.t == 0.0;
    let point = moved(norm(&va) + norm(&vb) + 2.0 * speed) + if at_start { 0.0 } else { delta };
    let normal = if span.is_finite() {
        let still = if at_start { 0.0 } else { c_eps * (reach / span) };
        if span > 0.0 { moved(curved) / span + still } else { f64::INFINITY }
    } else {
        0.0
    };
    let finite = |x: f64| if x.is_nan() { f64::MAX } else { x.min(f64::MAX) };
    ToiAllowance { t: finite(t), point: finite(point), normal: finite(normal) }
}
