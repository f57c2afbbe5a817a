//! Writers for TetGen's output formats: `.node`, `.ele`, `.face`, `.edge`, `.neigh`, and a
//! PLC as a self-contained `.poly` file.
//!
//! Layouts follow TetGen's output (a header line, then one item per line numbered from
//! `base`); fields are separated by single spaces and floats are written as
//! [`Real`](super::Real) writes them, so that they read back exactly. Every writer buffers
//! internally (in large blocks), so passing a bare `File` is fine.

use std::collections::HashMap;
use std::io::{self, Write};

use super::numfmt::Out;
use crate::input3d::Plc;
use crate::mesh3d::{TetMesh, NONE};

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message)
}

fn check_len(what: &str, got: usize, expected: usize) -> io::Result<()> {
    if got != expected {
        return Err(invalid(format!(
            "{got} {what} entries, expected {expected}"
        )));
    }
    Ok(())
}

/// Writes the `.node` file of `mesh`: header `n 3 0 m`, then `i x y z [marker]` per vertex
/// (markers when `markers` is set, as TetGen does when the input had point markers).
pub fn write_node<W: Write>(out: W, mesh: &TetMesh, base: u32, markers: bool) -> io::Result<()> {
    write_node_with(out, mesh, &[], 0, &[], base, markers)
}

/// [`write_node`] with `extra` points after the mesh's vertices (TetGen's `-o2` nodes, marker
/// 0) and `na` attributes per point (`attributes` covers every point written).
pub fn write_node_with<W: Write>(
    out: W,
    mesh: &TetMesh,
    extra: &[[f64; 3]],
    na: usize,
    attributes: &[f64],
    base: u32,
    markers: bool,
) -> io::Result<()> {
    if markers {
        check_len(
            "vertex marker",
            mesh.vertex_markers.len(),
            mesh.vertices.len(),
        )?;
    }
    let n = mesh.vertices.len() + extra.len();
    check_len("point attribute", attributes.len(), n * na)?;
    let mut w = Out::new(out);
    w.uint(n as u64)
        .uint(3)
        .uint(na as u64)
        .uint(markers as u64)
        .end_line()?;
    let b = base as u64;
    for (i, p) in mesh.vertices.iter().chain(extra).enumerate() {
        w.uint(i as u64 + b).real(p[0]).real(p[1]).real(p[2]);
        for a in &attributes[i * na..(i + 1) * na] {
            w.real(*a);
        }
        if markers {
            w.int(mesh.vertex_markers.get(i).copied().unwrap_or(0) as i64);
        }
        w.end_line()?;
    }
    w.finish()
}

/// Writes the `.ele` file of `mesh`: header `n 4 a` (`a` is 1 when the mesh carries regional
/// attributes, else 0), then `i v0 v1 v2 v3 [attribute]` per tetrahedron, positively
/// oriented as in TetGen.
pub fn write_ele<W: Write>(out: W, mesh: &TetMesh, base: u32) -> io::Result<()> {
    let corners: Vec<&[u32]> = mesh.tets.iter().map(|t| &t[..]).collect();
    write_ele_with(out, mesh, &corners, base)
}

/// [`write_ele`] with the node lists `corners` (one per tetrahedron, e.g. 10 nodes for
/// TetGen's `-o2`), all of the same length.
pub fn write_ele_with<W: Write>(
    out: W,
    mesh: &TetMesh,
    corners: &[&[u32]],
    base: u32,
) -> io::Result<()> {
    let nt = mesh.tets.len();
    check_len("tetrahedron", corners.len(), nt)?;
    let k = corners.first().map_or(4, |c| c.len());
    if corners.iter().any(|c| c.len() != k) {
        return Err(invalid("tetrahedra with different node counts".into()));
    }
    let with_attr = !mesh.tet_attributes.is_empty();
    if with_attr {
        check_len("tetrahedron attribute", mesh.tet_attributes.len(), nt)?;
    }
    let mut w = Out::new(out);
    w.uint(nt as u64)
        .uint(k as u64)
        .uint(with_attr as u64)
        .end_line()?;
    let b = base as u64;
    for (i, t) in corners.iter().enumerate() {
        w.uint(i as u64 + b);
        for v in t.iter() {
            w.uint(*v as u64 + b);
        }
        if with_attr {
            w.real(mesh.tet_attributes[i]);
        }
        w.end_line()?;
    }
    w.finish()
}

