//! Degenerate 3D inputs: cubes and grid-aligned boxes (every vertex set cospherical), boxes far
//! from the origin and at tiny scale, cylinders over regular polygons, lattices of input points
//! inside a cube and on its facets, and `delaunay3d` of lattices and cospherical point sets.
//! Each must terminate, validate and conform, judged by the independent checker in `common3d`.
//! The last tests corrupt meshes to show the checker does reject what it should.

mod common3d;

use std::time::Duration;

use common3d::{
    add_box, box_plc, check_delaunay, check_plc_mesh, check_point_mesh, mesh_and_check, prism_plc,
    regular_polygon, tetgen_positive, with_timeout, Cell, Domain, Frame, Spec3, P3,
};
use idmesh::{delaunay3d, Facet, Options3, Plc, TetMesh};

fn plain() -> Options3 {
    Options3::default()
}

fn quality(b: f64) -> Options3 {
    Options3 {
        radius_edge: Some(b),
        ..Options3::default()
    }
}

fn quality_volume(b: f64, v: f64) -> Options3 {
    Options3 {
        radius_edge: Some(b),
        max_volume: Some(v),
        ..Options3::default()
    }
}

fn box_spec(lo: P3, hi: P3) -> Spec3 {
    Spec3 {
        domain: Some(Domain {
            cells: vec![Cell::cuboid(lo, hi, 0.0)],
            frame: Frame::identity(),
        }),
        ..Spec3::default()
    }
}

/// Meshes and checks under each option set; panics with the checker's message.
fn run_all(plc: &Plc, spec: &Spec3, opts: &[Options3]) -> Vec<TetMesh> {
    opts.iter()
        .map(|o| match mesh_and_check(plc, o, spec) {
            Ok((m, _)) => m,
            Err(e) => panic!("{e}"),
        })
        .collect()
}

/// Checks a Delaunay tetrahedralization of `pts` (with a time limit).
fn delaunay_ok(pts: Vec<P3>) -> TetMesh {
    let p = pts.clone();
    let mesh = with_timeout(Duration::from_secs(60), move || delaunay3d(&p))
        .unwrap()
        .unwrap_or_else(|e| panic!("delaunay3d failed: {e}"));
    check_point_mesh(&pts, &mesh).unwrap();
    mesh
}

// ----------------------------------------------------------------------------------- cubes

#[test]
fn orientation_convention() {
    // det[b − a, c − a, d − a] = +1 for this tet: TetGen-positive, robust::orient3d negative.
    let t = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    assert!(common3d::orient(t[0], t[1], t[2], t[3]) < 0.0);
    assert!(tetgen_positive(t));
    assert!(common3d::tet_volume(t) > 0.0);
    assert!(!tetgen_positive([t[1], t[0], t[2], t[3]]));
    // And the mesher's tets follow it.
    let m = tetrahedralize_ok(&box_plc([0.0; 3], [1.0; 3]), &quality(2.0));
    for t in 0..m.tets.len() {
        assert!(tetgen_positive(m.corners(t)));
        assert!(common3d::tet_volume(m.corners(t)) > 0.0);
    }
}

fn tetrahedralize_ok(plc: &Plc, o: &Options3) -> TetMesh {
    idmesh::tetrahedralize(plc, o).unwrap()
}

#[test]
fn unit_cube() {
    let plc = box_plc([0.0; 3], [1.0; 3]);
    let spec = box_spec([0.0; 3], [1.0; 3]);
    let ms = run_all(
        &plc,
        &spec,
        &[
            plain(),
            quality(2.0),
            quality(1.414),
            quality_volume(1.414, 1.0 / 500.0),
        ],
    );
    // The plain cube needs no Steiner point: 8 cospherical vertices, 5 or 6 tets.
    assert_eq!(ms[0].vertices.len(), 8);
    assert!(ms[3].tets.len() >= 500);
}

#[test]
fn grid_aligned_box_3x2x1() {
    let (lo, hi) = ([0.0; 3], [3.0, 2.0, 1.0]);
    let plc = box_plc(lo, hi);
    let spec = box_spec(lo, hi);
    run_all(
        &plc,
        &spec,
        &[plain(), quality(1.414), quality_volume(1.414, 6.0 / 500.0)],
    );
}

#[test]
fn grid_aligned_stack_of_unit_cubes() {
    // Three unit cubes in a row sharing two facets: grid-aligned, every facet a unit square.
    let mut plc = Plc::default();
    for i in 0..3 {
        add_box(
            &mut plc,
            [i as f64, 0.0, 0.0],
            [i as f64 + 1.0, 1.0, 1.0],
            i + 1,
        );
    }
    // add_box made duplicate points and facets on the shared planes: merge them.
    let plc = merge_duplicates(&plc);
    let spec = box_spec([0.0; 3], [3.0, 1.0, 1.0]);
    run_all(&plc, &spec, &[plain(), quality(1.414)]);
}

