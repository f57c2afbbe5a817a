//! TetGen's `-c` (mesh the convex hull) and its facet and segment constraints
//! (`facetconstraintlist`, `segmentconstraintlist`, `.var` files): through the library's
//! [`Options3`] and through `idmesh tetgen`, each checked on the mesh made.

mod cli_common;

use cli_common::{idmesh, ok};
use idmesh::geometry::tet_volume;
use idmesh::predicates::orient3d;
use idmesh::{tetrahedralize, Facet, Options3, Plc, TetMesh, NONE};

/// An L-shaped prism: the square {0..2}² minus {1..2}², z from 0 to 1. Points 0..5 at z = 0
/// and 6..11 at z = 1; facet markers 1 (bottom), 2 (top), 3 (sides).
fn l_prism() -> Plc {
    let l = [
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [1.0, 2.0],
        [0.0, 2.0],
    ];
    let mut plc = Plc::default();
    for z in [0.0, 1.0] {
        plc.points.extend(l.iter().map(|p| [p[0], p[1], z]));
    }
    let f = |polygons: Vec<Vec<u32>>, marker| Facet {
        polygons,
        holes: Vec::new(),
        marker,
    };
    plc.facets.push(f(vec![(0..6).collect()], 1));
    plc.facets.push(f(vec![(6..12).collect()], 2));
    for i in 0..6u32 {
        let j = (i + 1) % 6;
        plc.facets.push(f(vec![vec![i, j, j + 6, i + 6]], 3));
    }
    plc
}

fn area(c: [[f64; 3]; 3]) -> f64 {
    idmesh::geometry::tri_area3(c[0], c[1], c[2])
}

fn corners(p: &[[f64; 3]], f: [u32; 3]) -> [[f64; 3]; 3] {
    f.map(|v| p[v as usize])
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The faces of the mesh with one tetrahedron only.
fn boundary_faces(m: &TetMesh) -> Vec<[u32; 3]> {
    let mut out = Vec::new();
    for (t, n) in m.tets.iter().zip(&m.neighbors) {
        for (i, _) in n.iter().enumerate().filter(|(_, &x)| x == NONE) {
            let f: Vec<u32> = (0..4).filter(|&j| j != i).map(|j| t[j]).collect();
            out.push([f[0], f[1], f[2]]);
        }
    }
    out
}

/// The longest subsegment on the input edge from `a` to `b` (axis-parallel): mesh face edges
/// whose ends both lie on it.
fn longest_piece(p: &[[f64; 3]], faces: &[[u32; 3]], a: [f64; 3], b: [f64; 3]) -> f64 {
    let on = |q: [f64; 3]| {
        (0..3).all(|k| q[k] >= a[k].min(b[k]) && q[k] <= a[k].max(b[k]))
            && (0..3).filter(|&k| a[k] == b[k]).all(|k| q[k] == a[k])
    };
    let mut longest: f64 = 0.0;
    for f in faces {
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            let (x, y) = (p[f[i] as usize], p[f[j] as usize]);
            if on(x) && on(y) {
                longest = longest.max(dist(x, y));
            }
        }
    }
    longest
}

#[test]
fn facet_and_segment_bounds_split_only_what_they_name() {
    let plc = l_prism();
    let opts = Options3 {
        radius_edge: Some(2.0),
        facet_max_area: vec![(1, 0.02)],
        // The side edge from (2,0,0) to (2,1,0).
        segment_max_length: vec![([2, 1], 0.07)],
        ..Options3::default()
    };
    let m = tetrahedralize(&plc, &opts).unwrap();
    m.validate().unwrap();
    let p = &m.vertices;
    let mut largest = [0.0f64; 4];
    for (f, &marker) in m.faces.iter().zip(&m.face_markers) {
        let a = area(corners(p, *f));
        largest[marker as usize] = largest[marker as usize].max(a);
    }
    assert!(
        largest[1] <= 0.02,
        "bottom faces: largest area {}",
        largest[1]
    );
    assert!(largest[1] > 0.0);
    assert!(
        largest[2] > 0.02,
        "the top is not bounded: its largest face {} should exceed the bottom's bound",
        largest[2]
    );
    let piece = longest_piece(p, &m.faces, [2.0, 0.0, 0.0], [2.0, 1.0, 0.0]);
    assert!(piece > 0.0 && piece <= 0.07, "bounded edge: {piece}");
    let other = longest_piece(p, &m.faces, [2.0, 0.0, 1.0], [2.0, 1.0, 1.0]);
    assert!(other > 0.07, "the top edge is not bounded: {other}");

    // Without the bounds the bottom keeps larger faces: the bound did the splitting.
    let plain = tetrahedralize(
        &plc,
        &Options3 {
            radius_edge: Some(2.0),
            ..Options3::default()
        },
    )
    .unwrap();
    let bottom = plain
        .faces
        .iter()
        .zip(&plain.face_markers)
        .filter(|(_, &mk)| mk == 1)
        .map(|(f, _)| area(corners(&plain.vertices, *f)))
        .fold(0.0, f64::max);
    assert!(bottom > 0.02, "{bottom}");

    for bad in [
        Options3 {
            facet_max_area: vec![(1, 0.0)],
            ..Options3::default()
        },
        Options3 {
            segment_max_length: vec![([0, 1], f64::NAN)],
            ..Options3::default()
        },
    ] {
        let e = tetrahedralize(&plc, &bad).unwrap_err().to_string();
        assert!(e.contains("positive"), "{e}");
    }
}

