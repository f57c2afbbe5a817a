//! Editing a carved store (TetGen's `-Y`, keeping the input surface): deleting the tets outside
//! the domain, replacing a group of tets by another tetrahedralization of the same region, and
//! inserting points without crossing walls (subfaces) once the tetrahedralization is no longer
//! Delaunay.
//!
//! Every edit is checked exactly before anything changes, so a rejected edit leaves the store
//! as it was.

use super::{
    get_state, neighbor_ref, set_state, TetId, Tets, VertexId, DEAD, FACE, GHOST, IN_CAVITY,
    TESTED_OUT,
};
use crate::hash::FastMap;
use crate::mesh3d::NONE;
use crate::predicates::{orient3d, orient3d_fast};

/// Why [`Tets::replace`] refused an edit (the store is unchanged).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReplaceError {
    /// New tet `k` (an index into the new tets) is flat or inverted.
    Inverted(usize),
    /// The new tets do not fill the old region exactly; the message names the face.
    Mismatch(String),
}

/// Whether `b` lists the vertices of `a` in the same cyclic order.
fn same_cycle(a: [VertexId; 3], b: [VertexId; 3]) -> bool {
    b == a || b == [a[1], a[2], a[0]] || b == [a[2], a[0], a[1]]
}

fn sorted(mut f: [VertexId; 3]) -> [VertexId; 3] {
    f.sort_unstable();
    f
}

impl Tets {
    /// Deletes every live tet for which `keep` is false (ghosts must not be kept): the faces
    /// the kept tets shared with deleted ones become open. Vertices that no kept tet uses leave
    /// the tetrahedralization.
    pub fn carve(&mut self, keep: impl Fn(TetId) -> bool) {
        self.clear_cavity();
        let n = self.tets.len();
        let kept: Vec<bool> = (0..n as TetId)
            .map(|t| self.alive(t) && !self.is_ghost(t) && keep(t))
            .collect();
        for (t, &k) in kept.iter().enumerate() {
            if !self.alive(t as TetId) {
                continue;
            }
            if k {
                for h in self.tets[t].n.iter_mut() {
                    if *h != NONE && !kept[(*h >> 2) as usize] {
                        *h = NONE;
                    }
                }
            } else {
                self.tets[t] = DEAD;
                self.free.push(t as TetId);
                self.live -= 1;
            }
        }
        self.ghost_tet = NONE;
        self.vtet.iter_mut().for_each(|x| *x = NONE);
        for (t, &k) in kept.iter().enumerate() {
            if k {
                for v in self.tets[t].v {
                    self.vtet[v as usize] = t as TetId;
                }
            }
        }
    }

