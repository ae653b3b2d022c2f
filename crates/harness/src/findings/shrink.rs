//! Shrinking a finding's case: the simplest case that still shows the same
//! defect.
//!
//! A candidate replaces the case by a simpler one — a number by 0, by a small
//! integer, by a short dyadic fraction (fewer significant bits), or by
//! another number already in the case (fewer distinct values); every length
//! scaled by a power of two (exact: the geometry is the same, smaller); the
//! scene moved toward the origin; half of a mesh's faces or of a point
//! cloud's points dropped — and is kept when it is simpler by [`cost`] and
//! the referee still gives the finding's signature ([`Signature::same_defect`])
//! for the engine's answer. Candidates are tried in a fixed order, so
//! shrinking is deterministic; it stops when a whole pass keeps nothing, or
//! after [`MAX_EVALUATIONS`] candidates ([`MAX_FAILED_PROCESS_EVALUATIONS`]
//! for a process engine's crash or hang). Every kept candidate lowers the cost,
//! a non-negative integer, so it ends.

use super::signature::{Cause, Signature, cause_of, signature};
use crate::case::SCHEMA;
use crate::check::{EngineResult, Truth, judge_engine};
use crate::engine::Engine;
use crate::engines::EngineSet;
use crate::load::{Loaded, LoadedCase, load_str_into};
use serde_json::Value;

/// Candidates judged per finding at most: a sphere–triangle case has 13
/// numbers and about ten candidates each, so this allows one and a half full
/// passes (a process engine's candidate counts [`STABLE_CHECKS`] times). The
/// referee's slowest queries (a full-range distance, a time of impact
/// against a mesh) take several milliseconds, so one finding costs at most a
/// second or two. Measured on the default report: at 400, 41 of its 348
/// shrunk findings stopped at the cap and shrinking took 47 s; at 200 it took
/// 36 s, and the 81 findings that had judged more than 200 candidates ended
/// 7% above the cost they reached at 400 (1,313,372 against 1,227,032, from
/// 1,490,487).
pub const MAX_EVALUATIONS: u32 = 200;

/// Candidates judged at most for a process engine's failure (a crash, or no
/// answer within the engine's own time limit): each judgement of a case that
/// hangs costs that limit (FCL's distance worker waits 0.25 s), so the
/// shrinking of one such finding stays within seconds.
pub const MAX_FAILED_PROCESS_EVALUATIONS: u32 = 24;

/// How often a shrunk case is judged again after shrinking: an engine that
/// answers the same case differently between calls (FCL's continuous
/// collision does, on some cases) shows the defect in only some of them, and
/// the finding says how many.
pub const REPLAYS: u32 = 5;

/// Judgements a process engine's candidate must pass, each showing the defect.
pub const STABLE_CHECKS: u32 = 3;

/// Whether one judgement of `lc` shows the defect of `sig` with the same
/// root cause `cause` (a case of an engine's precision stays one).
pub fn shows(lc: &LoadedCase, sig: &Signature, cause: &Cause, engine: &Engine, set: &EngineSet) -> bool {
    let (s, r, _) = judge_one(engine, set, lc);
    s.is_some_and(|s| s.same_defect(sig) && cause_of(&s, lc, Some(engine), &r) == *cause)
}

/// How many of [`REPLAYS`] judgements of `lc` show the defect of `sig` with
/// its cause.
pub fn replays(lc: &LoadedCase, sig: &Signature, cause: &Cause, engine: &Engine, set: &EngineSet) -> u32 {
    (0..REPLAYS).filter(|_| shows(lc, sig, cause, engine, set)).count() as u32
}

/// The numbers a case is shrunk over: its inputs, as JSON pointers into the
/// case (face indices are not numbers to shrink: faces are dropped whole).
fn slots(v: &Value) -> Vec<String> {
    crate::case::input_number_paths(v)
}

fn num(v: &Value, p: &str) -> Option<f64> {
    v.pointer(p).and_then(Value::as_f64)
}

fn set(v: &mut Value, p: &str, x: f64) -> bool {
    match (v.pointer_mut(p), serde_json::Number::from_f64(x)) {
        (Some(slot), Some(n)) => {
            *slot = Value::Number(n);
            true
        }
        _ => false,
    }
}

