//! Size bounds on the surface: TetGen's facet constraints (a maximum subface area per facet
//! marker) and segment constraints (a maximum subsegment length per input edge), the
//! [`Options3::facet_max_area`] and [`Options3::segment_max_length`] options.
//!
//! They join the work queue's checks (paper §4, Definition 4.1): a subsegment or subface
//! taken from the queue is split when it is missing, encroached, or over its bound, so the
//! split points are the usual ones (midpoints or concentric shells for subsegments,
//! circumcentres deferring to encroached subsegments for subfaces) and the mesh stays
//! conforming Delaunay. A simplex below the mesher's size floor is never split for a bound,
//! so a bound below the precision of the coordinates cannot run refinement into the limits of
//! floating point.

use crate::hash::FastMap as HashMap;

use super::super::features::{ekey, Features};
use super::super::Options3;

/// The bounds per facet and per input edge of one run, squared.
#[derive(Default)]
pub(super) struct Limits {
    /// Per facet (the mesher's numbering): the squared maximum area, or infinity.
    face_area2: Vec<f64>,
    /// Per input edge: the squared maximum length, or infinity.
    seg_len2: Vec<f64>,
}

impl Limits {
    /// The bounds of `opts` for the features `feat`; empty (nothing bounded) with
    /// `keep_surface`, which adds no point on the surface.
    pub fn new(opts: &Options3, feat: &Features) -> Limits {
        if opts.keep_surface
            || (opts.facet_max_area.is_empty() && opts.segment_max_length.is_empty())
        {
            return Limits::default();
        }
        let mut by_marker: HashMap<i32, f64> = HashMap::default();
        for &(m, a) in &opts.facet_max_area {
            let e = by_marker.entry(m).or_insert(f64::INFINITY);
            *e = e.min(a * a);
        }
        let mut by_edge: HashMap<u64, f64> = HashMap::default();
        for &([a, b], l) in &opts.segment_max_length {
            let e = by_edge.entry(ekey(a, b)).or_insert(f64::INFINITY);
            *e = e.min(l * l);
        }
        Limits {
            face_area2: feat
                .facets
                .iter()
                .map(|f| by_marker.get(&f.marker).copied().unwrap_or(f64::INFINITY))
                .collect(),
            seg_len2: feat
                .edges
                .iter()
                .map(|e| {
                    by_edge
                        .get(&ekey(e.ends[0], e.ends[1]))
                        .copied()
                        .unwrap_or(f64::INFINITY)
                })
                .collect(),
        }
    }

    /// Whether a subsegment `pa`-`pb` of input edge `e` is longer than its bound.
    pub fn seg_too_long(&self, e: u32, pa: [f64; 3], pb: [f64; 3]) -> bool {
        self.seg_len2
            .get(e as usize)
            .is_some_and(|&l2| l2.is_finite() && crate::geometry::dist2_3(pa, pb) > l2)
    }

    /// Whether subface `c` of facet `f` has a larger area than its bound.
    pub fn face_too_large(&self, f: u32, c: [[f64; 3]; 3]) -> bool {
        self.face_area2.get(f as usize).is_some_and(|&a2| {
            a2.is_finite() && crate::geometry::tri_area3(c[0], c[1], c[2]).powi(2) > a2
        })
    }
}
