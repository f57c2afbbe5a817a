//! The input features of a PLC as the mesher tracks them: input edges with their 1D meshes
//! (subsegments), facets with their outlines, and the lookup tables from mesh simplices to the
//! features they belong to.

use crate::hash::FastMap as HashMap;

use super::facet_mesh::Outline;
use crate::input3d::Plc;
use crate::predicates::orient2d;
pub(crate) use crate::predicates::{dominant_axis, proj};

/// Key of an undirected edge.
#[inline]
pub(crate) fn ekey(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    ((lo as u64) << 32) | hi as u64
}

/// Key of an unordered triangle.
#[inline]
pub(crate) fn fkey(v: [u32; 3]) -> [u32; 3] {
    let mut k = v;
    k.sort_unstable();
    k
}

/// One input edge: a free segment or a facet loop edge (shared by every facet it bounds).
#[derive(Debug, Clone)]
pub(crate) struct InputEdge {
    /// Its endpoints (input vertices).
    pub ends: [u32; 2],
    /// Boundary marker (the segment's, or the first facet's for loop edges).
    pub marker: i32,
    /// The facets whose meshes contain this edge.
    pub facets: Vec<u32>,
}

/// One input facet: marker, projection axis and outline.
#[derive(Debug, Clone)]
pub(crate) struct FacetInfo {
    /// Boundary marker.
    pub marker: i32,
    /// The coordinate dropped by the facet's projection (largest normal component).
    pub axis: usize,
    /// Loops in projected coordinates.
    pub outline: Outline,
    /// Input vertices of the facet.
    pub vertices: Vec<u32>,
    /// Three non-collinear input vertices spanning the facet's plane, well spread (see
    /// [`well_spread_triple`]).
    pub plane: [u32; 3],
}

/// All features of the PLC.
pub(crate) struct Features {
    /// Input edges.
    pub edges: Vec<InputEdge>,
    /// Facets.
    pub facets: Vec<FacetInfo>,
    /// Current subsegments: edge key → input edge.
    pub subsegs: HashMap<u64, u32>,
    /// Subsegment partners of each vertex on an input edge.
    pub seg_adj: HashMap<u32, Vec<u32>>,
    /// Current subfaces: sorted triangle → facet.
    pub subfaces: HashMap<[u32; 3], u32>,
    /// Facets containing each feature vertex (input vertices of facets and Steiner points on
    /// facets or input edges).
    pub vert_facets: HashMap<u32, Vec<u32>>,
    /// The input edge of each Steiner point made by splitting a subsegment.
    pub split_edge: HashMap<u32, u32>,
    /// Per facet: the representative of its group of exactly coplanar facets joined along
    /// input edges (a triangulated surface's flat parts).
    pub plane_group: Vec<u32>,
    /// Per vertex: lies on a segment or facet (so simplices made only of such vertices may be
    /// features). A cheap filter before hash lookups.
    on_feature: Vec<bool>,
    /// Per vertex: the [`id_bit`]s of the input edges with a subsegment ending at it. Both ends
    /// of a subsegment of edge `e` have `e`'s bit, so two vertices whose masks share no bit
    /// are no subsegment: a finer filter than `on_feature` where every vertex near the
    /// surface is a feature (a triangulated surface), which spares most hash lookups of the
    /// cavity's edges.
    edge_mask: Vec<u64>,
    /// Per vertex: the [`id_bit`]s of its facets (`vert_facets`); the same filter for subfaces.
    facet_mask: Vec<u64>,
}

