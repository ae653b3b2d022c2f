//! The scene section's run: the scenes built, every level's queries counted
//! and timed, the bounding spheres' tightness measured.

use super::data::{
    CLOUD_FAMILIES, CLOUD_SIZES, CloudTightness, Level, LevelStats, METHODS, SceneNeeds, SceneReport, TightnessStats,
};
use crate::defaults::TIMING_REPS;
use crate::rng::SplitMix64 as Rng;
use crate::summary::Timing;
use collide::bounds::{
    BoundingSphere, aabb_of_segment, aabb_of_sphere, bounding_sphere_centroid, bounding_sphere_minimal,
    bounding_sphere_ritter, test_aabb_aabb,
};
use collide::contact::contact_sphere_sphere;
use collide::mesh::{MeshBvh, TriMesh, intersect_segment_mesh_brute, intersect_segment_mesh_bvh};
use collide::{Aabb, Segment, Sphere, Vec3};
use oracle::geom::P3;
use oracle::parry::{Parry64, ParryEngine};
use std::path::PathBuf;

/// Radius of every scattered sphere (scene units).
pub const SCATTER_RADIUS: f64 = 0.5;

/// Half the side of the cube the scattered spheres' centres fill: with the
/// default 256 spheres, about one per 1000 cubic units — a sparse scene, where
/// the whole scene's bounds hold mostly empty space.
pub const SCATTER_HALF_SIDE: f64 = 20.0;

/// Query spheres' radii are uniform in `[SCATTER_RADIUS, QUERY_RADIUS_MAX]`.
pub const QUERY_RADIUS_MAX: f64 = 3.0;

/// The query regions grow the scene's box by this fraction of its largest size
/// on each side (bunny segments: 1, so that about half the segments miss its
/// box; sphere queries: 1/4 of the cube).
const BUNNY_GROW: f64 = 1.0;
const SCATTER_GROW: f64 = 0.25;

/// Most spheres in a leaf of [`SphereTree`].
pub const SPHERE_LEAF: usize = 4;

/// How far below 1 a tightness may fall through rounding alone. An enclosing
/// sphere's exact radius is at least the minimal one; a computed radius (the
/// largest computed distance to a point) may fall below the exact enclosing
/// radius by about `3ε` of it (collide's documented guarantee; parry's by as
/// much), and the referee's minimal radius is correctly rounded (`ε/2`).
/// `8ε` covers both.
pub const TIGHTNESS_ROUNDING: f64 = 8.0 * f64::EPSILON;

/// How far collide's minimal sphere may lie from the exact minimal radius,
/// relative. collide documents an excess of at most `64ε` times the scene's
/// size (at most `2·r_min`), so `128ε`, plus its support constructions'
/// rounding (a few tens of `ε` on well-shaped support sets); `1024ε`
/// (2.3e-13) leaves room for less well-shaped ones. Measured on the report's
/// default clouds and rotations: at most `4ε`.
pub const MINIMAL_TIGHTNESS_TOL: f64 = 1024.0 * f64::EPSILON;

/// What the section runs.
#[derive(Clone, Debug)]
pub struct SceneSettings {
    /// Seed of every random draw (queries, sphere positions, rotations, clouds).
    pub seed: u64,
    /// Whether to time the levels (off: no times, and the cheapest lossless
    /// level is chosen by exact tests per query).
    pub timing: bool,
    /// The bunny's OBJ file (by default the built-in fixtures' own,
    /// `fixtures/meshes/bunny.obj`, embedded in the binary).
    pub bunny: PathBuf,
    /// Segment queries against the bunny.
    pub bunny_queries: usize,
    /// Of those, how many are timed (the brute-force levels cost a few hundred
    /// microseconds a query).
    pub bunny_timed: usize,
    /// Scattered spheres.
    pub spheres: usize,
    /// Sphere queries against them (all timed).
    pub sphere_queries: usize,
    /// Random rotations of the bunny for the tightness measure.
    pub rotations: usize,
    /// Random clouds per size and family for the tightness measure.
    pub clouds_per_size: usize,
}

impl Default for SceneSettings {
    fn default() -> Self {
        Self {
            seed: 0x5ce4_e0ee_d500_0006,
            timing: true,
            bunny: PathBuf::from(crate::builtin::SHOWN).join("meshes/bunny.obj"),
            bunny_queries: 2_000,
            bunny_timed: 200,
            spheres: 256,
            sphere_queries: 2_000,
            rotations: 24,
            clouds_per_size: 8,
        }
    }
}

/// What one level did with one query.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outcome {
    /// The cheap test let it through.
    pub passed: bool,
    /// The level's answer reports a contact.
    pub contact: bool,
    /// Elements tested exactly.
    pub exact_tests: usize,
}

// ---------------------------------------------------------------------------
// Counting

/// The statistics of one level from its outcomes and the truth (per query:
/// in contact), with its timing.
pub fn level_stats(level: Level, truth: &[bool], outcomes: &[Outcome], timing: Option<Timing>) -> LevelStats {
    let misses = truth.iter().filter(|t| !**t).count();
    let passed = outcomes.iter().filter(|o| o.passed).count();
    let false_positives = truth.iter().zip(outcomes).filter(|(t, o)| !**t && o.passed).count();
    let lost = truth.iter().zip(outcomes).filter(|(t, o)| **t && !o.contact).count();
    let tests: usize = outcomes.iter().map(|o| o.exact_tests).sum();
    LevelStats {
        level,
        passed,
        false_positives,
        false_positive_rate: (misses > 0).then(|| false_positives as f64 / misses as f64),
        lost,
        exact_tests_per_query: if outcomes.is_empty() { 0.0 } else { tests as f64 / outcomes.len() as f64 },
        timing,
    }
}

