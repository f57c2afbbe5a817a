//! An independent checker of a 3D mesh against the PLC (or point set) it was made from.
//!
//! The checker establishes every fact itself, with Shewchuk's exact predicates from the `robust`
//! crate and its own face/edge maps and vertex grid, and only afterwards asks
//! `TetMesh::validate` for its verdict (the two must agree). Nothing of idmesh's internals is
//! used for a decision.
//!
//! Sign conventions (checked by `tests/degenerate3d.rs::orientation_convention`):
//! `robust::orient3d(a, b, c, d)` is positive when `d` lies below the plane of `a, b, c` seen
//! counter-clockwise from above, i.e. it is `det[a − d, b − d, c − d] = −det[b − a, c − a, d − a]`.
//! TetGen's (and `TetMesh`'s) positive tetrahedron has `det[b − a, c − a, d − a] > 0`, so a
//! tetrahedron is positive exactly when `robust::orient3d < 0`. `robust::insphere` is positive for
//! a point inside when the first four points are `robust`-positive; the product
//! `insphere · orient3d` is positive for "strictly inside" whatever the orientation.
//!
//! Tolerance: one, and only for *membership* of vertices in slanted input facets and edges,
//! since Steiner points there are rounded constructions: a vertex counts as on a slanted plane or
//! line when its distance is at most `Spec3::tol`. Axis-aligned facets and edges are held to exact
//! membership (equal coordinates). Every other decision is exact or a floating-point measure
//! (volume, area, radius-edge) compared with a stated relative slack.
#![allow(dead_code)]

use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use idmesh::{tetrahedralize, Options3, Plc, TetMesh};
use robust::Coord3D;

/// A point.
pub type P3 = [f64; 3];

/// The "no neighbour" value of `TetMesh::neighbors`.
pub const NO_TET: u32 = u32::MAX;
/// Relative tolerance of the total volume and of facet areas.
pub const REL_TOL: f64 = 1e-9;
/// Relative slack on the radius-edge and volume bounds (the ratio is a floating-point measure).
pub const BOUND_SLACK: f64 = 1e-9;

fn c3(p: P3) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

/// `robust::orient3d` (exact sign; see the module note for the convention).
pub fn orient(a: P3, b: P3, c: P3, d: P3) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// TetGen-positive: `det[b − a, c − a, d − a] > 0`, exactly.
pub fn tetgen_positive(t: [P3; 4]) -> bool {
    orient(t[0], t[1], t[2], t[3]) < 0.0
}

/// `e` lies strictly inside the circumsphere of the (non-degenerate) tetrahedron `t`, exactly.
pub fn strictly_in_sphere(t: [P3; 4], e: P3) -> bool {
    let s = robust::insphere(c3(t[0]), c3(t[1]), c3(t[2]), c3(t[3]), c3(e));
    let o = orient(t[0], t[1], t[2], t[3]);
    (s > 0.0 && o > 0.0) || (s < 0.0 && o < 0.0)
}

pub fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn add(a: P3, b: P3) -> P3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn scale(a: P3, s: f64) -> P3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: P3) -> f64 {
    dot(a, a).sqrt()
}

/// Signed volume in TetGen's sense (`det[b − a, c − a, d − a] / 6`), floating point.
pub fn tet_volume(t: [P3; 4]) -> f64 {
    dot(sub(t[1], t[0]), cross(sub(t[2], t[0]), sub(t[3], t[0]))) / 6.0
}

/// Circumcentre and squared circumradius (floating point), relative to nothing clever.
pub fn circumsphere(t: [P3; 4]) -> (P3, f64) {
    let a = t[0];
    let b = sub(t[1], a);
    let c = sub(t[2], a);
    let d = sub(t[3], a);
    let den = 2.0 * dot(b, cross(c, d));
    let num = add(
        add(scale(cross(c, d), dot(b, b)), scale(cross(d, b), dot(c, c))),
        scale(cross(b, c), dot(d, d)),
    );
    let o = scale(num, 1.0 / den);
    (add(a, o), dot(o, o))
}

/// Circumradius over shortest edge.
pub fn radius_edge(t: [P3; 4]) -> f64 {
    let (_, r2) = circumsphere(t);
    let mut lmin = f64::INFINITY;
    for i in 0..4 {
        for j in i + 1..4 {
            lmin = lmin.min(norm(sub(t[i], t[j])));
        }
    }
    r2.sqrt() / lmin
}

/// Neumaier-compensated sum.
pub fn sum_compensated(xs: impl IntoIterator<Item = f64>) -> f64 {
    let (mut s, mut c) = (0.0f64, 0.0f64);
    for x in xs {
        let t = s + x;
        c += if s.abs() >= x.abs() {
            (s - t) + x
        } else {
            (x - t) + s
        };
        s = t;
    }
    s + c
}

/// Signed area of a 2D polygon (shoelace, compensated).
pub fn polygon_area2(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    let o = poly[0];
    0.5 * sum_compensated((1..n.saturating_sub(1)).map(|i| {
        let a = [poly[i][0] - o[0], poly[i][1] - o[1]];
        let b = [poly[i + 1][0] - o[0], poly[i + 1][1] - o[1]];
        a[0] * b[1] - a[1] * b[0]
    }))
}

