//! Meshes, collide against parry, one run: `cargo bench --bench mesh`.
//!
//! - **Segment–bunny first hit**: collide's BVH query
//!   ([`intersect_segment_mesh_bvh`], both split rules, `f64` and `f32`)
//!   against parry's `TriMesh` ray cast (`cast_local_ray_and_get_normal` with
//!   the segment as a ray of direction `end − start` and `max_time_of_impact`
//!   1, as `oracle::parry` casts it), parry3d-f64 and parry3d (`f32`), on the
//!   same [`SEGMENTS`] pre-generated seeded segments ([`SEED`]): both endpoints
//!   uniform in the bunny's box grown by a quarter of its size on each side, so
//!   about half of them hit and the rest miss — many after crossing the box.
//!   collide answers more (the exact first hit's face, `t`, point, normal and
//!   barycentrics; parry its face, `t` and normal), so the comparison does not
//!   favour collide.
//! - **Batch: many segments against one mesh**: collide's batch query
//!   ([`intersect_segments_mesh`] over [`FaceArrays`]) against the
//!   one-at-a-time loops a user would otherwise write — the brute-force query
//!   (every face, the batch's like for like) and the BVH query — and parry's
//!   ray cast, on seeded height-field terrains of 32 and 288 faces and on the
//!   bunny ([`BATCH_SEGMENTS_BUNNY`] segments there, every face being tested
//!   for each), the segments drawn as above from each mesh's box. All answers
//!   are the same bits (the batch's tests check it); the table shows where the
//!   batch beats the loops and where the BVH is the better choice.
//! - **Build**: `TriMesh::new` + `MeshBvh::new` (collide's mesh checks and its
//!   tree; and `FaceArrays::new`, the batch query's arrays, instead of the tree) against parry's `TriMesh::new` (its checks and its BVH), both from
//!   vertex and index arrays cloned before timing.
//!
//! The bunny is `fixtures/meshes/bunny.obj` as loaded (no pose). Inputs are
//! converted to each engine's types before timing; each segment and answer
//! passes through `black_box` (the answer by reference: see
//! `shared/criterion.rs`). At the end, a table of ns per query (ms per
//! build) with the ratios collide / parry is printed and written to
//! `target/criterion/crashtest-mesh-table.md`.

#[path = "shared/criterion.rs"]
mod criterion_files;
use criterion_files::{PAIRING, Pairs, run};
#[path = "mesh/table.rs"]
mod table;

use collide::Vec3;
use collide::mesh::{
    FaceArrays, MeshBvh, SplitRule, TriMesh, intersect_segment_mesh_brute, intersect_segment_mesh_bvh,
    intersect_segments_mesh,
};
use criterion::{BatchSize, Criterion, Throughput};
use oracle::geom::P3;
use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, SystemTime};
use table::{Column, Row, Target};

/// Seed of the segments (fixed: every run times the same segments).
const SEED: u64 = 0x0B0B_5E6E;
/// Segments per iteration: enough to mix hits and misses and to defeat the
/// branch predictor's memory of a short loop; the bunny's trees (about 200 KiB
/// each) stay in L2 across them.
const SEGMENTS: usize = 1024;
/// Segments per iteration of the batch benchmarks on the bunny: each tests
/// all 3,674 faces in the brute-force loop and the batch, so fewer than
/// [`SEGMENTS`] keep an iteration near a millisecond.
const BATCH_SEGMENTS_BUNNY: usize = 64;
/// Cells per side of the batch benchmarks' terrains (two faces per cell): 8,
/// 32 and 288 faces, around where the BVH starts to pay.
const TERRAIN_CELLS: [usize; 3] = [2, 4, 12];
/// Height range of the terrains (their extent is 1 × 1).
const TERRAIN_HEIGHT: f64 = 0.2;
/// Seed of the terrains' heights.
const TERRAIN_SEED: u64 = 0x7E22_A1B0;

/// Growth of the bunny's box on each side, as a fraction of its largest size,
/// for the segments' endpoints.
const GROW: f64 = 0.25;

