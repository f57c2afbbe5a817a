#![allow(dead_code)] // each target uses part of this module
//! Structure-aware mutations of small PSLGs and PLCs, as issue 14 lists them: coordinates
//! perturbed by 1e-15..1e-3 (relative), snapped to coarse grids, scaled by 1e±30, translated
//! by up to 1e7, a point added very close to another, tiny segments or facets added, facets
//! dropped. The fuzzer's bytes choose the seed shape, the mutations and the switches.

use arbitrary::Arbitrary;

/// One mutation; indices are taken modulo the current counts.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum Mutation {
    /// Moves one point by `10^-(3 + e % 13)` of the bounding box along a direction.
    Perturb { point: u16, e: u8, dir: [i8; 3] },
    /// Rounds every coordinate to a multiple of `2^-(b % 40)` of the bounding box.
    Snap { b: u8 },
    /// Scales every coordinate by `10^(e % 61 - 30)`.
    Scale { e: u8 },
    /// Translates by `10^(e % 8)` along a direction.
    Translate { e: u8, dir: [i8; 3] },
    /// Adds a point `10^-(4 + e % 12)` of the box away from an existing one.
    NearDuplicate { point: u16, e: u8, dir: [i8; 3] },
    /// Adds a tiny segment (2D) or triangle facet (3D) at a point of the domain, of size
    /// `10^-(2 + e % 12)` of the box.
    Tiny { point: u16, e: u8 },
    /// Removes one segment (2D) or facet (3D).
    Drop { item: u16 },
}

fn unit(dir: [i8; 3]) -> [f64; 3] {
    let d = dir.map(|x| x as f64);
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if n == 0.0 {
        [1.0, 0.0, 0.0]
    } else {
        d.map(|x| x / n)
    }
}

fn diameter<const D: usize>(pts: &[[f64; D]]) -> f64 {
    let mut d = 0.0f64;
    for k in 0..D {
        let lo = pts.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = pts.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
        d = d.max(hi - lo);
    }
    if d > 0.0 {
        d
    } else {
        1.0
    }
}

/// Applies `m` to a point set with `D` coordinates; returns a point to add, if any.
/// Hole points move with the whole-set mutations (snap, scale, translate).
fn move_points<const D: usize>(
    pts: &mut [[f64; D]],
    holes: &mut [[f64; D]],
    m: Mutation,
) -> Option<[f64; D]> {
    if pts.is_empty() {
        return None;
    }
    let d = diameter(pts);
    let n = pts.len();
    match m {
        Mutation::Perturb { point, e, dir } => {
            let u = unit(dir);
            let h = d * 10f64.powi(-(3 + (e % 13) as i32));
            let p = &mut pts[point as usize % n];
            for k in 0..D {
                p[k] += h * u[k];
            }
        }
        Mutation::Snap { b } => {
            let g = d * 2f64.powi(-((b % 40) as i32));
            for p in pts.iter_mut().chain(holes.iter_mut()) {
                for x in p.iter_mut() {
                    *x = (*x / g).round() * g;
                }
            }
        }
        Mutation::Scale { e } => {
            let s = 10f64.powi((e % 61) as i32 - 30);
            for p in pts.iter_mut().chain(holes.iter_mut()) {
                for x in p.iter_mut() {
                    *x *= s;
                }
            }
        }
        Mutation::Translate { e, dir } => {
            let u = unit(dir);
            let t = 10f64.powi((e % 8) as i32);
            for p in pts.iter_mut().chain(holes.iter_mut()) {
                for k in 0..D {
                    p[k] += t * u[k];
                }
            }
        }
        Mutation::NearDuplicate { point, e, dir } => {
            let u = unit(dir);
            let h = d * 10f64.powi(-(4 + (e % 12) as i32));
            let mut q = pts[point as usize % n];
            for k in 0..D {
                q[k] += h * u[k];
            }
            return Some(q);
        }
        Mutation::Tiny { .. } | Mutation::Drop { .. } => {}
    }
    None
}

