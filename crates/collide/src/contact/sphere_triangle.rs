//! Sphere–triangle contact.

use super::Contact;
use super::closest_pt_triangle::{
    Closest, EDGE_TEST_ROUNDING, Region, closest_on_outer_edges, closest_pt_point_triangle_region_with_area,
    nearest_on_edges,
};
use super::exact_boundary::{Distance, nearest_on_boundary};
use super::sphere_sphere::CONCENTRIC_FALLBACK_NORMAL;
use crate::barycentric::barycentric_triangle_tight;
use crate::exact::filter::Filtered;
use crate::exact::norm::safe_squared_range;
use crate::real::{Real, Vec3, c, scale2, scale2v, stable_norm, try_normalize_stable, unit_scale};
use crate::shapes::{Sphere, Triangle};

/// Contact between a sphere `a` (centre `M`, radius `r`) and a triangle `b`.
///
/// **Method.** The triangle's point closest to the centre, `q`
/// ([`closest_pt_point_triangle`](super::closest_pt_point_triangle), computed in the frame of the centre — see the
/// comment in the body), is where the sphere meets the triangle first;
/// then, as for two spheres with `b` shrunk to the point `q`:
///
/// ```text
/// contact when ‖M − q‖ ≤ r,   n = (M − q) / ‖M − q‖,   p = q,   depth = r − ‖M − q‖
/// ```
///
/// The triangle is two-sided and has no thickness: a centre behind the face is
/// pushed out through the face it is behind, as for one in front.
///
/// **Clear misses first.** Before any closest point, two proven tests answer
/// "apart" for a sphere that certainly does not reach the triangle: its box
/// (the vertices in the centre's frame all beyond `r` on one side of an
/// axis; a dozen minima and maxima) and its plane (the centre's filtered
/// volume `n · (M − v0)` against `r ‖n‖`, squared: a dozen flops on the
/// filtered normal computed anyway). Each holds only when the exact
/// distance exceeds `r (1 + 2^−31)`: "apart" is the exact answer, and the
/// one the full computation gives wherever its distance is accurate to
/// `2^−38` (see `EARLY_MISS_MARGIN` in the source). On the benchmark's
/// mix of random and near-degenerate cases they settle over two in five
/// queries (three in five of the uniform ones), which then cost no closest
/// point, root or division.
///
/// **Deviation from the book: a certified region.** Ericson's region tests
/// decide on rounded values, and the edge tests among them are degree-4
/// polynomials: on a sliver, or for a centre whose projection is within
/// rounding of an edge, they can take a projection outside the triangle for
/// inside (the face point `M − n d` then lies off the triangle: `1.1e-2` off
/// on a rotated sliver of height `1e-15`, crashtest's sliver sweep) or one
/// inside for outside (an edge point up to the sliver's height off). Here the
/// face region is taken only when the projection is proven inside, by the
/// book's own edge tests against a rigorous bound on their rounding (every
/// ordinary query) or else by the signs of the centre's barycentric
/// coordinates, or else by the signs of the three edge tests in
/// compensated, then exact, arithmetic (a projection within `50 ε L` of an
/// edge, `L` the longest edge: for a small sphere beside a huge triangle
/// that is several radii); otherwise the
/// closest point is on an edge the projection is outside of. A book's edge
/// point far closer to the centre than the triangle's extent (`2^−20` of
/// it) is recomputed from the exact region, and every edge foot is formed
/// from its edge's nearer end, without overflow or underflow, so a sphere
/// of radius 4 beside a triangle with legs of `1e300` gets its closest
/// point to the rounding of its own scale, not of the triangle's
/// (`certified_region`, in the source, has the derivation). In the face region the normal and the distance `d` come
/// from the triangle's cross product and the centre's volume, certified by a
/// static filter (else compensated, else exact arithmetic) to `2^−40`: the
/// normal's direction, and `d` relative to the larger of itself and `r` — so
/// the depth `r − d` of a contact is within about `2^−39 r`.
///
/// **Degenerate input.** A centre exactly on the triangle (decided exactly, with
/// `orient3d` and `orient2d`) has no direction: the normal falls back to the face
/// normal `(v1 − v0) × (v2 − v0)`, normalized, depth `r`, point `M`, flagged. A
/// centre off the triangle but nearer than the rounding of `q` can resolve gets
/// the face normal on the centre's (exactly known) side, not flagged. A zero-area
/// triangle is answered as the segment or point it collapsed to; if even its
/// direction is lost, the normal is [`CONCENTRIC_FALLBACK_NORMAL`], flagged.
///
/// **Precision.** A type narrower than `f64` (`f32`) is answered in `f64` on
/// its exactly widened inputs and rounded once at the end, like the other
/// robust methods: the closest point's region tests multiply coordinates of
/// the centre's frame, and for a sphere far larger than the triangle (10⁴ times,
/// say) their cancellation in `f32` picked the wrong region, putting the point
/// a whole unit off on a triangle of size 3.
pub fn contact_sphere_triangle<T: Real>(a: &Sphere<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    contact_ranked(a, b, false).map(|(k, _)| k)
}

/// [`contact_sphere_triangle`] with the distance from the centre to the
/// triangle, accurate relative to itself (a few ulps on the boundary, `2^−40`
/// in the face region, 0 for a centre on the triangle): what a mesh's faces
/// are ranked by, where the depth `r − d` of a sphere far larger than the
/// mesh is `r` for every face.
pub(crate) fn contact_sphere_triangle_ranked<T: Real>(
    a: &Sphere<T>,
    b: &Triangle<T>,
) -> Option<(Contact<T>, Distance)> {
    contact_ranked(a, b, true)
}

/// [`contact_sphere_triangle`] and the distance of the contact; with `rank`,
/// the face region's distance is made accurate relative to itself also when
/// the sphere is far larger (without, it is accurate relative to the radius).
fn contact_ranked<T: Real>(a: &Sphere<T>, b: &Triangle<T>, rank: bool) -> Option<(Contact<T>, Distance)> {
    if T::EPSILON.wide() > f64::EPSILON {
        let w = |v: &Vec3<T>| Vec3::new(v.x.wide(), v.y.wide(), v.z.wide());
        let n = |v: &Vec3<f64>| Vec3::new(T::of(v.x), T::of(v.y), T::of(v.z));
        let [v0, v1, v2] = b.vertices;
        let (wide, dist) = contact_ranked::<f64>(
            &Sphere::new(w(&a.center), a.radius.wide()),
            &Triangle::new(w(&v0), w(&v1), w(&v2)),
            rank,
        )?;
        let k = Contact {
            point: n(&wide.point),
            normal: n(&wide.normal),
            depth: T::of(wide.depth),
            degenerate: wide.degenerate,
        };
        return Some((k, dist));
    }
    // Outside the plain range (a tiny or subnormal scene, or a huge one) the
    // scene is answered scaled by a power of two to about 1, where no square
    // of a distance under- or overflows, and its lengths are scaled back.
    // Scaling up is exact; scaling down is done only when it pushes no
    // non-zero number of the scene below the normal range (a scene whose
    // numbers span more than the range itself — a huge radius beside tiny
    // coordinates — is answered as it is, by the paths below that scale their
    // own squares).
    let amax = |p: &Vec3<T>| p.x.abs().max(p.y.abs()).max(p.z.abs());
    let size = b.vertices.iter().map(amax).fold(amax(&a.center).max(a.radius.abs()), |m, x| m.max(x));
    let safe = |k: i32| {
        k > 0 || {
            let numbers = b.vertices.iter().chain([&a.center]).flat_map(|p| [p.x, p.y, p.z]).chain([a.radius]);
            numbers.filter(|x| *x != T::zero()).all(|x| scale2(x.abs(), k).wide() >= f64::MIN_POSITIVE)
        }
    };
    if let Some(k) = unit_scale(size).filter(|k| safe(*k)) {
        let a2 = Sphere::new(scale2v(&a.center, k), scale2(a.radius, k));
        let b2 = Triangle { vertices: b.vertices.map(|p| scale2v(&p, k)) };
        return contact_ranked(&a2, &b2, rank).map(|(r, d)| {
            let back = Contact { point: scale2v(&r.point, -k), depth: scale2(r.depth, -k), ..r };
            (back, d.scaled(-i64::from(k)))
        });
    }
    // Work in the frame of the centre: `M − q` is then computed as `−q'`, the
    // closest point of the translated triangle to the origin, whose rounding is
    // relative to the triangle's distance and size, not to the coordinates' size.
    // A scene far from the origin (1e14, say) otherwise loses every digit of a
    // small `M − q` to the rounding of `q`. The translation overflows only for
    // coordinates of opposite signs near the top of the range: then the global
    // frame is used.
    let [v0, v1, v2] = b.vertices;
    let wide = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let (centre, verts) = (wide(&a.center), [wide(&v0), wide(&v1), wide(&v2)]);
    let local = Triangle::new(v0 - a.center, v1 - a.center, v2 - a.center);
    // Inputs within `exact::filter`'s fast range (`|x| ≤ 2^63`) translate
    // without overflow; only others need the check.
    let fast = crate::exact::filter::in_fast_range_points([centre, verts[0], verts[1], verts[2]]);
    let in_local = fast || local.vertices.iter().all(crate::real::finite3);
    // Clear misses first, before any closest point: the triangle's box, in
    // the centre's frame, beyond the sphere's reach on some axis (see
    // `box_clear_miss`).
    let radius = a.radius.wide();
    if in_local && box_clear_miss(local.vertices.map(|v| wide(&v)), radius) {
        return None;
    }
    // The face normal and the centre's volume, filtered once: they show the
    // triangle has area, which side of it the centre is on, and (in the face
    // region) the contact's normal and distance, for nearly every input; the
    // exact predicates answer the rest. The centre certainly farther from the
    // plane than the sphere reaches is the second clear miss.
    let face_filter = FaceFilter::new(centre, verts, fast);
    if face_filter.as_ref().is_some_and(|f| f.plane_clear_miss(radius)) {
        return None;
    }
    let flat = match &face_filter {
        Some(f) if f.has_area() => false,
        _ => collinear_of(b),
    };
    // The book's closest point where its region is certain, else the region
    // of the centre's projection decided with certainty, else the nearest
    // point of the edges (see `certified_region`), in the centre's frame
    // when its translation is finite. The book's tests are inlined once, on
    // the translated vertices just computed; the global frame's call is out
    // of line.
    let frame = || if in_local { (Vec3::zeros(), local) } else { (a.center, *b) };
    let (q_raw, region) = if flat {
        let (p, t) = frame();
        (nearest_on_edges(&p, &t), Region::Boundary)
    } else {
        let found = if in_local {
            // The origin built from its components (`Vec3::zeros` goes
            // through memory, and the book's differences reload it).
            let origin = Vec3::new(T::zero(), T::zero(), T::zero());
            closest_pt_point_triangle_region_with_area(&origin, &local)
        } else {
            closest_in_global_frame(&a.center, b)
        };
        match certified_region(&found, in_local, &a.center, b) {
            Certified::Face => (found.point, Region::Face),
            // The book's boundary point is formed from its region's base
            // vertex (`a + ab v`, `b + bc w`): from the far end of a huge
            // edge its rounding is of that edge's size. A point far closer
            // to the centre than the triangle's extent is recomputed from
            // the exact region, from the nearer end of its edge.
            Certified::Book if found.region == Region::Boundary && local_feature(&found, in_local) => {
                match exact_region(&a.center, b) {
                    Certified::Edges(outer) => {
                        let (p, t) = frame();
                        (closest_on_outer_edges(&p, &t, outer), Region::Boundary)
                    }
                    _ => (found.point, found.region),
                }
            }
            Certified::Book => (found.point, found.region),
            Certified::Edges(outer) => {
                let (p, t) = frame();
                (closest_on_outer_edges(&p, &t, outer), Region::Boundary)
            }
        }
    };
    let (q, delta) = if in_local { (a.center + q_raw, -q_raw) } else { (q_raw, a.center - q_raw) };
    // In the face region the direction is the face normal and the distance the
    // plane distance; both come accurately from exact-filtered volumes, where
    // the closest point's own rounding would tilt the normal of a thin triangle
    // by (its rounding) / (the distance).
    if region == Region::Face {
        // The compensated stage, formed at most once: the face normal and
        // distance where the plain filter was not accurate enough, and the
        // exact on-triangle test after it when the centre is in the plane.
        let (answer, compensated) = match face_filter.as_ref().and_then(|f| f.normal_and_distance(a.radius.wide())) {
            Some(answer) => (Some(answer), None),
            None => {
                let (answer, face) = face_normal_and_distance_of(a, b);
                (answer, Some(face))
            }
        };
        if let Some((n, d)) = answer {
            let (normal, dist) = (Vec3::new(c(n[0]), c(n[1]), c(n[2])), c::<T>(d));
            if !(dist <= a.radius) {
                return None;
            }
            let k = Contact { point: a.center - normal * dist, normal, depth: a.radius - dist, degenerate: false };
            // Deep inside (the distance far below the radius) the distance
            // is only known to 2^−40 of the radius: ranked, it is refined to
            // 2^−40 of itself.
            let ranked = if rank && d * DEEP_RATIO < a.radius.wide() {
                let (p, v) = widened(a, b);
                let face = compensated.flatten().or_else(|| FaceCompensated::new(p, v));
                face_normal_and_distance(p, v, 0.0, face.as_ref()).map_or(d, |(_, d0)| d0)
            } else {
                d
            };
            return Some((k, Distance::of(ranked, 0)));
        }
        // No normal: the centre is in the plane, hence on the triangle (its
        // projection is inside), or farther from the plane than `f64` reaches.
        let face = compensated.unwrap_or_else(|| compensated_of(a, b));
        if centre_on_triangle(&a.center, b, face.as_ref()) != OnTriangle::Exactly {
            return None;
        }
        let normal = face_unit_normal(b).unwrap_or_else(|| {
            let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
            Vec3::new(c(x), c(y), c(z))
        });
        return Some((Contact { point: a.center, normal, depth: a.radius, degenerate: true }, Distance::ZERO));
    }
    // Numbers spanning so many magnitudes that the closest point's rounding
    // (of the triangle's extent in the frame) may exceed the distance itself:
    // the direction and distance of the boundary point decided exactly.
    if boundary_unresolved(&delta, in_local, &local, b, &a.center)
        && let Some(bp) = nearest_on_boundary(&a.center, b)
    {
        let d = bp.distance.to_f64();
        if !(d <= a.radius.wide()) {
            return None;
        }
        let depth = a.radius - T::of(d);
        return Some((Contact { point: bp.point, normal: bp.normal, depth, degenerate: false }, bp.distance));
    }
    // A clear miss needs no root (see `CLEAR_MISS_EPS`).
    let nn = delta.norm_squared();
    let rr = a.radius * a.radius;
    let (lo, hi) = safe_squared_range::<T>();
    if nn.finite() && rr >= lo && nn > rr * (T::one() + c::<T>(CLEAR_MISS_EPS) * T::EPSILON) {
        return None;
    }
    let plain = nn >= lo && nn <= hi;
    let dist = if plain { nn.sqrt() } else { stable_norm(&delta) };
    if !(dist <= a.radius) {
        return None;
    }
    // Which side of the plane the centre is on: the filtered volume's sign
    // where it is certain, else the exact test (which also tells a centre
    // exactly on the triangle).
    let on = match face_filter.as_ref().and_then(FaceFilter::side) {
        Some(side) => OnTriangle::Side(side),
        None => centre_on_triangle(&a.center, b, compensated_of(a, b).as_ref()),
    };
    let face = || face_unit_normal(b);
    if on == OnTriangle::Exactly {
        // Exactly on the triangle: no direction is defined.
        let normal = face().unwrap_or_else(|| {
            let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
            Vec3::new(c(x), c(y), c(z))
        });
        return Some((Contact { point: a.center, normal, depth: a.radius, degenerate: true }, Distance::ZERO));
    }
    let normal = if plain { Some(delta * (T::one() / dist)) } else { try_normalize_stable(&delta) };
    let normal = match normal {
        Some(n) => n,
        // Off the triangle, but closer than the rounding of `q` can resolve: the
        // direction is the face normal toward the side the centre is on, which the
        // exact test knows.
        None => match (on, face()) {
            (OnTriangle::Side(s), Some(n)) if s != 0.0 => n * c::<T>(s),
            _ => {
                let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
                let k =
                    Contact { point: q, normal: Vec3::new(c(x), c(y), c(z)), depth: a.radius - dist, degenerate: true };
                return Some((k, Distance::of(dist.wide(), 0)));
            }
        },
    };
    Some((Contact { point: q, normal, depth: a.radius - dist, degenerate: false }, Distance::of(dist.wide(), 0)))
}

