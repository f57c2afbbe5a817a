//! An independent checker of a 2D mesh against the PSLG it was made from.
//!
//! The checker establishes every fact itself (exact predicates from `idmesh::predicates`, its own
//! walks and grids) and only afterwards asks `TriMesh::validate` for its verdict: the two must
//! agree on the structural facts `validate` covers. A bug in the mesher's own validator therefore
//! cannot hide a bug in the mesher.
//!
//! Tolerance: one, and only for *membership* of Steiner points in slanted input segments, since
//! those points are rounded constructions. A vertex `p` counts as on segment `ab` when its
//! distance to the line is at most `SEG_TOL_ULPS` ulps of the largest coordinate magnitude
//! involved, i.e. `|orient2d(a, b, p)| <= 16 · 2^-52 · max|coord| · |b - a|`. This is the same
//! notion (and the same default of 16 ulps) as `verify2d.py --seg-tol-ulps` in the shared tools.
//! Axis-aligned segments are held to exact membership. Every other decision is exact.
#![allow(dead_code)]

use std::collections::HashMap;
use std::fmt::Write as _;

use idmesh::predicates::{incircle, orient2d};
use idmesh::{triangulate, Options, Pslg, TriMesh, NONE};

/// `ulp(1.0)`.
pub const ULP1: f64 = f64::EPSILON;
/// Allowed distance of a Steiner vertex from its slanted segment, in ulps of the largest
/// coordinate magnitude (as `verify2d.py`'s default).
pub const SEG_TOL_ULPS: f64 = 16.0;
/// Slack on the minimum-angle bound, in degrees (the angle is a float measure).
pub const ANGLE_SLACK_DEG: f64 = 1e-9;
/// Relative tolerance of the total area against the domain area.
pub const AREA_REL_TOL: f64 = 1e-9;

/// Where a point lies relative to a closed polygon.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Loc {
    /// Strictly inside.
    Inside,
    /// Exactly on the boundary.
    On,
    /// Strictly outside.
    Outside,
}

/// A region the test expects: triangles whose centroid lies in `poly` and in none of `holes`
/// belong to it.
#[derive(Clone, Debug, Default)]
pub struct RegionSpec {
    /// The region's outer boundary.
    pub poly: Vec<[f64; 2]>,
    /// Polygons cut out of the region (islands of other regions, holes).
    pub holes: Vec<Vec<[f64; 2]>>,
    /// The attribute its triangles must carry when `region_attributes` is on.
    pub attribute: f64,
    /// The regional area bound, enforced when `region_max_area` is on.
    pub max_area: Option<f64>,
}

/// What the test knows about the domain it generated, beyond the PSLG itself.
#[derive(Clone, Debug)]
pub struct Spec {
    /// The exact area of the domain (outer polygon minus holes). `None`: in convex-hull mode the
    /// checker uses the hull area; otherwise the area is not checked.
    pub area: Option<f64>,
    /// The outer boundary: every triangle centroid must lie strictly inside it.
    pub outer: Option<Vec<[f64; 2]>>,
    /// Hole polygons: no triangle centroid may lie inside one.
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Expected regions (checked only when the options ask for attributes or regional areas).
    pub regions: Vec<RegionSpec>,
    /// Every input point lies in the closed domain, so every one must be used by a triangle.
    pub all_inputs_used: bool,
    /// Check the angle and area bounds (when the mesh is complete).
    pub check_quality: bool,
}

impl Default for Spec {
    fn default() -> Self {
        Spec {
            area: None,
            outer: None,
            holes: Vec::new(),
            regions: Vec::new(),
            all_inputs_used: true,
            check_quality: true,
        }
    }
}

/// Figures of a checked mesh, for tests that assert more than validity.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Number of triangles.
    pub triangles: usize,
    /// Number of Steiner vertices.
    pub steiner: usize,
    /// Smallest angle of any triangle, degrees.
    pub min_angle: f64,
    /// Smallest angle among triangles not covered by an exemption, degrees.
    pub min_angle_unexempt: f64,
    /// Number of triangles below the angle bound that were exempt.
    pub exempt_below_bound: usize,
    /// Largest triangle area.
    pub max_area: f64,
    /// Sum of triangle areas.
    pub area: f64,
}

// ---------------------------------------------------------------------------------------------
// Small exact geometry used by the checker and by the generators.

/// `a - b`.
pub fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// Dot product.
pub fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Euclidean distance.
pub fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = sub(a, b);
    d[0].hypot(d[1])
}

/// Sums with Neumaier's compensation: areas of flat or far-from-origin pieces must not drown
/// in rounding when compared to 1e-9 relative.
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

/// `2·area(a, b, c)` (the orientation determinant) correctly rounded up to an ulp or so: the
/// six products are split exactly (fused multiply-add) and summed as a floating-point
/// expansion. `robust::orient2d` has an exact sign but its magnitude may be off by a large
/// factor near its error bound, and the plain formula loses everything to cancellation for flat
/// triangles or large offsets; areas are compared to 1e-9 relative, so neither will do.
pub fn det2_accurate(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let terms = [
        (a[0], b[1]),
        (-a[0], c[1]),
        (-a[1], b[0]),
        (a[1], c[0]),
        (b[0], c[1]),
        (-b[1], c[0]),
    ];
    // Shewchuk's grow-expansion: components stay non-overlapping, increasing in magnitude.
    let mut e: Vec<f64> = Vec::with_capacity(12);
    let mut grow = |q0: f64| {
        let mut q = q0;
        for x in e.iter_mut() {
            let s = q + *x;
            let bv = s - q;
            let err = (q - (s - bv)) + (*x - bv);
            *x = err;
            q = s;
        }
        e.push(q);
    };
    for (x, y) in terms {
        let p = x * y;
        grow(x.mul_add(y, -p));
        grow(p);
    }
    e.iter().sum()
}

