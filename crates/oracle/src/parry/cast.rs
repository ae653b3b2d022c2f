//! parry's linear shape casts (`query::cast_shapes`) as a time-of-impact
//! reference: a sphere moving linearly against a sphere, a half-space or a
//! triangle moving linearly, over `[0, t_max]`, in both precisions ([`Parry64`]
//! and [`Parry32`]), answering in crashtest's `toi` convention (docs/FORMAT.md).
//!
//! # Options, set in one place
//!
//! Every cast is run with the [`ShapeCastOptions`](parry3d_f64::query::ShapeCastOptions)
//! built by one function (`options` below), every field set explicitly:
//!
//! | field | value | why |
//! | --- | --- | --- |
//! | `max_time_of_impact` | `t_max` | parry drops a hit with `time_of_impact > max`, so a touch exactly at `t_max` is kept, as the format asks |
//! | `target_distance` | `0` | an impact is a touch (distance 0), not an approach to within a margin |
//! | `stop_at_penetration` | `true` | shapes already in contact at `t = 0` answer `t = 0` whatever their velocities, as the format asks |
//! | `compute_impact_geometry_on_penetration` | `true` | so that the witnesses and normals of a `t = 0` answer mean something |
//!
//! # Conventions, and their translation
//!
//! Shape 1 is `a` (the sphere), shape 2 is `b`. parry answers in each shape's
//! **local frame**: `witness2` and `normal2` are expressed in the frame `b` was
//! given in, which moves with `b`. The translation (in `translate`, the only
//! place it happens) is:
//!
//! | | parry 0.31.1 | crashtest | translation |
//! | --- | --- | --- | --- |
//! | time | `time_of_impact` | `t` | as is |
//! | point | `witness2`: the point of shape 2 at the impact, in shape 2's local frame | on `b`'s surface at time `t`, world frame | `pose_b(t) · witness2`, with `pose_b(t)` = `b`'s initial pose translated by `t · v_b` |
//! | normal | `normal2`: the outward normal of shape 2 in its local frame, i.e. from `b` toward `a` | unit, from `b` toward `a`, world frame | `rotation_b · normal2` |
//! | status | `ShapeCastStatus` | — | kept as [`CastStatus`] beside the answer; `Failed` flags the answer `degenerate` |
//!
//! The shapes are placed as the contact adapter places them: a ball at the
//! translation of its centre, the plane `n · x = d` as parry's `HalfSpace` with unit
//! normal `n̂ = n/‖n‖` at the translation `(d/‖n‖) n̂` (solid `n · x ≤ d`), a
//! triangle from its world vertices at the identity pose. No rotation is ever
//! used, so the local frames differ from the world by translations only; the
//! conversion above is written for a general pose all the same.
//!
//! # Degenerate input and NaN
//!
//! No cast panics and none returns a NaN. A radius that is not positive, a plane
//! normal that cannot be normalized, or an input that is not finite in the
//! engine's scalar: no impact, `degenerate: true`. A triangle parry cannot give a
//! normal (zero area in the engine's scalar) is cast all the same and the answer
//! flagged. A non-finite number in parry's answer, or parry's `Failed` status,
//! flags the answer; a non-finite answer becomes "no impact", flagged. A
//! `t_max` beyond the engine's range is "no limit" (`Real::MAX`, parry's
//! default); a negative one is read as 0.
//!
//! # Known divergences
//!
//! [`cast_known_divergences`] lists what no translation removes, for both
//! engines; each entry is pinned by a test below that shows it still happens.

use crate::geom::{OrientedBox, P3, Plane, Sphere, ToiAnswer, Triangle};
use crate::parry::api::{KnownDivergence, Parry32, Parry64};

/// How parry's cast ended: `ShapeCastStatus`, by name. Which fields of the
/// answer mean something follows parry's documentation of each variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CastStatus {
    /// The algorithm converged: `t` is the impact time to parry's accuracy.
    Converged,
    /// The algorithm ran out of iterations; parry calls the answer "a
    /// conservative approximation", often fine to read as a success. Reported
    /// as given, not flagged.
    OutOfIterations,
    /// Something went wrong numerically; the answer is parry's conservative
    /// approximation and is flagged `degenerate`.
    Failed,
    /// The shapes touch or overlap at `t = 0` (closer than the target distance,
    /// 0): `t = 0`, and with `compute_impact_geometry_on_penetration` the witnesses
    /// and normals are computed.
    PenetratingOrWithinTargetDist,
}

impl CastStatus {
    /// The status's name as parry spells it (`"Converged"`, `"OutOfIterations"`,
    /// `"Failed"`, `"PenetratingOrWithinTargetDist"`).
    pub fn as_str(self) -> &'static str {
        match self {
            CastStatus::Converged => "Converged",
            CastStatus::OutOfIterations => "OutOfIterations",
            CastStatus::Failed => "Failed",
            CastStatus::PenetratingOrWithinTargetDist => "PenetratingOrWithinTargetDist",
        }
    }
}

