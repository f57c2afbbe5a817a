//! Every 3D `InputError` from a minimal bad PLC, with a message that names the offending
//! items; and the near misses that are *not* errors (one ulp away, shared vertices and edges,
//! listed points, facets filling another facet's hole).

use idmesh::input3d::check_plc;
use idmesh::{Error, Facet, InputError, Plc, Region3};

/// The unit cube: points 0-3 at z = 0, 4-7 at z = 1 (counter-clockwise from the origin),
/// facets 0 bottom, 1 top, 2-5 sides.
fn cube() -> Plc {
    let points = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let quads = [
        [0, 1, 2, 3],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    Plc {
        points,
        facets: quads.iter().map(|q| facet(&[q])).collect(),
        ..Plc::default()
    }
}

fn facet(polys: &[&[u32]]) -> Facet {
    Facet {
        polygons: polys.iter().map(|p| p.to_vec()).collect(),
        ..Facet::default()
    }
}

/// Adds a point and returns its index.
fn add(plc: &mut Plc, p: [f64; 3]) -> u32 {
    plc.points.push(p);
    (plc.points.len() - 1) as u32
}

/// The next float above `x`.
fn up(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}

/// Checks expecting an input error; returns it with its message.
fn input_err(plc: &Plc) -> (InputError, String) {
    match check_plc(plc) {
        Err(Error::Input(e)) => {
            let msg = Error::Input(e.clone()).to_string();
            (e, msg)
        }
        other => panic!("expected an input error, got {other:?}"),
    }
}

fn assert_err(plc: &Plc, want: InputError, needles: &[&str]) {
    let (e, msg) = input_err(plc);
    assert_eq!(e, want, "{msg}");
    for n in needles {
        assert!(msg.contains(n), "message {msg:?} does not name {n:?}");
    }
}

#[test]
fn the_cube_and_its_near_misses_are_fine() {
    let plc = cube();
    check_plc(&plc).unwrap();
    // A free point one ulp above the top face.
    let mut p = cube();
    add(&mut p, [0.5, 0.5, up(1.0)]);
    check_plc(&p).unwrap();
    // A free segment from a corner outwards, and one repeating a facet edge.
    let mut p = cube();
    let far = add(&mut p, [2.0, 2.0, 2.0]);
    p.segments = vec![[6, far], [5, 4]];
    check_plc(&p).unwrap();
    // A point on the top face, listed there as a one-vertex polygon.
    let mut p = cube();
    let c = add(&mut p, [0.5, 0.5, 1.0]);
    p.facets[1].polygons.push(vec![c]);
    check_plc(&p).unwrap();
}

#[test]
fn stacked_boxes_sharing_a_partition_facet_are_fine_only_when_sides_are_split() {
    let p = stacked_boxes();
    check_plc(&p).unwrap();
    // The same volume with each side as one tall rectangle: the partition's corners lie on
    // the tall rectangles' vertical edges without being their vertices.
    let mut tall = p.clone();
    tall.facets.truncate(2);
    tall.facets.push(facet(&[&[8, 9, 10, 11]]));
    for (a, b) in [(0, 1), (1, 2), (2, 3), (3, 0)] {
        tall.facets.push(facet(&[&[a, b, b + 8, a + 8]]));
    }
    let (e, msg) = input_err(&tall);
    assert!(
        matches!(
            e,
            InputError::VertexOnFacet {
                vertex: 4..=7,
                facet: 3..=6
            }
        ),
        "{msg}"
    );
    // Listing the partition corners in the tall sides is not enough: the partition's edges
    // run across the sides' interiors.
    for (k, (a, b)) in [(0, 1), (1, 2), (2, 3), (3, 0)].into_iter().enumerate() {
        tall.facets[3 + k].polygons[0] = vec![a, b, b + 4, b + 8, a + 8, a + 4];
    }
    let (e, msg) = input_err(&tall);
    assert!(
        matches!(
            e,
            InputError::FacetsIntersect {
                first: 1,
                second: 3..=6
            }
        ),
        "{msg}"
    );
    // Listing those edges too (as two-vertex polygons) makes it valid.
    for (k, (a, b)) in [(0, 1), (1, 2), (2, 3), (3, 0)].into_iter().enumerate() {
        tall.facets[3 + k].polygons.push(vec![a + 4, b + 4]);
    }
    check_plc(&tall).unwrap();
}

#[test]
fn counts_coordinates_and_markers() {
    let mut p = cube();
    p.points.truncate(3);
    p.facets.clear();
    assert_err(
        &p,
        InputError::TooFewPoints3 { count: 3 },
        &["4 points", "got 3"],
    );
    let mut p = cube();
    p.points[5][1] = f64::NAN;
    assert_err(&p, InputError::NonFinitePoint { point: 5 }, &["point 5"]);
    let mut p = cube();
    p.points[2][2] = -1e60;
    assert_err(
        &p,
        InputError::CoordinateTooLarge { point: 2 },
        &["point 2"],
    );
    let mut p = cube();
    p.point_markers = vec![1; 7];
    assert_err(
        &p,
        InputError::MarkerCountMismatch {
            what: "point",
            expected: 8,
            got: 7,
        },
        &["point markers"],
    );
    let mut p = cube();
    p.segments = vec![[0, 6]];
    p.segment_markers = vec![1, 2];
    let (e, _) = input_err(&p);
    assert!(
        matches!(
            e,
            InputError::MarkerCountMismatch {
                what: "segment",
                ..
            }
        ),
        "{e:?}"
    );
}

#[test]
fn segment_indices_lengths_and_duplicates() {
    let mut p = cube();
    p.segments = vec![[0, 6], [2, 8]];
    assert_err(
        &p,
        InputError::SegmentIndexOutOfRange {
            segment: 1,
            index: 8,
            num_points: 8,
        },
        &["segment 1", "point 8"],
    );
    let mut p = cube();
    p.segments = vec![[3, 3]];
    assert_err(
        &p,
        InputError::ZeroLengthSegment { segment: 0 },
        &["segment 0"],
    );
    let mut p = cube();
    p.segments = vec![[0, 6], [1, 7], [6, 0]];
    assert_err(
        &p,
        InputError::DuplicateSegment {
            first: 0,
            second: 2,
        },
        &["segments 0 and 2"],
    );
}

#[test]
fn duplicate_and_coplanar_points() {
    let mut p = cube();
    p.points.push([1.0, -0.0, 1.0]);
    assert_err(
        &p,
        InputError::DuplicatePoint {
            first: 5,
            second: 8,
        },
        &["points 5 and 8"],
    );
    let flat = Plc {
        points: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.5, 0.3, 0.0],
        ],
        ..Plc::default()
    };
    assert_err(&flat, InputError::AllCoplanar, &["one plane"]);
    let mut lifted = flat.clone();
    lifted.points[4][2] = 1e-300;
    check_plc(&lifted).unwrap();
    let line = Plc {
        points: (0..5).map(|i| [i as f64, 2.0 * i as f64, 0.5]).collect(),
        ..Plc::default()
    };
    assert_err(&line, InputError::AllCoplanar, &[]);
}

