//! Exact univariate polynomials in the time `t`, with [`BigFloat`]
//! coefficients, and their real roots: the exact stage's arithmetic.
//!
//! Everything here is division-free. A polynomial's sign at a dyadic time is
//! exact (Horner's rule in [`BigFloat`]); greatest common divisors and
//! square-free parts come from pseudo-remainder sequences (each step multiplies
//! by a leading coefficient instead of dividing by it, which changes a
//! polynomial only by a non-zero constant factor, so roots are kept); roots
//! are isolated by subdivision with Descartes' rule of signs on the Bernstein
//! coefficients (Vincent's theorem: for a square-free polynomial the count of
//! sign variations on a small enough interval is 0 or 1).
//!
//! An isolated root is an interval `(lo, hi)` of dyadic endpoints on which a
//! square-free polynomial `q` changes sign and has exactly one root, or an
//! exact dyadic value. The sign of another polynomial `g` at such a root is
//! decided exactly ([`sign_at`]): zero when `gcd(q, g)` vanishes there (the
//! gcd, a divisor of the square-free `q`, changes sign across the interval),
//! otherwise by refining the interval until `g`'s Bernstein coefficients on it
//! all have one strict sign.

use core::cmp::Ordering;

use crate::exact::{BigFloat, Sign};

/// A polynomial `Σ c_k t^k`, coefficients from degree 0 up, with no trailing
/// zero coefficient (the zero polynomial has none).
#[derive(Clone, Debug, Default)]
pub(crate) struct Poly(pub(crate) Vec<BigFloat>);

impl Poly {
    /// The polynomial with these coefficients (trailing zeros dropped).
    pub(crate) fn new(mut c: Vec<BigFloat>) -> Self {
        while c.last().is_some_and(BigFloat::is_zero) {
            c.pop();
        }
        Self(c)
    }

    /// `x0 + t (x1 − x0)`: a coordinate moving linearly from `x0` at `t = 0`
    /// to `x1` at `t = 1`.
    pub(crate) fn linear(x0: f64, x1: f64) -> Self {
        let a = BigFloat::from_f64(x0);
        let b = BigFloat::from_f64(x1);
        let d = &b - &a;
        Self::new(vec![a, d])
    }

    /// Whether the polynomial is identically zero.
    pub(crate) fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    /// The degree (`None` for the zero polynomial).
    pub(crate) fn degree(&self) -> Option<usize> {
        self.0.len().checked_sub(1)
    }

    fn lead(&self) -> BigFloat {
        self.0.last().cloned().unwrap_or(BigFloat::ZERO)
    }

    /// `self + other`.
    pub(crate) fn add(&self, other: &Self) -> Self {
        let n = self.0.len().max(other.0.len());
        let z = BigFloat::ZERO;
        Self::new((0..n).map(|i| self.0.get(i).unwrap_or(&z) + other.0.get(i).unwrap_or(&z)).collect())
    }

    /// `self − other`.
    pub(crate) fn sub(&self, other: &Self) -> Self {
        let n = self.0.len().max(other.0.len());
        let z = BigFloat::ZERO;
        Self::new((0..n).map(|i| self.0.get(i).unwrap_or(&z) - other.0.get(i).unwrap_or(&z)).collect())
    }

    /// `self · other`.
    pub(crate) fn mul(&self, other: &Self) -> Self {
        if self.is_zero() || other.is_zero() {
            return Self::default();
        }
        let mut c = vec![BigFloat::ZERO; self.0.len() + other.0.len() - 1];
        for (i, x) in self.0.iter().enumerate() {
            for (j, y) in other.0.iter().enumerate() {
                c[i + j] = &c[i + j] + &(x * y);
            }
        }
        Self::new(c)
    }

    /// `k · self`.
    fn scale(&self, k: &BigFloat) -> Self {
        Self::new(self.0.iter().map(|c| c * k).collect())
    }

