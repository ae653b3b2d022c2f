//! The report's time-of-impact section: accuracy against speed.
//!
//! On seeded impacts built backwards from their answer (so that every method
//! applies, the lecture's halving included: the end of each interval is in
//! contact), every method's time of impact is compared with the referee's
//! exact one, and timed on the same cases:
//!
//! - the lecture's interval halving after `k = 1 … 60` bisections (its error is
//!   at most `t_max / 2^k`, and it costs one static test per bisection);
//! - collide's robust methods: the closed forms (sphere–sphere, sphere–plane)
//!   and conservative advancement (sphere–triangle), in `f64` and `f32`;
//! - parry's `cast_shapes` in `f64` (parry3d-f64) and `f32` (parry3d), through
//!   the oracle's adapter (which converts the inputs into parry's types inside
//!   each call; `benches/toi.rs` times parry directly).
//!
//! Errors are `|t − t*| / t_max` (the referee's `t*`), per pair of shapes;
//! times are nanoseconds per query (the median of a few repetitions of a loop
//! over the cases, one thread). The misses the lecture's method is known for
//! (tunneling: the end of the interval clear) are the campaign's and the
//! dynamics section's subject; here every case is one halving can solve, so
//! the question is only how fast it gets there.

use crate::engine::{Answer, Engine};
use crate::engines::EngineSet;
use crate::load::LoadedCase;
use crate::render::markdown::{Table, table_md};
use crate::render::plot::{Axis, Line, line_chart};
use crate::render::section::{Section, SectionChart};
use crate::rng::SplitMix64;
use collide::Real;
use crashtest_core::vec3::{add, cross, dot, norm_sqrt_dot, scale, sub};
use oracle::geom::{P3, Plane, Sphere, Toi, Triangle};
use serde::Serialize;
use std::fmt::Write;
use std::hint::black_box;

/// What the section runs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Settings {
    /// Seed of the built impacts.
    pub seed: u64,
    /// Impacts per pair of shapes.
    pub cases: usize,
    /// Repetitions of each timing loop (the median is reported).
    pub reps: u32,
    /// Whether to time the methods at all (`report --no-timing` turns it off:
    /// the section then reports errors only, and says that nothing was timed).
    pub timing: bool,
}

impl Default for Settings {
    /// The campaign's seed, [`DEFAULT_CASES`] impacts per pair, [`DEFAULT_REPS`]
    /// repetitions, timed.
    fn default() -> Self {
        Self { seed: crate::defaults::DEFAULT_SEED, cases: DEFAULT_CASES, reps: DEFAULT_REPS, timing: true }
    }
}

/// Impacts per pair by default: 300. Reason: the medians and maxima of the
/// errors are stable to a few percent at that size, and the whole section
/// (60 halving depths, seven methods, three pairs, the referee) runs in well
/// under a second in a release build.
pub const DEFAULT_CASES: usize = 300;

/// Repetitions of each timing loop by default: 7 (the campaign's own choice).
pub const DEFAULT_REPS: u32 = 7;

/// The deepest halving charted: 60 bisections, past `f64`'s 53 bits (the
/// bracket then stops shrinking at the type's resolution, which the chart
/// shows as the error's floor).
pub const MAX_HALVING_STEPS: u32 = 60;

/// The halving depths that are timed (each costs one static test per
/// bisection; timing all 60 would say nothing more).
pub const TIMED_STEPS: [u32; 11] = [1, 2, 4, 8, 12, 16, 24, 32, 40, 48, 60];

/// Errors below this are drawn at it on the log axes (an error of exactly 0,
/// common for the closed forms on these cases, has no logarithm): 1e-18, two
/// orders below `f64`'s resolution of a time relative to the interval.
pub const ERROR_FLOOR: f64 = 1e-18;

/// The pairs of shapes timed and judged.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Pair {
    /// A sphere against a moving sphere.
    SphereSphere,
    /// A sphere against a moving plane (the solid half-space below it).
    SpherePlane,
    /// A sphere against a moving triangle.
    SphereTriangle,
}

impl Pair {
    /// Every pair, in report order.
    pub const ALL: [Pair; 3] = [Pair::SphereSphere, Pair::SpherePlane, Pair::SphereTriangle];

