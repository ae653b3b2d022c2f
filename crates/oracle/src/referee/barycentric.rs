//! Barycentric coordinates of a point with respect to a triangle, exactly.

use super::dyadic::{self as dy, Num};
use super::error::RefereeError;
use super::exact::{Q, V3, dot, round, sub, v3};
use crate::geom::{BarycentricAnswer, P3, Triangle};

/// Exact signed barycentrics `[α, β, γ]` of `p`'s orthogonal projection onto the
/// plane of `v`, or `None` when the triangle has zero area.
///
/// With `e1 = v1 − v0`, `e2 = v2 − v0`, `w = p − v0`, the projection is
/// `v0 + β e1 + γ e2` where `(β, γ)` solve the normal equations of the least
/// squares problem `min ‖β e1 + γ e2 − w‖`:
///
/// ```text
/// [e1·e1  e1·e2] [β]   [w·e1]
/// [e1·e2  e2·e2] [γ] = [w·e2],   det = (e1·e1)(e2·e2) − (e1·e2)² = ‖e1 × e2‖²
/// ```
///
/// solved by Cramer's rule; `α = 1 − β − γ`, so the sum is exactly 1.
pub(crate) fn barycentric_exact(p: &V3, v: &[V3; 3]) -> Option<[Q; 3]> {
    let e1 = sub(&v[1], &v[0]);
    let e2 = sub(&v[2], &v[0]);
    let w = sub(p, &v[0]);
    let (a, b, c) = (dot(&e1, &e1), dot(&e1, &e2), dot(&e2, &e2));
    let (d, e) = (dot(&w, &e1), dot(&w, &e2));
    let det = &a * &c - &b * &b;
    if det.is_zero() {
        return None;
    }
    let beta = (&c * &d - &b * &e) / &det;
    let gamma = (&a * &e - &b * &d) / &det;
    let alpha = Q::ONE - &beta - &gamma;
    Some([alpha, beta, gamma])
}

/// The fallback for a zero-area triangle: barycentrics of the point of the
/// longest edge closest to `p` (edges in the order v0v1, v1v2, v2v0; the first
/// wins a tie), or `[1, 0, 0]` when all three vertices coincide.
fn longest_edge_fallback(p: &V3, v: &[V3; 3]) -> [Q; 3] {
    let edges = [(0usize, 1usize), (1, 2), (2, 0)];
    let mut best = 0;
    let mut best_len = Q::ZERO;
    for (k, &(i, j)) in edges.iter().enumerate() {
        let e = sub(&v[j], &v[i]);
        let len = dot(&e, &e);
        if len > best_len {
            best_len = len;
            best = k;
        }
    }
    let mut coords = [Q::ZERO, Q::ZERO, Q::ZERO];
    if best_len.is_zero() {
        coords[0] = Q::ONE;
        return coords;
    }
    let (i, j) = edges[best];
    let s = dot(&sub(p, &v[i]), &sub(&v[j], &v[i])) / &best_len;
    let s = if s < Q::ZERO {
        Q::ZERO
    } else if s > Q::ONE {
        Q::ONE
    } else {
        s
    };
    coords[i] = Q::ONE - &s;
    coords[j] = s;
    coords
}

/// The floating-point stage ([`super::fast`]): the exact stage's rationals in
/// double-word numbers that account for their error exactly, each coordinate
/// kept when its correct rounding is certified. With `N = e1 × e2`, the
/// normal equations' `det` is `N·N` (Lagrange's identity) — a sum of squares,
/// so a sliver's `det` keeps its precision — and the coordinates are the
/// signed-area ratios `α = ((v1 − p) × (v2 − p))·N / N·N`, `β = ((v2 − p) ×
/// (v0 − p))·N / N·N`, `γ = ((v0 − p) × (v1 − p))·N / N·N`, the same
/// rationals as Cramer's rule gives. A triangle whose `N` is exactly zero takes
/// the exact stage's fallback, decided on certified signs
/// ([`longest_edge_fast`]), flagged. `None` (the exact stage decides) for
/// inputs that are not finite, an `N` neither certainly zero nor certainly
/// not, a comparison the bounds leave open, or a coordinate not certified (a
/// tie, or too close to one for the bounds).
///
/// The same code then runs in exact dyadic numbers ([`super::dyadic`]) when
/// the double-word bounds leave something open: every sign is then certain
/// and each coordinate a correctly rounded quotient of exact integers.
fn barycentric_fast(p: &P3, t: &Triangle) -> Option<BarycentricAnswer> {
    use super::dyadic::Dy;
    use super::fast::Dw;
    barycentric_in::<Dw>(p, t).or_else(|| barycentric_in::<Dy>(p, t))
}

