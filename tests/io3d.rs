//! TetGen formats and surface formats: every reader on small inline samples, round trips of
//! every writer through the matching reader (floats bit for bit), and errors that name the
//! file and line.

use std::path::{Path, PathBuf};

use idmesh::input3d::check_plc;
use idmesh::io::tetgen::{
    parse_edge, parse_ele, parse_face, parse_medit, parse_neigh, parse_node, parse_off, parse_ply,
    parse_poly, parse_smesh, parse_stl, parse_vtk, read_input, read_poly, write_all_faces,
    write_edge, write_ele, write_face, write_neigh, write_node, write_plc_poly, TetgenInput,
};
use idmesh::io::ParseError;
use idmesh::{Facet, Plc, Region3, TetMesh, NONE};

fn no_node() -> Result<TetgenInput, ParseError> {
    panic!("the .node loader must not be called for a file with vertices")
}

fn text(f: impl FnOnce(&mut Vec<u8>) -> std::io::Result<()>) -> String {
    let mut buf = Vec::new();
    f(&mut buf).unwrap();
    String::from_utf8(buf).unwrap()
}

fn same_bits(a: &[[f64; 3]], b: &[[f64; 3]]) {
    assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(b) {
        for k in 0..3 {
            assert_eq!(p[k].to_bits(), q[k].to_bits(), "{p:?} vs {q:?}");
        }
    }
}

/// A directory removed when the test ends.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let p = std::env::temp_dir().join(format!("idmesh-io3d-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(&p).unwrap();
        TempDir(p)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

// ---------------------------------------------------------------------------------------------
// .node, .poly, .smesh

#[test]
fn node_with_attributes_markers_and_defaults() {
    let text = "# three points\n3 3 2 1\n1 0.5 -1e-3 2 7 8 4\n2 1 0 0 9\n3 0 1 0.1\n";
    let inp = parse_node(text, "t.node").unwrap();
    assert_eq!(inp.base, 1);
    assert_eq!(
        inp.plc.points,
        vec![[0.5, -0.001, 2.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.1]]
    );
    assert_eq!(inp.num_point_attributes, 2);
    assert_eq!(inp.point_attributes, vec![7.0, 8.0, 9.0, 0.0, 0.0, 0.0]);
    assert_eq!(inp.plc.point_markers, vec![4, 0, 0]);
    // Header fields after the count are optional; no markers means an empty marker vector.
    let inp = parse_node("2\n0 1 2 3\n1 4 5 6\n", "t.node").unwrap();
    assert_eq!(inp.base, 0);
    assert!(inp.plc.point_markers.is_empty());
}

/// A unit cube with a facet hole in the top (a square window) filled by a lid facet, one
/// volume hole seed and two regions; 1-based with markers.
const CUBE_POLY: &str = "\
# cube
12 3 0 1
1 0 0 0 1
2 1 0 0 1
3 1 1 0 1
4 0 1 0 1
5 0 0 1 2
6 1 0 1 2
7 1 1 1 2
8 0 1 1 2
9 0.25 0.25 1 3
10 0.75 0.25 1 3
11 0.75 0.75 1 3
12 0.25 0.75 1 3
7 1
1 0 10
4 1 2 3 4
2 1 20   # top with a window
4 5 6 7 8
4 9 10 11 12
1 0.5 0.5 1
1 0 30
4 1 2 6 5
1 0 30
4 2 3 7 6
1 0 30
4 3 4 8 7
1 0 30
4 4 1 5 8
1        # the lid: no hole count, no marker
4 9 10 11 12
1
1 0.5 0.5 0.5
2
1 0.5 0.5 0.25 3 0.125
2 0.5 0.5 0.75 -4
";

