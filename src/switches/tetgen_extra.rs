//! The TetGen switches that change what is meshed or what is written beyond idmesh's own
//! [`Options3`]: `r` (refine a given mesh), `i` (insert extra points), `m` (a sizing function
//! given at points), `o2` (second-order tetrahedra), and the interpolation of point attributes
//! at Steiner points. Both `idmesh tetgen` and the C ABI behind the TetGen compatibility layer
//! mesh through [`mesh_for`], so a switch means the same thing on both.
//!
//! What is done, and how it differs from TetGen:
//! * `r`: the given tetrahedra are not refined in place. Their boundary faces, the faces
//!   between tetrahedra of different attribute or volume bound, and the given `.face`
//!   triangles become the facets of a PLC (markers from the `.face` list, else 0); every given
//!   point is kept (same index); each connected group of tetrahedra with one attribute and one
//!   volume bound becomes a region. That PLC is meshed by idmesh to the `q`/`a` bounds, so the
//!   output has the input's boundary, regions and points, but not its tetrahedra. Per-tetrahedron
//!   volume bounds (`.vol`, `tetrahedronvolumelist`) are applied with `a` without a number, as
//!   TetGen applies them; the input's first tetrahedron attribute is carried to the output.
//! * `i`: the points are added to the input as isolated vertices (exact duplicates of input
//!   points are skipped). A point outside the meshed volume is kept in the output's point list,
//!   used by no tetrahedron (TetGen drops it).
//! * `m`: one size per point (TetGen's isotropic metric; `numberofpointmtrs` 1) is interpolated
//!   linearly in the tetrahedra of a background mesh: the `bgmin` mesh (`FILE.b.node`,
//!   `FILE.b.ele`, `FILE.b.mtr`) when given, else the given mesh with `r`, else the Delaunay
//!   tetrahedralization of the input points. The point is located by a walk decided by exact
//!   orientation tests. A tetrahedron is split when its longest edge exceeds the size at its
//!   centroid (TetGen's exact rule is not documented). A size of 0 or less means no bound there,
//!   as in TetGen; outside the background mesh there is no bound either.
//! * Point attributes are interpolated linearly at Steiner points in the same background
//!   tetrahedra (the given mesh with `r`, else the Delaunay tetrahedralization of the input
//!   points), and at `o2` edge nodes as the mean of the edge's ends.
//! * Facet and segment constraints (`facetconstraintlist`, `segmentconstraintlist`, a `.var`
//!   file beside a PLC file) become [`Options3::facet_max_area`] and
//!   [`Options3::segment_max_length`], applied as TetGen applies them: when the mesh is
//!   refined (`q`, or `a`).
//! * `o2`: six nodes per tetrahedron at the midpoints of its edges, shared between
//!   tetrahedra, numbered after the mesh's vertices, in the order TetGen 1.5 writes them: on the
//!   edges (2,3), (0,3), (0,1), (1,2), (1,3), (0,2) of the corners 0..3.

use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;

use crate::error::Error;
use crate::input3d::{Facet, Plc, Region3};
use crate::mesh3d::{delaunay3d, tetrahedralize, Options3, SizingFn3, TetMesh, NONE};
use crate::predicates::orient3d;

use super::tetgen::TetSwitches;

/// A mesh given for refinement (`r`), numbered 0-based into the input's points.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GivenMesh {
    /// The tetrahedra (the first four corners of each).
    pub tets: Vec<[u32; 4]>,
    /// One attribute per tetrahedron (the first of the input's), or empty.
    pub attributes: Vec<f64>,
    /// One maximum volume per tetrahedron (0 or less: none), or empty.
    pub volumes: Vec<f64>,
    /// Boundary (or interior) triangles to keep, with their markers.
    pub faces: Vec<[u32; 3]>,
    /// One marker per face, or empty (all 0).
    pub face_markers: Vec<i32>,
}

/// Sizes given at points (`m`): the background mesh's points, its tetrahedra (empty: the
/// Delaunay tetrahedralization of the points is used) and one size per point.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Metric {
    /// The points.
    pub points: Vec<[f64; 3]>,
    /// The tetrahedra, 0-based; empty for the points' Delaunay tetrahedralization.
    pub tets: Vec<[u32; 4]>,
    /// One size per point.
    pub sizes: Vec<f64>,
}

/// What the switches `r`, `i`, `m` and point attributes bring beyond a PLC.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Extra {
    /// The mesh to refine (`r`).
    pub given: Option<GivenMesh>,
    /// Points to insert (`i`).
    pub addin: Vec<[f64; 3]>,
    /// The sizing function (`m`).
    pub metric: Option<Metric>,
    /// Attributes per input point.
    pub num_point_attributes: usize,
    /// `num_point_attributes` per input point.
    pub point_attributes: Vec<f64>,
    /// Facet and segment constraints (`.var`, `facetconstraintlist`, `segmentconstraintlist`).
    pub bounds: SurfaceBounds,
}

/// TetGen's facet constraints (maximum area per facet marker) and segment constraints
/// (maximum length per input edge, 0-based endpoints), as [`Options3`] takes them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceBounds {
    /// See [`Options3::facet_max_area`].
    pub facet_max_area: Vec<(i32, f64)>,
    /// See [`Options3::segment_max_length`].
    pub segment_max_length: Vec<([u32; 2], f64)>,
}

