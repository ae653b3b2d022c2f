//! The judge's second round: a normal is judged on its length as well as its
//! angle, and accuracy is measured in ulps (`--ulps N` holds every engine to
//! `N` ulps of each field's magnitude, the conditioning allowances kept).

use harness::case::Query;
use harness::check::{check_case, run_caught};
use harness::engine::{Answer, Engine, Queries, Reply};
use harness::engines::{EngineSet, referee};
use harness::judge::{self, Verdict};
use harness::load::LoadedCase;
use harness::report::campaign::{Config, cases};
use harness::tolerance::Tolerance;
use oracle::geom::{ContactAnswer, Plane, Sphere};

/// Full-range cases per query kind, beside every fixture and the random ones.
const FULL_RANGE: u64 = 100;

/// The campaign's cases of `only` (every kind for `None`): the fixtures, and
/// `random` random and [`FULL_RANGE`] full-range cases per kind.
fn campaign(only: Option<Query>, random: u64) -> Vec<LoadedCase> {
    let config = Config {
        cases_per_query: random,
        full_range_per_query: FULL_RANGE,
        only,
        fixtures: vec![concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures").into()],
        ..Default::default()
    };
    let (all, errors) = cases(&config);
    assert!(errors.is_empty(), "{errors:?}");
    all
}

/// `answer` with every normal multiplied by `k`.
fn scaled(answer: &Answer, k: f64) -> Option<Answer> {
    let s = |n: [f64; 3]| n.map(|x| x * k);
    match answer {
        Answer::Contact(a) => {
            let c = a.contact?;
            Some(Answer::Contact(ContactAnswer {
                contact: Some(oracle::geom::Contact { normal: s(c.normal), ..c }),
                ..*a
            }))
        }
        Answer::Intersect(a) => {
            let h = a.hit?;
            Some(Answer::Intersect(oracle::geom::IntersectAnswer {
                hit: Some(oracle::geom::SegmentHit { normal: s(h.normal), ..h }),
                ..*a
            }))
        }
        Answer::Toi(a) => {
            let t = a.toi?;
            Some(Answer::Toi(oracle::geom::ToiAnswer {
                toi: Some(oracle::geom::Toi { normal: s(t.normal), ..t }),
                ..*a
            }))
        }
        _ => None,
    }
}

/// The referee's own answer with its normals 1.01 and 1.5 times too long (the
/// point, depth and time exact) disagrees, saying so, on every case of the
/// campaign with a contact, a hit or an impact — fixtures, random and
/// full-range alike — for an `f64` and an `f32` engine; unscaled, it agrees.
#[test]
fn a_normal_that_is_not_unit_disagrees_on_every_case_with_a_normal() {
    let referee = referee();
    let mut with_normal = 0;
    for lc in campaign(None, 400) {
        let Ok(truth) = run_caught(&referee, &lc) else { continue };
        if !judge::all_finite(&truth) {
            continue;
        }
        let margin = harness::engines::referee::margin(&lc);
        for k in [1.01, 1.5] {
            let Some(wrong) = scaled(&truth, k) else { continue };
            for precision in [Some(53), Some(24)] {
                let tol = Tolerance::for_precision(precision);
                match judge::judge(&lc, &wrong, &truth, &tol, margin).0 {
                    Verdict::Disagree { reasons } => assert!(
                        reasons.iter().any(|r| r.starts_with("normal not unit: length")),
                        "{}: ×{k}: {reasons:?}",
                        lc.case.name
                    ),
                    v => panic!("{}: normals ×{k} judged {v:?}", lc.case.name),
                }
            }
            with_normal += 1;
        }
        let tol = Tolerance::for_precision(Some(53));
        assert_eq!(judge::judge(&lc, &truth, &truth, &tol, margin).0, Verdict::Agree, "{}", lc.case.name);
    }
    assert!(with_normal >= 1_200, "{with_normal} scaled answers judged");
}

/// A user's engine whose sphere–plane normals are 1.5 times too long, its
/// points and depths exact (the referee's).
struct LongNormals;

impl Queries for LongNormals {
    fn contact_sphere_plane(&self, a: &Sphere, b: &Plane) -> Reply<ContactAnswer> {
        let mut answer =
            oracle::referee::contact_sphere_plane(a, b).map_err(|e| harness::engine::Unsupported(format!("{e:?}")))?;
        if let Some(c) = &mut answer.contact {
            c.normal = c.normal.map(|x| x * 1.5);
        }
        Ok(answer)
    }
}

/// In process, through `check_case` as a user's engine is judged: every
/// sphere–plane contact of the campaign disagrees, the `expect` of the
/// fixtures that have one included.
#[test]
fn a_users_engine_with_long_sphere_plane_normals_disagrees_on_every_contact() {
    let set = EngineSet::of(vec![Engine::new("long normals", Some(53), LongNormals)]);
    let mut contacts = 0;
    for lc in campaign(Some(Query::Contact), 2_000) {
        let is_pair = matches!(
            (&lc.case.a, lc.case.b.as_ref()),
            (harness::case::Shape::Sphere(_), Some(harness::case::Shape::Plane(_)))
        );
        if !is_pair {
            continue;
        }
        let r = check_case(&lc, &set);
        let e = &r.engines[0];
        let Some(answer) = &e.answer else { continue };
        if answer.contact.as_ref().is_some_and(Option::is_some) {
            contacts += 1;
            assert!(
                matches!(&e.verdict, Verdict::Disagree { reasons } if reasons.iter().any(|x| x.contains("normal not unit"))),
                "{}: {:?}",
                lc.case.name,
                e.verdict
            );
            if let Some(m) = &e.expect_mismatches
                && lc.case.expect.as_ref().is_some_and(|x| x.contact.as_ref().is_some_and(Option::is_some))
            {
                assert!(m.iter().any(|m| m.field.starts_with("contact.normal")), "{}: {m:?}", lc.case.name);
            }
        }
    }
    assert!(contacts >= 200, "{contacts} sphere–plane contacts");
}

/// Segment–plane `t` off by a factor `1 + 1e-12` (about 4,500 ulps of 1),
/// everything else exact: within the default allowance (1e-9) on every hit,
/// and beyond `--ulps 64` on every well-conditioned one — where `t` moves by
/// at most 4 of its ulps per ulp of the inputs (so the conditioning allows
/// no more than the fixed 64 ulps) and `t ≥ 1/8` (the error at least 550
/// ulps of 1). The error in ulps is the answer's `Errors::ulps`.
#[test]
fn a_time_off_by_a_factor_one_plus_1e_12_agrees_by_default_and_disagrees_under_64_ulps() {
    const FACTOR: f64 = 1.0 + 1e-12;
    let referee = referee();
    let (default, strict) = (Tolerance::for_precision(Some(53)), Tolerance::for_engine(Some(53), Some(64.0)));
    let (mut hits, mut well_conditioned) = (0, 0);
    for lc in campaign(Some(Query::Intersect), 2_000) {
        if !matches!(lc.case.b, Some(harness::case::Shape::Plane(_))) {
            continue;
        }
        let Ok(truth) = run_caught(&referee, &lc) else { continue };
        let Answer::Intersect(w) = &truth else { continue };
        let Some(h) = w.hit else { continue };
        if !judge::all_finite(&truth) {
            continue;
        }
        hits += 1;
        let mut off = *w;
        off.hit = Some(oracle::geom::SegmentHit { t: (h.t * FACTOR).min(1.0), ..h });
        let wrong = Answer::Intersect(off);
        let margin = harness::engines::referee::margin(&lc);
        let (v, e) = judge::judge(&lc, &wrong, &truth, &default, margin);
        assert_eq!(v, Verdict::Agree, "{}: by default", lc.case.name);
        let sizes = harness::local::local(&lc, &truth);
        if sizes.t.condition <= 4.0 && h.t >= 0.125 && h.t * FACTOR <= 1.0 {
            well_conditioned += 1;
            let (v, _) = judge::judge(&lc, &wrong, &truth, &strict, margin);
            assert!(
                matches!(&v, Verdict::Disagree { reasons } if reasons.iter().any(|r| r.starts_with("t off by"))),
                "{}: under --ulps 64: {v:?}",
                lc.case.name
            );
            let ulps = e.ulps.expect("a hit's ulps");
            assert!(ulps > 64.0, "{}: {ulps} ulps", lc.case.name);
        }
    }
    assert!(hits >= 300 && well_conditioned >= 60, "{hits} hits, {well_conditioned} well-conditioned");
}
