//! Oriented boxes, capsules and convex distance, collide against parry3d-f64, one run:
//! `cargo bench --bench boxes`.
//!
//! Five pairs and `distance`, each on the campaign's own cases of it ([`PER_QUERY`]
//! generated cases of the default seed per query kind, a tenth full-range,
//! as a report draws them, kept where the shapes are the pair's):
//!
//! | pair | collide (robust and lecture) | parry3d-f64 |
//! | --- | --- | --- |
//! | sphere–box contact | `contact_sphere_box`, `contact_sphere_box_lecture` | `query::contact(pose, Ball, pose, Cuboid, 0)` |
//! | box–box overlap | `test_box_box`, `test_box_box_lecture` | `query::intersection_test(pose, Cuboid, pose, Cuboid)` |
//! | capsule–capsule contact | `contact_capsule_capsule`, `contact_capsule_capsule_lecture` | `query::contact(id, Capsule, id, Capsule, 0)` |
//! | box–box contact | `contact_box_box`, `contact_box_box_lecture` | `query::contact(pose, Cuboid, pose, Cuboid, 0)` |
//! | capsule–box contact | `contact_capsule_box`, `contact_capsule_box_lecture` | `query::contact(id, Capsule, pose, Cuboid, 0)` |
//! | distance (18 pairs) | `convex::distance_solids` (boxes exactly), `convex::distance_lecture` (and `_plane`): GJK and EPA | `query::contact(pose, shape, pose, shape, MAX)`, as its adapter asks |
//!
//! `distance` runs on the campaign's distance mix whole, and on its cases of
//! two `convex` shapes alone. Its inputs are built before timing as well:
//! collide's are each solid's core points and radius (collide's GJK takes
//! points; the robust form takes a box as a box, as collide's adapter gives
//! it), parry's its shapes (a hull's `ConvexPolyhedron` built once);
//! cases parry cannot build (flat, needle and one-point hulls) are left out
//! and counted.
//!
//! Every engine's inputs are built before timing, in its own types, as the
//! harness's adapters build them (parry's box: a `Cuboid` at the pose of the
//! normalized quaternion; its capsule: two points and a radius at the
//! identity). A timed iteration runs the query on every case
//! (`shared/criterion.rs`). Each collide method is also measured paired
//! against parry (both back to back, alternating, many rounds), and the table
//! gives ns per query (criterion's estimate and the paired rounds' median),
//! the paired ratio collide / parry with its quartiles, and how many cases
//! collide's robust method and parry answer alike (contact or not, overlap or
//! not). It is printed and written to `target/criterion/crashtest-boxes-table.md`.

#[path = "shared/criterion.rs"]
#[allow(
    dead_code,
    reason = "shared with the other benches; this one uses the loop, the estimates and the paired ratios"
)]
mod criterion_files;
use criterion_files::{PAIRING, Pairs, cell, criterion_dir, ns_per, paired_ratio, run};

use collide::Vec3;
use criterion::{Criterion, Throughput};
use harness::case::{Query, Shape};
use harness::generate::{generate, try_generate_full_range};
use harness::load::LoadedCase;
use oracle::geom::{Capsule, OrientedBox, Sphere};
use oracle::parry::{Parry64Solid, parry64_distance, parry64_solid};
use parry3d_f64::math::{Pose, Rotation, Vector};
use parry3d_f64::query;
use parry3d_f64::shape::{Ball, Capsule as ParryCapsule, Cuboid};
use std::time::{Duration, SystemTime};

/// Seed of the cases: the campaign's default, so the mix is a report's.
const SEED: u64 = harness::defaults::DEFAULT_SEED;

/// Cases generated per query kind (contact, overlap), a tenth full-range; the
/// box and capsule families are a share of them.
const PER_QUERY: u64 = 4000;

/// Warm-up per benchmark.
const WARM_UP: Duration = Duration::from_millis(300);
/// Measurement per benchmark.
const MEASUREMENT: Duration = Duration::from_millis(1000);
/// Samples per benchmark (criterion's minimum is 10).
const SAMPLES: usize = 20;
/// Bootstrap resamples.
const RESAMPLES: usize = 10_000;

