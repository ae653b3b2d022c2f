//! The **full-range family**: cases over the whole finite range of `f64`, kept
//! apart from the campaign's ordinary mix so that its scores are read on their
//! own (the report's "full range" table).
//!
//! Five sub-families, in turn by index:
//!
//! - **raw bit patterns**: a case of the ordinary mix whose every number is
//!   replaced by a random finite bit pattern (so magnitudes spread evenly over
//!   every binade from the subnormals to `f64::MAX`), kept valid (radii, masses
//!   and `t_max` positive, normals non-zero, boxes ordered);
//! - **huge magnitudes**: a case of the ordinary mix scaled by `2^k` (exact)
//!   up to where its largest number nears `f64::MAX`;
//! - **tiny and subnormal magnitudes**: scaled by `2^-k` down into the
//!   subnormals (where the scaling rounds: a different case, still valid);
//! - **signed zeros**: coordinates, offsets and velocities replaced by `+0.0`
//!   or `-0.0` one time in three;
//! - **multi-scale**: a small feature beside a huge one — a small sphere,
//!   segment or point near a vertex, an edge or the face of a triangle with legs
//!   up to 1e300; plane normals of length `2^±600` with matching offsets;
//!   points and boxes of mixed magnitudes; masses from the subnormals to 1e300.
//!   For `toi`, also scenes at `f64`'s extremes: radii and velocity components
//!   from the smallest subnormal to exactly `f64::MAX` (two spheres of radius
//!   `f64::MAX` overlap, and their depth is beyond `f64`), `t_max` from the
//!   smallest subnormal to 1e300, planes whose normal components mix huge and
//!   tiny magnitudes (`1e-282` beside `1e-68`), and spheres centred on a vertex
//!   of a sliver far from the origin, whose face normal cancels in `f64`.
//!
//! An exact answer beyond `f64`'s range is possible here (two spheres of radius
//! 1e308 overlap by more than `f64::MAX`): the referee refuses such a case, and
//! no engine is graded on it (see `fixtures/README.md`, "Answers beyond f64").

use super::build::*;
use crate::case::{Case, Query, Shape};
use crashtest_core::vec3::{add, dot, scale, sub};
use oracle::geom::P3;
use proptest::prelude::*;

/// The sub-families, in the order [`family_for`] takes them.
pub const FAMILIES: [&str; 5] =
    ["raw bit patterns", "huge magnitudes", "tiny and subnormal magnitudes", "signed zeros", "multi-scale"];

/// The sub-family of full-range case `index`.
pub fn family_for(index: u64) -> &'static str {
    FAMILIES[(index % FAMILIES.len() as u64) as usize]
}

/// What a number of a case is, for the transforms that must keep the case
/// valid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    /// A coordinate of a point (centres, vertices, ends, box corners).
    Coord,
    /// A radius (> 0).
    Radius,
    /// A component of a plane's normal (not all zero).
    Normal,
    /// A box's half-extent (≥ 0).
    Extent,
    /// A component of a box's quaternion (not all zero; scaling leaves it).
    Rotation,
    /// A plane's offset.
    Offset,
    /// A velocity component.
    Velocity,
    /// A mass (> 0).
    Mass,
}

