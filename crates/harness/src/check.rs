//! `crashtest check`: every case through every engine, each answer compared with
//! the case's `expect` and with the referee.
//!
//! A case passes when the gate engine ([`EngineSet::gate`], by default
//! [`crate::engines::DEFAULT_ENGINE`]) meets every named
//! expectation and does not disagree with the referee (borderline is not a
//! disagreement). An engine that panics is caught and recorded as failing that
//! case, the panic's message and location in the verdict's reason and nothing
//! on standard error (see [`run_caught`]); the run goes on.

use crate::case::{Expect, Query};
use crate::engine::{Answer, Engine};
use crate::engines::{self, EngineSet};
use crate::judge::tolerance::Tolerance;
use crate::judge::{self, Errors, Mismatch, Verdict};
use crate::load::{InputError, LoadedCase};
use crate::protocol::client::Outcome;
use serde::Serialize;
use std::cell::{Cell, RefCell};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Once;

/// One engine's result on one case.
#[derive(Clone, Debug, Serialize)]
pub struct EngineResult {
    /// The engine's name.
    pub engine: String,
    /// Its answer, written as a fixture's `expect` would be (absent when it gave none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub answer: Option<Expect>,
    /// Against the referee.
    #[serde(flatten)]
    pub verdict: Verdict,
    /// Its errors against the referee (absolute; see `scale`).
    pub errors: Errors,
    /// Mismatches with the case's `expect`: `None` when the case has no
    /// expectation or the engine gave no answer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub expect_mismatches: Option<Vec<Mismatch>>,
    /// For an engine of less precision than `f64` that disagrees: whether its
    /// answer agrees with the exact answer to the case's inputs rounded to
    /// its precision (what it was given, in effect). The disagreement stands;
    /// [`crate::findings`] files it under the engine's precision.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub rounding_explains: bool,
}

/// Everything about one case.
#[derive(Clone, Debug, Serialize)]
pub struct CaseResult {
    /// Its file.
    pub file: String,
    /// Its name.
    pub name: String,
    /// Its query.
    pub query: Query,
    /// The answer's length scale (relative errors divide by it): the local
    /// magnitude its lengths are judged by (`judge::answer_scale`).
    pub scale: f64,
    /// The referee's margin from the nearest decision boundary, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub margin: Option<f64>,
    /// The referee's answer (absent when it refused the case).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub referee: Option<Expect>,
    /// Whether the referee meets the case's expectation (absent without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub referee_meets_expect: Option<bool>,
    /// Each judged engine's result.
    pub engines: Vec<EngineResult>,
    /// Whether the gate engine passed.
    pub passed: bool,
    /// Whether the gate engine does not answer this kind of case (it neither
    /// passes nor fails it).
    pub unanswered: bool,
}

/// The whole check.
#[derive(Clone, Debug, Serialize)]
pub struct CheckResult {
    /// Per case, in file order.
    pub cases: Vec<CaseResult>,
    /// Refused input, one line each.
    pub errors: Vec<String>,
    /// The gate engine: its answers decide `passed`, `failed` and the exit code.
    pub gate: String,
    /// Cases the gate engine passed.
    pub passed: usize,
    /// Cases it failed.
    pub failed: usize,
    /// Cases it does not answer (their pair is not implemented by it): neither
    /// passed nor failed.
    pub unanswered: usize,
}

impl CheckResult {
    /// The process exit code: 2 for bad input, 1 when the gate engine failed a
    /// case or answered none, 0 otherwise.
    pub fn exit_code(&self) -> i32 {
        if !self.errors.is_empty() {
            2
        } else if self.failed > 0 || (self.passed == 0 && self.unanswered > 0) {
            1
        } else {
            0
        }
    }
}

/// Writes an answer as a fixture's `expect` (its wire form's fields, the
/// bounding sphere as its radius).
pub fn answer_as_expect(a: &Answer) -> Expect {
    crate::protocol::messages::WireAnswer::of(a).into_expect()
}

/// The reason given to every engine for a case whose exact answer lies beyond
/// `f64`'s range (see `fixtures/README.md`, "Answers beyond f64").
pub const OUT_OF_RANGE: &str =
    "out of range: the exact answer lies beyond f64's range (its rounding is infinite), so no engine is graded on it";

