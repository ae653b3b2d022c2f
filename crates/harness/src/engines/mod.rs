//! The engines crashtest runs, each behind [`crate::engine::Queries`]: collide's
//! adapter and the referee's here; parry implements the trait in the oracle
//! (`oracle::parry`), where its conventions are translated.

pub mod collide;
pub mod listed;
pub mod referee;

use crate::divergence::{LECTURE, PARRY};
use crate::engine::Engine;
use collide::{CollideQueries, Method};
use oracle::parry::{Parry32, Parry64};

/// The gate engine by default: the one whose answers decide `crashtest check`'s
/// exit code.
pub const DEFAULT_ENGINE: &str = "collide/robust";

/// The referee's name in reports.
pub const REFEREE: &str = "referee";

/// Every engine judged, in report order: collide's methods and precisions, then
/// parry in both precisions.
pub fn judged() -> Vec<Engine> {
    let collide = format!("collide {}", env!("CARGO_PKG_VERSION"));
    let parry = |name: &str| format!("{name} {}", oracle::parry::PARRY_VERSION);
    vec![
        Engine::new(COLLIDE[0], Some(53), CollideQueries::<f64>::new(Method::Robust)).with_version(&collide),
        Engine::new(COLLIDE[1], Some(53), CollideQueries::<f64>::new(Method::Lecture))
            .with_known(LECTURE)
            .with_version(&collide),
        Engine::new(COLLIDE[2], Some(24), CollideQueries::<f32>::new(Method::Robust))
            .with_version(&collide)
            .build_of(COLLIDE[0]),
        Engine::new(COLLIDE[3], Some(24), CollideQueries::<f32>::new(Method::Lecture))
            .with_known(LECTURE)
            .with_version(&collide)
            .build_of(COLLIDE[1]),
        Engine::new(Parry64::NAME, Some(53), Parry64).with_known(PARRY).with_version(parry(Parry64::NAME)),
        Engine::new(Parry32::NAME, Some(24), Parry32)
            .with_known(PARRY)
            .with_version(parry(Parry32::NAME))
            .build_of(Parry64::NAME),
    ]
}

/// Whether `e` is one of collide's built-in engines: the sections that measure
/// collide's methods through their own functions (halving depths, advancement
/// steps) run those instead of the seam.
pub fn is_collide(e: &Engine) -> bool {
    COLLIDE.contains(&e.name.as_str())
}

/// collide's engines, the first entries of [`judged`].
const COLLIDE: [&str; 4] = ["collide/robust", "collide/lecture", "collide-f32/robust", "collide-f32/lecture"];

/// The referee as an engine.
pub fn referee() -> Engine {
    Engine::new(REFEREE, None, referee::RefereeQueries)
}

/// The engines a run judges, the referee they are judged against, and the gate:
/// the engine whose answers decide `check`'s exit code. `check`, `report`,
/// `sweep` and every section take the set they are given.
#[derive(Clone, Debug)]
pub struct EngineSet {
    /// In report order.
    pub judged: Vec<Engine>,
    /// The truth.
    pub referee: Engine,
    /// The gate's name; one of `judged`.
    pub gate: String,
    /// Engines that `all` would have judged but that are not installed: each
    /// name, and why (with how to install it). The report's provenance lists
    /// them.
    pub missing: Vec<(String, String)>,
    /// `--ulps N`: every engine's fixed allowances are `N` of its ulps of
    /// each field's magnitude ([`crate::judge::tolerance::Tolerance::for_engine`]);
    /// `None`, the default, keeps the tolerance table's.
    pub ulps: Option<f64>,
}

impl Default for EngineSet {
    /// Every built-in engine ([`judged`]), gated by [`DEFAULT_ENGINE`].
    fn default() -> Self {
        Self { judged: judged(), referee: referee(), gate: DEFAULT_ENGINE.into(), missing: Vec::new(), ulps: None }
    }
}

impl EngineSet {
    /// `judged` against the referee, gated by `gate`. The names must be unique
    /// and the gate one of them; the error says which rule is broken.
    pub fn new(judged: Vec<Engine>, gate: &str) -> Result<Self, String> {
        if judged.is_empty() {
            return Err("no engine to judge".into());
        }
        for (i, e) in judged.iter().enumerate() {
            if e.name == REFEREE {
                return Err(format!("`{REFEREE}` is the truth every engine is judged against, not an engine to judge"));
            }
            if judged[..i].iter().any(|o| o.name == e.name) {
                return Err(format!("engine `{}` is named twice", e.name));
            }
        }
        if !judged.iter().any(|e| e.name == gate) {
            return Err(format!("the gate `{gate}` is not among the engines judged ({})", names(&judged)));
        }
        Ok(Self { judged, referee: referee(), gate: gate.into(), missing: Vec::new(), ulps: None })
    }

