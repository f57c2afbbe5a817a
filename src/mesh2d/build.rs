//! Driver: validation, insertion of the input, segment recovery, classification, refinement.
use super::{Options, TriMesh};
use crate::error::Error;
use crate::input::Pslg;

pub(super) fn run(_pslg: &Pslg, _opts: &Options) -> Result<TriMesh, Error> {
    Err(Error::Unsupported("the 2D core is being written".into()))
}
