//! Tests of the bounding volumes: hand-derived cases (derivation beside each),
//! degenerate inputs, and properties. Every test body is generic and runs for
//! `f32` and `f64`.

use super::*;
use crate::real::{Real, Vec3};
use crate::shapes::{Aabb, Segment, Sphere, Triangle};
use crate::test_support::{both, eps, v};
use proptest::prelude::*;

/// Hand-derived sphere cases on small integer inputs: the centre and radius
/// come out of a few roundings of values ≤ 8. Units: ε of the type under test
/// times the scene's size (here ≈ 1–5, so taken as 8).
const HAND_TOL_EPS: f64 = 64.0;

/// Enclosure: an input point's exact distance from the centre may exceed the
/// reported radius by the rounding of one difference and one `stable_norm`
/// (about 3ε relative, see `BoundingSphere`), and the check's own `f64` distance
/// adds up to 2 `f64` ε. Units: ε of the type times the radius.
const ENCLOSE_REL_EPS: f64 = 6.0;

/// Minimal against the other constructions and against brute force: the
/// minimal sphere may exceed the true minimum by its membership slack (64 ε of
/// the local unit, ≤ the scene's size) plus the support construction's
/// rounding. Units: ε of the type times the scene's size (largest offset from
/// the first point, ∞-norm).
const MINIMAL_TOL_EPS: f64 = 256.0;

/// Translations on the dyadic grid are exact, but the centre is mapped back and
/// the radius recomputed in the moved frame: a few roundings of the centre's
/// coordinates (magnitude ≤ shift + size) and of the distances. Units: ε of the
/// type times (shift + size).
const TRANSLATION_TOL_EPS: f64 = 16.0;

fn wide3<T: Real>(p: &Vec3<T>) -> Vec3<f64> {
    Vec3::new(p.x.wide(), p.y.wide(), p.z.wide())
}

/// Distance in `f64` without overflow or underflow: the difference (halved
/// when it overflows) is divided by its largest component before squaring.
fn dist_f64<T: Real>(p: &Vec3<T>, q: &Vec3<T>) -> f64 {
    let (p, q) = (wide3(p), wide3(q));
    let (d, k) = if (p - q).iter().all(|x| x.is_finite()) { (p - q, 1.0) } else { (p * 0.5 - q * 0.5, 2.0) };
    let m = d.amax();
    if m == 0.0 { 0.0 } else { (d / m).norm() * m * k }
}

type Method<T> = fn(&[Vec3<T>]) -> Option<BoundingSphere<T>>;

