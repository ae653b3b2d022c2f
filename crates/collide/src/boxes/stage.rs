//! The floating-point stage in front of the exact box decisions: the same
//! questions answered in plain `f64` with a rigorous running error bound,
//! certified or declined. A certified answer is the exact one (the sign of the
//! exact quantity is the sign of the computed value whenever the value lies
//! beyond its bound), so the robust forms answer bit for bit as without the
//! stage; a declined one falls back to the exact code (`crate::boxes::poly`).
//!
//! **The scene.** Every length (centres, half-extents, radius, the AABB's
//! corners) is scaled by one power of two `2^k` so that the largest lies in
//! `[1/2, 1)`: the signs asked for are those of positively homogeneous
//! quantities, unchanged by the scaling, and no value below can overflow. A
//! scaled length is exact unless it falls below `f64`'s normal range, where it
//! is within `2^−1074` of the exact one: every scaled length carries the
//! error [`ETA`].
//!
//! **The rotation.** [`rotation`] computes `R̃ ≈ R(q)` in `f64` within
//! [`ROTATION_ERROR`] per entry (derivation there), once per call and box.
//!
//! **The arithmetic.** [`Fe`] is a value with an absolute bound on its distance
//! to the exact quantity, propagated by standard forward error analysis (see
//! its methods); [`Fe::sign`] certifies a sign when the value lies beyond the
//! bound inflated by [`SLACK`] (which covers the rounding of the bounds
//! themselves) and [`ETA`] (underflow).

use crate::exact::frexp;
use crate::real::scale2;
use std::cmp::Ordering;

/// The unit roundoff of `f64`, `2^−53`: `|fl(x ∘ y) − x ∘ y| ≤ U |x ∘ y|`
/// for a result in the normal range.
const U: f64 = f64::EPSILON / 2.0;

/// The absolute error allowed for underflow, `2^−1022`: a rounded product (or
/// a product inside a bound) that falls below the normal range is off by at
/// most `2^−1075` beyond its relative error, and a length scaled into the
/// subnormal range by at most `2^−1074`. Each product adds `ETA` to its bound
/// (and each sum, for the product `U |x|` inside its bound), far more than
/// those losses. On a scene scaled to unit size it is negligible.
const ETA: f64 = f64::MIN_POSITIVE;

/// The inflation of a computed bound before it certifies: the bounds are
/// themselves rounded (each operation on them is off by at most a factor
/// `1 + U`, and `U |fl(x)|` stands for `U |x| ≤ U |fl(x)| / (1 − U)`), so a
/// bound formed in fewer than `2^20` operations is below the true one by a
/// factor of at most `1 + 2^−32`; `2^−30` covers it (and the rounding of the
/// multiplication by `SLACK`).
const SLACK: f64 = 1.0 + 1.0 / (1u64 << 30) as f64;

/// The error of every entry of [`rotation`]'s `R̃` against the exact `R(q)`:
/// `32 U = 2^−48`.
///
/// Derivation (`γ_k = k U / (1 − k U)`). `q` is scaled by a power of two so its
/// largest component lies in `[1, 2)` (`R` is unchanged: it is homogeneous of
/// degree 0); then `1 ≤ n = ‖q‖² < 16`.
/// - `ñ = ((w² + x²) + y²) + z²` (four products, three sums of non-negative
///   terms): `|ñ − n| ≤ γ_4 n`.
/// - `s̃ = fl(2 / ñ)` against `s = 2 / n ≤ 2`: `s̃ = s (n/ñ)(1 + δ)`, so
///   `|s̃ − s| ≤ γ_6 s`.
/// - Off the diagonal, `R_ij = s p` with `p = ab ± cd` (two distinct
///   components per product): `|p̃ − p| ≤ γ_2 (|ab| + |cd|) ≤ γ_2 n / 2` (as
///   `|ab| + |cd| ≤ (a² + b² + c² + d²)/2`), `|p| ≤ n/2`, so
///   `|fl(s̃ p̃) − s p| ≤ |s̃ − s||p̃| + s |p̃ − p| + U |s̃ p̃|
///   ≤ γ_6 (1 + γ_2) + γ_2 + U (1 + γ_8) ≈ 9 U`.
/// - On the diagonal, `R_ii = 1 − s a` with `a` a sum of two squares, `a ≤ n`,
///   `s a ≤ 2`: `|s̃ ã − s a| ≤ 2 γ_8`, its rounding `≤ 2 U (1 + γ_8)`, the
///   subtraction's rounding `≤ U (1 + 4 γ_8)`: `≈ 19 U`.
/// - Underflow: a component scaled below the normal range moves by at most
///   `2^−1074` (and `R` by at most 4 times that, as `|∂R/∂q| ≤ 4/‖q‖` and
///   `‖q‖ ≥ 1`), each product by `2^−1075`: below `2^−1060` in all.
///
/// So every entry is within `20 U` (second-order terms included); `32 U`
/// leaves room.
pub(super) const ROTATION_ERROR: f64 = 32.0 * U;

