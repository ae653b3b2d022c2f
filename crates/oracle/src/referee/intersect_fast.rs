//! The floating-point stage of a segment against a plane or a triangle
//! ([`super::fast`]): every output is a quotient of double-word polynomials
//! in the inputs, each certified correctly rounded ([`quotient`]), and every
//! decision a certified sign. A function here returns `None` whenever
//! anything is left open — a zero-length segment, a zero-area triangle, a
//! segment parallel to the plane (those the exact stage answers, with their
//! flags), a sign the bounds leave open, an output on a midpoint or beyond
//! `MAX`, inputs that are not finite or input the exact stage refuses — and the exact
//! stage then answers, with the same bits (`tests/referee_stages.rs`).
//!
//! For the triangle the crossing is written as Möller and Trumbore write it:
//! with `e1 = v1 − v0`, `e2 = v2 − v0`, `D = p1 − p0`, `T = p0 − v0`,
//! `det = e1·(D × e2)`, the crossing's `t = e2·(T × e1)/det` and its
//! barycentrics `β = T·(D × e2)/det`, `γ = D·(T × e1)/det`, `α = 1 − β − γ`:
//! degree 3 over degree 3, the same rationals as the exact stage's
//! `t = N·(v0 − p0)/(N·D)` and normal equations (the crossing lies in the
//! plane, where barycentrics are unique).

use super::fast::{Dw, all_finite, cross, diff3, dot, quotient};
use crate::geom::{IntersectAnswer, P3, Plane, Segment, SegmentHit, Triangle};

fn miss() -> IntersectAnswer {
    IntersectAnswer { hit: None, parallel: false, degenerate: false }
}

/// `v / ‖v‖` componentwise, certified, for a `v` with `v·v > 0` (the normal).
fn unit(v: &[Dw; 3]) -> Option<P3> {
    let s = dot(v, v);
    if !s.is_positive() {
        return None;
    }
    super::contact_fast::unit(v, s, super::fast::sqrt_approx(s))
}

/// The line's crossing as numerators over one denominator `den` (sign
/// certain, not zero): `t = tn/den`, the point `(p0·den + tn·D)/den`.
struct Crossing {
    p0: P3,
    d: [Dw; 3],
    den: Dw,
    tn: Dw,
    /// `den`'s sign.
    sd: i8,
}

impl Crossing {
    /// `x/den ≥ 0`.
    fn non_negative(&self, x: Dw) -> Option<bool> {
        Some(x.signum()? * self.sd >= 0)
    }

    /// `0 ≤ t ≤ 1`.
    fn on_segment(&self) -> Option<bool> {
        Some(self.non_negative(self.tn)? && self.non_negative(self.den.sub(self.tn))?)
    }

    fn t(&self) -> Option<f64> {
        quotient(self.tn, self.den)
    }

    fn point(&self) -> Option<P3> {
        let mut out = [0.0; 3];
        for (i, o) in out.iter_mut().enumerate() {
            *o = quotient(Dw::of(self.p0[i]).mul(self.den).add(self.tn.mul(self.d[i])), self.den)?;
        }
        Some(out)
    }

    /// The smallest of `xs[i]/den`, correctly rounded (equal numerators give
    /// the same value, whichever is taken).
    fn min_over(&self, xs: &[Dw]) -> Option<f64> {
        let mut best = xs[0];
        for &x in &xs[1..] {
            // x/den < best/den ⇔ (x − best)·sign(den) < 0.
            if x.sub(best).signum()? * self.sd < 0 {
                best = x;
            }
        }
        quotient(best, self.den)
    }
}

fn segment_parts(s: &Segment) -> Option<[Dw; 3]> {
    let d = diff3(&s.end, &s.start);
    if d.iter().all(|x| x.is_exact_zero()) {
        return None;
    }
    Some(d)
}

/// The segment against the plane `n·x = off`: `t = (off − n·p0)/(n·D)`.
fn plane_crossing(s: &Segment, p: &Plane) -> Option<([Dw; 3], Crossing)> {
    let numbers = s.start.iter().chain(&s.end).chain(&p.normal).copied().chain([p.offset]);
    if !all_finite(numbers) {
        return None;
    }
    let n = p.normal.map(Dw::of);
    if !dot(&n, &n).is_positive() {
        return None;
    }
    let d = segment_parts(s)?;
    let den = dot(&n, &d);
    let sd = den.signum()?;
    if sd == 0 {
        return None;
    }
    let tn = Dw::of(p.offset).sub(dot(&n, &s.start.map(Dw::of)));
    Some((n, Crossing { p0: s.start, d, den, tn, sd }))
}

/// Segment against plane, as `intersect_segment_plane` answers, or `None`.
pub(super) fn segment_plane(s: &Segment, p: &Plane) -> Option<IntersectAnswer> {
    let (n, c) = plane_crossing(s, p)?;
    if !c.on_segment()? {
        return Some(miss());
    }
    let hit = SegmentHit { t: c.t()?, point: c.point()?, normal: unit(&n)?, barycentric: None, triangle: None };
    Some(IntersectAnswer { hit: Some(hit), parallel: false, degenerate: false })
}

