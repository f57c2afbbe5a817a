//! Named degenerate inputs for the 2D mesher: exact cocircularity and collinearity, points on
//! segments, tiny input angles, extreme aspect ratios and coordinate scales, and the Steiner cap.
//! Every mesh goes through the independent checker in `common`.

mod common;

use common::{
    assert_mesh, hull_triangle_count, polygon_area, quality, regular_polygon, Builder, Spec,
    STEINER_GUARD,
};
use idmesh::{Options, Pslg};

fn grid_points(nx: usize, ny: usize, h: f64) -> Vec<[f64; 2]> {
    let mut pts = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            pts.push([i as f64 * h, j as f64 * h]);
        }
    }
    pts
}

fn points_only(points: Vec<[f64; 2]>) -> Pslg {
    Pslg {
        points,
        ..Pslg::default()
    }
}

/// A square `[0, s]²` whose four corners are joined by segments (and whose other points may
/// lie on those segments).
fn square_spec(s: f64) -> Spec {
    let outer = vec![[0.0, 0.0], [s, 0.0], [s, s], [0.0, s]];
    Spec {
        area: Some(s * s),
        outer: Some(outer),
        ..Spec::default()
    }
}

// ----------------------------------------------------------------------------- grids

#[test]
fn grid_30x30_plain_delaunay() {
    let n = 30;
    let pslg = points_only(grid_points(n, n, 1.0));
    let (mesh, r) = assert_mesh(&pslg, &Options::default(), &Spec::default());
    // Without segments or bounds nothing needs a Steiner point, and Euler's formula fixes the
    // triangle count: 2·V − 2 − (vertices on the hull boundary).
    assert_eq!(
        r.steiner, 0,
        "plain Delaunay of points added Steiner points"
    );
    let boundary = 4 * (n - 1);
    assert_eq!(common::hull_boundary_count(&pslg.points), boundary);
    assert_eq!(mesh.triangles.len(), 2 * n * n - 2 - boundary);
}

#[test]
fn grid_30x30_q30() {
    let pslg = points_only(grid_points(30, 30, 1.0));
    let (mesh, r) = assert_mesh(&pslg, &quality(30.0), &Spec::default());
    assert!(mesh.complete);
    assert!(r.min_angle >= 30.0 - 1e-9, "min angle {}", r.min_angle);
}

#[test]
fn grid_with_inexact_spacing_is_delaunay() {
    // Spacing 0.1 is not representable: the quadruples are only nearly cocircular, so the exact
    // predicates see tiny positive and negative incircle values instead of zeros.
    let pslg = points_only(grid_points(25, 25, 0.1));
    let want = hull_triangle_count(&pslg.points);
    let (mesh, r) = assert_mesh(&pslg, &Options::default(), &Spec::default());
    assert_eq!((r.steiner, mesh.triangles.len()), (0, want));
}

#[test]
fn grid_inside_square_boundary_q30_with_area() {
    // Only the corners are segment endpoints; the other boundary grid points lie exactly on the
    // boundary segments, which must be split there.
    let n = 12;
    let s = (n - 1) as f64;
    let mut b = Builder::default();
    let corners = [[0.0, 0.0], [s, 0.0], [s, s], [0.0, s]];
    b.closed_loop(&corners);
    for p in grid_points(n, n, 1.0) {
        if !corners.contains(&p) {
            b.point(p);
        }
    }
    // A diagonal chord through grid points: they lie exactly on it.
    b.segment(0, 2);
    let spec = square_spec(s);
    assert_mesh(&b.pslg, &Options::default(), &spec);
    let opts = Options {
        max_area: Some(0.3),
        ..quality(30.0)
    };
    let (mesh, _) = assert_mesh(&b.pslg, &opts, &spec);
    assert!(mesh.complete);
}

