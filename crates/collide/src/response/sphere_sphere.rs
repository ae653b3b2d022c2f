//! The impulse between two spheres along a given normal.

use super::impulse::Response;
use crate::exact::{frexp, ldexp};
use crate::real::{Real, Vec3, try_normalize_stable};

/// Velocities of spheres `a` (velocity `va`, mass `ma`) and `b` (`vb`, `mb`) after
/// one frictionless impulse with restitution `e` along the contact `normal`
/// (from `b` toward `a`; any non-zero length, it is normalized).
///
/// **Formula** (the lecture's rigid collision; Hecker, *Physics, Part 3:
/// Collision Response*, 1997, without the angular terms, which vanish for
/// spheres hit along the line of centres). With `n` the unit normal and the
/// relative velocity `v_rel = va − vb`, the normal approach speed is
/// `v_n = v_rel·n` (negative when approaching). Newton's restitution law asks
/// `v_n' = −e v_n` after the impulse `j n` on `a` and `−j n` on `b`:
///
/// ```text
/// v_n' = v_n + j (1/ma + 1/mb) = −e v_n
///   ⇒  j = −(1 + e) v_n / (1/ma + 1/mb)
/// va' = va + (j/ma) n,    vb' = vb − (j/mb) n
/// ```
///
/// Momentum `ma va + mb vb` is conserved (the impulses are opposite), the
/// tangential velocities are untouched (frictionless), and with `e = 1` the
/// kinetic energy is conserved; with `e = 0` the bodies leave with equal normal
/// velocities.
///
/// **Full range.** The formula is evaluated through the mass fractions
/// `ma/(ma + mb)` and `mb/(ma + mb)`, never through `1/ma` and `1/mb`:
///
/// ```text
/// va' = va − (1 + e) v_n · mb/(ma + mb) · n,    vb' = vb + (1 + e) v_n · ma/(ma + mb) · n
/// j   = −(1 + e) v_n · μ,    μ = ma mb/(ma + mb) = min(ma, mb) · (its partner's fraction)
/// ```
///
/// so a positive subnormal mass (whose inverse overflows) is a valid mass, and
/// masses of `1e300` (whose inverses' sum is far below the velocities'
/// scale) give finite velocities. An infinite mass is a static body (its
/// fraction of the other's change is 0, the other's is 1). Where the plain
/// evaluation overflows or a fraction leaves the normal range (a sum of masses
/// or a relative velocity beyond the largest finite value, a mass ratio beyond
/// `2^1022`), a scaled path recomputes it with the exponents carried apart
/// (`respond_scaled`, in the source): every velocity whose exact value is
/// representable comes out finite. An impulse `j` whose exact value overflows
/// (masses `1e300` at speeds `1e10`: `j ≈ 1e310`) is `∞`, the velocities
/// still exact to a few roundings, not flagged.
///
/// **Separating bodies.** When `v_n ≥ 0` (moving apart or sliding) there is
/// nothing to resolve: the velocities are returned unchanged, impulse 0.
///
/// **Degenerate input.** A zero or non-finite normal, a mass that is not
/// positive (or NaN), both masses infinite, a non-finite `e`, or non-finite
/// velocities whose approach is undefined: no impulse can be defined;
/// velocities unchanged, `degenerate: true`. `e` outside `[0, 1]` is applied
/// as given (`e > 1` adds energy).
pub fn respond_sphere_sphere<T: Real>(va: &Vec3<T>, ma: T, vb: &Vec3<T>, mb: T, normal: &Vec3<T>, e: T) -> Response<T> {
    let Some(n) = try_normalize_stable(normal) else {
        return Response::unchanged(va, vb, true);
    };
    if !(ma > T::zero() && mb > T::zero() && e.finite()) || !(ma.finite() || mb.finite()) {
        return Response::unchanged(va, vb, true);
    }
    let vn = (va - vb).dot(&n);
    if vn >= T::zero() {
        // Separating or sliding (`+∞` only from an overflowing difference of
        // finite velocities: separating too).
        return Response::unchanged(va, vb, false);
    }
    // Each body's share of the change of the relative velocity: the
    // partner's mass fraction (0 for a static body, 1 for its partner).
    let sum = ma + mb;
    let (fa, fb) = match (ma.finite(), mb.finite()) {
        (true, true) => (mb / sum, ma / sum),
        (true, false) => (T::one(), T::zero()),
        _ => (T::zero(), T::one()),
    };
    let closing = -(T::one() + e) * vn;
    let (da, db) = (closing * fa, closing * fb);
    let (new_a, new_b) = (va + n * da, vb - n * db);
    // The reduced mass from the lighter body and the heavier one's fraction
    // (at least 1/2): no product of two large masses, no underflowing one.
    let reduced = if ma <= mb { ma * fa } else { mb * fb };
    let j = closing * reduced;
    let min = min_normal::<T>();
    // Fractions in the normal range (a static body's 0 and 1 are exact).
    let fractions_ok = (fa.wide() >= min && fb.wide() >= min) || !(ma.finite() && mb.finite());
    // (A static body's infinite sum is no overflow: its fractions are exact.)
    let plain = vn.finite()
        && (sum.finite() || !(ma.finite() && mb.finite()))
        && fractions_ok
        && reduced.wide() >= min
        && j.finite()
        && crate::real::finite3(&new_a)
        && crate::real::finite3(&new_b);
    if plain {
        return Response { velocity_a: new_a, velocity_b: new_b, impulse: j, degenerate: false };
    }
    respond_scaled(va, ma, vb, mb, &n, e)
}

