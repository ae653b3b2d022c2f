//! Shared by the benchmarks of single queries (`queries`, `toi`): the
//! by-family paired ratios, each campaign family's cases timed alone, and
//! their table.

use super::criterion_files::{Pairs, cell, paired_ratio};
use std::fmt::Write as _;

/// The family name of a case the generators drew with no family (none do
/// today: every query kind has families of both kinds).
pub const NO_FAMILY: &str = "(no family)";

/// The distinct families of `families` in order of first appearance, with
/// their numbers of cases.
pub fn family_counts(families: &[&'static str]) -> Vec<(&'static str, usize)> {
    let mut out: Vec<(&'static str, usize)> = Vec::new();
    for f in families {
        match out.iter_mut().find(|(g, _)| g == f) {
            Some((_, n)) => *n += 1,
            None => out.push((f, 1)),
        }
    }
    out
}

/// The cases of `xs` drawn from `family` (`families[i]` the family of case
/// `i`).
fn of_family<X: Clone>(families: &[&'static str], xs: &[X], family: &str) -> Vec<X> {
    families.iter().zip(xs).filter(|(f, _)| **f == family).map(|(_, x)| x.clone()).collect()
}

/// The paired ratios' group of one family of `group`'s cases.
pub fn family_group(group: &str, family: &str) -> String {
    format!("{group} / {family}")
}

/// The two engines of the by-family ratios: collide's, then the peer's.
const FAMILY_PAIR: (&str, &str) = ("collide_robust_f64", "parry64");

/// collide's engine against the peer's on each family's cases alone, as
/// paired ratios (group [`family_group`], ids [`FAMILY_PAIR`]): `ours` and
/// `theirs` are the same cases in each engine's types with the call that
/// answers one, `families[i]` the family of case `i`.
pub fn by_family<I: Clone, J: Clone, O, P>(
    group: &str,
    families: &[&'static str],
    ours: (&[I], impl Fn(&I) -> O + Copy),
    theirs: (&[J], impl Fn(&J) -> P + Copy),
) {
    for (family, _) in family_counts(families) {
        let (ours_cases, theirs_cases) = (of_family(families, ours.0, family), of_family(families, theirs.0, family));
        let mut pairs = Pairs::new(family_group(group, family));
        pairs.keep(FAMILY_PAIR.0, &ours_cases, ours.1);
        pairs.keep(FAMILY_PAIR.1, &theirs_cases, theirs.1);
        pairs.measure(&[FAMILY_PAIR]);
    }
}

/// One group's cases by family, for [`family_table`].
pub struct FamilyTable {
    /// What is timed, for the reader.
    pub label: &'static str,
    /// The group [`by_family`] was given.
    pub group: &'static str,
    /// Each family and its number of cases, in the order drawn
    /// ([`family_counts`]).
    pub families: Vec<(&'static str, usize)>,
}

/// The by-family table of [`by_family`]'s ratios: `intro` says what the
/// families are, `engines` names collide's and the peer's columns.
pub fn family_table(tables: &[FamilyTable], intro: &str, engines: (&str, &str)) -> String {
    let (ours, theirs) = engines;
    let mut s = format!(
        "\n## By case family\n\n{intro} A family timed alone is a shorter loop of like cases, whose branches \
         predict better than the mix's, so the mix's time is not the cases' weighted mean of these.\n\n\
         | pair | family | cases | {ours} (ns) | {theirs} (ns) | {ours} / {theirs} (quartiles) |\n\
         | --- | --- | ---: | ---: | ---: | ---: |\n"
    );
    for table in tables {
        for &(family, n) in &table.families {
            let p = paired_ratio(&family_group(table.group, family), FAMILY_PAIR.0, FAMILY_PAIR.1);
            let _ = writeln!(
                s,
                "| {} | {family} | {n} | {} | {} | {} |",
                table.label,
                cell(p.map(|p| p.ns_a)),
                cell(p.map(|p| p.ns_b)),
                p.map_or("—".into(), |p| p.quartiles()),
            );
        }
    }
    s
}