/// A value `v` computed in `f64` and a bound `e` with `|v − x| ≤ e` for the
/// exact quantity `x` it stands for (up to [`SLACK`] and [`ETA`], see
/// [`Fe::sign`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct Fe {
    v: f64,
    e: f64,
}

impl Fe {
    /// An exact value.
    #[inline(always)]
    const fn exact(v: f64) -> Self {
        Self { v, e: 0.0 }
    }

    /// A length of the scene scaled by `2^k` (exact, or within `2^−1074` when
    /// it falls below the normal range).
    #[inline(always)]
    fn length(x: f64, k: i32) -> Self {
        Self { v: scale2(x, k), e: ETA }
    }

    /// `x + y`: the errors add, and the rounding adds `U |x + y|`.
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        let v = self.v + o.v;
        Self { v, e: self.e + o.e + U * v.abs() + ETA }
    }

    /// `x − y`, as [`Fe::add`].
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        let v = self.v - o.v;
        Self { v, e: self.e + o.e + U * v.abs() + ETA }
    }

    /// `x y`: `|x̃ ỹ − x y| ≤ |x̃| e_y + |ỹ| e_x + e_x e_y`, the rounding adds
    /// `U |x̃ ỹ|` and underflow [`ETA`].
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let v = self.v * o.v;
        Self { v, e: self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + U * v.abs() + ETA }
    }

    /// `|x|` (1-Lipschitz: the bound stays).
    #[inline(always)]
    fn abs(self) -> Self {
        Self { v: self.v.abs(), e: self.e }
    }

    /// `max(x, 0)` (1-Lipschitz: the bound stays).
    #[inline(always)]
    fn pos(self) -> Self {
        Self { v: self.v.max(0.0), e: self.e }
    }

    /// `−x` (exact).
    #[inline(always)]
    fn neg(self) -> Self {
        Self { v: -self.v, e: self.e }
    }

    /// The exact quantity's sign when the value lies beyond its bound
    /// (inflated by [`SLACK`], plus [`ETA`]); `None` when it may be either, or
    /// when a number is not finite. Never `Equal`: a zero is never certified.
    #[inline(always)]
    fn sign(self) -> Option<Ordering> {
        let b = self.e * SLACK + ETA;
        if !(self.v.is_finite() && b.is_finite()) {
            None
        } else if self.v > b {
            Some(Ordering::Greater)
        } else if self.v < -b {
            Some(Ordering::Less)
        } else {
            None
        }
    }
}

/// A rotation's entries `r[row][column]` (axis `i` is column `i`), each with
/// its bound.
pub(super) type Rot = [[Fe; 3]; 3];

/// `R(q)` (the rotation of `q/‖q‖`) in `f64`, every entry within
/// [`ROTATION_ERROR`] of the exact one; `None` for a zero or non-finite `q`.
pub(super) fn rotation(q: &[f64; 4]) -> Option<Rot> {
    let m = q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    let k = 1 - frexp(m).1 as i32;
    let [w, x, y, z] = q.map(|c| scale2(c, k));
    let s = 2.0 / (((w * w + x * x) + y * y) + z * z);
    let r = [
        [1.0 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)],
        [s * (x * y + w * z), 1.0 - s * (x * x + z * z), s * (y * z - w * x)],
        [s * (x * z - w * y), s * (y * z + w * x), 1.0 - s * (x * x + y * y)],
    ];
    Some(r.map(|row| row.map(|v| Fe { v, e: ROTATION_ERROR })))
}

/// The identity, exact.
const IDENTITY: Rot = {
    let (o, z) = (Fe::exact(1.0), Fe::exact(0.0));
    [[o, z, z], [z, o, z], [z, z, o]]
};

/// The exponent `k` that brings the largest of `lengths` into `[1/2, 1)`
/// (0 when all are zero).
fn unit_exponent(lengths: &[f64]) -> i32 {
    let m = lengths.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m > 0.0 { -(frexp(m).1 as i32) } else { 0 }
}

/// `x · y`.
#[inline(always)]
fn dot(x: [Fe; 3], y: [Fe; 3]) -> Fe {
    x[0].mul(y[0]).add(x[1].mul(y[1])).add(x[2].mul(y[2]))
}