/// Ratio of the radius to the face region's distance above which a ranked
/// contact refines the distance (see [`contact_sphere_triangle_ranked`]):
/// `2^20`, where 2^−40 of the radius is no longer 2^−20 of the distance.
const DEEP_RATIO: f64 = 1048576.0;

/// Ratio of the triangle's extent in the frame the closest point was
/// computed in to the offset from the centre below which that offset's
/// direction is recomputed exactly ([`nearest_on_boundary`]): `2^12`. The
/// point's rounding is a few ulps of the extent, so the plain direction is
/// within a few `2^−40` rad where the offset is larger.
const UNRESOLVED_RATIO: f64 = 4096.0;

/// Whether the boundary point's offset `delta` from the centre is below
/// [`UNRESOLVED_RATIO`] of the extent it was computed at: the translated
/// vertices in the centre's frame, else the vertices and the centre.
#[inline]
fn boundary_unresolved<T: Real>(
    delta: &Vec3<T>,
    in_local: bool,
    local: &Triangle<T>,
    b: &Triangle<T>,
    centre: &Vec3<T>,
) -> bool {
    let extent = if in_local {
        local.vertices.iter().fold(T::zero(), |m, v| m.max(v.amax()))
    } else {
        b.vertices.iter().fold(centre.amax(), |m, v| m.max(v.amax()))
    };
    delta.amax().wide() * UNRESOLVED_RATIO < extent.wide()
}

/// The centre and the vertices widened to `f64`.
#[inline(always)]
fn widened<T: Real>(a: &Sphere<T>, b: &Triangle<T>) -> ([f64; 3], [[f64; 3]; 3]) {
    let w = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    (w(&a.center), b.vertices.each_ref().map(w))
}

// The rarely taken paths below form the widened inputs themselves, out of
// line: passed down from the common path, the arrays would be laid out in
// memory there on every query, and reloaded across the stores that built
// them (a stall).

/// Whether the triangle's vertices are exactly collinear (zero area).
#[cold]
#[inline(never)]
fn collinear_of<T: Real>(b: &Triangle<T>) -> bool {
    let w = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let [v0, v1, v2] = &b.vertices;
    crate::exact::collinear(w(v0), w(v1), w(v2))
}

/// [`FaceCompensated::new`] of the query's inputs.
#[cold]
#[inline(never)]
fn compensated_of<T: Real>(a: &Sphere<T>, b: &Triangle<T>) -> Option<FaceCompensated> {
    let (p, v) = widened(a, b);
    FaceCompensated::new(p, v)
}

/// [`face_normal_and_distance`] of the query's inputs, with the compensated
/// stage it formed (for [`centre_on_triangle`] after it).
#[cold]
#[inline(never)]
fn face_normal_and_distance_of<T: Real>(
    a: &Sphere<T>,
    b: &Triangle<T>,
) -> (Option<([f64; 3], f64)>, Option<FaceCompensated>) {
    let (p, v) = widened(a, b);
    let face = FaceCompensated::new(p, v);
    (face_normal_and_distance(p, v, a.radius.wide(), face.as_ref()), face)
}

/// The book's closest point in the global frame, for the rare inputs whose
/// translation to the centre's frame overflows (kept out of line, so the
/// common path inlines the book's tests once).
#[cold]
#[inline(never)]
fn closest_in_global_frame<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Closest<T> {
    closest_pt_point_triangle_region_with_area(p, tri)
}

/// Margin of the root-free miss test of [`contact_sphere_triangle`], in units
/// of the type's ε: a computed `‖M − q‖²` above `fl(fl(r²) · (1 + 16ε))`, with
/// `r²` a normal number and `‖M − q‖²` finite, exceeds `r² (1 + 25u)` exactly
/// (`u = ε/2`; the three roundings of the sum of squares, one of `r²` and one
/// of the product take at most `5u`), so `‖M − q‖ > r (1 + 12u)`, and any
/// distance computed from `M − q` within `5u` of it (the plain root or the
/// scaled one) exceeds `r`: the test with the distance would say "apart" too.
const CLEAR_MISS_EPS: f64 = 16.0;

/// Relative margin of the two early misses of [`contact_sphere_triangle`]
/// (`box_clear_miss`, [`FaceFilter::plane_clear_miss`]): the sphere's reach
/// is taken as `r (1 + 2^−30)`. Each early miss is proven — the exact
/// distance from the centre to the triangle exceeds `r (1 + 2^−31)` — and
/// the margin keeps it clear of the full path's computed distance wherever
/// that is accurate to `2^−38` relative (the face region's filtered
/// distance; the closest point's distance whenever its rounding, relative
/// to the triangle's size, is small against `r`), so that it answers
/// "apart" where the full computation would. Elsewhere (a sphere far
/// smaller than the triangle, within the closest point's rounding of it)
/// the early answer is the exact one, where the full path's could be
/// "touching" by its rounding.
const EARLY_MISS_MARGIN: f64 = 1.0 + 1.0 / (1u64 << 30) as f64;

/// Whether the triangle's vertices `v`, given in the centre's frame
/// (`fl(v_i − M)`), all lie beyond the sphere's reach `R = fl(max(r, 0) (1 +
/// 2^−30))` ([`EARLY_MISS_MARGIN`]) on the same side of some axis: then the
/// whole triangle does, and the exact distance from the centre to it is at
/// least `min_i (v_i − M)_k > R / (1 + u) > r (1 + 2^−31)` (a rounded
/// difference above `R ≥ 0` is positive and within `u` of the exact one,
/// relative): certainly apart. Twelve minima and maxima, six comparisons,
/// one branch. A negative or NaN radius reaches `0` (the full path answers
/// "apart" for it too, except for a centre exactly on the triangle, which no
/// box excludes). The caller passes finite coordinates only.
#[inline(always)]
fn box_clear_miss(v: [[f64; 3]; 3], r: f64) -> bool {
    let min = |x: f64, y: f64| if x < y { x } else { y };
    let max = |x: f64, y: f64| if x > y { x } else { y };
    let reach = r.max(0.0) * EARLY_MISS_MARGIN;
    let mut miss = false;
    #[allow(clippy::needless_range_loop, reason = "`k` is the axis: it indexes the three vertices alike")]
    for k in 0..3 {
        // Plain selects (`minsd`, `maxsd`): the coordinates are finite.
        let (lo, hi) = (min(min(v[0][k], v[1][k]), v[2][k]), max(max(v[0][k], v[1][k]), v[2][k]));
        miss |= (lo > reach) | (hi < -reach);
    }
    miss
}

/// How the closest point of [`contact_sphere_triangle`] is taken.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Certified {
    /// The centre's projection is strictly inside the triangle: the face.
    Face,
    /// The book's region and point stand (a vertex or an edge).
    Book,
    /// The closest point of the edges `ab`, `bc`, `ca` that are set, the
    /// edges the projection may be outside of ([`closest_on_outer_edges`]).
    Edges([bool; 3]),
}

