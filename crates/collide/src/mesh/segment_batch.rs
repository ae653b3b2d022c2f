//! Many segments against one mesh: the faces laid out as a structure of
//! arrays, each segment tested against all of them in packed lanes first.

use super::bvh::SegmentProbe;
use super::filter::{FILTER_MAX_COORD, FaceFilter, SegmentFilter};
use super::hit::MeshIntersection;
use super::segment_mesh::{Candidate, brute, filtered_face, finish, prepare};
use super::trimesh::TriMesh;
use crate::batch::Aabbs;
use crate::batch::aabb::overlap_lanes;
use crate::exact::P3;
use crate::real::{Real, Vec3};
use crate::shapes::{Aabb, Segment, Triangle};

/// Faces per block of the lane pass: the lanes' keep flags of one block fit
/// in 64 bytes (one cache line), on the stack.
const BLOCK: usize = 64;

/// A mesh's faces prepared for [`intersect_segments_mesh`]: every face with
/// area, in index order, its box as six separate arrays (what each lane of
/// the culling pass reads), beside the per-face filter data and triangles
/// the faces kept are read from. Built once per mesh (a few copies per face,
/// no tree: about a tenth of the BVH's build time on the bunny); owns the mesh.
#[derive(Clone, Debug)]
pub struct FaceArrays<T: Real> {
    mesh: TriMesh<T>,
    /// Per lane: the mesh's face index.
    face: Vec<usize>,
    /// Per lane: the face's box (exact: the vertices' least and greatest
    /// coordinates, in `f64`).
    boxes: Aabbs<f64>,
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
            boxes: Aabbs::new(),
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
            arrays.boxes.push(&points_box(v));
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
/// **How it goes.** For each segment, every face's box is first tested
/// against the segment in packed lanes, a block of faces at a time,
/// branch-free over the arrays of [`FaceArrays`] (straight-line arithmetic
/// the compiler vectorizes): the BVH's conservative slab test (where the
/// segment enters and leaves each box, with a slack for rounding), or, for a
/// segment with a coordinate the same at both ends, the exact overlap of the
/// two boxes. A face whose box the segment certainly misses cannot be hit
/// and is not looked at again — most faces of a mesh, for most segments.
/// The faces kept go one at a time through the BVH query's
/// floating-point filter and, where it cannot decide, the exact test, and
/// the hits are ordered exactly as the other variants order them. The filter
/// is used when every coordinate is at most 2^60 in magnitude; a segment
/// beyond that (or any segment, on a mesh beyond it) is answered by the
/// brute-force query itself.
///
/// **When to use it.** It answers what the brute-force query answers, an
/// order of magnitude faster on meshes of a few hundred faces or more, and
/// needs no tree: building its arrays costs a fraction of building a
/// [`MeshBvh`](super::MeshBvh) (a mesh that deforms every frame). Its cost
/// still grows with the number of faces; the BVH query
/// ([`intersect_segment_mesh_bvh`](super::intersect_segment_mesh_bvh)), which
/// visits only the faces near each segment, is about as fast on a few dozen
/// faces and far faster on more. `cargo bench --bench mesh` measures the
/// batch against both loops on terrains of 8, 32 and 288 faces and the bunny.
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
        let v3 = |p: P3| Vec3::new(p[0], p[1], p[2]);
        let probe = SegmentProbe::new(&Segment::new(v3(q0), v3(q1)));
        let seg_box = points_box([q0, q1]);
        let mut best: Option<Candidate<T>> = None;
        let n = faces.len();
        let mut start = 0;
        while start < n {
            let end = (start + BLOCK).min(n);
            let lanes = faces.boxes.lanes(start..end);
            let kept = &mut keep[..end - start];
            if probe.all_slab() {
                let [lx, ly, lz, hx, hy, hz] = lanes;
                probe.keep_lanes([lx, ly, lz], [hx, hy, hz], kept);
            } else {
                box_lanes(&seg_box, lanes, kept);
            }
            for (j, _) in kept.iter().enumerate().filter(|(_, k)| **k) {
                let k = start + j;
                filtered_face(&faces.filters[k], Some(&filter), q, &mut best, || (&faces.tris[k], faces.face[k]));
            }
            start = end;
        }
        out.push(finish(best, seg, &faces.mesh, q));
    }
}

/// The box pass of one block, for a segment with a coordinate the same at
/// both ends: `keep[i]` is whether face `i`'s box meets the segment's
/// (touching counts; [`overlap_lanes`], out of line so that it vectorizes).
/// Exact comparisons of exact coordinates: a face the segment hits has the
/// hit point in both boxes, so no hit is dropped.
#[inline(never)]
fn box_lanes(seg_box: &Aabb<f64>, lanes: [&[f64]; 6], keep: &mut [bool]) {
    overlap_lanes(seg_box, lanes, keep);
}

/// The box of points given in `f64` (exact: least and greatest coordinates).
fn points_box<const N: usize>(ps: [P3; N]) -> Aabb<f64> {
    let lo = [0, 1, 2].map(|k| ps.iter().fold(f64::INFINITY, |m, p| m.min(p[k])));
    let hi = [0, 1, 2].map(|k| ps.iter().fold(f64::NEG_INFINITY, |m, p| m.max(p[k])));
    Aabb::new(Vec3::new(lo[0], lo[1], lo[2]), Vec3::new(hi[0], hi[1], hi[2]))
}
