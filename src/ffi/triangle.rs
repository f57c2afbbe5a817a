//! The C ABI for Triangle compatibility: parsing Triangle's switch string with the library's one
//! parser ([`crate::switches::triangle`]), and the outputs Triangle has that the plain 2D ABI
//! (`idm_mesher2d_*`) does not lend: all edges with markers, and the segments as Triangle
//! outputs them (hull edges included). `compat/triangle/triangle.c` is built on these; C
//! programs may call them directly too.
//!
//! The conventions are those of the rest of the C ABI (see [`crate::ffi`]): panics caught,
//! pointers checked, out-parameters written only on success, `idm_last_error()` explains.

#![allow(non_camel_case_types)]
#![deny(unsafe_op_in_unsafe_fn)]

use std::ffi::{c_char, CStr};

use crate::ffi::{
    change, check_out, guard, idm_mesher2d, idm_mesher2d_neighbors, idm_mesher2d_segments,
    idm_mesher2d_triangles, idm_mesher2d_vertices, idm_options2d, idm_status, input_slice, mesh_of,
    optional_slice, scaled, Failure,
};
use crate::geometry::circumcenter;
use crate::mesh2d::{TriMesh, NONE};
use crate::switches::triangle::{
    output_segments, parse_library, refine_input, GivenMesh, Switches,
};

/// The switches `idm_triangle_parse_switches` accepts: every Triangle switch whose meaning the
/// C ABI can deliver. `i F l s` pick Triangle's internal algorithms and `X` its arithmetic,
/// none of which changes what the output means, so they are accepted and do nothing; `g` writes
/// a file only from Triangle's command line (its library writes nothing), likewise `I`.
const C_HONOURED: &[&str] = &[
    "p", "q", "a", "u", "A", "c", "D", "j", "e", "v", "n", "g", "B", "P", "N", "E", "I", "O", "X",
    "z", "o2", "Y", "YY", "S", "r", "i", "F", "l", "s", "C", "Q", "V",
];

/// Triangle's switches, parsed (`idm_triangle_parse_switches`). Booleans are `int32_t`: 0 or 1.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct idm_triangle_switches {
    /// The mesher options they ask for (`q a Y S c`; `a` without a number and `A` only with
    /// `p`, as in Triangle), ready for `idm_mesher2d_set_options`.
    pub options: idm_options2d,
    /// `p`: the input is a PSLG (segments, holes and regions are read).
    pub poly: i32,
    /// `u`: call the user's sizing test.
    pub user_test: i32,
    /// `A`: regional attributes are output (only with `p`).
    pub region_attributes: i32,
    /// `c`: the convex hull is meshed.
    pub convex_hull: i32,
    /// `e`: output the edges.
    pub edges: i32,
    /// `n`: output the neighbours.
    pub neighbors: i32,
    /// `B`: no boundary markers in the output.
    pub no_boundary_markers: i32,
    /// `P`: no segments in the output.
    pub no_poly: i32,
    /// `N`: no vertices in the output.
    pub no_node: i32,
    /// `E`: no triangles in the output.
    pub no_ele: i32,
    /// `O`: the holes are ignored.
    pub ignore_holes: i32,
    /// `z`: items are numbered from 0 (else from 1).
    pub zero_based: i32,
    /// `Y`: no Steiner points on boundary segments.
    pub no_boundary_steiner: i32,
    /// `C`: check the mesh after meshing (`idm_mesher2d_validate`).
    pub check: i32,
    /// `Q`: print nothing but errors.
    pub quiet: i32,
    /// `V`: print statistics.
    pub verbose: i32,
    /// `v`: output the Voronoi diagram (`idm_triangle_voronoi`).
    pub voronoi: i32,
    /// `o2`: second-order (6-node) triangles (`idm_triangle_second_order`).
    pub second_order: i32,
    /// `j`: leave the vertices that are in no triangle out of the output, renumbering the rest.
    pub jettison: i32,
    /// `r`: remesh the given triangles (`idm_triangle_set_given_mesh`). With it, `options`
    /// applies the per-triangle area bounds when `a` has no number (`region_max_area`).
    pub refine: i32,
}

