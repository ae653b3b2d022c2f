//! Exact evaluation without allocation: floating-point expansions (Priest;
//! Shewchuk, *Adaptive Precision Floating-Point Arithmetic and Fast Robust
//! Geometric Predicates*, 1997, §2), on the stack.
//!
//! A value is held as a sum of `f64` components, nonoverlapping and in
//! increasing magnitude, with zeros eliminated; `+`, `−` and `×` on such sums
//! are exact as long as nothing overflows and no product's rounding error
//! underflows. The predicates' exact path uses them when every non-zero input
//! lies in `[2^−200, 2^200]` in magnitude ([`in_expansion_range`]): then every
//! value involved is a multiple of `2^(3·(−200 − 52)) = 2^−756` (the
//! predicates are of degree ≤ 3 in the inputs), so every product's error term
//! is a multiple of `2^−862` — representable, far above the subnormals — and no
//! component exceeds `2^603`, far below overflow (and below `2^996`, where
//! Dekker's split would overflow). Outside that range the predicates use
//! [`BigFloat`](super::BigFloat), as before.
//!
//! Cost: for inputs whose differences are exact (the usual case for a value
//! too close to zero for the filter: a point exactly on a plane, through an
//! edge) every expansion stays a few components long, a few hundred `f64`
//! operations in all; at worst (a 192-component orient3d) a few thousand —
//! against BigFloat's allocations, 10 to 100 times slower.
//!
//! The algorithms (`two_sum`, `two_product` by Dekker's split,
//! `fast_expansion_sum_zeroelim`, `scale_expansion_zeroelim`, `compress`) are
//! Shewchuk's, as in his public-domain `predicates.c`; they assume IEEE 754
//! binary64 with round-to-nearest-even, which Rust's `f64` arithmetic is.

use super::estimate::{EXACT_REL_ERR, Estimate};

/// Dekker's splitter `2^27 + 1`: `split` cuts a 53-bit significand into two
/// halves of 26 bits each, so their products are exact.
const SPLITTER: f64 = 134_217_729.0;

/// Smallest non-zero input magnitude of the expansion path (2^−200).
const RANGE_MIN: f64 = 6.223015277861142e-61;
/// Largest input magnitude of the expansion path (2^200).
const RANGE_MAX: f64 = 1.6069380442589903e60;

/// Whether every value is zero or of magnitude in `[2^−200, 2^200]` (false for
/// infinities and NaN): the inputs for which the expansion arithmetic of this
/// module is exact (see the module documentation).
pub(crate) fn in_expansion_range<'a>(values: impl IntoIterator<Item = &'a f64>) -> bool {
    values.into_iter().all(|&x| x == 0.0 || (RANGE_MIN..=RANGE_MAX).contains(&x.abs()))
}

#[inline(always)]
pub(super) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let bvirt = x - a;
    let avirt = x - bvirt;
    (x, (a - avirt) + (b - bvirt))
}

#[inline(always)]
fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    (x, b - (x - a))
}

#[inline(always)]
pub(super) fn two_diff(a: f64, b: f64) -> (f64, f64) {
    let x = a - b;
    let bvirt = a - x;
    let avirt = x + bvirt;
    (x, (a - avirt) + (bvirt - b))
}

#[inline(always)]
pub(super) fn split(a: f64) -> (f64, f64) {
    let c = SPLITTER * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

#[inline(always)]
pub(super) fn two_product_presplit(a: f64, b: f64, bhi: f64, blo: f64) -> (f64, f64) {
    let x = a * b;
    let (ahi, alo) = split(a);
    let err1 = x - ahi * bhi;
    let err2 = err1 - alo * bhi;
    let err3 = err2 - ahi * blo;
    (x, alo * blo - err3)
}

/// An exact value: `len` nonoverlapping components in increasing magnitude,
/// zeros eliminated (zero itself is the single component `0`). `N` is the
/// capacity; every operation below states the capacity its result needs.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Expansion<const N: usize> {
    c: [f64; N],
    len: usize,
}

impl Expansion<2> {
    /// `a − b`, exactly.
    #[inline]
    pub(crate) fn diff(a: f64, b: f64) -> Self {
        let (x, y) = two_diff(a, b);
        Self::from_pair(x, y)
    }

