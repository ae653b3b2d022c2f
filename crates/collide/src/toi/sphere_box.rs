//! Sphere–box time of impact from the features' closed forms, in the box's
//! own frame.

use super::time_of_impact::{Toi, ToiStatus, approach_fallback, clamp_t_max};
use crate::boxes::contact_sphere_box;
use crate::exact::frexp;
use crate::real::{Real, Vec3, scale2, scale2v, stable_norm, try_normalize_stable};
use crate::shapes::{OrientedBox, Sphere};

/// Time of impact of sphere `a` (centre `M`, radius `r`, velocity `va`) and
/// oriented box `b` (velocity `vb`, its rotation fixed) over `[0, t_max]`,
/// **robust form**: the first contact solved in closed form from the box's
/// faces, edges and corners in the box's own frame (Ericson, *Real-Time
/// Collision Detection*, §5.5.7, "Intersecting moving sphere against AABB":
/// the centre's path against the box grown by `r`, whose faces are planes,
/// whose edges are cylinders and whose corners are spheres).
///
/// **Method.** Relative to `b` the centre moves on a line: in the box's frame
/// (`R` the quaternion's rotation, [`OrientedBox::rotation_matrix`]) it is
/// `u(t) = u₀ + t w` with `u₀ = Rᵀ(M − c)` and `w = Rᵀ(va − vb)`, past the box
/// `[−h, h]` standing still. While the centre is outside the box its distance
/// to the box is the least of its distances to the six closed faces, so the
/// first time `t*` at which it reaches `r` is a time at which the closest
/// point lies in a face's interior, on an edge or at a corner, and `t*` is the
/// least of:
///
/// - each **face** `(i, s)` (`s = ±1`): `s uᵢ(t) − hᵢ = r`, linear, for a centre
///   beyond it by more than `r` at `t = 0` and approaching it
///   (`t = (s u₀ᵢ − hᵢ − r)/(−s wᵢ)`), kept when the foot lies on the face:
///   `|u_j(t)| ≤ h_j` for the two other axes;
/// - each of the 12 **edges** (along axis `i`, at `(s_j h_j, s_k h_k)`): the
///   first root of the cylinder `‖d + t e‖ = r` in the plane of the other two
///   axes (`d = (u₀_j − s_j h_j, u₀_k − s_k h_k)`, `e = (w_j, w_k)`), kept
///   when the foot lies on the edge: `|uᵢ(t)| ≤ hᵢ`;
/// - each of the 8 **corners** `C`: the first root of the sphere
///   `‖d + t w‖ = r`, `d = u₀ − C`.
///
/// Every kept root is a time at which the centre is within `r` of a point of
/// the box, so none is before `t*`; and `t*` is kept, since the distance to
/// the feature holding the closest point (a convex function of `t`) reaches
/// `r` there for the first time. A tie goes to the face, then the edge. The
/// quadratics are taken in a form without cancellation:
///
/// ```text
/// t = (‖d‖ − r)(‖d‖ + r) / (−d·e + √D),   D = (r‖e‖ − ‖d × e‖)(r‖e‖ + ‖d × e‖)
/// ```
///
/// (`D = (d·e)² − ‖e‖²(‖d‖² − r²)` by Lagrange's identity), with a root only
/// for `d·e < 0` (approaching) and `D ≥ 0`.
///
/// **Why a closed form and not advancement.** In the box's frame every
/// feature is axis-aligned, so each root costs a handful of operations and is
/// exact up to the rounding of its inputs; conservative advancement would
/// converge to the same time (one step for a face, many for a grazing edge or
/// corner, with the triangle query's tolerance and polishing) and needs a
/// scene-scale tolerance, which the closed form does not. No step is taken:
/// `iterations` is 0.
///
/// **Scale.** The work is done in `f64` (an `f32` input is one exactly), on
/// `M − c` and `va − vb` formed once each, so a small box far from the origin
/// is answered at its own scale (up to the rounding of its position). The
/// faces' equations are linear and need no scaling; each edge's or corner's
/// offset and radius, and its velocity, are scaled by their own power of two
/// to about 1 before anything is squared, so that a sphere of radius `1e-300`
/// at an edge of a needle `1e300` long is neither lost in the needle's
/// length nor squared into the subnormals. Lengths and speeds near the top
/// of the range are scaled down by `2^−4` first (`headroom`), so that no
/// difference overflows; the time is scaled back once. The point is `c + R p + t vb` with `p` the
/// contact on the box in its frame; the normal `R n`, with `n` the face's axis
/// or the direction from the edge's foot or the corner to the centre at `t`.
///
/// **Answer.** Already in contact at `t = 0` ([`contact_sphere_box`], exact
/// for the quaternion's own rotation, touching counts): `t = 0`,
/// [`ToiStatus::Penetrating`], the static contact. A contact found:
/// [`ToiStatus::Converged`]. A sphere that the exact static test finds clear
/// but within rounding of touching and approaching gets `t = 0` with the
/// feature's contact (still `Converged`: its first contact is within rounding
/// of 0).
///
/// **Degenerate input.** A zero radius meets the box at a point with no
/// direction: the normal is the direction it came from, `−v/‖v‖`, flagged
/// (as [`toi_sphere_triangle`](super::toi_sphere_triangle)). A zero
/// half-extent is a flat box (its two faces along that axis are one plane;
/// nothing changes). A zero quaternion is the identity. A negative radius, a
/// non-finite input, or a time beyond the type's range is no impact (`None`),
/// never NaN; a negative or NaN `t_max` is read as 0. No relative motion and
/// no contact at `t = 0` is no impact.
pub fn toi_sphere_box<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &OrientedBox<T>,
    vb: &Vec3<T>,
    t_max: T,
) -> Option<Toi<T>> {
    let t_max = clamp_t_max(t_max);
    if let Some(k) = contact_sphere_box(a, b) {
        return Some(Toi::penetrating(&k));
    }
    let w3 = |p: &Vec3<T>| Vec3::new(p.x.wide(), p.y.wide(), p.z.wide());
    let (m, c, h) = (w3(&a.center), w3(&b.center), w3(&b.half_extents).map(f64::abs));
    let (va, vb, r) = (w3(va), w3(vb), a.radius.wide());
    let q = b.rotation.map(|x| x.wide());
    let finite = |p: &Vec3<f64>| p.iter().all(|x| x.is_finite());
    if !(finite(&m) && finite(&c) && finite(&h) && finite(&va) && finite(&vb) && r.is_finite() && r >= 0.0)
        || !q.iter().all(|x| x.is_finite())
    {
        return None;
    }
    let rot = OrientedBox::new(c, h, q).rotation_matrix();
    // Lengths and speeds each kept clear of overflow (see `headroom`); no
    // scaling toward 1, which would push the small lengths of a scene of
    // mixed magnitudes into the subnormals: what is squared is scaled per
    // feature instead.
    let kl = headroom(amax(&m).max(amax(&c)).max(amax(&h)).max(r));
    let kv = headroom(amax(&va).max(amax(&vb)));
    let u0 = rot.transpose() * (scale2v(&m, kl) - scale2v(&c, kl));
    let v = scale2v(&va, kv) - scale2v(&vb, kv);
    let w = rot.transpose() * v;
    let local = Local { u0, w, h: scale2v(&h, kl), r: scale2(r, kl) };
    let hit = local.first_contact()?;
    // Local time (lengths over speeds as scaled) back to the scene's.
    let t = scale2(hit.t, kv - kl);
    if !(t <= t_max.wide()) {
        return None;
    }
    let point = c + rot * scale2v(&hit.point, -kl) + vb * t;
    let (normal, degenerate) = match hit.normal.and_then(|n| try_normalize_stable(&(rot * n))) {
        Some(n) if r > 0.0 => (n, false),
        _ => (approach_fallback(&v), true),
    };
    let toi = Toi {
        t: T::of(t),
        point: point.map(T::of),
        normal: normal.map(T::of),
        status: ToiStatus::Converged,
        iterations: 0,
        degenerate,
    };
    Some(toi).filter(Toi::in_range)
}

