//! The 2D part of the C ABI (`idm_mesher2d_*`, declared in `include/idmesh.h`).
//!
//! A thin layer over [`crate::triangulate`]: a handle collects the PSLG and the options, refine
//! runs the Rust mesher, and getters lend pointers into the resulting [`TriMesh`]. Only what is
//! 2D lives here; every body goes through the shared machinery of [`super::common`].

use std::ffi::c_void;
use std::mem::size_of;
use std::sync::Arc;

use super::common::{
    add_marked, change, counts, free_handle, idm_progress_fn, idm_status, impl_handle,
    init_options, input_slice, lend, lend_plain, new_handle, optional_slice, positive,
    read_options, reject_nan, reserve, run, scaled, set_progress, steiner_cap_to_c, validate,
    CCallback, Failure, Handle, SizedOptions,
};
use crate::input2d::{Pslg, Region};
use crate::mesh2d::{triangulate, Options, SizingFn, TriMesh};

/// Meshing options. Fill it with `idm_options2d_default` first, then change what you need, so
/// that code keeps working if fields are ever appended. Booleans are `int32_t`: 0 is false,
/// anything else true.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct idm_options2d {
    /// The size of this struct as the caller was compiled: `sizeof(idm_options2d)`, set by
    /// `idm_options2d_default`. It lets a library and a caller built against different versions of
    /// the header exchange the struct safely (see `idm_options2d_default_sized`).
    pub struct_size: usize,
    /// Minimum angle in degrees (Triangle's `-q`); `<= 0` means no angle refinement. Must not
    /// be NaN. Default 0.
    pub min_angle: f64,
    /// Global maximum triangle area (Triangle's `-a<area>`); `<= 0` means none. Must not be
    /// NaN. Default 0.
    pub max_area: f64,
    /// Apply each region's maximum area (Triangle's `-a`). Default 0.
    pub region_max_area: i32,
    /// Write each region's attribute to its triangles (Triangle's `-A`). Default 0.
    pub region_attributes: i32,
    /// Mesh the whole convex hull of the points (Triangle's `-c`). Default 0.
    pub convex_hull: i32,
    /// Use off-centers instead of circumcenters for skinny triangles. Default 1.
    pub off_centers: i32,
    /// Split crossing segments at their intersection instead of reporting them. Default 0.
    pub split_crossings: i32,
    /// Forbid Steiner points on boundary segments (Triangle's `-Y`): the mesh is then
    /// constrained Delaunay along them, and triangles next to them may miss the quality bounds
    /// (as in Triangle). Default 0.
    pub no_boundary_steiner: i32,
    /// Maximum number of Steiner points (Triangle's `-S`); `< 0` means no cap. When the cap is
    /// reached refine returns `IDM_INCOMPLETE`. Default -1.
    pub max_steiner: i64,
    /// Forbid Steiner points on every segment, interior ones included (Triangle's `-YY`);
    /// implies `no_boundary_steiner`, with the same consequences next to every segment.
    /// Default 0. (Appended after 0.2.0.)
    pub no_segment_steiner: i32,
    /// Threads a run may use (so far for the exact check every run ends with; the mesh and
    /// every message are the same for any count). 0: the environment variable
    /// `IDMESH_THREADS`, else all cores. Default 0. Appended after 0.2.0: a caller's older
    /// struct gets the default.
    pub threads: usize,
}

/// A user sizing test (Triangle's `triunsuitable`): returns nonzero when the triangle with
/// counter-clockwise corners `a`, `b`, `c` (each pointing to 2 doubles, valid only during the
/// call) and area `area` is too large and must be split.
///
/// It is called only during `idm_mesher2d_refine` on the handle it was set on, from the thread
/// that called refine, and `user` is passed through untouched. It must be deterministic, must
/// not call back into the same handle, and must return normally (no C++ exception, no
/// `longjmp`).
pub type idm_sizing2d_fn = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        a: *const f64,
        b: *const f64,
        c: *const f64,
        area: f64,
    ) -> i32,
>;

/// An opaque 2D mesher: the input PSLG and options, and the output of the last successful
/// refine. Create with `idm_mesher2d_new`, destroy with `idm_mesher2d_free`. A handle may be
/// moved between threads, but must not be used by two threads at once; distinct handles are
/// fully independent.
pub struct idm_mesher2d {
    /// The input collected so far (markers always have one entry per item: the defaults 0
    /// for points and 1 for segments fill in for calls made without markers).
    pub(crate) pslg: Pslg,
    /// The options, including the sizing callback.
    opts: Options,
    /// The output of the last successful (or `IDM_INCOMPLETE`) refine; dropped by any change
    /// of input or options, so getters never describe a mesh of other input.
    mesh: Option<TriMesh>,
}

impl_handle!(
    idm_mesher2d { pslg, "idm_mesher2d_refine" },
    TriMesh,
    |h, mesh| {
        // With -Y (-YY) boundary (all) segments are kept whole: the mesh is constrained
        // Delaunay.
        if h.opts.no_boundary_steiner || h.opts.no_segment_steiner {
            mesh.validate_constrained()
        } else {
            mesh.validate()
        }
    }
);

/// The C sizing function of `idm_sizing2d_fn`.
type SizingFn2C = unsafe extern "C" fn(*mut c_void, *const f64, *const f64, *const f64, f64) -> i32;

impl CCallback<SizingFn2C> {
    /// Calls the C function. A method (rather than field accesses in the closure) so that the
    /// closure captures the whole `Send + Sync` struct, not its bare raw pointer.
    fn call(&self, a: [f64; 2], b: [f64; 2], c: [f64; 2], area: f64) -> bool {
        // SAFETY: the pointers refer to locals that outlive the call; the function pointer and
        // `user` are the caller's contract (see `idm_mesher2d_set_sizing`).
        unsafe { (self.f)(self.user, a.as_ptr(), b.as_ptr(), c.as_ptr(), area) != 0 }
    }
}

