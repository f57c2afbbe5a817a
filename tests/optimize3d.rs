//! Mesh optimisation (TetGen's `-O` and `-o/<angle>`, `src/mesh3d/optimize.rs`): on boxes,
//! two boxes stacked as two regions (an internal facet), a cylinder and a box with a free
//! internal segment, meshed with and without sliver removal, the optimised mesh must have a
//! smallest dihedral angle no smaller and a largest no larger than the Delaunay mesh's, the
//! same vertices (input and boundary ones in place, none added or removed), the same subfaces
//! and subsegments, the same volume per region, and pass the exact `validate()` (without the
//! empty circumspheres: it is marked `optimized`). Bad levels, schemes and angles are refused
//! by name, by the library and on the command line.

mod cli_common;
mod common3d;

use common3d::{box_plc, prism_plc, regular_polygon, Frame};
use idmesh::{tetrahedralize, Error, Options3, Plc, Region3, TetMesh};

fn opts(volume: f64, min_dihedral: Option<f64>, level: u32) -> Options3 {
    Options3 {
        radius_edge: Some(1.414),
        max_volume: Some(volume),
        min_dihedral,
        region_attributes: true,
        optimize_level: level,
        max_steiner: Some(100_000),
        ..Options3::default()
    }
}

/// Volume per regional attribute, sorted by attribute.
fn region_volumes(m: &TetMesh) -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = Vec::new();
    for t in 0..m.tets.len() {
        let a = m.tet_attributes[t];
        let vol = idmesh::geometry::tet_volume(m.corners(t));
        match v.iter_mut().find(|(b, _)| *b == a) {
            Some(e) => e.1 += vol,
            None => v.push((a, vol)),
        }
    }
    v.sort_by(|x, y| x.0.total_cmp(&y.0));
    v
}

fn sorted<T: Ord + Clone>(v: &[T]) -> Vec<T> {
    let mut v = v.to_vec();
    v.sort();
    v
}

/// Meshes `plc` without and with optimisation and checks what optimisation must keep. Returns
/// whether it changed the mesh.
fn check(name: &str, plc: &Plc, volume: f64, min_dihedral: Option<f64>, level: u32) -> bool {
    let plain = tetrahedralize(plc, &opts(volume, min_dihedral, 0)).unwrap();
    assert!(
        !plain.optimized,
        "{name}: without -O the mesh stays Delaunay"
    );
    plain.validate().unwrap();
    let opt = tetrahedralize(plc, &opts(volume, min_dihedral, level)).unwrap();
    opt.validate()
        .unwrap_or_else(|e| panic!("{name} -O{level}: {e}"));
    let (s0, s1) = (plain.stats(), opt.stats());
    assert!(
        s1.min_dihedral >= s0.min_dihedral && s1.max_dihedral <= s0.max_dihedral,
        "{name} -O{level}: dihedral angles {}..{} became {}..{}",
        s0.min_dihedral,
        s0.max_dihedral,
        s1.min_dihedral,
        s1.max_dihedral
    );
    assert_eq!(opt.num_input_vertices, plc.points.len(), "{name}");
    assert_eq!(opt.vertices.len(), plain.vertices.len(), "{name}");
    assert_eq!(
        &opt.vertices[..plc.points.len()],
        &plc.points[..],
        "{name}: input vertices moved"
    );
    // Vertices on subfaces and subsegments stay where they were.
    for &v in plain
        .faces
        .iter()
        .flatten()
        .chain(plain.edges.iter().flatten())
    {
        assert_eq!(
            opt.vertices[v as usize], plain.vertices[v as usize],
            "{name}: boundary vertex {v} moved"
        );
    }
    assert_eq!(sorted(&opt.faces), sorted(&plain.faces), "{name}: subfaces");
    assert_eq!(
        sorted(&opt.edges),
        sorted(&plain.edges),
        "{name}: subsegments"
    );
    let (r0, r1) = (region_volumes(&plain), region_volumes(&opt));
    assert_eq!(r0.len(), r1.len(), "{name}: regions");
    for ((a0, v0), (a1, v1)) in r0.iter().zip(&r1) {
        assert_eq!(a0, a1, "{name}");
        assert!(
            (v0 - v1).abs() <= 1e-9 * v0.abs(),
            "{name}: region {a0} volume {v0} became {v1}"
        );
    }
    let changed = opt != plain;
    assert_eq!(opt.optimized, changed, "{name}: optimized flag");
    changed
}

