//! Dynamics: the time of impact and the response put to work in stepped worlds,
//! against the laws of mechanics and against rapier.
//!
//! Three experiments, each answered four ways:
//!
//! | experiment | (i) analytic law | (ii) rapier | (iii) stepped worlds on collide | (iv) closed-form sweep |
//! | --- | --- | --- | --- | --- |
//! | a ball dropped on a plane, restitution 0, 0.25, 0.5, 0.8, 1: apex heights bounce by bounce | `h_k = e^{2k} h_0` | [`oracle::rapier::bounce`] | closed-form toi + response; halving + response | — (gravity bends the path; collide's sweeps are linear) |
//! | tunnelling: a small fast ball at a thin wall, speeds over four decades | never passes | CCD off, on, soft | closed form; halving (misses a wall crossed within a step) | the whole run as one sweep |
//! | two balls, head-on and glancing: velocities after the impact | the response formula at the exact contact normal (the referee) | [`oracle::rapier::pair`] | closed form; halving | the whole run as one sweep |
//!
//! # Our stepped worlds
//!
//! A world of our own is a fixed-step loop built only on collide: every step of
//! `dt`, the body's motion over the step is a straight line (the chord of the
//! ballistic arc under gravity: start and end positions exact, velocity
//! `u = v + g τ/2` over the remaining `τ`), collide finds the first contact on
//! it ([`Sweep::ClosedForm`]: `toi_sphere_plane`/`toi_sphere_sphere`;
//! [`Sweep::Halving`]: the lecture's `toi_halving`, [`WORLD_HALVING_STEPS`]
//! bisections), the bodies are moved to that time, one impulse is applied
//! (`respond_sphere_plane`/`respond_sphere_sphere`) and the rest of the step
//! goes on, up to [`MAX_EVENTS_PER_STEP`] impacts per step. Between impacts the
//! motion is exact ballistic flight. Contact at the start of an interval is
//! resolved by its normal velocity: approaching — an impact; leaving — free
//! flight; neither (a ball at rest on the ground pressed by gravity) — a
//! **resting contact**, the one rule beyond the lecture: the normal components
//! of the velocity and of the rest of the step's motion are removed.
//!
//! Obstacles are intersections of half-spaces with parallel faces: the ground
//! (`z ≤ 0`) or a wall (the slab `|x| ≤ w/2`). A ball touches such an obstacle
//! exactly when it touches every face's half-space (in the direction across the
//! faces the condition is an interval), so the closed form is the **latest**
//! of the faces' first-touch times — each a half-line of touching times, so the
//! latest start is where they first all hold — and the halving's static test
//! asks for contact with every face. The halving method tests only the ends of
//! its interval: a wall crossed entirely within one step is never seen — the
//! tunnelling this module shows, not patches.
//!
//! Everything is deterministic: no clock, no randomness; the report's numbers
//! and SVG are the same on every run.

use crate::render::plot::{Axis, Line, line_chart};
use collide::Vec3;
use collide::contact::{Contact, contact_sphere_plane};
use collide::response::{respond_sphere_plane, respond_sphere_sphere};
use collide::toi::{Halving, toi_halving, toi_sphere_plane, toi_sphere_sphere, toi_sphere_sphere_halving};
use oracle::geom::{P3, Sphere as GSphere};
use oracle::rapier::{
    self, APEX_FLOOR, BounceRun, BounceScene, Ccd, PairRun, PairScene, RAPIER_NAME, RAPIER_VERSION, Settings,
    TunnelRun, TunnelScene, apexes,
};
use oracle::referee;
use serde::Serialize;
use std::fmt::Write;

// ---------------------------------------------------------------------------
// The experiments' design.

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

/// Bisections per halving search in our halving world: 40, as the collide
/// engine's lecture method (`engines::collide::HALVING_STEPS`), so the impact
/// time is within `dt / 2⁴⁰` of the first time the end-of-interval test sees.
pub const WORLD_HALVING_STEPS: u32 = 40;
/// Impacts handled within one step of our worlds before the rest of the step
/// is treated as a resting contact (the bounce's Zeno regime, where an exact
/// model bounces infinitely often in finite time).
pub const MAX_EVENTS_PER_STEP: usize = 8;

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
    fn name(self) -> &'static str {
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

fn v3(p: P3) -> Vec3<f64> {
    Vec3::new(p[0], p[1], p[2])
}

fn p3(v: &Vec3<f64>) -> P3 {
    [v.x, v.y, v.z]
}

fn norm(p: &P3) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

// ---------------------------------------------------------------------------
// One ball against a static obstacle (the ground, a wall).

