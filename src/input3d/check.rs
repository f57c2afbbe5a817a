//! Validation of a [`Plc`] before meshing.
//!
//! The checks run from cheap to expensive and the first problem found is reported, naming the
//! offending items by their 0-based indices:
//! 1. counts, finite and not too large coordinates, marker counts, index ranges, empty or
//!    repeating polygons, hole and region seeds;
//! 2. duplicate points (sorted, so `O(n log n)`), duplicate segments, all points coplanar;
//! 3. each facet alone: loops with all vertices on a line, facets without a plane, vertices
//!    or hole seeds off the facet's plane, polygon edges that cross;
//! 4. improper intersections between features, on the pairs a uniform grid finds close
//!    (each feature entered only in the cells it meets): near linear for surface meshes
//!    (a 13k-triangle CAD model: about 0.1 s in release), slower when thousands of
//!    features crowd a few cells, as along the rim of one facet with 20000 vertices (6 s).
//!
//! Every geometric decision is an exact predicate; floating point only narrows candidates.
//!
//! What counts as improper (the PLC must be closed under intersection, as in the paper's
//! Definition 2.1): segments meet only at shared endpoints; a segment meets a facet only at a
//! vertex of both or along one of the facet's polygon edges; two facets meet only along
//! shared vertices and polygon edges. A point lying on a facet (inside it or on its boundary)
//! must be one of the facet's vertices, listed in one of its polygons (a 1-vertex polygon
//! will do), else [`InputError::VertexOnFacet`]. TetGen accepts such dangling points and
//! silently inserts them; idmesh asks for them to be listed, so that every facet's own
//! triangulation knows all the vertices the 3D mesh will have on it. In the same way an edge
//! of another facet, or a segment, lying inside a facet must be one of the facet's polygon
//! edges (a 2-vertex polygon will do), else [`InputError::FacetsIntersect`] or
//! [`InputError::SegmentCrossesFacet`]. A point inside a segment is an error
//! ([`InputError::VertexOnSegment`]); a point inside one of a facet's own polygon edges is
//! fine (it splits the edge), as long as every other facet sharing that edge lists it too.
//!
//! Exactness has the usual limit of floating-point predicates: coordinates so small that
//! products of their differences underflow (differences below about 1e-100) can be misjudged.
//!
//! A facet's region is what TetGen makes of it: the area enclosed by its loops, minus what is
//! reachable from its hole seeds without crossing a polygon edge. A hole seed exactly on a
//! polygon edge floods whichever side is found first.

mod cdt;
mod exact3;
mod facets;
mod grid;
mod intersect;

#[cfg(test)]
mod tests;

use super::Plc;
use crate::error::{Error, InputError, MAX_COORD};
use crate::mesh3d::NONE;
use crate::predicates::orient3d;

pub(crate) use cdt::FacetTriangulation;

/// Each facet's region as triangles on its own vertices (global point indices) and the facet
/// of each triangle, as the checks see it; the PLC must have passed [`check_plc`].
pub(crate) fn facet_regions(plc: &Plc) -> Result<(Vec<[u32; 3]>, Vec<u32>), Error> {
    let f = facets::triangulate_facets(plc)?;
    Ok((f.tris, f.tri_facet))
}

/// Checks a PLC and reports the first problem found, naming the offending item.
pub fn check_plc(plc: &Plc) -> Result<(), Error> {
    // A bug must never take the host down: a panic becomes `Error::Internal`.
    crate::error::catch_panic("checking the PLC: ", || check(plc))
}

fn check(plc: &Plc) -> Result<(), Error> {
    check_items(plc)?;
    check_seeds(plc)?;
    check_duplicate_points(&plc.points)?;
    check_duplicate_segments(&plc.segments)?;
    check_not_coplanar(&plc.points)?;
    let facets = facets::triangulate_facets(plc)?;
    intersect::check_intersections(plc, &facets)
}

/// The first checks, on items one at a time: point count and coordinates, marker counts,
/// segment and polygon indices, empty polygons and polygons listing a point twice (what must
/// hold before points can be renumbered, as the surface repair does).
pub(crate) fn check_items(plc: &Plc) -> Result<(), Error> {
    check_points(plc)?;
    check_markers(plc)?;
    check_segments(plc)?;
    check_polygons(plc)
}

fn check_points(plc: &Plc) -> Result<(), Error> {
    let n = plc.points.len();
    if n < 4 {
        return Err(InputError::TooFewPoints3 { count: n }.into());
    }
    if n >= (NONE / 4) as usize {
        return Err(Error::InvalidOption(format!(
            "{n} points is more than this build supports"
        )));
    }
    for (i, p) in plc.points.iter().enumerate() {
        if !p.iter().all(|x| x.is_finite()) {
            return Err(InputError::NonFinitePoint { point: i }.into());
        }
        if p.iter().any(|x| x.abs() > MAX_COORD) {
            return Err(InputError::CoordinateTooLarge { point: i }.into());
        }
    }
    Ok(())
}

