//! A bounding volume hierarchy over a mesh's faces: a binary AABB tree, built top
//! down, stored flat.

use super::filter::{FILTER_MAX_COORD, FaceFilter};
use super::trimesh::TriMesh;
use crate::real::{Real, Vec3, c, stable_norm};
use crate::shapes::{Segment, Triangle};

/// The deepest a [`MeshBvh`] grows: a node at this depth becomes a leaf whatever
/// it holds. Traversals keep their pending nodes in a fixed array of
/// `BVH_MAX_DEPTH + 2` entries on the stack (an ordered depth-first traversal
/// holds at most one pending sibling per level), so no query allocates.
///
/// Reason for 64: the median rule halves the faces at every level, so it reaches
/// depth `⌈log2(n/4)⌉` (10 for the bunny); the SAH rule is less balanced but
/// stays within a few times that on real meshes (14 on the bunny). 64 levels
/// leave room for meshes of any size a `u32` face index allows.
pub const BVH_MAX_DEPTH: usize = 64;

/// Capacity of the traversal stacks.
pub(crate) const STACK: usize = BVH_MAX_DEPTH + 2;

/// Most faces a median-rule leaf holds: nodes with more are split.
const MEDIAN_LEAF: usize = 4;

/// Bins per axis of the binned SAH.
const SAH_BINS: usize = 16;

/// Most faces a SAH leaf holds, whatever the cost model says.
const SAH_MAX_LEAF: usize = 8;

/// The SAH's cost of visiting a node, in units of one face test. Reason: a
/// slab test is a dozen floating-point operations (both children's at once,
/// two lanes), the filter of `filter.rs` a few dozen. Measured on the bunny
/// (segment queries as in [`SplitRule`]'s table): cost 2 answered within the
/// noise of cost 1, cost 4 (larger leaves) about 7% slower; 1 is kept.
const SAH_TRAVERSAL_COST: f64 = 1.0;

/// How a node's faces are divided between its two children.
///
/// Both rules split top down, on face centroids, and stop at a small leaf.
/// Measured on the Stanford bunny (`fixtures/meshes/bunny.obj`, 3,674 faces),
/// `f64`, release build, one thread of the 2-core development machine (shared
/// with other work, so single runs vary by ±30%; each figure is the best of
/// many repetitions, parry timed in the same loop). Queries: the 1,024
/// segments of `benches/mesh.rs`, both endpoints uniform in the bunny's box
/// grown by a quarter of its size on each side (42% of them hit):
///
/// | rule | build | nodes | depth | segment query (mean) |
/// | --- | --- | --- | --- | --- |
/// | [`SplitRule::MedianCentroid`] | 0.8 ms | 2,047 | 10 | 0.49 µs |
/// | [`SplitRule::SahBinned`] | 3.5 ms | 4,295 | 14 | 0.40 µs |
/// | every face (`intersect_segment_mesh_brute`) | — | — | — | 196 µs |
/// | box-culled (`intersect_segment_mesh_culled`) | — | — | — | 173 µs |
/// | parry3d-f64 `TriMesh` ray cast (for scale) | 1.3 ms | | | 0.63 µs |
///
/// The binned SAH costs about five times as much to build and answers about
/// 20% faster; queries outnumber builds in every use crashtest makes of a mesh, so
/// it is the default. (Box culling gains little on these segments: most of
/// them cross the bunny's box.) `cargo bench --bench mesh` times both rules,
/// the build and parry in one run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SplitRule {
    /// Split on the longest axis of the centroids' box, at the median centroid
    /// (half the faces each side; ties by face index). Leaves hold at most
    /// 4 faces. The tree is balanced: depth `⌈log2(n/4)⌉`.
    MedianCentroid,
    /// The surface area heuristic, binned (Wald, *On fast Construction of
    /// SAH-based Bounding Volume Hierarchies*, 2007): on each axis, the
    /// centroids are dropped into 16 equal bins and every boundary between bins
    /// is priced as `C_trav·A + A_L·n_L + A_R·n_R` (`A` the surface areas of the
    /// boxes, `n` the face counts); the cheapest split wins unless keeping the
    /// node as a leaf (`n·A`) is cheaper and it holds at most 8 faces. A node
    /// whose centroids coincide is split at the median by index.
    #[default]
    SahBinned,
}

