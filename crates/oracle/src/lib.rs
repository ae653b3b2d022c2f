//! References for crashtest: the engines collide is judged against.
//!
//! - [`referee`]: the truth. It takes every `f64` input as an exact value and
//!   evaluates the fixture format's definitions with big rationals (every
//!   predicate — hit, miss, parallel, inside, touching — decided exactly) and big
//!   floats of at least 200 bits where a square root is unavoidable, rounding
//!   only the final answer to `f64`.
//! - [`parry`]: parry3d-f64 and parry3d (f32), with their conventions translated
//!   to crashtest's in one place per engine; their shape casts too.
//! - [`rapier`]: rapier3d-f64 worlds stepped at a fixed `dt`, every setting set
//!   in one constructor and echoed, for the dynamics experiments (bounces,
//!   tunnelling, two-ball impacts).
//!
//! The oracle never calls `collide`: a reference that borrowed from the code it
//! judges would judge nothing. Everything here speaks the plain `f64` vocabulary
//! of [`geom`].
#![deny(missing_docs)]

/// The neutral vocabulary, from `crashtest-core`.
pub use crashtest_core::geom;
pub mod parry;
#[cfg(feature = "rapier")]
pub mod rapier;
pub mod referee;
