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

/// The unit cube scaled by 1e-25 with a facet of 1e-3 of its size added at a corner, `-p`:
/// found by the 3D campaign (seed 1, run 6818) running past its 20 s limit. Ignored until
/// the termination work of issue 14 (constructions relative to the local feature size) lands;
/// run with `cargo test --release --test fuzz_regressions -- --ignored`.
#[test]
#[ignore]
fn scaled_cube_with_a_small_facet_terminates() {
    let case = mutate::Case3 {
        seed: 168,
        muts: vec![
            Tiny {
                point: 21877,
                e: 169,
            },
            Scale { e: 66 },
        ],
        ratio: None,
        keep_surface: false,
    };
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(case.run().map(|m| m.tets.len())));
    let r = rx
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("no answer within 20 s");
    assert!(!matches!(r, Err(idmesh::Error::Internal(_))), "{r:?}");
}

/// The cube with a cubic hole and one point added 1e-11 of the box from a corner, `-pq`: the
/// 3D campaign's most common internal error ("subface … cannot be split", 79 of 6,819 cases).
/// Ignored until fixed (issue 14).
#[test]
#[ignore]
fn near_duplicate_point_is_meshed_or_named() {
    let case = mutate::Case3 {
        seed: 202,
        muts: vec![NearDuplicate {
            point: 33828,
            e: 187,
            dir: [-44, 39, -109],
        }],
        ratio: Some(161),
        keep_surface: false,
    };
    let r = case.run();
    assert!(!matches!(r, Err(idmesh::Error::Internal(_))), "{r:?}");
}

/// The square with a hole, a segment of 3e-12 added at corner 0 and then its first end moved
/// by 3e-3 along x: a 3e-3 segment lying about 6e-13 above the boundary segment, `-p` with a
/// Steiner budget. Found by the fuzz smoke run in CI running past 20 s: the segment splits
/// that conformity needs (about length / gap of them) were not counted against the budget.
/// Now they are: the run stops at the budget with an incomplete, constrained Delaunay mesh.
#[test]
fn segment_hugging_the_boundary_terminates() {
    let case = mutate::Case2 {
        seed: 93,
        muts: vec![
            Tiny {
                point: 46896,
                e: 34,
            },
            Perturb {
                point: 48658,
                e: 0,
                dir: [0, 0, 0],
            },
        ],
        angle: None,
        no_boundary_steiner: false,
    };
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(case.run());
    });
    let m = rx
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("no answer within 20 s")
        .unwrap();
    assert!(!m.complete, "the Steiner budget must be reached");
    assert!(m.steiner_points <= 20_100, "{}", m.steiner_points);
    m.validate().unwrap();
    m.validate_constrained().unwrap();
}
