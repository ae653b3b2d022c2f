//! `overlap` scenes: two axis-aligned boxes.
//!
//! The uniform family places boxes at random in a small box. The biased ones sit
//! on the decision's boundary: boxes touching exactly on a face, an edge or a
//! corner, boxes a few ULPs apart at every magnitude, flat and point boxes,
//! nested boxes, far from the origin, tiny and huge, and an edge walker that
//! steps touching faces `k ∈ [-8, 8]` ULPs either way.

use super::build::*;
use super::family::Family;
use crashtest_core::vec3::{add, scale};
use oracle::geom::P3;
use proptest::prelude::*;

/// Extents of uniform boxes, per axis.
const EXTENT: std::ops::Range<f64> = 0.0..BOX;

fn uniform_boxes() -> SBoxedStrategy<Scene> {
    (vec3(BOX), prop::array::uniform3(EXTENT), vec3(BOX), prop::array::uniform3(EXTENT))
        .prop_map(|(a, ea, b, eb)| (aabb(a, add(a, ea)), Some(aabb(b, add(b, eb)))))
        .sboxed()
}

/// A grid box: corner on the 1/64 grid, extents positive multiples of 1/16 up to 4.
fn grid_box() -> impl Strategy<Value = (P3, P3)> + Clone {
    (grid_point(), prop::array::uniform3((1..=64i64).prop_map(|m| m as f64 / 16.0)))
        .prop_map(|(lo, e)| (lo, add(lo, e)))
}

/// How `b` sits against `a` on one axis.
#[derive(Clone, Copy, Debug)]
enum Contact {
    /// `b` starts where `a` ends.
    Above,
    /// `b` ends where `a` starts.
    Below,
    /// Their ranges overlap (or nest).
    Across,
}

/// Two boxes touching exactly: on each axis `b`'s range either starts at `a`'s
/// max, ends at `a`'s min, or overlaps `a`'s range; at least one axis touches
/// (one for a face, two for an edge, three for a corner). Every coordinate is a
/// short dyadic, so the touching coordinates are equal exactly.
fn touching_boxes() -> impl Strategy<Value = ((P3, P3), (P3, P3), [Contact; 3])> + Clone {
    let contact = || prop_oneof![Just(Contact::Above), Just(Contact::Below), Just(Contact::Across)];
    (
        grid_box(),
        prop::array::uniform3((1..=64i64, 0..=64i64)),
        prop::array::uniform3(contact()),
        0..3usize,
        any::<bool>(),
    )
        .prop_map(|((lo, hi), spans, mut how, forced, above)| {
            if how.iter().all(|h| matches!(h, Contact::Across)) {
                how[forced] = if above { Contact::Above } else { Contact::Below };
            }
            let (mut blo, mut bhi) = ([0.0; 3], [0.0; 3]);
            for i in 0..3 {
                let len = spans[i].0 as f64 / 16.0;
                match how[i] {
                    Contact::Above => (blo[i], bhi[i]) = (hi[i], hi[i] + len),
                    Contact::Below => (blo[i], bhi[i]) = (lo[i] - len, lo[i]),
                    Contact::Across => {
                        // b's centre anywhere in a's range: the ranges intersect.
                        let start = lo[i] + (hi[i] - lo[i]) * (spans[i].1 as f64 / 64.0) - len / 2.0;
                        (blo[i], bhi[i]) = (start, start + len);
                    }
                }
            }
            ((lo, hi), (blo, bhi), how)
        })
}

fn exactly_touching() -> SBoxedStrategy<Scene> {
    (touching_boxes(), any::<bool>())
        .prop_map(|(((lo, hi), (blo, bhi), _), flip)| {
            let (a, b) = (aabb(lo, hi), aabb(blo, bhi));
            if flip { (b, Some(a)) } else { (a, Some(b)) }
        })
        .sboxed()
}