/// A static obstacle: the intersection of half-spaces `n · x ≤ d` with
/// parallel (or single) faces.
#[derive(Clone, Debug)]
struct Obstacle {
    faces: Vec<collide::Plane<f64>>,
}

impl Obstacle {
    /// The ground: `z ≤ 0`.
    fn ground() -> Self {
        Obstacle { faces: vec![collide::Plane::new(Vec3::z(), 0.0)] }
    }

    /// The wall `|x| ≤ w/2`.
    fn wall(thickness: f64) -> Self {
        let h = thickness / 2.0;
        Obstacle { faces: vec![collide::Plane::new(-Vec3::x(), h), collide::Plane::new(Vec3::x(), h)] }
    }

    /// Signed distance of a point from face `f` (positive outside).
    fn height(&self, f: usize, c: &Vec3<f64>) -> f64 {
        let p = &self.faces[f];
        let len = p.normal.norm();
        p.normal.dot(c) / len - p.offset / len
    }

    /// The static contact of a ball with the obstacle: contact with every
    /// face's half-space, reported for the face the ball is least deep in
    /// (the way out).
    fn contact(&self, s: &collide::Sphere<f64>) -> Option<Contact<f64>> {
        let mut best: Option<Contact<f64>> = None;
        for f in &self.faces {
            let k = contact_sphere_plane(s, f)?;
            if best.is_none_or(|b| k.depth < b.depth) {
                best = Some(k);
            }
        }
        best
    }

    /// First contact of a ball (centre `c`, radius `r`) moving at `u` over
    /// `[0, tau]`: `(t, unit normal from the obstacle toward the ball)`.
    fn first_contact(&self, c: &Vec3<f64>, r: f64, u: &Vec3<f64>, tau: f64, sweep: Sweep) -> Option<(f64, Vec3<f64>)> {
        let ball = collide::Sphere::new(*c, r);
        match sweep {
            Sweep::ClosedForm => {
                // The latest of the faces' first touches (each a half-line of
                // touching times); all faces must be reachable.
                let mut best: Option<(f64, Vec3<f64>, f64)> = None;
                for (i, f) in self.faces.iter().enumerate() {
                    let hit = toi_sphere_plane(&ball, u, f, &Vec3::zeros(), tau)?;
                    let h = self.height(i, c);
                    let later = match best {
                        None => true,
                        // Equal times (all 0: in contact at the start): the face
                        // the ball is least deep in, as the static contact says.
                        Some((t, _, bh)) => hit.t > t || (hit.t >= t && h > bh),
                    };
                    if later {
                        best = Some((hit.t, hit.normal, h));
                    }
                }
                best.map(|(t, n, _)| (t, n))
            }
            Sweep::Halving => toi_halving(
                |t| self.contact(&collide::Sphere::new(c + u * t, r)),
                tau,
                Halving::Steps(WORLD_HALVING_STEPS),
            )
            .map(|k| (k.t, k.normal)),
        }
    }
}

/// A ball's state.
#[derive(Clone, Copy, Debug)]
struct Ball {
    c: Vec3<f64>,
    v: Vec3<f64>,
    r: f64,
}

/// One step of `dt` of a ball against an obstacle under gravity `g` (see the
/// module docs for the rules), restitution `e`.
fn step_ball(ball: &mut Ball, obstacle: &Obstacle, g: &Vec3<f64>, e: f64, dt: f64, sweep: Sweep) {
    let mut rem = dt;
    for _ in 0..MAX_EVENTS_PER_STEP {
        let u = ball.v + g * (rem / 2.0);
        let Some((t, n)) = obstacle.first_contact(&ball.c, ball.r, &u, rem, sweep) else {
            ball.c += u * rem;
            ball.v += g * rem;
            return;
        };
        if t > 0.0 {
            ball.c += u * t;
            ball.v += g * t;
            rem -= t;
        }
        let vn = ball.v.dot(&n);
        if vn < 0.0 {
            ball.v = respond_sphere_plane(&ball.v, &n, e).velocity_a;
        } else if vn > 0.0 {
            // Leaving: the contact at the start of the interval is left behind.
            ball.c += (ball.v + g * (rem / 2.0)) * rem;
            ball.v += g * rem;
            return;
        } else {
            rest(ball, &n, g, rem);
            return;
        }
    }
    // Too many impacts within one step: the bounce has died out.
    let n = obstacle.faces[0].normal.normalize();
    rest(ball, &n, g, rem);
}

