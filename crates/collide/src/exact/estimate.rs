//! Values of predicates held beyond `f64`'s range: `mant · 2^exp`.

use super::Sign;

/// The relative accuracy the queries ask of the values they compute with
/// (2^−40 ≈ 9.1e-13), and the bound a value requested at this accuracy meets:
/// `|estimate − exact| ≤ ESTIMATE_REL_ERR · |exact|`.
///
/// Reason: well below what crashtest's tolerances look at (a segment parameter
/// within ~2e-12 puts a hit point within 2e-10 on a 100-unit segment), yet large
/// enough that the fast path meets it for nearly every random input: Shewchuk's
/// orient3d bound is about `7.8e-16` of the permanent, so a single volume meets
/// it when it is above about 1/1200 of its permanent, and a set of volumes
/// refined jointly ([`Estimate::refine_jointly`]) when their sum is. At 2^−42
/// about 1% of random segment–triangle hits needed the exact path; at 2^−40,
/// none in 5000.
pub const ESTIMATE_REL_ERR: f64 = 9.094947017729282e-13; // 2^−40

/// Relative error of a value rounded from the exact path: the top 128 bits
/// rounded to `f64` (`2^−53 + 2^−127`), stated as 2^−52.
pub(crate) const EXACT_REL_ERR: f64 = f64::EPSILON;

/// A real value with an exact sign and a magnitude known to within a stated
/// relative error, held as `sign · mant · 2^exp` with `mant ∈ [0.5, 1)`
/// (zero: `mant == 0`) so that it neither overflows nor underflows: an orient3d
/// volume of a `1e300` scene (`~1e900`) or of a `1e-300` one (`~1e-900`) is
/// represented as well as one of a unit scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The exact sign.
    pub sign: Sign,
    /// The magnitude's mantissa, in `[0.5, 1)`, or `0` for zero.
    pub mant: f64,
    /// The binary exponent.
    pub exp: i64,
    /// A bound on the relative error of the magnitude:
    /// `|mant · 2^exp − |exact|| ≤ rel_err · |exact|` (0 for exact zeros; it may
    /// exceed 1 for a value whose sign is all the fast path could certify).
    pub rel_err: f64,
}

impl Estimate {
    /// Zero, exactly.
    pub const ZERO: Self = Self { sign: Sign::Zero, mant: 0.0, exp: 0, rel_err: 0.0 };

    /// `x · 2^exp` for a finite `x` (no rounding: the mantissa is `x`'s), with
    /// the given relative error bound.
    #[inline]
    pub fn from_scaled(x: f64, exp: i64, rel_err: f64) -> Self {
        if x == 0.0 || !x.is_finite() {
            return Self::ZERO;
        }
        let (mant, e) = frexp(x.abs());
        Self { sign: Sign::of(x), mant, exp: e + exp, rel_err }
    }

    /// The value as an `f64`: `±∞` above `f64::MAX`, rounded into the subnormals
    /// and then to `±0` below `f64::MIN_POSITIVE`.
    pub fn to_f64(self) -> f64 {
        let m = match self.sign {
            Sign::Zero => return 0.0,
            Sign::Negative => -self.mant,
            Sign::Positive => self.mant,
        };
        ldexp(m, self.exp)
    }

    /// The magnitudes on a common exponent (the largest is in `[0.5, 1)`), or
    /// `None` when all are zero.
    fn common_scale<const N: usize>(xs: &[Estimate; N]) -> Option<[f64; N]> {
        let emax = xs.iter().filter(|x| x.mant != 0.0).map(|x| x.exp).max()?;
        Some(xs.map(|x| if x.mant == 0.0 { 0.0 } else { ldexp(x.mant, x.exp - emax) }))
    }

    /// `Σ_j |x_j| · rel_err_j / Σ_j |x_j|`: the error of the estimates relative
    /// to their sum. It bounds the absolute error of every fraction from
    /// [`Estimate::abs_fractions`] (times 2) and of every component of
    /// [`Estimate::unit_vector`] (times about 3), apart from rounding. 0 when
    /// all are zero.
    pub fn joint_error<const N: usize>(xs: &[Estimate; N]) -> f64 {
        let Some(m) = Self::common_scale(xs) else {
            return 0.0;
        };
        let sum: f64 = m.iter().sum();
        let err: f64 = m.iter().zip(xs).map(|(v, x)| v * x.rel_err).sum();
        // Rounding of the two sums (≤ N + 1 roundings each) is negligible next
        // to the tolerances this is compared with; one ulp of slack is added.
        err / sum * (1.0 + 4.0 * f64::EPSILON)
    }

    /// Makes `xs` accurate as a whole: if their [`joint_error`](Self::joint_error)
    /// exceeds `tol`, every estimate whose own `rel_err` exceeds `tol` is replaced
    /// by `refine(i)` (which must return an estimate within `tol`), so the joint
    /// error ends at most `tol`. A small, loosely known term next to large ones
    /// costs nothing: that is what keeps the exact path rare.
    pub fn refine_jointly<const N: usize>(
        mut xs: [Estimate; N],
        tol: f64,
        mut refine: impl FnMut(usize) -> Estimate,
    ) -> [Estimate; N] {
        if Self::joint_error(&xs) > tol {
            for (i, x) in xs.iter_mut().enumerate() {
                if x.rel_err > tol {
                    *x = refine(i);
                }
            }
        }
        xs
    }

