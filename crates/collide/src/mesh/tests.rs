//! Mesh tests: hand-derived cases in both precisions, the three variants of each
//! query agreeing bit for bit on random meshes, and the tree's invariants.

use super::bvh::{Node, STACK};
use super::filter::FaceTest;
use super::*;
use crate::real::{Real, Vec3};
use crate::shapes::{Segment, Sphere};
use proptest::prelude::*;

type P3 = [f64; 3];

fn v<T: Real>(p: P3) -> Vec3<T> {
    Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]))
}

fn seg<T: Real>(a: P3, b: P3) -> Segment<T> {
    Segment::new(v(a), v(b))
}

fn mesh<T: Real>(vertices: &[P3], faces: &[[usize; 3]]) -> TriMesh<T> {
    TriMesh::new(vertices.iter().map(|p| v(*p)).collect(), faces.to_vec()).expect("valid mesh")
}

/// Tolerance on hand-case values (`t`, point coordinates, normal components,
/// barycentrics; all of order 1), absolute: a few roundings in `T` plus the
/// volumes' estimate error of the exact segment–triangle test.
fn tol<T: Real>() -> f64 {
    16.0 * T::EPSILON.wide() + 4.0 * crate::exact::ESTIMATE_REL_ERR
}

/// Two computations of one hit's values (the mesh's certified path and the
/// triangle query), each accurate to about `2·ESTIMATE_REL_ERR` plus a few
/// roundings (absolute, for values of order 1), may differ by this much:
/// `4·ESTIMATE_REL_ERR`.
const VALUE_TOL: f64 = 4.0 * crate::exact::ESTIMATE_REL_ERR;

fn close<T: Real>(got: T, want: f64, what: &str) {
    assert!((got.wide() - want).abs() <= tol::<T>(), "{what}: got {:e}, want {want:e}", got.wide());
}

fn close3<T: Real>(got: &Vec3<T>, want: P3, what: &str) {
    for k in 0..3 {
        close(got[k], want[k], what);
    }
}