/// A resting contact for the rest `rem` of a step: the normal components of the
/// velocity and of the motion are removed; the tangential motion goes on.
fn rest(ball: &mut Ball, n: &Vec3<f64>, g: &Vec3<f64>, rem: f64) {
    let tangential = |w: Vec3<f64>| w - n * w.dot(n);
    ball.v = tangential(ball.v);
    let u = tangential(ball.v + g * (rem / 2.0));
    ball.c += u * rem;
    ball.v = tangential(ball.v + g * rem);
}

/// [`BounceScene`] in our stepped world: heights after every step and the
/// apexes as [`apexes`] measures them (the measurement applied to rapier).
pub fn bounce_stepped(scene: &BounceScene, dt: f64, gravity: P3, sweep: Sweep) -> BounceRun {
    let g = v3(gravity);
    let ground = Obstacle::ground();
    let mut ball = Ball { c: Vec3::new(0.0, 0.0, scene.radius + scene.drop_height), v: Vec3::zeros(), r: scene.radius };
    let steps = (scene.duration / dt).ceil() as usize;
    let mut heights = Vec::with_capacity(steps + 1);
    heights.push(scene.drop_height);
    for _ in 0..steps {
        step_ball(&mut ball, &ground, &g, scene.restitution, dt, sweep);
        heights.push(ball.c.z - scene.radius);
    }
    BounceRun { apexes: apexes(&heights, dt, norm(&gravity), APEX_FLOOR), heights }
}

/// The analytic apexes of a [`BounceScene`]: Newton's restitution law returns
/// the ball with `e` times its impact speed, so each flight reaches
/// `e²` times the height of the one before: `h_k = e^{2k} h_0`, `k = 1 … n`.
pub fn bounce_analytic(scene: &BounceScene, n: usize) -> Vec<f64> {
    (1..=n).map(|k| scene.restitution.powi(2 * k as i32) * scene.drop_height).collect()
}

/// [`TunnelScene`] in our stepped world at `dt`.
pub fn tunnel_stepped(scene: &TunnelScene, dt: f64, sweep: Sweep) -> TunnelRun {
    run_tunnel(scene, dt, dt, scene.steps, sweep)
}

/// [`TunnelScene`] as one closed-form sweep: the whole run (`steps · dt`) as a
/// single step of our world.
pub fn tunnel_sweep(scene: &TunnelScene, dt: f64) -> TunnelRun {
    run_tunnel(scene, dt, dt * scene.steps as f64, 1, Sweep::ClosedForm)
}

fn run_tunnel(scene: &TunnelScene, dt: f64, step: f64, steps: usize, sweep: Sweep) -> TunnelRun {
    let wall = Obstacle::wall(scene.thickness);
    let mut ball = Ball { c: v3(scene.start(dt)), v: Vec3::new(scene.speed, 0.0, 0.0), r: scene.radius };
    for _ in 0..steps {
        step_ball(&mut ball, &wall, &Vec3::zeros(), scene.restitution, step, sweep);
    }
    TunnelRun { passed: ball.c.x > 0.0, final_x: ball.c.x }
}

// ---------------------------------------------------------------------------
// Two balls.

/// [`PairScene`] in our stepped world at `dt` (no gravity).
pub fn pair_stepped(scene: &PairScene, dt: f64, sweep: Sweep) -> PairRun {
    let steps = (scene.duration / dt).ceil() as usize;
    run_pair(scene, dt, steps, sweep)
}

/// [`PairScene`] as one closed-form sweep: the whole run as a single step.
pub fn pair_sweep(scene: &PairScene) -> PairRun {
    run_pair(scene, scene.duration, 1, Sweep::ClosedForm)
}

fn run_pair(scene: &PairScene, dt: f64, steps: usize, sweep: Sweep) -> PairRun {
    let (ra, rb) = (scene.a.radius, scene.b.radius);
    let (mut ca, mut cb) = (v3(scene.a.center), v3(scene.b.center));
    let (mut va, mut vb) = (v3(scene.va), v3(scene.vb));
    for _ in 0..steps {
        let mut rem = dt;
        for _ in 0..MAX_EVENTS_PER_STEP {
            let (a, b) = (collide::Sphere::new(ca, ra), collide::Sphere::new(cb, rb));
            let hit = match sweep {
                Sweep::ClosedForm => toi_sphere_sphere(&a, &va, &b, &vb, rem),
                Sweep::Halving => toi_sphere_sphere_halving(&a, &va, &b, &vb, rem, Halving::Steps(WORLD_HALVING_STEPS)),
            };
            let Some(hit) = hit else { break };
            ca += va * hit.t;
            cb += vb * hit.t;
            rem -= hit.t;
            if (va - vb).dot(&hit.normal) >= 0.0 {
                // In contact but not approaching: nothing to resolve.
                break;
            }
            let r = respond_sphere_sphere(&va, scene.ma, &vb, scene.mb, &hit.normal, scene.restitution);
            (va, vb) = (r.velocity_a, r.velocity_b);
        }
        ca += va * rem;
        cb += vb * rem;
    }
    PairRun { velocity_a: p3(&va), velocity_b: p3(&vb) }
}

