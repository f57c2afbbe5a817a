//! Meshing is reentrant: different inputs meshed on 8 threads at once give exactly the meshes
//! (and the errors) that the same inputs give one after another. Nothing in the library may keep
//! global state between calls (a shared scratch buffer, a global random generator, a cache).

use std::path::Path;

use idmesh::io::{tetgen, triangle};
use idmesh::{tetrahedralize, triangulate, Error, Options, Options3, TetMesh, TriMesh};

const THREADS: usize = 8;

/// One meshing job: a 2D or a 3D input with its options.
#[derive(Clone)]
enum Job {
    Tri(idmesh::Pslg, Options),
    Tet(idmesh::Plc, Options3),
}

#[derive(Debug, PartialEq)]
enum Outcome {
    Tri(TriMesh),
    Tet(TetMesh),
    Failed(String),
}

fn run(job: &Job) -> Outcome {
    let err = |e: Error| Outcome::Failed(e.to_string());
    match job {
        Job::Tri(p, o) => triangulate(p, o).map(Outcome::Tri).unwrap_or_else(err),
        Job::Tet(p, o) => tetrahedralize(p, o).map(Outcome::Tet).unwrap_or_else(err),
    }
}

fn data(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/data")
        .join(name)
}

/// Inputs shipped with the repository, with quality bounds, plus two bad inputs whose errors
/// must come out the same on every thread.
fn jobs() -> Vec<Job> {
    let q2 = |a: f64| Options {
        min_angle: Some(30.0),
        max_area: Some(a),
        ..Default::default()
    };
    let q3 = |v: f64| Options3 {
        radius_edge: Some(1.414),
        max_volume: Some(v),
        ..Default::default()
    };
    let mut jobs = Vec::new();
    for (f, a) in [
        ("square_hole.poly", 0.002),
        ("letter_l.poly", 0.01),
        ("small_angle.poly", 0.01),
    ] {
        let input = triangle::read_poly(&data(f)).unwrap();
        jobs.push(Job::Tri(input.pslg, q2(a)));
    }
    for (f, v) in [
        ("3d_box_hole.poly", 0.005),
        ("3d_cube.poly", 0.002),
        ("3d_lprism.smesh", 0.01),
        ("3d_pyramid.off", 0.001),
        ("3d_octahedron.mesh", 0.002),
    ] {
        let input = tetgen::read_input(&data(f)).unwrap();
        jobs.push(Job::Tet(input.plc, q3(v)));
    }
    // Two crossing segments, and a facet index out of range.
    let mut bad2 = triangle::read_poly(&data("square_hole.poly")).unwrap().pslg;
    bad2.segments.push([0, 2]);
    bad2.segments.push([1, 3]);
    jobs.push(Job::Tri(bad2, q2(0.01)));
    let mut bad3 = tetgen::read_input(&data("3d_cube.poly")).unwrap().plc;
    bad3.facets[0].polygons[0][0] = 999;
    jobs.push(Job::Tet(bad3, q3(0.01)));
    jobs
}

#[test]
fn eight_threads_give_the_serial_meshes_and_errors() {
    let jobs = jobs();
    let serial: Vec<Outcome> = jobs.iter().map(run).collect();
    assert!(
        serial
            .iter()
            .filter(|o| matches!(o, Outcome::Failed(_)))
            .count()
            == 2,
        "exactly the two bad inputs fail serially"
    );
    // Each thread takes the jobs in its own rotation, so that different inputs are meshed at
    // the same moment.
    let parallel: Vec<Vec<(usize, Outcome)>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..THREADS)
            .map(|k| {
                let jobs = &jobs;
                s.spawn(move || {
                    (0..jobs.len())
                        .map(|i| {
                            let j = (i + k) % jobs.len();
                            (j, run(&jobs[j]))
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a meshing thread panicked"))
            .collect()
    });
    for (k, results) in parallel.iter().enumerate() {
        assert_eq!(results.len(), jobs.len());
        for (j, outcome) in results {
            assert!(
                *outcome == serial[*j],
                "thread {k}, job {j}: differs from the serial result"
            );
        }
    }
}
