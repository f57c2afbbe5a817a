//! Unit tests of the 2D core on small inputs; the property tests live in tests/.
#![allow(clippy::field_reassign_with_default)]

use super::*;
use crate::error::InputError;
use crate::input2d::{Pslg, Region};

fn square_with_hole() -> Pslg {
    let mut p = Pslg::default();
    p.points = vec![
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 1.0],
        [0.0, 1.0],
        [0.4, 0.4],
        [0.6, 0.4],
        [0.6, 0.6],
        [0.4, 0.6],
    ];
    p.segments = vec![
        [0, 1],
        [1, 2],
        [2, 3],
        [3, 0],
        [4, 5],
        [5, 6],
        [6, 7],
        [7, 4],
    ];
    p.holes = vec![[0.5, 0.5]];
    p
}

fn assert_ok(m: &TriMesh, area: f64) {
    m.validate().unwrap();
    assert!(
        (m.area() - area).abs() <= 1e-12 * area.max(1.0),
        "area {} vs {}",
        m.area(),
        area
    );
}

#[test]
fn delaunay_of_points_covers_the_hull() {
    let mut p = Pslg::default();
    let mut s: u64 = 7;
    for _ in 0..2000 {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let x = (s >> 11) as f64 / (1u64 << 53) as f64;
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let y = (s >> 11) as f64 / (1u64 << 53) as f64;
        p.points.push([x, y]);
    }
    p.points
        .extend_from_slice(&[[-1.0, -1.0], [2.0, -1.0], [2.0, 2.0], [-1.0, 2.0]]);
    let m = triangulate(&p, &Options::default()).unwrap();
    assert_ok(&m, 9.0);
    assert_eq!(m.vertices.len(), p.points.len());
    // Euler: 2n - 2 - h triangles with h = 4 hull vertices.
    assert_eq!(m.triangles.len(), 2 * p.points.len() - 2 - 4);
}

#[test]
fn grid_points_are_cocircular_but_valid() {
    let mut p = Pslg::default();
    for i in 0..20 {
        for j in 0..20 {
            p.points.push([i as f64, j as f64]);
        }
    }
    let m = triangulate(&p, &Options::default()).unwrap();
    assert_ok(&m, 361.0);
    assert_eq!(m.triangles.len(), 2 * 19 * 19);
}

#[test]
fn square_with_hole_conforms_and_meets_quality() {
    let p = square_with_hole();
    let m = triangulate(&p, &Options::default()).unwrap();
    assert_ok(&m, 1.0 - 0.04);
    let opts = Options {
        min_angle: Some(30.0),
        max_area: Some(0.001),
        ..Options::default()
    };
    let m = triangulate(&p, &opts).unwrap();
    assert_ok(&m, 1.0 - 0.04);
    let (lo, _) = m.angle_range();
    assert!(lo >= 30.0 - 1e-9, "min angle {lo}");
    assert!(m.triangles.iter().all(|t| {
        let [a, b, c] = t.map(|v| m.vertices[v as usize]);
        0.5 * crate::geometry::area2(a, b, c) <= 0.001
    }));
    assert!(m.complete);
}

#[test]
fn regions_get_attributes_and_bounds() {
    let mut p = square_with_hole();
    p.holes.clear();
    p.regions = vec![
        Region {
            point: [0.5, 0.5],
            attribute: 7.0,
            max_area: Some(0.0005),
        },
        Region {
            point: [0.1, 0.1],
            attribute: 3.0,
            max_area: None,
        },
    ];
    let opts = Options {
        region_attributes: true,
        region_max_area: true,
        ..Options::default()
    };
    let m = triangulate(&p, &opts).unwrap();
    assert_ok(&m, 1.0);
    let inner = m.triangle_attributes.iter().filter(|&&a| a == 7.0).count();
    let outer = m.triangle_attributes.iter().filter(|&&a| a == 3.0).count();
    assert_eq!(inner + outer, m.triangles.len());
    assert!(inner >= 80, "inner region has {inner} triangles");
}

