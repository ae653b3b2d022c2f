//! Contact queries: where a sphere touches or sinks into another shape.
//!
//! One file per shape pair; every function takes `(a, b)` and answers in the
//! convention of [`Contact`] (normal from `b` toward `a`, point on `b`). The
//! reverse orders are thin wrappers over [`Contact::swapped`], but for the
//! triangle's, which forms the sphere's deepest point from its centre.

mod closest_pt_triangle;
#[allow(
    clippy::module_inception,
    reason = "`contact::contact` holds the result type; users name it `contact::Contact`"
)]
mod contact;
mod exact_boundary;
mod sphere_plane;
mod sphere_sphere;
mod sphere_triangle;

pub use closest_pt_triangle::{closest_pt_point_segment, closest_pt_point_triangle};
pub use contact::Contact;
pub(crate) use exact_boundary::Distance;
pub(crate) use sphere_plane::{clearly_apart, contact_sphere_plane_parts, normal_parts};
pub use sphere_plane::{contact_plane_sphere, contact_sphere_plane};
pub use sphere_sphere::{CONCENTRIC_FALLBACK_NORMAL, contact_sphere_sphere, contact_sphere_sphere_lecture};
pub use sphere_triangle::{contact_sphere_triangle, contact_triangle_sphere};
pub(crate) use sphere_triangle::{contact_sphere_triangle_ranked, face_unit_normal};