/// A parry cast in crashtest's vocabulary: the `toi` answer and the status parry
/// gave for it.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct CastAnswer {
    /// The answer in the fixture format's convention (see the module docs).
    pub answer: ToiAnswer,
    /// parry's status for the hit; `None` when parry found no impact or the input
    /// was refused.
    pub status: Option<CastStatus>,
}

impl CastAnswer {
    /// The status's name ([`CastStatus::as_str`]), or `"None"` when parry found no
    /// impact (or the input was refused).
    pub fn status_str(&self) -> &'static str {
        self.status.map_or("None", CastStatus::as_str)
    }
}

/// parry's linear shape casts for crashtest: implemented by [`Parry64`] and
/// [`Parry32`] from one body (a macro instantiated once per precision, in this
/// file). Every method answers `toi(a, b)` of the fixture format: the first time
/// in `[0, t_max]` at which sphere `a` (velocity `va`) touches `b` (velocity
/// `vb`), the point on `b` and the normal from `b` toward `a` at that time; 0 when
/// they touch or overlap at `t = 0`.
pub trait ParryCast {
    /// Sphere against sphere.
    ///
    /// **Formula** (parry's `cast_shapes_ball_ball`,
    /// `query/shape_cast/shape_cast_ball_ball.rs`, with the ray–ball root of
    /// `query/ray/ray_ball.rs`): with `Δ(t) = (M_b − M_a) + t (v_b − v_a)` and
    /// `R = r_a + r_b`, the touching time solves `‖Δ(t)‖ = R`. parry casts a ray
    /// from the origin along `v = v_b − v_a` at a ball of radius `R` centred on
    /// `M_a − M_b`: with `a = ‖v‖²`, `b = Δ(0)·v` and `c = ‖Δ(0)‖² − R²`, it takes
    /// the textbook root `t = (−b − √(b² − a c))/a`; a start with `c ≤ 0`
    /// (touching or overlapping) gives `t = 0`, a zero `a` with `c > 0` no
    /// impact. Normal (translated: parry's `normal2 = −normal1`)
    /// `−Δ(t)/R`, point `M_b(t) + r_b n`.
    ///
    /// **Deviations:** the textbook root cancels when `a c ≪ b²` (a near-touching
    /// start on a fast approach), so its relative error grows as the gap shrinks
    /// (reported as measured). For overlapping balls at `t = 0` parry divides by
    /// `R` instead of `‖Δ‖`: the normal has length `‖Δ‖/R` and the point lies
    /// inside `b` (a known divergence, [`cast_known_divergences`]).
    ///
    /// **Degenerate input:** concentric overlapping balls give parry's zero
    /// normal (`Δ = 0`), reported as it is and flagged `degenerate`. A radius that
    /// is not positive or a non-finite input: no impact, flagged.
    fn cast_sphere_sphere(&self, a: Sphere, va: P3, b: Sphere, vb: P3, t_max: f64) -> CastAnswer;

    /// Sphere against the solid half-space `n · x ≤ d`.
    ///
    /// **Formula** (parry's `cast_shapes_support_map_halfspace`, which swaps the
    /// shapes and calls `cast_shapes_halfspace_support_map`,
    /// `query/shape_cast/shape_cast_halfspace_support_map.rs`): in the half-space's
    /// frame, the ball's support point against the normal, `s = M − r n̂`, is cast
    /// as a ray along the relative velocity `v_a − v_b` against the solid
    /// half-space (`query/ray/ray_halfspace.rs`, `solid = true`):
    /// `t = −(n̂ · s − d/‖n‖)/(n̂ · (v_a − v_b))`, or `t = 0` when `s` is already
    /// inside. Witness on the plane: the ray's point at `t` projected onto the
    /// boundary. Translated: normal `n̂`, point that projection moved with the
    /// plane — the lecture's `p = M − (r − x) n` at time `t`.
    ///
    /// **Degenerate input:** a normal that cannot be normalized, a radius that is
    /// not positive, a non-finite input: no impact, flagged.
    fn cast_sphere_plane(&self, a: Sphere, va: P3, b: Plane, vb: P3, t_max: f64) -> CastAnswer;