/// `min(t, 1 − t)` for the segment and the plane, or `None`.
pub(super) fn segment_plane_margin(s: &Segment, p: &Plane) -> Option<f64> {
    let (_, c) = plane_crossing(s, p)?;
    c.min_over(&[c.tn, c.den.sub(c.tn)])
}

/// The segment's crossing with the triangle's plane and the barycentric
/// numerators `[α, β, γ]·det`, and the face normal `e1 × e2`.
fn triangle_crossing(s: &Segment, t: &Triangle) -> Option<([Dw; 3], Crossing, [Dw; 3])> {
    let numbers = s.start.iter().chain(&s.end).chain(t.vertices.iter().flatten()).copied();
    if !all_finite(numbers) {
        return None;
    }
    let d = segment_parts(s)?;
    crossing_of(s, d, &t.vertices)
}

/// [`triangle_crossing`] for a segment already checked (`d = p1 − p0`, not zero).
fn crossing_of(s: &Segment, d: [Dw; 3], v: &[P3; 3]) -> Option<([Dw; 3], Crossing, [Dw; 3])> {
    let [v0, v1, v2] = v;
    let (e1, e2) = (diff3(v1, v0), diff3(v2, v0));
    let n = cross(&e1, &e2);
    if !dot(&n, &n).is_positive() {
        return None;
    }
    let tt = diff3(&s.start, v0);
    let pv = cross(&d, &e2);
    let den = dot(&e1, &pv);
    let sd = den.signum()?;
    if sd == 0 {
        return None;
    }
    let qv = cross(&tt, &e1);
    let (beta, gamma) = (dot(&tt, &pv), dot(&d, &qv));
    let alpha = den.sub(beta).sub(gamma);
    let tn = dot(&e2, &qv);
    Some((n, Crossing { p0: s.start, d, den, tn, sd }, [alpha, beta, gamma]))
}

impl Crossing {
    /// Whether the segment hits the triangle whose barycentric numerators are
    /// `bary`.
    fn hits(&self, bary: &[Dw; 3]) -> Option<bool> {
        Some(
            self.on_segment()?
                && self.non_negative(bary[0])?
                && self.non_negative(bary[1])?
                && self.non_negative(bary[2])?,
        )
    }

    /// The hit's outputs, each certified.
    fn hit(&self, n: &[Dw; 3], bary: &[Dw; 3], triangle: Option<usize>) -> Option<SegmentHit> {
        let barycentric = [quotient(bary[0], self.den)?, quotient(bary[1], self.den)?, quotient(bary[2], self.den)?];
        Some(SegmentHit {
            t: self.t()?,
            point: self.point()?,
            normal: unit(n)?,
            barycentric: Some(barycentric),
            triangle,
        })
    }

    /// `self.t < other.t`, certified (`tn/den` against `tn'/den'`).
    fn before(&self, other: &Crossing) -> Option<bool> {
        let diff = self.tn.mul(other.den).sub(other.tn.mul(self.den));
        Some(diff.signum()? * self.sd * other.sd < 0)
    }
}

/// Segment against triangle, as `intersect_segment_triangle` answers, or `None`.
pub(super) fn segment_triangle(s: &Segment, t: &Triangle) -> Option<IntersectAnswer> {
    let (n, c, bary) = triangle_crossing(s, t)?;
    if !c.hits(&bary)? {
        return Some(miss());
    }
    Some(IntersectAnswer { hit: Some(c.hit(&n, &bary, None)?), parallel: false, degenerate: false })
}

/// Segment against mesh, as `intersect_segment_mesh` answers, or `None`: only
/// for a mesh whose every face has area and crosses the segment's line (a
/// zero-area or parallel face sets a flag the exact stage decides), with the
/// first hit certified earlier than every other (a tie goes to the lowest
/// face, as there).
pub(super) fn segment_mesh(s: &Segment, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<IntersectAnswer> {
    let numbers = s.start.iter().chain(&s.end).chain(vertices.iter().flatten()).copied();
    if !all_finite(numbers) {
        return None;
    }
    let d = segment_parts(s)?;
    let mut best: Option<([Dw; 3], Crossing, [Dw; 3], usize)> = None;
    for (face, tri) in triangles.iter().enumerate() {
        let v = [*vertices.get(tri[0])?, *vertices.get(tri[1])?, *vertices.get(tri[2])?];
        let (n, c, bary) = crossing_of(s, d, &v)?;
        if !c.hits(&bary)? {
            continue;
        }
        let earlier = match &best {
            None => true,
            Some((_, b, _, _)) => c.before(b)?,
        };
        if earlier {
            best = Some((n, c, bary, face));
        }
    }
    let hit = match best {
        Some((n, c, bary, face)) => Some(c.hit(&n, &bary, Some(face))?),
        None => None,
    };
    Some(IntersectAnswer { hit, parallel: false, degenerate: false })
}

/// `min(t, 1 − t, α, β, γ)` for the segment and the triangle, or `None`.
pub(super) fn segment_triangle_margin(s: &Segment, t: &Triangle) -> Option<f64> {
    let (_, c, [a, b, g]) = triangle_crossing(s, t)?;
    c.min_over(&[c.tn, c.den.sub(c.tn), a, b, g])
}