fn methods<T: Real>() -> [(&'static str, Method<T>); 3] {
    [
        ("centroid", bounding_sphere_centroid::<T>),
        ("ritter", bounding_sphere_ritter::<T>),
        ("minimal", bounding_sphere_minimal::<T>),
    ]
}

fn assert_sphere<T: Real>(got: &BoundingSphere<T>, center: [f64; 3], radius: f64, what: &str) {
    let tol = HAND_TOL_EPS * eps::<T>();
    let c = wide3(&got.center);
    assert!((c - Vec3::from(center)).amax() <= tol, "{what}: centre {c:?}, want {center:?}");
    let r = got.radius.wide();
    assert!((r - radius).abs() <= tol * radius.max(1.0), "{what}: radius {r}, want {radius}");
    assert!(!got.degenerate, "{what}: flagged degenerate");
}

// ------------------------------------------------------------------- AABB

fn aabb_hand<T: Real>() {
    assert!(aabb_from_points::<T>(&[]).is_none(), "empty input has no box");
    // Expansion over (1, −2, 3), (−4, 5, 0), (2, 0, −1): per-axis min and max.
    let pts = [v::<T>(1.0, -2.0, 3.0), v(-4.0, 5.0, 0.0), v(2.0, 0.0, -1.0)];
    let bb = aabb_from_points(&pts).expect("non-empty");
    assert!(wide3(&(bb.min - v(-4.0, -2.0, -1.0))).amax() <= 0.0, "min {:?}", bb.min);
    assert!(wide3(&(bb.max - v(2.0, 5.0, 3.0))).amax() <= 0.0, "max {:?}", bb.max);
    // The triangle of the same three points has the same box.
    let tb = aabb_of_triangle(&Triangle::new(pts[0], pts[1], pts[2]));
    assert!(tb == bb, "triangle box {tb:?} vs {bb:?}");
    // Segment (1, −2, 3) → (−4, 5, 0): min (−4, −2, 0), max (1, 5, 3).
    let sb = aabb_of_segment(&Segment::new(pts[0], pts[1]));
    assert!(sb == Aabb::new(v(-4.0, -2.0, 0.0), v(1.0, 5.0, 3.0)), "segment box {sb:?}");
    // Sphere at (1, 2, 3) of radius 0.5: [0.5, 1.5] × [1.5, 2.5] × [2.5, 3.5]
    // (exact: dyadic). A negative radius is read as its magnitude.
    let want = Aabb::new(v(0.5, 1.5, 2.5), v(1.5, 2.5, 3.5));
    for r in [0.5, -0.5] {
        let b = aabb_of_sphere(&Sphere::new(v(1.0, 2.0, 3.0), T::of(r)));
        assert!(b == want, "sphere box for radius {r}: {b:?}");
    }
    // A single point: the point box.
    let one = aabb_from_points(&pts[..1]).expect("non-empty");
    assert!(one.min == pts[0] && one.max == pts[0], "single point box {one:?}");
}
both!(aabb_hand_derived, aabb_hand);

fn overlap_hand<T: Real>() {
    let unit = Aabb::new(v::<T>(0.0, 0.0, 0.0), v(1.0, 1.0, 1.0));
    let cases: [(&str, [f64; 3], [f64; 3], bool); 6] = [
        ("overlapping", [0.5, 0.5, 0.5], [2.0, 2.0, 2.0], true),
        ("contained", [0.25, 0.25, 0.25], [0.75, 0.75, 0.75], true),
        ("touching face x = 1", [1.0, 0.0, 0.0], [2.0, 1.0, 1.0], true),
        ("touching corner (1,1,1)", [1.0, 1.0, 1.0], [2.0, 2.0, 2.0], true),
        ("separated on z only", [0.0, 0.0, 1.5], [1.0, 1.0, 2.0], false),
        ("overlapping x and y, gap on y below", [0.5, -2.0, 0.5], [0.6, -0.5, 0.6], false),
    ];
    for (what, lo, hi, want) in cases {
        let b = Aabb::new(v(lo[0], lo[1], lo[2]), v(hi[0], hi[1], hi[2]));
        assert_eq!(test_aabb_aabb(&unit, &b), want, "{what}");
        assert_eq!(test_aabb_aabb(&b, &unit), want, "{what}, swapped");
    }
    // One ulp apart on x: 1 + ε is the next value above 1.
    let gap = Aabb::new(Vec3::new(T::one() + T::EPSILON, T::zero(), T::zero()), v(2.0, 1.0, 1.0));
    assert!(!test_aabb_aabb(&unit, &gap), "one ulp gap separates");
}
both!(overlap_hand_derived, overlap_hand);

// ---------------------------------------------------------------- spheres

fn spheres_hand<T: Real>() {
    for (name, f) in methods::<T>() {
        assert!(f(&[]).is_none(), "{name}: empty input");
        // One point, and three copies of it: that point, radius 0.
        let p = v::<T>(3.0, -1.0, 2.0);
        assert_sphere(&f(&[p]).expect("non-empty"), [3.0, -1.0, 2.0], 0.0, &format!("{name}: single point"));
        assert_sphere(&f(&[p, p, p]).expect("non-empty"), [3.0, -1.0, 2.0], 0.0, &format!("{name}: duplicates"));
        // Two points 4 apart: every method gives the midpoint and radius 2
        // (centroid = midpoint; Ritter's pair is the two; minimal by definition).
        let two = [v::<T>(1.0, 1.0, 1.0), v(1.0, 5.0, 1.0)];
        assert_sphere(&f(&two).expect("non-empty"), [1.0, 3.0, 1.0], 2.0, &format!("{name}: two points"));
    }
    // Collinear 0, 1, 5 on x: minimal and Ritter (x = 0, farthest 5, farthest
    // from 5 is 0) are centred at 2.5 with radius 2.5; the centroid is 2, radius 3.
    let col = [v::<T>(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(5.0, 0.0, 0.0)];
    assert_sphere(&bounding_sphere_minimal(&col).unwrap(), [2.5, 0.0, 0.0], 2.5, "minimal, collinear");
    assert_sphere(&bounding_sphere_ritter(&col).unwrap(), [2.5, 0.0, 0.0], 2.5, "ritter, collinear");
    assert_sphere(&bounding_sphere_centroid(&col).unwrap(), [2.0, 0.0, 0.0], 3.0, "centroid, collinear");
    // Coplanar square (±1, ±1, 0) with its centre: all three give 0, √2.
    let sq = [v::<T>(1.0, 1.0, 0.0), v(-1.0, 1.0, 0.0), v(-1.0, -1.0, 0.0), v(1.0, -1.0, 0.0), v(0.0, 0.0, 0.0)];
    for (name, f) in methods::<T>() {
        assert_sphere(&f(&sq).unwrap(), [0.0, 0.0, 0.0], 2f64.sqrt(), &format!("{name}: square"));
    }
    // Equilateral triangle of side 2, (0,0,0), (2,0,0), (1,√3,0): the minimal
    // sphere is its circumcircle, centre (1, 1/√3, 0), radius 2/√3 (three
    // support points).
    let s3 = 3f64.sqrt();
    let eq = [v::<T>(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(1.0, s3, 0.0)];
    assert_sphere(&bounding_sphere_minimal(&eq).unwrap(), [1.0, 1.0 / s3, 0.0], 2.0 / s3, "minimal, equilateral");
    // Obtuse triangle (0,0,0), (4,0,0), (2,1,0): the third point is within the
    // sphere on the long side, so the minimal sphere is that: (2,0,0), radius 2.
    let obt = [v::<T>(0.0, 0.0, 0.0), v(4.0, 0.0, 0.0), v(2.0, 1.0, 0.0)];
    assert_sphere(&bounding_sphere_minimal(&obt).unwrap(), [2.0, 0.0, 0.0], 2.0, "minimal, obtuse");
    // Regular tetrahedron (1,1,1), (1,−1,−1), (−1,1,−1), (−1,−1,1) plus its
    // centre: circumsphere at the origin, radius √3 (four support points).
    let tet = [v::<T>(1.0, 1.0, 1.0), v(1.0, -1.0, -1.0), v(-1.0, 1.0, -1.0), v(-1.0, -1.0, 1.0), v(0.0, 0.0, 0.0)];
    assert_sphere(&bounding_sphere_minimal(&tet).unwrap(), [0.0, 0.0, 0.0], s3, "minimal, tetrahedron");
    // Nine points at (1,0,0) and one at (−1,0,0): the lecture's centroid is
    // pulled to x = 0.8 and needs radius 1.8; the minimal sphere is 0, radius 1.
    let mut lop = vec![v::<T>(1.0, 0.0, 0.0); 9];
    lop.push(v(-1.0, 0.0, 0.0));
    assert_sphere(&bounding_sphere_centroid(&lop).unwrap(), [0.8, 0.0, 0.0], 1.8, "centroid, lopsided");
    assert_sphere(&bounding_sphere_minimal(&lop).unwrap(), [0.0, 0.0, 0.0], 1.0, "minimal, lopsided");
    assert_sphere(&bounding_sphere_ritter(&lop).unwrap(), [0.0, 0.0, 0.0], 1.0, "ritter, lopsided");
}
both!(bounding_spheres_hand_derived, spheres_hand);

fn spheres_extreme<T: Real>() {
    let max = T::max_value().unwrap_or(T::one());
    let z = T::zero();
    // Four points on the axes at ±0.75 max: differences overflow (halved frame);
    // all methods: centre 0, radius 0.75 max, finite.
    let m = max * T::of(0.75);
    let pts = [Vec3::new(m, z, z), Vec3::new(-m, z, z), Vec3::new(z, m, z), Vec3::new(z, -m, z)];
    for (name, f) in methods::<T>() {
        let s = f(&pts).unwrap();
        assert!(!s.degenerate, "{name}: 0.75 max is representable");
        assert!(wide3(&s.center).amax() <= HAND_TOL_EPS * eps::<T>() * m.wide(), "{name}: centre {:?}", s.center);
        assert!((s.radius.wide() / m.wide() - 1.0).abs() <= HAND_TOL_EPS * eps::<T>(), "{name}: radius {:?}", s.radius);
    }
    // Opposite corners at ±max: the radius max·√3 overflows: degenerate, radius
    // +∞, centre finite.
    let corners = [Vec3::new(max, max, max), Vec3::new(-max, -max, -max)];
    for (name, f) in methods::<T>() {
        let s = f(&corners).unwrap();
        assert!(s.degenerate && s.radius > max, "{name}: overflowing radius: {s:?}");
        assert!(s.center.iter().all(|x| x.finite()), "{name}: centre finite: {s:?}");
    }
    // A subnormal-scale scene (1/max ≈ 2.9e-39 in f32, 5.6e-309 in f64): two
    // points 2/max apart, radius 1/max.
    let t = T::one() / max;
    let tiny = [Vec3::new(t, z, z), Vec3::new(-t, z, z)];
    for (name, f) in methods::<T>() {
        let s = f(&tiny).unwrap();
        assert!((s.radius.wide() - t.wide()).abs() <= eps::<T>() * t.wide() * 4.0, "{name}: tiny radius {s:?}");
    }
}
both!(bounding_spheres_extreme_scales, spheres_extreme);

fn spheres_many_points<T: Real>() {
    // 20 000 points on a sphere of radius 3 about (10, −20, 5) (a Fibonacci
    // lattice: every point is a support candidate): the minimal radius is 3
    // to within the lattice's gaps (it touches the sphere at points), and the
    // run is quick (expected linear time).
    let n = 20_000;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let pts: Vec<Vec3<T>> = (0..n)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - y * y).sqrt();
            let th = golden * i as f64;
            v(10.0 + 3.0 * r * th.cos(), -20.0 + 3.0 * y, 5.0 + 3.0 * r * th.sin())
        })
        .collect();
    let s = bounding_sphere_minimal(&pts).unwrap();
    // Lattice gaps: the nearest lattice point to any direction is within about
    // 3·√(4π/n) ≈ 0.075, so the minimal sphere of the lattice has radius within
    // 3 (1 − cos 0.025) ≈ 1e-3 of 3.
    assert!((s.radius.wide() - 3.0).abs() <= 1e-3, "radius {:?}", s.radius);
    assert!((wide3(&s.center) - Vec3::new(10.0, -20.0, 5.0)).amax() <= 1e-3, "centre {:?}", s.center);
}
both!(minimal_sphere_of_many_points, spheres_many_points);

