//! The verdict's third stage: the comparison. What each numeric field of an
//! answer is off by from the referee's, and whether the classification (a
//! contact, a hit, an impact, an overlap, a flag) is the referee's — before
//! any allowance: the next stage ([`super::judge`]) weighs each measured
//! error against its allowance ([`super::allowance`]).

use super::allowance::Allowed;
use super::sizes::Local;
use super::verdict::{Errors, Misclass, degenerate};
use crate::engine::Answer;
use crate::load::{LoadedCase, bounded_points};
use oracle::geom::P3;

/// The largest coordinate difference of two points.
pub(crate) fn dist3(a: &P3, b: &P3) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// The angle between two directions, radians: `atan2(‖a × b‖, a · b)`, accurate
/// for small and large angles alike, each vector scaled by its largest
/// coordinate first (so a normal of length 1e-200 or 1e200 is a direction like
/// any other). A zero vector is no direction: π from everything, never an
/// agreement.
pub fn angle(a: &P3, b: &P3) -> f64 {
    let (ma, mb) = (crashtest_core::vec3::max_abs(*a), crashtest_core::vec3::max_abs(*b));
    if !(ma > 0.0 && mb > 0.0 && ma.is_finite() && mb.is_finite()) {
        return std::f64::consts::PI;
    }
    let (a, b) = (&a.map(|x| x / ma), &b.map(|x| x / mb));
    let c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let s = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    s.atan2(d)
}

/// `‖n‖ − 1` for a normal `n`, to within a few units of `ε²` where the
/// length is near 1: the squares and their sum are carried in two words (each
/// square split exactly by a fused multiply-add), so the judge's own rounding
/// (an ulp or two of a plain `sqrt(x² + y² + z²)`) never decides a verdict at
/// [`super::tolerance::NORMAL_LENGTH_ULPS`]. A normal whose largest coordinate is outside
/// `[2⁻⁴, 2]` is far from unit whatever its other coordinates: its length is
/// taken by the scaled norm, which cannot overflow.
pub fn unit_excess(n: &P3) -> f64 {
    let m = crashtest_core::vec3::max_abs(*n);
    if !(0.0625..=2.0).contains(&m) {
        return super::sizes::norm(n) - 1.0;
    }
    // (hi, lo): the running sum x² + y² + z² − 1, exact but for the final
    // rounding of `lo`.
    let two_sum = |a: f64, b: f64| {
        let s = a + b;
        let bb = s - a;
        (s, (a - (s - bb)) + (b - bb))
    };
    let (mut hi, mut lo) = (-1.0, 0.0);
    for x in n {
        let p = x * x;
        let e = x.mul_add(*x, -p);
        let (s, err) = two_sum(hi, p);
        hi = s;
        lo += err + e;
    }
    let ss_minus_1 = hi + lo;
    // ‖n‖ − 1 = (‖n‖² − 1)/(‖n‖ + 1); the denominator needs no precision.
    ss_minus_1 / ((ss_minus_1 + 1.0).max(0.0).sqrt() + 1.0)
}

/// What an error is weighed against in the next stage.
#[derive(Clone, Copy, Debug)]
pub enum Against {
    /// A field of the allowances ([`Allowed`]): the verdict's, the
    /// conditioning alone and one ulp of the field's magnitude.
    Field(fn(&Allowed) -> f64),
    /// A quantity exact in the referee and judged by its own size: an
    /// AABB's coordinate `w` (the fixed allowance of `|w|`, at least the
    /// floor; rounding the inputs already costs ε of each), named in the
    /// reason by its value.
    Own(f64),
    /// A normal's distance from unit length, `|‖n‖ − 1|` (its length given):
    /// against `tol.normal_length_ulps` of the engine's ε.
    UnitLength(f64),
    /// A bounding sphere's farthest point outside it (that point's index): a
    /// classification — beyond the depth's allowance the sphere misses it.
    Outside(usize),
}

/// One measured error.
#[derive(Clone, Debug)]
pub struct Measured {
    /// The field, as reasons name it (`point`, `t`, `aabb coordinate`).
    pub field: &'static str,
    /// Its error (absolute; radians for a normal's angle).
    pub err: f64,
    /// The unit the reason prints after the error (`" rad"` or nothing).
    pub unit: &'static str,
    /// What the error is weighed against.
    pub against: Against,
}

/// What the comparison found.
#[derive(Clone, Debug, Default)]
pub struct Compared {
    /// The errors the reports keep (each field's error; `misclass` when the
    /// classification differs).
    pub errors: Errors,
    /// Each classification that differs, as a reason (`false contact
    /// (referee: apart)`, `degenerate: true (referee false)`).
    pub class: Vec<String>,
    /// Each numeric field's error.
    pub measured: Vec<Measured>,
    /// Reasons that need no allowance: a normal that is the zero vector.
    pub wrong: Vec<String>,
}