fn cases(q: Query) -> Vec<LoadedCase> {
    let full = PER_QUERY / 10;
    let mut out: Vec<LoadedCase> = (0..PER_QUERY - full).map(|i| generate(q, SEED, i)).collect();
    out.extend((0..full).filter_map(|i| try_generate_full_range(q, SEED, i)));
    out
}

fn v(p: &[f64; 3]) -> Vec3<f64> {
    Vec3::new(p[0], p[1], p[2])
}

fn pv(p: &[f64; 3]) -> Vector {
    Vector::new(p[0], p[1], p[2])
}

fn collide_box(b: &OrientedBox) -> collide::OrientedBox<f64> {
    collide::OrientedBox::new(v(&b.center), v(&b.half_extents), b.rotation)
}

fn collide_capsule(c: &Capsule) -> collide::Capsule<f64> {
    collide::Capsule::new(v(&c.start), v(&c.end), c.radius)
}

/// parry's box as the adapter builds it: the quaternion scaled by a power of
/// two (exact), normalized, at the centre; `None` where the adapter refuses
/// the box.
fn parry_box(b: &OrientedBox) -> Option<(Pose, Cuboid)> {
    let m = b.rotation.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(m > 0.0 && m.is_finite()) || b.half_extents.iter().any(|h| *h < 0.0) {
        return None;
    }
    let [w, x, y, z] = b.rotation.map(|c| c * 2f64.powi(-(m.log2().floor() as i32)));
    let q = Rotation::from_xyzw(x, y, z, w).normalize();
    q.is_finite().then(|| (Pose::from_parts(pv(&b.center), q), Cuboid::new(pv(&b.half_extents))))
}

fn parry_capsule(c: &Capsule) -> Option<ParryCapsule> {
    (c.radius > 0.0).then(|| ParryCapsule::new(pv(&c.start), pv(&c.end), c.radius))
}

/// One pair's inputs in every engine's types.
struct PairInputs<C, P> {
    collide: Vec<C>,
    parry: Vec<P>,
}

type SphereBox = (collide::Sphere<f64>, collide::OrientedBox<f64>);
type ParrySphereBox = (Pose, Ball, Pose, Cuboid);
type BoxBox = (collide::OrientedBox<f64>, collide::OrientedBox<f64>);
type ParryBoxBox = (Pose, Cuboid, Pose, Cuboid);
type CapsuleCapsule = (collide::Capsule<f64>, collide::Capsule<f64>);
type ParryCapsules = (ParryCapsule, ParryCapsule);
type CapsuleBox = (collide::Capsule<f64>, collide::OrientedBox<f64>);
type ParryCapsuleBox = (ParryCapsule, Pose, Cuboid);

fn sphere_box(all: &[LoadedCase]) -> PairInputs<SphereBox, ParrySphereBox> {
    let mut out = PairInputs { collide: Vec::new(), parry: Vec::new() };
    for lc in all {
        if let (Shape::Sphere(s), Some(Shape::Box(b))) = (&lc.case.a, lc.case.b.as_ref()) {
            let b = b.to_geom();
            let Some((pose, cuboid)) = parry_box(&b) else { continue };
            let s: Sphere = s.to_geom();
            out.collide.push((collide::Sphere::new(v(&s.center), s.radius), collide_box(&b)));
            out.parry.push((Pose::from_translation(pv(&s.center)), Ball::new(s.radius), pose, cuboid));
        }
    }
    out
}

fn box_box(all: &[LoadedCase]) -> PairInputs<BoxBox, ParryBoxBox> {
    let mut out = PairInputs { collide: Vec::new(), parry: Vec::new() };
    for lc in all {
        if let (Shape::Box(a), Some(Shape::Box(b))) = (&lc.case.a, lc.case.b.as_ref()) {
            let (a, b) = (a.to_geom(), b.to_geom());
            let (Some((pa, ca)), Some((pb, cb))) = (parry_box(&a), parry_box(&b)) else { continue };
            out.collide.push((collide_box(&a), collide_box(&b)));
            out.parry.push((pa, ca, pb, cb));
        }
    }
    out
}

