//! Time of impact, collide against parry, one run: `cargo bench --bench toi`.
//!
//! For sphere–sphere, sphere–plane and sphere–triangle (each shape moving),
//! on the same pre-generated seeded cases ([`PER_PAIR`] per pair, drawn from
//! the campaign's own toi generators, [`SEED`], so hits, misses, grazing
//! passes, shapes already overlapping and tunneling come in the campaign's
//! proportions):
//!
//! - collide's robust method: the closed form (sphere–sphere, sphere–plane) or
//!   conservative advancement (sphere–triangle), `f64` and `f32`;
//! - the lecture's interval halving to a bracket of 1e-12 (`f64`);
//! - for sphere–sphere, the textbook closed form with no checks around it
//!   (`toi/textbook.rs`): a reference, not an engine — how fast the formula
//!   alone runs on these cases;
//! - parry3d-f64's and parry3d's `query::cast_shapes`, called directly on
//!   inputs already in parry's types (poses and shapes built before timing, as
//!   the oracle's adapter builds them, with its options: stop at a touch, at
//!   `t_max` inclusive, `t = 0` when already in contact), and through the
//!   adapter (`oracle::parry::ParryCast`, which converts inside each call).
//!
//! Every engine's inputs are converted to its own types before timing; a timed
//! iteration runs the query on every case, each input and answer through
//! `black_box` (the answer by reference: see `shared/criterion.rs`). At the end a table of ns per query with the ratios is printed
//! and written to `target/criterion/crashtest-toi-table.md`; the target is
//! closed-form sphere–sphere toi at most a quarter of parry3d-f64's
//! `cast_shapes`.

#[path = "shared/criterion.rs"]
mod criterion_files;
use criterion_files::{PAIRING, Pairs, run};
#[path = "shared/families.rs"]
mod families;
use families::{FamilyTable, NO_FAMILY, by_family, family_counts, family_table};
#[path = "toi/table.rs"]
mod table;
#[path = "toi/textbook.rs"]
mod textbook;

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput};
use harness::case::{Query, Shape};
use harness::generate::{family_for, generate};
use oracle::geom::{self, P3};
use oracle::parry::{Parry32, Parry64, ParryCast};
use std::time::{Duration, SystemTime};
use table::{Row, Target};

/// Seed of the cases (fixed: every run times the same cases).
const SEED: u64 = 0x0070_1CA5;
/// Cases per pair: enough to mix every family several times and to defeat the
/// branch predictor's memory of a short loop; few enough to stay in L2.
const PER_PAIR: usize = 1024;
/// Generator indices tried before giving up on filling [`PER_PAIR`] (each pair
/// is about a quarter of the mix).
const MAX_INDICES: u64 = 100_000;

/// Warm-up per benchmark.
const WARM_UP: Duration = Duration::from_millis(300);
/// Measurement per benchmark.
const MEASUREMENT: Duration = Duration::from_millis(1000);
/// Samples per benchmark (criterion's minimum is 10).
const SAMPLES: usize = 20;
/// Bootstrap resamples (criterion's default, 100 000, costs more than the
/// measurement).
const RESAMPLES: usize = 10_000;

/// The halving's bracket: 1e-12 (units of time).
const HALVING_TOLERANCE: f64 = 1e-12;

/// One case: `a` moving at `va` against `b` moving at `vb` over `[0, t_max]`.
#[derive(Clone, Copy, Debug)]
struct Case<B> {
    a: geom::Sphere,
    va: P3,
    b: B,
    vb: P3,
    t_max: f64,
}

/// The cases of every pair.
struct Cases {
    sphere_sphere: Vec<Case<geom::Sphere>>,
    sphere_plane: Vec<Case<geom::Plane>>,
    sphere_triangle: Vec<Case<geom::Triangle>>,
    /// The campaign family of each sphere–sphere case, in order.
    sphere_sphere_families: Vec<&'static str>,
    /// The campaign family of each sphere–plane case, in order.
    sphere_plane_families: Vec<&'static str>,
}