/// The bit of an edge or facet id in a vertex's 64-bit mask (a one-hash Bloom filter).
#[inline]
fn id_bit(id: u32) -> u64 {
    1 << ((id as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 58)
}

/// Sets the bits of `ids` in `mask[v]`, growing `mask` as needed.
fn add_bits(mask: &mut Vec<u64>, v: u32, ids: impl IntoIterator<Item = u32>) {
    let i = v as usize;
    if mask.len() <= i {
        mask.resize(i + 1, 0);
    }
    for id in ids {
        mask[i] |= id_bit(id);
    }
}

/// A triple of `verts` spanning their plane about as well as any: `first[0]`, the vertex
/// farthest from it, and the vertex farthest from the line through these two (floating-point
/// choices, checked exactly non-collinear; `first` otherwise). The first non-collinear
/// triple may be a needle (a triangulated surface's sliver triangles), whose floating-point
/// normal is far from the facet's: points constructed on the plane ([`onto_plane`]) need a
/// well-conditioned one.
fn well_spread_triple(plc: &Plc, verts: &[u32], first: [u32; 3]) -> [u32; 3] {
    let p = |v: u32| glam::DVec3::from(plc.points[v as usize]);
    let a = first[0];
    let far = |key: &dyn Fn(u32) -> f64| {
        verts
            .iter()
            .copied()
            .max_by(|&x, &y| key(x).total_cmp(&key(y)))
    };
    let Some(b) = far(&|v| p(v).distance_squared(p(a))) else {
        return first;
    };
    let Some(c) = far(&|v| (p(b) - p(a)).cross(p(v) - p(a)).length_squared()) else {
        return first;
    };
    let pt = |v: u32| plc.points[v as usize];
    if dominant_axis(pt(a), pt(b), pt(c)).is_some() {
        [a, b, c]
    } else {
        first
    }
}

/// `q` moved along coordinate axis `k` onto the plane of the non-collinear triple `t`, to a
/// floating-point point next to it: the exact plane meets the line through the result along
/// axis `k` within one floating-point step of it ([`within_ulp_of_plane`]), found from the
/// floating-point solution with exact orientations (a search that doubles its steps, then a
/// bisection). The projection dropping axis `k` is `q`'s own. `None` when the plane is
/// parallel to axis `k` in floating point or no finite value is across it.
pub(crate) fn onto_plane(t: [[f64; 3]; 3], q: [f64; 3], k: usize) -> Option<[f64; 3]> {
    use crate::geometry::next_float;
    use crate::predicates::orient3d;
    let s = crate::geometry::along_axis_onto_plane(t, q, k)?;
    let side = |z: f64| {
        let mut x = s;
        x[k] = z;
        // partial_cmp: an exact zero may come back as -0.0.
        orient3d(t[0], t[1], t[2], x)
            .partial_cmp(&0.0)
            .unwrap_or(std::cmp::Ordering::Equal)
    };
    let start = side(s[k]);
    if start.is_eq() {
        return Some(s);
    }
    // orient3d is linear and monotone in the k-th coordinate: the plane is crossed in one
    // direction only. Steps doubling from one floating-point step find a value across it
    // (the solution's error is relative to the other coordinates, many steps of a coordinate
    // near zero), then bisection narrows the two to neighbours.
    let close = |mut near: f64, mut far: f64| {
        for _ in 0..2100 {
            let mid = near + (far - near) * 0.5;
            if mid == near || mid == far || !mid.is_finite() {
                break;
            }
            if side(mid) == start {
                near = mid;
            } else {
                far = mid;
            }
        }
        far
    };
    // The crossing is far closer than the input's own magnitude: the search stops there
    // (beyond, orientations of huge coordinates could overflow).
    let reach = t
        .iter()
        .chain(std::iter::once(&s))
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    for up in [true, false] {
        let mut near = s[k];
        let mut d = (next_float(s[k], up) - s[k]).abs();
        for _ in 0..1100 {
            let far = if up { s[k] + d } else { s[k] - d };
            if !far.is_finite() || d > reach {
                break;
            }
            if side(far) != start {
                let mut x = s;
                x[k] = close(near, far);
                return Some(x);
            }
            near = far;
            d *= 2.0;
        }
    }
    None
}

/// Whether the plane of `t` meets the line through `p` along axis `k` within one
/// floating-point step of `p` (between `p`'s two neighbours along that axis, ends included):
/// exact orientations. What [`onto_plane`] guarantees for the points it makes.
pub(crate) fn within_ulp_of_plane(t: [[f64; 3]; 3], p: [f64; 3], k: usize) -> bool {
    let side = |up: bool| {
        let mut x = p;
        x[k] = crate::geometry::next_float(p[k], up);
        crate::predicates::orient3d(t[0], t[1], t[2], x)
    };
    let (lo, hi) = (side(false), side(true));
    lo == 0.0 || hi == 0.0 || (lo < 0.0) != (hi < 0.0)
}

impl Features {
    /// `q` (a point meant for facet `fid`) moved along the facet's projection axis onto its
    /// plane ([`onto_plane`]): the facet mesh sees the same projected point, and the point is
    /// within one floating-point step of the plane. A construction from corners that are
    /// themselves rounded (a subface's circumcentre) tilts with their errors, and points made
    /// from such points drift further off at each step (issue 12: a scanned model drifted
    /// 56 ulps off after four generations). `q` itself when the walk fails (see [`onto_plane`]).
    pub fn onto_facet_plane(&self, fid: u32, q: [f64; 3], points: &[[f64; 3]]) -> [f64; 3] {
        let f = &self.facets[fid as usize];
        onto_plane(f.plane.map(|v| points[v as usize]), q, f.axis).unwrap_or(q)
    }

    /// Collects input edges (free segments and facet loop edges, each once) and facets.
    pub fn new(plc: &Plc) -> Result<Features, String> {
        let n = plc.points.len();
        // Raw input edges (endpoints, marker, facet); split at input vertices lying on them
        // further below.
        let mut raw: Vec<(u32, u32, i32, Option<u32>)> = Vec::new();
        let mut add_edge = |a: u32, b: u32, marker: i32, facet: Option<u32>| {
            if a != b {
                raw.push((a, b, marker, facet));
            }
        };
        for (i, s) in plc.segments.iter().enumerate() {
            let m = plc.segment_markers.get(i).copied().unwrap_or(0);
            add_edge(s[0], s[1], m, None);
        }
        let mut facets = Vec::with_capacity(plc.facets.len());
        let mut vert_facets: HashMap<u32, Vec<u32>> = HashMap::default();
        for (fi, f) in plc.facets.iter().enumerate() {
            let fid = fi as u32;
            let mut verts: Vec<u32> = f.polygons.iter().flatten().copied().collect();
            verts.sort_unstable();
            verts.dedup();
            // A non-collinear triple gives the plane's dominant axis.
            let mut axis = None;
            let mut plane = [0u32; 3];
            if let Some(&a) = verts.first() {
                let pa = plc.points[a as usize];
                'outer: for (j, &b) in verts.iter().enumerate().skip(1) {
                    let pb = plc.points[b as usize];
                    for &c in verts.iter().skip(j + 1) {
                        if let Some(ax) = dominant_axis(pa, pb, plc.points[c as usize]) {
                            axis = Some(ax);
                            plane = [a, b, c];
                            break 'outer;
                        }
                    }
                }
            }
            let Some(axis) = axis else {
                return Err(format!(
                    "facet {fi} is degenerate (its vertices are collinear)"
                ));
            };
            let plane = well_spread_triple(plc, &verts, plane);
            let mut loops = Vec::new();
            for poly in &f.polygons {
                match poly.len() {
                    0 => {}
                    1 => {}
                    2 => add_edge(poly[0], poly[1], f.marker, Some(fid)),
                    k => {
                        for i in 0..k {
                            add_edge(poly[i], poly[(i + 1) % k], f.marker, Some(fid));
                        }
                        loops.push(
                            poly.iter()
                                .map(|&v| proj(plc.points[v as usize], axis))
                                .collect::<Vec<_>>(),
                        );
                    }
                }
            }
            let convex = loops.len() == 1 && is_convex(&loops[0]);
            facets.push(FacetInfo {
                marker: f.marker,
                axis,
                outline: Outline { loops, convex },
                vertices: verts,
                plane,
            });
        }
        // An input vertex exactly on an input edge (a T-junction of the surface) splits it:
        // the pieces are the input edges, each with the union of the facets around it.
        let on_edges = vertices_on_edges(&plc.points, &raw);
        let mut edges: Vec<InputEdge> = Vec::new();
        let mut subsegs: HashMap<u64, u32> = HashMap::default();
        for (r, &(a, b, marker, facet)) in raw.iter().enumerate() {
            let mut chain = vec![a];
            chain.extend(on_edges[r].iter().copied());
            chain.push(b);
            if let Some(f) = facet {
                for &v in &on_edges[r] {
                    let fv = &mut facets[f as usize].vertices;
                    if !fv.contains(&v) {
                        fv.push(v);
                    }
                }
            }
            for w in chain.windows(2) {
                let id = *subsegs.entry(ekey(w[0], w[1])).or_insert_with(|| {
                    edges.push(InputEdge {
                        ends: [w[0], w[1]],
                        marker,
                        facets: Vec::new(),
                    });
                    (edges.len() - 1) as u32
                });
                if let Some(f) = facet {
                    let e = &mut edges[id as usize];
                    if !e.facets.contains(&f) {
                        e.facets.push(f);
                    }
                }
            }
        }
        for (fid, f) in facets.iter().enumerate() {
            for &v in &f.vertices {
                vert_facets.entry(v).or_default().push(fid as u32);
            }
        }
        let mut on_feature = vec![false; n];
        let mut seg_adj: HashMap<u32, Vec<u32>> = HashMap::default();
        for e in &edges {
            let [a, b] = e.ends;
            on_feature[a as usize] = true;
            on_feature[b as usize] = true;
            seg_adj.entry(a).or_default().push(b);
            seg_adj.entry(b).or_default().push(a);
        }
        for &v in vert_facets.keys() {
            on_feature[v as usize] = true;
        }
        let mut edge_mask = vec![0; n];
        for (id, e) in edges.iter().enumerate() {
            for v in e.ends {
                add_bits(&mut edge_mask, v, [id as u32]);
            }
        }
        let mut facet_mask = vec![0; n];
        for (&v, fs) in &vert_facets {
            add_bits(&mut facet_mask, v, fs.iter().copied());
        }
        let plane_group = coplanar_groups(&plc.points, &facets, &edges);
        Ok(Features {
            plane_group,
            edges,
            facets,
            subsegs,
            seg_adj,
            subfaces: HashMap::default(),
            vert_facets,
            split_edge: HashMap::default(),
            on_feature,
            edge_mask,
            facet_mask,
        })
    }

    /// Replaces subsegment `ab` of input edge `e` by `am` and `mb`.
    pub fn split_subseg(&mut self, a: u32, b: u32, m: u32, e: u32) {
        self.subsegs.remove(&ekey(a, b));
        self.subsegs.insert(ekey(a, m), e);
        self.subsegs.insert(ekey(m, b), e);
        for (x, y) in [(a, b), (b, a)] {
            if let Some(l) = self.seg_adj.get_mut(&x) {
                if let Some(s) = l.iter_mut().find(|s| **s == y) {
                    *s = m;
                }
            }
        }
        self.seg_adj.insert(m, vec![a, b]);
        self.split_edge.insert(m, e);
        add_bits(&mut self.edge_mask, m, [e]);
        let fs = self.edges[e as usize].facets.clone();
        self.set_vertex_facets(m, fs);
    }

    /// Records Steiner point `m` as lying on the facets `fs` (one facet, or the facets of the
    /// input edge it splits) and marks it a feature.
    pub fn set_vertex_facets(&mut self, m: u32, fs: Vec<u32>) {
        add_bits(&mut self.facet_mask, m, fs.iter().copied());
        self.vert_facets.insert(m, fs);
        self.mark_feature(m);
    }

    /// Forgets boundary Steiner point `s` (taken off the surface under `-Y`): it is on no
    /// feature any more.
    pub fn forget_vertex(&mut self, s: u32) {
        self.vert_facets.remove(&s);
        let i = s as usize;
        for x in [&mut self.edge_mask, &mut self.facet_mask] {
            if let Some(m) = x.get_mut(i) {
                *m = 0;
            }
        }
        if let Some(f) = self.on_feature.get_mut(i) {
            *f = false;
        }
    }

    /// Marks vertex `v` as lying on a feature.
    fn mark_feature(&mut self, v: u32) {
        let i = v as usize;
        if self.on_feature.len() <= i {
            self.on_feature.resize(i + 1, false);
        }
        self.on_feature[i] = true;
    }

    /// Whether the three vertices all lie on one input edge (a rounding-flat triangle).
    pub fn on_one_edge(&self, t: [u32; 3]) -> bool {
        let Some(e) = t.iter().find_map(|v| self.split_edge.get(v)) else {
            return false;
        };
        let ends = self.edges[*e as usize].ends;
        t.iter()
            .all(|v| ends.contains(v) || self.split_edge.get(v) == Some(e))
    }

    /// Whether the four vertices all lie on one facet: in exact arithmetic such a tet would be
    /// flat; with Steiner points rounded off a slanted facet it is a rounding sliver lying in
    /// the facet, which no refinement can improve (its circumcenter is far away).
    pub fn in_one_facet(&self, t: [u32; 4]) -> bool {
        // Exactly coplanar neighbouring facets count as one: a tet across their common edge
        // is just as flat.
        self.plane_facet(&t).is_some()
    }

    /// A facet containing all the given feature vertices, if there is one.
    pub fn common_facet(&self, vs: &[u32]) -> Option<u32> {
        if !vs.iter().all(|&v| self.is_feature(v)) {
            return None;
        }
        let f0 = self.vert_facets.get(&vs[0])?;
        f0.iter().copied().find(|f| {
            vs[1..]
                .iter()
                .all(|v| self.vert_facets.get(v).is_some_and(|fs| fs.contains(f)))
        })
    }

    /// A facet for a face whose corners all lie on one facet, or on one group of exactly
    /// coplanar neighbouring facets (see [`Features::in_one_facet`]).
    pub fn plane_facet(&self, vs: &[u32]) -> Option<u32> {
        if let Some(f) = self.common_facet(vs) {
            return Some(f);
        }
        if !vs.iter().all(|&v| self.is_feature(v)) {
            return None;
        }
        let f0 = self.vert_facets.get(&vs[0])?;
        f0.iter().copied().find(|&f| {
            let g = self.plane_group[f as usize];
            vs[1..].iter().all(|v| {
                self.vert_facets
                    .get(v)
                    .is_some_and(|fs| fs.iter().any(|&h| self.plane_group[h as usize] == g))
            })
        })
    }

    /// Checks that the vertex masks admit every current subsegment and subface (else
    /// [`Features::subseg`] and [`Features::subface`] would miss it): the one it misses.
    pub fn check_masks(&self) -> Result<(), String> {
        for &k in self.subsegs.keys() {
            let (a, b) = ((k >> 32) as u32, k as u32);
            if self.subseg(a, b).is_none() {
                return Err(format!("the edge mask hides subsegment {a}-{b}"));
            }
        }
        for &f in self.subfaces.keys() {
            if self.subface(f).is_none() {
                return Err(format!("the facet mask hides subface {f:?}"));
            }
        }
        Ok(())
    }

    /// Whether `v` lies on a feature.
    #[inline]
    pub fn is_feature(&self, v: u32) -> bool {
        self.on_feature.get(v as usize).copied().unwrap_or(false)
    }

    /// The input edge of subsegment `ab`, if it is one.
    #[inline]
    pub fn subseg(&self, a: u32, b: u32) -> Option<u32> {
        let m = |v: u32| self.edge_mask.get(v as usize).copied().unwrap_or(0);
        if m(a) & m(b) == 0 {
            return None;
        }
        self.subsegs.get(&ekey(a, b)).copied()
    }

    /// The facet of subface `abc`, if it is one.
    #[inline]
    pub fn subface(&self, v: [u32; 3]) -> Option<u32> {
        let m = |x: u32| self.facet_mask.get(x as usize).copied().unwrap_or(0);
        if m(v[0]) & m(v[1]) & m(v[2]) == 0 {
            return None;
        }
        self.subfaces.get(&fkey(v)).copied()
    }
}