#[test]
fn small_angle_terminates() {
    let mut p = Pslg::default();
    let a = 1f64.to_radians();
    p.points = vec![
        [0.0, 0.0],
        [1.0, 0.0],
        [a.cos(), a.sin()],
        [-0.5, -0.5],
        [1.5, -0.5],
        [1.5, 1.5],
        [-0.5, 1.5],
    ];
    p.segments = vec![[0, 1], [0, 2], [3, 4], [4, 5], [5, 6], [6, 3]];
    let opts = Options {
        min_angle: Some(30.0),
        ..Options::default()
    };
    let m = triangulate(&p, &opts).unwrap();
    assert_ok(&m, 4.0);
    assert!(m.complete);
}

#[test]
fn steiner_cap_reports_incomplete() {
    let p = square_with_hole();
    let opts = Options {
        min_angle: Some(33.0),
        max_area: Some(1e-5),
        max_steiner: Some(50),
        ..Options::default()
    };
    let m = triangulate(&p, &opts).unwrap();
    assert!(!m.complete);
    m.validate().unwrap();
}

#[test]
fn four_points() {
    let mut p = Pslg::default();
    p.points = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [0.5, 0.2]];
    let m = triangulate(&p, &Options::default()).unwrap();
    assert_ok(&m, 1.0);
}

#[test]
fn eight_points() {
    let p = square_with_hole();
    let p = Pslg {
        segments: vec![],
        holes: vec![],
        ..p
    };
    let m = triangulate(&p, &Options::default()).unwrap();
    assert_ok(&m, 1.0);
}

#[test]
fn right_triangle_area_refinement() {
    let mut p = Pslg::default();
    p.points = vec![[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]];
    p.segments = vec![[0, 1], [1, 2], [2, 0]];
    let opts = Options {
        max_area: Some(0.1),
        ..Options::default()
    };
    let m = triangulate(&p, &opts).unwrap();
    assert_ok(&m, 2.0);
}

#[test]
fn crossing_segments_are_reported_or_split() {
    let mut p = Pslg::default();
    p.points = vec![
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 1.0],
        [0.0, 1.0],
        [0.1, 0.2],
        [0.9, 0.75],
    ];
    p.segments = vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 2], [1, 3], [4, 5]];
    let err = triangulate(&p, &Options::default()).unwrap_err();
    assert!(
        matches!(
            err,
            crate::Error::Input(crate::InputError::CrossingSegments { .. })
        ),
        "{err}"
    );
    let opts = Options {
        split_crossings: true,
        min_angle: Some(28.0),
        ..Options::default()
    };
    let m = triangulate(&p, &opts).unwrap();
    assert_ok(&m, 1.0);
    // The two diagonals cross at the centre; [4, 5] crosses both diagonals.
    assert!(m.vertices.contains(&[0.5, 0.5]));
    assert!(m.complete);
    // Angles below the bound only at crossing points (4 subsegments meet there, the diagonal and
    // [4, 5] cross at about 10.5 degrees).
    let mut degree = vec![0; m.vertices.len()];
    for e in &m.segments {
        degree[e[0] as usize] += 1;
        degree[e[1] as usize] += 1;
    }
    for t in &m.triangles {
        let p = t.map(|v| m.vertices[v as usize]);
        let lo = crate::geometry::triangle_angles_deg(p[0], p[1], p[2])
            .into_iter()
            .fold(180.0, f64::min);
        // Exempt: triangles at a crossing, and the rings of isosceles triangles around it.
        let near_crossing = (0..m.vertices.len()).filter(|&v| degree[v] >= 4).any(|v| {
            p.iter()
                .all(|q| crate::geometry::dist2(*q, m.vertices[v]) < 0.2 * 0.2)
        });
        assert!(
            lo >= 28.0 - 1e-9 || near_crossing,
            "min angle {lo} at {p:?}"
        );
    }
}