impl Compared {
    fn measure(&mut self, field: &'static str, err: f64, unit: &'static str, against: Against) {
        self.measured.push(Measured { field, err, unit, against });
    }

    /// A normal: its angle to the referee's, the zero vector's reason, and
    /// its length.
    fn normal(&mut self, got: &P3, want: &P3) {
        let a = angle(got, want);
        self.errors.normal = Some(a);
        self.measure("normal", a, " rad", Against::Field(|a| a.normal));
        if no_direction(got, want) {
            self.wrong.push("normal is the zero vector (no direction)".into());
        } else if got.iter().any(|x| *x != 0.0) {
            let x = unit_excess(got);
            self.errors.normal_length = Some(x.abs());
            self.measure("normal length", x.abs(), "", Against::UnitLength(super::sizes::norm(got)));
        }
    }

    fn classify(&mut self, reason: String, how: Misclass) {
        self.class.push(reason);
        self.errors.misclass = Some(how);
    }
}

/// A normal that is the zero vector is no direction: whatever the normal's
/// allowance (π where the referee's own normal is a fallback, as for
/// concentric spheres), an engine's zero normal beside the referee's unit one
/// is a disagreement, never an agreement by the angle [`angle`] gives it.
fn no_direction(got: &P3, want: &P3) -> bool {
    let zero = |p: &P3| p.iter().all(|x| *x == 0.0);
    zero(got) && !zero(want)
}

