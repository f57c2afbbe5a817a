//! Input types: the planar straight-line graph (PSLG) handed to the 2D mesher.

/// A region seed: every triangle reachable from `point` without crossing a segment gets
/// `attribute`, and, when `max_area` is set and regional area bounds are on, that area bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Region {
    /// A point strictly inside the region.
    pub point: [f64; 2],
    /// The regional attribute written to each triangle of the region.
    pub attribute: f64,
    /// The maximum triangle area in this region (`None`: no regional bound).
    pub max_area: Option<f64>,
}

/// A planar straight-line graph: points, segments between them, hole seeds and region seeds.
///
/// Markers are optional: leave a marker vector empty for "all zero" (points) or "all one"
/// (segments, as Triangle does for boundary segments without markers).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pslg {
    /// Point coordinates. Output vertex `i` is input point `i` for every `i < points.len()`.
    pub points: Vec<[f64; 2]>,
    /// One marker per point, or empty.
    pub point_markers: Vec<i32>,
    /// Segments as pairs of 0-based point indices.
    pub segments: Vec<[u32; 2]>,
    /// One marker per segment, or empty.
    pub segment_markers: Vec<i32>,
    /// Hole seeds: the triangles reachable from each seed without crossing a segment are removed.
    pub holes: Vec<[f64; 2]>,
    /// Region seeds (attributes and regional area bounds).
    pub regions: Vec<Region>,
}