#[test]
fn pentagon_area_refinement() {
    let mut p = Pslg::default();
    p.points = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [2.0, 4.0], [0.0, 3.0]];
    p.segments = vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 0]];
    for opts in [
        Options {
            max_area: Some(0.05),
            ..Options::default()
        },
        Options {
            max_area: Some(0.01),
            min_angle: Some(20.0),
            ..Options::default()
        },
    ] {
        let m = triangulate(&p, &opts).unwrap();
        assert_ok(&m, 14.0);
    }
}

fn slanted_sliver() -> Pslg {
    let mut p = Pslg::default();
    p.points = vec![[0.0, 0.0], [1.0, 0.3], [1.0, 0.3 + 1e-3], [0.0, 1e-3]];
    p.segments = vec![[0, 1], [1, 2], [2, 3], [3, 0]];
    p
}

#[test]
fn slanted_sliver_conforms() {
    // Segments go in as constrained edges and the exterior is carved before any split, so no
    // split point's cavity can wrap around the end of the sliver.
    let p = slanted_sliver();
    let m = triangulate(&p, &Options::default()).unwrap();
    assert_ok(&m, 1e-3);
}

#[test]
fn slanted_sliver_q30() {
    let p = slanted_sliver();
    let m = triangulate(
        &p,
        &Options {
            min_angle: Some(30.0),
            ..Options::default()
        },
    )
    .unwrap();
    assert_ok(&m, 1e-3);
}

// ------------------------------------------------------------------ -Y (fixed segments)

fn no_boundary_steiner(min_angle: Option<f64>, max_area: Option<f64>) -> Options {
    Options {
        min_angle,
        max_area,
        no_boundary_steiner: true,
        ..Options::default()
    }
}

/// Every mesh edge with a triangle on one side only joins two input vertices.
fn assert_boundary_unsplit(m: &TriMesh) {
    for (t, tri) in m.triangles.iter().enumerate() {
        for i in 0..3 {
            if m.neighbors[t][i] == NONE {
                let (a, b) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                assert!(
                    (a as usize) < m.num_input_vertices && (b as usize) < m.num_input_vertices,
                    "boundary edge ({a}, {b}) has a Steiner endpoint"
                );
            }
        }
    }
}

#[test]
fn no_boundary_steiner_keeps_boundary_segments_whole() {
    let p = square_with_hole();
    for opts in [
        no_boundary_steiner(None, None),
        no_boundary_steiner(Some(30.0), None),
        no_boundary_steiner(Some(30.0), Some(0.001)),
    ] {
        let m = triangulate(&p, &opts).unwrap();
        m.validate_constrained().unwrap();
        assert_boundary_unsplit(&m);
        assert_eq!(m.segments.len(), 8, "a boundary segment was split");
        assert!((m.area() - 0.96).abs() < 1e-12);
    }
}

/// The square with a hole plus interior points on a 4 x 4 grid around the hole.
fn square_with_hole_and_points() -> Pslg {
    let mut p = square_with_hole();
    for i in 0..4 {
        for j in 0..4 {
            let (x, y) = (0.1 + 0.8 * i as f64 / 3.0, 0.1 + 0.8 * j as f64 / 3.0);
            if !(0.3..=0.7).contains(&x) || !(0.3..=0.7).contains(&y) {
                p.points.push([x, y]);
            }
        }
    }
    p
}

#[test]
fn no_boundary_steiner_refines_away_from_the_boundary() {
    // Interior input points give triangles whose refinement points encroach nothing: those
    // are refined, the rest stay as they are (as in Triangle, where -Y on the bare square with
    // a hole adds no point at all).
    let p = square_with_hole_and_points();
    let m = triangulate(&p, &no_boundary_steiner(Some(30.0), Some(0.002))).unwrap();
    m.validate_constrained().unwrap();
    assert_boundary_unsplit(&m);
    assert_eq!(m.segments.len(), 8);
    assert!(m.steiner_points > 20, "{} Steiner points", m.steiner_points);
    let good = m.triangles.iter().filter(|t| {
        let [a, b, c] = t.map(|v| m.vertices[v as usize]);
        0.5 * crate::geometry::area2(a, b, c) <= 0.002
    });
    assert!(2 * good.count() > m.triangles.len());
}