/// Fills `out` with the default options (the same defaults as the Rust `Options::default()`),
/// `struct_size` included. NULL is a no-op. Through the header this is a macro that calls
/// `idm_options2d_default_sized` with the caller's `sizeof(idm_options2d)`, so that a
/// program built against an older, smaller struct keeps working with a newer library.
///
/// # Safety
/// `out` must be NULL or valid for writing an `idm_options2d`.
#[no_mangle]
pub unsafe extern "C" fn idm_options2d_default(out: *mut idm_options2d) {
    // SAFETY: the caller's contract, forwarded.
    unsafe { init_options(out, size_of::<idm_options2d>()) }
}

/// `idm_options2d_default` for a caller's struct of `struct_size` bytes (the header's
/// `idm_options2d_default` macro passes `sizeof(idm_options2d)`): the fields this library knows
/// get their defaults and `struct_size` gets `struct_size`; bytes beyond them (fields of a
/// newer header) are zeroed. NULL, or a `struct_size` smaller than any version's struct, is
/// a no-op.
///
/// # Safety
/// `out` must be NULL or valid for writing `struct_size` bytes.
#[no_mangle]
pub unsafe extern "C" fn idm_options2d_default_sized(out: *mut idm_options2d, struct_size: usize) {
    // SAFETY: the caller's contract, forwarded.
    unsafe { init_options(out, struct_size) }
}

// SAFETY: `#[repr(C)]`, `struct_size: usize` first, only integer and float fields.
unsafe impl SizedOptions for idm_options2d {
    /// The 0.2.0 struct ended before `no_segment_steiner`.
    const BASELINE: usize = std::mem::offset_of!(idm_options2d, no_segment_steiner);
    const NAME: &'static str = "idm_options2d";

    fn defaults() -> Self {
        let d = Options::default();
        idm_options2d {
            struct_size: size_of::<idm_options2d>(),
            min_angle: d.min_angle.unwrap_or(0.0),
            max_area: d.max_area.unwrap_or(0.0),
            region_max_area: d.region_max_area.into(),
            region_attributes: d.region_attributes.into(),
            convex_hull: d.convex_hull.into(),
            off_centers: d.off_centers.into(),
            split_crossings: d.split_crossings.into(),
            no_boundary_steiner: d.no_boundary_steiner.into(),
            max_steiner: steiner_cap_to_c(d.max_steiner),
            no_segment_steiner: d.no_segment_steiner.into(),
            threads: d.threads.unwrap_or(0),
        }
    }
}

/// Creates an empty mesher with default options and stores it in `*out`.
///
/// # Safety
/// `out` must be NULL (an error) or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_new(out: *mut *mut idm_mesher2d) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { new_handle(out) }
}

/// Destroys a mesher and everything it lent out. NULL is a no-op.
///
/// # Safety
/// `m` must be NULL or a handle from `idm_mesher2d_new` not freed before and not in use.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_free(m: *mut idm_mesher2d) {
    // SAFETY: the caller's contract, forwarded.
    unsafe { free_handle(m) }
}

/// Appends `count` points: `xy` holds 2*count doubles (x0, y0, x1, y1, ...). `markers` is NULL
/// (all 0) or holds `count` markers. Points are numbered 0, 1, ... across all calls.
///
/// # Safety
/// `m` must be a live handle; `xy` and (when not NULL) `markers` must hold the stated number
/// of values.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_add_points(
    m: *mut idm_mesher2d,
    xy: *const f64,
    count: usize,
    markers: *const i32,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        add_marked(m, xy, count, markers, 0, ["xy", "points"], |m| {
            (&mut m.pslg.points, &mut m.pslg.point_markers)
        })
    }
}

/// Appends `count` segments: `ab` holds 2*count 0-based point indices. Indices may refer to
/// points added later; they are checked by refine. `markers` is NULL (all 1, as Triangle) or
/// holds `count` markers.
///
/// # Safety
/// `m` must be a live handle; `ab` and (when not NULL) `markers` must hold the stated number
/// of values.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_add_segments(
    m: *mut idm_mesher2d,
    ab: *const u32,
    count: usize,
    markers: *const i32,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        add_marked(m, ab, count, markers, 1, ["ab", "segments"], |m| {
            (&mut m.pslg.segments, &mut m.pslg.segment_markers)
        })
    }
}

/// Appends `count` hole seeds: `xy` holds 2*count doubles. The triangles reachable from a seed
/// without crossing a segment are removed.
///
/// # Safety
/// `m` must be a live handle; `xy` must hold 2*count doubles.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_add_holes(
    m: *mut idm_mesher2d,
    xy: *const f64,
    count: usize,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |m| {
            let xy = input_slice(xy, scaled(count, 2, "count")?, "xy")?;
            reserve(&mut m.pslg.holes, count, "holes")?;
            m.pslg
                .holes
                .extend(xy.chunks_exact(2).map(|p| [p[0], p[1]]));
            Ok(())
        })
    }
}

/// Appends `count` region seeds: `xy` holds 2*count doubles, `attributes` `count` regional
/// attributes, and `max_areas` is NULL (no regional bound) or holds `count` area bounds, where
/// `<= 0` means none (NaN is rejected). Attributes are written only with
/// `region_attributes`, area bounds applied only with `region_max_area`.
///
/// # Safety
/// `m` must be a live handle; the arrays must hold the stated number of values.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_add_regions(
    m: *mut idm_mesher2d,
    xy: *const f64,
    attributes: *const f64,
    max_areas: *const f64,
    count: usize,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |m| {
            let xy = input_slice(xy, scaled(count, 2, "count")?, "xy")?;
            let attributes = input_slice(attributes, count, "attributes")?;
            let max_areas = optional_slice(max_areas, count, "max_areas")?;
            if let Some(i) = max_areas.and_then(|a| a.iter().position(|x| x.is_nan())) {
                return Err(Failure::invalid(format!(
                    "max_areas[{i}] (region {}) is NaN",
                    m.pslg.regions.len() + i
                )));
            }
            reserve(&mut m.pslg.regions, count, "regions")?;
            for i in 0..count {
                m.pslg.regions.push(Region {
                    point: [xy[2 * i], xy[2 * i + 1]],
                    attribute: attributes[i],
                    max_area: positive(max_areas.map_or(0.0, |a| a[i])),
                });
            }
            Ok(())
        })
    }
}

