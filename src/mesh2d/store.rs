//! The 2D kernel: the triangulation store and the incremental Bowyer–Watson algorithm (paper
//! §2, Fig. 2), generic over the exact predicates of a [`Geometry`] and monomorphised for
//! each (see `geometry.rs`). One point location (a visibility walk), one cavity routine, one
//! segment recovery (`recover.rs`) and one flip loop (`flip.rs`) serve the 2D mesher and the
//! 3D input checks' facet triangulations.
//!
//! Triangles live in flat arrays indexed by `TriId`; half-edge `3t + i` is the edge of triangle
//! `t` opposite its vertex `i`, directed counter-clockwise (`v[i+1] → v[i+2]`). The triangulation
//! covers the whole plane: the convex hull is closed by *ghost* triangles sharing one symbolic
//! vertex at infinity (`ghost`), which plays the paper's bounding triangle with the bounding
//! vertices infinitely far away, so no bounding-box vertex can spoil the hull.
//!
//! Segments that are present in the mesh are *walls*: a cavity never crosses one. A point that
//! would delete a segment or lies inside its diametral circle reports it instead (paper Fig. 2
//! steps 5–6): a `Provisional` insertion aborts and hands the segment back; a `Force` insertion
//! queues the segment for splitting and continues.

use super::geometry::{Geometry, Plane};
use super::NONE;

/// A vertex index.
pub type VertexId = u32;
/// A triangle index.
pub type TriId = u32;
/// A segment (subsegment) index.
pub type SegId = u32;

/// Region label of triangles outside the domain (reached from infinity).
pub const EXTERIOR: u32 = NONE;
/// Region label of triangles inside a hole.
pub const HOLE: u32 = NONE - 1;
/// Region label of domain triangles that belong to no region seed.
pub const NO_REGION: u32 = NONE - 2;

/// How an insertion treats encroached segments (paper Fig. 2).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Mode {
    /// Insert anyway; encroached segments are queued for splitting.
    Force,
    /// Abort without changing the mesh and return the first encroached segment.
    Provisional,
}

/// Where an insertion starts.
#[derive(Clone, Copy, Debug)]
pub enum Start {
    /// Walk from this triangle to the point.
    Walk(TriId),
    /// The point splits the segment on this half-edge: seed the cavity with both of its
    /// triangles and let the cavity cross it.
    SplitEdge(u32),
}

/// The outcome of an insertion attempt.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Inserted {
    /// The point was inserted as this vertex; the new triangles are in `Cdt::new_tris`.
    Yes(VertexId),
    /// `Provisional` only: the point encroaches this segment; nothing changed.
    Encroached(SegId),
    /// The point coincides with this existing vertex; nothing changed.
    Duplicate(VertexId),
    /// The point lies exactly on this segment (not the one being split); nothing changed.
    OnSegment(SegId),
    /// Point location ran out of its step budget (a bug); nothing changed.
    LostWalk,
}

/// A subsegment: a piece of an input segment (or of the convex hull in convex-hull mode).
#[derive(Clone, Copy, Debug)]
pub struct Seg {
    /// First endpoint.
    pub a: VertexId,
    /// Second endpoint.
    pub b: VertexId,
    /// The input segment this piece belongs to (`NONE` for hull segments).
    pub input: u32,
    /// The output marker.
    pub marker: i32,
    /// No Steiner point may split it (Triangle's `-Y` on boundary segments, `-YY` on all):
    /// it stays one edge, encroached or not.
    pub fixed: bool,
}

/// Per-triangle data besides corners and links, in one record: a cavity search reads a
/// neighbour's mark, then its flatness, then (in the fan) its segments and region, and one
/// record makes that one cache miss instead of four.
#[derive(Clone, Copy, Debug)]
pub struct TriAux {
    /// `s[i]`: the segment on edge `i`, or `NONE`.
    pub s: [SegId; 3],
    /// Region label (see [`EXTERIOR`], [`HOLE`], [`NO_REGION`]).
    pub reg: u32,
    /// Mark of cavity searches: equal to the search's epoch (inside) or the next (outside).
    pub(super) stamp: u32,
    /// Made flat or inverted by rounding (see `same_input_segment`).
    pub(super) flat: bool,
}

impl TriAux {
    /// A fresh slot's record (stamp 0, which no epoch equals).
    pub const FRESH: TriAux = TriAux {
        s: [NONE; 3],
        reg: NO_REGION,
        stamp: 0,
        flat: false,
    };
}

/// The triangulation, its segments and reusable scratch space.
pub struct Cdt<G: Geometry = Plane> {
    /// The exact predicates.
    pub geom: G,
    /// Vertex coordinates; the ghost vertex holds [`Geometry::infinite`].
    pub pts: Vec<G::Point>,
    /// One triangle incident to each vertex (`NONE` before insertion).
    pub vtri: Vec<TriId>,
    /// For vertices on a segment: the input segment they lie on; else `NONE`.
    pub vseg: Vec<u32>,
    /// The symbolic vertex at infinity.
    pub ghost: VertexId,
    /// Triangle corners (counter-clockwise); `[NONE; 3]` for a free slot.
    pub tv: Vec<[VertexId; 3]>,
    /// `tn[t][i]`: the twin half-edge (`3t' + j`) across edge `i` of `t`.
    pub tn: Vec<[u32; 3]>,
    /// The rest of each triangle's record: segments, region, search mark, flatness.
    pub aux: Vec<TriAux>,
    pub(super) free: Vec<TriId>,
    /// Subsegments.
    pub segs: Vec<Seg>,
    /// Segments waiting to be split (paper's queue `P` of Force'd points).
    pub split_queue: Vec<SegId>,
    /// Whether a segment is in `split_queue`.
    pub seg_queued: Vec<bool>,
    /// Triangles created by the last successful insertion.
    pub new_tris: Vec<TriId>,
    /// The epoch pair of the current cavity search (see [`TriAux::stamp`]).
    pub(super) epoch: u32,
    cavity: Vec<TriId>,
    boundary: Vec<u32>,
    breg: Vec<u32>,
    bflat: Vec<bool>,
    bedge: Vec<(VertexId, VertexId, SegId)>,
    /// Endpoints of each input segment (to recognise points on one input segment).
    pub inseg_ends: Vec<[VertexId; 2]>,
    /// Per-vertex scratch of `fill`, sized lazily there.
    vmark: Vec<TriId>,
    /// Whether the exterior and holes have been carved away.
    pub carved: bool,
    /// Whether an insertion may have left an edge that is not locally Delaunay: a split
    /// point's cavity seeded with a triangle the point is not in conflict with, or stopped
    /// at an edge hidden from the point with a triangle in conflict behind it (both only for
    /// points rounded off their edge). [`Cdt::legalize_all`] mends such edges.
    pub unsettled: bool,
    /// Scratch space of constrained segment insertion (`recover.rs`).
    pub(super) rec: Scratch,
    /// The last triangle created (a walking hint).
    pub hint: TriId,
    /// Scratch of [`Cdt::insert_bulk`]: half-edges still to cross, and the cavity boundary
    /// as `[outer twin, q, r]` in counter-clockwise order.
    bulk_stack: Vec<u32>,
    bulk_bnd: Vec<[u32; 3]>,
}