#[test]
fn no_boundary_steiner_gives_a_constrained_not_a_conforming_mesh() {
    // A thin triangle whose circumcircle holds an input point lying outside the domain, behind
    // the long side: the conforming mesh splits that side, -Y must not.
    let mut p = Pslg::default();
    p.points = vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.1], [1.0, -0.2]];
    p.segments = vec![[0, 1], [1, 2], [2, 0]];
    let m = triangulate(&p, &no_boundary_steiner(None, None)).unwrap();
    assert_eq!((m.triangles.len(), m.steiner_points), (1, 0));
    m.validate_constrained().unwrap();
    let err = m.validate().unwrap_err();
    assert!(err.contains("vertex 3"), "{err}");
    let conforming = triangulate(&p, &Options::default()).unwrap();
    conforming.validate().unwrap();
    assert!(conforming.steiner_points > 0);
}

#[test]
fn no_boundary_steiner_still_splits_interior_segments() {
    // The diagonal has the domain on both sides: -Y may split it, and must where the
    // refinement needs it (a 1:20 rectangle with q30 cannot leave it whole).
    let mut p = Pslg::default();
    p.points = vec![[0.0, 0.0], [20.0, 0.0], [20.0, 1.0], [0.0, 1.0]];
    p.segments = vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]];
    let m = triangulate(&p, &no_boundary_steiner(Some(30.0), None)).unwrap();
    m.validate_constrained().unwrap();
    assert_boundary_unsplit(&m);
    let boundary = m.segments.iter().filter(|e| {
        let (a, b) = (e[0] as usize, e[1] as usize);
        a < 4 && b < 4 && !((a == 0 && b == 2) || (a == 2 && b == 0))
    });
    assert_eq!(boundary.count(), 4);
    assert!(
        m.segments.len() > 5,
        "the interior diagonal was never split"
    );
}

#[test]
fn no_steiner_on_any_segment_keeps_every_segment_whole() {
    let mut p = square_with_hole_and_points();
    let n = p.points.len() as u32;
    p.points.push([0.05, 0.95]);
    p.segments.push([0, n]);
    let opts = Options {
        min_angle: Some(30.0),
        max_area: Some(0.002),
        no_segment_steiner: true,
        ..Options::default()
    };
    let m = triangulate(&p, &opts).unwrap();
    m.validate_constrained().unwrap();
    assert_eq!(m.segments.len(), p.segments.len());
    for e in &m.segments {
        assert!(e.iter().all(|&v| (v as usize) < p.points.len()));
    }
    assert!(m.steiner_points > 10, "{} Steiner points", m.steiner_points);
}

#[test]
fn constrained_insertion_of_a_long_segment() {
    // A segment across a cloud of points crosses many triangles; with no segment split at
    // all it must come out as one edge of a triangulation of exactly the input points.
    let mut p = Pslg::default();
    let mut s: u64 = 11;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    p.points = vec![[-1.0, -1.0], [2.0, -1.0], [2.0, 2.0], [-1.0, 2.0]];
    for _ in 0..400 {
        p.points.push([rnd(), rnd()]);
    }
    p.points.push([-0.5, 0.3]);
    p.points.push([1.5, 0.71]);
    let n = p.points.len() as u32;
    p.segments = vec![[n - 2, n - 1]];
    let opts = Options {
        convex_hull: true,
        ..Options::default()
    };
    let fixed = Options {
        no_segment_steiner: true,
        ..opts.clone()
    };
    let m = triangulate(&p, &fixed).unwrap();
    m.validate_constrained().unwrap();
    assert_eq!(m.steiner_points, 0);
    assert_eq!(m.triangles.len(), 2 * p.points.len() - 2 - 4);
    let has_edge = m.triangles.iter().any(|t| {
        (0..3).any(|i| {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            (a, b) == (n - 2, n - 1) || (a, b) == (n - 1, n - 2)
        })
    });
    assert!(has_edge, "the segment is not an edge");
    // The conforming mesh of the same input is Delaunay and splits the segment.
    let c = triangulate(&p, &opts).unwrap();
    c.validate().unwrap();
    assert!(c.steiner_points > 0);
}