/// Applies `f` to every number of the case's shapes, with its role.
fn map_numbers(case: &mut Case, f: &mut dyn FnMut(f64, Role) -> f64) {
    let p3 = |p: &mut P3, role: Role, f: &mut dyn FnMut(f64, Role) -> f64| {
        for x in p.iter_mut() {
            *x = f(*x, role);
        }
    };
    for shape in [Some(&mut case.a), case.b.as_mut()].into_iter().flatten() {
        match shape {
            Shape::Sphere(s) => {
                p3(&mut s.center, Role::Coord, f);
                s.radius = f(s.radius, Role::Radius);
                if let Some(v) = &mut s.velocity {
                    p3(v, Role::Velocity, f);
                }
                if let Some(m) = &mut s.mass {
                    *m = f(*m, Role::Mass);
                }
            }
            Shape::Plane(p) => {
                p3(&mut p.normal, Role::Normal, f);
                p.offset = f(p.offset, Role::Offset);
                if let Some(v) = &mut p.velocity {
                    p3(v, Role::Velocity, f);
                }
            }
            Shape::Segment(s) => {
                p3(&mut s.start, Role::Coord, f);
                p3(&mut s.end, Role::Coord, f);
            }
            Shape::Triangle(t) => {
                for v in &mut t.vertices {
                    p3(v, Role::Coord, f);
                }
                if let Some(v) = &mut t.velocity {
                    p3(v, Role::Velocity, f);
                }
            }
            Shape::Point(p) => p3(&mut p.at, Role::Coord, f),
            Shape::Points(p) => p.points.iter_mut().for_each(|q| p3(q, Role::Coord, f)),
            Shape::Mesh(m) => {
                for v in m.vertices.iter_mut().flatten() {
                    p3(v, Role::Coord, f);
                }
                if let Some(v) = &mut m.velocity {
                    p3(v, Role::Velocity, f);
                }
            }
            Shape::Aabb(b) => {
                p3(&mut b.min, Role::Coord, f);
                p3(&mut b.max, Role::Coord, f);
            }
            Shape::MovingPoint(p) => {
                p3(&mut p.t0, Role::Coord, f);
                p3(&mut p.t1, Role::Coord, f);
            }
            Shape::MovingSegment(s) => s.t0.iter_mut().chain(&mut s.t1).for_each(|v| p3(v, Role::Coord, f)),
            Shape::MovingTriangle(t) => t.t0.iter_mut().chain(&mut t.t1).for_each(|v| p3(v, Role::Coord, f)),
            Shape::Box(b) => {
                p3(&mut b.center, Role::Coord, f);
                p3(&mut b.half_extents, Role::Extent, f);
                if let Some(q) = &mut b.rotation {
                    for x in q.iter_mut() {
                        *x = f(*x, Role::Rotation);
                    }
                }
                if let Some(v) = &mut b.velocity {
                    p3(v, Role::Velocity, f);
                }
            }
            Shape::Capsule(c) => {
                p3(&mut c.start, Role::Coord, f);
                p3(&mut c.end, Role::Coord, f);
                c.radius = f(c.radius, Role::Radius);
            }
            Shape::Convex(c) => {
                for p in &mut c.points {
                    p3(p, Role::Coord, f);
                }
            }
        }
    }
}

/// Restores what the transforms may break: positive radii and masses (a value
/// that underflowed to 0 becomes the smallest positive one), a non-zero normal,
/// ordered box corners.
fn make_valid(case: &mut Case) {
    map_numbers(case, &mut |x, role| match role {
        Role::Radius | Role::Mass if !(x > 0.0) => {
            if x < 0.0 {
                -x
            } else {
                f64::from_bits(1)
            }
        }
        Role::Extent => x.abs(),
        _ => x,
    });
    for shape in [Some(&mut case.a), case.b.as_mut()].into_iter().flatten() {
        match shape {
            Shape::Plane(p) if p.normal.iter().all(|x| *x == 0.0) => p.normal[2] = 1.0,
            Shape::Box(b) => {
                if let Some(q) = &mut b.rotation
                    && q.iter().all(|x| *x == 0.0)
                {
                    q[0] = 1.0;
                }
            }
            Shape::Aabb(b) => {
                for i in 0..3 {
                    if b.min[i] > b.max[i] {
                        std::mem::swap(&mut b.min[i], &mut b.max[i]);
                    }
                }
            }
            _ => {}
        }
    }
}

/// The largest magnitude among the case's numbers (normals excluded: scaling
/// leaves them as they are).
fn largest(case: &mut Case) -> f64 {
    let mut m = 0.0_f64;
    map_numbers(case, &mut |x, role| {
        if !matches!(role, Role::Normal | Role::Mass | Role::Rotation) {
            m = m.max(x.abs());
        }
        x
    });
    m
}

/// Lengths (coordinates, radii, offsets, velocities) multiplied by `s`; normals
/// and masses left as they are.
fn scaled(mut case: Case, s: f64) -> Case {
    map_numbers(&mut case, &mut |x, role| match role {
        Role::Normal | Role::Mass | Role::Rotation => x,
        _ => x * s,
    });
    make_valid(&mut case);
    case
}

