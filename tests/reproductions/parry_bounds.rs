// parry3d-f64 =0.31.1: bounding sphere of a point cloud (a crashtest finding; the exact answer is correctly rounded).
use parry3d_f64::bounding_volume::details::point_cloud_bounding_sphere;
use parry3d_f64::math::Vector;
fn main() {
    let points = [Vector::new(1.0, 1.0, 1.0), Vector::new(1.0, -1.0, -1.0), Vector::new(-1.0, 1.0, -1.0), Vector::new(-1.0, -1.0, 1.0)];
    let s = point_cloud_bounding_sphere(&points);
    println!("{s:?}");
    for p in &points { assert!((*p - s.center()).length() <= s.radius() + 2.7320508075688773e-9, "{p} outside"); }
}
