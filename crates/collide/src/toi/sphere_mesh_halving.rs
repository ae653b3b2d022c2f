//! Sphere–mesh time of impact by the lecture's interval halving.

use super::halving::{bisect, horizon};
use super::sphere_mesh::MeshToi;
use super::time_of_impact::Halving;
use crate::mesh::{MeshBvh, MeshContact, contact_sphere_mesh_bvh};
use crate::real::{Real, Vec3};
use crate::shapes::Sphere;

/// Time of impact of sphere `a` (velocity `va`) and a mesh `b` (every vertex
/// moving with `vb`) over `[0, t_max]` by **the lecture's interval halving** on
/// the static sphere–mesh test ([`contact_sphere_mesh_bvh`], the deepest
/// contact over the faces; the same answer as testing every face).
///
/// **Formula.** The bisection of [`toi_halving`](super::toi_halving): test the
/// end of the interval; if the sphere is clear of every face there, no impact;
/// otherwise keep `[lo, hi]` with `hi` in contact and `lo` clear, and answer
/// `hi` with the static contact there (the deepest face's point, moved to time
/// `hi`, its normal, and the face). After `k` bisections `hi` is within
/// `t_max / 2^k` of the first time the static test sees contact.
///
/// **Deviation.** The static test is run on the sphere moved by the relative
/// motion `(va − vb)·t` against the mesh where it is at time 0, and the point
/// is then moved by `vb·t`: the same contact, without rebuilding the tree at
/// every time tested. A `t_max` so large that the motion leaves the type's
/// range is cut to the last time it stays representable (as for the other
/// halving methods).
///
/// **Misses.** A mesh is a surface: a sphere that passes through a face (or
/// between the faces of a thin part) and is clear of the mesh at `t_max` is
/// missed, the tunneling the lecture's method is known for; so is one that
/// touches the mesh on the way and is clear again by the end. Conservative
/// advancement ([`toi_sphere_mesh`](super::toi_sphere_mesh)) sees both.
///
/// **Degenerate input.** As [`contact_sphere_mesh_bvh`] at each time: a centre
/// on a face gets that face's normal, flagged; a negative or NaN `t_max` is
/// read as 0.
pub fn toi_sphere_mesh_halving<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &MeshBvh<T>,
    vb: &Vec3<T>,
    t_max: T,
    stop: Halving<T>,
) -> Option<MeshToi<T>> {
    let v = va - vb;
    let contact_at = |t: T| {
        contact_sphere_mesh_bvh(&Sphere::new(a.center + v * t, a.radius), b).map(|mut k: MeshContact<T>| {
            k.contact.point += vb * t;
            k
        })
    };
    bisect(contact_at, horizon(t_max, &[va, vb]), stop).map(|h| {
        let triangle = h.at.triangle;
        MeshToi { toi: h.answer(|k| k.contact), triangle }
    })
}