/// One node of the flat tree. An internal node (`count == 0`) has its left child
/// right after it (depth-first layout) and its right child at `start`; a leaf
/// holds the faces `start .. start + count` of [`MeshBvh`]'s leaf arrays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Node<T: Real> {
    pub min: [T; 3],
    pub max: [T; 3],
    pub start: u32,
    pub count: u32,
}

/// The segment query's view of an internal node: both children's exact boxes
/// side by side, in `f64` (exact for both precisions), laid out per axis so
/// that one two-lane slab test covers both children, and where each child
/// goes. 128 bytes, aligned to a cache line: both children read together.
/// (Boxes rounded outward to `f32` would halve the memory, but they inflate by
/// the `f32` spacing of the coordinates — far from the origin, more than a
/// small face — and measured 4% slower on the bunny, for the conversions.)
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct Wide {
    /// Per axis, per child: the box's lower corner.
    pub min: [[f64; 2]; 3],
    /// Per axis, per child: the box's upper corner.
    pub max: [[f64; 2]; 3],
    /// Per child: a leaf's first face in the leaf arrays, or an internal
    /// child's index in [`MeshBvh`]'s wide records.
    pub start: [u32; 2],
    /// Per child: a leaf's face count (at least 1), or 0 for an internal child.
    pub count: [u32; 2],
}

/// The wide records of a flat tree: one per internal node, in node order (the
/// root's first).
fn wide_records<T: Real>(nodes: &[Node<T>]) -> Vec<Wide> {
    let mut index = vec![u32::MAX; nodes.len()];
    let mut next = 0u32;
    for (i, n) in nodes.iter().enumerate() {
        if n.count == 0 {
            index[i] = next;
            next += 1;
        }
    }
    let mut out = Vec::with_capacity(next as usize);
    for (i, n) in nodes.iter().enumerate() {
        if n.count > 0 {
            continue;
        }
        let mut w = Wide { min: [[0.0; 2]; 3], max: [[0.0; 2]; 3], start: [0; 2], count: [0; 2] };
        for (j, c) in [i + 1, n.start as usize].into_iter().enumerate() {
            let child = &nodes[c];
            for k in 0..3 {
                w.min[k][j] = child.min[k].wide();
                w.max[k][j] = child.max[k].wide();
            }
            (w.start[j], w.count[j]) = if child.count > 0 { (child.start, child.count) } else { (index[c], 0) };
        }
        out.push(w);
    }
    out
}

/// A mesh with a bounding volume hierarchy over its faces: a binary tree of
/// axis-aligned boxes, each the exact box of the faces below it.
///
/// **Layout.** Nodes are one flat array in depth-first order (the left child
/// follows its parent; the right child's index is stored), 56 bytes per node
/// in `f64`; the sphere query walks them. The segment query walks a second
/// view of the same tree: one 128-byte record per internal node holding both
/// children's boxes (read together, tested together). Leaves point into flat
/// arrays holding their faces' vertices in leaf order, each face's
/// precomputed filter data (its normal and that normal's error bounds) and the
/// faces' original indices, so a leaf's faces are contiguous in memory and a
/// query never goes back to the index buffer.
///
/// **Build.** Top down by the chosen [`SplitRule`]; every box is the exact
/// componentwise minimum and maximum of its faces' vertices (no rounding), which
/// is what makes the queries' culling provably conservative. Faces with a
/// non-finite vertex are left out of the tree (no query uses them). Cost
/// `O(n log n)`; see [`SplitRule`] for measured times.
///
/// **Queries** ([`intersect_segment_mesh_bvh`](super::intersect_segment_mesh_bvh),
/// [`contact_sphere_mesh_bvh`](super::contact_sphere_mesh_bvh)) traverse nearer
/// child first with a fixed-size stack ([`BVH_MAX_DEPTH`]); they do not
/// allocate.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshBvh<T: Real> {
    mesh: TriMesh<T>,
    nodes: Vec<Node<T>>,
    tris: Vec<Triangle<T>>,
    ids: Vec<u32>,
    /// Per leaf face, the segment filter's data (see `filter.rs`).
    filters: Vec<FaceFilter>,
    /// Every vertex of the tree's faces is within the filter's range.
    filter_ok: bool,
    /// The segment query's records (see [`Wide`]).
    wide: Vec<Wide>,
    split: SplitRule,
    depth: usize,
}