/// Reusable buffers of constrained segment insertion (`recover.rs`) and of the flips
/// (`flip.rs`), so that recovering many segments allocates nothing after warm-up.
#[derive(Default)]
pub(super) struct Scratch {
    pub(super) crossed: Vec<TriId>,
    pub(super) left: Vec<VertexId>,
    pub(super) right: Vec<VertexId>,
    pub(super) stack: Vec<(usize, usize)>,
    pub(super) tris: Vec<[VertexId; 3]>,
    /// Old boundary edges: (directed key, outer twin half-edge, segment).
    pub(super) border: Vec<(u64, u32, SegId)>,
    /// New half-edges: (directed key, index into `tris` * 3 + edge).
    pub(super) halves: Vec<(u64, u32)>,
    pub(super) fan: Vec<TriId>,
    /// The edge stack of `Cdt::legalize`.
    pub(super) flips: Vec<u32>,
}

#[inline]
pub(crate) fn next(i: usize) -> usize {
    if i == 2 {
        0
    } else {
        i + 1
    }
}

#[inline]
pub(crate) fn prev(i: usize) -> usize {
    if i == 0 {
        2
    } else {
        i - 1
    }
}

impl Cdt<Plane> {
    /// An empty store for `n` input points of the plane (the ghost vertex gets index `n`).
    pub fn new(points: &[[f64; 2]]) -> Cdt {
        Cdt::with_geometry(Plane, points)
    }
}

impl<G: Geometry> Cdt<G> {
    /// An empty store for `n` input points of geometry `geom` (the ghost vertex gets index
    /// `n`).
    pub fn with_geometry(geom: G, points: &[G::Point]) -> Cdt<G> {
        let n = points.len();
        let mut pts = Vec::with_capacity(n + 1 + n / 2);
        pts.extend_from_slice(points);
        pts.push(geom.infinite());
        let cap = 2 * n + 8;
        Cdt {
            geom,
            pts,
            vtri: vec![NONE; n + 1],
            vseg: vec![NONE; n + 1],
            ghost: n as u32,
            tv: Vec::with_capacity(cap),
            tn: Vec::with_capacity(cap),
            aux: Vec::with_capacity(cap),
            free: Vec::new(),
            segs: Vec::new(),
            split_queue: Vec::new(),
            seg_queued: Vec::new(),
            new_tris: Vec::new(),
            epoch: 0,
            cavity: Vec::new(),
            boundary: Vec::new(),
            breg: Vec::new(),
            bflat: Vec::new(),
            bedge: Vec::new(),
            inseg_ends: Vec::new(),
            vmark: Vec::new(),
            carved: false,
            unsettled: false,
            rec: Default::default(),
            hint: 0,
            bulk_stack: Vec::new(),
            bulk_bnd: Vec::new(),
        }
    }

    /// Number of triangle slots (live or free).
    #[inline]
    pub fn num_slots(&self) -> usize {
        self.tv.len()
    }

    /// Whether slot `t` holds a live triangle.
    #[inline]
    pub fn alive(&self, t: TriId) -> bool {
        self.tv[t as usize][0] != NONE
    }

    /// Whether triangle `t` has the ghost vertex.
    #[inline]
    pub fn is_ghost(&self, t: TriId) -> bool {
        let v = self.tv[t as usize];
        v[0] == self.ghost || v[1] == self.ghost || v[2] == self.ghost
    }

    #[inline]
    pub(super) fn p(&self, v: VertexId) -> G::Point {
        self.pts[v as usize]
    }

    pub(super) fn alloc(&mut self) -> TriId {
        if let Some(t) = self.free.pop() {
            return t;
        }
        let t = self.tv.len() as TriId;
        self.tv.push([NONE; 3]);
        self.tn.push([NONE; 3]);
        self.aux.push(TriAux::FRESH);
        t
    }

    /// Adds a new vertex (not yet inserted) and returns its id.
    pub fn push_vertex(&mut self, p: G::Point, on_input_seg: u32) -> VertexId {
        let id = self.pts.len() as VertexId;
        self.pts.push(p);
        self.vtri.push(NONE);
        self.vseg.push(on_input_seg);
        id
    }

