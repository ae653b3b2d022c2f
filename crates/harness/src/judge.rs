//! Judging answers: against a case's expectation (the fixture's `expect`, with its
//! absolute `tol`) and against the referee (the tolerance table applied to the
//! problem's own scale, [`crate::local`], with borderline cases and known
//! divergences kept apart).

use crate::case::{Case, Expect, Shape};
use crate::engine::Answer;
use crate::load::{LoadedCase, bounded_points};
use crate::tolerance::Tolerance;
use oracle::geom::P3;
use serde::Serialize;

/// One field of an answer that does not meet the expectation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Mismatch {
    /// The expectation's field: `contact.depth`, `hit`, `parallel`, …
    pub field: String,
    /// What the fixture expects.
    pub expected: String,
    /// What the engine answered.
    pub got: String,
}

fn mm(field: &str, expected: impl std::fmt::Debug, got: impl std::fmt::Debug) -> Mismatch {
    Mismatch { field: field.into(), expected: format!("{expected:?}"), got: format!("{got:?}") }
}

fn dist3(a: &P3, b: &P3) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

fn cmp3(out: &mut Vec<Mismatch>, field: &str, want: &P3, got: &P3, tol: f64) {
    if !(dist3(want, got) <= tol) {
        out.push(mm(field, want, got));
    }
}

fn cmp1(out: &mut Vec<Mismatch>, field: &str, want: f64, got: f64, tol: f64) {
    if !((want - got).abs() <= tol) {
        out.push(mm(field, want, got));
    }
}

/// Whether an answer carries the degenerate flag.
pub fn degenerate(answer: &Answer) -> bool {
    match answer {
        Answer::Contact(a) => a.degenerate,
        Answer::Intersect(a) => a.degenerate,
        Answer::Barycentric(a) => a.degenerate,
        Answer::Toi(a) => a.degenerate,
        Answer::Response(a) => a.degenerate,
        Answer::Bounds(_) | Answer::Overlap(_) => false,
    }
}

