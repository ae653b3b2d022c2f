//! Experiment (b): tunnelling — a small fast ball shot at a thin wall.

use super::world::{RapierWorld, Settings};
use serde::Serialize;

/// A ball of radius `radius` moving along `+x` at `speed` toward a wall: the
/// slab `|x| ≤ thickness/2` (a fixed box, `WALL_HALF_SPAN` wide along `y` and
/// `z`). The ball's centre starts on the `x` axis at
/// `−(thickness/2 + radius) − lead · speed · dt`, so that, unobstructed, it
/// would first touch the wall `lead` steps after the start (a fractional `lead`
/// puts the touch inside a step). The world is stepped `steps` times; the ball
/// **passed through** when its centre ends beyond the wall's mid-plane
/// (`x > 0`). With restitution 0 a ball the wall stops stays on the near side,
/// so the side it ends on answers the question; with restitution 1 rapier's
/// solver can leave a ball shuttling through the wall step after step (seen at
/// 1000 m/s with CCD on), so the end side would depend on the step count.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TunnelScene {
    /// Ball radius (m).
    pub radius: f64,
    /// Ball mass (kg).
    pub mass: f64,
    /// Wall thickness along `x` (m).
    pub thickness: f64,
    /// Ball speed (m/s).
    pub speed: f64,
    /// Steps (of the world's `dt`) before an unobstructed first touch.
    pub lead: f64,
    /// Steps simulated.
    pub steps: usize,
    /// Coefficient of restitution of the ball–wall contact.
    pub restitution: f64,
}

impl TunnelScene {
    /// The ball's initial centre for a world stepped at `dt`.
    pub fn start(&self, dt: f64) -> [f64; 3] {
        [-(self.thickness / 2.0 + self.radius) - self.lead * self.speed * dt, 0.0, 0.0]
    }
}

/// Half the wall's extent along `y` and `z` (m): wide enough that the ball,
/// moving along the `x` axis, can only meet the wall's broad faces.
pub const WALL_HALF_SPAN: f64 = 1.0;

/// What a stepped world did with a [`TunnelScene`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TunnelRun {
    /// The ball's centre ended beyond the wall's mid-plane (`x > 0`).
    pub passed: bool,
    /// Its final `x` (m).
    pub final_x: f64,
}

/// Runs a [`TunnelScene`] in rapier (the settings decide gravity, normally none,
/// and the CCD mode): the wall is a fixed cuboid centred at the origin, the ball
/// a dynamic body.
pub fn tunnel(settings: &Settings, scene: &TunnelScene) -> TunnelRun {
    let mut w = RapierWorld::new(*settings);
    w.add_wall([0.0; 3], [scene.thickness / 2.0, WALL_HALF_SPAN, WALL_HALF_SPAN], 0.0);
    let ball =
        w.add_ball(scene.start(settings.dt), scene.radius, [scene.speed, 0.0, 0.0], scene.mass, scene.restitution);
    for _ in 0..scene.steps {
        w.step();
    }
    let final_x = w.position(ball)[0];
    TunnelRun { passed: final_x > 0.0, final_x }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rapier::Ccd;

    fn scene(speed: f64) -> TunnelScene {
        TunnelScene { radius: 0.05, mass: 1.0, thickness: 0.01, speed, lead: 2.5, steps: 12, restitution: 0.0 }
    }

    #[test]
    fn rapier_slow_ball_bounces_off_the_wall_in_every_mode() {
        for ccd in [Ccd::Off, Ccd::On, Ccd::Soft { prediction: 1.0 }] {
            let run = tunnel(&Settings::validation(ccd).weightless(), &scene(1.0));
            assert!(!run.passed, "{ccd:?}: {run:?}");
        }
    }

    #[test]
    fn rapier_fast_ball_tunnels_without_ccd_and_not_with_it() {
        // 100 m/s: 1.67 m per step against a 0.11 m wide obstacle (ball and wall).
        let off = tunnel(&Settings::validation(Ccd::Off).weightless(), &scene(100.0));
        assert!(off.passed, "{off:?}");
        let on = tunnel(&Settings::validation(Ccd::On).weightless(), &scene(100.0));
        assert!(!on.passed, "{on:?}");
    }
}
