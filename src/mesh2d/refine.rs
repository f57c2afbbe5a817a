//! Segment splitting (the paper's queue `P` of Force'd points, Fig. 2 steps 6–8) and the
//! elimination of skinny and oversized triangles (`rm-tri`, Fig. 4).

use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

use super::build::{segment_marker, Piece};
use super::grid::PointGrid;
use super::store::{Cdt, Inserted, Mode, Seg, SegId, Start, TriId, EXTERIOR, HOLE, NO_REGION};
use super::{Options, NONE};
use crate::error::Error;
use crate::geometry::{area2, dist2, min_angle_sin2, steiner_point};
use crate::input::Pslg;
use crate::predicates::encroaches;

/// Refinement state: the triangulation plus the criteria and the queue of bad triangles.
pub(super) struct Refiner<'a> {
    /// The triangulation.
    pub cdt: Cdt,
    /// `false` once the Steiner cap stopped refinement early.
    pub complete: bool,
    pslg: &'a Pslg,
    opts: &'a Options,
    n_input: usize,
    /// Input vertices shared by two or more segments: segments are split at powers of two from
    /// them (Ruppert's concentric shells), so neighbouring segments split alike.
    apex: Vec<bool>,
    /// Crossing points (from `split_crossings`) lying on each input segment: like shared
    /// endpoints, they are corners that segments radiate from.
    crossing_apexes: std::collections::HashMap<u32, Vec<u32>>,
    sin2_min: f64,
    off_k: Option<f64>,
    max_area: f64,
    region_area: Vec<f64>,
    /// Bad triangles, smallest angle first (as Triangle does): keyed by the bits of sin² of
    /// the smallest angle, which order like the non-negative floats they encode.
    queue: BinaryHeap<Reverse<(u64, TriId, [u32; 3])>>,
    /// Triangles that are bad only by size, first in first out (cheap, cache-friendly); the
    /// skinny queue goes first, so quality cascades settle before the mesh grows further.
    size_queue: VecDeque<(TriId, [u32; 3])>,
    refining: bool,
}