    /// A single value.
    #[inline]
    pub(crate) fn single(a: f64) -> Self {
        Self { c: [a, 0.0], len: 1 }
    }

    /// `hi + lo` for a pair from `two_diff` or `two_product` (`lo` is the
    /// smaller, nonoverlapping), zero eliminated.
    #[inline]
    fn from_pair(hi: f64, lo: f64) -> Self {
        if lo == 0.0 { Self { c: [hi, 0.0], len: 1 } } else { Self { c: [lo, hi], len: 2 } }
    }
}

impl<const N: usize> Expansion<N> {
    const ZERO: Self = Self { c: [0.0; N], len: 1 };

    fn components(&self) -> &[f64] {
        &self.c[..self.len]
    }

    fn push(&mut self, x: f64) {
        self.c[self.len] = x;
        self.len += 1;
    }

    /// `−self`.
    pub(crate) fn neg(mut self) -> Self {
        for x in &mut self.c[..self.len] {
            *x = -*x;
        }
        self
    }

    /// `self + other` (Shewchuk's `fast_expansion_sum_zeroelim`); the result's
    /// capacity `K` must be at least `N + M`.
    pub(crate) fn add<const M: usize, const K: usize>(&self, other: &Expansion<M>) -> Expansion<K> {
        let (e, f) = (self.components(), other.components());
        let mut h = Expansion::<K> { c: [0.0; K], len: 0 };
        let (mut ei, mut fi) = (0, 0);
        // Take the smaller-magnitude head first.
        let take_e = |ei: usize, fi: usize| (f[fi] > e[ei]) == (f[fi] > -e[ei]);
        let mut q;
        if take_e(ei, fi) {
            q = e[ei];
            ei += 1;
        } else {
            q = f[fi];
            fi += 1;
        }
        if ei < e.len() && fi < f.len() {
            let (qn, hh) = if take_e(ei, fi) {
                ei += 1;
                fast_two_sum(e[ei - 1], q)
            } else {
                fi += 1;
                fast_two_sum(f[fi - 1], q)
            };
            q = qn;
            if hh != 0.0 {
                h.push(hh);
            }
            while ei < e.len() && fi < f.len() {
                let (qn, hh) = if take_e(ei, fi) {
                    ei += 1;
                    two_sum(q, e[ei - 1])
                } else {
                    fi += 1;
                    two_sum(q, f[fi - 1])
                };
                q = qn;
                if hh != 0.0 {
                    h.push(hh);
                }
            }
        }
        for &x in e[ei..].iter().chain(&f[fi..]) {
            let (qn, hh) = two_sum(q, x);
            q = qn;
            if hh != 0.0 {
                h.push(hh);
            }
        }
        if q != 0.0 || h.len == 0 {
            h.push(q);
        }
        h
    }

    /// `self − other`; capacity `K ≥ N + M`.
    pub(crate) fn sub<const M: usize, const K: usize>(&self, other: &Expansion<M>) -> Expansion<K> {
        self.add(&other.neg())
    }

    /// `self · b` (Shewchuk's `scale_expansion_zeroelim`); capacity `K ≥ 2N`.
    pub(crate) fn scale<const K: usize>(&self, b: f64) -> Expansion<K> {
        let e = self.components();
        let mut h = Expansion::<K> { c: [0.0; K], len: 0 };
        let (bhi, blo) = split(b);
        let (mut q, hh) = two_product_presplit(e[0], b, bhi, blo);
        if hh != 0.0 {
            h.push(hh);
        }
        for &x in &e[1..] {
            let (p1, p0) = two_product_presplit(x, b, bhi, blo);
            let (sum, hh) = two_sum(q, p0);
            if hh != 0.0 {
                h.push(hh);
            }
            let (qn, hh) = fast_two_sum(p1, sum);
            q = qn;
            if hh != 0.0 {
                h.push(hh);
            }
        }
        if q != 0.0 || h.len == 0 {
            h.push(q);
        }
        h
    }

    /// `self · other`: the sum of `self` scaled by each component of
    /// `other`; capacity `K ≥ 2NM`.
    pub(crate) fn mul<const M: usize, const K: usize>(&self, other: &Expansion<M>) -> Expansion<K> {
        let mut acc = Expansion::<K>::ZERO;
        for &b in other.components() {
            let term: Expansion<K> = self.scale(b);
            acc = acc.add(&term);
        }
        acc
    }

