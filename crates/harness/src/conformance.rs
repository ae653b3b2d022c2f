//! `crashtest engine test COMMAND`: the conformance run of a process engine —
//! the handshake, the fixture corpus judged against the referee, and
//! malformed-case probes — and what it found: what the engine supports, how it
//! scores per query, and every protocol violation.

use crate::check::check;
use crate::engine::Engine;
use crate::engines::EngineSet;
use crate::load::Loaded;
use crate::protocol::client::{Outcome, ProcessEngine, ProcessSpec};
use crate::protocol::messages::Capability;
use std::collections::BTreeMap;
use std::fmt::Write;

/// A malformed case crashtest never sends in a run, and what it breaks. The
/// engine should answer each with `error` or `unsupported`; one that answers it
/// is shown doing so, and one that exits, hangs or breaks the protocol on it
/// has committed a protocol violation.
pub const PROBES: [(&str, &str); 6] = [
    (
        "a sphere of negative radius",
        r#"{"name":"probe: negative radius","query":"contact","a":{"sphere":{"center":[0,0,0],"radius":-1}},"b":{"sphere":{"center":[1,0,0],"radius":1}}}"#,
    ),
    (
        "a zero plane normal",
        r#"{"name":"probe: zero normal","query":"contact","a":{"sphere":{"center":[0,0,0],"radius":1}},"b":{"plane":{"normal":[0,0,0],"offset":0}}}"#,
    ),
    (
        "a shape kind the format does not have",
        r#"{"name":"probe: unknown shape","query":"contact","a":{"capsule":{"a":[0,0,0],"b":[1,0,0],"radius":1}},"b":{"sphere":{"center":[1,0,0],"radius":1}}}"#,
    ),
    (
        "a pair the query does not take",
        r#"{"name":"probe: overlap of spheres","query":"overlap","a":{"sphere":{"center":[0,0,0],"radius":1}},"b":{"sphere":{"center":[1,0,0],"radius":1}}}"#,
    ),
    (
        "a mesh face indexing past its vertices",
        r#"{"name":"probe: mesh index","query":"intersect","a":{"segment":{"start":[0,0,1],"end":[0,0,-1]}},"b":{"mesh":{"vertices":[[0,0,0],[1,0,0],[0,1,0]],"triangles":[[0,1,7]]}}}"#,
    ),
    (
        "a case with no second shape",
        r#"{"name":"probe: no b","query":"contact","a":{"sphere":{"center":[0,0,0],"radius":1}}}"#,
    ),
];

/// One probe's outcome.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Probe {
    /// What the probe breaks.
    pub what: String,
    /// What the engine said (`error: …`, `unsupported: …`, or the fault).
    pub said: String,
    /// Whether the reply kept to the protocol (an entry, not a fault).
    pub ok: bool,
}

/// What the conformance run found.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Conformance {
    /// The command.
    pub command: String,
    /// The hello, as received (absent when the handshake failed).
    pub hello: Option<crate::protocol::messages::EngineHello>,
    /// Its capabilities as pairs of the table (`query a–b`).
    pub supports: Vec<String>,
    /// Per query: verdict label → count, over the fixture corpus.
    pub scores: BTreeMap<String, BTreeMap<String, usize>>,
    /// Fixture cases sent.
    pub cases: usize,
    /// The probes.
    pub probes: Vec<Probe>,
    /// Every protocol violation seen (faults of the process, capabilities
    /// outside the table, probes answered wrongly).
    pub violations: Vec<String>,
}

impl Conformance {
    /// 0 when the engine broke no rule of the protocol, 1 otherwise.
    pub fn exit_code(&self) -> i32 {
        i32::from(!self.violations.is_empty())
    }
}

