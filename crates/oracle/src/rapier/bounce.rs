//! Experiment (a): a ball dropped on a plane, apex heights bounce by bounce.

use super::world::{RapierWorld, Settings};
use serde::Serialize;

/// A ball of radius `radius` released at rest with its lowest point
/// `drop_height` above the ground `z = 0` (outward normal `+z`), under the
/// settings' gravity, for `duration` seconds. The ground's own restitution is 0;
/// with the `Max` combine rule the contact bounces with the ball's
/// `restitution`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BounceScene {
    /// Ball radius (m).
    pub radius: f64,
    /// Initial height of the ball's lowest point above the ground (m).
    pub drop_height: f64,
    /// Ball mass (kg).
    pub mass: f64,
    /// Coefficient of restitution of the ball–ground contact.
    pub restitution: f64,
    /// Simulated time (s).
    pub duration: f64,
}

/// What a stepped world did with a [`BounceScene`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BounceRun {
    /// Height of the ball's lowest point above the ground after each step
    /// (index 0: the start), m.
    pub heights: Vec<f64>,
    /// Apex heights of the flights after the 1st, 2nd, … impact (m), as
    /// [`apexes`] measures them; the series stops at the first flight the
    /// samples do not resolve.
    pub apexes: Vec<f64>,
}

/// Relative tolerance on the second difference of three free-flight samples
/// (dimensionless). In free flight under constant gravity the positions of a
/// semi-implicit Euler step (rapier's, per substep) and of an exact ballistic
/// step alike have the constant second difference `−g dt²` (2.7e-3 m at
/// `dt = 1/60`); rounding moves it by a few ulps of the heights (≈ 1e-15 m, a
/// relative 4e-13). 1e-6 accepts every free flight and refuses a triple touched
/// by a contact impulse (a velocity change of more than 1e-6 · g dt ≈ 1.6e-7 m/s).
pub const FREE_FLIGHT_REL: f64 = 1e-6;

/// Apex heights of a bouncing ball from its sampled heights (one per step of
/// `dt`, under gravity of magnitude `g`), flight by flight, after the first
/// impact.
///
/// **Method.** Each local maximum `h[k]` of the samples (`h[k−1] < h[k] ≥
/// h[k+1]`, `k ≥ 1`, so the release at rest is not counted) whose three samples
/// are in free flight — second difference `D = h[k−1] − 2h[k] + h[k+1]` within
/// [`FREE_FLIGHT_REL`] of `−g dt²` — is refined to the vertex of the parabola
/// through the three: with `S = (h[k+1] − h[k−1])/2`, apex `= h[k] − S²/(2D)`.
/// The positions of a free flight stepped at constant `dt` lie exactly on a
/// parabola in the step index (constant second difference), so this is the
/// highest point of the stepped flight, not of its samples (which can miss it by
/// up to `g dt²/8`, 3.4e-4 m at `dt = 1/60`).
///
/// **Stopping rule.** The series stops at the first local maximum that is not a
/// resolved free flight (a flight shorter than about two steps, or contact
/// jitter at rest) or whose apex is below `floor` (m): later bounces cannot be
/// measured from the samples.
pub fn apexes(heights: &[f64], dt: f64, g: f64, floor: f64) -> Vec<f64> {
    let free = g * dt * dt;
    let mut out = Vec::new();
    for k in 1..heights.len().saturating_sub(1) {
        let (a, b, c) = (heights[k - 1], heights[k], heights[k + 1]);
        if !(b > a && b >= c) {
            continue;
        }
        let d = a - 2.0 * b + c;
        let free_flight = (d + free).abs() <= FREE_FLIGHT_REL * free;
        if !free_flight {
            break;
        }
        let s = (c - a) / 2.0;
        let apex = b - s * s / (2.0 * d);
        let above_floor = apex >= floor;
        if !above_floor {
            break;
        }
        out.push(apex);
    }
    out
}

/// Smallest apex recorded (m): below it a "bounce" is contact jitter at rest,
/// not a flight (rapier's allowed linear error is 5e-3 m; a micrometre is far
/// below any flight the samples resolve at `dt = 1/60`, whose apex is at least
/// `g dt²/8` ≈ 3.4e-4 m).
pub const APEX_FLOOR: f64 = 1e-6;

/// Runs a [`BounceScene`] in rapier: the ground is a fixed half-space `z ≤ 0`,
/// the ball a dynamic body; heights are sampled after every step and measured by
/// [`apexes`] (with `g` the magnitude of the settings' gravity and
/// [`APEX_FLOOR`]).
pub fn bounce(settings: &Settings, scene: &BounceScene) -> BounceRun {
    let mut w = RapierWorld::new(*settings);
    w.add_ground([0.0, 0.0, 1.0], 0.0);
    let ball =
        w.add_ball([0.0, 0.0, scene.radius + scene.drop_height], scene.radius, [0.0; 3], scene.mass, scene.restitution);
    let steps = (scene.duration / settings.dt).ceil() as usize;
    let mut heights = Vec::with_capacity(steps + 1);
    heights.push(scene.drop_height);
    for _ in 0..steps {
        w.step();
        heights.push(w.position(ball)[2] - scene.radius);
    }
    let g = settings.gravity.iter().map(|x| x * x).sum::<f64>().sqrt();
    BounceRun { apexes: apexes(&heights, settings.dt, g, APEX_FLOOR), heights }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rapier::Ccd;

    /// Exactness of the parabola vertex on exact samples: a few ulps of heights
    /// of order 1 m.
    const VERTEX_TOL: f64 = 1e-12;

    #[test]
    fn apexes_recovers_the_vertex_between_samples() {
        // Exact ballistic samples of a flight launched upward at 3 m/s from the
        // ground at t = 0.3 dt: apex 9/(2g), between two samples.
        let (g, dt) = (9.81, 1.0 / 60.0);
        let t0 = 0.3 * dt;
        let h: Vec<f64> = (0..60)
            .map(|k| {
                let t = k as f64 * dt - t0;
                if t <= 0.0 { 0.0 } else { 3.0 * t - 0.5 * g * t * t }
            })
            .map(|h| h.max(0.0))
            .collect();
        let a = apexes(&h, dt, g, APEX_FLOOR);
        assert_eq!(a.len(), 1, "{a:?}");
        assert!((a[0] - 9.0 / (2.0 * g)).abs() <= VERTEX_TOL, "{a:?}");
    }

    #[test]
    fn rapier_bounce_restitution_half_bounces_lower_each_time() {
        let s = Settings::validation(Ccd::On);
        let run =
            bounce(&s, &BounceScene { radius: 0.1, drop_height: 1.0, mass: 1.0, restitution: 0.5, duration: 3.0 });
        assert!(run.apexes.len() >= 2, "{:?}", run.apexes);
        assert!(run.apexes.windows(2).all(|w| w[1] < w[0]), "{:?}", run.apexes);
        assert!(run.apexes[0] < 1.0, "{:?}", run.apexes);
    }
}
