//! Sizes of box–box, box–triangle, capsule–box and capsule–triangle contact:
//! the shapes' own sizes, and what conditions the separating axis the
//! referee's answer stands on.
//!
//! - **A cross-product axis** `aᵢ × bⱼ` of two edges at a small angle `θ`
//!   turns by `ε/sin θ` when the edges turn by `ε`: the normal's condition is
//!   `1/sin θ`, and the depth and the point (which project along it) move by
//!   the sizes over `sin θ`.
//! - **A near tie**: the next-least push in another direction within `gap` of
//!   the least could take over under a perturbation; the normal then jumps (by
//!   up to 2, the chord between unit normals) and the point across the shapes,
//!   weighed as the other pairs weigh a tie ([`super::tie`]).
//! - **Nearly collinear edges**: a corner of the region where an edge of `a`
//!   crosses one of `b` slides along them by the sizes over the sine of
//!   their angle, within the shorter edge; edges on one line decide between
//!   a stretch and a point.
//! - **A capsule apart from the solid** (its axis at distance `d > 0`): the
//!   normal turns by the sizes over `d` (as sphere–capsule), and an axis nearly
//!   parallel to a face slides its closest point along its length (as
//!   capsule–capsule).
//!
//! The pushes are computed in `f64` on the scene scaled by a power of two to
//! unit size (no square overflows or underflows), for sizes only: the answer
//! is the referee's.

use super::{Local, Size, box_size, capsule_size, clean, max_abs, ratio, tie, unit};
use crate::case::Shape;
use crashtest_core::vec3::{cross, dot, sub};
use oracle::geom::P3;

/// A polytope in `f64`, scaled: its vertices, edge directions and face normals.
struct Poly {
    vertices: Vec<P3>,
    /// Edges as pairs of vertex indices.
    edges: Vec<(usize, usize)>,
    directions: Vec<P3>,
    normals: Vec<P3>,
}

fn scaled(p: &P3, k: f64) -> P3 {
    p.map(|x| x * k)
}

fn of_box(b: &crate::case::BoxSpec, k: f64) -> Poly {
    let r = b.to_geom().rotation_matrix();
    let axes: Vec<P3> = (0..3).map(|j| [r[0][j], r[1][j], r[2][j]]).collect();
    let c = scaled(&b.center, k);
    let h = b.half_extents.map(|x| x.abs() * k);
    let vertices = (0..8usize)
        .map(|s| {
            std::array::from_fn(|i| {
                c[i] + (0..3).map(|j| if s >> j & 1 == 1 { h[j] } else { -h[j] } * axes[j][i]).sum::<f64>()
            })
        })
        .collect();
    let edges =
        (0..8usize).flat_map(|s| (0..3).filter(move |i| s >> i & 1 == 0).map(move |i| (s, s | 1 << i))).collect();
    Poly { vertices, edges, directions: axes.clone(), normals: axes }
}

fn of_triangle(v: &[P3; 3], k: f64) -> Poly {
    let v = v.map(|p| scaled(&p, k));
    let directions = vec![sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])];
    let normals = vec![cross(sub(v[1], v[0]), sub(v[2], v[0]))];
    Poly { vertices: v.to_vec(), edges: vec![(0, 1), (1, 2), (2, 0)], directions, normals }
}

fn of_segment(p0: &P3, p1: &P3, k: f64) -> Poly {
    let (p0, p1) = (scaled(p0, k), scaled(p1, k));
    Poly { vertices: vec![p0, p1], edges: vec![(0, 1)], directions: vec![sub(p1, p0)], normals: vec![] }
}

/// A push in `f64`: its amount over `‖L‖`, its unit direction, and the sine
/// of the angle of the two edges it crosses (1 for a face normal).
struct Push {
    amount: f64,
    direction: P3,
    sine: f64,
}