/// The cheapest level that loses no contact: the smallest median time when
/// every lossless level was timed, else the fewest exact tests per query; ties
/// to the earlier level. With what it was judged by.
pub fn cheapest_lossless(levels: &[LevelStats]) -> (Option<usize>, &'static str) {
    let lossless: Vec<usize> = (0..levels.len()).filter(|&i| levels[i].lost == 0).collect();
    let timed = !lossless.is_empty() && lossless.iter().all(|&i| levels[i].timing.is_some());
    let cost = |i: usize| {
        if timed {
            levels[i].timing.as_ref().map_or(f64::INFINITY, |t| t.median_ns)
        } else {
            levels[i].exact_tests_per_query
        }
    };
    let best = lossless.into_iter().fold(None, |b: Option<usize>, i| match b {
        Some(j) if cost(j) <= cost(i) => Some(j),
        _ => Some(i),
    });
    (best, if timed { "time" } else { "exact tests" })
}

/// Times `f` over `queries`: [`TIMING_REPS`] repetitions of one loop, each
/// input and answer through `black_box`; median, fastest and slowest per query.
fn time_loop<Q, R>(queries: &[Q], f: impl Fn(&Q) -> R) -> Option<Timing> {
    crate::timing::time_each(TIMING_REPS, queries, f)
}

// ---------------------------------------------------------------------------
// Random draws

fn v(p: P3) -> Vec3<f64> {
    Vec3::new(p[0], p[1], p[2])
}

fn bounds(points: &[P3]) -> (P3, P3) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// A point uniform in the box `(lo, hi)` grown by `grow` times its largest
/// size on each side.
fn point_in_grown(rng: &mut Rng, (lo, hi): (P3, P3), grow: f64) -> P3 {
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    [0, 1, 2].map(|k| rng.range(lo[k] - grow * size, hi[k] + grow * size))
}

// ---------------------------------------------------------------------------
// Cheap tests

/// The whole scene's bounding spheres, one per method, in [`Level`] order
/// (centroid, Ritter, minimal).
fn scene_spheres(points: &[Vec3<f64>]) -> Option<[BoundingSphere<f64>; 3]> {
    Some([bounding_sphere_centroid(points)?, bounding_sphere_ritter(points)?, bounding_sphere_minimal(points)?])
}

/// Whether the segment meets the closed ball: the squared distance from the
/// centre to the segment's closest point `q0 + t d`,
/// `t = clamp((c − q0)·d / d·d, 0, 1)` (`t = 0` for a point), against `r²`, in
/// `f64` — the test a reader would write; not conservative by construction
/// (rounding), which the "lost" column would show.
pub fn segment_meets_ball(q0: P3, q1: P3, center: P3, radius: f64) -> bool {
    let d = [0, 1, 2].map(|k| q1[k] - q0[k]);
    let w = [0, 1, 2].map(|k| center[k] - q0[k]);
    let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let t = if dd > 0.0 { ((w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd).clamp(0.0, 1.0) } else { 0.0 };
    let e = [0, 1, 2].map(|k| q0[k] + t * d[k] - center[k]);
    e[0] * e[0] + e[1] * e[1] + e[2] * e[2] <= radius * radius
}

/// An oriented box: `center + Σ uᵢ axesᵢ`, `|uᵢ| ≤ half[i]`, the axes orthonormal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb {
    /// Centre.
    pub center: P3,
    /// Orthonormal axes.
    pub axes: [P3; 3],
    /// Half-extents along them.
    pub half: P3,
}

/// The oriented box's growth on each side, relative to the largest
/// coordinate of the points: its axes, projections and centre are computed
/// in `f64` (a few roundings of size `2⁻⁵³` of that coordinate each), so a
/// point of the mesh could lie a rounding outside the box it was measured
/// into; `1e-12` is far above those roundings and far below the scene's
/// size, so the level stays conservative (no contact lost to rounding) and as
/// tight as measured.
pub const OBB_PAD_REL: f64 = 1e-12;

/// Jacobi sweeps of the symmetric 3×3 eigenproblem: more than enough for the
/// off-diagonal to fall below the diagonal's rounding (each sweep squares it).
const JACOBI_SWEEPS: usize = 16;

/// The oriented box of `points` along their principal axes — the
/// eigenvectors of their covariance (Jacobi rotations), the extents the
/// points' projections on them — as a textbook builds it, grown by
/// [`OBB_PAD_REL`] so that it encloses every point despite the roundings;
/// `None` for no point.
pub fn obb_of_points(points: &[P3]) -> Option<Obb> {
    let n = points.len() as f64;
    if points.is_empty() {
        return None;
    }
    let mean = [0, 1, 2].map(|k| points.iter().map(|p| p[k] / n).sum::<f64>());
    let mut c = [[0.0; 3]; 3];
    for p in points {
        let d = [0, 1, 2].map(|k| p[k] - mean[k]);
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] += d[i] * d[j] / n;
            }
        }
    }
    // v's columns become the eigenvectors.
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..JACOBI_SWEEPS {
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if c[p][q] == 0.0 {
                continue;
            }
            let theta = (c[q][q] - c[p][p]) / (2.0 * c[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let (cs, sn) = (1.0 / (t * t + 1.0).sqrt(), t / (t * t + 1.0).sqrt());
            for row in &mut c {
                let (a, b) = (row[p], row[q]);
                row[p] = cs * a - sn * b;
                row[q] = sn * a + cs * b;
            }
            let (rp, rq) = (c[p], c[q]);
            c[p] = std::array::from_fn(|k| cs * rp[k] - sn * rq[k]);
            c[q] = std::array::from_fn(|k| sn * rp[k] + cs * rq[k]);
            for row in &mut v {
                let (a, b) = (row[p], row[q]);
                row[p] = cs * a - sn * b;
                row[q] = sn * a + cs * b;
            }
        }
    }
    let axes = [0, 1, 2].map(|j| [v[0][j], v[1][j], v[2][j]]);
    let dot = |a: P3, b: P3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in points {
        for j in 0..3 {
            let x = dot(*p, axes[j]);
            lo[j] = lo[j].min(x);
            hi[j] = hi[j].max(x);
        }
    }
    let mid = [0, 1, 2].map(|j| (lo[j] + hi[j]) / 2.0);
    let center = [0, 1, 2].map(|k| (0..3).map(|j| mid[j] * axes[j][k]).sum::<f64>());
    let size = points.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let pad = OBB_PAD_REL * size;
    Some(Obb { center, axes, half: [0, 1, 2].map(|j| (hi[j] - lo[j]) / 2.0 + pad) })
}