    /// Its name in tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            Pair::SphereSphere => "sphere–sphere",
            Pair::SpherePlane => "sphere–plane",
            Pair::SphereTriangle => "sphere–triangle",
        }
    }

    /// collide's robust method for the pair.
    pub fn robust_method(self) -> &'static str {
        match self {
            Pair::SphereSphere | Pair::SpherePlane => "closed form",
            Pair::SphereTriangle => "conservative advancement",
        }
    }

    fn slug(self) -> &'static str {
        match self {
            Pair::SphereSphere => "sphere-sphere",
            Pair::SpherePlane => "sphere-plane",
            Pair::SphereTriangle => "sphere-triangle",
        }
    }
}

/// One method on one pair: its errors against the referee and its time.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodRow {
    /// The pair.
    pub pair: Pair,
    /// The method (`"collide closed form f64"`, `"parry3d-f64 cast_shapes"`, …).
    pub method: String,
    /// Median of `|t − t*| / t_max` over the cases it found an impact in.
    pub median_error: f64,
    /// Largest such error.
    pub max_error: f64,
    /// Cases where it found no impact (every case has one).
    pub misses: usize,
    /// Nanoseconds per query (median of the repetitions); `None` when the
    /// section was not timed.
    pub ns_per_query: Option<f64>,
}

/// The lecture's halving after `steps` bisections on one pair.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HalvingPoint {
    /// The pair.
    pub pair: Pair,
    /// Bisections.
    pub steps: u32,
    /// Median of `|t − t*| / t_max`.
    pub median_error: f64,
    /// Largest such error.
    pub max_error: f64,
    /// The method's bound on it, `2^-steps` (relative to `t_max`).
    pub bound: f64,
    /// Cases where it found no impact.
    pub misses: usize,
    /// Nanoseconds per query, for the timed depths ([`TIMED_STEPS`]).
    pub ns_per_query: Option<f64>,
}

/// Everything the section measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ToiReport {
    /// What was run.
    pub settings: Settings,
    /// How the impacts were built, in words.
    pub design: String,
    /// The fixed methods (robust, parry) per pair.
    pub methods: Vec<MethodRow>,
    /// Halving at every depth per pair.
    pub halving: Vec<HalvingPoint>,
    /// Engines given that do not answer a pair, with the reason.
    pub not_run: Vec<NotRun>,
}

/// An engine given to the section that it could not run on a pair.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NotRun {
    /// The engine.
    pub engine: String,
    /// The pair.
    pub pair: Pair,
    /// Why: its verdict on the first impact it did not answer.
    pub reason: String,
}

// ---------------------------------------------------------------- the cases

/// The cases' draws: [`SplitMix64`] (the cases depend on the seed alone), with
/// the points and directions the impacts are built from.
struct Rng(SplitMix64);

impl Rng {
    /// Uniform in `[lo, hi)`.
    fn in_range(&mut self, lo: f64, hi: f64) -> f64 {
        self.0.range(lo, hi)
    }

    fn point(&mut self, lim: f64) -> P3 {
        [0; 3].map(|_| self.in_range(-lim, lim))
    }

    /// A unit vector (a normalized point of the cube, redrawn when too short).
    fn unit(&mut self) -> P3 {
        loop {
            let p = self.point(1.0);
            let n = norm_sqrt_dot(p);
            if n > 0.1 {
                return scale(p, 1.0 / n);
            }
        }
    }
}

/// The target of one built impact.
#[derive(Clone, Copy, Debug)]
enum Target {
    Sphere(Sphere),
    Plane(Plane),
    Triangle(Triangle),
}

/// One built impact, with the referee's answer.
#[derive(Clone, Copy, Debug)]
struct Case {
    a: Sphere,
    va: P3,
    b: Target,
    vb: P3,
    t_max: f64,
    truth: f64,
}

/// How the impacts are built (echoed in the report).
const DESIGN: &str = "Each impact is built backwards from its answer: a contact normal n, a relative velocity \
     meeting it at an angle whose cosine is at least 0.2 (speed 0.5 to 8), an impact time t* in [0.05, 1) and the \
     sphere placed so that it touches b at t*; b moves at a random velocity. t_max lies inside the time the shapes \
     stay in contact after t* (for a plane, any time after it), so the end of the interval intersects and the \
     lecture's halving applies. Sphere radii 0.1 to 2, coordinates within 4 of the origin; triangles have sides \
     of about 70 around the touching point, so the crossing stays over the face. t* is then the referee's exact \
     answer, rounded once.";

