//! The dynamics experiments' design (the scenes' parameters, the methods and
//! their names) and what they measured: the report's types, plain data,
//! serializable, read by the rendering.

use oracle::geom::P3;
use oracle::rapier::{Ccd, RAPIER_NAME};
use serde::Serialize;

/// Ball radius of the bounce experiment (m).
pub const BOUNCE_RADIUS: f64 = 0.1;
/// Height of the ball's lowest point at release, at rest (m).
pub const DROP_HEIGHT: f64 = 1.0;
/// Restitutions of the bounce experiment.
pub const RESTITUTIONS: [f64; 5] = [0.0, 0.25, 0.5, 0.8, 1.0];
/// Bounces tabulated by the analytic law.
pub const BOUNCES: usize = 8;
/// Simulated time of each bounce run (s): eight bounces of the elastic ball
/// (`√(2h₀/g) · 17` ≈ 7.7 s).
pub const BOUNCE_DURATION: f64 = 8.0;

/// Ball radius of the tunnelling experiment (m): a small ball.
pub const TUNNEL_RADIUS: f64 = 0.05;
/// Wall thicknesses (m).
pub const THICKNESSES: [f64; 3] = [0.001, 0.01, 0.1];
/// Ball speeds (m/s): four decades, 1 to 10⁴ (at `dt = 1/60`, 1.7 cm to 167 m
/// per step against obstacles 0.1 to 0.2 m across).
pub const SPEEDS: [f64; 9] = [1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0, 10000.0];
/// Start phases per speed and thickness: the unobstructed first touch falls at
/// `2 + (j + ½)/PHASES` steps, `j = 0 … PHASES − 1`, spread over one step.
pub const PHASES: usize = 8;
/// Steps per tunnelling run: the ball would be well past the wall by then.
pub const TUNNEL_STEPS: usize = 12;
/// Restitution of the ball–wall contact: 0, so a stopped ball stays on the
/// near side and the side it ends on says whether it went through.
pub const TUNNEL_RESTITUTION: f64 = 0.0;
/// rapier's soft-CCD prediction distance (m): 1 m, twenty radii of the
/// tunnelling ball, covering a whole step's travel up to 60 m/s at `dt = 1/60`.
pub const SOFT_CCD_PREDICTION: f64 = 1.0;

/// How our stepped worlds find the impact within a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Sweep {
    /// collide's closed forms (`toi_sphere_plane`, `toi_sphere_sphere`): every
    /// touching time in the step is seen.
    ClosedForm,
    /// collide's interval halving (the lecture's): only a contact at the end of
    /// the interval is seen.
    Halving,
}

impl Sweep {
    pub(super) fn name(self) -> &'static str {
        match self {
            Sweep::ClosedForm => "collide closed form, stepped",
            Sweep::Halving => "collide halving, stepped",
        }
    }
}

/// The name of the closed-form sweep (the whole run as one step).
pub const SWEEP_NAME: &str = "collide closed-form sweep";
/// The name of the analytic answers.
pub const ANALYTIC_NAME: &str = "analytic";

/// One engine's apex series for one restitution.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ApexSeries {
    /// The engine or method.
    pub engine: String,
    /// Coefficient of restitution.
    pub restitution: f64,
    /// Apex heights after the 1st, 2nd, … impact (m), at most [`BOUNCES`]; for
    /// the stepped engines as far as the samples resolve them.
    pub apexes: Vec<f64>,
    /// The highest sampled height after the first landing (m): for `e = 0`, any
    /// rebound at all (the analytic answer is 0). Absent for the analytic law.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub highest_after_landing: Option<f64>,
}

/// Pass-through count of one method at one speed and thickness.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PassRow {
    /// The method.
    pub method: String,
    /// Wall thickness (m).
    pub thickness: f64,
    /// Ball speed (m/s).
    pub speed: f64,
    /// Runs (start phases) in which the ball ended beyond the wall.
    pub passed: usize,
    /// Runs.
    pub runs: usize,
}

