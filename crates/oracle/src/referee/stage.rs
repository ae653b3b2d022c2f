//! The referee's two stages, switched and counted: whether the
//! floating-point stages may answer on this thread ([`exact_only`] turns them
//! off), and how often each stage's answer was certified and how often the
//! exact stage had to decide ([`stage_counts`]).

use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};

thread_local! {
    static EXACT_ONLY: Cell<bool> = const { Cell::new(false) };
    /// This thread's counts: fast then exact, per stage.
    static HERE: Cell<[u64; 2 * STAGES]> = const { Cell::new([0; 2 * STAGES]) };
}

/// Runs `f` with the referee's floating-point stages off on this thread: every
/// answer then comes from the exact stage alone. The answers are the same bit
/// for bit either way (the stages only skip exact work they have proved
/// unneeded); this is how that is checked (`tests/referee_stages.rs`).
pub fn exact_only<T>(f: impl FnOnce() -> T) -> T {
    let before = EXACT_ONLY.with(|e| e.replace(true));
    let out = f();
    EXACT_ONLY.with(|e| e.set(before));
    out
}

/// Whether the floating-point stages may answer on this thread.
pub(crate) fn staged() -> bool {
    !EXACT_ONLY.with(Cell::get)
}

/// A floating-point stage's answer, counted under `stage`, when the stages
/// are on and it certified one; `None` sends the caller to its exact stage.
pub(crate) fn fast_stage<T>(stage: Stage, fast: impl FnOnce() -> Option<T>) -> Option<T> {
    if !staged() {
        return None;
    }
    let answer = fast();
    count(stage, answer.is_some(), 1);
    answer
}

/// Whether the floating-point stage certified that the shapes are apart
/// (counted under [`Stage::ShapesApart`]); `false` sends the caller to its
/// exact stage.
pub(crate) fn apart(fast: impl FnOnce() -> bool) -> bool {
    fast_stage(Stage::ShapesApart, || fast().then_some(())).is_some()
}

/// The referee's two-stage computations, each counted: how often the
/// floating-point stage's answer was certified, and how often the exact stage
/// had to decide.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// The minimal enclosing ball (`bounds`): a floating-point Welzl's support,
    /// certified exactly, or exact Welzl.
    MinBall,
    /// A sphere against a mesh (`toi` and its margin), when the exact stage
    /// answers: faces whose box is provably out of reach skipped, or a
    /// face's exact test run.
    MeshFaces,
    /// Barycentric coordinates: certified from double-word numbers or
    /// decided in exact dyadic ones, or computed in exact rationals.
    Barycentric,
    /// Contact of a sphere with a sphere, a plane, a triangle or a mesh, and
    /// its margin: certified from double-word numbers or decided in exact
    /// dyadic ones, or computed in exact rationals.
    Contact,
    /// A segment against a plane, a triangle or a mesh, and its margin:
    /// certified from double-word numbers or decided in exact dyadic ones, or
    /// computed in exact rationals.
    Intersect,
    /// A sphere's time of impact with a sphere, a plane, a triangle or a
    /// mesh, and its margin: certified from double-word numbers, or computed
    /// in exact rationals; with a box, a miss certified from bounded `f64`
    /// projections of the path's capsule, or the answer computed exactly.
    Toi,
    /// Collision response of a sphere against a sphere or a plane: certified
    /// from double-word numbers or decided in exact dyadic ones, or computed
    /// in exact rationals.
    Response,
    /// Continuous collision (`ccd`, vertex–face and edge–edge): a miss
    /// certified from the coplanarity cubic's double-word Bernstein bounds or
    /// disjoint swept boxes, or the answer computed in exact polynomials.
    Ccd,
    /// Overlap of an oriented box with a box or an aabb, and its margin: the
    /// decision (or the margin's least axis) certified from bounded `f64`
    /// separating axes, or all fifteen axes computed in rationals.
    BoxOverlap,
    /// Contact of a box or a capsule (sphere–box, box–plane, sphere–capsule,
    /// capsule–capsule, capsule–plane) and a segment against a box: shapes
    /// certainly apart (the segment certainly missing) along one direction
    /// chosen in `f64`, from bounded projections, or the answer computed in
    /// rationals.
    ShapesApart,
    /// The least push over separating axes (the penetration of two meeting
    /// polytopes: `distance`, and box and capsule contact): pushes set aside
    /// as certainly longer than another from bounded `f64` projections, or
    /// computed and compared in rationals.
    SeparatingAxes,
}

/// How many stages there are.
const STAGES: usize = 11;

impl Stage {
    /// Every stage, in report order.
    pub const ALL: [Stage; STAGES] = [
        Stage::MinBall,
        Stage::MeshFaces,
        Stage::Barycentric,
        Stage::Contact,
        Stage::Intersect,
        Stage::Toi,
        Stage::Response,
        Stage::Ccd,
        Stage::BoxOverlap,
        Stage::ShapesApart,
        Stage::SeparatingAxes,
    ];