    /// The exact sign: that of the largest component.
    #[cfg(test)]
    pub(crate) fn sign(&self) -> super::Sign {
        super::Sign::of(self.c[self.len - 1])
    }

    /// The value as an [`Estimate`] with relative error below
    /// [`EXACT_REL_ERR`]: Shewchuk's `compress` makes the expansion
    /// nonadjacent, so that everything below its two largest components is
    /// less than an ulp of the second; their rounded sum is then within half an
    /// ulp (plus that) of the value, `< 2^−53 (1 + 2^−50)` relative.
    pub(crate) fn estimate(&self) -> Estimate {
        let h = self.compress();
        let n = h.len;
        let top = if n >= 2 { h.c[n - 1] + h.c[n - 2] } else { h.c[0] };
        Estimate::from_scaled(top, 0, EXACT_REL_ERR)
    }

    /// Shewchuk's `compress`: the same value as a nonadjacent expansion.
    fn compress(&self) -> Self {
        let e = self.components();
        let m = e.len();
        let mut g = [0.0; N];
        let mut bottom = m - 1;
        let mut q = e[bottom];
        for &enow in e[..m - 1].iter().rev() {
            let (qn, qq) = fast_two_sum(q, enow);
            if qq != 0.0 {
                g[bottom] = qn;
                bottom -= 1;
                q = qq;
            } else {
                q = qn;
            }
        }
        g[bottom] = q;
        let mut h = Self { c: [0.0; N], len: 0 };
        for &gnow in &g[bottom + 1..m] {
            let (qn, qq) = fast_two_sum(gnow, q);
            if qq != 0.0 {
                h.push(qq);
            }
            q = qn;
        }
        h.push(q);
        h
    }
}

/// `det[a, b, c] = a · (b × c)` of three rows of exact differences
/// (192 components at most).
pub(crate) fn det3(a: [Expansion<2>; 3], b: [Expansion<2>; 3], c: [Expansion<2>; 3]) -> Expansion<192> {
    let minor = |i: usize, j: usize| -> Expansion<16> {
        let l: Expansion<8> = b[i].mul(&c[j]);
        let r: Expansion<8> = b[j].mul(&c[i]);
        l.sub(&r)
    };
    let t0: Expansion<64> = minor(1, 2).mul(&a[0]);
    let t1: Expansion<64> = minor(2, 0).mul(&a[1]);
    let t2: Expansion<64> = minor(0, 1).mul(&a[2]);
    let s: Expansion<128> = t0.add(&t1);
    s.add(&t2)
}

/// `(a0 b1 − a1 b0)` of two rows of exact differences (16 components at most).
pub(crate) fn det2(a: [Expansion<2>; 2], b: [Expansion<2>; 2]) -> Expansion<16> {
    let l: Expansion<8> = a[0].mul(&b[1]);
    let r: Expansion<8> = a[1].mul(&b[0]);
    l.sub(&r)
}

/// `Σ x_i y_i` of exact values (24 components at most).
pub(crate) fn dot3(x: [Expansion<2>; 3], y: [Expansion<2>; 3]) -> Expansion<24> {
    let p0: Expansion<8> = x[0].mul(&y[0]);
    let p1: Expansion<8> = x[1].mul(&y[1]);
    let p2: Expansion<8> = x[2].mul(&y[2]);
    let s: Expansion<16> = p0.add(&p1);
    s.add(&p2)
}

#[cfg(test)]
mod tests {
    use super::super::{BigFloat, Sign};
    use super::*;
    use proptest::prelude::*;

    fn big(e: &[f64]) -> BigFloat {
        e.iter().fold(BigFloat::ZERO, |acc, &x| &acc + &BigFloat::from_f64(x))
    }

    fn bf(x: f64) -> BigFloat {
        BigFloat::from_f64(x)
    }