fn pushes(a: &Poly, b: &Poly) -> Vec<Push> {
    let mut axes: Vec<(P3, f64)> = a.normals.iter().chain(&b.normals).map(|n| (*n, 1.0)).collect();
    for da in &a.directions {
        for db in &b.directions {
            let l = cross(*da, *db);
            let (ua, ub) = (unit(da), unit(db));
            axes.push((l, super::norm(&cross(ua, ub))));
        }
    }
    let project = |p: &Poly, u: &P3| {
        p.vertices
            .iter()
            .map(|v| dot(*u, *v))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)))
    };
    let mut out = Vec::new();
    for (l, sine) in axes {
        let u = unit(&l);
        if u.iter().all(|x| *x == 0.0) {
            continue;
        }
        let ((lo_a, hi_a), (lo_b, hi_b)) = (project(a, &u), project(b, &u));
        out.push(Push { amount: hi_b - lo_a, direction: u, sine });
        out.push(Push { amount: hi_a - lo_b, direction: u.map(|x| -x), sine });
    }
    out
}

/// The least push's sine, and the gap to the next least in another direction
/// (`f64::MAX` when there is none), unscaled by `1/k`.
fn least_and_gap(a: &Poly, b: &Poly, k: f64) -> (f64, f64) {
    let mut all = pushes(a, b);
    all.sort_by(|x, y| x.amount.total_cmp(&y.amount));
    let Some(least) = all.first() else { return (1.0, f64::MAX) };
    let other = all[1..].iter().find(|p| dot(p.direction, least.direction) < 1.0 - 1e-12);
    let gap = other.map_or(f64::MAX, |p| clean((p.amount - least.amount) / k));
    (least.sine, gap)
}

/// The power of two that brings the largest coordinate of `points` near 1.
fn unit_scale(points: &[P3]) -> f64 {
    let m = points.iter().copied().map(max_abs).fold(0.0, f64::max);
    if m == 0.0 || !m.is_finite() { 1.0 } else { 2f64.powi(-(m.log2().floor() as i32)) }
}

/// How far a corner of the region can slide: where an edge of `a` and an
/// edge of `b` nearly on one line overlap, a perturbation decides whether
/// the one runs inside or outside the other's face, and the region is their
/// shared stretch or one point (a capsule's axis along a triangle's edge);
/// crossing at a small angle `θ`, their crossing moves by the sizes over
/// `sin θ`. Weighed as a tie of the shorter edge's length with the gap
/// `max(sin θ · length, the edges' distance)`: edges side by side (parallel
/// faces of two boxes) are as far from crossing as they are apart.
fn slide(a: &Poly, b: &Poly, k: f64, size: f64) -> f64 {
    let mut worst = 0.0f64;
    for &(i, j) in &a.edges {
        let (p0, p1) = (a.vertices[i], a.vertices[j]);
        for &(m, n) in &b.edges {
            let (q0, q1) = (b.vertices[m], b.vertices[n]);
            let (da, db) = (sub(p1, p0), sub(q1, q0));
            let len = clean(super::norm(&da).min(super::norm(&db)) / k);
            if len == 0.0 {
                continue;
            }
            let sine = super::norm(&cross(unit(&da), unit(&db)));
            let apart = segment_distance(&p0, &p1, &q0, &q1) / k;
            worst = worst.max(tie(len, size, clean((sine * len).max(apart))));
        }
    }
    worst
}

