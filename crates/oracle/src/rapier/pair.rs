//! Experiment (c): two balls colliding, velocities after the impact.

use super::world::{RapierWorld, Settings};
use crate::geom::{P3, Sphere};
use serde::Serialize;

/// Two balls moving freely (no gravity in the settings used) that meet once:
/// head-on when their velocities are along the line of centres, glancing when
/// the approach is offset. Both carry the same restitution (combined by `Max`
/// it is the contact's). The world runs `duration` seconds, long enough for the
/// impact and the separation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PairScene {
    /// A short name for reports.
    pub name: &'static str,
    /// Ball `a` at the start.
    pub a: Sphere,
    /// `a`'s velocity (m/s).
    pub va: P3,
    /// `a`'s mass (kg).
    pub ma: f64,
    /// Ball `b` at the start.
    pub b: Sphere,
    /// `b`'s velocity (m/s).
    pub vb: P3,
    /// `b`'s mass (kg).
    pub mb: f64,
    /// Coefficient of restitution.
    pub restitution: f64,
    /// Simulated time (s).
    pub duration: f64,
}

/// Velocities at the end of a [`PairScene`] (after the impact).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PairRun {
    /// `a`'s final velocity (m/s).
    pub velocity_a: P3,
    /// `b`'s final velocity (m/s).
    pub velocity_b: P3,
}

/// Runs a [`PairScene`] in rapier: two dynamic balls, stepped for the scene's
/// duration; their final linear velocities.
pub fn pair(settings: &Settings, scene: &PairScene) -> PairRun {
    let mut w = RapierWorld::new(*settings);
    let a = w.add_ball(scene.a.center, scene.a.radius, scene.va, scene.ma, scene.restitution);
    let b = w.add_ball(scene.b.center, scene.b.radius, scene.vb, scene.mb, scene.restitution);
    let steps = (scene.duration / settings.dt).ceil() as usize;
    for _ in 0..steps {
        w.step();
    }
    PairRun { velocity_a: w.velocity(a), velocity_b: w.velocity(b) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rapier::Ccd;

    /// Momentum is conserved by rapier's contact impulses up to the solver's
    /// rounding; kg·m/s on momenta of order 1.
    const MOMENTUM_TOL: f64 = 1e-9;

    #[test]
    fn rapier_head_on_pair_conserves_momentum_and_separates() {
        let scene = PairScene {
            name: "head-on",
            a: Sphere { center: [-1.0, 0.0, 0.0], radius: 0.5 },
            va: [2.0, 0.0, 0.0],
            ma: 1.0,
            b: Sphere { center: [1.0, 0.0, 0.0], radius: 0.5 },
            vb: [0.0; 3],
            mb: 3.0,
            restitution: 0.5,
            duration: 1.0,
        };
        let run = pair(&Settings::validation(Ccd::On).weightless(), &scene);
        let p = run.velocity_a[0] * 1.0 + run.velocity_b[0] * 3.0;
        assert!((p - 2.0).abs() <= MOMENTUM_TOL, "momentum {p}, {run:?}");
        assert!(run.velocity_b[0] > run.velocity_a[0], "separating: {run:?}");
    }
}
