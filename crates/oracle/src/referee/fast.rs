//! The floating-point stage of an exact quotient: double-word numbers that
//! carry an exact account of the error they commit, and a correctly rounded
//! `N / D` certified from them, or nothing (the exact stage decides).
//!
//! A [`Dw`] is `hi + lo` (two `f64`) and a bound `err` on its distance from the
//! exact value it stands for. Differences of two inputs are exact (`two_sum`).
//! A sum or a product is computed with error-free transformations only
//! (`two_sum`, Dekker's `two_prod`), and the terms it drops are summed into
//! `err` as they are, not as a worst case: a computation that happens to be
//! exact carries `err = 0`, so an exact zero is known to be zero. Errors
//! carried in from the operands are propagated by the usual first-order rules
//! with their second-order term. Every bound is computed in round-to-nearest
//! `f64` from non-negative terms and then raised by [`UP`], which exceeds the
//! relative rounding of the few operations that computed it.
//!
//! The exact transformations hold only while no intermediate overflows or
//! underflows. A [`Dw`] carries its own binary exponent, so its words stay
//! near 1 at any magnitude — inputs from the smallest subnormal to `f64::MAX`
//! and products far beyond both ends of `f64`'s range. Every product still
//! guards itself: a factor too large to split, or a sum that overflows, makes
//! the result unknown (every sign test on it open); a product below `2^-969`,
//! where Dekker's error term would underflow, is kept rounded with a bound on
//! what it lost ([`guarded_prod`]); a word scaled below the normal range adds
//! what it may lose. So the bounds hold at any magnitude. [`all_finite`] admits
//! every finite input, and an output is certified anywhere below `MAX`,
//! subnormal or rounding to a signed zero included.
//!
//! **Certifying `RN(N / D)`.** `D`'s sign must be certain (`|D̃| > err`). An
//! exactly zero `N` gives `+0.0`, as the exact stage's rounding of zero does.
//! Otherwise a candidate `r` is taken from the double-word values and the
//! signs of `N − m·D` at the two midpoints `m = r ± ulp/2` around it (each an
//! exact double-word) are decided: when the quotient lies strictly between
//! them, `r` is its rounding to nearest — no tie is possible. A sign that the
//! error bound leaves open, or a quotient on a midpoint, returns `None`.

/// The unit roundoff of `f64`, `2^-53`.
const U: f64 = f64::EPSILON / 2.0;

/// Raises an error bound computed in `f64` (a handful of roundings to
/// nearest, each within a relative `U`) to an upper bound of the exact one.
const UP: f64 = 1.0 + 16.0 * U;

/// Dekker's splitter for `f64`: `2^27 + 1`.
const SPLITTER: f64 = 134_217_729.0;

