//! The operations of [`P3`] that every part of crashtest needs, written once:
//! plain `f64` arithmetic, each rounding as the expression written (no fused
//! multiply–add), so that two callers get the same bits.

use crate::geom::P3;

/// `a + b`.
pub fn add(a: P3, b: P3) -> P3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a − b`.
pub fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s · a`.
pub fn scale(a: P3, s: f64) -> P3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a + s · b`.
pub fn add_scaled(a: P3, s: f64, b: P3) -> P3 {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

/// `a · b`.
pub fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a × b`.
pub fn cross(a: P3, b: P3) -> P3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `‖a‖`, without overflow or underflow in the squares (`hypot` twice).
pub fn norm(a: P3) -> f64 {
    a[0].hypot(a[1]).hypot(a[2])
}

/// `√(a · a)`: the square root of [`dot`]`(a, a)`, one rounding per operation
/// as written. Not [`norm`]: the squares overflow above about `1e154` and
/// underflow below about `1e-154`, and the two may differ in the last bit;
/// for the callers whose numbers were defined by this formula.
pub fn norm_sqrt_dot(a: P3) -> f64 {
    dot(a, a).sqrt()
}

/// `‖a − b‖`, as [`norm`].
pub fn dist(a: P3, b: P3) -> f64 {
    norm(sub(a, b))
}

/// The largest absolute coordinate.
pub fn max_abs(a: P3) -> f64 {
    a[0].abs().max(a[1].abs()).max(a[2].abs())
}

/// `−a`.
pub fn neg(a: P3) -> P3 {
    [-a[0], -a[1], -a[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_norm_neither_overflows_nor_underflows() {
        // 3-4-5 at both ends of the range: the squares would be ∞ and 0.
        let big = norm([3e300, 4e300, 0.0]);
        let tiny = norm([3e-320, 4e-320, 0.0]);
        assert!((big / 5e300 - 1.0).abs() <= 4.0 * f64::EPSILON, "{big}");
        // Subnormal inputs carry only a few significant bits: 5e-320 to within
        // one unit of the subnormal grid.
        assert!((tiny - 5e-320).abs() <= f64::from_bits(1), "{tiny}");
    }

    #[test]
    fn norm_sqrt_dot_is_the_plain_formula_where_norm_is_not() {
        let a = [1.5, -2.0, 0.25];
        assert_eq!(norm_sqrt_dot(a).to_bits(), (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt().to_bits());
        // The square overflows: ∞ where `norm` is the length.
        assert!(norm_sqrt_dot([1e200, 0.0, 0.0]).is_infinite());
        assert_eq!(norm([1e200, 0.0, 0.0]).to_bits(), 1e200f64.to_bits());
    }

    #[test]
    fn cross_is_orthogonal_and_right_handed() {
        // One rounding per product and one per difference: a few ulps of the
        // inputs' products at most.
        const TOL: f64 = 16.0 * f64::EPSILON;
        let z = cross([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert!(dist(z, [0.0, 0.0, 1.0]) <= TOL, "{z:?}");
        let (a, b) = ([1.5, -2.0, 0.25], [0.5, 4.0, -1.0]);
        let c = cross(a, b);
        assert!(dot(c, a).abs() <= TOL * norm(c) * norm(a) && dot(c, b).abs() <= TOL * norm(c) * norm(b));
        assert!(dist(sub(add(a, b), b), a) <= TOL * (norm(a) + norm(b)));
    }
}