/// Runs one engine on one case, catching a panic.
/// How the reason of a [`Verdict::Failed`] for a caught panic begins: the
/// campaign counts these per engine ([`is_caught_panic`]).
pub const PANIC_REASON_PREFIX: &str = "panicked at ";

thread_local! {
    /// Whether this thread is inside [`run_caught`]'s call of an engine.
    static CATCHING: Cell<bool> = const { Cell::new(false) };
    /// The location and message of the panic caught on this thread, as the
    /// hook saw them.
    static CAUGHT: RefCell<Option<String>> = const { RefCell::new(None) };
}

static HOOK: Once = Once::new();

/// Installs (once per process) a panic hook that, on a thread inside
/// [`run_caught`], records the panic's location and message instead of
/// printing them and a backtrace: a campaign of thousands of cases whose
/// engine panics on some would otherwise bury its output under them. A panic
/// anywhere else — another thread, crashtest's own code — goes to the hook
/// that was there before, and prints as usual. The flag is per thread, so the
/// cases rayon runs in parallel do not see each other's.
fn install_quiet_hook() {
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if CATCHING.with(Cell::get) {
                let location = info
                    .location()
                    .map(|l| format!("{}:{}:{}", crate_relative(l.file()), l.line(), l.column()))
                    .unwrap_or_default();
                let payload = info.payload();
                let message = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "(no message)".into());
                CAUGHT.with(|c| *c.borrow_mut() = Some(format!("{location}: {message}")));
            } else {
                previous(info);
            }
        }));
    });
}

/// A source path from its crate's root: a dependency's file under cargo's
/// registry (`…/registry/src/<index>/parry3d-f64-0.31.1/src/x.rs`) is named
/// from its crate's folder (`parry3d-f64-0.31.1/src/x.rs`), the same on every
/// machine; the workspace's own files already are (`crates/collide/src/x.rs`).
pub fn crate_relative(file: &str) -> &str {
    match file.find("/registry/src/") {
        Some(i) => {
            let rest = &file[i + "/registry/src/".len()..];
            rest.split_once('/').map_or(rest, |(_, r)| r)
        }
        None => file,
    }
}

/// Whether a verdict is a panic [`run_caught`] caught.
pub fn is_caught_panic(v: &Verdict) -> bool {
    matches!(v, Verdict::Failed { reason } if reason.starts_with(PANIC_REASON_PREFIX))
}

/// Runs one engine on one case, catching a panic: it becomes a
/// [`Verdict::Failed`] whose reason is one line, `panicked at
/// <file>:<line>:<column>: <message>`, and nothing is printed.
pub fn run_caught(engine: &Engine, lc: &LoadedCase) -> Result<Answer, Verdict> {
    if let Some(p) = engine.process() {
        // A process engine's faults are contained by its client, which never
        // panics: its failures arrive as failures.
        return match p.answer(lc).outcome {
            Outcome::Answer(a) => Ok(a),
            Outcome::Unsupported(reason) => Err(Verdict::Unsupported { reason }),
            Outcome::Failed(reason) => Err(Verdict::Failed { reason }),
        };
    }
    install_quiet_hook();
    let outer = CATCHING.with(|c| c.replace(true));
    let result = catch_unwind(AssertUnwindSafe(|| engine.run(lc)));
    CATCHING.with(|c| c.set(outer));
    match result {
        Ok(Ok(a)) => Ok(a),
        Ok(Err(u)) => Err(Verdict::Unsupported { reason: u.0 }),
        Err(p) => {
            let seen = CAUGHT.with(|c| c.borrow_mut().take());
            let what = seen.unwrap_or_else(|| {
                p.downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| p.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "(no message)".into())
            });
            Err(Verdict::Failed { reason: format!("{PANIC_REASON_PREFIX}{what}") })
        }
    }
}

