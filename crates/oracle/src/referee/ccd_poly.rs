//! Exact polynomials in time for the continuous collision referee ([`super::ccd`]):
//! dyadic numbers, integer polynomials, their real roots isolated exactly, the
//! sign of a polynomial at such a root, the order of two roots, and a root's
//! correctly rounded `f64`.
//!
//! Every input is a dyadic rational (`m·2^e`), so every polynomial the referee
//! builds from the inputs (products of differences of coordinates moving
//! linearly in `t`) has dyadic coefficients; scaled by a power of two it has
//! integer ones. Nothing here needs a general rational: a polynomial is a
//! vector of big integers (its value's sign is all that is ever asked, so any
//! positive scaling is harmless), and every point it is evaluated at is
//! dyadic — a double, or the exact midpoint between two adjacent doubles (a
//! rounding boundary), or the midpoint of two such.
//!
//! **Roots.** A square-free polynomial's real roots in a closed interval are
//! isolated by its Sturm sequence (pseudo-remainders, kept primitive) and
//! bisection; a root is either a dyadic number exactly (the polynomial
//! vanished at a bisection point) or the only root of the polynomial in an
//! open interval whose ends it does not vanish at. Bisection first splits the
//! *doubles* between the ends in half (a split point is a double), so an
//! interval reaches two adjacent doubles in at most 64 steps at any magnitude,
//! then halves the interval.
//!
//! **Signs at a root.** The root's interval is first narrowed to a few
//! doubles around a floating-point estimate of the root, kept only when the
//! exact signs of `q` at its ends confirm it. Then `h`'s sign is settled on
//! the whole interval when `h(lo + w·s) = c₀ + c₁s + …` (`w` its width) has
//! `|c₀| > Σ|cₖ|`; the interval is halved until it is. After a few halvings
//! a zero is looked for: `h(r) = 0` exactly when `gcd(q, h)` vanishes at `r`,
//! and since that gcd divides the square-free `q`, whose only root in the
//! interval is `r`, that is a sign change of the gcd across the interval. (A
//! non-zero `h(r)` is always settled by halving: the `cₖ`, `k ≥ 1`, vanish
//! with `w`.)
//!
//! **Rounding.** The first root's `f64` is found by bisection over the doubles'
//! bit patterns (non-negative doubles are ordered as their bits): each step
//! compares the root with the exact midpoint between two adjacent doubles, a
//! sign of the polynomial at a dyadic point; a root on a midpoint is a tie,
//! and goes to the even double.

use std::cmp::Ordering;
use std::rc::Rc;

use dashu::base::{BitTest, Gcd, Sign, UnsignedAbs};
use dashu::integer::{IBig, UBig};
use dashu::rational::Relaxed;

/// `m·2^e`, exactly.
#[derive(Clone, Debug)]
pub(super) struct D {
    m: IBig,
    e: i64,
}

impl D {
    pub(super) fn zero() -> D {
        D { m: IBig::ZERO, e: 0 }
    }

    /// The exact value of a finite `x` (0 for ±0).
    pub(super) fn of(x: f64) -> D {
        let (mant, e, negative) = super::dyadic::parts(x);
        let m = IBig::from(mant);
        D { m: if negative { -m } else { m }, e }.norm()
    }

    /// The same value with an odd `m` (or `0·2^0`).
    fn norm(self) -> D {
        match self.m.trailing_zeros() {
            None => D::zero(),
            Some(0) => self,
            Some(k) => D { m: self.m >> k, e: self.e + k as i64 },
        }
    }

    fn aligned(&self, e: i64) -> IBig {
        // e ≤ self.e: exact.
        &self.m << (self.e - e) as usize
    }

    pub(super) fn add(&self, o: &D) -> D {
        if self.m.is_zero() {
            return o.clone();
        }
        if o.m.is_zero() {
            return self.clone();
        }
        let e = self.e.min(o.e);
        D { m: self.aligned(e) + o.aligned(e), e }.norm()
    }

    pub(super) fn neg(&self) -> D {
        D { m: -&self.m, e: self.e }
    }

    pub(super) fn sub(&self, o: &D) -> D {
        self.add(&o.neg())
    }

    pub(super) fn mul(&self, o: &D) -> D {
        D { m: &self.m * &o.m, e: self.e + o.e }.norm()
    }

    fn abs(&self) -> D {
        if self.sign() < 0 { self.neg() } else { self.clone() }
    }

    pub(super) fn sign(&self) -> i8 {
        sign(&self.m)
    }

