//! Judging an answer against a case's own `expect` (the fixture's numbers,
//! within its absolute `tol`), beside the verdict against the referee.

use super::compare::{dist3, unit_excess};
use super::sizes::Region;
use super::verdict::degenerate;
use crate::case::{Case, Expect};
use crate::engine::Answer;
use crate::load::{LoadedCase, bounded_points};
use oracle::geom::P3;
use serde::Serialize;

/// One field of an answer that does not meet the expectation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Mismatch {
    /// The expectation's field: `contact.depth`, `hit`, `parallel`, …
    pub field: String,
    /// What the fixture expects.
    pub expected: String,
    /// What the engine answered.
    pub got: String,
}

fn mm(field: &str, expected: impl std::fmt::Debug, got: impl std::fmt::Debug) -> Mismatch {
    Mismatch { field: field.into(), expected: format!("{expected:?}"), got: format!("{got:?}") }
}

fn cmp3(out: &mut Vec<Mismatch>, field: &str, want: &P3, got: &P3, tol: f64) {
    if !(dist3(want, got) <= tol) {
        out.push(mm(field, want, got));
    }
}

fn cmp1(out: &mut Vec<Mismatch>, field: &str, want: f64, got: f64, tol: f64) {
    if !((want - got).abs() <= tol) {
        out.push(mm(field, want, got));
    }
}

/// `contact.point`: where the contact region is a patch or a segment (a box
/// or a capsule on a plane, two capsules: `docs/FORMAT.md`, "any point of it
/// is right") and the expected point lies in it (within `tol`), any point of
/// the region within `tol` meets the expectation; otherwise the points are
/// compared.
fn contact_point(out: &mut Vec<Mismatch>, case: &Case, want: &P3, got: &P3, tol: f64) {
    let region = case.b.as_ref().and_then(|b| super::sizes::contact_region(&case.a, b));
    match region {
        Some(r) if r.distance(want) <= tol => {
            if !(r.distance(got) <= tol) {
                out.push(mm("contact.point (in the contact region)", want, got));
            }
        }
        _ => cmp3(out, "contact.point", want, got, tol),
    }
}

