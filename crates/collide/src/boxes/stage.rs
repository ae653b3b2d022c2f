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

use crate::exact::{Sign, frexp, ldexp};
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
pub(crate) struct Fe {
    v: f64,
    e: f64,
}

impl Fe {
    /// The value and its bound.
    #[inline(always)]
    pub(crate) fn parts(&self) -> (f64, f64) {
        (self.v, self.e)
    }

    /// An exact value.
    #[inline(always)]
    const fn exact(v: f64) -> Self {
        Self { v, e: 0.0 }
    }

    /// A length of the scene scaled by `2^k` (exact, or within `2^−1074` when
    /// it falls below the normal range).
    #[inline(always)]
    fn length(x: f64, k: i32) -> Self {
        Self { v: ldexp(x, i64::from(k)), e: ETA }
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
pub(crate) type Rot = [[Fe; 3]; 3];

/// `R(q)` (the rotation of `q/‖q‖`) in `f64`, every entry within
/// [`ROTATION_ERROR`] of the exact one; `None` for a zero or non-finite `q`.
pub(crate) fn rotation(q: &[f64; 4]) -> Option<Rot> {
    let m = q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    let k = 1 - frexp(m).1 as i32;
    let [w, x, y, z] = q.map(|c| ldexp(c, i64::from(k)));
    let s = 2.0 / (((w * w + x * x) + y * y) + z * z);
    // Off the diagonal, `s (ab ± cd)` with its own bound (see
    // OFF_DIAGONAL_ERROR): a small entry is known to a small error.
    let off = |ab: f64, cd: f64, v: f64| Fe {
        v,
        e: ROTATION_ERROR.min(OFF_DIAGONAL_ERROR * s * (ab.abs() + cd.abs()) + ETA),
    };
    let diag = |v: f64| Fe { v, e: ROTATION_ERROR };
    let (xy, wz, xz, wy, yz, wx) = (x * y, w * z, x * z, w * y, y * z, w * x);
    Some([
        [diag(1.0 - s * (y * y + z * z)), off(xy, wz, s * (xy - wz)), off(xz, wy, s * (xz + wy))],
        [off(xy, wz, s * (xy + wz)), diag(1.0 - s * (x * x + z * z)), off(yz, wx, s * (yz - wx))],
        [off(xz, wy, s * (xz - wy)), off(yz, wx, s * (yz + wx)), diag(1.0 - s * (x * x + y * y))],
    ])
}

/// The relative error of an entry of [`rotation`]'s `R̃` off the diagonal,
/// `16 U`, against `s̃ P̃` (`P = |ab| + |cd|` of its products, both as
/// computed), plus [`ETA`]: a small entry (a rotation near a quarter turn,
/// a quaternion with components of very different sizes) is then known to a
/// small error, where [`ROTATION_ERROR`] is absolute.
///
/// Derivation (as for [`ROTATION_ERROR`], `γ_k = k U / (1 − k U)`): the
/// entry is `s p` with `p = ab ± cd`, `|p̃ − p| ≤ γ_2 P` (two products and a
/// sum), `|p̃| ≤ (1 + γ_2) P`, `|s̃ − s| ≤ γ_6 s`, so
/// `|fl(s̃ p̃) − s p| ≤ |s̃ − s||p̃| + s |p̃ − p| + U |s̃ p̃|
/// ≤ s P (γ_6 (1 + γ_2) + γ_2 + U (1 + γ_6)(1 + γ_2)) ≈ 9 U s P`. The
/// computed `s̃ P̃` is at least `(1 − γ_8) s P`, so `16 U s̃ P̃` covers it
/// with room (and the rounding of the bound's own product, under [`SLACK`]).
/// Underflow (a product of components below `2^−511`, a component scaled
/// below the normal range) moves the entry by at most a few `2^−1074`:
/// [`ETA`] covers it.
const OFF_DIAGONAL_ERROR: f64 = 16.0 * U;

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
/// `Ok(false)` when some axis certainly separates, `Ok(true)` when every
/// one of the 15 certainly does not, otherwise `Err` of the mask of the axes
/// it could not decide (bit `i`: `A_i`; `3 + j`: `B_j`; `6 + 3i + j`:
/// `A_i × B_j`). The axes in `zero` are known to be the zero vector (they
/// separate nothing) and are skipped.
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
fn sat(ra: &Rot, rb: &Rot, d: [Fe; 3], ha: [Fe; 3], hb: [Fe; 3], zero: u16) -> Result<bool, u16> {
    let c: Rot = std::array::from_fn(|i| std::array::from_fn(|j| dot(col(ra, i), col(rb, j))));
    let ac = c.map(|row| row.map(Fe::abs));
    let t: [Fe; 3] = std::array::from_fn(|i| dot(col(ra, i), d));
    let mut undecided = 0u16;
    // Some(true) (separates) answers at once; an undecided axis is noted.
    let mut decide = |s: Fe, bit: usize| match s.sign() {
        Some(Ordering::Greater) => true,
        Some(_) => false,
        None => {
            undecided |= 1 << bit;
            false
        }
    };
    for i in 0..3 {
        let sa = t[i].abs().sub(ha[i]).sub(dot(hb, ac[i]));
        if decide(sa, i) {
            return Ok(false);
        }
        let sb = dot(col(rb, i), d).abs().sub(dot(ha, col(&ac, i))).sub(hb[i]);
        if decide(sb, 3 + i) {
            return Ok(false);
        }
    }
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let bit = 6 + 3 * i + j;
            if zero & (1 << bit) != 0 {
                continue;
            }
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            let along = t[i2].mul(c[i1][j]).sub(t[i1].mul(c[i2][j])).abs();
            let reach_a = ha[i1].mul(ac[i2][j]).add(ha[i2].mul(ac[i1][j]));
            let reach_b = hb[j1].mul(ac[i][j2]).add(hb[j2].mul(ac[i][j1]));
            if decide(along.sub(reach_a).sub(reach_b), bit) {
                return Ok(false);
            }
        }
    }
    if undecided == 0 { Ok(true) } else { Err(undecided) }
}