/// How complicated one number is: 0 for +0 (1 for −0); otherwise one, plus its
/// significant bits, plus how far its binary exponent is from 0 (1 and 0.5
/// are simple, 1e300 and 3.2918… are not).
pub fn number_cost(x: f64) -> u64 {
    if x == 0.0 {
        // −0 reads as a question about signed zeros: +0 is simpler.
        return u64::from(x.is_sign_negative());
    }
    if !x.is_finite() {
        return 2000;
    }
    let bits = x.abs().to_bits();
    let (exp, mant) = ((bits >> 52) as i64, bits & ((1u64 << 52) - 1));
    let (e, m) =
        if exp == 0 { (-1074 + 63 - mant.leading_zeros() as i64, mant) } else { (exp - 1023, mant | (1 << 52)) };
    let significant = 64 - m.leading_zeros() as u64 - m.trailing_zeros() as u64;
    1 + significant + e.unsigned_abs()
}

/// The case's cost: each number's [`number_cost`], plus 8 per distinct
/// magnitude (fewer distinct values read faster) and 16 per number (fewer
/// faces and points are simpler). Lower is simpler.
pub fn cost(v: &Value) -> u64 {
    let xs: Vec<f64> = slots(v).iter().filter_map(|p| num(v, p)).collect();
    let mut distinct: Vec<u64> = xs.iter().filter(|x| **x != 0.0).map(|x| x.abs().to_bits()).collect();
    distinct.sort_unstable();
    distinct.dedup();
    xs.iter().map(|&x| number_cost(x)).sum::<u64>() + 8 * distinct.len() as u64 + 16 * xs.len() as u64
}

/// `x` rounded to `k` significant bits.
fn round_bits(x: f64, k: u32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let e = x.abs().log2().floor() as i32;
    let q = 2f64.powi(e - k as i32 + 1);
    if !(q.is_finite() && q > 0.0) {
        return x;
    }
    let r = (x / q).round() * q;
    if r.is_finite() { r } else { x }
}

/// Simpler numbers for `x`, simplest first: 0, numbers already in the case,
/// the nearest integer, and `x` with fewer significant bits.
fn number_candidates(x: f64, present: &[f64]) -> Vec<f64> {
    let mut c = vec![0.0];
    c.extend(present.iter().copied());
    if x.abs() < 9.0e15 {
        c.push(x.round());
    }
    for k in [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 40] {
        c.push(round_bits(x, k));
    }
    let base = number_cost(x);
    c.retain(|y| y.is_finite() && y.to_bits() != x.to_bits() && number_cost(*y) < base);
    c.sort_by(|a, b| number_cost(*a).cmp(&number_cost(*b)).then(a.total_cmp(b)));
    c.dedup_by(|a, b| a.to_bits() == b.to_bits());
    c
}

/// The keys of a shape's fields that are lengths (scaled with the scene) and
/// positions (moved with it).
const LENGTH_KEYS: [&str; 11] =
    ["center", "radius", "velocity", "offset", "start", "end", "vertices", "at", "points", "min", "max"];
const POSITION_KEYS: [&str; 8] = ["center", "start", "end", "vertices", "at", "points", "min", "max"];

/// Whether the pointer goes through one of `keys` (a shape's field).
fn under(p: &str, keys: &[&str]) -> bool {
    p.split('/').nth(3).is_some_and(|k| keys.contains(&k))
}

/// The case with every length multiplied by `f` (a power of two: exact
/// unless it leaves the range).
fn scaled(v: &Value, f: f64) -> Option<Value> {
    let mut out = v.clone();
    for p in slots(v).iter().filter(|p| under(p, &LENGTH_KEYS)) {
        let x = num(v, p)? * f;
        if !x.is_finite() || !set(&mut out, p, x) {
            return None;
        }
    }
    Some(out)
}

/// The case moved by `-t` (positions, and a plane's offset by `n · t`).
fn moved(v: &Value, t: [f64; 3]) -> Option<Value> {
    let mut out = v.clone();
    for p in slots(v).iter().filter(|p| under(p, &POSITION_KEYS)) {
        let i: usize = p.rsplit('/').next()?.parse().ok()?;
        if !set(&mut out, p, num(v, p)? - t[i % 3]) {
            return None;
        }
    }
    for key in ["a", "b"] {
        if let Some(n) = v.pointer(&format!("/{key}/plane/normal")).and_then(Value::as_array) {
            let n: Vec<f64> = n.iter().filter_map(Value::as_f64).collect();
            let p = format!("/{key}/plane/offset");
            let d = num(v, &p)? - (n.first()? * t[0] + n.get(1)? * t[1] + n.get(2)? * t[2]);
            if !set(&mut out, &p, d) {
                return None;
            }
        }
    }
    Some(out)
}

