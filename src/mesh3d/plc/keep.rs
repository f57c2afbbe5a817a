//! Keeping the input surface (TetGen's `-Y`): no Steiner point on an input edge or facet.
//!
//! The conforming Delaunay mesh is made first, as without `-Y`: its Steiner points on edges and
//! facets are what recovers every facet, whatever the input (cospherical ties, surface
//! triangles that are not Delaunay, Schönhardt-like polyhedra). Then the outside is carved away
//! and every boundary Steiner point `s` is *suppressed*:
//! * each facet through `s` is triangulated again without it (its star in the facet is a
//!   polygon; its constrained Delaunay triangulation by the 2D kernel, exact in the facet's
//!   projection, [`crate::input3d::FacetTriangulation::polygon`]), and an input edge through `s`
//!   gets its two pieces back as one;
//! * the tets around `s` fall into groups, one per wedge of the domain between the facets
//!   through `s`; each group is re-coned from a new point moved off the facets into its
//!   wedge. Every face of the group's boundary (its faces opposite `s` and the new facet
//!   triangles) joined to a point strictly inside the group's kernel is a positive tet, and
//!   the kernel has interior right next to `s`, so such a point exists; it is picked with
//!   exact orientation tests ([`crate::mesh3d::store::Tets::replace`] checks the result again).
//! * a point on the free edge of a fin (a facet with the domain on both sides, its edge on no
//!   other facet) has one group, which reaches the fin from both sides: no one point is on
//!   both sides, so two points re-cone it, one on each side just past the edge, with tets on
//!   the edge between them filling the seam ([`Mesher::suppress_on_fin`]).
//! * In floating point the kernel can still be empty: where nearly coplanar facets meet (a
//!   fan of triangles at 179.99°), the point moved off for one split point of their edge sits
//!   in a wedge a few rounding errors thick and flattens the next split point's tets. Such a
//!   point is left as it is and tried again after the others, once the moved points have
//!   been taken out where possible, flips have reshaped its star and the moved points left
//!   have been recentred in their stars ([`RETRY_ROUNDS`] rounds; then the error).
//!
//! The moved points are then removed where their star can be re-coned from one of its own
//! vertices, so that points stay only where the surface needs them (a Schönhardt-like
//! region), and Lawson flips ([`super::flip`]) bring the tets next to the surface closer to
//! Delaunay. The result is a valid tetrahedralization whose boundary is exactly the input
//! surface; it is not Delaunay next to the surface. Quality refinement afterwards inserts
//! interior points only, with cavities that stop at subfaces and are shrunk to star shape
//! ([`crate::mesh3d::store::Tets::find_cavity_walled`]).

use super::{Mesher, UNKNOWN};
use crate::error::Error;
use crate::input3d::FacetTriangulation;
use crate::mesh3d::features::{ekey, fkey, proj};
use crate::mesh3d::store::{ReplaceError, FACE};
use crate::mesh3d::NONE;
use crate::predicates::{in_diametral_ball_seg3, in_lens_tri, orient2d, orient3d};

/// Height of the lens of a subface (relative to its circumradius) that refinement points must
/// stay out of once the surface is kept. TetGen refuses the whole diametral ball (height 1),
/// which leaves a cube's six tets as they are whatever the volume bound; a flatter lens lets
/// points in at a distance that still makes good tets with the subface (radius-edge about 1.1
/// at half the circumradius above its centre) and keeps them from creeping onto it.
const LENS_HEIGHT: f64 = 0.5;

/// Placeholder ids of the two points that take a fin's split point's place while their
/// positions are searched ([`Mesher::suppress_on_fin`]).
const QU: u32 = u32::MAX - 1;
const QD: u32 = u32::MAX - 2;

/// Rounds of retrying the boundary Steiner points that could not be taken off the surface at
/// first (see [`Mesher::keep_input_surface`]).
const RETRY_ROUNDS: usize = 4;

/// A facet's triangulation around a suppressed point: the facet and its new triangles
/// (counter-clockwise in the facet's projection), with the old subfaces they replace.
struct FacetPatch {
    facet: u32,
    old: Vec<[u32; 3]>,
    new: Vec<[u32; 3]>,
}

/// One group of tets around a suppressed point: the tets (star indices), and their floor faces
/// as seen from inside the group (outward, in [`FACE`] order), each with its facet.
#[derive(Default)]
struct Group {
    tets: Vec<usize>,
    floor: Vec<([u32; 3], u32)>,
}