/// One engine's velocities after a two-ball impact.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PairRow {
    /// The scene's name.
    pub scene: String,
    /// The engine or method.
    pub engine: String,
    /// `a`'s velocity afterwards (m/s).
    pub velocity_a: P3,
    /// `b`'s velocity afterwards (m/s).
    pub velocity_b: P3,
    /// Largest distance of either velocity from the analytic one, divided by the
    /// largest initial speed (dimensionless).
    pub error: f64,
    /// Relative change of the kinetic energy over the run (after − before) /
    /// before.
    pub energy_change: f64,
}

/// Where rapier's answer differs from the analytic law, reported as it is.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Deviation {
    /// `bounce`, `tunnel` or `pair`.
    pub experiment: String,
    /// The case (restitution and bounce, method and thickness, scene).
    pub case: String,
    /// The analytic answer.
    pub analytic: String,
    /// rapier's answer.
    pub rapier: String,
    /// The difference, in words and numbers.
    pub difference: String,
}

/// A setting and its value, as echoed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Echo {
    /// The setting's name.
    pub name: String,
    /// Its value.
    pub value: String,
}

/// The bounce experiment's fixed parameters, as reported.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BounceDesign {
    /// Ball radius (m).
    pub radius: f64,
    /// Height of the ball's lowest point at release (m).
    pub drop_height: f64,
    /// Simulated time per run (s).
    pub duration: f64,
    /// Bounces tabulated.
    pub bounces: usize,
}

/// Everything the dynamics experiments measured: plain data, serializable.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DynamicsReport {
    /// `rapier3d-f64 0.36.1`.
    pub rapier: String,
    /// rapier's settings, every one
    /// ([`Settings::echo`](oracle::rapier::Settings::echo)); the CCD mode
    /// varies per tunnelling method, as its name says.
    pub settings: Vec<Echo>,
    /// The bounce experiment's design (the restitution varies per series).
    pub bounce_design: BounceDesign,
    /// Apex series per restitution and engine.
    pub bounces: Vec<ApexSeries>,
    /// Pass-through counts per method, thickness and speed.
    pub tunnel: Vec<PassRow>,
    /// Velocities after two-ball impacts per scene and engine.
    pub pairs: Vec<PairRow>,
    /// rapier's deviations from the analytic answers.
    pub deviations: Vec<Deviation>,
    /// The settings each process engine that steps worlds used (its reply's
    /// `settings`, from its first world), in report order.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub engine_settings: Vec<EngineSettings>,
    /// Worlds a process engine did not step, and why (its error, or a fault).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub world_failures: Vec<WorldFailure>,
}

/// A process engine's world settings, as it echoed them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EngineSettings {
    /// The engine.
    pub engine: String,
    /// Its settings, every one it named.
    pub settings: Vec<Echo>,
}

/// A world a process engine did not step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorldFailure {
    /// The engine.
    pub engine: String,
    /// The world (`bounce, e = 0.5`, `tunnel, wall 0.01 m, 100 m/s, phase 3, CCD on`).
    pub world: String,
    /// Why.
    pub reason: String,
}

/// The tunnelling methods of crashtest's own runs, in report order (a process
/// engine's follow them: [`methods_of`]).
pub fn tunnel_methods() -> Vec<String> {
    let mut m: Vec<String> = ccd_modes().iter().map(rapier_method).collect();
    m.push(Sweep::Halving.name().into());
    m.push(Sweep::ClosedForm.name().into());
    m.push(SWEEP_NAME.into());
    m
}

/// The tunnelling methods of a report: [`tunnel_methods`], then those of the
/// process engines, in the order they appear.
pub fn methods_of(r: &DynamicsReport) -> Vec<String> {
    let mut m = tunnel_methods();
    for row in &r.tunnel {
        if !m.contains(&row.method) {
            m.push(row.method.clone());
        }
    }
    m
}

pub(super) fn ccd_modes() -> [Ccd; 3] {
    [Ccd::Off, Ccd::On, Ccd::Soft { prediction: SOFT_CCD_PREDICTION }]
}

pub(super) fn rapier_method(c: &Ccd) -> String {
    match c {
        Ccd::Soft { prediction } => format!("{RAPIER_NAME}, soft CCD ({prediction} m)"),
        c => format!("{RAPIER_NAME}, CCD {}", c.name()),
    }
}

pub(super) fn vec_str(p: &P3) -> String {
    format!("({:.6}, {:.6}, {:.6})", p[0], p[1], p[2])
}
