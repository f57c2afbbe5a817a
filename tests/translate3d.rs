//! Translation invariance of 3D meshing (issue 14): an input moved far from the origin is meshed as
//! the original, not forever. A U-shaped surface model translated by 1e6 hung with `-p`, `-pq` and
//! `-pY` (the original takes 0.03 s): every split point was rounded to the 1.2e-10 grid of
//! coordinates near 1e6, off its edge and its facet's plane, and the facet meshes and the 3D mesh
//! then broke the near-ties of the walls' rectangles differently, without end. The
//! input here is built the same way: a U-shaped prism whose walls are rectangles split into
//! two triangles, with coordinates of seven decimal digits.

use idmesh::{Facet, Options3, Plc, TetMesh};
use std::time::Duration;

/// The U prism: an outer and an inner arc of `n` points each (radii 0.3 and 0.2, a half
/// circle), joined by two straight arms, extruded from z = -0.0804051 to 0.0804051; the top
/// and bottom are polygons, the walls pairs of triangles.
fn u_prism(n: usize, shift: f64) -> Plc {
    let round7 = |x: f64| (x * 1e7).round() / 1e7;
    let mut ring: Vec<[f64; 2]> = Vec::new();
    for i in 0..n {
        let a = std::f64::consts::PI * i as f64 / (n - 1) as f64;
        ring.push([round7(0.3 * a.cos()), round7(-0.3 * a.sin())]);
    }
    ring.push([-0.3, 0.35]);
    ring.push([-0.2, 0.35]);
    for i in (0..n).rev() {
        let a = std::f64::consts::PI * i as f64 / (n - 1) as f64;
        ring.push([round7(0.2 * a.cos()), round7(-0.2 * a.sin())]);
    }
    ring.push([0.2, 0.35]);
    ring.push([0.3, 0.35]);
    let m = ring.len() as u32;
    let z = 0.0804051;
    let mut points = Vec::new();
    for &h in &[-z, z] {
        for p in &ring {
            points.push([p[0] + shift, p[1] + shift, h + shift]);
        }
    }
    let facet = |polygon: Vec<u32>| Facet {
        polygons: vec![polygon],
        ..Default::default()
    };
    let mut facets = vec![facet((0..m).collect()), facet((m..2 * m).collect())];
    for i in 0..m {
        let j = (i + 1) % m;
        facets.push(facet(vec![i, j, m + j]));
        facets.push(facet(vec![i, m + j, m + i]));
    }
    Plc {
        points,
        facets,
        ..Default::default()
    }
}

/// Meshes on a thread, failing the test when no answer comes within 20 s.
fn mesh_in_time(plc: Plc, opts: Options3) -> Result<TetMesh, idmesh::Error> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(idmesh::tetrahedralize(&plc, &opts));
    });
    rx.recv_timeout(Duration::from_secs(20))
        .expect("no answer within 20 s")
}

fn counts(m: &TetMesh) -> (usize, usize, usize) {
    (m.vertices.len(), m.tets.len(), m.faces.len())
}

#[test]
fn translated_prism_gets_the_original_mesh() {
    let opts = Options3::default();
    let here = mesh_in_time(u_prism(16, 0.0), opts.clone()).unwrap();
    here.validate().unwrap();
    let far = mesh_in_time(u_prism(16, 1e6), opts).unwrap();
    far.validate().unwrap();
    assert_eq!(counts(&far), counts(&here));
    // Input vertices come back exactly.
    let input = u_prism(16, 1e6);
    assert_eq!(&far.vertices[..input.points.len()], &input.points[..]);
}

#[test]
fn translated_prism_keeps_its_surface() {
    let opts = Options3 {
        keep_surface: true,
        ..Default::default()
    };
    let far = mesh_in_time(u_prism(16, 1e6), opts).unwrap();
    far.validate().unwrap();
    assert!(far.surface_kept);
    // 36 wall rectangles of two triangles and two caps of 36 - 2 triangles: nothing split.
    assert_eq!(far.faces.len(), 2 * 36 + 2 * 34);
}

/// With a radius-edge bound the move back onto the grid near 1e6 can leave the mesh not
/// exactly Delaunay; then the input is meshed where it is, with a Steiner budget from the
/// first run: either way the run ends, and a mesh it returns validates.
/// With a quality bound the translated prism is not meshed to the same tets (split points are
/// rounded to a coarser grid), but to a mesh of the same size and quality: within a band of
/// the original's tet count, of its number of tets above the bound (all exempt: they touch
/// the prism's small input angles), worst radius-edge ratio and smallest dihedral angle (issue
/// 14: "the same combinatorial mesh as the original, or one of equal quality"), never a budget
/// error or a hang. The band is what the shifts below measure with room to spare. Measured
/// (far / original): tets 0.77-1.16x, tets above the bound 1.06-1.13x, worst ratio 0.97-1.42x,
/// smallest angle 0.73-2.3x. The worst ratio is one exempt tet's, and varies that much with
/// the refinement order alone: before provisional points stopped their cavity search at the
/// first encroachment, the original at -q1.2 had 5.26 (now 3.75), the shift by 1e6 5.24 (now
/// 5.33).
#[test]
fn translated_prism_with_quality_matches_the_original() {
    for q in [1.414, 1.2] {
        let opts = Options3 {
            radius_edge: Some(q),
            ..Default::default()
        };
        let here = mesh_in_time(u_prism(16, 0.0), opts.clone()).unwrap();
        here.validate().unwrap();
        let s0 = here.stats();
        for shift in [1e6, -3e7] {
            let far = mesh_in_time(u_prism(16, shift), opts.clone())
                .unwrap_or_else(|e| panic!("-q{q}, shifted by {shift}: {e}"));
            far.validate().unwrap();
            let s = far.stats();
            let ratio = far.tets.len() as f64 / here.tets.len() as f64;
            assert!(
                (0.6..=1.6).contains(&ratio),
                "-q{q}, shifted by {shift}: {} tets against {}",
                far.tets.len(),
                here.tets.len()
            );
            let (n, n0) = (above(&far, q), above(&here, q));
            assert!(
                n as f64 <= 1.3 * n0 as f64 + 2.0,
                "-q{q}, shifted by {shift}: {n} tets above the bound against {n0}"
            );
            assert!(
                s.max_radius_edge <= 1.6 * s0.max_radius_edge,
                "-q{q}, shifted by {shift}: worst radius-edge ratio {} against {}",
                s.max_radius_edge,
                s0.max_radius_edge
            );
            assert!(
                s.min_dihedral >= 0.3 * s0.min_dihedral,
                "-q{q}, shifted by {shift}: smallest dihedral {} against {}",
                s.min_dihedral,
                s0.min_dihedral
            );
        }
    }
}

/// How many tets of `m` have a radius-edge ratio above `q`.
fn above(m: &TetMesh, q: f64) -> usize {
    m.tets
        .iter()
        .filter(|t| idmesh::geometry::tet_radius_edge(t.map(|v| m.vertices[v as usize])) > q)
        .count()
}