/// The region of the point closest to the centre `M`, certified. Ericson's
/// region tests decide on rounded values, and on a sliver (or for a centre
/// whose projection is within rounding of an edge) they can call a
/// projection outside the triangle inside — the face answer `M − n d` is
/// then a point off the triangle (by `1.1e-2` on a rotated sliver of height
/// `1e-15`) — or one inside outside (an edge point off by up to the sliver's
/// height: `1e-8` at height `1e-8`).
///
/// Whether the projection `P` is inside is the sign of the three edge tests
/// `((v_j − v_i) × (M − v_i)) · n`, `n = (v1 − v0) × (v2 − v0)`: Ericson's
/// `va`, `vb`, `vc` ([`Closest::edge_tests`]). Each stage below returns at
/// once when its rounding bound certifies every sign; only the cases it
/// cannot certify go on to the next, and every stage that answers gives
/// the exact signs, so the region is the exact one whichever stage decides:
///
/// 1. **The book's own values** (nearly every query): in the centre's frame
///    each computed test is within `512 u (Ē S)²` of the exact test on the
///    input ([`FRAME_EDGE_TEST_BOUND`]). When all three exceed it in
///    magnitude their signs are exact: all positive is the face (whatever
///    region the book picked: near a vertex of a sliver it can pick the
///    vertex); otherwise `P` is outside an edge and the book's vertex or edge
///    stands (its edge regions need the edge's test `≤ 0`, so they agree with
///    the exact signs; its vertex regions rest on dot products, which err by
///    a rounding of the point's parameter on an edge), or, if the book said
///    face, the closest point of the edges `P` is outside of is taken.
/// 2. **The centre's barycentric coordinates** otherwise (slivers, a
///    projection near an edge's line: [`projection_signs`], by
///    [`barycentric_triangle_tight`], exact where its filter cannot certify
///    `16 ε`, for any shape): each is within `17 ε` of the size
///    `max(1, |coords|)` ([`BARY_MARGIN`]), so a coordinate beyond `32 ε` of
///    the size on either side has the exact sign of its edge test. All of
///    them beyond it: all positive is the face, otherwise the closest point
///    is on the edges `P` is outside of ([`closest_on_outer_edges`]).
/// 3. **The edge tests in compensated, then exact, arithmetic** when a
///    coordinate is within the margin ([`exact_region`]): a projection
///    within `50 ε` of the triangle's size from an edge's line, which for a
///    small sphere beside a huge triangle is several radii.
///
/// Outside the centre's frame (coordinates near the overflow threshold)
/// stage 1 is skipped.
fn certified_region<T: Real>(found: &Closest<T>, in_local: bool, centre: &Vec3<T>, tri: &Triangle<T>) -> Certified {
    // `inner[k]`: the projection is strictly inside the edge opposite vertex
    // `k`; edges are listed `ab`, `bc`, `ca`, opposite `c`, `a`, `b`.
    let outer = |inner: [bool; 3]| [!inner[2], !inner[0], !inner[1]];
    if in_local && let Some(inner) = edge_tests_certain(found) {
        return match (inner, found.region) {
            ([true, true, true], _) => Certified::Face,
            (_, Region::Boundary) => Certified::Book,
            (_, Region::Face) => Certified::Edges(outer(inner)),
        };
    }
    match projection_signs(centre, tri) {
        Some([true, true, true]) => Certified::Face,
        Some(inner) => Certified::Edges(outer(inner)),
        None => exact_region(centre, tri),
    }
}

/// Stage 3 of [`certified_region`], where the barycentric coordinates
/// cannot tell (a projection within `50 ε` of the triangle's size from an
/// edge — which for a small sphere beside a huge triangle, `r = 4` against
/// legs of `1e15`, is several radii): the signs of the three edge tests
/// `va`, `vb`, `vc` in compensated arithmetic where its bound certifies
/// them ([`compensated_edge_tests`]: an exact zero on grid coordinates
/// included), else exactly ([`exact_edge_tests`]). All positive is the
/// face; otherwise the closest point is on the edges the projection is
/// outside of or on, exactly those.
#[cold]
#[inline(never)]
fn exact_region<T: Real>(centre: &Vec3<T>, tri: &Triangle<T>) -> Certified {
    let inner = match compensated_edge_tests(centre, tri) {
        Some(inner) => inner,
        None => exact_edge_tests(centre, tri).map(|s| s == crate::exact::Sign::Positive),
    };
    match inner {
        [true, true, true] => Certified::Face,
        _ => Certified::Edges([!inner[2], !inner[0], !inner[1]]),
    }
}

/// Whether each of the book's edge tests of `p` against `tri` (see
/// [`exact_edge_tests`]) is positive, from the tests in compensated
/// arithmetic (`exact::compensated::dot_cross` of the face normal and the
/// cross product of the offsets, each a compensated cross product of exact
/// differences): `None` unless every sign is certain, or when an input is
/// outside that arithmetic's domain. Its bound is zero when every operation
/// was exact, so a projection exactly on an edge's line (a sphere exactly
/// touching an edge, grid coordinates) is decided here, as is any test not
/// within about `u²` of its permanent; the rest go to [`exact_edge_tests`].
#[cold]
#[inline(never)]
fn compensated_edge_tests<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Option<[bool; 3]> {
    use crate::exact::compensated::{cross, diff, dot_cross, in_range_degree_4_points, sign_known};
    let w = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let (m, v) = (w(p), tri.vertices.each_ref().map(w));
    if !in_range_degree_4_points([m, v[0], v[1], v[2]]) {
        return None;
    }
    let n = cross(&diff(v[1], v[0]), &diff(v[2], v[0]));
    let rel = v.map(|x| diff(x, m));
    let mut inner = [false; 3];
    for (i, slot) in inner.iter_mut().enumerate() {
        let t = dot_cross(&n, &cross(&rel[(i + 1) % 3], &rel[(i + 2) % 3]));
        if !sign_known(&t) {
            return None;
        }
        *slot = t.value > 0.0;
    }
    Some(inner)
}

/// The exact signs of the book's edge tests of `p` against `tri` (see
/// [`Closest::edge_tests`]): `va = n · ((b − p) × (c − p))`, `vb`, `vc`
/// cyclically, `n = (b − a) × (c − a)`, in [`BigFloat`](crate::exact::BigFloat)
/// arithmetic on the widened inputs (degree 4, any finite magnitudes).
fn exact_edge_tests<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> [crate::exact::Sign; 3] {
    use crate::exact::BigFloat;
    type B3 = [BigFloat; 3];
    let big = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()].map(BigFloat::from_f64);
    let sub = |x: &B3, y: &B3| -> B3 { [0, 1, 2].map(|i| &x[i] - &y[i]) };
    let cross = |x: &B3, y: &B3| -> B3 {
        [0, 1, 2].map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            &(&x[j] * &y[k]) - &(&x[k] * &y[j])
        })
    };
    let dot = |x: &B3, y: &B3| &(&(&x[0] * &y[0]) + &(&x[1] * &y[1])) + &(&x[2] * &y[2]);
    let m = big(p);
    let v = tri.vertices.each_ref().map(big);
    let n = cross(&sub(&v[1], &v[0]), &sub(&v[2], &v[0]));
    let rel = v.each_ref().map(|x| sub(x, &m));
    [0, 1, 2].map(|i| dot(&n, &cross(&rel[(i + 1) % 3], &rel[(i + 2) % 3])).sign())
}

/// Ratio of a triangle's extent to its closest point's distance from the
/// centre above which the book's boundary point is recomputed (see
/// [`local_feature`]): `2^20`.
const LOCAL_FEATURE_RATIO: f64 = 1048576.0;

/// Whether the book's closest point `found`, computed in the centre's frame
/// (so its coordinates are its offset from the centre), is within
/// `1/`[`LOCAL_FEATURE_RATIO`] of the triangle's extent from the centre: a
/// small sphere beside a huge triangle, where the book's rounding (relative
/// to the extent) is far above the local scale. Ordinary queries (a
/// triangle and a sphere of comparable sizes) never are.
#[inline]
fn local_feature<T: Real>(found: &Closest<T>, in_local: bool) -> bool {
    in_local && found.point.amax().wide() * LOCAL_FEATURE_RATIO < found.edge_extent.wide()
}

/// Bound on the error of the book's edge tests computed in the centre's
/// frame, relative to `(Ē S)²`: `512 u = 2^−44` (`u = 2^−53`), with `S` the
/// largest magnitude of the translated vertices' components
/// ([`Closest::offset_extent`]: the offsets `0 − v'_i` are exact) and
/// `Ē = E + 8 u S`, `E` that of the computed edges ([`Closest::edge_extent`]).
///
/// Derivation. The tests are computed on the translated vertices
/// `v'_i = fl(v_i − M)`, each within `u S` of the exact `V_i = v_i − M` per
/// component. (1) On those inputs their rounding is at most
/// [`EDGE_TEST_ROUNDING`]` · u (E S)²` (`217`). (2) The exact tests on the
/// `v'_i` differ from those on the `V_i`: with the centre at the origin,
/// `vc = n · (A × (B − A))` (and cyclically for `va`, `vb`). The exact edges
/// of either triangle differ by at most `2 u S` per component and are at
/// most `E (1 + u) + 2 u S ≤ E + 4.001 u S ≤ Ē` in magnitude (`E ≤ 2.001 S`),
/// and `n`'s components at most `2 Ē²`; so `n` moves by at most `8 u S Ē` per
/// component against `A × (B − A)` of at most `2 S Ē`, and `A × (B − A)` by
/// at most `2 u S Ē + 4.001 u S²` against `n`: `48 u (S Ē)² + 48.03 u (S Ē)²`
/// (with `Ē ≤ 2.001 S`). (3) The sum, `312.3 u (Ē S)²`, stays below
/// `512 u (Ē S)²` after the roundings of the bound itself (three, relative;
/// `Ē` computed as `fl(E + 8 u S)` is still at least `E + 5.99 u S`) and of
/// any product that underflows (at most `2^−1075 (36 Ē S + 2)` in all),
/// both covered when `Ē S` is within [`CERTIFY_RANGE`].
const FRAME_EDGE_TEST_BOUND: f64 = 5.684341886080802e-14;

/// Part (2) of [`FRAME_EDGE_TEST_BOUND`]'s derivation, in units of
/// `u (Ē S)²`: how far the translation's rounding moves the exact tests.
const FRAME_PERTURBATION: f64 = 96.03;

// Parts (1) and (2) leave a quarter of the bound for its own roundings and
// for underflow (part (3)).
const _: () = assert!(EDGE_TEST_ROUNDING + FRAME_PERTURBATION <= 0.75 * 512.0);

/// Range of `Ē S` (see [`FRAME_EDGE_TEST_BOUND`]) in which the book's edge
/// tests are certified: `[2^−480, 2^480]`. Above it a test could overflow,
/// below it an underflowed product could exceed the margin; outside it the
/// barycentric stage of [`certified_region`] decides.
const CERTIFY_RANGE: (f64, f64) = (3.2033329522929615e-145, 3.1217485503159922e144);

/// On which side of each edge the centre's projection lies by the book's own
/// edge tests (stage 1 of [`certified_region`]): `Some([va > 0, vb > 0,
/// vc > 0])` (strictly inside the edge opposite `a`, `b`, `c`) when each
/// exceeds [`FRAME_EDGE_TEST_BOUND`]` · (Ē S)²` in magnitude (their signs are
/// then exact), `None` otherwise. `f64` only, the one precision
/// [`contact_sphere_triangle`] computes in.
#[inline]
fn edge_tests_certain<T: Real>(found: &Closest<T>) -> Option<[bool; 3]> {
    let bound = frame_edge_test_bound(found)?;
    let [va, vb, vc] = found.edge_tests.map(Real::wide);
    (va.abs() > bound && vb.abs() > bound && vc.abs() > bound).then_some([va > 0.0, vb > 0.0, vc > 0.0])
}

/// [`FRAME_EDGE_TEST_BOUND`]` · (Ē S)²` for the book's values `found`
/// (computed in the centre's frame), or `None` when `Ē S` is outside
/// [`CERTIFY_RANGE`] (an infinite extent included) or the values were not
/// computed in `f64`.
#[inline]
fn frame_edge_test_bound<T: Real>(found: &Closest<T>) -> Option<f64> {
    const U: f64 = f64::EPSILON / 2.0;
    if T::EPSILON.wide() > f64::EPSILON {
        return None;
    }
    let (e, s) = (found.edge_extent.wide(), found.offset_extent.wide());
    let es = (e + 8.0 * U * s) * s;
    (es >= CERTIFY_RANGE.0 && es <= CERTIFY_RANGE.1).then_some(FRAME_EDGE_TEST_BOUND * (es * es))
}

#[cfg(test)]
thread_local! {
    /// Stage-2 evaluations of [`certified_region`] on this thread, so tests
    /// can measure how rarely stage 1 leaves the question open.
    static STAGE_TWO: core::cell::Cell<u64> = const { core::cell::Cell::new(0) };
}

/// Margin of stage 2 of [`certified_region`], in units of the type's ε and of
/// the coordinates' size `max(1, |coords|)`: `32`.
/// [`barycentric_triangle_tight`] puts each coordinate within `16 ε` of the exact coordinates' size
/// (`2.5 ε` in `f32`), which is at most the returned size over `1 − 16 ε`:
/// within `17 ε` of the returned size, so a coordinate above `32 ε` of it is
/// certainly positive, and one below `−32 ε` of it certainly negative.
const BARY_MARGIN: f64 = 32.0;

