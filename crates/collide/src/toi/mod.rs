//! Time of impact: the first time in `[0, t_max]` at which a sphere moving
//! linearly touches another shape moving linearly, and the contact then.
//!
//! Three methods, side by side:
//!
//! - **interval halving** (`*_halving`, the lecture's): bisection on the static
//!   contact test, faithful down to what it misses — it needs the end of the
//!   interval to intersect, so a collision entered and left within the interval
//!   (tunneling) is not seen;
//! - **closed form** for sphere–sphere and sphere–plane: the touching time is a
//!   root of a quadratic (a linear equation for the plane), taken in a form
//!   without catastrophic cancellation;
//! - **closed form** for sphere–box (`toi_sphere_box`): in the box's own frame
//!   the faces give linear equations, the edges and corners quadratics, and
//!   the first contact is the least root whose contact lies on its feature;
//! - **conservative advancement** for triangles and meshes: step forward by a
//!   distance bound that can never step past the first contact, until the gap
//!   is below a tolerance; against a mesh, per face, over the faces its
//!   bounding volume hierarchy cannot rule out (or every face);
//! - **exact feature roots** for triangles and meshes whose coordinates reach
//!   far beyond the sphere's own scale, where advancement's rounding exceeds
//!   the sphere: the first contact with the face's plane (linear), each edge
//!   and each vertex (quadratics), with exact coefficients.
//!
//! Every function answers in the fixture format's convention (see [`Toi`]): the
//! normal points from `b` toward `a`, the point lies on `b`'s surface at time
//! `t`, and shapes already in contact at `t = 0` give `t = 0`.

mod feature_roots;
mod halving;
mod sphere_box;
mod sphere_box_halving;
mod sphere_mesh;
mod sphere_mesh_halving;
mod sphere_plane;
mod sphere_plane_halving;
mod sphere_sphere;
mod sphere_sphere_halving;
mod sphere_triangle;
mod sphere_triangle_halving;
mod sweep;
mod time_of_impact;

pub use halving::toi_halving;
pub use sphere_box::toi_sphere_box;
pub use sphere_box_halving::toi_sphere_box_halving;
pub use sphere_mesh::{MeshToi, toi_sphere_mesh, toi_sphere_mesh_brute};
pub use sphere_mesh_halving::toi_sphere_mesh_halving;
pub use sphere_plane::toi_sphere_plane;
pub use sphere_plane_halving::toi_sphere_plane_halving;
pub use sphere_sphere::toi_sphere_sphere;
pub use sphere_sphere_halving::toi_sphere_sphere_halving;
pub use sphere_triangle::{ADVANCE_TOL_EPS, Advancement, MAX_ADVANCE_STEPS, toi_sphere_triangle};
pub use sphere_triangle_halving::toi_sphere_triangle_halving;
pub use time_of_impact::{Halving, Toi, ToiStatus};

#[cfg(test)]
mod sphere_box_tests;
#[cfg(test)]
mod tests;
