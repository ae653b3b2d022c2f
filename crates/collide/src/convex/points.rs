//! The points the robust distance decides about: plain `f64` points, and the
//! corners of a box as the format defines it, `c + R(q)·Σ_i s_i h_i e_i`
//! with `R(q)` the rotation of `q/‖q‖` (rational in `q`: the 3-4-5 box's
//! `3/5` is not a binary number).
//!
//! A point is an [`Xp`]: an `f64` value `v` and a bound `e` on each
//! coordinate's distance from the exact point (0 for a plain point, and for a
//! box corner that `f64` holds exactly: a box turned by a signed permutation,
//! whose corners `c ± h` round to nothing). The filters of
//! `super::predicates` run on `v` with `e` as the leaves' error; the exact
//! stage, on the exact corners: with `n = ‖q‖²` and `M_i = n R(q) e_i`
//! (quadratics in `q`, `crate::boxes::poly::quaternion_axes`), a corner is
//! `(n c + Σ_i s_i h_i M_i) / n`, and [`lift`] multiplies every point of a
//! predicate by the product `D > 0` of the `n` of the boxes among them, so
//! that each coordinate is a polynomial in the inputs. The predicates are
//! homogeneous in the coordinates: their signs are unchanged by `D`.

use super::predicates::Dd;
use crate::boxes::poly::{Filt, Ring, norm2, quaternion_axes};
use crate::boxes::stage::rotation;
use crate::exact::{BigFloat, P3, frexp, ldexp, points_equal};

/// Unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// What underflow may lose in one product or sum of a corner's evaluation
/// (`2^−1074`, counted twice).
const CORNER_UNDERFLOW: f64 = f64::from_bits(2);

/// The enlargement of a corner's computed bound for the rounding of its own
/// few operations (each off by a factor at most `1 + u`; `2^−30` is far
/// above).
const BOUND_SLACK: f64 = 1.0 + 1.0 / (1u64 << 30) as f64;

/// A box as the format defines it: the points `c + R(q) u`, `|u_i| ≤ |h_i|`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ExactBox {
    c: P3,
    h: P3,
    /// The quaternion, never zero (a zero one is the identity `[1, 0, 0, 0]`).
    q: [f64; 4],
}

/// A point: its `f64` value `v`, a bound `e` on the distance of each of its
/// coordinates from the exact one's, and, for a box corner, the box and the
/// corner's sign bits (bit `k` set: `+h_k`).
/// A corner's further data ([`Corner`]) lies behind a reference, so that
/// a point stays small.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Xp<'a> {
    pub v: P3,
    pub e: f64,
    pub x: Option<&'a Corner<'a>>,
}

/// A box corner: the box, its sign bits, and a double-double value `v + lo`
/// (`|lo|` at most half an ulp of `v`) with its bound `ed`, for the
/// predicates' double-double stage.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Corner<'a> {
    pub b: &'a ExactBox,
    pub bits: u8,
    pub lo: P3,
    pub ed: f64,
}

impl<'a> Xp<'a> {
    /// A plain point, exact.
    pub(crate) const fn plain(v: P3) -> Self {
        Self { v, e: 0.0, x: None }
    }

    /// The box and sign bits of a corner.
    #[inline]
    pub(crate) fn corner(&self) -> Option<(&'a ExactBox, u8)> {
        self.x.map(|c| (c.b, c.bits))
    }

    /// The low part of the double-double value (0 for a plain point).
    #[inline]
    pub(crate) fn lo(&self) -> P3 {
        self.x.map_or([0.0; 3], |c| c.lo)
    }

    /// The double-double value's bound (`e` for a plain point).
    #[inline]
    pub(crate) fn ed(&self) -> f64 {
        self.x.map_or(self.e, |c| c.ed)
    }
}

/// A corner's values: `v` and its bound `e`, `v + lo` and its bound `ed`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CornerValue {
    pub v: P3,
    pub e: f64,
    pub lo: P3,
    pub ed: f64,
}