/// A face during the build, in `f64` (exact for both precisions).
#[derive(Clone, Copy, Debug)]
struct Item {
    lo: [f64; 3],
    hi: [f64; 3],
    centroid: [f64; 3],
    id: u32,
}

/// The box of two boxes. Selections rather than `f64::min`/`max` (whose NaN
/// handling cost a quarter of the SAH build on the bunny): the tree's faces
/// have finite vertices, so no NaN reaches here.
#[inline(always)]
fn union(a: ([f64; 3], [f64; 3]), lo: &[f64; 3], hi: &[f64; 3]) -> ([f64; 3], [f64; 3]) {
    let (mut l, mut h) = a;
    for k in 0..3 {
        l[k] = if lo[k] < l[k] { lo[k] } else { l[k] };
        h[k] = if hi[k] > h[k] { hi[k] } else { h[k] };
    }
    (l, h)
}

const EMPTY_BOX: ([f64; 3], [f64; 3]) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);

/// Surface area of a box (0 for an empty or flat one; `∞` or NaN beyond `f64`'s
/// range, which the SAH then never picks).
fn area(b: &([f64; 3], [f64; 3])) -> f64 {
    let d = [0, 1, 2].map(|k| (b.1[k] - b.0[k]).max(0.0));
    2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0])
}

impl<T: Real> MeshBvh<T> {
    /// Builds the tree with the default split rule ([`SplitRule::SahBinned`]).
    pub fn new(mesh: TriMesh<T>) -> Self {
        Self::with_split(mesh, SplitRule::default())
    }