/// The impact's frame: the unit normal `n`, a unit vector `m` across it, the
/// relative velocity meeting the surface at a cosine of at least 0.2, its
/// speed and that cosine.
fn approach(rng: &mut Rng) -> (P3, P3, P3, f64, f64) {
    let n = rng.unit();
    let w = rng.unit();
    let across = sub(w, scale(n, dot(n, w)));
    let m = if norm_sqrt_dot(across) > 1e-3 {
        scale(across, 1.0 / norm_sqrt_dot(across))
    } else {
        // w along n: any perpendicular, from the axis least aligned with n.
        let axis = if n[0].abs() < 0.5 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
        let c = cross(n, axis);
        scale(c, 1.0 / norm_sqrt_dot(c))
    };
    let cos = rng.in_range(0.2, 1.0);
    let sin = (1.0 - cos * cos).sqrt();
    let speed = rng.in_range(0.5, 8.0);
    let v = scale(add(scale(n, -cos), scale(m, sin)), speed);
    (n, m, v, speed, cos)
}

fn build(pair: Pair, rng: &mut Rng) -> Option<Case> {
    let (n, m, v, speed, cos) = approach(rng);
    let vb = rng.point(4.0);
    let va = add(vb, v);
    let t_star = rng.in_range(0.05, 1.0);
    let frac = rng.in_range(0.1, 0.9);
    let q = rng.point(4.0);
    let (a, b, t_max) = match pair {
        Pair::SphereSphere => {
            let (ra, rb) = (rng.in_range(0.1, 2.0), rng.in_range(0.1, 2.0));
            let r = ra + rb;
            // a − b = n R at t*; the path's chord through the sphere of radius
            // R is 2 R cos long, so the overlap lasts 2 R cos / speed.
            let ca = sub(add(q, scale(n, r)), scale(v, t_star));
            (Sphere { center: ca, radius: ra }, Target::Sphere(Sphere { center: q, radius: rb }), 2.0 * r * cos / speed)
        }
        Pair::SpherePlane => {
            let r = rng.in_range(0.1, 2.0);
            let len = rng.in_range(0.5, 3.0);
            let normal = scale(n, len);
            let ca = sub(add(q, scale(n, r)), scale(v, t_star));
            (Sphere { center: ca, radius: r }, Target::Plane(Plane { normal, offset: dot(normal, q) }), 1.0)
        }
        Pair::SphereTriangle => {
            let r = rng.in_range(0.1, 1.0);
            let e = cross(n, m);
            let corner = |s: f64, t: f64| add(q, scale(add(scale(m, s), scale(e, t)), 40.0));
            let tri = Triangle { vertices: [corner(1.0, 0.0), corner(-0.5, 0.9), corner(-0.5, -0.9)] };
            let ca = sub(add(q, scale(n, r)), scale(v, t_star));
            // The sheet's reach, 2r thick, is crossed in 2 r / (speed cos).
            (Sphere { center: ca, radius: r }, Target::Triangle(tri), 2.0 * r / (speed * cos))
        }
    };
    let t_max = t_star + frac * t_max;
    let truth = match &b {
        Target::Sphere(s) => oracle::referee::toi_sphere_sphere(&a, &va, s, &vb, t_max),
        Target::Plane(p) => oracle::referee::toi_sphere_plane(&a, &va, p, &vb, t_max),
        Target::Triangle(t) => oracle::referee::toi_sphere_triangle(&a, &va, t, &vb, t_max),
    }
    .ok()?
    .toi?
    .t;
    Some(Case { a, va, b, vb, t_max, truth })
}

fn cases(pair: Pair, settings: &Settings) -> Vec<Case> {
    let mut rng = Rng(SplitMix64(settings.seed ^ (pair as u64 + 1).wrapping_mul(0xA076_1D64_78BD_642F)));
    let mut out = Vec::with_capacity(settings.cases);
    // The construction always has an impact; the bound only guards the loop.
    for _ in 0..settings.cases.saturating_mul(4) {
        if out.len() == settings.cases {
            break;
        }
        if let Some(c) = build(pair, &mut rng) {
            out.push(c);
        }
    }
    out
}

// -------------------------------------------------------------- the methods

fn v<T: Real>(p: &P3) -> collide::Vec3<T> {
    collide::Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]))
}