/// Above this magnitude (`2^1019`) a scene's lengths, or its speeds, are
/// scaled by [`HEADROOM_SCALE`] first.
const HEADROOM_ABOVE: f64 = 5.617791046444737e306;

/// The power of two applied to lengths or speeds above [`HEADROOM_ABOVE`]:
/// `2^−4`. Reason: after it every length is at most `2^1020`, so `M − c` is
/// at most `2^1021`, its rotation into the box's frame `√3` times that, and
/// an offset from a face or a corner adds a half-extent and the radius:
/// below `2^1023`, clear of overflow (speeds likewise); only lengths below
/// `2^−1070` (beside ones above `2^1019`) lose bits, far below the scene's
/// rounding.
const HEADROOM_SCALE: i32 = -4;

/// The scaling of lengths or speeds whose largest magnitude is `m`: down by
/// [`HEADROOM_SCALE`] when `m` exceeds [`HEADROOM_ABOVE`], up to about 1 when
/// `m` is below 1/2 (exact), else none. Never down toward 1: a small length
/// beside a large one is left as it is, and each feature's squares are scaled
/// on their own (`first_root`). With lengths scaled by `2^kl` and speeds by
/// `2^kv`, a time in the box's frame is the scene's times `2^(kl − kv)`,
/// within `2^±4` of it: it overflows before the scene's only where `2^kv` is
/// `2^−4`, for a relative speed above `2^1019`, whose contact (both shapes
/// within the range) comes within a time of a few units.
fn headroom(m: f64) -> i32 {
    if m > HEADROOM_ABOVE {
        HEADROOM_SCALE
    } else if m > 0.0 && m < 0.5 {
        // Up toward 1: exact (no bit is lost scaling up), and it lifts a
        // scene of tiny or subnormal magnitudes out of the subnormals, where
        // the rotation into the box's frame would round at the subnormals'
        // absolute grid.
        to_unit(m)
    } else {
        0
    }
}