fn capsule_capsule(all: &[LoadedCase]) -> PairInputs<CapsuleCapsule, ParryCapsules> {
    let mut out = PairInputs { collide: Vec::new(), parry: Vec::new() };
    for lc in all {
        if let (Shape::Capsule(a), Some(Shape::Capsule(b))) = (&lc.case.a, lc.case.b.as_ref()) {
            let (Some(pa), Some(pb)) = (parry_capsule(a), parry_capsule(b)) else { continue };
            out.collide.push((collide_capsule(a), collide_capsule(b)));
            out.parry.push((pa, pb));
        }
    }
    out
}

fn capsule_box(all: &[LoadedCase]) -> PairInputs<CapsuleBox, ParryCapsuleBox> {
    let mut out = PairInputs { collide: Vec::new(), parry: Vec::new() };
    for lc in all {
        if let (Shape::Capsule(a), Some(Shape::Box(b))) = (&lc.case.a, lc.case.b.as_ref()) {
            let b = b.to_geom();
            let (Some(pa), Some((pb, cb))) = (parry_capsule(a), parry_box(&b)) else { continue };
            out.collide.push((collide_capsule(a), collide_box(&b)));
            out.parry.push((pa, pb, cb));
        }
    }
    out
}

/// A distance case in collide's types: each solid's core points and radius,
/// or `b`'s plane, and each solid's box when it is one (the robust form
/// takes boxes exactly, as collide's adapter gives them).
type CollideDistance = (Vec<Vec3<f64>>, f64, DistanceB, [Option<collide::OrientedBox<f64>>; 2]);
enum DistanceB {
    Rounded(Vec<Vec3<f64>>, f64),
    Plane(collide::Plane<f64>),
}
type ParryDistance = (Parry64Solid, Parry64Solid);

/// A distance solid's core points and radius, as collide's adapter takes them.
fn core(s: &Shape) -> Option<(Vec<Vec3<f64>>, f64)> {
    Some(match s {
        Shape::Sphere(x) => (vec![v(&x.center)], x.radius),
        Shape::Capsule(c) => (vec![v(&c.start), v(&c.end)], c.radius),
        Shape::Box(b) => (collide::convex::box_corners(&collide_box(&b.to_geom())).to_vec(), 0.0),
        Shape::Triangle(t) => (t.vertices.iter().map(v).collect(), 0.0),
        Shape::Convex(c) => (c.points.iter().map(v).collect(), 0.0),
        _ => return None,
    })
}

/// The distance cases (those of two `convex` shapes alone when `hulls`), and
/// how many parry cannot build.
fn distance_pairs(all: &[LoadedCase], hulls: bool) -> (PairInputs<CollideDistance, ParryDistance>, usize) {
    let mut out = PairInputs { collide: Vec::new(), parry: Vec::new() };
    let mut unbuilt = 0;
    for lc in all {
        let (a, Some(b)) = (&lc.case.a, lc.case.b.as_ref()) else { continue };
        if hulls && !matches!((a, b), (Shape::Convex(_), Shape::Convex(_))) {
            continue;
        }
        let (Ok(sa), Ok(sb)) = (harness::engine::SolidValue::of(a), harness::engine::SolidValue::of(b)) else {
            continue;
        };
        let (Ok(pa), Ok(pb)) = (parry64_solid(sa.solid()), parry64_solid(sb.solid())) else {
            unbuilt += 1;
            continue;
        };
        let Some((points_a, ra)) = core(a) else { continue };
        let other = match b {
            Shape::Plane(p) => DistanceB::Plane(collide::Plane::new(v(&p.normal), p.offset)),
            _ => match core(b) {
                Some((points, r)) => DistanceB::Rounded(points, r),
                None => continue,
            },
        };
        let as_box = |s: &Shape| match s {
            Shape::Box(b) => Some(collide_box(&b.to_geom())),
            _ => None,
        };
        out.collide.push((points_a, ra, other, [as_box(a), as_box(b)]));
        out.parry.push((pa, pb));
    }
    (out, unbuilt)
}

