//! Generated CAD-like parts (issue 12): the shapes real FEM inputs are made of, at random sizes,
//! positions and rotations, meshed with TetGen's usual switches and judged by the independent
//! checker in `common3d` (exact orientation, neighbours and Delaunay property, every facet
//! covered with its marker, every input edge a chain of subsegments, the enclosed volume, the
//! radius-edge bound on every tet).
//!
//! The families:
//! - **plates** with one to four cylindrical through-holes (regular 8- to 64-gons at random
//!   positions and phases), from thin sheets to blocks;
//! - **thin walls**: a plate with one hole whose circle passes within 10^-4 to 10^-1 of its
//!   radius from the plate's edge (TetGen 1.5 aborts on some: an assertion in `locate`);
//! - **brackets**: an L profile extruded, with an optional concave fillet of many thin facets in
//!   the inner corner, and through-holes in both legs (their axes at right angles);
//! - **gears**: 8 to 40 trapezoidal teeth around a polygonal bore;
//! - **tubes**: the ring between two 8- to 64-gons, walls down to a twelfth of the radius;
//! - **fillet blocks**: rectangles with rounded corners of 2 to 32 facets each, extruded, so
//!   the fillet facets are long thin quads;
//! - **slabs**: boxes 16 to 64 times wider than thick.
//!
//! Each family is meshed with `-p`, `-pq`, `-pq1.414` and `-pq1.414Y` (TetGen's switches, parsed
//! by idmesh's TetGen parser).
//!
//! Every family meets the checker's rule for asserting the bounds (no input angle below 90°:
//! polygon angles here are at least 90°, dihedral angles 90° or the polygon's), so the bound
//! is asserted on every tet, unless the surface is kept (`-Y`).
//!
//! Coordinates are dyadic (rounded to `2^-24`) and rotations exact ([`Frame`]), so the facets
//! are exactly planar, as idmesh requires of `.poly` input.

mod common3d;

use std::f64::consts::{PI, TAU};
use std::sync::atomic::{AtomicUsize, Ordering};

use common3d::{
    mesh_and_check, polygon_area2, prism_plc_holes, regular_polygon, Cell, Domain, Frame, Spec3, P3,
};
use idmesh::{Facet, Options3, Plc};
use proptest::prelude::*;

/// Cases per family and switch set; `PROPTEST_CASES` overrides.
const CASES: u32 = 16;

fn config() -> ProptestConfig {
    common3d::proptest_config(CASES, 0xcad3_d001)
}

/// Rounds to a multiple of `2^-bits`.
fn q(x: f64, bits: i32) -> f64 {
    let s = 2f64.powi(bits);
    (x * s).round() / s
}

/// A regular `n`-gon of radius `r` around `c`, turned by `phase`, rounded to dyadic
/// coordinates (it stays convex and star-shaped around `c`: `r` is far above `2^-24`).
fn ngon(n: usize, c: [f64; 2], r: f64, phase: f64) -> Vec<[f64; 2]> {
    regular_polygon(n, r)
        .into_iter()
        .map(|p| {
            let (s, co) = phase.sin_cos();
            [
                q(c[0] + co * p[0] - s * p[1], 24),
                q(c[1] + s * p[0] + co * p[1], 24),
            ]
        })
        .collect()
}

/// Frames: `None` (no rotation), or the quaternion `(w, x, y, z)` with `w` in 4..=10 and the
/// others in -3..=3: rotations by up to about 70 degrees.
type FrameRaw = Option<(i64, i64, i64, i64)>;

fn frame_raw() -> impl Strategy<Value = FrameRaw> {
    prop_oneof![
        1 => Just(None),
        3 => (4i64..=10, -3i64..=3, -3i64..=3, -3i64..=3)
            .prop_filter("a rotation", |r| (r.1, r.2, r.3) != (0, 0, 0))
            .prop_map(Some),
    ]
}

fn make_frame(f: FrameRaw) -> Frame {
    match f {
        None => Frame::identity(),
        Some((w, x, y, z)) => Frame::quaternion(w, x, y, z),
    }
}

/// What the checker is told about a part: its domain (prisms) or only its volume.
enum Truth {
    Domain(Domain),
    Volume(f64),
}

/// A hole of a part: a regular polygon (sides, radius fraction, centre fractions, phase).
type HoleRaw = (usize, f64, [f64; 2], f64);