/// Signed area of a polygon (positive when counter-clockwise): a fan of accurate
/// determinants summed with compensation.
pub fn polygon_area(poly: &[[f64; 2]]) -> f64 {
    if poly.len() < 3 {
        return 0.0;
    }
    0.5 * sum_compensated((1..poly.len() - 1).map(|i| det2_accurate(poly[0], poly[i], poly[i + 1])))
}

/// `r` is collinear with `p, q` (exact) and inside their bounding box: on the closed segment.
fn on_closed_segment(p: [f64; 2], q: [f64; 2], r: [f64; 2]) -> bool {
    orient2d(p, q, r) == 0.0
        && p[0].min(q[0]) <= r[0]
        && r[0] <= p[0].max(q[0])
        && p[1].min(q[1]) <= r[1]
        && r[1] <= p[1].max(q[1])
}

/// `r` lies exactly on the open segment `pq`.
pub fn strictly_inside_segment(p: [f64; 2], q: [f64; 2], r: [f64; 2]) -> bool {
    r != p && r != q && on_closed_segment(p, q, r)
}

/// Exact location of `p` relative to a simple polygon (either orientation), by winding number.
pub fn locate(poly: &[[f64; 2]], p: [f64; 2]) -> Loc {
    let n = poly.len();
    let mut wn = 0i32;
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        if on_closed_segment(a, b, p) {
            return Loc::On;
        }
        let o = orient2d(a, b, p);
        if a[1] <= p[1] {
            if b[1] > p[1] && o > 0.0 {
                wn += 1;
            }
        } else if b[1] <= p[1] && o < 0.0 {
            wn -= 1;
        }
    }
    if wn != 0 {
        Loc::Inside
    } else {
        Loc::Outside
    }
}

fn sign(x: f64) -> i32 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// Closed segments `pq` and `rs` meet somewhere other than at one shared endpoint (exact).
/// Identical segments and collinear overlaps count as meeting.
pub fn segments_conflict(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let shared_pr = p == r || p == s;
    let shared_qr = q == r || q == s;
    if shared_pr && shared_qr {
        return true;
    }
    if shared_pr || shared_qr {
        // One shared endpoint `o`: they conflict only when collinear and pointing the same way.
        let (o, a) = if shared_pr { (p, q) } else { (q, p) };
        let b = if r == o { s } else { r };
        if orient2d(o, a, b) != 0.0 {
            return false;
        }
        return sign(a[0] - o[0]) == sign(b[0] - o[0]) && sign(a[1] - o[1]) == sign(b[1] - o[1]);
    }
    let o1 = sign(orient2d(p, q, r));
    let o2 = sign(orient2d(p, q, s));
    let o3 = sign(orient2d(r, s, p));
    let o4 = sign(orient2d(r, s, q));
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && on_closed_segment(p, q, r))
        || (o2 == 0 && on_closed_segment(p, q, s))
        || (o3 == 0 && on_closed_segment(r, s, p))
        || (o4 == 0 && on_closed_segment(r, s, q))
}

/// The strictly convex hull of `pts`, counter-clockwise (monotone chain, exact turns).
pub fn convex_hull(pts: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = pts.to_vec();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && orient2d(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// `p` is on the line `ab` up to the Steiner tolerance (exact for axis-aligned `ab`).
pub fn on_line_tol(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    if a[1] == b[1] {
        return p[1] == a[1];
    }
    if a[0] == b[0] {
        return p[0] == a[0];
    }
    let o = orient2d(a, b, p);
    if o == 0.0 {
        return true;
    }
    let mag = [a[0], a[1], b[0], b[1], p[0], p[1]]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let len = dist(a, b);
    o.abs() <= SEG_TOL_ULPS * ULP1 * mag * len
}

/// The three angles of a triangle in degrees (at `p[0]`, `p[1]`, `p[2]`).
pub fn angles_deg(p: [[f64; 2]; 3]) -> [f64; 3] {
    let ang = |o: [f64; 2], u: [f64; 2], v: [f64; 2]| {
        let a = sub(u, o);
        let b = sub(v, o);
        (a[0] * b[1] - a[1] * b[0])
            .abs()
            .atan2(dot(a, b))
            .to_degrees()
    };
    [
        ang(p[0], p[1], p[2]),
        ang(p[1], p[2], p[0]),
        ang(p[2], p[0], p[1]),
    ]
}

/// Signed area of a triangle, accurate to about an ulp.
pub fn tri_area(p: [[f64; 2]; 3]) -> f64 {
    0.5 * det2_accurate(p[0], p[1], p[2])
}

fn edge_key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    ((lo as u64) << 32) | hi as u64
}

// ---------------------------------------------------------------------------------------------
// Reporting helpers.

/// The PSLG in Triangle's `.poly` format (0-based), to paste into a bug report or feed to
/// `triangle` / `verify2d.py`. Coordinates are printed round-trip exact.
pub fn poly_text(p: &Pslg) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} 2 0 {}",
        p.points.len(),
        usize::from(!p.point_markers.is_empty())
    );
    for (i, q) in p.points.iter().enumerate() {
        let _ = write!(s, "{i} {:?} {:?}", q[0], q[1]);
        if let Some(m) = p.point_markers.get(i) {
            let _ = write!(s, " {m}");
        }
        s.push('\n');
    }
    let _ = writeln!(
        s,
        "{} {}",
        p.segments.len(),
        usize::from(!p.segment_markers.is_empty())
    );
    for (i, q) in p.segments.iter().enumerate() {
        let _ = write!(s, "{i} {} {}", q[0], q[1]);
        if let Some(m) = p.segment_markers.get(i) {
            let _ = write!(s, " {m}");
        }
        s.push('\n');
    }
    let _ = writeln!(s, "{}", p.holes.len());
    for (i, h) in p.holes.iter().enumerate() {
        let _ = writeln!(s, "{i} {:?} {:?}", h[0], h[1]);
    }
    let _ = writeln!(s, "{}", p.regions.len());
    for (i, r) in p.regions.iter().enumerate() {
        let _ = writeln!(
            s,
            "{i} {:?} {:?} {:?} {}",
            r.point[0],
            r.point[1],
            r.attribute,
            r.max_area.map_or(-1.0, |a| a)
        );
    }
    s
}