/// Writes `<count> <markers>` and one `i v.. [marker]` line per simplex.
fn write_simplices<W: Write, const K: usize>(
    out: W,
    items: &[[u32; K]],
    item_markers: Option<&[i32]>,
    base: u32,
) -> io::Result<()> {
    let mut w = Out::new(out);
    w.uint(items.len() as u64)
        .uint(item_markers.is_some() as u64)
        .end_line()?;
    let b = base as u64;
    for (i, s) in items.iter().enumerate() {
        w.uint(i as u64 + b);
        for v in s {
            w.uint(*v as u64 + b);
        }
        if let Some(m) = item_markers {
            w.int(m[i] as i64);
        }
        w.end_line()?;
    }
    w.finish()
}

/// Writes the `.face` file of `mesh`: its subfaces (boundary faces and faces in facets),
/// header `n m`, then `i a b c [marker]`.
pub fn write_face<W: Write>(out: W, mesh: &TetMesh, base: u32, markers: bool) -> io::Result<()> {
    let m = if markers {
        check_len("face marker", mesh.face_markers.len(), mesh.faces.len())?;
        Some(mesh.face_markers.as_slice())
    } else {
        None
    };
    write_simplices(out, &mesh.faces, m, base)
}

/// Writes every face of the tetrahedralization once (TetGen's `-f`), in tetrahedron order;
/// the marker of a subface is its facet's, 0 for other faces.
pub fn write_all_faces<W: Write>(
    out: W,
    mesh: &TetMesh,
    base: u32,
    markers: bool,
) -> io::Result<()> {
    check_len("neighbour", mesh.neighbors.len(), mesh.tets.len())?;
    check_len("face marker", mesh.face_markers.len(), mesh.faces.len())?;
    let sorted = |f: [u32; 3]| {
        let mut k = f;
        k.sort_unstable();
        k
    };
    let marker_of: HashMap<[u32; 3], i32> = mesh
        .faces
        .iter()
        .zip(&mesh.face_markers)
        .map(|(f, &m)| (sorted(*f), m))
        .collect();
    let mut faces = Vec::new();
    let mut face_markers = Vec::new();
    for (t, tv) in mesh.tets.iter().enumerate() {
        for i in 0..4 {
            let n = mesh.neighbors[t][i];
            if n != NONE && n as usize <= t {
                continue;
            }
            // The face opposite corner i, ordered so that it is seen counter-clockwise from
            // outside the tetrahedron.
            let f = match i {
                0 => [tv[1], tv[2], tv[3]],
                1 => [tv[0], tv[3], tv[2]],
                2 => [tv[0], tv[1], tv[3]],
                _ => [tv[0], tv[2], tv[1]],
            };
            faces.push(f);
            face_markers.push(marker_of.get(&sorted(f)).copied().unwrap_or(0));
        }
    }
    write_simplices(
        out,
        &faces,
        markers.then_some(face_markers.as_slice()),
        base,
    )
}

/// Writes the `.edge` file of `mesh`: its subsegments, header `n m`, then `i a b [marker]`.
pub fn write_edge<W: Write>(out: W, mesh: &TetMesh, base: u32, markers: bool) -> io::Result<()> {
    let m = if markers {
        check_len("edge marker", mesh.edge_markers.len(), mesh.edges.len())?;
        Some(mesh.edge_markers.as_slice())
    } else {
        None
    };
    write_simplices(out, &mesh.edges, m, base)
}

/// Every edge of the tetrahedralization once, in tetrahedron order (corner pairs (0,1),
/// (1,2), (2,0), (0,3), (1,3), (2,3), as the TetGen compatibility layer lists them), with its
/// marker: the subsegment's, 0 for other edges. TetGen's `-e` writes these.
pub fn all_edges(mesh: &TetMesh) -> (Vec<[u32; 2]>, Vec<i32>) {
    let key = |a: u32, b: u32| ((a.min(b) as u64) << 32) | a.max(b) as u64;
    let marker_of: HashMap<u64, i32> = mesh
        .edges
        .iter()
        .zip(
            mesh.edge_markers
                .iter()
                .copied()
                .chain(std::iter::repeat(0)),
        )
        .map(|(e, m)| (key(e[0], e[1]), m))
        .collect();
    let mut seen = std::collections::HashSet::with_capacity(mesh.vertices.len() * 7);
    let mut edges = Vec::new();
    let mut markers = Vec::new();
    for t in &mesh.tets {
        for (i, j) in [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)] {
            let k = key(t[i], t[j]);
            if seen.insert(k) {
                edges.push([t[i], t[j]]);
                markers.push(marker_of.get(&k).copied().unwrap_or(0));
            }
        }
    }
    (edges, markers)
}