/// Judges one case with every engine.
///
/// ```
/// use harness::load::{Loaded, load_str_into};
/// let text = r#"{"schema": "crashtest-fixture/1", "cases": [{"name": "touching boxes", "query": "overlap",
///     "a": {"aabb": {"min": [0, 0, 0], "max": [1, 1, 1]}}, "b": {"aabb": {"min": [1, 0, 0], "max": [2, 1, 1]}},
///     "expect": {"overlap": true}}]}"#;
/// let mut loaded = Loaded::default();
/// load_str_into(std::path::Path::new("boxes.json"), text, &mut loaded);
/// let r = harness::check::check_case(&loaded.cases[0], &Default::default());
/// assert!(r.passed);
/// assert_eq!(r.engines[0].verdict.label(), "agree");
/// ```
pub fn check_case(lc: &LoadedCase, set: &EngineSet) -> CaseResult {
    let (judged, referee) = (&set.judged, &set.referee);
    let truth = Truth::of(referee, lc);
    let has_expect = lc.case.expect.is_some();
    let mut results = Vec::new();
    let mut passed = false;
    let mut unanswered = false;
    for engine in judged {
        let r = judge_engine(engine, set, lc, &truth);
        if engine.name == set.gate {
            let expect_ok = r.expect_mismatches.as_ref().is_none_or(|m| m.is_empty());
            let referee_ok = matches!(r.verdict, Verdict::Agree | Verdict::Borderline { .. })
                || (truth.answer.is_none() && has_expect && r.answer.is_some());
            passed = r.answer.is_some() && expect_ok && referee_ok;
            unanswered = r.answer.is_none() && matches!(r.verdict, Verdict::Unsupported { .. });
        }
        results.push(r);
    }
    let referee_meets_expect = match (&truth.answer, has_expect) {
        (Some(t), true) => Some(judge::check_expect(lc, t).is_empty()),
        _ => None,
    };
    CaseResult {
        file: lc.file.display().to_string(),
        name: lc.case.name.clone(),
        query: lc.case.query,
        scale: truth.scale,
        margin: truth.margin,
        referee: truth.answer.as_ref().map(|a| truth.unique_expect(a)),
        referee_meets_expect,
        engines: results,
        passed,
        unanswered,
    }
}

/// The referee's side of one case: its answer (or why there is none), the
/// answer's length scale and the case's margin from its decision boundary.
#[derive(Clone, Debug)]
pub struct Truth {
    /// The referee's answer; `None` when it refused the input or the exact
    /// answer lies beyond `f64`'s range (its rounding would be ±∞, and no
    /// engine is graded against an infinity).
    pub answer: Option<Answer>,
    /// Why there is no answer.
    pub missing: String,
    /// The answer's own length scale (relative errors divide by it); the
    /// scene's when the referee gave no answer.
    pub scale: f64,
    /// The referee's signed margin from the nearest decision boundary.
    pub margin: Option<f64>,
    /// The sizes of the answer's fields ([`judge::sizes::local`]), taken once
    /// for every engine judged on the case; `None` without an answer.
    pub sizes: Option<judge::sizes::Local>,
    /// Other answers as right as `answer`, with their sizes: a distance whose
    /// least push is reached in several directions has one per other
    /// direction ([`judge::sizes::alternatives`]); an engine that disagrees
    /// with `answer` is judged against them too.
    pub alternatives: Vec<(Answer, judge::sizes::Local)>,
}

impl Truth {
    /// The referee's answer as a fixture's `expect`, keeping only what is
    /// unique: where other answers are as right (a distance's least push in
    /// several directions), its normal and witnesses are one choice among
    /// them and are left out; the distance and `degenerate` stay.
    pub fn unique_expect(&self, answer: &Answer) -> Expect {
        let mut e = answer_as_expect(answer);
        if !self.alternatives.is_empty() {
            e.normal = None;
            e.point_a = None;
            e.point_b = None;
        }
        e
    }

    /// The referee's answer to `lc`.
    pub fn of(referee: &Engine, lc: &LoadedCase) -> Truth {
        let (answer, missing) = match run_caught(referee, lc) {
            Ok(a) if judge::all_finite(&a) => (Some(a), String::new()),
            Ok(_) => (None, OUT_OF_RANGE.to_string()),
            Err(Verdict::Unsupported { reason }) | Err(Verdict::Failed { reason }) => (None, reason),
            Err(_) => (None, "the referee gave no answer".to_string()),
        };
        Truth::new(lc, answer, missing)
    }

