//! The 3D mesher (paper §4): conforming Delaunay tetrahedralization of a PLC and Delaunay
//! refinement to a radius-edge bound and a maximum volume.
//!
//! Pipeline: validate the input; insert every input point into one Bowyer–Watson kernel
//! (`store.rs`); keep a 1D mesh per input edge and a 2D Delaunay mesh per facet, refined lazily
//! until each appears in the 3D mesh (work queue of Definition 4.1); classify exterior, holes
//! and regions by flooding up to facets; then remove skinny and oversized tetrahedra (Fig. 9),
//! then slivers (`plc/sliver.rs`), keeping the mesh Delaunay.

mod convex_hull;
mod coplanar;
mod delaunay;
mod facet_mesh;
mod features;
#[cfg(test)]
mod kernel_tests;
mod optimize;
mod order;
mod output;
mod plc;
#[cfg(test)]
pub(crate) mod plc_tests;
pub(crate) mod store;
pub(crate) mod surface;
mod validate;

use std::fmt;
use std::sync::Arc;

pub use coplanar::{snap_nearly_coplanar_facets, SnapReport};
pub use optimize::{DEFAULT_MAX_DIHEDRAL, DEFAULT_SCHEME, MAX_LEVEL};
pub use output::{TetMesh, TetStats, DIHEDRAL_BINS};
pub use plc::sliver::DEFAULT_MIN_DIHEDRAL;
pub use surface::{repair_surface, SurfaceRepair, SurfaceWarning};

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
    /// A progress callback, which may also cancel the run; see [`crate::progress`].
    /// Default: `None`.
    pub progress: Option<crate::progress::ProgressFn>,
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
    /// Minimum dihedral angle target in degrees (TetGen's `-q<ratio>/<angle>`), used with a
    /// radius-edge bound: after radius-edge refinement, tetrahedra with a dihedral angle below
    /// it (or above 180° minus it) are removed by inserting points near their circumcentres,
    /// so the mesh stays Delaunay (see the sliver module's docs). `None`:
    /// [`DEFAULT_MIN_DIHEDRAL`]; `Some(0.0)`: no sliver removal. Tetrahedra next to small
    /// input angles are exempt. Not applied with `keep_surface`. Default: `None`.
    pub min_dihedral: Option<f64>,
    /// Take the facets as a polygon surface mesh and repair it first, as
    /// [`repair_surface`] does (duplicate vertices merged, zero-area polygons and
    /// unreferenced vertices dropped, non-planar polygons triangulated); errors name the
    /// input's items. The mesh's vertices are then the kept input points in input order,
    /// then the Steiner points. The C API's `surface_input`; Rust callers who want the
    /// warnings and the vertex map call [`repair_surface`] themselves. Default: `false`.
    pub surface_input: bool,
    /// Mesh the convex hull of the input points (TetGen's `-c`): the hull's faces are added
    /// as facets with marker 0 (see the `convex_hull` module's docs), so the input facets and
    /// segments inside the hull stay in the mesh as internal constraints; hole and region
    /// seeds apply as usual. Default: `false`.
    pub convex_hull: bool,
    /// Maximum subface area per facet marker (TetGen's `facetconstraintlist`, `.var` files):
    /// every output face on a facet with that marker is split until its area is at most the
    /// bound. Bounds must be positive; the smallest applies when a marker is listed twice.
    /// Not applied with `keep_surface`. Default: empty.
    pub facet_max_area: Vec<(i32, f64)>,
    /// Maximum subsegment length per input edge given by its two endpoints, 0-based point
    /// indices (TetGen's `segmentconstraintlist`): the edge (a free segment or a facet polygon
    /// edge with exactly these endpoints) is split until every piece is at most the bound long.
    /// Bounds must be positive; pairs naming no input edge are ignored, as in TetGen. Not
    /// applied with `keep_surface`. Default: empty.
    pub segment_max_length: Vec<([u32; 2], f64)>,
    /// A relative tolerance for merging *nearly* coplanar neighbouring facets (TetGen's
    /// `-T<tol>`; TetGen's default is 1e-8), used only with `merge_coplanar` (and not with
    /// `keep_surface`). Facets that would be merged but for exact coplanarity are grouped when
    /// every vertex of each lies within `tol` times that facet's longest edge of the plane of
    /// the group's largest facet, and their vertices are moved exactly onto that plane first,
    /// so the boundary is then within the tolerance of the input, as TetGen's is, and the
    /// mesh's vertices are the moved points (see the `coplanar` module's docs, and
    /// [`snap_nearly_coplanar_facets`] for what moves). `None`: exact coplanarity only, the
    /// default: a flat tetrahedron between nearly coplanar facets is then for sliver removal
    /// to fix. Must be positive and at most [`MAX_COPLANAR_TOLERANCE`]. Default: `None`.
    pub coplanar_tolerance: Option<f64>,
    /// The facets are the boundary faces of a previous mesh (TetGen's `-r`; the `tetgen`
    /// switches set it): with `merge_coplanar`, neighbouring facets that are coplanar up to the
    /// rounding of that mesh's Steiner points are merged as exactly coplanar ones are (see the
    /// `coplanar` module's docs for the bound). A Steiner point on a slanted facet is rounded
    /// off its plane, so the faces of one flat side are not exactly coplanar; kept apart, the
    /// edges between them are input edges that cannot flip as the side is refined and must be
    /// split wherever a new point comes near. Should meshing the facets so merged end in an
    /// internal error (some real models' remeshes still do), the exactly merged facets are
    /// meshed instead. Default: `false`.
    pub remesh: bool,
    /// Mesh optimisation (TetGen's `-O<level>`): after meshing, `optimize_level` passes (0 to
    /// [`MAX_LEVEL`]) of flips and smoothing of interior Steiner vertices that improve the
    /// extreme dihedral angles and never make them worse; the mesh is then no longer Delaunay
    /// ([`TetMesh::optimized`]). Facets, segments, regions and input vertices are kept (see the
    /// optimize module's docs). 0: none, the mesh stays Delaunay. Default: 0.
    pub optimize_level: u32,
    /// The optimisation's operations (TetGen's `-O<level>/<scheme>`), bits: 1 flips, 2 vertex
    /// smoothing, 4 sliver splitting by new points (the Delaunay sliver removal, run before the
    /// flips and smoothing, also without `radius_edge`: it then aims at 180 minus
    /// `optimize_max_dihedral`). `None`:
    /// [`DEFAULT_SCHEME`] (7). Default: `None`.
    pub optimize_scheme: Option<u32>,
    /// The optimisation's maximum dihedral angle target in degrees (TetGen's `-o/<angle>`):
    /// tetrahedra with a dihedral angle above it or below 180° minus it are worked on. Must be
    /// above 0 and below 180. `None`: [`DEFAULT_MAX_DIHEDRAL`] (165). Default: `None`.
    pub optimize_max_dihedral: Option<f64>,
    /// Threads a run may use (so far for the exact check every 3D run ends with; the mesh and
    /// every message are the same for any count). `None`: the environment variable
    /// `IDMESH_THREADS`, else all cores ([`crate::threads::count`]). Must be at least 1.
    /// Default: `None`.
    pub threads: Option<usize>,
}

