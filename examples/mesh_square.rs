//! Meshes a unit square with a square hole through the Rust API and prints the mesh size and
//! its smallest angle: `cargo run --example mesh_square`. The C twin is
//! `examples/mesh_square.c`.

use idmesh::{triangulate, Options, Pslg};

fn main() {
    match summary() {
        Ok(line) => println!("{line}"),
        Err(e) => {
            eprintln!("mesh_square: {e}");
            std::process::exit(1);
        }
    }
}

/// Meshes the example and describes the result in one line (the same line the C example
/// prints, which `tests/c_api.rs` checks).
pub fn summary() -> Result<String, idmesh::Error> {
    // Outer square (points 0-3, segment marker 1) and hole (points 4-7, marker 2).
    let pslg = Pslg {
        points: vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.4, 0.4],
            [0.6, 0.4],
            [0.6, 0.6],
            [0.4, 0.6],
        ],
        segments: vec![
            [0, 1],
            [1, 2],
            [2, 3],
            [3, 0],
            [4, 5],
            [5, 6],
            [6, 7],
            [7, 4],
        ],
        segment_markers: vec![1, 1, 1, 1, 2, 2, 2, 2],
        holes: vec![[0.5, 0.5]],
        ..Pslg::default()
    };
    let opts = Options {
        min_angle: Some(30.0), // like Triangle's -q30
        max_area: Some(0.002), // like Triangle's -a0.002
        ..Options::default()
    };
    let mesh = triangulate(&pslg, &opts)?;
    let (min_angle, _) = mesh.angle_range();
    Ok(format!(
        "idmesh {}: {} vertices, {} triangles, {} subsegments, min angle {:.2} degrees",
        env!("CARGO_PKG_VERSION"),
        mesh.vertices.len(),
        mesh.triangles.len(),
        mesh.segments.len(),
        min_angle
    ))
}
