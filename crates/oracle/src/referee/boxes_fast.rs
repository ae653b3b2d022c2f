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
//! The same bounded numbers certify, for the contact of boxes and capsules
//! and for a segment against a box, that the shapes are apart (the segment
//! misses): the whole answer then, with no number to round. Any direction `n`
//! whose projections of the two shapes are further apart than the radii is a
//! proof; `n` is chosen in plain `f64` (from approximate closest points) and
//! taken as the exact vector it is, and only the projections are bounded.
//!
//! What it certifies for overlap:
//! - overlap (`overlap_box_box`, `overlap_box_aabb`): `false` when one axis
//!   separates by more than its bound, `true` when every axis overlaps by more
//!   than its bound (an axis whose cross product might be zero but is not known
//!   to be leaves `true` to the exact stage);
//! - the margins: which axis has the least `overlap/‖L‖`, when its interval
//!   lies strictly below every other's; the exact stage then evaluates that one
//!   axis in rationals and rounds it once, instead of all fifteen and their
//!   comparisons.

use crate::geom::{Aabb, Capsule, OrientedBox, P3, Plane, Segment, Sphere};

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

    /// Certainly > 0.
    fn positive(self) -> bool {
        self.v > self.e * SLACK
    }

    /// The larger of two bounded values (max is 1-Lipschitz: the larger bound
    /// holds).
    fn max(self, o: Self) -> Self {
        Self { v: self.v.max(o.v), e: self.e.max(o.e) }
    }

    /// The smaller of two bounded values.
    fn min(self, o: Self) -> Self {
        Self { v: self.v.min(o.v), e: self.e.max(o.e) }
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

fn exact_v(p: &P3) -> BV {
    p.map(Bounded::exact)
}

/// Whether shapes whose projections on `n` are `gap` apart (`gap` = the
/// lower end of one minus the upper end of the other, in units of `‖n‖`)
/// certainly stay apart with radii summing to `r`: `gap > 0` and
/// `gap² > r²·‖n‖²`.
fn clear_gap(gap: Bounded, r: Bounded, n: &BV) -> bool {
    gap.positive() && gap.mul(gap).sub(r.mul(r).mul(dot(n, n))).positive()
}

/// The box's projection on `n`: its centre's and its reach `Σ hᵢ|n·Aᵢ|`.
fn box_span(b: &FastBox, n: &BV) -> (Bounded, Bounded) {
    let reach = (0..3).fold(Bounded::exact(0.0), |acc, i| acc.add(b.h[i].mul(dot(n, &b.axes[i]).abs())));
    (dot(n, &b.c), reach)
}

/// The rotation's columns in plain `f64` (the bounded values'), for choosing
/// directions.
fn plain_axes(b: &FastBox) -> [P3; 3] {
    b.axes.map(|a| a.map(|x| x.v))
}

/// A sphere (checked input) certainly apart from a box: along `n = M − p`,
/// `p` the `f64` clamp of the centre into the box.
pub(crate) fn sphere_box_apart(s: &Sphere, b: &OrientedBox) -> bool {
    let fb = FastBox::of(b);
    let axes = plain_axes(&fb);
    let d: P3 = std::array::from_fn(|i| s.center[i] - b.center[i]);
    let u: P3 = std::array::from_fn(|i| axes[i][0] * d[0] + axes[i][1] * d[1] + axes[i][2] * d[2]);
    let w: P3 = std::array::from_fn(|i| u[i] - u[i].clamp(-b.half_extents[i], b.half_extents[i]));
    let n: P3 = std::array::from_fn(|k| (0..3).map(|i| w[i] * axes[i][k]).sum());
    if !n.iter().all(|x| x.is_finite()) || n.iter().all(|x| *x == 0.0) {
        return false;
    }
    let n = exact_v(&n);
    let (c, reach) = box_span(&fb, &n);
    clear_gap(dot(&n, &exact_v(&s.center)).sub(c.add(reach)), Bounded::exact(s.radius), &n)
}

/// A box (checked input) certainly above a plane (`n ≠ 0`): its lowest
/// point's `n·x` certainly beyond `d`.
pub(crate) fn box_plane_apart(a: &OrientedBox, p: &Plane) -> bool {
    let n = exact_v(&p.normal);
    let (c, reach) = box_span(&FastBox::of(a), &n);
    Bounded::exact(p.offset).sub(c.sub(reach)).negative()
}

/// The point of segment `[a, b]` nearest `p`, in plain `f64`.
fn nearest_on(p: &P3, a: &P3, b: &P3) -> P3 {
    let d: P3 = std::array::from_fn(|i| b[i] - a[i]);
    let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1] + (p[2] - a[2]) * d[2]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    std::array::from_fn(|i| a[i] + t * d[i])
}

