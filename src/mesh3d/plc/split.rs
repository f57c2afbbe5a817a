//! The steps of the work queue (paper §4, Definition 4.1): whether a queued subsegment,
//! subface or tetrahedron still needs splitting, where its split point goes (lazily: a point
//! that encroaches a lower-dimensional simplex is refused and that simplex is split instead),
//! and the input errors for features closer than floating point can separate.

use super::*;

impl Mesher<'_> {
    /// Whether subsegment `ab` must be split: missing from a facet mesh (`missing_in_facets`,
    /// as [`Mesher::recover_in_facets`] found) or from the 3D mesh, or encroached.
    pub(super) fn subseg_needs_split(&self, a: u32, b: u32, missing_in_facets: bool) -> bool {
        if missing_in_facets {
            return true;
        }
        let Some(t0) = self.tets.find_edge(a, b) else {
            return true;
        };
        if !self.sharp.is_empty() || self.opts.keep_surface {
            // Lazy mode (small input angles): vertices of nearby features would encroach each
            // other's subsegments forever; only refused circumcenters split them. Keeping the
            // surface, every split point is taken off it again: only missing ones are split.
            return false;
        }
        // The edge's link: a vertex strictly inside the diametral ball of a Delaunay edge shows
        // up among the tetrahedra around it.
        let mut ring = Vec::new();
        self.tets.edge_ring(t0, a, b, &mut ring);
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        for t in ring {
            let vs = self.tets.verts(t);
            for x in vs {
                if x != a
                    && x != b
                    && x != GHOST
                    && in_diametral_ball_seg3(pa, pb, self.pts[x as usize])
                {
                    return true;
                }
            }
        }
        false
    }

    pub(super) fn take_subseg(&mut self, s: [u32; 2], force: bool) -> Result<(), Error> {
        let [a, b] = s;
        let Some(e) = self.feat.subseg(a, b) else {
            return Ok(());
        };
        let missing_in_facets = self.recover_in_facets(a, b, e);
        if !force
            && !self.subseg_needs_split(a, b, missing_in_facets)
            && !self.seg_over_bound(a, b, e)
        {
            return Ok(());
        }
        if force && self.below_floor(&[self.pts[a as usize], self.pts[b as usize]]) {
            return Ok(());
        }
        let mid = self.split_point(a, b);
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        if mid == pa || mid == pb {
            return Err(Error::Internal(format!(
                "subsegment {a}-{b} is too short to split (precision exhausted)"
            )));
        }
        let m = self.new_vertex(mid)?;
        self.steiner += 1;
        if force {
            self.counts.seg_forced += 1;
        } else {
            self.counts.seg_missing += 1;
        }
        self.feat.split_subseg(a, b, m, e);
        self.seg_q.push_back(([a, m], Why::Check));
        self.seg_q.push_back(([m, b], Why::Check));
        let facets = self.feat.edges[e as usize].facets.clone();
        for f in facets {
            self.facet_insert(f, m, false, Some([a, b]))
                .map_err(|err| {
                    let info = match err {
                        FacetInsertError::Duplicate(d) => format!(
                        " (split of {a}-{b} at {mid:?}; vertex {d} made by {:?}, on facets {:?})",
                        self.feat.split_edge.get(&d).map(|e| self.feat.edges[*e as usize].ends),
                        self.feat.vert_facets.get(&d)
                    ),
                        _ => String::new(),
                    };
                    let internal = format!("segment split point in facet {f}: {err:?}{info}");
                    // The split point rounds onto a vertex of the facet mesh: two features
                    // of the facet run closer than floating point separates there (3D
                    // campaign seed 11 run 6722: two tiny facets 1e-27 apart). An input
                    // point that close to the facet is named; else the internal error.
                    match err {
                        FacetInsertError::Duplicate(_) => self.too_close_at(mid, f, internal),
                        _ => Error::Internal(internal),
                    }
                })?;
        }
        self.insert3d(m, false, false)
            .map_err(|_| Error::Internal(format!("segment split point {m} refused")))
    }

    /// Whether subsegment `ab` of input edge `e` exceeds its length bound (and is above the
    /// size floor).
    pub(super) fn seg_over_bound(&self, a: u32, b: u32, e: u32) -> bool {
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        self.limits.seg_too_long(e, pa, pb) && !self.below_floor(&[pa, pb])
    }

    /// Whether subface `v` of facet `fid` exceeds its area bound (and is above the size floor).
    pub(super) fn face_over_bound(&self, v: [u32; 3], fid: u32) -> bool {
        let c = v.map(|x| self.pts[x as usize]);
        self.limits.face_too_large(fid, c) && !self.below_floor(&c)
    }

    /// Where to split subsegment `ab`: the midpoint, or, when exactly one end is an input vertex
    /// where input edges meet (an apex), the point at the power-of-two distance from it nearest
    /// to half the length (Ruppert's concentric shells): split points of edges meeting at a
    /// small angle then sit at equal distances from the apex and stop encroaching each other.
    pub(super) fn split_point(&self, a: u32, b: u32) -> [f64; 3] {
        let apex = |v: u32| {
            (v as usize) < self.num_input && self.feat.seg_adj.get(&v).is_some_and(|l| l.len() >= 2)
        };
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        let (from, to) = match (apex(a), apex(b)) {
            (true, false) => (pa, pb),
            (false, true) => (pb, pa),
            _ => return [0, 1, 2].map(|k| 0.5 * (pa[k] + pb[k])),
        };
        let len = crate::geometry::dist2_3(from, to).sqrt();
        // Shells at power-of-two multiples of the input's largest extent, not of the unit of
        // length: the same split points, relative to the input, at every scale (issue 14).
        let unit = (0..3)
            .map(|k| self.bbox[1][k] - self.bbox[0][k])
            .fold(0.0, f64::max);
        let d = unit * (0.5 * len / unit).log2().round().exp2();
        let t = (d / len).clamp(0.25, 0.75);
        [0, 1, 2].map(|k| from[k] + (to[k] - from[k]) * t)
    }

    /// Whether subface `abc` is missing from the 3D mesh or encroached.
    pub(super) fn subface_needs_split(&self, v: [u32; 3]) -> bool {
        let Some(h) = self.tets.find_face(v[0], v[1], v[2]) else {
            return true;
        };
        if !self.sharp.is_empty() || self.opts.keep_surface {
            return false; // lazy mode, or keeping the surface, as for subsegments
        }
        let [a, b, c] = v.map(|x| self.pts[x as usize]);
        let (t, f) = (h / 4, (h % 4) as usize);
        let (n, nf) = self.tets.neighbor(t, f);
        for (tt, ff) in [(t, f), (n, nf)] {
            let x = self.tets.verts(tt)[ff];
            if x != GHOST && in_diametral_ball_tri(a, b, c, self.pts[x as usize]) {
                return true;
            }
        }
        false
    }

    pub(super) fn take_subface(&mut self, v: [u32; 3], fid: u32, why: Why) -> Result<(), Error> {
        let force = why.forced();
        if self.feat.subface(v) != Some(fid) {
            return Ok(());
        }
        if !force && !self.subface_needs_split(v) && !self.face_over_bound(v, fid) {
            return Ok(());
        }
        if !force && self.follow_3d(v, fid) {
            return Ok(());
        }
        let [a, b, c] = v.map(|x| self.pts[x as usize]);
        if force && self.below_floor(&[a, b, c]) {
            return Ok(()); // a refused circumcenter's demand; the face is present
        }
        let centroid = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
        let Some(mut cc) = tri_circumcenter3(a, b, c) else {
            return Err(Error::Internal(format!("degenerate subface {v:?}")));
        };
        {
            // A circumcentre beyond a subsegment (outside the facet) waits for that split.
            let feat = &self.feat;
            let is_sub = |a: u32, b: u32| feat.subseg(a, b).is_some();
            if let Err(FacetInsertError::Encroaches(mut segs)) =
                self.fmesh[fid as usize].check_reach(v, cc, &self.pts, &is_sub)
            {
                // Only subsegments whose diametral ball holds the circumcentre: splitting
                // them shrinks those balls until it is out. (A subsegment that merely lies
                // between the face and its circumcentre would be split forever without
                // the face changing, as next to small input angles.)
                let pts = &self.pts;
                segs.retain(|s| in_diametral_ball_seg3(pts[s[0] as usize], pts[s[1] as usize], cc));
                if self.defer_to_segments(&segs, v, fid, why) {
                    return Ok(());
                }
                // None, or every such subsegment is below the size floor: split inside the
                // face.
                cc = centroid;
            }
        }
        let centroid = self.feat.onto_facet_plane(fid, centroid, &self.pts);
        if cc != centroid {
            cc = self.feat.onto_facet_plane(fid, cc, &self.pts);
        }
        let m = self.new_vertex(cc)?;
        let mut tried_centroid = cc == centroid;
        loop {
            // A point on a 3D vertex missing from this facet mesh (rounding) is a duplicate too.
            let on_vertex = match self.tets.locate(self.pts[m as usize], self.hint) {
                Located::Vertex(w) => Err(FacetInsertError::Duplicate(w)),
                Located::InTet(_) => Ok(()),
            };
            match on_vertex.and_then(|()| self.facet_insert(fid, m, true, None)) {
                Ok(()) => break,
                // The circumcenter rounds onto an existing vertex (the facet mesh is then not
                // quite Delaunay around it): split at the centroid instead.
                Err(FacetInsertError::Duplicate(_) | FacetInsertError::Lost) if !tried_centroid => {
                    tried_centroid = true;
                    self.pts[m as usize] = centroid;
                }
                // Even the centroid rounds onto a vertex (a face at the precision limit): a
                // quality demand on a present face is dropped.
                Err(FacetInsertError::Duplicate(_)) if force => {
                    self.pts.pop();
                    return Ok(());
                }
                Err(FacetInsertError::Encroaches(segs)) => {
                    if self.defer_to_segments(&segs, v, fid, why) {
                        self.pts.pop();
                        return Ok(());
                    }
                    if tried_centroid {
                        self.pts.pop();
                        if force {
                            return Ok(()); // a quality demand on a present face: dropped
                        }
                        return Err(self.too_close(
                            v,
                            fid,
                            "cannot be split: the \
                             subsegments it encroaches are below the size floor",
                        ));
                    }
                    tried_centroid = true;
                    self.pts[m as usize] = centroid;
                }
                // The centroid rounds onto a corner (a face at the precision limit), or onto
                // a vertex of another feature that lies on the face within rounding.
                Err(FacetInsertError::Duplicate(d)) => {
                    self.pts.pop();
                    let what = if v.contains(&d) {
                        "a corner"
                    } else {
                        "another vertex"
                    };
                    return Err(self.too_close(
                        v,
                        fid,
                        &format!(
                            "is too small to split (precision exhausted: its centroid rounds \
                             onto {what})"
                        ),
                    ));
                }
                Err(e) => {
                    return Err(Error::Internal(format!(
                        "circumcenter of subface {v:?} in facet {fid}: {e:?}"
                    )))
                }
            }
        }
        self.steiner += 1;
        if force {
            self.counts.face_forced += 1;
        } else {
            self.counts.face_missing += 1;
        }
        self.feat.set_vertex_facets(m, vec![fid]);
        self.insert3d(m, false, false)
            .map_err(|_| Error::Internal(format!("facet point {m} refused")))
    }

    /// The error for a subface `v` of facet `fid` that conformity needs split but the size
    /// floor forbids: the input point nearest to it off the facet is too close to the facet
    /// (an input error naming both) when it lies within 2^8 size floors of the facet's plane;
    /// otherwise (no input point that close: the floor was reached for another reason) an
    /// internal error saying `what`.
    pub(super) fn too_close(&self, v: [u32; 3], fid: u32, what: &str) -> Error {
        let c = v.map(|x| self.pts[x as usize]);
        let centroid = [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0);
        self.too_close_at(
            centroid,
            fid,
            format!("subface {v:?} of facet {fid} {what}"),
        )
    }

    /// [`Mesher::too_close`] at point `centroid` of facet `fid`, with `internal` the message
    /// of the internal error.
    pub(super) fn too_close_at(&self, centroid: [f64; 3], fid: u32, internal: String) -> Error {
        let info = &self.feat.facets[fid as usize];
        let nearest = (0..self.plc.points.len() as u32)
            .filter(|x| !info.vertices.contains(x))
            .min_by(|&x, &y| {
                let d = |u: u32| crate::geometry::dist2_3(self.pts[u as usize], centroid);
                d(x).total_cmp(&d(y))
            });
        nearest
            .and_then(|point| self.too_close_to_facet(point, fid))
            .unwrap_or(Error::Internal(internal))
    }

    /// `PointTooCloseToFacet` when input point `point` (not a vertex of facet `fid`) lies
    /// within 2^8 size floors of the facet's plane: closer than the mesher can separate.
    pub(super) fn too_close_to_facet(&self, point: u32, fid: u32) -> Option<Error> {
        let info = &self.feat.facets[fid as usize];
        if point as usize >= self.plc.points.len() || info.vertices.contains(&point) {
            return None;
        }
        let [a, b, cc] = info
            .plane
            .map(|x| glam::DVec3::from_array(self.pts[x as usize]));
        let n = (b - a).cross(cc - a).normalize();
        let distance = (glam::DVec3::from_array(self.pts[point as usize]) - a)
            .dot(n)
            .abs();
        if distance.is_nan() || distance * distance >= self.floor2 * 65536.0 {
            return None;
        }
        Some(Error::Input(
            crate::error::InputError::PointTooCloseToFacet {
                point: point as usize,
                facet: fid as usize,
                distance,
            },
        ))
    }

    /// Brings a subface missing from the 3D mesh back by a flip in its facet mesh where the
    /// 3D mesh triangulates the quadrilateral the other way ([`FacetMesh::follow_flip`]).
    pub(super) fn follow_3d(&mut self, v: [u32; 3], fid: u32) -> bool {
        if self.tets.find_face(v[0], v[1], v[2]).is_some() {
            return false;
        }
        let feat = &self.feat;
        let tets = &self.tets;
        let is_sub = |a: u32, b: u32| feat.subseg(a, b).is_some();
        let flat = |t: [u32; 3]| feat.on_one_edge(t);
        let in_3d = |t: [u32; 3]| tets.find_face(t[0], t[1], t[2]).is_some();
        let Some(ch) = self.fmesh[fid as usize].follow_flip(v, &self.pts, &is_sub, &flat, &in_3d)
        else {
            return false;
        };
        self.apply_facet_change(fid, ch);
        true
    }

    /// Queues the subsegments a refused facet point encroaches (to be split first, unchecked,
    /// for the subface's own cause) and the subface again; `false` (nothing queued) when every
    /// one of them is below the size floor, so that a face cannot wait forever for splits that
    /// will never happen.
    pub(super) fn defer_to_segments(
        &mut self,
        segs: &[[u32; 2]],
        v: [u32; 3],
        fid: u32,
        why: Why,
    ) -> bool {
        let seg_why = match why {
            Why::Check => Why::Force,
            w => w,
        };
        let mut any = false;
        for &[x, y] in segs {
            if !self.below_floor(&[self.pts[x as usize], self.pts[y as usize]]) {
                self.seg_q.push_front(([x, y], seg_why));
                any = true;
            }
        }
        if any {
            self.face_q.push_back((v, fid, why));
        }
        any
    }

    /// Whether a queued demand has lost its cause: the bad tet whose refused circumcentre made
    /// it is no longer in the mesh (a split made for it, or any other insertion, removed it).
    pub(super) fn obsolete(&self, why: Why) -> bool {
        match why {
            Why::ForTet(t, vs) => !self.tets.alive(t) || self.tets.verts(t) != vs,
            Why::Check | Why::Force => false,
        }
    }

    pub(super) fn is_bad(&self, t: u32) -> bool {
        let vs = self.tets.verts(t);
        if self.feat.in_one_facet(vs) {
            return false;
        }
        let c = vs.map(|x| self.pts[x as usize]);
        if let Some(rho) = self.opts.radius_edge {
            if tet_radius_edge(c) > rho && !self.sharp.exempts(vs, &self.feat, &self.pts) {
                return true;
            }
        }
        self.too_large(t, c)
    }

    /// Whether tet `t` (corners `c`) exceeds a volume bound or the sizing test.
    pub(super) fn too_large(&self, t: u32, c: [[f64; 3]; 4]) -> bool {
        let vol = tet_volume(c).abs();
        if self.opts.max_volume.is_some_and(|mv| vol > mv) {
            return true;
        }
        if self.opts.region_max_volume {
            let r = self.region_of(t);
            if r != 0 && r != OUTSIDE {
                if let Some(Some(mv)) = self.region_max_vol.get((r - 1) as usize) {
                    if vol > *mv {
                        return true;
                    }
                }
            }
        }
        if let Some(f) = &self.opts.sizing {
            if f(c[0], c[1], c[2], c[3], vol) {
                return true;
            }
        }
        false
    }

    pub(super) fn maybe_queue_tet(&mut self, t: u32) {
        if !self.tets.alive(t) || self.tets.is_ghost(t) || self.region_of(t) >= UNKNOWN {
            return;
        }
        if self.is_bad(t) {
            self.tet_q.push_back((t, self.tets.verts(t)));
        }
    }

    pub(super) fn take_tet(&mut self, t: u32, vs: [u32; 4]) -> Result<(), Error> {
        if !self.tets.alive(t) || self.tets.verts(t) != vs || self.region_of(t) >= UNKNOWN {
            return Ok(());
        }
        let c = vs.map(|x| self.pts[x as usize]);
        if self.below_floor(&c) {
            return Ok(());
        }
        let Some(cc) = point_in_circumsphere(c) else {
            return Ok(());
        };
        self.place_for_tet(t, vs, c, cc)
    }

    /// Inserts `cc`, a point inside the circumsphere of tet `t` (vertices `vs`, corners `c`),
    /// provisionally to remove `t`; when refused, queues the splits it demands and `t` again.
    pub(super) fn place_for_tet(
        &mut self,
        t: u32,
        vs: [u32; 4],
        c: [[f64; 3]; 4],
        cc: [f64; 3],
    ) -> Result<(), Error> {
        if self.walled {
            let m = self.new_vertex(cc)?;
            return self.take_tet_walled(t, c, m);
        }
        // A refusal queues splits of what the point encroaches and `t` again. Were nothing
        // inserted before `t` comes back, it would be refused the same way for ever: the
        // second try searches the whole cavity (the first stops at the first encroached
        // feature, which may be one that cannot be split), and after a third `t` stays.
        if self.refused_at != self.steiner {
            self.refused.clear();
            self.refused_at = self.steiner;
        }
        let tries = self.refused.get(&(t, vs)).copied().unwrap_or(0);
        if tries >= 2 {
            self.counts.tet_given_up += 1;
            return Ok(());
        }
        let m = self.new_vertex(cc)?;
        match self.insert3d(m, true, tries == 0) {
            Ok(()) => {
                self.steiner += 1;
                self.counts.tet += 1;
                if self.opts.verbose && self.steiner % 100_000 == 0 {
                    eprintln!("idmesh: {} Steiner points", self.steiner);
                }
                Ok(())
            }
            Err(enc) => {
                self.pts.pop();
                self.counts.tet_refused += 1;
                self.refused.insert((t, vs), tries + 1);
                if enc.is_empty() {
                    // The circumcenter coincides with a vertex, or lies outside the box. Outside
                    // the box it is outside the domain, beyond a facet: the subface the way to
                    // it crosses first is split instead (Ruppert's rule; its diametral ball
                    // holds the circumcenter in exact arithmetic).
                    if !self.in_box(cc) {
                        if let Some((f, fid)) = self.subface_towards(t, cc) {
                            self.face_q.push_back((f, fid, Why::ForTet(t, vs)));
                            self.tet_q.push_back((t, vs));
                        }
                    }
                    return Ok(());
                }
                for e in enc {
                    match e {
                        Enc::Seg(s) => self.seg_q.push_back((s, Why::ForTet(t, vs))),
                        Enc::Face(f, fid) => self.face_q.push_back((f, fid, Why::ForTet(t, vs))),
                    }
                }
                self.tet_q.push_back((t, vs));
                Ok(())
            }
        }
    }

    /// The first subface met walking from tet `t` straight towards `p` (through the faces the
    /// segment from `t`'s centroid to `p` crosses), if the walk meets one before leaving the
    /// mesh; exact orientation tests, bounded steps.
    pub(super) fn subface_towards(&self, t: u32, p: [f64; 3]) -> Option<([u32; 3], u32)> {
        let c = self.tets.verts(t).map(|x| self.pts[x as usize]);
        let q = [0, 1, 2].map(|k| 0.25 * (c[0][k] + c[1][k] + c[2][k] + c[3][k]));
        let mut cur = t;
        let mut from = NONE;
        for _ in 0..10_000 {
            let vs = self.tets.verts(cur);
            if vs.contains(&GHOST) {
                return None;
            }
            let pt = vs.map(|x| self.pts[x as usize]);
            let mut exit = None;
            for (f, &opp) in pt.iter().enumerate() {
                let (n, _) = self.tets.neighbor(cur, f);
                if n == from {
                    continue;
                }
                let fv = face_of(vs, f);
                let [a, b, cc] = fv.map(|x| self.pts[x as usize]);
                let side_p = orient3d(a, b, cc, p);
                let side_v = orient3d(a, b, cc, opp);
                if side_p == 0.0 || side_p.signum() == side_v.signum() {
                    continue; // p is not beyond this face
                }
                // The segment q→p goes through the face's triangle.
                let s = [
                    orient3d(q, p, a, b),
                    orient3d(q, p, b, cc),
                    orient3d(q, p, cc, a),
                ];
                let through = s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0);
                if through || exit.is_none() {
                    exit = Some((f, fv, n));
                    if through {
                        break;
                    }
                }
            }
            let (_, fv, n) = exit?;
            if let Some(fid) = self.feat.subface(fv) {
                return Some((fv, fid));
            }
            from = cur;
            cur = n;
        }
        None
    }
}

