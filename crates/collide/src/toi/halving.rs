//! The lecture's interval halving, for any pair with a static contact test.

use super::time_of_impact::{Halving, Toi, ToiStatus, clamp_t_max};
use crate::contact::Contact;
use crate::real::{Real, c};

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
pub fn toi_halving<T, F>(mut contact_at: F, t_max: T, stop: Halving<T>) -> Option<Toi<T>>
where
    T: Real,
    F: FnMut(T) -> Option<Contact<T>>,
{
    let t_max = clamp_t_max(t_max);
    if let Some(k) = contact_at(T::zero()) {
        return Some(Toi::penetrating(&k));
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
    Some(Toi {
        t: hi,
        point: at_hi.point,
        normal: at_hi.normal,
        status: ToiStatus::Converged,
        iterations: steps,
        degenerate: at_hi.degenerate,
    })
}
