#![allow(dead_code)] // each target uses part of this module
//! What every meshing fuzz target checks on a result: a mesh handed back as a success passes
//! the exact `validate()`, and no panic hides behind an "internal error" (the library turns
//! panics into `Error::Internal("… caught a panic …")` at its boundary; the fuzzer must see
//! them). Other errors, internal ones included, are reported results: the campaign script
//! counts them.

use idmesh::Error;

/// Fails the run on a hidden panic.
pub fn no_hidden_panic(e: &Error) {
    if let Error::Internal(m) = e {
        assert!(!m.contains("caught a panic"), "{m}");
    }
}

/// Fails the run on a mesh that was returned as a success but does not validate.
pub fn check3(r: &Result<idmesh::TetMesh, Error>) {
    match r {
        Ok(m) => {
            if let Err(e) = m.validate() {
                panic!("a mesh returned as a success fails validate(): {e}");
            }
        }
        Err(e) => no_hidden_panic(e),
    }
}

/// As [`check3`] for 2D meshes; `constrained` (`-Y`) meshes are only constrained Delaunay.
pub fn check2(r: &Result<idmesh::TriMesh, Error>, constrained: bool) {
    match r {
        Ok(m) => {
            let check = if constrained {
                m.validate_constrained()
            } else {
                m.validate().map_err(|e| e.to_string())
            };
            if let Err(e) = check {
                panic!("a mesh returned as a success fails validate(): {e}");
            }
        }
        Err(e) => no_hidden_panic(e),
    }
}