/// A point strictly inside the circumsphere of the positive tet `c` (exact `insphere`), to
/// remove it by: its circumcentre when the rounded one passes, else the first that passes of
/// its centroid, its face centroids and its edge midpoints. The rounded circumcentre of a
/// nearly flat tet (four nearly cocircular points) can be far from the true one, outside the
/// sphere, or undefined (the rounded determinant is zero although the exact orientation is
/// not); inserting it would leave the tet in place. `None` when no candidate passes (a tet
/// flat to within rounding of its own points).
pub(super) fn point_in_circumsphere(c: [[f64; 3]; 4]) -> Option<[f64; 3]> {
    let o = crate::predicates::orient3d(c[0], c[1], c[2], c[3]);
    let inside = |p: [f64; 3]| crate::predicates::insphere(c[0], c[1], c[2], c[3], p) * o > 0.0;
    let mean = |ids: &[usize]| {
        let n = ids.len() as f64;
        [0, 1, 2].map(|k| ids.iter().map(|&i| c[i][k]).sum::<f64>() / n)
    };
    let faces = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
    let edges = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];
    tet_circumcenter(c)
        .into_iter()
        .chain(std::iter::once(mean(&[0, 1, 2, 3])))
        .chain(faces.iter().map(|f| mean(f)))
        .chain(edges.iter().map(|e| mean(e)))
        .find(|&p| inside(p))
}