/// Reads TetGen's `facetconstraintlist` (pairs: marker, maximum area) and
/// `segmentconstraintlist` (triples: endpoint, endpoint, maximum length; points numbered from
/// `base`), both arrays of doubles as in `tetgenio`. Markers and indices must be whole numbers
/// in range, bounds positive; the message names the first bad entry (numbered from 0).
pub fn tetgen_constraints(
    facets: &[f64],
    segments: &[f64],
    base: u32,
) -> Result<SurfaceBounds, String> {
    let whole = |x: f64, lo: f64, hi: f64| x.fract() == 0.0 && x >= lo && x <= hi;
    let bound = |x: f64| x.is_finite() && x > 0.0;
    let mut out = SurfaceBounds::default();
    for (i, c) in facets.chunks_exact(2).enumerate() {
        if !whole(c[0], i32::MIN as f64, i32::MAX as f64) {
            return Err(format!(
                "facet constraint {i}: the marker {} is not a 32-bit whole number",
                c[0]
            ));
        }
        if !bound(c[1]) {
            return Err(format!(
                "facet constraint {i}: the maximum area {} must be a positive number",
                c[1]
            ));
        }
        out.facet_max_area.push((c[0] as i32, c[1]));
    }
    let (lo, hi) = (base as f64, u32::MAX as f64 - 1.0 + base as f64);
    for (i, c) in segments.chunks_exact(3).enumerate() {
        if let Some(v) = c[..2].iter().find(|&&v| !whole(v, lo, hi)) {
            return Err(format!(
                "segment constraint {i}: the endpoint {v} is not a point index numbered from \
                 {base}"
            ));
        }
        if !bound(c[2]) {
            return Err(format!(
                "segment constraint {i}: the maximum length {} must be a positive number",
                c[2]
            ));
        }
        let e = [c[0], c[1]].map(|v| (v - base as f64) as u32);
        out.segment_max_length.push((e, c[2]));
    }
    Ok(out)
}

/// The `o2` output: the edge nodes (numbered after the mesh's vertices) and the 10-node
/// tetrahedra.
pub type Order2 = (Vec<[f64; 3]>, Vec<[u32; 10]>);

/// What is output beyond the [`TetMesh`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Post {
    /// With `o2`: the edge nodes (numbered after the mesh's vertices) and the 10-node
    /// tetrahedra.
    pub order2: Option<Order2>,
    /// Attributes per output point (0: none).
    pub num_point_attributes: usize,
    /// `num_point_attributes` per output point, edge nodes included.
    pub point_attributes: Vec<f64>,
}

impl Post {
    /// Number of points output: the mesh's vertices and the `o2` nodes.
    pub fn num_points(&self, mesh: &TetMesh) -> usize {
        mesh.vertices.len() + self.order2.as_ref().map_or(0, |(p, _)| p.len())
    }
}

/// TetGen 1.5's order of the six edge nodes of a 10-node tetrahedron (corner pairs).
pub const ORDER2_EDGES: [(usize, usize); 6] = [(2, 3), (0, 3), (0, 1), (1, 2), (1, 3), (0, 2)];

/// Meshes as the switches ask: with `r` the PLC made from the given mesh (see the module
/// docs), with `p` the PLC, else the Delaunay tetrahedralization of the points (input markers
/// copied); `i` points are added first and `m` sizes join `opts.sizing`. Returns the mesh
/// and what is output beside it.
pub fn mesh_for(
    sw: &TetSwitches,
    plc: &Plc,
    mut opts: Options3,
    extra: &Extra,
) -> Result<(TetMesh, Post), Error> {
    let num_given_points = plc.points.len();
    let mut work: Option<Plc> = None;
    // With `r`, points no given tetrahedron uses (e.g. the edge nodes of a 10-node mesh) are
    // left out of the meshing and put back, unused, at their indices: `keep[i]` is the output
    // index of the meshed input point `i`, `all` the output's input points.
    let mut keep: Option<(Vec<u32>, Plc)> = None;
    if sw.refine {
        let given = extra
            .given
            .as_ref()
            .filter(|g| !g.tets.is_empty())
            .ok_or_else(|| {
                Error::InvalidOption(
                    "-r: no tetrahedra given to refine (.ele file or tetrahedronlist)".into(),
                )
            })?;
        let (p, map) = plc_of_mesh(&plc.points, &plc.point_markers, given, sw.region_volume)?;
        if map.len() < plc.points.len() {
            keep = Some((map, plc.clone()));
        }
        work = Some(p);
        opts.remesh = true;
        opts.region_attributes |= !given.attributes.is_empty();
        opts.region_max_volume |= sw.region_volume && !given.volumes.is_empty();
    }
    if sw.insert_points && !extra.addin.is_empty() {
        let w = work.get_or_insert_with(|| plc.clone());
        let before = w.points.len();
        add_points(w, &extra.addin);
        if let Some((map, all)) = &mut keep {
            for p in &w.points[before..] {
                map.push(all.points.len() as u32);
                all.points.push(*p);
                if !all.point_markers.is_empty() {
                    all.point_markers.push(0);
                }
            }
        }
    }

    let plc = work.as_ref().unwrap_or(plc);
    // TetGen applies the constraints when it refines (`q`, or `a`).
    if sw.radius_edge.is_some() || sw.region_volume {
        let b = &extra.bounds;
        opts.facet_max_area.extend_from_slice(&b.facet_max_area);
        opts.segment_max_length
            .extend_from_slice(&b.segment_max_length);
    }
    if sw.metric {
        let metric = extra.metric.as_ref().ok_or_else(|| {
            Error::InvalidOption(
                "-m: no sizes given (a .mtr file, pointmtrlist of the input or of bgmin)".into(),
            )
        })?;
        let tets = if metric.tets.is_empty() && sw.refine && metric.points.len() == plc.points.len()
        {
            extra
                .given
                .as_ref()
                .map(|g| g.tets.clone())
                .unwrap_or_default()
        } else {
            metric.tets.clone()
        };
        let bg = Background::new(metric.points.clone(), tets, metric.sizes.clone(), 1)?;
        opts.sizing = Some(metric_sizing(Arc::new(bg), opts.sizing.take()));
    }
    let mesh = if sw.plc || sw.refine {
        tetrahedralize(plc, &opts)?
    } else if opts.optimize_level > 0 {
        // Never ignored: the Delaunay tetrahedralization of a point set has no optimisation.
        return Err(Error::InvalidOption(
            "-O (mesh optimisation) needs -p or -r; a point set's Delaunay \
             tetrahedralization is not optimised"
                .into(),
        ));
    } else {
        let mut mesh = delaunay3d(&plc.points)?;
        let n = plc.point_markers.len().min(mesh.vertex_markers.len());
        mesh.vertex_markers[..n].copy_from_slice(&plc.point_markers[..n]);
        mesh
    };
    let (mesh, plc) = match &keep {
        Some((map, all)) => (put_back(mesh, map, all), all),
        None => (mesh, plc),
    };
    let mut post = Post {
        order2: sw.order2.then(|| second_order(&mesh)),
        ..Post::default()
    };
    let na = extra.num_point_attributes;
    if na > 0 {
        // The points the attributes belong to: the input's, before any `i` points.
        let input = &plc.points[..num_given_points.min(plc.points.len())];
        let given = sw
            .refine
            .then(|| extra.given.as_ref().map(|g| g.tets.clone()))
            .flatten();
        post.point_attributes =
            interpolate_attributes(input, na, &extra.point_attributes, given, &mesh, &post)?;
        post.num_point_attributes = na;
    }
    Ok((mesh, post))
}

