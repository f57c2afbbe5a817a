//! The tetrahedralization store and the incremental Bowyer–Watson kernel (paper §2 "Incremental
//! Delaunay Algorithm", used by §4).
//!
//! Tetrahedra live in one flat array indexed by [`TetId`]. Tet `t` has four vertices `tv[4t+i]`
//! and four neighbours `tn[4t+f] = 4t'+f'`: across the face opposite vertex `i = f` lies tet `t'`,
//! and that face is face `f'` of `t'`. Both live in one 32-byte record per tet (one cache line
//! holds two tets), because every step of the kernel reads a tet's vertices and its neighbours
//! together. Dead slots hold `NONE` vertices and sit on a free list.
//!
//! Every real tet is positively oriented in TetGen's sense (`det[b−a, c−a, d−a] > 0`, i.e.
//! Shewchuk's `orient3d(a, b, c, d) < 0`). The convex hull is closed by *ghost* tets: a hull
//! triangle plus the symbolic vertex [`GHOST`], oriented as if [`GHOST`] were a point far outside
//! that triangle. So the structure covers all of space, no bounding-box vertex is needed, and the
//! output needs no deletion. With [`FACE`] listing each face's vertices counter-clockwise as seen
//! from outside the tet, a point `p` lies strictly outside face `f` of a real tet exactly when
//! `orient3d(face f, p) < 0`, and strictly beyond the hull triangle of a ghost whose ghost vertex
//! is at index `k` exactly when `orient3d(face k, p) > 0`.
//!
//! Insertion is two-phase so that a caller can inspect the cavity and veto the point
//! (Provisional insertion, paper Fig. 8): [`Tets::find_cavity`], then [`Tets::commit_cavity`]
//! or [`Tets::cancel_cavity`]. `Tets::insert` (in tests) does locate + find + commit.
//!
//! Keeping the input surface (TetGen's `-Y`) the store is *carved* ([`Tets::carve`]): the tets
//! outside the domain are deleted and the faces they shared with the domain become *open* (no
//! neighbour, [`NONE`]). A carved store is edited with [`Tets::replace`] and gets new points
//! through [`Tets::locate_walled`] and [`Tets::find_cavity_walled`], which never cross a wall
//! (a subface) or an open face; [`Tets::locate`] and [`Tets::find_cavity`] need a closed store.
//!
//! The conflict rule is the paper's (open circumballs, needed by Lemma 4.7): a real tet conflicts
//! with `p` iff `p` is strictly inside its circumsphere; a ghost iff `p` is strictly beyond its
//! hull triangle, or exactly in the triangle's plane and strictly inside its circumcircle. Both
//! are decided with exact predicates.

use crate::predicates::{insphere_filter, insphere_near_degenerate, orient3d, orient3d_fast};

use super::NONE;

mod edit;
pub use edit::ReplaceError;

/// A vertex index.
pub type VertexId = u32;
/// A tetrahedron index (a slot in the store; check [`Tets::alive`]).
pub type TetId = u32;

/// The symbolic vertex at infinity shared by all ghost tets. It has no coordinates:
/// [`Tets::point`] must never be called with it.
pub const GHOST: VertexId = NONE - 1;

/// `FACE[f]`: the vertex positions of face `f` (the face opposite vertex `f`), ordered
/// counter-clockwise as seen from outside the tet, so that `orient3d(face, opposite) > 0`.
pub const FACE: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// Largest number of tet slots: neighbour references pack `4t + f` into a `u32`.
const MAX_SLOTS: usize = 1 << 30;

/// One tetrahedron: vertices and neighbour half-faces side by side, 32 bytes, aligned so that a
/// record never straddles two cache lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(32))]
struct Tet {
    v: [VertexId; 4],
    n: [u32; 4],
}

const DEAD: Tet = Tet {
    v: [NONE; 4],
    n: [NONE; 4],
};

/// Where [`Tets::locate`] found a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Located {
    /// A tet in conflict with the point: a real tet containing it (possibly on its boundary),
    /// or, when the point is outside the convex hull, a ghost tet whose hull triangle it lies
    /// strictly beyond.
    InTet(TetId),
    /// The point equals this existing vertex exactly.
    Vertex(VertexId),
}

/// The outcome of [`Tets::try_insert`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Insertion {
    /// The vertex was inserted; this is one of its new tets (a good walking hint).
    Inserted(TetId),
    /// The vertex's point equals this existing vertex; nothing changed.
    Duplicate(VertexId),
    /// No tet in conflict with the point was found: the structure is corrupted (a bug);
    /// nothing changed.
    Lost,
}