// -------------------------------------------------------------- properties

/// A point cloud on a dyadic grid, its scale exponent and an exact translation.
#[derive(Clone, Debug)]
struct Cloud {
    pts: Vec<[i32; 3]>,
    /// Coordinates are `k · 2^scale`.
    scale: i32,
    shift: [i32; 3],
    /// How the cloud is flattened: 0 none, 1 coplanar (z = 0), 2 collinear.
    flat: u8,
}

fn cloud(max_points: usize) -> impl Strategy<Value = Cloud> {
    (
        prop::collection::vec([-1024i32..=1024, -1024i32..=1024, -1024i32..=1024], 1..max_points),
        -40i32..=40,
        [-4096i32..=4096, -4096i32..=4096, -4096i32..=4096],
        0u8..3,
    )
        .prop_map(|(pts, scale, shift, flat)| Cloud { pts, scale, shift, flat })
}

impl Cloud {
    /// The points (flattened as asked), each coordinate `k · 2^scale`; exact in
    /// both types (≤ 11 significant bits).
    fn points<T: Real>(&self) -> Vec<Vec3<T>> {
        let s = 2f64.powi(self.scale);
        self.pts
            .iter()
            .map(|k| {
                let k = match self.flat {
                    1 => [k[0], k[1], 0],
                    2 => [k[0], 2 * k[0] / 3, -k[0]],
                    _ => *k,
                };
                v(f64::from(k[0]) * s, f64::from(k[1]) * s, f64::from(k[2]) * s)
            })
            .collect()
    }

