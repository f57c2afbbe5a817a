//! The 2D Delaunay mesh of one input facet (paper §4.2): Bowyer–Watson in the facet's plane.
//!
//! Vertices are global vertex ids (shared with the 3D mesh), so one global insertion order
//! breaks cocircular ties the same way here and in the 3D mesh (paper Lemma 4.7).
//!
//! Decisions stay exact on the 3D coordinates: they are the 2D kernel's in-plane geometry
//! ([`InPlane`]): orientation is `orient2d` of the projection that drops the facet's dominant
//! normal axis (an affine projection: exact, sign-preserving), and the in-circle test is the 3D
//! one ([`crate::predicates::incircle3d`]): any sphere through a triangle's corners cuts the
//! plane in its circumcircle, so the facet mesh and the 3D mesh see the same circles for
//! coplanar points (paper §6: no rounded map into the plane). A triangle with one corner at
//! infinity is decided exactly as the kernel decides a ghost triangle.
//!
//! The insertion itself (cavity, edge splits, flips) is still this module's own, not the
//! kernel's `Cdt`: a facet's cavity is not walled by its subsegments (it crosses and reports
//! them, so that the facet stays conforming Delaunay like the 3D mesh), Steiner points only
//! reshape the inside of the facet, and the order of the reported subface changes drives the
//! 3D mesher's queue, so moving it onto the kernel changes the 3D meshes.

use std::ops::ControlFlow;

use crate::hash::FastMap as HashMap;

use crate::mesh2d::kernel::{next, prev, Geometry, InPlane, NONE};
use crate::predicates::orient2d;

/// Ids of the three corners of the bounding triangle (paper §6: the facet mesh starts from a
/// large triangle in the facet's plane; triangles touching it are never subfaces).
///
/// The corners are symbolic points at infinity, `λ·BDIR[k]` in projected coordinates as
/// `λ → ∞`: every predicate involving them is its exact limit. A finite bounding triangle is
/// not enough: the circumcircle of a needle triangle (0.07° angles in a triangulated CAD part) is hundreds of
/// times larger than its facet and would hold a finite corner, so the facet's own edges would
/// not be Delaunay in the facet mesh while they are in the 3D mesh.
const BOUND: u32 = u32::MAX - 4;

/// Directions of the corners at infinity (counter-clockwise, distinct lengths so that the
/// limits of cocircular ties are decided by the directions alone).
const BDIR: [[f64; 2]; 3] = [[-1.0, -1.0], [2.0, -1.0], [-1.0, 4.0]];

#[inline]
fn is_bound(v: u32) -> bool {
    (BOUND..BOUND + 3).contains(&v)
}
/// Why an insertion did not happen.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum FacetInsertError {
    /// The point coincides with an existing vertex of the facet mesh.
    Duplicate(u32),
    /// Provisional insertion refused: the point encroaches these subsegments (pairs of vertex
    /// ids) of the facet.
    Encroaches(Vec<[u32; 2]>),
    /// Point location failed (a bug or a badly non-planar point).
    Lost,
}

/// What an insertion changed, for the caller's subface bookkeeping.
#[derive(Debug, Default)]
pub(crate) struct FacetChange {
    /// Triangles (vertex triples) that were inside the facet and are gone.
    pub removed: Vec<[u32; 3]>,
    /// New triangles (vertex triples) inside the facet.
    pub added: Vec<[u32; 3]>,
    /// Subsegments whose diametral circle the (forced) point encroaches or whose edge it
    /// crossed.
    pub encroached: Vec<[u32; 2]>,
}

/// The facet polygon in projected coordinates, for classifying triangles of non-convex facets.
#[derive(Debug, Clone, Default)]
pub(crate) struct Outline {
    /// Closed loops (projected), each a vertex list; edges join consecutive vertices.
    pub loops: Vec<Vec<[f64; 2]>>,
    /// `true` when the facet is one convex loop with no inner loops: then every finite
    /// triangle is inside it.
    pub convex: bool,
}

impl Outline {
    /// Even–odd point-in-polygon, exact for the given point (crossing parity of a rightward ray).
    pub(crate) fn contains(&self, q: [f64; 2]) -> bool {
        let mut inside = false;
        for lp in &self.loops {
            let n = lp.len();
            for i in 0..n {
                let (u, w) = (lp[i], lp[(i + 1) % n]);
                if (u[1] > q[1]) != (w[1] > q[1]) {
                    // The edge straddles the ray's line; it crosses the ray when q is on the
                    // left of the upward-directed edge.
                    let o = if u[1] < w[1] {
                        orient2d(u, w, q)
                    } else {
                        orient2d(w, u, q)
                    };
                    if o > 0.0 {
                        inside = !inside;
                    }
                }
            }
        }
        inside
    }

    /// [`Outline::contains`] for the centroid of triangle `t`, exactly: the rounded centroid
    /// of a sliver (three nearly collinear loop vertices) can round across the loop edge next
    /// to it. When the rounded centroid is strictly inside the triangle it stands for the true
    /// one; otherwise the parity is computed on the exact centroid (a + b + c) / 3.
    pub(crate) fn contains_centroid(&self, t: [[f64; 2]; 3]) -> bool {
        let q = [0, 1].map(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0);
        let o = orient2d(t[0], t[1], t[2]);
        let strictly_in = (0..3).all(|i| orient2d(t[i], t[(i + 1) % 3], q) * o > 0.0);
        if strictly_in {
            return self.contains(q);
        }
        use crate::exact::DynExpansion as X;
        // 3 q - 3 x, coordinate k, exactly.
        let rel = |k: usize, x: f64| {
            X::from_f64(t[0][k])
                .add(&X::from_f64(t[1][k]))
                .add(&X::from_f64(t[2][k]))
                .sub(&X::from_product(3.0, x))
        };
        let mut inside = false;
        for lp in &self.loops {
            let n = lp.len();
            for i in 0..n {
                let (u, w) = (lp[i], lp[(i + 1) % n]);
                if (rel(1, u[1]).sign() < 0) != (rel(1, w[1]).sign() < 0) {
                    let (lo, hi) = if u[1] < w[1] { (u, w) } else { (w, u) };
                    // 3 orient2d(lo, hi, q).
                    let o3 = X::from_diff(hi[0], lo[0])
                        .mul(&rel(1, lo[1]))
                        .sub(&X::from_diff(hi[1], lo[1]).mul(&rel(0, lo[0])));
                    if o3.sign() > 0 {
                        inside = !inside;
                    }
                }
            }
        }
        inside
    }
}

/// The exact sign of `cx (p.x - a.x) + cy (p.y - a.y)` for small integers `cx`, `cy`.
fn lin_sign(cx: f64, cy: f64, p: [f64; 2], a: [f64; 2]) -> i32 {
    use crate::exact::{two_prod, Expansion};
    let mut e = Expansion::new();
    for (c, x) in [(cx, p[0]), (-cx, a[0]), (cy, p[1]), (-cy, a[1])] {
        let (hi, lo) = two_prod(c, x);
        e.add(lo);
        e.add(hi);
    }
    e.sign()
}