    /// Builds the tree with the given split rule.
    pub fn with_split(mesh: TriMesh<T>, split: SplitRule) -> Self {
        let mut items: Vec<Item> = (0..mesh.len())
            .filter(|&i| !mesh.has_nonfinite_vertex(i))
            .map(|i| {
                let t = mesh.triangle(i);
                let v = t.vertices.map(|p| [p.x.wide(), p.y.wide(), p.z.wide()]);
                let mut lo = v[0];
                let mut hi = v[0];
                for p in &v[1..] {
                    for k in 0..3 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
                // The centroid only orders faces (its rounding does not matter);
                // each term is divided first so that no sum overflows.
                let centroid = [0, 1, 2].map(|k| v[0][k] / 3.0 + v[1][k] / 3.0 + v[2][k] / 3.0);
                Item { lo, hi, centroid, id: i as u32 }
            })
            .collect();
        let mut bvh = Self {
            nodes: Vec::with_capacity(2 * items.len()),
            tris: Vec::with_capacity(items.len()),
            ids: Vec::with_capacity(items.len()),
            filters: Vec::with_capacity(items.len()),
            filter_ok: items.iter().all(|it| (0..3).all(|k| it.lo[k].abs().max(it.hi[k].abs()) <= FILTER_MAX_COORD)),
            wide: Vec::new(),
            mesh,
            split,
            depth: 0,
        };
        if !items.is_empty() {
            bvh.build(&mut items, 0);
        }
        bvh.wide = wide_records(&bvh.nodes);
        bvh
    }

    fn build(&mut self, items: &mut [Item], depth: usize) -> u32 {
        self.depth = self.depth.max(depth);
        let index = self.nodes.len();
        let bounds = items.iter().fold(EMPTY_BOX, |b, it| union(b, &it.lo, &it.hi));
        self.nodes.push(Node { min: bounds.0.map(T::of), max: bounds.1.map(T::of), start: 0, count: 0 });
        let mid = if depth >= BVH_MAX_DEPTH {
            None
        } else {
            match self.split {
                SplitRule::MedianCentroid => split_median(items),
                SplitRule::SahBinned => split_sah(items, &bounds),
            }
        };
        match mid {
            Some(mid) => {
                let (left, right) = items.split_at_mut(mid);
                self.build(left, depth + 1);
                let r = self.build(right, depth + 1);
                self.nodes[index].start = r;
            }
            None => {
                self.nodes[index].start = self.tris.len() as u32;
                self.nodes[index].count = items.len() as u32;
                for it in items.iter() {
                    let tri = self.mesh.triangle(it.id as usize);
                    self.filters.push(FaceFilter::new(tri.vertices.map(|p| [p.x.wide(), p.y.wide(), p.z.wide()])));
                    self.tris.push(tri);
                    self.ids.push(it.id);
                }
            }
        }
        index as u32
    }

    /// The mesh the tree indexes.
    pub fn mesh(&self) -> &TriMesh<T> {
        &self.mesh
    }

    /// The mesh back, the tree dropped.
    pub fn into_mesh(self) -> TriMesh<T> {
        self.mesh
    }

    /// The rule the tree was built with.
    pub fn split_rule(&self) -> SplitRule {
        self.split
    }

    /// Number of nodes (internal and leaves); 0 for a mesh without a finite face.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of leaves.
    pub fn leaf_count(&self) -> usize {
        self.nodes.iter().filter(|n| n.count > 0).count()
    }

    /// Depth of the deepest leaf (the root is at depth 0).
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// The tree's broad phase for a segment: appends to `out` (cleared first)
    /// the index of every face in a leaf whose box the segment may meet, in
    /// leaf order — a superset of the faces it hits, found by the same
    /// conservative slab tests as
    /// [`intersect_segment_mesh_bvh`](super::intersect_segment_mesh_bvh) but
    /// without its first-hit pruning. So `out` is empty only when the segment
    /// certainly hits no face, and its length is how many faces a query
    /// without pruning would test exactly. crashtest uses it to measure what
    /// the tree's cheap test lets through.
    ///
    /// **Degenerate input:** a segment with a non-finite coordinate gets no
    /// face; a zero-length one (a point) the faces of the leaves whose boxes
    /// contain it.
    pub fn faces_near_segment(&self, seg: &Segment<T>, out: &mut Vec<usize>) {
        out.clear();
        let (q0, q1) = (seg.start.map(|x| x.wide()), seg.end.map(|x| x.wide()));
        let Some(root) = self.nodes.first() else { return };
        if !(q0.iter().chain(q1.iter()).all(|x| x.is_finite())) {
            return;
        }
        let probe = SegmentProbe::new(&Segment::new(q0, q1));
        if probe.entry(&root.min.map(|x| x.wide()), &root.max.map(|x| x.wide())).is_none() {
            return;
        }
        let mut push_leaf =
            |start: u32, count: u32| out.extend((start..start + count).map(|k| self.ids[k as usize] as usize));
        if root.count > 0 {
            push_leaf(root.start, root.count);
            return;
        }
        let mut stack = [0u32; STACK];
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let w = &self.wide[stack[sp] as usize];
            let e = probe.entries(w);
            for (j, entry) in e.into_iter().enumerate() {
                if entry == f64::INFINITY {
                    continue;
                }
                if w.count[j] > 0 {
                    push_leaf(w.start[j], w.count[j]);
                } else if sp < STACK {
                    // Depth first: at most one pending sibling per level plus
                    // the current path, within STACK for depth ≤ BVH_MAX_DEPTH.
                    stack[sp] = w.start[j];
                    sp += 1;
                }
            }
        }
    }

    pub(crate) fn nodes(&self) -> &[Node<T>] {
        &self.nodes
    }

    /// Leaf face `k`'s filter data whether or not the filter may be used (its
    /// vertices in `f64` serve the exact test too).
    #[inline(always)]
    pub(crate) fn leaf_data(&self, k: usize) -> &FaceFilter {
        &self.filters[k]
    }

    /// Whether the filter may be used on this mesh (every vertex within its
    /// range).
    #[inline(always)]
    pub(crate) fn filter_ok(&self) -> bool {
        self.filter_ok
    }

