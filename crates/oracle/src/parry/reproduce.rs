//! Standalone reproductions for parry: a short Rust program, against the
//! pinned parry version alone, that builds one case's shapes exactly as the
//! adapter does (`engine.rs`: a ball at the translation of its centre, the
//! plane `n · x = d` as `HalfSpace::new(n̂)` at the translation `(d/‖n‖) n̂`, a
//! triangle at the identity, a segment as the ray `start + t (end − start)`
//! with a maximal time of 1), asks parry the same query, prints its answer,
//! and asserts the exact answer in parry's own convention: `dist = −depth`,
//! `normal1 = −normal` (parry's points from shape 1 to shape 2), `point2` the
//! point on shape 2. So the program panics exactly while parry's answer stays
//! outside the allowances crashtest judged it by — a bug report's test.
//!
//! A mesh is parry's `TriMesh` of the case's vertices and faces at the
//! identity; barycentric coordinates are `TrianglePointLocation`'s of the
//! point's projection (`project_local_point_and_get_location`); a bounding
//! sphere is `point_cloud_bounding_sphere`'s, asserted to enclose every point.

use crashtest_core::geom::{Aabb, Contact, P3, Plane, Segment, SegmentHit, Sphere, Toi, Triangle};

/// One shape of a reproduction.
#[derive(Clone, Debug)]
pub enum Shape {
    /// A ball.
    Sphere(Sphere),
    /// A half-space.
    Plane(Plane),
    /// A triangle.
    Triangle(Triangle),
    /// A triangle mesh: vertices and faces (0-based).
    Mesh(Vec<P3>, Vec<[usize; 3]>),
}

/// What the exact answer allows, from crashtest's judgement of the case.
#[derive(Clone, Copy, Debug)]
pub struct Allowed {
    /// A point's largest coordinate error.
    pub point: f64,
    /// The depth's (a length).
    pub depth: f64,
    /// The normal's angle, radians.
    pub normal: f64,
    /// A segment parameter's.
    pub t: f64,
    /// Each barycentric coordinate's.
    pub barycentric: f64,
}

/// A number as Rust source: the shortest decimal that reads back to it, with
/// a decimal point.
fn lit(x: f64) -> String {
    let s = format!("{x:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") { s } else { format!("{s}.0") }
}

fn vec3(p: &[f64; 3]) -> String {
    format!("Vector::new({}, {}, {})", lit(p[0]), lit(p[1]), lit(p[2]))
}

/// The lines that build shape `k` (1 or 2) as `pos{k}`, `shape{k}`.
fn build(s: &Shape, k: u8) -> Vec<String> {
    match s {
        Shape::Sphere(b) => vec![format!(
            "let (pos{k}, shape{k}) = (Pose::from_translation({}), Ball::new({}));",
            vec3(&b.center),
            lit(b.radius)
        )],
        Shape::Plane(p) => vec![
            format!("let n{k} = {};", vec3(&p.normal)),
            format!(
                "let (pos{k}, shape{k}) = (Pose::from_translation(n{k}.normalize() * ({} / n{k}.length())), \
                 HalfSpace::new(n{k}.normalize()));",
                lit(p.offset)
            ),
        ],
        Shape::Triangle(t) => vec![format!(
            "let (pos{k}, shape{k}) = (Pose::IDENTITY, Triangle::new({}, {}, {}));",
            vec3(&t.vertices[0]),
            vec3(&t.vertices[1]),
            vec3(&t.vertices[2])
        )],
        Shape::Mesh(vertices, faces) => vec![
            format!("let vertices{k} = vec![{}];", vertices.iter().map(vec3).collect::<Vec<_>>().join(", ")),
            format!(
                "let faces{k} = vec![{}];",
                faces.iter().map(|f| format!("[{}, {}, {}]", f[0], f[1], f[2])).collect::<Vec<_>>().join(", ")
            ),
            format!("let (pos{k}, shape{k}) = (Pose::IDENTITY, TriMesh::new(vertices{k}, faces{k}).unwrap());"),
        ],
    }
}

/// The program's first lines: what it is, its imports (`uses`, paths below
/// the crate), `fn main`.
fn header(krate: &str, version: &str, what: &str, uses: &[&str]) -> Vec<String> {
    let m = krate.replace('-', "_");
    let mut l =
        vec![format!("// {krate} ={version}: {what} (a crashtest finding; the exact answer is correctly rounded).")];
    l.extend(uses.iter().map(|u| format!("use {m}::{u};")));
    l.push("fn main() {".into());
    l
}

