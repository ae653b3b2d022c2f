//! Meshes as evidence: collide's BVH against the exact referee on the Stanford
//! bunny under random poses, parry's disagreements adjudicated, and the errors
//! a malformed mesh file gets.
//!
//! The referee answers a segment–mesh query by brute force in exact rationals:
//! about 50 µs per face, 0.2 s for the whole bunny — far too slow for 100,000
//! segments. So the differential test is in three parts, each exact:
//!
//! 1. **100,000 segments** (100 poses × 1,000): the referee's answer is computed
//!    on the faces collide's exact single-triangle test says are hit (every
//!    face whose box meets the segment's box is tested, not just those the BVH
//!    visits), and collide's BVH must name the same face, with `t`, the
//!    barycentrics, the normal and the point within [`T_TOL`] of the referee's
//!    (`assert_values`). This checks the BVH — traversal, culling, the exact
//!    ordering of hits, the tie rule and the winner's values — against brute
//!    force and the referee;
//!    a tenth of the segments pass exactly through a vertex, where several faces
//!    tie.
//! 2. **2,000 short segments** near the surface: the referee on every face
//!    whose box meets the segment's box (an exact superset of the faces that can
//!    be hit, independent of collide's predicates).
//! 3. collide's BVH against its own brute force, bit for bit, on a subset.
//!
//! parry3d-f64's answers on the 100,000 are compared too, and each
//! disagreement adjudicated (the referee on parry's face); they are counted
//! and printed, not failed — except that parry may never be right where
//! collide is wrong.

use collide::Vec3;
use collide::mesh::{
    MeshBvh, SplitRule, TriMesh, contact_sphere_mesh_brute, contact_sphere_mesh_bvh, intersect_segment_mesh_brute,
    intersect_segment_mesh_bvh,
};
use oracle::geom::{P3, Segment, SegmentHit, Triangle};
use oracle::parry::{Parry64, ParryEngine};
use std::path::Path;

/// Segment parameters (units: fractions of the segment's length), barycentrics
/// and normal components (unitless) from collide and the referee may differ by
/// this much. Reason: collide's hit values are accurate to `ESTIMATE_REL_ERR`
/// (2^−40) of their sums, so `t` and the barycentrics are within
/// `2·2^−40 + 3·2^−53` and the normal's components within about `3·2^−40`; the
/// referee's are correctly rounded. Four times `ESTIMATE_REL_ERR` covers them.
const T_TOL: f64 = 4.0 * collide::exact::ESTIMATE_REL_ERR;

/// The same tolerance for parry3d-f64's `t`, which is computed in plain `f64`
/// (Möller–Trumbore style, with cancellation for long segments): 1e-9 of the
/// segment's length, far above its rounding on the bunny (≈1e-14) and far below
/// any geometric difference between faces.
const PARRY_T_TOL: f64 = 1e-9;

const SEED: u64 = 0x5eed_b0b0_2024_0006;
const POSES: usize = 100;
const SEGMENTS_PER_POSE: usize = 1_000;
const SHORT_SEGMENTS: usize = 2_000;
const BRUTE_SUBSET: usize = 1_000;

use harness::rng::SplitMix64 as Rng;

fn bunny() -> harness::mesh::Mesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/meshes/bunny.obj");
    harness::mesh::load_mesh_file(&path).expect("the bunny loads")
}

/// A random rotation (a uniform unit quaternion) and a translation in
/// [−100, 100]³, applied to every vertex in `f64`.
fn pose(rng: &mut Rng, vertices: &[P3]) -> Vec<P3> {
    let r = rng.rotation();
    let t = [0; 3].map(|_| rng.range(-100.0, 100.0));
    vertices.iter().map(|p| [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + t[i])).collect()
}

