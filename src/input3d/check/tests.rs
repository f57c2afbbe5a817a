//! Tests of the checker's internals: facet regions as triangles, and the grid-driven tests on
//! a surface large enough to fill many cells.

use super::facets::triangulate_facets;
use super::*;
use crate::input3d::{Facet, Plc};

/// Twice the area of a facet region's triangles (exact for these axis-aligned inputs).
fn area2(plc: &Plc, tris: &[[u32; 3]]) -> f64 {
    tris.iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| plc.points[v as usize]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                u[1] * w[2] - u[2] * w[1],
                u[2] * w[0] - u[0] * w[2],
                u[0] * w[1] - u[1] * w[0],
            ];
            (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
        })
        .sum()
}

/// A vertical facet (x = 1) with a square hole, plus points off the plane to make the PLC
/// three-dimensional.
fn holed_wall() -> Plc {
    let mut points = vec![
        [1.0, 0.0, 0.0],
        [1.0, 4.0, 0.0],
        [1.0, 4.0, 4.0],
        [1.0, 0.0, 4.0],
        [1.0, 1.0, 1.0],
        [1.0, 3.0, 1.0],
        [1.0, 3.0, 3.0],
        [1.0, 1.0, 3.0],
    ];
    points.push([5.0, 5.0, 5.0]);
    Plc {
        points,
        facets: vec![Facet {
            polygons: vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]],
            holes: vec![[1.0, 2.0, 2.0]],
            marker: 0,
        }],
        ..Plc::default()
    }
}

#[test]
fn facet_region_leaves_out_the_hole() {
    let plc = holed_wall();
    let fs = triangulate_facets(&plc).unwrap();
    assert_eq!(area2(&plc, &fs.tris), 2.0 * 12.0);
    assert!(fs.tri_facet.iter().all(|&f| f == 0));
    // The ring: 8 triangles whose 24 edge slots are the 8 polygon edges once and 8 inner
    // diagonals twice.
    assert_eq!(fs.tris.len(), 8);
    assert_eq!(fs.diags.len(), 8);
    assert!(fs.has_vertex(0, 5) && !fs.has_vertex(0, 8));
    check_plc(&plc).unwrap();
    // Without the seed, the inner square is part of the facet.
    let mut whole = plc.clone();
    whole.facets[0].holes.clear();
    let fs = triangulate_facets(&whole).unwrap();
    assert_eq!(area2(&whole, &fs.tris), 2.0 * 16.0);
}

#[test]
fn a_facet_filling_the_hole_of_another_is_fine_but_not_without_the_hole() {
    // As in TetGen's example PLC: a facet with a hole, and another facet exactly in it.
    let mut plc = holed_wall();
    plc.facets.push(Facet {
        polygons: vec![vec![4, 5, 6, 7]],
        ..Facet::default()
    });
    check_plc(&plc).unwrap();
    plc.facets[0].holes.clear();
    assert_eq!(
        check_plc(&plc),
        Err(InputError::FacetsIntersect {
            first: 0,
            second: 1
        }
        .into())
    );
}

/// A closed, finely triangulated torus: many small facets meeting only properly.
fn torus(nu: usize, nv: usize) -> Plc {
    let (big, small) = (3.0, 1.0);
    let mut points = Vec::new();
    for i in 0..nu {
        let u = i as f64 / nu as f64 * std::f64::consts::TAU;
        for j in 0..nv {
            let v = j as f64 / nv as f64 * std::f64::consts::TAU;
            let r = big + small * v.cos();
            points.push([r * u.cos(), r * u.sin(), small * v.sin()]);
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let mut facets = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            facets.push(Facet {
                polygons: vec![vec![a, b, c]],
                ..Facet::default()
            });
            facets.push(Facet {
                polygons: vec![vec![a, c, d]],
                ..Facet::default()
            });
        }
    }
    Plc {
        points,
        facets,
        ..Plc::default()
    }
}

#[test]
fn a_large_valid_surface_passes_and_one_pushed_vertex_is_caught() {
    let plc = torus(60, 40);
    assert_eq!(plc.facets.len(), 4800);
    check_plc(&plc).unwrap();
    // Push one vertex of the outer equator (radius 4) through the inner one (radius 2): its
    // triangles now cross others.
    let mut bad = plc.clone();
    let v = 5 * 40; // i = 5, j = 0: the outer equator.
    let p = bad.points[v];
    bad.points[v] = [p[0] * 0.4, p[1] * 0.4, p[2]];
    match check_plc(&bad) {
        Err(Error::Input(InputError::FacetsIntersect { .. })) => {}
        other => panic!("expected intersecting facets, got {other:?}"),
    }
}
