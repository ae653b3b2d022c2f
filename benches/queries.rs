//! collide against parry, every query, one run: `cargo bench --bench queries`.
//!
//! For each query kind, each of collide's methods (the lecture's and the
//! robust one) in `f64` and `f32`, and parry3d-f64 and parry3d (`f32`), run on
//! the same cases: [`cases::PER_QUERY`] per query, drawn once from a fixed
//! seed by the campaign's own generators (`harness::generate`), so hits,
//! misses, touching and near-degenerate cases come in the campaign's
//! proportions. Every engine's inputs are converted to its own types before
//! timing; a timed iteration runs the query on every case, each input and
//! answer passed through `black_box` (the answer by reference, where the
//! query left it: see `shared/criterion.rs`) so that nothing is hoisted or
//! dropped.
//!
//! parry is timed twice: directly (its own calls on inputs already in its
//! types — see `parry_direct.rs`), which the ratios use, and through
//! `oracle::parry::ParryEngine`, whose conversions happen inside each call.
//! For the three contact queries, whose direct call is parry's generic
//! `query::contact` (a dynamic dispatch on the shapes' types before the pair
//! function), parry's pair function is timed too (`parry64_like`): collide's
//! functions are pair functions, so that column is the like-for-like one,
//! and the table gives the ratios against it beside the targets. For
//! segment–plane the like-for-like call is parry's ray cast answering what
//! collide's answer holds: the parameter, the hit point and the normal (the
//! direct call keeps only the parameter).
//!
//! At the end of the run a table is printed and written to
//! `target/criterion/crashtest-table.md`: ns per query per engine, the ratios
//! the speed targets are stated in, and a lower bound from each query's
//! hand-counted arithmetic (`cost.rs`) at this machine's measured peak
//! (`peak.rs`). Criterion is configured short (about 1.5 s per benchmark) so
//! that the whole run stays within a few minutes.

#[path = "queries/cases.rs"]
mod cases;
#[path = "queries/cost.rs"]
mod cost;
#[path = "shared/criterion.rs"]
mod criterion_files;
use criterion_files::{PAIRING, Pairs, run};
#[path = "shared/families.rs"]
mod families;
use families::{FamilyTable, by_family, family_counts};
#[path = "queries/parry_direct.rs"]
mod parry_direct;
#[path = "queries/peak.rs"]
mod peak;
#[path = "queries/table.rs"]
mod table;

use cases::{Cases, PER_QUERY, to_collide};
use collide::Vec3;
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput};
use oracle::geom;
use oracle::parry::{Parry32, Parry64, ParryEngine};
use parry_direct::{p32, p64};
use std::hint::black_box;
use std::time::{Duration, SystemTime};
use table::{BatchRow, Row, Target};

/// Warm-up per benchmark: long enough for criterion to size its iterations
/// (each iteration runs all the cases, 1–300 µs).
const WARM_UP: Duration = Duration::from_millis(300);
/// Measurement per benchmark: with [`SAMPLES`] samples of many iterations each,
/// the slope's confidence interval is within a few percent on a quiet machine.
const MEASUREMENT: Duration = Duration::from_millis(1000);
/// Samples per benchmark (criterion's minimum is 10).
const SAMPLES: usize = 20;
/// Bootstrap resamples of criterion's analysis (its default, 100 000, costs
/// more time than the measurement here).
const RESAMPLES: usize = 10_000;

fn group<'a>(c: &'a mut Criterion, name: &str, n: usize) -> BenchmarkGroup<'a, WallTime> {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(n as u64));
    g
}

/// Pairs converted with one function per side.
fn conv<A, B, X, Y>(pairs: &[(A, B)], fa: impl Fn(&A) -> X, fb: impl Fn(&B) -> Y) -> Vec<(X, Y)> {
    pairs.iter().map(|(a, b)| (fa(a), fb(b))).collect()
}

fn sphere_sphere(c: &mut Criterion, cases: &[(geom::Sphere, geom::Sphere)]) {
    use collide::contact::{contact_sphere_sphere, contact_sphere_sphere_lecture};
    let mut g = group(c, "sphere_sphere", cases.len());
    let c64 = conv(cases, to_collide::sphere::<f64>, to_collide::sphere::<f64>);
    let c32 = conv(cases, to_collide::sphere::<f32>, to_collide::sphere::<f32>);
    run(&mut g, "collide_lecture_f64", &c64, |(a, b)| contact_sphere_sphere_lecture(a, b));
    run(&mut g, "collide_robust_f64", &c64, |(a, b)| contact_sphere_sphere(a, b));
    run(&mut g, "collide_lecture_f32", &c32, |(a, b)| contact_sphere_sphere_lecture(a, b));
    run(&mut g, "collide_robust_f32", &c32, |(a, b)| contact_sphere_sphere(a, b));
    let d64 = conv(cases, p64::ball, p64::ball);
    let d32 = conv(cases, p32::ball, p32::ball);
    run(&mut g, "parry64", &d64, |(a, b)| p64::contact_sphere_sphere(a, b));
    run(&mut g, "parry64_like", &d64, |(a, b)| p64::contact_sphere_sphere_pair(a, b));
    run(&mut g, "parry32", &d32, |(a, b)| p32::contact_sphere_sphere(a, b));
    run(&mut g, "parry64_adapter", cases, |(a, b)| Parry64.contact_sphere_sphere(*a, *b));
    run(&mut g, "parry32_adapter", cases, |(a, b)| Parry32.contact_sphere_sphere(*a, *b));
    g.finish();
    let mut pairs = Pairs::new("sphere_sphere");
    pairs.keep("collide_robust_f64", &c64, |(a, b)| contact_sphere_sphere(a, b));
    pairs.keep("parry64", &d64, |(a, b)| p64::contact_sphere_sphere(a, b));
    pairs.keep("parry64_like", &d64, |(a, b)| p64::contact_sphere_sphere_pair(a, b));
    pairs.measure(&target_pairs("sphere_sphere"));
}