/// The largest [`Options3::coplanar_tolerance`] accepted: a fold of one hundredth of a
/// facet's size is a feature of the object, not noise.
pub const MAX_COPLANAR_TOLERANCE: f64 = 0.01;

impl fmt::Debug for Options3 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Options3")
            .field("radius_edge", &self.radius_edge)
            .field("max_volume", &self.max_volume)
            .field("region_max_volume", &self.region_max_volume)
            .field("region_attributes", &self.region_attributes)
            .field("max_steiner", &self.max_steiner)
            .field("sizing", &self.sizing.as_ref().map(|_| "<fn>"))
            .field("progress", &self.progress.as_ref().map(|_| "<fn>"))
            .field("keep_surface", &self.keep_surface)
            .field("merge_coplanar", &self.merge_coplanar)
            .field("verbose", &self.verbose)
            .field("min_dihedral", &self.min_dihedral)
            .field("surface_input", &self.surface_input)
            .field("convex_hull", &self.convex_hull)
            .field("facet_max_area", &self.facet_max_area)
            .field("segment_max_length", &self.segment_max_length)
            .field("coplanar_tolerance", &self.coplanar_tolerance)
            .field("remesh", &self.remesh)
            .field("optimize_level", &self.optimize_level)
            .field("optimize_scheme", &self.optimize_scheme)
            .field("optimize_max_dihedral", &self.optimize_max_dihedral)
            .field("threads", &self.threads)
            .finish()
    }
}