    /// Coordinates in the expansion range with heavy cancellation: small
    /// integers, values near 1e15 a few ulps apart, and random binades.
    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![
            (-8i32..8).prop_map(f64::from),
            (-4i64..4).prop_map(|k| 1e15 + k as f64 * 0.125),
            (-1.0..1.0f64, -150i32..150).prop_map(|(m, e)| m * 2f64.powi(e)),
            (-1.0..1.0f64).prop_map(|x| 0.1 + x * 1e-16),
        ]
    }

    fn diffs(p: [f64; 3], q: [f64; 3]) -> [Expansion<2>; 3] {
        [0, 1, 2].map(|i| Expansion::diff(p[i], q[i]))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// det3 of exact differences equals the BigFloat determinant, in sign
        /// and (through the estimate) in value.
        #[test]
        fn det3_is_exact(p in proptest::array::uniform12(coord())) {
            let pt = |i: usize| [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
            let (a, b, c, d) = (pt(0), pt(1), pt(2), pt(3));
            prop_assume!(in_expansion_range(&p));
            let e = det3(diffs(a, d), diffs(b, d), diffs(c, d));
            let r = |x: [f64; 3]| [0, 1, 2].map(|i| &bf(x[i]) - &bf(d[i]));
            let (ra, rb, rc) = (r(a), r(b), r(c));
            let minor = |i: usize, j: usize| &(&rb[i] * &rc[j]) - &(&rb[j] * &rc[i]);
            let exact = &(&(&ra[0] * &minor(1, 2)) + &(&ra[1] * &minor(2, 0))) + &(&ra[2] * &minor(0, 1));
            prop_assert_eq!(e.sign(), exact.sign());
            prop_assert_eq!(big(e.components()).cmp_value(&exact), core::cmp::Ordering::Equal);
            let (got, want) = (e.estimate(), exact.estimate());
            prop_assert_eq!(got.sign, want.sign);
            if want.sign != Sign::Zero {
                // Both estimates are within EXACT_REL_ERR of the exact value
                // (BigFloat's within 2^−53 + 2^−127): twice that apart at most.
                let rel = (got.to_f64() - want.to_f64()).abs() / want.to_f64().abs();
                prop_assert!(rel <= 2.0 * EXACT_REL_ERR, "relative error {rel:e}");
            }
        }

        /// det2 and dot3 likewise.
        #[test]
        fn det2_and_dot3_are_exact(p in proptest::array::uniform12(coord())) {
            prop_assume!(in_expansion_range(&p));
            let x = [0, 1, 2].map(|i| Expansion::diff(p[i], p[i + 3]));
            let y = [0, 1, 2].map(|i| Expansion::diff(p[i + 6], p[i + 9]));
            let bx = [0, 1, 2].map(|i| &bf(p[i]) - &bf(p[i + 3]));
            let by = [0, 1, 2].map(|i| &bf(p[i + 6]) - &bf(p[i + 9]));
            let d2 = det2([x[0], x[1]], [y[0], y[1]]);
            let want2 = &(&bx[0] * &by[1]) - &(&bx[1] * &by[0]);
            prop_assert_eq!(big(d2.components()).cmp_value(&want2), core::cmp::Ordering::Equal);
            prop_assert_eq!(d2.sign(), want2.sign());
            let d3 = dot3(x, y);
            let want3 = &(&(&bx[0] * &by[0]) + &(&bx[1] * &by[1])) + &(&bx[2] * &by[2]);
            prop_assert_eq!(big(d3.components()).cmp_value(&want3), core::cmp::Ordering::Equal);
            prop_assert_eq!(d3.sign(), want3.sign());
        }
    }

    #[test]
    fn range_check() {
        assert!(in_expansion_range(&[0.0, 1.0, -1e60, 1e-60]));
        assert!(!in_expansion_range(&[1e61]));
        assert!(!in_expansion_range(&[1e-61]));
        assert!(!in_expansion_range(&[f64::NAN]));
        assert!(!in_expansion_range(&[f64::INFINITY]));
    }

    #[test]
    fn an_exact_zero_is_zero() {
        // (1,2,3)·(4,5,6) − 32 = 0, and 0.1 − 0.1 = 0.
        let d = dot3([1.0, 2.0, 3.0].map(Expansion::single), [4.0, 5.0, 6.0].map(Expansion::single));
        let z: Expansion<32> = d.sub(&Expansion::single(32.0));
        assert_eq!(z.sign(), Sign::Zero);
        assert_eq!(Expansion::diff(0.1, 0.1).sign(), Sign::Zero);
        assert_eq!(z.estimate(), Estimate::ZERO);
    }
}
