//! What kind of input item was bad, and which, for C callers: `idm_last_error_item` reads the
//! [`InputError`] behind the thread's last `IDM_ERR_INVALID_INPUT` and reports it as a stable
//! kind code ([`idm_input_error`]) and up to three indices, next to the message of
//! `idm_last_error`.

use std::panic::{catch_unwind, AssertUnwindSafe};

use super::common::{write_out, LAST_ERROR};
use crate::error::InputError;

/// The kind of the bad input item behind an `IDM_ERR_INVALID_INPUT` (see
/// `idm_last_error_item`). The values are fixed (ABI); 2D and 3D share a kind where the
/// problem is the same. `item`, `part` and `other` are the indices `idm_last_error_item`
/// fills (-1 when the kind has none).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum idm_input_error {
    /// The last call did not fail with invalid input.
    IDM_INPUT_OK = 0,
    /// Too few points (3 in 2D, 4 in 3D).
    IDM_INPUT_TOO_FEW_POINTS = 1,
    /// `item`: a point with a NaN or infinite coordinate.
    IDM_INPUT_NON_FINITE_POINT = 2,
    /// `item` and `other`: two points with identical coordinates.
    IDM_INPUT_DUPLICATE_POINT = 3,
    /// All points on one line (2D).
    IDM_INPUT_ALL_COLLINEAR = 4,
    /// All points in one plane (3D).
    IDM_INPUT_ALL_COPLANAR = 5,
    /// `item`: a point with a coordinate too large to mesh safely.
    IDM_INPUT_COORDINATE_TOO_LARGE = 6,
    /// A marker array without one entry per item.
    IDM_INPUT_MARKER_COUNT = 7,
    /// `item`: a segment referring to point `other`, which does not exist.
    IDM_INPUT_SEGMENT_INDEX_OUT_OF_RANGE = 8,
    /// `item`: a segment of zero length.
    IDM_INPUT_ZERO_LENGTH_SEGMENT = 9,
    /// `item` and `other`: two segments joining the same two points.
    IDM_INPUT_DUPLICATE_SEGMENT = 10,
    /// `item` and `other`: two segments crossing other than at a shared endpoint.
    IDM_INPUT_CROSSING_SEGMENTS = 11,
    /// `item`: a hole seed with a NaN or infinite coordinate.
    IDM_INPUT_NON_FINITE_HOLE = 12,
    /// `item`: a hole seed outside the domain (or on a segment, or in 3D on a facet).
    IDM_INPUT_HOLE_OUTSIDE_DOMAIN = 13,
    /// `item`: a region with a NaN or infinite coordinate or attribute, or a bound that is not
    /// positive.
    IDM_INPUT_INVALID_REGION = 14,
    /// `item`: a region seed outside the domain (or on a segment, or in 3D on a facet).
    IDM_INPUT_REGION_OUTSIDE_DOMAIN = 15,
    /// `item`: a facet with no polygon.
    IDM_INPUT_FACET_WITHOUT_POLYGONS = 16,
    /// `item`: a facet whose polygon `part` has no vertex.
    IDM_INPUT_EMPTY_POLYGON = 17,
    /// `item`: a facet whose polygon `part` refers to point `other`, which does not exist.
    IDM_INPUT_FACET_INDEX_OUT_OF_RANGE = 18,
    /// `item`: a facet whose polygon `part` lists point `other` twice.
    IDM_INPUT_REPEATED_VERTEX_IN_POLYGON = 19,
    /// `item`: a facet whose loop `part` has all its vertices on one line.
    IDM_INPUT_DEGENERATE_POLYGON = 20,
    /// `item`: a facet whose vertices all lie on one line.
    IDM_INPUT_DEGENERATE_FACET = 21,
    /// `item`: a facet that is not planar; point `other` is off its plane.
    IDM_INPUT_NON_PLANAR_FACET = 22,
    /// `item`: a facet whose hole seed `part` has a NaN or infinite coordinate.
    IDM_INPUT_NON_FINITE_FACET_HOLE = 23,
    /// `item`: a facet whose hole seed `part` is off the facet's plane.
    IDM_INPUT_FACET_HOLE_OFF_PLANE = 24,
    /// `item`: a facet whose polygons `part` and `other` (maybe the same one) cross.
    IDM_INPUT_SELF_INTERSECTING_FACET = 25,
    /// `item`: a segment meeting facet `other` other than at a shared vertex or edge.
    IDM_INPUT_SEGMENT_CROSSES_FACET = 26,
    /// `item` and `other`: two facets meeting other than along shared edges and vertices.
    IDM_INPUT_FACETS_INTERSECT = 27,
    /// `item`: a point on facet `other` that is not one of its vertices.
    IDM_INPUT_VERTEX_ON_FACET = 28,
    /// `item`: a point inside segment `other`.
    IDM_INPUT_VERTEX_ON_SEGMENT = 29,
    /// `item` and `other`: the points of the first facet edge that only one facet uses (the
    /// facets enclose no volume); `part`: how many such edges there are.
    IDM_INPUT_OPEN_SURFACE = 30,
    /// `item` and `other`: the points of the first facet edge that three or more facets share
    /// (the facets enclose no volume and the surface is not manifold); `part`: how many such
    /// edges there are.
    IDM_INPUT_NON_MANIFOLD_EDGE = 31,
    /// `item`: a non-planar surface polygon that cannot be triangulated on its own vertices
    /// (`surface_input` only).
    IDM_INPUT_UNTRIANGULABLE_POLYGON = 32,
    /// `item`: a point too close to facet `other` to mesh them apart (closer than the 3D
    /// mesher's resolution, 2^-36 of the input's size).
    IDM_INPUT_POINT_TOO_CLOSE_TO_FACET = 33,
}

