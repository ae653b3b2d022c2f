//! Barycentric coordinates on a segment (1D) and a triangle (2D).

mod coords;

pub use coords::Barycentric;
