//! Segment recovery and splitting (the paper's queue `P` of Force'd points, Fig. 2 steps
//! 6–8) and the elimination of skinny and oversized triangles (`rm-tri`, Fig. 4).

use std::collections::VecDeque;

use super::kdtree::PointTree;
use super::recover::Recovery;
use super::store::{
    Cdt, Inserted, Mode, Seg, SegId, Start, TriId, VertexId, EXTERIOR, HOLE, NO_REGION,
};
use super::{Options, NONE};
use crate::error::{Error, InputError};
use crate::geometry::{area2, dist2, min_angle_sin2, steiner_point};
use crate::input2d::Pslg;
use crate::predicates::{encroaches, orient2d};
use crate::progress::{stage, tick, Stage};

/// One piece of an input segment after splitting it at input points lying on it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Piece {
    pub a: u32,
    pub b: u32,
    pub input: u32,
}

/// The marker of input segment `s` (1 when the input gives none, as for Triangle's boundary).
pub(super) fn segment_marker(pslg: &Pslg, s: usize) -> i32 {
    if pslg.segment_markers.is_empty() {
        1
    } else {
        pslg.segment_markers[s]
    }
}

/// The size class of a squared length `l2`: `floor(2 log2 l2)`, from its binary exponent and
/// whether its significand exceeds √2 (classes a factor 2^(1/4) apart in length, as Triangle's
/// queues). Monotone in `l2`; zero and subnormals fall in the lowest classes.
fn size_class(l2: f64) -> u32 {
    let bits = l2.max(0.0).to_bits();
    let exp = (bits >> 52) as u32;
    let above =
        f64::from_bits((bits & ((1u64 << 52) - 1)) | (1023u64 << 52)) > std::f64::consts::SQRT_2;
    2 * exp + above as u32
}

/// A conservative filter for "could this point lie in one of these squares": a grid of
/// [`NearSquares::SIDE`]² cells over the squares' bounding box, each cell marked when it or a
/// neighbouring cell meets a square (the margin of a cell absorbs the rounding of the cell
/// indices). Points off the grid fall in its border cells. It only selects candidates.
struct NearSquares {
    lo: [f64; 2],
    /// Cells per unit length.
    scale: f64,
    marked: Vec<u64>,
}

impl NearSquares {
    const SIDE: usize = 1024;

    /// The filter of the squares `(centre, half-side)`.
    fn new(squares: impl Iterator<Item = ([f64; 2], f64)> + Clone) -> NearSquares {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (c, r) in squares.clone() {
            for k in 0..2 {
                lo[k] = lo[k].min(c[k] - r);
                hi[k] = hi[k].max(c[k] + r);
            }
        }
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let scale = Self::SIDE as f64 / span;
        // No square, a single point, or a span too small to divide by: every point maps to
        // cell 0, which is marked.
        let scale = if scale.is_finite() && scale > 0.0 {
            scale
        } else {
            0.0
        };
        let mut f = NearSquares {
            lo,
            scale,
            marked: vec![0; Self::SIDE * Self::SIDE / 64],
        };
        for (c, r) in squares {
            let (x0, y0) = f.cell([c[0] - r, c[1] - r]);
            let (x1, y1) = f.cell([c[0] + r, c[1] + r]);
            for y in y0.saturating_sub(1)..=(y1 + 1).min(Self::SIDE - 1) {
                for x in x0.saturating_sub(1)..=(x1 + 1).min(Self::SIDE - 1) {
                    let i = y * Self::SIDE + x;
                    f.marked[i / 64] |= 1 << (i % 64);
                }
            }
        }
        f
    }

    /// The cell of `p`, clamped to the grid.
    fn cell(&self, p: [f64; 2]) -> (usize, usize) {
        let at = |k: usize| {
            let x = (p[k] - self.lo[k]) * self.scale;
            // NaN and negatives go to 0, beyond the grid to its last cell.
            (x.max(0.0) as usize).min(Self::SIDE - 1)
        };
        (at(0), at(1))
    }

    /// Whether `p` may lie in one of the squares (certainly not when `false`).
    fn may_hold(&self, p: [f64; 2]) -> bool {
        let (x, y) = self.cell(p);
        let i = y * Self::SIDE + x;
        self.marked[i / 64] >> (i % 64) & 1 != 0
    }
}

/// Size classes of [`size_class`]: twice the 11-bit binary exponent, plus one.
const SIZE_CLASSES: usize = 4096;

/// Queued triangles (each with its vertices, to tell whether it is still the same triangle
/// when popped) by size class, smallest class first, first in first out within a class: a
/// bucket per class and a bit per non-empty bucket, so that pushing and popping take constant
/// time (a binary heap keyed by class and arrival gives the same order at O(log n) a step,
/// 11% of a ~1M-triangle `-q33` run).
#[derive(Default)]
struct ClassQueue {
    buckets: Vec<VecDeque<(TriId, [u32; 3])>>,
    /// Bit `c % 64` of word `c / 64` is set when bucket `c` is not empty.
    nonempty: Vec<u64>,
    len: usize,
}

impl ClassQueue {
    fn push(&mut self, class: u32, item: (TriId, [u32; 3])) {
        let c = (class as usize).min(SIZE_CLASSES - 1);
        if self.buckets.is_empty() {
            self.buckets.resize_with(SIZE_CLASSES, VecDeque::new);
            self.nonempty = vec![0; SIZE_CLASSES / 64];
        }
        self.buckets[c].push_back(item);
        self.nonempty[c / 64] |= 1 << (c % 64);
        self.len += 1;
    }

    fn pop(&mut self) -> Option<(TriId, [u32; 3])> {
        let w = self.nonempty.iter().position(|&w| w != 0)?;
        let c = 64 * w + self.nonempty[w].trailing_zeros() as usize;
        let item = self.buckets[c].pop_front();
        if self.buckets[c].is_empty() {
            self.nonempty[w] &= !(1 << (c % 64));
        }
        self.len -= 1;
        item
    }

    fn len(&self) -> usize {
        self.len
    }
}