fn hole_raw() -> impl Strategy<Value = HoleRaw> {
    (
        8usize..=64,
        0.3..1.0f64,
        [0.0..1.0f64, 0.0..1.0f64],
        0.0..TAU,
    )
}

/// The hole polygon of `h` in the box `[x0, x1] × [y0, y1]`: radius at most 45% of the
/// box's smaller side, centre anywhere that keeps a margin of a tenth of the radius.
fn hole_in(h: &HoleRaw, x: [f64; 2], y: [f64; 2]) -> (Vec<[f64; 2]>, [f64; 2]) {
    let (n, rf, c, phase) = *h;
    let r = rf * 0.45 * (x[1] - x[0]).min(y[1] - y[0]);
    let m = 1.1 * r;
    let cx = q(x[0] + m + c[0] * (x[1] - x[0] - 2.0 * m), 24);
    let cy = q(y[0] + m + c[1] * (y[1] - y[0] - 2.0 * m), 24);
    (ngon(n, [cx, cy], r, phase), [cx, cy])
}

/// Area of a simple polygon.
fn area(p: &[[f64; 2]]) -> f64 {
    polygon_area2(p).abs()
}

/// A prism part over `outer` minus `holes`, between 0 and `h`.
fn prism_part(
    outer: Vec<[f64; 2]>,
    holes: Vec<(Vec<[f64; 2]>, [f64; 2])>,
    h: f64,
    frame: Frame,
) -> (Plc, Truth) {
    let refs: Vec<(&[[f64; 2]], [f64; 2])> =
        holes.iter().map(|(p, s)| (p.as_slice(), *s)).collect();
    let plc = prism_plc_holes(&outer, &refs, 0.0, h, &frame);
    let cell = Cell {
        outer,
        holes: holes.into_iter().map(|(p, _)| p).collect(),
        z0: 0.0,
        z1: h,
        attribute: 0.0,
    };
    (
        plc,
        Truth::Domain(Domain {
            cells: vec![cell],
            frame,
        }),
    )
}

// ---------------------------------------------------------------------------------- plates

/// Extents, thickness fraction, holes (one slot each along x), frame.
type PlateRaw = ([f64; 2], f64, Vec<HoleRaw>, FrameRaw);

fn plate_raw() -> impl Strategy<Value = PlateRaw> {
    (
        [1.0..4.0f64, 0.5..2.0f64],
        0.05..0.5f64,
        prop::collection::vec(hole_raw(), 1..=4),
        frame_raw(),
    )
}

fn plate(raw: &PlateRaw) -> (Plc, Truth) {
    let (e, tf, holes, f) = raw;
    let (lx, ly) = (q(e[0], 4), q(e[1], 4));
    let t = q(tf * ly, 6).max(1.0 / 64.0);
    let slot = lx / holes.len() as f64;
    let holes = holes
        .iter()
        .enumerate()
        .map(|(i, h)| hole_in(h, [i as f64 * slot, (i + 1) as f64 * slot], [0.0, ly]))
        .collect();
    let outer = vec![[0.0, 0.0], [lx, 0.0], [lx, ly], [0.0, ly]];
    prism_part(outer, holes, t, make_frame(*f))
}

/// A plate (extents, thickness fraction) with one hole whose circle passes `gap` times its
/// radius from the plate's edge: a thin wall down to a ten-thousandth of the radius.
type WallRaw = ([f64; 2], f64, HoleRaw, f64, FrameRaw);

fn wall_raw() -> impl Strategy<Value = WallRaw> {
    (
        [1.0..3.0f64, 0.5..2.0f64],
        0.05..0.5f64,
        hole_raw(),
        -4.0..-1.0f64,
        frame_raw(),
    )
}

fn thin_wall(raw: &WallRaw) -> (Plc, Truth) {
    let (e, tf, (n, rf, c, phase), gap, f) = *raw;
    let (lx, ly) = (q(e[0], 4), q(e[1], 4));
    let t = q(tf * ly, 6).max(1.0 / 64.0);
    let r = rf * 0.45 * lx.min(ly);
    let cx = q(1.1 * r + c[0] * (lx - 2.2 * r), 24);
    let cy = q(r * (1.0 + 10f64.powf(gap)), 24);
    let hole = (ngon(n, [cx, cy], r, phase), [cx, cy]);
    let outer = vec![[0.0, 0.0], [lx, 0.0], [lx, ly], [0.0, ly]];
    prism_part(outer, vec![hole], t, make_frame(f))
}