    /// Sphere against a triangle (two-sided, as a surface).
    ///
    /// **Formula** (parry's `cast_shapes_support_map_support_map`,
    /// `query/shape_cast/shape_cast_support_map_support_map.rs`): GJK's
    /// directional distance (`query/gjk/gjk.rs`, `directional_distance`, a
    /// conservative-advancement ray cast on the Minkowski difference) gives the
    /// time and the witnesses, to GJK's tolerance. For a time below `1e-4`
    /// (absolute, in the caller's time units) parry replaces the normal and the
    /// witnesses by those of the static contact at the *start* (`t = 0`), which
    /// it finds more robust.
    ///
    /// **Accuracy:** GJK stops at its own convergence threshold: on the smoke
    /// cases the witness points are off by up to 3e-6 in `f64` and 3e-3 in `f32`
    /// (times by 5e-12 and 1.5e-5), far above rounding — reported as measured.
    ///
    /// **Deviation:** because of that replacement, an impact at `0 < t < 1e-4`
    /// reports the closest points of time 0, carried along with the shapes: off
    /// by the tangential relative motion `t · v_t` (a known divergence).
    ///
    /// **Degenerate input:** a triangle without a normal in the engine's scalar
    /// (zero area) is cast and flagged; a radius that is not positive or a
    /// non-finite input: no impact, flagged.
    fn cast_sphere_triangle(&self, a: Sphere, va: P3, b: Triangle, vb: P3, t_max: f64) -> CastAnswer;

    /// Sphere against a box (a `Cuboid` at the box's pose, its rotation fixed,
    /// translated with `vb`): `cast_shapes` of a ball and a cuboid, parry's
    /// support-map cast (conservative advancement on GJK distances). The
    /// point is `witness2` placed by the box's pose at `t`, the normal
    /// `normal2` rotated by the box's rotation.
    ///
    /// **Degenerate input:** a negative half-extent, a zero quaternion, a
    /// radius that is not positive or a non-finite input: no impact, flagged.
    fn cast_sphere_box(&self, a: Sphere, va: P3, b: OrientedBox, vb: P3, t_max: f64) -> CastAnswer;
}

/// Every known divergence of the casts of [`Parry64`] and [`Parry32`] (each entry
/// once per engine), in the shape of [`crate::parry::known_divergences`].
pub fn cast_known_divergences() -> &'static [KnownDivergence] {
    &KNOWN_CAST
}

/// A divergence of the casts, shared by both precisions.
#[derive(Clone, Copy, Debug)]
struct CastDivergence {
    what: &'static str,
    reason: &'static str,
}

const OVERLAPPING_BALLS_NORMAL: CastDivergence = CastDivergence {
    what: "sphere–sphere cast, overlapping at t = 0: normal of length ‖M_a − M_b‖/(r_a + r_b), \
           not unit, and a point inside b (M_b + r_b · that normal)",
    reason: "cast_shapes_ball_ball divides the centre difference by the radius sum R to get \
             normal1 (exact only when touching) and ignores compute_impact_geometry_on_penetration; \
             the shortfall is parry's, reported raw.",
};

const SMALL_TOI_START_GEOMETRY: CastDivergence = CastDivergence {
    what: "sphere–triangle cast hitting at 0 < t < 1e-4: point and normal of the closest points at \
           t = 0, carried along with the shapes, not those at t",
    reason: "cast_shapes_support_map_support_map replaces GJK's witnesses by the static contact at \
             the start (pos12) whenever time_of_impact < 1.0e-4, an absolute threshold in time \
             units; the point is then off by the tangential relative motion t · v_t.",
};

/// The cast divergences, in the order [`cast_known_divergences`] lists them per engine.
const CAST_DIVERGENCES: [CastDivergence; 2] = [OVERLAPPING_BALLS_NORMAL, SMALL_TOI_START_GEOMETRY];

static KNOWN_CAST: [KnownDivergence; 2 * CAST_DIVERGENCES.len()] = stamp();

/// [`CAST_DIVERGENCES`] stamped with [`Parry64::NAME`], then [`Parry32::NAME`].
const fn stamp() -> [KnownDivergence; 2 * CAST_DIVERGENCES.len()] {
    const BLANK: KnownDivergence = KnownDivergence { engine: "", query: "", what: "", reason: "" };
    let mut out = [BLANK; 2 * CAST_DIVERGENCES.len()];
    let engines = [Parry64::NAME, Parry32::NAME];
    let mut e = 0;
    while e < engines.len() {
        let mut i = 0;
        while i < CAST_DIVERGENCES.len() {
            out[e * CAST_DIVERGENCES.len() + i] = KnownDivergence {
                engine: engines[e],
                query: "toi",
                what: CAST_DIVERGENCES[i].what,
                reason: CAST_DIVERGENCES[i].reason,
            };
            i += 1;
        }
        e += 1;
    }
    out
}

