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
//! underflows, and every product guards that itself: a factor too large to
//! split, or a sum that overflows, makes the result unknown (every sign test
//! on it open); a product below `2^-969`, where Dekker's error term would
//! underflow, is kept rounded with a bound on what it lost ([`guarded_prod`]).
//! So the bounds hold at any magnitude. [`in_range`] is a cheap filter on top:
//! it admits inputs of magnitude 0 or within `[2^-INPUT_EXP, 2^INPUT_EXP]`,
//! where the stage's products of degree up to 6 stay clear of both ends, and
//! a quotient is certified only within `[2^-QUOTIENT_EXP, 2^QUOTIENT_EXP]`.
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

/// Inputs are admitted of magnitude 0 or within `[2^-INPUT_EXP, 2^INPUT_EXP]`.
const INPUT_EXP: i32 = 100;

/// A quotient is certified only within `[2^-QUOTIENT_EXP, 2^QUOTIENT_EXP]`.
const QUOTIENT_EXP: i32 = 300;

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

/// A double-word number: the exact value lies within `err` of `hi + lo`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dw {
    hi: f64,
    lo: f64,
    err: f64,
}

impl Dw {
    /// `a − b`, exactly.
    pub(crate) fn diff(a: f64, b: f64) -> Dw {
        let (hi, lo) = two_sum(a, -b);
        Dw { hi, lo, err: 0.0 }
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
        Dw { hi: -self.hi, lo: -self.lo, err: self.err }
    }

    pub(crate) fn add(self, o: Dw) -> Dw {
        let (s, e1) = two_sum(self.hi, o.hi);
        let (t, e2) = two_sum(self.lo, o.lo);
        let (v, e3) = two_sum(e1, t);
        let (w, e4) = two_sum(v, e2);
        let (hi, lo) = two_sum(s, w);
        if !(hi.is_finite() && lo.is_finite()) {
            return Dw::UNKNOWN;
        }
        // self + o = s + e1 + t + e2 = s + v + e3 + e2 = s + w + e4 + e3 = hi + lo + e3 + e4
        // (two_sum is exact at any magnitude, subnormal included, short of overflow).
        Dw { hi, lo, err: (self.err + o.err + e3.abs() + e4.abs()) * UP }
    }

    /// A value about which nothing is known: every sign test on it is open.
    const UNKNOWN: Dw = Dw { hi: 0.0, lo: 0.0, err: f64::INFINITY };

    pub(crate) fn sub(self, o: Dw) -> Dw {
        self.add(o.neg())
    }