#[test]
fn facet_structure() {
    let mut p = cube();
    p.facets[3].polygons.clear();
    assert_err(
        &p,
        InputError::FacetWithoutPolygons { facet: 3 },
        &["facet 3"],
    );
    let mut p = cube();
    p.facets[2].polygons.push(vec![]);
    assert_err(
        &p,
        InputError::EmptyPolygon {
            facet: 2,
            polygon: 1,
        },
        &["facet 2 polygon 1"],
    );
    let mut p = cube();
    p.facets[4].polygons[0][2] = 99;
    assert_err(
        &p,
        InputError::FacetIndexOutOfRange {
            facet: 4,
            polygon: 0,
            index: 99,
            num_points: 8,
        },
        &["facet 4 polygon 0", "point 99", "only 8"],
    );
    let mut p = cube();
    p.facets[1].polygons[0] = vec![4, 5, 6, 5, 7];
    assert_err(
        &p,
        InputError::RepeatedVertexInPolygon {
            facet: 1,
            polygon: 0,
            vertex: 5,
        },
        &["facet 1 polygon 0", "point 5 twice"],
    );
}

#[test]
fn degenerate_and_nonplanar_facets() {
    let mut p = cube();
    let m = add(&mut p, [0.5, 0.0, 0.0]);
    p.facets.push(facet(&[&[0, m, 1]]));
    assert_err(
        &p,
        InputError::DegeneratePolygon {
            facet: 6,
            polygon: 0,
        },
        &["facet 6 polygon 0", "one line"],
    );
    // A facet of one segment spans no plane (TetGen's way of giving a free segment; use
    // Plc::segments instead).
    let mut p = cube();
    p.facets.push(facet(&[&[0, 6]]));
    assert_err(&p, InputError::DegenerateFacet { facet: 6 }, &["facet 6"]);
    // The top face with its last corner raised by one ulp (the plane is that of its first
    // three corners).
    let mut p = cube();
    p.points[7][2] = up(1.0);
    assert_err(
        &p,
        InputError::NonPlanarFacet {
            facet: 1,
            vertex: 7,
        },
        &["facet 1", "point 7"],
    );
}

