//! One rapier world, configured in one place.

use crate::geom::P3;
use rapier3d_f64::na::Unit;
use rapier3d_f64::prelude::{
    CCDSolver, CoefficientCombineRule, ColliderBuilder, ColliderSet, DefaultBroadPhase, ImpulseJointSet,
    IntegrationParameters, IslandManager, MultibodyJointSet, NarrowPhase, PhysicsPipeline, RigidBodyBuilder,
    RigidBodyHandle, RigidBodySet, SoftBodySet, SpringCoefficients, Vector,
};
use serde::Serialize;

/// Continuous collision detection, as rapier 0.36.1 offers it.
///
/// - `Off`: `IntegrationParameters::max_ccd_substeps = 0`, the world-wide switch,
///   which also turns off the automatic sweep of fast bodies against fixed
///   colliders; no soft CCD.
/// - `On`: `max_ccd_substeps = 1` and every dynamic body a "bullet"
///   (`RigidBodyBuilder::ccd_enabled(true)`): after the solver, bodies that moved
///   more than half their thinnest extent are swept and clamped to their earliest
///   impact (velocities untouched).
/// - `Soft`: `max_ccd_substeps = 0` and `soft_ccd_prediction(d)` on every dynamic
///   body: predictive contacts are generated up to `min(d, ‖v‖ dt)` ahead, no sweep.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "mode", rename_all = "snake_case")]
pub enum Ccd {
    /// No continuous collision detection at all.
    Off,
    /// Swept (bullet) CCD.
    On,
    /// Soft (predictive) CCD with this prediction distance, in length units.
    Soft {
        /// The prediction distance, in length units (m).
        prediction: f64,
    },
}

impl Ccd {
    /// A short name for reports: `off`, `on`, `soft`.
    pub fn name(&self) -> &'static str {
        match self {
            Ccd::Off => "off",
            Ccd::On => "on",
            Ccd::Soft { .. } => "soft",
        }
    }
}

/// Every setting of a rapier world that matters for validation. Nothing is left
/// to rapier's defaults silently: [`Settings::validation`] sets each field, and
/// [`Settings::echo`] lists them for the report. Units: SI (m, s, kg).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Settings {
    /// Fixed time step (s). `IntegrationParameters::dt`.
    pub dt: f64,
    /// Gravity (m/s²), world frame.
    pub gravity: P3,
    /// Solver iterations per step (rapier's substeps). `num_solver_iterations`.
    pub solver_iterations: usize,
    /// Projected Gauss–Seidel iterations per solver iteration.
    /// `num_internal_pgs_iterations`.
    pub pgs_iterations: usize,
    /// Stabilization iterations per solver iteration.
    /// `num_internal_stabilization_iterations`.
    pub stabilization_iterations: usize,
    /// Continuous collision detection mode.
    pub ccd: Ccd,
    /// Merge manifolds sharing a normal into one cluster (rapier's default: on).
    /// Off: a single ball–plane or ball–ball contact is solved as it is found.
    pub contact_clustering: bool,
    /// Reuse a pair's contacts while it moved less than the recycle distance
    /// (rapier's default: on). Off: contacts are recomputed every step.
    pub contact_recycling: bool,
    /// Cap on a body's linear speed after each substep (m/s); `f64::MAX` lifts it
    /// (rapier's default is 400 m/s, below the tunnelling experiment's speeds).
    pub max_linear_velocity: f64,
    /// Cap on the speed at which penetration is pushed out (m/s), rapier's default.
    pub max_corrective_velocity: f64,
    /// Distance below which speculative contacts are generated (m), rapier's default.
    pub prediction_distance: f64,
    /// Geometric slop, e.g. the stand-off kept by the CCD clamp (m), rapier's default.
    pub allowed_linear_error: f64,
    /// Contact constraint softness against a moving body: natural frequency (Hz)
    /// and damping ratio, rapier's defaults.
    pub contact_softness: (f64, f64),
    /// The same against a fixed body, rapier's defaults.
    pub static_contact_softness: (f64, f64),
    /// Warm-start coefficient, rapier's default.
    pub warmstart_coefficient: f64,
    /// Length unit (1: metres).
    pub length_unit: f64,
    /// Smallest substep of CCD substepping (s), rapier's default.
    pub min_ccd_dt: f64,
    /// Restitution combine rule: `Max`, so a pair with a restitution-0 ground
    /// and a ball of restitution `e` bounces with `e`, and two balls of `e` too.
    pub restitution_combine: Combine,
    /// Friction coefficient of every collider: 0 (the response formula is
    /// frictionless).
    pub friction: f64,
    /// Friction combine rule: `Min`, so any zero friction wins.
    pub friction_combine: Combine,
    /// Linear damping of every body: 0.
    pub linear_damping: f64,
    /// Angular damping of every body: 0.
    pub angular_damping: f64,
    /// Whether bodies may fall asleep: no (a resting ball must still be measured).
    pub can_sleep: bool,
    /// Contact skin of every collider (m): 0, so surfaces touch at distance 0.
    pub contact_skin: f64,
    /// Lift the angular speed cap on every body (`allow_fast_rotation`).
    pub allow_fast_rotation: bool,
}