/// Whether the segment meets the oriented box: its ends in the box's frame,
/// then the slab test (the entering parameter at most the leaving one within
/// `[0, 1]`), in `f64` — the test a reader would write.
pub fn segment_meets_obb(q0: P3, q1: P3, b: &Obb) -> bool {
    let local = |p: P3| {
        let d = [0, 1, 2].map(|k| p[k] - b.center[k]);
        [0, 1, 2].map(|j| d[0] * b.axes[j][0] + d[1] * b.axes[j][1] + d[2] * b.axes[j][2])
    };
    let (a, e) = (local(q0), local(q1));
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for j in 0..3 {
        let d = e[j] - a[j];
        let h = b.half[j];
        if d == 0.0 {
            if a[j].abs() > h {
                return false;
            }
            continue;
        }
        let (u, w) = ((-h - a[j]) / d, (h - a[j]) / d);
        t0 = t0.max(u.min(w));
        t1 = t1.min(u.max(w));
        if t0 > t1 {
            return false;
        }
    }
    true
}

fn p3(v: &Vec3<f64>) -> P3 {
    [v.x, v.y, v.z]
}

// ---------------------------------------------------------------------------
// Mesh scene: segments against a mesh

/// The levels of a mesh scene queried by segments: the statistics per level
/// (timed on the first `timed` queries when `timing`), and the queries in
/// contact. The truth is the brute-force query (every face, exactly).
pub fn mesh_levels(mesh: &TriMesh<f64>, segments: &[(P3, P3)], timing: bool, timed: usize) -> (Vec<LevelStats>, usize) {
    let points: Vec<Vec3<f64>> = mesh.vertices().to_vec();
    let bvh = MeshBvh::new(mesh.clone());
    let segs: Vec<Segment<f64>> = segments.iter().map(|(a, b)| Segment::new(v(*a), v(*b))).collect();
    let faces = mesh.len();
    let truth: Vec<bool> = segs.iter().map(|s| intersect_segment_mesh_brute(s, mesh).hit.is_some()).collect();
    let contacts = truth.iter().filter(|t| **t).count();
    let spheres = scene_spheres(&points);
    let aabb = mesh.aabb();
    let obb = obb_of_points(&points.iter().map(p3).collect::<Vec<_>>());
    let timed_segs = &segs[..timed.min(segs.len())];
    let time = |f: &dyn Fn(&Segment<f64>) -> bool| if timing { time_loop(timed_segs, f) } else { None };
    let brute = |s: &Segment<f64>| intersect_segment_mesh_brute(s, mesh).hit.is_some();
    // A level that tests one bounding volume first and, when it passes, every
    // face exactly.
    let filtered = |cheap: &dyn Fn(&Segment<f64>) -> bool| -> (Vec<Outcome>, Option<Timing>) {
        let outcomes = segs
            .iter()
            .zip(&truth)
            .map(|(s, &t)| {
                let passed = cheap(s);
                Outcome { passed, contact: passed && t, exact_tests: if passed { faces } else { 0 } }
            })
            .collect();
        (outcomes, time(&|s| cheap(s) && brute(s)))
    };
    let mut out = Vec::new();
    for level in Level::ALL {
        let (outcomes, timing): (Vec<Outcome>, Option<Timing>) = match level {
            Level::None => (
                truth.iter().map(|&t| Outcome { passed: true, contact: t, exact_tests: faces }).collect(),
                time(&brute),
            ),
            Level::SphereCentroid | Level::SphereRitter | Level::SphereMinimal => {
                let Some(spheres) = spheres else { continue };
                let b = spheres[level.sphere_method()];
                let (c, r) = (p3(&b.center), b.radius);
                filtered(&|s| segment_meets_ball(p3(&s.start), p3(&s.end), c, r))
            }
            Level::Aabb => {
                let Some(bb) = aabb else { continue };
                filtered(&|s| test_aabb_aabb(&aabb_of_segment(s), &bb))
            }
            Level::Obb => {
                let Some(ob) = obb else { continue };
                filtered(&|s| segment_meets_obb(p3(&s.start), p3(&s.end), &ob))
            }
            Level::Bvh => {
                let mut near = Vec::new();
                let outcomes = segs
                    .iter()
                    .map(|s| {
                        bvh.faces_near_segment(s, &mut near);
                        Outcome {
                            passed: !near.is_empty(),
                            contact: intersect_segment_mesh_bvh(s, &bvh).hit.is_some(),
                            exact_tests: near.len(),
                        }
                    })
                    .collect();
                (outcomes, time(&|s| intersect_segment_mesh_bvh(s, &bvh).hit.is_some()))
            }
        };
        out.push(level_stats(level, &truth, &outcomes, timing));
    }
    (out, contacts)
}

