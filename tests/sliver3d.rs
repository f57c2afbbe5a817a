//! Property tests of 3D sliver removal (`src/mesh3d/plc/sliver.rs`): on generated domains with
//! no input angle below 60° (boxes, prisms over nearly regular polygons, i.e. cylinders, a
//! randomly perturbed subdivided icosahedron, and the random boxes and stacked boxes of
//! `prop3d.rs`'s kind), meshing with a radius-edge bound and the default minimum dihedral
//! target must give every tetrahedron dihedral angles within [15°, 165°] (no tetrahedron is
//! exempt: there is no small input angle), a complete mesh, and a mesh that passes the exact
//! `validate()` (Delaunay) and the independent Delaunay check of `common3d`. The same holds for
//! prisms with a low pyramid on top, whose apex has input angles below 60° (fan angles of a
//! nearly flat surface) but none below the target.

mod common3d;

use std::f64::consts::TAU;

use common3d::{add_box, check_delaunay, prism_plc, Frame};
use idmesh::mesh3d::DEFAULT_MIN_DIHEDRAL;
use idmesh::{tetrahedralize, Error, Facet, Options3, Plc, TetMesh};
use proptest::prelude::*;

fn config(cases: u32) -> ProptestConfig {
    common3d::proptest_config(cases, 0x5117_e3d0)
}

/// Rounds to a multiple of `2^-bits`.
fn q(x: f64, bits: i32) -> f64 {
    let s = 2f64.powi(bits);
    (x * s).round() / s
}

/// The options under test: radius-edge `rho`, a volume bound of `volume / parts`, the default
/// (or given) dihedral target, a Steiner guard.
fn opts(rho: f64, volume: f64, parts: f64, target: Option<f64>) -> Options3 {
    Options3 {
        radius_edge: Some(rho),
        max_volume: Some(volume / parts),
        min_dihedral: target,
        max_steiner: Some(200_000),
        ..Options3::default()
    }
}

/// Meshes and checks: complete, valid and Delaunay (exact, and independently), every dihedral
/// angle within the target.
fn mesh_within(plc: &Plc, o: &Options3) -> Result<TetMesh, TestCaseError> {
    let mesh = tetrahedralize(plc, o).map_err(|e| TestCaseError::fail(e.to_string()))?;
    prop_assert!(
        mesh.complete,
        "incomplete ({} Steiner points)",
        mesh.steiner_points
    );
    mesh.validate()
        .map_err(|e| TestCaseError::fail(e.to_string()))?;
    check_delaunay(&mesh).map_err(TestCaseError::fail)?;
    let target = o.min_dihedral.unwrap_or(DEFAULT_MIN_DIHEDRAL);
    let s = mesh.stats();
    prop_assert!(
        s.min_dihedral >= target && s.max_dihedral <= 180.0 - target,
        "dihedral angles {}..{} outside {target}..{} ({} tets)\noptions: {o:?}",
        s.min_dihedral,
        s.max_dihedral,
        180.0 - target,
        mesh.tets.len()
    );
    Ok(mesh)
}

/// A prism over a polygon of `n` vertices at angles `2πi/n + jitter`, radii `1 ± jitter`
/// (nearly regular: every interior angle is well above 90°), height `h`.
fn cylinder(n: usize, jitter: &[(f64, f64)], h: f64, frame: &Frame) -> Plc {
    let outer: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let (da, dr) = jitter[i % jitter.len()];
            let a = TAU * (i as f64 + 0.1 * da) / n as f64;
            let r = 1.0 + 0.05 * dr;
            [q(r * a.cos(), 20), q(r * a.sin(), 20)]
        })
        .collect();
    prism_plc(&outer, None, 0.0, q(h, 8), frame)
}