/// Every one of [`sat`]'s 15 axes undecided.
pub(super) const ALL_AXES: u16 = (1 << 15) - 1;

/// The cross axes `A_i × B_i` (bits `6 + 4i` of [`sat`]'s mask), exactly zero
/// when both boxes have the same rotation.
const SAME_AXIS_CROSSES: u16 = (1 << 6) | (1 << 10) | (1 << 14);

/// Whether two quaternions are equal or opposite component for component
/// (as numbers: `0 = −0`): then they are exactly the same rotation.
#[allow(clippy::float_cmp, reason = "exact equality is the point: equal quaternions are one rotation")]
fn same_rotation(qa: &[f64; 4], qb: &[f64; 4]) -> bool {
    qa == qb || qa.map(|x| -x) == *qb
}

/// [`super::test_box_box`]'s answer when certain, or the mask of the axes
/// [`sat`] left undecided (bit `i`: `A_i`; `3 + j`: `B_j`; `6 + 3i + j`:
/// `A_i × B_j`), each of which the exact code must decide: the others
/// certainly do not separate. Quaternions `q_a`, `q_b` (finite, non-zero),
/// lengths `[c_a, c_b, h_a, h_b]` (finite, `h ≥ 0`). Two quaternions equal
/// or opposite component for component are the same rotation, so
/// `A_i × B_i` is exactly the zero vector there, and a zero axis separates
/// nothing (its separation is `0 > 0`, false): those axes are skipped.
pub(super) fn box_box_axes(qa: &[f64; 4], qb: &[f64; 4], lengths: &[f64; 12]) -> Result<bool, u16> {
    let (Some(ra), Some(rb)) = (rotation(qa).filter(|_| enabled()), rotation(qb)) else { return Err(ALL_AXES) };
    let k = unit_exponent(lengths);
    let l = lengths.map(|x| Fe::length(x, k));
    let d = [0, 1, 2].map(|i| l[3 + i].sub(l[i]));
    let same = same_rotation(qa, qb);
    let zero = if same { SAME_AXIS_CROSSES } else { 0 };
    sat(&ra, &rb, d, [l[6], l[7], l[8]], [l[9], l[10], l[11]], zero)
}

/// [`super::test_box_box`]'s answer when certain: quaternions `q_a`, `q_b`
/// (finite, non-zero) and lengths `[c_a, c_b, h_a, h_b]` (finite, `h ≥ 0`).
#[cfg(test)]
pub(super) fn box_box(qa: &[f64; 4], qb: &[f64; 4], lengths: &[f64; 12]) -> Option<bool> {
    box_box_axes(qa, qb, lengths).ok()
}

/// [`super::test_box_aabb`]'s answer when certain: quaternion `q` (finite,
/// non-zero) and lengths `[c, h, min, max]` (finite, `h ≥ 0`). The exact
/// code's separation along `L` is `|L · (min + max − 2c)| − 2 Σ h_i |L · A_i| −
/// Σ_k (max_k − min_k) |L_k|`: [`sat`]'s with `d = min + max − 2c`,
/// `h^a = 2h`, `h^b = max − min` and `B` the identity.
#[cfg(test)]
pub(super) fn box_aabb(q: &[f64; 4], lengths: &[f64; 12]) -> Option<bool> {
    box_aabb_axes(q, lengths).ok()
}

/// As [`box_box_axes`], for [`super::test_box_aabb`] (`B` the identity).
pub(super) fn box_aabb_axes(q: &[f64; 4], lengths: &[f64; 12]) -> Result<bool, u16> {
    let Some(ra) = rotation(q).filter(|_| enabled()) else { return Err(ALL_AXES) };
    let k = unit_exponent(lengths);
    let l = lengths.map(|x| Fe::length(x, k));
    let d = [0, 1, 2].map(|i| l[6 + i].add(l[9 + i]).sub(l[i]).sub(l[i]));
    let ha = [0, 1, 2].map(|i| l[3 + i].add(l[3 + i]));
    let hb = [0, 1, 2].map(|i| l[9 + i].sub(l[6 + i]));
    sat(&ra, &IDENTITY, d, ha, hb, 0)
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
    /// The slab classification of each axis alone, where certain.
    pub sides: [Option<i8>; 3],
    /// The sign of `(h_i − |u_i|) − (h_j − |u_j|)` (`sphere_box::gap_order`),
    /// where certain (never `Equal`).
    pub orders: [[Option<Ordering>; 3]; 3],
    /// The sign of `u_i` (`sphere_box::coord`), where certain (never `Equal`).
    pub coords: [Option<Ordering>; 3],
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
    let Some(rot) = rotation(q).filter(|_| enabled()) else { return SphereBox::default() };
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
        sides,
        orders: std::array::from_fn(|i| std::array::from_fn(|j| if i == j { None } else { order(i, j) })),
        coords: u.map(Fe::sign),
    }
}