/// Whether the projections of segments `[a0, a1]` and `[b0, b1]` on `n`
/// (a finite, non-zero `f64` vector) are certainly further apart than `r`.
fn segments_apart_along(n: P3, a: [&P3; 2], b: [&P3; 2], r: Bounded) -> bool {
    if !n.iter().all(|x| x.is_finite()) || n.iter().all(|x| *x == 0.0) {
        return false;
    }
    let n = exact_v(&n);
    let (a0, a1) = (dot(&n, &exact_v(a[0])), dot(&n, &exact_v(a[1])));
    let (b0, b1) = (dot(&n, &exact_v(b[0])), dot(&n, &exact_v(b[1])));
    clear_gap(a0.min(a1).sub(b0.max(b1)), r, &n)
}

/// A sphere (checked input) certainly apart from a capsule: along
/// `n = M − q`, `q` the `f64` nearest point of the axis.
pub(crate) fn sphere_capsule_apart(s: &Sphere, b: &Capsule) -> bool {
    let q = nearest_on(&s.center, &b.start, &b.end);
    let n = std::array::from_fn(|i| s.center[i] - q[i]);
    let r = Bounded::exact(s.radius).add(Bounded::exact(b.radius));
    segments_apart_along(n, [&s.center, &s.center], [&b.start, &b.end], r)
}

/// Two capsules (checked input) certainly apart: along `n = p_a − p_b`,
/// approximate closest points of the axes (the nearest of a's ends and
/// its `f64` Ericson closest pair, each against b's axis).
pub(crate) fn capsule_capsule_apart(a: &Capsule, b: &Capsule) -> bool {
    let r = Bounded::exact(a.radius).add(Bounded::exact(b.radius));
    let candidates = [a.start, a.end, closest_on_a(a, b)];
    candidates.iter().any(|pa| {
        let pb = nearest_on(pa, &b.start, &b.end);
        let n = std::array::from_fn(|i| pa[i] - pb[i]);
        segments_apart_along(n, [&a.start, &a.end], [&b.start, &b.end], r)
    })
}

/// The point of a's axis nearest b's (Ericson §5.1.9 in plain `f64`: the
/// unclamped solution clamped, then refined once against b).
fn closest_on_a(a: &Capsule, b: &Capsule) -> P3 {
    let d1: P3 = std::array::from_fn(|i| a.end[i] - a.start[i]);
    let d2: P3 = std::array::from_fn(|i| b.end[i] - b.start[i]);
    let r: P3 = std::array::from_fn(|i| a.start[i] - b.start[i]);
    let dt = |x: &P3, y: &P3| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let (aa, ee, bb, cc, ff) = (dt(&d1, &d1), dt(&d2, &d2), dt(&d1, &d2), dt(&d1, &r), dt(&d2, &r));
    let denom = aa * ee - bb * bb;
    let s = if denom > 0.0 { ((bb * ff - cc * ee) / denom).clamp(0.0, 1.0) } else { 0.0 };
    let pa: P3 = std::array::from_fn(|i| a.start[i] + s * d1[i]);
    let pb = nearest_on(&pa, &b.start, &b.end);
    nearest_on(&pb, &a.start, &a.end)
}

/// A capsule (checked input) certainly above a plane (`n ≠ 0`): its lowest
/// end more than `r` above.
pub(crate) fn capsule_plane_apart(a: &Capsule, p: &Plane) -> bool {
    let n = exact_v(&p.normal);
    let low = dot(&n, &exact_v(&a.start)).min(dot(&n, &exact_v(&a.end)));
    clear_gap(low.sub(Bounded::exact(p.offset)), Bounded::exact(a.radius), &n)
}

/// A segment (checked input) certainly missing a box: separated on one of
/// the box's axes or one of `d × Aᵢ` (`d = p1 − p0`).
pub(crate) fn segment_box_miss(s: &Segment, b: &OrientedBox) -> bool {
    let fb = FastBox::of(b);
    let axes = plain_axes(&fb);
    let d: P3 = std::array::from_fn(|i| s.end[i] - s.start[i]);
    let cross_f =
        |x: &P3, y: &P3| -> P3 { [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]] };
    let directions = [axes[0], axes[1], axes[2], cross_f(&d, &axes[0]), cross_f(&d, &axes[1]), cross_f(&d, &axes[2])];
    directions.iter().any(|n| {
        if !n.iter().all(|x| x.is_finite()) || n.iter().all(|x| *x == 0.0) {
            return false;
        }
        let n = exact_v(n);
        let (c, reach) = box_span(&fb, &n);
        let (p0, p1) = (dot(&n, &exact_v(&s.start)), dot(&n, &exact_v(&s.end)));
        let (lo, hi) = (p0.min(p1), p0.max(p1));
        lo.sub(c.add(reach)).positive() || c.sub(reach).sub(hi).positive()
    })
}

/// `x × y` in plain `f64`, for choosing directions.
fn cross_plain(x: &P3, y: &P3) -> P3 {
    [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]]
}

/// The lowest and highest of `n·p` over `points`, bounded.
fn points_span(n: &BV, points: &[P3]) -> (Bounded, Bounded) {
    let mut it = points.iter().map(|p| dot(n, &exact_v(p)));
    let first = it.next().expect("a point");
    it.fold((first, first), |(lo, hi), x| (lo.min(x), hi.max(x)))
}