/// The sign of `cross(d, p - a)`.
fn cross_sign(d: [f64; 2], p: [f64; 2], a: [f64; 2]) -> i32 {
    lin_sign(-d[1], d[0], p, a)
}

/// One facet's Delaunay triangulation.
pub(crate) struct FacetMesh {
    /// The facet's plane: the exact in-plane predicates on 3D coordinates.
    geom: InPlane,
    tv: Vec<[u32; 3]>,
    /// `tn[t][i]`: half-edge `3t' + i'` across the edge opposite vertex `i` (`NONE` only on the
    /// bounding triangle's outer edges).
    tn: Vec<[u32; 3]>,
    alive: Vec<bool>,
    inside: Vec<bool>,
    free: Vec<u32>,
    vtri: HashMap<u32, u32>,
    outline: Outline,
    stamp: Vec<u32>,
    cur: u32,
    cav: Vec<u32>,
    bnd: Vec<u32>,
    last: u32,
}

impl FacetMesh {
    /// A facet mesh projecting along `axis`, holding only the bounding triangle (at infinity).
    pub fn new(axis: usize, outline: Outline) -> FacetMesh {
        let mut fm = FacetMesh {
            geom: InPlane { axis },
            tv: Vec::new(),
            tn: Vec::new(),
            alive: Vec::new(),
            inside: Vec::new(),
            free: Vec::new(),
            vtri: HashMap::default(),
            outline,
            stamp: Vec::new(),
            cur: 0,
            cav: Vec::new(),
            bnd: Vec::new(),
            last: NONE,
        };
        fm.last = fm.alloc([BOUND, BOUND + 1, BOUND + 2]);
        fm
    }

    #[inline]
    fn proj(&self, p: [f64; 3]) -> [f64; 2] {
        self.geom.proj(p)
    }

    /// Coordinates of a finite vertex.
    #[inline]
    fn pt(&self, v: u32, pts: &[[f64; 3]]) -> [f64; 3] {
        debug_assert!(!is_bound(v));
        pts[v as usize]
    }

    /// The orientation sign of `(a, b, p)` in projection, `a` and `b` vertex ids (possibly
    /// corners at infinity), `p` a finite point of the plane: the exact limit.
    fn orient(&self, a: u32, b: u32, p: [f64; 3], pts: &[[f64; 3]]) -> f64 {
        match (is_bound(a), is_bound(b)) {
            (false, false) => self.geom.orient(pts[a as usize], pts[b as usize], p),
            (false, true) => {
                cross_sign(BDIR[(b - BOUND) as usize], self.proj(p), self.pp(a, pts)) as f64
            }
            (true, false) => {
                -cross_sign(BDIR[(a - BOUND) as usize], self.proj(p), self.pp(b, pts)) as f64
            }
            (true, true) => {
                if b - BOUND == (a - BOUND + 1) % 3 {
                    1.0
                } else {
                    -1.0
                }
            }
        }
    }

    #[inline]
    fn pp(&self, v: u32, pts: &[[f64; 3]]) -> [f64; 2] {
        self.proj(self.pt(v, pts))
    }

    fn alloc(&mut self, v: [u32; 3]) -> u32 {
        if let Some(t) = self.free.pop() {
            self.tv[t as usize] = v;
            self.tn[t as usize] = [NONE; 3];
            self.alive[t as usize] = true;
            self.inside[t as usize] = false;
            t
        } else {
            self.tv.push(v);
            self.tn.push([NONE; 3]);
            self.alive.push(true);
            self.inside.push(false);
            self.stamp.push(0);
            (self.tv.len() - 1) as u32
        }
    }

    fn link(&mut self, h1: u32, h2: u32) {
        if h1 != NONE {
            self.tn[(h1 / 3) as usize][(h1 % 3) as usize] = h2;
        }
        if h2 != NONE {
            self.tn[(h2 / 3) as usize][(h2 % 3) as usize] = h1;
        }
    }

    /// The index of the live triangle with corners `v` (any order), if there is one.
    fn find_triangle(&self, v: [u32; 3]) -> Option<u32> {
        let h = self.find_half_edge(v[0], v[1])?;
        let t = h / 3;
        if self.tv[t as usize].contains(&v[2]) {
            return Some(t);
        }
        let o = self.tn[t as usize][(h % 3) as usize];
        (o != NONE && self.tv[(o / 3) as usize].contains(&v[2])).then_some(o / 3)
    }

