//! The verdict: an engine's answer to one case against the referee's, in
//! four stages, one file each, read in this order —
//!
//! 1. [`sizes`]: the sizes that decide each field of the answer at that
//!    input (the problem's own scale, and each field's conditioning);
//! 2. [`allowance`]: what each field may be off by — the sizes through the
//!    tolerance table ([`tolerance`]: every constant with its reason), or `N`
//!    ulps of them under `--ulps N` — and beside it the conditioning alone and
//!    one ulp of each field's magnitude, for the accuracy in ulps;
//! 3. [`compare`]: each field's error and whether the classification is the
//!    referee's, before any allowance;
//! 4. the reasons ([`judge`], here): each error weighed against its
//!    allowance, a classification that differs weighed against the referee's
//!    margin from its boundary (inside the band: borderline), and the answer's
//!    accuracy in ulps.
//!
//! [`verdict`] holds the vocabulary the stages share. Two things happen after
//! the verdict, in `crate::check`: a disagreement a documented convention of
//! the engine explains becomes a known divergence, and an `f32` engine's is
//! also judged against the referee's answer to the case rounded to `f32`.
//! A case's own `expect` is judged apart, by [`expect`].

pub mod allowance;
pub mod compare;
pub mod expect;
pub mod sizes;
pub mod tolerance;
pub mod verdict;

pub use allowance::{Allowed, allowed};
pub use compare::{angle, unit_excess};
pub use expect::{Mismatch, check_expect};
pub use sizes::{answer_scale, scene_scale};
pub use verdict::{Errors, Misclass, NON_FINITE, Verdict, all_finite, degenerate, headline};

use crate::engine::Answer;
use crate::load::LoadedCase;
use allowance::{Allowances, ulps_of};
use compare::Against;
use tolerance::Tolerance;

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
    judge_sized(lc, answer, truth, &sizes::local(lc, truth), tol, margin)
}

