//! Signs and values of the small polynomials the box and capsule queries decide
//! with: written once over [`Ring`], evaluated first in `f64` with a running
//! error bound ([`Filt`]) and, when that bound cannot settle the sign (or the
//! value to the accuracy asked), again in [`BigFloat`], exactly.
//!
//! Every polynomial takes two groups of inputs: **lengths** (coordinates,
//! half-extents, radii, offsets) and **units** (rotation entries, plane
//! normals, signs and masks). It must be homogeneous in the lengths (every
//! term of the same degree in them): the filter then evaluates it on the
//! lengths scaled by one power of two that brings the largest to `[0.5, 1)`,
//! so nothing overflows at `1e300` or underflows at `1e-300`, and the sign
//! is unchanged. The exact path uses the inputs as given.
//!
//! The error bound is a running one (Wilkinson's): each operation adds the
//! propagated errors of its operands and its own rounding, `u·|result|`
//! (counted twice, for the rounding of the bound itself), plus `2^−1073` for a
//! product that may have underflowed. It is loose, which costs only an exact
//! evaluation now and then, and it is zero when every operation was exact
//! (checked by error-free transformations), so an exact zero — a point on a
//! face, a touching pair on a grid — is decided without the exact path.

use crate::exact::{BigFloat, Estimate, Sign, frexp, ldexp};

/// Unit roundoff of `f64`, `2^−53`.
const U: f64 = f64::EPSILON / 2.0;
/// The absolute error of a product that may have underflowed, `2^−1073`
/// (twice the largest, `2^−1074`).
const UNDERFLOW: f64 = f64::from_bits(2);
/// Relative accuracy asked of a value (2^−40, the kit's
/// [`crate::exact::ESTIMATE_REL_ERR`]).
pub(crate) const VALUE_REL_ERR: f64 = crate::exact::ESTIMATE_REL_ERR;

/// The arithmetic the polynomials are written in.
pub(crate) trait Ring: Clone {
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `self − o`.
    fn sub(&self, o: &Self) -> Self;
    /// `self · o`.
    fn mul(&self, o: &Self) -> Self;
    /// `|self|`.
    fn abs(&self) -> Self;
}

/// An `f64` value `v` whose exact counterpart lies within `e` of it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Filt {
    v: f64,
    e: f64,
}

/// Whether `a + b` rounded to `s` is exact (Knuth's TwoSum error is zero).
#[inline(always)]
fn sum_exact(a: f64, b: f64, s: f64) -> bool {
    let bv = s - a;
    let av = s - bv;
    (a - av) + (b - bv) == 0.0
}

/// Whether `a · b` rounded to `p` is exact (Dekker's product error is zero);
/// `false` where the splitting could overflow or the error underflow.
#[inline(always)]
fn product_exact(a: f64, b: f64, p: f64) -> bool {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    const BIG: f64 = 1e290;
    const SMALL: f64 = 1e-290;
    if p == 0.0 {
        return a == 0.0 || b == 0.0;
    }
    if !(a.abs() < BIG && b.abs() < BIG && p.abs() > SMALL) {
        return false;
    }
    let split = |x: f64| {
        let c = SPLITTER * x;
        let hi = c - (c - x);
        (hi, x - hi)
    };
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    let err = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    err == 0.0
}

impl Filt {
    /// The value and its bound (0 when every operation was exact).
    #[inline(always)]
    pub(crate) fn parts(&self) -> (f64, f64) {
        (self.v, self.e)
    }

    /// An exact value.
    #[inline(always)]
    pub(crate) fn exact(v: f64) -> Self {
        Self { v, e: 0.0 }
    }

    /// `x · 2^k`, with the error of a result that fell into the subnormals.
    #[inline(always)]
    fn scaled(x: f64, k: i64) -> Self {
        if k == 0 {
            return Self::exact(x);
        }
        let v = ldexp(x, k);
        Self { v, e: if v.abs() < f64::MIN_POSITIVE && x != 0.0 { f64::MIN_POSITIVE } else { 0.0 } }
    }

    /// The sign, when the bound settles it.
    #[inline(always)]
    pub(crate) fn sign(&self) -> Option<Sign> {
        if self.v.is_finite() && self.e.is_finite() && (self.v.abs() > self.e || self.e == 0.0) {
            Some(Sign::of(self.v))
        } else {
            None
        }
    }
}