/// Compares an answer with the case's `expect`, every scalar within the case's
/// absolute `tol`. Only what `expect` names is compared. An empty list is a pass.
pub fn check_expect(lc: &LoadedCase, answer: &Answer) -> Vec<Mismatch> {
    let case: &Case = &lc.case;
    let Some(e): Option<&Expect> = case.expect.as_ref() else { return Vec::new() };
    let tol = case.tol();
    let mut out = Vec::new();
    if let Some(want) = e.degenerate {
        let got = degenerate(answer);
        if want != got {
            out.push(mm("degenerate", want, got));
        }
    }
    match answer {
        Answer::Contact(a) => {
            if let Some(want) = &e.contact {
                match (want, &a.contact) {
                    (None, None) => {}
                    (Some(w), Some(g)) => {
                        cmp3(&mut out, "contact.point", &w.point, &g.point, tol);
                        cmp3(&mut out, "contact.normal", &w.normal, &g.normal, tol);
                        unit_expect(&mut out, "contact.normal", &g.normal, tol);
                        cmp1(&mut out, "contact.depth", w.depth, g.depth, tol);
                    }
                    (w, g) => out.push(mm("contact", w, g)),
                }
            }
        }
        Answer::Intersect(a) => {
            if let Some(want) = &e.hit {
                match (want, &a.hit) {
                    (None, None) => {}
                    (Some(w), Some(g)) => {
                        cmp1(&mut out, "hit.t", w.t, g.t, tol);
                        cmp3(&mut out, "hit.point", &w.point, &g.point, tol);
                        cmp3(&mut out, "hit.normal", &w.normal, &g.normal, tol);
                        unit_expect(&mut out, "hit.normal", &g.normal, tol);
                        if let Some(wb) = &w.barycentric {
                            match &g.barycentric {
                                Some(gb) => cmp3(&mut out, "hit.barycentric", wb, gb, tol),
                                None => out.push(mm("hit.barycentric", wb, "none")),
                            }
                        }
                        if let Some(wt) = w.triangle
                            && g.triangle != Some(wt)
                        {
                            out.push(mm("hit.triangle", wt, g.triangle));
                        }
                    }
                    (w, g) => out.push(mm("hit", w, g)),
                }
            }
            if let Some(want) = e.parallel
                && want != a.parallel
            {
                out.push(mm("parallel", want, a.parallel));
            }
        }
        Answer::Barycentric(a) => {
            if let Some(w) = &e.barycentric {
                cmp3(&mut out, "barycentric", w, &a.coords, tol);
            }
        }
        Answer::Bounds(a) => {
            if let Some(w) = &e.aabb {
                match &a.aabb {
                    Some(g) => {
                        cmp3(&mut out, "aabb.min", &w.min, &g.min, tol);
                        cmp3(&mut out, "aabb.max", &w.max, &g.max, tol);
                    }
                    None => out.push(mm("aabb", w, "none")),
                }
            }
            if let Some(r) = e.min_radius {
                match &a.sphere {
                    Some(s) => {
                        cmp1(&mut out, "min_radius", r, s.radius, tol);
                        let pts = bounded_points(lc);
                        if let Some((i, d)) = farthest_outside(&s.center, s.radius, pts, tol) {
                            out.push(mm(
                                "min_radius (encloses every point)",
                                format!("point {i} inside"),
                                format!("{d:e} outside"),
                            ));
                        }
                    }
                    None => out.push(mm("min_radius", r, "no sphere")),
                }
            }
        }
        Answer::Overlap(g) => {
            if let Some(w) = e.overlap
                && w != *g
            {
                out.push(mm("overlap", w, g));
            }
        }
        Answer::Toi(a) => {
            if let Some(want) = &e.toi {
                match (want, &a.toi) {
                    (None, None) => {}
                    (Some(w), Some(g)) => {
                        cmp1(&mut out, "toi.t", w.t, g.t, tol);
                        cmp3(&mut out, "toi.point", &w.point, &g.point, tol);
                        cmp3(&mut out, "toi.normal", &w.normal, &g.normal, tol);
                        unit_expect(&mut out, "toi.normal", &g.normal, tol);
                    }
                    (w, g) => out.push(mm("toi", w, g)),
                }
            }
        }
        Answer::Response(a) => {
            if let Some(w) = &e.velocity_a {
                cmp3(&mut out, "velocity_a", w, &a.velocity_a, tol);
            }
            if let Some(w) = &e.velocity_b {
                cmp3(&mut out, "velocity_b", w, &a.velocity_b, tol);
            }
        }
    }
    out
}

/// An expected normal is unit: the engine's must be too, its length within
/// the case's `tol` of 1 (a normal within `tol` of the expected one in every
/// coordinate may still be up to `√3·tol` longer).
fn unit_expect(out: &mut Vec<Mismatch>, field: &str, got: &P3, tol: f64) {
    let x = unit_excess(got);
    if !(x.abs() <= tol) {
        out.push(mm(&format!("{field} (unit length)"), 1.0, 1.0 + x));
    }
}

/// The first point farther than `radius + tol` from `center`, with its excess.
fn farthest_outside(center: &P3, radius: f64, pts: &[P3], tol: f64) -> Option<(usize, f64)> {
    pts.iter().enumerate().find_map(|(i, p)| {
        // Scaled: the distance of points 1e160 apart does not overflow.
        let d = crate::local::distance(p, center);
        (!(d <= radius + tol)).then_some((i, d - radius))
    })
}

/// The scene's scale: the largest magnitude among the case's coordinates, radii and
/// plane offsets (offsets in units of the normal's length), or 1 for an empty or
/// all-zero scene. Errors of lengths are divided by it.
pub fn scene_scale(lc: &LoadedCase) -> f64 {
    let mut m: f64 = 0.0;
    let mut p3 = |p: &P3| m = p.iter().fold(m, |m, x| m.max(x.abs()));
    let mut scalars = Vec::new();
    for (slot, shape) in [Some(&lc.case.a), lc.case.b.as_ref()].into_iter().enumerate() {
        match shape {
            Some(Shape::Sphere(s)) => {
                p3(&s.center);
                scalars.push(s.radius);
            }
            Some(Shape::Plane(p)) => {
                let n = p.normal.iter().map(|x| x * x).sum::<f64>().sqrt();
                if n > 0.0 && n.is_finite() {
                    scalars.push(p.offset / n);
                }
            }
            Some(Shape::Segment(s)) => {
                p3(&s.start);
                p3(&s.end);
            }
            Some(Shape::Triangle(t)) => t.vertices.iter().for_each(&mut p3),
            Some(Shape::Point(p)) => p3(&p.at),
            Some(Shape::Points(p)) => p.points.iter().for_each(&mut p3),
            Some(Shape::Mesh(_)) => {
                if let Some(mesh) = &lc.meshes[slot] {
                    mesh.vertices.iter().for_each(&mut p3);
                }
            }
            Some(Shape::Aabb(b)) => {
                p3(&b.min);
                p3(&b.max);
            }
            None => {}
        }
    }
    let m = scalars.iter().fold(m, |m, x| m.max(x.abs()));
    if m > 0.0 && m.is_finite() { m } else { 1.0 }
}