    fn cmp(&self, o: &D) -> Ordering {
        self.sub(o).sign().cmp(&0)
    }

    /// `(self + o)/2`, exactly.
    fn mid(&self, o: &D) -> D {
        let s = self.add(o);
        D { m: s.m, e: s.e - 1 }.norm()
    }

    /// The bits of the largest double `≤ self`, for `0 ≤ self ≤ f64::MAX`
    /// (truncating the significand to 53 bits, or to a multiple of `2^-1074`
    /// below the normal range: both round down).
    fn floor_bits(&self) -> u64 {
        if self.m.is_zero() {
            return 0;
        }
        let len = (&self.m).unsigned_abs().bit_len() as i64;
        // Keep 53 bits, or fewer where the double's last bit is 2^-1074.
        let e = (self.e + len - 53).max(-1074);
        let m = if e >= self.e { &self.m >> (e - self.e) as usize } else { &self.m << (self.e - e) as usize };
        let m = u64::try_from(m).unwrap_or(u64::MAX >> 11);
        // m·2^e exactly: m < 2^53 and the scaling is exact (a power of two in
        // two steps when e is below the normal range).
        let pow2 = |k: i64| f64::from_bits(((k.clamp(-1022, 1023) + 1023) as u64) << 52);
        let x = m as f64 * pow2(e + 60) * pow2(-60);
        x.to_bits()
    }

    /// The value correctly rounded to `f64` (nearest, ties to even).
    pub(super) fn round(&self) -> f64 {
        let (num, den) = if self.e >= 0 {
            (&self.m << self.e as usize, IBig::ONE)
        } else {
            (self.m.clone(), IBig::ONE << (-self.e) as usize)
        };
        super::exact::round_relaxed(&Relaxed::from_parts_signed(num, den))
    }
}

fn sign(x: &IBig) -> i8 {
    if x.is_zero() {
        0
    } else if x.sign() == Sign::Negative {
        -1
    } else {
        1
    }
}

/// A polynomial with dyadic coefficients, lowest degree first.
pub(super) type DPoly = Vec<D>;

fn trim_d(mut p: DPoly) -> DPoly {
    while p.last().is_some_and(|c| c.sign() == 0) {
        p.pop();
    }
    p
}

/// `x0 + t·(x1 − x0)`: a coordinate moving from `x0` (t = 0) to `x1` (t = 1).
pub(super) fn moving(x0: f64, x1: f64) -> DPoly {
    let a = D::of(x0);
    let b = D::of(x1).sub(&a);
    trim_d(vec![a, b])
}

pub(super) fn padd(a: &[D], b: &[D]) -> DPoly {
    let n = a.len().max(b.len());
    let z = D::zero();
    trim_d((0..n).map(|i| a.get(i).unwrap_or(&z).add(b.get(i).unwrap_or(&z))).collect())
}

pub(super) fn psub(a: &[D], b: &[D]) -> DPoly {
    let n = a.len().max(b.len());
    let z = D::zero();
    trim_d((0..n).map(|i| a.get(i).unwrap_or(&z).sub(b.get(i).unwrap_or(&z))).collect())
}

pub(super) fn pmul(a: &[D], b: &[D]) -> DPoly {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![D::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] = out[i + j].add(&x.mul(y));
        }
    }
    trim_d(out)
}

/// An integer polynomial, lowest degree first, without leading zeros (the
/// zero polynomial is empty).
pub(super) type IPoly = Vec<IBig>;

fn trim(mut p: IPoly) -> IPoly {
    while p.last().is_some_and(IBig::is_zero) {
        p.pop();
    }
    p
}

fn degree(p: &[IBig]) -> usize {
    p.len().saturating_sub(1)
}

/// `p` divided by the (positive) gcd of its coefficients.
fn primitive(p: IPoly) -> IPoly {
    let p = trim(p);
    let mut g = UBig::ZERO;
    for c in p.iter().filter(|c| !c.is_zero()) {
        g = (&g).gcd(c);
        if g == UBig::ONE {
            return p;
        }
    }
    if g.is_zero() {
        return p;
    }
    let g = IBig::from(g);
    p.into_iter().map(|c| c / &g).collect()
}

/// `p` times a positive power of two, with integer coefficients: the same
/// signs everywhere. (Not made primitive: the gcd of the coefficients costs
/// more than it saves where only signs are asked.)
pub(super) fn integer(p: &[D]) -> IPoly {
    let Some(e) = p.iter().filter(|c| c.sign() != 0).map(|c| c.e).min() else {
        return Vec::new();
    };
    trim(p.iter().map(|c| if c.sign() == 0 { IBig::ZERO } else { c.aligned(e) }).collect())
}