/// The tetrahedralization: vertex coordinates, tets with adjacency, and the kernel's reusable
/// scratch space (cavity, its boundary, the edge table that links new tets).
pub struct Tets {
    pts: Vec<[f64; 3]>,
    /// One live tet incident to each vertex (`NONE` before the vertex is inserted).
    vtet: Vec<TetId>,
    /// One live ghost tet (`NONE` before [`Tets::init`]).
    ghost_tet: TetId,
    tets: Vec<Tet>,
    free: Vec<TetId>,
    live: usize,
    /// Two bits per tet (32 tets per word): [`IN_CAVITY`], [`TESTED_OUT`] or 0. A bitmap stays
    /// in cache where a per-tet stamp array would not; the bits set by one cavity search are
    /// cleared from the cavity and boundary lists when it is cancelled or committed.
    state: Vec<u64>,
    pending: bool,
    cavity_point: [f64; 3],
    cavity: Vec<TetId>,
    boundary: Vec<u32>,
    /// Boundary faces copied out before the cavity's slots are recycled: `[a, b, c, outside]`.
    bface: Vec<[u32; 4]>,
    new_tets: Vec<TetId>,
    /// Open-addressing table from a directed boundary edge to the new tet face holding it;
    /// slots with a stale stamp are empty, so the table is never cleared.
    edges: Vec<EdgeSlot>,
    edge_epoch: u32,
}

#[inline]
fn neighbor_ref(t: TetId, f: usize) -> u32 {
    (t << 2) | f as u32
}

#[inline]
fn edge_hash(key: u64) -> u64 {
    key.wrapping_mul(0x9E37_79B9_7F4A_7C15)
}

/// One slot of the edge table of [`Tets::commit_cavity`].
#[derive(Clone, Copy, Default)]
struct EdgeSlot {
    key: u64,
    val: u32,
    stamp: u32,
}

/// Cavity state of a tet: in the pending cavity.
const IN_CAVITY: u64 = 1;
/// Cavity state of a tet: tested against the pending point and not in conflict.
const TESTED_OUT: u64 = 2;

#[inline]
fn get_state(state: &[u64], t: usize) -> u64 {
    (state[t >> 5] >> ((t & 31) * 2)) & 3
}

#[inline]
fn set_state(state: &mut [u64], t: usize, s: u64) {
    let w = &mut state[t >> 5];
    let sh = (t & 31) * 2;
    *w = (*w & !(3 << sh)) | (s << sh);
}