fn draw() -> Cases {
    let mut c = Cases {
        sphere_sphere: Vec::new(),
        sphere_plane: Vec::new(),
        sphere_triangle: Vec::new(),
        sphere_sphere_families: Vec::new(),
        sphere_plane_families: Vec::new(),
    };
    for i in 0..MAX_INDICES {
        if c.sphere_sphere.len() >= PER_PAIR && c.sphere_plane.len() >= PER_PAIR && c.sphere_triangle.len() >= PER_PAIR
        {
            break;
        }
        let lc = generate(Query::Toi, SEED, i);
        let case = &lc.case;
        let Shape::Sphere(a) = &case.a else { continue };
        let (a, va, t_max) = (a.to_geom(), case.a.velocity(), case.t_max());
        let Some(bs) = case.b.as_ref() else { continue };
        let vb = bs.velocity();
        let family = family_for(Query::Toi, i).unwrap_or(NO_FAMILY);
        match bs {
            Shape::Sphere(b) if c.sphere_sphere.len() < PER_PAIR => {
                c.sphere_sphere.push(Case { a, va, b: b.to_geom(), vb, t_max });
                c.sphere_sphere_families.push(family);
            }
            Shape::Plane(b) if c.sphere_plane.len() < PER_PAIR => {
                c.sphere_plane.push(Case { a, va, b: b.to_geom(), vb, t_max });
                c.sphere_plane_families.push(family);
            }
            Shape::Triangle(b) if c.sphere_triangle.len() < PER_PAIR => {
                c.sphere_triangle.push(Case { a, va, b: b.to_geom(), vb, t_max })
            }
            _ => {}
        }
    }
    c
}

/// collide's inputs in precision `T`.
mod to_collide {
    use collide::Real;
    use oracle::geom::{self, P3};

    pub fn v<T: Real>(p: P3) -> collide::Vec3<T> {
        collide::Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]))
    }
    pub fn sphere<T: Real>(s: &geom::Sphere) -> collide::Sphere<T> {
        collide::Sphere::new(v(s.center), T::of(s.radius))
    }
    pub fn plane<T: Real>(p: &geom::Plane) -> collide::Plane<T> {
        collide::Plane::new(v(p.normal), T::of(p.offset))
    }
    pub fn triangle<T: Real>(t: &geom::Triangle) -> collide::Triangle<T> {
        collide::Triangle::new(v(t.vertices[0]), v(t.vertices[1]), v(t.vertices[2]))
    }
    /// `t_max` as the harness's adapter reads it (beyond the type's range: its
    /// largest value).
    pub fn time<T: Real>(t: f64) -> T {
        let x = T::of(t);
        if t.is_finite() && !x.finite() { T::max_value().unwrap_or(x) } else { x }
    }
}

/// A case in collide's types.
#[derive(Clone, Copy)]
struct C<T: collide::Real, B> {
    a: collide::Sphere<T>,
    va: collide::Vec3<T>,
    b: B,
    vb: collide::Vec3<T>,
    t_max: T,
}

fn to_c<T: collide::Real, G, B>(cases: &[Case<G>], f: impl Fn(&G) -> B) -> Vec<C<T, B>> {
    cases
        .iter()
        .map(|c| C {
            a: to_collide::sphere(&c.a),
            va: to_collide::v(c.va),
            b: f(&c.b),
            vb: to_collide::v(c.vb),
            t_max: to_collide::time(c.t_max),
        })
        .collect()
}

/// parry called directly, written once for both precisions.
macro_rules! parry_cast {
    ($name:ident, $krate:ident) => {
        mod $name {
            use oracle::geom::{self, P3};
            use $krate::math::{Pose, Real, Vector};
            use $krate::query::{self, ShapeCastHit, ShapeCastOptions};
            use $krate::shape::{Ball, HalfSpace, Shape, Triangle};

            /// A vector in parry's scalar (rounded once for `f32`).
            pub fn v(p: P3) -> Vector {
                Vector::new(p[0] as Real, p[1] as Real, p[2] as Real)
            }
            /// A ball at its centre.
            pub fn ball(s: &geom::Sphere) -> (Pose, Ball) {
                (Pose::from_translation(v(s.center)), Ball::new(s.radius as Real))
            }
            /// A plane as the oracle places it (unit normal, anchored at
            /// `(d/‖n‖) n̂`).
            pub fn half_space(p: &geom::Plane) -> (Pose, HalfSpace) {
                let n = v(p.normal);
                let unit = n.normalize();
                (Pose::from_translation(unit * (p.offset as Real / n.length())), HalfSpace::new(unit))
            }
            /// A triangle at the identity pose.
            pub fn triangle(t: &geom::Triangle) -> (Pose, Triangle) {
                let [a, b, c] = t.vertices;
                (Pose::IDENTITY, Triangle::new(v(a), v(b), v(c)))
            }
            /// The oracle's options: stop at a touch, at `t_max` inclusive
            /// (beyond the scalar's range: parry's "no limit"), `t = 0` for
            /// shapes already in contact, with their geometry.
            pub fn options(t_max: f64) -> ShapeCastOptions {
                let t = t_max as Real;
                ShapeCastOptions {
                    max_time_of_impact: if t.is_finite() { t.max(0.0) } else { Real::MAX },
                    target_distance: 0.0,
                    stop_at_penetration: true,
                    compute_impact_geometry_on_penetration: true,
                }
            }
            /// One cast.
            #[inline]
            pub fn cast<S: Shape>(
                a: &(Pose, Ball),
                va: Vector,
                b: &(Pose, S),
                vb: Vector,
                o: ShapeCastOptions,
            ) -> Option<ShapeCastHit> {
                query::cast_shapes(&a.0, va, &a.1, &b.0, vb, &b.1, o).ok().flatten()
            }
        }
    };
}

