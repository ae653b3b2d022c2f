//! Bounding volumes of a point cloud, exactly: the tight AABB and the minimal
//! enclosing sphere.

use std::cell::OnceCell;

use dashu::base::{BitTest, Gcd, UnsignedAbs};
use dashu::integer::{IBig, UBig};

use super::error::RefereeError;
use super::exact::{Q, Root, V3, dot, round, sub, v3};
use crate::geom::{Aabb, Ball, P3};

/// Refuses an empty cloud or a non-finite coordinate.
fn check(points: &[P3]) -> Result<(), RefereeError> {
    if points.is_empty() {
        return Err(RefereeError::NoPoints { field: "a.points" });
    }
    if points.iter().flatten().any(|x| !x.is_finite()) {
        return Err(RefereeError::NonFinite { field: "a.points" });
    }
    Ok(())
}

/// The tight axis-aligned box of `points`: per axis, the least and the greatest
/// coordinate.
///
/// **Definition.** `min[k] = minᵢ pᵢ[k]`, `max[k] = maxᵢ pᵢ[k]` (the lecture's
/// expansion over the vertices). Comparing finite `f64` is exact and the extremes
/// are inputs, so the answer is exact with no rounding at all.
///
/// **Degenerate input.** One point gives a box of zero extent; coincident or
/// coplanar points a flat box. An empty cloud or a non-finite coordinate is
/// refused. `−0.0` and `+0.0` are the same number; either may be reported.
pub fn aabb_of_points(points: &[P3]) -> Result<Aabb, RefereeError> {
    check(points)?;
    let mut min = points[0];
    let mut max = points[0];
    for p in &points[1..] {
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
        }
    }
    Ok(Aabb { min, max })
}

/// Relative slack of the `f64` filter that answers most "is this point inside the
/// ball?" tests before the exact test: a point whose `f64` distance to the centre
/// is within this fraction of the radius is decided exactly. The filter's own
/// error is a few units of 2⁻⁵³ (one rounding of the centre, of `r²`, and of each
/// step of a `hypot`), so 1e-12 is a margin of about 10⁴. Dimensionless.
const FILTER_SLACK: f64 = 1e-12;

/// Absolute slack of the same filter, in the scaled frame (the cloud scaled by a
/// power of two so its largest coordinate is in `[½, 1)`): about 2000 times the
/// smallest subnormal, it covers the absolute errors of subnormal differences and
/// of `hypot` near underflow, where relative bounds fail.
const FILTER_TINY: f64 = 1e-320;

/// Seed of the deterministic shuffle (Welzl's expected linear time needs a
/// random order; a fixed seed keeps the referee reproducible).
const SHUFFLE_SEED: u64 = 0x9E37_79B9_7F4A_7C15;

/// `x · 2^s`, exactly.
fn shift(x: &Q, s: isize) -> Q {
    let (num, den) = x.clone().into_parts();
    if s >= 0 { Q::from_parts(num << s as usize, den) } else { Q::from_parts(num, den << (-s) as usize) }
}

/// A point of the cloud: its `f64` image in the filter's frame, and, made
/// when first asked for (most points are only ever filtered in `f64`), its
/// exact value as an integer vector over the cloud's common power-of-two
/// denominator.
struct Point {
    src: P3,
    approx: P3,
    /// The exact point times `2^denominator_bits`, an integer vector.
    int: OnceCell<[IBig; 3]>,
}

impl Point {
    /// The exact point as rationals (the tests' reference).
    #[cfg(test)]
    fn exact(&self) -> V3 {
        self.src.map(|x| dyadic(x).0)
    }

    fn int(&self, denominator_bits: usize) -> &[IBig; 3] {
        self.int.get_or_init(|| {
            self.src.map(|x| {
                let (_, m, e) = dyadic(x);
                // x·2^F = m·2^(e + F), an integer since F ≥ −e.
                m << (e + denominator_bits as i64) as usize
            })
        })
    }
}

/// A finite `x` exactly: as a rational, and as `m·2^e` with `m` odd (or 0,
/// with `e = 0`).
fn dyadic(x: f64) -> (Q, IBig, i64) {
    let (mant, exp, negative) = super::dyadic::parts(x);
    if mant == 0 {
        return (Q::ZERO, IBig::ZERO, 0);
    }
    let tz = i64::from(mant.trailing_zeros());
    let (odd, e) = (mant >> tz, exp + tz);
    let m = if negative { -IBig::from(odd) } else { IBig::from(odd) };
    (super::dyadic::rational(&m, e), m, e)
}

/// `x·2^s` correctly rounded, as the exact value shifted then rounded: one
/// IEEE multiplication by a representable power of two rounds once; a scale
/// past `2^1023` goes up in two exact steps.
fn scaled_f64(x: f64, s: isize) -> f64 {
    let pow2 = |k: isize| {
        if k >= -1022 { f64::from_bits(((1023 + k) as u64) << 52) } else { f64::from_bits(1u64 << (k + 1074)) }
    };
    // −0 is the rational 0, whose rounding is +0; a negative value that
    // rounds to zero keeps its sign.
    if x == 0.0 {
        return 0.0;
    }
    if s > 1023 { x * pow2(s - 1000) * pow2(1000) } else { x * pow2(s) }
}

