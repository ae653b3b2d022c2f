//! Segment against a triangle mesh: the first face the segment meets.

use super::bvh::{MeshBvh, STACK, SegmentProbe};
use super::filter::{FaceFilter, FaceTest, SegmentFilter};
use super::hit::{MeshHit, MeshIntersection};
use super::trimesh::TriMesh;
use super::values::hit_values;
use crate::bounds::{aabb_of_segment, test_aabb_aabb};
use crate::exact::{self, BigFloat, Estimate, P3, Sign};
use crate::intersect::{SegmentHit, intersect_segment_triangle, intersect_segment_triangle_lecture};
use crate::real::{Real, Vec3, finite3, to_f64_3};
use crate::shapes::{Segment, Triangle};
use core::cmp::Ordering;

/// Absolute slack added to a hit's bound on `t` for the roundings of
/// [`Estimate::abs_fractions`] and of the bound itself: [`Estimate::abs_fractions`]
/// guarantees `2·joint_error + 3·2^−53`; `8·2^−53` covers the rest. It only
/// widens the BVH's pruning bound, never decides an answer.
const T_ROUNDING: f64 = 8.0 * f64::EPSILON / 2.0;

/// The segment as exact `f64` endpoints, or `None` when it is degenerate
/// (a non-finite coordinate, or zero length exactly).
pub(super) fn prepare<T: Real>(seg: &Segment<T>) -> Option<(P3, P3)> {
    if !(finite3(&seg.start) && finite3(&seg.end)) {
        return None;
    }
    let (q0, q1) = (to_f64_3(&seg.start), to_f64_3(&seg.end));
    (!exact::points_equal(q0, q1)).then_some((q0, q1))
}

/// A face the segment hits, with what it takes to compare its segment
/// parameter exactly with another's.
pub(super) struct Candidate<T: Real> {
    face: usize,
    /// The face (a copy: the BVH's leaf copy is in cache, the mesh's index
    /// and vertex arrays may not be).
    tri: Triangle<T>,
    /// Bounds on the exact `t`: `lo ≤ t ≤ hi`.
    lo: f64,
    hi: f64,
    /// `s_i = orient3d(v0, v1, v2, q_i)`, the endpoints' signed volumes over
    /// the face (`t = |s0| / (|s0| + |s1|)`), once computed: by the exact test,
    /// or on demand when two candidates' bounds overlap.
    volumes: Option<[Estimate; 2]>,
}

impl<T: Real> Candidate<T> {
    /// A face the exact test says is hit, bracketed from its volumes: the
    /// estimate of `t` is within `2·joint_error + 3·2^−53` of the exact one
    /// ([`Estimate::abs_fractions`]); [`T_ROUNDING`] covers the rest.
    fn from_volumes(face: usize, tri: &Triangle<T>, volumes: [Estimate; 2]) -> Self {
        // Not both zero: a hit is not coplanar.
        let t_est = Estimate::abs_fractions(volumes).map_or(0.5, |f| f[0]);
        let t_err = 2.0 * Estimate::joint_error(&volumes) + T_ROUNDING;
        Self { face, tri: *tri, lo: t_est - t_err, hi: t_est + t_err, volumes: Some(volumes) }
    }

    /// The face's vertices and volumes, the volumes computed now if they were
    /// not.
    fn exact_data(&mut self, q: [P3; 2]) -> ([P3; 3], [Estimate; 2]) {
        let v = self.tri.vertices.map(|p| to_f64_3(&p));
        (v, *self.volumes.get_or_insert_with(|| volumes(v, q)))
    }
}

/// `orient3d(a, b, c, d) = det[a − d, b − d, c − d]`, exactly.
fn orient3d_exact(a: P3, b: P3, c: P3, d: P3) -> BigFloat {
    let f = BigFloat::from_f64;
    let sub = |p: P3| [0, 1, 2].map(|k| &f(p[k]) - &f(d[k]));
    let (u, v, w) = (sub(a), sub(b), sub(c));
    let x = &(&v[1] * &w[2]) - &(&v[2] * &w[1]);
    let y = &(&v[2] * &w[0]) - &(&v[0] * &w[2]);
    let z = &(&v[0] * &w[1]) - &(&v[1] * &w[0]);
    &(&(&u[0] * &x) + &(&u[1] * &y)) + &(&u[2] * &z)
}

