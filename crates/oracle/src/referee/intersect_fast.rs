//! The floating-point stage of a segment against a plane, a triangle or a
//! mesh ([`super::fast`]): every output is a quotient of polynomials in the
//! inputs, each correctly rounded ([`Num::quotient`]), and every decision a
//! certain sign. Every function is written over [`Num`]: it runs in
//! double-word numbers ([`Dw`]) first and, when their bounds leave a sign or
//! a rounding open (an output on or near a midpoint, or beyond `MAX`), again
//! in exact dyadic numbers ([`Dy`], [`super::dyadic`]), where every sign is
//! certain. A function returns `None` — the rationals of the exact stage
//! answer, with the same bits (`tests/referee_stages.rs`) — for what has the
//! exact stage's flags (a zero-length segment, a zero-area triangle, a
//! segment parallel to the plane), inputs that are not finite and input the
//! exact stage refuses.
//!
//! For the triangle the crossing is written as Möller and Trumbore write it:
//! with `e1 = v1 − v0`, `e2 = v2 − v0`, `D = p1 − p0`, `T = p0 − v0`,
//! `det = e1·(D × e2)`, the crossing's `t = e2·(T × e1)/det` and its
//! barycentrics `β = T·(D × e2)/det`, `γ = D·(T × e1)/det`, `α = 1 − β − γ`:
//! degree 3 over degree 3, the same rationals as the exact stage's
//! `t = N·(v0 − p0)/(N·D)` and normal equations (the crossing lies in the
//! plane, where barycentrics are unique).

use super::dyadic::{Dy, Num, cross, diff3, dot};
use super::fast::{Dw, all_finite};
use crate::geom::{IntersectAnswer, P3, Plane, Segment, SegmentHit, Triangle};

fn miss() -> IntersectAnswer {
    IntersectAnswer { hit: None, parallel: false, degenerate: false }
}

/// The line's crossing as numerators over one denominator `den` (sign
/// certain, not zero): `t = tn/den`, the point `(p0·den + tn·D)/den`.
struct Crossing<T> {
    p0: P3,
    d: [T; 3],
    den: T,
    tn: T,
    /// `den`'s sign.
    sd: i8,
}

impl<T: Num> Crossing<T> {
    /// `x/den ≥ 0`.
    fn non_negative(&self, x: &T) -> Option<bool> {
        Some(x.sign_of()? * self.sd >= 0)
    }

    /// `0 ≤ t ≤ 1`.
    fn on_segment(&self) -> Option<bool> {
        Some(self.non_negative(&self.tn)? && self.non_negative(&self.den.minus(&self.tn))?)
    }

    fn t(&self) -> Option<f64> {
        T::quotient(&self.tn, &self.den)
    }

    fn point(&self) -> Option<P3> {
        let mut out = [0.0; 3];
        for (i, o) in out.iter_mut().enumerate() {
            *o = T::quotient(&T::of(self.p0[i]).times(&self.den).plus(&self.tn.times(&self.d[i])), &self.den)?;
        }
        Some(out)
    }

    /// The smallest of `xs[i]/den`, correctly rounded (equal numerators give
    /// the same value, whichever is taken).
    fn min_over(&self, xs: &[T]) -> Option<f64> {
        let mut best = &xs[0];
        for x in &xs[1..] {
            // x/den < best/den ⇔ (x − best)·sign(den) < 0.
            if x.minus(best).sign_of()? * self.sd < 0 {
                best = x;
            }
        }
        T::quotient(best, &self.den)
    }
}

fn segment_parts<T: Num>(s: &Segment) -> Option<[T; 3]> {
    let d = diff3::<T>(&s.end, &s.start);
    if d.iter().all(T::exact_zero) {
        return None;
    }
    Some(d)
}