/// An input error as C sees it: its kind and its `item`, `part` and `other` indices (-1: none).
fn describe(e: &InputError) -> (idm_input_error, [i64; 3]) {
    use idm_input_error::*;
    use InputError::*;
    // Indices are far below 2^63; the conversion saturates all the same.
    let ix = |i: usize| i64::try_from(i).unwrap_or(i64::MAX);
    let ix64 = |i: u64| i64::try_from(i).unwrap_or(i64::MAX);
    let none = -1;
    match *e {
        TooFewPoints { .. } | TooFewPoints3 { .. } => (IDM_INPUT_TOO_FEW_POINTS, [none; 3]),
        NonFinitePoint { point } => (IDM_INPUT_NON_FINITE_POINT, [ix(point), none, none]),
        DuplicatePoint { first, second } => {
            (IDM_INPUT_DUPLICATE_POINT, [ix(first), none, ix(second)])
        }
        AllCollinear => (IDM_INPUT_ALL_COLLINEAR, [none; 3]),
        AllCoplanar => (IDM_INPUT_ALL_COPLANAR, [none; 3]),
        CoordinateTooLarge { point } => (IDM_INPUT_COORDINATE_TOO_LARGE, [ix(point), none, none]),
        MarkerCountMismatch { .. } => (IDM_INPUT_MARKER_COUNT, [none; 3]),
        SegmentIndexOutOfRange { segment, index, .. } => (
            IDM_INPUT_SEGMENT_INDEX_OUT_OF_RANGE,
            [ix(segment), none, ix64(index)],
        ),
        ZeroLengthSegment { segment } => (IDM_INPUT_ZERO_LENGTH_SEGMENT, [ix(segment), none, none]),
        DuplicateSegment { first, second } => {
            (IDM_INPUT_DUPLICATE_SEGMENT, [ix(first), none, ix(second)])
        }
        CrossingSegments { first, second } => {
            (IDM_INPUT_CROSSING_SEGMENTS, [ix(first), none, ix(second)])
        }
        NonFiniteHole { hole } => (IDM_INPUT_NON_FINITE_HOLE, [ix(hole), none, none]),
        HoleOutsideDomain { hole } => (IDM_INPUT_HOLE_OUTSIDE_DOMAIN, [ix(hole), none, none]),
        NonFiniteRegion { region } | InvalidRegion3 { region } => {
            (IDM_INPUT_INVALID_REGION, [ix(region), none, none])
        }
        RegionOutsideDomain { region } => {
            (IDM_INPUT_REGION_OUTSIDE_DOMAIN, [ix(region), none, none])
        }
        FacetWithoutPolygons { facet } => {
            (IDM_INPUT_FACET_WITHOUT_POLYGONS, [ix(facet), none, none])
        }
        EmptyPolygon { facet, polygon } => {
            (IDM_INPUT_EMPTY_POLYGON, [ix(facet), ix(polygon), none])
        }
        FacetIndexOutOfRange {
            facet,
            polygon,
            index,
            ..
        } => (
            IDM_INPUT_FACET_INDEX_OUT_OF_RANGE,
            [ix(facet), ix(polygon), ix64(index)],
        ),
        RepeatedVertexInPolygon {
            facet,
            polygon,
            vertex,
        } => (
            IDM_INPUT_REPEATED_VERTEX_IN_POLYGON,
            [ix(facet), ix(polygon), ix(vertex)],
        ),
        DegeneratePolygon { facet, polygon } => {
            (IDM_INPUT_DEGENERATE_POLYGON, [ix(facet), ix(polygon), none])
        }
        DegenerateFacet { facet } => (IDM_INPUT_DEGENERATE_FACET, [ix(facet), none, none]),
        NonPlanarFacet { facet, vertex } => {
            (IDM_INPUT_NON_PLANAR_FACET, [ix(facet), none, ix(vertex)])
        }
        NonFiniteFacetHole { facet, hole } => {
            (IDM_INPUT_NON_FINITE_FACET_HOLE, [ix(facet), ix(hole), none])
        }
        FacetHoleOffPlane { facet, hole } => {
            (IDM_INPUT_FACET_HOLE_OFF_PLANE, [ix(facet), ix(hole), none])
        }
        SelfIntersectingFacet {
            facet,
            first_polygon,
            second_polygon,
        } => (
            IDM_INPUT_SELF_INTERSECTING_FACET,
            [ix(facet), ix(first_polygon), ix(second_polygon)],
        ),
        SegmentCrossesFacet { segment, facet } => (
            IDM_INPUT_SEGMENT_CROSSES_FACET,
            [ix(segment), none, ix(facet)],
        ),
        FacetsIntersect { first, second } => {
            (IDM_INPUT_FACETS_INTERSECT, [ix(first), none, ix(second)])
        }
        VertexOnFacet { vertex, facet } => {
            (IDM_INPUT_VERTEX_ON_FACET, [ix(vertex), none, ix(facet)])
        }
        VertexOnSegment { vertex, segment } => {
            (IDM_INPUT_VERTEX_ON_SEGMENT, [ix(vertex), none, ix(segment)])
        }
        PointTooCloseToFacet { point, facet, .. } => (
            IDM_INPUT_POINT_TOO_CLOSE_TO_FACET,
            [ix(point), none, ix(facet)],
        ),
        OpenSurface {
            count, ref edges, ..
        } => {
            let e = edges.first().map_or([none, none], |e| [ix(e[0]), ix(e[1])]);
            (IDM_INPUT_OPEN_SURFACE, [e[0], ix(count), e[1]])
        }
        NonManifoldEdge { count, edge, .. } => (
            IDM_INPUT_NON_MANIFOLD_EDGE,
            [ix(edge[0]), ix(count), ix(edge[1])],
        ),
        UntriangulablePolygon { facet } => {
            (IDM_INPUT_UNTRIANGULABLE_POLYGON, [ix(facet), none, none])
        }
    }
}

