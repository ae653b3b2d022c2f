//! The robust method's filter arithmetic: `f64` values carried with a
//! rigorous bound on their absolute error (running error analysis, in the
//! manner of Wilkinson's and of the midpoint–radius intervals of
//! Rump's `INTLAB`, with the bound rounded up).
//!
//! A [`Fe`] `(v, e)` stands for an unknown real `x` with `|x − v| ≤ e`. Every
//! operation below keeps that true:
//!
//! - `x + y`, `x − y`: `|(x ± y) − fl(v_x ± v_y)| ≤ e_x + e_y + u |fl(·)| / (1 − u)`;
//! - `x · y`: `|xy − fl(v_x v_y)| ≤ |v_x| e_y + |v_y| e_x + e_x e_y +
//!   u |fl(·)| / (1 − u) + 2^−1075` (the last term: an underflowing product
//!   errs by at most half the smallest subnormal);
//!
//! with `u = 2^−53`. Each new bound is a sum of at most five non-negative
//! terms computed with rounding to nearest, so it may come out low by a
//! factor `(1 − u)^5`; it is multiplied by [`GROW`] `= 1 + 16u`, which covers
//! that, the `1/(1 − u)` above, and the multiplication's own rounding, and
//! [`ETA`] `= 2^−1073` is added (the underflow term, and the bound's own
//! roundings if they underflow). An overflow makes `e` infinite (or NaN),
//! and such a value decides nothing ([`Fe::sign`]).

use crate::exact::{P3, Sign};

/// Unit roundoff of `f64` (2^−53).
const U: f64 = 1.1102230246251565e-16;

/// Factor on every new bound: `1 + 16u` (see the module documentation).
const GROW: f64 = 1.0 + 16.0 * U;

/// Absolute slack added to every new bound: `2^−1073` (see the module
/// documentation).
const ETA: f64 = 2.0 * 5e-324;

/// A value with a bound on its absolute error.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fe {
    v: f64,
    e: f64,
}

impl Fe {
    /// An exact value.
    #[inline(always)]
    pub(crate) fn exact(v: f64) -> Self {
        Self { v, e: 0.0 }
    }

    /// The bound on the error.
    #[inline(always)]
    pub(crate) fn bound(self) -> f64 {
        self.e
    }

    /// The certain sign of the exact value, if the bound decides it (never
    /// [`Sign::Zero`]: an exact zero is not certified here).
    #[inline(always)]
    pub(crate) fn sign(self) -> Option<Sign> {
        if !(self.e < f64::INFINITY) || !self.v.is_finite() {
            return None;
        }
        if self.v > self.e {
            Some(Sign::Positive)
        } else if -self.v > self.e {
            Some(Sign::Negative)
        } else {
            None
        }
    }

    #[inline(always)]
    fn add(self, o: Self) -> Self {
        let v = self.v + o.v;
        Self { v, e: (self.e + o.e + U * v.abs()) * GROW + ETA }
    }

    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        let v = self.v - o.v;
        Self { v, e: (self.e + o.e + U * v.abs()) * GROW + ETA }
    }

    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let v = self.v * o.v;
        Self { v, e: (self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + U * v.abs()) * GROW + ETA }
    }
}

impl core::ops::Add for Fe {
    type Output = Fe;
    #[inline(always)]
    fn add(self, o: Fe) -> Fe {
        Fe::add(self, o)
    }
}

impl core::ops::Sub for Fe {
    type Output = Fe;
    #[inline(always)]
    fn sub(self, o: Fe) -> Fe {
        Fe::sub(self, o)
    }
}

impl core::ops::Mul for Fe {
    type Output = Fe;
    #[inline(always)]
    fn mul(self, o: Fe) -> Fe {
        Fe::mul(self, o)
    }
}

/// A point or direction of [`Fe`]s.
pub(crate) type FeV = [Fe; 3];

