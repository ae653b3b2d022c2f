//! `response` scenes: two spheres with velocities and masses, or a sphere and a
//! static plane, and a coefficient of restitution.
//!
//! The uniform families draw everything at random (positions in a small box,
//! velocities of a few units, masses from 0.1 to 10, `e ∈ [0, 1]`). The biased
//! ones sit where response formulas break or where their answers are easy to
//! get subtly wrong: head-on and glancing impacts built exactly (dyadic
//! velocities and masses, Pythagorean normals, `e` a multiple of 1/4, so the
//! referee's answer is a short rational); `e` exactly 0 and 1; mass ratios up
//! to `2^±40`; relative velocities at and near the switch between approaching
//! and separating (`v_rel · n` exactly 0, or from `2^-60` of the speed up,
//! either side); near-
//! concentric spheres (the normal defined by a tiny difference of centres, or
//! not at all); grazing incidence on a plane; tiny and huge speeds and masses,
//! far from the origin.

use super::build::*;
use super::family::{Family, Params, Posed};
use crate::case::{Shape, SphereSpec};
use crashtest_core::vec3::{add, dot, norm_sqrt_dot, scale, sub};
use oracle::geom::P3;
use proptest::prelude::*;

/// Radii of uniform scenes.
const RADIUS: std::ops::Range<f64> = 0.05..2.0;

/// Velocity components of uniform scenes.
const SPEED: f64 = 8.0;

/// Masses of uniform scenes.
const MASS: std::ops::Range<f64> = 0.1..10.0;

/// A ball with velocity and mass.
fn body(center: P3, radius: f64, velocity: P3, mass: f64) -> Shape {
    Shape::Sphere(SphereSpec { center, radius, velocity: Some(velocity), mass: Some(mass) })
}

/// A response scene with restitution `e`.
fn posed(a: Shape, b: Shape, e: f64) -> Posed {
    ((a, Some(b)), Params { t_max: None, restitution: Some(e) })
}

/// A restitution: uniform in `[0, 1]`, or exactly 0 or 1 one time in four each.
fn restitution() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![2 => 0.0..=1.0f64, 1 => Just(0.0), 1 => Just(1.0)]
}

/// A restitution that is a multiple of 1/4 (exact, and exact in sums).
fn quarter_restitution() -> impl Strategy<Value = f64> + Clone {
    (0..=4i64).prop_map(|k| k as f64 / 4.0)
}

/// A mass that is a power of two from 1/16 to 16 (exact in every product and
/// quotient of the formula).
fn dyadic_mass() -> impl Strategy<Value = f64> + Clone {
    (-4..=4i32).prop_map(pow2)
}

fn uniform_spheres() -> SBoxedStrategy<Posed> {
    ((vec3(BOX), RADIUS, vec3(SPEED), MASS), (vec3(BOX), RADIUS, vec3(SPEED), MASS), restitution())
        .prop_map(|((ca, ra, va, ma), (cb, rb, vb, mb), e)| posed(body(ca, ra, va, ma), body(cb, rb, vb, mb), e))
        .sboxed()
}

fn uniform_sphere_plane() -> SBoxedStrategy<Posed> {
    (vec3(BOX), RADIUS, vec3(SPEED), MASS, random_plane(), restitution())
        .prop_map(|(c, r, v, m, (n, d), e)| posed(body(c, r, v, m), plane(n, d), e))
        .sboxed()
}

/// Two spheres touching along a coordinate axis (`cb` on the 1/64 grid,
/// `ca = cb ± (ra + rb) e_i`), velocities multiples of 1/8, masses powers of
/// two, `e` a multiple of 1/4: every input is a short dyadic, the normal an
/// axis, and the answer a short rational (a dyadic whenever the inverse masses
/// sum to a power of two, as for equal masses).
fn head_on_exact() -> SBoxedStrategy<Posed> {
    (
        (grid_point(), (1..=256i64, 1..=256i64), (0..3usize, any::<bool>())),
        (prop::array::uniform3(dyadic(64, 3)), prop::array::uniform3(dyadic(64, 3))),
        (dyadic_mass(), dyadic_mass(), quarter_restitution()),
    )
        .prop_map(|((cb, (ra, rb), (axis, neg)), (va, vb), (ma, mb, e))| {
            let (ra, rb) = (ra as f64 / 64.0, rb as f64 / 64.0);
            let mut ca = cb;
            ca[axis] += if neg { -(ra + rb) } else { ra + rb };
            posed(body(ca, ra, va, ma), body(cb, rb, vb, mb), e)
        })
        .sboxed()
}

/// Two spheres touching along a Pythagorean direction (`ca = cb + k w`, `w` of
/// integer length `d`, radii summing to `k d`), dyadic velocities and masses,
/// `e` a multiple of 1/4: the normal is rational, the answer a short rational.
fn glancing_exact() -> SBoxedStrategy<Posed> {
    (
        (grid_point(), pythagorean(), 1..=256i64, 1..=15i64),
        (prop::array::uniform3(dyadic(64, 3)), prop::array::uniform3(dyadic(64, 3))),
        (dyadic_mass(), dyadic_mass(), quarter_restitution()),
    )
        .prop_map(|((cb, (w, d), k, j), (va, vb), (ma, mb, e))| {
            let k = k as f64 / 64.0;
            let ra = k * d * j as f64 / 16.0;
            posed(body(add(cb, scale(w, k)), ra, va, ma), body(cb, k * d - ra, vb, mb), e)
        })
        .sboxed()
}

