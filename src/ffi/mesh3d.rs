//! The 3D part of the C ABI (`idm_mesher3d_*`, declared in `include/idmesh.h`).
//!
//! A thin layer over [`crate::tetrahedralize`] and [`crate::delaunay3d`]: a handle collects the
//! PLC and the options, refine (or delaunay) runs the Rust mesher, and getters lend pointers
//! into the resulting [`TetMesh`]. Only what is 3D lives here (facets in CSR form, the
//! statistics); every body goes through the shared machinery of [`super::common`].

use std::ffi::c_void;
use std::mem::size_of;
use std::sync::Arc;

use super::common::{
    add_marked, change, check_index_room, check_out, counts, free_handle, guard, idm_progress_fn,
    idm_status, impl_handle, init_options, input_slice, lend, lend_plain, mesh_of, new_handle,
    positive, read_options, reject_nan, reserve, run, scaled, set_progress, steiner_cap_to_c,
    validate, CCallback, Failure, Handle, SizedOptions,
};
use crate::input3d::{Facet, Plc, Region3};
use crate::mesh3d::{delaunay3d, tetrahedralize, Options3, SizingFn3, TetMesh};
use crate::progress::observe;
use crate::switches::tetgen_extra::tetgen_constraints;

/// 3D meshing options. Fill it with `idm_options3d_default` first, then change what you need,
/// so that code keeps working if fields are ever appended. Booleans are `int32_t`: 0 is false,
/// anything else true.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct idm_options3d {
    /// The size of this struct as the caller was compiled: `sizeof(idm_options3d)`, set by
    /// `idm_options3d_default`. It lets a library and a caller built against different versions of
    /// the header exchange the struct safely (see `idm_options3d_default_sized`).
    pub struct_size: usize,
    /// Maximum radius-edge ratio (TetGen's `-q`); `<= 0` means no quality refinement. Must not
    /// be NaN; a positive value below 1 is rejected by refine. Default 0.
    pub radius_edge: f64,
    /// Global maximum tetrahedron volume (TetGen's `-a<volume>`); `<= 0` means none. Must not
    /// be NaN. Default 0.
    pub max_volume: f64,
    /// Apply each region's maximum volume (TetGen's `-a`). Default 0.
    pub region_max_volume: i32,
    /// Write each region's attribute to its tetrahedra (TetGen's `-A`). Default 0.
    pub region_attributes: i32,
    /// Maximum number of Steiner points (TetGen's `-S`); `< 0` means no cap. When the cap is
    /// reached refine returns `IDM_INCOMPLETE`. Default -1.
    pub max_steiner: i64,
    /// Print progress lines to standard error during long runs. Default 0.
    pub verbose: i32,
    /// Keep the input surface (TetGen's `-Y`): no Steiner points on input edges or facets;
    /// the boundary faces are the input's triangles (a polygon facet is triangulated on its
    /// own vertices). Interior Steiner points may be added where the surface needs them; the
    /// tetrahedra next to the surface are then not Delaunay, and quality and volume bounds
    /// are not met where meeting them would need a point on or next to the surface (see the
    /// Rust `Options3::keep_surface`). Default 0.
    pub keep_surface: i32,
    /// Minimum dihedral angle target, degrees (TetGen's `-q<ratio>/<angle>`), applied when
    /// `radius_edge > 0`: slivers (a dihedral angle below it or above 180 minus it) are removed
    /// by Delaunay refinement, so the mesh stays Delaunay; tetrahedra next to small input
    /// angles are exempt. 0 turns sliver removal off; must be from 0 to 70 (not NaN).
    /// Default 15 (`DEFAULT_MIN_DIHEDRAL` of the Rust library). Added in 0.3.0: a caller's
    /// older struct gets the default.
    pub min_dihedral: f64,
    /// Take the facets as a polygon surface mesh and repair it before meshing, as the README's
    /// "Surface input" says: exact duplicate points merged, zero-area polygons and points on
    /// no facet or segment dropped, non-planar polygons triangulated on their own vertices.
    /// The output vertices are then the kept input points in input order (coordinates
    /// unchanged), then the Steiner points; error indices name the input's items. Default 0.
    pub surface_input: i32,
    /// Mesh the convex hull of the points (TetGen's `-c`): the hull's faces are added as
    /// facets with marker 0, and the input's facets and segments inside the hull stay as
    /// internal constraints; hole and region seeds apply as usual. Default 0. Added after
    /// 0.2.0, like the four fields below: a caller's older struct gets the defaults.
    pub convex_hull: i32,
    /// Maximum subface areas per facet marker, as TetGen's `facetconstraintlist`:
    /// `num_facet_constraints` pairs (marker, maximum area) of doubles; every output face on a
    /// facet with that marker is split until its area is at most the bound. Markers must be
    /// whole numbers, areas positive. Copied by `idm_mesher3d_set_options`. Not applied with
    /// `keep_surface`. NULL when the count is 0. Default NULL.
    pub facet_constraints: *const f64,
    /// Number of pairs in `facet_constraints`. Default 0.
    pub num_facet_constraints: usize,
    /// Maximum subsegment lengths per input edge, as TetGen's `segmentconstraintlist`:
    /// `num_segment_constraints` triples (point a, point b, maximum length) of doubles with
    /// 0-based point indices; the input edge (free segment or facet polygon edge) with exactly
    /// these endpoints is split until every piece is at most the bound long (pairs naming no
    /// input edge are ignored, as in TetGen). Indices must be whole numbers, lengths positive.
    /// Copied by `idm_mesher3d_set_options`. NULL when the count is 0. Default NULL.
    pub segment_constraints: *const f64,
    /// Number of triples in `segment_constraints`. Default 0.
    pub num_segment_constraints: usize,
    /// Merge neighbouring facets with the same marker that are coplanar within this relative
    /// tolerance (TetGen's `-T<tol>`, whose default is 1e-8), exactly coplanar ones included:
    /// the vertices of nearly coplanar facets are moved exactly onto one plane (by at most
    /// about the tolerance times the facet's longest edge) and the shared edges are no longer
    /// input edges, so the output's vertices are the moved points (see the Rust
    /// `Options3::coplanar_tolerance`). Not with `keep_surface`. 0: no merging, coplanarity
    /// exact (the C API's default); must not be negative or NaN, and at most 0.01. Default 0.
    /// Appended after 0.2.0: a caller's older struct gets the default.
    pub coplanar_tolerance: f64,
    /// Mesh optimisation level (TetGen's `-O<level>`): 0 to 10 passes of flips and smoothing
    /// of interior Steiner vertices after meshing, which improve the extreme dihedral angles
    /// and never make them worse; the mesh is then no longer Delaunay (validate checks it
    /// without empty circumspheres). 0: none, the mesh stays Delaunay. Default 0. Added after
    /// 0.2.0, like the two fields below: a caller's older struct gets the defaults.
    pub optimize_level: i32,
    /// The optimisation's operations (TetGen's `-O<level>/<scheme>`), bits: 1 flips, 2 vertex
    /// smoothing, 4 sliver splitting by new points (idmesh's Delaunay sliver removal, run also
    /// without `radius_edge`, aiming at 180 minus `optimize_max_dihedral`); 0 to 7. Default 7.
    pub optimize_scheme: i32,
    /// The optimisation's maximum dihedral angle target, degrees (TetGen's `-o/<angle>`):
    /// tetrahedra with a dihedral angle above it or below 180 minus it are worked on. Above 0
    /// and below 180, not NaN. Default 165.
    pub optimize_max_dihedral: f64,
    /// Threads a run may use (so far for the exact check every run ends with; the mesh and
    /// every message are the same for any count). 0: the environment variable
    /// `IDMESH_THREADS`, else all cores. Default 0. Appended after 0.2.0: a caller's older
    /// struct gets the default.
    pub threads: usize,
}

/// Quality figures of the current mesh (see `idm_mesher3d_stats`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct idm_stats3d {
    /// Total volume of the tetrahedra.
    pub volume: f64,
    /// Largest circumradius-to-shortest-edge ratio (0 for an empty mesh).
    pub max_radius_edge: f64,
    /// Smallest dihedral angle, degrees (0 for an empty mesh).
    pub min_dihedral: f64,
    /// Largest dihedral angle, degrees (0 for an empty mesh).
    pub max_dihedral: f64,
    /// Number of Steiner points the mesher added.
    pub steiner_points: usize,
    /// 1 when every quality and size bound was met; 0 when refinement stopped at the Steiner
    /// point cap (refine then returned `IDM_INCOMPLETE`).
    pub complete: i32,
    /// Number of tetrahedra whose smallest dihedral angle is below 5 degrees (appended after
    /// 0.2.0: filled when the caller's struct has room, see `idm_mesher3d_stats`).
    pub tets_below_5: usize,
    /// Number of tetrahedra whose smallest dihedral angle is below 10 degrees.
    pub tets_below_10: usize,
    /// Number of tetrahedra whose smallest dihedral angle is below 15 degrees.
    pub tets_below_15: usize,
}

/// The size of `idm_stats3d` in 0.2.0 (it ended with `complete`): what the plain
/// `idm_mesher3d_stats` symbol writes, for programs built against that header.
const STATS3D_BASELINE: usize = std::mem::offset_of!(idm_stats3d, tets_below_5);

/// A user sizing test (TetGen's `tetunsuitable`): returns nonzero when the tetrahedron with
/// corners `a`, `b`, `c`, `d` (each pointing to 3 doubles, valid only during the call) and
/// volume `volume` is too large and must be split.
///
/// It is called only during `idm_mesher3d_refine` on the handle it was set on, from the thread
/// that called refine, and `user` is passed through untouched. It must be deterministic, must
/// not call back into the same handle, and must return normally (no C++ exception, no
/// `longjmp`).
pub type idm_sizing3d_fn = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        a: *const f64,
        b: *const f64,
        c: *const f64,
        d: *const f64,
        volume: f64,
    ) -> i32,
>;

/// An opaque 3D mesher: the input PLC and options, and the output of the last successful
/// refine or delaunay call. Create with `idm_mesher3d_new`, destroy with `idm_mesher3d_free`.
/// A handle may be moved between threads, but must not be used by two threads at once;
/// distinct handles are fully independent.
pub struct idm_mesher3d {
    /// The input collected so far (markers always have one entry per item: the default 0
    /// fills in for calls made without markers).
    pub(crate) plc: Plc,
    /// The options, including the sizing callback.
    pub(crate) opts: Options3,
    /// The output of the last successful (or `IDM_INCOMPLETE`) refine or delaunay call;
    /// dropped by any change of input or options, so getters never describe other input.
    pub(crate) mesh: Option<TetMesh>,
}

impl_handle!(
    idm_mesher3d { plc, "idm_mesher3d_refine or idm_mesher3d_delaunay" },
    TetMesh,
    |_h, mesh| mesh.validate().map_err(|e| e.to_string())
);

/// The C sizing function of `idm_sizing3d_fn`.
type SizingFn3C =
    unsafe extern "C" fn(*mut c_void, *const f64, *const f64, *const f64, *const f64, f64) -> i32;

