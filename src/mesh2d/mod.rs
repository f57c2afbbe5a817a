//! The 2D mesher (paper §3): conforming Delaunay triangulation of a PSLG and Delaunay
//! refinement to a minimum angle and maximum area.
//!
//! Pipeline: validate the input (and scale it up by a power of two when its coordinates are
//! so small that the exact predicates would underflow); insert every input point
//! (Bowyer–Watson, BRIO/Hilbert order, walking point location; without segments the whole run
//! names the points by their rank in that order, and the names go back at the end); insert
//! every segment as a
//! constrained edge (no Steiner point); classify exterior, holes and regions by flooding up to
//! segments and carve them away; split encroached segments until the constrained triangulation
//! is Delaunay (paper Fig. 2, `Force`); then eliminate skinny and oversized triangles (paper
//! Fig. 4, `Provisional` circumcenter / off-center insertion); flip the edges that rounded
//! split points left not locally Delaunay. With `no_boundary_steiner` (Triangle's `-Y`) boundary segments are
//! never split, with `no_segment_steiner` (`-YY`) no segment is, and the result is constrained
//! Delaunay.
//!
//! The incremental kernel underneath (`store.rs` with `recover.rs` and `flip.rs`: point
//! location, the Bowyer–Watson cavity, constrained segment recovery and Lawson flips, one
//! ghost vertex at infinity) is generic over the exact predicates of a `geometry::Geometry`
//! (paper §2). The mesher's pipeline (`build.rs` → `refine.rs` → `output.rs`) depends on the
//! kernel, never the other way round; the 3D input checks triangulate facets with the same
//! kernel (re-exported as `mesh2d::kernel`). `attributes.rs` carries input point attributes
//! to the output, interpolated at Steiner vertices (Triangle's point attributes).

mod attributes;
mod build;
mod flip;
mod geometry;
mod kdtree;
mod output;
mod recover;
mod refine;
mod store;
mod validate;

#[cfg(test)]
mod tests;

/// The incremental 2D kernel (paper §2) for the other layers that triangulate in a plane: the
/// 3D input checks triangulate each facet's projected vertices with it, and the 3D facet
/// meshes decide with its in-plane geometry.
pub(crate) mod kernel {
    pub(crate) use super::geometry::{Geometry, InPlane};
    pub(crate) use super::recover::Recovery;
    pub(crate) use super::store::{next, prev, Cdt, Inserted, Seg, EXTERIOR, HOLE, NO_REGION};
    pub(crate) use super::NONE;
}

use std::fmt;
use std::sync::Arc;

pub use attributes::interpolate_point_attributes;
pub use output::TriMesh;

use crate::error::Error;
use crate::input2d::Pslg;

pub use crate::NONE;

/// A user sizing test, as Triangle's `triunsuitable`: called with the three corners of a
/// triangle (counter-clockwise) and its area; returns `true` when the triangle is too large and
/// must be split. It must be deterministic; it is called from the meshing thread only.
pub type SizingFn = Arc<dyn Fn([f64; 2], [f64; 2], [f64; 2], f64) -> bool + Send + Sync>;

