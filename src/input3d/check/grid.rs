//! Candidate pairs of features that may touch, from a uniform grid over their bounding box.
//!
//! Each feature (point, segment or triangle) is entered only in the cells it meets, found by
//! splitting its box's cell range in halves and keeping the halves it overlaps (a separating
//! axis test), so a long thin triangle costs the cells along it, not those of its box. A pair
//! is a candidate when the two features meet a common cell and their boxes overlap; each is
//! reported once. Features of the same group (one facet's triangles and edges, or the points)
//! are never paired: the caller has nothing to test between them.
//!
//! Floating point only selects candidates and errs on the side of more: cells are widened by
//! a margin far above any rounding error before a feature is tested against them, so a pair
//! that truly touches always shares a cell. Every decision on a pair is left to the caller's
//! exact predicates.

use super::exact3::P3;

/// A feature's geometry.
#[derive(Debug, Clone, Copy)]
pub(super) enum Shape {
    Point(P3),
    Segment(P3, P3),
    Triangle([P3; 3]),
}

/// How many cells to aim for per feature.
const CELLS_PER_FEATURE: f64 = 2.0;
/// Cells along one axis, at most.
const MAX_DIM: usize = 1 << 10;
/// Relative widening of cells, and relative slack of the separating-axis comparisons: far
/// above rounding (about 1e-16), far below anything that matters for speed.
const WIDEN: f64 = 1e-6;
const SLACK: f64 = 1e-10;

impl Shape {
    fn bbox(&self) -> (P3, P3) {
        let (first, rest): (P3, &[P3]) = match self {
            Shape::Point(p) => (*p, &[]),
            Shape::Segment(a, b) => (*a, std::slice::from_ref(b)),
            Shape::Triangle(t) => (t[0], &t[1..]),
        };
        let (mut lo, mut hi) = (first, first);
        for p in rest {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }

    /// Whether the shape may meet the box with center `c` and half-widths `h` (conservative:
    /// `false` only when an axis separates them by more than the rounding slack).
    fn may_meet(&self, c: P3, h: P3) -> bool {
        let rel = |p: P3| [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
        let (v, n): ([P3; 3], usize) = match *self {
            Shape::Point(p) => ([rel(p); 3], 1),
            Shape::Segment(a, b) => ([rel(a), rel(b), rel(b)], 2),
            Shape::Triangle(t) => ([rel(t[0]), rel(t[1]), rel(t[2])], 3),
        };
        let v = &v[..n];
        // Rounding in the translation and the dot products stays below 1e-15 of this.
        let mut mag = 0.0f64;
        for x in v.iter().flatten().chain(&h).chain(&c) {
            mag = mag.max(x.abs());
        }
        // The box axes first: the cheap test that rejects most cells.
        for k in 0..3 {
            let (mut lo, mut hi) = (v[0][k], v[0][k]);
            for p in &v[1..] {
                lo = lo.min(p[k]);
                hi = hi.max(p[k]);
            }
            let slack = SLACK * mag;
            if lo > h[k] + slack || hi < -h[k] - slack {
                return false;
            }
        }
        // Projections of the shape on `axis` against the box's radius on it.
        let separated = |axis: P3| {
            let r = h[0] * axis[0].abs() + h[1] * axis[1].abs() + h[2] * axis[2].abs();
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in v {
                let d = axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2];
                lo = lo.min(d);
                hi = hi.max(d);
            }
            let slack = SLACK * mag * (axis[0].abs() + axis[1].abs() + axis[2].abs());
            lo > r + slack || hi < -r - slack
        };
        let sub = |a: P3, b: P3| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let edges: [P3; 3] = match n {
            2 => [sub(v[1], v[0]); 3],
            3 => [sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])],
            _ => return true,
        };
        if n == 3 {
            let (a, b) = (edges[0], edges[1]);
            let normal = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            if separated(normal) {
                return false;
            }
        }
        // Each edge crossed with each box axis.
        for e in &edges[..if n == 2 { 1 } else { 3 }] {
            for axis in [[0.0, e[2], -e[1]], [-e[2], 0.0, e[0]], [e[1], -e[0], 0.0]] {
                if separated(axis) {
                    return false;
                }
            }
        }
        true
    }
}