fn abs_big(x: BigFloat) -> BigFloat {
    if x.sign() == Sign::Negative { -x } else { x }
}

/// `|x|·|y|` as `(mantissa ∈ [0.25, 1), exponent, relative error bound)`.
fn product(x: &Estimate, y: &Estimate) -> (f64, i64, f64) {
    (
        x.mant * y.mant,
        x.exp + y.exp,
        // The two errors compounded, and the product's rounding (2^−53).
        x.rel_err + y.rel_err + x.rel_err * y.rel_err + f64::EPSILON / 2.0,
    )
}

/// Compares two non-zero products from their estimates; `None` when their
/// error bounds overlap.
fn compare_products(p: (f64, i64, f64), q: (f64, i64, f64)) -> Option<Ordering> {
    let (de, bound) = (p.1 - q.1, 2.0 * (p.2 + q.2) + 4.0 * f64::EPSILON);
    if bound.is_nan() || bound >= 0.25 {
        // Loose estimates (a volume barely certain of its sign): exactly.
        return None;
    }
    // Mantissas lie in [0.25, 1) and the errors below 1/4 (a factor within
    // (3/4, 5/4)): an exponent gap of 3 or more decides by itself.
    if de >= 3 {
        return Some(Ordering::Greater);
    }
    if de <= -3 {
        return Some(Ordering::Less);
    }
    let r = p.0 / q.0 * 2f64.powi(de as i32);
    if r > 1.0 + bound {
        Some(Ordering::Greater)
    } else if r < 1.0 - bound {
        Some(Ordering::Less)
    } else {
        None
    }
}

/// Exact order of the segment parameters of two hits, from their vertices and
/// volumes.
///
/// With `t = |s0| / (|s0| + |s1|)` (positive denominators),
/// `t_x < t_y ⇔ |s0x|·|s1y| < |s0y|·|s1x|`. The products are compared from the
/// estimates when their error bounds allow (almost always: they differ unless
/// the two parameters are within about `2^−38` of each other), otherwise from
/// the exact volumes in [`BigFloat`] — which a tie at a shared edge or vertex
/// always needs, and answers `Equal`.
fn compare_t(x: ([P3; 3], [Estimate; 2]), y: ([P3; 3], [Estimate; 2]), q: [P3; 2]) -> Ordering {
    let zero = |e: &Estimate| e.sign == Sign::Zero;
    let (p_zero, q_zero) = (zero(&x.1[0]) || zero(&y.1[1]), zero(&y.1[0]) || zero(&x.1[1]));
    match (p_zero, q_zero) {
        (true, true) => return Ordering::Equal,
        (true, false) => return Ordering::Less,
        (false, true) => return Ordering::Greater,
        (false, false) => {}
    }
    let p = product(&x.1[0], &y.1[1]);
    let r = product(&y.1[0], &x.1[1]);
    if let Some(o) = compare_products(p, r) {
        return o;
    }
    let vol = |v: [P3; 3], i: usize| {
        let [a, b, c] = v;
        abs_big(orient3d_exact(a, b, c, q[i]))
    };
    let p = &vol(x.0, 0) * &vol(y.0, 1);
    let r = &vol(y.0, 0) * &vol(x.0, 1);
    p.cmp(&r)
}