impl Settings {
    /// The settings crashtest validates with: `dt = 1/60` s, gravity
    /// `(0, 0, −9.81)` m/s², 4 solver iterations (1 PGS and 1 stabilization
    /// iteration each), the given CCD mode, contact clustering and recycling off,
    /// the linear and angular speed caps lifted, restitution combined by `Max`,
    /// friction 0 combined by `Min`, no damping, no sleeping, no contact skin; the
    /// contact model's own parameters (softness, slop, prediction distance,
    /// corrective velocity cap, warm start) at rapier's defaults, written out.
    pub fn validation(ccd: Ccd) -> Self {
        let d = IntegrationParameters::default();
        Settings {
            dt: 1.0 / 60.0,
            gravity: [0.0, 0.0, -9.81],
            solver_iterations: 4,
            pgs_iterations: 1,
            stabilization_iterations: 1,
            ccd,
            contact_clustering: false,
            contact_recycling: false,
            max_linear_velocity: f64::MAX,
            max_corrective_velocity: d.max_corrective_velocity(),
            prediction_distance: d.prediction_distance(),
            allowed_linear_error: d.allowed_linear_error(),
            contact_softness: (d.contact_softness.natural_frequency, d.contact_softness.damping_ratio),
            static_contact_softness: (
                d.static_contact_softness.natural_frequency,
                d.static_contact_softness.damping_ratio,
            ),
            warmstart_coefficient: d.warmstart_coefficient,
            length_unit: 1.0,
            min_ccd_dt: d.min_ccd_dt,
            restitution_combine: Combine::Max,
            friction: 0.0,
            friction_combine: Combine::Min,
            linear_damping: 0.0,
            angular_damping: 0.0,
            can_sleep: false,
            contact_skin: 0.0,
            allow_fast_rotation: true,
        }
    }

    /// These settings without gravity (the tunnelling and two-ball experiments).
    pub fn weightless(mut self) -> Self {
        self.gravity = [0.0; 3];
        self
    }

    /// Every setting as `(name, value)`, in declaration order, for the report.
    pub fn echo(&self) -> Vec<(&'static str, String)> {
        let ccd = match self.ccd {
            Ccd::Off => "off (max_ccd_substeps = 0)".to_string(),
            Ccd::On => "on (max_ccd_substeps = 1, ccd_enabled on every dynamic body)".into(),
            Ccd::Soft { prediction } => {
                format!("soft (max_ccd_substeps = 0, soft_ccd_prediction = {prediction} m)")
            }
        };
        let cap = |v: f64| {
            if v >= f64::MAX { "lifted (f64::MAX)".to_string() } else { format!("{v} m/s") }
        };
        vec![
            ("dt", format!("{} s", self.dt)),
            ("gravity", format!("{:?} m/s²", self.gravity)),
            ("solver_iterations", self.solver_iterations.to_string()),
            ("pgs_iterations", self.pgs_iterations.to_string()),
            ("stabilization_iterations", self.stabilization_iterations.to_string()),
            ("ccd", ccd),
            ("contact_clustering", self.contact_clustering.to_string()),
            ("contact_recycling", self.contact_recycling.to_string()),
            ("max_linear_velocity", cap(self.max_linear_velocity)),
            ("max_corrective_velocity", cap(self.max_corrective_velocity)),
            ("prediction_distance", format!("{} m", self.prediction_distance)),
            ("allowed_linear_error", format!("{} m", self.allowed_linear_error)),
            ("contact_softness", format!("{} Hz, damping ratio {}", self.contact_softness.0, self.contact_softness.1)),
            (
                "static_contact_softness",
                format!("{} Hz, damping ratio {}", self.static_contact_softness.0, self.static_contact_softness.1),
            ),
            ("warmstart_coefficient", self.warmstart_coefficient.to_string()),
            ("length_unit", self.length_unit.to_string()),
            ("min_ccd_dt", format!("{} s", self.min_ccd_dt)),
            ("restitution_combine", format!("{:?}", self.restitution_combine)),
            ("friction", self.friction.to_string()),
            ("friction_combine", format!("{:?}", self.friction_combine)),
            ("linear_damping", self.linear_damping.to_string()),
            ("angular_damping", self.angular_damping.to_string()),
            ("can_sleep", self.can_sleep.to_string()),
            ("contact_skin", format!("{} m", self.contact_skin)),
            ("allow_fast_rotation", self.allow_fast_rotation.to_string()),
        ]
    }

