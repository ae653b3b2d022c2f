//! The closest point of a triangle's boundary (its three edges) to a point,
//! with the direction and the distance decided in exact arithmetic: for
//! scenes whose numbers span so many magnitudes that the plain closest
//! point's rounding exceeds the distance itself.

use crate::exact::bigfloat::{B3, cross3 as cross, dot3 as dot, sub3 as sub};
use crate::exact::{BigFloat, Estimate, Sign, frexp, ldexp};
use crate::real::{Real, Vec3};
use crate::shapes::Triangle;

/// A distance as `mant · 2^exp` (`mant ∈ [0.5, 1)`, or `0` for zero), so that
/// distances of any finite scene compare without overflow or underflow:
/// ordered by value ([`Distance::less`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Distance {
    mant: f64,
    exp: i64,
}

impl Distance {
    /// Zero.
    pub(crate) const ZERO: Self = Self { mant: 0.0, exp: 0 };

    /// A finite, non-negative `f64` distance `d · 2^shift`.
    pub(crate) fn of(d: f64, shift: i64) -> Self {
        if !(d > 0.0) {
            return Self::ZERO;
        }
        if !d.is_finite() {
            return Self { mant: 0.5, exp: 1025 + shift };
        }
        let (mant, e) = frexp(d);
        Self { mant, exp: e + shift }
    }

    /// The distance times `2^k`.
    pub(crate) fn scaled(self, k: i64) -> Self {
        if self.mant == 0.0 { self } else { Self { exp: self.exp + k, ..self } }
    }

    /// Strictly smaller.
    pub(crate) fn less(&self, other: &Self) -> bool {
        match (self.mant == 0.0, other.mant == 0.0) {
            (_, true) => false,
            (true, false) => true,
            _ => self.exp < other.exp || (self.exp == other.exp && self.mant < other.mant),
        }
    }

    /// The nearest `f64` (saturating to `∞`, flushing to `0`).
    pub(crate) fn to_f64(self) -> f64 {
        ldexp(self.mant, self.exp)
    }

    /// `√(num / den)` of two positive estimates.
    fn sqrt_ratio(num: &Estimate, den: &Estimate) -> Self {
        if num.mant == 0.0 {
            return Self::ZERO;
        }
        let mut e = num.exp - den.exp;
        let mut m = num.mant / den.mant;
        if e.rem_euclid(2) != 0 {
            m *= 2.0;
            e -= 1;
        }
        Self::of(m.sqrt(), e / 2)
    }
}

/// The feature of the boundary nearest to the point, exactly.
pub(crate) struct BoundaryPoint<T: Real> {
    /// The closest point (a vertex exactly, or an edge's foot formed from its
    /// nearer end).
    pub point: Vec3<T>,
    /// The unit direction from the closest point toward the query point, from
    /// exact values (each component within a few ulps of the exact one).
    pub normal: Vec3<T>,
    /// The distance, to a few ulps.
    pub distance: Distance,
}

fn big3(p: &[f64; 3]) -> B3 {
    p.map(BigFloat::from_f64)
}

