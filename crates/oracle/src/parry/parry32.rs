//! The single-precision engine, [`super::Parry32`]: parry3d, whose scalar is
//! `f32`. Inputs are rounded to `f32` at the edge (to nearest; beyond `f32`'s
//! range they become infinite and are refused by the adapter), answers widened
//! back to `f64` exactly.

use parry3d as backend;

/// The engine's scalar.
type Real = f32;

/// The engine this instantiation of the adapter body implements.
type Engine = super::api::Parry32;

/// An input scalar in the engine's precision: rounded to the nearest `f32`
/// (overflowing to ±∞, underflowing to a subnormal or ±0).
fn narrow(x: f64) -> Real {
    x as f32
}

/// An engine scalar as an answer: widened to `f64`, exactly.
fn widen(x: Real) -> f64 {
    f64::from(x)
}

/// Tolerance of the hand-computed smoke cases, absolute, in the cases' length
/// units (lengths of order 1): a few ulps of `f32` at 1 (ulp ≈ 1.2e-7) cover the
/// handful of roundings in parry's formulas.
#[cfg(test)]
const SMOKE_TOL: f64 = 1e-6;

// The adapter body is shared with the other precision: compiling the same file
// once per parry crate is the point, not an accident.
#[allow(clippy::duplicate_mod, reason = "engine.rs is instantiated once per precision")]
#[path = "engine.rs"]
mod engine;

pub use engine::{PreparedMesh, PreparedSolid, distance_prepared, solid};
/// The edge conversions and shape placements, shared with the casts.
pub(crate) use engine::{answer_point, ball, cuboid, half_space, vector};
