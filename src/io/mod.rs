//! Readers and writers for mesh file formats.
//!
//! * [`triangle`]: Shewchuk's Triangle formats (.node, .poly in; .node, .ele, .poly, .edge,
//!   .neigh out).
//! * [`tetgen`]: Hang Si's TetGen formats (.node, .poly, .smesh, and the surface formats .off,
//!   .stl, .ply, .mesh in; .node, .ele, .face, .edge, .neigh out).
//!
//! Readers never panic: every problem is a [`ParseError`] naming the file and line. Writers
//! buffer internally and write floats so that they read back bit for bit.
//!
//! * [`picture`]: SVG and PNG pictures of meshes coloured by quality (`idmesh show`).
//! * [`exchange`]: VTK (.vtk, .vtu), Gmsh (.msh) and Medit (.mesh) out, 2D and 3D.
//!
//! The line tokenizer and number formatting are shared by both families of formats.

mod error;
pub mod exchange;
mod lines;
mod msh_read;
mod numfmt;
pub mod picture;
mod surface_read;
pub mod tetgen;
mod tetgen_input;
mod tetgen_read;
mod tetgen_write;
pub mod triangle;
mod triangle_read;
mod triangle_write;

pub use error::ParseError;
pub use msh_read::{parse_msh, read_msh};
pub use numfmt::Real;