/// Compares `answer` with the referee's `truth` for the case `lc`;
/// `sizes` gives the response's velocities their scale (the reports keep
/// their error relative to the largest input speed).
pub fn compare(lc: &LoadedCase, answer: &Answer, truth: &Answer, sizes: &Local) -> Compared {
    use Misclass::{FalseNegative, FalsePositive, Flag};
    let mut c = Compared::default();
    if degenerate(answer) != degenerate(truth) {
        c.classify(format!("degenerate: {} (referee {})", degenerate(answer), degenerate(truth)), Flag);
    }
    let field = Against::Field;
    match (answer, truth) {
        (Answer::Contact(g), Answer::Contact(w)) => match (&g.contact, &w.contact) {
            (Some(gc), Some(wc)) => {
                // Where the region is more than a point, any point of it is
                // right: the distance to it, not to the referee's choice.
                let dp = match &sizes.region {
                    Some(r) => r.distance(&gc.point),
                    None => dist3(&gc.point, &wc.point),
                };
                c.errors.point = Some(dp);
                c.measure("point", dp, "", field(|a| a.point));
                let dd = (gc.depth - wc.depth).abs();
                c.errors.depth = Some(dd);
                c.measure("depth", dd, "", field(|a| a.depth));
                c.normal(&gc.normal, &wc.normal);
            }
            (None, None) => {}
            (Some(_), None) => c.classify("false contact (referee: apart)".into(), FalsePositive),
            (None, Some(_)) => c.classify("missed contact (referee: touching)".into(), FalseNegative),
        },
        (Answer::Intersect(g), Answer::Intersect(w)) => {
            if g.parallel != w.parallel {
                c.classify(format!("parallel: {} (referee {})", g.parallel, w.parallel), Flag);
            }
            match (&g.hit, &w.hit) {
                (Some(gh), Some(wh)) => {
                    let dp = dist3(&gh.point, &wh.point);
                    c.errors.point = Some(dp);
                    c.measure("hit point", dp, "", field(|a| a.point));
                    let dt = (gh.t - wh.t).abs();
                    c.errors.t = Some(dt);
                    c.measure("t", dt, "", field(|a| a.t));
                    c.normal(&gh.normal, &wh.normal);
                    if let (Some(gb), Some(wb)) = (&gh.barycentric, &wh.barycentric) {
                        let err = dist3(gb, wb);
                        c.errors.barycentric = Some(err);
                        c.measure("barycentric", err, "", field(|a| a.barycentric));
                    }
                }
                (None, None) => {}
                (Some(_), None) => c.classify("false hit (referee: miss)".into(), FalsePositive),
                (None, Some(_)) => c.classify("missed hit (referee: hit)".into(), FalseNegative),
            }
        }
        (Answer::Barycentric(g), Answer::Barycentric(w)) => {
            let err = dist3(&g.coords, &w.coords);
            c.errors.barycentric = Some(err);
            c.measure("barycentric", err, "", field(|a| a.barycentric));
        }
        (Answer::Bounds(g), Answer::Bounds(w)) => {
            if let (Some(gb), Some(wb)) = (&g.aabb, &w.aabb) {
                // Each coordinate of the box by its own size: the box is exact,
                // and an engine that rounds its inputs loses ε of each.
                c.errors.point = Some(dist3(&gb.min, &wb.min).max(dist3(&gb.max, &wb.max)));
                for (gp, wp) in [(&gb.min, &wb.min), (&gb.max, &wb.max)] {
                    for i in 0..3 {
                        c.measure("aabb coordinate", (gp[i] - wp[i]).abs(), "", Against::Own(wp[i]));
                    }
                }
            }
            if let (Some(gs), Some(ws)) = (&g.sphere, &w.sphere) {
                // The engine's sphere must enclose every point (its farthest
                // point outside, weighed in the next stage); its excess radius
                // over the minimal one is its error (parry's and the lecture's
                // are not minimal by design: a known divergence).
                let (i, outside) = bounded_points(lc)
                    .iter()
                    .map(|p| super::sizes::distance(p, &gs.center) - gs.radius)
                    .enumerate()
                    .fold((0, 0.0), |best, (i, d)| if d > best.1 { (i, d) } else { best });
                c.measure("bounding sphere", outside, "", Against::Outside(i));
                let excess = gs.radius - ws.radius;
                c.errors.depth = Some(excess);
                c.measure("bounding radius", excess, "", field(|a| a.depth));
            }
        }
        (Answer::Overlap(g), Answer::Overlap(w)) => {
            if g != w {
                c.classify(format!("overlap: {g} (referee {w})"), if *g { FalsePositive } else { FalseNegative });
            }
        }
        (Answer::Toi(g), Answer::Toi(w)) => match (&g.toi, &w.toi) {
            (Some(gt), Some(wt)) => {
                let t_scale = lc.case.t_max().max(f64::MIN_POSITIVE);
                let dt = (gt.t - wt.t).abs();
                c.errors.t = Some(dt / t_scale);
                c.measure("t", dt, "", field(|a| a.t));
                let dp = dist3(&gt.point, &wt.point);
                c.errors.point = Some(dp);
                c.measure("point", dp, "", field(|a| a.point));
                c.normal(&gt.normal, &wt.normal);
            }
            (None, None) => {}
            (Some(_), None) => c.classify("false impact (referee: none)".into(), FalsePositive),
            (None, Some(_)) => c.classify("missed impact (referee: impact)".into(), FalseNegative),
        },
        (Answer::Response(g), Answer::Response(w)) => {
            let err = dist3(&g.velocity_a, &w.velocity_a).max(dist3(&g.velocity_b, &w.velocity_b));
            let speed = sizes.velocity.magnitude;
            c.errors.velocity = Some(if speed > 0.0 { err / speed } else { err });
            c.measure("velocity", err, "", field(|a| a.velocity));
        }
        (Answer::Ccd(g), Answer::Ccd(w)) => match (g.t, w.t) {
            (Some(gt), Some(wt)) => {
                let t_max = lc.case.t_max();
                let dt = (gt - wt).abs();
                c.errors.t = Some(dt / t_max.max(f64::MIN_POSITIVE));
                c.measure("t", dt, "", field(|a| a.t));
                // An impact outside the interval is no answer to the question,
                // however ill-conditioned the time (coplanar motion allows the
                // whole interval, never beyond it).
                if !(0.0..=t_max).contains(&gt) {
                    c.wrong.push(format!("impact time {gt:e} outside [0, t_max = {t_max:e}]"));
                }
            }
            (None, None) => {}
            (Some(_), None) => c.classify("false impact (referee: none)".into(), FalsePositive),
            (None, Some(_)) => c.classify("missed impact (referee: impact)".into(), FalseNegative),
        },
        (Answer::Distance(g), Answer::Distance(w)) => {
            let dd = (g.distance - w.distance).abs();
            c.errors.depth = Some(dd);
            c.measure("distance", dd, "", field(|a| a.depth));
            // Where the witnesses are not unique, any pair of the sets is
            // right: each point's distance to its set.
            let on = |r: &Option<super::sizes::Region>, got: &P3, want: &P3| match r {
                Some(r) => r.distance(got),
                None => dist3(got, want),
            };
            let dp = on(&sizes.region_a, &g.point_a, &w.point_a).max(on(&sizes.region, &g.point_b, &w.point_b));
            c.errors.point = Some(dp);
            c.measure("witness point", dp, "", field(|a| a.point));
            c.normal(&g.normal, &w.normal);
        }
        _ => c.class.push("answer of another query kind".into()),
    }
    c
}
