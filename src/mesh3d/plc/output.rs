//! The mesher's result: the tetrahedra inside the domain with their regions, the boundary
//! and constraint faces and edges with their markers, and the rounding slivers left out or
//! split away (paper §4, §6).

use super::*;

impl Mesher<'_> {
    /// Rounding slivers at the domain's boundary, which the output leaves out: tets inside
    /// the domain whose four vertices lie on one facet (flat in exact terms; Steiner points
    /// rounded off a slanted facet make them) and that touch the outside, directly or through
    /// other such slivers. Their other faces, which lie in the same facet, become the
    /// boundary. Slivers elsewhere (on internal facets: dropping them would tear the mesh
    /// apart) are split away after refinement (see [`Mesher::interior_flat_slivers`]).
    pub(super) fn rounding_slivers_on_boundary(&self) -> crate::hash::FastSet<u32> {
        let mut cand: Vec<u32> = (0..self.tets.num_slots() as u32)
            .filter(|&t| {
                self.tets.alive(t)
                    && !self.tets.is_ghost(t)
                    && self.region[t as usize] != OUTSIDE
                    && self.feat.in_one_facet(self.tets.verts(t))
            })
            .collect();
        let mut dropped = crate::hash::FastSet::default();
        loop {
            let before = dropped.len();
            cand.retain(|&t| {
                let out = (0..4).any(|f| {
                    let n = self.tets.neighbor(t, f).0;
                    n == NONE
                        || self.tets.is_ghost(n)
                        || self.region[n as usize] == OUTSIDE
                        || dropped.contains(&n)
                });
                if out {
                    dropped.insert(t);
                }
                !out
            });
            if dropped.len() == before {
                return dropped;
            }
        }
    }

    /// A subface of each rounding sliver (all four vertices on one facet plane) whose four
    /// neighbours are all in the domain.
    pub(super) fn interior_flat_slivers(&self) -> Result<Vec<([u32; 3], u32)>, Error> {
        let inside = |t: u32| !self.tets.is_ghost(t) && self.region_of(t) < UNKNOWN;
        let mut out = Vec::new();
        for t in 0..self.tets.num_slots() as u32 {
            tick(|| (self.steiner, self.steiner))?;
            if !self.tets.alive(t) || !inside(t) {
                continue;
            }
            let vs = self.tets.verts(t);
            if !self.feat.in_one_facet(vs) || !(0..4).all(|f| inside(self.tets.neighbor(t, f).0)) {
                continue;
            }
            if let Some((fv, fid)) = (0..4).find_map(|f| {
                let fv = face_of(vs, f);
                self.feat.subface(fv).map(|fid| (fv, fid))
            }) {
                out.push((fv, fid));
            }
        }
        Ok(out)
    }

    pub(super) fn output(&self, plc: &Plc) -> Result<TetMesh, Error> {
        let ns = self.tets.num_slots();
        let dropped = self.rounding_slivers_on_boundary();
        let mut index = vec![NONE; ns];
        let mut tets = Vec::new();
        let mut slots = Vec::new();
        // Progress: four passes over at most `ns` tets.
        let work = |pass: usize, i: usize| ((pass * ns + i) as u64, 4 * ns as u64);
        for t in 0..ns as u32 {
            tick(|| work(0, t as usize))?;
            if self.tets.alive(t)
                && !self.tets.is_ghost(t)
                && self.region[t as usize] != OUTSIDE
                && !dropped.contains(&t)
            {
                index[t as usize] = tets.len() as u32;
                let mut v = self.tets.verts(t);
                let c = v.map(|x| self.pts[x as usize]);
                // Shewchuk's orient3d is positive for det[b-a, c-a, d-a] < 0.
                if orient3d(c[0], c[1], c[2], c[3]) > 0.0 {
                    v.swap(0, 1);
                }
                tets.push(v);
                slots.push(t);
            }
        }
        let mut neighbors = Vec::with_capacity(tets.len());
        for (i, &t) in slots.iter().enumerate() {
            tick(|| work(1, i))?;
            let mut nb = [NONE; 4];
            for (k, &x) in tets[i].iter().enumerate() {
                // The face opposite x in the output order is the kernel face opposite x.
                let vs = self.tets.verts(t);
                let f = (0..4).find(|&f| vs[f] == x).unwrap_or(0);
                let (n, _) = self.tets.neighbor(t, f);
                nb[k] = if n == NONE { NONE } else { index[n as usize] };
            }
            neighbors.push(nb);
        }
        let tet_attributes = if self.opts.region_attributes {
            slots
                .iter()
                .map(|&t| {
                    let r = self.region[t as usize];
                    if r == 0 {
                        0.0
                    } else {
                        plc.regions[(r - 1) as usize].attribute
                    }
                })
                .collect()
        } else {
            Vec::new()
        };
        // Subfaces with the domain on at least one side (a facet between two holes is not
        // part of the mesh): the subfaces among the faces of the output tets; and the boundary
        // faces that a dropped rounding sliver uncovered, which lie in its facet.
        let mut faces: Vec<([u32; 3], u32)> = Vec::new();
        for (i, &t) in slots.iter().enumerate() {
            tick(|| work(2, i))?;
            let vs = self.tets.verts(t);
            for f in 0..4 {
                let fv = face_of(vs, f);
                if let Some(fid) = self.feat.subface(fv) {
                    faces.push((fkey(fv), fid));
                } else if !dropped.is_empty() && dropped.contains(&self.tets.neighbor(t, f).0) {
                    if let Some(fid) = self.feat.plane_facet(&fv) {
                        faces.push((fkey(fv), fid));
                    }
                }
            }
        }
        faces.sort_unstable();
        faces.dedup();
        let face_markers: Vec<i32> = faces
            .iter()
            .map(|&(_, f)| self.feat.facets[f as usize].marker)
            .collect();
        let faces: Vec<[u32; 3]> = faces.into_iter().map(|(k, _)| k).collect();
        let mut edges: Vec<(u64, u32)> = self.feat.subsegs.iter().map(|(k, &e)| (*k, e)).collect();
        edges.sort_unstable();
        let edge_markers: Vec<i32> = edges
            .iter()
            .map(|&(_, e)| self.feat.edges[e as usize].marker)
            .collect();
        let edges: Vec<[u32; 2]> = edges
            .into_iter()
            .map(|(k, _)| [(k >> 32) as u32, k as u32])
            .collect();
        let mut vertex_markers = vec![0i32; self.pts.len()];
        for (i, m) in plc.point_markers.iter().enumerate() {
            vertex_markers[i] = *m;
        }
        for (v, fs) in &self.feat.vert_facets {
            if (*v as usize) >= self.num_input && vertex_markers[*v as usize] == 0 {
                if let Some(&f) = fs.first() {
                    vertex_markers[*v as usize] = self.feat.facets[f as usize].marker;
                }
            }
        }
        // Steiner vertices no tet uses (on facets and edges inside holes) are dropped; input
        // vertices keep their indices whether used or not.
        let mut new_id = vec![NONE; self.pts.len()];
        for (i, id) in new_id.iter_mut().enumerate().take(self.num_input) {
            *id = i as u32;
        }
        let mut vertices: Vec<[f64; 3]> = self.pts[..self.num_input].to_vec();
        let mut markers: Vec<i32> = vertex_markers[..self.num_input].to_vec();
        for (i, t) in tets.iter().enumerate() {
            tick(|| work(3, i))?;
            for &v in t {
                if new_id[v as usize] == NONE {
                    new_id[v as usize] = vertices.len() as u32;
                    vertices.push(self.pts[v as usize]);
                    markers.push(vertex_markers[v as usize]);
                }
            }
        }
        let map = |v: u32| new_id[v as usize];
        let tets: Vec<[u32; 4]> = tets.iter().map(|t| t.map(map)).collect();
        let mut faces2 = Vec::with_capacity(faces.len());
        let mut face_markers2 = Vec::with_capacity(faces.len());
        for (f, m) in faces.iter().zip(face_markers.iter()) {
            faces2.push(f.map(map));
            face_markers2.push(*m);
        }
        let mut edges2 = Vec::with_capacity(edges.len());
        let mut edge_markers2 = Vec::with_capacity(edges.len());
        for (e, m) in edges.iter().zip(edge_markers.iter()) {
            if e.iter().all(|&v| new_id[v as usize] != NONE) {
                edges2.push(e.map(map));
                edge_markers2.push(*m);
            }
        }
        let steiner_points = vertices.len() - self.num_input;
        let mesh = TetMesh {
            vertices,
            vertex_markers: markers,
            num_input_vertices: self.num_input,
            tets,
            neighbors,
            tet_attributes,
            faces: faces2,
            face_markers: face_markers2,
            edges: edges2,
            edge_markers: edge_markers2,
            complete: self.complete,
            steiner_points,
            surface_kept: self.walled,
            optimized: false,
        };
        let _ = ekey;
        Ok(mesh)
    }
}