/// Column `i` of `r`.
#[inline(always)]
fn col(r: &Rot, i: usize) -> [Fe; 3] {
    [r[0][i], r[1][i], r[2][i]]
}

/// The separating-axis test of two boxes, certified or declined:
/// `Some(false)` when some axis certainly separates, `Some(true)` when every
/// one of the 15 certainly does not, `None` otherwise.
///
/// With `A = R_a`, `B = R_b` exact rotations, `C = Aᵀ B`, `t = Aᵀ d`, the
/// separation along an axis `L`, `S(L) = |L · d| − Σ_i h^a_i |L · A_i| −
/// Σ_j h^b_j |L · B_j|`, is positively homogeneous in `L`, so its sign along
/// the exact code's `M_j × M_k = ‖q‖⁴ A_i` (or `‖q_a‖²‖q_b‖² A_i × B_j`) is its
/// sign along `A_i` (or `A_i × B_j`); there the orthonormality of `A`, `B` and
/// `C` (all proper rotations) gives Ericson's forms exactly:
/// `S(A_i) = |t_i| − h^a_i − Σ_j h^b_j |C_ij|`,
/// `S(B_j) = |B_j · d| − Σ_i h^a_i |C_ij| − h^b_j`, and
/// `S(A_i × B_j) = |t_{i2} C_{i1 j} − t_{i1} C_{i2 j}| − h^a_{i1} |C_{i2 j}| −
/// h^a_{i2} |C_{i1 j}| − h^b_{j1} |C_{i j2}| − h^b_{j2} |C_{i j1}|` (indices
/// cyclic). These are evaluated on `R̃` with their bounds. Linear in the
/// half-extents, so a negative `h^b` (a malformed AABB) is the same formula.
fn sat(ra: &Rot, rb: &Rot, d: [Fe; 3], ha: [Fe; 3], hb: [Fe; 3]) -> Option<bool> {
    let c: Rot = std::array::from_fn(|i| std::array::from_fn(|j| dot(col(ra, i), col(rb, j))));
    let ac = c.map(|row| row.map(Fe::abs));
    let t: [Fe; 3] = std::array::from_fn(|i| dot(col(ra, i), d));
    let mut undecided = false;
    // Some(true) (separates) answers at once; an undecided axis is noted.
    let mut decide = |s: Fe| match s.sign() {
        Some(Ordering::Greater) => true,
        Some(_) => false,
        None => {
            undecided = true;
            false
        }
    };
    for i in 0..3 {
        let sa = t[i].abs().sub(ha[i]).sub(dot(hb, ac[i]));
        if decide(sa) {
            return Some(false);
        }
        let sb = dot(col(rb, i), d).abs().sub(dot(ha, col(&ac, i))).sub(hb[i]);
        if decide(sb) {
            return Some(false);
        }
    }
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            let along = t[i2].mul(c[i1][j]).sub(t[i1].mul(c[i2][j])).abs();
            let reach_a = ha[i1].mul(ac[i2][j]).add(ha[i2].mul(ac[i1][j]));
            let reach_b = hb[j1].mul(ac[i][j2]).add(hb[j2].mul(ac[i][j1]));
            if decide(along.sub(reach_a).sub(reach_b)) {
                return Some(false);
            }
        }
    }
    if undecided { None } else { Some(true) }
}

/// [`super::test_box_box`]'s answer when certain: quaternions `q_a`, `q_b`
/// (finite, non-zero) and lengths `[c_a, c_b, h_a, h_b]` (finite, `h ≥ 0`).
pub(super) fn box_box(qa: &[f64; 4], qb: &[f64; 4], lengths: &[f64; 12]) -> Option<bool> {
    let (ra, rb) = (rotation(qa)?, rotation(qb)?);
    let k = unit_exponent(lengths);
    let l = lengths.map(|x| Fe::length(x, k));
    let d = [0, 1, 2].map(|i| l[3 + i].sub(l[i]));
    sat(&ra, &rb, d, [l[6], l[7], l[8]], [l[9], l[10], l[11]])
}