/// The exact in-ball test in integers: with the centre `C/D` over a common
/// denominator, `r² = R/E` in lowest terms, and the point `P/2^F`, the test
/// `‖P/2^F − C/D‖² ≤ R/E` becomes `‖P·D − C·2^F‖²·E ≤ R·D²·4^F`; `C·2^F` and
/// `R·D²·4^F` are computed once per ball. No gcd per test, unlike rationals.
struct IntBall {
    c: [IBig; 3],
    d: IBig,
    e: IBig,
    rhs: IBig,
}

/// A ball through a support set, exact, with its `f64` image for the filter.
struct ExactBall {
    center: V3,
    r2: Q,
    int: IntBall,
    /// `Some((centre, radius, centre error bound))` in the filter's frame, when
    /// those are finite and `r²` is a normal `f64`.
    approx: Option<(P3, f64, f64)>,
    /// The cloud's `F`, for its points' integer vectors.
    denominator_bits: usize,
}

/// `lcm(a, b)`.
fn lcm(a: &UBig, b: &UBig) -> UBig {
    let g = a.gcd(b);
    (a / &g) * b
}

impl ExactBall {
    fn new(center: V3, r2: Q, frame: isize, denominator_bits: usize) -> Self {
        let c = [round(&shift(&center[0], frame)), round(&shift(&center[1], frame)), round(&shift(&center[2], frame))];
        let r2f = round(&shift(&r2, 2 * frame));
        let c_err: f64 = c.iter().map(|x| x.abs() * f64::EPSILON + FILTER_TINY).sum();
        let usable =
            c.iter().all(|x| x.is_finite()) && r2f.is_finite() && r2f >= f64::MIN_POSITIVE && c_err.is_finite();
        let approx = usable.then(|| (c, r2f.sqrt(), c_err));
        let d = lcm(&lcm(center[0].denominator(), center[1].denominator()), center[2].denominator());
        let scaled = |x: &Q| (x.numerator() * IBig::from(&d / x.denominator())) << denominator_bits;
        let int_c = [scaled(&center[0]), scaled(&center[1]), scaled(&center[2])];
        let d = IBig::from(d);
        let rhs = (r2.numerator() * &d * &d) << (2 * denominator_bits);
        let int = IntBall { c: int_c, d, e: IBig::from(r2.denominator().clone()), rhs };
        Self { center, r2, int, approx, denominator_bits }
    }

    /// Whether `p` lies in the closed ball, decided exactly (the filter only
    /// answers when its error bound leaves no doubt).
    fn contains(&self, p: &Point) -> bool {
        if let Some((c, r, c_err)) = &self.approx {
            let d = (p.approx[0] - c[0]).hypot(p.approx[1] - c[1]).hypot(p.approx[2] - c[2]);
            if d.is_finite() {
                let slack = c_err + FILTER_TINY;
                if (d + slack) * (1.0 + FILTER_SLACK) < r * (1.0 - FILTER_SLACK) {
                    return true;
                }
                if (d - slack) * (1.0 - FILTER_SLACK) > r * (1.0 + FILTER_SLACK) {
                    return false;
                }
            }
        }
        let b = &self.int;
        let int = p.int(self.denominator_bits);
        let w: [IBig; 3] = std::array::from_fn(|k| &int[k] * &b.d - &b.c[k]);
        (&w[0] * &w[0] + &w[1] * &w[1] + &w[2] * &w[2]) * &b.e <= b.rhs
    }
}

/// The smallest ball with every point of `support` on its boundary and its
/// centre in their affine hull — the circumsphere of 1 to 4 points — from
/// [`Circumsphere`], in integers (no gcd until the ball's rationals are made
/// once). A point in the affine hull of those before it adds nothing — exact
/// arithmetic makes Welzl's support points affinely independent, so this only
/// absorbs a repeated constraint.
fn ball_through(support: &[usize], points: &[Point], frame: isize, denominator_bits: usize) -> Option<ExactBall> {
    Circumsphere::new(support, points, denominator_bits)?.ball(frame, denominator_bits)
}

/// The circumsphere of a support set, in integers. Over the cloud's common
/// denominator `2^F` the points are integer vectors `P`. With `wᵢ = Pᵢ − P₀`
/// for the support points kept (a point whose `w` lies in the span of those
/// kept before it adds nothing: its Gram determinant with them is 0), the
/// centre is `P₀ + Σ μᵢ wᵢ` where `G μ = b/2`, `Gᵢⱼ = wᵢ·wⱼ`, `bᵢ = wᵢ·wᵢ`
/// (equal distance to every kept point). By Cramer's rule `μᵢ = nᵢ/(2d)` with
/// `d = det G > 0` and `nᵢ` the determinant with column `i` replaced by `b`;
/// the centre is `C/(2d·2^F)` with `C = 2d·P₀ + Σ nᵢ wᵢ` and the squared
/// radius `‖C − 2d·P₀‖²/(2d·2^F)²` — integers throughout.
struct Circumsphere {
    /// The Cramer numerators `nᵢ`, one per kept point after the first.
    n: Vec<IBig>,
    /// `2d`.
    two_d: IBig,
    /// `C`.
    c: [IBig; 3],
    /// `C − 2d·P₀`.
    off: [IBig; 3],
}