/// Checks that `m` fills the convex hull of the L prism: every boundary face lies in a plane
/// with all input points on one side (exact), and the volume is the hull's, 3.5.
fn assert_fills_hull(plc: &Plc, m: &TetMesh) {
    let p = &m.vertices;
    for f in boundary_faces(m) {
        let [a, b, c] = corners(p, f);
        let signs: Vec<f64> = plc.points.iter().map(|&d| orient3d(a, b, c, d)).collect();
        assert!(
            signs.iter().all(|&s| s >= 0.0) || signs.iter().all(|&s| s <= 0.0),
            "boundary face {f:?} is not on the hull"
        );
    }
    let vol: f64 = m
        .tets
        .iter()
        .map(|t| tet_volume(t.map(|v| p[v as usize])))
        .sum();
    assert!((vol - 3.5).abs() < 1e-12, "volume {vol}");
}

#[test]
fn convex_hull_fills_the_notch_and_keeps_the_input_facets() {
    let plc = l_prism();
    for (q, merge) in [(None, false), (Some(1.5), false), (Some(2.0), true)] {
        let m = tetrahedralize(
            &plc,
            &Options3 {
                convex_hull: true,
                radius_edge: q,
                merge_coplanar: merge,
                ..Options3::default()
            },
        )
        .unwrap();
        m.validate().unwrap();
        assert_fills_hull(&plc, &m);
        // The notch's walls (x = 1 or y = 1 inside the hull) are still faces, marker 3.
        let inner = m
            .faces
            .iter()
            .zip(&m.face_markers)
            .filter(|(f, &mk)| {
                mk == 3
                    && corners(&m.vertices, **f)
                        .iter()
                        .all(|c| c[0] == 1.0 && c[1] >= 1.0 || c[1] == 1.0 && c[0] >= 1.0)
            })
            .count();
        assert!(inner >= 4, "the inner walls are kept as faces ({inner})");
    }
    // Without -c the notch stays empty.
    let m = tetrahedralize(&plc, &Options3::default()).unwrap();
    let vol: f64 = m
        .tets
        .iter()
        .map(|t| tet_volume(t.map(|v| m.vertices[v as usize])))
        .sum();
    assert!((vol - 3.0).abs() < 1e-12, "{vol}");
}

/// The L prism as a `.poly` file (1-based), facet markers as in [`l_prism`].
fn l_poly() -> String {
    let plc = l_prism();
    let mut s = format!("{} 3 0 0\n", plc.points.len());
    for (i, p) in plc.points.iter().enumerate() {
        s += &format!("{} {} {} {}\n", i + 1, p[0], p[1], p[2]);
    }
    s += &format!("{} 1\n", plc.facets.len());
    for f in &plc.facets {
        let poly = &f.polygons[0];
        s += &format!("1 0 {}\n{}", f.marker, poly.len());
        for v in poly {
            s += &format!(" {}", v + 1);
        }
        s += "\n";
    }
    s + "0\n0\n"
}

#[test]
fn cli_reads_var_files_and_c_fills_the_hull() {
    let d = cli_common::workdir("tetgen-constraints", &[]);
    std::fs::write(d.join("l.poly"), l_poly()).unwrap();
    // Facet marker 1: area 0.02; the segment from point 3 to 2 (1-based): length 0.07.
    std::fs::write(
        d.join("l.var"),
        "# facets\n1\n1 1 0.02\n# segments\n1\n1 3 2 0.07\n",
    )
    .unwrap();
    let read = |f: &str| std::fs::read_to_string(d.join(f)).unwrap();
    let faces_of = |stem: &str| {
        let node = idmesh::io::tetgen::parse_node(&read(&format!("{stem}.node")), "n").unwrap();
        let f = idmesh::io::tetgen::parse_face(
            &read(&format!("{stem}.face")),
            "f",
            node.base,
            node.plc.points.len(),
        )
        .unwrap();
        (node.plc.points, f.items, f.markers)
    };
    ok(&idmesh(&d, &["tetgen", "-pqQ", "l.poly"]));
    let (p, faces, markers) = faces_of("l.1");
    let bottom: Vec<f64> = faces
        .iter()
        .zip(&markers)
        .filter(|(_, &m)| m == 1)
        .map(|(f, _)| area(corners(&p, *f)))
        .collect();
    assert!(
        !bottom.is_empty() && bottom.iter().all(|&a| a <= 0.02),
        "{bottom:?}"
    );
    let piece = longest_piece(&p, &faces, [2.0, 0.0, 0.0], [2.0, 1.0, 0.0]);
    assert!(piece > 0.0 && piece <= 0.07, "{piece}");
    // As in TetGen, the constraints apply only when refining.
    ok(&idmesh(&d, &["tetgen", "-pQ", "l.poly"]));
    let (p, _, _) = faces_of("l.1");
    assert_eq!(p.len(), 12, "no Steiner points without -q");

    ok(&idmesh(&d, &["tetgen", "-pcQ", "l.poly"]));
    let node = idmesh::io::tetgen::parse_node(&read("l.1.node"), "n").unwrap();
    let ele = idmesh::io::tetgen::parse_ele(&read("l.1.ele"), "e", node.base, 12).unwrap();
    let vol: f64 = ele
        .tets
        .iter()
        .map(|t| tet_volume(t.map(|v| node.plc.points[v as usize])))
        .sum();
    assert!((vol - 3.5).abs() < 1e-12, "{vol}");

    std::fs::write(d.join("l.var"), "1\n1 1 -2\n").unwrap();
    let out = idmesh(&d, &["tetgen", "-pqQ", "l.poly"]);
    assert!(!out.status.success());
    let msg = String::from_utf8_lossy(&out.stderr);
    assert!(msg.contains("l.var") && msg.contains("positive"), "{msg}");
}