/// The largest absolute coordinate.
fn amax(p: &Vec3<f64>) -> f64 {
    p.x.abs().max(p.y.abs()).max(p.z.abs())
}

/// The power of two `2^k` that brings a positive finite `x` into `[0.5, 1)`;
/// 0 for 0.
fn to_unit(x: f64) -> i32 {
    if x > 0.0 { -(frexp(x).1 as i32) } else { 0 }
}

/// The scene in the box's frame: the centre at `u0 + t w` past the box
/// `[−h, h]`, radius `r` (lengths and speeds each scaled by a power of two).
struct Local {
    u0: Vec3<f64>,
    w: Vec3<f64>,
    h: Vec3<f64>,
    r: f64,
}

/// The first contact in the box's frame.
#[derive(Clone, Copy, Debug)]
struct Hit {
    /// The time, in the frame's units (scaled lengths over scaled speeds).
    t: f64,
    /// The contact on the box, in its frame.
    point: Vec3<f64>,
    /// The direction from the contact toward the centre, in the box's frame
    /// (not unit); `None` where it vanishes.
    normal: Option<Vec3<f64>>,
}

impl Local {
    /// The centre's coordinate `i` at time `t`.
    fn at(&self, i: usize, t: f64) -> f64 {
        self.u0[i] + t * self.w[i]
    }