/// Whether the segment `q0 q1` hits the closed triangle `a b c`, decided
/// exactly as [`intersect_segment_triangle`] decides it (the same predicates in
/// the same cases), without computing the hit's values; with the endpoints'
/// volumes `[s0, s1]` (exact signs, fast magnitudes) when it does.
///
/// 1. `s_i = orient3d(a, b, c, q_i)`: both zero (coplanar) or both of one sign
///    — no hit (parallel, degenerate or a miss: none is a hit);
/// 2. `σ = sign(s1 − s0)`; the edge volumes `α' = orient3d(q1, c, b, q0)`,
///    `β' = orient3d(q1, a, c, q0)`, `γ' = orient3d(q1, b, a, q0)`: a hit iff
///    none has sign `−σ`.
#[inline]
pub(super) fn classify(v: [P3; 3], q: [P3; 2]) -> Option<[Estimate; 2]> {
    let [a, b, c] = v;
    let volumes = volumes(v, q);
    let sigma = match (volumes[0].sign, volumes[1].sign) {
        (x, y) if x == y => return None,
        (x, Sign::Zero) => -x,
        (_, y) => y,
    };
    let edges = [[q[1], c, b, q[0]], [q[1], a, c, q[0]], [q[1], b, a, q[0]]];
    for e in edges {
        if exact::orient3d(e[0], e[1], e[2], e[3]) == -sigma {
            return None;
        }
    }
    Some(volumes)
}

/// The endpoints' volumes over a face the segment is known to hit.
#[inline]
fn volumes(v: [P3; 3], q: [P3; 2]) -> [Estimate; 2] {
    let [a, b, c] = v;
    [exact::orient3d_estimate(a, b, c, q[0], f64::INFINITY), exact::orient3d_estimate(a, b, c, q[1], f64::INFINITY)]
}

/// Keeps a face the segment hits if it beats the best so far: smaller exact
/// `t`, or the same `t` and a lower face index. Disjoint brackets decide at
/// once (they hold the exact parameters); overlapping ones are compared
/// exactly ([`compare_t`]).
#[inline]
fn consider<T: Real>(best: &mut Option<Candidate<T>>, mut cand: Candidate<T>, q: [P3; 2]) {
    let better = match best {
        None => true,
        Some(b) if cand.hi < b.lo => true,
        Some(b) if cand.lo > b.hi => false,
        Some(b) => {
            let (x, y) = (cand.exact_data(q), b.exact_data(q));
            match compare_t(x, y, q) {
                Ordering::Less => true,
                Ordering::Equal => cand.face < b.face,
                Ordering::Greater => false,
            }
        }
    };
    if better {
        *best = Some(cand);
    }
}

/// The answer from the winning face (if any), with the mesh-wide flags. The
/// winner's values are computed once per query, from the face and the segment
/// alone (so every variant gives the same bits): see `values.rs`.
pub(super) fn finish<T: Real>(
    best: Option<Candidate<T>>,
    seg: &Segment<T>,
    mesh: &TriMesh<T>,
    q: [P3; 2],
) -> MeshIntersection<T> {
    let degenerate = mesh.degenerate_face_count() > 0;
    match best {
        Some(b) => match hit_values(seg, &b.tri, q) {
            Some(h) => MeshIntersection { hit: Some(mesh_hit(h, b.face)), parallel: false, degenerate },
            // Unreachable: `classify` decides exactly as the triangle query
            // does (a test checks they agree); answered as degenerate.
            None => MeshIntersection::DEGENERATE,
        },
        None => MeshIntersection { hit: None, parallel: mesh.parallel_to_every_face(q[0], q[1]), degenerate },
    }
}

fn mesh_hit<T: Real>(h: SegmentHit<T>, triangle: usize) -> MeshHit<T> {
    let third = T::one() / crate::real::c::<T>(3.0);
    MeshHit {
        t: h.t,
        point: h.point,
        normal: h.normal,
        // Both triangle queries always give barycentrics with a hit; the
        // centroid's weights stand in should one ever not.
        barycentric: h.barycentric.unwrap_or([third; 3]),
        triangle,
    }
}

