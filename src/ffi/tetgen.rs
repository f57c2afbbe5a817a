//! The part of the C ABI that TetGen's interface needs (`idm_tetgen_*`, `idm_plc3d_*` and
//! `idm_mesher3d_tetgen*`), used by the TetGen compatibility layer in `compat/tetgen`.
//!
//! * TetGen's switch strings are parsed here, by the same parser as `idmesh tetgen`
//!   ([`crate::switches::tetgen`]), into a plain struct ([`idm_tetgen_switches`]).
//! * Input files are read by idmesh's own readers ([`crate::io::tetgen::read_input`]) into an
//!   [`idm_plc3d`] whose arrays are lent to the caller.
//! * [`idm_mesher3d_tetgen`] meshes a handle as the switches ask and reports the failure with
//!   TetGen's error code; [`idm_mesher3d_write_tetgen`] writes the files TetGen's command line
//!   writes.
//!
//! The conventions of [`crate::ffi`] hold: panics caught, pointers checked, inputs copied,
//! out-parameters written only on success (except the TetGen code of
//! [`idm_mesher3d_tetgen`], which exists to describe failures), messages in `idm_last_error`.

#![allow(non_camel_case_types)]
#![deny(unsafe_op_in_unsafe_fn)]

use std::ffi::{c_char, CStr};
use std::path::Path;

use crate::error::{Error, InputError};
use crate::ffi::idm_mesher3d;
use crate::ffi::{array_ptr, check_out, guard, idm_status, input_slice, write_out, Failure};
use crate::ffi::{optional_slice, scaled};
use crate::input3d::check_plc;
use crate::io::exchange::Format;
use crate::io::tetgen::read_input;
use crate::switches::tetgen::{parse_string, renumber, resolve, write_outputs, TetSwitches};
use crate::switches::tetgen_extra::{mesh_for, tetgen_constraints, Extra, GivenMesh, Metric, Post};

/// TetGen's switches as parsed by `idm_tetgen_parse_switches` (the letter of each field is in
/// its comment). Booleans are `int32_t`, 0 false.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct idm_tetgen_switches {
    /// `p`: the input is a PLC (else a point set).
    pub plc: i32,
    /// `q`: the radius-edge bound; 0 when there is none.
    pub radius_edge: f64,
    /// `a<volume>`: the global maximum volume; 0 when there is none.
    pub max_volume: f64,
    /// `a` alone: apply the regions' volume bounds.
    pub region_volume: i32,
    /// `A`: regional attributes on the tetrahedra.
    pub region_attributes: i32,
    /// `S<n>`: the Steiner point cap; -1 when there is none.
    pub max_steiner: i64,
    /// `Y`: keep the input surface.
    pub keep_surface: i32,
    /// `M`: do not merge coplanar facets.
    pub no_merge: i32,
    /// `z`: number the output from 0.
    pub zero_based: i32,
    /// `f`: output every face.
    pub all_faces: i32,
    /// `e`: output edges.
    pub edges: i32,
    /// `n`: 1 for neighbours, 2 (`nn`) for the face-to-tetrahedra adjacency too.
    pub neighbors: i32,
    /// `N`: write no `.node` file.
    pub no_node: i32,
    /// `E`: write no `.ele` file.
    pub no_ele: i32,
    /// `F`: write no `.face` file.
    pub no_face: i32,
    /// `B`: no boundary markers in the output.
    pub no_markers: i32,
    /// `I`: no iteration number in output names.
    pub no_iteration: i32,
    /// `d`: only check the PLC for intersections.
    pub detect: i32,
    /// `C`: check the final mesh.
    pub check: i32,
    /// `Q`: quiet.
    pub quiet: i32,
    /// `V`: verbose.
    pub verbose: i32,
    /// `k`: also write a legacy VTK file.
    pub vtk: i32,
    /// `g`: also write a Medit `.mesh` file.
    pub medit: i32,
    /// `r`: refine the mesh given with `idm_tetgen_extra_set_mesh`.
    pub refine: i32,
    /// `i`: insert the points given with `idm_tetgen_extra_set_addin`.
    pub insert_points: i32,
    /// `m`: sizes from `idm_tetgen_extra_set_metric`.
    pub metric: i32,
    /// `o2`: second-order (10-node) tetrahedra.
    pub order2: i32,
    /// `c`: mesh the convex hull of the input, keeping the PLC inside it.
    pub convex_hull: i32,
    /// `T<tol>`: the relative tolerance for merging nearly coplanar facets (`T` alone: 1e-8);
    /// 0 when there is none (coplanarity decided exactly).
    pub coplanar_tolerance: f64,
    /// `O<level>`: mesh optimisation passes (flips and smoothing; the mesh is then not
    /// Delaunay), 0 to 10; 0 when `O` is not given (idmesh's default: no optimisation).
    pub optimize_level: i32,
    /// `O<level>/<scheme>`: the optimisation's operations, bits 1 flips, 2 smoothing, 4 sliver
    /// splitting by new points (idmesh's Delaunay sliver removal); 7 when not given.
    pub optimize_scheme: i32,
    /// `o/<angle>`: the optimisation's maximum dihedral angle target, degrees; 165 when not
    /// given.
    pub optimize_max_dihedral: f64,
    /// `q<ratio>/<angle>`: the minimum dihedral angle sliver removal aims at, degrees (0 turns
    /// it off); negative when no angle was given (the library's default target).
    pub min_dihedral: f64,
}

impl From<&TetSwitches> for idm_tetgen_switches {
    fn from(s: &TetSwitches) -> Self {
        idm_tetgen_switches {
            plc: s.plc.into(),
            radius_edge: s.radius_edge.unwrap_or(0.0),
            max_volume: s.max_volume.unwrap_or(0.0),
            region_volume: s.region_volume.into(),
            region_attributes: s.region_attributes.into(),
            max_steiner: s
                .max_steiner
                .map_or(-1, |n| i64::try_from(n).unwrap_or(i64::MAX)),
            keep_surface: s.keep_surface.into(),
            no_merge: s.no_merge.into(),
            zero_based: s.zero_based.into(),
            all_faces: s.all_faces.into(),
            edges: s.edges.into(),
            neighbors: i32::from(s.neighbors) + i32::from(s.face_adjacency),
            no_node: s.no_node.into(),
            no_ele: s.no_ele.into(),
            no_face: s.no_face.into(),
            no_markers: s.no_markers.into(),
            no_iteration: s.no_iteration.into(),
            detect: s.detect.into(),
            check: s.check.into(),
            quiet: s.quiet.into(),
            verbose: s.verbose.into(),
            vtk: s.formats.contains(&Format::Vtk).into(),
            medit: s.formats.contains(&Format::Medit).into(),
            refine: s.refine.into(),
            insert_points: s.insert_points.into(),
            metric: s.metric.into(),
            order2: s.order2.into(),
            convex_hull: s.convex_hull.into(),
            coplanar_tolerance: s.coplanar_tolerance.unwrap_or(0.0),
            optimize_level: s
                .optimize_level
                .map_or(0, |l| l.min(i32::MAX as u32) as i32),
            optimize_scheme: s.optimize_scheme.unwrap_or(crate::mesh3d::DEFAULT_SCHEME) as i32,
            optimize_max_dihedral: s
                .optimize_max_dihedral
                .unwrap_or(crate::mesh3d::DEFAULT_MAX_DIHEDRAL),
            min_dihedral: s.min_dihedral.unwrap_or(-1.0),
        }
    }
}

