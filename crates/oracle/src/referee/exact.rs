//! Exact number helpers: `f64` → rational conversion, rational 3-vectors, and the
//! correctly rounded evaluation of `a + b·√q`.

use dashu::base::{Approximation, BitTest, SquareRoot, SquareRootRem, UnsignedAbs};
use dashu::integer::{IBig, UBig};
use dashu::rational::{RBig, Relaxed};

use super::error::{PRECISION_BITS, RefereeError};
use crate::geom::P3;

/// An exact rational.
pub(crate) type Q = RBig;
/// An exact rational 3-vector.
pub(crate) type V3 = [Q; 3];

/// The largest square-root precision the rounding loop tries. The separation bound
/// of `a + b·√q` from the nearest rounding boundary for `f64`-derived inputs needs
/// a few tens of thousands of bits at most, so this is never reached; it only makes
/// termination evident. Bits.
const MAX_PRECISION_BITS: usize = 1 << 20;

/// The exact value of `x`, or an error naming `field` when `x` is NaN or ±∞.
pub(crate) fn q(x: f64, field: &'static str) -> Result<Q, RefereeError> {
    check(x, field)?;
    // Every finite f64 is a dyadic rational; the conversion is exact.
    Q::try_from(x).map_err(|_| RefereeError::NonFinite { field })
}

/// [`q`]'s check without the rational: the same error, or nothing. The
/// stages run on checked input before any rational is made (making one costs
/// more than a stage's whole answer); the conversions after them cannot fail.
pub(crate) fn check(x: f64, field: &'static str) -> Result<(), RefereeError> {
    if x.is_finite() { Ok(()) } else { Err(RefereeError::NonFinite { field }) }
}

/// [`v3`]'s checks without the rationals (see [`check`]).
pub(crate) fn check_v3(p: &P3, field: &'static str) -> Result<(), RefereeError> {
    p.iter().try_for_each(|&x| check(x, field))
}

/// [`radius`]'s checks without the rational (see [`check`]): `-0.0` is not
/// negative, as its rational is 0.
pub(crate) fn check_radius(r: f64, field: &'static str) -> Result<(), RefereeError> {
    check(r, field)?;
    if r < 0.0 { Err(RefereeError::NegativeRadius { field }) } else { Ok(()) }
}

/// The exact value of a point.
pub(crate) fn v3(p: &P3, field: &'static str) -> Result<V3, RefereeError> {
    Ok([q(p[0], field)?, q(p[1], field)?, q(p[2], field)?])
}

/// A radius, refused when negative.
pub(crate) fn radius(r: f64, field: &'static str) -> Result<Q, RefereeError> {
    check_radius(r, field)?;
    let r = q(r, field)?;
    Ok(r)
}

pub(crate) fn sub(a: &V3, b: &V3) -> V3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

pub(crate) fn add(a: &V3, b: &V3) -> V3 {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]]
}

pub(crate) fn scale(v: &V3, s: &Q) -> V3 {
    [&v[0] * s, &v[1] * s, &v[2] * s]
}

pub(crate) fn dot(a: &V3, b: &V3) -> Q {
    dot_relaxed(a, b).canonicalize()
}

/// [`dot`] unreduced: `Relaxed` drops only common factors of two (all a
/// dyadic input has) and compares exactly as [`Q`] does, so a value that is
/// only compared is never reduced by a gcd — the most of an exact
/// comparison's cost on large numbers.
pub(crate) fn dot_relaxed(a: &V3, b: &V3) -> Relaxed {
    let t = |i: usize| a[i].as_relaxed() * b[i].as_relaxed();
    t(0) + t(1) + t(2)
}

pub(crate) fn cross(a: &V3, b: &V3) -> V3 {
    [&a[1] * &b[2] - &a[2] * &b[1], &a[2] * &b[0] - &a[0] * &b[2], &a[0] * &b[1] - &a[1] * &b[0]]
}

pub(crate) fn is_zero(v: &V3) -> bool {
    v.iter().all(Q::is_zero)
}

/// `a + t (b − a)`.
pub(crate) fn lerp(a: &V3, b: &V3, t: &Q) -> V3 {
    add(a, &scale(&sub(b, a), t))
}

/// `x` correctly rounded to `f64` (nearest, ties to even; ±∞ beyond the range).
pub(crate) fn round(x: &Q) -> f64 {
    match x.to_f64() {
        Approximation::Exact(f) | Approximation::Inexact(f, _) => f,
    }
}