/// Writes every edge of `mesh` ([`all_edges`]), TetGen's `-e`: header `n m`, then
/// `i a b [marker]`.
pub fn write_all_edges<W: Write>(
    out: W,
    mesh: &TetMesh,
    base: u32,
    markers: bool,
) -> io::Result<()> {
    let (edges, m) = all_edges(mesh);
    write_simplices(out, &edges, markers.then_some(m.as_slice()), base)
}

/// Writes the `.neigh` file of `mesh`: header `n 4`, then `i n0 n1 n2 n3` where `nk` is the
/// tetrahedron opposite corner `k`, numbered from `base`, or -1 on the boundary.
pub fn write_neigh<W: Write>(out: W, mesh: &TetMesh, base: u32) -> io::Result<()> {
    check_len("neighbour", mesh.neighbors.len(), mesh.tets.len())?;
    let b = base as i64;
    let id = |n: u32| if n == NONE { -1 } else { n as i64 + b };
    let mut w = Out::new(out);
    w.uint(mesh.neighbors.len() as u64).uint(4).end_line()?;
    for (i, n) in mesh.neighbors.iter().enumerate() {
        w.int(i as i64 + b)
            .int(id(n[0]))
            .int(id(n[1]))
            .int(id(n[2]))
            .int(id(n[3]))
            .end_line()?;
    }
    w.finish()
}

/// Writes a PLC as a self-contained `.poly` file numbered from `base`: the inverse of
/// [`super::tetgen::parse_poly`]. Point markers are written when the PLC has them; facet
/// markers always. TetGen's `.poly` format has no section for free segments, so a PLC with
/// segments is refused.
pub fn write_plc_poly<W: Write>(out: W, plc: &Plc, base: u32) -> io::Result<()> {
    if !plc.segments.is_empty() {
        return Err(invalid(format!(
            "the PLC has {} free segments, which TetGen's .poly format cannot hold",
            plc.segments.len()
        )));
    }
    let np = plc.points.len();
    let markers = !plc.point_markers.is_empty();
    if markers {
        check_len("point marker", plc.point_markers.len(), np)?;
    }
    let b = base as u64;
    let mut w = Out::new(out);
    w.uint(np as u64)
        .uint(3)
        .uint(0)
        .uint(markers as u64)
        .end_line()?;
    for (i, p) in plc.points.iter().enumerate() {
        w.uint(i as u64 + b).real(p[0]).real(p[1]).real(p[2]);
        if markers {
            w.int(plc.point_markers[i] as i64);
        }
        w.end_line()?;
    }
    w.uint(plc.facets.len() as u64).uint(1).end_line()?;
    for f in &plc.facets {
        w.uint(f.polygons.len() as u64)
            .uint(f.holes.len() as u64)
            .int(f.marker as i64)
            .end_line()?;
        for poly in &f.polygons {
            w.uint(poly.len() as u64);
            for v in poly {
                w.uint(*v as u64 + b);
            }
            w.end_line()?;
        }
        write_points(&mut w, &f.holes, b)?;
    }
    w.uint(plc.holes.len() as u64).end_line()?;
    write_points(&mut w, &plc.holes, b)?;
    w.uint(plc.regions.len() as u64).end_line()?;
    for (i, r) in plc.regions.iter().enumerate() {
        // A negative volume is TetGen's "no bound".
        w.uint(i as u64 + b)
            .real(r.point[0])
            .real(r.point[1])
            .real(r.point[2])
            .real(r.attribute)
            .real(r.max_volume.unwrap_or(-1.0))
            .end_line()?;
    }
    w.finish()
}

/// Writes `i x y z` lines (hole seeds), numbered from `base`.
fn write_points<W: Write>(w: &mut Out<W>, points: &[[f64; 3]], base: u64) -> io::Result<()> {
    for (i, p) in points.iter().enumerate() {
        w.uint(i as u64 + base)
            .real(p[0])
            .real(p[1])
            .real(p[2])
            .end_line()?;
    }
    Ok(())
}