impl idm_tetgen_switches {
    /// Back to the parser's form; NaN bounds are refused.
    fn to_switches(self) -> Result<TetSwitches, Failure> {
        if self.radius_edge.is_nan() || self.max_volume.is_nan() || self.coplanar_tolerance.is_nan()
        {
            return Err(Failure::invalid("a switch value (q, a or T) is NaN"));
        }
        if self.min_dihedral.is_nan() {
            return Err(Failure::invalid("min_dihedral (q/) is NaN"));
        }
        if self.optimize_max_dihedral.is_nan() {
            return Err(Failure::invalid("optimize_max_dihedral (o/) is NaN"));
        }
        let (optimize_level, optimize_scheme) =
            crate::ffi::mesh3d::optimize_ints(self.optimize_level, self.optimize_scheme)?;
        let positive = |x: f64| (x > 0.0).then_some(x);
        Ok(TetSwitches {
            plc: self.plc != 0,
            radius_edge: positive(self.radius_edge),
            min_dihedral: (self.min_dihedral >= 0.0).then_some(self.min_dihedral),
            max_volume: positive(self.max_volume),
            region_volume: self.region_volume != 0,
            region_attributes: self.region_attributes != 0,
            max_steiner: u64::try_from(self.max_steiner).ok(),
            keep_surface: self.keep_surface != 0,
            no_merge: self.no_merge != 0,
            coplanar_tolerance: positive(self.coplanar_tolerance),
            zero_based: self.zero_based != 0,
            all_faces: self.all_faces != 0,
            edges: self.edges != 0,
            neighbors: self.neighbors > 0,
            face_adjacency: self.neighbors > 1,
            no_node: self.no_node != 0,
            no_ele: self.no_ele != 0,
            no_face: self.no_face != 0,
            no_markers: self.no_markers != 0,
            no_iteration: self.no_iteration != 0,
            detect: self.detect != 0,
            check: self.check != 0,
            quiet: self.quiet != 0,
            verbose: self.verbose != 0,
            formats: [(self.vtk, Format::Vtk), (self.medit, Format::Medit)]
                .into_iter()
                .filter(|&(on, _)| on != 0)
                .map(|(_, f)| f)
                .collect(),
            refine: self.refine != 0,
            insert_points: self.insert_points != 0,
            metric: self.metric != 0,
            order2: self.order2 != 0,
            convex_hull: self.convex_hull != 0,
            optimize_level: (optimize_level > 0).then_some(optimize_level),
            optimize_scheme: Some(optimize_scheme),
            optimize_max_dihedral: Some(self.optimize_max_dihedral),
        })
    }
}

/// Borrows a NUL-terminated UTF-8 string argument.
///
/// # Safety
/// `s` must be NULL (an error) or a NUL-terminated string unchanged during the call.
unsafe fn c_str<'a>(s: *const c_char, what: &str) -> Result<&'a str, Failure> {
    if s.is_null() {
        return Err(Failure::null(what));
    }
    // SAFETY: the caller's contract.
    unsafe { CStr::from_ptr(s) }
        .to_str()
        .map_err(|_| Failure::invalid(format!("argument `{what}` is not UTF-8")))
}

/// Reads the switches of `*sw` (checked pointer).
///
/// # Safety
/// `sw` must be NULL (an error) or point to an `idm_tetgen_switches`.
unsafe fn switches_of(sw: *const idm_tetgen_switches) -> Result<TetSwitches, Failure> {
    // SAFETY: the caller's contract, checked as far as possible.
    unsafe { input_slice(sw, 1, "sw") }?[0].to_switches()
}

/// Parses a TetGen switch string such as `"pq1.414a0.1nn"`: whitespace-separated groups, each
/// with or without a leading `-`, exactly as `idmesh tetgen` reads its switches (implications
/// included: `a<volume>` gives `q`, `q` and `d` give `p`). A switch idmesh does not implement
/// is `IDM_ERR_UNSUPPORTED`, an unknown or malformed one `IDM_ERR_INVALID_ARGUMENT`; either way
/// the message names it and `*out` is untouched.
///
/// # Safety
/// `switches` must be a NUL-terminated string; `out` valid for writing the struct.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_parse_switches(
    switches: *const c_char,
    out: *mut idm_tetgen_switches,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let text = unsafe { c_str(switches, "switches") }?;
        check_out(out, "out")?;
        let sw = parse_string(text).map_err(|e| {
            let status = if e.contains("not supported") {
                idm_status::IDM_ERR_UNSUPPORTED
            } else {
                idm_status::IDM_ERR_INVALID_ARGUMENT
            };
            Failure::new(status, e)
        })?;
        unsafe { out.write((&sw).into()) };
        Ok(())
    })
}

/// Copies `text` with its NUL into `buf` of `cap` bytes, or fails naming `what`.
///
/// # Safety
/// `buf` must be valid for `cap` bytes (checked non-NULL by the caller).
unsafe fn copy_c(text: &str, buf: *mut c_char, cap: usize, what: &str) -> Result<(), Failure> {
    if text.len() >= cap || text.contains('\0') {
        return Err(Failure::invalid(format!(
            "{what} '{text}' does not fit in {cap} bytes"
        )));
    }
    // SAFETY: the caller's contract; `text.len() + 1 <= cap`.
    unsafe {
        std::ptr::copy_nonoverlapping(text.as_ptr().cast::<c_char>(), buf, text.len());
        buf.add(text.len()).write(0);
    }
    Ok(())
}

/// Resolves a file argument as `idmesh tetgen` (and TetGen's command line) does: `input` gets
/// the file to read (a known extension names the format; without one `FILE.poly`, or
/// `FILE.smesh` when only that exists, with `p`, else `FILE.node`), `out_stem` the output name
/// without extension (`FILE.1`, or `FILE` with `I`), `*plc` whether the input is a PLC. Both
/// buffers hold `cap` bytes; a name that does not fit is an error.
///
/// # Safety
/// `file` a NUL-terminated string, `sw` an `idm_tetgen_switches`, `input` and `out_stem`
/// valid for `cap` bytes, `plc` NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_resolve(
    file: *const c_char,
    sw: *const idm_tetgen_switches,
    input: *mut c_char,
    out_stem: *mut c_char,
    cap: usize,
    plc: *mut i32,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let file = unsafe { c_str(file, "file") }?;
        let sw = unsafe { switches_of(sw) }?;
        check_out(input, "input")?;
        check_out(out_stem, "out_stem")?;
        if !plc.is_null() {
            check_out(plc, "plc")?;
        }
        let files = resolve(file, &sw);
        if files.input.len() >= cap || files.out_stem.len() >= cap {
            return Err(Failure::invalid(format!(
                "file name '{}' does not fit in {cap} bytes",
                files.input
            )));
        }
        unsafe {
            copy_c(&files.input, input, cap, "input file name")?;
            copy_c(&files.out_stem, out_stem, cap, "output file name")?;
            write_out(plc, files.plc.into());
        }
        Ok(())
    })
}