#[test]
fn poly_with_facet_holes_markers_holes_and_regions() {
    let inp = parse_poly(CUBE_POLY, "cube.poly", no_node).unwrap();
    assert_eq!(inp.base, 1);
    let p = &inp.plc;
    assert_eq!(p.points.len(), 12);
    assert_eq!(p.point_markers[8], 3);
    assert_eq!(p.facets.len(), 7);
    assert_eq!(
        p.facets[1],
        Facet {
            polygons: vec![vec![4, 5, 6, 7], vec![8, 9, 10, 11]],
            holes: vec![[0.5, 0.5, 1.0]],
            marker: 20,
        }
    );
    assert_eq!(p.facets[6].marker, 0, "a facet line without a marker field");
    assert_eq!(p.holes, vec![[0.5, 0.5, 0.5]]);
    assert_eq!(
        p.regions,
        vec![
            Region3 {
                point: [0.5, 0.5, 0.25],
                attribute: 3.0,
                max_volume: Some(0.125)
            },
            // Without a volume TetGen copies the attribute; a negative volume is no bound.
            Region3 {
                point: [0.5, 0.5, 0.75],
                attribute: -4.0,
                max_volume: None
            },
        ]
    );
    assert!(p.segments.is_empty());
    check_plc(p).unwrap();
}

#[test]
fn poly_sections_after_the_facets_are_optional() {
    let head = "4 3\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";
    let facets = "4\n1\n3 0 1 2\n1\n3 0 1 3\n1\n3 1 2 3\n1\n3 2 0 3\n";
    for tail in ["", "0\n", "0\n0\n"] {
        let inp = parse_poly(&format!("{head}{facets}{tail}"), "t.poly", no_node).unwrap();
        assert_eq!(inp.plc.facets.len(), 4, "{tail:?}");
        check_plc(&inp.plc).unwrap();
    }
    // A vertex section alone is a point set, as TetGen reads it.
    let inp = parse_poly(head, "t.poly", no_node).unwrap();
    assert!(inp.plc.facets.is_empty());
    // A region without a volume uses its attribute (TetGen's copy).
    let inp = parse_poly(
        &format!("{head}{facets}0\n1\n0 0.1 0.1 0.1 0.5\n"),
        "t.poly",
        no_node,
    )
    .unwrap();
    assert_eq!(inp.plc.regions[0].max_volume, Some(0.5));
}

#[test]
fn poly_with_zero_vertices_reads_the_node_file_beside_it() {
    let d = TempDir::new("zero");
    std::fs::write(
        d.0.join("t.node"),
        "4 3 0 1\n1 0 0 0 5\n2 1 0 0 6\n3 0 1 0 7\n4 0 0 1 8\n",
    )
    .unwrap();
    std::fs::write(
        d.0.join("t.poly"),
        "0 3 0 0\n4 1\n1 0 1\n3 1 2 3\n1 0 1\n3 1 2 4\n1 0 1\n3 2 3 4\n1 0 2\n3 3 1 4\n0\n",
    )
    .unwrap();
    let inp = read_poly(&d.0.join("t.poly")).unwrap();
    assert_eq!(inp.base, 1);
    assert_eq!(inp.plc.point_markers, vec![5, 6, 7, 8]);
    assert_eq!(inp.plc.facets[3].polygons, vec![vec![2, 0, 3]]);
    assert_eq!(inp.plc.facets[3].marker, 2);
    // The same through the extension dispatch.
    assert_eq!(read_input(&d.0.join("t.poly")).unwrap(), inp);
    // A missing .node file is named in the error.
    std::fs::remove_file(d.0.join("t.node")).unwrap();
    let e = read_poly(&d.0.join("t.poly")).unwrap_err();
    assert!(e.file.ends_with("t.node") && e.line == 0, "{e}");
}

#[test]
fn smesh_facets_are_one_polygon_lines_with_markers() {
    let text = "\
6 3 0 0
0 0 0 0
1 0 1 0
2 1 0 0
3 1 1 0
4 1 0 0.25
5 1 1 0.25
5 1
4 0 2 3 1 1
4 0 4 5 1 2
3 0 2 4 3
3 1 3
  5 4
4 2 3 5 4 5
0
0
";
    let inp = parse_smesh(text, "w.smesh", no_node).unwrap();
    assert_eq!(inp.base, 0);
    let f = &inp.plc.facets;
    assert_eq!(f.len(), 5);
    assert_eq!(f[0].polygons, vec![vec![0, 2, 3, 1]]);
    assert_eq!((f[0].marker, f[2].marker, f[4].marker), (1, 3, 5));
    // Corners and marker may continue on the next line, as TetGen reads them.
    assert_eq!((f[3].polygons[0].clone(), f[3].marker), (vec![1, 3, 5], 4));
    check_plc(&inp.plc).unwrap();
}

// ---------------------------------------------------------------------------------------------
// Surface formats