fn d_robust(x: &CollideDistance) -> collide::convex::Distance<f64> {
    use collide::convex::Solid;
    let a = collide::convex::Rounded { points: &x.0, radius: x.1 };
    match &x.2 {
        DistanceB::Rounded(points, r) => {
            let b = collide::convex::Rounded { points, radius: *r };
            let sa = x.3[0].as_ref().map_or(Solid::Hull(a), Solid::Box);
            let sb = x.3[1].as_ref().map_or(Solid::Hull(b), Solid::Box);
            collide::convex::distance_solids(&sa, &sb)
        }
        DistanceB::Plane(p) => collide::convex::distance_plane(&a, p),
    }
}
fn d_lecture(x: &CollideDistance) -> collide::convex::Distance<f64> {
    let a = collide::convex::Rounded { points: &x.0, radius: x.1 };
    match &x.2 {
        DistanceB::Rounded(points, r) => {
            collide::convex::distance_lecture(&a, &collide::convex::Rounded { points, radius: *r })
        }
        DistanceB::Plane(p) => collide::convex::distance_plane_lecture(&a, p),
    }
}
fn d_parry(x: &ParryDistance) -> Option<f64> {
    parry64_distance(&x.0, &x.1).ok().map(|d| d.distance)
}

/// Leaves out the cases parry panics on (its EPA indexes out of bounds on
/// some capsule pairs): a panic is not an answer to time, and the report
/// shows those cases as findings. The count goes in the table.
fn without_parry_panics<C, P, B>(inputs: PairInputs<C, P>, parry: fn(&P) -> B) -> (PairInputs<C, P>, usize) {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut kept = PairInputs { collide: Vec::new(), parry: Vec::new() };
    let mut panics = 0;
    for (c, p) in inputs.collide.into_iter().zip(inputs.parry) {
        if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| parry(&p))).is_ok() {
            kept.collide.push(c);
            kept.parry.push(p);
        } else {
            panics += 1;
        }
    }
    std::panic::set_hook(hook);
    (kept, panics)
}

/// One row of the table.
struct Row {
    label: &'static str,
    group: &'static str,
    n: usize,
    /// Cases left out because parry panicked on them.
    panics: usize,
    /// Cases where collide's robust method and parry give the same decision.
    alike: usize,
    /// Cases left out because parry cannot build a shape of them.
    unbuilt: usize,
}

/// One pair's three engines and how each answer reads as a decision
/// (contact or not, overlap or not).
struct Engines<C, P, A, B> {
    robust: fn(&C) -> A,
    lecture: fn(&C) -> A,
    parry: fn(&P) -> B,
    decided: fn(&A) -> bool,
    parry_decided: fn(&B) -> bool,
}

/// Times the three engines on one pair as group `group`, paired ratios of
/// both collide methods against parry, and counts the cases where collide's
/// robust method and parry decide alike.
fn bench<C, P, A, B>(
    c: &mut Criterion,
    (label, group): (&'static str, &'static str),
    inputs: PairInputs<C, P>,
    e: Engines<C, P, A, B>,
) -> Row {
    let (kept, panics) = without_parry_panics(inputs, e.parry);
    let inputs = &kept;
    let n = inputs.collide.len();
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(n as u64));
    run(&mut g, "robust", &inputs.collide, e.robust);
    run(&mut g, "lecture", &inputs.collide, e.lecture);
    run(&mut g, "parry64", &inputs.parry, e.parry);
    g.finish();
    let mut pairs = Pairs::new(group);
    pairs.keep("robust", &inputs.collide, e.robust);
    pairs.keep("lecture", &inputs.collide, e.lecture);
    pairs.keep("parry64", &inputs.parry, e.parry);
    pairs.measure(&[("robust", "parry64"), ("lecture", "parry64")]);
    let alike = inputs
        .collide
        .iter()
        .zip(&inputs.parry)
        .filter(|(x, p)| (e.decided)(&(e.robust)(x)) == (e.parry_decided)(&(e.parry)(p)))
        .count();
    Row { label, group, n, panics, alike, unbuilt: 0 }
}

