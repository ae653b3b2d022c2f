//! A process engine: a command that speaks `crashtest-engine/1`, run behind the
//! engine seam.
//!
//! Its faults are contained here (`docs/PROTOCOL.md`, "Faults"): an engine that
//! exits, hangs, writes what is not a message, or answers the wrong cases gets
//! the cases concerned `FAILED` with the reason, is restarted a bounded number of
//! times and then marked down. Nothing here panics, and nothing waits without a
//! deadline: lines are read on a thread and awaited with a time limit, and lines
//! are written on a thread too, so an engine that stops reading cannot block the
//! run either.

use super::messages::{EngineHello, FromEngine, PROTOCOL, Said, ToEngine, WireCase, World, WorldReply};
use crate::case::Query;
use crate::load::LoadedCase;
use crashtest_core::engine::Answer;
use crashtest_core::pair::Pair;
use std::collections::{HashMap, HashSet, VecDeque};
use std::io::{BufRead, BufReader, Write};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// The time limit for one batch (or the handshake), by default: generous for
/// the batches crashtest sends (at most [`DEFAULT_BATCH`] cases), far below a
/// hang anyone would wait for.
pub const DEFAULT_TIMEOUT: Duration = Duration::from_secs(60);

/// Cases per batch: large enough that the process and JSON costs per case are
/// small (the protocol bench measures them against batch size), small enough
/// that a fault fails few cases.
pub const DEFAULT_BATCH: usize = 1024;

/// Batches sent ahead of the answer awaited: two, so that crashtest's writing
/// of one batch overlaps the engine's answering of the other.
pub const IN_FLIGHT: usize = 2;

/// Restarts of an engine in one run before it is marked down.
pub const MAX_RESTARTS: u32 = 3;

/// The read buffer on an engine's output: a batch's answers arrive in a few
/// large reads instead of many small ones (a system call and a task switch
/// each).
pub const PIPE_BUFFER: usize = 1 << 20;

/// Lines of an engine's standard error kept for messages.
const STDERR_LINES: usize = 20;

/// The time a shut-down engine has to exit before it is killed.
const EXIT_GRACE: Duration = Duration::from_secs(2);

/// How to run a process engine.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProcessSpec {
    /// The name it is shown under (the command line's `NAME=`).
    pub name: String,
    /// The program.
    pub program: String,
    /// Its arguments.
    pub args: Vec<String>,
    /// The time limit per batch.
    pub timeout: Duration,
    /// Cases per batch.
    pub batch: usize,
}

impl ProcessSpec {
    /// `NAME=COMMAND`, the command split on white space (no shell).
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (name, command) = spec
            .split_once('=')
            .ok_or_else(|| format!("`{spec}`: expected NAME=COMMAND, for example mine=./engine"))?;
        let words: Vec<String> = command.split_whitespace().map(String::from).collect();
        Self::new(name, words)
    }

    /// A named command: `words` is the program and its arguments.
    pub fn new(name: &str, words: Vec<String>) -> Result<Self, String> {
        let name = name.trim();
        if name.is_empty() {
            return Err("an engine needs a name (NAME=COMMAND)".into());
        }
        let mut words = words.into_iter();
        let program = words.next().filter(|p| !p.is_empty()).ok_or_else(|| format!("engine `{name}`: no command"))?;
        Ok(Self { name: name.into(), program, args: words.collect(), timeout: DEFAULT_TIMEOUT, batch: DEFAULT_BATCH })
    }

    /// The command as one line, for messages and provenance. A word that is
    /// a path inside the current folder is shown relative to it: a report
    /// made at the repository's root names `engines/.venv/bin/python
    /// engines/fcl/engine.py`, a command that runs there, never the machine's
    /// own folders.
    pub fn command_line(&self) -> String {
        std::iter::once(self.program.as_str())
            .chain(self.args.iter().map(String::as_str))
            .map(shown_path)
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// A word as messages and reports show it: a path inside the current folder
/// relative to it (`engines/fcl/engine.py`), anything else as it is.
pub fn shown_path(word: &str) -> String {
    let here = std::env::current_dir().ok();
    match here.as_deref().and_then(|h| std::path::Path::new(word).strip_prefix(h).ok()) {
        Some(r) if r.as_os_str().is_empty() => ".".to_string(),
        Some(r) => r.display().to_string(),
        None => word.to_string(),
    }
}

/// What a process engine said of one case.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// Its answer.
    Answer(Answer),
    /// It does not answer the case, and why.
    Unsupported(String),
    /// It failed on the case (its own error, or a fault of the process).
    Failed(String),
}

