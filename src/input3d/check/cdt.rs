//! A constrained triangulation of one facet's projected vertices, without Steiner points, and
//! the classification of its triangles into the facet's region, its holes and the outside.
//!
//! The facet checks need the facet as a set of triangles on its own vertices, whatever its
//! loops look like (holes, nested loops, loops sharing edges, dangling edges). So: a sweep
//! triangulation of the points (sorted, each point joined to the hull edges it sees, then
//! made Delaunay by flips), each polygon edge recovered by flipping the edges that cross it
//! (Sloan's method), and a flood from the outside and from the hole seeds that stops at
//! polygon edges, as TetGen defines a facet's region. Every decision is an exact `orient2d`
//! or `incircle`; Delaunay flips only keep the walks short.

use std::collections::{HashMap, VecDeque};

use crate::predicates::{incircle, orient2d};

const NONE: u32 = u32::MAX;

/// Triangle labels after [`Cdt::classify`].
const UNKNOWN: u8 = 0;
const OUTSIDE: u8 = 1;
const HOLE: u8 = 2;
const REGION: u8 = 3;

/// Why a facet could not be triangulated.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum CdtError {
    /// Two constraint edges cross; the tags they were inserted with.
    Crossing(u32, u32),
    /// A loop ran out of its iteration budget (a bug; never expected).
    Budget(&'static str),
}

/// The triangulation and its scratch buffers, reused from facet to facet.
#[derive(Default)]
pub(super) struct Cdt {
    pts: Vec<[f64; 2]>,
    /// Triangles, counter-clockwise.
    tri: Vec<[u32; 3]>,
    /// `nbr[t][i]`: the triangle across the edge opposite `tri[t][i]`, or `NONE`.
    nbr: Vec<[u32; 3]>,
    /// One triangle incident to each vertex (`NONE` before it is inserted).
    vtri: Vec<u32>,
    /// The counter-clockwise hull during the sweep, and the triangle on each hull edge
    /// `v -> hnext[v]`.
    hnext: Vec<u32>,
    hprev: Vec<u32>,
    htri: Vec<u32>,
    /// Recovered constraint edges (undirected key) and the tag each was inserted with.
    constraints: HashMap<u64, u32>,
    label: Vec<u8>,
    order: Vec<u32>,
    around: Vec<u32>,
    stack: Vec<(u32, u32)>,
    queue: VecDeque<(u32, u32)>,
}

#[inline]
fn key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    ((lo as u64) << 32) | hi as u64
}

#[inline]
fn opposite(x: f64, y: f64) -> bool {
    (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0)
}

impl Cdt {
    /// Triangulates `pts` (distinct points). Collinear input gives no triangles.
    pub fn triangulate(&mut self, pts: &[[f64; 2]]) -> Result<(), CdtError> {
        let n = pts.len();
        self.pts.clear();
        self.pts.extend_from_slice(pts);
        self.tri.clear();
        self.nbr.clear();
        self.constraints.clear();
        self.label.clear();
        for v in [
            &mut self.vtri,
            &mut self.hnext,
            &mut self.hprev,
            &mut self.htri,
        ] {
            v.clear();
            v.resize(n, NONE);
        }
        self.order.clear();
        self.order.extend(0..n as u32);
        let p = &self.pts;
        // Numeric order (not `total_cmp`, which would put -0.0 before 0.0): the sweep needs
        // each new point to be lexicographically beyond the hull of the earlier ones.
        let cmp = |x: f64, y: f64| x.partial_cmp(&y).unwrap_or(std::cmp::Ordering::Equal);
        self.order.sort_unstable_by(|&i, &j| {
            let (a, b) = (p[i as usize], p[j as usize]);
            cmp(a[0], b[0]).then(cmp(a[1], b[1]))
        });
        if n < 3 {
            return Ok(());
        }
        let (s0, s1) = (self.order[0], self.order[1]);
        let Some(k) = (2..n).find(|&k| self.orient(s0, s1, self.order[k]) != 0.0) else {
            return Ok(());
        };
        self.fan(k);
        for i in k + 1..n {
            self.add_beyond_hull(self.order[i], self.order[i - 1])?;
        }
        Ok(())
    }

