//! Small-angle protection (paper §6): input angles below 60° between edges and between
//! facets, the protection balls and concentric shells around sharp vertices and edges, and the
//! rule that exempts from the radius-edge bound only the tets such an angle forces.

use super::*;

/// Input angles below 60°: between two input edges at a vertex (for two edges of one facet,
/// below [`wedge_sharp_angle`]), and between two facets along an edge (dihedral). Radius-edge
/// refinement next to them would never end (each split makes a smaller bad tet between the two
/// features), so tets whose badness they cause are exempt from the bound, as Triangle and the
/// paper (§6) do for small 2D angles.
///
/// At a sharp vertex the judgement goes by the tet's shortest edge, which is what makes its
/// radius-edge ratio large: only a short edge pinned by the small angle excuses the tet (one
/// ending in the apex's protection ball, one across the wedge between concentric shells, or
/// one next to a thin wedge). A tet that merely touches a sharp vertex is not excused:
/// exempting every such tet, however large, left whole inputs unrefined (a finely triangulated
/// CAD surface has a sharp vertex almost everywhere).
#[derive(Default)]
pub(crate) struct Sharp {
    /// Input vertices where two input edges meet below 60° (two edges of one facet: below
    /// [`wedge_sharp_angle`]).
    pub(crate) vertices: crate::hash::FastSet<u32>,
    /// Input edges along which two facets meet below 60°.
    edges: crate::hash::FastSet<u32>,
    /// Facet pairs (smaller id first) meeting below 60° along an edge or at a vertex.
    facet_pairs: crate::hash::FastSet<(u32, u32)>,
    /// Input edge pairs (smaller id first) meeting at a sharp vertex, with the apex's position:
    /// a tet whose shortest edge joins points of the two at equal distances from the apex (the
    /// concentric shells of [`Mesher::split_point`]) spans the wedge, and refining it would
    /// only move the problem closer to the apex (Triangle's rule for a skinny triangle whose
    /// short edge faces a small input angle).
    seg_pairs: crate::hash::FastMap<(u32, u32), [f64; 3]>,
    /// The angle (degrees) of each pair of `seg_pairs`: sliver removal exempts only pairs
    /// narrower than its target (see [`Sharp::exempts_sliver`]).
    pair_angle: crate::hash::FastMap<(u32, u32), f64>,
    /// Per facet: protection zones of the sharp edges on it. Tets with a vertex on the facet
    /// inside a zone are exempt: next to a sharp edge the two facets' refinement feeds itself
    /// (each split near one facet encroaches the other), ever closer to the edge.
    zones: Vec<Vec<Zone>>,
    /// Protection zones of thin wedges (see [`Wedge`]).
    wedges: Vec<Wedge>,
    /// Protection balls of the sharp vertices: (apex, squared radius), the radius
    /// [`BALL_FRACTION`] of the shorter edge of a sharp pair there (the largest such). Inside, the concentric shells
    /// split the edges and tets with a shortest edge ending there are not refined (corner
    /// lopping, as in Pav and Walkington's Delaunay refinement for small angles): below the
    /// theoretical bound (a radius-edge ratio of 2) refinement next to a sharp vertex can
    /// otherwise run towards it (a triangulated U-shaped part at -pq1.2: 4,000 tets within 0.02 of one 9-degree corner).
    balls: Vec<([f64; 3], f64)>,
    /// Per ball: the smallest angle (degrees) of a sharp pair at its vertex.
    ball_angle: Vec<f64>,
    /// `balls` and `wedges` indexed by their boxes (nearly every vertex of a scanned surface
    /// is sharp: scanning them all for every tet made refinement quadratic).
    ball_index: box_index::BoxIndex,
    wedge_index: box_index::BoxIndex,
}

/// The part of a sharp vertex's protection ball (relative to its radius) inside which
/// sliver removal excuses every tet ([`Sharp::deep_in_ball`]).
const DEEP_FRACTION: f64 = 1.0 / 16.0;

/// A thin wedge: two input edges from `apex` to `ends` meeting at an angle whose sine is below
/// [`THIN_WEDGE`], with its protection zone, the points within `sqrt(r2)` of both edges
/// (bounding box `lo`, `hi`). The two edges run side by side along their whole length (0.07°
/// needle triangles of a triangulated U-shaped part: two edges 0.04 long never more than 5e-5 apart), so shells near
/// the apex do not help: everywhere along them, tets join points on both and are as short as
/// the gap, and refinement would resolve the gap (at about 1/angle tets per doubling of the
/// distance from the apex, 50,000 tets for that part) where TetGen just leaves such tets alone. A
/// tet whose shortest edge has an endpoint in the zone is exempt.
#[derive(Clone, Copy)]
struct Wedge {
    apex: [f64; 3],
    ends: [[f64; 3]; 2],
    r2: f64,
    lo: [f64; 3],
    hi: [f64; 3],
}

