//! A small arbitrary-precision binary float: exact `+`, `−`, `×` and sign for
//! values built from `f64`.
//!
//! A [`BigFloat`] is `±mag · 2^exp` with `mag` an unbounded unsigned integer
//! (little-endian `u64` limbs) and `exp` an `i64`. Every finite `f64` — normal,
//! subnormal or zero — is exactly such a value (`m · 2^e` with `m < 2^53`), and
//! sums, differences and products of such values are again such values, so the
//! three operations are exact with no rounding and no overflow: the result simply
//! grows. A polynomial of degree 3 in `f64` inputs spans at most about
//! `3 · 2098 + 3 · 53` bits, i.e. around a hundred limbs; that is the size of the
//! worst case crashtest's predicates meet.
//!
//! There is no division and no rounding mode: the type exists to decide signs
//! exactly and to give the nearest-`f64`-sized [`Estimate`] of a value.

use core::cmp::Ordering;
use core::ops::{Add, Mul, Neg, Sub};

use super::{Estimate, Sign};

/// An exact binary floating-point number of unbounded precision and range.
///
/// Invariant: `mag` has no high zero limb and no low zero limb (a low zero limb
/// is folded into `exp`); zero is the empty `mag` with `negative == false`.
/// Equality and order are those of the values (`1 · 2^1 == 2 · 2^0`).
#[derive(Clone, Debug, Default)]
pub struct BigFloat {
    negative: bool,
    mag: Vec<u64>,
    exp: i64,
}

impl BigFloat {
    /// Zero (does not allocate).
    pub const ZERO: Self = Self { negative: false, mag: Vec::new(), exp: 0 };

    /// The exact value of a finite `f64` (subnormals and `−0.0` included; `−0.0`
    /// becomes zero). `None` for an infinity or a NaN.
    pub fn try_from_f64(x: f64) -> Option<Self> {
        if !x.is_finite() {
            return None;
        }
        let bits = x.to_bits();
        let biased = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1u64 << 52) - 1);
        let (mut m, mut e) = if biased == 0 {
            // Subnormal (or zero): fraction · 2^−1074.
            (fraction, -1074)
        } else {
            (fraction | (1u64 << 52), biased - 1075)
        };
        if m == 0 {
            return Some(Self::ZERO);
        }
        let tz = m.trailing_zeros();
        m >>= tz;
        e += i64::from(tz);
        Some(Self { negative: x.is_sign_negative(), mag: vec![m], exp: e })
    }

    /// The exact value of a finite `f64`; a non-finite `x` gives zero (callers
    /// check finiteness first; see [`BigFloat::try_from_f64`]).
    pub fn from_f64(x: f64) -> Self {
        Self::try_from_f64(x).unwrap_or(Self::ZERO)
    }

    /// The sign of the value, exactly.
    pub fn sign(&self) -> Sign {
        if self.mag.is_empty() {
            Sign::Zero
        } else if self.negative {
            Sign::Negative
        } else {
            Sign::Positive
        }
    }

    /// Whether the value is zero.
    pub fn is_zero(&self) -> bool {
        self.mag.is_empty()
    }

    /// Exact comparison of two values.
    pub fn cmp_value(&self, other: &Self) -> Ordering {
        match (self - other).sign() {
            Sign::Negative => Ordering::Less,
            Sign::Zero => Ordering::Equal,
            Sign::Positive => Ordering::Greater,
        }
    }

    /// The value as an [`Estimate`] (`mant · 2^exp`, `mant ∈ [0.5, 1)`): the top
    /// 128 bits of the magnitude rounded to the nearest `f64`, so the relative
    /// error is below `2^−53 + 2^−127`, whatever the value's size.
    pub fn estimate(&self) -> Estimate {
        let n = self.mag.len();
        if n == 0 {
            return Estimate::ZERO;
        }
        // Top two limbs as one u128, the rest dropped (truncation, ≤ 2^−64
        // relative since the top limb is non-zero).
        let (top, low_limbs) = if n >= 2 {
            ((u128::from(self.mag[n - 1]) << 64) | u128::from(self.mag[n - 2]), n - 2)
        } else {
            (u128::from(self.mag[0]), 0)
        };
        // `top as f64` rounds to nearest and cannot overflow (top < 2^128).
        let (mant, e) = super::estimate::frexp(top as f64);
        Estimate {
            sign: self.sign(),
            mant,
            exp: e + self.exp + 64 * low_limbs as i64,
            rel_err: super::estimate::EXACT_REL_ERR,
        }
    }

    /// The nearest `f64` as far as an [`Estimate`] goes (faithful, not always
    /// correctly rounded); saturates to `±∞` and flushes toward zero outside the
    /// `f64` range.
    pub fn to_f64(&self) -> f64 {
        self.estimate().to_f64()
    }

    fn from_parts(negative: bool, mut mag: Vec<u64>, mut exp: i64) -> Self {
        while mag.last() == Some(&0) {
            mag.pop();
        }
        if mag.is_empty() {
            return Self::ZERO;
        }
        let low = mag.iter().take_while(|&&l| l == 0).count();
        if low > 0 {
            mag.drain(..low);
            exp += 64 * low as i64;
        }
        Self { negative, mag, exp }
    }

    fn add_signed(&self, other: &Self, negate_other: bool) -> Self {
        let other_negative = other.negative ^ negate_other;
        if other.is_zero() {
            return self.clone();
        }
        if self.is_zero() {
            return Self { negative: other_negative, mag: other.mag.clone(), exp: other.exp };
        }
        // Align on the smaller exponent: the operand with the larger one is
        // shifted into a fresh buffer (the only allocation), the other is added
        // or subtracted in place.
        let ((hi, hi_neg), (lo, lo_neg)) = if self.exp >= other.exp {
            ((self, self.negative), (other, other_negative))
        } else {
            ((other, other_negative), (self, self.negative))
        };
        let mut acc = shifted_left(&hi.mag, (hi.exp - lo.exp) as u64, lo.mag.len() + 1);
        if hi_neg == lo_neg {
            add_in_place(&mut acc, &lo.mag);
            return Self::from_parts(hi_neg, acc, lo.exp);
        }
        match cmp_mag(&acc, &lo.mag) {
            Ordering::Equal => Self::ZERO,
            Ordering::Greater => {
                sub_in_place(&mut acc, &lo.mag);
                Self::from_parts(hi_neg, acc, lo.exp)
            }
            Ordering::Less => {
                reverse_sub_in_place(&mut acc, &lo.mag);
                Self::from_parts(lo_neg, acc, lo.exp)
            }
        }
    }

    fn mul_ref(&self, other: &Self) -> Self {
        if self.is_zero() || other.is_zero() {
            return Self::ZERO;
        }
        let mut out = vec![0u64; self.mag.len() + other.mag.len()];
        for (i, &x) in self.mag.iter().enumerate() {
            let mut carry: u128 = 0;
            for (j, &y) in other.mag.iter().enumerate() {
                let cur = u128::from(out[i + j]) + u128::from(x) * u128::from(y) + carry;
                out[i + j] = cur as u64;
                carry = cur >> 64;
            }
            out[i + other.mag.len()] = carry as u64;
        }
        Self::from_parts(self.negative != other.negative, out, self.exp + other.exp)
    }
}