    /// The translation, multiples of `2^(scale + 6)`: sums need ≤ 17 bits.
    fn shift<T: Real>(&self) -> Vec3<T> {
        let s = 2f64.powi(self.scale + 6);
        v(f64::from(self.shift[0]) * s, f64::from(self.shift[1]) * s, f64::from(self.shift[2]) * s)
    }
}

/// The scene's size: largest ∞-norm offset from the first point (at least the
/// smallest grid step, so tolerances never vanish).
fn size<T: Real>(pts: &[Vec3<T>]) -> f64 {
    let p0 = wide3(&pts[0]);
    pts.iter().map(|p| (wide3(p) - p0).amax()).fold(0.0, f64::max)
}

fn check_aabb<T: Real>(c: &Cloud) -> Result<(), TestCaseError> {
    let pts = c.points::<T>();
    let bb = aabb_from_points(&pts).expect("non-empty");
    for p in &pts {
        for i in 0..3 {
            prop_assert!(bb.min[i] <= p[i] && p[i] <= bb.max[i], "point {p:?} outside {bb:?}");
        }
    }
    // Tight: each face is touched (with containment above, `≤` means equality).
    for i in 0..3 {
        prop_assert!(pts.iter().any(|p| p[i] <= bb.min[i]), "min face {i} untouched");
        prop_assert!(pts.iter().any(|p| p[i] >= bb.max[i]), "max face {i} untouched");
    }
    Ok(())
}

