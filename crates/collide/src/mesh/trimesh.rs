//! A triangle mesh: vertices and faces, with what every mesh query needs to know
//! about them computed once.

use super::filter::FILTER_MAX_COORD;
use crate::exact::filter::{cross, sub, triple};
use crate::exact::{self, P3};
use crate::real::{Real, Vec3, finite3, to_f64_3};
use crate::shapes::{Aabb, Triangle};
use core::fmt;

/// Why a mesh cannot be built. Degenerate geometry is *not* an error (zero-area
/// faces and non-finite vertices are answered by the queries with their
/// documented fallback); only input that no query could even read is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshError {
    /// A face names a vertex that does not exist.
    IndexOutOfRange {
        /// The face.
        face: usize,
        /// Which of its three corners (0, 1, 2).
        corner: usize,
        /// The index it names.
        index: usize,
        /// How many vertices the mesh has.
        vertices: usize,
    },
    /// More faces than a [`MeshBvh`](super::MeshBvh) indexes (`u32::MAX`).
    TooManyFaces {
        /// How many faces were given.
        faces: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            MeshError::IndexOutOfRange { face, corner, index, vertices } => {
                write!(f, "face {face} corner {corner}: vertex index {index} out of range ({vertices} vertices)")
            }
            MeshError::TooManyFaces { faces } => {
                write!(f, "{faces} faces: at most {} are supported", u32::MAX)
            }
        }
    }
}

impl std::error::Error for MeshError {}

/// A triangle soup: each face `[i, j, k]` indexes `vertices` and is oriented as a
/// [`Triangle`] (face normal `(vj − vi) × (vk − vi)`).
///
/// Built once by [`TriMesh::new`], which checks the indices and computes:
///
/// - which faces are **degenerate**: a face with a non-finite vertex, or with
///   zero area (collinear vertices, decided exactly by
///   [`exact::collinear`]) — the segment queries skip them and flag their
///   answers `degenerate`;
/// - the mesh's **AABB**, the box of the vertices of every face whose vertices
///   are finite (the `_culled` queries' bounding volume);
/// - three **witness faces** used to answer the `parallel` flag of a missing
///   segment quickly (see [`intersect_segment_mesh_brute`](super::intersect_segment_mesh_brute)).
///
/// The mesh is immutable after construction, so these stay true.
#[derive(Clone, Debug, PartialEq)]
pub struct TriMesh<T: Real> {
    vertices: Vec<Vec3<T>>,
    faces: Vec<[usize; 3]>,
    /// Per face: degenerate (non-finite vertex or zero area).
    degenerate: Vec<bool>,
    /// Per face: some vertex is not finite.
    nonfinite: Vec<bool>,
    degenerate_count: usize,
    aabb: Option<Aabb<T>>,
    witnesses: [Option<usize>; 3],
    /// Per witness within the filter's range (every vertex at most
    /// [`FILTER_MAX_COORD`]): its rounded normal `fl((v1 − v0) × (v2 − v0))` and
    /// the normal's permanents, for the filtered parallel test.
    witness_normals: [Option<(P3, P3)>; 3],
}

