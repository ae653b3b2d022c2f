//! The dynamics experiments' run: our stepped worlds on collide, the analytic
//! answers, rapier's runs, and the report they make.

use super::data::{
    ANALYTIC_NAME, ApexSeries, BOUNCE_DURATION, BOUNCE_RADIUS, BOUNCES, BounceDesign, DROP_HEIGHT, Deviation,
    DynamicsReport, Echo, EngineSettings, PHASES, PairRow, PassRow, RESTITUTIONS, SPEEDS, SWEEP_NAME, Sweep,
    THICKNESSES, TUNNEL_RADIUS, TUNNEL_RESTITUTION, TUNNEL_STEPS, WorldFailure, ccd_modes, rapier_method, vec_str,
};
use crate::protocol::messages::{Body, Cuboid, World, WorldReply};
use collide::Vec3;
use collide::contact::{Contact, contact_sphere_plane};
use collide::response::{respond_sphere_plane, respond_sphere_sphere};
use collide::toi::{Halving, toi_halving, toi_sphere_plane, toi_sphere_sphere, toi_sphere_sphere_halving};
use crashtest_core::vec3::{norm_sqrt_dot, sub};
use oracle::geom::{P3, Sphere as GSphere};
use oracle::rapier::{
    self, APEX_FLOOR, BounceRun, BounceScene, Ccd, PairRun, PairScene, RAPIER_NAME, RAPIER_VERSION, Settings,
    TunnelRun, TunnelScene, apexes,
};
use oracle::referee;

/// Bisections per halving search in our halving world: 40, as the collide
/// engine's lecture method (`engines::collide::HALVING_STEPS`), so the impact
/// time is within `dt / 2⁴⁰` of the first time the end-of-interval test sees.
pub const WORLD_HALVING_STEPS: u32 = 40;
/// Impacts handled within one step of our worlds before the rest of the step
/// is treated as a resting contact (the bounce's Zeno regime, where an exact
/// model bounces infinitely often in finite time).
pub const MAX_EVENTS_PER_STEP: usize = 8;

fn v3(p: P3) -> Vec3<f64> {
    Vec3::new(p[0], p[1], p[2])
}

fn p3(v: &Vec3<f64>) -> P3 {
    [v.x, v.y, v.z]
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
    BounceRun { apexes: apexes(&heights, dt, norm_sqrt_dot(gravity), APEX_FLOOR), heights }
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
    0.5 * ma * norm_sqrt_dot(*va).powi(2) + 0.5 * mb * norm_sqrt_dot(*vb).powi(2)
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
        let speed = norm_sqrt_dot(scene.va).max(norm_sqrt_dot(scene.vb)).max(f64::MIN_POSITIVE);
        let before = kinetic_energy(scene.ma, &scene.va, scene.mb, &scene.vb);
        let runs = [
            (ANALYTIC_NAME.to_string(), analytic),
            (format!("{RAPIER_NAME}, CCD on"), rapier::pair(&weightless, &scene)),
            (Sweep::ClosedForm.name().into(), pair_stepped(&scene, dt, Sweep::ClosedForm)),
            (Sweep::Halving.name().into(), pair_stepped(&scene, dt, Sweep::Halving)),
            (SWEEP_NAME.into(), pair_sweep(&scene)),
        ];
        for (i, (engine, run)) in runs.into_iter().enumerate() {
            let d = |g: &P3, w: &P3| norm_sqrt_dot(sub(*g, *w));
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
        engine_settings: Vec::new(),
        world_failures: Vec::new(),
    }
}

/// [`run`], and the same experiments stepped by every engine of `engines`
/// that steps worlds (a process engine whose hello says `worlds`), through the
/// protocol: its apexes, pass-throughs and two-ball velocities beside rapier's
/// and collide's, its settings as it echoed them, and every world it did not
/// step with the reason.
pub fn run_with(engines: &[crate::engine::Engine]) -> DynamicsReport {
    let mut r = run();
    for e in engines {
        if let Some(p) = e.process().filter(|p| p.hello().is_some_and(|h| h.worlds)) {
            process_worlds(&mut r, &e.name, p);
        }
    }
    r
}

/// Whether `e` steps worlds: the dynamics section runs it.
pub fn steps_worlds(e: &crate::engine::Engine) -> bool {
    e.process().and_then(|p| p.hello()).is_some_and(|h| h.worlds)
}

fn ball_body(center: P3, radius: f64, velocity: P3, mass: f64, restitution: f64) -> Body {
    Body {
        sphere: Some(crashtest_core::geom::Ball { center, radius }),
        velocity: Some(velocity),
        mass: Some(mass),
        restitution,
        ..Default::default()
    }
}