/// Touching boxes scaled by `2^j` (exact, `j ∈ [-30, 50]`, so coordinates from
/// about 1e-9 to 1e16), then on one touching axis `b` moved away by
/// `k ∈ [1, 8]` ULPs of the touching coordinate: apart by a hair (`b` stays a
/// box: its extent is at least 1/16 of the scale, far more than 8 ULPs).
fn few_ulps_apart() -> SBoxedStrategy<Scene> {
    (touching_boxes(), -30..=50i32, 1..=8i32)
        .prop_map(|(((lo, hi), (blo, bhi), how), j, k)| {
            let s = pow2(j);
            let (lo, hi, mut blo, mut bhi) = (scale(lo, s), scale(hi, s), scale(blo, s), scale(bhi, s));
            if let Some(i) = how.iter().position(|h| !matches!(h, Contact::Across)) {
                match how[i] {
                    Contact::Above => blo[i] = step_ulps(blo[i], k),
                    _ => bhi[i] = step_ulps(bhi[i], -k),
                }
            }
            (aabb(lo, hi), Some(aabb(blo, bhi)))
        })
        .sboxed()
}

/// The edge walker: touching boxes (at a random power-of-two scale), then each
/// touching coordinate of `b` stepped its own `k ∈ [-8, 8]` ULPs (toward `a`
/// overlaps, away separates; 0 keeps touching).
fn walk_box_faces() -> SBoxedStrategy<Scene> {
    (touching_boxes(), -30..=50i32, prop::array::uniform3(ulps()))
        .prop_map(|(((lo, hi), (blo, bhi), how), j, ks)| {
            let s = pow2(j);
            let (lo, hi, mut blo, mut bhi) = (scale(lo, s), scale(hi, s), scale(blo, s), scale(bhi, s));
            for i in 0..3 {
                match how[i] {
                    Contact::Above => blo[i] = step_ulps(blo[i], ks[i]),
                    Contact::Below => bhi[i] = step_ulps(bhi[i], ks[i]),
                    Contact::Across => {}
                }
            }
            (aabb(lo, hi), Some(aabb(blo, bhi)))
        })
        .sboxed()
}

/// Boxes flat on one to three axes (zero extent: a rectangle, a segment or a
/// point), touching or crossing a grid box or each other.
fn flat_boxes() -> SBoxedStrategy<Scene> {
    (touching_boxes(), prop::array::uniform3(any::<bool>()), prop::array::uniform3(any::<bool>()))
        .prop_map(|(((lo, hi), (blo, bhi), _), flat_a, flat_b)| {
            let (mut hi, mut bhi) = (hi, bhi);
            for i in 0..3 {
                if flat_a[i] {
                    hi[i] = lo[i];
                }
                if flat_b[i] {
                    bhi[i] = blo[i];
                }
            }
            (aabb(lo, hi), Some(aabb(blo, bhi)))
        })
        .sboxed()
}

/// `b` inside `a` (sharing faces when an inset is 0).
fn nested_boxes() -> SBoxedStrategy<Scene> {
    (grid_box(), prop::array::uniform3((0..=16i64, 0..=16i64)), any::<bool>())
        .prop_map(|((lo, hi), insets, flip)| {
            let mut blo = lo;
            let mut bhi = hi;
            for i in 0..3 {
                let len = hi[i] - lo[i];
                blo[i] = lo[i] + len * insets[i].0 as f64 / 64.0;
                bhi[i] = hi[i] - len * insets[i].1 as f64 / 64.0;
            }
            let (a, b) = (aabb(lo, hi), aabb(blo, bhi));
            if flip { (b, Some(a)) } else { (a, Some(b)) }
        })
        .sboxed()
}

/// What the far and resized families move.
fn moved_base() -> SBoxedStrategy<Scene> {
    prop_oneof![uniform_boxes(), exactly_touching()].sboxed()
}

/// The overlap families: uniform first, then biased.
pub(super) fn families() -> Vec<Family> {
    vec![
        Family::uniform("uniform boxes", uniform_boxes),
        Family::biased("boxes touching exactly on a face, edge or corner", exactly_touching),
        Family::biased("boxes a few ulps apart", few_ulps_apart),
        Family::biased("flat and point boxes", flat_boxes),
        Family::biased("nested boxes", nested_boxes),
        Family::biased("overlap far from the origin", || far_from_origin(moved_base())),
        Family::biased("overlap at tiny and huge sizes", || resized(moved_base())),
        Family::biased("edge walker: box faces ± k ulps", walk_box_faces),
    ]
}
