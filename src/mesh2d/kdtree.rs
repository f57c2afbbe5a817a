//! A static 2D k-d tree over a set of points, for "which points lie near here" queries (the
//! encroachment sweep and the empty-circle check). Unlike a uniform grid it stays
//! logarithmic on strongly graded meshes, where nearly all points can crowd into one grid
//! cell. It only selects candidates; every decision on them is made with exact predicates by
//! the caller.

/// Leaves at most this many points are scanned directly.
const LEAF: usize = 8;

use crate::error::Error;
use crate::progress::tick;

/// Points in k-d order: every range `[lo, hi)` has its splitting point at `(lo + hi) / 2`,
/// smaller coordinates (along the axis of its depth, x first) before, larger after.
pub(super) struct PointTree {
    ids: Vec<u32>,
    xy: Vec<[f64; 2]>,
}

impl PointTree {
    /// Builds the tree over the points `ids` (indices into `pts`, finite coordinates). Fails
    /// only when the run is cancelled: the build reports progress (on a million points it
    /// takes about a tenth of a second), without an estimate of its own.
    pub fn new(pts: &[[f64; 2]], ids: &[u32]) -> Result<PointTree, Error> {
        let mut ids = ids.to_vec();
        // Explicit stack of (lo, hi, axis): no recursion depth to worry about.
        let mut stack = vec![(0usize, ids.len(), 0usize)];
        while let Some((lo, hi, axis)) = stack.pop() {
            if hi - lo <= LEAF {
                continue;
            }
            tick(|| (0, 0))?;
            let mid = (lo + hi) / 2;
            ids[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
                pts[a as usize][axis].total_cmp(&pts[b as usize][axis])
            });
            stack.push((lo, mid, 1 - axis));
            stack.push((mid + 1, hi, 1 - axis));
        }
        let xy = ids.iter().map(|&v| pts[v as usize]).collect();
        Ok(PointTree { ids, xy })
    }

    /// Calls `f` for every point in the closed square of half-side `r` around `center` (a
    /// superset of the points within distance `r`), until `f` returns `false`. Returns
    /// `false` when `f` stopped the scan.
    pub fn for_each_near(&self, center: [f64; 2], r: f64, mut f: impl FnMut(u32) -> bool) -> bool {
        let inside = |p: [f64; 2]| (p[0] - center[0]).abs() <= r && (p[1] - center[1]).abs() <= r;
        // Depth is about log2(n / LEAF), so a small fixed stack suffices; it grows if not.
        let mut stack: Vec<(usize, usize, usize)> = Vec::with_capacity(64);
        stack.push((0, self.ids.len(), 0));
        while let Some((lo, hi, axis)) = stack.pop() {
            if hi - lo <= LEAF {
                for i in lo..hi {
                    if inside(self.xy[i]) && !f(self.ids[i]) {
                        return false;
                    }
                }
                continue;
            }
            let mid = (lo + hi) / 2;
            let p = self.xy[mid];
            if inside(p) && !f(self.ids[mid]) {
                return false;
            }
            if center[axis] - r <= p[axis] {
                stack.push((lo, mid, 1 - axis));
            }
            if center[axis] + r >= p[axis] {
                stack.push((mid + 1, hi, 1 - axis));
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_exactly_the_points_in_the_box() {
        // A strongly graded set: a geometric cluster plus a coarse lattice.
        let mut pts = Vec::new();
        for k in 0..200 {
            let t = 0.5f64.powi(k / 4);
            pts.push([t * (k % 4) as f64, t * ((k + 1) % 3) as f64]);
        }
        for i in 0..20 {
            for j in 0..20 {
                pts.push([i as f64 * 0.37, j as f64 * 0.29]);
            }
        }
        let ids: Vec<u32> = (0..pts.len() as u32).collect();
        let tree = PointTree::new(&pts, &ids).unwrap();
        for (c, r) in [([0.0, 0.0], 1e-6), ([1.0, 1.0], 0.5), ([3.0, 2.0], 10.0)] {
            let mut got = Vec::new();
            tree.for_each_near(c, r, |v| {
                got.push(v);
                true
            });
            got.sort_unstable();
            let want: Vec<u32> = ids
                .iter()
                .copied()
                .filter(|&v| {
                    let p = pts[v as usize];
                    (p[0] - c[0]).abs() <= r && (p[1] - c[1]).abs() <= r
                })
                .collect();
            assert_eq!(got, want, "box at {c:?} of half-side {r}");
        }
        // Stopping early reports it.
        assert!(!tree.for_each_near([0.0, 0.0], 100.0, |_| false));
    }
}
