//! Each query's arithmetic, counted by hand: the lower bound of the table is
//! this count at the machine's measured peak (see `peak.rs`).
//!
//! What is counted: floating-point operations on the FP pipes — add, subtract,
//! multiply, compare — one each ("ops"), and square roots and divisions apart
//! (they share the divider, far slower). Moves, abs, and integer work are not
//! counted. The count is of the textbook formula on the path the case takes
//! (a miss stops early), in `f64`, with no error bounds, scaling or
//! degenerate-case checks: the least arithmetic that produces the answer the
//! query returns, which is what a perfect implementation of the formula would
//! execute. Every engine answers the same question, so the bound is one per
//! query.
//!
//! Besides the arithmetic, a query must read its inputs: [`Cost::reading`]
//! adds the bytes of the `f64` inputs (in collide's types; parry3d-f64's, with
//! their poses, are no smaller), timed at the machine's measured read rate. For the cheapest
//! queries (AABB overlap: six compares on 96 bytes) that, not the arithmetic,
//! is the floor.

use crashtest_core::vec3::{dot, sub};
use oracle::geom::{P3, Sphere, Triangle};

/// One query's arithmetic.
#[derive(Clone, Copy, Debug, Default)]
pub struct Cost {
    /// add, sub, mul, compare.
    pub ops: f64,
    /// Square roots.
    pub sqrt: f64,
    /// Divisions.
    pub div: f64,
    /// Bytes of input read (the query's `f64` arguments).
    pub bytes: f64,
}

impl Cost {
    const fn new(ops: u32, sqrt: u32, div: u32) -> Self {
        Self { ops: ops as f64, sqrt: sqrt as f64, div: div as f64, bytes: 0.0 }
    }

    /// This cost with `bytes` of input read per query.
    pub fn reading(self, bytes: usize) -> Cost {
        Cost { bytes: bytes as f64, ..self }
    }

    /// The sum of two costs.
    pub fn plus(self, o: Cost) -> Cost {
        Cost { ops: self.ops + o.ops, sqrt: self.sqrt + o.sqrt, div: self.div + o.div, bytes: self.bytes + o.bytes }
    }

    /// The mean of several costs.
    pub fn mean(costs: impl IntoIterator<Item = Cost>) -> Cost {
        let (mut sum, mut n) = (Cost::default(), 0.0);
        for c in costs {
            sum = sum.plus(c);
            n += 1.0;
        }
        Cost { ops: sum.ops / n, sqrt: sum.sqrt / n, div: sum.div / n, bytes: sum.bytes / n }
    }
}

/// Sphere–sphere, a miss: `Δ = M1 − M2` (3 sub), `‖Δ‖²` (3 mul + 2 add),
/// `r1 + r2` (1 add), `(r1 + r2)²` (1 mul), `‖Δ‖² ≤ (r1 + r2)²` (1 cmp): 11 ops.
pub const SPHERE_SPHERE_MISS: Cost = Cost::new(11, 0, 0);
/// Sphere–sphere, a contact: the miss's 11 ops, then `d = √‖Δ‖²` (1 sqrt),
/// `1/d` (1 div), `n = Δ·(1/d)` (3 mul), `p = M2 + r2 n` (3 mul + 3 add),
/// `depth = r1 + r2 − d` (1 sub): 21 ops, 1 sqrt, 1 div.
pub const SPHERE_SPHERE_HIT: Cost = Cost::new(21, 1, 1);

/// Sphere–plane (`n · x = d`, `n` of any length), a miss: `s' = n · M − d`
/// (3 mul + 3 add/sub), `n · n` (3 mul + 2 add), the squared test
/// `s' ≤ 0 ∨ s'² ≤ r²(n · n)` (3 mul + 2 cmp): 16 ops, no root.
pub const SPHERE_PLANE_MISS: Cost = Cost::new(16, 0, 0);
/// Sphere–plane, a contact: `s'` and `n · n` (11 ops), `‖n‖ = √(n · n)`
/// (1 sqrt), `1/‖n‖` (1 div), `n̂ = n/‖n‖` (3 mul), `s = s'/‖n‖` (1 mul),
/// `s ≤ r` (1 cmp), `depth = r − s` (1 sub), `p = M − s n̂` (3 mul + 3 sub):
/// 23 ops, 1 sqrt, 1 div.
pub const SPHERE_PLANE_HIT: Cost = Cost::new(23, 1, 1);

