//! Errors reported by the mesher. Every error names the offending input item by its index
//! (0-based, in the order the items were given).

use std::any::Any;
use std::fmt;

/// Coordinates beyond this magnitude are refused in every dimension
/// ([`InputError::CoordinateTooLarge`]): the exact insphere test of the 3D mesher (degree 5 in
/// coordinate differences, plus the splitting products of the exact arithmetic) and the 2D
/// in-circle test (degree 4) and circumcentres must not overflow.
pub const MAX_COORD: f64 = 1e50;

/// A problem with the input: a 2D PSLG or a 3D PLC (the C ABI reports each variant as an
/// `idm_input_error` kind). Indices are 0-based positions in the input arrays.
#[derive(Debug, Clone, PartialEq)]
pub enum InputError {
    /// Fewer than three points were given.
    TooFewPoints {
        /// How many points were given.
        count: usize,
    },
    /// A point has a NaN or infinite coordinate.
    NonFinitePoint {
        /// The point.
        point: usize,
    },
    /// Two points have identical coordinates.
    DuplicatePoint {
        /// The first of the two items.
        first: usize,
        /// The second of the two items.
        second: usize,
    },
    /// All points lie on one line, so there is no triangle to make.
    AllCollinear,
    /// A segment refers to a point index that does not exist.
    SegmentIndexOutOfRange {
        /// The segment.
        segment: usize,
        /// The point index it refers to.
        index: u64,
        /// How many points there are.
        num_points: usize,
    },
    /// A segment joins a point to itself (or to a point with the same coordinates).
    ZeroLengthSegment {
        /// The segment.
        segment: usize,
    },
    /// Two segments join the same pair of points.
    DuplicateSegment {
        /// The first of the two items.
        first: usize,
        /// The second of the two items.
        second: usize,
    },
    /// Two segments cross or overlap somewhere other than at a shared endpoint.
    CrossingSegments {
        /// The first of the two items.
        first: usize,
        /// The second of the two items.
        second: usize,
    },
    /// A hole seed has a NaN or infinite coordinate.
    NonFiniteHole {
        /// The hole seed (of the facet, for facet holes).
        hole: usize,
    },
    /// A hole seed lies outside the meshed domain (or on a segment, or in 3D on a facet).
    HoleOutsideDomain {
        /// The hole seed (of the facet, for facet holes).
        hole: usize,
    },
    /// A region seed has a NaN or infinite coordinate or attribute, or a maximum area that is
    /// not positive.
    NonFiniteRegion {
        /// The region seed.
        region: usize,
    },
    /// A region seed lies outside the meshed domain (or on a segment, or in 3D on a facet).
    RegionOutsideDomain {
        /// The region seed.
        region: usize,
    },
    /// The marker array does not have one entry per item.
    MarkerCountMismatch {
        /// Which items (points, segments, ...).
        what: &'static str,
        /// How many markers there should be (one per item).
        expected: usize,
        /// How many markers were given.
        got: usize,
    },
    /// A coordinate is so large that circumcenters would overflow.
    CoordinateTooLarge {
        /// The point.
        point: usize,
    },
    /// Fewer than four points were given to a 3D mesher.
    TooFewPoints3 {
        /// How many points were given.
        count: usize,
    },
    /// All points lie in one plane, so there is no tetrahedron to make.
    AllCoplanar,
    /// A facet has no polygon.
    FacetWithoutPolygons {
        /// The facet.
        facet: usize,
    },
    /// A facet polygon has no vertex.
    EmptyPolygon {
        /// The facet.
        facet: usize,
        /// The polygon, within the facet.
        polygon: usize,
    },
    /// A facet polygon refers to a point index that does not exist.
    FacetIndexOutOfRange {
        /// The facet.
        facet: usize,
        /// The polygon, within the facet.
        polygon: usize,
        /// The point index it refers to.
        index: u64,
        /// How many points there are.
        num_points: usize,
    },
    /// A facet polygon lists the same point twice.
    RepeatedVertexInPolygon {
        /// The facet.
        facet: usize,
        /// The polygon, within the facet.
        polygon: usize,
        /// The point.
        vertex: usize,
    },
    /// A facet loop (three or more vertices) has all its vertices on one line.
    DegeneratePolygon {
        /// The facet.
        facet: usize,
        /// The polygon, within the facet.
        polygon: usize,
    },
    /// All vertices of a facet lie on one line, so it spans no plane.
    DegenerateFacet {
        /// The facet.
        facet: usize,
    },
    /// A facet vertex lies off the plane of the facet's first three non-collinear vertices.
    NonPlanarFacet {
        /// The facet.
        facet: usize,
        /// The point.
        vertex: usize,
    },
    /// A facet hole seed has a NaN or infinite coordinate.
    NonFiniteFacetHole {
        /// The facet.
        facet: usize,
        /// The hole seed (of the facet, for facet holes).
        hole: usize,
    },
    /// A facet hole seed does not lie in the facet's plane.
    FacetHoleOffPlane {
        /// The facet.
        facet: usize,
        /// The hole seed (of the facet, for facet holes).
        hole: usize,
    },
    /// Two edges of one facet's polygons cross (the polygons may be the same one).
    SelfIntersectingFacet {
        /// The facet.
        facet: usize,
        /// The first polygon, within the facet.
        first_polygon: usize,
        /// The second polygon (maybe the same as the first).
        second_polygon: usize,
    },
    /// A 3D region seed has a NaN or infinite coordinate or attribute, or a maximum volume that
    /// is not positive.
    InvalidRegion3 {
        /// The region seed.
        region: usize,
    },
    /// A segment meets a facet other than at a vertex of both (or along an edge of the facet).
    SegmentCrossesFacet {
        /// The segment.
        segment: usize,
        /// The facet.
        facet: usize,
    },
    /// Two facets meet other than along shared edges and vertices.
    FacetsIntersect {
        /// The first of the two items.
        first: usize,
        /// The second of the two items.
        second: usize,
    },
    /// A point lies on a facet (inside it or on its boundary) but is not one of its vertices.
    VertexOnFacet {
        /// The point.
        vertex: usize,
        /// The facet.
        facet: usize,
    },
    /// A point and a facet are closer than the 3D mesher resolves: the mesh between them would
    /// need elements below the size floor (2^-36 of the input's diameter), which floating point
    /// constructions cannot place reliably. `distance` is the point's distance from the
    /// facet's plane.
    PointTooCloseToFacet {
        /// The point.
        point: usize,
        /// The facet.
        facet: usize,
        /// Its distance from the facet's plane.
        distance: f64,
    },
    /// A point lies in the interior of a segment.
    VertexOnSegment {
        /// The point.
        vertex: usize,
        /// The segment.
        segment: usize,
    },
    /// The facets enclose no volume: the surface is open. `edges` are the first few facet
    /// edges (point pairs) that only one facet uses; `count` is how many there are.
    OpenSurface {
        /// How many facet edges only one facet uses.
        count: usize,
        /// The first few of them, as point indices.
        edges: Vec<[usize; 2]>,
        /// The facets those first few edges belong to.
        facets: Vec<usize>,
    },
    /// The facets enclose no volume although every facet edge is shared: some edges are
    /// shared by three or more facets (a non-manifold surface, such as sheets glued along an
    /// edge) and no closed region is left between them.
    NonManifoldEdge {
        /// How many facet edges three or more facets share.
        count: usize,
        /// The first of them, as point indices.
        edge: [usize; 2],
        /// The first few facets on that edge.
        facets: Vec<usize>,
    },
    /// A polygon of a surface mesh is not planar and cannot be triangulated on its own
    /// vertices: no projection along a coordinate axis makes it a simple polygon (or it has
    /// more vertices than the triangulation of non-planar polygons takes).
    UntriangulablePolygon {
        /// The facet (the polygon's face in the file).
        facet: usize,
    },
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
    /// The progress callback asked to stop (see [`crate::progress`]); the stage the run was
    /// in. Nothing of the run is kept.
    Cancelled(crate::progress::Stage),
}