/// Replaces the options (the sizing and progress callbacks are kept; see
/// `idm_mesher2d_set_sizing` and `idm_mesher2d_set_progress`). Value
/// ranges are checked by refine, except NaN angle or area, rejected here.
///
/// # Safety
/// `m` must be a live handle; `opts` must point to an `idm_options2d`.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_set_options(
    m: *mut idm_mesher2d,
    opts: *const idm_options2d,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |m| {
            let o = read_options(opts)?;
            reject_nan(&[("min_angle", o.min_angle), ("max_area", o.max_area)])?;
            m.opts = Options {
                min_angle: positive(o.min_angle),
                max_area: positive(o.max_area),
                region_max_area: o.region_max_area != 0,
                region_attributes: o.region_attributes != 0,
                convex_hull: o.convex_hull != 0,
                max_steiner: u64::try_from(o.max_steiner).ok(),
                no_boundary_steiner: o.no_boundary_steiner != 0,
                no_segment_steiner: o.no_segment_steiner != 0,
                off_centers: o.off_centers != 0,
                split_crossings: o.split_crossings != 0,
                sizing: m.opts.sizing.take(),
                progress: m.opts.progress.take(),
                verbose: m.opts.verbose,
                threads: (o.threads != 0).then_some(o.threads),
            };
            Ok(())
        })
    }
}

/// Sets the user sizing test (see `idm_sizing2d_fn`); `fn` NULL clears it (`user` is then
/// ignored). `user` is stored, never dereferenced by the library, and handed to every call of
/// `fn`; it must stay valid, and be usable from whichever thread calls refine, until the
/// sizing test is cleared or the handle freed.
///
/// # Safety
/// `m` must be a live handle; `fn` must be NULL or a function with the `idm_sizing2d_fn`
/// contract.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_set_sizing(
    m: *mut idm_mesher2d,
    r#fn: idm_sizing2d_fn,
    user: *mut c_void,
) -> idm_status {
    let sizing = r#fn.map(|f| {
        let c = CCallback { f, user };
        Arc::new(move |a, b, c3, area| c.call(a, b, c3, area)) as SizingFn
    });
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        change(m, |m| {
            m.opts.sizing = sizing;
            Ok(())
        })
    }
}

/// Sets the progress callback (see `idm_progress_fn`), which also lets the caller cancel a
/// refine; `fn` NULL clears it (`user` is then ignored). `user` is stored, never dereferenced
/// by the library, and handed to every call of `fn`; it must stay valid, and be usable from
/// whichever thread calls refine, until the callback is cleared or the handle freed. The
/// current mesh, if any, is kept.
///
/// # Safety
/// `m` must be a live handle; `fn` must be NULL or a function with the `idm_progress_fn`
/// contract.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_set_progress(
    m: *mut idm_mesher2d,
    r#fn: idm_progress_fn,
    user: *mut c_void,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { set_progress(m, r#fn, user, |h, p| h.opts.progress = p) }
}

/// Meshes the input with the current options, replacing any previous mesh. Returns `IDM_OK`,
/// `IDM_INCOMPLETE` (Steiner cap reached; the mesh is readable and valid; the message says so),
/// `IDM_CANCELLED` (the progress callback asked to stop) or an error; on `IDM_CANCELLED` or an
/// error there is no mesh. The input is kept either way.
///
/// # Safety
/// `m` must be a live handle.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_refine(m: *mut idm_mesher2d) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { run(m, true, |h| triangulate(&h.pslg, &h.opts)) }
}

/// The output sizes: vertices, triangles and subsegments. Each out-pointer may be NULL when
/// that number is not wanted.
///
/// # Safety
/// `m` must be a live handle; each out-pointer NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_counts(
    m: *const idm_mesher2d,
    num_vertices: *mut usize,
    num_triangles: *mut usize,
    num_segments: *mut usize,
) -> idm_status {
    let outs = [
        (num_vertices, "num_vertices"),
        (num_triangles, "num_triangles"),
        (num_segments, "num_segments"),
    ];
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        counts(m, outs, |mesh| {
            [
                mesh.vertices.len(),
                mesh.triangles.len(),
                mesh.segments.len(),
            ]
        })
    }
}

/// Lends the vertex coordinates: `*xy` gets 2*count doubles, `*count` the number of vertices.
/// Vertex i < (number of input points) is input point i.
///
/// # Safety
/// `m` must be a live handle; `xy` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_vertices(
    m: *const idm_mesher2d,
    xy: *mut *const f64,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, xy, count, "xy", |mesh| &mesh.vertices) }
}

/// Lends one marker per vertex (`*count` = number of vertices).
///
/// # Safety
/// `m` must be a live handle; `markers` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_vertex_markers(
    m: *const idm_mesher2d,
    markers: *mut *const i32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, markers, count, "markers", |mesh| &mesh.vertex_markers) }
}

/// Lends the triangles: `*abc` gets 3*count vertex indices, each triangle counter-clockwise.
///
/// # Safety
/// `m` must be a live handle; `abc` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_triangles(
    m: *const idm_mesher2d,
    abc: *mut *const u32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, abc, count, "abc", |mesh| &mesh.triangles) }
}