    /// The built-in engines named in `list` (comma-separated, or `all`), in that
    /// order, gated by `gate` — [`DEFAULT_ENGINE`] when `None`, which then must
    /// be selected; with one engine selected and no gate named, that engine.
    ///
    /// ```
    /// use harness::engines::EngineSet;
    /// let set = EngineSet::select("parry3d-f64, collide/robust", None).unwrap();
    /// assert_eq!(set.gate, "collide/robust");
    /// assert!(EngineSet::select("collide/robust,nope", None).unwrap_err().contains("unknown engine `nope`"));
    /// ```
    pub fn select(list: &str, gate: Option<&str>) -> Result<Self, String> {
        Self::select_with(list, gate, Vec::new())
    }

    /// `engine` as the gate, with the built-in engines named in `builtins`
    /// beside it (`["all"]` for every one) — the way a user's own engine is
    /// judged and shown next to collide and parry.
    ///
    /// ```
    /// use harness::engine::{Engine, Queries};
    /// use harness::engines::EngineSet;
    /// struct Nothing;
    /// impl Queries for Nothing {}
    /// let set = EngineSet::with_builtins(Engine::new("mine", Some(53), Nothing), &["parry3d-f64"]).unwrap();
    /// let names: Vec<&str> = set.judged.iter().map(|e| e.name.as_str()).collect();
    /// assert_eq!((names, set.gate.as_str()), (vec!["mine", "parry3d-f64"], "mine"));
    /// ```
    pub fn with_builtins(engine: Engine, builtins: &[&str]) -> Result<Self, String> {
        let gate = engine.name.clone();
        let mut judged = vec![engine];
        if !builtins.is_empty() {
            judged.extend(pick(&builtins.join(","))?);
        }
        Self::new(judged, &gate)
    }

    /// `judged` against the referee, gated by [`DEFAULT_ENGINE`] when it is
    /// among them and by the first engine otherwise.
    ///
    /// # Panics
    /// When `judged` is empty or names an engine twice.
    pub fn of(judged: Vec<Engine>) -> Self {
        let gate = match judged.iter().find(|e| e.name == DEFAULT_ENGINE).or(judged.first()) {
            Some(e) => e.name.clone(),
            None => panic!("EngineSet::of: no engine"),
        };
        Self::new(judged, &gate).unwrap_or_else(|e| panic!("EngineSet::of: {e}"))
    }

    /// The built-in engines and the listed process engines `listed` (in that
    /// order under `all`), those named in `list` (comma-separated, or `all`)
    /// chosen, gated as [`EngineSet::select`] gates. Only the listed engines
    /// chosen are started. Under `all`, a listed engine that is not installed
    /// is left out and recorded in [`EngineSet::missing`]; named, it is an
    /// error that says how to install it.
    pub fn select_with(list: &str, gate: Option<&str>, listed: Vec<listed::Listed>) -> Result<Self, String> {
        let all = list.trim() == "all";
        let named: Vec<&str> = list.split(',').map(str::trim).collect();
        let mut started = Vec::new();
        let mut missing = Vec::new();
        for l in listed {
            if !all && !named.contains(&l.spec.name.as_str()) {
                continue;
            }
            match &l.missing {
                Some(why) if all => missing.push((l.spec.name.clone(), why.clone())),
                Some(why) => return Err(format!("engine `{}`: {why}", l.spec.name)),
                None => started.push(l.start()),
            }
        }
        let chosen = pick_from(list, judged().into_iter().chain(started).collect())?;
        let gate = match (gate, chosen.as_slice()) {
            (Some(g), _) => g.to_string(),
            (None, [only]) => only.name.clone(),
            (None, _) => DEFAULT_ENGINE.to_string(),
        };
        Ok(Self { missing, ..Self::new(chosen, &gate)? })
    }

