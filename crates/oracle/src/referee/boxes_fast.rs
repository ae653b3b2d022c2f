//! The floating-point stage of box overlap ([`super::boxes`]): the 15
//! separating axes evaluated in `f64` with a rigorous bound on each value's
//! error, certifying the clear cases.
//!
//! Every quantity is carried as a value `v` and a bound `e` with
//! `|exact − v| ≤ e` ([`Bounded`]): the inputs are exact (`e = 0`), and each
//! operation adds its own rounding under the standard model — for a result
//! `r`, `|fl(x) − x| ≤ u·|r|` with `u = 2⁻⁵³`, plus `2⁻¹⁰⁷⁴` per product or
//! quotient for underflow (sums of doubles are exact when subnormal). A value
//! that is computed exactly (no rounding happened, as for the identity
//! rotation or for axis-aligned boxes) keeps `e = 0`, so an exactly zero cross
//! product is known to be zero, and is skipped as the exact stage skips it.
//! The bounds are themselves computed in `f64`; each is a sum and product of
//! at most a few hundred non-negative terms, so its own rounding is below a
//! relative `10⁻¹³`, and every certified comparison asks for a relative
//! [`SLACK`] beyond it. An overflow or a NaN anywhere makes a comparison fail
//! to certify, and the exact stage decides.
//!
//! What it certifies:
//! - overlap (`overlap_box_box`, `overlap_box_aabb`): `false` when one axis
//!   separates by more than its bound, `true` when every axis overlaps by more
//!   than its bound (an axis whose cross product might be zero but is not known
//!   to be leaves `true` to the exact stage);
//! - the margins: which axis has the least `overlap/‖L‖`, when its interval
//!   lies strictly below every other's; the exact stage then evaluates that one
//!   axis in rationals and rounds it once, instead of all fifteen and their
//!   comparisons.

use crate::geom::{Aabb, OrientedBox};

/// `u = 2⁻⁵³`, the unit roundoff of round-to-nearest.
const U: f64 = f64::EPSILON / 2.0;

/// An underflow allowance per product or quotient: four times the least
/// subnormal, covering the few products inside one operation's bound.
const TINY: f64 = 4.0 * f64::from_bits(1);

/// Relative inflation of every bound before it is compared: far above the
/// rounding of the bounds' own computation (below `10⁻¹³`).
const SLACK: f64 = 1.0 + 1e-10;

/// A value and a bound on its error: the exact value lies in `[v − e, v + e]`.
#[derive(Clone, Copy, Debug)]
struct Bounded {
    v: f64,
    e: f64,
}

/// Below this, a product's or quotient's rounding error may itself fall
/// below the subnormals, so a zero residual would not prove exactness:
/// `2⁻⁹⁶⁰`.
const SAFE_EXACT: f64 = f64::from_bits(((1023 - 960) as u64) << 52);

impl Bounded {
    fn exact(v: f64) -> Self {
        Self { v, e: 0.0 }
    }

    /// The bound of a result `v` of one rounded operation on bounded inputs
    /// whose propagated error is `carried`: nothing more when both inputs
    /// were exact and the operation rounded nothing (`exact`).
    fn rounded(v: f64, carried: f64, exact: bool, tiny: f64) -> Self {
        if exact && carried == 0.0 && v.is_finite() {
            Self { v, e: 0.0 }
        } else {
            Self { v, e: carried + U * v.abs() + tiny }
        }
    }

    /// Whether `v = fl(a + b)` is `a + b` exactly (Knuth's TwoSum error is 0).
    fn sum_is_exact(a: f64, b: f64, v: f64) -> bool {
        let bb = v - a;
        (a - (v - bb)) + (b - bb) == 0.0
    }

    /// Whether `fl(x·y) = v` is exact, or `fl(x/y) = v` (`x = v·y`): a zero
    /// fused residual proves it where the residual cannot underflow.
    fn product_is_exact(x: f64, y: f64, v: f64) -> bool {
        if x == 0.0 || y == 0.0 {
            return v == 0.0;
        }
        v.abs() >= SAFE_EXACT && x.mul_add(y, -v) == 0.0
    }

    fn add(self, o: Self) -> Self {
        let v = self.v + o.v;
        Self::rounded(v, self.e + o.e, Self::sum_is_exact(self.v, o.v, v), 0.0)
    }