/// Even-odd point-in-polygon (floating point; used for centroids, which are far from edges).
pub fn inside2(poly: &[[f64; 2]], p: [f64; 2]) -> bool {
    let n = poly.len();
    let mut inside = false;
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

// ---------------------------------------------------------------------------------------------
// The domain a generator built, in its own ("local") frame, and the similarity to the PLC frame.

/// An exact similarity `global = m · local / div`, where `m = s·R` is the integer matrix of the
/// quaternion `(w, x, y, z)` with `s = w² + x² + y² + z²` and `div` a power of two. With small
/// integer entries and dyadic local coordinates, the products are exact: coplanar local points
/// stay exactly coplanar.
#[derive(Clone, Debug)]
pub struct Frame {
    pub m: [[f64; 3]; 3],
    pub s: f64,
    pub div: f64,
}

impl Frame {
    pub fn identity() -> Frame {
        Frame {
            m: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            s: 1.0,
            div: 1.0,
        }
    }

    /// The frame of the quaternion `(w, x, y, z)` (integers), divided by the power of two
    /// nearest to its norm.
    pub fn quaternion(w: i64, x: i64, y: i64, z: i64) -> Frame {
        let s = w * w + x * x + y * y + z * z;
        assert!(s > 0);
        let m = [
            [
                w * w + x * x - y * y - z * z,
                2 * (x * y - w * z),
                2 * (x * z + w * y),
            ],
            [
                2 * (x * y + w * z),
                w * w - x * x + y * y - z * z,
                2 * (y * z - w * x),
            ],
            [
                2 * (x * z - w * y),
                2 * (y * z + w * x),
                w * w - x * x - y * y + z * z,
            ],
        ]
        .map(|r| r.map(|v| v as f64));
        let div = 2f64.powi((s as f64).log2().round() as i32);
        Frame {
            m,
            s: s as f64,
            div,
        }
    }

    /// Local to global (exact for the inputs the generators build).
    pub fn apply(&self, p: P3) -> P3 {
        let m = &self.m;
        [0, 1, 2].map(|i| (m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2]) / self.div)
    }

    /// Global to local (floating point: for classification of centroids only).
    pub fn invert(&self, p: P3) -> P3 {
        let m = &self.m;
        let k = self.div / (self.s * self.s);
        [0, 1, 2].map(|j| (m[0][j] * p[0] + m[1][j] * p[1] + m[2][j] * p[2]) * k)
    }

    /// The linear scale factor `s / div`.
    pub fn factor(&self) -> f64 {
        self.s / self.div
    }
}

/// A prism cell of the domain in the local frame: `outer` minus `holes` (2D, in the xy-plane)
/// times `[z0, z1]`, carrying a region attribute.
#[derive(Clone, Debug)]
pub struct Cell {
    pub outer: Vec<[f64; 2]>,
    pub holes: Vec<Vec<[f64; 2]>>,
    pub z0: f64,
    pub z1: f64,
    pub attribute: f64,
}

impl Cell {
    pub fn cuboid(lo: P3, hi: P3, attribute: f64) -> Cell {
        Cell {
            outer: vec![
                [lo[0], lo[1]],
                [hi[0], lo[1]],
                [hi[0], hi[1]],
                [lo[0], hi[1]],
            ],
            holes: vec![],
            z0: lo[2],
            z1: hi[2],
            attribute,
        }
    }

    pub fn volume(&self) -> f64 {
        let a = polygon_area2(&self.outer).abs()
            - self
                .holes
                .iter()
                .map(|h| polygon_area2(h).abs())
                .sum::<f64>();
        a * (self.z1 - self.z0)
    }

    pub fn contains(&self, p: P3) -> bool {
        p[2] > self.z0
            && p[2] < self.z1
            && inside2(&self.outer, [p[0], p[1]])
            && !self.holes.iter().any(|h| inside2(h, [p[0], p[1]]))
    }
}

/// The domain: disjoint cells in the local frame and the frame.
#[derive(Clone, Debug)]
pub struct Domain {
    pub cells: Vec<Cell>,
    pub frame: Frame,
}

impl Domain {
    pub fn volume(&self) -> f64 {
        self.cells.iter().map(Cell::volume).sum::<f64>() * self.frame.factor().powi(3)
    }

    /// The cell containing global point `p`, if any.
    pub fn locate(&self, p: P3) -> Option<usize> {
        let q = self.frame.invert(p);
        self.cells.iter().position(|c| c.contains(q))
    }
}

// ---------------------------------------------------------------------------------------------
// The specification a test gives the checker.

#[derive(Clone, Debug)]
pub struct Spec3 {
    /// The domain (volume, hole-freedom, regions). `None`: only `volume` is checked, if set.
    pub domain: Option<Domain>,
    /// Expected total volume when there is no domain.
    pub volume: Option<f64>,
    /// Assert the radius-edge and volume bounds on every tetrahedron (only for inputs without
    /// input angles below 90 degrees).
    pub check_quality: bool,
    /// Every input point must be a vertex of some tetrahedron.
    pub all_inputs_used: bool,
    /// Membership tolerance for slanted facets and edges (absolute distance).
    pub tol: f64,
    /// The mesher must return within this time.
    pub timeout: Duration,
}

impl Default for Spec3 {
    fn default() -> Self {
        Spec3 {
            domain: None,
            volume: None,
            check_quality: true,
            all_inputs_used: true,
            tol: 0.0,
            timeout: Duration::from_secs(120),
        }
    }
}

/// Figures of a checked mesh.
#[derive(Clone, Debug, Default)]
pub struct Report3 {
    pub tets: usize,
    pub vertices: usize,
    pub steiner: usize,
    pub volume: f64,
    pub max_radius_edge: f64,
    /// Largest distance of a vertex counted as lying in a slanted facet from its plane.
    pub max_plane_dev: f64,
    pub seconds: f64,
}