/// The icosahedron subdivided once (42 vertices, 80 triangles) with vertex `i` at radius
/// `radii[i]`, coordinates rounded to dyadic numbers (triangular facets are always planar).
fn icosphere(radii: &[f64]) -> Plc {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut pts: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let faces: [[usize; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut mid = std::collections::HashMap::new();
    let mut tris = Vec::new();
    for f in faces {
        let mut m = [0usize; 3];
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            m[k] = *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                pts.push([0, 1, 2].map(|i| 0.5 * (pts[a][i] + pts[b][i])));
                pts.len() - 1
            });
        }
        tris.extend([
            [f[0], m[0], m[2]],
            [f[1], m[1], m[0]],
            [f[2], m[2], m[1]],
            [m[0], m[1], m[2]],
        ]);
    }
    let points = pts
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            p.map(|x| q(x / n * radii[i % radii.len()], 24))
        })
        .collect();
    Plc {
        points,
        facets: tris
            .into_iter()
            .map(|t| Facet {
                polygons: vec![t.iter().map(|&v| v as u32).collect()],
                holes: Vec::new(),
                marker: 1,
            })
            .collect(),
        ..Plc::default()
    }
}

proptest! {
    #![proptest_config(config(24))]

    /// Boxes of random proportions (up to 1:4), radius-edge 1.414 or 2.0.
    #[test]
    fn boxes_have_no_slivers(
        ext in [0.25..1.0f64, 0.25..1.0f64, 0.25..1.0f64],
        loose in any::<bool>(),
        parts in 100.0..600.0f64,
    ) {
        let hi = ext.map(|x| q(x, 8));
        let mut plc = Plc::default();
        add_box(&mut plc, [0.0; 3], hi, 1);
        let rho = if loose { 2.0 } else { 1.414 };
        mesh_within(&plc, &opts(rho, hi[0] * hi[1] * hi[2], parts, None))?;
    }

    /// Two stacked boxes sharing a facet (an internal facet: slivers against it on both sides).
    #[test]
    fn stacked_boxes_have_no_slivers(
        ext in [0.25..1.0f64, 0.25..1.0f64, 0.25..1.0f64],
        top in 0.25..1.0f64,
    ) {
        let hi = ext.map(|x| q(x, 8));
        let z = [0.0, hi[2], hi[2] + q(top, 8)];
        let mut plc = Plc::default();
        for &zk in &z {
            for [x, y] in [[0.0, 0.0], [hi[0], 0.0], [hi[0], hi[1]], [0.0, hi[1]]] {
                plc.points.push([x, y, zk]);
            }
        }
        let mut facet = |p: Vec<u32>| {
            plc.facets.push(Facet { polygons: vec![p], holes: Vec::new(), marker: 1 })
        };
        for level in 0..3u32 {
            facet((0..4).map(|i| 4 * level + i).collect());
        }
        for level in 0..2u32 {
            for i in 0..4u32 {
                let (a, b) = (4 * level + i, 4 * level + (i + 1) % 4);
                facet(vec![a, b, b + 4, a + 4]);
            }
        }
        mesh_within(&plc, &opts(1.414, hi[0] * hi[1] * z[2], 300.0, None))?;
    }

    /// Cylinders: prisms over nearly regular polygons of 8 to 20 sides, some under an exact
    /// rotation (slanted facets, rounded Steiner points on them).
    #[test]
    fn cylinders_have_no_slivers(
        n in 8usize..=20,
        jitter in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 1..=20),
        h in 0.5..3.0f64,
        target in prop_oneof![Just(None), Just(Some(10.0)), Just(Some(18.0))],
        rot in prop::option::of((6i64..=10, -2i64..=2, -2i64..=2, 1i64..=2)),
    ) {
        let frame = rot.map_or_else(Frame::identity, |(w, x, y, z)| Frame::quaternion(w, x, y, z));
        let plc = cylinder(n, &jitter, h, &frame);
        mesh_within(&plc, &opts(1.414, std::f64::consts::PI * h, 300.0, target))?;
    }

    /// A sphere-like polyhedron: the subdivided icosahedron with radii perturbed by up to 8 %.
    #[test]
    fn perturbed_icospheres_have_no_slivers(
        radii in prop::collection::vec(0.92..1.08f64, 42),
    ) {
        let plc = icosphere(&radii);
        mesh_within(&plc, &opts(1.414, 4.0, 400.0, None))?;
    }
}

