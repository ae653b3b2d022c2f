// parry3d-f64 =0.31.1: ray cast of a segment (a crashtest finding; the exact answer is correctly rounded).
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{Ray, RayCast};
use parry3d_f64::shape::*;
fn main() {
    let ray = Ray::new(Vector::new(0.25, 0.25, 2.0), Vector::new(0.25, 0.25, -1.0) - Vector::new(0.25, 0.25, 2.0));
    let vertices2 = vec![Vector::new(0.0, 0.0, 0.0), Vector::new(0.0, 1.0, 0.0), Vector::new(1.0, 0.0, 0.0), Vector::new(0.0, 0.0, 1.0)];
    let faces2 = vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [2, 1, 3]];
    let (pos2, shape2) = (Pose::IDENTITY, TriMesh::new(vertices2, faces2).unwrap());
    let hit = shape2.cast_ray_and_get_normal(&pos2, &ray, 1.0, false);
    println!("{hit:?}");
    let hit = hit.expect("exact: a hit at t = 0.5");
    assert!((hit.time_of_impact - 0.5).abs() <= 1.000031482169194e-9, "t {}, exact 0.5", hit.time_of_impact);
}
