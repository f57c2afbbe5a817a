//! The 2D Delaunay mesh of one input facet (paper §4.2): Bowyer–Watson in the facet's plane.
//!
//! Vertices are global vertex ids (shared with the 3D mesh), so one global insertion order
//! breaks cocircular ties the same way here and in the 3D mesh (paper Lemma 4.7).
//!
//! Decisions stay exact on the 3D coordinates: orientation is `orient2d` of the projection that
//! drops the facet's dominant normal axis (an affine projection: exact, sign-preserving), and
//! the in-circle test is the 3D one ([`crate::predicates::incircle3d`]): any sphere through a
//! triangle's corners cuts the plane in its circumcircle, so the facet mesh and the 3D mesh see
//! the same circles for coplanar points (paper §6: no rounded map into the plane).

use std::collections::HashMap;

use crate::predicates::{incircle3d, orient2d};

/// The ghost vertex: ghost triangles `(x, y, GHOST)` sit outside hull edges `x → y`.
pub(crate) const GHOST: u32 = u32::MAX - 1;
const NONE: u32 = u32::MAX;

#[inline]
fn next(i: usize) -> usize {
    if i == 2 {
        0
    } else {
        i + 1
    }
}
#[inline]
fn prev(i: usize) -> usize {
    if i == 0 {
        2
    } else {
        i - 1
    }
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
    fn contains(&self, q: [f64; 2]) -> bool {
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
}

/// One facet's Delaunay triangulation.
pub(crate) struct FacetMesh {
    /// The coordinate dropped by the projection.
    pub axis: usize,
    tv: Vec<[u32; 3]>,
    /// `tn[t][i]`: half-edge `3t' + i'` across the edge opposite vertex `i`.
    tn: Vec<[u32; 3]>,
    alive: Vec<bool>,
    inside: Vec<bool>,
    free: Vec<u32>,
    vtri: HashMap<u32, u32>,
    outline: Outline,
    /// Points waiting for three non-collinear points to start the triangulation.
    pending: Vec<u32>,
    started: bool,
    stamp: Vec<u32>,
    cur: u32,
    cav: Vec<u32>,
    bnd: Vec<u32>,
    last: u32,
}

impl FacetMesh {
    /// An empty facet mesh projecting along `axis`.
    pub fn new(axis: usize, outline: Outline) -> FacetMesh {
        FacetMesh {
            axis,
            tv: Vec::new(),
            tn: Vec::new(),
            alive: Vec::new(),
            inside: Vec::new(),
            free: Vec::new(),
            vtri: HashMap::new(),
            outline,
            pending: Vec::new(),
            started: false,
            stamp: Vec::new(),
            cur: 0,
            cav: Vec::new(),
            bnd: Vec::new(),
            last: NONE,
        }
    }

    #[inline]
    fn proj(&self, p: [f64; 3]) -> [f64; 2] {
        match self.axis {
            0 => [p[1], p[2]],
            1 => [p[2], p[0]],
            _ => [p[0], p[1]],
        }
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
        self.tn[(h1 / 3) as usize][(h1 % 3) as usize] = h2;
        self.tn[(h2 / 3) as usize][(h2 % 3) as usize] = h1;
    }

    fn is_ghost(&self, t: u32) -> bool {
        self.tv[t as usize].contains(&GHOST)
    }

    /// Whether the facet mesh has a triangle yet.
    pub fn started(&self) -> bool {
        self.started
    }

    /// Every live triangle inside the facet, as vertex triples.
    pub fn inside_triangles(&self) -> Vec<[u32; 3]> {
        (0..self.tv.len())
            .filter(|&t| self.alive[t] && self.inside[t])
            .map(|t| self.tv[t])
            .collect()
    }

    /// Whether `v` is a vertex of the mesh.
    pub fn has_vertex(&self, v: u32) -> bool {
        self.vtri.contains_key(&v) || self.pending.contains(&v)
    }

    /// Whether `a b` is an edge of the mesh.
    pub fn has_edge(&self, a: u32, b: u32) -> bool {
        let Some(&t0) = self.vtri.get(&a) else {
            return false;
        };
        // Walk around a in both directions (the star may be cut by nothing: ghosts close it).
        let mut t = t0;
        for _ in 0..100_000 {
            let v = self.tv[t as usize];
            if v.contains(&b) {
                return true;
            }
            let i = (0..3).find(|&i| v[i] == a).unwrap_or(0);
            // Rotate to the triangle across the edge a → v[next(i)] (opposite v[prev(i)]).
            let h = self.tn[t as usize][prev(i)];
            if h == NONE {
                return false;
            }
            t = h / 3;
            if t == t0 {
                return false;
            }
        }
        false
    }

    /// A half-edge `3t + i` whose edge joins `a` and `b` (either direction).
    fn find_half_edge(&self, a: u32, b: u32) -> Option<u32> {
        let &t0 = self.vtri.get(&a)?;
        let mut t = t0;
        for _ in 0..100_000 {
            let v = self.tv[t as usize];
            if let Some(j) = (0..3).find(|&j| v[j] == b) {
                let i = (0..3).find(|&i| v[i] == a)?;
                // The edge ab is opposite the third corner.
                return Some(3 * t + (3 - i - j) as u32);
            }
            let i = (0..3).find(|&i| v[i] == a)?;
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

    /// The triangles (vertex triples, inside the facet) incident to `v`.
    pub fn inside_star(&self, v: u32, out: &mut Vec<[u32; 3]>) {
        out.clear();
        let Some(&t0) = self.vtri.get(&v) else {
            return;
        };
        let mut t = t0;
        for _ in 0..100_000 {
            if self.inside[t as usize] {
                out.push(self.tv[t as usize]);
            }
            let vv = self.tv[t as usize];
            let i = (0..3).find(|&i| vv[i] == v).unwrap_or(0);
            let h = self.tn[t as usize][prev(i)];
            if h == NONE {
                return;
            }
            t = h / 3;
            if t == t0 {
                return;
            }
        }
    }

    fn conflict(&self, t: u32, p: [f64; 3], pts: &[[f64; 3]]) -> bool {
        let v = self.tv[t as usize];
        if let Some(k) = (0..3).find(|&k| v[k] == GHOST) {
            let a = pts[v[next(k)] as usize];
            let b = pts[v[prev(k)] as usize];
            let (a2, b2, p2) = (self.proj(a), self.proj(b), self.proj(p));
            let o = orient2d(a2, b2, p2);
            o > 0.0 || (o == 0.0 && strictly_between(a2, b2, p2))
        } else {
            incircle3d(pts[v[0] as usize], pts[v[1] as usize], pts[v[2] as usize], p) > 0.0
        }
    }

    /// Classifies a new finite triangle: inside the facet polygon or not.
    fn classify(&self, v: [u32; 3], pts: &[[f64; 3]]) -> bool {
        if self.outline.convex {
            return true;
        }
        let [a, b, c] = v.map(|x| self.proj(pts[x as usize]));
        let q = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
        self.outline.contains(q)
    }

    fn start(&mut self, a: u32, b: u32, c: u32, pts: &[[f64; 3]]) {
        let (pa, pb, pc) = (
            self.proj(pts[a as usize]),
            self.proj(pts[b as usize]),
            self.proj(pts[c as usize]),
        );
        let (b, c) = if orient2d(pa, pb, pc) > 0.0 {
            (b, c)
        } else {
            (c, b)
        };
        let t = self.alloc([a, b, c]);
        self.inside[t as usize] = self.classify([a, b, c], pts);
        // Ghosts outside each edge: edge opposite i runs v[next(i)] → v[prev(i)].
        let v = [a, b, c];
        let mut g = [0u32; 3];
        for i in 0..3 {
            g[i] = self.alloc([v[prev(i)], v[next(i)], GHOST]);
            self.link(3 * t + i as u32, 3 * g[i] + 2);
        }
        // Ghost i = (y, x, G); its edge opposite y (index 0) is x → G, opposite x is G → y.
        for i in 0..3 {
            // ghost i's edge x→G where x = v[next(i)] pairs with the ghost whose edge is G→x.
            let j = next(i); // ghost j = (v[prev(j)], v[next(j)], G) = (v[i], v[next(j)], G)
            // ghost i = (v[prev(i)], v[next(i)], G); its vertex 0 is v[prev(i)]; edge opposite
            // index 0 runs v[next(i)] → G. Ghost k with v[prev(k)] = v[next(i)] has edge
            // opposite index 1 running G → v[prev(k)]; k = next(next(i)) = prev(i).
            let _ = j;
            let k = prev(i);
            self.link(3 * g[i], 3 * g[k] + 1);
        }
        for x in [a, b, c] {
            self.vtri.insert(x, t);
        }
        self.last = t;
        self.started = true;
    }

    fn locate(&self, p: [f64; 3], pts: &[[f64; 3]]) -> Option<u32> {
        let p2 = self.proj(p);
        let mut t = self.last;
        if t == NONE || !self.alive[t as usize] {
            t = (0..self.tv.len() as u32).find(|&t| self.alive[t as usize])?;
        }
        if self.is_ghost(t) {
            let k = (0..3).find(|&k| self.tv[t as usize][k] == GHOST)?;
            t = self.tn[t as usize][k] / 3;
        }
        let budget = 4 * self.tv.len() + 64;
        let mut rot = 0;
        'walk: for _ in 0..budget {
            if self.is_ghost(t) {
                return Some(t);
            }
            let v = self.tv[t as usize];
            rot = (rot + 1) % 3;
            for d in 0..3 {
                let i = (rot + d) % 3;
                let a = self.proj(pts[v[next(i)] as usize]);
                let b = self.proj(pts[v[prev(i)] as usize]);
                if orient2d(a, b, p2) < 0.0 {
                    t = self.tn[t as usize][i] / 3;
                    continue 'walk;
                }
            }
            return Some(t);
        }
        // Budget exhausted (should not happen): scan.
        (0..self.tv.len() as u32).find(|&t| {
            if !self.alive[t as usize] {
                return false;
            }
            if self.is_ghost(t) {
                return self.conflict(t, p, pts);
            }
            let v = self.tv[t as usize].map(|x| self.proj(pts[x as usize]));
            (0..3).all(|i| orient2d(v[next(i)], v[prev(i)], p2) >= 0.0)
        })
    }

    /// Inserts vertex `pv` (coordinates `pts[pv]`). `is_subseg(a, b)` says whether an edge is a
    /// subsegment of this facet; `on_one_edge(t)` whether a triangle's corners all lie on one
    /// input edge (such a triangle is flat up to rounding and never a subface). With `provisional`, a point that encroaches a subsegment (or
    /// whose cavity crosses one) is refused and nothing changes.
    pub fn insert(
        &mut self,
        pv: u32,
        pts: &[[f64; 3]],
        provisional: bool,
        is_subseg: &dyn Fn(u32, u32) -> bool,
        on_one_edge: &dyn Fn([u32; 3]) -> bool,
        split_of: Option<[u32; 2]>,
    ) -> Result<FacetChange, FacetInsertError> {
        let mut change = FacetChange::default();
        if !self.started {
            self.pending.push(pv);
            // Start as soon as three points are not collinear (in rank order of arrival).
            let n = self.pending.len();
            if n >= 3 {
                let a = self.pending[0];
                let pa = self.proj(pts[a as usize]);
                let mut pair = None;
                'find: for i in 1..n {
                    for j in i + 1..n {
                        let (b, c) = (self.pending[i], self.pending[j]);
                        if orient2d(pa, self.proj(pts[b as usize]), self.proj(pts[c as usize]))
                            != 0.0
                        {
                            pair = Some((b, c));
                            break 'find;
                        }
                    }
                }
                if let Some((b, c)) = pair {
                    let rest: Vec<u32> = self
                        .pending
                        .iter()
                        .copied()
                        .filter(|&x| x != a && x != b && x != c)
                        .collect();
                    self.pending.clear();
                    self.start(a, b, c, pts);
                    change.added.extend(self.inside_of_all());
                    for x in rest {
                        let c2 = self.insert(x, pts, false, is_subseg, on_one_edge, None)?;
                        change.removed.extend(c2.removed);
                        change.added.extend(c2.added);
                        change.encroached.extend(c2.encroached);
                    }
                }
            }
            return Ok(change);
        }
        let p = pts[pv as usize];
        let split_edge = split_of.and_then(|[a, b]| self.find_half_edge(a, b));
        let start = match split_edge {
            Some(h) => h / 3,
            None => self.locate(p, pts).ok_or(FacetInsertError::Lost)?,
        };
        // Duplicate?
        for &x in &self.tv[start as usize] {
            if x != GHOST && pts[x as usize] == p {
                return Err(FacetInsertError::Duplicate(x));
            }
        }
        self.cur = self.cur.wrapping_add(1);
        if self.cur == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.cur = 1;
        }
        let cur = self.cur;
        self.cav.clear();
        self.bnd.clear();
        self.cav.push(start);
        self.stamp[start as usize] = cur;
        // A split point lies on its subsegment up to rounding: both sides of the edge belong to
        // its cavity, so no rounding-flat triangle (a, m, b) is ever made.
        if let Some(h) = split_edge {
            for t in [h / 3, self.tn[(h / 3) as usize][(h % 3) as usize] / 3] {
                if self.stamp[t as usize] != cur {
                    self.stamp[t as usize] = cur;
                    self.cav.push(t);
                }
            }
        }
        let mut seeds: Vec<u32> = self.cav.clone();
        let mut k = 0;
        let mut crossed: Vec<[u32; 2]> = Vec::new();
        while k < self.cav.len() {
            let t = self.cav[k];
            k += 1;
            for i in 0..3 {
                let h = self.tn[t as usize][i];
                let n = h / 3;
                if self.stamp[n as usize] == cur {
                    continue;
                }
                if self.conflict(n, p, pts) {
                    let v = self.tv[t as usize];
                    let (x, y) = (v[next(i)], v[prev(i)]);
                    if x != GHOST && y != GHOST && is_subseg(x, y) {
                        crossed.push([x, y]);
                    }
                    self.stamp[n as usize] = cur;
                    self.cav.push(n);
                }
            }
        }
        // Boundary, made star-shaped from p. In exact coplanar geometry the conflict region is
        // star-shaped already; rounded Steiner points (a hair off the plane) can break that near
        // rounding-flat triangles, so drop offending triangles (never a seed) until it holds.
        for _round in 0..(4 * self.cav.len() + 8) {
            let mut bad: Vec<u32> = Vec::new();
            let mut grow: Vec<u32> = Vec::new();
            for &t in self.cav.iter() {
                let v = self.tv[t as usize];
                for i in 0..3 {
                    let h = self.tn[t as usize][i];
                    if self.stamp[(h / 3) as usize] == cur {
                        continue;
                    }
                    let (x, y) = (v[next(i)], v[prev(i)]);
                    if x != GHOST && y != GHOST {
                        let o = orient2d(
                            self.proj(pts[x as usize]),
                            self.proj(pts[y as usize]),
                            self.proj(p),
                        );
                        if o <= 0.0 {
                            if seeds.contains(&t) {
                                // A seed must stay: take the triangle behind the edge too.
                                let n = h / 3;
                                if !seeds.contains(&n) {
                                    grow.push(n);
                                }
                                continue;
                            }
                            bad.push(t);
                            break;
                        }
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
                if self.stamp[n as usize] != cur {
                    self.stamp[n as usize] = cur;
                    self.cav.push(n);
                }
            }
            if bad.is_empty() {
                continue;
            }
            for &t in &bad {
                self.stamp[t as usize] = cur.wrapping_sub(1);
            }
            // Keep what is still connected to the seeds.
            let old = std::mem::take(&mut self.cav);
            for &t in &old {
                if self.stamp[t as usize] == cur {
                    self.stamp[t as usize] = cur.wrapping_sub(1);
                }
            }
            for &t in &seeds {
                self.stamp[t as usize] = cur;
                self.cav.push(t);
            }
            let mut k = 0;
            while k < self.cav.len() {
                let t = self.cav[k];
                k += 1;
                for i in 0..3 {
                    let n = self.tn[t as usize][i] / 3;
                    if self.stamp[n as usize] != cur
                        && (old.contains(&n) || seeds.contains(&n))
                        && !bad.contains(&n)
                    {
                        self.stamp[n as usize] = cur;
                        self.cav.push(n);
                    }
                }
            }
        }
        self.bnd.clear();
        crossed.clear();
        for &t in &self.cav {
            let v = self.tv[t as usize];
            for i in 0..3 {
                let h = self.tn[t as usize][i];
                let (x, y) = (v[next(i)], v[prev(i)]);
                if self.stamp[(h / 3) as usize] == cur {
                    if x != GHOST && y != GHOST && x < y && is_subseg(x, y) {
                        crossed.push([x, y]);
                    }
                } else {
                    self.bnd.push(3 * t + i as u32);
                }
            }
        }
        for &h in &self.bnd {
            let (t, i) = ((h / 3) as usize, (h % 3) as usize);
            let v = self.tv[t];
            let (x, y) = (v[next(i)], v[prev(i)]);
            if x != GHOST
                && y != GHOST
                && is_subseg(x, y)
                && crate::predicates::in_diametral_ball_seg3(pts[x as usize], pts[y as usize], p)
            {
                crossed.push([x, y]);
            }
        }
        if provisional && !crossed.is_empty() {
            return Err(FacetInsertError::Encroaches(crossed));
        }
        change.encroached = crossed;
        #[cfg(debug_assertions)]
        let dbg_before: Vec<(u32, [u32; 3], [u32; 3])> = (0..self.tv.len())
            .filter(|&t| self.alive[t])
            .map(|t| (t as u32, self.tv[t], self.tn[t]))
            .collect();
        #[cfg(debug_assertions)]
        let dbg_cav = (self.cav.clone(), self.bnd.clone());
        // Commit.
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
            let nt = self.alloc([x, y, pv]);
            self.link(3 * nt + 2, outer);
            made.push((x, y, nt));
        }
        for &t in &cav {
            self.alive[t as usize] = false;
            self.free.push(t);
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
            if !v.contains(&GHOST) {
                // Three points of one input edge are only rounding-flat, never a subface.
                let ins = !on_one_edge(v) && self.classify(v, pts);
                self.inside[nt as usize] = ins;
                if ins {
                    change.added.push(v);
                }
            }
            for &u in &v {
                if u != GHOST {
                    self.vtri.insert(u, nt);
                }
            }
            self.last = nt;
        }
        self.cav = cav;
        self.bnd = bnd;
        #[cfg(debug_assertions)]
        if let Err(e) = self.check() {
            eprintln!("insert {pv} at {:?} (proj {:?})", p, self.proj(p));
            for (t, v, n) in &dbg_before {
                let pr: Vec<[f64; 2]> = v.iter().map(|&x| if x == GHOST { [f64::NAN; 2] } else { self.proj(pts[x as usize]) }).collect();
                eprintln!("  tri {t} {v:?} nb {n:?} {pr:?}");
            }
            eprintln!("  cavity {:?} boundary {:?} split_of {split_of:?}", dbg_cav.0, dbg_cav.1);
            for &t in &dbg_cav.0 {
                eprintln!("   cav {t} conflict {}", self.conflict(t, p, pts));
            }
            panic!("facet mesh: {e}");
        }
        Ok(change)
    }

    /// Structural check (adjacency symmetric and consistent, no dangling half-edge).
    pub fn check(&self) -> Result<(), String> {
        for t in 0..self.tv.len() {
            if !self.alive[t] {
                continue;
            }
            for i in 0..3 {
                let h = self.tn[t][i];
                if h == NONE {
                    return Err(format!("triangle {t} {:?} edge {i} unlinked", self.tv[t]));
                }
                let (n, j) = ((h / 3) as usize, (h % 3) as usize);
                if !self.alive[n] || self.tn[n][j] != (3 * t + i) as u32 {
                    return Err(format!("triangle {t} edge {i}: asymmetric link"));
                }
                let v = self.tv[t];
                let w = self.tv[n];
                if v[next(i)] != w[prev(j)] || v[prev(i)] != w[next(j)] {
                    return Err(format!("triangle {t} {v:?} edge {i} vs {n} {w:?} edge {j}"));
                }
            }
        }
        Ok(())
    }

    fn inside_of_all(&self) -> Vec<[u32; 3]> {
        self.inside_triangles()
    }
}

/// For `p` collinear with `a` and `b` (projected): strictly between them.
fn strictly_between(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    crate::predicates::strictly_between(a, b, p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn build(pts: &[[f64; 3]], convex: bool) -> (FacetMesh, usize) {
        let mut fm = FacetMesh::new(
            2,
            Outline {
                loops: vec![],
                convex,
            },
        );
        let no = |_: u32, _: u32| false;
        let flat = |_: [u32; 3]| false;
        let mut added = 0;
        for v in 0..pts.len() as u32 {
            let ch = fm.insert(v, pts, false, &no, &flat, None).unwrap();
            added += ch.added.len();
            fm.check().unwrap();
        }
        (fm, added)
    }

    #[test]
    fn start_and_grow_outside_the_hull() {
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
            [-1.0, 0.5, 0.0],
            [0.5, -1.0, 0.0],
        ];
        let (fm, added) = build(&pts, true);
        assert!(added >= fm.inside_triangles().len());
        // 6 points, hull of 4 vertices ([2,2], [-1,.5], [.5,-1] and [0,1]? ) : Euler says
        // triangles = 2n - 2 - h.
        let tris = fm.inside_triangles().len();
        assert!(tris == 2 * 6 - 2 - 4 || tris == 2 * 6 - 2 - 5, "{tris}");
    }

    #[test]
    fn grid_points_cocircular() {
        let mut pts = Vec::new();
        for i in 0..7 {
            for j in 0..7 {
                pts.push([i as f64, j as f64, 0.0]);
            }
        }
        let (fm, _) = build(&pts, true);
        // 49 points, 24 on the hull: 2n - 2 - h triangles.
        assert_eq!(fm.inside_triangles().len(), 2 * 49 - 2 - 24);
        assert!(fm.has_edge(0, 1));
        assert!(!fm.has_edge(0, 48));
    }

    #[test]
    fn collinear_start_waits() {
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, -1.0, 0.0],
        ];
        let (fm, _) = build(&pts, true);
        assert!(fm.started());
        assert_eq!(fm.inside_triangles().len(), 4);
    }
}
