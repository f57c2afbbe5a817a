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

use std::collections::VecDeque;

mod box_index;
mod constraints;
mod flip;
mod frame;
pub(super) mod keep;
pub(super) mod sliver;

use super::facet_mesh::{FacetChange, FacetInsertError, FacetMesh};
use super::features::{ekey, fkey, Features};
use super::store::{Located, Tets, GHOST};
use super::{Options3, TetMesh, NONE};
use crate::error::Error;
use crate::geometry::{tet_circumcenter, tet_radius_edge, tet_volume, tri_circumcenter3};
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
        // (Walled cavities never cross a subface, so regions cannot go wrong there.)
        for _round in 0..if m.walled { 0 } else { 8 } {
            if m.reclassify()? == 0 || !m.complete {
                break;
            }
            m.run()?;
        }
    } else if m.sliver_target().is_some() {
        // No bounds, but `-O` with scheme bit 4: only the (Delaunay) sliver pass.
        stage(Stage::Slivers, || (m.steiner, m.steiner))?;
        m.remove_slivers()?;
    }
    // A rounding sliver lying in a facet with the domain on both sides (an internal facet)
    // cannot be left out of the output like those touching the outside: split its subface
    // (the facet point at its circumcentre removes it) and refine again.
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
        }
    }
    super::validate::check_facet_points(&m.feat, &m.pts, m.num_input)?;
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
            self.insert3d(v, false).map_err(|_| {
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
    /// scaffolding ([`FacetMesh::recover_edge`]), before it is judged missing and split.
    fn recover_in_facets(&mut self, a: u32, b: u32, e: u32) {
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
        }
    }

    /// Inserts vertex `v` into the 3D mesh. Provisional insertion is refused (nothing changes)
    /// when `v` encroaches a subsegment or subface, which are returned.
    fn insert3d(&mut self, v: u32, provisional: bool) -> Result<(), Vec<Enc>> {
        debug_assert!(!self.walled, "insert3d on a carved mesh");
        let p = self.pts[v as usize];
        let start = match self.tets.locate(p, self.hint) {
            Located::InTet(t) => t,
            Located::Vertex(_) => return Err(Vec::new()),
        };
        if !self.tets.find_cavity(p, start) {
            self.tets.cancel_cavity();
            return Err(Vec::new());
        }
        let mut enc: Vec<Enc> = Vec::new();
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
                    touched_faces.push((fv, fid));
                }
            }
            for (i, j) in EDGES {
                let (a, b) = (vs[i], vs[j]);
                if self.feat.subseg(a, b).is_some() {
                    if in_diametral_ball_seg3(self.pts[a as usize], self.pts[b as usize], p) {
                        enc.push(Enc::Seg([a, b]));
                    }
                    touched_segs.push([a, b]);
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
                     {} refused)",
                    self.seg_q.len(),
                    self.face_q.len(),
                    self.tet_q.len(),
                    self.steiner,
                    c.seg_missing,
                    c.seg_forced,
                    c.face_missing,
                    c.face_forced,
                    c.tet,
                    c.tet_refused
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

    /// Whether subsegment `ab` is missing from the 3D mesh or a facet mesh, or encroached.
    fn subseg_needs_split(&self, a: u32, b: u32, e: u32) -> bool {
        let Some(t0) = self.tets.find_edge(a, b) else {
            return true;
        };
        for &f in &self.feat.edges[e as usize].facets {
            let fm = &self.fmesh[f as usize];
            if fm.started() && !fm.has_edge(a, b) {
                return true;
            }
        }
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

    fn take_subseg(&mut self, s: [u32; 2], force: bool) -> Result<(), Error> {
        let [a, b] = s;
        let Some(e) = self.feat.subseg(a, b) else {
            return Ok(());
        };
        self.recover_in_facets(a, b, e);
        if !force && !self.subseg_needs_split(a, b, e) && !self.seg_over_bound(a, b, e) {
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
        self.insert3d(m, false)
            .map_err(|_| Error::Internal(format!("segment split point {m} refused")))
    }

    /// Whether subsegment `ab` of input edge `e` exceeds its length bound (and is above the
    /// size floor).
    fn seg_over_bound(&self, a: u32, b: u32, e: u32) -> bool {
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        self.limits.seg_too_long(e, pa, pb) && !self.below_floor(&[pa, pb])
    }

    /// Whether subface `v` of facet `fid` exceeds its area bound (and is above the size floor).
    fn face_over_bound(&self, v: [u32; 3], fid: u32) -> bool {
        let c = v.map(|x| self.pts[x as usize]);
        self.limits.face_too_large(fid, c) && !self.below_floor(&c)
    }

    /// Where to split subsegment `ab`: the midpoint, or, when exactly one end is an input vertex
    /// where input edges meet (an apex), the point at the power-of-two distance from it nearest
    /// to half the length (Ruppert's concentric shells): split points of edges meeting at a
    /// small angle then sit at equal distances from the apex and stop encroaching each other.
    fn split_point(&self, a: u32, b: u32) -> [f64; 3] {
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
    fn subface_needs_split(&self, v: [u32; 3]) -> bool {
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

    fn take_subface(&mut self, v: [u32; 3], fid: u32, why: Why) -> Result<(), Error> {
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
        self.feat.mark_feature(m);
        self.feat.vert_facets.insert(m, vec![fid]);
        self.insert3d(m, false)
            .map_err(|_| Error::Internal(format!("facet point {m} refused")))
    }

    /// The error for a subface `v` of facet `fid` that conformity needs split but the size
    /// floor forbids: the input point nearest to it off the facet is too close to the facet
    /// (an input error naming both) when it lies within 2^8 size floors of the facet's plane;
    /// otherwise (no input point that close: the floor was reached for another reason) an
    /// internal error saying `what`.
    fn too_close(&self, v: [u32; 3], fid: u32, what: &str) -> Error {
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
    fn too_close_at(&self, centroid: [f64; 3], fid: u32, internal: String) -> Error {
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
    fn follow_3d(&mut self, v: [u32; 3], fid: u32) -> bool {
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
    fn defer_to_segments(&mut self, segs: &[[u32; 2]], v: [u32; 3], fid: u32, why: Why) -> bool {
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
    fn obsolete(&self, why: Why) -> bool {
        match why {
            Why::ForTet(t, vs) => !self.tets.alive(t) || self.tets.verts(t) != vs,
            Why::Check | Why::Force => false,
        }
    }

    fn is_bad(&self, t: u32) -> bool {
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
    fn too_large(&self, t: u32, c: [[f64; 3]; 4]) -> bool {
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

    fn maybe_queue_tet(&mut self, t: u32) {
        if !self.tets.alive(t) || self.tets.is_ghost(t) || self.region_of(t) >= UNKNOWN {
            return;
        }
        if self.is_bad(t) {
            self.tet_q.push_back((t, self.tets.verts(t)));
        }
    }

    fn take_tet(&mut self, t: u32, vs: [u32; 4]) -> Result<(), Error> {
        if !self.tets.alive(t) || self.tets.verts(t) != vs || self.region_of(t) >= UNKNOWN {
            return Ok(());
        }
        let c = vs.map(|x| self.pts[x as usize]);
        if self.below_floor(&c) {
            return Ok(());
        }
        let Some(mut cc) = tet_circumcenter(c) else {
            return Ok(());
        };
        // The rounded circumcenter of a nearly flat tet (four nearly cocircular points) can be
        // far from the true one and outside the tet's circumsphere: inserting it would leave
        // the tet in place. Its centroid is in the sphere (inside the tet) and removes it.
        let o = crate::predicates::orient3d(c[0], c[1], c[2], c[3]);
        if crate::predicates::insphere(c[0], c[1], c[2], c[3], cc) * o <= 0.0 {
            cc = [0, 1, 2].map(|k| 0.25 * (c[0][k] + c[1][k] + c[2][k] + c[3][k]));
        }
        self.place_for_tet(t, vs, c, cc)
    }

    /// Inserts `cc`, a point inside the circumsphere of tet `t` (vertices `vs`, corners `c`),
    /// provisionally to remove `t`; when refused, queues the splits it demands and `t` again.
    fn place_for_tet(
        &mut self,
        t: u32,
        vs: [u32; 4],
        c: [[f64; 3]; 4],
        cc: [f64; 3],
    ) -> Result<(), Error> {
        let m = self.new_vertex(cc)?;
        if self.walled {
            return self.take_tet_walled(t, c, m);
        }
        match self.insert3d(m, true) {
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
    fn subface_towards(&self, t: u32, p: [f64; 3]) -> Option<([u32; 3], u32)> {
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

    /// Gives the tets made while conformity was broken (region [`UNKNOWN`]) their region, now
    /// that every subface is back in the 3D mesh: each connected group of them (across
    /// non-subfaces) takes the region of the known tets next to it, which regions cannot
    /// cross. A group with no known neighbour, or with neighbours that disagree, falls back on
    /// a full classification. Then the resolved tets are judged for quality.
    fn resolve_unknown(&mut self) -> Result<(), Error> {
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
    fn reclassify(&mut self) -> Result<usize, Error> {
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
    fn classify(&mut self, plc: &Plc) -> Result<(), Error> {
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
    fn open_surface(&self) -> Error {
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

    fn seed_tet(&self, p: [f64; 3]) -> Option<u32> {
        match self.tets.locate(p, self.hint) {
            Located::InTet(t) if !self.tets.is_ghost(t) => Some(t),
            Located::InTet(_) => None,
            // A Steiner point landed exactly on the seed: any real tet around it will do.
            Located::Vertex(v) => {
                let mut star = Vec::new();
                self.tets.star(v, &mut star);
                star.into_iter().find(|&t| !self.tets.is_ghost(t))
            }
        }
    }

    fn flood(
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

    /// Rounding slivers at the domain's boundary, which the output leaves out: tets inside
    /// the domain whose four vertices lie on one facet (flat in exact terms; Steiner points
    /// rounded off a slanted facet make them) and that touch the outside, directly or through
    /// other such slivers. Their other faces, which lie in the same facet, become the
    /// boundary. Slivers elsewhere (on internal facets: dropping them would tear the mesh
    /// apart) are split away after refinement (see [`Mesher::interior_flat_slivers`]).
    fn rounding_slivers_on_boundary(&self) -> crate::hash::FastSet<u32> {
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
    fn interior_flat_slivers(&self) -> Result<Vec<([u32; 3], u32)>, Error> {
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

    fn output(&self, plc: &Plc) -> Result<TetMesh, Error> {
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

/// The six edges of a tetrahedron as corner pairs.
const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

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

/// Whether `p` lies exactly on the line through `a` and `b` (2D).
fn on_line2(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    crate::predicates::orient2d(a, b, p) == 0.0
}

/// Input angles below 60°: between two input edges at a vertex (for two edges of one facet,
/// below [`wedge_sharp_angle`]), and between two facets along an edge (dihedral). Radius-edge
/// refinement next to them would never end (each split makes a smaller bad tet between the two
/// features), so tets whose badness they cause are exempt from the bound, as Triangle and the
/// paper (§6) do for small 2D angles.
///
/// At a sharp vertex the judgement goes by the tet's shortest edge, which is what makes its
/// radius-edge ratio large: only a short edge pinned by the small angle excuses the tet (one
/// ending in the apex's protection ball, one across the wedge between concentric shells, or
/// one next to a thin wedge). A tet that merely touches a sharp vertex is not excused:
/// exempting every such tet, however large, left whole inputs unrefined (a finely triangulated
/// CAD surface has a sharp vertex almost everywhere).
#[derive(Default)]
pub(super) struct Sharp {
    /// Input vertices where two input edges meet below 60° (two edges of one facet: below
    /// [`wedge_sharp_angle`]).
    pub(super) vertices: crate::hash::FastSet<u32>,
    /// Input edges along which two facets meet below 60°.
    edges: crate::hash::FastSet<u32>,
    /// Facet pairs (smaller id first) meeting below 60° along an edge or at a vertex.
    facet_pairs: crate::hash::FastSet<(u32, u32)>,
    /// Input edge pairs (smaller id first) meeting at a sharp vertex, with the apex's position:
    /// a tet whose shortest edge joins points of the two at equal distances from the apex (the
    /// concentric shells of [`Mesher::split_point`]) spans the wedge, and refining it would
    /// only move the problem closer to the apex (Triangle's rule for a skinny triangle whose
    /// short edge faces a small input angle).
    seg_pairs: crate::hash::FastMap<(u32, u32), [f64; 3]>,
    /// The angle (degrees) of each pair of `seg_pairs`: sliver removal exempts only pairs
    /// narrower than its target (see [`Sharp::exempts_sliver`]).
    pair_angle: crate::hash::FastMap<(u32, u32), f64>,
    /// Per facet: protection zones of the sharp edges on it. Tets with a vertex on the facet
    /// inside a zone are exempt: next to a sharp edge the two facets' refinement feeds itself
    /// (each split near one facet encroaches the other), ever closer to the edge.
    zones: Vec<Vec<Zone>>,
    /// Protection zones of thin wedges (see [`Wedge`]).
    wedges: Vec<Wedge>,
    /// Protection balls of the sharp vertices: (apex, squared radius), the radius
    /// [`BALL_FRACTION`] of the shorter edge of a sharp pair there (the largest such). Inside, the concentric shells
    /// split the edges and tets with a shortest edge ending there are not refined (corner
    /// lopping, as in Pav and Walkington's Delaunay refinement for small angles): below the
    /// theoretical bound (a radius-edge ratio of 2) refinement next to a sharp vertex can
    /// otherwise run towards it (a triangulated U-shaped part at -pq1.2: 4,000 tets within 0.02 of one 9-degree corner).
    balls: Vec<([f64; 3], f64)>,
    /// Per ball: the smallest angle (degrees) of a sharp pair at its vertex.
    ball_angle: Vec<f64>,
    /// `balls` and `wedges` indexed by their boxes (nearly every vertex of a scanned surface
    /// is sharp: scanning them all for every tet made refinement quadratic).
    ball_index: box_index::BoxIndex,
    wedge_index: box_index::BoxIndex,
}

/// The part of a sharp vertex's protection ball (relative to its radius) inside which
/// sliver removal excuses every tet ([`Sharp::deep_in_ball`]).
const DEEP_FRACTION: f64 = 1.0 / 16.0;

/// A thin wedge: two input edges from `apex` to `ends` meeting at an angle whose sine is below
/// [`THIN_WEDGE`], with its protection zone, the points within `sqrt(r2)` of both edges
/// (bounding box `lo`, `hi`). The two edges run side by side along their whole length (0.07°
/// needle triangles of a triangulated U-shaped part: two edges 0.04 long never more than 5e-5 apart), so shells near
/// the apex do not help: everywhere along them, tets join points on both and are as short as
/// the gap, and refinement would resolve the gap (at about 1/angle tets per doubling of the
/// distance from the apex, 50,000 tets for that part) where TetGen just leaves such tets alone. A
/// tet whose shortest edge has an endpoint in the zone is exempt.
#[derive(Clone, Copy)]
struct Wedge {
    apex: [f64; 3],
    ends: [[f64; 3]; 2],
    r2: f64,
    lo: [f64; 3],
    hi: [f64; 3],
}

/// Sine of the largest angle of a thin wedge: its widest gap (at the end of the shorter edge)
/// is below a quarter of its zone radius ([`ZONE_FRACTION`] of that edge's length), so at the
/// zone's scale the two edges are one feature. (About 3.6°: 0.07° needle wedges are thin,
/// 5.7° surface triangles are not.)
const THIN_WEDGE: f64 = ZONE_FRACTION / 4.0;

/// Radius of a sharp vertex's protection ball, relative to the shorter edge of the pair: half
/// the zone fraction of edges. (On a triangulated U-shaped part at -pq1.2, a quarter left a tenth of
/// the tets above the bound, an eighth 4.4 % as TetGen does; a sixteenth let its corners take
/// 1.4x TetGen's tets.)
const BALL_FRACTION: f64 = ZONE_FRACTION / 2.0;

/// Relative tolerance of "equal distances from the apex" for points on the two edges of a
/// sharp vertex: shell points sit at the same power-of-two distance up to rounding.
const SHELL_TOLERANCE: f64 = 1e-3;

impl Wedge {
    /// The wedge at `apex` between the edges to `a` and `b`, with its zone.
    fn new(apex: glam::DVec3, a: glam::DVec3, b: glam::DVec3) -> Wedge {
        let r = ZONE_FRACTION * (a - apex).length().min((b - apex).length());
        let lo = apex.min(a).min(b) - glam::DVec3::splat(r);
        let hi = apex.max(a).max(b) + glam::DVec3::splat(r);
        Wedge {
            apex: apex.to_array(),
            ends: [a.to_array(), b.to_array()],
            r2: r * r,
            lo: lo.to_array(),
            hi: hi.to_array(),
        }
    }
}

/// The angle below which two input edges of one facet meeting at a vertex make it sharp, for
/// the radius-edge bound `radius_edge`: 30° (a spike's tip), or more when the bound is below √2.
///
/// Why: take the vertex `A`, the wedge's split points `P1`, `P2` at the same distance `r` from
/// it (concentric shells, see `split_point`) and the wedge angle `θ`. Any tet with corners
/// `A`, `P1`, `P2` has its circumcentre above the circumcentre `O` of the subface `A P1 P2`
/// (radius `ρf = r / (2 cos(θ/2))`), so its circumradius is `R ≥ ρf`, and the circumcentre is
/// in the subface's diametral ball exactly when `R < √2 ρf`; its shortest edge is at most
/// `|P1 P2| = 2 r sin(θ/2)`. So some such tet is bad (`R > ρ |P1 P2|`) with its circumcentre
/// refused for encroaching the subface iff `√2 ρf > ρ |P1 P2|`, i.e. `sin θ < 1 / (√2 ρ)`.
/// The subface is then split at `O`, which encroaches both wedge subsegments (the angle
/// `A O P1` is `180° − θ`); they are split at `r / 2`, and the same tet comes back at half the
/// size, forever (a CAD fan-disk model with `-q1.2`: a 30.1° wedge, a tet of ratio 1.38 at every scale,
/// down to subfaces 1e-9 across). At `ρ = √2` this angle is 30°; for `ρ = 1.2`, 36.1°.
/// Looser bounds (and no bound) keep 30°: a spike's tip is sharp whatever the bound.
pub(super) fn wedge_sharp_angle(radius_edge: Option<f64>) -> f64 {
    let rho = radius_edge.unwrap_or(std::f64::consts::SQRT_2);
    let sin = (1.0 / (std::f64::consts::SQRT_2 * rho)).min(1.0);
    sin.asin().max(30f64.to_radians())
}

/// A protection zone: the points within `sqrt(r2)` of the segment `a b`.
#[derive(Clone, Copy)]
struct Zone {
    a: [f64; 3],
    b: [f64; 3],
    r2: f64,
}

/// Radius of the protection zone of a sharp edge, relative to the edge's length.
const ZONE_FRACTION: f64 = 0.25;

impl Sharp {
    /// The small angles of `plc`; `radius_edge` is the quality bound (it decides how narrow
    /// a wedge inside one facet must be to sustain endless refinement).
    pub(super) fn find(plc: &Plc, feat: &Features, radius_edge: Option<f64>) -> Sharp {
        use glam::DVec3;
        let p = |v: u32| DVec3::from(plc.points[v as usize]);
        let small = 60f64.to_radians().cos();
        let narrow_wedge = wedge_sharp_angle(radius_edge).cos();
        let mut sharp = Sharp::default();
        let mut ball_r2: crate::hash::FastMap<u32, f64> = Default::default();
        let mut vertex_angle: crate::hash::FastMap<u32, f64> = Default::default();
        for (&v, nbrs) in &feat.seg_adj {
            if (v as usize) >= plc.points.len() {
                continue;
            }
            let facets_of = |w: u32| {
                feat.subsegs
                    .get(&super::features::ekey(v, w))
                    .map(|&e| feat.edges[e as usize].facets.clone())
                    .unwrap_or_default()
            };
            for (i, &a) in nbrs.iter().enumerate() {
                for &b in &nbrs[i + 1..] {
                    let (da, db) = ((p(a) - p(v)).normalize(), (p(b) - p(v)).normalize());
                    let cos = da.dot(db);
                    // Two edges of one facet meeting at a moderate angle are the facet mesh's
                    // business; a narrower wedge (see `wedge_sharp_angle`) is sharp anyway.
                    let share = facets_of(a).iter().any(|f| facets_of(b).contains(f));
                    if (cos > small && !share) || cos > narrow_wedge {
                        sharp.vertices.insert(v);
                        let angle = cos.clamp(-1.0, 1.0).acos().to_degrees();
                        let least = vertex_angle.entry(v).or_insert(angle);
                        *least = least.min(angle);
                        let edge = |w: u32| feat.subsegs.get(&super::features::ekey(v, w));
                        if let (Some(&e1), Some(&e2)) = (edge(a), edge(b)) {
                            let key = (e1.min(e2), e1.max(e2));
                            sharp.seg_pairs.insert(key, p(v).to_array());
                            sharp.pair_angle.insert(key, angle);
                        }
                        if (1.0 - cos * cos).max(0.0).sqrt() < THIN_WEDGE {
                            sharp.wedges.push(Wedge::new(p(v), p(a), p(b)));
                        }
                        let r = BALL_FRACTION * (p(a) - p(v)).length().min((p(b) - p(v)).length());
                        let ball = ball_r2.entry(v).or_insert(0.0);
                        *ball = ball.max(r * r);
                    }
                }
            }
        }
        // The directions into facet f from edge ab: the in-plane normals to the edge (n × e)
        // on whose side the facet lies next to the edge's midpoint (both for an edge inside
        // the facet, none for a degenerate one). Taking, say, the direction towards the
        // farthest facet vertex instead would cross a hole of a ring facet.
        let mut balls: Vec<(u32, f64)> = ball_r2.into_iter().collect();
        balls.sort_unstable_by_key(|b| b.0);
        sharp.ball_angle = balls.iter().map(|b| vertex_angle[&b.0]).collect();
        sharp.balls = balls
            .into_iter()
            .map(|(v, r2)| (p(v).to_array(), r2))
            .collect();
        sharp.ball_index = box_index::BoxIndex::new(
            &sharp
                .balls
                .iter()
                .map(|&(c, r2)| {
                    // Widened far beyond the rounding of the square root, so a point the
                    // distance test puts inside is in the box.
                    let r = r2.sqrt() * (1.0 + 1e-6);
                    (c.map(|x| x - r), c.map(|x| x + r))
                })
                .collect::<Vec<_>>(),
        );
        sharp.wedge_index = box_index::BoxIndex::new(
            &sharp
                .wedges
                .iter()
                .map(|w| (w.lo, w.hi))
                .collect::<Vec<_>>(),
        );
        let inward = |f: u32, a: u32, b: u32| -> Vec<DVec3> {
            let fi = &feat.facets[f as usize];
            let [u, v, w] = fi.plane.map(p);
            let n = (v - u).cross(w - u);
            let (pa, pb) = (p(a), p(b));
            let e = pb - pa;
            let d = n.cross(e).normalize_or_zero();
            if d == DVec3::ZERO {
                return Vec::new();
            }
            let mid = 0.5 * (pa + pb);
            // Step off the midpoint by less than its distance to any other outline edge, so
            // the probes see only the facet's side of this edge.
            let q = super::features::proj(mid.to_array(), fi.axis);
            let (qa, qb) = (
                super::features::proj(pa.to_array(), fi.axis),
                super::features::proj(pb.to_array(), fi.axis),
            );
            let mut reach = 0.25 * e.length();
            for lp in &fi.outline.loops {
                for i in 0..lp.len() {
                    let (s, t) = (lp[i], lp[(i + 1) % lp.len()]);
                    if on_line2(s, qa, qb) && on_line2(t, qa, qb) {
                        continue; // the edge itself (or a collinear piece of its loop edge)
                    }
                    let lift = |u: [f64; 2]| [u[0], u[1], 0.0];
                    let d2 = crate::geometry::dist2_point_segment3(lift(q), lift(s), lift(t));
                    reach = reach.min(d2.sqrt());
                }
            }
            // (The projection does not lengthen the step.)
            let step = 0.5 * reach;
            [d, -d]
                .into_iter()
                .filter(|&s| {
                    let probe = (mid + s * step).to_array();
                    fi.outline.contains(super::features::proj(probe, fi.axis))
                })
                .collect()
        };
        for (ei, e) in feat.edges.iter().enumerate() {
            let [a, b] = e.ends;
            for (i, &f1) in e.facets.iter().enumerate() {
                for &f2 in &e.facets[i + 1..] {
                    let (d1, d2) = (inward(f1, a, b), inward(f2, a, b));
                    if d1.iter().any(|x| d2.iter().any(|y| x.dot(*y) > small)) {
                        sharp.edges.insert(ei as u32);
                        sharp.facet_pairs.insert((f1.min(f2), f1.max(f2)));
                    }
                }
            }
        }
        sharp.zones = vec![Vec::new(); feat.facets.len()];
        for &ei in &sharp.edges {
            let [a, b] = feat.edges[ei as usize].ends;
            let r = ZONE_FRACTION * (p(b) - p(a)).length();
            for &f in &feat.edges[ei as usize].facets {
                sharp.zones[f as usize].push(Zone {
                    a: p(a).to_array(),
                    b: p(b).to_array(),
                    r2: r * r,
                });
            }
        }
        sharp
    }

    /// Whether a vertex on facet `f` at `q` lies in a protection zone of the facet.
    fn in_zone(&self, f: u32, q: [f64; 3]) -> bool {
        self.zones.get(f as usize).is_some_and(|zs| {
            zs.iter()
                .any(|z| crate::geometry::dist2_point_segment3(q, z.a, z.b) < z.r2)
        })
    }

    /// Whether `q` lies in the protection ball of a sharp vertex whose narrowest sharp pair is
    /// below `below` degrees (all of them for an infinite `below`).
    fn in_ball(&self, q: [f64; 3], below: f64) -> bool {
        self.ball_index.candidates(q).any(|i| {
            let (c, r2) = self.balls[i as usize];
            self.ball_angle[i as usize] < below && crate::geometry::dist2_3(q, c) < r2
        })
    }

    /// Whether all four vertices `vs` lie deep inside one sharp vertex's protection ball,
    /// within [`DEEP_FRACTION`] of its radius. Sliver removal excuses such a tet whatever the
    /// angle there: where input edges meet a little above the target (armadillo.off has
    /// corners of 15.3° and 17.3°), a tet on the corner's subfaces can still have a dihedral
    /// angle below it, and each point that removes one makes a smaller one closer to the apex,
    /// until floating point runs out. Larger tets there are still treated, so that fan angles
    /// of triangulated surfaces keep no sliver (`exempts_sliver`).
    fn deep_in_ball(&self, vs: [u32; 4], pts: &[[f64; 3]]) -> bool {
        let q = vs.map(|v| pts[v as usize]);
        self.ball_index.candidates(q[0]).any(|i| {
            let (c, r2) = self.balls[i as usize];
            let deep2 = r2 * DEEP_FRACTION * DEEP_FRACTION;
            q.iter().all(|&x| crate::geometry::dist2_3(x, c) < deep2)
        })
    }

    /// Whether `q` lies in the protection zone of a thin wedge.
    fn in_wedge(&self, q: [f64; 3]) -> bool {
        use crate::geometry::dist2_point_segment3 as d2;
        self.wedge_index.candidates(q).any(|i| {
            let w = &self.wedges[i as usize];
            (0..3).all(|k| w.lo[k] <= q[k] && q[k] <= w.hi[k])
                && d2(q, w.apex, w.ends[0]) < w.r2
                && d2(q, w.apex, w.ends[1]) < w.r2
        })
    }

    /// Whether the points `p`, `q` on the two edges of the sharp vertex pair `pair` are at the
    /// same distance from its apex (up to [`SHELL_TOLERANCE`]).
    fn on_one_shell(&self, pair: (u32, u32), p: [f64; 3], q: [f64; 3]) -> bool {
        let Some(&a) = self.seg_pairs.get(&pair) else {
            return false;
        };
        let (dp, dq) = (
            crate::geometry::dist2_3(a, p).sqrt(),
            crate::geometry::dist2_3(a, q).sqrt(),
        );
        (dp - dq).abs() <= SHELL_TOLERANCE * dp.max(dq)
    }

    /// Whether the shortest edge of a tet with these vertices (which decides its radius-edge
    /// ratio) is pinned by a sharp vertex: it has an end in the apex's protection ball or in a
    /// thin wedge's zone, or it joins points of the apex's two edges on one concentric shell. Refining
    /// such a tet would only make a shorter edge of the same kind.
    /// Only sharp vertex pairs narrower than `below` degrees count.
    fn short_edge_pinned(
        &self,
        vs: [u32; 4],
        feat: &Features,
        pts: &[[f64; 3]],
        below: f64,
    ) -> bool {
        if self.vertices.is_empty() {
            return false;
        }
        let len2 = |(a, b): (usize, usize)| {
            crate::geometry::dist2_3(pts[vs[a] as usize], pts[vs[b] as usize])
        };
        let (i, j) = EDGES
            .iter()
            .copied()
            .min_by(|&x, &y| len2(x).total_cmp(&len2(y)))
            .unwrap_or((0, 1));
        let (u, w) = (vs[i], vs[j]);
        let (pu, pw) = (pts[u as usize], pts[w as usize]);
        if self.in_ball(pu, below)
            || self.in_ball(pw, below)
            || self.in_wedge(pu)
            || self.in_wedge(pw)
        {
            return true;
        }
        match (feat.split_edge.get(&u), feat.split_edge.get(&w)) {
            (Some(&e1), Some(&e2)) if e1 != e2 => {
                let pair = (e1.min(e2), e1.max(e2));
                self.pair_angle.get(&pair).is_some_and(|&a| a < below)
                    && self.on_one_shell(pair, pu, pw)
            }
            _ => false,
        }
    }

    /// Whether the input has no small angle at all.
    fn is_empty(&self) -> bool {
        self.vertices.is_empty() && self.edges.is_empty() && self.facet_pairs.is_empty()
    }

    /// Whether a small input angle excuses a tet with these vertices from the radius-edge
    /// bound: it has a vertex next to a sharp edge, its shortest edge is pinned by a sharp
    /// vertex, or it spans two facets meeting at a sharp edge.
    fn exempts(&self, vs: [u32; 4], feat: &Features, pts: &[[f64; 3]]) -> bool {
        self.exempts_sliver(vs, feat, pts, f64::INFINITY)
    }

    /// Whether a small input angle excuses a sliver with these vertices from sliver removal
    /// with the minimum dihedral angle `target` (degrees; infinite: [`Sharp::exempts`]): as
    /// [`Sharp::exempts`], but a sharp vertex (two input edges below 60°, or below the wedge
    /// angle in one facet) counts only where two input edges meet below `target`. Where they
    /// meet below the target, a subface at the corner has that angle and a tet on it with a
    /// vertex off the facet has a dihedral angle of about that size at the corner; wider pairs
    /// force no such tet. On triangulated surfaces such wider pairs are fan angles at nearly
    /// every vertex (two edges of a flat fan two triangles apart): a fan-disk model at
    /// -pq1.414 kept 44 slivers down to 0.05°, all excused by one, which sliver removal (a
    /// point, or the splits it demands) removes. Radius-edge refinement keeps the broader
    /// rule: there the protection balls stop refinement from running towards such vertices.
    pub(super) fn exempts_sliver(
        &self,
        vs: [u32; 4],
        feat: &Features,
        pts: &[[f64; 3]],
        target: f64,
    ) -> bool {
        if self.vertices.is_empty() && self.edges.is_empty() {
            return false;
        }
        for &v in &vs {
            if let Some(fs) = feat.vert_facets.get(&v) {
                if fs.iter().any(|&f| self.in_zone(f, pts[v as usize])) {
                    return true;
                }
            }
            if let Some(e) = feat.split_edge.get(&v) {
                if self.edges.contains(e) {
                    return true;
                }
            }
        }
        if self.short_edge_pinned(vs, feat, pts, target) || self.deep_in_ball(vs, pts) {
            return true;
        }
        if self.facet_pairs.is_empty() {
            return false;
        }
        let none = Vec::new();
        let fs: Vec<&Vec<u32>> = vs
            .iter()
            .map(|v| feat.vert_facets.get(v).unwrap_or(&none))
            .collect();
        for i in 0..4 {
            for j in i + 1..4 {
                for &f1 in fs[i] {
                    for &f2 in fs[j] {
                        if f1 != f2 && self.facet_pairs.contains(&(f1.min(f2), f1.max(f2))) {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
}