impl<'a> Refiner<'a> {
    pub fn new(cdt: Cdt, pslg: &'a Pslg, opts: &'a Options) -> Refiner<'a> {
        let n = pslg.points.len();
        let mut degree = vec![0u8; n];
        for s in &pslg.segments {
            for &v in s {
                degree[v as usize] = degree[v as usize].saturating_add(1);
            }
        }
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
            apex: degree.iter().map(|&d| d >= 2).collect(),
            crossing_apexes: std::collections::HashMap::new(),
            sin2_min,
            off_k,
            max_area: opts.max_area.unwrap_or(f64::INFINITY),
            region_area,
            queue: BinaryHeap::new(),
            size_queue: VecDeque::new(),
            refining: false,
        }
    }

    /// Adds the input segment pieces; present ones become walls, missing or encroached ones are
    /// queued for splitting (paper Fig. 2 step 7 for the input).
    pub fn register_segments(&mut self, pieces: &[Piece]) -> Result<(), Error> {
        for pc in pieces {
            for v in [pc.a, pc.b] {
                if v as usize > self.n_input {
                    let list = self.crossing_apexes.entry(pc.input).or_default();
                    if !list.contains(&v) {
                        list.push(v);
                    }
                }
            }
            let s = self.cdt.segs.len() as SegId;
            let marker = segment_marker(self.pslg, pc.input as usize);
            self.cdt.segs.push(Seg {
                a: pc.a,
                b: pc.b,
                input: pc.input,
                marker,
            });
            self.cdt.seg_queued.push(false);
            if let Some(h) = self.cdt.find_edge(pc.a, pc.b) {
                self.cdt.set_seg(h, s);
            }
        }
        for s in 0..self.cdt.segs.len() as SegId {
            self.check_encroached(s);
        }
        Ok(())
    }

    /// Queues segment `s` when it is missing from the mesh or a vertex of an adjacent triangle
    /// lies inside its diametral circle (by Lemma 3.1 that is the only place to look).
    pub fn check_encroached(&mut self, s: SegId) {
        let Seg { a, b, .. } = self.cdt.segs[s as usize];
        match self.cdt.find_edge(a, b) {
            None => self.cdt.queue_split(s),
            Some(h) => {
                if self.cdt.seg_at(h) != s {
                    self.cdt.set_seg(h, s);
                }
                let (pa, pb) = (self.cdt.pts[a as usize], self.cdt.pts[b as usize]);
                for e in [h, self.cdt.twin(h)] {
                    if e == NONE {
                        continue;
                    }
                    let c = self.cdt.apex(e);
                    if c != self.cdt.ghost && encroaches(pa, pb, self.cdt.pts[c as usize]) {
                        self.cdt.queue_split(s);
                        return;
                    }
                }
            }
        }
    }

    /// Queues every subsegment that some vertex (used by the domain, or an input point)
    /// encroaches; returns how many. A uniform grid over the vertices keeps it near-linear.
    pub fn sweep_encroached(&mut self) -> usize {
        let refining = self.will_refine();
        let cdt = &self.cdt;
        let live = |s: &Seg| s.a != NONE && (refining || s.input != NONE);
        if !cdt.segs.iter().any(live) {
            return 0;
        }
        let used: Vec<u32> = (0..cdt.pts.len() as u32)
            .filter(|&v| {
                v != cdt.ghost && ((v as usize) < self.n_input || cdt.vtri[v as usize] != NONE)
            })
            .collect();
        if used.is_empty() {
            return 0;
        }
        let grid = PointGrid::new(&cdt.pts, &used);
        let mut hits = Vec::new();
        for (s, seg) in cdt.segs.iter().enumerate() {
            // Retired segments are gone; hull edges only bound the domain when refining.
            if cdt.seg_queued[s] || !live(seg) {
                continue;
            }
            let (pa, pb) = (cdt.pts[seg.a as usize], cdt.pts[seg.b as usize]);
            let c = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
            // The float radius only picks grid cells; it is padded, the test itself is exact.
            let r = 0.5 * dist2(pa, pb).sqrt() * (1.0 + 1e-9) + 1e-300;
            let clear = grid.for_each_near(c, r, |v| {
                v == seg.a || v == seg.b || !encroaches(pa, pb, cdt.pts[v as usize])
            });
            if !clear {
                hits.push(s as SegId);
            }
        }
        for &s in &hits {
            self.cdt.queue_split(s);
        }
        hits.len()
    }

    /// Splits queued segments until none is left (the recursion of Fig. 2 step 8).
    pub fn drain_splits(&mut self) -> Result<(), Error> {
        while let Some(s) = self.cdt.split_queue.pop() {
            self.cdt.seg_queued[s as usize] = false;
            self.split_segment(s)?;
        }
        Ok(())
    }

    /// Where to split subsegment `ab`: the midpoint, or, when exactly one end is an apex, the
    /// point at the power-of-two distance from it nearest to half the length.
    fn split_point(&self, a: u32, b: u32) -> [f64; 2] {
        let pa = self.cdt.pts[a as usize];
        let pb = self.cdt.pts[b as usize];
        // Input vertices shared by segments are apexes; so are crossing points inserted by
        // `split_crossings`: the only Steiner segment endpoints lying on no single segment.
        let apex = |v: u32| {
            if (v as usize) < self.n_input {
                self.apex[v as usize]
            } else {
                self.cdt.vseg[v as usize] == NONE
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

    fn split_segment(&mut self, s: SegId) -> Result<(), Error> {
        let Seg {
            a,
            b,
            input,
            marker,
        } = self.cdt.segs[s as usize];
        let m = self.split_point(a, b);
        let (pa, pb) = (self.cdt.pts[a as usize], self.cdt.pts[b as usize]);
        if m == pa || m == pb {
            return Err(Error::Internal(format!(
                "segment ({pa:?}, {pb:?}) is too short to split in double precision"
            )));
        }
        let start = match self.cdt.find_edge(a, b) {
            Some(h) => Start::SplitEdge(h),
            None => Start::Walk(self.cdt.vtri[a as usize]),
        };
        let mv = match self.cdt.insert(m, start, Mode::Force, input, None) {
            Inserted::Yes(v) => v,
            // The rounded split point is an existing vertex lying (within rounding) on the
            // segment: split there instead.
            Inserted::Duplicate(v) if v != a && v != b => {
                self.cdt.new_tris.clear();
                v
            }
            other => {
                return Err(Error::Internal(format!(
                    "splitting segment ({pa:?}, {pb:?}) at {m:?}: {other:?}"
                )))
            }
        };
        self.cdt.segs[s as usize].b = mv;
        let s2 = self.cdt.segs.len() as SegId;
        self.cdt.segs.push(Seg {
            a: mv,
            b,
            input,
            marker,
        });
        self.cdt.seg_queued.push(false);
        self.queue_new_triangles();
        self.check_encroached(s);
        self.check_encroached(s2);
        Ok(())
    }

    fn queue_new_triangles(&mut self) {
        if !self.refining {
            return;
        }
        for k in 0..self.cdt.new_tris.len() {
            let t = self.cdt.new_tris[k];
            if self.is_bad(t) {
                self.push_bad(t);
            }
        }
    }

    fn push_bad(&mut self, t: TriId) {
        let v = self.cdt.tv[t as usize];
        let [a, b, c] = v.map(|x| self.cdt.pts[x as usize]);
        let s2 = min_angle_sin2(a, b, c).max(0.0);
        if s2 < self.sin2_min {
            self.queue.push(Reverse((s2.to_bits(), t, v)));
        } else {
            self.size_queue.push_back((t, v));
        }
    }

    fn pop_bad(&mut self) -> Option<(TriId, [u32; 3])> {
        if let Some(x) = self.size_queue.pop_front() {
            return Some(x);
        }
        self.queue.pop().map(|Reverse((_, t, v))| (t, v))
    }

    /// Whether triangle `t` must be split: too large (global, regional or user bound) or
    /// skinny and not exempt.
    fn is_bad(&self, t: TriId) -> bool {
        let reg = self.cdt.treg[t as usize];
        if reg == EXTERIOR || reg == HOLE || self.cdt.is_ghost(t) {
            return false;
        }
        let v = self.cdt.tv[t as usize];
        let [pa, pb, pc] = v.map(|x| self.cdt.pts[x as usize]);
        let area = 0.5 * area2(pa, pb, pc);
        let bound = if reg == NO_REGION {
            self.max_area
        } else {
            self.max_area.min(self.region_area[reg as usize])
        };
        if area > bound {
            return true;
        }
        if let Some(f) = &self.opts.sizing {
            if f(pa, pb, pc, area) {
                return true;
            }
        }
        self.sin2_min > 0.0 && min_angle_sin2(pa, pb, pc) < self.sin2_min && !self.exempt(t)
    }

    /// Small input angles (paper §6 "grooming"): a skinny triangle is left alone when its
    /// smallest angle lies between two segments (the isosceles triangles that concentric
    /// shells make at a sharp input corner), or when its shortest edge joins two points on
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
        let ts = self.cdt.ts[t as usize];
        // The edges at vertex k are edges k+1 and k+2.
        if ts[(k + 1) % 3] != NONE && ts[(k + 2) % 3] != NONE {
            return true;
        }
        let (x, y) = (v[(k + 1) % 3], v[(k + 2) % 3]);
        let (sx, sy) = (self.cdt.vseg[x as usize], self.cdt.vseg[y as usize]);
        if sx == NONE || sy == NONE || sx == sy {
            return false;
        }
        let corners = |s: u32| {
            let e = self.pslg.segments[s as usize];
            let extra = self.crossing_apexes.get(&s).map_or(&[][..], |v| &v[..]);
            e.into_iter().chain(extra.iter().copied())
        };
        for c in corners(sx) {
            if corners(sy).any(|d| d == c) {
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

    /// Eliminates bad triangles (paper Fig. 4): insert each one's circumcenter (or off-center)
    /// provisionally; if it encroaches a segment, split that segment instead (Force) and keep
    /// the triangle queued.
    /// Whether any refinement criterion is set.
    pub fn will_refine(&self) -> bool {
        let o = self.opts;
        o.min_angle.is_some()
            || o.max_area.is_some()
            || o.sizing.is_some()
            || (o.region_max_area && self.region_area.iter().any(|a| a.is_finite()))
    }

    pub fn refine(&mut self) -> Result<(), Error> {
        let o = self.opts;
        if !self.will_refine() {
            return Ok(());
        }
        self.refining = true;
        for t in 0..self.cdt.num_slots() as TriId {
            if self.cdt.alive(t) && self.is_bad(t) {
                self.push_bad(t);
            }
        }
        let base = self.n_input + 1;
        let cap = o.max_steiner.unwrap_or(u64::MAX);
        let mut last_report = 0usize;
        while let Some((t, vs)) = self.pop_bad() {
            if !self.cdt.alive(t) || self.cdt.tv[t as usize] != vs {
                continue;
            }
            let added = self.cdt.pts.len() - base;
            if added as u64 >= cap || self.cdt.pts.len() >= (NONE / 2) as usize {
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
        Ok(())
    }
}
