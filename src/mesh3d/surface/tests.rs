use super::*;
use crate::mesh3d::plc_tests::{add_box, box_plc};
use crate::mesh3d::{tetrahedralize, Options3};

fn face(v: &[u32]) -> Facet {
    Facet {
        polygons: vec![v.to_vec()],
        ..Facet::default()
    }
}

/// The unit cube: vertex `i` at `(i & 1, i >> 1 & 1, i >> 2)`, six quadrilaterals.
fn cube() -> Plc {
    box_plc([0.0; 3], [1.0; 3])
}

/// The volume between z = 0 and the triangles the repair made of input facet `facet`, a
/// graph over the xy plane: the sum of projected area times mean height.
fn volume_under(r: &SurfaceRepair, facet: u32) -> f64 {
    let mut v = 0.0;
    for (_, f) in r
        .facet_origin
        .iter()
        .zip(&r.plc.facets)
        .filter(|(&o, _)| o == facet)
    {
        let [a, b, c] = [0, 1, 2].map(|i| r.plc.points[f.polygons[0][i] as usize]);
        let area = orient2d([a[0], a[1]], [b[0], b[1]], [c[0], c[1]]).abs() / 2.0;
        v += area * (a[2] + b[2] + c[2]) / 3.0;
    }
    v
}

/// Meshes the repaired PLC, validates the mesh and returns its volume.
fn mesh_volume(r: &SurfaceRepair) -> f64 {
    let m = tetrahedralize(&r.plc, &Options3::default()).expect("the repaired surface meshes");
    m.validate().expect("a valid mesh");
    m.stats().volume
}

#[test]
fn a_clean_surface_is_left_as_it_is() {
    let plc = cube();
    let r = repair_surface(&plc).unwrap();
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    assert_eq!(r.plc, plc);
    assert_eq!(r.vertex_map, (0..8).collect::<Vec<u32>>());
    assert_eq!(r.facet_origin, (0..6).collect::<Vec<u32>>());
}

#[test]
fn duplicate_vertices_are_merged_into_the_first() {
    let mut plc = cube();
    // Vertex 8 repeats vertex 1 (with a negative zero) and the bottom face uses it.
    plc.points.push([1.0, -0.0, 0.0]);
    plc.facets[0] = face(&[0, 8, 3, 2]);
    assert!(crate::input3d::check_plc(&plc).is_err());
    let r = repair_surface(&plc).unwrap();
    assert_eq!(
        r.warnings,
        vec![SurfaceWarning::DuplicateVertices {
            count: 1,
            first: [8, 1]
        }]
    );
    assert_eq!(r.plc.points.len(), 8);
    assert_eq!(r.vertex_map[8], 1);
    assert_eq!(r.plc.facets[0].polygons[0], vec![0, 1, 3, 2]);
    assert!((mesh_volume(&r) - 1.0).abs() < 1e-12);
    // A triangle with two copies of one corner collapses to an edge: dropped.
    let mut plc = cube();
    plc.points.push([0.0, 0.0, 0.0]);
    plc.facets.push(face(&[0, 8, 5]));
    let r = repair_surface(&plc).unwrap();
    assert_eq!(r.plc.facets.len(), 6);
    assert!(matches!(
        r.warnings[1],
        SurfaceWarning::ZeroAreaPolygons { count: 1, first: 6 }
    ));
}

#[test]
fn a_non_planar_quadrilateral_is_triangulated() {
    let mut plc = cube();
    // Raise corner 7: the top is no longer planar (the sides through it stay in x = 1 and
    // y = 1).
    plc.points[7][2] = 1.25;
    assert!(matches!(
        crate::input3d::check_plc(&plc),
        Err(Error::Input(InputError::NonPlanarFacet { .. }))
    ));
    let r = repair_surface(&plc).unwrap();
    assert_eq!(
        r.warnings,
        vec![SurfaceWarning::NonPlanarPolygons {
            count: 1,
            first: 1,
            triangles: 2
        }]
    );
    assert_eq!(r.plc.facets.len(), 5 + 2);
    assert_eq!(r.facet_origin, vec![0, 1, 1, 2, 3, 4, 5]);
    for (f, o) in r.plc.facets.iter().zip(&r.facet_origin) {
        let input = &plc.facets[*o as usize].polygons[0];
        assert!(f.polygons[0].iter().all(|v| input.contains(v)));
    }
    let v = mesh_volume(&r);
    assert!((v - volume_under(&r, 1)).abs() < 1e-12, "{v}");
    assert!(v > 1.0 && v < 1.25, "{v}");
}