/// The point of the edges of `tri` nearest to `p`, with its direction and
/// distance, decided exactly: per edge `ab`, with `w = p − a` and
/// `u = b − a`, the foot's side of each end is the sign of `w · u` and of
/// `w · u − u · u`; inside, the squared distance is `‖w × u‖² / ‖u‖²` and the
/// direction `u × (w × u) = w ‖u‖² − u (u · w)`, the part of `w` across the
/// edge (a polynomial: no foot is rounded on the way); at an end, `p` minus
/// that vertex. The nearest edge wins, the first on a tie. `None` when `p` is
/// on the boundary (no direction) or an input is not finite.
///
/// Costs a few hundred exact operations: for the rare inputs whose plain
/// closest point cannot resolve the direction.
pub(crate) fn nearest_on_boundary<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Option<BoundaryPoint<T>> {
    let w64 = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let pw = w64(p);
    let vw = tri.vertices.each_ref().map(w64);
    if !pw.iter().chain(vw.iter().flatten()).all(|x| x.is_finite()) {
        return None;
    }
    let pb = big3(&pw);
    let vb = vw.each_ref().map(big3);
    // (distance, direction, edge, foot inside)
    let mut best: Option<(Distance, B3, usize, Option<usize>)> = None;
    for (e, (i, j)) in [(0usize, 1usize), (1, 2), (2, 0)].into_iter().enumerate() {
        let w = sub(&pb, &vb[i]);
        let u = sub(&vb[j], &vb[i]);
        let uu = dot(&u, &u);
        let wu = dot(&w, &u);
        let (dist, dir, vertex) = if uu.is_zero() || wu.sign() != Sign::Positive {
            (Distance::sqrt_ratio(&dot(&w, &w).estimate(), &Estimate::from_scaled(1.0, 0, 0.0)), w, Some(i))
        } else if (&wu - &uu).sign() != Sign::Negative {
            let wb = sub(&pb, &vb[j]);
            (Distance::sqrt_ratio(&dot(&wb, &wb).estimate(), &Estimate::from_scaled(1.0, 0, 0.0)), wb, Some(j))
        } else {
            let c = cross(&w, &u);
            (Distance::sqrt_ratio(&dot(&c, &c).estimate(), &uu.estimate()), cross(&u, &c), None)
        };
        if best.as_ref().is_none_or(|b| dist.less(&b.0)) {
            best = Some((dist, dir, e, vertex));
        }
    }
    let (distance, dir, e, vertex) = best?;
    let n = Estimate::unit_vector(dir.each_ref().map(BigFloat::estimate))?;
    let normal = Vec3::new(T::of(n[0]), T::of(n[1]), T::of(n[2]));
    let [a, b, c] = tri.vertices;
    let point = match vertex {
        Some(k) => tri.vertices[k],
        None => {
            let (u, w) = [(a, b), (b, c), (c, a)][e];
            super::closest_pt_point_segment(p, &u, &w)
        }
    };
    Some(BoundaryPoint { point, normal, distance })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Components of a unit normal from exact values, rounded: a few ulps.
    const UNIT_TOL: f64 = 4.0 * f64::EPSILON;

    #[test]
    fn edge_direction_is_exact_where_the_foot_rounds_away_the_distance() {
        // An edge nearly along y from (0, 4e223, 0) to (0, 0, 0), and a point
        // 2e72 off it in x at y = 3.7e164: the foot's y rounds by ~1e149,
        // far more than the distance; the direction is +x.
        let tri =
            Triangle::<f64>::new(Vec3::new(0.0, 4e223, 0.0), Vec3::new(0.0, 0.0, 0.0), Vec3::new(-3e259, 0.0, 3e134));
        let p = Vec3::new(1.9e72, 3.7e164, 0.0);
        let b = nearest_on_boundary(&p, &tri).expect("off the boundary");
        assert!((b.normal.x - 1.0).abs() <= UNIT_TOL && b.normal.y.abs() <= UNIT_TOL, "{:?}", b.normal);
        assert!((b.distance.to_f64() / 1.9e72 - 1.0).abs() <= UNIT_TOL);
    }

    #[test]
    fn vertex_direction_and_distance() {
        let tri = Triangle::<f64>::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
        let b = nearest_on_boundary(&Vec3::new(5.0, -4.0, 0.0), &tri).expect("off");
        assert!((b.point.x - 2.0).abs() <= UNIT_TOL && b.point.y.abs() <= UNIT_TOL);
        assert!((b.distance.to_f64() - 5.0).abs() <= 5.0 * UNIT_TOL);
        assert!((b.normal.x - 0.6).abs() <= UNIT_TOL && (b.normal.y + 0.8).abs() <= UNIT_TOL);
        assert!(nearest_on_boundary(&Vec3::new(1.0, 0.0, 0.0), &tri).is_none(), "on an edge: no direction");
    }

    #[test]
    fn distances_order_by_value_across_the_range() {
        let small = Distance::of(f64::from_bits(1), 0);
        let big = Distance::of(f64::MAX, 0);
        assert!(small.less(&big) && !big.less(&small) && Distance::ZERO.less(&small));
        assert!(Distance::of(3.0, 0).less(&Distance::of(3.0, 1)));
        assert!(Distance::of(1.0, -2000).less(&Distance::of(f64::from_bits(1), 0)));
    }
}