/// The quaternion `[w, x, y, z]` the turned bunny is rotated by: `‖q‖ = 5`, so
/// its rotation's entries are multiples of `1/25` (an oblique turn, about
/// 47° about `(1, 2, 2)/3`), fixed so the scene is the same in every run.
pub const BUNNY_TURN: [f64; 4] = [4.0, 1.0, 2.0, 2.0];

fn bunny_scene(settings: &SceneSettings, turned: bool) -> Result<SceneNeeds, String> {
    let bunny = crate::mesh::load_mesh_builtin_or_file(&settings.bunny)?;
    let r = crashtest_core::geom::rotation_matrix(BUNNY_TURN);
    let vertices: Vec<P3> =
        if turned { bunny.vertices.iter().map(|p| rotate(&r, p)).collect() } else { bunny.vertices };
    let mesh = TriMesh::new(vertices.iter().map(|p| v(*p)).collect(), bunny.triangles.clone())
        .map_err(|e| format!("{}: {e}", settings.bunny.display()))?;
    let mut rng = Rng(settings.seed ^ 0xb0b0);
    let b = bounds(&vertices);
    let segments: Vec<(P3, P3)> = (0..settings.bunny_queries)
        .map(|_| (point_in_grown(&mut rng, b, BUNNY_GROW), point_in_grown(&mut rng, b, BUNNY_GROW)))
        .collect();
    let timed = if settings.timing { settings.bunny_timed.min(segments.len()) } else { 0 };
    let (levels, contacts) = mesh_levels(&mesh, &segments, settings.timing, timed);
    let (cheapest, by) = cheapest_lossless(&levels);
    let (name, turn) = if turned {
        ("The bunny turned, queried by segments", format!(", turned by the quaternion {BUNNY_TURN:?}"))
    } else {
        ("The bunny, queried by segments", String::new())
    };
    Ok(SceneNeeds {
        name: name.into(),
        description: format!(
            "{} faces{turn}; {} segments with both endpoints uniform in the bunny's box grown by {BUNNY_GROW} of \
             its largest size on each side; exact test: collide's robust segment–mesh first hit over every face",
            mesh.len(),
            segments.len()
        ),
        elements: mesh.len(),
        queries: segments.len(),
        contacts,
        timed_queries: timed,
        levels,
        cheapest_lossless: cheapest,
        cheapest_by: by.into(),
    })
}

// ---------------------------------------------------------------------------
// Scattered spheres: spheres against spheres

/// A binary AABB tree over spheres: median split on the longest axis of the
/// centres' box, leaves of at most [`SPHERE_LEAF`] spheres, every node's box
/// the union of its spheres' boxes (collide's `aabb_of_sphere`), so a query
/// box that misses a node's box misses all of its spheres.
pub struct SphereTree {
    nodes: Vec<TreeNode>,
    order: Vec<usize>,
}

struct TreeNode {
    bb: Aabb<f64>,
    /// Leaf: `order[start..start + count]`; internal (`count == 0`): children
    /// at `start` and `start + 1`.
    start: usize,
    count: usize,
}

impl SphereTree {
    /// Builds the tree (`None` for no spheres).
    pub fn new(spheres: &[Sphere<f64>]) -> Option<Self> {
        if spheres.is_empty() {
            return None;
        }
        let mut tree = SphereTree { nodes: Vec::new(), order: (0..spheres.len()).collect() };
        tree.nodes.push(TreeNode { bb: Aabb::new(Vec3::zeros(), Vec3::zeros()), start: 0, count: 0 });
        let mut pending = vec![(0usize, 0usize, spheres.len())];
        while let Some((node, lo, hi)) = pending.pop() {
            let ids = &mut tree.order[lo..hi];
            let bb = ids
                .iter()
                .map(|&i| aabb_of_sphere(&spheres[i]))
                .reduce(|a, b| Aabb::new(a.min.zip_map(&b.min, f64::min), a.max.zip_map(&b.max, f64::max)));
            let Some(bb) = bb else { continue };
            tree.nodes[node].bb = bb;
            if ids.len() <= SPHERE_LEAF {
                tree.nodes[node].start = lo;
                tree.nodes[node].count = ids.len();
                continue;
            }
            let ext = bb.max - bb.min;
            let axis = if ext.x >= ext.y && ext.x >= ext.z {
                0
            } else if ext.y >= ext.z {
                1
            } else {
                2
            };
            let mid = ids.len() / 2;
            ids.select_nth_unstable_by(mid, |a, b| {
                spheres[*a].center[axis].total_cmp(&spheres[*b].center[axis]).then(a.cmp(b))
            });
            let first = tree.nodes.len();
            for _ in 0..2 {
                tree.nodes.push(TreeNode { bb, start: 0, count: 0 });
            }
            tree.nodes[node].start = first;
            pending.push((first, lo, lo + mid));
            pending.push((first + 1, lo + mid, hi));
        }
        Some(tree)
    }