/// The imports of a program over shapes.
const SHAPE_USES: [&str; 2] = ["math::{Pose, Vector}", "{query, shape::*}"];

/// The program for a contact between `a` (shape 1) and `b` (shape 2), the
/// exact contact `exact` (crashtest's convention) or none.
pub fn contact(krate: &str, version: &str, a: &Shape, b: &Shape, exact: Option<&Contact>, allow: &Allowed) -> String {
    let mut l = header(krate, version, "contact", &SHAPE_USES);
    l.extend(build(a, 1));
    l.extend(build(b, 2));
    l.push("let c = query::contact(&pos1, &shape1, &pos2, &shape2, 0.0).unwrap();".into());
    l.push("println!(\"{c:?}\");".into());
    match exact {
        None => l.push("assert!(c.is_none(), \"exact: no contact (the shapes are apart)\");".into()),
        Some(e) => {
            let (dist, normal1) = (0.0 - e.depth, e.normal.map(|x| 0.0 - x));
            l.push(format!("let c = c.expect(\"exact: a contact, dist {}\");", lit(dist)));
            l.push(format!(
                "assert!((c.dist - {}).abs() <= {:e}, \"dist {{}}, exact {}\", c.dist);",
                lit(dist),
                allow.depth,
                lit(dist)
            ));
            l.push(format!(
                "assert!((c.point2 - {}).abs().max_element() <= {:e}, \"point2 {{}}\", c.point2);",
                vec3(&e.point),
                allow.point
            ));
            l.push(format!(
                "assert!(c.normal1.angle_between({}) <= {:e}, \"normal1 {{}}\", c.normal1);",
                vec3(&normal1),
                allow.normal
            ));
        }
    }
    finish(l)
}

/// The program for a segment cast against a plane or a triangle (`b`), the
/// exact first hit `exact` or none.
pub fn intersect(
    krate: &str,
    version: &str,
    s: &Segment,
    b: &Shape,
    exact: Option<&SegmentHit>,
    allow: &Allowed,
) -> String {
    let mut l =
        header(krate, version, "ray cast of a segment", &["math::{Pose, Vector}", "query::{Ray, RayCast}", "shape::*"]);
    l.push(format!("let ray = Ray::new({}, {} - {});", vec3(&s.start), vec3(&s.end), vec3(&s.start)));
    l.extend(build(b, 2));
    l.push("let hit = shape2.cast_ray_and_get_normal(&pos2, &ray, 1.0, false);".into());
    l.push("println!(\"{hit:?}\");".into());
    time_asserted(&mut l, exact.map(|h| h.t), allow.t, "the segment misses", "a hit");
    finish(l)
}

/// The program for a time of impact: the ball `a` moving at `va` against `b`
/// moving at `vb` over `[0, t_max]`, cast with the adapter's options
/// (`cast.rs`: target distance 0, stop at penetration, impact geometry
/// computed), the exact first impact `exact` or none. Only the time is
/// asserted: parry's witnesses and normals are in each shape's local frame.
#[allow(clippy::too_many_arguments, reason = "one case's shapes, motions and answer, as the adapter takes them")]
pub fn toi(
    krate: &str,
    version: &str,
    a: &Sphere,
    va: &P3,
    b: &Shape,
    vb: &P3,
    t_max: f64,
    exact: Option<&Toi>,
    allow: &Allowed,
) -> String {
    let mut l =
        header(krate, version, "shape cast", &["math::{Pose, Vector}", "query::{self, ShapeCastOptions}", "shape::*"]);
    l.extend(build(&Shape::Sphere(*a), 1));
    l.extend(build(b, 2));
    l.push(format!(
        "let options = ShapeCastOptions {{ max_time_of_impact: {}, target_distance: 0.0, stop_at_penetration: true, \
         compute_impact_geometry_on_penetration: true }};",
        lit(t_max)
    ));
    l.push(format!(
        "let hit = query::cast_shapes(&pos1, {}, &shape1, &pos2, {}, &shape2, options).unwrap();",
        vec3(va),
        vec3(vb)
    ));
    l.push("println!(\"{hit:?}\");".into());
    time_asserted(&mut l, exact.map(|h| h.t), allow.t, "no impact before t_max", "an impact");
    finish(l)
}

