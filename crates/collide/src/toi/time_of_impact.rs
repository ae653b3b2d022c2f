//! The result of a time-of-impact query and the halving method's stopping rule.

use crate::contact::{CONCENTRIC_FALLBACK_NORMAL, Contact};
use crate::real::{Real, Vec3, c, finite3, try_normalize_stable};

/// How a time-of-impact answer was reached, and so which fields of [`Toi`] mean
/// what (after parry's `ShapeCastStatus`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ToiStatus {
    /// The method finished by its own rule. `t` is the first time of contact to
    /// the method's stated accuracy, and `point` and `normal` are the contact at
    /// `t`:
    ///
    /// - closed forms: `t` up to rounding;
    /// - halving: the upper end of the final bracket, within `t_max / 2^k` of the
    ///   first contact after `k` bisections; the contact is the static test's at
    ///   that time (slightly overlapping, depth ≥ 0);
    /// - conservative advancement (triangles, meshes): the gap at `t` fell
    ///   within the tolerance and a few more safe steps took it to the
    ///   distance's rounding, so `t` is at the impact or just before it (the
    ///   shapes may not quite touch, by a rounding).
    Converged,
    /// Conservative advancement hit its iteration cap. `t` is a time before which
    /// the shapes certainly do not touch (a lower bound on the time of impact, if
    /// there is one); `point` and `normal` are the closest point of `b` and the
    /// direction toward `a` at `t` — a separation, not a contact. The pair may in
    /// fact never touch.
    OutOfIterations,
    /// The shapes are already in contact (touching counts) at `t = 0`: `t = 0`,
    /// and `point` and `normal` are the static contact at time 0.
    Penetrating,
}

/// A time of impact, in the fixture format's convention for `toi(a, b)`.
///
/// - `t ∈ [0, t_max]`: the first time the shapes touch (see [`ToiStatus`] for how
///   exactly each method means it);
/// - `point` lies on `b`'s surface at time `t` (world frame, `b` moved by its
///   velocity);
/// - `normal` is unit length and points from `b` toward `a`.
///
/// When `degenerate` is set, the normal is a documented fallback, not a defined
/// answer (concentric spheres at `t = 0`, a sphere centre on a triangle, or two
/// shapes of zero total radius meeting at a point); `t` and `point` stay
/// meaningful.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Toi<T: Real> {
    /// Time of impact, in `[0, t_max]`.
    pub t: T,
    /// Contact point on `b`'s surface at time `t`.
    pub point: Vec3<T>,
    /// Unit normal from `b` toward `a` at time `t`.
    pub normal: Vec3<T>,
    /// How the answer was reached.
    pub status: ToiStatus,
    /// Bisections (halving) or advancement steps (conservative advancement)
    /// taken; 0 for the closed forms.
    pub iterations: u32,
    /// The normal is a documented fallback.
    pub degenerate: bool,
}

impl<T: Real> Toi<T> {
    /// Whether every number of the answer is finite: a contact point beyond
    /// the type's range (an impact so late that `b` has moved past `MAX`) is
    /// no answer (see [`toi_sphere_triangle`](super::toi_sphere_triangle)).
    pub(crate) fn in_range(&self) -> bool {
        self.t.finite() && finite3(&self.point) && finite3(&self.normal)
    }

    /// The answer for shapes already in contact at `t = 0`: the static
    /// contact, flagged `degenerate` when `fallback` (its normal is a
    /// documented fallback, or its point lies beyond the type's range). The
    /// static contact's own flag also marks a depth beyond the range (two
    /// spheres of radius `MAX` overlap by more than `MAX`), which a time of
    /// impact, reporting no depth, does not share.
    pub(crate) fn penetrating_flagged(k: &Contact<T>, fallback: bool) -> Self {
        Self { degenerate: fallback, ..Self::penetrating(k) }
    }

    /// The answer for shapes already in contact at `t = 0`: the static contact.
    pub(crate) fn penetrating(k: &Contact<T>) -> Self {
        Self {
            t: T::zero(),
            point: k.point,
            normal: k.normal,
            status: ToiStatus::Penetrating,
            iterations: 0,
            degenerate: k.degenerate,
        }
    }
}

/// When interval halving stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Halving<T: Real> {
    /// Exactly this many bisections (fewer only if the bracket reaches the
    /// type's resolution first). After `k` of them the bracket, and so the error
    /// in `t`, is at most `t_max / 2^k`.
    Steps(u32),
    /// Bisect until the bracket is no wider than this (units of time), or until
    /// it cannot be narrowed in the type (its midpoint rounds to an end). A
    /// tolerance that is not positive therefore runs to the type's resolution.
    Tolerance(T),
}

/// `t_max` as the methods read it: a negative or NaN value is 0 (the interval
/// `[0, 0]`: only a contact at time 0 is found).
pub(crate) fn clamp_t_max<T: Real>(t_max: T) -> T {
    if t_max > T::zero() { t_max } else { T::zero() }
}

/// The normal reported when two shapes meet at a single point with no radius
/// between them (a zero total radius), where `a − b` vanishes at the impact: the
/// direction `a` came from, `−v/‖v‖` for the relative velocity `v = va − vb`
/// (it points from `b` toward where `a` was). A zero velocity cannot reach this
/// case (nothing moves), but falls back to [`CONCENTRIC_FALLBACK_NORMAL`].
pub(crate) fn approach_fallback<T: Real>(v: &Vec3<T>) -> Vec3<T> {
    try_normalize_stable(&(-v)).unwrap_or_else(|| {
        let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
        Vec3::new(c(x), c(y), c(z))
    })
}