    #[inline]
    fn orient(&self, a: u32, b: u32, c: u32) -> f64 {
        orient2d(
            self.pts[a as usize],
            self.pts[b as usize],
            self.pts[c as usize],
        )
    }

    /// The first triangles: points `order[..k]` lie on a line (sorted along it) and
    /// `order[k]` does not; join them all to it.
    fn fan(&mut self, k: usize) {
        let apex = self.order[k];
        let left = self.orient(self.order[0], self.order[1], apex) > 0.0;
        for j in 0..k - 1 {
            let (u, v) = (self.order[j], self.order[j + 1]);
            let t = if left { [u, v, apex] } else { [v, u, apex] };
            let id = self.push_triangle(t);
            if j > 0 {
                // Consecutive fan triangles share the edge from order[j] to the apex.
                self.link(id - 1, self.order[j - 1], id, self.order[j + 1]);
            }
        }
        // The hull, counter-clockwise: along the line, then to the apex and back.
        let mut cycle: Vec<u32> = self.order[..k].to_vec();
        if !left {
            cycle.reverse();
        }
        cycle.push(apex);
        let m = cycle.len();
        for i in 0..m {
            let (a, b) = (cycle[i], cycle[(i + 1) % m]);
            self.hnext[a as usize] = b;
            self.hprev[b as usize] = a;
        }
        for t in 0..self.tri.len() as u32 {
            for i in 0..3 {
                let (a, b) = (self.tri[t as usize][i], self.tri[t as usize][(i + 1) % 3]);
                if self.hnext[a as usize] == b {
                    self.htri[a as usize] = t;
                }
            }
        }
    }

    fn push_triangle(&mut self, t: [u32; 3]) -> u32 {
        let id = self.tri.len() as u32;
        self.tri.push(t);
        self.nbr.push([NONE; 3]);
        for v in t {
            self.vtri[v as usize] = id;
        }
        id
    }

    /// The index in triangle `t` of vertex `v`.
    #[inline]
    fn index_of(&self, t: u32, v: u32) -> usize {
        let tv = self.tri[t as usize];
        if tv[0] == v {
            0
        } else if tv[1] == v {
            1
        } else {
            2
        }
    }

    /// Makes `s` and `t` neighbours across the edge opposite `vs` in `s` and `vt` in `t`.
    fn link(&mut self, s: u32, vs: u32, t: u32, vt: u32) {
        let (i, j) = (self.index_of(s, vs), self.index_of(t, vt));
        self.nbr[s as usize][i] = t;
        self.nbr[t as usize][j] = s;
    }

    /// Adds point `p`, lexicographically beyond every point so far, by joining it to the hull
    /// edges it sees (a contiguous chain next to `last`, the previous point), then restores the
    /// Delaunay property around it.
    fn add_beyond_hull(&mut self, p: u32, last: u32) -> Result<(), CdtError> {
        let budget = self.tri.len() + 8;
        let visible = |s: &Self, u: u32| s.orient(u, s.hnext[u as usize], p) < 0.0;
        let (mut l, mut r) = (last, last);
        let mut steps = 0;
        while visible(self, self.hprev[l as usize]) {
            l = self.hprev[l as usize];
            steps += 1;
            if steps > budget {
                return Err(CdtError::Budget("hull walk"));
            }
        }
        while visible(self, r) {
            r = self.hnext[r as usize];
            steps += 1;
            if steps > budget {
                return Err(CdtError::Budget("hull walk"));
            }
        }
        if l == r {
            return Err(CdtError::Budget("a new point sees no hull edge"));
        }
        self.stack.clear();
        let (mut u, mut prev, mut first) = (l, NONE, NONE);
        while u != r {
            let v = self.hnext[u as usize];
            let t = self.push_triangle([v, u, p]);
            let outer = self.htri[u as usize];
            let far = self.third(outer, u, v);
            self.link(t, p, outer, far);
            if prev == NONE {
                first = t;
            } else {
                self.link(prev, self.tri[prev as usize][1], t, v);
            }
            self.stack.push((t, p));
            prev = t;
            u = v;
        }
        let mut v = self.hnext[l as usize];
        while v != r {
            let next = self.hnext[v as usize];
            self.hnext[v as usize] = NONE;
            self.hprev[v as usize] = NONE;
            v = next;
        }
        self.hnext[l as usize] = p;
        self.hprev[p as usize] = l;
        self.hnext[p as usize] = r;
        self.hprev[r as usize] = p;
        self.htri[l as usize] = first;
        self.htri[p as usize] = prev;
        self.legalize()
    }