/// A loop is convex when no two consecutive turns have opposite signs (collinear runs allowed).
fn is_convex(lp: &[[f64; 2]]) -> bool {
    let n = lp.len();
    let (mut pos, mut neg) = (false, false);
    for i in 0..n {
        let o = orient2d(lp[i], lp[(i + 1) % n], lp[(i + 2) % n]);
        pos |= o > 0.0;
        neg |= o < 0.0;
    }
    !(pos && neg)
}

/// For each raw edge, the input vertices strictly inside it (exactly collinear), sorted from its
/// first endpoint. Candidates come from a sort on x, so this is fast unless edges are long and
/// the points dense.
fn vertices_on_edges(points: &[[f64; 3]], raw: &[(u32, u32, i32, Option<u32>)]) -> Vec<Vec<u32>> {
    let mut by_x: Vec<u32> = (0..points.len() as u32).collect();
    by_x.sort_by(|&i, &j| points[i as usize][0].total_cmp(&points[j as usize][0]));
    let xs: Vec<f64> = by_x.iter().map(|&i| points[i as usize][0]).collect();
    raw.iter()
        .map(|&(a, b, _, _)| {
            let (pa, pb) = (points[a as usize], points[b as usize]);
            let lo = [0, 1, 2].map(|k| pa[k].min(pb[k]));
            let hi = [0, 1, 2].map(|k| pa[k].max(pb[k]));
            let start = xs.partition_point(|&x| x < lo[0]);
            let end = xs.partition_point(|&x| x <= hi[0]);
            let mut on: Vec<u32> = by_x[start..end]
                .iter()
                .copied()
                .filter(|&v| {
                    if v == a || v == b {
                        return false;
                    }
                    let p = points[v as usize];
                    (0..3).all(|k| lo[k] <= p[k] && p[k] <= hi[k])
                        && (0..3).all(|ax| orient2d(proj(pa, ax), proj(pb, ax), proj(p, ax)) == 0.0)
                        && p != pa
                        && p != pb
                })
                .collect();
            on.sort_by(|&u, &v| {
                crate::geometry::dist2_3(pa, points[u as usize])
                    .total_cmp(&crate::geometry::dist2_3(pa, points[v as usize]))
            });
            on
        })
        .collect()
}