    fn sub(self, o: Self) -> Self {
        let v = self.v - o.v;
        Self::rounded(v, self.e + o.e, Self::sum_is_exact(self.v, -o.v, v), 0.0)
    }

    fn mul(self, o: Self) -> Self {
        let v = self.v * o.v;
        // (a + α)(b + β) − ab = aβ + bα + αβ, then the product's rounding.
        let carried = self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e;
        let carried = if carried == 0.0 { 0.0 } else { carried + TINY };
        Self::rounded(v, carried, Self::product_is_exact(self.v, o.v, v), TINY)
    }

    /// `self / o`; an unbounded error when `o` may be 0.
    fn div(self, o: Self) -> Self {
        let v = self.v / o.v;
        if self.e == 0.0 && o.e == 0.0 {
            let exact = o.v != 0.0 && (self.v == 0.0 || (self.v.abs() >= SAFE_EXACT && v.mul_add(o.v, -self.v) == 0.0));
            return Self::rounded(v, 0.0, exact, TINY);
        }
        // |a/b − a₀/b₀| ≤ (α + |a₀/b₀|·β)/(|b₀| − β).
        let d = o.v.abs() - o.e * SLACK;
        let e = if d > 0.0 { (self.e + v.abs() * SLACK * o.e) / d * SLACK + TINY } else { f64::INFINITY };
        Self::rounded(v, e, false, TINY)
    }

    fn abs(self) -> Self {
        Self { v: self.v.abs(), e: self.e }
    }

    /// `√self` for an exact value ≥ 0; an unbounded error when it may be 0.
    fn sqrt(self) -> Self {
        let v = self.v.sqrt();
        // |√x − √x₀| = |x − x₀|/(√x + √x₀) ≤ e/√x₀ (over a lower bound of √x₀).
        let low = (self.v - self.e * SLACK).max(0.0).sqrt() * (1.0 - 4.0 * U);
        let e = if low > 0.0 {
            self.e / low * SLACK
        } else if self.e == 0.0 {
            0.0
        } else {
            f64::INFINITY
        };
        Self { v, e: e + U * v + TINY }
    }

    /// Certainly ≥ 0.
    fn nonnegative(self) -> bool {
        self.v >= self.e * SLACK
    }

    /// Certainly < 0.
    fn negative(self) -> bool {
        -self.v > self.e * SLACK
    }

    /// Certainly not 0.
    fn nonzero(self) -> bool {
        self.v.abs() > self.e * SLACK
    }

    /// Known to be exactly 0.
    fn is_exact_zero(self) -> bool {
        self.v == 0.0 && self.e == 0.0
    }
}

type BV = [Bounded; 3];

fn dot(a: &BV, b: &BV) -> Bounded {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}

fn cross(a: &BV, b: &BV) -> BV {
    [a[1].mul(b[2]).sub(a[2].mul(b[1])), a[2].mul(b[0]).sub(a[0].mul(b[2])), a[0].mul(b[1]).sub(a[1].mul(b[0]))]
}

/// A box in bounded `f64`: centre, half-extents, axes (the rotation's
/// columns, as the exact stage's `columns` computes them).
pub(crate) struct FastBox {
    c: BV,
    h: BV,
    axes: [BV; 3],
}

impl FastBox {
    /// The box of checked input (finite, `h ≥ 0`, `q ≠ 0`).
    pub(crate) fn of(b: &OrientedBox) -> Self {
        let [w, x, y, z] = b.rotation.map(Bounded::exact);
        let n2 = w.mul(w).add(x.mul(x)).add(y.mul(y)).add(z.mul(z));
        let two = Bounded::exact(2.0);
        let (xx, yy, zz) = (x.mul(x), y.mul(y), z.mul(z));
        let (xy, xz, yz) = (x.mul(y), x.mul(z), y.mul(z));
        let (wx, wy, wz) = (w.mul(x), w.mul(y), w.mul(z));
        let e = |v: Bounded| v.div(n2);
        let axes = [
            [e(n2.sub(two.mul(yy.add(zz)))), e(two.mul(xy.add(wz))), e(two.mul(xz.sub(wy)))],
            [e(two.mul(xy.sub(wz))), e(n2.sub(two.mul(xx.add(zz)))), e(two.mul(yz.add(wx)))],
            [e(two.mul(xz.add(wy))), e(two.mul(yz.sub(wx))), e(n2.sub(two.mul(xx.add(yy))))],
        ];
        Self { c: b.center.map(Bounded::exact), h: b.half_extents.map(Bounded::exact), axes }
    }