/// Coordinates below 2^-64 are meshed scaled up by a power of two (`geometry::tiny_scale`):
/// the square with a hole at 2^-300 of its size, with a region's area bound, a global one and
/// a sizing test, gets exactly the mesh of the unscaled square scaled down, and it validates
/// (the in-circle test underflows on the raw coordinates).
#[test]
fn tiny_coordinates_mesh_as_their_scaled_up_copy() {
    let s = 2f64.powi(-300);
    let mut g = square_with_hole();
    g.regions = vec![Region {
        point: [0.1, 0.1],
        attribute: 1.0,
        max_area: Some(0.02),
    }];
    let sizing = |scale: f64| -> SizingFn {
        Arc::new(move |a: [f64; 2], _b, _c, area| {
            a[0] < 0.3 * scale && area > 0.004 * scale * scale
        })
    };
    let o = Options {
        min_angle: Some(30.0),
        max_area: Some(0.05),
        region_max_area: true,
        sizing: Some(sizing(1.0)),
        ..Default::default()
    };
    let mut tiny = g.clone();
    for p in tiny.points.iter_mut().chain(tiny.holes.iter_mut()) {
        *p = [p[0] * s, p[1] * s];
    }
    tiny.regions[0].point = [0.1 * s, 0.1 * s];
    tiny.regions[0].max_area = Some(0.02 * s * s);
    let ot = Options {
        max_area: Some(0.05 * s * s),
        sizing: Some(sizing(s)),
        ..o.clone()
    };
    let m = triangulate(&g, &o).unwrap();
    let mt = triangulate(&tiny, &ot).unwrap();
    assert!(m.steiner_points > 20, "{}", m.steiner_points);
    assert_eq!(mt.triangles, m.triangles);
    assert_eq!(mt.segments, m.segments);
    for (p, q) in mt.vertices.iter().zip(&m.vertices) {
        assert_eq!(*p, [q[0] * s, q[1] * s]);
    }
    mt.validate().unwrap();
}

/// The final check splits its passes over threads; what it reports must not depend on how
/// many: the same mesh for every count, a valid mesh passes, and with faults in both halves
/// of the triangles the first one (in triangle order) is named for every count.
#[test]
fn final_check_reports_the_same_for_any_thread_count() {
    let mut o = Options::default();
    o.min_angle = Some(30.0);
    o.max_area = Some(2e-6);
    o.threads = Some(1);
    let m = triangulate(&square_with_hole(), &o).unwrap();
    assert!(
        m.triangles.len() > 4 << 16,
        "{} triangles: too few for four chunks",
        m.triangles.len()
    );
    for threads in [2, 3] {
        o.threads = Some(threads);
        let again = triangulate(&square_with_hole(), &o).unwrap();
        assert_eq!(
            (&again.triangles, &again.vertices),
            (&m.triangles, &m.vertices)
        );
    }
    for threads in [1, 2, 3, 4] {
        validate::validate_final(&m, threads).unwrap();
    }
    let n = m.triangles.len();
    let message = |m: &TriMesh, threads| match validate::validate_final(m, threads) {
        Err(s) => s,
        Ok(()) => panic!("fault not caught with {threads} threads"),
    };
    // Turned triangles (the structure pass), a flipped pair whose far vertices now see each
    // other's circles (the empty-circle pass), and a subsegment that is no edge.
    let mut turned = m.clone();
    turned.triangles[n / 2].swap(0, 1);
    turned.triangles[n - 1].swap(0, 1);
    let first = message(&turned, 1);
    assert!(first.contains(&format!("triangle {} ", n / 2)), "{first}");
    let mut lost = m.clone();
    lost.segments.push([0, 2]);
    let flipped = flip_an_edge(&m, 3 * n / 4);
    let flip_message = message(&flipped, 1);
    assert!(flip_message.contains("circumcircle"), "{flip_message}");
    // Links the fused pass does not read (to earlier triangles): a boundary edge of a late
    // triangle linked to triangle 0, which does not link back (caught by the link counts),
    // and a late triangle's link to an earlier neighbour moved to triangle 0.
    let late = |want: &dyn Fn(u32) -> bool| {
        (n / 2..n)
            .find_map(|t| {
                let i =
                    (0..3).find(|&i| want(m.neighbors[t][i]) && !m.neighbors[t].contains(&0))?;
                Some((t, i))
            })
            .expect("a late triangle with such a link")
    };
    let mut one_sided = m.clone();
    let (t, i) = late(&|x| x == NONE);
    one_sided.neighbors[t][i] = 0;
    let one_sided_message = message(&one_sided, 1);
    assert!(
        one_sided_message.contains(&format!("triangles {t} and 0 are not mutual")),
        "{one_sided_message}"
    );
    let mut moved = m.clone();
    let (t, i) = late(&|x| x != NONE && (x as usize) < n / 4 && x > 0);
    moved.neighbors[t][i] = 0;
    let moved_message = message(&moved, 1);
    assert!(moved_message.contains("not mutual"), "{moved_message}");
    for broken in [turned, lost, flipped, one_sided, moved] {
        let one = message(&broken, 1);
        for threads in [2, 3, 4] {
            assert_eq!(message(&broken, threads), one);
        }
    }
}

