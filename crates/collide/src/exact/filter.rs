//! The queries' inline filter: plain `f64` evaluations of the volumes and dot
//! products a query needs, each with a static forward error bound (in the
//! manner of Shewchuk's stage-A filters), computed together so that shared
//! differences and cross products are formed once.
//!
//! A query first checks [`in_fast_range`] on all its inputs. Within that range
//! (every coordinate `|x| ≤ 2^63`) no difference exceeds `2^64`, no product of
//! three differences exceeds `2^192`, so nothing overflows; a product that
//! underflows errs by at most `2^−1075`, and every such error is covered by
//! [`UNDERFLOW_SLACK`]. A [`Filtered`] value whose magnitude exceeds its bound
//! has the sign of the exact value, and its magnitude is known to
//! `bound / (|value| − bound)` relative. When a value is not decided (or the
//! inputs are out of range) the query falls back to the predicates of
//! [`crate::exact`] (their own scaled filter, then the exact path); the
//! fallback is rare for random input and costs what it always cost.
//!
//! Error analysis (standard, with `u = 2^−53` and `γ_k = k u / (1 − k u)`):
//! a rounded difference is `d = d*(1 + δ)`, `|δ| ≤ u`; a cross-product
//! component `c = fl(fl(p_j q_k) − fl(p_k q_j))` of rounded differences is
//! within `γ4 (|p*_j q*_k| + |p*_k q*_j|)` of the exact one (two roundings of
//! the factors, one of the product, one of the subtraction); the dot product
//! `((c_x w_x + c_y w_y) + c_z w_z)` with a rounded `w` then errs by at most
//! `γ4 (2 + γ4) Σ |w*_i| P*_i`, `P*_i` the exact permanents of the cross
//! components. The computed permanent `((P_x |w_x| + P_y |w_y|) + P_z |w_z|)`
//! is at least `(1 − γ8)` times the exact one. Hence [`TRIPLE_BOUND`] and
//! [`CROSS_BOUND`] below, each with room for the rounding of the bound's own
//! product.

use super::P3;

/// Unit roundoff of `f64` (2^−53).
const U: f64 = 1.1102230246251565e-16;

/// Largest input magnitude of the fast path (2^63): differences stay within
/// `2^64` and products of three within `2^192`, far from overflow.
pub(crate) const FAST_MAX: f64 = 9_223_372_036_854_775_808.0;

/// Error bound of a triple product `(p × q) · w` of rounded differences,
/// relative to its computed permanent: `γ4 (2 + γ4) / (1 − γ8) ≤ 8u + 114u²`,
/// and one more rounding of `bound = fl(TRIPLE_BOUND · permanent)`:
/// `(8 + 256u) u` covers both.
pub(crate) const TRIPLE_BOUND: f64 = (8.0 + 256.0 * U) * U;

/// Error bound of a cross-product component `p_j q_k − p_k q_j` of rounded
/// differences, relative to its computed permanent `|p_j q_k| + |p_k q_j|`:
/// `γ4 / (1 − γ4) ≤ 4u + 33u²`, plus the bound's own rounding: `(4 + 64u) u`.
pub(crate) const CROSS_BOUND: f64 = (4.0 + 64.0 * U) * U;

/// Error bound of `((x1 y1 + x2 y2) + x3 y3) − d` on exact inputs, relative to
/// its computed permanent `((|x1 y1| + |x2 y2|) + |x3 y3|) + |d|`: every term
/// passes through at most 4 roundings (`γ4`), the computed permanent is at
/// least `(1 − u)^4` times the exact one, and the bound's product rounds once:
/// `(4 + 64u) u`.
pub(crate) const PLANE_BOUND: f64 = (4.0 + 64.0 * U) * U;

/// Absolute slack for underflow (2^−1000). In the fast range a product of two
/// differences (`≤ 2^64` each) that underflows errs by at most `2^−1075`; it is
/// multiplied by at most one more difference (`≤ 2^64`), and a triple product
/// has at most 6 such products and 3 more that may underflow themselves:
/// `(6 · 2^64 + 3) · 2^−1075 · (1 + small) < 2^−1008`.
pub(crate) const UNDERFLOW_SLACK: f64 = 9.332636185032189e-302;

