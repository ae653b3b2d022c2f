//! `concentric` and `grazing`: two spheres whose centres come together, or
//! whose surfaces just meet.
//!
//! - `concentric`: centre distance `d` from 1 down to 1e-16, and exactly 0 (the
//!   contact normal is undefined: a documented fallback and the `degenerate`
//!   flag). Radii 0.5–2, so the spheres always overlap. Canonically the second
//!   centre is the origin and the first is `d·û`, exact however small `d` is.
//! - `grazing`: the gap `|d − (r1 + r2)|` from 1 down to 1e-16, and exactly
//!   touching; `apart` puts the centres `r1 + r2 + g` apart (no contact),
//!   `overlapping` `r1 + r2 − g` (depth `g`). The radii are multiples of 1/32
//!   in `[0.75, 2]`, so `r1 + r2` is exact and exactly touching is exact; the
//!   centres lie on an axis, so the distance is `fl(r1 + r2 ± g)` itself.
//!   Gaps below half an ulp of `r1 + r2` (1.1e-16 to 2.2e-16 of it) round to
//!   exactly touching: the smallest nominal gaps are a rounding, and the
//!   referee judges what they rounded to.
//!
//! An exact pose permutes the axes (no translation, which would round the
//! small distances away); a rotated pose turns and moves the pair, rounding
//! every coordinate at the scene's scale.

use super::grid::{Pose, Rng};
use crate::generate::build::{Scene, sphere};
use crashtest_core::vec3::scale;

/// Centres `d` apart.
pub(super) fn concentric(rng: &mut Rng, d: f64, pose: &Pose) -> Scene {
    let (r1, r2) = (rng.uniform(0.5, 2.0), rng.uniform(0.5, 2.0));
    let u = rng.unit();
    pose.scene(&(sphere(scale(u, d), r1), Some(sphere([0.0; 3], r2))))
}

fn radii(rng: &mut Rng) -> (f64, f64) {
    (rng.int(24, 64) as f64 / 32.0, rng.int(24, 64) as f64 / 32.0)
}

/// Surfaces `g` apart.
pub(super) fn apart(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let (r1, r2) = radii(rng);
    pose.scene(&(sphere([r1 + r2 + g, 0.0, 0.0], r1), Some(sphere([0.0; 3], r2))))
}

/// Surfaces overlapping by `g`.
pub(super) fn overlapping(rng: &mut Rng, g: f64, pose: &Pose) -> Scene {
    let (r1, r2) = radii(rng);
    pose.scene(&(sphere([r1 + r2 - g, 0.0, 0.0], r1), Some(sphere([0.0; 3], r2))))
}
