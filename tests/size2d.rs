//! Mesh size next to small input angles and thin channels (issue 13, item 5): every member of
//! the family in `tests/data/family2d/` (written by `bench/family2d.py`) is meshed at 30 and
//! 33 degrees, checked independently (conformity, Delaunay, the angle bound for every triangle
//! no small-angle rule exempts: `common::assert_mesh`), and its triangle count must stay within
//! a checked-in bound taken from Triangle 1.6's count on the same file and switches
//! (`python3 bench/quality2d.py` prints both; see bench/RESULTS.md).

mod common;

use common::{assert_mesh, quality, Spec};
use idmesh::Pslg;

/// Reads one of the family's `.poly` files (0-based, no markers, attributes, holes or regions,
/// as `bench/family2d.py` writes them).
fn read_family(name: &str) -> Pslg {
    let path = format!(
        "{}/tests/data/family2d/{name}.poly",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut lines = text
        .lines()
        .map(|l| {
            l.split('#')
                .next()
                .unwrap_or("")
                .split_whitespace()
                .collect::<Vec<_>>()
        })
        .filter(|t| !t.is_empty());
    let mut next = || lines.next().unwrap_or_else(|| panic!("{path}: truncated"));
    let n: usize = next()[0].parse().unwrap();
    let points = (0..n)
        .map(|_| {
            let t = next();
            [t[1].parse().unwrap(), t[2].parse().unwrap()]
        })
        .collect();
    let m: usize = next()[0].parse().unwrap();
    let segments = (0..m)
        .map(|_| {
            let t = next();
            [t[1].parse().unwrap(), t[2].parse().unwrap()]
        })
        .collect();
    Pslg {
        points,
        segments,
        ..Default::default()
    }
}

/// (member, angle, bound). The bound is the smaller of Triangle's triangle counts with
/// `-pq<angle>` and `-pq<angle>D` on the same file (PyPI `triangle` 20250106, Triangle 1.6).
/// Where idmesh does not reach it yet the bound is that count times 1.2 (marked "not yet",
/// with idmesh's ratio when this was written), so that regressions still fail; the code before
/// issue 13 made up to 2.3x on these (slot-200 at 33°: 1791 against 766; tee-3 at 30°: 10040
/// against 211). bench/RESULTS.md has the numbers.
const CASES: &[(&str, f64, usize)] = &[
    ("channel-100", 30.0, 128),
    ("channel-100", 33.0, 256),
    ("comb-8", 30.0, 288 * 12 / 10), // not yet: 1.12x
    ("comb-8", 33.0, 296 * 12 / 10), // not yet: 1.08x
    ("fan-6", 30.0, 124 * 12 / 10),  // not yet: 1.16x
    ("fan-6", 33.0, 167),
    ("slot-50", 30.0, 174),
    ("slot-50", 33.0, 246 * 12 / 10),  // not yet: 1.10x
    ("slot-200", 30.0, 406 * 12 / 10), // not yet: 1.09x
    ("slot-200", 33.0, 766),
    ("slot-1000", 30.0, 2234),
    ("slot-1000", 33.0, 2455),
    ("star-5-10", 30.0, 79 * 12 / 10), // not yet: 1.05x
    ("star-5-10", 33.0, 124),
    ("star-8-5", 30.0, 136),
    ("star-8-5", 33.0, 150),
    ("star-12-mixed", 30.0, 175 * 12 / 10), // not yet: 1.05x
    ("star-12-mixed", 33.0, 196),
    ("tee-3", 30.0, 211 * 12 / 10), // not yet: 1.19x
    ("tee-3", 33.0, 318),
    ("wedge-2", 30.0, 42),
    ("wedge-2", 33.0, 52 * 12 / 10), // not yet: 1.02x
    ("wedge-10", 30.0, 11),
    ("wedge-10", 33.0, 28 * 12 / 10), // not yet: 1.14x
];

#[test]
fn family_meshes_within_triangles_count_and_angle_bound() {
    let mut over = Vec::new();
    for &(name, angle, bound) in CASES {
        let pslg = read_family(name);
        let (mesh, report) = assert_mesh(&pslg, &quality(angle), &Spec::default());
        assert!(mesh.complete, "{name} q{angle}: refinement incomplete");
        // Triangles below the bound are only the exempt ones (the checker fails otherwise);
        // the smallest angle of the rest meets the bound.
        assert!(
            report.min_angle_unexempt >= angle - 1e-9,
            "{name} q{angle}: {}° outside the small-angle exemptions",
            report.min_angle_unexempt
        );
        if mesh.triangles.len() > bound {
            over.push(format!(
                "{name} q{angle}: {} > {bound}",
                mesh.triangles.len()
            ));
        }
    }
    assert!(over.is_empty(), "more triangles than the bound: {over:?}");
}

#[test]
fn family_covers_what_it_claims() {
    // The family holds sharp input angles (below 10 degrees) and thin channels (1:1000): a
    // guard against a regenerated family that lost its hard cases.
    let star = read_family("star-12-mixed");
    let sharp = star.points.iter().enumerate().any(|(i, &p)| {
        let n = star.points.len();
        let (a, b) = (star.points[(i + n - 1) % n], star.points[(i + 1) % n]);
        let (u, v) = ([a[0] - p[0], a[1] - p[1]], [b[0] - p[0], b[1] - p[1]]);
        let ang = (u[0] * v[1] - u[1] * v[0])
            .abs()
            .atan2(u[0] * v[0] + u[1] * v[1]);
        ang.to_degrees() < 5.0
    });
    assert!(sharp, "star-12-mixed has no spike below 5 degrees");
    let slot = read_family("slot-1000");
    let ys: Vec<f64> = slot.points.iter().map(|p| p[1].abs()).collect();
    let narrow = ys.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(
        narrow <= 0.5 / 1000.0 + 1e-15,
        "slot-1000 channel half-width {narrow}"
    );
}