// -------------------------------------------------------------------------------- brackets

/// Flange length, leg height, width, thickness fraction, fillet (radius fraction, facets),
/// flange holes, leg holes, frame.
type BracketRaw = (
    f64,
    f64,
    f64,
    f64,
    Option<(f64, usize)>,
    Vec<HoleRaw>,
    Vec<HoleRaw>,
    FrameRaw,
);

fn bracket_raw() -> impl Strategy<Value = BracketRaw> {
    (
        1.0..3.0f64,
        1.0..3.0f64,
        0.5..2.0f64,
        0.08..0.3f64,
        prop::option::of((0.1..0.5f64, 2usize..=24)),
        prop::collection::vec(hole_raw(), 0..=3),
        prop::collection::vec(hole_raw(), 0..=3),
        frame_raw(),
    )
}

/// An L profile in the (x, z) plane extruded along y from 0 to `w`. The flange is
/// `[0, l] × [0, t]`, the leg `[0, t] × [0, h]`; the inner corner is optionally rounded by a
/// concave arc. Flange holes run along z (from z = 0 to t), leg holes along x (from x = 0 to t),
/// each in its own slot along y.
fn bracket(raw: &BracketRaw) -> (Plc, Truth) {
    let (l, h, w, tf, fillet, fh, lh, f) = raw;
    let (l, h, w) = (q(*l, 4), q(*h, 4), q(*w, 4));
    let t = q(tf * l.min(h), 6).max(1.0 / 32.0);
    let frame = make_frame(*f);
    // The profile, counter-clockwise in (x, z).
    let mut prof: Vec<[f64; 2]> = vec![[0.0, 0.0], [l, 0.0], [l, t]];
    let mut rho = 0.0;
    if let Some((rf, _)) = fillet {
        rho = q(rf * (l.min(h) - t) * 0.5, 8);
    }
    let flange_top = prof.len() - 1; // edge (l, t) -> (t + rho, t)
    if rho > 0.0 {
        let m = fillet.unwrap().1;
        let c = [t + rho, t + rho];
        prof.push([t + rho, t]);
        for k in 1..m {
            let a = -0.5 * PI - 0.5 * PI * k as f64 / m as f64;
            prof.push([q(c[0] + rho * a.cos(), 24), q(c[1] + rho * a.sin(), 24)]);
        }
        prof.push([t, t + rho]);
    } else {
        prof.push([t, t]);
    }
    let leg_inner = prof.len() - 1; // edge (t, t + rho) -> (t, h)
    prof.push([t, h]);
    prof.push([0.0, h]);
    let back = prof.len() - 1; // edge (0, h) -> (0, 0)
    let n = prof.len();

    let mut plc = Plc::default();
    let at = |plc: &mut Plc, p: P3| -> u32 {
        plc.points.push(frame.apply(p));
        plc.points.len() as u32 - 1
    };
    let front: Vec<u32> = prof
        .iter()
        .map(|p| at(&mut plc, [p[0], 0.0, p[1]]))
        .collect();
    let rear: Vec<u32> = prof.iter().map(|p| at(&mut plc, [p[0], w, p[1]])).collect();
    plc.facets.push(Facet {
        polygons: vec![front.clone()],
        holes: vec![],
        marker: 1,
    });
    plc.facets.push(Facet {
        polygons: vec![rear.clone()],
        holes: vec![],
        marker: 1,
    });
    let first_side = plc.facets.len();
    for i in 0..n {
        let j = (i + 1) % n;
        plc.facets.push(Facet {
            polygons: vec![vec![front[i], front[j], rear[j], rear[i]]],
            holes: vec![],
            marker: 2,
        });
    }
    let mut removed = 0.0;
    // Flange holes: (x, y) polygons at z = 0 and z = t; leg holes: (y, z) polygons at x = 0
    // and x = t.
    let x_from = t + rho;
    let z_from = t + rho;
    let groups: [(&Vec<HoleRaw>, [f64; 2], usize, usize); 2] = [
        (fh, [x_from, l], 0, flange_top),
        (lh, [z_from, h], back, leg_inner),
    ];
    for (gi, (holes, span, e0, e1)) in groups.into_iter().enumerate() {
        if holes.is_empty() || span[1] - span[0] < 4.0 / 64.0 {
            continue;
        }
        let slot = w / holes.len() as f64;
        for (i, hr) in holes.iter().enumerate() {
            let ys = [i as f64 * slot, (i + 1) as f64 * slot];
            let (poly, seed) = if gi == 0 {
                hole_in(hr, span, ys)
            } else {
                hole_in(hr, ys, span)
            };
            removed += area(&poly) * t;
            let map = |p: [f64; 2], depth: f64| -> P3 {
                if gi == 0 {
                    [p[0], p[1], depth]
                } else {
                    [depth, p[0], p[1]]
                }
            };
            let lo: Vec<u32> = poly.iter().map(|&p| at(&mut plc, map(p, 0.0))).collect();
            let hi: Vec<u32> = poly.iter().map(|&p| at(&mut plc, map(p, t))).collect();
            plc.facets[first_side + e0].polygons.push(lo.clone());
            plc.facets[first_side + e0]
                .holes
                .push(frame.apply(map(seed, 0.0)));
            plc.facets[first_side + e1].polygons.push(hi.clone());
            plc.facets[first_side + e1]
                .holes
                .push(frame.apply(map(seed, t)));
            let k = lo.len();
            for a in 0..k {
                let b = (a + 1) % k;
                plc.facets.push(Facet {
                    polygons: vec![vec![lo[a], lo[b], hi[b], hi[a]]],
                    holes: vec![],
                    marker: 3,
                });
            }
            plc.holes.push(frame.apply(map(seed, 0.5 * t)));
        }
    }
    let volume = (area(&prof) * w - removed) * frame.factor().powi(3);
    (plc, Truth::Volume(volume))
}

