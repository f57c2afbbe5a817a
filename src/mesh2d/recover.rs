//! Constrained segment insertion: a missing segment becomes an edge without any new vertex, by
//! removing the triangles it crosses and retriangulating the two pseudo-polygons on either side
//! constrained Delaunay (Anglada's algorithm; Shewchuk and Brown, 2015, prove it yields the CDT).
//! Every decision is an exact orientation or in-circle test.
//!
//! Nothing changes unless the whole operation can be done: the walk, the retriangulation and
//! the edge matching are all checked on scratch data before a single triangle is rewritten.

use super::geometry::Geometry;
use super::store::{next, prev, Cdt, Scratch, SegId, TriId, VertexId};
use super::NONE;

/// The outcome of [`Cdt::insert_segment`].
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Recovery {
    /// The segment is the edge on this half-edge (it was there, or has been inserted).
    Edge(u32),
    /// This vertex lies exactly on the open segment: split the segment there. Nothing changed.
    Through(VertexId),
    /// The segment crosses this (other) segment. Nothing changed.
    Blocked(SegId),
    /// The walk or the retriangulation met geometry it cannot handle (inverted rounding
    /// slivers, an open boundary, a region border), or ran out of budget. Nothing changed.
    Failed,
}

#[inline]
fn key(from: VertexId, to: VertexId) -> u64 {
    ((from as u64) << 32) | to as u64
}

impl<G: Geometry> Cdt<G> {
    /// Collects the live triangles around vertex `a` into `self.rec.fan` (both ways round, so
    /// fans opened by carving are complete). Returns `false` when the fan is inconsistent.
    fn collect_fan(&mut self, a: VertexId) -> bool {
        let mut fan = std::mem::take(&mut self.rec.fan);
        fan.clear();
        let start = self.vtri[a as usize];
        let ok = start != NONE && self.alive(start) && {
            let corner = |cdt: &Self, t: TriId| cdt.tv[t as usize].iter().position(|&v| v == a);
            let budget = self.num_slots() + 3;
            let mut closed = false;
            let mut bad = false;
            // Clockwise: leave through the edge (v[k+2], a), which is opposite v[k+1].
            let mut t = start;
            for _ in 0..budget {
                let Some(k) = corner(self, t) else {
                    bad = true;
                    break;
                };
                fan.push(t);
                let h = self.tn[t as usize][next(k)];
                if h == NONE {
                    break;
                }
                t = h / 3;
                if t == start {
                    closed = true;
                    break;
                }
            }
            if !closed && !bad {
                // Open fan: go counter-clockwise from the start too.
                let mut t = start;
                for _ in 0..budget {
                    let Some(k) = corner(self, t) else {
                        bad = true;
                        break;
                    };
                    let h = self.tn[t as usize][prev(k)];
                    if h == NONE {
                        break;
                    }
                    t = h / 3;
                    if t == start {
                        bad = true;
                        break;
                    }
                    fan.push(t);
                }
            }
            !bad && fan.len() <= budget
        };
        self.rec.fan = fan;
        ok
    }

    /// Makes segment `s` (its current endpoints `a`, `b`) an edge of the triangulation; see
    /// [`Recovery`]. On success the edge carries `s` (a wall) and the new triangles are in
    /// `new_tris`.
    pub fn insert_segment(&mut self, s: SegId) -> Recovery {
        let (a, b) = (self.segs[s as usize].a, self.segs[s as usize].b);
        if let Some(h) = self.find_edge(a, b) {
            self.set_seg(h, s);
            self.new_tris.clear();
            return Recovery::Edge(h);
        }
        match self.walk_segment(a, b) {
            Ok(()) => {}
            Err(r) => return r,
        }
        if !self.plan_pseudo_polygons() {
            return Recovery::Failed;
        }
        self.commit(a, b, s)
    }