/// Meshes a PLC: conforming Delaunay tetrahedralization of the volume enclosed by the facets
/// (minus holes), refined to the options' radius-edge and volume bounds.
///
/// Returns an error naming the offending item for invalid input. When the Steiner cap is hit the
/// mesh is still returned (valid and conforming) with `complete == false`. With
/// [`Options3::progress`] set, the run reports to it and returns [`Error::Cancelled`] when told
/// to stop.
pub fn tetrahedralize(plc: &Plc, opts: &Options3) -> Result<TetMesh, Error> {
    let seeds = plc.holes.iter().chain(plc.regions.iter().map(|r| &r.point));
    let facet_holes = plc.facets.iter().flat_map(|f| f.holes.iter());
    if let Some(s) = crate::geometry::tiny_scale(plc.points.iter().chain(seeds).chain(facet_holes))
    {
        return tetrahedralize_scaled(plc, opts, s);
    }
    catch_panic("", || {
        if opts.surface_input {
            let r = repair_surface(plc)?;
            let opts = Options3 {
                surface_input: false,
                ..opts.clone()
            };
            return tetrahedralize(&r.plc, &opts).map_err(|e| r.error(e));
        }
        crate::progress::observe(opts.progress.as_ref(), || {
            use crate::progress::{stage, Stage};
            stage(Stage::Reading, || (0, plc.points.len() as u64))?;
            crate::input3d::check_plc(plc)?;
            check_options(opts)?;
            let hulled = if opts.convex_hull {
                let h = convex_hull::with_hull_facets(plc)?;
                crate::input3d::check_plc(&h).map_err(|e| {
                    Error::InvalidOption(format!(
                        "-c: the input with its convex hull's faces added is not a valid PLC \
                         (facets numbered from {} are hull faces): {e}",
                        plc.facets.len()
                    ))
                })?;
                Some(h)
            } else {
                None
            };
            let plc = hulled.as_ref().unwrap_or(plc);
            let merge = opts.merge_coplanar && !opts.keep_surface;
            let snapped = match opts.coplanar_tolerance {
                Some(tol) if merge => {
                    let (snapped, r) = coplanar::snap_nearly_coplanar(plc, tol);
                    if opts.verbose {
                        eprintln!(
                            "idmesh: -T{tol:e}: {} groups of {} nearly coplanar facets snapped \
                             onto their planes ({} vertices moved), {} groups kept as they are",
                            r.groups, r.facets, r.moved, r.refused
                        );
                    }
                    snapped
                }
                _ => None,
            };
            let plc = snapped.as_ref().unwrap_or(plc);
            let merged = merge
                .then(|| coplanar::merge_coplanar_facets(plc, opts.remesh))
                .flatten();
            let mut mesh = match plc::mesh_plc(merged.as_ref().unwrap_or(plc), opts) {
                // Facets merged up to rounding can still end a remesh in an internal error
                // that the exactly merged ones do not (a CAD rotor remeshed with
                // -rq1.414a0.0005: a point inside a merged facet in line with two of its
                // boundary vertices up to rounding makes a flat subface): the run is then made
                // again with the exact merge.
                Err(Error::Internal(e)) if opts.remesh && merge => {
                    if opts.verbose {
                        eprintln!(
                            "idmesh: -r: meshing the facets merged up to rounding failed ({e}); \
                             meshing with the exactly coplanar ones merged"
                        );
                    }
                    let exact = coplanar::merge_coplanar_facets(plc, false);
                    plc::mesh_plc(exact.as_ref().unwrap_or(plc), opts)?
                }
                other => other?,
            };
            if opts.optimize_level > 0 {
                // Reported in the Slivers stage; `mesh_plc` enters Output only without -O.
                stage(Stage::Slivers, || (0, 0))?;
                let c = optimize::optimize(
                    &mut mesh,
                    opts.optimize_level,
                    opts.optimize_scheme.unwrap_or(DEFAULT_SCHEME),
                    opts.optimize_max_dihedral.unwrap_or(DEFAULT_MAX_DIHEDRAL),
                )?;
                if opts.verbose {
                    eprintln!(
                        "optimisation: {} passes, {} 2-3, {} 3-2 and {} 4-4 flips, {} other edge \
                         removals, {} vertices moved",
                        c.passes, c.flips23, c.flips32, c.flips44, c.edge_removals, c.moves
                    );
                }
                stage(Stage::Output, || (0, mesh.tets.len() as u64))?;
            }
            validate::check_output(&mesh, crate::threads::resolve(opts.threads)?)?;
            Ok(mesh)
        })
    })
}