/// The corner tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), faces oriented
/// outward: 0 = z=0 (normal −z), 1 = y=0 (−y), 2 = x=0 (−x), 3 = the slanted
/// face x+y+z=1 (normal (1,1,1)/√3).
const TETRA_V: [P3; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
const TETRA_F: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

/// An open unit quad in z = 0 as two faces sharing the diagonal v0 v2 (both
/// normals +z).
const QUAD_V: [P3; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
const QUAD_F: [[usize; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

/// Every segment variant of one query, answered for the same inputs (the
/// batch query with a batch of one).
fn all_segment<T: Real>(s: &Segment<T>, m: &TriMesh<T>) -> [MeshIntersection<T>; 5] {
    let median = MeshBvh::with_split(m.clone(), SplitRule::MedianCentroid);
    let sah = MeshBvh::with_split(m.clone(), SplitRule::SahBinned);
    [
        intersect_segment_mesh_brute(s, m),
        intersect_segment_mesh_culled(s, m),
        intersect_segment_mesh_bvh(s, &median),
        intersect_segment_mesh_bvh(s, &sah),
        batch_of_one(s, m),
    ]
}

/// [`intersect_segments_mesh`] on one segment; the output holds exactly one
/// answer.
fn batch_of_one<T: Real>(s: &Segment<T>, m: &TriMesh<T>) -> MeshIntersection<T> {
    let mut out = vec![MeshIntersection::DEGENERATE; 3];
    intersect_segments_mesh(core::slice::from_ref(s), &FaceArrays::new(m.clone()), &mut out);
    assert_eq!(out.len(), 1, "one answer per segment");
    out[0]
}

/// The robust variants agree exactly (bit for bit is the claim, so `==`); the
/// answer is theirs.
fn robust<T: Real>(s: &Segment<T>, m: &TriMesh<T>) -> MeshIntersection<T> {
    let all = all_segment(s, m);
    for (k, a) in all.iter().enumerate() {
        assert_eq!(*a, all[0], "variant {k} differs from brute force");
    }
    all[0]
}

fn tetra_hits<T: Real>() {
    let m = mesh::<T>(&TETRA_V, &TETRA_F);
    // Down the line x = y = 0.25 from z = 2 to z = −1: the slanted face at
    // z = 0.5 (t = 1.5/3 = 0.5), then the base at t = 2/3: face 3 first.
    let a = robust(&seg::<T>([0.25, 0.25, 2.0], [0.25, 0.25, -1.0]), &m);
    let h = a.hit.expect("hit");
    assert_eq!(h.triangle, 3);
    close(h.t, 0.5, "t");
    close3(&h.point, [0.25, 0.25, 0.5], "point");
    let r3 = 1.0 / 3f64.sqrt();
    close3(&h.normal, [r3, r3, r3], "normal: the face's own");
    // point = α(1,0,0) + β(0,1,0) + γ(0,0,1): [0.25, 0.25, 0.5].
    for k in 0..3 {
        close(h.barycentric[k], [0.25, 0.25, 0.5][k], "barycentric");
    }
    assert!(!a.parallel && !a.degenerate);
    // Reversed: the base first (t = 1/3), its normal −z, not flipped.
    let h = robust(&seg::<T>([0.25, 0.25, -1.0], [0.25, 0.25, 2.0]), &m).hit.expect("hit");
    assert_eq!(h.triangle, 0);
    close(h.t, 1.0 / 3.0, "t");
    close3(&h.normal, [0.0, 0.0, -1.0], "normal");
    // Starting inside: the first hit is where it leaves.
    let h = robust(&seg::<T>([0.1, 0.1, 0.1], [0.1, 0.1, -0.9]), &m).hit.expect("hit");
    assert_eq!(h.triangle, 0);
    close(h.t, 0.1, "t");
}

#[test]
fn mesh_tetrahedron_first_hit_f64() {
    tetra_hits::<f64>();
}

#[test]
fn mesh_tetrahedron_first_hit_f32() {
    tetra_hits::<f32>();
}

fn ties<T: Real>() {
    let quad = mesh::<T>(&QUAD_V, &QUAD_F);
    // Through the shared diagonal at (0.5, 0.5): both faces at t = 1/2; the
    // lower index wins, whichever the tree reaches first.
    let h = robust(&seg::<T>([0.5, 0.5, 1.0], [0.5, 0.5, -1.0]), &quad).hit.expect("hit");
    assert_eq!(h.triangle, 0, "tie to the lowest face index");
    close(h.t, 0.5, "t");
    // The same faces listed the other way round: still the lower index.
    let swapped = mesh::<T>(&QUAD_V, &[QUAD_F[1], QUAD_F[0]]);
    let h = robust(&seg::<T>([0.5, 0.5, 1.0], [0.5, 0.5, -1.0]), &swapped).hit.expect("hit");
    assert_eq!(h.triangle, 0);
    // Through the tetrahedron's apex (0,0,1), shared by faces 1, 2 and 3, along
    // d = (1, 2, −4) (in none of their planes: d·n ≠ 0 for y = 0, x = 0 and
    // x+y+z = 1): from apex − d/2 to apex + d/2 all three are met at t = 1/2,
    // then the base at t = 3/4. The tie goes to face 1.
    let tetra = mesh::<T>(&TETRA_V, &TETRA_F);
    let h = robust(&seg::<T>([-0.5, -1.0, 3.0], [0.5, 1.0, -1.0]), &tetra).hit.expect("hit");
    assert_eq!(h.triangle, 1, "vertex tie");
    close(h.t, 0.5, "t");
    close3(&h.point, [0.0, 0.0, 1.0], "the apex");
}

#[test]
fn mesh_shared_edge_and_vertex_ties_go_to_the_lowest_index_f64() {
    ties::<f64>();
}

#[test]
fn mesh_shared_edge_and_vertex_ties_go_to_the_lowest_index_f32() {
    ties::<f32>();
}

#[test]
fn mesh_first_hit_is_decided_exactly_below_rounding() {
    // Two parallel faces 2^-60 apart; a segment from z = 1 to z = −1 meets them
    // at t = 1/2 − 2^-61 and t = 1/2, both rounding to 0.5 in f64. The upper face
    // is listed second, so only an exact comparison picks it.
    let e = 2f64.powi(-60);
    let m = mesh::<f64>(
        &[[-1.0, -1.0, 0.0], [3.0, -1.0, 0.0], [-1.0, 3.0, 0.0], [-1.0, -1.0, e], [3.0, -1.0, e], [-1.0, 3.0, e]],
        &[[0, 1, 2], [3, 4, 5]],
    );
    let h = robust(&seg([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]), &m).hit.expect("hit");
    assert_eq!(h.triangle, 1, "the upper face is first, by 2^-61");
}

fn misses_and_flags<T: Real>() {
    let tetra = mesh::<T>(&TETRA_V, &TETRA_F);
    // Through the box [0,1]³ but outside the tetrahedron: from (0.9, 0.9, −1)
    // up to (0.9, 0.9, 2) crosses the box; x + y = 1.8 > 1, so no face.
    let a = robust(&seg::<T>([0.9, 0.9, -1.0], [0.9, 0.9, 2.0]), &tetra);
    assert_eq!(a, MeshIntersection { hit: None, parallel: false, degenerate: false });
    // Stopping short of the base (z from −1 to −2^-20): a plain miss.
    let a = robust(&seg::<T>([0.25, 0.25, -1.0], [0.25, 0.25, -(2f64.powi(-20))]), &tetra);
    assert!(a.hit.is_none() && !a.parallel);
    // Ending exactly on the base: a hit at t = 1.
    let h = robust(&seg::<T>([0.25, 0.25, -1.0], [0.25, 0.25, 0.0]), &tetra).hit.expect("touching counts");
    close(h.t, 1.0, "t");
    // The open quad is flat: a segment in its plane (or parallel to it) is
    // parallel to every face.
    let quad = mesh::<T>(&QUAD_V, &QUAD_F);
    for s in [seg::<T>([-1.0, 0.5, 0.0], [2.0, 0.5, 0.0]), seg::<T>([-1.0, 0.5, 1.0], [2.0, 0.5, 1.0])] {
        let a = robust(&s, &quad);
        assert!(a.hit.is_none() && a.parallel && !a.degenerate, "{a:?}");
        let l = intersect_segment_mesh_lecture(&s, &quad);
        assert!(l.hit.is_none() && l.parallel && !l.degenerate, "lecture: {l:?}");
    }
    // The tetrahedron has faces in every direction: never parallel.
    let a = robust(&seg::<T>([5.0, 0.5, 0.0], [6.0, 0.5, 0.0]), &tetra);
    assert!(a.hit.is_none() && !a.parallel);
}

#[test]
fn mesh_misses_and_parallel_flag_f64() {
    misses_and_flags::<f64>();
}

#[test]
fn mesh_misses_and_parallel_flag_f32() {
    misses_and_flags::<f32>();
}

fn degenerate_input<T: Real>() {
    // The quad plus a zero-area face (three collinear points) listed first.
    let mut verts = QUAD_V.to_vec();
    verts.push([2.0, 2.0, 0.0]);
    let m = mesh::<T>(&verts, &[[0, 2, 4], QUAD_F[0], QUAD_F[1]]);
    assert!(m.is_degenerate_face(0) && m.degenerate_face_count() == 1);
    // The degenerate face lies on the segment's path: skipped, flagged, and
    // the next face answers (the diagonal tie between faces 1 and 2 → 1).
    let a = robust(&seg::<T>([0.5, 0.5, 1.0], [0.5, 0.5, -1.0]), &m);
    assert!(a.degenerate);
    assert_eq!(a.hit.expect("hit").triangle, 1);
    let l = intersect_segment_mesh_lecture(&seg::<T>([0.5, 0.5, 1.0], [0.5, 0.5, -1.0]), &m);
    assert!(l.degenerate && l.hit.is_some(), "lecture: {l:?}");
    // A zero-length segment: degenerate, nothing else.
    let p = [0.5, 0.25, 0.0];
    assert_eq!(robust(&seg::<T>(p, p), &m), MeshIntersection::DEGENERATE);
    assert_eq!(intersect_segment_mesh_lecture(&seg::<T>(p, p), &m), MeshIntersection::DEGENERATE);
    // Only degenerate faces: flagged, never parallel.
    let flat = mesh::<T>(&verts, &[[0, 2, 4]]);
    let a = robust(&seg::<T>([-1.0, 0.5, 0.0], [2.0, 0.5, 0.0]), &flat);
    assert!(a.hit.is_none() && !a.parallel && a.degenerate);
    // An empty mesh: nothing at all.
    let empty = mesh::<T>(&verts, &[]);
    assert_eq!(
        robust(&seg::<T>([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]), &empty),
        MeshIntersection { hit: None, parallel: false, degenerate: false }
    );
}

#[test]
fn mesh_degenerate_faces_and_segments_f64() {
    degenerate_input::<f64>();
}

#[test]
fn mesh_degenerate_faces_and_segments_f32() {
    degenerate_input::<f32>();
}

#[test]
fn mesh_non_finite_vertices_are_degenerate_faces_not_errors() {
    // 1e39 is finite in f64 and infinite in f32: the face using it is skipped
    // and flagged in f32 only; the other face still answers.
    let verts = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1e39, 0.0, 5.0]];
    let faces = [[0, 1, 3], [0, 1, 2]];
    let s = [[0.25, 0.25, 1.0], [0.25, 0.25, -1.0]];
    let m32 = mesh::<f32>(&verts, &faces);
    assert!(m32.has_nonfinite_vertex(0) && m32.is_degenerate_face(0));
    let a = robust(&seg::<f32>(s[0], s[1]), &m32);
    assert!(a.degenerate && a.hit.expect("hit").triangle == 1, "{a:?}");
    assert!(!mesh::<f64>(&verts, &faces).has_nonfinite_vertex(0));
    let c = contact_sphere_mesh_brute(&Sphere::new(v::<f32>([0.25, 0.25, 0.5]), 1.0), &m32)
        .expect("contact with the finite face");
    assert_eq!(c.triangle, 1);
    assert_eq!(MeshBvh::new(m32).node_count(), 1, "one finite face, one leaf");
}

#[test]
fn mesh_index_out_of_range_is_refused() {
    let e = TriMesh::<f64>::new(vec![Vec3::zeros(); 3], vec![[0, 1, 2], [0, 3, 1]]);
    assert_eq!(e, Err(MeshError::IndexOutOfRange { face: 1, corner: 1, index: 3, vertices: 3 }));
    let msg = e.expect_err("refused").to_string();
    assert!(msg.contains("face 1") && msg.contains("index 3"), "{msg}");
}

#[test]
fn mesh_aabb_covers_the_finite_faces_only() {
    let m = mesh::<f64>(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, -3.0], [9.0, 9.0, 9.0]], &[[0, 1, 2]]);
    // Exact: a box selects input coordinates, no arithmetic.
    let bb = m.aabb().expect("box");
    assert_eq!(bb.min, Vec3::new(0.0, 0.0, -3.0));
    assert_eq!(bb.max, Vec3::new(1.0, 2.0, 0.0), "the unused vertex is not in it");
    assert!(mesh::<f64>(&TETRA_V, &[]).aabb().is_none());
}