    /// Walks from `a` to `b` collecting the crossed triangles and the vertex chains left and
    /// right of `ab` (each from `a` to `b`).
    fn walk_segment(&mut self, a: VertexId, b: VertexId) -> Result<(), Recovery> {
        let (pa, pb) = (self.p(a), self.p(b));
        if !self.collect_fan(a) {
            return Err(Recovery::Failed);
        }
        let g = self.ghost;
        // The triangle at `a` whose opposite edge the segment leaves through.
        let mut first = None;
        for j in 0..self.rec.fan.len() {
            let t = self.rec.fan[j];
            let v = self.tv[t as usize];
            let Some(k) = v.iter().position(|&x| x == a) else {
                return Err(Recovery::Failed);
            };
            let (u, w) = (v[next(k)], v[prev(k)]);
            if u == g || w == g {
                continue;
            }
            for x in [u, w] {
                let px = self.p(x);
                if self.geom.orient(pa, pb, px) == 0.0 && self.geom.strictly_between(pa, pb, px) {
                    return Err(Recovery::Through(x));
                }
            }
            let (pu, pw) = (self.p(u), self.p(w));
            if self.geom.orient(pa, pu, pw) > 0.0
                && self.geom.orient(pa, pu, pb) > 0.0
                && self.geom.orient(pa, pb, pw) > 0.0
            {
                first = Some((t, k));
                break;
            }
        }
        let Some((t0, k0)) = first else {
            return Err(Recovery::Failed);
        };
        let rec = &mut self.rec;
        rec.crossed.clear();
        rec.left.clear();
        rec.right.clear();
        let v0 = self.tv[t0 as usize];
        let (mut rv, mut lv) = (v0[next(k0)], v0[prev(k0)]);
        rec.crossed.push(t0);
        rec.left.extend_from_slice(&[a, lv]);
        rec.right.extend_from_slice(&[a, rv]);
        // The crossed half-edge, directed from its right end to its left end.
        let mut h = 3 * t0 + k0 as u32;
        for _ in 0..self.tv.len() + 1 {
            let sh = self.aux[(h / 3) as usize].s[(h % 3) as usize];
            if sh != NONE {
                return Err(Recovery::Blocked(sh));
            }
            let tw = self.tn[(h / 3) as usize][(h % 3) as usize];
            if tw == NONE {
                return Err(Recovery::Failed);
            }
            let (t2, j) = (tw / 3, (tw % 3) as usize);
            let v = self.tv[t2 as usize];
            let x = v[j];
            if x == g || v[next(j)] != lv || v[prev(j)] != rv {
                return Err(Recovery::Failed);
            }
            let rec = &mut self.rec;
            rec.crossed.push(t2);
            if x == b {
                rec.left.push(b);
                rec.right.push(b);
                return Ok(());
            }
            let px = self.p(x);
            let o = self.geom.orient(pa, pb, px);
            if o == 0.0 {
                return Err(if self.geom.strictly_between(pa, pb, px) {
                    Recovery::Through(x)
                } else {
                    Recovery::Failed
                });
            }
            if o > 0.0 {
                self.rec.left.push(x);
                lv = x;
                h = 3 * t2 + next(j) as u32;
            } else {
                self.rec.right.push(x);
                rv = x;
                h = 3 * t2 + prev(j) as u32;
            }
        }
        Err(Recovery::Failed)
    }

    /// Triangulates both pseudo-polygons into `rec.tris` (counter-clockwise triangles, those
    /// holding `ab` first on each side). Returns `false` when a triangle would not be strictly
    /// counter-clockwise.
    fn plan_pseudo_polygons(&mut self) -> bool {
        let mut rec = std::mem::take(&mut self.rec);
        rec.tris.clear();
        // Left chain: a, L…, b with every L left of a→b. Right chain reversed: b, R…, a with
        // every R left of b→a. Either way the chain lies left of its base edge.
        rec.right.reverse();
        let mut ok = true;
        for side in 0..2 {
            let chain = if side == 0 { &rec.left } else { &rec.right };
            rec.stack.clear();
            rec.stack.push((0, chain.len() - 1));
            while let Some((lo, hi)) = rec.stack.pop() {
                if hi < lo + 2 {
                    continue;
                }
                let (p, q) = (self.p(chain[lo]), self.p(chain[hi]));
                // The vertex whose circle through the base holds no other chain vertex.
                let mut c = lo + 1;
                for i in lo + 2..hi {
                    if self.geom.incircle(p, q, self.p(chain[c]), self.p(chain[i])) > 0.0 {
                        c = i;
                    }
                }
                if self.geom.orient(p, q, self.p(chain[c])) <= 0.0 {
                    ok = false;
                    break;
                }
                rec.tris.push([chain[lo], chain[hi], chain[c]]);
                rec.stack.push((lo, c));
                rec.stack.push((c, hi));
            }
            if !ok {
                break;
            }
        }
        rec.right.reverse();
        self.rec = rec;
        ok
    }

    /// Replaces the crossed triangles by the planned ones, after checking that their edges
    /// match the old boundary exactly.
    fn commit(&mut self, a: VertexId, b: VertexId, s: SegId) -> Recovery {
        let mut rec = std::mem::take(&mut self.rec);
        let result = self.commit_with(&mut rec, a, b, s);
        self.rec = rec;
        result
    }

