//! Mesh optimisation by flips and vertex smoothing (TetGen's `-O<level>/<scheme>` and
//! `-o/<angle>`), run on the finished mesh when asked for ([`super::Options3::optimize_level`]).
//! It gives up the Delaunay property for better dihedral angles, as TetGen's `optimizemesh`
//! does; without it idmesh's meshes stay Delaunay (the paper's §4 refinement and the Delaunay
//! sliver removal of `plc/sliver.rs` are unchanged).
//!
//! A tetrahedron is *bad* when a dihedral angle exceeds the target (`-o/`, default 165°) or is
//! below its supplement. Each pass takes the bad tetrahedra, worst first, and tries:
//! * (scheme bit 1) 2-3 flips across each face and 3-2 flips around each edge of degree three;
//! * (scheme bit 2) moving each of its free vertices (Steiner vertices on no subface and no
//!   subsegment) to the centroid of its link, half way there, or away from the face opposite
//!   it in the worst tetrahedron of its star.
//!
//! Scheme bit 4 (TetGen splits slivers by new points) is not done here: it is the Delaunay
//! sliver removal of `plc/sliver.rs`, which runs before this (with `-q`, and under `-O` with bit
//! 4 also without it, aiming at 180° minus the `o/` target); this pass adds and removes no
//! vertices. What makes the result valid, whatever the floating-point quality figures say:
//! * a change is made only when every new tetrahedron is positively oriented by the exact
//!   [`orient3d`] (a moved vertex: every tetrahedron of its star, which keeps the star's
//!   boundary, so the star is still a triangulation of the same polyhedron);
//! * a subface is never flipped, a subsegment never removed, and the tetrahedra of a flip share
//!   one regional attribute, so the facets, segments and regions are kept;
//! * input vertices and vertices on facets or segments never move;
//! * a change is accepted only when the smallest dihedral angle of the tetrahedra it makes is
//!   not smaller and their largest not larger than those of the tetrahedra it replaces, one of
//!   them strictly better: the mesh's extreme dihedral angles never get worse.
//!
//! Work is bounded: `level` passes (at most [`MAX_LEVEL`]), each over the bad tetrahedra of
//! its start, trying each edge and each vertex at most once, stars larger than [`MAX_STAR`]
//! not smoothed; a pass that changes nothing ends the optimisation. The result is checked by the exact `validate_mesh` without the empty
//! circumsphere test (the mesh is marked [`TetMesh::optimized`]) and is never returned when
//! that check fails.

use super::output::TetMesh;
use super::store::FACE;
use super::NONE;
use crate::error::Error;
use crate::geometry::tet_dihedral_range;
use crate::hash::FastSet;
use crate::predicates::orient3d;
use crate::progress::tick;
use glam::DVec3;

/// The largest optimisation level (number of passes).
pub const MAX_LEVEL: u32 = 10;

/// TetGen's default optimisation scheme: flips, smoothing, vertex insertion and deletion.
pub const DEFAULT_SCHEME: u32 = 7;

/// TetGen's default maximum dihedral angle target of the optimisation, degrees.
pub const DEFAULT_MAX_DIHEDRAL: f64 = 165.0;

/// Stars with more tetrahedra than this are not smoothed (a budget; interior vertices of a
/// quality mesh have a few dozen).
const MAX_STAR: usize = 256;

/// Edges with more tetrahedra around them than this are not removed.
const MAX_RING: usize = 7;

/// The smallest and the largest dihedral angle of a group of tetrahedra.
#[derive(Clone, Copy, Debug)]
struct Range {
    lo: f64,
    hi: f64,
}

impl Range {
    const EMPTY: Range = Range { lo: 180.0, hi: 0.0 };

    fn add(self, c: [[f64; 3]; 4]) -> Range {
        let (lo, hi) = tet_dihedral_range(c);
        Range {
            lo: self.lo.min(lo),
            hi: self.hi.max(hi),
        }
    }

    /// Not worse at either end and better at one.
    fn improves_on(self, old: Range) -> bool {
        self.lo >= old.lo && self.hi <= old.hi && (self.lo > old.lo || self.hi < old.hi)
    }
}