/// Sine of the largest angle of a thin wedge: its widest gap (at the end of the shorter edge)
/// is below a quarter of its zone radius ([`ZONE_FRACTION`] of that edge's length), so at the
/// zone's scale the two edges are one feature. (About 3.6°: 0.07° needle wedges are thin,
/// 5.7° surface triangles are not.)
const THIN_WEDGE: f64 = ZONE_FRACTION / 4.0;

/// Radius of a sharp vertex's protection ball, relative to the shorter edge of the pair: half
/// the zone fraction of edges. (On a triangulated U-shaped part at -pq1.2, a quarter left a tenth of
/// the tets above the bound, an eighth 4.4 % as TetGen does; a sixteenth let its corners take
/// 1.4x TetGen's tets.)
const BALL_FRACTION: f64 = ZONE_FRACTION / 2.0;

/// Relative tolerance of "equal distances from the apex" for points on the two edges of a
/// sharp vertex: shell points sit at the same power-of-two distance up to rounding.
const SHELL_TOLERANCE: f64 = 1e-3;

impl Wedge {
    /// The wedge at `apex` between the edges to `a` and `b`, with its zone.
    fn new(apex: glam::DVec3, a: glam::DVec3, b: glam::DVec3) -> Wedge {
        let r = ZONE_FRACTION * (a - apex).length().min((b - apex).length());
        let lo = apex.min(a).min(b) - glam::DVec3::splat(r);
        let hi = apex.max(a).max(b) + glam::DVec3::splat(r);
        Wedge {
            apex: apex.to_array(),
            ends: [a.to_array(), b.to_array()],
            r2: r * r,
            lo: lo.to_array(),
            hi: hi.to_array(),
        }
    }
}

/// The angle below which two input edges of one facet meeting at a vertex make it sharp, for
/// the radius-edge bound `radius_edge`: 30° (a spike's tip), or more when the bound is below √2.
///
/// Why: take the vertex `A`, the wedge's split points `P1`, `P2` at the same distance `r` from
/// it (concentric shells, see `split_point`) and the wedge angle `θ`. Any tet with corners
/// `A`, `P1`, `P2` has its circumcentre above the circumcentre `O` of the subface `A P1 P2`
/// (radius `ρf = r / (2 cos(θ/2))`), so its circumradius is `R ≥ ρf`, and the circumcentre is
/// in the subface's diametral ball exactly when `R < √2 ρf`; its shortest edge is at most
/// `|P1 P2| = 2 r sin(θ/2)`. So some such tet is bad (`R > ρ |P1 P2|`) with its circumcentre
/// refused for encroaching the subface iff `√2 ρf > ρ |P1 P2|`, i.e. `sin θ < 1 / (√2 ρ)`.
/// The subface is then split at `O`, which encroaches both wedge subsegments (the angle
/// `A O P1` is `180° − θ`); they are split at `r / 2`, and the same tet comes back at half the
/// size, forever (a CAD fan-disk model with `-q1.2`: a 30.1° wedge, a tet of ratio 1.38 at every scale,
/// down to subfaces 1e-9 across). At `ρ = √2` this angle is 30°; for `ρ = 1.2`, 36.1°.
/// Looser bounds (and no bound) keep 30°: a spike's tip is sharp whatever the bound.
pub(crate) fn wedge_sharp_angle(radius_edge: Option<f64>) -> f64 {
    let rho = radius_edge.unwrap_or(std::f64::consts::SQRT_2);
    let sin = (1.0 / (std::f64::consts::SQRT_2 * rho)).min(1.0);
    sin.asin().max(30f64.to_radians())
}

/// A protection zone: the points within `sqrt(r2)` of the segment `a b`.
#[derive(Clone, Copy)]
struct Zone {
    a: [f64; 3],
    b: [f64; 3],
    r2: f64,
}

/// Radius of the protection zone of a sharp edge, relative to the edge's length.
const ZONE_FRACTION: f64 = 0.25;

