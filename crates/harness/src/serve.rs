//! An in-process engine served over `crashtest-engine/1` (`docs/PROTOCOL.md`):
//! what `crashtest-engine-collide` runs, and what a Rust engine's author can run
//! to put their engine behind the protocol.
//!
//! Each answer is written in the shortest form that reads back to the same f64,
//! so an engine judged through the protocol is judged on exactly the bits it
//! computed (a test compares collide through the protocol with collide in
//! process, bit for bit).

use crate::case::Shape;
use crate::check::run_caught;
use crate::engine::Engine;
use crate::judge::Verdict;
use crate::load::LoadedCase;
use crate::mesh::Mesh;
use crate::protocol::messages::{
    Capability, EngineHello, Entry, FromEngine, PROTOCOL, ToEngine, WireCase, read_to_engine,
};
use crashtest_core::pair::Pair;
use std::collections::BTreeMap;
use std::io::{BufRead, Write};
use std::path::PathBuf;
use std::time::Instant;

/// What a served engine says of itself beyond its name and precision.
#[derive(Clone, Debug, Default)]
pub struct Served {
    /// Its version.
    pub version: Option<String>,
    /// The pairs it answers.
    pub capabilities: Vec<Pair>,
    /// What the report's provenance should echo.
    pub provenance: BTreeMap<String, String>,
}

/// Serves `engine` on `input` and `output` until `shutdown` or the end of
/// the input. A line that is not a message is answered on standard error and
/// skipped (crashtest never sends one). Returns the output's error, if writing
/// failed.
///
/// ```
/// use harness::serve::{Served, serve};
/// let engine = harness::engines::judged().remove(0);
/// let served = Served { capabilities: crashtest_core::pair::Pair::ALL.to_vec(), ..Default::default() };
/// let input = concat!(
///     r#"{"type":"hello","protocol":"crashtest-engine/1"}"#, "\n",
///     r#"{"type":"batch","id":1,"cases":[{"name":"c","query":"overlap","a":{"aabb":{"min":[0,0,0],"max":[1,1,1]}},"b":{"aabb":{"min":[2,0,0],"max":[3,1,1]}}}]}"#, "\n",
///     r#"{"type":"shutdown"}"#, "\n",
/// );
/// let mut out = Vec::new();
/// serve(&engine, &served, input.as_bytes(), &mut out).unwrap();
/// let out = String::from_utf8(out).unwrap();
/// assert!(out.lines().nth(1).unwrap().contains(r#""answer":{"overlap":false}"#), "{out}");
/// ```
pub fn serve(engine: &Engine, served: &Served, mut input: impl BufRead, mut output: impl Write) -> std::io::Result<()> {
    // One line buffer and one output buffer for the whole session: a batch's
    // line is hundreds of kilobytes, and a fresh one each time costs page
    // faults.
    let mut line = String::new();
    let mut text = Vec::new();
    loop {
        line.clear();
        if input.read_line(&mut line)? == 0 {
            return Ok(());
        }
        if line.trim().is_empty() {
            continue;
        }
        let reply = match read_to_engine(line.trim_end()) {
            Ok(ToEngine::Hello { .. }) => FromEngine::Hello(hello_of(engine, served)),
            Ok(ToEngine::Batch { id, cases }) => {
                FromEngine::Answers { id, answers: cases.into_iter().map(|c| answer(engine, c)).collect(), ns: None }
            }
            Ok(ToEngine::World(w)) => FromEngine::World(crate::protocol::messages::WorldReply {
                id: w.id,
                error: Some(format!("{} answers queries and does not step worlds", engine.name)),
                ..Default::default()
            }),
            Ok(ToEngine::Shutdown) => return Ok(()),
            // A batch with a case this engine cannot read (crashtest sends none:
            // the conformance run's probes do): an error for that case, an
            // answer for the others.
            Err(e) => match case_by_case(engine, &line) {
                Some(reply) => reply,
                None => {
                    eprintln!("{}: not a message: {e}", engine.name);
                    continue;
                }
            },
        };
        text.clear();
        serde_json::to_writer(&mut text, &reply).map_err(std::io::Error::other)?;
        text.push(b'\n');
        output.write_all(&text)?;
        output.flush()?;
    }
}

/// A batch read case by case: each case that does not read is answered with
/// the error that says why. `None` when the line is not a batch at all.
fn case_by_case(engine: &Engine, line: &str) -> Option<FromEngine> {
    let v: serde_json::Value = serde_json::from_str(line).ok()?;
    if v.get("type")?.as_str()? != "batch" {
        return None;
    }
    let id = v.get("id")?.as_u64()?;
    let answers = v
        .get("cases")?
        .as_array()?
        .iter()
        .map(|c| match serde_json::from_value::<WireCase>(c.clone()) {
            Ok(w) => answer(engine, w),
            Err(e) => Entry { error: Some(format!("the case does not read: {e}")), ..Default::default() },
        })
        .collect();
    Some(FromEngine::Answers { id, answers, ns: None })
}

/// The hello a served engine gives (for tests and the conformance run).
pub fn hello_of(engine: &Engine, served: &Served) -> EngineHello {
    EngineHello {
        protocol: PROTOCOL.into(),
        name: engine.name.clone(),
        version: served.version.clone(),
        precision: engine.precision.unwrap_or(53),
        capabilities: served.capabilities.iter().map(|p| Capability::of(*p)).collect(),
        provenance: served.provenance.clone(),
        worlds: false,
        reproductions: Vec::new(),
    }
}

/// One case's entry: the answer, `unsupported`, or the error (a caught panic,
/// a non-finite number, a mesh that does not hold together).
fn answer(engine: &Engine, wire: WireCase) -> Entry {
    let lc = match loaded(wire) {
        Ok(lc) => lc,
        Err(e) => return Entry { error: Some(e), ..Default::default() },
    };
    let start = Instant::now();
    let result = run_caught(engine, &lc);
    let ns = Some(start.elapsed().as_nanos() as f64);
    match result {
        Ok(a) if crate::judge::all_finite(&a) => Entry::answer(&a, ns),
        Ok(_) => Entry { error: Some("non-finite number in the answer".into()), ns, ..Default::default() },
        Err(Verdict::Unsupported { reason }) => Entry { unsupported: Some(reason), ns, ..Default::default() },
        Err(v) => Entry { error: Some(format!("{v:?}")), ns, ..Default::default() },
    }
}

/// A wire case as a loaded case: its inline meshes built.
fn loaded(wire: WireCase) -> Result<LoadedCase, String> {
    let mesh = |s: Option<&Shape>, field: &str| -> Result<Option<Mesh>, String> {
        match s {
            Some(Shape::Mesh(m)) => match (&m.vertices, &m.triangles) {
                (Some(v), Some(t)) => {
                    Mesh::new(v.clone(), t.clone()).map(Some).map_err(|(f, msg)| format!("{field}.mesh.{f}: {msg}"))
                }
                _ => Err(format!("{field}.mesh: a mesh on the wire is inline (vertices and triangles)")),
            },
            _ => Ok(None),
        }
    };
    let meshes = [mesh(Some(&wire.a), "a")?, mesh(wire.b.as_ref(), "b")?];
    Ok(LoadedCase { file: PathBuf::from("<protocol>"), case: wire.into_case(), meshes })
}