#[test]
fn rotated_grid_is_delaunay() {
    // The grid rotated by 45° with exact coordinates: still full of cocircular quadruples.
    let mut pts = Vec::new();
    for i in 0..20i32 {
        for j in 0..20i32 {
            pts.push([(i + j) as f64, (i - j) as f64]);
        }
    }
    let (_, r) = assert_mesh(
        &points_only(pts.clone()),
        &Options::default(),
        &Spec::default(),
    );
    assert_eq!(r.steiner, 0);
    assert_mesh(&points_only(pts), &quality(28.0), &Spec::default());
}

// ----------------------------------------------------------------------------- cocircular

#[test]
fn regular_polygons_points_only() {
    for n in 3..=200 {
        for center in [false, true] {
            let mut pts = regular_polygon(n, [0.0, 0.0], 1.0, 0.0);
            if center {
                pts.push([0.0, 0.0]);
            }
            let want = hull_triangle_count(&pts);
            let (mesh, r) = assert_mesh(&points_only(pts), &Options::default(), &Spec::default());
            assert_eq!(r.steiner, 0, "n = {n}");
            // Rounding may pull a polygon vertex just inside the hull; Euler's count is exact.
            assert_eq!(mesh.triangles.len(), want, "n = {n}, center = {center}");
        }
    }
}

#[test]
fn regular_polygons_with_segments() {
    for n in 3..=200 {
        for center in [false, true] {
            let poly = regular_polygon(n, [0.0, 0.0], 1.0, 0.3);
            let mut b = Builder::default();
            b.closed_loop(&poly);
            if center {
                b.point([0.0, 0.0]);
            }
            let spec = Spec {
                area: Some(polygon_area(&poly)),
                outer: Some(poly.clone()),
                ..Spec::default()
            };
            assert_mesh(&b.pslg, &Options::default(), &spec);
            if n <= 40 || n % 8 == 0 {
                let (mesh, _) = assert_mesh(&b.pslg, &quality(30.0), &spec);
                assert!(mesh.complete, "n = {n}");
            }
        }
    }
}

/// All integer points on the circle of radius `r`, counter-clockwise: exactly cocircular.
fn lattice_circle(r: i64) -> Vec<[f64; 2]> {
    let mut pts = Vec::new();
    for x in -r..=r {
        for y in -r..=r {
            if x * x + y * y == r * r {
                pts.push([x as f64, y as f64]);
            }
        }
    }
    pts.sort_by(|a, b| a[1].atan2(a[0]).total_cmp(&b[1].atan2(b[0])));
    pts
}

#[test]
fn exactly_cocircular_lattice_points() {
    for r in [5, 25, 65, 325] {
        let circle = lattice_circle(r);
        assert!(circle.len() >= 12);
        for center in [false, true] {
            let mut pts = circle.clone();
            if center {
                pts.push([0.0, 0.0]);
            }
            let (mesh, rep) = assert_mesh(&points_only(pts), &Options::default(), &Spec::default());
            assert_eq!(rep.steiner, 0);
            assert_eq!(
                mesh.triangles.len(),
                if center {
                    circle.len()
                } else {
                    circle.len() - 2
                }
            );

            let mut b = Builder::default();
            b.closed_loop(&circle);
            if center {
                b.point([0.0, 0.0]);
            }
            let spec = Spec {
                area: Some(polygon_area(&circle)),
                outer: Some(circle.clone()),
                ..Spec::default()
            };
            assert_mesh(&b.pslg, &Options::default(), &spec);
            let (mesh, _) = assert_mesh(&b.pslg, &quality(30.0), &spec);
            assert!(mesh.complete);
        }
    }
}

// ----------------------------------------------------------------------------- collinear

#[test]
fn collinear_chain_plus_one_point() {
    for k in [1usize, 2, 5, 50] {
        let mut pts: Vec<[f64; 2]> = (0..=k).map(|i| [i as f64, 0.0]).collect();
        pts.push([k as f64 / 2.0, 1.0]);
        assert_eq!(hull_triangle_count(&pts), k);
        let (mesh, r) = assert_mesh(&points_only(pts), &Options::default(), &Spec::default());
        assert_eq!(r.steiner, 0);
        assert_eq!(mesh.triangles.len(), k, "a fan over {k} chain edges");
    }
    // The off-line point very close to the line (positive orientation only in exact arithmetic).
    let mut pts: Vec<[f64; 2]> = (0..=10).map(|i| [i as f64 * 0.1, i as f64 * 0.3]).collect();
    pts.push([0.5, 1.5 + 1e-12]);
    assert_mesh(&points_only(pts), &Options::default(), &Spec::default());
}