/// A case in collide's types and precision.
struct Prepared<T: Real> {
    a: collide::Sphere<T>,
    va: collide::Vec3<T>,
    b: PreparedTarget<T>,
    vb: collide::Vec3<T>,
    t_max: T,
}

enum PreparedTarget<T: Real> {
    Sphere(collide::Sphere<T>),
    Plane(collide::Plane<T>),
    Triangle(collide::Triangle<T>),
}

fn prepare<T: Real>(c: &Case) -> Prepared<T> {
    Prepared {
        a: collide::Sphere::new(v(&c.a.center), T::of(c.a.radius)),
        va: v(&c.va),
        b: match &c.b {
            Target::Sphere(s) => PreparedTarget::Sphere(collide::Sphere::new(v(&s.center), T::of(s.radius))),
            Target::Plane(p) => PreparedTarget::Plane(collide::Plane::new(v(&p.normal), T::of(p.offset))),
            Target::Triangle(t) => PreparedTarget::Triangle(collide::Triangle::new(
                v(&t.vertices[0]),
                v(&t.vertices[1]),
                v(&t.vertices[2]),
            )),
        },
        vb: v(&c.vb),
        t_max: T::of(c.t_max),
    }
}

/// collide's robust method on a prepared case: the time, if any.
fn robust<T: Real>(p: &Prepared<T>) -> Option<T> {
    use collide::toi::{Advancement, toi_sphere_plane, toi_sphere_sphere, toi_sphere_triangle};
    match &p.b {
        PreparedTarget::Sphere(b) => toi_sphere_sphere(&p.a, &p.va, b, &p.vb, p.t_max).map(|k| k.t),
        PreparedTarget::Plane(b) => toi_sphere_plane(&p.a, &p.va, b, &p.vb, p.t_max).map(|k| k.t),
        PreparedTarget::Triangle(b) => {
            toi_sphere_triangle(&p.a, &p.va, b, &p.vb, p.t_max, &Advancement::default()).map(|k| k.t)
        }
    }
}

/// The lecture's halving after `steps` bisections on a prepared case.
fn halving<T: Real>(p: &Prepared<T>, steps: u32) -> Option<T> {
    use collide::toi::{Halving, toi_sphere_plane_halving, toi_sphere_sphere_halving, toi_sphere_triangle_halving};
    let stop = Halving::Steps(steps);
    match &p.b {
        PreparedTarget::Sphere(b) => toi_sphere_sphere_halving(&p.a, &p.va, b, &p.vb, p.t_max, stop).map(|k| k.t),
        PreparedTarget::Plane(b) => toi_sphere_plane_halving(&p.a, &p.va, b, &p.vb, p.t_max, stop).map(|k| k.t),
        PreparedTarget::Triangle(b) => toi_sphere_triangle_halving(&p.a, &p.va, b, &p.vb, p.t_max, stop).map(|k| k.t),
    }
}

/// A built impact as a fixture case, for an engine behind the seam.
fn as_loaded(c: &Case) -> LoadedCase {
    use crate::case::{PlaneSpec, Shape, SphereSpec, TriangleSpec};
    let b = match &c.b {
        Target::Sphere(s) => {
            Shape::Sphere(SphereSpec { center: s.center, radius: s.radius, velocity: Some(c.vb), mass: None })
        }
        Target::Plane(p) => Shape::Plane(PlaneSpec { normal: p.normal, offset: p.offset, velocity: Some(c.vb) }),
        Target::Triangle(t) => Shape::Triangle(TriangleSpec { vertices: t.vertices, velocity: Some(c.vb) }),
    };
    crate::generate::loaded(crate::case::Case {
        name: "toi section impact".into(),
        source: "generated: the toi section's built impacts".into(),
        query: crate::case::Query::Toi,
        a: Shape::Sphere(SphereSpec { center: c.a.center, radius: c.a.radius, velocity: Some(c.va), mass: None }),
        b: Some(b),
        expect: None,
        tol: None,
        t_max: Some(c.t_max),
        restitution: None,
    })
}

/// An engine's time of impact on a built impact, through the seam: `Err` with
/// its reason when it does not answer this pair; a failure (a panic, a
/// non-finite number) counts as a miss, as a wrong answer would.
fn seam(e: &Engine, lc: &LoadedCase) -> Result<Option<f64>, String> {
    match crate::check::run_caught(e, lc) {
        Ok(Answer::Toi(a)) => Ok(a.toi.map(|k: Toi| k.t)),
        Ok(_) => Ok(None),
        Err(crate::judge::Verdict::Unsupported { reason }) => Err(reason),
        Err(_) => Ok(None),
    }
}