/// Lends the neighbours: `*nbr` gets 3*count triangle indices; entry 3t+i is the triangle
/// across the edge opposite corner i of triangle t, or `IDM_NONE` on the boundary.
///
/// # Safety
/// `m` must be a live handle; `nbr` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_neighbors(
    m: *const idm_mesher2d,
    nbr: *mut *const u32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, nbr, count, "nbr", |mesh| &mesh.neighbors) }
}

/// Lends one regional attribute per triangle (0 for triangles in no region). `*count` is 0
/// (and `*attr` NULL) unless the `region_attributes` option was set.
///
/// # Safety
/// `m` must be a live handle; `attr` and `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_triangle_attributes(
    m: *const idm_mesher2d,
    attr: *mut *const f64,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { lend_plain(m, attr, count, "attr", |mesh| &mesh.triangle_attributes) }
}

/// Lends the subsegments: `*ab` gets 2*count vertex indices and `*markers` (which may be NULL
/// when not wanted) one marker per subsegment, inherited from its input segment.
///
/// # Safety
/// `m` must be a live handle; `ab` and `count` valid for a write, `markers` NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_segments(
    m: *const idm_mesher2d,
    ab: *mut *const u32,
    markers: *mut *const i32,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        lend(m, ab, markers, count, "ab", |mesh| {
            (&mesh.segments, &mesh.segment_markers)
        })
    }
}

/// Checks the output mesh invariants exactly (index ranges, counter-clockwise orientation,
/// neighbour symmetry, empty circumcircles, segments present as edges). `IDM_OK`, or
/// `IDM_ERR_INTERNAL` with a message naming the first violation (a bug).
///
/// # Safety
/// `m` must be a live handle.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher2d_validate(m: *const idm_mesher2d) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { validate(m) }
}

#[cfg(test)]
mod tests {
    use super::super::common::testing::{last_error, TestHandle};
    use super::super::common::{guard, idm_version, mesh_of, IDM_NONE};
    use super::*;
    use crate::NONE;
    use std::ffi::CStr;
    use std::sync::atomic::{AtomicUsize, Ordering};

    use idm_status::*;

    /// A fresh handle, freed on drop.
    type Handle = TestHandle<idm_mesher2d>;

    /// A 10x10 square with a 2x2 square hole in the middle; outer segments marker 1, hole
    /// segments marker 2, point markers 10 + index.
    fn square_with_hole() -> Pslg {
        Pslg {
            points: vec![
                [0.0, 0.0],
                [10.0, 0.0],
                [10.0, 10.0],
                [0.0, 10.0],
                [4.0, 4.0],
                [6.0, 4.0],
                [6.0, 6.0],
                [4.0, 6.0],
            ],
            point_markers: (10..18).collect(),
            segments: vec![
                [0, 1],
                [1, 2],
                [2, 3],
                [3, 0],
                [4, 5],
                [5, 6],
                [6, 7],
                [7, 4],
            ],
            segment_markers: vec![1, 1, 1, 1, 2, 2, 2, 2],
            holes: vec![[5.0, 5.0]],
            regions: Vec::new(),
        }
    }

    /// Loads `p` into the handle through the C entry points.
    fn load(m: &Handle, p: &Pslg) {
        let xy: Vec<f64> = p.points.iter().flatten().copied().collect();
        let ab: Vec<u32> = p.segments.iter().flatten().copied().collect();
        let holes: Vec<f64> = p.holes.iter().flatten().copied().collect();
        unsafe {
            assert_eq!(
                idm_mesher2d_add_points(m.0, xy.as_ptr(), p.points.len(), p.point_markers.as_ptr()),
                IDM_OK
            );
            assert_eq!(
                idm_mesher2d_add_segments(
                    m.0,
                    ab.as_ptr(),
                    p.segments.len(),
                    p.segment_markers.as_ptr()
                ),
                IDM_OK
            );
            assert_eq!(
                idm_mesher2d_add_holes(m.0, holes.as_ptr(), p.holes.len()),
                IDM_OK
            );
        }
    }

    fn options(min_angle: f64, max_area: f64) -> idm_options2d {
        let mut o = std::mem::MaybeUninit::<idm_options2d>::uninit();
        unsafe { idm_options2d_default(o.as_mut_ptr()) };
        let mut o = unsafe { o.assume_init() };
        o.min_angle = min_angle;
        o.max_area = max_area;
        o
    }

    /// Reads the whole output of the handle back into a `TriMesh` (only the fields the C API
    /// exposes), through the getters.
    fn read_back(m: &Handle) -> TriMesh {
        unsafe fn arr<T: Copy>(p: *const T, n: usize) -> Vec<T> {
            if n == 0 {
                assert!(p.is_null(), "an empty array must be lent as NULL");
                Vec::new()
            } else {
                unsafe { std::slice::from_raw_parts(p, n) }.to_vec()
            }
        }
        let mut out = TriMesh::default();
        unsafe {
            let (mut nv, mut nt, mut ns) = (0usize, 0usize, 0usize);
            assert_eq!(idm_mesher2d_counts(m.0, &mut nv, &mut nt, &mut ns), IDM_OK);
            let mut n = 0usize;
            let mut pf: *const f64 = std::ptr::null();
            let mut pu: *const u32 = std::ptr::null();
            let mut pi: *const i32 = std::ptr::null();
            assert_eq!(idm_mesher2d_vertices(m.0, &mut pf, &mut n), IDM_OK);
            assert_eq!(n, nv);
            out.vertices = arr(pf, 2 * n)
                .chunks_exact(2)
                .map(|c| [c[0], c[1]])
                .collect();
            assert_eq!(idm_mesher2d_vertex_markers(m.0, &mut pi, &mut n), IDM_OK);
            assert_eq!(n, nv);
            out.vertex_markers = arr(pi, n);
            assert_eq!(idm_mesher2d_triangles(m.0, &mut pu, &mut n), IDM_OK);
            assert_eq!(n, nt);
            out.triangles = arr(pu, 3 * n)
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect();
            assert_eq!(idm_mesher2d_neighbors(m.0, &mut pu, &mut n), IDM_OK);
            assert_eq!(n, nt);
            out.neighbors = arr(pu, 3 * n)
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect();
            assert_eq!(
                idm_mesher2d_triangle_attributes(m.0, &mut pf, &mut n),
                IDM_OK
            );
            out.triangle_attributes = arr(pf, n);
            assert_eq!(idm_mesher2d_segments(m.0, &mut pu, &mut pi, &mut n), IDM_OK);
            assert_eq!(n, ns);
            out.segments = arr(pu, 2 * n)
                .chunks_exact(2)
                .map(|c| [c[0], c[1]])
                .collect();
            out.segment_markers = arr(pi, n);
        }
        out
    }