/// First hit of a segment on a mesh, testing every face: the exact answer.
///
/// **Definition** (the fixture format's, for meshes). Every face is
/// classified by the exact
/// [`intersect_segment_triangle`](crate::intersect::intersect_segment_triangle)
/// (a two-sided closed triangle: edges and vertices count, a coplanar segment
/// is parallel and does not hit). Among the faces hit, the first hit is the one
/// with the smallest segment parameter `t`, compared **exactly**: with
/// `s_i = orient3d(v0, v1, v2, q_i)` (the endpoints' signed volumes over the
/// face), `t = |s0| / (|s0| + |s1|)`, so
/// `t_x < t_y ⇔ |s0x|·|s1y| < |s0y|·|s1x|`, decided from error-bounded
/// estimates and, when those cannot tell, in exact arithmetic. Ties (a segment
/// through an edge or vertex shared by faces) go to the **lowest face index**.
/// The hit's `t`, point, normal and barycentrics are that face's, accurate to
/// about `2^−40` as `intersect_segment_triangle` gives them: computed once, for
/// the winner, with the triangle query's formulas for `t`, the point and the
/// normal (so the same bits whenever its filter answers) and its edge volumes
/// for the barycentrics with the apex moved to the hit point (`values.rs`),
/// the triangle query itself answering when that path cannot certify them.
///
/// **Flags.** With no hit, `parallel` is set when the mesh has a face with area
/// and the segment is parallel to every face with area (exactly:
/// `((v1 − v0) × (v2 − v0)) · (q1 − q0) = 0`). `degenerate` is set when the mesh
/// has a degenerate face (zero area exactly, or a non-finite vertex): such a
/// face is skipped — it has no plane to cross.
///
/// **Degenerate input.** A segment with a non-finite coordinate or zero length:
/// [`MeshIntersection::DEGENERATE`] (no hit, not parallel, flagged). An empty
/// mesh: no hit, not parallel, not degenerate. Never NaN, never a panic.
///
/// **Cost.** One exact segment–triangle test per face (two filtered orient3d
/// evaluations for most misses); the exact comparison only between faces hit.
///
/// Source: the lecture's "test every triangle, keep the smallest `t`", with the
/// exact predicates of [`crate::exact`]. **Deviation from the lecture**: the
/// comparison of `t` is exact and the tie rule is stated.
pub fn intersect_segment_mesh_brute<T: Real>(seg: &Segment<T>, mesh: &TriMesh<T>) -> MeshIntersection<T> {
    let Some((q0, q1)) = prepare(seg) else {
        return MeshIntersection::DEGENERATE;
    };
    brute(seg, mesh, [q0, q1])
}

pub(super) fn brute<T: Real>(seg: &Segment<T>, mesh: &TriMesh<T>, q: [P3; 2]) -> MeshIntersection<T> {
    let mut best = None;
    for face in 0..mesh.len() {
        if mesh.is_degenerate_face(face) {
            continue;
        }
        // The triangle query classifies (its own filter makes most misses
        // cheap); `classify` would decide the same, exactly.
        let tri = mesh.triangle(face);
        if intersect_segment_triangle(seg, &tri).hit.is_some() {
            let v = tri.vertices.map(|p| to_f64_3(&p));
            consider(&mut best, Candidate::from_volumes(face, &tri, volumes(v, q)), q);
        }
    }
    finish(best, seg, mesh, q)
}

/// First hit of a segment on a mesh, culled by the mesh's bounding box: if the
/// segment's box does not overlap the mesh's ([`TriMesh::aabb`]), no face can be
/// hit; otherwise every face is tested as by [`intersect_segment_mesh_brute`].
///
/// The box test ([`test_aabb_aabb`] of [`aabb_of_segment`] and the mesh's box,
/// touching counts) compares exact coordinates, so culling never drops a hit:
/// the answer equals [`intersect_segment_mesh_brute`]'s, flags included (a
/// culled segment still gets the mesh's `parallel` and `degenerate` flags).
/// It is cheap but coarse: a segment through the box's empty corners (common
/// for a bunny) pays for every face.
///
/// **Degenerate input:** as [`intersect_segment_mesh_brute`].
pub fn intersect_segment_mesh_culled<T: Real>(seg: &Segment<T>, mesh: &TriMesh<T>) -> MeshIntersection<T> {
    let Some((q0, q1)) = prepare(seg) else {
        return MeshIntersection::DEGENERATE;
    };
    match mesh.aabb() {
        Some(bb) if test_aabb_aabb(&aabb_of_segment(seg), &bb) => brute(seg, mesh, [q0, q1]),
        _ => finish(None, seg, mesh, [q0, q1]),
    }
}