impl Ring for Filt {
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        let v = self.v + o.v;
        let e = if self.e == 0.0 && o.e == 0.0 && sum_exact(self.v, o.v, v) {
            0.0
        } else {
            (self.e + o.e + 2.0 * U * v.abs()) * (1.0 + 4.0 * U)
        };
        Self { v, e }
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        self.add(&Self { v: -o.v, e: o.e })
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        let v = self.v * o.v;
        let exact_zero = (self.v == 0.0 && self.e == 0.0) || (o.v == 0.0 && o.e == 0.0);
        let e = if exact_zero || (self.e == 0.0 && o.e == 0.0 && product_exact(self.v, o.v, v)) {
            0.0
        } else {
            (self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + 2.0 * U * v.abs() + UNDERFLOW) * (1.0 + 8.0 * U)
        };
        Self { v, e }
    }
    #[inline(always)]
    fn abs(&self) -> Self {
        Self { v: self.v.abs(), e: self.e }
    }
}

/// [`Filt`] without its exactness tracking (only an exactly zero operand
/// still gives an exact zero product): the same values, cheaper, and at every
/// node a bound at least [`Filt`]'s. By induction: the leaves are the same;
/// each operation computes the same value, and [`Filt`]'s bound is either 0
/// or the same formula, which grows with the operands' bounds. So when
/// [`Fast`] settles a sign or a value, [`Filt`] settles the same one (the
/// same value, with a bound no larger), and [`sign_fast`] and [`value_fast`]
/// answer as [`sign`] and [`value`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fast {
    pub(crate) v: f64,
    pub(crate) e: f64,
}

impl Ring for Fast {
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        let v = self.v + o.v;
        Self { v, e: (self.e + o.e + 2.0 * U * v.abs()) * (1.0 + 4.0 * U) }
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        self.add(&Self { v: -o.v, e: o.e })
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        let v = self.v * o.v;
        let exact_zero = (self.v == 0.0 && self.e == 0.0) || (o.v == 0.0 && o.e == 0.0);
        let e = if exact_zero {
            0.0
        } else {
            (self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + 2.0 * U * v.abs() + UNDERFLOW) * (1.0 + 8.0 * U)
        };
        Self { v, e }
    }
    #[inline(always)]
    fn abs(&self) -> Self {
        Self { v: self.v.abs(), e: self.e }
    }
}

impl Fast {
    /// As [`Filt::scaled`].
    #[inline(always)]
    fn scaled(x: f64, k: i64) -> Self {
        let f = Filt::scaled(x, k);
        Self { v: f.v, e: f.e }
    }
}

impl Ring for BigFloat {
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn abs(&self) -> Self {
        if self.sign() == Sign::Negative { -self } else { self.clone() }
    }
}

/// A polynomial over lengths `[N; K]` and units `[N; J]`.
pub(crate) type Poly<N, const K: usize, const J: usize> = fn(&[N; K], &[N; J]) -> N;

/// The power of two bringing the largest of `len` into `[0.5, 1)` (0 when all
/// are zero).
#[inline(always)]
fn exponent_of<const K: usize>(len: &[f64; K]) -> i64 {
    let m = len.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() { 0 } else { -frexp(m).1 }
}

/// The filtered evaluation: the value and its bound on the scaled lengths, and
/// the power of two they were scaled by.
#[inline(always)]
fn filtered<const K: usize, const J: usize>(len: &[f64; K], unit: &[f64; J], f: Poly<Filt, K, J>) -> (Filt, i64) {
    let k = exponent_of(len);
    (f(&len.map(|x| Filt::scaled(x, k)), &unit.map(Filt::exact)), k)
}

#[cold]
fn exact<const K: usize, const J: usize>(len: &[f64; K], unit: &[f64; J], g: Poly<BigFloat, K, J>) -> BigFloat {
    g(&len.map(BigFloat::from_f64), &unit.map(BigFloat::from_f64))
}

/// The exact sign of the polynomial (`f` and `g` are the same polynomial over
/// [`Filt`] and [`BigFloat`]). Inputs must be finite.
#[inline]
pub(crate) fn sign<const K: usize, const J: usize>(
    len: [f64; K],
    unit: [f64; J],
    f: Poly<Filt, K, J>,
    g: Poly<BigFloat, K, J>,
) -> Sign {
    let (x, _) = filtered(&len, &unit, f);
    x.sign().unwrap_or_else(|| exact(&len, &unit, g).sign())
}

