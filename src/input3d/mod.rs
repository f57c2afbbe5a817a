//! Input types for the 3D mesher: the piecewise linear complex (PLC).
//!
//! A PLC is a set of points, segments (input edges) and facets (planar polygons with optional
//! holes), plus volume hole seeds and region seeds, as in TetGen's `.poly` files.

mod check;

pub use check::check_plc;
pub(crate) use check::{by_coordinates, check_items, facet_regions, FacetTriangulation};

/// A planar facet: one or more vertex loops in one plane, as in TetGen's `.poly` facets.
///
/// Each polygon is a list of 0-based point indices. A polygon with three or more vertices is a
/// closed loop (the last vertex joins the first); with two vertices it is a segment lying in the
/// facet; with one vertex an isolated point of the facet. Which loops bound holes is decided by
/// the facet's `holes` seeds (points in the facet's plane), exactly as TetGen does: the facet is
/// the set of points enclosed by the loops and not reachable from a hole seed without crossing a
/// loop edge.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Facet {
    /// The vertex loops (and in-facet segments and points), as point indices.
    pub polygons: Vec<Vec<u32>>,
    /// Hole seeds lying in the facet's plane.
    pub holes: Vec<[f64; 3]>,
    /// The facet's boundary marker (written to the output faces that lie in it).
    pub marker: i32,
}

/// A volume region seed: every tetrahedron reachable from `point` without crossing a facet gets
/// `attribute`, and, when `max_volume` is set and regional bounds are on, that volume bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Region3 {
    /// A point strictly inside the region.
    pub point: [f64; 3],
    /// The regional attribute written to each tetrahedron of the region.
    pub attribute: f64,
    /// The maximum tetrahedron volume in this region (`None`: no regional bound).
    pub max_volume: Option<f64>,
}

/// A piecewise linear complex: points, segments, facets, hole seeds and region seeds.
///
/// Markers are optional: leave a marker vector empty for "all zero".
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Plc {
    /// Point coordinates. Output vertex `i` is input point `i` for every `i < points.len()`.
    pub points: Vec<[f64; 3]>,
    /// One marker per point, or empty.
    pub point_markers: Vec<i32>,
    /// Free-standing input edges as pairs of 0-based point indices (facet loop edges need not
    /// be repeated here).
    pub segments: Vec<[u32; 2]>,
    /// One marker per segment, or empty.
    pub segment_markers: Vec<i32>,
    /// The facets.
    pub facets: Vec<Facet>,
    /// Volume hole seeds: the tetrahedra reachable from each seed without crossing a facet are
    /// removed.
    pub holes: Vec<[f64; 3]>,
    /// Region seeds (attributes and regional volume bounds).
    pub regions: Vec<Region3>,
}