fn check_overlap<T: Real>(pair: &(Cloud, Cloud)) -> Result<(), TestCaseError> {
    let a = aabb_from_points(&pair.0.points::<T>()).expect("non-empty");
    let mut pb = pair.1.points::<T>();
    let t = pair.1.shift::<T>() * T::of(2f64.powi(pair.0.scale - pair.1.scale - 6));
    pb.iter_mut().for_each(|p| *p += t);
    let b = aabb_from_points(&pb).expect("non-empty");
    let ab = test_aabb_aabb(&a, &b);
    prop_assert_eq!(ab, test_aabb_aabb(&b, &a), "not symmetric");
    // Characterization: they overlap exactly when the corner max(a.min, b.min)
    // lies in both boxes.
    let w = a.min.zip_map(&b.min, |x, y| x.max(y));
    let inside = |bb: &Aabb<T>| (0..3).all(|i| bb.min[i] <= w[i] && w[i] <= bb.max[i]);
    prop_assert_eq!(ab, inside(&a) && inside(&b), "witness corner {:?}", w);
    Ok(())
}

fn check_spheres<T: Real>(c: &Cloud) -> Result<(), TestCaseError> {
    let pts = c.points::<T>();
    let scale = size(&pts).max(2f64.powi(c.scale));
    let mut radii = [0.0; 3];
    for (k, (name, f)) in methods::<T>().into_iter().enumerate() {
        let s = f(&pts).expect("non-empty");
        prop_assert!(s.center.iter().all(|x| x.finite()), "{name}: centre {s:?}");
        prop_assert!(s.radius >= T::zero() && s.radius.finite() && !s.degenerate, "{name}: radius {s:?}");
        let r = s.radius.wide();
        for p in &pts {
            let d = dist_f64(p, &s.center);
            prop_assert!(d <= r * (1.0 + ENCLOSE_REL_EPS * eps::<T>()), "{name}: {p:?} at {d} outside radius {r}");
        }
        radii[k] = r;
    }
    let tol = MINIMAL_TOL_EPS * eps::<T>() * scale;
    prop_assert!(radii[2] <= radii[0] + tol, "minimal {} > centroid {}", radii[2], radii[0]);
    prop_assert!(radii[2] <= radii[1] + tol, "minimal {} > ritter {}", radii[2], radii[1]);
    Ok(())
}