#[test]
fn off_variants_comments_colours_and_numbering() {
    let tet = "4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
    let inp = parse_off(&format!("OFF\n# comment\n{tet}"), "t.off").unwrap();
    assert_eq!(inp.base, 0);
    assert_eq!(inp.plc.facets[2].polygons, vec![vec![1, 2, 3]]);
    check_plc(&inp.plc).unwrap();
    // Counts on the keyword line, no edge count, colours on vertices and faces.
    let coff = "COFF 4 4\n0 0 0 1 0 0 1\n1 0 0 1 0 0 1\n0 1 0 1 0 0 1\n0 0 1 1 0 0 1\n\
                3 0 2 1 255 0 0\n3 0 1 3 0 255 0\n3 1 2 3 0 0 255\n3 2 0 3 9 9 9\n";
    let c = parse_off(coff, "c.off").unwrap();
    assert_eq!(c.plc.points, inp.plc.points);
    assert_eq!(c.plc.facets, inp.plc.facets);
    // No keyword at all.
    assert_eq!(parse_off(tet, "n.off").unwrap().plc, inp.plc);
    // Smallest index 1: 1-based, as TetGen decides.
    let one = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 1 3 2\n3 1 2 4\n3 2 3 4\n3 3 1 4\n";
    let o = parse_off(one, "o.off").unwrap();
    assert_eq!(o.base, 1);
    assert_eq!(o.plc.facets, inp.plc.facets);
}

/// The unit tetrahedron's surface as legacy VTK POLYDATA: a title, comments, coordinates
/// running over line breaks, a line cell (skipped) and the marker cell data.
const TET_VTK: &str = "# vtk DataFile Version 2.0
a tetrahedron
ASCII
DATASET POLYDATA
POINTS 4 float
0 0 0 1 0 0
0 1 0
0 0 1
LINES 1 3
2 0 1
POLYGONS 4 16
3 0 2 1
3 0 1 3
3 1 2 3
3 2 0 3
CELL_DATA 5
SCALARS marker int 1
LOOKUP_TABLE default
0 4 5 6 7
";

#[test]
fn vtk_polydata_and_unstructured_grids_read_as_surfaces() {
    let inp = parse_vtk(TET_VTK, "t.vtk").unwrap();
    assert_eq!(inp.base, 0);
    assert_eq!(inp.plc.points[3], [0.0, 0.0, 1.0]);
    assert_eq!(inp.plc.facets.len(), 4, "the line cell is skipped");
    assert_eq!(inp.plc.facets[2].polygons, vec![vec![1, 2, 3]]);
    let markers: Vec<i32> = inp.plc.facets.iter().map(|f| f.marker).collect();
    assert_eq!(markers, [4, 5, 6, 7], "the line's marker is skipped");
    check_plc(&inp.plc).unwrap();
    // Without cell data the markers are 0; an empty title line is allowed.
    let plain = TET_VTK
        .split("CELL_DATA")
        .next()
        .unwrap()
        .replace("a tetrahedron", "");
    let p = parse_vtk(&plain, "p.vtk").unwrap();
    assert!(p.plc.facets.iter().all(|f| f.marker == 0));
    assert_eq!(p.plc.points, inp.plc.points);
    // A tetrahedral mesh as idmesh's -k writes it reads back as its boundary triangles.
    let m = two_tets();
    let vtk = text(|b| {
        idmesh::io::exchange::write(
            b,
            idmesh::io::exchange::MeshView::from(&m),
            idmesh::io::exchange::Format::Vtk,
        )
    });
    let back = parse_vtk(&vtk, "m.vtk").unwrap();
    same_bits(&back.plc.points, &m.vertices);
    let faces: Vec<Vec<u32>> = back
        .plc
        .facets
        .iter()
        .map(|f| f.polygons[0].clone())
        .collect();
    let want: Vec<Vec<u32>> = m.faces.iter().map(|f| f.to_vec()).collect();
    assert_eq!(faces, want);
    let markers: Vec<i32> = back.plc.facets.iter().map(|f| f.marker).collect();
    assert_eq!(markers, m.face_markers);
    // Quads and pixels (raster order) in an unstructured grid.
    let grid = "# vtk DataFile Version 3.0\nsquare\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                POINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n1 1 0\nCELLS 2 10\n4 0 1 3 2\n4 0 1 2 3\n\
                CELL_TYPES 2\n9\n8\n";
    let g = parse_vtk(grid, "g.vtk").unwrap();
    assert_eq!(g.plc.facets[0].polygons, vec![vec![0, 1, 3, 2]]);
    assert_eq!(
        g.plc.facets[1].polygons,
        vec![vec![0, 1, 3, 2]],
        "pixel reordered"
    );
}