// ----------------------------------------------------------------------------------- gears

/// Teeth, tooth height fraction, bore (sides, radius fraction, phase), thickness, frame.
type GearRaw = (usize, f64, (usize, f64, f64), f64, FrameRaw);

fn gear_raw() -> impl Strategy<Value = GearRaw> {
    (
        8usize..=40,
        0.05..0.25f64,
        (8usize..=64, 0.2..0.7f64, 0.0..TAU),
        0.1..0.8f64,
        frame_raw(),
    )
}

/// Root radius 1; per tooth a root chord over 40% of the pitch and a tip over 30%, so the tip
/// corners are obtuse and the root corners reflex.
fn gear(raw: &GearRaw) -> (Plc, Truth) {
    let (z, hf, (bn, bf, bp), t, f) = *raw;
    let tip = 1.0 + hf;
    let pitch = TAU / z as f64;
    let pt = |r: f64, a: f64| [q(r * a.cos(), 24), q(r * a.sin(), 24)];
    let mut outer = Vec::with_capacity(4 * z);
    for i in 0..z {
        let a = i as f64 * pitch;
        outer.push(pt(1.0, a));
        outer.push(pt(1.0, a + 0.4 * pitch));
        outer.push(pt(tip, a + 0.55 * pitch));
        outer.push(pt(tip, a + 0.85 * pitch));
    }
    let bore = ngon(bn, [0.0, 0.0], bf * (PI / z as f64).cos().min(0.9), bp);
    prism_part(outer, vec![(bore, [0.0, 0.0])], q(t, 6), make_frame(f))
}

// ----------------------------------------------------------------------------------- tubes

/// Sides, inner sides, wall fraction, inner phase, length, frame.
type TubeRaw = (usize, usize, f64, f64, f64, FrameRaw);

fn tube_raw() -> impl Strategy<Value = TubeRaw> {
    (
        8usize..=64,
        8usize..=64,
        0.08..0.3f64,
        0.0..TAU,
        0.25..1.0f64,
        frame_raw(),
    )
}

/// Outer polygon of radius 1; the inner one lies within the outer one's inscribed circle,
/// shrunk by the wall fraction.
fn tube(raw: &TubeRaw) -> (Plc, Truth) {
    let (n, ni, wf, phase, len, f) = *raw;
    let outer = ngon(n, [0.0, 0.0], 1.0, 0.0);
    let inner = ngon(ni, [0.0, 0.0], (1.0 - wf) * (PI / n as f64).cos(), phase);
    prism_part(outer, vec![(inner, [0.0, 0.0])], q(len, 6), make_frame(f))
}

// ---------------------------------------------------------------------------- fillet blocks

/// Extents, fillet radius fraction, facets per fillet, which corners are rounded, length,
/// frame.
type FilletRaw = ([f64; 2], f64, usize, [bool; 4], f64, FrameRaw);