impl CCallback<SizingFn3C> {
    /// Calls the C function. A method (rather than field accesses in the closure) so that the
    /// closure captures the whole `Send + Sync` struct, not its bare raw pointer.
    fn call(&self, a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], volume: f64) -> bool {
        let [a, b, c, d] = [a.as_ptr(), b.as_ptr(), c.as_ptr(), d.as_ptr()];
        // SAFETY: the pointers refer to arguments that outlive the call; the function pointer
        // and `user` are the caller's contract (see `idm_mesher3d_set_sizing`).
        unsafe { (self.f)(self.user, a, b, c, d, volume) != 0 }
    }
}

/// Fills `out` with the default options (the same defaults as the Rust `Options3::default()`),
/// `struct_size` included. NULL is a no-op. Through the header this is a macro that calls
/// `idm_options3d_default_sized` with the caller's `sizeof(idm_options3d)`, so that a
/// program built against an older, smaller struct keeps working with a newer library.
///
/// # Safety
/// `out` must be NULL or valid for writing an `idm_options3d`.
#[no_mangle]
pub unsafe extern "C" fn idm_options3d_default(out: *mut idm_options3d) {
    // SAFETY: the caller's contract, forwarded.
    unsafe { init_options(out, size_of::<idm_options3d>()) }
}

/// `idm_options3d_default` for a caller's struct of `struct_size` bytes (the header's
/// `idm_options3d_default` macro passes `sizeof(idm_options3d)`): the fields this library knows
/// get their defaults and `struct_size` gets `struct_size`; bytes beyond them (fields of a
/// newer header) are zeroed. NULL, or a `struct_size` smaller than any version's struct, is
/// a no-op.
///
/// # Safety
/// `out` must be NULL or valid for writing `struct_size` bytes.
#[no_mangle]
pub unsafe extern "C" fn idm_options3d_default_sized(out: *mut idm_options3d, struct_size: usize) {
    // SAFETY: the caller's contract, forwarded.
    unsafe { init_options(out, struct_size) }
}

// SAFETY: `#[repr(C)]`, `struct_size: usize` first, only integer, float and raw pointer fields
// (every bit pattern valid; the pointers are checked and read only by `set_options`).
unsafe impl SizedOptions for idm_options3d {
    /// The 0.2.0 struct ended before `min_dihedral`.
    const BASELINE: usize = std::mem::offset_of!(idm_options3d, min_dihedral);
    const NAME: &'static str = "idm_options3d";

    fn defaults() -> Self {
        let d = Options3::default();
        idm_options3d {
            struct_size: size_of::<idm_options3d>(),
            radius_edge: d.radius_edge.unwrap_or(0.0),
            max_volume: d.max_volume.unwrap_or(0.0),
            region_max_volume: d.region_max_volume.into(),
            region_attributes: d.region_attributes.into(),
            max_steiner: steiner_cap_to_c(d.max_steiner),
            verbose: d.verbose.into(),
            keep_surface: d.keep_surface.into(),
            min_dihedral: d
                .min_dihedral
                .unwrap_or(crate::mesh3d::DEFAULT_MIN_DIHEDRAL),
            surface_input: d.surface_input.into(),
            convex_hull: d.convex_hull.into(),
            facet_constraints: std::ptr::null(),
            num_facet_constraints: 0,
            segment_constraints: std::ptr::null(),
            num_segment_constraints: 0,
            coplanar_tolerance: d.coplanar_tolerance.unwrap_or(0.0),
            optimize_level: d.optimize_level as i32,
            optimize_scheme: d.optimize_scheme.unwrap_or(crate::mesh3d::DEFAULT_SCHEME) as i32,
            optimize_max_dihedral: d
                .optimize_max_dihedral
                .unwrap_or(crate::mesh3d::DEFAULT_MAX_DIHEDRAL),
            threads: d.threads.unwrap_or(0),
        }
    }
}

/// Creates an empty 3D mesher with default options and stores it in `*out`.
///
/// # Safety
/// `out` must be NULL (an error) or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_new(out: *mut *mut idm_mesher3d) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { new_handle(out) }
}

/// Destroys a 3D mesher and everything it lent out. NULL is a no-op.
///
/// # Safety
/// `m` must be NULL or a handle from `idm_mesher3d_new` not freed before and not in use.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_free(m: *mut idm_mesher3d) {
    // SAFETY: the caller's contract, forwarded.
    unsafe { free_handle(m) }
}

/// Appends `count` points: `xyz` holds 3*count doubles (x0, y0, z0, x1, ...). `markers` is
/// NULL (all 0) or holds `count` markers. Points are numbered 0, 1, ... across all calls.
///
/// # Safety
/// `m` must be a live handle; `xyz` and (when not NULL) `markers` must hold the stated number
/// of values.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_add_points(
    m: *mut idm_mesher3d,
    xyz: *const f64,
    count: usize,
    markers: *const i32,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        add_marked(m, xyz, count, markers, 0, ["xyz", "points"], |m| {
            (&mut m.plc.points, &mut m.plc.point_markers)
        })
    }
}

/// Appends `count` free-standing segments (input edges): `ab` holds 2*count 0-based point
/// indices. Facet loop edges need not be repeated here. Indices may refer to points added
/// later; they are checked by refine. `markers` is NULL (all 0) or holds `count` markers.
///
/// # Safety
/// `m` must be a live handle; `ab` and (when not NULL) `markers` must hold the stated number
/// of values.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_add_segments(
    m: *mut idm_mesher3d,
    ab: *const u32,
    count: usize,
    markers: *const i32,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        add_marked(m, ab, count, markers, 0, ["ab", "segments"], |m| {
            (&mut m.plc.segments, &mut m.plc.segment_markers)
        })
    }
}

/// Checks the loop offsets of facet `facet` (CSR form: `num_loops + 1` entries, the first 0,
/// each loop non-empty) and returns the loops as index ranges.
fn loop_ranges(offsets: &[usize], facet: usize) -> Result<Vec<std::ops::Range<usize>>, Failure> {
    if offsets[0] != 0 {
        return Err(Failure::invalid(format!(
            "facet {facet}: loop_offsets[0] is {}, must be 0",
            offsets[0]
        )));
    }
    let mut ranges = Vec::new();
    reserve(&mut ranges, offsets.len() - 1, "facet loops")?;
    for (k, w) in offsets.windows(2).enumerate() {
        if w[1] <= w[0] {
            return Err(Failure::invalid(format!(
                "facet {facet}: loop {k} is empty or reversed (loop_offsets[{k}] = {}, \
                 loop_offsets[{}] = {})",
                w[0],
                k + 1,
                w[1]
            )));
        }
        ranges.push(w[0]..w[1]);
    }
    Ok(ranges)
}

/// Appends one planar facet. Its `num_loops` polygons are given in CSR form: `loop_offsets`
/// holds `num_loops + 1` increasing offsets starting at 0, and polygon k is
/// `indices[loop_offsets[k] .. loop_offsets[k+1]]` (so `indices` holds
/// `loop_offsets[num_loops]` point indices). A polygon of three or more vertices is a closed
/// loop; of two, a segment lying in the facet; of one, an isolated point of the facet.
/// `holes_xyz` holds 3*num_holes doubles: hole seeds in the facet's plane, which decide the
/// loops that bound holes (as TetGen). `marker` is written to the output faces in the facet.
/// Point indices may refer to points added later; they and the facet's planarity are checked
/// by refine. Facets are numbered 0, 1, ... in the order added.
///
/// # Safety
/// `m` must be a live handle; the arrays must hold the stated number of values.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_add_facet(
    m: *mut idm_mesher3d,
    indices: *const u32,
    loop_offsets: *const usize,
    num_loops: usize,
    holes_xyz: *const f64,
    num_holes: usize,
    marker: i32,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |m| {
            let facet = m.plc.facets.len();
            if num_loops == 0 {
                return Err(Failure::invalid(format!(
                    "facet {facet}: num_loops is 0 (a facet needs at least one polygon)"
                )));
            }
            let num_offsets = num_loops.checked_add(1).ok_or_else(|| {
                Failure::invalid(format!("`num_loops` = {num_loops} is too large"))
            })?;
            let offsets = input_slice(loop_offsets, num_offsets, "loop_offsets")?;
            let ranges = loop_ranges(offsets, facet)?;
            let indices = input_slice(indices, offsets[num_loops], "indices")?;
            let holes = input_slice(holes_xyz, scaled(num_holes, 3, "num_holes")?, "holes_xyz")?;
            check_index_room(facet, 1, "facets")?;
            let mut polygons: Vec<Vec<u32>> = Vec::new();
            reserve(&mut polygons, ranges.len(), "facet loops")?;
            for r in ranges {
                let mut poly = Vec::new();
                reserve(&mut poly, r.len(), "facet loop indices")?;
                poly.extend_from_slice(&indices[r]);
                polygons.push(poly);
            }
            let mut hole_seeds = Vec::new();
            reserve(&mut hole_seeds, num_holes, "facet holes")?;
            hole_seeds.extend(holes.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
            reserve(&mut m.plc.facets, 1, "facets")?;
            m.plc.facets.push(Facet {
                polygons,
                holes: hole_seeds,
                marker,
            });
            Ok(())
        })
    }
}

/// Appends one volume hole seed: `xyz` holds 3 doubles. The tetrahedra reachable from the seed
/// without crossing a facet are removed.
///
/// # Safety
/// `m` must be a live handle; `xyz` must hold 3 doubles.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_add_hole(
    m: *mut idm_mesher3d,
    xyz: *const f64,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |m| {
            let p = input_slice(xyz, 3, "xyz")?;
            reserve(&mut m.plc.holes, 1, "holes")?;
            m.plc.holes.push([p[0], p[1], p[2]]);
            Ok(())
        })
    }
}

/// Appends one region seed: `xyz` holds 3 doubles (a point strictly inside the region),
/// `attribute` is written to the region's tetrahedra with `region_attributes`, and
/// `max_volume` bounds their volume with `region_max_volume`; `<= 0` means no regional bound
/// (NaN is rejected, as everywhere in the API). Regions are numbered 0, 1, ... in the order
/// added.
///
/// # Safety
/// `m` must be a live handle; `xyz` must hold 3 doubles.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_add_region(
    m: *mut idm_mesher3d,
    xyz: *const f64,
    attribute: f64,
    max_volume: f64,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |m| {
            let p = input_slice(xyz, 3, "xyz")?;
            if max_volume.is_nan() {
                return Err(Failure::invalid(format!(
                    "max_volume of region {} is NaN",
                    m.plc.regions.len()
                )));
            }
            reserve(&mut m.plc.regions, 1, "regions")?;
            m.plc.regions.push(Region3 {
                point: [p[0], p[1], p[2]],
                attribute,
                max_volume: positive(max_volume),
            });
            Ok(())
        })
    }
}

