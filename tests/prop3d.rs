//! Property tests of the 3D mesher on random PLCs: axis-aligned boxes (some flat), prisms over
//! random star-shaped polygons with and without a polygonal hole through them, two stacked boxes
//! sharing a facet (two regions with attributes), and a box split by an internal facet; each
//! optionally under a small random rotation (slanted facets). Every case is meshed with no
//! quality bound, with radius-edge 2.0, and with radius-edge 1.414 plus a volume bound of a
//! 500th of the domain, and judged by the independent checker in `common3d`; some also keeping
//! the surface (-Y, with no bound and with the last set's), where the checker asserts that no
//! Steiner point lies on the surface instead of the Delaunay property.
//!
//! Rotations are exact: the integer matrix of a quaternion with small integer entries, divided
//! by a power of two, applied to dyadic coordinates, so facets stay exactly planar (idmesh
//! demands exact planarity). The domain is known analytically in the unrotated frame: the
//! checker compares the total volume with it and classifies every tet centroid against it.
//!
//! Generators draw raw numbers; the PLC is built from them deterministically, so proptest
//! shrinks towards fewer polygon vertices and simpler frames. A failure message carries the
//! shrunk input as a Rust `Plc` literal.

mod common3d;

use std::f64::consts::TAU;

use common3d::{
    add_box, inside2, mesh_and_check, prism_plc, Cell, Domain, Frame, Report3, Spec3, P3,
};
use idmesh::{Facet, Options3, Plc, Region3};
use proptest::prelude::*;

/// Fixed seed for reproducible CI runs; `PROPTEST_SEED` and `PROPTEST_CASES` override.
fn config(cases: u32) -> ProptestConfig {
    common3d::proptest_config(cases, 0x3d3e_5a11)
}

/// Rounds to a multiple of `2^-bits`.
fn q(x: f64, bits: i32) -> f64 {
    let s = 2f64.powi(bits);
    (x * s).round() / s
}

/// Frames: `None` (no rotation), or the quaternion `(w, x, y, z)` with `w` in 6..=10 and the
/// others in -2..=2, not all zero: rotations by up to about 40 degrees.
type FrameRaw = Option<(i64, i64, i64, i64)>;

fn frame(rotated: bool) -> BoxedStrategy<FrameRaw> {
    if rotated {
        (6i64..=10, -2i64..=2, -2i64..=2, -2i64..=2)
            .prop_filter("a rotation", |r| (r.1, r.2, r.3) != (0, 0, 0))
            .prop_map(Some)
            .boxed()
    } else {
        Just(None).boxed()
    }
}

fn make_frame(f: FrameRaw) -> Frame {
    match f {
        None => Frame::identity(),
        Some((w, x, y, z)) => Frame::quaternion(w, x, y, z),
    }
}

/// The three option sets of the brief, then keeping the surface (-Y) without and with the
/// third set's bounds.
fn option_sets(volume: f64) -> [Options3; 5] {
    let guard = Options3 {
        max_steiner: Some(200_000),
        ..Options3::default()
    };
    [
        guard.clone(),
        Options3 {
            radius_edge: Some(2.0),
            ..guard.clone()
        },
        Options3 {
            radius_edge: Some(1.414),
            max_volume: Some(volume / 500.0),
            ..guard.clone()
        },
        Options3 {
            keep_surface: true,
            ..guard.clone()
        },
        Options3 {
            radius_edge: Some(1.414),
            max_volume: Some(volume / 500.0),
            keep_surface: true,
            ..guard
        },
    ]
}

/// Meshes under the three option sets and checks each.
fn run(
    plc: &Plc,
    domain: Domain,
    strict: bool,
    attributes: bool,
    mode: usize,
) -> Result<Report3, TestCaseError> {
    let o = &option_sets(1.0)[mode];
    let spec = Spec3 {
        // Keeping the surface, the bounds are not met next to it (as in TetGen).
        check_quality: strict && !o.keep_surface,
        tol: common3d::tolerance(plc),
        domain: Some(domain),
        timeout: std::time::Duration::from_secs(30),
        ..Spec3::default()
    };
    let vol = spec.domain.as_ref().unwrap().volume();
    let mut o = option_sets(vol)[mode].clone();
    o.region_attributes = attributes;
    {
        let (mesh, rep) = mesh_and_check(plc, &o, &spec).map_err(TestCaseError::fail)?;
        prop_assert!(
            mesh.complete,
            "refinement stopped at the Steiner guard ({} Steiner points)\noptions: {o:?}\ninput:\n{}",
            rep.steiner,
            common3d::plc_rust(plc)
        );
        Ok(rep)
    }
}