parry_cast!(p64, parry3d_f64);
parry_cast!(p32, parry3d);

fn group<'a>(c: &'a mut Criterion, name: &str, n: usize) -> BenchmarkGroup<'a, WallTime> {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(n as u64));
    g
}

/// The parry direct and adapter benchmarks of one pair: `place64` and
/// `place32` build `b` in parry's types, `adapter` is the oracle's call. The
/// `f64` inputs in parry's types are returned, for the paired ratios.
macro_rules! parry_benches {
    ($g:expr, $cases:expr, $place64:path, $place32:path, $adapter:ident) => {{
        let d64: Vec<_> = $cases
            .iter()
            .map(|c| (p64::ball(&c.a), p64::v(c.va), $place64(&c.b), p64::v(c.vb), p64::options(c.t_max)))
            .collect();
        let d32: Vec<_> = $cases
            .iter()
            .map(|c| (p32::ball(&c.a), p32::v(c.va), $place32(&c.b), p32::v(c.vb), p32::options(c.t_max)))
            .collect();
        run($g, "parry64", &d64, |(a, va, b, vb, o)| p64::cast(a, *va, b, *vb, *o));
        run($g, "parry32", &d32, |(a, va, b, vb, o)| p32::cast(a, *va, b, *vb, *o));
        run($g, "parry64_adapter", $cases, |c| Parry64.$adapter(c.a, c.va, c.b, c.vb, c.t_max));
        run($g, "parry32_adapter", $cases, |c| Parry32.$adapter(c.a, c.va, c.b, c.vb, c.t_max));
        d64
    }};
}

/// The target's pair of a group (see [`targets`]), measured paired.
const TARGET_PAIR: [(&str, &str); 1] = [("collide_robust_f64", "parry64")];

