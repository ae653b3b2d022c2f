// parry3d-f64 =0.31.1: barycentric coordinates of a projection (a crashtest finding; the exact answer is correctly rounded).
use parry3d_f64::math::Vector;
use parry3d_f64::query::PointQueryWithLocation;
use parry3d_f64::shape::Triangle;
fn main() {
    let tri = Triangle::new(Vector::new(0.0, 0.0, 0.0), Vector::new(3.0, 0.0, 0.0), Vector::new(0.0, 3.0, 0.0));
    let (_, location) = tri.project_local_point_and_get_location(Vector::new(1.0, 1.0, 0.0), false);
    println!("{location:?}");
    let w = location.barycentric_coordinates().expect("coordinates");
    let exact = [0.3333333333333333, 0.3333333333333333, 0.3333333333333333];
    assert!((0..3).all(|i| (w[i] - exact[i]).abs() <= 1.0000050242958679e-9), "{w:?}, exact {exact:?}");
}