fn fillet_raw() -> impl Strategy<Value = FilletRaw> {
    (
        [0.5..2.0f64, 0.5..2.0f64],
        0.1..0.45f64,
        2usize..=32,
        [any::<bool>(), any::<bool>(), any::<bool>(), any::<bool>()],
        0.5..2.0f64,
        frame_raw(),
    )
}

fn fillet_block(raw: &FilletRaw) -> (Plc, Truth) {
    let (e, rf, m, corners, len, f) = *raw;
    let (a, b) = (q(e[0], 4), q(e[1], 4));
    let rho = q(rf * a.min(b), 8);
    let box_corners = [[a, 0.0], [a, b], [0.0, b], [0.0, 0.0]];
    let mut outer = Vec::new();
    for (k, &c) in box_corners.iter().enumerate() {
        if !corners[k] {
            outer.push(c);
            continue;
        }
        // The corner's arc, counter-clockwise: its centre is `rho` inside both sides.
        let sx = if c[0] > 0.0 { -1.0 } else { 1.0 };
        let sy = if c[1] > 0.0 { -1.0 } else { 1.0 };
        let centre = [c[0] + sx * rho, c[1] + sy * rho];
        let start = k as f64 * 0.5 * PI - 0.5 * PI;
        for i in 0..=m {
            let t = start + 0.5 * PI * i as f64 / m as f64;
            let p = [centre[0] + rho * t.cos(), centre[1] + rho * t.sin()];
            // The arc's ends lie exactly on the box's sides.
            let p = if i == 0 || i == m {
                [0, 1].map(|d| {
                    if (p[d] - c[d]).abs() < 0.5 * rho {
                        c[d]
                    } else {
                        centre[d]
                    }
                })
            } else {
                p.map(|x| q(x, 24))
            };
            outer.push(p);
        }
    }
    prism_part(outer, vec![], q(len, 6), make_frame(f))
}

// ----------------------------------------------------------------------------------- slabs

/// Extents, thickness divisor, frame.
type SlabRaw = ([f64; 2], u32, FrameRaw);

fn slab_raw() -> impl Strategy<Value = SlabRaw> {
    ([0.5..2.0f64, 0.5..2.0f64], 16u32..=64, frame_raw())
}

fn slab(raw: &SlabRaw) -> (Plc, Truth) {
    let (e, d, f) = *raw;
    let (a, b) = (q(e[0], 4), q(e[1], 4));
    let t = q(a.min(b) / d as f64, 12);
    let outer = vec![[0.0, 0.0], [a, 0.0], [a, b], [0.0, b]];
    prism_part(outer, vec![], t, make_frame(f))
}

// ------------------------------------------------------------------------------ properties

/// TetGen's usual switches: `-p`, `-pq` (radius-edge 2), `-pq1.414`, `-pq1.414Y`.
const SWITCHES: [&str; 4] = ["p", "pq", "pq1.414", "pq1.414Y"];

fn options(mode: usize) -> Options3 {
    let mut o = idmesh::switches::tetgen::parse_string(SWITCHES[mode])
        .unwrap_or_else(|e| panic!("-{}: {e}", SWITCHES[mode]))
        .options();
    // A guard, far above what these parts need.
    o.max_steiner = Some(300_000);
    o
}

/// With `IDMESH_CAD_DUMP=DIR`, every part is written as `DIR/<family>-<n>.poly` (with its
/// switches in `<family>-<n>.switches`) instead of being meshed, for the command line and
/// `verify3d.py`. Returns whether it was.
fn dump(family: &str, plc: &Plc, mode: usize) -> bool {
    static N: AtomicUsize = AtomicUsize::new(0);
    let Some(dir) = std::env::var_os("IDMESH_CAD_DUMP") else {
        return false;
    };
    let dir = std::path::PathBuf::from(dir);
    std::fs::create_dir_all(&dir).expect("dump directory");
    let n = N.fetch_add(1, Ordering::Relaxed);
    let f = std::fs::File::create(dir.join(format!("{family}-{n}.poly"))).expect("dump file");
    idmesh::io::tetgen::write_plc_poly(std::io::BufWriter::new(f), plc, 1).expect("dump");
    std::fs::write(dir.join(format!("{family}-{n}.switches")), SWITCHES[mode]).expect("dump file");
    true
}

