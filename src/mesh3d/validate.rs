//! Exact checks of the 3D mesh invariants. (Being written.)

use super::TetMesh;
use crate::error::Error;

/// Checks orientation, neighbour symmetry, empty circumspheres and subfaces (exact).
pub fn validate_mesh(_mesh: &TetMesh) -> Result<(), Error> {
    Ok(())
}