#[test]
fn vtk_errors_name_the_line() {
    let err = |t: &str| parse_vtk(t, "e.vtk").unwrap_err();
    let e = err(&TET_VTK.replace("3 1 2 3", "3 1 2 9"));
    assert_eq!(e.line, 14);
    assert!(e.message.contains("corner 9 is out of range"), "{e}");
    let e = err(&TET_VTK.replace("0 1 0\n0 0 1", "0 1 0\n0 x 1"));
    assert_eq!(e.line, 8);
    assert!(e.message.contains("bad number 'x'"), "{e}");
    let e = err(&TET_VTK.replace("ASCII", "BINARY"));
    assert_eq!(e.line, 3);
    assert!(e.message.contains("binary"), "{e}");
    let e = err(&TET_VTK.replace("POLYDATA", "STRUCTURED_POINTS"));
    assert!(e.message.contains("STRUCTURED_POINTS"), "{e}");
    let e = err(&TET_VTK.replace("CELL_DATA 5", "CELL_DATA 4"));
    assert_eq!(e.line, 16);
    let e = err(TET_VTK.split("POLYGONS").next().unwrap());
    assert!(e.message.contains("no surface cells"), "{e}");
    let grid = "x\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 0 1 0 0 0 1 0\n\
                CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n22\n";
    let e = err(grid);
    assert_eq!(e.line, 9);
    assert!(e.message.contains("type 22"), "{e}");
    assert!(mangle(TET_VTK, |t| parse_vtk(t, "m.vtk")) > 100);
}

/// A binary STL of the given triangles (f32 corners).
fn binary_stl(tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b[..5].copy_from_slice(b"solid"); // A misleading header, as some exporters write.
    b.extend((tris.len() as u32).to_le_bytes());
    for t in tris {
        b.extend([0u8; 12]);
        for c in t {
            for x in c {
                b.extend(x.to_le_bytes());
            }
        }
        b.extend([0u8; 2]);
    }
    b
}

#[test]
fn stl_ascii_and_binary_merge_equal_corners() {
    let ascii = "solid t\n\
        facet normal 0 0 -1\n outer loop\n  vertex 0 0 0\n  vertex 0 1 0\n  vertex 1 0 0\n endloop\nendfacet\n\
        facet normal 0 -1 0\n outer loop\n  vertex -0 0 0\n  vertex 1 0 0\n  vertex 0 0 1\n endloop\nendfacet\n\
        facet normal -1 0 0\n outer loop\n  vertex 0 0 0\n  vertex 0 0 1\n  vertex 0 1 0\n endloop\nendfacet\n\
        facet normal 1 1 1\n outer loop\n  vertex 1 0 0\n  vertex 0 1 0\n  vertex 0 0 1\n endloop\nendfacet\n\
        endsolid t\n";
    let a = parse_stl(ascii.as_bytes(), "a.stl").unwrap();
    assert_eq!(a.base, 1, "TetGen numbers STL output from 1");
    assert_eq!(a.plc.points.len(), 4, "-0 and 0 are the same corner");
    assert_eq!(
        a.plc
            .facets
            .iter()
            .map(|f| f.polygons[0].clone())
            .collect::<Vec<_>>(),
        vec![vec![0, 1, 2], vec![0, 2, 3], vec![0, 3, 1], vec![2, 1, 3]]
    );
    check_plc(&a.plc).unwrap();
    let z = [0.0f32; 3];
    let (x, y, w) = ([1.0f32, 0.0, 0.0], [0.0f32, 1.0, 0.0], [0.0f32, 0.0, 1.0]);
    let bin = binary_stl(&[[z, y, x], [z, x, w], [z, w, y], [x, y, w]]);
    let b = parse_stl(&bin, "b.stl").unwrap();
    assert_eq!(b.plc, a.plc);
    // f32 values widen exactly.
    let odd = binary_stl(&[[[0.1f32, 0.0, 0.0], y, w]]);
    assert_eq!(
        parse_stl(&odd, "o.stl").unwrap().plc.points[0][0],
        0.1f32 as f64
    );
}