// ------------------------------------------------------------------------------------ boxes

/// Corner, extents, an optional flat axis (its extent divided by 8), a frame.
type BoxRaw = ([f64; 3], [f64; 3], Option<usize>, FrameRaw);

fn box_raw(rotated: bool) -> impl Strategy<Value = BoxRaw> {
    (
        [-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64],
        [1.0..2.5f64, 1.0..2.5f64, 1.0..2.5f64],
        prop_oneof![2 => Just(None), 1 => (0usize..3).prop_map(Some)],
        frame(rotated),
    )
}

fn build_box(raw: &BoxRaw) -> (Plc, Domain) {
    let (c, e, flat, f) = raw;
    let lo = c.map(|x| q(x, 4));
    let mut ext = e.map(|x| q(x, 4));
    if let Some(k) = flat {
        ext[*k] = q(ext[*k] / 8.0, 6).max(1.0 / 16.0);
    }
    let hi = [0, 1, 2].map(|k| lo[k] + ext[k]);
    let frame = make_frame(*f);
    let mut plc = Plc::default();
    add_box(&mut plc, lo, hi, 1);
    for p in &mut plc.points {
        *p = frame.apply(*p);
    }
    (
        plc,
        Domain {
            cells: vec![Cell::cuboid(lo, hi, 0.0)],
            frame,
        },
    )
}

// ----------------------------------------------------------------------------------- prisms

/// Outer star polygon (per vertex: angular jitter, radius fraction), phase, height, optional
/// hole star polygon (same) with its size fraction, frame.
type PrismRaw = (
    Vec<(f64, f64)>,
    f64,
    f64,
    Option<(Vec<(f64, f64)>, f64)>,
    FrameRaw,
);

fn prism_raw(rotated: bool) -> impl Strategy<Value = PrismRaw> {
    (
        // Star polygons, and nearly regular ones (mostly free of angles below 90 degrees, so
        // that the bounds are asserted on a good share of the cases).
        prop_oneof![
            prop::collection::vec((0.0..0.5f64, 0.0..1.0f64), 3..=9),
            prop::collection::vec((0.0..0.15f64, 0.85..1.0f64), 5..=9),
        ],
        0.0..TAU,
        0.5..2.0f64,
        prop::option::of((
            prop::collection::vec((0.0..0.4f64, 0.0..1.0f64), 4..=6),
            0.3..1.0f64,
        )),
        frame(rotated),
    )
}

/// A polygon star-shaped around the origin, angles strictly increasing, quantized.
fn star(raw: &[(f64, f64)], rmin: f64, rmax: f64, phase: f64) -> Vec<[f64; 2]> {
    let n = raw.len() as f64;
    raw.iter()
        .enumerate()
        .map(|(i, &(j, f))| {
            let a = phase + TAU * (i as f64 + j) / n;
            let r = rmin + (rmax - rmin) * f;
            [q(r * a.cos(), 6), q(r * a.sin(), 6)]
        })
        .collect()
}

/// Distance from the origin to the nearest edge of `poly`.
fn inradius(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let a = poly[i];
            let b = poly[(i + 1) % n];
            let d = [b[0] - a[0], b[1] - a[1]];
            let l2 = d[0] * d[0] + d[1] * d[1];
            let t = (-(a[0] * d[0] + a[1] * d[1]) / l2).clamp(0.0, 1.0);
            let p = [a[0] + t * d[0], a[1] + t * d[1]];
            p[0].hypot(p[1])
        })
        .fold(f64::INFINITY, f64::min)
}