    /// Builds the first triangle `a, b, c` (counter-clockwise, inserted) and its three ghosts.
    pub fn init_triangle(&mut self, a: VertexId, b: VertexId, c: VertexId) {
        let g = self.ghost;
        let t = self.alloc();
        let g0 = self.alloc(); // across edge 0 (b, c): ghost (c, b, g)
        let g1 = self.alloc(); // across edge 1 (c, a): ghost (a, c, g)
        let g2 = self.alloc(); // across edge 2 (a, b): ghost (b, a, g)
        self.tv[t as usize] = [a, b, c];
        self.tv[g0 as usize] = [c, b, g];
        self.tv[g1 as usize] = [a, c, g];
        self.tv[g2 as usize] = [b, a, g];
        self.tn[t as usize] = [3 * g0 + 2, 3 * g1 + 2, 3 * g2 + 2];
        self.tn[g0 as usize][2] = 3 * t;
        self.tn[g1 as usize][2] = 3 * t + 1;
        self.tn[g2 as usize][2] = 3 * t + 2;
        // Ghost-to-ghost edges: (c, b, g) edge 0 is (b, g); its twin is (g, b) in (b, a, g) edge 1.
        self.link(3 * g0, 3 * g2 + 1);
        // (c, b, g) edge 1 is (g, c); twin (c, g) in (a, c, g) edge 0.
        self.link(3 * g0 + 1, 3 * g1);
        // (a, c, g) edge 1 is (g, a); twin (a, g) in (b, a, g) edge 0.
        self.link(3 * g1 + 1, 3 * g2);
        for v in [a, b, c] {
            self.vtri[v as usize] = t;
        }
        self.vtri[g as usize] = g0;
        self.hint = t;
    }

    #[inline]
    pub(super) fn link(&mut self, h1: u32, h2: u32) {
        self.tn[(h1 / 3) as usize][(h1 % 3) as usize] = h2;
        self.tn[(h2 / 3) as usize][(h2 % 3) as usize] = h1;
    }

    /// The twin of half-edge `h`.
    #[inline]
    pub fn twin(&self, h: u32) -> u32 {
        self.tn[(h / 3) as usize][(h % 3) as usize]
    }

    /// The endpoints `(from, to)` of half-edge `h`.
    #[inline]
    pub fn edge_ends(&self, h: u32) -> (VertexId, VertexId) {
        let t = (h / 3) as usize;
        let i = (h % 3) as usize;
        (self.tv[t][next(i)], self.tv[t][prev(i)])
    }

    /// The vertex opposite half-edge `h` in its triangle.
    #[inline]
    pub fn apex(&self, h: u32) -> VertexId {
        self.tv[(h / 3) as usize][(h % 3) as usize]
    }

    /// The segment on half-edge `h`, or `NONE`.
    #[inline]
    pub fn seg_at(&self, h: u32) -> SegId {
        self.aux[(h / 3) as usize].s[(h % 3) as usize]
    }

    /// Marks (or clears, with `NONE`) the segment on half-edge `h` and its twin.
    pub fn set_seg(&mut self, h: u32, s: SegId) {
        let tw = self.twin(h);
        self.aux[(h / 3) as usize].s[(h % 3) as usize] = s;
        if tw != NONE {
            self.aux[(tw / 3) as usize].s[(tw % 3) as usize] = s;
        }
    }

    /// Whether `q` and `r` and a new point on input segment `seg` all lie on input segment
    /// `seg` by construction. Split points are rounded, so three such points can be flat or
    /// even turn the wrong way by an ulp; the triangles they make only ever sit in the empty
    /// exterior or a hole (a near-flat triangle elsewhere has vertices in its circumcircle).
    /// Only splits before carving (the fallback when a segment cannot be inserted as a
    /// constrained edge) can make them; after carving such a point is refused instead.
    fn same_input_segment(&self, seg: u32, q: VertexId, r: VertexId) -> bool {
        if seg == NONE {
            return false;
        }
        let ends = self.inseg_ends[seg as usize];
        let on = |v: VertexId| self.vseg[v as usize] == seg || ends.contains(&v);
        on(q) && on(r)
    }

    /// Deletes every triangle whose region is [`EXTERIOR`] or [`HOLE`] (Triangle's carving):
    /// refinement then only ever sees the domain, bounded by segments with no neighbour.
    pub fn carve(&mut self) {
        self.carved = true;
        // Segments with no domain triangle on either side (dangling in a hole or outside)
        // leave the mesh with the exterior: retire them (endpoint `a` set to `NONE`).
        for s in 0..self.segs.len() {
            let Seg { a, b, .. } = self.segs[s];
            if let Some(h) = self.find_edge(a, b) {
                let tw = self.twin(h);
                let outside = |t: u32| matches!(self.aux[t as usize].reg, EXTERIOR | HOLE);
                if outside(h / 3) && (tw == NONE || outside(tw / 3)) {
                    self.segs[s].a = NONE;
                }
            }
        }
        // A vertex whose triangle goes moves to a kept triangle beside it across one of its
        // edges; one with none there (in a hole, outside, or kept only further round) is
        // `lost`, and only then are all vertices' triangles found again by a pass over the
        // mesh (a million scattered points lose only the ghost, which leaves the mesh).
        let kept = |cdt: &Cdt<G>, t: u32| {
            cdt.tv[t as usize][0] != NONE && !matches!(cdt.aux[t as usize].reg, EXTERIOR | HOLE)
        };
        let mut lost = false;
        for t in 0..self.tv.len() {
            if self.tv[t][0] == NONE || !matches!(self.aux[t].reg, EXTERIOR | HOLE) {
                continue;
            }
            for i in 0..3 {
                let v = self.tv[t][i];
                if self.vtri[v as usize] != t as TriId {
                    continue;
                }
                let beside = [self.tn[t][(i + 1) % 3], self.tn[t][(i + 2) % 3]]
                    .into_iter()
                    .find(|&h| h != NONE && kept(self, h / 3));
                match beside {
                    Some(h) => self.vtri[v as usize] = h / 3,
                    None if v == self.ghost => self.vtri[v as usize] = NONE,
                    None => lost = true,
                }
            }
            for i in 0..3 {
                let tw = self.tn[t][i];
                if tw != NONE {
                    self.tn[(tw / 3) as usize][(tw % 3) as usize] = NONE;
                }
            }
            self.tv[t] = [NONE; 3];
            self.tn[t] = [NONE; 3];
            self.free.push(t as TriId);
        }
        if lost {
            self.vtri.iter_mut().for_each(|v| *v = NONE);
            for t in 0..self.tv.len() {
                for &v in &self.tv[t] {
                    if v != NONE {
                        self.vtri[v as usize] = t as TriId;
                        self.hint = t as TriId;
                    }
                }
            }
        } else if let Some(t) = (0..self.tv.len() as u32)
            .rev()
            .find(|&t| self.tv[t as usize][0] != NONE)
        {
            // The hint the pass would leave: the last triangle.
            self.hint = t;
        }
    }