/// A prism over a regular `n`-gon of radius 1 and height `h` whose top is a low pyramid: `n`
/// triangles from the top rim to an apex `dome` above it. Each triangle is its own facet (not
/// coplanar with its neighbours), as in a triangulated CAD surface: two top rim edges to the
/// apex two triangles apart meet at `720°/n`, below 60° without sharing a facet, and each
/// triangle's corner at the apex is `360°/n`, so the radius-edge rule counts the apex (and
/// its protection ball) as sharp; with `n < 24` no two input edges meet below 15° there.
fn domed_prism(n: usize, dome: f64, h: f64) -> Plc {
    let rim = |z: f64| {
        (0..n).map(move |i| {
            let a = TAU * i as f64 / n as f64;
            [q(a.cos(), 20), q(a.sin(), 20), z]
        })
    };
    let mut plc = Plc::default();
    plc.points.extend(rim(0.0));
    plc.points.extend(rim(q(h, 8)));
    plc.points.push([0.0, 0.0, q(h + dome, 12)]);
    let n = n as u32;
    let mut facet = |p: Vec<u32>, marker: i32| {
        plc.facets.push(Facet {
            polygons: vec![p],
            holes: Vec::new(),
            marker,
        })
    };
    facet((0..n).collect(), 1);
    for i in 0..n {
        let (a, b) = (i, (i + 1) % n);
        facet(vec![a, b, b + n, a + n], 2);
        facet(vec![a + n, b + n, 2 * n], 3);
    }
    plc
}

/// Slivers next to the apex of a domed prism are removed: its fan angles (wider than the
/// target) excuse none (they once did: `n = 16`, `dome = 0.05` left 11 slivers down to 0.6°,
/// "exempt next to small input angles").
#[test]
fn fan_angles_excuse_no_sliver() {
    for n in [14, 16, 18, 20] {
        for dome in [0.05, 0.1] {
            for parts in [None, Some(300.0), Some(3000.0)] {
                let plc = domed_prism(n, dome, 1.0);
                let mut o = opts(1.414, std::f64::consts::PI, parts.unwrap_or(1.0), None);
                if parts.is_none() {
                    o.max_volume = None;
                }
                if let Err(e) = mesh_within(&plc, &o) {
                    panic!("n = {n}, dome = {dome}, parts = {parts:?}: {e}");
                }
            }
        }
    }
}

/// Tets refined after the sliver pass are held to the target too: in this rotated 15-gon
/// prism (found by a property test) the full classification after the pass corrects the
/// regions of hundreds of rounding slivers on the slanted facets, and the tets refined then
/// kept a dihedral angle of 13.4° against the target of 18° when the pass did not run again.
#[test]
fn tets_refined_after_the_sliver_pass_meet_the_target() {
    let jitter = [
        (-0.07711946417596226, 0.0),
        (-0.061994083341126, 0.9434459888432276),
        (-0.7829951031428659, -0.9005011601113089),
        (0.0, 0.0),
    ];
    let h = 2.1499763802005267;
    let plc = cylinder(15, &jitter, h, &Frame::quaternion(9, 2, 2, 1));
    let o = opts(1.414, std::f64::consts::PI * h, 300.0, Some(18.0));
    if let Err(e) = mesh_within(&plc, &o) {
        panic!("{e}");
    }
}