/// A finite `f64` from random bits: every finite pattern (NaN and infinities
/// are folded back into the finite range by clearing the top exponent bit).
fn finite_from_bits(bits: u64) -> f64 {
    let x = f64::from_bits(bits);
    if x.is_finite() { x } else { f64::from_bits(bits & !(1u64 << 62)) }
}

fn raw_bits(base: SBoxedStrategy<Case>) -> SBoxedStrategy<Case> {
    (base, prop::collection::vec(any::<u64>(), 128))
        .prop_map(|(mut case, bits)| {
            let mut it = bits.into_iter().cycle();
            map_numbers(&mut case, &mut |_, _| finite_from_bits(it.next().unwrap_or(0)));
            if let Some(t) = case.t_max.as_mut() {
                *t = finite_from_bits(it.next().unwrap_or(0)).abs().max(f64::from_bits(1));
                // A ccd case's motion is given at times 0 and 1: its t_max is
                // a bit pattern of [0, 1] (the top exponent bit cleared puts it
                // in [0, 2); one in [1, 2) is halved).
                if case.query == Query::Ccd {
                    let u = f64::from_bits(t.to_bits() & !(1u64 << 62));
                    *t = if u >= 1.0 { u / 2.0 } else { u };
                }
            }
            make_valid(&mut case);
            case
        })
        .sboxed()
}

fn huge(base: SBoxedStrategy<Case>) -> SBoxedStrategy<Case> {
    (base, 0.0..1.0f64)
        .prop_map(|(mut case, u)| {
            // The largest number after scaling lands in [2^(1023 − room), 2^1023),
            // room ∈ [0, 600): sums of a few such numbers may overflow, on
            // purpose (an exact answer beyond f64 is refused, not graded).
            let m = largest(&mut case).max(f64::MIN_POSITIVE);
            let room = (u * 600.0) as i32;
            let k = 1022 - room - m.log2().ceil() as i32;
            scaled(case, pow2(k.max(0)))
        })
        .sboxed()
}

fn tiny(base: SBoxedStrategy<Case>) -> SBoxedStrategy<Case> {
    (base, 0.0..1.0f64)
        .prop_map(|(mut case, u)| {
            // The largest number lands in [2^-1074, 2^-600): down to the last
            // subnormals. Two steps of at most 2^-1022 each keep the factor normal.
            let m = largest(&mut case).max(f64::MIN_POSITIVE);
            let target = -600 - (u * 474.0) as i32;
            let k = target - m.log2().floor() as i32;
            let first = k.max(-1022);
            let case = scaled(case, pow2(first));
            scaled(case, pow2((k - first).max(-1022)))
        })
        .sboxed()
}

fn signed_zeros(base: SBoxedStrategy<Case>) -> SBoxedStrategy<Case> {
    (base, prop::collection::vec(0u8..6, 128))
        .prop_map(|(mut case, picks)| {
            let mut it = picks.into_iter().cycle();
            map_numbers(&mut case, &mut |x, role| {
                let pick = it.next().unwrap_or(0);
                match role {
                    Role::Coord | Role::Offset | Role::Velocity | Role::Normal | Role::Rotation | Role::Extent => {
                        match pick {
                            0 => 0.0,
                            1 => -0.0,
                            // A zero already there changes its sign.
                            2 if x == 0.0 => -x,
                            _ => x,
                        }
                    }
                    _ => x,
                }
            });
            make_valid(&mut case);
            case
        })
        .sboxed()
}