#[test]
fn facet_holes() {
    let mut p = cube();
    p.facets[1].holes = vec![[0.5, 0.5, 1.0], [0.5, f64::INFINITY, 1.0]];
    assert_err(
        &p,
        InputError::NonFiniteFacetHole { facet: 1, hole: 1 },
        &["facet 1 hole 1"],
    );
    let mut p = cube();
    p.facets[1].holes = vec![[0.5, 0.5, up(1.0)]];
    assert_err(
        &p,
        InputError::FacetHoleOffPlane { facet: 1, hole: 0 },
        &["facet 1 hole 0", "plane"],
    );
}

#[test]
fn crossing_polygon_edges_within_a_facet() {
    let mut p = cube();
    p.facets[1].polygons[0] = vec![4, 6, 5, 7];
    assert_err(
        &p,
        InputError::SelfIntersectingFacet {
            facet: 1,
            first_polygon: 0,
            second_polygon: 0,
        },
        &["facet 1 polygon 0 crosses itself"],
    );
    let mut p = cube();
    p.facets[0].polygons.push(vec![0, 2]);
    p.facets[0].polygons.push(vec![1, 3]);
    assert_err(
        &p,
        InputError::SelfIntersectingFacet {
            facet: 0,
            first_polygon: 1,
            second_polygon: 2,
        },
        &["facet 0", "polygons 1 and 2"],
    );
}

#[test]
fn seeds() {
    let mut p = cube();
    p.holes = vec![[0.5, 0.5, 0.5], [f64::NAN, 0.0, 0.0]];
    assert_err(&p, InputError::NonFiniteHole { hole: 1 }, &["hole 1"]);
    let region = |point: [f64; 3], attribute: f64, max_volume: Option<f64>| Region3 {
        point,
        attribute,
        max_volume,
    };
    for (bad, _why) in [
        (region([0.5, f64::NAN, 0.5], 1.0, None), "coordinate"),
        (region([0.5, 0.5, 0.5], f64::INFINITY, None), "attribute"),
        (region([0.5, 0.5, 0.5], 1.0, Some(0.0)), "zero volume"),
        (region([0.5, 0.5, 0.5], 1.0, Some(-1.0)), "negative volume"),
        (region([0.5, 0.5, 0.5], 1.0, Some(f64::NAN)), "NaN volume"),
    ] {
        let mut p = cube();
        p.regions = vec![region([0.5, 0.5, 0.5], 2.0, Some(0.1)), bad];
        assert_err(
            &p,
            InputError::InvalidRegion3 { region: 1 },
            &["region 1", "volume"],
        );
    }
}

