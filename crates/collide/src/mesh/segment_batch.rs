//! Many segments against one mesh: the faces laid out as a structure of
//! arrays, each segment tested against all of them in packed lanes first.

use super::filter::{FILTER_MAX_COORD, FaceFilter, SegmentFilter};
use super::hit::MeshIntersection;
use super::segment_mesh::{Candidate, brute, filtered_face, finish, prepare};
use super::trimesh::TriMesh;
use crate::exact::P3;
use crate::real::Real;
use crate::shapes::{Segment, Triangle};

/// Faces per block of the lane pass: the lanes' keep flags of one block fit
/// in 64 bytes (one cache line), and a block's arrays (15 × 64 `f64`, 7.5 KiB)
/// stay in L1 between the lane pass and the faces it keeps.
const BLOCK: usize = 64;

/// A mesh's faces prepared for [`intersect_segments_mesh`]: every face with
/// area, in index order, as separate arrays of each coordinate of its
/// vertices, its rounded normal and that normal's permanents (what each lane
/// of the filter reads), beside the per-face filter data and triangles the
/// faces the lanes keep are read from. Built once per mesh; owns the mesh.
#[derive(Clone, Debug)]
pub struct FaceArrays<T: Real> {
    mesh: TriMesh<T>,
    /// Per lane: the mesh's face index.
    face: Vec<usize>,
    /// Per lane: the face's vertices, in `f64` (`v[i][k]`: vertex `i`,
    /// coordinate `k`).
    v: [[Vec<f64>; 3]; 3],
    /// Per lane: the face's box, `lo[k] ≤ v[i][k] ≤ hi[k]` (exact: the
    /// vertices' least and greatest coordinates).
    lo: [Vec<f64>; 3],
    hi: [Vec<f64>; 3],
    /// Per lane: the rounded normal `n̂ = fl((v1 − v0) × (v2 − v0))`.
    n: [Vec<f64>; 3],
    /// Per lane: the normal's computed permanents.
    n_perm: [Vec<f64>; 3],
    /// Per lane: the face's filter data (vertices, normal, permanents).
    filters: Vec<FaceFilter>,
    /// Per lane: the face as a triangle.
    tris: Vec<Triangle<T>>,
    /// Whether every vertex is within the filter's range.
    filter_ok: bool,
}

impl<T: Real> FaceArrays<T> {
    /// The arrays of `mesh`'s faces with area (degenerate faces — zero area
    /// or a non-finite vertex — take part in no query and are left out).
    pub fn new(mesh: TriMesh<T>) -> Self {
        let mut arrays = Self {
            face: Vec::new(),
            v: Default::default(),
            lo: Default::default(),
            hi: Default::default(),
            n: Default::default(),
            n_perm: Default::default(),
            filters: Vec::new(),
            tris: Vec::new(),
            filter_ok: true,
            mesh,
        };
        for i in (0..arrays.mesh.len()).filter(|&i| !arrays.mesh.is_degenerate_face(i)) {
            let tri = arrays.mesh.triangle(i);
            let v: [P3; 3] = tri.vertices.map(|p| [p.x.wide(), p.y.wide(), p.z.wide()]);
            arrays.filter_ok &= v.iter().flatten().all(|x| x.abs() <= FILTER_MAX_COORD);
            let f = FaceFilter::new(v);
            for k in 0..3 {
                for (i, p) in v.iter().enumerate() {
                    arrays.v[i][k].push(p[k]);
                }
                arrays.lo[k].push(v[0][k].min(v[1][k]).min(v[2][k]));
                arrays.hi[k].push(v[0][k].max(v[1][k]).max(v[2][k]));
                arrays.n[k].push(f.n[k]);
                arrays.n_perm[k].push(f.n_perm[k]);
            }
            arrays.face.push(i);
            arrays.filters.push(f);
            arrays.tris.push(tri);
        }
        arrays
    }

    /// The mesh.
    pub fn mesh(&self) -> &TriMesh<T> {
        &self.mesh
    }

    /// The mesh back.
    pub fn into_mesh(self) -> TriMesh<T> {
        self.mesh
    }

    /// Number of lanes: the faces with area.
    pub fn len(&self) -> usize {
        self.face.len()
    }

    /// Whether no face has area.
    pub fn is_empty(&self) -> bool {
        self.face.is_empty()
    }
}