fn sphere_plane(c: &mut Criterion, cases: &[(geom::Sphere, geom::Plane)]) {
    use collide::contact::contact_sphere_plane;
    let mut g = group(c, "sphere_plane", cases.len());
    let c64 = conv(cases, to_collide::sphere::<f64>, to_collide::plane::<f64>);
    let c32 = conv(cases, to_collide::sphere::<f32>, to_collide::plane::<f32>);
    run(&mut g, "collide_robust_f64", &c64, |(a, b)| contact_sphere_plane(a, b));
    run(&mut g, "collide_robust_f32", &c32, |(a, b)| contact_sphere_plane(a, b));
    let d64 = conv(cases, p64::ball, p64::half_space);
    let d32 = conv(cases, p32::ball, p32::half_space);
    run(&mut g, "parry64", &d64, |(a, b)| p64::contact_sphere_plane(a, b));
    run(&mut g, "parry64_like", &d64, |(a, b)| p64::contact_sphere_plane_pair(a, b));
    run(&mut g, "parry32", &d32, |(a, b)| p32::contact_sphere_plane(a, b));
    run(&mut g, "parry64_adapter", cases, |(a, b)| Parry64.contact_sphere_plane(*a, *b));
    run(&mut g, "parry32_adapter", cases, |(a, b)| Parry32.contact_sphere_plane(*a, *b));
    g.finish();
    let mut pairs = Pairs::new("sphere_plane");
    pairs.keep("collide_robust_f64", &c64, |(a, b)| contact_sphere_plane(a, b));
    pairs.keep("parry64", &d64, |(a, b)| p64::contact_sphere_plane(a, b));
    pairs.keep("parry64_like", &d64, |(a, b)| p64::contact_sphere_plane_pair(a, b));
    pairs.measure(&target_pairs("sphere_plane"));
}