impl Circumsphere {
    fn new(support: &[usize], points: &[Point], bits: usize) -> Option<Self> {
        let (&first, rest) = support.split_first()?;
        let s0 = points[first].int(bits).clone();
        let mut kept: Vec<[IBig; 3]> = Vec::with_capacity(3);
        for &j in rest {
            let pj = points[j].int(bits);
            let w: [IBig; 3] = std::array::from_fn(|k| &pj[k] - &s0[k]);
            kept.push(w);
            if gram_det(&kept).is_zero() {
                kept.pop();
            }
        }
        let g: Vec<Vec<IBig>> = kept.iter().map(|a| kept.iter().map(|b| idot(a, b)).collect()).collect();
        let b: Vec<IBig> = kept.iter().map(|w| idot(w, w)).collect();
        let d = det(&g);
        let n: Vec<IBig> = (0..kept.len())
            .map(|i| {
                let replaced: Vec<Vec<IBig>> = g
                    .iter()
                    .zip(&b)
                    .map(|(row, bj)| {
                        row.iter().enumerate().map(|(c, x)| if c == i { bj.clone() } else { x.clone() }).collect()
                    })
                    .collect();
                det(&replaced)
            })
            .collect();
        let two_d = &d * IBig::from(2u8);
        let c: [IBig; 3] =
            std::array::from_fn(|k| kept.iter().zip(&n).fold(&two_d * &s0[k], |acc, (w, ni)| acc + ni * &w[k]));
        let off: [IBig; 3] = std::array::from_fn(|k| &c[k] - &two_d * &s0[k]);
        Some(Self { n, two_d, c, off })
    }

    /// Whether the centre lies in the convex hull of the kept points: every
    /// barycentric weight `≥ 0`, that is every `nᵢ ≥ 0` and `Σ nᵢ ≤ 2d`.
    fn centred(&self) -> bool {
        let total = self.n.iter().fold(IBig::ZERO, |acc, x| acc + x);
        self.n.iter().all(|x| *x >= IBig::ZERO) && total <= self.two_d
    }

    /// The ball as rationals, with its integer and `f64` tests (`None` only
    /// if `2d ≤ 0`, which cannot be: the Gram matrix of linearly independent
    /// vectors is positive definite, and 1 for a single point).
    fn ball(&self, frame: isize, bits: usize) -> Option<ExactBall> {
        let den = UBig::try_from(self.two_d.clone()).ok()? << bits;
        let center: V3 = std::array::from_fn(|k| Q::from_parts(self.c[k].clone(), den.clone()));
        let r2 = Q::from_parts(idot(&self.off, &self.off), &den * &den);
        Some(ExactBall::new(center, r2, frame, bits))
    }
}

struct Welzl<'a> {
    points: &'a [Point],
    order: Vec<usize>,
    frame: isize,
    denominator_bits: usize,
}

impl Welzl<'_> {
    /// Move-to-front Welzl (Gärtner's `mtf_mb`): the smallest ball enclosing
    /// `order[..end]` with `support` on its boundary.
    fn mtf(&mut self, end: usize, support: &mut Vec<usize>) -> Option<ExactBall> {
        let mut ball = ball_through(support, self.points, self.frame, self.denominator_bits);
        if support.len() == 4 {
            return ball;
        }
        for i in 0..end {
            let idx = self.order[i];
            let inside = ball.as_ref().is_some_and(|b| b.contains(&self.points[idx]));
            if !inside {
                support.push(idx);
                ball = self.mtf(i, support);
                support.pop();
                self.order[..=i].rotate_right(1);
            }
        }
        ball
    }
}

/// A small deterministic generator (SplitMix64) for the shuffle.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The exact minimal ball: centre and squared radius as rationals.
/// The cloud made exact: its points, the filter's frame (`2^frame` brings the
/// largest coordinate into `[½, 1)`) and the bits `F` of the common
/// power-of-two denominator.
struct Cloud {
    points: Vec<Point>,
    frame: isize,
    denominator_bits: usize,
}

fn cloud(points: &[P3]) -> Result<Cloud, RefereeError> {
    check(points)?;
    // The largest coordinate m·2^e (m odd) is the rational num/den with
    // num = m·2^max(e, 0), den = 2^max(−e, 0): 2^frame, frame =
    // bits(den) − bits(num), brings it into [½, 1).
    let largest = points.iter().flatten().copied().max_by(|a, b| a.abs().total_cmp(&b.abs())).unwrap_or(0.0);
    let frame = match dyadic(largest) {
        (_, m, _) if m.is_zero() => 0,
        (_, m, e) => (e.min(0).unsigned_abs() + 1) as isize - (m.unsigned_abs().bit_len() as i64 + e.max(0)) as isize,
    };
    // Every coordinate is dyadic: over the common denominator 2^F, an integer.
    let denominator_bits =
        points.iter().flatten().map(|&x| dyadic(x).2.min(0).unsigned_abs() as usize).max().unwrap_or(0);
    let points = points
        .iter()
        .map(|p| Point { src: *p, approx: p.map(|x| scaled_f64(x, frame)), int: OnceCell::new() })
        .collect();
    Ok(Cloud { points, frame, denominator_bits })
}

/// The exact minimal ball: centre and squared radius as rationals (by the two
/// stages of [`min_ball_staged`]).
fn min_ball_exact(points: &[P3]) -> Result<(V3, Q), RefereeError> {
    min_ball_staged(points).map(|(ball, _)| ball)
}