/// Errors of an answer against the referee's, each `None` where not applicable.
/// Lengths are absolute here; divide by [`scene_scale`] for relative ones.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Errors {
    /// Largest coordinate error of the contact or hit point (or bounding centre).
    pub point: Option<f64>,
    /// Depth error (contact) or radius error (bounds).
    pub depth: Option<f64>,
    /// Angle between the normals, radians.
    pub normal: Option<f64>,
    /// How far the engine's normal's length is from 1 (`|‖n‖ − 1|`, unitless).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_length: Option<f64>,
    /// Error of the segment parameter `t`.
    pub t: Option<f64>,
    /// Largest barycentric coordinate error.
    pub barycentric: Option<f64>,
    /// Largest velocity component error (response), relative to the largest
    /// input speed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<f64>,
    /// The answer's accuracy in ulps: over its numeric fields, the largest
    /// error beyond what the field's conditioning and the precision's floor
    /// allow, in units of the engine's `ε` times the field's magnitude (the
    /// sizes of [`crate::local`]); for a contact, hit, impact or overlap
    /// found or missed against the referee, the referee's margin from the
    /// decision boundary measured the same way. So the answer is within
    /// `--ulps N` (the fixed allowance `N · ε` of the magnitude: agreement,
    /// or a borderline classification) when this is at most `N`. A normal's
    /// length counts as `|‖n‖ − 1| / ε`. Absent when nothing was measured
    /// (a classification without a margin, such as a mesh's hit).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ulps: Option<f64>,
    /// The classification differs from the referee's, and how.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub misclass: Option<Misclass>,
}

/// How a classification differs from the referee's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Misclass {
    /// A contact, hit or overlap the referee does not have.
    FalsePositive,
    /// A contact, hit or overlap the referee has, missed (or a bounding sphere
    /// that misses a point).
    FalseNegative,
    /// Only a flag differs: `parallel` or `degenerate`.
    Flag,
}

/// A verdict on one engine's answer to one case, against the referee.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "verdict", rename_all = "snake_case")]
pub enum Verdict {
    /// Same classification, every error within tolerance.
    Agree,
    /// Beyond tolerance; each reason names the field and the sizes.
    Disagree {
        /// What differs.
        reasons: Vec<String>,
    },
    /// A classification differs, but the referee's margin is inside the tolerance
    /// band: counted apart, neither agreement nor disagreement.
    Borderline {
        /// What differs.
        reasons: Vec<String>,
    },
    /// A documented convention of the engine, not an error.
    KnownDivergence {
        /// The documented reason.
        reason: String,
    },
    /// The engine does not answer this case.
    Unsupported {
        /// Why.
        reason: String,
    },
    /// The engine panicked or returned a non-finite number.
    Failed {
        /// What happened.
        reason: String,
    },
}

impl Verdict {
    /// A short label for tables.
    pub fn label(&self) -> &'static str {
        match self {
            Verdict::Agree => "agree",
            Verdict::Disagree { .. } => "DISAGREE",
            Verdict::Borderline { .. } => "borderline",
            Verdict::KnownDivergence { .. } => "known",
            Verdict::Unsupported { .. } => "unsupported",
            Verdict::Failed { .. } => "FAILED",
        }
    }
}