/// `a + b` as `(s, e)` with `s + e = a + b` exactly (no overflow).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a` split into two halves of at most 26 significant bits each.
fn split(a: f64) -> (f64, f64) {
    let c = SPLITTER * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a · b` as `(p, e)` with `p + e = a · b` exactly (Dekker; no overflow, and
/// no underflow of the error term: see [`guarded_prod`]).
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// Dekker's product stays exact while `|a · b| ≥ 2^-969` (its error term is
/// then a normal number) and the splitter cannot overflow (`|a|, |b| ≤ 2^995`).
const PROD_MIN: f64 = f64::from_bits((1023 - 969) << 52);

/// See [`PROD_MIN`]: `2^995`.
const SPLIT_MAX: f64 = f64::from_bits((1023 + 995) << 52);

/// A bound on `|a·b − RN(a·b)|` whenever `|RN(a·b)| < 2^-969`: half an ulp of
/// a number below `2^-969` is at most `2^-1022`; `2^-1021` is kept.
const UNDERFLOW_ERR: f64 = f64::from_bits((1023 - 1021) << 52);

/// [`two_prod`] where it is exact, and otherwise `(RN(a·b), 0)` with a bound
/// on what that drops: `Some(0)` exactly, [`UNDERFLOW_ERR`] near underflow;
/// `None` when a factor is too large to split (the caller's bound is then
/// infinite).
fn guarded_prod(a: f64, b: f64) -> Option<(f64, f64, f64)> {
    if a.abs() > SPLIT_MAX || b.abs() > SPLIT_MAX {
        return None;
    }
    let p = a * b;
    if a != 0.0 && b != 0.0 && p.abs() < PROD_MIN {
        return Some((p, 0.0, UNDERFLOW_ERR));
    }
    let (p, e) = two_prod(a, b);
    Some((p, e, 0.0))
}

/// A double-word number with its own binary exponent: the exact value lies
/// within `err·2^e` of `(hi + lo)·2^e`.
///
/// The exponent keeps the words near 1 whatever the magnitude: whenever the
/// leading word (or, for a value known only by its bound, `err`) leaves
/// `[2^-RESCALE_EXP, 2^RESCALE_EXP]`, [`Dw::norm`] scales the words by a
/// power of two, exactly (a word that the scaling takes below the normal
/// range adds what it may lose, at most `2^-1074` each, to `err`). Values of
/// ordinary magnitude are never rescaled: their arithmetic is the plain
/// double-word arithmetic, with `e = 0`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dw {
    hi: f64,
    lo: f64,
    err: f64,
    e: i64,
}

/// Words stay unscaled while their leading exponent is within
/// `[-RESCALE_EXP, RESCALE_EXP]`: the products of two such (and their Dekker
/// error terms, down to `2^-2·RESCALE_EXP-106`) stay clear of overflow and of
/// [`PROD_MIN`].
const RESCALE_EXP: i64 = 400;

/// The smallest positive normal `f64`, `2^-1022`.
const MIN_NORMAL: f64 = f64::MIN_POSITIVE;

/// What scaling a word into the subnormal range may lose, rounded up:
/// `2^-1073`, the subnormal `2·2^-1074` (each such rounding loses at most
/// `2^-1075`).
const SCALE_LOSS: f64 = f64::from_bits(2);

/// `⌊log₂|x|⌋` for a finite non-zero `x` (subnormals included).
fn exponent(x: f64) -> i64 {
    let biased = ((x.to_bits() >> 52) & 0x7ff) as i64;
    if biased == 0 {
        // Subnormal: 2^64 scales it exactly into the normal range.
        return exponent(x * f64::from_bits((1023 + 64) << 52)) - 64;
    }
    biased - 1023
}

/// `x · 2^k`, rounded once at the end when the result is subnormal (the
/// scaling steps go toward the result, so only the last may round).
fn ldexp(mut x: f64, mut k: i64) -> f64 {
    while k != 0 && x != 0.0 && x.is_finite() {
        let step = k.clamp(-1000, 1000);
        x *= f64::from_bits(((1023 + step) as u64) << 52);
        k -= step;
    }
    x
}

/// `x · 2^k` and a bound on what the scaling lost: 0 unless the result is
/// below the normal range (then [`SCALE_LOSS`]).
fn scaled(x: f64, k: i64) -> (f64, f64) {
    let y = ldexp(x, k);
    let lost = if x != 0.0 && y.abs() < MIN_NORMAL { SCALE_LOSS } else { 0.0 };
    (y, lost)
}

/// An error bound scaled by `2^k`, rounded up (a bound that would be below
/// the normal range becomes [`MIN_NORMAL`]).
fn scaled_bound(err: f64, k: i64) -> f64 {
    let y = ldexp(err, k);
    if err > 0.0 && y < MIN_NORMAL { MIN_NORMAL } else { y }
}

impl Dw {
    /// Exactly zero.
    pub(crate) const ZERO: Dw = Dw { hi: 0.0, lo: 0.0, err: 0.0, e: 0 };

    /// `(hi + lo ± err)·2^e` rescaled when its leading magnitude leaves
    /// `2^±RESCALE_EXP` (see [`Dw`]); unknown when anything is not finite.
    fn norm(hi: f64, lo: f64, err: f64, e: i64) -> Dw {
        if !(hi.is_finite() && lo.is_finite() && err.is_finite()) {
            return Dw::UNKNOWN;
        }
        let lead = if hi != 0.0 {
            hi
        } else if err != 0.0 {
            err
        } else {
            return Dw::ZERO;
        };
        let k = exponent(lead);
        if (-RESCALE_EXP..=RESCALE_EXP).contains(&k) {
            return Dw { hi, lo, err, e };
        }
        let (hi, l1) = scaled(hi, -k);
        let (lo, l2) = scaled(lo, -k);
        let err = scaled_bound(err, -k) + l1 + l2;
        if !err.is_finite() {
            return Dw::UNKNOWN;
        }
        Dw { hi, lo, err: if l1 + l2 > 0.0 { err * UP } else { err }, e: e + k }
    }

    /// Whether this is the exact zero (no words, no error).
    fn is_zero_exactly(self) -> bool {
        self.hi == 0.0 && self.lo == 0.0 && self.err == 0.0
    }

    /// The words rescaled to exponent `e ≥ self.e` (exactly, or with what a
    /// word taken below the normal range may lose added to `err`).
    fn at(self, e: i64) -> (f64, f64, f64) {
        let k = self.e - e;
        if k == 0 {
            return (self.hi, self.lo, self.err);
        }
        if k < -1100 {
            // Far below the other operand's scale: only a bound on its
            // magnitude is kept.
            return (0.0, 0.0, scaled_bound((self.hi.abs() + self.lo.abs() + self.err) * UP, k));
        }
        let (hi, l1) = scaled(self.hi, k);
        let (lo, l2) = scaled(self.lo, k);
        (hi, lo, scaled_bound(self.err, k) + l1 + l2)
    }

    /// `a − b`, exactly (short of a difference beyond `f64`'s range, which the
    /// exponent takes).
    pub(crate) fn diff(a: f64, b: f64) -> Dw {
        let (hi, lo) = two_sum(a, -b);
        if hi.is_finite() { Dw::norm(hi, lo, 0.0, 0) } else { Dw::of(a).sub(Dw::of(b)) }
    }

    /// An upper bound of `|hi + lo|`.
    fn mag(self) -> f64 {
        (self.hi.abs() + self.lo.abs()) * UP
    }

    /// A lower bound of `|hi + lo|` (`hi` is its rounding: `|lo| ≤ ulp(hi)/2`).
    fn mag_below(self) -> f64 {
        (self.hi.abs() - self.lo.abs()) * (1.0 - 4.0 * U)
    }

    pub(crate) fn neg(self) -> Dw {
        Dw { hi: -self.hi, lo: -self.lo, err: self.err, e: self.e }
    }

    pub(crate) fn add(self, o: Dw) -> Dw {
        if !(self.err.is_finite() && o.err.is_finite()) {
            return Dw::UNKNOWN;
        }
        if self.is_zero_exactly() {
            return o;
        }
        if o.is_zero_exactly() {
            return self;
        }
        let e = self.e.max(o.e);
        let ((ah, al, ae), (bh, bl, be)) = (self.at(e), o.at(e));
        let (s, e1) = two_sum(ah, bh);
        let (t, e2) = two_sum(al, bl);
        let (v, e3) = two_sum(e1, t);
        let (w, e4) = two_sum(v, e2);
        let (hi, lo) = two_sum(s, w);
        // self + o = s + e1 + t + e2 = s + v + e3 + e2 = s + w + e4 + e3 = hi + lo + e3 + e4
        // (two_sum is exact at any magnitude, subnormal included, short of overflow).
        Dw::norm(hi, lo, (ae + be + e3.abs() + e4.abs()) * UP, e)
    }

    /// A value about which nothing is known: every sign test on it is open.
    const UNKNOWN: Dw = Dw { hi: 0.0, lo: 0.0, err: f64::INFINITY, e: 0 };

    pub(crate) fn sub(self, o: Dw) -> Dw {
        self.add(o.neg())
    }

    pub(crate) fn mul(self, o: Dw) -> Dw {
        if !(self.err.is_finite() && o.err.is_finite()) {
            return Dw::UNKNOWN;
        }
        if self.is_zero_exactly() || o.is_zero_exactly() {
            return Dw::ZERO;
        }
        // A product with a zero word is an exact zero: not computed (a
        // word-sized number, the common input, has no low word).
        let prod = |x: f64, y: f64| if x == 0.0 || y == 0.0 { Some((0.0, 0.0, 0.0)) } else { guarded_prod(x, y) };
        let (Some((p, e0, u0)), Some((a, ea, ua)), Some((b, eb, ub)), Some((c, ec, uc))) =
            (guarded_prod(self.hi, o.hi), prod(self.hi, o.lo), prod(self.lo, o.hi), prod(self.lo, o.lo))
        else {
            return Dw::UNKNOWN;
        };
        let (s1, f1) = two_sum(a, b);
        let (s2, f2) = two_sum(s1, c);
        let (s3, f3) = two_sum(e0, s2);
        let (hi, lo) = two_sum(p, s3);
        // (hi + lo) of the product = p + s3 exactly; the terms dropped are
        // f1 + f2 + f3 + ea + eb + ec, and what an underflowing product lost.
        let dropped = f1.abs() + f2.abs() + f3.abs() + ea.abs() + eb.abs() + ec.abs() + u0 + ua + ub + uc;
        // With x = x̃ + δx, y = ỹ + δy: |xy − x̃ỹ| ≤ |x̃|·|δy| + |ỹ|·|δx| + |δx|·|δy|.
        let carried = self.mag() * o.err + o.mag() * self.err + self.err * o.err;
        // Computing the bound in f64 may underflow a product of tiny terms to
        // 0: a carried error that is not exactly 0 gets UNDERFLOW_ERR more.
        let floor = if self.err > 0.0 || o.err > 0.0 { UNDERFLOW_ERR } else { 0.0 };
        Dw::norm(hi, lo, (carried + dropped) * UP + floor, self.e + o.e)
    }

    /// The sign of the exact value, when `err` leaves it certain: `Some(0)`
    /// only for an exact zero.
    fn sign(self) -> Option<i8> {
        if !self.err.is_finite() {
            return None;
        }
        if self.hi == 0.0 && self.lo == 0.0 {
            return (self.err == 0.0).then_some(0);
        }
        if self.mag_below() > self.err {
            // hi + lo is normalized (`two_sum`): its sign is hi's.
            return Some(if self.hi > 0.0 { 1 } else { -1 });
        }
        None
    }
}

/// The dot product of two exact differences' vectors.
pub(crate) fn dot(a: &[Dw; 3], b: &[Dw; 3]) -> Dw {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}

/// `u × v`.
pub(crate) fn cross(u: &[Dw; 3], v: &[Dw; 3]) -> [Dw; 3] {
    [u[1].mul(v[2]).sub(u[2].mul(v[1])), u[2].mul(v[0]).sub(u[0].mul(v[2])), u[0].mul(v[1]).sub(u[1].mul(v[0]))]
}

/// `p − q`, componentwise, exactly.
pub(crate) fn diff3(p: &[f64; 3], q: &[f64; 3]) -> [Dw; 3] {
    [Dw::diff(p[0], q[0]), Dw::diff(p[1], q[1]), Dw::diff(p[2], q[2])]
}

/// Whether every input is a finite number: the exponent of [`Dw`] takes any
/// magnitude, and a NaN or an infinity is the exact stage's to refuse.
pub(crate) fn all_finite(xs: impl IntoIterator<Item = f64>) -> bool {
    xs.into_iter().all(f64::is_finite)
}

/// `N / D` correctly rounded (to nearest, ties to even), when the error
/// bounds certify it; `None` when the exact stage must decide.
pub(crate) fn quotient(n: Dw, d: Dw) -> Option<f64> {
    let d_sign = match d.sign()? {
        0 => return None,
        s => s,
    };
    if n.sign()? == 0 {
        return Some(0.0);
    }
    // Where the quotient lies against m: the sign of (N − m·D)·sign(D).
    certify(div_approx(n, d).approx(), |m| n.sub(m.mul(d)).sign().map(|s| s * d_sign))
}

/// The correct rounding (to nearest, ties to even) of an exact value `x`,
/// from a candidate `r` near it and `side(m)`, the sign of `x − m` for an
/// exact double-word `m` (or `None` when the error bounds leave it open).
///
/// The signs at the two midpoints around `r` decide: `x` strictly between
/// them rounds to `r` — no tie is possible. Otherwise `r` moves an ulp toward
/// `x` (at most a few times). Below the normal range the grid is the
/// subnormals' (`2^-1074` apart, midpoints at odd multiples of `2^-1075`),
/// and a value that rounds to zero is zero with the value's sign. A value
/// that `side(0)` proves exactly 0 is `+0.0` (as the exact stage rounds the
/// rational 0), whatever the candidate. Otherwise a midpoint exactly (a tie),
/// an open sign, or a candidate at `±MAX` or beyond gives `None`.
pub(crate) fn certify(r: f64, side: impl Fn(Dw) -> Option<i8>) -> Option<f64> {
    // A candidate many ulps from an exact 0 (cancellation leaves it some tiny
    // number) does not reach it by steps: an exact 0 is checked on its own.
    round_near(r, &side).or_else(|| (side(Dw::ZERO)? == 0).then_some(0.0))
}

/// [`certify`] from the candidate alone.
fn round_near(mut r: f64, side: &impl Fn(Dw) -> Option<i8>) -> Option<f64> {
    // The candidate may be off by an ulp or two; each step moves it one.
    for _ in 0..4 {
        if r.is_nan() || r.abs() >= f64::MAX {
            return None;
        }
        let (below, above) = if r.abs() <= MIN_NORMAL {
            // r = k·2^-1074 exactly (|2k| ≤ 2^53), and the grid is 2^-1074 on
            // both sides, MIN_NORMAL's included: the midpoints are
            // (2k ∓ 1)·2^-1075, in two words.
            let k2 = ldexp(r, 1075);
            let at = |d: f64| {
                let (hi, lo) = two_sum(k2, d);
                Dw::norm(hi, lo, 0.0, -1075)
            };
            (at(-1.0), at(1.0))
        } else {
            (Dw::midpoint(r, false), Dw::midpoint(r, true))
        };
        match (side(below)?, side(above)?) {
            (1, -1) if r == 0.0 => {
                return Some(if side(Dw::ZERO)? < 0 { -0.0 } else { 0.0 });
            }
            (1, -1) => return Some(r),
            (_, 1) => r = r.next_up(),
            (-1, _) => r = r.next_down(),
            // On a midpoint: a tie, which the exact stage rounds.
            _ => return None,
        }
    }
    None
}

/// The sign of `P + Q·√S` for an exact `S > 0` (the caller has made sure of
/// `S`'s sign), when the error bounds leave it certain; `Some(0)` only for an
/// exact zero.
///
/// With `P` and `Q` of one sign (or either zero) it is theirs. Otherwise it is
/// `P`'s times the sign of `P² − Q²·S`.
pub(crate) fn sign_affine_root(p: Dw, q: Dw, s: Dw) -> Option<i8> {
    let (sp, sq) = (p.sign()?, q.sign()?);
    if sq == 0 {
        return Some(sp);
    }
    if sp == 0 || sp == sq {
        return Some(sq);
    }
    p.mul(p).sub(q.mul(q).mul(s)).sign().map(|d| d * sp)
}

/// `√s` to about twice `f64`'s precision (one Newton step from `f64`'s
/// square root, its residual computed exactly): a candidate's ingredient, not
/// a bound (its `err` is not kept).
pub(crate) fn sqrt_approx(s: Dw) -> Dw {
    // √((hi + lo)·2^e) with an even exponent: 2^(e/2)·√(hi + lo).
    let (hi, lo, e) = if s.e % 2 == 0 { (s.hi, s.lo, s.e) } else { (2.0 * s.hi, 2.0 * s.lo, s.e - 1) };
    let r = (hi + lo).sqrt();
    if !(r > 0.0 && r.is_finite()) {
        return Dw::of(r);
    }
    let (p, pe) = two_prod(r, r);
    let residual = ((hi - p) - pe) + lo;
    let (h, l) = two_sum(r, residual / (2.0 * r));
    Dw::norm(h, l, 0.0, e / 2)
}

/// `a / b` to about twice `f64`'s precision (one correction step): a
/// candidate's ingredient, not a bound.
pub(crate) fn div_approx(a: Dw, b: Dw) -> Dw {
    let q0 = (a.hi + a.lo) / (b.hi + b.lo);
    if !q0.is_finite() || q0 == 0.0 {
        return Dw::norm(q0, 0.0, 0.0, a.e - b.e);
    }
    let q = Dw::norm(q0, 0.0, 0.0, a.e - b.e);
    let residual = a.sub(q.mul(b));
    // The correction residual / b, at q's exponent.
    let correction = ldexp((residual.hi + residual.lo) / (b.hi + b.lo), residual.e - b.e - q.e);
    let (hi, lo) = two_sum(q.hi, correction);
    Dw::norm(hi, lo, 0.0, q.e)
}

impl Dw {
    /// An input, exactly (`None`-like [`Dw::UNKNOWN`] when not finite).
    pub(crate) fn of(x: f64) -> Dw {
        Dw::norm(x, 0.0, 0.0, 0)
    }

    /// A number near `(hi + lo)·2^e` (a candidate: not certified; `±∞` or 0
    /// beyond `f64`'s range).
    pub(crate) fn approx(self) -> f64 {
        ldexp(self.hi + self.lo, self.e)
    }

    /// The midpoint between a normal `r` and its neighbour above (`up`) or
    /// below, exactly: `r`'s words scaled to near 1, where half an ulp is a
    /// word too.
    fn midpoint(r: f64, up: bool) -> Dw {
        let k = exponent(r);
        let m = ldexp(r, -k);
        let half = if up { (m.next_up() - m) / 2.0 } else { -(m - m.next_down()) / 2.0 };
        Dw { hi: m, lo: half, err: 0.0, e: k }
    }

    /// Whether it is exactly zero.
    pub(crate) fn is_exact_zero(self) -> bool {
        self.sign() == Some(0)
    }

    /// Whether its sign is certainly positive.
    pub(crate) fn is_positive(self) -> bool {
        self.sign() == Some(1)
    }

    /// The sign of the exact value, when certain (`Some(0)`: exactly zero).
    pub(crate) fn signum(self) -> Option<i8> {
        self.sign()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::within_ulps;

    /// A certified quotient is the correctly rounded one: 0 ulps from the
    /// reference, itself correctly rounded (an IEEE division of exact inputs).
    const EXACT_ULPS: u64 = 0;

    fn exact(x: f64) -> Dw {
        Dw::of(x)
    }

    /// Whether the stage certified `got` as the correct rounding `want`
    /// (the same sign of zero included).
    fn certified(got: Option<f64>, want: f64) -> bool {
        got.is_some_and(|g| within_ulps(g, want, EXACT_ULPS) && g.is_sign_negative() == want.is_sign_negative())
    }

    #[test]
    fn exact_operations_carry_no_error_and_zero_is_known() {
        // (1 − 2^-30)(3 − 2^-20) = 3 − 2^-20 − 3·2^-30 + 2^-50: 52 bits, held exactly.
        let x = Dw::diff(1.0, 2f64.powi(-30)).mul(Dw::diff(3.0, 2f64.powi(-20)));
        assert!(x.err == 0.0, "a product two words hold exactly carries no error: {x:?}");
        let z = x.sub(x);
        assert_eq!(z.sign(), Some(0));
        assert!(certified(quotient(z, exact(3.0)), 0.0), "an exact zero is +0.0");
        // (1 − 2^-60)(3 − 2^-70) = 3 − 3·2^-60 − 2^-70 + 2^-130: two words hold
        // all but 2^-130, which the bound must cover (and not much more).
        let y = Dw::diff(1.0, 2f64.powi(-60)).mul(Dw::diff(3.0, 2f64.powi(-70)));
        assert!(y.err >= 2f64.powi(-130) && y.err <= 2f64.powi(-129), "{y:?}");
    }

    #[test]
    fn quotients_are_rounded_to_nearest_and_a_tie_is_left_to_the_exact_stage() {
        assert!(certified(quotient(exact(1.0), exact(3.0)), 1.0 / 3.0));
        assert!(certified(quotient(exact(-2.0), exact(7.0)), -2.0 / 7.0));
        assert!(certified(quotient(exact(1.0), exact(-2.0)), -0.5));
        // (1 + 2^-53) / 1 lies exactly between 1 and its successor.
        assert_eq!(quotient(Dw::diff(1.0, -(2f64.powi(-53))), exact(1.0)), None);
        // Just above the midpoint it rounds up, just below it rounds down.
        let above = Dw::diff(1.0, -(2f64.powi(-53))).add(Dw::diff(2f64.powi(-80), 0.0));
        assert!(certified(quotient(above, exact(1.0)), 1.0f64.next_up()));
        let below = Dw::diff(1.0, -(2f64.powi(-53))).sub(Dw::diff(2f64.powi(-80), 0.0));
        assert!(certified(quotient(below, exact(1.0)), 1.0));
        // A divisor whose sign the bound leaves open, and one exactly zero.
        assert_eq!(quotient(exact(1.0), Dw { hi: 1e-20, lo: 0.0, err: 1e-19, e: 0 }), None);
        assert_eq!(quotient(exact(1.0), exact(0.0)), None);
    }

    #[test]
    fn the_guards_are_the_powers_of_two_they_name() {
        assert_eq!(SCALE_LOSS.to_bits(), 2f64.powi(-1073).to_bits());
        assert_eq!(PROD_MIN.to_bits(), 2f64.powi(-969).to_bits());
        assert_eq!(SPLIT_MAX.to_bits(), 2f64.powi(995).to_bits());
        assert_eq!(UNDERFLOW_ERR.to_bits(), 2f64.powi(-1021).to_bits());
    }

    #[test]
    fn products_beyond_the_range_of_f64_are_exact_with_the_exponent() {
        // 2^-530 · 2^-530 = 2^-1060 and 2^1000 · 2^1000 = 2^2000: exact, with
        // their words near 1; back to 1 exactly.
        let tiny = exact(2f64.powi(-530)).mul(exact(2f64.powi(-530)));
        let huge = exact(2f64.powi(1000)).mul(exact(2f64.powi(1000)));
        assert!(tiny.err == 0.0 && huge.err == 0.0, "{tiny:?} {huge:?}");
        let one = tiny.mul(huge).mul(exact(2f64.powi(-940)));
        assert!(certified(quotient(one, exact(1.0)), 1.0), "{one:?}");
        // The smallest subnormal, squared, is 2^-2148: its sign is known.
        let sub = exact(f64::from_bits(1)).mul(exact(f64::from_bits(1)));
        assert_eq!(sub.sign(), Some(1));
        assert!(sub.err == 0.0);
        // MAX + MAX − 2·MAX is exactly 0.
        let max = exact(f64::MAX);
        assert_eq!(max.add(max).sub(max.mul(exact(2.0))).sign(), Some(0));
        // 1 + 2^-100 − 1 is 2^-100 exactly; 2^900 + 2^-900 − 2^900 is beyond
        // two words: only a bound on the small term is kept, and its sign is
        // left open rather than guessed.
        let (a, b) = (exact(1.0), exact(2f64.powi(-100)));
        assert!(certified(quotient(a.add(b).sub(a), exact(1.0)), 2f64.powi(-100)));
        let (a, b) = (exact(2f64.powi(900)), exact(2f64.powi(-900)));
        assert_eq!(a.add(b).sub(a).sign(), None);
    }

    #[test]
    fn the_product_guards_still_hold_on_raw_words() {
        // Dekker's product is refused where the splitter would overflow, and
        // kept rounded with a bound where its error term would underflow.
        assert_eq!(guarded_prod(2f64.powi(1000), 1.0), None);
        let (p, e, u) = guarded_prod(2f64.powi(-500), 2f64.powi(-500)).expect("splits");
        assert!(p > 0.0 && e == 0.0 && u == UNDERFLOW_ERR);
    }

    #[test]
    fn quotients_are_certified_down_to_the_subnormals() {
        // 2^-1000 / (3·2^20) = 2^-1020/3, normal: the correct rounding.
        let want = (1.0 / 3.0) * 2f64.powi(-1020);
        assert!(certified(quotient(exact(2f64.powi(-1000)), exact(3.0 * 2f64.powi(20))), want));
        // 2^-1070 / 3 is subnormal: rounded on the subnormal grid, as IEEE
        // division (correctly rounded there too) gives it.
        let x = 2f64.powi(-1070);
        assert!(certified(quotient(exact(x), exact(3.0)), x / 3.0));
        // Values that round to zero keep their sign; an exact zero is +0.0.
        let tiny = exact(f64::from_bits(1)).mul(exact(f64::from_bits(1)));
        assert!(certified(quotient(tiny, exact(-3.0)), -0.0));
        assert!(certified(quotient(tiny, exact(3.0)), 0.0));
        // Half the smallest subnormal is a tie between 0 and it: the exact
        // stage's to round.
        assert_eq!(quotient(exact(f64::from_bits(1)), exact(2.0)), None);
        // A quotient beyond MAX is the exact stage's.
        assert_eq!(quotient(exact(f64::MAX), exact(0.5)), None);
    }

    #[test]
    fn every_finite_input_is_admitted() {
        assert!(all_finite([0.0, -0.0, 1.0, f64::MAX, -f64::MAX, f64::from_bits(1), 2f64.powi(-1022)]));
        assert!(!all_finite([f64::NAN]));
        assert!(!all_finite([1.0, f64::INFINITY]));
    }
}