    /// The vertex of triangle `t` other than `a` and `b`.
    #[inline]
    fn third(&self, t: u32, a: u32, b: u32) -> u32 {
        let tv = self.tri[t as usize];
        tv.into_iter().find(|&x| x != a && x != b).unwrap_or(NONE)
    }

    /// Lawson flips from the queued (triangle, apex) pairs until every edge they reach is
    /// locally Delaunay.
    fn legalize(&mut self) -> Result<(), CdtError> {
        let mut budget = 64 * (self.tri.len() + 8);
        while let Some((t, a)) = self.stack.pop() {
            budget -= 1;
            if budget == 0 {
                return Err(CdtError::Budget("Delaunay flips"));
            }
            let i = self.index_of(t, a);
            let u = self.nbr[t as usize][i];
            if u == NONE {
                continue;
            }
            let tv = self.tri[t as usize];
            let d = self.third(u, tv[(i + 1) % 3], tv[(i + 2) % 3]);
            let [pa, pb, pc] = tv.map(|v| self.pts[v as usize]);
            if incircle(pa, pb, pc, self.pts[d as usize]) > 0.0 {
                self.flip(t, i);
                self.stack.push((t, a));
                self.stack.push((u, a));
            }
        }
        Ok(())
    }

    /// Flips the edge opposite `tri[t][i]`: triangles `abc` and `dcb` become `abd` and `adc`.
    /// The quadrilateral must be strictly convex.
    fn flip(&mut self, t: u32, i: usize) {
        let tv = self.tri[t as usize];
        let (a, b, c) = (tv[i], tv[(i + 1) % 3], tv[(i + 2) % 3]);
        let u = self.nbr[t as usize][i];
        let j = self.index_of(u, self.third(u, b, c));
        let d = self.tri[u as usize][j];
        let n_ab = self.nbr[t as usize][(i + 2) % 3];
        let n_ca = self.nbr[t as usize][(i + 1) % 3];
        let uv = self.tri[u as usize];
        // In u = (d, c, b) rotated: the edge bd is opposite c, the edge dc opposite b.
        let n_bd = self.nbr[u as usize][self.index_of(u, c)];
        let n_dc = self.nbr[u as usize][self.index_of(u, b)];
        debug_assert!(uv.contains(&d));
        self.tri[t as usize] = [a, b, d];
        self.nbr[t as usize] = [n_bd, u, n_ab];
        self.tri[u as usize] = [a, d, c];
        self.nbr[u as usize] = [n_dc, n_ca, t];
        self.repoint(n_bd, u, t);
        self.repoint(n_ca, t, u);
        self.vtri[a as usize] = t;
        self.vtri[b as usize] = t;
        self.vtri[d as usize] = t;
        self.vtri[c as usize] = u;
        // Hull edges keep their triangle pointers (they only matter during the sweep).
        if n_bd == NONE {
            self.htri[b as usize] = t;
        }
        if n_ca == NONE {
            self.htri[c as usize] = u;
        }
        if n_ab == NONE {
            self.htri[a as usize] = t;
        }
        if n_dc == NONE {
            self.htri[d as usize] = u;
        }
    }

    /// In triangle `n` (if any), the neighbour pointer to `old` becomes `new`.
    fn repoint(&mut self, n: u32, old: u32, new: u32) {
        if n != NONE {
            for x in self.nbr[n as usize].iter_mut() {
                if *x == old {
                    *x = new;
                }
            }
        }
    }

