//! parry as a reference: parry3d-f64 ([`Parry64`]) and parry3d in `f32`
//! ([`Parry32`]), pinned at [`PARRY_VERSION`], speaking crashtest's neutral
//! vocabulary ([`crate::geom`]).
//!
//! Both engines implement [`ParryEngine`]. The two parry crates have the same API
//! over different scalars, so the adapter body is written once (`engine.rs`) and
//! compiled once per precision; the precision modules supply only the crate, the
//! scalar and the two conversions at the edge:
//!
//! - **inputs** are rounded to the engine's scalar first (`f64` → `f32` rounds to
//!   nearest; a value beyond `f32`'s range becomes infinite and is refused as
//!   below), and everything after that — differences, normalizations, the shapes'
//!   placement — is computed in the engine's scalar, as a user of that crate would;
//! - **answers** are widened back to `f64` exactly.
//!
//! # Conventions, and their translation
//!
//! Everything parry says is translated to crashtest's conventions (docs/FORMAT.md) in
//! exactly one place per kind of answer (`translate_contact`, `translate_hit` and
//! `translate_location` in `engine.rs`). What parry says:
//!
//! | | parry 0.31.1 | crashtest | translation |
//! | --- | --- | --- | --- |
//! | contact normal | `normal1`: unit, outward from shape 1, i.e. from shape 1 toward shape 2 (`normal2 = −normal1` in world space) | unit, from `b` toward `a` | query `contact(a, b)` calls parry with shape 1 = `a`, shape 2 = `b`; normal = `−normal1` |
//! | contact point | `point1` on shape 1, `point2` on shape 2, both world frame (`query::contact` moves them out of the local frames) | on `b`'s surface | point = `point2` |
//! | depth | `dist`: signed distance, `< 0` is penetration, `0` touching | depth ≥ 0 | depth = `−dist` (computed as `0 − dist`, so an exact touch gives `+0`) |
//! | touching | counted by `dist ≤ prediction` (ball–half-space, ball–triangle); **not** by ball–ball (`‖Δ‖² < (r1 + r2)²`, strict) | counted | prediction is `0`, parry's raw behaviour is reported (a known divergence for ball–ball) |
//! | plane | [`HalfSpace`](parry3d_f64::shape::HalfSpace): unit outward normal, boundary through the shape's origin, solid on `normal · x ≤ 0` | `n · x = d`, solid `n · x ≤ d` | half-space with normal `n̂ = n/‖n‖`, placed at the translation `(d/‖n‖) n̂` |
//! | ray hit normal | toward the ray's origin side: a half-space's normal is negated when the origin is inside it; a triangle's `(b − a) × (c − a)` normal is negated when the origin is behind it | the surface's own normal, never flipped | the returned normal is negated when it opposes the surface's own normal (`n̂`, or parry's `Triangle::normal()`) |
//! | ray parameter | `time_of_impact` along `dir`, hits with `toi ≤ max` | `t ∈ [0, 1]` along `end − start` | ray origin `start`, `dir = end − start`, max time of impact `1`; `t = toi`, point = `ray.point_at(toi)` |
//! | triangle sides | ray casts and contacts are two-sided | a segment hits a triangle from either side; a contact normal points toward the sphere | none needed beyond the normal's orientation |
//! | barycentrics | `TrianglePointLocation` of the projection onto the *triangle* (clamped to its edges and vertices) | signed coordinates of the projection onto the triangle's *plane* | identical inside the triangle (`OnFace`); outside, parry's clamped answer is reported raw (a known divergence) |
//! | frames | shapes are placed by a `Pose` (world); the triangle is built from world vertices at the identity pose; the ball at the translation of its centre | world | answers are read in world space |
//!
//! # Degenerate input and NaN
//!
//! No query panics and none returns a NaN. A zero or non-finite plane normal, a
//! zero-length segment, a radius that is not positive, an empty point set, or an
//! input that is not finite in the engine's scalar is answered with the fallback
//! the query documents (no contact, no hit, `None`) and `degenerate: true`. A
//! triangle is zero-area exactly when parry's own `Triangle::normal()` is `None`
//! (its cross product is zero, or too small or too large to normalize in the
//! engine's scalar). Every number parry returns is checked: a non-finite one turns
//! the answer into its fallback with `degenerate: true`.
//!
//! # Known defects
//!
//! parry 0.31.1's `contact(ball, half-space)` (in that order) mis-places the ball
//! (see [`ParryEngine::contact_sphere_plane`]). Defects are reported raw, not
//! translated away and not listed as divergences; each is pinned by a test.
//!
//! # Known divergences
//!
//! Differences that cannot be translated are data: [`known_divergences`] lists
//! them for both engines, and each is pinned by a test that shows it still
//! happens, so a parry release that stops diverging fails the build's tests
//! instead of leaving a stale entry.

mod api;
mod cast;
mod parry32;
mod parry64;
mod queries;
pub mod reproduce;

pub use api::{KnownDivergence, PARRY_VERSION, Parry32, Parry64, ParryEngine, known_divergences};
pub use cast::{CastAnswer, CastStatus, ParryCast, cast_known_divergences};
pub use parry32::PreparedMesh as Parry32Mesh;
/// A distance's solids built once in each precision's shapes, and the
/// distance of two of them (the adapters' `distance`, split for benches).
pub use parry32::{PreparedSolid as Parry32Solid, distance_prepared as parry32_distance, solid as parry32_solid};
pub use parry64::PreparedMesh as Parry64Mesh;
pub use parry64::{PreparedSolid as Parry64Solid, distance_prepared as parry64_distance, solid as parry64_solid};

#[cfg(test)]
mod tests {
    use super::api::*;

    #[test]
    fn parry_known_divergences_listed_once_per_engine() {
        for engine in [Parry64::NAME, Parry32::NAME] {
            let listed: Vec<_> = known_divergences().iter().filter(|k| k.engine == engine).collect();
            assert_eq!(listed.len(), DIVERGENCES.len(), "entries for {engine}");
            for d in DIVERGENCES {
                assert_eq!(
                    listed.iter().filter(|k| k.what == d.what).count(),
                    1,
                    "{engine}: `{}` listed exactly once",
                    d.what
                );
            }
        }
    }

    #[test]
    fn parry_version_matches_the_pinned_manifest() {
        let manifest = include_str!("../../../../Cargo.toml");
        for krate in ["parry3d-f64", "parry3d"] {
            let line = format!("{krate} = \"={PARRY_VERSION}\"");
            assert!(manifest.lines().any(|l| l.trim() == line), "workspace manifest pins `{line}`");
        }
    }
}
