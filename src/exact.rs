//! Exact sign of small polynomial expressions in floating-point inputs, by floating-point
//! expansions (Shewchuk's two-sum / two-product). Used behind a fast filter where `robust`
//! has no ready-made predicate: the fixed [`Expansion`] for the dot-product sign of the
//! encroachment tests, the growable [`DynExpansion`] for the degree-6 facet predicates of 3D
//! meshing (`predicates::in_diametral_ball_tri`).

/// `a + b = hi + lo` exactly.
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// `a - b = hi + lo` exactly.
#[inline]
pub fn two_diff(a: f64, b: f64) -> (f64, f64) {
    let s = a - b;
    let bv = a - s;
    let av = s + bv;
    (s, (a - av) + (bv - b))
}

/// `a * b = hi + lo` exactly (barring underflow), using a fused multiply-add.
#[inline]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// A small expansion: a sum of non-overlapping doubles in increasing magnitude.
pub struct Expansion {
    terms: [f64; 64],
    len: usize,
}

impl Default for Expansion {
    fn default() -> Self {
        Self::new()
    }
}

impl Expansion {
    /// The empty sum (zero).
    pub fn new() -> Self {
        Expansion {
            terms: [0.0; 64],
            len: 0,
        }
    }

    /// Adds one double exactly (Shewchuk's Grow-Expansion, zero elimination).
    pub fn add(&mut self, mut q: f64) {
        let mut out = 0;
        for i in 0..self.len {
            let (s, e) = two_sum(q, self.terms[i]);
            q = s;
            if e != 0.0 {
                self.terms[out] = e;
                out += 1;
            }
        }
        if q != 0.0 {
            // The bound 64 is never reached by the expressions in this crate (at most 16 terms);
            // dropping a term would only be possible after 64 non-overlapping terms.
            if out < self.terms.len() {
                self.terms[out] = q;
                out += 1;
            }
        }
        self.len = out;
    }

    /// Adds the exact product of two 2-term values `(a1 + a0) * (b1 + b0)`.
    pub fn add_product2(&mut self, a: (f64, f64), b: (f64, f64)) {
        for x in [a.0, a.1] {
            for y in [b.0, b.1] {
                let (p, e) = two_prod(x, y);
                self.add(e);
                self.add(p);
            }
        }
    }

    /// The sign of the exact sum: -1, 0 or 1.
    pub fn sign(&self) -> i32 {
        match self.terms[..self.len].last() {
            Some(&v) if v > 0.0 => 1,
            Some(&v) if v < 0.0 => -1,
            _ => 0,
        }
    }
}