fn sb_robust(x: &SphereBox) -> Option<collide::contact::Contact<f64>> {
    collide::boxes::contact_sphere_box(&x.0, &x.1)
}
fn sb_lecture(x: &SphereBox) -> Option<collide::contact::Contact<f64>> {
    collide::boxes::contact_sphere_box_lecture(&x.0, &x.1)
}
fn sb_parry(x: &ParrySphereBox) -> Option<query::Contact> {
    query::contact(&x.0, &x.1, &x.2, &x.3, 0.0).ok().flatten()
}
fn bb_robust(x: &BoxBox) -> bool {
    collide::boxes::test_box_box(&x.0, &x.1)
}
fn bb_lecture(x: &BoxBox) -> bool {
    collide::boxes::test_box_box_lecture(&x.0, &x.1)
}
fn bb_parry(x: &ParryBoxBox) -> bool {
    query::intersection_test(&x.0, &x.1, &x.2, &x.3).is_ok_and(|i| i.intersecting)
}
fn cc_robust(x: &CapsuleCapsule) -> Option<collide::contact::Contact<f64>> {
    collide::boxes::contact_capsule_capsule(&x.0, &x.1)
}
fn cc_lecture(x: &CapsuleCapsule) -> Option<collide::contact::Contact<f64>> {
    collide::boxes::contact_capsule_capsule_lecture(&x.0, &x.1)
}
fn cc_parry(x: &ParryCapsules) -> Option<query::Contact> {
    query::contact(&Pose::IDENTITY, &x.0, &Pose::IDENTITY, &x.1, 0.0).ok().flatten()
}

fn bbc_robust(x: &BoxBox) -> Option<collide::contact::Contact<f64>> {
    collide::boxes::contact_box_box(&x.0, &x.1)
}
fn bbc_lecture(x: &BoxBox) -> Option<collide::contact::Contact<f64>> {
    collide::boxes::contact_box_box_lecture(&x.0, &x.1)
}
fn bbc_parry(x: &ParryBoxBox) -> Option<query::Contact> {
    query::contact(&x.0, &x.1, &x.2, &x.3, 0.0).ok().flatten()
}
fn cb_robust(x: &CapsuleBox) -> Option<collide::contact::Contact<f64>> {
    collide::boxes::contact_capsule_box(&x.0, &x.1)
}
fn cb_lecture(x: &CapsuleBox) -> Option<collide::contact::Contact<f64>> {
    collide::boxes::contact_capsule_box_lecture(&x.0, &x.1)
}
fn cb_parry(x: &ParryCapsuleBox) -> Option<query::Contact> {
    query::contact(&Pose::IDENTITY, &x.0, &x.1, &x.2, 0.0).ok().flatten()
}

fn table(rows: &[Row], since: SystemTime) -> String {
    let mut s = format!(
        "# crashtest speed: oriented boxes, capsules and convex distance, collide against parry3d-f64, one run\n\n\
         The campaign's own cases of each pair ({PER_QUERY} cases of seed {SEED} per query kind, a tenth \
         full-range, kept where the shapes are the pair's; parry's inputs built as its adapter builds them, before \
         timing). ns per query: criterion's estimate (slope, else mean, over the cases per iteration). The ratios \
         are paired medians (both engines back to back over the same cases, alternating, 31 rounds) with their \
         quartiles. \"alike\": cases where collide's robust method and parry give the same decision (contact or \
         not, overlap or not). \"parry panics\": cases left out because parry3d-f64 panicked on them (the \
         report shows them as findings). For distance, \"alike\" is the same sign (apart or not), and \"parry \
         unbuilt\" counts the cases left out because parry builds no shape of them (flat, needle and one-point \
         hulls).\n\n\
         | pair | cases | parry panics | parry unbuilt | robust ns | lecture ns | parry3d-f64 ns | robust / parry \
         (quartiles) | lecture / parry (quartiles) | alike |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | \
         ---: | ---: |\n"
    );
    for r in rows {
        let ns = |id: &str| cell(ns_per(r.group, id, r.n, since));
        let q = |id: &str| paired_ratio(r.group, id, "parry64").map_or("—".into(), |p| p.quartiles());
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            r.label,
            r.n,
            r.panics,
            r.unbuilt,
            ns("robust"),
            ns("lecture"),
            ns("parry64"),
            q("robust"),
            q("lecture"),
            r.alike
        ));
    }
    s
}