/// Merges equal points and drops repeated facets (same vertex set); the first marker wins.
fn merge_duplicates(plc: &Plc) -> Plc {
    let mut out = Plc::default();
    let mut map = Vec::new();
    for p in &plc.points {
        let i = out.points.iter().position(|q| q == p).unwrap_or_else(|| {
            out.points.push(*p);
            out.points.len() - 1
        });
        map.push(i as u32);
    }
    let mut seen: Vec<Vec<u32>> = Vec::new();
    for f in &plc.facets {
        let polys: Vec<Vec<u32>> = f
            .polygons
            .iter()
            .map(|p| p.iter().map(|&v| map[v as usize]).collect())
            .collect();
        let mut key: Vec<u32> = polys.iter().flatten().copied().collect();
        key.sort_unstable();
        if seen.contains(&key) {
            continue;
        }
        seen.push(key);
        out.facets.push(Facet {
            polygons: polys,
            holes: f.holes.clone(),
            marker: f.marker,
        });
    }
    out
}

#[test]
fn box_far_from_origin() {
    let o = 1e6;
    let (lo, hi) = ([o, o, o], [o + 3.0, o + 2.0, o + 1.0]);
    let plc = box_plc(lo, hi);
    let spec = box_spec(lo, hi);
    run_all(
        &plc,
        &spec,
        &[plain(), quality(1.414), quality_volume(1.414, 6.0 / 500.0)],
    );
}

#[test]
fn box_at_tiny_scale() {
    let s = 1e-6;
    let (lo, hi) = ([0.0; 3], [3.0 * s, 2.0 * s, s]);
    let plc = box_plc(lo, hi);
    let spec = box_spec(lo, hi);
    let v = 3.0 * s * 2.0 * s * s;
    run_all(
        &plc,
        &spec,
        &[plain(), quality(1.414), quality_volume(1.414, v / 500.0)],
    );
}

/// Far below 2^-64 the exact insphere test underflows (3D campaign seed 3, run 6475: a cube of
/// 1e-54 came back with a vertex "inside" a tet's circumsphere); such inputs are meshed scaled
/// up by a power of two, and give the same mesh as the box at scale 1, scaled.
#[test]
fn box_at_underflow_scale() {
    // (The test harness's own exact checks underflow there too: `validate` is the check.) At
    // 2^-180 the run is exactly the run on the box 2^179 times larger, scaled back.
    let s = 2f64.powi(-180);
    let plc = box_plc([0.0; 3], [3.0 * s, 2.0 * s, s]);
    let big = box_plc([0.0; 3], [1.5, 1.0, 0.5]);
    let v = 1.5 * 0.5 / 500.0;
    for (opts, small) in [
        (plain(), plain()),
        (quality(1.414), quality(1.414)),
        (
            quality_volume(1.414, v),
            quality_volume(1.414, v * s * s * s * 8.0),
        ),
    ] {
        let a = idmesh::tetrahedralize(&plc, &small).unwrap();
        let b = idmesh::tetrahedralize(&big, &opts).unwrap();
        a.validate().unwrap();
        assert_eq!(a.tets.len(), b.tets.len());
        assert!(a.tets == b.tets);
        for (p, q) in a.vertices.iter().zip(&b.vertices) {
            assert_eq!(p.map(|x| x * 2f64.powi(179)), *q);
        }
    }
}

#[test]
fn box_at_tiny_scale_far_from_origin() {
    let (o, s) = (1.0, 1e-6);
    let (lo, hi) = ([o, o, o], [o + 3.0 * s, o + 2.0 * s, o + s]);
    let plc = box_plc(lo, hi);
    let spec = box_spec(lo, hi);
    run_all(&plc, &spec, &[plain(), quality(2.0)]);
}

// ------------------------------------------------------------------------------- cylinders

fn cylinder(n: usize) {
    let poly = regular_polygon(n, 1.0);
    let h = 1.5;
    let plc = prism_plc(&poly, None, 0.0, h, &Frame::identity());
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![Cell {
                outer: poly.clone(),
                holes: vec![],
                z0: 0.0,
                z1: h,
                attribute: 0.0,
            }],
            frame: Frame::identity(),
        }),
        ..Spec3::default()
    };
    // Dihedral angles are 90 degrees (top/bottom with the sides) and 180 − 360/n between sides:
    // no small input angle, so the bounds hold everywhere.
    run_all(&plc, &spec, &[plain(), quality(2.0), quality(1.414)]);
}

/// The cylinder with radius-edge 1.414 and a volume bound of a 500th of its volume.
fn cylinder_volume(n: usize) {
    let poly = regular_polygon(n, 1.0);
    let h = 1.5;
    let plc = prism_plc(&poly, None, 0.0, h, &Frame::identity());
    let dom = Domain {
        cells: vec![Cell {
            outer: poly.clone(),
            holes: vec![],
            z0: 0.0,
            z1: h,
            attribute: 0.0,
        }],
        frame: Frame::identity(),
    };
    let v = dom.volume();
    let spec = Spec3 {
        domain: Some(dom),
        timeout: Duration::from_secs(30),
        ..Spec3::default()
    };
    let opts = Options3 {
        max_steiner: Some(200_000),
        ..quality_volume(1.414, v / 500.0)
    };
    run_all(&plc, &spec, &[opts]);
}