/// Segment–plane, a miss (both ends on one side): `s0 = n · p0 − d`,
/// `s1 = n · p1 − d` (2 × (3 mul + 3 add/sub)), their signs (2 cmp): 14 ops.
pub const SEGMENT_PLANE_MISS: Cost = Cost::new(14, 0, 0);
/// Segment–plane, a hit: the miss's 14 ops, `t = s0/(s0 − s1)` (1 sub, 1 div),
/// `p = p0 + t (p1 − p0)` (3 sub + 3 mul + 3 add), `n̂ = n/‖n‖` (`n · n`:
/// 3 mul + 2 add; 1 sqrt; 1 div; 3 mul): 32 ops, 1 sqrt, 2 div.
pub const SEGMENT_PLANE_HIT: Cost = Cost::new(32, 1, 2);

/// Segment–triangle, a miss by the plane (both ends on one side):
/// `e1 = v1 − v0`, `e2 = v2 − v0` (6 sub), `n = e1 × e2` (6 mul + 3 sub),
/// `s_i = n · (q_i − v0)` (2 × (3 sub + 3 mul + 2 add)), signs (2 cmp): 33 ops.
pub const SEGMENT_TRIANGLE_PLANE_MISS: Cost = Cost::new(33, 0, 0);
/// Segment–triangle, a miss by an edge (Ericson §5.3.4): the plane stage's 33
/// ops, then `pq = q1 − q0` and one offset `q0 − v` (6 sub), one scalar triple
/// product (`pq × (v − q0)`: 6 mul + 3 sub; dot: 3 mul + 2 add), its sign
/// (1 cmp) — the least a miss by the first edge costs: 54 ops.
pub const SEGMENT_TRIANGLE_EDGE_MISS: Cost = Cost::new(54, 0, 0);
/// Segment–triangle, a hit: the plane stage (33), `pq` and three offsets
/// (12 sub), `m = pq × (v2 − q0)` (9), `u = (v1 − q0) · m`, `v = −(v0 − q0) · m`
/// (5 + 6), `w` (a full triple product: 14), three signs (3 cmp); then
/// `t = s0/(s0 − s1)` (1 sub, 1 div), `[u, v, w]/(u + v + w)` (2 add, 1 div,
/// 3 mul), `p = q0 + t pq` (3 mul + 3 add), `n̂` (5 + 3 mul, 1 sqrt, 1 div):
/// 100 ops, 1 sqrt, 3 div.
pub const SEGMENT_TRIANGLE_HIT: Cost = Cost::new(100, 1, 3);

/// Barycentric coordinates of the projection, in the Gram form collide's
/// filter evaluates (Lagrange's identity turns the cross-product form's
/// `n · n` and `n · (q × e1)` into dot products): `e0 = v1 − v0`,
/// `e1 = v2 − v0`, `q = p − v0` (9 sub), `d00, d01, d11, d20, d21` (5 × 5),
/// `D = d00 d11 − d01²` (3), `β' = d11 d20 − d01 d21`, `γ' = d00 d21 − d01 d20`
/// (2 × 3), `1/D` (1 div), `β = β'/D`, `γ = γ'/D` (2 mul), `α = 1 − β − γ`
/// (2 sub): 47 ops, 1 div.
pub const BARYCENTRIC: Cost = Cost::new(47, 0, 1);

/// AABB overlap: `a.min_i ≤ b.max_i` and `b.min_i ≤ a.max_i` on three axes:
/// 6 compares (the answer on a miss can stop at the first failing one; the
/// bound counts all six, as a branch-free test does).
pub const AABB_OVERLAP: Cost = Cost::new(6, 0, 0);

