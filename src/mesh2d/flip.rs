//! Lawson flips: restores the constrained Delaunay property after a wall is taken off an edge
//! (a segment split at a vertex lying beside it within rounding), when that edge and the ones
//! behind it may no longer be locally Delaunay, and, once meshing is done, wherever a rounded
//! split point left an edge that is not ([`Cdt::legalize_all`]).

use super::geometry::Geometry;
use super::store::{next, prev, Cdt};
use super::NONE;

impl<G: Geometry> Cdt<G> {
    /// Flips edges, starting from half-edge `h`, until every edge reached is a wall, on the
    /// hull or carved boundary, or locally Delaunay (exact in-circle test). The budget is
    /// generous (flips are quadratic at worst); running out leaves a valid triangulation.
    /// The triangles changed are left in `new_tris`.
    pub fn legalize(&mut self, h: u32) {
        let mut stack = std::mem::take(&mut self.rec.flips);
        stack.clear();
        self.new_tris.clear();
        stack.push(h);
        let mut budget = 16 * self.num_slots() + 64;
        while let Some(h) = stack.pop() {
            if budget == 0 {
                break;
            }
            budget -= 1;
            let (t1, i) = ((h / 3) as usize, (h % 3) as usize);
            if self.tv[t1][0] == NONE || self.aux[t1].s[i] != NONE {
                continue;
            }
            let tw = self.tn[t1][i];
            if tw == NONE || self.is_ghost(t1 as u32) || self.is_ghost(tw / 3) {
                continue;
            }
            let (t2, j) = ((tw / 3) as usize, (tw % 3) as usize);
            let (p, u, w) = (self.tv[t1][i], self.tv[t1][next(i)], self.tv[t1][prev(i)]);
            let q = self.tv[t2][j];
            let (pp, pu, pw, pq) = (self.p(p), self.p(u), self.p(w), self.p(q));
            if self.geom.orient(pp, pu, pw) <= 0.0 || self.geom.incircle(pp, pu, pw, pq) <= 0.0 {
                continue;
            }
            // The quadrilateral p, u, q, w must be strictly convex for the flip.
            if self.geom.orient(pp, pu, pq) <= 0.0 || self.geom.orient(pq, pw, pp) <= 0.0 {
                continue;
            }
            // Outer edges: A = (w, p) and B = (p, u) of t1; C = (u, q) and D = (q, w) of t2.
            let (a, sa) = (self.tn[t1][next(i)], self.aux[t1].s[next(i)]);
            let (b, sb) = (self.tn[t1][prev(i)], self.aux[t1].s[prev(i)]);
            let (c, sc) = (self.tn[t2][next(j)], self.aux[t2].s[next(j)]);
            let (d, sd) = (self.tn[t2][prev(j)], self.aux[t2].s[prev(j)]);
            let (t1u, t2u) = (t1 as u32, t2 as u32);
            // New t1 = (p, u, q): edges (u, q) = C, (q, p) = diagonal, (p, u) = B.
            // New t2 = (q, w, p): edges (w, p) = A, (p, q) = diagonal, (q, w) = D.
            self.tv[t1] = [p, u, q];
            self.tv[t2] = [q, w, p];
            self.tn[t1] = [c, 3 * t2u + 1, b];
            self.tn[t2] = [a, 3 * t1u + 1, d];
            self.aux[t1].s = [sc, NONE, sb];
            self.aux[t2].s = [sa, NONE, sd];
            self.aux[t1].flat = false;
            self.aux[t2].flat = false;
            for (outer, me) in [
                (c, 3 * t1u),
                (b, 3 * t1u + 2),
                (a, 3 * t2u),
                (d, 3 * t2u + 2),
            ] {
                if outer != NONE {
                    self.tn[(outer / 3) as usize][(outer % 3) as usize] = me;
                }
            }
            for v in [p, u] {
                self.vtri[v as usize] = t1u;
            }
            for v in [q, w] {
                self.vtri[v as usize] = t2u;
            }
            stack.extend_from_slice(&[3 * t1u, 3 * t1u + 2, 3 * t2u, 3 * t2u + 2]);
            self.new_tris.extend_from_slice(&[t1u, t2u]);
        }
        self.rec.flips = stack;
        self.hint = h / 3;
    }

    /// Flips every edge that is not locally Delaunay and is no wall, until none is left (or
    /// the budgets of [`Cdt::legalize`] run out); returns how many edges started a flip.
    ///
    /// Once every edge that is no wall is locally Delaunay the triangulation is constrained
    /// Delaunay, and, when no subsegment is encroached by any vertex, Delaunay, of the float
    /// points as they are, chains bent by rounding included (Shewchuk's lemma: walking from a
    /// triangle toward a vertex inside its circumcircle, the circles of the triangles crossed
    /// keep the vertex up to the first subsegment crossed, which the vertex or that last
    /// triangle's apex then encroaches). An edge that is not locally Delaunay can always be
    /// flipped: a vertex inside the circle across it makes the angles at it and at the apex
    /// sum to more than 180 degrees, so the quadrilateral is strictly convex (the flip checks
    /// it exactly all the same). Flips keep the union of the two triangles, so the domain and
    /// every wall stay as they are.
    pub fn legalize_all(&mut self) -> usize {
        let mut started = 0;
        for t in 0..self.num_slots() {
            if !self.alive(t as u32) || self.is_ghost(t as u32) {
                continue;
            }
            for i in 0..3 {
                let h = (3 * t + i) as u32;
                let tw = self.tn[t][i];
                // Each edge once (from its lower half-edge); walls and open edges stay.
                if self.aux[t].s[i] != NONE || tw == NONE || tw < h || self.is_ghost(tw / 3) {
                    continue;
                }
                let (p, u, w) = (self.tv[t][i], self.tv[t][next(i)], self.tv[t][prev(i)]);
                let q = self.tv[(tw / 3) as usize][(tw % 3) as usize];
                if self
                    .geom
                    .incircle(self.p(p), self.p(u), self.p(w), self.p(q))
                    > 0.0
                {
                    started += 1;
                    self.legalize(h);
                }
            }
        }
        started
    }
}