/// The relative-accuracy check of a set of filtered magnitudes: with the
/// computed magnitudes summing to `sum` and their bounds to `err`, the exact
/// magnitudes differ from the computed ones by at most `err` in total, and
/// their exact sum is at least `sum − err`; so the set is accurate to
/// `max_rel` of its exact sum when `err ≤ max_rel (sum − err)`. The two
/// computed sums (3 terms at most) carry at most 2 roundings each, and the
/// comparison's products 1 more: an `8u` margin on `err` covers them.
#[inline(always)]
pub(crate) fn jointly_accurate(err: f64, sum: f64, max_rel: f64) -> bool {
    err * (1.0 + 8.0 * U) <= max_rel * (sum - err)
}

/// Whether every value is within the fast range `|x| ≤ FAST_MAX` (false for
/// infinities and NaN). Branch-free.
#[inline(always)]
pub(crate) fn in_fast_range<const N: usize>(xs: [f64; N]) -> bool {
    xs.iter().fold(true, |ok, x| ok & (x.abs() <= FAST_MAX))
}

/// [`in_fast_range`] over points: every coordinate within `|x| ≤ FAST_MAX`.
/// Branch-free, and folded over the points as they are (no flattened copy,
/// whose reload through memory would stall on the stores just made).
#[inline(always)]
pub(crate) fn in_fast_range_points<const N: usize>(ps: [P3; N]) -> bool {
    ps.iter().fold(true, |ok, p| ok & (p[0].abs() <= FAST_MAX) & (p[1].abs() <= FAST_MAX) & (p[2].abs() <= FAST_MAX))
}

/// A value of the fast path and its error bound: the exact value lies in
/// `[value − bound, value + bound]`, and `bound > 0`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Filtered {
    /// The computed value.
    pub value: f64,
    /// The bound on its error.
    pub bound: f64,
}

impl Filtered {
    /// Whether the sign of `value` is the exact sign (then the exact value is
    /// non-zero).
    #[inline(always)]
    pub(crate) fn decided(&self) -> bool {
        self.value.abs() > self.bound
    }

    /// Whether the exact values of `self` and `other` certainly differ: the
    /// computed difference `g = fl(other − self)` is within `u |g|` of
    /// `other − self`, which is within both bounds of the exact difference,
    /// so `|g| (1 − u) > bound_self + bound_other` (with `4u` of margin for
    /// the comparison's own roundings) shows it non-zero.
    #[inline(always)]
    pub(crate) fn differs_from(&self, other: &Filtered) -> bool {
        (other.value - self.value).abs() * (1.0 - 4.0 * U) > self.bound + other.bound
    }
}

/// `a − b`, per component.
#[inline(always)]
pub(crate) fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `p × q` of (rounded) differences, with each component's computed
/// permanent `|p_j q_k| + |p_k q_j|`.
#[inline(always)]
pub(crate) fn cross(p: P3, q: P3) -> (P3, P3) {
    let (yz, zy) = (p[1] * q[2], p[2] * q[1]);
    let (zx, xz) = (p[2] * q[0], p[0] * q[2]);
    let (xy, yx) = (p[0] * q[1], p[1] * q[0]);
    ([yz - zy, zx - xz, xy - yx], [yz.abs() + zy.abs(), zx.abs() + xz.abs(), xy.abs() + yx.abs()])
}

/// The triple product `c · w` of a cross product `c` (with its permanents
/// `perm`, from [`cross`]) and a rounded difference `w`, with its
/// [`TRIPLE_BOUND`].
#[inline(always)]
pub(crate) fn triple(c: P3, perm: P3, w: P3) -> Filtered {
    let value = (c[0] * w[0] + c[1] * w[1]) + c[2] * w[2];
    let permanent = (perm[0] * w[0].abs() + perm[1] * w[1].abs()) + perm[2] * w[2].abs();
    Filtered { value, bound: TRIPLE_BOUND * permanent + UNDERFLOW_SLACK }
}