    /// The truth of `lc` from the referee's `answer` (or why there is
    /// none): its scale, the case's margin and the answer's sizes.
    pub fn new(lc: &LoadedCase, answer: Option<Answer>, missing: String) -> Truth {
        let scale = answer.as_ref().map_or_else(|| judge::scene_scale(lc), |t| judge::answer_scale(lc, t));
        let sizes = answer.as_ref().map(|t| judge::sizes::local(lc, t));
        let alternatives = answer.as_ref().map_or_else(Vec::new, |t| judge::sizes::alternatives(lc, t));
        Truth { answer, missing, scale, margin: engines::referee::margin(lc), sizes, alternatives }
    }
}

/// One engine's answer to `lc`, judged against the referee's `truth` (and
/// the case's `expect`, when it has one); a disagreement the engine's known
/// divergences explain is a known divergence. For an `f32` engine that
/// disagrees, `referee` also answers the case rounded to `f32`
/// ([`EngineResult::rounding_explains`]).
pub fn judge_engine(engine: &Engine, set: &EngineSet, lc: &LoadedCase, truth: &Truth) -> EngineResult {
    let has_expect = lc.case.expect.is_some();
    let precision = engine.precision_for(lc);
    let tol = Tolerance::for_engine(precision, set.ulps);
    let mut rounding_explains = false;
    let (answer, verdict, errors, mism) = match run_caught(engine, lc) {
        Ok(a) => {
            let mism = has_expect.then(|| judge::check_expect(lc, &a));
            let (v, e) = match (&truth.answer, &truth.sizes) {
                (Some(t), Some(sizes)) => {
                    let (v, e) = judge::judge_sized(lc, &a, t, sizes, &tol, truth.margin);
                    // Disagreeing with the referee's first answer, the engine
                    // may have given another that is as right.
                    let (v, e) = match &v {
                        Verdict::Disagree { .. } => truth
                            .alternatives
                            .iter()
                            .map(|(alt, alt_sizes)| judge::judge_sized(lc, &a, alt, alt_sizes, &tol, truth.margin))
                            .find(|(v, _)| matches!(v, Verdict::Agree | Verdict::Borderline { .. }))
                            .unwrap_or((v, e)),
                        _ => (v, e),
                    };
                    match &v {
                        Verdict::Disagree { reasons } => match engine.known.explain(&engine.name, lc, &a, t, reasons) {
                            Some(reason) => (Verdict::KnownDivergence { reason }, e),
                            None => {
                                rounding_explains =
                                    precision == Some(F32_BITS) && agrees_rounded(&set.referee, lc, &a, &tol);
                                (v, e)
                            }
                        },
                        _ => (v, e),
                    }
                }
                _ => (Verdict::Unsupported { reason: truth.missing.clone() }, Errors::default()),
            };
            (Some(answer_as_expect(&a)), v, e, mism)
        }
        Err(v) => (None, v, Errors::default(), None),
    };
    EngineResult { engine: engine.name.clone(), answer, verdict, errors, expect_mismatches: mism, rounding_explains }
}

/// Bits of mantissa of `f32`: engines of this precision are given their
/// inputs rounded to it.
pub const F32_BITS: u32 = 24;

/// Whether `a` agrees (or is borderline) with the referee's answer to `lc`
/// with every input rounded to `f32` as an `f32` engine rounds it.
fn agrees_rounded(referee: &Engine, lc: &LoadedCase, a: &Answer, tol: &Tolerance) -> bool {
    let Some(rounded) = rounded_to_f32(lc) else { return false };
    let t = Truth::of(referee, &rounded);
    t.answer.as_ref().zip(t.sizes.as_ref()).is_some_and(|(t_ans, sizes)| {
        let (v, _) = judge::judge_sized(&rounded, a, t_ans, sizes, tol, t.margin);
        matches!(v, Verdict::Agree | Verdict::Borderline { .. })
    })
}

