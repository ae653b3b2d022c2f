//! What the referee refuses ([`RefereeError`]), and the starting precision of
//! its square roots.

use std::fmt;

/// The starting precision, in bits, of the referee's square roots.
///
/// A square root is enclosed between two rationals whose gap is about
/// `2^-PRECISION_BITS` of its size; when that enclosure does not yet decide the
/// rounding of the final `f64` (an answer that cancels, like a depth close to 0
/// between large radii), the precision is doubled until it does. The reported
/// values are thus correctly rounded whatever this constant is; 256 bits (well
/// above the 200 the design asks for) settles nearly every case at the first try.
pub const PRECISION_BITS: usize = 256;

/// Input the referee refuses: not a geometric question at all. Valid but
/// degenerate geometry is never an error (see each function's fallback).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefereeError {
    /// A number is NaN or infinite; `field` names it (e.g. `"a.center"`).
    NonFinite {
        /// The offending field.
        field: &'static str,
    },
    /// A sphere's radius is negative.
    NegativeRadius {
        /// The offending field.
        field: &'static str,
    },
    /// A plane's normal is the zero vector.
    ZeroNormal {
        /// The offending field.
        field: &'static str,
    },
    /// A box has `min > max` on some axis.
    InvertedAabb {
        /// The offending field.
        field: &'static str,
    },
    /// A point cloud has no points.
    NoPoints {
        /// The offending field.
        field: &'static str,
    },
    /// A mesh face names a vertex that does not exist.
    IndexOutOfRange {
        /// The offending field.
        field: &'static str,
        /// The face index.
        face: usize,
    },
    /// A `ccd` case's `t_max` is outside `[0, 1]` (its motion is given at
    /// times 0 and 1).
    TimeOutOfRange {
        /// The offending field.
        field: &'static str,
    },
    /// An oriented box has a negative half-extent.
    NegativeHalfExtent {
        /// The offending field.
        field: &'static str,
    },
    /// An oriented box's rotation quaternion is zero (it has no direction to
    /// normalize).
    ZeroRotation {
        /// The offending field.
        field: &'static str,
    },
}

impl fmt::Display for RefereeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { field } => write!(f, "{field}: not a finite number"),
            Self::NegativeRadius { field } => write!(f, "{field}: negative radius"),
            Self::ZeroNormal { field } => write!(f, "{field}: zero normal"),
            Self::InvertedAabb { field } => write!(f, "{field}: min > max"),
            Self::NoPoints { field } => write!(f, "{field}: no points"),
            Self::IndexOutOfRange { field, face } => {
                write!(f, "{field}: face {face} has a vertex index out of range")
            }
            Self::TimeOutOfRange { field } => write!(f, "{field}: outside [0, 1] (the motion is given at 0 and 1)"),
            Self::NegativeHalfExtent { field } => write!(f, "{field}: negative half-extent"),
            Self::ZeroRotation { field } => write!(f, "{field}: zero quaternion"),
        }
    }
}

impl std::error::Error for RefereeError {}