/// Collects the first few violations of each kind (a broken mesh would otherwise produce
/// thousands of lines) and counts the rest.
#[derive(Default)]
struct Fails {
    lines: Vec<String>,
    per_kind: HashMap<&'static str, usize>,
}

impl Fails {
    fn push(&mut self, kind: &'static str, msg: String) {
        let n = self.per_kind.entry(kind).or_default();
        *n += 1;
        if *n <= 4 {
            self.lines.push(format!("[{kind}] {msg}"));
        }
    }

    fn is_empty(&self) -> bool {
        self.lines.is_empty()
    }

    fn any(&self, kinds: &[&str]) -> bool {
        kinds.iter().any(|k| self.per_kind.contains_key(k))
    }

    fn summary(&self) -> String {
        let mut kinds: Vec<_> = self.per_kind.iter().collect();
        kinds.sort();
        let counts: Vec<String> = kinds.iter().map(|(k, n)| format!("{k}: {n}")).collect();
        format!("{}\n  {}", counts.join(", "), self.lines.join("\n  "))
    }
}

/// The structural kinds `TriMesh::validate` is documented to check.
const STRUCTURAL: &[&str] = &[
    "index",
    "orientation",
    "neighbors",
    "edges",
    "delaunay",
    "subsegment",
];

// ---------------------------------------------------------------------------------------------
// Delaunay check on a uniform grid.

