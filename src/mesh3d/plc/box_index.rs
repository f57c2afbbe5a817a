//! Which of many axis-aligned boxes may contain a point: a uniform grid over the boxes, each
//! entered in the cells it overlaps.
//!
//! The protection balls and thin-wedge zones of small input angles (`Sharp` in `sharp.rs`,
//! the corner lopping of the paper's §4 small-angle protection) are asked about every
//! candidate tetrahedron. On scanned surfaces nearly every input vertex is sharp (most surface
//! triangles have an angle below 60°), so scanning them all made that question linear in the
//! input size and the whole refinement quadratic.
//!
//! The index only selects candidates; the caller's own test on each decides. No box that
//! contains a point is missed: a point inside a box lies, coordinate by coordinate, between
//! the box's corners, and the cell of a coordinate is a monotone function of it (a rounded
//! subtraction and division, then truncation), so its cell lies in the box's range of cells.

/// Boxes that overlap more cells than this are not entered in cells but tried for every
/// query (a few huge boxes must not fill the grid).
const MAX_CELLS_PER_BOX: usize = 64;
/// Cells along one axis, at most.
const MAX_DIM: usize = 128;

/// The index: box ids cell by cell (compressed rows), and the wide boxes.
#[derive(Default)]
pub(super) struct BoxIndex {
    lo: [f64; 3],
    w: [f64; 3],
    /// Cells per axis; 0 when there are no boxes.
    g: usize,
    /// Cell `(x, y, z)` is number `(x·g + y)·g + z`; its boxes are
    /// `items[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    items: Vec<u32>,
    /// Boxes tried for every query.
    wide: Vec<u32>,
}

impl BoxIndex {
    /// Indexes `boxes` (`(lo, hi)` corners; box `i` is reported as `i`).
    pub(super) fn new(boxes: &[([f64; 3], [f64; 3])]) -> BoxIndex {
        if boxes.is_empty() {
            return BoxIndex::default();
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for (a, b) in boxes {
            for k in 0..3 {
                lo[k] = lo[k].min(a[k]);
                hi[k] = hi[k].max(b[k]);
            }
        }
        // About half a box per cell.
        let g = ((2.0 * boxes.len() as f64).cbrt().ceil() as usize).clamp(1, MAX_DIM);
        let w = [0, 1, 2].map(|k| ((hi[k] - lo[k]) / g as f64).max(f64::MIN_POSITIVE));
        let mut index = BoxIndex {
            lo,
            w,
            g,
            start: vec![0; g * g * g + 1],
            items: Vec::new(),
            wide: Vec::new(),
        };
        let ranges: Vec<Option<[(usize, usize); 3]>> = boxes
            .iter()
            .map(|(a, b)| {
                let r = [0, 1, 2].map(|k| (index.cell(a[k], k), index.cell(b[k], k)));
                let cells: usize = r.iter().map(|&(i, j)| j + 1 - i).product();
                (cells <= MAX_CELLS_PER_BOX).then_some(r)
            })
            .collect();
        // Count, prefix-sum, fill: two passes over the same ranges.
        for r in ranges.iter().flatten() {
            for c in cells(r, g) {
                index.start[c + 1] += 1;
            }
        }
        for i in 0..g * g * g {
            index.start[i + 1] += index.start[i];
        }
        let mut fill = index.start.clone();
        index.items = vec![0; index.start[g * g * g] as usize];
        for (i, r) in ranges.iter().enumerate() {
            match r {
                Some(r) => {
                    for c in cells(r, g) {
                        index.items[fill[c] as usize] = i as u32;
                        fill[c] += 1;
                    }
                }
                None => index.wide.push(i as u32),
            }
        }
        index
    }

    /// The cell of coordinate `x` along axis `k`, clamped into the grid (NaN to cell 0).
    fn cell(&self, x: f64, k: usize) -> usize {
        let c = (x - self.lo[k]) / self.w[k];
        if c >= 0.0 {
            (c as usize).min(self.g - 1)
        } else {
            0
        }
    }

    /// The ids of the boxes that may contain `q`: every box that does, and some others.
    pub(super) fn candidates(&self, q: [f64; 3]) -> impl Iterator<Item = u32> + '_ {
        let cell: &[u32] = if self.g == 0 {
            &[]
        } else {
            let c =
                (self.cell(q[0], 0) * self.g + self.cell(q[1], 1)) * self.g + self.cell(q[2], 2);
            &self.items[self.start[c] as usize..self.start[c + 1] as usize]
        };
        cell.iter().chain(&self.wide).copied()
    }
}

/// The cells of a range of cells per axis, in a grid of `g` cells per axis.
fn cells(r: &[(usize, usize); 3], g: usize) -> impl Iterator<Item = usize> + '_ {
    (r[0].0..=r[0].1).flat_map(move |x| {
        (r[1].0..=r[1].1).flat_map(move |y| (r[2].0..=r[2].1).map(move |z| (x * g + y) * g + z))
    })
}

#[cfg(test)]
mod tests {
    use super::BoxIndex;

    /// A small deterministic generator (no dependency on a random crate's stream).
    fn next(s: &mut u64) -> f64 {
        *s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*s >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn every_box_holding_a_point_is_a_candidate() {
        let mut s = 7;
        for scale in [1e-20, 1.0, 1e6] {
            for shift in [0.0, -3.0 * scale, 1e5 * scale] {
                let mut boxes = Vec::new();
                for i in 0..500 {
                    let c = [0; 3].map(|_| shift + scale * next(&mut s));
                    // Mostly small boxes, some wide ones, some flat ones.
                    let r = scale
                        * if i % 50 == 0 {
                            0.6
                        } else {
                            0.02 * next(&mut s)
                        };
                    let flat = i % 7 == 0;
                    let lo = [c[0] - r, c[1] - r, if flat { c[2] } else { c[2] - r }];
                    let hi = [c[0] + r, c[1] + r, if flat { c[2] } else { c[2] + r }];
                    boxes.push((lo, hi));
                }
                let index = BoxIndex::new(&boxes);
                assert!(!index.wide.is_empty() && index.items.len() >= 400);
                for _ in 0..5000 {
                    // Points near and on box corners as well as random ones.
                    let b = boxes[(next(&mut s) * 500.0) as usize];
                    let q = [0, 1, 2].map(|k| match (next(&mut s) * 3.0) as u32 {
                        0 => b.0[k],
                        1 => b.1[k],
                        _ => shift + scale * next(&mut s),
                    });
                    let found: Vec<u32> = index.candidates(q).collect();
                    for (i, (lo, hi)) in boxes.iter().enumerate() {
                        if (0..3).all(|k| lo[k] <= q[k] && q[k] <= hi[k]) {
                            assert!(found.contains(&(i as u32)), "box {i} holds {q:?}");
                        }
                    }
                    // It selects: far fewer candidates than boxes.
                    assert!(found.len() < 100, "{} candidates", found.len());
                }
            }
        }
    }

    #[test]
    fn no_boxes_no_candidates() {
        assert_eq!(BoxIndex::new(&[]).candidates([0.0; 3]).count(), 0);
    }
}