    /// `k t^shift · self`.
    fn scale_shift(&self, k: &BigFloat, shift: usize) -> Self {
        let mut c = vec![BigFloat::ZERO; shift];
        c.extend(self.0.iter().map(|x| x * k));
        Self::new(c)
    }

    /// The derivative.
    pub(crate) fn derivative(&self) -> Self {
        Self::new(self.0.iter().enumerate().skip(1).map(|(k, c)| c * &BigFloat::from_f64(k as f64)).collect())
    }

    /// The exact value at `t` (Horner's rule).
    pub(crate) fn eval(&self, t: &BigFloat) -> BigFloat {
        let mut acc = BigFloat::ZERO;
        for c in self.0.iter().rev() {
            acc = &(&acc * t) + c;
        }
        acc
    }

    /// The exact sign at `t`.
    pub(crate) fn sign_at_point(&self, t: &BigFloat) -> Sign {
        self.eval(t).sign()
    }

    /// Pseudo-division by a non-zero `d`: `(q, r)` with `k · self = q · d + r`
    /// for some non-zero constant `k` (a power of `d`'s leading coefficient)
    /// and `deg r < deg d`.
    fn pseudo_divide(&self, d: &Self) -> (Self, Self) {
        let dd = d.degree().unwrap_or(0);
        let ld = d.lead();
        let mut q = Self::default();
        let mut r = self.clone();
        while let Some(dr) = r.degree() {
            if dr < dd {
                break;
            }
            // r ← ld · r − lc(r) t^(dr − dd) · d, whose degree-dr term cancels;
            // q follows the same steps so that ld^s · self = q · d + r holds.
            let lr = r.lead();
            let mut unit = vec![BigFloat::ZERO; dr - dd];
            unit.push(lr.clone());
            q = q.scale(&ld).add(&Self::new(unit));
            r = r.scale(&ld).sub(&d.scale_shift(&lr, dr - dd));
        }
        (q, r)
    }

    /// A greatest common divisor, up to a non-zero constant factor (zero only
    /// when both are zero).
    pub(crate) fn gcd(&self, other: &Self) -> Self {
        let (mut a, mut b) =
            if self.degree() >= other.degree() { (self.clone(), other.clone()) } else { (other.clone(), self.clone()) };
        while !b.is_zero() {
            let (_, r) = a.pseudo_divide(&b);
            a = b;
            b = r;
        }
        a
    }

    /// The square-free part (same roots, each simple), up to a constant
    /// factor; `self` must be non-zero.
    pub(crate) fn square_free(&self) -> Self {
        let g = self.gcd(&self.derivative());
        if g.degree().unwrap_or(0) == 0 { self.clone() } else { self.pseudo_divide(&g).0 }
    }

    /// The Bernstein coefficients of `self` on `[lo, hi]`, each multiplied by
    /// a positive constant (the binomial `C(n, j)`), so only their signs are
    /// meaningful: with `p(lo + h s) = Σ a_k s^k`, `h = hi − lo`, they are
    /// `c_j = Σ_{k ≤ j} C(n − k, j − k) a_k` (`C(n, j) C(j, k) / C(n, k) =
    /// C(n − k, j − k)`, so no division).
    pub(crate) fn bernstein(&self, lo: &BigFloat, hi: &BigFloat) -> Vec<BigFloat> {
        let n = match self.degree() {
            None => return vec![BigFloat::ZERO],
            Some(n) => n,
        };
        // Taylor shift by lo (repeated synthetic division), then scale by h^k.
        let mut a = self.0.clone();
        for i in 0..n {
            for k in (i..n).rev() {
                a[k] = &a[k] + &(&a[k + 1] * lo);
            }
        }
        let h = hi - lo;
        let mut hk = BigFloat::from_f64(1.0);
        for c in a.iter_mut() {
            *c = &*c * &hk;
            hk = &hk * &h;
        }
        (0..=n)
            .map(|j| {
                let mut s = BigFloat::ZERO;
                for (k, ak) in a.iter().enumerate().take(j + 1) {
                    s = &s + &(ak * &BigFloat::from_f64(binomial(n - k, j - k)));
                }
                s
            })
            .collect()
    }
}