/// An exact point.
#[cfg(test)]
pub(crate) fn exact3(p: P3) -> FeV {
    p.map(Fe::exact)
}

/// `x − y`.
#[inline(always)]
pub(crate) fn sub3(x: &FeV, y: &FeV) -> FeV {
    [x[0] - y[0], x[1] - y[1], x[2] - y[2]]
}

/// `x · y`.
#[inline(always)]
pub(crate) fn dot3(x: &FeV, y: &FeV) -> Fe {
    x[0] * y[0] + x[1] * y[1] + x[2] * y[2]
}

/// `x × y`.
#[inline(always)]
pub(crate) fn cross3(x: &FeV, y: &FeV) -> FeV {
    [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]]
}

/// `det[x, y, z] = (x × y) · z`.
#[inline(always)]
pub(crate) fn det3(x: &FeV, y: &FeV, z: &FeV) -> Fe {
    dot3(&cross3(x, y), z)
}

/// The positions at every time `t ∈ [t_lo, t_hi]` (doubles, `0 ≤ t_lo ≤
/// t_hi`) of points moving linearly from `x0` to `x1`: `x0 + t_lo (x1 − x0)`,
/// whose bound also covers the motion over the interval,
/// `|x1 − x0| (t_hi − t_lo)` (the difference's rounding, at most `u` relative,
/// covered by one more `GROW`).
pub(crate) fn positions<const N: usize>(x0: &[P3; N], x1: &[P3; N], t_lo: f64, t_hi: f64) -> [FeV; N] {
    let width = Fe::exact(t_hi - t_lo).v * GROW;
    core::array::from_fn(|i| {
        core::array::from_fn(|k| {
            let (a, b) = (Fe::exact(x0[i][k]), Fe::exact(x1[i][k]));
            let d = b - a;
            let x = a + Fe::exact(t_lo) * d;
            let spread = (d.v.abs() + d.e) * width * GROW + ETA;
            Fe { v: x.v, e: (x.e + spread) * GROW + ETA }
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::BigFloat;
    use proptest::prelude::*;

    fn bf(x: f64) -> BigFloat {
        BigFloat::from_f64(x)
    }

    /// Whether `|exact − v| ≤ e`, decided exactly.
    fn covers(exact: &BigFloat, f: Fe) -> bool {
        let err = exact - &bf(f.v);
        (&bf(f.e) - &err).sign() != Sign::Negative && (&bf(f.e) + &err).sign() != Sign::Negative
    }

    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![
            -1.0e3..1.0e3f64,
            (-1.0..1.0f64, -300i32..300).prop_map(|(m, e)| m * 2f64.powi(e)),
            Just(0.0),
            (-1.0..1.0f64).prop_map(|x| 1.0 + x * 1e-15),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// A determinant of differences is within its bound of the exact one.
        #[test]
        fn determinant_bound_holds(x in proptest::array::uniform12(coord())) {
            let p = |i: usize| [x[3 * i], x[3 * i + 1], x[3 * i + 2]];
            let (a, b, c, d) = (exact3(p(0)), exact3(p(1)), exact3(p(2)), exact3(p(3)));
            let f = det3(&sub3(&b, &a), &sub3(&c, &a), &sub3(&d, &a));
            let bd = |i: usize| [bf(x[3 * i]), bf(x[3 * i + 1]), bf(x[3 * i + 2])];
            let (ea, eb, ec, ed) = (bd(0), bd(1), bd(2), bd(3));
            let u = crate::exact::bigfloat::sub3(&eb, &ea);
            let v = crate::exact::bigfloat::sub3(&ec, &ea);
            let w = crate::exact::bigfloat::sub3(&ed, &ea);
            let exact = crate::exact::bigfloat::dot3(&crate::exact::bigfloat::cross3(&u, &v), &w);
            prop_assert!(!f.v.is_finite() || !f.e.is_finite() || covers(&exact, f), "{f:?}");
        }
    }
}
