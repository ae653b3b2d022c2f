//! The benchmark's cases: drawn once, from a fixed seed, by the campaign's own
//! generators (`harness::generate`), so the mix of hits and misses, of uniform
//! and failure-biased families, is the campaign's. Every engine runs the same
//! cases; each engine's inputs are converted to its own types here, before any
//! timing starts.

use super::families::NO_FAMILY;
use harness::case::{Query, Shape};
use harness::generate::{family_for, generate};
use oracle::geom;

/// Seed of the benchmark's cases (fixed: every run times the same cases).
pub const SEED: u64 = 0x0C0F_FEE5;

/// Cases per query kind. Enough to cover every family several times over and
/// to defeat the branch predictor's memory of a short loop; few enough that
/// each engine's inputs stay in L2 (1024 sphere pairs are 64 KiB).
pub const PER_QUERY: usize = 1024;

/// Indices tried per query before giving up on filling [`PER_QUERY`] (the
/// rarest pair, a family among many, is about one index in 16).
const MAX_INDICES: u64 = 200_000;

/// The campaign's family of uniform segment–triangle cases: the "random cases"
/// of the exact-vs-lecture target.
pub const UNIFORM_SEGMENT_TRIANGLE: &str = "uniform segment–triangle";

/// Every case set, in the neutral `f64` vocabulary.
pub struct Cases {
    /// Sphere–sphere contact.
    pub sphere_sphere: Vec<(geom::Sphere, geom::Sphere)>,
    /// Sphere–plane contact (plane–sphere cases turned around).
    pub sphere_plane: Vec<(geom::Sphere, geom::Plane)>,
    /// Sphere–triangle contact (triangle–sphere cases turned around).
    pub sphere_triangle: Vec<(geom::Sphere, geom::Triangle)>,
    /// Segment–plane.
    pub segment_plane: Vec<(geom::Segment, geom::Plane)>,
    /// Segment–triangle, the campaign's mix.
    pub segment_triangle: Vec<(geom::Segment, geom::Triangle)>,
    /// Segment–triangle, the uniform family only.
    pub segment_triangle_uniform: Vec<(geom::Segment, geom::Triangle)>,
    /// Barycentric coordinates of a point in a triangle.
    pub barycentric: Vec<(geom::P3, geom::Triangle)>,
    /// AABB overlap.
    pub overlap: Vec<(geom::Aabb, geom::Aabb)>,
    /// Point clouds (bounding sphere).
    pub clouds: Vec<Vec<geom::P3>>,
    /// The campaign family each case of the four queries whose targets
    /// depend most on the mix was drawn from, case by case.
    pub families: Families,
}

/// The campaign family of each case (`harness::generate::family_for`), in
/// the order of the case sets, for the by-family table.
pub struct Families {
    /// Of [`Cases::sphere_triangle`].
    pub sphere_triangle: Vec<&'static str>,
    /// Of [`Cases::segment_plane`].
    pub segment_plane: Vec<&'static str>,
    /// Of [`Cases::segment_triangle`].
    pub segment_triangle: Vec<&'static str>,
    /// Of [`Cases::barycentric`].
    pub barycentric: Vec<&'static str>,
}

fn sphere(s: &Shape) -> Option<geom::Sphere> {
    match s {
        Shape::Sphere(s) => Some(geom::Sphere { center: s.center, radius: s.radius }),
        _ => None,
    }
}

fn plane(s: &Shape) -> Option<geom::Plane> {
    match s {
        Shape::Plane(p) => Some(geom::Plane { normal: p.normal, offset: p.offset }),
        _ => None,
    }
}

fn triangle(s: &Shape) -> Option<geom::Triangle> {
    match s {
        Shape::Triangle(t) => Some(geom::Triangle { vertices: t.vertices }),
        _ => None,
    }
}

fn segment(s: &Shape) -> Option<geom::Segment> {
    match s {
        Shape::Segment(s) => Some(geom::Segment { start: s.start, end: s.end }),
        _ => None,
    }
}

fn aabb(s: &Shape) -> Option<geom::Aabb> {
    match s {
        Shape::Aabb(b) => Some(geom::Aabb { min: b.min, max: b.max }),
        _ => None,
    }
}