/// Warm-up per benchmark.
const WARM_UP: Duration = Duration::from_millis(300);
/// Measurement per benchmark: with [`SAMPLES`] samples the slope's confidence
/// interval is within a few percent on a quiet machine.
const MEASUREMENT: Duration = Duration::from_millis(1500);
/// Samples per benchmark (criterion's minimum is 10).
const SAMPLES: usize = 20;
/// Bootstrap resamples of criterion's analysis (its default, 100 000, costs
/// more time than the measurement here).
const RESAMPLES: usize = 10_000;

use harness::rng::SplitMix64 as Rng;

fn bunny() -> harness::mesh::Mesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/meshes/bunny.obj");
    harness::mesh::load_mesh_file(&path).expect("the bunny loads")
}

/// A height field over the unit square, `cells × cells` cells of two faces,
/// heights seeded uniform in `[0, TERRAIN_HEIGHT]`.
fn terrain(cells: usize) -> harness::mesh::Mesh {
    let mut rng = Rng(TERRAIN_SEED);
    let side = cells + 1;
    let mut vertices = Vec::with_capacity(side * side);
    for j in 0..side {
        for i in 0..side {
            let (x, y) = (i as f64 / cells as f64, j as f64 / cells as f64);
            vertices.push([x, y, rng.range(0.0, TERRAIN_HEIGHT)]);
        }
    }
    let mut faces = Vec::with_capacity(2 * cells * cells);
    for j in 0..cells {
        for i in 0..cells {
            let k = j * side + i;
            faces.push([k, k + 1, k + side + 1]);
            faces.push([k, k + side + 1, k + side]);
        }
    }
    harness::mesh::Mesh::new(vertices, faces).expect("a terrain is a valid mesh")
}

/// [`SEGMENTS`] segments with both endpoints uniform in the mesh's grown box.
fn segments(vertices: &[P3]) -> Vec<(P3, P3)> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let mut rng = Rng(SEED);
    let mut point = || [0, 1, 2].map(|k| rng.range(lo[k] - GROW * size, hi[k] + GROW * size));
    (0..SEGMENTS).map(|_| (point(), point())).collect()
}

fn v<T: collide::Real>(p: P3) -> Vec3<T> {
    Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]))
}

/// collide's mesh and tree in `T`.
fn collide_bvh<T: collide::Real>(m: &harness::mesh::Mesh, split: SplitRule) -> MeshBvh<T> {
    let mesh = TriMesh::new(m.vertices.iter().map(|&p| v(p)).collect(), m.triangles.clone()).expect("mesh");
    MeshBvh::with_split(mesh, split)
}

/// parry called directly, written once for both precisions.
macro_rules! parry_mesh {
    ($name:ident, $krate:ident) => {
        mod $name {
            use super::P3;
            use $krate::math::{Real, Vector};
            use $krate::query::{Ray, RayCast, RayIntersection};
            use $krate::shape::TriMesh;

            /// A point in parry's scalar (rounded once for `f32`).
            pub fn v(p: P3) -> Vector {
                Vector::new(p[0] as Real, p[1] as Real, p[2] as Real)
            }
            /// The mesh's arrays in parry's types.
            pub fn arrays(m: &harness::mesh::Mesh) -> (Vec<Vector>, Vec<[u32; 3]>) {
                let vs = m.vertices.iter().map(|&p| v(p)).collect();
                let fs = m.triangles.iter().map(|t| t.map(|i| i as u32)).collect();
                (vs, fs)
            }
            /// `TriMesh::new` (checks and BVH).
            pub fn build((vs, fs): (Vec<Vector>, Vec<[u32; 3]>)) -> TriMesh {
                TriMesh::new(vs, fs).expect("parry mesh")
            }
            /// The segment as `oracle::parry` casts it.
            pub fn ray(s: &(P3, P3)) -> Ray {
                let start = v(s.0);
                Ray::new(start, v(s.1) - start)
            }
            /// The first hit, `t ≤ 1`.
            pub fn cast(mesh: &TriMesh, ray: &Ray) -> Option<RayIntersection> {
                mesh.cast_local_ray_and_get_normal(ray, 1.0, false)
            }
        }
    };
}

parry_mesh!(p64, parry3d_f64);
parry_mesh!(p32, parry3d);

