//! Property tests: random PSLGs (star-shaped polygons with holes, islands, chords and loose
//! points; thin wedges; grids; regular polygons), meshed under several option sets, every mesh
//! judged by the independent checker in `common`.
//!
//! Generators draw raw numbers only; the PSLG is built from them deterministically, so proptest
//! shrinks towards fewer vertices, holes and chords. A failure message carries the shrunk input
//! in Triangle's `.poly` format.

mod common;

use std::collections::{HashMap, HashSet};
use std::f64::consts::TAU;

use common::{
    locate, mesh_and_check, polygon_area, quality, regular_polygon, segments_conflict,
    strictly_inside_segment, Builder, Loc, RegionSpec, Spec,
};
use idmesh::predicates::incircle;
use idmesh::{Options, Pslg, Region};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

/// Case counts are chosen to keep the whole file well under a minute with the test profile;
/// `PROPTEST_CASES=<n>` overrides them for a deeper run. The seed is fixed so that CI runs are
/// reproducible; `PROPTEST_SEED=<u64>` explores other inputs.
fn config(cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(cases);
    let seed = std::env::var("PROPTEST_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x1d3e_5a11);
    ProptestConfig {
        cases,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        max_shrink_iters: 400,
        // Failures are reported with their `.poly` text; no regression files in the tree.
        failure_persistence: Some(Box::new(FileFailurePersistence::Off)),
        ..ProptestConfig::default()
    }
}

// ----------------------------------------------------------------------------- option sets

/// The option sets of the brief: (a) default, (b) a minimum angle, (c) a maximum area (as a
/// fraction of the domain area), and the two combined.
#[derive(Clone, Copy, Debug)]
enum Mode {
    Plain,
    Quality(f64),
    Area(f64),
    QualityArea(f64, f64),
}

fn mode() -> impl Strategy<Value = Mode> {
    let angle = prop_oneof![Just(20.0), Just(25.0), Just(30.0)];
    prop_oneof![
        Just(Mode::Plain),
        angle.clone().prop_map(Mode::Quality),
        (10.0..300.0f64).prop_map(Mode::Area),
        (angle, 10.0..150.0f64).prop_map(|(a, k)| Mode::QualityArea(a, k)),
    ]
}

/// Options for `mode` on a domain of area `area`, with the Steiner guard that turns a
/// non-terminating refinement into a reported failure.
fn options(mode: Mode, area: f64) -> Options {
    let base = quality(30.0);
    match mode {
        Mode::Plain => Options {
            min_angle: None,
            ..base
        },
        Mode::Quality(a) => Options {
            min_angle: Some(a),
            ..base
        },
        Mode::Area(k) => Options {
            min_angle: None,
            max_area: Some(area / k),
            ..base
        },
        Mode::QualityArea(a, k) => Options {
            min_angle: Some(a),
            max_area: Some(area / k),
            ..base
        },
    }
}

/// Meshes and checks; also demands completion (the guard was not hit).
fn run(pslg: &Pslg, opts: &Options, spec: &Spec) -> Result<common::Report, TestCaseError> {
    let (mesh, report) = mesh_and_check(pslg, opts, spec).map_err(TestCaseError::fail)?;
    prop_assert!(
        mesh.complete,
        "refinement stopped at the Steiner guard ({} Steiner points)\noptions: {opts:?}\ninput:\n{}",
        report.steiner,
        common::poly_text(pslg)
    );
    Ok(report)
}

// ----------------------------------------------------------------------------- star polygons

/// Raw numbers for a star-shaped polygon: per vertex an angular jitter in `[0, 0.8)` of its
/// sector and a radius fraction in `[0, 1)`.
type StarRaw = Vec<(f64, f64)>;

fn star_raw(n: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = StarRaw> {
    prop::collection::vec((0.0..0.8f64, 0.0..1.0f64), n)
}

/// A polygon star-shaped around `c`: angles strictly increase, so it is simple and CCW.
fn star(c: [f64; 2], rmin: f64, rmax: f64, phase: f64, raw: &StarRaw) -> Vec<[f64; 2]> {
    let n = raw.len() as f64;
    raw.iter()
        .enumerate()
        .map(|(i, &(j, f))| {
            let a = phase + TAU * (i as f64 + j) / n;
            let r = rmin + (rmax - rmin) * f;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect()
}

fn quantizer(bits: Option<u32>) -> impl Fn([f64; 2]) -> [f64; 2] {
    move |p| match bits {
        None => p,
        Some(k) => {
            let s = (1u64 << k) as f64;
            [(p[0] * s).round() / s, (p[1] * s).round() / s]
        }
    }
}

/// Distance from the origin to the nearest edge of `poly` (its inscribed disk about the origin,
/// since the polygon is star-shaped around it with sectors below π).
fn inradius(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let d = common::sub(b, a);
            let t = (-common::dot(a, d) / common::dot(d, d)).clamp(0.0, 1.0);
            common::dist([0.0, 0.0], [a[0] + t * d[0], a[1] + t * d[1]])
        })
        .fold(f64::INFINITY, f64::min)
}

/// One of three slots around the origin: a hole or an island (a region with its own seed).
#[derive(Clone, Debug)]
struct SlotRaw {
    island: bool,
    jitter: f64,
    shape: StarRaw,
}

#[derive(Clone, Debug)]
struct DomainRaw {
    outer: StarRaw,
    slots: Vec<Option<SlotRaw>>,
    /// Loose points, polar around the origin: (angle fraction, radius fraction).
    points: Vec<(f64, f64)>,
    /// Chords as pairs of point-index fractions.
    chords: Vec<(f64, f64)>,
    /// Round every coordinate to a multiple of 2^-k: exact collinearities and cocircularities.
    quantize: Option<u32>,
}

fn domain_raw(islands: bool, chords: usize) -> impl Strategy<Value = DomainRaw> {
    let slot =
        (any::<bool>(), -1.0..1.0f64, star_raw(3..=12)).prop_map(move |(i, jitter, shape)| {
            SlotRaw {
                island: islands && i,
                jitter,
                shape,
            }
        });
    (
        star_raw(5..=40),
        prop::collection::vec(prop::option::of(slot), 3),
        prop::collection::vec((0.0..1.0f64, 0.2..0.95f64), 0..=6),
        prop::collection::vec((0.0..1.0f64, 0.0..1.0f64), 0..=chords),
        prop::option::of(8u32..=14),
    )
        .prop_map(|(outer, slots, points, chords, quantize)| DomainRaw {
            outer,
            slots,
            points,
            chords,
            quantize,
        })
}

/// A generated domain: the PSLG plus what the checker should expect.
struct Domain {
    pslg: Pslg,
    spec: Spec,
    area: f64,
}

/// Every segment pair is free of conflicts and no two points coincide (exact).
fn pslg_is_valid(p: &Pslg) -> bool {
    let mut pts = p.points.clone();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    if pts.windows(2).any(|w| w[0] == w[1]) {
        return false;
    }
    let s = &p.segments;
    for i in 0..s.len() {
        for j in i + 1..s.len() {
            let (a, b) = (p.points[s[i][0] as usize], p.points[s[i][1] as usize]);
            let (c, d) = (p.points[s[j][0] as usize], p.points[s[j][1] as usize]);
            if segments_conflict(a, b, c, d) {
                return false;
            }
        }
    }
    true
}

/// Strictly inside the outer polygon and strictly outside every slot polygon.
fn in_domain(outer: &[[f64; 2]], slots: &[Vec<[f64; 2]>], p: [f64; 2]) -> bool {
    locate(outer, p) == Loc::Inside && slots.iter().all(|h| locate(h, p) == Loc::Outside)
}

fn build_domain(raw: &DomainRaw) -> Option<Domain> {
    let q = quantizer(raw.quantize);
    let outer: Vec<[f64; 2]> = star([0.0, 0.0], 0.5, 1.0, 0.0, &raw.outer)
        .into_iter()
        .map(&q)
        .collect();
    let rho = inradius(&outer);
    let mut b = Builder::default();
    b.closed_loop(&outer);
    let mut holes = Vec::new();
    let mut slot_polys = Vec::new();
    let mut islands = Vec::new();
    for (k, slot) in raw.slots.iter().enumerate() {
        let Some(slot) = slot else { continue };
        // Slot centres 120° ± 0.15 rad apart at 0.5ρ; radius 0.35ρ keeps them disjoint and
        // inside the inscribed disk, and leaves a disk of 0.15ρ around the origin free.
        let phi = TAU * k as f64 / 3.0 + 0.15 * slot.jitter;
        let c = q([0.5 * rho * phi.cos(), 0.5 * rho * phi.sin()]);
        let rh = 0.35 * rho;
        let poly: Vec<[f64; 2]> = star(c, 0.3 * rh, rh, phi, &slot.shape)
            .into_iter()
            .map(&q)
            .collect();
        if locate(&poly, c) != Loc::Inside || polygon_area(&poly) <= 0.0 {
            return None;
        }
        b.closed_loop(&poly);
        if slot.island {
            islands.push((poly.clone(), c));
        } else {
            b.pslg.holes.push(c);
            holes.push(poly.clone());
        }
        slot_polys.push(poly);
    }
    for &(a, r) in &raw.points {
        let p = q([r * rho * (TAU * a).cos(), r * rho * (TAU * a).sin()]);
        let on_seg = b.pslg.segments.iter().any(|s| {
            strictly_inside_segment(
                b.pslg.points[s[0] as usize],
                b.pslg.points[s[1] as usize],
                p,
            )
        });
        if in_domain(&outer, &slot_polys, p) && !on_seg && !b.pslg.points.contains(&p) {
            b.point(p);
        }
    }
    let n = b.pslg.points.len();
    for &(fa, fb) in &raw.chords {
        let (i, j) = (
            ((fa * n as f64) as usize).min(n - 1),
            ((fb * n as f64) as usize).min(n - 1),
        );
        if i == j {
            continue;
        }
        let (pi, pj) = (b.pslg.points[i], b.pslg.points[j]);
        let crosses = b.pslg.segments.iter().any(|s| {
            segments_conflict(
                pi,
                pj,
                b.pslg.points[s[0] as usize],
                b.pslg.points[s[1] as usize],
            )
        });
        let through = b
            .pslg
            .points
            .iter()
            .any(|&x| strictly_inside_segment(pi, pj, x));
        let mid = [0.5 * (pi[0] + pj[0]), 0.5 * (pi[1] + pj[1])];
        if !crosses && !through && in_domain(&outer, &slot_polys, mid) {
            b.segment(i as u32, j as u32);
        }
    }
    if !pslg_is_valid(&b.pslg) {
        return None;
    }
    let area = polygon_area(&outer) - holes.iter().map(|h| polygon_area(h)).sum::<f64>();
    let mut spec = Spec {
        area: Some(area),
        outer: Some(outer.clone()),
        holes,
        ..Spec::default()
    };
    if !islands.is_empty() {
        // Region 0 is everything outside the slots, seeded at the origin (kept free above).
        spec.regions.push(RegionSpec {
            poly: outer,
            holes: slot_polys,
            attribute: 1.0,
            max_area: None,
        });
        b.pslg.regions.push(Region {
            point: [0.0, 0.0],
            attribute: 1.0,
            max_area: None,
        });
        for (k, (poly, c)) in islands.into_iter().enumerate() {
            let attribute = 2.0 + k as f64;
            spec.regions.push(RegionSpec {
                poly,
                holes: vec![],
                attribute,
                max_area: None,
            });
            b.pslg.regions.push(Region {
                point: c,
                attribute,
                max_area: None,
            });
        }
    }
    Some(Domain {
        pslg: b.pslg,
        spec,
        area,
    })
}

proptest! {
    #![proptest_config(config(48))]

    /// Random star polygons with up to three holes, loose points and non-crossing chords,
    /// optionally snapped to a binary grid, under every option set.
    #[test]
    fn star_domains(raw in domain_raw(false, 8), mode in mode()) {
        let d = build_domain(&raw);
        prop_assume!(d.is_some());
        let d = d.unwrap();
        run(&d.pslg, &options(mode, d.area), &d.spec)?;
    }

    /// Islands carry regional attributes (and, sometimes, regional area bounds).
    #[test]
    fn regions_with_attributes(
        raw in domain_raw(true, 0),
        angle in prop::option::of(prop_oneof![Just(20.0), Just(30.0)]),
        region_area in prop::option::of((20.0..200.0f64, 5.0..60.0f64)),
    ) {
        let d = build_domain(&raw);
        prop_assume!(d.is_some());
        let mut d = d.unwrap();
        prop_assume!(!d.pslg.regions.is_empty());
        if let Some((k0, k1)) = region_area {
            for (i, r) in d.pslg.regions.iter_mut().enumerate() {
                let a = if i == 0 { d.area / k0 } else { polygon_area(&d.spec.regions[i].poly) / k1 };
                r.max_area = Some(a);
                d.spec.regions[i].max_area = Some(a);
            }
        }
        let opts = Options {
            min_angle: angle,
            region_attributes: true,
            region_max_area: region_area.is_some(),
            ..quality(30.0)
        };
        run(&d.pslg, &opts, &d.spec)?;
    }
}

// ----------------------------------------------------------------------------- small angles

/// A wedge with apex angle `deg` at the origin (1°–10°), its far side a chain at random radii,
/// rotated by `rot`.
fn wedge(deg: f64, rot: f64, far: &[f64]) -> Vec<[f64; 2]> {
    let a = deg.to_radians();
    let m = far.len() + 1;
    let mut poly = vec![[0.0, 0.0], [1.0, 0.0]];
    for (k, &r) in far.iter().enumerate() {
        let t = a * (k + 1) as f64 / m as f64;
        poly.push([r * t.cos(), r * t.sin()]);
    }
    poly.push([a.cos(), a.sin()]);
    let (s, c) = rot.sin_cos();
    poly.iter()
        .map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]])
        .collect()
}