fn sphere_cases<T: Real>() {
    let m = mesh::<T>(&TETRA_V, &TETRA_F);
    let variants = |s: &Sphere<T>| {
        let a = [
            contact_sphere_mesh_brute(s, &m),
            contact_sphere_mesh_culled(s, &m),
            contact_sphere_mesh_bvh(s, &MeshBvh::with_split(m.clone(), SplitRule::MedianCentroid)),
            contact_sphere_mesh_bvh(s, &MeshBvh::new(m.clone())),
        ];
        for (k, x) in a.iter().enumerate() {
            assert_eq!(*x, a[0], "variant {k}");
        }
        a[0]
    };
    // Below the base: centre (0.25, 0.25, −0.5), r = 1: the base at distance
    // 0.5 is deepest (depth 0.5), normal −z toward the centre.
    let k = variants(&Sphere::new(v([0.25, 0.25, -0.5]), T::one())).expect("contact");
    assert_eq!(k.triangle, 0);
    close(k.contact.depth, 0.5, "depth");
    close3(&k.contact.normal, [0.0, 0.0, -1.0], "normal");
    close3(&k.contact.point, [0.25, 0.25, 0.0], "point");
    // Inside, nearest the slanted face: centre (0.3, 0.3, 0.3) is 0.1/√3 from
    // x+y+z = 1 and 0.3 from the others: face 3, depth r − 0.1/√3.
    let k = variants(&Sphere::new(v([0.3, 0.3, 0.3]), T::one())).expect("contact");
    assert_eq!(k.triangle, 3);
    close(k.contact.depth, 1.0 - 0.1 / 3f64.sqrt(), "depth");
    // Equidistant from faces 0, 1 and 2 (centre (0.2, 0.2, 0.2)): lowest index.
    let k = variants(&Sphere::new(v([0.2, 0.2, 0.2]), T::one())).expect("contact");
    assert_eq!(k.triangle, 0, "tie to the lowest face index");
    // Touching the apex from above: depth 0 counts; just apart: none.
    let k = variants(&Sphere::new(v([0.0, 0.0, 2.0]), T::one())).expect("touching");
    close(k.contact.depth, 0.0, "depth");
    assert!(variants(&Sphere::new(v([0.0, 0.0, 2.5]), T::one())).is_none());
    // Far away: culled, none.
    assert!(variants(&Sphere::new(v([10.0, 10.0, 10.0]), T::one())).is_none());
    // Centre on a face: the face normal as fallback, flagged.
    let k = variants(&Sphere::new(v([0.25, 0.25, 0.0]), T::one())).expect("contact");
    assert!(k.contact.degenerate);
    close(k.contact.depth, 1.0, "depth");
    // Non-finite centre: none.
    let nan = T::zero() / T::zero();
    let s = Sphere::new(Vec3::new(nan, T::zero(), T::zero()), T::one());
    assert!(variants(&s).is_none());
}

