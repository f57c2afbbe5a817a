//! Cases found by the fuzz targets (`fuzz/`, `scripts/fuzz_smoke.sh`) and the campaign
//! (`examples/fuzz_campaign.rs`), rebuilt from their mutations (the same mutation code).
//! Each asserts what failed when it was found; a comment says what that was.

#[path = "../fuzz/fuzz_targets/mutate.rs"]
mod mutate;

use mutate::Mutation::*;

/// The star with a segment of 1e-11 of its size added at an inner corner, and a tip moved by
/// 1e-3: the mesh came back as a success with a vertex inside a triangle's circumcircle (the
/// final check then only looked at the structure). Now the local empty-circle rule is part of
/// every run's final check, so such a mesh can never be returned.
#[test]
fn star_with_a_tiny_segment_never_returns_a_non_delaunay_mesh() {
    let mut g = mutate::seed2(8);
    mutate::mutate2(
        &mut g,
        &[
            Tiny {
                point: 54741,
                e: 213,
            },
            Perturb {
                point: 0,
                e: 0,
                dir: [0, 0, 0],
            },
        ],
    );
    match idmesh::triangulate(&g, &idmesh::Options::default()) {
        Ok(m) => m.validate().unwrap(),
        Err(idmesh::Error::Internal(e)) => assert!(e.contains("output check failed"), "{e}"),
        Err(e) => panic!("{e}"),
    }
}
