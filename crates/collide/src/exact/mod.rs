//! Exact arithmetic and filtered predicates.