    /// The wide records of the segment query: one per internal node, the
    /// root's at index 0 (none when the root is a leaf).
    #[inline(always)]
    pub(crate) fn wide(&self) -> &[Wide] {
        &self.wide
    }

    /// Leaf face `k` (in leaf order) and its index in the mesh.
    #[inline(always)]
    pub(crate) fn leaf_face(&self, k: usize) -> (&Triangle<T>, usize) {
        (&self.tris[k], self.ids[k] as usize)
    }
}

/// Median split on the longest axis of the centroids' box; `None` for a leaf.
fn split_median(items: &mut [Item]) -> Option<usize> {
    if items.len() <= MEDIAN_LEAF {
        return None;
    }
    let mid = items.len() / 2;
    let cb = items.iter().fold(EMPTY_BOX, |b, it| union(b, &it.centroid, &it.centroid));
    let ext = [0, 1, 2].map(|k| cb.1[k] - cb.0[k]);
    let axis = (0..3).max_by(|&a, &b| ext[a].total_cmp(&ext[b])).unwrap_or(0);
    if ext[axis].is_nan() || ext[axis] <= 0.0 {
        // Coincident centroids: any halving is as good as another.
        return Some(mid);
    }
    items.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]).then(a.id.cmp(&b.id)));
    Some(mid)
}

/// Binned SAH split; `None` for a leaf.
fn split_sah(items: &mut [Item], bounds: &([f64; 3], [f64; 3])) -> Option<usize> {
    let n = items.len();
    if n <= 1 {
        return None;
    }
    let cb = items.iter().fold(EMPTY_BOX, |b, it| union(b, &it.centroid, &it.centroid));
    let node_area = area(bounds);
    let leaf_cost = n as f64 * node_area;
    // (cost, axis, boundary): faces in bins < boundary go left.
    let mut best: Option<(f64, usize, usize)> = None;
    for axis in 0..3 {
        let (lo, ext) = (cb.0[axis], cb.1[axis] - cb.0[axis]);
        if !(ext > 0.0 && ext.is_finite()) {
            continue;
        }
        let mut count = [0usize; SAH_BINS];
        let mut boxes = [EMPTY_BOX; SAH_BINS];
        for it in items.iter() {
            let b = bin(it.centroid[axis], lo, ext);
            count[b] += 1;
            boxes[b] = union(boxes[b], &it.lo, &it.hi);
        }
        // Right-to-left suffix areas and counts.
        let mut right_area = [0.0; SAH_BINS];
        let mut right_count = [0usize; SAH_BINS];
        let (mut acc, mut cnt) = (EMPTY_BOX, 0);
        for b in (1..SAH_BINS).rev() {
            acc = union(acc, &boxes[b].0, &boxes[b].1);
            cnt += count[b];
            right_area[b] = area(&acc);
            right_count[b] = cnt;
        }
        let (mut acc, mut cnt) = (EMPTY_BOX, 0);
        for boundary in 1..SAH_BINS {
            acc = union(acc, &boxes[boundary - 1].0, &boxes[boundary - 1].1);
            cnt += count[boundary - 1];
            if cnt == 0 || right_count[boundary] == 0 {
                continue;
            }
            let cost = SAH_TRAVERSAL_COST * node_area
                + area(&acc) * cnt as f64
                + right_area[boundary] * right_count[boundary] as f64;
            if cost.is_finite() && best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, boundary));
            }
        }
    }
    match best {
        Some((cost, _, _)) if n <= SAH_MAX_LEAF && leaf_cost <= cost => None,
        Some((_, axis, boundary)) => {
            let (lo, ext) = (cb.0[axis], cb.1[axis] - cb.0[axis]);
            let mid = partition(items, |it| bin(it.centroid[axis], lo, ext) < boundary);
            if mid == 0 || mid == n {
                // Unreachable (both sides counted non-empty), kept total.
                split_median(items).or(Some(n / 2))
            } else {
                Some(mid)
            }
        }
        None if n <= SAH_MAX_LEAF => None,
        None => split_median(items).or(Some(n / 2)),
    }
}

