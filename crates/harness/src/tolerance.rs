//! Tolerances for judging an engine against the referee: one entry per precision
//! and quantity, each with its reason. Errors of points, depths and times are
//! measured relative to the scene's scale (the largest coordinate, radius or
//! offset in the case), so the same table serves a scene at the origin and one at
//! 1e9; normals are judged by their angle.

/// Relative (to the scene's scale) error allowed of an `f64` engine's points,
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

/// The tolerances in force for one engine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Points, depths, distances, radii: relative to the scene's scale.
    pub rel: f64,
    /// Normals: radians.
    pub normal_rad: f64,
    /// Barycentric coordinates and segment parameters `t`: absolute.
    pub unitless: f64,
    /// The engine's machine epsilon (unit roundoff × 2), for the conditioning
    /// allowances.
    pub eps: f64,
}

impl Tolerance {
    /// The table entry for an engine of `precision` mantissa bits (53 for f64, 24
    /// for f32; `None`, the referee itself, is held to the f64 entry).
    pub fn for_precision(precision: Option<u32>) -> Self {
        match precision {
            Some(p) if p < 53 => {
                Tolerance { rel: F32_REL, normal_rad: F32_NORMAL_RAD, unitless: F32_BARY, eps: f64::from(f32::EPSILON) }
            }
            _ => Tolerance { rel: F64_REL, normal_rad: F64_NORMAL_RAD, unitless: F64_BARY, eps: f64::EPSILON },
        }
    }
}