    pub(crate) fn mul(self, o: Dw) -> Dw {
        if !(self.err.is_finite() && o.err.is_finite()) {
            return Dw::UNKNOWN;
        }
        let (Some((p, e0, u0)), Some((a, ea, ua)), Some((b, eb, ub)), Some((c, ec, uc))) = (
            guarded_prod(self.hi, o.hi),
            guarded_prod(self.hi, o.lo),
            guarded_prod(self.lo, o.hi),
            guarded_prod(self.lo, o.lo),
        ) else {
            return Dw::UNKNOWN;
        };
        let (s1, f1) = two_sum(a, b);
        let (s2, f2) = two_sum(s1, c);
        let (s3, f3) = two_sum(e0, s2);
        let (hi, lo) = two_sum(p, s3);
        if !(hi.is_finite() && lo.is_finite()) {
            return Dw::UNKNOWN;
        }
        // (hi + lo) of the product = p + s3 exactly; the terms dropped are
        // f1 + f2 + f3 + ea + eb + ec, and what an underflowing product lost.
        let dropped = f1.abs() + f2.abs() + f3.abs() + ea.abs() + eb.abs() + ec.abs() + u0 + ua + ub + uc;
        // With x = x̃ + δx, y = ỹ + δy: |xy − x̃ỹ| ≤ |x̃|·|δy| + |ỹ|·|δx| + |δx|·|δy|.
        let carried = self.mag() * o.err + o.mag() * self.err + self.err * o.err;
        // Computing the bound in f64 may underflow a product of tiny terms to
        // 0: a carried error that is not exactly 0 gets UNDERFLOW_ERR more.
        let floor = if self.err > 0.0 || o.err > 0.0 { UNDERFLOW_ERR } else { 0.0 };
        Dw { hi, lo, err: (carried + dropped) * UP + floor }
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

/// Whether every input is 0 or of magnitude within the module's range.
pub(crate) fn in_range(xs: impl IntoIterator<Item = f64>) -> bool {
    let (lo, hi) = (2f64.powi(-INPUT_EXP), 2f64.powi(INPUT_EXP));
    xs.into_iter().all(|x| x == 0.0 || (x.abs() >= lo && x.abs() <= hi))
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
/// `x` (at most a few times). A candidate below `2^-QUOTIENT_EXP` is `+0.0`
/// when `side(0)` proves `x` exactly 0 (as the exact stage rounds the
/// rational 0). A midpoint exactly (a tie), an open sign, any other candidate
/// outside `[2^-QUOTIENT_EXP, 2^QUOTIENT_EXP]` gives `None`.
pub(crate) fn certify(mut r: f64, side: impl Fn(Dw) -> Option<i8>) -> Option<f64> {
    let (lo, hi) = (2f64.powi(-QUOTIENT_EXP), 2f64.powi(QUOTIENT_EXP));
    // The candidate may be off by an ulp or two; each step moves it one.
    for _ in 0..4 {
        if !(r.abs() >= lo && r.abs() <= hi) {
            // A value exactly 0 (touching, say) is +0.0, as the exact stage
            // rounds the rational 0; anything else this small is left to it.
            return (r.abs() < lo && side(Dw::of(0.0))? == 0).then_some(0.0);
        }
        let (up, down) = (r.next_up() - r, r - r.next_down());
        let at = |half: f64| Dw { hi: r, lo: half, err: 0.0 };
        match (side(at(-down / 2.0))?, side(at(up / 2.0))?) {
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
    let r = s.approx().sqrt();
    if !(r > 0.0 && r.is_finite()) {
        return Dw::of(r);
    }
    let (p, e) = two_prod(r, r);
    let residual = ((s.hi - p) - e) + s.lo;
    let (hi, lo) = two_sum(r, residual / (2.0 * r));
    Dw { hi, lo, err: 0.0 }
}

/// `a / b` to about twice `f64`'s precision (one correction step): a
/// candidate's ingredient, not a bound.
pub(crate) fn div_approx(a: Dw, b: Dw) -> Dw {
    let q0 = a.approx() / b.approx();
    if !q0.is_finite() {
        return Dw::of(q0);
    }
    let residual = a.sub(Dw::of(q0).mul(b));
    let (hi, lo) = two_sum(q0, residual.approx() / b.approx());
    Dw { hi, lo, err: 0.0 }
}

impl Dw {
    /// An input, exactly.
    pub(crate) fn of(x: f64) -> Dw {
        Dw { hi: x, lo: 0.0, err: 0.0 }
    }

    /// The nearest `f64` to `hi + lo` (a candidate: not certified).
    pub(crate) fn approx(self) -> f64 {
        self.hi + self.lo
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
        Dw { hi: x, lo: 0.0, err: 0.0 }
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
        assert_eq!(quotient(exact(1.0), Dw { hi: 1e-20, lo: 0.0, err: 1e-19 }), None);
        assert_eq!(quotient(exact(1.0), exact(0.0)), None);
    }

    #[test]
    fn the_guards_are_the_powers_of_two_they_name() {
        assert_eq!(PROD_MIN.to_bits(), 2f64.powi(-969).to_bits());
        assert_eq!(SPLIT_MAX.to_bits(), 2f64.powi(995).to_bits());
        assert_eq!(UNDERFLOW_ERR.to_bits(), 2f64.powi(-1021).to_bits());
    }

    #[test]
    fn products_near_underflow_or_overflow_are_bounded_not_trusted() {
        // 2^-500 · 2^-500 underflows: the product is kept with a bound, so its
        // sign stays known (2^-1000 far above 2^-1021) but it is not exact.
        let t = exact(2f64.powi(-500)).mul(exact(2f64.powi(-500)));
        assert_eq!(t.sign(), Some(1));
        assert!(t.err > 0.0);
        // 2^-530 · 2^-530 = 2^-1060 is below the bound: its sign is open.
        assert_eq!(exact(2f64.powi(-530)).mul(exact(2f64.powi(-530))).sign(), None);
        // Too large to split, and a sum that overflows: nothing is known.
        assert_eq!(exact(2f64.powi(1000)).mul(exact(1.0)).sign(), None);
        assert_eq!(exact(f64::MAX).add(exact(f64::MAX)).sign(), None);
    }

    #[test]
    fn only_inputs_within_the_range_are_admitted() {
        assert!(in_range([0.0, -0.0, 1.0, 2f64.powi(100), -(2f64.powi(-100))]));
        assert!(!in_range([2f64.powi(101)]));
        assert!(!in_range([2f64.powi(-101)]));
        assert!(!in_range([f64::NAN]));
    }
}