/// The polynomial's value (homogeneous of degree `deg` in the lengths) as an
/// [`Estimate`] with an exact sign and a relative error at most
/// [`VALUE_REL_ERR`]. Inputs must be finite.
#[inline]
pub(crate) fn value<const K: usize, const J: usize>(
    len: [f64; K],
    unit: [f64; J],
    deg: i64,
    f: Poly<Filt, K, J>,
    g: Poly<BigFloat, K, J>,
) -> Estimate {
    let (x, k) = filtered(&len, &unit, f);
    if x.e == 0.0 && x.v.is_finite() {
        return Estimate::from_scaled(x.v, -k * deg, 0.0);
    }
    if x.v.is_finite() && x.e.is_finite() && x.v.abs() > x.e {
        let rel = x.e / (x.v.abs() - x.e) * (1.0 + 4.0 * U);
        if rel <= VALUE_REL_ERR {
            return Estimate::from_scaled(x.v, -k * deg, rel);
        }
    }
    exact(&len, &unit, g).estimate()
}

/// [`sign`], after a first evaluation in [`Fast`] (`fast` the same
/// polynomial) that answers when it settles the sign: the same answer.
#[inline]
pub(crate) fn sign_fast<const K: usize, const J: usize>(
    len: [f64; K],
    unit: [f64; J],
    fast: Poly<Fast, K, J>,
    f: Poly<Filt, K, J>,
    g: Poly<BigFloat, K, J>,
) -> Sign {
    let k = exponent_of(&len);
    let x = fast(&len.map(|x| Fast::scaled(x, k)), &unit.map(|u| Fast { v: u, e: 0.0 }));
    if x.v.is_finite() && x.e.is_finite() && (x.v.abs() > x.e || x.e == 0.0) {
        return Sign::of(x.v);
    }
    sign(len, unit, f, g)
}

/// [`value`], after a first evaluation in [`Fast`] (`fast` the same
/// polynomial) that answers when it meets the accuracy: the same value (its
/// stated relative error may be larger, never above [`VALUE_REL_ERR`]).
#[inline]
pub(crate) fn value_fast<const K: usize, const J: usize>(
    len: [f64; K],
    unit: [f64; J],
    deg: i64,
    fast: Poly<Fast, K, J>,
    f: Poly<Filt, K, J>,
    g: Poly<BigFloat, K, J>,
) -> Estimate {
    let k = exponent_of(&len);
    let x = fast(&len.map(|x| Fast::scaled(x, k)), &unit.map(|u| Fast { v: u, e: 0.0 }));
    if x.e == 0.0 && x.v.is_finite() {
        return Estimate::from_scaled(x.v, -k * deg, 0.0);
    }
    if x.v.is_finite() && x.e.is_finite() && x.v.abs() > x.e {
        let rel = x.e / (x.v.abs() - x.e) * (1.0 + 4.0 * U);
        if rel <= VALUE_REL_ERR {
            return Estimate::from_scaled(x.v, -k * deg, rel);
        }
    }
    value(len, unit, deg, f, g)
}

/// `sign_of!(p, lengths, units)`: [`sign`] of the generic polynomial `p`
/// (through [`sign_fast`]).
macro_rules! sign_of {
    ($p:ident, $len:expr, $unit:expr) => {
        $crate::boxes::poly::sign_fast(
            $len,
            $unit,
            $p::<$crate::boxes::poly::Fast>,
            $p::<$crate::boxes::poly::Filt>,
            $p::<$crate::exact::BigFloat>,
        )
    };
}
pub(crate) use sign_of;

/// `value_of!(p, degree, lengths, units)`: [`value`] of the generic polynomial
/// `p` (through [`value_fast`]).
macro_rules! value_of {
    ($p:ident, $deg:expr, $len:expr, $unit:expr) => {
        $crate::boxes::poly::value_fast(
            $len,
            $unit,
            $deg,
            $p::<$crate::boxes::poly::Fast>,
            $p::<$crate::boxes::poly::Filt>,
            $p::<$crate::exact::BigFloat>,
        )
    };
}
pub(crate) use value_of;

/// An [`Estimate`]'s value times `2^k`, as an `f64` (infinite or zero beyond
/// the range).
#[inline]
pub(crate) fn scaled_f64(x: Estimate, k: i64) -> f64 {
    match x.sign {
        Sign::Zero => 0.0,
        Sign::Positive => ldexp(x.mant, x.exp + k),
        Sign::Negative => -ldexp(x.mant, x.exp + k),
    }
}

