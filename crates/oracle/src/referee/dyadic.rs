//! Exact dyadic numbers: the stage between the double-word numbers of
//! [`super::fast`] and the exact stage's rationals.
//!
//! Every finite `f64` is `m·2^e` with an integer `m`, and sums, differences
//! and products of such numbers are again such numbers, computed exactly with
//! a big integer and an exponent: no rounding, no error bound, no gcd. The
//! stages written over [`Num`] — contact, intersect, barycentric coordinates
//! and response — run first in double-word numbers, where the bounds decide
//! nearly every case, and then, when they leave something open, in these:
//! every sign is then certain, and each output `N/D` is rounded once,
//! correctly, from the exact integers (the rational's own correct rounding,
//! without reducing it). An output with a square root (a unit normal, a
//! depth, a point on a sphere) is rounded by the exact stage's own `Root` from
//! these numbers' rationals. An answer here is the exact stage's, bit for bit
//! (`tests/referee_stages.rs`); only the exact stage's own fallbacks and flags
//! (concentric spheres, a parallel segment, a zero-area triangle) and refusals
//! still reach the rationals. Time of impact, whose candidates are ordered by
//! roots of quadratics, is not written over it.
//!
//! What it saves: a full-range case (coordinates from `2^-1074` to `2^1023`
//! in one question) can need two thousand bits to decide `t ≤ 1`, beyond any
//! fixed precision, and the rationals pay a gcd on every operation for it.

use dashu::integer::{IBig, UBig};
use dashu::rational::Relaxed;

use super::exact::{Q, Root};
use super::fast::Dw;
use crate::geom::P3;

/// `m·2^e`, exactly.
#[derive(Clone, Debug)]
pub(crate) struct Dy {
    m: IBig,
    e: i64,
}

/// A finite `x` as `±mant·2^e`: its significand (`mant < 2^53`, 0 for ±0),
/// its exponent and whether it is negative — IEEE 754's fields, read exactly.
pub(crate) fn parts(x: f64) -> (u64, i64, bool) {
    let bits = x.to_bits();
    let field = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    let (mant, e) = if field == 0 { (frac, -1074) } else { (frac | (1u64 << 52), field - 1075) };
    (mant, e, x < 0.0)
}

/// The rational `m·2^e`.
pub(crate) fn rational(m: &IBig, e: i64) -> Q {
    if e >= 0 { Q::from(m << e as usize) } else { Q::from_parts(m.clone(), UBig::ONE << (-e) as usize) }
}

impl Dy {
    /// The exact value of a finite `x` (0 for ±0).
    pub(crate) fn of(x: f64) -> Dy {
        let (mant, e, negative) = parts(x);
        let m = IBig::from(mant);
        Dy { m: if negative { -m } else { m }, e }
    }

    fn aligned(&self, e: i64) -> IBig {
        // e ≤ self.e: shifting left is exact.
        &self.m << (self.e - e) as usize
    }

    fn add(&self, o: &Dy) -> Dy {
        let e = self.e.min(o.e);
        Dy { m: self.aligned(e) + o.aligned(e), e }
    }

    fn mul(&self, o: &Dy) -> Dy {
        Dy { m: &self.m * &o.m, e: self.e + o.e }
    }

    fn neg(&self) -> Dy {
        Dy { m: -&self.m, e: self.e }
    }

    fn sign(&self) -> i8 {
        match self.m.signum() {
            s if s > IBig::ZERO => 1,
            s if s < IBig::ZERO => -1,
            _ => 0,
        }
    }

    /// The exact rational.
    fn rational(&self) -> Q {
        rational(&self.m, self.e)
    }
}

/// The arithmetic a stage is written in: [`Dw`], double-word numbers whose
/// error bounds may leave a sign open, or [`Dy`], exact numbers whose signs
/// are always certain. The same code runs in both; `None` from either means
/// "not decided here".
pub(crate) trait Num: Clone {
    fn of(x: f64) -> Self;
    /// `a − b`.
    fn diff(a: f64, b: f64) -> Self;
    fn plus(&self, o: &Self) -> Self;
    fn minus(&self, o: &Self) -> Self;
    fn times(&self, o: &Self) -> Self;
    /// The sign, when certain; `Some(0)` only for an exact zero.
    fn sign_of(&self) -> Option<i8>;
    /// `RN(n/d)`, certified, or `None`: `d`'s sign must be certain and not
    /// zero; an exact zero `n` gives `+0.0`, as the exact stage rounds 0.
    fn quotient(n: &Self, d: &Self) -> Option<f64>;
    /// `v/‖v‖` componentwise, correctly rounded, given `s = v·v` (`None`
    /// unless `s > 0`).
    fn unit(v: &[Self; 3], s: &Self) -> Option<P3>;
    fn neg(&self) -> Self;
    /// `a + p/√s` (`s > 0`), correctly rounded; `a + 0` when `p` is exactly 0.
    fn over_root(a: f64, p: &Self, s: &Self) -> Option<f64>;
    /// `c − √s`, correctly rounded (`+0.0` when exactly 0).
    fn minus_root(c: &Self, s: &Self) -> Option<f64>;
    /// `r − e/√s` (`s > 0`), correctly rounded; `r + 0` when `e` is exactly 0.
    fn minus_over_root(r: f64, e: &Self, s: &Self) -> Option<f64>;
    /// `r − √w/l` (`l > 0`), correctly rounded.
    fn minus_root_over(r: f64, w: &Self, l: &Self) -> Option<f64>;

    fn exact_zero(&self) -> bool {
        self.sign_of() == Some(0)
    }