/// Whether the convex hull of `points` and the box are certainly further
/// apart than `r` along `n` (a plain `f64` vector, taken exactly).
fn points_box_apart_along(n: &P3, points: &[P3], fb: &FastBox, r: Bounded) -> bool {
    if !n.iter().all(|x| x.is_finite()) || n.iter().all(|x| *x == 0.0) {
        return false;
    }
    let n = exact_v(n);
    let (c, reach) = box_span(fb, &n);
    let (lo, hi) = points_span(&n, points);
    clear_gap(lo.sub(c.add(reach)), r, &n) || clear_gap(c.sub(reach).sub(hi), r, &n)
}

/// A capsule (checked input) certainly apart from a box: along one of the
/// box's axes, `d × Aᵢ` (`d` the axis's direction), or `m − p` for `m` an
/// end or the axis's point nearest the box's centre and `p` its `f64` clamp
/// into the box.
pub(crate) fn capsule_box_apart(a: &Capsule, b: &OrientedBox) -> bool {
    let fb = FastBox::of(b);
    let axes = plain_axes(&fb);
    let d: P3 = std::array::from_fn(|i| a.end[i] - a.start[i]);
    let clamp_dir = |m: &P3| -> P3 {
        let rel: P3 = std::array::from_fn(|i| m[i] - b.center[i]);
        let u: P3 = std::array::from_fn(|i| axes[i][0] * rel[0] + axes[i][1] * rel[1] + axes[i][2] * rel[2]);
        let w: P3 = std::array::from_fn(|i| u[i] - u[i].clamp(-b.half_extents[i], b.half_extents[i]));
        std::array::from_fn(|k| (0..3).map(|i| w[i] * axes[i][k]).sum())
    };
    let mid = nearest_on(&b.center, &a.start, &a.end);
    let directions = [
        clamp_dir(&a.start),
        clamp_dir(&a.end),
        clamp_dir(&mid),
        axes[0],
        axes[1],
        axes[2],
        cross_plain(&d, &axes[0]),
        cross_plain(&d, &axes[1]),
        cross_plain(&d, &axes[2]),
    ];
    let r = Bounded::exact(a.radius);
    directions.iter().any(|n| points_box_apart_along(n, &[a.start, a.end], &fb, r))
}

/// Whether the hulls of `pa` and `pb` are certainly further apart than `r`
/// along `n`.
fn hulls_apart_along(n: &P3, pa: &[P3], pb: &[P3], r: Bounded) -> bool {
    if !n.iter().all(|x| x.is_finite()) || n.iter().all(|x| *x == 0.0) {
        return false;
    }
    let n = exact_v(n);
    let ((lo_a, hi_a), (lo_b, hi_b)) = (points_span(&n, pa), points_span(&n, pb));
    clear_gap(lo_a.sub(hi_b), r, &n) || clear_gap(lo_b.sub(hi_a), r, &n)
}

/// A triangle's edges `v1 − v0`, `v2 − v1`, `v0 − v2` and normal, in `f64`.
fn triangle_frame(t: &crate::geom::Triangle) -> ([P3; 3], P3) {
    let v = &t.vertices;
    let e = [0, 1, 2].map(|k| {
        let (p, q) = (v[k], v[(k + 1) % 3]);
        std::array::from_fn(|i| q[i] - p[i])
    });
    (e, cross_plain(&e[0], &std::array::from_fn(|i| v[2][i] - v[0][i])))
}

/// A box and a triangle (checked input) certainly apart: along one of the
/// separating axes (the box's, the triangle's normal, the box's axes crossed
/// with the edges), taken in `f64` and bounded.
pub(crate) fn box_triangle_apart(a: &OrientedBox, t: &crate::geom::Triangle) -> bool {
    let fb = FastBox::of(a);
    let axes = plain_axes(&fb);
    let (edges, normal) = triangle_frame(t);
    let mut directions = vec![axes[0], axes[1], axes[2], normal];
    directions.extend(axes.iter().flat_map(|x| edges.iter().map(move |e| cross_plain(x, e))));
    directions.iter().any(|n| points_box_apart_along(n, &t.vertices, &fb, Bounded::exact(0.0)))
}

/// A capsule and a triangle (checked input) certainly apart: along the
/// triangle's normal, the axis's direction crossed with the edges, or the
/// normal crossed with them (the edges' outward directions in its plane).
pub(crate) fn capsule_triangle_apart(a: &Capsule, t: &crate::geom::Triangle) -> bool {
    let d: P3 = std::array::from_fn(|i| a.end[i] - a.start[i]);
    let (edges, normal) = triangle_frame(t);
    let mut directions = vec![normal];
    directions.extend(edges.iter().map(|e| cross_plain(&d, e)));
    directions.extend(edges.iter().map(|e| cross_plain(&normal, e)));
    let r = Bounded::exact(a.radius);
    directions.iter().any(|n| hulls_apart_along(n, &[a.start, a.end], &t.vertices, r))
}