/// The first position in the case (a sphere's centre, a segment's start, …).
fn first_position(v: &Value) -> Option<[f64; 3]> {
    let p = slots(v).into_iter().find(|p| under(p, &POSITION_KEYS))?;
    let base = p.rsplit_once('/')?.0.to_string();
    Some([num(v, &format!("{base}/0"))?, num(v, &format!("{base}/1"))?, num(v, &format!("{base}/2"))?])
}

/// A mesh keeping only the faces in `keep` (and their vertices, renumbered).
fn mesh_subset(mesh: &Value, keep: std::ops::Range<usize>) -> Option<Value> {
    let tris = mesh.get("triangles")?.as_array()?;
    let verts = mesh.get("vertices")?.as_array()?;
    let mut map = std::collections::BTreeMap::new();
    let mut new_tris = Vec::new();
    let mut new_verts = Vec::new();
    for t in tris.get(keep)? {
        let mut nt = Vec::new();
        for i in t.as_array()? {
            let i = i.as_u64()? as usize;
            let j = *map.entry(i).or_insert_with(|| {
                new_verts.push(verts.get(i).cloned().unwrap_or(Value::Null));
                new_verts.len() - 1
            });
            nt.push(Value::from(j));
        }
        new_tris.push(Value::Array(nt));
    }
    let mut out = mesh.clone();
    out["triangles"] = Value::Array(new_tris);
    out["vertices"] = Value::Array(new_verts);
    Some(out)
}

/// Whole-case candidates: halves of a mesh's faces or a cloud's points, the
/// scene scaled toward unit size, moved toward the origin.
fn case_candidates(v: &Value) -> Vec<Value> {
    let mut out = Vec::new();
    for key in ["a", "b"] {
        if let Some(mesh) = v.pointer(&format!("/{key}/mesh")) {
            let n = mesh.get("triangles").and_then(Value::as_array).map_or(0, Vec::len);
            if n > 1 {
                for r in [0..n / 2, n / 2..n] {
                    if let Some(m) = mesh_subset(mesh, r) {
                        let mut c = v.clone();
                        c[key]["mesh"] = m;
                        out.push(c);
                    }
                }
            }
        }
        if let Some(points) = v.pointer(&format!("/{key}/points/points")).and_then(Value::as_array) {
            let n = points.len();
            if n > 1 {
                for r in [0..n / 2, n / 2..n] {
                    let mut c = v.clone();
                    c[key]["points"]["points"] = Value::Array(points[r].to_vec());
                    out.push(c);
                }
            }
        }
    }
    let largest = slots(v)
        .iter()
        .filter(|p| under(p, &LENGTH_KEYS))
        .filter_map(|p| num(v, p))
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if largest > 0.0 && largest.is_finite() {
        let e = largest.log2().floor() as i32;
        for k in [e, 1, -1] {
            if k != 0
                && let Some(c) = scaled(v, 2f64.powi(-k))
            {
                out.push(c);
            }
        }
    }
    if let Some(t) = first_position(v) {
        for bits in [1, 4, 16] {
            let t = t.map(|x| round_bits(x, bits));
            if t.iter().any(|x| *x != 0.0)
                && let Some(c) = moved(v, t)
            {
                out.push(c);
            }
        }
    }
    out
}

/// The case a JSON value denotes, loaded as a fixture would be (its checks
/// applied); `None` when it is no valid case.
fn load(v: &Value, file: &std::path::Path) -> Option<LoadedCase> {
    let text = serde_json::to_string(&serde_json::json!({ "schema": SCHEMA, "cases": [v] })).ok()?;
    let mut loaded = Loaded::default();
    load_str_into(file, &text, &mut loaded);
    if !loaded.errors.is_empty() {
        return None;
    }
    loaded.cases.pop()
}