struct Layout {
    lo: P3,
    width: P3,
    dims: [usize; 3],
}

impl Layout {
    fn cell(&self, x: f64, k: usize) -> usize {
        if self.dims[k] == 1 {
            return 0;
        }
        let c = ((x - self.lo[k]) / self.width[k]).floor();
        if c.is_nan() || c < 0.0 {
            0
        } else {
            (c as usize).min(self.dims[k] - 1)
        }
    }

    fn id(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// The box of cells `r[k][0]..=r[k][1]`, widened by a margin far above the rounding of
    /// the cell arithmetic: center and half-widths. Every feature lies inside the grid's box,
    /// so the outer cells need not reach further.
    fn range_box(&self, r: [[usize; 2]; 3]) -> (P3, P3) {
        let (mut c, mut h) = ([0.0; 3], [0.0; 3]);
        for k in 0..3 {
            let lo = self.lo[k] + r[k][0] as f64 * self.width[k];
            let hi = self.lo[k] + (r[k][1] + 1) as f64 * self.width[k];
            c[k] = 0.5 * lo + 0.5 * hi;
            h[k] = 0.5 * hi - 0.5 * lo
                + WIDEN * self.width[k]
                + 1e-13 * (lo.abs() + hi.abs())
                + f64::MIN_POSITIVE;
        }
        (c, h)
    }

    /// Appends to `out` the cells of `range` that `s` may meet (halving the range).
    fn rasterize(
        &self,
        s: &Shape,
        range: [[usize; 2]; 3],
        stack: &mut Vec<[[usize; 2]; 3]>,
        out: &mut Vec<u32>,
    ) {
        stack.clear();
        stack.push(range);
        while let Some(r) = stack.pop() {
            let (c, h) = self.range_box(r);
            if !s.may_meet(c, h) {
                continue;
            }
            let sizes = [0, 1, 2].map(|k| r[k][1] - r[k][0]);
            let k = (0..3).max_by_key(|&k| sizes[k]).unwrap_or(0);
            if sizes[k] == 0 {
                out.push(self.id([r[0][0], r[1][0], r[2][0]]) as u32);
                continue;
            }
            let mid = r[k][0] + sizes[k] / 2;
            let mut a = r;
            let mut b = r;
            a[k][1] = mid;
            b[k][0] = mid + 1;
            stack.push(b);
            stack.push(a);
        }
    }
}

/// A grid of about `target` cells, about equally wide on every axis that has extent. An axis
/// too thin for one cell gets exactly one and the others share the target; computed in
/// logarithms so that tiny or huge extents cannot underflow.
fn layout(lo: P3, hi: P3, target: f64) -> Layout {
    let ext = [0, 1, 2].map(|k| hi[k] - lo[k]);
    let mut live: Vec<usize> = (0..3).filter(|&k| ext[k] > 0.0).collect();
    let mut dims = [1usize; 3];
    while !live.is_empty() {
        let log_h = (live.iter().map(|&k| ext[k].ln()).sum::<f64>() - target.max(1.0).ln())
            / live.len() as f64;
        let thin: Vec<usize> = live
            .iter()
            .copied()
            .filter(|&k| ext[k].ln() - log_h < 0.0)
            .collect();
        if thin.is_empty() {
            for &k in &live {
                let d = (ext[k].ln() - log_h).exp().ceil();
                dims[k] = if d.is_finite() && d >= 1.0 {
                    (d as usize).min(MAX_DIM)
                } else {
                    1
                };
            }
            break;
        }
        live.retain(|k| !thin.contains(k));
    }
    let width = [0, 1, 2].map(|k| ext[k] / dims[k] as f64);
    Layout { lo, width, dims }
}

/// Calls `f(i, j)` (with `i < j`, in increasing `i`) once for every pair of shapes in
/// different groups that may touch, except pairs with `i >= first_below` (the caller has
/// nothing to test between the last shapes), and stops at the first error.
pub(super) fn for_each_candidate<E>(
    shapes: &[Shape],
    groups: &[u32],
    first_below: usize,
    mut f: impl FnMut(u32, u32) -> Result<(), E>,
) -> Result<(), E> {
    let n = shapes.len();
    if n < 2 {
        return Ok(());
    }
    let boxes: Vec<(P3, P3)> = shapes.iter().map(Shape::bbox).collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for b in &boxes {
        for k in 0..3 {
            lo[k] = lo[k].min(b.0[k]);
            hi[k] = hi[k].max(b.1[k]);
        }
    }
    // Coarsen until the entries stay within a linear budget (a one-cell grid always does).
    let mut budget = 64 * n + (1 << 20);
    let mut target = CELLS_PER_FEATURE * n as f64;
    let mut stack = Vec::new();
    let (grid, estart, ecells) = loop {
        let grid = layout(lo, hi, target);
        let mut estart = Vec::with_capacity(n + 1);
        let mut ecells: Vec<u32> = Vec::with_capacity(2 * n);
        estart.push(0u32);
        let mut over = false;
        for (s, b) in shapes.iter().zip(&boxes) {
            let range = [0, 1, 2].map(|k| [grid.cell(b.0[k], k), grid.cell(b.1[k], k)]);
            grid.rasterize(s, range, &mut stack, &mut ecells);
            estart.push(ecells.len() as u32);
            if ecells.len() > budget {
                over = true;
                break;
            }
        }
        if !over {
            break (grid, estart, ecells);
        }
        if target <= 1.0 {
            budget = usize::MAX;
        }
        target /= 8.0;
    };
    let ncells = grid.dims[0] * grid.dims[1] * grid.dims[2];
    let mut start = vec![0u32; ncells + 1];
    for &c in &ecells {
        start[c as usize + 1] += 1;
    }
    for c in 0..ncells {
        start[c + 1] += start[c];
    }
    let mut fill = start.clone();
    let mut items = vec![0u32; ecells.len()];
    for i in 0..n {
        for &c in &ecells[estart[i] as usize..estart[i + 1] as usize] {
            items[fill[c as usize] as usize] = i as u32;
            fill[c as usize] += 1;
        }
    }
    drop(fill);
    for c in 0..ncells {
        items[start[c] as usize..start[c + 1] as usize]
            .sort_unstable_by_key(|&j| (groups[j as usize], j));
    }
    let mut stamp = vec![u32::MAX; n];
    for i in 0..first_below.min(n) {
        let (g, bi) = (groups[i], &boxes[i]);
        for &c in &ecells[estart[i] as usize..estart[i + 1] as usize] {
            let here = &items[start[c as usize] as usize..start[c as usize + 1] as usize];
            // The block of i's own group is skipped whole.
            let from = here.partition_point(|&j| groups[j as usize] < g);
            let to = here.partition_point(|&j| groups[j as usize] <= g);
            for &j in here[..from].iter().chain(&here[to..]) {
                if j as usize <= i || stamp[j as usize] == i as u32 {
                    continue;
                }
                stamp[j as usize] = i as u32;
                let bj = &boxes[j as usize];
                if (0..3).all(|k| bi.0[k] <= bj.1[k] && bj.0[k] <= bi.1[k]) {
                    f(i as u32, j)?;
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pairs in different groups whose boxes overlap: a superset of the candidates.
    fn boxes_overlapping(shapes: &[Shape], groups: &[u32]) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for i in 0..shapes.len() {
            for j in i + 1..shapes.len() {
                let (a, b) = (shapes[i].bbox(), shapes[j].bbox());
                if groups[i] != groups[j] && (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k]) {
                    out.push((i as u32, j as u32));
                }
            }
        }
        out
    }

    fn candidates(shapes: &[Shape], groups: &[u32]) -> Vec<(u32, u32)> {
        let mut got = Vec::new();
        for_each_candidate(shapes, groups, shapes.len(), |i, j| {
            got.push((i, j));
            Ok::<(), ()>(())
        })
        .unwrap();
        got
    }

    #[test]
    fn touching_features_are_always_candidates_and_reported_once() {
        // Deterministic pseudo-random features of very different sizes, some flat, some
        // touching exactly (shared corners), in a few groups.
        let mut state: u64 = 0x2545_F491_4F6C_DD1D;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut shapes = Vec::new();
        let mut corners: Vec<P3> = Vec::new();
        for i in 0..300 {
            let size = if i % 40 == 0 { 8.0 } else { 0.8 };
            let p = |rnd: &mut dyn FnMut() -> f64| -> P3 {
                if !corners.is_empty() && rnd() < 0.3 {
                    corners[(rnd() * corners.len() as f64) as usize]
                } else {
                    [
                        rnd() * 10.0,
                        rnd() * 10.0,
                        if i % 3 == 0 { 0.0 } else { rnd() },
                    ]
                }
            };
            let a = p(&mut rnd);
            let c = p(&mut rnd);
            let b = [a[0] + size * rnd(), a[1] + size * rnd(), a[2]];
            shapes.push(match i % 3 {
                0 => Shape::Point(a),
                1 => Shape::Segment(a, b),
                _ => Shape::Triangle([a, b, c]),
            });
            corners.extend([a, b]);
        }
        let groups: Vec<u32> = (0..shapes.len() as u32).map(|i| i % 5).collect();
        let got = candidates(&shapes, &groups);
        let mut sorted = got.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), got.len(), "a pair was reported twice");
        let superset = boxes_overlapping(&shapes, &groups);
        assert!(sorted.iter().all(|p| superset.binary_search(p).is_ok()));
        // Every pair sharing a corner touches, so it must be a candidate.
        let mut shared = 0;
        let all = |s: &Shape| -> Vec<P3> {
            match *s {
                Shape::Point(p) => vec![p],
                Shape::Segment(p, q) => vec![p, q],
                Shape::Triangle(t) => t.to_vec(),
            }
        };
        for &(i, j) in &superset {
            let (pa, pb) = (all(&shapes[i as usize]), all(&shapes[j as usize]));
            if pa.iter().any(|p| pb.contains(p)) {
                shared += 1;
                assert!(
                    sorted.binary_search(&(i, j)).is_ok(),
                    "touching pair {i}, {j} missed"
                );
            }
        }
        assert!(
            shared > 50,
            "the test should produce touching pairs, got {shared}"
        );
    }

    #[test]
    fn a_long_thin_triangle_is_not_paired_with_what_lies_beside_it() {
        // A long diagonal sliver, and points near the diagonal but off it, beside it.
        let t = Shape::Triangle([[0.0, 0.0, 0.0], [100.0, 100.0, 0.0], [100.0, 100.5, 0.0]]);
        let mut shapes = vec![t];
        for i in 0..2000 {
            let x = i as f64 * 0.05;
            shapes.push(Shape::Point([x, x + 30.0, 0.0]));
        }
        let mut groups = vec![1u32];
        groups.resize(shapes.len(), 0);
        let got = candidates(&shapes, &groups);
        assert!(
            got.len() < 200,
            "{} candidates for a triangle far from the points",
            got.len()
        );
        // A point on the sliver's edge is a candidate.
        shapes.push(Shape::Point([50.0, 50.0, 0.0]));
        groups.push(0);
        let got = candidates(&shapes, &groups);
        assert!(got.contains(&(0, shapes.len() as u32 - 1)));
    }

    #[test]
    fn groups_are_never_paired_and_errors_stop_the_walk() {
        let p = Shape::Point([0.0; 3]);
        assert!(candidates(&[p, p, p], &[0, 0, 0]).is_empty());
        let mut calls = 0;
        let r = for_each_candidate(&[p, p, p, p], &[0, 1, 2, 3], 4, |_, _| {
            calls += 1;
            if calls == 3 {
                Err("stop")
            } else {
                Ok(())
            }
        });
        assert_eq!((r, calls), (Err("stop"), 3));
        let tiny = [
            Shape::Point([0.0; 3]),
            Shape::Segment([0.0; 3], [1e-300; 3]),
        ];
        assert_eq!(candidates(&tiny, &[0, 1]), vec![(0, 1)]);
    }
}