/// One engine's runs of the three experiments, added to `r`.
fn process_worlds(r: &mut DynamicsReport, name: &str, p: &crate::protocol::ProcessEngine) {
    let base = Settings::validation(Ccd::Off);
    let (dt, gravity) = (base.dt, base.gravity);
    let g = norm_sqrt_dot(gravity);
    let mut settings_seen = false;
    let mut step = |r: &mut DynamicsReport, world: World| -> Option<WorldReply> {
        match p.world(&world) {
            Ok(reply)
                if reply.positions.len() as u64 == world.steps + 1
                    && reply
                        .positions
                        .iter()
                        .all(|at| at.len() == world.bodies.iter().filter(|b| b.sphere.is_some()).count())
                    && reply.velocities.len() == world.bodies.iter().filter(|b| b.sphere.is_some()).count() =>
            {
                if !settings_seen {
                    settings_seen = true;
                    r.engine_settings.push(EngineSettings {
                        engine: name.into(),
                        settings: reply
                            .settings
                            .iter()
                            .map(|(k, v)| Echo { name: k.clone(), value: v.clone() })
                            .collect(),
                    });
                }
                Some(reply)
            }
            Ok(reply) => {
                r.world_failures.push(WorldFailure {
                    engine: name.into(),
                    world: world.name.clone(),
                    reason: format!(
                        "a trajectory of {} samples and {} velocities, expected {} samples of every sphere",
                        reply.positions.len(),
                        reply.velocities.len(),
                        world.steps + 1
                    ),
                });
                None
            }
            Err(why) => {
                r.world_failures.push(WorldFailure { engine: name.into(), world: world.name.clone(), reason: why });
                None
            }
        }
    };
    for &e in &RESTITUTIONS {
        let scene = bounce_scene(e);
        let world = World {
            id: 0,
            name: format!("bounce, e = {e}"),
            dt,
            steps: (scene.duration / dt).ceil() as u64,
            gravity,
            ccd: false,
            bodies: vec![
                ball_body([0.0, 0.0, scene.radius + scene.drop_height], scene.radius, [0.0; 3], scene.mass, e),
                Body {
                    plane: Some(crashtest_core::geom::Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 }),
                    restitution: e,
                    ..Default::default()
                },
            ],
        };
        if let Some(reply) = step(r, world) {
            let heights: Vec<f64> = reply.positions.iter().map(|at| at[0][2] - scene.radius).collect();
            let mut apexes = rapier::apexes(&heights, dt, g, APEX_FLOOR);
            apexes.truncate(BOUNCES);
            r.bounces.push(ApexSeries {
                engine: name.into(),
                restitution: e,
                apexes,
                highest_after_landing: Some(highest_after_landing(&heights)),
            });
        }
    }
    for ccd in [false, true] {
        let method = format!("{name}, CCD {}", if ccd { "requested" } else { "off" });
        for &w in &THICKNESSES {
            for &speed in &SPEEDS {
                let (mut passed, mut runs) = (0, 0);
                for j in 0..PHASES {
                    let scene = tunnel_scene(w, speed, j);
                    let world = World {
                        id: 0,
                        name: format!(
                            "tunnel, wall {w} m, {speed} m/s, phase {j}, CCD {}",
                            if ccd { "requested" } else { "off" }
                        ),
                        dt,
                        steps: scene.steps as u64,
                        gravity: [0.0; 3],
                        ccd,
                        bodies: vec![
                            ball_body(scene.start(dt), scene.radius, [speed, 0.0, 0.0], scene.mass, scene.restitution),
                            Body {
                                cuboid: Some(Cuboid {
                                    center: [0.0; 3],
                                    half_extents: [w / 2.0, rapier::WALL_HALF_SPAN, rapier::WALL_HALF_SPAN],
                                }),
                                restitution: scene.restitution,
                                ..Default::default()
                            },
                        ],
                    };
                    if let Some(reply) = step(r, world) {
                        runs += 1;
                        if reply.positions.last().is_some_and(|at| at[0][0] > 0.0) {
                            passed += 1;
                        }
                    }
                }
                r.tunnel.push(PassRow { method: method.clone(), thickness: w, speed, passed, runs });
            }
        }
    }
    for scene in pair_scenes() {
        let world = World {
            id: 0,
            name: format!("two balls, {}", scene.name),
            dt,
            steps: (scene.duration / dt).ceil() as u64,
            gravity: [0.0; 3],
            ccd: false,
            bodies: vec![
                ball_body(scene.a.center, scene.a.radius, scene.va, scene.ma, scene.restitution),
                ball_body(scene.b.center, scene.b.radius, scene.vb, scene.mb, scene.restitution),
            ],
        };
        let Some(reply) = step(r, world) else { continue };
        let analytic = pair_analytic(&scene);
        let speed = norm_sqrt_dot(scene.va).max(norm_sqrt_dot(scene.vb)).max(f64::MIN_POSITIVE);
        let (va, vb) = (reply.velocities[0], reply.velocities[1]);
        let d = |g: &P3, w: &P3| norm_sqrt_dot(sub(*g, *w));
        let before = kinetic_energy(scene.ma, &scene.va, scene.mb, &scene.vb);
        let after = kinetic_energy(scene.ma, &va, scene.mb, &vb);
        r.pairs.push(PairRow {
            scene: scene.name.into(),
            engine: name.into(),
            velocity_a: va,
            velocity_b: vb,
            error: d(&va, &analytic.velocity_a).max(d(&vb, &analytic.velocity_b)) / speed,
            energy_change: (after - before) / before,
        });
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