/// One engine's result on a case and its signature.
///
/// A process engine is asked anew each time (its answer to `lc` from an earlier
/// judgement is forgotten first), so repeated judgements are independent: an
/// engine that answers one input differently from call to call shows it.
pub fn judge_one(engine: &Engine, set: &EngineSet, lc: &LoadedCase) -> (Option<Signature>, EngineResult, Truth) {
    engine.forget_case(lc);
    let truth = truth_of(set, lc);
    let r = judge_engine(engine, set, lc, &truth);
    let misclassified = r.errors.misclass.is_some() || matches!(r.verdict, crate::judge::Verdict::Failed { .. });
    let headline = if misclassified { 1.0 } else { crate::judge::headline(&r.errors, truth.scale) };
    (signature(lc, &r, headline), r, truth)
}

/// Cases whose truths [`truth_of`] keeps at most: 4,096. Reason: a finding's
/// shrinking judges at most [`MAX_EVALUATIONS`] candidates, and the findings
/// that share candidates are shrunk side by side, so this holds all of several
/// findings' candidates; beyond it the memory is emptied and starts again.
pub const TRUTH_CACHE_CASES: usize = 4096;

/// The referee's truths of the cases judged while shrinking, by the case's
/// input (its name, source, expectation and tolerance left out): one engine's
/// candidate is often another's — Coal's three GJK variants, FCL's two solvers
/// and collide's two methods shrink the same case along the same path — and a
/// process engine's candidate is judged [`STABLE_CHECKS`] times.
type TruthCache = std::sync::Mutex<std::collections::HashMap<String, Truth>>;

fn truth_cache() -> &'static TruthCache {
    static CACHE: std::sync::OnceLock<TruthCache> = std::sync::OnceLock::new();
    CACHE.get_or_init(Default::default)
}

/// The referee's truth of `lc`, computed once per input (see [`TruthCache`]).
fn truth_of(set: &EngineSet, lc: &LoadedCase) -> Truth {
    let c = &lc.case;
    let key = serde_json::to_string(&(&set.referee.name, c.query, &c.a, &c.b, c.t_max, c.restitution)).ok();
    let lock = || truth_cache().lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(t) = key.as_ref().and_then(|k| lock().get(k).cloned()) {
        return t;
    }
    let truth = Truth::of(&set.referee, lc);
    if let Some(k) = key {
        let mut cache = lock();
        if cache.len() >= TRUTH_CACHE_CASES {
            cache.clear();
        }
        cache.insert(k, truth.clone());
    }
    truth
}

/// What shrinking gave.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The simplest case found (the original when nothing simpler kept the signature).
    pub case: LoadedCase,
    /// Numbers before and after.
    pub numbers: (usize, usize),
    /// [`cost`] before and after.
    pub cost: (u64, u64),
    /// Candidates judged.
    pub evaluations: u32,
}