/// Compares an answer with the case's `expect`, every scalar within the case's
/// absolute `tol`. Only what `expect` names is compared. An empty list is a pass.
pub fn check_expect(lc: &LoadedCase, answer: &Answer) -> Vec<Mismatch> {
    let case: &Case = &lc.case;
    let Some(e): Option<&Expect> = case.expect.as_ref() else { return Vec::new() };
    let tol = case.tol();
    let mut out = Vec::new();
    if let Some(want) = e.degenerate {
        let got = degenerate(answer);
        if want != got {
            out.push(mm("degenerate", want, got));
        }
    }
    match answer {
        Answer::Contact(a) => {
            if let Some(want) = &e.contact {
                match (want, &a.contact) {
                    (None, None) => {}
                    (Some(w), Some(g)) => {
                        contact_point(&mut out, case, &w.point, &g.point, tol);
                        cmp3(&mut out, "contact.normal", &w.normal, &g.normal, tol);
                        unit_expect(&mut out, "contact.normal", &g.normal, tol);
                        cmp1(&mut out, "contact.depth", w.depth, g.depth, tol);
                    }
                    (w, g) => out.push(mm("contact", w, g)),
                }
            }
        }
        Answer::Intersect(a) => {
            if let Some(want) = &e.hit {
                match (want, &a.hit) {
                    (None, None) => {}
                    (Some(w), Some(g)) => {
                        cmp1(&mut out, "hit.t", w.t, g.t, tol);
                        cmp3(&mut out, "hit.point", &w.point, &g.point, tol);
                        cmp3(&mut out, "hit.normal", &w.normal, &g.normal, tol);
                        unit_expect(&mut out, "hit.normal", &g.normal, tol);
                        if let Some(wb) = &w.barycentric {
                            match &g.barycentric {
                                Some(gb) => cmp3(&mut out, "hit.barycentric", wb, gb, tol),
                                None => out.push(mm("hit.barycentric", wb, "none")),
                            }
                        }
                        if let Some(wt) = w.triangle
                            && g.triangle != Some(wt)
                        {
                            out.push(mm("hit.triangle", wt, g.triangle));
                        }
                    }
                    (w, g) => out.push(mm("hit", w, g)),
                }
            }
            if let Some(want) = e.parallel
                && want != a.parallel
            {
                out.push(mm("parallel", want, a.parallel));
            }
        }
        Answer::Barycentric(a) => {
            if let Some(w) = &e.barycentric {
                cmp3(&mut out, "barycentric", w, &a.coords, tol);
            }
        }
        Answer::Bounds(a) => {
            if let Some(w) = &e.aabb {
                match &a.aabb {
                    Some(g) => {
                        cmp3(&mut out, "aabb.min", &w.min, &g.min, tol);
                        cmp3(&mut out, "aabb.max", &w.max, &g.max, tol);
                    }
                    None => out.push(mm("aabb", w, "none")),
                }
            }
            if let Some(r) = e.min_radius {
                match &a.sphere {
                    Some(s) => {
                        cmp1(&mut out, "min_radius", r, s.radius, tol);
                        let pts = bounded_points(lc);
                        let pts = &pts[..];
                        if let Some((i, d)) = farthest_outside(&s.center, s.radius, pts, tol) {
                            out.push(mm(
                                "min_radius (encloses every point)",
                                format!("point {i} inside"),
                                format!("{d:e} outside"),
                            ));
                        }
                    }
                    None => out.push(mm("min_radius", r, "no sphere")),
                }
            }
        }
        Answer::Overlap(g) => {
            if let Some(w) = e.overlap
                && w != *g
            {
                out.push(mm("overlap", w, g));
            }
        }
        Answer::Toi(a) => {
            if let Some(want) = &e.toi {
                match (want, &a.toi) {
                    (None, None) => {}
                    (Some(w), Some(g)) => {
                        cmp1(&mut out, "toi.t", w.t, g.t, tol);
                        cmp3(&mut out, "toi.point", &w.point, &g.point, tol);
                        cmp3(&mut out, "toi.normal", &w.normal, &g.normal, tol);
                        unit_expect(&mut out, "toi.normal", &g.normal, tol);
                    }
                    (w, g) => out.push(mm("toi", w, g)),
                }
            }
        }
        Answer::Response(a) => {
            if let Some(w) = &e.velocity_a {
                cmp3(&mut out, "velocity_a", w, &a.velocity_a, tol);
            }
            if let Some(w) = &e.velocity_b {
                cmp3(&mut out, "velocity_b", w, &a.velocity_b, tol);
            }
        }
        Answer::Ccd(a) => {
            if let Some(want) = e.impact
                && want != a.t.is_some()
            {
                out.push(mm("impact", want, a.t.is_some()));
            }
            if let Some(want) = &e.ccd {
                match (want, &a.t) {
                    (None, None) => {}
                    (Some(w), Some(g)) => cmp1(&mut out, "ccd.t", w.t, *g, tol),
                    (w, g) => out.push(mm("ccd", w, g)),
                }
            }
        }
        Answer::Distance(a) => {
            if let Some(w) = e.distance {
                cmp1(&mut out, "distance", w, a.distance, tol);
            }
            let witnesses = case.b.as_ref().and_then(|b| super::sizes::distance_regions(&case.a, b));
            if let Some(w) = &e.point_a {
                witness(&mut out, "point_a", witnesses.as_ref().map(|w| &w.0), w, &a.point_a, tol);
            }
            if let Some(w) = &e.point_b {
                witness(&mut out, "point_b", witnesses.as_ref().map(|w| &w.1), w, &a.point_b, tol);
            }
            if let Some(w) = &e.normal {
                cmp3(&mut out, "normal", w, &a.normal, tol);
                unit_expect(&mut out, "normal", &a.normal, tol);
            }
        }
    }
    out
}