    #[test]
    fn null_handle_is_reported_with_its_name() {
        let xy = [0.0; 6];
        let st = unsafe {
            idm_mesher2d_add_points(std::ptr::null_mut(), xy.as_ptr(), 3, std::ptr::null())
        };
        assert_eq!(st, IDM_ERR_NULL_POINTER);
        assert!(last_error().contains("`m`"), "{}", last_error());
        assert_eq!(
            unsafe { idm_mesher2d_refine(std::ptr::null_mut()) },
            IDM_ERR_NULL_POINTER
        );
        assert_eq!(
            unsafe { idm_mesher2d_validate(std::ptr::null()) },
            IDM_ERR_NULL_POINTER
        );
        assert_eq!(
            unsafe { idm_mesher2d_new(std::ptr::null_mut()) },
            IDM_ERR_NULL_POINTER
        );
        assert!(last_error().contains("`out`"), "{}", last_error());
    }

    #[test]
    fn null_array_is_an_error_unless_the_count_is_zero() {
        let m = Handle::new();
        let st = unsafe { idm_mesher2d_add_points(m.0, std::ptr::null(), 3, std::ptr::null()) };
        assert_eq!(st, IDM_ERR_NULL_POINTER);
        assert!(last_error().contains("`xy`"), "{}", last_error());
        let st = unsafe { idm_mesher2d_add_segments(m.0, std::ptr::null(), 0, std::ptr::null()) };
        assert_eq!(st, IDM_OK);
        let xy = [0.0; 4];
        let attr = [1.0; 2];
        let st = unsafe {
            idm_mesher2d_add_regions(m.0, xy.as_ptr(), std::ptr::null(), attr.as_ptr(), 2)
        };
        assert_eq!(st, IDM_ERR_NULL_POINTER);
        assert!(last_error().contains("`attributes`"), "{}", last_error());
        // The failed calls left the handle unchanged.
        let h = unsafe { &*m.0 };
        assert!(h.pslg.points.is_empty() && h.pslg.regions.is_empty());
    }

    #[test]
    fn overflowing_counts_are_rejected_before_any_read() {
        let m = Handle::new();
        // The pointer is valid for one pair only: the checks must fail before reading.
        let xy = [0.0; 2];
        for count in [usize::MAX, usize::MAX / 2 + 1, usize::MAX / 4] {
            let st = unsafe { idm_mesher2d_add_points(m.0, xy.as_ptr(), count, std::ptr::null()) };
            assert_eq!(st, IDM_ERR_INVALID_ARGUMENT, "count {count}");
            assert!(last_error().contains("too large"), "{}", last_error());
        }
        let ab = [0u32; 2];
        let st =
            unsafe { idm_mesher2d_add_segments(m.0, ab.as_ptr(), usize::MAX, std::ptr::null()) };
        assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
        assert!(unsafe { &*m.0 }.pslg.points.is_empty());
    }

    #[test]
    fn misaligned_input_is_rejected() {
        let m = Handle::new();
        let buf = [0.0f64; 8];
        let bad = unsafe { buf.as_ptr().cast::<u8>().add(1) }.cast::<f64>();
        let st = unsafe { idm_mesher2d_add_points(m.0, bad, 3, std::ptr::null()) };
        assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
        assert!(last_error().contains("aligned"), "{}", last_error());
    }

    #[test]
    fn free_null_is_a_no_op_and_default_null_too() {
        unsafe {
            idm_mesher2d_free(std::ptr::null_mut());
            idm_options2d_default(std::ptr::null_mut());
        }
    }

