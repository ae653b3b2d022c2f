//! Seeded case generators: proptest strategies per query kind, in one place for
//! the randomized tests (`tests/differential.rs`) and the report's campaigns.
//!
//! Each query kind has named **families** of scenes. Half are *uniform* (shapes at
//! random in a small box); the other half are *biased* toward where methods fail:
//! touching and grazing contact built exactly, near-concentric spheres,
//! near-parallel segments, crossings near edges and vertices (and exactly on
//! them), slivers down to an aspect ratio of 1e-15, points on and off a
//! triangle's plane, scenes far from the origin (offsets up to 1e15), tiny and
//! huge sizes (1e-6 to 1e6), and an **edge walker** that takes an exactly
//! touching configuration and steps it `k ∈ [-8, 8]` ULPs either way. Every
//! family is bounded (finite coordinates well inside `f64`'s range, positive
//! radii, non-zero normals), so every case is valid input; degenerate geometry
//! (concentric spheres, zero-area triangles) is generated on purpose.
//!
//! **Reproducibility.** [`generate`]`(query, seed, index)` depends on nothing
//! but its arguments: the family is chosen by `index` (even indices take the
//! uniform families in turn, odd ones the biased families in turn, so exactly
//! half of any run of cases is biased and every family gets its share), and the
//! family's strategy draws its values from a ChaCha generator keyed by
//! `(seed, index)`. Any case of a campaign can be regenerated from its name. No
//! transcendental function is used in building a case, so the same arguments
//! give the same case on every platform.
//!
//! The strategies themselves ([`strategy`], [`family_strategy`]) serve
//! proptest, which shrinks a failing case toward a simpler one of the same
//! family.

mod barycentric;
mod bounds;
mod boxes;
pub(crate) mod build;
mod ccd;
mod contact;
mod distance;
mod family;
pub mod full_range;
mod intersect;
mod overlap;
mod response;
mod toi;

use crate::case::{Case, Query};
use crate::load::LoadedCase;
use family::Family;
use proptest::strategy::{BoxedStrategy, SBoxedStrategy, Strategy, Union, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::path::PathBuf;
use std::sync::OnceLock;

/// The query kinds with generators, in the format's order: every kind.
pub const GENERATED: [Query; 9] = Query::ALL;

/// The `file` of every generated [`LoadedCase`].
pub const GENERATED_FILE: &str = "generated";

/// A family's strategy, built once and shared.
struct Entry {
    name: &'static str,
    biased: bool,
    strategy: SBoxedStrategy<Case>,
}

/// Every kind's families, uniform ones first.
struct Registry {
    kinds: Vec<(Query, Vec<Entry>, Vec<&'static str>)>,
}

fn families_of(query: Query) -> Vec<Family> {
    match query {
        Query::Contact => contact::families().into_iter().chain(boxes::contact_families()).collect(),
        Query::Intersect => intersect::families().into_iter().chain(boxes::intersect_families()).collect(),
        Query::Barycentric => barycentric::families(),
        Query::Bounds => bounds::families().into_iter().chain(boxes::bounds_families()).collect(),
        Query::Overlap => overlap::families().into_iter().chain(boxes::overlap_families()).collect(),
        Query::Toi => toi::families(),
        Query::Response => response::families(),
        Query::Ccd => ccd::families(),
        Query::Distance => distance::families(),
    }
}

/// The name a strategy gives its cases; [`generate`] replaces it with one that
/// carries the seed and index.
fn proptest_name(query: Query, family: &str) -> String {
    format!("{query} ({family})")
}

fn registry() -> &'static Registry {
    static REGISTRY: OnceLock<Registry> = OnceLock::new();
    REGISTRY.get_or_init(|| Registry {
        kinds: GENERATED
            .iter()
            .map(|&query| {
                let fams = families_of(query);
                let names = fams.iter().map(|f| f.name).collect();
                let entries = fams
                    .into_iter()
                    .map(|f| {
                        let name = f.name;
                        let strategy = f
                            .strategy()
                            .prop_map(move |((a, b), p)| Case {
                                name: proptest_name(query, name),
                                source: format!("generated: proptest, family {name}"),
                                query,
                                a,
                                b,
                                expect: None,
                                tol: None,
                                t_max: p.t_max,
                                restitution: p.restitution,
                            })
                            .sboxed();
                        Entry { name, biased: f.biased, strategy }
                    })
                    .collect();
                (query, entries, names)
            })
            .collect(),
    })
}

fn entries(query: Query) -> &'static [Entry] {
    registry().kinds.iter().find(|(q, _, _)| *q == query).map_or(&[], |(_, e, _)| e.as_slice())
}