    /// Checks a provisional Steiner point `p` meant to split the triangle `origin` (with `p`
    /// in its circumcircle, typically its circumcentre) before it is inserted: `p` must be
    /// reachable from `origin` through triangles inside the facet that are in conflict with
    /// it, without crossing a subsegment. In exact arithmetic a point that is not lies beyond
    /// a subsegment on that region's boundary (outside the facet, in a hole, or across an
    /// inner subsegment); inserting it anyway would put a vertex outside the facet into the
    /// facet mesh (and into the 3D mesh as a facet point). Such a point encroaches the
    /// boundary subsegments of the region that face it: they are returned to be split first
    /// (paper §4.1: the facet waits until the segment is split), as Ruppert does when a
    /// circumcentre falls outside the domain (the list is empty when `p` lies outside the
    /// facet but the region met no subsegment). `Ok` when `p` is reached, or lies inside the
    /// facet, or `origin` is not a triangle of this mesh (then [`FacetMesh::insert`] decides).
    pub fn check_reach(
        &mut self,
        origin: [u32; 3],
        p: [f64; 3],
        pts: &[[f64; 3]],
        is_subseg: &dyn Fn(u32, u32) -> bool,
    ) -> Result<(), FacetInsertError> {
        let Some(t0) = self.find_triangle(origin) else {
            return Ok(());
        };
        let target = self.locate(p, pts);
        if target == Some(t0) {
            return Ok(());
        }
        self.cur = self.cur.wrapping_add(2);
        if self.cur < 2 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.cur = 2;
        }
        let cur = self.cur;
        let mut region = vec![t0];
        self.stamp[t0 as usize] = cur;
        let (mut facing, mut other) = (Vec::new(), Vec::new());
        let mut k = 0;
        while k < region.len() {
            let t = region[k];
            k += 1;
            let v = self.tv[t as usize];
            for i in 0..3 {
                let h = self.tn[t as usize][i];
                let (x, y) = (v[next(i)], v[prev(i)]);
                if h == NONE {
                    continue;
                }
                if !is_bound(x) && !is_bound(y) && is_subseg(x, y) {
                    let seg = [x.min(y), x.max(y)];
                    if self.geom.orient(pts[x as usize], pts[y as usize], p) <= 0.0 {
                        facing.push(seg);
                    } else {
                        other.push(seg);
                    }
                    continue;
                }
                let n = h / 3;
                if self.stamp[n as usize] == cur
                    || !self.inside[n as usize]
                    || !self.conflict(n, p, pts)
                {
                    continue;
                }
                if Some(n) == target {
                    return Ok(());
                }
                self.stamp[n as usize] = cur;
                region.push(n);
            }
        }
        if facing.is_empty() {
            facing = other;
        }
        // No subsegment met: the region ran into triangles out of conflict with `p` (a facet
        // mesh that follows the 3D mesh on nearly cocircular quadrilaterals is not quite
        // Delaunay in its own plane, so the conflict region need not reach `p`). Then `p` is
        // inserted only if it lies inside the facet; outside it, an empty list tells the
        // caller to split inside the face instead.
        if facing.is_empty() && target.is_some_and(|t| self.inside[t as usize]) {
            return Ok(());
        }
        facing.sort_unstable();
        facing.dedup();
        Err(FacetInsertError::Encroaches(facing))
    }

    /// Whether the mesh has a vertex of the facet yet.
    pub fn started(&self) -> bool {
        !self.vtri.is_empty()
    }

    /// Every live triangle inside the facet, as vertex triples.
    #[cfg(test)]
    pub fn inside_triangles(&self) -> Vec<[u32; 3]> {
        (0..self.tv.len())
            .filter(|&t| self.alive[t] && self.inside[t])
            .map(|t| self.tv[t])
            .collect()
    }

    /// Whether `a b` is an edge of the mesh.
    pub fn has_edge(&self, a: u32, b: u32) -> bool {
        self.find_half_edge(a, b).is_some()
    }

    /// Recovers the missing edge `a b` (a subsegment on the facet's boundary, both ends
    /// vertices of this mesh) by flipping the triangles *outside* the facet that cross it.
    ///
    /// Steiner points reshape only the inside of the facet (see [`FacetMesh::insert`]), so an
    /// outside triangle can keep an edge that crosses a boundary subsegment split after it was
    /// made: the subsegment is then in the 3D mesh but never in this one, and splitting it
    /// again cannot help (the crossing edge survives every split). Lawson's edge recovery on
    /// the scaffolding alone brings it back: every flip stays inside the union of the crossed
    /// triangles, so no triangle inside the facet changes; the ones the recovery puts inside
    /// the facet are returned in `added`. `None` when the segment passes through a vertex,
    /// meets a corner at infinity, a subsegment or a triangle inside the facet (nothing
    /// changed), or when the flips run out of budget before the edge appears (some outside
    /// triangles flipped, none inside); the caller then splits the subsegment as before.
    pub fn recover_edge(
        &mut self,
        a: u32,
        b: u32,
        pts: &[[f64; 3]],
        is_subseg: &dyn Fn(u32, u32) -> bool,
        on_one_edge: &dyn Fn([u32; 3]) -> bool,
    ) -> Option<FacetChange> {
        if is_bound(a) || is_bound(b) || !self.vtri.contains_key(&b) {
            return None;
        }
        let pb = self.pt(b, pts);
        let side = |fm: &Self, q: u32| fm.orient(a, b, fm.pt(q, pts), pts);
        // The triangle of a's star that the segment leaves through: (a, x, y) with x strictly
        // right of a->b and y strictly left.
        let first = self.around(a, |t, i| {
            let v = self.tv[t as usize];
            let (x, y) = (v[next(i)], v[prev(i)]);
            if is_bound(x) || is_bound(y) {
                return ControlFlow::Break(None);
            }
            let (sx, sy) = (side(self, x), side(self, y));
            if sx == 0.0
                && self
                    .geom
                    .strictly_between(self.pt(a, pts), pb, self.pt(x, pts))
            {
                return ControlFlow::Break(None); // a vertex on the segment
            }
            if sx < 0.0 && sy > 0.0 {
                return ControlFlow::Break(Some((t, i)));
            }
            ControlFlow::Continue(())
        });
        let (mut t, i) = first?;
        // Walk along the segment, collecting the crossed edges (as vertex pairs: flips keep
        // edges' identities only by their ends) and the triangles they bound.
        let mut region = vec![t];
        let v = self.tv[t as usize];
        let (mut x, mut y) = (v[next(i)], v[prev(i)]);
        let mut crossed: std::collections::VecDeque<[u32; 2]> = Default::default();
        for _ in 0..self.tv.len() + 1 {
            if self.inside[t as usize] || is_subseg(x, y) {
                return None;
            }
            crossed.push_back([x, y]);
            let h = self.find_half_edge(x, y)?;
            let (h0, k0) = (h / 3, (h % 3) as usize);
            // The triangle across (x, y) from t.
            let o = if h0 == t { self.tn[t as usize][k0] } else { h };
            if o == NONE {
                return None;
            }
            let n = o / 3;
            let q = self.tv[n as usize][(o % 3) as usize];
            if is_bound(q) || self.inside[n as usize] {
                return None;
            }
            region.push(n);
            if q == b {
                break;
            }
            match side(self, q) {
                s if s < 0.0 => x = q,
                s if s > 0.0 => y = q,
                _ => return None, // a vertex on the segment's line, inside the crossed region
            }
            t = n;
        }
        if self.tv[*region.last()? as usize].iter().all(|&q| q != b) {
            return None;
        }
        let crosses = |fm: &Self, c: u32, q: u32| {
            if [c, q].iter().any(|u| *u == a || *u == b) {
                return false;
            }
            let (pc, pq) = (fm.pt(c, pts), fm.pt(q, pts));
            let (s1, s2) = (side(fm, c), side(fm, q));
            let (s3, s4) = (
                fm.geom.orient(pc, pq, fm.pt(a, pts)),
                fm.geom.orient(pc, pq, pb),
            );
            s1 * s2 < 0.0 && s3 * s4 < 0.0
        };
        let mut budget = 4 * crossed.len() * crossed.len() + 16;
        while let Some([x, y]) = crossed.pop_front() {
            if budget == 0 {
                break;
            }
            budget -= 1;
            let h = self.find_half_edge(x, y)?;
            let (t, k) = (h / 3, (h % 3) as usize);
            let o = self.tn[t as usize][k];
            if o == NONE {
                return None;
            }
            let c = self.tv[t as usize][k];
            let (ex, ey) = (self.tv[t as usize][next(k)], self.tv[t as usize][prev(k)]);
            let q = self.tv[(o / 3) as usize][(o % 3) as usize];
            let (pc, pq) = (self.pt(c, pts), self.pt(q, pts));
            let convex = self.geom.orient(pc, self.pt(ex, pts), pq) > 0.0
                && self.geom.orient(pc, pq, self.pt(ey, pts)) > 0.0;
            if !convex {
                crossed.push_back([x, y]);
                continue;
            }
            self.flip_edge(t, k);
            if crosses(self, c, q) {
                crossed.push_back([c, q]);
            }
        }
        if !crossed.is_empty() || !self.has_edge(a, b) {
            // Out of budget: the flips made are of the outside alone; the mesh stays valid.
            return None;
        }
        let mut change = FacetChange::default();
        for &t in &region {
            let v = self.tv[t as usize];
            let ins = !on_one_edge(v) && self.classify(v, pts);
            self.inside[t as usize] = ins;
            if ins {
                change.added.push(v);
            }
        }
        self.last = region[0];
        debug_assert!(self.check().is_ok(), "facet mesh: {:?}", self.check());
        Some(change)
    }

    /// Flips an edge of the inside triangle `v` to the other diagonal of its quadrilateral when
    /// the 3D mesh has both triangles of that diagonal (`in_3d`), so that this mesh follows the
    /// 3D mesh instead of the subface `v` being split.
    ///
    /// The 3D mesh and this one disagree only where four points of the facet are nearly
    /// cocircular: facet points are rounded a hair off the plane, and the 3D insphere test
    /// sees that while this mesh's in-plane test does not. Circumcentre insertion makes such
    /// quadrilaterals all the time; on a facet small against its distance from the origin
    /// (1e-8 of a unit box, next to a hole corner), splitting the missing subface instead made
    /// ever smaller ones, down to the precision limit. Either diagonal is then Delaunay up to
    /// rounding, and both new triangles are already faces of the 3D mesh, so the flip ends
    /// that subface's recovery. Only a convex quadrilateral (exact orientation in the facet's
    /// projection) of two inside triangles is flipped, never across a subsegment.
    pub fn follow_flip(
        &mut self,
        v: [u32; 3],
        pts: &[[f64; 3]],
        is_subseg: &dyn Fn(u32, u32) -> bool,
        on_one_edge: &dyn Fn([u32; 3]) -> bool,
        in_3d: &dyn Fn([u32; 3]) -> bool,
    ) -> Option<FacetChange> {
        // Only when the half-edge found is `v`'s own (not its neighbour's across `v0 v1`):
        // following the 3D mesh from both sides flipped more and left a 3.6° sliver on a domed
        // prism (`sliver3d::hard_slivers_get_more_candidates`); either way, `None` only means
        // the subface is split as before.
        let h = self.find_half_edge(v[0], v[1])?;
        let t = h / 3;
        let tv = self.tv[t as usize];
        if !self.inside[t as usize] || !v.iter().all(|x| tv.contains(x)) {
            return None;
        }
        for k in 0..3 {
            let (c, x, y) = (tv[k], tv[next(k)], tv[prev(k)]);
            let o = self.tn[t as usize][k];
            if o == NONE || is_subseg(x, y) {
                continue;
            }
            let n = o / 3;
            let q = self.tv[n as usize][(o % 3) as usize];
            if is_bound(q) || !self.inside[n as usize] {
                continue;
            }
            let (pc, pq) = (self.pt(c, pts), self.pt(q, pts));
            let convex = self.geom.orient(pc, self.pt(x, pts), pq) > 0.0
                && self.geom.orient(pc, pq, self.pt(y, pts)) > 0.0;
            let (t1, t2) = ([c, x, q], [c, q, y]);
            if !convex || on_one_edge(t1) || on_one_edge(t2) || !in_3d(t1) || !in_3d(t2) {
                continue;
            }
            let old = self.tv[n as usize];
            self.flip_edge(t, k);
            let mut change = FacetChange {
                removed: vec![tv, old],
                ..Default::default()
            };
            // Both lie in the union of two inside triangles, so inside.
            for tt in [t, n] {
                self.inside[tt as usize] = true;
                change.added.push(self.tv[tt as usize]);
            }
            self.last = t;
            debug_assert!(self.check().is_ok(), "facet mesh: {:?}", self.check());
            return Some(change);
        }
        None
    }

    /// A half-edge `3t + i` whose edge joins `a` and `b` (either direction).
    fn find_half_edge(&self, a: u32, b: u32) -> Option<u32> {
        self.around(a, |t, i| {
            let v = self.tv[t as usize];
            match (0..3).find(|&j| v[j] == b) {
                Some(j) => ControlFlow::Break(Some(3 * t + (3 - i - j) as u32)),
                None => ControlFlow::Continue(()),
            }
        })
    }

    /// Visits the triangles of `a`'s star as `(t, i)` with `tv[t][i] == a`, until `visit`
    /// breaks with its answer; `None` when `a` is not a vertex or the star is exhausted.
    fn around<R>(
        &self,
        a: u32,
        mut visit: impl FnMut(u32, usize) -> ControlFlow<Option<R>>,
    ) -> Option<R> {
        let &t0 = self.vtri.get(&a)?;
        if !self.alive[t0 as usize] {
            return None;
        }
        let mut t = t0;
        // The star of a facet vertex is a closed cycle (the bounding triangle surrounds it).
        for _ in 0..self.tv.len() + 1 {
            let v = self.tv[t as usize];
            let i = (0..3).find(|&i| v[i] == a)?;
            if let ControlFlow::Break(r) = visit(t, i) {
                return r;
            }
            let h = self.tn[t as usize][prev(i)];
            if h == NONE {
                return None;
            }
            t = h / 3;
            if t == t0 {
                return None;
            }
        }
        None
    }

    /// Whether `p` lies strictly inside the circumcircle of triangle `t`. For triangles with
    /// corners at infinity the circle's limit is a half-plane: beyond the edge `x y` for one
    /// corner, beyond the parallel through `x` to the corners' edge for two.
    fn conflict(&self, t: u32, p: [f64; 3], pts: &[[f64; 3]]) -> bool {
        let v = self.tv[t as usize];
        let nb = v.iter().filter(|&&x| is_bound(x)).count();
        match nb {
            0 => {
                let [a, b, c] = v.map(|x| self.pt(x, pts));
                self.geom.incircle(a, b, c, p) > 0.0
            }
            1 => {
                let k = (0..3).find(|&k| is_bound(v[k])).unwrap_or(0);
                // As a ghost triangle of the kernel: beyond its finite edge, or on it.
                let (x, y) = (self.pt(v[next(k)], pts), self.pt(v[prev(k)], pts));
                let o = self.geom.orient(x, y, p);
                o > 0.0 || (o == 0.0 && self.geom.strictly_between(x, y, p))
            }
            2 => {
                let k = (0..3).find(|&k| !is_bound(v[k])).unwrap_or(0);
                let di = BDIR[(v[next(k)] - BOUND) as usize];
                let dj = BDIR[(v[prev(k)] - BOUND) as usize];
                let e = [dj[0] - di[0], dj[1] - di[1]];
                let (x, p2) = (self.pp(v[k], pts), self.proj(p));
                match cross_sign(e, p2, x) {
                    c if c < 0 => true,
                    0 => {
                        let s = (dj[0] * dj[0] + dj[1] * dj[1]) - (di[0] * di[0] + di[1] * di[1]);
                        (lin_sign(e[0], e[1], p2, x) as f64) * s > 0.0
                    }
                    _ => false,
                }
            }
            _ => true,
        }
    }

    /// Classifies a new triangle: inside the facet polygon or not.
    fn classify(&self, v: [u32; 3], pts: &[[f64; 3]]) -> bool {
        if v.iter().any(|&x| is_bound(x)) {
            return false;
        }
        if self.outline.convex {
            return true;
        }
        self.outline.contains_centroid(v.map(|x| self.pp(x, pts)))
    }

    fn locate(&self, p: [f64; 3], pts: &[[f64; 3]]) -> Option<u32> {
        let mut t = self.last;
        if t == NONE || !self.alive[t as usize] {
            t = (0..self.tv.len() as u32).find(|&t| self.alive[t as usize])?;
        }
        let budget = 4 * self.tv.len() + 64;
        let mut rot = 0;
        'walk: for _ in 0..budget {
            let v = self.tv[t as usize];
            rot = (rot + 1) % 3;
            for d in 0..3 {
                let i = (rot + d) % 3;
                if self.orient(v[next(i)], v[prev(i)], p, pts) < 0.0 {
                    let h = self.tn[t as usize][i];
                    if h == NONE {
                        return None; // outside the bounding triangle
                    }
                    t = h / 3;
                    continue 'walk;
                }
            }
            return Some(t);
        }
        (0..self.tv.len() as u32).find(|&t| {
            self.alive[t as usize] && {
                let v = self.tv[t as usize];
                (0..3).all(|i| self.orient(v[next(i)], v[prev(i)], p, pts) >= 0.0)
            }
        })
    }

    /// Inserts vertex `pv` (coordinates `pts[pv]`). `is_subseg(a, b)` says whether an edge is a
    /// subsegment of this facet; `on_one_edge(t)` whether a triangle's corners all lie on one
    /// input edge (such a triangle is flat up to rounding and never a subface); `split_of` names
    /// the subsegment `pv` splits, if it is a split point. With `provisional`, a point that
    /// encroaches a subsegment (or whose cavity crosses one) is refused and nothing changes.
    pub fn insert(
        &mut self,
        pv: u32,
        pts: &[[f64; 3]],
        provisional: bool,
        is_subseg: &dyn Fn(u32, u32) -> bool,
        on_one_edge: &dyn Fn([u32; 3]) -> bool,
        split_of: Option<[u32; 2]>,
    ) -> Result<FacetChange, FacetInsertError> {
        if let Some([a, b]) = split_of {
            if let Some(h) = self.find_half_edge(a, b) {
                return self.split_edge(pv, h, pts, is_subseg, on_one_edge);
            }
        }
        match self.insert_with(
            pv,
            pts,
            provisional,
            is_subseg,
            on_one_edge,
            split_of,
            false,
        ) {
            // Rounded points next to rounding-flat triangles can leave no valid Delaunay
            // cavity; then insert into the smallest cavity and restore Delaunay by flips.
            Err(FacetInsertError::Lost) => {
                self.insert_with(pv, pts, provisional, is_subseg, on_one_edge, split_of, true)
            }
            r => r,
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn insert_with(
        &mut self,
        pv: u32,
        pts: &[[f64; 3]],
        provisional: bool,
        is_subseg: &dyn Fn(u32, u32) -> bool,
        on_one_edge: &dyn Fn([u32; 3]) -> bool,
        split_of: Option<[u32; 2]>,
        minimal: bool,
    ) -> Result<FacetChange, FacetInsertError> {
        let mut change = FacetChange::default();
        let p = pts[pv as usize];
        let steiner = provisional || split_of.is_some();
        let split_edge = split_of.and_then(|[a, b]| self.find_half_edge(a, b));
        let start = match split_edge {
            Some(h) => h / 3,
            None => self.locate(p, pts).ok_or(FacetInsertError::Lost)?,
        };
        for &x in &self.tv[start as usize] {
            if !is_bound(x) && pts[x as usize] == p {
                return Err(FacetInsertError::Duplicate(x));
            }
        }
        self.cur = self.cur.wrapping_add(2);
        if self.cur < 2 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.cur = 2;
        }
        let cur = self.cur;
        self.cav.clear();
        self.cav.push(start);
        self.stamp[start as usize] = cur;
        // A split point lies on its subsegment up to rounding: both sides of the edge belong to
        // its cavity, so no rounding-flat triangle (a, m, b) is ever made.
        if let Some(h) = split_edge {
            let o = self.tn[(h / 3) as usize][(h % 3) as usize];
            if o != NONE && self.stamp[(o / 3) as usize] != cur {
                self.stamp[(o / 3) as usize] = cur;
                self.cav.push(o / 3);
            }
        }
        let mut seeds: Vec<u32> = self.cav.clone();
        let mut k = 0;
        while k < self.cav.len() {
            let t = self.cav[k];
            k += 1;
            for i in 0..3 {
                let h = self.tn[t as usize][i];
                if h == NONE {
                    continue;
                }
                let n = h / 3;
                // Steiner points only reshape the inside of the facet (plus their seeds): the
                // outside is scaffolding, and its huge, rounding-sensitive triangles would only
                // make the cavity fragile.
                if !minimal
                    && self.stamp[n as usize] != cur
                    && (!steiner || self.inside[n as usize])
                    && self.conflict(n, p, pts)
                {
                    self.stamp[n as usize] = cur;
                    self.cav.push(n);
                }
            }
        }
        // The boundary must be star-shaped from p. In exact coplanar geometry the conflict
        // region is; rounded Steiner points (a hair off the plane) can break that next to
        // rounding-flat triangles, so drop offending triangles (a seed instead pulls in the
        // triangle behind the offending edge) until it holds.
        for _round in 0..(4 * self.cav.len() + 8) {
            let mut bad: Vec<u32> = Vec::new();
            let mut grow: Vec<u32> = Vec::new();
            for &t in &self.cav {
                let v = self.tv[t as usize];
                for i in 0..3 {
                    let h = self.tn[t as usize][i];
                    if h != NONE && self.stamp[(h / 3) as usize] == cur {
                        continue;
                    }
                    let o = self.orient(v[next(i)], v[prev(i)], p, pts);
                    if o <= 0.0 {
                        if seeds.contains(&t) {
                            if h == NONE {
                                return Err(FacetInsertError::Lost);
                            }
                            grow.push(h / 3);
                            continue;
                        }
                        bad.push(t);
                        break;
                    }
                }
            }
            if bad.is_empty() && grow.is_empty() {
                break;
            }
            for &n in &grow {
                if !seeds.contains(&n) {
                    seeds.push(n);
                }
            }
            // Rebuild: seeds plus what stays connected to them through kept cavity triangles.
            let old = std::mem::take(&mut self.cav);
            for &t in &old {
                self.stamp[t as usize] = cur - 1;
            }
            for &t in &seeds {
                if self.stamp[t as usize] != cur {
                    self.stamp[t as usize] = cur;
                    self.cav.push(t);
                }
            }
            let mut k = 0;
            while k < self.cav.len() {
                let t = self.cav[k];
                k += 1;
                for i in 0..3 {
                    let h = self.tn[t as usize][i];
                    if h == NONE {
                        continue;
                    }
                    let n = h / 3;
                    if self.stamp[n as usize] != cur && old.contains(&n) && !bad.contains(&n) {
                        self.stamp[n as usize] = cur;
                        self.cav.push(n);
                    }
                }
            }
        }
        let mut crossed: Vec<[u32; 2]> = Vec::new();
        self.bnd.clear();
        for &t in &self.cav {
            let v = self.tv[t as usize];
            for i in 0..3 {
                let h = self.tn[t as usize][i];
                let (x, y) = (v[next(i)], v[prev(i)]);
                let real = !is_bound(x) && !is_bound(y);
                if h != NONE && self.stamp[(h / 3) as usize] == cur {
                    if real && x < y && is_subseg(x, y) {
                        crossed.push([x, y]);
                    }
                } else {
                    if real
                        && is_subseg(x, y)
                        && self.geom.encroaches(pts[x as usize], pts[y as usize], p)
                    {
                        crossed.push([x, y]);
                    }
                    self.bnd.push(3 * t + i as u32);
                }
            }
        }
        if provisional && !crossed.is_empty() {
            return Err(FacetInsertError::Encroaches(crossed));
        }
        // The boundary must be one simple cycle (each vertex starts exactly one edge).
        let mut starts: Vec<u32> = self
            .bnd
            .iter()
            .map(|&h| self.tv[(h / 3) as usize][next((h % 3) as usize)])
            .collect();
        starts.sort_unstable();
        if starts.windows(2).any(|w| w[0] == w[1]) {
            return Err(FacetInsertError::Lost);
        }
        // Every vertex of the cavity must stay on its boundary: one inside would vanish from
        // this mesh while staying in the 3D mesh. Exact Delaunay cavities never swallow a
        // vertex; points rounded a hair off the plane, packed at 1e-8 of the model's size,
        // did (a scanned model at -pq, before sliver removal stopped short of sharp corners).
        if self.cav.iter().any(|&t| {
            self.tv[t as usize]
                .iter()
                .any(|x| starts.binary_search(x).is_err())
        }) {
            return Err(FacetInsertError::Lost);
        }
        change.encroached = crossed;
        for &t in &self.cav {
            if self.inside[t as usize] {
                change.removed.push(self.tv[t as usize]);
            }
        }
        let cav = std::mem::take(&mut self.cav);
        let bnd = std::mem::take(&mut self.bnd);
        let mut made: Vec<(u32, u32, u32)> = Vec::with_capacity(bnd.len()); // (x, y, tri)
        for &h in &bnd {
            let (t, i) = ((h / 3) as usize, (h % 3) as usize);
            let v = self.tv[t];
            let (x, y) = (v[next(i)], v[prev(i)]);
            let outer = self.tn[t][i];
            made.push((x, y, outer));
        }
        for &t in &cav {
            self.alive[t as usize] = false;
            self.free.push(t);
        }
        for m in made.iter_mut() {
            let nt = self.alloc([m.0, m.1, pv]);
            self.link(3 * nt + 2, m.2);
            m.2 = nt;
        }
        // Edge p→x of the triangle (x, y, p) is opposite y (index 1); it pairs with the edge
        // x→p of the triangle (w, x, p), opposite w (index 0).
        for &(x, _y, nt) in &made {
            if let Some(&(_, _, ot)) = made.iter().find(|m| m.1 == x) {
                self.link(3 * nt + 1, 3 * ot);
            }
        }
        for &(x, y, nt) in &made {
            let v = [x, y, pv];
            // Three points of one input edge are only rounding-flat, never a subface.
            let ins = !on_one_edge(v) && self.classify(v, pts);
            self.inside[nt as usize] = ins;
            if ins {
                change.added.push(v);
            }
            for &u in &v {
                if !is_bound(u) {
                    self.vtri.insert(u, nt);
                }
            }
            self.last = nt;
        }
        self.cav = cav;
        self.bnd = bnd;
        if minimal {
            let made_ids: Vec<u32> = made.iter().map(|m| m.2).collect();
            self.flip_around(pv, pts, &made_ids, is_subseg, on_one_edge, &mut change);
        }
        debug_assert!(self.check().is_ok(), "facet mesh: {:?}", self.check());
        Ok(change)
    }

    /// Inserts the split point `pv` of the edge of half-edge `h` by splitting that edge and its
    /// two triangles (a topological 2-to-4 split), then restores Delaunay by flips.
    ///
    /// A split point lies on its subsegment up to rounding, so the split needs no orientation
    /// test; a Bowyer–Watson cavity built from the rounded point can be non-star-shaped next to
    /// needle triangles (angles of a few hundredths of a degree). The flips below ask the exact
    /// 3D in-circle test (and convexity). In exact coplanar arithmetic both give the same mesh:
    /// the triangles flipped away are exactly those whose circumcircle holds the point.
    fn split_edge(
        &mut self,
        pv: u32,
        h: u32,
        pts: &[[f64; 3]],
        is_subseg: &dyn Fn(u32, u32) -> bool,
        on_one_edge: &dyn Fn([u32; 3]) -> bool,
    ) -> Result<FacetChange, FacetInsertError> {
        let p = pts[pv as usize];
        let (t, i) = (h / 3, (h % 3) as usize);
        let o = self.tn[t as usize][i];
        if o == NONE {
            return Err(FacetInsertError::Lost);
        }
        let (n, j) = (o / 3, (o % 3) as usize);
        let tv = self.tv[t as usize];
        let nv = self.tv[n as usize];
        let (c, x, y) = (tv[i], tv[next(i)], tv[prev(i)]);
        let d = nv[j];
        for q in [c, x, y, d] {
            if !is_bound(q) && pts[q as usize] == p {
                return Err(FacetInsertError::Duplicate(q));
            }
        }
        let mut change = FacetChange::default();
        let (in_t, in_n) = (self.inside[t as usize], self.inside[n as usize]);
        if in_t {
            change.removed.push(tv);
        }
        if in_n {
            change.removed.push(nv);
        }
        // Outer neighbours: across y-c and c-x of (c, x, y); across x-d and d-y of (d, y, x).
        let ayc = self.tn[t as usize][next(i)];
        let bcx = self.tn[t as usize][prev(i)];
        let cxd = self.tn[n as usize][next(j)];
        let ddy = self.tn[n as usize][prev(j)];
        // t1 = (c, x, p), t2 = (c, p, y), n1 = (d, y, p), n2 = (d, p, x).
        let t1 = t;
        self.tv[t1 as usize] = [c, x, pv];
        self.tn[t1 as usize] = [NONE; 3];
        let n1 = n;
        self.tv[n1 as usize] = [d, y, pv];
        self.tn[n1 as usize] = [NONE; 3];
        let t2 = self.alloc([c, pv, y]);
        let n2 = self.alloc([d, pv, x]);
        self.link(3 * t1 + 2, bcx);
        self.link(3 * t2 + 1, ayc);
        self.link(3 * n1 + 2, ddy);
        self.link(3 * n2 + 1, cxd);
        self.link(3 * t1 + 1, 3 * t2 + 2);
        self.link(3 * t1, 3 * n2);
        self.link(3 * t2, 3 * n1);
        self.link(3 * n1 + 1, 3 * n2 + 2);
        for (tt, parent_inside) in [(t1, in_t), (t2, in_t), (n1, in_n), (n2, in_n)] {
            let vv = self.tv[tt as usize];
            let ins = parent_inside && !on_one_edge(vv);
            self.inside[tt as usize] = ins;
            if ins {
                change.added.push(vv);
            }
            for &u in &vv {
                if !is_bound(u) {
                    self.vtri.insert(u, tt);
                }
            }
        }
        self.last = t1;
        self.flip_from_split(
            pv,
            p,
            pts,
            [t1, t2, n1, n2],
            is_subseg,
            on_one_edge,
            &mut change,
        );
        debug_assert!(self.check().is_ok(), "facet mesh: {:?}", self.check());
        Ok(change)
    }

    /// Lawson flips around the split point `pv` (see [`FacetMesh::split_edge`]): an edge of
    /// its link is flipped when the exact in-circle test says the opposite corner lies in the
    /// circle of `pv`'s triangle. As in the Bowyer–Watson cavity of a Steiner point, only
    /// triangles inside the facet are flipped away (the outside is scaffolding). A subsegment
    /// flipped away is reported in `change.encroached`, as are the subsegments of the final
    /// link whose diametral ball holds the point. A flip also needs the quadrilateral to be
    /// convex in projection (it is in exact coplanar arithmetic for a point in the circle and
    /// across the edge): flipping a rounding-concave one would fold the mesh over itself, and a
    /// later point located in the fold would leave a triangle it covers in place.
    #[allow(clippy::too_many_arguments)]
    fn flip_from_split(
        &mut self,
        pv: u32,
        p: [f64; 3],
        pts: &[[f64; 3]],
        created: [u32; 4],
        is_subseg: &dyn Fn(u32, u32) -> bool,
        on_one_edge: &dyn Fn([u32; 3]) -> bool,
        change: &mut FacetChange,
    ) {
        let mut fresh: Vec<u32> = created.to_vec();
        let mut stack: Vec<u32> = created.to_vec();
        let mut budget = 4 * self.tv.len() + 64;
        while let Some(t) = stack.pop() {
            if budget == 0 {
                break;
            }
            budget -= 1;
            if !self.alive[t as usize] {
                continue;
            }
            let v = self.tv[t as usize];
            let Some(k) = (0..3).find(|&k| v[k] == pv) else {
                continue;
            };
            let (x, y) = (v[next(k)], v[prev(k)]);
            let h = self.tn[t as usize][k];
            if h == NONE || is_bound(x) || is_bound(y) {
                continue;
            }
            let (n, j) = (h / 3, (h % 3) as usize);
            if !self.inside[n as usize] || !self.inside[t as usize] {
                continue;
            }
            let q = self.tv[n as usize][j];
            if is_bound(q) || q == pv {
                continue;
            }
            if !self.conflict(n, p, pts) {
                continue;
            }
            if self.orient(x, q, p, pts) <= 0.0 || self.orient(q, y, p, pts) <= 0.0 {
                continue;
            }
            if is_subseg(x, y) {
                let s = if x < y { [x, y] } else { [y, x] };
                if !change.encroached.contains(&s) {
                    change.encroached.push(s);
                }
            }
            if !fresh.contains(&n) {
                // `n` was an old inside triangle: it is gone.
                change.removed.push([q, y, x]);
                fresh.push(n);
            }
            self.flip_edge(t, k);
            for tt in [t, n] {
                // Both triangles were inside, so their union is: no outline test needed.
                self.inside[tt as usize] = !on_one_edge(self.tv[tt as usize]);
                stack.push(tt);
            }
        }
        change.added.clear();
        for &t in &fresh {
            if !(self.alive[t as usize] && self.inside[t as usize]) {
                continue;
            }
            let v = self.tv[t as usize];
            change.added.push(v);
            let k = (0..3)
                .position(|k| v[k] == pv)
                .expect("fresh triangles hold the point");
            let (x, y) = (v[next(k)], v[prev(k)]);
            if !is_bound(x)
                && !is_bound(y)
                && is_subseg(x, y)
                && self.geom.encroaches(pts[x as usize], pts[y as usize], p)
            {
                let s = if x < y { [x, y] } else { [y, x] };
                if !change.encroached.contains(&s) {
                    change.encroached.push(s);
                }
            }
        }
    }

    /// Flips the edge opposite corner `k` of triangle `t`: `t = (c, x, y)` and its neighbour
    /// `(q, y, x)` become `(c, x, q)` (in `t`) and `(c, q, y)` (in the neighbour), relinked,
    /// with the star pointers of their corners updated. The caller sets `inside`.
    fn flip_edge(&mut self, t: u32, k: usize) {
        let v = self.tv[t as usize];
        let (c, x, y) = (v[k], v[next(k)], v[prev(k)]);
        let h = self.tn[t as usize][k];
        let (n, j) = (h / 3, (h % 3) as usize);
        let q = self.tv[n as usize][j];
        let a_ = self.tn[t as usize][next(k)];
        let b_ = self.tn[t as usize][prev(k)];
        let c_ = self.tn[n as usize][next(j)];
        let d_ = self.tn[n as usize][prev(j)];
        self.tv[t as usize] = [c, x, q];
        self.tv[n as usize] = [c, q, y];
        self.link(3 * t, c_);
        self.link(3 * t + 2, b_);
        self.link(3 * n, d_);
        self.link(3 * n + 1, a_);
        self.link(3 * t + 1, 3 * n + 2);
        for tt in [t, n] {
            for u in self.tv[tt as usize] {
                if !is_bound(u) {
                    self.vtri.insert(u, tt);
                }
            }
        }
    }

    /// Lawson flips around the new vertex `pv` until its link is locally Delaunay (never
    /// flipping a subsegment, and only convex quadrilaterals, so the mesh stays valid whatever
    /// rounding does). `created` are the triangles just made; `change` is updated.
    fn flip_around(
        &mut self,
        pv: u32,
        pts: &[[f64; 3]],
        created: &[u32],
        is_subseg: &dyn Fn(u32, u32) -> bool,
        on_one_edge: &dyn Fn([u32; 3]) -> bool,
        change: &mut FacetChange,
    ) {
        let mut fresh: Vec<u32> = created.to_vec();
        let mut stack: Vec<u32> = created.to_vec();
        let p = pts[pv as usize];
        let mut budget = 100_000;
        while let Some(t) = stack.pop() {
            budget -= 1;
            if budget == 0 {
                break;
            }
            if !self.alive[t as usize] {
                continue;
            }
            let v = self.tv[t as usize];
            let Some(k) = (0..3).find(|&k| v[k] == pv) else {
                continue;
            };
            let (x, y) = (v[next(k)], v[prev(k)]);
            let h = self.tn[t as usize][k];
            if h == NONE || (!is_bound(x) && !is_bound(y) && is_subseg(x, y)) {
                continue;
            }
            let (n, j) = (h / 3, (h % 3) as usize);
            let q = self.tv[n as usize][j];
            if !self.conflict(n, p, pts) {
                continue;
            }
            if self.orient(x, q, p, pts) <= 0.0 || self.orient(q, y, p, pts) <= 0.0 {
                continue;
            }
            for tt in [t, n] {
                if self.inside[tt as usize] && !fresh.contains(&tt) {
                    change.removed.push(self.tv[tt as usize]);
                }
            }
            self.flip_edge(t, k);
            for tt in [t, n] {
                let vv = self.tv[tt as usize];
                self.inside[tt as usize] = !on_one_edge(vv) && self.classify(vv, pts);
                if !fresh.contains(&tt) {
                    fresh.push(tt);
                }
                stack.push(tt);
            }
        }
        change.added.retain(|_| false);
        for &t in &fresh {
            if self.alive[t as usize] && self.inside[t as usize] {
                change.added.push(self.tv[t as usize]);
            }
        }
    }

    /// Structural check (adjacency symmetric and consistent).
    pub fn check(&self) -> Result<(), String> {
        for t in 0..self.tv.len() {
            if !self.alive[t] {
                continue;
            }
            for i in 0..3 {
                let h = self.tn[t][i];
                let v = self.tv[t];
                if h == NONE {
                    if !(is_bound(v[next(i)]) && is_bound(v[prev(i)])) {
                        return Err(format!("triangle {t} {v:?} edge {i} unlinked"));
                    }
                    continue;
                }
                let (n, j) = ((h / 3) as usize, (h % 3) as usize);
                if !self.alive[n] || self.tn[n][j] != (3 * t + i) as u32 {
                    return Err(format!("triangle {t} edge {i}: asymmetric link"));
                }
                let w = self.tv[n];
                if v[next(i)] != w[prev(j)] || v[prev(i)] != w[next(j)] {
                    return Err(format!("triangle {t} {v:?} edge {i} vs {n} {w:?} edge {j}"));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::predicates::incircle3d;

    fn build(pts: &[[f64; 3]], convex: bool) -> FacetMesh {
        let mut fm = FacetMesh::new(
            2,
            Outline {
                loops: vec![],
                convex,
            },
        );
        let no = |_: u32, _: u32| false;
        let flat = |_: [u32; 3]| false;
        for v in 0..pts.len() as u32 {
            fm.insert(v, pts, false, &no, &flat, None).unwrap();
            fm.check().unwrap();
        }
        fm
    }

    #[test]
    fn circumcentre_beyond_a_subsegment_is_refused() {
        // An obtuse facet triangle: its circumcentre (5, -12) lies outside the facet, beyond
        // the subsegment 0-1, which it encroaches; a point inside is reached.
        let mut pts = vec![[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [5.0, 1.0, 0.0]];
        let mut fm = build(&pts, true);
        let sub = |a: u32, b: u32| a != b && a < 3 && b < 3;
        let cc = crate::geometry::tri_circumcenter3(pts[0], pts[1], pts[2]).unwrap();
        assert_eq!(cc[1], -12.0);
        assert_eq!(
            fm.check_reach([0, 1, 2], cc, &pts, &sub),
            Err(FacetInsertError::Encroaches(vec![[0, 1]]))
        );
        assert_eq!(
            fm.check_reach([2, 0, 1], [5.0, 0.5, 0.0], &pts, &sub),
            Ok(())
        );
        // Not a triangle of the mesh: left to `insert`.
        pts.push([5.0, 0.2, 0.0]);
        assert_eq!(fm.check_reach([0, 1, 3], cc, &pts, &sub), Ok(()));
    }

    #[test]
    fn points_in_general_position() {
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
            [-1.0, 0.5, 0.0],
            [0.5, -1.0, 0.0],
        ];
        let fm = build(&pts, true);
        // Euler: 2n - 2 - h triangles for n points with h on the hull (here 5: (0, 1) lies on
        // the hull edge from (2, 2) to (-1, 0.5)).
        assert_eq!(fm.inside_triangles().len(), 2 * 6 - 2 - 5);
    }

    #[test]
    fn grid_points_cocircular() {
        let mut pts = Vec::new();
        for i in 0..7 {
            for j in 0..7 {
                pts.push([i as f64, j as f64, 0.0]);
            }
        }
        let fm = build(&pts, true);
        // 49 points, 24 on the hull: 2n - 2 - h triangles.
        assert_eq!(fm.inside_triangles().len(), 2 * 49 - 2 - 24);
        assert!(fm.has_edge(0, 1));
        assert!(!fm.has_edge(0, 48));
    }

    #[test]
    fn collinear_first_points() {
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, -1.0, 0.0],
        ];
        let fm = build(&pts, true);
        assert!(fm.started());
        assert_eq!(fm.inside_triangles().len(), 4);
    }

    #[test]
    fn tilted_plane_matches_the_true_circles() {
        // Points on the plane z = x + 2y (integer lattice): the facet mesh must be Delaunay for
        // the true (3D) circles, not for the projected ellipses.
        let mut pts = Vec::new();
        let mut s = 12345u64;
        for _ in 0..60 {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let x = ((s >> 33) % 40) as f64;
            let y = ((s >> 45) % 40) as f64;
            let p = [x, y, x + 2.0 * y];
            if !pts.contains(&p) {
                pts.push(p);
            }
        }
        let fm = build(&pts, true);
        assert!(fm.inside_triangles().len() >= pts.len());
        for t in fm.inside_triangles() {
            let [a, b, c] = t.map(|v| pts[v as usize]);
            for (i, &q) in pts.iter().enumerate() {
                if !t.contains(&(i as u32)) {
                    assert!(
                        incircle3d(a, b, c, q) <= 0.0,
                        "triangle {t:?} has point {i} inside"
                    );
                }
            }
        }
    }

    #[test]
    fn sliver_of_a_reflex_boundary_vertex_is_outside() {
        // Three boundary vertices of a CAD fan-disk model (projected on x = -0.207) are nearly
        // collinear and 6268 is reflex: the sliver between them lies outside the facet, but
        // its rounded centroid falls inside for some vertex orders (then it was taken for a
        // subface that no split could put into the 3D mesh: "too small to split").
        let (a, b, c) = ([0.15655, 0.296], [0.17635, 0.2954], [0.19615, 0.2948]);
        // The loop runs a -> b -> c and closes on the side b bulges towards (b reflex).
        let loops = vec![vec![a, b, c, [0.17635, 0.5]]];
        let outline = Outline {
            loops,
            convex: false,
        };
        let orders = [
            [a, b, c],
            [a, c, b],
            [b, a, c],
            [b, c, a],
            [c, a, b],
            [c, b, a],
        ];
        let mut rounded_inside = 0;
        for t in orders {
            assert!(!outline.contains_centroid(t), "{t:?} taken for inside");
            let q = [0, 1].map(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0);
            rounded_inside += outline.contains(q) as usize;
        }
        assert!(rounded_inside > 0, "the rounded centroids are all outside");
        // A fat triangle inside is inside (the fast path).
        assert!(outline.contains_centroid([[0.16, 0.33], [0.18, 0.33], [0.17, 0.36]]));
    }
}