impl Fe {
    /// `min(x, y)`: 1-Lipschitz in each argument, so the larger bound holds.
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Self { v: self.v.min(o.v), e: self.e.max(o.e) }
    }

    /// `max(x, y)`, as [`Fe::min`].
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        Self { v: self.v.max(o.v), e: self.e.max(o.e) }
    }
}

/// `x + y` of vectors.
#[inline(always)]
fn add3(x: [Fe; 3], y: [Fe; 3]) -> [Fe; 3] {
    [x[0].add(y[0]), x[1].add(y[1]), x[2].add(y[2])]
}

/// `x − y` of vectors.
#[inline(always)]
fn sub3(x: [Fe; 3], y: [Fe; 3]) -> [Fe; 3] {
    [x[0].sub(y[0]), x[1].sub(y[1]), x[2].sub(y[2])]
}

/// `x s` of a vector by a scalar.
#[inline(always)]
fn scale3(x: [Fe; 3], s: Fe) -> [Fe; 3] {
    [x[0].mul(s), x[1].mul(s), x[2].mul(s)]
}

/// The values of a vector (no bounds).
#[inline(always)]
fn values(x: [Fe; 3]) -> [f64; 3] {
    x.map(|c| c.v)
}

/// Nearly the closest points of two segments `[p0, p1]`, `[q0, q1]` in plain
/// `f64` (Ericson's, §5.1.9, without epsilon): any pair will do for
/// [`capsule_box_edges_apart`], which only takes their difference as a
/// direction to separate along.
fn nearly_closest(p0: [f64; 3], p1: [f64; 3], q0: [f64; 3], q1: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let at = |a: [f64; 3], d: [f64; 3], t: f64| [a[0] + d[0] * t, a[1] + d[1] * t, a[2] + d[2] * t];
    let clamp01 = |x: f64| if x.is_finite() { x.clamp(0.0, 1.0) } else { 0.0 };
    let (d1, d2, r) = (sub(p1, p0), sub(q1, q0), sub(p0, q0));
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    let (s, t) = if !(a > 0.0) && !(e > 0.0) {
        (0.0, 0.0)
    } else if !(a > 0.0) {
        (0.0, clamp01(f / e))
    } else {
        let c = dot(d1, r);
        if !(e > 0.0) {
            (clamp01(-c / a), 0.0)
        } else {
            let b = dot(d1, d2);
            let denom = a * e - b * b;
            let s0 = if denom > 0.0 { clamp01((b * f - c * e) / denom) } else { 0.0 };
            let t0 = (b * s0 + f) / e;
            if t0 < 0.0 {
                (clamp01(-c / a), 0.0)
            } else if t0 > 1.0 {
                (clamp01((b - c) / a), 1.0)
            } else {
                (s0, t0)
            }
        }
    };
    (at(p0, d1, s), at(q0, d2, t))
}

/// The corner signs of the box's edges in `capsule_polytope::box_edges`'
/// order: edge `e` runs along axis `i = e / 4` at the signs `CORNERS[e % 4]`
/// of axes `i + 1`, `i + 2`.
const CORNERS: [[f64; 2]; 4] = [[1.0, 1.0], [1.0, -1.0], [-1.0, 1.0], [-1.0, -1.0]];

/// The edges of the box (quaternion `q`, finite and non-zero) that the
/// segment `[p0, p1]` is certainly farther than `r` from, as a mask (bit `e`
/// for edge `e` in `capsule_polytope::box_edges`' order, `E_0,1 = c + Σ s h ∓
/// h_i A_i` for the exact `R(q)`): lengths `[p0, p1, c, h, r]` (finite,
/// `h ≥ 0`, `r ≥ 0`). For any non-zero `v`, every point `x` of the segment
/// and `y` of the edge have `‖x − y‖ ≥ v · (x − y) / ‖v‖ ≥ (min_k v · p_k −
/// max_k v · E_k) / ‖v‖`; so a positive `S = min_k v · p_k − max_k v · E_k`
/// with `S² > r² ‖v‖²` puts the edge out of reach, as the exact
/// `capsule_polytope::edge_reach` would find. `v` is the difference of the
/// two segments' nearly closest points computed in plain `f64` (taken as an
/// exact vector: any direction is sound; this one is nearly the best), `S`
/// and `‖v‖²` are evaluated with their bounds.
pub(super) fn capsule_box_edges_apart(q: &[f64; 4], lengths: &[f64; 13]) -> u16 {
    let Some(rot) = rotation(q).filter(|_| enabled()) else { return 0 };
    let k = unit_exponent(lengths);
    let l = lengths.map(|x| Fe::length(x, k));
    let (p0, p1, c) = ([l[0], l[1], l[2]], [l[3], l[4], l[5]], [l[6], l[7], l[8]]);
    let (h, r) = ([l[9], l[10], l[11]], l[12]);
    let mut apart = 0u16;
    for e in 0..12 {
        let (i, [sj, sk]) = (e / 4, CORNERS[e % 4]);
        let (j, jk) = ((i + 1) % 3, (i + 2) % 3);
        let corner =
            add3(scale3(col(&rot, j), h[j].mul(Fe::exact(sj))), scale3(col(&rot, jk), h[jk].mul(Fe::exact(sk))));
        let mid = add3(c, corner);
        let half = scale3(col(&rot, i), h[i]);
        let (e0, e1) = (sub3(mid, half), add3(mid, half));
        let (x, y) = nearly_closest(values(p0), values(p1), values(e0), values(e1));
        let v = [0, 1, 2].map(|n| Fe::exact(x[n] - y[n]));
        if !v.iter().all(|c| c.v.is_finite()) || v.iter().all(|c| c.v == 0.0) {
            continue;
        }
        let sep = dot(v, p0).min(dot(v, p1)).sub(dot(v, e0).max(dot(v, e1)));
        let reach = sep.mul(sep).sub(r.mul(r).mul(dot(v, v)));
        if sep.sign() == Some(Ordering::Greater) && reach.sign() == Some(Ordering::Greater) {
            apart |= 1 << e;
        }
    }
    apart
}

