//! Validation of a [`Plc`](super::Plc) before meshing. (Being written.)

use super::Plc;
use crate::error::Error;

/// Checks a PLC and reports the first problem found, naming the offending item.
pub fn check_plc(_plc: &Plc) -> Result<(), Error> {
    Ok(())
}