/// Uniform scenes with masses `m` and `m · 2^p`, `p` from −40 to 40: a light
/// ball against a heavy one (the heavy one barely moves, the light one
/// reflects), either way round.
fn extreme_mass_ratio() -> SBoxedStrategy<Posed> {
    (uniform_spheres(), -40..=40i32, 1.0..2.0f64)
        .prop_map(|(((a, b), p), k, m)| {
            let set = |s: Option<Shape>, mass: f64| match s {
                Some(Shape::Sphere(mut s)) => {
                    s.mass = Some(mass);
                    Shape::Sphere(s)
                }
                Some(other) => other,
                None => body([0.0; 3], 1.0, [0.0; 3], mass),
            };
            ((set(Some(a), m), Some(set(b, m * pow2(k)))), p)
        })
        .sboxed()
}

/// The relative velocity at the switch between approaching and separating:
/// `v_rel = s·t + δ·n` with `t` perpendicular to the line of centres `n` and
/// `δ` exactly 0 (sliding: no impulse) one time in four, else from `2^-60` to
/// `2^-3` of the speed either way. The exact zero uses an axis-aligned normal
/// and a tangential velocity on the other axes.
fn near_separating() -> SBoxedStrategy<Posed> {
    (
        (vec3(BOX), unit(), unit(), RADIUS, RADIUS),
        (0.5..8.0f64, signed_magnitude(-60, -3), vec3(SPEED), (MASS, MASS), restitution()),
        ((0..3usize, prop::array::uniform3(dyadic(64, 3))), 0..4u8),
    )
        .prop_map(|((cb, u, w, ra, rb), (speed, delta, vb, (ma, mb), e), ((axis, slide), pick))| {
            if pick == 0 {
                let mut ca = cb;
                ca[axis] += ra + rb;
                let mut slide = slide;
                slide[axis] = 0.0;
                return posed(body(ca, ra, add(vb, slide), ma), body(cb, rb, vb, mb), e);
            }
            let t = normalize_or(sub(w, scale(u, dot(u, w))), perpendicular(u));
            let v_rel = add(scale(t, speed), scale(u, delta * speed));
            let ca = add(cb, scale(u, ra + rb));
            posed(body(ca, ra, add(vb, v_rel), ma), body(cb, rb, vb, mb), e)
        })
        .sboxed()
}

/// Centres `rb · m` apart (`m` from `2^-60` to 1), or exactly concentric one
/// time in eight (the degenerate case: no line of centres).
fn near_concentric() -> SBoxedStrategy<Posed> {
    (
        (vec3(BOX), unit(), RADIUS, RADIUS, magnitude(-60, 0), 0..8u8),
        (vec3(SPEED), vec3(SPEED), MASS, MASS, restitution()),
    )
        .prop_map(|((cb, u, ra, rb, m, pick), (va, vb, ma, mb, e))| {
            let ca = if pick == 0 { cb } else { add(cb, scale(u, rb * m)) };
            posed(body(ca, ra, va, ma), body(cb, rb, vb, mb), e)
        })
        .sboxed()
}

/// A ball meeting a plane at grazing incidence: the normal component of its
/// velocity `θ` times the tangential one, `|θ|` from `2^-60` to `2^-3`, toward
/// the plane or away from it (no impulse then).
fn grazing_plane() -> SBoxedStrategy<Posed> {
    (random_plane(), vec3(BOX), unit(), RADIUS, (signed_magnitude(-60, -3), 0.5..8.0f64, MASS, restitution()))
        .prop_map(|((n, d), c, dir, r, (theta, speed, m, e))| {
            let u = scale(n, 1.0 / norm_sqrt_dot(n));
            let along = normalize_or(sub(dir, scale(u, dot(u, dir))), perpendicular(u));
            let v = scale(add(along, scale(u, theta)), speed);
            posed(body(c, r, v, m), plane(n, d), e)
        })
        .sboxed()
}

/// A uniform scene with its velocities scaled by `2^k` (`k` from −20 to 20),
/// its masses by `2^j` (`j` from −30 to 30) and its positions moved far from
/// the origin: the answer scales with the speeds, the masses cancel, the
/// normal is a difference of large centres.
fn scaled() -> SBoxedStrategy<Posed> {
    (prop_oneof![uniform_spheres(), uniform_sphere_plane()], -20..=20i32, -30..=30i32, far_shift(), any::<bool>())
        .prop_map(|(((a, b), p), k, j, shift, move_far)| {
            let f = |s: Shape| match s {
                Shape::Sphere(mut s) => {
                    s.velocity = s.velocity.map(|v| scale(v, pow2(k)));
                    s.mass = s.mass.map(|m| m * pow2(j));
                    if move_far {
                        s.center = add(s.center, shift);
                    }
                    Shape::Sphere(s)
                }
                Shape::Plane(mut pl) if move_far => {
                    pl.offset += dot(pl.normal, shift);
                    Shape::Plane(pl)
                }
                other => other,
            };
            ((f(a), b.map(f)), p)
        })
        .sboxed()
}

/// The response families: uniform first, then biased.
pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform_posed("uniform sphere–sphere", uniform_spheres),
        Family::uniform_posed("uniform sphere–plane", uniform_sphere_plane),
        Family::biased_posed("head-on along an axis, exact", head_on_exact),
        Family::biased_posed("glancing at a Pythagorean normal, exact", glancing_exact),
        Family::biased_posed("extreme mass ratios", extreme_mass_ratio),
        Family::biased_posed("at and near the switch to separating", near_separating),
        Family::biased_posed("near-concentric spheres", near_concentric),
        Family::biased_posed("grazing incidence on a plane", grazing_plane),
        Family::biased_posed("tiny and huge speeds and masses, far from the origin", scaled),
    ]
}