/// Shrinks `lc` while `engine`'s answer, judged against `referee`, keeps the
/// defect of `sig`. The case keeps its name; its source says it was shrunk
/// and from what (so its family stays the original's).
pub fn shrink(lc: &LoadedCase, sig: &Signature, cause: &Cause, engine: &Engine, judge: &EngineSet) -> Outcome {
    let Ok(mut best) = serde_json::to_value(&lc.case) else {
        return Outcome { case: lc.clone(), numbers: (0, 0), cost: (0, 0), evaluations: 0 };
    };
    if let Some(o) = best.as_object_mut() {
        o.remove("expect");
        o.remove("tol");
    }
    let start_cost = cost(&best);
    let start_numbers = slots(&best).len();
    let mut best_cost = start_cost;
    let mut best_case = lc.clone();
    let mut evaluations = 0u32;
    // A process engine may answer one case differently between calls (FCL's
    // distance on a degenerate triangle does, about half the time): its
    // candidate must show the defect in every one of STABLE_CHECKS judgements.
    let checks = if engine.process().is_some() { STABLE_CHECKS } else { 1 };
    let most = if engine.process().is_some() && sig.wrong.starts_with("failed") {
        MAX_FAILED_PROCESS_EVALUATIONS
    } else {
        MAX_EVALUATIONS
    };
    let keeps = |c: &Value, evaluations: &mut u32| -> Option<LoadedCase> {
        let cand = load(c, &lc.file)?;
        for _ in 0..checks {
            *evaluations += 1;
            if !shows(&cand, sig, cause, engine, judge) {
                return None;
            }
        }
        Some(cand)
    };
    'passes: loop {
        let mut kept = false;
        for c in case_candidates(&best) {
            if evaluations >= most {
                break 'passes;
            }
            let k = cost(&c);
            if k < best_cost
                && let Some(lc) = keeps(&c, &mut evaluations)
            {
                (best, best_cost, best_case, kept) = (c, k, lc, true);
            }
        }
        for p in slots(&best) {
            let Some(x) = num(&best, &p) else { continue };
            let mut present: Vec<f64> = slots(&best).iter().filter_map(|q| num(&best, q)).collect();
            present.sort_by(f64::total_cmp);
            present.dedup();
            for y in number_candidates(x, &present) {
                if evaluations >= most {
                    break 'passes;
                }
                let mut c = best.clone();
                if !set(&mut c, &p, y) {
                    continue;
                }
                let k = cost(&c);
                if k >= best_cost {
                    continue;
                }
                if let Some(lc) = keeps(&c, &mut evaluations) {
                    (best, best_cost, best_case, kept) = (c, k, lc, true);
                    break;
                }
            }
        }
        if !kept {
            break;
        }
    }
    if best_cost < start_cost {
        best_case.case.source = format!("shrunk by `crashtest report` from {}", lc.case.source);
    }
    Outcome {
        case: best_case,
        numbers: (start_numbers, slots(&best).len()),
        cost: (start_cost, best_cost),
        evaluations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_numbers_cost_less() {
        assert_eq!(number_cost(0.0), 0);
        assert!(number_cost(-0.0) > number_cost(0.0));
        assert!(number_cost(1.0) < number_cost(3.0));
        assert!(number_cost(3.0) < number_cost(3.2918));
        assert!(number_cost(0.5) < number_cost(0.1));
        assert!(number_cost(1.0) < number_cost(1e300));
        assert!(number_cost(1.0) < number_cost(5e-324));
        assert!(number_cost(f64::MIN_POSITIVE) > number_cost(1.0));
    }

    #[test]
    fn candidates_are_simpler_and_simplest_first() {
        let c = number_candidates(3.2918, &[1.0, 7.25]);
        assert_eq!(c[0].to_bits(), 0.0f64.to_bits());
        assert!(c.iter().all(|y| number_cost(*y) < number_cost(3.2918)));
        assert!(c.windows(2).all(|w| number_cost(w[0]) <= number_cost(w[1])));
        assert!(c.contains(&3.0) && c.contains(&1.0));
    }

    #[test]
    fn rounding_to_few_bits_gives_short_dyadic_fractions() {
        assert_eq!(round_bits(3.2918, 2).to_bits(), 3.0f64.to_bits());
        assert_eq!(round_bits(3.2918, 4).to_bits(), 3.25f64.to_bits());
        assert_eq!(round_bits(-0.3, 1).to_bits(), (-0.25f64).to_bits());
    }

    #[test]
    fn the_truth_kept_is_the_inputs_own_whatever_the_cases_name() {
        let set = EngineSet::new(crate::engines::judged(), "collide/robust").expect("the built-in set");
        let case = |name: &str, x: f64| {
            let v = serde_json::json!({"name": name, "source": "a test", "query": "distance",
                "a": {"sphere": {"center": [x, 0.0, 0.0], "radius": 1.0}},
                "b": {"sphere": {"center": [0.0, 0.0, 0.0], "radius": 1.0}}});
            load(&v, std::path::Path::new("test")).expect("a valid case")
        };
        let distance = |t: &Truth| match &t.answer {
            Some(crate::engine::Answer::Distance(d)) => d.distance,
            other => panic!("no distance: {other:?}"),
        };
        // Spheres 3 and 5 apart: separations 1 and 3, exact in f64.
        let (a, renamed, other) = (case("one", 3.0), case("two", 3.0), case("one", 5.0));
        for _ in 0..2 {
            assert_eq!(distance(&truth_of(&set, &a)).to_bits(), 1.0f64.to_bits());
            assert_eq!(distance(&truth_of(&set, &renamed)).to_bits(), 1.0f64.to_bits());
            assert_eq!(distance(&truth_of(&set, &other)).to_bits(), 3.0f64.to_bits());
        }
    }

    #[test]
    fn a_mesh_subset_renumbers_its_vertices() {
        let m = serde_json::json!({"vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "triangles": [[0,1,2],[1,2,3]]});
        let s = mesh_subset(&m, 1..2).unwrap();
        assert_eq!(s["triangles"], serde_json::json!([[0, 1, 2]]));
        assert_eq!(s["vertices"], serde_json::json!([[1, 0, 0], [0, 1, 0], [0, 0, 1]]));
    }
}