/// The sign of `p(x)`.
pub(super) fn sign_at_point(p: &[IBig], x: &D) -> i8 {
    let Some((top, rest)) = p.split_last() else {
        return 0;
    };
    if x.m.is_zero() {
        return sign(&p[0]);
    }
    let mut acc = top.clone();
    if x.e >= 0 {
        let xi = &x.m << x.e as usize;
        for c in rest.iter().rev() {
            acc = acc * &xi + c;
        }
    } else {
        // p(m/2^s)·2^(s·d) = Σ cᵢ mⁱ 2^(s(d−i)) (d the degree), by Horner.
        let s = (-x.e) as usize;
        for (k, c) in rest.iter().rev().enumerate() {
            acc = acc * &x.m + (c << (s * (k + 1)));
        }
    }
    sign(&acc)
}

fn derivative(p: &[IBig]) -> IPoly {
    trim(p.iter().enumerate().skip(1).map(|(i, c)| c * IBig::from(i)).collect())
}

/// Pseudo-division of `a` by a non-zero `b`: `(quotient, remainder, l^k)`'s
/// sign, with `l^k·a = quotient·b + remainder`, `l = lc(b)`.
fn pdiv(a: &[IBig], b: &[IBig]) -> (IPoly, IPoly, i8) {
    let db = degree(b);
    let l = b[db].clone();
    let mut r = a.to_vec();
    let mut q = vec![IBig::ZERO; a.len().saturating_sub(db).max(1)];
    let mut k = 0u32;
    while !r.is_empty() && r.len() >= b.len() {
        let shift = r.len() - b.len();
        let c = r.last().cloned().unwrap_or(IBig::ZERO);
        for x in q.iter_mut() {
            *x *= &l;
        }
        q[shift] += &c;
        for x in r.iter_mut() {
            *x *= &l;
        }
        for (j, y) in b.iter().enumerate() {
            r[j + shift] -= &c * y;
        }
        r.pop();
        r = trim(r);
        k += 1;
    }
    let s = if sign(&l) < 0 && !k.is_multiple_of(2) { -1 } else { 1 };
    (trim(q), r, s)
}

/// The gcd of two polynomials (up to a constant factor), primitive.
pub(super) fn gcd(a: &[IBig], b: &[IBig]) -> IPoly {
    let (mut a, mut b) = if a.len() >= b.len() { (a.to_vec(), b.to_vec()) } else { (b.to_vec(), a.to_vec()) };
    while !b.is_empty() {
        let (_, r, _) = pdiv(&a, &b);
        a = b;
        b = primitive(r);
    }
    primitive(a)
}

/// The square-free part of a non-zero `p` (the same roots, each simple).
pub(super) fn square_free(p: &[IBig]) -> IPoly {
    let g = gcd(p, &derivative(p));
    if g.len() <= 1 {
        return p.to_vec();
    }
    primitive(pdiv(p, &g).0)
}

/// The Sturm sequence of a square-free `q` of degree ≥ 1.
fn sturm(q: &[IBig]) -> Vec<IPoly> {
    let mut seq = vec![q.to_vec(), primitive(derivative(q))];
    loop {
        let n = seq.len();
        if seq[n - 1].len() <= 1 {
            break;
        }
        let (_, r, s) = pdiv(&seq[n - 2], &seq[n - 1]);
        if r.is_empty() {
            break;
        }
        // −rem(a, b) up to a positive factor: the remainder is r/(l^k), of sign s·r.
        let next = if s > 0 { r.into_iter().map(|c| -c).collect() } else { r };
        seq.push(primitive(next));
    }
    seq
}

/// Sign variations of the Sturm sequence at `x` (zeros skipped).
fn variations(seq: &[IPoly], x: &D) -> usize {
    let mut last = 0i8;
    let mut v = 0;
    for p in seq {
        let s = sign_at_point(p, x);
        if s != 0 {
            if last != 0 && s != last {
                v += 1;
            }
            last = s;
        }
    }
    v
}

/// A point strictly between non-negative `lo < hi`: a double halfway between
/// them in the order of the doubles while there is one at least two doubles
/// from either end, else their midpoint.
fn split(lo: &D, hi: &D) -> D {
    let kl = lo.floor_bits();
    let kh = hi.floor_bits();
    if kh >= kl + 2 {
        // Strictly inside: at least the double after RD(lo) (> lo), at most
        // the one before RD(hi) (< hi).
        return D::of(f64::from_bits(kl + (kh - kl) / 2));
    }
    lo.mid(hi)
}

