//! Triangle meshes: a bounding volume hierarchy over their faces, and the queries
//! that take a mesh.
//!
//! The lecture motivates bounding volumes with meshes: a segment tested against
//! every triangle pays for every triangle, even when it misses the whole mesh.
//! Each mesh query therefore comes in three variants, all public so crashtest can
//! time and compare them:
//!
//! | suffix | what it tests |
//! | --- | --- |
//! | `_brute` | every face, in index order (the lecture's method) |
//! | `_culled` | one bounding volume of the whole mesh first (its AABB), then every face |
//! | `_bvh` | the faces a [`MeshBvh`] (an AABB tree) cannot rule out |
//!
//! **The three variants give identical answers**, bit for bit: they decide each
//! face by the same exact predicates, pick the winner by the same total order
//! and compute its values the same way, and every culling test (boxes, the
//! BVH's floating-point filter) is conservative: it may keep a face that cannot
//! win, never drop one that could. The robust segment queries classify faces
//! exactly as
//! [`intersect_segment_triangle`](crate::intersect::intersect_segment_triangle)
//! does, compare the faces' segment parameters exactly, and report the winning
//! face's values to that query's accuracy (about `2^−40`; computed once, for
//! the winner, by a certified path of their own, that query answering when the
//! path cannot certify them), so their answer is the exact first hit, ties
//! included.
//!
//! Queries:
//!
//! - segment–mesh first hit ([`intersect_segment_mesh_brute`],
//!   [`intersect_segment_mesh_culled`], [`intersect_segment_mesh_bvh`], and the
//!   lecture's [`intersect_segment_mesh_lecture`]), answering a
//!   [`MeshIntersection`] whose [`MeshHit`] names the face;
//! - many segments against one mesh at once ([`intersect_segments_mesh`] over
//!   a mesh's [`FaceArrays`]): every face, its box culled in packed lanes first;
//!   each answer the same bits as [`intersect_segment_mesh_brute`]'s;
//! - sphere–mesh contact, the deepest over the faces
//!   ([`contact_sphere_mesh_brute`], [`contact_sphere_mesh_culled`],
//!   [`contact_sphere_mesh_bvh`]), answering a [`MeshContact`].
//!
//! **Tie rule** (documented once, used everywhere): when several faces share the
//! winning value — a segment through an edge or a vertex shared by faces, a
//! sphere whose closest points on two faces are equally far — the **lowest face
//! index** wins. crashtest's referee uses the same rule.

mod bvh;
mod filter;
mod hit;
mod segment_batch;
mod segment_mesh;
mod sphere_mesh;
mod trimesh;
mod values;

#[cfg(test)]
mod tests;

pub use bvh::{BVH_MAX_DEPTH, MeshBvh, SplitRule};
pub use hit::{MeshContact, MeshHit, MeshIntersection};
pub use segment_batch::{FaceArrays, intersect_segments_mesh};
pub use segment_mesh::{
    intersect_segment_mesh_brute, intersect_segment_mesh_bvh, intersect_segment_mesh_culled,
    intersect_segment_mesh_lecture,
};
pub(crate) use sphere_mesh::contact_sphere_mesh_nearest;
pub use sphere_mesh::{
    contact_sphere_mesh_brute, contact_sphere_mesh_bvh, contact_sphere_mesh_culled, contact_sphere_mesh_nearest_bvh,
};
pub use trimesh::{MeshError, TriMesh};
