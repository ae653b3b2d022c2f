//! The verdict's vocabulary: what an answer is off by ([`Errors`]), how a
//! classification differs ([`Misclass`]), the [`Verdict`] itself, and the
//! checks every stage shares (finite numbers, the degenerate flag, the
//! headline error of the reports).

use crate::engine::Answer;
use oracle::geom::P3;
use serde::Serialize;

/// Errors of an answer against the referee's, each `None` where not applicable.
/// Lengths are absolute here; divide by [`super::sizes::scene_scale`] for relative ones.
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
    /// sizes of [`super::sizes`]); for a contact, hit, impact or overlap
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

/// Whether an answer carries the degenerate flag.
pub fn degenerate(answer: &Answer) -> bool {
    match answer {
        Answer::Contact(a) => a.degenerate,
        Answer::Intersect(a) => a.degenerate,
        Answer::Barycentric(a) => a.degenerate,
        Answer::Toi(a) => a.degenerate,
        Answer::Response(a) => a.degenerate,
        Answer::Ccd(a) => a.degenerate,
        Answer::Distance(a) => a.degenerate,
        Answer::Bounds(_) | Answer::Overlap(_) => false,
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
        Answer::Ccd(a) => a.t.is_none_or(f64::is_finite),
        Answer::Distance(a) => a.distance.is_finite() && f3(&a.point_a) && f3(&a.point_b) && f3(&a.normal),
    }
}

/// The reason of a `Failed` verdict on an answer holding NaN or an infinity
/// (the referee's answer is finite: see [`all_finite`]); counted apart in
/// reports.
pub const NON_FINITE: &str = "non-finite number in the answer";

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