/// Appends `points` to the PLC as isolated vertices, skipping exact duplicates.
fn add_points(plc: &mut Plc, points: &[[f64; 3]]) {
    let key = |p: &[f64; 3]| p.map(|x| (x + 0.0).to_bits());
    let mut seen: std::collections::HashSet<[u64; 3]> = plc.points.iter().map(key).collect();
    for p in points {
        if seen.insert(key(p)) {
            plc.points.push(*p);
            if !plc.point_markers.is_empty() {
                plc.point_markers.push(0);
            }
        }
    }
}

fn sorted3(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

/// The face of a tetrahedron opposite corner `i`.
fn face_of(t: [u32; 4], i: usize) -> [u32; 3] {
    match i {
        0 => [t[1], t[2], t[3]],
        1 => [t[0], t[3], t[2]],
        2 => [t[0], t[1], t[3]],
        _ => [t[0], t[2], t[1]],
    }
}

/// Face-to-face adjacency of tetrahedra: `n[t][i]` is the tetrahedron across the face
/// opposite corner `i`, or [`NONE`]. A face shared by more than two tetrahedra is an error.
fn neighbors(tets: &[[u32; 4]]) -> Result<Vec<[u32; 4]>, Error> {
    // Per face: the first tetrahedron and its corner, and whether a second one was found.
    let mut seen: HashMap<[u32; 3], (u32, usize, bool)> = HashMap::with_capacity(tets.len() * 2);
    let mut n = vec![[NONE; 4]; tets.len()];
    for (t, tv) in tets.iter().enumerate() {
        for i in 0..4 {
            let k = sorted3(face_of(*tv, i));
            match seen.get_mut(&k) {
                Some((_, _, true)) => return Err(face_overused(k)),
                Some((u, j, paired)) => {
                    *paired = true;
                    n[*u as usize][*j] = t as u32;
                    n[t][i] = *u;
                }
                None => {
                    seen.insert(k, (t as u32, i, false));
                }
            }
        }
    }
    Ok(n)
}

fn face_overused(k: [u32; 3]) -> Error {
    Error::InvalidOption(format!(
        "the given mesh has more than two tetrahedra on the face {} {} {} (0-based)",
        k[0], k[1], k[2]
    ))
}

/// The PLC of a given mesh (see the module docs for `r`).
fn plc_of_mesh(
    points: &[[f64; 3]],
    point_markers: &[i32],
    given: &GivenMesh,
    use_volumes: bool,
) -> Result<(Plc, Vec<u32>), Error> {
    let nt = given.tets.len();
    for (t, tv) in given.tets.iter().enumerate() {
        if let Some(&v) = tv.iter().find(|&&v| v as usize >= points.len()) {
            return Err(Error::InvalidOption(format!(
                "-r: tetrahedron {t} (0-based) uses point {v}, but there are {} points",
                points.len()
            )));
        }
    }
    for (what, len) in [
        ("attributes", given.attributes.len()),
        ("volume bounds", given.volumes.len()),
    ] {
        if len != 0 && len != nt {
            return Err(Error::InvalidOption(format!(
                "-r: {len} tetrahedron {what} for {nt} tetrahedra"
            )));
        }
    }
    let attr = |t: usize| given.attributes.get(t).copied().unwrap_or(0.0);
    let vol = |t: usize| {
        let v = if use_volumes {
            given.volumes.get(t).copied().unwrap_or(-1.0)
        } else {
            -1.0
        };
        if v > 0.0 {
            v
        } else {
            -1.0
        }
    };
    let group = |t: usize| ((attr(t) + 0.0).to_bits(), vol(t).to_bits());
    let nb = neighbors(&given.tets)?;
    let mut marker_of: HashMap<[u32; 3], i32> = HashMap::new();
    for (i, f) in given.faces.iter().enumerate() {
        if let Some(&v) = f.iter().find(|&&v| v as usize >= points.len()) {
            return Err(Error::InvalidOption(format!(
                "-r: face {i} (0-based) uses point {v}, but there are {} points",
                points.len()
            )));
        }
        marker_of.insert(sorted3(*f), given.face_markers.get(i).copied().unwrap_or(0));
    }
    let mut facets = Vec::new();
    let mut is_wall = |t: usize, i: usize| -> bool {
        let f = face_of(given.tets[t], i);
        let n = nb[t][i];
        let key = sorted3(f);
        let wall = n == NONE || group(n as usize) != group(t) || marker_of.contains_key(&key);
        // Each face once: from the tetrahedron with the smaller index (or the only one).
        if wall && (n == NONE || (n as usize) > t) {
            facets.push(Facet {
                polygons: vec![f.to_vec()],
                holes: Vec::new(),
                marker: marker_of.get(&key).copied().unwrap_or(0),
            });
        }
        wall
    };
    let mut walls = vec![[false; 4]; nt];
    for (t, w) in walls.iter_mut().enumerate() {
        for (i, wi) in w.iter_mut().enumerate() {
            *wi = is_wall(t, i);
        }
    }
    let mut regions = Vec::new();
    if !given.attributes.is_empty() || given.volumes.iter().any(|&v| v > 0.0) && use_volumes {
        let mut seen = vec![false; nt];
        let mut stack = Vec::new();
        for s in 0..nt {
            if seen[s] {
                continue;
            }
            seen[s] = true;
            stack.push(s);
            while let Some(t) = stack.pop() {
                for i in 0..4 {
                    let n = nb[t][i];
                    if n != NONE && !walls[t][i] && !seen[n as usize] {
                        seen[n as usize] = true;
                        stack.push(n as usize);
                    }
                }
            }
            let c = given.tets[s].map(|v| points[v as usize]);
            let centroid = [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k] + c[3][k]) / 4.0);
            let v = vol(s);
            regions.push(Region3 {
                point: centroid,
                attribute: attr(s),
                max_volume: (v > 0.0).then_some(v),
            });
        }
    }
    // Only the points the tetrahedra use, renumbered in order; `map` gives the old index.
    let mut new_id = vec![NONE; points.len()];
    for t in &given.tets {
        for &v in t {
            new_id[v as usize] = 0;
        }
    }
    let mut map = Vec::new();
    for (i, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = map.len() as u32;
            map.push(i as u32);
        }
    }
    for f in &mut facets {
        for poly in &mut f.polygons {
            for v in poly.iter_mut() {
                *v = new_id[*v as usize];
            }
        }
    }
    let plc = Plc {
        points: map.iter().map(|&i| points[i as usize]).collect(),
        point_markers: if point_markers.is_empty() {
            Vec::new()
        } else {
            map.iter().map(|&i| point_markers[i as usize]).collect()
        },
        segments: Vec::new(),
        segment_markers: Vec::new(),
        facets,
        holes: Vec::new(),
        regions,
    };
    Ok((plc, map))
}

