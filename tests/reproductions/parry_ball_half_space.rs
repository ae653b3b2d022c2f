// parry3d-f64 =0.31.1: contact (a crashtest finding; the exact answer is correctly rounded).
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::{query, shape::*};
fn main() {
    let (pos1, shape1) = (Pose::from_translation(Vector::new(0.0, 0.0, 1.0)), Ball::new(1.0));
    let n2 = Vector::new(0.0, 0.0, 1.0);
    let (pos2, shape2) = (Pose::from_translation(n2.normalize() * (0.0 / n2.length())), HalfSpace::new(n2.normalize()));
    let c = query::contact(&pos1, &shape1, &pos2, &shape2, 0.0).unwrap();
    println!("{c:?}");
    let c = c.expect("exact: a contact, dist 0.0");
    assert!((c.dist - 0.0).abs() <= 3.0000000000000004e-9, "dist {}, exact 0.0", c.dist);
    assert!((c.point2 - Vector::new(0.0, 0.0, 0.0)).abs().max_element() <= 4e-9, "point2 {}", c.point2);
    assert!(c.normal1.angle_between(Vector::new(0.0, 0.0, -1.0)) <= 1.0000000355271367e-7, "normal1 {}", c.normal1);
}
