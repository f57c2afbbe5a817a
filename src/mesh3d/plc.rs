//! PLC meshing (paper §4): the 3D Delaunay mesh, one 1D mesh per input edge and one 2D mesh
//! per facet, driven by a work queue in the order of Definition 4.1.
//!
//! * Points first: every point is inserted into the meshes of the features containing it,
//!   lowest dimension first, then into the 3D mesh (§6), as soon as it is made.
//! * Then simplices, lowest dimension first: subsegments, then subfaces, then tetrahedra.
//!   A queued simplex is re-verified when it is taken (it may be gone or already fine), unless
//!   it was queued because a point that must go in, or a refused circumcentre, encroaches it
//!   (see [`Why`]).
//! * The 3D mesh is always the Delaunay tetrahedralization of its vertices (no constraints):
//!   features appear in it because they are refined until they do (induction hypotheses 2, 3).
//! * Exterior, holes and regions are found by flooding across non-subfaces once every feature
//!   is present; quality refinement then treats only tetrahedra inside the domain.
//!
//! This file holds the [`Mesher`] state, point insertion into every mesh and the work loop
//! ([`Mesher::run`]). Its sub-modules each do one job: `split` (judging and splitting a
//! queued subsegment, subface or tet), `sharp` (small-angle protection and exemptions),
//! `classify` (regions by flooding), `output` (the result and its rounding slivers),
//! `constraints` (facet and segment size bounds), `frame` (meshing in a local frame),
//! `box_index` (which protection zones may contain a point), `sliver` (sliver removal),
//! `keep`, `flip` (`-Y`: taking Steiner points off the surface, then Lawson flips).

use std::collections::VecDeque;

mod box_index;
mod classify;
mod constraints;
mod flip;
mod frame;
pub(super) mod keep;
mod output;
pub(super) mod sharp;
pub(super) mod sliver;
mod split;

use sharp::Sharp;

use super::facet_mesh::{FacetChange, FacetInsertError, FacetMesh};
use super::features::{ekey, fkey, Features};
use super::store::{Located, Tets, GHOST};
use super::{Options3, TetMesh, NONE};
use crate::error::Error;
use crate::geometry::{tet_circumcenter, tet_radius_edge, tet_volume, tri_circumcenter3};
use crate::hash::FastMap as HashMap;
use crate::input3d::Plc;
use crate::predicates::{
    collinear3 as collinear, in_diametral_ball_seg3, in_diametral_ball_tri, orient3d,
};
use crate::progress::{stage, tick, Stage};

/// Refinement stops (with an error) before the kernel's slot space runs out.
const MAX_TET_SLOTS: usize = (1 << 30) - 1024;

/// Region id of tetrahedra outside the domain (exterior or holes).
const OUTSIDE: u32 = u32::MAX;

/// Region id of tetrahedra made while a subface was missing from the 3D mesh: their region is
/// found once conformity is restored (see [`Mesher::resolve_unknown`]).
const UNKNOWN: u32 = u32::MAX - 1;

/// Scratch mark of tetrahedra in the component being resolved.
const RESOLVING: u32 = u32::MAX - 2;

/// Why a subsegment or subface is on the work queue.
#[derive(Debug, Clone, Copy)]
enum Why {
    /// To be checked when taken: split only if missing from a mesh (or, outside lazy mode,
    /// encroached).
    Check,
    /// To be split unchecked: a point that must go in (a missing subface's split point, a
    /// rounding sliver's facet point) encroaches it or lies on it.
    Force,
    /// To be split unchecked for the bad tet in slot `.0` with corners `.1`, whose circumcentre
    /// was refused for encroaching it, while that tet is in the mesh. One split usually removes
    /// the tet; its other demands are then dropped, and the tets that replaced it are judged
    /// afresh (each encroached simplex split anyway would refine the surface for a tet that is
    /// gone: a tessellated pipe at -pq1.2 made 705k tets that way, 431k without).
    ForTet(u32, [u32; 4]),
}

impl Why {
    /// Whether the simplex is split without checking it first.
    fn forced(self) -> bool {
        !matches!(self, Why::Check)
    }
}

