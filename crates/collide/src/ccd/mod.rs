//! Continuous collision detection of linearly moving points: vertex–face and
//! edge–edge, the primitives of cloth and deformable-body simulators.
//!
//! Every point moves on a straight line between its positions at `t = 0` and
//! `t = 1`, `x(t) = (1 − t) x0 + t x1`, and the queries ask for the **first
//! time** in `[0, t_max]` (`t_max ∈ [0, 1]`) at which
//!
//! - **vertex–face**: the point `p` lies on the closed triangle `a b c`;
//! - **edge–edge**: the closed segments `a0 a1` and `b0 b1` share a point.
//!
//! Both happen only when the four points are coplanar, at the roots in
//! `[0, t_max]` of the coplanarity cubic `f(t) = det[b − a, c − a, p − a]`
//! (edge–edge: `det[a1 − a0, b0 − a0, b1 − a0]`), and at a root the question
//! is a static one.
//!
//! Two methods, side by side (the crate's naming: `_lecture` is the lecture's
//! form, the unsuffixed function the robust one):
//!
//! - **the lecture's** ([`ccd_vertex_face_lecture`], [`ccd_edge_edge_lecture`]),
//!   as simulators write it (Provot 1997; Bridson, Fedkiw & Anderson 2002):
//!   the cubic's coefficients in `f64`, its roots by bracketing at the
//!   derivative's roots and Newton's method, and at each root, in increasing
//!   order, a static inside test widened by [`LECTURE_INSIDE_TOL`]. It misses
//!   and invents contacts on near-degenerate queries: that is what is
//!   measured.
//! - **robust** ([`ccd_vertex_face`], [`ccd_edge_edge`]): the answer is the
//!   exact one for every finite input — no false positive, no false
//!   negative — and the time is the exact first time correctly rounded
//!   (within 2 ulps where the filter answers). A floating-point filter with
//!   rigorous error bounds decides ordinary queries (certifying that the
//!   cubic has no root, or bracketing a simple root and certifying the
//!   contact test's margins around it); the rest goes to an exact stage on
//!   polynomials in `t` with exact coefficients: square-free parts and
//!   greatest common divisors by pseudo-remainders, roots isolated by
//!   Bernstein subdivision, signs at algebraic roots decided exactly
//!   (tangencies, contacts exactly on an edge or vertex, coplanar motion,
//!   zero-area triangles, parallel edges included).
//!
//! **The answer** ([`Ccd`]): the time, or `None`, and a `degenerate` flag set
//! exactly when the motion is coplanar throughout (`f ≡ 0` as a polynomial),
//! or, at the reported time, the triangle has zero area (the segments are
//! parallel, or one has zero length). The lecture's method sets the flag by
//! its own floating-point view of the same conditions.
//!
//! **Input**: the four points at `t = 0` and at `t = 1`, in the order
//! `[p, a, b, c]` (vertex–face) or `[a0, a1, b0, b1]` (edge–edge) — the
//! order of the published CCD benchmark's queries (Wang et al., *A Large
//! Scale Benchmark and an Inclusion-Based Algorithm for Continuous Collision
//! Detection*, 2021). `t_max` is clamped to `[0, 1]`. A non-finite
//! coordinate or a NaN `t_max` gives [`Ccd::DEGENERATE_MISS`]. Never a panic,
//! never a NaN.

mod exact_stage;
mod fe;
mod filter;
mod lecture;
mod poly;

#[cfg(test)]
mod tests;

pub use lecture::{LECTURE_INSIDE_TOL, LECTURE_PARALLEL_TOL};

use crate::real::Vec3;

/// The answer of a continuous collision query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ccd {
    /// The first time of contact in `[0, t_max]`, or `None`.
    pub t: Option<f64>,
    /// Coplanar motion throughout, or a zero-area triangle (parallel or
    /// zero-length segments) at the reported time; see the module
    /// documentation.
    pub degenerate: bool,
}

impl Ccd {
    /// No contact, not degenerate.
    pub const MISS: Self = Self { t: None, degenerate: false };
    /// No contact, input degenerate (non-finite input, for instance).
    pub const DEGENERATE_MISS: Self = Self { t: None, degenerate: true };

    /// A contact at `t`, not degenerate.
    pub(crate) fn hit(t: f64) -> Self {
        Self { t: Some(t), degenerate: false }
    }
}