/// What an optimisation did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OptimizeCounts {
    /// Passes run.
    pub passes: u32,
    /// 2-3 flips made.
    pub flips23: usize,
    /// 3-2 flips made.
    pub flips32: usize,
    /// 4-4 flips made.
    pub flips44: usize,
    /// Removals of edges with five or more tetrahedra around them.
    pub edge_removals: usize,
    /// Vertex moves made.
    pub moves: usize,
}

impl OptimizeCounts {
    /// Whether anything changed.
    pub fn changed(&self) -> bool {
        self.flips23 + self.flips32 + self.flips44 + self.edge_removals + self.moves > 0
    }
}

/// Sorted face key.
fn face_key(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

/// Sorted edge key.
fn edge_key(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// Positive in TetGen's sense (`det[b-a, c-a, d-a] > 0`), which is Shewchuk's exact
/// `orient3d < 0`.
fn positive(c: [[f64; 3]; 4]) -> bool {
    orient3d(c[0], c[1], c[2], c[3]) < 0.0
}

/// The optimiser's view of a mesh: its arrays with dead slots, and the constraints.
struct Opt<'a> {
    m: &'a mut TetMesh,
    alive: Vec<bool>,
    free: Vec<u32>,
    /// One live tetrahedron of each vertex (NONE when unused).
    v2t: Vec<u32>,
    subfaces: FastSet<[u32; 3]>,
    subsegs: FastSet<[u32; 2]>,
    /// Vertices that may move: Steiner vertices on no subface and no subsegment.
    free_vertex: Vec<bool>,
    target: f64,
    counts: OptimizeCounts,
    /// Edges and vertices tried in vain in this pass (a budget: each once per pass).
    tried_edges: FastSet<[u32; 2]>,
    tried_vertices: FastSet<u32>,
}

impl Opt<'_> {
    fn corners(&self, tv: [u32; 4]) -> [[f64; 3]; 4] {
        tv.map(|v| self.m.vertices[v as usize])
    }

    fn range_of(&self, ts: &[u32]) -> Range {
        ts.iter().fold(Range::EMPTY, |r, &t| {
            r.add(self.corners(self.m.tets[t as usize]))
        })
    }

    fn attr(&self, t: u32) -> Option<f64> {
        self.m.tet_attributes.get(t as usize).copied()
    }

    /// How bad tetrahedron `t` is (smaller is worse), `None` when it meets the target.
    fn badness(&self, t: u32) -> Option<f64> {
        let (lo, hi) = tet_dihedral_range(self.corners(self.m.tets[t as usize]));
        let score = lo.min(180.0 - hi);
        (hi > self.target || lo < 180.0 - self.target).then_some(score)
    }

    /// Replaces the tetrahedra `old` (a connected group with one attribute) by `new`, which
    /// fill the same polyhedron, relinking neighbours by their shared faces.
    fn replace(&mut self, old: &[u32], new: &[[u32; 4]]) {
        let mut outer: Vec<([u32; 3], u32)> = Vec::with_capacity(4 * old.len());
        for &o in old {
            let tv = self.m.tets[o as usize];
            for (i, f) in FACE.iter().enumerate() {
                let n = self.m.neighbors[o as usize][i];
                if n == NONE || !old.contains(&n) {
                    outer.push((face_key(f.map(|k| tv[k])), n));
                }
            }
        }
        let attr = self.attr(old[0]);
        let mut slots: Vec<u32> = old.iter().copied().take(new.len()).collect();
        for &o in &old[slots.len()..] {
            self.alive[o as usize] = false;
            self.free.push(o);
        }
        while slots.len() < new.len() {
            let s = match self.free.pop() {
                Some(s) => s,
                None => {
                    self.m.tets.push([NONE; 4]);
                    self.m.neighbors.push([NONE; 4]);
                    self.alive.push(false);
                    if let Some(a) = attr {
                        self.m.tet_attributes.push(a);
                    }
                    (self.m.tets.len() - 1) as u32
                }
            };
            slots.push(s);
        }
        for (k, &tv) in new.iter().enumerate() {
            let s = slots[k] as usize;
            self.m.tets[s] = tv;
            self.alive[s] = true;
            if let Some(a) = attr {
                self.m.tet_attributes[s] = a;
            }
            for &v in &tv {
                self.v2t[v as usize] = s as u32;
            }
        }
        for (k, &tv) in new.iter().enumerate() {
            let s = slots[k];
            for (i, f) in FACE.iter().enumerate() {
                let key = face_key(f.map(|q| tv[q]));
                let n = match outer.iter().find(|(fk, _)| *fk == key) {
                    Some(&(_, n)) => {
                        if n != NONE {
                            let nt = self.m.tets[n as usize];
                            if let Some(j) = (0..4).find(|&j| !key.contains(&nt[j])) {
                                self.m.neighbors[n as usize][j] = s;
                            }
                        }
                        n
                    }
                    None => (0..new.len())
                        .find(|&k2| {
                            k2 != k && FACE.iter().any(|g| face_key(g.map(|q| new[k2][q])) == key)
                        })
                        .map_or(NONE, |k2| slots[k2]),
                };
                self.m.neighbors[s as usize][i] = n;
            }
        }
    }

    /// Flips tetrahedron `t` with its neighbour across face `i` into three tetrahedra around
    /// the edge joining their apexes, when allowed and better.
    fn try_flip23(&mut self, t: u32, i: usize) -> bool {
        let tv = self.m.tets[t as usize];
        let [x, y, z] = FACE[i].map(|k| tv[k]);
        let n = self.m.neighbors[t as usize][i];
        if n == NONE || self.subfaces.contains(&face_key([x, y, z])) || self.attr(n) != self.attr(t)
        {
            return false;
        }
        let d = tv[i];
        let Some(&e) = self.m.tets[n as usize]
            .iter()
            .find(|&&v| v != x && v != y && v != z)
        else {
            return false;
        };
        // [x, y, z] is seen counter-clockwise from outside t, so [x, y, z, e] is positive and
        // these three are the positive tetrahedra around the new edge d-e.
        let new = [[x, y, d, e], [y, z, d, e], [z, x, d, e]];
        if !new.iter().all(|&q| positive(self.corners(q))) {
            return false;
        }
        let after = new
            .iter()
            .fold(Range::EMPTY, |r, &q| r.add(self.corners(q)));
        if !after.improves_on(self.range_of(&[t, n])) {
            return false;
        }
        self.replace(&[t, n], &new);
        self.counts.flips23 += 1;
        true
    }

    /// The tetrahedra around edge `a`-`b` of `t` in order, with the third vertex of each face
    /// crossed, or `None` when the fan is open (the edge is on the boundary) or has more than
    /// `limit` tetrahedra.
    fn ring(&self, t: u32, a: u32, b: u32, limit: usize) -> Option<(Vec<u32>, Vec<u32>)> {
        let tv = self.m.tets[t as usize];
        let mut w = *tv.iter().find(|&&v| v != a && v != b)?;
        let (mut ring, mut thirds) = (vec![t], Vec::new());
        let mut cur = t;
        loop {
            let cv = self.m.tets[cur as usize];
            let i = cv.iter().position(|&v| v == w)?;
            let u = *cv.iter().find(|&&v| v != a && v != b && v != w)?;
            thirds.push(u);
            let n = self.m.neighbors[cur as usize][i];
            if n == NONE {
                return None;
            }
            if n == t {
                return Some((ring, thirds));
            }
            if ring.len() >= limit {
                return None;
            }
            ring.push(n);
            (cur, w) = (n, u);
        }
    }

    /// Removes edge `a`-`b` of `t` (edge removal): the `n` tetrahedra around it (at most
    /// [`MAX_RING`], the fan closed inside the domain) are replaced by `2n - 4` tetrahedra
    /// triangulating the ring of their apexes as a fan from one of them (`n = 3`: the 3-2
    /// flip; `n = 4`: the 4-4 flip), when allowed and better.
    fn try_remove_edge(&mut self, t: u32, a: u32, b: u32) -> bool {
        if self.subsegs.contains(&edge_key(a, b)) {
            return false;
        }
        let tv = self.m.tets[t as usize];
        let Some(w0) = tv.iter().copied().find(|&v| v != a && v != b) else {
            return false;
        };
        let Some((ring, thirds)) = self.ring(t, a, b, MAX_RING) else {
            return false;
        };
        let n = ring.len();
        if n < 3
            || thirds
                .iter()
                .any(|&u| self.subfaces.contains(&face_key([a, b, u])))
            || ring.iter().any(|&r| self.attr(r) != self.attr(t))
        {
            return false;
        }
        // The apexes in walk order: w0, then the third vertex of each face crossed (the last
        // is w0 again). Orient the sequence so that [x_k, x_k+1, a, b] is positive: t is
        // [w0, u0, a, b] up to an even permutation, or that is [u0, w0, a, b].
        let mut x: Vec<u32> = std::iter::once(w0)
            .chain(thirds[..n - 1].iter().copied())
            .collect();
        let pos = |v: u32| tv.iter().position(|&u| u == v);
        let (Some(i0), Some(i1), Some(ia), Some(ib)) = (pos(x[0]), pos(x[1]), pos(a), pos(b))
        else {
            return false;
        };
        let perm = [i0, i1, ia, ib];
        let inversions = (0..4)
            .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
            .filter(|&(i, j)| perm[i] > perm[j])
            .count();
        if inversions % 2 == 1 {
            x.reverse();
        }
        let old = self.range_of(&ring);
        let mut best: Option<(Vec<[u32; 4]>, Range)> = None;
        // For n = 3 every fan is the same triangulation.
        for s in 0..if n == 3 { 1 } else { n } {
            let y = |i: usize| x[(s + i) % n];
            let new: Vec<[u32; 4]> = (1..n - 1)
                .flat_map(|k| [[y(0), y(k), y(k + 1), b], [y(k), y(0), y(k + 1), a]])
                .collect();
            if !new.iter().all(|&q| positive(self.corners(q))) {
                continue;
            }
            let after = new
                .iter()
                .fold(Range::EMPTY, |r, &q| r.add(self.corners(q)));
            if after.improves_on(old) && best.as_ref().map_or(true, |(_, b)| after.improves_on(*b))
            {
                best = Some((new, after));
            }
        }
        let Some((new, _)) = best else {
            return false;
        };
        self.replace(&ring, &new);
        match n {
            3 => self.counts.flips32 += 1,
            4 => self.counts.flips44 += 1,
            _ => self.counts.edge_removals += 1,
        }
        true
    }

    /// The tetrahedra around vertex `v` (`None` when it touches the boundary or has more than
    /// [`MAX_STAR`]).
    fn star(&self, v: u32) -> Option<Vec<u32>> {
        let t0 = self.v2t[v as usize];
        if t0 == NONE || !self.alive[t0 as usize] || !self.m.tets[t0 as usize].contains(&v) {
            return None;
        }
        let mut star = vec![t0];
        let mut k = 0;
        while k < star.len() {
            let t = star[k];
            k += 1;
            let tv = self.m.tets[t as usize];
            for (i, &u) in tv.iter().enumerate() {
                if u == v {
                    continue;
                }
                let n = self.m.neighbors[t as usize][i];
                if n == NONE {
                    return None;
                }
                if !star.contains(&n) {
                    if star.len() >= MAX_STAR {
                        return None;
                    }
                    star.push(n);
                }
            }
        }
        Some(star)
    }

    /// The smallest and largest dihedral angle of `star` with `v` at `p`, when every
    /// tetrahedron stays positive.
    fn star_range_at(&self, star: &[u32], v: u32, p: [f64; 3]) -> Option<Range> {
        let mut r = Range::EMPTY;
        for &t in star {
            let c = self.m.tets[t as usize].map(|u| {
                if u == v {
                    p
                } else {
                    self.m.vertices[u as usize]
                }
            });
            if !positive(c) {
                return None;
            }
            r = r.add(c);
        }
        Some(r)
    }

    /// Moves free vertex `v` to a better place, if one of a few candidates is better.
    fn try_smooth(&mut self, v: u32) -> bool {
        let Some(star) = self.star(v) else {
            return false;
        };
        let p = self.m.vertices[v as usize];
        let old = self.range_of(&star);
        let mut link: Vec<u32> = star
            .iter()
            .flat_map(|&t| self.m.tets[t as usize])
            .filter(|&u| u != v)
            .collect();
        link.sort_unstable();
        link.dedup();
        let mut centroid = [0.0; 3];
        for &u in &link {
            let q = self.m.vertices[u as usize];
            for k in 0..3 {
                centroid[k] += q[k] / link.len() as f64;
            }
        }
        let lerp = |s: f64| std::array::from_fn::<f64, 3, _>(|k| p[k] + s * (centroid[k] - p[k]));
        let mut candidates = vec![lerp(1.0), lerp(0.5)];
        // Away from the face opposite v in the worst tetrahedron of the star: raises that
        // tetrahedron's height, the usual cure for a flat one.
        let worst = star.iter().copied().min_by(|&s, &t| {
            let q = |t: u32| {
                let (lo, hi) = tet_dihedral_range(self.corners(self.m.tets[t as usize]));
                lo.min(180.0 - hi)
            };
            q(s).total_cmp(&q(t))
        });
        if let Some(w) = worst {
            let tv = self.m.tets[w as usize];
            if let Some(i) = tv.iter().position(|&u| u == v) {
                let [a, b, c] = FACE[i].map(|k| DVec3::from(self.m.vertices[tv[k] as usize]));
                let nrm = (b - a).cross(c - a);
                let len2 = nrm.length_squared();
                if len2 > 0.0 {
                    // p's offset from the face's plane, along the normal.
                    let h = (DVec3::from(p) - a).dot(nrm) / len2;
                    for s in [0.5, 1.0] {
                        candidates.push((DVec3::from(p) + s * h * nrm).to_array());
                    }
                }
            }
        }
        let mut best: Option<([f64; 3], Range)> = None;
        for q in candidates {
            if !q.iter().all(|x| x.is_finite()) || q == p {
                continue;
            }
            if let Some(r) = self.star_range_at(&star, v, q) {
                if r.improves_on(old) && best.map_or(true, |(_, b)| r.improves_on(b)) {
                    best = Some((q, r));
                }
            }
        }
        let Some((q, _)) = best else {
            return false;
        };
        self.m.vertices[v as usize] = q;
        self.counts.moves += 1;
        true
    }

    /// One pass over the bad tetrahedra; the number of changes.
    fn pass(&mut self, scheme: u32) -> Result<usize, Error> {
        let mut bad: Vec<(f64, u32)> = (0..self.m.tets.len() as u32)
            .filter(|&t| self.alive[t as usize])
            .filter_map(|t| self.badness(t).map(|s| (s, t)))
            .collect();
        bad.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        self.tried_edges.clear();
        self.tried_vertices.clear();
        let total = bad.len() as u64;
        let mut changes = 0;
        for (k, &(_, t)) in bad.iter().enumerate() {
            tick(|| (k as u64, total))?;
            if !self.alive[t as usize] || self.badness(t).is_none() {
                continue;
            }
            if scheme & 1 != 0 && self.flip_around(t) {
                changes += 1;
                continue;
            }
            if scheme & 2 != 0 {
                let tv = self.m.tets[t as usize];
                for v in tv {
                    if self.free_vertex[v as usize]
                        && self.tried_vertices.insert(v)
                        && self.try_smooth(v)
                    {
                        changes += 1;
                        break;
                    }
                }
            }
        }
        Ok(changes)
    }

    /// Tries the flips of tetrahedron `t`: 2-3 across each face, edge removal around each
    /// edge.
    fn flip_around(&mut self, t: u32) -> bool {
        for i in 0..4 {
            if self.try_flip23(t, i) {
                return true;
            }
        }
        let tv = self.m.tets[t as usize];
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            if !self.tried_edges.insert(edge_key(tv[i], tv[j])) {
                continue;
            }
            if self.try_remove_edge(t, tv[i], tv[j]) {
                return true;
            }
        }
        false
    }

    /// Drops the dead slots, renumbering the neighbours.
    fn compact(&mut self) {
        let mut map = vec![NONE; self.m.tets.len()];
        let mut next = 0u32;
        for (t, &a) in self.alive.iter().enumerate() {
            if a {
                map[t] = next;
                next += 1;
            }
        }
        let keep = |t: usize| self.alive[t];
        let m = &mut *self.m;
        let mut k = 0;
        m.tets.retain(|_| {
            k += 1;
            keep(k - 1)
        });
        k = 0;
        m.neighbors.retain(|_| {
            k += 1;
            keep(k - 1)
        });
        if !m.tet_attributes.is_empty() {
            k = 0;
            m.tet_attributes.retain(|_| {
                k += 1;
                keep(k - 1)
            });
        }
        for row in &mut m.neighbors {
            for n in row.iter_mut() {
                if *n != NONE {
                    *n = map[*n as usize];
                }
            }
        }
    }
}