    fn positive(&self) -> bool {
        self.sign_of() == Some(1)
    }
}

impl Num for Dw {
    fn of(x: f64) -> Self {
        Dw::of(x)
    }
    fn diff(a: f64, b: f64) -> Self {
        Dw::diff(a, b)
    }
    fn plus(&self, o: &Self) -> Self {
        self.add(*o)
    }
    fn minus(&self, o: &Self) -> Self {
        self.sub(*o)
    }
    fn times(&self, o: &Self) -> Self {
        self.mul(*o)
    }
    fn sign_of(&self) -> Option<i8> {
        self.signum()
    }
    fn quotient(n: &Self, d: &Self) -> Option<f64> {
        super::fast::quotient(*n, *d)
    }
    fn unit(v: &[Self; 3], s: &Self) -> Option<P3> {
        if !s.is_positive() {
            return None;
        }
        super::root_fast::unit(v, *s, super::fast::sqrt_approx(*s))
    }
    fn neg(&self) -> Self {
        Dw::neg(*self)
    }
    fn over_root(a: f64, p: &Self, s: &Self) -> Option<f64> {
        super::root_fast::over_root(a, *p, *s, super::fast::sqrt_approx(*s))
    }
    fn minus_root(c: &Self, s: &Self) -> Option<f64> {
        super::root_fast::minus_root(*c, *s, super::fast::sqrt_approx(*s))
    }
    fn minus_over_root(r: f64, e: &Self, s: &Self) -> Option<f64> {
        super::root_fast::plane_depth(r, *e, *s, super::fast::sqrt_approx(*s))
    }
    fn minus_root_over(r: f64, w: &Self, l: &Self) -> Option<f64> {
        super::root_fast::root_over_depth(r, *w, *l)
    }
}

impl Num for Dy {
    fn of(x: f64) -> Self {
        Dy::of(x)
    }
    fn diff(a: f64, b: f64) -> Self {
        Dy::of(a).add(&Dy::of(b).neg())
    }
    fn plus(&self, o: &Self) -> Self {
        self.add(o)
    }
    fn minus(&self, o: &Self) -> Self {
        self.add(&o.neg())
    }
    fn times(&self, o: &Self) -> Self {
        self.mul(o)
    }
    fn sign_of(&self) -> Option<i8> {
        Some(self.sign())
    }
    fn quotient(n: &Self, d: &Self) -> Option<f64> {
        if d.sign() == 0 {
            return None;
        }
        if n.sign() == 0 {
            return Some(0.0);
        }
        // n/d = (m_n·2^(e_n − e_d))/m_d, the power of two on its side.
        let k = n.e - d.e;
        let (num, den) = if k >= 0 { (&n.m << k as usize, d.m.clone()) } else { (n.m.clone(), &d.m << (-k) as usize) };
        // Correct rounding is a property of the value: the unreduced
        // rational rounds as the reduced one does.
        Some(super::exact::round_relaxed(&Relaxed::from_parts_signed(num, den)))
    }
    fn unit(v: &[Self; 3], s: &Self) -> Option<P3> {
        if s.sign() <= 0 {
            return None;
        }
        let v = [v[0].rational(), v[1].rational(), v[2].rational()];
        Some(Root::new(s.rational()).round_over_v(&[Q::ZERO, Q::ZERO, Q::ZERO], &Q::ONE, &v))
    }
    fn neg(&self) -> Self {
        Dy::neg(self)
    }
    // The square roots are the exact stage's own (`Root`): an enclosure of
    // √s narrowed until the output's rounding is decided, from the exact
    // rationals of these numbers (a power of two below each: no gcd to speak
    // of).
    fn over_root(a: f64, p: &Self, s: &Self) -> Option<f64> {
        if p.sign() == 0 {
            return Some(a + 0.0);
        }
        (s.sign() > 0).then(|| Root::new(s.rational()).round_over(&Dy::of(a).rational(), &p.rational()))
    }
    fn minus_root(c: &Self, s: &Self) -> Option<f64> {
        (s.sign() >= 0).then(|| Root::new(s.rational()).round_affine(&c.rational(), &-Q::ONE))
    }
    fn minus_over_root(r: f64, e: &Self, s: &Self) -> Option<f64> {
        if e.sign() == 0 {
            return Some(r + 0.0);
        }
        (s.sign() > 0).then(|| Root::new(s.rational()).round_over(&Dy::of(r).rational(), &-e.rational()))
    }
    fn minus_root_over(r: f64, w: &Self, l: &Self) -> Option<f64> {
        (w.sign() >= 0 && l.sign() > 0)
            .then(|| Root::new(w.rational()).round_affine(&Dy::of(r).rational(), &-(Q::ONE / l.rational())))
    }
}

/// `a·b` for vectors in either arithmetic.
pub(crate) fn dot<T: Num>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0].times(&b[0]).plus(&a[1].times(&b[1])).plus(&a[2].times(&b[2]))
}

/// `u × v`.
pub(crate) fn cross<T: Num>(u: &[T; 3], v: &[T; 3]) -> [T; 3] {
    [
        u[1].times(&v[2]).minus(&u[2].times(&v[1])),
        u[2].times(&v[0]).minus(&u[0].times(&v[2])),
        u[0].times(&v[1]).minus(&u[1].times(&v[0])),
    ]
}

/// `p − q`, componentwise, exactly (double-word differences are exact too).
pub(crate) fn diff3<T: Num>(p: &P3, q: &P3) -> [T; 3] {
    [T::diff(p[0], q[0]), T::diff(p[1], q[1]), T::diff(p[2], q[2])]
}