/// Interior angles of a counter-clockwise polygon, degrees (reflex ones above 180).
fn interior_angles(poly: &[[f64; 2]]) -> Vec<f64> {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let p = poly[(i + n - 1) % n];
            let o = poly[i];
            let r = poly[(i + 1) % n];
            let u = [p[0] - o[0], p[1] - o[1]];
            let v = [r[0] - o[0], r[1] - o[1]];
            // Angle from v (to the next vertex) counter-clockwise round to u (the previous).
            let a = (v[0] * u[1] - v[1] * u[0]).atan2(v[0] * u[0] + v[1] * u[1]);
            let a = if a < 0.0 { a + TAU } else { a };
            a.to_degrees()
        })
        .collect()
}

/// The prism PLC, its domain, and whether it has no input angle below 90 degrees.
fn build_prism(raw: &PrismRaw) -> Option<(Plc, Domain, bool)> {
    let (oraw, phase, h, hole, f) = raw;
    let outer = star(oraw, 0.6, 1.6, *phase);
    if !inside2(&outer, [0.0, 0.0]) {
        return None;
    }
    let z1 = q(*h, 4);
    let hole = match hole {
        Some((hraw, frac)) => {
            let r = 0.7 * inradius(&outer) - 0.05;
            if r < 0.2 {
                return None;
            }
            let hp = star(hraw, 0.5 * r * frac, r * frac, 0.0);
            if !inside2(&hp, [0.0, 0.0]) || inradius(&hp) < 0.02 {
                return None;
            }
            Some(hp)
        }
        None => None,
    };
    let frame = make_frame(*f);
    let plc = prism_plc(
        &outer,
        hole.as_deref().map(|h| (h, [0.0, 0.0])),
        0.0,
        z1,
        &frame,
    );
    let mut min_angle = interior_angles(&outer)
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    if let Some(hp) = &hole {
        for a in interior_angles(hp) {
            min_angle = min_angle.min(360.0 - a);
        }
    }
    let dom = Domain {
        cells: vec![Cell {
            outer,
            holes: hole.into_iter().collect(),
            z0: 0.0,
            z1,
            attribute: 0.0,
        }],
        frame,
    };
    Some((plc, dom, min_angle >= 90.0))
}

// ---------------------------------------------------------------------- stacked boxes

/// Lower box extents, upper box height, optional inset of the upper box's footprint (four
/// fractions), frame.
type StackRaw = ([f64; 3], f64, Option<[f64; 4]>, FrameRaw);

fn stack_raw(rotated: bool, inset: bool) -> impl Strategy<Value = StackRaw> {
    let inset = if inset {
        [0.1..0.4f64, 0.1..0.4f64, 0.1..0.4f64, 0.1..0.4f64]
            .prop_map(Some)
            .boxed()
    } else {
        Just(None).boxed()
    };
    (
        [1.0..2.5f64, 1.0..2.5f64, 0.5..1.5f64],
        0.5..1.5f64,
        inset,
        frame(rotated),
    )
}

fn push_facet(plc: &mut Plc, polygons: Vec<Vec<u32>>, holes: Vec<P3>, marker: i32) {
    plc.facets.push(Facet {
        polygons,
        holes,
        marker,
    });
}

/// The corners of the rectangle `[x0, x1] × [y0, y1]` at height `z`, counter-clockwise, as new
/// points.
fn rect(plc: &mut Plc, x: [f64; 2], y: [f64; 2], z: f64, frame: &Frame) -> Vec<u32> {
    let o = plc.points.len() as u32;
    for p in [[x[0], y[0]], [x[1], y[0]], [x[1], y[1]], [x[0], y[1]]] {
        plc.points.push(frame.apply([p[0], p[1], z]));
    }
    (o..o + 4).collect()
}

/// The four side quads between two counter-clockwise loops of four.
fn sides(plc: &mut Plc, b: &[u32], t: &[u32], marker: i32) {
    for i in 0..4 {
        let j = (i + 1) % 4;
        push_facet(plc, vec![vec![b[i], b[j], t[j], t[i]]], vec![], marker);
    }
}