#[test]
fn cylinder_8_quality_volume() {
    cylinder_volume(8);
}

#[test]
fn cylinder_16_quality_volume() {
    cylinder_volume(16);
}

#[test]
fn cylinder_8() {
    cylinder(8);
}

#[test]
fn cylinder_16() {
    cylinder(16);
}

#[test]
fn cylinder_32() {
    cylinder(32);
}

#[test]
fn cylinder_64() {
    cylinder(64);
}

#[test]
fn cylindrical_tube_16_with_hole_8() {
    let outer = regular_polygon(16, 2.0);
    let hole = regular_polygon(8, 1.0);
    let plc = prism_plc(
        &outer,
        Some((&hole, [0.0, 0.0])),
        0.0,
        1.0,
        &Frame::identity(),
    );
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![Cell {
                outer,
                holes: vec![hole],
                z0: 0.0,
                z1: 1.0,
                attribute: 0.0,
            }],
            frame: Frame::identity(),
        }),
        ..Spec3::default()
    };
    run_all(&plc, &spec, &[plain(), quality(2.0), quality(1.414)]);
}

// ------------------------------------------------------------------------- lattice inputs

#[test]
fn cube_with_interior_lattice() {
    // A 6-cube with the 5×5×5 integer points inside it as input points: every unit cell of the
    // lattice has 8 cospherical vertices.
    let k = 6.0;
    let mut plc = box_plc([0.0; 3], [k; 3]);
    for i in 1..6 {
        for j in 1..6 {
            for l in 1..6 {
                plc.points.push([i as f64, j as f64, l as f64]);
            }
        }
    }
    let spec = box_spec([0.0; 3], [k; 3]);
    run_all(&plc, &spec, &[plain(), quality(2.0), quality(1.414)]);
}

/// The lattice points on the surface of `[0, k]³` and the cube's facets through them: each facet
/// is the loop of its boundary lattice points and its interior lattice points as 1-vertex
/// polygons.
fn cube_with_facet_lattice(k: i32) -> Plc {
    let mut plc = Plc::default();
    let mut index = std::collections::HashMap::new();
    let mut id = |plc: &mut Plc, p: [i32; 3]| -> u32 {
        *index.entry(p).or_insert_with(|| {
            plc.points.push(p.map(f64::from));
            plc.points.len() as u32 - 1
        })
    };
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [0, k] {
            let at = |a: i32, b: i32| {
                let mut p = [0; 3];
                p[axis] = side;
                p[u] = a;
                p[v] = b;
                p
            };
            let mut ring = Vec::new();
            for a in 0..k {
                ring.push(at(a, 0));
            }
            for b in 0..k {
                ring.push(at(k, b));
            }
            for a in (1..=k).rev() {
                ring.push(at(a, k));
            }
            for b in (1..=k).rev() {
                ring.push(at(0, b));
            }
            let mut polygons = vec![ring.iter().map(|&p| id(&mut plc, p)).collect::<Vec<_>>()];
            for a in 1..k {
                for b in 1..k {
                    polygons.push(vec![id(&mut plc, at(a, b))]);
                }
            }
            plc.facets.push(Facet {
                polygons,
                holes: vec![],
                marker: 1 + axis as i32,
            });
        }
    }
    plc
}

#[test]
fn cube_with_facet_lattice_4() {
    let plc = cube_with_facet_lattice(4);
    assert_eq!(plc.points.len(), 6 * 9 + 12 * 3 + 8);
    let spec = box_spec([0.0; 3], [4.0; 3]);
    run_all(&plc, &spec, &[plain(), quality(2.0), quality(1.414)]);
}

#[test]
fn cube_with_facet_and_interior_lattice_3() {
    let mut plc = cube_with_facet_lattice(3);
    for i in 1..3 {
        for j in 1..3 {
            for l in 1..3 {
                plc.points.push([i as f64, j as f64, l as f64]);
            }
        }
    }
    let spec = box_spec([0.0; 3], [3.0; 3]);
    run_all(
        &plc,
        &spec,
        &[plain(), quality(1.414), quality_volume(1.414, 27.0 / 500.0)],
    );
}

// ------------------------------------------------------------------------------ delaunay3d

#[test]
fn delaunay_lattice_6() {
    let mut pts = Vec::new();
    for i in 0..6 {
        for j in 0..6 {
            for l in 0..6 {
                pts.push([i as f64, j as f64, l as f64]);
            }
        }
    }
    let m = delaunay_ok(pts);
    assert!(
        (common3d::sum_compensated(
            (0..m.tets.len()).map(|t| { common3d::tet_volume(m.corners(t)) })
        ) - 125.0)
            .abs()
            < 1e-9 * 125.0
    );
}

