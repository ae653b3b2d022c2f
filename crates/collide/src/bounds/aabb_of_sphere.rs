//! The AABB of a sphere.

use crate::real::{Real, Vec3};
use crate::shapes::{Aabb, Sphere};

/// The axis-aligned box of the ball: `center ∓ r` on each axis (the smallest box
/// containing it, up to the rounding of each face),
///
/// ```text
/// min = center − (r, r, r),   max = center + (r, r, r),   r = |radius|
/// ```
///
/// Derivation: the ball's extreme points along axis `i` are `center ± r e_i` (the
/// support function of a ball in direction `e_i` is `center_i + r`).
///
/// Numerics: each face is one rounded addition, rounded to nearest, so it may sit
/// up to half an ulp inside the true face; a face beyond the type's range becomes
/// ±∞, which still bounds the ball.
///
/// Degenerate input: a zero radius gives the point box `[center, center]`; a
/// negative radius (malformed, which the fixture reader refuses) is read as its
/// absolute value so that `min ≤ max` always holds.
pub fn aabb_of_sphere<T: Real>(sphere: &Sphere<T>) -> Aabb<T> {
    let r = sphere.radius.abs();
    let ext = Vec3::new(r, r, r);
    Aabb::new(sphere.center - ext, sphere.center + ext)
}
