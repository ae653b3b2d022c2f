//! `crashtest-engine/1`: engines in any language, as commands speaking JSON
//! Lines (`docs/PROTOCOL.md`, the authority).
//!
//! - [`messages`]: the messages as types (the schema is generated from them),
//!   and the one place where a case and an answer meet their wire form;
//! - [`client`]: a process engine behind the engine seam, its faults contained.
//!
//! Serving an in-process engine over the protocol is [`crate::serve`]'s.

pub mod client;
pub mod messages;

pub use client::{ProcessEngine, ProcessSpec};
pub use messages::PROTOCOL;
