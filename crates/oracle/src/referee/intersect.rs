//! Segment against a plane, a triangle or a triangle mesh, exactly.
//!
//! A segment is `p0 + t (p1 − p0)`, `t ∈ [0, 1]`. The reported normal is the
//! surface's own unit normal (a plane's `n/‖n‖`, a triangle's
//! `(v1 − v0) × (v2 − v0)` normalized), never flipped toward the segment.

use super::barycentric::barycentric_exact;
use super::error::RefereeError;
use super::exact::{Q, V3, add, cross, dot, is_zero, q, round, round_unit, round_v, scale, sub, v3};
use crate::geom::{IntersectAnswer, P3, Plane, Segment, SegmentHit, Triangle};

/// Where the segment's line crosses a plane `N·x = k`, exactly.
enum Crossing {
    /// `N·(p1 − p0) = 0`: parallel (coplanar included).
    Parallel,
    /// The line meets the plane at parameter `t` (any real; not yet clamped).
    At(Q),
}

/// `t = (k − N·p0) / (N·(p1 − p0))`, from `N·(p0 + t (p1 − p0)) = k`.
fn crossing(p0: &V3, dir: &V3, n: &V3, k: &Q) -> Crossing {
    let den = dot(n, dir);
    if den.is_zero() {
        return Crossing::Parallel;
    }
    Crossing::At((k - dot(n, p0)) / den)
}

/// The floating-point stage's answer ([`super::intersect_fast`]), counted.
fn staged<T>(fast: impl FnOnce() -> Option<T>) -> Option<T> {
    super::stage::fast_stage(super::stage::Stage::Intersect, fast)
}