/// `C(n, k)` for the small degrees met here (exact in `f64`).
fn binomial(n: usize, k: usize) -> f64 {
    let mut r = 1.0;
    for i in 0..k {
        r = r * (n - i) as f64 / (i + 1) as f64;
    }
    r.round()
}

/// Sign variations of a sequence, zeros skipped.
fn variations(c: &[BigFloat]) -> usize {
    let mut last = Sign::Zero;
    let mut v = 0;
    for s in c.iter().map(BigFloat::sign).filter(|s| !s.is_zero()) {
        if !last.is_zero() && s != last {
            v += 1;
        }
        last = s;
    }
    v
}

/// The common strict sign of all the values, if they have one.
fn common_sign(c: &[BigFloat]) -> Option<Sign> {
    let s = c.first()?.sign();
    (!s.is_zero() && c.iter().all(|x| x.sign() == s)).then_some(s)
}

/// A real root of a polynomial, held exactly.
#[derive(Clone, Debug)]
pub(crate) enum Root {
    /// The root is this dyadic value (a double, or the midpoint of two).
    Exact(BigFloat),
    /// The only root of the square-free `q` in `(lo, hi)`, where `q(lo)` and
    /// `q(hi)` are non-zero and of opposite signs (`q(lo)` has `sign_lo`).
    Isolated { q: Poly, lo: BigFloat, hi: BigFloat, sign_lo: Sign },
}

/// The next `f64` above a non-negative finite `x`.
pub(crate) fn next_up(x: f64) -> f64 {
    if x == 0.0 { f64::from_bits(1) } else { f64::from_bits(x.to_bits() + 1) }
}

/// The next `f64` below a positive finite `x`.
fn next_down(x: f64) -> f64 {
    f64::from_bits(x.to_bits() - 1)
}

/// A split point strictly inside `(lo, hi)` (`0 ≤ lo < hi`): a double when
/// one lies there (so roots end up between adjacent doubles quickly: the
/// bit-pattern midpoint halves the count of doubles in between), else the
/// exact midpoint.
fn split(lo: &BigFloat, hi: &BigFloat) -> BigFloat {
    let (dl, dh) = (lo.to_f64().max(0.0), hi.to_f64().max(0.0));
    if dl.is_finite() && dh.is_finite() && dl < dh {
        let mid = f64::from_bits((dl.to_bits() + dh.to_bits()) / 2);
        for m in [mid, next_up(dl), if dh > 0.0 { next_down(dh) } else { dh }] {
            let b = BigFloat::from_f64(m);
            if b > *lo && b < *hi {
                return b;
            }
        }
    }
    &(lo + hi) * &BigFloat::from_f64(0.5)
}

/// The real roots of the non-zero square-free `q` in `[lo, hi]` (`0 ≤ lo ≤
/// hi`), in increasing order.
pub(crate) fn roots_in(q: &Poly, lo: f64, hi: f64) -> Vec<Root> {
    let mut out = Vec::new();
    if q.degree().unwrap_or(0) == 0 {
        return out;
    }
    let (lo, hi) = (BigFloat::from_f64(lo), BigFloat::from_f64(hi));
    let (slo, shi) = (q.sign_at_point(&lo), q.sign_at_point(&hi));
    if slo.is_zero() {
        out.push(Root::Exact(lo.clone()));
    }
    if lo < hi {
        isolate(q, lo, slo, hi.clone(), shi, &mut out);
        if shi.is_zero() {
            out.push(Root::Exact(hi));
        }
    }
    out
}

