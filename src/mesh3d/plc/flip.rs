//! Lawson flips once the surface is kept (`-Y`): taking the boundary Steiner points off the
//! surface leaves tets that are not Delaunay; flipping the faces that are not locally Delaunay
//! (2-3 and 3-2 flips, never removing a subface or subsegment) brings the tetrahedralization
//! back towards the constrained Delaunay one, with better tets and cavities that behave.

use super::Mesher;
use crate::mesh3d::store::FACE;
use crate::mesh3d::NONE;
use crate::predicates::orient3d;

impl Mesher<'_> {
    /// Flips every face that is not locally Delaunay (the vertex across it lies strictly inside
    /// the tet's circumsphere) and is not a subface, when a 2-3 or 3-2 flip can without making
    /// the worst tet involved worse, until none is left or none can be flipped. Each flip
    /// lowers the lifted tetrahedralization, so this ends; a budget guards it anyway. Returns
    /// the number of flips.
    pub(super) fn delaunay_flips(&mut self) -> usize {
        self.flips(true)
    }

    /// [`Mesher::delaunay_flips`], with `guard` whether a flip may not make the worst shape
    /// worse (off: every flip that removes a non-Delaunay face, as after moving points by a
    /// rounding in `plc/frame.rs`).
    pub(super) fn flips(&mut self, guard: bool) -> usize {
        let mut stack: Vec<(u32, [u32; 4])> = (0..self.tets.num_slots() as u32)
            .filter(|&t| self.tets.alive(t))
            .map(|t| (t, self.tets.verts(t)))
            .collect();
        let budget = 64 * stack.len() + 1024;
        let mut flips = 0;
        for _ in 0..budget {
            let Some((t, vs)) = stack.pop() else {
                break;
            };
            if !self.tets.alive(t) || self.tets.verts(t) != vs {
                continue;
            }
            for f in 0..4 {
                if let Some(new) = self.try_flip(t, f, guard) {
                    flips += 1;
                    stack.extend(new.into_iter().map(|u| (u, self.tets.verts(u))));
                    break;
                }
            }
        }
        flips
    }

    /// Flips face `f` of tet `t` if it is not locally Delaunay, not a subface, and a 2-3 flip
    /// (the union of the two tets is convex across it) or a 3-2 flip (an edge of it has exactly
    /// three tets around it, and is no subsegment) can remove it. Returns the new tets.
    fn try_flip(&mut self, t: u32, f: usize, guard: bool) -> Option<Vec<u32>> {
        let vs = self.tets.verts(t);
        let (n, g) = self.tets.neighbor(t, f);
        if n == NONE || self.tets.is_ghost(t) || self.tets.is_ghost(n) {
            return None;
        }
        let [a, b, c] = FACE[f].map(|k| vs[k]);
        if self.feat.subface([a, b, c]).is_some() {
            return None;
        }
        let (d, e) = (vs[f], self.tets.verts(n)[g]);
        let pts = &self.pts;
        let p = |v: u32| pts[v as usize];
        if !self.tets.conflict(t, p(e)) {
            return None;
        }
        let reg = self.region_of(t);
        // 2-3: the segment de crosses the triangle abc.
        let s = [(a, b), (b, c), (c, a)].map(|(x, y)| orient3d(p(d), p(e), p(x), p(y)));
        if s.iter().all(|&x| x > 0.0) || s.iter().all(|&x| x < 0.0) {
            let new: Vec<[u32; 4]> = [(a, b), (b, c), (c, a)]
                .iter()
                .map(|&(x, y)| positive([d, e, x, y], &p))
                .collect();
            return self.commit_flip(&[t, n], &new, reg, guard);
        }
        // 3-2: an edge xy of abc around which t, n and one more tet (x, y, d, e) are all.
        let mut cands: Vec<(u32, [[u32; 4]; 2])> = Vec::new();
        for (x, y, z) in [(a, b, c), (b, c, a), (c, a, b)] {
            if self.feat.subseg(x, y).is_some()
                || self.feat.subface([x, y, d]).is_some()
                || self.feat.subface([x, y, e]).is_some()
            {
                continue;
            }
            let iz = vs.iter().position(|&v| v == z)?;
            let (m, _) = self.tets.neighbor(t, iz);
            if m == NONE {
                continue;
            }
            let mv = self.tets.verts(m);
            if ![x, y, d, e].iter().all(|v| mv.contains(v)) {
                continue;
            }
            cands.push((m, [positive([z, d, e, x], &p), positive([z, d, e, y], &p)]));
        }
        cands
            .into_iter()
            .find_map(|(m, new)| self.commit_flip(&[t, n, m], &new, reg, guard))
    }

    /// Replaces `old` by `new` (checked exactly by [`crate::mesh3d::store::Tets::replace`])
    /// unless that makes the worst of their shapes worse: Delaunay flips among nearly
    /// coplanar surface vertices would otherwise glue flat tets onto the surface. The new tets
    /// get region `reg`.
    fn commit_flip(
        &mut self,
        old: &[u32],
        new: &[[u32; 4]],
        reg: u32,
        guard: bool,
    ) -> Option<Vec<u32>> {
        let shape = |q: [u32; 4]| crate::geometry::tet_shape(q.map(|v| self.pts[v as usize]));
        let before = old
            .iter()
            .map(|&t| shape(self.tets.verts(t)))
            .fold(f64::INFINITY, f64::min);
        let after = new.iter().map(|&q| shape(q)).fold(f64::INFINITY, f64::min);
        if guard && after < before {
            return None;
        }
        let ids = self.tets.replace(old, new, &[]).ok()?;
        for &u in &ids {
            self.set_region(u, reg);
        }
        Some(ids)
    }
}

/// The tet on these vertices in the kernel's positive order (a flat one stays as it is and
/// is refused later).
fn positive(mut q: [u32; 4], p: &dyn Fn(u32) -> [f64; 3]) -> [u32; 4] {
    if orient3d(p(q[0]), p(q[1]), p(q[2]), p(q[3])) > 0.0 {
        q.swap(0, 1);
    }
    q
}