impl Sharp {
    /// The small angles of `plc`; `radius_edge` is the quality bound (it decides how narrow
    /// a wedge inside one facet must be to sustain endless refinement).
    pub(crate) fn find(plc: &Plc, feat: &Features, radius_edge: Option<f64>) -> Sharp {
        use glam::DVec3;
        let p = |v: u32| DVec3::from(plc.points[v as usize]);
        let small = 60f64.to_radians().cos();
        let narrow_wedge = wedge_sharp_angle(radius_edge).cos();
        let mut sharp = Sharp::default();
        let mut ball_r2: crate::hash::FastMap<u32, f64> = Default::default();
        let mut vertex_angle: crate::hash::FastMap<u32, f64> = Default::default();
        for (&v, nbrs) in &feat.seg_adj {
            if (v as usize) >= plc.points.len() {
                continue;
            }
            let facets_of = |w: u32| {
                feat.subsegs
                    .get(&crate::mesh3d::features::ekey(v, w))
                    .map(|&e| feat.edges[e as usize].facets.clone())
                    .unwrap_or_default()
            };
            for (i, &a) in nbrs.iter().enumerate() {
                for &b in &nbrs[i + 1..] {
                    let (da, db) = ((p(a) - p(v)).normalize(), (p(b) - p(v)).normalize());
                    let cos = da.dot(db);
                    // Two edges of one facet meeting at a moderate angle are the facet mesh's
                    // business; a narrower wedge (see `wedge_sharp_angle`) is sharp anyway.
                    let share = facets_of(a).iter().any(|f| facets_of(b).contains(f));
                    if (cos > small && !share) || cos > narrow_wedge {
                        sharp.vertices.insert(v);
                        let angle = cos.clamp(-1.0, 1.0).acos().to_degrees();
                        let least = vertex_angle.entry(v).or_insert(angle);
                        *least = least.min(angle);
                        let edge = |w: u32| feat.subsegs.get(&crate::mesh3d::features::ekey(v, w));
                        if let (Some(&e1), Some(&e2)) = (edge(a), edge(b)) {
                            let key = (e1.min(e2), e1.max(e2));
                            sharp.seg_pairs.insert(key, p(v).to_array());
                            sharp.pair_angle.insert(key, angle);
                        }
                        if (1.0 - cos * cos).max(0.0).sqrt() < THIN_WEDGE {
                            sharp.wedges.push(Wedge::new(p(v), p(a), p(b)));
                        }
                        let r = BALL_FRACTION * (p(a) - p(v)).length().min((p(b) - p(v)).length());
                        let ball = ball_r2.entry(v).or_insert(0.0);
                        *ball = ball.max(r * r);
                    }
                }
            }
        }
        // The directions into facet f from edge ab: the in-plane normals to the edge (n × e)
        // on whose side the facet lies next to the edge's midpoint (both for an edge inside
        // the facet, none for a degenerate one). Taking, say, the direction towards the
        // farthest facet vertex instead would cross a hole of a ring facet.
        let mut balls: Vec<(u32, f64)> = ball_r2.into_iter().collect();
        balls.sort_unstable_by_key(|b| b.0);
        sharp.ball_angle = balls.iter().map(|b| vertex_angle[&b.0]).collect();
        sharp.balls = balls
            .into_iter()
            .map(|(v, r2)| (p(v).to_array(), r2))
            .collect();
        sharp.ball_index = box_index::BoxIndex::new(
            &sharp
                .balls
                .iter()
                .map(|&(c, r2)| {
                    // Widened far beyond the rounding of the square root, so a point the
                    // distance test puts inside is in the box.
                    let r = r2.sqrt() * (1.0 + 1e-6);
                    (c.map(|x| x - r), c.map(|x| x + r))
                })
                .collect::<Vec<_>>(),
        );
        sharp.wedge_index = box_index::BoxIndex::new(
            &sharp
                .wedges
                .iter()
                .map(|w| (w.lo, w.hi))
                .collect::<Vec<_>>(),
        );
        let inward = |f: u32, a: u32, b: u32| -> Vec<DVec3> {
            let fi = &feat.facets[f as usize];
            let [u, v, w] = fi.plane.map(p);
            let n = (v - u).cross(w - u);
            let (pa, pb) = (p(a), p(b));
            let e = pb - pa;
            let d = n.cross(e).normalize_or_zero();
            if d == DVec3::ZERO {
                return Vec::new();
            }
            let mid = 0.5 * (pa + pb);
            // Step off the midpoint by less than its distance to any other outline edge, so
            // the probes see only the facet's side of this edge.
            let q = crate::mesh3d::features::proj(mid.to_array(), fi.axis);
            let (qa, qb) = (
                crate::mesh3d::features::proj(pa.to_array(), fi.axis),
                crate::mesh3d::features::proj(pb.to_array(), fi.axis),
            );
            let mut reach = 0.25 * e.length();
            for lp in &fi.outline.loops {
                for i in 0..lp.len() {
                    let (s, t) = (lp[i], lp[(i + 1) % lp.len()]);
                    if on_line2(s, qa, qb) && on_line2(t, qa, qb) {
                        continue; // the edge itself (or a collinear piece of its loop edge)
                    }
                    let lift = |u: [f64; 2]| [u[0], u[1], 0.0];
                    let d2 = crate::geometry::dist2_point_segment3(lift(q), lift(s), lift(t));
                    reach = reach.min(d2.sqrt());
                }
            }
            // (The projection does not lengthen the step.)
            let step = 0.5 * reach;
            [d, -d]
                .into_iter()
                .filter(|&s| {
                    let probe = (mid + s * step).to_array();
                    fi.outline
                        .contains(crate::mesh3d::features::proj(probe, fi.axis))
                })
                .collect()
        };
        for (ei, e) in feat.edges.iter().enumerate() {
            let [a, b] = e.ends;
            for (i, &f1) in e.facets.iter().enumerate() {
                for &f2 in &e.facets[i + 1..] {
                    let (d1, d2) = (inward(f1, a, b), inward(f2, a, b));
                    if d1.iter().any(|x| d2.iter().any(|y| x.dot(*y) > small)) {
                        sharp.edges.insert(ei as u32);
                        sharp.facet_pairs.insert((f1.min(f2), f1.max(f2)));
                    }
                }
            }
        }
        sharp.zones = vec![Vec::new(); feat.facets.len()];
        for &ei in &sharp.edges {
            let [a, b] = feat.edges[ei as usize].ends;
            let r = ZONE_FRACTION * (p(b) - p(a)).length();
            for &f in &feat.edges[ei as usize].facets {
                sharp.zones[f as usize].push(Zone {
                    a: p(a).to_array(),
                    b: p(b).to_array(),
                    r2: r * r,
                });
            }
        }
        sharp
    }