#[test]
fn segments_meeting_improperly() {
    // Two free segments crossing at the cube's centre.
    let mut p = cube();
    let a = add(&mut p, [0.25, 0.25, 0.5]);
    let b = add(&mut p, [0.75, 0.75, 0.5]);
    let c = add(&mut p, [0.75, 0.25, 0.5]);
    let d = add(&mut p, [0.25, 0.75, 0.5]);
    p.segments = vec![[a, b], [c, d]];
    assert_err(
        &p,
        InputError::CrossingSegments {
            first: 0,
            second: 1,
        },
        &["segments 0 and 1"],
    );
    // Skew by one ulp: fine.
    p.points[d as usize][2] = up(0.5);
    check_plc(&p).unwrap();
    // A free point inside a free segment.
    let mut p = cube();
    let a = add(&mut p, [0.25, 0.25, 0.25]);
    let b = add(&mut p, [0.75, 0.75, 0.75]);
    let m = add(&mut p, [0.5, 0.5, 0.5]);
    p.segments = vec![[a, b]];
    assert_err(
        &p,
        InputError::VertexOnSegment {
            vertex: m as usize,
            segment: 0,
        },
        &["point 10", "segment 0"],
    );
}

#[test]
fn segments_meeting_facets_improperly() {
    // From the centre through the top face.
    let mut p = cube();
    let a = add(&mut p, [0.5, 0.5, 0.5]);
    let b = add(&mut p, [0.5, 0.5, 2.0]);
    p.segments = vec![[a, b]];
    assert_err(
        &p,
        InputError::SegmentCrossesFacet {
            segment: 0,
            facet: 1,
        },
        &["segment 0", "facet 1"],
    );
    // Through the top face's edge 5-6 (the line x = 1, z = 1).
    let mut p = cube();
    let a = add(&mut p, [0.5, 0.5, 1.5]);
    let b = add(&mut p, [1.5, 0.5, 0.5]);
    p.segments = vec![[a, b]];
    let (e, msg) = input_err(&p);
    assert!(
        matches!(
            e,
            InputError::SegmentCrossesFacet {
                segment: 0,
                facet: 1 | 3
            }
        ),
        "{msg}"
    );
    // A diagonal of the top face given as a free segment lies inside the facet.
    let mut p = cube();
    p.segments = vec![[4, 6]];
    assert_err(
        &p,
        InputError::SegmentCrossesFacet {
            segment: 0,
            facet: 1,
        },
        &["segment 0", "facet 1"],
    );
    // Ending on the top face without being one of its vertices.
    let mut p = cube();
    let a = add(&mut p, [0.5, 0.5, 2.0]);
    let b = add(&mut p, [0.5, 0.5, 1.0]);
    p.segments = vec![[a, b]];
    assert_err(
        &p,
        InputError::VertexOnFacet {
            vertex: b as usize,
            facet: 1,
        },
        &["point 9", "facet 1"],
    );
}

#[test]
fn facets_meeting_improperly() {
    // A square fin through the top face.
    let mut p = cube();
    let q: Vec<u32> = [
        [0.5, 0.2, 0.5],
        [0.5, 0.8, 0.5],
        [0.5, 0.8, 1.5],
        [0.5, 0.2, 1.5],
    ]
    .into_iter()
    .map(|x| add(&mut p, x))
    .collect();
    p.facets.push(facet(&[&q]));
    assert_err(
        &p,
        InputError::FacetsIntersect {
            first: 1,
            second: 6,
        },
        &["facets 1 and 6"],
    );
    // The same fin, stopped one ulp short of the top face, is fine.
    p.points[q[2] as usize][2] = 1.0 - f64::EPSILON / 2.0;
    p.points[q[3] as usize][2] = 1.0 - f64::EPSILON / 2.0;
    check_plc(&p).unwrap();
    // Touching the top face from below along a line inside it: its top corners lie on it.
    p.points[q[2] as usize][2] = 1.0;
    p.points[q[3] as usize][2] = 1.0;
    let (e, msg) = input_err(&p);
    assert!(
        matches!(e, InputError::VertexOnFacet { facet: 1, .. }),
        "{msg}"
    );
    // The bottom face listed twice.
    let mut p = cube();
    p.facets.push(p.facets[0].clone());
    assert_err(
        &p,
        InputError::FacetsIntersect {
            first: 0,
            second: 6,
        },
        &["facets 0 and 6"],
    );
    // Half of the bottom face, given again as a triangle: coplanar overlap.
    let mut p = cube();
    p.facets.push(facet(&[&[0, 1, 2]]));
    let (e, msg) = input_err(&p);
    assert_eq!(
        e,
        InputError::FacetsIntersect {
            first: 0,
            second: 6
        },
        "{msg}"
    );
    // A triangle sharing the front face's bottom edge 0-1, in its plane, sticking out above
    // it: it overlaps the front face and crosses its top edge 4-5.
    let mut p = cube();
    let apex = add(&mut p, [0.5, 0.0, 1.5]);
    p.facets.push(facet(&[&[0, 1, apex]]));
    let (e, msg) = input_err(&p);
    assert!(
        matches!(
            e,
            InputError::FacetsIntersect {
                first: 1 | 2,
                second: 6
            }
        ),
        "{msg}"
    );
    // Leaning outwards instead, it only shares the edge: fine.
    p.points[apex as usize] = [0.5, -0.5, 0.5];
    check_plc(&p).unwrap();
}