fn main() {
    let since = SystemTime::now();
    // `cargo bench` passes `--bench`; `cargo test --benches` does not: then
    // each benchmark runs once as a test, with no pairs and no table.
    let benching = std::env::args().any(|a| a == "--bench");
    PAIRING.store(benching, std::sync::atomic::Ordering::Relaxed);
    let (contact, overlap) = (cases(Query::Contact), cases(Query::Overlap));
    let (sb, bb, cc) = (sphere_box(&contact), box_box(&overlap), capsule_capsule(&contact));
    let (bbc, cb) = (box_box(&contact), capsule_box(&contact));
    let distance_cases = cases(Query::Distance);
    let ((dist, dist_unbuilt), (hulls, hulls_unbuilt)) =
        (distance_pairs(&distance_cases, false), distance_pairs(&distance_cases, true));
    assert!(
        [sb.collide.len(), bb.collide.len(), cc.collide.len(), bbc.collide.len(), cb.collide.len()]
            .iter()
            .all(|n| *n > 0),
        "no box or capsule cases"
    );
    let mut c = Criterion::default()
        .output_directory(&criterion_dir())
        .warm_up_time(WARM_UP)
        .measurement_time(MEASUREMENT)
        .sample_size(SAMPLES)
        .nresamples(RESAMPLES)
        .configure_from_args();
    let rows = vec![
        bench(
            &mut c,
            ("sphere–box contact", "boxes_sphere_box"),
            sb,
            Engines {
                robust: sb_robust,
                lecture: sb_lecture,
                parry: sb_parry,
                decided: Option::is_some,
                parry_decided: Option::is_some,
            },
        ),
        bench(
            &mut c,
            ("box–box overlap", "boxes_box_box"),
            bb,
            Engines { robust: bb_robust, lecture: bb_lecture, parry: bb_parry, decided: |x| *x, parry_decided: |x| *x },
        ),
        bench(
            &mut c,
            ("capsule–capsule contact", "boxes_capsule_capsule"),
            cc,
            Engines {
                robust: cc_robust,
                lecture: cc_lecture,
                parry: cc_parry,
                decided: Option::is_some,
                parry_decided: Option::is_some,
            },
        ),
        bench(
            &mut c,
            ("box–box contact", "boxes_box_box_contact"),
            bbc,
            Engines {
                robust: bbc_robust,
                lecture: bbc_lecture,
                parry: bbc_parry,
                decided: Option::is_some,
                parry_decided: Option::is_some,
            },
        ),
        bench(
            &mut c,
            ("capsule–box contact", "boxes_capsule_box"),
            cb,
            Engines {
                robust: cb_robust,
                lecture: cb_lecture,
                parry: cb_parry,
                decided: Option::is_some,
                parry_decided: Option::is_some,
            },
        ),
    ];
    let distance_engines = || Engines {
        robust: d_robust,
        lecture: d_lecture,
        parry: d_parry,
        decided: |d: &collide::convex::Distance<f64>| d.distance > 0.0,
        parry_decided: |d: &Option<f64>| d.is_some_and(|d| d > 0.0),
    };
    let mut rows = rows;
    let mut row = bench(&mut c, ("distance (campaign mix)", "boxes_distance"), dist, distance_engines());
    row.unbuilt = dist_unbuilt;
    rows.push(row);
    let mut row = bench(&mut c, ("distance, hull–hull", "boxes_distance_hulls"), hulls, distance_engines());
    row.unbuilt = hulls_unbuilt;
    rows.push(row);
    c.final_summary();
    if benching {
        let report = table(&rows, since);
        println!("\n{report}");
        let path = criterion_dir().join("crashtest-boxes-table.md");
        match std::fs::create_dir_all(criterion_dir()).and_then(|()| std::fs::write(&path, &report)) {
            Ok(()) => println!("(written to {})", path.display()),
            Err(e) => eprintln!("could not write {}: {e}", path.display()),
        }
    }
}