fn run(family: &str, part: (Plc, Truth), mode: usize) -> Result<(), TestCaseError> {
    let (plc, truth) = part;
    if dump(family, &plc, mode) {
        return Ok(());
    }
    let o = options(mode);
    let (domain, volume) = match truth {
        Truth::Domain(d) => (Some(d), None),
        Truth::Volume(v) => (None, Some(v)),
    };
    let spec = Spec3 {
        check_quality: !o.keep_surface,
        tol: common3d::tolerance(&plc),
        domain,
        volume,
        timeout: std::time::Duration::from_secs(60),
        ..Spec3::default()
    };
    let (mesh, rep) = mesh_and_check(&plc, &o, &spec)
        .map_err(|e| TestCaseError::fail(format!("-{}: {e}", SWITCHES[mode])))?;
    prop_assert!(
        mesh.complete,
        "-{}: refinement stopped at the Steiner guard ({} Steiner points)\ninput:\n{}",
        SWITCHES[mode],
        rep.steiner,
        common3d::plc_rust(&plc)
    );
    Ok(())
}

macro_rules! family {
    ($name:ident, $strategy:expr, $build:expr, $modes:expr) => {
        proptest! {
            #![proptest_config(config())]
            #[test]
            fn $name(raw in $strategy, pick in 0usize..$modes.len()) {
                run(stringify!($name), $build(&raw), $modes[pick])?;
            }
        }
    };
}

/// All four switch sets.
const ALL: [usize; 4] = [0, 1, 2, 3];

family!(plates_with_holes, plate_raw(), plate, ALL);
family!(plates_with_a_thin_wall, wall_raw(), thin_wall, ALL);
family!(
    brackets_with_holes_and_fillets,
    bracket_raw(),
    bracket,
    [0, 1, 2]
);
family!(gears, gear_raw(), gear, ALL);
family!(tubes, tube_raw(), tube, ALL);
family!(fillet_blocks, fillet_raw(), fillet_block, ALL);
family!(thin_slabs, slab_raw(), slab, ALL);

// Keeping the surface (-Y), brackets with their inner fillet too (see the reproducer below).
family!(
    brackets_with_holes_keeping_the_surface,
    bracket_raw(),
    bracket,
    [3]
);

/// A bracket whose concave inner fillet is made of 16 facets 560 times longer than wide, with a
/// hole in each leg, at `-pq1.414Y` (issue 12). Taking the boundary Steiner points of the
/// fillet's edges off the surface re-triangulates each fillet facet around them; with ear
/// clipping's triangles that left a tet of volume 7e-18 with edges near 2, all four corners in
/// the plane of a fillet facet. The re-triangulation is now the facet polygon's constrained
/// Delaunay triangulation (`FacetTriangulation::polygon`), and the part meshes. In the CAD
/// conformance step `verify3d.py` reports tets not winding once around one of its vertices, a
/// claim it decides in floating point; `fuzz/recheck3d.py` decides it exactly, and the mesh
/// passes.
#[test]
fn bracket_with_a_thin_facet_fillet_keeping_the_surface() {
    let raw: BracketRaw = (
        2.5969355936561294,
        1.0,
        1.929917303088518,
        0.29673390856461396,
        Some((0.1, 16)),
        vec![(15, 0.757914782732278, [0.0, 0.3892406044074471], 0.0)],
        vec![(12, 0.3, [0.0, 0.0], 3.033354544600125)],
        None,
    );
    run("bracket_fillet_y", bracket(&raw), 3).unwrap();
}

/// A rotated plate with two holes at `-pq`: four Steiner points on four edges around a corner
/// are the corners of a rectangle, coplanar before the rotation's rounding. Sliver removal
/// left that flat tet (0° dihedral, radius-edge unbounded) in the mesh because its rounded
/// circumcentre was undefined; now it gets a point inside its circumsphere.
#[test]
fn rotated_plate_with_a_flat_tet_across_a_corner() {
    let raw: PlateRaw = (
        [1.8070359766907915, 1.2885778259934857],
        0.2975397439852687,
        vec![
            (
                25,
                0.4477723405481752,
                [0.8825323573008198, 0.9720304027066543],
                2.4900000474837998,
            ),
            (
                17,
                0.429929297566125,
                [0.0, 0.5790452249611462],
                2.9991648243920097,
            ),
        ],
        Some((7, 2, 0, -1)),
    );
    run("plate_flat_corner", plate(&raw), 1).unwrap();
}