#[test]
fn a_non_planar_hexagon_is_triangulated_with_its_orientation() {
    // A hexagonal drum: a planar bottom, a zigzag top (heights 1 and 1.5), planar sides.
    let mut points = Vec::new();
    for k in 0..6 {
        let a = std::f64::consts::PI / 3.0 * k as f64;
        points.push([a.cos(), a.sin(), 0.0]);
    }
    for k in 0..6 {
        let [x, y, _] = points[k];
        points.push([x, y, if k % 2 == 0 { 1.0 } else { 1.5 }]);
    }
    let mut facets = vec![face(&[5, 4, 3, 2, 1, 0]), face(&[6, 7, 8, 9, 10, 11])];
    for k in 0..6u32 {
        let j = (k + 1) % 6;
        facets.push(face(&[k, j, 6 + j, 6 + k]));
    }
    let plc = Plc {
        points,
        facets,
        ..Plc::default()
    };
    let r = repair_surface(&plc).unwrap();
    assert_eq!(
        r.warnings,
        vec![SurfaceWarning::NonPlanarPolygons {
            count: 1,
            first: 1,
            triangles: 4
        }]
    );
    // The triangles keep the hexagon's (outward, counter-clockwise from above) orientation.
    let top: Vec<&Facet> = r
        .plc
        .facets
        .iter()
        .zip(&r.facet_origin)
        .filter(|(_, &o)| o == 1)
        .map(|(f, _)| f)
        .collect();
    assert_eq!(top.len(), 4);
    for t in &top {
        let [a, b, c] = [0, 1, 2].map(|i| r.plc.points[t.polygons[0][i] as usize]);
        assert!(orient2d([a[0], a[1]], [b[0], b[1]], [c[0], c[1]]) > 0.0);
    }
    let v = mesh_volume(&r);
    assert!((v - volume_under(&r, 1)).abs() < 1e-12, "{v}");
    let area = 1.5 * 3f64.sqrt();
    assert!(v > area && v < 1.5 * area, "{v}");
}

#[test]
fn a_polygon_simple_in_no_projection_is_refused_by_name() {
    // A non-planar bow tie: its projections along every axis cross themselves.
    let plc = Plc {
        points: vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [1.0, 0.0, 0.3],
            [0.0, 1.0, 0.7],
            [5.0, 5.0, 5.0],
        ],
        facets: vec![face(&[0, 1, 2, 3]), face(&[0, 1, 4])],
        ..Plc::default()
    };
    assert_eq!(
        repair_surface(&plc),
        Err(Error::Input(InputError::UntriangulablePolygon { facet: 0 }))
    );
}

#[test]
fn a_zero_area_triangle_is_dropped_and_its_t_junction_closed() {
    let mut plc = cube();
    // Vertex 8 halves edge 0-1: the bottom lists it, the front face does not, and a
    // zero-area triangle 0-8-1 fills the "gap" as exported surfaces do.
    plc.points.push([0.5, 0.0, 0.0]);
    plc.facets[0] = face(&[0, 8, 1, 3, 2]);
    plc.facets.push(face(&[0, 8, 1]));
    let r = repair_surface(&plc).unwrap();
    assert_eq!(
        r.warnings,
        vec![SurfaceWarning::ZeroAreaPolygons { count: 1, first: 6 }]
    );
    assert_eq!(r.plc.facets.len(), 6);
    assert_eq!(
        r.plc.facets[2].polygons[0],
        vec![0, 8, 1, 5, 4],
        "the front face gets the T-junction's vertex"
    );
    assert!((mesh_volume(&r) - 1.0).abs() < 1e-12);
}