impl idm_triangle_switches {
    fn from_switches(s: &Switches) -> Self {
        let o = s.options(s.poly);
        let b = i32::from;
        idm_triangle_switches {
            options: idm_options2d {
                struct_size: std::mem::size_of::<idm_options2d>(),
                min_angle: o.min_angle.unwrap_or(0.0),
                max_area: o.max_area.unwrap_or(0.0),
                region_max_area: b(o.region_max_area),
                region_attributes: b(o.region_attributes),
                convex_hull: b(o.convex_hull),
                off_centers: b(o.off_centers),
                split_crossings: b(o.split_crossings),
                no_boundary_steiner: b(o.no_boundary_steiner),
                max_steiner: o
                    .max_steiner
                    .map_or(-1, |n| i64::try_from(n).unwrap_or(i64::MAX)),
                no_segment_steiner: b(o.no_segment_steiner),
                threads: o.threads.unwrap_or(0),
            },
            poly: b(s.poly),
            user_test: b(s.user_test),
            region_attributes: b(o.region_attributes),
            convex_hull: b(s.convex_hull),
            edges: b(s.edges),
            neighbors: b(s.neighbors),
            no_boundary_markers: b(s.no_boundary_markers),
            no_poly: b(s.no_poly),
            no_node: b(s.no_node),
            no_ele: b(s.no_ele),
            ignore_holes: b(s.ignore_holes),
            zero_based: b(s.zero_based),
            no_boundary_steiner: b(s.no_boundary_steiner),
            check: b(s.check),
            quiet: b(s.quiet),
            verbose: b(s.verbose),
            voronoi: b(s.voronoi),
            second_order: b(s.second_order),
            jettison: b(s.jettison),
            refine: b(s.refine),
        }
    }
}

/// Parses a switch string as Triangle's `triangulate()` takes it (`"pq30a0.1zQ"`; a leading
/// `-` is tolerated) into `*out`. A switch Triangle does not know is `IDM_ERR_INVALID_ARGUMENT`;
/// one the C ABI cannot honour (`w W`) is `IDM_ERR_UNSUPPORTED`; the message names
/// it. Never ignores a switch.
///
/// # Safety
/// `text` must be NULL (an error) or a NUL-terminated string; `out` NULL (an error) or valid
/// for writing an `idm_triangle_switches`.
#[no_mangle]
pub unsafe extern "C" fn idm_triangle_parse_switches(
    text: *const c_char,
    out: *mut idm_triangle_switches,
) -> idm_status {
    guard(|| {
        if text.is_null() {
            return Err(Failure::null("text"));
        }
        check_out(out, "out")?;
        // SAFETY: non-NULL; NUL termination is the caller's contract.
        let text = unsafe { CStr::from_ptr(text) }
            .to_str()
            .map_err(|_| Failure::invalid("the switch string is not valid UTF-8"))?;
        let sw = parse_library(text).map_err(Failure::invalid)?;
        sw.refuse_except(C_HONOURED)
            .map_err(|e| Failure::new(idm_status::IDM_ERR_UNSUPPORTED, e))?;
        // SAFETY: checked by check_out.
        unsafe { out.write(idm_triangle_switches::from_switches(&sw)) };
        Ok(())
    })
}

/// Triangle's `r`: makes the handle's input the PSLG that remeshes the given triangles
/// (idmesh does not refine them in place; see `idmesh::switches::triangle::refine_input`).
/// Call it after adding the points (and, with `p`, the segments) the triangles refer to: the
/// handle's segments become those segments followed by the triangles' boundary edges
/// (marker 1) and the edges between triangles of different attribute or area bound (marker
/// 0); its holes and regions are replaced by hole seeds where the triangles leave an enclosed
/// area uncovered and one region per connected group of triangles with one attribute and one
/// area bound. Then refine as usual (set `region_attributes` to carry `attributes` to the
/// output, `region_max_area` to apply `max_areas`).
///
/// `triangles`: 3 corners per triangle, 0-based; `attributes` and `max_areas`: NULL or one
/// per triangle (a bound of 0 or less is none). `first` is how the caller numbers items, used
/// in messages (Triangle's 0 or 1). Errors name the triangle or edge: a corner out of range, a
/// degenerate triangle, an edge of more than two triangles, triangles that overlap.
///
/// # Safety
/// `m` a live handle; `triangles` valid for `3*num_triangles` reads, `attributes` and
/// `max_areas` NULL or valid for `num_triangles` reads.
#[no_mangle]
pub unsafe extern "C" fn idm_triangle_set_given_mesh(
    m: *mut idm_mesher2d,
    triangles: *const u32,
    num_triangles: usize,
    attributes: *const f64,
    max_areas: *const f64,
    first: u32,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |h| {
            let tri: &[[u32; 3]] = input_slice(triangles.cast(), num_triangles, "triangles")?;
            let attr = optional_slice(attributes, num_triangles, "attributes")?;
            let area = optional_slice(max_areas, num_triangles, "max_areas")?;
            let given = GivenMesh {
                triangles: tri.to_vec(),
                attributes: attr.map_or_else(Vec::new, <[f64]>::to_vec),
                max_areas: area.map_or_else(Vec::new, <[f64]>::to_vec),
            };
            h.pslg = refine_input(&h.pslg, &given, area.is_some(), first)?;
            Ok(())
        })
    }
}

/// Records `message` (NULL: a generic one) as this thread's `idm_last_error()` and returns
/// `status` (`IDM_OK` is turned into `IDM_ERR_INVALID_ARGUMENT`). For shims over the C ABI
/// (such as `compat/triangle`) that find an error before calling the library.
///
/// # Safety
/// `message` must be NULL or a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn idm_triangle_fail(
    status: idm_status,
    message: *const c_char,
) -> idm_status {
    let text = if message.is_null() {
        "invalid input".to_string()
    } else {
        // SAFETY: the caller's contract.
        unsafe { CStr::from_ptr(message) }
            .to_string_lossy()
            .into_owned()
    };
    let status = if status == idm_status::IDM_OK {
        idm_status::IDM_ERR_INVALID_ARGUMENT
    } else {
        status
    };
    guard(|| Err(Failure::new(status, text)))
}