/// Median nanoseconds per query of `reps` loops of `f` over `n` queries, or
/// `None` without running `f` when the section is not timed.
fn time_ns(settings: &Settings, n: usize, f: impl FnMut()) -> Option<f64> {
    settings.timing.then(|| crate::timing::median_ns(settings.reps, n, f))
}

/// Median and largest of the errors, and the misses.
fn summarize(cases: &[Case], answers: &[Option<f64>]) -> (f64, f64, usize) {
    let mut errs: Vec<f64> =
        cases.iter().zip(answers).filter_map(|(c, a)| a.map(|t| (t - c.truth).abs() / c.t_max)).collect();
    let misses = answers.iter().filter(|a| a.is_none()).count();
    errs.sort_by(f64::total_cmp);
    let median = errs.get(errs.len() / 2).copied().unwrap_or(f64::NAN);
    (median, errs.last().copied().unwrap_or(f64::NAN), misses)
}

fn method_row(pair: Pair, method: &str, cases: &[Case], answers: &[Option<f64>], ns: Option<f64>) -> MethodRow {
    let (median_error, max_error, misses) = summarize(cases, answers);
    MethodRow { pair, method: method.into(), median_error, max_error, misses, ns_per_query: ns }
}

fn fixed_methods<T: Real>(pair: Pair, cases: &[Case], settings: &Settings, precision: &str) -> MethodRow {
    let prepared: Vec<Prepared<T>> = cases.iter().map(prepare).collect();
    let answers: Vec<Option<f64>> = prepared.iter().map(|p| robust(p).map(|t| t.wide())).collect();
    let ns = time_ns(settings, prepared.len(), || {
        for p in &prepared {
            black_box(robust(black_box(p)));
        }
    });
    method_row(pair, &format!("collide {} {precision}", pair.robust_method()), cases, &answers, ns)
}

/// An engine's row, through the seam (parry's is its `cast_shapes`, through the
/// oracle's adapter); `Err` with the reason when it does not answer the pair.
fn seam_row(pair: Pair, e: &Engine, cases: &[Case], settings: &Settings) -> Result<MethodRow, String> {
    let loaded: Vec<LoadedCase> = cases.iter().map(as_loaded).collect();
    e.prefetch(&loaded);
    let answers = loaded.iter().map(|lc| seam(e, lc)).collect::<Result<Vec<Option<f64>>, String>>()?;
    let ns = match e.process() {
        // A process engine's own times, measured inside it.
        Some(p) => p.mean_ns(&loaded).map(|(ns, _)| ns).filter(|_| settings.timing),
        None => time_ns(settings, loaded.len(), || {
            for lc in &loaded {
                let _ = black_box(e.run(black_box(lc)));
            }
        }),
    };
    let method = if e.name.starts_with("parry3d") { format!("{} cast_shapes", e.name) } else { e.name.clone() };
    Ok(method_row(pair, &method, cases, &answers, ns))
}

/// Runs the section's measurements.
///
/// collide's methods are measured through their own functions (the halving at
/// every depth, the robust closed forms and advancement); every other engine of
/// `engines` through the seam, and one that does not answer a pair is listed
/// in `not_run` with the reason.
pub fn run(settings: &Settings, engines: &EngineSet) -> ToiReport {
    let mut methods = Vec::new();
    let mut points = Vec::new();
    let mut not_run = Vec::new();
    for pair in Pair::ALL {
        let cases = cases(pair, settings);
        methods.push(fixed_methods::<f64>(pair, &cases, settings, "f64"));
        methods.push(fixed_methods::<f32>(pair, &cases, settings, "f32"));
        for e in engines.judged.iter().filter(|e| !crate::engines::is_collide(e)) {
            match seam_row(pair, e, &cases, settings) {
                Ok(row) => methods.push(row),
                Err(why) => not_run.push(NotRun { engine: e.name.clone(), pair, reason: why }),
            }
        }
        let prepared: Vec<Prepared<f64>> = cases.iter().map(prepare).collect();
        for steps in 1..=MAX_HALVING_STEPS {
            let answers: Vec<Option<f64>> = prepared.iter().map(|p| halving(p, steps)).collect();
            let (median_error, max_error, misses) = summarize(&cases, &answers);
            let ns_per_query = if TIMED_STEPS.contains(&steps) {
                time_ns(settings, prepared.len(), || {
                    for p in &prepared {
                        black_box(halving(black_box(p), steps));
                    }
                })
            } else {
                None
            };
            let bound = 0.5f64.powi(steps as i32);
            points.push(HalvingPoint { pair, steps, median_error, max_error, bound, misses, ns_per_query });
        }
    }
    ToiReport { settings: *settings, design: DESIGN.into(), methods, halving: points, not_run }
}