/// Draws cases of `query` from index 0 on, keeping those `keep` accepts, until
/// `PER_QUERY` are kept (or [`MAX_INDICES`] were tried); with each kept
/// case's family.
fn draw_with_families<T>(
    query: Query,
    mut keep: impl FnMut(u64, &Shape, Option<&Shape>) -> Option<T>,
) -> (Vec<T>, Vec<&'static str>) {
    let (mut out, mut families) = (Vec::with_capacity(PER_QUERY), Vec::with_capacity(PER_QUERY));
    for index in 0..MAX_INDICES {
        if out.len() == PER_QUERY {
            break;
        }
        let lc = generate(query, SEED, index);
        if let Some(x) = keep(index, &lc.case.a, lc.case.b.as_ref()) {
            out.push(x);
            families.push(family_for(query, index).unwrap_or(NO_FAMILY));
        }
    }
    assert!(out.len() == PER_QUERY, "only {} {query} cases in {MAX_INDICES} indices", out.len());
    (out, families)
}

/// [`draw_with_families`] without the families.
fn draw<T>(query: Query, keep: impl FnMut(u64, &Shape, Option<&Shape>) -> Option<T>) -> Vec<T> {
    draw_with_families(query, keep).0
}

/// The pair `(x, y)` of the kinds asked for, in either order.
fn either<X, Y>(
    a: &Shape,
    b: Option<&Shape>,
    fx: fn(&Shape) -> Option<X>,
    fy: fn(&Shape) -> Option<Y>,
) -> Option<(X, Y)> {
    let b = b?;
    match (fx(a), fy(b)) {
        (Some(x), Some(y)) => Some((x, y)),
        _ => Some((fx(b)?, fy(a)?)),
    }
}

impl Cases {
    /// Draws every set (about a second: the generators are proptest strategies).
    pub fn draw() -> Self {
        let seg_tri = |_: u64, a: &Shape, b: Option<&Shape>| either(a, b, segment, triangle);
        let (sphere_triangle, sphere_triangle_families) =
            draw_with_families(Query::Contact, |_, a, b| either(a, b, sphere, triangle));
        let (segment_plane, segment_plane_families) =
            draw_with_families(Query::Intersect, |_, a, b| either(a, b, segment, plane));
        let (segment_triangle, segment_triangle_families) = draw_with_families(Query::Intersect, seg_tri);
        let (barycentric, barycentric_families) = draw_with_families(Query::Barycentric, |_, a, b| {
            let point = |s: &Shape| match s {
                Shape::Point(p) => Some(p.at),
                _ => None,
            };
            either(a, b, point, triangle)
        });
        Self {
            sphere_sphere: draw(Query::Contact, |_, a, b| Some((sphere(a)?, sphere(b?)?))),
            sphere_plane: draw(Query::Contact, |_, a, b| either(a, b, sphere, plane)),
            sphere_triangle,
            segment_plane,
            segment_triangle,
            segment_triangle_uniform: draw(Query::Intersect, |i, a, b| {
                (family_for(Query::Intersect, i) == Some(UNIFORM_SEGMENT_TRIANGLE)).then(|| seg_tri(i, a, b)).flatten()
            }),
            barycentric,
            overlap: draw(Query::Overlap, |_, a, b| Some((aabb(a)?, aabb(b?)?))),
            clouds: draw(Query::Bounds, |_, a, _| match a {
                Shape::Points(p) => Some(p.points.clone()),
                _ => None,
            }),
            families: Families {
                sphere_triangle: sphere_triangle_families,
                segment_plane: segment_plane_families,
                segment_triangle: segment_triangle_families,
                barycentric: barycentric_families,
            },
        }
    }
}

/// collide's shapes from the neutral ones, in precision `T` (rounded once).
pub mod to_collide {
    use collide::{Aabb, Plane, Real, Segment, Sphere, Triangle, Vec3};
    use oracle::geom;

    /// A point in `T`.
    pub fn v<T: Real>(p: geom::P3) -> Vec3<T> {
        Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]))
    }
    /// A sphere in `T`.
    pub fn sphere<T: Real>(s: &geom::Sphere) -> Sphere<T> {
        Sphere::new(v(s.center), T::of(s.radius))
    }
    /// A plane in `T`.
    pub fn plane<T: Real>(p: &geom::Plane) -> Plane<T> {
        Plane::new(v(p.normal), T::of(p.offset))
    }
    /// A segment in `T`.
    pub fn segment<T: Real>(s: &geom::Segment) -> Segment<T> {
        Segment::new(v(s.start), v(s.end))
    }
    /// A triangle in `T`.
    pub fn triangle<T: Real>(t: &geom::Triangle) -> Triangle<T> {
        let [a, b, c] = t.vertices;
        Triangle::new(v(a), v(b), v(c))
    }
    /// A box in `T`.
    pub fn aabb<T: Real>(b: &geom::Aabb) -> Aabb<T> {
        Aabb::new(v(b.min), v(b.max))
    }
}