    /// Lets every process engine of the set answer `cases` in batches before
    /// they are judged one by one. The engines are separate processes, so they
    /// are asked side by side, as many at a time as the run has threads
    /// ([`prefetch_threads`]): a thread takes the next engine not yet asked
    /// until none is left. Each engine keeps its own answers, so the result is
    /// the same in any order.
    pub fn prefetch<'a, I>(&self, cases: I)
    where
        I: IntoIterator<Item = &'a crate::load::LoadedCase> + Clone,
    {
        let process: Vec<&Engine> = self.judged.iter().filter(|e| e.process().is_some()).collect();
        let threads = prefetch_threads(process.len());
        if threads <= 1 {
            for e in process {
                e.prefetch(cases.clone());
            }
            return;
        }
        let cases: Vec<&crate::load::LoadedCase> = cases.into_iter().collect();
        let next = std::sync::atomic::AtomicUsize::new(0);
        std::thread::scope(|scope| {
            for _ in 0..threads {
                scope.spawn(|| {
                    while let Some(e) = process.get(next.fetch_add(1, std::sync::atomic::Ordering::Relaxed)) {
                        e.prefetch(cases.iter().copied());
                    }
                });
            }
        });
    }

    /// Marks `cases` as answers the process engines keep when they forget.
    pub fn keep<'a, I>(&self, cases: I)
    where
        I: IntoIterator<Item = &'a crate::load::LoadedCase> + Clone,
    {
        if self.judged.iter().any(|e| e.process().is_some()) {
            for e in &self.judged {
                e.keep(cases.clone());
            }
        }
    }

    /// Lets every process engine forget its answers but the kept ones.
    pub fn forget(&self) {
        for e in &self.judged {
            e.forget();
        }
    }

    /// The gate engine.
    pub fn gate_engine(&self) -> &Engine {
        self.judged.iter().find(|e| e.name == self.gate).unwrap_or(&self.judged[0])
    }

    /// The judged engine named `name`.
    pub fn get(&self, name: &str) -> Option<&Engine> {
        self.judged.iter().find(|e| e.name == name)
    }
}

/// How many process engines are asked at a time, of `engines`: one per thread
/// of the run (rayon's count, which `RAYON_NUM_THREADS` sets), at most one per
/// engine. A process engine times its own calls (docs/PROTOCOL.md), so two
/// engines on two cores do not slow each other's figures the way two on one
/// core would; no more run at once than there are threads.
pub fn prefetch_threads(engines: usize) -> usize {
    rayon::current_num_threads().min(engines).max(1)
}

/// The built-in engines named in `list` (comma-separated, or `all`), in order.
fn pick(list: &str) -> Result<Vec<Engine>, String> {
    pick_from(list, judged())
}

/// The engines of `all` named in `list` (comma-separated, or `all`), in order.
fn pick_from(list: &str, all: Vec<Engine>) -> Result<Vec<Engine>, String> {
    if list.trim() == "all" {
        return Ok(all);
    }
    let mut chosen = Vec::new();
    for name in list.split(',').map(str::trim) {
        match all.iter().find(|e| e.name == name) {
            Some(e) => chosen.push(e.clone()),
            None if name.is_empty() => return Err(format!("empty engine name in `{list}`")),
            None => return Err(format!("unknown engine `{name}`; the engines are: {}, or `all`", names(&all))),
        }
    }
    Ok(chosen)
}

fn names(engines: &[Engine]) -> String {
    engines.iter().map(|e| e.name.as_str()).collect::<Vec<_>>().join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_set_is_every_engine_gated_by_collide_robust() {
        let set = EngineSet::default();
        assert_eq!(set.judged.len(), judged().len());
        assert_eq!(set.gate_engine().name, DEFAULT_ENGINE);
    }

    #[test]
    fn a_selection_keeps_its_order_and_checks_its_gate() {
        let set = EngineSet::select("parry3d-f64, collide/robust", None).expect("valid");
        let got: Vec<&str> = set.judged.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(got, ["parry3d-f64", "collide/robust"]);
        assert_eq!(set.gate, DEFAULT_ENGINE);
        assert_eq!(EngineSet::select("parry3d", None).expect("one engine").gate, "parry3d");
        let err = EngineSet::select("parry3d,parry3d-f64", None).expect_err("no default gate among them");
        assert!(err.contains("the gate `collide/robust` is not among"), "{err}");
        let err = EngineSet::select("collide/robust,nope", None).expect_err("unknown");
        assert!(err.contains("unknown engine `nope`") && err.contains("parry3d-f64"), "{err}");
        let err = EngineSet::select("collide/robust,collide/robust", None).expect_err("twice");
        assert!(err.contains("named twice"), "{err}");
        assert!(EngineSet::select("all", Some("parry3d")).is_ok());
        assert!(EngineSet::select("all", Some("referee")).is_err());
    }
}
