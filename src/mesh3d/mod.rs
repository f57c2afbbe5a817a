//! The 3D mesher (paper §4): conforming Delaunay tetrahedralization of a PLC and Delaunay
//! refinement to a radius-edge bound and a maximum volume.
//!
//! Pipeline: validate the input; insert every input point into one Bowyer–Watson kernel
//! ([`store`]); keep a 1D mesh per input edge and a 2D Delaunay mesh per facet, refined lazily
//! until each appears in the 3D mesh (work queue of Definition 4.1); classify exterior, holes
//! and regions by flooding up to facets; then remove skinny and oversized tetrahedra (Fig. 9).

mod coplanar;
mod delaunay;
mod facet_mesh;
mod features;
#[cfg(test)]
mod kernel_tests;
mod order;
mod output;
mod plc;
#[cfg(test)]
pub(crate) mod plc_tests;
pub mod store;
mod validate;

use std::fmt;
use std::sync::Arc;

pub use output::{TetMesh, TetStats, DIHEDRAL_BINS};

use crate::error::{catch_panic, Error};
use crate::input3d::Plc;

pub use crate::NONE;

/// A user sizing test, as TetGen's `tetunsuitable`: called with the four corners of a
/// tetrahedron and its volume; returns `true` when the tetrahedron is too large and must be
/// split. It must be deterministic; it is called from the meshing thread only.
pub type SizingFn3 = Arc<dyn Fn([f64; 3], [f64; 3], [f64; 3], [f64; 3], f64) -> bool + Send + Sync>;

/// Meshing options for [`tetrahedralize`]. `Options3::default()` gives a conforming Delaunay
/// tetrahedralization of the PLC with no quality or size refinement.
#[derive(Clone, Default)]
pub struct Options3 {
    /// Maximum radius-edge ratio (TetGen's `-q`). `None`: no quality refinement. Must be at
    /// least 1.0; bounds below about 1.2 may not terminate (as in TetGen). Tetrahedra near
    /// small input angles are exempt. Default: `None` (TetGen's `-q` alone means 2.0).
    pub radius_edge: Option<f64>,
    /// Global maximum tetrahedron volume (TetGen's `-a<volume>`). Default: `None`.
    pub max_volume: Option<f64>,
    /// Apply each region's `max_volume` (TetGen's `-a` without a number). Default: `false`.
    pub region_max_volume: bool,
    /// Write each region's attribute to its tetrahedra (TetGen's `-A`). Default: `false`.
    pub region_attributes: bool,
    /// Maximum number of Steiner points (TetGen's `-S<n>`). When reached, refinement stops and
    /// the mesh is returned with [`TetMesh::complete`] set to `false`. Default: `None`.
    pub max_steiner: Option<u64>,
    /// A user sizing test; see [`SizingFn3`]. Default: `None`.
    pub sizing: Option<SizingFn3>,
    /// Keep the input surface (TetGen's `-Y`): no Steiner points on input edges or facets.
    /// The boundary faces of the mesh are then the input's triangles (a polygon facet is
    /// triangulated on its own vertices) and [`TetMesh::surface_kept`] is set.
    ///
    /// How: the conforming Delaunay mesh is made first (its boundary Steiner points recover
    /// every facet, whatever the input); each of those points is then moved off the surface
    /// into the domain (exactly checked to give positive tetrahedra) and removed where its
    /// neighbourhood allows. So any closed PLC works, including surfaces whose triangles are
    /// not Delaunay and polyhedra that cannot be tetrahedralized without interior points;
    /// the tetrahedra next to the surface are not Delaunay. Refinement afterwards adds
    /// interior points only, and, as in TetGen, a tetrahedron whose circumcenter would
    /// encroach a subface or subsegment stays as it is: the quality and volume bounds may not
    /// be met next to the boundary. A free input edge inside the volume (on no facet) cannot
    /// be kept whole: meshing then fails naming the point. Default: `false`.
    pub keep_surface: bool,
    /// Merge exactly coplanar neighbouring facets with the same marker into one facet before
    /// meshing, as TetGen does unless given `-M`: the edges between them (a triangulated
    /// surface's diagonals across its flat faces) are then not input edges, need not appear in
    /// the mesh and make no small angles; the output's boundary faces cover each merged facet
    /// but not necessarily the input triangles. Ignored with `keep_surface`. Default: `false`.
    pub merge_coplanar: bool,
    /// Print progress lines to standard error during long runs. Default: `false`.
    pub verbose: bool,
}

impl fmt::Debug for Options3 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Options3")
            .field("radius_edge", &self.radius_edge)
            .field("max_volume", &self.max_volume)
            .field("region_max_volume", &self.region_max_volume)
            .field("region_attributes", &self.region_attributes)
            .field("max_steiner", &self.max_steiner)
            .field("sizing", &self.sizing.as_ref().map(|_| "<fn>"))
            .field("keep_surface", &self.keep_surface)
            .field("merge_coplanar", &self.merge_coplanar)
            .field("verbose", &self.verbose)
            .finish()
    }
}

/// Meshes a PLC: conforming Delaunay tetrahedralization of the volume enclosed by the facets
/// (minus holes), refined to the options' radius-edge and volume bounds.
///
/// Returns an error naming the offending item for invalid input. When the Steiner cap is hit the
/// mesh is still returned (valid and conforming) with `complete == false`.
pub fn tetrahedralize(plc: &Plc, opts: &Options3) -> Result<TetMesh, Error> {
    catch_panic("", || {
        crate::input3d::check_plc(plc)?;
        check_options(opts)?;
        let merged = (opts.merge_coplanar && !opts.keep_surface)
            .then(|| coplanar::merge_coplanar_facets(plc))
            .flatten();
        plc::mesh_plc(merged.as_ref().unwrap_or(plc), opts)
    })
}

/// Delaunay tetrahedralization of a point set (TetGen without `-p`): the tetrahedra fill the
/// convex hull; there are no facets. Duplicate points are reported as errors.
pub fn delaunay3d(points: &[[f64; 3]]) -> Result<TetMesh, Error> {
    catch_panic("", || delaunay::delaunay(points))
}

/// Rejects option values that cannot work.
fn check_options(opts: &Options3) -> Result<(), Error> {
    if let Some(r) = opts.radius_edge {
        if !(r.is_finite() && r >= 1.0) {
            return Err(Error::InvalidOption(format!(
                "radius-edge bound {r} must be a number of at least 1.0"
            )));
        }
    }
    if let Some(v) = opts.max_volume {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::InvalidOption(format!(
                "maximum volume {v} must be a positive number"
            )));
        }
    }
    Ok(())
}
