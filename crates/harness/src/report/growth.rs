//! How each engine's `distance` cost grows with the hull: the report's
//! cost-growth chart (`charts/distance-cost-growth.svg`).
//!
//! The cases are the `distance-points` sweep's scene (`crate::sweep`): a hull
//! of `n` points on the unit sphere (each a vertex), 2.25 above a unit cube
//! given as the hull of its corners, for `n` in [`GROWTH_POINTS`] from 4 to
//! 10⁴, [`GROWTH_CASES`] orders of the points each. The cores are apart, so
//! this is GJK's growth (every engine's, the referee's exact GJK included);
//! meeting hulls (EPA, and the referee's separating axes, which grow with the
//! product of the two hulls' edge counts) are not in it.
//!
//! Each engine is timed as the report times it per query kind
//! (`campaign::time_engine`): an in-process engine's whole call, building
//! its shapes from the case's points included; a process engine's own time of
//! its engine call, as it reports it. So a line shows what one query costs an
//! engine's user who holds the points, not a prebuilt shape's query alone.

use crate::case::{Case, Query};
use crate::engines::EngineSet;
use crate::load::LoadedCase;
pub use crate::summary::{GROWTH_CASES, GROWTH_POINTS, Growth};

/// The cases of `n` points.
pub fn cases(seed: u64, n: usize) -> Vec<LoadedCase> {
    (0..GROWTH_CASES)
        .map(|k| {
            let (a, b) = crate::sweep::distance::growth_scene(seed, n, k);
            let name = format!("distance cost growth: {n} points, order {k}");
            crate::generate::loaded(Case {
                name: name.clone(),
                source: name,
                query: Query::Distance,
                a,
                b,
                expect: None,
                tol: None,
                t_max: None,
                restitution: None,
            })
        })
        .collect()
}

/// Every judged engine's growth and the referee's, in engine order (engines
/// that answer none of the cases left out), each timed by `time` (the
/// campaign's `time_engine`).
pub fn measure(
    set: &EngineSet,
    seed: u64,
    time: impl Fn(&crate::engine::Engine, &[&LoadedCase]) -> Option<crate::summary::Timing>,
) -> Vec<Growth> {
    let ladder: Vec<(usize, Vec<LoadedCase>)> = GROWTH_POINTS.iter().map(|&n| (n, cases(seed, n))).collect();
    set.prefetch(ladder.iter().flat_map(|(_, c)| c));
    let mut out = Vec::new();
    for engine in set.judged.iter().chain([&set.referee]) {
        let points: Vec<(u64, f64)> = ladder
            .iter()
            .filter_map(|(n, cases)| {
                let refs: Vec<&LoadedCase> = cases.iter().collect();
                time(engine, &refs).map(|t| (*n as u64, t.median_ns))
            })
            .collect();
        if !points.is_empty() {
            out.push(Growth { engine: engine.name.clone(), points });
        }
    }
    set.forget();
    out
}