/// `lc` with every input number rounded to `f32` (a finite `t_max` beyond
/// `f32`'s range to its largest value, as the adapters do), or `None` when the
/// rounded case is no longer valid (a radius rounded to 0): what an `f32`
/// engine is given, in effect.
pub fn rounded_to_f32(lc: &LoadedCase) -> Option<LoadedCase> {
    let mut v = serde_json::to_value(&lc.case).ok()?;
    for path in crate::case::input_number_paths(&v) {
        let n = v.pointer_mut(&path)?;
        let x = n.as_f64()?;
        let y = x as f32;
        let y = if path == "/t_max" && x.is_finite() && !y.is_finite() { f32::MAX } else { y };
        // A number beyond f32's range leaves no case to answer.
        *n = serde_json::Number::from_f64(f64::from(y))?.into();
    }
    let case: crate::case::Case = serde_json::from_value(v).ok()?;
    let mut meshes = lc.meshes.clone();
    for x in meshes.iter_mut().flatten().flat_map(|m| m.vertices.iter_mut().flatten()) {
        *x = f64::from(*x as f32);
        if !x.is_finite() {
            return None;
        }
    }
    crate::load::validate(&case).ok()?;
    Some(LoadedCase { file: lc.file.clone(), case, meshes })
}

/// Checks every loaded case; `errors` are the input errors met while loading.
pub fn check(cases: &[LoadedCase], errors: &[InputError], set: &EngineSet) -> CheckResult {
    set.prefetch(cases);
    let results: Vec<CaseResult> = cases.iter().map(|lc| check_case(lc, set)).collect();
    let passed = results.iter().filter(|c| c.passed).count();
    let unanswered = results.iter().filter(|c| c.unanswered).count();
    CheckResult {
        gate: set.gate.clone(),
        unanswered,
        failed: results.len() - passed - unanswered,
        passed,
        cases: results,
        errors: errors.iter().map(|e| e.to_string()).collect(),
    }
}

fn fmt_err(x: Option<f64>) -> String {
    x.map(|v| format!("{v:.1e}")).unwrap_or_else(|| "-".into())
}

/// The human-readable report: a table per case, and last the line `N passed, M
/// failed` (cases, gate engine). The input errors are not in it: they are
/// for standard error ([`render_errors`]), so that a pipe of the results does
/// not carry them.
pub fn render_text(r: &CheckResult) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    for c in &r.cases {
        let _ = writeln!(
            s,
            "{} {} › {} [{}]{}",
            if c.passed { "PASS" } else { "FAIL" },
            c.file,
            c.name,
            c.query,
            match c.referee_meets_expect {
                Some(false) => "  (the referee does not meet this case's expectation)",
                _ => "",
            }
        );
        let _ = writeln!(
            s,
            "  {:<20} {:<11} {:<8} {:>8} {:>8} {:>8} {:>8} {:>8}",
            "engine", "referee", "expect", "point", "depth", "normal", "t", "bary"
        );
        for e in &c.engines {
            let expect = match &e.expect_mismatches {
                None => "-",
                Some(m) if m.is_empty() => "ok",
                Some(_) => "MISMATCH",
            };
            let _ = writeln!(
                s,
                "  {:<20} {:<11} {:<8} {:>8} {:>8} {:>8} {:>8} {:>8}",
                e.engine,
                e.verdict.label(),
                expect,
                fmt_err(e.errors.point),
                fmt_err(e.errors.depth),
                fmt_err(e.errors.normal),
                fmt_err(e.errors.t),
                fmt_err(e.errors.barycentric)
            );
            if e.engine == r.gate || !c.passed {
                for m in e.expect_mismatches.iter().flatten() {
                    let _ = writeln!(s, "      expect.{}: want {}, got {}", m.field, m.expected, m.got);
                }
            }
            match &e.verdict {
                Verdict::Disagree { reasons } | Verdict::Borderline { reasons } if e.engine == r.gate => {
                    for why in reasons {
                        let _ = writeln!(s, "      {why}");
                    }
                }
                Verdict::Failed { reason } | Verdict::Unsupported { reason } if e.engine == r.gate => {
                    let _ = writeln!(s, "      {reason}");
                }
                _ => {}
            }
        }
    }
    s.push_str(&closing_line(r));
    s
}

/// The closing line, `N passed, M failed (gate: E)`, with `K not answered by
/// the gate` before the parenthesis when the gate does not answer some cases.
pub fn closing_line(r: &CheckResult) -> String {
    let unanswered =
        if r.unanswered > 0 { format!(", {} not answered by the gate", r.unanswered) } else { String::new() };
    format!("{} passed, {} failed{unanswered} (gate: {})\n", r.passed, r.failed, r.gate)
}

/// The input errors, one `error:` line each.
pub fn render_errors(r: &CheckResult) -> String {
    r.errors.iter().map(|e| format!("error: {e}\n")).collect()
}