/// The angle between two directions, radians: `atan2(‖a × b‖, a · b)`, accurate
/// for small and large angles alike, each vector scaled by its largest
/// coordinate first (so a normal of length 1e-200 or 1e200 is a direction like
/// any other). A zero vector is no direction: π from everything, never an
/// agreement.
pub fn angle(a: &P3, b: &P3) -> f64 {
    let (ma, mb) = (crashtest_core::vec3::max_abs(*a), crashtest_core::vec3::max_abs(*b));
    if !(ma > 0.0 && mb > 0.0 && ma.is_finite() && mb.is_finite()) {
        return std::f64::consts::PI;
    }
    let (a, b) = (&a.map(|x| x / ma), &b.map(|x| x / mb));
    let c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let s = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    s.atan2(d)
}

/// A normal that is the zero vector is no direction: whatever the normal's
/// allowance (π where the referee's own normal is a fallback, as for
/// concentric spheres), an engine's zero normal beside the referee's unit one
/// is a disagreement, never an agreement by the angle `angle` gives it.
fn no_direction(got: &P3, want: &P3, value: &mut Vec<String>) {
    let zero = |p: &P3| p.iter().all(|x| *x == 0.0);
    if zero(got) && !zero(want) {
        value.push("normal is the zero vector (no direction)".into());
    }
}

/// `‖n‖ − 1` for a normal `n`, to within a few units of `ε²` where the
/// length is near 1: the squares and their sum are carried in two words (each
/// square split exactly by a fused multiply-add), so the judge's own rounding
/// (an ulp or two of a plain `sqrt(x² + y² + z²)`) never decides a verdict at
/// [`crate::tolerance::NORMAL_LENGTH_ULPS`]. A normal whose largest coordinate is outside
/// `[2⁻⁴, 2]` is far from unit whatever its other coordinates: its length is
/// taken by the scaled norm, which cannot overflow.
pub fn unit_excess(n: &P3) -> f64 {
    let m = crashtest_core::vec3::max_abs(*n);
    if !(0.0625..=2.0).contains(&m) {
        return crate::local::norm(n) - 1.0;
    }
    // (hi, lo): the running sum x² + y² + z² − 1, exact but for the final
    // rounding of `lo`.
    let two_sum = |a: f64, b: f64| {
        let s = a + b;
        let bb = s - a;
        (s, (a - (s - bb)) + (b - bb))
    };
    let (mut hi, mut lo) = (-1.0, 0.0);
    for x in n {
        let p = x * x;
        let e = x.mul_add(*x, -p);
        let (s, err) = two_sum(hi, p);
        hi = s;
        lo += err + e;
    }
    let ss_minus_1 = hi + lo;
    // ‖n‖ − 1 = (‖n‖² − 1)/(‖n‖ + 1); the denominator needs no precision.
    ss_minus_1 / ((ss_minus_1 + 1.0).max(0.0).sqrt() + 1.0)
}

/// A normal whose length is not 1 within `tol.normal_length_ulps` (by
/// default [`crate::tolerance::NORMAL_LENGTH_ULPS`]) of the
/// engine's `ε`: its reason, with the length and its distance from 1 in ulps.
/// The zero vector has its own reason ([`no_direction`]) and is not repeated
/// here.
fn not_unit(got: &P3, tol: &Tolerance, excess: f64, value: &mut Vec<String>) {
    if got.iter().all(|x| *x == 0.0) {
        return;
    }
    let allowed = tol.normal_length_ulps * tol.eps;
    if !(excess.abs() <= allowed) {
        // The length itself (scaled: 1 + excess rounds a subnormal length to 0).
        let len = crate::local::norm(got);
        value.push(format!(
            "normal not unit: length {len} ({:.3e} ulps from 1, allowed {})",
            excess.abs() / tol.eps,
            tol.normal_length_ulps
        ));
    }
}