fn check_translation<T: Real>(c: &Cloud) -> Result<(), TestCaseError> {
    let pts = c.points::<T>();
    let t = c.shift::<T>();
    let moved: Vec<Vec3<T>> = pts.iter().map(|p| p + t).collect();
    let tol = TRANSLATION_TOL_EPS * eps::<T>() * (wide3(&t).amax() + size(&pts) + 2f64.powi(c.scale));
    for (name, f) in methods::<T>() {
        let (here, there) = (f(&pts).unwrap(), f(&moved).unwrap());
        let dc = (wide3(&there.center) - wide3(&here.center) - wide3(&t)).amax();
        prop_assert!(dc <= tol, "{name}: centre moved by {dc:e} more than the shift (tol {tol:e})");
        let dr = (there.radius.wide() - here.radius.wide()).abs();
        prop_assert!(dr <= tol, "{name}: radius changed by {dr:e} (tol {tol:e})");
    }
    Ok(())
}

fn check_two_points<T: Real>(c: &Cloud) -> Result<(), TestCaseError> {
    let mut pts = c.points::<T>();
    pts.push(pts[0] + c.shift::<T>());
    let pair = [pts[0], pts[pts.len() - 1]];
    let s = bounding_sphere_minimal(&pair).unwrap();
    let half = dist_f64(&pair[0], &pair[1]) / 2.0;
    prop_assert!(
        (s.radius.wide() - half).abs() <= HAND_TOL_EPS * eps::<T>() * half.max(f64::MIN_POSITIVE),
        "radius {:?}, half distance {half}",
        s.radius
    );
    Ok(())
}