/// An outcome and the engine's own time for the case.
#[derive(Clone, Debug, PartialEq)]
pub struct Reply {
    /// What it said.
    pub outcome: Outcome,
    /// Nanoseconds, measured inside the engine (when it said).
    pub ns: Option<f64>,
}

/// What the report's provenance says of a process engine.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ProcessInfo {
    /// The command.
    pub command: String,
    /// Its hello (absent when it never gave one).
    pub hello: Option<EngineHello>,
    /// Restarts in this run.
    pub restarts: u32,
    /// Why it is down, if it is.
    pub down: Option<String>,
    /// The time limit per batch, in seconds.
    pub timeout_seconds: f64,
    /// Every fault met, in order (at most the first 100).
    pub faults: Vec<String>,
    /// Cases sent to it in this run (unsupported pairs are answered without
    /// asking and not counted).
    #[serde(default)]
    pub cases_sent: u64,
    /// Wall time spent exchanging those cases with it (writing, its work,
    /// reading), in seconds: where a run's time went, engine by engine.
    #[serde(default)]
    pub seconds_sent: f64,
}

/// A running engine process.
struct Running {
    child: Child,
    to_engine: Sender<String>,
    lines: Receiver<Line>,
    stderr: Arc<Mutex<VecDeque<String>>>,
    /// Lines of its standard output read so far (for messages).
    line_no: u64,
}

enum Line {
    Text(String),
    End,
    Unreadable(String),
}

struct State {
    running: Option<Running>,
    hello: Option<EngineHello>,
    restarts: u32,
    down: Option<String>,
    next_id: u64,
    faults: Vec<String>,
    cases_sent: u64,
    seconds_sent: f64,
}

/// A process engine. Calls are serialized (one process answers one batch at a
/// time); answers are kept by case, so a campaign that asked for them in
/// batches ([`ProcessEngine::prefetch`]) finds them when it judges case by case.
pub struct ProcessEngine {
    spec: ProcessSpec,
    state: Mutex<State>,
    memo: Mutex<HashMap<String, Reply, KeyHasher>>,
    /// Keys of the answers [`ProcessEngine::forget`] keeps.
    kept: Mutex<HashSet<String, KeyHasher>>,
    /// The precision the last hello declared per pair: read for every
    /// judgement, so kept apart from `state` (held through a batch's whole
    /// exchange) and from the hello itself (its reproductions are long).
    precisions: Mutex<Vec<(Pair, Option<u32>)>>,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

impl ProcessEngine {
    /// Starts the engine and shakes hands. An engine that cannot start or
    /// answers the handshake wrongly is returned marked down (every case
    /// `FAILED` with the reason; [`ProcessEngine::down`] says it), so the rest of
    /// the run still happens.
    pub fn start(spec: ProcessSpec) -> Self {
        let engine = ProcessEngine {
            spec,
            state: Mutex::new(State {
                running: None,
                hello: None,
                restarts: 0,
                down: None,
                next_id: 1,
                faults: Vec::new(),
                cases_sent: 0,
                seconds_sent: 0.0,
            }),
            memo: Mutex::new(HashMap::with_hasher(KeyHasher::default())),
            kept: Mutex::new(HashSet::with_hasher(KeyHasher::default())),
            precisions: Mutex::new(Vec::new()),
        };
        {
            let mut st = lock(&engine.state);
            if let Err(e) = engine.launch(&mut st) {
                let why = format!("the handshake failed: {e}");
                fault(&mut st, &why);
                st.down = Some(why);
            }
        }
        engine
    }