    /// Calls `f` with every sphere of every leaf whose box the query box
    /// meets. No allocation: the pending nodes sit in a fixed array (the
    /// median split halves every node, so the depth is at most
    /// `log2(n) + 1 < 64`).
    pub fn for_each_near(&self, query: &Aabb<f64>, mut f: impl FnMut(usize)) {
        let mut stack = [0usize; 64];
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let n = &self.nodes[stack[sp]];
            if !test_aabb_aabb(query, &n.bb) {
                continue;
            }
            if n.count > 0 {
                self.order[n.start..n.start + n.count].iter().for_each(|&i| f(i));
            } else if sp + 2 <= stack.len() {
                stack[sp] = n.start;
                stack[sp + 1] = n.start + 1;
                sp += 2;
            }
        }
    }

    /// The spheres of every leaf whose box the query box meets, appended to
    /// `out` (cleared first).
    pub fn near(&self, query: &Aabb<f64>, out: &mut Vec<usize>) {
        out.clear();
        self.for_each_near(query, |i| out.push(i));
    }
}

/// Contacts of `q` with the spheres `ids` (collide's robust sphere–sphere
/// contact; touching counts).
fn contacts_among(q: &Sphere<f64>, spheres: &[Sphere<f64>], ids: impl Iterator<Item = usize>) -> usize {
    ids.filter(|&i| contact_sphere_sphere(q, &spheres[i]).is_some()).count()
}

/// The levels of a scene of spheres queried by spheres (all contacts wanted):
/// statistics per level (timed when `timing`), and the queries in contact.
/// The whole scene's bounding spheres enclose the centres with the largest
/// radius added (the minimal one is then the minimal sphere enclosing spheres
/// of equal radii).
pub fn sphere_levels(spheres: &[Sphere<f64>], queries: &[Sphere<f64>], timing: bool) -> (Vec<LevelStats>, usize) {
    let n = spheres.len();
    let all = |q: &Sphere<f64>| contacts_among(q, spheres, 0..n);
    let truth: Vec<bool> = queries.iter().map(|q| all(q) > 0).collect();
    let contacts = truth.iter().filter(|t| **t).count();
    let centres: Vec<Vec3<f64>> = spheres.iter().map(|s| s.center).collect();
    let r_max = spheres.iter().map(|s| s.radius).fold(0.0, f64::max);
    let bounding = scene_spheres(&centres).map(|b| b.map(|b| Sphere::new(b.center, b.radius + r_max)));
    let scene_box = spheres
        .iter()
        .map(aabb_of_sphere)
        .reduce(|a, b| Aabb::new(a.min.zip_map(&b.min, f64::min), a.max.zip_map(&b.max, f64::max)));
    let tree = SphereTree::new(spheres);
    let time = |f: &dyn Fn(&Sphere<f64>) -> usize| if timing { time_loop(queries, f) } else { None };
    let mut out = Vec::new();
    for level in Level::ALL {
        let gated =
            |passed: bool, t: bool| Outcome { passed, contact: passed && t, exact_tests: if passed { n } else { 0 } };
        let (outcomes, timing): (Vec<Outcome>, Option<Timing>) = match level {
            Level::None => (truth.iter().map(|&t| gated(true, t)).collect(), time(&all)),
            Level::SphereCentroid | Level::SphereRitter | Level::SphereMinimal => {
                let Some(b) = bounding else { continue };
                let b = b[level.sphere_method()];
                let cheap = |q: &Sphere<f64>| contact_sphere_sphere(q, &b).is_some();
                let outcomes = queries.iter().zip(&truth).map(|(q, &t)| gated(cheap(q), t)).collect();
                (outcomes, time(&|q| if cheap(q) { all(q) } else { 0 }))
            }
            // The spheres' scene is the analytic one (a sphere stays a
            // sphere): an oriented box of it is not measured.
            Level::Obb => continue,
            Level::Aabb => {
                let Some(bb) = scene_box else { continue };
                let cheap = |q: &Sphere<f64>| test_aabb_aabb(&aabb_of_sphere(q), &bb);
                let outcomes = queries.iter().zip(&truth).map(|(q, &t)| gated(cheap(q), t)).collect();
                (outcomes, time(&|q| if cheap(q) { all(q) } else { 0 }))
            }
            Level::Bvh => {
                let Some(tree) = &tree else { continue };
                let mut near = Vec::new();
                let outcomes = queries
                    .iter()
                    .map(|q| {
                        tree.near(&aabb_of_sphere(q), &mut near);
                        Outcome {
                            passed: !near.is_empty(),
                            contact: contacts_among(q, spheres, near.iter().copied()) > 0,
                            exact_tests: near.len(),
                        }
                    })
                    .collect();
                let timed = |q: &Sphere<f64>| {
                    let mut count = 0usize;
                    tree.for_each_near(&aabb_of_sphere(q), |i| {
                        count += usize::from(contact_sphere_sphere(q, &spheres[i]).is_some());
                    });
                    count
                };
                (outcomes, time(&timed))
            }
        };
        out.push(level_stats(level, &truth, &outcomes, timing));
    }
    (out, contacts)
}