/// First hit of a segment on a mesh through its bounding volume hierarchy: the
/// same answer as [`intersect_segment_mesh_brute`], bit for bit, faster.
///
/// **Traversal.** Depth first, nearer child first, with a fixed-size stack (no
/// allocation), over the tree's two-child records (both children's boxes,
/// read and tested together). A child is visited only
/// if the segment may meet its box: the slab test of `SegmentProbe`, which is
/// conservative (it accepts every box the segment meets exactly, and reports a
/// lower bound on where it enters). Once a hit is known, a child whose entry
/// bound exceeds an upper bound on the best hit's exact `t` is skipped: none
/// of its faces can come first, nor tie.
///
/// **Faces: a filter first, exactness where it cannot decide.** Each face
/// visited goes through a floating-point filter with certified error bounds
/// (`filter.rs`: the exact test's volumes, evaluated as the triangle query's
/// own filter evaluates them, the face's normal precomputed), which answers
/// "no hit", "a hit, with `t` between these bounds", or "not certain". Only the
/// last goes to the exact test (an endpoint within rounding of the face's
/// plane, the line within rounding of an edge or vertex — every tie at a
/// shared edge). Two hits whose brackets on `t` are disjoint are ordered at
/// once; overlapping brackets are ordered exactly, as in the brute-force
/// query, with the same tie rule; so the winner is the same face. The filter
/// is used when every coordinate is at most 2^60 in magnitude (beyond, its
/// error bounds would not hold and every face goes to the exact test).
///
/// **Values.** The winner's `t`, point, normal and barycentrics are computed
/// once, from the face and the segment alone, by a certified path accurate to
/// about `2^−40` (`values.rs`), the exact segment–triangle query answering
/// when it cannot certify them: the same values as every other variant's.
///
/// **Flags and degenerate input:** as [`intersect_segment_mesh_brute`] (the
/// `parallel` flag of a miss is a property of the whole mesh and is answered
/// from its faces, witnesses first).
///
/// **Cost** on the bunny: see [`SplitRule`](super::SplitRule).
pub fn intersect_segment_mesh_bvh<T: Real>(seg: &Segment<T>, bvh: &MeshBvh<T>) -> MeshIntersection<T> {
    let mesh = bvh.mesh();
    let Some((q0, q1)) = prepare(seg) else {
        return MeshIntersection::DEGENERATE;
    };
    let q = [q0, q1];
    let mut best: Option<Candidate<T>> = None;
    let Some(root) = bvh.nodes().first() else {
        return finish(best, seg, mesh, q);
    };
    let v3 = |p: P3| Vec3::new(p[0], p[1], p[2]);
    let probe = SegmentProbe::new(&Segment::new(v3(q0), v3(q1)));
    let Some(entry) = probe.entry(&root.min.map(|x| x.wide()), &root.max.map(|x| x.wide())) else {
        return finish(best, seg, mesh, q);
    };
    let filter = SegmentFilter::new(q0, q1).filter(|_| bvh.filter_ok());
    if root.count > 0 {
        for k in root.start as usize..(root.start + root.count) as usize {
            leaf_face(bvh, k, filter.as_ref(), q, &mut best);
        }
        return finish(best, seg, mesh, q);
    }
    let wide = bvh.wide();
    // Pending children as a wide record gives them — (start, count): a leaf's
    // faces when count > 0, else an internal node's record — with their entry
    // bound.
    let mut stack = [(0u32, 0u32, 0.0f64); STACK];
    stack[0] = (0, 0, entry);
    let mut sp = 1usize;
    while sp > 0 {
        sp -= 1;
        let (start, count, entry) = stack[sp];
        // Every entry bound is at most 1 + slack < 2: with no hit yet, nothing
        // is pruned.
        let bound = best.as_ref().map_or(NO_HIT_BOUND, |b| b.hi);
        if entry > bound {
            continue;
        }
        if count > 0 {
            for k in start as usize..(start + count) as usize {
                leaf_face(bvh, k, filter.as_ref(), q, &mut best);
            }
            continue;
        }
        let w = &wide[start as usize];
        let e = probe.entries(w);
        // Farther child first, so the nearer is popped next.
        let order = if e[0] <= e[1] { [1, 0] } else { [0, 1] };
        for j in order {
            if e[j] <= bound {
                // At most one pending sibling per level plus the current
                // path: depth ≤ BVH_MAX_DEPTH keeps this within STACK.
                debug_assert!(sp < STACK, "traversal stack overflow");
                if sp < STACK {
                    stack[sp] = (w.start[j], w.count[j], e[j]);
                    sp += 1;
                }
            }
        }
    }
    finish(best, seg, mesh, q)
}