fn barycentric_in<T: Num>(p: &P3, t: &Triangle) -> Option<BarycentricAnswer> {
    let inputs = p.iter().chain(t.vertices.iter().flatten()).copied();
    if !super::fast::all_finite(inputs) {
        return None;
    }
    let v = &t.vertices;
    let n = dy::cross(&dy::diff3::<T>(&v[1], &v[0]), &dy::diff3::<T>(&v[2], &v[0]));
    let signs = [n[0].sign_of(), n[1].sign_of(), n[2].sign_of()];
    if signs.iter().all(|s| *s == Some(0)) {
        return Some(BarycentricAnswer { coords: longest_edge_fast::<T>(p, v)?, degenerate: true });
    }
    if !signs.iter().any(|s| matches!(s, Some(1 | -1))) {
        return None;
    }
    let det = dy::dot(&n, &n);
    let r: [[T; 3]; 3] = std::array::from_fn(|k| dy::diff3::<T>(&v[k], p));
    let area = |i: usize, j: usize| dy::dot(&dy::cross(&r[i], &r[j]), &n);
    let coords = [T::quotient(&area(1, 2), &det)?, T::quotient(&area(2, 0), &det)?, T::quotient(&area(0, 1), &det)?];
    Some(BarycentricAnswer { coords, degenerate: false })
}

/// [`longest_edge_fallback`] on certified signs: the longest edge (the first
/// of v0v1, v1v2, v2v0 on an exact tie), `p`'s parameter on it clamped to
/// `[0, 1]`, each coordinate a certified quotient; `[1, 0, 0]` when the
/// vertices coincide.
fn longest_edge_fast<T: Num>(p: &P3, v: &[P3; 3]) -> Option<[f64; 3]> {
    let edges = [(0usize, 1usize), (1, 2), (2, 0)];
    let mut best: Option<(usize, T)> = None;
    for (k, &(i, j)) in edges.iter().enumerate() {
        let e = dy::diff3::<T>(&v[j], &v[i]);
        let len = dy::dot(&e, &e);
        let longer = match &best {
            None => len.sign_of()? > 0,
            Some((_, b)) => len.minus(b).sign_of()? > 0,
        };
        if longer {
            best = Some((k, len));
        }
    }
    let Some((k, len)) = best else {
        return Some([1.0, 0.0, 0.0]);
    };
    let (i, j) = edges[k];
    let num = dy::dot(&dy::diff3::<T>(p, &v[i]), &dy::diff3::<T>(&v[j], &v[i]));
    let (ci, cj) = if num.sign_of()? <= 0 {
        (1.0, 0.0)
    } else if num.minus(&len).sign_of()? >= 0 {
        (0.0, 1.0)
    } else {
        (T::quotient(&len.minus(&num), &len)?, T::quotient(&num, &len)?)
    };
    let mut coords = [0.0; 3];
    coords[i] = ci;
    coords[j] = cj;
    Some(coords)
}