#[test]
fn delaunay_exactly_cospherical_integer_points() {
    // Every integer point at distance 13 from the origin (all exactly cospherical) and the
    // centre.
    let mut pts = vec![[0.0; 3]];
    for x in -13i32..=13 {
        for y in -13i32..=13 {
            for z in -13i32..=13 {
                if x * x + y * y + z * z == 169 {
                    pts.push([x, y, z].map(f64::from));
                }
            }
        }
    }
    assert!(pts.len() > 50, "{} points", pts.len());
    delaunay_ok(pts.clone());
    // Without the centre: every tet has all its neighbours' apexes on its circumsphere.
    delaunay_ok(pts[1..].to_vec());
}

#[test]
fn delaunay_nearly_cospherical_points() {
    // A Fibonacci sphere (rounded: nearly, not exactly, cospherical) plus two concentric copies.
    let n = 300;
    let mut pts = Vec::new();
    for r in [1.0, 0.5, 1e-3] {
        for i in 0..n {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
            let rho = (1.0 - z * z).sqrt();
            let a = i as f64 * 2.399_963_229_728_653;
            pts.push([r * rho * a.cos(), r * rho * a.sin(), r * z]);
        }
    }
    delaunay_ok(pts);
}

#[test]
fn delaunay_cube_corners_and_lattice_offset() {
    // A 4×4×4 lattice far from the origin.
    let o = 1e6;
    let mut pts = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            for l in 0..4 {
                pts.push([o + i as f64, o + j as f64, o + l as f64]);
            }
        }
    }
    delaunay_ok(pts);
}

// ------------------------------------------------------------- minimal reproducers of bugs
//
// The smallest inputs found by shrinking the failing properties of prop3d.rs. Each asserts what
// must hold and is ignored while the bug stands.

/// A PLC from literal points and single-loop facets (marker 1 unless given).
fn literal_plc(points: &[P3], facets: &[(&[u32], i32)]) -> Plc {
    Plc {
        points: points.to_vec(),
        facets: facets
            .iter()
            .map(|(p, m)| Facet {
                polygons: vec![p.to_vec()],
                holes: vec![],
                marker: *m,
            })
            .collect(),
        ..Plc::default()
    }
}

/// The six facets of a box whose corners are numbered as `add_box` numbers them.
const BOX_FACETS: [(&[u32], i32); 6] = [
    (&[0, 1, 3, 2], 1),
    (&[4, 5, 7, 6], 1),
    (&[0, 1, 5, 4], 1),
    (&[2, 3, 7, 6], 1),
    (&[0, 2, 6, 4], 1),
    (&[1, 3, 7, 5], 1),
];

#[test]
fn bug_a_rotated_cube_quality_volume_completes() {
    // The unit cube under the exact 3-4-5 rotation about z, scaled by 5/4.
    let points = [
        [0.0, 0.0, 0.0],
        [0.75, 1.0, 0.0],
        [-1.0, 0.75, 0.0],
        [-0.25, 1.75, 0.0],
        [0.0, 0.0, 1.25],
        [0.75, 1.0, 1.25],
        [-1.0, 0.75, 1.25],
        [-0.25, 1.75, 1.25],
    ];
    let plc = literal_plc(&points, &BOX_FACETS);
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![Cell::cuboid([0.0; 3], [1.0; 3], 0.0)],
            frame: Frame::quaternion(2, 0, 0, 1),
        }),
        timeout: Duration::from_secs(30),
        ..Spec3::default()
    };
    assert_eq!(spec.domain.as_ref().unwrap().volume(), 1.953125);
    let opts = Options3 {
        max_steiner: Some(20_000),
        ..quality_volume(1.414, 1.953125 / 500.0)
    };
    run_all(&plc, &spec, &[opts]);
}

#[test]
fn bug_a_triangular_prism_quality_volume_completes() {
    let tri = [[0.59375, 0.0], [-0.296875, 0.515625], [-0.671875, -1.3125]];
    let plc = prism_plc(&tri, None, 0.0, 1.8125, &Frame::identity());
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![Cell {
                outer: tri.to_vec(),
                holes: vec![],
                z0: 0.0,
                z1: 1.8125,
                attribute: 0.0,
            }],
            frame: Frame::identity(),
        }),
        // The triangle has angles below 90 degrees: only completion and validity are asserted.
        check_quality: false,
        timeout: Duration::from_secs(30),
        ..Spec3::default()
    };
    let opts = Options3 {
        max_steiner: Some(20_000),
        ..quality_volume(1.414, 0.0033015289306640625)
    };
    let m = run_all(&plc, &spec, &[opts]);
    assert!(m[0].complete, "refinement did not complete");
}