    /// Deletes the triangle of half-edge `h`, an open edge of the carved domain, when its
    /// other two edges are inner edges: they become the open boundary instead (each keeps
    /// its segment, if any). How a vertex lying within rounding inside a boundary segment
    /// joins it: the sliver between the vertex and the segment leaves the domain. Returns
    /// whether it was done.
    pub fn peel(&mut self, h: u32) -> bool {
        let t = h / 3;
        let i = (h % 3) as usize;
        if self.twin(h) != NONE || !self.alive(t) {
            return false;
        }
        let v = self.tv[t as usize];
        let (tn, tp) = (self.tn[t as usize][next(i)], self.tn[t as usize][prev(i)]);
        if tn == NONE || tp == NONE {
            return false;
        }
        for tw in [tn, tp] {
            self.tn[(tw / 3) as usize][(tw % 3) as usize] = NONE;
        }
        // Edge next(i) is opposite v[next(i)]: its far triangle holds v[prev(i)] and v[i].
        self.vtri[v[i] as usize] = tn / 3;
        self.vtri[v[prev(i)] as usize] = tn / 3;
        self.vtri[v[next(i)] as usize] = tp / 3;
        self.tv[t as usize] = [NONE; 3];
        self.tn[t as usize] = [NONE; 3];
        self.free.push(t);
        if self.hint == t {
            self.hint = tn / 3;
        }
        true
    }

    /// Finds the half-edge from `b` to `a` (or, when only `a → b` exists on an open boundary,
    /// that one) by turning around `a` both ways; `None` if `ab` is no edge. The answer
    /// depends only on the mesh, not on which triangle `vtri` keeps for `a`: callers seed
    /// cavities from it, so the side would otherwise steer the order of the new triangles.
    /// (`b → a`, not `a → b`: of the two fixed choices it is the one that keeps every count
    /// of the small-angle family of `tests/size2d.rs`; `a → b` made 328 triangles of the
    /// T-junction at 33°, where Triangle makes 318.)
    pub fn find_edge(&self, a: VertexId, b: VertexId) -> Option<u32> {
        let h = self.find_either_edge(a, b)?;
        let tw = self.twin(h);
        if self.edge_ends(h).0 == a && tw != NONE {
            Some(tw)
        } else {
            Some(h)
        }
    }

    /// A half-edge between `a` and `b`, either way: the first met turning around `a`.
    fn find_either_edge(&self, a: VertexId, b: VertexId) -> Option<u32> {
        let start = self.vtri[a as usize];
        if start == NONE {
            return None;
        }
        let corner = |t: TriId| {
            let v = self.tv[t as usize];
            if v[0] == a {
                0
            } else if v[1] == a {
                1
            } else {
                2
            }
        };
        let hit = |t: TriId| {
            let k = corner(t);
            let v = self.tv[t as usize];
            if v[next(k)] == b {
                Some(3 * t + prev(k) as u32)
            } else if v[prev(k)] == b {
                Some(3 * t + next(k) as u32)
            } else {
                None
            }
        };
        // Clockwise: cross edge (v[k+2], a), opposite v[k+1]. The budget guards a corrupted fan.
        let mut t = start;
        for _ in 0..1_000_000 {
            if let Some(h) = hit(t) {
                return Some(h);
            }
            let h = self.tn[t as usize][next(corner(t))];
            if h == NONE {
                break;
            }
            t = h / 3;
            if t == start {
                return None;
            }
        }
        // Counter-clockwise from the start, for fans cut open by carving.
        let mut t = start;
        for _ in 0..1_000_000 {
            let h = self.tn[t as usize][prev(corner(t))];
            if h == NONE {
                return None;
            }
            t = h / 3;
            if let Some(h) = hit(t) {
                return Some(h);
            }
        }
        None
    }

    /// The orientation of vertices `a, b, c` (see [`Geometry::orient`]).
    #[inline]
    pub fn orient_ids(&self, a: VertexId, b: VertexId, c: VertexId) -> f64 {
        self.geom.orient(self.p(a), self.p(b), self.p(c))
    }

    /// The orientation of vertices `a, b` and point `p` (see [`Geometry::orient`]).
    #[inline]
    pub fn orient_at(&self, a: VertexId, b: VertexId, p: G::Point) -> f64 {
        self.geom.orient(self.p(a), self.p(b), p)
    }

    /// Spreads region label `label` from the triangles on `stack` to every triangle reached
    /// without crossing a segment (or an open edge). The exterior overrides everything; a
    /// hole overrides regions; a region never enters the exterior or a hole.
    pub fn flood(&mut self, stack: &mut Vec<TriId>, label: u32) {
        while let Some(t) = stack.pop() {
            for i in 0..3 {
                let tw = self.tn[t as usize][i];
                if self.aux[t as usize].s[i] != NONE || tw == NONE {
                    continue;
                }
                let n = tw / 3;
                let cur = self.aux[n as usize].reg;
                if cur == label || (label != EXTERIOR && cur == EXTERIOR) {
                    continue;
                }
                if label == EXTERIOR || label == HOLE || cur != HOLE {
                    self.aux[n as usize].reg = label;
                    stack.push(n);
                }
            }
        }
    }