// ------------------------------------------------------------ the rendering

fn sci(x: f64) -> String {
    crate::render::markdown::sci(x)
}

/// A time per query as a table cell: `—` where nothing was timed.
fn ns_cell(ns: Option<f64>) -> String {
    ns.map_or("—".into(), |ns| format!("{ns:.1}"))
}

/// What the section says of its times: how they were measured, or that they
/// were not.
fn timing_words(s: &Settings) -> String {
    if s.timing {
        format!(
            "times are ns per query, the median of {} loops over the cases on one thread. parry is called through \
             the oracle's adapter (its conversions included; `cargo bench --bench toi` times it directly).",
            s.reps
        )
    } else {
        "nothing was timed (the report was run with --no-timing): the ns / query column is empty and the \
         error-against-time charts are left out."
            .into()
    }
}

/// The table of the fixed methods and of halving at a few depths.
fn table(r: &ToiReport) -> Table {
    let mut t = Table {
        header: ["pair", "method", "median error", "max error", "misses", "ns / query"].map(String::from).to_vec(),
        numeric: vec![false, false, true, true, true, true],
        rows: Vec::new(),
    };
    for pair in Pair::ALL {
        for m in r.methods.iter().filter(|m| m.pair == pair) {
            t.rows.push(vec![
                pair.label().into(),
                m.method.clone(),
                sci(m.median_error),
                sci(m.max_error),
                m.misses.to_string(),
                ns_cell(m.ns_per_query),
            ]);
        }
        for h in r.halving.iter().filter(|h| h.pair == pair && [8, 24, 40, 60].contains(&h.steps)) {
            t.rows.push(vec![
                pair.label().into(),
                format!("collide lecture halving f64, {} bisections", h.steps),
                sci(h.median_error),
                sci(h.max_error),
                h.misses.to_string(),
                ns_cell(h.ns_per_query),
            ]);
        }
    }
    t
}

/// The section's Markdown.
pub fn markdown(r: &ToiReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## Time of impact: accuracy against speed\n");
    let _ = writeln!(
        s,
        "{} impacts per pair (seed {}); errors are |t − t*| / t_max against the referee's exact t*; {}\n",
        r.settings.cases,
        r.settings.seed,
        timing_words(&r.settings)
    );
    let _ = writeln!(s, "{}\n", r.design);
    let _ = writeln!(
        s,
        "The lecture's halving gains one bit per bisection (its error stays under t_max / 2^k) until the type's \
         resolution; every bisection costs one static test. The closed forms reach the referee's answer to \
         rounding in one evaluation; conservative advancement in a few steps.\n"
    );
    s.push_str(&table_md(&table(r)));
    s.push_str(&not_run_words(r));
    for c in charts(r) {
        let _ = writeln!(s, "\n![{}](charts/{})", c.title, c.file);
    }
    s
}

/// The engines given that the section did not run, with the reasons (empty
/// when it ran them all).
fn not_run_words(r: &ToiReport) -> String {
    let mut s = String::new();
    for n in &r.not_run {
        let _ = writeln!(s, "\nNot run: {} on {} ({}).", n.engine, n.pair.label(), n.reason);
    }
    s
}

fn floor(x: f64) -> f64 {
    if x.is_nan() { x } else { x.max(ERROR_FLOOR) }
}