impl<T: Real> TriMesh<T> {
    /// Builds a mesh, refusing a face index out of range (or more than
    /// `u32::MAX` faces). An empty mesh (no faces) is allowed: every query
    /// answers it with no hit and no contact.
    ///
    /// Cost: one exact collinearity test per face (a few `f64` operations each,
    /// exact arithmetic only for faces within rounding of collinear).
    pub fn new(vertices: Vec<Vec3<T>>, faces: Vec<[usize; 3]>) -> Result<Self, MeshError> {
        if faces.len() > u32::MAX as usize {
            return Err(MeshError::TooManyFaces { faces: faces.len() });
        }
        for (face, f) in faces.iter().enumerate() {
            for (corner, &index) in f.iter().enumerate() {
                if index >= vertices.len() {
                    return Err(MeshError::IndexOutOfRange { face, corner, index, vertices: vertices.len() });
                }
            }
        }
        let mut degenerate = Vec::with_capacity(faces.len());
        let mut nonfinite = Vec::with_capacity(faces.len());
        let mut aabb: Option<Aabb<T>> = None;
        // Witnesses: per axis, the face with area whose normal is most aligned
        // with it (|n_i| / ‖n‖₁ largest, in f64; only the search order depends on
        // these roundings).
        let mut witnesses = [None; 3];
        let mut alignment = [f64::NEG_INFINITY; 3];
        for (i, f) in faces.iter().enumerate() {
            let [a, b, c] = f.map(|k| vertices[k]);
            let finite = finite3(&a) && finite3(&b) && finite3(&c);
            nonfinite.push(!finite);
            if !finite {
                degenerate.push(true);
                continue;
            }
            for p in [a, b, c] {
                let bb = aabb.get_or_insert(Aabb::new(p, p));
                for k in 0..3 {
                    if p[k] < bb.min[k] {
                        bb.min[k] = p[k];
                    }
                    if p[k] > bb.max[k] {
                        bb.max[k] = p[k];
                    }
                }
            }
            let (pa, pb, pc) = (to_f64_3(&a), to_f64_3(&b), to_f64_3(&c));
            let flat = exact::collinear(pa, pb, pc);
            degenerate.push(flat);
            if flat {
                continue;
            }
            let u = [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]];
            let v = [pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]];
            let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
            let l1 = n[0].abs() + n[1].abs() + n[2].abs();
            for axis in 0..3 {
                let al = if l1 > 0.0 && l1.is_finite() { n[axis].abs() / l1 } else { 0.0 };
                if al > alignment[axis] {
                    alignment[axis] = al;
                    witnesses[axis] = Some(i);
                }
            }
        }
        let degenerate_count = degenerate.iter().filter(|d| **d).count();
        let witness_normals = witnesses.map(|w| {
            let [a, b, c] = faces[w?].map(|k| to_f64_3(&vertices[k]));
            let small = [a, b, c].iter().flatten().all(|x| x.abs() <= FILTER_MAX_COORD);
            small.then(|| cross(sub(b, a), sub(c, a)))
        });
        Ok(Self { vertices, faces, degenerate, nonfinite, degenerate_count, aabb, witnesses, witness_normals })
    }

    /// The vertex positions.
    pub fn vertices(&self) -> &[Vec3<T>] {
        &self.vertices
    }

    /// The faces, 0-based vertex indices.
    pub fn faces(&self) -> &[[usize; 3]] {
        &self.faces
    }

    /// Number of faces.
    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// Whether the mesh has no face.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// Face `i` as a triangle. Panics if `i ≥ len()`, like slice indexing.
    pub fn triangle(&self, i: usize) -> Triangle<T> {
        let [a, b, c] = self.faces[i];
        Triangle::new(self.vertices[a], self.vertices[b], self.vertices[c])
    }

    /// Whether face `i` is degenerate: a non-finite vertex, or zero area
    /// (exactly). Panics if `i ≥ len()`.
    pub fn is_degenerate_face(&self, i: usize) -> bool {
        self.degenerate[i]
    }

    /// Whether face `i` has a non-finite vertex (such a face takes part in no
    /// query). Panics if `i ≥ len()`.
    pub fn has_nonfinite_vertex(&self, i: usize) -> bool {
        self.nonfinite[i]
    }

    /// Number of degenerate faces.
    pub fn degenerate_face_count(&self) -> usize {
        self.degenerate_count
    }

    /// The box of the vertices of every face whose vertices are finite; `None`
    /// when there is no such face.
    pub fn aabb(&self) -> Option<Aabb<T>> {
        self.aabb
    }

    /// Whether the segment `q0 q1` (as `f64`, non-degenerate) is parallel to every
    /// face with area, exactly; `false` when the mesh has no face with area.
    ///
    /// A face is parallel when `((v1 − v0) × (v2 − v0)) · (q1 − q0) = 0` exactly
    /// ([`exact::triple_product`]), the robust segment–triangle test's parallel
    /// condition; a degenerate face gives 0 too, so only the existence of a face
    /// with area needs separate care. The witnesses go first: for a segment
    /// that is not parallel to the mesh, one of them almost always answers, so
    /// a miss costs one or two predicates instead of a scan — first through a
    /// floating-point filter (the triple product `n̂ · r̂` of the witness's
    /// precomputed rounded normal and `r̂ = fl(q1 − q0)`, with
    /// `crate::exact::filter`'s bound: a value beyond its bound is certainly
    /// non-zero, so the segment is certainly not parallel to that face).
    pub(crate) fn parallel_to_every_face(&self, q0: [f64; 3], q1: [f64; 3]) -> bool {
        if self.degenerate_count == self.faces.len() {
            return false;
        }
        if q0.iter().chain(&q1).all(|x| x.abs() <= FILTER_MAX_COORD) {
            let r = sub(q1, q0);
            if self.witness_normals.iter().flatten().any(|(n, n_perm)| triple(*n, *n_perm, r).decided()) {
                return false;
            }
        }
        let crosses = |i: usize| {
            let [a, b, c] = self.faces[i].map(|k| to_f64_3(&self.vertices[k]));
            !self.degenerate[i] && exact::triple_product(a, b, a, c, q0, q1) != exact::Sign::Zero
        };
        if self.witnesses.iter().flatten().any(|&i| crosses(i)) {
            return false;
        }
        !(0..self.faces.len()).any(crosses)
    }
}