/// Meshing options. `Options::default()` gives a conforming Delaunay triangulation of the PSLG
/// with no quality or size refinement.
#[derive(Clone)]
pub struct Options {
    /// Minimum angle in degrees (Triangle's `-q`). `None`: no angle refinement. Must lie in
    /// `(0, 34]`: termination is proven up to 20.7° and observed up to 35°; above that
    /// refinement can run away (Triangle's too), so larger bounds are refused. Triangles whose small angle sits between input segments meeting at less
    /// than 60° are exempt. Default: `None`.
    pub min_angle: Option<f64>,
    /// Global maximum triangle area (Triangle's `-a<area>`). Default: `None`.
    pub max_area: Option<f64>,
    /// Apply each region's `max_area` (Triangle's `-a` without a number). Default: `false`.
    pub region_max_area: bool,
    /// Write each region's attribute to its triangles (Triangle's `-A`). Default: `false`.
    pub region_attributes: bool,
    /// Mesh the whole convex hull of the points instead of only the area enclosed by segments
    /// (Triangle's `-c`). Without segments the convex hull is always meshed. Default: `false`.
    pub convex_hull: bool,
    /// Maximum number of Steiner points (Triangle's `-S<n>`). When reached, refinement stops and
    /// the mesh is returned with [`TriMesh::complete`] set to `false`. The cap counts every
    /// Steiner point, the segment splits that make segments conforming included: once it is
    /// reached, segments still encroached are left as they are, and the mesh is constrained
    /// Delaunay (what [`TriMesh::validate`] checks of an incomplete mesh). A segment missing
    /// from the mesh is still split until it is present, which can add a few points beyond
    /// the cap. Default: `None` (no cap other than an internal safety cap of 2^31 vertices).
    pub max_steiner: Option<u64>,
    /// Forbid Steiner points on boundary segments (Triangle's `-Y`): segments with the domain
    /// on one side only (outer boundary, hole boundaries, the hull with `convex_hull`) stay
    /// single edges. Interior segments are still split where encroached. The result is then
    /// constrained Delaunay, not conforming Delaunay: check it with
    /// [`TriMesh::validate_constrained`].
    ///
    /// As in Triangle, a refinement point that would encroach a boundary segment (or fall
    /// beyond one) is rejected and its triangle is left as it is: triangles near boundary
    /// segments, typically those with a boundary edge whose circumcenter lies outside or near
    /// the boundary, may keep angles below `min_angle` and areas above the bounds. A domain all
    /// of whose triangles touch the boundary may get no Steiner point at all. Default: `false`.
    pub no_boundary_steiner: bool,
    /// Forbid Steiner points on every segment (Triangle's `-YY`), interior segments included:
    /// every input segment stays a single edge (or the pieces between input points lying on
    /// it). Implies [`Options::no_boundary_steiner`] and has the same consequences, now next
    /// to every segment: the mesh is constrained Delaunay (check it with
    /// [`TriMesh::validate_constrained`]), and a refinement point that would encroach a
    /// segment is rejected, so triangles next to segments may keep angles below `min_angle`
    /// and areas above the bounds. Default: `false`.
    pub no_segment_steiner: bool,
    /// Use off-centers (Üngör) instead of circumcenters for skinny triangles: fewer triangles for
    /// the same angle bound. Default: `true`.
    pub off_centers: bool,
    /// Resolve crossing segments by inserting their intersection point (rounded to floating
    /// point, as Triangle does) instead of reporting [`crate::InputError::CrossingSegments`].
    /// Segments that cross at an input point are split there; crossings of several segments
    /// through one point that round a few ulps apart become one vertex. Collinear overlaps
    /// are still errors. Default: `false`.
    pub split_crossings: bool,
    /// A user sizing test (Triangle's `-u`); see [`SizingFn`]. Default: `None`.
    pub sizing: Option<SizingFn>,
    /// A progress callback, which may also cancel the run; see [`crate::progress`].
    /// Default: `None`.
    pub progress: Option<crate::progress::ProgressFn>,
    /// Print progress lines to standard error during long runs. Default: `false`.
    pub verbose: bool,
    /// Threads a run may use (so far for the exact check every run ends with; the mesh and
    /// every message are the same for any count). `None`: the environment variable
    /// `IDMESH_THREADS`, else all cores ([`crate::threads::count`]). Must be at least 1.
    /// Default: `None`.
    pub threads: Option<usize>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            min_angle: None,
            max_area: None,
            region_max_area: false,
            region_attributes: false,
            convex_hull: false,
            max_steiner: None,
            no_boundary_steiner: false,
            no_segment_steiner: false,
            off_centers: true,
            split_crossings: false,
            sizing: None,
            progress: None,
            verbose: false,
            threads: None,
        }
    }
}

impl fmt::Debug for Options {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Options")
            .field("min_angle", &self.min_angle)
            .field("max_area", &self.max_area)
            .field("region_max_area", &self.region_max_area)
            .field("region_attributes", &self.region_attributes)
            .field("convex_hull", &self.convex_hull)
            .field("max_steiner", &self.max_steiner)
            .field("no_boundary_steiner", &self.no_boundary_steiner)
            .field("no_segment_steiner", &self.no_segment_steiner)
            .field("off_centers", &self.off_centers)
            .field("split_crossings", &self.split_crossings)
            .field("sizing", &self.sizing.as_ref().map(|_| "<fn>"))
            .field("progress", &self.progress.as_ref().map(|_| "<fn>"))
            .field("verbose", &self.verbose)
            .field("threads", &self.threads)
            .finish()
    }
}

/// Meshes a PSLG: conforming Delaunay triangulation of the domain enclosed by the segments
/// (minus holes), refined to the options' angle and area bounds.
///
/// Returns an error naming the offending item for invalid input. When the Steiner cap is hit the
/// mesh is still returned (valid and conforming) with `complete == false`. With
/// [`Options::progress`] set, the run reports to it and returns [`Error::Cancelled`] when told
/// to stop.
pub fn triangulate(pslg: &Pslg, opts: &Options) -> Result<TriMesh, Error> {
    // A bug must never take the host program down: a panic becomes `Error::Internal`.
    crate::error::catch_panic("", || {
        crate::progress::observe(opts.progress.as_ref(), || build::run(pslg, opts))
    })
}