#[test]
fn a_thread_count_of_zero_is_refused_before_the_run() {
    let mut o = Options::default();
    o.threads = Some(0);
    match triangulate(&square_with_hole(), &o) {
        Err(crate::Error::InvalidOption(m)) => assert!(m.contains("threads"), "{m}"),
        other => panic!("{other:?}"),
    }
}

/// `m` with the first edge of a triangle from `from` on flipped to the other diagonal of its
/// convex, not cocircular quadrilateral: a valid structure that is not Delaunay.
fn flip_an_edge(m: &TriMesh, from: usize) -> TriMesh {
    use crate::predicates::{incircle, orient2d};
    let mut f = m.clone();
    let p = |v: u32| m.vertices[v as usize];
    for t in from..m.triangles.len() {
        for i in 0..3 {
            let n = m.neighbors[t][i];
            if n == NONE || (n as usize) < t {
                continue;
            }
            let n = n as usize;
            let tri = m.triangles[t];
            let (x, a, b) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
            let j = (0..3).find(|&j| m.neighbors[n][j] == t as u32).unwrap();
            let y = m.triangles[n][j];
            if orient2d(p(x), p(a), p(y)) <= 0.0
                || orient2d(p(y), p(b), p(x)) <= 0.0
                || incircle(p(x), p(a), p(b), p(y)) == 0.0
            {
                continue;
            }
            let (outer_a, outer_b) = (m.neighbors[t][(i + 1) % 3], m.neighbors[t][(i + 2) % 3]);
            let (outer_c, outer_d) = (m.neighbors[n][(j + 1) % 3], m.neighbors[n][(j + 2) % 3]);
            f.triangles[t] = [x, a, y];
            f.neighbors[t] = [outer_c, n as u32, outer_b];
            f.triangles[n] = [y, b, x];
            f.neighbors[n] = [outer_a, t as u32, outer_d];
            for (outer, old, new) in [(outer_a, t, n), (outer_c, n, t)] {
                if outer != NONE {
                    for k in 0..3 {
                        if f.neighbors[outer as usize][k] == old as u32 {
                            f.neighbors[outer as usize][k] = new as u32;
                        }
                    }
                }
            }
            validate::validate_structure(&f, true, 1).unwrap();
            return f;
        }
    }
    panic!("no edge to flip");
}