    /// Collects the triangles around vertex `a` into `self.around`.
    fn collect_around(&mut self, a: u32) -> Result<(), CdtError> {
        self.around.clear();
        let start = self.vtri[a as usize];
        if start == NONE {
            return Ok(());
        }
        let budget = self.tri.len() + 1;
        // Counter-clockwise: across the edge (a, w), which is opposite u = the vertex after a.
        let mut t = start;
        loop {
            self.around.push(t);
            let i = self.index_of(t, a);
            t = self.nbr[t as usize][(i + 1) % 3];
            if t == start {
                return Ok(());
            }
            if t == NONE {
                break;
            }
            if self.around.len() > budget {
                return Err(CdtError::Budget("rotation around a vertex"));
            }
        }
        // A hull vertex: the rest lies clockwise from the start.
        let mut t = start;
        loop {
            let i = self.index_of(t, a);
            t = self.nbr[t as usize][(i + 2) % 3];
            if t == NONE {
                return Ok(());
            }
            self.around.push(t);
            if self.around.len() > budget {
                return Err(CdtError::Budget("rotation around a vertex"));
            }
        }
    }

    /// Makes the edge `ab` part of the triangulation and records it with `tag`. Vertices lying
    /// inside `ab` split it. Fails when `ab` crosses an edge recovered before.
    pub fn constrain(&mut self, a: u32, b: u32, tag: u32) -> Result<(), CdtError> {
        let mut a = a;
        let mut guard = self.pts.len() + 1;
        while a != b {
            guard -= 1;
            if guard == 0 {
                return Err(CdtError::Budget("constraint splits"));
            }
            let v = self.trace(a, b)?;
            for &(u, w) in &self.queue {
                if let Some(&other) = self.constraints.get(&key(u, w)) {
                    return Err(CdtError::Crossing(tag, other));
                }
            }
            self.recover(a, v)?;
            self.constraints.insert(key(a, v), tag);
            a = v;
        }
        Ok(())
    }

    /// Walks from `a` towards `b`, leaving the edges that cross the open segment in
    /// `self.queue`. Returns where the walk stopped: `b`, or the first vertex lying inside the
    /// segment.
    fn trace(&mut self, a: u32, b: u32) -> Result<u32, CdtError> {
        self.queue.clear();
        self.collect_around(a)?;
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        // Along an existing edge, or onto a vertex in the segment's direction.
        let k = if pa[0] != pb[0] { 0 } else { 1 };
        let ahead = |q: [f64; 2]| q[k] != pa[k] && (q[k] > pa[k]) == (pb[k] > pa[k]);
        let mut start = None;
        for &t in &self.around {
            let i = self.index_of(t, a);
            let tv = self.tri[t as usize];
            let (u, w) = (tv[(i + 1) % 3], tv[(i + 2) % 3]);
            if u == b || w == b {
                return Ok(b);
            }
            let (ou, ow) = (self.orient(a, b, u), self.orient(a, b, w));
            if ou == 0.0 && ahead(self.pts[u as usize]) {
                return Ok(u);
            }
            if ow == 0.0 && ahead(self.pts[w as usize]) {
                return Ok(w);
            }
            if ou < 0.0 && ow > 0.0 {
                start = Some((t, u, w));
            }
        }
        let Some((mut t, mut u, mut w)) = start else {
            return Err(CdtError::Budget(
                "no triangle around the constraint's start",
            ));
        };
        let budget = self.tri.len() + 1;
        for _ in 0..budget {
            self.queue.push_back((u, w));
            let far = self.third(t, u, w);
            let t2 = self.nbr[t as usize][self.index_of(t, far)];
            if t2 == NONE {
                return Err(CdtError::Budget("constraint walk left the triangulation"));
            }
            let x = self.third(t2, u, w);
            if x == b {
                return Ok(b);
            }
            let o = self.orient(a, b, x);
            if o == 0.0 {
                return Ok(x);
            }
            if o > 0.0 {
                w = x;
            } else {
                u = x;
            }
            t = t2;
        }
        Err(CdtError::Budget("constraint walk"))
    }

    /// The triangle holding edge `uw` and the index of its third vertex.
    fn find_edge(&mut self, u: u32, w: u32) -> Result<(u32, usize), CdtError> {
        self.collect_around(u)?;
        for &t in &self.around {
            if self.tri[t as usize].contains(&w) {
                return Ok((t, self.index_of(t, self.third(t, u, w))));
            }
        }
        Err(CdtError::Budget("a crossing edge disappeared"))
    }