/// A triangle with legs of length `2^k`, `k ∈ [40, 996]`, from a small vertex
/// `p0`, in random directions, its vertices in a random order; and a point near
/// `p0` (within `2^j`, `j ∈ [-8, 4]`), near one of its legs or over its face.
fn huge_triangle_and_near_point() -> impl Strategy<Value = ([P3; 3], P3)> + Clone {
    (vec3(BOX), unit(), unit(), 40..=996i32, vec3(1.0), -8..=4i32, 0..3usize, 0..6usize).prop_map(
        |(p0, u1, u2, k, off, j, near, order)| {
            let l = pow2(k);
            let v1 = add(p0, scale(u1, l));
            let v2 = add(p0, scale(u2, l));
            let small = pow2(j);
            // Near the vertex, a point along a leg at a small distance, or a
            // point a little inside the face.
            let at = match near {
                0 => add(p0, scale(off, small)),
                1 => add(add(p0, scale(u1, small * 3.0)), scale(off, small)),
                _ => add(add(p0, scale(add(u1, u2), small * 2.0)), scale(off, small)),
            };
            let v = [p0, v1, v2];
            let perms = [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]];
            let p = perms[order];
            ([v[p[0]], v[p[1]], v[p[2]]], at)
        },
    )
}

/// A plane through a point near the origin with a normal of length `2^k`,
/// `k ∈ [-600, 600]`, and its matching offset.
fn scaled_plane() -> impl Strategy<Value = (P3, f64)> + Clone {
    (unit(), -600..=600i32, vec3(BOX)).prop_map(|(u, k, p)| {
        let n = scale(u, pow2(k));
        (n, dot(n, p))
    })
}

/// A positive length or speed at `f64`'s extremes: exactly `f64::MAX`, the
/// smallest subnormal, any subnormal, a normal number of any binade, or one of
/// ordinary size (so that extremes meet ordinary numbers too).
fn extreme_magnitude() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        Just(f64::MAX),
        Just(f64::from_bits(1)),
        (1u64..1u64 << 52).prop_map(f64::from_bits),
        magnitude(-1022, 1023),
        magnitude(-8, 8),
    ]
}

/// A coordinate or velocity component at `f64`'s extremes (either sign), or
/// zero.
fn extreme_component() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        4 => (extreme_magnitude(), any::<bool>()).prop_map(|(m, neg)| if neg { -m } else { m }),
        1 => Just(0.0),
    ]
}

fn extreme_vec3() -> impl Strategy<Value = P3> + Clone {
    prop::array::uniform3(extreme_component())
}

/// The end of a `toi` interval from the smallest subnormal to 1e300:
/// `5e-324`, any subnormal, a normal number of any binade up to `2^996`,
/// 1 or 1e300.
fn extreme_t_max() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        Just(f64::from_bits(1)),
        (1u64..1u64 << 52).prop_map(f64::from_bits),
        magnitude(-1022, 995),
        Just(1.0),
        Just(1e300),
    ]
}

/// A sliver far from the origin and a point on it: vertices `v0` and `v1`
/// with coordinates up to `2^1000` apart, `v2` near their midpoint, off the
/// line by `2^-j` of the edge (`j ∈ [20, 60]`; the face normal's `f64` cross
/// product cancels, often to zero); the point is one of the vertices
/// exactly, or one of them moved by up to a unit.
fn sliver_and_vertex() -> impl Strategy<Value = ([P3; 3], P3)> + Clone {
    (extreme_vec3(), vec3(BOX), unit(), 20..=60i32, 0..3usize, any::<bool>(), vec3(1.0)).prop_map(
        |(v0, v1, u, j, at, exact, off)| {
            // The midpoint and the edge at half scale: no sum overflows.
            let mid = add(scale(v0, 0.5), scale(v1, 0.5));
            let half_edge = sub(scale(v1, 0.5), scale(v0, 0.5));
            let across = crashtest_core::vec3::norm_sqrt_dot(half_edge) * pow2(-j);
            let v2 = add(mid, scale(u, if across.is_finite() { across } else { pow2(1000 - j) }));
            let v = [v0, v1, v2];
            let p = if exact { v[at] } else { add(v[at], off) };
            (v, p)
        },
    )
}