fn bounds(vertices: &[P3]) -> (P3, P3) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// A segment through the vertex `v` exactly: `v ± d` with `d` a small multiple
/// of a power of two at least `v`'s ulp, kept only when both endpoints are
/// exact (`(v + d) − v = d` and `v − (v − d) = d`), so the segment's midpoint is
/// `v` itself and every face around `v` not parallel to it ties at `t = 1/2`.
fn through_vertex(rng: &mut Rng, v: P3, scale: f64) -> Option<Segment> {
    let mut a = [0.0; 3];
    let mut b = [0.0; 3];
    for k in 0..3 {
        let ulp = (v[k].abs().max(scale) * f64::EPSILON).max(f64::MIN_POSITIVE);
        let step = 2f64.powi(ulp.log2().ceil() as i32 + 40);
        let d = step * rng.range(-8.0, 8.0).round();
        a[k] = v[k] + d;
        b[k] = v[k] - d;
        #[allow(clippy::float_cmp, reason = "an exactness test")]
        let exact = a[k] - v[k] == d && v[k] - b[k] == d;
        if !exact {
            return None;
        }
    }
    (!collide::exact::points_equal(a, b)).then_some(Segment { start: a, end: b })
}

fn vec3(p: &P3) -> Vec3<f64> {
    Vec3::new(p[0], p[1], p[2])
}

fn collide_segment(s: &Segment) -> collide::Segment<f64> {
    collide::Segment::new(vec3(&s.start), vec3(&s.end))
}

fn triangle(vertices: &[P3], f: [usize; 3]) -> Triangle {
    Triangle { vertices: f.map(|i| vertices[i]) }
}

/// Every face's box (exact: componentwise minimum and maximum).
fn face_boxes(vertices: &[P3], faces: &[[usize; 3]]) -> Vec<(P3, P3)> {
    faces
        .iter()
        .map(|f| {
            let t = f.map(|j| vertices[j]);
            ([0, 1, 2].map(|k| t[0][k].min(t[1][k]).min(t[2][k])), [0, 1, 2].map(|k| t[0][k].max(t[1][k]).max(t[2][k])))
        })
        .collect()
}

/// Faces whose box meets the segment's box: an exact superset of the faces the
/// segment can hit.
fn box_candidates(s: &Segment, boxes: &[(P3, P3)]) -> Vec<usize> {
    let lo = [0, 1, 2].map(|k| s.start[k].min(s.end[k]));
    let hi = [0, 1, 2].map(|k| s.start[k].max(s.end[k]));
    (0..boxes.len())
        .filter(|&i| {
            let (fl, fh) = &boxes[i];
            fl[0] <= hi[0] && lo[0] <= fh[0] && fl[1] <= hi[1] && lo[1] <= fh[1] && fl[2] <= hi[2] && lo[2] <= fh[2]
        })
        .collect()
}

/// The referee's first hit on a subset of the faces, with the face index mapped
/// back to the whole mesh (the subset keeps the mesh's order, so the referee's
/// tie rule — lowest index — is the whole mesh's).
fn referee_on(s: &Segment, vertices: &[P3], faces: &[[usize; 3]], subset: &[usize]) -> Option<(usize, SegmentHit)> {
    // Only the subset's vertices go to the referee (it converts every vertex it
    // is given to a rational), each face as three fresh corners.
    let sub_vertices: Vec<P3> = subset.iter().flat_map(|&i| faces[i].map(|j| vertices[j])).collect();
    let sub: Vec<[usize; 3]> = (0..subset.len()).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
    let a = oracle::referee::intersect_segment_mesh(s, &sub_vertices, &sub).expect("referee");
    a.hit.map(|h| (subset[h.triangle.expect("face")], h))
}

/// collide's hit values against the referee's on the same face: `t` and the
/// barycentrics within [`T_TOL`], the normal's components within [`T_TOL`],
/// each point coordinate within [`T_TOL`] of the segment's length plus the
/// coordinate (a few roundings of the point's own computation).
fn assert_values(got: &collide::mesh::MeshHit<f64>, want: &SegmentHit, s: &Segment, case: &dyn Fn() -> String) {
    assert!((got.t - want.t).abs() <= T_TOL, "t {} vs the referee's {}; {}", got.t, want.t, case());
    let bary = want.barycentric.expect("the referee's barycentrics");
    let len = (0..3).map(|k| (s.end[k] - s.start[k]).abs()).fold(0.0, f64::max);
    for k in 0..3 {
        assert!(
            (got.barycentric[k] - bary[k]).abs() <= T_TOL,
            "barycentric {:?} vs {bary:?}; {}",
            got.barycentric,
            case()
        );
        assert!(
            (got.normal[k] - want.normal[k]).abs() <= T_TOL,
            "normal {:?} vs {:?}; {}",
            got.normal,
            want.normal,
            case()
        );
        let p = want.point[k];
        assert!(
            (got.point[k] - p).abs() <= T_TOL * (len + p.abs()),
            "point {:?} vs {:?}; {}",
            got.point,
            want.point,
            case()
        );
    }
}