#[cfg(test)]
thread_local! {
    /// Tests turn the stage off to compare with the exact code alone.
    static DISABLED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Whether the stage answers (always, except in a test's [`without`]).
#[inline(always)]
fn enabled() -> bool {
    #[cfg(test)]
    {
        !DISABLED.with(std::cell::Cell::get)
    }
    #[cfg(not(test))]
    {
        true
    }
}

/// `f()` with the stage turned off on this thread: the exact code alone.
#[cfg(test)]
pub(super) fn without<R>(f: impl FnOnce() -> R) -> R {
    DISABLED.with(|d| d.set(true));
    let r = f();
    DISABLED.with(|d| d.set(false));
    r
}

/// The certified sign `o` as an exact [`Sign`], or `exact()` when the stage
/// could not certify it (or is off).
#[inline(always)]
pub(super) fn or_exact(o: Option<Ordering>, exact: impl FnOnce() -> Sign) -> Sign {
    if !enabled() {
        return exact();
    }
    match o {
        Some(Ordering::Greater) => Sign::Positive,
        Some(Ordering::Less) => Sign::Negative,
        _ => exact(),
    }
}

/// The lengths scaled to unit size, each with its bound.
#[inline(always)]
fn scene<const K: usize>(lengths: &[f64; K]) -> [Fe; K] {
    let k = unit_exponent(lengths);
    lengths.map(|x| Fe::length(x, k))
}

/// Three consecutive lengths from `i`.
#[inline(always)]
fn at<const K: usize>(l: &[Fe; K], i: usize) -> [Fe; 3] {
    [l[i], l[i + 1], l[i + 2]]
}

/// `x × y`.
#[inline(always)]
fn cross(x: [Fe; 3], y: [Fe; 3]) -> [Fe; 3] {
    [x[1].mul(y[2]).sub(x[2].mul(y[1])), x[2].mul(y[0]).sub(x[0].mul(y[2])), x[0].mul(y[1]).sub(x[1].mul(y[0]))]
}

/// The signs [`super::contact_capsule_capsule`] decides with, where certain.
#[derive(Clone, Copy, Debug)]
pub(super) struct CapsulePair {
    /// `capsule_capsule::critical` with the weights `[0, 0, 1]` (`denom`),
    /// `[1, 0, 0]` (`s_num`), `[−1, 0, 1]`, `[0, 1, 0]` (`t_num`) and
    /// `[0, −1, 1]`, in that order.
    pub critical: [Option<Ordering>; 5],
    /// `capsule_capsule::skew_reach`.
    pub skew: Option<Ordering>,
}

/// [`CapsulePair`] of lengths `[A0, A1, B0, B1, r_a, r_b]` (finite): the
/// same polynomials (homogeneous in the lengths) on the scene scaled to unit
/// size, each with its bound.
pub(super) fn capsule_capsule(lengths: &[f64; 14]) -> CapsulePair {
    let l = scene(lengths);
    let (da, db, r) = (sub3(at(&l, 3), at(&l, 0)), sub3(at(&l, 9), at(&l, 6)), sub3(at(&l, 0), at(&l, 6)));
    let (a, e, b) = (dot(da, da), dot(db, db), dot(da, db));
    let (c, f) = (dot(da, r), dot(db, r));
    let denom = a.mul(e).sub(b.mul(b));
    let s = b.mul(f).sub(c.mul(e));
    let t = a.mul(f).sub(b.mul(c));
    let n = cross(da, db);
    let nr = dot(n, r);
    let reach = l[12].add(l[13]);
    let skew = nr.mul(nr).sub(reach.mul(reach).mul(dot(n, n)));
    CapsulePair { critical: [denom, s, denom.sub(s), t, denom.sub(t)].map(Fe::sign), skew: skew.sign() }
}

/// `(m − a) · (b − a)` (`sphere_capsule::along`) of lengths `[m, a, b]`,
/// where certain.
pub(super) fn along(lengths: &[f64; 9]) -> Option<Ordering> {
    let l = scene(lengths);
    dot(sub3(at(&l, 0), at(&l, 3)), sub3(at(&l, 6), at(&l, 3))).sign()
}

/// `‖m − e‖² − (r_a + r_b)²` (`sphere_capsule::point_reach`) of lengths
/// `[m, e, r_a, r_b]`, where certain.
pub(super) fn point_reach(lengths: &[f64; 8]) -> Option<Ordering> {
    let l = scene(lengths);
    let v = sub3(at(&l, 0), at(&l, 3));
    let r = l[6].add(l[7]);
    dot(v, v).sub(r.mul(r)).sign()
}

/// `‖(m − a) × (b − a)‖² − (r_a + r_b)² ‖b − a‖²`
/// (`sphere_capsule::line_reach`) of lengths `[m, a, b, r_a, r_b]`, where
/// certain.
pub(super) fn line_reach(lengths: &[f64; 11]) -> Option<Ordering> {
    let l = scene(lengths);
    let (v, d) = (sub3(at(&l, 0), at(&l, 3)), sub3(at(&l, 6), at(&l, 3)));
    let x = cross(v, d);
    let r = l[9].add(l[10]);
    dot(x, x).sub(r.mul(r).mul(dot(d, d))).sign()
}

/// `n_1 d_2 − n_2 d_1` (`capsule_capsule::distance_order`) of lengths
/// `[p_1, a_1, b_1, p_2, a_2, b_2]`, each feature a line (`true`) or its end
/// `a`, where certain.
pub(super) fn distance_order(lengths: &[f64; 18], line: [bool; 2]) -> Option<Ordering> {
    let l = scene(lengths);
    let part = |o: usize, line: bool| {
        let v = sub3(at(&l, o), at(&l, o + 3));
        if line {
            let d = sub3(at(&l, o + 6), at(&l, o + 3));
            let x = cross(v, d);
            (dot(x, x), dot(d, d))
        } else {
            (dot(v, v), Fe::exact(1.0))
        }
    };
    let ((n1, d1), (n2, d2)) = (part(0, line[0]), part(9, line[1]));
    n1.mul(d2).sub(n2.mul(d1)).sign()
}

/// What the stage knows of a least-push problem's candidates
/// (`super::box_contact::least_push`): for each of its `N` axes, `‖L'‖²`,
/// the push's numerator `o'` both ways and `L' · w` for the vectors `w` the
/// exact code takes signs along, with their bounds, where the exact code's
/// `L` is a positive multiple of `L'` and its `o` the same positive multiple
/// of `o'` for every candidate (see [`box_box_contact`] and
/// [`capsule_box_contact`]): so every sign the exact code takes (`‖L‖² > 0`,
/// the sign of `o`, `o_1² ‖L_2‖² − o_2² ‖L_1‖²`, `dir L · w`) is the sign of
/// the same expression in `L'` and `o'`, evaluated here in the frame of the
/// box on `R̃` (rotations are orthonormal: the exact identities below) with
/// its bound.
#[derive(Clone, Copy, Debug)]
pub(super) struct Pushes<const N: usize> {
    /// Per axis: `‖L'‖²`, `o'` for `dir = +1`, `−1`, and `L' · w` for up to
    /// six vectors `w`.
    axes: [(Fe, [Fe; 2], [Fe; 6]); N],
    /// Per axis, whether it is non-zero where known exactly.
    nonzero: [Option<bool>; N],
    /// Per axis and vector `w`, the sign of `L' · w` where known exactly:
    /// `Some(0)` perpendicular, `Some(1)` positive (the axis itself).
    exact_along: [[Option<i8>; 6]; N],
    /// The axis (`0..N`) and way (0: `+`, 1: `−`) of a candidate.
    axis_of: fn(&super::box_contact::Cand) -> (usize, usize),
    /// Per axis and way, a class where known exactly: candidates of one
    /// class are the same direction with the same push (two boxes of one
    /// rotation, see [`box_box_contact`]).
    class: Option<[[u8; 2]; N]>,
    /// Some axis certainly separates by more than a radius (see
    /// [`capsule_box_contact`]).
    far: bool,
}

/// The exact sign, where certain.
#[inline(always)]
fn certain(x: Fe) -> Option<Sign> {
    match x.sign() {
        Some(Ordering::Greater) => Some(Sign::Positive),
        Some(Ordering::Less) => Some(Sign::Negative),
        _ => None,
    }
}

impl<const N: usize> Pushes<N> {
    /// `o_c'² ‖L_d'‖² − o_d'² ‖L_c'‖²`.
    fn order(&self, c: (usize, usize), d: (usize, usize)) -> Fe {
        let ((x, u), (y, w)) = (c, d);
        let (oc, od) = (self.axes[x].1[u], self.axes[y].1[w]);
        oc.mul(oc).mul(self.axes[y].0).sub(od.mul(od).mul(self.axes[x].0))
    }

    /// Some axis certainly separates the features by more than the radius
    /// given (a capsule's axis and a box: no contact at all).
    pub(super) fn far(&self) -> bool {
        self.far
    }

    /// Some push certainly negative: the exact code finds the axes apart (it
    /// returns on the first negative push in its order; a zero axis has
    /// `o' = 0`, so a negative one is an axis).
    pub(super) fn apart(&self) -> bool {
        self.axes.iter().any(|(_, o, _)| o.iter().any(|o| o.sign() == Some(Ordering::Less)))
    }

    /// The exact least push when the stage alone settles it (`axes` the
    /// exact code's, all `N` in its order): every axis certainly non-zero,
    /// every push certainly positive, and the least computed push certainly
    /// below every other (so the exact loop ends there and nothing ties it).
    pub(super) fn least(&self, axes: &[super::box_contact::Cand]) -> Option<super::box_contact::Least> {
        use super::box_contact::Least;
        let ids: Vec<(usize, usize)> = axes.iter().map(|c| (self.axis_of)(c)).collect();
        for &(x, _) in &ids {
            let nonzero = self.nonzero[x].unwrap_or_else(|| self.axes[x].0.sign() == Some(Ordering::Greater));
            if !nonzero || self.axes[x].1.iter().any(|o| o.sign() != Some(Ordering::Greater)) {
                return None;
            }
        }
        let value = |(x, u): (usize, usize)| self.axes[x].1[u].v / self.axes[x].0.v.sqrt();
        // The first least computed push, in the exact code's order.
        let (mut best, mut least) = ((0, 0), f64::INFINITY);
        for (a, &(x, _)) in ids.iter().enumerate() {
            for u in 0..2 {
                let v = value((x, u));
                if v < least || (a, u) == (0, 0) {
                    (best, least) = ((a, u), v);
                }
            }
        }
        let b = (ids[best.0].0, best.1);
        let alone = ids
            .iter()
            .flat_map(|&(x, _)| [(x, 0), (x, 1)])
            .all(|c| c == b || self.order(c, b).sign() == Some(Ordering::Greater));
        let mut c = axes[best.0];
        c[9] = if best.1 == 0 { 1.0 } else { -1.0 };
        alone.then_some(Least::Touch { best: c, tie: false })
    }

    /// The signs of `dir L' · w` for candidate `c` (the exact code's
    /// `along`), where known exactly or certain.
    pub(super) fn along(&self, c: &super::box_contact::Cand) -> [Option<Sign>; 6] {
        let (x, u) = (self.axis_of)(c);
        let (dir, way) = if u == 0 { (Sign::Positive, 1.0) } else { (Sign::Negative, -1.0) };
        std::array::from_fn(|w| match self.exact_along[x][w] {
            Some(0) => Some(Sign::Zero),
            Some(_) => Some(dir),
            None => certain(self.axes[x].2[w].mul(Fe::exact(way))),
        })
    }
}

impl<const N: usize> super::box_contact::Hints for Pushes<N> {
    fn nonzero(&self, c: &super::box_contact::Cand) -> Option<bool> {
        let (x, _) = (self.axis_of)(c);
        self.nonzero[x].or_else(|| (self.axes[x].0.sign() == Some(Ordering::Greater)).then_some(true))
    }

    fn push(&self, c: &super::box_contact::Cand) -> Option<Sign> {
        let (x, u) = (self.axis_of)(c);
        certain(self.axes[x].1[u])
    }

    fn cmp(&self, c: &super::box_contact::Cand, d: &super::box_contact::Cand) -> Option<Sign> {
        let (c, d) = ((self.axis_of)(c), (self.axis_of)(d));
        if let Some(class) = &self.class
            && class[c.0][c.1] == class[d.0][d.1]
        {
            return Some(Sign::Zero);
        }
        certain(self.order(c, d))
    }

    fn same(&self, c: &super::box_contact::Cand, d: &super::box_contact::Cand) -> Option<bool> {
        let (c, d) = ((self.axis_of)(c), (self.axis_of)(d));
        let class = self.class.as_ref()?;
        (class[c.0][c.1] == class[d.0][d.1]).then_some(true)
    }
}

/// The first one-hot selector set among three, as an index.
#[inline(always)]
fn picked(s: &[f64]) -> usize {
    (0..3).find(|&i| s[i] != 0.0).unwrap_or(0)
}

/// The components `[i] = 0`, `[i + 1] = −v_{i+2}`, `[i + 2] = v_{i+1}` of
/// `e_i × v`.
#[inline(always)]
fn cross_unit(i: usize, v: [Fe; 3]) -> [Fe; 3] {
    let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
    let mut x = [Fe::exact(0.0); 3];
    x[i1] = v[i2].neg();
    x[i2] = v[i1];
    x
}

/// [`Pushes`] of [`super::contact_box_box`]: quaternions `q_a`, `q_b`
/// (finite, non-zero) and lengths `[c_a, c_b, h_a, h_b]` (finite, `h ≥ 0`);
/// `None` when the stage is off.
///
/// The exact code's axes are `M^a_i`, `M^b_j`, `M^a_i × M^b_j`
/// (`M = ‖q‖² R(q)`, candidates `[s_a, s_b, (face a, face b, cross), dir]`),
/// and its `o` is `‖q_a‖²‖q_b‖²` times the push along `dir L` times `‖L‖`:
/// with `L' = A_i`, `B_j`, `A_i × B_j` (`L` is `‖q_a‖⁴`, `‖q_b‖⁴`,
/// `‖q_a‖²‖q_b‖²` times it: the ratio `o / ‖L‖` is the same for all),
/// `o' = Σ_k h^a_k |L' · A_k| + Σ_k h^b_k |L' · B_k| + dir L' · (c_b − c_a)`.
/// Axes `0..3`: `A_i`; `3..6`: `B_j`; `6 + 3i + j`: `A_i × B_j`; the vectors
/// `w`: `A_0..2`, `B_0..2`.
///
/// In `a`'s frame, with `C = Aᵀ B` and `t = Aᵀ (c_b − c_a)` (exact
/// rotations: `A`, `B`, `C` orthonormal, proper): `A_i · A_k = δ_ik`,
/// `‖A_i‖ = 1`, `A_i · B_k = C_ik`, `A_i · d = t_i`; `B_j · A_k = C_kj`,
/// `B_j · B_k = δ_jk`; `A_i × B_j = e_i × C_{·j}`, so (indices cyclic)
/// `(A_i × B_j) · A_{i+1} = −C_{i+2 j}`, `· A_{i+2} = C_{i+1 j}`,
/// `· A_i = 0`, `· B_{j+1} = C_{i j+2}`, `· B_{j+2} = −C_{i j+1}`,
/// `· B_j = 0`, `‖A_i × B_j‖² = C_{i+1 j}² + C_{i+2 j}²` and
/// `· d = t_{i+2} C_{i+1 j} − t_{i+1} C_{i+2 j}` (Ericson's forms). Known
/// exactly: a face axis is never zero, `A_i × B_i` is zero when the
/// quaternions are equal or opposite component for component (the same
/// rotation), and the zeros and ones above.
pub(super) fn box_box_contact(qa: &[f64; 4], qb: &[f64; 4], lengths: &[f64; 12]) -> Option<Pushes<15>> {
    if !enabled() {
        return None;
    }
    let (ra, rb) = (rotation(qa)?, rotation(qb)?);
    let l = scene(lengths);
    let d = sub3(at(&l, 3), at(&l, 0));
    let (ha, hb) = (at(&l, 6), at(&l, 9));
    let c: Rot = std::array::from_fn(|i| std::array::from_fn(|j| dot(col(&ra, i), col(&rb, j))));
    let t: [Fe; 3] = std::array::from_fn(|i| dot(col(&ra, i), d));
    let (one, zero) = (Fe::exact(1.0), Fe::exact(0.0));
    let axes = std::array::from_fn(|x| {
        // L' · A_k, L' · B_k, L' · d and ‖L'‖².
        let (wa, wb, ld, n) = match x {
            0..3 => {
                let mut wa = [zero; 3];
                wa[x] = one;
                (wa, c[x], t[x], one)
            }
            3..6 => {
                let j = x - 3;
                let mut wb = [zero; 3];
                wb[j] = one;
                (col(&c, j), wb, dot(col(&rb, j), d), one)
            }
            _ => {
                let (i, j) = ((x - 6) / 3, (x - 6) % 3);
                let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
                let wa = cross_unit(i, col(&c, j));
                let mut wb = cross_unit(j, c[i]);
                wb = wb.map(Fe::neg);
                let ld = t[i2].mul(c[i1][j]).sub(t[i1].mul(c[i2][j]));
                (wa, wb, ld, c[i1][j].mul(c[i1][j]).add(c[i2][j].mul(c[i2][j])))
            }
        };
        let reach = (0..3).fold(zero, |s, k| s.add(ha[k].mul(wa[k].abs())).add(hb[k].mul(wb[k].abs())));
        (n, [reach.add(ld), reach.sub(ld)], [wa[0], wa[1], wa[2], wb[0], wb[1], wb[2]])
    });
    let same = same_rotation(qa, qb);
    let nonzero = std::array::from_fn(|x| match x {
        0..6 => Some(true),
        _ if same && (x - 6) / 3 == (x - 6) % 3 => Some(false),
        _ => None,
    });
    let exact_along = std::array::from_fn(|x| {
        std::array::from_fn(|w| match x {
            0..3 => (w < 3).then_some(i8::from(w == x)),
            3..6 => (w >= 3).then_some(i8::from(w == x)),
            _ => (w == (x - 6) / 3 || w == 3 + (x - 6) % 3).then_some(0),
        })
    });
    let axis_of = |c: &super::box_contact::Cand| {
        let (i, j) = (picked(&c[0..3]), picked(&c[3..6]));
        let x = if c[6] != 0.0 {
            i
        } else if c[7] != 0.0 {
            3 + j
        } else {
            6 + 3 * i + j
        };
        (x, usize::from(c[9] < 0.0))
    };
    // One rotation: B_k = A_k, and A_i × A_j = ±A_k (`+` for j = i + 1,
    // cyclic): each candidate is `±A_k` with the push of face `A_k` that way
    // (the push depends only on the direction). Class `2k + way`.
    let class = same.then(|| {
        std::array::from_fn(|x| {
            let (k, flip) = match x {
                0..3 => (x, false),
                3..6 => (x - 3, false),
                _ => {
                    let (i, j) = ((x - 6) / 3, (x - 6) % 3);
                    // i == j is no axis: a class of its own, never compared.
                    if i == j { (3 + x, true) } else { (3 - i - j, j != (i + 1) % 3) }
                }
            };
            [0, 1].map(|u| (2 * k + (u ^ usize::from(flip))) as u8)
        })
    });
    Some(Pushes { axes, nonzero, exact_along, axis_of, class, far: false })
}

/// [`Pushes`] of the capsule–box least push (`capsule_polytope::cb`):
/// quaternion `q` (finite, non-zero) and lengths `[p0, p1, c, h, r]`
/// (finite, `h ≥ 0`); `None` when the stage is off.
///
/// A negative `o'` is a gap: along `dir L'` the box reaches `L' · c + R`
/// (`R = Σ_k h_k |L' · A_k|`) and the axis starts at `min_i L' · p_i`, so
/// `o' = max_i L' · (c − p_i) + R` is minus the gap between them for
/// `dir = +1` (and likewise for `−1`), and the axis is at least
/// `−o' / ‖L'‖` from the box. So `o' < 0` with `o'² > r² ‖L'‖²` puts the
/// capsule (radius `r`) out of reach of the box: every end and every edge
/// the exact code tries is farther than `r`, and it answers no contact
/// ([`Pushes::far`]).
///
/// The exact code's axes are `M_j` and `D × M_j` (`D = p1 − p0`,
/// candidates `[s, _, (face, _, cross), dir]`) and its
/// `o = ‖q‖² max2x2(x_0, x_1) + 2 Σ_k h_k |L · M_k|`, `x_i = dir L · (c − p_i)`;
/// with `L' = A_j`, `D × A_j` (`L = ‖q‖² L'`),
/// `o = 2‖q‖⁴ o'` for `o' = max(x_0', x_1') + Σ_k h_k |L' · A_k|`. Axes
/// `0..3`: `A_j`; `3..6`: `D × A_j`; the vectors `w`: `A_0..2`, `D`.
///
/// In the box's frame (`D' = Aᵀ D`, `u_i = Aᵀ (c − p_i)`; exact rotations
/// are orthonormal and proper): `A_j · A_k = δ_jk`, `‖A_j‖ = 1`,
/// `A_j · (c − p_i) = u_{ij}`, `A_j · D = D'_j`; `D × A_j = D' × e_j`, whose
/// components are `[j] = 0`, `[j + 1] = D'_{j+2}`, `[j + 2] = −D'_{j+1}` (its
/// dot products with `A_k` and with `u_i`), `‖D × A_j‖² = D'_{j+1}² +
/// D'_{j+2}²` and `(D × A_j) · D = 0`. Known exactly: a face axis is never
/// zero, and those zeros and ones.
pub(super) fn capsule_box_contact(q: &[f64; 4], lengths: &[f64; 13]) -> Option<Pushes<6>> {
    if !enabled() {
        return None;
    }
    let rot = rotation(q)?;
    let l = scene(lengths);
    let (p0, p1, c, h) = (at(&l, 0), at(&l, 3), at(&l, 6), at(&l, 9));
    let frame = |v: [Fe; 3]| [0, 1, 2].map(|j| dot(col(&rot, j), v));
    let (dv, u0, u1) = (frame(sub3(p1, p0)), frame(sub3(c, p0)), frame(sub3(c, p1)));
    let (one, zero) = (Fe::exact(1.0), Fe::exact(0.0));
    let axes = std::array::from_fn(|x| {
        let (lv, n, ld) = if x < 3 {
            let mut lv = [zero; 3];
            lv[x] = one;
            (lv, one, dv[x])
        } else {
            let j = x - 3;
            (
                cross_unit(j, dv).map(Fe::neg),
                dv[(j + 1) % 3].mul(dv[(j + 1) % 3]).add(dv[(j + 2) % 3].mul(dv[(j + 2) % 3])),
                zero,
            )
        };
        let reach = (0..3).fold(zero, |s, k| s.add(h[k].mul(lv[k].abs())));
        let (x0, x1) = (dot(lv, u0), dot(lv, u1));
        let o = [x0.max(x1).add(reach), x0.neg().max(x1.neg()).add(reach)];
        (n, o, [lv[0], lv[1], lv[2], ld, zero, zero])
    });
    let nonzero = std::array::from_fn(|x| (x < 3).then_some(true));
    let exact_along = std::array::from_fn(|x| {
        std::array::from_fn(|w| match x {
            0..3 => (w < 3).then_some(i8::from(w == x)),
            _ => (w == x - 3 || w == 3).then_some(0),
        })
    });
    let axis_of =
        |c: &super::box_contact::Cand| (picked(&c[0..3]) + if c[6] != 0.0 { 0 } else { 3 }, usize::from(c[9] < 0.0));
    let r = l[12];
    let far = axes.iter().any(|(n, o, _): &(Fe, [Fe; 2], [Fe; 6])| {
        o.iter().any(|o| {
            o.sign() == Some(Ordering::Less) && o.mul(*o).sub(r.mul(r).mul(*n)).sign() == Some(Ordering::Greater)
        })
    });
    Some(Pushes { axes, nonzero, exact_along, axis_of, class: None, far })
}