/// Which segments may receive Steiner points (Triangle's `-Y` and `-YY`).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum SegmentSteiner {
    /// Any segment may be split (conforming Delaunay output).
    Anywhere,
    /// Segments with the domain on one side only are never split (`-Y`).
    NotOnBoundary,
    /// No segment is ever split (`-YY`).
    Nowhere,
}

/// Refinement state: the triangulation plus the criteria and the queue of bad triangles.
pub(super) struct Refiner<'a> {
    /// The triangulation.
    pub cdt: Cdt,
    /// `false` once the Steiner cap stopped refinement early.
    pub complete: bool,
    pslg: &'a Pslg,
    opts: &'a Options,
    n_input: usize,
    /// Input vertices where two segments meet at less than 90 degrees (`is_sharp_corner`):
    /// segments are split at powers of two from them (Ruppert's concentric shells), so
    /// neighbouring segments split alike.
    apex: Vec<bool>,
    /// Crossing points (from `split_crossings`) and input points lying inside each input
    /// segment: like shared endpoints, they are corners that segments radiate from.
    inner_corners: std::collections::HashMap<u32, Vec<u32>>,
    /// The crossing points among `inner_corners` (all of them apexes).
    crossing: std::collections::HashSet<u32>,
    /// The ends of the hull edge (`-c`) each split point of a hull segment lies on: the
    /// small-angle exemption treats hull edges as the segments they are.
    hull_ends: std::collections::HashMap<u32, [u32; 2]>,
    sin2_min: f64,
    off_k: Option<f64>,
    max_area: f64,
    region_area: Vec<f64>,
    /// Skinny triangles, shortest edge first (as Triangle 1.6 does): keyed by the size class
    /// of the shortest edge, then by arrival. Splitting the smallest first lets the fine
    /// vertices near sharp corners and narrow gaps settle before the coarse triangles around
    /// them are split, so these grade outward instead of being split at the fine size too
    /// (smallest angle first made 2.3x Triangle's count on a slot of aspect 1:200 at 33°).
    queue: ClassQueue,
    /// Triangles that are bad only by size, first in first out (cheap, cache-friendly); the
    /// skinny queue goes first, so quality cascades settle before the mesh grows further.
    size_queue: VecDeque<(TriId, [u32; 3])>,
    refining: bool,
    /// Which segments may be split.
    pub policy: SegmentSteiner,
    /// Segments waiting for recovery or an encroachment check (`settle`).
    settle_work: Vec<SegId>,
    /// Whether encroached segments are split: not before carving, so that no split point
    /// ever sees the exterior (set by `fix_segments`).
    conforming: bool,
}

