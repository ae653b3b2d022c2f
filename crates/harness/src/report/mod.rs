//! Reports: the campaign ([`campaign`]) over the fixtures, the generated cases
//! and the experiments' sections, the peers' section ([`peers`]), the bench's
//! timings ([`bench`]), where it ran ([`provenance`]), and how it is written
//! ([`write`](mod@write)). What it measured is a [`crate::summary::Summary`],
//! shown by [`crate::render`].

pub mod bench;
pub mod campaign;
pub mod growth;
pub mod peers;
pub mod provenance;
pub mod shard;
pub mod write;