/// Copies the handle's triangles, neighbours and segments into a [`TriMesh`] (vertices left
/// out: the edge and segment outputs need only the connectivity).
///
/// # Safety
/// `m` must be NULL or a live handle.
unsafe fn connectivity_of(m: *const idm_mesher2d) -> Result<TriMesh, Failure> {
    let status = |s: idm_status| {
        if s == idm_status::IDM_OK {
            Ok(())
        } else {
            // The getter has recorded its own message; keep it.
            // SAFETY: idm_last_error never returns NULL.
            let msg = unsafe { CStr::from_ptr(crate::ffi::idm_last_error()) };
            Err(Failure::new(s, msg.to_string_lossy().into_owned()))
        }
    };
    let (mut tri, mut nbr, mut seg) = (std::ptr::null(), std::ptr::null(), std::ptr::null());
    let mut mk: *const i32 = std::ptr::null();
    let (mut nt, mut nn, mut ns) = (0usize, 0usize, 0usize);
    // SAFETY (all blocks here): `m` is the caller's contract; the getters check it and lend
    // arrays of the stated lengths, read before any other call on the handle.
    unsafe {
        status(idm_mesher2d_triangles(m, &mut tri, &mut nt))?;
        status(idm_mesher2d_neighbors(m, &mut nbr, &mut nn))?;
        status(idm_mesher2d_segments(m, &mut seg, &mut mk, &mut ns))?;
    }
    let tri: &[[u32; 3]] = unsafe { input_slice(tri.cast(), nt, "triangles") }?;
    let nbr: &[[u32; 3]] = unsafe { input_slice(nbr.cast(), nn, "neighbors") }?;
    let seg: &[[u32; 2]] = unsafe { input_slice(seg.cast(), ns, "segments") }?;
    let mk: &[i32] = unsafe { input_slice(mk, ns, "segment markers") }?;
    Ok(TriMesh {
        triangles: tri.to_vec(),
        neighbors: nbr.to_vec(),
        segments: seg.to_vec(),
        segment_markers: mk.to_vec(),
        ..TriMesh::default()
    })
}

/// The connectivity (as [`connectivity_of`]) and the vertices, borrowed from the handle.
///
/// # Safety
/// `m` must be NULL or a live handle, not changed while the vertices are borrowed.
unsafe fn geometry_of<'a>(m: *const idm_mesher2d) -> Result<(TriMesh, &'a [[f64; 2]]), Failure> {
    // SAFETY (all blocks here): the caller's contract, forwarded; the getter lends an array of
    // the stated length.
    let mesh = unsafe { connectivity_of(m) }?;
    let (mut xy, mut nv) = (std::ptr::null(), 0usize);
    let st = unsafe { idm_mesher2d_vertices(m, &mut xy, &mut nv) };
    if st != idm_status::IDM_OK {
        return Err(Failure::new(st, "cannot read the vertices"));
    }
    let xy: &[[f64; 2]] = unsafe { input_slice(xy.cast(), nv, "vertices") }?;
    Ok((mesh, xy))
}

/// Vertex pairs with a marker each (edges, segments).
type Pairs = Vec<([u32; 2], i32)>;

/// The body of the pair outputs: computes `which` of the handle's mesh and writes it into the
/// caller's arrays: `*count` always gets the number of items; `ab` (2 per item) and `markers`
/// (1 per item), each optional, are filled when not NULL, which needs `capacity >= *count`.
///
/// # Safety
/// `m` NULL or a live handle; `ab` and `markers` NULL or valid for `2*capacity` / `capacity`
/// writes; `count` checked.
unsafe fn pairs(
    m: *const idm_mesher2d,
    which: fn(&TriMesh) -> Pairs,
    ab: *mut u32,
    markers: *mut i32,
    capacity: usize,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    guard(|| unsafe { fill(&which(&connectivity_of(m)?), ab, markers, capacity, count) })
}

/// Writes `items` as `pairs` says.
///
/// # Safety
/// As `pairs`.
unsafe fn fill(
    items: &[([u32; 2], i32)],
    ab: *mut u32,
    markers: *mut i32,
    capacity: usize,
    count: *mut usize,
) -> Result<(), Failure> {
    check_out(count, "count")?;
    if (!ab.is_null() || !markers.is_null()) && capacity < items.len() {
        return Err(Failure::invalid(format!(
            "capacity {capacity} is less than the {} items to write",
            items.len()
        )));
    }
    if !ab.is_null() {
        check_out(ab, "ab")?;
    }
    if !markers.is_null() {
        check_out(markers, "markers")?;
    }
    // SAFETY: the caller's contract on the lengths, checked against `capacity` above.
    unsafe {
        for (i, (e, mark)) in items.iter().enumerate() {
            if !ab.is_null() {
                ab.add(2 * i).write(e[0]);
                ab.add(2 * i + 1).write(e[1]);
            }
            if !markers.is_null() {
                markers.add(i).write(*mark);
            }
        }
        count.write(items.len());
    }
    Ok(())
}