/// First hits of many segments on one mesh: `out` is cleared and gets one
/// answer per segment, in order, each equal **bit for bit** to
/// [`intersect_segment_mesh_brute`](super::intersect_segment_mesh_brute)'s
/// (and so to the BVH query's): the exact first hit, ties to the lowest face
/// index, the same flags.
///
/// **How it goes.** For each segment, every face is first put through the
/// BVH query's floating-point filter in packed lanes, a block of faces at a
/// time: the endpoints' volumes over the face and the three edge volumes,
/// with their static error bounds, computed branch-free over the arrays of
/// [`FaceArrays`] (straight-line arithmetic the compiler vectorizes), and the
/// filter's "certainly no hit" decided as a mask. A face it rules out is not
/// looked at again — all but a handful of faces, for most segments. The
/// faces left (hits, and the few the filter cannot decide) go one at a time
/// through the filter's scalar form and, where it cannot decide, the exact
/// test, and the hits are ordered exactly as the other variants order them. The filter is used when every coordinate is at
/// most 2^60 in magnitude; a segment beyond that (or any segment, on a mesh
/// beyond it) is answered by the brute-force query itself.
///
/// **When to use it.** It tests every face, as the brute-force query does,
/// only faster; for a mesh of more than a few hundred faces the BVH query
/// ([`intersect_segment_mesh_bvh`](super::intersect_segment_mesh_bvh)), which
/// visits only the faces near each segment, is faster still
/// (`cargo bench --bench mesh` measures both against the one-at-a-time loop).
///
/// **Degenerate input:** as the one-segment queries — a segment with a
/// non-finite coordinate or zero length gets
/// [`MeshIntersection::DEGENERATE`]. Never NaN, never a panic.
pub fn intersect_segments_mesh<T: Real>(
    segs: &[Segment<T>],
    faces: &FaceArrays<T>,
    out: &mut Vec<MeshIntersection<T>>,
) {
    out.clear();
    out.reserve(segs.len());
    let mut keep = [false; BLOCK];
    for seg in segs {
        let Some((q0, q1)) = prepare(seg) else {
            out.push(MeshIntersection::DEGENERATE);
            continue;
        };
        let q = [q0, q1];
        let Some(filter) = SegmentFilter::new(q0, q1).filter(|_| faces.filter_ok) else {
            out.push(brute(seg, &faces.mesh, q));
            continue;
        };
        let mut best: Option<Candidate<T>> = None;
        let n = faces.len();
        let mut start = 0;
        while start < n {
            let end = (start + BLOCK).min(n);
            let cut = |x| block(x, start, end);
            let kept = &mut keep[..end - start];
            box_lanes(q, cut(&faces.lo), cut(&faces.hi), kept);
            for (j, _) in kept.iter().enumerate().filter(|(_, k)| **k) {
                let k = start + j;
                filtered_face(&faces.filters[k], Some(&filter), q, &mut best, || (&faces.tris[k], faces.face[k]));
            }
            start = end;
        }
        out.push(finish(best, seg, &faces.mesh, q));
    }
}

/// The box pass of one block: `keep[i]` is whether face `i`'s box meets the
/// segment's (touching counts). Exact comparisons of exact coordinates: a
/// face the segment hits has the hit point in both boxes, so no hit is
/// dropped. Branch-free; a function of its own, with every array cut to the
/// block's length, so that the loop needs no bounds checks and vectorizes.
#[inline(never)]
fn box_lanes(q: [P3; 2], lo: [&[f64]; 3], hi: [&[f64]; 3], keep: &mut [bool]) {
    let len = keep.len();
    let ([lx, ly, lz], [hx, hy, hz]) = (prefix(lo, len), prefix(hi, len));
    let smin = [0, 1, 2].map(|k| q[0][k].min(q[1][k]));
    let smax = [0, 1, 2].map(|k| q[0][k].max(q[1][k]));
    for i in 0..len {
        keep[i] = (lx[i] <= smax[0])
            & (ly[i] <= smax[1])
            & (lz[i] <= smax[2])
            & (hx[i] >= smin[0])
            & (hy[i] >= smin[1])
            & (hz[i] >= smin[2]);
    }
}

/// Lanes `start..end` of three arrays.
#[inline(always)]
fn block(x: &[Vec<f64>; 3], start: usize, end: usize) -> [&[f64]; 3] {
    [&x[0][start..end], &x[1][start..end], &x[2][start..end]]
}

/// The first `len` lanes of three arrays.
#[inline(always)]
fn prefix(x: [&[f64]; 3], len: usize) -> [&[f64]; 3] {
    [&x[0][..len], &x[1][..len], &x[2][..len]]
}