proptest! {
    #![proptest_config(config(48))]

    /// A polygon with one very small angle between two boundary segments.
    #[test]
    fn small_angle_wedges(
        deg in 1.0..10.0f64,
        rot in 0.0..TAU,
        far in prop::collection::vec(0.6..1.5f64, 0..=5),
        mode in mode(),
    ) {
        let poly = wedge(deg, rot, &far);
        let mut b = Builder::default();
        b.closed_loop(&poly);
        prop_assume!(pslg_is_valid(&b.pslg));
        let area = polygon_area(&poly);
        let spec = Spec { area: Some(area), outer: Some(poly), ..Spec::default() };
        run(&b.pslg, &options(mode, area), &spec)?;
    }

    /// Two chords from an interior point meeting at a small angle inside a star polygon.
    #[test]
    fn small_angle_chords(
        outer in star_raw(5..=20),
        deg in 1.0..10.0f64,
        dir in 0.0..TAU,
        len in (0.3..0.9f64, 0.3..0.9f64),
        mode in mode(),
    ) {
        let outer = star([0.0, 0.0], 0.5, 1.0, 0.0, &outer);
        let rho = inradius(&outer);
        let mut b = Builder::default();
        b.closed_loop(&outer);
        let o = b.point([0.0, 0.0]);
        let a = deg.to_radians();
        let p = b.point([len.0 * rho * dir.cos(), len.0 * rho * dir.sin()]);
        let r = b.point([len.1 * rho * (dir + a).cos(), len.1 * rho * (dir + a).sin()]);
        b.segment(o, p);
        b.segment(o, r);
        prop_assume!(pslg_is_valid(&b.pslg));
        let area = polygon_area(&outer);
        let spec = Spec { area: Some(area), outer: Some(outer), ..Spec::default() };
        run(&b.pslg, &options(mode, area), &spec)?;
    }
}