/// Every edge of the mesh once (Triangle's `-e` output), as 0-based vertex pairs in `ab`, with
/// its marker in `markers`: the segment's marker for edges on a segment, else 0. Call with
/// `ab` and `markers` NULL to learn `*count`, then with arrays of `capacity >= *count`.
///
/// # Safety
/// `m` a live handle; `ab` NULL or valid for `2*capacity` writes, `markers` NULL or valid for
/// `capacity`, `count` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_triangle_edges(
    m: *const idm_mesher2d,
    ab: *mut u32,
    markers: *mut i32,
    capacity: usize,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { pairs(m, TriMesh::edges, ab, markers, capacity, count) }
}

/// The segments as Triangle outputs them (with `-p` or `-c`): the subsegments, then every
/// boundary edge that is no subsegment (the convex hull of a point set) with marker 1. Same
/// calling convention as `idm_triangle_edges`.
///
/// # Safety
/// As `idm_triangle_edges`.
#[no_mangle]
pub unsafe extern "C" fn idm_triangle_segments(
    m: *const idm_mesher2d,
    ab: *mut u32,
    markers: *mut i32,
    capacity: usize,
    count: *mut usize,
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe { pairs(m, output_segments, ab, markers, capacity, count) }
}

/// Triangle's point attributes on the mesh (`numberofpointattributes`): `attributes` holds
/// `per_point` values per input point (the points added to the handle, in order); `out` gets
/// `per_point` values per mesh vertex (`capacity` vertices at least, the number
/// `idm_mesher2d_vertices` gives): the input values at input vertices, and at Steiner vertices
/// the values interpolated linearly, along its input segment for a vertex on one, else in the
/// triangle of the input points' Delaunay triangulation containing it (see
/// `idmesh::mesh2d::interpolate_point_attributes`). Exact for attributes linear in x and y.
///
/// # Safety
/// `m` a live handle with a mesh; `attributes` valid for `per_point` reads per input point,
/// `out` valid for `per_point * capacity` writes.
#[no_mangle]
pub unsafe extern "C" fn idm_triangle_point_attributes(
    m: *const idm_mesher2d,
    attributes: *const f64,
    per_point: usize,
    out: *mut f64,
    capacity: usize,
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let mesh = unsafe { mesh_of(m) }?;
        let ni = mesh.num_input_vertices;
        let values: &[f64] = unsafe {
            input_slice(
                attributes,
                scaled(ni, per_point, "per_point")?,
                "attributes",
            )
        }?;
        let nv = mesh.vertices.len();
        if capacity < nv {
            return Err(Failure::invalid(format!(
                "capacity {capacity} is less than the {nv} vertices"
            )));
        }
        let all = crate::mesh2d::interpolate_point_attributes(mesh, per_point, values)?;
        if !all.is_empty() {
            check_out(out, "out")?;
            // SAFETY: `out` holds `per_point * capacity >= all.len()` values.
            unsafe { std::ptr::copy_nonoverlapping(all.as_ptr(), out, all.len()) };
        }
        Ok(())
    })
}