/// Replaces the options (the sizing and progress callbacks are kept; see
/// `idm_mesher3d_set_sizing` and `idm_mesher3d_set_progress`). Value
/// ranges are checked by refine, except NaN radius-edge or volume, rejected here.
///
/// # Safety
/// `m` must be a live handle; `opts` must point to an `idm_options3d`.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_set_options(
    m: *mut idm_mesher3d,
    opts: *const idm_options3d,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |m| {
            let o = read_options(opts)?;
            reject_nan(&[
                ("radius_edge", o.radius_edge),
                ("max_volume", o.max_volume),
                ("min_dihedral", o.min_dihedral),
                ("coplanar_tolerance", o.coplanar_tolerance),
                ("optimize_max_dihedral", o.optimize_max_dihedral),
            ])?;
            if o.coplanar_tolerance < 0.0 {
                return Err(Failure::invalid(format!(
                    "option coplanar_tolerance {} is negative (0: no merging)",
                    o.coplanar_tolerance
                )));
            }
            let (optimize_level, optimize_scheme) =
                optimize_ints(o.optimize_level, o.optimize_scheme)?;
            let facets = input_slice(
                o.facet_constraints,
                scaled(o.num_facet_constraints, 2, "num_facet_constraints")?,
                "opts.facet_constraints",
            )?;
            let segments = input_slice(
                o.segment_constraints,
                scaled(o.num_segment_constraints, 3, "num_segment_constraints")?,
                "opts.segment_constraints",
            )?;
            let bounds = tetgen_constraints(facets, segments, 0).map_err(Failure::invalid)?;
            m.opts = Options3 {
                radius_edge: positive(o.radius_edge),
                max_volume: positive(o.max_volume),
                region_max_volume: o.region_max_volume != 0,
                region_attributes: o.region_attributes != 0,
                max_steiner: u64::try_from(o.max_steiner).ok(),
                sizing: m.opts.sizing.take(),
                progress: m.opts.progress.take(),
                keep_surface: o.keep_surface != 0,
                merge_coplanar: o.coplanar_tolerance > 0.0,
                coplanar_tolerance: positive(o.coplanar_tolerance),
                // The C API's meshers take a PLC; remeshing is the TetGen interface's `-r`.
                remesh: false,
                verbose: o.verbose != 0,
                min_dihedral: Some(o.min_dihedral),
                surface_input: o.surface_input != 0,
                convex_hull: o.convex_hull != 0,
                facet_max_area: bounds.facet_max_area,
                segment_max_length: bounds.segment_max_length,
                optimize_level,
                optimize_scheme: Some(optimize_scheme),
                optimize_max_dihedral: Some(o.optimize_max_dihedral),
                threads: (o.threads != 0).then_some(o.threads),
            };
            Ok(())
        })
    }
}

/// The optimisation level and scheme of the C structs as the Rust options take them: negative
/// values are refused here, too large ones by refine (`Options3`'s check).
pub(crate) fn optimize_ints(level: i32, scheme: i32) -> Result<(u32, u32), Failure> {
    let ok = |v: i32, name: &str, max: u32| {
        u32::try_from(v)
            .map_err(|_| Failure::invalid(format!("{name} {v} must be from 0 to {max}")))
    };
    Ok((
        ok(level, "optimize_level", crate::mesh3d::MAX_LEVEL)?,
        ok(scheme, "optimize_scheme", 7)?,
    ))
}

/// Sets the user sizing test (see `idm_sizing3d_fn`); `fn` NULL clears it (`user` is then
/// ignored). `user` is stored, never dereferenced by the library, and handed to every call of
/// `fn`; it must stay valid, and be usable from whichever thread calls refine, until the
/// sizing test is cleared or the handle freed.
///
/// # Safety
/// `m` must be a live handle; `fn` must be NULL or a function with the `idm_sizing3d_fn`
/// contract.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_set_sizing(
    m: *mut idm_mesher3d,
    r#fn: idm_sizing3d_fn,
    user: *mut c_void,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        change(m, |m| {
            m.opts.sizing = r#fn.map(|f| {
                let c = CCallback { f, user };
                Arc::new(move |a, b, c3, d, volume| c.call(a, b, c3, d, volume)) as SizingFn3
            });
            Ok(())
        })
    }
}

/// Sets the progress callback (see `idm_progress_fn`), which also lets the caller cancel a
/// refine or delaunay call; `fn` NULL clears it (`user` is then ignored). `user` is stored, never dereferenced
/// by the library, and handed to every call of `fn`; it must stay valid, and be usable from
/// whichever thread calls refine, until the callback is cleared or the handle freed. The
/// current mesh, if any, is kept.
///
/// # Safety
/// `m` must be a live handle; `fn` must be NULL or a function with the `idm_progress_fn`
/// contract.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_set_progress(
    m: *mut idm_mesher3d,
    r#fn: idm_progress_fn,
    user: *mut c_void,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { set_progress(m, r#fn, user, |h, p| h.opts.progress = p) }
}

/// Meshes the PLC with the current options (TetGen's `-p`), replacing any previous mesh.
/// Returns `IDM_OK`, `IDM_INCOMPLETE` (Steiner cap reached; the mesh is readable and valid;
/// the message says so), `IDM_CANCELLED` (the progress callback asked to stop) or an error;
/// on `IDM_CANCELLED` or an error there is no mesh. The input is kept either way.
///
/// # Safety
/// `m` must be a live handle.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_refine(m: *mut idm_mesher3d) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { run(m, true, |h| tetrahedralize(&h.plc, &h.opts)) }
}

/// Delaunay tetrahedralization of the points added so far (TetGen without `-p`), replacing
/// any previous mesh: the tetrahedra fill the convex hull, the faces are the hull faces
/// (marker 0) and vertex i keeps input point i's marker. Segments, facets, holes, regions and
/// options are ignored, except the progress callback. Returns `IDM_OK`, `IDM_CANCELLED` or an
/// error (then there is no mesh).
///
/// # Safety
/// `m` must be a live handle.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_delaunay(m: *mut idm_mesher3d) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        run(m, false, |h| {
            let mut mesh = observe(h.opts.progress.as_ref(), || delaunay3d(&h.plc.points))?;
            // `delaunay3d` sees coordinates only; the markers are the handle's to restore, as
            // TetGen keeps the .node markers.
            for (dst, &src) in mesh.vertex_markers.iter_mut().zip(&h.plc.point_markers) {
                *dst = src;
            }
            Ok(mesh)
        })
    }
}

/// The output sizes: vertices, tetrahedra, subfaces and subsegments. Each out-pointer may be
/// NULL when that number is not wanted.
///
/// # Safety
/// `m` must be a live handle; each out-pointer NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_counts(
    m: *const idm_mesher3d,
    num_vertices: *mut usize,
    num_tets: *mut usize,
    num_faces: *mut usize,
    num_edges: *mut usize,
) -> idm_status {
    let outs = [
        (num_vertices, "num_vertices"),
        (num_tets, "num_tets"),
        (num_faces, "num_faces"),
        (num_edges, "num_edges"),
    ];
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        counts(m, outs, |mesh| {
            [
                mesh.vertices.len(),
                mesh.tets.len(),
                mesh.faces.len(),
                mesh.edges.len(),
            ]
        })
    }
}

/// Lends the vertex coordinates: `*xyz` gets 3*count doubles, `*count` the number of vertices.
/// Vertex i < (number of input points) is input point i, even when no tetrahedron uses it.
///
/// # Safety
/// `m` must be a live handle; `xyz` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_vertices(
    m: *const idm_mesher3d,
    xyz: *mut *const f64,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, xyz, count, "xyz", |mesh| &mesh.vertices) }
}

/// Lends one marker per vertex (`*count` = number of vertices): the input marker for input
/// points, the facet's or segment's marker for Steiner points on one, 0 otherwise.
///
/// # Safety
/// `m` must be a live handle; `markers` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_vertex_markers(
    m: *const idm_mesher3d,
    markers: *mut *const i32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, markers, count, "markers", |mesh| &mesh.vertex_markers) }
}

/// Lends the tetrahedra: `*abcd` gets 4*count vertex indices, each tetrahedron positively
/// oriented as in TetGen (det[b - a, c - a, d - a] > 0).
///
/// # Safety
/// `m` must be a live handle; `abcd` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_tets(
    m: *const idm_mesher3d,
    abcd: *mut *const u32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, abcd, count, "abcd", |mesh| &mesh.tets) }
}

/// Lends the neighbours: `*nbr` gets 4*count tetrahedron indices; entry 4t+i is the
/// tetrahedron across the face opposite corner i of tetrahedron t, or `IDM_NONE` on the
/// boundary of the meshed volume.
///
/// # Safety
/// `m` must be a live handle; `nbr` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_neighbors(
    m: *const idm_mesher3d,
    nbr: *mut *const u32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, nbr, count, "nbr", |mesh| &mesh.neighbors) }
}

/// Lends one regional attribute per tetrahedron (0 for tetrahedra in no region). `*count` is
/// 0 (and `*attr` NULL) unless the `region_attributes` option was set.
///
/// # Safety
/// `m` must be a live handle; `attr` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_tet_attributes(
    m: *const idm_mesher3d,
    attr: *mut *const f64,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, attr, count, "attr", |mesh| &mesh.tet_attributes) }
}

/// Lends the subfaces (boundary faces and faces lying in input facets): `*abc` gets 3*count
/// vertex indices and `*markers` (which may be NULL when not wanted) one marker per subface,
/// inherited from its facet (0 for the hull faces of `idm_mesher3d_delaunay`).
///
/// # Safety
/// `m` must be a live handle; `abc` and `count` valid for a write, `markers` NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_faces(
    m: *const idm_mesher3d,
    abc: *mut *const u32,
    markers: *mut *const i32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        lend(m, abc, markers, count, "abc", |mesh| {
            (&mesh.faces, &mesh.face_markers)
        })
    }
}

/// Lends the subsegments (every input segment and facet loop edge is a union of them): `*ab`
/// gets 2*count vertex indices and `*markers` (which may be NULL when not wanted) one marker
/// per subsegment.
///
/// # Safety
/// `m` must be a live handle; `ab` and `count` valid for a write, `markers` NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_edges(
    m: *const idm_mesher3d,
    ab: *mut *const u32,
    markers: *mut *const i32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        lend(m, ab, markers, count, "ab", |mesh| {
            (&mesh.edges, &mesh.edge_markers)
        })
    }
}

/// Computes the quality figures of the mesh into `*out` (one pass over the tetrahedra), with
/// its Steiner point count and complete flag. Through the header this is a macro that calls
/// `idm_mesher3d_stats_sized` with the caller's `sizeof(idm_stats3d)`; the function itself
/// (for programs built against 0.2.0) writes only the fields up to `complete`.
///
/// # Safety
/// `m` must be a live handle; `out` valid for writing the fields up to `complete`.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_stats(
    m: *const idm_mesher3d,
    out: *mut idm_stats3d,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { idm_mesher3d_stats_sized(m, out, STATS3D_BASELINE) }
}

