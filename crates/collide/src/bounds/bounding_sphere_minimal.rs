//! The minimal enclosing sphere: Welzl's algorithm.

use super::bounding_sphere::BoundingSphere;
use super::sphere_frame::{enclose, local_cloud};
use crate::barycentric::local::is_flat_triangle;
use crate::real::{Real, Vec3, c};

/// Slack of the "inside the current sphere" test, in units of ε, in the local
/// frame (where the largest offset component lies in `[1, 2)`, so the unit is
/// about the scene's size).
///
/// Reason: the support-sphere constructions below are accurate to a few tens of
/// ε on well-shaped support sets. A point that lies on the sphere up to that
/// error is counted inside instead of being made a support point, which would
/// hand the next construction a nearly degenerate set (two nearly equal points,
/// four nearly cospherical ones). Its excess, at most this slack, is absorbed by
/// the final radius fix-up, so the radius may exceed the minimum by up to
/// `64 ε` times the scene's size.
const WELZL_SLACK_EPS: f64 = 64.0;

/// Flatness threshold of a tetrahedron of support points, in units of ε: flat
/// when `|u·(v × w)| ≤ FLAT_TETRA_EPS · ε · L³` (`u, v, w` the edges from one
/// vertex, `L` the longest of the six edges; scale-free). Reason: the computed
/// triple product of four exactly coplanar points is rounding noise of about
/// `5 ε L³`; 32 leaves a margin of six. Below it the circumsphere's linear system
/// is too ill-conditioned to solve, and the smallest sphere of the four is found
/// among their pairs and triples instead.
const FLAT_TETRA_EPS: f64 = 32.0;

/// Seed of the internal shuffle (SplitMix64): fixed, so the construction is
/// deterministic for a given input, while its expected linear running time holds
/// for every input order that was not built against this seed.
const WELZL_SHUFFLE_SEED: u64 = 0x9E37_79B9_7F4A_7C15;