/// The `toi` scenes at `f64`'s extremes of the multi-scale family (see the
/// module docs): sphere–sphere, sphere–plane and a sphere on a sliver's
/// vertex, each moving at extreme speeds over an extreme interval.
fn extreme_toi(case: impl Fn(Scene, Option<f64>) -> Case + Clone + Send + Sync + 'static) -> SBoxedStrategy<Case> {
    let moving = super::toi::moving;
    let valid = |mut c: Case| {
        make_valid(&mut c);
        c
    };
    let (c1, c2, c3) = (case.clone(), case.clone(), case);
    prop_oneof![
        (
            (extreme_vec3(), extreme_magnitude(), extreme_vec3()),
            (extreme_vec3(), extreme_magnitude(), extreme_vec3()),
            extreme_t_max()
        )
            .prop_map(move |((ca, ra, va), (cb, rb, vb), t)| valid(c1(
                (moving(sphere(ca, ra), va), Some(moving(sphere(cb, rb), vb))),
                Some(t)
            ))),
        (
            (extreme_vec3(), extreme_magnitude(), extreme_vec3()),
            (
                // Components each at an extreme, or a direction of any length
                // (a normal of length 4e121 beside a subnormal radius).
                prop_oneof![extreme_vec3(), (unit(), magnitude(-1022, 1000)).prop_map(|(u, m)| scale(u, m))],
                prop_oneof![extreme_component(), vec3(BOX).prop_map(|p| p[0]), Just(0.0)],
                extreme_vec3()
            ),
            extreme_t_max()
        )
            .prop_map(move |((c, r, va), (n, d, vb), t)| valid(c2(
                (moving(sphere(c, r), va), Some(moving(plane(n, d), vb))),
                Some(t)
            ))),
        (sliver_and_vertex(), extreme_magnitude(), extreme_vec3(), extreme_vec3(), extreme_t_max()).prop_map(
            move |((v, at), r, va, vb, t)| valid(c3(
                (moving(sphere(at, r), va), Some(moving(triangle(v), vb))),
                Some(t)
            ))
        ),
    ]
    .sboxed()
}