    /// rapier's integration parameters for these settings.
    fn integration_parameters(&self) -> IntegrationParameters {
        IntegrationParameters {
            dt: self.dt,
            length_unit: self.length_unit,
            num_solver_iterations: self.solver_iterations,
            num_internal_pgs_iterations: self.pgs_iterations,
            num_internal_stabilization_iterations: self.stabilization_iterations,
            max_ccd_substeps: match self.ccd {
                Ccd::On => 1,
                Ccd::Off | Ccd::Soft { .. } => 0,
            },
            contact_clustering: self.contact_clustering,
            contact_recycling: self.contact_recycling,
            // The normalized fields are multiplied by length_unit (1 here);
            // f64::MAX is rapier's own "no cap" value and is kept as it is.
            normalized_max_linear_velocity: self.max_linear_velocity,
            normalized_max_corrective_velocity: self.max_corrective_velocity,
            normalized_prediction_distance: self.prediction_distance,
            normalized_allowed_linear_error: self.allowed_linear_error,
            contact_softness: SpringCoefficients::new(self.contact_softness.0, self.contact_softness.1),
            static_contact_softness: SpringCoefficients::new(
                self.static_contact_softness.0,
                self.static_contact_softness.1,
            ),
            warmstart_coefficient: self.warmstart_coefficient,
            min_ccd_dt: self.min_ccd_dt,
            ..IntegrationParameters::default()
        }
    }
}

/// How rapier combines the coefficients of two colliders in contact
/// (`CoefficientCombineRule`), named here so that settings serialize.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Combine {
    /// The mean of the two.
    Average,
    /// The smaller.
    Min,
    /// The product.
    Multiply,
    /// The larger.
    Max,
    /// The sum, clamped.
    ClampedSum,
    /// The square root of the product.
    GeometricMean,
}

impl Combine {
    fn rule(self) -> CoefficientCombineRule {
        match self {
            Combine::Average => CoefficientCombineRule::Average,
            Combine::Min => CoefficientCombineRule::Min,
            Combine::Multiply => CoefficientCombineRule::Multiply,
            Combine::Max => CoefficientCombineRule::Max,
            Combine::ClampedSum => CoefficientCombineRule::ClampedSum,
            Combine::GeometricMean => CoefficientCombineRule::GeometricMean,
        }
    }
}

/// A body of a [`RapierWorld`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Body(RigidBodyHandle);

/// A rapier world: the pipeline and every set it steps, built from [`Settings`].
pub struct RapierWorld {
    settings: Settings,
    params: IntegrationParameters,
    gravity: Vector,
    pipeline: PhysicsPipeline,
    islands: IslandManager,
    broad_phase: DefaultBroadPhase,
    narrow_phase: NarrowPhase,
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    soft_bodies: SoftBodySet,
    ccd_solver: CCDSolver,
    steps: usize,
}

fn v(p: P3) -> Vector {
    Vector::new(p[0], p[1], p[2])
}

fn p3(v: Vector) -> P3 {
    [v.x, v.y, v.z]
}

impl RapierWorld {
    /// An empty world with these settings: the only place a rapier world is
    /// configured. Bodies added later take their per-body settings (CCD,
    /// damping, sleeping, speed caps) and their colliders' (friction,
    /// restitution rules, skin) from the same [`Settings`].
    pub fn new(settings: Settings) -> Self {
        RapierWorld {
            params: settings.integration_parameters(),
            gravity: v(settings.gravity),
            settings,
            pipeline: PhysicsPipeline::new(),
            islands: IslandManager::new(),
            broad_phase: DefaultBroadPhase::default(),
            narrow_phase: NarrowPhase::new(),
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd_solver: CCDSolver::new(),
            steps: 0,
        }
    }

    /// The settings the world was built with.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// A dynamic ball (centre, radius, initial velocity, mass, restitution).
    pub fn add_ball(&mut self, center: P3, radius: f64, velocity: P3, mass: f64, restitution: f64) -> Body {
        let s = &self.settings;
        let mut rb = RigidBodyBuilder::dynamic()
            .translation(v(center))
            .linvel(v(velocity))
            .linear_damping(s.linear_damping)
            .angular_damping(s.angular_damping)
            .can_sleep(s.can_sleep)
            .allow_fast_rotation(s.allow_fast_rotation)
            .ccd_enabled(s.ccd == Ccd::On);
        if let Ccd::Soft { prediction } = s.ccd {
            rb = rb.soft_ccd_prediction(prediction);
        }
        let handle = self.bodies.insert(rb.build());
        let collider = self.collider(ColliderBuilder::ball(radius), restitution).mass(mass);
        self.colliders.insert_with_parent(collider.build(), handle, &mut self.bodies);
        Body(handle)
    }