/// [`super::test_box_aabb`]'s answer when certain: quaternion `q` (finite,
/// non-zero) and lengths `[c, h, min, max]` (finite, `h ≥ 0`). The exact
/// code's separation along `L` is `|L · (min + max − 2c)| − 2 Σ h_i |L · A_i| −
/// Σ_k (max_k − min_k) |L_k|`: [`sat`]'s with `d = min + max − 2c`,
/// `h^a = 2h`, `h^b = max − min` and `B` the identity.
pub(super) fn box_aabb(q: &[f64; 4], lengths: &[f64; 12]) -> Option<bool> {
    let ra = rotation(q)?;
    let k = unit_exponent(lengths);
    let l = lengths.map(|x| Fe::length(x, k));
    let d = [0, 1, 2].map(|i| l[6 + i].add(l[9 + i]).sub(l[i]).sub(l[i]));
    let ha = [0, 1, 2].map(|i| l[3 + i].add(l[3 + i]));
    let hb = [0, 1, 2].map(|i| l[9 + i].sub(l[6 + i]));
    sat(&ra, &IDENTITY, d, ha, hb)
}

/// What the stage settles of a sphere–box contact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct SphereBox {
    /// Certainly no contact: `Σ_i max(|u_i| − h_i, 0)² > r²`.
    pub apart: bool,
    /// The exact slab classification (`sphere_box::classify`), when every
    /// axis is certain.
    pub side: Option<[i8; 3]>,
    /// Certainly `Σ_i max(|u_i| − h_i, 0)² < r²` (the exact `outside_reach`
    /// is negative).
    pub within: bool,
    /// `sphere_box::nearest_face` (axis, side, tie), when every order of the
    /// gaps `h_i − |u_i|` and the sign of `u` on the nearest axis are certain
    /// (then nothing ties).
    pub nearest: Option<(usize, i8, bool)>,
}

/// [`super::contact_sphere_box`]'s decisions when certain: quaternion `q`
/// (finite, non-zero) and lengths `[m, c, h, r]` (finite, `h ≥ 0`), with
/// `u = Rᵀ (m − c)`. The exact code's slab test along axis `i` is the sign of
/// `±M_i · (m − c) − n h_i = n (±u_i − h_i)`, and its reach test the sign of
/// `Σ_{outside} (s_i M_i · (m − c) − n h_i)² − n² r² =
/// n² (Σ_i max(|u_i| − h_i, 0)² − r²)` (a term is zero exactly when the centre
/// is within the slab): both are evaluated on `R̃` with their bounds
/// (`max(·, 0)` is 1-Lipschitz). From inside, the exact code orders the gaps
/// `n h_i − |M_i · (m − c)| = n (h_i − |u_i|)` and takes the sign of
/// `M_i · (m − c) = n u_i`: the same on `R̃`.
pub(super) fn sphere_box(q: &[f64; 4], lengths: &[f64; 10]) -> SphereBox {
    let Some(rot) = rotation(q) else { return SphereBox::default() };
    let k = unit_exponent(lengths);
    let l = lengths.map(|x| Fe::length(x, k));
    let d = [0, 1, 2].map(|i| l[i].sub(l[3 + i]));
    let u: [Fe; 3] = std::array::from_fn(|i| dot(col(&rot, i), d));
    let side = |i: usize| match (u[i].sub(l[6 + i]).sign(), u[i].neg().sub(l[6 + i]).sign()) {
        (Some(Ordering::Greater), _) => Some(1),
        (Some(Ordering::Less), Some(Ordering::Greater)) => Some(-1),
        (Some(Ordering::Less), Some(Ordering::Less)) => Some(0),
        _ => None,
    };
    let excess = |i: usize| u[i].abs().sub(l[6 + i]).pos();
    let sq = |x: Fe| x.mul(x);
    let reach = sq(excess(0)).add(sq(excess(1))).add(sq(excess(2))).sub(sq(l[9]));
    let sides = [side(0), side(1), side(2)];
    // nearest_face's loop on the signs of g_j − g_best (`n` times the exact
    // code's `gap_order`), then the sign of `u_best` (its `coord`).
    let gaps = [0, 1, 2].map(|i| l[6 + i].sub(u[i].abs()));
    let order = |i: usize, j: usize| gaps[i].sub(gaps[j]).sign();
    let nearest = || {
        let mut best = 0;
        for j in 1..3 {
            if order(j, best)? == Ordering::Less {
                best = j;
            }
        }
        for j in (0..3).filter(|j| *j != best) {
            order(j, best)?;
        }
        let side = if u[best].sign()? == Ordering::Greater { 1 } else { -1 };
        Some((best, side, false))
    };
    SphereBox {
        apart: reach.sign() == Some(Ordering::Greater),
        side: if sides.iter().all(Option::is_some) { Some(sides.map(|s| s.unwrap_or(0))) } else { None },
        within: reach.sign() == Some(Ordering::Less),
        nearest: nearest(),
    }
}