#[test]
fn bug_b_no_flat_tet_on_rotated_facet() {
    let points = [
        [0.5234375, 0.947265625, 0.724609375],
        [2.095703125, 0.810546875, -0.232421875],
        [0.515625, 1.048828125, 0.697265625],
        [2.087890625, 0.912109375, -0.259765625],
        [0.9609375, 1.166015625, 1.412109375],
        [2.533203125, 1.029296875, 0.455078125],
        [0.953125, 1.267578125, 1.384765625],
        [2.525390625, 1.130859375, 0.427734375],
    ];
    let plc = literal_plc(&points, &BOX_FACETS);
    let frame = Frame::quaternion(7, -1, 2, 0);
    let (lo, hi) = ([0.0, 0.8125, 1.3125], [2.1875, 0.9375, 2.3125]);
    for (i, p) in points.iter().enumerate() {
        let l = [0, 1, 2].map(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] });
        assert_eq!(frame.apply(l), *p);
    }
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![Cell::cuboid(lo, hi, 0.0)],
            frame,
        }),
        ..Spec3::default()
    };
    run_all(&plc, &spec, &[quality(2.0)]);
}

/// Two boxes: `[0, 1]² × [0, 0.5]` and `[0.125, 0.875]² × [0.5, 1]` on a shared facet, the
/// lower top a ring facet; regions with attributes 1 and 2.
fn inset_stack() -> (Plc, Spec3) {
    let mut plc = Plc::default();
    for (x0, x1, z) in [
        (0.0, 1.0, 0.0),
        (0.0, 1.0, 0.5),
        (0.125, 0.875, 0.5),
        (0.125, 0.875, 1.0),
    ] {
        for (x, y) in [(x0, x0), (x1, x0), (x1, x1), (x0, x1)] {
            plc.points.push([x, y, z]);
        }
    }
    let quad = |a: u32, b: u32, c: u32, d: u32| vec![a, b, c, d];
    let mut f = |polygons: Vec<Vec<u32>>, holes: Vec<P3>, marker: i32| {
        plc.facets.push(Facet {
            polygons,
            holes,
            marker,
        })
    };
    f(vec![quad(0, 1, 2, 3)], vec![], 1);
    for i in 0..4 {
        let j = (i + 1) % 4;
        f(vec![quad(i, j, 4 + j, 4 + i)], vec![], 2);
        f(vec![quad(8 + i, 8 + j, 12 + j, 12 + i)], vec![], 5);
    }
    f(
        vec![quad(4, 5, 6, 7), quad(8, 9, 10, 11)],
        vec![[0.5, 0.5, 0.5]],
        3,
    );
    f(vec![quad(8, 9, 10, 11)], vec![], 4);
    f(vec![quad(12, 13, 14, 15)], vec![], 6);
    for (z, a) in [(0.25, 1.0), (0.75, 2.0)] {
        plc.regions.push(idmesh::Region3 {
            point: [0.5, 0.5, z],
            attribute: a,
            max_volume: None,
        });
    }
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![
                Cell::cuboid([0.0; 3], [1.0, 1.0, 0.5], 1.0),
                Cell::cuboid([0.125, 0.125, 0.5], [0.875, 0.875, 1.0], 2.0),
            ],
            frame: Frame::identity(),
        }),
        ..Spec3::default()
    };
    (plc, spec)
}

#[test]
fn inset_stack_plain() {
    let (plc, spec) = inset_stack();
    let o = Options3 {
        region_attributes: true,
        ..plain()
    };
    run_all(&plc, &spec, &[o]);
}

#[test]
fn bug_c_inset_stack_meets_radius_edge_2() {
    let (plc, spec) = inset_stack();
    let o = Options3 {
        region_attributes: true,
        ..quality(2.0)
    };
    run_all(&plc, &spec, &[o]);
}

#[test]
fn bug_d_rotated_split_box_meets_radius_edge_2() {
    // The box [0, 2] × [0, 2.4375] × [0, 2.5] split at x = 0.375, rotated by the quaternion
    // (9, -1, 0, -1) and divided by 64 (exact).
    let frame = Frame::quaternion(9, -1, 0, -1);
    let (ax, ay, az, xt) = (2.0, 2.4375, 2.5, 0.375);
    let mut points = Vec::new();
    for x in [0.0, xt, ax] {
        for (y, z) in [(0.0, 0.0), (ay, 0.0), (ay, az), (0.0, az)] {
            points.push(frame.apply([x, y, z]));
        }
    }
    let facets: Vec<(Vec<u32>, i32)> = vec![
        (vec![0, 1, 2, 3], 1),
        (vec![8, 9, 10, 11], 2),
        (vec![4, 5, 6, 7], 7),
        (vec![0, 4, 5, 1], 3),
        (vec![4, 8, 9, 5], 3),
        (vec![1, 5, 6, 2], 3),
        (vec![5, 9, 10, 6], 3),
        (vec![2, 6, 7, 3], 3),
        (vec![6, 10, 11, 7], 3),
        (vec![3, 7, 4, 0], 3),
        (vec![7, 11, 8, 4], 3),
    ];
    let f: Vec<(&[u32], i32)> = facets.iter().map(|(p, m)| (p.as_slice(), *m)).collect();
    let mut plc = literal_plc(&points, &f);
    for (x, a) in [(0.5 * xt, 3.0), (0.5 * (xt + ax), 4.0)] {
        plc.regions.push(idmesh::Region3 {
            point: frame.apply([x, 0.5 * ay, 0.5 * az]),
            attribute: a,
            max_volume: None,
        });
    }
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![
                Cell::cuboid([0.0; 3], [xt, ay, az], 3.0),
                Cell::cuboid([xt, 0.0, 0.0], [ax, ay, az], 4.0),
            ],
            frame,
        }),
        ..Spec3::default()
    };
    let o = Options3 {
        region_attributes: true,
        ..quality(2.0)
    };
    run_all(&plc, &spec, &[o]);
}