/// Runs the conformance test of the engine `spec` on the fixture cases `loaded`.
pub fn run(spec: ProcessSpec, loaded: &Loaded) -> Conformance {
    let command = spec.command_line();
    let engine = Engine::from_process(ProcessEngine::start(spec));
    let Some(p) = engine.process() else {
        // `from_process` always makes a process engine; said, not panicked.
        let violations = vec!["the engine is not a process engine".to_string()];
        let (supports, scores, probes) = (Vec::new(), BTreeMap::new(), Vec::new());
        return Conformance { command, hello: None, supports, scores, cases: 0, probes, violations };
    };
    let hello = p.hello();
    let mut violations = Vec::new();
    let mut supports = Vec::new();
    if let Some(h) = &hello {
        for c in &h.capabilities {
            match c.pair() {
                Some(pair) => supports.push(pair_name(pair)),
                None => violations.push(format!("capability {} is not a pair of the table", capability_name(c))),
            }
        }
    }
    let mut scores: BTreeMap<String, BTreeMap<String, usize>> = BTreeMap::new();
    let mut probes = Vec::new();
    if p.down().is_none() {
        let name = engine.name.clone();
        let set = EngineSet::of(vec![engine.clone()]);
        let result = check(&loaded.cases, &loaded.errors, &set);
        for c in &result.cases {
            for r in c.engines.iter().filter(|r| r.engine == name) {
                *scores.entry(c.query.to_string()).or_default().entry(r.verdict.label().to_string()).or_default() += 1;
            }
        }
        for (what, json) in PROBES {
            let (reply, fault) = p.ask_raw(json);
            let (said, ok) = match reply.outcome {
                Outcome::Failed(m) if fault => (format!("FAULT: {m}"), false),
                Outcome::Failed(m) => (format!("error: {m}"), true),
                Outcome::Unsupported(u) => (format!("unsupported: {u}"), true),
                // Not a protocol violation: the engine does not refuse input
                // the format refuses, which the report of the probes shows.
                Outcome::Answer(a) => (format!("answered, not refused: {a:?}"), true),
            };
            if !ok {
                violations.push(format!("probe `{what}`: {said}"));
            }
            probes.push(Probe { what: what.into(), said, ok });
        }
    }
    let info = p.info();
    for f in &info.faults {
        violations.push(f.clone());
    }
    if let Some(d) = info.down {
        violations.push(format!("the engine is down: {d}"));
    }
    violations.dedup();
    Conformance { command, hello, supports, scores, cases: loaded.cases.len(), probes, violations }
}

fn pair_name(pair: crashtest_core::pair::Pair) -> String {
    let r = pair.row();
    match r.b {
        Some(b) => format!("{} {}–{}", r.query, r.a, b),
        None => format!("{} {}", r.query, r.a),
    }
}

fn capability_name(c: &Capability) -> String {
    serde_json::to_string(c).unwrap_or_default()
}

/// The conformance run as text.
pub fn render(c: &Conformance) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "engine test: {}", c.command);
    match &c.hello {
        Some(h) => {
            let _ = writeln!(
                out,
                "hello: {} {} (precision {} bits), protocol {}",
                h.name,
                h.version.as_deref().unwrap_or("(no version)"),
                h.precision,
                h.protocol
            );
            for (k, v) in &h.provenance {
                let _ = writeln!(out, "  {k}: {v}");
            }
        }
        None => {
            let _ = writeln!(out, "hello: none");
        }
    }
    let _ = writeln!(out, "supports ({}): {}", c.supports.len(), c.supports.join(", "));
    let _ = writeln!(out, "fixture cases: {} (judged against the referee)", c.cases);
    let labels = ["agree", "borderline", "known", "DISAGREE", "unsupported", "FAILED"];
    let _ = writeln!(out, "  {:<12}{}", "query", labels.iter().map(|l| format!("{l:>12}")).collect::<String>());
    for (q, counts) in &c.scores {
        let cells: String = labels.iter().map(|l| format!("{:>12}", counts.get(*l).copied().unwrap_or(0))).collect();
        let _ = writeln!(out, "  {q:<12}{cells}");
    }
    let _ = writeln!(out, "malformed-case probes:");
    for p in &c.probes {
        let _ = writeln!(out, "  {} {}: {}", if p.ok { "ok   " } else { "FAULT" }, p.what, p.said);
    }
    if c.violations.is_empty() {
        let _ = writeln!(out, "protocol violations: none");
    } else {
        let _ = writeln!(out, "protocol violations: {}", c.violations.len());
        for v in &c.violations {
            let _ = writeln!(out, "  {v}");
        }
    }
    out
}