/// An input file read by `idm_tetgen_read`, in flat arrays. Free with `idm_plc3d_free`.
pub struct idm_plc3d {
    base: u32,
    points: Vec<f64>,
    point_markers: Vec<i32>,
    num_point_attributes: usize,
    point_attributes: Vec<f64>,
    facet_polygon_offsets: Vec<usize>,
    polygon_offsets: Vec<usize>,
    polygon_indices: Vec<u32>,
    facet_hole_offsets: Vec<usize>,
    facet_holes: Vec<f64>,
    facet_markers: Vec<i32>,
    holes: Vec<f64>,
    regions: Vec<f64>,
}

/// The arrays of an `idm_plc3d`, lent (valid until `idm_plc3d_free`). Indices are 0-based;
/// `base` is the numbering the file used. An empty array is NULL. Facet `f` has the polygons
/// `facet_polygon_offsets[f] .. facet_polygon_offsets[f+1]`, polygon `k` the vertices
/// `polygon_indices[polygon_offsets[k] .. polygon_offsets[k+1]]` and facet `f` the hole
/// seeds `facet_holes[3*facet_hole_offsets[f] ..]` up to the next offset. Free segments of the
/// file come last as facets with one 2-vertex polygon.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct idm_plc3d_view {
    /// The first index of the file (0 or 1).
    pub base: u32,
    /// Number of points.
    pub num_points: usize,
    /// 3 doubles per point.
    pub points: *const f64,
    /// One marker per point, or NULL when the file has none.
    pub point_markers: *const i32,
    /// Attributes per point.
    pub num_point_attributes: usize,
    /// `num_point_attributes` doubles per point.
    pub point_attributes: *const f64,
    /// Number of facets.
    pub num_facets: usize,
    /// `num_facets + 1` offsets into the polygons.
    pub facet_polygon_offsets: *const usize,
    /// One more offset than there are polygons, into `polygon_indices`.
    pub polygon_offsets: *const usize,
    /// The polygons' vertex indices.
    pub polygon_indices: *const u32,
    /// `num_facets + 1` offsets into the facet hole seeds (counted in seeds).
    pub facet_hole_offsets: *const usize,
    /// 3 doubles per facet hole seed.
    pub facet_holes: *const f64,
    /// One marker per facet.
    pub facet_markers: *const i32,
    /// Number of volume hole seeds.
    pub num_holes: usize,
    /// 3 doubles per hole seed.
    pub holes: *const f64,
    /// Number of regions.
    pub num_regions: usize,
    /// 5 doubles per region: x, y, z, attribute, maximum volume (-1 for none).
    pub regions: *const f64,
}

/// Reads an input file with idmesh's readers (`.node`, `.poly`, `.smesh`, `.off`, `.stl`,
/// `.ply`, `.mesh`; the extension chooses) into `*out`. Errors name the file and line.
///
/// # Safety
/// `path` a NUL-terminated string; `out` valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_read(
    path: *const c_char,
    out: *mut *mut idm_plc3d,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let path = unsafe { c_str(path, "path") }?;
        check_out(out, "out")?;
        let input = read_input(Path::new(path))
            .map_err(|e| Failure::new(idm_status::IDM_ERR_INVALID_INPUT, e.to_string()))?;
        let p = plc3d_of(&input);
        // SAFETY: checked above.
        unsafe { out.write(Box::into_raw(Box::new(p))) };
        Ok(())
    })
}

/// Parses the text of a `.node` file (header line included) with idmesh's reader into `*out`,
/// as `idm_tetgen_read` reads a file; `name` names it in errors. For readers that have the
/// lines already, such as the TetGen shim's `tetgenio::load_node_call`.
///
/// # Safety
/// `text` and `name` NUL-terminated strings; `out` valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_parse_node(
    text: *const c_char,
    name: *const c_char,
    out: *mut *mut idm_plc3d,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let text = unsafe { c_str(text, "text") }?;
        let name = unsafe { c_str(name, "name") }?;
        check_out(out, "out")?;
        let input = crate::io::tetgen::parse_node(text, name)
            .map_err(|e| Failure::new(idm_status::IDM_ERR_INVALID_INPUT, e.to_string()))?;
        let p = plc3d_of(&input);
        // SAFETY: checked above.
        unsafe { out.write(Box::into_raw(Box::new(p))) };
        Ok(())
    })
}

/// The C form of a read input: points, facets (segments as 2-vertex facets), holes, regions.
fn plc3d_of(input: &crate::io::tetgen::TetgenInput) -> idm_plc3d {
    let plc = &input.plc;
    let mut p = idm_plc3d {
        base: input.base,
        points: plc.points.iter().flatten().copied().collect(),
        point_markers: plc.point_markers.clone(),
        num_point_attributes: input.num_point_attributes,
        point_attributes: input.point_attributes.clone(),
        facet_polygon_offsets: vec![0],
        polygon_offsets: vec![0],
        polygon_indices: Vec::new(),
        facet_hole_offsets: vec![0],
        facet_holes: Vec::new(),
        facet_markers: Vec::new(),
        holes: plc.holes.iter().flatten().copied().collect(),
        regions: plc
            .regions
            .iter()
            .flat_map(|r| {
                let [x, y, z] = r.point;
                [x, y, z, r.attribute, r.max_volume.unwrap_or(-1.0)]
            })
            .collect(),
    };
    let segments = plc.segments.iter().zip(
        plc.segment_markers
            .iter()
            .copied()
            .chain(std::iter::repeat(0)),
    );
    let facets = plc
        .facets
        .iter()
        .map(|f| (f.polygons.clone(), f.holes.as_slice(), f.marker))
        .chain(segments.map(|(s, m)| (vec![s.to_vec()], &[][..], m)));
    for (polygons, holes, marker) in facets {
        for poly in &polygons {
            p.polygon_indices.extend_from_slice(poly);
            p.polygon_offsets.push(p.polygon_indices.len());
        }
        p.facet_polygon_offsets.push(p.polygon_offsets.len() - 1);
        p.facet_holes.extend(holes.iter().flatten());
        p.facet_hole_offsets.push(p.facet_holes.len() / 3);
        p.facet_markers.push(marker);
    }
    p
}

/// Lends the arrays of `p` in `*out`.
///
/// # Safety
/// `p` a live `idm_plc3d`; `out` valid for writing the struct.
#[no_mangle]
pub unsafe extern "C" fn idm_plc3d_arrays(
    p: *const idm_plc3d,
    out: *mut idm_plc3d_view,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let p = unsafe { p.as_ref() }.ok_or_else(|| Failure::null("p"))?;
        check_out(out, "out")?;
        let view = idm_plc3d_view {
            base: p.base,
            num_points: p.points.len() / 3,
            points: array_ptr(&p.points),
            point_markers: array_ptr(&p.point_markers),
            num_point_attributes: p.num_point_attributes,
            point_attributes: array_ptr(&p.point_attributes),
            num_facets: p.facet_markers.len(),
            facet_polygon_offsets: p.facet_polygon_offsets.as_ptr(),
            polygon_offsets: p.polygon_offsets.as_ptr(),
            polygon_indices: array_ptr(&p.polygon_indices),
            facet_hole_offsets: p.facet_hole_offsets.as_ptr(),
            facet_holes: array_ptr(&p.facet_holes),
            facet_markers: array_ptr(&p.facet_markers),
            num_holes: p.holes.len() / 3,
            holes: array_ptr(&p.holes),
            num_regions: p.regions.len() / 5,
            regions: array_ptr(&p.regions),
        };
        unsafe { out.write(view) };
        Ok(())
    })
}