/// The section's charts: the error against the number of bisections, and for
/// each pair the error against the time per query (when timed).
pub fn charts(r: &ToiReport) -> Vec<SectionChart> {
    let mut out = Vec::new();
    let mut series: Vec<Line> = Pair::ALL
        .iter()
        .enumerate()
        .map(|(i, &pair)| Line {
            name: format!("halving, {} (median)", pair.label()),
            style: i,
            points: r
                .halving
                .iter()
                .filter(|h| h.pair == pair)
                .map(|h| (f64::from(h.steps), floor(h.median_error)))
                .collect(),
            failures: Vec::new(),
        })
        .collect();
    series.push(Line {
        name: "halving, largest over all pairs".into(),
        style: 3,
        points: (1..=MAX_HALVING_STEPS)
            .map(|k| {
                let worst = r.halving.iter().filter(|h| h.steps == k).map(|h| h.max_error).fold(0.0, f64::max);
                (f64::from(k), floor(worst))
            })
            .collect(),
        failures: Vec::new(),
    });
    series.push(Line {
        name: "bound t_max / 2^k".into(),
        style: 4,
        points: (1..=MAX_HALVING_STEPS).map(|k| (f64::from(k), floor(0.5f64.powi(k as i32)))).collect(),
        failures: Vec::new(),
    });
    for (style, prefix, label) in [
        (5, "collide", "collide robust f64 (median, worst pair)"),
        (6, "parry3d-f64", "parry3d-f64 (median, worst pair)"),
    ] {
        let rows: Vec<f64> = r
            .methods
            .iter()
            .filter(|m| m.method.starts_with(prefix) && (prefix != "collide" || m.method.ends_with("f64")))
            .map(|m| m.median_error)
            .collect();
        if rows.is_empty() {
            continue;
        }
        let worst = rows.into_iter().fold(0.0, f64::max);
        series.push(Line {
            name: label.into(),
            style,
            points: vec![(0.0, floor(worst)), (f64::from(MAX_HALVING_STEPS), floor(worst))],
            failures: Vec::new(),
        });
    }
    let ya = Axis::log_covering(series.iter().flat_map(|l| l.points.iter().map(|p| p.1)));
    let title = "Time-of-impact error against halving bisections".to_string();
    out.push(SectionChart {
        svg: line_chart(
            &title,
            "bisections k",
            "|t − t*| / t_max",
            Axis::Linear { min: 0.0, max: f64::from(MAX_HALVING_STEPS), step: 10.0 },
            ya,
            &series,
            0.0,
        ),
        title,
        file: "toi-halving.svg".into(),
    });
    for pair in Pair::ALL.into_iter().filter(|_| r.settings.timing) {
        let mut series = vec![Line {
            name: "collide lecture halving f64 (k bisections)".into(),
            style: 0,
            points: r
                .halving
                .iter()
                .filter(|h| h.pair == pair)
                .filter_map(|h| Some((h.ns_per_query?, floor(h.median_error))))
                .collect(),
            failures: Vec::new(),
        }];
        for (i, m) in r.methods.iter().filter(|m| m.pair == pair).enumerate() {
            series.push(Line {
                name: m.method.clone(),
                style: i + 1,
                points: m.ns_per_query.map(|ns| (ns, floor(m.median_error))).into_iter().collect(),
                failures: Vec::new(),
            });
        }
        let xa = Axis::log_covering(series.iter().flat_map(|l| l.points.iter().map(|p| p.0)));
        let ya = Axis::log_covering(series.iter().flat_map(|l| l.points.iter().map(|p| p.1)));
        let title = format!("Time-of-impact error against time per query, {}", pair.label());
        out.push(SectionChart {
            svg: line_chart(&title, "ns per query", "median |t − t*| / t_max", xa, ya, &series, 0.0),
            title,
            file: format!("toi-speed-{}.svg", pair.slug()),
        });
    }
    out
}

/// The report's time-of-impact section (id `"toi"`): [`run`], then its
/// Markdown, an HTML body (the table and the reading notes) and its charts; the
/// data is the whole [`ToiReport`].
pub fn section(settings: &Settings, engines: &EngineSet) -> Section {
    section_of(&run(settings, engines))
}