impl Mesher<'_> {
    /// Turns the classified conforming mesh into one that keeps the input surface (see the
    /// module documentation). Afterwards points enter with walls ([`Mesher::insert3d_walled`]).
    pub(super) fn keep_input_surface(&mut self) -> Result<(), Error> {
        let region = &self.region;
        self.tets
            .carve(|t| region.get(t as usize).is_some_and(|&r| r < UNKNOWN));
        self.walled = true;
        let steiner: Vec<u32> = (self.num_input as u32..self.pts.len() as u32)
            .filter(|v| {
                self.feat.vert_facets.contains_key(v) || self.feat.split_edge.contains_key(v)
            })
            .collect();
        let mut moved = Vec::new();
        let mut pending = steiner;
        let mut retried = 0;
        for round in 0..=RETRY_ROUNDS {
            let mut stuck = Vec::new();
            let mut why = None;
            for s in pending {
                if self.tets.vertex_tet(s) == NONE {
                    continue; // outside the domain (on a facet between holes, say)
                }
                if let Err(e) = self.suppress(s, &mut moved)? {
                    stuck.push(s);
                    why = Some(e);
                }
            }
            let Some(e) = why else { break };
            if round == RETRY_ROUNDS {
                return Err(e);
            }
            // A group's wedge can be too thin for any point: a neighbour's point, moved just
            // off the surface into its own thin wedge, flattened the tets around it. Taking
            // the moved points out again and flipping reshape the star; then the point is
            // tried again.
            self.remove_moved_points(&moved);
            self.delaunay_flips();
            self.recentre_moved_points(&moved);
            retried += stuck.len();
            pending = stuck;
        }
        // Flips change the stars of the moved points, so a point that could not go may go
        // after them.
        let mut flips = 0;
        for _round in 0..3 {
            self.remove_moved_points(&moved);
            let f = self.delaunay_flips();
            flips += f;
            if f == 0 {
                break;
            }
        }
        if self.opts.verbose {
            eprintln!(
                "idmesh: -Y: {} boundary Steiner points taken off the surface ({retried} tried \
                 again), {} interior points left, {flips} flips",
                moved.len(),
                moved
                    .iter()
                    .filter(|&&v| self.tets.vertex_tet(v) != NONE)
                    .count()
            );
        }
        Ok(())
    }

    /// Suppresses boundary Steiner point `s`; the points it moves into the domain are added
    /// to `moved`. `Ok(Err(..))`, with nothing changed, when some group of its tets has no
    /// point that sees all of the group (to be tried again after the others).
    fn suppress(&mut self, s: u32, moved: &mut Vec<u32>) -> Result<Result<(), Error>, Error> {
        let at = self.pts[s as usize];
        let fail = |why: String| {
            Error::Internal(format!(
                "-Y (keep the surface): cannot take the Steiner point {at:?} off the surface: {why}"
            ))
        };
        let mut star = Vec::new();
        self.tets.star(s, &mut star);
        // Groups: star tets joined across faces through s that are not subfaces.
        let mut parent: Vec<usize> = (0..star.len()).collect();
        fn root(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        let mut floor_faces: Vec<(usize, [u32; 3], u32)> = Vec::new();
        for (i, &t) in star.iter().enumerate() {
            let vs = self.tets.verts(t);
            for f in 0..4 {
                if vs[f] == s {
                    continue;
                }
                let face = FACE[f].map(|k| vs[k]);
                if let Some(fid) = self.feat.subface(face) {
                    floor_faces.push((i, face, fid));
                    continue;
                }
                let (n, _) = self.tets.neighbor(t, f);
                if n == NONE {
                    return Err(fail(format!("the open face {face:?} is not a subface")));
                }
                let j = star
                    .iter()
                    .position(|&u| u == n)
                    .ok_or_else(|| fail("its star is not closed".into()))?;
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a] = b;
            }
        }
        let mut groups: Vec<Group> = Vec::new();
        let mut group_of = vec![usize::MAX; star.len()];
        for i in 0..star.len() {
            let r = root(&mut parent, i);
            if group_of[r] == usize::MAX {
                group_of[r] = groups.len();
                groups.push(Group::default());
            }
            group_of[i] = group_of[r];
            groups[group_of[i]].tets.push(i);
        }
        for &(i, face, fid) in &floor_faces {
            groups[group_of[i]].floor.push((face, fid));
        }
        if groups.iter().any(|g| g.floor.is_empty()) {
            // A free input edge through the volume: no facet to move the point off.
            return Err(Error::Unsupported(format!(
                "-Y (keep the surface): the Steiner point {at:?} on an input edge with the \
                 domain all around it (a free segment, on no facet bounding the domain) cannot \
                 be taken off: mesh without -Y"
            )));
        }
        for g in &groups {
            let mut seen: Vec<[u32; 3]> = g.floor.iter().map(|f| fkey(f.0)).collect();
            seen.sort_unstable();
            if let Some(w) = seen.windows(2).find(|w| w[0] == w[1]) {
                // The group reaches a subface from both sides: s is on a free edge of a facet
                // inside the domain (a fin), and no one point moved off it is on both sides
                // of the facet: two are.
                let fid = self.feat.subface(w[0]).unwrap_or(NONE);
                let only_fin = groups.len() == 1 && floor_faces.iter().all(|f| f.2 == fid);
                if only_fin && self.suppress_on_fin(s, &star, &floor_faces, fid, moved)? {
                    return Ok(Ok(()));
                }
                return Err(Error::Unsupported(format!(
                    "-Y (keep the surface): the Steiner point {at:?} on a free edge of facet \
                     {fid} (an edge of no other facet, with the domain all around it) cannot \
                     be taken off: mesh without -Y"
                )));
            }
        }
        // Each facet through s, triangulated again without it.
        let mut facets: Vec<u32> = floor_faces.iter().map(|f| f.2).collect();
        facets.sort_unstable();
        facets.dedup();
        let mut patches = Vec::with_capacity(facets.len());
        for fid in facets {
            let mut old: Vec<[u32; 3]> = floor_faces
                .iter()
                .filter(|f| f.2 == fid)
                .map(|f| fkey(f.1))
                .collect();
            old.sort_unstable();
            old.dedup();
            let new = self.retriangulate(s, fid, &old).map_err(fail)?;
            patches.push(FacetPatch {
                facet: fid,
                old,
                new,
            });
        }
        // Each group's new tets, from the best apex found in its wedge.
        let mut new_tets: Vec<[u32; 4]> = Vec::new();
        let mut new_region: Vec<u32> = Vec::new();
        let mut apexes = Vec::new();
        let mut chosen = Vec::with_capacity(groups.len());
        for g in &groups {
            let floor = self.group_floor(g, &patches).map_err(fail)?;
            let link: Vec<[u32; 4]> = g.tets.iter().map(|&i| self.tets.verts(star[i])).collect();
            let Some(q) = self.best_apex(s, &link, &floor) else {
                // An input point within rounding of a facet through s can leave the wedge
                // no room at all: that is the input's doing, and it is named.
                let near = link.iter().flatten().find_map(|&x| {
                    patches
                        .iter()
                        .find_map(|p| self.too_close_to_facet(x, p.facet))
                });
                return Ok(Err(near.unwrap_or_else(|| {
                    fail("no point of its wedge sees the whole group".into())
                })));
            };
            chosen.push((floor, link, q));
        }
        for (g, (floor, link, q)) in groups.iter().zip(chosen) {
            let v = self.new_vertex(q)?;
            apexes.push(v);
            let reg = self.region_of(star[g.tets[0]]);
            for t in &link {
                new_tets.push(t.map(|x| if x == s { v } else { x }));
                new_region.push(reg);
            }
            for f in &floor {
                new_tets.push([v, f[0], f[1], f[2]]);
                new_region.push(reg);
            }
        }
        // Facet triangles with no group on one side are open on that side.
        let open: Vec<[u32; 3]> = patches.iter().flat_map(|p| p.new.clone()).collect();
        while self.tets.num_vertices() < self.pts.len() {
            let p = self.pts[self.tets.num_vertices()];
            self.tets.push_vertex(p);
        }
        let ids = self
            .tets
            .replace(&star, &new_tets, &open)
            .map_err(|e| fail(format!("{e:?}")))?;
        for (t, r) in ids.into_iter().zip(new_region) {
            self.set_region(t, r);
        }
        moved.extend(apexes);
        self.forget_suppressed(s, &patches);
        Ok(Ok(()))
    }

    /// The features after `s` is suppressed: its facets' subfaces around it are the patches'
    /// new triangles, and the input edge through it is one subsegment again.
    fn forget_suppressed(&mut self, s: u32, patches: &[FacetPatch]) {
        for p in patches {
            for f in &p.old {
                self.feat.subfaces.remove(f);
            }
            for f in &p.new {
                self.feat.subfaces.insert(fkey(*f), p.facet);
            }
        }
        if let Some(e) = self.feat.split_edge.remove(&s) {
            if let Some(ends) = self.feat.seg_adj.remove(&s) {
                let [a, b] = [ends[0], ends[1]];
                self.feat.subsegs.remove(&ekey(a, s));
                self.feat.subsegs.remove(&ekey(s, b));
                self.feat.subsegs.insert(ekey(a, b), e);
                for (x, y) in [(a, b), (b, a)] {
                    if let Some(l) = self.feat.seg_adj.get_mut(&x) {
                        if let Some(w) = l.iter_mut().find(|w| **w == s) {
                            *w = y;
                        }
                    }
                }
            }
        }
        self.feat.forget_vertex(s);
    }

    /// Suppresses `s` on the free edge of fin `fid` (a facet inside the domain, with the domain
    /// all around that edge), its star `star` one group whose floor faces `floor` are the fin's
    /// subfaces around `s`, seen from both sides. The star's tets fall into the two sides of
    /// the fin's plane (a tet on the fin on the side its face on the fin turns to; any other
    /// on the side of a seam path of growing angle around `s`, [`monotone_seam`], or else of
    /// its link face's centroid); each side is re-coned from its own point, `q+` and `q-`,
    /// moved off `s` past the free edge and to that side, and the seam between the two cones
    /// is filled with tets on the edge `q+ q-`: one per face through `s` between tets of the
    /// two sides, and one on the fin's new boundary edge. The points are searched along a few
    /// directions and tilts at halving distances; every new tet is checked exactly, and
    /// [`crate::mesh3d::store::Tets::replace`] checks the whole again. `Ok(false)`, with
    /// nothing changed, when no candidate gives positive tets.
    fn suppress_on_fin(
        &mut self,
        s: u32,
        star: &[u32],
        floor: &[(usize, [u32; 3], u32)],
        fid: u32,
        moved: &mut Vec<u32>,
    ) -> Result<bool, Error> {
        let Some(&[a, b]) = self.feat.seg_adj.get(&s).map(|v| v.as_slice()) else {
            return Ok(false);
        };
        let mut old: Vec<[u32; 3]> = floor.iter().map(|f| fkey(f.1)).collect();
        old.sort_unstable();
        old.dedup();
        let Ok(new) = self.retriangulate(s, fid, &old) else {
            return Ok(false);
        };
        let p = |v: u32| self.pts[v as usize];
        let plane = self.feat.facets[fid as usize].plane.map(p);
        let above = |x: [f64; 3]| orient3d(plane[0], plane[1], plane[2], x) > 0.0;
        // The side of each star tet: true for the side `orient3d(plane, x) > 0`.
        let tets: Vec<[u32; 4]> = star.iter().map(|&t| self.tets.verts(t)).collect();
        let mut side: Vec<bool> = tets
            .iter()
            .map(|t| {
                let l: Vec<[f64; 3]> = t.iter().filter(|&&v| v != s).map(|&v| p(v)).collect();
                above([0, 1, 2].map(|k| (l[0][k] + l[1][k] + l[2][k]) / 3.0))
            })
            .collect();
        // A tet on the fin lies on the side its floor face turns to: a face of a tet turns like
        // the plane's points, in the fin's projection, exactly when the tet's fourth vertex
        // lies on the side where `orient3d(plane, x) > 0` (each face of a positive tet is
        // turned so). The winding decides, not the fourth vertex: `s` is on the fin's plane
        // only to rounding, and a vertex within rounding of the plane can lie on the other
        // side of it than its tet.
        let axis = self.feat.facets[fid as usize].axis;
        let ccw = |f: [[f64; 3]; 3]| {
            let o = orient2d(proj(f[0], axis), proj(f[1], axis), proj(f[2], axis));
            (o != 0.0).then_some(o > 0.0)
        };
        let Some(up_ccw) = ccw(plane) else {
            return Ok(false);
        };
        for &(i, face, _) in floor {
            let Some(turn) = ccw(face.map(p)) else {
                return Ok(false);
            };
            side[i] = turn == up_ccw;
        }
        if !side.iter().any(|&u| u) || side.iter().all(|&u| u) {
            return Ok(false);
        }
        // Directions: n to the upper side, o in the fin's plane, away from the fin.
        let v3 = |x: [f64; 3]| glam::DVec3::from(x);
        let ps = v3(p(s));
        let ell = v3(p(b)) - v3(p(a));
        let mut n = (v3(plane[1]) - v3(plane[0])).cross(v3(plane[2]) - v3(plane[0]));
        let mut o = n.cross(ell);
        if n.length() == 0.0 || o.length() == 0.0 {
            return Ok(false);
        }
        n = n.normalize();
        o = o.normalize();
        let reach = tets
            .iter()
            .flatten()
            .filter(|&&v| v != s)
            .map(|&v| (v3(p(v)) - ps).length())
            .fold(f64::INFINITY, f64::min);
        if !above((ps + n * reach).to_array()) {
            n = -n;
        }
        let inner = new
            .iter()
            .flatten()
            .copied()
            .find(|&v| v != a && v != b)
            .map_or(ps, |v| v3(p(v)));
        if (inner - ps).dot(o) > 0.0 {
            o = -o;
        }
        let mut forced = vec![false; tets.len()];
        for &(i, _, _) in floor {
            forced[i] = true;
        }
        // A tet flat on the fin (its four vertices on the fin's plane up to rounding) can have
        // one of the fin's new triangles as its face opposite `s`, with a tet outside the
        // star across it. That triangle then has one side taken already: its cone tet is the
        // flat tet's own, on the side of the triangle where `s` lies, whatever the windings
        // of the flat tet's faces on the fin say (those faces go with `s`).
        let sent = |t: &[u32; 4], q: [f64; 3]| {
            let c = t.map(|v| if v == s { q } else { p(v) });
            orient3d(c[0], c[1], c[2], c[3])
        };
        for (i, t) in tets.iter().enumerate() {
            if closes_new_triangle(s, t, &new) {
                side[i] = sent(t, (ps + n * reach).to_array()) < 0.0;
                forced[i] = true;
            }
        }
        // The seam tets want the edge `q+ q-` to cross every seam face the same way. For each
        // direction of that edge (the fin's normal, tilted along the free edge or across it),
        // the seam is first a path of link edges from `a` to `b` whose angle around `s`, seen
        // along that direction, only grows ([`monotone_seam`]); failing that, the sides above.
        // A vertex within rounding of the fin's plane can still put a tet on the wrong side
        // of the seam, which then folds back over the fin (no candidate works, whatever its
        // distance): the upper tet of each seam tet that stays inverted goes to the lower side
        // (or the lower one up), and the points are searched again.
        let along = ell.normalize();
        let tilts = [
            glam::DVec3::ZERO,
            along * 0.5,
            along * -0.5,
            o * 0.5,
            o * -0.5,
        ];
        let by_centroid = side;
        let mut best = None;
        let mut cand = Vec::new();
        'tilts: for tilt in tilts {
            let d = n + tilt;
            // An orthonormal frame across `d`: `e1` towards `a`, `e2` away from the fin.
            let e1 = -along;
            let e1 = (e1 - d * (e1.dot(d) / d.length_squared())).normalize();
            let mut e2 = d.normalize().cross(e1);
            if e2.dot(o) < 0.0 {
                e2 = -e2;
            }
            let mut side = monotone_seam(
                s,
                star,
                &tets,
                &by_centroid,
                &forced,
                [a, b],
                |v| {
                    let x = v3(p(v)) - ps;
                    let x = x - d * (x.dot(d) / d.length_squared());
                    (x.dot(e2).atan2(x.dot(e1)), (v3(p(v)) - ps).dot(n).abs())
                },
                |t, f| self.tets.neighbor(t, f).0,
                |f| self.feat.subface(f).is_some(),
            )
            .unwrap_or_else(|| by_centroid.clone());
            for _repair in 0..8 {
                let seams = fin_cones(
                    s,
                    star,
                    &tets,
                    &side,
                    &new,
                    up_ccw,
                    [a, b],
                    |t, f| self.tets.neighbor(t, f).0,
                    |f| self.feat.subface(f).is_some(),
                    &mut cand,
                );
                let Some(seams) = seams else {
                    return Ok(false);
                };
                let fixed = cand.len() - seams.len();
                let mut fewest: Option<Vec<usize>> = None;
                for alpha in [1.0, 0.5, 2.0, 0.25, 4.0] {
                    let mut delta = 0.5 * reach;
                    for _ in 0..60 {
                        let qu = (ps + (o * alpha + n + tilt) * delta).to_array();
                        let qd = (ps + (o * alpha - n - tilt) * delta).to_array();
                        let at = |v: u32| match v {
                            QU => qu,
                            QD => qd,
                            v => p(v),
                        };
                        let mut worst = f64::INFINITY;
                        let mut bad = Vec::new();
                        for (k, t) in cand.iter().enumerate() {
                            let c = t.map(at);
                            if orient3d(c[0], c[1], c[2], c[3]) >= 0.0 {
                                worst = 0.0;
                                bad.push(k);
                            } else {
                                worst = worst.min(crate::geometry::tet_shape(c));
                            }
                        }
                        if worst > 0.0 {
                            if best.map_or(true, |b: ([f64; 3], [f64; 3], f64)| worst > b.2) {
                                best = Some((qu, qd, worst));
                            }
                            break;
                        }
                        // Only a candidate whose inverted tets are all seam tets says which
                        // star tets to move across: an inverted cone tet means too far.
                        let seam_only = bad.iter().all(|&k| k >= fixed);
                        if seam_only && fewest.as_ref().map_or(true, |f| bad.len() < f.len()) {
                            fewest = Some(bad);
                        }
                        delta *= 0.5;
                    }
                }
                if best.is_some() {
                    // `cand` is the seam the points were found for.
                    break 'tilts;
                }
                let Some(bad) = fewest else {
                    continue 'tilts;
                };
                let mut changed = false;
                for k in bad {
                    let Some((i, j)) = seams[k - fixed] else {
                        continue;
                    };
                    if !forced[i] {
                        side[i] = false;
                        changed = true;
                    } else if !forced[j] {
                        side[j] = true;
                        changed = true;
                    }
                }
                if !changed {
                    continue 'tilts;
                }
            }
        }
        let Some((qu, qd, _)) = best else {
            return Ok(false);
        };
        let vu = self.new_vertex(qu)?;
        let vd = self.new_vertex(qd)?;
        while self.tets.num_vertices() < self.pts.len() {
            let x = self.pts[self.tets.num_vertices()];
            self.tets.push_vertex(x);
        }
        let new_tets: Vec<[u32; 4]> = cand
            .iter()
            .map(|t| {
                t.map(|v| match v {
                    QU => vu,
                    QD => vd,
                    v => v,
                })
            })
            .collect();
        let reg = self.region_of(star[0]);
        let ids = match self.tets.replace(star, &new_tets, &[]) {
            Ok(ids) => ids,
            Err(_) => {
                // Nothing changed: the two points go again.
                for _ in 0..2 {
                    self.tets.pop_vertex();
                    self.pts.pop();
                }
                return Ok(false);
            }
        };
        for t in ids {
            self.set_region(t, reg);
        }
        moved.extend([vu, vd]);
        self.forget_suppressed(
            s,
            &[FacetPatch {
                facet: fid,
                old,
                new,
            }],
        );
        Ok(true)
    }

    /// The new triangles of facet `fid` around `s` (its subfaces `old` there), without `s`:
    /// the polygon around `s`, split along the input edge through `s` when that edge runs
    /// across the facet, triangulated counter-clockwise in the facet's projection.
    fn retriangulate(&self, s: u32, fid: u32, old: &[[u32; 3]]) -> Result<Vec<[u32; 3]>, String> {
        let axis = self.feat.facets[fid as usize].axis;
        let p2 = |v: u32| proj(self.pts[v as usize], axis);
        // next[x] = y for each subface (s, x, y), counter-clockwise around s.
        let mut next: Vec<(u32, u32)> = Vec::with_capacity(old.len());
        for f in old {
            let [x, y] = {
                let mut o = f.iter().copied().filter(|&v| v != s);
                [o.next().unwrap_or(NONE), o.next().unwrap_or(NONE)]
            };
            let o = orient2d(p2(s), p2(x), p2(y));
            if o == 0.0 {
                return Err(format!("subface {f:?} is flat in facet {fid}'s projection"));
            }
            next.push(if o > 0.0 { (x, y) } else { (y, x) });
        }
        let succ = |x: u32| next.iter().find(|e| e.0 == x).map(|e| e.1);
        // A chain (s on the facet's border) starts where no edge arrives; a ring anywhere.
        let first = next
            .iter()
            .map(|e| e.0)
            .find(|&x| !next.iter().any(|e| e.1 == x))
            .unwrap_or(next[0].0);
        let mut poly = vec![first];
        let mut cur = first;
        while let Some(y) = succ(cur) {
            if y == first {
                break;
            }
            if poly.len() > old.len() {
                return Err(format!(
                    "the subfaces of facet {fid} around it are not a disk"
                ));
            }
            poly.push(y);
            cur = y;
        }
        let ring = succ(cur) == Some(first);
        if poly.len() != old.len() + usize::from(!ring) {
            return Err(format!(
                "the subfaces of facet {fid} around it are not one disk"
            ));
        }
        let ends = self
            .feat
            .seg_adj
            .get(&s)
            .filter(|_| self.feat.split_edge.contains_key(&s));
        let mut polys = Vec::new();
        match (ring, ends) {
            // The input edge through s crosses the facet: keep its two pieces as one edge.
            (true, Some(e)) => {
                let i = poly.iter().position(|&v| v == e[0]);
                let j = poly.iter().position(|&v| v == e[1]);
                let (Some(i), Some(j)) = (i, j) else {
                    return Err(format!("its input edge is not in facet {fid}'s polygon"));
                };
                let (i, j) = (i.min(j), i.max(j));
                polys.push(poly[i..=j].to_vec());
                let mut rest = poly[j..].to_vec();
                rest.extend_from_slice(&poly[..=i]);
                polys.push(rest);
            }
            (false, Some(e)) => {
                let chain_ends = [poly[0], poly[poly.len() - 1]];
                if !(chain_ends.contains(&e[0]) && chain_ends.contains(&e[1])) {
                    return Err(format!("facet {fid} does not end at its input edge"));
                }
                polys.push(poly);
            }
            (false, None) => {
                return Err(format!(
                    "it is on the border of facet {fid} but on no input edge"
                ))
            }
            (true, None) => polys.push(poly),
        }
        let mut tris = Vec::new();
        for p in polys {
            FacetTriangulation::polygon(&p, &p2, &mut tris)
                .ok_or_else(|| format!("facet {fid}'s polygon around it cannot be triangulated"))?;
        }
        Ok(tris)
    }

    /// The new floor faces of group `g`, oriented as seen from inside the group: the new
    /// triangles of every facet the group lies on, turned like the group's old floor faces.
    fn group_floor(&self, g: &Group, patches: &[FacetPatch]) -> Result<Vec<[u32; 3]>, String> {
        let mut out = Vec::new();
        for p in patches {
            let mine: Vec<&([u32; 3], u32)> = g.floor.iter().filter(|f| f.1 == p.facet).collect();
            if mine.is_empty() {
                continue;
            }
            if mine.len() != p.old.len() {
                return Err(format!(
                    "facet {} is only partly on one side of it",
                    p.facet
                ));
            }
            let axis = self.feat.facets[p.facet as usize].axis;
            let p2 = |v: u32| proj(self.pts[v as usize], axis);
            let side = |f: [u32; 3]| orient2d(p2(f[0]), p2(f[1]), p2(f[2])) > 0.0;
            let up = side(mine[0].0);
            if mine.iter().any(|f| side(f.0) != up) {
                return Err(format!("facet {} folds around it", p.facet));
            }
            for &[a, b, c] in &p.new {
                out.push(if up { [a, b, c] } else { [a, c, b] });
            }
        }
        Ok(out)
    }

    /// The best point to re-cone group `g` of `s` from: its tets `link` with `s` replaced by
    /// the point and the `floor` faces joined to it must all be positive, i.e. the point must
    /// lie strictly inside the kernel of the group's region. Candidates: the kernel's
    /// Chebyshev centre (the deepest point), points on the way from `s` to it (the kernel is
    /// convex and `s` is on its border), and the centroid of the group's other vertices; the
    /// valid one whose worst tet is best wins.
    fn best_apex(&self, s: u32, link: &[[u32; 4]], floor: &[[u32; 3]]) -> Option<[f64; 3]> {
        self.best_apex_scored(s, link, floor).map(|b| b.0)
    }

    /// [`Mesher::best_apex`] with the shape of the worst of its tets.
    fn best_apex_scored(
        &self,
        s: u32,
        link: &[[u32; 4]],
        floor: &[[u32; 3]],
    ) -> Option<([f64; 3], f64)> {
        let p = |v: u32| self.pts[v as usize];
        let ps = p(s);
        // Each new tet's face opposite the apex, in FACE order: the apex must be below it.
        let faces: Vec<[u32; 3]> = link
            .iter()
            .map(|t| {
                let i = t.iter().position(|&v| v == s).unwrap_or(0);
                FACE[i].map(|k| t[k])
            })
            .chain(floor.iter().copied())
            .collect();
        let score = |q: [f64; 3]| -> f64 {
            let mut worst = f64::INFINITY;
            for f in &faces {
                let c = [p(f[0]), p(f[1]), p(f[2]), q];
                if orient3d(c[0], c[1], c[2], c[3]) <= 0.0 {
                    return 0.0;
                }
                worst = worst.min(crate::geometry::tet_shape(c));
            }
            worst
        };
        let mut best: Option<([f64; 3], f64)> = None;
        let mut consider = |q: [f64; 3]| {
            let sc = score(q);
            if sc > 0.0 && best.map_or(true, |b| sc > b.1) {
                best = Some((q, sc));
            }
            sc > 0.0
        };
        let rel = |v: u32| glam::DVec3::from(p(v)) - glam::DVec3::from(ps);
        let mut reach = 0.0f64;
        let planes: Vec<([f64; 3], f64)> = faces
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(rel);
                let n = (b - a).cross(c - a);
                reach = reach.max(a.abs().max(b.abs()).max(c.abs()).max_element());
                // Below the face: n · (x - s) <= n · (a - s).
                (n.to_array(), n.dot(a))
            })
            .collect();
        // Whether the kernel's deepest point or a point on the way to it is valid.
        let deepest = |unit: bool, consider: &mut dyn FnMut([f64; 3]) -> bool| -> bool {
            let Some((c, _)) = crate::lp::chebyshev_center(ps, &planes, reach, unit) else {
                return false;
            };
            let centre = consider(c);
            let mut found = 0;
            let mut t = 0.5;
            for _ in 0..60 {
                let q = [0, 1, 2].map(|k| ps[k] + (c[k] - ps[k]) * t);
                if consider(q) {
                    found += 1;
                    if found == 2 {
                        break;
                    }
                }
                t *= 0.5;
            }
            centre || found > 0
        };
        let mut valid = deepest(false, &mut consider);
        let mut others: Vec<u32> = link.iter().flatten().copied().filter(|&v| v != s).collect();
        others.sort_unstable();
        others.dedup();
        let n = others.len().max(1) as f64;
        valid |= consider([0, 1, 2].map(|k| others.iter().map(|&v| p(v)[k]).sum::<f64>() / n));
        if !valid {
            // The raw program's tolerances are absolute: on a star far below unit size they
            // take its planes for zeros. Then the deepest point in units of the star.
            deepest(true, &mut consider);
        }
        best
    }

    /// Removes the points made by [`Mesher::suppress`] where the star of one can be re-coned
    /// from one of its own vertices (the one giving the best worst tet), a few rounds.
    fn remove_moved_points(&mut self, moved: &[u32]) {
        let mut left: Vec<u32> = moved.to_vec();
        let mut star = Vec::new();
        for _round in 0..4 {
            let before = left.len();
            left.retain(|&r| {
                self.tets.star(r, &mut star);
                !self.recone_from_link(r, &star)
            });
            if left.len() == before {
                break;
            }
        }
    }

    /// Moves each point made by [`Mesher::suppress`] that is still in the mesh to the best point
    /// of its star's kernel ([`Mesher::best_apex`], no floor: it lies on no facet) when that
    /// makes the star's worst tet better. A point moved off the surface where its wedge was a
    /// few rounding errors thick (next to a tiny input facet, say) stays within rounding of
    /// the facets even once flips have opened its star, and then leaves a neighbouring split
    /// point's wedge no room; its star's kernel has room by then.
    fn recentre_moved_points(&mut self, moved: &[u32]) {
        let mut star = Vec::new();
        for &r in moved {
            if self.tets.vertex_tet(r) == NONE {
                continue;
            }
            self.tets.star(r, &mut star);
            let link: Vec<[u32; 4]> = star.iter().map(|&t| self.tets.verts(t)).collect();
            let p = |v: u32| self.pts[v as usize];
            let now = link
                .iter()
                .map(|t| crate::geometry::tet_shape(t.map(p)))
                .fold(f64::INFINITY, f64::min);
            let Some((q, worst)) = self.best_apex_scored(r, &link, &[]) else {
                continue;
            };
            if worst > now {
                self.pts[r as usize] = q;
                self.tets.set_point(r, q);
            }
        }
    }

    /// Replaces the star of interior vertex `r` by the cone from the link vertex that gives
    /// the best worst tet, if that tet is positive and not much worse than the star's worst.
    /// Returns whether `r` is gone.
    fn recone_from_link(&mut self, r: u32, star: &[u32]) -> bool {
        if star.is_empty() {
            return false;
        }
        let p = |v: u32| self.pts[v as usize];
        let tets: Vec<[u32; 4]> = star.iter().map(|&t| self.tets.verts(t)).collect();
        // The cone must not make the worst tet much worse than the star's.
        let now = tets
            .iter()
            .map(|t| crate::geometry::tet_shape(t.map(p)))
            .fold(f64::INFINITY, f64::min);
        let mut cands: Vec<u32> = tets.iter().flatten().copied().filter(|&v| v != r).collect();
        cands.sort_unstable();
        cands.dedup();
        let mut best: Option<(u32, f64)> = None;
        for &w in &cands {
            let mut worst = f64::INFINITY;
            for t in tets.iter().filter(|t| !t.contains(&w)) {
                let c = t.map(|v| if v == r { p(w) } else { p(v) });
                if orient3d(c[0], c[1], c[2], c[3]) >= 0.0 {
                    worst = 0.0;
                    break;
                }
                worst = worst.min(crate::geometry::tet_shape(c));
            }
            if worst >= 0.5 * now && best.map_or(true, |b| worst > b.1) {
                best = Some((w, worst));
            }
        }
        let Some((w, _)) = best else {
            return false;
        };
        let reg = self.region_of(star[0]);
        let new: Vec<[u32; 4]> = tets
            .iter()
            .filter(|t| !t.contains(&w))
            .map(|t| t.map(|v| if v == r { w } else { v }))
            .collect();
        match self.tets.replace(star, &new, &[]) {
            Ok(ids) => {
                for t in ids {
                    self.set_region(t, reg);
                }
                true
            }
            Err(ReplaceError::Inverted(_) | ReplaceError::Mismatch(_)) => false,
        }
    }

    /// Refines bad tet `t` (corners `c`) once the surface is kept, with its circumcenter, the
    /// new vertex `m`; when that is refused and the tet is too large (volume bound or sizing
    /// test), with its centroid, which lies inside it and is refused near the surface by the
    /// same rules; otherwise the tet stays as it is (nothing may go on the surface).
    pub(super) fn take_tet_walled(
        &mut self,
        t: u32,
        c: [[f64; 3]; 4],
        m: u32,
    ) -> Result<(), Error> {
        let mut short2 = f64::INFINITY;
        for i in 0..4 {
            for j in i + 1..4 {
                short2 = short2.min(crate::geometry::dist2_3(c[i], c[j]));
            }
        }
        if self.insert3d_walled(m, t, 0.25 * short2) {
            self.steiner += 1;
            self.counts.tet += 1;
            return Ok(());
        }
        self.counts.tet_refused += 1;
        if !self.too_large(t, c) {
            self.pts.pop();
            return Ok(());
        }
        self.pts[m as usize] = [0, 1, 2].map(|k| 0.25 * (c[0][k] + c[1][k] + c[2][k] + c[3][k]));
        if self.insert3d_walled(m, t, 0.0625 * short2) {
            self.steiner += 1;
            self.counts.tet += 1;
        } else {
            self.pts.pop();
        }
        Ok(())
    }

    /// Inserts interior vertex `v` after the surface is kept: located by a walk from
    /// `self.hint` that never crosses a subface, with a walled, star-shaped cavity. Refused
    /// (nothing changes) when `v` is not reached that way, lies on a subface or is a vertex,
    /// or when it comes too close to a subface or subsegment of its cavity (see
    /// [`Mesher::encroaches_cavity`]): they cannot be split, and points ever closer to them
    /// would only make ever flatter tets next to them.
    ///
    /// As the tetrahedralization is not Delaunay next to the surface, a point must also remove
    /// the tet `bad` it is meant for, and keep at least `sqrt(gap2)` from every vertex of its
    /// cavity: in a Delaunay mesh both hold by themselves (the circumsphere of a tet is
    /// empty), and without them refinement can feed on itself there.
    pub(super) fn insert3d_walled(&mut self, v: u32, bad: u32, gap2: f64) -> bool {
        let p = self.pts[v as usize];
        self.hint = bad;
        let feat = &self.feat;
        let wall = |f: [u32; 3]| feat.subface(f).is_some();
        let Some(t) = self.tets.locate_walled(p, bad, &wall) else {
            return false;
        };
        if !self.tets.find_cavity_walled(p, t, &wall) {
            self.tets.cancel_cavity();
            return false;
        }
        let crowded = || {
            self.tets.cavity().iter().any(|&u| {
                self.tets
                    .verts(u)
                    .iter()
                    .any(|&w| crate::geometry::dist2_3(self.pts[w as usize], p) < gap2)
            })
        };
        if !self.tets.in_cavity(bad) || crowded() || self.encroaches_cavity(p) {
            self.tets.cancel_cavity();
            return false;
        }
        let reg = self.region_of(bad);
        while self.tets.num_vertices() <= v as usize {
            let q = self.pts[self.tets.num_vertices()];
            self.tets.push_vertex(q);
        }
        let new = self.tets.commit_cavity(v).to_vec();
        if let Some(&t) = new.first() {
            self.hint = t;
        }
        for t in new {
            self.set_region(t, reg);
            self.maybe_queue_tet(t);
        }
        true
    }
}