impl<'a> Xp<'a> {
    /// When `self` and `o` are corners of one box: the box and the axes
    /// their signs differ in (`self − o` lies in the span of those axes).
    #[inline]
    pub(crate) fn box_diff(&self, o: &Xp<'a>) -> Option<(&'a ExactBox, u8)> {
        match (self.corner(), o.corner()) {
            (Some((x, s)), Some((y, t))) if std::ptr::eq(x, y) => Some((x, s ^ t)),
            _ => None,
        }
    }

    /// Whether `self` and `o` are one input point (the same plain value, or
    /// the same corner of one box): cheaper than [`same`], and only `true`
    /// when it is.
    #[inline]
    pub(crate) fn identical(&self, o: &Xp<'a>) -> bool {
        match (self.corner(), o.corner()) {
            (Some((x, s)), Some((y, t))) => std::ptr::eq(x, y) && s == t,
            _ => self.e == 0.0 && o.e == 0.0 && points_equal(self.v, o.v),
        }
    }
}

/// What `q`'s scaling may move an entry of `R(q)` by when a component
/// falls into the subnormals: each component by `2^−1074`, the entry by at
/// most four times that over `‖q‖ ≥ 1` (`|∂R/∂q| ≤ 4/‖q‖`), with room
/// (`2^−1068`).
const SCALED_Q_LOSS: f64 = f64::from_bits(7 << 52);

/// `(a + b, error)`, Knuth's TwoSum.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, two_sum_err(a, b, s))
}

/// Whether `a + b` rounds to `s` exactly, and the rounding error (Knuth's
/// TwoSum).
fn two_sum_err(a: f64, b: f64, s: f64) -> f64 {
    let bv = s - a;
    let av = s - bv;
    (a - av) + (b - bv)
}

impl ExactBox {
    /// Whether every half extent is positive: the eight corners are then
    /// distinct and span space, and the box's hull is known (its faces and
    /// edges, `super::hull`).
    pub(crate) fn solid(&self) -> bool {
        self.h.iter().all(|h| *h > 0.0)
    }

    /// `log₂ ‖q‖²`, within `16u` (the quaternion scaled by a power of two
    /// into `[1, 2)` at its largest component: four squares and three sums
    /// of non-negative terms, `4u` relative; the logarithm of a number in
    /// `[1, 16)` and the exponent added, a few ulps of a number below
    /// `2^12`).
    pub(crate) fn log2_norm2(&self) -> f64 {
        let m = self.q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let k = 1 - frexp(m).1;
        let n: f64 = self.q.iter().map(|x| ldexp(*x, k) * ldexp(*x, k)).sum();
        n.log2() - 2.0 * k as f64
    }

    /// The axes with a non-zero half extent, as a bit mask: a difference of
    /// two corners has no component along the others.
    pub(crate) fn nonzero(&self) -> u8 {
        (0..3).filter(|&i| self.h[i] != 0.0).fold(0, |m, i| m | 1 << i)
    }

    /// The box of centre `c`, half extents `h` and quaternion `q`; `None`
    /// when a number is not finite.
    pub(crate) fn new(c: P3, h: P3, q: [f64; 4]) -> Option<Self> {
        if !c.iter().chain(&h).chain(&q).all(|x| x.is_finite()) {
            return None;
        }
        let q = if q.iter().all(|x| *x == 0.0) { [1.0, 0.0, 0.0, 0.0] } else { q };
        Some(Self { c, h, q })
    }

    /// The axes `R(q) e_i` (as `[axis][coordinate]`) when every entry is
    /// exactly 0 or ±1 (a signed permutation: the identity, half turns, the
    /// quarter turns of `q = (1, 1, 0, 0)` and the like), decided from the
    /// quadratics `M_i` and `‖q‖²`, evaluated with exactness tracking on `q`
    /// scaled by a power of two (`None` when the scaling is not exact).
    fn exact_axes(&self) -> Option<[[f64; 3]; 3]> {
        let m = self.q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let k = 1 - frexp(m).1;
        let qs = self.q.map(|x| ldexp(x, k));
        if qs.iter().zip(&self.q).any(|(s, x)| ldexp(*s, -k).to_bits() != x.to_bits()) {
            return None;
        }
        let f = qs.map(Filt::exact);
        let r = [&f[0], &f[1], &f[2], &f[3]];
        let (n, nb) = norm2(r).parts();
        if nb != 0.0 || !(n > 0.0) {
            return None;
        }
        let axes = quaternion_axes(r);
        let mut out = [[0.0; 3]; 3];
        for (i, ax) in axes.iter().enumerate() {
            for (k, x) in ax.iter().enumerate() {
                let (v, b) = x.parts();
                #[expect(clippy::float_cmp, reason = "exact values, compared exactly")]
                let unit = v == n || v == -n || v == 0.0;
                if b != 0.0 || !unit {
                    return None;
                }
                out[i][k] = v / n;
            }
        }
        Some(out)
    }