/// `x · 2^k / ‖n‖` for a plane normal in parts (`‖n‖ = m·l`, see
/// [`crate::contact::normal_parts`]), formed on the exponents so that neither
/// the quotient's numerator nor its denominator over- or underflows.
#[inline]
pub(crate) fn over_norm(x: Estimate, m: f64, l: f64, k: i64) -> f64 {
    let (mm, me) = frexp(m);
    let q = x.mant / (mm * l);
    match x.sign {
        Sign::Zero => 0.0,
        Sign::Positive => ldexp(q, x.exp - me + k),
        Sign::Negative => -ldexp(q, x.exp - me + k),
    }
}

/// `x / y` of two estimates, formed on their exponents (0 when `y` is zero).
#[inline]
pub(crate) fn ratio(x: Estimate, y: Estimate) -> f64 {
    if y.sign == Sign::Zero || x.sign == Sign::Zero {
        return 0.0;
    }
    let q = ldexp(x.mant / y.mant, x.exp - y.exp);
    if x.sign == y.sign { q } else { -q }
}

/// `x / ‖q‖²` of a finite non-zero quaternion `q`, within a few more
/// roundings (`‖q‖²` formed on `q` scaled by a power of two, so it neither
/// over- nor underflows): a length that a polynomial of the quaternion's axes
/// ([`quaternion_axes`]) returned multiplied by `‖q‖²`.
#[inline]
pub(crate) fn over_norm2(x: Estimate, q: &[f64; 4]) -> Estimate {
    let m = q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if x.sign == Sign::Zero || m == 0.0 {
        return x;
    }
    let e = frexp(m).1;
    let n: f64 = q.iter().map(|x| ldexp(*x, -e) * ldexp(*x, -e)).sum();
    let (mant, ex) = frexp(x.mant / n);
    Estimate { sign: x.sign, mant, exp: x.exp + ex - 2 * e, rel_err: x.rel_err + 16.0 * U }
}

// Vector helpers over a ring.

/// The columns of `‖q‖² R(q)`, `q = [w, x, y, z]`: the box's axes scaled by
/// `‖q‖²`, each entry a quadratic in `q` (exact in the ring):
/// `M_0 = (w²+x²−y²−z², 2(xy+wz), 2(xz−wy))`,
/// `M_1 = (2(xy−wz), w²−x²+y²−z², 2(yz+wx))`,
/// `M_2 = (2(xz+wy), 2(yz−wx), w²−x²−y²+z²)`.
pub(crate) fn quaternion_axes<N: Ring>(q: [&N; 4]) -> [[N; 3]; 3] {
    let [w, x, y, z] = q;
    let (ww, xx, yy, zz) = (w.mul(w), x.mul(x), y.mul(y), z.mul(z));
    let two = |a: N| a.add(&a);
    let (xy, wz, xz, wy, yz, wx) = (x.mul(y), w.mul(z), x.mul(z), w.mul(y), y.mul(z), w.mul(x));
    [
        [ww.add(&xx).sub(&yy).sub(&zz), two(xy.add(&wz)), two(xz.sub(&wy))],
        [two(xy.sub(&wz)), ww.sub(&xx).add(&yy).sub(&zz), two(yz.add(&wx))],
        [two(xz.add(&wy)), two(yz.sub(&wx)), ww.sub(&xx).sub(&yy).add(&zz)],
    ]
}

/// `‖q‖²`.
pub(crate) fn norm2<N: Ring>(q: [&N; 4]) -> N {
    q[0].mul(q[0]).add(&q[1].mul(q[1])).add(&q[2].mul(q[2])).add(&q[3].mul(q[3]))
}

/// `Σ_i s_i v_i` of one-hot selectors `s` (0 or 1) over `K ≥ 1` vectors.
pub(crate) fn select<N: Ring, const K: usize>(s: &[N], v: &[[N; 3]; K]) -> [N; 3] {
    std::array::from_fn(|k| (1..K).fold(s[0].mul(&v[0][k]), |acc, i| acc.add(&s[i].mul(&v[i][k]))))
}

/// The quaternion `u[0..4]`, `‖q‖²` and the axis `M_i = ‖q‖² R(q) e_i` picked
/// by the one-hot selector `u[4..7]` (see [`crate::boxes::quaternion_units`]).
pub(crate) fn picked_axis<N: Ring>(u: &[N]) -> ([N; 3], N) {
    let q = [&u[0], &u[1], &u[2], &u[3]];
    (select(&u[4..7], &quaternion_axes(q)), norm2(q))
}

/// `a − b`.
#[inline(always)]
pub(crate) fn sub3<N: Ring>(a: [&N; 3], b: [&N; 3]) -> [N; 3] {
    [a[0].sub(b[0]), a[1].sub(b[1]), a[2].sub(b[2])]
}

