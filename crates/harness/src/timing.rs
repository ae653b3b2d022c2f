//! The one timing loop: a pass over some queries, repeated, timed per query.
//!
//! The campaign times each engine on its generated cases, the scene section
//! each level of its pipelines, the toi section each method on its impacts —
//! all through [`per_query_ns`], so a repetition means the same everywhere: one
//! pass over every query, its wall time divided by the queries.

use crate::summary::Timing;
use std::hint::black_box;
use std::time::Instant;

/// The time per query of each of `reps` passes (at least one) of `pass`, a loop
/// over `queries` queries (at least one counted), in nanoseconds, fastest
/// first.
pub fn per_query_ns(reps: u32, queries: usize, mut pass: impl FnMut()) -> Vec<f64> {
    let mut per_query = Vec::with_capacity(reps.max(1) as usize);
    for _ in 0..reps.max(1) {
        let start = Instant::now();
        pass();
        per_query.push(start.elapsed().as_nanos() as f64 / queries.max(1) as f64);
    }
    per_query.sort_by(f64::total_cmp);
    per_query
}

/// The median time per query of `reps` passes of `pass` over `queries`
/// queries, in nanoseconds ([`per_query_ns`]).
pub fn median_ns(reps: u32, queries: usize, pass: impl FnMut()) -> f64 {
    let per_query = per_query_ns(reps, queries, pass);
    per_query[per_query.len() / 2]
}

/// Times `f` over `queries`: `reps` passes of one loop, each input and answer
/// through `black_box`; the median, fastest and slowest time per query.
/// `None` when there is no query.
pub fn time_each<Q, R>(reps: u32, queries: &[Q], f: impl Fn(&Q) -> R) -> Option<Timing> {
    if queries.is_empty() {
        return None;
    }
    let per_query = per_query_ns(reps, queries.len(), || {
        for q in queries {
            black_box(f(black_box(q)));
        }
    });
    Some(Timing {
        median_ns: per_query[per_query.len() / 2],
        min_ns: per_query[0],
        max_ns: per_query[per_query.len() - 1],
        reps,
        queries: queries.len() as u64,
    })
}
