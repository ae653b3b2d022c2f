//! Contact queries: where a sphere touches or sinks into another shape.

mod contact;

pub use contact::Contact;