/// The mesh of a PLC whose input points are a subset of `all`'s (point `i` is `all`'s
/// `map[i]`), renumbered so that every point of `all` is at its index (unused when not in the
/// subset), Steiner points after them.
fn put_back(mesh: TetMesh, map: &[u32], all: &Plc) -> TetMesh {
    let ni = mesh.num_input_vertices;
    let n = all.points.len();
    let id = |v: u32| {
        if (v as usize) < ni {
            map[v as usize]
        } else {
            (n + v as usize - ni) as u32
        }
    };
    let mut vertices = all.points.clone();
    vertices.extend_from_slice(&mesh.vertices[ni..]);
    let mut markers: Vec<i32> = (0..n)
        .map(|i| all.point_markers.get(i).copied().unwrap_or(0))
        .collect();
    markers.extend_from_slice(&mesh.vertex_markers[ni..]);
    TetMesh {
        vertices,
        vertex_markers: markers,
        num_input_vertices: n,
        tets: mesh.tets.iter().map(|t| t.map(id)).collect(),
        faces: mesh.faces.iter().map(|t| t.map(id)).collect(),
        edges: mesh.edges.iter().map(|t| t.map(id)).collect(),
        ..mesh
    }
}

/// A tetrahedral mesh with values at its points, interpolated linearly in its tetrahedra.
#[derive(Debug)]
pub struct Background {
    points: Vec<[f64; 3]>,
    tets: Vec<[u32; 4]>,
    neighbors: Vec<[u32; 4]>,
    per_point: usize,
    values: Vec<f64>,
}