#[derive(Default, Debug)]
struct ParryTally {
    agree: usize,
    /// Same `t`, another face of the tie (a known divergence).
    tie_other_face: usize,
    /// parry found no hit where the referee has one.
    missed: usize,
    /// parry's hit is on a face the referee says is not hit, or hit later.
    wrong_face: usize,
    /// Same face, `t` beyond [`PARRY_T_TOL`].
    t_off: usize,
    /// parry hit, the referee says the segment misses.
    false_hit: usize,
}

/// What one pose's segments showed.
#[derive(Default, Debug)]
struct PoseStats {
    checked: usize,
    hits: usize,
    ties: usize,
    parry: ParryTally,
}

/// One pose of the bunny and its [`SEGMENTS_PER_POSE`] segments: every tenth
/// through a vertex exactly (when that can be made exact), two in ten spanning
/// the box (grown by a quarter on each side), the rest shorter (up to 0.4 of the
/// box's size) from a random point of the grown box — short segments keep the
/// brute-force reference cheap, long ones make the BVH prune.
fn check_pose(bunny: &harness::mesh::Mesh, pose_index: usize) -> PoseStats {
    let faces = &bunny.triangles;
    let mut rng = Rng(SEED ^ (pose_index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
    let vertices = pose(&mut rng, &bunny.vertices);
    let (lo, hi) = bounds(&vertices);
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let mesh = TriMesh::new(vertices.iter().map(vec3).collect(), faces.clone()).expect("mesh");
    let rule = if pose_index.is_multiple_of(2) { SplitRule::SahBinned } else { SplitRule::MedianCentroid };
    let bvh = MeshBvh::with_split(mesh, rule);
    let parry_mesh = Parry64.mesh(&vertices, faces).expect("parry mesh");
    let boxes = face_boxes(&vertices, faces);
    let triangles: Vec<collide::Triangle<f64>> = (0..faces.len()).map(|i| bvh.mesh().triangle(i)).collect();
    let mut stats = PoseStats::default();
    for k in 0..SEGMENTS_PER_POSE {
        let point = |rng: &mut Rng| [0, 1, 2].map(|i| rng.range(lo[i] - 0.25 * size, hi[i] + 0.25 * size));
        let through = if k % 10 == 0 {
            let v = vertices[rng.index(vertices.len())];
            through_vertex(&mut rng, v, size)
        } else {
            None
        };
        let s = match through {
            Some(s) => s,
            None if k % 10 < 3 => Segment { start: point(&mut rng), end: point(&mut rng) },
            None => {
                let start = point(&mut rng);
                let len = rng.range(0.0, 0.4 * size);
                let d = [0; 3].map(|_| rng.range(-1.0, 1.0));
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-3);
                Segment { start, end: [0, 1, 2].map(|i| start[i] + d[i] / n * len) }
            }
        };
        let cs = collide_segment(&s);
        let got = intersect_segment_mesh_bvh(&cs, &bvh);
        let case = || format!("seed {SEED:#x}, pose {pose_index}, segment {k}: {s:?}");
        assert!(!got.degenerate && !got.parallel, "{got:?}; {}", case());
        // Every face whose box meets the segment's, through collide's exact
        // single-triangle test; the referee orders the faces hit.
        let hit_faces: Vec<usize> = box_candidates(&s, &boxes)
            .into_iter()
            .filter(|&i| collide::intersect::intersect_segment_triangle(&cs, &triangles[i]).hit.is_some())
            .collect();
        let want = referee_on(&s, &vertices, faces, &hit_faces);
        match (got.hit, want) {
            (None, None) => {}
            (Some(h), Some((face, w))) => {
                assert_eq!(h.triangle, face, "same face as the referee; {}", case());
                assert_values(&h, &w, &s, &case);
                stats.hits += 1;
            }
            (g, w) => panic!("collide {g:?}, referee {w:?}; {}", case()),
        }
        let want = want.map(|(face, w)| (face, w.t));
        if through.is_some() {
            stats.ties += usize::from(hit_faces.len() > 1);
        }
        let p = Parry64.intersect_segment_prepared_mesh(s, &parry_mesh);
        tally_parry(&mut stats.parry, &s, &vertices, faces, &hit_faces, want, p);
        stats.checked += 1;
    }
    stats
}

#[test]
fn bvh_equals_the_referee_on_100k_segments_against_the_posed_bunny() {
    let started = std::time::Instant::now();
    let bunny = bunny();
    // Poses are independent (each seeded from SEED and its index): spread them
    // over the cores.
    let next = std::sync::atomic::AtomicUsize::new(0);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(4);
    let all: Vec<PoseStats> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut mine = Vec::new();
                    loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        if i >= POSES {
                            break mine;
                        }
                        mine.push(check_pose(&bunny, i));
                    }
                })
            })
            .collect();
        workers.into_iter().flat_map(|w| w.join().expect("a pose failed")).collect()
    });
    let mut total = PoseStats::default();
    for p in all {
        total.checked += p.checked;
        total.hits += p.hits;
        total.ties += p.ties;
        let (t, q) = (&mut total.parry, p.parry);
        t.agree += q.agree;
        t.tie_other_face += q.tie_other_face;
        t.missed += q.missed;
        t.wrong_face += q.wrong_face;
        t.t_off += q.t_off;
        t.false_hit += q.false_hit;
    }
    println!(
        "mesh differential: {} segments on {POSES} poses of the bunny (seed {SEED:#x}): {} hits, {} vertex \
         segments with a tie; collide's BVH equal to the referee on all; {:.1} s on {threads} threads",
        total.checked,
        total.hits,
        total.ties,
        started.elapsed().as_secs_f64()
    );
    println!("parry3d-f64 against the referee: {:?}", total.parry);
    assert!(total.checked >= 100_000, "at least 100,000 segments: {}", total.checked);
    assert!(
        total.hits >= total.checked / 10 && total.ties >= 1_000,
        "the segments exercise hits ({}) and ties ({})",
        total.hits,
        total.ties
    );
}