// ----------------------------------------------------------------------------- cocircular

proptest! {
    #![proptest_config(config(32))]

    /// Grid points (full of exactly cocircular quadruples when the spacing is representable)
    /// inside a square whose side segments pass through the boundary grid points.
    #[test]
    fn grids(
        nx in 2usize..12,
        ny in 2usize..12,
        h in prop_oneof![Just(1.0), Just(0.5), Just(0.1), Just(0.3)],
        keep in prop::collection::vec(any::<bool>(), 144),
        chords in prop::collection::vec((0.0..1.0f64, 0.0..1.0f64), 0..=6),
        mode in mode(),
    ) {
        let (w, ht) = ((nx - 1) as f64 * h, (ny - 1) as f64 * h);
        let outer = vec![[0.0, 0.0], [w, 0.0], [w, ht], [0.0, ht]];
        let mut b = Builder::default();
        b.closed_loop(&outer);
        for j in 0..ny {
            for i in 0..nx {
                let p = [i as f64 * h, j as f64 * h];
                if !outer.contains(&p) && keep[j * 12 + i] {
                    b.point(p);
                }
            }
        }
        let n = b.pslg.points.len();
        for &(fa, fb) in &chords {
            let (i, j) = (((fa * n as f64) as usize).min(n - 1), ((fb * n as f64) as usize).min(n - 1));
            let (pi, pj) = (b.pslg.points[i], b.pslg.points[j]);
            let ok = i != j
                && !b.pslg.segments.iter().any(|s| {
                    segments_conflict(pi, pj, b.pslg.points[s[0] as usize], b.pslg.points[s[1] as usize])
                })
                && locate(&outer, [0.5 * (pi[0] + pj[0]), 0.5 * (pi[1] + pj[1])]) == Loc::Inside;
            if ok {
                b.segment(i as u32, j as u32);
            }
        }
        prop_assume!(pslg_is_valid(&b.pslg));
        let area = w * ht;
        let spec = Spec { area: Some(area), outer: Some(outer), ..Spec::default() };
        run(&b.pslg, &options(mode, area), &spec)?;
    }

    /// A regular polygon (all vertices nearly cocircular), optionally with its centre and a
    /// concentric inner ring that is a hole or a second region.
    #[test]
    fn regular_polygons(
        n in 3usize..64,
        r in 0.1..100.0f64,
        phase in 0.0..TAU,
        center in any::<bool>(),
        inner in prop::option::of((3usize..24, 0.2..0.7f64, any::<bool>())),
        mode in mode(),
    ) {
        let poly = regular_polygon(n, [0.0, 0.0], r, phase);
        let mut b = Builder::default();
        b.closed_loop(&poly);
        let mut spec = Spec { outer: Some(poly.clone()), ..Spec::default() };
        let mut area = polygon_area(&poly);
        let mut opts_regions = false;
        if let Some((m, f, is_hole)) = inner {
            // The inner ring must fit inside the outer polygon's inscribed circle.
            let inr = r * (std::f64::consts::PI / n as f64).cos() * f;
            let ring = regular_polygon(m, [0.0, 0.0], inr, phase * 0.5);
            b.closed_loop(&ring);
            let mid = [0.0, 0.0];
            if is_hole {
                b.pslg.holes.push(mid);
                area -= polygon_area(&ring);
                spec.holes.push(ring);
            } else {
                // Between the ring's circumcircle and the outer polygon's incircle.
                let out = [0.5 * (inr + r * (std::f64::consts::PI / n as f64).cos()), 0.0];
                b.pslg.regions.push(Region { point: mid, attribute: 7.0, max_area: None });
                b.pslg.regions.push(Region { point: out, attribute: 3.0, max_area: None });
                spec.regions.push(RegionSpec { poly: ring.clone(), holes: vec![], attribute: 7.0, max_area: None });
                spec.regions.push(RegionSpec { poly: poly.clone(), holes: vec![ring], attribute: 3.0, max_area: None });
                opts_regions = true;
            }
        } else if center {
            b.point([0.0, 0.0]);
        }
        prop_assume!(pslg_is_valid(&b.pslg));
        spec.area = Some(area);
        let opts = Options { region_attributes: opts_regions, ..options(mode, area) };
        run(&b.pslg, &opts, &spec)?;
    }
}