fn sphere_triangle(c: &mut Criterion, cases: &[(geom::Sphere, geom::Triangle)], families: &[&'static str]) {
    use collide::contact::contact_sphere_triangle;
    let mut g = group(c, "sphere_triangle", cases.len());
    let c64 = conv(cases, to_collide::sphere::<f64>, to_collide::triangle::<f64>);
    let c32 = conv(cases, to_collide::sphere::<f32>, to_collide::triangle::<f32>);
    run(&mut g, "collide_robust_f64", &c64, |(a, b)| contact_sphere_triangle(a, b));
    run(&mut g, "collide_robust_f32", &c32, |(a, b)| contact_sphere_triangle(a, b));
    let d64 = conv(cases, p64::ball, p64::triangle);
    let d32 = conv(cases, p32::ball, p32::triangle);
    run(&mut g, "parry64", &d64, |(a, b)| p64::contact_sphere_triangle(a, b));
    run(&mut g, "parry64_like", &d64, |(a, b)| p64::contact_sphere_triangle_pair(a, b));
    run(&mut g, "parry32", &d32, |(a, b)| p32::contact_sphere_triangle(a, b));
    run(&mut g, "parry64_adapter", cases, |(a, b)| Parry64.contact_sphere_triangle(*a, *b));
    run(&mut g, "parry32_adapter", cases, |(a, b)| Parry32.contact_sphere_triangle(*a, *b));
    g.finish();
    let mut pairs = Pairs::new("sphere_triangle");
    pairs.keep("collide_robust_f64", &c64, |(a, b)| contact_sphere_triangle(a, b));
    pairs.keep("parry64", &d64, |(a, b)| p64::contact_sphere_triangle(a, b));
    pairs.keep("parry64_like", &d64, |(a, b)| p64::contact_sphere_triangle_pair(a, b));
    pairs.measure(&target_pairs("sphere_triangle"));
    by_family(
        "sphere_triangle",
        families,
        (&c64, |(a, b)| contact_sphere_triangle(a, b)),
        (&d64, |(a, b)| p64::contact_sphere_triangle(a, b)),
    );
}

fn segment_plane(c: &mut Criterion, cases: &[(geom::Segment, geom::Plane)], families: &[&'static str]) {
    use collide::intersect::{intersect_segment_plane, intersect_segment_plane_lecture};
    let mut g = group(c, "segment_plane", cases.len());
    let c64 = conv(cases, to_collide::segment::<f64>, to_collide::plane::<f64>);
    let c32 = conv(cases, to_collide::segment::<f32>, to_collide::plane::<f32>);
    run(&mut g, "collide_lecture_f64", &c64, |(s, p)| intersect_segment_plane_lecture(s, p));
    run(&mut g, "collide_robust_f64", &c64, |(s, p)| intersect_segment_plane(s, p));
    run(&mut g, "collide_lecture_f32", &c32, |(s, p)| intersect_segment_plane_lecture(s, p));
    run(&mut g, "collide_robust_f32", &c32, |(s, p)| intersect_segment_plane(s, p));
    let d64 = conv(cases, p64::ray, p64::half_space);
    let d32 = conv(cases, p32::ray, p32::half_space);
    run(&mut g, "parry64", &d64, |(r, p)| p64::intersect_segment_plane(r, p));
    run(&mut g, "parry64_like", &d64, |(r, p)| p64::intersect_segment_plane_like(r, p));
    run(&mut g, "parry32", &d32, |(r, p)| p32::intersect_segment_plane(r, p));
    run(&mut g, "parry64_adapter", cases, |(s, p)| Parry64.intersect_segment_plane(*s, *p));
    run(&mut g, "parry32_adapter", cases, |(s, p)| Parry32.intersect_segment_plane(*s, *p));
    g.finish();
    let mut pairs = Pairs::new("segment_plane");
    pairs.keep("collide_robust_f64", &c64, |(s, p)| intersect_segment_plane(s, p));
    pairs.keep("parry64", &d64, |(r, p)| p64::intersect_segment_plane(r, p));
    pairs.keep("parry64_like", &d64, |(r, p)| p64::intersect_segment_plane_like(r, p));
    pairs.measure(&target_pairs("segment_plane"));
    by_family(
        "segment_plane",
        families,
        (&c64, |(s, p)| intersect_segment_plane(s, p)),
        (&d64, |(r, p)| p64::intersect_segment_plane(r, p)),
    );
}

/// Segment–triangle over `cases`, as group `name`; with the parry adapters
/// and the by-family ratios when `families` is given (the campaign mix).
fn segment_triangle(
    c: &mut Criterion,
    name: &'static str,
    cases: &[(geom::Segment, geom::Triangle)],
    families: Option<&[&'static str]>,
) {
    use collide::intersect::{intersect_segment_triangle, intersect_segment_triangle_lecture};
    let mut g = group(c, name, cases.len());
    let c64 = conv(cases, to_collide::segment::<f64>, to_collide::triangle::<f64>);
    let c32 = conv(cases, to_collide::segment::<f32>, to_collide::triangle::<f32>);
    run(&mut g, "collide_lecture_f64", &c64, |(s, t)| intersect_segment_triangle_lecture(s, t));
    run(&mut g, "collide_robust_f64", &c64, |(s, t)| intersect_segment_triangle(s, t));
    run(&mut g, "collide_lecture_f32", &c32, |(s, t)| intersect_segment_triangle_lecture(s, t));
    run(&mut g, "collide_robust_f32", &c32, |(s, t)| intersect_segment_triangle(s, t));
    let d64 = conv(cases, p64::ray, p64::triangle);
    let d32 = conv(cases, p32::ray, p32::triangle);
    run(&mut g, "parry64", &d64, |(r, t)| p64::intersect_segment_triangle(r, t));
    run(&mut g, "parry32", &d32, |(r, t)| p32::intersect_segment_triangle(r, t));
    if families.is_some() {
        run(&mut g, "parry64_adapter", cases, |(s, t)| Parry64.intersect_segment_triangle(*s, *t));
        run(&mut g, "parry32_adapter", cases, |(s, t)| Parry32.intersect_segment_triangle(*s, *t));
    }
    g.finish();
    let mut pairs = Pairs::new(name);
    pairs.keep("collide_robust_f64", &c64, |(s, t)| intersect_segment_triangle(s, t));
    pairs.keep("collide_lecture_f64", &c64, |(s, t)| intersect_segment_triangle_lecture(s, t));
    pairs.keep("parry64", &d64, |(r, t)| p64::intersect_segment_triangle(r, t));
    pairs.measure(&target_pairs(name));
    if let Some(families) = families {
        by_family(
            name,
            families,
            (&c64, |(s, t)| intersect_segment_triangle(s, t)),
            (&d64, |(r, t)| p64::intersect_segment_triangle(r, t)),
        );
    }
}

fn barycentric(c: &mut Criterion, cases: &[(geom::P3, geom::Triangle)], families: &[&'static str]) {
    use collide::barycentric::{barycentric_triangle, barycentric_triangle_lecture};
    let mut g = group(c, "barycentric", cases.len());
    let c64 = conv(cases, |p| to_collide::v::<f64>(*p), to_collide::triangle::<f64>);
    let c32 = conv(cases, |p| to_collide::v::<f32>(*p), to_collide::triangle::<f32>);
    run(&mut g, "collide_lecture_f64", &c64, |(p, t)| barycentric_triangle_lecture(p, t));
    run(&mut g, "collide_robust_f64", &c64, |(p, t)| barycentric_triangle(p, t));
    run(&mut g, "collide_lecture_f32", &c32, |(p, t)| barycentric_triangle_lecture(p, t));
    run(&mut g, "collide_robust_f32", &c32, |(p, t)| barycentric_triangle(p, t));
    let d64 = conv(cases, |p| p64::v(*p), p64::triangle);
    let d32 = conv(cases, |p| p32::v(*p), p32::triangle);
    run(&mut g, "parry64", &d64, |(p, t)| p64::barycentric(p, t));
    run(&mut g, "parry32", &d32, |(p, t)| p32::barycentric(p, t));
    run(&mut g, "parry64_adapter", cases, |(p, t)| Parry64.barycentric_triangle(*p, *t));
    run(&mut g, "parry32_adapter", cases, |(p, t)| Parry32.barycentric_triangle(*p, *t));
    g.finish();
    let mut pairs = Pairs::new("barycentric");
    pairs.keep("collide_robust_f64", &c64, |(p, t)| barycentric_triangle(p, t));
    pairs.keep("parry64", &d64, |(p, t)| p64::barycentric(p, t));
    pairs.measure(&target_pairs("barycentric"));
    by_family(
        "barycentric",
        families,
        (&c64, |(p, t)| barycentric_triangle(p, t)),
        (&d64, |(p, t)| p64::barycentric(p, t)),
    );
}

fn overlap(c: &mut Criterion, cases: &[(geom::Aabb, geom::Aabb)]) {
    use collide::bounds::test_aabb_aabb;
    let mut g = group(c, "overlap", cases.len());
    let c64 = conv(cases, to_collide::aabb::<f64>, to_collide::aabb::<f64>);
    let c32 = conv(cases, to_collide::aabb::<f32>, to_collide::aabb::<f32>);
    run(&mut g, "collide_robust_f64", &c64, |(a, b)| test_aabb_aabb(a, b));
    run(&mut g, "collide_robust_f32", &c32, |(a, b)| test_aabb_aabb(a, b));
    let d64 = conv(cases, p64::aabb, p64::aabb);
    let d32 = conv(cases, p32::aabb, p32::aabb);
    run(&mut g, "parry64", &d64, |(a, b)| p64::overlap(a, b));
    run(&mut g, "parry32", &d32, |(a, b)| p32::overlap(a, b));
    run(&mut g, "parry64_adapter", cases, |(a, b)| Parry64.overlap_aabb_aabb(*a, *b));
    run(&mut g, "parry32_adapter", cases, |(a, b)| Parry32.overlap_aabb_aabb(*a, *b));
    overlap_batch(&mut g, &c64, "f64");
    overlap_batch(&mut g, &c32, "f32");
    g.finish();
    let mut pairs = Pairs::new("overlap");
    pairs.keep("collide_robust_f64", &c64, |(a, b)| test_aabb_aabb(a, b));
    pairs.keep("parry64", &d64, |(a, b)| p64::overlap(a, b));
    pairs.keep("read_f64", &c64, |(a, b)| read_both(a, b));
    let [looped, batched] = overlap_passes(&c64);
    pairs.keep_pass("loop_f64", c64.len(), looped);
    pairs.keep_pass("batch_f64", c64.len(), batched);
    pairs.measure(&target_pairs("overlap"));
}

/// The floor of any box test in this loop: both boxes' twelve coordinates
/// read and folded by bitwise or, nothing compared (the read rate of
/// `peak.rs`, on the bench's own cases). A test that answers from fewer
/// loads (one axis's, when it separates) pays a branch for it.
#[inline(always)]
fn read_both(a: &collide::Aabb<f64>, b: &collide::Aabb<f64>) -> u64 {
    let bits = |v: &Vec3<f64>| v.x.to_bits() | v.y.to_bits() | v.z.to_bits();
    bits(&a.min) | bits(&a.max) | bits(&b.min) | bits(&b.max)
}

/// The one-at-a-time loop a user writes over `pairs`: each pair's `f`
/// stored into an array (owned by the pass), no `black_box` inside.
fn loop_pass<'a, P, O: Clone + 'a>(
    pairs: &'a [(P, P)],
    init: O,
    f: impl Fn(&P, &P) -> O + 'a,
) -> Box<dyn FnMut() + 'a> {
    let mut out = vec![init; pairs.len()];
    Box::new(move || {
        for (o, (x, y)) in out.iter_mut().zip(black_box(pairs)) {
            *o = f(x, y);
        }
        black_box(&mut out);
    })
}

/// One pass of the box loop and one of the box batch over `pairs`, each
/// owning its arrays and answers: criterion's benchmarks and the paired
/// ratios time the same closures.
fn overlap_passes<T: collide::Real>(pairs: &[(collide::Aabb<T>, collide::Aabb<T>)]) -> [Box<dyn FnMut() + '_>; 2] {
    use collide::batch::{Aabbs, test_aabbs_aabbs};
    use collide::bounds::test_aabb_aabb;
    let a: Aabbs<T> = pairs.iter().map(|p| &p.0).collect();
    let b: Aabbs<T> = pairs.iter().map(|p| &p.1).collect();
    let mut all = vec![false; pairs.len()];
    [
        loop_pass(pairs, false, test_aabb_aabb),
        Box::new(move || {
            test_aabbs_aabbs(black_box(&a), black_box(&b), &mut all);
            black_box(&mut all);
        }),
    ]
}

/// The box batch API against the one-at-a-time loop over the same pairs,
/// both writing their answers to an array (what a broad phase does): the
/// loop calls `test_aabb_aabb` per pair, the batch is `test_aabbs_aabbs` over
/// the pairs as arrays (see [`overlap_passes`]).
fn overlap_batch<T: collide::Real>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    pairs: &[(collide::Aabb<T>, collide::Aabb<T>)],
    p: &str,
) {
    let [mut looped, mut batched] = overlap_passes(pairs);
    g.bench_function(format!("loop_{p}"), |bn| bn.iter(&mut looped));
    g.bench_function(format!("batch_{p}"), |bn| bn.iter(&mut batched));
}

fn bounding_sphere(c: &mut Criterion, clouds: &[Vec<geom::P3>]) {
    use collide::bounds::{bounding_sphere_centroid, bounding_sphere_minimal, bounding_sphere_ritter};
    let mut g = group(c, "bounding_sphere", clouds.len());
    let cloud = |ps: &Vec<geom::P3>| -> Vec<Vec3<f64>> { ps.iter().map(|&p| to_collide::v(p)).collect() };
    let cloud32 = |ps: &Vec<geom::P3>| -> Vec<Vec3<f32>> { ps.iter().map(|&p| to_collide::v(p)).collect() };
    let c64: Vec<_> = clouds.iter().map(cloud).collect();
    let c32: Vec<_> = clouds.iter().map(cloud32).collect();
    run(&mut g, "collide_lecture_f64", &c64, |p| bounding_sphere_centroid(p));
    run(&mut g, "collide_robust_f64", &c64, |p| bounding_sphere_minimal(p));
    run(&mut g, "collide_ritter_f64", &c64, |p| bounding_sphere_ritter(p));
    run(&mut g, "collide_lecture_f32", &c32, |p| bounding_sphere_centroid(p));
    run(&mut g, "collide_robust_f32", &c32, |p| bounding_sphere_minimal(p));
    let d64: Vec<_> = clouds.iter().map(|p| p64::cloud(p)).collect();
    let d32: Vec<_> = clouds.iter().map(|p| p32::cloud(p)).collect();
    run(&mut g, "parry64", &d64, |p| p64::bounding_sphere(p));
    run(&mut g, "parry32", &d32, |p| p32::bounding_sphere(p));
    run(&mut g, "parry64_adapter", clouds, |p| Parry64.bounding_sphere_of_points(p));
    run(&mut g, "parry32_adapter", clouds, |p| Parry32.bounding_sphere_of_points(p));
    g.finish();
}

/// The batch API against the one-at-a-time loop over the same pairs (the
/// sphere–sphere cases): the loop is what a user writes — each pair's
/// `contact_sphere_sphere` stored into an array, no `black_box` inside — and
/// the batch is `contact_spheres_spheres` (and `test_spheres_spheres`) over
/// the same pairs as arrays.
fn sphere_sphere_batch(c: &mut Criterion, cases: &[(geom::Sphere, geom::Sphere)]) {
    let mut g = group(c, "sphere_sphere_batch", cases.len());
    batch_of::<f64>(&mut g, cases, "f64");
    batch_of::<f32>(&mut g, cases, "f32");
    g.finish();
    let c64 = conv(cases, to_collide::sphere::<f64>, to_collide::sphere::<f64>);
    let [looped, batched, _, _] = sphere_batch_passes(&c64);
    let mut pairs = Pairs::new("sphere_sphere_batch");
    pairs.keep_pass("loop_contact_f64", c64.len(), looped);
    pairs.keep_pass("batch_contact_f64", c64.len(), batched);
    pairs.measure(&target_pairs("sphere_sphere_batch"));
}

fn batch_of<T: collide::Real>(g: &mut BenchmarkGroup<'_, WallTime>, cases: &[(geom::Sphere, geom::Sphere)], p: &str) {
    let pairs = conv(cases, to_collide::sphere::<T>, to_collide::sphere::<T>);
    let passes = sphere_batch_passes(&pairs);
    for (name, mut pass) in ["loop_contact", "batch_contact", "loop_test", "batch_test"].into_iter().zip(passes) {
        g.bench_function(format!("{name}_{p}"), |bn| bn.iter(&mut pass));
    }
}

/// One pass over `pairs` of: the contact loop, the contact batch, the
/// overlap-test loop, the overlap-test batch — each owning its arrays and
/// answers (criterion's benchmarks and the paired ratios time the same
/// closures). The loops are what a user writes: each pair's
/// `contact_sphere_sphere` stored into an array, no `black_box` inside.
fn sphere_batch_passes<T: collide::Real>(
    pairs: &[(collide::Sphere<T>, collide::Sphere<T>)],
) -> [Box<dyn FnMut() + '_>; 4] {
    use collide::batch::{SphereContacts, Spheres, contact_spheres_spheres, test_spheres_spheres};
    use collide::contact::{Contact, contact_sphere_sphere};
    let a: Spheres<T> = pairs.iter().map(|p| &p.0).collect();
    let b: Spheres<T> = pairs.iter().map(|p| &p.1).collect();
    let (a2, b2) = (a.clone(), b.clone());
    let mut out = SphereContacts::new();
    let mut flags = vec![false; pairs.len()];
    [
        loop_pass(pairs, None::<Contact<T>>, contact_sphere_sphere),
        Box::new(move || {
            contact_spheres_spheres(black_box(&a), black_box(&b), &mut out);
            black_box(&mut out);
        }),
        loop_pass(pairs, false, |x, y| contact_sphere_sphere(x, y).is_some()),
        Box::new(move || {
            test_spheres_spheres(black_box(&a2), black_box(&b2), &mut flags);
            black_box(&mut flags);
        }),
    ]
}

fn batches(cases: &Cases) -> Vec<BatchRow> {
    use collide::contact::contact_sphere_sphere;
    use cost::{Cost, SPHERE_SPHERE_HIT, SPHERE_SPHERE_MISS};
    let c = |x: &geom::Sphere| to_collide::sphere::<f64>(x);
    let cost = Cost::mean(cases.sphere_sphere.iter().map(|(a, b)| {
        if contact_sphere_sphere(&c(a), &c(b)).is_some() { SPHERE_SPHERE_HIT } else { SPHERE_SPHERE_MISS }
    }));
    let row = |label, ids, cost| BatchRow { group: "sphere_sphere_batch", label, per_iter: PER_QUERY, ids, cost };
    vec![
        row(
            "sphere–sphere contact, f64",
            ("loop_contact_f64", "batch_contact_f64"),
            Some(cost.reading(input_bytes("sphere_sphere"))),
        ),
        row("sphere–sphere contact, f32", ("loop_contact_f32", "batch_contact_f32"), None),
        row("sphere–sphere overlap test, f64", ("loop_test_f64", "batch_test_f64"), None),
        row("sphere–sphere overlap test, f32", ("loop_test_f32", "batch_test_f32"), None),
        BatchRow {
            group: "overlap",
            label: "AABB overlap, f64",
            per_iter: PER_QUERY,
            ids: ("loop_f64", "batch_f64"),
            cost: Some(cost::AABB_OVERLAP.reading(input_bytes("overlap"))),
        },
        BatchRow {
            group: "overlap",
            label: "AABB overlap, f32",
            per_iter: PER_QUERY,
            ids: ("loop_f32", "batch_f32"),
            cost: None,
        },
    ]
}

/// Fraction of `xs` for which `f` holds.
fn fraction<X>(xs: &[X], f: impl Fn(&X) -> bool) -> f64 {
    xs.iter().filter(|x| f(x)).count() as f64 / xs.len() as f64
}

/// The rows of the main table, with each query's hit fraction and mean cost
/// over its cases (decided by collide's robust `f64` answer, which is exact in
/// its classification).
fn rows(cases: &Cases) -> Vec<Row> {
    use collide::contact::{contact_sphere_plane, contact_sphere_sphere};
    use collide::intersect::{intersect_segment_plane, intersect_segment_triangle};
    use cost::*;
    let c = |x: &geom::Sphere| to_collide::sphere::<f64>(x);
    let ss_hit = |(a, b): &(geom::Sphere, geom::Sphere)| contact_sphere_sphere(&c(a), &c(b)).is_some();
    let sp_hit = |(a, b): &(geom::Sphere, geom::Plane)| contact_sphere_plane(&c(a), &to_collide::plane(b)).is_some();
    let st_hit = |(a, b): &(geom::Sphere, geom::Triangle)| sphere_triangle(a, b).sqrt > 0.0;
    let sgp_hit = |(s, p): &(geom::Segment, geom::Plane)| {
        intersect_segment_plane(&to_collide::segment::<f64>(s), &to_collide::plane(p)).hit.is_some()
    };
    let seg_tri_cost = |(s, t): &(geom::Segment, geom::Triangle)| {
        let r = intersect_segment_triangle(&to_collide::segment::<f64>(s), &to_collide::triangle(t));
        if r.hit.is_some() {
            SEGMENT_TRIANGLE_HIT
        } else if plane_miss(s, t) {
            SEGMENT_TRIANGLE_PLANE_MISS
        } else {
            SEGMENT_TRIANGLE_EDGE_MISS
        }
    };
    let seg_tri_hit = |x: &(geom::Segment, geom::Triangle)| seg_tri_cost(x).sqrt > 0.0;
    let ov_hit = |(a, b): &(geom::Aabb, geom::Aabb)| {
        collide::bounds::test_aabb_aabb(&to_collide::aabb::<f64>(a), &to_collide::aabb(b))
    };
    let pick = |hit: bool, h: Cost, m: Cost| if hit { h } else { m };
    let row = |group, label, hits, cost: Cost, one_method| Row {
        group,
        label,
        per_iter: PER_QUERY,
        cost: Some(match input_bytes(group) {
            0 => cost,
            bytes => cost.reading(bytes),
        }),
        hits,
        one_method,
    };
    vec![
        row(
            "sphere_sphere",
            "sphere–sphere contact",
            Some(fraction(&cases.sphere_sphere, ss_hit)),
            Cost::mean(cases.sphere_sphere.iter().map(|x| pick(ss_hit(x), SPHERE_SPHERE_HIT, SPHERE_SPHERE_MISS))),
            false,
        ),
        row(
            "sphere_plane",
            "sphere–plane contact",
            Some(fraction(&cases.sphere_plane, sp_hit)),
            Cost::mean(cases.sphere_plane.iter().map(|x| pick(sp_hit(x), SPHERE_PLANE_HIT, SPHERE_PLANE_MISS))),
            true,
        ),
        row(
            "sphere_triangle",
            "sphere–triangle contact",
            Some(fraction(&cases.sphere_triangle, st_hit)),
            Cost::mean(cases.sphere_triangle.iter().map(|(a, b)| sphere_triangle(a, b))),
            true,
        ),
        row(
            "segment_plane",
            "segment–plane",
            Some(fraction(&cases.segment_plane, sgp_hit)),
            Cost::mean(cases.segment_plane.iter().map(|x| pick(sgp_hit(x), SEGMENT_PLANE_HIT, SEGMENT_PLANE_MISS))),
            false,
        ),
        row(
            "segment_triangle",
            "segment–triangle (campaign mix)",
            Some(fraction(&cases.segment_triangle, seg_tri_hit)),
            Cost::mean(cases.segment_triangle.iter().map(seg_tri_cost)),
            false,
        ),
        row(
            "segment_triangle_uniform",
            "segment–triangle (uniform random)",
            Some(fraction(&cases.segment_triangle_uniform, seg_tri_hit)),
            Cost::mean(cases.segment_triangle_uniform.iter().map(seg_tri_cost)),
            false,
        ),
        row("barycentric", "barycentric", None, BARYCENTRIC, false),
        row("overlap", "AABB overlap", Some(fraction(&cases.overlap, ov_hit)), AABB_OVERLAP, true),
        row(
            "bounding_sphere",
            "bounding sphere (lecture: centroid; robust: minimal)",
            None,
            Cost::mean(cases.clouds.iter().map(|ps| {
                let n = ps.len() as f64;
                Cost { ops: BOUNDING_SPHERE_PER_POINT.ops * n, ..BOUNDING_SPHERE_ONCE }
                    .reading(ps.len() * size_of::<collide::Vec3<f64>>())
            })),
            false,
        ),
    ]
}

/// Bytes of one query's `f64` input in collide's types, per group of the main
/// table (0 for the bounding sphere, whose input is the cloud: counted per
/// cloud with its cost).
fn input_bytes(group: &str) -> usize {
    use collide::{Aabb, Plane, Segment, Sphere, Triangle, Vec3};
    match group {
        "sphere_sphere" => 2 * size_of::<Sphere<f64>>(),
        "sphere_plane" => size_of::<(Sphere<f64>, Plane<f64>)>(),
        "sphere_triangle" => size_of::<(Sphere<f64>, Triangle<f64>)>(),
        "segment_plane" => size_of::<(Segment<f64>, Plane<f64>)>(),
        "segment_triangle" | "segment_triangle_uniform" => size_of::<(Segment<f64>, Triangle<f64>)>(),
        "barycentric" => size_of::<(Vec3<f64>, Triangle<f64>)>(),
        "overlap" => 2 * size_of::<Aabb<f64>>(),
        _ => 0,
    }
}

/// Whether both ends of the segment are strictly on one side of the
/// triangle's plane (the cheap miss), decided exactly.
fn plane_miss(s: &geom::Segment, t: &geom::Triangle) -> bool {
    let [a, b, c] = t.vertices;
    let s0 = collide::exact::orient3d(a, b, c, s.start);
    let s1 = collide::exact::orient3d(a, b, c, s.end);
    s0 == s1 && !s0.is_zero()
}

/// The numerator and denominator ids of `group`'s targets (see
/// [`targets`]), for its paired ratios.
fn target_pairs(group: &str) -> Vec<(&'static str, &'static str)> {
    let targets: Vec<Target> = targets().into_iter().filter(|t| t.group == group).collect();
    let floors = targets.iter().filter_map(|t| Some((t.floor?, t.ids.1)));
    targets.iter().map(|t| t.ids).chain(floors).collect()
}

fn targets() -> Vec<Target> {
    let half = |group, what| Target { group, what, ids: ("collide_robust_f64", "parry64"), target: 0.5, floor: None };
    vec![
        half("sphere_sphere", "sphere–sphere: robust f64 / parry3d-f64"),
        half("sphere_plane", "sphere–plane: robust f64 / parry3d-f64"),
        half("sphere_triangle", "sphere–triangle: robust f64 / parry3d-f64"),
        half("segment_plane", "segment–plane: robust f64 / parry3d-f64"),
        half("barycentric", "barycentric: robust f64 / parry3d-f64"),
        Target { floor: Some("read_f64"), ..half("overlap", "AABB overlap: robust f64 / parry3d-f64") },
        Target {
            group: "sphere_sphere",
            what: "(like for like) sphere–sphere: robust f64 / parry3d-f64 pair function",
            ids: ("collide_robust_f64", "parry64_like"),
            target: 0.5,
            floor: None,
        },
        Target {
            group: "sphere_plane",
            what: "(like for like) sphere–plane: robust f64 / parry3d-f64 pair function",
            ids: ("collide_robust_f64", "parry64_like"),
            target: 0.5,
            floor: None,
        },
        Target {
            group: "sphere_triangle",
            what: "(like for like) sphere–triangle: robust f64 / parry3d-f64 pair function",
            ids: ("collide_robust_f64", "parry64_like"),
            target: 0.5,
            floor: None,
        },
        Target {
            group: "segment_plane",
            what: "(like for like) segment–plane: robust f64 / parry3d-f64 answering t, point and normal",
            ids: ("collide_robust_f64", "parry64_like"),
            target: 0.5,
            floor: None,
        },
        Target {
            group: "segment_triangle",
            what: "segment–triangle (campaign mix): robust f64 / parry3d-f64",
            ids: ("collide_robust_f64", "parry64"),
            target: 1.0,
            floor: None,
        },
        Target {
            group: "segment_triangle_uniform",
            what: "segment–triangle (uniform random): exact (robust) f64 / lecture f64",
            ids: ("collide_robust_f64", "collide_lecture_f64"),
            target: 1.5,
            floor: None,
        },
        Target {
            group: "segment_triangle",
            what: "segment–triangle (campaign mix): exact (robust) f64 / lecture f64",
            ids: ("collide_robust_f64", "collide_lecture_f64"),
            target: 1.5,
            floor: None,
        },
        Target {
            group: "overlap",
            what: "AABB overlap, many pairs (broad phase): collide batch f64 / parry3d-f64 one at a time",
            ids: ("batch_f64", "parry64"),
            target: 0.5,
            floor: None,
        },
        Target {
            group: "overlap",
            what: "AABB overlap f64: batch / one-at-a-time loop",
            ids: ("batch_f64", "loop_f64"),
            target: 1.0,
            floor: None,
        },
        Target {
            group: "sphere_sphere_batch",
            what: "sphere–sphere contact f64: batch / one-at-a-time loop",
            ids: ("batch_contact_f64", "loop_contact_f64"),
            target: 1.0,
            floor: None,
        },
    ]
}

fn main() {
    let since = SystemTime::now();
    // `cargo bench` passes `--bench`; `cargo test --benches` does not, and then
    // criterion runs each benchmark once as a test: no peak, no table.
    let benching = std::env::args().any(|a| a == "--bench");
    PAIRING.store(benching, std::sync::atomic::Ordering::Relaxed);
    let peak = benching.then(peak::measure);
    let cases = Cases::draw();
    let mut c = Criterion::default()
        .output_directory(&table::criterion_dir())
        .warm_up_time(WARM_UP)
        .measurement_time(MEASUREMENT)
        .sample_size(SAMPLES)
        .nresamples(RESAMPLES)
        .configure_from_args();
    sphere_sphere(&mut c, &cases.sphere_sphere);
    sphere_plane(&mut c, &cases.sphere_plane);
    sphere_triangle(&mut c, &cases.sphere_triangle, &cases.families.sphere_triangle);
    segment_plane(&mut c, &cases.segment_plane, &cases.families.segment_plane);
    segment_triangle(&mut c, "segment_triangle", &cases.segment_triangle, Some(&cases.families.segment_triangle));
    segment_triangle(&mut c, "segment_triangle_uniform", &cases.segment_triangle_uniform, None);
    barycentric(&mut c, &cases.barycentric, &cases.families.barycentric);
    overlap(&mut c, &cases.overlap);
    bounding_sphere(&mut c, &cases.clouds);
    sphere_sphere_batch(&mut c, &cases.sphere_sphere);
    c.final_summary();
    if let Some(peak) = peak.map(|p| p.best(peak::measure())) {
        let families = [
            FamilyTable {
                label: "sphere–triangle",
                group: "sphere_triangle",
                families: family_counts(&cases.families.sphere_triangle),
            },
            FamilyTable {
                label: "segment–plane",
                group: "segment_plane",
                families: family_counts(&cases.families.segment_plane),
            },
            FamilyTable {
                label: "segment–triangle",
                group: "segment_triangle",
                families: family_counts(&cases.families.segment_triangle),
            },
            FamilyTable {
                label: "barycentric",
                group: "barycentric",
                families: family_counts(&cases.families.barycentric),
            },
        ];
        let tables =
            table::Tables { rows: &rows(&cases), batches: &batches(&cases), targets: &targets(), families: &families };
        table::publish(&table::render(&tables, &peak, since));
        table::write_figures(&rows(&cases), since);
    }
}