/// Signed barycentric coordinates `[α, β, γ]` of the orthogonal projection of `p`
/// onto the plane of triangle `t`, with `projection = α v0 + β v1 + γ v2` and
/// `α + β + γ = 1` (negative outside the triangle).
///
/// **Method.** The normal equations above, solved exactly in rationals by
/// Cramer's rule (`det = ‖(v1 − v0) × (v2 − v0)‖²`); they are equivalent to the
/// signed-area ratios `β = ((w × e2)·N)/‖N‖²`, `γ = ((e1 × w)·N)/‖N‖²` with
/// `N = e1 × e2` (Lagrange's identity), and for a point in the plane to the
/// lecture's area ratios with signs. The three coordinates sum to exactly 1
/// before each is correctly rounded. Source: Ericson §3.4 (`Barycentric`, the same
/// normal equations with `d00, d01, d11, d20, d21`), here in exact arithmetic.
///
/// **Degenerate input.** A zero-area triangle (`det = 0` exactly) has no plane:
/// `degenerate: true`, and the coordinates are those of the point of the longest
/// edge closest to `p` (clamped to the edge; the first of v0v1, v1v2, v2v0 wins a
/// tie), or `[1, 0, 0]` when all three vertices coincide. They still sum to 1.
///
/// **Stages.** A floating-point stage answers first and is kept only when
/// its error bounds certify every coordinate's rounding (`barycentric_fast`);
/// what they leave open is computed again in exact dyadic numbers, and only
/// what is still open then goes to the exact stage above. The bits are the
/// same either way.
pub fn barycentric_triangle(p: &P3, t: &Triangle) -> Result<BarycentricAnswer, RefereeError> {
    if super::stage::staged() {
        let fast = barycentric_fast(p, t);
        super::stage::count(super::stage::Stage::Barycentric, fast.is_some(), 1);
        if let Some(answer) = fast {
            return Ok(answer);
        }
    }
    let p = v3(p, "a.at")?;
    let v = [v3(&t.vertices[0], "b.vertices")?, v3(&t.vertices[1], "b.vertices")?, v3(&t.vertices[2], "b.vertices")?];
    let (coords, degenerate) = match barycentric_exact(&p, &v) {
        Some(c) => (c, false),
        None => (longest_edge_fallback(&p, &v), true),
    };
    Ok(BarycentricAnswer { coords: [round(&coords[0]), round(&coords[1]), round(&coords[2])], degenerate })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::within_ulps;

    /// Largest accepted distance, in ulps, from a correctly rounded reference
    /// computed independently. The referee is correctly rounded, so 0; kept named
    /// so every comparison states its allowance.
    const EXACT_ULPS: u64 = 0;

    fn tri(v: [[f64; 3]; 3]) -> Triangle {
        Triangle { vertices: v }
    }

    fn assert_coords(got: [f64; 3], want: [f64; 3], what: &str) {
        for k in 0..3 {
            assert!(within_ulps(got[k], want[k], EXACT_ULPS), "{what}: coord {k}: {got:?} vs {want:?}");
        }
    }

    #[test]
    fn referee_barycentric_vertices_centroid_and_outside() {
        // Right triangle (0,0,0), (2,0,0), (0,2,0): for a point (x, y, z),
        // β = x/2, γ = y/2, α = 1 − β − γ; z is dropped by the projection.
        let t = tri([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]]);
        let cases = [
            ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], "v0"),
            ([2.0, 0.0, 5.0], [0.0, 1.0, 0.0], "v1 lifted"),
            ([0.0, 2.0, -1.0], [0.0, 0.0, 1.0], "v2 lowered"),
            ([1.0, 1.0, 0.0], [0.0, 0.5, 0.5], "midpoint of v1v2"),
            ([3.0, 1.0, 0.0], [-1.0, 1.5, 0.5], "outside past v1v2"),
            ([-2.0, -2.0, 0.0], [3.0, -1.0, -1.0], "outside behind v0"),
        ];
        for (p, want, what) in cases {
            let got = barycentric_triangle(&p, &t).unwrap();
            assert!(!got.degenerate, "{what}");
            assert_coords(got.coords, want, what);
        }
    }

    #[test]
    fn referee_barycentric_thirds_are_correctly_rounded() {
        // Centroid of (0,0,0), (3,0,0), (0,3,0) is (1,1,0): every coordinate is
        // exactly 1/3, whose correct rounding is the literal 1.0/3.0 (IEEE
        // division is correctly rounded).
        let t = tri([[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.0, 3.0, 0.0]]);
        let got = barycentric_triangle(&[1.0, 1.0, 7.0], &t).unwrap();
        let third = 1.0 / 3.0;
        assert_coords(got.coords, [third, third, third], "centroid");
    }

    #[test]
    fn referee_barycentric_tilted_triangle_projects() {
        // Triangle (1,0,0), (0,1,0), (0,0,1) with normal (1,1,1)/√3. The point
        // (1,1,1) projects to (1/3,1/3,1/3) + ... : (1,1,1) − ((3 − 1)/3)(1,1,1)
        // = (1/3,1/3,1/3), the centroid: all coordinates 1/3.
        let t = tri([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let got = barycentric_triangle(&[1.0, 1.0, 1.0], &t).unwrap();
        let third = 1.0 / 3.0;
        assert_coords(got.coords, [third, third, third], "tilted centroid");
    }

    #[test]
    fn referee_barycentric_zero_area_uses_longest_edge() {
        // Collinear (0,0,0), (1,0,0), (4,0,0): the longest edge is v2v0
        // (length 4, from v2 to v0). The point (1,5,0) is closest to (1,0,0) on
        // it: s = ((1,5,0) − v2)·(v0 − v2)/16 = (−3·−4)/16 = 3/4, so v2 gets 1/4
        // and v0 gets 3/4.
        let t = tri([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [4.0, 0.0, 0.0]]);
        let got = barycentric_triangle(&[1.0, 5.0, 0.0], &t).unwrap();
        assert!(got.degenerate);
        assert_coords(got.coords, [0.75, 0.0, 0.25], "collinear");
        // All vertices equal: [1, 0, 0].
        let dot = tri([[2.0, 2.0, 2.0]; 3]);
        let got = barycentric_triangle(&[0.0, 0.0, 0.0], &dot).unwrap();
        assert!(got.degenerate);
        assert_coords(got.coords, [1.0, 0.0, 0.0], "coincident");
    }

    #[test]
    fn referee_barycentric_huge_and_tiny_scales() {
        // The unit right triangle scaled by 1e300 and by 1e-300, point at
        // (0.25, 0.5)·scale: β = 0.25, γ = 0.5, α = 0.25 exactly (the scale
        // cancels in the ratios; the f64 products 0.25·s and 0.5·s are exact
        // power-of-two scalings, and s itself is the same f64 in every vertex).
        for s in [1e300, 1e-300] {
            let t = tri([[0.0, 0.0, 0.0], [s, 0.0, 0.0], [0.0, s, 0.0]]);
            let got = barycentric_triangle(&[0.25 * s, 0.5 * s, s], &t).unwrap();
            assert_coords(got.coords, [0.25, 0.25, 0.5], "scaled");
        }
    }

    #[test]
    fn referee_barycentric_refuses_nan() {
        let t = tri([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(barycentric_triangle(&[f64::NAN, 0.0, 0.0], &t), Err(RefereeError::NonFinite { field: "a.at" }));
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use crate::referee::exact::{cross, is_zero};
    use proptest::prelude::*;

    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![(-2i8..=2).prop_map(f64::from), -3.0..3.0f64]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn referee_barycentric_exact_sum_and_reconstruction(p in [coord(), coord(), coord()], v in [[coord(), coord(), coord()], [coord(), coord(), coord()], [coord(), coord(), coord()]]) {
            // Before rounding: α + β + γ = 1 exactly, and αv0 + βv1 + γv2 − p is
            // parallel to the face normal (it is the projection's offset).
            let pe = v3(&p, "p").unwrap();
            let ve = [v3(&v[0], "v").unwrap(), v3(&v[1], "v").unwrap(), v3(&v[2], "v").unwrap()];
            let normal = cross(&sub(&ve[1], &ve[0]), &sub(&ve[2], &ve[0]));
            match barycentric_exact(&pe, &ve) {
                None => prop_assert!(is_zero(&normal), "only a zero-area triangle has no barycentrics"),
                Some(b) => {
                    prop_assert!((&b[0] + &b[1] + &b[2]) == Q::ONE, "sum is exactly 1");
                    let rebuilt: V3 = std::array::from_fn(|k| &b[0] * &ve[0][k] + &b[1] * &ve[1][k] + &b[2] * &ve[2][k]);
                    prop_assert!(is_zero(&cross(&sub(&rebuilt, &pe), &normal)), "offset along the normal");
                }
            }
            let answer = barycentric_triangle(&p, &Triangle { vertices: v }).unwrap();
            prop_assert_eq!(answer.degenerate, is_zero(&normal));
        }
    }
}