/// Whether every number of an answer is finite. The referee's answer to a case
/// whose exact answer lies beyond `f64`'s range is not (its rounding is ±∞):
/// such a case is refused as out of range, and no engine is graded on it.
pub fn all_finite(answer: &Answer) -> bool {
    let f3 = |p: &P3| p.iter().all(|x| x.is_finite());
    match answer {
        Answer::Contact(a) => a.contact.is_none_or(|c| f3(&c.point) && f3(&c.normal) && c.depth.is_finite()),
        Answer::Intersect(a) => a
            .hit
            .is_none_or(|h| h.t.is_finite() && f3(&h.point) && f3(&h.normal) && h.barycentric.is_none_or(|b| f3(&b))),
        Answer::Barycentric(a) => f3(&a.coords),
        Answer::Bounds(a) => {
            a.aabb.is_none_or(|b| f3(&b.min) && f3(&b.max))
                && a.sphere.is_none_or(|s| f3(&s.center) && s.radius.is_finite())
        }
        Answer::Overlap(_) => true,
        Answer::Toi(a) => a.toi.is_none_or(|t| t.t.is_finite() && f3(&t.point) && f3(&t.normal)),
        Answer::Response(a) => f3(&a.velocity_a) && f3(&a.velocity_b),
    }
}

/// The reason of a `Failed` verdict on an answer holding NaN or an infinity
/// (the referee's answer is finite: see [`all_finite`]); counted apart in
/// reports.
pub const NON_FINITE: &str = "non-finite number in the answer";

/// What each field of one case's answer is allowed to be off by, for one
/// engine: from the sizes that decide the field ([`crate::local`]) and the
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
fn allowance(size: crate::local::Size, fixed: f64, ulps: f64, tol: &Tolerance, cap: f64, parts: Parts) -> f64 {
    let condition = if parts.condition { ulps * tol.eps * size.condition } else { 0.0 };
    let x = fixed * size.magnitude + condition;
    let floor = if parts.floor { tol.floor() } else { 0.0 };
    if x.is_nan() { cap } else { x.clamp(floor, cap) }
}

/// The allowances of every field of the case's answer (see [`Allowed`]), from
/// the referee's answer `truth`.
pub fn allowed(lc: &LoadedCase, truth: &Answer, tol: &Tolerance) -> Allowed {
    allowed_from(lc, truth, tol, &crate::local::local(lc, truth), Parts::ALL)
}

/// [`allowed`] from the case's sizes `l`, already taken, counting `parts`.
fn allowed_from(lc: &LoadedCase, truth: &Answer, tol: &Tolerance, l: &crate::local::Local, parts: Parts) -> Allowed {
    use crate::tolerance::{BARY_CONDITION_ULPS, LENGTH_CONDITION_ULPS, NORMAL_CONDITION_ULPS};
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
    a
}

/// An error in units of the engine's ulp at the field's magnitude, beyond
/// what conditioning and the floor allow: `(err − conditioned) / one`, 0 when
/// the error is within `conditioned`, `∞` when the field has no magnitude to
/// measure an ulp of.
fn ulps_of(err: f64, conditioned: f64, one: f64) -> f64 {
    if err <= conditioned {
        0.0
    } else if one > 0.0 {
        ((err - conditioned) / one).min(f64::MAX)
    } else {
        f64::INFINITY
    }
}

/// The length scale of a case's answer, for relative errors in reports: the
/// magnitude of the sizes its point, depth and margin are judged by (at least
/// the smallest positive number, never 0).
pub fn answer_scale(lc: &LoadedCase, truth: &Answer) -> f64 {
    let l = crate::local::local(lc, truth);
    let m = l.point.magnitude.max(l.depth.magnitude).max(l.margin.magnitude).max(l.velocity.magnitude);
    if m > 0.0 && m.is_finite() {
        m
    } else if m > 0.0 {
        f64::MAX
    } else {
        scene_scale(lc)
    }
}