#[test]
fn inexact_slanted_chain_points_only() {
    // i·(0.1, 0.3) rounds off the line: some triples are collinear, others turn by an ulp.
    let mut pts: Vec<[f64; 2]> = (0..40).map(|i| [i as f64 * 0.1, i as f64 * 0.3]).collect();
    pts.push([0.0, 5.0]);
    let want = hull_triangle_count(&pts);
    let (mesh, _) = assert_mesh(&points_only(pts), &Options::default(), &Spec::default());
    assert_eq!(mesh.triangles.len(), want);
}

#[test]
fn segments_along_collinear_chain() {
    for q in [None, Some(30.0)] {
        let k = 8;
        let mut b = Builder::default();
        let chain: Vec<u32> = (0..=k).map(|i| b.point([i as f64, 0.0])).collect();
        let top = b.point([k as f64 / 2.0, 2.0]);
        for w in chain.windows(2) {
            b.segment(w[0], w[1]);
        }
        b.segment(chain[k], top);
        b.segment(top, chain[0]);
        let outer = vec![[0.0, 0.0], [k as f64, 0.0], [k as f64 / 2.0, 2.0]];
        let spec = Spec {
            area: Some(polygon_area(&outer)),
            outer: Some(outer),
            ..Spec::default()
        };
        let opts = q.map_or_else(Options::default, quality);
        let (mesh, _) = assert_mesh(&b.pslg, &opts, &spec);
        assert!(mesh.complete);
    }
}

#[test]
fn slanted_exact_collinear_chain_with_one_long_segment() {
    // Points exactly on the line y = x/2 (representable), joined by ONE segment end to end.
    let mut b = Builder::default();
    let chain: Vec<u32> = (0..=6)
        .map(|i| b.point([i as f64 * 1.5, i as f64 * 0.75]))
        .collect();
    let top = b.point([0.0, 6.0]);
    b.segment(chain[0], chain[6]);
    b.segment(chain[6], top);
    b.segment(top, chain[0]);
    let outer = vec![[0.0, 0.0], [9.0, 4.5], [0.0, 6.0]];
    let spec = Spec {
        area: Some(polygon_area(&outer)),
        outer: Some(outer),
        ..Spec::default()
    };
    assert_mesh(&b.pslg, &Options::default(), &spec);
    assert_mesh(&b.pslg, &quality(25.0), &spec);
}

// ----------------------------------------------------------------------------- points on segments