    /// What is counted, for the report.
    pub fn label(self) -> &'static str {
        match self {
            Stage::MinBall => "bounds: minimal balls certified from floating point / by exact Welzl",
            Stage::MeshFaces => "toi sphere–mesh: faces ruled out in floating point / tested exactly",
            Stage::Barycentric => {
                "barycentric: certified from double-word or exact dyadic numbers / computed in rationals"
            }
            Stage::Contact => {
                "contact of a sphere with a sphere, plane, triangle or mesh, and margins: certified from double-word or exact dyadic numbers / computed in rationals"
            }
            Stage::Intersect => {
                "intersect of a segment with a plane, triangle or mesh, and margins: certified from double-word or exact dyadic numbers / computed in rationals"
            }
            Stage::Toi => {
                "toi of a sphere with a sphere, plane, triangle, mesh or box, and margins: certified from double-word numbers (a box: a miss from bounded f64 projections) / computed exactly"
            }
            Stage::Response => {
                "response of a sphere against a sphere or plane: certified from double-word or exact dyadic numbers / computed in rationals"
            }
            Stage::Ccd => {
                "ccd vertex–face and edge–edge: misses certified from double-word Bernstein bounds / computed in exact polynomials"
            }
            Stage::BoxOverlap => {
                "overlap of boxes, and margins: decision or least axis certified from bounded f64 / all axes computed in rationals"
            }
            Stage::ShapesApart => {
                "contact of a box or capsule, segment–box: apart certified from bounded f64 projections / computed in rationals"
            }
            Stage::SeparatingAxes => {
                "least push over separating axes (distance, box and capsule contact): pushes set aside from bounded f64 projections / compared in rationals"
            }
        }
    }
}

/// The query kinds the referee answers in its exact stage alone (every case
/// of them is decided exactly: its share without the exact stage is 0 %), for
/// the report beside [`Stage`]'s counts.
pub const EXACT_STAGE_ONLY: &str = "overlap of two aabbs (its exact stage is already a handful of f64 comparisons); a box's bounds (a handful of products, rounded once); box and capsule contact and segment–box where the shapes meet (the floating-point stage certifies only that they are apart)";

static FAST: [AtomicU64; STAGES] = [const { AtomicU64::new(0) }; STAGES];
static EXACT: [AtomicU64; STAGES] = [const { AtomicU64::new(0) }; STAGES];

/// Counts `n` answers of `stage`, by the floating-point stage or the exact one.
pub(crate) fn count(stage: Stage, fast: bool, n: u64) {
    let counters = if fast { &FAST } else { &EXACT };
    counters[stage as usize].fetch_add(n, Ordering::Relaxed);
    HERE.with(|h| {
        let mut c = h.get();
        c[2 * stage as usize + usize::from(!fast)] += n;
        h.set(c);
    });
}

/// A one-entry memory of an exact computation on this thread: the last key
/// (with whether the stages were on), its value and the stage counts
/// computing it made.
pub(crate) type Memo<K, V> = std::cell::RefCell<Option<((K, bool), V, [u64; 2 * STAGES])>>;

/// `f()`, remembered for `key` on this thread (in `slot`, one entry): asked
/// again for the same key — as a case's answer, its margin and its contact
/// region each ask for the same polytopes and least push — it returns the
/// value computed before and counts that computation's stages again, so the
/// counts are what computing it each time would give. The key holds whether
/// the floating-point stages are on ([`exact_only`] computes afresh).
pub(crate) fn remembered<K: PartialEq, V: Clone>(
    slot: &'static std::thread::LocalKey<Memo<K, V>>,
    key: K,
    f: impl FnOnce() -> V,
) -> V {
    let key = (key, staged());
    let hit = slot.with(|m| m.borrow().as_ref().filter(|(k, _, _)| *k == key).map(|(_, v, c)| (v.clone(), *c)));
    if let Some((value, counts)) = hit {
        for (i, &stage) in Stage::ALL.iter().enumerate() {
            count(stage, true, counts[2 * i]);
            count(stage, false, counts[2 * i + 1]);
        }
        return value;
    }
    let before = HERE.with(Cell::get);
    let value = f();
    let after = HERE.with(Cell::get);
    let made: [u64; 2 * STAGES] = std::array::from_fn(|i| after[i] - before[i]);
    slot.with(|m| *m.borrow_mut() = Some((key, value.clone(), made)));
    value
}

/// [`stage_counts`] for the work done on this thread only.
pub fn stage_counts_on_this_thread() -> Vec<(Stage, u64, u64)> {
    let c = HERE.with(Cell::get);
    Stage::ALL.iter().map(|&s| (s, c[2 * s as usize], c[2 * s as usize + 1])).collect()
}

/// The counts so far in this process, per stage: `(stage, fast, exact)`.
/// Subtract an earlier reading to count one stretch of work.
pub fn stage_counts() -> Vec<(Stage, u64, u64)> {
    Stage::ALL
        .iter()
        .map(|&s| (s, FAST[s as usize].load(Ordering::Relaxed), EXACT[s as usize].load(Ordering::Relaxed)))
        .collect()
}