#[test]
fn bug_e_rotated_stacked_boxes_no_panic() {
    // Boxes [0, 1]² × [0, 0.5] and [0, 1]² × [0.5, 1.625] (sharing the facet z = 0.5), rotated
    // by the quaternion (6, 0, 0, 1) and divided by 32 (exact).
    let frame = Frame::quaternion(6, 0, 0, 1);
    let mut points = Vec::new();
    for z in [0.0, 0.5, 1.625] {
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            points.push(frame.apply([x, y, z]));
        }
    }
    assert_eq!(points[10], [0.71875, 1.46875, 1.87890625]);
    let mut facets: Vec<(Vec<u32>, i32)> = vec![(vec![0, 1, 2, 3], 1), (vec![4, 5, 6, 7], 4)];
    for i in 0..4u32 {
        let j = (i + 1) % 4;
        facets.push((vec![i, j, 4 + j, 4 + i], 2));
        facets.push((vec![4 + i, 4 + j, 8 + j, 8 + i], 5));
    }
    facets.push((vec![8, 9, 10, 11], 6));
    let f: Vec<(&[u32], i32)> = facets.iter().map(|(p, m)| (p.as_slice(), *m)).collect();
    let mut plc = literal_plc(&points, &f);
    for (z, a) in [(0.25, 1.0), (1.0625, 2.0)] {
        plc.regions.push(idmesh::Region3 {
            point: frame.apply([0.5, 0.5, z]),
            attribute: a,
            max_volume: None,
        });
    }
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![
                Cell::cuboid([0.0; 3], [1.0, 1.0, 0.5], 1.0),
                Cell::cuboid([0.0, 0.0, 0.5], [1.0, 1.0, 1.625], 2.0),
            ],
            frame,
        }),
        timeout: Duration::from_secs(30),
        ..Spec3::default()
    };
    let o = Options3 {
        region_attributes: true,
        max_steiner: Some(200_000),
        ..quality_volume(1.414, 0.0050238723754882815)
    };
    run_all(&plc, &spec, &[o]);
}

#[test]
fn bug_f_prism_with_thin_hole_radius_edge_2() {
    // Found by prism_rotated_q2 (a rotation about z by the quaternion (6, 0, 0, -1), so the
    // top and bottom stay horizontal); written here in the rotated frame.
    let outer = [
        [0.6494140625, -0.22265625],
        [-0.333984375, 1.69970703125],
        [-1.33544921875, -1.16552734375],
    ];
    let hole = [
        [0.0341796875, -0.01171875],
        [0.01171875, 0.0341796875],
        [-0.0341796875, 0.01171875],
        [-0.017578125, -0.05126953125],
    ];
    let h = 1.373046875;
    let plc = prism_plc(
        &outer,
        Some((&hole, [0.0, 0.0])),
        0.0,
        h,
        &Frame::identity(),
    );
    assert_eq!(plc.points.len(), 14);
    let spec = Spec3 {
        domain: Some(Domain {
            cells: vec![Cell {
                outer: outer.to_vec(),
                holes: vec![hole.to_vec()],
                z0: 0.0,
                z1: h,
                attribute: 0.0,
            }],
            frame: Frame::identity(),
        }),
        // The triangle's angles are below 90 degrees: validity and conformity only.
        check_quality: false,
        timeout: Duration::from_secs(30),
        ..Spec3::default()
    };
    run_all(&plc, &spec, &[quality(2.0)]);
}

/// The star of one vertex of a CAD-like surface model (its six surface triangles, coordinates
/// as in that model) closed by an apex below it. Two edges of one triangle meet at the vertex
/// at 30.1°.
fn fandisk_wedge_plc() -> Plc {
    let points = [
        [-0.001, -0.17341, 0.47099],
        [0.0026, -0.17658, 0.45306],
        [0.0026, -0.15798, 0.44983],
        [-0.0011, -0.15485, 0.4682],
        [-0.0113, -0.17074, 0.48622],
        [-0.0231, -0.17257, 0.47577],
        [-0.0204, -0.17449, 0.46489],
        [-0.02246, -0.15528, 0.46047],
    ];
    let facets: [(&[u32], i32); 12] = [
        (&[1, 2, 0], 1),
        (&[1, 0, 6], 1),
        (&[2, 3, 0], 1),
        (&[0, 3, 4], 1),
        (&[0, 4, 5], 1),
        (&[0, 5, 6], 1),
        (&[2, 1, 7], 2),
        (&[3, 2, 7], 2),
        (&[4, 3, 7], 2),
        (&[5, 4, 7], 2),
        (&[6, 5, 7], 2),
        (&[1, 6, 7], 2),
    ];
    literal_plc(&points, &facets)
}