fn stacked_boxes() -> Plc {
    // Corners (x, y) of the unit square at z = 0, 1, 2: point 4 z + k.
    let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut plc = Plc::default();
    for z in 0..3 {
        for c in sq {
            plc.points.push([c[0], c[1], z as f64]);
        }
    }
    let facet = |v: Vec<u32>, marker: i32| idmesh::Facet {
        polygons: vec![v],
        holes: vec![],
        marker,
    };
    for z in 0..3u32 {
        // Bottom, the internal square between the regions, top.
        plc.facets
            .push(facet((0..4).map(|k| 4 * z + k).collect(), 1 + z as i32));
    }
    for z in 0..2u32 {
        for k in 0..4u32 {
            let (a, b) = (4 * z + k, 4 * z + (k + 1) % 4);
            plc.facets.push(facet(vec![a, b, b + 4, a + 4], 4));
        }
    }
    plc.regions = vec![
        Region3 {
            point: [0.5, 0.5, 0.5],
            attribute: 1.0,
            max_volume: None,
        },
        Region3 {
            point: [0.5, 0.5, 1.5],
            attribute: 2.0,
            max_volume: None,
        },
    ];
    plc
}

#[test]
fn optimisation_never_worsens_the_extreme_angles_and_keeps_the_constraints() {
    let cube = box_plc([0.0; 3], [1.0; 3]);
    let stacked = stacked_boxes();
    let cylinder = prism_plc(
        &regular_polygon(12, 1.0),
        None,
        0.0,
        1.5,
        &Frame::identity(),
    );
    let mut segment = box_plc([0.0; 3], [2.0, 1.0, 1.0]);
    segment.points.extend([[0.5, 0.5, 0.3], [1.5, 0.5, 0.7]]);
    segment.segments.push([8, 9]);
    let mut changed = 0;
    for (name, plc, volume) in [
        ("cube", &cube, 0.001),
        ("stacked boxes", &stacked, 0.004),
        ("cylinder", &cylinder, 0.01),
        ("box with a segment", &segment, 0.004),
    ] {
        for (target, level) in [(Some(0.0), 2), (Some(0.0), 6), (None, 3)] {
            changed += usize::from(check(name, plc, volume, target, level));
        }
    }
    assert!(changed >= 4, "optimisation changed only {changed} meshes");
}

#[test]
fn a_lower_angle_target_and_smoothing_alone_also_keep_the_mesh_valid() {
    let cube = box_plc([0.0; 3], [1.0; 3]);
    let plain = tetrahedralize(&cube, &opts(0.001, None, 0)).unwrap();
    for scheme in [1, 2, 3] {
        let o = Options3 {
            optimize_scheme: Some(scheme),
            optimize_max_dihedral: Some(130.0),
            ..opts(0.001, None, 4)
        };
        let m = tetrahedralize(&cube, &o).unwrap();
        m.validate().unwrap();
        let (s0, s1) = (plain.stats(), m.stats());
        assert!(s1.min_dihedral >= s0.min_dihedral && s1.max_dihedral <= s0.max_dihedral);
        assert_eq!(m.faces.len(), plain.faces.len());
        if scheme == 1 {
            // Flips only: no vertex moves.
            assert_eq!(m.vertices, plain.vertices);
        }
        if scheme == 2 {
            // Smoothing only: the same tetrahedra.
            assert_eq!(sorted(&m.tets), sorted(&plain.tets));
        }
    }
}

