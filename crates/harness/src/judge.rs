//! Judging answers: against a case's expectation (the fixture's `expect`, with its
//! absolute `tol`) and against the referee (the tolerance table, relative to the
//! scene's scale, with borderline cases and known divergences kept apart).

use crate::case::{Case, Expect, Shape};
use crate::engine::Answer;
use crate::load::LoadedCase;
use crate::tolerance::Tolerance;
use oracle::geom::{Contact, P3, SegmentHit};
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

/// The points a `bounds` case bounds.
pub fn bounded_points(lc: &LoadedCase) -> &[P3] {
    match (&lc.case.a, &lc.meshes[0]) {
        (Shape::Points(p), _) => &p.points,
        (_, Some(m)) => &m.vertices,
        _ => &[],
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
                        if let Some(wb) = &w.barycentric {
                            match &g.barycentric {
                                Some(gb) => cmp3(&mut out, "hit.barycentric", wb, gb, tol),
                                None => out.push(mm("hit.barycentric", wb, "none")),
                            }
                        }
                        if let Some(wt) = w.triangle {
                            if g.triangle != Some(wt) {
                                out.push(mm("hit.triangle", wt, g.triangle));
                            }
                        }
                    }
                    (w, g) => out.push(mm("hit", w, g)),
                }
            }
            if let Some(want) = e.parallel {
                if want != a.parallel {
                    out.push(mm("parallel", want, a.parallel));
                }
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
            if let Some(w) = e.overlap {
                if w != *g {
                    out.push(mm("overlap", w, g));
                }
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

/// The first point farther than `radius + tol` from `center`, with its excess.
fn farthest_outside(center: &P3, radius: f64, pts: &[P3], tol: f64) -> Option<(usize, f64)> {
    pts.iter().enumerate().find_map(|(i, p)| {
        let d = ((p[0] - center[0]).powi(2) + (p[1] - center[1]).powi(2) + (p[2] - center[2]).powi(2)).sqrt();
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
    /// Error of the segment parameter `t`.
    pub t: Option<f64>,
    /// Largest barycentric coordinate error.
    pub barycentric: Option<f64>,
    /// Largest velocity component error (response), relative to the largest
    /// input speed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<f64>,
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

fn angle(a: &P3, b: &P3) -> f64 {
    // atan2(‖a × b‖, a · b): accurate for small and large angles alike.
    let c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let s = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    s.atan2(d)
}

fn all_finite(answer: &Answer) -> bool {
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

/// Judges `answer` against the referee's `truth` for the case `lc`, with the
/// tolerances `tol`. `margin` is the referee's signed distance of the case from
/// its nearest decision boundary (relative to the scene's scale); a
/// classification difference within the tolerance band of the boundary is
/// borderline.
pub fn judge(
    lc: &LoadedCase,
    answer: &Answer,
    truth: &Answer,
    tol: &Tolerance,
    margin: Option<f64>,
) -> (Verdict, Errors) {
    let scale = scene_scale(lc);
    let mut e = Errors::default();
    if !all_finite(answer) {
        return (Verdict::Failed { reason: "non-finite number in the answer".into() }, e);
    }
    let mut class = Vec::new();
    let mut value = Vec::new();
    let len_tol = tol.rel * scale;
    let mut len = |what: &str, err: f64, slot: &mut Option<f64>, value: &mut Vec<String>| {
        *slot = Some(err);
        if !(err <= len_tol) {
            value.push(format!("{what} off by {err:.3e} (allowed {len_tol:.1e})"));
        }
    };
    // The conditioning allowance of a contact normal (see
    // `tolerance::NORMAL_CONDITION_ULPS`): the referee's distance between the
    // points the normal joins is the sum of the radii (sphere–sphere) or the
    // sphere's radius (sphere–triangle) less the depth; a plane's normal is an
    // input, not a difference.
    let normal_extra = |w: &Contact| -> f64 {
        let d = match (&lc.case.a, lc.case.b.as_ref()) {
            (Shape::Sphere(a), Some(Shape::Sphere(b))) => a.radius + b.radius - w.depth,
            (Shape::Sphere(s), Some(Shape::Triangle(_))) | (Shape::Triangle(_), Some(Shape::Sphere(s))) => {
                s.radius - w.depth
            }
            _ => return 0.0,
        };
        if d > 0.0 { crate::tolerance::NORMAL_CONDITION_ULPS * tol.eps * scale / d } else { f64::INFINITY }
    };
    let contact_cmp = |g: &Contact, w: &Contact, e: &mut Errors, value: &mut Vec<String>| {
        let extra = normal_extra(w);
        // A point built from the normal (the reverse orders: centre − r·n) moves
        // by up to the scene's scale times the normal's allowance.
        let point_tol = len_tol + scale * extra.min(2.0);
        let dp = dist3(&g.point, &w.point);
        e.point = Some(dp);
        if !(dp <= point_tol) {
            value.push(format!("point off by {dp:.3e} (allowed {point_tol:.1e})"));
        }
        let dd = (g.depth - w.depth).abs();
        e.depth = Some(dd);
        if !(dd <= len_tol) {
            value.push(format!("depth off by {dd:.3e} (allowed {len_tol:.1e})"));
        }
        let a = angle(&g.normal, &w.normal);
        e.normal = Some(a);
        let allowed = tol.normal_rad + extra;
        if !(a <= allowed) {
            value.push(format!("normal off by {a:.3e} rad (allowed {allowed:.1e})"));
        }
    };
    if degenerate(answer) != degenerate(truth) {
        class.push(format!("degenerate: {} (referee {})", degenerate(answer), degenerate(truth)));
        e.misclass = Some(Misclass::Flag);
    }
    let fp = |e: &mut Errors| e.misclass = Some(Misclass::FalsePositive);
    let fneg = |e: &mut Errors| e.misclass = Some(Misclass::FalseNegative);
    match (answer, truth) {
        (Answer::Contact(g), Answer::Contact(w)) => match (&g.contact, &w.contact) {
            (Some(gc), Some(wc)) => contact_cmp(gc, wc, &mut e, &mut value),
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
                (Some(gh), Some(wh)) => hit_cmp(gh, wh, tol, &mut e, &mut value, &mut len),
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
            let size = w.coords.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
            let allowed = tol.unitless + bary_extra(lc, tol, scale) * size;
            if !(err <= allowed) {
                value.push(format!("barycentric off by {err:.3e} (allowed {allowed:.1e})"));
            }
        }
        (Answer::Bounds(g), Answer::Bounds(w)) => {
            if let (Some(gb), Some(wb)) = (&g.aabb, &w.aabb) {
                let err = dist3(&gb.min, &wb.min).max(dist3(&gb.max, &wb.max));
                len("aabb", err, &mut e.point, &mut value);
            }
            if let (Some(gs), Some(ws)) = (&g.sphere, &w.sphere) {
                // The engine's sphere must enclose every point; its excess radius
                // over the minimal one is its error (parry's and the lecture's are
                // not minimal by design: a known divergence).
                let pts = bounded_points(lc);
                if let Some((i, d)) = farthest_outside(&gs.center, gs.radius, pts, len_tol) {
                    class.push(format!("bounding sphere misses point {i} by {d:.3e}"));
                    fneg(&mut e);
                }
                len("bounding radius", gs.radius - ws.radius, &mut e.depth, &mut value);
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
                // A time is judged relative to the interval: t_max plays the
                // scene's scale for the time axis; the conditioning of the
                // impact adds to it, and through the time to the point and the
                // normal (see `toi_allowance`).
                let extra = toi_allowance(lc, wt, tol, scale);
                let t_scale = lc.case.t_max().max(f64::MIN_POSITIVE);
                let dt = (gt.t - wt.t).abs();
                e.t = Some(dt / t_scale);
                let t_allowed = tol.rel * t_scale + extra.t;
                if !(dt <= t_allowed) {
                    value.push(format!("t off by {dt:.3e} (allowed {t_allowed:.1e})"));
                }
                let dp = dist3(&gt.point, &wt.point);
                e.point = Some(dp);
                let p_allowed = len_tol + extra.point;
                if !(dp <= p_allowed) {
                    value.push(format!("point off by {dp:.3e} (allowed {p_allowed:.1e})"));
                }
                let a = angle(&gt.normal, &wt.normal);
                e.normal = Some(a);
                let n_allowed = tol.normal_rad + extra.normal;
                if !(a <= n_allowed) {
                    value.push(format!("normal off by {a:.3e} rad (allowed {n_allowed:.1e})"));
                }
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
            let speed = [lc.case.a.velocity(), lc.case.b.as_ref().map(Shape::velocity).unwrap_or_default()]
                .iter()
                .flatten()
                .fold(0.0_f64, |m, x| m.max(x.abs()));
            let speed = if speed > 0.0 { speed } else { 1.0 };
            let err = dist3(&g.velocity_a, &w.velocity_a).max(dist3(&g.velocity_b, &w.velocity_b));
            e.velocity = Some(err / speed);
            if !(err <= tol.rel * speed) {
                value.push(format!("velocity off by {err:.3e} (allowed {:.1e})", tol.rel * speed));
            }
        }
        _ => class.push("answer of another query kind".into()),
    }
    let verdict = if !class.is_empty() {
        match margin {
            Some(m) if m.abs() <= tol.rel => Verdict::Borderline { reasons: class },
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
/// `w` and the case's motion.
///
/// Perturbing the inputs by `δ = TIME_CONDITION_ULPS · ε · scale'` (what any
/// method in the engine's precision commits in the distance it tests, `scale'`
/// the scene's scale grown by how far both shapes move until the impact) moves the
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
/// `tolerance::NORMAL_CONDITION_ULPS` gives a static contact.
fn toi_allowance(lc: &LoadedCase, w: &oracle::geom::Toi, tol: &Tolerance, scale: f64) -> ToiAllowance {
    let norm = |v: &P3| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let va = lc.case.a.velocity();
    let vb = lc.case.b.as_ref().map(Shape::velocity).unwrap_or_default();
    let v = [va[0] - vb[0], va[1] - vb[1], va[2] - vb[2]];
    let speed = norm(&v);
    let closing = -(v[0] * w.normal[0] + v[1] * w.normal[1] + v[2] * w.normal[2]);
    // The scene's scale at the impact: the shapes have moved by then.
    let reach = scale + (norm(&va) + norm(&vb)) * w.t.abs();
    let delta = crate::tolerance::TIME_CONDITION_ULPS * tol.eps * reach;
    let radius = |s: &Shape| if let Shape::Sphere(s) = s { s.radius } else { 0.0 };
    let ra = radius(&lc.case.a);
    // (radius of curvature, distance the normal spans)
    let (curvature, span) = match lc.case.b.as_ref() {
        Some(Shape::Sphere(b)) => (ra + b.radius, ra + b.radius),
        Some(Shape::Plane(_)) => (f64::INFINITY, f64::INFINITY),
        _ => (ra, ra),
    };
    let first = if closing > 0.0 { delta / closing } else { f64::INFINITY };
    let second =
        if curvature.is_finite() && speed > 0.0 { (2.0 * curvature * delta).sqrt() / speed } else { f64::INFINITY };
    let t = first.min(second);
    // A speed of 0 moves nothing, however long the time (no 0 · ∞).
    let moved = |speed: f64| if speed > 0.0 { speed * t } else { 0.0 };
    let point = moved(norm(&va) + norm(&vb) + 2.0 * speed) + delta;
    let normal =
        if span.is_finite() { if span > 0.0 { (moved(speed) + delta) / span } else { f64::INFINITY } } else { 0.0 };
    ToiAllowance { t, point, normal }
}

/// The conditioning allowance of barycentric coordinates on the case's triangle
/// (see `tolerance::BARY_CONDITION_ULPS`): `K · ε · scale · L / ‖n‖`, per unit of
/// the coordinates' size (a coordinate is a ratio of areas, and the relative
/// error of the triangle's area carries over to every coordinate in proportion).
fn bary_extra(lc: &LoadedCase, tol: &Tolerance, scale: f64) -> f64 {
    let Some(Shape::Triangle(t)) = &lc.case.b else { return 0.0 };
    let [a, b, c] = t.vertices;
    let sub = |p: &P3, q: &P3| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let norm = |v: &P3| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let (u, v, w) = (sub(&b, &a), sub(&c, &a), sub(&c, &b));
    let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    let longest = norm(&u).max(norm(&v)).max(norm(&w));
    let twice_area = norm(&n);
    if twice_area > 0.0 {
        // A point at height D off the plane moves its projection by D times the
        // plane's tilt, and a sliver's plane tilts by about ε · scale · L / ‖n‖
        // when its vertices move by ε · scale: the factor (1 + D · L / ‖n‖).
        let height = match &lc.case.a {
            Shape::Point(p) => {
                let d = sub(&p.at, &a);
                (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]).abs() / twice_area
            }
            _ => 0.0,
        };
        crate::tolerance::BARY_CONDITION_ULPS * tol.eps * scale * longest / twice_area
            * (1.0 + height * longest / twice_area)
    } else {
        f64::INFINITY
    }
}

fn hit_cmp(
    g: &SegmentHit,
    w: &SegmentHit,
    tol: &Tolerance,
    e: &mut Errors,
    value: &mut Vec<String>,
    len: &mut dyn FnMut(&str, f64, &mut Option<f64>, &mut Vec<String>),
) {
    len("hit point", dist3(&g.point, &w.point), &mut e.point, value);
    let dt = (g.t - w.t).abs();
    e.t = Some(dt);
    if !(dt <= tol.unitless) {
        value.push(format!("t off by {dt:.3e} (allowed {:.1e})", tol.unitless));
    }
    let a = angle(&g.normal, &w.normal);
    e.normal = Some(a);
    if !(a <= tol.normal_rad) {
        value.push(format!("normal off by {a:.3e} rad (allowed {:.1e})", tol.normal_rad));
    }
    if let (Some(gb), Some(wb)) = (&g.barycentric, &w.barycentric) {
        let err = dist3(gb, wb);
        e.barycentric = Some(err);
        if !(err <= tol.unitless) {
            value.push(format!("barycentric off by {err:.3e} (allowed {:.1e})", tol.unitless));
        }
    }
}