fn build_stack(raw: &StackRaw) -> (Plc, Domain) {
    let (e, bh, inset, f) = raw;
    let (ax, ay, az) = (q(e[0], 4), q(e[1], 4), q(e[2], 4));
    let z2 = az + q(*bh, 4);
    let frame = make_frame(*f);
    let mut plc = Plc::default();
    let a_bot = rect(&mut plc, [0.0, ax], [0.0, ay], 0.0, &frame);
    let a_top = rect(&mut plc, [0.0, ax], [0.0, ay], az, &frame);
    push_facet(&mut plc, vec![a_bot.clone()], vec![], 1);
    sides(&mut plc, &a_bot, &a_top, 2);
    let (bx, by) = match inset {
        None => ([0.0, ax], [0.0, ay]),
        Some(s) => (
            [q(s[0] * ax, 4), ax - q(s[1] * ax, 4)],
            [q(s[2] * ay, 4), ay - q(s[3] * ay, 4)],
        ),
    };
    let b_bot = if inset.is_some() {
        let b = rect(&mut plc, bx, by, az, &frame);
        // The lower box's top: a ring (outer loop, inner loop, seed inside the inner loop).
        let seed = frame.apply([0.5 * (bx[0] + bx[1]), 0.5 * (by[0] + by[1]), az]);
        push_facet(&mut plc, vec![a_top.clone(), b.clone()], vec![seed], 3);
        b
    } else {
        a_top.clone()
    };
    // The shared facet.
    push_facet(&mut plc, vec![b_bot.clone()], vec![], 4);
    let b_top = rect(&mut plc, bx, by, z2, &frame);
    sides(&mut plc, &b_bot, &b_top, 5);
    push_facet(&mut plc, vec![b_top], vec![], 6);
    let ca = Cell::cuboid([0.0, 0.0, 0.0], [ax, ay, az], 1.0);
    let cb = Cell::cuboid([bx[0], by[0], az], [bx[1], by[1], z2], 2.0);
    for c in [&ca, &cb] {
        let m = [
            0.5 * (c.outer[0][0] + c.outer[2][0]),
            0.5 * (c.outer[0][1] + c.outer[2][1]),
            0.5 * (c.z0 + c.z1),
        ];
        plc.regions.push(Region3 {
            point: frame.apply(m),
            attribute: c.attribute,
            max_volume: None,
        });
    }
    (
        plc,
        Domain {
            cells: vec![ca, cb],
            frame,
        },
    )
}

// ------------------------------------------------------------------- internal facet

/// Box extents, split position fraction, whether the side facets are hexagons with the split
/// edge as a 2-vertex polygon (else two quads each), frame.
type SplitRaw = ([f64; 3], f64, bool, FrameRaw);

fn split_raw(rotated: bool) -> impl Strategy<Value = SplitRaw> {
    (
        [1.0..2.5f64, 1.0..2.5f64, 1.0..2.5f64],
        0.2..0.8f64,
        any::<bool>(),
        frame(rotated),
    )
}

fn build_split(raw: &SplitRaw) -> (Plc, Domain) {
    let (e, t, hex, f) = raw;
    let (ax, ay, az) = (q(e[0], 4), q(e[1], 4), q(e[2], 4));
    let xt = q(t * ax, 4).clamp(0.125, ax - 0.125);
    let frame = make_frame(*f);
    let mut plc = Plc::default();
    // Points: index 4*i + (corner in the yz-plane) at x = [0, xt, ax][i], corners
    // (y, z) = (0,0), (ay,0), (ay,az), (0,az).
    for x in [0.0, xt, ax] {
        for (y, z) in [(0.0, 0.0), (ay, 0.0), (ay, az), (0.0, az)] {
            plc.points.push(frame.apply([x, y, z]));
        }
    }
    let at = |i: u32, c: u32| 4 * i + c;
    push_facet(
        &mut plc,
        vec![(0..4).map(|c| at(0, c)).collect()],
        vec![],
        1,
    );
    push_facet(
        &mut plc,
        vec![(0..4).map(|c| at(2, c)).collect()],
        vec![],
        2,
    );
    // The internal facet.
    push_facet(
        &mut plc,
        vec![(0..4).map(|c| at(1, c)).collect()],
        vec![],
        7,
    );
    for c in 0..4 {
        let d = (c + 1) % 4;
        if *hex {
            push_facet(
                &mut plc,
                vec![
                    vec![at(0, c), at(1, c), at(2, c), at(2, d), at(1, d), at(0, d)],
                    vec![at(1, c), at(1, d)],
                ],
                vec![],
                3,
            );
        } else {
            for i in 0..2 {
                push_facet(
                    &mut plc,
                    vec![vec![at(i, c), at(i + 1, c), at(i + 1, d), at(i, d)]],
                    vec![],
                    3,
                );
            }
        }
    }
    let c0 = Cell::cuboid([0.0; 3], [xt, ay, az], 3.0);
    let c1 = Cell::cuboid([xt, 0.0, 0.0], [ax, ay, az], 4.0);
    for (x, a) in [(0.5 * xt, 3.0), (0.5 * (xt + ax), 4.0)] {
        plc.regions.push(Region3 {
            point: frame.apply([x, 0.5 * ay, 0.5 * az]),
            attribute: a,
            max_volume: None,
        });
    }
    (
        plc,
        Domain {
            cells: vec![c0, c1],
            frame,
        },
    )
}