/// The kinds of item an [`InputError`] names, for [`InputError::map_items`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Item {
    /// A point (vertex) index.
    Point,
    /// A segment index.
    Segment,
    /// A facet index.
    Facet,
    /// A polygon index within a facet.
    Polygon,
    /// A hole seed index (of the domain, or of a facet).
    Hole,
    /// A region seed index.
    Region,
}

impl InputError {
    /// The same error with every item index shifted by `b` (a file's numbering base, 0 or 1);
    /// counts are kept.
    pub fn renumbered(&self, b: usize) -> InputError {
        self.map_items(&|_, i| i + b)
    }

    /// The same error with every item index `i` of kind `k` replaced by `f(k, i)` (counts are
    /// kept): how an error about a repaired or renumbered input is told in the numbering of
    /// the input as the user gave it.
    pub fn map_items(&self, f: &dyn Fn(Item, usize) -> usize) -> InputError {
        use InputError::*;
        use Item::*;
        let pt = |x: usize| f(Point, x);
        let ix = |x: u64| usize::try_from(x).map_or(x, |x| f(Point, x) as u64);
        let fc = |x: usize| f(Facet, x);
        let pg = |x: usize| f(Polygon, x);
        let sg = |x: usize| f(Segment, x);
        let hl = |x: usize| f(Hole, x);
        let rg = |x: usize| f(Region, x);
        match self.clone() {
            NonFinitePoint { point } => NonFinitePoint { point: pt(point) },
            DuplicatePoint { first, second } => DuplicatePoint {
                first: pt(first),
                second: pt(second),
            },
            SegmentIndexOutOfRange {
                segment,
                index,
                num_points,
            } => SegmentIndexOutOfRange {
                segment: sg(segment),
                index: ix(index),
                num_points,
            },
            ZeroLengthSegment { segment } => ZeroLengthSegment {
                segment: sg(segment),
            },
            DuplicateSegment { first, second } => DuplicateSegment {
                first: sg(first),
                second: sg(second),
            },
            CrossingSegments { first, second } => CrossingSegments {
                first: sg(first),
                second: sg(second),
            },
            NonFiniteHole { hole } => NonFiniteHole { hole: hl(hole) },
            HoleOutsideDomain { hole } => HoleOutsideDomain { hole: hl(hole) },
            NonFiniteRegion { region } => NonFiniteRegion { region: rg(region) },
            RegionOutsideDomain { region } => RegionOutsideDomain { region: rg(region) },
            CoordinateTooLarge { point } => CoordinateTooLarge { point: pt(point) },
            FacetWithoutPolygons { facet } => FacetWithoutPolygons { facet: fc(facet) },
            EmptyPolygon { facet, polygon } => EmptyPolygon {
                facet: fc(facet),
                polygon: pg(polygon),
            },
            FacetIndexOutOfRange {
                facet,
                polygon,
                index,
                num_points,
            } => FacetIndexOutOfRange {
                facet: fc(facet),
                polygon: pg(polygon),
                index: ix(index),
                num_points,
            },
            RepeatedVertexInPolygon {
                facet,
                polygon,
                vertex,
            } => RepeatedVertexInPolygon {
                facet: fc(facet),
                polygon: pg(polygon),
                vertex: pt(vertex),
            },
            DegeneratePolygon { facet, polygon } => DegeneratePolygon {
                facet: fc(facet),
                polygon: pg(polygon),
            },
            DegenerateFacet { facet } => DegenerateFacet { facet: fc(facet) },
            NonPlanarFacet { facet, vertex } => NonPlanarFacet {
                facet: fc(facet),
                vertex: pt(vertex),
            },
            NonFiniteFacetHole { facet, hole } => NonFiniteFacetHole {
                facet: fc(facet),
                hole: hl(hole),
            },
            FacetHoleOffPlane { facet, hole } => FacetHoleOffPlane {
                facet: fc(facet),
                hole: hl(hole),
            },
            SelfIntersectingFacet {
                facet,
                first_polygon,
                second_polygon,
            } => SelfIntersectingFacet {
                facet: fc(facet),
                first_polygon: pg(first_polygon),
                second_polygon: pg(second_polygon),
            },
            InvalidRegion3 { region } => InvalidRegion3 { region: rg(region) },
            SegmentCrossesFacet { segment, facet } => SegmentCrossesFacet {
                segment: sg(segment),
                facet: fc(facet),
            },
            FacetsIntersect { first, second } => FacetsIntersect {
                first: fc(first),
                second: fc(second),
            },
            VertexOnFacet { vertex, facet } => VertexOnFacet {
                vertex: pt(vertex),
                facet: fc(facet),
            },
            PointTooCloseToFacet {
                point,
                facet,
                distance,
            } => PointTooCloseToFacet {
                point: pt(point),
                facet: fc(facet),
                distance,
            },
            VertexOnSegment { vertex, segment } => VertexOnSegment {
                vertex: pt(vertex),
                segment: sg(segment),
            },
            OpenSurface {
                count,
                edges,
                facets,
            } => OpenSurface {
                count,
                edges: edges.iter().map(|e| e.map(pt)).collect(),
                facets: facets.into_iter().map(fc).collect(),
            },
            NonManifoldEdge {
                count,
                edge,
                facets,
            } => NonManifoldEdge {
                count,
                edge: edge.map(pt),
                facets: facets.into_iter().map(fc).collect(),
            },
            UntriangulablePolygon { facet } => UntriangulablePolygon { facet: fc(facet) },
            other => other,
        }
    }
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
                write!(
                    f,
                    "hole {hole} lies outside the domain or on its boundary (a segment or facet)"
                )
            }
            NonFiniteRegion { region } => {
                write!(
                    f,
                    "region {region} has a NaN or infinite coordinate or attribute, or a maximum area that is not positive"
                )
            }
            RegionOutsideDomain { region } => {
                write!(f, "region {region} lies outside the domain or on its boundary (a segment or facet)")
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
                    "point {point} has a coordinate too large to mesh safely (|x| > {MAX_COORD:e})"
                )
            }
            TooFewPoints3 { count } => write!(f, "need at least 4 points, got {count}"),
            AllCoplanar => write!(f, "all points lie in one plane"),
            FacetWithoutPolygons { facet } => write!(f, "facet {facet} has no polygon"),
            EmptyPolygon { facet, polygon } => {
                write!(f, "facet {facet} polygon {polygon} has no vertex")
            }
            FacetIndexOutOfRange {
                facet,
                polygon,
                index,
                num_points,
            } => write!(
                f,
                "facet {facet} polygon {polygon} refers to point {index}, but there are only \
                 {num_points} points"
            ),
            RepeatedVertexInPolygon {
                facet,
                polygon,
                vertex,
            } => write!(
                f,
                "facet {facet} polygon {polygon} lists point {vertex} twice"
            ),
            DegeneratePolygon { facet, polygon } => write!(
                f,
                "facet {facet} polygon {polygon} has all its vertices on one line"
            ),
            DegenerateFacet { facet } => {
                write!(f, "facet {facet} has all its vertices on one line")
            }
            NonPlanarFacet { facet, vertex } => write!(
                f,
                "facet {facet} is not planar: point {vertex} is off the plane of its first \
                 three non-collinear vertices"
            ),
            NonFiniteFacetHole { facet, hole } => {
                write!(
                    f,
                    "facet {facet} hole {hole} has a NaN or infinite coordinate"
                )
            }
            FacetHoleOffPlane { facet, hole } => {
                write!(f, "facet {facet} hole {hole} is not in the facet's plane")
            }
            SelfIntersectingFacet {
                facet,
                first_polygon,
                second_polygon,
            } => {
                if first_polygon == second_polygon {
                    write!(f, "facet {facet} polygon {first_polygon} crosses itself")
                } else {
                    write!(
                        f,
                        "facet {facet}: polygons {first_polygon} and {second_polygon} cross"
                    )
                }
            }
            InvalidRegion3 { region } => write!(
                f,
                "region {region} has a NaN or infinite coordinate or attribute, or a maximum \
                 volume that is not positive"
            ),
            SegmentCrossesFacet { segment, facet } => write!(
                f,
                "segment {segment} meets facet {facet} other than at a shared vertex or edge"
            ),
            FacetsIntersect { first, second } => write!(
                f,
                "facets {first} and {second} intersect other than along shared edges and \
                 vertices"
            ),
            VertexOnFacet { vertex, facet } => write!(
                f,
                "point {vertex} lies on facet {facet} but is not one of its vertices"
            ),
            VertexOnSegment { vertex, segment } => {
                write!(f, "point {vertex} lies inside segment {segment}")
            }
            PointTooCloseToFacet {
                point,
                facet,
                distance,
            } => write!(
                f,
                "point {point} is {distance:.3e} from the plane of facet {facet}: too close to \
                 mesh apart (the 3D mesher resolves 2^-36 of the input's size); move it onto \
                 the facet or further away"
            ),
            OpenSurface {
                count,
                edges,
                facets,
            } => {
                write!(f, "the facets enclose no volume: the surface is open")?;
                if *count > 0 {
                    let list: Vec<String> =
                        edges.iter().map(|e| format!("{}-{}", e[0], e[1])).collect();
                    write!(
                        f,
                        " ({count} facet edge{} used by one facet only, e.g. {}",
                        if *count == 1 { " is" } else { "s are" },
                        list.join(", ")
                    )?;
                    if !facets.is_empty() {
                        write!(f, " of facet{} {}", plural(facets.len()), join(facets))?;
                    }
                    write!(f, ")")?;
                }
                Ok(())
            }
            NonManifoldEdge {
                count,
                edge,
                facets,
            } => write!(
                f,
                "the facets enclose no volume and the surface is not manifold: {count} facet \
                 edge{} shared by three or more facets, e.g. {}-{} by facets {}",
                if *count == 1 { " is" } else { "s are" },
                edge[0],
                edge[1],
                join(facets)
            ),
            UntriangulablePolygon { facet } => write!(
                f,
                "facet {facet} is not planar and cannot be triangulated on its own vertices: \
                 no projection along a coordinate axis makes it a simple polygon"
            ),
        }
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