// ---------------------------------------------------------------------------------------------
// A uniform grid over the vertices.

pub struct Grid {
    lo: P3,
    h: f64,
    dims: [usize; 3],
    cells: Vec<Vec<u32>>,
}

impl Grid {
    pub fn new(pts: &[P3], ids: impl Iterator<Item = u32>) -> Grid {
        let ids: Vec<u32> = ids.collect();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for &i in &ids {
            for k in 0..3 {
                lo[k] = lo[k].min(pts[i as usize][k]);
                hi[k] = hi[k].max(pts[i as usize][k]);
            }
        }
        if ids.is_empty() {
            lo = [0.0; 3];
            hi = [1.0; 3];
        }
        let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f64, f64::max);
        let ext = if ext > 0.0 { ext } else { 1.0 };
        // About two points per cell in the bounding cube's worth of cells.
        let per_axis = ((ids.len() as f64 / 2.0).cbrt().ceil() as usize).clamp(1, 64);
        let h = ext / per_axis as f64 * (1.0 + 1e-9);
        let dims = [0, 1, 2].map(|k| (((hi[k] - lo[k]) / h) as usize + 1).max(1));
        let mut cells = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        let mut g = Grid {
            lo,
            h,
            dims,
            cells: Vec::new(),
        };
        for &i in &ids {
            let c = g.cell_of(pts[i as usize]);
            cells[g.index(c)].push(i);
        }
        g.cells = cells;
        g
    }

    fn cell_of(&self, p: P3) -> [usize; 3] {
        [0, 1, 2].map(|k| {
            let x = ((p[k] - self.lo[k]) / self.h).floor();
            if x.is_nan() || x < 0.0 {
                0
            } else {
                (x as usize).min(self.dims[k] - 1)
            }
        })
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// Calls `f` on every point in a cell meeting the box `[lo, hi]`.
    pub fn query(&self, lo: P3, hi: P3, mut f: impl FnMut(u32) -> bool) -> bool {
        let a = self.cell_of(lo);
        let b = self.cell_of(hi);
        for z in a[2]..=b[2] {
            for y in a[1]..=b[1] {
                for x in a[0]..=b[0] {
                    for &i in &self.cells[self.index([x, y, z])] {
                        if !f(i) {
                            return false;
                        }
                    }
                }
            }
        }
        true
    }
}

// ---------------------------------------------------------------------------------------------
// Mesh topology the checker builds itself.