impl<'a> Refiner<'a> {
    pub fn new(cdt: Cdt, pslg: &'a Pslg, opts: &'a Options) -> Refiner<'a> {
        let n = pslg.points.len();
        let sin2_min = opts.min_angle.map_or(0.0, |a| a.to_radians().sin().powi(2));
        let off_k = match opts.min_angle {
            Some(a) if opts.off_centers => Some(0.475 / (0.5 * a.to_radians()).tan()),
            _ => None,
        };
        let region_area = pslg
            .regions
            .iter()
            .map(|r| match r.max_area {
                Some(a) if opts.region_max_area && a > 0.0 => a,
                _ => f64::INFINITY,
            })
            .collect();
        Refiner {
            cdt,
            complete: true,
            pslg,
            opts,
            n_input: n,
            apex: vec![false; n],
            inner_corners: std::collections::HashMap::new(),
            crossing: std::collections::HashSet::new(),
            hull_ends: std::collections::HashMap::new(),
            sin2_min,
            off_k,
            max_area: opts.max_area.unwrap_or(f64::INFINITY),
            region_area,
            queue: ClassQueue::default(),
            size_queue: VecDeque::new(),
            refining: false,
            policy: SegmentSteiner::Anywhere,
            settle_work: Vec::new(),
            conforming: false,
        }
    }

    /// Adds the input segment pieces and makes each an edge: present ones become walls,
    /// missing ones are inserted as constrained edges (no Steiner point). Splitting for
    /// conformity comes later, once the exterior is carved away (`sweep_encroached`).
    pub fn register_segments(&mut self, pieces: &[Piece]) -> Result<(), Error> {
        // An input point inside a segment ends two pieces of it, so a segment ending there
        // is seen with both.
        self.mark_sharp_corners(pieces.iter().map(|pc| (pc.a, pc.b)));
        for pc in pieces {
            let whole = self.pslg.segments[pc.input as usize];
            for v in [pc.a, pc.b] {
                // Crossing points, and input points inside the segment (where another segment
                // may end at a small angle: a T-junction), are corners of this segment for
                // the small-angle exemption.
                if v as usize > self.n_input {
                    self.crossing.insert(v);
                } else if whole.contains(&v) {
                    continue;
                }
                let list = self.inner_corners.entry(pc.input).or_default();
                if !list.contains(&v) {
                    list.push(v);
                }
            }
            let marker = segment_marker(self.pslg, pc.input as usize);
            self.cdt.segs.push(Seg {
                a: pc.a,
                b: pc.b,
                input: pc.input,
                marker,
                fixed: false,
            });
            self.cdt.seg_queued.push(false);
        }
        for s in 0..self.cdt.segs.len() as SegId {
            self.settle(s)?;
        }
        Ok(())
    }

    /// Marks as apexes the input vertices where two of the segments `segs` meet sharply
    /// ([`Self::is_sharp_corner`]). Only the vertices that end a segment are visited: a
    /// million scattered points have a few dozen hull segments, and a table of end lists for
    /// every vertex took longer to allocate than the check itself.
    fn mark_sharp_corners(&mut self, segs: impl Iterator<Item = (u32, u32)>) {
        let mut ends: Vec<(u32, u32)> = segs
            .flat_map(|(a, b)| [(a, b), (b, a)])
            .filter(|&(v, _)| (v as usize) < self.n_input)
            .collect();
        ends.sort_unstable_by_key(|e| e.0);
        let mut list = Vec::new();
        for group in ends.chunk_by(|x, y| x.0 == y.0) {
            let v = group[0].0;
            list.clear();
            list.extend(group.iter().map(|e| e.1));
            if !self.apex[v as usize] && self.is_sharp_corner(v, &list) {
                self.apex[v as usize] = true;
            }
        }
    }

    /// Whether two of the segments from input point `v` to the points `ends` meet at less than
    /// 90 degrees (decided exactly): only there can splitting one segment encroach the other
    /// at the corner over and over, so only there are segments split on concentric shells;
    /// at wider corners Ruppert's midpoints terminate and grade better. Points with many
    /// segments count as sharp without the pairwise check.
    fn is_sharp_corner(&self, v: u32, ends: &[u32]) -> bool {
        if ends.len() < 2 {
            return false;
        }
        if ends.len() > 8 {
            return true;
        }
        let pts = &self.cdt.pts;
        let pv = pts[v as usize];
        ends.iter().enumerate().any(|(i, &b)| {
            ends[i + 1..].iter().any(|&c| {
                b != c && crate::exact::dot_sign_2d(pts[b as usize], pts[c as usize], pv) > 0
            })
        })
    }

    /// Marks the segments no Steiner point may split, once carving has told boundary from
    /// interior: with `-Y` those with a triangle on one side only, with `-YY` all of them.
    /// From here on, encroached segments are split.
    pub fn fix_segments(&mut self) {
        self.conforming = true;
        // Hull segments (`-c`) exist from here on: a sharp angle between one and an input
        // segment needs the shells as much as one between two input segments.
        let segs = std::mem::take(&mut self.cdt.segs);
        self.mark_sharp_corners(segs.iter().filter(|s| s.a != NONE).map(|s| (s.a, s.b)));
        self.cdt.segs = segs;
        for s in 0..self.cdt.segs.len() {
            let Seg { a, b, .. } = self.cdt.segs[s];
            if a == NONE {
                continue;
            }
            let fixed = match self.policy {
                SegmentSteiner::Anywhere => false,
                SegmentSteiner::Nowhere => true,
                SegmentSteiner::NotOnBoundary => self
                    .cdt
                    .find_edge(a, b)
                    .is_some_and(|h| self.cdt.twin(h) == NONE),
            };
            self.cdt.segs[s].fixed = fixed;
        }
    }

    /// Makes segment `s` an edge again if it is missing (constrained insertion, splitting it
    /// at any vertex lying on it), then queues it for splitting when a vertex of an adjacent
    /// triangle encroaches it (by Lemma 3.1 the only place to look in a Delaunay mesh; the
    /// sweep finds the rest). Pieces made along the way are settled the same way.
    pub fn settle(&mut self, s: SegId) -> Result<(), Error> {
        let mut work = std::mem::take(&mut self.settle_work);
        work.clear();
        work.push(s);
        let mut budget = 4 * self.cdt.pts.len() + 64;
        let mut result = Ok(());
        while let Some(s) = work.pop() {
            budget -= 1;
            if budget == 0 {
                result = Err(Error::Internal(
                    "segment recovery did not settle within its budget".into(),
                ));
                break;
            }
            let Seg { a, b, fixed, .. } = self.cdt.segs[s as usize];
            if a == NONE {
                continue;
            }
            if let Some(h) = self.cdt.find_edge(a, b) {
                // Another subsegment already on this edge: two input segments run within
                // rounding of each other here (a vertex of one became a vertex of the other)
                // and share the edge. One subsegment per edge: otherwise splitting one would
                // leave the other's edge missing. The input segment's piece is kept over a
                // hull edge's.
                let t = self.cdt.seg_at(h);
                if t != NONE && t != s {
                    let other = self.cdt.segs[t as usize];
                    if other.a != NONE && (other.a == b || other.b == b) {
                        let keep_s = other.input == NONE && self.cdt.segs[s as usize].input != NONE;
                        let retire = if keep_s { t } else { s };
                        self.cdt.segs[retire as usize].a = NONE;
                        if keep_s {
                            self.cdt.set_seg(h, s);
                        } else {
                            continue;
                        }
                    }
                }
            }
            let h = match self.cdt.insert_segment(s) {
                Recovery::Edge(h) => {
                    self.queue_new_triangles();
                    h
                }
                Recovery::Through(v) => {
                    let s2 = self.split_at_vertex(s, v);
                    work.push(s);
                    work.push(s2);
                    continue;
                }
                Recovery::Blocked(_) | Recovery::Failed => {
                    if self.policy != SegmentSteiner::Anywhere {
                        let (pa, pb) = (self.cdt.pts[a as usize], self.cdt.pts[b as usize]);
                        result = Err(Error::Internal(format!(
                            "segment ({pa:?}, {pb:?}) cannot be recovered without Steiner \
                             points"
                        )));
                        break;
                    }
                    // Fall back to recovery by splitting (paper Fig. 2, step 7).
                    self.cdt.queue_split(s);
                    continue;
                }
            };
            if fixed || !self.conforming {
                continue;
            }
            let (pa, pb) = (self.cdt.pts[a as usize], self.cdt.pts[b as usize]);
            for e in [h, self.cdt.twin(h)] {
                if e == NONE {
                    continue;
                }
                let c = self.cdt.apex(e);
                if c != self.cdt.ghost && encroaches(pa, pb, self.cdt.pts[c as usize]) {
                    self.cdt.queue_split(s);
                    break;
                }
            }
        }
        self.settle_work = work;
        result
    }

    /// Whether vertex `c`, which encroaches segment `s` (so it projects strictly inside it),
    /// lies within four units in the last place of the coordinates from its line: then no
    /// split point could separate it from the segment, and it becomes a vertex of it. That
    /// includes a split point of another input segment running along this one within
    /// rounding (the two then share the subsegments there) and the crossing point of two
    /// segments that a third one passes through up to rounding. The output checks allow
    /// vertices of a slanted segment this far off its line (split points are rounded too).
    fn within_rounding_of(&self, s: SegId, c: VertexId) -> bool {
        let Seg { a, b, .. } = self.cdt.segs[s as usize];
        let (pa, pb, pc) = (
            self.cdt.pts[a as usize],
            self.cdt.pts[b as usize],
            self.cdt.pts[c as usize],
        );
        let mag = [pa[0], pa[1], pb[0], pb[1], pc[0], pc[1]]
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let o = orient2d(pa, pb, pc).abs();
        o <= 4.0 * f64::EPSILON * mag * dist2(pa, pb).sqrt()
    }

    /// Splits segment `s` at the existing vertex `v` (lying on it, exactly or up to rounding):
    /// `s` keeps the first half, the returned new segment is the second. The halves are not
    /// recovered here.
    fn split_at_vertex(&mut self, s: SegId, v: VertexId) -> SegId {
        let seg = self.cdt.segs[s as usize];
        if let Some(h) = self.cdt.find_edge(seg.a, seg.b) {
            if self.cdt.seg_at(h) == s {
                // `v` lies beside the edge (within rounding): without its wall the edge and
                // the ones behind it may no longer be locally Delaunay.
                self.cdt.set_seg(h, NONE);
                self.cdt.legalize(h);
                self.queue_new_triangles();
            }
        }
        if (v as usize) > self.n_input
            && self.cdt.vseg[v as usize] == NONE
            && !self.crossing.contains(&v)
        {
            self.cdt.vseg[v as usize] = seg.input;
            self.note_hull_point(s, v);
        }
        self.cdt.segs[s as usize].b = v;
        let s2 = self.cdt.segs.len() as SegId;
        self.cdt.segs.push(Seg { a: v, ..seg });
        self.cdt.seg_queued.push(false);
        s2
    }

    /// Records the hull edge (`-c`) that vertex `v`, a split point of segment `s`, lies on when
    /// `s` is a hull segment: the ends of that edge, known from an end of `s` (an input
    /// point, or an earlier split point of the same edge).
    fn note_hull_point(&mut self, s: SegId, v: VertexId) {
        let seg = self.cdt.segs[s as usize];
        if seg.input != NONE || (v as usize) <= self.n_input || self.crossing.contains(&v) {
            return;
        }
        let ends = if (seg.a as usize) > self.n_input {
            self.hull_ends.get(&seg.a).copied()
        } else if (seg.b as usize) > self.n_input {
            self.hull_ends.get(&seg.b).copied()
        } else {
            Some([seg.a, seg.b])
        };
        if let Some(e) = ends {
            self.hull_ends.insert(v, e);
        }
    }

    /// Queues every subsegment that some vertex (used by the domain, or an input point)
    /// encroaches; returns how many. A k-d tree over the vertices keeps it near-linear.
    /// Fails only when the run is cancelled (it reports progress: on a 1M-triangle mesh a
    /// sweep takes a noticeable part of a second).
    pub fn sweep_encroached(&mut self) -> Result<usize, Error> {
        let refining = self.will_refine();
        let steiner = self.steiner();
        let cdt = &self.cdt;
        let live = |s: &Seg| s.a != NONE && !s.fixed && (refining || s.input != NONE);
        if !cdt.segs.iter().any(live) {
            return Ok(0);
        }
        // The subsegments to check, each with the square its diametral circle lies in. The
        // float radius only picks candidates; it is padded, the test itself is exact.
        let mut disks: Vec<(usize, [f64; 2], f64)> = Vec::new();
        for (s, seg) in cdt.segs.iter().enumerate() {
            tick(|| (steiner, 0))?;
            // Retired segments are gone; hull edges only bound the domain when refining.
            if cdt.seg_queued[s] || !live(seg) {
                continue;
            }
            let (pa, pb) = (cdt.pts[seg.a as usize], cdt.pts[seg.b as usize]);
            let c = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
            let r = 0.5 * dist2(pa, pb).sqrt() * (1.0 + 1e-9) + 1e-300;
            disks.push((s, c, r));
        }
        let near = NearSquares::new(disks.iter().map(|&(_, c, r)| (c, r)));
        // Only vertices in a cell near some square can encroach: on a refined mesh the
        // subsegments' circles cover a thin band along the segments, and the tree over that
        // band costs a fraction of one over every vertex.
        let mut used: Vec<u32> = Vec::new();
        for v in 0..cdt.pts.len() as u32 {
            tick(|| (steiner, 0))?;
            if v != cdt.ghost
                && ((v as usize) < self.n_input || cdt.vtri[v as usize] != NONE)
                && near.may_hold(cdt.pts[v as usize])
            {
                used.push(v);
            }
        }
        if used.is_empty() {
            return Ok(0);
        }
        let tree = PointTree::new(&cdt.pts, &used)?;
        let mut hits = Vec::new();
        for &(s, c, r) in &disks {
            tick(|| (steiner, 0))?;
            let seg = &cdt.segs[s];
            let (pa, pb) = (cdt.pts[seg.a as usize], cdt.pts[seg.b as usize]);
            let clear = tree.for_each_near(c, r, |v| {
                v == seg.a || v == seg.b || !encroaches(pa, pb, cdt.pts[v as usize])
            });
            if !clear {
                hits.push(s as SegId);
            }
        }
        for &s in &hits {
            self.cdt.queue_split(s);
        }
        Ok(hits.len())
    }

    /// Splits queued segments until none is left (the recursion of Fig. 2 step 8).
    ///
    /// Splits for conformity count against the Steiner budget like any other point (two
    /// nearly touching features need as many points as their length over their gap): once
    /// it is spent, a segment that is an edge is left encroached and the run is incomplete
    /// (the mesh stays constrained Delaunay); a segment that is missing from the mesh is
    /// still split, as the mesh needs it, under a work budget of its own.
    pub fn drain_splits(&mut self) -> Result<(), Error> {
        let mut recovery_budget = 4 * self.cdt.segs.len() + 1024;
        while let Some(s) = self.cdt.split_queue.pop() {
            tick(|| (self.steiner(), 0))?;
            self.cdt.seg_queued[s as usize] = false;
            if self.budget_spent() {
                let Seg { a, b, .. } = self.cdt.segs[s as usize];
                if a == NONE || self.cdt.find_edge(a, b).is_some() {
                    self.complete = false;
                    continue;
                }
                recovery_budget -= 1;
                if recovery_budget == 0 {
                    return Err(Error::Internal(
                        "segment recovery did not finish within its work budget".into(),
                    ));
                }
            }
            self.split_segment(s)?;
        }
        Ok(())
    }

    /// Whether the Steiner budget ([`Options::max_steiner`], and the vertex-index cap) is
    /// spent.
    pub fn budget_spent(&self) -> bool {
        let cap = self.opts.max_steiner.unwrap_or(u64::MAX);
        self.steiner() >= cap || self.cdt.pts.len() >= (NONE / 2) as usize
    }

    /// Where to split subsegment `ab`: the midpoint, or, when exactly one end is an apex, the
    /// point at the power-of-two distance from it nearest to half the length.
    fn split_point(&self, a: u32, b: u32) -> [f64; 2] {
        let pa = self.cdt.pts[a as usize];
        let pb = self.cdt.pts[b as usize];
        // Input vertices shared by segments are apexes; so are crossing points inserted by
        // `split_crossings`: the only Steiner segment endpoints lying on no single segment.
        // Split points of convex-hull segments (`-c`) lie on no input segment either, but
        // they are no corners: taking them for apexes would split a hull segment at
        // midpoints, never on the shells of its apex, and at a sharp angle between the hull
        // and an input segment the two would split each other down to rounding.
        let apex = |v: u32| {
            if (v as usize) < self.n_input {
                self.apex[v as usize]
            } else {
                self.crossing.contains(&v)
            }
        };
        let (from, to) = match (apex(a), apex(b)) {
            (true, false) => (pa, pb),
            (false, true) => (pb, pa),
            _ => return [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])],
        };
        let len = dist2(from, to).sqrt();
        let d = (0.5 * len).log2().round().exp2();
        let t = (d / len).clamp(0.25, 0.75);
        [
            from[0] + (to[0] - from[0]) * t,
            from[1] + (to[1] - from[1]) * t,
        ]
    }

    /// A float point near `m` (the rounded split point of the edge on half-edge `h`) that
    /// splits the edge, when `m` itself fell outside the edge's two triangles (past a
    /// neighbour thinner than its rounding, typically a piece of the same input segment bent
    /// by an ulp). With `side` `None`, the point sees every outer edge of the two triangles
    /// strictly and lies on the edge's line or on the side of a triangle where the other side
    /// has none. With `side` `Some(e)`, it lies strictly inside the triangle of half-edge
    /// `e` only (the other one being too thin): inserted from there, the edge stays as a wall
    /// and the segment bends through the point by rounding, as split points on slanted
    /// segments do. Either way it projects strictly inside the edge. Every test is exact.
    /// Candidates fix one coordinate at `m`'s or a few units in the last place beside it,
    /// take the other from the edge's line and step it by a few units in the last place; the
    /// one nearest the line wins. `None` when no candidate qualifies.
    fn split_point_inside(&self, h: u32, m: [f64; 2], side: Option<u32>) -> Option<[f64; 2]> {
        let cdt = &self.cdt;
        let (a, b) = cdt.edge_ends(h);
        let (pa, pb) = (cdt.pts[a as usize], cdt.pts[b as usize]);
        // Edges to be seen strictly, and edges to be seen or lain on.
        let mut strict: Vec<([f64; 2], [f64; 2])> = Vec::new();
        let mut weak: Vec<([f64; 2], [f64; 2])> = Vec::new();
        let real = |e: u32| e != NONE && cdt.apex(e) != cdt.ghost;
        for (e, other) in [(h, cdt.twin(h)), (cdt.twin(h), h)] {
            if !real(e) || side.is_some_and(|f| f != e) {
                continue;
            }
            let (u, w) = cdt.edge_ends(e);
            let c = cdt.apex(e);
            let (pu, pw, pc) = (
                cdt.pts[u as usize],
                cdt.pts[w as usize],
                cdt.pts[c as usize],
            );
            strict.push((pw, pc));
            strict.push((pc, pu));
            if side.is_some() {
                strict.push((pu, pw));
            } else if !real(other) {
                weak.push((pu, pw));
            }
        }
        if strict.is_empty() {
            return None;
        }
        let ok = |q: [f64; 2]| {
            q != pa
                && q != pb
                && encroaches(pa, pb, q)
                && strict.iter().all(|&(u, w)| orient2d(u, w, q) > 0.0)
                && weak.iter().all(|&(u, w)| orient2d(u, w, q) >= 0.0)
        };
        let mut best: Option<(f64, [f64; 2])> = None;
        for k in 0..2 {
            let o = 1 - k;
            if pb[k] == pa[k] {
                continue;
            }
            for i in -2i64..=2 {
                let x = ulp_step(m[k], i);
                let y0 = pa[o] + (x - pa[k]) * ((pb[o] - pa[o]) / (pb[k] - pa[k]));
                for j in -4i64..=4 {
                    let mut q = [0.0; 2];
                    q[k] = x;
                    q[o] = ulp_step(y0, j);
                    if !ok(q) {
                        continue;
                    }
                    let off = orient2d(pa, pb, q).abs();
                    if best.map_or(true, |(d, _)| off < d) {
                        best = Some((off, q));
                    }
                }
            }
        }
        best.map(|(_, q)| q)
    }

    /// Inserts a split point of segment `s` (its edge on half-edge `h`) near `m`, whose
    /// insertion was refused: inside both triangles of the edge if a float point there can
    /// be found, else inside one of them with the edge kept as a wall for now
    /// (`split_at_vertex` then retires it). `None` when neither works.
    fn split_nearby(&mut self, s: SegId, h: u32, m: [f64; 2]) -> Option<Inserted> {
        let input = self.cdt.segs[s as usize].input;
        let fine = |r: Inserted| !matches!(r, Inserted::OnSegment(_) | Inserted::LostWalk);
        if let Some(q) = self.split_point_inside(h, m, None) {
            let r = self
                .cdt
                .insert(q, Start::SplitEdge(h), Mode::Force, input, None);
            if fine(r) {
                return Some(r);
            }
        }
        for e in [h, self.cdt.twin(h)] {
            if e == NONE {
                continue;
            }
            let Some(q) = self.split_point_inside(h, m, Some(e)) else {
                continue;
            };
            // The point encroaches `s` itself, which it is about to split: not a reason to
            // queue it again.
            let queued = self.cdt.seg_queued[s as usize];
            self.cdt.seg_queued[s as usize] = true;
            let r = self
                .cdt
                .insert(q, Start::Walk(e / 3), Mode::Force, input, None);
            self.cdt.seg_queued[s as usize] = queued;
            if fine(r) {
                return Some(r);
            }
        }
        // The edge's triangles can be slivers of this segment's own chain, thinner than an
        // ulp: its split points rounded outward, a fan of them seen from one far chain vertex
        // (2D campaign, issue 14: a point 2e-9 from a star's reflex corner; seed 11 run 2045).
        // No float point lies inside them; the split point goes a few ulps into the domain
        // instead, where its cavity takes the whole fan and every new triangle is
        // counter-clockwise (the segment bends inward by that much, as by rounding).
        let (pa, pb) = (
            self.cdt.pts[self.cdt.segs[s as usize].a as usize],
            self.cdt.pts[self.cdt.segs[s as usize].b as usize],
        );
        for e in [h, self.cdt.twin(h)] {
            if e == NONE || self.cdt.apex(e) == self.cdt.ghost {
                continue;
            }
            let (u, w) = self.cdt.edge_ends(e);
            let (pu, pw) = (self.cdt.pts[u as usize], self.cdt.pts[w as usize]);
            // The triangle of `e` lies to its left: step along the left normal's signs.
            let sgn = |x: f64| (x > 0.0) as i64 - (x < 0.0) as i64;
            let sign = [-sgn(pw[1] - pu[1]), sgn(pw[0] - pu[0])];
            for steps in [1i64, 2, 4, 8, 16, 32, 64] {
                for axes in [[true, false], [false, true], [true, true]] {
                    let mut q = m;
                    for k in 0..2 {
                        if axes[k] {
                            q[k] = ulp_step(m[k], steps * sign[k]);
                        }
                    }
                    if q == m || orient2d(pu, pw, q) <= 0.0 || !encroaches(pa, pb, q) {
                        continue;
                    }
                    let r = self
                        .cdt
                        .insert(q, Start::SplitEdge(h), Mode::Force, input, None);
                    if fine(r) {
                        return Some(r);
                    }
                }
            }
        }
        None
    }

    fn split_segment(&mut self, s: SegId) -> Result<(), Error> {
        let Seg {
            a, b, input, fixed, ..
        } = self.cdt.segs[s as usize];
        if a == NONE || fixed {
            return Ok(());
        }
        let (pa, pb) = (self.cdt.pts[a as usize], self.cdt.pts[b as usize]);
        if let Some(h) = self.cdt.find_edge(a, b) {
            for e in [h, self.cdt.twin(h)] {
                if e == NONE {
                    continue;
                }
                let c = self.cdt.apex(e);
                if c != self.cdt.ghost
                    && encroaches(pa, pb, self.cdt.pts[c as usize])
                    && self.within_rounding_of(s, c)
                {
                    // No split point could separate `c` from the segment in floating point:
                    // `c` is on it, up to rounding (as split points on slanted segments are).
                    // On the domain's boundary the sliver between `c` and the segment leaves
                    // the domain (by a few ulps): a boundary edge stays a segment.
                    if self.cdt.twin(e) == NONE && !self.cdt.peel(e) {
                        // The sliver has a second boundary edge: `c` is within rounding of
                        // this segment and of the boundary at one of its ends, closer to
                        // the corner than floating point can separate.
                        if (c as usize) < self.n_input && input != NONE {
                            return Err(InputError::VertexOnSegment {
                                vertex: c as usize,
                                segment: input as usize,
                            }
                            .into());
                        }
                        // A split point of another segment: the two segments run within
                        // rounding of each other near that corner.
                        let other = self.cdt.vseg[c as usize];
                        if (c as usize) > self.n_input
                            && input != NONE
                            && other != NONE
                            && other != input
                        {
                            return Err(InputError::CrossingSegments {
                                first: input.min(other) as usize,
                                second: input.max(other) as usize,
                            }
                            .into());
                        }
                        return Err(Error::Internal(format!(
                            "vertex {c} lies within rounding of boundary segment ({pa:?}, \
                             {pb:?}) at a corner of the domain"
                        )));
                    }
                    let s2 = self.split_at_vertex(s, c);
                    self.settle(s)?;
                    return self.settle(s2);
                }
            }
        }
        let m = self.split_point(a, b);
        if m == pa || m == pb {
            return Err(Error::Internal(format!(
                "segment ({pa:?}, {pb:?}) is too short to split in double precision"
            )));
        }
        let start = match self.cdt.find_edge(a, b) {
            Some(h) => Start::SplitEdge(h),
            None => Start::Walk(self.cdt.vtri[a as usize]),
        };
        let mut got = self.cdt.insert(m, start, Mode::Force, input, None);
        if let (Inserted::OnSegment(_) | Inserted::LostWalk, Start::SplitEdge(h)) = (got, start) {
            got = self.split_nearby(s, h, m).unwrap_or(got);
        }
        let mv = match got {
            Inserted::Yes(v) => v,
            // The rounded split point is an existing vertex lying (within rounding) on the
            // segment: split there instead.
            Inserted::Duplicate(v) if v != a && v != b => {
                self.cdt.new_tris.clear();
                v
            }
            // The split point, on this segment up to rounding, lies exactly on another one:
            // the two run within rounding of each other there, closer than floating point
            // can separate.
            Inserted::OnSegment(t)
                if input != NONE
                    && self.cdt.segs[t as usize].input != NONE
                    && self.cdt.segs[t as usize].input != input =>
            {
                let other = self.cdt.segs[t as usize].input;
                return Err(InputError::CrossingSegments {
                    first: input.min(other) as usize,
                    second: input.max(other) as usize,
                }
                .into());
            }
            other => {
                return Err(Error::Internal(format!(
                    "splitting segment ({pa:?}, {pb:?}) at {m:?}: {other:?}"
                )))
            }
        };
        // Before the new triangles are judged: the small-angle exemption needs to know which
        // hull edge a split point lies on.
        self.note_hull_point(s, mv);
        self.queue_new_triangles();
        let s2 = self.split_at_vertex(s, mv);
        self.settle(s)?;
        self.settle(s2)
    }

    fn queue_new_triangles(&mut self) {
        if !self.refining {
            return;
        }
        for k in 0..self.cdt.new_tris.len() {
            let t = self.cdt.new_tris[k];
            self.push_if_bad(t);
        }
    }

    fn push_bad(&mut self, t: TriId) {
        let v = self.cdt.tv[t as usize];
        let [a, b, c] = v.map(|x| self.cdt.pts[x as usize]);
        self.push_judged(t, v, [a, b, c], min_angle_sin2(a, b, c));
    }

    /// Queues triangle `t` (vertices `v`, corners `p`, squared sine of its smallest angle
    /// `s2`): skinny ones by the size class of their shortest edge, the others by arrival.
    fn push_judged(&mut self, t: TriId, v: [u32; 3], p: [[f64; 2]; 3], s2: f64) {
        let [a, b, c] = p;
        if s2.max(0.0) < self.sin2_min {
            let short = dist2(a, b).min(dist2(b, c)).min(dist2(c, a));
            self.queue.push(size_class(short), (t, v));
        } else {
            self.size_queue.push_back((t, v));
        }
    }

    /// Queues triangle `t` if it must be split (too large, or skinny and not exempt).
    fn push_if_bad(&mut self, t: TriId) {
        let reg = self.cdt.aux[t as usize].reg;
        if reg == EXTERIOR || reg == HOLE || self.cdt.is_ghost(t) {
            return;
        }
        let v = self.cdt.tv[t as usize];
        let p = v.map(|x| self.cdt.pts[x as usize]);
        let s2 = min_angle_sin2(p[0], p[1], p[2]);
        if self.too_large(reg, p) || (self.sin2_min > 0.0 && s2 < self.sin2_min && !self.exempt(t))
        {
            self.push_judged(t, v, p, s2);
        }
    }

    /// Whether the triangle with corners `p` in region `reg` exceeds an area bound or the
    /// user's sizing test.
    fn too_large(&self, reg: u32, p: [[f64; 2]; 3]) -> bool {
        let [pa, pb, pc] = p;
        let area = 0.5 * area2(pa, pb, pc);
        let bound = if reg == NO_REGION {
            self.max_area
        } else {
            self.max_area.min(self.region_area[reg as usize])
        };
        area > bound
            || self
                .opts
                .sizing
                .as_ref()
                .is_some_and(|f| f(pa, pb, pc, area))
    }

    fn pop_bad(&mut self) -> Option<(TriId, [u32; 3])> {
        if let Some(x) = self.size_queue.pop_front() {
            return Some(x);
        }
        self.queue.pop()
    }

    /// Small input angles (paper §6 "grooming"): a skinny triangle is left alone when its
    /// smallest angle lies between two segments and its shortest edge has a split point at
    /// one end at least (the isosceles triangles that concentric shells make at a sharp input
    /// corner; a triangle spanning the whole corner still gets split), or when its shortest
    /// edge joins two points on
    /// different segments sharing an endpoint, at equal distance from it (Miller, Pav and
    /// Walkington), since splitting those would only cascade toward the corner.
    fn exempt(&self, t: TriId) -> bool {
        let v = self.cdt.tv[t as usize];
        let p = v.map(|x| self.cdt.pts[x as usize]);
        // k: the vertex opposite the shortest edge (the smallest angle).
        let l = [dist2(p[1], p[2]), dist2(p[2], p[0]), dist2(p[0], p[1])];
        let k = if l[0] <= l[1] && l[0] <= l[2] {
            0
        } else if l[1] <= l[2] {
            1
        } else {
            2
        };
        let ts = self.cdt.aux[t as usize].s;
        let (x, y) = (v[(k + 1) % 3], v[(k + 2) % 3]);
        // The edges at vertex k are edges k+1 and k+2. A triangle spanning the corner between
        // two whole input segments is split all the same: the shells have not reached it.
        let steiner = |u: u32| u as usize > self.n_input;
        if ts[(k + 1) % 3] != NONE && ts[(k + 2) % 3] != NONE && (steiner(x) || steiner(y)) {
            return true;
        }
        // The corners of the segment (input or hull edge) split point `u` lies on.
        let corners = |u: u32| -> Option<Vec<u32>> {
            let s = self.cdt.vseg[u as usize];
            if s != NONE {
                let e = self.pslg.segments[s as usize];
                let extra = self.inner_corners.get(&s).map_or(&[][..], |v| &v[..]);
                return Some(e.into_iter().chain(extra.iter().copied()).collect());
            }
            self.hull_ends.get(&u).map(|e| e.to_vec())
        };
        let (Some(cx), Some(cy)) = (corners(x), corners(y)) else {
            return false;
        };
        let (sx, sy) = (self.cdt.vseg[x as usize], self.cdt.vseg[y as usize]);
        if (sx != NONE && sx == sy) || (sx == NONE && sy == NONE && cx == cy) {
            return false;
        }
        for &c in &cx {
            if cy.contains(&c) {
                let pc = self.cdt.pts[c as usize];
                let d1 = dist2(pc, p[(k + 1) % 3]).sqrt();
                let d2 = dist2(pc, p[(k + 2) % 3]).sqrt();
                if d1 < 1.001 * d2 && d2 < 1.001 * d1 {
                    return true;
                }
            }
        }
        false
    }

    /// Steiner points so far (the progress reports' `done`).
    fn steiner(&self) -> u64 {
        self.cdt.pts.len().saturating_sub(self.n_input + 1) as u64
    }

    /// Whether any refinement criterion is set.
    pub fn will_refine(&self) -> bool {
        let o = self.opts;
        o.min_angle.is_some()
            || o.max_area.is_some()
            || o.sizing.is_some()
            || (o.region_max_area && self.region_area.iter().any(|a| a.is_finite()))
    }

    /// Eliminates bad triangles (paper Fig. 4): insert each one's circumcenter (or off-center)
    /// provisionally; if it encroaches a segment, split that segment instead (Force) and keep
    /// the triangle queued. If it encroaches only fixed segments (`-Y`), or lies beyond one,
    /// the point is rejected and the triangle dropped from the queue, as Triangle does: such
    /// triangles keep their bad angle or size. Returns whether any vertex was added.
    pub fn refine(&mut self) -> Result<bool, Error> {
        let o = self.opts;
        if !self.will_refine() {
            return Ok(false);
        }
        stage(Stage::Refining, || (self.steiner(), 0))?;
        let before = self.cdt.pts.len();
        self.refining = true;
        for t in 0..self.cdt.num_slots() as TriId {
            tick(|| (self.steiner(), self.steiner()))?;
            if self.cdt.alive(t) {
                self.push_if_bad(t);
            }
        }
        let base = self.n_input + 1;
        let mut last_report = 0usize;
        while let Some((t, vs)) = self.pop_bad() {
            tick(|| {
                let queued = (self.queue.len() + self.size_queue.len()) as u64;
                (self.steiner(), self.steiner() + queued)
            })?;
            if !self.cdt.alive(t) || self.cdt.tv[t as usize] != vs {
                continue;
            }
            let added = self.cdt.pts.len() - base;
            if self.budget_spent() {
                self.complete = false;
                break;
            }
            if o.verbose && added >= last_report + 1_000_000 {
                last_report = added;
                eprintln!(
                    "idmesh: {added} Steiner points, {} triangles queued",
                    self.queue.len()
                );
            }
            let [pa, pb, pc] = vs.map(|x| self.cdt.pts[x as usize]);
            let Some(c) = steiner_point(pa, pb, pc, self.off_k) else {
                continue;
            };
            match self
                .cdt
                .insert(c, Start::Walk(t), Mode::Provisional, NONE, None)
            {
                Inserted::Yes(_) => self.queue_new_triangles(),
                // Triangle's -Y: a point encroaching a fixed segment is rejected and the
                // triangle stays as it is.
                Inserted::Encroached(s) if self.cdt.segs[s as usize].fixed => {}
                Inserted::Encroached(s) => {
                    self.cdt.queue_split(s);
                    self.drain_splits()?;
                    if self.cdt.alive(t) && self.cdt.tv[t as usize] == vs {
                        self.push_bad(t);
                    }
                }
                // The point coincides with a vertex or sits on a segment only through rounding
                // of a nearly degenerate triangle; leave that triangle as it is.
                Inserted::Duplicate(_) | Inserted::OnSegment(_) => {}
                Inserted::LostWalk => {
                    return Err(Error::Internal(
                        "point location exceeded its step budget".into(),
                    ))
                }
            }
        }
        self.refining = false;
        Ok(self.cdt.pts.len() > before)
    }
}