/// `idm_mesher3d_stats` for a caller's struct of `struct_size` bytes (the header's
/// `idm_mesher3d_stats` macro passes `sizeof(idm_stats3d)`): the fields that fit are written,
/// bytes beyond this library's struct (fields of a newer header) are zeroed. A `struct_size`
/// smaller than 0.2.0's struct is `IDM_ERR_INVALID_ARGUMENT`.
///
/// # Safety
/// `m` must be a live handle; `out` valid for writing `struct_size` bytes.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_stats_sized(
    m: *const idm_mesher3d,
    out: *mut idm_stats3d,
    struct_size: usize,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let mesh = unsafe { mesh_of(m) }?;
        check_out(out, "out")?;
        if struct_size < STATS3D_BASELINE || struct_size > isize::MAX as usize {
            return Err(Failure::invalid(format!(
                "struct_size is {struct_size}, not the size of an idm_stats3d of any version \
                 (this library's is {})",
                size_of::<idm_stats3d>()
            )));
        }
        let s = mesh.stats();
        let value = idm_stats3d {
            volume: s.volume,
            max_radius_edge: s.max_radius_edge,
            min_dihedral: s.min_dihedral,
            max_dihedral: s.max_dihedral,
            steiner_points: mesh.steiner_points,
            complete: mesh.complete.into(),
            tets_below_5: s.tets_below[0],
            tets_below_10: s.tets_below[1],
            tets_below_15: s.tets_below[2],
        };
        let known = struct_size.min(size_of::<idm_stats3d>());
        // SAFETY: `out` is valid for `struct_size` bytes (the caller's contract), `value` for
        // its own size; they do not overlap.
        unsafe {
            let dst = out.cast::<u8>();
            std::ptr::copy_nonoverlapping((&value as *const idm_stats3d).cast::<u8>(), dst, known);
            std::ptr::write_bytes(dst.add(known), 0, struct_size - known);
        }
        Ok(())
    })
}

/// Checks the output mesh invariants exactly (positive orientation, neighbour symmetry, empty
/// circumspheres, subfaces present as faces). `IDM_OK`, or `IDM_ERR_INTERNAL` with a message
/// naming the first violation (a bug).
///
/// # Safety
/// `m` must be a live handle.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_validate(m: *const idm_mesher3d) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { validate(m) }
}

#[cfg(test)]
mod tests {
    use super::super::common::testing::{last_error, TestHandle};
    use super::*;
    use crate::error::Error;
    use crate::predicates::orient3d;
    use crate::NONE;

    use idm_status::*;

    /// A fresh handle, freed on drop.
    type Handle = TestHandle<idm_mesher3d>;