    /// Its spec.
    pub fn spec(&self) -> &ProcessSpec {
        &self.spec
    }

    /// Its hello, once it gave one.
    pub fn hello(&self) -> Option<EngineHello> {
        lock(&self.state).hello.clone()
    }

    /// The precision the engine's hello declares for `pair`, if it declares one.
    pub fn precision_for(&self, pair: Pair) -> Option<u32> {
        lock(&self.precisions).iter().find(|(p, _)| *p == pair).and_then(|(_, precision)| *precision)
    }

    /// Why it is down, if it is.
    pub fn down(&self) -> Option<String> {
        lock(&self.state).down.clone()
    }

    /// What the provenance shows.
    pub fn info(&self) -> ProcessInfo {
        let st = lock(&self.state);
        ProcessInfo {
            command: self.spec.command_line(),
            hello: st.hello.clone(),
            restarts: st.restarts,
            down: st.down.clone(),
            timeout_seconds: self.spec.timeout.as_secs_f64(),
            faults: st.faults.clone(),
            cases_sent: st.cases_sent,
            seconds_sent: st.seconds_sent,
        }
    }

    /// Its answer to one case: kept from an earlier batch, or asked now.
    pub fn answer(&self, lc: &LoadedCase) -> Reply {
        let key = case_key(lc);
        if let Some(r) = lock(&self.memo).get(&key) {
            return r.clone();
        }
        self.ask(vec![Pending::written(key, lc)], true)
            .pop()
            .unwrap_or(Reply { outcome: Outcome::Failed("no reply".into()), ns: None })
    }

    /// Asks for `cases` now, in batches, whether or not it answered them
    /// before, and keeps nothing: the protocol's exchange alone, which the
    /// protocol bench times (a run asks through [`ProcessEngine::prefetch`],
    /// which also keeps the answers).
    pub fn run_batches(&self, cases: &[&LoadedCase]) -> Vec<Reply> {
        self.ask(cases.iter().map(|lc| Pending::unwritten(lc)).collect(), false)
    }

    /// The engine's own mean time per case over the cases of `cases` it
    /// answered (and timed), with their count; `None` when it timed none.
    pub fn mean_ns<'a>(&self, cases: impl IntoIterator<Item = &'a LoadedCase>) -> Option<(f64, usize)> {
        let ns: Vec<f64> = cases
            .into_iter()
            .map(|lc| self.answer(lc))
            .filter(|r| matches!(r.outcome, Outcome::Answer(_)))
            .filter_map(|r| r.ns)
            .collect();
        (!ns.is_empty()).then(|| (ns.iter().sum::<f64>() / ns.len() as f64, ns.len()))
    }

    /// Forgets its answer to `lc`, so that the next judgement asks again: a
    /// repeated judgement of one case (a replay, a stability check) must see
    /// the engine answer anew, not the first answer again.
    pub fn forget_case(&self, lc: &LoadedCase) {
        lock(&self.memo).remove(&case_key(lc));
    }