/// A simplex a refused point encroaches (to be split before retrying).
#[derive(Debug, Clone, Copy)]
enum Enc {
    Seg([u32; 2]),
    Face([u32; 3], u32),
}

struct Mesher<'a> {
    opts: &'a Options3,
    plc: &'a Plc,
    /// Squared size floor for quality work (see `below_floor`).
    floor2: f64,
    /// Bounding box of the input points (lowest and highest corner).
    bbox: [[f64; 3]; 2],
    /// A cavity crossed a subface of a facet the new point is not on: until conformity is
    /// restored, new tetrahedra get the region [`UNKNOWN`] (inheriting a region across the
    /// missing subface could be wrong) and are listed in `unknown`.
    dirty: bool,
    unknown: Vec<u32>,
    /// The surface is kept (`-Y`) and the exterior carved away: points enter through
    /// [`Mesher::insert3d_walled`] and nothing on the surface is split any more.
    walled: bool,
    pts: Vec<[f64; 3]>,
    tets: Tets,
    feat: Features,
    fmesh: Vec<FacetMesh>,
    seg_q: VecDeque<([u32; 2], Why)>,
    face_q: VecDeque<([u32; 3], u32, Why)>,
    tet_q: VecDeque<(u32, [u32; 4])>,
    /// Region per tetrahedron slot once classified (`OUTSIDE`, or 0 = no region, r + 1).
    region: Vec<u32>,
    classified: bool,
    region_max_vol: Vec<Option<f64>>,
    hint: u32,
    num_input: usize,
    steiner: u64,
    /// Steiner budget: quality refinement stops there, and feature recovery fails at twice as
    /// many (the caller's cap, or the budget of a second run in [`mesh_plc`]).
    hard_cap: u64,
    complete: bool,
    /// Small input angles (see [`Sharp`]): tets touching them are exempt from the
    /// radius-edge bound, so refinement cannot chase them forever.
    sharp: Sharp,
    /// Scratch: (sorted boundary face, region of the cavity tet behind it).
    face_region: Vec<([u32; 3], u32)>,
    /// Scratch buffers of `insert3d`, kept to avoid allocating per insertion.
    scratch_segs: Vec<[u32; 2]>,
    scratch_faces: Vec<([u32; 3], u32)>,
    scratch_new: Vec<u32>,
    /// What the Steiner points were made for, for the progress lines of `-V`.
    counts: Counts,
    /// Tets whose circumcentres were refused since the Steiner count was `refused_at`, with
    /// how often (see [`Mesher::place_for_tet`]).
    refused: HashMap<(u32, [u32; 4]), u8>,
    refused_at: u64,
    /// Facet area and segment length bounds.
    limits: constraints::Limits,
}

/// Steiner point counts by cause, reported in verbose progress lines.
#[derive(Default, Debug)]
struct Counts {
    /// Subsegments split because missing from the 3D mesh or a facet mesh (or encroached).
    seg_missing: u64,
    /// Subsegments split because a refused point encroached them.
    seg_forced: u64,
    /// Subfaces split because missing from the 3D mesh (or encroached).
    face_missing: u64,
    /// Subfaces split because a refused point encroached them.
    face_forced: u64,
    /// Circumcenters of tetrahedra inserted.
    tet: u64,
    /// Circumcenters of tetrahedra refused (encroaching).
    tet_refused: u64,
    /// Bad tetrahedra left as they are: refused twice (the second time after a whole cavity
    /// search) with no Steiner point inserted in between, so the splits their refusals demand
    /// change nothing (see [`Mesher::place_for_tet`]).
    tet_given_up: u64,
}

/// Meshes a PLC (already checked); far from the origin, in an exactly shifted frame
/// (`plc/frame.rs`), and in the caller's frame when the result does not survive the move
/// back (with a Steiner budget from the first run, so that the second cannot run away).
pub(crate) fn mesh_plc(plc: &Plc, opts: &Options3) -> Result<TetMesh, Error> {
    let Some(s) = frame::shift_of(plc) else {
        return mesh_plc_in(plc, opts, None, u64::MAX).map(|(m, _)| m.expect("no frame"));
    };
    let local = frame::shifted(plc, s);
    let o = frame::shifted_options(opts, s);
    let (mesh, steiner) = mesh_plc_in(&local, &o, Some(s), u64::MAX)?;
    if let Some(mut mesh) = mesh {
        frame::unshift(&mut mesh, s);
        if super::validate::validate_mesh(&mesh).is_ok() {
            return Ok(mesh);
        }
    }
    let cap = steiner.saturating_mul(8).saturating_add(1024);
    mesh_plc_in(plc, opts, None, cap).map(|(m, _)| m.expect("no frame"))
}