/// Groups facets that are exactly coplanar and joined along input edges (union–find); returns
/// each facet's group representative.
fn coplanar_groups(points: &[[f64; 3]], facets: &[FacetInfo], edges: &[InputEdge]) -> Vec<u32> {
    fn root(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let up = parent[parent[x as usize] as usize];
            parent[x as usize] = up;
            x = up;
        }
        x
    }
    let mut parent: Vec<u32> = (0..facets.len() as u32).collect();
    let coplanar = |f: &FacetInfo, g: &FacetInfo| {
        let [a, b, c] = f.plane.map(|v| points[v as usize]);
        g.vertices
            .iter()
            .all(|&v| crate::predicates::orient3d(a, b, c, points[v as usize]) == 0.0)
    };
    for e in edges {
        for (i, &f1) in e.facets.iter().enumerate() {
            for &f2 in &e.facets[i + 1..] {
                let (r1, r2) = (root(&mut parent, f1), root(&mut parent, f2));
                if r1 != r2 && coplanar(&facets[f1 as usize], &facets[f2 as usize]) {
                    parent[r1.max(r2) as usize] = r1.min(r2);
                }
            }
        }
    }
    (0..facets.len() as u32)
        .map(|f| root(&mut parent, f))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{onto_plane, proj, within_ulp_of_plane};
    use crate::geometry::{next_float, tri_circumcenter3};

    /// A slanted plane through three input-like points (none of its floating-point points need
    /// be exactly on it).
    const T: [[f64; 3]; 3] = [
        [1.449825, -3.263366, -1.31193],
        [1.49884, -3.274333, -1.574848],
        [1.357913, -3.231977, -1.413651],
    ];

    fn axis() -> usize {
        super::dominant_axis(T[0], T[1], T[2]).unwrap()
    }

    #[test]
    fn points_moved_onto_a_slanted_plane_are_within_one_step_and_keep_their_projection() {
        let k = axis();
        let mut checked = 0;
        for i in 0..40 {
            for j in 0..40 {
                let u = i as f64 / 39.0;
                let v = j as f64 / 39.0 * (1.0 - u);
                let mut q =
                    [0, 1, 2].map(|c| T[0][c] + u * (T[1][c] - T[0][c]) + v * (T[2][c] - T[0][c]));
                // Off the plane by far more than rounding, along the axis and across it.
                q[k] += 1e-9 * (i as f64 - 20.0);
                let r = onto_plane(T, q, k).expect("a point on the plane");
                assert_eq!(proj(r, k), proj(q, k));
                assert!(within_ulp_of_plane(T, r, k), "{r:?}");
                // Four steps off along the axis is more than one step from the plane.
                let mut far = r;
                for _ in 0..4 {
                    far[k] = next_float(far[k], true);
                }
                assert!(!within_ulp_of_plane(T, far, k), "{far:?}");
                checked += 1;
            }
        }
        assert_eq!(checked, 1600);
    }

    #[test]
    fn circumcentres_of_needle_subfaces_leave_the_plane_and_are_brought_back() {
        // Corners on the plane (each within a step of it), two of them very close: the plane
        // of the three rounded corners is tilted, and so is their circumcentre's position.
        let k = axis();
        let on = |u: f64, v: f64| {
            let q = [0, 1, 2].map(|c| T[0][c] + u * (T[1][c] - T[0][c]) + v * (T[2][c] - T[0][c]));
            onto_plane(T, q, k).unwrap()
        };
        let mut off = 0;
        for i in 1..200 {
            let d = 1e-4 * i as f64;
            let (a, b, c) = (on(0.3, 0.0), on(0.3 + 1e-3, 0.0), on(0.31, d));
            let cc = tri_circumcenter3(a, b, c).unwrap();
            if !within_ulp_of_plane(T, cc, k) {
                off += 1;
            }
            assert!(within_ulp_of_plane(T, onto_plane(T, cc, k).unwrap(), k));
        }
        // The construction alone leaves the plane for a good share of them.
        assert!(off > 20, "{off}");
    }
}
