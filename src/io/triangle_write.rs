//! Writers for Triangle's output formats: `.node`, `.ele`, `.poly`, `.edge`, `.neigh`.
//!
//! Layouts follow Triangle's output (one item per line, numbered from `base`); fields are
//! separated by single spaces and floats are written as [`Real`](super::Real) writes them, so
//! that they read back exactly. Every writer buffers internally (in large blocks, see
//! [`Out`]), so passing a bare `File` is fine.

use std::io::{self, Write};

use super::numfmt::Out;
use crate::input2d::{Pslg, Region};
use crate::mesh2d::{TriMesh, NONE};

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message)
}

/// Writes the `.node` file of `mesh`: header `n 2 0 1`, then `i x y marker` per vertex.
pub fn write_node<W: Write>(out: W, mesh: &TriMesh, base: u32) -> io::Result<()> {
    write_node_attributes(out, mesh, base, 0, &[])
}

/// Writes the `.node` file of `mesh` with `per_point` attributes per vertex (`attributes`,
/// vertex by vertex, as [`crate::mesh2d::interpolate_point_attributes`] gives them): header
/// `n 2 per_point 1`, then `i x y attributes... marker` per vertex.
pub fn write_node_attributes<W: Write>(
    out: W,
    mesh: &TriMesh,
    base: u32,
    per_point: usize,
    attributes: &[f64],
) -> io::Result<()> {
    if attributes.len() != per_point * mesh.vertices.len() {
        return Err(invalid(format!(
            "{} point attribute values for {} vertices with {per_point} each",
            attributes.len(),
            mesh.vertices.len()
        )));
    }
    let mut w = Out::new(out);
    w.uint(mesh.vertices.len() as u64)
        .uint(2)
        .uint(per_point as u64)
        .uint(1)
        .end_line()?;
    for (i, p) in mesh.vertices.iter().enumerate() {
        let marker = mesh.vertex_markers.get(i).copied().unwrap_or(0);
        w.uint(i as u64 + base as u64).real(p[0]).real(p[1]);
        for &a in &attributes[i * per_point..(i + 1) * per_point] {
            w.real(a);
        }
        w.int(marker as i64).end_line()?;
    }
    w.finish()
}

/// Writes the `.ele` file of `mesh`: header `n 3 a` (`a` is 1 when the mesh carries regional
/// attributes, else 0), then `i v0 v1 v2 [attribute]` per triangle, corners counter-clockwise.
pub fn write_ele<W: Write>(out: W, mesh: &TriMesh, base: u32) -> io::Result<()> {
    let nt = mesh.triangles.len();
    let with_attr = !mesh.triangle_attributes.is_empty();
    if with_attr && mesh.triangle_attributes.len() != nt {
        return Err(invalid(format!(
            "mesh has {nt} triangles but {} triangle attributes",
            mesh.triangle_attributes.len()
        )));
    }
    let mut w = Out::new(out);
    w.uint(nt as u64)
        .uint(3)
        .uint(with_attr as u64)
        .end_line()?;
    let b = base as u64;
    for (i, t) in mesh.triangles.iter().enumerate() {
        w.uint(i as u64 + b)
            .uint(t[0] as u64 + b)
            .uint(t[1] as u64 + b)
            .uint(t[2] as u64 + b);
        if with_attr {
            w.real(mesh.triangle_attributes[i]);
        }
        w.end_line()?;
    }
    w.finish()
}

/// Writes the output `.poly` file of `mesh`, as Triangle does: header `0 2 0 1` (the vertices
/// are in the `.node` file), the mesh's subsegments with their markers, the input's holes,
/// and the input's regions (only when there are any).
pub fn write_poly<W: Write>(
    out: W,
    mesh: &TriMesh,
    base: u32,
    holes: &[[f64; 2]],
    regions: &[Region],
) -> io::Result<()> {
    write_poly_segments(
        out,
        &mesh.segments,
        &mesh.segment_markers,
        base,
        holes,
        regions,
    )
}