    /// The axis-aligned box of checked input (finite, `min ≤ max`): centre
    /// `(min + max)/2`, half-extents `(max − min)/2`, the identity's axes.
    pub(crate) fn of_aabb(b: &Aabb) -> Self {
        let half = Bounded::exact(0.5);
        let c = std::array::from_fn(|i| Bounded::exact(b.min[i]).add(Bounded::exact(b.max[i])).mul(half));
        let h = std::array::from_fn(|i| Bounded::exact(b.max[i]).sub(Bounded::exact(b.min[i])).mul(half));
        let unit = |k: usize| std::array::from_fn(|i| Bounded::exact(if i == k { 1.0 } else { 0.0 }));
        Self { c, h, axes: [unit(0), unit(1), unit(2)] }
    }
}

/// One axis's overlap (times `‖L‖`) and `‖L‖²`, bounded; `None` for an axis
/// known to be the zero vector (skipped, as exactly); `Some` with `known:
/// false` for a cross product that may or may not be zero.
struct Axis {
    overlap: Bounded,
    norm2: Bounded,
    known: bool,
}

/// The 15 axes in the exact stage's order (`a`'s, `b`'s, then `aᵢ × bⱼ`
/// row by row), `None` where the exact stage skips a zero cross product.
fn axes(a: &FastBox, b: &FastBox) -> [Option<Axis>; 15] {
    let t: BV = std::array::from_fn(|i| b.c[i].sub(a.c[i]));
    let radius = |bx: &FastBox, l: &BV| {
        (0..3).fold(Bounded::exact(0.0), |acc, i| acc.add(bx.h[i].mul(dot(l, &bx.axes[i]).abs())))
    };
    std::array::from_fn(|k| {
        if k < 6 {
            // A box's own axis: its own radius is exactly its half-extent
            // (the exact axes are orthonormal), the other's is computed.
            let (own, other) = if k < 3 { (a, b) } else { (b, a) };
            let i = k % 3;
            let l = &own.axes[i];
            let overlap = own.h[i].add(radius(other, l)).sub(dot(l, &t).abs());
            return Some(Axis { overlap, norm2: Bounded::exact(1.0), known: true });
        }
        let (i, j) = ((k - 6) / 3, (k - 6) % 3);
        let l = cross(&a.axes[i], &b.axes[j]);
        if l.iter().all(|x| x.is_exact_zero()) {
            return None;
        }
        let known = l.iter().any(|x| x.nonzero());
        let overlap = radius(a, &l).add(radius(b, &l)).sub(dot(&l, &t).abs());
        Some(Axis { overlap, norm2: dot(&l, &l), known })
    })
}

/// Whether the boxes overlap, when certified: `Some(false)` as soon as one
/// axis separates beyond its bound, `Some(true)` when every axis is known and
/// overlaps beyond its bound.
pub(crate) fn overlap(a: &FastBox, b: &FastBox) -> Option<bool> {
    let mut all_overlap = true;
    for axis in axes(a, b).into_iter().flatten() {
        // A separating value needs no known axis: a zero axis gives overlap 0.
        if axis.overlap.negative() {
            return Some(false);
        }
        all_overlap &= axis.known && axis.overlap.nonnegative();
    }
    all_overlap.then_some(true)
}

/// The index (in the exact stage's order) of the axis with the least
/// `overlap/‖L‖`, when its interval lies strictly below every other axis's;
/// `None` when an axis is not known to be non-zero or two intervals meet.
pub(crate) fn least_axis(a: &FastBox, b: &FastBox) -> Option<usize> {
    let mut values: Vec<(usize, Bounded)> = Vec::with_capacity(15);
    for (k, axis) in axes(a, b).into_iter().enumerate() {
        let Some(axis) = axis else { continue };
        if !axis.known {
            return None;
        }
        let value = if k < 6 { axis.overlap } else { axis.overlap.div(axis.norm2.sqrt()) };
        values.push((k, value));
    }
    let (best, low) = values.iter().min_by(|x, y| x.1.v.total_cmp(&y.1.v))?;
    let clear = values.iter().filter(|(k, _)| k != best).all(|(_, other)| {
        // other − low > both bounds, in f64 (the subtraction's rounding is
        // within the slack; an overflow to +∞ is a true "far above").
        other.v - low.v > (other.e + low.e) * SLACK + TINY
    });
    clear.then_some(*best)
}
