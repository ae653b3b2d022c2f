//! Batch queries over contiguous arrays: many pairs at once, laid out as a
//! structure of arrays so that the compiler can vectorize the loop.
//!
//! One query at a time, a sphere–sphere contact is a dozen dependent
//! operations and a square root; a loop over many pairs is then bound by
//! latency and by the branch on each pair's outcome. Here the pairs come as
//! separate arrays of `x`, `y`, `z` and radius ([`Spheres`]), every lane is
//! computed the same way without branches (the outcome is a mask, the answers
//! of non-contacts are zeroed by selection), and the results go to arrays of
//! the same shape ([`SphereContacts`]): the loop body is straight-line
//! arithmetic on slices, which the compiler turns into packed SIMD.
//!
//! Each lane computes exactly what the one-pair function computes, in the same
//! order, so the answers are the same to the bit ([`contact_spheres_spheres`]
//! against [`crate::contact::contact_sphere_sphere`]); the rare lane the fast
//! arithmetic cannot answer (a squared distance that would underflow or
//! overflow, other than exactly concentric centres, and for the overlap test
//! nearly concentric ones that certainly touch) is answered afterwards by the
//! one-pair function itself.
//!
//! Each batch type keeps its arrays in one allocation, their starts
//! staggered modulo 4 KiB (`columns.rs`): arrays allocated one by one at a
//! power-of-two length start at the same offset in their pages, and a loop
//! reading a dozen of them at once then evicts its own lines from the L1
//! cache (the box batch ran at 2.2 ns per pair that way, 1.3 staggered, on
//! the same data).
//!
//! Boxes ([`Aabbs`]) come the same way: [`test_aabbs_aabbs`] pairwise and
//! [`test_aabb_aabbs`] one box against many (the broad phase), the same six
//! comparisons as [`crate::bounds::test_aabb_aabb`] per lane.
//! Segments against one mesh ([`intersect_segments_mesh`] over the mesh's
//! [`FaceArrays`], defined with the other mesh queries in [`crate::mesh`])
//! test each segment against every face's box in packed lanes, and
//! only the faces kept go on to the filter and the exact test.
//! `cargo bench --bench queries` measures the pair batches against the
//! one-at-a-time loop, `cargo bench --bench mesh` the segment batch.

pub(crate) mod aabb;
mod columns;
mod sphere_sphere;

pub use crate::mesh::{FaceArrays, intersect_segments_mesh};
pub use aabb::{Aabbs, test_aabb_aabbs, test_aabbs_aabbs};
pub use sphere_sphere::{SphereContacts, Spheres, contact_spheres_spheres, test_spheres_spheres};