/// How many times a root's interval is halved, looking for the sign of a
/// polynomial there, before the gcd that detects a zero is computed.
const HALVINGS_BEFORE_GCD: usize = 8;

/// A real root of a square-free integer polynomial, exactly: `exact` (then
/// `lo = hi` is its value), or the only root of `q` in `(lo, hi)`, where `q`
/// does not vanish at either end (`q(lo)` has the sign `s_lo`).
#[derive(Clone, Debug)]
pub(super) struct Root {
    q: Rc<IPoly>,
    lo: D,
    hi: D,
    exact: bool,
    s_lo: i8,
    /// Whether [`Root::tighten`] ran.
    tight: bool,
}

impl Root {
    fn at(q: &Rc<IPoly>, x: D) -> Root {
        Root { q: Rc::clone(q), hi: x.clone(), lo: x, exact: true, s_lo: 0, tight: true }
    }

    /// The root `0` (of `t`).
    pub(super) fn zero() -> Root {
        Root::at(&Rc::new(vec![IBig::ZERO, IBig::ONE]), D::zero())
    }

    /// Halves the interval (in the doubles' order first).
    fn refine(&mut self) {
        if self.exact {
            return;
        }
        let m = split(&self.lo, &self.hi);
        match sign_at_point(&self.q, &m) {
            0 => {
                self.lo = m.clone();
                self.hi = m;
                self.exact = true;
            }
            s if s == self.s_lo => self.lo = m,
            _ => self.hi = m,
        }
    }

    /// Narrows the interval, once, to a few doubles around a floating-point
    /// estimate of the root, when the exact signs of `q` there confirm it
    /// (two evaluations instead of dozens of halvings); otherwise leaves it.
    fn tighten(&mut self) {
        if self.exact || self.tight {
            return;
        }
        self.tight = true;
        let Some(d) = self.estimate() else {
            return;
        };
        for ulps in [2, 1 << 20] {
            let below = D::of(f64::from_bits(d.to_bits().saturating_sub(ulps)));
            let above = D::of(f64::from_bits(d.to_bits() + ulps));
            let lo = if below.cmp(&self.lo) == Ordering::Greater { below } else { self.lo.clone() };
            let hi = if above.cmp(&self.hi) == Ordering::Less { above } else { self.hi.clone() };
            let (s_lo, s_hi) = (sign_at_point(&self.q, &lo), sign_at_point(&self.q, &hi));
            if s_lo == self.s_lo && s_hi == -self.s_lo {
                self.lo = lo;
                self.hi = hi;
                return;
            }
        }
    }

    /// A floating-point estimate of the root: bisection over the doubles
    /// of `[lo, hi]` with `q` evaluated in `f64` (its coefficients scaled by a
    /// power of two so that the largest is near `2^900`). Only a guess: the
    /// caller checks it exactly.
    fn estimate(&self) -> Option<f64> {
        let bits = self.q.iter().map(|c| c.unsigned_abs().bit_len()).max()?;
        let shift = bits.saturating_sub(900);
        let c: Vec<f64> = self.q.iter().map(|c| (c >> shift).to_f64().value()).collect();
        let value = |t: f64| c.iter().rev().fold(0.0, |acc, &x| acc * t + x);
        let (mut a, mut b) = (self.lo.floor_bits(), self.hi.floor_bits() + 1);
        if f64::from_bits(b) > 1.0 {
            b = 1f64.to_bits();
        }
        while b > a + 1 {
            let m = a + (b - a) / 2;
            let v = value(f64::from_bits(m));
            if !v.is_finite() {
                return None;
            }
            if (v > 0.0) == (self.s_lo > 0) && v != 0.0 {
                a = m;
            } else {
                b = m;
            }
        }
        Some(f64::from_bits(a))
    }

    /// `x` against the root.
    fn cmp_point(&self, x: &D) -> Ordering {
        if self.exact {
            return x.cmp(&self.lo);
        }
        if x.cmp(&self.lo) != Ordering::Greater {
            return Ordering::Less;
        }
        if x.cmp(&self.hi) != Ordering::Less {
            return Ordering::Greater;
        }
        match sign_at_point(&self.q, x) {
            0 => Ordering::Equal,
            s if s == self.s_lo => Ordering::Less,
            _ => Ordering::Greater,
        }
    }