/// Records `message` as this thread's last error and returns `IDM_ERR_INVALID_INPUT`: how the
/// TetGen layer reports what it refuses itself (input idmesh does not implement, such as point
/// attributes), so that `idm_last_error` explains every failure. NULL records an empty message.
///
/// # Safety
/// `message` NULL or a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_report(message: *const c_char) -> idm_status {
    guard(|| {
        let text = if message.is_null() {
            ""
        } else {
            // SAFETY: the caller's contract.
            unsafe { c_str(message, "message") }?
        };
        Err(Failure::new(idm_status::IDM_ERR_INVALID_INPUT, text))
    })
}

/// Frees an `idm_plc3d`. NULL is a no-op.
///
/// # Safety
/// `p` NULL or from `idm_tetgen_read`, not freed before.
#[no_mangle]
pub unsafe extern "C" fn idm_plc3d_free(p: *mut idm_plc3d) {
    if !p.is_null() {
        // Plain vectors: dropping them cannot panic.
        // SAFETY: the caller's contract.
        drop(unsafe { Box::from_raw(p) });
    }
}

/// TetGen's error code for a failure: 3 for intersecting input, 1 for exhausted memory, 2 for
/// a bug, 10 for any other input error.
fn tetgen_code(e: &Error) -> i32 {
    use InputError::*;
    match e {
        Error::Input(
            CrossingSegments { .. }
            | SelfIntersectingFacet { .. }
            | SegmentCrossesFacet { .. }
            | FacetsIntersect { .. }
            | VertexOnFacet { .. }
            | PointTooCloseToFacet { .. }
            | VertexOnSegment { .. },
        ) => 3,
        Error::Internal(m) if m.contains("out of memory") => 1,
        Error::Internal(_) => 2,
        _ => 10,
    }
}

/// Meshes the handle's input as TetGen does for the switches `*sw`: with `p` the PLC is
/// refined (`idm_mesher3d_refine` with the options the switches ask for, coplanar facets merged
/// unless `M`), without it the points are tetrahedralized (`idm_mesher3d_delaunay`); with `r`
/// the mesh given in `extra` is remeshed, with `i` and `m` its points and sizes are used (see
/// the module docs of `switches::tetgen_extra`); with `d` the PLC is only checked and no mesh
/// is made; with `C` the mesh is validated. The switches' options replace the handle's (its
/// sizing and progress callbacks are kept). `extra` (NULL: none) also receives what is output beside the mesh
/// (`o2` nodes, point attributes; see `idm_tetgen_extra_output`). `*tetgen_code` (when not
/// NULL) gets TetGen's code for the outcome, also on failure: 0 success (including
/// `IDM_INCOMPLETE`, a mesh stopped at the `S` cap), 3 intersecting input, 10 other input
/// errors, 2 internal errors, 1 out of memory. Items named in input error messages are
/// numbered from `base` (the caller's `firstnumber`).
///
/// # Safety
/// `m` a live handle; `sw` an `idm_tetgen_switches`; `extra` NULL or a live
/// `idm_tetgen_extra`; `tetgen_code` NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_tetgen(
    m: *mut idm_mesher3d,
    sw: *const idm_tetgen_switches,
    base: u32,
    extra: *mut idm_tetgen_extra,
    tetgen_code: *mut i32,
) -> idm_status {
    let mut code = 2;
    let status = guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let m = unsafe { m.as_mut() }.ok_or_else(|| Failure::null("m"))?;
        let sw = unsafe { switches_of(sw) }?;
        let mut extra = unsafe { extra.as_mut() };
        code = 10;
        m.mesh = None;
        let (sizing, progress) = (m.opts.sizing.take(), m.opts.progress.take());
        m.opts = sw.options();
        (m.opts.sizing, m.opts.progress) = (sizing, progress);
        let mut fail = |e: Error| {
            code = self::tetgen_code(&e);
            match e {
                Error::Input(ie) => Failure::from(Error::Input(renumber(&ie, base as usize))),
                other => Failure::from(other),
            }
        };
        if sw.detect {
            check_plc(&m.plc).map_err(&mut fail)?;
            code = 0;
            return Ok(());
        }
        let none = Extra::default();
        let input = extra.as_ref().map_or(&none, |e| &e.input);
        let (mesh, post) = mesh_for(&sw, &m.plc, m.opts.clone(), input).map_err(&mut fail)?;
        if sw.check {
            mesh.validate().map_err(|e| {
                code = 2;
                Failure::new(
                    idm_status::IDM_ERR_INTERNAL,
                    format!("mesh validation failed: {e}"),
                )
            })?;
        }
        let (complete, steiner) = (mesh.complete, mesh.steiner_points);
        m.mesh = Some(mesh);
        if let Some(e) = extra.as_mut() {
            e.post = post;
        }
        code = 0;
        if complete {
            Ok(())
        } else {
            Err(Failure::new(
                idm_status::IDM_INCOMPLETE,
                format!(
                    "refinement stopped at the Steiner point cap after {steiner} Steiner \
                     points: the mesh is valid but does not meet every bound"
                ),
            ))
        }
    });
    if !tetgen_code.is_null() && tetgen_code.is_aligned() {
        // SAFETY: the caller's contract.
        unsafe {
            tetgen_code.write(if status == idm_status::IDM_OK {
                0
            } else {
                code
            })
        };
    }
    status
}

/// Writes the handle's mesh to the files TetGen's command line writes for `*sw`:
/// `out_stem.node`, `.ele`, `.face` (unless `N`, `E`, `F`), `.edge` with `e`, `.neigh` with
/// `n`, numbered from `base` (0 or 1). Face and edge markers are written when `plc` is
/// nonzero, vertex markers when `node_markers` is, both unless `B`. The `o2` nodes and point
/// attributes that `idm_mesher3d_tetgen` left in `extra` (NULL: none) are written too.
/// "Writing ..." lines are printed unless `Q`.
///
/// # Safety
/// `m` a live handle with a mesh; `out_stem` a NUL-terminated string; `sw` a switches struct;
/// `extra` NULL or a live `idm_tetgen_extra`.
#[no_mangle]
pub unsafe extern "C" fn idm_mesher3d_write_tetgen(
    m: *const idm_mesher3d,
    out_stem: *const c_char,
    sw: *const idm_tetgen_switches,
    plc: i32,
    node_markers: i32,
    base: u32,
    extra: *const idm_tetgen_extra,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let m = unsafe { m.as_ref() }.ok_or_else(|| Failure::null("m"))?;
        let mesh = m.mesh.as_ref().ok_or_else(|| {
            Failure::new(
                idm_status::IDM_ERR_NO_MESH,
                "no mesh: call idm_mesher3d_tetgen first",
            )
        })?;
        let stem = unsafe { c_str(out_stem, "out_stem") }?;
        let sw = unsafe { switches_of(sw) }?;
        if base > 1 {
            return Err(Failure::invalid(format!("base is {base}, must be 0 or 1")));
        }
        let none = Post::default();
        let post = unsafe { extra.as_ref() }.map_or(&none, |e| &e.post);
        write_outputs(&sw, stem, plc != 0, node_markers != 0, mesh, post, base)
            .map_err(|e| Failure::new(idm_status::IDM_ERR_INVALID_INPUT, e))
    })
}