#[test]
fn bug_g_narrow_wedge_in_a_facet_does_not_cascade() {
    // Was (that surface model, -pq1.2): no end without a volume bound, "facet point refused" with
    // one. With the bound 1.2, the tet of vertex 0 and three split points at one distance from
    // it on its edges (two of them the 30.1° wedge) has radius-edge ratio 1.38 at every scale;
    // its circumcentre encroaches the wedge subface, whose split encroaches the wedge
    // subsegments: the same tet came back at half the size until precision ran out. Such a
    // vertex is sharp for that bound (its tets are exempt), so refinement stays at the scale of
    // the input.
    let plc = fandisk_wedge_plc();
    let volume = {
        let o = plc.points[0];
        let parts = plc.facets.iter().map(|f| {
            let p = &f.polygons[0];
            common3d::tet_volume([
                o,
                plc.points[p[0] as usize],
                plc.points[p[1] as usize],
                plc.points[p[2] as usize],
            ])
        });
        common3d::sum_compensated(parts).abs()
    };
    let spec = Spec3 {
        volume: Some(volume),
        // Small angles (the wedge, the apex below): validity and conformity only.
        check_quality: false,
        timeout: Duration::from_secs(30),
        ..Spec3::default()
    };
    let shortest_input = common3d::input_edges(&plc)
        .iter()
        .map(|e| {
            common3d::norm(common3d::sub(
                plc.points[e[0] as usize],
                plc.points[e[1] as usize],
            ))
        })
        .fold(f64::INFINITY, f64::min);
    for mesh in run_all(&plc, &spec, &[quality(1.2), quality_volume(1.2, 1e-8)]) {
        assert!(mesh.complete, "refinement did not complete");
        let mut shortest = f64::INFINITY;
        for t in 0..mesh.tets.len() {
            let c = mesh.corners(t);
            for i in 0..4 {
                for j in i + 1..4 {
                    shortest = shortest.min(common3d::norm(common3d::sub(c[i], c[j])));
                }
            }
        }
        assert!(
            shortest > shortest_input / 64.0,
            "an edge of {shortest} next to input edges of {shortest_input} and more"
        );
    }
}

// ------------------------------------------------------------------ the checker can fail

