// parry3d-f64 =0.31.1: contact (a crashtest finding; the exact answer is correctly rounded).
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::{query, shape::*};
fn main() {
    let (pos1, shape1) = (Pose::from_translation(Vector::new(0.1, 0.1, 0.1)), Ball::new(0.5));
    let vertices2 = vec![Vector::new(0.0, 0.0, 0.0), Vector::new(0.0, 1.0, 0.0), Vector::new(1.0, 0.0, 0.0), Vector::new(0.0, 0.0, 1.0)];
    let faces2 = vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [2, 1, 3]];
    let (pos2, shape2) = (Pose::IDENTITY, TriMesh::new(vertices2, faces2).unwrap());
    let c = query::contact(&pos1, &shape1, &pos2, &shape2, 0.0).unwrap();
    println!("{c:?}");
    let c = c.expect("exact: a contact, dist -0.4");
    assert!((c.dist - -0.4).abs() <= 1.3000007105427359e-9, "dist {}, exact -0.4", c.dist);
    assert!((c.point2 - Vector::new(0.1, 0.1, 0.0)).abs().max_element() <= 5.000007105427358e-10, "point2 {}", c.point2);
    assert!(c.normal1.angle_between(Vector::new(0.0, 0.0, -1.0)) <= 1.0000002131628207e-7, "normal1 {}", c.normal1);
}
