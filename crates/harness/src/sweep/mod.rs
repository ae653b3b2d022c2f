//! Stability sweeps: where each method breaks.
//!
//! A sweep walks one degeneracy parameter over many decades (ten points per
//! decade, [`grid::R10`]) from its benign end to its degenerate end — a segment
//! turning parallel to a plane, a crossing creeping onto an edge, a triangle
//! thinning to a sliver, a scene moving away from the origin, two spheres
//! becoming concentric or just touching, one shape dwarfing another — and,
//! where the degenerate end is a configuration of its own, exactly onto it
//! (exactly parallel, exactly on the edge, exactly flat, …). At each point a
//! sweep's queries (its *probes*) are asked in many random rigid poses; every
//! case is an ordinary fixture case ([`crate::load::LoadedCase`]) and goes through every
//! judged engine and the referee exactly as in the campaign
//! ([`crate::check::check_case`]): a panic is caught per engine and case, a NaN is a
//! failure, a classification the referee does not share is a failure.
//!
//! What is measured per sweep, query, engine and point ([`PointStats`]): the
//! largest and the median error over the poses — the campaign's headline
//! error, relative to the scene's scale ([`headline`]) — and the failures by
//! kind. The **breaking point** of an engine is the first point, walking from
//! the benign end, where its largest error exceeds [`BREAK_REL`] or where it
//! fails on any pose ([`Series::walks`]).
//!
//! Decisions:
//! - **Poses keep the parameter honest.** An *exact* pose is a signed
//!   permutation of the axes: every coordinate moves without rounding, so a
//!   crossing 1e-17 from an edge is exactly that far from it, and exactly on
//!   stays exactly on. A *rotated* pose turns and moves the scene at random:
//!   every coordinate rounds once, and the parameter holds only to about an
//!   ulp of the scene — which is what a generic scene in `f64` looks like, and
//!   where formulas that round meet their limits. Sweeps whose parameter is a
//!   small distance or angle alternate the two kinds (even poses exact, odd
//!   ones rotated; only exact ones at an exact point); `offset` and
//!   `size-ratio` use rotated poses only ([`PoseMix`]).
//! - **Common random numbers.** A pose's shapes depend on the seed, the sweep,
//!   the query and the pose index — not on the point — so each pose is one
//!   scene family carried down the whole sweep, and a curve shows the
//!   parameter's effect rather than the noise between scenes.
//! - **Deterministic and portable.** Cases come from a keyed SplitMix64
//!   ([`grid::Rng`]) and basic arithmetic only (no libm transcendental), and
//!   are judged in parallel but folded in order: the same seed gives the same
//!   results on any machine and thread count.
//!
//! `crashtest sweep NAME` runs one sweep and writes its charts and data
//! ([`write()`]); the report's stability section ([`section`]) runs them all.

mod angle;
mod boxes;
mod catalog;
mod ccd;
pub(crate) mod distance;
mod feature;
pub mod grid;
mod measure;
mod offset;
mod render;
mod scene;
mod size_ratio;
mod sliver;
mod spheres;

pub use catalog::{
    BREAK_REL, BYTES_PER_SWEEP_CASE, DEFAULT_POSES, DEFAULT_SEED, PoseMix, Probe, REPORT_POSES, STANDALONE, SWEEP_FILE,
    SWEEP_MEMORY_BYTES, SWEEPS, Settings, Sweep, SweepCase, SweepPoint, cases, check_poses, find, fixture_at,
    list_text, max_poses, names, rounded_to_f32, standalone, unknown_name,
};
pub use measure::{Break, BreakWhy, PointStats, ProbeResult, Series, SweepResult, Walk, headline, run, run_all};
pub use render::{SECTION_ID, breaking_table, chart, files, section_from, table_text, write};

use crate::engines::EngineSet;
use crate::render::section::Section;

/// The stability section of a report: every sweep run with `settings`, then
/// rendered ([`section_from`]).
pub fn section(settings: &Settings, engines: &EngineSet) -> Section {
    section_from(&run_all(settings, engines), settings)
}

#[cfg(test)]
mod tests;
