//! TetGen's file formats, and the surface formats TetGen reads as PLCs.
//!
//! Reading: [`read_input`] picks the reader by extension; [`parse_node`], [`parse_poly`],
//! [`parse_smesh`], [`parse_off`], [`parse_stl`], [`parse_ply`], [`parse_medit`] and
//! [`parse_vtk`] read text
//! (bytes for STL). Each gives a [`TetgenInput`] whose [`Plc`](crate::Plc) is 0-based and
//! ready for [`tetrahedralize`](crate::tetrahedralize); its `base` records the file's
//! numbering (0 or 1) so that output can be numbered the same way. [`parse_ele`],
//! [`parse_face`], [`parse_edge`] and [`parse_neigh`] read a mesh back.
//!
//! Writing: [`write_node`], [`write_ele`], [`write_face`] (or [`write_all_faces`] for `-f`),
//! [`write_edge`] (or [`write_all_edges`] for `-e`) and [`write_neigh`] write a [`TetMesh`](crate::TetMesh) in TetGen's output
//! layouts; [`write_plc_poly`] writes a PLC back as a self-contained `.poly` file.
//!
//! ```
//! use idmesh::io::tetgen::parse_poly;
//! // A tetrahedron: 4 points (1-based), 4 triangular facets with marker 5.
//! let text = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n\
//!             4 1\n1 0 5\n3 1 2 3\n1 0 5\n3 1 2 4\n1 0 5\n3 2 3 4\n1 0 5\n3 3 1 4\n0\n";
//! let input = parse_poly(text, "tet.poly", || unreachable!()).unwrap();
//! assert_eq!(input.base, 1);
//! assert_eq!(input.plc.facets[3].polygons, vec![vec![2, 0, 3]]);
//! assert_eq!(input.plc.facets[3].marker, 5);
//! idmesh::input3d::check_plc(&input.plc).unwrap();
//! ```

use std::path::Path;

use super::error::ParseError;

pub use super::surface_read::{
    parse_medit, parse_off, parse_ply, parse_stl, parse_vtk, read_medit, read_off, read_ply,
    read_stl, read_vtk,
};
pub use super::tetgen_input::TetgenInput;
pub use super::tetgen_read::{
    parse_edge, parse_ele, parse_face, parse_mtr, parse_neigh, parse_node, parse_poly, parse_smesh,
    parse_var, parse_vol, read_node, read_poly, read_smesh, EleData3, Simplices, VarData,
};
pub use super::tetgen_write::{
    all_edges, write_all_edges, write_all_faces, write_edge, write_ele, write_ele_with, write_face,
    write_neigh, write_node, write_node_with, write_plc_poly,
};

/// Reads any input file TetGen reads, chosen by extension: `.node`, `.poly`, `.smesh`,
/// `.off`, `.stl`, `.ply`, `.mesh` (Medit), `.msh` (Gmsh) or `.vtk` (legacy VTK surface).
pub fn read_input(path: &Path) -> Result<TetgenInput, ParseError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("node") => read_node(path),
        Some("poly") => read_poly(path),
        Some("smesh") => read_smesh(path),
        Some("off") => read_off(path),
        Some("stl") => read_stl(path),
        Some("ply") => read_ply(path),
        Some("mesh") => read_medit(path),
        Some("msh") => super::msh_read::read_msh(path),
        Some("vtk") => read_vtk(path),
        _ => Err(ParseError::new(
            &path.display().to_string(),
            0,
            "unknown file type: expected .node, .poly, .smesh, .off, .stl, .ply, .mesh, .msh \
             or .vtk",
        )),
    }
}