    /// `|x_i| / Σ_j |x_j|` for each `i`: the estimates' magnitudes normalized by
    /// their sum, computed on a common exponent so that no term overflows or
    /// underflows spuriously. Each result is in `[0, 1]`; they sum to 1 within
    /// `N` roundings. Each is within `2 · joint_error + (N + 1)·2^−53` of the
    /// exact fraction. `None` when every `x_i` is zero.
    pub fn abs_fractions<const N: usize>(xs: [Estimate; N]) -> Option<[f64; N]> {
        let m = Self::common_scale(&xs)?;
        let sum: f64 = m.iter().sum();
        Some(m.map(|v| (v / sum).clamp(0.0, 1.0)))
    }

    /// The signed vector `x / ‖x‖` of three estimates (each component within
    /// about `3 · joint_error + 3·2^−53` of the exact unit vector's,
    /// absolutely). `None` when all three are zero.
    pub fn unit_vector(xs: [Estimate; 3]) -> Option<[f64; 3]> {
        let m = Self::common_scale(&xs)?;
        // Each component in (−1, 1), the largest of magnitude ≥ 0.5: the norm
        // below neither overflows nor underflows.
        let v = [0, 1, 2].map(|i| match xs[i].sign {
            Sign::Negative => -m[i],
            _ => m[i],
        });
        let norm = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        Some(v.map(|c| c / norm))
    }
}

/// `2^e` for `e ∈ [−1022, 1023]` (a normal power of two, built from its bits).
#[inline]
pub(crate) fn pow2(e: i64) -> f64 {
    debug_assert!((-1022..=1023).contains(&e), "pow2({e}) out of range");
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// `x · 2^e` for any `e`, in steps of at most `2^±1000` (each step exact
/// unless the result leaves the normal range, where it overflows to `±∞` or
/// rounds into the subnormals once).
#[inline]
pub(crate) fn ldexp(mut x: f64, mut e: i64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    // Beyond these the answer is ±∞ or ±0 whatever `x` is (|x| < 2^1024 and
    // ≥ 2^−1074).
    if e > 2200 {
        return x * f64::INFINITY;
    }
    if e < -2200 {
        return x * 0.0;
    }
    while e > 1000 {
        x *= pow2(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= pow2(-1000);
        e += 1000;
    }
    x * pow2(e)
}

/// `(m, e)` with `x = m · 2^e` and `m ∈ [0.5, 1)`, for finite `x > 0`
/// (subnormals included); `(0, 0)` for zero.
#[inline]
pub(crate) fn frexp(x: f64) -> (f64, i64) {
    const FRACTION: u64 = (1u64 << 52) - 1;
    if x == 0.0 {
        return (0.0, 0);
    }
    let (x, shift) = if x < f64::MIN_POSITIVE { (x * pow2(64), -64) } else { (x, 0) };
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let mant = f64::from_bits((bits & FRACTION) | (1022u64 << 52));
    (mant, biased - 1022 + shift)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact results: `frexp` and `ldexp` only move exponents.
    const EXACT: f64 = 0.0; // no error allowed, absolute

    #[test]
    fn frexp_and_ldexp_invert_each_other() {
        for x in [1.0, 0.75, 3.0, 1e300, f64::MAX, f64::MIN_POSITIVE, 5e-324, 1.5e-310] {
            let (m, e) = frexp(x);
            assert!((0.5..1.0).contains(&m), "mantissa of {x:e} is {m}");
            assert!((ldexp(m, e) - x).abs() <= EXACT, "{x:e} ↦ ({m}, {e}) does not invert");
        }
    }

    #[test]
    fn fractions_survive_extreme_exponents() {
        // 1·2^5000 and 3·2^5000 are 1/4 and 3/4 of their sum; a third value
        // 2^−5000 smaller is negligible.
        const TOL: f64 = 4.0 * f64::EPSILON; // a few roundings, absolute on [0, 1]
        let a = Estimate { sign: Sign::Positive, mant: 0.5, exp: 5001, rel_err: 0.0 };
        let b = Estimate { sign: Sign::Negative, mant: 0.75, exp: 5002, rel_err: 0.0 };
        let c = Estimate { sign: Sign::Positive, mant: 0.5, exp: 1, rel_err: 0.5 };
        let f = Estimate::abs_fractions([a, b, c]).expect("non-zero");
        assert!((f[0] - 0.25).abs() <= TOL, "{f:?}");
        assert!((f[1] - 0.75).abs() <= TOL, "{f:?}");
        assert!(f[2].abs() <= TOL, "{f:?}");
        // c's large relative error hardly counts next to a and b.
        assert!(Estimate::joint_error(&[a, b, c]) <= TOL, "joint error");
        let refined = Estimate::refine_jointly([a, b, c], TOL, |_| panic!("nothing to refine"));
        assert!(refined[2].rel_err > TOL, "c kept as it was");
        // Alone with an equal partner, it counts: half its error.
        let d = Estimate { sign: Sign::Positive, mant: 0.5, exp: 1, rel_err: 0.0 };
        let je = Estimate::joint_error(&[c, d]);
        assert!((je - 0.25).abs() <= TOL, "joint error {je}");
        let refined = Estimate::refine_jointly([c, d], TOL, |i| {
            assert!(i == 0, "only the loose one is refined");
            Estimate { rel_err: 0.0, ..c }
        });
        assert!(Estimate::joint_error(&refined) <= TOL, "refined");
        assert!(Estimate::abs_fractions([Estimate::ZERO; 2]).is_none(), "all zero");
        let u = Estimate::unit_vector([a, Estimate::ZERO, b]).expect("non-zero");
        let want = [1.0 / 10f64.sqrt(), 0.0, -3.0 / 10f64.sqrt()];
        for i in 0..3 {
            assert!((u[i] - want[i]).abs() <= TOL, "{u:?} vs {want:?}");
        }
    }
}