/// [`judge`] with the case's sizes `sizes` already taken ([`sizes::local`] of
/// `lc` and `truth`): they depend on the case and the referee's answer only,
/// so a case judged for several engines takes them once (a box's exact
/// contact region is most of a judgement's time).
pub fn judge_sized(
    lc: &LoadedCase,
    answer: &Answer,
    truth: &Answer,
    sizes: &sizes::Local,
    tol: &Tolerance,
    margin: Option<f64>,
) -> (Verdict, Errors) {
    if !all_finite(answer) {
        return (Verdict::Failed { reason: NON_FINITE.into() }, Errors::default());
    }
    // 1. The sizes (given); 2. the allowances; 3. the comparison.
    let allow = Allowances::of(lc, truth, tol, sizes);
    let compared = compare::compare(lc, answer, truth, sizes);
    // 4. The reasons: each measured error against its allowance, and its
    // ulps beyond the conditioning.
    let mut e = compared.errors;
    let mut class = compared.class;
    let mut value = compared.wrong;
    let mut ulps: Option<f64> = None;
    for m in &compared.measured {
        let (allowed, conditioned, one) = match m.against {
            Against::Field(f) => (f(&allow.verdict), f(&allow.conditioned), f(&allow.one)),
            Against::Own(w) => ((tol.rel * w.abs()).max(tol.floor()), tol.floor(), tol.eps * w.abs()),
            Against::UnitLength(_) => (tol.normal_length_ulps * tol.eps, 0.0, tol.eps),
            Against::Outside(_) => (allow.verdict.depth, allow.conditioned.depth, allow.one.depth),
        };
        let u = ulps_of(m.err, conditioned, one);
        ulps = Some(ulps.map_or(u, |x| x.max(u)));
        if m.err <= allowed {
            continue;
        }
        match m.against {
            Against::UnitLength(length) => value.push(format!(
                "normal not unit: length {length} ({:.3e} ulps from 1, allowed {})",
                m.err / tol.eps,
                tol.normal_length_ulps
            )),
            Against::Outside(i) => {
                class.push(format!("bounding sphere misses point {i} by {:.3e}", m.err));
                e.misclass = Some(Misclass::FalseNegative);
            }
            Against::Own(w) => {
                value.push(format!("{} {w:.17e} off by {:.3e}{} (allowed {allowed:.1e})", m.field, m.err, m.unit))
            }
            Against::Field(_) => {
                value.push(format!("{} off by {:.3e}{} (allowed {allowed:.1e})", m.field, m.err, m.unit))
            }
        }
    }
    // A contact, hit, impact or overlap found or missed is as far off as the
    // referee's margin from the boundary: in ulps beyond the band's
    // conditioning, the same measure `--ulps N` decides borderline by.
    let misclassified = matches!(e.misclass, Some(Misclass::FalsePositive | Misclass::FalseNegative));
    if misclassified && let Some(m) = margin {
        let u = ulps_of(m.abs(), allow.conditioned.margin, allow.one.margin);
        ulps = Some(ulps.map_or(u, |x| x.max(u)));
    }
    e.ulps = ulps;
    let verdict = if !class.is_empty() {
        match margin {
            Some(m) if m.abs() <= allow.verdict.margin => Verdict::Borderline { reasons: class },
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::{Loaded, load_str_into};
    use oracle::geom::P3;

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

    /// The time allowance of a sphere's impact on a box is the window in
    /// which its path is within δ of touching: a head-on hit on a face pins
    /// the time to a few ulps, a path gliding exactly `r` above a face (it
    /// first touches at the face's edge, t = 2, and stays touching to t = 4)
    /// allows any time from the edge on — a perturbation of one ulp lifts the
    /// path clear or sinks it along the whole face.
    #[test]
    fn a_box_impact_is_allowed_the_window_its_path_is_within_reach() {
        let case = |name: &str, center: &str, velocity: &str| {
            format!(
                r#"{{"name": "{name}", "query": "toi", "t_max": 4,
                "a": {{"sphere": {{"center": {center}, "radius": 0.5, "velocity": {velocity}}}}},
                "b": {{"box": {{"center": [0, 0, 0], "half_extents": [1, 1, 1]}}}}}}"#
            )
        };
        let text = format!(
            r#"{{"schema": "crashtest-fixture/1", "cases": [{}, {}]}}"#,
            case("head-on", "[3, 0, 0]", "[-1, 0, 0]"),
            case("gliding", "[-3, 1.5, 0]", "[1, 0, 0]")
        );
        let mut loaded = Loaded::default();
        load_str_into(std::path::Path::new("c.json"), &text, &mut loaded);
        let set = crate::engines::EngineSet::default();
        let tol = Tolerance::for_precision(Some(53));
        let t_allowed = |lc: &LoadedCase| {
            let truth = set.referee.run(lc).expect("the referee answers");
            allowed(lc, &truth, &tol).t
        };
        let (head_on, gliding) = (t_allowed(&loaded.cases[0]), t_allowed(&loaded.cases[1]));
        // The table's fixed part (its relative tolerance of t_max = 4) and
        // δ = 64 ε of the reach (about 8) over a closing speed of 1: below
        // twice the fixed part.
        let fixed = tol.rel * 4.0;
        assert!(head_on < 2.0 * fixed, "a face hit head-on: {head_on:e} against {fixed:e}");
        // The glide over the face lasts from t = 2 (the edge x = −1) to t = 4.
        assert!(gliding >= 2.0, "a glide along the face: {gliding:e}");
    }

    /// Coplanar motion (the referee's degenerate flag) allows a time anywhere
    /// in the interval, but an impact after `t_max` is no answer: a point
    /// entering a face in its plane at t = 1/4, the interval cut at 1/2.
    #[test]
    fn a_ccd_impact_outside_the_interval_never_agrees() {
        let text = r#"{"schema": "crashtest-fixture/1", "cases": [{"name": "sliding in", "query": "ccd", "t_max": 0.5,
            "a": {"moving_point": {"t0": [-1, 1, 0], "t1": [3, 1, 0]}},
            "b": {"moving_triangle": {"t0": [[0, 0, 0], [4, 0, 0], [0, 4, 0]], "t1": [[0, 0, 0], [4, 0, 0], [0, 4, 0]]}}}]}"#;
        let mut loaded = Loaded::default();
        load_str_into(std::path::Path::new("c.json"), text, &mut loaded);
        let lc = &loaded.cases[0];
        let set = crate::engines::EngineSet::default();
        let truth = set.referee.run(lc).expect("the referee answers");
        let Answer::Ccd(w) = truth else { panic!("a ccd answer") };
        assert!(w.degenerate && w.t.is_some(), "coplanar motion, an impact: {w:?}");
        let tol = Tolerance::for_precision(Some(53));
        let at =
            |t: f64| judge(lc, &Answer::Ccd(crashtest_core::geom::CcdAnswer { t: Some(t), ..w }), &truth, &tol, None).0;
        // Within the interval, an ill-posed time is allowed.
        assert_eq!(at(0.45), Verdict::Agree);
        for t in [0.5f64.next_up(), 0.75, -1e-300] {
            match at(t) {
                Verdict::Disagree { reasons } => {
                    assert!(reasons.iter().any(|r| r.contains("outside [0, t_max")), "{t}: {reasons:?}")
                }
                other => panic!("an impact at {t} judged {other:?}"),
            }
        }
    }
}
