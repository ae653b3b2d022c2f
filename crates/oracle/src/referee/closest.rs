//! Exact closest points (Ericson, *Real-Time Collision Detection*, §5.1.2 and
//! §5.1.5), evaluated in rationals so every region test is decided exactly.

use super::exact::{Q, V3, cross, dot, is_zero, lerp, sub};

/// The point of segment `[a, b]` closest to `p`, exactly.
///
/// `t = (p − a)·(b − a) / ‖b − a‖²` clamped to `[0, 1]` (Ericson §5.1.2); a
/// zero-length segment is the point `a`.
pub(crate) fn closest_on_segment(p: &V3, a: &V3, b: &V3) -> V3 {
    let ab = sub(b, a);
    let len2 = dot(&ab, &ab);
    if len2.is_zero() {
        return a.clone();
    }
    let t = dot(&sub(p, a), &ab) / len2;
    if t <= Q::ZERO {
        a.clone()
    } else if t >= Q::ONE {
        b.clone()
    } else {
        lerp(a, b, &t)
    }
}

/// The point of the (solid) triangle `v` closest to `p`, exactly.
///
/// Ericson's `ClosestPtPointTriangle` (§5.1.5): the Voronoi regions of the three
/// vertices, then of the three edges, are tested in turn with the dot products
/// `d1 … d6` and the scaled barycentrics `va, vb, vc`; what remains is the face
/// region, answered by `a + v·ab + w·ac` with `v = vb/(va+vb+vc)`,
/// `w = vc/(va+vb+vc)`. In exact arithmetic every test is decided correctly, and
/// every denominator is a squared length (`d1 − d3 = ‖ab‖²`, `d2 − d6 = ‖ac‖²`,
/// `(d4 − d3) + (d5 − d6) = ‖bc‖²`, `va + vb + vc = ‖ab × ac‖²`).
///
/// Deviation from the book: a zero-area triangle (`ab × ac = 0`), on which the
/// book may divide by zero, is the segment or point it collapsed to; its closest
/// point is the closest of its three edges' (the longest edge spans it).
pub(crate) fn closest_on_triangle(p: &V3, v: &[V3; 3]) -> V3 {
    let [a, b, c] = v;
    let ab = sub(b, a);
    let ac = sub(c, a);
    if is_zero(&cross(&ab, &ac)) {
        let candidates = [closest_on_segment(p, a, b), closest_on_segment(p, b, c), closest_on_segment(p, c, a)];
        let dist2 = |x: &V3| {
            let d = sub(p, x);
            dot(&d, &d)
        };
        let mut best = candidates[0].clone();
        let mut best_d = dist2(&best);
        for cand in &candidates[1..] {
            let d = dist2(cand);
            if d < best_d {
                best_d = d;
                best = cand.clone();
            }
        }
        return best;
    }

    let ap = sub(p, a);
    let d1 = dot(&ab, &ap);
    let d2 = dot(&ac, &ap);
    if d1 <= Q::ZERO && d2 <= Q::ZERO {
        return a.clone();
    }
    let bp = sub(p, b);
    let d3 = dot(&ab, &bp);
    let d4 = dot(&ac, &bp);
    if d3 >= Q::ZERO && d4 <= d3 {
        return b.clone();
    }
    let vc = &d1 * &d4 - &d3 * &d2;
    if vc <= Q::ZERO && d1 >= Q::ZERO && d3 <= Q::ZERO {
        let t = &d1 / (&d1 - &d3);
        return lerp(a, b, &t);
    }
    let cp = sub(p, c);
    let d5 = dot(&ab, &cp);
    let d6 = dot(&ac, &cp);
    if d6 >= Q::ZERO && d5 <= d6 {
        return c.clone();
    }
    let vb = &d5 * &d2 - &d1 * &d6;
    if vb <= Q::ZERO && d2 >= Q::ZERO && d6 <= Q::ZERO {
        let t = &d2 / (&d2 - &d6);
        return lerp(a, c, &t);
    }
    let va = &d3 * &d6 - &d5 * &d4;
    let d43 = &d4 - &d3;
    let d56 = &d5 - &d6;
    if va <= Q::ZERO && d43 >= Q::ZERO && d56 >= Q::ZERO {
        let t = &d43 / (&d43 + &d56);
        return lerp(b, c, &t);
    }
    let denom = &va + &vb + &vc;
    let v = vb / &denom;
    let w = vc / &denom;
    let mut q = a.clone();
    for i in 0..3 {
        q[i] = &q[i] + &v * &ab[i] + &w * &ac[i];
    }
    q
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::v3;

    fn pt(x: f64, y: f64, z: f64) -> V3 {
        v3(&[x, y, z], "p").unwrap()
    }

    fn tri() -> [V3; 3] {
        // Right triangle in z = 0 with legs 2 on x and y.
        [pt(0.0, 0.0, 0.0), pt(2.0, 0.0, 0.0), pt(0.0, 2.0, 0.0)]
    }

    #[test]
    fn referee_closest_every_region_of_ericson() {
        // (point, expected closest point, region) — each derived by hand from the
        // triangle (0,0,0), (2,0,0), (0,2,0).
        let cases = [
            ((0.5, 0.5, 3.0), (0.5, 0.5, 0.0), "face: drop z"),
            ((-1.0, -1.0, 1.0), (0.0, 0.0, 0.0), "vertex a"),
            ((3.0, -1.0, 0.0), (2.0, 0.0, 0.0), "vertex b"),
            ((-1.0, 3.0, 0.0), (0.0, 2.0, 0.0), "vertex c"),
            ((1.0, -1.0, 0.0), (1.0, 0.0, 0.0), "edge ab: drop y"),
            ((-1.0, 1.0, 0.0), (0.0, 1.0, 0.0), "edge ac: drop x"),
            // Edge bc is x + y = 2; (2,2,0) projects to (1,1,0).
            ((2.0, 2.0, 5.0), (1.0, 1.0, 0.0), "edge bc"),
        ];
        for (p, want, what) in cases {
            let got = closest_on_triangle(&pt(p.0, p.1, p.2), &tri());
            assert_eq!(got, pt(want.0, want.1, want.2), "{what}");
        }
    }

    #[test]
    fn referee_closest_zero_area_triangle_is_its_segment() {
        // Collinear vertices on the x axis spanning [0, 4]: (1, 3, 0) → (1, 0, 0),
        // (7, 1, 0) → (4, 0, 0); all three vertices equal → that vertex.
        let flat = [pt(0.0, 0.0, 0.0), pt(4.0, 0.0, 0.0), pt(2.0, 0.0, 0.0)];
        assert_eq!(closest_on_triangle(&pt(1.0, 3.0, 0.0), &flat), pt(1.0, 0.0, 0.0));
        assert_eq!(closest_on_triangle(&pt(7.0, 1.0, 0.0), &flat), pt(4.0, 0.0, 0.0));
        let dot3 = [pt(1.0, 1.0, 1.0), pt(1.0, 1.0, 1.0), pt(1.0, 1.0, 1.0)];
        assert_eq!(closest_on_triangle(&pt(0.0, 0.0, 0.0), &dot3), pt(1.0, 1.0, 1.0));
    }
}