    /// Whether a vertex on facet `f` at `q` lies in a protection zone of the facet.
    fn in_zone(&self, f: u32, q: [f64; 3]) -> bool {
        self.zones.get(f as usize).is_some_and(|zs| {
            zs.iter()
                .any(|z| crate::geometry::dist2_point_segment3(q, z.a, z.b) < z.r2)
        })
    }

    /// Whether `q` lies in the protection ball of a sharp vertex whose narrowest sharp pair is
    /// below `below` degrees (all of them for an infinite `below`).
    fn in_ball(&self, q: [f64; 3], below: f64) -> bool {
        self.ball_index.candidates(q).any(|i| {
            let (c, r2) = self.balls[i as usize];
            self.ball_angle[i as usize] < below && crate::geometry::dist2_3(q, c) < r2
        })
    }

    /// Whether all four vertices `vs` lie deep inside one sharp vertex's protection ball,
    /// within [`DEEP_FRACTION`] of its radius. Sliver removal excuses such a tet whatever the
    /// angle there: where input edges meet a little above the target (scanned models have
    /// corners of 15° to 17°), a tet on the corner's subfaces can still have a dihedral
    /// angle below it, and each point that removes one makes a smaller one closer to the apex,
    /// until floating point runs out. Larger tets there are still treated, so that fan angles
    /// of triangulated surfaces keep no sliver (`exempts_sliver`).
    fn deep_in_ball(&self, vs: [u32; 4], pts: &[[f64; 3]]) -> bool {
        let q = vs.map(|v| pts[v as usize]);
        self.ball_index.candidates(q[0]).any(|i| {
            let (c, r2) = self.balls[i as usize];
            let deep2 = r2 * DEEP_FRACTION * DEEP_FRACTION;
            q.iter().all(|&x| crate::geometry::dist2_3(x, c) < deep2)
        })
    }

    /// Whether `q` lies in the protection zone of a thin wedge.
    fn in_wedge(&self, q: [f64; 3]) -> bool {
        use crate::geometry::dist2_point_segment3 as d2;
        self.wedge_index.candidates(q).any(|i| {
            let w = &self.wedges[i as usize];
            (0..3).all(|k| w.lo[k] <= q[k] && q[k] <= w.hi[k])
                && d2(q, w.apex, w.ends[0]) < w.r2
                && d2(q, w.apex, w.ends[1]) < w.r2
        })
    }

    /// Whether the points `p`, `q` on the two edges of the sharp vertex pair `pair` are at the
    /// same distance from its apex (up to [`SHELL_TOLERANCE`]).
    fn on_one_shell(&self, pair: (u32, u32), p: [f64; 3], q: [f64; 3]) -> bool {
        let Some(&a) = self.seg_pairs.get(&pair) else {
            return false;
        };
        let (dp, dq) = (
            crate::geometry::dist2_3(a, p).sqrt(),
            crate::geometry::dist2_3(a, q).sqrt(),
        );
        (dp - dq).abs() <= SHELL_TOLERANCE * dp.max(dq)
    }