    /// Marks `cases` as answers [`ProcessEngine::forget`] keeps.
    pub fn keep<'a>(&self, cases: impl IntoIterator<Item = &'a LoadedCase>) {
        lock(&self.kept).extend(cases.into_iter().map(case_key));
    }

    /// Forgets every answer it keeps but those marked with
    /// [`ProcessEngine::keep`]: a streaming run calls it once a chunk is
    /// judged, so the answers it holds stay a chunk's.
    pub fn forget(&self) {
        let kept = lock(&self.kept);
        lock(&self.memo).retain(|k, _| kept.contains(k));
    }

    /// Asks for every case of `cases` it has not answered yet, in batches, and
    /// keeps the answers for [`ProcessEngine::answer`].
    pub fn prefetch<'a>(&self, cases: impl IntoIterator<Item = &'a LoadedCase>) {
        let mut want = Vec::new();
        {
            let memo = lock(&self.memo);
            let mut seen = HashSet::with_hasher(KeyHasher::default());
            for lc in cases {
                let key = case_key(lc);
                if !memo.contains_key(&key) && seen.insert(key.clone()) {
                    want.push(Pending::written(key, lc));
                }
            }
        }
        self.ask(want, true);
    }

    /// Steps one world ([`World`]; its `id` is set here) and returns what the
    /// engine did, or why it did not: its own error for the world, or a fault of
    /// the process (which is then restarted for the next message, as after a
    /// batch's fault).
    pub fn world(&self, world: &World) -> Result<WorldReply, String> {
        let mut st = lock(&self.state);
        if !st.hello.as_ref().is_some_and(|h| h.worlds) && st.down.is_none() {
            return Err("the engine does not step worlds (its hello has no `worlds`)".into());
        }
        self.ensure_running(&mut st)?;
        let id = st.next_id;
        st.next_id += 1;
        let fault_of = |this: &Self, st: &mut State, why: String| {
            let why = format!("world {id} ({}): {why}", world.name);
            fault(st, &why);
            this.kill(st);
            why
        };
        let line = match serde_json::to_string(&ToEngine::World(World { id, ..world.clone() })) {
            Ok(l) => l + "\n",
            Err(e) => return Err(format!("world {id}: cannot write it: {e}")),
        };
        let timeout = self.spec.timeout;
        let Some(run) = st.running.as_mut() else { return Err("the engine is not running".into()) };
        if run.to_engine.send(line).is_err() {
            let why = gone(run, "before the world was sent");
            return Err(fault_of(self, &mut st, why));
        }
        let got = read_line(run, Instant::now() + timeout, timeout).and_then(|text| parse(&text, run.line_no));
        let line_no = run.line_no;
        match got {
            Ok(FromEngine::World(r)) if r.id == id => match r.error {
                Some(e) => Err(format!("the engine's error: {e}")),
                None => Ok(r),
            },
            Ok(FromEngine::World(r)) => {
                Err(fault_of(self, &mut st, format!("line {line_no}: answered world {}, expected {id}", r.id)))
            }
            Ok(_) => Err(fault_of(self, &mut st, format!("line {line_no}: expected `world`, got another message"))),
            Err(why) => Err(fault_of(self, &mut st, why)),
        }
    }

    /// Sends one case written as raw JSON (for the conformance run's
    /// malformed-case probes; a run sends only loaded cases) and returns what
    /// the engine said, and whether it was a fault of the process. The answer
    /// is not kept.
    pub fn ask_raw(&self, json: &str) -> (Reply, bool) {
        let query = serde_json::from_str::<serde_json::Value>(json)
            .ok()
            .and_then(|v| v.get("query").and_then(|q| q.as_str()).and_then(Query::parse))
            .unwrap_or(Query::Contact);
        let mut st = lock(&self.state);
        let before = st.faults.len();
        let raw = Pending { text: Some(json.to_string()), case: None, query, pair: None };
        let reply = self.exchange_all(&mut st, vec![vec![raw]], |_, _| {}).pop();
        let fault = st.faults.len() > before || st.down.is_some();
        (reply.unwrap_or(Reply { outcome: Outcome::Failed("no reply".into()), ns: None }), fault)
    }

    /// Asks for `cases` in batches, and keeps every reply when `keep`.
    fn ask(&self, cases: Vec<Pending<'_>>, keep: bool) -> Vec<Reply> {
        let mut st = lock(&self.state);
        let n = cases.len();
        let mut replies: Vec<Option<Reply>> = vec![None; n];
        let mut sent = Vec::new();
        let mut batches: Vec<Vec<Pending>> = Vec::new();
        for (i, case) in cases.into_iter().enumerate() {
            let capable = st
                .hello
                .as_ref()
                .is_some_and(|h| case.pair.is_some_and(|p| h.capabilities.iter().any(|c| c.pair() == Some(p))));
            if st.down.is_none() && !capable {
                replies[i] = Some(Reply {
                    outcome: Outcome::Unsupported("not among the engine's capabilities".into()),
                    ns: None,
                });
            } else {
                match batches.last_mut() {
                    Some(b) if b.len() < self.spec.batch.max(1) => b.push(case),
                    _ => batches.push(vec![case]),
                }
                sent.push(i);
            }
        }
        // Each batch's answers are kept as they come, while the engine answers
        // the next one.
        let start = Instant::now();
        st.cases_sent += sent.len() as u64;
        let got = self.exchange_all(&mut st, batches, |batch, answers| {
            if keep {
                let mut memo = lock(&self.memo);
                for (case, r) in batch.iter_mut().zip(answers) {
                    if let Some(key) = case.text.take() {
                        memo.insert(key, r.clone());
                    }
                }
            }
        });
        st.seconds_sent += start.elapsed().as_secs_f64();
        drop(st);
        for (&i, r) in sent.iter().zip(got) {
            replies[i] = Some(r);
        }
        replies
            .into_iter()
            .map(|r| r.unwrap_or(Reply { outcome: Outcome::Failed("no reply".into()), ns: None }))
            .collect()
    }

    /// Batches, in order, with up to [`IN_FLIGHT`] of them sent ahead of the
    /// answer awaited, so that the engine answers one batch while crashtest
    /// writes the next and reads the last. A fault fails every case of the
    /// batch whose answer it spoiled, kills the process, and sends the batches
    /// that were in flight again to the restarted engine. `done` is given each
    /// batch with its replies as they come; the replies, one per case, in order.
    fn exchange_all(
        &self,
        st: &mut State,
        mut batches: Vec<Vec<Pending<'_>>>,
        mut done: impl FnMut(&mut [Pending<'_>], &[Reply]),
    ) -> Vec<Reply> {
        let mut out: Vec<Vec<Reply>> = vec![Vec::new(); batches.len()];
        let failed = |batch: &[Pending], why: &str| {
            batch.iter().map(|_| Reply { outcome: Outcome::Failed(why.to_string()), ns: None }).collect::<Vec<_>>()
        };
        // Batches sent and not yet answered: (id, index), oldest first.
        let mut in_flight: VecDeque<(u64, usize)> = VecDeque::new();
        let mut next = 0;
        while next < batches.len() || !in_flight.is_empty() {
            while next < batches.len() && in_flight.len() < IN_FLIGHT {
                if let Err(why) = self.ensure_running(st) {
                    if in_flight.is_empty() {
                        out[next] = failed(&batches[next], &why);
                        done(&mut batches[next], &out[next]);
                        next += 1;
                        continue;
                    }
                    break;
                }
                let id = st.next_id;
                st.next_id += 1;
                match self.send(st, &mut batches[next], id) {
                    Ok(()) => {
                        in_flight.push_back((id, next));
                        next += 1;
                    }
                    // The engine is gone: the answer awaited says how (or, with
                    // nothing awaited, the next round restarts it).
                    Err(why) if in_flight.is_empty() => {
                        let why = format!("batch {id}: {why}");
                        fault(st, &why);
                        self.kill(st);
                        out[next] = failed(&batches[next], &why);
                        done(&mut batches[next], &out[next]);
                        next += 1;
                    }
                    Err(_) => break,
                }
            }
            let Some((id, ix)) = in_flight.pop_front() else { continue };
            match self.receive(st, &batches[ix], id) {
                Ok(replies) => out[ix] = replies,
                Err(why) => {
                    let why = format!("batch {id}: {why}");
                    fault(st, &why);
                    self.kill(st);
                    out[ix] = failed(&batches[ix], &why);
                    // The batches in flight behind it go again, to the restarted engine.
                    if let Some(&(_, first)) = in_flight.front() {
                        next = first;
                    }
                    in_flight.clear();
                }
            }
            done(&mut batches[ix], &out[ix]);
        }
        out.into_iter().flatten().collect()
    }

    /// A running engine: restarted if a fault ended it (at most
    /// [`MAX_RESTARTS`] times, then marked down). The error is what every case
    /// sent now fails with.
    fn ensure_running(&self, st: &mut State) -> Result<(), String> {
        if let Some(down) = &st.down {
            return Err(format!("the engine is down: {down}"));
        }
        if st.running.is_some() {
            return Ok(());
        }
        if st.restarts >= MAX_RESTARTS {
            let why = format!(
                "restarted {MAX_RESTARTS} times; the last fault: {}",
                st.faults.last().map(String::as_str).unwrap_or("none")
            );
            st.down = Some(why.clone());
            return Err(format!("the engine is down: {why}"));
        }
        st.restarts += 1;
        self.launch(st).map_err(|e| {
            let why = format!("restart {} failed: {e}", st.restarts);
            fault(st, &why);
            why
        })
    }

    /// Writes one batch line (through the writer thread: never blocks); each
    /// case's wire text is written now if it was not before.
    fn send(&self, st: &mut State, batch: &mut [Pending<'_>], id: u64) -> Result<(), String> {
        let run = st.running.as_mut().ok_or("the engine is not running")?;
        let mut line = String::with_capacity(32 + batch.len() * TEXT_CAPACITY);
        line.push_str(&format!("{{\"type\":\"batch\",\"id\":{id},\"cases\":["));
        for (k, case) in batch.iter_mut().enumerate() {
            if k > 0 {
                line.push(',');
            }
            line.push_str(case.text());
        }
        line.push_str("]}\n");
        run.to_engine.send(line).map_err(|_| gone(run, "before the batch was sent"))
    }

    /// Reads the answers to batch `id`, within the time limit.
    fn receive(&self, st: &mut State, batch: &[Pending<'_>], id: u64) -> Result<Vec<Reply>, String> {
        let timeout = self.spec.timeout;
        let run = st.running.as_mut().ok_or("the engine is not running")?;
        let text = read_line(run, Instant::now() + timeout, timeout)?;
        let msg = parse(&text, run.line_no)?;
        let FromEngine::Answers { id: got_id, answers, ns } = msg else {
            return Err(format!(
                "line {} of the engine's output: expected `answers`, got another message",
                run.line_no
            ));
        };
        if got_id != id {
            return Err(format!("line {}: answered batch {got_id}, expected {id}", run.line_no));
        }
        if answers.len() != batch.len() {
            return Err(format!("line {}: answered {} cases of {}", run.line_no, answers.len(), batch.len()));
        }
        let per_case = ns.map(|t| t / batch.len().max(1) as f64);
        Ok(answers
            .iter()
            .zip(batch)
            .map(|(e, case)| Reply {
                outcome: match e.said(case.query) {
                    Said::Answer(a) => Outcome::Answer(a),
                    Said::Unsupported(u) => Outcome::Unsupported(u),
                    Said::Error(m) => Outcome::Failed(m),
                },
                ns: e.ns.or(per_case).filter(|t| t.is_finite() && *t >= 0.0),
            })
            .collect())
    }

    /// Starts the process and shakes hands.
    fn launch(&self, st: &mut State) -> Result<(), String> {
        let mut child = Command::new(&self.spec.program)
            .args(&self.spec.args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("cannot start `{}`: {e}", self.spec.command_line()))?;
        let (Some(stdin), Some(stdout), Some(stderr)) = (child.stdin.take(), child.stdout.take(), child.stderr.take())
        else {
            let _ = child.kill();
            let _ = child.wait();
            return Err("no pipes to the engine".into());
        };
        let (to_engine, outbox) = mpsc::channel::<String>();
        std::thread::spawn(move || {
            let mut stdin = stdin;
            for line in outbox {
                if stdin.write_all(line.as_bytes()).and_then(|()| stdin.flush()).is_err() {
                    break;
                }
            }
        });
        let (tx, lines) = mpsc::channel();
        std::thread::spawn(move || {
            let mut r = BufReader::with_capacity(PIPE_BUFFER, stdout);
            loop {
                let mut buf = Vec::new();
                let line = match r.read_until(b'\n', &mut buf) {
                    Ok(0) => Line::End,
                    Ok(_) => match String::from_utf8(buf) {
                        Ok(s) => Line::Text(s),
                        Err(e) => Line::Unreadable(format!("not UTF-8: {e}")),
                    },
                    Err(e) => Line::Unreadable(e.to_string()),
                };
                let end = !matches!(line, Line::Text(_));
                if tx.send(line).is_err() || end {
                    break;
                }
            }
        });
        let tail = Arc::new(Mutex::new(VecDeque::new()));
        let keep = Arc::clone(&tail);
        std::thread::spawn(move || {
            let mut r = BufReader::new(stderr);
            let mut buf = Vec::new();
            loop {
                buf.clear();
                match r.read_until(b'\n', &mut buf) {
                    Ok(0) | Err(_) => break,
                    Ok(_) => {
                        let mut t = lock(&keep);
                        if t.len() == STDERR_LINES {
                            t.pop_front();
                        }
                        t.push_back(String::from_utf8_lossy(&buf).trim_end().to_string());
                    }
                }
            }
        });
        let mut run = Running { child, to_engine, lines, stderr: tail, line_no: 0 };
        let hello = serde_json::to_string(&ToEngine::Hello { protocol: PROTOCOL.into() }).unwrap_or_default();
        let shake = (|| {
            if run.to_engine.send(format!("{hello}\n")).is_err() {
                return Err(gone(&mut run, "before the hello was sent"));
            }
            let text = read_line(&mut run, Instant::now() + self.spec.timeout, self.spec.timeout)?;
            match parse(&text, run.line_no)? {
                FromEngine::Hello(h) if h.protocol == PROTOCOL => Ok(h),
                FromEngine::Hello(h) => {
                    Err(format!("the engine speaks `{}`; crashtest speaks `{PROTOCOL}`", h.protocol))
                }
                FromEngine::Answers { .. } | FromEngine::World(_) => {
                    Err("expected `hello`, got another message".into())
                }
            }
        })();
        match shake {
            Ok(h) => {
                *lock(&self.precisions) =
                    h.capabilities.iter().filter_map(|c| Some((c.pair()?, c.precision))).collect();
                st.hello = Some(h);
                st.running = Some(run);
                Ok(())
            }
            Err(e) => {
                let _ = run.child.kill();
                let _ = run.child.wait();
                Err(e)
            }
        }
    }

    /// Kills the running process (a fault ended its session).
    fn kill(&self, st: &mut State) {
        if let Some(mut run) = st.running.take() {
            let _ = run.child.kill();
            let _ = run.child.wait();
        }
    }

    /// Replaces the running process with a new one (not counted as a restart
    /// after a fault). A stability check asks this, since an engine may answer
    /// an input the same way all through one process and differently in the
    /// next (the answers kept from the old process stay: a judgement that
    /// wants the new process's answer forgets the case's first, as
    /// [`crate::findings::shrink::judge_one`] does). An engine that is down
    /// stays down.
    pub fn fresh_process(&self) -> Result<(), String> {
        self.shutdown();
        let mut st = lock(&self.state);
        if let Some(down) = &st.down {
            return Err(format!("the engine is down: {down}"));
        }
        self.launch(&mut st)
    }

    /// Asks the engine to exit, and kills it if it has not within
    /// [`EXIT_GRACE`].
    pub fn shutdown(&self) {
        let mut st = lock(&self.state);
        if let Some(mut run) = st.running.take() {
            let bye = serde_json::to_string(&ToEngine::Shutdown).unwrap_or_default();
            let _ = run.to_engine.send(format!("{bye}\n"));
            drop(run.to_engine);
            let until = Instant::now() + EXIT_GRACE;
            loop {
                match run.child.try_wait() {
                    Ok(Some(_)) => break,
                    Ok(None) if Instant::now() < until => std::thread::sleep(Duration::from_millis(10)),
                    _ => {
                        let _ = run.child.kill();
                        let _ = run.child.wait();
                        break;
                    }
                }
            }
        }
    }
}

impl Drop for ProcessEngine {
    fn drop(&mut self) {
        self.shutdown();
    }
}

impl std::fmt::Debug for ProcessEngine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ProcessEngine").field("spec", &self.spec).finish_non_exhaustive()
    }
}

/// A case's key in the kept answers: its wire form (what is sent).
fn case_key(lc: &LoadedCase) -> String {
    let mut text = Vec::with_capacity(TEXT_CAPACITY);
    match serde_json::to_writer(&mut text, &WireCase::of(lc)) {
        // serde_json writes UTF-8 only.
        Ok(()) => String::from_utf8(text).unwrap_or_default(),
        Err(_) => String::new(),
    }
}

/// Room for a case's wire text: most cases' fit (a primitive pair's is a few
/// hundred bytes), so writing one rarely grows its buffer.
const TEXT_CAPACITY: usize = 512;

/// The hasher of the kept answers' keys (wire texts of a few hundred bytes:
/// the standard library's hasher takes longer over them than the rest of a
/// lookup; no key here comes from an adversary).
type KeyHasher = foldhash::fast::RandomState;

/// A case waiting for its batch.
struct Pending<'a> {
    /// Its wire text, once written (the key its answer is kept under).
    text: Option<String>,
    /// The case, to write the text from when its batch is sent.
    case: Option<&'a LoadedCase>,
    query: Query,
    pair: Option<Pair>,
}

