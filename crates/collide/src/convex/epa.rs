//! The expanding polytope algorithm (van den Bergen 2001; Ericson §9.5),
//! **the lecture's form**: from GJK's final simplex (blown up to a
//! tetrahedron the standard way), grow a polytope inside the Minkowski
//! difference `A − B` toward its boundary nearest the origin.

use super::gjk::{Vertex, extreme};
use crate::real::{Real, Vec3};

/// EPA stops when the support point in the nearest face's normal lies less
/// than this fraction of its distance beyond the face (the textbook's
/// relative accuracy; below it further faces change the depth only in the
/// sixth digit).
pub const EPA_REL_TOL: f64 = 1e-6;

/// EPA's iteration cap (each iteration adds one vertex; a polytope of boxes
/// and small hulls converges in a few dozen).
pub const EPA_MAX_ITER: usize = 64;

/// A face of the polytope: outward unit normal `n` and distance `d = n·w`.
#[derive(Clone, Copy, Debug)]
struct Face<T: Real> {
    v: [usize; 3],
    n: Vec3<T>,
    d: T,
}

/// EPA's answer: the depth, the nearest face's outward normal `n` of `A − B`
/// (so `a` is pushed out along `−n`), and the witness points.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Epa<T: Real> {
    /// Penetration depth (distance from the origin to the nearest face).
    pub depth: T,
    /// Outward unit normal of that face.
    pub n: Vec3<T>,
    /// Witness on `a`.
    pub pa: Vec3<T>,
    /// Witness on `b`.
    pub pb: Vec3<T>,
}

fn support<T: Real>(a: &[Vec3<T>], b: &[Vec3<T>], d: &Vec3<T>) -> Vertex<T> {
    let ia = extreme(a, d, false);
    let ib = extreme(b, d, true);
    Vertex { w: a[ia] - b[ib], ia, ib }
}

fn face<T: Real>(verts: &[Vertex<T>], v: [usize; 3]) -> Option<Face<T>> {
    let (p0, p1, p2) = (verts[v[0]].w, verts[v[1]].w, verts[v[2]].w);
    let n = (p1 - p0).cross(&(p2 - p0));
    let len = n.norm();
    if !(len > T::zero()) || !len.finite() {
        return None;
    }
    let n = n / len;
    Some(Face { v, n, d: n.dot(&p0) })
}

/// Blows `simplex` up to a tetrahedron of support points (the standard way:
/// a point along the six axis directions, a segment along six directions
/// around it, a triangle along its two normals); `None` when the Minkowski
/// difference is flat.
fn blow_up<T: Real>(a: &[Vec3<T>], b: &[Vec3<T>], mut s: Vec<Vertex<T>>) -> Option<Vec<Vertex<T>>> {
    let (z, o) = (T::zero(), T::one());
    if s.len() == 1 {
        let axes = [Vec3::x(), -Vec3::x(), Vec3::y(), -Vec3::y(), Vec3::z(), -Vec3::z()];
        let w0 = s[0].w;
        let found = axes.iter().map(|d| support(a, b, d)).find(|p| (p.w - w0).norm_squared() > z)?;
        s.push(found);
    }
    if s.len() == 2 {
        let e = s[1].w - s[0].w;
        let k = e.try_normalize(z)?;
        let ax = if k.x.abs() <= k.y.abs() && k.x.abs() <= k.z.abs() {
            Vec3::x()
        } else if k.y.abs() <= k.z.abs() {
            Vec3::y()
        } else {
            Vec3::z()
        };
        let mut d = k.cross(&ax);
        let (c, sn) = (T::of(0.5), T::of(3f64.sqrt() / 2.0));
        let mut found = None;
        for _ in 0..6 {
            let p = support(a, b, &d);
            if (p.w - s[0].w).cross(&e).norm_squared() > z {
                found = Some(p);
                break;
            }
            d = d * c + k.cross(&d) * sn + k * (k.dot(&d) * (o - c));
        }
        s.push(found?);
    }
    if s.len() == 3 {
        let n = (s[1].w - s[0].w).cross(&(s[2].w - s[0].w));
        let p = [support(a, b, &n), support(a, b, &-n)].into_iter().find(|p| n.dot(&(p.w - s[0].w)) != z)?;
        s.push(p);
    }
    (s.len() == 4).then_some(s)
}

/// EPA from a simplex containing the origin; `None` when no polytope can be
/// formed (a flat Minkowski difference, a zero-area face).
pub(crate) fn epa<T: Real>(a: &[Vec3<T>], b: &[Vec3<T>], simplex: Vec<Vertex<T>>) -> Option<Epa<T>> {
    let mut verts = blow_up(a, b, simplex)?;
    let vol = (verts[1].w - verts[0].w).cross(&(verts[2].w - verts[0].w)).dot(&(verts[3].w - verts[0].w));
    if vol == T::zero() || !vol.finite() {
        return None;
    }
    if vol < T::zero() {
        verts.swap(0, 1);
    }
    let mut faces = Vec::new();
    for v in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
        faces.push(face(&verts, v)?);
    }
    let tol = T::of(EPA_REL_TOL);
    let mut best = faces[0];
    for _ in 0..EPA_MAX_ITER {
        best = *faces.iter().min_by(|x, y| x.d.partial_cmp(&y.d).unwrap_or(core::cmp::Ordering::Equal))?;
        let p = support(a, b, &best.n);
        let sd = best.n.dot(&p.w);
        if sd - best.d <= tol * sd.abs().max(best.d.abs()) || verts.iter().any(|q| q.ia == p.ia && q.ib == p.ib) {
            break;
        }
        let iw = verts.len();
        verts.push(p);
        let (visible, kept): (Vec<Face<T>>, Vec<Face<T>>) =
            faces.iter().partition(|f| f.n.dot(&(p.w - verts[f.v[0]].w)) > T::zero());
        let mut edges: Vec<(usize, usize)> = Vec::new();
        for f in &visible {
            for k in 0..3 {
                edges.push((f.v[k], f.v[(k + 1) % 3]));
            }
        }
        let horizon: Vec<(usize, usize)> = edges.iter().copied().filter(|&(i, j)| !edges.contains(&(j, i))).collect();
        faces = kept;
        for (i, j) in horizon {
            if let Some(f) = face(&verts, [i, j, iw]) {
                faces.push(f);
            }
        }
        if faces.is_empty() {
            return None;
        }
    }
    // The origin's projection onto the nearest face, in barycentric
    // coordinates of its vertices.
    let [i, j, k] = best.v;
    let (p0, p1, p2) = (verts[i].w, verts[j].w, verts[k].w);
    let q = best.n * best.d;
    let total = best.n.dot(&(p1 - p0).cross(&(p2 - p0)));
    let l1 = best.n.dot(&(p2 - q).cross(&(p0 - q))) / total;
    let l2 = best.n.dot(&(p0 - q).cross(&(p1 - q))) / total;
    let l0 = T::one() - l1 - l2;
    let pa = a[verts[i].ia] * l0 + a[verts[j].ia] * l1 + a[verts[k].ia] * l2;
    let pb = b[verts[i].ib] * l0 + b[verts[j].ib] * l1 + b[verts[k].ib] * l2;
    Some(Epa { depth: best.d, n: best.n, pa, pb })
}