/// `mag · 2^bits` as a new limb vector of at least `min_len` limbs (one spare
/// limb above the shifted value for carries).
fn shifted_left(mag: &[u64], bits: u64, min_len: usize) -> Vec<u64> {
    let limbs = (bits / 64) as usize;
    let rem = (bits % 64) as u32;
    let mut out = vec![0u64; (limbs + mag.len() + 1).max(min_len)];
    if rem == 0 {
        out[limbs..limbs + mag.len()].copy_from_slice(mag);
    } else {
        for (i, &l) in mag.iter().enumerate() {
            out[limbs + i] |= l << rem;
            out[limbs + i + 1] = l >> (64 - rem);
        }
    }
    out
}

/// Number of limbs below the highest non-zero one, plus one.
fn significant_len(a: &[u64]) -> usize {
    a.len() - a.iter().rev().take_while(|&&l| l == 0).count()
}

fn cmp_mag(a: &[u64], b: &[u64]) -> Ordering {
    let (la, lb) = (significant_len(a), significant_len(b));
    if la != lb {
        return la.cmp(&lb);
    }
    for i in (0..la).rev() {
        match a[i].cmp(&b[i]) {
            Ordering::Equal => continue,
            o => return o,
        }
    }
    Ordering::Equal
}

/// `acc += b`; `acc` is longer than `b` and has room for the carry.
fn add_in_place(acc: &mut [u64], b: &[u64]) {
    let mut carry = false;
    for (i, x) in acc.iter_mut().enumerate() {
        let y = b.get(i).copied().unwrap_or(0);
        if i >= b.len() && !carry {
            break;
        }
        let (s1, c1) = x.overflowing_add(y);
        let (s2, c2) = s1.overflowing_add(u64::from(carry));
        *x = s2;
        carry = c1 || c2;
    }
    debug_assert!(!carry, "add_in_place without room for the carry");
}