/// Classifies parry's answer against the referee's (`want`, computed on the
/// faces hit), asking the referee about parry's face when it is not among them.
fn tally_parry(
    tally: &mut ParryTally,
    s: &Segment,
    vertices: &[P3],
    faces: &[[usize; 3]],
    hit_faces: &[usize],
    want: Option<(usize, f64)>,
    got: oracle::geom::IntersectAnswer,
) {
    match (got.hit, want) {
        (None, None) => tally.agree += 1,
        (None, Some(_)) => tally.missed += 1,
        (Some(h), Some((wf, wt))) if h.triangle == Some(wf) && (h.t - wt).abs() <= PARRY_T_TOL => tally.agree += 1,
        (Some(h), w) => {
            let face = h.triangle.expect("parry names the face");
            // The referee on parry's face alone: is it hit, and where?
            let alone =
                oracle::referee::intersect_segment_triangle(s, &triangle(vertices, faces[face])).expect("referee");
            match alone.hit {
                None => {
                    assert!(
                        !hit_faces.contains(&face),
                        "collide's triangle test hits face {face}, the referee not: {s:?}"
                    );
                    if w.is_none() {
                        tally.false_hit += 1;
                    } else {
                        tally.wrong_face += 1;
                    }
                }
                Some(a) => {
                    assert!(
                        hit_faces.contains(&face),
                        "the referee hits face {face}, collide's triangle test not: {s:?}"
                    );
                    // The referee's first hit over the faces hit, parry's among them.
                    let (wf, wt) = w.expect("a face is hit");
                    if wf == face {
                        if (h.t - wt).abs() <= PARRY_T_TOL {
                            tally.agree += 1;
                        } else {
                            tally.t_off += 1;
                        }
                    } else if (a.t - wt).abs() <= T_TOL {
                        tally.tie_other_face += 1;
                    } else {
                        tally.wrong_face += 1;
                    }
                }
            }
        }
    }
}

