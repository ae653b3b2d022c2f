//! Bounding volumes: AABBs by expansion and their overlap test, and bounding
//! spheres three ways (the lecture's centroid sphere, Ritter's, and the minimal
//! one by Welzl's algorithm).

mod aabb_from_points;
mod aabb_of_segment;
mod aabb_of_sphere;
mod aabb_of_triangle;
mod bounding_sphere;
mod bounding_sphere_centroid;
mod bounding_sphere_minimal;
mod bounding_sphere_ritter;
mod sphere_frame;
mod test_aabb_aabb;

pub use aabb_from_points::aabb_from_points;
pub use aabb_of_segment::aabb_of_segment;
pub use aabb_of_sphere::aabb_of_sphere;
pub use aabb_of_triangle::aabb_of_triangle;
pub use bounding_sphere::BoundingSphere;
pub use bounding_sphere_centroid::bounding_sphere_centroid;
pub use bounding_sphere_minimal::bounding_sphere_minimal;
pub use bounding_sphere_ritter::bounding_sphere_ritter;
pub use test_aabb_aabb::test_aabb_aabb;
#[cfg(test)]
mod tests;