impl Background {
    /// A background mesh; with no tetrahedra, the Delaunay tetrahedralization of the points.
    /// `values` has `per_point` values per point.
    pub fn new(
        points: Vec<[f64; 3]>,
        tets: Vec<[u32; 4]>,
        values: Vec<f64>,
        per_point: usize,
    ) -> Result<Background, Error> {
        if values.len() != points.len() * per_point {
            return Err(Error::InvalidOption(format!(
                "{} values for {} points ({per_point} per point)",
                values.len(),
                points.len()
            )));
        }
        let mut tets = if tets.is_empty() {
            delaunay3d(&points)?.tets
        } else {
            tets
        };
        for (t, tv) in tets.iter_mut().enumerate() {
            if tv.iter().any(|&v| v as usize >= points.len()) {
                return Err(Error::InvalidOption(format!(
                    "background tetrahedron {t} (0-based) uses a point that does not exist"
                )));
            }
            let c = tv.map(|v| points[v as usize]);
            // Shewchuk's sign: positive is TetGen's negative orientation.
            if orient3d(c[0], c[1], c[2], c[3]) > 0.0 {
                tv.swap(0, 1);
            }
        }
        let neighbors = neighbors(&tets)?;
        Ok(Background {
            points,
            tets,
            neighbors,
            per_point,
            values,
        })
    }

    /// Signed volumes (Shewchuk's sign, negated) with `p` in place of each corner of `t`;
    /// all non-negative exactly when `p` is in the closed tetrahedron.
    fn sub_volumes(&self, t: usize, p: [f64; 3]) -> [f64; 4] {
        let c = self.tets[t].map(|v| self.points[v as usize]);
        std::array::from_fn(|i| {
            let mut q = c;
            q[i] = p;
            -orient3d(q[0], q[1], q[2], q[3])
        })
    }

    /// The tetrahedron containing `p` and its barycentric weights: a walk from `*hint`
    /// (updated), then, if the walk leaves the mesh or runs out of steps, a scan.
    pub fn locate(&self, p: [f64; 3], hint: &mut u32) -> Option<(usize, [f64; 4])> {
        crate::geometry::locate_in_simplices(&self.neighbors, |t| self.sub_volumes(t, p), hint)
    }

    /// Writes the values interpolated at `p` into `out` (`per_point` of them); `false` when
    /// `p` is outside the mesh.
    pub fn interpolate(&self, p: [f64; 3], hint: &mut u32, out: &mut [f64]) -> bool {
        let Some((t, w)) = self.locate(p, hint) else {
            return false;
        };
        let k = self.per_point;
        for (a, o) in out.iter_mut().enumerate().take(k) {
            *o = (0..4)
                .map(|i| w[i] * self.values[self.tets[t][i] as usize * k + a])
                .sum();
        }
        true
    }

    /// The values of point `v`.
    fn values_of(&self, v: usize) -> &[f64] {
        &self.values[v * self.per_point..(v + 1) * self.per_point]
    }

    /// The size at `p` from a background with one size per point: `None` outside the mesh or
    /// where a corner's size is 0 or less (no bound).
    fn size_at(&self, p: [f64; 3], hint: &mut u32) -> Option<f64> {
        let (t, w) = self.locate(p, hint)?;
        let mut h = 0.0;
        for (&v, wi) in self.tets[t].iter().zip(w) {
            let s = self.values_of(v as usize)[0];
            if s.is_nan() || s <= 0.0 {
                return None;
            }
            h += wi * s;
        }
        Some(h)
    }
}

/// The sizing test of `m`: a tetrahedron is too large when its longest edge exceeds the size
/// at its centroid; `user` (the caller's test) is asked too.
fn metric_sizing(bg: Arc<Background>, user: Option<SizingFn3>) -> SizingFn3 {
    let hint = AtomicU32::new(0);
    Arc::new(move |a, b, c, d, vol| {
        if let Some(u) = &user {
            if u(a, b, c, d, vol) {
                return true;
            }
        }
        let q = [a, b, c, d];
        let centroid = [0, 1, 2].map(|k| (a[k] + b[k] + c[k] + d[k]) / 4.0);
        let mut h = hint.load(Ordering::Relaxed);
        let size = bg.size_at(centroid, &mut h);
        hint.store(h, Ordering::Relaxed);
        let Some(size) = size else { return false };
        let mut longest2: f64 = 0.0;
        for i in 0..4 {
            for j in i + 1..4 {
                let d2: f64 = (0..3).map(|k| (q[i][k] - q[j][k]).powi(2)).sum();
                longest2 = longest2.max(d2);
            }
        }
        longest2 > size * size
    })
}

/// The `o2` nodes of `mesh`: one per edge at its midpoint, numbered after the vertices in
/// the order first met, and the 10-node tetrahedra ([`ORDER2_EDGES`]).
pub fn second_order(mesh: &TetMesh) -> Order2 {
    let nv = mesh.vertices.len() as u32;
    let mut id: HashMap<(u32, u32), u32> = HashMap::with_capacity(mesh.tets.len() * 2);
    let mut nodes = Vec::new();
    let tets = mesh
        .tets
        .iter()
        .map(|t| {
            let mut out = [0u32; 10];
            out[..4].copy_from_slice(t);
            for (k, &(i, j)) in ORDER2_EDGES.iter().enumerate() {
                let (a, b) = (t[i].min(t[j]), t[i].max(t[j]));
                out[4 + k] = *id.entry((a, b)).or_insert_with(|| {
                    let (p, q) = (mesh.vertices[a as usize], mesh.vertices[b as usize]);
                    nodes.push([0, 1, 2].map(|c| (p[c] + q[c]) / 2.0));
                    nv + nodes.len() as u32 - 1
                });
            }
            out
        })
        .collect();
    (nodes, tets)
}

