//! The double-precision engine, [`super::Parry64`]: parry3d-f64, whose scalar is
//! `f64`, so the edge conversions are the identity.

use parry3d_f64 as backend;

/// The engine's scalar.
type Real = f64;

/// The engine this instantiation of the adapter body implements.
type Engine = super::api::Parry64;

/// An input scalar in the engine's precision: unchanged.
fn narrow(x: f64) -> Real {
    x
}

/// An engine scalar as an answer: unchanged.
fn widen(x: Real) -> f64 {
    x
}

/// Tolerance of the hand-computed smoke cases, absolute, in the cases' length
/// units (lengths of order 1): a few ulps of `f64` at 1 cover the handful of
/// roundings in parry's formulas.
#[cfg(test)]
const SMOKE_TOL: f64 = 1e-14;

// The adapter body is shared with the other precision: compiling the same file
// once per parry crate is the point, not an accident.
#[allow(clippy::duplicate_mod, reason = "engine.rs is instantiated once per precision")]
#[path = "engine.rs"]
mod engine;

pub use engine::{PreparedMesh, PreparedSolid, distance_prepared, solid};
/// The edge conversions and shape placements, shared with the casts.
pub(crate) use engine::{answer_point, ball, cuboid, half_space, vector};
