//! Exact arithmetic and filtered predicates.
//!
//! The robust queries decide hit, miss and parallel with these predicates, so
//! their classification is right for every finite input, at every scale: a
//! segment stopping `1e-300` short of a face misses it, one touching it hits,
//! and a `1e300` scene is decided as a unit one is.
//!
//! - [`BigFloat`]: an arbitrary-precision binary float with exact `+`, `−`, `×`
//!   and sign, built from `f64` exactly (subnormals included).
//! - Predicates on `f64` points ([`P3`]): [`orient3d`], [`triple_product`],
//!   [`plane_side`], [`dot_diff`], [`orient2d`], [`collinear`],
//!   [`points_equal`], answering a [`Sign`]. Each runs a fast `f64` evaluation
//!   with a static forward error bound first; when that cannot decide, the
//!   exact value is computed with floating-point expansions on the stack
//!   (Shewchuk's arithmetic, no allocation) for inputs within `2^±200`, and
//!   with [`BigFloat`] (which allocates) beyond that.
//! - `_estimate` variants (and [`cross_estimate`]) also give the value, as an
//!   [`Estimate`] (`mant · 2^exp`, so it never overflows or underflows) with a
//!   stated relative error, refined on the exact path only as far as the
//!   caller asks ([`Estimate::refine_jointly`]); the queries compute segment
//!   parameters, barycentric coordinates and face normals from them, to
//!   [`ESTIMATE_REL_ERR`].
//!
//! The queries themselves first run an inline filter (`filter`, crate-private):
//! the same volumes in plain `f64`, sharing differences and cross products,
//! each with its error bound, deciding nearly every random query without
//! calling a predicate at all. Where that stage A cannot decide, a stage B
//! (`compensated`, crate-private) evaluates the undecided volumes again with
//! error-free transformations, with a bound of order `u²` times the
//! permanent that is zero when every operation was exact: near-degenerate
//! queries (within ulps of an edge or a plane, far from the origin) and exact
//! zeros on grid-like inputs (an endpoint on a plane, a line through an edge)
//! are decided there, without the expansions.
//!
//! `f32` inputs are exactly `f64` values ([`Real::wide`](crate::Real::wide)), so
//! the same predicates serve both precisions.

pub(crate) mod bigfloat;
pub(crate) mod compensated;
mod estimate;
mod expansion;
pub(crate) mod filter;
pub(crate) mod norm;
mod predicates;
mod sign;

#[cfg(test)]
mod tests;

pub use bigfloat::BigFloat;
pub use estimate::{ESTIMATE_REL_ERR, Estimate};
pub(crate) use estimate::{frexp, ldexp};

#[cfg(test)]
pub(crate) use predicates::exact_evaluations;
pub use predicates::{
    P3, collinear, cross_estimate, dot_diff, orient2d, orient2d_estimate, orient3d, orient3d_estimate, plane_side,
    plane_side_estimate, points_equal, triple_product,
};
pub use sign::Sign;