/// What TetGen's `r`, `i`, `m` and point attributes bring beyond the PLC of an
/// `idm_mesher3d` (inputs), and what `idm_mesher3d_tetgen` outputs beside the mesh (`o2`
/// nodes, point attributes). Create with `idm_tetgen_extra_new`, free with
/// `idm_tetgen_extra_free`.
#[derive(Default)]
pub struct idm_tetgen_extra {
    input: Extra,
    post: Post,
}

/// Creates an empty `idm_tetgen_extra` in `*out`.
///
/// # Safety
/// `out` valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_extra_new(out: *mut *mut idm_tetgen_extra) -> idm_status {
    guard(|| {
        check_out(out, "out")?;
        // SAFETY: checked above.
        unsafe { out.write(Box::into_raw(Box::default())) };
        Ok(())
    })
}

/// Frees an `idm_tetgen_extra`. NULL is a no-op.
///
/// # Safety
/// `e` NULL or from `idm_tetgen_extra_new`, not freed before.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_extra_free(e: *mut idm_tetgen_extra) {
    if !e.is_null() {
        // SAFETY: the caller's contract; dropping plain vectors cannot panic.
        drop(unsafe { Box::from_raw(e) });
    }
}

/// Reads `count` simplices of `corners` indices each (the first `K` used), numbered from
/// `base`, as 0-based arrays.
///
/// # Safety
/// `ptr` NULL (only with `count` 0) or valid for `count * corners` values.
unsafe fn simplices<const K: usize>(
    ptr: *const i32,
    count: usize,
    corners: usize,
    base: u32,
    what: &str,
) -> Result<Vec<[u32; K]>, Failure> {
    if corners < K {
        return Err(Failure::invalid(format!(
            "`{what}`: {corners} corners per item, at least {K} needed"
        )));
    }
    // SAFETY: the caller's contract.
    let flat = unsafe { input_slice(ptr, scaled(count, corners, what)?, what) }?;
    flat.chunks_exact(corners)
        .enumerate()
        .map(|(i, c)| {
            let mut out = [0u32; K];
            for (o, &v) in out.iter_mut().zip(c) {
                *o = u32::try_from(i64::from(v) - i64::from(base)).map_err(|_| {
                    Failure::invalid(format!("`{what}`: item {i} has the index {v} below {base}"))
                })?;
            }
            Ok(out)
        })
        .collect()
}

/// Gives the mesh to refine with `r` (TetGen's `tetrahedronlist`, `tetrahedronattributelist`,
/// `tetrahedronvolumelist`, `trifacelist`, `trifacemarkerlist`), indices numbered from `base`
/// into the handle's points: `num_tets` tetrahedra of `corners` nodes (the first 4 used),
/// `num_attributes` attributes per tetrahedron (the first used; NULL with 0), one volume bound
/// per tetrahedron or NULL, `num_faces` triangles with markers (NULL: 0). Replaces what was
/// given before.
///
/// # Safety
/// Every non-NULL pointer valid for the stated number of values.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_extra_set_mesh(
    e: *mut idm_tetgen_extra,
    tets: *const i32,
    num_tets: usize,
    corners: usize,
    attributes: *const f64,
    num_attributes: usize,
    volumes: *const f64,
    faces: *const i32,
    face_markers: *const i32,
    num_faces: usize,
    base: u32,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let e = unsafe { e.as_mut() }.ok_or_else(|| Failure::null("e"))?;
        let tets = unsafe { simplices::<4>(tets, num_tets, corners, base, "tets") }?;
        let attrs = unsafe {
            input_slice(
                attributes,
                scaled(num_tets, num_attributes, "num_attributes")?,
                "attributes",
            )
        }?;
        let attributes = if num_attributes == 0 {
            Vec::new()
        } else {
            attrs.iter().step_by(num_attributes).copied().collect()
        };
        let volumes = unsafe { optional_slice(volumes, num_tets, "volumes") }?
            .map(<[f64]>::to_vec)
            .unwrap_or_default();
        let faces = unsafe { simplices::<3>(faces, num_faces, 3, base, "faces") }?;
        let face_markers = unsafe { optional_slice(face_markers, num_faces, "face_markers") }?
            .map(<[i32]>::to_vec)
            .unwrap_or_default();
        e.input.given = Some(GivenMesh {
            tets,
            attributes,
            volumes,
            faces,
            face_markers,
        });
        Ok(())
    })
}

/// Gives TetGen's facet and segment constraints: `facets` holds `num_facets` pairs (facet
/// marker, maximum area) and `segments` holds `num_segments` triples (endpoint, endpoint,
/// maximum length), points numbered from `base`, all doubles as in `tetgenio`'s
/// `facetconstraintlist` and `segmentconstraintlist` (NULL with a count of 0). They are
/// applied by `idm_mesher3d_tetgen` when the switches refine (`q` or `a`), as in TetGen.
/// Markers and indices must be whole numbers, bounds positive. Replaces what was given before.
///
/// # Safety
/// Every non-NULL pointer valid for the stated number of values.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_extra_set_constraints(
    e: *mut idm_tetgen_extra,
    facets: *const f64,
    num_facets: usize,
    segments: *const f64,
    num_segments: usize,
    base: u32,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let e = unsafe { e.as_mut() }.ok_or_else(|| Failure::null("e"))?;
        let f = unsafe { input_slice(facets, scaled(num_facets, 2, "num_facets")?, "facets") }?;
        let s = unsafe {
            input_slice(
                segments,
                scaled(num_segments, 3, "num_segments")?,
                "segments",
            )
        }?;
        if base > 1 {
            return Err(Failure::invalid(format!("base is {base}, must be 0 or 1")));
        }
        e.input.bounds = tetgen_constraints(f, s, base).map_err(Failure::invalid)?;
        Ok(())
    })
}

/// Gives the points to insert with `i` (TetGen's `addin->pointlist`): `num_points` points of
/// 3 doubles. Replaces what was given before.
///
/// # Safety
/// `points` valid for `3 * num_points` doubles.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_extra_set_addin(
    e: *mut idm_tetgen_extra,
    points: *const f64,
    num_points: usize,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let e = unsafe { e.as_mut() }.ok_or_else(|| Failure::null("e"))?;
        let p = unsafe { input_slice(points, scaled(num_points, 3, "num_points")?, "points") }?;
        reject_nan_points(p)?;
        e.input.addin = p.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        Ok(())
    })
}

fn reject_nan_points(p: &[f64]) -> Result<(), Failure> {
    match p.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(Failure::invalid(format!(
            "point {} has a coordinate that is not finite",
            i / 3
        ))),
        None => Ok(()),
    }
}