    /// Replaces the live real tets `old` by new tets on the vertex quadruples `new` (no
    /// [`GHOST`]; every vertex pushed). The new tets must fill exactly the region of the old
    /// ones, which is checked exactly before anything changes:
    /// * every new tet is positively oriented;
    /// * each face of a new tet is shared with exactly one other new tet, in the opposite
    ///   orientation; or it is a face of the old region's boundary, in the same orientation
    ///   as there (it then takes over the neighbour outside); or it is listed in `open` (a new
    ///   open face, where the old region had open faces);
    /// * every boundary face of the old region that has a tet outside it is matched.
    ///
    /// A vertex of the old tets that no new tet uses leaves the tetrahedralization: it must not
    /// be used by any other tet either. Returns the new tets, in the order of `new`.
    pub fn replace(
        &mut self,
        old: &[TetId],
        new: &[[VertexId; 4]],
        open: &[[VertexId; 3]],
    ) -> Result<Vec<TetId>, ReplaceError> {
        self.clear_cavity();
        let mism = |m: String| Err(ReplaceError::Mismatch(m));
        let mut olds: Vec<TetId> = old.to_vec();
        olds.sort_unstable();
        olds.dedup();
        if olds.len() != old.len() {
            return mism("a tet is listed twice among the old ones".into());
        }
        for &t in &olds {
            if t as usize >= self.tets.len() || !self.alive(t) || self.is_ghost(t) {
                return mism(format!("old tet {t} is not a live real tet"));
            }
        }
        let is_old = |t: TetId| olds.binary_search(&t).is_ok();
        // The old region's boundary: sorted face -> (face as seen from inside, outside ref).
        let mut boundary: FastMap<[VertexId; 3], ([VertexId; 3], u32, bool)> = FastMap::default();
        for &t in &olds {
            let tet = self.tets[t as usize];
            for (f, fv) in FACE.iter().enumerate() {
                let h = tet.n[f];
                if h != NONE && is_old(h >> 2) {
                    continue;
                }
                let face = fv.map(|i| tet.v[i]);
                if boundary.insert(sorted(face), (face, h, false)).is_some() {
                    return mism(format!(
                        "face {face:?} is twice on the old region's boundary"
                    ));
                }
            }
        }
        for (k, q) in new.iter().enumerate() {
            if q.iter()
                .any(|&v| v == GHOST || v as usize >= self.pts.len())
            {
                return mism(format!(
                    "new tet {k} {q:?} has a vertex that is not a point"
                ));
            }
            let [a, b, c, d] = q.map(|v| self.pts[v as usize]);
            if orient3d(a, b, c, d) >= 0.0 {
                return Err(ReplaceError::Inverted(k));
            }
        }
        // New faces: sorted face -> the (up to two) half-faces `4k + f` holding it.
        let mut faces: FastMap<[VertexId; 3], [u32; 2]> = FastMap::default();
        for (k, q) in new.iter().enumerate() {
            for (f, fv) in FACE.iter().enumerate() {
                let face = fv.map(|i| q[i]);
                let e = faces.entry(sorted(face)).or_insert([NONE, NONE]);
                let h = neighbor_ref(k as TetId, f);
                if e[0] == NONE {
                    e[0] = h;
                } else if e[1] == NONE {
                    e[1] = h;
                } else {
                    return mism(format!("face {face:?} is in three new tets"));
                }
            }
        }
        let face_of = |h: u32| FACE[(h & 3) as usize].map(|i| new[(h >> 2) as usize][i]);
        for (key, hs) in &faces {
            if hs[1] != NONE {
                let (f0, f1) = (face_of(hs[0]), face_of(hs[1]));
                if !same_cycle(f0, [f1[0], f1[2], f1[1]]) {
                    return mism(format!("new tets on both sides of {f0:?} overlap"));
                }
                if boundary.contains_key(key) {
                    return mism(format!(
                        "face {f0:?} is inside the new region but on the old boundary"
                    ));
                }
            } else if let Some(b) = boundary.get_mut(key) {
                if !same_cycle(face_of(hs[0]), b.0) {
                    return mism(format!("new face {:?} is reversed", face_of(hs[0])));
                }
                b.2 = true;
            } else if !open.iter().any(|o| sorted(*o) == *key) {
                return mism(format!("new face {:?} matches nothing", face_of(hs[0])));
            }
        }
        if let Some((_, (face, _, _))) = boundary.iter().find(|(_, b)| !b.2 && b.1 != NONE) {
            return mism(format!("the old boundary face {face:?} is not covered"));
        }

        // Checked: commit.
        let mut old_verts: Vec<VertexId> = Vec::with_capacity(4 * olds.len());
        for &t in &olds {
            old_verts.extend_from_slice(&self.tets[t as usize].v);
            self.tets[t as usize] = DEAD;
            self.free.push(t);
            self.live -= 1;
        }
        let ids: Vec<TetId> = new.iter().map(|_| self.alloc()).collect();
        for (k, q) in new.iter().enumerate() {
            let t = ids[k] as usize;
            self.tets[t].v = *q;
            self.tets[t].n = [NONE; 4];
        }
        let real = |h: u32| neighbor_ref(ids[(h >> 2) as usize], (h & 3) as usize);
        for (key, hs) in &faces {
            let h0 = real(hs[0]);
            if hs[1] != NONE {
                let h1 = real(hs[1]);
                self.tets[(h0 >> 2) as usize].n[(h0 & 3) as usize] = h1;
                self.tets[(h1 >> 2) as usize].n[(h1 & 3) as usize] = h0;
            } else if let Some(&(_, out, _)) = boundary.get(key) {
                self.tets[(h0 >> 2) as usize].n[(h0 & 3) as usize] = out;
                if out != NONE {
                    self.tets[(out >> 2) as usize].n[(out & 3) as usize] = h0;
                }
            }
        }
        for v in old_verts {
            self.vtet[v as usize] = NONE;
        }
        for &t in &ids {
            for v in self.tets[t as usize].v {
                self.vtet[v as usize] = t;
            }
        }
        Ok(ids)
    }