/// Like [`write_poly`] but with explicit segments, for callers that write other edges (for
/// example the convex hull edges of a point set). `markers` may be empty (all 1, Triangle's
/// boundary marker).
pub fn write_poly_segments<W: Write>(
    out: W,
    segments: &[[u32; 2]],
    markers: &[i32],
    base: u32,
    holes: &[[f64; 2]],
    regions: &[Region],
) -> io::Result<()> {
    if !markers.is_empty() && markers.len() != segments.len() {
        return Err(invalid(format!(
            "{} segments but {} segment markers",
            segments.len(),
            markers.len()
        )));
    }
    let mut w = Out::new(out);
    w.uint(0).uint(2).uint(0).uint(1).end_line()?;
    write_segments(&mut w, segments, markers, true, base)?;
    write_holes_and_regions(&mut w, holes, regions, base)?;
    w.finish()
}

fn write_segments<W: Write>(
    w: &mut Out<W>,
    segments: &[[u32; 2]],
    markers: &[i32],
    with_markers: bool,
    base: u32,
) -> io::Result<()> {
    let b = base as u64;
    w.uint(segments.len() as u64)
        .uint(with_markers as u64)
        .end_line()?;
    for (i, s) in segments.iter().enumerate() {
        w.uint(i as u64 + b)
            .uint(s[0] as u64 + b)
            .uint(s[1] as u64 + b);
        if with_markers {
            w.int(markers.get(i).copied().unwrap_or(1) as i64);
        }
        w.end_line()?;
    }
    Ok(())
}

fn write_holes_and_regions<W: Write>(
    w: &mut Out<W>,
    holes: &[[f64; 2]],
    regions: &[Region],
    base: u32,
) -> io::Result<()> {
    let b = base as u64;
    w.uint(holes.len() as u64).end_line()?;
    for (i, h) in holes.iter().enumerate() {
        w.uint(i as u64 + b).real(h[0]).real(h[1]).end_line()?;
    }
    if !regions.is_empty() {
        w.uint(regions.len() as u64).end_line()?;
        for (i, r) in regions.iter().enumerate() {
            // A negative area is Triangle's "no bound".
            w.uint(i as u64 + b)
                .real(r.point[0])
                .real(r.point[1])
                .real(r.attribute)
                .real(r.max_area.unwrap_or(-1.0))
                .end_line()?;
        }
    }
    Ok(())
}

/// Writes the `.edge` file of `mesh`: header `n 1`, then `i a b marker` for every edge in the
/// order of [`TriMesh::edges`] (marker: the segment's marker, 0 for other edges).
pub fn write_edge<W: Write>(out: W, mesh: &TriMesh, base: u32) -> io::Result<()> {
    check_neighbors(mesh)?;
    let edges = mesh.edges();
    let b = base as u64;
    let mut w = Out::new(out);
    w.uint(edges.len() as u64).uint(1).end_line()?;
    for (i, (e, m)) in edges.iter().enumerate() {
        w.uint(i as u64 + b)
            .uint(e[0] as u64 + b)
            .uint(e[1] as u64 + b)
            .int(*m as i64)
            .end_line()?;
    }
    w.finish()
}

/// Writes the `.neigh` file of `mesh`: header `n 3`, then `i n0 n1 n2` where `nk` is the
/// triangle opposite corner `k`, numbered from `base`, or -1 on the boundary.
pub fn write_neigh<W: Write>(out: W, mesh: &TriMesh, base: u32) -> io::Result<()> {
    check_neighbors(mesh)?;
    let b = base as i64;
    let id = |n: u32| if n == NONE { -1 } else { n as i64 + b };
    let mut w = Out::new(out);
    w.uint(mesh.neighbors.len() as u64).uint(3).end_line()?;
    for (i, n) in mesh.neighbors.iter().enumerate() {
        w.int(i as i64 + b)
            .int(id(n[0]))
            .int(id(n[1]))
            .int(id(n[2]))
            .end_line()?;
    }
    w.finish()
}

