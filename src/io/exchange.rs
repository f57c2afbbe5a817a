//! Writers for the formats that visualisation and FEM tools read: legacy VTK (`.vtk`, TetGen's
//! `-k`), VTK XML unstructured grids (`.vtu`), Gmsh 4.1 (`.msh`) and Medit (`.mesh`, TetGen's
//! `-g`), for 2D triangle meshes and 3D tetrahedral meshes alike.
//!
//! Every writer sees a mesh through one [`MeshView`]: the vertices, the cells (triangles or
//! tetrahedra, with their regional attribute when the mesh has one) and the boundary elements
//! (subsegments in 2D, subfaces in 3D) with their markers. Each file holds both the cells and
//! the boundary elements, so that boundary conditions can be attached by marker:
//!
//! * VTK and VTU: the cells come first, then the boundary elements; cell data `region` (the
//!   regional attribute of a cell, 0 for boundary elements) and `marker` (the boundary marker,
//!   0 for cells); point data `marker` (the vertex markers).
//! * Gmsh: one elementary entity per region of cells and one per boundary marker; its physical
//!   tag is the marker (markers above 0) or, for regions, its number from 1, named
//!   `region_<attribute>`; nodes are numbered from 1 in vertex order.
//! * Medit: the reference of a vertex is its marker, of a boundary element its marker, of a
//!   cell its regional attribute rounded to an integer (0 without attributes).
//!
//! Orientation is kept: triangles counter-clockwise, tetrahedra positively oriented, which is
//! each format's own convention. Floats are written so that they read back bit for bit.

use std::collections::BTreeMap;
use std::io::{self, BufWriter, Write};

use super::numfmt::Real;
use crate::mesh2d::TriMesh;
use crate::mesh3d::TetMesh;

const BUFFER: usize = 1 << 16;

/// The exchange formats idmesh writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Legacy VTK, ASCII (`.vtk`).
    Vtk,
    /// VTK XML unstructured grid, ASCII (`.vtu`).
    Vtu,
    /// Gmsh 4.1, ASCII (`.msh`).
    Msh,
    /// Medit (`.mesh`).
    Medit,
}

impl Format {
    /// The format named `name` (`vtk`, `vtu`, `msh`, `mesh`), as given to `--format`.
    pub fn from_name(name: &str) -> Option<Format> {
        match name {
            "vtk" => Some(Format::Vtk),
            "vtu" => Some(Format::Vtu),
            "msh" => Some(Format::Msh),
            "mesh" => Some(Format::Medit),
            _ => None,
        }
    }

    /// The file name extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Vtk => "vtk",
            Format::Vtu => "vtu",
            Format::Msh => "msh",
            Format::Medit => "mesh",
        }
    }
}

/// A mesh as the exchange writers see it: `D` coordinates per vertex, `C` vertices per cell,
/// `B` vertices per boundary element.
#[derive(Debug, Clone, Copy)]
pub struct MeshView<'a, const D: usize, const C: usize, const B: usize> {
    /// Vertex coordinates.
    pub vertices: &'a [[f64; D]],
    /// One marker per vertex (or empty).
    pub vertex_markers: &'a [i32],
    /// The cells.
    pub cells: &'a [[u32; C]],
    /// One regional attribute per cell (or empty).
    pub cell_attributes: &'a [f64],
    /// The boundary elements.
    pub boundary: &'a [[u32; B]],
    /// One marker per boundary element (or empty).
    pub boundary_markers: &'a [i32],
}

impl<'a> From<&'a TriMesh> for MeshView<'a, 2, 3, 2> {
    fn from(m: &'a TriMesh) -> Self {
        MeshView {
            vertices: &m.vertices,
            vertex_markers: &m.vertex_markers,
            cells: &m.triangles,
            cell_attributes: &m.triangle_attributes,
            boundary: &m.segments,
            boundary_markers: &m.segment_markers,
        }
    }
}

impl<'a> From<&'a TetMesh> for MeshView<'a, 3, 4, 3> {
    fn from(m: &'a TetMesh) -> Self {
        MeshView {
            vertices: &m.vertices,
            vertex_markers: &m.vertex_markers,
            cells: &m.tets,
            cell_attributes: &m.tet_attributes,
            boundary: &m.faces,
            boundary_markers: &m.face_markers,
        }
    }
}