/// The seed PSLGs: a square with a square hole, an L with a slit, a star with sharp spikes.
pub fn seed2(which: u8) -> idmesh::Pslg {
    type Shape = (Vec<[f64; 2]>, Vec<[u32; 2]>, Vec<[f64; 2]>);
    let (points, segments, holes): Shape = match which % 3 {
        0 => (
            vec![
                [0., 0.],
                [3., 0.],
                [3., 3.],
                [0., 3.],
                [1., 1.],
                [2., 1.],
                [2., 2.],
                [1., 2.],
            ],
            vec![
                [0, 1],
                [1, 2],
                [2, 3],
                [3, 0],
                [4, 5],
                [5, 6],
                [6, 7],
                [7, 4],
            ],
            vec![[1.5, 1.5]],
        ),
        1 => (
            vec![
                [0., 0.],
                [2., 0.],
                [2., 1.],
                [1., 1.],
                [1., 2.],
                [0., 2.],
                [0.5, 0.5],
                [1.5, 0.5],
            ],
            vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [6, 7]],
            vec![],
        ),
        _ => {
            let mut p = Vec::new();
            for i in 0..10 {
                let a = i as f64 * std::f64::consts::PI / 5.0;
                let r = if i % 2 == 0 { 1.0 } else { 0.15 };
                p.push([r * a.cos(), r * a.sin()]);
            }
            let s = (0..10u32).map(|i| [i, (i + 1) % 10]).collect();
            (p, s, vec![])
        }
    };
    idmesh::Pslg {
        points,
        segments,
        holes,
        ..Default::default()
    }
}

/// Applies the mutations to a PSLG.
pub fn mutate2(g: &mut idmesh::Pslg, muts: &[Mutation]) {
    for &m in muts {
        let n = g.points.len() as u32;
        match m {
            Mutation::Tiny { point, e } => {
                let d = diameter(&g.points) * 10f64.powi(-(2 + (e % 12) as i32));
                let c = g.points[point as usize % n as usize];
                let a = [c[0] + 0.3 * d, c[1] + 0.2 * d];
                g.points.push(a);
                g.points.push([a[0] + d, a[1] + 0.5 * d]);
                g.segments.push([n, n + 1]);
            }
            Mutation::Drop { item } if !g.segments.is_empty() => {
                let i = item as usize % g.segments.len();
                g.segments.remove(i);
            }
            _ => {
                if let Some(q) = move_points(&mut g.points, &mut g.holes, m) {
                    g.points.push(q);
                }
            }
        }
    }
    g.point_markers.clear();
    g.segment_markers.clear();
}

fn quad(v: [u32; 4]) -> idmesh::Facet {
    idmesh::Facet {
        polygons: vec![v.to_vec()],
        ..Default::default()
    }
}

/// The seed PLCs: a cube, a cube with a cubic hole, two boxes sharing a face.
pub fn seed3(which: u8) -> idmesh::Plc {
    let cube = |o: [f64; 3], s: [f64; 3], base: u32| {
        let mut p = Vec::new();
        for k in 0..8 {
            p.push([
                o[0] + s[0] * (k & 1) as f64,
                o[1] + s[1] * ((k >> 1) & 1) as f64,
                o[2] + s[2] * ((k >> 2) & 1) as f64,
            ]);
        }
        let f = [
            [0, 1, 3, 2],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 3, 7, 5],
        ]
        .map(|q: [u32; 4]| quad(q.map(|v| v + base)));
        (p, f.to_vec())
    };
    let mut plc = idmesh::Plc::default();
    let (p, f) = cube([0.; 3], [1.; 3], 0);
    plc.points = p;
    plc.facets = f;
    match which % 3 {
        0 => {}
        1 => {
            let (p, f) = cube([0.4, 0.4, 0.4], [0.2, 0.3, 0.25], 8);
            plc.points.extend(p);
            plc.facets.extend(f);
            plc.holes.push([0.5, 0.55, 0.5]);
        }
        _ => {
            let (p, f) = cube([1.0, 0.0, 0.0], [0.5, 1.0, 1.0], 8);
            plc.points.extend(p);
            // The shared face is listed once: drop the second box's face at x = 1.
            plc.facets.extend(
                f.into_iter()
                    .enumerate()
                    .filter(|(i, _)| *i != 4)
                    .map(|(_, f)| f),
            );
        }
    }
    plc
}