    /// The eight corners' values and bounds (corner `i`: sign bit `k` of `i`
    /// set for `+h_k`): in double-double when the rotation is not a signed
    /// permutation ([`Self::corners_dd`]) and the scene lies within its range,
    /// else in `f64` as follows (`lo = 0`, `ed = e`); `None` when a corner's
    /// value is not finite.
    ///
    /// A signed permutation's corner coordinate is `c_k ± h_j`, one rounded
    /// sum whose error TwoSum gives exactly. Otherwise `R̃` from
    /// `crate::boxes::stage::rotation` (each entry within its bound `ε_ki` of
    /// `R(q)`'s), `t̃_i = fl(s_i h_i R̃_ki)` and three rounded sums from
    /// `c_k`: `|x̃_k − x_k| ≤ Σ|h_i| ε_ki + u Σ|t̃_i| + 3u(|c_k| + Σ|t̃_i|) +
    /// 6·2^−1074` to first order (the partial sums are below
    /// `|c_k| + Σ|t̃_i|`; each product and sum may lose `2^−1074` to
    /// underflow), enlarged by [`BOUND_SLACK`].
    pub(crate) fn corners(&self) -> Option<[CornerValue; 8]> {
        let c = self.corners_f64()?;
        let plain = c.map(|(v, e)| CornerValue { v, e, lo: [0.0; 3], ed: e });
        if self.exact_axes().is_some() {
            return Some(plain);
        }
        // Far below the normal range the double-double's underflow terms
        // can exceed the `f64` evaluation's bound: the tighter one.
        let worst = |c: &[CornerValue; 8]| c.iter().fold(0.0f64, |m, x| m.max(x.e));
        match self.corners_dd() {
            Some(d) if worst(&d) <= worst(&plain) => Some(d),
            _ => Some(plain),
        }
    }

    /// The rotation `R(q)` as double-doubles, each entry with a bound on its
    /// distance from the exact one (`[row][column]`), from `q` scaled by a
    /// power of two so that its largest component lies in `[1, 2)` (a
    /// component that falls into the subnormals moves by at most
    /// `2^−1074`, `R` by at most four times that: [`SCALED_Q_LOSS`]):
    /// `M_i` and `n = ‖q‖² ≥ 1` in [`Dd`] with their bounds, then each
    /// `M_ki/n` as `r₀ + r₁` (`r₀ = M/n` in `f64`, `r₁` the residual's
    /// quotient), whose error is `|M − n r|/n ≤ |res| + e_res` for the
    /// residual `res = M − n r` formed in [`Dd`] with its bound `e_res`.
    fn rotation_dd(&self) -> Option<[[Dd; 3]; 3]> {
        let m = self.q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let k = 1 - frexp(m).1;
        let qs = self.q.map(|x| ldexp(x, k));
        let lossy = qs.iter().zip(&self.q).any(|(s, x)| ldexp(*s, -k).to_bits() != x.to_bits());
        let f = qs.map(|x| Dd::new(x, 0.0, 0.0));
        let r = [&f[0], &f[1], &f[2], &f[3]];
        let n = norm2(r);
        let axes = quaternion_axes(r);
        let (nh, nl, _) = n.parts();
        let extra = if lossy { SCALED_Q_LOSS } else { 0.0 };
        let mut out = [[Dd::new(0.0, 0.0, 0.0); 3]; 3];
        for (i, ax) in axes.iter().enumerate() {
            for (kk, mk) in ax.iter().enumerate() {
                let (mh, _, _) = mk.parts();
                let r0 = mh / (nh + nl);
                let res = mk.sub(&n.mul(&Dd::new(r0, 0.0, 0.0)));
                let r1 = res.parts().0 / (nh + nl);
                let (hi, lo) = two_sum(r0, r1);
                let rr = Dd::new(hi, lo, 0.0);
                let (h2, l2, e2) = mk.sub(&n.mul(&rr)).parts();
                let e = (h2.abs() + l2.abs() + e2) * (1.0 + 8.0 * U) + extra;
                if !e.is_finite() || !hi.is_finite() {
                    return None;
                }
                out[kk][i] = Dd::new(hi, lo, e);
            }
        }
        Some(out)
    }