/// Without segments the run names the points by their insertion rank; the mesh comes back in
/// the input's names: each input point at its own index with its own marker, the same
/// triangles whatever order the points come in, and a duplicate named by input indices.
#[test]
fn a_point_set_comes_back_in_input_names() {
    let n = 500;
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let pts: Vec<[f64; 2]> = (0..n).map(|_| [next(), next()]).collect();
    let mut p = Pslg::default();
    p.points = pts.clone();
    p.point_markers = (0..n as i32).map(|i| i + 10).collect();
    // Triangles as sorted triples of input names.
    let tris = |m: &TriMesh, name: &dyn Fn(u32) -> u32| {
        let mut v: Vec<[u32; 3]> = m
            .triangles
            .iter()
            .map(|t| {
                let mut t = t.map(name);
                t.sort_unstable();
                t
            })
            .collect();
        v.sort_unstable();
        v
    };
    for min_angle in [None, Some(25.0)] {
        let mut o = Options::default();
        o.min_angle = min_angle;
        let m = triangulate(&p, &o).unwrap();
        m.validate().unwrap();
        assert_eq!(&m.vertices[..n], &pts[..]);
        assert_eq!(&m.vertex_markers[..n], &p.point_markers[..]);
        if min_angle.is_some() {
            assert!(m.steiner_points > 0);
            continue;
        }
        let mut r = p.clone();
        r.points.reverse();
        r.point_markers.reverse();
        let back = triangulate(&r, &o).unwrap();
        let last = n as u32 - 1;
        assert_eq!(tris(&m, &|v| v), tris(&back, &|v| last - v));
    }
    let mut d = p.clone();
    d.points.push(pts[17]);
    d.point_markers.push(0);
    match triangulate(&d, &Options::default()) {
        Err(Error::Input(InputError::DuplicatePoint { first, second })) => {
            assert_eq!((first, second), (17, n))
        }
        other => panic!("{other:?}"),
    }
}

/// `find_edge` names the same half-edge, the one directed to its first vertex, whichever
/// triangle around that vertex `vtri` keeps (cavities are seeded from it, so a side that
/// followed `vtri` would make the mesh depend on how `vtri` was last rebuilt).
#[test]
fn find_edge_does_not_depend_on_the_triangle_kept_per_vertex() {
    let mut z: u64 = 7;
    let pts: Vec<[f64; 2]> = (0..40)
        .map(|_| {
            z = z
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            [
                (z >> 40) as f64 / 16.0,
                ((z >> 16) & 0xffffff) as f64 / 16.0,
            ]
        })
        .collect();
    let mut cdt = store::Cdt::new(&pts);
    let o = crate::predicates::orient2d(pts[0], pts[1], pts[2]);
    assert_ne!(o, 0.0);
    if o > 0.0 {
        cdt.init_triangle(0, 1, 2);
    } else {
        cdt.init_triangle(0, 2, 1);
    }
    for v in 3..pts.len() as u32 {
        assert!(matches!(cdt.insert_bulk(v), store::Inserted::Yes(_)));
    }
    cdt.sync_aux();
    let n = pts.len() as u32;
    let mut checked = 0;
    for a in 0..n {
        let fan: Vec<u32> = (0..cdt.tv.len() as u32)
            .filter(|&t| cdt.alive(t) && cdt.tv[t as usize].contains(&a))
            .collect();
        let ends: std::collections::BTreeSet<u32> = fan
            .iter()
            .flat_map(|&t| cdt.tv[t as usize])
            .filter(|&b| b != a && b < n)
            .collect();
        for b in ends {
            let mut found = std::collections::BTreeSet::new();
            for &t in &fan {
                cdt.vtri[a as usize] = t;
                let h = cdt.find_edge(a, b).expect("an edge of the mesh");
                assert_eq!(cdt.edge_ends(h), (b, a), "edge {a}-{b} from triangle {t}");
                found.insert(h);
            }
            assert_eq!(found.len(), 1, "edge {a}-{b}: {found:?}");
            checked += fan.len();
        }
    }
    assert!(checked > 500, "{checked}");
}