/// The segment against the plane `n·x = off`: `t = (off − n·p0)/(n·D)`.
fn plane_crossing<T: Num>(s: &Segment, p: &Plane) -> Option<([T; 3], Crossing<T>)> {
    let numbers = s.start.iter().chain(&s.end).chain(&p.normal).copied().chain([p.offset]);
    if !all_finite(numbers) {
        return None;
    }
    let n = p.normal.map(T::of);
    if !dot(&n, &n).positive() {
        return None;
    }
    let d = segment_parts::<T>(s)?;
    let den = dot(&n, &d);
    let sd = den.sign_of()?;
    if sd == 0 {
        return None;
    }
    let tn = T::of(p.offset).minus(&dot(&n, &s.start.map(T::of)));
    Some((n, Crossing { p0: s.start, d, den, tn, sd }))
}

fn segment_plane_in<T: Num>(s: &Segment, p: &Plane) -> Option<IntersectAnswer> {
    let (n, c) = plane_crossing::<T>(s, p)?;
    if !c.on_segment()? {
        return Some(miss());
    }
    let hit = SegmentHit {
        t: c.t()?,
        point: c.point()?,
        normal: T::unit(&n, &dot(&n, &n))?,
        barycentric: None,
        triangle: None,
    };
    Some(IntersectAnswer { hit: Some(hit), parallel: false, degenerate: false })
}

/// Segment against plane, as `intersect_segment_plane` answers, or `None`.
pub(super) fn segment_plane(s: &Segment, p: &Plane) -> Option<IntersectAnswer> {
    segment_plane_in::<Dw>(s, p).or_else(|| segment_plane_in::<Dy>(s, p))
}

fn segment_plane_margin_in<T: Num>(s: &Segment, p: &Plane) -> Option<f64> {
    let (_, c) = plane_crossing::<T>(s, p)?;
    c.min_over(&[c.tn.clone(), c.den.minus(&c.tn)])
}

/// `min(t, 1 − t)` for the segment and the plane, or `None`.
pub(super) fn segment_plane_margin(s: &Segment, p: &Plane) -> Option<f64> {
    segment_plane_margin_in::<Dw>(s, p).or_else(|| segment_plane_margin_in::<Dy>(s, p))
}

/// The segment's crossing with the triangle's plane and the barycentric
/// numerators `[α, β, γ]·det`, and the face normal `e1 × e2`.
type TriangleCrossing<T> = ([T; 3], Crossing<T>, [T; 3]);

fn triangle_crossing<T: Num>(s: &Segment, t: &Triangle) -> Option<TriangleCrossing<T>> {
    let numbers = s.start.iter().chain(&s.end).chain(t.vertices.iter().flatten()).copied();
    if !all_finite(numbers) {
        return None;
    }
    let d = segment_parts::<T>(s)?;
    crossing_of(s, d, &t.vertices)
}

/// [`triangle_crossing`] for a segment already checked (`d = p1 − p0`, not zero).
fn crossing_of<T: Num>(s: &Segment, d: [T; 3], v: &[P3; 3]) -> Option<TriangleCrossing<T>> {
    let [v0, v1, v2] = v;
    let (e1, e2) = (diff3::<T>(v1, v0), diff3::<T>(v2, v0));
    let n = cross(&e1, &e2);
    if !dot(&n, &n).positive() {
        return None;
    }
    let tt = diff3::<T>(&s.start, v0);
    let pv = cross(&d, &e2);
    let den = dot(&e1, &pv);
    let sd = den.sign_of()?;
    if sd == 0 {
        return None;
    }
    let qv = cross(&tt, &e1);
    let (beta, gamma) = (dot(&tt, &pv), dot(&d, &qv));
    let alpha = den.minus(&beta).minus(&gamma);
    let tn = dot(&e2, &qv);
    Some((n, Crossing { p0: s.start, d, den, tn, sd }, [alpha, beta, gamma]))
}

impl<T: Num> Crossing<T> {
    /// Whether the segment hits the triangle whose barycentric numerators are
    /// `bary`.
    fn hits(&self, bary: &[T; 3]) -> Option<bool> {
        Some(
            self.on_segment()?
                && self.non_negative(&bary[0])?
                && self.non_negative(&bary[1])?
                && self.non_negative(&bary[2])?,
        )
    }