/// Point attributes at every output point: copied at input points, interpolated linearly at
/// Steiner points in `given` (the mesh refined with `r`) or the Delaunay tetrahedralization
/// of the input points, and the mean of the ends at `o2` nodes.
fn interpolate_attributes(
    input: &[[f64; 3]],
    na: usize,
    attrs: &[f64],
    given: Option<Vec<[u32; 4]>>,
    mesh: &TetMesh,
    post: &Post,
) -> Result<Vec<f64>, Error> {
    let ni = input.len().min(mesh.vertices.len());
    let mut values = attrs.to_vec();
    values.resize(input.len() * na, 0.0);
    let bg = Background::new(input.to_vec(), given.unwrap_or_default(), values, na)?;
    let mut out = Vec::with_capacity(post.num_points(mesh) * na);
    out.extend_from_slice(&bg.values[..ni * na]);
    let mut hint = 0;
    let mut buf = vec![0.0; na];
    for p in &mesh.vertices[ni..] {
        if !bg.interpolate(*p, &mut hint, &mut buf) {
            buf.fill(0.0);
        }
        out.extend_from_slice(&buf);
    }
    if let Some((nodes, tets)) = &post.order2 {
        let mut mean = vec![0.0; nodes.len() * na];
        let nv = mesh.vertices.len();
        let mut done = vec![false; nodes.len()];
        for t in tets {
            for (k, &(i, j)) in ORDER2_EDGES.iter().enumerate() {
                let m = t[4 + k] as usize - nv;
                if !done[m] {
                    done[m] = true;
                    for a in 0..na {
                        mean[m * na + a] =
                            (out[t[i] as usize * na + a] + out[t[j] as usize * na + a]) / 2.0;
                    }
                }
            }
        }
        out.extend_from_slice(&mean);
    }
    Ok(out)
}