/// Gives the sizes for `m` (TetGen's `pointmtrlist` with `numberofpointmtrs` 1): a background
/// mesh of `num_points` points (3 doubles each) with `sizes_per_point` values per point (only
/// 1 is supported: an isotropic size; 0 or less means no bound there) and `num_tets`
/// tetrahedra of `corners` nodes numbered from `base` (NULL with 0: the Delaunay
/// tetrahedralization of the points, or with `r` the mesh being refined when the points are
/// its points). Replaces what was given before.
///
/// # Safety
/// Every non-NULL pointer valid for the stated number of values.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_extra_set_metric(
    e: *mut idm_tetgen_extra,
    points: *const f64,
    num_points: usize,
    sizes: *const f64,
    sizes_per_point: usize,
    tets: *const i32,
    num_tets: usize,
    corners: usize,
    base: u32,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let e = unsafe { e.as_mut() }.ok_or_else(|| Failure::null("e"))?;
        if sizes_per_point != 1 {
            return Err(Failure::new(
                idm_status::IDM_ERR_UNSUPPORTED,
                format!(
                    "{sizes_per_point} metric values per point: only isotropic sizes (1 per \
                     point) are supported"
                ),
            ));
        }
        let p = unsafe { input_slice(points, scaled(num_points, 3, "num_points")?, "points") }?;
        reject_nan_points(p)?;
        let s = unsafe { input_slice(sizes, num_points, "sizes") }?;
        let tets = if num_tets == 0 {
            Vec::new()
        } else {
            unsafe { simplices::<4>(tets, num_tets, corners, base, "tets") }?
        };
        e.input.metric = Some(Metric {
            points: p.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
            tets,
            sizes: s.to_vec(),
        });
        Ok(())
    })
}

/// Gives `num_attributes` attributes per input point (TetGen's `pointattributelist`) for
/// `num_points` points: copied to the input points of the output and interpolated at the
/// others (see `idm_tetgen_extra_output`). Replaces what was given before.
///
/// # Safety
/// `attributes` valid for `num_points * num_attributes` doubles.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_extra_set_point_attributes(
    e: *mut idm_tetgen_extra,
    attributes: *const f64,
    num_points: usize,
    num_attributes: usize,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let e = unsafe { e.as_mut() }.ok_or_else(|| Failure::null("e"))?;
        let n = scaled(num_points, num_attributes, "num_attributes")?;
        let a = unsafe { input_slice(attributes, n, "attributes") }?;
        e.input.num_point_attributes = num_attributes;
        e.input.point_attributes = a.to_vec();
        Ok(())
    })
}

/// What `idm_mesher3d_tetgen` output beside the mesh, lent until the next call on the
/// `idm_tetgen_extra`. An empty array is NULL.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct idm_tetgen_extra_view {
    /// Number of `o2` nodes (after the mesh's vertices); 0 without `o2`.
    pub num_order2_nodes: usize,
    /// 3 doubles per `o2` node.
    pub order2_nodes: *const f64,
    /// With `o2`: 10 nodes per tetrahedron (0-based; corners, then the nodes on the edges
    /// (2,3), (0,3), (0,1), (1,2), (1,3), (0,2), TetGen 1.5's order); else NULL.
    pub tets10: *const u32,
    /// Attributes per output point; 0 when no point attributes were given.
    pub num_point_attributes: usize,
    /// `num_point_attributes` per output point (vertices, then `o2` nodes).
    pub point_attributes: *const f64,
}

/// Lends what the last `idm_mesher3d_tetgen` call with `e` output beside the mesh.
///
/// # Safety
/// `e` a live `idm_tetgen_extra`; `out` valid for writing the struct.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_extra_output(
    e: *const idm_tetgen_extra,
    out: *mut idm_tetgen_extra_view,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let e = unsafe { e.as_ref() }.ok_or_else(|| Failure::null("e"))?;
        check_out(out, "out")?;
        let (nodes, tets): (&[[f64; 3]], &[[u32; 10]]) = match &e.post.order2 {
            Some((n, t)) => (n, t),
            None => (&[], &[]),
        };
        let view = idm_tetgen_extra_view {
            num_order2_nodes: nodes.len(),
            order2_nodes: array_ptr(nodes),
            tets10: array_ptr(tets),
            num_point_attributes: e.post.num_point_attributes,
            point_attributes: array_ptr(&e.post.point_attributes),
        };
        unsafe { out.write(view) };
        Ok(())
    })
}

/// Items read from a TetGen mesh file by `idm_tetgen_read_items`. Free with
/// `idm_tetgen_items_free`.
#[derive(Default)]
pub struct idm_tetgen_items {
    per_item: usize,
    num_attributes: usize,
    indices: Vec<i32>,
    attributes: Vec<f64>,
    markers: Vec<i32>,
    values: Vec<f64>,
}

/// The arrays of an `idm_tetgen_items`, lent until `idm_tetgen_items_free`. An empty array
/// is NULL.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct idm_tetgen_items_view {
    /// Number of items (tetrahedra, faces, volume bounds or sizes).
    pub count: usize,
    /// Indices per item: 4 for `.ele` (the corners of 10-node files too), 3 for `.face`, 2
    /// for `.edge` and `.var` segment constraints, 0 for `.vol`, `.mtr` and `.var` facet constraints.
    pub per_item: usize,
    /// The indices, numbered from the `base` given to `idm_tetgen_read_items`.
    pub indices: *const i32,
    /// Attributes per item (`.ele`).
    pub num_attributes: usize,
    /// `num_attributes` per item.
    pub attributes: *const f64,
    /// One marker per item (`.face` and `.edge` with markers; `.var` facet constraints), else
    /// NULL.
    pub markers: *const i32,
    /// One value per item (`.vol`: maximum volume; `.mtr`: size; `.var`: maximum area or
    /// length), else NULL.
    pub values: *const f64,
}

/// Reads a TetGen mesh file with idmesh's readers: `kind` 0 an `.ele` file, 1 a `.face`
/// file, 2 a `.vol` file (`num_tets` lines), 3 an `.mtr` file (`num_points` lines, one size
/// each), 4 the facet constraints of a `.var` file (`markers` and `values`: marker and
/// maximum area per constraint), 5 its segment constraints (2 `indices` and one `values`,
/// the maximum length, per constraint), 6 an `.edge` file (2 `indices` per edge, `markers`
/// when the file has them); indices refer to `num_points` points numbered from `base` (0 or 1). Errors name the
/// file and line.
///
/// # Safety
/// `path` a NUL-terminated string; `out` valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_read_items(
    path: *const c_char,
    kind: i32,
    num_points: usize,
    num_tets: usize,
    base: u32,
    out: *mut *mut idm_tetgen_items,
) -> idm_status {
    use crate::io::tetgen::{parse_edge, parse_ele, parse_face, parse_mtr, parse_var, parse_vol};
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let path = unsafe { c_str(path, "path") }?;
        check_out(out, "out")?;
        if base > 1 {
            return Err(Failure::invalid(format!("base is {base}, must be 0 or 1")));
        }
        let text = std::fs::read_to_string(path).map_err(|e| {
            Failure::new(
                idm_status::IDM_ERR_INVALID_INPUT,
                format!("cannot read {path}: {e}"),
            )
        })?;
        let bad = |e: crate::io::ParseError| {
            Failure::new(idm_status::IDM_ERR_INVALID_INPUT, e.to_string())
        };
        let shift = |v: u32| v as i32 + base as i32;
        let mut items = idm_tetgen_items::default();
        match kind {
            0 => {
                let e = parse_ele(&text, path, base, num_points).map_err(bad)?;
                items.per_item = 4;
                items.indices = e.tets.iter().flatten().map(|&v| shift(v)).collect();
                items.num_attributes = e.num_attributes;
                items.attributes = e.attributes;
            }
            1 => {
                let f = parse_face(&text, path, base, num_points).map_err(bad)?;
                items.per_item = 3;
                items.indices = f.items.iter().flatten().map(|&v| shift(v)).collect();
                items.markers = f.markers;
            }
            2 => items.values = parse_vol(&text, path, num_tets).map_err(bad)?,
            3 => items.values = parse_mtr(&text, path, num_points).map_err(bad)?,
            4 => {
                let v = parse_var(&text, path, base, num_points).map_err(bad)?;
                items.markers = v.facets.iter().map(|c| c.0).collect();
                items.values = v.facets.iter().map(|c| c.1).collect();
            }
            5 => {
                let v = parse_var(&text, path, base, num_points).map_err(bad)?;
                items.per_item = 2;
                items.indices = v.segments.iter().flat_map(|c| c.0).map(shift).collect();
                items.values = v.segments.iter().map(|c| c.1).collect();
            }
            6 => {
                let e = parse_edge(&text, path, base, num_points).map_err(bad)?;
                items.per_item = 2;
                items.indices = e.items.iter().flatten().map(|&v| shift(v)).collect();
                items.markers = e.markers;
            }
            k => return Err(Failure::invalid(format!("kind {k} is not 0 to 6"))),
        }
        unsafe { out.write(Box::into_raw(Box::new(items))) };
        Ok(())
    })
}