#[test]
fn ply_reads_xyz_wherever_they_are_and_skips_other_elements() {
    let text = "ply\nformat ascii 1.0\ncomment made by hand\n\
        element vertex 4\nproperty uchar red\nproperty float z\nproperty float x\nproperty float y\n\
        element face 4\nproperty uchar flags\nproperty list uchar int vertex_indices\n\
        element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n\
        9 0 0 0\n9 0 1 0\n9 0 0 1\n9 1 0 0\n\
        0 3 0 2 1\n0 3 0 1 3\n0 3 1 2 3\n0 3 2 0 3\n0 1\n";
    let inp = parse_ply(text, "t.ply").unwrap();
    assert_eq!(
        inp.plc.points,
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0]
        ]
    );
    assert_eq!(inp.plc.facets[0].polygons, vec![vec![0, 2, 1]]);
    check_plc(&inp.plc).unwrap();
    let e = parse_ply(
        "ply\nformat binary_little_endian 1.0\nend_header\n",
        "b.ply",
    )
    .unwrap_err();
    assert!(e.message.contains("ASCII"), "{e}");
}

#[test]
fn medit_sections_references_and_unknown_keywords() {
    let text = "MeshVersionFormatted 2\nDimension\n3\n\
        Vertices\n5\n0 0 0 0\n2 0 0 0\n2 2 0 0\n0 2 0 0\n1 1 1 0\n\
        Edges 1\n1 2 0\n\
        Quadrilaterals 1\n4 3 2 1 7\n\
        Triangles\n4\n1 2 5 8\n2 3 5 8\n3 4 5 8\n4 1 5\n\
        End\n";
    let inp = parse_medit(text, "p.mesh").unwrap();
    assert_eq!(inp.base, 1);
    let f = &inp.plc.facets;
    assert_eq!(f.len(), 5);
    assert_eq!(
        (f[0].polygons[0].clone(), f[0].marker),
        (vec![3, 2, 1, 0], 7)
    );
    assert_eq!((f[1].marker, f[4].marker), (8, 0));
    check_plc(&inp.plc).unwrap();
    let e = parse_medit("Dimension 2\n", "d.mesh").unwrap_err();
    assert!(e.message.contains("dimension must be 3"), "{e}");
}

#[test]
fn every_example_file_reads_and_passes_the_check() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if !name.starts_with("3d_") {
            continue;
        }
        let inp = read_input(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(inp.plc.points.len() >= 4, "{name}");
        check_plc(&inp.plc).unwrap_or_else(|e| panic!("{name}: {e}"));
        seen += 1;
    }
    assert!(seen >= 8, "expected the 3d_* example files, found {seen}");
}

// ---------------------------------------------------------------------------------------------
// Writers, read back

/// Two positively oriented tetrahedra sharing the face 1-2-3.
fn two_tets() -> TetMesh {
    TetMesh {
        vertices: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
        ],
        vertex_markers: vec![1, 0, -4, 2, 9],
        num_input_vertices: 5,
        tets: vec![[0, 1, 2, 3], [1, 2, 3, 4]],
        neighbors: vec![[1, NONE, NONE, NONE], [NONE, NONE, NONE, 0]],
        tet_attributes: vec![],
        faces: vec![[0, 2, 1], [0, 1, 3], [1, 4, 3]],
        face_markers: vec![5, 6, 7],
        edges: vec![[0, 1], [1, 4]],
        edge_markers: vec![3, -1],
        complete: true,
        steiner_points: 0,
        surface_kept: false,
        optimized: false,
    }
}