/// [`round`] of a rational not reduced to lowest terms: the same correct
/// rounding (round to nearest, ties to even) of the same value, without the
/// gcd that reducing it costs.
pub(crate) fn round_relaxed(x: &dashu::rational::Relaxed) -> f64 {
    match x.to_f64() {
        Approximation::Exact(f) | Approximation::Inexact(f, _) => f,
    }
}

/// Each component correctly rounded.
pub(crate) fn round_v(v: &V3) -> P3 {
    [round(&v[0]), round(&v[1]), round(&v[2])]
}

/// `√q` for an exact `q ≥ 0`, ready to round expressions `a + b·√q`.
pub(crate) struct Root {
    q: Q,
    /// `√q` when it is rational.
    exact: Option<Q>,
    /// `q = num / den` in lowest terms; `√q = √(num·den) / den`.
    num_den: UBig,
    den: UBig,
    /// The enclosure at [`PRECISION_BITS`], computed once.
    first: Option<(Q, Q)>,
}

impl Root {
    /// Prepares `√q`. A negative `q` (never produced by the callers, which pass
    /// sums of squares) is treated as 0.
    pub(crate) fn new(q: Q) -> Self {
        let q = if q < Q::ZERO { Q::ZERO } else { q };
        let (num, den) = q.clone().into_parts();
        let num = num.unsigned_abs();
        let (sn, rn) = num.sqrt_rem();
        let (sd, rd) = den.sqrt_rem();
        let exact = (rn.is_zero() && rd.is_zero()).then(|| Q::from_parts(IBig::from(sn), sd));
        let num_den = &num * &den;
        let mut root = Self { q, exact, num_den, den, first: None };
        if root.exact.is_none() {
            root.first = Some(root.bounds(PRECISION_BITS));
        }
        root
    }

    /// `q` itself.
    pub(crate) fn square(&self) -> &Q {
        &self.q
    }

    /// Rationals `lo ≤ √q ≤ hi` with `hi − lo ≈ 2^-bits · √q`.
    ///
    /// With `P = num·den` and `M = ⌊P·4^k⌋`, `m = ⌊√M⌋` satisfies `m ≤ √(P·4^k) < m + 1`
    /// (`m² ≤ M ≤ P·4^k` and `(m+1)² ≥ M + 1 > P·4^k`), so
    /// `√q = √P / den ∈ [m, m + 1] / (den·2^k)`. `k` is chosen so `m` has about
    /// `bits + 2` bits.
    fn bounds(&self, bits: usize) -> (Q, Q) {
        let target = 2 * (bits as isize + 2);
        let have = self.num_den.bit_len() as isize;
        let k = (target - have + 1).div_euclid(2);
        if k >= 0 {
            let k = k as usize;
            let m = (&self.num_den << (2 * k)).sqrt();
            let d = &self.den << k;
            let hi = Q::from_parts(IBig::from(&m + UBig::ONE), d.clone());
            (Q::from_parts(IBig::from(m), d), hi)
        } else {
            let k = (-k) as usize;
            let m = (&self.num_den >> (2 * k)).sqrt();
            let hi = Q::from_parts(IBig::from((&m + UBig::ONE) << k), self.den.clone());
            (Q::from_parts(IBig::from(m << k), self.den.clone()), hi)
        }
    }

    /// `a + b·√q`, correctly rounded to `f64`.
    pub(crate) fn round_affine(&self, a: &Q, b: &Q) -> f64 {
        if b.is_zero() || self.q.is_zero() {
            return round(a);
        }
        if let Some(s) = &self.exact {
            return round(&(a + b * s));
        }
        // √q is irrational, so is a + b√q: it lies strictly inside one rounding
        // interval, and a narrow enough enclosure rounds to one value at both ends.
        let mut bits = PRECISION_BITS;
        loop {
            let (lo, hi) = match (&self.first, bits == PRECISION_BITS) {
                (Some(first), true) => first.clone(),
                _ => self.bounds(bits),
            };
            let x0 = a + b * &lo;
            let x1 = a + b * &hi;
            let (r0, r1) = (round(&x0), round(&x1));
            if r0.to_bits() == r1.to_bits() || bits >= MAX_PRECISION_BITS {
                return r0;
            }
            bits *= 2;
        }
    }

    /// `√q`, correctly rounded.
    pub(crate) fn round_sqrt(&self) -> f64 {
        self.round_affine(&Q::ZERO, &Q::ONE)
    }