    #[test]
    fn getters_before_refine_report_no_mesh() {
        let m = Handle::new();
        load(&m, &square_with_hole());
        let mut n = 7usize;
        let mut p: *const f64 = std::ptr::null();
        let mut pu: *const u32 = std::ptr::null();
        let mut pi: *const i32 = std::ptr::null();
        unsafe {
            assert_eq!(idm_mesher2d_vertices(m.0, &mut p, &mut n), IDM_ERR_NO_MESH);
            assert!(last_error().contains("refine"), "{}", last_error());
            assert_eq!(
                idm_mesher2d_vertex_markers(m.0, &mut pi, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(
                idm_mesher2d_triangles(m.0, &mut pu, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(
                idm_mesher2d_neighbors(m.0, &mut pu, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(
                idm_mesher2d_triangle_attributes(m.0, &mut p, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(
                idm_mesher2d_segments(m.0, &mut pu, &mut pi, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(
                idm_mesher2d_counts(m.0, &mut n, std::ptr::null_mut(), std::ptr::null_mut()),
                IDM_ERR_NO_MESH
            );
            assert_eq!(idm_mesher2d_validate(m.0), IDM_ERR_NO_MESH);
        }
        // Out-parameters are untouched on failure.
        assert_eq!(n, 7);
        assert!(p.is_null() && pu.is_null() && pi.is_null());
    }

    #[test]
    fn last_error_is_cleared_on_success_and_thread_local() {
        let m = Handle::new();
        let st = unsafe { idm_mesher2d_add_holes(m.0, std::ptr::null(), 1) };
        assert_eq!(st, IDM_ERR_NULL_POINTER);
        assert!(!last_error().is_empty());
        // Another thread has its own (empty) message.
        let other = std::thread::spawn(last_error).join().unwrap();
        assert_eq!(other, "");
        assert!(!last_error().is_empty());
        let hole = [1.0, 1.0];
        assert_eq!(
            unsafe { idm_mesher2d_add_holes(m.0, hole.as_ptr(), 1) },
            IDM_OK
        );
        assert_eq!(last_error(), "");
    }

    #[test]
    fn panics_become_internal_errors() {
        let st = guard(|| panic!("boom {}", 42));
        assert_eq!(st, IDM_ERR_INTERNAL);
        let msg = last_error();
        assert!(msg.contains("boom 42") && msg.contains("internal"), "{msg}");
        let st = guard(|| std::panic::panic_any(3u8));
        assert_eq!(st, IDM_ERR_INTERNAL);
        assert!(last_error().contains("panic"), "{}", last_error());
    }

    #[test]
    fn default_options_match_the_rust_defaults() {
        let o = options(0.0, 0.0);
        let d = Options::default();
        assert_eq!(o.min_angle, d.min_angle.unwrap_or(0.0));
        assert_eq!(o.max_area, d.max_area.unwrap_or(0.0));
        assert_eq!(o.off_centers != 0, d.off_centers);
        assert_eq!(o.convex_hull != 0, d.convex_hull);
        assert_eq!(o.split_crossings != 0, d.split_crossings);
        assert_eq!(o.region_attributes != 0, d.region_attributes);
        assert_eq!(o.region_max_area != 0, d.region_max_area);
        assert_eq!(o.no_boundary_steiner != 0, d.no_boundary_steiner);
        assert_eq!(o.max_steiner < 0, d.max_steiner.is_none());
        // The documented values of the header.
        assert_eq!((o.off_centers, o.max_steiner), (1, -1));
    }

    /// The options struct as a caller built against a newer header sees it: 16 bytes of
    /// fields this library does not know after the ones it does.
    #[repr(C, align(8))]
    struct Bigger {
        o: idm_options2d,
        tail: [u8; 16],
    }

    #[test]
    fn the_thread_count_maps_and_an_older_struct_gets_the_default() {
        let mut o = options(25.0, 0.0);
        assert_eq!(o.threads, 0, "default: IDMESH_THREADS or all cores");
        let m = Handle::new();
        load(&m, &square_with_hole());
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(unsafe { &*m.0 }.opts.threads, None);
        o.threads = 2;
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(unsafe { &*m.0 }.opts.threads, Some(2));
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        o.struct_size = std::mem::offset_of!(idm_options2d, threads);
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(
            unsafe { &*m.0 }.opts.threads,
            None,
            "beyond the caller's struct"
        );
    }

    #[test]
    fn options_struct_size_is_checked_and_honoured() {
        let m = Handle::new();
        let size = std::mem::size_of::<idm_options2d>();
        let mut o = options(25.0, 0.0);
        assert_eq!(o.struct_size, size);
        // A struct that never went through `_default` (a 0.1 caller, or garbage) is refused.
        o.struct_size = 3;
        assert_eq!(
            unsafe { idm_mesher2d_set_options(m.0, &o) },
            IDM_ERR_INVALID_ARGUMENT
        );
        assert!(last_error().contains("struct_size"), "{}", last_error());
        // A newer caller's larger struct: the unknown tail is zeroed by `_default_sized` and
        // accepted while zero; a set unknown field is refused, not dropped.
        let mut b = Bigger {
            o,
            tail: [0xa5; 16],
        };
        let big = size + 16;
        unsafe { idm_options2d_default_sized(&mut b.o, big) };
        assert_eq!((b.o.struct_size, b.tail), (big, [0; 16]));
        assert_eq!(b.o.off_centers, 1);
        b.o.min_angle = 20.0;
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &b.o) }, IDM_OK);
        assert_eq!(unsafe { &*m.0 }.opts.min_angle, Some(20.0));
        b.tail[5] = 1;
        assert_eq!(
            unsafe { idm_mesher2d_set_options(m.0, &b.o) },
            IDM_ERR_UNSUPPORTED
        );
        assert!(last_error().contains("does not know"), "{}", last_error());
        assert_eq!(
            unsafe { &*m.0 }.opts.min_angle,
            Some(20.0),
            "handle unchanged"
        );
        // Too small for any version: `_default_sized` leaves the struct alone.
        let mut c = options(0.0, 0.0);
        c.min_angle = 7.0;
        unsafe { idm_options2d_default_sized(&mut c, 8) };
        assert_eq!(c.min_angle, 7.0);
    }

    #[test]
    fn options_are_translated_and_nan_rejected() {
        let m = Handle::new();
        let mut o = options(25.0, -1.0);
        o.region_attributes = 7;
        o.max_steiner = 100;
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &o) }, IDM_OK);
        let h = unsafe { &*m.0 };
        assert_eq!(h.opts.min_angle, Some(25.0));
        assert_eq!(h.opts.max_area, None);
        assert!(h.opts.region_attributes);
        assert_eq!(h.opts.max_steiner, Some(100));
        o.max_area = f64::NAN;
        assert_eq!(
            unsafe { idm_mesher2d_set_options(m.0, &o) },
            IDM_ERR_INVALID_ARGUMENT
        );
        assert!(last_error().contains("max_area"), "{}", last_error());
        assert_eq!(
            unsafe { &*m.0 }.opts.max_steiner,
            Some(100),
            "handle unchanged"
        );
        assert_eq!(
            unsafe { idm_mesher2d_set_options(m.0, std::ptr::null()) },
            IDM_ERR_NULL_POINTER
        );
        assert!(last_error().contains("`opts`"), "{}", last_error());
    }

    #[test]
    fn markers_default_per_call() {
        let m = Handle::new();
        let xy = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
        let mk = [5, 6];
        let ab = [0u32, 1, 1, 2, 2, 0];
        unsafe {
            assert_eq!(
                idm_mesher2d_add_points(m.0, xy.as_ptr(), 1, std::ptr::null()),
                IDM_OK
            );
            assert_eq!(
                idm_mesher2d_add_points(m.0, xy[2..].as_ptr(), 2, mk.as_ptr()),
                IDM_OK
            );
            assert_eq!(
                idm_mesher2d_add_segments(m.0, ab.as_ptr(), 2, mk.as_ptr()),
                IDM_OK
            );
            assert_eq!(
                idm_mesher2d_add_segments(m.0, ab[4..].as_ptr(), 1, std::ptr::null()),
                IDM_OK
            );
        }
        let h = unsafe { &*m.0 };
        assert_eq!(h.pslg.points, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(h.pslg.point_markers, vec![0, 5, 6]);
        assert_eq!(h.pslg.segments, vec![[0, 1], [1, 2], [2, 0]]);
        assert_eq!(h.pslg.segment_markers, vec![5, 6, 1]);
    }

    #[test]
    fn regions_translate_area_bounds() {
        let m = Handle::new();
        let xy = [1.0, 1.0, 2.0, 2.0, 3.0, 3.0];
        let attr = [7.0, 8.0, 9.0];
        let areas = [0.5, 0.0, -3.0];
        unsafe {
            assert_eq!(
                idm_mesher2d_add_regions(m.0, xy.as_ptr(), attr.as_ptr(), areas.as_ptr(), 3),
                IDM_OK
            );
            assert_eq!(
                idm_mesher2d_add_regions(m.0, xy.as_ptr(), attr.as_ptr(), std::ptr::null(), 1),
                IDM_OK
            );
        }
        let r = &unsafe { &*m.0 }.pslg.regions;
        assert_eq!(r.len(), 4);
        assert_eq!(r[0].point, [1.0, 1.0]);
        assert_eq!(r[0].max_area, Some(0.5));
        assert_eq!(
            (r[1].max_area, r[2].max_area, r[3].max_area),
            (None, None, None)
        );
        assert_eq!(r[2].attribute, 9.0);
        let nan = [f64::NAN];
        let st =
            unsafe { idm_mesher2d_add_regions(m.0, xy.as_ptr(), attr.as_ptr(), nan.as_ptr(), 1) };
        assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
        assert!(last_error().contains("region 4"), "{}", last_error());
    }

    #[test]
    fn version_is_the_crate_version() {
        let v = unsafe { CStr::from_ptr(idm_version()) };
        assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
    }

    #[test]
    fn none_constant_matches_the_rust_one() {
        assert_eq!(IDM_NONE, NONE);
    }

    #[test]
    fn handle_is_send() {
        fn assert_send<T: Send>() {}
        assert_send::<idm_mesher2d>();
    }

    // The tests below need the mesher itself (`triangulate`).

    #[test]
    fn refine_gives_the_rust_result() {
        let p = square_with_hole();
        let m = Handle::new();
        load(&m, &p);
        let o = options(25.0, 1.0);
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        assert_eq!(last_error(), "");
        assert_eq!(
            unsafe { idm_mesher2d_validate(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        let got = read_back(&m);
        let opts = Options {
            min_angle: Some(25.0),
            max_area: Some(1.0),
            ..Options::default()
        };
        let want = triangulate(&p, &opts).unwrap();
        assert!(want.triangles.len() > 10);
        assert_eq!(got.vertices, want.vertices);
        assert_eq!(got.vertex_markers, want.vertex_markers);
        assert_eq!(got.triangles, want.triangles);
        assert_eq!(got.neighbors, want.neighbors);
        assert_eq!(got.segments, want.segments);
        assert_eq!(got.segment_markers, want.segment_markers);
        assert!(got.triangle_attributes.is_empty());
        // Only the counts wanted.
        let mut nt = 0usize;
        let st = unsafe {
            idm_mesher2d_counts(m.0, std::ptr::null_mut(), &mut nt, std::ptr::null_mut())
        };
        assert_eq!((st, nt), (IDM_OK, want.triangles.len()));
        // Changing the input drops the mesh.
        let xy = [20.0, 20.0];
        assert_eq!(
            unsafe { idm_mesher2d_add_points(m.0, xy.as_ptr(), 1, std::ptr::null()) },
            IDM_OK
        );
        assert_eq!(unsafe { idm_mesher2d_validate(m.0) }, IDM_ERR_NO_MESH);
    }

    #[test]
    fn invalid_input_names_the_item_and_leaves_no_mesh() {
        let mut p = square_with_hole();
        let m = Handle::new();
        load(&m, &p);
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        let bad = [3u32, 17];
        assert_eq!(
            unsafe { idm_mesher2d_add_segments(m.0, bad.as_ptr(), 1, std::ptr::null()) },
            IDM_OK
        );
        assert_eq!(unsafe { idm_mesher2d_refine(m.0) }, IDM_ERR_INVALID_INPUT);
        let msg = last_error();
        assert!(msg.contains("segment 8") && msg.contains("17"), "{msg}");
        p.segments.push([3, 17]);
        p.segment_markers.push(1);
        let want = triangulate(&p, &Options::default())
            .unwrap_err()
            .to_string();
        assert_eq!(msg, want);
        assert_eq!(unsafe { idm_mesher2d_validate(m.0) }, IDM_ERR_NO_MESH);
    }

    #[test]
    fn no_boundary_steiner_keeps_boundary_segments_whole() {
        let m = Handle::new();
        load(&m, &square_with_hole());
        let mut o = options(25.0, 0.0);
        o.no_boundary_steiner = 1;
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        assert_eq!(
            unsafe { idm_mesher2d_validate(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        // Every boundary subsegment joins two input vertices.
        let Ok(mesh) = (unsafe { mesh_of(m.0) }) else {
            panic!("no mesh after a successful refine")
        };
        let n = mesh.num_input_vertices as u32;
        assert!(mesh.segments.iter().all(|s| s[0] < n && s[1] < n));
    }

    #[test]
    fn steiner_cap_gives_a_readable_incomplete_mesh() {
        let m = Handle::new();
        load(&m, &square_with_hole());
        let mut o = options(30.0, 0.01);
        o.max_steiner = 3;
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_INCOMPLETE,
            "{}",
            last_error()
        );
        assert!(last_error().contains("Steiner"), "{}", last_error());
        assert_eq!(
            unsafe { idm_mesher2d_validate(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        let got = read_back(&m);
        assert!(!got.triangles.is_empty());
        let opts = Options {
            min_angle: Some(30.0),
            max_area: Some(0.01),
            max_steiner: Some(3),
            ..Options::default()
        };
        let want = triangulate(&square_with_hole(), &opts).unwrap();
        assert!(!want.complete);
        assert_eq!(
            (&got.vertices, &got.triangles),
            (&want.vertices, &want.triangles)
        );
        // The cap bounds refinement only approximately (a split cascade may finish), but far
        // below the uncapped mesh.
        let uncapped = Options {
            max_steiner: None,
            ..opts
        };
        let full = triangulate(&square_with_hole(), &uncapped).unwrap();
        assert!(want.triangles.len() * 10 < full.triangles.len());
    }

    /// A C-style sizing test: too large when the area exceeds `*user` (a `[f64; 1]` bound
    /// followed by nothing else); counts its calls in a global so the test can see them.
    static SIZING_CALLS: AtomicUsize = AtomicUsize::new(0);

    unsafe extern "C" fn too_large(
        user: *mut c_void,
        a: *const f64,
        b: *const f64,
        c: *const f64,
        area: f64,
    ) -> i32 {
        SIZING_CALLS.fetch_add(1, Ordering::Relaxed);
        let bound = unsafe { *user.cast::<f64>() };
        // Only triangles touching the left half are constrained.
        let left = unsafe { *a < 5.0 || *b < 5.0 || *c < 5.0 };
        i32::from(left && area > bound)
    }

    #[test]
    fn c_sizing_callback_is_called_and_obeyed() {
        let m = Handle::new();
        load(&m, &square_with_hole());
        let mut bound = 0.25f64;
        let user = (&mut bound as *mut f64).cast::<c_void>();
        assert_eq!(
            unsafe { idm_mesher2d_set_sizing(m.0, Some(too_large), user) },
            IDM_OK
        );
        let before = SIZING_CALLS.load(Ordering::Relaxed);
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        assert!(
            SIZING_CALLS.load(Ordering::Relaxed) > before,
            "callback never called"
        );
        let mesh = read_back(&m);
        let area = |t: &[u32; 3]| {
            let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        };
        let left_max = mesh
            .triangles
            .iter()
            .filter(|t| t.iter().any(|&i| mesh.vertices[i as usize][0] < 5.0))
            .map(area)
            .fold(0.0, f64::max);
        assert!(
            left_max <= 0.25 * (1.0 + 1e-12),
            "left triangle of area {left_max}"
        );
        // Clearing the callback gives the unconstrained (coarser) mesh.
        let fine = mesh.triangles.len();
        assert_eq!(unsafe { idm_mesher2d_set_sizing(m.0, None, user) }, IDM_OK);
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        assert!(read_back(&m).triangles.len() < fine);
    }

    #[test]
    fn panicking_sizing_path_cannot_escape() {
        let m = Handle::new();
        load(&m, &square_with_hole());
        // Rust-side sizing closures can panic (an `extern "C"` callback cannot unwind at all):
        // install one directly and check the panic turns into a status.
        unsafe { &mut *m.0 }.opts.sizing = Some(Arc::new(|_, _, _, _| panic!("sizing exploded")));
        assert_eq!(unsafe { idm_mesher2d_refine(m.0) }, IDM_ERR_INTERNAL);
        assert!(last_error().contains("sizing exploded"), "{}", last_error());
        assert_eq!(unsafe { idm_mesher2d_validate(m.0) }, IDM_ERR_NO_MESH);
        // The handle is still usable afterwards.
        assert_eq!(
            unsafe { idm_mesher2d_set_sizing(m.0, None, std::ptr::null_mut()) },
            IDM_OK
        );
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
    }

    #[test]
    fn region_attributes_come_through() {
        let m = Handle::new();
        load(&m, &square_with_hole());
        let seed = [1.0, 1.0];
        let attr = [7.5];
        assert_eq!(
            unsafe {
                idm_mesher2d_add_regions(m.0, seed.as_ptr(), attr.as_ptr(), std::ptr::null(), 1)
            },
            IDM_OK
        );
        let mut o = options(0.0, 0.0);
        o.region_attributes = 1;
        assert_eq!(unsafe { idm_mesher2d_set_options(m.0, &o) }, IDM_OK);
        assert_eq!(
            unsafe { idm_mesher2d_refine(m.0) },
            IDM_OK,
            "{}",
            last_error()
        );
        let mesh = read_back(&m);
        assert_eq!(mesh.triangle_attributes.len(), mesh.triangles.len());
        assert!(mesh.triangle_attributes.iter().all(|&a| a == 7.5));
    }
}