    /// The sign of `h` at the root, exactly.
    pub(super) fn sign_of(&mut self, h: &[IBig]) -> i8 {
        if h.is_empty() {
            return 0;
        }
        if self.exact {
            return sign_at_point(h, &self.lo);
        }
        self.tighten();
        if self.exact {
            return sign_at_point(h, &self.lo);
        }
        // A sign that a few halvings settle needs no gcd (the common case);
        // after them, a zero is ruled in or out by the gcd.
        let mut step = 0;
        loop {
            if let Some(s) = certain_sign(h, &self.lo, &self.hi) {
                return s;
            }
            step += 1;
            if step == HALVINGS_BEFORE_GCD {
                let g = gcd(&self.q, h);
                if g.len() > 1 && sign_at_point(&g, &self.lo) != sign_at_point(&g, &self.hi) {
                    return 0;
                }
            }
            self.refine();
            if self.exact {
                return sign_at_point(h, &self.lo);
            }
        }
    }

    /// The root against another, exactly.
    pub(super) fn cmp(&mut self, o: &mut Root) -> Ordering {
        if self.exact {
            return o.cmp_point(&self.lo);
        }
        if o.exact {
            return self.cmp_point(&o.lo).reverse();
        }
        let g = gcd(&self.q, &o.q);
        let vanishes = |r: &Root| sign_at_point(&g, &r.lo) != sign_at_point(&g, &r.hi);
        let common = g.len() > 1 && vanishes(self) && vanishes(o);
        loop {
            if self.exact {
                return o.cmp_point(&self.lo);
            }
            if o.exact {
                return self.cmp_point(&o.lo).reverse();
            }
            if self.hi.cmp(&o.lo) != Ordering::Greater {
                return Ordering::Less;
            }
            if o.hi.cmp(&self.lo) != Ordering::Greater {
                return Ordering::Greater;
            }
            // Both roots of g, one's interval inside the other's, which holds
            // only one root of g: the same number.
            let inside = |a: &Root, b: &Root| a.lo.cmp(&b.lo) != Ordering::Less && a.hi.cmp(&b.hi) != Ordering::Greater;
            if common && (inside(self, o) || inside(o, self)) {
                return Ordering::Equal;
            }
            if self.hi.sub(&self.lo).cmp(&o.hi.sub(&o.lo)) == Ordering::Greater {
                self.refine();
            } else {
                o.refine();
            }
        }
    }

    /// The root correctly rounded to `f64` (nearest, ties to even); the
    /// root is in `[0, 1]`.
    pub(super) fn round(&mut self) -> f64 {
        self.tighten();
        if self.exact {
            return self.lo.round();
        }
        let (mut kl, mut kh) = (self.lo.round().to_bits(), self.hi.round().to_bits());
        while kl < kh {
            let m = kl + (kh - kl) / 2;
            // The exact midpoint between the doubles m and m + 1.
            let boundary = D::of(f64::from_bits(m)).mid(&D::of(f64::from_bits(m + 1)));
            match self.cmp_point(&boundary) {
                Ordering::Equal => return f64::from_bits(if m.is_multiple_of(2) { m } else { m + 1 }),
                Ordering::Less => kl = m + 1,
                Ordering::Greater => kh = m,
            }
        }
        f64::from_bits(kl)
    }
}

/// `h`'s sign on all of `[lo, hi]` when `h(lo + w·s) = Σ cₖ sᵏ` (`w = hi − lo`,
/// `s ∈ [0, 1]`) has `|c₀| > Σₖ₌₁ |cₖ|`.
fn certain_sign(h: &[IBig], lo: &D, hi: &D) -> Option<i8> {
    let w = hi.sub(lo);
    let line = [lo.clone(), w];
    let mut acc: DPoly = Vec::new();
    for c in h.iter().rev() {
        acc = padd(&pmul(&acc, &line), &[D { m: c.clone(), e: 0 }.norm()]);
    }
    let c0 = acc.first().cloned().unwrap_or_else(D::zero);
    let rest = acc.iter().skip(1).fold(D::zero(), |s, c| s.add(&c.abs()));
    (c0.abs().cmp(&rest) == Ordering::Greater).then(|| c0.sign())
}