// ------------------------------------------------------------------------------ properties

/// Cases per property (each case is one mesh); `PROPTEST_CASES` overrides.
const CASES: u32 = 32;

/// One property: a generator, whether it is rotated, one option set. `$build` maps the raw
/// value to `Option<(plc, domain, strict)>`, `None` rejecting the case.
macro_rules! property {
    ($(#[$m:meta])* $name:ident, $strategy:expr, |$raw:ident| $build:expr, $attrs:expr, $mode:expr) => {
        proptest! {
            #![proptest_config(config(CASES))]
            $(#[$m])*
            #[test]
            fn $name($raw in $strategy) {
                let Some((plc, dom, strict)) = $build else {
                    return Err(TestCaseError::reject("degenerate input"));
                };
                run(&plc, dom, strict, $attrs, $mode)?;
            }
        }
    };
}

fn boxed(raw: &BoxRaw) -> Option<(Plc, Domain, bool)> {
    let (p, d) = build_box(raw);
    Some((p, d, true))
}

fn stacked(raw: &StackRaw) -> Option<(Plc, Domain, bool)> {
    let (p, d) = build_stack(raw);
    Some((p, d, true))
}

fn split(raw: &SplitRaw) -> Option<(Plc, Domain, bool)> {
    let (p, d) = build_split(raw);
    Some((p, d, true))
}

// Boxes, some flat (1:8 to 1:40): all dihedral angles are 90 degrees, so every bound must hold
// on every tet.
property!(
    box_aligned_plain,
    box_raw(false),
    |raw| boxed(&raw),
    false,
    0
);
property!(box_aligned_q2, box_raw(false), |raw| boxed(&raw), false, 1);
property!(
    box_aligned_q1414_vol,
    box_raw(false),
    |raw| boxed(&raw),
    false,
    2
);
property!(
    box_rotated_plain,
    box_raw(true),
    |raw| boxed(&raw),
    false,
    0
);
property!(box_rotated_q2, box_raw(true), |raw| boxed(&raw), false, 1);
property!(
    box_rotated_q1414_vol,
    box_raw(true),
    |raw| boxed(&raw),
    false,
    2
);

// Prisms over random star-shaped polygons, about half with a polygonal hole through them (facet
// holes in the top and bottom facets and a volume hole seed). The bounds are asserted on every
// tet when no polygon angle is below 90 degrees (the prism's dihedral angles are the polygon
// angles and 90); otherwise only validity and conformity.
property!(
    prism_aligned_plain,
    prism_raw(false),
    |raw| build_prism(&raw),
    false,
    0
);
property!(
    prism_aligned_q2,
    prism_raw(false),
    |raw| build_prism(&raw),
    false,
    1
);
property!(
    prism_aligned_q1414_vol,
    prism_raw(false),
    |raw| build_prism(&raw),
    false,
    2
);
property!(
    prism_rotated_plain,
    prism_raw(true),
    |raw| build_prism(&raw),
    false,
    0
);
property!(
    prism_rotated_q2,
    prism_raw(true),
    |raw| build_prism(&raw),
    false,
    1
);
property!(
    prism_rotated_q1414_vol,
    prism_raw(true),
    |raw| build_prism(&raw),
    false,
    2
);

// Two boxes stacked on a shared facet, two regions with attributes: every tet must carry its
// box's attribute. `stack_*`: same footprint; `inset_*`: the upper box is inset, so the lower
// box's top is a ring facet around the shared facet. Angles are 90, 180 or 270 degrees: bounds
// asserted everywhere.
property!(
    stack_aligned_plain,
    stack_raw(false, false),
    |raw| stacked(&raw),
    true,
    0
);
property!(
    stack_aligned_q2,
    stack_raw(false, false),
    |raw| stacked(&raw),
    true,
    1
);
property!(
    stack_aligned_q1414_vol,
    stack_raw(false, false),
    |raw| stacked(&raw),
    true,
    2
);
property!(
    stack_rotated_plain,
    stack_raw(true, false),
    |raw| stacked(&raw),
    true,
    0
);
property!(
    stack_rotated_q2,
    stack_raw(true, false),
    |raw| stacked(&raw),
    true,
    1
);
property!(
    stack_rotated_q1414_vol,
    stack_raw(true, false),
    |raw| stacked(&raw),
    true,
    2
);

property!(
    inset_aligned_plain,
    stack_raw(false, true),
    |raw| stacked(&raw),
    true,
    0
);
property!(
    inset_aligned_q2,
    stack_raw(false, true),
    |raw| stacked(&raw),
    true,
    1
);
property!(
    inset_aligned_q1414_vol,
    stack_raw(false, true),
    |raw| stacked(&raw),
    true,
    2
);
property!(
    inset_rotated_plain,
    stack_raw(true, true),
    |raw| stacked(&raw),
    true,
    0
);
property!(
    inset_rotated_q2,
    stack_raw(true, true),
    |raw| stacked(&raw),
    true,
    1
);
property!(
    inset_rotated_q1414_vol,
    stack_raw(true, true),
    |raw| stacked(&raw),
    true,
    2
);

// A box split in two by an internal facet (two regions with attributes); the side facets are
// either two quads each or one hexagon with the split edge as a 2-vertex polygon.
property!(
    split_aligned_plain,
    split_raw(false),
    |raw| split(&raw),
    true,
    0
);
property!(
    split_aligned_q2,
    split_raw(false),
    |raw| split(&raw),
    true,
    1
);
property!(
    split_aligned_q1414_vol,
    split_raw(false),
    |raw| split(&raw),
    true,
    2
);
property!(
    split_rotated_plain,
    split_raw(true),
    |raw| split(&raw),
    true,
    0
);
property!(
    split_rotated_q2,
    split_raw(true),
    |raw| split(&raw),
    true,
    1
);
property!(
    split_rotated_q1414_vol,
    split_raw(true),
    |raw| split(&raw),
    true,
    2
);

// Keeping the surface (-Y): every kind of input, aligned and rotated (slanted facets, whose
// Steiner points must all come off the surface again), internal facets (two wedges around
// every point taken off) and ring facets.
property!(box_rotated_keep, box_raw(true), |raw| boxed(&raw), false, 3);
property!(
    box_rotated_keep_q1414_vol,
    box_raw(true),
    |raw| boxed(&raw),
    false,
    4
);
property!(
    prism_aligned_keep_q1414_vol,
    prism_raw(false),
    |raw| build_prism(&raw),
    false,
    4
);
property!(
    prism_rotated_keep,
    prism_raw(true),
    |raw| build_prism(&raw),
    false,
    3
);
property!(
    stack_rotated_keep_q1414_vol,
    stack_raw(true, false),
    |raw| stacked(&raw),
    true,
    4
);
property!(
    inset_rotated_keep,
    stack_raw(true, true),
    |raw| stacked(&raw),
    true,
    3
);
property!(
    split_rotated_keep,
    split_raw(true),
    |raw| split(&raw),
    true,
    3
);
property!(
    split_aligned_keep_q1414_vol,
    split_raw(false),
    |raw| split(&raw),
    true,
    4
);