#[test]
fn input_points_on_segments_split_them() {
    let mut b = Builder::default();
    b.closed_loop(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    b.segment(0, 2); // the diagonal
    b.point([0.25, 0.25]); // on the diagonal
    b.point([0.5, 0.5]); // on the diagonal
    b.point([0.5, 0.0]); // on the bottom edge
    b.point([1.0, 0.75]); // on the right edge
    let spec = square_spec(1.0);
    for opts in [Options::default(), quality(30.0)] {
        let (mesh, _) = assert_mesh(&b.pslg, &opts, &spec);
        // The split must show in the subsegment list: no subsegment spans an input point.
        for s in &mesh.segments {
            let (p, q) = (mesh.vertices[s[0] as usize], mesh.vertices[s[1] as usize]);
            for (i, &x) in b.pslg.points.iter().enumerate() {
                assert!(
                    !common::strictly_inside_segment(p, q, x),
                    "subsegment {s:?} passes through input point {i}"
                );
            }
        }
    }
}

#[test]
fn point_on_slanted_segment_and_t_junction() {
    // (1.5, 0.5) lies exactly on the segment (0,0)-(3,1); a second segment starts there.
    let mut b = Builder::default();
    b.closed_loop(&[[0.0, 0.0], [3.0, 1.0], [0.0, 2.0]]);
    let mid = b.point([1.5, 0.5]);
    let tip = b.point([0.5, 1.0]);
    b.segment(mid, tip);
    let outer = vec![[0.0, 0.0], [3.0, 1.0], [0.0, 2.0]];
    let spec = Spec {
        area: Some(polygon_area(&outer)),
        outer: Some(outer),
        ..Spec::default()
    };
    assert_mesh(&b.pslg, &Options::default(), &spec);
    assert_mesh(&b.pslg, &quality(30.0), &spec);
}

// ----------------------------------------------------------------------------- small angles

/// A square box with two dangling segments from an interior vertex, `deg` degrees apart.
fn dangling_pair(deg: f64) -> (Pslg, Spec) {
    let mut b = Builder::default();
    let outer = vec![[-1.0, -1.0], [2.0, -1.0], [2.0, 2.0], [-1.0, 2.0]];
    b.closed_loop(&outer);
    let o = b.point([0.0, 0.0]);
    let p = b.point([1.0, 0.0]);
    let a = deg.to_radians();
    let q = b.point([a.cos(), a.sin()]);
    b.segment(o, p);
    b.segment(o, q);
    (
        b.pslg,
        Spec {
            area: Some(9.0),
            outer: Some(outer),
            ..Spec::default()
        },
    )
}

/// A wedge polygon with its apex angle `deg` degrees: two segments of the boundary meet there.
fn wedge(deg: f64) -> (Pslg, Spec) {
    let a = deg.to_radians();
    let mut outer = vec![[0.0, 0.0], [1.0, 0.0]];
    for k in 1..4 {
        let t = a * k as f64 / 4.0;
        outer.push([1.2 * t.cos(), 1.2 * t.sin()]);
    }
    outer.push([a.cos(), a.sin()]);
    let mut b = Builder::default();
    b.closed_loop(&outer);
    (
        b.pslg,
        Spec {
            area: Some(polygon_area(&outer)),
            outer: Some(outer),
            ..Spec::default()
        },
    )
}

fn small_angle_case(pslg: &Pslg, spec: &Spec, name: &str) {
    assert_mesh(pslg, &Options::default(), spec);
    for q in [20.0, 30.0] {
        let (mesh, r) = assert_mesh(pslg, &quality(q), spec);
        assert!(
            mesh.complete,
            "{name} q{q}: refinement hit the {STEINER_GUARD} Steiner guard"
        );
        assert!((r.steiner as u64) < STEINER_GUARD);
    }
}

#[test]
fn segments_meeting_at_1_degree() {
    let (p, s) = dangling_pair(1.0);
    small_angle_case(&p, &s, "dangling 1°");
    let (p, s) = wedge(1.0);
    small_angle_case(&p, &s, "wedge 1°");
}

#[test]
fn segments_meeting_at_0_1_degree() {
    let (p, s) = dangling_pair(0.1);
    small_angle_case(&p, &s, "dangling 0.1°");
    let (p, s) = wedge(0.1);
    small_angle_case(&p, &s, "wedge 0.1°");
}

#[test]
fn segment_ending_on_another_at_a_small_angle() {
    // The T-junction vertex lies exactly inside the long segment (slope 2); the short one
    // (slope 1.8) ends there, 2.5° away: a corner for concentric shells although no two input
    // segments share an endpoint.
    let mut b = Builder::default();
    let outer = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    b.closed_loop(&outer);
    let p = b.point([0.1875, 0.0625]);
    let q = b.point([0.5, 0.6875]);
    let t = b.point([0.25, 0.1875]);
    let r = b.point([0.5625, 0.75]);
    b.segment(p, q);
    b.segment(t, r);
    small_angle_case(&b.pslg, &square_spec(1.0), "T-junction 2.5°");
}

#[test]
fn three_segments_crossing_at_one_unrepresentable_point() {
    // All three pass through (1/3, 1/3); the three computed pairwise crossings differ by an
    // ulp and must become one vertex.
    let mut b = Builder::default();
    let outer = vec![[-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]];
    b.closed_loop(&outer);
    for (u, v) in [
        ([-1.0, -1.0], [1.0, 1.0]),
        ([-1.0, 1.0], [1.0, 0.0]),
        ([0.0, 1.0], [1.0, -1.0]),
    ] {
        let (i, j) = (b.point(u), b.point(v));
        b.segment(i, j);
    }
    let spec = Spec {
        area: Some(16.0),
        outer: Some(outer),
        ..Spec::default()
    };
    for opts in [Options::default(), quality(30.0)] {
        let opts = Options {
            split_crossings: true,
            ..opts
        };
        let (mesh, _) = assert_mesh(&b.pslg, &opts, &spec);
        assert!(mesh.complete);
        let near: Vec<_> = mesh.vertices[b.pslg.points.len()..]
            .iter()
            .filter(|v| (v[0] - 1.0 / 3.0).abs() < 1e-9 && (v[1] - 1.0 / 3.0).abs() < 1e-9)
            .collect();
        assert_eq!(near.len(), 1, "crossing vertices near (1/3, 1/3): {near:?}");
    }
}

#[test]
fn many_segments_in_a_tight_fan() {
    // Five segments from one vertex, 2° apart: several small angles share the vertex.
    let mut b = Builder::default();
    let outer = vec![[-1.0, -1.0], [2.0, -1.0], [2.0, 2.0], [-1.0, 2.0]];
    b.closed_loop(&outer);
    let o = b.point([0.0, 0.0]);
    for k in 0..5 {
        let a = (2.0 * k as f64).to_radians();
        let p = b.point([a.cos(), a.sin()]);
        b.segment(o, p);
    }
    let spec = Spec {
        area: Some(9.0),
        outer: Some(outer),
        ..Spec::default()
    };
    small_angle_case(&b.pslg, &spec, "fan");
}

// ----------------------------------------------------------------------------- thin and scaled

fn rectangle(w: f64, h: f64) -> (Pslg, Spec) {
    let outer = vec![[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]];
    let mut b = Builder::default();
    b.closed_loop(&outer);
    (
        b.pslg,
        Spec {
            area: Some(w * h),
            outer: Some(outer),
            ..Spec::default()
        },
    )
}

#[test]
fn very_thin_domain_aspect_1e6() {
    let (p, s) = rectangle(1.0, 1e-6);
    let (mesh, _) = assert_mesh(&p, &Options::default(), &s);
    assert_eq!(mesh.triangles.len(), 2);
    // Full refinement would need millions of triangles: cap it and check the partial mesh.
    let opts = Options {
        max_steiner: Some(2000),
        ..quality(30.0)
    };
    let (mesh, r) = assert_mesh(&p, &opts, &s);
    assert!(!mesh.complete && r.steiner <= 2000);
}

#[test]
fn thin_domain_aspect_1e3_q30() {
    let (p, s) = rectangle(1.0, 1e-3);
    let (mesh, _) = assert_mesh(&p, &quality(30.0), &s);
    assert!(mesh.complete);
    // A slanted thin sliver too.
    let outer = vec![[0.0, 0.0], [1.0, 0.3], [1.0, 0.3 + 1e-3], [0.0, 1e-3]];
    let mut b = Builder::default();
    b.closed_loop(&outer);
    let spec = Spec {
        area: Some(polygon_area(&outer)),
        outer: Some(outer),
        ..Spec::default()
    };
    let (mesh, _) = assert_mesh(&b.pslg, &quality(30.0), &spec);
    assert!(mesh.complete);
}

/// A square with a slanted triangular hole and a slanted interior chord, scaled and offset.
fn scaled_shape(scale: f64, offset: f64) -> (Pslg, Spec) {
    let t = |p: [f64; 2]| [offset + scale * p[0], offset + scale * p[1]];
    let outer: Vec<[f64; 2]> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        .map(t)
        .to_vec();
    let hole: Vec<[f64; 2]> = [[0.2, 0.2], [0.45, 0.25], [0.3, 0.4]].map(t).to_vec();
    let mut b = Builder::default();
    b.closed_loop(&outer);
    b.closed_loop(&hole);
    let c0 = b.point(t([0.6, 0.3]));
    let c1 = b.point(t([0.85, 0.8]));
    b.segment(c0, c1);
    b.pslg.holes.push(t([0.31, 0.28]));
    let area = polygon_area(&outer) - polygon_area(&hole);
    (
        b.pslg,
        Spec {
            area: Some(area),
            outer: Some(outer),
            holes: vec![hole],
            ..Spec::default()
        },
    )
}

#[test]
fn tiny_coordinates() {
    let (p, s) = scaled_shape(1e-8, 0.0);
    assert_mesh(&p, &Options::default(), &s);
    let (mesh, _) = assert_mesh(&p, &quality(30.0), &s);
    assert!(mesh.complete);
}

#[test]
fn huge_coordinates() {
    for offset in [0.0, 1e6] {
        let (p, s) = scaled_shape(1e8, offset);
        assert_mesh(&p, &Options::default(), &s);
        let (mesh, _) = assert_mesh(&p, &quality(30.0), &s);
        assert!(mesh.complete);
    }
}

#[test]
fn unit_shape_offset_by_1e6() {
    let (p, s) = scaled_shape(1.0, 1e6);
    assert_mesh(&p, &Options::default(), &s);
    let (mesh, _) = assert_mesh(&p, &quality(30.0), &s);
    assert!(mesh.complete);
}

#[test]
fn tiny_shape_offset_by_1e6() {
    // Only ~86 representable steps across the shape: the angle bound may be unattainable in
    // floating point, but the mesh must stay valid, conforming and Delaunay, and must stop.
    let (p, s) = scaled_shape(1e-8, 1e6);
    assert_mesh(&p, &Options::default(), &s);
    let opts = Options {
        max_steiner: Some(20_000),
        ..quality(20.0)
    };
    let spec = Spec {
        check_quality: false,
        ..s
    };
    assert_mesh(&p, &opts, &spec);
}

// ----------------------------------------------------------------------------- Steiner cap

/// The cap is checked before each skinny or oversized triangle is split; the segment splits
/// that split triggers still finish (documented on `Options::max_steiner`), so a few points
/// beyond the cap are allowed, but nothing like an uncapped run.
const CAP_SLACK: usize = 64;

#[test]
fn steiner_cap_stops_refinement() {
    for (p, s) in [wedge(5.0), rectangle(3.0, 1.0)] {
        let opts = Options {
            min_angle: Some(33.0),
            max_area: Some(1e-4),
            max_steiner: Some(10),
            ..Options::default()
        };
        let (mesh, r) = assert_mesh(&p, &opts, &s);
        assert!(
            !mesh.complete,
            "10 Steiner points cannot meet q33 with this area bound"
        );
        assert!(
            r.steiner <= 10 + CAP_SLACK,
            "{} Steiner points despite the cap of 10",
            r.steiner
        );
        assert_eq!(mesh.steiner_points, r.steiner);
        // The uncapped run needs far more, so the cap really stopped something.
        let full = Options {
            max_steiner: Some(STEINER_GUARD),
            ..opts.clone()
        };
        let (full_mesh, full_r) = assert_mesh(&p, &full, &s);
        assert!(full_mesh.complete);
        assert!(
            full_r.steiner > 2 * r.steiner,
            "capped run {} vs uncapped {} Steiner points",
            r.steiner,
            full_r.steiner
        );
    }
    // A cap of zero: the rectangle needs no segment split to conform, so no point at all.
    let (p, s) = rectangle(3.0, 1.0);
    let opts = Options {
        min_angle: Some(33.0),
        max_steiner: Some(0),
        ..Options::default()
    };
    let (mesh, r) = assert_mesh(&p, &opts, &s);
    assert!(!mesh.complete);
    assert_eq!(r.steiner, 0);
}