/// The smallest positive normal number of `T`, as `f64`.
#[inline(always)]
fn min_normal<T: Real>() -> f64 {
    if T::EPSILON.wide() > 1e-10 { f64::from(f32::MIN_POSITIVE) } else { f64::MIN_POSITIVE }
}

/// A number `m · 2^k` with its exponent carried apart (`m` an `f64`, `0` or
/// of magnitude in `[2^−4, 4)` after the operations below): products and
/// quotients of such numbers neither overflow nor underflow.
#[derive(Clone, Copy, Debug)]
struct Scaled {
    m: f64,
    k: i64,
}

impl Scaled {
    /// `x` exactly (finite `x`).
    fn of(x: f64) -> Self {
        let (m, k) = frexp(x.abs());
        Self { m: m.copysign(x), k }
    }

    fn mul(self, o: Self) -> Self {
        Self { m: self.m * o.m, k: self.k + o.k }
    }

    fn div(self, o: Self) -> Self {
        Self { m: self.m / o.m, k: self.k - o.k }
    }

    /// The value rounded to `f64` (`±∞` beyond the range).
    fn value(self) -> f64 {
        ldexp(self.m, self.k)
    }

    /// `x + c · self` per component without spurious overflow: at a scale
    /// that keeps `c · self` finite when `self` exceeds `2^1000`, then
    /// scaled back (overflowing only when the sum does, up to a rounding).
    fn add_to(self, x: [f64; 3], c: [f64; 3]) -> [f64; 3] {
        if self.k <= 1000 {
            let d = self.value();
            return [0, 1, 2].map(|i| x[i] + c[i] * d);
        }
        let up = self.k - 1000;
        let d = ldexp(self.m, 1000);
        [0, 1, 2].map(|i| ldexp(ldexp(x[i], -up) + c[i] * d, up))
    }
}

/// The scaled path of [`respond_sphere_sphere`] (valid masses and `e`, a unit
/// normal `n`, bodies approaching or undecided by the plain evaluation), in
/// `f64` on the widened inputs with exponents carried apart: the relative
/// velocity at a quarter of its scale (exact for normal velocities, and its
/// dot product with a unit vector cannot overflow), the sum of the masses at
/// half scale when it overflows, the fractions, the changes and the reduced
/// mass as [`Scaled`] numbers, each velocity formed at a scale where the
/// change is finite. A few roundings in all, none spurious.
#[cold]
#[inline(never)]
fn respond_scaled<T: Real>(va: &Vec3<T>, ma: T, vb: &Vec3<T>, mb: T, n: &Vec3<T>, e: T) -> Response<T> {
    let w = crate::real::to_f64_3::<T>;
    let (a, b, nn) = (w(va), w(vb), w(n));
    let (ma, mb, e) = (ma.wide(), mb.wide(), e.wide());
    let rel = [0, 1, 2].map(|i| a[i] * 0.25 - b[i] * 0.25);
    let quarter = (rel[0] * nn[0] + rel[1] * nn[1]) + rel[2] * nn[2];
    if quarter.is_nan() {
        // Non-finite velocities: no approach speed is defined.
        return Response::unchanged(va, vb, true);
    }
    if quarter >= 0.0 {
        return Response::unchanged(va, vb, false);
    }
    // (1 + e) · (−v_n), with v_n = 4 · quarter.
    let closing = Scaled::of(1.0 + e).mul(Scaled::of(-quarter)).mul(Scaled { m: 1.0, k: 2 });
    let (fa, fb, reduced) = match (ma.is_finite(), mb.is_finite()) {
        (true, true) => {
            let (sum, half) = match ma + mb {
                s if s.is_finite() => (s, 0),
                _ => (ma * 0.5 + mb * 0.5, 1),
            };
            let sum = Scaled::of(sum).mul(Scaled { m: 1.0, k: half });
            let (fa, fb) = (Scaled::of(mb).div(sum), Scaled::of(ma).div(sum));
            let reduced = if ma <= mb { Scaled::of(ma).mul(fa) } else { Scaled::of(mb).mul(fb) };
            (Some(fa), Some(fb), reduced)
        }
        (true, false) => (Some(Scaled::of(1.0)), None, Scaled::of(ma)),
        _ => (None, Some(Scaled::of(1.0)), Scaled::of(mb)),
    };
    let minus = nn.map(|x| -x);
    let new_a = fa.map_or(a, |f| closing.mul(f).add_to(a, nn));
    let new_b = fb.map_or(b, |f| closing.mul(f).add_to(b, minus));
    let t = |p: [f64; 3]| Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]));
    Response {
        velocity_a: t(new_a),
        velocity_b: t(new_b),
        impulse: T::of(closing.mul(reduced).value()),
        degenerate: false,
    }
}
