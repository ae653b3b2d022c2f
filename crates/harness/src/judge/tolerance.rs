//! Tolerances for judging an engine against the referee: one entry per precision
//! and quantity, each with its reason.
//!
//! **The rule: each field is judged by the problem's own scale.** What a field
//! may be off by is derived from the sizes that decide that field at that input
//! (see [`super::sizes`], which writes the rule out per query kind), never from
//! the scene's bounding size alone:
//!
//! `allowed = FIXED · magnitude + K · ε · condition`, at least [`Tolerance::floor`]
//!
//! - `magnitude` sums the magnitudes the field is built from: for a contact with
//!   a triangle, the sphere's centre and radius, the answer's point, and the
//!   triangle's vertices each weighted by the share the closest point takes of it
//!   (a sphere of radius 4 beside a triangle with legs of 1e15 is judged at the
//!   size of 4, not of 1e15); for a segment hit, the segment's ends and the
//!   surface at the hit; for a barycentric coordinate, the coordinates' own
//!   size; for a time, `t_max`; for a velocity, the input and output speeds;
//! - `condition` is the first-order change of the field when every input point
//!   moves by `ε` of its own size (backward error): a normal between two points
//!   at distance `d` turns by their sizes over `d`; a crossing's `t` moves by the
//!   ends' distance changes over the segment's extent across the surface; a
//!   sliver's plane tilts by the vertices' sizes over its altitudes; a time moves
//!   by a distance change over the closing speed;
//! - `FIXED` is the precision's fixed allowance below ([`F64_REL`], …), `K` the
//!   conditioning allowance in units of the engine's ε ([`NORMAL_CONDITION_ULPS`],
//!   …), and the floor a few of the precision's smallest subnormals, so that no
//!   allowance is 0 (an answer of 4.9e-324 off by 4.9e-324 is one rounding, not a
//!   disagreement) — and none is NaN or infinite: every size is computed with norms
//!   that scale before they square, and an infinite condition is capped by the
//!   field's own range (π for a normal, `t_max` for a time).
//!
//! The same table therefore serves a scene at the origin, one at 1e9, and a small
//! feature beside a huge one; normals are judged by their angle.

/// Relative (to the field's local magnitude) error allowed of an `f64` engine's points,
/// depths and barycentric reconstructions: 1e-9. A well-conditioned query loses a
/// few hundred ulps at most (2.2e-16 each); the remaining six orders of magnitude
/// are left for the conditioning of near-degenerate cases (grazing contacts,
/// near-parallel segments), which the stability sweeps chart separately.
pub const F64_REL: f64 = 1e-9;

/// Relative error allowed of an `f32` engine: 1e-4. Rounding the inputs to `f32`
/// alone costs 6e-8 of the scale (half an ulp), and each operation as much again;
/// 1e-4 leaves three orders of magnitude for conditioning, as for f64.
pub const F32_REL: f64 = 1e-4;

/// Normal angle allowed of an `f64` engine, in radians: 1e-7. A unit normal from a
/// difference of points of the scene's size is off by about `ε · scale / distance`;
/// 1e-7 admits distances down to 1e-9 of the scene before a normal is called
/// wrong.
pub const F64_NORMAL_RAD: f64 = 1e-7;

/// Normal angle allowed of an `f32` engine, in radians: 1e-2 (`f32`'s ε is 1.2e-7;
/// the same reasoning as [`F64_NORMAL_RAD`], with distances down to 1e-5 of the
/// scene).
pub const F32_NORMAL_RAD: f64 = 1e-2;

/// Barycentric coordinates are dimensionless: an `f64` engine may be off by 1e-9
/// in each (the same allowance as [`F64_REL`], since a coordinate is a ratio of
/// lengths of the scene's size).
pub const F64_BARY: f64 = 1e-9;

/// Barycentric allowance of an `f32` engine (as [`F32_REL`]).
pub const F32_BARY: f64 = 1e-4;

/// Conditioning allowance for normals, in units of the engine's epsilon: a normal
/// built from a difference of points of the scene's size carries an absolute
/// error of a few ulps of the scale in each component, and dividing by the true
/// distance `d` between them turns that into an angle of about
/// `ε · scale / d`. When `d` is tiny (a centre almost on a triangle, two nearly
/// concentric spheres) no method working in the engine's precision can do
/// better, so the allowance is `NORMAL_CONDITION_ULPS · ε · scale / d` on top of
/// the fixed one. 16 covers the few roundings of a closest-point computation.
pub const NORMAL_CONDITION_ULPS: f64 = 16.0;

/// Conditioning allowance for barycentric coordinates, in units of the engine's
/// epsilon: perturbing the inputs by `ε · scale` moves a coordinate (a ratio of
/// areas) by about `(1 + max |coordinate|) · ε · scale · L / ‖n‖`, with `L` the
/// longest edge and `‖n‖` twice the area; a sliver makes that large for every
/// method in the engine's precision. 16 covers the cross and dot products.
pub const BARY_CONDITION_ULPS: f64 = 16.0;

