//! # harness — crashtest's vocabulary and machinery
//!
//! Cases come in (from fixture files, [`load`]), go to every [`engine::Engine`]
//! (adapters in [`engines`]), and each answer is judged against the case's
//! expectation and against the referee ([`judge`]). Nothing flows back: engines
//! never see each other's answers.
//!
//! Decisions:
//! - The fixture format (`docs/FORMAT.md`) is read and written exactly by
//!   [`case`]; its JSON Schema is generated from these types
//!   (`schema/crashtest-fixture-1.schema.json`, kept current by a test).
//! - Conventions are translated once per engine, in that engine's adapter.
//! - Every tolerance is a named constant with its reason ([`judge::tolerance`]).
//!
//! Layers, each importing only from the ones above it in this list (checked by
//! `tests/layering.rs`: no module imports one that imports it back):
//! 1. vocabulary and machinery: [`builtin`] (the fixtures embedded in the
//!    binary), [`case`], [`mesh`], [`rng`],
//!    [`load`], [`protocol`] (process engines), [`divergence`], [`engine`],
//!    [`engines`], [`judge`] (the verdict, one stage a file: sizes,
//!    tolerances, allowances, comparison, reasons), [`check`], [`serve`] (an engine served
//!    over the protocol), [`conformance`] (a process engine's conformance
//!    run), [`generate`];
//! 2. what a report measured ([`summary`]), its findings ([`findings`]:
//!    discrepancies grouped by signature, shrunk, drafted, compared), the campaign's defaults
//!    ([`defaults`]) and the one timing loop ([`timing`]);
//! 3. rendering ([`render`]): pages, tables, charts and sections from measured
//!    data, never running anything;
//! 4. the experiments — [`sweep`], [`scene`], [`toi_report`], [`dynamics`],
//!    [`ccd_report`] (the CCD benchmark's queries, `report --ccd-benchmark`) —
//!    each a run and a rendering of what it measured;
//! 5. the report ([`report`]): the campaign that runs the cases and the
//!    experiments, the peers' section, the bench's timings, provenance, and
//!    the report's files.
#![deny(missing_docs)]
// `!(x <= y)` is the judge's idiom for "not certainly within": it is true for a
// NaN, so a NaN error or allowance never passes; `partial_cmp` would hide that
// behind an `Option`.
#![allow(clippy::neg_cmp_op_on_partial_ord, reason = "`!(x <= y)` is deliberately true for NaN")]

pub mod builtin;
pub mod case;
pub mod ccd_benchmark;
pub mod ccd_report;
pub mod check;
pub mod conformance;
pub mod defaults;
pub mod divergence;
#[cfg(feature = "dynamics")]
pub mod dynamics;
pub mod engine;
pub mod engines;
pub mod findings;
pub mod generate;
pub mod judge;
pub mod load;
pub mod mesh;
pub mod protocol;
pub mod render;
pub mod report;
pub mod rng;
pub mod scene;
pub mod serve;
pub mod summary;
pub mod sweep;
pub mod timing;
pub mod toi_report;