#[test]
fn checker_rejects_corrupted_meshes() {
    let (lo, hi) = ([0.0; 3], [2.0, 1.0, 1.0]);
    let plc = box_plc(lo, hi);
    let opts = quality_volume(1.414, 2.0 / 100.0);
    let spec = box_spec(lo, hi);
    let (mesh, rep) = mesh_and_check(&plc, &opts, &spec).unwrap();
    assert!(rep.steiner > 0 && rep.tets > 100);
    let reject = |m: &TetMesh, o: &Options3, s: &Spec3, what: &str| {
        let r = check_plc_mesh(&plc, o, m, s);
        assert!(r.is_err(), "checker accepted: {what}");
        r.unwrap_err()
    };
    // A moved input vertex.
    let mut m = mesh.clone();
    m.vertices[3][0] += 1e-9;
    reject(&m, &opts, &spec, "moved input vertex");
    // A Steiner vertex moved by a little (it stays valid for orientation, but breaks Delaunay,
    // conformity or volume).
    let mut m = mesh.clone();
    let v = (8..m.vertices.len())
        .find(|&v| m.vertices[v][2] == 0.0 && m.vertices[v][0] > 0.0 && m.vertices[v][0] < 2.0)
        .expect("a Steiner vertex on the bottom facet");
    m.vertices[v][2] = 1e-7;
    reject(&m, &opts, &spec, "Steiner vertex lifted off its facet");
    // A dropped tet.
    let mut m = mesh.clone();
    m.tets.pop();
    m.neighbors.pop();
    reject(&m, &opts, &spec, "dropped tet");
    // A dropped tet with the neighbours patched (so only volume and conformity see it).
    let mut m = mesh.clone();
    let last = m.tets.len() as u32 - 1;
    m.tets.pop();
    m.neighbors.pop();
    for row in &mut m.neighbors {
        for n in row.iter_mut() {
            if *n == last {
                *n = u32::MAX;
            }
        }
    }
    let e = reject(&m, &opts, &spec, "dropped tet, neighbours patched");
    assert!(
        e.contains("volume") || e.contains("subface") || e.contains("cover"),
        "{e}"
    );
    // An inverted tet.
    let mut m = mesh.clone();
    m.tets[0].swap(0, 1);
    let e = reject(&m, &opts, &spec, "inverted tet");
    assert!(e.contains("positively oriented"), "{e}");
    // A missing subface and a missing subsegment.
    let mut m = mesh.clone();
    m.faces.pop();
    m.face_markers.pop();
    reject(&m, &opts, &spec, "missing subface");
    let mut m = mesh.clone();
    m.edges.pop();
    m.edge_markers.pop();
    let e = reject(&m, &opts, &spec, "missing subsegment");
    assert!(e.contains("subsegment"), "{e}");
    // A wrong marker on a subface.
    let mut m = mesh.clone();
    m.face_markers[0] += 7;
    reject(&m, &opts, &spec, "wrong subface marker");
    // A facet the mesh was not made to conform to: the diagonal rectangle through the edges
    // 0-4 and 3-7 (the checker reads facets from the PLC it is given).
    let mut diag = plc.clone();
    diag.facets.push(Facet {
        polygons: vec![vec![0, 3, 7, 4]],
        holes: vec![],
        marker: 9,
    });
    let r = check_plc_mesh(&diag, &opts, &mesh, &spec);
    let e = r.expect_err("checker accepted: a facet the mesh does not conform to");
    assert!(e.contains("facet 6") || e.contains("input edge"), "{e}");
    // The wrong volume, a hole where the mesh has tets, a bound the mesh does not meet.
    let wrong = box_spec(lo, [2.0, 1.0, 1.0 + 1e-6]);
    let e = reject(&mesh, &opts, &wrong, "wrong volume");
    assert!(e.contains("volume"), "{e}");
    let holed = Spec3 {
        domain: Some(Domain {
            cells: vec![Cell {
                holes: vec![vec![[0.5, 0.25], [1.5, 0.25], [1.5, 0.75], [0.5, 0.75]]],
                ..Cell::cuboid(lo, hi, 0.0)
            }],
            frame: Frame::identity(),
        }),
        volume: None,
        ..Spec3::default()
    };
    reject(&mesh, &opts, &holed, "tets in a hole");
    // (The mesh is good: its worst ratio may be below 1.0; ask for a bit less than it.)
    assert!(rep.max_radius_edge > 0.7);
    let e = reject(
        &mesh,
        &quality(rep.max_radius_edge * 0.999),
        &spec,
        "radius-edge below the mesh's worst",
    );
    assert!(e.contains("radius-edge"), "{e}");
    let e = reject(&mesh, &quality_volume(1.414, 1e-4), &spec, "max volume");
    assert!(e.contains("volume"), "{e}");
    // Attributes asked for but absent.
    let attr = Options3 {
        region_attributes: true,
        ..opts.clone()
    };
    let two = Spec3 {
        domain: Some(Domain {
            cells: vec![Cell::cuboid(lo, hi, 5.0)],
            frame: Frame::identity(),
        }),
        ..Spec3::default()
    };
    reject(&mesh, &attr, &two, "missing attributes");
}

#[test]
fn delaunay_checker_rejects_a_non_delaunay_pair() {
    // Two tets on the face (a, b, c); the apex e of the second is inside the first's
    // circumsphere (a flat pair: d and e close to the plane of a, b, c).
    let a = [0.0, 0.0, 0.0];
    let b = [1.0, 0.0, 0.0];
    let c = [0.0, 1.0, 0.0];
    let d = [0.2, 0.2, 1.0];
    let e = [0.2, 0.2, -0.1];
    let mut m = TetMesh {
        vertices: vec![a, b, c, d, e],
        vertex_markers: vec![0; 5],
        num_input_vertices: 5,
        tets: vec![[0, 1, 2, 3], [1, 0, 2, 4]],
        neighbors: vec![
            [u32::MAX, u32::MAX, u32::MAX, 1],
            [u32::MAX, u32::MAX, u32::MAX, 0],
        ],
        complete: true,
        ..TetMesh::default()
    };
    for t in 0..2 {
        assert!(tetgen_positive(m.corners(t)), "tet {t}");
    }
    let err = check_delaunay(&m).unwrap_err();
    assert!(err.contains("not Delaunay"), "{err}");
    // With e far below, the pair is Delaunay.
    m.vertices[4] = [0.2, 0.2, -10.0];
    check_delaunay(&m).unwrap();
    // The pair's union is convex (de crosses the triangle abc): a valid tetrahedralization of
    // its five points, which check_point_mesh accepts; with e moved so that de misses abc the
    // union is not convex, still Delaunay, and it must be rejected as not the hull.
    m.faces = vec![
        [0, 1, 3],
        [1, 2, 3],
        [0, 2, 3],
        [0, 1, 4],
        [1, 2, 4],
        [0, 2, 4],
    ];
    m.face_markers = vec![0; 6];
    check_point_mesh(&m.vertices.clone(), &m).unwrap();
    m.vertices[4] = [3.0, 3.0, -0.5];
    assert!(tetgen_positive(m.corners(1)));
    check_delaunay(&m).unwrap();
    let err = check_point_mesh(&m.vertices.clone(), &m).unwrap_err();
    assert!(err.contains("not convex"), "{err}");
}