#[test]
fn bad_optimisation_options_are_refused_by_name() {
    let cube = box_plc([0.0; 3], [1.0; 3]);
    let cases = [
        (
            Options3 {
                optimize_level: 11,
                ..Options3::default()
            },
            "optimisation level 11",
        ),
        (
            Options3 {
                optimize_level: 2,
                optimize_scheme: Some(8),
                ..Options3::default()
            },
            "optimisation scheme 8",
        ),
        (
            Options3 {
                optimize_level: 2,
                optimize_max_dihedral: Some(180.0),
                ..Options3::default()
            },
            "maximum dihedral angle 180",
        ),
        (
            Options3 {
                optimize_level: 2,
                optimize_max_dihedral: Some(f64::NAN),
                ..Options3::default()
            },
            "maximum dihedral angle NaN",
        ),
    ];
    for (o, words) in cases {
        match tetrahedralize(&cube, &o) {
            Err(Error::InvalidOption(m)) => assert!(m.contains(words), "{m}"),
            other => panic!("{words}: {other:?}"),
        }
    }
}

#[test]
fn command_line_o_switches() {
    let d = cli_common::workdir("optimize3d", &["3d_cube.poly"]);
    for (sw, words) in [
        ("-pO11", "-O11"),
        ("-pO2/8", "-O2/8"),
        ("-po/190", "-o/190"),
        ("-po/", "-o/"),
    ] {
        let o = cli_common::idmesh(&d, &["tetgen", sw, "3d_cube.poly"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(words), "{sw}: {err}");
    }
    // A point set gets its Delaunay tetrahedralization: -O is refused, not ignored.
    std::fs::write(
        d.join("pts.node"),
        "5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n",
    )
    .unwrap();
    let o = cli_common::idmesh(&d, &["tetgen", "-O", "pts"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("-O"), "{err}");
    let out = cli_common::ok(&cli_common::idmesh(
        &d,
        &["tetgen", "-pq1.414/0a0.001O3VC", "3d_cube.poly"],
    ));
    assert!(out.contains("no longer Delaunay"), "{out}");
    let out = cli_common::ok(&cli_common::idmesh(
        &d,
        &["tetgen", "-pq1.414/0a0.001VC", "3d_cube.poly"],
    ));
    assert!(!out.contains("no longer Delaunay"), "{out}");
}

/// Scheme bit 4 (TetGen splits slivers by new points) without quality bounds: idmesh runs its
/// Delaunay sliver removal, aiming at 180 minus the `o/` target. The mesh stays Delaunay (the
/// full `validate()`, empty circumspheres included) with every tetrahedron within the target
/// except those next to a small input angle (none here), and without bit 4 no point is added.
#[test]
fn scheme_bit_4_removes_slivers_without_quality_bounds_and_keeps_the_mesh_delaunay() {
    let cylinder = prism_plc(
        &regular_polygon(24, 1.0),
        None,
        0.0,
        0.4,
        &Frame::identity(),
    );
    let bare = Options3 {
        max_steiner: Some(100_000),
        ..Options3::default()
    };
    let plain = tetrahedralize(&cylinder, &bare).unwrap();
    let s0 = plain.stats();
    assert!(s0.tets_below[2] > 0, "the test needs slivers: {s0:?}");
    let with = |scheme: u32, max: Option<f64>| {
        let o = Options3 {
            optimize_level: 1,
            optimize_scheme: Some(scheme),
            optimize_max_dihedral: max,
            ..bare.clone()
        };
        tetrahedralize(&cylinder, &o).unwrap()
    };
    for (max, target) in [(None, 15.0), (Some(160.0), 20.0)] {
        let m = with(4, max);
        assert!(
            !m.optimized,
            "bit 4 alone makes no flips and moves no vertex"
        );
        m.validate().unwrap();
        let s = m.stats();
        assert!(
            s.min_dihedral >= target && s.max_dihedral <= 180.0 - target,
            "O1/4 with o/{max:?}: {s:?}"
        );
        assert!(m.vertices.len() > plain.vertices.len());
    }
    // Flips and smoothing only: no vertex added.
    assert_eq!(with(3, None).vertices.len(), plain.vertices.len());
}