#[test]
fn mesh_sphere_contact_deepest_face_f64() {
    sphere_cases::<f64>();
}

#[test]
fn mesh_sphere_contact_deepest_face_f32() {
    sphere_cases::<f32>();
}

/// Checks the flat tree: every finite face in exactly one leaf, every box the
/// exact box of what is below it, depth within the cap and the stack.
fn check_tree<T: Real>(bvh: &MeshBvh<T>) {
    let m = bvh.mesh();
    let nodes = bvh.nodes();
    let mut seen = vec![0usize; m.len()];
    fn walk<T: Real>(
        bvh: &MeshBvh<T>,
        nodes: &[Node<T>],
        i: usize,
        depth: usize,
        seen: &mut [usize],
    ) -> ([T; 3], [T; 3]) {
        assert!(depth <= BVH_MAX_DEPTH && depth <= bvh.depth());
        let n = nodes[i];
        let (lo, hi) = if n.count > 0 {
            let mut lo = [T::of(f64::INFINITY); 3];
            let mut hi = [T::of(f64::NEG_INFINITY); 3];
            for k in n.start..n.start + n.count {
                let (tri, face) = bvh.leaf_face(k as usize);
                seen[face] += 1;
                assert_eq!(*tri, bvh.mesh().triangle(face), "leaf copy of face {face}");
                for p in tri.vertices {
                    for a in 0..3 {
                        lo[a] = lo[a].min(p[a]);
                        hi[a] = hi[a].max(p[a]);
                    }
                }
            }
            (lo, hi)
        } else {
            let l = walk(bvh, nodes, i + 1, depth + 1, seen);
            let r = walk(bvh, nodes, n.start as usize, depth + 1, seen);
            ([0, 1, 2].map(|a| l.0[a].min(r.0[a])), [0, 1, 2].map(|a| l.1[a].max(r.1[a])))
        };
        assert_eq!((n.min, n.max), (lo, hi), "node {i}: exact box of its contents");
        (lo, hi)
    }
    if !nodes.is_empty() {
        walk(bvh, nodes, 0, 0, &mut seen);
    }
    for (face, count) in seen.iter().enumerate() {
        let want = usize::from(!m.has_nonfinite_vertex(face));
        assert_eq!(*count, want, "face {face} appears {count} times");
    }
    assert!(bvh.depth() + 2 <= STACK);
}

