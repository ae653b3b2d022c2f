//! A moving sphere's traversal of a mesh's bounding volume hierarchy: the faces
//! whose boxes it can reach, nearer entry first, pruned by a time bound.
//!
//! This is the one place in `toi` that reads the tree's nodes (the crate's own
//! accessors of [`MeshBvh`]: each node's box, its right child's index or its
//! leaf's faces); the mesh module's queries traverse the same layout.

use crate::mesh::{BVH_MAX_DEPTH, MeshBvh};
use crate::real::{Real, Vec3, c};
use crate::shapes::{Aabb, Sphere, Triangle};

/// The rounding margin added to the boxes' growth, in units of ε times the
/// scene's scale (the largest of the centre's coordinates, the mesh box's, the
/// radius and the tolerance). Reason: each slab bound `(lo − R − c)/v` is two
/// subtractions and a division from exact inputs; the subtractions err by at
/// most `2 u (|lo| + R + |c|) ≤ 6 u · scale` (`u = ε/2`), which a growth of
/// `16 ε · scale` covers with room, and the division's relative error is taken
/// by [`ENTRY_SLACK_EPS`]. The closest points and distances advancement
/// computes carry a few ε·scale too (they decide when it stops, within the
/// tolerance); 16 covers them. Units: ε·scale.
const SWEEP_MARGIN_EPS: f64 = 16.0;

/// Relative slack on the entry and exit times of the slab test, in units of
/// ε: 4. Reason: each time is one rounded division (relative error `u`), and
/// advancement may report a time up to `u` relative before its face's true
/// contact when its last step no longer changes `t`; `4 ε = 8 u` covers both.
const ENTRY_SLACK_EPS: f64 = 4.0;

/// A sphere moving on the ray `center + t v`, grown for the box tests.
pub(crate) struct Sweep<T: Real> {
    center: Vec3<T>,
    v: Vec3<T>,
    /// How far the boxes are grown: radius, tolerance and rounding margin.
    grow: T,
    slack: T,
}

impl<T: Real> Sweep<T> {
    /// The sweep of sphere `a` along `v` (relative velocity), for faces reached
    /// to within `tol`, in a scene whose mesh has the box `bbox`.
    pub(crate) fn new(a: &Sphere<T>, v: &Vec3<T>, tol: T, bbox: Option<Aabb<T>>) -> Self {
        let amax = |p: &Vec3<T>| p.x.abs().max(p.y.abs()).max(p.z.abs());
        let mut s = amax(&a.center).max(a.radius.abs()).max(tol.abs());
        if let Some(b) = bbox {
            s = s.max(amax(&b.min)).max(amax(&b.max));
        }
        let margin = c::<T>(SWEEP_MARGIN_EPS) * T::EPSILON * s;
        Self { center: a.center, v: *v, grow: a.radius + tol + margin, slack: c::<T>(ENTRY_SLACK_EPS) * T::EPSILON }
    }

    /// A lower bound on the time in `[0, limit]` at which the centre comes
    /// within the growth of the box `[min, max]`, or `None` when it certainly
    /// does not within `[0, limit]`.
    ///
    /// **Method** (slabs, as for a ray against a box, Ericson §5.3.3): per axis,
    /// the grown slab `[min_k − R, max_k + R]` is entered and left at
    /// `(near − c_k)/v_k` and `(far − c_k)/v_k`; an axis without motion keeps
    /// the centre in or out of its slab for good. The centre is in the grown
    /// box during the intersection of these intervals with `[0, limit]`. The
    /// growth's margin covers the subtractions' rounding; the entering time is
    /// lowered and the leaving time raised by [`ENTRY_SLACK_EPS`] for the
    /// division's, so the test is conservative: it never answers `None` for a
    /// box the exact ray enters.
    #[inline]
    pub(crate) fn entry(&self, min: &[T; 3], max: &[T; 3], limit: T) -> Option<T> {
        let mut enter = T::zero();
        let mut exit = limit;
        for k in 0..3 {
            let lo = min[k] - self.grow - self.center[k];
            let hi = max[k] + self.grow - self.center[k];
            let v = self.v[k];
            if v == T::zero() {
                if lo > T::zero() || hi < T::zero() {
                    return None;
                }
                continue;
            }
            let (t0, t1) = (lo / v, hi / v);
            let (near, far) = if v > T::zero() { (t0, t1) } else { (t1, t0) };
            if near > enter {
                enter = near;
            }
            if far < exit {
                exit = far;
            }
        }
        let enter = enter - enter.abs() * self.slack;
        let exit = exit + exit.abs() * self.slack;
        if enter <= exit { Some(enter) } else { None }
    }
}

/// Visits the faces of `bvh` whose grown boxes the sweep enters within
/// `[0, t_max]`, nearer entry first, skipping every node entered after
/// `bound(state)` (the best time so far, if any). `visit(state, face, tri)`
/// gets the face's index in the mesh and the face.
///
/// The traversal is depth first with a fixed-size stack of
/// `BVH_MAX_DEPTH + 2` entries (at most one pending sibling per level): it does
/// not allocate.
pub(crate) fn sweep_faces<T: Real, S>(
    bvh: &MeshBvh<T>,
    sweep: &Sweep<T>,
    t_max: T,
    bound: impl Fn(&S) -> Option<T>,
    state: &mut S,
    mut visit: impl FnMut(&mut S, usize, &Triangle<T>),
) {
    let nodes = bvh.nodes();
    let Some(root) = nodes.first() else { return };
    let pruned = |state: &S, lb: T| bound(state).is_some_and(|best| lb > best);
    let mut stack = [(0u32, T::zero()); BVH_MAX_DEPTH + 2];
    let mut sp = 0usize;
    if let Some(lb) = sweep.entry(&root.min, &root.max, t_max) {
        stack[0] = (0, lb);
        sp = 1;
    }
    while sp > 0 {
        sp -= 1;
        let (i, lb) = stack[sp];
        if pruned(state, lb) {
            continue;
        }
        let node = &nodes[i as usize];
        if node.count > 0 {
            for k in node.start..node.start + node.count {
                let (tri, face) = bvh.leaf_face(k as usize);
                visit(state, face, tri);
            }
            continue;
        }
        let (l, r) = (i + 1, node.start);
        let (nl, nr) = (&nodes[l as usize], &nodes[r as usize]);
        let el = sweep.entry(&nl.min, &nl.max, t_max).map(|lb| (l, lb));
        let er = sweep.entry(&nr.min, &nr.max, t_max).map(|lb| (r, lb));
        let (near, far) = match (el, er) {
            (Some(x), Some(y)) if y.1 < x.1 => (Some(y), Some(x)),
            (x, y) => (x, y),
        };
        for item in [far, near].into_iter().flatten() {
            if !pruned(state, item.1) && sp < stack.len() {
                stack[sp] = item;
                sp += 1;
            }
        }
    }
}