/// The four points of a query at one time.
pub(crate) type Inputs = [[f64; 3]; 4];

/// Which query: the points are `[p, a, b, c]` or `[a0, a1, b0, b1]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Query {
    VertexFace,
    EdgeEdge,
}

/// The inputs as plain arrays, and `t_max` clamped; `None` for a non-finite
/// input.
fn prepare(x0: &[Vec3<f64>; 4], x1: &[Vec3<f64>; 4], t_max: f64) -> Option<(Inputs, Inputs, f64)> {
    let arr = |x: &[Vec3<f64>; 4]| x.map(|p| [p.x, p.y, p.z]);
    let (a, b) = (arr(x0), arr(x1));
    let finite = a.iter().chain(b.iter()).flatten().all(|c| c.is_finite());
    (finite && !t_max.is_nan()).then(|| (a, b, t_max.clamp(0.0, 1.0)))
}

fn robust(q: Query, x0: &[Vec3<f64>; 4], x1: &[Vec3<f64>; 4], t_max: f64) -> Ccd {
    let Some((a, b, t_max)) = prepare(x0, x1, t_max) else {
        return Ccd::DEGENERATE_MISS;
    };
    filter::solve(q, &a, &b, t_max).unwrap_or_else(|| exact_stage::solve(q, &a, &b, t_max))
}

/// Robust vertex–face continuous collision: the first time in `[0, t_max]`
/// at which the point `p` lies on the closed triangle `a b c`, exactly
/// decided and correctly rounded (see the [module](self) documentation).
///
/// `x0 = [p, a, b, c]` at `t = 0`, `x1` the same points at `t = 1`.
pub fn ccd_vertex_face(x0: &[Vec3<f64>; 4], x1: &[Vec3<f64>; 4], t_max: f64) -> Ccd {
    robust(Query::VertexFace, x0, x1, t_max)
}

/// Robust edge–edge continuous collision: the first time in `[0, t_max]` at
/// which the closed segments `a0 a1` and `b0 b1` share a point, exactly
/// decided and correctly rounded (see the [module](self) documentation).
///
/// `x0 = [a0, a1, b0, b1]` at `t = 0`, `x1` the same points at `t = 1`.
pub fn ccd_edge_edge(x0: &[Vec3<f64>; 4], x1: &[Vec3<f64>; 4], t_max: f64) -> Ccd {
    robust(Query::EdgeEdge, x0, x1, t_max)
}

/// The lecture's vertex–face continuous collision (Provot; Bridson et al.):
/// the coplanarity cubic's roots in `f64`, and at each, in increasing order,
/// the barycentric coordinates of `p` (Ericson's Cramer form), inside when
/// all are at least `−LECTURE_INSIDE_TOL`.
///
/// Degenerate ([`Ccd::degenerate`]): the cubic's computed coefficients are
/// all zero (coplanar motion; the lecture then tests `t = 0` alone), or at a
/// root the triangle's 2 × 2 system is singular (no contact counted there).
/// Non-finite input or coefficients: [`Ccd::DEGENERATE_MISS`].
pub fn ccd_vertex_face_lecture(x0: &[Vec3<f64>; 4], x1: &[Vec3<f64>; 4], t_max: f64) -> Ccd {
    match prepare(x0, x1, t_max) {
        Some((a, b, t_max)) => lecture::vertex_face(&a, &b, t_max),
        None => Ccd::DEGENERATE_MISS,
    }
}

/// The lecture's edge–edge continuous collision: the coplanarity cubic's
/// roots in `f64`, and at each, in increasing order, the parameters of the
/// lines' closest points (Ericson §5.1.9), a contact when both are within
/// `[−LECTURE_INSIDE_TOL, 1 + LECTURE_INSIDE_TOL]`.
///
/// Degenerate: coplanar motion as for [`ccd_vertex_face_lecture`], or at a
/// root the edges parallel by [`LECTURE_PARALLEL_TOL`] (no contact counted
/// there). Non-finite input or coefficients: [`Ccd::DEGENERATE_MISS`].
pub fn ccd_edge_edge_lecture(x0: &[Vec3<f64>; 4], x1: &[Vec3<f64>; 4], t_max: f64) -> Ccd {
    match prepare(x0, x1, t_max) {
        Some((a, b, t_max)) => lecture::edge_edge(&a, &b, t_max),
        None => Ccd::DEGENERATE_MISS,
    }
}