    /// The corners as double-doubles (`c_k + Σ_i s_i h_i R_ki` in [`Dd`] on
    /// [`Self::rotation_dd`]): `v + lo` within `ed` of the exact coordinate,
    /// `v` within `|lo| + ed`. `None` when a bound is not finite (a scene
    /// beyond [`Dd`]'s range).
    fn corners_dd(&self) -> Option<[CornerValue; 8]> {
        let r = self.rotation_dd()?;
        let mut out = [CornerValue::default(); 8];
        for (i, o) in out.iter_mut().enumerate() {
            let (mut e, mut ed) = (0.0f64, 0.0f64);
            for (k, row) in r.iter().enumerate() {
                let mut x = Dd::new(self.c[k], 0.0, 0.0);
                for (j, rkj) in row.iter().enumerate() {
                    let h = if i >> j & 1 == 1 { self.h[j] } else { -self.h[j] };
                    x = x.add(&Dd::new(h, 0.0, 0.0).mul(rkj));
                }
                let (hi, lo, xe) = x.parts();
                if !(hi.is_finite() && lo.is_finite() && xe.is_finite()) {
                    return None;
                }
                o.v[k] = hi;
                o.lo[k] = lo;
                ed = ed.max(xe);
                e = e.max((lo.abs() + xe) * (1.0 + 4.0 * U));
            }
            (o.e, o.ed) = (e, ed);
        }
        Some(out)
    }

    /// The corners in `f64`: see [`Self::corners`].
    fn corners_f64(&self) -> Option<[(P3, f64); 8]> {
        let sign = |i: usize, k: usize| if i >> k & 1 == 1 { 1.0 } else { -1.0 };
        let mut out = [([0.0; 3], 0.0); 8];
        if let Some(ax) = self.exact_axes() {
            for (i, o) in out.iter_mut().enumerate() {
                let mut e = 0.0f64;
                for (k, x) in o.0.iter_mut().enumerate() {
                    let t = (0..3).fold(0.0, |t, j| t + sign(i, j) * self.h[j] * ax[j][k]);
                    *x = self.c[k] + t;
                    e = e.max(two_sum_err(self.c[k], t, *x).abs());
                }
                o.1 = e;
            }
        } else {
            let r = rotation(&self.q)?;
            for (i, o) in out.iter_mut().enumerate() {
                let mut e = 0.0f64;
                for ((x, c), row) in o.0.iter_mut().zip(self.c).zip(&r) {
                    let t: [f64; 3] = std::array::from_fn(|j| sign(i, j) * self.h[j] * row[j].parts().0);
                    *x = ((c + t[0]) + t[1]) + t[2];
                    let st = t[0].abs() + t[1].abs() + t[2].abs();
                    let rot: f64 = (0..3).map(|j| self.h[j].abs() * row[j].parts().1).sum();
                    let ek = (rot + U * st + 3.0 * U * (c.abs() + st)) * BOUND_SLACK + 3.0 * CORNER_UNDERFLOW;
                    e = e.max(ek);
                }
                o.1 = e;
            }
        }
        out.iter().all(|(v, e)| v.iter().all(|x| x.is_finite()) && e.is_finite()).then_some(out)
    }
}

/// A ring the lifted coordinates are formed in: [`Filt`] (exact when every
/// operation was, which settles the exact zeros of small quaternions and
/// binary coordinates without big numbers) or [`BigFloat`] (exact).
pub(crate) trait Leaf: Ring {
    /// An input, exactly.
    fn leaf(x: f64) -> Self;
}

