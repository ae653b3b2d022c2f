//! The referee: crashtest's ground truth.
//!
//! Every `f64` input is taken as the exact rational number it denotes, and the
//! definitions of the fixture format (`docs/FORMAT.md`) are evaluated with big
//! rationals ([`dashu::rational::RBig`]). Every predicate — contact or apart, hit or
//! miss, parallel, inside or outside, touching — is therefore decided exactly:
//! touching (depth exactly 0) is contact, a segment stopping one ulp short of a face
//! misses it.
//!
//! Square roots are the only irrational step (norms, normalization, the distance
//! of two centres, a bounding sphere's radius). Every answer is a number of the
//! form `a + b·√q` with exact rationals `a`, `b`, `q`; it is enclosed between two
//! rationals using an integer square root of at least [`PRECISION_BITS`] bits, and
//! the enclosure is narrowed (doubling the bits) until both ends round to the same
//! `f64`. So every scalar the referee reports is the **correctly rounded** value
//! (round to nearest, ties to even) of the exact answer — the rounding happens
//! once, at the very end — and engines are measured against it as libm is measured
//! against MPFR. (The loop terminates: when `√q` is irrational, `a + b·√q` is
//! irrational and so never lies on a rounding boundary; when `√q` is rational it
//! is computed exactly.)
//!
//! Layout follows parry's: one file per query family ([`contact`], [`intersect`],
//! [`barycentric`], [`bounds`], [`overlap`]), the exact number helpers apart.
//! Each family also offers a *margin*: the exact signed quantity behind its
//! decision, rounded to `f64`, so the harness can tell a case that sits within
//! tolerance of a decision boundary ("borderline") from a clear one. A margin's
//! sign bit is the decision (`+0.0` exactly on the boundary counts as contact,
//! hit or overlap; a negative value too small for `f64` rounds to `−0.0`).
//!
//! **Two stages where the time goes.** Exact rationals cost microseconds to
//! milliseconds per query; engines answer in well under one. Where the
//! referee's time went, a floating-point stage does the search and the exact
//! stage only certifies or decides what is left:
//! - the minimal enclosing ball ([`bounds`]): Welzl's algorithm in `f64` finds
//!   a candidate support; it is kept when its exact circumball has its centre in
//!   the support's convex hull and holds every point (then it is the unique
//!   minimal ball), else exact Welzl runs;
//! - a sphere against a mesh ([`toi`] and its margin): faces whose box a
//!   rigorous `f64` lower bound puts out of reach of the sphere's whole path are
//!   skipped; the margin tests faces nearest-bound first and stops once the
//!   bound exceeds the nearest exact distance;
//! - barycentric coordinates ([`barycentric`]): computed in double-word numbers
//!   that account for their error exactly ([`fast`]), each coordinate kept when
//!   its correct rounding is certified;
//! - contact of a sphere with a sphere, a plane, a triangle or a mesh, and its margin
//!   ([`contact`]): the same, each output `A + B/√S` certified by the signs of
//!   `P + Q·√S` at the midpoints around its candidate (`contact_fast`);
//! - a segment against a plane, a triangle or a mesh, and its margin ([`intersect`]):
//!   every output a certified quotient (`intersect_fast`);
//! - a sphere's time of impact with a sphere, a plane, a triangle or a mesh,
//!   and its margin ([`toi`]): every output `(P + Q·√D)/K` certified the same
//!   way, a triangle's candidates (its vertices, edges and face) ordered by
//!   their certified roundings, a margin the largest of its candidates'
//!   certified margins (`toi_fast`);
//! - collision response ([`response`]): every velocity a certified quotient
//!   (`response_fast`).
//!
//! **Exact dyadic numbers.** What the double-word bounds leave open in
//! contact, intersect, barycentric coordinates and response is computed again,
//! by the same code, in exact dyadic numbers (`m·2^e`, big integers without a
//! gcd: `dyadic`), where every sign is certain and each quotient is rounded
//! once from exact integers (a square root by the exact stage's own `Root`).
//! A full-range case that needs two thousand bits costs tens of microseconds
//! there, milliseconds in rationals. Only the exact stage's fallbacks and
//! flags, and refused input, then reach the rationals.
//!
//! The answers are the same bits as the exact stage's alone, by construction
//! and by test ([`exact_only`] switches the stages off; `tests/referee_stages.rs`).
//! Each stage is counted ([`stage_counts`]) and a report shows the counts.
//!
//! Inputs that are not numbers (NaN, ±∞), a negative radius, a zero plane normal,
//! an inverted box or an empty point cloud are refused with a [`RefereeError`]
//! naming the field — never a panic. Geometry that is valid but degenerate
//! (concentric spheres, a zero-length segment, a zero-area triangle) is answered
//! with the documented fallback of each function and a `degenerate` flag.
//! An exact answer beyond the `f64` range rounds to ±∞, as IEEE 754 rounding does.