#[cfg(test)]
mod tests {
    use super::point_in_circumsphere;
    use crate::geometry::tet_circumcenter;
    use crate::predicates::{insphere, orient3d};

    /// The four corners of a rectangle cutting a corner off a rotated plate (Steiner points on
    /// four of its edges, from `tests/cad3d.rs`): coplanar before the rotation's rounding,
    /// barely positive after it. The mesher's old rule (the rounded circumcentre, else
    /// nothing) left this tet in a `-pq` mesh with a 0° dihedral angle.
    #[test]
    fn a_flat_tet_gets_a_point_inside_its_circumsphere() {
        let mut c = [
            [
                0.033406575520833336,
                0.010823567708333343,
                0.3964029947916667,
            ],
            [
                0.057820638020833336,
                0.18172200520833334,
                0.11564127604166667,
            ],
            [
                0.42952473958333337,
                -0.11564127604166667,
                -0.033040364583333336,
            ],
            [
                0.40511067708333337,
                -0.2865397135416667,
                0.24772135416666666,
            ],
        ];
        let o = orient3d(c[0], c[1], c[2], c[3]);
        assert_ne!(o, 0.0, "the corners are not exactly coplanar");
        if o < 0.0 {
            c.swap(0, 1);
        }
        let o = orient3d(c[0], c[1], c[2], c[3]);
        let inside = |p: [f64; 3]| insphere(c[0], c[1], c[2], c[3], p) * o > 0.0;
        // The rounded circumcentre does not do.
        assert!(tet_circumcenter(c).map_or(true, |cc| !inside(cc)));
        let p = point_in_circumsphere(c).expect("a point inside the sphere");
        assert!(inside(p));
        // A regular tet keeps its circumcentre.
        let r = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let r = if orient3d(r[0], r[1], r[2], r[3]) > 0.0 {
            r
        } else {
            [r[1], r[0], r[2], r[3]]
        };
        assert_eq!(point_in_circumsphere(r), tet_circumcenter(r));
    }
}