/// The analytic answer to a [`PairScene`]: the referee's exact time of impact
/// and contact normal, then its exactly evaluated response formula along that
/// normal (each rounded once to `f64`). Balls that never meet within the
/// scene's duration keep their velocities.
pub fn pair_analytic(scene: &PairScene) -> PairRun {
    let unchanged = PairRun { velocity_a: scene.va, velocity_b: scene.vb };
    let Ok(toi) = referee::toi_sphere_sphere(&scene.a, &scene.va, &scene.b, &scene.vb, scene.duration) else {
        return unchanged;
    };
    let Some(t) = toi.toi else { return unchanged };
    // The response depends on the centres only through their direction, the
    // contact normal: place a at the normal, b at the origin.
    let a = GSphere { center: t.normal, radius: scene.a.radius };
    let b = GSphere { center: [0.0; 3], radius: scene.b.radius };
    match referee::response_sphere_sphere(&a, &scene.va, scene.ma, &b, &scene.vb, scene.mb, scene.restitution) {
        Ok(r) => PairRun { velocity_a: r.velocity_a, velocity_b: r.velocity_b },
        Err(_) => unchanged,
    }
}

/// Kinetic energy `½ m_a ‖v_a‖² + ½ m_b ‖v_b‖²` of a pair's velocities (J).
pub fn kinetic_energy(ma: f64, va: &P3, mb: f64, vb: &P3) -> f64 {
    0.5 * ma * norm(va).powi(2) + 0.5 * mb * norm(vb).powi(2)
}

/// The two-ball scenes: radii 0.5 m, impact at t = 0.5 s, run for 1 s.
pub fn pair_scenes() -> Vec<PairScene> {
    let ball = |x: f64, y: f64| GSphere { center: [x, y, 0.0], radius: 0.5 };
    let scene =
        |name, a, va, ma, b, vb, mb, restitution| PairScene { name, a, va, ma, b, vb, mb, restitution, duration: 1.0 };
    vec![
        // Gap 3 − 1 = 2 closing at 4: impact at 0.5 s; equal masses swap velocities.
        scene(
            "head-on, equal masses, e = 1",
            ball(-1.5, 0.0),
            [2.0, 0.0, 0.0],
            1.0,
            ball(1.5, 0.0),
            [-2.0, 0.0, 0.0],
            1.0,
            1.0,
        ),
        // Both stop: e = 0 leaves them with the common velocity 0.
        scene(
            "head-on, equal masses, e = 0",
            ball(-1.5, 0.0),
            [2.0, 0.0, 0.0],
            1.0,
            ball(1.5, 0.0),
            [-2.0, 0.0, 0.0],
            1.0,
            0.0,
        ),
        // a (1 kg, 4 m/s) on b (3 kg, at rest), e = 0.5: j = 4.5, a → −0.5, b → 1.5.
        scene(
            "head-on, masses 1 and 3, e = 0.5",
            ball(-1.5, 0.0),
            [4.0, 0.0, 0.0],
            1.0,
            ball(0.5, 0.0),
            [0.0; 3],
            3.0,
            0.5,
        ),
        // Offset 0.5 = half the radius sum: the normal at impact is 30° off the
        // motion; a → (1, √3), b → (3, −√3).
        scene(
            "glancing 30°, equal masses, e = 1",
            ball(-2.0, 0.5),
            [4.0, 0.0, 0.0],
            1.0,
            ball(0.0, 0.0),
            [0.0; 3],
            1.0,
            1.0,
        ),
        scene(
            "glancing 30°, masses 2 and 1, e = 0.5",
            ball(-2.0, 0.5),
            [4.0, 0.0, 0.0],
            2.0,
            ball(0.0, 0.0),
            [0.0; 3],
            1.0,
            0.5,
        ),
    ]
}

// ---------------------------------------------------------------------------
// The report.

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
    /// rapier's settings, every one ([`Settings::echo`]); the CCD mode varies
    /// per tunnelling method, as its name says.
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
}

/// The tunnelling methods, in report order.
pub fn tunnel_methods() -> Vec<String> {
    let mut m: Vec<String> = ccd_modes().iter().map(rapier_method).collect();
    m.push(Sweep::Halving.name().into());
    m.push(Sweep::ClosedForm.name().into());
    m.push(SWEEP_NAME.into());
    m
}