pub mod barycentric;
pub mod bounds;
mod closest;
pub mod contact;
mod contact_fast;
mod dyadic;
mod exact;
mod fast;
pub mod intersect;
mod intersect_fast;
pub mod overlap;
pub mod response;
mod response_fast;
pub mod toi;
mod toi_fast;

pub use barycentric::barycentric_triangle;
pub use bounds::{aabb_of_points, enclosure_margin, min_ball};
pub use contact::{
    CONCENTRIC_FALLBACK_NORMAL, contact_margin_sphere_mesh, contact_margin_sphere_plane, contact_margin_sphere_sphere,
    contact_margin_sphere_triangle, contact_plane_sphere, contact_sphere_mesh, contact_sphere_plane,
    contact_sphere_sphere, contact_sphere_triangle, contact_triangle_sphere,
};
pub use intersect::{
    intersect_margin_segment_plane, intersect_margin_segment_triangle, intersect_segment_mesh, intersect_segment_plane,
    intersect_segment_triangle,
};
pub use overlap::{overlap_aabb_aabb, overlap_margin_aabb_aabb};
pub use response::{response_sphere_plane, response_sphere_sphere};
pub use toi::{
    toi_margin_sphere_mesh, toi_margin_sphere_plane, toi_margin_sphere_sphere, toi_margin_sphere_triangle,
    toi_sphere_mesh, toi_sphere_plane, toi_sphere_sphere, toi_sphere_triangle,
};

use std::cell::Cell;
use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering};

thread_local! {
    static EXACT_ONLY: Cell<bool> = const { Cell::new(false) };
    /// This thread's counts: fast then exact, per stage.
    static HERE: Cell<[u64; 14]> = const { Cell::new([0; 14]) };
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
    /// in exact rationals.
    Toi,
    /// Collision response of a sphere against a sphere or a plane: certified
    /// from double-word numbers or decided in exact dyadic ones, or computed
    /// in exact rationals.
    Response,
}

impl Stage {
    /// Every stage, in report order.
    pub const ALL: [Stage; 7] = [
        Stage::MinBall,
        Stage::MeshFaces,
        Stage::Barycentric,
        Stage::Contact,
        Stage::Intersect,
        Stage::Toi,
        Stage::Response,
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
                "toi of a sphere with a sphere, plane, triangle or mesh, and margins: certified from double-word numbers / computed exactly"
            }
            Stage::Response => {
                "response of a sphere against a sphere or plane: certified from double-word or exact dyadic numbers / computed in rationals"
            }
        }
    }
}

/// The query kinds the referee answers in its exact stage alone (every case
/// of them is decided exactly: its share without the exact stage is 0 %), for
/// the report beside [`Stage`]'s counts.
pub const EXACT_STAGE_ONLY: &str = "overlap (its exact stage is already a handful of f64 comparisons)";

static FAST: [AtomicU64; 7] = [const { AtomicU64::new(0) }; 7];
static EXACT: [AtomicU64; 7] = [const { AtomicU64::new(0) }; 7];

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

/// The starting precision, in bits, of the referee's square roots.
///
/// A square root is enclosed between two rationals whose gap is about
/// `2^-PRECISION_BITS` of its size; when that enclosure does not yet decide the
/// rounding of the final `f64` (an answer that cancels, like a depth close to 0
/// between large radii), the precision is doubled until it does. The reported
/// values are thus correctly rounded whatever this constant is; 256 bits (well
/// above the 200 the design asks for) settles nearly every case at the first try.
pub const PRECISION_BITS: usize = 256;

/// Input the referee refuses: not a geometric question at all. Valid but
/// degenerate geometry is never an error (see each function's fallback).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefereeError {
    /// A number is NaN or infinite; `field` names it (e.g. `"a.center"`).
    NonFinite {
        /// The offending field.
        field: &'static str,
    },
    /// A sphere's radius is negative.
    NegativeRadius {
        /// The offending field.
        field: &'static str,
    },
    /// A plane's normal is the zero vector.
    ZeroNormal {
        /// The offending field.
        field: &'static str,
    },
    /// A box has `min > max` on some axis.
    InvertedAabb {
        /// The offending field.
        field: &'static str,
    },
    /// A point cloud has no points.
    NoPoints {
        /// The offending field.
        field: &'static str,
    },
    /// A mesh face names a vertex that does not exist.
    IndexOutOfRange {
        /// The offending field.
        field: &'static str,
        /// The face index.
        face: usize,
    },
}

impl fmt::Display for RefereeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { field } => write!(f, "{field}: not a finite number"),
            Self::NegativeRadius { field } => write!(f, "{field}: negative radius"),
            Self::ZeroNormal { field } => write!(f, "{field}: zero normal"),
            Self::InvertedAabb { field } => write!(f, "{field}: min > max"),
            Self::NoPoints { field } => write!(f, "{field}: no points"),
            Self::IndexOutOfRange { field, face } => {
                write!(f, "{field}: face {face} has a vertex index out of range")
            }
        }
    }
}

impl std::error::Error for RefereeError {}