    /// The least kept root over the faces, edges and corners (see
    /// [`toi_sphere_box`]); `None` when none is met.
    fn first_contact(&self) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut keep = |hit: Option<Hit>| {
            if let Some(hit) = hit
                && hit.t.is_finite()
                && best.is_none_or(|b| hit.t < b.t)
            {
                best = Some(hit);
            }
        };
        for i in 0..3 {
            for s in [1.0, -1.0] {
                keep(self.face(i, s));
            }
        }
        for i in 0..3 {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            for sj in [1.0, -1.0] {
                for sk in [1.0, -1.0] {
                    keep(self.edge(i, j, k, sj, sk));
                }
            }
        }
        for sx in [1.0, -1.0] {
            for sy in [1.0, -1.0] {
                for sz in [1.0, -1.0] {
                    keep(self.corner(Vec3::new(sx * self.h.x, sy * self.h.y, sz * self.h.z)));
                }
            }
        }
        best
    }

    /// The face `s e_i` (`s = ±1`): the linear root, kept when the foot is on
    /// the face. A centre within `r` of the plane at `t = 0` on the face's
    /// side (the exact static test found it clear: rounding) and approaching
    /// it over the face is met at `t = 0`.
    fn face(&self, i: usize, s: f64) -> Option<Hit> {
        let rate = s * self.w[i];
        if !(rate < 0.0) {
            return None;
        }
        let gap = (s * self.u0[i] - self.h[i]) - self.r;
        // Within r of the plane at t = 0: only on this face's side of the
        // box's middle (s u₀ᵢ ≥ 0) is that a touch; beyond the opposite face
        // the centre is moving away from the box.
        let t = if gap > 0.0 {
            gap / -rate
        } else if s * self.u0[i] >= 0.0 {
            0.0
        } else {
            return None;
        };
        let mut point = Vec3::zeros();
        for j in 0..3 {
            if j == i {
                point[j] = s * self.h[j];
            } else {
                let x = self.at(j, t);
                if !(x.abs() <= self.h[j]) {
                    return None;
                }
                point[j] = x;
            }
        }
        let mut n = Vec3::zeros();
        n[i] = s;
        Some(Hit { t, point, normal: Some(n) })
    }

    /// The edge along axis `i` at `(s_j h_j, s_k h_k)`: the cylinder's first
    /// root, kept when the foot is on the edge.
    fn edge(&self, i: usize, j: usize, k: usize, sj: f64, sk: f64) -> Option<Hit> {
        let d = [self.u0[j] - sj * self.h[j], self.u0[k] - sk * self.h[k]];
        let e = [self.w[j], self.w[k]];
        let (t, dir) = first_root(&[d[0], d[1], 0.0], &[e[0], e[1], 0.0], self.r)?;
        let x = self.at(i, t);
        if !(x.abs() <= self.h[i]) {
            return None;
        }
        let mut point = Vec3::zeros();
        point[i] = x;
        point[j] = sj * self.h[j];
        point[k] = sk * self.h[k];
        let normal = dir.map(|d2| {
            let mut n = Vec3::zeros();
            n[j] = d2[0];
            n[k] = d2[1];
            n
        });
        Some(Hit { t, point, normal })
    }

    /// The corner `corner`: the sphere's first root.
    fn corner(&self, corner: Vec3<f64>) -> Option<Hit> {
        let d = self.u0 - corner;
        let (t, dir) = first_root(&[d.x, d.y, d.z], &[self.w.x, self.w.y, self.w.z], self.r)?;
        Some(Hit { t, point: corner, normal: dir.map(|n| Vec3::new(n[0], n[1], n[2])) })
    }
}

/// The first time `t ≥ 0` at which `‖d + t e‖ = r` for a point approaching
/// (`d·e < 0`), in the cancellation-free form of [`toi_sphere_box`], with the
/// offset `d + t e` then (scaled, not unit; `None` when it vanishes). `d` and
/// `r` are scaled together by a power of two to about 1 and `e` by its own
/// before anything is squared; the time is scaled back. A point already
/// within `r` (by rounding: the exact static test found it clear) and
/// approaching is met at `t = 0`. `None`: not approaching, passing by
/// (`D < 0`), or a non-finite value.
fn first_root(d: &[f64; 3], e: &[f64; 3], r: f64) -> Option<(f64, Option<[f64; 3]>)> {
    let m = |x: &[f64; 3]| x.iter().fold(0.0f64, |m, y| m.max(y.abs()));
    let (kd, ke) = (to_unit(m(d).max(r)), to_unit(m(e)));
    let ds = d.map(|x| scale2(x, kd));
    let es = e.map(|x| scale2(x, ke));
    let rs = scale2(r, kd);
    let de = ds[0] * es[0] + ds[1] * es[1] + ds[2] * es[2];
    if !(de < 0.0) {
        return None;
    }
    let nd = stable_norm(&Vec3::from(ds));
    let ts = if nd <= rs {
        0.0
    } else {
        let ne = stable_norm(&Vec3::from(es));
        let cross = Vec3::from(ds).cross(&Vec3::from(es));
        let nx = stable_norm(&cross);
        let (lo, hi) = (rs * ne - nx, rs * ne + nx);
        if !(lo >= 0.0) {
            return None;
        }
        let root = lo.sqrt() * hi.sqrt();
        ((nd - rs) / (root - de)) * (nd + rs)
    };
    if !ts.is_finite() {
        return None;
    }
    let off = [0, 1, 2].map(|k| ds[k] + ts * es[k]);
    let dir = (off.iter().any(|x| *x != 0.0)).then_some(off);
    Some((scale2(ts, ke - kd), dir))
}
