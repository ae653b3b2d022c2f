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
//! [`barycentric`], [`bounds`], [`overlap`]), the exact number helpers apart;
//! the oriented box ([`boxes`]: sphere–box and box–plane contact, segment–box,
//! a box's bounds, box–box and box–aabb overlap) and the capsule ([`capsule`]:
//! sphere–capsule, capsule–capsule and capsule–plane contact) each have their
//! own file across the families. A box's rotation is exact (its quaternion's
//! matrix has rational entries and exactly unit columns), so every decision
//! about boxes is a comparison of rationals too. Where a contact point is not
//! unique (a box resting on a plane, parallel capsules side by side), the
//! referee also gives the whole contact region (`contact_region_*`).
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
//! - the overlap of an oriented box with a box or an aabb, and its margin
//!   ([`boxes`]): the fifteen separating axes in `f64`, each value with a
//!   rigorous bound on its error, decide the clear cases and pick the margin's
//!   least axis, which alone is then computed in rationals (`boxes_fast`).
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
//! an inverted box, an oriented box's negative half-extent or zero quaternion,
//! or an empty point cloud are refused with a [`RefereeError`]
//! naming the field — never a panic. Geometry that is valid but degenerate
//! (concentric spheres, a zero-length segment, a zero-area triangle) is answered
//! with the documented fallback of each function and a `degenerate` flag.
//! An exact answer beyond the `f64` range rounds to ±∞, as IEEE 754 rounding does.

pub mod barycentric;
pub mod bounds;
pub mod boxes;
mod boxes_fast;
pub mod capsule;
pub mod ccd;
mod ccd_fast;
mod ccd_poly;
mod closest;
pub mod contact;
mod contact_fast;
pub mod convex;
pub mod distance;
mod dyadic;
mod error;
mod exact;
mod fast;
pub mod hull;
pub mod intersect;
mod intersect_fast;
pub mod overlap;
mod push_filter;
pub mod response;
mod response_fast;
mod root_fast;
mod stage;
pub mod toi;
pub mod toi_box;
mod toi_fast;

pub use barycentric::barycentric_triangle;
pub use bounds::{aabb_of_points, enclosure_margin, min_ball};
pub use boxes::{
    bounds_box, contact_box_plane, contact_margin_box_plane, contact_margin_sphere_box, contact_region_box_plane,
    contact_sphere_box, intersect_segment_box, overlap_box_aabb, overlap_box_box, overlap_margin_box_aabb,
    overlap_margin_box_box,
};
pub use capsule::{
    contact_capsule_capsule, contact_capsule_plane, contact_margin_capsule_capsule, contact_margin_capsule_plane,
    contact_margin_sphere_capsule, contact_region_capsule_capsule, contact_region_capsule_plane,
    contact_sphere_capsule, intersect_margin_segment_capsule, intersect_segment_capsule,
};
pub use ccd::{ccd_point_triangle, ccd_segment_segment};
pub use contact::{
    CONCENTRIC_FALLBACK_NORMAL, contact_margin_sphere_mesh, contact_margin_sphere_plane, contact_margin_sphere_sphere,
    contact_margin_sphere_triangle, contact_plane_sphere, contact_sphere_mesh, contact_sphere_plane,
    contact_sphere_sphere, contact_sphere_triangle, contact_triangle_sphere,
};
pub use convex::{
    contact_box_box, contact_box_triangle, contact_capsule_box, contact_capsule_triangle, contact_margin_box_box,
    contact_margin_box_triangle, contact_margin_capsule_box, contact_margin_capsule_triangle, contact_region_box_box,
    contact_region_box_triangle, contact_region_capsule_box, contact_region_capsule_triangle,
};
pub use distance::{distance, distance_alternatives, distance_witnesses};
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
pub use toi_box::{toi_margin_sphere_box, toi_sphere_box};

pub use error::{PRECISION_BITS, RefereeError};
pub use stage::{EXACT_STAGE_ONLY, Stage, exact_only, stage_counts, stage_counts_on_this_thread};
