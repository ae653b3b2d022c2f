//! The result of a contact query.

use crate::real::{Real, Vec3};

/// Where two shapes touch or overlap, in crashtest's (the lecture's) convention for
/// a query `contact(a, b)`:
///
/// - `point` lies on `b`'s surface;
/// - `normal` is unit length and points from `b` toward `a`;
/// - `depth ≥ 0` is the penetration (0 when touching; touching counts as contact).
///
/// When `degenerate` is set the pair has no well-defined normal (concentric
/// spheres, a sphere centre exactly on a triangle, a scene that overflows the
/// type); `normal` then holds the documented fallback of the function that
/// answered, still unit length, and `point` and `depth` stay meaningful.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact<T: Real> {
    /// Contact point on `b`'s surface.
    pub point: Vec3<T>,
    /// Unit normal from `b` toward `a`.
    pub normal: Vec3<T>,
    /// Penetration depth, ≥ 0.
    pub depth: T,
    /// The normal is a documented fallback, not a defined answer.
    pub degenerate: bool,
}

impl<T: Real> Contact<T> {
    /// The same contact seen from the other shape, as `contact(b, a)` reports it:
    /// the normal flips, and the point moves from `b`'s surface to the deepest
    /// point of `a`, `depth` against the old normal (`a` sinks into `b` along
    /// `−normal`).
    pub fn swapped(&self) -> Self {
        Self {
            point: self.point - self.normal * self.depth,
            normal: -self.normal,
            depth: self.depth,
            degenerate: self.degenerate,
        }
    }
}
