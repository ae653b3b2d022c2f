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
//!
//! Split as the experiments are: `data` (the experiments' design and the
//! report's types), `run` (our stepped worlds, the analytic answers and
//! rapier's runs, measured) and `render` (Markdown and charts, from the data
//! alone).

mod data;
mod render;
mod run;

pub use data::{
    ANALYTIC_NAME, ApexSeries, BOUNCE_DURATION, BOUNCE_RADIUS, BOUNCES, BounceDesign, DROP_HEIGHT, Deviation,
    DynamicsReport, Echo, EngineSettings, PHASES, PairRow, PassRow, RESTITUTIONS, SOFT_CCD_PREDICTION, SPEEDS,
    SWEEP_NAME, Sweep, THICKNESSES, TUNNEL_RADIUS, TUNNEL_RESTITUTION, TUNNEL_STEPS, WorldFailure, methods_of,
    tunnel_methods,
};
pub use render::{DynamicsChart, charts, markdown, section};
pub use run::{
    APEX_REPORT_FLOOR, MAX_EVENTS_PER_STEP, PAIR_REPORT_FLOOR, WORLD_HALVING_STEPS, bounce_analytic, bounce_scene,
    bounce_stepped, kinetic_energy, pair_analytic, pair_scenes, pair_stepped, pair_sweep, run, run_with, steps_worlds,
    tunnel_scene, tunnel_stepped, tunnel_sweep,
};
