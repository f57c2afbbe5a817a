//! TetGen's `-T<tol>`: the opt-in merge of nearly coplanar facets
//! (`Options3::coplanar_tolerance`, `idmesh::mesh3d::snap_nearly_coplanar_facets`). Without it
//! the input is kept exactly; with it the fold goes and so does the flat tetrahedron.

use idmesh::mesh3d::{snap_nearly_coplanar_facets, SnapReport, MAX_COPLANAR_TOLERANCE};
use idmesh::switches::tetgen::parse_string;
use idmesh::{tetrahedralize, Error, Facet, Options3, Plc, TetMesh};

fn facet(v: &[u32]) -> Facet {
    Facet {
        polygons: vec![v.to_vec()],
        holes: Vec::new(),
        marker: 0,
    }
}

/// The unit cube (corner `x + 2y + 4z` at `(x, y, z)`) whose top face is two triangles along
/// the diagonal 4-7, the corner 6 moved by `dz` out of the top's plane (so the top is folded
/// along 4-7; the sides through 6 stay planar).
fn folded_box(dz: f64) -> Plc {
    let mut points: Vec<[f64; 3]> = (0..8u32)
        .map(|i| [i & 1, (i >> 1) & 1, i >> 2].map(f64::from))
        .collect();
    points[6][2] += dz;
    let facets = [
        &[0, 1, 3, 2][..],
        &[0, 1, 5, 4],
        &[2, 3, 7, 6],
        &[0, 2, 6, 4],
        &[1, 3, 7, 5],
        &[4, 5, 7],
        &[4, 7, 6],
    ];
    Plc {
        points,
        facets: facets.iter().map(|f| facet(f)).collect(),
        ..Plc::default()
    }
}

/// The unit cube with each face an `n`×`n` grid of squares split into triangles, the grid
/// points inside each face moved along the face's normal by up to `noise` (a fixed
/// pseudo-random sequence): a scanned box.
fn noisy_box(n: u32, noise: f64) -> Plc {
    let mut plc = Plc::default();
    let mut index = std::collections::HashMap::new();
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut id = |plc: &mut Plc, p: [f64; 3]| -> u32 {
        let key = p.map(f64::to_bits);
        *index.entry(key).or_insert_with(|| {
            plc.points.push(p);
            plc.points.len() as u32 - 1
        })
    };
    for axis in 0..3 {
        for side in [0.0, 1.0] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let mut grid = vec![vec![0u32; n as usize + 1]; n as usize + 1];
            for (i, row) in grid.iter_mut().enumerate() {
                for (j, g) in row.iter_mut().enumerate() {
                    let mut p = [0.0; 3];
                    p[axis] = side;
                    p[u] = i as f64 / n as f64;
                    p[v] = j as f64 / n as f64;
                    *g = id(&mut plc, p);
                }
            }
            for i in 0..n as usize {
                for j in 0..n as usize {
                    let (a, b, c, d) = (
                        grid[i][j],
                        grid[i + 1][j],
                        grid[i + 1][j + 1],
                        grid[i][j + 1],
                    );
                    plc.facets.push(facet(&[a, b, c]));
                    plc.facets.push(facet(&[a, c, d]));
                }
            }
        }
    }
    for p in &mut plc.points {
        let on: Vec<usize> = (0..3).filter(|&k| p[k] == 0.0 || p[k] == 1.0).collect();
        if let [k] = on[..] {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let r = (seed >> 11) as f64 / (1u64 << 53) as f64;
            p[k] += noise * (2.0 * r - 1.0);
        }
    }
    plc
}

fn mesh(plc: &Plc, opts: &Options3) -> TetMesh {
    let m = tetrahedralize(plc, opts).expect("meshes");
    m.validate().expect("valid mesh");
    m
}

/// Merge as `idmesh tetgen` does; no sliver removal, so a flat tetrahedron stays visible.
fn merging(tol: Option<f64>) -> Options3 {
    Options3 {
        merge_coplanar: true,
        coplanar_tolerance: tol,
        ..Options3::default()
    }
}

#[test]
fn a_tiny_fold_leaves_a_flat_tet_unless_merged_within_a_tolerance() {
    let plc = folded_box(-1e-9);
    let exact = mesh(&plc, &merging(None));
    assert!(
        exact.stats().min_dihedral < 1.0,
        "the fold makes a flat tetrahedron: {:?}",
        exact.stats()
    );
    assert_eq!(exact.vertices[6], plc.points[6], "kept exactly without -T");
    let merged = mesh(&plc, &merging(Some(1e-8)));
    let s = merged.stats();
    assert!(s.min_dihedral > 30.0, "no flat tetrahedron with -T: {s:?}");
    assert_eq!(
        merged.vertices[6],
        [0.0, 1.0, 1.0],
        "moved onto the top's plane"
    );
    assert!((merged.volume() - 1.0).abs() < 1e-12);
    // The same with -pq through the switch parser (TetGen's default tolerance for `T` alone).
    let o = parse_string("pqT").unwrap().options();
    assert_eq!(o.coplanar_tolerance, Some(1e-8));
    let q = mesh(&plc, &o);
    assert_eq!(q.vertices[6], [0.0, 1.0, 1.0]);
    assert!(q.stats().min_dihedral >= 15.0, "{:?}", q.stats());
    // A fold of 1e-6 is beyond the tolerance: kept.
    let (_, r) = snap_nearly_coplanar_facets(&folded_box(-1e-6), 1e-8).unwrap();
    assert_eq!(r.moved, 0, "{r:?}");
    let (_, r) = snap_nearly_coplanar_facets(&folded_box(-1e-6), 1e-5).unwrap();
    assert_eq!(r.moved, 1, "{r:?}");
}

