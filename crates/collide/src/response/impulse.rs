//! The result of a collision response.

use crate::real::{Real, Vec3};

/// Velocities after one frictionless impulse along the contact normal.
///
/// `impulse` is the magnitude `j ≥ 0` of the impulse `j n` applied to `a` (and
/// `−j n` to `b`); it is 0 when the bodies were already separating. When
/// `degenerate` is set the impulse could not be defined (a zero or non-finite
/// normal, a mass that is not positive, two bodies of infinite mass, a
/// non-finite restitution) and the velocities are returned unchanged; for
/// concentric spheres the normal is a documented fallback and the impulse is
/// applied along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Response<T: Real> {
    /// `a`'s velocity after the impulse.
    pub velocity_a: Vec3<T>,
    /// `b`'s velocity after the impulse (zero for a static plane).
    pub velocity_b: Vec3<T>,
    /// Magnitude of the impulse along the normal, ≥ 0.
    pub impulse: T,
    /// The answer is a documented fallback.
    pub degenerate: bool,
}

impl<T: Real> Response<T> {
    /// Velocities unchanged, no impulse.
    pub(crate) fn unchanged(va: &Vec3<T>, vb: &Vec3<T>, degenerate: bool) -> Self {
        Self { velocity_a: *va, velocity_b: *vb, impulse: T::zero(), degenerate }
    }
}