impl Leaf for Filt {
    fn leaf(x: f64) -> Self {
        Filt::exact(x)
    }
}

impl Leaf for BigFloat {
    fn leaf(x: f64) -> Self {
        BigFloat::from_f64(x)
    }
}

/// A box's lifted quantities: `n = ‖q‖²`, `M_i` and `n (c − t)` for a
/// translation `t`.
struct Lifted<N> {
    n: N,
    m: [[N; 3]; 3],
    nc: [N; 3],
}

fn lifted<N: Leaf>(b: &ExactBox, t: &P3) -> Lifted<N> {
    let q = b.q.map(N::leaf);
    let r = [&q[0], &q[1], &q[2], &q[3]];
    let n = norm2(r);
    let nc = std::array::from_fn(|k| n.mul(&N::leaf(b.c[k]).sub(&N::leaf(t[k]))));
    Lifted { m: quaternion_axes(r), nc, n }
}

/// The coordinates of the exact corner `signs` of `b` times `n`:
/// `n c + Σ_i s_i h_i M_i`.
fn corner_times_n<N: Leaf>(b: &ExactBox, l: &Lifted<N>, signs: u8) -> [N; 3] {
    std::array::from_fn(|k| {
        let mut x = l.nc[k].clone();
        for i in 0..3 {
            let hm = N::leaf(b.h[i]).mul(&l.m[i][k]);
            x = if signs >> i & 1 == 1 { x.add(&hm) } else { x.sub(&hm) };
        }
        x
    })
}

/// The exact coordinates of `pts` (flattened, `3·pts.len() = K`), less a
/// translation `t` (the centre of the first box below: its corners' lifted
/// coordinates then carry no digits of a centre far from the origin), each
/// multiplied by `D`, the product of `‖q‖²` over the distinct boxes whose
/// corners among `pts` are not exact in `f64` (`D = 1` when there are none),
/// formed in `N`. The predicates are homogeneous in the coordinates and
/// depend on differences of the points only: their signs, their directions'
/// unit vectors and the equality of two points are unchanged.
pub(crate) fn lift<N: Leaf, const K: usize>(pts: &[Xp]) -> [N; K] {
    let t = pts.iter().find_map(|p| p.corner().filter(|_| p.e > 0.0)).map_or([0.0; 3], |(b, _)| b.c);
    let mut boxes: Vec<(&ExactBox, Lifted<N>)> = Vec::with_capacity(2);
    for p in pts {
        if let (true, Some((b, _))) = (p.e > 0.0, p.corner())
            && !boxes.iter().any(|(x, _)| std::ptr::eq(*x, b))
        {
            boxes.push((b, lifted(b, &t)));
        }
    }
    let prod = |skip: Option<&ExactBox>| -> Option<N> {
        boxes.iter().filter(|(x, _)| !skip.is_some_and(|s| std::ptr::eq(*x, s))).fold(None, |acc, (_, l)| {
            Some(match acc {
                None => l.n.clone(),
                Some(a) => a.mul(&l.n),
            })
        })
    };
    let d = prod(None);
    let mut out: [N; K] = std::array::from_fn(|_| N::leaf(0.0));
    for (j, p) in pts.iter().enumerate() {
        let coords: [N; 3] = match (p.e > 0.0, p.corner()) {
            (true, Some((b, s))) => {
                let l = &boxes.iter().find(|(x, _)| std::ptr::eq(*x, b)).expect("collected above").1;
                let x = corner_times_n(b, l, s);
                match prod(Some(b)) {
                    Some(o) => x.map(|c| o.mul(&c)),
                    None => x,
                }
            }
            _ => std::array::from_fn(|k| {
                let x = N::leaf(p.v[k]).sub(&N::leaf(t[k]));
                match &d {
                    Some(d) => d.mul(&x),
                    None => x,
                }
            }),
        };
        for (k, c) in coords.into_iter().enumerate() {
            out[3 * j + k] = c;
        }
    }
    out
}