    /// The hit's outputs, each certified.
    fn hit(&self, n: &[T; 3], bary: &[T; 3], triangle: Option<usize>) -> Option<SegmentHit> {
        let barycentric =
            [T::quotient(&bary[0], &self.den)?, T::quotient(&bary[1], &self.den)?, T::quotient(&bary[2], &self.den)?];
        Some(SegmentHit {
            t: self.t()?,
            point: self.point()?,
            normal: T::unit(n, &dot(n, n))?,
            barycentric: Some(barycentric),
            triangle,
        })
    }

    /// `self.t < other.t`, certified (`tn/den` against `tn'/den'`).
    fn before(&self, other: &Crossing<T>) -> Option<bool> {
        let diff = self.tn.times(&other.den).minus(&other.tn.times(&self.den));
        Some(diff.sign_of()? * self.sd * other.sd < 0)
    }
}

fn segment_triangle_in<T: Num>(s: &Segment, t: &Triangle) -> Option<IntersectAnswer> {
    let (n, c, bary) = triangle_crossing::<T>(s, t)?;
    if !c.hits(&bary)? {
        return Some(miss());
    }
    Some(IntersectAnswer { hit: Some(c.hit(&n, &bary, None)?), parallel: false, degenerate: false })
}

/// Segment against triangle, as `intersect_segment_triangle` answers, or `None`.
pub(super) fn segment_triangle(s: &Segment, t: &Triangle) -> Option<IntersectAnswer> {
    segment_triangle_in::<Dw>(s, t).or_else(|| segment_triangle_in::<Dy>(s, t))
}

fn segment_mesh_in<T: Num>(s: &Segment, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<IntersectAnswer> {
    let numbers = s.start.iter().chain(&s.end).chain(vertices.iter().flatten()).copied();
    if !all_finite(numbers) {
        return None;
    }
    let d = segment_parts::<T>(s)?;
    let mut best: Option<(TriangleCrossing<T>, usize)> = None;
    for (face, tri) in triangles.iter().enumerate() {
        let v = [*vertices.get(tri[0])?, *vertices.get(tri[1])?, *vertices.get(tri[2])?];
        let (n, c, bary) = crossing_of(s, d.clone(), &v)?;
        if !c.hits(&bary)? {
            continue;
        }
        let earlier = match &best {
            None => true,
            Some(((_, b, _), _)) => c.before(b)?,
        };
        if earlier {
            best = Some(((n, c, bary), face));
        }
    }
    let hit = match best {
        Some(((n, c, bary), face)) => Some(c.hit(&n, &bary, Some(face))?),
        None => None,
    };
    Some(IntersectAnswer { hit, parallel: false, degenerate: false })
}

/// Segment against mesh, as `intersect_segment_mesh` answers, or `None`: only
/// for a mesh whose every face has area and crosses the segment's line (a
/// zero-area or parallel face sets a flag the exact stage decides), with the
/// first hit certified earlier than every other (a tie goes to the lowest
/// face, as there).
pub(super) fn segment_mesh(s: &Segment, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<IntersectAnswer> {
    segment_mesh_in::<Dw>(s, vertices, triangles).or_else(|| segment_mesh_in::<Dy>(s, vertices, triangles))
}

fn segment_triangle_margin_in<T: Num>(s: &Segment, t: &Triangle) -> Option<f64> {
    let (_, c, [a, b, g]) = triangle_crossing::<T>(s, t)?;
    c.min_over(&[c.tn.clone(), c.den.minus(&c.tn), a, b, g])
}

/// `min(t, 1 − t, α, β, γ)` for the segment and the triangle, or `None`.
pub(super) fn segment_triangle_margin(s: &Segment, t: &Triangle) -> Option<f64> {
    segment_triangle_margin_in::<Dw>(s, t).or_else(|| segment_triangle_margin_in::<Dy>(s, t))
}