/// Lends the arrays of `p` in `*out`.
///
/// # Safety
/// `p` a live `idm_tetgen_items`; `out` valid for writing the struct.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_items_arrays(
    p: *const idm_tetgen_items,
    out: *mut idm_tetgen_items_view,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let p = unsafe { p.as_ref() }.ok_or_else(|| Failure::null("p"))?;
        check_out(out, "out")?;
        let count = p
            .indices
            .len()
            .checked_div(p.per_item)
            .unwrap_or(p.values.len());
        let view = idm_tetgen_items_view {
            count,
            per_item: p.per_item,
            indices: array_ptr(&p.indices),
            num_attributes: p.num_attributes,
            attributes: array_ptr(&p.attributes),
            markers: array_ptr(&p.markers),
            values: array_ptr(&p.values),
        };
        unsafe { out.write(view) };
        Ok(())
    })
}

/// Frees an `idm_tetgen_items`. NULL is a no-op.
///
/// # Safety
/// `p` NULL or from `idm_tetgen_read_items`, not freed before.
#[no_mangle]
pub unsafe extern "C" fn idm_tetgen_items_free(p: *mut idm_tetgen_items) {
    if !p.is_null() {
        // SAFETY: the caller's contract; dropping plain vectors cannot panic.
        drop(unsafe { Box::from_raw(p) });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::idm_last_error;
    use crate::ffi::{
        idm_mesher3d_add_facet, idm_mesher3d_add_points, idm_mesher3d_counts, idm_mesher3d_free,
        idm_mesher3d_new,
    };
    use std::ffi::CString;
    use std::ptr::{null, null_mut};

    fn last_error() -> String {
        // SAFETY: idm_last_error never returns NULL.
        unsafe { CStr::from_ptr(idm_last_error()) }
            .to_string_lossy()
            .into_owned()
    }

    fn parse(text: &str) -> Result<idm_tetgen_switches, (idm_status, String)> {
        let c = CString::new(text).unwrap();
        let mut out = std::mem::MaybeUninit::uninit();
        // SAFETY: valid string and out-pointer.
        match unsafe { idm_tetgen_parse_switches(c.as_ptr(), out.as_mut_ptr()) } {
            // SAFETY: written on success.
            idm_status::IDM_OK => Ok(unsafe { out.assume_init() }),
            s => Err((s, last_error())),
        }
    }

    #[test]
    fn switches_parse_round_trip_and_refusals_name_the_switch() {
        let s = parse("pq1.414a0.01nnfAzQ").unwrap();
        assert_eq!(
            (s.plc, s.neighbors, s.all_faces, s.zero_based),
            (1, 2, 1, 1)
        );
        assert_eq!(
            (s.radius_edge, s.max_volume, s.max_steiner),
            (1.414, 0.01, -1)
        );
        let Ok(back) = s.to_switches() else {
            panic!("to_switches failed")
        };
        assert_eq!(idm_tetgen_switches::from(&back), s);
        assert_eq!(parse("pqc").unwrap().convex_hull, 1);
        let t = parse("pT1e-7").unwrap();
        assert_eq!((t.coplanar_tolerance, s.coplanar_tolerance), (1e-7, 0.0));
        let back = t.to_switches().ok().unwrap();
        assert_eq!(back.coplanar_tolerance, Some(1e-7));
        assert_eq!(back.options().coplanar_tolerance, Some(1e-7));
        // q's minimum dihedral angle goes through the struct: given, off (/0), not given.
        for (sw, angle, target) in [
            ("pq1.414/10", 10.0, Some(10.0)),
            ("pq1.414/0", 0.0, Some(0.0)),
            ("pq1.414", -1.0, None),
        ] {
            let q = parse(sw).unwrap();
            assert_eq!(q.min_dihedral, angle, "{sw}");
            let back = q.to_switches().ok().unwrap();
            assert_eq!(back.min_dihedral, target, "{sw}");
            assert_eq!(back.options().min_dihedral, target, "{sw}");
        }
        let (st, msg) = parse("pT2").unwrap_err();
        assert_eq!(st, idm_status::IDM_ERR_INVALID_ARGUMENT);
        assert!(msg.contains("-T"), "{msg}");
        let (st, msg) = parse("pqw").unwrap_err();
        assert_eq!(st, idm_status::IDM_ERR_UNSUPPORTED);
        assert!(msg.contains("-w"), "{msg}");
        let (st, msg) = parse("pq#").unwrap_err();
        assert_eq!(st, idm_status::IDM_ERR_INVALID_ARGUMENT);
        assert!(msg.contains("-#"), "{msg}");
        // SAFETY: NULL is reported, not dereferenced.
        let st = unsafe { idm_tetgen_parse_switches(null(), null_mut()) };
        assert_eq!(st, idm_status::IDM_ERR_NULL_POINTER);
        let msg = CString::new("point attributes are not supported").unwrap();
        // SAFETY: a valid string.
        let st = unsafe { idm_tetgen_report(msg.as_ptr()) };
        assert_eq!(st, idm_status::IDM_ERR_INVALID_INPUT);
        assert_eq!(last_error(), "point attributes are not supported");
    }

    /// A unit cube as a handle: 8 points, 6 quads with markers 1..6.
    fn cube() -> *mut idm_mesher3d {
        let mut m = null_mut();
        let pts: Vec<f64> = (0..8)
            .flat_map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        let quads: [[u32; 4]; 6] = [
            [0, 1, 3, 2],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 3, 7, 5],
        ];
        // SAFETY: valid arguments throughout.
        unsafe {
            assert_eq!(idm_mesher3d_new(&mut m), idm_status::IDM_OK);
            assert_eq!(
                idm_mesher3d_add_points(m, pts.as_ptr(), 8, null()),
                idm_status::IDM_OK
            );
            for (k, q) in quads.iter().enumerate() {
                let offsets = [0usize, 4];
                let st = idm_mesher3d_add_facet(
                    m,
                    q.as_ptr(),
                    offsets.as_ptr(),
                    1,
                    null(),
                    0,
                    k as i32 + 1,
                );
                assert_eq!(st, idm_status::IDM_OK);
            }
        }
        m
    }

    #[test]
    fn meshing_by_switches_reports_tetgen_codes() {
        let m = cube();
        let sw = parse("pq1.5a0.01").unwrap();
        let mut code = -1;
        let mut tets = 0usize;
        // SAFETY: live handle and valid pointers.
        unsafe {
            assert_eq!(
                idm_mesher3d_tetgen(m, &sw, 0, null_mut(), &mut code),
                idm_status::IDM_OK
            );
            assert_eq!(code, 0);
            let st = idm_mesher3d_counts(m, null_mut(), &mut tets, null_mut(), null_mut());
            assert_eq!(st, idm_status::IDM_OK);
            assert!(tets >= 100, "a0.01 on a unit cube: {tets} tets");
            // A facet crossing the cube: TetGen's code 3.
            let pts = [0.5, 0.5, -1.0, 0.5, 0.5, 2.0, 0.5, 2.0, 0.5];
            assert_eq!(
                idm_mesher3d_add_points(m, pts.as_ptr(), 3, null()),
                idm_status::IDM_OK
            );
            let tri = [8u32, 9, 10];
            let off = [0usize, 3];
            let st = idm_mesher3d_add_facet(m, tri.as_ptr(), off.as_ptr(), 1, null(), 0, 9);
            assert_eq!(st, idm_status::IDM_OK);
            let st = idm_mesher3d_tetgen(m, &sw, 0, null_mut(), &mut code);
            assert_eq!(st, idm_status::IDM_ERR_INVALID_INPUT);
            assert_eq!(code, 3, "{}", last_error());
            idm_mesher3d_free(m);
        }
    }

    #[test]
    fn files_resolve_and_read() {
        let dir = std::env::temp_dir().join(format!("idmesh-ffi-tetgen-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let poly = dir.join("t.poly");
        std::fs::write(
            &poly,
            "4 3 0 1\n1 0 0 0 5\n2 1 0 0 5\n3 0 1 0 5\n4 0 0 1 5\n\
             4 1\n1 0 1\n3 1 2 3\n1 0 2\n3 1 2 4\n1 0 3\n3 1 3 4\n1 0 4\n3 2 3 4\n0\n1\n1 .1 .1 .1 7 -1\n",
        )
        .unwrap();
        let stem = CString::new(dir.join("t").to_str().unwrap()).unwrap();
        let sw = parse("p").unwrap();
        let mut input = [0 as c_char; 256];
        let mut out = [0 as c_char; 256];
        let mut plc = 0;
        // SAFETY: valid buffers of the stated size.
        unsafe {
            let st = idm_tetgen_resolve(
                stem.as_ptr(),
                &sw,
                input.as_mut_ptr(),
                out.as_mut_ptr(),
                256,
                &mut plc,
            );
            assert_eq!(st, idm_status::IDM_OK);
            let input = CStr::from_ptr(input.as_ptr()).to_str().unwrap();
            assert_eq!(input, poly.to_str().unwrap());
            assert!(CStr::from_ptr(out.as_ptr())
                .to_str()
                .unwrap()
                .ends_with("t.1"));
            assert_eq!(plc, 1);
            let st = idm_tetgen_resolve(
                stem.as_ptr(),
                &sw,
                input.as_ptr() as *mut _,
                out.as_mut_ptr(),
                2,
                &mut plc,
            );
            assert_eq!(st, idm_status::IDM_ERR_INVALID_ARGUMENT);
            let path = CString::new(poly.to_str().unwrap()).unwrap();
            let mut p = null_mut();
            assert_eq!(idm_tetgen_read(path.as_ptr(), &mut p), idm_status::IDM_OK);
            let mut v = std::mem::MaybeUninit::uninit();
            assert_eq!(idm_plc3d_arrays(p, v.as_mut_ptr()), idm_status::IDM_OK);
            let v = v.assume_init();
            assert_eq!((v.base, v.num_points, v.num_facets), (1, 4, 4));
            assert_eq!(*v.point_markers, 5);
            assert_eq!(*v.facet_markers.add(3), 4);
            assert_eq!(*v.polygon_offsets.add(*v.facet_polygon_offsets.add(4)), 12);
            assert_eq!((v.num_regions, *v.regions.add(3)), (1, 7.0));
            idm_plc3d_free(p);
            let bad = CString::new(dir.join("none.poly").to_str().unwrap()).unwrap();
            assert_eq!(
                idm_tetgen_read(bad.as_ptr(), &mut p),
                idm_status::IDM_ERR_INVALID_INPUT
            );
            assert!(last_error().contains("none.poly"), "{}", last_error());
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn mesh_files_are_read_as_items() {
        let dir = std::env::temp_dir().join(format!("idmesh-ffi-items-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = |name: &str, text: &str| {
            let p = dir.join(name);
            std::fs::write(&p, text).unwrap();
            CString::new(p.to_str().unwrap()).unwrap()
        };
        let ele = file("m.ele", "1 10 1\n1 1 2 3 4 5 5 5 5 5 5 7.5\n");
        let vol = file("m.vol", "1\n1 0.25\n");
        let mtr = file("m.mtr", "5 1\n0.1\n0.2\n0.3\n0.4\n0.5\n");
        let face = file("m.face", "1 1\n1 1 2 3 9\n");
        let mut p = null_mut();
        let mut v = std::mem::MaybeUninit::uninit();
        // SAFETY: valid strings and out-pointers; the items are freed once.
        unsafe {
            assert_eq!(
                idm_tetgen_read_items(ele.as_ptr(), 0, 5, 0, 1, &mut p),
                idm_status::IDM_OK
            );
            assert_eq!(
                idm_tetgen_items_arrays(p, v.as_mut_ptr()),
                idm_status::IDM_OK
            );
            let w = v.assume_init();
            assert_eq!((w.count, w.per_item, w.num_attributes), (1, 4, 1));
            assert_eq!(std::slice::from_raw_parts(w.indices, 4), &[1, 2, 3, 4]);
            assert_eq!(*w.attributes, 7.5);
            idm_tetgen_items_free(p);
            for (path, kind, value) in [(&vol, 2, 0.25), (&mtr, 3, 0.1)] {
                let st = idm_tetgen_read_items(path.as_ptr(), kind, 5, 1, 1, &mut p);
                assert_eq!(st, idm_status::IDM_OK, "{}", last_error());
                assert_eq!(
                    idm_tetgen_items_arrays(p, v.as_mut_ptr()),
                    idm_status::IDM_OK
                );
                let w = v.assume_init();
                assert_eq!((w.per_item, *w.values), (0, value));
                idm_tetgen_items_free(p);
            }
            let st = idm_tetgen_read_items(face.as_ptr(), 1, 5, 0, 1, &mut p);
            assert_eq!(st, idm_status::IDM_OK);
            assert_eq!(
                idm_tetgen_items_arrays(p, v.as_mut_ptr()),
                idm_status::IDM_OK
            );
            assert_eq!(*v.assume_init().markers, 9);
            idm_tetgen_items_free(p);
            // Wrong counts are errors naming the file.
            let st = idm_tetgen_read_items(vol.as_ptr(), 2, 5, 3, 1, &mut p);
            assert_eq!(st, idm_status::IDM_ERR_INVALID_INPUT);
            assert!(last_error().contains("m.vol"), "{}", last_error());
            idm_tetgen_items_free(null_mut());
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