/// Conditioning allowance for a time of impact, in units of the engine's
/// epsilon: the first touch is where a distance reaches the radius, and any
/// method evaluates that distance with an absolute error of a few ulps of the
/// scene's scale; the touching time moves by that error over the speed at
/// which the gap closes (`closing`), which a near-parallel approach or a
/// grazing pass makes small — no method that tests distances in the engine's
/// precision does better on the same inputs. So a time is allowed `K · ε · scale / closing` (for
/// curved surfaces at most `√(2 R K ε scale)/‖v‖`, `R` the radius of
/// curvature) on top of the fixed allowance, and the point and the normal what
/// that time moves them by (see `judge::toi_allowance`). The distance behind
/// a time is the moved centre (a multiply-add of coordinates of the scene's
/// size at the impact), a triangle's closest point (a dozen dot products and a
/// division) and a norm: on the generated grazing passes the `f64` engines'
/// distances were off by up to 25 ulps of that scale, so 64 leaves room while
/// staying far below what a wrong first touch costs (a whole feature's time).
pub const TIME_CONDITION_ULPS: f64 = 64.0;

/// Conditioning allowance for lengths (points, depths, velocities), in units of
/// the engine's epsilon: a point built from a normal turns with it (a sphere's
/// surface point moves by its radius times the normal's turn), a crossing moves
/// along its segment by the length times the error of `t`. 16, as for normals.
pub const LENGTH_CONDITION_ULPS: f64 = 16.0;

/// How far a normal's length may be from 1, in units of the engine's
/// epsilon: 4. Every normal in an answer is a unit vector by the format's
/// convention, and normalizing any non-zero direction in the engine's
/// precision gives a length within about 2 ulps of 1 (the sum of squares, the
/// square root and the division each round once), at any conditioning: the
/// direction may be ill-conditioned (its angle has its own allowance), its
/// length is not. So no conditioning term is added; 4 leaves room for an
/// engine that multiplies by a rounded reciprocal instead of dividing. The
/// judge measures the length in two words ([`super::compare::unit_excess`]), so
/// its own rounding does not count against the engine.
pub const NORMAL_LENGTH_ULPS: f64 = 4.0;

/// The floor of every allowance, in units of the precision's smallest positive
/// (subnormal) number: an answer of that size has no finer grid, so one
/// rounding of it is that far. 16 leaves room for the few roundings of a
/// subnormal result.
pub const FLOOR_SUBNORMALS: f64 = 16.0;

/// The tolerances in force for one engine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Points, depths, distances, radii: relative to the field's local magnitude.
    pub rel: f64,
    /// Normals: radians.
    pub normal_rad: f64,
    /// Barycentric coordinates and segment parameters `t`: absolute.
    pub unitless: f64,
    /// The engine's machine epsilon (unit roundoff × 2), for the conditioning
    /// allowances.
    pub eps: f64,
    /// The precision's smallest positive (subnormal) number.
    pub tiny: f64,
    /// How far a normal's length may be from 1, in units of `eps`:
    /// [`NORMAL_LENGTH_ULPS`], or `N` under `--ulps N`.
    pub normal_length_ulps: f64,
}

impl Tolerance {
    /// The table entry for an engine of `precision` mantissa bits (53 for f64, 24
    /// for f32; `None`, the referee itself, is held to the f64 entry).
    pub fn for_precision(precision: Option<u32>) -> Self {
        match precision {
            Some(p) if p < 53 => Tolerance {
                rel: F32_REL,
                normal_rad: F32_NORMAL_RAD,
                unitless: F32_BARY,
                eps: f64::from(f32::EPSILON),
                tiny: f64::from(f32::from_bits(1)),
                normal_length_ulps: NORMAL_LENGTH_ULPS,
            },
            _ => Tolerance {
                rel: F64_REL,
                normal_rad: F64_NORMAL_RAD,
                unitless: F64_BARY,
                eps: f64::EPSILON,
                tiny: f64::from_bits(1),
                normal_length_ulps: NORMAL_LENGTH_ULPS,
            },
        }
    }

    /// This tolerance with its fixed allowances (relative, angle, unitless)
    /// all `x`: `N · ε` under `--ulps N`, 0 for the conditioning alone.
    pub fn fixed(self, x: f64) -> Self {
        Tolerance { rel: x, normal_rad: x, unitless: x, ..self }
    }

    /// The entry for `precision` ([`Tolerance::for_precision`]), its fixed
    /// allowances replaced by `N` of the precision's ulps when `ulps` is
    /// `Some(N)` (`--ulps N`: is the engine backward stable to `N` ulps?),
    /// and a normal's length held to `N` ulps of 1 as well; the conditioning
    /// allowances and the floor stay as they are.
    pub fn for_engine(precision: Option<u32>, ulps: Option<f64>) -> Self {
        let t = Tolerance::for_precision(precision);
        match ulps {
            Some(n) => Tolerance { normal_length_ulps: n, ..t.fixed(n * t.eps) },
            None => t,
        }
    }

    /// The smallest allowance of any field: [`FLOOR_SUBNORMALS`] of the
    /// precision's smallest positive number.
    pub fn floor(&self) -> f64 {
        FLOOR_SUBNORMALS * self.tiny
    }
}