/// The Voronoi diagram of the mesh as Triangle outputs it with `-v` (the dual of the
/// triangulation, which is Delaunay): Voronoi vertex `t` is the circumcentre of triangle `t`
/// (`points`, 2 per triangle); one Voronoi edge per mesh edge, joining the circumcentres of its
/// two triangles (`edges`, 2 per edge, 0-based), or, for a boundary edge, a ray from its one
/// triangle's circumcentre: second index -1 and `norms` holding the ray direction, the edge's
/// outward normal (dy, -dx) for the edge taken counter-clockwise; `norms` is (0, 0) for finite
/// edges. `*num_points` and `*num_edges` always get the sizes; the arrays (each optional) are
/// filled when not NULL, which needs `capacity_points >= *num_points` and
/// `capacity_edges >= *num_edges`.
///
/// # Safety
/// `m` a live handle; `points` NULL or valid for `2*capacity_points` writes, `edges` and
/// `norms` NULL or valid for `2*capacity_edges`; `num_points`, `num_edges` valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_triangle_voronoi(
    m: *const idm_mesher2d,
    points: *mut f64,
    edges: *mut i32,
    norms: *mut f64,
    capacity_points: usize,
    capacity_edges: usize,
    num_points: *mut usize,
    num_edges: *mut usize,
) -> idm_status {
    guard(|| {
        check_out(num_points, "num_points")?;
        check_out(num_edges, "num_edges")?;
        // SAFETY: the caller's contract, forwarded.
        let (mesh, xy) = unsafe { geometry_of(m) }?;
        let mut centres = Vec::with_capacity(mesh.triangles.len());
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|v| xy[v as usize]);
            centres.push(circumcenter(a, b, c).ok_or_else(|| {
                Failure::new(
                    idm_status::IDM_ERR_INTERNAL,
                    format!("triangle {t} is degenerate: no circumcentre"),
                )
            })?);
        }
        let mut vedges: Vec<([i32; 2], [f64; 2])> = Vec::new();
        for (t, (tri, nbr)) in mesh.triangles.iter().zip(&mesh.neighbors).enumerate() {
            for i in 0..3 {
                let n = nbr[i];
                if n == NONE {
                    let (a, b) = (xy[tri[(i + 1) % 3] as usize], xy[tri[(i + 2) % 3] as usize]);
                    vedges.push(([t as i32, -1], [b[1] - a[1], a[0] - b[0]]));
                } else if n as usize > t {
                    vedges.push(([t as i32, n as i32], [0.0, 0.0]));
                }
            }
        }
        let i32_max = i32::MAX as usize;
        if centres.len() > i32_max {
            return Err(Failure::invalid("too many triangles for int indices"));
        }
        for (ptr, cap, need, what) in [
            (
                points.is_null(),
                capacity_points,
                centres.len(),
                "capacity_points",
            ),
            (
                edges.is_null() && norms.is_null(),
                capacity_edges,
                vedges.len(),
                "capacity_edges",
            ),
        ] {
            if !ptr && cap < need {
                return Err(Failure::invalid(format!(
                    "{what} {cap} is less than {need}"
                )));
            }
        }
        // SAFETY: lengths checked against the capacities above; the caller's contract.
        unsafe {
            for (k, p) in centres.iter().enumerate() {
                if !points.is_null() {
                    points.add(2 * k).write(p[0]);
                    points.add(2 * k + 1).write(p[1]);
                }
            }
            for (k, (e, nrm)) in vedges.iter().enumerate() {
                if !edges.is_null() {
                    edges.add(2 * k).write(e[0]);
                    edges.add(2 * k + 1).write(e[1]);
                }
                if !norms.is_null() {
                    norms.add(2 * k).write(nrm[0]);
                    norms.add(2 * k + 1).write(nrm[1]);
                }
            }
            num_points.write(centres.len());
            num_edges.write(vedges.len());
        }
        Ok(())
    })
}