    fn commit_with(&mut self, rec: &mut Scratch, a: VertexId, b: VertexId, s: SegId) -> Recovery {
        // The crossed triangles must all carry one region label (they do before
        // classification; afterwards a mixed set means a region border: leave it).
        let label = self.aux[rec.crossed[0] as usize].reg;
        if rec
            .crossed
            .iter()
            .any(|&t| self.aux[t as usize].reg != label)
        {
            return Recovery::Failed;
        }
        let mark = self.ready_stamps();
        for &t in &rec.crossed {
            self.aux[t as usize].stamp = mark;
        }
        rec.border.clear();
        for &t in &rec.crossed {
            for i in 0..3 {
                let tw = self.tn[t as usize][i];
                if tw != NONE && self.aux[(tw / 3) as usize].stamp == mark {
                    continue;
                }
                let (f, to) = self.edge_ends(3 * t + i as u32);
                rec.border.push((key(f, to), tw, self.aux[t as usize].s[i]));
            }
        }
        rec.border.sort_unstable_by_key(|e| e.0);
        rec.halves.clear();
        for (n, tri) in rec.tris.iter().enumerate() {
            for i in 0..3 {
                rec.halves
                    .push((key(tri[next(i)], tri[prev(i)]), 3 * n as u32 + i as u32));
            }
        }
        rec.halves.sort_unstable_by_key(|e| e.0);
        // Every new half-edge is an old boundary edge or has its reverse among the new ones;
        // every old boundary edge is used exactly once.
        let mut used = 0;
        for w in rec.halves.windows(2) {
            if w[0].0 == w[1].0 {
                return Recovery::Failed;
            }
        }
        for w in rec.border.windows(2) {
            if w[0].0 == w[1].0 {
                return Recovery::Failed;
            }
        }
        for &(k, _) in &rec.halves {
            if rec.border.binary_search_by_key(&k, |e| e.0).is_ok() {
                used += 1;
            } else {
                let rev = k.rotate_left(32);
                if rec.halves.binary_search_by_key(&rev, |e| e.0).is_err() {
                    return Recovery::Failed;
                }
            }
        }
        if used != rec.border.len() {
            return Recovery::Failed;
        }
        // Commit: reuse the crossed slots, allocate or free the difference.
        let mut slots = std::mem::take(&mut self.new_tris);
        slots.clear();
        for j in 0..rec.tris.len() {
            let t = if j < rec.crossed.len() {
                rec.crossed[j]
            } else {
                self.alloc()
            };
            slots.push(t);
        }
        for &t in rec.crossed.iter().skip(rec.tris.len()) {
            self.tv[t as usize] = [NONE; 3];
            self.tn[t as usize] = [NONE; 3];
            self.aux[t as usize].s = [NONE; 3];
            self.free.push(t);
        }
        for (j, tri) in rec.tris.iter().enumerate() {
            let t = slots[j] as usize;
            self.tv[t] = *tri;
            self.tn[t] = [NONE; 3];
            self.aux[t].s = [NONE; 3];
            self.aux[t].reg = label;
            self.aux[t].flat = false;
        }
        for &(k, hn) in &rec.halves {
            let t = slots[(hn / 3) as usize];
            let h = 3 * t + hn % 3;
            let (tu, i) = (t as usize, (hn % 3) as usize);
            if let Ok(p) = rec.border.binary_search_by_key(&k, |e| e.0) {
                let (_, outer, seg) = rec.border[p];
                self.aux[tu].s[i] = seg;
                self.tn[tu][i] = outer;
                if outer != NONE {
                    self.tn[(outer / 3) as usize][(outer % 3) as usize] = h;
                }
            } else {
                let rev = k.rotate_left(32);
                if let Ok(p) = rec.halves.binary_search_by_key(&rev, |e| e.0) {
                    let other = rec.halves[p].1;
                    let t2 = slots[(other / 3) as usize];
                    self.tn[tu][i] = 3 * t2 + other % 3;
                }
            }
        }
        for (j, tri) in rec.tris.iter().enumerate() {
            for &v in tri {
                self.vtri[v as usize] = slots[j];
            }
        }
        self.hint = slots[0];
        self.new_tris = slots;
        match self.find_edge(a, b) {
            Some(h) => {
                self.set_seg(h, s);
                Recovery::Edge(h)
            }
            None => Recovery::Failed,
        }
    }
}