/// The section of measurements already made.
pub fn section_of(r: &ToiReport) -> Section {
    let md = markdown(r);
    let not_run = not_run_words(r);
    let html = format!(
        "<p>{}</p>\n<p>{}</p>\n{}{}",
        crate::render::html::escape(&format!(
            "{} impacts per pair (seed {}); errors are |t − t*| / t_max against the referee's exact t*; {}",
            r.settings.cases,
            r.settings.seed,
            timing_words(&r.settings)
        )),
        crate::render::html::escape(&r.design),
        crate::render::html::table_html(&table(r)),
        not_run
            .lines()
            .filter(|l| !l.is_empty())
            .map(|l| format!("<p>{}</p>\n", crate::render::html::escape(l)))
            .collect::<String>()
    );
    Section {
        id: "toi".into(),
        title: "Time of impact: accuracy against speed".into(),
        html,
        markdown: md,
        charts: charts(r),
        data: serde_json::to_value(r).unwrap_or_else(|e| serde_json::Value::String(format!("unserializable: {e}"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> Settings {
        Settings { seed: 3, cases: 40, reps: 1, timing: true }
    }

    #[test]
    fn toi_section_untimed_times_nothing_and_says_so() {
        let s = section(&Settings { timing: false, ..small() }, &Default::default());
        assert!(s.markdown.contains("nothing was timed"), "{}", s.markdown);
        assert!(s.html.contains("nothing was timed"), "{}", s.html);
        assert_eq!(s.charts.len(), 1, "only the error-against-bisections chart");
        let methods = s.data["methods"].as_array().expect("methods");
        assert!(!methods.is_empty() && methods.iter().all(|m| m["ns_per_query"].is_null()), "{methods:?}");
        let halving = s.data["halving"].as_array().expect("halving");
        assert!(halving.iter().all(|h| h["ns_per_query"].is_null()));
    }

    #[test]
    fn toi_section_renders_its_table_and_charts() {
        let s = section(&small(), &Default::default());
        assert_eq!(s.id, "toi");
        assert!(s.markdown.starts_with("## Time of impact"), "{}", s.markdown);
        assert!(s.html.contains("<table>"), "the table is in the body");
        assert_eq!(s.charts.len(), 1 + Pair::ALL.len());
        for c in &s.charts {
            assert!(c.svg.starts_with("<svg") && c.svg.ends_with("</svg>") && c.file.ends_with(".svg"), "{}", c.file);
            assert!(s.markdown.contains(&format!("charts/{}", c.file)), "{} linked", c.file);
        }
        assert!(s.data.get("halving").and_then(|h| h.as_array()).is_some_and(|h| h.len() == 3 * 60));
    }

    #[test]
    fn toi_halving_stays_within_its_bound_and_the_robust_methods_within_rounding() {
        let r = run(&small(), &Default::default());
        // Halving's bracket holds the first touch the static test sees, so its
        // error is under t_max / 2^k, plus the rounding of the static tests
        // and of t_max itself (a few ulps relative to the interval).
        const ROUNDING: f64 = 64.0 * f64::EPSILON;
        for h in &r.halving {
            assert_eq!(h.misses, 0, "{:?}: the end of every interval is in contact", h.pair);
            assert!(
                h.max_error <= h.bound + ROUNDING,
                "{:?} after {}: {:e} > {:e}",
                h.pair,
                h.steps,
                h.max_error,
                h.bound
            );
        }
        // The closed forms and advancement, in f64, on these well-conditioned
        // impacts: a few ulps of the scene's scale (up to about 45, the
        // triangles' corners) over the closing speed (at least 0.1) and the
        // interval (at least 0.05), so at most about 1e-12 of t_max.
        const ROBUST: f64 = 1e-12;
        for m in r.methods.iter().filter(|m| m.method.starts_with("collide") && m.method.ends_with("f64")) {
            assert!(m.misses == 0 && m.max_error <= ROBUST, "{}: {m:?}", m.method);
        }
        // f32 and parry answer every case, to their own precision.
        for m in &r.methods {
            assert!(m.misses == 0 && m.max_error < 1e-2, "{}: {m:?}", m.method);
        }
    }

    #[test]
    fn toi_cases_depend_on_the_seed_alone() {
        let (a, b) = (cases(Pair::SphereTriangle, &small()), cases(Pair::SphereTriangle, &small()));
        assert_eq!(a.len(), 40);
        assert!(
            a.iter()
                .zip(&b)
                .all(|(x, y)| x.truth.to_bits() == y.truth.to_bits() && x.t_max.to_bits() == y.t_max.to_bits())
        );
        let c = cases(Pair::SphereTriangle, &Settings { seed: 4, ..small() });
        assert!(a.iter().zip(&c).any(|(x, y)| x.truth.to_bits() != y.truth.to_bits()));
    }
}