/// The real roots of a non-zero `p` in `[lo, hi]` (`0 ≤ lo ≤ hi`), each once,
/// in increasing order.
pub(super) fn roots(p: &[IBig], lo: &D, hi: &D) -> Vec<Root> {
    if p.len() <= 1 {
        return Vec::new();
    }
    let q = Rc::new(square_free(p));
    let mut out = Vec::new();
    if sign_at_point(&q, lo) == 0 {
        out.push(Root::at(&q, lo.clone()));
    }
    if lo.cmp(hi) != Ordering::Less {
        return out;
    }
    let seq = sturm(&q);
    let at_hi = sign_at_point(&q, hi) == 0;
    let count = variations(&seq, lo) - variations(&seq, hi) - usize::from(at_hi);
    isolate(&q, &seq, lo.clone(), hi.clone(), count, &mut out);
    if at_hi {
        out.push(Root::at(&q, hi.clone()));
    }
    out
}

/// The `count` roots of `q` in the open `(lo, hi)`, in order.
fn isolate(q: &Rc<IPoly>, seq: &[IPoly], lo: D, hi: D, count: usize, out: &mut Vec<Root>) {
    if count == 0 {
        return;
    }
    let (s_lo, s_hi) = (sign_at_point(q, &lo), sign_at_point(q, &hi));
    if count == 1 && s_lo != 0 && s_hi != 0 {
        out.push(Root { q: Rc::clone(q), lo, hi, exact: false, s_lo, tight: false });
        return;
    }
    let m = split(&lo, &hi);
    let vm = variations(seq, &m);
    let left = variations(seq, &lo) - vm;
    if sign_at_point(q, &m) == 0 {
        // The root at m is counted in (lo, m].
        isolate(q, seq, lo, m.clone(), left - 1, out);
        out.push(Root::at(q, m.clone()));
        isolate(q, seq, m, hi, count - left, out);
    } else {
        isolate(q, seq, lo, m.clone(), left, out);
        isolate(q, seq, m, hi, count - left, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ip(c: &[i64]) -> IPoly {
        trim(c.iter().map(|&x| IBig::from(x)).collect())
    }

    #[test]
    fn roots_of_a_cubic_with_a_double_root_and_a_root_on_a_split_point() {
        // (t − 1/2)²(t − 3/4)·64 = (4t² − 4t + 1)(16t − 12)·... : roots 1/2 (double), 3/4.
        // (2t − 1)²(4t − 3) = (4t² − 4t + 1)(4t − 3) = 16t³ − 28t² + 16t − 3.
        let p = ip(&[-3, 16, -28, 16]);
        let mut r = roots(&p, &D::zero(), &D::of(1.0));
        assert_eq!(r.len(), 2);
        // 1/2 and 3/4 are doubles: each root is exactly representable.
        assert_eq!(r[0].round().to_bits(), 0.5f64.to_bits());
        assert_eq!(r[1].round().to_bits(), 0.75f64.to_bits());
    }

    #[test]
    fn an_irrational_root_rounds_between_its_neighbours() {
        // 2t² − 1: root 1/√2. The rounded root d must have 2d² − 1 change sign
        // between the midpoints around d (checked exactly, in dyadics).
        let p = ip(&[-1, 0, 2]);
        let mut r = roots(&p, &D::zero(), &D::of(1.0));
        assert_eq!(r.len(), 1);
        let d = r[0].round();
        let below = D::of(d).mid(&D::of(d.next_down()));
        let above = D::of(d).mid(&D::of(d.next_up()));
        assert_eq!(sign_at_point(&p, &below), -1);
        assert_eq!(sign_at_point(&p, &above), 1);
    }

    #[test]
    fn signs_at_a_root_and_comparison_of_equal_roots() {
        // r = 1/√2 as a root of 2t² − 1 and of (2t² − 1)(t + 1).
        let p = ip(&[-1, 0, 2]);
        let q = ip(&[-1, -1, 2, 2]);
        let mut a = roots(&p, &D::zero(), &D::of(1.0)).remove(0);
        let mut b = roots(&q, &D::zero(), &D::of(1.0)).remove(0);
        assert_eq!(a.cmp(&mut b), Ordering::Equal);
        // h = 10t − 7 > 0 at 0.7071…; h = 5t − 4 < 0; h = 2t² − 1 = 0.
        assert_eq!(a.sign_of(&ip(&[-7, 10])), 1);
        assert_eq!(a.sign_of(&ip(&[-4, 5])), -1);
        assert_eq!(a.sign_of(&ip(&[-1, 0, 2])), 0);
        let mut c = roots(&ip(&[-7, 10]), &D::zero(), &D::of(1.0)).remove(0);
        assert_eq!(c.cmp(&mut a), Ordering::Less);
    }
}