    /// Whether `p` conflicts with triangle `t`: strictly inside its circumcircle, or, for a
    /// ghost triangle, strictly outside its hull edge or on the open hull edge.
    #[inline]
    pub fn conflict(&self, t: TriId, p: G::Point) -> bool {
        let v = self.tv[t as usize];
        let g = self.ghost;
        if v[0] == g || v[1] == g || v[2] == g {
            let k = if v[0] == g {
                0
            } else if v[1] == g {
                1
            } else {
                2
            };
            let a = self.p(v[next(k)]);
            let b = self.p(v[prev(k)]);
            let o = self.geom.orient(a, b, p);
            o > 0.0 || (o == 0.0 && self.geom.strictly_between(a, b, p))
        } else if self.aux[t as usize].flat {
            // A rounding-flat sliver (three points of one input segment): decide with its true
            // orientation, so the cavity search sees the geometry the coordinates really have.
            let (a, b, c) = (self.p(v[0]), self.p(v[1]), self.p(v[2]));
            let o = self.geom.orient(a, b, c);
            if o > 0.0 {
                self.geom.incircle(a, b, c, p) > 0.0
            } else if o < 0.0 {
                self.geom.incircle(a, c, b, p) > 0.0
            } else {
                false
            }
        } else {
            self.geom
                .incircle(self.p(v[0]), self.p(v[1]), self.p(v[2]), p)
                > 0.0
        }
    }

    /// Visibility walk from `start` to the triangle containing `p`. Returns the triangle (or a
    /// ghost when `p` is outside the hull). With `stop_at_walls`, crossing a segment is refused
    /// and the segment is returned as `Err(seg)`.
    pub fn locate(
        &self,
        start: TriId,
        p: G::Point,
        stop_at_walls: bool,
    ) -> Result<TriId, Option<SegId>> {
        let mut t = start;
        if t == NONE || !self.alive(t) {
            return Err(None);
        }
        if self.is_ghost(t) {
            // Start from the finite triangle across the ghost's hull edge.
            let v = self.tv[t as usize];
            let k = (0..3).find(|&k| v[k] == self.ghost).unwrap_or(0);
            t = self.tn[t as usize][k] / 3;
        }
        let budget = 4 * self.tv.len() + 64;
        let mut rot = 0usize;
        for _ in 0..budget {
            let v = self.tv[t as usize];
            if self.is_ghost(t) {
                return Ok(t);
            }
            let mut moved = false;
            rot = if rot == 2 { 0 } else { rot + 1 };
            for d in 0..3 {
                let i = (rot + d) % 3;
                let a = self.p(v[next(i)]);
                let b = self.p(v[prev(i)]);
                if self.geom.orient(a, b, p) < 0.0 {
                    let s = self.aux[t as usize].s[i];
                    let tw = self.tn[t as usize][i];
                    if (stop_at_walls && s != NONE) || tw == NONE {
                        // After carving, every open edge is a segment.
                        return Err((s != NONE).then_some(s));
                    }
                    t = tw / 3;
                    moved = true;
                    break;
                }
            }
            if !moved {
                return Ok(t);
            }
        }
        Err(None)
    }

    /// Finds a live, properly oriented triangle containing `p` (or a ghost in conflict with it)
    /// by scanning every triangle: the fallback when a walk fails.
    fn scan_locate(&self, p: G::Point) -> Option<TriId> {
        let mut ghost_hit = None;
        for t in 0..self.tv.len() as TriId {
            if !self.alive(t) {
                continue;
            }
            if self.is_ghost(t) {
                if ghost_hit.is_none() && self.conflict(t, p) {
                    ghost_hit = Some(t);
                }
                continue;
            }
            let [a, b, c] = self.tv[t as usize].map(|v| self.p(v));
            if self.geom.orient(a, b, c) > 0.0
                && self.geom.orient(a, b, p) >= 0.0
                && self.geom.orient(b, c, p) >= 0.0
                && self.geom.orient(c, a, p) >= 0.0
            {
                return Some(t);
            }
        }
        ghost_hit
    }

    /// A slot for [`Cdt::insert_bulk`]: only `tv` and `tn` grow; the other per-triangle
    /// arrays catch up in [`Cdt::sync_aux`].
    #[inline]
    fn alloc_bulk(&mut self) -> TriId {
        if let Some(t) = self.free.pop() {
            return t;
        }
        let t = self.tv.len() as TriId;
        self.tv.push([NONE; 3]);
        self.tn.push([NONE; 3]);
        t
    }

    /// Brings the per-triangle arrays other than `tv` and `tn` to the slot count, with the
    /// values a fresh slot gets (after [`Cdt::insert_bulk`]).
    pub fn sync_aux(&mut self) {
        let n = self.tv.len();
        self.aux.resize(n, TriAux::FRESH);
    }

    /// Gives every slot a stamp (new slots get 0, which no epoch equals) and starts a new
    /// epoch pair; returns the first epoch of the pair.
    pub(super) fn ready_stamps(&mut self) -> u32 {
        if self.aux.len() < self.tv.len() {
            self.sync_aux();
        }
        self.epoch = self.epoch.wrapping_add(2);
        if self.epoch < 2 {
            // Wrapped around: clear the stamps so old values cannot alias the new epoch.
            self.aux.iter_mut().for_each(|a| a.stamp = 0);
            self.epoch = 2;
        }
        self.epoch
    }

    /// Renames every vertex `r < ghost` of the triangles (and their `vtri` entries) to
    /// `names[r]`: the way back from the ranked names of the bulk insertion.
    pub fn rename_vertices(&mut self, names: &[u32]) {
        let g = self.ghost;
        for tri in &mut self.tv {
            for v in tri.iter_mut() {
                if *v < g {
                    *v = names[*v as usize];
                }
            }
        }
        let mut vtri = vec![NONE; self.vtri.len()];
        for (r, &t) in self.vtri.iter().enumerate().take(g as usize) {
            vtri[names[r] as usize] = t;
        }
        vtri[g as usize..].copy_from_slice(&self.vtri[g as usize..]);
        self.vtri = vtri;
    }