    /// Whether the shortest edge of a tet with these vertices (which decides its radius-edge
    /// ratio) is pinned by a sharp vertex: it has an end in the apex's protection ball or in a
    /// thin wedge's zone, or it joins points of the apex's two edges on one concentric shell. Refining
    /// such a tet would only make a shorter edge of the same kind.
    /// Only sharp vertex pairs narrower than `below` degrees count.
    fn short_edge_pinned(
        &self,
        vs: [u32; 4],
        feat: &Features,
        pts: &[[f64; 3]],
        below: f64,
    ) -> bool {
        if self.vertices.is_empty() {
            return false;
        }
        let len2 = |(a, b): (usize, usize)| {
            crate::geometry::dist2_3(pts[vs[a] as usize], pts[vs[b] as usize])
        };
        let (i, j) = EDGES
            .iter()
            .copied()
            .min_by(|&x, &y| len2(x).total_cmp(&len2(y)))
            .unwrap_or((0, 1));
        let (u, w) = (vs[i], vs[j]);
        let (pu, pw) = (pts[u as usize], pts[w as usize]);
        if self.in_ball(pu, below)
            || self.in_ball(pw, below)
            || self.in_wedge(pu)
            || self.in_wedge(pw)
        {
            return true;
        }
        match (feat.split_edge.get(&u), feat.split_edge.get(&w)) {
            (Some(&e1), Some(&e2)) if e1 != e2 => {
                let pair = (e1.min(e2), e1.max(e2));
                self.pair_angle.get(&pair).is_some_and(|&a| a < below)
                    && self.on_one_shell(pair, pu, pw)
            }
            _ => false,
        }
    }

    /// Whether the input has no small angle at all.
    pub(super) fn is_empty(&self) -> bool {
        self.vertices.is_empty() && self.edges.is_empty() && self.facet_pairs.is_empty()
    }

    /// Whether a small input angle excuses a tet with these vertices from the radius-edge
    /// bound: it has a vertex next to a sharp edge, its shortest edge is pinned by a sharp
    /// vertex, or it spans two facets meeting at a sharp edge.
    pub(super) fn exempts(&self, vs: [u32; 4], feat: &Features, pts: &[[f64; 3]]) -> bool {
        self.exempts_sliver(vs, feat, pts, f64::INFINITY)
    }

    /// Whether a small input angle excuses a sliver with these vertices from sliver removal
    /// with the minimum dihedral angle `target` (degrees; infinite: [`Sharp::exempts`]): as
    /// [`Sharp::exempts`], but a sharp vertex (two input edges below 60°, or below the wedge
    /// angle in one facet) counts only where two input edges meet below `target`. Where they
    /// meet below the target, a subface at the corner has that angle and a tet on it with a
    /// vertex off the facet has a dihedral angle of about that size at the corner; wider pairs
    /// force no such tet. On triangulated surfaces such wider pairs are fan angles at nearly
    /// every vertex (two edges of a flat fan two triangles apart): a fan-disk model at
    /// -pq1.414 kept 44 slivers down to 0.05°, all excused by one, which sliver removal (a
    /// point, or the splits it demands) removes. Radius-edge refinement keeps the broader
    /// rule: there the protection balls stop refinement from running towards such vertices.
    pub(crate) fn exempts_sliver(
        &self,
        vs: [u32; 4],
        feat: &Features,
        pts: &[[f64; 3]],
        target: f64,
    ) -> bool {
        if self.vertices.is_empty() && self.edges.is_empty() {
            return false;
        }
        for &v in &vs {
            if let Some(fs) = feat.vert_facets.get(&v) {
                if fs.iter().any(|&f| self.in_zone(f, pts[v as usize])) {
                    return true;
                }
            }
            if let Some(e) = feat.split_edge.get(&v) {
                if self.edges.contains(e) {
                    return true;
                }
            }
        }
        if self.short_edge_pinned(vs, feat, pts, target) || self.deep_in_ball(vs, pts) {
            return true;
        }
        if self.facet_pairs.is_empty() {
            return false;
        }
        let none = Vec::new();
        let fs: Vec<&Vec<u32>> = vs
            .iter()
            .map(|v| feat.vert_facets.get(v).unwrap_or(&none))
            .collect();
        for i in 0..4 {
            for j in i + 1..4 {
                for &f1 in fs[i] {
                    for &f2 in fs[j] {
                        if f1 != f2 && self.facet_pairs.contains(&(f1.min(f2), f1.max(f2))) {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
}
