//! # idmesh
//!
//! Quality Delaunay meshes by incremental Delaunay refinement (Ruppert / Shewchuk style,
//! implemented as in "An Incremental Delaunay Meshing Algorithm", §3 for 2D).
//!
//! * Output is **conforming Delaunay**: every input segment is a union of mesh edges and every
//!   triangle's circumcircle is empty of mesh vertices.
//! * Every geometric decision (orientation, in-circle, encroachment) is exact.
//! * Bad input is reported as an [`Error`] naming the offending item; nothing panics.
//!
//! ```
//! use idmesh::{Pslg, Options, triangulate};
//! let mut pslg = Pslg::default();
//! pslg.points = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
//! pslg.segments = vec![[0, 1], [1, 2], [2, 3], [3, 0]];
//! let opts = Options { min_angle: Some(30.0), max_area: Some(0.01), ..Options::default() };
//! let mesh = triangulate(&pslg, &opts).unwrap();
//! assert!(mesh.triangles.len() >= 100);
//! mesh.validate().unwrap();
//! ```

#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod error;
pub mod exact;
// The C ABI is the one place that dereferences caller pointers (each `unsafe` block with its
// SAFETY note); everything else is safe Rust.
#[allow(unsafe_code)]
pub mod ffi;
pub mod geometry;
mod hash;
pub mod input2d;
pub mod input3d;
pub mod io;
mod lp;
pub mod mesh2d;
pub mod mesh3d;
pub mod predicates;
pub mod progress;
pub mod switches;
pub mod threads;

pub use error::{Error, InputError};

/// The "no index" value used in index arrays (for example a missing neighbour), in every
/// dimension and in the C ABI (`IDM_NONE`).
pub const NONE: u32 = u32::MAX;
pub use input2d::{Pslg, Region};
pub use input3d::{Facet, Plc, Region3};
pub use mesh2d::{triangulate, Options, SizingFn, TriMesh};
pub use mesh3d::{delaunay3d, tetrahedralize, Options3, SizingFn3, TetMesh};
pub use progress::{ProgressFn, Stage};