/// Meshes `plc`; with `frame`, the shift of the caller's frame, whose grid the Steiner points
/// are moved onto before output (no mesh when a tet turns over). Also returns the number of
/// Steiner points made. Past `hard_cap` Steiner points, quality refinement stops (the mesh is
/// incomplete) and feature recovery fails.
fn mesh_plc_in(
    plc: &Plc,
    opts: &Options3,
    frame: Option<[f64; 3]>,
    hard_cap: u64,
) -> Result<(Option<TetMesh>, u64), Error> {
    let feat = Features::new(plc).map_err(Error::Internal)?;
    let n = plc.points.len();
    let mut tets = Tets::with_capacity(n * 4 + 64);
    for &p in &plc.points {
        tets.push_vertex(p);
    }
    let limits = constraints::Limits::new(opts, &feat);
    let fmesh = feat
        .facets
        .iter()
        .map(|f| FacetMesh::new(f.axis, f.outline.clone()))
        .collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &plc.points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let mut m = Mesher {
        opts,
        plc,
        floor2: crate::geometry::dist2_3(lo, hi) * 2f64.powi(-72),
        bbox: [lo, hi],
        dirty: false,
        unknown: Vec::new(),
        walled: false,
        pts: plc.points.clone(),
        tets,
        feat,
        fmesh,
        seg_q: VecDeque::new(),
        face_q: VecDeque::new(),
        tet_q: VecDeque::new(),
        region: Vec::new(),
        classified: false,
        region_max_vol: plc.regions.iter().map(|r| r.max_volume).collect(),
        hint: NONE,
        num_input: n,
        steiner: 0,
        // The caller's Steiner cap bounds feature recovery too (at twice the cap), so that no
        // input (two facets 1e-11 apart asking for 1e8 points) can keep a capped run going.
        hard_cap: hard_cap.min(opts.max_steiner.unwrap_or(u64::MAX)),
        complete: true,
        sharp: Sharp::default(),
        face_region: Vec::new(),
        scratch_segs: Vec::new(),
        scratch_faces: Vec::new(),
        scratch_new: Vec::new(),
        counts: Counts::default(),
        refused: HashMap::default(),
        refused_at: 0,
        limits,
    };
    m.sharp = Sharp::find(plc, &m.feat, opts.radius_edge);
    stage(Stage::Delaunay, || (0, n as u64))?;
    m.insert_input_points()?;
    stage(Stage::Boundary, || (0, m.queued()))?;
    // Every subsegment and subface starts on the queue; taking one checks it.
    let mut keys: Vec<u64> = m.feat.subsegs.keys().copied().collect();
    keys.sort_unstable();
    for k in keys {
        m.seg_q
            .push_back(([(k >> 32) as u32, k as u32], Why::Check));
    }
    m.run()?;
    m.classify(plc)?;
    if opts.keep_surface {
        m.keep_input_surface()?;
    }
    if m.wants_quality() {
        stage(Stage::Refining, || (m.steiner, m.steiner))?;
        for t in 0..m.tets.num_slots() as u32 {
            m.maybe_queue_tet(t);
        }
        m.run()?;
        stage(Stage::Slivers, || (m.steiner, m.steiner))?;
        m.remove_slivers()?;
        // Regions are tracked through refinement (inherited from the cavity, or resolved
        // after conformity was restored); a full classification checks that and requeues any
        // tet whose region it corrects. It should find none; the rounds are a safety net.
        // (Walled cavities never cross a subface, so regions cannot go wrong there.) Rounding
        // slivers on a slanted facet can be on either side of it, and a fix makes new tets:
        // slivers are removed again (a rotated 15-gon prism kept one of 13.4° against a target
        // of 18°, made after the pass when hundreds of corrected regions were refined).
        for _round in 0..if m.walled { 0 } else { 8 } {
            if m.reclassify()? == 0 || !m.complete {
                break;
            }
            m.run()?;
            if m.complete {
                m.remove_slivers()?;
            }
        }
    } else if m.sliver_target().is_some() {
        // No bounds, but `-O` with scheme bit 4: only the (Delaunay) sliver pass.
        stage(Stage::Slivers, || (m.steiner, m.steiner))?;
        m.remove_slivers()?;
    }
    // A rounding sliver lying in a facet with the domain on both sides (an internal facet)
    // cannot be left out of the output like those touching the outside: split its subface
    // (the facet point at its circumcentre removes it) and refine again, slivers included.
    if !m.opts.keep_surface {
        stage(Stage::Slivers, || (m.steiner, m.steiner))?;
        for _round in 0..8 {
            let faces = m.interior_flat_slivers()?;
            if faces.is_empty() || !m.complete {
                break;
            }
            for (f, fid) in faces {
                m.face_q.push_back((f, fid, Why::Force));
            }
            m.run()?;
            if m.complete {
                m.remove_slivers()?;
            }
        }
    }
    super::validate::check_facet_points(&m.feat, &m.pts, m.num_input)?;
    m.feat.check_masks().map_err(Error::Internal)?;
    if let Some(s) = frame {
        if !m.snap_to_frame(s) {
            return Ok((None, m.steiner));
        }
    }
    // With -O the optimisation (`super::optimize`, after this) comes before Output.
    if opts.optimize_level == 0 {
        stage(Stage::Output, || (0, 4 * m.tets.num_slots() as u64))?;
    }
    Ok((Some(m.output(plc)?), m.steiner))
}