fn join(items: &[usize]) -> String {
    let list: Vec<String> = items.iter().map(|i| i.to_string()).collect();
    list.join(", ")
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Input(e) => write!(f, "invalid input: {e}"),
            Error::InvalidOption(m) => write!(f, "invalid option: {m}"),
            Error::Unsupported(m) => write!(f, "unsupported: {m}"),
            Error::Internal(m) => write!(f, "internal error (please report): {m}"),
            Error::Cancelled(s) => write!(f, "cancelled by the progress callback (stage: {s})"),
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

/// The text of a caught panic's payload (the `&str` or `String` that `panic!` carries).
pub(crate) fn panic_message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic payload".into())
}

/// Runs `f`, turning a panic into [`Error::Internal`] (`context` says what was running) so a
/// bug never takes the host program down. The state `f` worked on is discarded with the
/// error, so unwind safety of what it borrowed is not a concern.
pub(crate) fn catch_panic<T>(
    context: &str,
    f: impl FnOnce() -> Result<T, Error>,
) -> Result<T, Error> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).unwrap_or_else(|payload| {
        Err(Error::Internal(format!(
            "{context}caught a panic: {}",
            panic_message(payload.as_ref())
        )))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_coordinate_limit_message_states_the_limit() {
        let msg = InputError::CoordinateTooLarge { point: 4 }.to_string();
        assert!(msg.ends_with("(|x| > 1e50)"), "{msg}");
        assert_eq!(format!("{MAX_COORD:e}"), "1e50");
    }

    #[test]
    fn a_panic_becomes_an_internal_error_with_its_text() {
        let r: Result<(), Error> = catch_panic("doing x: ", || panic!("boom {}", 7));
        assert_eq!(
            r,
            Err(Error::Internal("doing x: caught a panic: boom 7".into()))
        );
        let r: Result<(), Error> = catch_panic("", || std::panic::panic_any(3u8));
        assert_eq!(
            r,
            Err(Error::Internal(
                "caught a panic: unknown panic payload".into()
            ))
        );
    }
}
