//! rapier3d-f64 as the dynamics reference: worlds stepped at a fixed `dt`, with
//! every setting that matters for validation set explicitly in one constructor
//! ([`RapierWorld::new`]) and echoed ([`Settings::echo`]) in every report.
//!
//! A geometric question goes to a parry query ([`crate::parry`]); rapier is used
//! only where dynamics are the question. Three experiments, each a function that
//! returns plain data:
//!
//! - [`bounce`]: a ball dropped on a plane, apex heights bounce by bounce;
//! - [`tunnel`]: a small fast ball shot at a thin wall: does it pass through?
//! - [`pair`]: two balls colliding head-on or glancing: velocities afterwards.
//!
//! Scenes are plain data ([`BounceScene`], [`TunnelScene`], [`PairScene`]) so
//! that the harness runs the very same scenes through its own worlds. The apex
//! measurement ([`apexes`]) is shared for the same reason.
//!
//! Axes: gravity acts along `−z` and the ground is the plane `z = 0` (solid
//! below), as in the fixture format's examples; walls face `−x`.
//!
//! rapier is pinned at [`RAPIER_VERSION`] and uses parry3d-f64 0.31.1, the
//! release [`crate::parry`] is pinned to.

mod bounce;
mod pair;
mod tunnel;
mod world;

pub use bounce::{APEX_FLOOR, BounceRun, BounceScene, FREE_FLIGHT_REL, apexes, bounce};
pub use pair::{PairRun, PairScene, pair};
pub use tunnel::{TunnelRun, TunnelScene, WALL_HALF_SPAN, tunnel};
pub use world::{Body, Ccd, Combine, RapierWorld, Settings};

/// The rapier release the dynamics reference is pinned to (`=0.36.1` in the
/// workspace manifest); reports print it beside the engine's name.
pub const RAPIER_VERSION: &str = "0.36.1";

/// The engine's name in reports.
pub const RAPIER_NAME: &str = "rapier3d-f64";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rapier_version_matches_the_pinned_manifest() {
        let manifest = include_str!("../../../../Cargo.toml");
        let line = format!("rapier3d-f64 = \"={RAPIER_VERSION}\"");
        assert!(manifest.lines().any(|l| l.trim() == line), "workspace manifest pins `{line}`");
    }
}