impl<'a> Pending<'a> {
    /// A case whose wire text is `key`.
    fn written(key: String, lc: &'a LoadedCase) -> Self {
        Pending { text: Some(key), case: Some(lc), query: lc.case.query, pair: lc.case.pair() }
    }

    /// A case whose wire text is written when its batch is sent (while the
    /// engine answers the batch before).
    fn unwritten(lc: &'a LoadedCase) -> Self {
        Pending { text: None, case: Some(lc), query: lc.case.query, pair: lc.case.pair() }
    }

    fn text(&mut self) -> &str {
        let case = self.case;
        self.text.get_or_insert_with(|| case.map(case_key).unwrap_or_default())
    }
}

fn fault(st: &mut State, why: &str) {
    if st.faults.len() < 100 {
        st.faults.push(why.to_string());
    }
}

/// The next line of the engine's output, by `deadline`.
fn read_line(run: &mut Running, deadline: Instant, timeout: Duration) -> Result<String, String> {
    let wait = deadline.saturating_duration_since(Instant::now());
    match run.lines.recv_timeout(wait) {
        Ok(Line::Text(t)) => {
            run.line_no += 1;
            Ok(t)
        }
        Ok(Line::Unreadable(e)) => {
            run.line_no += 1;
            Err(format!("line {} of the engine's output is unreadable: {e}", run.line_no))
        }
        Ok(Line::End) | Err(RecvTimeoutError::Disconnected) => Err(gone(run, "before it answered")),
        Err(RecvTimeoutError::Timeout) => Err(format!("no answer within {} s", timeout.as_secs_f64())),
    }
}

/// The message of an engine whose output ended: its exit status (waited for
/// briefly) and its last lines of standard error.
fn gone(run: &mut Running, when: &str) -> String {
    let until = Instant::now() + Duration::from_millis(500);
    let status = loop {
        match run.child.try_wait() {
            Ok(Some(s)) => break s.to_string(),
            Ok(None) if Instant::now() < until => std::thread::sleep(Duration::from_millis(5)),
            _ => break "still running, output closed".to_string(),
        }
    };
    // Give the standard error reader a moment to take the last lines.
    std::thread::sleep(Duration::from_millis(20));
    let tail = lock(&run.stderr).iter().cloned().collect::<Vec<_>>().join(" | ");
    let tail = if tail.is_empty() { String::new() } else { format!("; its standard error ends: {tail}") };
    format!("the engine exited ({status}) {when}{tail}")
}

/// A line of the engine's output as a message; the error names the line, and
/// the field (or the column, for JSON syntax).
fn parse(text: &str, line_no: u64) -> Result<FromEngine, String> {
    super::messages::read_from_engine(text.trim_end()).map_err(|e| {
        let preview: String = text.trim_end().chars().take(120).collect();
        format!("line {line_no} of the engine's output is not a message: {e} (`{preview}`)")
    })
}
