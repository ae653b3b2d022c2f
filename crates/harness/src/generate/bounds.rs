//! `bounds` scenes: clouds of 1 to 64 points.
//!
//! The uniform family scatters points in a small box. The biased ones sit where
//! bounding-volume methods break: points exactly on a sphere (every one of them
//! a support point, the hard case for Welzl's recursion) and nearly on one,
//! repeated points, exactly and nearly collinear or coplanar clouds (slivers
//! down to a thickness of 1e-15), one and two points, far from the origin, and
//! tiny and huge.

use super::build::*;
use super::family::Family;
use crashtest_core::vec3::{add, scale};
use oracle::geom::P3;
use proptest::prelude::*;
use std::sync::OnceLock;

/// At most this many points per cloud (the format's bound for generated cases).
const MAX_POINTS: usize = 64;

fn uniform_cloud() -> SBoxedStrategy<Scene> {
    prop::collection::vec(vec3(BOX), 1..=MAX_POINTS).prop_map(|p| (points(p), None)).sboxed()
}

/// Radii of spheres with many integer points: `x² + y² + z² = R²`.
const LATTICE_RADII: [i32; 5] = [3, 5, 7, 9, 11];

/// The integer points on each sphere of [`LATTICE_RADII`], computed once.
fn lattice() -> &'static Vec<Vec<P3>> {
    static LATTICE: OnceLock<Vec<Vec<P3>>> = OnceLock::new();
    LATTICE.get_or_init(|| {
        LATTICE_RADII
            .iter()
            .map(|&r| {
                let mut pts = Vec::new();
                for x in -r..=r {
                    for y in -r..=r {
                        for z in -r..=r {
                            if x * x + y * y + z * z == r * r {
                                pts.push([x as f64, y as f64, z as f64]);
                            }
                        }
                    }
                }
                pts
            })
            .collect()
    })
}

/// Points exactly on a sphere: integer points of a lattice sphere (radius 3 to
/// 11), picked at random (repeats allowed), scaled by `2^j` (`j ∈ [-4, 2]`) and
/// shifted by a grid point — all exact, so every point is at exactly the same
/// distance from the centre.
fn exactly_cospherical() -> SBoxedStrategy<Scene> {
    (
        0..LATTICE_RADII.len(),
        prop::collection::vec(any::<prop::sample::Index>(), 1..=MAX_POINTS),
        -4..=2i32,
        grid_point(),
    )
        .prop_map(|(r, picks, j, shift)| {
            let sphere_pts = &lattice()[r];
            let s = pow2(j);
            let pts = picks.iter().map(|i| add(scale(*i.get(sphere_pts), s), shift)).collect();
            (points(pts), None)
        })
        .sboxed()
}

/// Points nearly on a sphere: random directions at radius `R (1 + g)` with `|g|`
/// from `2^-55` to `2^-10` (rounded, so on the sphere to within rounding, or a
/// little off it).
fn nearly_cospherical() -> SBoxedStrategy<Scene> {
    (vec3(BOX), 0.1..BOX, prop::collection::vec((unit(), signed_magnitude(-55, -10)), 2..=MAX_POINTS))
        .prop_map(|(c, r, dirs)| (points(dirs.iter().map(|&(u, g)| add(c, scale(u, r * (1.0 + g)))).collect()), None))
        .sboxed()
}

/// A few distinct points (1 to 4), each repeated, up to 64 in all.
fn repeated_points() -> SBoxedStrategy<Scene> {
    (prop::collection::vec(vec3(BOX), 1..=4), prop::collection::vec(any::<prop::sample::Index>(), 1..=MAX_POINTS))
        .prop_map(|(distinct, picks)| (points(picks.iter().map(|i| *i.get(&distinct)).collect()), None))
        .sboxed()
}

/// Collinear or coplanar clouds: exactly on a line `p + t v` (`v` an integer
/// vector, `t` dyadic) or in a plane `z = z0` moved by a signed permutation; one
/// time in two thickened by a random offset of size `2^-50 … 2^-3` per point
/// (a sliver of a cloud).
fn collinear_or_coplanar() -> SBoxedStrategy<Scene> {
    (
        (grid_point(), pythagorean(), any::<bool>()),
        prop::collection::vec((prop::array::uniform3(dyadic(64, 4)), vec3(1.0)), 2..=MAX_POINTS),
        (signed_perm(), magnitude(-50, -3), any::<bool>()),
    )
        .prop_map(|((p, (v, _), line), raw, (sp, thick, thicken))| {
            let pts = raw
                .iter()
                .map(|&(q, jitter)| {
                    let exact = if line { add(p, scale(v, q[0] / 4.0)) } else { add(p, sp.apply([q[0], q[1], 0.0])) };
                    if thicken { add(exact, scale(jitter, thick)) } else { exact }
                })
                .collect();
            (points(pts), None)
        })
        .sboxed()
}

/// One or two points.
fn one_or_two() -> SBoxedStrategy<Scene> {
    prop::collection::vec(vec3(BOX), 1..=2).prop_map(|p| (points(p), None)).sboxed()
}

/// What the far and resized families move.
fn moved_base() -> SBoxedStrategy<Scene> {
    prop_oneof![uniform_cloud(), exactly_cospherical(), collinear_or_coplanar()].sboxed()
}

/// The bounds families: uniform first, then biased.
pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform("uniform point cloud", uniform_cloud),
        Family::biased("points exactly on a sphere", exactly_cospherical),
        Family::biased("points nearly on a sphere", nearly_cospherical),
        Family::biased("repeated points", repeated_points),
        Family::biased("collinear or coplanar points, exactly or nearly", collinear_or_coplanar),
        Family::biased("one or two points", one_or_two),
        Family::biased("bounds far from the origin", || far_from_origin(moved_base())),
        Family::biased("bounds at tiny and huge sizes", || resized(moved_base())),
    ]
}