/// `a · b`.
#[inline(always)]
pub(crate) fn dot3<N: Ring>(a: [&N; 3], b: [&N; 3]) -> N {
    a[0].mul(b[0]).add(&a[1].mul(b[1])).add(&a[2].mul(b[2]))
}

/// `a × b`.
#[inline(always)]
pub(crate) fn cross3<N: Ring>(a: [&N; 3], b: [&N; 3]) -> [N; 3] {
    [a[1].mul(b[2]).sub(&a[2].mul(b[1])), a[2].mul(b[0]).sub(&a[0].mul(b[2])), a[0].mul(b[1]).sub(&a[1].mul(b[0]))]
}

/// References to three consecutive entries of `x` from `i`.
#[inline(always)]
pub(crate) fn at<N, const K: usize>(x: &[N; K], i: usize) -> [&N; 3] {
    [&x[i], &x[i + 1], &x[i + 2]]
}

/// References to the three entries of an array.
#[inline(always)]
pub(crate) fn refs<N>(x: &[N; 3]) -> [&N; 3] {
    [&x[0], &x[1], &x[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(m·a − c)² − r²` with m a unit: a small homogeneous polynomial.
    fn p<N: Ring>(l: &[N; 3], u: &[N; 1]) -> N {
        let x = u[0].mul(&l[0]).sub(&l[1]);
        x.mul(&x).sub(&l[2].mul(&l[2]))
    }

    #[test]
    fn signs_are_exact_at_every_scale_and_at_zero() {
        // 0.1·3 − 0.3 is not 0 in binary (0.1 and 0.3 are rounded
        // differently): its square against r = 0 is positive, which the
        // filter cannot see and the exact path does.
        for s in [1.0, 1e300, 1e-300, 2f64.powi(-1060)] {
            assert_eq!(sign_of!(p, [3.0 * s, 0.3 * s, 0.0], [0.1]), Sign::Positive, "scale {s:e}");
            // (2·1 − 1)² − 1² = 0 exactly, decided by the filter's exact
            // tracking.
            assert_eq!(sign_of!(p, [1.0 * s, 1.0 * s, 1.0 * s], [2.0]), Sign::Zero, "scale {s:e}");
            assert_eq!(sign_of!(p, [1.0 * s, 1.0 * s, 2.0 * s], [2.0]), Sign::Negative, "scale {s:e}");
        }
    }

    #[test]
    fn values_are_accurate_beyond_the_range() {
        // (1·1e300 − 0)² − 0 = 1e600: held as an estimate, 2^−40 relative.
        let x = value_of!(p, 2, [1e300, 0.0, 0.0], [1.0]);
        let want_log2 = 600.0 * 10f64.log2();
        let got_log2 = x.mant.log2() + x.exp as f64;
        assert!((got_log2 - want_log2).abs() < 1e-9, "{x:?}");
        assert_eq!(x.sign, Sign::Positive);
        // The same value at unit scale, exactly.
        let y = value_of!(p, 2, [3.0, 1.0, 1.0], [1.0]);
        assert!((y.to_f64() - 3.0).abs() <= 3.0 * VALUE_REL_ERR, "{y:?}");
    }

    #[test]
    fn the_fast_evaluation_answers_as_the_filtered_one() {
        // Random, grid (exact) and near-cancelling inputs at several scales:
        // the sign and the value through `Fast` first are those of `Filt`
        // then the exact path.
        let mut x = 0x1234_5678_9abc_def0u64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in 0..3000 {
            let s = [1.0, 1e300, 1e-300, 2f64.powi(-1060)][n % 4];
            let (a, c, r, m) = match n % 3 {
                0 => (next(), next(), next(), next() * 4.0),
                1 => ((next() * 8.0).round(), (next() * 8.0).round(), (next() * 8.0).round(), (next() * 4.0).round()),
                _ => {
                    let a = next();
                    (a, a * 3.0, 0.0, 3.0)
                }
            };
            let (len, unit) = ([a * s, c * s, r * s], [m]);
            let fast = sign_of!(p, len, unit);
            assert_eq!(fast, sign(len, unit, p::<Filt>, p::<BigFloat>), "{len:?} {unit:?}");
            let (v, w) = (value_of!(p, 2, len, unit), value(len, unit, 2, p::<Filt>, p::<BigFloat>));
            assert!(v.sign == w.sign && v.mant.to_bits() == w.mant.to_bits() && v.exp == w.exp, "{v:?} {w:?}");
        }
    }
}
