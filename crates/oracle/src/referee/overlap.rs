//! Overlap of two axis-aligned boxes, exactly.

use super::error::RefereeError;
use crate::geom::Aabb;

fn check(b: &Aabb, min: &'static str, max: &'static str) -> Result<(), RefereeError> {
    if b.min.iter().any(|x| !x.is_finite()) {
        return Err(RefereeError::NonFinite { field: min });
    }
    if b.max.iter().any(|x| !x.is_finite()) {
        return Err(RefereeError::NonFinite { field: max });
    }
    if (0..3).any(|k| b.min[k] > b.max[k]) {
        return Err(RefereeError::InvertedAabb { field: min });
    }
    Ok(())
}

/// Whether boxes `a` and `b` overlap; touching faces, edges or corners overlap.
///
/// **Definition** (separating axis theorem for boxes, Ericson §4.2.1): the boxes
/// overlap iff on every axis `k` their intervals meet,
/// `a.min[k] ≤ b.max[k]` and `b.min[k] ≤ a.max[k]`. Comparisons of two finite
/// `f64` are exact, so no rational arithmetic is needed; `≤` makes touching count.
///
/// **Degenerate input.** Zero-thickness boxes (`min = max` on an axis, down to a
/// point) are valid and treated the same way. Non-finite numbers and inverted
/// boxes (`min > max`) are refused.
pub fn overlap_aabb_aabb(a: &Aabb, b: &Aabb) -> Result<bool, RefereeError> {
    check(a, "a.min", "a.max")?;
    check(b, "b.min", "b.max")?;
    Ok((0..3).all(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k]))
}

/// The signed overlap behind [`overlap_aabb_aabb`]'s decision: the minimum over
/// the axes of `min(a.max, b.max) − max(a.min, b.min)`, the length of the
/// intervals' common part (negative: minus the gap), correctly rounded. ≥ 0
/// exactly when the boxes overlap (0 when they touch).
///
/// Each difference of two `f64` is correctly rounded by IEEE 754 subtraction, and
/// rounding is monotone, so the minimum of the rounded differences is the
/// rounded minimum. An exact 0 is reported as `+0.0` (`−0.0 − 0.0` would give
/// `−0.0`), so the sign bit alone carries the decision.
pub fn overlap_margin_aabb_aabb(a: &Aabb, b: &Aabb) -> Result<f64, RefereeError> {
    check(a, "a.min", "a.max")?;
    check(b, "b.min", "b.max")?;
    Ok((0..3).map(|k| (a.max[k].min(b.max[k]) - a.min[k].max(b.min[k])) + 0.0).fold(f64::INFINITY, f64::min))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::within_ulps;

    /// The margin is correctly rounded, and the expectations below are exact
    /// differences of small dyadic numbers: 0 ulps allowed.
    const EXACT_ULPS: u64 = 0;

    fn aabb(min: [f64; 3], max: [f64; 3]) -> Aabb {
        Aabb { min, max }
    }

    #[test]
    fn referee_overlap_cases() {
        let unit = aabb([0.0; 3], [1.0; 3]);
        // (b, overlaps, margin, why) — margins by hand: the common part's length
        // on the tightest axis.
        let cases = [
            (aabb([0.5; 3], [2.0; 3]), true, 0.5, "corner sunk half a unit"),
            (aabb([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]), true, 0.0, "touching faces overlap"),
            (aabb([1.0; 3], [2.0; 3]), true, 0.0, "touching corners overlap"),
            (aabb([1.25, 0.0, 0.0], [2.0, 1.0, 1.0]), false, -0.25, "gap of a quarter on x"),
            (aabb([0.25; 3], [0.5; 3]), true, 0.25, "nested: the inner box's extent"),
            (aabb([0.5, 0.5, 0.5], [0.5, 0.5, 0.5]), true, 0.0, "a point inside"),
        ];
        for (b, want, margin, why) in cases {
            assert_eq!(overlap_aabb_aabb(&unit, &b).unwrap(), want, "{why}");
            assert_eq!(overlap_aabb_aabb(&b, &unit).unwrap(), want, "{why} (swapped)");
            let m = overlap_margin_aabb_aabb(&unit, &b).unwrap();
            assert!(within_ulps(m, margin, EXACT_ULPS), "{why}: margin {m} vs {margin}");
        }
    }

    #[test]
    fn referee_overlap_touching_at_signed_zeros_has_a_positive_margin() {
        // a ends at −0, b starts at +0: the same number, so they touch; the
        // margin is +0 (the raw f64 difference −0 − 0 would be −0).
        let a = aabb([-1.0, 0.0, 0.0], [-0.0, 1.0, 1.0]);
        let b = aabb([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
        assert!(overlap_aabb_aabb(&a, &b).unwrap());
        assert!(!overlap_margin_aabb_aabb(&a, &b).unwrap().is_sign_negative());
    }

    #[test]
    fn referee_overlap_one_ulp_gap_is_separate() {
        // b starts at the next f64 after 1: a gap of exactly 2^-52.
        let unit = aabb([0.0; 3], [1.0; 3]);
        let next = f64::from_bits(1.0f64.to_bits() + 1);
        let b = aabb([next, 0.0, 0.0], [2.0, 1.0, 1.0]);
        assert!(!overlap_aabb_aabb(&unit, &b).unwrap());
        let m = overlap_margin_aabb_aabb(&unit, &b).unwrap();
        assert!(within_ulps(m, -f64::EPSILON, EXACT_ULPS), "margin {m}");
    }

    #[test]
    fn referee_overlap_refuses_bad_boxes() {
        let unit = aabb([0.0; 3], [1.0; 3]);
        let inverted = aabb([1.0, 0.0, 0.0], [0.0, 1.0, 1.0]);
        assert_eq!(overlap_aabb_aabb(&unit, &inverted), Err(RefereeError::InvertedAabb { field: "b.min" }));
        let nan = aabb([0.0; 3], [f64::NAN, 1.0, 1.0]);
        assert_eq!(overlap_aabb_aabb(&nan, &unit), Err(RefereeError::NonFinite { field: "a.max" }));
    }
}