#[test]
fn node_round_trips_exactly_in_both_bases() {
    let mut m = two_tets();
    m.vertices = vec![
        [0.1, -0.0, 1e-300],
        [1.0 / 3.0, 5e-324, f64::MAX],
        [0.0, 2.5e17, -1e-7],
        [123_456_789.123_456_79, 0.0, -7.25],
        [1.0, 1.0, 0.6000000000000001],
    ];
    for base in [0, 1] {
        let s = text(|b| write_node(b, &m, base, true));
        assert!(s.starts_with("5 3 0 1\n"), "{s}");
        let back = parse_node(&s, "o.node").unwrap();
        assert_eq!(back.base, base);
        assert_eq!(back.plc.point_markers, m.vertex_markers);
        same_bits(&back.plc.points, &m.vertices);
    }
    let s = text(|b| write_node(b, &m, 1, false));
    assert!(s.starts_with("5 3 0 0\n"), "{s}");
    assert!(parse_node(&s, "o.node")
        .unwrap()
        .plc
        .point_markers
        .is_empty());
}

#[test]
fn ele_round_trips_with_and_without_attributes() {
    let mut m = two_tets();
    let s = text(|b| write_ele(b, &m, 1));
    assert_eq!(s, "2 4 0\n1 1 2 3 4\n2 2 3 4 5\n");
    let back = parse_ele(&s, "o.ele", 1, 5).unwrap();
    assert_eq!(back.tets, m.tets);
    m.tet_attributes = vec![2.5, -1.0 / 3.0];
    let s = text(|b| write_ele(b, &m, 0));
    let back = parse_ele(&s, "o.ele", 0, 5).unwrap();
    assert_eq!(
        (back.tets, back.attributes),
        (m.tets.clone(), m.tet_attributes.clone())
    );
    m.tet_attributes = vec![1.0];
    assert!(write_ele(Vec::new(), &m, 0).is_err());
}

#[test]
fn face_edge_and_neigh_round_trip() {
    let m = two_tets();
    let s = text(|b| write_face(b, &m, 1, true));
    assert!(s.starts_with("3 1\n1 1 3 2 5\n"), "{s}");
    let f = parse_face(&s, "o.face", 1, 5).unwrap();
    assert_eq!(
        (f.items, f.markers),
        (m.faces.clone(), m.face_markers.clone())
    );
    let f = parse_face(&text(|b| write_face(b, &m, 0, false)), "o.face", 0, 5).unwrap();
    assert!(f.markers.is_empty());
    let e = parse_edge(&text(|b| write_edge(b, &m, 0, true)), "o.edge", 0, 5).unwrap();
    assert_eq!(
        (e.items, e.markers),
        (m.edges.clone(), m.edge_markers.clone())
    );
    let s = text(|b| write_neigh(b, &m, 1));
    assert_eq!(s, "2 4\n1 2 -1 -1 -1\n2 -1 -1 -1 1\n");
    assert_eq!(parse_neigh(&s, "o.neigh", 1, 2).unwrap(), m.neighbors);
}

#[test]
fn all_faces_lists_each_face_once_outward_with_subface_markers() {
    let m = two_tets();
    let s = text(|b| write_all_faces(b, &m, 0, true));
    let f = parse_face(&s, "o.face", 0, 5).unwrap();
    assert_eq!(f.items.len(), 7, "4 + 4 faces, one shared");
    let key = |t: [u32; 3]| {
        let mut k = t;
        k.sort_unstable();
        k
    };
    let mut keys: Vec<[u32; 3]> = f.items.iter().map(|&t| key(t)).collect();
    keys.sort_unstable();
    keys.dedup();
    assert_eq!(keys.len(), 7);
    for (t, &mk) in f.items.iter().zip(&f.markers) {
        let want = m
            .faces
            .iter()
            .position(|&g| key(g) == key(*t))
            .map_or(0, |i| m.face_markers[i]);
        assert_eq!(mk, want, "{t:?}");
    }
    // Boundary faces face away from their tetrahedron (its fourth corner is behind them).
    let p = |v: u32| m.vertices[v as usize];
    for t in &f.items {
        if key(*t) == [1, 2, 3] {
            continue;
        }
        let tet = m
            .tets
            .iter()
            .find(|tv| t.iter().all(|v| tv.contains(v)))
            .unwrap();
        let apex = *tet.iter().find(|v| !t.contains(v)).unwrap();
        let o = idmesh::predicates::orient3d(p(t[0]), p(t[1]), p(t[2]), p(apex));
        assert!(o > 0.0, "face {t:?} is not outward");
    }
}