fn scatter_scene(settings: &SceneSettings) -> SceneNeeds {
    let mut rng = Rng(settings.seed ^ 0x5ca7);
    let h = SCATTER_HALF_SIDE;
    let spheres: Vec<Sphere<f64>> =
        (0..settings.spheres).map(|_| Sphere::new(v([0; 3].map(|_| rng.range(-h, h))), SCATTER_RADIUS)).collect();
    let b = ([-h; 3], [h; 3]);
    let queries: Vec<Sphere<f64>> = (0..settings.sphere_queries)
        .map(|_| Sphere::new(v(point_in_grown(&mut rng, b, SCATTER_GROW)), rng.range(SCATTER_RADIUS, QUERY_RADIUS_MAX)))
        .collect();
    let (levels, contacts) = sphere_levels(&spheres, &queries, settings.timing);
    let (cheapest, by) = cheapest_lossless(&levels);
    SceneNeeds {
        name: "Scattered spheres, queried by spheres".into(),
        description: format!(
            "{} spheres of radius {SCATTER_RADIUS}, centres uniform in [−{h}, {h}]³; {} query spheres, radius \
             uniform in [{SCATTER_RADIUS}, {QUERY_RADIUS_MAX}], centres uniform in that cube grown by {SCATTER_GROW} \
             of its side on each side; every contact wanted; exact test: collide's sphere–sphere contact",
            spheres.len(),
            queries.len()
        ),
        elements: spheres.len(),
        queries: queries.len(),
        contacts,
        timed_queries: if settings.timing { queries.len() } else { 0 },
        levels,
        cheapest_lossless: cheapest,
        cheapest_by: by.into(),
    }
}

// ---------------------------------------------------------------------------
// Tightness

/// Each method's radius over the exact minimal radius (the referee's), in
/// [`METHODS`] order; `None` when a method or the referee gives no sphere, or
/// the minimal radius is 0.
pub fn tightness(points: &[P3]) -> Option<[f64; 4]> {
    let r_min = oracle::referee::bounds::min_ball(points).ok()?.radius;
    if r_min.is_nan() || r_min <= 0.0 {
        return None;
    }
    let vs: Vec<Vec3<f64>> = points.iter().map(|p| v(*p)).collect();
    let radii = [
        bounding_sphere_centroid(&vs)?.radius,
        bounding_sphere_ritter(&vs)?.radius,
        Parry64.bounding_sphere_of_points(points)?.radius,
        bounding_sphere_minimal(&vs)?.radius,
    ];
    Some(radii.map(|r| r / r_min))
}

fn stats(per_cloud: &[[f64; 4]]) -> Vec<TightnessStats> {
    METHODS
        .iter()
        .enumerate()
        .map(|(m, name)| {
            let values: Vec<f64> = per_cloud.iter().map(|t| t[m]).collect();
            let n = values.len().max(1) as f64;
            TightnessStats {
                method: (*name).into(),
                mean: values.iter().sum::<f64>() / n,
                min: values.iter().copied().fold(f64::INFINITY, f64::min),
                max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                values,
            }
        })
        .collect()
}

fn cloud(rng: &mut Rng, family: usize, n: usize) -> Vec<P3> {
    (0..n)
        .map(|_| match family {
            0 => [0; 3].map(|_| rng.range(-1.0, 1.0)),
            _ => [0; 3].map(|_| rng.normal()),
        })
        .collect()
}

fn rotate(r: &[[f64; 3]; 3], p: &P3) -> P3 {
    [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2])
}

// ---------------------------------------------------------------------------
// The section