impl Mesher<'_> {
    /// Whether `p` lies strictly inside the lens ([`LENS_HEIGHT`]) of a subface or the
    /// diametral ball of a subsegment of the pending walled cavity (on its boundary, or an
    /// edge of its tets).
    fn encroaches_cavity(&self, p: [f64; 3]) -> bool {
        let at = |v: u32| self.pts[v as usize];
        for &h in self.tets.cavity_boundary() {
            let (t, f) = (h >> 2, (h & 3) as usize);
            let vs = self.tets.verts(t);
            let face = FACE[f].map(|k| vs[k]);
            if self.feat.subface(face).is_some() {
                let [a, b, c] = face.map(at);
                if in_lens_tri(a, b, c, p, LENS_HEIGHT) {
                    return true;
                }
            }
        }
        for &t in self.tets.cavity() {
            let vs = self.tets.verts(t);
            for (i, j) in super::EDGES {
                if self.feat.subseg(vs[i], vs[j]).is_some()
                    && in_diametral_ball_seg3(at(vs[i]), at(vs[j]), p)
                {
                    return true;
                }
            }
        }
        false
    }
}

/// The sides of the star tets of `s` on the free edge `ab` of a fin
/// ([`Mesher::suppress_on_fin`]) for a seam whose faces all turn one way seen along a
/// direction: `angle(v)` is the angle of link vertex `v` around `s` seen along that direction,
/// from `a` (0) through the side away from the fin to `b` (pi), and its distance to the fin's
/// plane. The seam is a path of link edges (faces through `s` that are not subfaces,
/// `neighbor(tet, face)` across them) from `a` to `b` over vertices strictly between 0 and pi
/// whose angle grows at every step, the one nearest the fin's plane in sum: with `q+ q-` along
/// that direction, each seam tet is positive for points close enough to `s`, and so is every
/// cone tet, whatever the sides. The sides are then those reached from the tets on the fin
/// (`forced`, with their sides in `init`) without crossing the fin or the seam. `None` when
/// there is no such path or the two sides meet.
#[allow(clippy::too_many_arguments)]
fn monotone_seam(
    s: u32,
    star: &[u32],
    tets: &[[u32; 4]],
    init: &[bool],
    forced: &[bool],
    [a, b]: [u32; 2],
    angle: impl Fn(u32) -> (f64, f64),
    neighbor: impl Fn(u32, usize) -> u32,
    is_subface: impl Fn([u32; 3]) -> bool,
) -> Option<Vec<bool>> {
    use std::f64::consts::PI;
    // The faces through s inside the star, as link edges (x, y) between star tets i and j.
    let mut links: Vec<(u32, u32, usize, usize)> = Vec::new();
    for (i, t) in tets.iter().enumerate() {
        for f in 0..4 {
            if t[f] == s {
                continue;
            }
            let face = FACE[f].map(|k| t[k]);
            if is_subface(face) {
                continue;
            }
            let j = star.iter().position(|&x| x == neighbor(star[i], f))?;
            if j < i {
                continue;
            }
            let mut xy = face.iter().copied().filter(|&v| v != s);
            let (x, y) = (xy.next()?, xy.next()?);
            links.push((x.min(y), x.max(y), i, j));
        }
    }
    // Link vertices in front of the free edge, by angle: (angle, distance, vertex, cost, from).
    let mut front: Vec<(f64, f64, u32, f64, u32)> = links
        .iter()
        .flat_map(|l| [l.0, l.1])
        .filter_map(|v| {
            let (th, h) = match v {
                _ if v == a => (0.0, 0.0),
                _ if v == b => (PI, 0.0),
                _ => angle(v),
            };
            let inside = v == a || v == b || (th > 0.0 && th < PI);
            inside.then_some((th, h, v, f64::INFINITY, NONE))
        })
        .collect();
    front.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.2.cmp(&y.2)));
    front.dedup_by_key(|x| x.2);
    let at = |front: &[(f64, f64, u32, f64, u32)], v: u32| front.iter().position(|x| x.2 == v);
    let start = at(&front, a)?;
    front[start].3 = 0.0;
    // Cheapest path in angle order (the edges only go forward, so one pass settles each).
    for k in 0..front.len() {
        let (th, _, v, cost, _) = front[k];
        if cost == f64::INFINITY {
            continue;
        }
        for l in &links {
            let w = if l.0 == v {
                l.1
            } else if l.1 == v {
                l.0
            } else {
                continue;
            };
            let Some(m) = at(&front, w) else {
                continue;
            };
            if front[m].0 > th && cost + front[m].1 < front[m].3 {
                front[m].3 = cost + front[m].1;
                front[m].4 = v;
            }
        }
    }
    let mut seam: Vec<(u32, u32)> = Vec::new();
    let mut v = b;
    while v != a {
        let from = front[at(&front, v)?].4;
        if from == NONE || seam.len() > front.len() {
            return None;
        }
        seam.push((v.min(from), v.max(from)));
        v = from;
    }
    // The sides, flooded from the tets on the fin across faces that are not on the seam.
    let mut side: Vec<Option<bool>> = vec![None; tets.len()];
    let mut queue: Vec<usize> = Vec::new();
    for i in (0..tets.len()).filter(|&i| forced[i]) {
        side[i] = Some(init[i]);
        queue.push(i);
    }
    while let Some(i) = queue.pop() {
        for l in links.iter().filter(|l| l.2 == i || l.3 == i) {
            if seam.contains(&(l.0, l.1)) {
                continue;
            }
            let j = if l.2 == i { l.3 } else { l.2 };
            match side[j] {
                None => {
                    side[j] = side[i];
                    queue.push(j);
                }
                Some(u) if Some(u) != side[i] => return None,
                Some(_) => {}
            }
        }
    }
    side.into_iter().collect()
}