    /// Walks from `start` towards `p` through faces that `p` lies strictly beyond, never
    /// through an open face or a face for which `wall` is true. Returns the tet whose closure
    /// contains `p`; `None` when the walk is blocked (`p` lies beyond a wall or an open face
    /// from where the walk stands), runs out of its budget (a non-Delaunay tetrahedralization
    /// can make a walk circle), or `p` is a vertex.
    pub fn locate_walled(
        &self,
        p: [f64; 3],
        start: TetId,
        wall: &dyn Fn([VertexId; 3]) -> bool,
    ) -> Option<TetId> {
        if start as usize >= self.tets.len() || !self.alive(start) || self.is_ghost(start) {
            return None;
        }
        let mut t = start;
        let mut came_from = 4usize;
        let budget = 64 + self.tets.len();
        'walk: for step in 0..budget {
            let tet = &self.tets[t as usize];
            if let Some(f) = self.exit_face(t, came_from, step, p) {
                let h = tet.n[f];
                if h == NONE || wall(FACE[f].map(|i| tet.v[i])) {
                    return None;
                }
                t = h >> 2;
                came_from = (h & 3) as usize;
                continue 'walk;
            }
            if tet.v.iter().any(|&x| self.point(x) == p) {
                return None;
            }
            return Some(t);
        }
        None
    }

    /// The cavity of `p` in a carved tetrahedralization that need not be Delaunay: the tets in
    /// conflict with `p` reachable from `start` (which must contain `p`) without crossing an
    /// open face or a face for which `wall` is true, shrunk until `p` sees every face of the
    /// cavity's boundary strictly from inside (a tet with a boundary face `p` does not see is
    /// dropped, again and again). Joining `p` to the boundary then gives positive tets only, so
    /// the cavity is a ball, star-shaped from `p`. Returns `false` (cavity empty) when `start`
    /// does not conflict with `p` or had to be dropped (`p` on a wall or an open face). Follow
    /// with [`Tets::commit_cavity`] or [`Tets::cancel_cavity`].
    pub fn find_cavity_walled(
        &mut self,
        p: [f64; 3],
        start: TetId,
        wall: &dyn Fn([VertexId; 3]) -> bool,
    ) -> bool {
        self.clear_cavity();
        self.pending = true;
        self.cavity_point = p;
        if start as usize >= self.tets.len()
            || !self.alive(start)
            || self.is_ghost(start)
            || !self.conflict(start, p)
        {
            return false;
        }
        let mut tested: Vec<TetId> = Vec::new();
        set_state(&mut self.state, start as usize, IN_CAVITY);
        self.cavity.push(start);
        let mut i = 0;
        while i < self.cavity.len() {
            let t = self.cavity[i];
            i += 1;
            let tet = self.tets[t as usize];
            for (&h, fv) in tet.n.iter().zip(FACE.iter()) {
                if h == NONE {
                    continue;
                }
                let u = (h >> 2) as usize;
                if get_state(&self.state, u) != 0 || wall(fv.map(|k| tet.v[k])) {
                    continue;
                }
                if self.conflict(u as TetId, p) {
                    set_state(&mut self.state, u, IN_CAVITY);
                    self.cavity.push(u as TetId);
                } else {
                    set_state(&mut self.state, u, TESTED_OUT);
                    tested.push(u as TetId);
                }
            }
        }
        // A face is inside the cavity when the tet across is in it and no wall separates them.
        let inner = |s: &Tets, t: TetId, f: usize| {
            let tet = &s.tets[t as usize];
            let h = tet.n[f];
            h != NONE
                && get_state(&s.state, (h >> 2) as usize) == IN_CAVITY
                && !wall(FACE[f].map(|k| tet.v[k]))
        };
        // Each pass drops at least one tet, so the passes are bounded by the cavity's size.
        let mut ok = true;
        loop {
            let mut dropped = false;
            let mut k = 0;
            while k < self.cavity.len() {
                let t = self.cavity[k];
                let tet = self.tets[t as usize];
                let sees_all = (0..4).all(|f| {
                    if inner(self, t, f) {
                        return true;
                    }
                    let [a, b, c] = FACE[f].map(|i| self.point(tet.v[i]));
                    orient3d_fast(a, b, c, p) > 0.0
                });
                if sees_all {
                    k += 1;
                    continue;
                }
                if t == start {
                    ok = false;
                }
                set_state(&mut self.state, t as usize, TESTED_OUT);
                tested.push(t);
                self.cavity.swap_remove(k);
                dropped = true;
            }
            if !dropped || !ok {
                break;
            }
        }
        for &t in &tested {
            set_state(&mut self.state, t as usize, 0);
        }
        if !ok {
            for &t in &self.cavity {
                set_state(&mut self.state, t as usize, 0);
            }
            self.cavity.clear();
            return false;
        }
        for k in 0..self.cavity.len() {
            let t = self.cavity[k];
            for f in 0..4 {
                if !inner(self, t, f) {
                    self.boundary.push(neighbor_ref(t, f));
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A store over `pts` (the first four not coplanar), every point inserted.
    fn build(pts: &[[f64; 3]]) -> Tets {
        let mut s = Tets::with_capacity(pts.len());
        for &p in pts {
            s.push_vertex(p);
        }
        s.init(0, 1, 2, 3);
        for v in 4..pts.len() as u32 {
            s.insert(v, 0).unwrap();
        }
        s
    }

    fn cube_with_centre() -> Tets {
        let mut pts = Vec::new();
        for z in [0.0, 1.0] {
            for y in [0.0, 1.0] {
                for x in [0.0, 1.0] {
                    pts.push([x, y, z]);
                }
            }
        }
        pts.swap(3, 4); // corners 0, 1, 2, 4 first: not coplanar
        pts.push([0.5, 0.5, 0.5]);
        build(&pts)
    }

    fn real_tets(s: &Tets) -> Vec<TetId> {
        (0..s.num_slots() as TetId)
            .filter(|&t| s.alive(t) && !s.is_ghost(t))
            .collect()
    }

    fn volume(s: &Tets) -> f64 {
        real_tets(s)
            .iter()
            .map(|&t| crate::geometry::tet_volume(s.verts(t).map(|v| s.point(v))).abs())
            .sum()
    }

    #[test]
    fn carve_opens_the_hull_faces() {
        let mut s = cube_with_centre();
        s.carve(|_| true);
        s.check_structure().unwrap();
        let open = real_tets(&s)
            .iter()
            .map(|&t| (0..4).filter(|&f| s.neighbor(t, f).0 == NONE).count())
            .sum::<usize>();
        assert_eq!(open, 12, "two open triangles per side of the cube");
        assert!((volume(&s) - 1.0).abs() < 1e-12);
        assert_eq!(s.vertex_tet(GHOST), NONE);
    }

    #[test]
    fn replace_removes_an_interior_point_by_coning_from_a_corner() {
        // A tetrahedron with a point inside: its star is four tets, one per face.
        let mut s = build(&[
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [0.0, 4.0, 0.0],
            [0.0, 0.0, 4.0],
            [1.0, 1.0, 1.0],
        ]);
        s.carve(|_| true);
        let mut star = Vec::new();
        s.star(4, &mut star);
        assert_eq!(star.len(), 4);
        let new: Vec<[u32; 4]> = star
            .iter()
            .map(|&t| s.verts(t))
            .filter(|v| !v.contains(&0))
            .map(|v| v.map(|x| if x == 4 { 0 } else { x }))
            .collect();
        let ids = s.replace(&star, &new, &[]).unwrap();
        assert_eq!(ids.len(), 1);
        s.check_structure().unwrap();
        assert_eq!(
            s.vertex_tet(4),
            NONE,
            "the point left the tetrahedralization"
        );
        assert_eq!(real_tets(&s).len(), 1);
        assert!((volume(&s) - 32.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn replace_refuses_overlaps_and_holes_without_changing_anything() {
        let mut s = cube_with_centre();
        s.carve(|_| true);
        let mut star = Vec::new();
        s.star(8, &mut star);
        let before: Vec<[u32; 4]> = real_tets(&s).iter().map(|&t| s.verts(t)).collect();
        // Leaving a tet out uncovers a face.
        let mut new: Vec<[u32; 4]> = star.iter().map(|&t| s.verts(t)).collect();
        new.pop();
        assert!(matches!(
            s.replace(&star, &new, &[]),
            Err(ReplaceError::Mismatch(_))
        ));
        // A tet listed twice overlaps itself.
        let mut twice: Vec<[u32; 4]> = star.iter().map(|&t| s.verts(t)).collect();
        twice.push(twice[0]);
        assert!(s.replace(&star, &twice, &[]).is_err());
        // Moving the centre outside the cube inverts some tets.
        let w = s.push_vertex([0.5, 0.5, 1.5]);
        let moved: Vec<[u32; 4]> = star
            .iter()
            .map(|&t| s.verts(t).map(|x| if x == 8 { w } else { x }))
            .collect();
        assert!(matches!(
            s.replace(&star, &moved, &[]),
            Err(ReplaceError::Inverted(_))
        ));
        let after: Vec<[u32; 4]> = real_tets(&s).iter().map(|&t| s.verts(t)).collect();
        assert_eq!(before, after);
        s.check_structure().unwrap();
        // Moving it inside is fine.
        let w = s.push_vertex([0.4, 0.55, 0.5]);
        let moved: Vec<[u32; 4]> = star
            .iter()
            .map(|&t| s.verts(t).map(|x| if x == 8 { w } else { x }))
            .collect();
        s.replace(&star, &moved, &[]).unwrap();
        s.check_structure().unwrap();
        assert!((volume(&s) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn walled_insertion_stays_behind_walls_and_keeps_the_mesh_valid() {
        let mut s = cube_with_centre();
        s.carve(|_| true);
        // Walls: faces lying in the plane x = y.
        let pts: Vec<[f64; 3]> = (0..s.num_vertices() as u32).map(|v| s.point(v)).collect();
        let wall = move |f: [u32; 3]| f.iter().all(|&v| pts[v as usize][0] == pts[v as usize][1]);
        let p = [0.3, 0.6, 0.45];
        let start = real_tets(&s)
            .into_iter()
            .find(|&t| {
                let c = s.verts(t).map(|v| s.point(v));
                (0..4).all(|f| {
                    let [a, b, cc] = FACE[f].map(|i| c[i]);
                    orient3d(a, b, cc, p) >= 0.0
                })
            })
            .unwrap();
        let at = s.locate_walled(p, start, &wall).unwrap();
        assert!(s.find_cavity_walled(p, at, &wall));
        assert!(!s.cavity().is_empty());
        for &t in s.cavity() {
            for (f, fv) in FACE.iter().enumerate() {
                let (n, _) = s.neighbor(t, f);
                if wall(fv.map(|i| s.verts(t)[i])) {
                    assert!(n == NONE || !s.in_cavity(n), "the cavity crossed a wall");
                }
            }
        }
        let v = s.push_vertex(p);
        s.commit_cavity(v);
        s.check_structure().unwrap();
        assert!((volume(&s) - 1.0).abs() < 1e-12);
        // A point outside the cube is not reached, nor is an existing vertex.
        let from = s.vertex_tet(v);
        assert_eq!(s.locate_walled([0.5, 0.5, 2.0], from, &|_| false), None);
        assert_eq!(s.locate_walled(p, from, &|_| false), None);
    }
}