    /// The unit cube: corners 0-3 at z = 0 and 4-7 at z = 1 (markers 10 + index), six square
    /// facets with markers 1..=6; the top facet carries a segment and a point of the facet
    /// (the in-facet polygons of two and one vertices), with extra points 8-10.
    fn cube() -> Plc {
        let mut points = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ];
        points.extend([[0.25, 0.5, 1.0], [0.75, 0.5, 1.0], [0.5, 0.25, 1.0]]);
        let loops: [[u32; 4]; 6] = [
            [0, 3, 2, 1],
            [4, 5, 6, 7],
            [0, 1, 5, 4],
            [1, 2, 6, 5],
            [2, 3, 7, 6],
            [3, 0, 4, 7],
        ];
        let mut facets: Vec<Facet> = loops
            .iter()
            .zip(1..)
            .map(|(l, marker)| Facet {
                polygons: vec![l.to_vec()],
                holes: Vec::new(),
                marker,
            })
            .collect();
        facets[1].polygons.push(vec![8, 9]);
        facets[1].polygons.push(vec![10]);
        Plc {
            point_markers: (10..10 + points.len() as i32).collect(),
            points,
            ..Plc::default()
        }
        .with(facets)
    }

    /// Builder sugar for the fixtures.
    trait With {
        fn with(self, facets: Vec<Facet>) -> Plc;
    }

    impl With for Plc {
        fn with(mut self, facets: Vec<Facet>) -> Plc {
            self.facets = facets;
            self
        }
    }

    /// Loads `p` into the handle through the C entry points (facets in CSR form).
    fn load(m: &Handle, p: &Plc) {
        let xyz: Vec<f64> = p.points.iter().flatten().copied().collect();
        let ab: Vec<u32> = p.segments.iter().flatten().copied().collect();
        let pmk = (!p.point_markers.is_empty()).then_some(p.point_markers.as_ptr());
        let smk = (!p.segment_markers.is_empty()).then_some(p.segment_markers.as_ptr());
        unsafe {
            assert_eq!(
                idm_mesher3d_add_points(
                    m.0,
                    xyz.as_ptr(),
                    p.points.len(),
                    pmk.unwrap_or(std::ptr::null())
                ),
                IDM_OK
            );
            assert_eq!(
                idm_mesher3d_add_segments(
                    m.0,
                    ab.as_ptr(),
                    p.segments.len(),
                    smk.unwrap_or(std::ptr::null())
                ),
                IDM_OK
            );
            for f in &p.facets {
                let (indices, offsets) = csr(&f.polygons);
                let holes: Vec<f64> = f.holes.iter().flatten().copied().collect();
                assert_eq!(
                    idm_mesher3d_add_facet(
                        m.0,
                        indices.as_ptr(),
                        offsets.as_ptr(),
                        f.polygons.len(),
                        holes.as_ptr(),
                        f.holes.len(),
                        f.marker
                    ),
                    IDM_OK,
                    "{}",
                    last_error()
                );
            }
            for h in &p.holes {
                assert_eq!(idm_mesher3d_add_hole(m.0, h.as_ptr()), IDM_OK);
            }
            for r in &p.regions {
                let v = r.max_volume.unwrap_or(0.0);
                assert_eq!(
                    idm_mesher3d_add_region(m.0, r.point.as_ptr(), r.attribute, v),
                    IDM_OK
                );
            }
        }
    }

    /// Polygons as (indices, offsets) in the CSR form of `idm_mesher3d_add_facet`.
    fn csr(polygons: &[Vec<u32>]) -> (Vec<u32>, Vec<usize>) {
        let mut offsets = vec![0];
        for p in polygons {
            offsets.push(offsets.last().unwrap() + p.len());
        }
        (polygons.concat(), offsets)
    }

    fn options(radius_edge: f64, max_volume: f64) -> idm_options3d {
        let mut o = std::mem::MaybeUninit::<idm_options3d>::uninit();
        unsafe { idm_options3d_default(o.as_mut_ptr()) };
        let mut o = unsafe { o.assume_init() };
        o.radius_edge = radius_edge;
        o.max_volume = max_volume;
        o
    }

    /// Copies `n` elements lent at `p`; an empty array must be lent as NULL.
    unsafe fn arr<T: Copy>(p: *const T, n: usize) -> Vec<T> {
        if n == 0 {
            assert!(p.is_null(), "an empty array must be lent as NULL");
            Vec::new()
        } else {
            unsafe { std::slice::from_raw_parts(p, n) }.to_vec()
        }
    }

    fn chunks<const K: usize, T: Copy + Default>(v: Vec<T>) -> Vec<[T; K]> {
        v.chunks_exact(K)
            .map(|c| std::array::from_fn(|i| c[i]))
            .collect()
    }

    /// Reads the whole output of the handle back into a `TetMesh` through the getters (the
    /// fields the C API exposes; `num_input_vertices` is copied from the input).
    fn read_back(m: &Handle) -> TetMesh {
        let mut out = TetMesh::default();
        unsafe {
            let (mut nv, mut nt, mut nf, mut ne) = (0usize, 0usize, 0usize, 0usize);
            assert_eq!(
                idm_mesher3d_counts(m.0, &mut nv, &mut nt, &mut nf, &mut ne),
                IDM_OK
            );
            let mut n = 0usize;
            let mut pf: *const f64 = std::ptr::null();
            let mut pu: *const u32 = std::ptr::null();
            let mut pi: *const i32 = std::ptr::null();
            assert_eq!(idm_mesher3d_vertices(m.0, &mut pf, &mut n), IDM_OK);
            assert_eq!(n, nv);
            out.vertices = chunks(arr(pf, 3 * n));
            assert_eq!(idm_mesher3d_vertex_markers(m.0, &mut pi, &mut n), IDM_OK);
            assert_eq!(n, nv);
            out.vertex_markers = arr(pi, n);
            assert_eq!(idm_mesher3d_tets(m.0, &mut pu, &mut n), IDM_OK);
            assert_eq!(n, nt);
            out.tets = chunks(arr(pu, 4 * n));
            assert_eq!(idm_mesher3d_neighbors(m.0, &mut pu, &mut n), IDM_OK);
            assert_eq!(n, nt);
            out.neighbors = chunks(arr(pu, 4 * n));
            assert_eq!(idm_mesher3d_tet_attributes(m.0, &mut pf, &mut n), IDM_OK);
            out.tet_attributes = arr(pf, n);
            assert_eq!(idm_mesher3d_faces(m.0, &mut pu, &mut pi, &mut n), IDM_OK);
            assert_eq!(n, nf);
            out.faces = chunks(arr(pu, 3 * n));
            out.face_markers = arr(pi, n);
            assert_eq!(idm_mesher3d_edges(m.0, &mut pu, &mut pi, &mut n), IDM_OK);
            assert_eq!(n, ne);
            out.edges = chunks(arr(pu, 2 * n));
            out.edge_markers = arr(pi, n);
            let mut s = std::mem::MaybeUninit::<idm_stats3d>::uninit();
            assert_eq!(
                idm_mesher3d_stats_sized(m.0, s.as_mut_ptr(), size_of::<idm_stats3d>()),
                IDM_OK
            );
            let s = s.assume_init();
            out.complete = s.complete != 0;
            out.steiner_points = s.steiner_points;
        }
        out.num_input_vertices = m.get().plc.points.len();
        out
    }

    /// One positively oriented tetrahedron with its four faces and six edges, hand-made so
    /// that the getters can be tested without the mesher.
    fn one_tet() -> TetMesh {
        TetMesh {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [0.0, 2.0, 0.0],
                [0.0, 0.0, 2.0],
            ],
            vertex_markers: vec![5, 6, 7, 8],
            num_input_vertices: 4,
            tets: vec![[0, 1, 2, 3]],
            neighbors: vec![[NONE; 4]],
            tet_attributes: vec![2.5],
            faces: vec![[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]],
            face_markers: vec![1, 2, 3, 4],
            edges: vec![[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]],
            edge_markers: vec![9, 9, 9, 8, 8, 8],
            complete: false,
            steiner_points: 3,
            surface_kept: false,
            optimized: false,
        }
    }

    /// TetGen's positive orientation, exactly: det[b − a, c − a, d − a] > 0, which is
    /// Shewchuk's orient3d < 0 (pinned by the reference tetrahedron of `one_tet`).
    fn positive(c: [[f64; 3]; 4]) -> bool {
        orient3d(c[0], c[1], c[2], c[3]) < 0.0
    }

    /// `Some(value)` when the Rust call succeeded; `None` when the mesher reports it is not
    /// implemented yet (the status the FFI must then pass through). Any other error fails.
    fn implemented<T>(r: Result<T, Error>, what: &str) -> Option<T> {
        match r {
            Ok(v) => Some(v),
            Err(Error::Unsupported(msg)) => {
                eprintln!("note: {what} not implemented yet ({msg}); success checks skipped");
                None
            }
            Err(e) => panic!("{what} failed: {e}"),
        }
    }

    #[test]
    fn orientation_convention_is_pinned() {
        let t = one_tet();
        assert!(positive(t.corners(0)));
        assert!(crate::geometry::tet_volume(t.corners(0)) > 0.0);
        let [a, b, c, d] = t.corners(0);
        assert!(!positive([b, a, c, d]));
    }

    #[test]
    fn null_handle_is_reported_with_its_name() {
        let xyz = [0.0; 6];
        let null = std::ptr::null_mut::<idm_mesher3d>();
        unsafe {
            let st = idm_mesher3d_add_points(null, xyz.as_ptr(), 2, std::ptr::null());
            assert_eq!(st, IDM_ERR_NULL_POINTER);
            assert!(last_error().contains("`m`"), "{}", last_error());
            let idx = [0u32, 1, 2];
            let off = [0usize, 3];
            let st =
                idm_mesher3d_add_facet(null, idx.as_ptr(), off.as_ptr(), 1, std::ptr::null(), 0, 1);
            assert_eq!(st, IDM_ERR_NULL_POINTER);
            assert_eq!(
                idm_mesher3d_add_hole(null, xyz.as_ptr()),
                IDM_ERR_NULL_POINTER
            );
            assert_eq!(
                idm_mesher3d_add_region(null, xyz.as_ptr(), 1.0, 0.0),
                IDM_ERR_NULL_POINTER
            );
            assert_eq!(idm_mesher3d_refine(null), IDM_ERR_NULL_POINTER);
            assert_eq!(idm_mesher3d_delaunay(null), IDM_ERR_NULL_POINTER);
            assert_eq!(idm_mesher3d_validate(null), IDM_ERR_NULL_POINTER);
            let mut s = std::mem::MaybeUninit::<idm_stats3d>::uninit();
            assert_eq!(
                idm_mesher3d_stats_sized(null, s.as_mut_ptr(), size_of::<idm_stats3d>()),
                IDM_ERR_NULL_POINTER
            );
            assert!(last_error().contains("`m`"), "{}", last_error());
            assert_eq!(idm_mesher3d_new(std::ptr::null_mut()), IDM_ERR_NULL_POINTER);
            assert!(last_error().contains("`out`"), "{}", last_error());
        }
    }

    #[test]
    fn null_array_is_an_error_unless_the_count_is_zero() {
        let m = Handle::new();
        let idx = [0u32, 1, 2];
        let off = [0usize, 3];
        let xyz = [0.5; 3];
        let null_f = std::ptr::null::<f64>();
        unsafe {
            let st = idm_mesher3d_add_points(m.0, null_f, 3, std::ptr::null());
            assert_eq!(st, IDM_ERR_NULL_POINTER);
            assert!(last_error().contains("`xyz`"), "{}", last_error());
            let st = idm_mesher3d_add_segments(m.0, std::ptr::null(), 0, std::ptr::null());
            assert_eq!(st, IDM_OK);
            let st = idm_mesher3d_add_facet(m.0, std::ptr::null(), off.as_ptr(), 1, null_f, 0, 1);
            assert_eq!(st, IDM_ERR_NULL_POINTER);
            assert!(last_error().contains("`indices`"), "{}", last_error());
            let st = idm_mesher3d_add_facet(m.0, idx.as_ptr(), std::ptr::null(), 1, null_f, 0, 1);
            assert_eq!(st, IDM_ERR_NULL_POINTER);
            assert!(last_error().contains("`loop_offsets`"), "{}", last_error());
            let st = idm_mesher3d_add_facet(m.0, idx.as_ptr(), off.as_ptr(), 1, null_f, 2, 1);
            assert_eq!(st, IDM_ERR_NULL_POINTER);
            assert!(last_error().contains("`holes_xyz`"), "{}", last_error());
            assert_eq!(idm_mesher3d_add_hole(m.0, null_f), IDM_ERR_NULL_POINTER);
            assert!(last_error().contains("`xyz`"), "{}", last_error());
            assert_eq!(
                idm_mesher3d_add_region(m.0, null_f, 1.0, 1.0),
                IDM_ERR_NULL_POINTER
            );
            assert_eq!(
                idm_mesher3d_set_options(m.0, std::ptr::null()),
                IDM_ERR_NULL_POINTER
            );
            assert!(last_error().contains("`opts`"), "{}", last_error());
            // NULL hole seeds with a zero count are fine.
            let st = idm_mesher3d_add_facet(m.0, idx.as_ptr(), off.as_ptr(), 1, null_f, 0, 4);
            assert_eq!(st, IDM_OK, "{}", last_error());
            assert_eq!(idm_mesher3d_add_hole(m.0, xyz.as_ptr()), IDM_OK);
        }
        // The failed calls left the handle unchanged.
        let p = &m.get().plc;
        assert!(p.points.is_empty() && p.regions.is_empty());
        assert_eq!(p.facets.len(), 1);
        assert_eq!(p.facets[0].marker, 4);
        assert_eq!(p.holes, vec![[0.5; 3]]);
    }

    #[test]
    fn overflowing_counts_are_rejected_before_any_read() {
        let m = Handle::new();
        // Each pointer is valid for one item only: the checks must fail before reading.
        let xyz = [0.0; 3];
        for count in [usize::MAX, usize::MAX / 3 + 1, usize::MAX / 8] {
            let st = unsafe { idm_mesher3d_add_points(m.0, xyz.as_ptr(), count, std::ptr::null()) };
            assert_eq!(st, IDM_ERR_INVALID_ARGUMENT, "count {count}");
            assert!(last_error().contains("too large"), "{}", last_error());
        }
        let ab = [0u32; 2];
        let st =
            unsafe { idm_mesher3d_add_segments(m.0, ab.as_ptr(), usize::MAX, std::ptr::null()) };
        assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
        let idx = [0u32, 1, 2];
        let off = [0usize, 3];
        unsafe {
            let st = idm_mesher3d_add_facet(
                m.0,
                idx.as_ptr(),
                off.as_ptr(),
                usize::MAX,
                xyz.as_ptr(),
                0,
                1,
            );
            assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
            assert!(last_error().contains("num_loops"), "{}", last_error());
            let st = idm_mesher3d_add_facet(
                m.0,
                idx.as_ptr(),
                off.as_ptr(),
                1,
                xyz.as_ptr(),
                usize::MAX / 2,
                1,
            );
            assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
            assert!(last_error().contains("num_holes"), "{}", last_error());
            // An offset claiming more indices than fit in memory.
            let huge = [0usize, usize::MAX];
            let st =
                idm_mesher3d_add_facet(m.0, idx.as_ptr(), huge.as_ptr(), 1, xyz.as_ptr(), 0, 1);
            assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
            assert!(last_error().contains("`indices`"), "{}", last_error());
        }
        let p = &m.get().plc;
        assert!(p.points.is_empty() && p.segments.is_empty() && p.facets.is_empty());
    }

    #[test]
    fn misaligned_input_is_rejected() {
        let m = Handle::new();
        let buf = [0.0f64; 8];
        let bad = unsafe { buf.as_ptr().cast::<u8>().add(1) }.cast::<f64>();
        let st = unsafe { idm_mesher3d_add_points(m.0, bad, 2, std::ptr::null()) };
        assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
        assert!(last_error().contains("aligned"), "{}", last_error());
    }

    #[test]
    fn bad_loop_offsets_name_the_facet_and_loop() {
        let m = Handle::new();
        let idx = [0u32, 1, 2, 3, 4, 5];
        let good = [0usize, 3, 6];
        let null_f = std::ptr::null::<f64>();
        let add = |off: &[usize], loops: usize| unsafe {
            idm_mesher3d_add_facet(m.0, idx.as_ptr(), off.as_ptr(), loops, null_f, 0, 1)
        };
        assert_eq!(add(&good, 2), IDM_OK, "{}", last_error());
        // The next facet is facet 1: every message names it.
        for (off, loops, needle) in [
            (&[1usize, 3, 6][..], 2, "loop_offsets[0] is 1"),
            (&[0, 3, 3][..], 2, "loop 1 is empty"),
            (&[0, 4, 2][..], 2, "loop 1 is empty or reversed"),
            (&[0, 0][..], 1, "loop 0"),
            (&[0][..], 0, "num_loops is 0"),
        ] {
            assert_eq!(add(off, loops), IDM_ERR_INVALID_ARGUMENT, "{off:?}");
            let msg = last_error();
            assert!(
                msg.contains("facet 1") && msg.contains(needle),
                "{off:?}: {msg}"
            );
        }
        assert_eq!(
            m.get().plc.facets.len(),
            1,
            "failed calls changed the handle"
        );
    }

    #[test]
    fn input_round_trips_through_the_entry_points() {
        let mut p = cube();
        p.segments = vec![[0, 6], [8, 10]];
        p.segment_markers = vec![7, 8];
        p.facets[2].holes = vec![[0.5, 0.0, 0.5], [0.25, 0.0, 0.25]];
        p.holes = vec![[0.5, 0.5, 0.5]];
        p.regions = vec![
            Region3 {
                point: [0.1, 0.1, 0.1],
                attribute: 3.0,
                max_volume: Some(0.01),
            },
            Region3 {
                point: [0.9, 0.9, 0.9],
                attribute: -1.0,
                max_volume: None,
            },
        ];
        let m = Handle::new();
        load(&m, &p);
        assert_eq!(m.get().plc, p);
    }

    #[test]
    fn markers_default_per_call() {
        let m = Handle::new();
        let xyz = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        let mk = [5, 6];
        let ab = [0u32, 1, 1, 2, 2, 0];
        unsafe {
            assert_eq!(
                idm_mesher3d_add_points(m.0, xyz.as_ptr(), 1, std::ptr::null()),
                IDM_OK
            );
            assert_eq!(
                idm_mesher3d_add_points(m.0, xyz[3..].as_ptr(), 2, mk.as_ptr()),
                IDM_OK
            );
            assert_eq!(
                idm_mesher3d_add_segments(m.0, ab.as_ptr(), 2, mk.as_ptr()),
                IDM_OK
            );
            assert_eq!(
                idm_mesher3d_add_segments(m.0, ab[4..].as_ptr(), 1, std::ptr::null()),
                IDM_OK
            );
        }
        let p = &m.get().plc;
        assert_eq!(p.points, vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(p.point_markers, vec![0, 5, 6]);
        assert_eq!(p.segments, vec![[0, 1], [1, 2], [2, 0]]);
        assert_eq!(p.segment_markers, vec![5, 6, 0]);
    }

    #[test]
    fn regions_translate_volume_bounds_and_reject_nan() {
        let m = Handle::new();
        let xyz = [1.0, 2.0, 3.0];
        unsafe {
            for v in [0.5, 0.0, -3.0, f64::NEG_INFINITY] {
                assert_eq!(idm_mesher3d_add_region(m.0, xyz.as_ptr(), 9.0, v), IDM_OK);
            }
            let st = idm_mesher3d_add_region(m.0, xyz.as_ptr(), 9.0, f64::NAN);
            assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
        }
        assert!(last_error().contains("region 4"), "{}", last_error());
        let r = &m.get().plc.regions;
        assert_eq!(r.len(), 4);
        assert_eq!((r[0].point, r[0].attribute), ([1.0, 2.0, 3.0], 9.0));
        assert_eq!(r[0].max_volume, Some(0.5));
        assert!(r[1..].iter().all(|r| r.max_volume.is_none()));
    }

    #[test]
    fn default_options_match_the_rust_defaults() {
        let o = options(0.0, 0.0);
        let d = Options3::default();
        assert_eq!(o.radius_edge, d.radius_edge.unwrap_or(0.0));
        assert_eq!(o.max_volume, d.max_volume.unwrap_or(0.0));
        assert_eq!(o.region_max_volume != 0, d.region_max_volume);
        assert_eq!(o.region_attributes != 0, d.region_attributes);
        assert_eq!(o.max_steiner < 0, d.max_steiner.is_none());
        assert_eq!(o.verbose != 0, d.verbose);
        assert_eq!(o.keep_surface != 0, d.keep_surface);
        assert_eq!(o.surface_input != 0, d.surface_input);
        // The documented values of the header.
        assert_eq!((o.max_steiner, o.verbose, o.keep_surface), (-1, 0, 0));
        assert_eq!(o.surface_input, 0);
    }

    #[test]
    fn options_are_translated_and_nan_rejected() {
        let mut m = Handle::new();
        let mut o = options(2.0, -1.0);
        o.region_attributes = 7;
        o.region_max_volume = 1;
        o.max_steiner = 100;
        o.verbose = 1;
        o.keep_surface = 1;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        let h = &m.get_mut().opts;
        assert_eq!((h.radius_edge, h.max_volume), (Some(2.0), None));
        assert!(h.region_attributes && h.region_max_volume && h.verbose && h.keep_surface);
        assert_eq!(h.max_steiner, Some(100));
        for field in ["radius_edge", "max_volume"] {
            let mut bad = o;
            if field == "radius_edge" {
                bad.radius_edge = f64::NAN;
            } else {
                bad.max_volume = f64::NAN;
            }
            assert_eq!(
                unsafe { idm_mesher3d_set_options(m.0, &bad) },
                IDM_ERR_INVALID_ARGUMENT
            );
            assert!(last_error().contains(field), "{}", last_error());
        }
        assert_eq!(m.get().opts.max_steiner, Some(100), "handle unchanged");
        o.max_steiner = -5;
        o.max_volume = 0.25;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(m.get().opts.max_steiner, None);
        assert_eq!(m.get().opts.max_volume, Some(0.25));
    }

    #[test]
    fn convex_hull_and_constraint_options_are_validated_and_copied() {
        let mut m = Handle::new();
        let mut o = options(0.0, -1.0);
        let facets = [1.0, 0.5, 3.0, 0.25];
        let segs = [0.0, 1.0, 0.1];
        o.convex_hull = 1;
        o.facet_constraints = facets.as_ptr();
        o.num_facet_constraints = 2;
        o.segment_constraints = segs.as_ptr();
        o.num_segment_constraints = 1;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        let h = &m.get_mut().opts;
        assert!(h.convex_hull);
        assert_eq!(h.facet_max_area, vec![(1, 0.5), (3, 0.25)]);
        assert_eq!(h.segment_max_length, vec![([0, 1], 0.1)]);
        for (f, s, needle) in [
            ([1.5, 0.5, 3.0, 0.25], [0.0, 1.0, 0.1], "marker"),
            ([1.0, -0.5, 3.0, 0.25], [0.0, 1.0, 0.1], "area"),
            ([1.0, 0.5, 3.0, 0.25], [-1.0, 1.0, 0.1], "endpoint"),
            ([1.0, 0.5, 3.0, 0.25], [0.0, 1.0, f64::NAN], "length"),
        ] {
            let mut bad = o;
            bad.facet_constraints = f.as_ptr();
            bad.segment_constraints = s.as_ptr();
            assert_eq!(
                unsafe { idm_mesher3d_set_options(m.0, &bad) },
                IDM_ERR_INVALID_ARGUMENT
            );
            assert!(last_error().contains(needle), "{}", last_error());
        }
        let mut null = o;
        null.facet_constraints = std::ptr::null();
        assert_eq!(
            unsafe { idm_mesher3d_set_options(m.0, &null) },
            IDM_ERR_NULL_POINTER
        );
        // A struct of 0.2.0's size gets the defaults: no hull, no constraints.
        let mut old = o;
        old.struct_size = <idm_options3d as SizedOptions>::BASELINE;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &old) }, IDM_OK);
        let h = &m.get_mut().opts;
        assert!(!h.convex_hull && h.facet_max_area.is_empty() && h.segment_max_length.is_empty());
    }

    #[test]
    fn coplanar_tolerance_turns_the_merge_on_and_is_validated() {
        let mut m = Handle::new();
        let mut o = options(0.0, -1.0);
        assert_eq!(o.coplanar_tolerance, 0.0, "exact by default");
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        let h = &m.get_mut().opts;
        assert!(!h.merge_coplanar && h.coplanar_tolerance.is_none());
        o.coplanar_tolerance = 1e-8;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        let h = &m.get_mut().opts;
        assert!(h.merge_coplanar && h.coplanar_tolerance == Some(1e-8));
        for bad in [f64::NAN, -1e-8] {
            let mut b = o;
            b.coplanar_tolerance = bad;
            assert_eq!(
                unsafe { idm_mesher3d_set_options(m.0, &b) },
                IDM_ERR_INVALID_ARGUMENT
            );
            assert!(
                last_error().contains("coplanar_tolerance"),
                "{}",
                last_error()
            );
        }
        // Too large: refused by refine, naming it.
        let m = Handle::new();
        load(&m, &split_cube());
        o.coplanar_tolerance = 0.5;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert_ne!(unsafe { idm_mesher3d_refine(m.0) }, IDM_OK);
        assert!(
            last_error().contains("coplanar tolerance"),
            "{}",
            last_error()
        );
        // An older struct gets the default: no merging.
        let mut old = o;
        old.struct_size = <idm_options3d as SizedOptions>::BASELINE;
        let mut m = Handle::new();
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &old) }, IDM_OK);
        assert!(m.get_mut().opts.coplanar_tolerance.is_none());
    }

    #[test]
    fn min_dihedral_option_removes_slivers_and_old_structs_get_the_default() {
        let o = options(1.414, 0.0005);
        assert_eq!(o.min_dihedral, crate::mesh3d::DEFAULT_MIN_DIHEDRAL);
        let run = |o: &idm_options3d| -> idm_stats3d {
            let m = Handle::new();
            load(&m, &cube());
            let mut s = std::mem::MaybeUninit::<idm_stats3d>::uninit();
            unsafe {
                assert_eq!(idm_mesher3d_set_options(m.0, o), IDM_OK);
                assert_eq!(idm_mesher3d_refine(m.0), IDM_OK, "{}", last_error());
                assert_eq!(idm_mesher3d_validate(m.0), IDM_OK, "{}", last_error());
                assert_eq!(
                    idm_mesher3d_stats_sized(m.0, s.as_mut_ptr(), size_of::<idm_stats3d>()),
                    IDM_OK
                );
                s.assume_init()
            }
        };
        let on = run(&o);
        assert!(
            on.min_dihedral >= 15.0 && on.max_dihedral <= 165.0,
            "{} {}",
            on.min_dihedral,
            on.max_dihedral
        );
        let mut off = o;
        off.min_dihedral = 0.0;
        let s = run(&off);
        assert!(
            s.min_dihedral < 15.0,
            "slivers without removal: {}",
            s.min_dihedral
        );
        let mut t = o;
        t.min_dihedral = 20.0;
        assert!(run(&t).min_dihedral >= 20.0);
        // NaN is refused by set_options, an impossible target by refine.
        let m = Handle::new();
        load(&m, &cube());
        let mut bad = o;
        bad.min_dihedral = f64::NAN;
        assert_eq!(
            unsafe { idm_mesher3d_set_options(m.0, &bad) },
            IDM_ERR_INVALID_ARGUMENT
        );
        assert!(last_error().contains("min_dihedral"), "{}", last_error());
        bad.min_dihedral = 75.0;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &bad) }, IDM_OK);
        assert_ne!(unsafe { idm_mesher3d_refine(m.0) }, IDM_OK);
        assert!(last_error().contains("dihedral"), "{}", last_error());
        // A caller built against 0.2.0 (a struct ending before the field) gets the default.
        let mut old = o;
        old.struct_size = <idm_options3d as SizedOptions>::BASELINE;
        old.min_dihedral = 0.0;
        let mut m = Handle::new();
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &old) }, IDM_OK);
        assert_eq!(
            m.get_mut().opts.min_dihedral,
            Some(crate::mesh3d::DEFAULT_MIN_DIHEDRAL)
        );
    }

    #[test]
    fn free_null_is_a_no_op_and_default_null_too() {
        unsafe {
            idm_mesher3d_free(std::ptr::null_mut());
            idm_options3d_default(std::ptr::null_mut());
        }
    }

    #[test]
    fn getters_before_refine_report_no_mesh() {
        let m = Handle::new();
        load(&m, &cube());
        let mut n = 7usize;
        let mut pf: *const f64 = std::ptr::null();
        let mut pu: *const u32 = std::ptr::null();
        let mut pi: *const i32 = std::ptr::null();
        let mut s = idm_stats3d {
            volume: -1.0,
            max_radius_edge: -1.0,
            min_dihedral: -1.0,
            max_dihedral: -1.0,
            steiner_points: 99,
            complete: 42,
            tets_below_5: 5,
            tets_below_10: 10,
            tets_below_15: 15,
        };
        let before = s;
        unsafe {
            assert_eq!(idm_mesher3d_vertices(m.0, &mut pf, &mut n), IDM_ERR_NO_MESH);
            assert!(
                last_error().contains("idm_mesher3d_refine"),
                "{}",
                last_error()
            );
            assert_eq!(
                idm_mesher3d_vertex_markers(m.0, &mut pi, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(idm_mesher3d_tets(m.0, &mut pu, &mut n), IDM_ERR_NO_MESH);
            assert_eq!(
                idm_mesher3d_neighbors(m.0, &mut pu, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(
                idm_mesher3d_tet_attributes(m.0, &mut pf, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(
                idm_mesher3d_faces(m.0, &mut pu, &mut pi, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(
                idm_mesher3d_edges(m.0, &mut pu, &mut pi, &mut n),
                IDM_ERR_NO_MESH
            );
            let np = std::ptr::null_mut();
            assert_eq!(
                idm_mesher3d_counts(m.0, &mut n, np, np, np),
                IDM_ERR_NO_MESH
            );
            assert_eq!(idm_mesher3d_stats(m.0, &mut s), IDM_ERR_NO_MESH);
            assert_eq!(idm_mesher3d_validate(m.0), IDM_ERR_NO_MESH);
        }
        // Out-parameters are untouched on failure.
        assert_eq!(n, 7);
        assert!(pf.is_null() && pu.is_null() && pi.is_null());
        assert_eq!(s, before);
    }

    #[test]
    fn getters_lend_the_mesh_exactly() {
        let mut m = Handle::new();
        let want = one_tet();
        m.get_mut().mesh = Some(want.clone());
        let mut got = read_back(&m);
        // Not lent by the C API (callers know how many points they added).
        got.num_input_vertices = want.num_input_vertices;
        assert_eq!(got, want);
        assert_eq!(last_error(), "");
        // Stats are the Rust figures, with the complete flag and Steiner count.
        let mut s = std::mem::MaybeUninit::<idm_stats3d>::uninit();
        assert_eq!(
            unsafe { idm_mesher3d_stats_sized(m.0, s.as_mut_ptr(), size_of::<idm_stats3d>()) },
            IDM_OK
        );
        let s = unsafe { s.assume_init() };
        let r = want.stats();
        assert_eq!(
            (s.volume, s.max_radius_edge, s.min_dihedral, s.max_dihedral),
            (r.volume, r.max_radius_edge, r.min_dihedral, r.max_dihedral)
        );
        assert!((s.volume - 8.0 / 6.0).abs() < 1e-15, "{}", s.volume);
        assert_eq!((s.complete, s.steiner_points), (0, 3));
        assert_eq!(
            [s.tets_below_5, s.tets_below_10, s.tets_below_15],
            r.tets_below
        );
        // The plain symbol (0.2.0 callers) writes 0.2.0's fields and nothing beyond; a newer
        // caller's larger struct gets its unknown tail zeroed; a too small size is refused.
        #[repr(C)]
        struct Wider {
            stats: idm_stats3d,
            newer: [u64; 2],
        }
        let mut w = Wider {
            stats: s,
            newer: [u64::MAX; 2],
        };
        w.stats.tets_below_5 = 77;
        assert_eq!(unsafe { idm_mesher3d_stats(m.0, &mut w.stats) }, IDM_OK);
        assert_eq!(w.stats.tets_below_5, 77);
        assert_eq!(w.stats.volume, s.volume);
        let p = (&mut w as *mut Wider).cast::<idm_stats3d>();
        assert_eq!(
            unsafe { idm_mesher3d_stats_sized(m.0, p, size_of::<Wider>()) },
            IDM_OK
        );
        assert_eq!((w.stats, w.newer), (s, [0, 0]));
        assert_eq!(
            unsafe { idm_mesher3d_stats_sized(m.0, p, STATS3D_BASELINE - 1) },
            IDM_ERR_INVALID_ARGUMENT
        );
        assert!(last_error().contains("struct_size"), "{}", last_error());
        // Only some counts wanted; marker arrays not wanted.
        let np = std::ptr::null_mut();
        let mut nf = 0usize;
        assert_eq!(
            unsafe { idm_mesher3d_counts(m.0, np, np, &mut nf, np) },
            IDM_OK
        );
        assert_eq!(nf, 4);
        let (mut pu, mut n) = (std::ptr::null::<u32>(), 0usize);
        assert_eq!(
            unsafe { idm_mesher3d_edges(m.0, &mut pu, np.cast(), &mut n) },
            IDM_OK
        );
        assert_eq!(unsafe { arr(pu, 2 * n) }.len(), 12);
        // A missing required out-parameter is named, and nothing is written.
        let mut n = 5usize;
        assert_eq!(
            unsafe { idm_mesher3d_tets(m.0, std::ptr::null_mut(), &mut n) },
            IDM_ERR_NULL_POINTER
        );
        assert!(last_error().contains("`abcd`"), "{}", last_error());
        assert_eq!(n, 5);
        assert_eq!(
            unsafe { idm_mesher3d_faces(m.0, &mut pu, np.cast(), std::ptr::null_mut()) },
            IDM_ERR_NULL_POINTER
        );
        assert!(last_error().contains("`count`"), "{}", last_error());
        assert_eq!(
            unsafe { idm_mesher3d_stats(m.0, std::ptr::null_mut()) },
            IDM_ERR_NULL_POINTER
        );
        // Empty arrays are lent as NULL with a zero count.
        m.get_mut().mesh.as_mut().unwrap().tet_attributes.clear();
        let mut pf: *const f64 = [1.0].as_ptr();
        assert_eq!(
            unsafe { idm_mesher3d_tet_attributes(m.0, &mut pf, &mut n) },
            IDM_OK
        );
        assert!(pf.is_null() && n == 0);
    }

    #[test]
    fn validate_reports_what_the_rust_validator_reports() {
        let mut m = Handle::new();
        let good = one_tet();
        m.get_mut().mesh = Some(good.clone());
        let st = unsafe { idm_mesher3d_validate(m.0) };
        match good.validate() {
            Ok(()) => assert_eq!(st, IDM_OK, "{}", last_error()),
            Err(e) => panic!("the reference tetrahedron is invalid: {e}"),
        }
        // An inverted tetrahedron: whatever the validator finds must come through verbatim.
        let mut bad = good;
        bad.tets[0].swap(0, 1);
        m.get_mut().mesh = Some(bad.clone());
        let st = unsafe { idm_mesher3d_validate(m.0) };
        match bad.validate() {
            Ok(()) => assert_eq!(st, IDM_OK),
            Err(e) => {
                assert_eq!(st, IDM_ERR_INTERNAL);
                let msg = last_error();
                assert!(msg.starts_with("mesh validation failed: "), "{msg}");
                assert!(msg.ends_with(&e.to_string()), "{msg}");
            }
        }
    }

    #[test]
    fn any_input_or_option_change_drops_the_mesh() {
        let mut m = Handle::new();
        let xyz = [3.0; 3];
        let idx = [0u32];
        let off = [0usize, 1];
        let o = options(0.0, 0.0);
        let changes: [&dyn Fn(*mut idm_mesher3d) -> idm_status; 7] = [
            &|h| unsafe { idm_mesher3d_add_points(h, xyz.as_ptr(), 1, std::ptr::null()) },
            &|h| unsafe { idm_mesher3d_add_segments(h, idx.as_ptr(), 0, std::ptr::null()) },
            &|h| unsafe {
                idm_mesher3d_add_facet(h, idx.as_ptr(), off.as_ptr(), 1, xyz.as_ptr(), 0, 0)
            },
            &|h| unsafe { idm_mesher3d_add_hole(h, xyz.as_ptr()) },
            &|h| unsafe { idm_mesher3d_add_region(h, xyz.as_ptr(), 0.0, 0.0) },
            &|h| unsafe { idm_mesher3d_set_options(h, &o) },
            &|h| unsafe { idm_mesher3d_set_sizing(h, None, std::ptr::null_mut()) },
        ];
        for (i, change) in changes.iter().enumerate() {
            m.get_mut().mesh = Some(one_tet());
            assert_eq!(unsafe { idm_mesher3d_validate(m.0) }, IDM_OK);
            assert_eq!(change(m.0), IDM_OK, "change {i}: {}", last_error());
            assert_eq!(
                unsafe { idm_mesher3d_validate(m.0) },
                IDM_ERR_NO_MESH,
                "change {i} kept the mesh"
            );
        }
    }

    #[test]
    fn last_error_is_shared_with_2d_and_thread_local() {
        let m = Handle::new();
        assert_eq!(
            unsafe { idm_mesher3d_add_hole(m.0, std::ptr::null()) },
            IDM_ERR_NULL_POINTER
        );
        assert!(!last_error().is_empty());
        let other = std::thread::spawn(last_error).join().unwrap();
        assert_eq!(other, "");
        assert!(!last_error().is_empty());
        // A successful 2D call clears the message of a failed 3D call: one error per thread.
        let mut m2 = std::ptr::null_mut();
        assert_eq!(
            unsafe { super::super::mesh2d::idm_mesher2d_new(&mut m2) },
            IDM_OK
        );
        assert_eq!(last_error(), "");
        unsafe { super::super::mesh2d::idm_mesher2d_free(m2) };
    }

    #[test]
    fn handle_is_send() {
        fn assert_send<T: Send>() {}
        assert_send::<idm_mesher3d>();
    }

    /// A C-style sizing test: records its arguments, too large when the volume exceeds the
    /// bound stored in `user`.
    #[repr(C)]
    struct SizingRecord {
        bound: f64,
        calls: usize,
        last: [f64; 13],
    }

    unsafe extern "C" fn record_sizing(
        user: *mut c_void,
        a: *const f64,
        b: *const f64,
        c: *const f64,
        d: *const f64,
        volume: f64,
    ) -> i32 {
        let r = unsafe { &mut *user.cast::<SizingRecord>() };
        r.calls += 1;
        for (k, p) in [a, b, c, d].into_iter().enumerate() {
            for i in 0..3 {
                r.last[3 * k + i] = unsafe { *p.add(i) };
            }
        }
        r.last[12] = volume;
        i32::from(volume > r.bound)
    }

    #[test]
    fn c_sizing_callback_receives_corners_volume_and_user() {
        let mut m = Handle::new();
        let mut rec = SizingRecord {
            bound: 0.5,
            calls: 0,
            last: [0.0; 13],
        };
        let user = (&mut rec as *mut SizingRecord).cast::<c_void>();
        assert_eq!(
            unsafe { idm_mesher3d_set_sizing(m.0, Some(record_sizing), user) },
            IDM_OK
        );
        let f = m.get().opts.sizing.clone().expect("sizing installed");
        let (a, b, c, d) = (
            [1.0, 2.0, 3.0],
            [4.0, 5.0, 6.0],
            [7.0, 8.0, 9.0],
            [10.0, 11.0, 12.0],
        );
        assert!(f(a, b, c, d, 0.75));
        assert!(!f(a, b, c, d, 0.25));
        drop(f);
        let want: Vec<f64> = (1..=12).map(f64::from).chain([0.25]).collect();
        assert_eq!((rec.calls, rec.last.to_vec()), (2, want));
        // Options keep the callback; NULL clears it.
        let o = options(0.0, 0.0);
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert!(m.get().opts.sizing.is_some());
        assert_eq!(unsafe { idm_mesher3d_set_sizing(m.0, None, user) }, IDM_OK);
        assert!(m.get_mut().opts.sizing.is_none());
    }

    // The tests below run the mesher: they compare the C entry points with the Rust calls,
    // and check the mesh itself once `tetrahedralize` / `delaunay3d` are implemented.

    #[test]
    fn refine_gives_the_rust_result() {
        let p = cube();
        let m = Handle::new();
        load(&m, &p);
        let st = unsafe { idm_mesher3d_refine(m.0) };
        let Some(want) = implemented(tetrahedralize(&p, &Options3::default()), "tetrahedralize")
        else {
            assert_eq!(st, IDM_ERR_UNSUPPORTED);
            let msg = last_error();
            assert_eq!(
                msg,
                tetrahedralize(&p, &Options3::default())
                    .unwrap_err()
                    .to_string()
            );
            assert_eq!(unsafe { idm_mesher3d_validate(m.0) }, IDM_ERR_NO_MESH);
            return;
        };
        assert_eq!(st, IDM_OK, "{}", last_error());
        assert_eq!(last_error(), "");
        assert_eq!(
            unsafe { idm_mesher3d_validate(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        let got = read_back(&m);
        assert_eq!(got, want);
        assert!(!got.tets.is_empty());
        assert!(got
            .tets
            .iter()
            .enumerate()
            .all(|(t, _)| positive(got.corners(t))));
        assert!(
            (got.volume() - 1.0).abs() < 1e-12,
            "volume {}",
            got.volume()
        );
        assert_eq!(&got.vertices[..p.points.len()], &p.points[..]);
        assert_eq!(&got.vertex_markers[..p.points.len()], &p.point_markers[..]);
        // Each facet is covered by faces of its marker: area 1 per cube side.
        for marker in 1..=6 {
            let area: f64 = got
                .faces
                .iter()
                .zip(&got.face_markers)
                .filter(|(_, &k)| k == marker)
                .map(|(f, _)| tri_area(f.map(|v| got.vertices[v as usize])))
                .sum();
            assert!((area - 1.0).abs() < 1e-12, "facet {marker}: area {area}");
        }
    }

    fn tri_area([a, b, c]: [[f64; 3]; 3]) -> f64 {
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
    }

    #[test]
    fn an_options_struct_of_0_2_0_leaves_the_appended_fields_at_their_defaults() {
        assert_eq!(<idm_options3d as SizedOptions>::BASELINE, 48);
        let mut o = options(2.0, 0.0);
        o.surface_input = 1;
        o.struct_size = 48;
        let mut m = Handle::new();
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        let h = &m.get_mut().opts;
        assert_eq!(h.radius_edge, Some(2.0));
        assert!(!h.surface_input, "beyond the caller's struct");
    }

    #[test]
    fn the_thread_count_maps_and_an_older_struct_gets_the_default() {
        let mut o = options(0.0, 0.0);
        assert_eq!(o.threads, 0, "default: IDMESH_THREADS or all cores");
        let m = Handle::new();
        load(&m, &cube());
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(m.get().opts.threads, None);
        o.threads = 2;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(m.get().opts.threads, Some(2));
        assert_eq!(
            unsafe { idm_mesher3d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        o.struct_size = std::mem::offset_of!(idm_options3d, threads);
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(m.get().opts.threads, None, "beyond the caller's struct");
    }

    #[test]
    fn optimisation_options_map_default_and_are_checked() {
        let d = options(0.0, 0.0);
        assert_eq!(
            (d.optimize_level, d.optimize_scheme, d.optimize_max_dihedral),
            (0, 7, 165.0),
            "off by default: the mesh stays Delaunay"
        );
        // A struct that ends before the optimisation fields gets their defaults.
        let mut o = options(1.414, 0.001);
        o.optimize_level = 3;
        o.struct_size = std::mem::offset_of!(idm_options3d, optimize_level);
        let p = cube();
        let m = Handle::new();
        load(&m, &p);
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(m.get().opts.optimize_level, 0, "beyond the caller's struct");
        o.struct_size = size_of::<idm_options3d>();
        o.min_dihedral = 0.0;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(
            unsafe { idm_mesher3d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        let want = tetrahedralize(
            &p,
            &Options3 {
                radius_edge: Some(1.414),
                max_volume: Some(0.001),
                min_dihedral: Some(0.0),
                optimize_level: 3,
                ..Options3::default()
            },
        )
        .unwrap();
        assert!(want.optimized, "the cube's slivers are flipped away");
        assert_eq!(m.get().mesh.as_ref(), Some(&want));
        // The getters lend the optimised mesh (the flag itself has no getter).
        let got = read_back(&m);
        assert_eq!(
            got,
            TetMesh {
                optimized: false,
                ..want.clone()
            }
        );
        assert_eq!(
            unsafe { idm_mesher3d_validate(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        for (field, value) in [("optimize_level", -1), ("optimize_scheme", -2)] {
            let mut bad = o;
            if field == "optimize_level" {
                bad.optimize_level = value;
            } else {
                bad.optimize_scheme = value;
            }
            assert_eq!(
                unsafe { idm_mesher3d_set_options(m.0, &bad) },
                IDM_ERR_INVALID_ARGUMENT
            );
            assert!(last_error().contains(field), "{}", last_error());
        }
        let mut bad = o;
        bad.optimize_max_dihedral = f64::NAN;
        assert_eq!(
            unsafe { idm_mesher3d_set_options(m.0, &bad) },
            IDM_ERR_INVALID_ARGUMENT
        );
        bad.optimize_max_dihedral = 200.0;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &bad) }, IDM_OK);
        assert_eq!(
            unsafe { idm_mesher3d_refine(m.0) },
            IDM_ERR_INVALID_ARGUMENT
        );
        assert!(last_error().contains("200"), "{}", last_error());
    }

    #[test]
    fn surface_input_repairs_the_facets_first() {
        // The cube with its vertex 1 given again (as the last point) for one facet: refused
        // as it is, meshed with `surface_input`, whose output has the other points first.
        let mut p = cube();
        let n = p.points.len();
        p.points.push(p.points[1]);
        p.point_markers.push(0);
        let f = p
            .facets
            .iter()
            .position(|f| f.polygons[0].contains(&1))
            .unwrap();
        p.facets[f].polygons[0].iter_mut().for_each(|v| {
            if *v == 1 {
                *v = n as u32;
            }
        });
        let m = Handle::new();
        load(&m, &p);
        assert_eq!(unsafe { idm_mesher3d_refine(m.0) }, IDM_ERR_INVALID_INPUT);
        let mut o = options(0.0, 0.0);
        o.surface_input = 1;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        assert!(m.get().opts.surface_input);
        assert_eq!(
            unsafe { idm_mesher3d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        let got = read_back(&m);
        assert_eq!(&got.vertices[..n], &p.points[..n]);
        assert!(
            !got.vertices[n..].contains(&p.points[1]),
            "merged into vertex 1"
        );
        assert!(
            (got.volume() - 1.0).abs() < 1e-12,
            "volume {}",
            got.volume()
        );
    }

    #[test]
    fn bad_input_gives_the_rust_error_and_no_mesh() {
        let mut p = cube();
        p.facets[3].polygons[0][2] = 17;
        let m = Handle::new();
        load(&m, &p);
        let st = unsafe { idm_mesher3d_refine(m.0) };
        let want = tetrahedralize(&p, &Options3::default()).expect_err("index 17 is invalid");
        // Whatever the mesher reports comes through with its status and its exact message;
        // the Rust side's own tests pin which error it is.
        let status = match want {
            Error::Input(_) => IDM_ERR_INVALID_INPUT,
            Error::InvalidOption(_) => IDM_ERR_INVALID_ARGUMENT,
            Error::Unsupported(_) => IDM_ERR_UNSUPPORTED,
            Error::Internal(_) => IDM_ERR_INTERNAL,
            Error::Cancelled(_) => IDM_CANCELLED,
        };
        assert_eq!(st, status);
        assert_eq!(last_error(), want.to_string());
        if status == IDM_ERR_INVALID_INPUT {
            assert!(last_error().contains("17"), "{}", last_error());
        } else {
            eprintln!("note: a facet index out of range gives `{want}`, not an input error yet");
        }
        assert_eq!(unsafe { idm_mesher3d_validate(m.0) }, IDM_ERR_NO_MESH);
    }

    #[test]
    fn delaunay_gives_the_rust_result_with_input_markers() {
        let mut p = cube();
        p.points.truncate(8);
        p.point_markers.truncate(8);
        p.points.push([0.5, 0.5, 0.5]);
        p.point_markers.push(99);
        p.facets.clear();
        let m = Handle::new();
        load(&m, &p);
        let st = unsafe { idm_mesher3d_delaunay(m.0) };
        let Some(want) = implemented(delaunay3d(&p.points), "delaunay3d") else {
            assert_eq!(st, IDM_ERR_UNSUPPORTED);
            assert_eq!(last_error(), delaunay3d(&p.points).unwrap_err().to_string());
            assert_eq!(unsafe { idm_mesher3d_validate(m.0) }, IDM_ERR_NO_MESH);
            return;
        };
        assert_eq!(st, IDM_OK, "{}", last_error());
        assert_eq!(
            unsafe { idm_mesher3d_validate(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        let got = read_back(&m);
        assert_eq!((&got.vertices, &got.tets), (&want.vertices, &want.tets));
        assert_eq!(&got.vertex_markers[..9], &p.point_markers[..]);
        assert!(got
            .tets
            .iter()
            .enumerate()
            .all(|(t, _)| positive(got.corners(t))));
        assert!(
            (got.volume() - 1.0).abs() < 1e-12,
            "volume {}",
            got.volume()
        );
        // Duplicate points are reported by index.
        assert_eq!(
            unsafe { idm_mesher3d_add_points(m.0, p.points[3].as_ptr(), 1, std::ptr::null()) },
            IDM_OK
        );
        assert_eq!(unsafe { idm_mesher3d_delaunay(m.0) }, IDM_ERR_INVALID_INPUT);
        assert!(
            last_error().contains("3") && last_error().contains("9"),
            "{}",
            last_error()
        );
    }

    /// The unit cube split at z = 0.5 by an inner facet (marker 7), each side two quads.
    fn split_cube() -> Plc {
        let mut p = cube();
        p.points.truncate(8);
        p.points.extend([
            [0.0, 0.0, 0.5],
            [1.0, 0.0, 0.5],
            [1.0, 1.0, 0.5],
            [0.0, 1.0, 0.5],
        ]);
        p.point_markers = (10..22).collect();
        let quads: [([u32; 4], i32); 11] = [
            ([0, 3, 2, 1], 1),
            ([4, 5, 6, 7], 2),
            ([8, 9, 10, 11], 7),
            ([0, 1, 9, 8], 3),
            ([8, 9, 5, 4], 3),
            ([1, 2, 10, 9], 4),
            ([9, 10, 6, 5], 4),
            ([2, 3, 11, 10], 5),
            ([10, 11, 7, 6], 5),
            ([3, 0, 8, 11], 6),
            ([11, 8, 4, 7], 6),
        ];
        p.facets = quads
            .iter()
            .map(|(q, marker)| Facet {
                polygons: vec![q.to_vec()],
                holes: Vec::new(),
                marker: *marker,
            })
            .collect();
        p.regions = vec![
            Region3 {
                point: [0.3, 0.6, 0.2],
                attribute: 1.0,
                max_volume: Some(0.002),
            },
            Region3 {
                point: [0.7, 0.4, 0.8],
                attribute: 2.0,
                max_volume: None,
            },
        ];
        p
    }

    #[test]
    fn regions_give_the_rust_result() {
        let p = split_cube();
        let m = Handle::new();
        load(&m, &p);
        let mut o = options(0.0, 0.05);
        o.region_attributes = 1;
        o.region_max_volume = 1;
        assert_eq!(unsafe { idm_mesher3d_set_options(m.0, &o) }, IDM_OK);
        let st = unsafe { idm_mesher3d_refine(m.0) };
        let opts = Options3 {
            max_volume: Some(0.05),
            region_attributes: true,
            region_max_volume: true,
            ..Options3::default()
        };
        let Some(want) = implemented(tetrahedralize(&p, &opts), "tetrahedralize") else {
            assert_eq!(st, IDM_ERR_UNSUPPORTED);
            return;
        };
        assert_eq!(st, IDM_OK, "{}", last_error());
        let got = read_back(&m);
        assert_eq!(got, want);
        assert_eq!(got.tet_attributes.len(), got.tets.len());
        for (t, &a) in got.tet_attributes.iter().enumerate() {
            let z: f64 = got.corners(t).iter().map(|c| c[2]).sum::<f64>() / 4.0;
            assert_eq!(a, if z < 0.5 { 1.0 } else { 2.0 }, "tet {t}");
        }
    }
}