fn segment_bunny(c: &mut Criterion, m: &harness::mesh::Mesh, segs: &[(P3, P3)]) {
    let mut g = c.benchmark_group("mesh_segment_bunny");
    g.throughput(Throughput::Elements(segs.len() as u64));
    let sah64 = collide_bvh::<f64>(m, SplitRule::SahBinned);
    let med64 = collide_bvh::<f64>(m, SplitRule::MedianCentroid);
    let sah32 = collide_bvh::<f32>(m, SplitRule::SahBinned);
    let s64: Vec<_> = segs.iter().map(|s| collide::Segment::new(v::<f64>(s.0), v(s.1))).collect();
    let s32: Vec<_> = segs.iter().map(|s| collide::Segment::new(v::<f32>(s.0), v(s.1))).collect();
    run(&mut g, "collide_bvh_f64", &s64, |s| intersect_segment_mesh_bvh(s, &sah64));
    run(&mut g, "collide_bvh_median_f64", &s64, |s| intersect_segment_mesh_bvh(s, &med64));
    run(&mut g, "collide_bvh_f32", &s32, |s| intersect_segment_mesh_bvh(s, &sah32));
    let mesh64 = p64::build(p64::arrays(m));
    let mesh32 = p32::build(p32::arrays(m));
    let r64: Vec<_> = segs.iter().map(p64::ray).collect();
    let r32: Vec<_> = segs.iter().map(p32::ray).collect();
    run(&mut g, "parry64", &r64, |r| p64::cast(&mesh64, r));
    run(&mut g, "parry32", &r32, |r| p32::cast(&mesh32, r));
    g.finish();
    let mut pairs = Pairs::new("mesh_segment_bunny");
    pairs.keep("collide_bvh_f64", &s64, |s| intersect_segment_mesh_bvh(s, &sah64));
    pairs.keep("parry64", &r64, |r| p64::cast(&mesh64, r));
    pairs.measure(&[("collide_bvh_f64", "parry64")]);
}

/// The batch query against the one-at-a-time loops and parry, on one mesh.
fn segment_batch(c: &mut Criterion, group: &'static str, m: &harness::mesh::Mesh, segs: &[(P3, P3)]) {
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(segs.len() as u64));
    let bvh = collide_bvh::<f64>(m, SplitRule::SahBinned);
    let faces = FaceArrays::new(bvh.mesh().clone());
    let s64: Vec<_> = segs.iter().map(|s| collide::Segment::new(v::<f64>(s.0), v(s.1))).collect();
    run(&mut g, "loop_brute_f64", &s64, |s| intersect_segment_mesh_brute(s, bvh.mesh()));
    run(&mut g, "loop_bvh_f64", &s64, |s| intersect_segment_mesh_bvh(s, &bvh));
    let mut out = Vec::with_capacity(s64.len());
    g.bench_function("batch_f64", |b| {
        b.iter(|| {
            intersect_segments_mesh(black_box(&s64), &faces, &mut out);
            black_box(&out);
        })
    });
    let mesh64 = p64::build(p64::arrays(m));
    let r64: Vec<_> = segs.iter().map(p64::ray).collect();
    run(&mut g, "parry64", &r64, |r| p64::cast(&mesh64, r));
    g.finish();
    let mut pairs = Pairs::new(group);
    pairs.keep("loop_brute_f64", &s64, |s| intersect_segment_mesh_brute(s, bvh.mesh()));
    pairs.keep_pass("batch_f64", s64.len(), || {
        intersect_segments_mesh(black_box(&s64), &faces, &mut out);
        black_box(&out);
    });
    pairs.measure(&[("batch_f64", "loop_brute_f64")]);
}

/// One mesh of the batch benchmarks.
struct BatchMesh {
    /// criterion's group.
    group: &'static str,
    /// The table's row heading.
    label: String,
    mesh: harness::mesh::Mesh,
    segs: Vec<(P3, P3)>,
}

/// The batch benchmarks' meshes: the terrains and the bunny, with their
/// criterion groups and segments.
fn batch_meshes(bunny: &harness::mesh::Mesh) -> Vec<BatchMesh> {
    let mut out = Vec::new();
    for (cells, group) in TERRAIN_CELLS.into_iter().zip([
        "mesh_segment_batch_terrain_8",
        "mesh_segment_batch_terrain_32",
        "mesh_segment_batch_terrain_288",
    ]) {
        let m = terrain(cells);
        let segs = segments(&m.vertices);
        out.push(BatchMesh { group, label: format!("terrain, {} faces", m.triangles.len()), mesh: m, segs });
    }
    let mut segs = segments(&bunny.vertices);
    segs.truncate(BATCH_SEGMENTS_BUNNY);
    let label = format!("bunny, {} faces", bunny.triangles.len());
    out.push(BatchMesh { group: "mesh_segment_batch_bunny", label, mesh: bunny.clone(), segs });
    out
}