fn segment(s: &Segment, field: [&'static str; 2]) -> Result<(V3, V3), RefereeError> {
    let p0 = v3(&s.start, field[0])?;
    let p1 = v3(&s.end, field[1])?;
    let dir = sub(&p1, &p0);
    Ok((p0, dir))
}

fn degenerate() -> IntersectAnswer {
    IntersectAnswer { hit: None, parallel: false, degenerate: true }
}

fn parallel() -> IntersectAnswer {
    IntersectAnswer { hit: None, parallel: true, degenerate: false }
}

fn miss() -> IntersectAnswer {
    IntersectAnswer { hit: None, parallel: false, degenerate: false }
}

/// The smaller of two exact rationals.
fn min_q(a: Q, b: Q) -> Q {
    if b < a { b } else { a }
}

/// `min(t, 1 − t)`: ≥ 0 exactly when `t ∈ [0, 1]`.
fn t_margin(t: &Q) -> Q {
    min_q(t.clone(), Q::ONE - t)
}

/// Intersection of segment `s` with the plane `p` (`n·x = d`).
///
/// **Definition** (the lecture's formula, decided exactly): with `u = p1 − p0`,
///
/// ```text
/// parallel ⇔ n·u = 0                        (exactly; coplanar included)
/// t        = (d − n·p0) / (n·u)             (from n·(p0 + t u) = d)
/// hit      ⇔ 0 ≤ t ≤ 1,   point = p0 + t u,   normal = n/‖n‖
/// ```
///
/// Source: the lecture's formula; Ericson §5.3.1.
///
/// `t` and the point are exact rationals, correctly rounded; the normal is
/// correctly rounded componentwise. A parallel segment never hits, even lying in
/// the plane (the fixture format's convention): `parallel: true`, no hit.
///
/// **Degenerate input.** A zero-length segment (`p0 = p1`) has no direction:
/// `degenerate: true`, no hit, `parallel: false` (a point is neither parallel nor
/// crossing). A zero normal is refused with [`RefereeError::ZeroNormal`].
pub fn intersect_segment_plane(s: &Segment, p: &Plane) -> Result<IntersectAnswer, RefereeError> {
    if let Some(answer) = staged(|| super::intersect_fast::segment_plane(s, p)) {
        return Ok(answer);
    }
    let (p0, dir) = segment(s, ["a.start", "a.end"])?;
    let n = v3(&p.normal, "b.normal")?;
    let d = q(p.offset, "b.offset")?;
    if is_zero(&n) {
        return Err(RefereeError::ZeroNormal { field: "b.normal" });
    }
    if is_zero(&dir) {
        return Ok(degenerate());
    }
    let t = match crossing(&p0, &dir, &n, &d) {
        Crossing::Parallel => return Ok(parallel()),
        Crossing::At(t) => t,
    };
    if t < Q::ZERO || t > Q::ONE {
        return Ok(miss());
    }
    let point = along(&p0, &dir, &t);
    Ok(IntersectAnswer {
        hit: Some(SegmentHit {
            t: round(&t),
            point: round_v(&point),
            normal: round_unit(&n),
            barycentric: None,
            triangle: None,
        }),
        parallel: false,
        degenerate: false,
    })
}

/// `p0 + t u`, exactly.
fn along(p0: &V3, dir: &V3, t: &Q) -> V3 {
    add(p0, &scale(dir, t))
}

/// The signed distance of [`intersect_segment_plane`]'s candidate from the edge
/// of the valid region, `min(t, 1 − t)`, correctly rounded: ≥ 0 exactly when the
/// segment hits. `None` when there is no candidate point (parallel or
/// zero-length segment).
pub fn intersect_margin_segment_plane(s: &Segment, p: &Plane) -> Result<Option<f64>, RefereeError> {
    if let Some(margin) = staged(|| super::intersect_fast::segment_plane_margin(s, p)) {
        return Ok(Some(margin));
    }
    let (p0, dir) = segment(s, ["a.start", "a.end"])?;
    let n = v3(&p.normal, "b.normal")?;
    let d = q(p.offset, "b.offset")?;
    if is_zero(&n) {
        return Err(RefereeError::ZeroNormal { field: "b.normal" });
    }
    if is_zero(&dir) {
        return Ok(None);
    }
    Ok(match crossing(&p0, &dir, &n, &d) {
        Crossing::Parallel => None,
        Crossing::At(t) => Some(round(&t_margin(&t))),
    })
}

/// One triangle's exact candidate: `t`, the point of the line on the plane, its
/// barycentrics, and the face normal `(v1 − v0) × (v2 − v0)` (not normalized).
struct Candidate {
    t: Q,
    point: V3,
    bary: [Q; 3],
    normal: V3,
}

impl Candidate {
    fn hits(&self) -> bool {
        self.t >= Q::ZERO && self.t <= Q::ONE && self.bary.iter().all(|b| *b >= Q::ZERO)
    }

    /// `min(t, 1 − t, α, β, γ)`.
    fn margin(&self) -> Q {
        let mut m = t_margin(&self.t);
        for b in &self.bary {
            m = min_q(m, b.clone());
        }
        m
    }
}

enum TriangleCase {
    /// Zero-area triangle: no plane, no normal.
    Flat,
    Parallel,
    /// The line crosses the plane (boxed: rationals are large).
    Line(Box<Candidate>),
}

fn triangle_case(p0: &V3, dir: &V3, v: &[V3; 3]) -> TriangleCase {
    let normal = cross(&sub(&v[1], &v[0]), &sub(&v[2], &v[0]));
    if is_zero(&normal) {
        return TriangleCase::Flat;
    }
    let k = dot(&normal, &v[0]);
    let t = match crossing(p0, dir, &normal, &k) {
        Crossing::Parallel => return TriangleCase::Parallel,
        Crossing::At(t) => t,
    };
    let point = along(p0, dir, &t);
    // The triangle has area, so its barycentrics exist.
    match barycentric_exact(&point, v) {
        Some(bary) => TriangleCase::Line(Box::new(Candidate { t, point, bary, normal })),
        None => TriangleCase::Flat,
    }
}

fn hit_of(c: &Candidate, face: Option<usize>) -> SegmentHit {
    SegmentHit {
        t: round(&c.t),
        point: round_v(&c.point),
        normal: round_unit(&c.normal),
        barycentric: Some([round(&c.bary[0]), round(&c.bary[1]), round(&c.bary[2])]),
        triangle: face,
    }
}

fn triangle(t: &Triangle, field: &'static str) -> Result<[V3; 3], RefereeError> {
    Ok([v3(&t.vertices[0], field)?, v3(&t.vertices[1], field)?, v3(&t.vertices[2], field)?])
}

/// Intersection of segment `s` with triangle `t` (a two-sided solid sheet, edges
/// and vertices included).
///
/// **Definition** (decided exactly, the robust counterpart of the lecture's
/// "plane hit, then inside test"): with `u = p1 − p0` and the face normal
/// `N = (v1 − v0) × (v2 − v0)`,
///
/// ```text
/// parallel ⇔ N·u = 0                               (coplanar included: no hit)
/// t        = N·(v0 − p0) / (N·u),   X = p0 + t u   (the line meets the plane)
/// [α,β,γ]  = barycentrics of X                     (normal equations, exact)
/// hit      ⇔ 0 ≤ t ≤ 1  and  α, β, γ ≥ 0
/// ```
///
/// Source: the lecture's plane-then-inside method, with Ericson §5.3.6's
/// conventions (two-sided, closed triangle); the inside test uses exact
/// barycentrics instead of floating-point triple products.
///
/// So a segment through an edge or a vertex hits, one ending on the face hits
/// (`t = 1`), and one stopping any positive distance short misses. The reported
/// `t`, point and barycentrics are the exact rationals correctly rounded, and the
/// normal is `N/‖N‖` correctly rounded (not flipped toward the segment).
///
/// **Degenerate input.** A zero-length segment or a zero-area triangle
/// (`N = 0`): `degenerate: true`, no hit, `parallel: false` — the direction or
/// the plane needed to classify does not exist (the fixture format's rule).
pub fn intersect_segment_triangle(s: &Segment, t: &Triangle) -> Result<IntersectAnswer, RefereeError> {
    if let Some(answer) = staged(|| super::intersect_fast::segment_triangle(s, t)) {
        return Ok(answer);
    }
    let (p0, dir) = segment(s, ["a.start", "a.end"])?;
    let v = triangle(t, "b.vertices")?;
    if is_zero(&dir) {
        return Ok(degenerate());
    }
    Ok(match triangle_case(&p0, &dir, &v) {
        TriangleCase::Flat => degenerate(),
        TriangleCase::Parallel => parallel(),
        TriangleCase::Line(c) if c.hits() => {
            IntersectAnswer { hit: Some(hit_of(&c, None)), parallel: false, degenerate: false }
        }
        TriangleCase::Line(..) => miss(),
    })
}

/// The signed distance of [`intersect_segment_triangle`]'s candidate point from
/// the edge of the valid region, `min(t, 1 − t, α, β, γ)` (exact, then correctly
/// rounded): ≥ 0 exactly when the segment hits, negative when the line's
/// crossing lies off the segment or outside the triangle (the sign bit is the
/// decision, as for every referee margin). `None` when there is no candidate
/// (parallel, zero-length segment, zero-area triangle): no crossing point exists
/// to measure, and the case is decided by the `parallel` / `degenerate` flags.
pub fn intersect_margin_segment_triangle(s: &Segment, t: &Triangle) -> Result<Option<f64>, RefereeError> {
    if let Some(margin) = staged(|| super::intersect_fast::segment_triangle_margin(s, t)) {
        return Ok(Some(margin));
    }
    let (p0, dir) = segment(s, ["a.start", "a.end"])?;
    let v = triangle(t, "b.vertices")?;
    if is_zero(&dir) {
        return Ok(None);
    }
    Ok(match triangle_case(&p0, &dir, &v) {
        TriangleCase::Line(c) => Some(round(&c.margin())),
        TriangleCase::Flat | TriangleCase::Parallel => None,
    })
}

/// First intersection of segment `s` with a triangle mesh (`vertices`, and
/// `triangles` as 0-based index triples, each face oriented as a triangle).
///
/// **Definition.** Every face is classified as by [`intersect_segment_triangle`];
/// the hit is the one with the smallest exact `t` (ties — a segment through a
/// shared edge or vertex — go to the lowest face index), reported with its face
/// index in `triangle`.
///
/// - `parallel: true` when nothing is hit, at least one face has area, and every
///   face with area is parallel to the segment (a flat mesh in the segment's
///   plane, say).
/// - `degenerate: true` when the segment has zero length (no hit, as for one
///   triangle), or when some face has zero area: such a face has no normal and is
///   skipped, and the flag says the answer ignored it.
///
/// A face naming a vertex out of range is refused with
/// [`RefereeError::IndexOutOfRange`].
pub fn intersect_segment_mesh(
    s: &Segment,
    vertices: &[P3],
    triangles: &[[usize; 3]],
) -> Result<IntersectAnswer, RefereeError> {
    if let Some(answer) = staged(|| super::intersect_fast::segment_mesh(s, vertices, triangles)) {
        return Ok(answer);
    }
    let (p0, dir) = segment(s, ["a.start", "a.end"])?;
    let verts = vertices.iter().map(|p| v3(p, "b.vertices")).collect::<Result<Vec<_>, _>>()?;
    for (face, tri) in triangles.iter().enumerate() {
        if tri.iter().any(|&i| i >= verts.len()) {
            return Err(RefereeError::IndexOutOfRange { field: "b.triangles", face });
        }
    }
    if is_zero(&dir) {
        return Ok(degenerate());
    }
    let mut best: Option<(Box<Candidate>, usize)> = None;
    let mut skipped_flat = false;
    let mut all_parallel = true;
    let mut any_area = false;
    for (face, tri) in triangles.iter().enumerate() {
        let v = [verts[tri[0]].clone(), verts[tri[1]].clone(), verts[tri[2]].clone()];
        match triangle_case(&p0, &dir, &v) {
            TriangleCase::Flat => skipped_flat = true,
            TriangleCase::Parallel => any_area = true,
            TriangleCase::Line(c) => {
                any_area = true;
                all_parallel = false;
                let better = best.as_ref().is_none_or(|(b, _)| c.t < b.t);
                if c.hits() && better {
                    best = Some((c, face));
                }
            }
        }
    }
    let hit = best.map(|(c, face)| hit_of(&c, Some(face)));
    let parallel = hit.is_none() && any_area && all_parallel;
    Ok(IntersectAnswer { hit, parallel, degenerate: skipped_flat })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::within_ulps;

    /// The referee is correctly rounded and the expectations are exact small
    /// dyadic numbers or independently derived correctly rounded literals.
    const EXACT_ULPS: u64 = 0;

    /// `1/√3` correctly rounded: `float(Decimal(1) / Decimal(3).sqrt())` at 60
    /// digits in CPython (Decimal → float is correctly rounded). Naive f64
    /// `1.0 / 3f64.sqrt()` gives the next float up, 0.5773502691896258.
    const INV_SQRT3: f64 = 0.5773502691896257;

    fn close(got: f64, want: f64, what: &str) {
        assert!(within_ulps(got, want, EXACT_ULPS), "{what}: got {got:e}, want {want:e}");
    }

    fn close_v(got: P3, want: P3, what: &str) {
        for k in 0..3 {
            assert!(within_ulps(got[k], want[k], EXACT_ULPS), "{what}[{k}]: got {got:?}, want {want:?}");
        }
    }

    fn seg(start: P3, end: P3) -> Segment {
        Segment { start, end }
    }

    fn ground() -> Plane {
        Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 }
    }

    fn unit_tri() -> Triangle {
        Triangle { vertices: [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] }
    }

    fn hit(a: Result<IntersectAnswer, RefereeError>, what: &str) -> SegmentHit {
        let a = a.unwrap_or_else(|e| panic!("{what}: refused: {e}"));
        assert!(!a.parallel && !a.degenerate, "{what}: flags {a:?}");
        a.hit.unwrap_or_else(|| panic!("{what}: expected a hit"))
    }

    #[test]
    fn referee_segment_plane_hits() {
        // (segment, plane, t, point) by hand from t = (d − n·p0)/(n·u).
        let half = Plane { normal: [0.0, 0.0, 4.0], offset: 2.0 }; // z = 0.5
        let cases = [
            (seg([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]), ground(), 0.5, [0.0; 3], "through"),
            (seg([0.0, 0.0, 1.0], [0.0, 0.0, 0.0]), ground(), 1.0, [0.0; 3], "ends on the plane"),
            (seg([3.0, 0.0, 0.0], [3.0, 0.0, 5.0]), ground(), 0.0, [3.0, 0.0, 0.0], "starts on it"),
            (seg([0.0, 0.0, 0.0], [0.0, 0.0, 2.0]), half, 0.25, [0.0, 0.0, 0.5], "unnormalized n"),
        ];
        for (s, p, t, point, what) in cases {
            let h = hit(intersect_segment_plane(&s, &p), what);
            close(h.t, t, what);
            close_v(h.point, point, what);
            close_v(h.normal, [0.0, 0.0, 1.0], what);
            assert_eq!(h.barycentric, None, "{what}");
            assert!(intersect_margin_segment_plane(&s, &p).unwrap().unwrap() >= 0.0, "{what}");
        }
    }

    #[test]
    fn referee_segment_plane_tilted_normal_is_correctly_rounded() {
        // n = (1,1,1), d = 1, segment (0,0,0)→(1,1,1): t = 1/3, point (1/3,1/3,1/3),
        // normal (1,1,1)/√3. 1/3 correctly rounded is 1.0/3.0 (IEEE division).
        let p = Plane { normal: [1.0; 3], offset: 1.0 };
        let h = hit(intersect_segment_plane(&seg([0.0; 3], [1.0; 3]), &p), "tilted");
        let third = 1.0 / 3.0;
        close(h.t, third, "t");
        close_v(h.point, [third; 3], "point");
        close_v(h.normal, [INV_SQRT3; 3], "normal");
    }

    #[test]
    fn referee_segment_plane_stopping_1e_300_short_misses() {
        // End at z = ε = 1e-300: t = 1/(1 − ε) > 1, a miss. The margin 1 − t =
        // −ε/(1 − ε) differs from −ε by a relative ε, far below half an ulp, so
        // it rounds to the f64 −ε itself.
        let s = seg([0.0, 0.0, 1.0], [0.0, 0.0, 1e-300]);
        let a = intersect_segment_plane(&s, &ground()).unwrap();
        assert_eq!(a.hit, None);
        assert!(!a.parallel && !a.degenerate);
        close(intersect_margin_segment_plane(&s, &ground()).unwrap().unwrap(), -1e-300, "margin");
    }

    #[test]
    fn referee_segment_plane_parallel_and_degenerate() {
        for (s, what) in
            [(seg([0.0, 0.0, 1.0], [1.0, 0.0, 1.0]), "above"), (seg([0.0, 0.0, 0.0], [1.0, 2.0, 0.0]), "coplanar")]
        {
            let a = intersect_segment_plane(&s, &ground()).unwrap();
            assert_eq!(a, IntersectAnswer { hit: None, parallel: true, degenerate: false }, "{what}");
            assert_eq!(intersect_margin_segment_plane(&s, &ground()).unwrap(), None, "{what}");
        }
        let point = seg([0.0; 3], [0.0; 3]);
        let a = intersect_segment_plane(&point, &ground()).unwrap();
        assert_eq!(a, IntersectAnswer { hit: None, parallel: false, degenerate: true });
        let zero = Plane { normal: [0.0; 3], offset: 0.0 };
        assert_eq!(intersect_segment_plane(&point, &zero), Err(RefereeError::ZeroNormal { field: "b.normal" }));
        let nan = seg([0.0; 3], [0.0, f64::INFINITY, 0.0]);
        assert_eq!(intersect_segment_plane(&nan, &ground()), Err(RefereeError::NonFinite { field: "a.end" }));
    }

    #[test]
    fn referee_segment_plane_huge_and_tiny() {
        // Along z from 1·s to −3·s (s = 2^±1000, exact scalings): t = 1/4,
        // point (s, 0, 0). Naive f64 products n·p overflow or underflow in none of
        // the rational steps.
        for s in [2f64.powi(1000), 2f64.powi(-1000), 1e300] {
            let h = hit(intersect_segment_plane(&seg([s, 0.0, s], [s, 0.0, -3.0 * s]), &ground()), "scaled");
            close(h.t, 0.25, "t");
            close_v(h.point, [s, 0.0, 0.0], "point");
        }
    }

    #[test]
    fn referee_segment_triangle_face_edge_vertex() {
        // Unit right triangle in z = 0; vertical segments from z = 1 to z = −1 cross
        // at t = 1/2; the barycentrics of (x, y, 0) are [1 − x − y, x, y].
        let cases = [
            ([0.25, 0.25], [0.5, 0.25, 0.25], 0.25, "face"),
            ([0.5, 0.0], [0.5, 0.5, 0.0], 0.0, "edge v0v1"),
            ([0.5, 0.5], [0.0, 0.5, 0.5], 0.0, "edge v1v2 (hypotenuse)"),
            ([1.0, 0.0], [0.0, 1.0, 0.0], 0.0, "vertex v1"),
        ];
        for ([x, y], bary, margin, what) in cases {
            let s = seg([x, y, 1.0], [x, y, -1.0]);
            let h = hit(intersect_segment_triangle(&s, &unit_tri()), what);
            close(h.t, 0.5, what);
            close_v(h.point, [x, y, 0.0], what);
            close_v(h.normal, [0.0, 0.0, 1.0], what);
            close_v(h.barycentric.expect("barycentric"), bary, what);
            close(intersect_margin_segment_triangle(&s, &unit_tri()).unwrap().unwrap(), margin, what);
        }
        // From below: same hit, normal not flipped toward the segment.
        let h = hit(intersect_segment_triangle(&seg([0.25, 0.25, -1.0], [0.25, 0.25, 1.0]), &unit_tri()), "below");
        close_v(h.normal, [0.0, 0.0, 1.0], "below");
        // Clockwise winding: the face normal is −z.
        let cw = Triangle { vertices: [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]] };
        let h = hit(intersect_segment_triangle(&seg([0.25, 0.25, 1.0], [0.25, 0.25, -1.0]), &cw), "cw");
        close_v(h.normal, [0.0, 0.0, -1.0], "cw");
    }

    #[test]
    fn referee_segment_triangle_misses_by_the_smallest_amounts() {
        // Just outside edge v0v1: y = −2⁻⁶⁰ makes γ = −2⁻⁶⁰ < 0, a miss with that margin.
        let y = -(2f64.powi(-60));
        let s = seg([0.5, y, 1.0], [0.5, y, -1.0]);
        assert_eq!(intersect_segment_triangle(&s, &unit_tri()).unwrap().hit, None);
        close(intersect_margin_segment_triangle(&s, &unit_tri()).unwrap().unwrap(), y, "edge margin");
        // Stopping 1e-300 above the face: t = 1/(1 − 1e-300) > 1, a miss; margin
        // min(t, 1 − t, ½, ¼, ¼) = 1 − t, which rounds to −1e-300 (see the plane case).
        let s = seg([0.25, 0.25, 1.0], [0.25, 0.25, 1e-300]);
        let a = intersect_segment_triangle(&s, &unit_tri()).unwrap();
        assert_eq!(a, IntersectAnswer { hit: None, parallel: false, degenerate: false });
        close(intersect_margin_segment_triangle(&s, &unit_tri()).unwrap().unwrap(), -1e-300, "short margin");
        // Ending exactly on the face: t = 1, a hit.
        let h = hit(intersect_segment_triangle(&seg([0.25, 0.25, 1.0], [0.25, 0.25, 0.0]), &unit_tri()), "ends on");
        close(h.t, 1.0, "t");
    }

    #[test]
    fn referee_segment_triangle_parallel_and_degenerate() {
        for (s, what) in [
            (seg([-1.0, 0.25, 0.0], [2.0, 0.25, 0.0]), "coplanar, crossing the triangle"),
            (seg([0.0, 0.0, 1.0], [1.0, 1.0, 1.0]), "parallel above"),
        ] {
            let a = intersect_segment_triangle(&s, &unit_tri()).unwrap();
            assert_eq!(a, IntersectAnswer { hit: None, parallel: true, degenerate: false }, "{what}");
        }
        let degenerate = IntersectAnswer { hit: None, parallel: false, degenerate: true };
        let flat = Triangle { vertices: [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]] };
        let s = seg([0.5, 0.0, 1.0], [0.5, 0.0, -1.0]);
        assert_eq!(intersect_segment_triangle(&s, &flat).unwrap(), degenerate, "zero area");
        assert_eq!(intersect_margin_segment_triangle(&s, &flat).unwrap(), None);
        let point = seg([0.25, 0.25, 0.0], [0.25, 0.25, 0.0]);
        assert_eq!(intersect_segment_triangle(&point, &unit_tri()).unwrap(), degenerate, "zero length");
    }

    #[test]
    fn referee_segment_triangle_huge_and_tiny() {
        // The face case scaled by s (2^±1000 exact; 1e300 where x·s products are
        // exact powers of two of s): t = 1/2, point (s/4, s/4, 0), barycentrics
        // [1/2, 1/4, 1/4] whatever the scale.
        for s in [2f64.powi(1000), 2f64.powi(-1000), 1e300, 1e-300] {
            let t = Triangle { vertices: [[0.0; 3], [s, 0.0, 0.0], [0.0, s, 0.0]] };
            let h =
                hit(intersect_segment_triangle(&seg([0.25 * s, 0.25 * s, s], [0.25 * s, 0.25 * s, -s]), &t), "scaled");
            close(h.t, 0.5, "t");
            close_v(h.point, [0.25 * s, 0.25 * s, 0.0], "point");
            close_v(h.barycentric.unwrap(), [0.5, 0.25, 0.25], "barycentric");
        }
    }

    #[test]
    fn referee_segment_mesh_first_hit_and_ties() {
        // A unit square in z = 0 as two faces sharing the diagonal v0v2, and a
        // second square at z = −1.
        let vertices = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, -1.0],
            [1.0, 1.0, -1.0],
        ];
        let triangles = [[4, 5, 6], [0, 1, 2], [0, 2, 3]];
        // Downward through the diagonal at (0.5, 0.5): faces 1 and 2 both hit at
        // t = 1/4 (z from 1 to −3), face 0 later at t = 1/2: face 1 wins the tie.
        let s = seg([0.5, 0.5, 1.0], [0.5, 0.5, -3.0]);
        let a = intersect_segment_mesh(&s, &vertices, &triangles).unwrap();
        let h = a.hit.expect("hit");
        assert_eq!(h.triangle, Some(1));
        close(h.t, 0.25, "t");
        close_v(h.barycentric.unwrap(), [0.5, 0.0, 0.5], "barycentric on v0v2");
        // Upward from below: the lower square comes first (t = 1/4 of z −2 → 2).
        let s = seg([0.75, 0.25, -2.0], [0.75, 0.25, 2.0]);
        let h = intersect_segment_mesh(&s, &vertices, &triangles).unwrap().hit.expect("hit");
        assert_eq!(h.triangle, Some(0));
        close(h.t, 0.25, "t");
        // In the upper square's plane, stopping short of x = 1: every horizontal
        // face is parallel, so the mesh is; adding the wall x = 1 (face [1, 2, 5],
        // crossed by the line at t = 4/3 > 1) makes it a plain miss.
        let s = seg([-1.0, 0.5, 0.0], [0.5, 0.5, 0.0]);
        let a = intersect_segment_mesh(&s, &vertices, &triangles).unwrap();
        assert_eq!(a, IntersectAnswer { hit: None, parallel: true, degenerate: false });
        let a = intersect_segment_mesh(&s, &vertices, &[[0, 1, 2], [1, 2, 5]]).unwrap();
        assert_eq!(a, IntersectAnswer { hit: None, parallel: false, degenerate: false });
        // A zero-area face is skipped and flagged; an index out of range refused.
        let a = intersect_segment_mesh(&seg([0.5, 0.5, 1.0], [0.5, 0.5, -3.0]), &vertices, &[[0, 1, 1], [0, 1, 2]])
            .unwrap();
        assert!(a.degenerate);
        assert_eq!(a.hit.expect("hit").triangle, Some(1));
        assert_eq!(
            intersect_segment_mesh(&s, &vertices, &[[0, 1, 7]]),
            Err(RefereeError::IndexOutOfRange { field: "b.triangles", face: 0 })
        );
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use proptest::prelude::*;

    fn coord() -> impl Strategy<Value = f64> {
        // Small integers make edge, vertex, coplanar and parallel cases common.
        prop_oneof![(-2i8..=2).prop_map(f64::from), -3.0..3.0f64]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coord(), coord(), coord()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn referee_intersect_margin_sign_is_the_decision(p0 in point(), p1 in point(), v0 in point(), v1 in point(), v2 in point()) {
            let s = Segment { start: p0, end: p1 };
            let t = Triangle { vertices: [v0, v1, v2] };
            let a = intersect_segment_triangle(&s, &t).unwrap();
            match intersect_margin_segment_triangle(&s, &t).unwrap() {
                Some(m) => prop_assert_eq!(a.hit.is_some(), !m.is_sign_negative(), "margin {}", m),
                None => prop_assert!(a.hit.is_none() && (a.parallel || a.degenerate), "no candidate: {:?}", a),
            }
        }

        #[test]
        fn referee_intersect_reversed_segment_hits_the_same_point(p0 in point(), p1 in point(), v0 in point(), v1 in point(), v2 in point()) {
            // The same exact point and barycentrics, so bitwise equal roundings.
            let t = Triangle { vertices: [v0, v1, v2] };
            let x = intersect_segment_triangle(&Segment { start: p0, end: p1 }, &t).unwrap();
            let y = intersect_segment_triangle(&Segment { start: p1, end: p0 }, &t).unwrap();
            prop_assert_eq!((x.parallel, x.degenerate, x.hit.is_some()), (y.parallel, y.degenerate, y.hit.is_some()));
            if let (Some(x), Some(y)) = (x.hit, y.hit) {
                prop_assert_eq!(x.point.map(f64::to_bits), y.point.map(f64::to_bits));
                prop_assert_eq!(x.barycentric.map(|b| b.map(f64::to_bits)), y.barycentric.map(|b| b.map(f64::to_bits)));
            }
        }

        #[test]
        fn referee_intersect_cyclic_relabelling_rotates_barycentrics(p0 in point(), p1 in point(), v0 in point(), v1 in point(), v2 in point()) {
            // (v1, v2, v0) has the same face normal; [α, β, γ] becomes [β, γ, α].
            let s = Segment { start: p0, end: p1 };
            let x = intersect_segment_triangle(&s, &Triangle { vertices: [v0, v1, v2] }).unwrap();
            let y = intersect_segment_triangle(&s, &Triangle { vertices: [v1, v2, v0] }).unwrap();
            prop_assert_eq!((x.parallel, x.degenerate, x.hit.is_some()), (y.parallel, y.degenerate, y.hit.is_some()));
            if let (Some(x), Some(y)) = (x.hit, y.hit) {
                let (bx, by) = (x.barycentric.unwrap(), y.barycentric.unwrap());
                prop_assert_eq!([bx[1], bx[2], bx[0]].map(f64::to_bits), by.map(f64::to_bits));
                prop_assert_eq!(x.t.to_bits(), y.t.to_bits());
                prop_assert_eq!(x.normal.map(f64::to_bits), y.normal.map(f64::to_bits));
            }
        }
    }
}