/// The names of `query`'s families: the uniform ones first, then the biased ones.
/// Empty for a kind without generators (see [`GENERATED`]).
pub fn families(query: Query) -> &'static [&'static str] {
    registry().kinds.iter().find(|(q, _, _)| *q == query).map_or(&[], |(_, _, n)| n.as_slice())
}

/// Whether the family `name` of `query` is one of the biased ones (`None` for an
/// unknown name).
pub fn is_biased(query: Query, name: &str) -> Option<bool> {
    entries(query).iter().find(|e| e.name == name).map(|e| e.biased)
}

/// The family that case `index` of `query` is drawn from: even indices cycle
/// through the uniform families, odd ones through the biased families. `None`
/// for a kind without generators.
pub fn family_for(query: Query, index: u64) -> Option<&'static str> {
    entry_for(query, index).map(|e| e.name)
}

fn entry_for(query: Query, index: u64) -> Option<&'static Entry> {
    let all = entries(query);
    let biased = index % 2 == 1;
    let pool: Vec<&Entry> = all.iter().filter(|e| e.biased == biased).collect();
    if pool.is_empty() {
        return None;
    }
    let i = ((index / 2) % pool.len() as u64) as usize;
    Some(pool[i])
}

/// One family's strategy (`None` for an unknown name).
pub fn family_strategy(query: Query, name: &str) -> Option<BoxedStrategy<Case>> {
    entries(query).iter().find(|e| e.name == name).map(|e| e.strategy.clone().boxed())
}

/// The strategy of a query kind: every family, weighted so that the uniform
/// families and the biased ones each make up half of the cases.
///
/// # Panics
///
/// If `query` is not one of [`GENERATED`], as [`generate`].
pub fn strategy(query: Query) -> BoxedStrategy<Case> {
    let all = entries(query);
    let nu = all.iter().filter(|e| !e.biased).count() as u32;
    let nb = all.iter().filter(|e| e.biased).count() as u32;
    if nu == 0 || nb == 0 {
        panic!("no generator for query `{query}` (generated kinds: {GENERATED:?})");
    }
    let weighted = all.iter().map(|e| (if e.biased { nu } else { nb }, e.strategy.clone())).collect();
    Union::new_weighted(weighted).boxed()
}

/// The 32-byte ChaCha key of case `(seed, index)`: both numbers in full, then
/// each mixed by SplitMix64 so that nearby seeds and indices differ in every
/// byte. Distinct pairs give distinct keys.
fn key(seed: u64, index: u64) -> [u8; 32] {
    fn splitmix64(mut z: u64) -> u64 {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    let mut k = [0u8; 32];
    k[..8].copy_from_slice(&seed.to_le_bytes());
    k[8..16].copy_from_slice(&index.to_le_bytes());
    k[16..24].copy_from_slice(&splitmix64(seed).to_le_bytes());
    k[24..].copy_from_slice(&splitmix64(index ^ splitmix64(seed)).to_le_bytes());
    k
}

/// Case `index` of the campaign `seed` for `query`, as a fixture case ready to
/// run: named `"<query> #<index> (seed <seed>, <family>)"`, with source
/// `"generated: seed <seed>, index <index>, family <family>"`, no expectation
/// (engines are judged against the referee), `file` [`GENERATED_FILE`].
///
/// Deterministic in `(query, seed, index)` alone; see the module docs for how the
/// family and the values are chosen. `None` for a kind without generators (see
/// [`GENERATED`]) — the only way it can fail, since no generator filters.
pub fn try_generate(query: Query, seed: u64, index: u64) -> Option<LoadedCase> {
    let entry = entry_for(query, index)?;
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &key(seed, index));
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    // The generators use no filters, so a value tree is always produced.
    let mut case = entry.strategy.new_tree(&mut runner).ok()?.current();
    case.name = format!("{query} #{index} (seed {seed}, {})", entry.name);
    case.source = format!("generated: seed {seed}, index {index}, family {}", entry.name);
    Some(loaded(case))
}