/// On which side of each edge the projection of `centre` onto the plane of
/// `tri` lies, by its barycentric coordinates (stage 2 of
/// [`certified_region`]): `Some([λ0 > 0, λ1 > 0, λ2 > 0])` (strictly inside
/// the edge opposite each vertex) when every coordinate is beyond
/// [`BARY_MARGIN`] of their size on either side, so that every sign is
/// exact; `None` when one is within it (the projection within rounding of
/// an edge's line) or the answer is degenerate (no coordinates).
///
/// The signs are those of the book's edge tests (`va = ‖n‖² λ0`, and
/// cyclically: [`Closest::edge_tests`]), so a `Some` is what
/// [`exact_region`] would decide.
#[cold]
fn projection_signs<T: Real>(centre: &Vec3<T>, tri: &Triangle<T>) -> Option<[bool; 3]> {
    #[cfg(test)]
    STAGE_TWO.with(|n| n.set(n.get() + 1));
    let bary = barycentric_triangle_tight(centre, tri);
    if bary.degenerate {
        return None;
    }
    let size = bary.coords.iter().fold(T::one(), |m, x| m.max(x.abs()));
    let margin = c::<T>(BARY_MARGIN) * T::EPSILON * size;
    bary.coords.iter().all(|x| x.abs() > margin).then(|| bary.coords.map(|x| x > T::zero()))
}

/// The face normal `n = (v1 − v0) × (v2 − v0)` and the centre's volume
/// `n · (p − v0)` in plain `f64` with their error bounds (`exact::filter`),
/// for inputs within its range.
struct FaceFilter {
    /// `n`'s components with their bounds.
    n: [Filtered; 3],
    /// `n · (p − v0)`.
    vol: Filtered,
}

impl FaceFilter {
    /// The filtered normal and volume of the centre `p` and vertices `v`;
    /// `None` unless `fast`, whether they are in the filter's range
    /// (`exact::filter::in_fast_range_points`, computed by the caller).
    #[inline]
    fn new(p: [f64; 3], v: [[f64; 3]; 3], fast: bool) -> Option<Self> {
        use crate::exact::filter::{cross, cross_bounds, sub, triple};
        if !fast {
            return None;
        }
        let (n, perm) = cross(sub(v[1], v[0]), sub(v[2], v[0]));
        let vol = triple(n, perm, sub(p, v[0]));
        let nb = cross_bounds(perm);
        Some(Self { n: [0, 1, 2].map(|i| Filtered { value: n[i], bound: nb[i] }), vol })
    }

    /// Whether a component of `n` is certainly non-zero: the triangle has
    /// area.
    #[inline]
    fn has_area(&self) -> bool {
        self.n.iter().any(Filtered::decided)
    }

    /// Whether the centre is certainly farther from the triangle's plane
    /// than the sphere reaches: with `m = fl(|vol| − bound)` (a lower bound
    /// on the exact `|n · (M − v0)|`, within `u`), the reach
    /// `R = max(fl(r (1 + 2^−30)), 2^−240)` ([`EARLY_MISS_MARGIN`]) and
    /// `N = Σ max(fl(|n_i| + bound_i), 2^−240)²` (at least `(1 − u)^5`
    /// times the exact `‖n‖²`), the test `fl(m²) > fl(R² N)`
    /// with `m > 2^−240` proves `|n · (M − v0)|² > r² (1 + 2^−31)² ‖n‖²`
    /// (fewer than 12 roundings of `u` against the margin's `2^−30`): the
    /// plane distance, hence the distance to the triangle, exceeds
    /// `r (1 + 2^−31)`.
    ///
    /// The floors `2^−240` only enlarge the reach and `N` (a weaker test,
    /// still proven), and keep every square and product normal: no rounding
    /// is absolute, and none takes the processor's slow path for subnormal
    /// results (exactly zero normal components — any axis-aligned triangle —
    /// have `bound_i` near `2^−1000`, whose square would be subnormal). A
    /// negative or NaN radius reaches `2^−240`; an infinite one (or `R² N`
    /// beyond the range) never misses early. Eleven flops, no branch.
    #[inline(always)]
    fn plane_clear_miss(&self, r: f64) -> bool {
        /// Floor of the test's factors (2^−240): squares and products of
        /// two stay at least 2^−960, normal.
        const FLOOR: f64 = 5.659799424266695e-73;
        let floor = |x: f64| if x > FLOOR { x } else { FLOOR };
        let reach = floor(r * EARLY_MISS_MARGIN);
        let up = |f: &Filtered| floor(f.value.abs() + f.bound);
        let (x, y, z) = (up(&self.n[0]), up(&self.n[1]), up(&self.n[2]));
        let far = (reach * reach) * ((x * x + y * y) + z * z);
        let m = self.vol.value.abs() - self.vol.bound;
        let m = if m > FLOOR { m } else { 0.0 };
        m * m > far
    }

    /// `+1` when the centre is certainly on the side `n` points to, `−1` on
    /// the other, `None` when the filter cannot tell (in or near the plane).
    #[inline]
    fn side(&self) -> Option<f64> {
        self.vol.decided().then_some(if self.vol.value > 0.0 { 1.0 } else { -1.0 })
    }

    /// [`face_normal_and_distance`] from the filtered values, when their
    /// bounds make `n` jointly accurate to `REL` of its components' sum (which
    /// bounds the unit normal's error by about `3 REL`) and the volume
    /// accurate to `REL` of the larger of itself and `r ‖n‖` — so the
    /// distance `d` is within about `2 REL · max(d, r)`, and a sphere of
    /// radius `r` gets its depth `r − d` to `2 REL · r` wherever it touches
    /// (`d ≤ r`), as a relative bound on `d` alone would give, without asking
    /// for `d`'s own digits when the centre is deep (`d ≪ r`) — and the
    /// side is certain; and `n · n` is in the range where its plain root
    /// keeps full precision. `None` otherwise (`r` not finite counts as 0).
    #[inline]
    fn normal_and_distance(&self, r: f64) -> Option<([f64; 3], f64)> {
        use crate::exact::filter::jointly_accurate;
        const REL: f64 = FACE_REL;
        /// Unit roundoff of `f64`.
        const U: f64 = f64::EPSILON / 2.0;
        /// Smallest `n · n` normalized here (2^−960), as in the segment queries.
        const NORMAL_MIN_SQUARED: f64 = 1.0261342003245941e-289;
        let (vol, n) = (&self.vol, &self.n);
        let magnitude = vol.value.abs();
        let n_sum = (n[0].value.abs() + n[1].value.abs()) + n[2].value.abs();
        let n_err = (n[0].bound + n[1].bound) + n[2].bound;
        let nn = (n[0].value * n[0].value + n[1].value * n[1].value) + n[2].value * n[2].value;
        if !(jointly_accurate(n_err, n_sum, REL) && nn >= NORMAL_MIN_SQUARED && nn.is_finite()) {
            return None;
        }
        let norm = nn.sqrt();
        // `r ‖n‖` from below: `√(n·n)` carries at most 3 roundings of the
        // sum and 1 of the root, the components are off by at most `n_err`
        // in all, and the products 2 more roundings.
        let reach = r.max(0.0) * (norm * (1.0 - 8.0 * U) - n_err) * (1.0 - 4.0 * U);
        let reach = if reach.is_finite() { reach } else { 0.0 };
        if !(magnitude > vol.bound && jointly_accurate(vol.bound, magnitude.max(reach), REL)) {
            return None;
        }
        let inv = 1.0 / norm;
        let side = if vol.value > 0.0 { inv } else { -inv };
        let d = magnitude * inv;
        d.is_finite().then_some(([n[0].value * side, n[1].value * side, n[2].value * side], d))
    }
}

/// The face normal and the centre's volume in compensated arithmetic
/// ([`crate::exact::compensated`]): bounds of order `u²` times the permanent,
/// `0` when every operation was exact — so a centre exactly in the plane, or
/// exactly on an edge, is certified without the exact predicates for most
/// inputs.
struct FaceCompensated {
    /// The vertices and the centre.
    v: [[f64; 3]; 3],
    p: [f64; 3],
    /// `n = (v1 − v0) × (v2 − v0)`.
    n: crate::exact::compensated::Cross,
    /// `n · (p − v0)`.
    vol: Filtered,
}

impl FaceCompensated {
    /// `None` outside the compensated arithmetic's domain.
    #[inline]
    fn new(p: [f64; 3], v: [[f64; 3]; 3]) -> Option<Self> {
        use crate::exact::compensated::{cross, diff, dot, in_range_points};
        let inputs = [p, v[0], v[1], v[2]];
        if !in_range_points(inputs) {
            return None;
        }
        let n = cross(&diff(v[1], v[0]), &diff(v[2], v[0]));
        let vol = dot(&n, &diff(p, v[0]));
        Some(Self { v, p, n, vol })
    }

    /// The answer of `centre_on_triangle` where every sign it needs is
    /// certain: the side of the plane, or for a centre exactly in it,
    /// whether it lies in the closed triangle (tested in the projection that
    /// drops an axis along which `n` is certainly non-zero: the projection
    /// keeps inside-ness for coplanar points). `None`: not certain.
    fn centre_on_triangle(&self) -> Option<OnTriangle> {
        use crate::exact::Sign;
        use crate::exact::compensated::{cross_component, diff, sign_known};
        if !sign_known(&self.vol) {
            return None;
        }
        match Sign::of(self.vol.value) {
            Sign::Positive => return Some(OnTriangle::Side(1.0)),
            Sign::Negative => return Some(OnTriangle::Side(-1.0)),
            Sign::Zero => {}
        }
        let n = self.n.components();
        let k = (0..3).find(|&k| n[k].value.abs() > n[k].bound)?;
        let area = Sign::of(n[k].value);
        let [a, b, c] = self.v;
        let mut inside = true;
        for (u, w) in [(a, b), (b, c), (c, a)] {
            let s = cross_component(&diff(w, u), &diff(self.p, u), k);
            if !sign_known(&s) {
                return None;
            }
            let sign = Sign::of(s.value);
            inside &= sign == area || sign == Sign::Zero;
        }
        Some(if inside { OnTriangle::Exactly } else { OnTriangle::Side(0.0) })
    }
}

/// Relative accuracy of the face region's normal and distance, 2^−40: the
/// accuracy of crashtest's other computed values
/// ([`ESTIMATE_REL_ERR`](crate::exact::ESTIMATE_REL_ERR)). The distance is
/// held to it relative to the larger of itself and the sphere's radius (see
/// `FaceFilter::normal_and_distance`).
const FACE_REL: f64 = 1.0 / (1u64 << 40) as f64;

/// The unit face normal on `p`'s side and `p`'s distance from the triangle's
/// plane, from the triangle's cross product and the volume `orient3d`, each
/// refined to a relative error of 2^-40 by the exact filters (the distance
/// relative to the larger of itself and the radius `r`: the compensated
/// filter stops there; the exact estimates give 2^-40 of the distance
/// itself): accurate however thin the triangle. `None` for `p` in the plane,
/// a zero-area triangle, or a distance beyond `f64`'s range.
///
/// `face` is [`FaceCompensated::new`]`(p, v)`, formed by the caller (which
/// may need it again for [`centre_on_triangle`]).
fn face_normal_and_distance(
    p: [f64; 3],
    v: [[f64; 3]; 3],
    r: f64,
    face: Option<&FaceCompensated>,
) -> Option<([f64; 3], f64)> {
    use crate::exact::{Estimate, Sign, cross_estimate, orient3d_estimate};
    const REL: f64 = FACE_REL;
    if let Some(face) = face {
        if face.vol.bound == 0.0 && face.vol.value == 0.0 {
            // Exactly in the plane.
            return None;
        }
        let filter = FaceFilter { n: face.n.components(), vol: face.vol };
        if let Some(answer) = filter.normal_and_distance(r) {
            return Some(answer);
        }
    }
    let vol = orient3d_estimate(v[0], v[1], v[2], p, REL);
    let n = cross_estimate(v[0], v[1], v[2], REL);
    let unit = Estimate::unit_vector(n)?;
    let emax = n.iter().filter(|e| e.sign != Sign::Zero).map(|e| e.exp).max()?;
    let norm = n
        .iter()
        .filter(|e| e.sign != Sign::Zero)
        .map(|e| {
            let m = e.mant * pow2(e.exp - emax);
            m * m
        })
        .sum::<f64>()
        .sqrt();
    // orient3d is −n · (p − v0): positive when p is on the side n points away from.
    let side = match vol.sign {
        Sign::Zero => return None,
        Sign::Positive => -1.0,
        Sign::Negative => 1.0,
    };
    let d = vol.mant / norm * pow2(vol.exp - emax);
    d.is_finite().then_some((unit.map(|x| x * side), d))
}