/// A closed UV sphere of radius 1 (a real, curved mesh with shared edges and
/// vertices): `rings × segments` quads split into two faces each.
fn uv_sphere(rings: usize, segments: usize) -> (Vec<P3>, Vec<[usize; 3]>) {
    let mut vs = Vec::new();
    for i in 0..=rings {
        let th = core::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..segments {
            let ph = 2.0 * core::f64::consts::PI * j as f64 / segments as f64;
            // The poles exactly: sin(π) ≠ 0 in floating point would leave a
            // 1e-16-wide hole around the z axis.
            let pole = if i == 0 {
                Some(1.0)
            } else if i == rings {
                Some(-1.0)
            } else {
                None
            };
            vs.push(match pole {
                Some(z) => [0.0, 0.0, z],
                None => [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()],
            });
        }
    }
    let mut fs = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let a = i * segments + j;
            let b = i * segments + (j + 1) % segments;
            let (c, d) = (a + segments, b + segments);
            fs.push([a, c, b]);
            fs.push([b, c, d]);
        }
    }
    (vs, fs)
}

#[test]
fn mesh_bvh_trees_are_exact_and_within_the_depth_cap() {
    let (vs, fs) = uv_sphere(24, 48);
    for rule in [SplitRule::MedianCentroid, SplitRule::SahBinned] {
        let bvh = MeshBvh::with_split(mesh::<f64>(&vs, &fs), rule);
        check_tree(&bvh);
        assert!(bvh.leaf_count() >= fs.len() / 8, "{rule:?}: leaves hold ≤ 8 faces");
        check_tree(&MeshBvh::with_split(mesh::<f32>(&vs, &fs), rule));
    }
    // Every face the same (coincident centroids): still split, still exact.
    let same = vec![[0, 1, 2]; 100];
    let bvh = MeshBvh::new(mesh::<f64>(&TETRA_V, &same));
    check_tree(&bvh);
    assert!(bvh.depth() <= 8, "halved by index: depth {}", bvh.depth());
    let empty = MeshBvh::new(mesh::<f64>(&TETRA_V, &[]));
    assert_eq!(empty.node_count(), 0);
}

#[test]
fn mesh_bvh_agrees_with_brute_force_on_a_closed_sphere() {
    // Segments from outside to the centre: exactly one crossing each, near the
    // shared edges as often as not.
    let (vs, fs) = uv_sphere(16, 32);
    let m = mesh::<f64>(&vs, &fs);
    let bvh = MeshBvh::new(m.clone());
    let mut hits = 0;
    let mut segs = Vec::new();
    for i in 0..2000 {
        let a = i as f64 * 0.618_033_988_749_895;
        let z = 2.0 * ((i as f64 * 0.414_213_562_373_095) % 1.0) - 1.0;
        let r = (1.0 - z * z).sqrt();
        let far = [2.0 * r * a.cos(), 2.0 * r * a.sin(), 2.0 * z];
        let s = seg::<f64>(far, [0.0, 0.0, 0.0]);
        segs.push(s);
        let b = intersect_segment_mesh_brute(&s, &m);
        assert_eq!(intersect_segment_mesh_bvh(&s, &bvh), b, "segment {i}");
        let h = b.hit.unwrap_or_else(|| panic!("segment {i} {far:?} misses: {b:?}"));
        assert!(h.t.wide() > 0.45 && h.t.wide() < 0.55, "t {} near 1/2", h.t);
        hits += 1;
    }
    assert_eq!(hits, 2000);
    // The batch query over all of them at once (many blocks of faces).
    let faces = FaceArrays::new(m.clone());
    assert!(faces.len() > 900, "{} faces with area", faces.len());
    let mut out = Vec::new();
    intersect_segments_mesh(&segs, &faces, &mut out);
    assert_eq!(out.len(), segs.len());
    for (i, (s, got)) in segs.iter().zip(&out).enumerate() {
        assert_eq!(*got, intersect_segment_mesh_brute(s, &m), "batch, segment {i}");
    }
}

