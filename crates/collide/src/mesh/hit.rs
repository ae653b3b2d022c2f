//! The results of mesh queries.

use crate::contact::Contact;
use crate::real::{Real, Vec3};

/// Where a segment first meets a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshHit<T: Real> {
    /// Segment parameter of the hit, in `[0, 1]`: `point = start + t (end − start)`.
    pub t: T,
    /// The hit point.
    pub point: Vec3<T>,
    /// The face's own unit normal `(v1 − v0) × (v2 − v0)` normalized, never
    /// flipped toward the segment.
    pub normal: Vec3<T>,
    /// `[α, β, γ]` with `point = α v0 + β v1 + γ v2` for the face's vertices.
    pub barycentric: [T; 3],
    /// Index of the face hit (0-based, as in [`TriMesh::faces`](super::TriMesh::faces)).
    pub triangle: usize,
}

/// The answer of a segment–mesh query, with the fixture format's rule for meshes:
///
/// - `hit`: the first hit (smallest `t`; ties to the lowest face index), or `None`;
/// - `parallel`: nothing is hit, the mesh has at least one face with area, and
///   the segment is parallel to every face with area (a flat mesh and a segment
///   in its plane, say);
/// - `degenerate`: the segment has zero length or a non-finite coordinate (no
///   hit then), or the mesh has a degenerate face (zero area, or a non-finite
///   vertex): such a face is skipped, and the flag says the answer ignored it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshIntersection<T: Real> {
    /// First hit, if any.
    pub hit: Option<MeshHit<T>>,
    /// No hit, and the segment is parallel to every face with area.
    pub parallel: bool,
    /// A degenerate segment, or a degenerate face skipped.
    pub degenerate: bool,
}

impl<T: Real> MeshIntersection<T> {
    /// Degenerate segment: no hit, not parallel, flagged.
    pub const DEGENERATE: Self = Self { hit: None, parallel: false, degenerate: true };
}

/// The deepest contact between a sphere and a mesh: the contact with the face
/// closest to the sphere's centre, in the convention of [`Contact`] (the mesh is
/// `b`: the point lies on the mesh, the normal points from the mesh toward the
/// sphere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshContact<T: Real> {
    /// The contact with that face.
    pub contact: Contact<T>,
    /// Index of the face.
    pub triangle: usize,
}