/// The adapter body, written once and instantiated per precision. The invoking
/// module supplies `backend` (the parry crate), `Real` (its scalar), `narrow` and
/// `widen` (the edge conversions), `SMOKE_TOL` (the smoke tests' tolerance) and
/// names the engine type.
macro_rules! cast_adapter {
    ($engine:path, $edge:path) => {
        use crate::parry::cast::{CastAnswer, CastStatus, ParryCast};
        // The edge conversions and shape placements are the query adapter's, so
        // a sphere or a plane is placed the same way for every parry query.
        use crate::geom::{OrientedBox, P3, Plane, Sphere, Toi, ToiAnswer, Triangle};
        use backend::math::{Pose, Vector};
        use backend::query::{self, ShapeCastHit, ShapeCastOptions, ShapeCastStatus, Unsupported};
        use backend::shape::{Ball, Shape, Triangle as EngineTriangle};
        use $edge::{answer_point, ball, cuboid, half_space, vector};

        /// The options of every cast (the table in the module docs): stop at a
        /// touch (target distance 0), at `t_max` inclusive, answer `t = 0` for
        /// shapes already in contact, with their geometry computed.
        fn options(t_max: Real) -> ShapeCastOptions {
            ShapeCastOptions {
                max_time_of_impact: t_max,
                target_distance: 0.0,
                stop_at_penetration: true,
                compute_impact_geometry_on_penetration: true,
            }
        }

        /// No impact, flagged: the fallback of every refused input.
        const REFUSED: CastAnswer = CastAnswer { answer: ToiAnswer { toi: None, degenerate: true }, status: None };

        /// The status by name.
        fn status(s: ShapeCastStatus) -> CastStatus {
            match s {
                ShapeCastStatus::Converged => CastStatus::Converged,
                ShapeCastStatus::OutOfIterations => CastStatus::OutOfIterations,
                ShapeCastStatus::Failed => CastStatus::Failed,
                ShapeCastStatus::PenetratingOrWithinTargetDist => CastStatus::PenetratingOrWithinTargetDist,
            }
        }

        /// parry's hit in crashtest's convention — the one place where its
        /// conventions meet crashtest's: `t` as is; the point is `witness2` (in
        /// `b`'s local frame) placed by `b`'s pose at time `t` (its initial pose
        /// translated by `t · v_b`); the normal is `normal2` (b's outward normal,
        /// from `b` toward `a`) rotated by `b`'s rotation. `None` when a number
        /// is not finite.
        fn translate(hit: &ShapeCastHit, pose_b: &Pose, vb: Vector) -> Option<Toi> {
            let t = hit.time_of_impact;
            let pose_b_at_t = pose_b.append_translation(vb * t);
            Some(Toi {
                t: t.is_finite().then(|| widen(t))?,
                point: answer_point(pose_b_at_t.transform_point(hit.witness2))?,
                normal: answer_point(pose_b.rotation * hit.normal2)?,
            })
        }

        /// Runs one cast (shape 1 = `a` at `pose_a` moving at `va`, shape 2 = `b`)
        /// and translates its answer. `flag` marks the answer `degenerate` (the
        /// caller's own finding about the input). A zero or unnormalizable normal,
        /// the `Failed` status or a non-finite number also flag it.
        #[allow(clippy::too_many_arguments)]
        fn run(
            pose_a: &Pose,
            va: Vector,
            shape_a: &dyn Shape,
            pose_b: &Pose,
            vb: Vector,
            shape_b: &dyn Shape,
            t_max: Real,
            flag: bool,
        ) -> CastAnswer {
            let result = query::cast_shapes(pose_a, va, shape_a, pose_b, vb, shape_b, options(t_max));
            match result {
                Ok(None) => CastAnswer { answer: ToiAnswer { toi: None, degenerate: flag }, status: None },
                Ok(Some(hit)) => match translate(&hit, pose_b, vb) {
                    Some(toi) => {
                        let s = status(hit.status);
                        let unnormalizable = hit.normal2.try_normalize().is_none();
                        CastAnswer {
                            answer: ToiAnswer {
                                toi: Some(toi),
                                degenerate: flag || unnormalizable || s == CastStatus::Failed,
                            },
                            status: Some(s),
                        }
                    }
                    None => CastAnswer { status: Some(status(hit.status)), ..REFUSED },
                },
                // parry dispatches every pair cast here; kept total all the same.
                Err(Unsupported) => REFUSED,
            }
        }

        /// `t_max` in the engine's scalar. A bound beyond the scalar's range
        /// (a finite `f64` that rounds to infinity in `f32`) means "no limit":
        /// `Real::MAX`, parry's own default. A negative bound is read as 0 (the
        /// interval `[0, 0]`, as collide reads it); NaN is refused.
        fn limit(t_max: f64) -> Option<Real> {
            let t = narrow(t_max);
            if t.is_nan() {
                None
            } else if t == Real::INFINITY {
                Some(Real::MAX)
            } else {
                Some(t.max(0.0))
            }
        }

        /// The moving inputs every cast shares: `a`'s placement and both
        /// velocities and `t_max` in the engine's scalar.
        fn inputs(a: &Sphere, va: P3, vb: P3, t_max: f64) -> Option<((Pose, Ball), Vector, Vector, Real)> {
            Some((ball(a)?, vector(va)?, vector(vb)?, limit(t_max)?))
        }

        impl ParryCast for $engine {
            fn cast_sphere_sphere(&self, a: Sphere, va: P3, b: Sphere, vb: P3, t_max: f64) -> CastAnswer {
                let (Some(((pa, ba), va, vb, t_max)), Some((pb, bb))) = (inputs(&a, va, vb, t_max), ball(&b)) else {
                    return REFUSED;
                };
                run(&pa, va, &ba, &pb, vb, &bb, t_max, false)
            }

            fn cast_sphere_plane(&self, a: Sphere, va: P3, b: Plane, vb: P3, t_max: f64) -> CastAnswer {
                let (Some(((pa, ba), va, vb, t_max)), Some((pb, hb))) = (inputs(&a, va, vb, t_max), half_space(&b))
                else {
                    return REFUSED;
                };
                run(&pa, va, &ba, &pb, vb, &hb, t_max, false)
            }

            fn cast_sphere_triangle(&self, a: Sphere, va: P3, b: Triangle, vb: P3, t_max: f64) -> CastAnswer {
                let [v0, v1, v2] = b.vertices;
                let (Some(((pa, ba), va, vb, t_max)), Some(v0), Some(v1), Some(v2)) =
                    (inputs(&a, va, vb, t_max), vector(v0), vector(v1), vector(v2))
                else {
                    return REFUSED;
                };
                let tri = EngineTriangle::new(v0, v1, v2);
                let flat = tri.normal().is_none();
                run(&pa, va, &ba, &Pose::IDENTITY, vb, &tri, t_max, flat)
            }

            fn cast_sphere_box(&self, a: Sphere, va: P3, b: OrientedBox, vb: P3, t_max: f64) -> CastAnswer {
                let (Some(((pa, ba), va, vb, t_max)), Some((pb, cb))) = (inputs(&a, va, vb, t_max), cuboid(&b)) else {
                    return REFUSED;
                };
                run(&pa, va, &ba, &pb, vb, &cb, t_max, false)
            }
        }

        #[cfg(test)]
        mod tests {
            //! One body for both precisions. Cases use coordinates exact in `f32`.

            use super::*;
            use crate::parry::cast::{OVERLAPPING_BALLS_NORMAL, SMALL_TOI_START_GEOMETRY};
            use crate::parry::cast_known_divergences;

            const E: $engine = $engine;

            fn sphere(center: P3, radius: f64) -> Sphere {
                Sphere { center, radius }
            }

            fn plane(normal: P3, offset: f64) -> Plane {
                Plane { normal, offset }
            }

            fn tri(v0: P3, v1: P3, v2: P3) -> Triangle {
                Triangle { vertices: [v0, v1, v2] }
            }

            fn close(got: f64, want: f64, tol: f64) -> bool {
                (got - want).abs() <= tol
            }

            fn assert_hit(c: CastAnswer, t: f64, point: P3, normal: P3, tol: f64) {
                let name = <$engine>::NAME;
                let toi = c.answer.toi.unwrap_or_else(|| panic!("{name}: an impact, got {c:?}"));
                assert!(close(toi.t, t, tol), "{name}: t = {}, want {t}", toi.t);
                for i in 0..3 {
                    assert!(close(toi.point[i], point[i], tol), "{name}: point = {:?}, want {point:?}", toi.point);
                    assert!(close(toi.normal[i], normal[i], tol), "{name}: normal = {:?}, want {normal:?}", toi.normal);
                }
                assert!(!c.answer.degenerate, "{name}: not degenerate");
            }

            fn listed(d: super::super::CastDivergence) -> bool {
                cast_known_divergences().iter().any(|k| k.engine == <$engine>::NAME && k.what == d.what)
            }

            #[test]
            fn cast_ball_ball_parry_issue_35() {
                // parry's own test (crates/parry3d/tests/geometry/ball_ball_toi.rs):
                // radius 0.5 each, a at 0 moving +y at 10, b at y = 10: the gap
                // 10 − 1 = 9 closes at speed 10, t = 0.9; normal from b toward a
                // (0, −1, 0); point M_b(t) + r_b n = (0, 9.5, 0).
                let c = E.cast_sphere_sphere(
                    sphere([0.0; 3], 0.5),
                    [0.0, 10.0, 0.0],
                    sphere([0.0, 10.0, 0.0], 0.5),
                    [0.0; 3],
                    1.0,
                );
                assert_hit(c, 0.9, [0.0, 9.5, 0.0], [0.0, -1.0, 0.0], SMOKE_TOL);
                assert_eq!(c.status, Some(CastStatus::Converged));
                assert_eq!(c.status_str(), "Converged");
            }

            #[test]
            fn cast_ball_ball_both_moving_and_miss() {
                // Head-on along x, closing speed 3 + 1 = 4, gap 10 − 2 = 8: t = 2;
                // at t = 2, b's centre is at 10 − 2 = 8, normal (−1, 0, 0), point
                // 8 − 1 = 7.
                let c = E.cast_sphere_sphere(
                    sphere([0.0; 3], 1.0),
                    [3.0, 0.0, 0.0],
                    sphere([10.0, 0.0, 0.0], 1.0),
                    [-1.0, 0.0, 0.0],
                    4.0,
                );
                assert_hit(c, 2.0, [7.0, 0.0, 0.0], [-1.0, 0.0, 0.0], SMOKE_TOL);
                // The same with t_max = 1.5: the impact is later, none.
                let miss = E.cast_sphere_sphere(
                    sphere([0.0; 3], 1.0),
                    [3.0, 0.0, 0.0],
                    sphere([10.0, 0.0, 0.0], 1.0),
                    [-1.0, 0.0, 0.0],
                    1.5,
                );
                assert_eq!(miss, CastAnswer::default(), "{}", <$engine>::NAME);
            }

            #[test]
            fn cast_t_max_beyond_the_scalar_means_no_limit() {
                // parry's own test of issue #35 casts with max f32::MAX; the
                // fixture says so with the largest f64, which f32 rounds to ∞.
                let c = E.cast_sphere_sphere(
                    sphere([0.0; 3], 0.5),
                    [0.0, 10.0, 0.0],
                    sphere([0.0, 10.0, 0.0], 0.5),
                    [0.0; 3],
                    f64::MAX,
                );
                assert_hit(c, 0.9, [0.0, 9.5, 0.0], [0.0, -1.0, 0.0], SMOKE_TOL);
            }

            #[test]
            fn cast_impact_exactly_at_t_max_is_kept() {
                // Gap 8 at speed 4 ends at t = 2 = t_max: parry drops only t > max.
                let c = E.cast_sphere_sphere(
                    sphere([0.0; 3], 1.0),
                    [4.0, 0.0, 0.0],
                    sphere([10.0, 0.0, 0.0], 1.0),
                    [0.0; 3],
                    2.0,
                );
                assert_hit(c, 2.0, [9.0, 0.0, 0.0], [-1.0, 0.0, 0.0], SMOKE_TOL);
            }

            #[test]
            fn cast_ball_moving_plane_point_moves_with_the_plane() {
                // Ball r = 1 at z = 3 falling at 1, plane z = 0 rising at 1: the gap
                // 2 closes at 2, t = 1; the plane is then at z = 1, the point is the
                // projection (0.5, 0.25, 1), normal +z. A point left in the plane's
                // initial frame would read z = 0.
                let c = E.cast_sphere_plane(
                    sphere([0.5, 0.25, 3.0], 1.0),
                    [0.0, 0.0, -1.0],
                    plane([0.0, 0.0, 2.0], 0.0),
                    [0.0, 0.0, 1.0],
                    1.0,
                );
                assert_hit(c, 1.0, [0.5, 0.25, 1.0], [0.0, 0.0, 1.0], SMOKE_TOL);
                assert_eq!(c.status, Some(CastStatus::Converged));
            }

            #[test]
            fn cast_ball_plane_offset_and_separating() {
                // Plane 3x + 4y = 10 (n̂ = (0.6, 0.8, 0), d/‖n‖ = 2); ball r = 1 at
                // (6, 8, 0) (signed distance 10 − 2 = 8) moving along −n̂ at 2: the
                // gap 7 closes at t = 3.5; centre then (6, 8, 0) − 7 n̂ = (1.8, 2.4, 0),
                // point on the plane (1.2, 1.6, 0).
                let c = E.cast_sphere_plane(
                    sphere([6.0, 8.0, 0.0], 1.0),
                    [-1.2, -1.6, 0.0],
                    plane([3.0, 4.0, 0.0], 10.0),
                    [0.0; 3],
                    4.0,
                );
                assert_hit(c, 3.5, [1.2, 1.6, 0.0], [0.6, 0.8, 0.0], 8.0 * SMOKE_TOL);
                let away = E.cast_sphere_plane(
                    sphere([6.0, 8.0, 0.0], 1.0),
                    [1.2, 1.6, 0.0],
                    plane([3.0, 4.0, 0.0], 10.0),
                    [0.0; 3],
                    4.0,
                );
                assert_eq!(away, CastAnswer::default(), "{}", <$engine>::NAME);
            }

            #[test]
            fn cast_penetrating_at_start_gives_t_zero_with_its_geometry() {
                // Ball r = 1 sunk half a unit into z ≤ 0 and moving away: t = 0, the
                // centre's projection (0, 0, 0), normal +z.
                let c = E.cast_sphere_plane(
                    sphere([0.0, 0.0, 0.5], 1.0),
                    [0.0, 0.0, 5.0],
                    plane([0.0, 0.0, 1.0], 0.0),
                    [0.0; 3],
                    1.0,
                );
                assert_hit(c, 0.0, [0.0; 3], [0.0, 0.0, 1.0], SMOKE_TOL);
                assert_eq!(c.status, Some(CastStatus::PenetratingOrWithinTargetDist));
                // Ball r = 1 centred 0.5 above the unit triangle's face: t = 0,
                // point the centre's projection, normal +z.
                let k = E.cast_sphere_triangle(
                    sphere([0.25, 0.25, 0.5], 1.0),
                    [0.0, 0.0, 1.0],
                    tri([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
                    [0.0; 3],
                    1.0,
                );
                assert_hit(k, 0.0, [0.25, 0.25, 0.0], [0.0, 0.0, 1.0], GJK_TOL);
                assert_eq!(k.status, Some(CastStatus::PenetratingOrWithinTargetDist));
            }

            #[test]
            fn cast_ball_triangle_face_and_moving_triangle() {
                // Ball r = 1 at (0.25, 0.25, 3) falling at 2 onto the unit triangle
                // in z = 0: gap 2, t = 1, point (0.25, 0.25, 0), normal +z. GJK
                // converges to its own tolerance (GJK_TOL), not to the rounding of a
                // formula.
                let c = E.cast_sphere_triangle(
                    sphere([0.25, 0.25, 3.0], 1.0),
                    [0.0, 0.0, -2.0],
                    tri([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
                    [0.0; 3],
                    2.0,
                );
                assert_hit(c, 1.0, [0.25, 0.25, 0.0], [0.0, 0.0, 1.0], GJK_TOL);
                // The triangle slides along +x at 0.5 as the ball (centre x = 0.75)
                // falls: at t = 1 its vertices are (0.5, 0, 0), (1.5, 0, 0),
                // (0.5, 1, 0) and the centre is over its face, so the point is
                // (0.75, 0.25, 0) in the world — (0.25, 0.25, 0) in the triangle's
                // local frame, which is what parry's witness2 says.
                let m = E.cast_sphere_triangle(
                    sphere([0.75, 0.25, 3.0], 1.0),
                    [0.0, 0.0, -2.0],
                    tri([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
                    [0.5, 0.0, 0.0],
                    2.0,
                );
                assert_hit(m, 1.0, [0.75, 0.25, 0.0], [0.0, 0.0, 1.0], GJK_TOL);
            }

            #[test]
            fn cast_refuses_bad_input_flagged() {
                let bad = E.cast_sphere_sphere(
                    sphere([0.0; 3], 0.0),
                    [1.0, 0.0, 0.0],
                    sphere([3.0, 0.0, 0.0], 1.0),
                    [0.0; 3],
                    1.0,
                );
                assert_eq!(bad, REFUSED);
                let flat =
                    E.cast_sphere_plane(sphere([0.0; 3], 1.0), [1.0, 0.0, 0.0], plane([0.0; 3], 1.0), [0.0; 3], 1.0);
                assert_eq!(flat, REFUSED);
                let nan = E.cast_sphere_triangle(
                    sphere([0.0; 3], 1.0),
                    [f64::NAN, 0.0, 0.0],
                    tri([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
                    [0.0; 3],
                    1.0,
                );
                assert_eq!(nan, REFUSED);
            }

            #[test]
            fn cast_zero_area_triangle_is_flagged() {
                // Collinear vertices along x; the ball falls onto the segment's
                // middle. parry casts it (GJK handles the segment); the flag says
                // the face normal is undefined.
                let c = E.cast_sphere_triangle(
                    sphere([0.5, 0.0, 3.0], 1.0),
                    [0.0, 0.0, -2.0],
                    tri([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]),
                    [0.0; 3],
                    2.0,
                );
                assert!(c.answer.degenerate, "{}: flagged, {c:?}", <$engine>::NAME);
            }

            #[test]
            fn cast_divergence_overlapping_balls_normal_not_unit() {
                // Centres 1 apart, radii 1 + 1: parry's normal is Δ/R of length
                // 1/2, its point M_b + r_b Δ/R = (0.5, 0, 0), inside b.
                assert!(listed(OVERLAPPING_BALLS_NORMAL));
                let c =
                    E.cast_sphere_sphere(sphere([1.0, 0.0, 0.0], 1.0), [0.0; 3], sphere([0.0; 3], 1.0), [0.0; 3], 1.0);
                let toi = c.answer.toi.expect("t = 0");
                assert_eq!(c.status, Some(CastStatus::PenetratingOrWithinTargetDist));
                assert!(close(toi.t, 0.0, SMOKE_TOL));
                let len = toi.normal.iter().map(|x| x * x).sum::<f64>().sqrt();
                assert!(
                    close(len, 0.5, SMOKE_TOL),
                    "{}: still diverging: normal length {len} (crashtest: 1)",
                    <$engine>::NAME
                );
                assert!(close(toi.point[0], 0.5, SMOKE_TOL), "point {:?}", toi.point);
            }

            #[test]
            fn cast_divergence_small_toi_reports_start_geometry() {
                // Ball r = 1 at (0.25, 0.25, 1 + 2⁻¹⁵) moving (512, 0, −1): it
                // reaches the face at t = 2⁻¹⁵ ≈ 3.05e-5 < 1e-4, centre then
                // (0.25 + 512 · 2⁻¹⁵, 0.25, 1) = (0.265625, 0.25, 1): crashtest's
                // point (0.265625, 0.25, 0). parry reports the closest point of
                // t = 0, (0.25, 0.25, 0), to GJK's accuracy.
                assert!(listed(SMALL_TOI_START_GEOMETRY));
                let h = (2.0f64).powi(-15);
                let c = E.cast_sphere_triangle(
                    sphere([0.25, 0.25, 1.0 + h], 1.0),
                    [512.0, 0.0, -1.0],
                    tri([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
                    [0.0; 3],
                    1.0,
                );
                let toi = c.answer.toi.expect("an impact");
                assert!(close(toi.t, h, GJK_TOL), "t = {}", toi.t);
                let x = toi.point[0];
                assert!(
                    close(x, 0.25, GJK_TOL) && (x - 0.25).abs() < (x - 0.265625).abs(),
                    "{}: still diverging? point x = {x} (crashtest: 0.265625)",
                    <$engine>::NAME
                );
            }
        }
    };
}

/// parry3d-f64's casts.
mod cast64 {
    use parry3d_f64 as backend;

    /// The engine's scalar.
    type Real = f64;

    /// An input scalar: unchanged.
    fn narrow(x: f64) -> Real {
        x
    }

    /// An answer scalar: unchanged.
    fn widen(x: Real) -> f64 {
        x
    }

    /// Tolerance of the hand-computed smoke cases, absolute, in the cases' length
    /// and time units (of order 1): a few ulps of `f64` at 1.
    #[cfg(test)]
    const SMOKE_TOL: f64 = 1e-14;

    /// Tolerance of the smoke cases answered by GJK (sphere–triangle), absolute,
    /// in length and time units of order 1: GJK stops at its own convergence
    /// threshold, not at rounding. Measured on these cases: witness points off by
    /// up to 3.1e-6 (the moving triangle), times by 5e-12 (3e-9 for the cast under
    /// 1e-4); 1e-5 leaves a factor 3.
    #[cfg(test)]
    const GJK_TOL: f64 = 1e-5;

    cast_adapter!(crate::parry::api::Parry64, crate::parry::parry64);
}

/// parry3d's (f32) casts: inputs rounded to `f32` at the edge, answers widened.
mod cast32 {
    use parry3d as backend;

    /// The engine's scalar.
    type Real = f32;

    /// An input scalar, rounded to the nearest `f32`.
    fn narrow(x: f64) -> Real {
        x as f32
    }

    /// An answer scalar, widened exactly.
    fn widen(x: Real) -> f64 {
        f64::from(x)
    }

    /// Tolerance of the hand-computed smoke cases, absolute, in the cases' length
    /// and time units (of order 1): a few ulps of `f32` at 1 (ulp ≈ 1.2e-7).
    #[cfg(test)]
    const SMOKE_TOL: f64 = 1e-6;

    /// Tolerance of the smoke cases answered by GJK (sphere–triangle), absolute,
    /// in length and time units of order 1: GJK stops at its own convergence
    /// threshold, which in `f32` is coarse. Measured on these cases: witness
    /// points off by up to 2.8e-3 (about 2·10⁴ ulps at 1), times by 1.5e-5;
    /// 1e-2 leaves a factor 3.
    #[cfg(test)]
    const GJK_TOL: f64 = 1e-2;

    cast_adapter!(crate::parry::api::Parry32, crate::parry::parry32);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cast_known_divergences_listed_once_per_engine() {
        for engine in [Parry64::NAME, Parry32::NAME] {
            for d in CAST_DIVERGENCES {
                let n = cast_known_divergences()
                    .iter()
                    .filter(|k| k.engine == engine && k.what == d.what && k.query == "toi")
                    .count();
                assert_eq!(n, 1, "{engine}: `{}` listed once", d.what);
            }
        }
        assert_eq!(cast_known_divergences().len(), 2 * CAST_DIVERGENCES.len());
    }

    #[test]
    fn cast_status_names_are_parrys() {
        for (s, name) in [
            (CastStatus::Converged, "Converged"),
            (CastStatus::OutOfIterations, "OutOfIterations"),
            (CastStatus::Failed, "Failed"),
            (CastStatus::PenetratingOrWithinTargetDist, "PenetratingOrWithinTargetDist"),
        ] {
            assert_eq!(s.as_str(), name);
        }
        assert_eq!(CastAnswer::default().status_str(), "None");
    }
}