struct Grid {
    lo: [f64; 2],
    cell: [f64; 2],
    n: [usize; 2],
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    fn new(pts: &[[f64; 2]]) -> Grid {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in pts {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let target = (pts.len() / 2).max(1) as f64;
        let w = (hi[0] - lo[0]).max(f64::MIN_POSITIVE);
        let h = (hi[1] - lo[1]).max(f64::MIN_POSITIVE);
        let nx = (target * w / h).sqrt().round().clamp(1.0, target) as usize;
        let ny = (target / nx as f64).round().clamp(1.0, target) as usize;
        let cell = [w / nx as f64, h / ny as f64];
        let mut g = Grid {
            lo,
            cell,
            n: [nx, ny],
            start: vec![0; nx * ny + 1],
            items: Vec::new(),
        };
        let ids: Vec<usize> = pts.iter().map(|&p| g.cell_of(p)).collect();
        for &c in &ids {
            g.start[c + 1] += 1;
        }
        for c in 0..nx * ny {
            g.start[c + 1] += g.start[c];
        }
        let mut fill = g.start.clone();
        g.items = vec![0; pts.len()];
        for (i, &c) in ids.iter().enumerate() {
            g.items[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        g
    }

    fn coord(&self, x: f64, k: usize) -> usize {
        let c = ((x - self.lo[k]) / self.cell[k]).floor();
        if c.is_nan() || c < 0.0 {
            0
        } else {
            (c as usize).min(self.n[k] - 1)
        }
    }

    fn cell_of(&self, p: [f64; 2]) -> usize {
        self.coord(p[1], 1) * self.n[0] + self.coord(p[0], 0)
    }

    /// Calls `f` for every point in the cells overlapping the box `[lo, hi]`.
    fn for_box(&self, lo: [f64; 2], hi: [f64; 2], mut f: impl FnMut(u32)) {
        let (x0, x1) = (self.coord(lo[0], 0), self.coord(hi[0], 0));
        let (y0, y1) = (self.coord(lo[1], 1), self.coord(hi[1], 1));
        for y in y0..=y1 {
            for x in x0..=x1 {
                let c = y * self.n[0] + x;
                for &i in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                    f(i);
                }
            }
        }
    }
}

/// Circumcenter and radius in floating point; `None` when not finite.
fn circle(p: [[f64; 2]; 3]) -> Option<([f64; 2], f64)> {
    let b = sub(p[1], p[0]);
    let c = sub(p[2], p[0]);
    let d = 2.0 * (b[0] * c[1] - b[1] * c[0]);
    let b2 = dot(b, b);
    let c2 = dot(c, c);
    let u = [(c[1] * b2 - b[1] * c2) / d, (b[0] * c2 - c[0] * b2) / d];
    let r = u[0].hypot(u[1]);
    let o = [p[0][0] + u[0], p[0][1] + u[1]];
    (o[0].is_finite() && o[1].is_finite() && r.is_finite()).then_some((o, r))
}

fn check_delaunay(m: &TriMesh, fails: &mut Fails) {
    let verts = &m.vertices;
    if verts.is_empty() || m.triangles.is_empty() {
        return;
    }
    let grid = Grid::new(verts);
    for (t, tri) in m.triangles.iter().enumerate() {
        let p = tri.map(|i| verts[i as usize]);
        let mut test = |v: u32| {
            let q = verts[v as usize];
            if incircle(p[0], p[1], p[2], q) > 0.0 {
                fails.push(
                    "delaunay",
                    format!("vertex {v} {q:?} lies strictly inside the circumcircle of triangle {t} {tri:?} {p:?}"),
                );
            }
        };
        match circle(p) {
            Some((o, r)) => {
                // Inflate generously: the float circle only selects candidates; incircle decides.
                let mag = p
                    .iter()
                    .fold(0.0f64, |a, q| a.max(q[0].abs()).max(q[1].abs()));
                let rr = r * (1.0 + 1e-6) + 64.0 * ULP1 * mag;
                grid.for_box([o[0] - rr, o[1] - rr], [o[0] + rr, o[1] + rr], &mut test);
            }
            None => (0..verts.len() as u32).for_each(&mut test),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The checker.

/// Meshes `pslg` with `opts` and checks the result; `Err` carries a readable account of every
/// kind of violation plus the input in `.poly` form.
pub fn mesh_and_check(
    pslg: &Pslg,
    opts: &Options,
    spec: &Spec,
) -> Result<(TriMesh, Report), String> {
    let mesh = triangulate(pslg, opts).map_err(|e| {
        format!(
            "triangulate failed: {e}\noptions: {opts:?}\ninput:\n{}",
            poly_text(pslg)
        )
    })?;
    match check(&mesh, pslg, opts, spec) {
        Ok(r) => Ok((mesh, r)),
        Err(e) => Err(format!(
            "{e}\noptions: {opts:?}\ninput:\n{}",
            poly_text(pslg)
        )),
    }
}

/// As [`mesh_and_check`], panicking on failure.
pub fn assert_mesh(pslg: &Pslg, opts: &Options, spec: &Spec) -> (TriMesh, Report) {
    match mesh_and_check(pslg, opts, spec) {
        Ok(x) => x,
        Err(e) => panic!("{e}"),
    }
}

/// Checks every invariant of `m` as a mesh of `pslg` under `opts`; see the module docs.
pub fn check(m: &TriMesh, pslg: &Pslg, opts: &Options, spec: &Spec) -> Result<Report, String> {
    let mut fails = Fails::default();
    let nv = m.vertices.len();
    let nt = m.triangles.len();
    let ni = pslg.points.len();
    let hull_mode = pslg.segments.is_empty() || opts.convex_hull;

    // --- array shapes and input preservation
    if m.num_input_vertices != ni {
        fails.push(
            "shape",
            format!(
                "num_input_vertices {} != {} input points",
                m.num_input_vertices, ni
            ),
        );
    }
    if nv < ni {
        fails.push("shape", format!("{nv} vertices for {ni} input points"));
    }
    if m.vertex_markers.len() != nv {
        fails.push(
            "shape",
            format!(
                "{} vertex markers for {nv} vertices",
                m.vertex_markers.len()
            ),
        );
    }
    if m.neighbors.len() != nt {
        fails.push(
            "shape",
            format!("{} neighbour rows for {nt} triangles", m.neighbors.len()),
        );
    }
    if m.segment_markers.len() != m.segments.len() {
        fails.push(
            "shape",
            format!(
                "{} segment markers for {} segments",
                m.segment_markers.len(),
                m.segments.len()
            ),
        );
    }
    let want_attrs = if opts.region_attributes { nt } else { 0 };
    if m.triangle_attributes.len() != want_attrs {
        fails.push(
            "shape",
            format!(
                "{} triangle attributes, expected {want_attrs}",
                m.triangle_attributes.len()
            ),
        );
    }
    if m.steiner_points != nv.saturating_sub(ni) {
        fails.push(
            "shape",
            format!(
                "steiner_points {} but {} vertices beyond the input",
                m.steiner_points,
                nv.saturating_sub(ni)
            ),
        );
    }
    for (i, p) in pslg.points.iter().enumerate().take(nv) {
        let v = m.vertices[i];
        if v[0].to_bits() != p[0].to_bits() || v[1].to_bits() != p[1].to_bits() {
            fails.push(
                "input-vertex",
                format!("vertex {i} is {v:?}, input point was {p:?}"),
            );
        }
    }
    for (i, v) in m.vertices.iter().enumerate() {
        if !(v[0].is_finite() && v[1].is_finite()) {
            fails.push("index", format!("vertex {i} is not finite: {v:?}"));
        }
    }
    if !fails.is_empty() && (m.neighbors.len() != nt || nv < ni) {
        return Err(fails.summary());
    }

    // --- indices, orientation
    let mut index_ok = true;
    for (t, tri) in m.triangles.iter().enumerate() {
        if tri.iter().any(|&i| i as usize >= nv) {
            fails.push(
                "index",
                format!("triangle {t} {tri:?} has a vertex index >= {nv}"),
            );
            index_ok = false;
        }
        if m.neighbors[t]
            .iter()
            .any(|&n| n != NONE && n as usize >= nt)
        {
            fails.push(
                "index",
                format!("triangle {t} has neighbours {:?}, >= {nt}", m.neighbors[t]),
            );
            index_ok = false;
        }
    }
    for (s, seg) in m.segments.iter().enumerate() {
        if seg.iter().any(|&i| i as usize >= nv) {
            fails.push(
                "index",
                format!("subsegment {s} {seg:?} has a vertex index >= {nv}"),
            );
            index_ok = false;
        }
    }
    if !index_ok {
        return Err(fails.summary());
    }
    let pts = |tri: &[u32; 3]| tri.map(|i| m.vertices[i as usize]);
    for (t, tri) in m.triangles.iter().enumerate() {
        let p = pts(tri);
        if orient2d(p[0], p[1], p[2]) <= 0.0 {
            fails.push(
                "orientation",
                format!("triangle {t} {tri:?} {p:?} is not strictly counter-clockwise"),
            );
        }
    }

    // --- edges, neighbours
    let mut directed: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * nt);
    for (t, tri) in m.triangles.iter().enumerate() {
        for i in 0..3 {
            let e = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
            if let Some(u) = directed.insert(e, t as u32) {
                fails.push("edges", format!("directed edge {e:?} is used by triangles {u} and {t} (overlap or duplicate)"));
            }
        }
    }
    let mut use_count: HashMap<u64, u32> = HashMap::with_capacity(2 * nt);
    for &(a, b) in directed.keys() {
        *use_count.entry(edge_key(a, b)).or_default() += 1;
    }
    for (t, tri) in m.triangles.iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
            let expect = directed.get(&(b, a)).copied().unwrap_or(NONE);
            let got = m.neighbors[t][i];
            if got != expect {
                fails.push("neighbors", format!("neighbors[{t}][{i}] is {got}, but the triangle across edge {a}-{b} is {expect}"));
            }
        }
    }
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for &(a, b) in directed.keys() {
        adj[a as usize].push(b);
        if !directed.contains_key(&(b, a)) {
            adj[b as usize].push(a);
        }
    }
    let mut used = vec![false; nv];
    for tri in &m.triangles {
        for &i in tri {
            used[i as usize] = true;
        }
    }
    for (v, &u) in used.iter().enumerate() {
        if !u && (v >= ni || spec.all_inputs_used) {
            let what = if v >= ni { "Steiner" } else { "input" };
            fails.push(
                "unused-vertex",
                format!("{what} vertex {v} {:?} is in no triangle", m.vertices[v]),
            );
        }
    }

    // --- Delaunay against all vertices
    check_delaunay(m, &mut fails);

    // --- subsegments are mesh edges
    let mut subseg: HashMap<u64, usize> = HashMap::with_capacity(m.segments.len());
    for (s, seg) in m.segments.iter().enumerate() {
        let k = edge_key(seg[0], seg[1]);
        if !use_count.contains_key(&k) || seg[0] == seg[1] {
            fails.push(
                "subsegment",
                format!("subsegment {s} {seg:?} is not a mesh edge"),
            );
        }
        if subseg.insert(k, s).is_some() {
            fails.push(
                "subsegment-dup",
                format!("subsegment {s} {seg:?} is listed twice"),
            );
        }
    }

    // --- input vertex markers: the given marker; a zero marker on a subsegment becomes that
    // subsegment's marker (as Triangle does).
    let mut sub_marks: Vec<Vec<i32>> = vec![Vec::new(); nv];
    for (seg, &mk) in m.segments.iter().zip(&m.segment_markers) {
        for &v in seg {
            sub_marks[v as usize].push(mk);
        }
    }
    for (i, marks) in sub_marks.iter().enumerate().take(ni) {
        let given = pslg.point_markers.get(i).copied().unwrap_or(0);
        let Some(&got) = m.vertex_markers.get(i) else {
            continue;
        };
        let ok = if given != 0 || marks.is_empty() {
            got == given
        } else {
            marks.contains(&got)
        };
        if !ok {
            fails.push(
                "marker",
                format!(
                    "input vertex {i} has marker {got}, expected {given} or the marker of a \
                     subsegment at it {marks:?}"
                ),
            );
        }
    }

    // --- conformity: walk each input segment through mesh edges lying on it
    let seg_marker = |s: usize| pslg.segment_markers.get(s).copied().unwrap_or(1);
    let mut on_seg_edge: HashMap<u64, usize> = HashMap::new();
    let mut interior_seg: Vec<u32> = vec![NONE; nv];
    let mut dirs: Vec<Vec<[f64; 2]>> = vec![Vec::new(); ni];
    for (s, seg) in pslg.segments.iter().enumerate() {
        let (ia, ib) = (seg[0], seg[1]);
        if ia as usize >= ni || ib as usize >= ni {
            fails.push(
                "conformity",
                format!(
                    "input segment {s} has an invalid index (the input should have been rejected)"
                ),
            );
            continue;
        }
        match walk_segment(&adj, &m.vertices, ia, ib) {
            Err(e) => fails.push("conformity", format!("input segment {s} {seg:?}: {e}")),
            Ok(chain) => {
                let (a, b) = (pslg.points[ia as usize], pslg.points[ib as usize]);
                for w in chain.windows(2) {
                    on_seg_edge.insert(edge_key(w[0], w[1]), s);
                    match subseg.get(&edge_key(w[0], w[1])) {
                        None => fails.push("subsegment-missing", format!("input segment {s}: edge {}-{} is not listed as a subsegment", w[0], w[1])),
                        Some(&k) if m.segment_markers.get(k).is_some_and(|&mk| mk != seg_marker(s)) => fails.push(
                            "marker",
                            format!("subsegment {k} of input segment {s} has marker {}, expected {}", m.segment_markers[k], seg_marker(s)),
                        ),
                        _ => {}
                    }
                }
                for &v in &chain[1..chain.len() - 1] {
                    interior_seg[v as usize] = s as u32;
                    if (v as usize) >= ni {
                        let mk = m.vertex_markers.get(v as usize).copied();
                        if mk.is_some_and(|mk| mk != seg_marker(s)) {
                            fails.push("marker", format!("Steiner vertex {v} on input segment {s} has marker {mk:?}, expected {}", seg_marker(s)));
                        }
                    }
                }
                for &v in &chain {
                    if (v as usize) < ni {
                        let p = m.vertices[v as usize];
                        if p != a {
                            dirs[v as usize].push(sub(a, p));
                        }
                        if p != b {
                            dirs[v as usize].push(sub(b, p));
                        }
                    }
                }
            }
        }
    }
    let hull = if hull_mode {
        convex_hull(&pslg.points)
    } else {
        Vec::new()
    };
    if hull_mode {
        let hn = hull.len();
        for i in 0..hn {
            let (p, a, b) = (hull[i], hull[(i + hn - 1) % hn], hull[(i + 1) % hn]);
            if let Some(v) = pslg.points.iter().position(|&q| q == p) {
                dirs[v].push(sub(a, p));
                dirs[v].push(sub(b, p));
            }
        }
    }
    // Every subsegment lies on an input segment, or on the hull in convex-hull mode.
    for (s, seg) in m.segments.iter().enumerate() {
        let k = edge_key(seg[0], seg[1]);
        let (pa, pb) = (m.vertices[seg[0] as usize], m.vertices[seg[1] as usize]);
        let on_hull_edge = hull_mode && on_hull(&hull, pa, pb);
        if !on_seg_edge.contains_key(&k) && !on_hull_edge {
            fails.push(
                "subsegment-extra",
                format!("subsegment {s} {seg:?} lies on no input segment"),
            );
        }
    }
    // Boundary edges lie on input segments (or on the hull).
    for (&(a, b), &t) in &directed {
        if directed.contains_key(&(b, a)) {
            continue;
        }
        let (pa, pb) = (m.vertices[a as usize], m.vertices[b as usize]);
        let ok = on_seg_edge.contains_key(&edge_key(a, b)) || (hull_mode && on_hull(&hull, pa, pb));
        if !ok {
            fails.push(
                "boundary",
                format!(
                    "boundary edge {a}-{b} {pa:?}-{pb:?} of triangle {t} lies on no input segment"
                ),
            );
        }
    }
    for (v, &s) in interior_seg.iter().enumerate() {
        if v >= ni
            && s == NONE
            && !hull_mode
            && m.vertex_markers.get(v).is_some_and(|&mk| mk != 0)
            && used[v]
        {
            fails.push(
                "marker",
                format!(
                    "interior Steiner vertex {v} has marker {}, expected 0",
                    m.vertex_markers[v]
                ),
            );
        }
    }

    // --- area, holes, outer boundary, regions
    let mut report = Report {
        triangles: nt,
        steiner: nv.saturating_sub(ni),
        min_angle: 180.0,
        min_angle_unexempt: 180.0,
        ..Report::default()
    };
    let areas: Vec<f64> = m.triangles.iter().map(|t| tri_area(pts(t))).collect();
    let total = sum_compensated(areas.iter().copied());
    report.area = total;
    report.max_area = areas.iter().cloned().fold(0.0, f64::max);
    let want_area = spec.area.or_else(|| hull_mode.then(|| polygon_area(&hull)));
    if let Some(w) = want_area {
        if (total - w).abs() > AREA_REL_TOL * w.abs() {
            fails.push(
                "area",
                format!(
                    "total area {total:e} differs from the domain area {w:e} (rel {:e})",
                    (total - w).abs() / w.abs()
                ),
            );
        }
    }
    let centroid = |p: [[f64; 2]; 3]| {
        [
            (p[0][0] + p[1][0] + p[2][0]) / 3.0,
            (p[0][1] + p[1][1] + p[2][1]) / 3.0,
        ]
    };
    for (t, tri) in m.triangles.iter().enumerate() {
        let c = centroid(pts(tri));
        if let Some(outer) = &spec.outer {
            if locate(outer, c) != Loc::Inside {
                fails.push(
                    "domain",
                    format!("triangle {t} (centroid {c:?}) is outside the outer boundary"),
                );
            }
        }
        for (h, poly) in spec.holes.iter().enumerate() {
            if locate(poly, c) != Loc::Outside {
                fails.push(
                    "hole",
                    format!("triangle {t} (centroid {c:?}) lies in hole polygon {h}"),
                );
            }
        }
    }
    let region_of = |c: [f64; 2]| {
        spec.regions.iter().position(|r| {
            locate(&r.poly, c) == Loc::Inside
                && r.holes.iter().all(|h| locate(h, c) == Loc::Outside)
        })
    };
    if opts.region_attributes || opts.region_max_area {
        for (t, tri) in m.triangles.iter().enumerate() {
            let c = centroid(pts(tri));
            let r = region_of(c);
            if opts.region_attributes && m.triangle_attributes.len() == nt {
                let want = r.map_or(0.0, |r| spec.regions[r].attribute);
                if m.triangle_attributes[t] != want {
                    fails.push(
                        "region",
                        format!(
                            "triangle {t} (centroid {c:?}) has attribute {}, expected {want}",
                            m.triangle_attributes[t]
                        ),
                    );
                }
            }
            if opts.region_max_area && m.complete && spec.check_quality {
                if let Some(a) = r.and_then(|r| spec.regions[r].max_area) {
                    if areas[t] > a * (1.0 + 1e-12) {
                        fails.push(
                            "region-area",
                            format!(
                                "triangle {t} has area {:e} above its region's bound {a:e}",
                                areas[t]
                            ),
                        );
                    }
                }
            }
        }
    }

    // --- quality
    let small_angle_vertex: Vec<bool> = dirs.iter().map(|d| min_pair_angle(d) < 60.0).collect();
    let bound = if spec.check_quality && m.complete {
        opts.min_angle
    } else {
        None
    };
    for (t, tri) in m.triangles.iter().enumerate() {
        let p = pts(tri);
        let ang = angles_deg(p);
        let lo = ang.iter().cloned().fold(180.0, f64::min);
        report.min_angle = report.min_angle.min(lo);
        let exempt = tri
            .iter()
            .any(|&v| (v as usize) < ni && small_angle_vertex[v as usize])
            || mpw_exempt(tri, &m.vertices, &interior_seg, ni, pslg);
        if !exempt {
            report.min_angle_unexempt = report.min_angle_unexempt.min(lo);
        }
        if let Some(b) = bound {
            if lo < b - ANGLE_SLACK_DEG {
                if exempt {
                    report.exempt_below_bound += 1;
                } else {
                    fails.push("angle", format!("triangle {t} {tri:?} {p:?} has a {lo}° angle (bound {b}°) and no exemption"));
                }
            }
        }
        if let (Some(a), true) = (opts.max_area, spec.check_quality && m.complete) {
            if areas[t] > a * (1.0 + 1e-12) {
                fails.push(
                    "max-area",
                    format!("triangle {t} has area {:e} above the bound {a:e}", areas[t]),
                );
            }
        }
    }

    // --- agreement with the mesher's own validator on the structural facts
    let ours = !fails.any(STRUCTURAL);
    match (ours, m.validate()) {
        (true, Err(e)) => fails.push(
            "validate-disagrees",
            format!("TriMesh::validate rejects a mesh the checker accepts: {e}"),
        ),
        (false, Ok(())) => fails.push(
            "validate-disagrees",
            "TriMesh::validate accepts a mesh with the structural violations above".into(),
        ),
        _ => {}
    }

    if fails.is_empty() {
        Ok(report)
    } else {
        Err(format!(
            "mesh check failed ({nt} triangles, {nv} vertices, complete={}): {}",
            m.complete,
            fails.summary()
        ))
    }
}

/// `pa-pb` lies on an edge of the convex hull (up to the Steiner tolerance).
fn on_hull(hull: &[[f64; 2]], pa: [f64; 2], pb: [f64; 2]) -> bool {
    let n = hull.len();
    (0..n).any(|i| {
        let (a, b) = (hull[i], hull[(i + 1) % n]);
        on_line_tol(a, b, pa) && on_line_tol(a, b, pb) && {
            let d = sub(b, a);
            let l2 = dot(d, d);
            let t = |p: [f64; 2]| dot(sub(p, a), d);
            (-l2 * 1e-12..=l2 * (1.0 + 1e-12)).contains(&t(pa))
                && (-l2 * 1e-12..=l2 * (1.0 + 1e-12)).contains(&t(pb))
        }
    })
}

/// The smallest angle between any two of the directions, in degrees (180 when fewer than two).
fn min_pair_angle(d: &[[f64; 2]]) -> f64 {
    let mut lo: f64 = 180.0;
    for i in 0..d.len() {
        for j in i + 1..d.len() {
            let (u, v) = (d[i], d[j]);
            let a = (u[0] * v[1] - u[1] * v[0])
                .abs()
                .atan2(dot(u, v))
                .to_degrees();
            lo = lo.min(a);
        }
    }
    lo
}

/// The Miller–Pav–Walkington exemption (as Triangle's `testtriangle`): the triangle's shortest
/// edge joins Steiner points interior to two different input segments that share an endpoint
/// (or where one ends inside the other), and both lie at the same distance from that point to
/// within 0.1%.
fn mpw_exempt(
    tri: &[u32; 3],
    v: &[[f64; 2]],
    interior_seg: &[u32],
    ni: usize,
    pslg: &Pslg,
) -> bool {
    let p = tri.map(|i| v[i as usize]);
    let lens = [dist(p[1], p[2]), dist(p[2], p[0]), dist(p[0], p[1])];
    let k = (0..3)
        .min_by(|&a, &b| lens[a].total_cmp(&lens[b]))
        .unwrap_or(0);
    let (u, w) = (tri[(k + 1) % 3] as usize, tri[(k + 2) % 3] as usize);
    if u < ni || w < ni {
        return false;
    }
    let (su, sw) = (interior_seg[u], interior_seg[w]);
    if su == NONE || sw == NONE || su == sw {
        return false;
    }
    let (a, b) = (pslg.segments[su as usize], pslg.segments[sw as usize]);
    // A shared endpoint, or a T-junction: an endpoint of one segment lying inside the other
    // (the input point splits that segment there, so both pieces end at it, as in Triangle).
    let shared = a.iter().find(|x| b.contains(x));
    let inside = || {
        a.iter()
            .find(|&&x| interior_seg[x as usize] == sw)
            .or_else(|| b.iter().find(|&&x| interior_seg[x as usize] == su))
    };
    let Some(&o) = shared.or_else(inside) else {
        return false;
    };
    let o = pslg.points[o as usize];
    let (du, dw) = (dist(o, v[u]), dist(o, v[w]));
    (du - dw).abs() <= 0.001 * du.max(dw)
}

/// The chain of mesh vertices from input vertex `ia` to `ib` along mesh edges whose vertices lie
/// on the segment (within the Steiner tolerance), with strictly increasing position along it;
/// an error naming where the walk got stuck.
///
/// At extreme offsets (a 1e-8 shape at 1e6) the ulp tolerance is a sizeable part of the shape,
/// so several vertices may pass it. The walk therefore tries the candidates nearest the line
/// first (exactly collinear ones, including `ib`, before rounded ones) and backtracks from
/// dead ends, so an unrelated vertex near the line cannot derail it.
fn walk_segment(
    adj: &[Vec<u32>],
    verts: &[[f64; 2]],
    ia: u32,
    ib: u32,
) -> Result<Vec<u32>, String> {
    let (a, b) = (verts[ia as usize], verts[ib as usize]);
    let d = sub(b, a);
    let l2 = dot(d, d);
    let len = l2.sqrt();
    let candidates = |cur: u32, tcur: f64| -> Vec<(f64, f64, u32)> {
        let mut c: Vec<(f64, f64, u32)> = adj[cur as usize]
            .iter()
            .filter_map(|&w| {
                if w == ib {
                    return Some((0.0, l2, w));
                }
                let p = verts[w as usize];
                if !on_line_tol(a, b, p) {
                    return None;
                }
                let t = dot(sub(p, a), d);
                (t > tcur && t < l2).then(|| (orient2d(a, b, p).abs() / len, t, w))
            })
            .collect();
        c.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
        c
    };
    let mut dead = vec![false; verts.len()];
    // DFS stack: (vertex, its position, its candidates, next candidate to try).
    let mut stack = vec![(ia, 0.0, candidates(ia, 0.0), 0usize)];
    let mut budget = 4 * verts.len() + 16;
    while let Some(top) = stack.last_mut() {
        if top.0 == ib {
            return Ok(stack.iter().map(|f| f.0).collect());
        }
        budget -= 1;
        if budget == 0 {
            return Err("walk does not terminate".into());
        }
        if top.3 >= top.2.len() {
            dead[top.0 as usize] = true;
            stack.pop();
            continue;
        }
        let (_, t, w) = top.2[top.3];
        top.3 += 1;
        if !dead[w as usize] {
            let c = candidates(w, t);
            stack.push((w, t, c, 0));
        }
    }
    let near: Vec<String> = adj[ia as usize]
        .iter()
        .map(|&w| format!("{w} {:?}", verts[w as usize]))
        .collect();
    Err(format!(
        "no chain of mesh edges along the segment from {ia} {a:?} to {ib} {b:?}; neighbours of {ia}: [{}]",
        near.join(", ")
    ))
}

// ---------------------------------------------------------------------------------------------
// Building inputs.

/// Appends loops, points and segments to a PSLG.
#[derive(Clone, Debug, Default)]
pub struct Builder {
    /// The PSLG built so far.
    pub pslg: Pslg,
}

impl Builder {
    /// Adds a point; returns its index.
    pub fn point(&mut self, p: [f64; 2]) -> u32 {
        self.pslg.points.push(p);
        (self.pslg.points.len() - 1) as u32
    }

    /// Adds a segment between two existing points.
    pub fn segment(&mut self, a: u32, b: u32) {
        self.pslg.segments.push([a, b]);
    }

    /// Adds a closed polygon (points and the segments joining consecutive ones); returns the
    /// indices of its points.
    pub fn closed_loop(&mut self, pts: &[[f64; 2]]) -> Vec<u32> {
        let ids: Vec<u32> = pts.iter().map(|&p| self.point(p)).collect();
        for i in 0..ids.len() {
            self.segment(ids[i], ids[(i + 1) % ids.len()]);
        }
        ids
    }
}

/// `n` points evenly spread on a circle (nearly, not exactly, cocircular after rounding).
pub fn regular_polygon(n: usize, center: [f64; 2], r: f64, phase: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let a = phase + std::f64::consts::TAU * i as f64 / n as f64;
            [center[0] + r * a.cos(), center[1] + r * a.sin()]
        })
        .collect()
}

/// Options with a minimum angle and a safety cap on Steiner points, so a refinement that does
/// not terminate shows up as `complete == false` (a test failure) instead of a hung test.
pub fn quality(min_angle: f64) -> Options {
    Options {
        min_angle: Some(min_angle),
        max_steiner: Some(STEINER_GUARD),
        ..Options::default()
    }
}

/// The Steiner cap used as a termination guard in tests that expect completion.
pub const STEINER_GUARD: u64 = 300_000;

/// How many of `pts` lie on the boundary of their convex hull (hull corners and points exactly
/// on hull edges). A triangulation of the hull using exactly these points has
/// `2·n − 2 − boundary` triangles (Euler).
pub fn hull_boundary_count(pts: &[[f64; 2]]) -> usize {
    let hull = convex_hull(pts);
    let n = hull.len();
    pts.iter()
        .filter(|&&p| (0..n).any(|i| on_closed_segment(hull[i], hull[(i + 1) % n], p)))
        .count()
}

/// The triangle count of any triangulation of the convex hull of `pts` without Steiner points.
pub fn hull_triangle_count(pts: &[[f64; 2]]) -> usize {
    2 * pts.len() - 2 - hull_boundary_count(pts)
}