impl Mesher<'_> {
    fn wants_quality(&self) -> bool {
        self.opts.radius_edge.is_some()
            || self.opts.max_volume.is_some()
            || self.opts.sizing.is_some()
            || (self.opts.region_max_volume && self.region_max_vol.iter().any(|r| r.is_some()))
    }

    /// Inserts the input points into the facet meshes and the 3D mesh in one global order.
    fn insert_input_points(&mut self) -> Result<(), Error> {
        let order = super::order::brio_hilbert_order(&self.pts, 0x1d3e_5a11);
        // The 3D kernel needs a first tetrahedron: four non-coplanar points early in the order.
        let mut first = vec![order[0]];
        for &v in &order[1..] {
            let ok = match first.len() {
                1 => self.pts[v as usize] != self.pts[first[0] as usize],
                2 => !collinear(
                    self.pts[first[0] as usize],
                    self.pts[first[1] as usize],
                    self.pts[v as usize],
                ),
                3 => {
                    orient3d(
                        self.pts[first[0] as usize],
                        self.pts[first[1] as usize],
                        self.pts[first[2] as usize],
                        self.pts[v as usize],
                    ) != 0.0
                }
                _ => false,
            };
            if ok {
                first.push(v);
                if first.len() == 4 {
                    break;
                }
            }
        }
        if first.len() < 4 {
            return Err(Error::Input(crate::InputError::AllCollinear));
        }
        // Facet meshes: each facet takes its input vertices in the global order.
        let mut rank = vec![0u32; self.pts.len()];
        for (r, &v) in order.iter().enumerate() {
            rank[v as usize] = r as u32;
        }
        for f in 0..self.fmesh.len() {
            let mut vs = self.feat.facets[f].vertices.clone();
            vs.sort_by_key(|&v| rank[v as usize]);
            for v in vs {
                self.facet_insert(f as u32, v, false, None)
                    .map_err(|e| Error::Internal(format!("facet {f}: {e:?}")))?;
            }
        }
        self.tets.init(first[0], first[1], first[2], first[3]);
        self.hint = self.tets.vertex_tet(first[0]);
        for (k, &v) in order.iter().enumerate() {
            tick(|| (k as u64, order.len() as u64))?;
            if first.contains(&v) {
                continue;
            }
            self.insert3d(v, false, false).map_err(|_| {
                Error::Internal(format!("input point {v} refused in forced insertion"))
            })?;
        }
        Ok(())
    }

    /// Inserts vertex `v` into facet `f`'s mesh and books the subface changes.
    fn facet_insert(
        &mut self,
        f: u32,
        v: u32,
        provisional: bool,
        split_of: Option<[u32; 2]>,
    ) -> Result<(), FacetInsertError> {
        let feat = &self.feat;
        let is_sub = |a: u32, b: u32| feat.subseg(a, b).is_some();
        let flat = |t: [u32; 3]| feat.on_one_edge(t);
        let ch =
            self.fmesh[f as usize].insert(v, &self.pts, provisional, &is_sub, &flat, split_of)?;
        self.apply_facet_change(f, ch);
        Ok(())
    }

    /// Records a facet mesh's change: its new subfaces (queued for a check), the ones gone,
    /// and the subsegments it encroaches.
    fn apply_facet_change(&mut self, f: u32, ch: FacetChange) {
        for t in ch.removed {
            self.feat.subfaces.remove(&fkey(t));
        }
        for t in ch.added {
            self.feat.subfaces.insert(fkey(t), f);
            self.face_q.push_back((t, f, Why::Check));
        }
        for s in ch.encroached {
            self.seg_q.push_back((s, Why::Check));
        }
    }

    /// Brings subsegment `a b` back into the facet meshes that lost it to their outside
    /// scaffolding ([`FacetMesh::recover_edge`]), before it is judged missing and split;
    /// whether some facet mesh still lacks it.
    fn recover_in_facets(&mut self, a: u32, b: u32, e: u32) -> bool {
        let mut missing = false;
        for i in 0..self.feat.edges[e as usize].facets.len() {
            let f = self.feat.edges[e as usize].facets[i];
            let fm = &self.fmesh[f as usize];
            if !fm.started() || fm.has_edge(a, b) {
                continue;
            }
            let feat = &self.feat;
            let is_sub = |x: u32, y: u32| feat.subseg(x, y).is_some();
            let flat = |t: [u32; 3]| feat.on_one_edge(t);
            if let Some(ch) = self.fmesh[f as usize].recover_edge(a, b, &self.pts, &is_sub, &flat) {
                self.apply_facet_change(f, ch);
            }
            missing |= !self.fmesh[f as usize].has_edge(a, b);
        }
        missing
    }

    /// Inserts vertex `v` into the 3D mesh. Provisional insertion is refused (nothing changes)
    /// when `v` encroaches a subsegment or subface, which are returned: with `early`, only
    /// those of the first cavity tet that shows any (the cavity search stops there).
    fn insert3d(&mut self, v: u32, provisional: bool, early: bool) -> Result<(), Vec<Enc>> {
        debug_assert!(!self.walled, "insert3d on a carved mesh");
        let p = self.pts[v as usize];
        let start = match self.tets.locate(p, self.hint) {
            Located::InTet(t) => t,
            Located::Vertex(_) => return Err(Vec::new()),
        };
        let mut enc: Vec<Enc> = Vec::new();
        if provisional && early {
            // A provisional point is refused as soon as one cavity tet shows a subsegment or
            // subface it encroaches (or a subface the cavity crosses): the splits queued for
            // that tet's features stand for the point, as any encroached feature may, and the
            // rest of the cavity is not searched. Refused circumcentres beyond the boundary
            // have huge cavities reaching outside the domain: searching them whole took four
            // fifths of a CAD rotor's refinement at -pq (832,000 of 972,000 cavity tets).
            let (feat, pts) = (&self.feat, &self.pts);
            let found = self
                .tets
                .find_cavity_visit(p, start, usize::MAX, |vs, joined| {
                    if !vs.contains(&GHOST) {
                        encroached_in(feat, pts, p, vs, joined, |e, _, _| enc.push(e));
                    }
                    enc.is_empty()
                });
            match found {
                Some(true) => {}
                Some(false) => {
                    self.tets.cancel_cavity();
                    return Err(Vec::new());
                }
                None => {
                    self.tets.cancel_cavity();
                    return Err(enc);
                }
            }
        } else if !self.tets.find_cavity(p, start) {
            self.tets.cancel_cavity();
            return Err(Vec::new());
        }
        let mut touched_segs = std::mem::take(&mut self.scratch_segs);
        let mut touched_faces = std::mem::take(&mut self.scratch_faces);
        touched_segs.clear();
        touched_faces.clear();
        self.face_region.clear();
        for &t in self.tets.cavity() {
            let vs = self.tets.verts(t);
            if vs.contains(&GHOST) {
                // Hull faces of ghosts are seen from the real tet on the other side.
                for f in 0..4 {
                    let (n, _) = self.tets.neighbor(t, f);
                    if !self.tets.in_cavity(n) {
                        self.face_region.push((fkey(face_of(vs, f)), OUTSIDE));
                    }
                }
                continue;
            }
            let reg = self.region_of(t);
            for f in 0..4 {
                let fv = face_of(vs, f);
                let (n, _) = self.tets.neighbor(t, f);
                let crossed = self.tets.in_cavity(n);
                if !crossed {
                    self.face_region.push((fkey(fv), reg));
                }
                if let Some(fid) = self.feat.subface(fv) {
                    let [a, b, c] = fv.map(|x| self.pts[x as usize]);
                    if crossed || in_diametral_ball_tri(a, b, c, p) {
                        enc.push(Enc::Face(fv, fid));
                    }
                    if crossed
                        && !self
                            .feat
                            .vert_facets
                            .get(&v)
                            .is_some_and(|fs| fs.contains(&fid))
                    {
                        self.dirty = true;
                    }
                    let k = fkey(fv);
                    if !listed_already(&touched_faces, |&(g, _)| fkey(g) == k) {
                        touched_faces.push((fv, fid));
                    }
                }
            }
            for (i, j) in EDGES {
                let (a, b) = (vs[i], vs[j]);
                if self.feat.subseg(a, b).is_some() {
                    if in_diametral_ball_seg3(self.pts[a as usize], self.pts[b as usize], p) {
                        enc.push(Enc::Seg([a, b]));
                    }
                    if !listed_already(&touched_segs, |&[x, y]| {
                        (x == a && y == b) || (x == b && y == a)
                    }) {
                        touched_segs.push([a, b]);
                    }
                }
            }
        }
        // A point outside the input's bounding box is outside the domain: in exact arithmetic
        // it encroaches a subface and is refused above; should rounding let it slip past that
        // test, it is refused all the same (inserting it would feed a runaway outside).
        if provisional && (!enc.is_empty() || !self.in_box(p)) {
            self.tets.cancel_cavity();
            self.scratch_segs = touched_segs;
            self.scratch_faces = touched_faces;
            return Err(enc);
        }
        self.face_region.sort_unstable();
        // Steiner vertices enter the kernel only when they are really inserted.
        while self.tets.num_vertices() <= v as usize {
            let q = self.pts[self.tets.num_vertices()];
            self.tets.push_vertex(q);
        }
        let mut new = std::mem::take(&mut self.scratch_new);
        new.clear();
        new.extend_from_slice(self.tets.commit_cavity(v));
        if let Some(&t) = new.first() {
            self.hint = t;
        }
        for &s in &touched_segs {
            self.seg_q.push_back((s, Why::Check));
        }
        for &(f, fid) in &touched_faces {
            self.face_q.push_back((f, fid, Why::Check));
        }
        if self.classified {
            for &t in &new {
                let vs = self.tets.verts(t);
                let reg = if vs.contains(&GHOST) {
                    OUTSIDE
                } else if self.dirty {
                    self.unknown.push(t);
                    UNKNOWN
                } else {
                    let k = (0..4).find(|&k| vs[k] == v).unwrap_or(0);
                    let key = fkey(face_of(vs, k));
                    match self.face_region.binary_search_by(|e| e.0.cmp(&key)) {
                        Ok(i) => self.face_region[i].1,
                        Err(_) => OUTSIDE,
                    }
                };
                self.set_region(t, reg);
                self.maybe_queue_tet(t);
            }
        }
        self.scratch_segs = touched_segs;
        self.scratch_faces = touched_faces;
        self.scratch_new = new;
        Ok(())
    }

    fn region_of(&self, t: u32) -> u32 {
        self.region.get(t as usize).copied().unwrap_or(OUTSIDE)
    }

    fn set_region(&mut self, t: u32, r: u32) {
        let i = t as usize;
        if self.region.len() <= i {
            self.region.resize(i + 1, OUTSIDE);
        }
        self.region[i] = r;
    }

    /// Makes a new vertex (not yet in any mesh).
    fn new_vertex(&mut self, p: [f64; 3]) -> Result<u32, Error> {
        if self.pts.len() >= (u32::MAX - 16) as usize {
            return Err(Error::Internal("too many vertices".into()));
        }
        self.pts.push(p);
        Ok((self.pts.len() - 1) as u32)
    }

    /// Whether a simplex is too small for quality work: its shortest edge is below 2^-36 of the
    /// input's diameter. Quality refinement (and the splits a refused circumcenter demands)
    /// stops there instead of running into the limits of floating point; feature recovery is
    /// never cut short by this.
    fn below_floor(&self, c: &[[f64; 3]]) -> bool {
        let mut e2 = f64::INFINITY;
        for i in 0..c.len() {
            for j in i + 1..c.len() {
                e2 = e2.min(crate::geometry::dist2_3(c[i], c[j]));
            }
        }
        e2 < self.floor2
    }

    /// Whether `p` lies in the bounding box of the input points.
    fn in_box(&self, p: [f64; 3]) -> bool {
        (0..3).all(|k| self.bbox[0][k] <= p[k] && p[k] <= self.bbox[1][k])
    }

    /// Subsegments, subfaces and tets waiting on the work queue (the progress estimate).
    fn queued(&self) -> u64 {
        (self.seg_q.len() + self.face_q.len() + self.tet_q.len()) as u64
    }

    fn cap_reached(&self) -> bool {
        self.opts.max_steiner.is_some_and(|c| self.steiner >= c) || self.steiner >= self.hard_cap
    }

    /// The work loop: subsegments, then subfaces, then tetrahedra (Definition 4.1).
    fn run(&mut self) -> Result<(), Error> {
        let budget = 1u64 << 40;
        for it in 0..budget {
            tick(|| (self.steiner, self.steiner + self.queued()))?;
            // Recovering the features costs a few queue entries per split point; 16 per point
            // of the budget bounds the work of a run whose queue fills with subsegments that
            // are fine (two facets 1e-10 apart: a million entries for 10k points).
            let work_cap = self.hard_cap.saturating_add(self.num_input as u64);
            if self.steiner / 2 > self.hard_cap || (!self.classified && it / 16 > work_cap) {
                return Err(self.budget_error());
            }
            if self.opts.verbose && it % (1 << 12) == (1 << 12) - 1 {
                let c = &self.counts;
                eprintln!(
                    "idmesh: work queue: {} subsegments, {} subfaces, {} tets; {} Steiner points \
                     (segment splits {}+{} forced, facet splits {}+{} forced, tet circumcenters {}, \
                     {} refused, {} bad tets left)",
                    self.seg_q.len(),
                    self.face_q.len(),
                    self.tet_q.len(),
                    self.steiner,
                    c.seg_missing,
                    c.seg_forced,
                    c.face_missing,
                    c.face_forced,
                    c.tet,
                    c.tet_refused,
                    c.tet_given_up
                );
            }
            if let Some((s, why)) = self.seg_q.pop_front() {
                if !self.obsolete(why) {
                    self.take_subseg(s, why.forced())?;
                }
            } else if let Some((f, fid, why)) = self.face_q.pop_front() {
                if !self.obsolete(why) {
                    self.take_subface(f, fid, why)?;
                }
            } else if self.dirty && self.classified {
                // Conformity is restored: find the regions of the tets made meanwhile before
                // judging tets again.
                self.dirty = false;
                self.resolve_unknown()?;
            } else if let Some((t, vs)) = self.tet_q.pop_front() {
                if self.cap_reached() {
                    self.complete = false;
                    self.tet_q.clear();
                    continue;
                }
                if self.tets.num_slots() > MAX_TET_SLOTS {
                    return Err(Error::Internal("out of tetrahedron slots".into()));
                }
                self.take_tet(t, vs)?;
            } else {
                return Ok(());
            }
        }
        Err(Error::Internal("work loop budget exhausted".into()))
    }

    /// The error when recovering the features runs out of budget: where a facet with work
    /// on the queue has an input point too close to it to be meshed apart (3D campaign seed
    /// 8 run 5813: two tiny facets 1e-27 apart split each other until the budget), that
    /// input error ([`Mesher::too_close_at`], tried on the first 64 such facets); else an
    /// internal error.
    fn budget_error(&self) -> Error {
        let internal = format!(
            "the input's edges and facets were not recovered within {} Steiner points (work \
             budget)",
            self.steiner
        );
        let p = |v: u32| self.pts[v as usize];
        let faces = self.face_q.iter().map(|&(v, fid, _)| {
            let at = [0, 1, 2].map(|k| (p(v[0])[k] + p(v[1])[k] + p(v[2])[k]) / 3.0);
            (at, fid)
        });
        let segs = self.seg_q.iter().filter_map(|&([a, b], _)| {
            let e = self.feat.subseg(a, b)?;
            let fid = *self.feat.edges[e as usize].facets.first()?;
            Some(([0, 1, 2].map(|k| 0.5 * (p(a)[k] + p(b)[k])), fid))
        });
        let mut tried = std::collections::HashSet::new();
        for (at, fid) in segs.chain(faces) {
            if tried.len() >= 64 {
                break;
            }
            if !tried.insert(fid) {
                continue;
            }
            // Only a point next to the work as well as to the plane: a coplanar neighbour's
            // vertex far from it is not what keeps the queue busy.
            if let e @ Error::Input(crate::error::InputError::PointTooCloseToFacet {
                point, ..
            }) = self.too_close_at(at, fid, String::new())
            {
                if crate::geometry::dist2_3(p(point as u32), at) < self.floor2 * 65536.0 {
                    return e;
                }
            }
        }
        Error::Internal(internal)
    }
}