    /// Flips the queued crossing edges until none crosses the open segment `av` (Sloan): an
    /// edge in a strictly convex quadrilateral is flipped, and kept queued if the new diagonal
    /// still crosses; any other waits its turn. Some crossing edge is always flippable.
    fn recover(&mut self, a: u32, v: u32) -> Result<(), CdtError> {
        let m = self.queue.len() + 1;
        let mut budget = 16 * m * m + 64;
        while let Some((u, w)) = self.queue.pop_front() {
            budget -= 1;
            if budget == 0 {
                return Err(CdtError::Budget("constraint recovery flips"));
            }
            let (t, i) = self.find_edge(u, w)?;
            let p = self.tri[t as usize][i];
            let t2 = self.nbr[t as usize][i];
            if t2 == NONE {
                return Err(CdtError::Budget("a crossing edge on the hull"));
            }
            let q = self.third(t2, u, w);
            if opposite(self.orient(p, q, u), self.orient(p, q, w)) {
                self.flip(t, i);
                let crosses = p != a
                    && p != v
                    && q != a
                    && q != v
                    && opposite(self.orient(a, v, p), self.orient(a, v, q));
                if crosses {
                    self.queue.push_back((p, q));
                }
            } else {
                self.queue.push_back((u, w));
            }
        }
        Ok(())
    }

    /// Whether edge `ab` was recovered as a constraint.
    pub fn is_constrained(&self, a: u32, b: u32) -> bool {
        self.constraints.contains_key(&key(a, b))
    }

    /// Labels the triangles: those reachable from the hull without crossing a constraint are
    /// outside, those reachable from a hole seed are holes, the rest form the region. A seed
    /// on an edge starts from the first unlabelled triangle containing it; seeds outside the
    /// triangulation or in the outside do nothing.
    pub fn classify(&mut self, seeds: &[[f64; 2]]) {
        self.label.clear();
        self.label.resize(self.tri.len(), UNKNOWN);
        for t in 0..self.tri.len() as u32 {
            for i in 0..3 {
                let tv = self.tri[t as usize];
                if self.nbr[t as usize][i] == NONE
                    && self.label[t as usize] == UNKNOWN
                    && !self.is_constrained(tv[(i + 1) % 3], tv[(i + 2) % 3])
                {
                    self.flood(t, OUTSIDE);
                }
            }
        }
        for &s in seeds {
            let hit = (0..self.tri.len() as u32).find(|&t| {
                let [a, b, c] = self.tri[t as usize].map(|v| self.pts[v as usize]);
                self.label[t as usize] == UNKNOWN
                    && orient2d(a, b, s) >= 0.0
                    && orient2d(b, c, s) >= 0.0
                    && orient2d(c, a, s) >= 0.0
            });
            if let Some(t) = hit {
                self.flood(t, HOLE);
            }
        }
        for l in self.label.iter_mut() {
            if *l == UNKNOWN {
                *l = REGION;
            }
        }
    }

    fn flood(&mut self, t0: u32, label: u8) {
        self.label[t0 as usize] = label;
        let mut stack = std::mem::take(&mut self.stack);
        stack.clear();
        stack.push((t0, 0));
        while let Some((t, _)) = stack.pop() {
            let tv = self.tri[t as usize];
            for i in 0..3 {
                let n = self.nbr[t as usize][i];
                if n != NONE
                    && self.label[n as usize] == UNKNOWN
                    && !self.is_constrained(tv[(i + 1) % 3], tv[(i + 2) % 3])
                {
                    self.label[n as usize] = label;
                    stack.push((n, 0));
                }
            }
        }
        self.stack = stack;
    }

    /// The triangles of the region (after [`Cdt::classify`]).
    pub fn region(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        (0..self.tri.len())
            .filter(|&t| self.label[t] == REGION)
            .map(|t| self.tri[t])
    }

