//! A user's engine: naive sphere–sphere contact and segment–triangle intersection,
//! judged by crashtest. `cargo run --release --example naive_engine` writes the
//! full report with it beside collide and parry; `cargo test` runs the tests below.
use crashtest::geom::vec3::{add, cross, dot, norm, scale, sub};
use crashtest::geom::{Contact, ContactAnswer, IntersectAnswer, Segment, SegmentHit, Sphere, Triangle};
use crashtest::{Campaign, Engine, EngineSet, Queries, Reply};

pub struct Naive;

impl Queries for Naive {
    fn contact_sphere_sphere(&self, a: &Sphere, b: &Sphere) -> Reply<ContactAnswer> {
        let d = sub(a.center, b.center);
        let (len, depth) = (norm(d), a.radius + b.radius - norm(d));
        let normal = if len > 0.0 { scale(d, 1.0 / len) } else { [0.0, 0.0, 1.0] };
        let contact = (depth >= 0.0).then(|| Contact { point: add(b.center, scale(normal, b.radius)), normal, depth });
        Ok(ContactAnswer { contact, degenerate: len == 0.0 })
    }

    fn intersect_segment_triangle(&self, s: &Segment, t: &Triangle) -> Reply<IntersectAnswer> {
        let [v0, v1, v2] = t.vertices;
        let (e1, e2, dir) = (sub(v1, v0), sub(v2, v0), sub(s.end, s.start));
        let n = cross(e1, e2);
        let degenerate = norm(n) == 0.0 || norm(dir) == 0.0;
        let denom = dot(n, dir);
        if degenerate || denom == 0.0 {
            return Ok(IntersectAnswer { hit: None, parallel: !degenerate, degenerate });
        }
        let tt = dot(n, sub(v0, s.start)) / denom;
        let p = add(s.start, scale(dir, tt));
        let w = sub(p, v0);
        let beta = dot(cross(w, e2), n) / dot(n, n);
        let gamma = dot(cross(e1, w), n) / dot(n, n);
        let bary = [1.0 - beta - gamma, beta, gamma];
        let inside = (0.0..=1.0).contains(&tt) && bary.iter().all(|x| *x >= 0.0);
        let normal = scale(n, 1.0 / norm(n));
        let hit = inside.then_some(SegmentHit { t: tt, point: p, normal, barycentric: Some(bary), triangle: None });
        Ok(IntersectAnswer { hit, parallel: false, degenerate: false })
    }
}

fn main() {
    let set = EngineSet::with_builtins(Engine::new("naive", Some(53), Naive), &["all"]).expect("engine set");
    match Campaign::new().engines(set).run() {
        Ok(w) => println!("report: {}", w.index.display()),
        Err(e) => eprintln!("error: {e}"),
    }
}
