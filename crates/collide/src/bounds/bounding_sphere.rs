//! The result of a bounding-sphere construction.

use crate::real::{Real, Vec3};
use crate::shapes::Sphere;

/// A sphere enclosing a point set, as the `bounding_sphere_*` constructions
/// return it.
///
/// Guarantee shared by every construction: `radius` is the largest distance
/// from `center` to an input point, computed (see each function for how); so
/// every point's computed distance is `≤ radius`, and its exact distance exceeds
/// `radius` by at most the rounding of one difference and one norm (about
/// `3 ε · radius`, ε the type's machine epsilon). `radius ≥ 0`, and `center`
/// lies in the points' AABB.
///
/// `degenerate` is set when the scene is beyond the type's range: the radius
/// overflowed to `+∞` (points spread over more than the largest finite value).
/// The sphere then still encloses every point, trivially, and `center` is still
/// finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingSphere<T: Real> {
    /// Centre, inside the points' AABB.
    pub center: Vec3<T>,
    /// Radius: the largest computed distance from `center` to a point, ≥ 0.
    pub radius: T,
    /// The radius overflowed the type; see the type's documentation.
    pub degenerate: bool,
}

impl<T: Real> BoundingSphere<T> {
    /// The bounding sphere as a [`Sphere`] shape.
    pub fn to_sphere(&self) -> Sphere<T> {
        Sphere::new(self.center, self.radius)
    }
}