    /// [`Cdt::conflict`] for triangle corners `v` while no triangle is flat (before any
    /// segment exists).
    #[inline(always)]
    fn conflict_plain(&self, v: [VertexId; 3], p: G::Point) -> bool {
        let g = self.ghost;
        if v[0] == g || v[1] == g || v[2] == g {
            let (a, b) = if v[0] == g {
                (v[1], v[2])
            } else if v[1] == g {
                (v[2], v[0])
            } else {
                (v[0], v[1])
            };
            let (a, b) = (self.p(a), self.p(b));
            let o = self.geom.orient(a, b, p);
            o > 0.0 || (o == 0.0 && self.geom.strictly_between(a, b, p))
        } else {
            self.geom
                .incircle_bulk(self.p(v[0]), self.p(v[1]), self.p(v[2]), p)
                > 0.0
        }
    }

    /// Visibility walk without walls from `start` to the triangle containing `p` (or a ghost
    /// when `p` is outside the hull). The edge the walk came in through is not tested again:
    /// `p` lies strictly beyond it (the same exact orientation, seen from the other side).
    /// `None` when the budget runs out.
    fn walk_plain(&self, start: TriId, p: G::Point) -> Option<TriId> {
        let g = self.ghost;
        let mut t = start;
        let v = self.tv[t as usize];
        if v[0] == g || v[1] == g || v[2] == g {
            let k = (0..3).find(|&k| v[k] == g).unwrap_or(0);
            t = self.tn[t as usize][k] / 3;
        }
        // `from`: the edge of `t` the walk entered through (3: none).
        let mut from = 3usize;
        let budget = 4 * self.tv.len() + 64;
        for _ in 0..budget {
            let v = self.tv[t as usize];
            if v[0] == g || v[1] == g || v[2] == g {
                return Some(t);
            }
            let pv = [self.p(v[0]), self.p(v[1]), self.p(v[2])];
            let start_edge = if from == 3 { 0 } else { next(from) };
            let mut moved = false;
            let mut i = start_edge;
            for _ in 0..3 {
                if i != from && self.geom.orient(pv[next(i)], pv[prev(i)], p) < 0.0 {
                    let tw = self.tn[t as usize][i];
                    t = tw / 3;
                    from = (tw % 3) as usize;
                    moved = true;
                    break;
                }
                i = next(i);
            }
            if !moved {
                return Some(t);
            }
        }
        None
    }

    /// Inserts input vertex `pv` (already in `pts`) while the mesh has no segment and nothing
    /// is carved: the Bowyer–Watson step of [`Cdt::insert`] for `Mode::Force` without walls.
    /// Without walls the cavity (the triangles whose circumcircle holds `p` strictly, or ghosts
    /// `p` sees) is a topological disk whose dual graph is a tree and whose vertices all lie
    /// on its boundary, and `p` sees every boundary edge strictly. So the depth-first search
    /// needs no marks, and visiting each triangle's edges in counter-clockwise order yields
    /// the boundary in counter-clockwise order, which links the new fan directly.
    /// Only `tv` and `tn` are kept up to date; call [`Cdt::sync_aux`] afterwards.
    pub fn insert_bulk(&mut self, pv: VertexId) -> Inserted {
        debug_assert!(self.segs.is_empty() && !self.carved);
        let p = self.pts[pv as usize];
        let mut t = match self.walk_plain(self.hint, p) {
            Some(t) => t,
            None => {
                self.sync_aux();
                match self.scan_locate(p) {
                    Some(t) => t,
                    None => return Inserted::LostWalk,
                }
            }
        };
        let v = self.tv[t as usize];
        for &u in &v {
            if u != self.ghost && self.pts[u as usize] == p {
                return Inserted::Duplicate(u);
            }
        }
        if !self.conflict_plain(v, p) {
            // See `insert`: a point on the line of a hull edge but outside it.
            let mut found = NONE;
            for i in 0..3 {
                let n = self.tn[t as usize][i] / 3;
                if self.conflict_plain(self.tv[n as usize], p) {
                    found = n;
                    break;
                }
            }
            if found == NONE {
                return Inserted::LostWalk;
            }
            t = found;
        }
        let mut cavity = std::mem::take(&mut self.cavity);
        let mut stack = std::mem::take(&mut self.bulk_stack);
        let mut bnd = std::mem::take(&mut self.bulk_bnd);
        cavity.clear();
        stack.clear();
        bnd.clear();
        cavity.push(t);
        stack.extend_from_slice(&[3 * t + 2, 3 * t + 1, 3 * t]);
        while let Some(h) = stack.pop() {
            let tw = self.tn[(h / 3) as usize][(h % 3) as usize];
            let n = tw / 3;
            let j = (tw % 3) as usize;
            let nv = self.tv[n as usize];
            if self.conflict_plain(nv, p) {
                cavity.push(n);
                // Edge `j` of `n` runs r → q; its other edges, counter-clockwise from q.
                stack.push(3 * n + prev(j) as u32);
                stack.push(3 * n + next(j) as u32);
            } else {
                bnd.push([tw, nv[prev(j)], nv[next(j)]]);
            }
        }
        let result = self.fill_bulk(pv, &mut cavity, &bnd);
        self.cavity = cavity;
        self.bulk_stack = stack;
        self.bulk_bnd = bnd;
        result
    }

    /// The fan from `pv` over the boundary `bnd` (counter-clockwise, see
    /// [`Cdt::insert_bulk`]), reusing the cavity's slots.
    fn fill_bulk(&mut self, pv: VertexId, cavity: &mut Vec<TriId>, bnd: &[[u32; 3]]) -> Inserted {
        let nb = bnd.len();
        // A disk of `k` triangles has `k + 2` boundary edges forming one closed chain; check
        // it before changing anything (it always holds with exact predicates).
        if nb != cavity.len() + 2 || (0..nb).any(|k| bnd[k][2] != bnd[(k + 1) % nb][1]) {
            return Inserted::LostWalk;
        }
        let a = self.alloc_bulk();
        cavity.push(a);
        let b = self.alloc_bulk();
        cavity.push(b);
        let mut prev_t = cavity[nb - 1];
        for k in 0..nb {
            let t = cavity[k];
            let next_t = if k + 1 < nb { cavity[k + 1] } else { cavity[0] };
            let [outer, q, r] = bnd[k];
            let tu = t as usize;
            self.tv[tu] = [pv, q, r];
            self.tn[tu] = [outer, 3 * next_t + 2, 3 * prev_t + 1];
            self.tn[(outer / 3) as usize][(outer % 3) as usize] = 3 * t;
            self.vtri[q as usize] = t;
            prev_t = t;
        }
        self.vtri[pv as usize] = cavity[0];
        self.hint = cavity[0];
        Inserted::Yes(pv)
    }