/// Optimises `mesh` in place with `level` passes of the operations in `scheme` (bits: 1 flips,
/// 2 smoothing; 4, sliver splitting, is done before, see the module docs), aiming at dihedral angles between
/// `180 - max_dihedral` and `max_dihedral` degrees; see the module docs. On success the mesh
/// passed the exact check and is marked [`TetMesh::optimized`] when anything changed.
pub(crate) fn optimize(
    mesh: &mut TetMesh,
    level: u32,
    scheme: u32,
    max_dihedral: f64,
) -> Result<OptimizeCounts, Error> {
    let mut o = Opt::new(mesh, max_dihedral);
    for _ in 0..level.min(MAX_LEVEL) {
        o.counts.passes += 1;
        if o.pass(scheme)? == 0 {
            break;
        }
    }
    o.compact();
    let counts = o.counts;
    if counts.changed() {
        mesh.optimized = true;
        super::validate::validate_mesh(mesh)
            .map_err(|e| Error::Internal(format!("after mesh optimisation (-O): {e}")))?;
    }
    Ok(counts)
}

impl<'a> Opt<'a> {
    fn new(mesh: &'a mut TetMesh, target: f64) -> Opt<'a> {
        let nv = mesh.vertices.len();
        let mut constrained = vec![false; nv];
        for v in (0..mesh.num_input_vertices.min(nv)).chain(
            mesh.faces
                .iter()
                .flatten()
                .chain(mesh.edges.iter().flatten())
                .map(|&v| v as usize),
        ) {
            if let Some(c) = constrained.get_mut(v) {
                *c = true;
            }
        }
        let mut v2t = vec![NONE; nv];
        for (t, tv) in mesh.tets.iter().enumerate() {
            for &v in tv {
                v2t[v as usize] = t as u32;
            }
        }
        let subfaces = mesh.faces.iter().map(|&f| face_key(f)).collect();
        let subsegs = mesh.edges.iter().map(|&[a, b]| edge_key(a, b)).collect();
        let n = mesh.tets.len();
        Opt {
            m: mesh,
            alive: vec![true; n],
            free: Vec::new(),
            v2t,
            subfaces,
            subsegs,
            free_vertex: constrained.iter().map(|&c| !c).collect(),
            target,
            counts: OptimizeCounts::default(),
            tried_edges: FastSet::default(),
            tried_vertices: FastSet::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two tetrahedra glued on the triangle x y z (at z = 0), apexes d below and e above at
    /// height `h` over its centroid; or the three tetrahedra around d-e.
    fn bipyramid(h: f64, three: bool) -> TetMesh {
        let s = 3f64.sqrt();
        let vertices = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, s / 2.0, 0.0],
            [0.5, s / 6.0, -h],
            [0.5, s / 6.0, h],
        ];
        let (x, y, z, d, e) = (0, 1, 2, 3, 4);
        let (tets, neighbors) = if three {
            (
                vec![[x, y, d, e], [y, z, d, e], [z, x, d, e]],
                // Face 0 of [x y d e] is y d e, shared with [y z d e] (its face 1, opposite z).
                vec![[1, 2, NONE, NONE], [2, 0, NONE, NONE], [0, 1, NONE, NONE]],
            )
        } else {
            (
                vec![[y, x, z, d], [x, y, z, e]],
                vec![[NONE, NONE, NONE, 1], [NONE, NONE, NONE, 0]],
            )
        };
        let n = tets.len();
        TetMesh {
            vertex_markers: vec![0; 5],
            num_input_vertices: 5,
            vertices,
            tets,
            neighbors,
            complete: true,
            tet_attributes: vec![1.0; n],
            // Not Delaunay in general: checked without empty circumspheres.
            optimized: true,
            ..TetMesh::default()
        }
    }

    fn range(m: &TetMesh) -> Range {
        (0..m.tets.len()).fold(Range::EMPTY, |r, t| r.add(m.corners(t)))
    }

    #[test]
    fn flips_2_3_and_3_2_go_to_the_better_configuration_and_stay_valid() {
        let mut tried = 0;
        for h in [0.05, 0.2, 0.5, 1.0, 3.0] {
            let (two, three) = (bipyramid(h, false), bipyramid(h, true));
            two.validate().unwrap();
            three.validate().unwrap();
            let (r2, r3) = (range(&two), range(&three));
            for (mut m, better) in [(two, r3.improves_on(r2)), (three, r2.improves_on(r3))] {
                let before = m.tets.len();
                let mut o = Opt::new(&mut m, 90.0);
                let done = if before == 2 {
                    o.try_flip23(1, 3)
                } else {
                    o.try_remove_edge(0, 3, 4)
                };
                o.compact();
                assert_eq!(done, better, "h = {h}, {before} tets: {r2:?} vs {r3:?}");
                if done {
                    tried += 1;
                    assert_eq!(m.tets.len(), 5 - before);
                    m.optimized = true;
                    m.validate().unwrap();
                    assert_eq!(m.tet_attributes, vec![1.0; m.tets.len()]);
                }
            }
        }
        assert!(tried >= 2, "both directions should occur: {tried}");
    }

    #[test]
    fn constrained_faces_and_edges_are_not_flipped() {
        let (mut faces_kept, mut edges_kept) = (0, 0);
        for h in [0.05, 0.2, 0.5, 1.0, 3.0] {
            if Opt::new(&mut bipyramid(h, false), 90.0).try_flip23(1, 3) {
                let mut two = bipyramid(h, false);
                two.faces = vec![[0, 2, 1]];
                two.face_markers = vec![1];
                assert!(!Opt::new(&mut two, 90.0).try_flip23(1, 3), "h = {h}");
                faces_kept += 1;
            }
            if Opt::new(&mut bipyramid(h, true), 90.0).try_remove_edge(0, 3, 4) {
                let mut three = bipyramid(h, true);
                three.edges = vec![[4, 3]];
                three.edge_markers = vec![1];
                assert!(
                    !Opt::new(&mut three, 90.0).try_remove_edge(0, 3, 4),
                    "h = {h}"
                );
                let mut three = bipyramid(h, true);
                three.faces = vec![[0, 3, 4]];
                three.face_markers = vec![1];
                assert!(
                    !Opt::new(&mut three, 90.0).try_remove_edge(0, 3, 4),
                    "h = {h}"
                );
                let mut three = bipyramid(h, true);
                three.tet_attributes[2] = 2.0;
                assert!(
                    !Opt::new(&mut three, 90.0).try_remove_edge(0, 3, 4),
                    "h = {h}"
                );
                edges_kept += 1;
            }
        }
        assert!(
            faces_kept > 0 && edges_kept > 0,
            "{faces_kept} {edges_kept}"
        );
    }

    #[test]
    fn a_free_vertex_moves_to_a_better_place_and_input_vertices_do_not() {
        // The centre of a regular-ish octahedron, pushed towards one corner: smoothing moves
        // it back; marked as an input vertex it stays.
        let mut vertices = vec![
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ];
        vertices.push([0.6, 0.1, 0.05]);
        let c = 6u32;
        // The eight faces of the octahedron, each seen counter-clockwise from outside.
        let faces = [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        let tets: Vec<[u32; 4]> = faces.iter().map(|f| [f[0], f[2], f[1], c]).collect();
        let mut m = TetMesh {
            vertex_markers: vec![0; 7],
            num_input_vertices: 6,
            vertices,
            neighbors: vec![[NONE; 4]; 8],
            tets,
            complete: true,
            ..TetMesh::default()
        };
        for t in 0..8 {
            assert!(positive(m.corners(t)), "tet {t}");
        }
        // Neighbours by shared faces.
        for t in 0..8 {
            for (i, f) in FACE.iter().enumerate() {
                let key = face_key(f.map(|k| m.tets[t][k]));
                m.neighbors[t][i] = (0..8)
                    .find(|&u| {
                        u != t
                            && FACE
                                .iter()
                                .any(|g| face_key(g.map(|k| m.tets[u][k])) == key)
                    })
                    .map_or(NONE, |u| u as u32);
            }
        }
        m.validate().unwrap();
        let before = range(&m);
        let mut input = m.clone();
        input.num_input_vertices = 7;
        let mut o = Opt::new(&mut m, 90.0);
        assert_eq!(o.star(c).map(|s| s.len()), Some(8));
        assert!(o.free_vertex[6]);
        assert!(o.try_smooth(c), "the off-centre vertex should move");
        let after = range(&m);
        assert!(after.improves_on(before), "{after:?} vs {before:?}");
        assert_ne!(m.vertices[6], [0.6, 0.1, 0.05]);
        m.optimized = true;
        m.validate().unwrap();
        let counts = optimize(&mut input, 3, 2, 90.0).unwrap();
        assert!(!counts.changed(), "an input vertex never moves");
        assert_eq!(input.vertices[6], [0.6, 0.1, 0.05]);
    }
}
