//! Coverage of the pair table (`crashtest_core::pair::PAIRS`): every pair has a
//! generator in the random campaign, cases in the shipped fixtures, an answer
//! from the referee, and a stability sweep — or a stated reason why not, kept
//! here beside the check it excuses. A reason that no longer applies (the pair
//! gained what it lacked) fails too, so the list stays true.

use crashtest::Pair;
use harness::engines::referee;
use harness::load::LoadedCase;
use std::collections::BTreeSet;

/// Random cases drawn per query kind to find the generated pairs: 2000. Reason:
/// every generator family is then drawn many times (the rarest pair, a mesh
/// among intersect cases, comes up in hundreds).
const DRAWS: u64 = 2000;

/// Pairs without a generator in the random campaign, with the reason.
const NO_GENERATOR: &[(Pair, &str)] = &[
    (
        Pair::IntersectSegmentMesh,
        "the campaign draws single primitives; meshes come from fixtures (fixtures/mesh.json, fixtures/meshes) \
         and the mesh tests' seeded soups (tests/mesh.rs)",
    ),
    (Pair::BoundsMesh, "as intersect segment–mesh: a mesh's bounds are those of its vertices, drawn as points"),
    (
        Pair::ContactSphereMesh,
        "as intersect segment–mesh: meshes come from fixtures (fixtures/mesh.json); a mesh's contact is its nearest \
         face's sphere–triangle contact, which the campaign draws",
    ),
];

/// Pairs without a stability sweep, with the reason.
const NO_SWEEP: &[(Pair, &str)] = &[
    (
        Pair::BoundsBox,
        "a box's bounds are sums |Rᵢⱼ|hⱼ about its centre, with no decision to sweep toward; the flat-box family \
         and fixtures cover a zero extent",
    ),
    (Pair::ContactPlaneSphere, "the reverse order of sphere–plane: the same geometry, swept as sphere–plane"),
    (Pair::ContactTriangleSphere, "the reverse order of sphere–triangle: the same geometry, swept as sphere–triangle"),
    (
        Pair::IntersectSegmentMesh,
        "a mesh's hit is its faces' segment–triangle hits, which the angle, edge and vertex sweeps cover",
    ),
    (Pair::BoundsMesh, "a mesh's bounds are those of its vertices, swept as points"),
    (
        Pair::ContactSphereMesh,
        "a mesh's contact is its nearest face's sphere–triangle contact, which the sphere–triangle sweeps cover",
    ),
    (
        Pair::ToiSphereTriangle,
        "sweeps hold one degeneracy parameter; the triangle's own (sliver, edge) are swept by contact sphere–triangle",
    ),
    (Pair::ToiSphereMesh, "as toi sphere–triangle, face by face"),
    (
        Pair::ResponseSphereSphere,
        "response has no degeneracy parameter beyond the masses' ratio, which the random campaign spans",
    ),
    (Pair::ResponseSpherePlane, "as response sphere–sphere"),
];

fn pairs_of<'a>(cases: impl IntoIterator<Item = &'a LoadedCase>) -> BTreeSet<Pair> {
    cases.into_iter().filter_map(|lc| lc.case.pair()).collect()
}

fn generated() -> Vec<LoadedCase> {
    let seed = crashtest::DEFAULT_SEED;
    crashtest::Query::ALL
        .into_iter()
        .flat_map(|q| (0..DRAWS).filter_map(move |i| harness::generate::try_generate(q, seed, i)))
        .collect()
}

#[test]
fn every_pair_has_a_generator() {
    let seen = pairs_of(&generated());
    for pair in Pair::ALL {
        let excused = NO_GENERATOR.iter().find(|(p, _)| *p == pair);
        match (seen.contains(&pair), excused) {
            (true, Some((_, why))) => panic!("{pair} is generated now; drop its reason ({why})"),
            (false, None) => panic!("no random case of {pair} in {DRAWS} draws per query kind, and no stated reason"),
            _ => {}
        }
    }
}

#[test]
fn every_pair_has_shipped_fixtures() {
    let loaded = harness::load::load_paths(&[crashtest::builtin_fixtures()]);
    assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
    let seen = pairs_of(&loaded.cases);
    let missing: Vec<Pair> = Pair::ALL.into_iter().filter(|p| !seen.contains(p)).collect();
    assert!(missing.is_empty(), "no fixture of {missing:?}");
}

#[test]
fn the_referee_answers_every_pair() {
    let mut cases = generated();
    cases.extend(harness::load::load_paths(&[crashtest::builtin_fixtures()]).cases);
    let r = referee();
    for pair in Pair::ALL {
        let answered =
            cases.iter().filter(|lc| lc.case.pair() == Some(pair)).take(20).filter(|lc| r.run(lc).is_ok()).count();
        assert!(answered > 0, "the referee answers none of 20 cases of {pair}");
    }
}

#[test]
fn every_pair_has_a_sweep_or_a_reason() {
    let settings = harness::sweep::Settings { poses: 1, seed: 1 };
    let swept: BTreeSet<Pair> = harness::sweep::SWEEPS
        .iter()
        .flat_map(|s| harness::sweep::cases(s, &settings))
        .filter_map(|c| c.case.case.pair())
        .collect();
    for pair in Pair::ALL {
        let excused = NO_SWEEP.iter().find(|(p, _)| *p == pair);
        match (swept.contains(&pair), excused) {
            (true, Some((_, why))) => panic!("{pair} is swept now; drop its reason ({why})"),
            (false, None) => panic!("{pair} has no sweep and no stated reason"),
            _ => {}
        }
    }
}