/// The distance between segments `[p0, p1]` and `[q0, q1]` in plain `f64`
/// (Ericson's closest points of two segments, §5.1.9), for sizes only.
fn segment_distance(p0: &P3, p1: &P3, q0: &P3, q1: &P3) -> f64 {
    let (d1, d2, r) = (sub(*p1, *p0), sub(*q1, *q0), sub(*p0, *q0));
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    let (mut s, mut t);
    if a == 0.0 && e == 0.0 {
        (s, t) = (0.0, 0.0);
    } else if a == 0.0 {
        (s, t) = (0.0, (f / e).clamp(0.0, 1.0));
    } else {
        let c = dot(d1, r);
        if e == 0.0 {
            (s, t) = ((-c / a).clamp(0.0, 1.0), 0.0);
        } else {
            let b = dot(d1, d2);
            let denom = a * e - b * b;
            s = if denom > 0.0 { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
            t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
        }
    }
    let at = |o: &P3, d: &P3, x: f64| [o[0] + d[0] * x, o[1] + d[1] * x, o[2] + d[2] * x];
    clean(super::norm(&sub(at(p0, &d1, s), at(q0, &d2, t))))
}

/// The sizes of a contact between polytopes `a` and `b` (a capsule's axis
/// when it meets the solid), `size` the shapes' and the answer's sizes.
fn resting(a: &Poly, b: &Poly, k: f64, size: f64, across: f64) -> Local {
    let (sine, gap) = least_and_gap(a, b, k);
    let turn = ratio(1.0, sine).min(std::f64::consts::PI / f64::EPSILON);
    let depth = Size::new(size, clean(size * (turn - 1.0)));
    Local {
        point: Size::new(size, clean(size * (turn - 1.0) + tie(across, size, gap) + slide(a, b, k, size))),
        depth,
        normal: Size::new(1.0, clean(turn + tie(2.0, size, gap))),
        margin: depth,
        ..Local::default()
    }
}

fn triangle_size(v: &[P3; 3]) -> f64 {
    v.iter().copied().map(max_abs).fold(0.0, f64::max)
}

/// The sizes of the four pairs; `None` for another pair.
pub(super) fn contact(a: &Shape, b: &Shape, w: &oracle::geom::Contact) -> Option<Local> {
    let extra = max_abs(w.point) + w.depth.abs();
    Some(match (a, b) {
        (Shape::Box(ba), Shape::Box(bb)) => {
            let k = unit_scale(&[ba.center, ba.half_extents, bb.center, bb.half_extents]) / 4.0;
            let (pa, pb) = (of_box(ba, k), of_box(bb, k));
            let size = clean(box_size(ba) + box_size(bb) + extra);
            resting(&pa, &pb, k, size, size)
        }
        (Shape::Box(ba), Shape::Triangle(t)) => {
            let k = unit_scale(&[ba.center, ba.half_extents, t.vertices[0], t.vertices[1], t.vertices[2]]) / 4.0;
            let (pa, pb) = (of_box(ba, k), of_triangle(&t.vertices, k));
            let size = clean(box_size(ba) + triangle_size(&t.vertices) + extra);
            resting(&pa, &pb, k, size, size)
        }
        (Shape::Capsule(c), Shape::Box(_) | Shape::Triangle(_)) => {
            let (k, pb, b_size) = match b {
                Shape::Box(bb) => {
                    let k = unit_scale(&[c.start, c.end, bb.center, bb.half_extents]) / 4.0;
                    (k, of_box(bb, k), box_size(bb))
                }
                Shape::Triangle(t) => {
                    let k = unit_scale(&[c.start, c.end, t.vertices[0], t.vertices[1], t.vertices[2]]) / 4.0;
                    (k, of_triangle(&t.vertices, k), triangle_size(&t.vertices))
                }
                _ => return None,
            };
            let size = clean(capsule_size(c) + b_size + extra);
            let pa = of_segment(&c.start, &c.end, k);
            let d = c.radius - w.depth;
            if d > 0.0 {
                // The axis apart from the solid: the closest pair's normal
                // turns by the sizes over d; near parallel to a face, the
                // closest point slides along the axis.
                let turn = ratio(size, d).min(std::f64::consts::PI / f64::EPSILON);
                let axis = sub(pa.vertices[1], pa.vertices[0]);
                let len = clean(super::norm(&axis) / k);
                let slide = tie(len, size, clean(dot(axis, unit(&w.normal)).abs() / k));
                let depth = Size::new(size, 0.0);
                Local {
                    point: Size::new(size, clean(size * turn + slide)),
                    depth,
                    normal: Size::new(1.0, turn),
                    margin: depth,
                    ..Local::default()
                }
            } else {
                resting(&pa, &pb, k, size, size)
            }
        }
        _ => return None,
    })
}
