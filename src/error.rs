//! Errors reported by the mesher. Every error names the offending input item by its index
//! (0-based, in the order the items were given).

use std::fmt;

/// A problem with the input PSLG. Indices are 0-based positions in the input arrays.
#[derive(Debug, Clone, PartialEq)]
pub enum InputError {
    /// Fewer than three points were given.
    TooFewPoints { count: usize },
    /// A point has a NaN or infinite coordinate.
    NonFinitePoint { point: usize },
    /// Two points have identical coordinates.
    DuplicatePoint { first: usize, second: usize },
    /// All points lie on one line, so there is no triangle to make.
    AllCollinear,
    /// A segment refers to a point index that does not exist.
    SegmentIndexOutOfRange {
        segment: usize,
        index: u64,
        num_points: usize,
    },
    /// A segment joins a point to itself (or to a point with the same coordinates).
    ZeroLengthSegment { segment: usize },
    /// Two segments join the same pair of points.
    DuplicateSegment { first: usize, second: usize },
    /// Two segments cross or overlap somewhere other than at a shared endpoint.
    CrossingSegments { first: usize, second: usize },
    /// A hole seed has a NaN or infinite coordinate.
    NonFiniteHole { hole: usize },
    /// A hole seed lies outside the meshed domain (or on a segment).
    HoleOutsideDomain { hole: usize },
    /// A region seed has a NaN or infinite coordinate or attribute, or a maximum area that is
    /// not positive.
    NonFiniteRegion { region: usize },
    /// A region seed lies outside the meshed domain (or on a segment).
    RegionOutsideDomain { region: usize },
    /// The marker array does not have one entry per item.
    MarkerCountMismatch {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    /// A coordinate is so large that circumcenters would overflow.
    CoordinateTooLarge { point: usize },
}

/// Any failure of a meshing call.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// The input is invalid; see [`InputError`].
    Input(InputError),
    /// An option has an invalid value (the message says which).
    InvalidOption(String),
    /// A requested feature is not available.
    Unsupported(String),
    /// An internal invariant failed (a bug): the message says which. Never a panic.
    Internal(String),
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use InputError::*;
        match self {
            TooFewPoints { count } => write!(f, "need at least 3 points, got {count}"),
            NonFinitePoint { point } => write!(f, "point {point} has a NaN or infinite coordinate"),
            DuplicatePoint { first, second } => {
                write!(f, "points {first} and {second} have identical coordinates")
            }
            AllCollinear => write!(f, "all points are collinear"),
            SegmentIndexOutOfRange {
                segment,
                index,
                num_points,
            } => write!(
                f,
                "segment {segment} refers to point {index}, but there are only {num_points} points"
            ),
            ZeroLengthSegment { segment } => write!(f, "segment {segment} has zero length"),
            DuplicateSegment { first, second } => {
                write!(f, "segments {first} and {second} join the same two points")
            }
            CrossingSegments { first, second } => {
                write!(
                    f,
                    "segments {first} and {second} intersect other than at a shared endpoint"
                )
            }
            NonFiniteHole { hole } => write!(f, "hole {hole} has a NaN or infinite coordinate"),
            HoleOutsideDomain { hole } => {
                write!(f, "hole {hole} lies outside the domain or on a segment")
            }
            NonFiniteRegion { region } => {
                write!(
                    f,
                    "region {region} has a NaN or infinite coordinate or attribute, or a maximum area that is not positive"
                )
            }
            RegionOutsideDomain { region } => {
                write!(f, "region {region} lies outside the domain or on a segment")
            }
            MarkerCountMismatch {
                what,
                expected,
                got,
            } => {
                write!(f, "{what} markers: expected {expected} entries, got {got}")
            }
            CoordinateTooLarge { point } => {
                write!(
                    f,
                    "point {point} has a coordinate too large to mesh safely (|x| > 1e150)"
                )
            }
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Input(e) => write!(f, "invalid input: {e}"),
            Error::InvalidOption(m) => write!(f, "invalid option: {m}"),
            Error::Unsupported(m) => write!(f, "unsupported: {m}"),
            Error::Internal(m) => write!(f, "internal error (please report): {m}"),
        }
    }
}

impl std::error::Error for InputError {}
impl std::error::Error for Error {}

impl From<InputError> for Error {
    fn from(e: InputError) -> Self {
        Error::Input(e)
    }
}