/// The exact minimal ball by exact Welzl alone (no floating-point stage): the
/// reference the two stages are checked against.
#[cfg(test)]
fn min_ball_welzl(points: &[P3]) -> Result<(V3, Q), RefereeError> {
    super::stage::exact_only(|| min_ball_staged(points)).map(|(ball, _)| ball)
}

/// The floating-point stage of [`min_ball`]: move-to-front Welzl on the cloud's
/// `f64` images (in the filter's frame), tracking the support of each ball. Its
/// answer is only a candidate support, which [`certified`] checks exactly; a
/// wrong candidate (rounding in a nearly degenerate cloud) costs the exact
/// stage, never a wrong ball.
struct FloatWelzl<'a> {
    points: &'a [Point],
    order: Vec<usize>,
}

/// Relative slack of the floating-point stage's "inside" test: generous, since
/// a point let in wrongly is caught by the exact certificate, and a point kept
/// out wrongly only grows the candidate. Dimensionless.
const FLOAT_STAGE_SLACK: f64 = 1e-10;

/// The floating-point stage takes a support point as affinely dependent on
/// the earlier ones when its new direction's squared length is at most this
/// fraction of its squared offset (a sine of 1e-12). Like the slack above, it
/// only steers the search: the certificate is exact. Dimensionless.
const FLOAT_STAGE_DEPENDENT: f64 = 1e-24;

/// The `f64` ball through `support`: centre and squared radius, or `None`
/// when it is not finite.
///
/// Incremental (as in Gärtner's Miniball): with `c`, `r²` the ball through
/// `s0 … s(j−1)` and `u` the part of `sj − s0` orthogonal to the earlier
/// directions (Gram–Schmidt), the new centre is `c + λu`. Every earlier point
/// keeps distance² `r² + λ²‖u‖²` (its offset from `c` is orthogonal to `u`),
/// and `sj` gets `e − 2λ‖u‖² + λ²‖u‖²` with `e = ‖sj − c‖²` (because
/// `(sj − c)·u = ‖u‖²`); equating gives `λ = (e − r²)/(2‖u‖²)`,
/// `r²' = r² + λ²‖u‖²`. The exact balls are the same circumspheres by
/// Cramer's rule ([`Circumsphere`]).
fn float_ball_through(support: &[usize], points: &[Point]) -> Option<(P3, f64)> {
    let (&first, rest) = support.split_first()?;
    let s0 = points[first].approx;
    let (mut c, mut r2) = (s0, 0.0f64);
    let mut basis: Vec<(P3, f64)> = Vec::with_capacity(3);
    let d = |a: &P3, b: &P3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for &j in rest {
        let sj = points[j].approx;
        let w = [sj[0] - s0[0], sj[1] - s0[1], sj[2] - s0[2]];
        let mut u = w;
        for (b, bb) in &basis {
            let f = d(&w, b) / bb;
            u = [u[0] - f * b[0], u[1] - f * b[1], u[2] - f * b[2]];
        }
        let uu = d(&u, &u);
        // Affinely dependent up to rounding: nothing new (the exact
        // certificate decides whether that was right).
        if uu.partial_cmp(&(FLOAT_STAGE_DEPENDENT * d(&w, &w))) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        let off = [sj[0] - c[0], sj[1] - c[1], sj[2] - c[2]];
        let lambda = (d(&off, &off) - r2) / (2.0 * uu);
        c = [c[0] + lambda * u[0], c[1] + lambda * u[1], c[2] + lambda * u[2]];
        r2 += lambda * lambda * uu;
        basis.push((u, uu));
    }
    (c.iter().all(|x| x.is_finite()) && r2.is_finite()).then_some((c, r2))
}

impl FloatWelzl<'_> {
    /// As [`Welzl::mtf`], in `f64`: the ball and the support it was built on.
    fn mtf(&mut self, end: usize, support: &mut Vec<usize>) -> Option<(P3, f64, Vec<usize>)> {
        let mut ball = float_ball_through(support, self.points).map(|(c, r2)| (c, r2, support.clone()));
        if support.len() == 4 {
            return ball;
        }
        for i in 0..end {
            let idx = self.order[i];
            let p = self.points[idx].approx;
            let inside = ball.as_ref().is_some_and(|(c, r2, _)| {
                let w = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
                w[0] * w[0] + w[1] * w[1] + w[2] * w[2] <= r2 * (1.0 + FLOAT_STAGE_SLACK)
            });
            if !inside {
                support.push(idx);
                ball = self.mtf(i, support);
                support.pop();
                ball.as_ref()?;
                self.order[..=i].rotate_right(1);
            }
        }
        ball
    }
}

/// The exact ball through `support` when it is provably the minimal ball of
/// the cloud, else `None`.
///
/// **Certificate.** The ball through the affinely independent points `S` of
/// the support with its centre in their affine hull, and the centre inside
/// their convex hull (every barycentric weight ≥ 0), is the minimal ball of
/// `S` (any ball holding `S` has a radius at least as large). If it also holds
/// every point of the cloud, it is the minimal ball of the cloud, which is
/// unique: the same ball Welzl's exact algorithm finds. All three checks are
/// exact (the containment test's `f64` filter answers only where its error
/// bound leaves no doubt).
///
/// **In integers** ([`Circumsphere`]): the weights are `≥ 0` exactly when
/// every Cramer numerator `nᵢ ≥ 0` and `Σ nᵢ ≤ 2d`; one rational per output.
fn certified(cloud: &Cloud, support: &[usize]) -> Option<(V3, Q)> {
    let sphere = Circumsphere::new(support, &cloud.points, cloud.denominator_bits)?;
    if !sphere.centred() {
        return None;
    }
    let ball = sphere.ball(cloud.frame, cloud.denominator_bits)?;
    cloud.points.iter().all(|p| ball.contains(p)).then_some((ball.center, ball.r2))
}