#[test]
fn plc_round_trips_through_poly_text() {
    let inp = parse_poly(CUBE_POLY, "cube.poly", no_node).unwrap();
    for base in [0, 1] {
        let s = text(|b| write_plc_poly(b, &inp.plc, base));
        let back = parse_poly(&s, "p.poly", no_node).unwrap();
        assert_eq!(back.base, base);
        assert_eq!(back.plc, inp.plc, "{s}");
    }
    let mut with_segments = inp.plc.clone();
    with_segments.segments.push([0, 6]);
    assert!(write_plc_poly(Vec::new(), &with_segments, 0).is_err());
    let bare = Plc {
        point_markers: vec![],
        ..inp.plc.clone()
    };
    let s = text(|b| write_plc_poly(b, &bare, 1));
    assert!(s.starts_with("12 3 0 0\n"), "{s}");
    assert_eq!(parse_poly(&s, "p.poly", no_node).unwrap().plc, bare);
}

// ---------------------------------------------------------------------------------------------
// Errors name the file and line

fn poly_err(text: &str) -> ParseError {
    parse_poly(text, "e.poly", no_node).unwrap_err()
}

#[test]
fn poly_errors_name_the_line_and_item() {
    let head = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
    let e = poly_err("4 2 0 0\n");
    assert!(e.message.contains("dimension must be 3"), "{e}");
    let e = poly_err("4 3 0 0\n1 0 0 0\n2 1 0\n");
    assert_eq!(
        (e.line, e.message.as_str()),
        (3, "vertex 2: missing z coordinate")
    );
    let e = poly_err(&format!("{head}1 0\n1\n3 1 2 5\n"));
    assert_eq!(e.line, 8);
    assert!(
        e.message.contains("facet 1") && e.message.contains("corner 5 is out of range"),
        "{e}"
    );
    let e = poly_err(&format!("{head}1 0\n0\n"));
    assert!(e.message.contains("at least one polygon"), "{e}");
    let e = poly_err(&format!("{head}1 0\n1\n0\n"));
    assert!(e.message.contains("at least one corner"), "{e}");
    let e = poly_err(&format!("{head}1 0\n1\n3 1 2 3 4\n"));
    assert_eq!(e.line, 8);
    assert!(e.message.contains("unexpected field '4'"), "{e}");
    let e = poly_err(&format!("{head}1 0\n1\n3 1 2\n"));
    assert!(e.message.contains("unexpected end of file"), "{e}");
    let e = poly_err(&format!("{head}1 0\n1 1\n3 1 2 3\n1 0.5 x 0\n"));
    assert_eq!(e.line, 9);
    assert!(e.message.contains("'x'"), "{e}");
    let e = poly_err(&format!("{head}1 0\n1\n3 1 2 3\n1\n1 0 0\n"));
    assert!(e.message.contains("hole 1: missing z"), "{e}");
    let e = poly_err(&format!("{head}1 0\n1\n3 1 2 3\n0\n1\n1 0 0 0\n"));
    assert!(
        e.message.contains("region 1: missing regional attribute"),
        "{e}"
    );
    let e = poly_err(&format!("{head}1 0\n1\n3 1 2 3\n0\n0\n7\n"));
    assert_eq!(e.line, 11);
    assert!(e.message.contains("unexpected data"), "{e}");
    let e = poly_err(&format!("{head}1 2\n"));
    assert!(e.message.contains("0 or 1"), "{e}");
    let e = poly_err("4 3 0 0 1\n");
    assert!(e.message.contains("not supported"), "{e}");
}

#[test]
fn output_file_readers_check_ranges() {
    let e = parse_ele("1 4 0\n1 1 2 3 9\n", "o.ele", 1, 5).unwrap_err();
    assert_eq!(e.line, 2);
    assert!(e.message.contains("corner 9 is out of range"), "{e}");
    assert!(parse_ele("1 6 0\n", "o.ele", 1, 5)
        .unwrap_err()
        .message
        .contains("4 or 10 nodes"));
    // A 10-node (-o2) file: the corners are read, the edge nodes range-checked.
    let e = parse_ele("1 10 1\n1 1 2 3 4 5 5 5 5 5 5 2.5\n", "o.ele", 1, 5).unwrap();
    assert_eq!((e.tets, e.attributes), (vec![[0, 1, 2, 3]], vec![2.5]));
    let e = parse_ele("1 10 0\n1 1 2 3 4 5 5 5 5 5 6\n", "o.ele", 1, 5).unwrap_err();
    assert!(e.message.contains("node 6 is out of range"), "{e}");
    let e = parse_neigh("1 4\n1 2 -1 -1 -1\n", "o.neigh", 1, 1).unwrap_err();
    assert!(e.message.contains("neighbour 2 is out of range"), "{e}");
    let e = parse_face("2 0\n0 0 1 2\n", "o.face", 0, 3).unwrap_err();
    assert!(e.message.contains("face 2 of 2"), "{e}");
}

