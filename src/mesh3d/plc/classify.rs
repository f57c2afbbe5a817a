//! Where the tetrahedra are: exterior, holes and regions, found by flooding across
//! non-subfaces once every feature is in the 3D mesh (paper §4: the domain is known only
//! when conformity holds), and the open-surface input error when the flood reaches every tet.

use super::*;

impl Mesher<'_> {
    /// Gives the tets made while conformity was broken (region [`UNKNOWN`]) their region, now
    /// that every subface is back in the 3D mesh: each connected group of them (across
    /// non-subfaces) takes the region of the known tets next to it, which regions cannot
    /// cross; flat tets lying in one facet are not asked, as their side of it is arbitrary. A
    /// group with no known neighbour, or with neighbours that disagree, falls back on a full
    /// classification. Then the resolved tets are judged for quality.
    pub(super) fn resolve_unknown(&mut self) -> Result<(), Error> {
        let list = std::mem::take(&mut self.unknown);
        let mut comp = Vec::new();
        let mut stack = Vec::new();
        for &s in &list {
            if !self.tets.alive(s) || self.region_of(s) != UNKNOWN {
                continue;
            }
            comp.clear();
            self.set_region(s, RESOLVING);
            stack.push(s);
            let mut found = None;
            let mut agree = true;
            while let Some(t) = stack.pop() {
                tick(|| (self.steiner, self.steiner + self.queued()))?;
                comp.push(t);
                let vs = self.tets.verts(t);
                for f in 0..4 {
                    if self.feat.subface(face_of(vs, f)).is_some() {
                        continue;
                    }
                    let (n, _) = self.tets.neighbor(t, f);
                    match self.region_of(n) {
                        UNKNOWN => {
                            self.set_region(n, RESOLVING);
                            stack.push(n);
                        }
                        RESOLVING => {}
                        // A flat tet with all four vertices in one facet took its region from
                        // whichever side the cavity that made it lay on: no evidence.
                        _ if self.feat.in_one_facet(self.tets.verts(n)) => {}
                        r => match found {
                            None => found = Some(r),
                            Some(x) => agree &= x == r,
                        },
                    }
                }
            }
            match found {
                Some(r) if agree => {
                    for &t in &comp {
                        self.set_region(t, r);
                    }
                }
                _ => {
                    for &t in &comp {
                        self.set_region(t, UNKNOWN);
                    }
                    self.reclassify()?;
                    break;
                }
            }
        }
        for t in list {
            self.maybe_queue_tet(t);
        }
        Ok(())
    }

    /// Classifies every tet again and queues those whose region changed; returns how many.
    pub(super) fn reclassify(&mut self) -> Result<usize, Error> {
        let old = std::mem::take(&mut self.region);
        self.classify(self.plc)?;
        self.unknown.clear();
        let mut changed = 0;
        for t in 0..self.tets.num_slots() as u32 {
            tick(|| (self.steiner, self.steiner))?;
            if self.tets.alive(t) && old.get(t as usize) != Some(&self.region[t as usize]) {
                changed += 1;
                self.maybe_queue_tet(t);
            }
        }
        Ok(changed)
    }

    /// Floods regions: outside from the ghosts and hole seeds, then region seeds; the rest is
    /// region 0 (inside, no attribute). Floods never cross a subface.
    pub(super) fn classify(&mut self, plc: &Plc) -> Result<(), Error> {
        let ns = self.tets.num_slots();
        self.region = vec![0; ns];
        let mut seen = vec![false; ns];
        let mut stack = Vec::new();
        let ghosts: Vec<u32> = (0..ns as u32)
            .filter(|&t| self.tets.alive(t) && self.tets.is_ghost(t))
            .collect();
        if self.feat.facets.is_empty() {
            // No facets (a point set with -q): the convex hull is the domain, as in TetGen.
            for &g in &ghosts {
                seen[g as usize] = true;
                self.region[g as usize] = OUTSIDE;
            }
        } else {
            self.flood(&ghosts, OUTSIDE, &mut seen, &mut stack)?;
        }
        for (i, h) in plc.holes.iter().enumerate() {
            let t =
                self.seed_tet(*h)
                    .ok_or(Error::Input(crate::InputError::HoleOutsideDomain {
                        hole: i,
                    }))?;
            self.flood(&[t], OUTSIDE, &mut seen, &mut stack)?;
        }
        for (i, r) in plc.regions.iter().enumerate() {
            if let Some(t) = self.seed_tet(r.point) {
                if !seen[t as usize] {
                    self.flood(&[t], i as u32 + 1, &mut seen, &mut stack)?;
                }
            } else {
                return Err(Error::Input(crate::InputError::RegionOutsideDomain {
                    region: i,
                }));
            }
        }
        self.classified = true;
        if !(0..ns as u32).any(|t| self.tets.alive(t) && self.region[t as usize] != OUTSIDE) {
            return Err(self.open_surface());
        }
        Ok(())
    }

    /// Why no tetrahedron is inside: the input facets' loop edges that only one facet uses
    /// (an open surface), or, when there is none, those three or more facets share (a
    /// non-manifold surface): input errors naming the first few edges and their facets. An
    /// internal error only when every edge has exactly two facets.
    pub(super) fn open_surface(&self) -> Error {
        let mut uses: crate::hash::FastMap<[u32; 2], Vec<u32>> = Default::default();
        for (f, facet) in self.plc.facets.iter().enumerate() {
            for poly in facet.polygons.iter().filter(|p| p.len() >= 3) {
                for (i, &a) in poly.iter().enumerate() {
                    let b = poly[(i + 1) % poly.len()];
                    uses.entry([a.min(b), a.max(b)]).or_default().push(f as u32);
                }
            }
        }
        let mut edges: Vec<([u32; 2], Vec<u32>)> = uses.into_iter().collect();
        edges.sort_unstable();
        let open: Vec<&([u32; 2], Vec<u32>)> = edges.iter().filter(|e| e.1.len() == 1).collect();
        let first_facets = |list: &mut dyn Iterator<Item = u32>| {
            let mut fs: Vec<usize> = list.map(|f| f as usize).collect();
            fs.sort_unstable();
            fs.dedup();
            fs
        };
        if !open.is_empty() {
            let shown = &open[..open.len().min(3)];
            return Error::Input(crate::InputError::OpenSurface {
                count: open.len(),
                edges: shown.iter().map(|e| e.0.map(|v| v as usize)).collect(),
                facets: first_facets(&mut shown.iter().map(|e| e.1[0])),
            });
        }
        let crowded: Vec<&([u32; 2], Vec<u32>)> = edges.iter().filter(|e| e.1.len() > 2).collect();
        if let Some(first) = crowded.first() {
            return Error::Input(crate::InputError::NonManifoldEdge {
                count: crowded.len(),
                edge: first.0.map(|v| v as usize),
                facets: first_facets(&mut first.1.iter().copied().take(4)),
            });
        }
        Error::Internal("the facets enclose no volume, yet every facet edge is shared".into())
    }

    /// The tet a hole or region seed `p` names, or `None` when `p` lies outside the hull or
    /// on a facet (a subface, closed). A seed on a facet names no side of it: the flood would
    /// start from whichever of the facet's two tets the walk ended in, and a hole seed on the
    /// partition between two boxes carved one box or the other, with the seed left inside a
    /// kept tet (3D campaign seed 9 run 9527); 2D refuses a seed on a segment the same way.
    /// The seed is on a facet exactly when the closed tet holding it has a subface holding it:
    /// on a face of that tet, on an edge around which some face is a subface, or on a vertex
    /// lying on a facet. Every test is exact.
    pub(super) fn seed_tet(&self, p: [f64; 3]) -> Option<u32> {
        match self.tets.locate(p, self.hint) {
            Located::InTet(t) if !self.tets.is_ghost(t) => {
                let vs = self.tets.verts(t);
                let on: Vec<usize> = (0..4)
                    .filter(|&f| {
                        let [a, b, c] = face_of(vs, f).map(|v| self.pts[v as usize]);
                        orient3d(a, b, c, p) == 0.0
                    })
                    .collect();
                if on
                    .iter()
                    .any(|&f| self.feat.subface(face_of(vs, f)).is_some())
                {
                    return None;
                }
                if let [f1, f2] = on[..] {
                    // On the edge the two faces share: the vertices opposite neither.
                    let [a, b] = {
                        let mut e = (0..4).filter(|&k| k != f1 && k != f2).map(|k| vs[k]);
                        [e.next()?, e.next()?]
                    };
                    let mut ring = Vec::new();
                    self.tets.edge_ring(t, a, b, &mut ring);
                    let on_facet = ring.iter().any(|&u| {
                        let us = self.tets.verts(u);
                        (0..4).any(|f| {
                            let face = face_of(us, f);
                            face.contains(&a)
                                && face.contains(&b)
                                && self.feat.subface(face).is_some()
                        })
                    });
                    if on_facet {
                        return None;
                    }
                }
                Some(t)
            }
            Located::InTet(_) => None,
            Located::Vertex(v) => {
                if self
                    .feat
                    .vert_facets
                    .get(&v)
                    .is_some_and(|fs| !fs.is_empty())
                {
                    return None;
                }
                // A Steiner point landed exactly on the seed, off every facet: any real tet
                // around it will do.
                let mut star = Vec::new();
                self.tets.star(v, &mut star);
                star.into_iter().find(|&t| !self.tets.is_ghost(t))
            }
        }
    }

    pub(super) fn flood(
        &mut self,
        seeds: &[u32],
        reg: u32,
        seen: &mut [bool],
        stack: &mut Vec<u32>,
    ) -> Result<(), Error> {
        stack.clear();
        for &s in seeds {
            if !seen[s as usize] {
                seen[s as usize] = true;
                stack.push(s);
            }
        }
        while let Some(t) = stack.pop() {
            tick(|| (self.steiner, self.steiner))?;
            self.region[t as usize] = reg;
            let vs = self.tets.verts(t);
            for f in 0..4 {
                let (n, _) = self.tets.neighbor(t, f);
                if seen[n as usize] {
                    continue;
                }
                let fv = face_of(vs, f);
                if !fv.contains(&GHOST) && self.feat.subface(fv).is_some() {
                    continue;
                }
                seen[n as usize] = true;
                stack.push(n);
            }
        }
        Ok(())
    }
}