#[test]
fn a_scanned_box_is_snapped_to_its_faces_and_loses_its_flat_tets() {
    let plc = noisy_box(6, 1e-10);
    let (snapped, r) = snap_nearly_coplanar_facets(&plc, 1e-8).unwrap();
    assert_eq!((r.groups, r.facets, r.refused), (6, 432, 0), "{r:?}");
    assert_eq!(r.moved, 6 * 25, "the grid points inside the faces");
    for (p, q) in plc.points.iter().zip(&snapped.points) {
        let moved: Vec<usize> = (0..3).filter(|&k| p[k] != q[k]).collect();
        assert!(moved.len() <= 1, "moved along one axis");
        for k in moved {
            assert!(q[k] == 0.0 || q[k] == 1.0);
            assert!((p[k] - q[k]).abs() <= 1e-10);
        }
    }
    let sw = parse_string("pq/0").unwrap().options();
    let exact = mesh(&plc, &sw);
    assert!(exact.stats().min_dihedral < 1.0, "{:?}", exact.stats());
    let tol = mesh(&plc, &parse_string("pq/0T1e-8").unwrap().options());
    assert!(tol.stats().min_dihedral > 1.0, "{:?}", tol.stats());
    let q = mesh(&plc, &parse_string("pqT1e-8").unwrap().options());
    assert!(q.stats().min_dihedral >= 15.0, "{:?}", q.stats());
}

/// Which vertices move, and the report.
fn decisions(plc: &Plc, tol: f64) -> (Vec<usize>, SnapReport) {
    let (out, r) = snap_nearly_coplanar_facets(plc, tol).unwrap();
    let moved = (0..plc.points.len())
        .filter(|&i| out.points[i] != plc.points[i])
        .collect();
    (moved, r)
}

#[test]
fn the_rule_does_not_change_under_scaling_and_translation() {
    let transform = |plc: &Plc| Plc {
        points: plc
            .points
            .iter()
            .map(|p| p.map(|x| x * 1e6 + 1e6))
            .collect(),
        ..plc.clone()
    };
    for (name, plc) in [
        ("fold 1e-9", folded_box(-1e-9)),
        ("fold 3e-8", folded_box(3e-8)),
        ("fold 1e-7", folded_box(-1e-7)),
        ("scanned box", noisy_box(4, 3e-9)),
    ] {
        for tol in [1e-8, 1e-7] {
            let here = decisions(&plc, tol);
            let there = decisions(&transform(&plc), tol);
            assert_eq!(here, there, "{name}, tolerance {tol}");
        }
    }
    // The scanned box: at 1e-7 every face is snapped whole (its 9 inner grid points moved).
    let (moved, r) = decisions(&noisy_box(4, 3e-9), 1e-7);
    assert_eq!((r.groups, r.facets, r.refused), (6, 6 * 32, 0), "{r:?}");
    assert_eq!(moved.len(), 6 * 9);
    // And the decisions differ between the two tolerances where they should.
    assert_eq!(decisions(&folded_box(3e-8), 1e-8).0, Vec::<usize>::new());
    assert_eq!(decisions(&folded_box(3e-8), 1e-7).0, vec![6]);
}

#[test]
fn m_disables_and_y_ignores_the_merge() {
    let plc = folded_box(-1e-9);
    let o = parse_string("pq/0MT1e-8").unwrap().options();
    assert!(!o.merge_coplanar);
    let m = mesh(&plc, &o);
    assert_eq!(m.vertices[6], plc.points[6], "-M: nothing merged or moved");
    assert!(m.stats().min_dihedral < 1.0);
    let o = parse_string("pYT1e-8").unwrap().options();
    let m = mesh(&plc, &o);
    assert_eq!(m.vertices[6], plc.points[6], "-Y keeps the input surface");
}

#[test]
fn bad_tolerances_are_refused_by_name() {
    for bad in ["pT0", "pT0.5", "pT1e-400", "pT0.0100001"] {
        let e = parse_string(bad).unwrap_err();
        assert!(e.contains("-T") && e.contains("tolerance"), "{bad}: {e}");
    }
    assert!(parse_string("pT-1").is_err());
    let s = parse_string("pT1e-5").unwrap();
    assert_eq!(s.coplanar_tolerance, Some(1e-5));
    assert_eq!(
        parse_string(&format!("pT{MAX_COPLANAR_TOLERANCE}"))
            .unwrap()
            .coplanar_tolerance,
        Some(MAX_COPLANAR_TOLERANCE)
    );
    assert_eq!(parse_string("pq").unwrap().coplanar_tolerance, None);
    for bad in [f64::NAN, 0.0, -1e-8, 0.5, f64::INFINITY] {
        match tetrahedralize(&folded_box(-1e-9), &merging(Some(bad))) {
            Err(Error::InvalidOption(m)) => assert!(m.contains("coplanar tolerance"), "{m}"),
            other => panic!("{bad}: {other:?}"),
        }
        assert!(snap_nearly_coplanar_facets(&folded_box(-1e-9), bad).is_err());
    }
}
