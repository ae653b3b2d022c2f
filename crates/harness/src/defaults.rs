//! The campaign's defaults, shared by the campaign and the experiments that
//! run with it (the sweeps, the scene and toi sections): its seed, its case
//! counts, and how long its timing loops run.

/// The built-in campaign's random cases per query kind.
pub const DEFAULT_CASES: u64 = 10_000;

/// The built-in campaign's seed.
pub const DEFAULT_SEED: u64 = 20_261_122;

/// The built-in campaign's full-range cases per query kind (see
/// `generate::full_range`), judged and scored apart from the ordinary mix: enough
/// that each of its five sub-families gets a few hundred cases of every kind.
pub const DEFAULT_FULL_RANGE_CASES: u64 = 1_000;

/// Timing loops run over at most this many generated cases per query kind:
/// enough to mix the families as the campaign does, small enough that a
/// repetition takes milliseconds.
pub const TIMING_CASES: usize = 2_000;

/// The referee's timing loop runs over at most this many of those cases: it
/// takes tens of microseconds to a millisecond a query (the engines take well
/// under one), so over [`TIMING_CASES`] its seven repetitions took most of the
/// timing phase — about 5 s of a 16.6 s default report — for a figure that
/// only estimates its share of the campaign. A tenth still mixes the families.
pub const REFEREE_TIMING_CASES: usize = 200;

/// Repetitions of each timing loop; the median is reported with the spread.
pub const TIMING_REPS: u32 = 7;