fn check_markers(plc: &Plc) -> Result<(), Error> {
    let counts = [
        ("point", plc.point_markers.len(), plc.points.len()),
        ("segment", plc.segment_markers.len(), plc.segments.len()),
    ];
    for (what, got, expected) in counts {
        if got != 0 && got != expected {
            return Err(InputError::MarkerCountMismatch {
                what,
                expected,
                got,
            }
            .into());
        }
    }
    Ok(())
}

fn check_segments(plc: &Plc) -> Result<(), Error> {
    let n = plc.points.len();
    for (s, e) in plc.segments.iter().enumerate() {
        if let Some(&i) = e.iter().find(|&&i| i as usize >= n) {
            return Err(InputError::SegmentIndexOutOfRange {
                segment: s,
                index: i as u64,
                num_points: n,
            }
            .into());
        }
        if e[0] == e[1] || plc.points[e[0] as usize] == plc.points[e[1] as usize] {
            return Err(InputError::ZeroLengthSegment { segment: s }.into());
        }
    }
    Ok(())
}

fn check_polygons(plc: &Plc) -> Result<(), Error> {
    let n = plc.points.len();
    let mut sorted: Vec<u32> = Vec::new();
    for (f, facet) in plc.facets.iter().enumerate() {
        if facet.polygons.is_empty() {
            return Err(InputError::FacetWithoutPolygons { facet: f }.into());
        }
        for (p, poly) in facet.polygons.iter().enumerate() {
            if poly.is_empty() {
                return Err(InputError::EmptyPolygon {
                    facet: f,
                    polygon: p,
                }
                .into());
            }
            if let Some(&i) = poly.iter().find(|&&i| i as usize >= n) {
                return Err(InputError::FacetIndexOutOfRange {
                    facet: f,
                    polygon: p,
                    index: i as u64,
                    num_points: n,
                }
                .into());
            }
            sorted.clear();
            sorted.extend_from_slice(poly);
            sorted.sort_unstable();
            if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
                return Err(InputError::RepeatedVertexInPolygon {
                    facet: f,
                    polygon: p,
                    vertex: w[0] as usize,
                }
                .into());
            }
        }
    }
    Ok(())
}

fn check_seeds(plc: &Plc) -> Result<(), Error> {
    for (i, h) in plc.holes.iter().enumerate() {
        if !h.iter().all(|x| x.is_finite()) {
            return Err(InputError::NonFiniteHole { hole: i }.into());
        }
    }
    for (i, r) in plc.regions.iter().enumerate() {
        let bad_volume = matches!(r.max_volume, Some(v) if v.is_nan() || v <= 0.0);
        if !r.point.iter().all(|x| x.is_finite()) || !r.attribute.is_finite() || bad_volume {
            return Err(InputError::InvalidRegion3 { region: i }.into());
        }
    }
    Ok(())
}

/// Point indices sorted by coordinates, then index: points with equal coordinates (-0.0
/// equals 0.0) are neighbours, the first of them first.
pub(crate) fn by_coordinates(points: &[[f64; 3]]) -> Vec<u32> {
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    let cmp = |x: f64, y: f64| x.partial_cmp(&y).unwrap_or(std::cmp::Ordering::Equal);
    order.sort_unstable_by(|&i, &j| {
        let (a, b) = (points[i as usize], points[j as usize]);
        cmp(a[0], b[0])
            .then(cmp(a[1], b[1]))
            .then(cmp(a[2], b[2]))
            .then(i.cmp(&j))
    });
    order
}

/// Equal neighbours in [`by_coordinates`] order are duplicates.
fn check_duplicate_points(points: &[[f64; 3]]) -> Result<(), Error> {
    let order = by_coordinates(points);
    if let Some(w) = order
        .windows(2)
        .find(|w| points[w[0] as usize] == points[w[1] as usize])
    {
        return Err(InputError::DuplicatePoint {
            first: w[0] as usize,
            second: w[1] as usize,
        }
        .into());
    }
    Ok(())
}

fn check_duplicate_segments(segments: &[[u32; 2]]) -> Result<(), Error> {
    let mut keys: Vec<(u32, u32, usize)> = segments
        .iter()
        .enumerate()
        .map(|(s, e)| (e[0].min(e[1]), e[0].max(e[1]), s))
        .collect();
    keys.sort_unstable();
    if let Some(w) = keys
        .windows(2)
        .find(|w| w[0].0 == w[1].0 && w[0].1 == w[1].1)
    {
        return Err(InputError::DuplicateSegment {
            first: w[0].2,
            second: w[1].2,
        }
        .into());
    }
    Ok(())
}

/// Fails when every point lies in one plane (exact).
fn check_not_coplanar(points: &[[f64; 3]]) -> Result<(), Error> {
    let (a, b) = (points[0], points[1]);
    let Some(c) = points[2..]
        .iter()
        .copied()
        .find(|&c| !exact3::collinear(a, b, c))
    else {
        return Err(InputError::AllCoplanar.into());
    };
    if points.iter().all(|&d| orient3d(a, b, c, d) == 0.0) {
        return Err(InputError::AllCoplanar.into());
    }
    Ok(())
}
