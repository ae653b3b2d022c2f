//! # collide — collision queries from scratch
//!
//! The methods of a computer-animation lecture on collision, written faithfully,
//! and beside each one that is fragile or slow, a robust or faster method. Both are
//! public: crashtest runs them side by side against parry and an exact referee to
//! show where each stands.
//!
//! Decisions:
//! - **Generic over `f32` and `f64`** ([`Real`]), so precision is measurable.
//! - **Conventions are the fixture format's** (`docs/FORMAT.md`): in
//!   `contact(a, b)` the normal points from `b` toward `a` and is unit length, the
//!   point lies on `b`'s surface, depth ≥ 0 and touching counts as contact. A
//!   plane `n · x = d` bounds the solid `n · x ≤ d`. A triangle's face normal is
//!   `(v1 − v0) × (v2 − v0)`, normalized.
//! - **Naming** (after Ericson): `test_*` answers yes/no, `intersect_*` and
//!   `contact_*` say where, `closest_pt_*` returns a point. The lecture's form of a
//!   query carries the suffix `_lecture`; the unsuffixed function is the robust one.
//!   One argument order everywhere; the reverse order is a thin wrapper.
//! - **Degenerate input never panics and never yields NaN**: it is answered with a
//!   documented fallback and a `degenerate` flag.
//! - **No serde, no parry, no rapier**: nalgebra only. This is a library someone
//!   could use alone.
#![deny(missing_docs)]
// `!(x <= y)` is this crate's idiom for "not certainly at most": it is true for
// a NaN, which is the point (a NaN never passes a test it cannot pass);
// `partial_cmp` would hide that behind an `Option`.
#![allow(clippy::neg_cmp_op_on_partial_ord, reason = "`!(x <= y)` is deliberately true for NaN")]

pub mod barycentric;
pub mod batch;
pub mod bounds;
pub mod boxes;
pub mod ccd;
pub mod contact;
pub mod convex;
pub mod exact;
pub mod intersect;
pub mod mesh;
pub mod real;
pub mod response;
pub mod shapes;
#[cfg(test)]
mod test_support;
pub mod toi;

pub use ccd::Ccd;
pub use real::{Real, Vec3};
pub use shapes::{Aabb, Capsule, OrientedBox, Plane, Segment, Sphere, Triangle};