/// `x` moved by `k` units in the last place (toward +∞ for `k > 0`): the neighbouring floats
/// [`Refiner::split_point_inside`] tries. Infinities and NaN stay as they are.
fn ulp_step(x: f64, k: i64) -> f64 {
    if !x.is_finite() {
        return x;
    }
    (0..k.unsigned_abs()).fold(x, |y, _| crate::geometry::next_float(y, k > 0))
}

#[cfg(test)]
mod queue_tests {
    use super::*;

    /// The bucket queue pops in the order of a min-heap keyed by (class, arrival), as the
    /// binary heap it replaced did, whatever the interleaving of pushes and pops.
    #[test]
    fn class_queue_pops_smallest_class_first_in_arrival_order() {
        let mut q = ClassQueue::default();
        let mut heap = std::collections::BinaryHeap::new();
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut arrival = 0u64;
        for step in 0..20_000u32 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            if state % 3 != 0 || q.len() == 0 {
                // Classes from the whole range, crowded at a few values.
                let class = if state % 5 == 0 {
                    (state >> 20) as u32 % SIZE_CLASSES as u32
                } else {
                    2040 + (state >> 20) as u32 % 8
                };
                arrival += 1;
                q.push(class, (step, [step, 0, 0]));
                heap.push(std::cmp::Reverse((class, arrival, step)));
            } else {
                let std::cmp::Reverse((_, _, want)) = heap.pop().unwrap();
                assert_eq!(q.pop().map(|x| x.0), Some(want));
            }
            assert_eq!(q.len(), heap.len());
        }
        while let Some(std::cmp::Reverse((_, _, want))) = heap.pop() {
            assert_eq!(q.pop().map(|x| x.0), Some(want));
        }
        assert_eq!(q.pop(), None);
    }

    /// The filter never drops a point of a square (it may keep others), at any scale and
    /// for degenerate sets of squares.
    #[test]
    fn near_squares_keep_every_point_of_every_square() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut unit = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for scale in [1e-300, 1e-9, 1.0, 3e7, 1e300] {
            let squares: Vec<([f64; 2], f64)> = (0..200)
                .map(|_| {
                    (
                        [unit() * scale, unit() * scale],
                        unit() * unit() * 0.01 * scale,
                    )
                })
                .collect();
            let f = NearSquares::new(squares.iter().copied());
            let mut kept = 0;
            for &(c, r) in &squares {
                // Corners, edges and inside of the closed square.
                for (u, v) in [
                    (-1.0, -1.0),
                    (1.0, 1.0),
                    (1.0, -1.0),
                    (0.3, 1.0),
                    (unit(), -unit()),
                ] {
                    let p = [c[0] + u * r, c[1] + v * r];
                    if (p[0] - c[0]).abs() <= r && (p[1] - c[1]).abs() <= r {
                        assert!(f.may_hold(p), "{p:?} in square {c:?} {r} at scale {scale}");
                    }
                }
            }
            // Far points are mostly dropped: the filter filters.
            for _ in 0..1000 {
                kept += f.may_hold([unit() * scale, unit() * scale]) as usize;
            }
            assert!(kept < 1000, "scale {scale}: every point kept");
        }
        // One square of size zero, and none at all.
        let f = NearSquares::new([([1.0, 2.0], 0.0)].into_iter());
        assert!(f.may_hold([1.0, 2.0]));
        let f = NearSquares::new(std::iter::empty());
        assert!(!f.may_hold([1.0, 2.0]), "no square holds anything");
    }
}