/// Roots of `q` in the open interval `(lo, hi)`, in increasing order, by
/// Bernstein subdivision (depth first, left half first).
fn isolate(q: &Poly, lo: BigFloat, slo: Sign, hi: BigFloat, shi: Sign, out: &mut Vec<Root>) {
    let v = variations(&q.bernstein(&lo, &hi));
    if v == 0 {
        return;
    }
    if v == 1 && !slo.is_zero() && !shi.is_zero() {
        out.push(Root::Isolated { q: q.clone(), lo, hi, sign_lo: slo });
        return;
    }
    let m = split(&lo, &hi);
    let sm = q.sign_at_point(&m);
    isolate(q, lo, slo, m.clone(), sm, out);
    if sm.is_zero() {
        out.push(Root::Exact(m.clone()));
    }
    isolate(q, m, sm, hi, shi, out);
}

/// One bisection step of an isolated root: `false` when the split point is
/// the root itself (then `root` becomes [`Root::Exact`]).
fn bisect(root: &mut Root) {
    if let Root::Isolated { q, lo, hi, sign_lo } = root {
        let m = split(lo, hi);
        let s = q.sign_at_point(&m);
        if s.is_zero() {
            *root = Root::Exact(m);
        } else if s == *sign_lo {
            *lo = m;
        } else {
            *hi = m;
        }
    }
}

/// Bisections tried in [`sign_at`] before the gcd test: enough for a root
/// well separated from `g`'s roots (each halves the interval), few enough
/// that a zero of `g` at the root costs little before the gcd finds it.
const QUICK_BISECTIONS: u32 = 8;

/// The exact sign of `g` at `root`.
pub(crate) fn sign_at(root: &Root, g: &Poly) -> Sign {
    let (q, lo, hi) = match root {
        Root::Exact(t) => return g.sign_at_point(t),
        Root::Isolated { q, lo, hi, .. } => (q, lo, hi),
    };
    if g.is_zero() {
        return Sign::Zero;
    }
    // Most often g has one strict sign near the root after a few bisections,
    // which shows g(root) ≠ 0 without the gcd.
    // g's sign at the root when the interval settles it: at an exact root, or
    // where g has one strict sign over the whole interval.
    let settled = |r: &Root| match r {
        Root::Exact(t) => Some(g.sign_at_point(t)),
        Root::Isolated { lo, hi, .. } => common_sign(&g.bernstein(lo, hi)),
    };
    let mut r = root.clone();
    for _ in 0..QUICK_BISECTIONS {
        if let Some(s) = settled(&r) {
            return s;
        }
        bisect(&mut r);
    }
    let h = q.gcd(g);
    if h.degree().unwrap_or(0) > 0 {
        // h divides the square-free q, whose only root in (lo, hi) is simple
        // and which is non-zero at lo and hi: h vanishes at the root iff it
        // changes sign across the interval.
        if h.sign_at_point(lo) != h.sign_at_point(hi) {
            return Sign::Zero;
        }
    }
    // g(root) ≠ 0: refine until g has one strict sign on the whole interval.
    loop {
        if let Some(s) = settled(&r) {
            return s;
        }
        bisect(&mut r);
    }
}

/// The root rounded to the nearest `f64` (ties to even): exact.
pub(crate) fn round(root: &Root) -> f64 {
    let mut r = root.clone();
    loop {
        let (q, lo, hi, sign_lo) = match &r {
            Root::Exact(t) => return round_dyadic(t),
            Root::Isolated { q, lo, hi, sign_lo } => (q, lo, hi, *sign_lo),
        };
        // The largest double d ≤ lo; if d⁺ = next_up(d) < hi, a double lies
        // inside: bisect further.
        let mut d = lo.to_f64();
        if BigFloat::from_f64(d) > *lo {
            d = next_down(d);
        }
        let up = next_up(d);
        let bup = BigFloat::from_f64(up);
        if bup < *hi {
            bisect(&mut r);
            continue;
        }
        // lo ≥ d, hi ≤ d⁺: the root is in (d, d⁺); compare with the midpoint.
        let mid = &(&BigFloat::from_f64(d) + &bup) * &BigFloat::from_f64(0.5);
        if mid <= *lo {
            return up;
        }
        if mid >= *hi {
            return d;
        }
        let s = q.sign_at_point(&mid);
        return if s.is_zero() {
            if d.to_bits().is_multiple_of(2) { d } else { up }
        } else if s == sign_lo {
            up
        } else {
            d
        };
    }
}