/// Judges `answer` against the referee's `truth` for the case `lc`, with the
/// tolerances `tol`. `margin` is the referee's signed distance of the case from
/// its nearest decision boundary, a length; a classification difference
/// within the allowance band of the boundary ([`Allowed::margin`]) is
/// borderline.
///
/// Every allowance comes from the problem's own scale ([`allowed`]): a wrong
/// answer is a disagreement at every magnitude, however large the rest of the
/// scene.
pub fn judge(
    lc: &LoadedCase,
    answer: &Answer,
    truth: &Answer,
    tol: &Tolerance,
    margin: Option<f64>,
) -> (Verdict, Errors) {
    let mut e = Errors::default();
    if !all_finite(answer) {
        return (Verdict::Failed { reason: NON_FINITE.into() }, e);
    }
    let sizes = crate::local::local(lc, truth);
    let allow = allowed_from(lc, truth, tol, &sizes, Parts::ALL);
    // The accuracy in ulps: what exceeds the conditioning and the floor, over
    // one ulp of each field's magnitude.
    let conditioned = allowed_from(lc, truth, &tol.fixed(0.0), &sizes, Parts::ALL);
    let one = allowed_from(lc, truth, &tol.fixed(tol.eps), &sizes, Parts::FIXED);
    let ulps = std::cell::Cell::new(None::<f64>);
    let count = |u: f64| ulps.set(Some(ulps.get().map_or(u, |x: f64| x.max(u))));
    let mut class = Vec::new();
    let mut value = Vec::new();
    let over = |what: &str, err: f64, field: fn(&Allowed) -> f64, unit: &str, value: &mut Vec<String>| {
        let allowed = field(&allow);
        if !(err <= allowed) {
            value.push(format!("{what} off by {err:.3e}{unit} (allowed {allowed:.1e})"));
        }
        count(ulps_of(err, field(&conditioned), field(&one)));
    };
    // A normal's length: `‖n‖ − 1`, kept as an error and judged against
    // `NORMAL_LENGTH_ULPS` ulps of the engine's precision.
    let unit = |n: &P3, e: &mut Errors, value: &mut Vec<String>| {
        let x = unit_excess(n);
        e.normal_length = Some(x.abs());
        not_unit(n, tol, x, value);
        count(x.abs() / tol.eps);
    };
    if degenerate(answer) != degenerate(truth) {
        class.push(format!("degenerate: {} (referee {})", degenerate(answer), degenerate(truth)));
        e.misclass = Some(Misclass::Flag);
    }
    let fp = |e: &mut Errors| e.misclass = Some(Misclass::FalsePositive);
    let fneg = |e: &mut Errors| e.misclass = Some(Misclass::FalseNegative);
    match (answer, truth) {
        (Answer::Contact(g), Answer::Contact(w)) => match (&g.contact, &w.contact) {
            (Some(gc), Some(wc)) => {
                let dp = dist3(&gc.point, &wc.point);
                e.point = Some(dp);
                over("point", dp, |a| a.point, "", &mut value);
                let dd = (gc.depth - wc.depth).abs();
                e.depth = Some(dd);
                over("depth", dd, |a| a.depth, "", &mut value);
                let a = angle(&gc.normal, &wc.normal);
                no_direction(&gc.normal, &wc.normal, &mut value);
                e.normal = Some(a);
                over("normal", a, |a| a.normal, " rad", &mut value);
                unit(&gc.normal, &mut e, &mut value);
            }
            (None, None) => {}
            (Some(_), None) => {
                class.push("false contact (referee: apart)".into());
                fp(&mut e);
            }
            (None, Some(_)) => {
                class.push("missed contact (referee: touching)".into());
                fneg(&mut e);
            }
        },
        (Answer::Intersect(g), Answer::Intersect(w)) => {
            if g.parallel != w.parallel {
                class.push(format!("parallel: {} (referee {})", g.parallel, w.parallel));
                e.misclass = Some(Misclass::Flag);
            }
            match (&g.hit, &w.hit) {
                (Some(gh), Some(wh)) => {
                    let dp = dist3(&gh.point, &wh.point);
                    e.point = Some(dp);
                    over("hit point", dp, |a| a.point, "", &mut value);
                    let dt = (gh.t - wh.t).abs();
                    e.t = Some(dt);
                    over("t", dt, |a| a.t, "", &mut value);
                    let a = angle(&gh.normal, &wh.normal);
                    no_direction(&gh.normal, &wh.normal, &mut value);
                    e.normal = Some(a);
                    over("normal", a, |a| a.normal, " rad", &mut value);
                    unit(&gh.normal, &mut e, &mut value);
                    if let (Some(gb), Some(wb)) = (&gh.barycentric, &wh.barycentric) {
                        let err = dist3(gb, wb);
                        e.barycentric = Some(err);
                        over("barycentric", err, |a| a.barycentric, "", &mut value);
                    }
                }
                (None, None) => {}
                (Some(_), None) => {
                    class.push("false hit (referee: miss)".into());
                    fp(&mut e);
                }
                (None, Some(_)) => {
                    class.push("missed hit (referee: hit)".into());
                    fneg(&mut e);
                }
            }
        }
        (Answer::Barycentric(g), Answer::Barycentric(w)) => {
            let err = dist3(&g.coords, &w.coords);
            e.barycentric = Some(err);
            over("barycentric", err, |a| a.barycentric, "", &mut value);
        }
        (Answer::Bounds(g), Answer::Bounds(w)) => {
            if let (Some(gb), Some(wb)) = (&g.aabb, &w.aabb) {
                // Each coordinate of the box by its own size: the box is exact,
                // and an engine that rounds its inputs loses ε of each.
                let err = dist3(&gb.min, &wb.min).max(dist3(&gb.max, &wb.max));
                e.point = Some(err);
                for (gp, wp) in [(&gb.min, &wb.min), (&gb.max, &wb.max)] {
                    for i in 0..3 {
                        let allowed = (tol.rel * wp[i].abs()).max(tol.floor());
                        count(ulps_of((gp[i] - wp[i]).abs(), tol.floor(), tol.eps * wp[i].abs()));
                        if !((gp[i] - wp[i]).abs() <= allowed) {
                            value.push(format!(
                                "aabb coordinate {:.17e} off by {:.3e} (allowed {allowed:.1e})",
                                wp[i],
                                (gp[i] - wp[i]).abs()
                            ));
                        }
                    }
                }
            }
            if let (Some(gs), Some(ws)) = (&g.sphere, &w.sphere) {
                // The engine's sphere must enclose every point; its excess radius
                // over the minimal one is its error (parry's and the lecture's are
                // not minimal by design: a known divergence).
                let pts = bounded_points(lc);
                if let Some((i, d)) = farthest_outside(&gs.center, gs.radius, pts, allow.depth) {
                    class.push(format!("bounding sphere misses point {i} by {d:.3e}"));
                    fneg(&mut e);
                }
                // A miss has no referee margin: the farthest point's distance
                // outside is how far off the sphere is, in ulps of the radius's
                // magnitude.
                let outside = pts.iter().map(|p| crate::local::distance(p, &gs.center) - gs.radius).fold(0.0, f64::max);
                count(ulps_of(outside, conditioned.depth, one.depth));
                let excess = gs.radius - ws.radius;
                e.depth = Some(excess);
                over("bounding radius", excess, |a| a.depth, "", &mut value);
            }
        }
        (Answer::Overlap(g), Answer::Overlap(w)) => {
            if g != w {
                class.push(format!("overlap: {g} (referee {w})"));
                if *g { fp(&mut e) } else { fneg(&mut e) }
            }
        }
        (Answer::Toi(g), Answer::Toi(w)) => match (&g.toi, &w.toi) {
            (Some(gt), Some(wt)) => {
                let t_scale = lc.case.t_max().max(f64::MIN_POSITIVE);
                let dt = (gt.t - wt.t).abs();
                e.t = Some(dt / t_scale);
                over("t", dt, |a| a.t, "", &mut value);
                let dp = dist3(&gt.point, &wt.point);
                e.point = Some(dp);
                over("point", dp, |a| a.point, "", &mut value);
                let a = angle(&gt.normal, &wt.normal);
                no_direction(&gt.normal, &wt.normal, &mut value);
                e.normal = Some(a);
                over("normal", a, |a| a.normal, " rad", &mut value);
                unit(&gt.normal, &mut e, &mut value);
            }
            (None, None) => {}
            (Some(_), None) => {
                class.push("false impact (referee: none)".into());
                fp(&mut e);
            }
            (None, Some(_)) => {
                class.push("missed impact (referee: impact)".into());
                fneg(&mut e);
            }
        },
        (Answer::Response(g), Answer::Response(w)) => {
            let err = dist3(&g.velocity_a, &w.velocity_a).max(dist3(&g.velocity_b, &w.velocity_b));
            let speed = sizes.velocity.magnitude;
            e.velocity = Some(if speed > 0.0 { err / speed } else { err });
            over("velocity", err, |a| a.velocity, "", &mut value);
        }
        _ => class.push("answer of another query kind".into()),
    }
    // A classification that differs is as far off as the referee's margin
    // from the boundary: in ulps beyond the band's conditioning, the same
    // measure `--ulps N` decides borderline by.
    if matches!(e.misclass, Some(Misclass::FalsePositive | Misclass::FalseNegative))
        && let Some(m) = margin
    {
        count(ulps_of(m.abs(), conditioned.margin, one.margin));
    }
    e.ulps = ulps.get();
    let verdict = if !class.is_empty() {
        match margin {
            Some(m) if m.abs() <= allow.margin => Verdict::Borderline { reasons: class },
            _ => {
                class.extend(value);
                Verdict::Disagree { reasons: class }
            }
        }
    } else if !value.is_empty() {
        Verdict::Disagree { reasons: value }
    } else {
        Verdict::Agree
    };
    (verdict, e)
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
/// scale of [`crate::local`]: the sphere's centre and radius, `b`'s own size
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
    use crate::local::norm;
    let va = lc.case.a.velocity();
    let vb = b.velocity();
    // The relative velocity, halved where its difference would overflow (and
    // its norm doubled back).
    let (v, k) = crate::local::diff(&va, &vb);
    let speed = norm(&v) * k;
    let closing = -(v[0] * w.normal[0] + v[1] * w.normal[1] + v[2] * w.normal[2]) * k;
    // `δ` itself underflows for a reach near the subnormals (64 ε · 1e-313 is
    // below the smallest f64): every quotient by a speed or a length is
    // formed from `reach` first, then multiplied by `64 ε`.
    let c_eps = crate::tolerance::TIME_CONDITION_ULPS * tol.eps;
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
    // A contact at t = 0 has the static contact's sizes (`local`), whose
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

/// The campaign's headline error of one answer: the largest of the point and
/// depth errors relative to the answer's scale, the normal's angle (radians)
/// and its length's distance from 1, and the segment parameter's and barycentrics' errors (unitless) — the
/// measure of the report's accuracy tables and charts, and of the stability
/// sweeps.
pub fn headline(e: &Errors, scale: f64) -> f64 {
    [e.point.map(|x| x / scale), e.depth.map(|x| x.abs() / scale), e.normal, e.normal_length, e.t, e.barycentric]
        .into_iter()
        .flatten()
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::{Loaded, load_str_into};

    /// Concentric spheres: the referee's normal is its fallback, and any
    /// direction is allowed (π) — but not the zero vector.
    #[test]
    fn a_zero_normal_is_never_an_agreement() {
        let text = r#"{"schema": "crashtest-fixture/1", "cases": [{"name": "concentric", "query": "contact",
            "a": {"sphere": {"center": [1, 2, 3], "radius": 1}}, "b": {"sphere": {"center": [1, 2, 3], "radius": 2}}}]}"#;
        let mut loaded = Loaded::default();
        load_str_into(std::path::Path::new("c.json"), text, &mut loaded);
        let lc = &loaded.cases[0];
        let set = crate::engines::EngineSet::default();
        let truth = set.referee.run(lc).expect("the referee answers");
        let tol = Tolerance::for_precision(Some(53));
        let Answer::Contact(w) = &truth else { panic!("a contact answer") };
        let wc = w.contact.expect("concentric spheres touch");
        let allowed = allowed(lc, &truth, &tol);
        assert!(allowed.normal >= std::f64::consts::PI, "any direction is allowed here: {allowed:?}");
        let with = |normal: P3| {
            let mut a = *w;
            a.contact = Some(crashtest_core::geom::Contact { normal, ..wc });
            judge(lc, &Answer::Contact(a), &truth, &tol, None).0
        };
        assert_eq!(with([0.0, 1.0, 0.0]), Verdict::Agree, "another direction is allowed");
        match with([0.0, 0.0, 0.0]) {
            Verdict::Disagree { reasons } => assert!(reasons.iter().any(|r| r.contains("zero vector")), "{reasons:?}"),
            other => panic!("a zero normal judged {other:?}"),
        }
    }
}
