//! A uniform grid over a set of points, for near-linear "which points lie near here" queries
//! (the encroachment sweep and the empty-circle check). It only selects candidates; every
//! decision on them is made with exact predicates by the caller.

/// Points bucketed into a `g × g` grid over their bounding box (compressed rows).
pub(super) struct PointGrid {
    lo: [f64; 2],
    w: [f64; 2],
    g: usize,
    start: Vec<u32>,
    items: Vec<u32>,
}

impl PointGrid {
    /// Buckets the points `ids` (indices into `pts`).
    pub fn new(pts: &[[f64; 2]], ids: &[u32]) -> PointGrid {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &v in ids {
            let p = pts[v as usize];
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let g = ((ids.len() as f64).sqrt().ceil() as usize).clamp(1, 2048);
        let w = [
            ((hi[0] - lo[0]) / g as f64).max(f64::MIN_POSITIVE),
            ((hi[1] - lo[1]) / g as f64).max(f64::MIN_POSITIVE),
        ];
        let mut grid = PointGrid {
            lo,
            w,
            g,
            start: vec![0; g * g + 1],
            items: vec![0; ids.len()],
        };
        for &v in ids {
            let c = grid.cell_of(pts[v as usize]);
            grid.start[c + 1] += 1;
        }
        for i in 0..g * g {
            grid.start[i + 1] += grid.start[i];
        }
        let mut fill = grid.start.clone();
        for &v in ids {
            let c = grid.cell_of(pts[v as usize]);
            grid.items[fill[c] as usize] = v;
            fill[c] += 1;
        }
        grid
    }

    fn cell(&self, x: f64, k: usize) -> usize {
        let c = ((x - self.lo[k]) / self.w[k]).floor();
        if c.is_nan() || c < 0.0 {
            0
        } else {
            (c as usize).min(self.g - 1)
        }
    }

    fn cell_of(&self, p: [f64; 2]) -> usize {
        self.cell(p[1], 1) * self.g + self.cell(p[0], 0)
    }

    /// Calls `f` for every point in the cells that the square of half-side `r` around `center`
    /// touches (a superset of the points within distance `r`), until `f` returns `false`.
    /// Returns `false` when `f` stopped the scan.
    pub fn for_each_near(&self, center: [f64; 2], r: f64, mut f: impl FnMut(u32) -> bool) -> bool {
        for y in self.cell(center[1] - r, 1)..=self.cell(center[1] + r, 1) {
            for x in self.cell(center[0] - r, 0)..=self.cell(center[0] + r, 0) {
                let c = y * self.g + x;
                for &v in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                    if !f(v) {
                        return false;
                    }
                }
            }
        }
        true
    }
}