/// Runs everything the section measures.
pub fn run(settings: &SceneSettings) -> SceneReport {
    let mut scenes = Vec::new();
    let mut problems = Vec::new();
    let bunny = match crate::mesh::load_mesh_builtin_or_file(&settings.bunny) {
        Ok(b) => Some(b),
        Err(e) => {
            problems.push(format!("the bunny scene and its tightness were not measured: {e}"));
            None
        }
    };
    if bunny.is_some() {
        for turned in [false, true] {
            match bunny_scene(settings, turned) {
                Ok(s) => scenes.push(s),
                Err(e) => problems.push(format!("the bunny scene was not measured: {e}")),
            }
        }
    }
    scenes.push(scatter_scene(settings));
    let mut rng = Rng(settings.seed ^ 0x7167);
    let bunny_tightness = match &bunny {
        Some(b) => {
            let per: Vec<[f64; 4]> = (0..settings.rotations)
                .filter_map(|_| {
                    let r = rng.rotation();
                    tightness(&b.vertices.iter().map(|p| rotate(&r, p)).collect::<Vec<_>>())
                })
                .collect();
            stats(&per)
        }
        None => Vec::new(),
    };
    let mut cloud_tightness = Vec::new();
    for (family, name) in CLOUD_FAMILIES.iter().enumerate() {
        for &n in &CLOUD_SIZES {
            let per: Vec<[f64; 4]> =
                (0..settings.clouds_per_size).filter_map(|_| tightness(&cloud(&mut rng, family, n))).collect();
            cloud_tightness.push(CloudTightness { family: (*name).into(), points: n, methods: stats(&per) });
        }
    }
    SceneReport { seed: settings.seed, scenes, problems, bunny_tightness, cloud_tightness }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outcome(passed: bool, contact: bool, exact_tests: usize) -> Outcome {
        Outcome { passed, contact, exact_tests }
    }

    fn timing(median_ns: f64) -> Option<Timing> {
        Some(Timing { median_ns, min_ns: median_ns, max_ns: median_ns, reps: 1, queries: 1 })
    }

    fn stats_with(level: Level, lost: usize, tests: f64, t: Option<Timing>) -> LevelStats {
        LevelStats {
            level,
            passed: 0,
            false_positives: 0,
            false_positive_rate: None,
            lost,
            exact_tests_per_query: tests,
            timing: t,
        }
    }

    /// How closely the principal axes of a box's eight corners recover its
    /// half-extents: the Jacobi sweeps converge to the covariance's rounding,
    /// far below this, and [`OBB_PAD_REL`] adds `1e-12` of the size.
    const OBB_RECOVERY_TOL: f64 = 1e-9;

    #[test]
    fn scene_obb_of_a_turned_box_is_the_box() {
        let r = crashtest_core::geom::rotation_matrix(BUNNY_TURN);
        let half = [3.0, 2.0, 1.0];
        let center = [10.0, -4.0, 2.5];
        let corners: Vec<P3> = (0..8)
            .map(|k| {
                let u = [0, 1, 2].map(|i| if k >> i & 1 == 1 { half[i] } else { -half[i] });
                let p = rotate(&r, &u);
                [0, 1, 2].map(|i| p[i] + center[i])
            })
            .collect();
        let ob = obb_of_points(&corners).expect("eight points");
        let mut got = ob.half;
        got.sort_by(f64::total_cmp);
        for (g, w) in got.iter().zip([1.0, 2.0, 3.0]) {
            assert!((g - w).abs() <= OBB_RECOVERY_TOL * w, "half-extents {:?}", ob.half);
        }
        for (got, want) in ob.center.iter().zip(center) {
            assert!((got - want).abs() <= OBB_RECOVERY_TOL * 10.0, "centre {:?}", ob.center);
        }
        // A segment through the centre meets it; one beside a corner of the
        // turned box, inside the box's AABB but outside the box, does not.
        assert!(segment_meets_obb([0.0, 0.0, 0.0], [20.0, -8.0, 5.0], &ob));
        let aabb_max = [0, 1, 2].map(|i| corners.iter().map(|p| p[i]).fold(f64::NEG_INFINITY, f64::max));
        let near_corner = [0, 1, 2].map(|i| aabb_max[i] - 0.01);
        let inside = |p: P3| {
            let d = [0, 1, 2].map(|i| p[i] - center[i]);
            (0..3).all(|j| (d[0] * r[0][j] + d[1] * r[1][j] + d[2] * r[2][j]).abs() <= half[j])
        };
        assert!(!inside(near_corner), "the AABB's corner region is outside the turned box");
        assert!(!segment_meets_obb(near_corner, near_corner, &ob));
        assert!(obb_of_points(&[]).is_none());
    }

    #[test]
    fn scene_the_oriented_box_loses_no_contact_on_either_bunny() {
        let settings = SceneSettings { timing: false, bunny_queries: 300, ..SceneSettings::default() };
        for turned in [false, true] {
            let scene = bunny_scene(&settings, turned).expect("the built-in bunny");
            let obb = scene.levels.iter().find(|l| l.level == Level::Obb).expect("an OBB row");
            assert_eq!(obb.lost, 0, "{}: the oriented box lost contacts", scene.name);
            assert!(obb.passed >= scene.contacts, "{}", scene.name);
        }
    }

    #[test]
    fn scene_level_stats_count_false_positives_among_misses_and_lost_contacts() {
        let truth = [true, false, false, true, false];
        let outcomes = [
            outcome(true, true, 4),
            outcome(true, false, 4),
            outcome(false, false, 0),
            outcome(false, false, 0),
            outcome(false, false, 0),
        ];
        let s = level_stats(Level::Aabb, &truth, &outcomes, None);
        assert_eq!((s.passed, s.false_positives, s.lost), (2, 1, 1));
        assert_eq!(s.false_positive_rate.map(|r| (r * 3.0).round()), Some(1.0), "1 of 3 misses passed");
        assert!((s.exact_tests_per_query - 1.6).abs() < 1e-12, "8 tests over 5 queries");
        // Every query in contact: no rate.
        let all = level_stats(Level::None, &[true], &[outcome(true, true, 1)], None);
        assert_eq!(all.false_positive_rate, None);
    }

    #[test]
    fn scene_cheapest_lossless_is_the_fastest_level_that_loses_nothing() {
        let levels = [
            stats_with(Level::None, 0, 100.0, timing(10_000.0)),
            stats_with(Level::SphereCentroid, 1, 5.0, timing(1_000.0)),
            stats_with(Level::Aabb, 0, 60.0, timing(4_000.0)),
            stats_with(Level::Bvh, 0, 3.0, timing(5_000.0)),
        ];
        assert_eq!(cheapest_lossless(&levels), (Some(2), "time"), "AABB: faster than BVH here, lossless");
        // Untimed: by exact tests.
        let untimed: Vec<LevelStats> = levels.iter().map(|l| LevelStats { timing: None, ..l.clone() }).collect();
        assert_eq!(cheapest_lossless(&untimed), (Some(3), "exact tests"));
        // Ties go to the earlier level; nothing lossless gives none.
        let tie = [stats_with(Level::None, 0, 1.0, None), stats_with(Level::Aabb, 0, 1.0, None)];
        assert_eq!(cheapest_lossless(&tie).0, Some(0));
        assert_eq!(cheapest_lossless(&[stats_with(Level::None, 2, 1.0, None)]).0, None);
    }

    /// The corner tetrahedron: its box is [0,1]³; its minimal sphere is the
    /// slanted face's circumsphere (centre (⅓,⅓,⅓), radius √(2/3) ≈ 0.816,
    /// which holds the origin), its centroid sphere is centred at (¼,¼,¼) with
    /// radius √0.6875 ≈ 0.829.
    fn tetra() -> TriMesh<f64> {
        let vs = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        TriMesh::new(vs.iter().map(|p| v(*p)).collect(), vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
            .expect("mesh")
    }

    #[test]
    fn scene_mesh_levels_on_a_hand_made_scene() {
        let segments = [
            // A: through the tetrahedron (a hit); every level passes it.
            ([0.25, 0.25, 2.0], [0.25, 0.25, -1.0]),
            // B: through the box at x = y = 0.9, beside the slanted face (x + y > 1):
            // the box and the minimal sphere (0.80 from its centre) pass it, the
            // centroid sphere (0.92 from its centre) does not.
            ([0.9, 0.9, -1.0], [0.9, 0.9, 2.0]),
            // C: far away: nothing passes it.
            ([3.0, 3.0, 3.0], [4.0, 4.0, 4.0]),
            // D: beside the box and both spheres.
            ([1.2, 1.2, -0.5], [1.2, 1.2, 0.5]),
            // E: above the box (z = 1.1) but inside the minimal sphere (0.77 from
            // its centre); the centroid sphere's centre is 0.85 away.
            ([0.3, 0.3, 1.1], [0.4, 0.4, 1.1]),
        ];
        let (levels, contacts) = mesh_levels(&tetra(), &segments, false, 0);
        assert_eq!(contacts, 1);
        let get = |l: Level| levels.iter().find(|s| s.level == l).expect("level measured");
        let rate = |l: Level| get(l).false_positive_rate.map(|r| (r * 4.0).round() as usize);
        assert_eq!(rate(Level::None), Some(4), "no cheap test: every miss goes on");
        assert_eq!(rate(Level::Aabb), Some(1), "B only");
        assert_eq!(rate(Level::SphereMinimal), Some(2), "B and E");
        assert_eq!(rate(Level::SphereCentroid), Some(0), "the centroid sphere misses B and E");
        assert!(levels.iter().all(|l| l.lost == 0), "every level here is conservative: {levels:?}");
        assert!((get(Level::None).exact_tests_per_query - 4.0).abs() < 1e-12);
        assert!((get(Level::SphereCentroid).exact_tests_per_query - 0.8).abs() < 1e-12, "A only, 4 faces");
        let bvh = get(Level::Bvh);
        assert!(bvh.false_positive_rate <= get(Level::Aabb).false_positive_rate, "the tree's root is the box");
        // Untimed, the cheapest lossless level is the one with the fewest exact
        // tests: the centroid sphere's 0.8 (A's 4 faces over 5 queries), or the
        // tree's if its leaves hand A fewer faces (A meets the boxes of two of
        // the four); Ritter's sphere, lossless only if it passes A, can at best
        // tie the centroid's, and ties go to the earlier level.
        let (cheapest, by) = cheapest_lossless(&levels);
        assert_eq!(by, "exact tests");
        let chosen = &levels[cheapest.expect("a lossless level")];
        assert!(matches!(chosen.level, Level::SphereCentroid | Level::Bvh), "{chosen:?}");
        let fewest = levels.iter().map(|l| l.exact_tests_per_query).fold(f64::INFINITY, f64::min);
        assert!((chosen.exact_tests_per_query - fewest).abs() < 1e-12, "{chosen:?}");
        assert!(chosen.exact_tests_per_query <= 0.8 + 1e-12);
    }

    #[test]
    fn scene_sphere_levels_on_a_hand_made_scene() {
        // Three unit-diameter spheres at (0,0,0), (4,0,0), (0,4,0): box
        // [−½, 4½]×[−½, 4½]×[−½, ½]; the centres' minimal sphere has centre
        // (2,2,0) and radius 2√2, so the scene's minimal bound has radius 2√2 + ½.
        let spheres: Vec<Sphere<f64>> =
            [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]].iter().map(|c| Sphere::new(v(*c), 0.5)).collect();
        let queries: Vec<Sphere<f64>> = [
            ([0.8, 0.0, 0.0], 0.5),    // touches the first sphere
            ([2.0, 2.0, 0.0], 0.5),    // in the box and the bounds, touches nothing
            ([10.0, 10.0, 10.0], 0.5), // far from everything
            ([2.0, 0.0, 3.0], 0.5),    // above the box (z ≥ 2.5), 3.6 from (2,2,0): inside 2√2 + 1 ≈ 3.83
        ]
        .iter()
        .map(|(c, r)| Sphere::new(v(*c), *r))
        .collect();
        let (levels, contacts) = sphere_levels(&spheres, &queries, false);
        assert_eq!(contacts, 1);
        let get = |l: Level| levels.iter().find(|s| s.level == l).expect("level measured");
        let rate = |l: Level| get(l).false_positive_rate.map(|r| (r * 3.0).round() as usize);
        assert_eq!(rate(Level::None), Some(3));
        assert_eq!(rate(Level::Aabb), Some(1), "the second query only");
        assert_eq!(rate(Level::SphereMinimal), Some(2), "the second and the fourth");
        assert!(levels.iter().all(|l| l.lost == 0), "{levels:?}");
        assert!(get(Level::Bvh).false_positive_rate <= get(Level::Aabb).false_positive_rate);
    }

    #[test]
    fn scene_tightness_is_at_least_one_and_minimal_is_one() {
        let mut rng = Rng(0x7167_7e57);
        let mut clouds: Vec<Vec<P3>> = Vec::new();
        for n in [2, 3, 5, 17, 60] {
            for family in 0..2 {
                clouds.push(cloud(&mut rng, family, n));
            }
        }
        // A rotated tetrahedron: its minimal sphere is its circumsphere.
        let r = rng.rotation();
        clouds.push(
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
                .iter()
                .map(|p| rotate(&r, p))
                .collect(),
        );
        for (i, c) in clouds.iter().enumerate() {
            let t = tightness(c).expect("every method answers");
            for (m, x) in t.iter().enumerate() {
                assert!(*x >= 1.0 - TIGHTNESS_ROUNDING, "cloud {i}, {}: {x}", METHODS[m]);
            }
            assert!((t[3] - 1.0).abs() <= MINIMAL_TIGHTNESS_TOL, "cloud {i}: minimal {}", t[3]);
        }
    }
}