/// The exact sign of `(a - p)·(b - p)` for 2D points.
pub fn dot_sign_2d(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> i32 {
    let t1 = (a[0] - p[0]) * (b[0] - p[0]);
    let t2 = (a[1] - p[1]) * (b[1] - p[1]);
    let det = t1 + t2;
    let bound = 8.0 * f64::EPSILON * (t1.abs() + t2.abs());
    if det > bound {
        return 1;
    }
    if det < -bound {
        return -1;
    }
    let mut e = Expansion::new();
    for k in 0..2 {
        e.add_product2(two_diff(a[k], p[k]), two_diff(b[k], p[k]));
    }
    e.sign()
}

/// The exact sign of `(a - p)·(b - p)` for 3D points.
pub fn dot_sign_3d(a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> i32 {
    let t = [0, 1, 2].map(|k| (a[k] - p[k]) * (b[k] - p[k]));
    let det = t[0] + t[1] + t[2];
    let bound = 8.0 * f64::EPSILON * (t[0].abs() + t[1].abs() + t[2].abs());
    if det > bound {
        return 1;
    }
    if det < -bound {
        return -1;
    }
    let mut e = Expansion::new();
    for k in 0..3 {
        e.add_product2(two_diff(a[k], p[k]), two_diff(b[k], p[k]));
    }
    e.sign()
}

/// How many components a [`DynExpansion`] keeps inline before moving to the heap: enough for
/// every intermediate of the degree-6 facet predicates on ordinary inputs (they stay under a
/// dozen terms), so the exact stage normally does not allocate.
const INLINE: usize = 16;

/// Component storage with a small inline buffer and a heap fallback of unbounded length.
#[derive(Clone, Debug)]
enum Terms {
    Inline(usize, [f64; INLINE]),
    Heap(Vec<f64>),
}

impl Terms {
    fn with_capacity(n: usize) -> Self {
        if n <= INLINE {
            Terms::Inline(0, [0.0; INLINE])
        } else {
            Terms::Heap(Vec::with_capacity(n))
        }
    }

    fn push(&mut self, x: f64) {
        match self {
            Terms::Inline(len, buf) if *len < INLINE => {
                buf[*len] = x;
                *len += 1;
            }
            Terms::Inline(_, buf) => {
                let mut v = Vec::with_capacity(2 * INLINE);
                v.extend_from_slice(buf);
                v.push(x);
                *self = Terms::Heap(v);
            }
            Terms::Heap(v) => v.push(x),
        }
    }

    fn as_slice(&self) -> &[f64] {
        match self {
            Terms::Inline(len, buf) => &buf[..*len],
            Terms::Heap(v) => v,
        }
    }

    fn as_mut_slice(&mut self) -> &mut [f64] {
        match self {
            Terms::Inline(len, buf) => &mut buf[..*len],
            Terms::Heap(v) => v,
        }
    }

    fn truncate(&mut self, n: usize) {
        match self {
            Terms::Inline(len, _) => *len = (*len).min(n),
            Terms::Heap(v) => v.truncate(n),
        }
    }
}

/// An exact real number as a growable expansion: a sum of non-overlapping, non-zero doubles
/// stored in increasing magnitude (Shewchuk's representation), so the largest term alone gives
/// the sign. Unlike the fixed [`Expansion`], it has no length bound, which is what products of
/// degree six need (the 3D facet predicates). It is meant for the exact stage behind a float
/// filter: results of up to 16 components live inline, longer ones on the heap.
///
/// Exact barring overflow and underflow (like all of Shewchuk's arithmetic); relies on IEEE
/// round-to-nearest-even, which Rust guarantees for `f64`.
#[derive(Clone, Debug)]
pub struct DynExpansion {
    /// Zero-free, non-overlapping, increasing magnitude; empty means zero.
    terms: Terms,
}

impl Default for DynExpansion {
    fn default() -> Self {
        Self::zero()
    }
}

/// Equality of the component lists, not of the values: equal values may be split into
/// components differently (compare values with `a.sub(&b).sign() == 0`).
impl PartialEq for DynExpansion {
    fn eq(&self, other: &Self) -> bool {
        self.terms() == other.terms()
    }
}

impl DynExpansion {
    /// Zero.
    pub fn zero() -> Self {
        DynExpansion {
            terms: Terms::with_capacity(0),
        }
    }

    /// The double `x` exactly.
    pub fn from_f64(x: f64) -> Self {
        Self::from_pair(x, 0.0)
    }

    /// The exact difference `a - b` (at most two terms).
    pub fn from_diff(a: f64, b: f64) -> Self {
        let (hi, lo) = two_diff(a, b);
        Self::from_pair(hi, lo)
    }

    /// The exact product `a * b` (at most two terms).
    pub fn from_product(a: f64, b: f64) -> Self {
        let (hi, lo) = two_prod(a, b);
        Self::from_pair(hi, lo)
    }

    /// `hi + lo` where `lo` is the rounding error of `hi` (already non-overlapping).
    fn from_pair(hi: f64, lo: f64) -> Self {
        let mut terms = Terms::with_capacity(2);
        for t in [lo, hi] {
            if t != 0.0 {
                terms.push(t);
            }
        }
        DynExpansion { terms }
    }

    /// The components, smallest magnitude first (empty for zero).
    pub fn terms(&self) -> &[f64] {
        self.terms.as_slice()
    }

    /// The sign of the exact value: -1, 0 or 1.
    pub fn sign(&self) -> i32 {
        match self.terms().last() {
            Some(&v) if v > 0.0 => 1,
            Some(&v) if v < 0.0 => -1,
            _ => 0,
        }
    }

    /// A double close to the exact value (the rounded sum of the components); only for
    /// magnitudes, never for decisions.
    pub fn estimate(&self) -> f64 {
        self.terms().iter().sum()
    }

    /// The exact sum (Shewchuk's Fast-Expansion-Sum with zero elimination: the components of
    /// both, taken in increasing magnitude, run through one Two-Sum sweep).
    pub fn add(&self, other: &DynExpansion) -> DynExpansion {
        let (e, f) = (self.terms(), other.terms());
        if e.is_empty() {
            return other.clone();
        }
        if f.is_empty() {
            return self.clone();
        }
        let (mut i, mut j) = (0, 0);
        let mut next = || {
            if j == f.len() || (i < e.len() && e[i].abs() < f[j].abs()) {
                i += 1;
                e[i - 1]
            } else {
                j += 1;
                f[j - 1]
            }
        };
        let mut out = Terms::with_capacity(e.len() + f.len());
        let mut q = next();
        for _ in 1..e.len() + f.len() {
            let (s, err) = two_sum(q, next());
            if err != 0.0 {
                out.push(err);
            }
            q = s;
        }
        if q != 0.0 {
            out.push(q);
        }
        DynExpansion { terms: out }
    }

    /// The exact negation.
    pub fn neg(&self) -> DynExpansion {
        let mut out = self.clone();
        for t in out.terms.as_mut_slice() {
            *t = -*t;
        }
        out
    }

    /// The exact difference `self - other`.
    pub fn sub(&self, other: &DynExpansion) -> DynExpansion {
        self.add(&other.neg())
    }

    /// The exact product with one double (Shewchuk's Scale-Expansion with zero elimination).
    pub fn scale(&self, b: f64) -> DynExpansion {
        let mut out = Terms::with_capacity(2 * self.terms().len());
        let Some((&first, rest)) = self.terms().split_first() else {
            return DynExpansion::zero();
        };
        let (mut q, lo) = two_prod(first, b);
        if lo != 0.0 {
            out.push(lo);
        }
        for &t in rest {
            let (p1, p0) = two_prod(t, b);
            let (s, err) = two_sum(q, p0);
            if err != 0.0 {
                out.push(err);
            }
            let (s2, err2) = two_sum(p1, s);
            if err2 != 0.0 {
                out.push(err2);
            }
            q = s2;
        }
        if q != 0.0 {
            out.push(q);
        }
        DynExpansion { terms: out }
    }

    /// The exact product of two expansions: the shorter one's components each scale the
    /// other, the partial products are summed, and the result is compressed so that chains of
    /// products stay short.
    pub fn mul(&self, other: &DynExpansion) -> DynExpansion {
        let (long, short) = if self.terms().len() >= other.terms().len() {
            (self, other)
        } else {
            (other, self)
        };
        let Some((&first, rest)) = short.terms().split_first() else {
            return DynExpansion::zero();
        };
        let mut acc = long.scale(first);
        for &t in rest {
            acc = acc.add(&long.scale(t));
        }
        acc.compress();
        acc
    }

    /// Rewrites the expansion in place with as few components as its value allows
    /// (Shewchuk's Compress); the value is unchanged. Both sweeps only overwrite components
    /// they have already consumed, so no buffer is needed.
    pub fn compress(&mut self) {
        let len = self.terms().len();
        if len < 2 {
            return;
        }
        let e = self.terms.as_mut_slice();
        // Top-down sweep: gather the large parts at the top, carrying the remainders down.
        let mut bottom = len - 1;
        let mut q = e[bottom];
        for i in (0..len - 1).rev() {
            let (s, err) = two_sum(q, e[i]);
            if err != 0.0 {
                e[bottom] = s;
                bottom -= 1;
                q = err;
            } else {
                q = s;
            }
        }
        // Bottom-up sweep: the final non-overlapping components, zero-free, packed at the start.
        let mut top = 0;
        for h in bottom + 1..len {
            let (s, err) = two_sum(e[h], q);
            if err != 0.0 {
                e[top] = err;
                top += 1;
            }
            q = s;
        }
        if q != 0.0 {
            e[top] = q;
            top += 1;
        }
        self.terms.truncate(top);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_dot_sign_on_the_circle_is_zero() {
        // p on the circle with diameter ab (Thales): the dot product is exactly 0.
        assert_eq!(dot_sign_2d([0.0, 0.0], [2.0, 0.0], [1.0, 1.0]), 0);
        assert_eq!(dot_sign_2d([0.0, 0.0], [2.0, 0.0], [1.0, 0.5]), -1);
        assert_eq!(dot_sign_2d([0.0, 0.0], [2.0, 0.0], [1.0, 1.5]), 1);
    }

    #[test]
    fn exact_dot_sign_beats_rounding() {
        // A point a hair inside / outside the diametral circle, where the float sum cancels.
        let a = [0.1, 0.1];
        let b = [0.3, 0.3];
        let p_in = [0.1, 0.3 - 1e-17];
        let s = dot_sign_2d(a, b, p_in);
        // (0.1-0.1)*(0.3-0.1) + (0.1-p1)*(0.3-p1): first term 0, second negative iff p1 in (0.1, 0.3).
        assert_eq!(s, if p_in[1] < 0.3 { -1 } else { 0 });
        let mut e = Expansion::new();
        e.add(1e300);
        e.add(1.0);
        e.add(-1e300);
        assert_eq!(e.sign(), 1);
    }

    /// A small deterministic generator (splitmix64), so failures reproduce.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        }

        fn below(&mut self, n: u64) -> i64 {
            (self.next() % n) as i64
        }

        /// `X * 2^s` with `|X| < 2^bits`, `s` in `lo..=hi`: exactly `X * 2^(s - lo)` units
        /// of `2^lo`, returned with that integer.
        fn dyadic(&mut self, bits: u32, lo: i32, hi: i32) -> (f64, i128) {
            let x = self.below(1 << bits) - (1 << (bits - 1));
            let s = lo + self.below((hi - lo + 1) as u64) as i32;
            let units = (x as i128) << (s - lo);
            ((x as f64) * 2f64.powi(s), units)
        }
    }

    /// The exact value of `e` in units of `2^lo`, checking the representation invariants on
    /// the way: zero-free, increasing magnitude, non-overlapping.
    fn value_in_units(e: &DynExpansion, lo: i32) -> i128 {
        let t = e.terms();
        for w in t.windows(2) {
            assert!(
                w[0] != 0.0 && w[0].abs() < w[1].abs(),
                "not increasing: {t:?}"
            );
            // Non-overlapping: the smaller term is below the lowest set bit of the larger.
            let low_bit = {
                let (m, ex) = frexp_int(w[1]);
                ex + m.trailing_zeros() as i32
            };
            assert!(w[0].abs() < 2f64.powi(low_bit), "overlapping terms: {t:?}");
        }
        t.iter()
            .map(|&v| {
                let scaled = v * 2f64.powi(-lo);
                assert_eq!(scaled.fract(), 0.0, "term {v} below the unit 2^{lo}");
                scaled as i128
            })
            .sum()
    }

    /// `|v| = m * 2^ex` with `m` the integer significand (v finite, non-zero).
    fn frexp_int(v: f64) -> (u64, i32) {
        let bits = v.abs().to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1 << 52) - 1);
        if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1 << 52), exp - 1075)
        }
    }

    #[test]
    fn dyn_expansion_matches_i128_on_wide_exponent_ranges() {
        let mut rng = Rng(7);
        let mut two_term = 0;
        for _ in 0..20_000 {
            // 40-bit significands scaled by 2^-20 .. 2^0: a difference can need ~60 bits, so
            // many are genuinely two-term expansions.
            let mut v = [(0.0, 0i128); 4];
            for x in &mut v {
                *x = rng.dyadic(40, -20, 0);
            }
            let d1 = DynExpansion::from_diff(v[0].0, v[1].0);
            let d2 = DynExpansion::from_diff(v[2].0, v[3].0);
            assert_eq!(value_in_units(&d1, -20), v[0].1 - v[1].1);
            two_term += usize::from(d1.terms().len() == 2);
            let prod = d1.mul(&d2);
            let want = (v[0].1 - v[1].1) * (v[2].1 - v[3].1);
            assert_eq!(value_in_units(&prod, -40), want);
            assert_eq!(prod.sign(), want.signum() as i32);
            // A sum of two products that often cancels to (nearly) zero.
            let other = d2
                .mul(&d1)
                .sub(&DynExpansion::from_f64(v[0].0).scale(v[2].0));
            let sum = prod.sub(&other);
            let want_sum = want - (want - v[0].1 * v[2].1);
            assert_eq!(value_in_units(&sum, -40), want_sum);
            assert_eq!(sum.sign(), want_sum.signum() as i32);
            let mut compressed = sum.clone();
            compressed.compress();
            assert_eq!(value_in_units(&compressed, -40), want_sum);
            assert!(compressed.terms().len() <= sum.terms().len());
        }
        // The point of the wide range: many differences are not representable as one double.
        assert!(two_term > 500, "only {two_term} inexact differences");
    }

    #[test]
    fn dyn_expansion_degree_three_and_cancellation() {
        let mut rng = Rng(11);
        for _ in 0..5_000 {
            let (a, ai) = rng.dyadic(12, -20, 8);
            let (b, bi) = rng.dyadic(12, -20, 8);
            let (c, ci) = rng.dyadic(12, -20, 8);
            let ab = DynExpansion::from_diff(a, b);
            let cube = ab.mul(&ab).mul(&DynExpansion::from_diff(b, c));
            let want = (ai - bi) * (ai - bi) * (bi - ci);
            assert_eq!(value_in_units(&cube, -60), want);
            // (a-b)^2 - a^2 + 2ab - b^2 is exactly zero.
            let zero = ab
                .mul(&ab)
                .sub(&DynExpansion::from_product(a, a))
                .add(&DynExpansion::from_product(a, b).scale(2.0))
                .sub(&DynExpansion::from_product(b, b));
            assert_eq!(zero.sign(), 0);
            assert!(zero.terms().is_empty());
        }
        assert_eq!(
            DynExpansion::zero()
                .mul(&DynExpansion::from_f64(3.0))
                .sign(),
            0
        );
        assert_eq!(DynExpansion::from_diff(1e300, -1e300).estimate(), 2e300);
        let tiny = DynExpansion::from_f64(1e300)
            .add(&DynExpansion::from_f64(1.0))
            .sub(&DynExpansion::from_f64(1e300));
        assert_eq!(tiny.terms(), &[1.0]);
    }

    #[test]
    fn dyn_expansion_spills_to_the_heap_exactly() {
        // 18 components 2^54 apart (from 2^500 down, so products stay clear of underflow):
        // longer than the inline buffer, and long products.
        let mut a = DynExpansion::zero();
        let mut b = DynExpansion::zero();
        for k in 0..18 {
            a = a.add(&DynExpansion::from_f64(3.0 * 2f64.powi(500 - 54 * k)));
            b = b.add(&DynExpansion::from_f64(-5.0 * 2f64.powi(500 - 54 * k - 17)));
        }
        assert_eq!(a.terms().len(), 18);
        assert!(a.terms().len() > INLINE);
        // (a + b)^2 - a^2 - 2ab - b^2 and (a + b)(a - b) - (a^2 - b^2) are exactly zero.
        let (aa, bb, ab) = (a.mul(&a), b.mul(&b), a.mul(&b));
        let s = a.add(&b);
        assert_eq!(s.mul(&s).sub(&aa).sub(&ab.scale(2.0)).sub(&bb).sign(), 0);
        assert_eq!(s.mul(&a.sub(&b)).sub(&aa.sub(&bb)).sign(), 0);
        // ... and a change far below the leading bits is still seen.
        let smallest = DynExpansion::from_f64(aa.terms()[0].abs() / 4.0);
        assert_eq!(aa.sub(&aa.add(&smallest)).sign(), -1);
        assert_eq!(aa.add(&smallest).sub(&aa), smallest);
        let mut c = s.mul(&s);
        let before = c.clone();
        c.compress();
        assert_eq!(c.sub(&before).sign(), 0);
        assert_eq!(c.neg().add(&before).sign(), 0);
    }
}
