//! The judge's second round: a normal is judged on its length as well as its
//! angle, and accuracy is measured in ulps (`--ulps N` holds every engine to
//! `N` ulps of each field's magnitude, the conditioning allowances kept).

use harness::case::Query;
use harness::check::{check_case, run_caught};
use harness::engine::{Answer, Engine, Queries, Reply};
use harness::engines::{EngineSet, referee};
use harness::judge::tolerance::Tolerance;
use harness::judge::{self, Verdict};
use harness::load::LoadedCase;
use harness::report::campaign::{Config, cases};
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
    for lc in campaign(Some(Query::Contact), 4_000) {
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
    for lc in campaign(Some(Query::Intersect), 3_000) {
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
        let sizes = harness::judge::sizes::local(&lc, &truth);
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

/// `shape` standing still.
fn still(shape: &harness::case::Shape) -> harness::case::Shape {
    use harness::case::Shape as S;
    match shape.clone() {
        S::Sphere(s) => S::Sphere(harness::case::SphereSpec { velocity: None, ..s }),
        S::Plane(p) => S::Plane(harness::case::PlaneSpec { velocity: None, ..p }),
        S::Triangle(t) => S::Triangle(harness::case::TriangleSpec { velocity: None, ..t }),
        S::Mesh(m) => S::Mesh(harness::case::MeshSpec { velocity: None, ..m }),
        S::Box(b) => S::Box(harness::case::BoxSpec { velocity: None, ..b }),
        other => other,
    }
}

/// The verdict's kind, for comparing two judges.
fn kind(v: &Verdict) -> &'static str {
    v.label()
}

/// One rule for a contact at t = 0: shapes standing still and touching or
/// overlapping are a time-of-impact case answered at t = 0 and a contact
/// case with the same point and normal, and the two judges give the same
/// verdict to the same answer — a miss (borderline or disagreement by the
/// same band), and a point or a normal moved by half and by twice either
/// judge's allowance.
#[test]
fn a_contact_at_t_zero_is_judged_alike_as_a_time_of_impact_and_as_a_contact() {
    let referee = referee();
    let tol = Tolerance::for_precision(Some(53));
    let (mut compared, mut misses_borderline) = (0, 0);
    for lc in campaign(Some(Query::Toi), 1_000) {
        let mut toi = lc.clone();
        toi.case.a = still(&lc.case.a);
        toi.case.b = lc.case.b.as_ref().map(still);
        let mut contact = toi.clone();
        contact.case.query = Query::Contact;
        contact.case.t_max = None;
        contact.case.expect = None;
        let (Ok(Answer::Toi(tw)), Ok(Answer::Contact(cw))) =
            (run_caught(&referee, &toi), run_caught(&referee, &contact))
        else {
            continue;
        };
        let (Some(t), Some(c)) = (tw.toi, cw.contact) else {
            assert!(tw.toi.is_none() && cw.contact.is_none(), "{}: {tw:?} against {cw:?}", lc.case.name);
            continue;
        };
        if !judge::all_finite(&Answer::Toi(tw)) || !judge::all_finite(&Answer::Contact(cw)) {
            continue;
        }
        // The referee rounds the same exact point and normal once in both
        // queries: the same bits (and the time is exactly 0).
        let bits = |p: [f64; 3]| p.map(f64::to_bits);
        assert!(
            t.t == 0.0 && bits(t.point) == bits(c.point) && bits(t.normal) == bits(c.normal),
            "{}: {t:?} against {c:?}",
            lc.case.name
        );
        let (tm, cm) = (harness::engines::referee::margin(&toi), harness::engines::referee::margin(&contact));
        let (tt, ct) = (Answer::Toi(tw), Answer::Contact(cw));
        compared += 1;
        // A miss.
        let miss_t = judge::judge(&toi, &Answer::Toi(oracle::geom::ToiAnswer { toi: None, ..tw }), &tt, &tol, tm).0;
        let miss_c = judge::judge(&contact, &Answer::Contact(ContactAnswer { contact: None, ..cw }), &ct, &tol, cm).0;
        assert_eq!(kind(&miss_t), kind(&miss_c), "{}: a miss: {miss_t:?} against {miss_c:?}", lc.case.name);
        misses_borderline += usize::from(matches!(miss_c, Verdict::Borderline { .. }));
        // A point and a normal moved: the same point and normal in both
        // answers, judged as a time of impact and as a contact.
        let both = |point: [f64; 3], normal: [f64; 3]| {
            let vt = judge::judge(
                &toi,
                &Answer::Toi(oracle::geom::ToiAnswer { toi: Some(oracle::geom::Toi { point, normal, ..t }), ..tw }),
                &tt,
                &tol,
                tm,
            )
            .0;
            let vc = judge::judge(
                &contact,
                &Answer::Contact(ContactAnswer { contact: Some(oracle::geom::Contact { point, normal, ..c }), ..cw }),
                &ct,
                &tol,
                cm,
            )
            .0;
            (vt, vc)
        };
        let (at, ac) = (judge::allowed(&toi, &tt, &tol), judge::allowed(&contact, &ct, &tol));
        for allowance in [at.point, ac.point] {
            for f in [0.5, 2.0] {
                let d = allowance * f;
                let (vt, vc) = both([c.point[0] + d, c.point[1], c.point[2]], c.normal);
                assert_eq!(kind(&vt), kind(&vc), "{}: point moved by {d:e}: {vt:?} against {vc:?}", lc.case.name);
            }
        }
        for allowance in [at.normal, ac.normal] {
            for f in [0.5, 2.0] {
                let a = (allowance * f).min(3.0);
                // Turned by `a` about an axis across the normal (scaled: a
                // unit normal's largest coordinate is at least 1/√3).
                let n = c.normal;
                let k = if n[0].abs() < 0.5 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
                let u = crashtest_core::vec3::cross(n, k);
                let l = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
                let (s, co) = a.sin_cos();
                let (vt, vc) = both(c.point, [0, 1, 2].map(|i| n[i] * co + u[i] / l * s));
                assert_eq!(kind(&vt), kind(&vc), "{}: normal turned by {a:e}: {vt:?} against {vc:?}", lc.case.name);
            }
        }
    }
    assert!(
        compared >= 150 && misses_borderline >= 10,
        "{compared} contacts at t = 0, {misses_borderline} borderline misses"
    );
}

/// The accuracy in ulps is the measure `--ulps N` decides by: over the
/// campaign, an answer of the lecture's methods or of parry measured within
/// `N` ulps (`Errors::ulps`) agrees or is borderline under `--ulps N`, and
/// one measured beyond `N` disagrees — for `N` = 1, 4 and 64 (a flag that
/// differs is a disagreement whatever its ulps, and left out; so are answers
/// within a part in 10⁹ of `N`, where the floor's clamp may round either way).
#[test]
fn an_answer_within_n_ulps_is_what_ulps_n_lets_through() {
    let engines: Vec<Engine> = harness::engines::judged()
        .into_iter()
        .filter(|e| ["collide/lecture", "parry3d-f64", "collide-f32/lecture"].contains(&e.name.as_str()))
        .collect();
    assert_eq!(engines.len(), 3);
    let referee = referee();
    let mut checked = [0usize; 2];
    for lc in campaign(None, 300) {
        let Ok(truth) = run_caught(&referee, &lc) else { continue };
        if !judge::all_finite(&truth) {
            continue;
        }
        let margin = harness::engines::referee::margin(&lc);
        for engine in &engines {
            let Ok(answer) = run_caught(engine, &lc) else { continue };
            let precision = engine.precision_for(&lc);
            let (_, e) = judge::judge(&lc, &answer, &truth, &Tolerance::for_precision(precision), margin);
            let Some(u) = e.ulps else { continue };
            if e.misclass == Some(judge::Misclass::Flag) || !judge::all_finite(&answer) {
                continue;
            }
            for n in [1.0, 4.0, 64.0] {
                if (u - n).abs() <= 1e-9 * n {
                    continue;
                }
                let (v, _) = judge::judge(&lc, &answer, &truth, &Tolerance::for_engine(precision, Some(n)), margin);
                let within = matches!(v, Verdict::Agree | Verdict::Borderline { .. });
                assert_eq!(within, u <= n, "{} by {}: {u} ulps under --ulps {n}: {v:?}", lc.case.name, engine.name);
                checked[usize::from(within)] += 1;
            }
        }
    }
    assert!(checked[0] >= 500 && checked[1] >= 5_000, "{checked:?} (beyond, within)");
}

/// A user's engine that answers a distance with the referee's other least
/// push where there is one (the last of them), and with the referee's answer
/// turned by a quarter turn about z otherwise.
struct OtherPush;

impl Queries for OtherPush {
    fn distance(&self, a: oracle::geom::Solid<'_>, b: oracle::geom::Solid<'_>) -> Reply<oracle::geom::DistanceAnswer> {
        let err = |e: oracle::referee::RefereeError| harness::engine::Unsupported(format!("{e:?}"));
        let alts = oracle::referee::distance_alternatives(a, b).map_err(err)?;
        match alts.last() {
            Some((alt, _)) => Ok(*alt),
            None => {
                let mut d = oracle::referee::distance(a, b).map_err(err)?;
                d.normal = [-d.normal[1], d.normal[0], d.normal[2]];
                Ok(d)
            }
        }
    }
}

/// Where the least push is reached in several directions, every one is
/// right: the judge agrees with an engine that takes another than the
/// referee's first, and the case's expect (the referee's answer) keeps only
/// the distance and the flag. A normal that is no least push still
/// disagrees.
#[test]
fn a_distance_along_another_least_push_agrees_and_a_wrong_direction_does_not() {
    use harness::case::{Case, Shape};
    use oracle::geom::Convex;
    let cube = |c: [f64; 3], h: f64| {
        Shape::Convex(Convex {
            points: (0..8).map(|s| [0, 1, 2].map(|i| c[i] + if s >> i & 1 == 1 { h } else { -h })).collect(),
        })
    };
    let case = |a: Shape, b: Shape, name: &str| {
        harness::generate::loaded(Case {
            name: name.into(),
            source: name.into(),
            query: Query::Distance,
            a,
            b: Some(b),
            expect: None,
            tol: None,
            t_max: None,
            restitution: None,
        })
    };
    let set = EngineSet::of(vec![Engine::new("other push", Some(53), OtherPush)]);
    // Concentric cubes: six least pushes.
    let tied = case(cube([0.0; 3], 1.0), cube([0.0; 3], 1.0), "concentric cubes");
    let r = check_case(&tied, &set);
    assert_eq!(r.engines[0].verdict, Verdict::Agree, "{:?}", r.engines[0]);
    let referee = r.referee.as_ref().expect("the referee answers");
    assert!(referee.normal.is_none() && referee.point_a.is_none() && referee.distance.is_some(), "{referee:?}");
    // Shifted along x: one least push; the turned normal is wrong.
    let unique = case(cube([0.5, 0.0, 0.0], 1.0), cube([0.0; 3], 1.0), "shifted cubes");
    let r = check_case(&unique, &set);
    assert!(
        matches!(&r.engines[0].verdict, Verdict::Disagree { reasons } if reasons.iter().any(|x| x.contains("normal"))),
        "{:?}",
        r.engines[0]
    );
}