    /// Queues segment `s` for splitting (once); fixed segments are never split.
    pub fn queue_split(&mut self, s: SegId) {
        if !self.seg_queued[s as usize] && !self.segs[s as usize].fixed {
            self.seg_queued[s as usize] = true;
            self.split_queue.push(s);
        }
    }

    /// Inserts point `p` (paper Fig. 2, steps 4–6). On success the new vertex's triangles are in
    /// `new_tris`. `split` is the segment being split by `p` (with `Start::SplitEdge`), if any.
    ///
    /// `existing` names an input vertex that already has its slot (input points keep their
    /// index); otherwise a new vertex lying on input segment `on_input_seg` (or `NONE`) is added.
    pub fn insert(
        &mut self,
        p: G::Point,
        start: Start,
        mode: Mode,
        on_input_seg: u32,
        existing: Option<VertexId>,
    ) -> Inserted {
        let inside = self.ready_stamps();
        let outside = inside + 1;
        self.cavity.clear();
        self.boundary.clear();
        let mut split_half = NONE;
        match start {
            Start::Walk(t0) => {
                let t = match self.locate(t0, p, mode == Mode::Provisional) {
                    Ok(t) => t,
                    Err(Some(s)) => return Inserted::Encroached(s),
                    // The walk can cycle through rounding-inverted slivers outside the domain:
                    // fall back to a scan (rare).
                    Err(None) => match self.scan_locate(p) {
                        Some(t) => t,
                        None => return Inserted::LostWalk,
                    },
                };
                let v = self.tv[t as usize];
                for &u in &v {
                    if u != self.ghost && self.pts[u as usize] == p {
                        return Inserted::Duplicate(u);
                    }
                }
                if !self.conflict(t, p) {
                    // Only possible for a point on the line of a hull edge but outside it, seen
                    // from a ghost whose neighbour holds the conflict; take the neighbour ghosts.
                    let mut found = NONE;
                    for i in 0..3 {
                        let n = self.tn[t as usize][i] / 3;
                        if self.conflict(n, p) {
                            found = n;
                            break;
                        }
                    }
                    if found == NONE {
                        return Inserted::LostWalk;
                    }
                    self.aux[found as usize].stamp = inside;
                    self.cavity.push(found);
                } else {
                    self.aux[t as usize].stamp = inside;
                    self.cavity.push(t);
                }
            }
            Start::SplitEdge(h) => {
                let tw = self.twin(h);
                split_half = h;
                for t in [h / 3, tw / 3] {
                    if t == NONE / 3 || self.aux[t as usize].stamp == inside {
                        continue;
                    }
                    self.aux[t as usize].stamp = inside;
                    self.cavity.push(t);
                    // A point on the edge is inside both circles; one rounded a hair beyond
                    // the edge, past a cap thinner than the rounding (a short edge, a far
                    // apex), is not, and the fan then has an edge to that apex that is not
                    // locally Delaunay (2D campaign, issue 14).
                    if !self.conflict(t, p) {
                        self.unsettled = true;
                    }
                }
                // The split point is computed in floating point and may round to just outside
                // both triangles of the edge (beyond a third, nearly flat one): seed the
                // triangle that really contains it too, so the cavity is star-shaped from it.
                if let Ok(t) = self.locate(h / 3, p, false) {
                    if self.aux[t as usize].stamp != inside && self.conflict(t, p) {
                        self.aux[t as usize].stamp = inside;
                        self.cavity.push(t);
                    }
                }
            }
        }
        let split_twin = if split_half != NONE {
            self.twin(split_half)
        } else {
            NONE
        };
        // Grow the cavity by depth-first search over the dual graph, stopping at walls.
        // A Provisional point encroaching only fixed segments is rejected, but one that also
        // encroaches a splittable segment reports that one, so it gets split.
        let mut fixed_hit = NONE;
        let mut k = 0;
        let mut taken = 0u32;
        'grow: loop {
            while k < self.cavity.len() {
                let t = self.cavity[k];
                k += 1;
                for i in 0..3 {
                    let h = 3 * t + i as u32;
                    if h == split_half || h == split_twin {
                        // The edge being split is inside the cavity (or, on a carved boundary,
                        // has no outside): the fan closes over it.
                        continue;
                    }
                    let tw = self.tn[t as usize][i];
                    let n = tw / 3;
                    let st = if tw == NONE {
                        0
                    } else {
                        self.aux[n as usize].stamp
                    };
                    if st == inside {
                        continue;
                    }
                    let s = self.aux[t as usize].s[i];
                    if s != NONE || tw == NONE {
                        let (a, b) = self.edge_ends(h);
                        if s != NONE && self.geom.encroaches(self.p(a), self.p(b), p) {
                            match mode {
                                Mode::Provisional if self.segs[s as usize].fixed => fixed_hit = s,
                                Mode::Provisional => return Inserted::Encroached(s),
                                Mode::Force => self.queue_split(s),
                            }
                        }
                        self.boundary.push(h);
                        continue;
                    }
                    // Visibility: cross an edge only when `p` sees it from the cavity side (or lies
                    // on its line). Without walls this loses no cavity triangle (the cavity is
                    // star-shaped from `p`); with walls it stops the cavity from wrapping around a
                    // vertex into triangles hidden behind a segment.
                    // (While the input points go in there are no segments and nothing to hide.)
                    let visible = self.segs.is_empty() || {
                        let (a, b) = self.edge_ends(h);
                        a == self.ghost
                            || b == self.ghost
                            || self.geom.orient(self.p(a), self.p(b), p) >= 0.0
                    };
                    if st != outside && visible && self.conflict(n, p) {
                        self.aux[n as usize].stamp = inside;
                        self.cavity.push(n);
                    } else {
                        if !visible && st != outside && self.conflict(n, p) {
                            self.unsettled = true;
                        }
                        self.aux[n as usize].stamp = outside;
                        self.boundary.push(h);
                    }
                }
            }
            if fixed_hit != NONE {
                return Inserted::Encroached(fixed_hit);
            }
            // Every new finite triangle must be counter-clockwise; a point exactly on a wall
            // (not the segment being split) would make a flat one.
            self.bflat.clear();
            // A split point (seeded, not located) can round onto an existing vertex.
            for j in 0..self.boundary.len() {
                let (q, r) = self.edge_ends(self.boundary[j]);
                for v in [q, r] {
                    if v != self.ghost && self.p(v) == p {
                        return Inserted::Duplicate(v);
                    }
                }
            }
            for j in 0..self.boundary.len() {
                let h = self.boundary[j];
                let (q, r) = self.edge_ends(h);
                let flat = q != self.ghost
                    && r != self.ghost
                    && self.geom.orient(p, self.p(q), self.p(r)) <= 0.0;
                let tolerated = flat && !self.carved && self.same_input_segment(on_input_seg, q, r);
                self.bflat.push(tolerated);
                if flat && !tolerated {
                    let s = self.seg_at(h);
                    if s != NONE {
                        return Inserted::OnSegment(s);
                    }
                    // A split point seeds the edge's triangles whether or not they conflict
                    // with it; past a fan of chain slivers thinner than an ulp (a boundary
                    // segment's split points rounded outward, seen from one far vertex of
                    // the chain) the cavity is then not star-shaped from it. Take the triangle behind
                    // the edge it cannot see as well (the fan is not locally Delaunay there
                    // for now: `unsettled`), and grow on (2D campaign, issue 14).
                    let tw = self.twin(h);
                    if split_twin != NONE || split_half == NONE || tw == NONE || taken >= 64 {
                        return Inserted::LostWalk;
                    }
                    taken += 1;
                    let n = tw / 3;
                    self.aux[n as usize].stamp = inside;
                    self.cavity.push(n);
                    self.unsettled = true;
                    let aux = &self.aux;
                    let tn = &self.tn;
                    self.boundary.retain(|&e| {
                        let o = tn[(e / 3) as usize][(e % 3) as usize];
                        o == NONE || aux[(o / 3) as usize].stamp != inside
                    });
                    continue 'grow;
                }
            }
            break;
        }
        if self.pts.len() >= (NONE - 8) as usize {
            return Inserted::LostWalk;
        }
        let pv = match existing {
            Some(v) => v,
            None => self.push_vertex(p, on_input_seg),
        };
        self.fill(pv)
    }

    /// Replaces the cavity by the fan of triangles from `pv` to its boundary (paper step 6).
    /// New triangles are `[pv, q, r]` for each boundary edge `q → r`, so edge 0 is the old
    /// boundary edge, edge 1 is `(r, pv)` and edge 2 is `(pv, q)`.
    fn fill(&mut self, pv: VertexId) -> Inserted {
        self.new_tris.clear();
        self.breg.clear();
        if self.vmark.len() < self.pts.len() {
            self.vmark.resize(self.pts.len(), NONE);
        }
        let ncav = self.cavity.len();
        let nb = self.boundary.len();
        // Save what lives in cavity slots before they are reused: the outer twin of each
        // boundary edge (which also gives its ends and segment) and the region label.
        self.bedge.clear();
        for j in 0..nb {
            let h = self.boundary[j];
            let t_in = (h / 3) as usize;
            let i = (h % 3) as usize;
            self.breg.push(self.aux[t_in].reg);
            let (q, r) = self.edge_ends(h);
            self.bedge.push((q, r, self.aux[t_in].s[i]));
            self.boundary[j] = self.tn[t_in][i];
        }
        for j in 0..nb {
            let outer = self.boundary[j];
            let (q, r, s) = self.bedge[j];
            let t = if j < ncav {
                self.cavity[j]
            } else {
                self.alloc()
            };
            self.new_tris.push(t);
            let tu = t as usize;
            self.tv[tu] = [pv, q, r];
            self.aux[tu].flat = self.bflat[j];
            self.aux[tu].s = [s, NONE, NONE];
            self.aux[tu].reg = self.breg[j];
            self.tn[tu] = [outer, NONE, NONE];
            if outer != NONE {
                self.tn[(outer / 3) as usize][(outer % 3) as usize] = 3 * t;
            }
        }
        for j in nb..ncav {
            let t = self.cavity[j];
            self.tv[t as usize] = [NONE; 3];
            self.free.push(t);
        }
        // Link the fan: the triangle starting at q (edge 2 = (pv, q)) meets the triangle ending
        // at q (edge 1 = (q, pv)).
        for &t in &self.new_tris {
            let q = self.tv[t as usize][1];
            self.vmark[q as usize] = t;
        }
        for j in 0..nb {
            let t = self.new_tris[j];
            let [_, q, r] = self.tv[t as usize];
            self.vtri[q as usize] = t;
            self.vtri[r as usize] = t;
            let t2 = self.vmark[r as usize];
            if t2 == NONE {
                // The fan is open here: a boundary segment was split and has no outside.
                continue;
            }
            self.tn[t as usize][1] = 3 * t2 + 2;
            self.tn[t2 as usize][2] = 3 * t + 1;
        }
        for j in 0..nb {
            let q = self.tv[self.new_tris[j] as usize][1];
            self.vmark[q as usize] = NONE;
        }
        self.vtri[pv as usize] = self.new_tris[0];
        self.hint = self.new_tris[0];
        Inserted::Yes(pv)
    }
}