/// The triangle's unit face normal, the direction of `(v1 − v0) × (v2 − v0)`,
/// from the cross product's components each accurate to [`FACE_REL`]
/// (`cross_estimate`: filtered, else exact): the fallback normal of a centre
/// on the triangle, and the direction of one nearer than `q`'s rounding. The
/// cross product in `T` cancels on a sliver far from the origin (a sliver at
/// 1e15 whose rounded cross product is exactly zero, leaving the `+z`
/// fallback 2.4 rad off its face) and overflows for vertices near `MAX` (a
/// NaN normal). `None` only for a zero-area triangle.
pub(crate) fn face_unit_normal<T: Real>(b: &Triangle<T>) -> Option<Vec3<T>> {
    let w = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let [v0, v1, v2] = b.vertices.map(|v| w(&v));
    let [x, y, z] = crate::exact::Estimate::unit_vector(crate::exact::cross_estimate(v0, v1, v2, FACE_REL))?;
    Some(Vec3::new(T::of(x), T::of(y), T::of(z)))
}

/// `2^k` as an `f64` (0 below the subnormal range, infinity above the top).
fn pow2(k: i64) -> f64 {
    if k < -1074 {
        0.0
    } else if k > 1023 {
        f64::INFINITY
    } else if k < -1022 {
        f64::from_bits(1u64 << (k + 1074))
    } else {
        f64::from_bits(((k + 1023) as u64) << 52)
    }
}

/// Where a point is with respect to a triangle, decided exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
enum OnTriangle {
    /// On the triangle (its plane, within or on its edges).
    Exactly,
    /// Not on it; the sign of the side of its plane (+1 the face normal's side,
    /// −1 the other, 0 in the plane but outside the triangle).
    Side(f64),
}

/// Decides exactly whether `p` lies on the triangle: coplanar (`orient3d = 0`)
/// and inside or on the boundary, tested by `orient2d` in a coordinate plane onto
/// which the triangle projects with non-zero area (projection preserves
/// inside-ness for coplanar points). A zero-area triangle is never "exactly on":
/// its contacts are those of the segment or point it collapsed to.
///
/// `face` is [`FaceCompensated::new`] of the widened `p` and vertices,
/// formed by the caller (which may have needed it already): it decides
/// nearly every input without the exact predicates.
fn centre_on_triangle<T: Real>(p: &Vec3<T>, t: &Triangle<T>, face: Option<&FaceCompensated>) -> OnTriangle {
    use crate::exact::{Sign, orient2d, orient3d};
    let w = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let [a, b, cc] = t.vertices.map(|v| w(&v));
    let q = w(p);
    if let Some(on) = face.and_then(FaceCompensated::centre_on_triangle) {
        return on;
    }
    match orient3d(a, b, cc, q) {
        // Shewchuk's sign: positive below, i.e. against the face normal.
        Sign::Positive => return OnTriangle::Side(-1.0),
        Sign::Negative => return OnTriangle::Side(1.0),
        Sign::Zero => {}
    }
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let pr = |v: [f64; 3]| [v[i], v[j]];
        let area = orient2d(pr(a), pr(b), pr(cc));
        if area == Sign::Zero {
            continue;
        }
        let inside = [(a, b), (b, cc), (cc, a)].iter().all(|&(u, v)| {
            let s = orient2d(pr(u), pr(v), pr(q));
            s == area || s == Sign::Zero
        });
        return if inside { OnTriangle::Exactly } else { OnTriangle::Side(0.0) };
    }
    OnTriangle::Side(0.0)
}