/// The bin of a centroid coordinate `x` in `[lo, lo + ext]`.
#[inline]
fn bin(x: f64, lo: f64, ext: f64) -> usize {
    let b = ((x - lo) / ext * SAH_BINS as f64) as usize; // saturating cast; NaN → 0
    b.min(SAH_BINS - 1)
}

/// Moves the items for which `left` holds to the front (order otherwise
/// unspecified but deterministic); returns how many there are.
fn partition(items: &mut [Item], left: impl Fn(&Item) -> bool) -> usize {
    let mut i = 0;
    for j in 0..items.len() {
        if left(&items[j]) {
            items.swap(i, j);
            i += 1;
        }
    }
    i
}

// ---------------------------------------------------------------------------
// Culling tests used by the traversals. Both are conservative: they may keep a
// box that a face-level test then rejects, never reject a box holding a face
// that the face-level test would accept.

/// Absolute slack for underflow: a product that underflows errs by at most
/// half the smallest subnormal (`2^−1075` in `f64`, `2^−150` in `f32`);
/// `ε³` (≈ 1e-47 and 2e-21) covers that with room and is negligible next to any
/// segment parameter or distance the queries compare.
fn tiny<T: Real>() -> T {
    T::EPSILON * T::EPSILON * T::EPSILON
}

/// Slack of the slab test, absolute in segment-parameter units: `8ε + ε³`
/// (16 units of roundoff). Reason: each slab parameter `(b − o) · (1/d)`
/// carries at most 4 roundings (the difference `d = q1 − q0`, the
/// reciprocal, `b − o`, the product), so it is within `4u|t|` (`u = ε/2`) of
/// the exact `(b − o)/(q1 − q0)`. The entering parameter `max(0, …)` is then
/// within `4u·enter` of the exact one, and the leaving one `min(1, …)` within
/// `4u·max(1, |exit|)`; when the exact interval is not empty both lie in
/// `[0, 1]`, so the computed ones differ by at most `8u` more than the exact
/// ones, and `16u` covers that and the underflow slack.
fn slab_slack<T: Real>() -> T {
    c::<T>(8.0) * T::EPSILON + tiny::<T>()
}

/// How one axis of a segment enters the slab test.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Axis {
    /// `q1 = q0` on this axis: the segment stays at `o`.
    Flat,
    /// `1/d` is finite and non-zero: the usual slab.
    Slab,
    /// `d` or `1/d` is not finite (overflowing coordinates, or a subnormal
    /// direction): the axis is not used to cull (conservative).
    Free,
}

/// A segment prepared for slab tests against many boxes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegmentProbe<T: Real> {
    o: [T; 3],
    inv: [T; 3],
    axis: [Axis; 3],
    /// Per axis: the direction is negative, so the segment enters through the
    /// box's `max` plane and leaves through its `min` plane.
    negative: [bool; 3],
    /// Every axis is [`Axis::Slab`]: the common case, tested without branches
    /// on the axis kind.
    all_slab: bool,
    slack: T,
}

impl<T: Real> SegmentProbe<T> {
    pub(crate) fn new(seg: &Segment<T>) -> Self {
        let (mut o, mut inv, mut axis) = ([T::zero(); 3], [T::zero(); 3], [Axis::Free; 3]);
        for k in 0..3 {
            o[k] = seg.start[k];
            let d = seg.end[k] - seg.start[k];
            if d == T::zero() {
                axis[k] = Axis::Flat;
            } else if d.finite() {
                let r = T::one() / d;
                if r.finite() && r != T::zero() {
                    inv[k] = r;
                    axis[k] = Axis::Slab;
                }
            }
        }
        Self {
            o,
            inv,
            axis,
            negative: inv.map(|r| r < T::zero()),
            all_slab: axis.iter().all(|a| *a == Axis::Slab),
            slack: slab_slack::<T>(),
        }
    }