/// Asks the CPU to start loading `r` into the cache (a hint; no effect on the program's
/// meaning). The kernel's tets are visited in an order no hardware prefetcher can guess.
#[inline(always)]
#[allow(unsafe_code)] // the crate denies unsafe code outside the C ABI; this hint is the exception
fn prefetch<T>(r: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch has no architectural effect (it cannot fault or change memory), and
    // `r` is a valid reference anyway; SSE is part of the x86_64 baseline.
    unsafe {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>((r as *const T).cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = r;
}

/// The ghost half of [`conflict_in`], kept out of line: ghosts are few, and inlining their
/// test would crowd the hot loop.
#[inline(never)]
fn ghost_conflict_in(pts: &[[f64; 3]], v: [VertexId; 4], p: [f64; 3]) -> bool {
    let k = v.iter().position(|&x| x == GHOST).unwrap_or(0);
    let [a, b, c] = FACE[k].map(|i| pts[v[i] as usize]);
    ghost_conflict(a, b, c, p)
}

/// The conflict rule of [`Tets::conflict`] on the raw arrays (the cavity search's hot path).
#[inline(always)]
fn conflict_in(tets: &[Tet], pts: &[[f64; 3]], t: usize, p: [f64; 3]) -> bool {
    let v = tets[t].v;
    if v[0] == GHOST || v[1] == GHOST || v[2] == GHOST || v[3] == GHOST {
        return ghost_conflict_in(pts, v, p);
    }
    let [a, b, c, d] = v.map(|x| pts[x as usize]);
    // Real tets have orient3d < 0, which flips Shewchuk's insphere sign. The slow path reads
    // the points again, so that the hot path never has to keep copies of them in memory.
    match insphere_filter(a, b, c, d, p) {
        Some(det) => det < 0.0,
        None => {
            let [a, b, c, d] = v.map(|x| &pts[x as usize]);
            insphere_near_degenerate(a, b, c, d, &p) < 0.0
        }
    }
}

impl Tets {
    /// An empty store sized for about `nv` vertices (a Delaunay tetrahedralization of `n`
    /// random points has about `6.7 n` tets).
    pub fn with_capacity(nv: usize) -> Tets {
        let nt = nv.saturating_mul(7).saturating_add(64);
        Tets {
            pts: Vec::with_capacity(nv),
            vtet: Vec::with_capacity(nv),
            ghost_tet: NONE,
            tets: Vec::with_capacity(nt),
            free: Vec::with_capacity(256),
            live: 0,
            state: Vec::with_capacity(nt / 32 + 1),
            pending: false,
            cavity_point: [0.0; 3],
            cavity: Vec::with_capacity(256),
            boundary: Vec::with_capacity(512),
            bface: Vec::with_capacity(512),
            new_tets: Vec::with_capacity(512),
            edges: vec![EdgeSlot::default(); 1024],
            edge_epoch: 0,
        }
    }

    /// Adds a vertex (coordinates only; it is not in the tetrahedralization until
    /// [`Tets::init`] or an insertion uses it) and returns its id. Ids are consecutive from 0.
    pub fn push_vertex(&mut self, p: [f64; 3]) -> VertexId {
        let id = self.pts.len();
        assert!(id < GHOST as usize, "too many vertices");
        self.pts.push(p);
        self.vtet.push(NONE);
        id as VertexId
    }

    /// Takes back the last vertex pushed, which no tet uses (a point made for a replacement
    /// that [`Tets::replace`] refused, which changes nothing).
    pub fn pop_vertex(&mut self) {
        debug_assert!(self.vtet.last().is_some_and(|&t| t == NONE));
        self.pts.pop();
        self.vtet.pop();
    }

    /// Moves vertex `v` to `p`. The caller keeps the tetrahedralization valid (every real tet
    /// positively oriented), as `plc/frame.rs` checks after moving Steiner points onto the
    /// caller's grid.
    pub fn set_point(&mut self, v: VertexId, p: [f64; 3]) {
        self.pts[v as usize] = p;
    }

    /// The coordinates of vertex `v` (not [`GHOST`]).
    #[inline]
    pub fn point(&self, v: VertexId) -> [f64; 3] {
        self.pts[v as usize]
    }

    /// The coordinates of every vertex pushed, by id (the kernel is gone).
    pub fn into_points(self) -> Vec<[f64; 3]> {
        self.pts
    }

    /// Number of vertices pushed (inserted or not).
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.pts.len()
    }

    /// Number of tet slots; tets are `0..num_slots()`, live ones pass [`Tets::alive`].
    #[inline]
    pub fn num_slots(&self) -> usize {
        self.tets.len()
    }

    /// Number of live tets, ghosts included.
    #[cfg(test)]
    #[inline]
    pub fn num_live(&self) -> usize {
        self.live
    }

    /// Whether slot `t` holds a live tet (real or ghost).
    #[inline]
    pub fn alive(&self, t: TetId) -> bool {
        self.tets[t as usize].v[0] != NONE
    }

    /// Whether tet `t` is a ghost (has the vertex [`GHOST`]).
    #[inline]
    pub fn is_ghost(&self, t: TetId) -> bool {
        self.tets[t as usize].v.contains(&GHOST)
    }

    /// The four vertices of tet `t` (ghost tets contain [`GHOST`]).
    #[inline]
    pub fn verts(&self, t: TetId) -> [VertexId; 4] {
        self.tets[t as usize].v
    }

    /// The neighbour across face `f` of tet `t` (the face opposite `verts(t)[f]`), and which
    /// face of the neighbour it is; `(NONE, 0)` for an open face (see [`Tets::carve`]).
    #[inline]
    pub fn neighbor(&self, t: TetId, f: usize) -> (TetId, usize) {
        let h = self.tets[t as usize].n[f];
        if h == NONE {
            return (NONE, 0);
        }
        (h >> 2, (h & 3) as usize)
    }

    /// Some live tet with vertex `v` (possibly a ghost); `NONE` if `v` is not inserted.
    #[inline]
    pub fn vertex_tet(&self, v: VertexId) -> TetId {
        if v == GHOST {
            self.ghost_tet
        } else {
            self.vtet[v as usize]
        }
    }

    fn alloc(&mut self) -> TetId {
        self.live += 1;
        if let Some(t) = self.free.pop() {
            return t;
        }
        let t = self.tets.len();
        assert!(t < MAX_SLOTS, "too many tetrahedra (more than 2^30)");
        self.tets.push(DEAD);
        if t & 31 == 0 {
            self.state.push(0);
        }
        t as TetId
    }

    /// Builds the first real tet on the four vertices (which must not be coplanar; they are
    /// reordered to positive orientation) and the four ghost tets that close its hull.
    pub fn init(&mut self, a: VertexId, b: VertexId, c: VertexId, d: VertexId) {
        assert!(self.live == 0, "Tets::init called twice");
        let o = orient3d(self.point(a), self.point(b), self.point(c), self.point(d));
        assert!(o != 0.0, "Tets::init: the four vertices are coplanar");
        let first = if o < 0.0 { [a, b, c, d] } else { [b, a, c, d] };
        let t0 = self.alloc();
        self.tets[t0 as usize].v = first;
        let mut all = [t0; 5];
        for f in 0..4 {
            // The ghost beyond face f: that face's vertices in outward order, then GHOST, is
            // positively oriented with GHOST standing for a far point beyond the face.
            let g = self.alloc();
            let fv = FACE[f].map(|i| first[i]);
            self.tets[g as usize].v = [fv[0], fv[1], fv[2], GHOST];
            all[f + 1] = g;
        }
        // Pair up the 20 faces by vertex set (five tets, so brute force is fine).
        for i in 0..5 {
            for fi in 0..4 {
                let key = self.face_key(all[i], fi);
                for j in 0..5 {
                    for fj in 0..4 {
                        if (i, fi) != (j, fj) && key == self.face_key(all[j], fj) {
                            self.tets[all[i] as usize].n[fi] = neighbor_ref(all[j], fj);
                        }
                    }
                }
            }
        }
        for v in first {
            self.vtet[v as usize] = t0;
        }
        self.ghost_tet = all[1];
    }

    /// The sorted vertex triple of face `f` of `t`.
    fn face_key(&self, t: TetId, f: usize) -> [VertexId; 3] {
        let v = self.tets[t as usize].v;
        let mut k = FACE[f].map(|i| v[i]);
        k.sort_unstable();
        k
    }

    /// Whether tet `t` is in conflict with `p` (the paper's open-ball rule; see the module
    /// documentation). Exact.
    #[inline]
    pub fn conflict(&self, t: TetId, p: [f64; 3]) -> bool {
        conflict_in(&self.tets, &self.pts, t as usize, p)
    }

    /// Finds a tet in conflict with `p`, walking from `hint` (any slot; a dead or out-of-range
    /// hint is replaced by a live tet). The walk is a remembering stochastic visibility walk
    /// (it never goes back through the face it came in by, and tries faces in a pseudo-random
    /// order so it cannot cycle forever); when its step budget runs out it falls back to a scan
    /// of all tets.
    pub fn locate(&self, p: [f64; 3], hint: TetId) -> Located {
        let mut t = hint;
        if t as usize >= self.tets.len() || !self.alive(t) {
            t = self.ghost_tet;
        }
        if t == NONE {
            return Located::InTet(NONE);
        }
        let budget = 64 + self.tets.len();
        let mut came_from = 4usize;
        let mut step = 0usize;
        'walk: while step < budget {
            step += 1;
            let tet = &self.tets[t as usize];
            if let Some(k) = tet.v.iter().position(|&x| x == GHOST) {
                let [a, b, c] = FACE[k].map(|i| self.point(tet.v[i]));
                if orient3d_fast(a, b, c, p) > 0.0 {
                    return Located::InTet(t);
                }
                // Not beyond this hull triangle: continue inside the hull.
                let h = tet.n[k];
                t = h >> 2;
                came_from = (h & 3) as usize;
                continue;
            }
            if let Some(f) = self.exit_face(t, came_from, step, p) {
                let h = tet.n[f];
                t = h >> 2;
                came_from = (h & 3) as usize;
                continue 'walk;
            }
            // p is in the closed tet t.
            return match tet.v.iter().find(|&&x| self.point(x) == p) {
                Some(&v) => Located::Vertex(v),
                None => Located::InTet(t),
            };
        }
        self.locate_by_scan(p)
    }

    /// A face of real tet `t` that `p` lies strictly beyond, other than `came_from`, tried in a
    /// pseudo-random order seeded by `t` and `step` (so a remembering walk cannot cycle
    /// forever); `None` when `p` is in the closed tet.
    #[inline(always)]
    fn exit_face(&self, t: TetId, came_from: usize, step: usize, p: [f64; 3]) -> Option<usize> {
        let tet = &self.tets[t as usize];
        let r = (t as usize ^ step).wrapping_mul(0x9E37_79B9) >> 7;
        (0..4).map(|j| (r + j) & 3).find(|&f| {
            f != came_from && {
                let [a, b, c] = FACE[f].map(|i| self.point(tet.v[i]));
                orient3d_fast(a, b, c, p) < 0.0
            }
        })
    }

    /// Locates `p` by testing every live tet (the fallback of [`Tets::locate`]).
    fn locate_by_scan(&self, p: [f64; 3]) -> Located {
        let mut beyond = NONE;
        for t in 0..self.tets.len() as TetId {
            if !self.alive(t) {
                continue;
            }
            let v = self.tets[t as usize].v;
            if let Some(k) = v.iter().position(|&x| x == GHOST) {
                let [a, b, c] = FACE[k].map(|i| self.point(v[i]));
                if beyond == NONE && orient3d(a, b, c, p) > 0.0 {
                    beyond = t;
                }
                continue;
            }
            let inside = (0..4).all(|f| {
                let [a, b, c] = FACE[f].map(|i| self.point(v[i]));
                orient3d(a, b, c, p) >= 0.0
            });
            if inside {
                return match v.iter().find(|&&x| self.point(x) == p) {
                    Some(&w) => Located::Vertex(w),
                    None => Located::InTet(t),
                };
            }
        }
        Located::InTet(beyond)
    }

    /// Clears the cavity-state bits set by the last [`Tets::find_cavity`] (the cavity's tets
    /// and the tested neighbours across its boundary) and forgets the cavity.
    fn clear_cavity(&mut self) {
        for &t in &self.cavity {
            set_state(&mut self.state, t as usize, 0);
        }
        for &h in &self.boundary {
            let u = self.tets[(h >> 2) as usize].n[(h & 3) as usize];
            if u != NONE {
                set_state(&mut self.state, (u >> 2) as usize, 0);
            }
        }
        self.cavity.clear();
        self.boundary.clear();
        self.pending = false;
    }

    /// Collects the cavity of `p`: every tet in conflict with `p` that is connected to `start`
    /// through faces of conflicting tets, and the cavity's boundary. `start` must be in conflict
    /// with `p` (as returned by [`Tets::locate`]); if it is not, the cavity is left empty and
    /// `false` is returned. The mesh is not changed: follow with [`Tets::commit_cavity`] or
    /// [`Tets::cancel_cavity`] (a new `find_cavity` also drops a pending cavity). Every tet must
    /// have all four neighbours (the store is closed by ghosts).
    pub fn find_cavity(&mut self, p: [f64; 3], start: TetId) -> bool {
        self.find_cavity_visit(p, start, usize::MAX, |_, _| true) == Some(true)
    }

    /// [`Tets::find_cavity`] that shows each tet to `visit` as it joins the cavity (its
    /// vertices, and for each face whether the neighbour across it joined before) and gives up
    /// once the cavity holds more than `cap` tets or `visit` returns `false`: `None` then, with
    /// a partial cavity pending (to be cancelled). For probes that judge a cavity tet by tet
    /// and can give up on the first bad one, or on a huge cavity, instead of paying for it all.
    pub fn find_cavity_visit(
        &mut self,
        p: [f64; 3],
        start: TetId,
        cap: usize,
        mut visit: impl FnMut([VertexId; 4], [bool; 4]) -> bool,
    ) -> Option<bool> {
        self.clear_cavity();
        self.pending = true;
        self.cavity_point = p;
        if start as usize >= self.tets.len() || !self.alive(start) || !self.conflict(start, p) {
            return Some(false);
        }
        let Tets {
            tets,
            pts,
            state,
            cavity,
            boundary,
            ..
        } = self;
        set_state(state, start as usize, IN_CAVITY);
        cavity.push(start);
        if !visit(tets[start as usize].v, [false; 4]) {
            return None;
        }
        let mut i = 0;
        // Each tet enters the cavity once, so the loop is bounded by the number of tets.
        while i < cavity.len() {
            let t = cavity[i];
            i += 1;
            let n = tets[t as usize].n;
            for (f, &h) in n.iter().enumerate() {
                let u = (h >> 2) as usize;
                match get_state(state, u) {
                    IN_CAVITY => continue,
                    TESTED_OUT => {}
                    _ => {
                        if conflict_in(tets, pts, u, p) {
                            if cavity.len() >= cap {
                                // Every tet in the cavity or tested out has its state
                                // recorded where clear_cavity finds it.
                                return None;
                            }
                            set_state(state, u, IN_CAVITY);
                            cavity.push(u as TetId);
                            let joined = tets[u]
                                .n
                                .map(|h| get_state(state, (h >> 2) as usize) == IN_CAVITY);
                            if !visit(tets[u].v, joined) {
                                return None;
                            }
                            // u's neighbours are tested when u's turn comes: start loading
                            // them now, so the cache misses overlap with other tests.
                            for h in tets[u].n {
                                prefetch(&tets[(h >> 2) as usize]);
                            }
                            continue;
                        }
                        set_state(state, u, TESTED_OUT);
                    }
                }
                boundary.push(neighbor_ref(t, f));
            }
        }
        Some(true)
    }

    /// The tets of the pending cavity (empty when none is pending).
    #[inline]
    pub fn cavity(&self) -> &[TetId] {
        &self.cavity
    }

    /// The boundary of the pending cavity as half-faces `4t + f`: `t` is in the cavity and its
    /// neighbour across face `f` is not.
    #[inline]
    pub fn cavity_boundary(&self) -> &[u32] {
        &self.boundary
    }

    /// Whether `t` is in the pending cavity (O(1)).
    #[inline]
    pub fn in_cavity(&self, t: TetId) -> bool {
        get_state(&self.state, t as usize) == IN_CAVITY
    }

    /// Drops the pending cavity; the mesh is unchanged.
    pub fn cancel_cavity(&mut self) {
        self.clear_cavity();
    }

    /// Replaces the pending cavity by the tets joining `v` to each boundary face, and returns
    /// the new tets (valid until the next call that changes the store): new tet `k` is
    /// `[v, a, b, c]` on boundary face `k` of [`Tets::cavity_boundary`] (its face 0, opposite
    /// `v`, is that face; ghosts among them have [`GHOST`] in place of one of `a, b, c`).
    /// `v`'s point must be the point given to [`Tets::find_cavity`]. Updates the vertex-to-tet
    /// map. Slots of the cavity's tets are recycled.
    pub fn commit_cavity(&mut self, v: VertexId) -> &[TetId] {
        debug_assert!(self.pending, "commit_cavity without find_cavity");
        debug_assert!(
            self.point(v) == self.cavity_point,
            "commit_cavity: vertex {v} is not the cavity's point"
        );
        self.new_tets.clear();
        if self.cavity.is_empty() {
            self.clear_cavity();
            return &self.new_tets;
        }
        // Room in the edge table for 3 directed edges per face at load <= 1/8, so that nearly
        // every key sits in its home slot and the probe loops below rarely iterate.
        let need = (self.boundary.len() * 24).next_power_of_two().max(64);
        if need > self.edges.len() {
            self.edges = vec![EdgeSlot::default(); need];
            self.edge_epoch = 0;
        }
        self.edge_epoch = self.edge_epoch.wrapping_add(1);
        if self.edge_epoch == 0 {
            self.edges.iter_mut().for_each(|e| e.stamp = 0);
            self.edge_epoch = 1;
        }
        let Tets {
            tets,
            vtet,
            ghost_tet,
            free,
            live,
            state,
            cavity,
            boundary,
            bface,
            new_tets,
            edges,
            edge_epoch,
            ..
        } = self;
        // Copy the boundary faces out first: the cavity's slots are recycled for the new tets.
        bface.clear();
        for &h in boundary.iter() {
            let tet = &tets[(h >> 2) as usize];
            let f = (h & 3) as usize;
            let [a, b, c] = FACE[f].map(|i| tet.v[i]);
            let outside = tet.n[f];
            if outside != NONE {
                set_state(state, (outside >> 2) as usize, 0);
            }
            bface.push([a, b, c, outside]);
        }
        for &t in cavity.iter() {
            set_state(state, t as usize, 0);
            tets[t as usize] = DEAD;
            free.push(t);
        }
        *live -= cavity.len();
        cavity.clear();
        boundary.clear();

        let epoch = *edge_epoch;
        let mask = edges.len() - 1;
        let shift = 64 - edges.len().trailing_zeros();
        for &[a, b, c, outside] in bface.iter() {
            let nt = match free.pop() {
                Some(t) => t,
                None => {
                    let t = tets.len();
                    assert!(t < MAX_SLOTS, "too many tetrahedra (more than 2^30)");
                    tets.push(DEAD);
                    if t & 31 == 0 {
                        state.push(0);
                    }
                    t as TetId
                }
            };
            *live += 1;
            // [v, a, b, c] is positive: (a, b, c) is outward for a cavity tet and v is inside.
            tets[nt as usize] = Tet {
                v: [v, a, b, c],
                n: [outside, NONE, NONE, NONE],
            };
            if outside != NONE {
                tets[(outside >> 2) as usize].n[(outside & 3) as usize] = neighbor_ref(nt, 0);
            }
            new_tets.push(nt);
            // Face j (1..=3) holds the directed boundary edge below; the neighbouring new tet
            // holds the same edge reversed. File every half now, link them in a second pass:
            // that keeps the branches predictable (insert always finds a free slot, lookup
            // always finds its partner).
            for (j, x, y) in [(1, b, c), (2, c, a), (3, a, b)] {
                let key = ((x as u64) << 32) | y as u64;
                let mut s = (edge_hash(key) >> shift) as usize & mask;
                while edges[s].stamp == epoch {
                    s = (s + 1) & mask;
                }
                edges[s] = EdgeSlot {
                    key,
                    val: neighbor_ref(nt, j),
                    stamp: epoch,
                };
            }
            for x in [a, b, c] {
                if x == GHOST {
                    *ghost_tet = nt;
                } else {
                    vtet[x as usize] = nt;
                }
            }
        }
        for &nt in new_tets.iter() {
            let [_, a, b, c] = tets[nt as usize].v;
            for (j, x, y) in [(1, b, c), (2, c, a), (3, a, b)] {
                let want = ((y as u64) << 32) | x as u64;
                let mut s = (edge_hash(want) >> shift) as usize & mask;
                // The boundary is a closed surface, so the partner is there; the stamp test
                // only guards against a corrupted cavity looping forever.
                while edges[s].key != want && edges[s].stamp == epoch {
                    s = (s + 1) & mask;
                }
                if edges[s].stamp == epoch {
                    tets[nt as usize].n[j] = edges[s].val;
                }
            }
        }
        vtet[v as usize] = new_tets[0];
        self.pending = false;
        #[cfg(debug_assertions)]
        self.debug_check_new_tets(v);
        &self.new_tets
    }

    /// Debug check of a commit: every new tet is linked on all faces and every new real tet is
    /// positively oriented, i.e. the cavity was a star-shaped ball around `v`.
    #[cfg(debug_assertions)]
    fn debug_check_new_tets(&self, v: VertexId) {
        for &t in &self.new_tets {
            let tet = &self.tets[t as usize];
            // Face 0 lies on the cavity's boundary, which may be open (after a carve).
            assert!(
                !tet.n[1..].contains(&NONE),
                "cavity of vertex {v} is not a topological ball (new tet {t} left unlinked)"
            );
            if !tet.v.contains(&GHOST) {
                let [a, b, c, d] = tet.v.map(|x| self.point(x));
                assert!(
                    orient3d(a, b, c, d) < 0.0,
                    "cavity of vertex {v} is not star-shaped (new tet {t} is flat or inverted)"
                );
            }
        }
    }

    /// Inserts vertex `v` (pushed, not yet inserted): locate from `hint`, find the cavity,
    /// commit. Returns one of the new tets, or `Err(w)` when `v`'s point equals vertex `w`'s
    /// (nothing changes then). Panics if the structure is corrupted so that no conflicting tet
    /// exists; use [`Tets::try_insert`] to get that as a value.
    #[cfg(test)]
    pub fn insert(&mut self, v: VertexId, hint: TetId) -> Result<TetId, VertexId> {
        match self.try_insert(v, hint) {
            Insertion::Inserted(t) => Ok(t),
            Insertion::Duplicate(w) => Err(w),
            Insertion::Lost => panic!("no tet is in conflict with vertex {v}"),
        }
    }

    /// `Tets::insert` (in tests) reporting every outcome as a value.
    pub fn try_insert(&mut self, v: VertexId, hint: TetId) -> Insertion {
        let p = self.point(v);
        match self.locate(p, hint) {
            Located::Vertex(w) => Insertion::Duplicate(w),
            Located::InTet(t) => {
                if !self.find_cavity(p, t) {
                    self.cancel_cavity();
                    return Insertion::Lost;
                }
                Insertion::Inserted(self.commit_cavity(v)[0])
            }
        }
    }

    /// All live tets incident to `v` (ghosts included), in `out` (cleared first). Empty when
    /// `v` is not inserted.
    pub fn star(&self, v: VertexId, out: &mut Vec<TetId>) {
        self.search_star(v, out, |_| false);
    }

    /// Walks `v`'s star (breadth first from its vertex tet, into `out`, cleared first) until
    /// `hit` accepts a tet, which is returned; `None` after the whole star.
    fn search_star(
        &self,
        v: VertexId,
        out: &mut Vec<TetId>,
        hit: impl FnMut(&Tet) -> bool,
    ) -> Option<TetId> {
        out.clear();
        let start = self.vertex_tet(v);
        if start == NONE {
            return None;
        }
        self.search_around(start, [v, v], out, hit)
    }

    /// The live tets around edge `ab` (ghosts included), in `out` (cleared first), from `t0`,
    /// a tet containing both.
    pub fn edge_ring(&self, t0: TetId, a: VertexId, b: VertexId, out: &mut Vec<TetId>) {
        self.search_around(t0, [a, b], out, |_| false);
    }

    /// The tets containing the pivot vertices `piv` (one vertex twice, or an edge), reached
    /// from `start` (which contains them) across faces that contain them, breadth first into
    /// `out` (cleared first), until `hit` accepts one, which is returned.
    fn search_around(
        &self,
        start: TetId,
        piv: [VertexId; 2],
        out: &mut Vec<TetId>,
        mut hit: impl FnMut(&Tet) -> bool,
    ) -> Option<TetId> {
        out.clear();
        out.push(start);
        if hit(&self.tets[start as usize]) {
            return Some(start);
        }
        // Most stars are small (tens of tets) and rings smaller, where a linear membership
        // test beats hashing; vertices where many facets meet (real surface models) have stars
        // of hundreds, where it would be quadratic: past `LINEAR` tets a set takes over.
        const LINEAR: usize = 48;
        let mut seen: Option<crate::hash::FastSet<TetId>> = None;
        let mut i = 0;
        while i < out.len() {
            let t = out[i];
            i += 1;
            let tet = &self.tets[t as usize];
            for f in 0..4 {
                if piv.contains(&tet.v[f]) || tet.n[f] == NONE {
                    continue;
                }
                let u = tet.n[f] >> 2;
                let new = match &mut seen {
                    Some(set) => set.insert(u),
                    None => !out.contains(&u),
                };
                if new {
                    out.push(u);
                    if hit(&self.tets[u as usize]) {
                        return Some(u);
                    }
                    if seen.is_none() && out.len() > LINEAR {
                        seen = Some(out.iter().copied().collect());
                    }
                }
            }
        }
        None
    }

    /// A live tet (possibly a ghost, when `ab` is a hull edge or one end is [`GHOST`])
    /// containing both `a` and `b`.
    pub fn find_edge(&self, a: VertexId, b: VertexId) -> Option<TetId> {
        let mut star = Vec::with_capacity(64);
        self.search_star(a, &mut star, |t| t.v.contains(&b))
    }

    /// A half-face `4t + f` whose face has the vertices `a, b, c` (in any order): `t` contains
    /// all three and `f` is the position of its fourth vertex.
    pub fn find_face(&self, a: VertexId, b: VertexId, c: VertexId) -> Option<u32> {
        let mut star = Vec::with_capacity(64);
        let t = self.search_star(a, &mut star, |t| t.v.contains(&b) && t.v.contains(&c))?;
        let v = self.tets[t as usize].v;
        let f = (0..4).find(|&i| v[i] != a && v[i] != b && v[i] != c)?;
        Some(neighbor_ref(t, f))
    }
}

/// Whether `p` conflicts with the ghost tet on hull triangle `a, b, c` (given in the ghost's
/// face order, so that `orient3d(a, b, c, q) > 0` for `q` strictly outside the hull): `p` is
/// strictly beyond the triangle's plane, or in that plane and strictly inside the triangle's
/// circumcircle. Exact.
#[inline]
pub fn ghost_conflict(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> bool {
    let o = orient3d_fast(a, b, c, p);
    if o != 0.0 {
        return o > 0.0;
    }
    in_circumcircle_coplanar(a, b, c, p)
}

/// For `p` exactly in the plane of the (non-degenerate) triangle `a, b, c`: whether `p` lies
/// strictly inside the triangle's circumcircle. Exact (see [`crate::predicates::incircle3d`]).
pub fn in_circumcircle_coplanar(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> bool {
    crate::predicates::incircle3d(a, b, c, p) > 0.0
}