#[test]
fn bvh_equals_the_referee_on_every_candidate_face_for_short_segments() {
    // Independent of collide's predicates: the referee decides every face whose
    // box meets the segment's box.
    let bunny = bunny();
    let faces = bunny.triangles.clone();
    let mut rng = Rng(SEED ^ 0x5407);
    let vertices = pose(&mut rng, &bunny.vertices);
    let bvh = MeshBvh::new(TriMesh::new(vertices.iter().map(vec3).collect(), faces.clone()).expect("mesh"));
    let boxes = face_boxes(&vertices, &faces);
    let mut hits = 0;
    for k in 0..SHORT_SEGMENTS {
        // Around a random point of a random face, half a unit each way.
        let f = triangle(&vertices, faces[rng.index(faces.len())]).vertices;
        let (u, v) = (rng.unit(), rng.unit());
        let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
        let c = [0, 1, 2].map(|i| f[0][i] + u * (f[1][i] - f[0][i]) + v * (f[2][i] - f[0][i]));
        let d = [0; 3].map(|_| rng.range(-0.5, 0.5));
        let s = Segment { start: [0, 1, 2].map(|i| c[i] - d[i]), end: [0, 1, 2].map(|i| c[i] + d[i]) };
        let want = referee_on(&s, &vertices, &faces, &box_candidates(&s, &boxes));
        let got = intersect_segment_mesh_bvh(&collide_segment(&s), &bvh).hit;
        match (got, want) {
            (None, None) => {}
            (Some(h), Some((face, w))) => {
                assert_eq!(h.triangle, face, "short segment {k}: {s:?}");
                assert_values(&h, &w, &s, &|| format!("short segment {k}: {s:?}"));
                hits += 1;
            }
            (g, w) => panic!("short segment {k}: collide {g:?}, referee {w:?}: {s:?}"),
        }
    }
    assert!(hits > SHORT_SEGMENTS / 4, "most short segments cross the surface: {hits}");
}

#[test]
fn bvh_equals_brute_force_bit_for_bit_on_the_bunny() {
    let bunny = bunny();
    let mut rng = Rng(SEED ^ 0xb0);
    let vertices = pose(&mut rng, &bunny.vertices);
    let (lo, hi) = bounds(&vertices);
    let mesh = TriMesh::new(vertices.iter().map(vec3).collect(), bunny.triangles.clone()).expect("mesh");
    let bvh = MeshBvh::new(mesh.clone());
    // Bit for bit is the claim, so the answers are compared with `==`.
    for k in 0..BRUTE_SUBSET {
        let p = |rng: &mut Rng| Vec3::new(rng.range(lo[0], hi[0]), rng.range(lo[1], hi[1]), rng.range(lo[2], hi[2]));
        let s = collide::Segment::new(p(&mut rng), p(&mut rng));
        assert_eq!(intersect_segment_mesh_bvh(&s, &bvh), intersect_segment_mesh_brute(&s, &mesh), "segment {k}");
        let sphere = collide::Sphere::new(s.start, rng.range(0.0, 1.5));
        assert_eq!(contact_sphere_mesh_bvh(&sphere, &bvh), contact_sphere_mesh_brute(&sphere, &mesh), "sphere {k}");
    }
}

#[test]
fn the_bunny_fixture_is_the_package_mesh() {
    // fixtures/meshes/README.md: counts, no zero-area face, the box.
    let bunny = bunny();
    assert_eq!((bunny.vertices.len(), bunny.triangles.len()), (1_839, 3_674));
    let mesh = TriMesh::new(bunny.vertices.iter().map(vec3).collect(), bunny.triangles.clone()).expect("mesh");
    assert_eq!(mesh.degenerate_face_count(), 0);
    // Exact: a box selects input coordinates, no arithmetic.
    let bb = mesh.aabb().expect("box");
    assert_eq!(bb.min, Vec3::new(-4.958475, -0.003149, -3.729833));
    assert_eq!(bb.max, Vec3::new(4.94885, 9.654748, 3.810639));
}