/// Writes `mesh` in `format`.
pub fn write<W: Write, const D: usize, const C: usize, const B: usize>(
    out: W,
    mesh: MeshView<'_, D, C, B>,
    format: Format,
) -> io::Result<()> {
    mesh.check()?;
    let mut w = BufWriter::with_capacity(BUFFER, out);
    match format {
        Format::Vtk => write_vtk(&mut w, &mesh)?,
        Format::Vtu => write_vtu(&mut w, &mesh)?,
        Format::Msh => write_msh(&mut w, &mesh)?,
        Format::Medit => write_medit(&mut w, &mesh)?,
    }
    w.flush()
}

impl<const D: usize, const C: usize, const B: usize> MeshView<'_, D, C, B> {
    fn check(&self) -> io::Result<()> {
        let lens = [
            (
                "vertex marker",
                self.vertex_markers.len(),
                self.vertices.len(),
            ),
            (
                "cell attribute",
                self.cell_attributes.len(),
                self.cells.len(),
            ),
            (
                "boundary marker",
                self.boundary_markers.len(),
                self.boundary.len(),
            ),
        ];
        for (what, got, want) in lens {
            if got != 0 && got != want {
                return Err(io::Error::new(
                    io::ErrorKind::InvalidData,
                    format!("{got} {what} entries, expected {want}"),
                ));
            }
        }
        let n = self.vertices.len();
        let bad = self
            .cells
            .iter()
            .flatten()
            .chain(self.boundary.iter().flatten());
        if let Some(v) = bad.into_iter().find(|&&v| v as usize >= n) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!("vertex index {v} out of range (the mesh has {n} vertices)"),
            ));
        }
        Ok(())
    }

    fn vertex_marker(&self, i: usize) -> i32 {
        self.vertex_markers.get(i).copied().unwrap_or(0)
    }

    fn boundary_marker(&self, i: usize) -> i32 {
        self.boundary_markers.get(i).copied().unwrap_or(0)
    }

    fn cell_attribute(&self, i: usize) -> f64 {
        self.cell_attributes.get(i).copied().unwrap_or(0.0)
    }

    /// The coordinates of vertex `i` padded to 3D.
    fn xyz(&self, i: usize) -> [f64; 3] {
        let mut p = [0.0; 3];
        p[..D].copy_from_slice(&self.vertices[i]);
        p
    }

    fn num_elements(&self) -> usize {
        self.cells.len() + self.boundary.len()
    }
}

/// VTK cell type of a simplex with `k` vertices (line, triangle, tetrahedron).
fn vtk_type(k: usize) -> u8 {
    match k {
        2 => 3,
        3 => 5,
        _ => 10,
    }
}

/// Gmsh element type of a simplex with `k` vertices (line, triangle, tetrahedron).
fn msh_type(k: usize) -> u8 {
    match k {
        2 => 1,
        3 => 2,
        _ => 4,
    }
}

fn write_vtk<W: Write, const D: usize, const C: usize, const B: usize>(
    w: &mut W,
    m: &MeshView<'_, D, C, B>,
) -> io::Result<()> {
    let (nv, nc, nb) = (m.vertices.len(), m.cells.len(), m.boundary.len());
    writeln!(w, "# vtk DataFile Version 3.0")?;
    writeln!(w, "idmesh {}D mesh", D)?;
    writeln!(w, "ASCII")?;
    writeln!(w, "DATASET UNSTRUCTURED_GRID")?;
    writeln!(w, "POINTS {nv} double")?;
    for i in 0..nv {
        let p = m.xyz(i);
        writeln!(w, "{} {} {}", Real(p[0]), Real(p[1]), Real(p[2]))?;
    }
    writeln!(w, "CELLS {} {}", nc + nb, nc * (C + 1) + nb * (B + 1))?;
    for c in m.cells {
        write!(w, "{C}")?;
        for v in c {
            write!(w, " {v}")?;
        }
        writeln!(w)?;
    }
    for b in m.boundary {
        write!(w, "{B}")?;
        for v in b {
            write!(w, " {v}")?;
        }
        writeln!(w)?;
    }
    writeln!(w, "CELL_TYPES {}", nc + nb)?;
    for _ in 0..nc {
        writeln!(w, "{}", vtk_type(C))?;
    }
    for _ in 0..nb {
        writeln!(w, "{}", vtk_type(B))?;
    }
    writeln!(w, "CELL_DATA {}", nc + nb)?;
    writeln!(w, "SCALARS region double 1\nLOOKUP_TABLE default")?;
    for i in 0..nc {
        writeln!(w, "{}", Real(m.cell_attribute(i)))?;
    }
    for _ in 0..nb {
        writeln!(w, "0")?;
    }
    writeln!(w, "SCALARS marker int 1\nLOOKUP_TABLE default")?;
    for _ in 0..nc {
        writeln!(w, "0")?;
    }
    for i in 0..nb {
        writeln!(w, "{}", m.boundary_marker(i))?;
    }
    writeln!(w, "POINT_DATA {nv}")?;
    writeln!(w, "SCALARS marker int 1\nLOOKUP_TABLE default")?;
    for i in 0..nv {
        writeln!(w, "{}", m.vertex_marker(i))?;
    }
    Ok(())
}