/// Above every entry bound of a box the segment may meet (`1 + slack`), below
/// the `+∞` of a box it misses: the pruning bound before any hit.
const NO_HIT_BOUND: f64 = 2.0;

/// One face of a leaf: the filter, then (if it cannot tell) the exact test;
/// a face hit becomes a candidate.
#[inline(always)]
fn leaf_face<T: Real>(
    bvh: &MeshBvh<T>,
    k: usize,
    filter: Option<&SegmentFilter>,
    q: [P3; 2],
    best: &mut Option<Candidate<T>>,
) {
    filtered_face(bvh.leaf_data(k), filter, q, best, || bvh.leaf_face(k));
}

/// One face, given its filter data: the filter (when `filter` is given), then
/// (if it cannot tell) the exact test; a face hit becomes a candidate. `face`
/// answers the triangle and its index in the mesh, read only for a hit.
#[inline(always)]
pub(super) fn filtered_face<'a, T: Real + 'a>(
    data: &FaceFilter,
    filter: Option<&SegmentFilter>,
    q: [P3; 2],
    best: &mut Option<Candidate<T>>,
    face: impl FnOnce() -> (&'a Triangle<T>, usize),
) {
    let test = match filter {
        Some(f) => data.test(f),
        None => FaceTest::Undecided,
    };
    let cand = match test {
        FaceTest::Miss => return,
        FaceTest::Hit { lo, hi } => {
            // A face that cannot come first (or tie) is dropped unread.
            if best.as_ref().is_some_and(|b| lo > b.hi) {
                return;
            }
            let (tri, face) = face();
            Candidate { face, tri: *tri, lo, hi, volumes: None }
        }
        FaceTest::Undecided => {
            let Some(vol) = classify(data.v, q) else {
                return;
            };
            let (tri, face) = face();
            Candidate::from_volumes(face, tri, vol)
        }
    };
    consider(best, cand, q);
}

/// The lecture's segment–mesh query: every face through the lecture's
/// [`intersect_segment_triangle_lecture`] (plane hit, then Sunday's `s`, `t`
/// test), keeping the smallest `t` as computed; ties (equal computed `t`) to the
/// lowest face index.
///
/// **Flags** (the fixture format's rule for meshes, applied to the lecture's
/// per-face answers): a face the lecture's test calls degenerate is skipped and
/// flags the answer `degenerate`; with no hit, `parallel` is set when some face
/// was not degenerate and every such face was parallel (`n · (q1 − q0) == 0` in
/// floating point).
///
/// **Degenerate input.** Whatever the per-face test says: a zero-length or
/// non-finite segment makes every face degenerate, so the answer is no hit,
/// not parallel, flagged. Never NaN, never a panic.
///
/// **Deviation from the robust queries**: the comparison of `t` is in floating
/// point, so two faces within rounding of each other may be ordered either way
/// and a hit near a shared edge may be missed by both faces (the lecture's
/// inside test is not watertight).
pub fn intersect_segment_mesh_lecture<T: Real>(seg: &Segment<T>, mesh: &TriMesh<T>) -> MeshIntersection<T> {
    let mut best: Option<MeshHit<T>> = None;
    let mut all_parallel = true;
    let mut any_area = false;
    let mut degenerate = false;
    for face in 0..mesh.len() {
        let r = intersect_segment_triangle_lecture(seg, &mesh.triangle(face));
        if r.degenerate {
            degenerate = true;
            continue;
        }
        any_area = true;
        all_parallel &= r.parallel;
        if let Some(h) = r.hit
            && best.is_none_or(|b| h.t < b.t)
        {
            best = Some(mesh_hit(h, face));
        }
    }
    MeshIntersection { hit: best, parallel: best.is_none() && any_area && all_parallel, degenerate }
}