fn sorted3(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

fn sorted2(a: u32, b: u32) -> [u32; 2] {
    if a < b {
        [a, b]
    } else {
        [b, a]
    }
}

/// The face of `tet` opposite corner `i`.
fn face_opposite(tet: [u32; 4], i: usize) -> [u32; 3] {
    let mut f = [0u32; 3];
    let mut k = 0;
    for (j, &v) in tet.iter().enumerate() {
        if j != i {
            f[k] = v;
            k += 1;
        }
    }
    sorted3(f)
}

pub struct Topology {
    /// Sorted face -> the tets (and local index) having it.
    pub faces: HashMap<[u32; 3], Vec<(u32, u8)>>,
    pub edges: HashSet<[u32; 2]>,
    pub used: Vec<bool>,
}

/// Structural checks: indices, distinct corners, faces shared by at most two tets, neighbours
/// symmetric and matching the faces, positive orientation (exact).
pub fn topology(mesh: &TetMesh) -> Result<Topology, String> {
    let nv = mesh.vertices.len();
    if mesh.vertex_markers.len() != nv {
        return Err(format!(
            "{} vertex markers for {nv} vertices",
            mesh.vertex_markers.len()
        ));
    }
    if mesh.neighbors.len() != mesh.tets.len() {
        return Err(format!(
            "{} neighbour rows for {} tets",
            mesh.neighbors.len(),
            mesh.tets.len()
        ));
    }
    let mut faces: HashMap<[u32; 3], Vec<(u32, u8)>> = HashMap::new();
    let mut edges = HashSet::new();
    let mut used = vec![false; nv];
    for (t, tet) in mesh.tets.iter().enumerate() {
        for &v in tet {
            if v as usize >= nv {
                return Err(format!("tet {t} {tet:?}: vertex index out of range"));
            }
            used[v as usize] = true;
        }
        let mut s = *tet;
        s.sort_unstable();
        if s.windows(2).any(|w| w[0] == w[1]) {
            return Err(format!("tet {t} {tet:?}: repeated vertex"));
        }
        let c = tet.map(|v| mesh.vertices[v as usize]);
        if !tetgen_positive(c) {
            return Err(format!(
                "tet {t} {tet:?} is not positively oriented (exact orient3d = {:e})",
                orient(c[0], c[1], c[2], c[3])
            ));
        }
        for i in 0..4 {
            faces
                .entry(face_opposite(*tet, i))
                .or_default()
                .push((t as u32, i as u8));
            for j in i + 1..4 {
                edges.insert(sorted2(tet[i], tet[j]));
            }
        }
    }
    for (f, ts) in &faces {
        if ts.len() > 2 {
            return Err(format!("face {f:?} is shared by {} tets", ts.len()));
        }
        for (k, &(t, i)) in ts.iter().enumerate() {
            let want = if ts.len() == 2 { ts[1 - k].0 } else { NO_TET };
            let got = mesh.neighbors[t as usize][i as usize];
            if got != want {
                return Err(format!(
                    "neighbour of tet {t} across face {f:?} is {got}, expected {want}"
                ));
            }
        }
        if ts.len() == 2 {
            // The two tets lie on opposite sides of their common face (exact).
            let sides: Vec<f64> = ts
                .iter()
                .map(|&(t, i)| {
                    let p = mesh.vertices[mesh.tets[t as usize][i as usize] as usize];
                    let q = f.map(|v| mesh.vertices[v as usize]);
                    orient(q[0], q[1], q[2], p)
                })
                .collect();
            if sides[0] * sides[1] >= 0.0 {
                return Err(format!("tets {:?} overlap across face {f:?}", ts));
            }
        }
    }
    Ok(Topology { faces, edges, used })
}

/// Exact Delaunay: no vertex of `mesh` strictly inside any tet's circumsphere.
pub fn check_delaunay(mesh: &TetMesh) -> Result<(), String> {
    let pts = &mesh.vertices;
    let grid = Grid::new(pts, 0..pts.len() as u32);
    let mut diam = 0.0f64;
    for k in 0..3 {
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p[k]), b.max(p[k]))
            });
        diam = diam.max(hi - lo);
    }
    for (t, tet) in mesh.tets.iter().enumerate() {
        let c = tet.map(|v| pts[v as usize]);
        let (o, r2) = circumsphere(c);
        let mut bad = None;
        let mut test = |v: u32| {
            if tet.contains(&v) {
                return true;
            }
            if strictly_in_sphere(c, pts[v as usize]) {
                bad = Some(v);
                return false;
            }
            true
        };
        // The float centre is trusted only for tets that are not flat relative to their
        // edges (its error grows like the determinant's condition number); flat ones are
        // checked against every vertex.
        let (e1, e2, e3) = (sub(c[1], c[0]), sub(c[2], c[0]), sub(c[3], c[0]));
        let det = dot(e1, cross(e2, e3)).abs();
        let well = o.iter().all(|x| x.is_finite())
            && r2.is_finite()
            && r2.sqrt() < 1e3 * diam
            && det > 1e-6 * norm(e1) * norm(e2) * norm(e3);
        if well {
            // The centre's rounding error is far below this margin; points strictly inside
            // the sphere are within r of the float centre.
            let r = r2.sqrt() * (1.0 + 1e-6) + 1e-9 * diam;
            let lo = [0, 1, 2].map(|k| o[k] - r);
            let hi = [0, 1, 2].map(|k| o[k] + r);
            grid.query(lo, hi, |v| {
                let d = sub(pts[v as usize], o);
                if dot(d, d) > r * r {
                    return true;
                }
                test(v)
            });
        } else {
            for v in 0..pts.len() as u32 {
                if !test(v) {
                    break;
                }
            }
        }
        if let Some(v) = bad {
            return Err(format!(
                "not Delaunay: vertex {v} {:?} is strictly inside the circumsphere of tet {t} {tet:?} {c:?}",
                pts[v as usize]
            ));
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Facets and input edges.

/// A facet's plane and projection.
struct FacetGeom {
    a: P3,
    /// Unit normal (floating point).
    n: P3,
    /// The normal's single non-zero axis when the facet is axis-aligned (exact).
    axis: Option<usize>,
    /// Dropped coordinate for the 2D projection.
    drop: usize,
    loops: Vec<Vec<[f64; 2]>>,
    area: f64,
}

fn project(p: P3, drop: usize) -> [f64; 2] {
    match drop {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

fn facet_geom(plc: &Plc, f: usize) -> Result<FacetGeom, String> {
    let facet = &plc.facets[f];
    let verts: Vec<P3> = facet
        .polygons
        .iter()
        .flatten()
        .map(|&v| plc.points[v as usize])
        .collect();
    let a = verts[0];
    let mut best = ([0.0; 3], 0.0);
    for &b in &verts {
        for &c in &verts {
            let n = cross(sub(b, a), sub(c, a));
            let l = norm(n);
            if l > best.1 {
                best = (n, l);
            }
        }
    }
    let (n0, l) = best;
    if l == 0.0 {
        return Err(format!("facet {f} has no plane"));
    }
    let n = scale(n0, 1.0 / l);
    let zeros: Vec<usize> = (0..3).filter(|&k| n0[k] == 0.0).collect();
    let axis = if zeros.len() == 2 {
        (0..3).find(|k| !zeros.contains(k))
    } else {
        None
    };
    if let Some(k) = axis {
        if verts.iter().any(|p| p[k] != a[k]) {
            return Err(format!("facet {f} is not planar"));
        }
    }
    let drop = (0..3)
        .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap();
    let mut loops = Vec::new();
    let mut area = 0.0;
    for (pi, poly) in facet.polygons.iter().enumerate() {
        if poly.len() < 3 {
            continue;
        }
        let pts: Vec<P3> = poly.iter().map(|&v| plc.points[v as usize]).collect();
        // Newell's area vector, relative to the first vertex.
        let mut s = [0.0; 3];
        for i in 1..pts.len() - 1 {
            s = add(s, cross(sub(pts[i], pts[0]), sub(pts[i + 1], pts[0])));
        }
        let la = 0.5 * norm(s);
        // Convention of the generators: the first loop is the outer boundary, later loops
        // bound holes (each with a hole seed); 1- and 2-vertex polygons carry no area.
        area += if pi == 0 { la } else { -la };
        loops.push(pts.iter().map(|&p| project(p, drop)).collect());
    }
    Ok(FacetGeom {
        a,
        n,
        axis,
        drop,
        loops,
        area,
    })
}

impl FacetGeom {
    /// Distance of `p` from the plane when it counts as on it.
    fn on_plane(&self, p: P3, tol: f64) -> Option<f64> {
        match self.axis {
            Some(k) => (p[k] == self.a[k]).then_some(0.0),
            None => {
                let d = dot(sub(p, self.a), self.n).abs();
                (d <= tol).then_some(d)
            }
        }
    }

    /// Even-odd over all loops.
    fn region_contains(&self, p: P3) -> bool {
        let q = project(p, self.drop);
        self.loops.iter().filter(|l| inside2(l, q)).count() % 2 == 1
    }
}

/// Every input edge: segments and polygon edges (loops closed), deduplicated.
pub fn input_edges(plc: &Plc) -> Vec<[u32; 2]> {
    let mut set = HashSet::new();
    for s in &plc.segments {
        set.insert(sorted2(s[0], s[1]));
    }
    for f in &plc.facets {
        for poly in &f.polygons {
            match poly.len() {
                0 | 1 => {}
                2 => {
                    set.insert(sorted2(poly[0], poly[1]));
                }
                n => {
                    for i in 0..n {
                        set.insert(sorted2(poly[i], poly[(i + 1) % n]));
                    }
                }
            }
        }
    }
    let mut v: Vec<[u32; 2]> = set.into_iter().collect();
    v.sort_unstable();
    v
}

/// The vertices of `mesh` on the open input edge `(a, b)`, sorted from `a` to `b`, with `a`
/// and `b` at the ends.
fn vertices_on_edge(mesh: &TetMesh, grid: &Grid, e: [u32; 2], tol: f64) -> Vec<u32> {
    let pa = mesh.vertices[e[0] as usize];
    let pb = mesh.vertices[e[1] as usize];
    let d = sub(pb, pa);
    let len2 = dot(d, d);
    let same: Vec<usize> = (0..3).filter(|&k| pa[k] == pb[k]).collect();
    let lo = [0, 1, 2].map(|k| pa[k].min(pb[k]) - tol);
    let hi = [0, 1, 2].map(|k| pa[k].max(pb[k]) + tol);
    let mut on: Vec<(f64, u32)> = Vec::new();
    grid.query(lo, hi, |v| {
        if v == e[0] || v == e[1] {
            return true;
        }
        let p = mesh.vertices[v as usize];
        let t = dot(sub(p, pa), d) / len2;
        let hit = if same.len() == 2 {
            // Axis-aligned: exact.
            let k = 3 - same[0] - same[1];
            same.iter().all(|&j| p[j] == pa[j])
                && p[k] > pa[k].min(pb[k])
                && p[k] < pa[k].max(pb[k])
        } else {
            let foot = add(pa, scale(d, t));
            t > 0.0 && t < 1.0 && norm(sub(p, foot)) <= tol
        };
        if hit {
            on.push((t, v));
        }
        true
    });
    on.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut out = vec![e[0]];
    out.extend(on.into_iter().map(|x| x.1));
    out.push(e[1]);
    out
}

// ---------------------------------------------------------------------------------------------
// The checks.

/// Checks a mesh of a PLC. Returns figures, or the first violated invariant.
pub fn check_plc_mesh(
    plc: &Plc,
    opts: &Options3,
    mesh: &TetMesh,
    spec: &Spec3,
) -> Result<Report3, String> {
    let n_in = plc.points.len();
    if mesh.num_input_vertices != n_in || mesh.vertices.len() < n_in {
        return Err(format!(
            "{} input vertices reported, {} vertices, {n_in} input points",
            mesh.num_input_vertices,
            mesh.vertices.len()
        ));
    }
    for (i, p) in plc.points.iter().enumerate() {
        if mesh.vertices[i].map(f64::to_bits) != p.map(f64::to_bits) {
            return Err(format!(
                "input vertex {i} moved: {:?} -> {:?}",
                p, mesh.vertices[i]
            ));
        }
    }
    if mesh.tets.is_empty() {
        return Err("no tetrahedra".into());
    }
    let topo = topology(mesh)?;
    if opts.keep_surface {
        // Keeping the surface (-Y): no Steiner point on it; not Delaunay next to it.
        if !mesh.surface_kept {
            return Err("keep_surface was asked, the mesh does not say it kept the surface".into());
        }
        for f in &mesh.faces {
            if let Some(&v) = f.iter().find(|&&v| v as usize >= n_in) {
                return Err(format!("subface {f:?} has the Steiner vertex {v} (-Y)"));
            }
        }
        for e in &mesh.edges {
            if let Some(&v) = e.iter().find(|&&v| v as usize >= n_in) {
                return Err(format!("subsegment {e:?} has the Steiner vertex {v} (-Y)"));
            }
        }
    } else {
        check_delaunay(mesh)?;
    }
    if spec.all_inputs_used {
        if let Some(i) = (0..n_in).find(|&i| !topo.used[i]) {
            return Err(format!("input vertex {i} {:?} is in no tet", plc.points[i]));
        }
    }
    // Volume, holes, regions.
    let vols: Vec<f64> = (0..mesh.tets.len())
        .map(|t| tet_volume(mesh.corners(t)))
        .collect();
    let volume = sum_compensated(vols.iter().copied());
    let want = spec.domain.as_ref().map(Domain::volume).or(spec.volume);
    if let Some(w) = want {
        if (volume - w).abs() > REL_TOL * w.abs() {
            return Err(format!("total volume {volume} vs the PLC's {w}"));
        }
    }
    // Subfaces.
    let subfaces: HashMap<[u32; 3], i32> = mesh
        .faces
        .iter()
        .enumerate()
        .map(|(i, f)| (sorted3(*f), mesh.face_markers.get(i).copied().unwrap_or(0)))
        .collect();
    if subfaces.len() != mesh.faces.len() {
        return Err("repeated subface".into());
    }
    for f in subfaces.keys() {
        if !topo.faces.contains_key(f) {
            return Err(format!("subface {f:?} is not a face of any tet"));
        }
    }
    for (f, ts) in &topo.faces {
        if ts.len() == 1 && !subfaces.contains_key(f) {
            return Err(format!("boundary face {f:?} is not a subface"));
        }
    }
    // Facets: the faces in each facet cover exactly its area, and are subfaces with its marker.
    // The membership tolerance: at least 64 ulps of the largest coordinate (the plane test's own
    // rounding is far below that).
    let mag = mesh
        .vertices
        .iter()
        .flatten()
        .fold(0.0f64, |a, x| a.max(x.abs()));
    let tol = spec.tol.max(64.0 * f64::EPSILON * mag);
    let geoms: Vec<FacetGeom> = (0..plc.facets.len())
        .map(|f| facet_geom(plc, f))
        .collect::<Result<_, _>>()?;
    // No tet may have all four vertices in one facet's plane (a flat tet glued onto a facet:
    // exactly positive only through the rounding of its Steiner points).
    for t in 0..mesh.tets.len() {
        let c = mesh.corners(t);
        for (fi, g) in geoms.iter().enumerate() {
            if c.iter().all(|&p| g.on_plane(p, tol).is_some()) {
                return Err(format!(
                    "tet {t} {:?} is flat: all four vertices lie in the plane of facet {fi} (volume {:e}, corners {c:?})",
                    mesh.tets[t],
                    tet_volume(c)
                ));
            }
        }
    }
    if let Some(dom) = &spec.domain {
        for t in 0..mesh.tets.len() {
            let c = mesh.corners(t);
            let g = scale(add(add(c[0], c[1]), add(c[2], c[3])), 0.25);
            let Some(cell) = dom.locate(g) else {
                return Err(format!(
                    "tet {t} {:?}: centroid {g:?} lies outside the domain or in a hole",
                    mesh.tets[t]
                ));
            };
            if opts.region_attributes {
                let want = dom.cells[cell].attribute;
                if mesh.tet_attributes.get(t) != Some(&want) {
                    return Err(format!(
                        "tet {t}: attribute {:?}, expected {want} (cell {cell})",
                        mesh.tet_attributes.get(t)
                    ));
                }
            }
        }
    }
    let mut area_in = vec![Vec::new(); geoms.len()];
    let mut in_some_facet: HashSet<[u32; 3]> = HashSet::new();
    let mut max_dev = 0.0f64;
    for f in topo.faces.keys() {
        let q = f.map(|v| mesh.vertices[v as usize]);
        let centroid = scale(add(add(q[0], q[1]), q[2]), 1.0 / 3.0);
        for (fi, g) in geoms.iter().enumerate() {
            let devs: Vec<Option<f64>> = q.iter().map(|&p| g.on_plane(p, tol)).collect();
            if devs.iter().all(Option::is_some) && g.region_contains(centroid) {
                for d in devs.into_iter().flatten() {
                    max_dev = max_dev.max(d);
                }
                let a = 0.5 * norm(cross(sub(q[1], q[0]), sub(q[2], q[0])));
                area_in[fi].push(a);
                in_some_facet.insert(*f);
                match subfaces.get(f) {
                    None => return Err(format!("face {f:?} lies in facet {fi} but is no subface")),
                    Some(&m) if m != plc.facets[fi].marker => {
                        return Err(format!(
                            "subface {f:?} in facet {fi} has marker {m}, expected {}",
                            plc.facets[fi].marker
                        ))
                    }
                    _ => {}
                }
            }
        }
    }
    for (fi, g) in geoms.iter().enumerate() {
        let a = sum_compensated(area_in[fi].iter().copied());
        if (a - g.area).abs() > REL_TOL * g.area {
            return Err(format!(
                "facet {fi}: mesh faces in it cover area {a}, the facet has {} ({} faces)",
                g.area,
                area_in[fi].len()
            ));
        }
    }
    for f in subfaces.keys() {
        if !in_some_facet.contains(f) {
            return Err(format!("subface {f:?} lies in no input facet"));
        }
    }
    // Input edges: the vertices on each, in order, are joined by mesh edges and subsegments.
    let subsegs: HashSet<[u32; 2]> = mesh.edges.iter().map(|e| sorted2(e[0], e[1])).collect();
    for e in &subsegs {
        if !topo.edges.contains(e) {
            return Err(format!("subsegment {e:?} is not an edge of any tet"));
        }
    }
    let used_ids = (0..mesh.vertices.len() as u32).filter(|&v| topo.used[v as usize]);
    let vgrid = Grid::new(&mesh.vertices, used_ids);
    for e in input_edges(plc) {
        let chain = vertices_on_edge(mesh, &vgrid, e, tol);
        for w in chain.windows(2) {
            let k = sorted2(w[0], w[1]);
            if !topo.edges.contains(&k) {
                return Err(format!(
                    "input edge {e:?}: consecutive vertices {k:?} on it are not joined by a mesh edge (chain {chain:?})"
                ));
            }
            if !subsegs.contains(&k) {
                return Err(format!(
                    "input edge {e:?}: mesh edge {k:?} on it is not a subsegment"
                ));
            }
        }
    }
    // Quality.
    let mut max_re = 0.0f64;
    for t in 0..mesh.tets.len() {
        max_re = max_re.max(radius_edge(mesh.corners(t)));
    }
    if spec.check_quality {
        if !mesh.complete {
            return Err("refinement did not complete".into());
        }
        if let Some(b) = opts.radius_edge {
            for t in 0..mesh.tets.len() {
                let r = radius_edge(mesh.corners(t));
                if r > b * (1.0 + BOUND_SLACK) {
                    return Err(format!(
                        "tet {t} {:?} {:?}: radius-edge {r} > {b}",
                        mesh.tets[t],
                        mesh.corners(t)
                    ));
                }
            }
        }
        if let Some(vmax) = opts.max_volume {
            if let Some(t) = (0..vols.len()).find(|&t| vols[t] > vmax * (1.0 + BOUND_SLACK)) {
                return Err(format!("tet {t}: volume {} > {vmax}", vols[t]));
            }
        }
    }
    // Only now the mesher's own validator; it must agree.
    mesh.validate()
        .map_err(|e| format!("checker accepts, validate() rejects: {e}"))?;
    Ok(Report3 {
        tets: mesh.tets.len(),
        vertices: mesh.vertices.len(),
        steiner: mesh.vertices.len() - n_in,
        volume,
        max_radius_edge: max_re,
        max_plane_dev: max_dev,
        seconds: 0.0,
    })
}

/// Checks a Delaunay tetrahedralization of a point set: structure, exact Delaunay, every point
/// used, the boundary faces are exactly the subfaces, and the union is convex (no vertex strictly
/// outside any boundary face's plane, exact), i.e. it is the convex hull.
pub fn check_point_mesh(points: &[P3], mesh: &TetMesh) -> Result<Report3, String> {
    if mesh.vertices.len() != points.len() {
        return Err(format!(
            "{} vertices for {} points",
            mesh.vertices.len(),
            points.len()
        ));
    }
    for (i, p) in points.iter().enumerate() {
        if mesh.vertices[i].map(f64::to_bits) != p.map(f64::to_bits) {
            return Err(format!("vertex {i} moved"));
        }
    }
    let topo = topology(mesh)?;
    check_delaunay(mesh)?;
    if let Some(i) = (0..points.len()).find(|&i| !topo.used[i]) {
        return Err(format!("point {i} {:?} is in no tet", points[i]));
    }
    let subfaces: HashSet<[u32; 3]> = mesh.faces.iter().map(|f| sorted3(*f)).collect();
    for (f, ts) in &topo.faces {
        if ts.len() == 1 {
            if !subfaces.contains(f) {
                return Err(format!("hull face {f:?} is not a subface"));
            }
            let (t, i) = ts[0];
            let tet = mesh.tets[t as usize];
            let apex = mesh.vertices[tet[i as usize] as usize];
            let q = f.map(|v| mesh.vertices[v as usize]);
            let inner = orient(q[0], q[1], q[2], apex);
            for (v, &p) in points.iter().enumerate() {
                let o = orient(q[0], q[1], q[2], p);
                if o * inner < 0.0 {
                    return Err(format!(
                        "not convex: point {v} lies outside the hull face {f:?}"
                    ));
                }
            }
        } else if subfaces.contains(f) {
            return Err(format!("interior face {f:?} listed as a subface"));
        }
    }
    let volume = sum_compensated((0..mesh.tets.len()).map(|t| tet_volume(mesh.corners(t))));
    mesh.validate()
        .map_err(|e| format!("checker accepts, validate() rejects: {e}"))?;
    Ok(Report3 {
        tets: mesh.tets.len(),
        vertices: mesh.vertices.len(),
        steiner: 0,
        volume,
        max_radius_edge: 0.0,
        max_plane_dev: 0.0,
        seconds: 0.0,
    })
}

/// Runs `f` on a thread and gives up after `timeout` (the thread is left running: the test
/// fails with "did not terminate").
pub fn with_timeout<T: Send + 'static>(
    timeout: Duration,
    f: impl FnOnce() -> T + Send + 'static,
) -> Result<T, String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(timeout).map_err(|e| match e {
        mpsc::RecvTimeoutError::Timeout => {
            format!("did not terminate within {} s", timeout.as_secs_f64())
        }
        mpsc::RecvTimeoutError::Disconnected => "the meshing thread panicked".to_string(),
    })
}

/// Meshes `plc` under `opts` (with a time limit) and checks the result.
pub fn mesh_and_check(
    plc: &Plc,
    opts: &Options3,
    spec: &Spec3,
) -> Result<(TetMesh, Report3), String> {
    let start = Instant::now();
    let (p, o) = (plc.clone(), opts.clone());
    let mesh = with_timeout(spec.timeout, move || tetrahedralize(&p, &o))
        .and_then(|r| r.map_err(|e| format!("tetrahedralize failed: {e}")))
        .map_err(|e| format!("{e}\noptions: {opts:?}\ninput:\n{}", plc_rust(plc)))?;
    let secs = start.elapsed().as_secs_f64();
    let mut rep = check_plc_mesh(plc, opts, &mesh, spec)
        .map_err(|e| format!("{e}\noptions: {opts:?}\ninput:\n{}", plc_rust(plc)))?;
    rep.seconds = secs;
    Ok((mesh, rep))
}

/// A PLC as a Rust literal (for reproducers in failure messages).
pub fn plc_rust(plc: &Plc) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Plc {{");
    let _ = writeln!(s, "    points: vec![");
    for p in &plc.points {
        let _ = writeln!(s, "        [{:?}, {:?}, {:?}],", p[0], p[1], p[2]);
    }
    let _ = writeln!(s, "    ],");
    if !plc.segments.is_empty() {
        let _ = writeln!(s, "    segments: vec!{:?},", plc.segments);
    }
    let _ = writeln!(s, "    facets: vec![");
    for f in &plc.facets {
        let _ = writeln!(
            s,
            "        Facet {{ polygons: vec!{:?}.into_iter().map(|p: &[u32]| p.to_vec()).collect(), holes: vec!{:?}, marker: {} }},",
            f.polygons.iter().map(|p| p.as_slice()).collect::<Vec<_>>(),
            f.holes,
            f.marker
        );
    }
    let _ = writeln!(s, "    ],");
    if !plc.holes.is_empty() {
        let _ = writeln!(s, "    holes: vec!{:?},", plc.holes);
    }
    if !plc.regions.is_empty() {
        let _ = writeln!(s, "    regions: vec!{:?},", plc.regions);
    }
    let _ = writeln!(s, "    ..Plc::default()\n}}");
    s
}

// ---------------------------------------------------------------------------------------------
// PLC builders shared by the tests.

/// The six quadrilateral facets of an axis-aligned box with corners `lo`, `hi`.
pub fn add_box(plc: &mut Plc, lo: P3, hi: P3, marker: i32) {
    let o = plc.points.len() as u32;
    for i in 0..8 {
        plc.points.push([
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]);
    }
    let quads = [
        [0, 1, 3, 2],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 3, 7, 5],
    ];
    for q in quads {
        plc.facets.push(idmesh::Facet {
            polygons: vec![q.iter().map(|&i| o + i).collect()],
            holes: vec![],
            marker,
        });
    }
}

pub fn box_plc(lo: P3, hi: P3) -> Plc {
    let mut plc = Plc::default();
    add_box(&mut plc, lo, hi, 1);
    plc
}

/// A prism over `outer` (minus `hole`) between `z0` and `z1`: top and bottom facets (with the
/// hole's loop and a facet hole seed), side quads, and a volume hole seed. Points are mapped by
/// `frame`. The hole polygon must be star-shaped around `hole_seed`.
pub fn prism_plc(
    outer: &[[f64; 2]],
    hole: Option<(&[[f64; 2]], [f64; 2])>,
    z0: f64,
    z1: f64,
    frame: &Frame,
) -> Plc {
    let holes: Vec<_> = hole.into_iter().collect();
    prism_plc_holes(outer, &holes, z0, z1, frame)
}

/// [`prism_plc`] with any number of disjoint holes through the prism, each star-shaped around
/// its seed.
pub fn prism_plc_holes(
    outer: &[[f64; 2]],
    holes: &[(&[[f64; 2]], [f64; 2])],
    z0: f64,
    z1: f64,
    frame: &Frame,
) -> Plc {
    let mut plc = Plc::default();
    let loop_at = |plc: &mut Plc, poly: &[[f64; 2]]| -> (Vec<u32>, Vec<u32>) {
        let o = plc.points.len() as u32;
        let n = poly.len() as u32;
        for &p in poly {
            plc.points.push(frame.apply([p[0], p[1], z0]));
        }
        for &p in poly {
            plc.points.push(frame.apply([p[0], p[1], z1]));
        }
        ((o..o + n).collect(), (o + n..o + 2 * n).collect())
    };
    let (ob, ot) = loop_at(&mut plc, outer);
    let mut bottom = idmesh::Facet {
        polygons: vec![ob.clone()],
        holes: vec![],
        marker: 1,
    };
    let mut top = idmesh::Facet {
        polygons: vec![ot.clone()],
        holes: vec![],
        marker: 2,
    };
    let sides = |plc: &mut Plc, b: &[u32], t: &[u32], marker: i32| {
        let n = b.len();
        for i in 0..n {
            let j = (i + 1) % n;
            plc.facets.push(idmesh::Facet {
                polygons: vec![vec![b[i], b[j], t[j], t[i]]],
                holes: vec![],
                marker,
            });
        }
    };
    sides(&mut plc, &ob, &ot, 3);
    for &(h, seed) in holes {
        let (hb, ht) = loop_at(&mut plc, h);
        bottom.polygons.push(hb.clone());
        bottom.holes.push(frame.apply([seed[0], seed[1], z0]));
        top.polygons.push(ht.clone());
        top.holes.push(frame.apply([seed[0], seed[1], z1]));
        sides(&mut plc, &hb, &ht, 4);
        plc.holes
            .push(frame.apply([seed[0], seed[1], 0.5 * (z0 + z1)]));
    }
    plc.facets.push(bottom);
    plc.facets.push(top);
    plc
}

/// Tolerance for Steiner points on slanted facets and edges (`Spec3::tol`): 64 ulps of the
/// largest coordinate.
pub fn tolerance(plc: &Plc) -> f64 {
    let m = plc
        .points
        .iter()
        .flatten()
        .fold(0.0f64, |a, x| a.max(x.abs()));
    64.0 * f64::EPSILON * m.max(1.0)
}

/// A regular `n`-gon of radius `r` around the origin.
pub fn regular_polygon(n: usize, r: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

/// Proptest settings for CI: `cases` cases from a fixed seed (`seed`), reproducible run to run;
/// the environment variables `PROPTEST_CASES` and `PROPTEST_SEED` override both. No failure
/// files; at most 200 shrink steps.
pub fn proptest_config(cases: u32, seed: u64) -> proptest::test_runner::Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(cases);
    let seed = std::env::var("PROPTEST_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(seed);
    proptest::test_runner::Config {
        cases,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        max_shrink_iters: 200,
        failure_persistence: Some(Box::new(proptest::test_runner::FileFailurePersistence::Off)),
        ..proptest::test_runner::Config::default()
    }
}
