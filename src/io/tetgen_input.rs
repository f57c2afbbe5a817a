//! The result of every TetGen-family reader: [`TetgenInput`], shared by the readers of
//! TetGen's own formats and of the surface formats.

use crate::input3d::Plc;

/// The contents of a TetGen input file (or of a surface mesh read as one).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TetgenInput {
    /// The PLC with 0-based indices (only `points` for a `.node` file). Marker vectors are
    /// empty when the file declares no markers.
    pub plc: Plc,
    /// The numbering base of the file (0 or 1): output files are numbered the same way.
    pub base: u32,
    /// Number of attributes per vertex declared in the header.
    pub num_point_attributes: usize,
    /// Vertex attributes, `num_point_attributes` per vertex, vertex by vertex.
    pub point_attributes: Vec<f64>,
    /// The line of the file each facet was read from (surface formats; empty when unknown),
    /// for error messages.
    pub facet_lines: Vec<usize>,
}
