//! The lecture's interval halving, for any pair with a static contact test.

use super::time_of_impact::{Halving, Toi, ToiStatus, clamp_t_max};
use crate::contact::Contact;
use crate::real::{Real, Vec3, c};

/// Time of impact by **interval halving** on a static contact test, the
/// lecture's method: `contact_at(t)` is the static test (a `collide::contact`
/// query) between the two shapes moved to time `t`.
///
/// **Method** (the lecture's). Test the end of the step, `t_max`. If the shapes
/// do not intersect there, report no collision. Otherwise bisect `[lo, hi] =
/// [0, t_max]` keeping the invariant "`hi` intersects, `lo` does not": test the
/// midpoint `m = lo + (hi − lo)/2`, and set `hi = m` if it intersects, else
/// `lo = m`. Stop after a number of steps or at a bracket width ([`Halving`]),
/// and report `hi` with the static contact at `hi`.
///
/// **Accuracy.** For convex shapes in linear motion the set of times at which
/// they touch is one interval `[t₁, t₂]`; with `lo` outside it and `hi` inside,
/// `t₁ ∈ (lo, hi]`, so after `k` bisections the error `hi − t₁` is at most
/// `hi − lo = t_max / 2^k`. The reported `t` is never before the impact (up to
/// the static test's own rounding), and the contact at `hi` overlaps slightly
/// (depth ≥ 0): it is the contact the step would resolve.
///
/// **What it misses (tunneling), kept as the lecture has it.** The method only
/// looks at the end of the interval: a collision entered and left within
/// `[0, t_max]` — a small fast sphere passing through a thin wall, or a glancing
/// pass — leaves the end clear, and the answer is "no impact" although the
/// shapes touched. crashtest shows these misses beside the closed forms, which
/// see every touching time; they are not patched here.
///
/// **Deviation from the lecture.** Before testing the end, the start `t = 0` is
/// tested: shapes already in contact there get `t = 0` with status
/// [`ToiStatus::Penetrating`], as the fixture format asks. In the lecture's use
/// (a stepped simulation whose previous step resolved every contact) the start
/// is always clear, so this changes nothing there.
///
/// **Termination and degenerate input.** The bracket also stops shrinking when
/// its midpoint rounds to one of its ends (the type's resolution), so a
/// tolerance that is 0, negative or NaN runs to that resolution and stops. A
/// negative or NaN `t_max` is read as 0. The contact's `degenerate` flag is
/// passed on. The status is [`ToiStatus::Converged`]; `iterations` counts the
/// bisections.
pub fn toi_halving<T, F>(contact_at: F, t_max: T, stop: Halving<T>) -> Option<Toi<T>>
where
    T: Real,
    F: FnMut(T) -> Option<Contact<T>>,
{
    bisect(contact_at, t_max, stop).map(|b| b.answer(|k| k))
}

/// Where [`bisect`] ended: the time, the static test's answer there (of any
/// type: a [`Contact`], or a mesh contact with its face), and how.
pub(crate) struct Bisected<T: Real, K> {
    pub t: T,
    pub at: K,
    pub steps: u32,
    pub penetrating: bool,
}

impl<T: Real, K> Bisected<T, K> {
    /// The answer, with `contact` reading the [`Contact`] out of the payload.
    pub(crate) fn answer(self, contact: impl FnOnce(K) -> Contact<T>) -> Toi<T> {
        let k = contact(self.at);
        if self.penetrating {
            return Toi::penetrating(&k);
        }
        Toi {
            t: self.t,
            point: k.point,
            normal: k.normal,
            status: ToiStatus::Converged,
            iterations: self.steps,
            degenerate: k.degenerate,
        }
    }
}

/// The bisection of [`toi_halving`] for any static test whose answer (`K`) is a
/// contact with more attached (a mesh's face index, say).
pub(crate) fn bisect<T, K, F>(mut contact_at: F, t_max: T, stop: Halving<T>) -> Option<Bisected<T, K>>
where
    T: Real,
    F: FnMut(T) -> Option<K>,
{
    let t_max = clamp_t_max(t_max);
    if let Some(k) = contact_at(T::zero()) {
        return Some(Bisected { t: T::zero(), at: k, steps: 0, penetrating: true });
    }
    // The lecture's test at the end of the interval: clear there means no impact.
    let mut at_hi = contact_at(t_max)?;
    let (mut lo, mut hi) = (T::zero(), t_max);
    let mut steps = 0u32;
    loop {
        let done = match stop {
            Halving::Steps(k) => steps >= k,
            Halving::Tolerance(tol) => hi - lo <= tol,
        };
        if done {
            break;
        }
        let mid = lo + (hi - lo) * c::<T>(0.5);
        if !(mid > lo && mid < hi) {
            break;
        }
        steps += 1;
        match contact_at(mid) {
            Some(k) => {
                hi = mid;
                at_hi = k;
            }
            None => lo = mid,
        }
    }
    Some(Bisected { t: hi, at: at_hi, steps, penetrating: false })
}

/// The fraction of the type's largest finite value that a moved coordinate may
/// reach in the halving methods: 1/4, so that a coordinate of the scene (at most
/// about as large, or the static test could not run on it either) plus the
/// displacement stays finite, and the static tests' own differences of such
/// coordinates do too.
const HORIZON_FRACTION: f64 = 0.25;

/// `t_max` as the lecture's halving reads it for shapes moving with
/// `velocities`: at most the last time at which every displacement
/// `t · v_k` stays within [`HORIZON_FRACTION`] of the type's largest finite
/// value. Beyond it the moved shapes are not representable and the static test
/// has nothing to test (`t_max = f64::MAX`, parry's "no limit", moves a sphere
/// of speed 10 to infinity); the end of the step is the horizon instead.
///
/// This is a deviation from the lecture, which never meets such a step: the
/// lecture's method then tests the end of the shortened interval, as for any
/// other step, and misses an impact that is over by then (the tunneling it is
/// known for).
pub(crate) fn horizon<T: Real>(t_max: T, velocities: &[&Vec3<T>]) -> T {
    let reach = T::max_value().unwrap_or_else(|| c(f64::MAX)) * c::<T>(HORIZON_FRACTION);
    let mut t = clamp_t_max(t_max);
    for v in velocities {
        for k in 0..3 {
            let speed = v[k].abs();
            if speed > T::zero() {
                let limit = reach / speed;
                if limit < t {
                    t = limit;
                }
            }
        }
    }
    t
}