/// `n · p − d` on exact inputs, with its [`PLANE_BOUND`].
#[inline(always)]
pub(crate) fn plane(n: P3, d: f64, p: P3) -> Filtered {
    let (x, y, z) = (n[0] * p[0], n[1] * p[1], n[2] * p[2]);
    let value = ((x + y) + z) - d;
    let permanent = ((x.abs() + y.abs()) + z.abs()) + d.abs();
    Filtered { value, bound: PLANE_BOUND * permanent + UNDERFLOW_SLACK }
}

/// The error bound of each component of a [`cross`] product, from its
/// permanents.
#[inline(always)]
pub(crate) fn cross_bounds(perm: P3) -> P3 {
    perm.map(|p| CROSS_BOUND * p + UNDERFLOW_SLACK)
}

#[cfg(test)]
mod tests {
    use super::super::{BigFloat, Sign};
    use super::*;
    use proptest::prelude::*;

    fn bf(x: f64) -> BigFloat {
        BigFloat::from_f64(x)
    }

    fn diff(a: P3, b: P3) -> [BigFloat; 3] {
        [0, 1, 2].map(|i| &bf(a[i]) - &bf(b[i]))
    }

    fn exact_cross(p: &[BigFloat; 3], q: &[BigFloat; 3]) -> [BigFloat; 3] {
        [&(&p[1] * &q[2]) - &(&p[2] * &q[1]), &(&p[2] * &q[0]) - &(&p[0] * &q[2]), &(&p[0] * &q[1]) - &(&p[1] * &q[0])]
    }

    /// Whether `|exact − value| ≤ bound`, decided exactly.
    fn within(exact: &BigFloat, value: f64, bound: f64) -> bool {
        let err = exact - &bf(value);
        let lo = &err + &bf(bound);
        let hi = &bf(bound) - &err;
        lo.sign() != Sign::Negative && hi.sign() != Sign::Negative
    }

    /// Coordinates over many binades, zero included, and near-coincident pairs
    /// (so differences cancel): the bounds must hold for all of them.
    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![
            -1.0e3..1.0e3f64,
            (-1.0..1.0f64, -60i32..60).prop_map(|(m, e)| m * 2f64.powi(e)),
            Just(0.0),
            (-1.0..1.0f64).prop_map(|x| 1.0 + x * 1e-15),
        ]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coord(), coord(), coord()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// The triple product `((b − a) × (c − a)) · (q − a)` and each cross
        /// component are within their bounds of the exact values.
        #[test]
        fn triple_and_cross_bounds_hold(a in point(), b in point(), c in point(), q in point()) {
            prop_assume!(in_fast_range([a, b, c, q].concat().try_into().unwrap_or([f64::NAN; 12])));
            let (e1, e2, w) = (sub(b, a), sub(c, a), sub(q, a));
            let (n, perm) = cross(e1, e2);
            let exact_n = exact_cross(&diff(b, a), &diff(c, a));
            let nb = cross_bounds(perm);
            for i in 0..3 {
                prop_assert!(within(&exact_n[i], n[i], nb[i]), "cross component {i}");
            }
            let f = triple(n, perm, w);
            let ew = diff(q, a);
            let exact = &(&(&exact_n[0] * &ew[0]) + &(&exact_n[1] * &ew[1])) + &(&exact_n[2] * &ew[2]);
            prop_assert!(within(&exact, f.value, f.bound), "triple product");
        }

        /// `n · p − d` is within its bound of the exact value.
        #[test]
        fn plane_bound_holds(n in point(), p in point(), d in coord()) {
            let f = plane(n, d, p);
            let exact = &(&(&(&bf(n[0]) * &bf(p[0])) + &(&bf(n[1]) * &bf(p[1]))) + &(&bf(n[2]) * &bf(p[2]))) - &bf(d);
            prop_assert!(within(&exact, f.value, f.bound), "plane value");
        }
    }

    #[test]
    fn fast_range_rejects_non_finite_and_huge() {
        assert!(in_fast_range([0.0, -1e18, 9.2e18]));
        assert!(!in_fast_range([0.0, f64::NAN]));
        assert!(!in_fast_range([f64::INFINITY]));
        assert!(!in_fast_range([1e19]));
    }
}