/// `a·b` of integer vectors.
fn idot(a: &[IBig; 3], b: &[IBig; 3]) -> IBig {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

/// The Gram determinant of up to three integer vectors: 0 exactly when they
/// are linearly dependent (1 for none).
fn gram_det(vs: &[[IBig; 3]]) -> IBig {
    let g: Vec<Vec<IBig>> = vs.iter().map(|a| vs.iter().map(|b| idot(a, b)).collect()).collect();
    det(&g)
}

/// The determinant of a square integer matrix of order 0 to 3 (1 for order 0).
fn det(m: &[Vec<IBig>]) -> IBig {
    match m.len() {
        0 => IBig::ONE,
        1 => m[0][0].clone(),
        2 => &m[0][0] * &m[1][1] - &m[0][1] * &m[1][0],
        _ => {
            let minor = |a: usize, b: usize| &m[1][a] * &m[2][b] - &m[1][b] * &m[2][a];
            &m[0][0] * minor(1, 2) - &m[0][1] * minor(0, 2) + &m[0][2] * minor(0, 1)
        }
    }
}

/// The minimal ball by the two stages: the floating-point candidate when its
/// exact certificate holds (see [`certified`]), else exact Welzl. The answer is
/// the same exact ball either way; `fast` says which stage gave it.
fn min_ball_staged(points: &[P3]) -> Result<((V3, Q), bool), RefereeError> {
    let cloud = cloud(points)?;
    let n = cloud.points.len();
    let mut order: Vec<usize> = (0..n).collect();
    let mut state = SHUFFLE_SEED;
    for i in (1..n).rev() {
        let j = (splitmix(&mut state) % (i as u64 + 1)) as usize;
        order.swap(i, j);
    }
    if super::stage::staged() {
        let mut float = FloatWelzl { points: &cloud.points, order: order.clone() };
        if let Some((_, _, support)) = float.mtf(n, &mut Vec::with_capacity(4))
            && let Some(ball) = certified(&cloud, &support)
        {
            super::stage::count(super::stage::Stage::MinBall, true, 1);
            return Ok((ball, true));
        }
        super::stage::count(super::stage::Stage::MinBall, false, 1);
        // The exact run starts from the floating-point run's move-to-front
        // order, which puts the points that bounded its ball first: nearly
        // every other point is then inside the exact run's ball at once,
        // where the shuffled order recurses again and again (on the campaign's
        // clouds left to the exact stage, about half the time). The minimal
        // ball is unique: any order finds it.
        order = float.order;
    }
    let mut welzl =
        Welzl { points: &cloud.points, order, frame: cloud.frame, denominator_bits: cloud.denominator_bits };
    // A non-empty cloud always yields a ball (its first point is outside the
    // empty support's "ball" and starts one).
    let ball = welzl.mtf(n, &mut Vec::with_capacity(4)).ok_or(RefereeError::NoPoints { field: "a.points" })?;
    Ok(((ball.center, ball.r2), false))
}

/// The smallest sphere enclosing `points`, computed exactly.
///
/// **Method.** Welzl's algorithm in Gärtner's move-to-front form (Welzl 1991,
/// "Smallest enclosing disks (balls and ellipsoids)"; Gärtner 1999, "Fast and
/// robust smallest enclosing balls"), every step exact: the ball through 1–4
/// support points is their exact circumsphere (Cramer's rule in integers over
/// the cloud's common power-of-two denominator, `Circumsphere`), and "is
/// this point in the ball?" is decided exactly (`‖p − c‖² ≤ r²`), after a
/// cheap `f64` filter that answers only when its rigorous error bound leaves no
/// doubt. The points are first shuffled with a fixed seed, which gives Welzl's
/// expected linear time and a reproducible run (when the floating-point
/// stage's candidate fails its certificate, the exact run starts from that
/// stage's move-to-front order instead). The exact minimal ball is unique; its centre (a rational
/// point) is correctly rounded per coordinate, and its radius `√(r²)` correctly
/// rounded.
///
/// **Degenerate input.** One point, or coincident points: radius 0 at that point.
/// Collinear or coplanar clouds are handled like any other (the support has 2 or
/// 3 points). An empty cloud or a non-finite coordinate is refused.
pub fn min_ball(points: &[P3]) -> Result<Ball, RefereeError> {
    let (center, r2) = min_ball_exact(points)?;
    Ok(Ball { center: [round(&center[0]), round(&center[1]), round(&center[2])], radius: Root::new(r2).round_sqrt() })
}

/// How well `ball` encloses `points`: `radius − maxᵢ ‖pᵢ − centre‖`, from the
/// exact largest squared distance, correctly rounded. ≥ 0 exactly when every
/// point lies in the closed ball; negative by how far the worst point sticks out.
/// The harness's margin for the `bounds` query.
pub fn enclosure_margin(ball: &Ball, points: &[P3]) -> Result<f64, RefereeError> {
    check(points)?;
    let c = v3(&ball.center, "ball.center")?;
    let r = super::exact::radius(ball.radius, "ball.radius")?;
    let mut worst = Q::ZERO;
    for p in points {
        let w = sub(&v3(p, "a.points")?, &c);
        let d2 = dot(&w, &w);
        if d2 > worst {
            worst = d2;
        }
    }
    Ok(Root::new(worst).round_affine(&r, &Q::NEG_ONE))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::within_ulps;
    use dashu::base::AbsOrd;
    use proptest::prelude::*;

    /// Expectations are exact dyadic numbers or IEEE-correctly-rounded square
    /// roots (`f64::sqrt` is correctly rounded by IEEE 754): no ulp of slack.
    const EXACT_ULPS: u64 = 0;

    fn close(got: f64, want: f64, what: &str) {
        assert!(within_ulps(got, want, EXACT_ULPS), "{what}: got {got:e}, want {want:e}");
    }

    fn close_ball(got: Ball, center: P3, radius: f64, what: &str) {
        for (g, w) in got.center.iter().zip(center) {
            close(*g, w, what);
        }
        close(got.radius, radius, what);
    }

    /// Every point in the exact closed ball.
    fn encloses(center: &V3, r2: &Q, points: &[P3]) -> bool {
        points.iter().all(|p| {
            let w = sub(&v3(p, "p").unwrap(), center);
            dot(&w, &w) <= *r2
        })
    }

    /// The cloud read from `f64` bits is the cloud read through rationals:
    /// the same frame, common denominator, `f64` images and integer vectors,
    /// on values from the smallest subnormal to `MAX`, signed, and zero.
    #[test]
    fn referee_cloud_from_bits_is_the_rational_one() {
        let mut values = vec![0.0, -0.0, 1.0, -1.5, 0.1, f64::MAX, -f64::MAX, f64::MIN_POSITIVE, 3e-310];
        values.extend([f64::from_bits(1), -f64::from_bits(7), 2f64.powi(-1000), 1e300, -7.25e-200, 123456.789]);
        let mut state = 7u64;
        for _ in 0..200 {
            let bits = splitmix(&mut state);
            let x = f64::from_bits(bits);
            if x.is_finite() {
                values.push(x);
            }
        }
        for chunk in values.chunks(5).chain([&values[..1], &values[9..11], &values[1..2]]) {
            let points: Vec<P3> = chunk.iter().map(|&x| [x, x * 0.5, -x]).collect();
            let cloud = cloud(&points).expect("finite");
            let exact: Vec<V3> = points.iter().map(|p| v3(p, "a.points").expect("finite")).collect();
            let largest = exact.iter().flatten().max_by(|a, b| (*a).abs_cmp(*b)).cloned().unwrap_or(Q::ZERO);
            let frame = if largest.is_zero() {
                0
            } else {
                let (num, den) = largest.into_parts();
                den.bit_len() as isize - num.unsigned_abs().bit_len() as isize
            };
            let bits = exact.iter().flatten().map(|x| x.denominator().bit_len() - 1).max().unwrap_or(0);
            assert_eq!((cloud.frame, cloud.denominator_bits), (frame, bits), "{chunk:?}");
            for (point, e) in cloud.points.iter().zip(&exact) {
                assert_eq!(&point.exact(), e);
                for (k, ek) in e.iter().enumerate() {
                    let approx = round(&shift(ek, frame));
                    assert_eq!(point.approx[k].to_bits(), approx.to_bits(), "{chunk:?}");
                    let (num, den) = ek.clone().into_parts();
                    assert_eq!(point.int(bits)[k], num << (bits - (den.bit_len() - 1)), "{chunk:?}");
                }
            }
        }
    }

    /// The certificate refuses a support whose circumcentre lies outside its
    /// hull — whichever point comes first, so both the weights' signs and
    /// their sum are checked — and accepts the true support.
    #[test]
    fn referee_certificate_refuses_a_centre_outside_the_support() {
        // An obtuse triangle: the ball through all three is centred far below
        // it; the minimal ball is AB's (centre 0, radius 1), which holds C.
        let points = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.125, 0.0]];
        let cloud = cloud(&points).expect("finite");
        for support in [[0, 1, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]] {
            assert!(certified(&cloud, &support).is_none(), "support {support:?}");
        }
        let (center, r2) = certified(&cloud, &[0, 1]).expect("AB's ball is the minimal one");
        assert!(center.iter().all(Q::is_zero) && r2 == Q::ONE, "{center:?} {r2:?}");
    }

    #[test]
    fn referee_aabb_of_points_is_the_extremes() {
        let pts = [[1.0, -2.0, 3.0], [-4.0, 5.0, 0.5], [2.0, 0.0, -1e300]];
        let b = aabb_of_points(&pts).unwrap();
        assert_eq!(b, Aabb { min: [-4.0, -2.0, -1e300], max: [2.0, 5.0, 3.0] });
        let one = aabb_of_points(&[[7.0, 8.0, 9.0]]).unwrap();
        assert_eq!(one, Aabb { min: [7.0, 8.0, 9.0], max: [7.0, 8.0, 9.0] });
        assert_eq!(aabb_of_points(&[]), Err(RefereeError::NoPoints { field: "a.points" }));
        assert_eq!(aabb_of_points(&[[f64::NAN, 0.0, 0.0]]), Err(RefereeError::NonFinite { field: "a.points" }));
    }

    #[test]
    fn referee_min_ball_hand_derived() {
        // Two points: the midpoint, half the distance.
        close_ball(min_ball(&[[0.0; 3], [2.0, 0.0, 0.0]]).unwrap(), [1.0, 0.0, 0.0], 1.0, "pair");
        // Acute triangle (0,0,0), (2,0,0), (1,2,0): circumcentre (1, y, 0) with
        // 1 + y² = (2 − y)² → y = 3/4, r² = 1 + 9/16 = 25/16, r = 5/4.
        let acute = [[0.0; 3], [2.0, 0.0, 0.0], [1.0, 2.0, 0.0]];
        close_ball(min_ball(&acute).unwrap(), [1.0, 0.75, 0.0], 1.25, "acute");
        // Obtuse triangle: the longest edge's diameter ball, (2,0,0) r 2, contains (2,1,0).
        let obtuse = [[0.0; 3], [4.0, 0.0, 0.0], [2.0, 1.0, 0.0]];
        close_ball(min_ball(&obtuse).unwrap(), [2.0, 0.0, 0.0], 2.0, "obtuse");
        // Regular tetrahedron on alternate cube corners, plus its centre and a point
        // inside: centre 0, r = √3 (correctly rounded by IEEE sqrt).
        let tet = [[1.0, 1.0, 1.0], [1.0, -1.0, -1.0], [0.0; 3], [-1.0, 1.0, -1.0], [0.5, 0.5, 0.0], [-1.0, -1.0, 1.0]];
        close_ball(min_ball(&tet).unwrap(), [0.0; 3], 3f64.sqrt(), "tetrahedron");
        // Collinear 0..=10 on x, shuffled: centre 5, r 5.
        let line: Vec<P3> = [3, 10, 0, 7, 5, 1].iter().map(|&x| [f64::from(x), 0.0, 0.0]).collect();
        close_ball(min_ball(&line).unwrap(), [5.0, 0.0, 0.0], 5.0, "collinear");
        // Coincident points: radius 0 at the point.
        close_ball(min_ball(&[[1.5, 2.5, 3.5]; 5]).unwrap(), [1.5, 2.5, 3.5], 0.0, "coincident");
    }

    #[test]
    fn referee_min_ball_huge_and_tiny() {
        // (±s, 0, 0) and a point inside: centre 0, r = s, for s = 1e300 (r² overflows
        // f64) and 1e-300 (r² underflows).
        for s in [1e300, 1e-300] {
            let pts = [[-s, 0.0, 0.0], [0.0, 0.5 * s, 0.25 * s], [s, 0.0, 0.0]];
            close_ball(min_ball(&pts).unwrap(), [0.0; 3], s, "scaled");
        }
        // Mixed scales in one cloud: (0,0,0), (1e-300,0,0) and (0,1e300,0): the ball
        // has the two far points as diameter ends (the third is inside, as the
        // angle at the origin is a right angle): centre (5e-301, 5e299, 0) — halving
        // is exact — and r = ½‖(1e-300, −1e300, 0)‖ = ½·1e300·√(1 + 1e-1200),
        // which rounds to 5e299 (the correction is far below an ulp).
        let mixed = [[0.0; 3], [1e-300, 0.0, 0.0], [0.0, 1e300, 0.0]];
        close_ball(min_ball(&mixed).unwrap(), [0.5e-300, 0.5e300, 0.0], 0.5e300, "mixed");
    }

    #[test]
    fn referee_min_ball_2000_points_near_a_sphere() {
        // Unit vectors rounded to f64 lie within ~1e-16 of the unit sphere, the worst
        // case for the f64 filter (every test goes exact). Keep those exactly inside
        // the closed unit ball, then add (±1, 0, 0): the minimal ball is then exactly
        // the unit ball (any ball holding two antipodal points of it has r ≥ 1).
        let mut state = 7u64;
        let mut pts = vec![[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]];
        while pts.len() < 2000 {
            let mut v = [0.0; 3];
            for x in &mut v {
                *x = (splitmix(&mut state) >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
            }
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if n < 0.1 {
                continue;
            }
            let u = [v[0] / n, v[1] / n, v[2] / n];
            let e = v3(&u, "u").unwrap();
            if dot(&e, &e) <= Q::ONE {
                pts.push(u);
            }
        }
        let (center, r2) = min_ball_exact(&pts).unwrap();
        assert!(center.iter().all(Q::is_zero), "centre");
        assert_eq!(r2, Q::ONE, "r²");
    }

    #[test]
    fn referee_enclosure_margin() {
        let ball = Ball { center: [0.0; 3], radius: 1.0 };
        // Worst point on the sphere: 0; one sticking out to (2,0,0): 1 − 2 = −1;
        // all well inside: 1 − ½.
        close(enclosure_margin(&ball, &[[1.0, 0.0, 0.0], [0.0, 0.5, 0.0]]).unwrap(), 0.0, "on");
        close(enclosure_margin(&ball, &[[2.0, 0.0, 0.0], [0.0, 0.5, 0.0]]).unwrap(), -1.0, "out");
        close(enclosure_margin(&ball, &[[0.0, 0.0, 0.5]]).unwrap(), 0.5, "in");
    }

    /// The smallest enclosing circumball over every subset of 1–4 points: an
    /// exhaustive reference for small clouds (the minimal ball is the circumball
    /// of its support, 1–4 affinely independent points).
    fn brute_force(points: &[P3]) -> Q {
        let cloud = cloud(points).unwrap();
        let n = points.len();
        let mut best: Option<Q> = None;
        for mask in 1u32..(1 << n) {
            if mask.count_ones() > 4 {
                continue;
            }
            let support: Vec<usize> = (0..n).filter(|i| mask & (1 << i) != 0).collect();
            let ball = ball_through(&support, &cloud.points, cloud.frame, cloud.denominator_bits).unwrap();
            if encloses(&ball.center, &ball.r2, points) && best.as_ref().is_none_or(|b| ball.r2 < *b) {
                best = Some(ball.r2);
            }
        }
        best.unwrap()
    }

    /// The two stages give exactly the exact Welzl's ball (the same rationals),
    /// and which stage answered.
    fn same_as_welzl(points: &[P3]) -> bool {
        let ((center, r2), fast) = min_ball_staged(points).unwrap();
        let (c, r) = min_ball_welzl(points).unwrap();
        assert!(center == c && r2 == r, "two stages {center:?} r² {r2} against Welzl {c:?} r² {r}");
        fast
    }

    #[test]
    fn referee_min_ball_stages_fast_and_forced_fallback() {
        // A plain cloud: the floating-point candidate is certified.
        assert!(same_as_welzl(&[[0.0; 3], [2.0, 0.0, 0.0], [1.0, 2.0, 0.0], [0.5, 0.5, 0.5]]), "plain cloud");
        // A point outside the ball of (±1, 0, 0) by a relative 1e-12, which the
        // floating-point stage's slack lets in: its candidate (the two ends) fails
        // the exact containment check and exact Welzl answers.
        let outside = [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0 + 1e-12, 0.0]];
        assert!(!same_as_welzl(&outside), "the certificate must refuse a candidate that leaves a point out");
    }

    fn coord() -> impl Strategy<Value = f64> {
        // Small integers make duplicates, collinear and cospherical sets common.
        prop_oneof![(-3i8..=3).prop_map(f64::from), -100.0..100.0f64]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn referee_min_ball_matches_brute_force(points in prop::collection::vec([coord(), coord(), coord()], 1..=7)) {
            let (center, r2) = min_ball_exact(&points).unwrap();
            prop_assert!(encloses(&center, &r2, &points), "the ball must enclose every point");
            prop_assert_eq!(r2, brute_force(&points), "r² must be the minimum");
        }

        #[test]
        fn referee_min_ball_stages_match_exact_welzl(points in prop::collection::vec([coord(), coord(), coord()], 1..=40)) {
            same_as_welzl(&points);
        }

        #[test]
        fn referee_min_ball_stages_match_exact_welzl_near_a_sphere(
            dirs in prop::collection::vec([-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64], 2..=30),
            scale_exp in -300i32..=300,
        ) {
            // Points rounded onto a sphere of radius 2^scale_exp: nearly cospherical,
            // where a floating-point support is least reliable.
            let s = 2f64.powi(scale_exp);
            let pts: Vec<P3> = dirs.iter().filter_map(|v| {
                let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                (n > 1e-3).then(|| [v[0] / n * s, v[1] / n * s, v[2] / n * s])
            }).collect();
            if !pts.is_empty() {
                same_as_welzl(&pts);
            }
        }

        #[test]
        fn referee_min_ball_filtered_test_agrees_with_rationals(points in prop::collection::vec([coord(), coord(), coord()], 2..=12)) {
            // The f64 filter plus integer test must decide exactly as the rational
            // ‖p − c‖² ≤ r², also for points exactly on the sphere (common here).
            let cloud = cloud(&points).unwrap();
            let support: Vec<usize> = (0..points.len().min(4)).collect();
            let ball = ball_through(&support, &cloud.points, cloud.frame, cloud.denominator_bits).unwrap();
            for (p, point) in points.iter().zip(&cloud.points) {
                let w = sub(&point.exact(), &ball.center);
                prop_assert_eq!(ball.contains(point), dot(&w, &w) <= ball.r2, "point {:?}", p);
            }
            // The first support point is on the sphere by construction (later ones
            // too unless affinely dependent on earlier ones, which are skipped).
            let w = sub(&cloud.points[0].exact(), &ball.center);
            prop_assert!(dot(&w, &w) == ball.r2, "first support point on the sphere");
        }

        #[test]
        fn referee_min_ball_scales_with_powers_of_two(
            points in prop::collection::vec([(-3i8..=3).prop_map(f64::from), (-3i8..=3).prop_map(f64::from), (-3i8..=3).prop_map(f64::from)], 1..=40),
            shift in -4i32..=4,
        ) {
            // Scaling every coordinate by 2^shift is exact: the radius scales by it.
            let s = 2f64.powi(shift);
            let scaled: Vec<P3> = points.iter().map(|p| [p[0] * s, p[1] * s, p[2] * s]).collect();
            let a = min_ball(&points).unwrap();
            let b = min_ball(&scaled).unwrap();
            prop_assert!(within_ulps(a.radius * s, b.radius, EXACT_ULPS), "radius {} vs {}", a.radius * s, b.radius);
        }
    }
}