/// The smallest sphere enclosing every point (minimal enclosing ball), by
/// Welzl's randomized algorithm (E. Welzl, "Smallest enclosing disks (balls and
/// ellipsoids)", 1991), in its iterative form with the recursion unrolled into
/// four nested loops (depth bounded by the at most 4 support points, never by
/// the number of points):
///
/// ```text
/// shuffle the points
/// S := {p0}
/// for i:        if p_i ∉ S: S := ball(p_i)
///   for j < i:    if p_j ∉ S: S := ball(p_i, p_j)
///     for k < j:    if p_k ∉ S: S := ball(p_i, p_j, p_k)
///       for l < k:    if p_l ∉ S: S := ball(p_i, p_j, p_k, p_l)
/// ```
///
/// where `ball(…)` is the smallest sphere with the given points on its boundary.
/// Derivation (Welzl's lemma): if `p` lies outside the minimal sphere of a set,
/// it lies on the boundary of the minimal sphere of the set with `p`; each loop
/// level fixes one more boundary point, and in 3-D at most 4 are needed. With
/// the points in random order a point is outside the current sphere with
/// probability at most `4/i`, which makes the expected work `O(n)`; the order here
/// is a deterministic shuffle (SplitMix64 from the fixed seed `WELZL_SHUFFLE_SEED`).
///
/// Support spheres (offsets from the first support point `a`):
/// - 2 points: `center = (a + b)/2`.
/// - 3 points: the circumcircle, `center = a + ((‖u‖² v − ‖v‖² u) × (u × v)) /
///   (2 ‖u × v‖²)`, `u = b − a`, `v = c − a` (equidistant from the three and in
///   their plane). Collinear or coincident support points (by the scale-relative
///   flatness test `FLAT_TRIANGLE_EPS`, `‖u × v‖ ≤ 16 ε L²`) have no circumcircle: the sphere on
///   their farthest pair is used, which contains the third (it lies between
///   them, up to rounding).
/// - 4 points: the circumsphere, `center = a + (‖u‖² (v × w) + ‖v‖² (w × u) +
///   ‖w‖² (u × v)) / (2 u·(v × w))`, `w = d − a` (Cramer's rule on
///   `2 (x − a)·e = ‖e‖²` for the three edges `e`). Coplanar, collinear or
///   coincident support points (`FLAT_TETRA_EPS`, `|u·(v × w)| ≤ 32 ε L³`) have none: the smallest
///   of the spheres on their pairs and triples, measured by the largest distance
///   to the four, is used; for coplanar points that is their minimal sphere.
///
/// Each support sphere's radius is the largest distance from its centre to its
/// support points, so those are inside as computed. The membership test allows
/// a slack of `WELZL_SLACK_EPS = 64` ε in the local frame, about the scene's
/// size (see that constant's reason).
///
/// Finally the centre is mapped back, clamped into the points' AABB, and the
/// radius is recomputed as the largest computed distance to any point: a point
/// that rounding (or the slack) left outside by a hair grows the radius to
/// include it. So every point's computed distance is `≤ radius` and its exact
/// distance within about `3 ε·radius` of it (see [`BoundingSphere`]); the radius
/// exceeds the true minimum by at most about `64 ε` times the scene's size plus
/// the support construction's rounding.
///
/// Numerics: computed in a local frame (offsets from the first point, scaled by
/// an exact power of two), so nothing overflows or underflows.
///
/// Degenerate input: no points gives `None`. A single point, or coincident points,
/// give that point with radius 0. Duplicates, collinear and coplanar sets are
/// handled by the support fallbacks above (two points: the sphere on their
/// segment; collinear: on the extreme pair). A scene spread over more than the
/// type's range gets radius `+∞` with `degenerate` set. Never NaN for finite
/// input.
pub fn bounding_sphere_minimal<T: Real>(points: &[Vec3<T>]) -> Option<BoundingSphere<T>> {
    let first = *points.first()?;
    let Some(mut cloud) = local_cloud(points) else {
        return Some(enclose(points, first));
    };
    let mut pts = std::mem::take(&mut cloud.points);
    shuffle(&mut pts);
    extremes_first(&mut pts);
    let slack = c::<T>(WELZL_SLACK_EPS) * T::EPSILON;
    let mut s = Ball { center: pts[0], radius: T::zero() };
    for i in 1..pts.len() {
        if s.contains(&pts[i], slack) {
            continue;
        }
        s = Ball { center: pts[i], radius: T::zero() };
        for j in 0..i {
            if s.contains(&pts[j], slack) {
                continue;
            }
            s = ball2(&pts[i], &pts[j]);
            for k in 0..j {
                if s.contains(&pts[k], slack) {
                    continue;
                }
                s = ball3(&pts[i], &pts[j], &pts[k]);
                for l in 0..k {
                    if !s.contains(&pts[l], slack) {
                        s = ball4(&pts[i], &pts[j], &pts[k], &pts[l]);
                    }
                }
            }
        }
    }
    Some(enclose(points, cloud.to_world(&s.center)))
}

/// A sphere in the local frame.
#[derive(Clone, Copy)]
struct Ball<T: Real> {
    center: Vec3<T>,
    radius: T,
}

impl<T: Real> Ball<T> {
    /// `‖p − center‖ ≤ radius + slack`, compared squared (no square root: in
    /// the local frame nothing overflows, and the slack absorbs the rounding
    /// either way; [`enclose`] makes the final radius reach every point).
    fn contains(&self, p: &Vec3<T>, slack: T) -> bool {
        let reach = self.radius + slack;
        (p - self.center).norm_squared() <= reach * reach
    }

    /// The sphere about `center` reaching the farthest of `support`.
    fn about(center: Vec3<T>, support: &[&Vec3<T>]) -> Self {
        let radius = support.iter().map(|p| (*p - center).norm()).fold(T::zero(), |a, b| a.max(b));
        Self { center, radius }
    }
}

/// The sphere with `a`, `b` on its boundary: centred at their midpoint.
fn ball2<T: Real>(a: &Vec3<T>, b: &Vec3<T>) -> Ball<T> {
    Ball::about((a + b) * c::<T>(0.5), &[a, b])
}