/// The program for two boxes' overlap (touching overlaps).
pub fn overlap(krate: &str, version: &str, a: &Aabb, b: &Aabb, exact: bool) -> String {
    let mut l =
        header(krate, version, "AABB intersection", &["bounding_volume::{Aabb, BoundingVolume}", "math::Vector"]);
    l.push(format!(
        "let (a, b) = (Aabb::new({}, {}), Aabb::new({}, {}));",
        vec3(&a.min),
        vec3(&a.max),
        vec3(&b.min),
        vec3(&b.max)
    ));
    l.push(format!(
        "assert_eq!(a.intersects(&b), {exact}, \"exact: {}\");",
        if exact { "they overlap" } else { "apart" }
    ));
    finish(l)
}

/// The program for the barycentric coordinates of `p`'s projection on `t`,
/// the exact ones `exact` (of the projection on the triangle's plane).
pub fn barycentric(krate: &str, version: &str, p: &P3, t: &Triangle, exact: &[f64; 3], allow: &Allowed) -> String {
    let mut l = header(
        krate,
        version,
        "barycentric coordinates of a projection",
        &["math::Vector", "query::PointQueryWithLocation", "shape::Triangle"],
    );
    l.push(format!(
        "let tri = Triangle::new({}, {}, {});",
        vec3(&t.vertices[0]),
        vec3(&t.vertices[1]),
        vec3(&t.vertices[2])
    ));
    l.push(format!("let (_, location) = tri.project_local_point_and_get_location({}, false);", vec3(p)));
    l.push("println!(\"{location:?}\");".into());
    l.push("let w = location.barycentric_coordinates().expect(\"coordinates\");".into());
    l.push(format!("let exact = [{}, {}, {}];", lit(exact[0]), lit(exact[1]), lit(exact[2])));
    l.push(format!(
        "assert!((0..3).all(|i| (w[i] - exact[i]).abs() <= {:e}), \"{{w:?}}, exact {{exact:?}}\");",
        allow.barycentric
    ));
    finish(l)
}

/// The program for the bounding sphere of `points`: it must enclose every
/// point (within `allow.depth`, crashtest's allowance for a radius).
pub fn bounds(krate: &str, version: &str, points: &[P3], allow: &Allowed) -> String {
    let mut l = header(
        krate,
        version,
        "bounding sphere of a point cloud",
        &["bounding_volume::details::point_cloud_bounding_sphere", "math::Vector"],
    );
    l.push(format!("let points = [{}];", points.iter().map(vec3).collect::<Vec<_>>().join(", ")));
    l.push("let s = point_cloud_bounding_sphere(&points);".into());
    l.push("println!(\"{s:?}\");".into());
    l.push(format!(
        "for p in &points {{ assert!((*p - s.center()).length() <= s.radius() + {:e}, \"{{p}} outside\"); }}",
        allow.depth
    ));
    finish(l)
}

/// The lines asserting a `hit` (a ray's or a cast's, with `time_of_impact`):
/// none when the exact answer has none (`none` says why), else one at the
/// exact time `t` (`some` names it) within `allowed`.
fn time_asserted(l: &mut Vec<String>, t: Option<f64>, allowed: f64, none: &str, some: &str) {
    match t {
        None => l.push(format!("assert!(hit.is_none(), \"exact: {none}\");")),
        Some(t) => {
            l.push(format!("let hit = hit.expect(\"exact: {some} at t = {}\");", lit(t)));
            l.push(format!(
                "assert!((hit.time_of_impact - {}).abs() <= {allowed:e}, \"t {{}}, exact {}\", hit.time_of_impact);",
                lit(t),
                lit(t)
            ));
        }
    }
}

fn finish(mut l: Vec<String>) -> String {
    let mut out = String::new();
    let first = l.iter().position(|x| x == "fn main() {").map_or(0, |i| i + 1);
    let last = l.len();
    l.push("}".into());
    for (i, line) in l.into_iter().enumerate() {
        let indent = if (first..last).contains(&i) { "    " } else { "" };
        out.push_str(indent);
        out.push_str(&line);
        out.push('\n');
    }
    out
}
