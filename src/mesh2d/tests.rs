//! Unit tests of the 2D core on small inputs; the property tests live in tests/.
#![allow(clippy::field_reassign_with_default)]

use super::*;
use crate::input::{Pslg, Region};

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
#[ignore = "known bug: in a slanted 1000:1 sliver a split point's cavity wraps around the end of \
            the domain through exterior slivers and meets the opposite segment from behind \
            (Error::Internal OnSegment); see issue 2 note"]
fn slanted_sliver_conforms() {
    // Rounding-inverted slivers appear outside this domain; conflict tests on them use their
    // true orientation.
    let p = slanted_sliver();
    let m = triangulate(&p, &Options::default()).unwrap();
    assert_ok(&m, 1e-3);
}

#[test]
#[ignore = "known bug: q30 in a slanted 1000:1 sliver ends in Error::Internal (a split point lands \
            flat against a segment); see issue 2 note"]
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
