//! Insertion order for incremental Delaunay: a biased randomized insertion order (BRIO, Amenta,
//! Choi and Rote 2003) whose rounds are each sorted along a 3D Hilbert curve.
//!
//! Random rounds keep the expected cavity sizes of a random order; the Hilbert sort inside each
//! round makes consecutive points close, so the walk from the last inserted tet is a few steps
//! and the tets and vertices being touched stay in cache. The order is deterministic (a fixed
//! seed), so a run is reproducible.

/// Most bits per axis of a Hilbert index (3 × 21 = 63 bits fit one `u64`).
const BITS: u32 = 21;

/// Each round is this fraction of the points not yet placed (the last round holds the largest
/// share; the first round is a small random sample that spreads over the whole domain).
const ROUND_RATIO: f64 = 0.25;

/// Rounds smaller than this are not split further.
const SMALLEST_ROUND: usize = 64;

/// SplitMix64: a tiny, good-enough generator for the shuffle (no dependency).
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (Lemire's multiply-shift; the tiny bias is irrelevant here).
    fn below(&mut self, n: usize) -> usize {
        (((self.next() >> 32) * n as u64) >> 32) as usize
    }
}

/// The BRIO + Hilbert insertion order of `points`: a permutation of `0..points.len()`.
/// Non-finite coordinates are tolerated (they sort somewhere) but callers reject them first.
pub fn brio_hilbert_order(points: &[[f64; 3]], seed: u64) -> Vec<u32> {
    let n = points.len();
    let keys = hilbert_keys(points);
    let mut ids: Vec<u32> = (0..n as u32).collect();
    let mut rng = SplitMix64(seed);
    for i in (1..n).rev() {
        let j = rng.below(i + 1);
        ids.swap(i, j);
    }
    // Round boundaries, from the end: the last round takes (1 - ratio) of what is left.
    let mut pairs: Vec<(u64, u32)> = ids.iter().map(|&i| (keys[i as usize], i)).collect();
    drop(keys);
    let mut end = n;
    while end > 0 {
        let start = if end > SMALLEST_ROUND {
            ((end as f64) * ROUND_RATIO) as usize
        } else {
            0
        };
        pairs[start..end].sort_unstable();
        end = start;
    }
    pairs.into_iter().map(|(_, i)| i).collect()
}

/// The Hilbert index of each point, on a grid over the points' bounding box with 8 to 64
/// cells per point (at most `2^21` per axis) and the same scale on every axis, so the curve
/// follows the geometry.
pub fn hilbert_keys(points: &[[f64; 3]]) -> Vec<u64> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            if p[k].is_finite() {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    let extent =
        (0..3)
            .map(|k| hi[k] - lo[k])
            .fold(0.0f64, |a, b| if b.is_finite() { a.max(b) } else { a });
    // One level finer than one cell per point (8 to 64 cells per point) is plenty for
    // locality; fewer levels make the keys cheaper.
    let levels = (usize::BITS - points.len().leading_zeros()).div_ceil(3) + 1;
    let bits = levels.clamp(1, BITS);
    let max = ((1u32 << bits) - 1) as f64;
    let scale = if extent > 0.0 { max / extent } else { 0.0 };
    points
        .iter()
        .map(|p| {
            let cell = |k: usize| {
                let x = (p[k] - lo[k]) * scale;
                // NaN and out-of-range values clamp into the grid.
                if x >= 0.0 {
                    x.min(max) as u32
                } else {
                    0
                }
            };
            hilbert_index_bits([cell(0), cell(1), cell(2)], bits)
        })
        .collect()
}

/// Position of grid cell `x` along the 3D Hilbert curve on a `2^bits` grid (`1 <= bits <= 21`,
/// coordinates below `2^bits`, the result below `2^(3 bits)`): Skilling's transpose algorithm
/// ("Programming the Hilbert curve", 2004), written without data-dependent branches (they
/// would be mispredicted half the time).
pub fn hilbert_index_bits(mut x: [u32; 3], bits: u32) -> u64 {
    let m = 1u32 << (bits - 1);
    // Inverse undo of the excess work.
    let mut q = m;
    while q > 1 {
        let p = q - 1;
        for i in 0..3 {
            // All ones when bit q of x[i] is set: then invert the low bits of x[0], else
            // exchange the low bits of x[0] and x[i] (a no-op for i = 0).
            let set = 0u32.wrapping_sub((x[i] & q != 0) as u32);
            let t = (x[0] ^ x[i]) & p & !set;
            x[0] ^= (p & set) ^ t;
            x[i] ^= t;
        }
        q >>= 1;
    }
    // Gray encode.
    x[1] ^= x[0];
    x[2] ^= x[1];
    let mut t = 0;
    let mut q = m;
    while q > 1 {
        t ^= (q - 1) & 0u32.wrapping_sub((x[2] & q != 0) as u32);
        q >>= 1;
    }
    for xi in &mut x {
        *xi ^= t;
    }
    // Interleave: the key's bits from the top are x0, x1, x2 of the top bit, then the next.
    (spread(x[0]) << 2) | (spread(x[1]) << 1) | spread(x[2])
}

/// Spreads the low 21 bits of `v` so that bit `i` moves to bit `3i`.
fn spread(v: u32) -> u64 {
    let mut x = (v as u64) & 0x1f_ffff;
    x = (x | (x << 32)) & 0x001f_0000_0000_ffff;
    x = (x | (x << 16)) & 0x001f_0000_ff00_00ff;
    x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
    x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
    x = (x | (x << 2)) & 0x1249_2492_4924_9249;
    x
}