/// The first words of every full-range case's `source`: the campaign keeps
/// these cases apart from the ordinary mix.
pub const FULL_RANGE_SOURCE: &str = "generated: full range";

/// The full-range family of `query` (see [`full_range`]): one strategy per
/// sub-family, built once and shared.
fn full_range_entries(query: Query) -> &'static [SBoxedStrategy<Case>] {
    static FULL: OnceLock<Vec<(Query, Vec<SBoxedStrategy<Case>>)>> = OnceLock::new();
    let all = FULL.get_or_init(|| {
        GENERATED
            .iter()
            .map(|&q| {
                let es = entries(q);
                let nu = es.iter().filter(|e| !e.biased).count() as u32;
                let nb = es.iter().filter(|e| e.biased).count() as u32;
                let base = Union::new_weighted(
                    es.iter().map(|e| (if e.biased { nu } else { nb }, e.strategy.clone())).collect(),
                )
                .sboxed();
                (q, full_range::FAMILIES.iter().map(|f| full_range::sub_family(q, f, base.clone())).collect())
            })
            .collect()
    });
    all.iter().find(|(q, _)| *q == query).map_or(&[], |(_, s)| s.as_slice())
}

/// Case `index` of the full-range family of `query` for the campaign `seed`:
/// the sub-family [`full_range::family_for`]`(index)`, its values drawn from a
/// ChaCha generator keyed by `(seed, index)` apart from the ordinary cases'
/// keys. Named `"<query> full range #<index> (seed <seed>, <sub-family>)"`,
/// with source `"generated: full range, seed <seed>, index <index>, family
/// <sub-family>"`. Deterministic in its arguments; `None` for a kind without
/// generators.
pub fn try_generate_full_range(query: Query, seed: u64, index: u64) -> Option<LoadedCase> {
    let strategies = full_range_entries(query);
    let family = full_range::family_for(index);
    let strategy = strategies.get((index % full_range::FAMILIES.len() as u64) as usize)?;
    let mut k = key(seed, index);
    // Apart from the ordinary cases' keys: the last byte flipped.
    k[31] ^= 0xA5;
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &k);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let mut case = strategy.new_tree(&mut runner).ok()?.current();
    case.name = format!("{query} full range #{index} (seed {seed}, {family})");
    case.source = format!("{FULL_RANGE_SOURCE}, seed {seed}, index {index}, family {family}");
    Some(loaded(case))
}

/// One full-range sub-family's strategy for proptest (`None` for an unknown
/// name or a kind without generators).
pub fn full_range_strategy(query: Query, family: &str) -> Option<BoxedStrategy<Case>> {
    let i = full_range::FAMILIES.iter().position(|f| *f == family)?;
    full_range_entries(query).get(i).map(|s| s.clone().boxed())
}

/// A generated case ready to run: `file` [`GENERATED_FILE`], and its inline
/// meshes (the `toi` generators' only kind of mesh) built as the fixture loader
/// builds them. A mesh the loader would refuse is left unloaded, and engines
/// then answer the case `Unsupported`; the generators make none.
pub fn loaded(case: Case) -> LoadedCase {
    let mesh = |shape: Option<&crate::case::Shape>| match shape {
        Some(crate::case::Shape::Mesh(m)) => match (&m.vertices, &m.triangles) {
            (Some(v), Some(t)) => crate::mesh::Mesh::new(v.clone(), t.clone()).ok(),
            _ => None,
        },
        _ => None,
    };
    let meshes = [mesh(Some(&case.a)), mesh(case.b.as_ref())];
    LoadedCase { file: PathBuf::from(GENERATED_FILE), case, meshes }
}

/// [`try_generate`] for a kind that has generators.
///
/// # Panics
///
/// If `query` is not one of [`GENERATED`] (today every kind is): asking for a
/// case no generator makes is a caller's mistake, not a property of any input.
pub fn generate(query: Query, seed: u64, index: u64) -> LoadedCase {
    match try_generate(query, seed, index) {
        Some(lc) => lc,
        None => panic!("no generator for query `{query}` (generated kinds: {GENERATED:?})"),
    }
}

#[cfg(test)]
mod tests;