/// Whether two points are exactly one point.
pub(crate) fn same(a: &Xp, b: &Xp) -> bool {
    if a.e == 0.0 && b.e == 0.0 {
        return points_equal(a.v, b.v);
    }
    if let (Some((x, s)), Some((y, t))) = (a.corner(), b.corner())
        && std::ptr::eq(x, y)
        && s == t
    {
        return true;
    }
    // |fl(a − b)| ≤ (1 + u)|a − b|: beyond the bounds (enlarged for that and
    // their own rounding), the exact points differ.
    let tol = (a.e + b.e) * (1.0 + 4.0 * U);
    if (0..3).any(|k| !((a.v[k] - b.v[k]).abs() <= tol)) {
        return false;
    }
    let f: [Filt; 6] = lift(&[*a, *b]);
    let diff: [Option<crate::exact::Sign>; 3] = std::array::from_fn(|k| f[k].sub(&f[k + 3]).sign());
    if diff.iter().all(Option::is_some) {
        return diff.iter().all(|s| *s == Some(crate::exact::Sign::Zero));
    }
    let l: [BigFloat; 6] = lift(&[*a, *b]);
    (0..3).all(|k| l[k] == l[k + 3])
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Whether every corner's exact point lies within its bound of its
    /// value: `|v·n − (n c + Σ s_i h_i M_i)| ≤ e·n` per coordinate, exactly.
    fn bounds_hold(b: &ExactBox) -> Result<(), TestCaseError> {
        let Some(cs) = b.corners() else { return Ok(()) };
        let l: Lifted<BigFloat> = lifted(b, &[0.0; 3]);
        for (i, c) in cs.iter().enumerate() {
            let x = corner_times_n(b, &l, i as u8);
            for (k, xk) in x.iter().enumerate() {
                let off = (&(&BigFloat::from_f64(c.v[k]) * &l.n) - xk).abs();
                let bound = &BigFloat::from_f64(c.e) * &l.n;
                prop_assert!(off <= bound, "corner {} coordinate {} of {:?}: {:?}", i, k, b, c);
                let dd = &BigFloat::from_f64(c.v[k]) + &BigFloat::from_f64(c.lo[k]);
                let off = (&(&dd * &l.n) - xk).abs();
                let bound = &BigFloat::from_f64(c.ed) * &l.n;
                prop_assert!(off <= bound, "corner {} coordinate {} of {:?} (double-double): {:?}", i, k, b, c);
            }
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn every_corner_lies_within_its_bound(
            c in prop::array::uniform3(-1.0e3..1.0e3f64),
            h in prop::array::uniform3(0.0..1.0e3f64),
            q in prop::array::uniform4(-2.0..2.0f64),
            (s, t) in (-1070i32..1020, -1000i32..1000),
            grid in any::<bool>(),
        ) {
            let r = |x: f64| if grid { (x * 4.0).round() / 4.0 } else { x };
            let c = c.map(|x| r(x) * 2f64.powi(s));
            let h = h.map(|x| r(x) * 2f64.powi(s));
            let q = q.map(|x| r(x) * 2f64.powi(t));
            if let Some(b) = ExactBox::new(c, h, q) {
                bounds_hold(&b)?;
            }
        }
    }

    #[test]
    fn signed_permutations_give_exact_corners() {
        for q in [[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 3.0, 0.0], [1.0, 1.0, 0.0, 0.0], [0.5; 4]] {
            let b = ExactBox::new([0.5, -1.0, 2.0], [1.0, 0.25, 3.0], q).expect("finite");
            let cs = b.corners().expect("finite corners");
            assert!(cs.iter().all(|c| c.e == 0.0 && c.ed == 0.0), "{q:?}: {cs:?}");
            bounds_hold(&b).expect("exact");
        }
        // The 3-4-5 box's corners are not binary.
        let b = ExactBox::new([0.0; 3], [1.0; 3], [2.0, 0.0, 0.0, 1.0]).expect("finite");
        assert!(b.corners().expect("finite corners").iter().all(|c| c.e > 0.0 && c.ed > 0.0));
        bounds_hold(&b).expect("within the bounds");
    }
}