fn check_neighbors(mesh: &TriMesh) -> io::Result<()> {
    if mesh.neighbors.len() != mesh.triangles.len() {
        return Err(invalid(format!(
            "mesh has {} triangles but {} neighbour entries",
            mesh.triangles.len(),
            mesh.neighbors.len()
        )));
    }
    Ok(())
}

/// Writes a PSLG as a self-contained `.poly` file (vertices included), numbered from `base`:
/// the inverse of [`super::triangle::parse_poly`]. Markers are written only when the PSLG has
/// them.
pub fn write_pslg_poly<W: Write>(out: W, pslg: &Pslg, base: u32) -> io::Result<()> {
    let np = pslg.points.len();
    let point_markers = !pslg.point_markers.is_empty();
    if point_markers && pslg.point_markers.len() != np {
        return Err(invalid(format!(
            "{np} points but {} point markers",
            pslg.point_markers.len()
        )));
    }
    let seg_markers = !pslg.segment_markers.is_empty();
    if seg_markers && pslg.segment_markers.len() != pslg.segments.len() {
        return Err(invalid(format!(
            "{} segments but {} segment markers",
            pslg.segments.len(),
            pslg.segment_markers.len()
        )));
    }
    let mut w = Out::new(out);
    w.uint(np as u64)
        .uint(2)
        .uint(0)
        .uint(point_markers as u64)
        .end_line()?;
    for (i, p) in pslg.points.iter().enumerate() {
        w.uint(i as u64 + base as u64).real(p[0]).real(p[1]);
        if point_markers {
            w.int(pslg.point_markers[i] as i64);
        }
        w.end_line()?;
    }
    write_segments(
        &mut w,
        &pslg.segments,
        &pslg.segment_markers,
        seg_markers,
        base,
    )?;
    write_holes_and_regions(&mut w, &pslg.holes, &pslg.regions, base)?;
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::super::triangle::{parse_ele, parse_node, parse_poly, TriangleInput};
    use super::*;
    use crate::io::ParseError;

    fn no_node() -> Result<TriangleInput, ParseError> {
        Err(ParseError::new("none", 0, "no .node"))
    }

    fn text(f: impl FnOnce(&mut Vec<u8>) -> io::Result<()>) -> String {
        let mut buf = Vec::new();
        f(&mut buf).unwrap();
        String::from_utf8(buf).unwrap()
    }

    /// Two triangles forming the unit square, split along 0-2, with awkward coordinates.
    fn square() -> TriMesh {
        TriMesh {
            vertices: vec![
                [0.1, -0.0],
                [1.0 / 3.0, 1e-300],
                [2.5e17, 0.7],
                [-7.25, 1.0],
            ],
            vertex_markers: vec![1, 0, -4, 2],
            num_input_vertices: 4,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            neighbors: vec![[NONE, 1, NONE], [NONE, NONE, 0]],
            triangle_attributes: vec![],
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
            segment_markers: vec![5, 5, 6, 7],
            complete: true,
            steiner_points: 0,
        }
    }

    #[test]
    fn node_round_trips_exactly_in_both_bases() {
        let m = square();
        for base in [0, 1] {
            let s = text(|b| write_node(b, &m, base));
            assert!(s.starts_with("4 2 0 1\n"), "{s}");
            let back = parse_node(&s, "out.node").unwrap();
            assert_eq!(back.base, base);
            assert_eq!(back.pslg.point_markers, m.vertex_markers);
            for (a, b) in back.pslg.points.iter().zip(&m.vertices) {
                assert_eq!(a[0].to_bits(), b[0].to_bits());
                assert_eq!(a[1].to_bits(), b[1].to_bits());
            }
        }
    }

    #[test]
    fn ele_round_trips_with_and_without_attributes() {
        let mut m = square();
        let s = text(|b| write_ele(b, &m, 1));
        assert_eq!(s, "2 3 0\n1 1 2 3\n2 1 3 4\n");
        let back = parse_ele(&s, "o.ele", 1, 4).unwrap();
        assert_eq!(back.triangles, m.triangles);
        m.triangle_attributes = vec![2.5, -1.0];
        let s = text(|b| write_ele(b, &m, 0));
        let back = parse_ele(&s, "o.ele", 0, 4).unwrap();
        assert_eq!(back.triangles, m.triangles);
        assert_eq!(back.attributes, m.triangle_attributes);
        m.triangle_attributes = vec![1.0];
        assert!(write_ele(Vec::new(), &m, 0).is_err());
    }

    #[test]
    fn output_poly_lists_subsegments_holes_and_regions() {
        let m = square();
        let regions = [Region {
            point: [0.5, 0.5],
            attribute: 3.0,
            max_area: None,
        }];
        let s = text(|b| write_poly(b, &m, 1, &[[0.25, 0.75]], &regions));
        assert!(s.starts_with("0 2 0 1\n4 1\n1 1 2 5\n"), "{s}");
        assert!(s.ends_with("1\n1 0.25 0.75\n1\n1 0.5 0.5 3 -1\n"), "{s}");
        // Read back against the written .node: same segments, markers, holes, regions.
        let node = text(|b| write_node(b, &m, 1));
        let back = parse_poly(&s, "o.poly", || parse_node(&node, "o.node")).unwrap();
        assert_eq!(back.pslg.segments, m.segments);
        assert_eq!(back.pslg.segment_markers, m.segment_markers);
        assert_eq!(back.pslg.holes, vec![[0.25, 0.75]]);
        assert_eq!(back.pslg.regions, regions.to_vec());
        // No regions: the optional section is left out, as Triangle does.
        let s = text(|b| write_poly(b, &m, 0, &[], &[]));
        assert!(s.ends_with("3 3 0 7\n0\n"), "{s}");
    }

    #[test]
    fn edge_file_lists_each_edge_once_with_markers() {
        let m = square();
        let s = text(|b| write_edge(b, &m, 1));
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines[0], "5 1");
        assert_eq!(lines.len(), 6);
        // The diagonal 0-2 (1-3 in base 1) is no segment: marker 0.
        let diag: Vec<&&str> = lines
            .iter()
            .filter(|l| l.ends_with(" 1 3 0") || l.ends_with(" 3 1 0"))
            .collect();
        assert_eq!(diag.len(), 1, "{s}");
        assert!(lines.iter().any(|l| l.ends_with(" 5")), "{s}");
    }

    #[test]
    fn neigh_file_numbers_from_base_and_keeps_minus_one() {
        let m = square();
        assert_eq!(
            text(|b| write_neigh(b, &m, 0)),
            "2 3\n0 -1 1 -1\n1 -1 -1 0\n"
        );
        assert_eq!(
            text(|b| write_neigh(b, &m, 1)),
            "2 3\n1 -1 2 -1\n2 -1 -1 1\n"
        );
        let mut bad = square();
        bad.neighbors.pop();
        assert!(write_neigh(Vec::new(), &bad, 0).is_err());
    }

    #[test]
    fn pslg_round_trips_through_poly_text() {
        let pslg = Pslg {
            points: vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [0.1, 1e-17]],
            point_markers: vec![1, 1, 2, 2, 0],
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
            segment_markers: vec![-1, 2, 3, 4],
            holes: vec![[0.5, 0.5]],
            regions: vec![
                Region {
                    point: [1.5, 0.5],
                    attribute: 2.0,
                    max_area: Some(0.125),
                },
                Region {
                    point: [0.2, 0.2],
                    attribute: -1.0,
                    max_area: None,
                },
            ],
        };
        for base in [0, 1] {
            let s = text(|b| write_pslg_poly(b, &pslg, base));
            let back = parse_poly(&s, "p.poly", no_node).unwrap();
            assert_eq!(back.base, base);
            assert_eq!(back.pslg, pslg, "{s}");
        }
        // Without markers the marker columns are left out and read back as empty.
        let bare = Pslg {
            point_markers: vec![],
            segment_markers: vec![],
            ..pslg.clone()
        };
        let s = text(|b| write_pslg_poly(b, &bare, 1));
        assert!(s.starts_with("5 2 0 0\n"), "{s}");
        assert_eq!(parse_poly(&s, "p.poly", no_node).unwrap().pslg, bare);
    }
}