/// Whether tet `t` of the star of `s` has one of the triangles `new` as its face opposite
/// `s` (a tet flat on a fin, between the old subfaces around `s` and a new one).
fn closes_new_triangle(s: u32, t: &[u32; 4], new: &[[u32; 3]]) -> bool {
    let Some(k) = t.iter().position(|&v| v == s) else {
        return false;
    };
    let link = fkey(FACE[k].map(|i| t[i]));
    new.iter().any(|&f| fkey(f) == link)
}

/// The tets that replace the star of `s` on the free edge `ab` of a fin
/// ([`Mesher::suppress_on_fin`]), into `out`, with [`QU`] and [`QD`] for the two new points:
/// each star tet (vertices `tets`, ids `star`) with `s` replaced by the point of its side
/// (`up`: true for [`QU`]), the fin's new triangles `new` coned from both points (but for
/// one a star tet closes, [`closes_new_triangle`], which that tet's replacement covers)
/// (counter-clockwise in the fin's projection seen from the upper side when `up_ccw`), and
/// the seam: for each face through `s` between an upper and a lower tet (`neighbor(tet,
/// face)`, not a subface by `is_subface`), the tet on `QU QD` and its other two vertices,
/// closed by one on `QU QD a b`. Returns, for each seam tet in order (they come last in
/// `out`), its upper and lower star tets (none for the last); `None` when the fin's new
/// triangles do not have the edge `ab`.
#[allow(clippy::too_many_arguments)]
fn fin_cones(
    s: u32,
    star: &[u32],
    tets: &[[u32; 4]],
    up: &[bool],
    new: &[[u32; 3]],
    up_ccw: bool,
    [a, b]: [u32; 2],
    neighbor: impl Fn(u32, usize) -> u32,
    is_subface: impl Fn([u32; 3]) -> bool,
    out: &mut Vec<[u32; 4]>,
) -> Option<Vec<Option<(usize, usize)>>> {
    out.clear();
    for (t, &u) in tets.iter().zip(up) {
        let q = if u { QU } else { QD };
        out.push(t.map(|v| if v == s { q } else { v }));
    }
    for &[x, y, z] in new {
        // A new triangle that a star tet closes has its cone tet from that tet, and a tet
        // outside the star on its other side.
        if tets.iter().any(|t| closes_new_triangle(s, t, &[[x, y, z]])) {
            continue;
        }
        out.push(if up_ccw { [QU, x, y, z] } else { [QU, x, z, y] });
        out.push(if up_ccw { [QD, x, z, y] } else { [QD, x, y, z] });
    }
    let mut seams = Vec::new();
    // A face through s seen from the upper tet, closed by the lower point in place of the
    // upper tet's fourth vertex: the tuple turns negative, and a swap makes it positive.
    for (i, (t, &u)) in tets.iter().zip(up).enumerate() {
        if !u {
            continue;
        }
        for f in 0..4 {
            if t[f] == s {
                continue;
            }
            let n = neighbor(star[i], f);
            let Some(j) = star.iter().position(|&x| x == n) else {
                continue;
            };
            // A tet that closes a new triangle lies on the fin: its faces through `s` are
            // the fin's, with no seam across.
            if up[j]
                || is_subface(FACE[f].map(|k| t[k]))
                || closes_new_triangle(s, t, new)
                || closes_new_triangle(s, &tets[j], new)
            {
                continue;
            }
            let mut seam = t.map(|v| if v == s { QU } else { v });
            seam[f] = QD;
            let mut uw = (0..4).filter(|&k| k != f && t[k] != s);
            let (Some(x), Some(y)) = (uw.next(), uw.next()) else {
                return None;
            };
            seam.swap(x, y);
            out.push(seam);
            seams.push(Some((i, j)));
        }
    }
    let &edge_tri = new.iter().find(|t| t.contains(&a) && t.contains(&b))?;
    let [x, y, z] = edge_tri;
    let mut seam = if up_ccw { [QU, x, y, z] } else { [QU, x, z, y] };
    let c = (1..4).find(|&k| seam[k] != a && seam[k] != b)?;
    seam[c] = QD;
    let mut uw = (1..4).filter(|&k| k != c);
    let (Some(x), Some(y)) = (uw.next(), uw.next()) else {
        return None;
    };
    seam.swap(x, y);
    out.push(seam);
    seams.push(None);
    Some(seams)
}