/// Applies the mutations to a PLC.
pub fn mutate3(g: &mut idmesh::Plc, muts: &[Mutation]) {
    for &m in muts {
        let n = g.points.len() as u32;
        match m {
            Mutation::Tiny { point, e } => {
                let d = diameter(&g.points) * 10f64.powi(-(2 + (e % 12) as i32));
                let c = g.points[point as usize % n as usize];
                g.points
                    .push([c[0] + 0.3 * d, c[1] + 0.2 * d, c[2] + 0.1 * d]);
                g.points
                    .push([c[0] + 1.3 * d, c[1] + 0.4 * d, c[2] + 0.1 * d]);
                g.points
                    .push([c[0] + 0.5 * d, c[1] + 1.1 * d, c[2] + 0.3 * d]);
                g.facets.push(idmesh::Facet {
                    polygons: vec![vec![n, n + 1, n + 2]],
                    ..Default::default()
                });
            }
            Mutation::Drop { item } if !g.facets.is_empty() => {
                let i = item as usize % g.facets.len();
                g.facets.remove(i);
            }
            _ => {
                if let Some(q) = move_points(&mut g.points, &mut g.holes, m) {
                    g.points.push(q);
                }
            }
        }
    }
    g.point_markers.clear();
}

/// A 2D case: a seed PSLG, its mutations, and the switches (`-q` angle 20..34, `-Y`).
#[derive(Arbitrary, Debug)]
pub struct Case2 {
    /// The seed shape ([`seed2`]).
    pub seed: u8,
    /// The mutations, in order (at most 8 are applied).
    pub muts: Vec<Mutation>,
    /// Minimum angle 20..34 degrees, or none.
    pub angle: Option<u8>,
    /// `-Y`: the result is then only constrained Delaunay.
    pub no_boundary_steiner: bool,
}

impl Case2 {
    /// The mutated input.
    pub fn input(&self) -> idmesh::Pslg {
        let mut g = seed2(self.seed);
        mutate2(&mut g, &self.muts[..self.muts.len().min(8)]);
        g
    }

    /// Builds the input and meshes it with the campaign's Steiner budget, 20,000.
    pub fn run(&self) -> Result<idmesh::TriMesh, idmesh::Error> {
        self.run_with_budget(20_000)
    }

    /// Builds the input and meshes it with at most `max_steiner` Steiner points.
    pub fn run_with_budget(&self, max_steiner: u64) -> Result<idmesh::TriMesh, idmesh::Error> {
        let g = self.input();
        let opts = idmesh::Options {
            min_angle: self.angle.map(|a| 20.0 + (a % 15) as f64),
            no_boundary_steiner: self.no_boundary_steiner,
            max_steiner: Some(max_steiner),
            ..Default::default()
        };
        idmesh::triangulate(&g, &opts)
    }
}

/// A 3D case: a seed PLC, its mutations, and the switches (`-q` ratio 1.2..2.0, `-Y`).
#[derive(Arbitrary, Debug)]
pub struct Case3 {
    /// The seed shape ([`seed3`]).
    pub seed: u8,
    /// The mutations, in order (at most 8 are applied).
    pub muts: Vec<Mutation>,
    /// Radius-edge bound 1.2..2.0, or none.
    pub ratio: Option<u8>,
    /// `-Y`: keep the input surface.
    pub keep_surface: bool,
}

impl Case3 {
    /// The mutated input.
    pub fn input(&self) -> idmesh::Plc {
        let mut g = seed3(self.seed);
        mutate3(&mut g, &self.muts[..self.muts.len().min(8)]);
        g
    }

    /// Builds the input and meshes it with the campaign's Steiner budget, 20,000.
    pub fn run(&self) -> Result<idmesh::TetMesh, idmesh::Error> {
        self.run_with_budget(20_000)
    }

    /// Builds the input and meshes it with at most `max_steiner` Steiner points.
    pub fn run_with_budget(&self, max_steiner: u64) -> Result<idmesh::TetMesh, idmesh::Error> {
        let g = self.input();
        let opts = idmesh::Options3 {
            radius_edge: self.ratio.map(|r| 1.2 + (r % 9) as f64 / 10.0),
            keep_surface: self.keep_surface,
            max_steiner: Some(max_steiner),
            ..Default::default()
        };
        idmesh::tetrahedralize(&g, &opts)
    }
}