/// Meshes an input whose coordinates all lie below `2^-64` (see
/// [`crate::geometry::tiny_scale`]) scaled up by the power of two `s`, and scales the mesh
/// back: exactly, so input points come back as they were and every sign is the same as on
/// the scaled-up input (the exact insphere test underflows on such coordinates: a cube of
/// 1e-54 was returned with a vertex "inside" a tet's circumsphere). Sizes given with the
/// input (volumes, areas, lengths, the sizing callback) are scaled with it.
fn tetrahedralize_scaled(plc: &Plc, opts: &Options3, s: f64) -> Result<TetMesh, Error> {
    let up = |p: &mut [f64; 3]| *p = p.map(|x| x * s);
    let mut g = plc.clone();
    g.points.iter_mut().for_each(up);
    g.holes.iter_mut().for_each(up);
    for f in &mut g.facets {
        f.holes.iter_mut().for_each(up);
    }
    let s3 = s * s * s;
    for r in &mut g.regions {
        up(&mut r.point);
        r.max_volume = r.max_volume.map(|v| v * s3);
    }
    let mut o = opts.clone();
    o.max_volume = opts.max_volume.map(|v| v * s3);
    o.facet_max_area = opts
        .facet_max_area
        .iter()
        .map(|&(m, a)| (m, a * s * s))
        .collect();
    o.segment_max_length = opts
        .segment_max_length
        .iter()
        .map(|&(e, l)| (e, l * s))
        .collect();
    if let Some(f) = opts.sizing.clone() {
        let down = move |p: [f64; 3]| p.map(|x| x / s);
        o.sizing = Some(Arc::new(move |a, b, c, d, vol| {
            f(down(a), down(b), down(c), down(d), vol / s3)
        }));
    }
    let mut m = tetrahedralize(&g, &o)?;
    crate::geometry::scale_back(&mut m.vertices, &plc.points, s)?;
    Ok(m)
}

/// Delaunay tetrahedralization of a point set (TetGen without `-p`): the tetrahedra fill the
/// convex hull; there are no facets. Duplicate points are reported as errors. To watch its
/// progress (or cancel it), call it inside [`crate::progress::observe`].
pub fn delaunay3d(points: &[[f64; 3]]) -> Result<TetMesh, Error> {
    if let Some(s) = crate::geometry::tiny_scale(points.iter()) {
        // As in `tetrahedralize_scaled`: the insphere test underflows on such coordinates.
        let up: Vec<[f64; 3]> = points.iter().map(|p| p.map(|x| x * s)).collect();
        let mut m = delaunay3d(&up)?;
        crate::geometry::scale_back(&mut m.vertices, points, s)?;
        return Ok(m);
    }
    catch_panic("", || {
        let threads = crate::threads::count()?;
        delaunay::delaunay(points, |m| validate::check_output(m, threads))
    })
}

/// Rejects option values that cannot work.
fn check_options(opts: &Options3) -> Result<(), Error> {
    crate::threads::resolve(opts.threads)?;
    if let Some(r) = opts.radius_edge {
        if !(r.is_finite() && r >= 1.0) {
            return Err(Error::InvalidOption(format!(
                "radius-edge bound {r} must be a number of at least 1.0"
            )));
        }
    }
    if let Some(a) = opts.min_dihedral {
        if !(a.is_finite() && (0.0..=plc::sliver::MAX_MIN_DIHEDRAL).contains(&a)) {
            return Err(Error::InvalidOption(format!(
                "minimum dihedral angle {a} must be a number from 0 to {} degrees",
                plc::sliver::MAX_MIN_DIHEDRAL
            )));
        }
    }
    if let Some(&(m, a)) = opts
        .facet_max_area
        .iter()
        .find(|(_, a)| !(a.is_finite() && *a > 0.0))
    {
        return Err(Error::InvalidOption(format!(
            "maximum area {a} of facets with marker {m} must be a positive number"
        )));
    }
    if let Some(&([a, b], l)) = opts
        .segment_max_length
        .iter()
        .find(|(_, l)| !(l.is_finite() && *l > 0.0))
    {
        return Err(Error::InvalidOption(format!(
            "maximum length {l} of segment {a}-{b} must be a positive number"
        )));
    }
    if opts.optimize_level > MAX_LEVEL {
        return Err(Error::InvalidOption(format!(
            "optimisation level {} must be from 0 to {MAX_LEVEL}",
            opts.optimize_level
        )));
    }
    if let Some(s) = opts.optimize_scheme.filter(|&s| s > 7) {
        return Err(Error::InvalidOption(format!(
            "optimisation scheme {s} must be from 0 to 7 (bits: 1 flips, 2 smoothing, 4 \
             sliver splitting)"
        )));
    }
    if let Some(a) = opts.optimize_max_dihedral {
        if !(a.is_finite() && a > 0.0 && a < 180.0) {
            return Err(Error::InvalidOption(format!(
                "optimisation maximum dihedral angle {a} must be a number above 0 and below \
                 180 degrees"
            )));
        }
    }
    if let Some(t) = opts.coplanar_tolerance {
        if !(t.is_finite() && t > 0.0 && t <= MAX_COPLANAR_TOLERANCE) {
            return Err(Error::InvalidOption(format!(
                "coplanar tolerance (-T) {t} must be a number greater than 0 and at most \
                 {MAX_COPLANAR_TOLERANCE}"
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