/// The extra nodes of second-order (6-node) triangles, Triangle's `-o2`: one new vertex at the
/// midpoint of every mesh edge, numbered after the mesh's vertices (the first new one is
/// number `num_vertices`) in order of first use. `xy` gets 2 coordinates and `markers` 1 marker
/// per new vertex (the segment's marker for the midpoint of a subsegment, else 0); `nodes` gets
/// 3 vertex numbers per triangle: the midpoints opposite its corners 0, 1 and 2 (Triangle's
/// nodes 4, 5, 6). `*num_new` always gets the number of new vertices; the arrays (each
/// optional) are filled when not NULL, which needs `capacity_vertices >= *num_new` and
/// `capacity_triangles >=` the number of triangles.
///
/// # Safety
/// `m` a live handle; `xy` NULL or valid for `2*capacity_vertices` writes, `markers` NULL or
/// valid for `capacity_vertices`, `nodes` NULL or valid for `3*capacity_triangles`; `num_new`
/// valid for a write.
#[no_mangle]
pub unsafe extern "C" fn idm_triangle_second_order(
    m: *const idm_mesher2d,
    xy: *mut f64,
    markers: *mut i32,
    capacity_vertices: usize,
    nodes: *mut u32,
    capacity_triangles: usize,
    num_new: *mut usize,
) -> idm_status {
    guard(|| {
        check_out(num_new, "num_new")?;
        // SAFETY: the caller's contract, forwarded.
        let (mesh, vx) = unsafe { geometry_of(m) }?;
        let nv = vx.len();
        let key = |a: u32, b: u32| (a.min(b), a.max(b));
        let seg_marker: std::collections::HashMap<(u32, u32), i32> = mesh
            .segments
            .iter()
            .zip(&mesh.segment_markers)
            .map(|(s, &k)| (key(s[0], s[1]), k))
            .collect();
        let nt = mesh.triangles.len();
        let mut mid = vec![[0u32; 3]; nt];
        let mut new: Vec<([f64; 2], i32)> = Vec::new();
        for t in 0..nt {
            let tri = mesh.triangles[t];
            for i in 0..3 {
                let n = mesh.neighbors[t][i];
                // The neighbour across a shared edge, when numbered lower, made its midpoint.
                let shared = (n != NONE && (n as usize) < t)
                    .then(|| {
                        mesh.neighbors[n as usize]
                            .iter()
                            .position(|&x| x as usize == t)
                    })
                    .flatten();
                mid[t][i] = match shared {
                    Some(j) => mid[n as usize][j],
                    None => {
                        let (a, b) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                        let (pa, pb) = (vx[a as usize], vx[b as usize]);
                        let id = nv + new.len();
                        if id >= NONE as usize {
                            return Err(Failure::invalid("too many vertices for uint32_t"));
                        }
                        let mark = seg_marker.get(&key(a, b)).copied().unwrap_or(0);
                        new.push(([0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])], mark));
                        id as u32
                    }
                };
            }
        }
        if (!xy.is_null() || !markers.is_null()) && capacity_vertices < new.len() {
            return Err(Failure::invalid(format!(
                "capacity_vertices {capacity_vertices} is less than {}",
                new.len()
            )));
        }
        if !nodes.is_null() && capacity_triangles < nt {
            return Err(Failure::invalid(format!(
                "capacity_triangles {capacity_triangles} is less than {nt}"
            )));
        }
        // SAFETY: lengths checked against the capacities above; the caller's contract.
        unsafe {
            for (k, (p, mark)) in new.iter().enumerate() {
                if !xy.is_null() {
                    xy.add(2 * k).write(p[0]);
                    xy.add(2 * k + 1).write(p[1]);
                }
                if !markers.is_null() {
                    markers.add(k).write(*mark);
                }
            }
            if !nodes.is_null() {
                for (t, m3) in mid.iter().enumerate() {
                    for (i, &v) in m3.iter().enumerate() {
                        nodes.add(3 * t + i).write(v);
                    }
                }
            }
            num_new.write(new.len());
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::*;
    use idm_status::*;

    fn parse(text: &str) -> Result<idm_triangle_switches, (idm_status, String)> {
        let c = std::ffi::CString::new(text).unwrap();
        let mut out = std::mem::MaybeUninit::<idm_triangle_switches>::uninit();
        let st = unsafe { idm_triangle_parse_switches(c.as_ptr(), out.as_mut_ptr()) };
        if st == IDM_OK {
            Ok(unsafe { out.assume_init() })
        } else {
            let msg = unsafe { CStr::from_ptr(idm_last_error()) };
            Err((st, msg.to_string_lossy().into_owned()))
        }
    }

    #[test]
    fn parses_into_options_and_flags() {
        let s = parse("pq30a0.5zenBQ").unwrap();
        assert_eq!((s.options.min_angle, s.options.max_area), (30.0, 0.5));
        assert_eq!((s.poly, s.zero_based, s.edges, s.neighbors), (1, 1, 1, 1));
        assert_eq!((s.no_boundary_markers, s.quiet, s.verbose), (1, 1, 0));
        assert_eq!(s.options.max_steiner, -1);
        let s = parse("aA").unwrap();
        assert_eq!(s.options.region_max_area, 0, "regional bounds need p");
        assert_eq!(s.region_attributes, 0, "regional attributes need p");
        assert_eq!(parse("pv").unwrap().voronoi, 1);
        assert_eq!(parse("po2").unwrap().second_order, 1);
        assert_eq!(parse("pj").unwrap().jettison, 1);
        let s = parse("pYY").unwrap();
        assert_eq!(s.options.no_segment_steiner, 1, "-YY reaches the mesher");
        assert_eq!(
            (s.no_boundary_steiner, s.options.no_boundary_steiner),
            (1, 1)
        );
        assert_eq!(parse("pY").unwrap().options.no_segment_steiner, 0);
        let s = parse("-paAS10iFlsXgI").unwrap();
        assert_eq!((s.options.region_max_area, s.region_attributes), (1, 1));
        assert_eq!(s.options.max_steiner, 10);
    }

    #[test]
    fn refuses_by_name() {
        for (sw, name) in [("w", "-w"), ("pW", "-W")] {
            let (st, msg) = parse(sw).unwrap_err();
            assert_eq!(st, IDM_ERR_UNSUPPORTED, "{sw}");
            assert!(msg.contains(name), "{sw}: {msg}");
        }
        let (st, msg) = parse("pk").unwrap_err();
        assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
        assert!(msg.contains("-k"), "{msg}");
        let mut out = std::mem::MaybeUninit::<idm_triangle_switches>::uninit();
        let st = unsafe { idm_triangle_parse_switches(std::ptr::null(), out.as_mut_ptr()) };
        assert_eq!(st, IDM_ERR_NULL_POINTER);
    }

    #[test]
    fn fail_records_the_message() {
        let msg = c"numberofpointattributes is 2";
        let st = unsafe { idm_triangle_fail(IDM_ERR_INVALID_INPUT, msg.as_ptr()) };
        assert_eq!(st, IDM_ERR_INVALID_INPUT);
        let got = unsafe { CStr::from_ptr(idm_last_error()) };
        assert_eq!(got, msg);
        assert_eq!(
            unsafe { idm_triangle_fail(IDM_OK, std::ptr::null()) },
            IDM_ERR_INVALID_ARGUMENT
        );
    }

    #[test]
    fn edges_and_segments_of_a_square_point_set() {
        let mut m = std::ptr::null_mut();
        unsafe {
            assert_eq!(idm_mesher2d_new(&mut m), IDM_OK);
            let xy = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.5, 0.4];
            assert_eq!(
                idm_mesher2d_add_points(m, xy.as_ptr(), 5, std::ptr::null()),
                IDM_OK
            );
            let mut n = 0usize;
            assert_eq!(
                idm_triangle_edges(m, std::ptr::null_mut(), std::ptr::null_mut(), 0, &mut n),
                IDM_ERR_NO_MESH
            );
            assert_eq!(idm_mesher2d_refine(m), IDM_OK);
            let none = std::ptr::null_mut();
            assert_eq!(idm_triangle_edges(m, none, none.cast(), 0, &mut n), IDM_OK);
            assert_eq!(n, 8, "4 hull edges and 4 spokes");
            let mut ab = vec![0u32; 2 * n];
            let mut mk = vec![-1i32; n];
            assert_eq!(
                idm_triangle_edges(m, ab.as_mut_ptr(), mk.as_mut_ptr(), n - 1, &mut n),
                IDM_ERR_INVALID_ARGUMENT,
                "too small"
            );
            assert_eq!(
                idm_triangle_edges(m, ab.as_mut_ptr(), mk.as_mut_ptr(), n, &mut n),
                IDM_OK
            );
            for (e, k) in ab.chunks(2).zip(&mk) {
                let hull = e[0] < 4 && e[1] < 4;
                assert_eq!(
                    *k,
                    i32::from(hull),
                    "hull edges 1 (as in Triangle), spokes 0"
                );
            }
            assert_eq!(
                idm_triangle_segments(m, none, none.cast(), 0, &mut n),
                IDM_OK
            );
            assert_eq!(n, 4, "the hull");
            let mut ab = vec![0u32; 2 * n];
            let mut mk = vec![0i32; n];
            assert_eq!(
                idm_triangle_segments(m, ab.as_mut_ptr(), mk.as_mut_ptr(), n, &mut n),
                IDM_OK
            );
            assert!(mk.iter().all(|&k| k == 1), "hull edges get marker 1");
            assert!(ab.iter().all(|&v| v < 4), "hull edges join the corners");
            // Voronoi: 4 circumcentres, 4 rays (the hull edges) and 4 finite edges.
            let (mut np, mut ne) = (0usize, 0usize);
            let nul = std::ptr::null_mut();
            assert_eq!(
                idm_triangle_voronoi(m, nul, nul.cast(), nul, 0, 0, &mut np, &mut ne),
                IDM_OK
            );
            assert_eq!((np, ne), (4, 8));
            let mut pts = vec![0.0; 2 * np];
            let mut ed = vec![0i32; 2 * ne];
            let mut nr = vec![0.0; 2 * ne];
            let (pp, ep, rp) = (pts.as_mut_ptr(), ed.as_mut_ptr(), nr.as_mut_ptr());
            assert_eq!(
                idm_triangle_voronoi(m, pp, ep, rp, np, ne - 1, &mut np, &mut ne),
                IDM_ERR_INVALID_ARGUMENT
            );
            assert_eq!(
                idm_triangle_voronoi(m, pp, ep, rp, np, ne, &mut np, &mut ne),
                IDM_OK
            );
            let (mut tri, mut nt, mut vx, mut nv) = (std::ptr::null(), 0, std::ptr::null(), 0);
            assert_eq!(idm_mesher2d_triangles(m, &mut tri, &mut nt), IDM_OK);
            assert_eq!(idm_mesher2d_vertices(m, &mut vx, &mut nv), IDM_OK);
            let tri = std::slice::from_raw_parts(tri, 3 * nt);
            let vx = std::slice::from_raw_parts(vx, 2 * nv);
            for t in 0..nt {
                let c = [pts[2 * t], pts[2 * t + 1]];
                let d: Vec<f64> = (0..3)
                    .map(|k| {
                        let v = tri[3 * t + k] as usize;
                        (vx[2 * v] - c[0]).hypot(vx[2 * v + 1] - c[1])
                    })
                    .collect();
                assert!((d[0] - d[1]).abs() < 1e-12 && (d[0] - d[2]).abs() < 1e-12);
            }
            // -o2: 4 hull midpoints + 4 spoke midpoints; hull ones carry the hull marker 1.
            let mut nn = 0usize;
            let nul32 = std::ptr::null_mut::<u32>();
            assert_eq!(
                idm_triangle_second_order(m, nul, nul.cast(), 0, nul32, 0, &mut nn),
                IDM_OK
            );
            assert_eq!(nn, 8, "one midpoint per edge");
            let mut mxy = vec![0.0; 2 * nn];
            let mut mmk = vec![-1; nn];
            let mut nodes = vec![0u32; 3 * nt];
            let (xp, kp, np3) = (mxy.as_mut_ptr(), mmk.as_mut_ptr(), nodes.as_mut_ptr());
            assert_eq!(
                idm_triangle_second_order(m, xp, kp, nn, np3, nt - 1, &mut nn),
                IDM_ERR_INVALID_ARGUMENT
            );
            assert_eq!(
                idm_triangle_second_order(m, xp, kp, nn, np3, nt, &mut nn),
                IDM_OK
            );
            for t in 0..nt {
                for i in 0..3 {
                    let (a, b) = (
                        tri[3 * t + (i + 1) % 3] as usize,
                        tri[3 * t + (i + 2) % 3] as usize,
                    );
                    let k = nodes[3 * t + i] as usize - nv;
                    assert_eq!(mxy[2 * k], 0.5 * (vx[2 * a] + vx[2 * b]));
                    assert_eq!(mxy[2 * k + 1], 0.5 * (vx[2 * a + 1] + vx[2 * b + 1]));
                    assert_eq!(mmk[k], i32::from(a < 4 && b < 4), "hull midpoints marker 1");
                }
            }
            let mut ray_norms = Vec::new();
            for k in 0..ne {
                let n = [nr[2 * k], nr[2 * k + 1]];
                let ray = ed[2 * k + 1] == -1;
                assert_eq!(ray, n != [0.0, 0.0], "norms only on rays");
                if ray {
                    ray_norms.push(n);
                } else {
                    assert!(ed[2 * k] >= 0 && (ed[2 * k + 1] as usize) < nt);
                }
            }
            ray_norms.sort_by(|a, b| a.partial_cmp(b).unwrap());
            // The hull edges' outward normals (dy, -dx), one ray each.
            let want = [[-1.0, 0.0], [0.0, -1.0], [0.0, 1.0], [1.0, 0.0]];
            assert_eq!(ray_norms, want);
            idm_mesher2d_free(m);
        }
    }

    #[test]
    fn a_given_mesh_is_remeshed_with_its_area_bounds() {
        let mut m = std::ptr::null_mut();
        unsafe {
            assert_eq!(idm_mesher2d_new(&mut m), IDM_OK);
            let xy = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.5, 0.5];
            assert_eq!(
                idm_mesher2d_add_points(m, xy.as_ptr(), 5, std::ptr::null()),
                IDM_OK
            );
            // Four triangles around the centre; a small bound on the first only.
            let tri: [u32; 12] = [0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4];
            let attr = [1.0, 2.0, 2.0, 2.0];
            let area = [0.001, -1.0, -1.0, -1.0];
            let bad: [u32; 12] = [0, 1, 9, 1, 2, 4, 2, 3, 4, 3, 0, 4];
            let st =
                idm_triangle_set_given_mesh(m, bad.as_ptr(), 4, attr.as_ptr(), area.as_ptr(), 1);
            assert_eq!(st, IDM_ERR_INVALID_ARGUMENT);
            let msg = CStr::from_ptr(idm_last_error())
                .to_string_lossy()
                .into_owned();
            assert!(msg.contains("triangle 1 has corner 10"), "{msg}");
            let st =
                idm_triangle_set_given_mesh(m, tri.as_ptr(), 4, attr.as_ptr(), area.as_ptr(), 0);
            assert_eq!(st, IDM_OK);
            let s = parse("raQ").unwrap();
            assert_eq!((s.refine, s.options.region_max_area), (1, 1));
            let mut o = s.options;
            o.region_attributes = 1;
            assert_eq!(idm_mesher2d_set_options(m, &o), IDM_OK);
            assert_eq!(idm_mesher2d_refine(m), IDM_OK);
            assert_eq!(idm_mesher2d_validate(m), IDM_OK);
            let (mut t, mut nt, mut v, mut nv) = (std::ptr::null(), 0, std::ptr::null(), 0);
            let (mut a, mut na) = (std::ptr::null(), 0);
            assert_eq!(idm_mesher2d_triangles(m, &mut t, &mut nt), IDM_OK);
            assert_eq!(idm_mesher2d_vertices(m, &mut v, &mut nv), IDM_OK);
            assert_eq!(idm_mesher2d_triangle_attributes(m, &mut a, &mut na), IDM_OK);
            let t = std::slice::from_raw_parts(t, 3 * nt);
            let v = std::slice::from_raw_parts(v, 2 * nv);
            let a = std::slice::from_raw_parts(a, na);
            assert_eq!(v[..10], xy, "the given points keep their indices");
            let (mut small, mut sum1) = (0, 0.0);
            for k in 0..nt {
                let p = |c: usize| {
                    [
                        v[2 * t[3 * k + c] as usize],
                        v[2 * t[3 * k + c] as usize + 1],
                    ]
                };
                let ar = 0.5 * crate::geometry::area2(p(0), p(1), p(2));
                if a[k] == 1.0 {
                    assert!(ar <= 0.001);
                    small += 1;
                    sum1 += ar;
                } else {
                    assert_eq!(a[k], 2.0);
                }
            }
            assert!(
                small >= 250 && (sum1 - 0.25f64).abs() < 1e-12,
                "{small} {sum1}"
            );
            assert!(nt < small + 60, "the rest stays coarse: {nt} triangles");
            idm_mesher2d_free(m);
        }
    }
}