#[test]
fn unreferenced_vertices_are_dropped_and_numbering_kept_in_order() {
    let mut plc = cube();
    // One stray point inside, one outside, placed before the cube's last vertices.
    plc.points.insert(2, [0.5, 0.5, 0.5]);
    plc.points.insert(5, [9.0, 9.0, 9.0]);
    let old = |v: u32| match v {
        0 | 1 => v,
        2..=3 => v + 1,
        _ => v + 2,
    };
    for f in &mut plc.facets {
        f.polygons[0].iter_mut().for_each(|v| *v = old(*v));
    }
    let r = repair_surface(&plc).unwrap();
    assert_eq!(
        r.warnings,
        vec![SurfaceWarning::UnreferencedVertices { count: 2, first: 2 }]
    );
    assert_eq!(r.point_origin, vec![0, 1, 3, 4, 6, 7, 8, 9]);
    assert_eq!(r.vertex_map[2], NONE);
    assert_eq!(r.vertex_map[5], NONE);
    assert_eq!(r.plc, cube());
    let m = tetrahedralize(&r.plc, &Options3::default()).unwrap();
    assert!(!m.vertices.contains(&[0.5, 0.5, 0.5]));
}

#[test]
fn errors_about_the_repaired_surface_name_input_items() {
    // Two overlapping cubes, the first with a non-planar top (two triangles), so repaired
    // facet numbers differ from the input's.
    let mut plc = cube();
    plc.points[7][2] = 1.25;
    add_box(&mut plc, [0.5; 3], [1.5; 3], 1);
    plc.points.push([0.25, 0.25, 0.25]); // unreferenced: shifts point numbers too
    let r = repair_surface(&plc).unwrap();
    let e = crate::input3d::check_plc(&r.plc).unwrap_err();
    let Error::Input(InputError::FacetsIntersect { first, second }) = r.error(e.clone()) else {
        panic!("{e}");
    };
    assert!(first < 6 && (6..12).contains(&second), "{first} {second}");
    // The repaired numbers would name other facets.
    let Error::Input(InputError::FacetsIntersect { second: raw, .. }) = e else {
        panic!("{e}");
    };
    assert_eq!(r.facet_origin[raw] as usize, second);
    assert_ne!(raw, second);
}

#[test]
fn an_open_surface_is_an_input_error_naming_its_faces() {
    let mut plc = cube();
    plc.points[7][2] = 1.25;
    plc.facets.remove(0);
    let r = repair_surface(&plc).unwrap();
    let e = tetrahedralize(&r.plc, &Options3::default()).unwrap_err();
    let Error::Input(InputError::OpenSurface { count, facets, .. }) = r.error(e.clone()) else {
        panic!("{e}");
    };
    assert_eq!(count, 4);
    // The bottom's edges belong to the four input sides (facets 1..=4 after the removal).
    assert!(!facets.is_empty() && facets.iter().all(|f| (1..=4).contains(f)));
}

#[test]
fn a_non_manifold_edge_between_two_closed_parts_meshes() {
    // Two cubes sharing only the edge from (1, 0, 0) to (1, 0, 1) (four faces on it, its
    // ends given twice), as exported models have them: not an error.
    let mut plc = cube();
    add_box(&mut plc, [1.0, -1.0, 0.0], [2.0, 0.0, 1.0], 1);
    let r = repair_surface(&plc).unwrap();
    assert!(matches!(
        r.warnings[0],
        SurfaceWarning::DuplicateVertices { count: 2, .. }
    ));
    assert!((mesh_volume(&r) - 2.0).abs() < 1e-12);
}

#[test]
fn projected_simplicity_is_exact() {
    let p = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [1.0, 0.0]];
    let q = |v: u32| p[v as usize];
    assert!(simple(&[0, 1, 2, 3], &q));
    assert!(simple(&[0, 4, 1, 2, 3], &q), "a straight corner is fine");
    assert!(!simple(&[0, 2, 1, 3], &q), "a bow tie");
    assert!(!simple(&[0, 1, 4, 3], &q), "an edge folding back");
    assert!(!simple(&[4, 1, 2, 3, 0, 2], &q), "a corner visited twice");
}
