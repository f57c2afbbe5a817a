//! Shewchuk's Triangle file formats.
//!
//! Reading: [`read_node`] / [`read_poly`] (or [`parse_node`] / [`parse_poly`] on text) give a
//! [`TriangleInput`] whose [`Pslg`](crate::Pslg) is 0-based and ready for
//! [`triangulate`](crate::triangulate); its `base` records the file's numbering (0 or 1) so
//! that output can be numbered the same way. [`parse_ele`] reads a mesh's triangles back and [`parse_area`] its
//! per-triangle area bounds (both for `-r`).
//!
//! Writing: [`write_node`] (with point attributes: [`write_node_attributes`]), [`write_ele`], [`write_poly`], [`write_edge`] and [`write_neigh`]
//! write a [`TriMesh`](crate::TriMesh) in Triangle's output layouts; [`write_pslg_poly`] writes
//! a PSLG back as a self-contained `.poly` file.
//!
//! ```
//! use idmesh::io::triangle::parse_poly;
//! let text = "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2\n2 2 3\n3 3 1\n0\n";
//! let input = parse_poly(text, "tri.poly", || unreachable!()).unwrap();
//! assert_eq!(input.base, 1);
//! assert_eq!(input.pslg.segments, vec![[0, 1], [1, 2], [2, 0]]);
//! ```

pub use super::triangle_read::{
    parse_area, parse_ele, parse_node, parse_poly, read_area, read_ele, read_node, read_poly,
    EleData, TriangleInput,
};
pub use super::triangle_write::{
    write_edge, write_ele, write_neigh, write_node, write_node_attributes, write_poly,
    write_poly_segments, write_pslg_poly,
};