fn build(c: &mut Criterion, m: &harness::mesh::Mesh) {
    let mut g = c.benchmark_group("mesh_build_bunny");
    g.throughput(Throughput::Elements(1));
    let arrays64 = (m.vertices.iter().map(|&p| v::<f64>(p)).collect::<Vec<_>>(), m.triangles.clone());
    let arrays32 = (m.vertices.iter().map(|&p| v::<f32>(p)).collect::<Vec<_>>(), m.triangles.clone());
    g.bench_function("collide_bvh_f64", |b| {
        b.iter_batched(
            || arrays64.clone(),
            |(vs, fs)| MeshBvh::new(TriMesh::new(vs, fs).expect("mesh")),
            BatchSize::SmallInput,
        )
    });
    g.bench_function("collide_bvh_median_f64", |b| {
        b.iter_batched(
            || arrays64.clone(),
            |(vs, fs)| MeshBvh::with_split(TriMesh::new(vs, fs).expect("mesh"), SplitRule::MedianCentroid),
            BatchSize::SmallInput,
        )
    });
    g.bench_function("collide_bvh_f32", |b| {
        b.iter_batched(
            || arrays32.clone(),
            |(vs, fs)| MeshBvh::new(TriMesh::new(vs, fs).expect("mesh")),
            BatchSize::SmallInput,
        )
    });
    g.bench_function("collide_faces_f64", |b| {
        b.iter_batched(
            || arrays64.clone(),
            |(vs, fs)| FaceArrays::new(TriMesh::new(vs, fs).expect("mesh")),
            BatchSize::SmallInput,
        )
    });
    let (a64, a32) = (p64::arrays(m), p32::arrays(m));
    g.bench_function("parry64", |b| b.iter_batched(|| a64.clone(), p64::build, BatchSize::SmallInput));
    g.bench_function("parry32", |b| b.iter_batched(|| a32.clone(), p32::build, BatchSize::SmallInput));
    g.finish();
}

/// Fraction of the segments collide's `f64` BVH query says hit (exact).
fn hit_fraction(m: &harness::mesh::Mesh, segs: &[(P3, P3)]) -> f64 {
    let bvh = collide_bvh::<f64>(m, SplitRule::SahBinned);
    let hits = segs
        .iter()
        .filter(|s| intersect_segment_mesh_bvh(&collide::Segment::new(v(s.0), v(s.1)), &bvh).hit.is_some())
        .count();
    hits as f64 / segs.len() as f64
}

/// The batch table: one row per mesh, the batch against the loops and parry.
fn batch_report(batches: &[BatchMesh], since: SystemTime) -> String {
    let columns = [
        Column { id: "loop_brute_f64", heading: "loop, brute force f64" },
        Column { id: "batch_f64", heading: "batch f64" },
        Column { id: "loop_bvh_f64", heading: "loop, BVH f64" },
        Column { id: "parry64", heading: "parry3d-f64" },
    ];
    let ratios = [
        ("batch_f64", "loop_brute_f64", "batch / brute-force loop"),
        ("batch_f64", "loop_bvh_f64", "batch / BVH loop"),
        ("batch_f64", "parry64", "batch / parry3d-f64"),
    ];
    let rows: Vec<Row> = batches
        .iter()
        .map(|b| Row {
            group: b.group,
            label: format!("{} ({} segments)", b.label, b.segs.len()),
            per_iter: b.segs.len(),
            unit_ns: 1.0,
            unit: "ns/segment",
        })
        .collect();
    let intro = format!(
        "`intersect_segments_mesh` over `FaceArrays` (every face: its box culled in packed lanes — the BVH's slab test — then the filter and the exact test on the faces kept) against \
         the one-at-a-time loops over the same segments: `intersect_segment_mesh_brute` (every face: like for \
         like) and `intersect_segment_mesh_bvh`, and parry's `TriMesh` ray cast. Terrains: height fields over \
         the unit square, heights seeded ({TERRAIN_SEED:#x}) in [0, {TERRAIN_HEIGHT}]. Segments as above, from \
         each mesh's grown box. Every answer is the same bits in the three collide columns."
    );
    table::render("Batch: many segments against one mesh", &intro, &columns, &rows, &ratios, since)
}