/// A distance witness: where the witnesses are not unique (`docs/FORMAT.md`,
/// "Distance") and the expected one lies in their set within `tol`, any point
/// of the set within `tol` meets it; otherwise the points are compared.
fn witness(out: &mut Vec<Mismatch>, field: &str, set: Option<&Region>, want: &P3, got: &P3, tol: f64) {
    match set {
        Some(r) if r.distance(want) <= tol => {
            if !(r.distance(got) <= tol) {
                out.push(mm(&format!("{field} (in the witness set)"), want, got));
            }
        }
        _ => cmp3(out, field, want, got, tol),
    }
}

/// An expected normal is unit: the engine's must be too, its length within
/// the case's `tol` of 1 (a normal within `tol` of the expected one in every
/// coordinate may still be up to `√3·tol` longer).
fn unit_expect(out: &mut Vec<Mismatch>, field: &str, got: &P3, tol: f64) {
    let x = unit_excess(got);
    if !(x.abs() <= tol) {
        out.push(mm(&format!("{field} (unit length)"), 1.0, 1.0 + x));
    }
}

/// The first point farther than `radius + tol` from `center`, with its excess.
fn farthest_outside(center: &P3, radius: f64, pts: &[P3], tol: f64) -> Option<(usize, f64)> {
    pts.iter().enumerate().find_map(|(i, p)| {
        // Scaled: the distance of points 1e160 apart does not overflow.
        let d = super::sizes::distance(p, center);
        (!(d <= radius + tol)).then_some((i, d - radius))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::{Loaded, load_str_into};
    use oracle::geom::{Contact, ContactAnswer};

    /// A box resting face down on the plane z = 0 (its face z = 0 is the
    /// region), expecting the face's centre; and two capsules side by side.
    fn cases() -> Vec<LoadedCase> {
        let text = r#"{"schema": "crashtest-fixture/1", "cases": [
            {"name": "resting box", "query": "contact",
             "a": {"box": {"center": [0, 0, 1], "half_extents": [1, 1, 1]}},
             "b": {"plane": {"normal": [0, 0, 1], "offset": 0}},
             "expect": {"contact": {"point": [0, 0, 0], "normal": [0, 0, 1], "depth": 0}}},
            {"name": "parallel capsules", "query": "contact",
             "a": {"capsule": {"start": [0, 0, 1], "end": [4, 0, 1], "radius": 0.5}},
             "b": {"capsule": {"start": [0, 0, 0], "end": [4, 0, 0], "radius": 0.5}},
             "expect": {"contact": {"point": [2, 0, 0.5], "normal": [0, 0, 1], "depth": 0}}}
        ]}"#;
        let mut loaded = Loaded::default();
        load_str_into(std::path::Path::new("region.json"), text, &mut loaded);
        assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
        loaded.cases
    }

    fn answer(point: P3, normal: P3) -> Answer {
        Answer::Contact(ContactAnswer { contact: Some(Contact { point, normal, depth: 0.0 }), degenerate: false })
    }

    #[test]
    fn expect_takes_any_point_of_the_contact_region() {
        let cs = cases();
        // Another corner of the resting face, and another point of the
        // capsules' contact segment: right.
        assert!(check_expect(&cs[0], &answer([1.0, -1.0, 0.0], [0.0, 0.0, 1.0])).is_empty());
        assert!(check_expect(&cs[1], &answer([0.5, 0.0, 0.5], [0.0, 0.0, 1.0])).is_empty());
        // Beside the face, and beyond the segment's end: wrong.
        let off = check_expect(&cs[0], &answer([1.5, 0.0, 0.0], [0.0, 0.0, 1.0]));
        assert_eq!(off.len(), 1, "{off:?}");
        assert!(off[0].field.starts_with("contact.point"), "{off:?}");
        assert_eq!(check_expect(&cs[1], &answer([5.0, 0.0, 0.5], [0.0, 0.0, 1.0])).len(), 1);
    }
}