fn write_vtu<W: Write, const D: usize, const C: usize, const B: usize>(
    w: &mut W,
    m: &MeshView<'_, D, C, B>,
) -> io::Result<()> {
    let (nv, nc, nb) = (m.vertices.len(), m.cells.len(), m.boundary.len());
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">"
    )?;
    writeln!(w, "<UnstructuredGrid>")?;
    writeln!(
        w,
        "<Piece NumberOfPoints=\"{nv}\" NumberOfCells=\"{}\">",
        nc + nb
    )?;
    writeln!(w, "<Points>")?;
    writeln!(
        w,
        "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
    )?;
    for i in 0..nv {
        let p = m.xyz(i);
        writeln!(w, "{} {} {}", Real(p[0]), Real(p[1]), Real(p[2]))?;
    }
    writeln!(w, "</DataArray>\n</Points>\n<Cells>")?;
    writeln!(
        w,
        "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
    )?;
    for c in m.cells {
        write_row(w, c)?;
    }
    for b in m.boundary {
        write_row(w, b)?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(
        w,
        "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
    )?;
    let mut off = 0usize;
    for k in std::iter::repeat(C)
        .take(nc)
        .chain(std::iter::repeat(B).take(nb))
    {
        off += k;
        writeln!(w, "{off}")?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(
        w,
        "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"
    )?;
    for k in std::iter::repeat(C)
        .take(nc)
        .chain(std::iter::repeat(B).take(nb))
    {
        writeln!(w, "{}", vtk_type(k))?;
    }
    writeln!(w, "</DataArray>\n</Cells>\n<CellData>")?;
    writeln!(
        w,
        "<DataArray type=\"Float64\" Name=\"region\" format=\"ascii\">"
    )?;
    for i in 0..nc {
        writeln!(w, "{}", Real(m.cell_attribute(i)))?;
    }
    for _ in 0..nb {
        writeln!(w, "0")?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(
        w,
        "<DataArray type=\"Int32\" Name=\"marker\" format=\"ascii\">"
    )?;
    for _ in 0..nc {
        writeln!(w, "0")?;
    }
    for i in 0..nb {
        writeln!(w, "{}", m.boundary_marker(i))?;
    }
    writeln!(w, "</DataArray>\n</CellData>\n<PointData>")?;
    writeln!(
        w,
        "<DataArray type=\"Int32\" Name=\"marker\" format=\"ascii\">"
    )?;
    for i in 0..nv {
        writeln!(w, "{}", m.vertex_marker(i))?;
    }
    writeln!(w, "</DataArray>\n</PointData>")?;
    writeln!(w, "</Piece>\n</UnstructuredGrid>\n</VTKFile>")?;
    Ok(())
}

fn write_row<W: Write>(w: &mut W, vs: &[u32]) -> io::Result<()> {
    for (i, v) in vs.iter().enumerate() {
        if i > 0 {
            w.write_all(b" ")?;
        }
        write!(w, "{v}")?;
    }
    writeln!(w)
}

/// Groups element indices by key, in key order: Gmsh's entities (regions and markers).
fn groups<K: Ord + Copy>(n: usize, key: impl Fn(usize) -> K) -> BTreeMap<K, Vec<usize>> {
    let mut g: BTreeMap<K, Vec<usize>> = BTreeMap::new();
    for i in 0..n {
        g.entry(key(i)).or_default().push(i);
    }
    g
}

fn write_msh<W: Write, const D: usize, const C: usize, const B: usize>(
    w: &mut W,
    m: &MeshView<'_, D, C, B>,
) -> io::Result<()> {
    let nv = m.vertices.len();
    // Regions are keyed by the attribute's bits (attributes are copied, never computed, so
    // equal attributes have equal bits); markers by value.
    let regions = groups(m.cells.len(), |i| m.cell_attribute(i).to_bits());
    let markers = groups(m.boundary.len(), |i| m.boundary_marker(i));
    let (cdim, bdim) = (C - 1, B - 1);

    // Bounding box, for the entities' records.
    let (mut lo, mut hi) = ([0.0f64; 3], [0.0f64; 3]);
    if nv > 0 {
        lo = m.xyz(0);
        hi = lo;
        for i in 1..nv {
            let p = m.xyz(i);
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    let bbox = |w: &mut W| -> io::Result<()> {
        write!(
            w,
            "{} {} {} {} {} {}",
            Real(lo[0]),
            Real(lo[1]),
            Real(lo[2]),
            Real(hi[0]),
            Real(hi[1]),
            Real(hi[2])
        )
    };

    writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?;
    let named_markers: Vec<i32> = markers.keys().copied().filter(|&k| k > 0).collect();
    writeln!(w, "$PhysicalNames\n{}", regions.len() + named_markers.len())?;
    for (r, bits) in regions.keys().enumerate() {
        writeln!(
            w,
            "{cdim} {} \"region_{}\"",
            r + 1,
            Real(f64::from_bits(*bits))
        )?;
    }
    for k in &named_markers {
        writeln!(w, "{bdim} {k} \"marker_{k}\"")?;
    }
    writeln!(w, "$EndPhysicalNames")?;

    // Entities: curves (2D) or surfaces (3D) for the markers, surfaces (2D) or volumes (3D)
    // for the regions; no bounding relations (they are optional for a mesh file).
    let mut counts = [0usize; 4];
    counts[bdim] = markers.len();
    counts[cdim] = regions.len();
    writeln!(w, "$Entities")?;
    writeln!(w, "{} {} {} {}", counts[0], counts[1], counts[2], counts[3])?;
    for dim in 1..4 {
        if dim == bdim {
            for (e, k) in markers.keys().enumerate() {
                write!(w, "{} ", e + 1)?;
                bbox(w)?;
                if *k > 0 {
                    writeln!(w, " 1 {k} 0")?;
                } else {
                    writeln!(w, " 0 0")?;
                }
            }
        } else if dim == cdim {
            for e in 0..regions.len() {
                write!(w, "{} ", e + 1)?;
                bbox(w)?;
                writeln!(w, " 1 {} 0", e + 1)?;
            }
        }
    }
    writeln!(w, "$EndEntities")?;

    // Nodes: one block, classified on the first cell entity (a mesh file needs no more).
    writeln!(w, "$Nodes")?;
    if nv == 0 {
        writeln!(w, "0 0 0 0")?;
    } else {
        writeln!(w, "1 {nv} 1 {nv}")?;
        writeln!(w, "{cdim} 1 0 {nv}")?;
        for i in 1..=nv {
            writeln!(w, "{i}")?;
        }
        for i in 0..nv {
            let p = m.xyz(i);
            writeln!(w, "{} {} {}", Real(p[0]), Real(p[1]), Real(p[2]))?;
        }
    }
    writeln!(w, "$EndNodes")?;

    let ne = m.num_elements();
    writeln!(w, "$Elements")?;
    writeln!(
        w,
        "{} {ne} {} {ne}",
        regions.len() + markers.len(),
        ne.min(1)
    )?;
    let mut tag = 0usize;
    for (e, cells) in regions.values().enumerate() {
        writeln!(w, "{cdim} {} {} {}", e + 1, msh_type(C), cells.len())?;
        for &i in cells {
            tag += 1;
            write!(w, "{tag}")?;
            for v in &m.cells[i] {
                write!(w, " {}", *v as u64 + 1)?;
            }
            writeln!(w)?;
        }
    }
    for (e, items) in markers.values().enumerate() {
        writeln!(w, "{bdim} {} {} {}", e + 1, msh_type(B), items.len())?;
        for &i in items {
            tag += 1;
            write!(w, "{tag}")?;
            for v in &m.boundary[i] {
                write!(w, " {}", *v as u64 + 1)?;
            }
            writeln!(w)?;
        }
    }
    writeln!(w, "$EndElements")?;
    Ok(())
}

fn write_medit<W: Write, const D: usize, const C: usize, const B: usize>(
    w: &mut W,
    m: &MeshView<'_, D, C, B>,
) -> io::Result<()> {
    writeln!(w, "MeshVersionFormatted 2\n\nDimension {D}\n")?;
    writeln!(w, "Vertices\n{}", m.vertices.len())?;
    for (i, p) in m.vertices.iter().enumerate() {
        for x in p {
            write!(w, "{} ", Real(*x))?;
        }
        writeln!(w, "{}", m.vertex_marker(i))?;
    }
    let (bname, cname) = if D == 2 {
        ("Edges", "Triangles")
    } else {
        ("Triangles", "Tetrahedra")
    };
    writeln!(w, "\n{bname}\n{}", m.boundary.len())?;
    for (i, b) in m.boundary.iter().enumerate() {
        for v in b {
            write!(w, "{} ", *v as u64 + 1)?;
        }
        writeln!(w, "{}", m.boundary_marker(i))?;
    }
    writeln!(w, "\n{cname}\n{}", m.cells.len())?;
    for (i, c) in m.cells.iter().enumerate() {
        for v in c {
            write!(w, "{} ", *v as u64 + 1)?;
        }
        // Medit references are integers: a regional attribute is rounded (TetGen's -g does
        // the same with its region numbers).
        let a = m.cell_attribute(i);
        let r = if a.is_finite() {
            a.round().clamp(i32::MIN as f64, i32::MAX as f64) as i32
        } else {
            0
        };
        writeln!(w, "{r}")?;
    }
    writeln!(w, "\nEnd")?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_tets() -> TetMesh {
        TetMesh {
            vertices: vec![
                [0., 0., 0.],
                [1., 0., 0.],
                [0., 1., 0.],
                [0., 0., 1.],
                [1., 1., 1.],
            ],
            vertex_markers: vec![1, 1, 1, 1, 2],
            num_input_vertices: 5,
            tets: vec![[0, 1, 2, 3], [1, 2, 3, 4]],
            neighbors: vec![
                [1, u32::MAX, u32::MAX, u32::MAX],
                [u32::MAX, u32::MAX, u32::MAX, 0],
            ],
            tet_attributes: vec![1.0, 2.5],
            faces: vec![[0, 2, 1], [0, 1, 3], [1, 4, 2]],
            face_markers: vec![3, 3, 7],
            edges: vec![],
            edge_markers: vec![],
            complete: true,
            steiner_points: 0,
            surface_kept: false,
            optimized: false,
        }
    }

    fn render<const D: usize, const C: usize, const B: usize>(
        m: MeshView<'_, D, C, B>,
        f: Format,
    ) -> String {
        let mut out = Vec::new();
        write(&mut out, m, f).unwrap();
        String::from_utf8(out).unwrap()
    }

    /// The lines between a line equal to `start` and the next line starting with `$End` or
    /// `</`, split into tokens.
    fn section<'a>(text: &'a str, start: &str) -> Vec<Vec<&'a str>> {
        text.lines()
            .skip_while(|l| l.trim() != start)
            .skip(1)
            .take_while(|l| !l.starts_with("$End") && !l.starts_with("</"))
            .map(|l| l.split_whitespace().collect())
            .collect()
    }

    #[test]
    fn vtk_lists_cells_then_boundary_with_data() {
        let mesh = two_tets();
        let s = render(MeshView::from(&mesh), Format::Vtk);
        assert!(s.contains("POINTS 5 double"));
        assert!(s.contains("CELLS 5 22"), "{s}");
        let types: Vec<&str> = s
            .lines()
            .skip_while(|l| !l.starts_with("CELL_TYPES"))
            .skip(1)
            .take(5)
            .collect();
        assert_eq!(types, ["10", "10", "5", "5", "5"]);
        let marker_block: Vec<&str> = s
            .lines()
            .skip_while(|l| *l != "SCALARS marker int 1")
            .skip(2)
            .take(5)
            .collect();
        assert_eq!(marker_block, ["0", "0", "3", "3", "7"]);
        assert!(s.contains("SCALARS region double 1\nLOOKUP_TABLE default\n1\n2.5\n0\n"));
    }

    #[test]
    fn vtu_offsets_and_coordinates_read_back() {
        let mesh = two_tets();
        let s = render(MeshView::from(&mesh), Format::Vtu);
        let offsets: Vec<usize> = section(
            &s,
            "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">",
        )
        .iter()
        .map(|r| r[0].parse().unwrap())
        .collect();
        assert_eq!(offsets, [4, 8, 11, 14, 17]);
        let pts = section(
            &s,
            "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">",
        );
        assert_eq!(pts.len(), 5);
        assert_eq!(pts[4], ["1", "1", "1"]);
        assert_eq!(
            s.matches("<DataArray").count(),
            s.matches("</DataArray>").count()
        );
    }

    #[test]
    fn msh_groups_by_region_and_marker() {
        let mesh = two_tets();
        let s = render(MeshView::from(&mesh), Format::Msh);
        let ents = section(&s, "$Entities");
        assert_eq!(ents[0], ["0", "0", "2", "2"]);
        let els = section(&s, "$Elements");
        assert_eq!(els[0], ["4", "5", "1", "5"]);
        // Blocks: two regions (one tet each), then marker 3 (two faces), marker 7 (one face).
        assert_eq!(els[1], ["3", "1", "4", "1"]);
        assert_eq!(els[2], ["1", "1", "2", "3", "4"]);
        assert_eq!(els[5], ["2", "1", "2", "2"]);
        assert_eq!(els[6], ["3", "1", "3", "2"]);
        let names = section(&s, "$PhysicalNames");
        assert_eq!(names[0], ["4"]);
        assert_eq!(names[2], ["3", "2", "\"region_2.5\""]);
        assert_eq!(names[4], ["2", "7", "\"marker_7\""]);
    }

    #[test]
    fn medit_2d_and_3d() {
        let mesh = two_tets();
        let s = render(MeshView::from(&mesh), Format::Medit);
        assert!(s.contains("Dimension 3"));
        assert!(s.contains("Tetrahedra\n2\n1 2 3 4 1\n2 3 4 5 3\n"), "{s}");
        assert!(s.contains("Triangles\n3\n1 3 2 3\n"));
        let tri = TriMesh {
            vertices: vec![[0., 0.], [1., 0.], [0., 1.]],
            vertex_markers: vec![1, 1, 1],
            num_input_vertices: 3,
            triangles: vec![[0, 1, 2]],
            neighbors: vec![[u32::MAX; 3]],
            triangle_attributes: vec![],
            segments: vec![[0, 1], [1, 2], [2, 0]],
            segment_markers: vec![1, 2, 3],
            complete: true,
            steiner_points: 0,
        };
        let s = render(MeshView::from(&tri), Format::Medit);
        assert!(s.contains("Dimension 2"));
        assert!(s.contains("Vertices\n3\n0 0 1\n1 0 1\n"));
        assert!(s.contains("Edges\n3\n1 2 1\n2 3 2\n3 1 3\n"));
        assert!(s.contains("Triangles\n1\n1 2 3 0\n"));
        let v = render(MeshView::from(&tri), Format::Vtk);
        assert!(v.contains("0 1 0\n"), "2D points are padded with z = 0");
    }

    #[test]
    fn refuses_inconsistent_views() {
        let mut mesh = two_tets();
        mesh.tets[1][3] = 9;
        let err = write(Vec::new(), MeshView::from(&mesh), Format::Vtk).unwrap_err();
        assert!(err.to_string().contains("vertex index 9"), "{err}");
        let mut mesh = two_tets();
        mesh.face_markers.pop();
        let err = write(Vec::new(), MeshView::from(&mesh), Format::Msh).unwrap_err();
        assert!(err.to_string().contains("boundary marker"), "{err}");
    }
}