/// The kind of the bad input item behind this thread's last failure, when that failure was
/// `IDM_ERR_INVALID_INPUT` (`IDM_INPUT_OK` otherwise, the out-parameters then get -1). Each
/// out-pointer may be NULL when not wanted; they get the indices the kind documents: `item`
/// (the point, segment, hole, region or facet the message names first), `part` (a polygon or
/// hole seed of facet `item`) and `other` (the second item the message names), -1 where the
/// kind has none. Indices are 0-based in the order the items were added.
///
/// This call reads the last error and leaves it (and `idm_last_error`) as it is.
///
/// # Safety
/// Each out-pointer must be NULL or valid for writing an `int64_t`.
#[no_mangle]
pub unsafe extern "C" fn idm_last_error_item(
    item: *mut i64,
    part: *mut i64,
    other: *mut i64,
) -> idm_input_error {
    let found = catch_unwind(AssertUnwindSafe(|| {
        LAST_ERROR
            .try_with(|e| e.borrow().input.as_ref().map(describe))
            .ok()
            .flatten()
    }))
    .ok()
    .flatten();
    let (kind, ix) = found.unwrap_or((idm_input_error::IDM_INPUT_OK, [-1; 3]));
    for (p, v) in [item, part, other].into_iter().zip(ix) {
        if p.is_aligned() {
            // SAFETY: NULL is skipped; otherwise the caller's contract.
            unsafe { write_out(p, v) };
        }
    }
    kind
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::common::{idm_last_error, idm_status};
    use crate::ffi::mesh2d::*;
    use crate::ffi::mesh3d::*;
    use idm_input_error::*;
    use std::ffi::CStr;

    fn last_item() -> (idm_input_error, [i64; 3]) {
        let mut ix = [7i64; 3];
        let [a, b, c] = &mut ix;
        let kind = unsafe { idm_last_error_item(a, b, c) };
        (kind, ix)
    }

    /// Meshes the 2D points `xy` and segments `ab` through the C entry points.
    fn refine2d(xy: &[f64], ab: &[u32]) -> idm_status {
        let mut m = std::ptr::null_mut();
        unsafe {
            assert_eq!(idm_mesher2d_new(&mut m), idm_status::IDM_OK);
            let np = std::ptr::null();
            assert_eq!(
                idm_mesher2d_add_points(m, xy.as_ptr(), xy.len() / 2, np),
                idm_status::IDM_OK
            );
            assert_eq!(
                idm_mesher2d_add_segments(m, ab.as_ptr(), ab.len() / 2, np),
                idm_status::IDM_OK
            );
            let st = idm_mesher2d_refine(m);
            idm_mesher2d_free(m);
            st
        }
    }

    const SQUARE: [f64; 8] = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];

    #[test]
    fn input_errors_reach_c_with_kind_and_indices() {
        // The diagonals cross: segments 4 and 5.
        let ab = [0, 1, 1, 2, 2, 3, 3, 0, 0, 2, 1, 3];
        assert_eq!(refine2d(&SQUARE, &ab), idm_status::IDM_ERR_INVALID_INPUT);
        assert_eq!(last_item(), (IDM_INPUT_CROSSING_SEGMENTS, [4, -1, 5]));
        // Reading the item leaves the message alone.
        let msg = unsafe { CStr::from_ptr(idm_last_error()) }
            .to_str()
            .unwrap();
        assert!(msg.contains("segments 4 and 5"), "{msg}");
        // Segment 1 refers to point 9.
        assert_eq!(
            refine2d(&SQUARE, &[0, 1, 1, 9]),
            idm_status::IDM_ERR_INVALID_INPUT
        );
        assert_eq!(
            last_item(),
            (IDM_INPUT_SEGMENT_INDEX_OUT_OF_RANGE, [1, -1, 9])
        );
        // Point 4 repeats point 2.
        let mut dup = SQUARE.to_vec();
        dup.extend([1.0, 1.0]);
        assert_eq!(refine2d(&dup, &[]), idm_status::IDM_ERR_INVALID_INPUT);
        assert_eq!(last_item(), (IDM_INPUT_DUPLICATE_POINT, [2, -1, 4]));
        // Point 1 has a NaN coordinate.
        let mut nan = SQUARE;
        nan[3] = f64::NAN;
        assert_eq!(refine2d(&nan, &[]), idm_status::IDM_ERR_INVALID_INPUT);
        assert_eq!(last_item(), (IDM_INPUT_NON_FINITE_POINT, [1, -1, -1]));
        // A success clears it; NULL out-pointers are fine.
        assert_eq!(refine2d(&SQUARE, &[]), idm_status::IDM_OK);
        assert_eq!(last_item(), (IDM_INPUT_OK, [-1; 3]));
        let np = std::ptr::null_mut();
        assert_eq!(unsafe { idm_last_error_item(np, np, np) }, IDM_INPUT_OK);
    }

    #[test]
    fn a_3d_facet_error_names_facet_polygon_and_point() {
        let mut m = std::ptr::null_mut();
        let xyz = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let tri = [0u32, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 9];
        let off = [0usize, 3];
        unsafe {
            assert_eq!(idm_mesher3d_new(&mut m), idm_status::IDM_OK);
            let np = std::ptr::null();
            assert_eq!(
                idm_mesher3d_add_points(m, xyz.as_ptr(), 4, np),
                idm_status::IDM_OK
            );
            for f in tri.chunks_exact(3) {
                let st =
                    idm_mesher3d_add_facet(m, f.as_ptr(), off.as_ptr(), 1, std::ptr::null(), 0, 0);
                assert_eq!(st, idm_status::IDM_OK);
            }
            assert_eq!(idm_mesher3d_refine(m), idm_status::IDM_ERR_INVALID_INPUT);
            idm_mesher3d_free(m);
        }
        assert_eq!(last_item(), (IDM_INPUT_FACET_INDEX_OUT_OF_RANGE, [3, 0, 9]));
    }

    /// Every kind code is distinct (the ABI values are fixed by the enum's discriminants).
    #[test]
    fn kinds_are_distinct() {
        let samples = [
            InputError::TooFewPoints { count: 1 },
            InputError::TooFewPoints3 { count: 1 },
            InputError::AllCollinear,
            InputError::AllCoplanar,
            InputError::NonFiniteRegion { region: 0 },
            InputError::InvalidRegion3 { region: 0 },
            InputError::VertexOnSegment {
                vertex: 0,
                segment: 1,
            },
        ];
        let kinds: Vec<i32> = samples.iter().map(|e| describe(e).0 as i32).collect();
        assert_eq!(kinds, [1, 1, 4, 5, 14, 14, 29]);
    }
}