#[test]
fn surface_errors_name_the_line() {
    let e = parse_off("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 7\n", "t.off").unwrap_err();
    assert_eq!(e.line, 7);
    assert!(e.message.contains("corner 7 is out of range"), "{e}");
    let e = parse_off("4OFF\n", "t.off").unwrap_err();
    assert_eq!(e.line, 1);
    let e = parse_off("OFF\n4 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1\n", "t.off").unwrap_err();
    assert!(e.message.contains("announces 3 corners but lists 2"), "{e}");
    let e = parse_stl(
        b"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0\n",
        "t.stl",
    )
    .unwrap_err();
    assert_eq!(e.line, 4);
    let e = parse_stl(b"\x01\x02", "t.stl").unwrap_err();
    assert!(e.message.contains("neither"), "{e}");
    let e = parse_stl(
        b"solid x\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n endloop\n",
        "t.stl",
    )
    .unwrap_err();
    assert!(e.message.contains("2 vertices"), "{e}");
    let e = parse_ply(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n",
        "t.ply",
    )
    .unwrap_err();
    assert!(e.message.contains("x, y or z"), "{e}");
    let e = parse_medit("Vertices\n2\n0 0 0 0\n1 1\n", "t.mesh").unwrap_err();
    assert_eq!(e.line, 4);
    assert!(e.message.contains("vertex 2: missing z"), "{e}");
    let e = parse_medit("Vertices 1\n0 0 0 0\nTriangles 1\n1 2 3 0\n", "t.mesh").unwrap_err();
    assert_eq!(e.line, 4);
    assert!(e.message.contains("out of range"), "{e}");
    let e = read_input(Path::new("/nonexistent-idmesh/x.obj")).unwrap_err();
    assert!(e.message.contains("unknown file type"), "{e}");
}

/// Deterministic pseudo-random edits of a valid file: every outcome is Ok or an error with a
/// line inside the file (never a panic).
fn mangle(valid: &str, parse: impl Fn(&str) -> Result<TetgenInput, ParseError>) -> usize {
    let base = valid.as_bytes();
    let lines = valid.lines().count();
    let pieces: [&[u8]; 9] = [b"", b" ", b"\n", b"#", b"-", b"9", b"1e400", b"x", b"0"];
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = |m: usize| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1);
        ((state >> 33) as usize) % m
    };
    let mut errors = 0;
    for _ in 0..1500 {
        let mut t = base.to_vec();
        for _ in 0..1 + next(3) {
            let at = next(t.len() + 1);
            let cut = next(4).min(t.len() - at.min(t.len()));
            let piece = pieces[next(pieces.len())];
            t.splice(at..at + cut, piece.iter().copied());
        }
        let t = String::from_utf8_lossy(&t).into_owned();
        if let Err(e) = parse(&t) {
            errors += 1;
            assert!(e.line <= lines + 4, "{e}");
        }
    }
    errors
}

#[test]
fn mangled_files_give_errors_not_panics() {
    let n = mangle(CUBE_POLY, |t| {
        parse_poly(t, "m.poly", || Err(ParseError::new("m.node", 0, "none")))
    });
    assert!(n > 100, "the edits should break many files, broke {n}");
    let off = "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
    assert!(mangle(off, |t| parse_off(t, "m.off")) > 100);
    let mesh =
        "Vertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTriangles\n2\n1 2 3 0\n1 2 4 0\nEnd\n";
    assert!(mangle(mesh, |t| parse_medit(t, "m.mesh")) > 100);
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    assert!(mangle(ply, |t| parse_ply(t, "m.ply")) > 100);
    assert!(
        mangle(
            &String::from_utf8(binary_stl(&[[[0.0; 3]; 3]])).unwrap_or_default(),
            |t| { parse_stl(t.as_bytes(), "m.stl") }
        ) > 0
    );
}