/// `acc −= b` for `acc ≥ b`.
fn sub_in_place(acc: &mut [u64], b: &[u64]) {
    let mut borrow = false;
    for (i, x) in acc.iter_mut().enumerate() {
        let y = b.get(i).copied().unwrap_or(0);
        if i >= b.len() && !borrow {
            break;
        }
        let (d1, b1) = x.overflowing_sub(y);
        let (d2, b2) = d1.overflowing_sub(u64::from(borrow));
        *x = d2;
        borrow = b1 || b2;
    }
    debug_assert!(!borrow, "sub_in_place with acc < b");
}

/// `acc = b − acc` for `b > acc` (`acc` at least as long as `b`).
fn reverse_sub_in_place(acc: &mut [u64], b: &[u64]) {
    let mut borrow = false;
    for (i, x) in acc.iter_mut().enumerate() {
        let y = b.get(i).copied().unwrap_or(0);
        let (d1, b1) = y.overflowing_sub(*x);
        let (d2, b2) = d1.overflowing_sub(u64::from(borrow));
        *x = d2;
        borrow = b1 || b2;
    }
    debug_assert!(!borrow, "reverse_sub_in_place with b < acc");
}

impl PartialEq for BigFloat {
    fn eq(&self, other: &Self) -> bool {
        self.cmp_value(other) == Ordering::Equal
    }
}

impl Eq for BigFloat {}