/// Contact between a triangle `a` and a sphere `b`: the reverse order of
/// [`contact_sphere_triangle`] (normal from the sphere toward the triangle, point
/// the sphere's deepest point).
///
/// The deepest point is formed as `centre − r n`, not as
/// [`Contact::swapped`]'s `q − n · depth` (equal in exact arithmetic): the
/// closest point `q` carries the rounding of the edge end it was formed
/// from, which on a huge edge is far larger than the sphere (a foot near
/// the origin on an edge from `−2.7e267` is `6e251` off along it, inside a
/// sphere of radius `1.7e235`); `centre − r n` is rounded to the sphere's
/// own size.
pub fn contact_triangle_sphere<T: Real>(a: &Triangle<T>, b: &Sphere<T>) -> Option<Contact<T>> {
    contact_sphere_triangle(b, a).map(|k| Contact {
        point: b.center - k.normal * b.radius,
        normal: -k.normal,
        depth: k.depth,
        degenerate: k.degenerate,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The answers below are exact small dyadic values or one rounded square
    /// root: 8 ulps of the answer's size covers the closest-point arithmetic.
    const ULPS: f64 = 8.0;

    fn close<T: Real>(a: T, b: f64) -> bool {
        (a.wide() - b).abs() <= ULPS * T::EPSILON.wide() * (1.0 + b.abs())
    }

    fn v<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
        Vec3::new(c(x), c(y), c(z))
    }

    /// Relative error allowed on a coordinate of the huge-edge answers
    /// below, each formed by a few rounded operations from exact inputs
    /// (a scaled offset, a product, a sum): 8 ulps of the coordinate.
    fn within_ulps(a: f64, b: f64) -> bool {
        (a - b).abs() <= ULPS * f64::EPSILON * b.abs()
    }

    /// A foot `7.2e-55` from the end of an edge of length `3.7e303` (the
    /// full-range campaign, raw bit patterns, index 3800): its parameter
    /// (`2e-358`) underflows, and the foot was taken for the end (`z = 0`).
    #[test]
    fn a_foot_near_the_end_of_a_huge_edge_is_not_its_end() {
        let s = Sphere::new(
            v::<f64>(-2.1797482487979055e-300, 1.4706778739662349e-249, 7.238951690163617e-55),
            5.0858359477770045e+231,
        );
        let t = Triangle::new(
            v(3.796234833260682e-78, -3.781149537639335e-244, 4.066951617276957e-247),
            v(-3.8573463642415374e-119, -2.7196405130348315e+159, 5.0445766859638205e+92),
            v(-1.1337068712159971e-262, -3.442577365552834e-177, 3.7276057721076633e+303),
        );
        let k = contact_sphere_triangle(&s, &t).expect("the sphere holds the triangle's near end");
        // The referee's point: (3.796e-78, -3.781e-244, 7.239e-55).
        assert!(within_ulps(k.point.z, 7.238951690163617e-55), "{:?}", k.point);
        assert!(within_ulps(k.point.x, 3.796234833260682e-78), "{:?}", k.point);
    }

    /// A centre `1e26` from an edge whose foot lies `1.8e56` along it (the
    /// full-range campaign, raw bit patterns, index 14335): the foot's
    /// rounding along the edge (`2e40`) swamps the distance, and the normal
    /// taken as centre minus foot pointed along the edge. The exact normal
    /// is `(3.3e-195, 1, -5.8e-23)`; in the reverse order the sphere's
    /// deepest point is `centre − r n`, `(-1.6e108, -4.9e302, 2.8e280)`.
    #[test]
    fn the_normal_to_a_huge_edge_is_across_it() {
        let s = Sphere::new(
            v::<f64>(1.7702592031397714e+56, 1.0212668022875161e+26, -5894.59007441647),
            4.918565576084892e+302,
        );
        let t = Triangle::new(
            v(3.3627509181147913e-69, -1.324379897733534e+47, 2.975027893590003e+193),
            v(8.672205556851418e-292, 1.4909137178941164e-108, 1.7941519537498704e-239),
            v(4.5683505341957413e+86, -3.0584212840271063e-153, -1.5447717696326936e-167),
        );
        let k = contact_sphere_triangle(&s, &t).expect("the sphere holds the triangle");
        assert!(within_ulps(k.normal.y, 1.0) && within_ulps(k.normal.z, -5.771841463184048e-23), "{:?}", k.normal);
        assert!(k.normal.x.abs() <= ULPS * f64::EPSILON, "{:?}", k.normal);
        let r = contact_triangle_sphere(&t, &s).expect("the same contact");
        assert!(within_ulps(r.point.y, -4.918565576084892e+302), "{:?}", r.point);
        assert!(
            (r.point.x - -1.6052088899167074e+108).abs() <= ULPS * f64::EPSILON * 4.918565576084892e+302,
            "{:?}",
            r.point
        );
    }

    fn tri<T: Real>() -> Triangle<T> {
        // Right triangle in z = 0 with legs 2 on x and y; face normal +z.
        Triangle::new(v(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(0.0, 2.0, 0.0))
    }

    fn face_region<T: Real>() {
        // Centre (0.5, 0.5, 0.75), r = 1: q = (0.5, 0.5, 0) (above the face),
        // ‖M − q‖ = 0.75, depth 0.25, normal +z.
        let k = contact_sphere_triangle(&Sphere::new(v::<T>(0.5, 0.5, 0.75), c(1.0)), &tri()).expect("overlap");
        assert!(close(k.depth, 0.25) && close(k.normal.z, 1.0) && close(k.point.x, 0.5));
        // Below the face: normal −z, same depth (two-sided).
        let k = contact_sphere_triangle(&Sphere::new(v::<T>(0.5, 0.5, -0.75), c(1.0)), &tri()).expect("overlap");
        assert!(close(k.depth, 0.25) && close(k.normal.z, -1.0));
    }

    #[test]
    fn face_region_f64() {
        face_region::<f64>();
    }

    #[test]
    fn face_region_f32() {
        face_region::<f32>();
    }

    #[test]
    fn vertex_and_edge_regions() {
        // Beyond vertex v1 = (2,0,0): centre (3,0,0), r = 1.5: q = v1, depth 0.5,
        // normal (1,0,0).
        let k = contact_sphere_triangle(&Sphere::new(v(3.0, 0.0, 0.0), 1.5), &tri::<f64>()).expect("vertex");
        assert!(close(k.point.x, 2.0) && close(k.depth, 0.5) && close(k.normal.x, 1.0));
        // Beyond the hypotenuse x + y = 2: centre (2,2,0), q = (1,1,0),
        // ‖M − q‖ = √2, r = 2: depth 2 − √2, normal (1,1,0)/√2.
        let k = contact_sphere_triangle(&Sphere::new(v(2.0, 2.0, 0.0), 2.0), &tri::<f64>()).expect("edge");
        assert!(close(k.point.x, 1.0) && close(k.point.y, 1.0));
        assert!(close(k.depth, 2.0 - 2f64.sqrt()) && close(k.normal.x, 0.5f64.sqrt()));
    }

    #[test]
    fn touching_vertex_is_contact() {
        // Centre (3,0,0), r = 1: ‖M − v1‖ = 1 = r.
        let k = contact_sphere_triangle(&Sphere::new(v(3.0, 0.0, 0.0), 1.0), &tri::<f64>());
        assert!(k.is_some_and(|k| close(k.depth, 0.0)));
        let apart = Sphere::new(v(3.0_f64.next_up(), 0.0, 0.0), 1.0);
        assert!(contact_sphere_triangle(&apart, &tri::<f64>()).is_none());
    }

    #[test]
    fn centre_on_the_face_falls_back_to_the_face_normal() {
        let k =
            contact_sphere_triangle(&Sphere::new(v(0.5, 0.5, 0.0), 1.0), &tri::<f64>()).expect("centre on the face");
        assert!(k.degenerate && close(k.normal.z, 1.0) && close(k.depth, 1.0));
    }

    #[test]
    fn zero_area_triangle_is_its_segment() {
        // Vertices on the x axis from 0 to 2 (v2 repeats v1): centre (1, 0.5, 0),
        // r = 1: q = (1,0,0), depth 0.5, normal +y.
        let flat = Triangle::new(v(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(2.0, 0.0, 0.0));
        let k = contact_sphere_triangle(&Sphere::new(v(1.0, 0.5, 0.0), 1.0), &flat).expect("hit");
        assert!(close(k.point.x, 1.0) && close(k.depth, 0.5) && close(k.normal.y, 1.0));
        assert!(!k.degenerate);
    }

    #[test]
    fn reverse_order_flips_the_normal_and_moves_the_point() {
        // From face_region: normal +z, q = (0.5,0.5,0), depth 0.25. Reversed:
        // normal −z, point M − r·(+z) = (0.5, 0.5, −0.25).
        let k = contact_triangle_sphere(&tri::<f64>(), &Sphere::new(v(0.5, 0.5, 0.75), 1.0)).expect("overlap");
        assert!(close(k.normal.z, -1.0) && close(k.point.z, -0.25) && close(k.depth, 0.25));
    }

    #[test]
    fn far_from_the_origin_the_normal_keeps_its_digits() {
        // The triangle of `tri` and a centre 0.75 above (0.5, 0.5), all shifted by
        // 2^46 (about 7e13) on x and y: the shift is exact, so the answer is the
        // unshifted one, normal +z, depth 0.25. Without the centre's frame, `q`
        // rounds to 2^-6 at that size and the normal tilts.
        let s = 2f64.powi(46);
        let t = Triangle::new(v(s, s, 0.0), v(s + 2.0, s, 0.0), v(s, s + 2.0, 0.0));
        let k = contact_sphere_triangle(&Sphere::new(v(s + 0.5, s + 0.5, 0.75), 1.0), &t).expect("overlap");
        assert!(close(k.normal.z, 1.0) && close(k.depth, 0.25), "{k:?}");
    }

    #[test]
    fn a_centre_a_hair_off_the_face_gets_the_side_it_is_on() {
        // Centre 1e-300 below the face z = 0 (inside it in x, y): the closest point
        // rounds onto the centre, but the exact side test says below, so the
        // normal is −z and the contact is not degenerate.
        let k = contact_sphere_triangle(&Sphere::new(v(0.5, 0.5, -1e-300), 1.0), &tri::<f64>()).expect("overlap");
        assert!(!k.degenerate && close(k.normal.z, -1.0), "{k:?}");
    }

    #[test]
    fn a_centre_in_the_plane_but_outside_the_triangle_is_not_degenerate() {
        // Centre (3, 3, 0), r = 2: in the plane, beyond the hypotenuse; q = (1,1,0),
        // ‖M − q‖ = 2√2 > 2: no contact. With r = 3: normal (1,1,0)/√2.
        assert!(contact_sphere_triangle(&Sphere::new(v(3.0, 3.0, 0.0), 2.0), &tri::<f64>()).is_none());
        let k = contact_sphere_triangle(&Sphere::new(v(3.0, 3.0, 0.0), 3.0), &tri::<f64>()).expect("overlap");
        assert!(!k.degenerate && close(k.normal.x, 0.5f64.sqrt()), "{k:?}");
    }

    /// Sliver cases: the exact closest point by brute force, compared with
    /// collide's answer in both precisions.
    mod slivers {
        use super::super::*;
        use crate::exact::{BigFloat, Sign};
        use crate::test_support::{both, eps, prop_both};
        use proptest::prelude::*;

        type P3 = [f64; 3];
        type B3 = [BigFloat; 3];

        /// Accuracy of an `f64` answer against the exact one, relative to the
        /// scene's size: the face region's normal and distance are refined to
        /// `FACE_REL = 2^−40` (about 9e-13, the unit normal to about three
        /// times that), and `1e-11` covers it with room; everything else is a
        /// few ulps. An `f32` answer is the `f64` one rounded once:
        /// `16 ε_f32` of the scene's size.
        const F64_TOL: f64 = 1e-11;

        fn tol<T: Real>() -> f64 {
            (16.0 * eps::<T>()).max(F64_TOL)
        }

        fn big(p: &P3) -> B3 {
            p.map(BigFloat::from_f64)
        }

        fn sub(a: &B3, b: &B3) -> B3 {
            [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
        }

        fn cross(a: &B3, b: &B3) -> B3 {
            [
                &(&a[1] * &b[2]) - &(&a[2] * &b[1]),
                &(&a[2] * &b[0]) - &(&a[0] * &b[2]),
                &(&a[0] * &b[1]) - &(&a[1] * &b[0]),
            ]
        }

        fn dot(a: &B3, b: &B3) -> BigFloat {
            &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2])
        }

        /// `x / y` as `f64` (`y > 0`), within a few ulps.
        fn ratio(x: &BigFloat, y: &BigFloat) -> f64 {
            let (x, y) = (x.estimate(), y.estimate());
            let q = x.mant / y.mant * if x.sign == Sign::Negative { -1.0 } else { 1.0 };
            if x.sign == Sign::Zero { 0.0 } else { q * 2f64.powi((x.exp - y.exp) as i32) }
        }

        /// The exact closest point of the triangle `v` to `m` (rounded to
        /// `f64`) and whether it is the face's: the face when the projection
        /// of `m` is inside (the three edge tests `n · ((v_j − v_i) × (m − v_i))`
        /// non-negative, exactly), else the nearest of the three edges' closest
        /// points, their squared distances compared exactly as fractions.
        /// Independent of collide's region logic: no rounded decision.
        fn exact_closest(m: &P3, v: &[P3; 3]) -> (P3, bool) {
            let (mb, vb) = (big(m), v.map(|x| big(&x)));
            let n = cross(&sub(&vb[1], &vb[0]), &sub(&vb[2], &vb[0]));
            let nn = dot(&n, &n);
            let inside = !nn.is_zero()
                && (0..3).all(|i| {
                    let j = (i + 1) % 3;
                    dot(&n, &cross(&sub(&vb[j], &vb[i]), &sub(&mb, &vb[i]))).sign() != Sign::Negative
                });
            if inside {
                let f = ratio(&dot(&n, &sub(&mb, &vb[0])), &nn);
                let nf = n.map(|x| x.to_f64());
                return ([0, 1, 2].map(|k| m[k] - nf[k] * f), true);
            }
            // (squared distance as numerator / denominator, point).
            let mut best: Option<(BigFloat, BigFloat, P3)> = None;
            for i in 0..3 {
                let j = (i + 1) % 3;
                let (e, w) = (sub(&vb[j], &vb[i]), sub(&mb, &vb[i]));
                let (num, den) = (dot(&w, &e), dot(&e, &e));
                let one = BigFloat::from_f64(1.0);
                let (d_num, d_den, point) = if num.sign() != Sign::Positive || den.is_zero() {
                    (dot(&w, &w), one, v[i])
                } else if num >= den {
                    let wj = sub(&mb, &vb[j]);
                    (dot(&wj, &wj), one, v[j])
                } else {
                    let t = ratio(&num, &den);
                    let d_num = &(&dot(&w, &w) * &den) - &(&num * &num);
                    (d_num, den, [0, 1, 2].map(|k| v[i][k] + (v[j][k] - v[i][k]) * t))
                };
                let better = match &best {
                    None => true,
                    Some((bn, bd, _)) => &d_num * bd < bn * &d_den,
                };
                if better {
                    best = Some((d_num, d_den, point));
                }
            }
            (best.expect("three edges").2, false)
        }

        /// collide's contact for the sphere (`centre`, `r`) and triangle `v`,
        /// all rounded to `T`, against the exact answer for those rounded
        /// inputs: point, depth and normal within [`tol`] of the scene's size.
        fn check<T: Real>(centre: &P3, r: f64, v: &[P3; 3]) -> Result<(), String> {
            let to = |p: &P3| Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]));
            let (m, tri) = (to(centre), Triangle::new(to(&v[0]), to(&v[1]), to(&v[2])));
            let wide = |p: &Vec3<T>| [p.x.wide(), p.y.wide(), p.z.wide()];
            let (mw, vw) = (wide(&m), tri.vertices.map(|x| wide(&x)));
            let (q, face) = exact_closest(&mw, &vw);
            let delta = [mw[0] - q[0], mw[1] - q[1], mw[2] - q[2]];
            let dist = (delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2]).sqrt();
            let radius = T::of(r);
            let depth = radius.wide() - dist;
            let scale = mw.iter().chain(vw.as_flattened()).fold(1f64, |s, x| s.max(x.abs()));
            let tol = tol::<T>() * scale;
            let what = format!("{centre:?} r {r} {v:?} in {}: exact {q:?} (face {face}), depth {depth}", eps::<T>());
            let Some(k) = contact_sphere_triangle(&Sphere::new(m, radius), &tri) else {
                return Err(format!("no contact: {what}"));
            };
            let p = wide(&k.point);
            let off = (0..3).map(|i| (p[i] - q[i]).abs()).fold(0.0, f64::max);
            let normal = wide(&k.normal);
            let n_off = (0..3).map(|i| (normal[i] - delta[i] / dist).abs()).fold(0.0, f64::max);
            if off > tol || (k.depth.wide() - depth).abs() > tol || n_off > tol / dist.min(1.0) {
                return Err(format!("{k:?}, point off by {off:e}, normal by {n_off:e}: {what}"));
            }
            Ok(())
        }

        /// The stability sweep's reproducer: `sliver` at `1e-15`, pose 17
        /// (rotated). The book's region tests called the projection of the
        /// centre inside this sliver, and the face answer `M − n d` was
        /// `1.1e-2` off the triangle, its normal `2.4e-2` rad off.
        const SWEEP_CENTRE: P3 = [-0.5327433866814169, -2.154630646748096, -0.0028854950561417736];
        const SWEEP_RADIUS: f64 = 0.7566051217875389;
        const SWEEP_TRIANGLE: [P3; 3] = [
            [-1.3268705335154625, -3.174406480249224, 0.8363359833435955],
            [-0.00031507780270017063, -2.3774489245180432, 0.3442837809720972],
            [1.5057474756203766, -1.4726485061221157, -0.21435204019144305],
        ];

        fn sweep_sliver_reproducer<T: Real>() {
            check::<T>(&SWEEP_CENTRE, SWEEP_RADIUS, &SWEEP_TRIANGLE).unwrap();
        }
        both!(sweep_sliver_at_1e_15_pose_17, sweep_sliver_reproducer);

        #[test]
        fn the_exact_reference_is_the_referees_answer_on_the_reproducer() {
            // The referee's answer (crashtest's arbitrary-precision oracle) for
            // the reproducer: point [-0.18035472855852946, -2.4856117302139173,
            // 0.4110649368499735], an edge point, so the brute force above must
            // find it to a few ulps.
            let want = [-0.18035472855852946, -2.4856117302139173, 0.4110649368499735];
            let (q, face) = exact_closest(&SWEEP_CENTRE, &SWEEP_TRIANGLE);
            assert!(!face, "the exact closest point is on an edge");
            assert!((0..3).all(|i| (q[i] - want[i]).abs() <= 8.0 * f64::EPSILON), "{q:?}");
        }

        /// A triangle with base `[−a, b]` on the x axis and apex
        /// `(−a + α L, ρ L, 0)` (`L = a + b`), and a centre at `h` above the
        /// in-plane point `(x, y ρ L)`, turned by the unit quaternion `rot`
        /// and moved by `shift`: the sweep's sliver, rounded once.
        #[derive(Debug)]
        struct Sliver {
            rho: f64,
            a: f64,
            b: f64,
            alpha: f64,
            x: f64,
            y: f64,
            h: f64,
            rot: [f64; 4],
            shift: P3,
        }

        impl Sliver {
            fn scene(&self) -> (P3, [P3; 3]) {
                let l = self.a + self.b;
                let n = self.rot.iter().map(|x| x * x).sum::<f64>().sqrt();
                let [w, x, y, z] = self.rot.map(|c| c / n);
                let turn = |p: P3| -> P3 {
                    let r = [
                        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
                        [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
                        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
                    ];
                    [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + self.shift[i])
                };
                let tri = [[-self.a, 0.0, 0.0], [self.b, 0.0, 0.0], [-self.a + self.alpha * l, self.rho * l, 0.0]];
                (turn([self.x, self.y * self.rho * l, self.h]), tri.map(turn))
            }

            /// The case, its sphere sunk a quarter of the exact distance.
            fn check<T: Real>(&self) -> Result<(), String> {
                let (m, v) = self.scene();
                let to = |p: &P3| p.map(|x| T::of(x).wide());
                let (mt, vt) = (to(&m), v.map(|p| to(&p)));
                let (q, _) = exact_closest(&mt, &vt);
                let dist = (0..3).map(|i| (mt[i] - q[i]).powi(2)).sum::<f64>().sqrt();
                check::<T>(&mt, dist * 1.25, &vt)
            }
        }

        fn listed_rotated_slivers<T: Real>() {
            // Heights from 1e-15 (below the rounding of a rotated pose: the
            // triangle is whatever the rounding made it) to 1e-6, the centre
            // over the inside (x in the base, y a fraction of the height), just
            // beyond the apex's side, and beyond the base's end.
            let rot = [0.8, -0.3, 0.45, 0.25];
            let shift = [0.3, -1.7, 0.9];
            for rho in [1e-15, 1e-13, 1e-11, 1e-9, 1e-8, 1e-6] {
                for (x, y, h) in [(0.1, 0.3, 0.9), (-0.6, 0.5, 0.6), (0.4, 1.5, 1.2), (2.3, 0.0, 0.7)] {
                    let s = Sliver { rho, a: 1.3, b: 1.6, alpha: 0.4, x, y, h, rot, shift };
                    s.check::<T>().unwrap();
                }
            }
        }
        both!(rotated_slivers, listed_rotated_slivers);

        fn sliver() -> impl Strategy<Value = Sliver> {
            (
                (-15.0..0.0f64, 1.0..2.0f64, 1.0..2.0f64, 0.15..0.85f64),
                (-2.5..2.5f64, -0.5..1.5f64, 0.3..1.5f64),
                ([-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64], [-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64]),
            )
                .prop_filter("a rotation", |(_, _, (rot, _))| rot.iter().map(|x| x * x).sum::<f64>() > 0.01)
                .prop_map(|((k, a, b, alpha), (x, y, h), (rot, shift))| Sliver {
                    rho: 10f64.powf(k),
                    a,
                    b,
                    alpha,
                    x,
                    y,
                    h,
                    rot,
                    shift,
                })
        }

        fn agrees_with_the_exact_closest_point<T: Real>(s: &Sliver) -> Result<(), TestCaseError> {
            s.check::<T>().map_err(TestCaseError::fail)
        }
        prop_both!(512, random_rotated_slivers, sliver(), agrees_with_the_exact_closest_point);

        /// Deep face contacts: a well-shaped triangle, the centre over its
        /// inside at `10^k` (`k` from −14 to −2) above the plane, and a sphere
        /// of radius 0.5 to 3 — the distance far below the radius, where the
        /// face filter holds the distance to `2^−40` of the radius rather than
        /// of itself. Point, depth and normal agree with the exact answer.
        fn deep() -> impl Strategy<Value = (Sliver, f64)> {
            (
                (0.2..1.0f64, 0.15..0.85f64, -0.8..1.2f64, 0.1..0.5f64, -14.0..-2.0f64, 0.5..3.0f64),
                ([-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64], [-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64]),
            )
                .prop_filter("a rotation", |(_, (rot, _))| rot.iter().map(|x| x * x).sum::<f64>() > 0.01)
                .prop_map(|((rho, alpha, x, y, k, r), (rot, shift))| {
                    (Sliver { rho, a: 1.3, b: 1.6, alpha, x, y, h: 10f64.powf(k), rot, shift }, r)
                })
        }

        fn deep_contacts_agree<T: Real>(case: &(Sliver, f64)) -> Result<(), TestCaseError> {
            let (s, r) = case;
            let (m, v) = s.scene();
            let to = |p: &P3| p.map(|x| T::of(x).wide());
            check::<T>(&to(&m), *r, &v.map(|p| to(&p))).map_err(TestCaseError::fail)
        }
        prop_both!(512, deep_face_contacts, deep(), deep_contacts_agree);

        /// Depth of a face contact against the exact distance to the plane,
        /// relative to the radius: the face filter promises the distance to
        /// `2 · 2^−40` of the larger of itself and `r` (two `FACE_REL`, from
        /// the volume and from `‖n‖`), and `r − d` adds a rounding of `r`;
        /// `4 · 2^−40` leaves room. An `f32` answer is the `f64` one rounded
        /// once: `16 ε_f32` of `r`.
        const DEPTH_OF_RADIUS: f64 = 4.0 * FACE_REL;

        /// Small spheres sunk deep into a well-shaped triangle: radius `10^k`
        /// (`k` from −12 to −4) of a scene of size about 3, the centre `10^j`
        /// of the radius above a point inside (`j` from −6 to −1). The plain
        /// formula's rounding (about `u` of the scene) is far above `2^−40` of
        /// such a radius, so the face filter must send these on to the
        /// compensated stage: a depth accurate to the scene only would fail.
        fn small_and_deep() -> impl Strategy<Value = (Sliver, f64)> {
            (
                (0.2..1.0f64, 0.15..0.85f64, 0.1..0.45f64, 0.1..0.45f64, -12.0..-4.0f64, -6.0..-1.0f64),
                ([-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64], [-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64]),
            )
                .prop_filter("a rotation", |(_, (rot, _))| rot.iter().map(|x| x * x).sum::<f64>() > 0.01)
                .prop_map(|((rho, alpha, u, w, k, j), (rot, shift))| {
                    // The projection `v0 + u (v1 − v0) + w (v2 − v0)`, inside.
                    let (a, b) = (1.3, 1.6);
                    let (x, y) = (-a + (u + w * alpha) * (a + b), w);
                    let r = 10f64.powf(k);
                    (Sliver { rho, a, b, alpha, x, y, h: r * 10f64.powf(j), rot, shift }, r)
                })
        }

        fn small_deep_depth_holds<T: Real>(case: &(Sliver, f64)) -> Result<(), TestCaseError> {
            let (s, r) = case;
            let (m, v) = s.scene();
            let to = |p: &P3| p.map(|x| T::of(x).wide());
            let (mt, vt) = (to(&m), v.map(|p| to(&p)));
            let (mb, vb) = (big(&mt), vt.map(|x| big(&x)));
            let n = cross(&sub(&vb[1], &vb[0]), &sub(&vb[2], &vb[0]));
            let vol = dot(&n, &sub(&mb, &vb[0]));
            let d = ratio(&(&vol * &vol), &dot(&n, &n)).sqrt();
            let radius = T::of(*r);
            let want = radius.wide() - d;
            let tol = (16.0 * eps::<T>()).max(DEPTH_OF_RADIUS) * radius.wide();
            let tri =
                Triangle::new(Vec3::from(vt[0].map(T::of)), Vec3::from(vt[1].map(T::of)), Vec3::from(vt[2].map(T::of)));
            let k = contact_sphere_triangle(&Sphere::new(Vec3::from(mt.map(T::of)), radius), &tri);
            // Rounded to `f32`, the centre may land above the sphere's reach:
            // then "apart" is the answer, and within the tolerance either is.
            let got = k.map(|k| k.depth.wide());
            let right = match got {
                Some(g) => (g - want).abs() <= tol,
                None => want <= tol,
            };
            prop_assert!(right, "depth {got:?}, exact {want:e} (r {r:e}, d {d:e}), tolerance {tol:e}");
            Ok(())
        }
        prop_both!(256, small_deep_face_contacts, small_and_deep(), small_deep_depth_holds);
    }

    /// Small spheres beside huge (and tiny) triangles.
    mod huge_triangles {
        use super::super::*;
        use crate::test_support::{both, eps, prop_both};
        use proptest::prelude::*;

        /// A small sphere beside a huge triangle: a right triangle with its
        /// corner `V` and legs of length `L` along two coordinate axes (so its
        /// edges from `V` stay exactly on the axis lines however `V + L`
        /// rounds), its vertices listed in any rotation, a sphere of radius
        /// `r` centred at `V + o` (`V`, `o` on a grid of `2^−20`, `|V| ≤ 8`,
        /// `|o| ≤ 6`, all scaled by `2^j`, `j` from −100 to 0 in `f64`, −20
        /// to 0 in `f32`): the exact closest point is
        /// `V + (max(o_1, 0), max(o_2, 0), 0)` in the legs' frame, for
        /// `L` far above `|o|`.
        #[derive(Clone, Debug)]
        struct Beside {
            corner: [i32; 3],
            offset: [i32; 3],
            /// Decimal exponent of `L`, a fraction of the type's range.
            legs: f64,
            /// Which axes the legs run along (the third is the normal's) and their signs.
            axes: usize,
            signs: [bool; 3],
            rotation: usize,
            radius: f64,
            /// Power-of-two scale of the whole scene, a fraction of the type's range.
            scale: f64,
        }

        /// Tolerance of the huge-triangle family, relative to the local scale
        /// (the largest of `r`, `|o|`, `|V|` and 1 grid step, times `2^j`):
        /// the face region's normal and distance are held to `FACE_REL = 2^−40`
        /// of `r`, the edge and vertex points to a few ulps; `8 FACE_REL`
        /// covers both with room. An `f32` answer is the `f64` one rounded once:
        /// `16 ε_f32`.
        const BESIDE_REL: f64 = 8.0 * FACE_REL;

        impl Beside {
            /// The scene in `T` (exact: grid values times powers of two) and
            /// the exact closest point, all as `f64`.
            fn scene<T: Real>(&self) -> ([f64; 3], f64, [[f64; 3]; 3], [f64; 3], f64) {
                let f64_type = eps::<T>() < 1e-10;
                let (top, low) = if f64_type { (300.0, -100) } else { (36.0, -20) };
                let s = 2f64.powi((self.scale * f64::from(low)) as i32);
                let grid = 2f64.powi(-20) * s;
                let l = T::of(10f64.powf(2.0 + self.legs * (top - 2.0)) * s).wide();
                let (i, j, k) = [(0, 1, 2), (1, 2, 0), (2, 0, 1)][self.axes % 3];
                let sign = |b: bool| if b { 1.0 } else { -1.0 };
                let v = self.corner.map(|c| f64::from(c) * grid);
                let o = self.offset.map(|c| f64::from(c) * grid);
                let m = [0, 1, 2].map(|d| v[d] + o[d]);
                let mut b = v;
                b[i] += sign(self.signs[0]) * l;
                let mut c = v;
                c[j] += sign(self.signs[1]) * l;
                let tri = [v, b, c];
                let r = self.rotation % 3;
                let tri = [tri[r], tri[(r + 1) % 3], tri[(r + 2) % 3]];
                let mut q = v;
                q[i] += if o[i] * sign(self.signs[0]) > 0.0 { o[i] } else { 0.0 };
                q[j] += if o[j] * sign(self.signs[1]) > 0.0 { o[j] } else { 0.0 };
                let _ = k;
                let local = [v, o].as_flattened().iter().fold(self.radius.max(1.0), |x, y| x.max(y.abs() / s)) * s;
                (m, self.radius * s, tri, q, local)
            }
        }

        fn beside() -> impl Strategy<Value = Beside> {
            let c = |k: i32| [-k..=k, -k..=k, -k..=k];
            (c(8 << 20), c(6 << 20), 0.0..=1.0f64, 0..3usize, [any::<bool>(), any::<bool>(), any::<bool>()], 0..3usize)
                .prop_flat_map(|(corner, offset, legs, axes, signs, rotation)| {
                    (0.5..8.0f64, 0.0..=1.0f64).prop_map(move |(radius, scale)| Beside {
                        corner,
                        offset,
                        legs,
                        axes,
                        signs,
                        rotation,
                        radius,
                        scale,
                    })
                })
        }

        /// The contact of a small sphere beside a huge triangle: whenever the
        /// exact distance is below `r`, a contact, finite, whose point is the
        /// exact closest point, whose depth is `r − ‖M − q‖` and whose normal is
        /// `(M − q)/‖M − q‖`, all within [`BESIDE_REL`] of the local scale
        /// (never of the triangle's).
        fn beside_agrees<T: Real>(case: &Beside) -> Result<(), TestCaseError> {
            let (m, r, tri, q, local) = case.scene::<T>();
            let to = |p: &[f64; 3]| Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]));
            let delta = [0, 1, 2].map(|d| m[d] - q[d]);
            let dist = delta.iter().map(|x| (x / local).powi(2)).sum::<f64>().sqrt() * local;
            prop_assume!(dist < r * (1.0 - 1e-6) && dist > r * 1e-6);
            let k = contact_sphere_triangle(
                &Sphere::new(to(&m), T::of(r)),
                &Triangle::new(to(&tri[0]), to(&tri[1]), to(&tri[2])),
            );
            let tol = (16.0 * eps::<T>()).max(BESIDE_REL) * local;
            let what = format!("{case:?}: exact point {q:?}, distance {dist:e}, r {r:e}");
            let Some(k) = k else {
                return Err(TestCaseError::fail(format!("no contact: {what}")));
            };
            let p = [k.point.x.wide(), k.point.y.wide(), k.point.z.wide()];
            let off = (0..3).map(|d| (p[d] - q[d]).abs()).fold(0.0, f64::max);
            let n = [k.normal.x.wide(), k.normal.y.wide(), k.normal.z.wide()];
            let n_off = (0..3).map(|d| (n[d] - delta[d] / dist).abs()).fold(0.0, f64::max);
            let depth_off = (k.depth.wide() - (r - dist)).abs();
            prop_assert!(
                off <= tol && depth_off <= tol && n_off <= tol / dist,
                "{k:?}: point off {off:e}, depth {depth_off:e}, normal {n_off:e} (tol {tol:e}): {what}"
            );
            Ok(())
        }
        prop_both!(256, small_sphere_beside_a_huge_triangle, beside(), beside_agrees);

        /// The user's reproducer: `r = 4` at `(3.5, 2.25, 1)` over the triangle
        /// `(0,0,0), (L,0,0), (0,L,0)`: the exact contact is the face's, point
        /// `(3.5, 2.25, 0)`, normal `+z`, depth 3, for every `L` above the
        /// sphere's reach. From `L = 1e15` the barycentric stage could not
        /// certify the face and the edge point `(3.5, 0, 0)` was taken (normal
        /// 0.79 rad off); at `1e300` the answer was "apart". The vertices in
        /// each rotation (the corner first, second, third), and beside an edge:
        /// the centre at `(3.5, −2, 1)` touches the edge `y = 0` at `(3.5, 0, 0)`,
        /// distance √5.
        fn huge_triangle_reproducer<T: Real>() {
            let tops: &[f64] =
                if eps::<T>() < 1e-10 { &[1e15, 1e16, 1e20, 1e100, 1e300] } else { &[1e8, 1e15, 1e30, 1e38] };
            for &l in tops {
                let corners = [[0.0, 0.0, 0.0], [l, 0.0, 0.0], [0.0, l, 0.0]];
                for rot in 0..3 {
                    let v = |i: usize| {
                        let p = corners[(rot + i) % 3];
                        Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]))
                    };
                    let tri = Triangle::new(v(0), v(1), v(2));
                    let tol = (16.0 * eps::<T>()).max(BESIDE_REL) * 4.0;
                    for (m, q, depth) in [
                        ([3.5, 2.25, 1.0], [3.5, 2.25, 0.0], 3.0),
                        ([3.5, -2.0, 1.0], [3.5, 0.0, 0.0], 4.0 - 5f64.sqrt()),
                    ] {
                        let centre = Vec3::new(T::of(m[0]), T::of(m[1]), T::of(m[2]));
                        let k = contact_sphere_triangle(&Sphere::new(centre, T::of(4.0)), &tri)
                            .unwrap_or_else(|| panic!("L {l:e}, rotation {rot}: no contact"));
                        let d = (m[1] - q[1]).hypot(m[2] - q[2]);
                        let p = [k.point.x.wide(), k.point.y.wide(), k.point.z.wide()];
                        let n = [k.normal.x.wide(), k.normal.y.wide(), k.normal.z.wide()];
                        let ok = (0..3).all(|i| (p[i] - q[i]).abs() <= tol && (n[i] - (m[i] - q[i]) / d).abs() <= tol)
                            && (k.depth.wide() - depth).abs() <= tol;
                        assert!(ok, "L {l:e}, rotation {rot}, centre {m:?}: {k:?}, want point {q:?}, depth {depth}");
                    }
                }
            }
        }
        both!(small_sphere_beside_huge_triangles, huge_triangle_reproducer);
    }

    /// Stage 1 of `certified_region` settles ordinary queries: random
    /// triangles in a box of size 6 and spheres around them (the report's
    /// random contact cases are of that kind) go to the barycentric stage
    /// less than once in a thousand (its cost stays off the fast path).
    #[test]
    fn the_book_edge_tests_settle_ordinary_queries() {
        use proptest::strategy::{Strategy, ValueTree};
        use proptest::test_runner::TestRunner;
        let coord = || -3.0..3.0f64;
        let point = || [coord(), coord(), coord()];
        let strategy = (point(), [point(), point(), point()], 0.1..3.0f64);
        let mut runner = TestRunner::deterministic();
        let before = STAGE_TWO.with(|n| n.get());
        const QUERIES: u64 = 20_000;
        for _ in 0..QUERIES {
            let (m, v, r) = strategy.new_tree(&mut runner).expect("a case").current();
            let tri = Triangle::new(Vec3::from(v[0]), Vec3::from(v[1]), Vec3::from(v[2]));
            let _ = contact_sphere_triangle(&Sphere::new(Vec3::from(m), r), &tri);
        }
        let stage_two = STAGE_TWO.with(|n| n.get()) - before;
        assert!(stage_two * 1000 < QUERIES, "{stage_two} of {QUERIES} queries needed the barycentric stage");
    }

    /// Stages 2 and 3 of `certified_region` give the exact signs of the
    /// book's edge tests or decline: centres whose projections approach an
    /// edge's line from either side at offsets from the triangle's size down
    /// to `1e-40` of it, beside an ordinary triangle and a sliver, at scales
    /// from `1e-3` to `1e12` (coordinates not on a grid, so the compensated
    /// arithmetic is not exact), and beside a triangle with legs of `2.6e15`
    /// (multi-scale: the centre's own ulps are far finer than the
    /// triangle's). Each stage must decide some of them (it is
    /// not dead code) and decline some (the next stage answers those), and
    /// every stage that answers, and `exact_region` itself, must agree with
    /// the signs in exact arithmetic.
    #[test]
    fn the_filtered_edge_signs_are_exact_or_decline() {
        use crate::exact::Sign;
        let (mut decided, mut declined) = ([0u32; 2], [0u32; 2]);
        let at = |p: [f64; 3], s: f64| Vec3::new(p[0] * s, p[1] * s, p[2] * s);
        for (scale, height) in [(1.0, 0.7), (1e-3, 1e-9), (1e12, 0.3), (3.0, 1e-13)] {
            let a = at([0.1, 0.2, 0.3], scale);
            let (ab, ac) = (at([1.3, 0.1, -0.2], scale), at([0.4, height, 0.1], scale));
            let tri = Triangle::new(a, a + ab, a + ac);
            let foot = a + ab * 0.37;
            // Off the plane along its normal: the projection stays at the
            // foot, up to the rounding of the sum.
            let normal = ab.cross(&ac);
            let lift = normal * (0.25 * scale / normal.norm());
            for k in 0..=40 {
                for side in [1.0, -1.0] {
                    let offset = side * 10f64.powi(-k);
                    let centre = foot + ac * offset + lift;
                    let exact = exact_edge_tests(&centre, &tri).map(|s| s == Sign::Positive);
                    for (i, got) in
                        [projection_signs(&centre, &tri), compensated_edge_tests(&centre, &tri)].into_iter().enumerate()
                    {
                        match got {
                            Some(signs) => {
                                assert_eq!(signs, exact, "stage {} at 1e-{k} of {scale:e}", i + 2);
                                decided[i] += 1;
                            }
                            None => declined[i] += 1,
                        }
                    }
                    let want = if exact == [true; 3] {
                        Certified::Face
                    } else {
                        Certified::Edges([!exact[2], !exact[0], !exact[1]])
                    };
                    assert_eq!(exact_region(&centre, &tri), want, "at 1e-{k} of {scale:e}");
                }
            }
        }
        // Multi-scale: legs of about 2.6e15, not on a grid, with the edge
        // `ab` through the origin (`a = −b`), and centres near the origin
        // at `1` down to `1e-40` (their coordinates' own ulps are that fine).
        let b = v(1.2345678901234567e15, 3.333_333_333_333_334e14, 7.777777777777777e13);
        let tri = Triangle::<f64>::new(-b, b, v(-4.444444444444444e14, 1.9191919191919192e15, -2.2e14));
        for k in 0..=40 {
            for side in [1.0, -1.0] {
                let centre = v(0.3, -0.7, 0.5) * (side * 10f64.powi(-k));
                let exact = exact_edge_tests(&centre, &tri).map(|s| s == Sign::Positive);
                for (i, got) in
                    [projection_signs(&centre, &tri), compensated_edge_tests(&centre, &tri)].into_iter().enumerate()
                {
                    match got {
                        Some(signs) => {
                            assert_eq!(signs, exact, "stage {} at 1e-{k} beside legs of 2.6e15", i + 2);
                            decided[i] += 1;
                        }
                        None => declined[i] += 1,
                    }
                }
            }
        }
        for i in 0..2 {
            assert!(
                decided[i] > 0 && declined[i] > 0,
                "stage {}: {} decided, {} declined",
                i + 2,
                decided[i],
                declined[i]
            );
        }
    }

    /// The compensated edge tests decide exact zeros: a centre whose
    /// projection lies exactly on an edge's line (grid coordinates, where
    /// every operation is exact) is answered without the exact arithmetic,
    /// as on the edge (not strictly inside it).
    #[test]
    fn the_compensated_edge_tests_decide_exact_zeros() {
        let tri = Triangle::<f64>::new(v(0.25, -1.5, 2.0), v(3.75, -1.5, 2.0), v(0.25, 2.5, 2.0));
        // Above the edge from (0.25, -1.5) to (3.75, -1.5): y = -1.5 exactly.
        let centre = v(1.125, -1.5, 2.75);
        assert_eq!(compensated_edge_tests(&centre, &tri), Some([true, true, false]));
        assert_eq!(projection_signs(&centre, &tri), None, "the barycentric stage cannot tell a zero");
    }

    /// [`FRAME_EDGE_TEST_BOUND`] holds: the book's edge tests computed in
    /// the centre's frame are within it of the exact tests on the input.
    mod frame_bound {
        use super::super::*;
        use crate::exact::{BigFloat, Sign};
        use proptest::prelude::*;

        type P3 = [f64; 3];

        /// Coordinates over many binades, near-coincident ones (so that
        /// differences cancel) and sliver-like ones.
        fn coord() -> impl Strategy<Value = f64> {
            prop_oneof![
                -4.0..4.0f64,
                (-1.0..1.0f64, -40i32..40).prop_map(|(m, e)| m * 2f64.powi(e)),
                (-1.0..1.0f64).prop_map(|x| 1.0 + x * 1e-15),
                Just(0.0),
            ]
        }

        fn point() -> impl Strategy<Value = P3> {
            [coord(), coord(), coord()]
        }

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(1000))]

            #[test]
            fn the_book_edge_tests_are_within_the_frame_bound(m in point(), a in point(), b in point(), c in point()) {
                let local = Triangle::new(
                    Vec3::from(a) - Vec3::from(m),
                    Vec3::from(b) - Vec3::from(m),
                    Vec3::from(c) - Vec3::from(m),
                );
                prop_assume!(local.vertices.iter().all(crate::real::finite3));
                let found = closest_pt_point_triangle_region_with_area(&Vec3::zeros(), &local);
                let Some(bound) = frame_edge_test_bound(&found) else {
                    return Ok(());
                };
                let big = |p: &P3| p.map(BigFloat::from_f64);
                let sub = |x: &[BigFloat; 3], y: &[BigFloat; 3]| [0, 1, 2].map(|i| &x[i] - &y[i]);
                let cross = |x: &[BigFloat; 3], y: &[BigFloat; 3]| {
                    [0, 1, 2].map(|i| {
                        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                        &(&x[j] * &y[k]) - &(&x[k] * &y[j])
                    })
                };
                let dot = |x: &[BigFloat; 3], y: &[BigFloat; 3]| {
                    &(&(&x[0] * &y[0]) + &(&x[1] * &y[1])) + &(&x[2] * &y[2])
                };
                let (mb, v) = (big(&m), [big(&a), big(&b), big(&c)]);
                let n = cross(&sub(&v[1], &v[0]), &sub(&v[2], &v[0]));
                let rel = v.each_ref().map(|x| sub(x, &mb));
                for (i, got) in found.edge_tests.iter().enumerate() {
                    // va, vb, vc: n · ((b − M) × (c − M)) and cyclically.
                    let exact = dot(&n, &cross(&rel[(i + 1) % 3], &rel[(i + 2) % 3]));
                    let err = &exact - &BigFloat::from_f64(*got);
                    let bound = BigFloat::from_f64(bound);
                    prop_assert!(
                        (&bound - &err).sign() != Sign::Negative && (&bound + &err).sign() != Sign::Negative,
                        "test {i}: {got:e} against {:e}, bound {:e}", exact.to_f64(), bound.to_f64()
                    );
                }
            }
        }
    }
}