// ----------------------------------------------------------------------------- -Y

/// The failure kinds the common checker reported, from the first line of its message
/// (`mesh check failed (...): kind: n, kind: n`); `None` when the line has another shape.
fn failure_kinds(msg: &str) -> Option<Vec<String>> {
    let first = msg.lines().next()?;
    let counts = first.split("): ").nth(1)?;
    counts
        .split(", ")
        .map(|kc| kc.split(": ").next().map(str::to_string))
        .collect()
}

/// Whether the closed segments `pq` and `rs` share a point (exact).
fn touches(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let o = |a, b, c| idmesh::predicates::orient2d(a, b, c);
    let between = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        o(a, b, c) == 0.0
            && a[0].min(b[0]) <= c[0]
            && c[0] <= a[0].max(b[0])
            && a[1].min(b[1]) <= c[1]
            && c[1] <= a[1].max(b[1])
    };
    let (o1, o2, o3, o4) = (o(p, q, r), o(p, q, s), o(r, s, p), o(r, s, q));
    ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0))
        && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0))
        || between(p, q, r)
        || between(p, q, s)
        || between(r, s, p)
        || between(r, s, q)
}

/// Checks a mesh made with `no_boundary_steiner`: everything the common checker checks except
/// the strict empty-circle rule and the quality bounds, then, independently of the mesher:
/// * no boundary edge (a triangle on one side only) has a Steiner endpoint;
/// * constrained Delaunay, exactly: every edge that is not a subsegment is locally Delaunay
///   (equivalent to the global rule for a domain bounded by segments), and no vertex inside a
///   circumcircle is seen from the triangle's centroid without crossing a subsegment;
/// * `validate_constrained` agrees.
fn run_fixed_boundary(pslg: &Pslg, opts: &Options, spec: &Spec) -> Result<(), TestCaseError> {
    let ctx = || format!("\noptions: {opts:?}\ninput:\n{}", common::poly_text(pslg));
    let m = idmesh::triangulate(pslg, opts)
        .map_err(|e| TestCaseError::fail(format!("triangulate failed: {e}{}", ctx())))?;
    prop_assert!(m.complete, "stopped at the Steiner guard{}", ctx());
    let loose = Spec {
        check_quality: false,
        ..spec.clone()
    };
    if let Err(msg) = common::check(&m, pslg, opts, &loose) {
        let kinds = failure_kinds(&msg);
        prop_assert!(
            kinds.is_some_and(|k| k.iter().all(|k| k == "delaunay")),
            "{msg}{}",
            ctx()
        );
    }
    let ni = pslg.points.len() as u32;
    let mut across: HashMap<(u32, u32), (usize, u32)> = HashMap::new();
    for (t, tri) in m.triangles.iter().enumerate() {
        for i in 0..3 {
            across.insert((tri[(i + 1) % 3], tri[(i + 2) % 3]), (t, tri[i]));
        }
    }
    let subseg: HashSet<(u32, u32)> = m
        .segments
        .iter()
        .map(|e| (e[0].min(e[1]), e[0].max(e[1])))
        .collect();
    for (&(a, b), &(t, _)) in &across {
        if !across.contains_key(&(b, a)) {
            prop_assert!(
                a < ni && b < ni,
                "boundary edge {a}-{b} of triangle {t} has a Steiner endpoint{}",
                ctx()
            );
        }
    }
    let pt = |v: u32| m.vertices[v as usize];
    for (&(a, b), &(t, _)) in &across {
        let Some(&(_, far)) = across.get(&(b, a)) else {
            continue;
        };
        if subseg.contains(&(a.min(b), a.max(b))) {
            continue;
        }
        let [p, q, r] = m.triangles[t].map(pt);
        prop_assert!(
            incircle(p, q, r, pt(far)) <= 0.0,
            "edge {a}-{b} is no subsegment and not locally Delaunay (vertex {far} in the circle of triangle {t}){}",
            ctx()
        );
    }
    for (t, tri) in m.triangles.iter().enumerate() {
        let [p, q, r] = tri.map(pt);
        let c = [(p[0] + q[0] + r[0]) / 3.0, (p[1] + q[1] + r[1]) / 3.0];
        let o = idmesh::predicates::orient2d;
        if !(o(p, q, c) > 0.0 && o(q, r, c) > 0.0 && o(r, p, c) > 0.0) {
            continue;
        }
        for v in 0..m.vertices.len() as u32 {
            if tri.contains(&v) || incircle(p, q, r, pt(v)) <= 0.0 {
                continue;
            }
            let hidden = m
                .segments
                .iter()
                .any(|e| touches(c, pt(v), pt(e[0]), pt(e[1])));
            prop_assert!(
                hidden,
                "vertex {v} in the circle of triangle {t} is seen from its centroid{}",
                ctx()
            );
        }
    }
    if let Err(e) = m.validate_constrained() {
        return Err(TestCaseError::fail(format!(
            "validate_constrained: {e}{}",
            ctx()
        )));
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(32))]

    /// -Y on random star domains with holes, chords (interior segments, which -Y may still
    /// split) and loose points; or with islands (regions) and no chords, since a chord would
    /// cut a region off its seed.
    #[test]
    fn fixed_boundary_star_domains(
        islands in any::<bool>(),
        raw_h in domain_raw(false, 8),
        raw_i in domain_raw(true, 0),
        mode in mode(),
    ) {
        let raw = if islands { raw_i } else { raw_h };
        let d = build_domain(&raw);
        prop_assume!(d.is_some());
        let d = d.unwrap();
        let opts = Options {
            no_boundary_steiner: true,
            region_attributes: !d.pslg.regions.is_empty(),
            ..options(mode, d.area)
        };
        run_fixed_boundary(&d.pslg, &opts, &d.spec)?;
    }

    /// -Y on small-angle wedges: the sharp corner is all boundary.
    #[test]
    fn fixed_boundary_wedges(
        deg in 1.0..10.0f64,
        rot in 0.0..TAU,
        far in prop::collection::vec(0.6..1.5f64, 0..=5),
        mode in mode(),
    ) {
        let poly = wedge(deg, rot, &far);
        let mut b = Builder::default();
        b.closed_loop(&poly);
        prop_assume!(pslg_is_valid(&b.pslg));
        let area = polygon_area(&poly);
        let spec = Spec { area: Some(area), outer: Some(poly), ..Spec::default() };
        let opts = Options { no_boundary_steiner: true, ..options(mode, area) };
        run_fixed_boundary(&b.pslg, &opts, &spec)?;
    }
}
