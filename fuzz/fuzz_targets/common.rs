#![allow(dead_code)] // each target uses part of this module
//! What every meshing fuzz target checks on a result: a mesh handed back as a success passes
//! the exact `validate()`, and no internal error comes back (a panic the library caught at
//! its boundary, `Error::Internal("… caught a panic …")`, or the mesher giving up): issue 14
//! asks for none, and the counted campaign (`examples/fuzz_campaign.rs`) has found none since
//! the `-Y` fin and wedge fixes. Input errors, `Unsupported` refusals and a reached budget are
//! reported results.

use idmesh::Error;

/// The Steiner budget of a fuzzed case. Under the fuzzer's instrumentation (coverage and
/// AddressSanitizer) the exact checks of `validate()` run some 400 times slower: a cube with
/// a 1e-12 facet at `-q1.2` and the campaign's budget of 20,000 (14,188 Steiner points, 80,970
/// tets, 0.26 s from the command line) took 104 s, past the 20 s hang limit. The fuzzer looks
/// for wrong results on small inputs; the campaign, uninstrumented, runs the full budget.
pub const FUZZ_BUDGET: u64 = 2_000;

/// Fails the run on an internal error (a caught panic included).
pub fn no_internal_error(e: &Error) {
    if let Error::Internal(m) = e {
        panic!("internal error: {m}");
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
        Err(e) => no_internal_error(e),
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
        Err(e) => no_internal_error(e),
    }
}