#[test]
fn a_facet_in_another_facets_hole_is_fine_only_with_the_hole_seed() {
    // The top face with a square window (facet hole seed) and a lid facet in the window, as
    // TetGen's own example PLC does.
    let mut p = cube();
    let w: Vec<u32> = [[0.25, 0.25], [0.75, 0.25], [0.75, 0.75], [0.25, 0.75]]
        .into_iter()
        .map(|q| add(&mut p, [q[0], q[1], 1.0]))
        .collect();
    p.facets[1].polygons.push(w.clone());
    p.facets[1].holes = vec![[0.5, 0.5, 1.0]];
    p.facets.push(facet(&[&w]));
    check_plc(&p).unwrap();
    p.facets[1].holes.clear();
    assert_err(
        &p,
        InputError::FacetsIntersect {
            first: 1,
            second: 6,
        },
        &["facets 1 and 6"],
    );
}

#[test]
fn shared_edges_split_by_a_vertex_must_be_split_in_every_facet() {
    // The top face gets a vertex in the middle of its edge 4-5, listed in its loop; the front
    // face shares that edge and must list it too.
    let mut p = cube();
    let m = add(&mut p, [0.5, 0.0, 1.0]);
    p.facets[1].polygons[0] = vec![4, m, 5, 6, 7];
    assert_err(
        &p,
        InputError::VertexOnFacet {
            vertex: m as usize,
            facet: 2,
        },
        &["point 8", "facet 2"],
    );
    p.facets[2].polygons[0] = vec![0, 1, 5, m, 4];
    check_plc(&p).unwrap();
}

#[test]
fn every_message_is_one_line_and_names_something() {
    // A sample of the Display texts: no newline, and the numbers appear.
    let samples = [
        InputError::SelfIntersectingFacet {
            facet: 3,
            first_polygon: 1,
            second_polygon: 4,
        },
        InputError::FacetsIntersect {
            first: 2,
            second: 9,
        },
        InputError::NonPlanarFacet {
            facet: 12,
            vertex: 40,
        },
        InputError::InvalidRegion3 { region: 7 },
    ];
    for e in samples {
        let s = e.to_string();
        assert!(!s.contains('\n'), "{s}");
        assert!(s.chars().any(|c| c.is_ascii_digit()), "{s}");
    }
}