    /// Where the segment enters the box `[min, max]`, as a lower bound on the
    /// exact parameter, or `None` when the segment certainly misses the box.
    ///
    /// **Method** (Kay and Kajiya's slabs, Ericson §5.3.3): per axis with
    /// `d_k ≠ 0`, the parameters `(near_k − o_k)/d_k` and `(far_k − o_k)/d_k`
    /// (near and far the box's planes in the direction of travel) bound the
    /// segment's stay in the slab; the segment meets the box iff
    /// `max(0, entering) ≤ min(1, leaving)`. A flat axis (`d_k = 0`) is decided
    /// exactly (`min_k ≤ o_k ≤ max_k`).
    ///
    /// **Conservative.** The test accepts when
    /// `entering ≤ leaving + slack` ([`slab_slack`]), which the computed values
    /// satisfy whenever the exact ones meet; the returned bound
    /// `entering − slack` is below the exact entering parameter, hence below
    /// the segment parameter of every point of the box on the segment. Rounding
    /// is monotone, so the near plane's computed parameter never exceeds the
    /// far one's. Overflowing differences give `±∞` on the side the exact value
    /// lies (beyond `[0, 1]`), so they cull correctly.
    #[inline(always)]
    pub(crate) fn entry(&self, min: &[T; 3], max: &[T; 3]) -> Option<T> {
        let mut enter = T::zero();
        let mut exit = T::one();
        if self.all_slab {
            for k in 0..3 {
                let (near, far) = if self.negative[k] { (max[k], min[k]) } else { (min[k], max[k]) };
                // No NaN can arise here (finite non-zero reciprocals), so
                // `max`/`min` are plain selections, compiled without branches.
                enter = enter.max((near - self.o[k]) * self.inv[k]);
                exit = exit.min((far - self.o[k]) * self.inv[k]);
            }
        } else {
            for k in 0..3 {
                match self.axis[k] {
                    Axis::Slab => {
                        let t0 = (min[k] - self.o[k]) * self.inv[k];
                        let t1 = (max[k] - self.o[k]) * self.inv[k];
                        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
                        enter = if near > enter { near } else { enter };
                        exit = if far < exit { far } else { exit };
                    }
                    Axis::Flat => {
                        if self.o[k] < min[k] || self.o[k] > max[k] {
                            return None;
                        }
                    }
                    Axis::Free => {}
                }
            }
        }
        if enter <= exit + self.slack { Some(enter - self.slack) } else { None }
    }
}

impl SegmentProbe<f64> {
    /// [`entry`](Self::entry) for both children of a [`Wide`] record at once:
    /// per child, the lower bound on where the segment enters its box, or `+∞`
    /// when it certainly misses it. Same method, slack and analysis.
    #[inline(always)]
    pub(crate) fn entries(&self, w: &Wide) -> [f64; 2] {
        let mut enter = [0.0f64; 2];
        let mut exit = [1.0f64; 2];
        if self.all_slab {
            for k in 0..3 {
                let (near, far) = if self.negative[k] { (&w.max[k], &w.min[k]) } else { (&w.min[k], &w.max[k]) };
                for j in 0..2 {
                    // Selections, not `f64::max`: no NaN can arise (finite
                    // non-zero reciprocals), and these compile without branches.
                    let tn = (near[j] - self.o[k]) * self.inv[k];
                    let tf = (far[j] - self.o[k]) * self.inv[k];
                    enter[j] = if tn > enter[j] { tn } else { enter[j] };
                    exit[j] = if tf < exit[j] { tf } else { exit[j] };
                }
            }
        } else {
            for k in 0..3 {
                for j in 0..2 {
                    let (lo, hi) = (w.min[k][j], w.max[k][j]);
                    match self.axis[k] {
                        Axis::Slab => {
                            let t0 = (lo - self.o[k]) * self.inv[k];
                            let t1 = (hi - self.o[k]) * self.inv[k];
                            let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
                            enter[j] = if near > enter[j] { near } else { enter[j] };
                            exit[j] = if far < exit[j] { far } else { exit[j] };
                        }
                        Axis::Flat => {
                            if self.o[k] < lo || self.o[k] > hi {
                                exit[j] = f64::NEG_INFINITY;
                            }
                        }
                        Axis::Free => {}
                    }
                }
            }
        }
        // Written out, not `[0, 1].map(..)`, which is not always inlined.
        let slack = self.slack;
        let entry = |j: usize| if enter[j] <= exit[j] + slack { enter[j] - slack } else { f64::INFINITY };
        [entry(0), entry(1)]
    }