/// The smallest enclosing ball by brute force over all supports of 1 to 4
/// points (`f64`, centre solved in each support's affine hull by least squares
/// on its Gram system); `O(n⁵)`, for small clouds only.
fn brute_force_radius(pts: &[Vec3<f64>]) -> f64 {
    let n = pts.len();
    let scale = pts.iter().map(|p| (p - pts[0]).amax()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
    let mut best = f64::INFINITY;
    let mut consider = |support: &[usize]| {
        let a = pts[support[0]];
        let k = support.len() - 1;
        let center = if k == 0 {
            a
        } else {
            let e = nalgebra::DMatrix::from_fn(3, k, |r, c| pts[support[c + 1]][r] - a[r]);
            let g = e.transpose() * &e;
            let rhs = nalgebra::DVector::from_fn(k, |r, _| 0.5 * (pts[support[r + 1]] - a).norm_squared());
            let Some(lambda) = g.lu().solve(&rhs) else {
                return;
            };
            let x = &e * lambda;
            a + Vec3::new(x[0], x[1], x[2])
        };
        if !center.iter().all(|x| x.is_finite()) {
            return;
        }
        let r = pts.iter().map(|p| (p - center).norm()).fold(0.0, f64::max);
        let on = support.iter().map(|&i| (pts[i] - center).norm()).fold(0.0, f64::max);
        // Only balls that have their support on the boundary (a least-squares
        // centre of an inconsistent system does not) and enclose everything.
        if (r - on).abs() <= 1e-9 * scale && r < best {
            best = r;
        }
    };
    for i in 0..n {
        consider(&[i]);
        for j in i + 1..n {
            consider(&[i, j]);
            for k in j + 1..n {
                consider(&[i, j, k]);
                for l in k + 1..n {
                    consider(&[i, j, k, l]);
                }
            }
        }
    }
    best
}

fn check_brute_force<T: Real>(c: &Cloud) -> Result<(), TestCaseError> {
    let pts = c.points::<T>();
    let wide: Vec<Vec3<f64>> = pts.iter().map(wide3).collect();
    let want = brute_force_radius(&wide);
    let got = bounding_sphere_minimal(&pts).unwrap().radius.wide();
    let scale = size(&pts).max(2f64.powi(c.scale));
    let tol = MINIMAL_TOL_EPS * eps::<T>() * scale;
    prop_assert!((got - want).abs() <= tol, "minimal radius {got}, brute force {want} (tol {tol:e})");
    Ok(())
}

/// A finite value of `T` from a mantissa in [−1, 1] and an exponent fraction,
/// spread over the type's whole range (subnormals to the largest finite value).
fn finite_of<T: Real>(m: f64, frac: f64) -> T {
    let max = T::max_value().unwrap_or(T::one()).wide();
    let top = max.log2();
    let bottom = -top - T::EPSILON.wide().log2().abs();
    let e = bottom + frac * (top - bottom);
    let x = T::of((m * e.exp2()).clamp(-max, max));
    if x.finite() { x } else { T::of(max.copysign(m)) }
}

fn check_any_finite<T: Real>(raw: &[[(f64, f64); 3]]) -> Result<(), TestCaseError> {
    let pts: Vec<Vec3<T>> = raw
        .iter()
        .map(|c| Vec3::new(finite_of(c[0].0, c[0].1), finite_of(c[1].0, c[1].1), finite_of(c[2].0, c[2].1)))
        .collect();
    for (name, f) in methods::<T>() {
        let s = f(&pts).expect("non-empty");
        prop_assert!(s.center.iter().all(|x| x.finite()), "{name}: centre {s:?}");
        prop_assert!(s.radius >= T::zero(), "{name}: radius {s:?}");
        prop_assert_eq!(s.degenerate, !s.radius.finite(), "{}: flag means overflow", name);
        if !s.degenerate {
            let r = s.radius.wide();
            for p in &pts {
                let d = dist_f64(p, &s.center);
                prop_assert!(d <= r * (1.0 + ENCLOSE_REL_EPS * eps::<T>()), "{name}: {p:?} at {d} outside {r}");
            }
        }
    }
    Ok(())
}

fn any_cloud() -> impl Strategy<Value = Vec<[(f64, f64); 3]>> {
    let c = || (-1.0f64..=1.0, 0.0f64..=1.0);
    prop::collection::vec([c(), c(), c()], 1..12)
}

/// Runs a generic property for both precisions.
macro_rules! prop_both {
    ($cases:expr, $name:ident, $strat:expr, $check:ident) => {
        mod $name {
            use super::*;
            proptest! {
                #![proptest_config(ProptestConfig::with_cases($cases))]
                #[test]
                fn f32(s in $strat) { $check::<f32>(&s)?; }
                #[test]
                fn f64(s in $strat) { $check::<f64>(&s)?; }
            }
        }
    };
}

prop_both!(1000, aabb_contains_every_point_and_is_tight, cloud(40), check_aabb);
prop_both!(1000, overlap_is_symmetric_and_has_a_witness, (cloud(6), cloud(6)), check_overlap);
prop_both!(500, spheres_enclose_and_minimal_is_smallest, cloud(40), check_spheres);
prop_both!(300, spheres_translation_invariant, cloud(30), check_translation);
prop_both!(500, minimal_sphere_of_two_points_is_half_their_distance, cloud(2), check_two_points);
prop_both!(200, minimal_sphere_matches_brute_force, cloud(8), check_brute_force);
prop_both!(1000, spheres_of_any_finite_input, any_cloud(), check_any_finite);