#[test]
fn mesh_batch_answers_segments_beyond_the_filter_range_and_degenerate_ones() {
    // A batch mixing a segment within the filter's range, one beyond it (2^61,
    // answered by the brute-force query), a zero-length one and a non-finite
    // one; then a mesh beyond the range (every segment brute force).
    let m = mesh::<f64>(&QUAD_V, &QUAD_F);
    let big = 2.0f64.powi(61);
    let segs = [
        seg::<f64>([0.5, 0.25, 1.0], [0.5, 0.25, -1.0]),
        seg::<f64>([0.5, 0.25, big], [0.5, 0.25, -big]),
        seg::<f64>([0.5, 0.25, 0.0], [0.5, 0.25, 0.0]),
        seg::<f64>([0.5, f64::NAN, 1.0], [0.5, 0.25, -1.0]),
        seg::<f64>([2.0, 2.0, 1.0], [2.0, 2.0, -1.0]),
    ];
    let mut out = Vec::new();
    intersect_segments_mesh(&segs, &FaceArrays::new(m.clone()), &mut out);
    assert_eq!(out.len(), segs.len());
    for (i, (s, got)) in segs.iter().zip(&out).enumerate() {
        assert_eq!(*got, intersect_segment_mesh_brute(s, &m), "segment {i}");
    }
    assert_eq!(out[0].hit.expect("hit").triangle, 0);
    assert_eq!(out[1].hit.expect("hit").triangle, 0);
    assert_eq!(out[2], MeshIntersection::DEGENERATE);
    assert_eq!(out[3], MeshIntersection::DEGENERATE);
    assert!(out[4].hit.is_none() && !out[4].degenerate);
    let far: Vec<P3> = QUAD_V.iter().map(|p| p.map(|x| x * big)).collect();
    let mf = mesh::<f64>(&far, &QUAD_F);
    let faces = FaceArrays::new(mf.clone());
    assert_eq!(faces.len(), 2);
    let segs = [seg::<f64>([0.5 * big, 0.25 * big, 1.0], [0.5 * big, 0.25 * big, -1.0])];
    intersect_segments_mesh(&segs, &faces, &mut out);
    assert_eq!(out, vec![intersect_segment_mesh_brute(&segs[0], &mf)]);
    assert_eq!(out[0].hit.expect("hit").triangle, 0);
}

fn coord() -> impl Strategy<Value = f64> {
    // Small integers make shared edges, coplanar faces, ties and degenerate
    // faces common; the continuous range covers the general case.
    prop_oneof![(-2i8..=2).prop_map(f64::from), -3.0..3.0f64]
}

fn point() -> impl Strategy<Value = P3> {
    [coord(), coord(), coord()]
}