    /// `a + b / √q` (`q ≠ 0`), correctly rounded: `b/√q = (b/q)·√q`.
    pub(crate) fn round_over(&self, a: &Q, b: &Q) -> f64 {
        if self.q.is_zero() {
            return round(a);
        }
        self.round_affine(a, &(b / &self.q))
    }

    /// `a + (b / √q) · v` component-wise, correctly rounded.
    pub(crate) fn round_over_v(&self, a: &V3, b: &Q, v: &V3) -> P3 {
        [
            self.round_over(&a[0], &(b * &v[0])),
            self.round_over(&a[1], &(b * &v[1])),
            self.round_over(&a[2], &(b * &v[2])),
        ]
    }
}

/// `v / ‖v‖` (`v ≠ 0`), each component correctly rounded.
pub(crate) fn round_unit(v: &V3) -> P3 {
    let root = Root::new(dot(v, v));
    root.round_over_v(&[Q::ZERO, Q::ZERO, Q::ZERO], &Q::ONE, v)
}

/// The number of representable `f64` between `a` and `b` (0 when equal, and
/// `+0` and `−0` are 0 apart): the distance tests measure rounding by.
#[cfg(test)]
pub(crate) fn ulps(a: f64, b: f64) -> u64 {
    fn ordered(x: f64) -> i128 {
        let bits = x.to_bits();
        let mag = i128::from(bits & !(1u64 << 63));
        if bits >> 63 == 1 { -mag } else { mag }
    }
    let d = ordered(a) - ordered(b);
    u64::try_from(d.unsigned_abs()).unwrap_or(u64::MAX)
}

/// Whether `a` and `b` are at most `allowance` ulps apart.
#[cfg(test)]
pub(crate) fn within_ulps(a: f64, b: f64, allowance: u64) -> bool {
    ulps(a, b) <= allowance
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn referee_exact_round_matches_std_sqrt_which_is_correctly_rounded() {
        // IEEE 754 requires sqrt to be correctly rounded, so std's f64::sqrt of an
        // exactly representable q is an independent correctly rounded reference.
        for x in [2.0, 3.0, 0.5, 1e-300, 1e300, 7.0e-310, 123456.789, f64::MAX] {
            let root = Root::new(q(x, "x").unwrap());
            let got = root.round_sqrt();
            assert_eq!(got.to_bits(), x.sqrt().to_bits(), "sqrt({x}): {got} vs {}", x.sqrt());
        }
    }

    #[test]
    fn referee_exact_rational_roots_are_exact() {
        // q = 9/4: √q = 3/2 is found exactly (no enclosure).
        let root = Root::new(Q::from_parts(IBig::from(9), UBig::from(4u8)));
        assert!(root.exact.is_some());
        assert_eq!(root.round_sqrt().to_bits(), 1.5f64.to_bits());
        // 1 − √(9/4)·(2/3) = 0 exactly, not a tiny residue.
        let r = root.round_affine(&Q::ONE, &Q::from_parts(IBig::from(-2), UBig::from(3u8)));
        assert_eq!(r.to_bits(), 0.0f64.to_bits());
    }

    /// The expected value below is known to a relative 1e-33, so the correct
    /// rounding is the reference literal or, were it that close to a midpoint,
    /// a neighbour: 1 ulp.
    const NEIGHBOUR_ULPS: u64 = 1;

    #[test]
    fn referee_exact_cancellation_is_resolved_by_raising_precision() {
        // x = 1e16 − √(1e32 − 1) = 1 / (1e16 + √(1e32 − 1)) ≈ 5e-17: the leading
        // 53 digits cancel. Rationalized independently: 1/(2e16) up to a relative
        // 1.25e-33, far below one ulp, so the answer is within 1 ulp of 5e-17.
        let big = q(1e16, "x").unwrap();
        let qq = &big * &big - Q::ONE;
        let root = Root::new(qq);
        let got = root.round_affine(&big, &Q::NEG_ONE);
        assert!(within_ulps(got, 5e-17, NEIGHBOUR_ULPS), "{got}");
    }

    #[test]
    fn referee_exact_refuses_non_finite() {
        assert_eq!(q(f64::NAN, "f"), Err(RefereeError::NonFinite { field: "f" }));
        assert_eq!(q(f64::INFINITY, "f"), Err(RefereeError::NonFinite { field: "f" }));
        assert_eq!(radius(-1.0, "r"), Err(RefereeError::NegativeRadius { field: "r" }));
    }
}