/// The smallest sphere with `a`, `b`, `p` on its boundary (their circumcircle);
/// for a flat triple, the sphere on its farthest pair.
fn ball3<T: Real>(a: &Vec3<T>, b: &Vec3<T>, p: &Vec3<T>) -> Ball<T> {
    let (u, v) = (b - a, p - a);
    let n = u.cross(&v);
    if is_flat_triangle(&u, &v, &n) {
        return farthest_pair_ball(&[a, b, p]);
    }
    let x = (v * u.norm_squared() - u * v.norm_squared()).cross(&n) / (n.norm_squared() * c::<T>(2.0));
    Ball::about(a + x, &[a, b, p])
}

/// The smallest sphere with the four points on its boundary (their
/// circumsphere); for a flat set, their smallest enclosing sphere among the
/// spheres on pairs and triples.
fn ball4<T: Real>(a: &Vec3<T>, b: &Vec3<T>, p: &Vec3<T>, q: &Vec3<T>) -> Ball<T> {
    let (u, v, w) = (b - a, p - a, q - a);
    let l2 = [u, v, w, p - b, q - b, q - p].iter().map(|e| e.norm_squared()).fold(T::zero(), |x, y| x.max(y));
    let det = u.dot(&v.cross(&w));
    let tol = c::<T>(FLAT_TETRA_EPS) * T::EPSILON * l2 * l2.sqrt();
    if det.abs() <= tol {
        return smallest_ball_of_four([a, b, p, q]);
    }
    let x = (v.cross(&w) * u.norm_squared() + w.cross(&u) * v.norm_squared() + u.cross(&v) * w.norm_squared())
        / (det * c::<T>(2.0));
    Ball::about(a + x, &[a, b, p, q])
}

/// The sphere on the farthest pair of `pts`.
fn farthest_pair_ball<T: Real>(pts: &[&Vec3<T>]) -> Ball<T> {
    let mut best = (0, 0);
    let mut best_d2 = -T::one();
    for i in 0..pts.len() {
        for j in i + 1..pts.len() {
            let d2 = (pts[j] - pts[i]).norm_squared();
            if d2 > best_d2 {
                best = (i, j);
                best_d2 = d2;
            }
        }
    }
    ball2(pts[best.0], pts[best.1])
}

/// For four flat support points: among the spheres on their 6 pairs and 4
/// triples, the one whose largest distance to the four is least, grown to that
/// distance. The minimal sphere of a coplanar set has at most 3 points on its
/// boundary, so it is among these candidates.
fn smallest_ball_of_four<T: Real>(q: [&Vec3<T>; 4]) -> Ball<T> {
    const PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    const TRIPLES: [(usize, usize, usize); 4] = [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)];
    let candidates =
        PAIRS.iter().map(|&(i, j)| ball2(q[i], q[j])).chain(TRIPLES.iter().map(|&(i, j, k)| ball3(q[i], q[j], q[k])));
    let mut best = Ball::about(*q[0], &q);
    for cand in candidates {
        let grown = Ball::about(cand.center, &q);
        if grown.radius < best.radius {
            best = grown;
        }
    }
    best
}

/// Moves the points of least and greatest `x`, `y` and `z` (the first of
/// equals, in the shuffled order) to the front, in that order, the rest keeping
/// their shuffled order. The sphere of the first points then nearly encloses
/// the cloud, and few later points fall outside it and restart the inner
/// loops: the answer is the same minimal sphere (Welzl's algorithm is correct
/// for every order; only its expected time rests on the order being random,
/// and six points first change that by a constant).
fn extremes_first<T: Real>(pts: &mut [Vec3<T>]) {
    let mut front = 0;
    for axis in 0..3 {
        for greatest in [false, true] {
            if front >= pts.len() {
                return;
            }
            let mut best = front;
            for i in front + 1..pts.len() {
                let (x, b) = (pts[i][axis], pts[best][axis]);
                if (greatest && x > b) || (!greatest && x < b) {
                    best = i;
                }
            }
            pts[front..=best].rotate_right(1);
            front += 1;
        }
    }
}

/// Fisher–Yates shuffle driven by SplitMix64 from [`WELZL_SHUFFLE_SEED`].
fn shuffle<T>(v: &mut [T]) {
    let mut state = WELZL_SHUFFLE_SEED;
    for i in (1..v.len()).rev() {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        v.swap(i, (z % (i as u64 + 1)) as usize);
    }
}