/// Bounding sphere, per point: any construction must at least check each
/// point against its sphere: `p − c` (3 sub), `‖p − c‖²` (3 mul + 2 add), the
/// comparison with the running radius² (1 cmp): 9 ops per point.
pub const BOUNDING_SPHERE_PER_POINT: Cost = Cost::new(9, 0, 0);
/// Bounding sphere, once: the radius `√(max ‖p − c‖²)` (1 sqrt).
pub const BOUNDING_SPHERE_ONCE: Cost = Cost::new(0, 1, 0);

/// Sphere–triangle contact: Ericson's closest point on the triangle
/// (*Real-Time Collision Detection* §5.1.5) on the Voronoi region the centre
/// falls in, then the sphere test and, for a contact, the normal:
///
/// - `ab`, `ac`, `ap` (9 sub), `d1 = ab·ap`, `d2 = ac·ap` (10), 2 cmp: vertex A
///   stops here (21);
/// - `bp` (3), `d3`, `d4` (10), 2 cmp: vertex B (36);
/// - `vc = d1 d4 − d3 d2` (3), 3 cmp: edge AB adds `v = d1/(d1 − d3)` (1 sub,
///   1 div) and `a + v ab` (6) (49, 1 div);
/// - `cp` (3), `d5`, `d6` (10), 2 cmp: vertex C (57);
/// - `vb` (3), 3 cmp: edge AC adds `d2 − d6` (1), the division (1 div) and
///   `a + w ac` (6) (70, 1 div);
/// - `va` (3), `d4 − d3`, `d5 − d6` (2), 3 cmp: edge BC adds their sum (1),
///   the division (1 div), `bc = c − b` (3) and `b + w bc` (6) (81, 1 div);
/// - the face: `denom = va + vb + vc` (2), `1/denom` (1 div), `v`, `w` (2 mul),
///   `a + v ab + w ac` (12): 87, 1 div.
///
/// Then `Δ = M − q` (3), `‖Δ‖²`, `r²`, compare (5 + 1 + 1): 10 for a miss; a
/// contact adds `√` (1 sqrt), `1/d` (1 div), `n = Δ/d` (3 mul), `depth = r − d`
/// (1 sub).
pub fn sphere_triangle(s: &Sphere, t: &Triangle) -> Cost {
    let [a, b, c] = t.vertices;
    let p = s.center;
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    let (region_ops, region_div, q): (u32, u32, P3) = 'region: {
        if d1 <= 0.0 && d2 <= 0.0 {
            break 'region (21, 0, a);
        }
        let bp = sub(p, b);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        if d3 >= 0.0 && d4 <= d3 {
            break 'region (36, 0, b);
        }
        let vc = d1 * d4 - d3 * d2;
        if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            let v = d1 / (d1 - d3);
            break 'region (49, 1, [a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]]);
        }
        let cp = sub(p, c);
        let (d5, d6) = (dot(ab, cp), dot(ac, cp));
        if d6 >= 0.0 && d5 <= d6 {
            break 'region (57, 0, c);
        }
        let vb = d5 * d2 - d1 * d6;
        if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            let w = d2 / (d2 - d6);
            break 'region (70, 1, [a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]]);
        }
        let va = d3 * d6 - d5 * d4;
        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
            let bc = sub(c, b);
            break 'region (81, 1, [b[0] + w * bc[0], b[1] + w * bc[1], b[2] + w * bc[2]]);
        }
        let inv = 1.0 / (va + vb + vc);
        let (v, w) = (vb * inv, vc * inv);
        let q = [0, 1, 2].map(|i| a[i] + ab[i] * v + ac[i] * w);
        (87, 1, q)
    };
    let d = sub(p, q);
    let hit = dot(d, d) <= s.radius * s.radius;
    let tail = if hit { Cost::new(14, 1, 1) } else { Cost::new(10, 0, 0) };
    Cost::new(region_ops, 0, region_div).plus(tail)
}