    /// Whether every axis is a usual slab ([`entry`](Self::entry)'s
    /// branch-free case): [`keep_lanes`](Self::keep_lanes) needs it.
    pub(crate) fn all_slab(&self) -> bool {
        self.all_slab
    }

    /// [`entry`](Self::entry)'s test over arrays of boxes, for a segment all
    /// of whose axes are slabs ([`all_slab`](Self::all_slab); else every
    /// lane is kept): `keep[i]` is false when the segment certainly misses
    /// box `i` (`lo[k][i] ≤ x_k ≤ hi[k][i]`). The same arithmetic, slack and
    /// analysis, without a branch, so that the loop vectorizes (out of line,
    /// a function of its own); every array is cut to `keep`'s length first
    /// (no bounds checks in the loop).
    #[inline(never)]
    pub(crate) fn keep_lanes(&self, lo: [&[f64]; 3], hi: [&[f64]; 3], keep: &mut [bool]) {
        let len = keep.len();
        if !self.all_slab {
            keep.fill(true);
            return;
        }
        // Per axis, the planes the segment enters and leaves through.
        let pick =
            |k: usize| if self.negative[k] { (&hi[k][..len], &lo[k][..len]) } else { (&lo[k][..len], &hi[k][..len]) };
        let ((nx, fx), (ny, fy), (nz, fz)) = (pick(0), pick(1), pick(2));
        let (o, inv, slack) = (self.o, self.inv, self.slack);
        for i in 0..len {
            let mut enter = 0.0f64;
            let mut exit = 1.0f64;
            for (k, (near, far)) in [(nx[i], fx[i]), (ny[i], fy[i]), (nz[i], fz[i])].into_iter().enumerate() {
                let tn = (near - o[k]) * inv[k];
                let tf = (far - o[k]) * inv[k];
                enter = if tn > enter { tn } else { enter };
                exit = if tf < exit { tf } else { exit };
            }
            keep[i] = enter <= exit + slack;
        }
    }
}

/// Relative slack of the sphere culling, `8ε` of the type (16 units of
/// roundoff). Reason: a face's distance and a box's distance are each computed
/// by [`stable_norm`] (one division and one multiplication by the largest
/// component, three squares, two sums and a square root: within `4.5u` of the
/// exact norm of the computed difference vector), and the computed difference
/// vectors are ordered componentwise (see [`box_distance_lower_bound`]); two
/// such errors are at most `9u + O(u²)`.
fn sphere_slack<T: Real>() -> T {
    c::<T>(8.0) * T::EPSILON
}

/// A lower bound on the distance [`contact_sphere_mesh_bvh`](super::contact_sphere_mesh_bvh)
/// computes from `center` to any face inside the box `[min, max]`:
/// `stable_norm(center − clamp(center, min, max))·(1 − 16u) − ε³`.
///
/// **Why it is a bound.** The per-face computation clamps its closest point `q`
/// into the face's box, which lies inside `[min, max]`; so for each axis
/// `|c_k − q_k| ≥ |c_k − clamp(c_k)|` exactly, with the same sign, and the
/// rounded differences keep that order (rounding is monotone). The two norms
/// then differ from the exact norms of those ordered vectors by at most `4.5u`
/// each ([`sphere_slack`]).
#[inline(always)]
pub(crate) fn box_distance_lower_bound<T: Real>(center: &Vec3<T>, min: &[T; 3], max: &[T; 3]) -> T {
    let mut d = Vec3::zeros();
    for k in 0..3 {
        let p = center[k].max(min[k]).min(max[k]);
        d[k] = center[k] - p;
    }
    // Written as a product so that an infinite distance stays infinite.
    stable_norm(&d) * (T::one() - sphere_slack::<T>()) - tiny::<T>()
}