fn sphere_sphere(c: &mut Criterion, cases: &[Case<geom::Sphere>], families: &[&'static str]) {
    use collide::toi::{Halving, toi_sphere_sphere, toi_sphere_sphere_halving};
    let mut g = group(c, "toi_sphere_sphere", cases.len());
    let c64 = to_c::<f64, _, _>(cases, to_collide::sphere::<f64>);
    let c32 = to_c::<f32, _, _>(cases, to_collide::sphere::<f32>);
    run(&mut g, "collide_robust_f64", &c64, |c| toi_sphere_sphere(&c.a, &c.va, &c.b, &c.vb, c.t_max));
    run(&mut g, "collide_robust_f32", &c32, |c| toi_sphere_sphere(&c.a, &c.va, &c.b, &c.vb, c.t_max));
    run(&mut g, "textbook_f64", &c64, |c| textbook::toi_sphere_sphere(&c.a, &c.va, &c.b, &c.vb, c.t_max));
    let stop = Halving::Tolerance(HALVING_TOLERANCE);
    run(&mut g, "collide_halving_f64", &c64, |c| toi_sphere_sphere_halving(&c.a, &c.va, &c.b, &c.vb, c.t_max, stop));
    let d64 = parry_benches!(&mut g, cases, p64::ball, p32::ball, cast_sphere_sphere);
    g.finish();
    let mut pairs = Pairs::new("toi_sphere_sphere");
    pairs.keep("collide_robust_f64", &c64, |c| toi_sphere_sphere(&c.a, &c.va, &c.b, &c.vb, c.t_max));
    pairs.keep("parry64", &d64, |(a, va, b, vb, o)| p64::cast(a, *va, b, *vb, *o));
    pairs.measure(&TARGET_PAIR);
    by_family(
        "toi_sphere_sphere",
        families,
        (&c64, |c| toi_sphere_sphere(&c.a, &c.va, &c.b, &c.vb, c.t_max)),
        (&d64, |(a, va, b, vb, o)| p64::cast(a, *va, b, *vb, *o)),
    );
}

fn sphere_plane(c: &mut Criterion, cases: &[Case<geom::Plane>], families: &[&'static str]) {
    use collide::toi::{Halving, toi_sphere_plane, toi_sphere_plane_halving};
    let mut g = group(c, "toi_sphere_plane", cases.len());
    let c64 = to_c::<f64, _, _>(cases, to_collide::plane::<f64>);
    let c32 = to_c::<f32, _, _>(cases, to_collide::plane::<f32>);
    run(&mut g, "collide_robust_f64", &c64, |c| toi_sphere_plane(&c.a, &c.va, &c.b, &c.vb, c.t_max));
    run(&mut g, "collide_robust_f32", &c32, |c| toi_sphere_plane(&c.a, &c.va, &c.b, &c.vb, c.t_max));
    let stop = Halving::Tolerance(HALVING_TOLERANCE);
    run(&mut g, "collide_halving_f64", &c64, |c| toi_sphere_plane_halving(&c.a, &c.va, &c.b, &c.vb, c.t_max, stop));
    let d64 = parry_benches!(&mut g, cases, p64::half_space, p32::half_space, cast_sphere_plane);
    g.finish();
    let mut pairs = Pairs::new("toi_sphere_plane");
    pairs.keep("collide_robust_f64", &c64, |c| toi_sphere_plane(&c.a, &c.va, &c.b, &c.vb, c.t_max));
    pairs.keep("parry64", &d64, |(a, va, b, vb, o)| p64::cast(a, *va, b, *vb, *o));
    pairs.measure(&TARGET_PAIR);
    by_family(
        "toi_sphere_plane",
        families,
        (&c64, |c| toi_sphere_plane(&c.a, &c.va, &c.b, &c.vb, c.t_max)),
        (&d64, |(a, va, b, vb, o)| p64::cast(a, *va, b, *vb, *o)),
    );
}

fn sphere_triangle(c: &mut Criterion, cases: &[Case<geom::Triangle>]) {
    use collide::toi::{Advancement, Halving, toi_sphere_triangle, toi_sphere_triangle_halving};
    let mut g = group(c, "toi_sphere_triangle", cases.len());
    let c64 = to_c::<f64, _, _>(cases, to_collide::triangle::<f64>);
    let c32 = to_c::<f32, _, _>(cases, to_collide::triangle::<f32>);
    let rule = Advancement::default();
    run(&mut g, "collide_robust_f64", &c64, |c| toi_sphere_triangle(&c.a, &c.va, &c.b, &c.vb, c.t_max, &rule));
    run(&mut g, "collide_robust_f32", &c32, |c| toi_sphere_triangle(&c.a, &c.va, &c.b, &c.vb, c.t_max, &rule));
    let stop = Halving::Tolerance(HALVING_TOLERANCE);
    run(&mut g, "collide_halving_f64", &c64, |c| toi_sphere_triangle_halving(&c.a, &c.va, &c.b, &c.vb, c.t_max, stop));
    parry_benches!(&mut g, cases, p64::triangle, p32::triangle, cast_sphere_triangle);
    g.finish();
}

/// Fraction of the cases collide's robust `f64` method finds an impact in.
fn hits<B>(cases: &[Case<B>], f: impl Fn(&Case<B>) -> bool) -> f64 {
    cases.iter().filter(|c| f(c)).count() as f64 / cases.len().max(1) as f64
}

fn rows(c: &Cases) -> Vec<Row> {
    use collide::toi::{Advancement, toi_sphere_plane, toi_sphere_sphere, toi_sphere_triangle};
    let v = to_collide::v::<f64>;
    let s = to_collide::sphere::<f64>;
    vec![
        Row {
            group: "toi_sphere_sphere",
            label: "sphere–sphere",
            robust: "closed form",
            per_iter: c.sphere_sphere.len(),
            hits: hits(&c.sphere_sphere, |x| {
                toi_sphere_sphere(&s(&x.a), &v(x.va), &s(&x.b), &v(x.vb), x.t_max).is_some()
            }),
        },
        Row {
            group: "toi_sphere_plane",
            label: "sphere–plane",
            robust: "closed form",
            per_iter: c.sphere_plane.len(),
            hits: hits(&c.sphere_plane, |x| {
                toi_sphere_plane(&s(&x.a), &v(x.va), &to_collide::plane(&x.b), &v(x.vb), x.t_max).is_some()
            }),
        },
        Row {
            group: "toi_sphere_triangle",
            label: "sphere–triangle",
            robust: "conservative advancement",
            per_iter: c.sphere_triangle.len(),
            hits: hits(&c.sphere_triangle, |x| {
                let b = to_collide::triangle(&x.b);
                toi_sphere_triangle(&s(&x.a), &v(x.va), &b, &v(x.vb), x.t_max, &Advancement::default()).is_some()
            }),
        },
    ]
}

fn targets() -> Vec<Target> {
    vec![
        Target {
            group: "toi_sphere_sphere",
            what: "sphere–sphere: closed form f64 / parry3d-f64 cast_shapes",
            ids: ("collide_robust_f64", "parry64"),
            target: 0.25,
        },
        Target {
            group: "toi_sphere_plane",
            what: "sphere–plane: closed form f64 / parry3d-f64 cast_shapes",
            ids: ("collide_robust_f64", "parry64"),
            target: 0.25,
        },
    ]
}

/// How far the textbook reference's answers are from collide's on the
/// sphere–sphere cases (so its column times the same work): cases where one
/// finds an impact and the other not, and the largest difference in `t`
/// relative to `max(t, 1)` where both do.
fn textbook_agreement(cases: &[Case<geom::Sphere>]) -> String {
    use collide::toi::toi_sphere_sphere;
    let (mut differ, mut worst) = (0usize, 0.0f64);
    for x in cases {
        let (a, b) = (to_collide::sphere::<f64>(&x.a), to_collide::sphere::<f64>(&x.b));
        let (va, vb) = (to_collide::v::<f64>(x.va), to_collide::v::<f64>(x.vb));
        match (toi_sphere_sphere(&a, &va, &b, &vb, x.t_max), textbook::toi_sphere_sphere(&a, &va, &b, &vb, x.t_max)) {
            (Some(r), Some(t)) => worst = worst.max((r.t - t.t).abs() / r.t.abs().max(1.0)),
            (None, None) => {}
            _ => differ += 1,
        }
    }
    format!(
        "\nThe textbook reference against collide's closed form on the {} sphere–sphere cases: {differ} \
         differ in whether there is an impact; where both find one, `t` differs by at most {worst:.1e} of \
         max(t, 1).\n",
        cases.len()
    )
}

fn main() {
    let since = SystemTime::now();
    // `cargo bench` passes `--bench`; `cargo test --benches` does not, and then
    // criterion runs each benchmark once as a test: no table.
    let benching = std::env::args().any(|a| a == "--bench");
    PAIRING.store(benching, std::sync::atomic::Ordering::Relaxed);
    let cases = draw();
    let mut c = Criterion::default()
        .output_directory(&table::criterion_dir())
        .warm_up_time(WARM_UP)
        .measurement_time(MEASUREMENT)
        .sample_size(SAMPLES)
        .nresamples(RESAMPLES)
        .configure_from_args();
    sphere_sphere(&mut c, &cases.sphere_sphere, &cases.sphere_sphere_families);
    sphere_plane(&mut c, &cases.sphere_plane, &cases.sphere_plane_families);
    sphere_triangle(&mut c, &cases.sphere_triangle);
    c.final_summary();
    if benching {
        let mut report = table::render(&rows(&cases), &targets(), SEED, since);
        report.push_str(&textbook_agreement(&cases.sphere_sphere));
        let families = [
            FamilyTable {
                label: "sphere–sphere",
                group: "toi_sphere_sphere",
                families: family_counts(&cases.sphere_sphere_families),
            },
            FamilyTable {
                label: "sphere–plane",
                group: "toi_sphere_plane",
                families: family_counts(&cases.sphere_plane_families),
            },
        ];
        report.push_str(&family_table(
            &families,
            "The cases above are the campaign's toi mix: hits, misses, grazing passes, shapes already in contact, \
             tunneling. Here each family's cases are timed alone, collide's closed form f64 against parry3d-f64's \
             `cast_shapes`, paired as the targets are, to show where the time goes.",
            ("closed form f64", "parry3d-f64"),
        ));
        table::publish(&report);
    }
}