/// Reads what the switches need beside the input file `input_path` (already read as
/// `input`), as TetGen's command line finds it: with `r` `FILE.ele` (and `FILE.face`,
/// `FILE.vol` when present), with `i` `FILE.a.node`, with `m` the background mesh
/// `FILE.b.node` + `FILE.b.ele` + `FILE.b.mtr` when `FILE.b.node` exists, else `FILE.mtr`
/// (sizes at the input points); with a PLC `FILE.var` when present; and the input's point
/// attributes. `FILE` is the input path without its extension.
pub fn read_extra(
    sw: &TetSwitches,
    input_path: &str,
    input: &crate::io::tetgen::TetgenInput,
) -> Result<Extra, String> {
    use crate::io::tetgen::{parse_ele, parse_face, parse_mtr, parse_var, parse_vol, read_node};
    use std::path::Path;
    let path = Path::new(input_path);
    let stem = path.with_extension("");
    let stem = stem.to_string_lossy();
    let file = |ext: &str| format!("{stem}.{ext}");
    let exists = |name: &str| Path::new(name).exists();
    let text =
        |name: &str| std::fs::read_to_string(name).map_err(|e| format!("cannot read {name}: {e}"));
    let np = input.plc.points.len();
    let base = input.base;
    let mut extra = Extra {
        num_point_attributes: input.num_point_attributes,
        point_attributes: input.point_attributes.clone(),
        ..Extra::default()
    };
    if sw.refine {
        let ele = file("ele");
        let e = parse_ele(&text(&ele).map_err(|e| format!("-r: {e}"))?, &ele, base, np)
            .map_err(|e| e.to_string())?;
        let mut given = GivenMesh {
            attributes: if e.num_attributes > 0 {
                e.attributes
                    .iter()
                    .step_by(e.num_attributes)
                    .copied()
                    .collect()
            } else {
                Vec::new()
            },
            tets: e.tets,
            ..GivenMesh::default()
        };
        let face = file("face");
        if exists(&face) {
            let f = parse_face(&text(&face)?, &face, base, np).map_err(|e| e.to_string())?;
            given.faces = f.items;
            given.face_markers = f.markers;
        }
        let vol = file("vol");
        if exists(&vol) {
            given.volumes =
                parse_vol(&text(&vol)?, &vol, given.tets.len()).map_err(|e| e.to_string())?;
        }
        extra.given = Some(given);
    }
    let var = file("var");
    if (sw.plc || sw.refine) && exists(&var) {
        let v = parse_var(&text(&var)?, &var, base, np).map_err(|e| e.to_string())?;
        extra.bounds = SurfaceBounds {
            facet_max_area: v.facets,
            segment_max_length: v.segments,
        };
    }
    if sw.insert_points {
        let a = file("a.node");
        let add = read_node(Path::new(&a)).map_err(|e| format!("-i: {e}"))?;
        extra.addin = add.plc.points;
    }
    if sw.metric {
        let bnode = file("b.node");
        extra.metric = Some(if exists(&bnode) {
            let bg = read_node(Path::new(&bnode)).map_err(|e| e.to_string())?;
            let n = bg.plc.points.len();
            let bele = file("b.ele");
            let tets = parse_ele(&text(&bele)?, &bele, bg.base, n)
                .map_err(|e| e.to_string())?
                .tets;
            let bmtr = file("b.mtr");
            let sizes = parse_mtr(&text(&bmtr)?, &bmtr, n).map_err(|e| e.to_string())?;
            Metric {
                points: bg.plc.points,
                tets,
                sizes,
            }
        } else {
            let mtr = file("mtr");
            let sizes = parse_mtr(&text(&mtr).map_err(|e| format!("-m: {e}"))?, &mtr, np)
                .map_err(|e| e.to_string())?;
            Metric {
                points: input.plc.points.clone(),
                tets: Vec::new(),
                sizes,
            }
        });
    }
    Ok(extra)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube as a PLC: 8 corners (x + 2y + 4z), 6 quads.
    fn cube() -> Plc {
        crate::mesh3d::plc_tests::box_plc([0.0; 3], [1.0; 3])
    }

    fn sw(text: &str) -> TetSwitches {
        super::super::tetgen::parse_string(text).unwrap()
    }

    #[test]
    fn second_order_nodes_are_shared_midpoints_in_tetgen_order() {
        let (mesh, post) = mesh_for(
            &sw("pq1.5a0.1o2"),
            &cube(),
            sw("pq1.5a0.1").options(),
            &Extra::default(),
        )
        .unwrap();
        let (nodes, tets) = post.order2.as_ref().unwrap();
        assert_eq!(tets.len(), mesh.tets.len());
        let nv = mesh.vertices.len();
        let point = |v: u32| {
            if (v as usize) < nv {
                mesh.vertices[v as usize]
            } else {
                nodes[v as usize - nv]
            }
        };
        let mut node_of = HashMap::new();
        for t in tets {
            for (k, &(i, j)) in ORDER2_EDGES.iter().enumerate() {
                let (a, b) = (point(t[i]), point(t[j]));
                assert_eq!(point(t[4 + k]), [0, 1, 2].map(|c| (a[c] + b[c]) / 2.0));
                let e = (t[i].min(t[j]), t[i].max(t[j]));
                assert_eq!(*node_of.entry(e).or_insert(t[4 + k]), t[4 + k], "shared");
            }
        }
        assert_eq!(node_of.len(), nodes.len(), "one node per edge");
    }

    #[test]
    fn background_interpolates_linear_functions_and_knows_its_outside() {
        let plc = cube();
        let f = |p: [f64; 3]| 1.0 + p[0] - 2.0 * p[1] + 0.5 * p[2];
        let values = plc.points.iter().map(|p| f(*p)).collect();
        let bg = Background::new(plc.points.clone(), Vec::new(), values, 1).unwrap();
        let mut hint = 0;
        let mut out = [0.0];
        for p in [
            [0.3, 0.2, 0.9],
            [0.5, 0.5, 0.5],
            [1.0, 0.0, 0.25],
            [0.0, 0.0, 0.0],
        ] {
            assert!(bg.interpolate(p, &mut hint, &mut out), "{p:?} is inside");
            assert!(
                (out[0] - f(p)).abs() < 1e-12,
                "{p:?}: {} vs {}",
                out[0],
                f(p)
            );
        }
        assert!(!bg.interpolate([1.5, 0.5, 0.5], &mut hint, &mut out));
        assert!(Background::new(plc.points.clone(), Vec::new(), vec![1.0], 1).is_err());
    }

    #[test]
    fn a_given_mesh_becomes_a_plc_with_its_regions_and_keeps_its_points() {
        // Two tets sharing the face 1 2 3, with different attributes, and an unused point 5.
        let points = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.5, 0.0, 0.0],
        ];
        let given = GivenMesh {
            tets: vec![[0, 1, 2, 3], [1, 2, 3, 4]],
            attributes: vec![1.0, 2.0],
            volumes: vec![0.01, -1.0],
            ..GivenMesh::default()
        };
        let (plc, map) = plc_of_mesh(&points, &[], &given, true).unwrap();
        assert_eq!(map, vec![0, 1, 2, 3, 4], "the unused point is left out");
        assert_eq!(
            plc.facets.len(),
            7,
            "6 boundary faces and the face between the regions"
        );
        assert_eq!(plc.regions.len(), 2);
        assert_eq!(plc.regions[0].max_volume, Some(0.01));
        assert_eq!(plc.regions[1].attribute, 2.0);
        let extra = Extra {
            given: Some(given),
            ..Extra::default()
        };
        let s = sw("raA");
        let input = Plc {
            points: points.clone(),
            ..Plc::default()
        };
        let (mesh, _) = mesh_for(&s, &input, s.options(), &extra).unwrap();
        assert_eq!(
            &mesh.vertices[..6],
            &points[..],
            "input points at their indices"
        );
        assert!(mesh.tets.iter().all(|t| !t.contains(&5)));
        let vol = |a: f64| -> f64 {
            (0..mesh.tets.len())
                .filter(|&t| mesh.tet_attributes[t] == a)
                .map(|t| crate::geometry::tet_volume(mesh.corners(t)))
                .sum()
        };
        assert!((vol(1.0) - 1.0 / 6.0).abs() < 1e-12);
        assert!((vol(2.0) - 1.0 / 3.0).abs() < 1e-12);
        for t in 0..mesh.tets.len() {
            if mesh.tet_attributes[t] == 1.0 {
                assert!(crate::geometry::tet_volume(mesh.corners(t)) <= 0.01 * (1.0 + 1e-12));
            }
        }
        let e = mesh_for(&sw("r"), &input, Options3::default(), &Extra::default()).unwrap_err();
        assert!(e.to_string().contains("-r"), "{e}");
    }

    #[test]
    fn a_thin_slanted_wedge_is_remeshed_as_it_is_meshed() {
        // A wedge 0.05 thick at x = 1 and 0 at x = 0: the Steiner points on its slanted side
        // are rounded off that side's plane, so the given mesh's faces there are not exactly
        // coplanar. Kept apart, their edges had to be split wherever new points came near:
        // -r made 5,206 tets where meshing the wedge at the same bound makes 476.
        let h = 0.05;
        let mut points = Vec::new();
        for &x in &[0.0, 1.0] {
            for &y in &[0.0, 1.0] {
                points.push([x, y, 0.0]);
                if x == 1.0 {
                    points.push([x, y, h]);
                }
            }
        }
        // 0 (0,0,0), 1 (0,1,0), 2 (1,0,0), 3 (1,0,h), 4 (1,1,0), 5 (1,1,h).
        let facet = |v: &[u32], marker| crate::input3d::Facet {
            polygons: vec![v.to_vec()],
            holes: Vec::new(),
            marker,
        };
        let wedge = Plc {
            points,
            facets: vec![
                facet(&[0, 2, 4, 1], 1),
                facet(&[0, 3, 5, 1], 2),
                facet(&[0, 2, 3], 3),
                facet(&[1, 4, 5], 3),
                facet(&[2, 4, 5, 3], 4),
            ],
            ..Plc::default()
        };
        let run = |text: &str, plc: &Plc, extra: &Extra| {
            let s = sw(text);
            mesh_for(&s, plc, s.options(), extra).unwrap().0
        };
        let coarse = run("pq1.414a0.0005", &wedge, &Extra::default());
        let slanted = |p: &[f64; 3]| p[2] != 0.0 && p[0] != 1.0 && p[2] != h * p[0];
        assert!(
            coarse.vertices.iter().any(slanted),
            "some point on the slanted side is rounded off its plane"
        );
        let direct = run("pq1.414a0.0001", &wedge, &Extra::default());
        let given = Extra {
            given: Some(GivenMesh {
                tets: coarse.tets.clone(),
                faces: coarse.faces.clone(),
                face_markers: coarse.face_markers.clone(),
                ..GivenMesh::default()
            }),
            ..Extra::default()
        };
        let input = Plc {
            points: coarse.vertices.clone(),
            ..Plc::default()
        };
        let remeshed = run("rq1.414a0.0001", &input, &given);
        assert_eq!(&remeshed.vertices[..input.points.len()], &input.points[..]);
        assert!(
            remeshed.tets.len() * 2 <= direct.tets.len() * 3,
            "-r: {} tets, meshed directly: {}",
            remeshed.tets.len(),
            direct.tets.len()
        );
        let volume: f64 = (0..remeshed.tets.len())
            .map(|t| crate::geometry::tet_volume(remeshed.corners(t)))
            .sum();
        assert!((volume - h / 2.0).abs() < 1e-12, "volume {volume}");
        for m in 1..=4 {
            assert!(remeshed.face_markers.contains(&m), "marker {m} kept");
        }
    }

    #[test]
    fn inserted_points_are_vertices_and_duplicates_are_skipped() {
        let extra = Extra {
            addin: vec![[0.5, 0.5, 0.5], [0.0, 0.0, 0.0], [0.25, 0.75, 0.5]],
            ..Extra::default()
        };
        let (mesh, _) = mesh_for(&sw("pi"), &cube(), Options3::default(), &extra).unwrap();
        assert_eq!(
            mesh.num_input_vertices, 10,
            "the corner (0,0,0) is not added twice"
        );
        for v in [8u32, 9] {
            assert!(mesh.tets.iter().any(|t| t.contains(&v)));
        }
        assert_eq!(mesh.vertices[9], [0.25, 0.75, 0.5]);
    }

    #[test]
    fn metric_sizes_grade_the_mesh_and_attributes_follow() {
        let plc = cube();
        let extra = Extra {
            metric: Some(Metric {
                points: plc.points.clone(),
                tets: Vec::new(),
                sizes: plc.points.iter().map(|p| 0.1 + 0.4 * p[0]).collect(),
            }),
            num_point_attributes: 2,
            point_attributes: plc
                .points
                .iter()
                .flat_map(|p| [p[0], p[1] + p[2]])
                .collect(),
            ..Extra::default()
        };
        let (mesh, post) = mesh_for(&sw("pm"), &plc, Options3::default(), &extra).unwrap();
        assert!(mesh.tets.len() > 100);
        for t in 0..mesh.tets.len() {
            let c = mesh.corners(t);
            let cx = (c[0][0] + c[1][0] + c[2][0] + c[3][0]) / 4.0;
            let mut longest: f64 = 0.0;
            for i in 0..4 {
                for j in i + 1..4 {
                    let d: f64 = (0..3).map(|k| (c[i][k] - c[j][k]).powi(2)).sum();
                    longest = longest.max(d.sqrt());
                }
            }
            assert!(longest <= (0.1 + 0.4 * cx) * (1.0 + 1e-12), "tet {t}");
        }
        assert_eq!(post.num_point_attributes, 2);
        for (v, p) in mesh.vertices.iter().enumerate() {
            let a = &post.point_attributes[2 * v..2 * v + 2];
            assert!((a[0] - p[0]).abs() < 1e-12 && (a[1] - p[1] - p[2]).abs() < 1e-12);
        }
        let e = mesh_for(&sw("pm"), &plc, Options3::default(), &Extra::default()).unwrap_err();
        assert!(e.to_string().contains("-m"), "{e}");
    }
}