/// A sliver whose first candidate points all make a new sliver gets more of them: this domed
/// prism (found by a property test) ran out of sliver rounds with one of 5.9° left when each
/// sliver had 13 candidates. Its apex has input angles of 17° (21 dome facets), and the
/// refinement reaches deep into the apex's protection ball, where a tet is exempt whatever
/// its angles (`Sharp::deep_in_ball`: removing it would make a smaller one closer to the
/// apex); every other tet meets the target.
#[test]
fn hard_slivers_get_more_candidates() {
    let (h, dome) = (1.2105159808464607, 0.11836250407785101);
    let plc = domed_prism(21, dome, h);
    let apex = plc.points[42];
    let o = opts(1.414, std::f64::consts::PI * h, 3000.0, None);
    let mesh = tetrahedralize(&plc, &o).unwrap();
    assert!(
        mesh.complete,
        "incomplete ({} Steiner points)",
        mesh.steiner_points
    );
    mesh.validate().unwrap();
    check_delaunay(&mesh).unwrap();
    let target = DEFAULT_MIN_DIHEDRAL;
    let mut near_apex = 0;
    for t in 0..mesh.tets.len() {
        let c = mesh.corners(t);
        let (lo, hi) = idmesh::geometry::tet_dihedral_range(c);
        if lo >= target && hi <= 180.0 - target {
            continue;
        }
        let far = c
            .iter()
            .map(|p| (0..3).map(|k| (p[k] - apex[k]).powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        // The domain is about 2 wide; the shells around the apex are far inside 1/50 of that.
        assert!(
            far < 0.04,
            "tet {t} with dihedral angles {lo}..{hi} reaches {far} from the apex"
        );
        near_apex += 1;
    }
    // A handful, however the refinement happens to approach the apex (4 to 6 so far).
    assert!(
        near_apex <= 8,
        "{near_apex} tets next to the apex outside the target"
    );
}

/// The default target is on with a radius-edge bound, and `Some(0.0)` turns it off: the same
/// input then keeps slivers (so the property tests above test something), and the sliver-free
/// mesh has at most 1.25 times as many tetrahedra.
#[test]
fn target_zero_turns_removal_off() {
    let mut plc = Plc::default();
    add_box(&mut plc, [0.0; 3], [1.0; 3], 1);
    let off = tetrahedralize(&plc, &opts(1.414, 1.0, 2000.0, Some(0.0))).unwrap();
    let on = tetrahedralize(&plc, &opts(1.414, 1.0, 2000.0, None)).unwrap();
    let (s_off, s_on) = (off.stats(), on.stats());
    assert!(s_off.min_dihedral < 10.0, "{}", s_off.min_dihedral);
    assert!(
        s_on.min_dihedral >= DEFAULT_MIN_DIHEDRAL,
        "{}",
        s_on.min_dihedral
    );
    assert!(s_on.max_dihedral <= 180.0 - DEFAULT_MIN_DIHEDRAL);
    assert!(
        on.tets.len() as f64 <= 1.25 * off.tets.len() as f64,
        "{} tets with sliver removal, {} without",
        on.tets.len(),
        off.tets.len()
    );
    on.validate().unwrap();
    // Without a radius-edge bound there is no target.
    let plain = Options3 {
        max_volume: Some(0.01),
        ..Options3::default()
    };
    let m = tetrahedralize(&plc, &plain).unwrap();
    let with_target = Options3 {
        min_dihedral: Some(20.0),
        ..plain
    };
    assert_eq!(tetrahedralize(&plc, &with_target).unwrap().tets, m.tets);
}

/// Targets outside 0..=70 degrees (and NaN) are invalid options.
#[test]
fn impossible_targets_are_refused() {
    let mut plc = Plc::default();
    add_box(&mut plc, [0.0; 3], [1.0; 3], 1);
    for a in [-1.0, 71.0, f64::NAN, f64::INFINITY] {
        let r = tetrahedralize(&plc, &opts(1.414, 1.0, 10.0, Some(a)));
        assert!(
            matches!(r, Err(Error::InvalidOption(ref m)) if m.contains("dihedral")),
            "{a}: {:?}",
            r.err()
        );
    }
}