/// The six edges of a tetrahedron as corner pairs.
const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// The features of a tet joining the cavity of point `p` that `p` encroaches, to which it
/// yields (paper §4): each subface of the tet that holds `p` in its diametral ball or that the
/// cavity crosses (`joined[f]`: the neighbour across face `f` joined before), and each
/// subsegment that holds `p` in its diametral ball. `found` gets each with, for a subface,
/// whether the cavity crosses it and whether `p` is in its ball.
fn encroached_in(
    feat: &Features,
    pts: &[[f64; 3]],
    p: [f64; 3],
    vs: [u32; 4],
    joined: [bool; 4],
    mut found: impl FnMut(Enc, bool, bool),
) {
    for (f, &crossed) in joined.iter().enumerate() {
        let fv = face_of(vs, f);
        if let Some(fid) = feat.subface(fv) {
            let [a, b, c] = fv.map(|x| pts[x as usize]);
            let ball = in_diametral_ball_tri(a, b, c, p);
            if crossed || ball {
                found(Enc::Face(fv, fid), crossed, ball);
            }
        }
    }
    for (i, j) in EDGES {
        let (a, b) = (vs[i], vs[j]);
        if feat.subseg(a, b).is_some()
            && in_diametral_ball_seg3(pts[a as usize], pts[b as usize], p)
        {
            found(Enc::Seg([a, b]), false, true);
        }
    }
}

/// The face of a tetrahedron opposite corner `f`.
#[inline]
fn face_of(v: [u32; 4], f: usize) -> [u32; 3] {
    match f {
        0 => [v[1], v[2], v[3]],
        1 => [v[0], v[2], v[3]],
        2 => [v[0], v[1], v[3]],
        _ => [v[0], v[1], v[2]],
    }
}

/// Whether a feature that an insertion touched is already listed (`same`) for a check: every
/// cavity tetrahedron around a subsegment, and both sides of a crossed subface, see it, and a
/// second check queued right behind the first mostly finds nothing new (a later insertion
/// that changes the feature's neighbourhood lists it again). Long lists (a huge cavity) are
/// not searched: a repeated check costs less than the search.
fn listed_already<T>(listed: &[T], same: impl Fn(&T) -> bool) -> bool {
    listed.len() <= 64 && listed.iter().any(same)
}

/// Whether `p` lies exactly on the line through `a` and `b` (2D).
fn on_line2(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    crate::predicates::orient2d(a, b, p) == 0.0
}