fn report(m: &harness::mesh::Mesh, segs: &[(P3, P3)], batches: &[BatchMesh], since: SystemTime) -> String {
    let columns = [
        Column { id: "collide_bvh_f64", heading: "collide BVH f64 (SAH)" },
        Column { id: "collide_bvh_median_f64", heading: "collide BVH f64 (median)" },
        Column { id: "collide_bvh_f32", heading: "collide BVH f32 (SAH)" },
        Column { id: "collide_faces_f64", heading: "collide FaceArrays f64 (batch, no tree)" },
        Column { id: "parry64", heading: "parry3d-f64" },
        Column { id: "parry32", heading: "parry3d" },
    ];
    let ratios = [
        ("collide_bvh_f64", "parry64", "collide f64 / parry3d-f64"),
        ("collide_bvh_f64", "parry32", "collide f64 / parry3d"),
        ("collide_bvh_f32", "parry32", "collide f32 / parry3d"),
    ];
    let rows = [
        Row {
            group: "mesh_segment_bunny",
            label: format!("segment–bunny first hit ({:.0}% hit)", 100.0 * hit_fraction(m, segs)),
            per_iter: segs.len(),
            unit_ns: 1.0,
            unit: "ns/query",
        },
        Row {
            group: "mesh_build_bunny",
            label: format!("build ({} faces)", m.triangles.len()),
            per_iter: 1,
            unit_ns: 1e6,
            unit: "ms/build",
        },
    ];
    let intro = format!(
        "The Stanford bunny ({} vertices, {} faces). Segments: {} drawn once from seed {SEED:#x}, both \
         endpoints uniform in the bunny's box grown by {GROW} of its size on each side. criterion's slope \
         estimate of this run, divided by the queries per iteration. parry: `TriMesh::cast_local_ray_and_get_normal` \
         (face, t, normal); collide: the exact first hit (face, t, point, normal, barycentrics).",
        m.vertices.len(),
        m.triangles.len(),
        segs.len()
    );
    let mut targets = vec![Target {
        group: "mesh_segment_bunny",
        per_iter: segs.len(),
        what: "segment–bunny: collide BVH f64 / parry3d-f64 TriMesh ray cast".into(),
        ids: ("collide_bvh_f64", "parry64"),
        target: 1.0,
    }];
    // The batch API against the loop it replaces (every face, one segment at
    // a time), on each mesh.
    for b in batches {
        targets.push(Target {
            group: b.group,
            per_iter: b.segs.len(),
            what: format!("segments–mesh batch / brute-force loop, {}", b.label),
            ids: ("batch_f64", "loop_brute_f64"),
            target: 1.0,
        });
    }
    format!(
        "# crashtest speed: meshes, collide against parry, one run\n\n{}\n{}\n{}",
        table::render("Segment–bunny and build", &intro, &columns, &rows, &ratios, since),
        batch_report(batches, since),
        table::render_targets(&targets, since)
    )
}

fn main() {
    let since = SystemTime::now();
    // `cargo bench` passes `--bench`; `cargo test --benches` does not, and then
    // criterion runs each benchmark once as a test: no table.
    let benching = std::env::args().any(|a| a == "--bench");
    PAIRING.store(benching, std::sync::atomic::Ordering::Relaxed);
    let m = bunny();
    let segs = segments(&m.vertices);
    let mut c = Criterion::default()
        .output_directory(&table::criterion_dir())
        .warm_up_time(WARM_UP)
        .measurement_time(MEASUREMENT)
        .sample_size(SAMPLES)
        .nresamples(RESAMPLES)
        .configure_from_args();
    segment_bunny(&mut c, &m, &segs);
    let batches = batch_meshes(&m);
    for b in &batches {
        segment_batch(&mut c, b.group, &b.mesh, &b.segs);
    }
    build(&mut c, &m);
    c.final_summary();
    if benching {
        table::publish(&report(&m, &segs, &batches, since));
    }
}
