//! Collision response: one frictionless impulse with restitution along the
//! contact normal, for two spheres and for a sphere against a static plane.
//!
//! Conventions are the fixture format's (`response`): the normal points from `b`
//! toward `a`; bodies already separating along it keep their velocities. The
//! impulse acts along the normal only (no friction, no spin: spheres hit along
//! the line of centres get no torque from a frictionless impulse).

mod impulse;
mod sphere_plane;
mod sphere_sphere;
mod sphere_sphere_contact;

pub use impulse::Response;
pub use sphere_plane::respond_sphere_plane;
pub use sphere_sphere::respond_sphere_sphere;
pub use sphere_sphere_contact::respond_sphere_sphere_contact;

#[cfg(test)]
mod tests;