fn ccd_modes() -> [Ccd; 3] {
    [Ccd::Off, Ccd::On, Ccd::Soft { prediction: SOFT_CCD_PREDICTION }]
}

fn rapier_method(c: &Ccd) -> String {
    match c {
        Ccd::Soft { prediction } => format!("{RAPIER_NAME}, soft CCD ({prediction} m)"),
        c => format!("{RAPIER_NAME}, CCD {}", c.name()),
    }
}

/// The tunnelling scene at one thickness, speed and phase.
pub fn tunnel_scene(thickness: f64, speed: f64, phase: usize) -> TunnelScene {
    TunnelScene {
        radius: TUNNEL_RADIUS,
        mass: 1.0,
        thickness,
        speed,
        lead: 2.0 + (phase as f64 + 0.5) / PHASES as f64,
        steps: TUNNEL_STEPS,
        restitution: TUNNEL_RESTITUTION,
    }
}

/// The bounce scene at one restitution.
pub fn bounce_scene(restitution: f64) -> BounceScene {
    BounceScene { radius: BOUNCE_RADIUS, drop_height: DROP_HEIGHT, mass: 1.0, restitution, duration: BOUNCE_DURATION }
}

/// The highest sample after the first landing (the first local minimum).
fn highest_after_landing(heights: &[f64]) -> f64 {
    let landing = (1..heights.len()).find(|&k| k + 1 < heights.len() && heights[k] <= heights[k + 1]).unwrap_or(0);
    heights[landing..].iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// Runs every experiment with crashtest's settings ([`Settings::validation`]).
pub fn run() -> DynamicsReport {
    let base = Settings::validation(Ccd::On);
    let (dt, gravity) = (base.dt, base.gravity);
    let mut bounces = Vec::new();
    let mut deviations = Vec::new();
    for &e in &RESTITUTIONS {
        let scene = bounce_scene(e);
        let analytic = bounce_analytic(&scene, BOUNCES);
        bounces.push(ApexSeries {
            engine: ANALYTIC_NAME.into(),
            restitution: e,
            apexes: analytic.clone(),
            highest_after_landing: None,
        });
        let runs = [
            (format!("{RAPIER_NAME}, CCD on"), rapier::bounce(&base, &scene)),
            (Sweep::ClosedForm.name().into(), bounce_stepped(&scene, dt, gravity, Sweep::ClosedForm)),
            (Sweep::Halving.name().into(), bounce_stepped(&scene, dt, gravity, Sweep::Halving)),
        ];
        for (i, (engine, mut run)) in runs.into_iter().enumerate() {
            let highest = highest_after_landing(&run.heights);
            // The table and the law stop at BOUNCES; later flights are not compared.
            run.apexes.truncate(BOUNCES);
            if i == 0 {
                bounce_deviations(&mut deviations, e, &analytic, &run.apexes, highest);
            }
            bounces.push(ApexSeries {
                engine,
                restitution: e,
                apexes: run.apexes,
                highest_after_landing: Some(highest),
            });
        }
    }

    let mut tunnel = Vec::new();
    for &w in &THICKNESSES {
        for (mode, ccd) in ccd_modes().iter().enumerate() {
            let settings = Settings::validation(*ccd).weightless();
            let method = rapier_method(ccd);
            let mut passes = Vec::new();
            for &speed in &SPEEDS {
                let passed =
                    (0..PHASES).filter(|&j| rapier::tunnel(&settings, &tunnel_scene(w, speed, j)).passed).count();
                if passed > 0 {
                    passes.push(format!("{speed} m/s: {passed}/{PHASES}"));
                }
                tunnel.push(PassRow { method: method.clone(), thickness: w, speed, passed, runs: PHASES });
            }
            if !passes.is_empty() {
                deviations.push(Deviation {
                    experiment: "tunnel".into(),
                    case: format!("{method}, wall {w} m"),
                    analytic: "never passes".into(),
                    rapier: format!("passes at {}", passes.join(", ")),
                    difference: if mode == 1 {
                        "the sweep stops the ball at the wall; the next step's contact solve carries it through".into()
                    } else {
                        "tunnels: the wall is crossed within a step".into()
                    },
                });
            }
        }
        for sweep in [Sweep::Halving, Sweep::ClosedForm] {
            for &speed in &SPEEDS {
                let passed =
                    (0..PHASES).filter(|&j| tunnel_stepped(&tunnel_scene(w, speed, j), dt, sweep).passed).count();
                tunnel.push(PassRow { method: sweep.name().into(), thickness: w, speed, passed, runs: PHASES });
            }
        }
        for &speed in &SPEEDS {
            let passed = (0..PHASES).filter(|&j| tunnel_sweep(&tunnel_scene(w, speed, j), dt).passed).count();
            tunnel.push(PassRow { method: SWEEP_NAME.into(), thickness: w, speed, passed, runs: PHASES });
        }
    }

    let mut pairs = Vec::new();
    let weightless = base.weightless();
    for scene in pair_scenes() {
        let analytic = pair_analytic(&scene);
        let speed = norm(&scene.va).max(norm(&scene.vb)).max(f64::MIN_POSITIVE);
        let before = kinetic_energy(scene.ma, &scene.va, scene.mb, &scene.vb);
        let runs = [
            (ANALYTIC_NAME.to_string(), analytic),
            (format!("{RAPIER_NAME}, CCD on"), rapier::pair(&weightless, &scene)),
            (Sweep::ClosedForm.name().into(), pair_stepped(&scene, dt, Sweep::ClosedForm)),
            (Sweep::Halving.name().into(), pair_stepped(&scene, dt, Sweep::Halving)),
            (SWEEP_NAME.into(), pair_sweep(&scene)),
        ];
        for (i, (engine, run)) in runs.into_iter().enumerate() {
            let d = |g: &P3, w: &P3| norm(&[g[0] - w[0], g[1] - w[1], g[2] - w[2]]);
            let error = d(&run.velocity_a, &analytic.velocity_a).max(d(&run.velocity_b, &analytic.velocity_b)) / speed;
            let after = kinetic_energy(scene.ma, &run.velocity_a, scene.mb, &run.velocity_b);
            if i == 1 && error > PAIR_REPORT_FLOOR {
                deviations.push(Deviation {
                    experiment: "pair".into(),
                    case: scene.name.into(),
                    analytic: format!("a {}, b {}", vec_str(&analytic.velocity_a), vec_str(&analytic.velocity_b)),
                    rapier: format!("a {}, b {}", vec_str(&run.velocity_a), vec_str(&run.velocity_b)),
                    difference: format!("{error:.3e} of the largest initial speed"),
                });
            }
            pairs.push(PairRow {
                scene: scene.name.into(),
                engine,
                velocity_a: run.velocity_a,
                velocity_b: run.velocity_b,
                error,
                energy_change: (after - before) / before,
            });
        }
    }

    DynamicsReport {
        rapier: format!("{RAPIER_NAME} {RAPIER_VERSION}"),
        settings: base.echo().into_iter().map(|(n, v)| Echo { name: n.into(), value: v }).collect(),
        bounce_design: BounceDesign {
            radius: BOUNCE_RADIUS,
            drop_height: DROP_HEIGHT,
            duration: BOUNCE_DURATION,
            bounces: BOUNCES,
        },
        bounces,
        tunnel,
        pairs,
        deviations,
    }
}

/// Velocity errors below this fraction of the largest initial speed are not
/// listed as deviations of rapier (dimensionless): a few hundred ulps of the
/// speeds, the rounding of rapier's solver iterations.
pub const PAIR_REPORT_FLOOR: f64 = 1e-12;

/// Relative apex differences below this are not listed as deviations
/// (dimensionless): a few hundred ulps of heights of order 1.
pub const APEX_REPORT_FLOOR: f64 = 1e-12;

fn bounce_deviations(out: &mut Vec<Deviation>, e: f64, analytic: &[f64], apexes: &[f64], highest: f64) {
    if e == 0.0 {
        if highest > 0.0 {
            out.push(Deviation {
                experiment: "bounce".into(),
                case: "e = 0".into(),
                analytic: "no rebound (apex 0)".into(),
                rapier: format!("rises to {highest:.3e} m after landing"),
                difference: format!("{highest:.3e} m"),
            });
        }
        return;
    }
    for (k, (a, r)) in analytic.iter().zip(apexes).enumerate() {
        let rel = (r - a) / a;
        if rel.abs() > APEX_REPORT_FLOOR {
            out.push(Deviation {
                experiment: "bounce".into(),
                case: format!("e = {e}, bounce {}", k + 1),
                analytic: format!("{a:.6} m"),
                rapier: format!("{r:.6} m"),
                difference: format!("{:+.3}%", 100.0 * rel),
            });
        }
    }
    if apexes.len() < analytic.len() {
        out.push(Deviation {
            experiment: "bounce".into(),
            case: format!("e = {e}, bounces {}–{}", apexes.len() + 1, analytic.len()),
            analytic: format!("apexes down to {:.3e} m", analytic[analytic.len() - 1]),
            rapier: "not resolved by the samples (flight shorter than two steps, or at rest)".into(),
            difference: "not measured".into(),
        });
    }
}

fn vec_str(p: &P3) -> String {
    format!("({:.6}, {:.6}, {:.6})", p[0], p[1], p[2])
}

// ---------------------------------------------------------------------------
// Markdown and charts.

/// One chart of the dynamics section.
#[derive(Clone, Debug, PartialEq)]
pub struct DynamicsChart {
    /// Its caption.
    pub title: String,
    /// Its file name inside the report's `charts/` folder.
    pub file: String,
    /// The SVG document (no XML declaration, no element ids).
    pub svg: String,
}

fn file_number(x: f64) -> String {
    format!("{x}").replace('.', "_")
}

/// The section's Markdown: settings, apex tables, pass-through tables, the
/// two-ball velocities and rapier's deviations; charts are linked as
/// `charts/<file>` ([`charts`]).
pub fn markdown(r: &DynamicsReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## Dynamics\n");
    let _ = writeln!(
        s,
        "Stepped worlds at a fixed dt: {} and worlds of our own built on collide (time of impact + one \
         impulse per impact), against the analytic laws. rapier's settings, every one:\n",
        r.rapier
    );
    let _ = writeln!(s, "| setting | value |\n| --- | --- |");
    for e in &r.settings {
        let _ = writeln!(s, "| {} | {} |", e.name, e.value);
    }
    let b = &r.bounce_design;
    let _ = writeln!(
        s,
        "\n### Bounces\n\nA ball of radius {} m released at rest {} m above the ground, {} s simulated. Apex \
         heights of the ball's lowest point (m) after each impact; `—` where the samples no longer resolve a \
         flight (shorter than about two steps, or at rest). The analytic law is h_k = e^(2k) h_0.\n",
        b.radius, b.drop_height, b.duration
    );
    for &e in &RESTITUTIONS {
        let series: Vec<&ApexSeries> = r.bounces.iter().filter(|a| a.restitution.total_cmp(&e).is_eq()).collect();
        let _ = writeln!(s, "**e = {e}**\n");
        let _ = write!(s, "| bounce |");
        for a in &series {
            let _ = write!(s, " {} |", a.engine);
        }
        let _ = write!(s, "\n| --- |");
        for _ in &series {
            let _ = write!(s, " ---: |");
        }
        let _ = writeln!(s);
        for k in 0..BOUNCES {
            let _ = write!(s, "| {} |", k + 1);
            for a in &series {
                match a.apexes.get(k) {
                    Some(h) => {
                        let _ = write!(s, " {h:.6} |");
                    }
                    None => {
                        let _ = write!(s, " — |");
                    }
                }
            }
            let _ = writeln!(s);
        }
        if e == 0.0 {
            let _ = write!(s, "| highest after landing |");
            for a in &series {
                match a.highest_after_landing {
                    Some(h) => {
                        let _ = write!(s, " {h:.3e} |");
                    }
                    None => {
                        let _ = write!(s, " 0 |");
                    }
                }
            }
            let _ = writeln!(s);
        } else {
            let _ = writeln!(s, "\n![apex heights, e = {e}](charts/dynamics-apex-e{}.svg)", file_number(e));
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(
        s,
        "### Tunnelling\n\nA ball of radius {TUNNEL_RADIUS} m shot along x at a wall, restitution \
         {TUNNEL_RESTITUTION}, {PHASES} start phases per speed (the unobstructed touch falls at 2 + (j + ½)/{PHASES} \
         steps), {TUNNEL_STEPS} steps; a run passes when the ball ends beyond the wall's mid-plane. Passes out of \
         {PHASES}:\n"
    );
    let methods = tunnel_methods();
    for &w in &THICKNESSES {
        let _ = writeln!(s, "**wall {w} m**\n");
        let _ = write!(s, "| speed (m/s) |");
        for m in &methods {
            let _ = write!(s, " {m} |");
        }
        let _ = write!(s, "\n| ---: |");
        for _ in &methods {
            let _ = write!(s, " ---: |");
        }
        let _ = writeln!(s);
        for &v in &SPEEDS {
            let _ = write!(s, "| {v} |");
            for m in &methods {
                let row = r
                    .tunnel
                    .iter()
                    .find(|p| &p.method == m && p.thickness.total_cmp(&w).is_eq() && p.speed.total_cmp(&v).is_eq());
                let _ = write!(s, " {} |", row.map_or("—".to_string(), |p| p.passed.to_string()));
            }
            let _ = writeln!(s);
        }
        let _ = writeln!(s, "\n![pass-through, wall {w} m](charts/dynamics-tunnel-w{}.svg)\n", file_number(w));
    }
    let _ = writeln!(
        s,
        "### Two balls\n\nVelocities after the impact (m/s); error: largest velocity difference from the analytic \
         answer over the largest initial speed; energy: relative change of the kinetic energy.\n"
    );
    let _ = writeln!(s, "| scene | engine | a | b | error | energy |\n| --- | --- | --- | --- | ---: | ---: |");
    for p in &r.pairs {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.3e} | {:+.3e} |",
            p.scene,
            p.engine,
            vec_str(&p.velocity_a),
            vec_str(&p.velocity_b),
            p.error,
            p.energy_change
        );
    }
    let _ = writeln!(s, "\n### rapier against the laws\n\nReported as they are, not corrected:\n");
    if r.deviations.is_empty() {
        let _ = writeln!(s, "None.");
    } else {
        let _ = writeln!(s, "| experiment | case | analytic | rapier | difference |\n| --- | --- | --- | --- | --- |");
        for d in &r.deviations {
            let _ = writeln!(s, "| {} | {} | {} | {} | {} |", d.experiment, d.case, d.analytic, d.rapier, d.difference);
        }
    }
    s
}

/// The dynamics section of a report: its Markdown (also shown folded in the
/// page), its charts, and the whole [`DynamicsReport`] as `dynamics.json`.
pub fn section(r: &DynamicsReport) -> crate::render::section::Section {
    use crate::render::section::{Section, SectionChart};
    let md = markdown(r);
    Section {
        id: "dynamics".into(),
        title: "Dynamics: bounces, tunneling, two balls".into(),
        html: format!(
            "<details><summary>Tables (as in summary.md)</summary><pre>{}</pre></details>\n",
            crate::render::html::escape(&md)
        ),
        markdown: md,
        charts: charts(r).into_iter().map(|c| SectionChart { title: c.title, file: c.file, svg: c.svg }).collect(),
        data: serde_json::to_value(r).unwrap_or_else(|e| serde_json::Value::String(format!("unserializable: {e}"))),
    }
}

/// The section's charts: apex heights per bounce per engine for each
/// restitution above 0 (log y), and pass-throughs against speed per method for
/// each wall thickness (log x).
pub fn charts(r: &DynamicsReport) -> Vec<DynamicsChart> {
    let mut out = Vec::new();
    for &e in RESTITUTIONS.iter().filter(|e| **e > 0.0) {
        let series: Vec<Line> = r
            .bounces
            .iter()
            .filter(|a| a.restitution.total_cmp(&e).is_eq())
            .enumerate()
            .map(|(i, a)| Line {
                name: a.engine.clone(),
                style: i,
                points: std::iter::once((0.0, r.bounce_design.drop_height))
                    .chain(a.apexes.iter().enumerate().map(|(k, h)| ((k + 1) as f64, *h)))
                    .collect(),
                failures: Vec::new(),
            })
            .collect();
        let title = format!("Apex height per bounce, e = {e}");
        out.push(DynamicsChart {
            svg: line_chart(
                &title,
                "bounce",
                "apex height (m)",
                Axis::Linear { min: 0.0, max: BOUNCES as f64, step: 1.0 },
                Axis::log_covering(series.iter().flat_map(|l| l.points.iter().map(|p| p.1))),
                &series,
                0.0,
            ),
            file: format!("dynamics-apex-e{}.svg", file_number(e)),
            title,
        });
    }
    for &w in &THICKNESSES {
        let series: Vec<Line> = tunnel_methods()
            .into_iter()
            .enumerate()
            .map(|(i, m)| Line {
                points: r
                    .tunnel
                    .iter()
                    .filter(|p| p.method == m && p.thickness.total_cmp(&w).is_eq())
                    .map(|p| (p.speed, p.passed as f64 / p.runs.max(1) as f64))
                    .collect(),
                name: m,
                style: i,
                failures: Vec::new(),
            })
            .collect();
        let title = format!("Pass-through against speed, wall {w} m");
        out.push(DynamicsChart {
            svg: line_chart(
                &title,
                "speed (m/s)",
                "fraction of runs passing through",
                Axis::log_covering(SPEEDS.iter().copied()),
                Axis::Linear { min: 0.0, max: 1.0, step: 0.25 },
                &series,
                LINE_OFFSET_PX,
            ),
            file: format!("dynamics-tunnel-w{}.svg", file_number(w)),
            title,
        });
    }
    out
}

/// Vertical offset between the lines of a pass-through chart, px: lines at the
/// same value (most sit at 0 or 1) would hide each other, so each is shifted by
/// `(i − (n − 1)/2) ·` this; the caption says so. Under 1 % of the axis.
const LINE_OFFSET_PX: f64 = 2.5;