impl PartialOrd for BigFloat {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for BigFloat {
    fn cmp(&self, other: &Self) -> Ordering {
        self.cmp_value(other)
    }
}

impl Add for &BigFloat {
    type Output = BigFloat;
    fn add(self, other: &BigFloat) -> BigFloat {
        self.add_signed(other, false)
    }
}

impl Sub for &BigFloat {
    type Output = BigFloat;
    fn sub(self, other: &BigFloat) -> BigFloat {
        self.add_signed(other, true)
    }
}

impl Mul for &BigFloat {
    type Output = BigFloat;
    fn mul(self, other: &BigFloat) -> BigFloat {
        self.mul_ref(other)
    }
}

impl Neg for &BigFloat {
    type Output = BigFloat;
    fn neg(self) -> BigFloat {
        let mut out = self.clone();
        if !out.is_zero() {
            out.negative = !out.negative;
        }
        out
    }
}

impl Add for BigFloat {
    type Output = BigFloat;
    fn add(self, other: BigFloat) -> BigFloat {
        &self + &other
    }
}

impl Sub for BigFloat {
    type Output = BigFloat;
    fn sub(self, other: BigFloat) -> BigFloat {
        &self - &other
    }
}

impl Mul for BigFloat {
    type Output = BigFloat;
    fn mul(self, other: BigFloat) -> BigFloat {
        &self * &other
    }
}

impl Neg for BigFloat {
    type Output = BigFloat;
    fn neg(mut self) -> BigFloat {
        if !self.is_zero() {
            self.negative = !self.negative;
        }
        self
    }
}

/// A vector of exact numbers: the exact paths' points and directions.
pub(crate) type B3 = [BigFloat; 3];

/// `x − y`, exactly.
pub(crate) fn sub3(x: &B3, y: &B3) -> B3 {
    [0, 1, 2].map(|i| &x[i] - &y[i])
}

/// `x · y`, exactly.
pub(crate) fn dot3(x: &B3, y: &B3) -> BigFloat {
    &(&(&x[0] * &y[0]) + &(&x[1] * &y[1])) + &(&x[2] * &y[2])
}

/// `x × y`, exactly.
pub(crate) fn cross3(x: &B3, y: &B3) -> B3 {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        &(&x[j] * &y[k]) - &(&x[k] * &y[j])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn bf(x: f64) -> BigFloat {
        BigFloat::from_f64(x)
    }

    /// Every finite f64 except NaN and infinities, across the whole range.
    fn any_finite() -> impl Strategy<Value = f64> {
        use proptest::num::f64::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
        POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO
    }

    /// Values `m · 2^k` with `|k| ≤ 500`: products stay normal f64 numbers.
    fn wide_range() -> impl Strategy<Value = f64> {
        (-1.0..1.0f64, -500i32..500).prop_map(|(m, k)| m * 2f64.powi(k))
    }

    #[test]
    fn integers_add_sub_mul_like_i128() {
        // Small integers are exact in f64 and their sums/products exact in i128,
        // so the expected values are computed independently of BigFloat.
        let values: [i64; 9] = [0, 1, -1, 3, -7, 1 << 40, -(1 << 52), 123_456_789, -987_654_321];
        for &a in &values {
            for &b in &values {
                let (x, y) = (bf(a as f64), bf(b as f64));
                let cases = [
                    (&x + &y, i128::from(a) + i128::from(b), "sum"),
                    (&x - &y, i128::from(a) - i128::from(b), "difference"),
                    (&x * &y, i128::from(a) * i128::from(b), "product"),
                ];
                for (got, want, what) in cases {
                    // Compare via an exact difference against the i128 split into
                    // two f64-exact parts: |want| ≤ 2^104, so want >> 52 has at
                    // most 53 bits and the low part 52.
                    let hi = (want >> 52) as f64 * 4_503_599_627_370_496.0; // · 2^52
                    let lo = (want & ((1 << 52) - 1)) as f64;
                    let residual = &(&got - &bf(hi)) - &bf(lo);
                    assert!(residual.is_zero(), "{what} of {a} and {b}: residual {residual:?}");
                }
            }
        }
    }

    #[test]
    fn subnormal_and_extreme_values_round_trip() {
        for x in
            [f64::MIN_POSITIVE, f64::MIN_POSITIVE / 4096.0, 5e-324, -5e-324, f64::MAX, f64::MIN, 1e300, -1e-300, 0.1]
        {
            let e = bf(x).estimate();
            assert!(e.to_f64().to_bits() == x.to_bits(), "{x:e} became {e:?}");
        }
        assert!(BigFloat::try_from_f64(f64::NAN).is_none(), "NaN has no exact value");
        assert!(BigFloat::try_from_f64(f64::INFINITY).is_none(), "∞ has no exact value");
        assert!(bf(-0.0).sign() == Sign::Zero, "−0 is zero");
    }

    #[test]
    fn huge_times_tiny_cancels_exactly() {
        // MAX · 5e-324 − (MAX · 5e-324) is zero, and (MAX + 5e-324) − MAX is the
        // smallest subnormal: both need ~2100 bits of alignment.
        let big = bf(f64::MAX);
        let tiny = bf(5e-324);
        let sum = &big + &tiny;
        let back = &sum - &big;
        assert!((&back - &tiny).is_zero(), "MAX + tiny − MAX must be tiny");
        assert!(back.sign() == Sign::Positive, "tiny is positive");
        let p = &big * &tiny;
        assert!((&p - &(&tiny * &big)).is_zero(), "products commute");
        assert!(&(&p * &p) - &(&p * &p) == BigFloat::ZERO, "x − x is zero");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        #[test]
        fn product_matches_two_product(a in -1e100..1e100f64, b in -1e100..1e100f64) {
            // In this range a·b neither overflows nor underflows, so
            // a·b = hi + lo exactly with hi = fl(a·b), lo = fma(a, b, −hi).
            let hi = a * b;
            let lo = a.mul_add(b, -hi);
            let residual = &(&(&bf(a) * &bf(b)) - &bf(hi)) - &bf(lo);
            prop_assert!(residual.is_zero(), "a·b ≠ hi + lo for {a:e}, {b:e}");
        }

        #[test]
        fn sum_matches_two_sum(a in any_finite(), b in any_finite()) {
            // Knuth's TwoSum: a + b = s + err exactly when s does not overflow.
            let s = a + b;
            prop_assume!(s.is_finite());
            let bb = s - a;
            let err = (a - (s - bb)) + (b - bb);
            let residual = &(&(&bf(a) + &bf(b)) - &bf(s)) - &bf(err);
            prop_assert!(residual.is_zero(), "a + b ≠ s + err for {a:e}, {b:e}");
        }

        #[test]
        fn sign_of_difference_matches_comparison(a in any_finite(), b in any_finite()) {
            let want = a.partial_cmp(&b).expect("finite values compare");
            prop_assert_eq!(bf(a).cmp_value(&bf(b)), want);
        }

        #[test]
        fn ring_identities_hold(a in any_finite(), b in any_finite(), c in any_finite()) {
            let (x, y, z) = (bf(a), bf(b), bf(c));
            let lhs = &x * &(&y + &z);
            let rhs = &(&x * &y) + &(&x * &z);
            prop_assert!(lhs == rhs, "distributivity");
            prop_assert!(&(&x + &y) - &y == x, "(x + y) − y = x");
            prop_assert!(-&(&x * &y) == &(-&x) * &y, "−(xy) = (−x)y");
        }

        #[test]
        fn estimate_is_within_its_bound(a in wide_range(), b in wide_range()) {
            // The estimate of a·b against hi + lo (when both are representable):
            // |est − ab| ≤ 2^−52 |ab| is a loose form of the documented bound.
            const REL: f64 = 2.220446049250313e-16; // 2^−52, relative
            let p = &bf(a) * &bf(b);
            let e = p.estimate();
            let hi = a * b;
            prop_assume!(hi.abs() >= f64::MIN_POSITIVE);
            let err = (e.to_f64() - hi).abs();
            prop_assert!(err <= REL * hi.abs(), "estimate {e:?} of {hi:e}");
        }
    }
}