    /// A fixed half-space: the plane `n̂ · x = 0` through the origin, solid on
    /// the side `n̂ · x ≤ 0` (outward normal `n̂`, unit).
    pub fn add_ground(&mut self, outward_normal: P3, restitution: f64) -> Body {
        let handle = self.bodies.insert(RigidBodyBuilder::fixed().build());
        // Normalized here (glam's vectors are not nalgebra's `Normed`); a zero
        // normal falls back to +z rather than panicking.
        let n = Unit::new_unchecked(v(outward_normal).try_normalize().unwrap_or(Vector::Z));
        let collider = self.collider(ColliderBuilder::halfspace(n), restitution);
        self.colliders.insert_with_parent(collider.build(), handle, &mut self.bodies);
        Body(handle)
    }

    /// A fixed box centred at `center` with these half extents.
    pub fn add_wall(&mut self, center: P3, half_extents: P3, restitution: f64) -> Body {
        let handle = self.bodies.insert(RigidBodyBuilder::fixed().translation(v(center)).build());
        let [hx, hy, hz] = half_extents;
        let collider = self.collider(ColliderBuilder::cuboid(hx, hy, hz), restitution);
        self.colliders.insert_with_parent(collider.build(), handle, &mut self.bodies);
        Body(handle)
    }

    /// A collider with the settings' friction, combine rules and skin.
    fn collider(&self, builder: ColliderBuilder, restitution: f64) -> ColliderBuilder {
        let s = &self.settings;
        builder
            .restitution(restitution)
            .restitution_combine_rule(s.restitution_combine.rule())
            .friction(s.friction)
            .friction_combine_rule(s.friction_combine.rule())
            .contact_skin(s.contact_skin)
    }

    /// One step of `dt`: `PhysicsPipeline::step` with every set (the soft-body
    /// set included, as rapier 0.36.1's signature asks), no hooks, no events.
    pub fn step(&mut self) {
        self.pipeline.step(
            self.gravity,
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.soft_bodies,
            &mut self.ccd_solver,
            &(),
            &(),
        );
        self.steps += 1;
    }

    /// Steps taken so far.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// A body's position (its centre: balls are built centred on their body).
    pub fn position(&self, b: Body) -> P3 {
        p3(self.bodies[b.0].translation())
    }

    /// A body's linear velocity.
    pub fn velocity(&self, b: Body) -> P3 {
        p3(self.bodies[b.0].linvel())
    }

    /// A body's mass as rapier computed it.
    pub fn mass(&self, b: Body) -> f64 {
        self.bodies[b.0].mass()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A free ball under gravity for one step: semi-implicit Euler, `v += g dt`
    /// then `x += v dt` (per substep). Tolerance: a few ulps of the numbers
    /// involved (of order 1 m and 1 m/s).
    const FREE_FLIGHT_TOL: f64 = 1e-12;

    #[test]
    fn rapier_world_free_fall_follows_gravity() {
        let mut w = RapierWorld::new(Settings::validation(Ccd::On));
        let b = w.add_ball([0.0, 0.0, 10.0], 0.5, [1.0, 0.0, 0.0], 2.0, 0.5);
        w.step();
        let s = w.settings();
        let vz = w.velocity(b)[2];
        assert!((vz - s.gravity[2] * s.dt).abs() <= FREE_FLIGHT_TOL, "vz = {vz}");
        let x = w.position(b)[0];
        assert!((x - s.dt).abs() <= FREE_FLIGHT_TOL, "x = {x}");
        assert!((w.mass(b) - 2.0).abs() <= FREE_FLIGHT_TOL, "mass {}", w.mass(b));
        assert_eq!(w.steps(), 1);
    }

    #[test]
    fn rapier_settings_echo_every_field() {
        let s = Settings::validation(Ccd::Soft { prediction: 1.0 });
        let echo = s.echo();
        for name in [
            "dt",
            "gravity",
            "ccd",
            "contact_clustering",
            "contact_recycling",
            "max_linear_velocity",
            "restitution_combine",
            "friction",
            "linear_damping",
            "angular_damping",
            "can_sleep",
        ] {
            assert!(echo.iter().any(|(n, _)| *n == name), "echo lists `{name}`");
        }
        assert!(echo.iter().any(|(_, v)| v.contains("soft_ccd_prediction = 1 m")));
        let p = s.integration_parameters();
        assert_eq!(p.max_ccd_substeps, 0, "soft CCD runs without the sweep");
        assert!(!p.contact_clustering && !p.contact_recycling);
        assert!(p.max_linear_velocity() >= f64::MAX, "speed cap lifted");
    }
}