fn soup() -> impl Strategy<Value = (Vec<P3>, Vec<[usize; 3]>)> {
    prop::collection::vec(point(), 3..12).prop_flat_map(|vs| {
        let n = vs.len();
        (Just(vs), prop::collection::vec([0..n, 0..n, 0..n], 0..24))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn mesh_classification_and_filter_agree_with_the_triangle_query(
        a in point(), b in point(), c in point(), q0 in point(), q1 in point(), nudge in -2i32..=2
    ) {
        // Nudging an endpoint by a few ulps puts it just off edges, vertices and
        // planes, where the filter's bounds matter.
        let q1 = q1.map(|x| {
            let mut y = x;
            for _ in 0..nudge.unsigned_abs() {
                y = if nudge > 0 { y.next_up() } else { y.next_down() };
            }
            y
        });
        prop_assume!(!crate::exact::points_equal(q0, q1));
        let s = seg::<f64>(q0, q1);
        let tri = crate::shapes::Triangle::new(v(a), v(b), v(c));
        let one = crate::intersect::intersect_segment_triangle(&s, &tri).hit;
        prop_assert_eq!(super::segment_mesh::classify([a, b, c], [q0, q1]).is_some(), one.is_some());
        let sf = super::filter::SegmentFilter::new(q0, q1).expect("small coordinates");
        match super::filter::FaceFilter::new([a, b, c]).test(&sf) {
            FaceTest::Miss => prop_assert!(one.is_none(), "the filter dropped a hit"),
            FaceTest::Hit { lo, hi } => {
                let h = one.expect("the filter's hit is a hit");
                // The bracket is widened by its own rounding, so with an end a
                // few ulps off the plane `hi` may pass 1 (the exact t < 1 lies
                // inside it all the same); only its order and sign are asserted.
                prop_assert!(lo <= hi && lo > 0.0, "bracket [{}, {}]", lo, hi);
                prop_assert!(lo - VALUE_TOL <= h.t && h.t <= hi + VALUE_TOL, "t {} outside [{}, {}]", h.t, lo, hi);
            }
            FaceTest::Undecided => {}
        }
        // The winner's values (certified path or the triangle query's) against
        // the triangle query's.
        if let Some(want) = one {
            let got = super::values::hit_values(&s, &tri, [q0, q1]).expect("a hit has values");
            prop_assert!((got.t - want.t).abs() <= VALUE_TOL, "t {} vs {}", got.t, want.t);
            let (gb, wb) = (got.barycentric.expect("barycentrics"), want.barycentric.expect("barycentrics"));
            for k in 0..3 {
                prop_assert!((gb[k] - wb[k]).abs() <= VALUE_TOL, "barycentric {}: {:?} vs {:?}", k, gb, wb);
                prop_assert!((got.normal[k] - want.normal[k]).abs() <= VALUE_TOL, "normal {:?} vs {:?}", got.normal, want.normal);
                let scale = 1.0 + q0[k].abs().max(q1[k].abs());
                prop_assert!((got.point[k] - want.point[k]).abs() <= VALUE_TOL * scale, "point {:?} vs {:?}", got.point, want.point);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(768))]

    #[test]
    fn mesh_segment_variants_agree_exactly((vs, fs) in soup(), a in point(), b in point()) {
        let all = all_segment(&seg::<f64>(a, b), &mesh::<f64>(&vs, &fs));
        for (k, x) in all.iter().enumerate() {
            prop_assert_eq!(*x, all[0], "variant {}", k);
        }
        let m32 = mesh::<f32>(&vs, &fs);
        let s32 = seg::<f32>(a, b);
        let b32 = intersect_segment_mesh_brute(&s32, &m32);
        for x in all_segment(&s32, &m32) {
            prop_assert_eq!(x, b32, "f32");
        }
        let l = intersect_segment_mesh_lecture(&seg::<f64>(a, b), &mesh::<f64>(&vs, &fs));
        if let Some(h) = l.hit {
            prop_assert!(h.t.is_finite() && (0.0..=1.0).contains(&h.t), "lecture t {}", h.t);
        }
    }

    #[test]
    fn mesh_batch_agrees_exactly_across_blocks(
        vs in prop::collection::vec(point(), 3..16),
        picks in prop::collection::vec([0..1000usize, 0..1000usize, 0..1000usize], 0..200),
        ends in prop::collection::vec((point(), point()), 1..6),
    ) {
        // Up to 200 faces: several blocks of lanes, a part-filled last one.
        let fs: Vec<[usize; 3]> = picks.iter().map(|p| p.map(|i| i % vs.len())).collect();
        let segs: Vec<Segment<f64>> = ends.iter().map(|&(a, b)| seg(a, b)).collect();
        let m = mesh::<f64>(&vs, &fs);
        let mut out = Vec::new();
        intersect_segments_mesh(&segs, &FaceArrays::new(m.clone()), &mut out);
        prop_assert_eq!(out.len(), segs.len());
        for (s, got) in segs.iter().zip(&out) {
            prop_assert_eq!(*got, intersect_segment_mesh_brute(s, &m));
        }
        let m32 = mesh::<f32>(&vs, &fs);
        let s32: Vec<Segment<f32>> = ends.iter().map(|&(a, b)| seg(a, b)).collect();
        let mut out32 = Vec::new();
        intersect_segments_mesh(&s32, &FaceArrays::new(m32.clone()), &mut out32);
        for (s, got) in s32.iter().zip(&out32) {
            prop_assert_eq!(*got, intersect_segment_mesh_brute(s, &m32), "f32");
        }
    }

    #[test]
    fn mesh_first_hit_is_no_later_than_any_face_hit((vs, fs) in soup(), a in point(), b in point()) {
        let m = mesh::<f64>(&vs, &fs);
        let s = seg::<f64>(a, b);
        let got = intersect_segment_mesh_brute(&s, &m);
        for face in 0..m.len() {
            let one = crate::intersect::intersect_segment_triangle(&s, &m.triangle(face));
            if let Some(h) = one.hit {
                let first = got.hit.expect("a face is hit, so the mesh is");
                prop_assert!(first.t <= h.t + 4.0 * crate::exact::ESTIMATE_REL_ERR,
                    "face {} hit at {} before the answer's {}", face, h.t, first.t);
                prop_assert!(!got.parallel);
            }
        }
        if let Some(h) = got.hit {
            let one = crate::intersect::intersect_segment_triangle(&s, &m.triangle(h.triangle));
            let t = one.hit.expect("the answer's face is hit").t;
            prop_assert!((t - h.t).abs() <= VALUE_TOL, "the answer is its face's hit: t {} vs {}", h.t, t);
        }
    }

    #[test]
    fn mesh_sphere_variants_agree_exactly((vs, fs) in soup(), c in point(), r in 0.0..3.0f64) {
        let m = mesh::<f64>(&vs, &fs);
        let s = Sphere::new(v::<f64>(c), r);
        let want = contact_sphere_mesh_brute(&s, &m);
        prop_assert_eq!(contact_sphere_mesh_culled(&s, &m), want);
        prop_assert_eq!(contact_sphere_mesh_bvh(&s, &MeshBvh::new(m.clone())), want);
        prop_assert_eq!(contact_sphere_mesh_bvh(&s, &MeshBvh::with_split(m, SplitRule::MedianCentroid)), want);
        if let Some(k) = want {
            prop_assert!(k.contact.depth >= 0.0 && k.contact.depth <= r, "depth {}", k.contact.depth);
            prop_assert!((k.contact.normal.norm() - 1.0).abs() <= 1e-12, "unit normal");
        }
    }
}

#[test]
fn mesh_hit_values_are_certified_for_small_far_faces() {
    // The bunny's regime: faces a few hundredths of the segment's length,
    // far from both endpoints, where the triangle query's own barycentrics
    // need exact arithmetic. The certified path must answer almost always and
    // agree with the triangle query.
    let mut state = 0x5eed_0006_u64;
    let mut unit = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut hits, mut certified) = (0, 0);
    for _ in 0..8000 {
        let centre = [0; 3].map(|_| 10.0 * unit() - 5.0);
        let tri = [0; 3].map(|_| [0, 1, 2].map(|k| centre[k] + 0.2 * unit() - 0.1));
        let dir = [0; 3].map(|_| 2.0 * unit() - 1.0);
        let (a, b) = (10.0 * unit(), 10.0 * unit());
        let q0 = [0, 1, 2].map(|k| centre[k] - a * dir[k]);
        let q1 = [0, 1, 2].map(|k| centre[k] + b * dir[k]);
        let s = seg::<f64>(q0, q1);
        let t = crate::shapes::Triangle::new(v(tri[0]), v(tri[1]), v(tri[2]));
        let Some(want) = crate::intersect::intersect_segment_triangle(&s, &t).hit else {
            continue;
        };
        hits += 1;
        let Some(got) = super::values::certified(tri, [q0, q1]) else {
            continue;
        };
        certified += 1;
        assert!((got.t - want.t).abs() <= VALUE_TOL, "t {} vs {}", got.t, want.t);
        let wb = want.barycentric.expect("barycentrics");
        for k in 0..3 {
            assert!((got.barycentric[k] - wb[k]).abs() <= VALUE_TOL, "{:?} vs {wb:?}", got.barycentric);
            assert!((got.normal[k] - want.normal[k]).abs() <= VALUE_TOL, "{:?} vs {:?}", got.normal, want.normal);
            assert!((got.point[k] - want.point[k]).abs() <= 16.0 * VALUE_TOL, "{:?} vs {:?}", got.point, want.point);
        }
    }
    assert!(hits >= 1000, "the cases hit: {hits}");
    assert!(certified * 100 >= hits * 99, "certified {certified} of {hits}");
}

#[test]
fn mesh_faces_near_segment_hold_every_face_hit() {
    let (vs, fs) = uv_sphere(12, 24);
    let m = mesh::<f64>(&vs, &fs);
    for rule in [SplitRule::MedianCentroid, SplitRule::SahBinned] {
        let bvh = MeshBvh::with_split(m.clone(), rule);
        let mut near = Vec::new();
        let mut total = 0;
        for i in 0..500 {
            let x = i as f64 * 0.618_033_988_749_895;
            let a = [2.0 * (x % 1.0) - 1.0, 2.0 * ((x * 1.7) % 1.0) - 1.0, 1.5];
            let b = [2.0 * ((x * 2.3) % 1.0) - 1.0, 2.0 * ((x * 3.1) % 1.0) - 1.0, -1.5];
            let s = seg::<f64>(a, b);
            bvh.faces_near_segment(&s, &mut near);
            total += near.len();
            for face in 0..m.len() {
                if crate::intersect::intersect_segment_triangle(&s, &m.triangle(face)).hit.is_some() {
                    assert!(near.contains(&face), "{rule:?}, segment {i}: face {face} is hit but not near");
                }
            }
        }
        assert!(total < 500 * m.len() / 4, "{rule:?}: the tree prunes ({total} faces near in all)");
        // Beside the sphere's box: nothing; a non-finite segment: nothing.
        bvh.faces_near_segment(&seg::<f64>([3.0, 3.0, -1.0], [3.0, 3.0, 1.0]), &mut near);
        assert!(near.is_empty(), "{rule:?}: {near:?}");
        bvh.faces_near_segment(&seg::<f64>([f64::NAN, 0.0, 0.0], [0.0, 0.0, 0.0]), &mut near);
        assert!(near.is_empty());
        // A point on the surface: the faces of the leaves around it.
        bvh.faces_near_segment(&seg::<f64>([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]), &mut near);
        assert!(!near.is_empty(), "{rule:?}: the pole");
    }
}