    /// The edges inside the region that are no constraint (each once).
    pub fn diagonals(&self) -> impl Iterator<Item = [u32; 2]> + '_ {
        (0..self.tri.len()).flat_map(move |t| {
            (0..3).filter_map(move |i| {
                let n = self.nbr[t][i];
                let tv = self.tri[t];
                let (a, b) = (tv[(i + 1) % 3], tv[(i + 2) % 3]);
                let inner = self.label[t] == REGION
                    && n != NONE
                    && (t as u32) < n
                    && self.label[n as usize] == REGION
                    && !self.is_constrained(a, b);
                inner.then_some([a, b])
            })
        })
    }

    /// Number of triangles (all labels).
    #[cfg(test)]
    pub fn num_triangles(&self) -> usize {
        self.tri.len()
    }

    /// Checks adjacency and orientation (tests only).
    #[cfg(test)]
    pub fn check(&self) -> Result<(), String> {
        for (t, tv) in self.tri.iter().enumerate() {
            let [a, b, c] = tv.map(|v| self.pts[v as usize]);
            if orient2d(a, b, c) <= 0.0 {
                return Err(format!("triangle {t} {tv:?} is not counter-clockwise"));
            }
            for i in 0..3 {
                let n = self.nbr[t][i];
                if n == NONE {
                    continue;
                }
                let (x, y) = (tv[(i + 1) % 3], tv[(i + 2) % 3]);
                let nv = self.tri[n as usize];
                if !(nv.contains(&x) && nv.contains(&y)) {
                    return Err(format!(
                        "triangles {t} and {n} are linked but share no edge"
                    ));
                }
                if !self.nbr[n as usize].contains(&(t as u32)) {
                    return Err(format!("triangles {t} and {n} are not mutual"));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(cdt: &Cdt) -> f64 {
        cdt.region()
            .map(|t| {
                let [a, b, c] = t.map(|v| cdt.pts[v as usize]);
                0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
            })
            .sum()
    }

    fn run(pts: &[[f64; 2]], loops: &[&[u32]], seeds: &[[f64; 2]]) -> Result<Cdt, CdtError> {
        let mut cdt = Cdt::default();
        cdt.triangulate(pts)?;
        cdt.check().unwrap();
        for (tag, l) in loops.iter().enumerate() {
            let k = l.len();
            let edges = if k == 2 { 1 } else { k };
            for i in 0..edges {
                cdt.constrain(l[i], l[(i + 1) % k], tag as u32)?;
            }
        }
        cdt.check().unwrap();
        cdt.classify(seeds);
        Ok(cdt)
    }

    #[test]
    fn collinear_prefix_and_grid_points() {
        // Many points on the first vertical line, then a grid: exercises the fan start and
        // cocircular flips.
        let mut pts = Vec::new();
        for i in 0..6 {
            for j in 0..6 {
                pts.push([i as f64, j as f64]);
            }
        }
        let mut cdt = Cdt::default();
        cdt.triangulate(&pts).unwrap();
        cdt.check().unwrap();
        assert_eq!(
            cdt.num_triangles(),
            50,
            "2n - 2 - hull vertices = 72 - 2 - 20"
        );
        // All collinear: nothing, and no failure.
        cdt.triangulate(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
            .unwrap();
        assert_eq!(cdt.num_triangles(), 0);
    }

    #[test]
    fn square_with_square_hole() {
        let pts = [
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [0.0, 4.0],
            [1.0, 1.0],
            [3.0, 1.0],
            [3.0, 3.0],
            [1.0, 3.0],
        ];
        let outer: &[u32] = &[0, 1, 2, 3];
        let inner: &[u32] = &[4, 5, 6, 7];
        let c = run(&pts, &[outer, inner], &[[2.0, 2.0]]).unwrap();
        assert_eq!(area(&c), 12.0);
        // Without the seed the inner square belongs to the facet too.
        let c = run(&pts, &[outer, inner], &[]).unwrap();
        assert_eq!(area(&c), 16.0);
        // Only the inner loop: the outer ring is outside.
        let c = run(&pts, &[inner], &[]).unwrap();
        assert_eq!(area(&c), 4.0);
    }

    #[test]
    fn nonconvex_loop_recovers_every_edge() {
        // A comb: teeth force constraints across the convex hull triangulation.
        let mut pts = vec![[0.0, 0.0], [10.0, 0.0]];
        for i in (0..10).rev() {
            let x = i as f64;
            pts.push([x + 1.0, 5.0]);
            pts.push([x + 0.5, 0.5]);
        }
        let n = pts.len() as u32;
        let lp: Vec<u32> = (0..n).collect();
        let c = run(&pts, &[&lp], &[]).unwrap();
        for i in 0..n {
            assert!(c.is_constrained(i, (i + 1) % n));
        }
        // Shoelace area of the polygon equals the region's area.
        let mut shoelace = 0.0;
        for i in 0..pts.len() {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            shoelace += a[0] * b[1] - a[1] * b[0];
        }
        assert!((area(&c) - shoelace / 2.0).abs() < 1e-12, "{}", area(&c));
    }

    #[test]
    fn random_star_polygons_with_holes_and_free_points_keep_their_area() {
        let mut state: u64 = 0x853C_49E6_748F_EA9B;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let shoelace = |p: &[[f64; 2]]| {
            (0..p.len())
                .map(|i| {
                    let (a, b) = (p[i], p[(i + 1) % p.len()]);
                    a[0] * b[1] - a[1] * b[0]
                })
                .sum::<f64>()
                / 2.0
        };
        for round in 0..20 {
            let n = 8 + round * 13;
            // A star-shaped outer loop (radii in [2, 4]) around the origin, a star-shaped
            // hole (radii in [0.5, 1]) with its seed at the origin, and free points between.
            let star = |k: usize, lo: f64, hi: f64, rnd: &mut dyn FnMut() -> f64| {
                (0..k)
                    .map(|i| {
                        let t = (i as f64 + 0.5 * rnd()) / k as f64 * std::f64::consts::TAU;
                        let r = lo + (hi - lo) * rnd();
                        [r * t.cos(), r * t.sin()]
                    })
                    .collect::<Vec<_>>()
            };
            let outer = star(n, 2.0, 4.0, &mut rnd);
            let hole = star(n / 2 + 3, 0.5, 1.0, &mut rnd);
            let mut pts = outer.clone();
            pts.extend_from_slice(&hole);
            for i in 0..n {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                pts.push([1.5 * t.cos(), 1.5 * t.sin()]);
            }
            let lo: Vec<u32> = (0..outer.len() as u32).collect();
            let hi: Vec<u32> = (outer.len() as u32..(outer.len() + hole.len()) as u32).collect();
            let c = run(&pts, &[&lo, &hi], &[[0.0, 0.0]]).unwrap();
            let want = shoelace(&outer) - shoelace(&hole);
            assert!((area(&c) - want).abs() < 1e-9 * want, "round {round}");
            for l in [&lo, &hi] {
                for i in 0..l.len() {
                    assert!(c.is_constrained(l[i], l[(i + 1) % l.len()]));
                }
            }
        }
    }

    #[test]
    fn crossing_loops_and_self_crossing_are_reported() {
        let pts = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        // The bow tie 0-2-1-3 crosses itself.
        let e = run(&pts, &[&[0, 2, 1, 3]], &[]).err().unwrap();
        assert_eq!(e, CdtError::Crossing(0, 0));
        // Two segments crossing, from two polygons.
        let e = run(&pts, &[&[0, 2], &[1, 3]], &[]).err().unwrap();
        assert_eq!(e, CdtError::Crossing(1, 0));
    }

    #[test]
    fn vertices_on_a_constraint_split_it() {
        let pts = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 1.0], [1.0, -1.0]];
        let c = run(&pts, &[&[0, 2]], &[]).unwrap();
        assert!(c.is_constrained(0, 1) && c.is_constrained(1, 2));
        assert!(!c.is_constrained(0, 2));
        // A loop with an unlisted vertex inside one of its edges, and one in its interior.
        let c = run(&pts, &[&[0, 2, 3]], &[]).unwrap();
        assert_eq!(area(&c), 1.0);
        assert_eq!(
            c.diagonals().count(),
            1,
            "the edge from vertex 1 to the apex"
        );
        let c = run(&pts, &[&[0, 4, 2, 3]], &[]).unwrap();
        assert_eq!(area(&c), 2.0);
        assert_eq!(c.diagonals().count(), 4, "the four spokes to vertex 1");
    }
}