fn multi_scale(query: Query) -> SBoxedStrategy<Case> {
    let case = move |(a, b): Scene, t_max: Option<f64>, restitution: Option<f64>| Case {
        name: String::new(),
        source: String::new(),
        query,
        a,
        b,
        expect: None,
        tol: None,
        t_max,
        restitution,
    };
    match query {
        Query::Contact => prop_oneof![
            (huge_triangle_and_near_point(), magnitude(-8, 4), any::<bool>()).prop_map(move |((v, c), r, flip)| {
                let (s, t) = (sphere(c, r), triangle(v));
                case(if flip { (t, Some(s)) } else { (s, Some(t)) }, None, None)
            }),
            (scaled_plane(), vec3(BOX), magnitude(-8, 3), any::<bool>()).prop_map(move |((n, d), c, r, flip)| {
                let (s, p) = (sphere(c, r), plane(n, d));
                case(if flip { (p, Some(s)) } else { (s, Some(p)) }, None, None)
            }),
            (vec3(BOX), magnitude(-8, 3), unit(), magnitude(40, 1000)).prop_map(move |(c, r, u, big)| {
                // A small sphere against a huge one whose surface passes near it.
                let cb = sub(c, scale(u, big));
                case((sphere(c, r), Some(sphere(cb, big))), None, None)
            }),
        ]
        .sboxed(),
        Query::Intersect => prop_oneof![
            (huge_triangle_and_near_point(), unit(), magnitude(-8, 4)).prop_map(move |((v, at), u, len)| {
                case((segment(sub(at, scale(u, len)), add(at, scale(u, len))), Some(triangle(v))), None, None)
            }),
            (scaled_plane(), vec3(BOX), vec3(BOX))
                .prop_map(move |((n, d), s0, s1)| { case((segment(s0, s1), Some(plane(n, d))), None, None) }),
        ]
        .sboxed(),
        Query::Barycentric => huge_triangle_and_near_point()
            .prop_map(move |(v, at)| case((point(at), Some(triangle(v))), None, None))
            .sboxed(),
        Query::Bounds => prop::collection::vec((signed_magnitude(-1074, 1000), vec3(1.0)), 1..8)
            .prop_map(move |ps| {
                let pts = ps.into_iter().map(|(m, u)| scale(u, m)).collect();
                case((points(pts), None), None, None)
            })
            .sboxed(),
        Query::Overlap => (vec3(BOX), magnitude(-1074, 0), signed_magnitude(40, 1000), 0..3usize, any::<bool>())
            .prop_map(move |(c, small, big, axis, touch)| {
                // A tiny box at c, a huge one whose face lies at the tiny box's
                // face (touching) or just beyond it.
                let lo = sub(c, [small; 3]);
                let hi = add(c, [small; 3]);
                let (mut bmin, mut bmax) = ([-big.abs(); 3], [big.abs(); 3]);
                let face = if touch { hi[axis] } else { hi[axis].next_up() };
                if big > 0.0 {
                    bmin[axis] = face;
                } else {
                    bmax[axis] = lo[axis];
                }
                case((aabb(lo, hi), Some(aabb(bmin, bmax))), None, None)
            })
            .sboxed(),
        Query::Toi => prop_oneof![
            2 => extreme_toi(move |scene, t_max| case(scene, t_max, None)),
            1 => (huge_triangle_and_near_point(), magnitude(-8, 4), unit(), magnitude(-8, 6)).prop_map(
                move |((v, c), r, u, speed)| {
                    // The sphere starts a little off and moves through the spot.
                    let start = sub(c, scale(u, speed / 2.0));
                    let mut s = sphere(start, r);
                    if let Shape::Sphere(sp) = &mut s {
                        sp.velocity = Some(scale(u, speed));
                    }
                    case((s, Some(triangle(v))), None, None)
                }
            ),
            1 => (scaled_plane(), vec3(BOX), magnitude(-8, 3), vec3(8.0), magnitude(-300, 300)).prop_map(
                move |((n, d), c, r, v, speed)| {
                    let mut s = sphere(c, r);
                    if let Shape::Sphere(sp) = &mut s {
                        sp.velocity = Some(scale(v, speed));
                    }
                    case((s, Some(plane(n, d))), None, None)
                }
            ),
        ]
        .sboxed(),
        Query::Distance => super::distance::full_range_scene().prop_map(move |s| case(s, None, None)).sboxed(),
        Query::Ccd => super::ccd::full_range_scene().prop_map(move |(scene, p)| case(scene, p.t_max, None)).sboxed(),
        Query::Response => (
            vec3(BOX),
            unit(),
            magnitude(-8, 3),
            magnitude(-8, 3),
            (signed_magnitude(-500, 500), vec3(1.0), vec3(1.0)),
            (magnitude(-1074, 1000), magnitude(-1074, 1000)),
            0.0..=1.0f64,
            any::<bool>(),
        )
            .prop_map(move |(ca, u, ra, rb, (speed, wa, wb), (ma, mb), e, with_plane)| {
                let cb = sub(ca, scale(u, ra + rb));
                let mut a = sphere(ca, ra);
                if let Shape::Sphere(s) = &mut a {
                    s.velocity = Some(scale(wa, speed));
                    s.mass = Some(ma);
                }
                let b = if with_plane {
                    // The plane tangent to a at its lowest point along −u, its
                    // normal of length 2^k.
                    let n = scale(u, speed.abs().max(f64::MIN_POSITIVE));
                    plane(n, dot(n, sub(ca, scale(u, ra))))
                } else {
                    let mut b = sphere(cb, rb);
                    if let Shape::Sphere(s) = &mut b {
                        s.velocity = Some(scale(wb, speed));
                        s.mass = Some(mb);
                    }
                    b
                };
                let mut c = case((a, Some(b)), None, Some(e));
                make_valid(&mut c);
                c
            })
            .sboxed(),
    }
}

/// The strategy of one sub-family of `query`'s full-range family (see the
/// module docs), built on `base`, the query's ordinary strategy.
pub(crate) fn sub_family(query: Query, family: &str, base: SBoxedStrategy<Case>) -> SBoxedStrategy<Case> {
    match family {
        "raw bit patterns" => raw_bits(base),
        "huge magnitudes" => huge(base),
        "tiny and subnormal magnitudes" => tiny(base),
        "signed zeros" => signed_zeros(base),
        _ => multi_scale(query),
    }
}