/// An open surface passes the PLC checks (facets may dangle inside a volume) but encloses no
/// volume: meshing reports an input error naming the edges that only one facet uses, never an
/// internal error.
#[test]
fn an_open_surface_names_its_open_edges() {
    let mut plc = cube();
    plc.facets.remove(1); // the top
    check_plc(&plc).unwrap();
    let err = idmesh::tetrahedralize(&plc, &idmesh::Options3::default()).unwrap_err();
    let want = InputError::OpenSurface {
        count: 4,
        edges: vec![[4, 5], [4, 7], [5, 6]],
        facets: vec![1, 2, 4],
    };
    assert_eq!(err, Error::Input(want), "{err}");
    let msg = err.to_string();
    assert!(
        msg.contains("4 facet edges are used by one facet only, e.g. 4-5, 4-7, 5-6 of facets"),
        "{msg}"
    );
    // A closed surface with a dangling internal facet still meshes.
    let mut closed = cube();
    closed
        .points
        .extend([[0.5, 0.2, 0.2], [0.5, 0.8, 0.2], [0.5, 0.5, 0.8]]);
    closed.facets.push(facet(&[&[8, 9, 10]]));
    idmesh::tetrahedralize(&closed, &idmesh::Options3::default())
        .unwrap()
        .validate()
        .unwrap();
}

/// Two unit boxes on top of each other: points 8-11 at z = 2; the middle square at z = 1 is
/// facet 1 of the cube and shared.
fn stacked_boxes() -> Plc {
    let mut p = cube();
    for q in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
        add(&mut p, [q[0], q[1], 2.0]);
    }
    p.facets.push(facet(&[&[8, 9, 10, 11]]));
    for (a, b) in [(4, 5), (5, 6), (6, 7), (7, 4)] {
        p.facets.push(facet(&[&[a, b, b + 4, a + 4]]));
    }
    p
}

/// Meshing error, with its message.
fn mesh_err(plc: &Plc) -> (InputError, String) {
    match idmesh::tetrahedralize(plc, &idmesh::Options3::default()) {
        Err(Error::Input(e)) => {
            let msg = Error::Input(e.clone()).to_string();
            (e, msg)
        }
        other => panic!(
            "expected an input error, got {:?}",
            other.map(|m| m.tets.len())
        ),
    }
}

#[test]
fn a_seed_on_a_facet_names_no_side_and_is_refused() {
    // The shared square is two subfaces: (0.25, 0.5) is inside one, the centre on their
    // common diagonal whichever it is, (1, 0.5) on the square's edge (a subsegment), and
    // (1, 1) on its corner. A hole seed there could carve either box (3D campaign seed 9 run
    // 9527 carved one and kept the tet holding the seed); a region seed could name either.
    let good = stacked_boxes();
    let whole = idmesh::tetrahedralize(&good, &idmesh::Options3::default()).unwrap();
    for at in [
        [0.25, 0.5, 1.0],
        [0.5, 0.5, 1.0],
        [1.0, 0.5, 1.0],
        [1.0, 1.0, 1.0],
    ] {
        let mut p = good.clone();
        p.holes = vec![[0.5, 0.5, 1.5], at];
        let (e, msg) = mesh_err(&p);
        assert_eq!(
            e,
            InputError::HoleOutsideDomain { hole: 1 },
            "hole at {at:?}: {msg}"
        );
        assert!(msg.contains("hole 1") && msg.contains("facet"), "{msg}");
        let mut p = good.clone();
        p.regions = vec![Region3 {
            point: at,
            attribute: 1.0,
            max_volume: None,
        }];
        let (e, msg) = mesh_err(&p);
        assert_eq!(
            e,
            InputError::RegionOutsideDomain { region: 0 },
            "region at {at:?}: {msg}"
        );
    }
    // A hole seed an ulp off the square is on one side: that box goes, the other stays.
    for (z, kept_below) in [(up(1.0), true), (1.0 - f64::EPSILON / 2.0, false)] {
        let mut p = good.clone();
        p.holes = vec![[0.25, 0.5, z]];
        let m = idmesh::tetrahedralize(&p, &idmesh::Options3::default()).unwrap();
        assert!(!m.tets.is_empty() && m.tets.len() < whole.tets.len());
        for t in &m.tets {
            let zs = t.map(|v| m.vertices[v as usize][2]);
            let below = zs.iter().all(|&z| z <= 1.0);
            assert_eq!(below, kept_below, "hole at z = {z}: tet {t:?} at {zs:?}");
        }
    }
}