/// A non-negative dyadic value rounded to the nearest `f64` (ties to even).
fn round_dyadic(t: &BigFloat) -> f64 {
    let mut d = t.to_f64();
    let bd = BigFloat::from_f64(d);
    match bd.cmp(t) {
        Ordering::Equal => return d,
        Ordering::Greater => d = next_down(d),
        Ordering::Less => {}
    }
    let up = next_up(d);
    let mid = &(&BigFloat::from_f64(d) + &BigFloat::from_f64(up)) * &BigFloat::from_f64(0.5);
    match t.cmp(&mid) {
        Ordering::Less => d,
        Ordering::Greater => up,
        Ordering::Equal => {
            if d.to_bits().is_multiple_of(2) {
                d
            } else {
                up
            }
        }
    }
}

/// A vector of polynomials: a point or direction moving in time.
pub(crate) type PVec = [Poly; 3];

/// The point moving linearly from `x0` to `x1`.
pub(crate) fn moving(x0: [f64; 3], x1: [f64; 3]) -> PVec {
    [0, 1, 2].map(|i| Poly::linear(x0[i], x1[i]))
}

/// `x − y`.
pub(crate) fn vsub(x: &PVec, y: &PVec) -> PVec {
    [0, 1, 2].map(|i| x[i].sub(&y[i]))
}

/// `x · y`.
pub(crate) fn vdot(x: &PVec, y: &PVec) -> Poly {
    x[0].mul(&y[0]).add(&x[1].mul(&y[1])).add(&x[2].mul(&y[2]))
}

/// `x × y`.
pub(crate) fn vcross(x: &PVec, y: &PVec) -> PVec {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        x[j].mul(&y[k]).sub(&x[k].mul(&y[j]))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(c: &[f64]) -> Poly {
        Poly::new(c.iter().map(|&x| BigFloat::from_f64(x)).collect())
    }

    #[test]
    fn roots_of_a_cubic_with_a_double_root_are_found_once_each() {
        // (t − 1/4)² (t − 3/4) = t³ − 5/4 t² + 7/16 t − 3/64: roots 1/4 (double)
        // and 3/4, both dyadic, so both are found exactly.
        let f = p(&[-3.0 / 64.0, 7.0 / 16.0, -5.0 / 4.0, 1.0]);
        let q = f.square_free();
        assert!(q.degree() == Some(2), "square-free part of degree 2, got {q:?}");
        let r: Vec<f64> = roots_in(&q, 0.0, 1.0).iter().map(round).collect();
        assert!(r == vec![0.25, 0.75], "roots {r:?}");
    }

    #[test]
    fn an_irrational_root_is_correctly_rounded() {
        // t² − 1/2: root 1/√2; f64's correctly rounded value is
        // core::f64::consts::FRAC_1_SQRT_2 (the constant is the correctly rounded value).
        let q = p(&[-0.5, 0.0, 1.0]);
        let r: Vec<f64> = roots_in(&q, 0.0, 1.0).iter().map(round).collect();
        assert!(r == vec![core::f64::consts::FRAC_1_SQRT_2], "roots {r:?}");
        // The sign of t² − 1/2 + 0 (same polynomial) at its root is zero, of
        // t − 0.7 positive (1/√2 ≈ 0.7071), of 4t² − 3 negative.
        let root = &roots_in(&q, 0.0, 1.0)[0];
        assert!(sign_at(root, &p(&[-1.0, 0.0, 2.0])) == Sign::Zero);
        assert!(sign_at(root, &p(&[-0.7, 1.0])) == Sign::Positive);
        assert!(sign_at(root, &p(&[-3.0, 0.0, 4.0])) == Sign::Negative);
    }
}
