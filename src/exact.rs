//! Exact sign of small polynomial expressions in floating-point inputs, by floating-point
//! expansions (Shewchuk's two-sum / two-product). Used behind a fast filter:
//!
//! - [`orient2d_exact`], [`incircle_exact`], [`orient3d_exact`] and [`insphere_exact`], the
//!   exact stage of the orientation and in-circle/in-sphere predicates of
//!   [`crate::predicates`]. They work in a per-thread scratch buffer that is grown on demand
//!   and reused, and compress every minor before it is multiplied further, so a call neither
//!   allocates (after the first) nor clears large stack arrays; their results are exact for any
//!   inputs barring overflow and underflow.
//! - the fixed [`Expansion`] for the dot-product sign of the encroachment tests;
//! - the growable [`DynExpansion`] for the degree-6 facet predicates of 3D meshing
//!   (`predicates::in_diametral_ball_tri`).

use std::cell::Cell;

/// `a + b = hi + lo` exactly.
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// `a + b = hi + lo` exactly when `|a| >= |b|` or `a == 0` (Dekker's Fast-Two-Sum).
#[inline]
pub fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// `a - b = hi + lo` exactly.
#[inline]
pub fn two_diff(a: f64, b: f64) -> (f64, f64) {
    let s = a - b;
    let bv = a - s;
    let av = s + bv;
    (s, (a - av) + (bv - b))
}

/// `a * b = hi + lo` exactly (barring underflow and overflow): a fused multiply-add where the
/// target has one, Dekker's product with Veltkamp's split otherwise (without hardware FMA,
/// `mul_add` is a slow library call).
#[inline]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    #[cfg(target_feature = "fma")]
    {
        (p, a.mul_add(b, -p))
    }
    #[cfg(not(target_feature = "fma"))]
    {
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }
}

/// Veltkamp's split of `a` into two halves of at most 26 significant bits each.
#[cfg(not(target_feature = "fma"))]
#[inline]
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// Shewchuk's Fast-Expansion-Sum with zero elimination: writes `e + f` (or `e - f` when
/// `negate_f`) into `out`, which must hold `e.len() + f.len()` components, and returns the
/// number written. Inputs and output are zero-free, non-overlapping, in increasing magnitude.
fn sum_into(e: &[f64], f: &[f64], negate_f: bool, out: &mut [f64]) -> usize {
    let sf = if negate_f { -1.0 } else { 1.0 };
    let (mut i, mut j) = (0, 0);
    let mut next = || {
        if j == f.len() || (i < e.len() && e[i].abs() < f[j].abs()) {
            i += 1;
            e[i - 1]
        } else {
            j += 1;
            sf * f[j - 1]
        }
    };
    let total = e.len() + f.len();
    if total == 0 {
        return 0;
    }
    let mut n = 0;
    let mut q = next();
    for _ in 1..total {
        let (s, err) = two_sum(q, next());
        if err != 0.0 {
            out[n] = err;
            n += 1;
        }
        q = s;
    }
    if q != 0.0 {
        out[n] = q;
        n += 1;
    }
    n
}

/// Shewchuk's Scale-Expansion with zero elimination: writes `e * b` into `out`, which must
/// hold `2 * e.len()` components, and returns the number written.
fn scale_into(e: &[f64], b: f64, out: &mut [f64]) -> usize {
    let Some((&first, rest)) = e.split_first() else {
        return 0;
    };
    let mut n = 0;
    let (mut q, lo) = two_prod(first, b);
    if lo != 0.0 {
        out[n] = lo;
        n += 1;
    }
    for &t in rest {
        let (p1, p0) = two_prod(t, b);
        let (s, err) = two_sum(q, p0);
        if err != 0.0 {
            out[n] = err;
            n += 1;
        }
        let (s2, err2) = fast_two_sum(p1, s);
        if err2 != 0.0 {
            out[n] = err2;
            n += 1;
        }
        q = s2;
    }
    if q != 0.0 {
        out[n] = q;
        n += 1;
    }
    n
}

/// Rewrites the expansion `e` in place with as few components as its value allows
/// (Shewchuk's Compress) and returns the new length; the value is unchanged. Both sweeps only
/// overwrite components they have already consumed, so no buffer is needed.
fn compress(e: &mut [f64]) -> usize {
    let len = e.len();
    if len < 2 {
        return len;
    }
    // Top-down sweep: gather the large parts at the top, carrying the remainders down.
    let mut bottom = len - 1;
    let mut q = e[bottom];
    for i in (0..len - 1).rev() {
        let (s, err) = fast_two_sum(q, e[i]);
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
        let (s, err) = fast_two_sum(e[h], q);
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
    top
}

/// `x·y - z·w` exactly into `out` (at most four components, zero-free), returning the count.
#[inline(always)]
fn two_two_diff(x: f64, y: f64, z: f64, w: f64, out: &mut [f64; 4]) -> usize {
    let (p1, p0) = two_prod(x, y);
    let (q1, q0) = two_prod(z, w);
    sum_into(&[p0, p1], &[q0, q1], true, out)
}

thread_local! {
    /// The exact predicates' working storage, one per thread: taken for a call and put back
    /// after, so it is cleared only when it grows (a re-entrant or panicking call just starts
    /// a fresh one).
    static SCRATCH: Cell<Vec<f64>> = const { Cell::new(Vec::new()) };
}

/// An expansion held in a [`Scratch`]: `len` components from index `at`.
#[derive(Clone, Copy)]
struct Span {
    at: usize,
    len: usize,
}

/// A stack of expansions in one buffer: every operation appends its result above the
/// operands, so the exact stage of a predicate is a straight sequence of appends, and the whole
/// stack is dropped at once when the predicate returns.
struct Scratch {
    t: Vec<f64>,
    top: usize,
}

impl Scratch {
    /// Runs `f` with this thread's scratch buffer.
    fn with<R>(f: impl FnOnce(&mut Scratch) -> R) -> R {
        let mut s = Scratch {
            t: SCRATCH.take(),
            top: 0,
        };
        let r = f(&mut s);
        SCRATCH.set(s.t);
        r
    }

    /// Makes room for `n` more components above the top.
    #[inline(always)]
    fn reserve(&mut self, n: usize) {
        if self.t.len() < self.top + n {
            self.grow(n);
        }
    }

    #[cold]
    #[inline(never)]
    fn grow(&mut self, n: usize) {
        let need = self.top + n;
        self.t.resize(need.max(2 * self.t.len()).max(512), 0.0);
    }

    /// Claims the `n` components just written above the top.
    #[inline]
    fn claim(&mut self, n: usize) -> Span {
        let s = Span {
            at: self.top,
            len: n,
        };
        self.top += n;
        s
    }

    #[inline]
    fn get(&self, e: Span) -> &[f64] {
        &self.t[e.at..e.at + e.len]
    }

    /// The exact difference `a - b`.
    #[inline(always)]
    fn diff(&mut self, a: f64, b: f64) -> Span {
        self.reserve(2);
        let (hi, lo) = two_diff(a, b);
        let at = self.top;
        let mut n = 0;
        if lo != 0.0 {
            self.t[at] = lo;
            n = 1;
        }
        if hi != 0.0 {
            self.t[at + n] = hi;
            n += 1;
        }
        self.claim(n)
    }

    /// The exact `e + f` (`e - f` when `negate_f`); operands must lie below the top.
    fn sum(&mut self, e: Span, f: Span, negate_f: bool) -> Span {
        self.reserve(e.len + f.len);
        let (lo, hi) = self.t.split_at_mut(self.top);
        let n = sum_into(
            &lo[e.at..e.at + e.len],
            &lo[f.at..f.at + f.len],
            negate_f,
            hi,
        );
        self.claim(n)
    }

    /// The exact product, compressed: the shorter operand's components each scale the longer
    /// one, and the partial products are accumulated (each partial sum is written above the
    /// previous one rather than copied back: the space is reclaimed when the predicate ends).
    fn mul(&mut self, e: Span, f: Span) -> Span {
        let (long, short) = if e.len >= f.len { (e, f) } else { (f, e) };
        let mut acc = Span {
            at: self.top,
            len: 0,
        };
        for j in 0..short.len {
            let b = self.t[short.at + j];
            self.reserve(2 * long.len + acc.len + 2 * long.len);
            let scaled_at = self.top;
            let (lo, hi) = self.t.split_at_mut(scaled_at);
            let ns = scale_into(&lo[long.at..long.at + long.len], b, hi);
            if acc.len == 0 {
                acc = self.claim(ns);
                continue;
            }
            let scaled = self.claim(ns);
            acc = self.sum(acc, scaled, false);
        }
        let n = compress(&mut self.t[acc.at..acc.at + acc.len]);
        self.top = acc.at + n;
        Span { at: acc.at, len: n }
    }

    /// `x·y ± z·w`, compressed.
    fn det2(&mut self, x: Span, y: Span, z: Span, w: Span, negate: bool) -> Span {
        let p = self.mul(x, y);
        let q = self.mul(z, w);
        let s = self.sum(p, q, negate);
        self.compressed(s)
    }

    /// `Σ sᵢ·xᵢ·yᵢ` for three terms with signs `sᵢ` (`true` = minus), compressed.
    fn dot3(&mut self, t: [(Span, Span, bool); 3]) -> Span {
        let [p, q, r] = t.map(|(x, y, _)| self.mul(x, y));
        let pq = self.sum(p, q, t[0].2 != t[1].2);
        let s = self.sum(pq, r, t[0].2 != t[2].2);
        let s = self.compressed(s);
        if t[0].2 {
            self.negate(s);
        }
        s
    }

    /// Compresses `e` (which must be the topmost expansion) in place.
    fn compressed(&mut self, e: Span) -> Span {
        debug_assert_eq!(e.at + e.len, self.top);
        let n = compress(&mut self.t[e.at..e.at + e.len]);
        self.top = e.at + n;
        Span { at: e.at, len: n }
    }

    fn negate(&mut self, e: Span) {
        for x in &mut self.t[e.at..e.at + e.len] {
            *x = -*x;
        }
    }

    /// The largest component, whose sign is that of the exact value (0 for zero): after
    /// compression it approximates the value to within one unit in the last place.
    fn value(&mut self, e: Span) -> f64 {
        self.get(e).last().copied().unwrap_or(0.0)
    }
}

/// The exact `orient2d` of [`crate::predicates::orient2d`]: `(a - c) × (b - c)`, positive when
/// `a, b, c` are counter-clockwise. Returns a double with the exact sign (0 only when the
/// determinant is exactly 0) that approximates the determinant.
#[inline(never)]
pub fn orient2d_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    Scratch::with(|s| {
        let [acx, acy, bcx, bcy] =
            [(a, 0), (a, 1), (b, 0), (b, 1)].map(|(p, k)| s.diff(p[k], c[k]));
        let d = s.det2(acx, bcy, acy, bcx, true);
        s.value(d)
    })
}

/// The exact `incircle` of [`crate::predicates::incircle`]: positive when `d` is inside the
/// circle through the counter-clockwise `a, b, c`. Exact sign, approximate magnitude.
#[inline(never)]
pub fn incircle_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    // The usual case, as in `orient3d_exact`: every coordinate difference is exact (nearby
    // points; refinement meets it at every cocircular grid of Steiner points, where the exact
    // stage decides a zero), and the determinant of the rounded differences is the exact one,
    // at most 96 components, on the stack.
    let diff = |p: [f64; 2], k: usize| two_diff(p[k], d[k]);
    let dd = [a, b, c].map(|p| [diff(p, 0), diff(p, 1)]);
    if dd.iter().all(|v| v[0].1 == 0.0 && v[1].1 == 0.0) {
        let [[adx, ady], [bdx, bdy], [cdx, cdy]] = dd.map(|v| v.map(|x| x.0));
        // (x² + y²)·m for the lifted point (x, y) and its opposite minor m.
        let lifted = |x: f64, y: f64, m: &[f64]| {
            let mut xm = [0.0; 8];
            let nx = scale_into(m, x, &mut xm);
            let mut xxm = [0.0; 16];
            let nxx = scale_into(&xm[..nx], x, &mut xxm);
            let mut ym = [0.0; 8];
            let ny = scale_into(m, y, &mut ym);
            let mut yym = [0.0; 16];
            let nyy = scale_into(&ym[..ny], y, &mut yym);
            let mut out = [0.0; 32];
            let n = sum_into(&xxm[..nxx], &yym[..nyy], false, &mut out);
            (out, n)
        };
        let mut m = [0.0; 4];
        let n = two_two_diff(bdx, cdy, cdx, bdy, &mut m);
        let (t1, n1) = lifted(adx, ady, &m[..n]);
        let n = two_two_diff(cdx, ady, adx, cdy, &mut m);
        let (t2, n2) = lifted(bdx, bdy, &m[..n]);
        let n = two_two_diff(adx, bdy, bdx, ady, &mut m);
        let (t3, n3) = lifted(cdx, cdy, &m[..n]);
        let mut s12 = [0.0; 64];
        let n12 = sum_into(&t1[..n1], &t2[..n2], false, &mut s12);
        let mut det = [0.0; 96];
        let n = sum_into(&s12[..n12], &t3[..n3], false, &mut det);
        return det[..n].last().copied().unwrap_or(0.0);
    }
    Scratch::with(|s| {
        let [adx, ady] = [0, 1].map(|k| s.diff(a[k], d[k]));
        let [bdx, bdy] = [0, 1].map(|k| s.diff(b[k], d[k]));
        let [cdx, cdy] = [0, 1].map(|k| s.diff(c[k], d[k]));
        let bc = s.det2(bdx, cdy, cdx, bdy, true);
        let ca = s.det2(cdx, ady, adx, cdy, true);
        let ab = s.det2(adx, bdy, bdx, ady, true);
        let alift = s.det2(adx, adx, ady, ady, false);
        let blift = s.det2(bdx, bdx, bdy, bdy, false);
        let clift = s.det2(cdx, cdx, cdy, cdy, false);
        let det = s.dot3([(alift, bc, false), (blift, ca, false), (clift, ab, false)]);
        s.value(det)
    })
}

/// The exact `orient3d` of [`crate::predicates::orient3d`], with Shewchuk's sign: positive
/// when `d` lies below the plane of `a, b, c` seen counter-clockwise from above. Exact sign,
/// approximate magnitude.
#[inline(never)]
pub fn orient3d_exact(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    // The usual case: every coordinate difference is exact (nearby points), and the
    // determinant of the rounded differences is the exact one, at most 24 components, so
    // small stack arrays hold it (Shewchuk's stage B without its error bound).
    let diff = |p: [f64; 3], k: usize| two_diff(p[k], d[k]);
    let dd = [a, b, c].map(|p| [0, 1, 2].map(|k| diff(p, k)));
    if dd.iter().all(|v| v.iter().all(|x| x.1 == 0.0)) {
        let [[adx, ady, adz], [bdx, bdy, bdz], [cdx, cdy, cdz]] = dd.map(|v| v.map(|x| x.0));
        let minor = |x: f64, y: f64, z: f64, w: f64, h: f64| {
            let mut m = [0.0; 4];
            let n = two_two_diff(x, y, z, w, &mut m);
            let mut out = [0.0; 8];
            let n = scale_into(&m[..n], h, &mut out);
            (out, n)
        };
        let (t1, n1) = minor(bdx, cdy, cdx, bdy, adz);
        let (t2, n2) = minor(cdx, ady, adx, cdy, bdz);
        let (t3, n3) = minor(adx, bdy, bdx, ady, cdz);
        let mut s12 = [0.0; 16];
        let n12 = sum_into(&t1[..n1], &t2[..n2], false, &mut s12);
        let mut det = [0.0; 24];
        let n = sum_into(&s12[..n12], &t3[..n3], false, &mut det);
        return det[..n].last().copied().unwrap_or(0.0);
    }
    Scratch::with(|s| {
        let [adx, ady, adz] = [0, 1, 2].map(|k| s.diff(a[k], d[k]));
        let [bdx, bdy, bdz] = [0, 1, 2].map(|k| s.diff(b[k], d[k]));
        let [cdx, cdy, cdz] = [0, 1, 2].map(|k| s.diff(c[k], d[k]));
        let bc = s.det2(bdx, cdy, cdx, bdy, true);
        let ca = s.det2(cdx, ady, adx, cdy, true);
        let ab = s.det2(adx, bdy, bdx, ady, true);
        let det = s.dot3([(adz, bc, false), (bdz, ca, false), (cdz, ab, false)]);
        s.value(det)
    })
}

/// The exact `insphere` of [`crate::predicates::insphere`]: positive when `e` is inside the
/// sphere through `a, b, c, d` for `orient3d(a, b, c, d) > 0`. Exact sign, approximate
/// magnitude.
#[inline(never)]
pub fn insphere_exact(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
    Scratch::with(|s| {
        let [aex, aey, aez] = [0, 1, 2].map(|k| s.diff(a[k], e[k]));
        let [bex, bey, bez] = [0, 1, 2].map(|k| s.diff(b[k], e[k]));
        let [cex, cey, cez] = [0, 1, 2].map(|k| s.diff(c[k], e[k]));
        let [dex, dey, dez] = [0, 1, 2].map(|k| s.diff(d[k], e[k]));
        let ab = s.det2(aex, bey, bex, aey, true);
        let bc = s.det2(bex, cey, cex, bey, true);
        let cd = s.det2(cex, dey, dex, cey, true);
        let da = s.det2(dex, aey, aex, dey, true);
        let ac = s.det2(aex, cey, cex, aey, true);
        let bd = s.det2(bex, dey, dex, bey, true);
        let abc = s.dot3([(aez, bc, false), (bez, ac, true), (cez, ab, false)]);
        let bcd = s.dot3([(bez, cd, false), (cez, bd, true), (dez, bc, false)]);
        let cda = s.dot3([(cez, da, false), (dez, ac, false), (aez, cd, false)]);
        let dab = s.dot3([(dez, ab, false), (aez, bd, false), (bez, da, false)]);
        let lift = |s: &mut Scratch, x: Span, y: Span, z: Span| {
            s.dot3([(x, x, false), (y, y, false), (z, z, false)])
        };
        let alift = lift(s, aex, aey, aez);
        let blift = lift(s, bex, bey, bez);
        let clift = lift(s, cex, cey, cez);
        let dlift = lift(s, dex, dey, dez);
        let left = s.det2(dlift, abc, clift, dab, true);
        let right = s.det2(blift, cda, alift, bcd, true);
        let det = s.sum(left, right, false);
        let det = s.compressed(det);
        s.value(det)
    })
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
    /// `n` zeros, to be overwritten and truncated.
    fn zeroed(n: usize) -> Self {
        if n <= INLINE {
            Terms::Inline(n, [0.0; INLINE])
        } else {
            Terms::Heap(vec![0.0; n])
        }
    }

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
        self.sum(other, false)
    }

    /// `self + other`, or `self - other` when `negate`.
    fn sum(&self, other: &DynExpansion, negate: bool) -> DynExpansion {
        let (e, f) = (self.terms(), other.terms());
        let mut out = Terms::zeroed(e.len() + f.len());
        let n = sum_into(e, f, negate, out.as_mut_slice());
        out.truncate(n);
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
        self.sum(other, true)
    }

    /// The exact product with one double (Shewchuk's Scale-Expansion with zero elimination).
    pub fn scale(&self, b: f64) -> DynExpansion {
        let e = self.terms();
        let mut out = Terms::zeroed(2 * e.len());
        let n = scale_into(e, b, out.as_mut_slice());
        out.truncate(n);
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
    /// (Shewchuk's Compress); the value is unchanged.
    pub fn compress(&mut self) {
        let n = compress(self.terms.as_mut_slice());
        self.terms.truncate(n);
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

    #[test]
    fn exact_predicates_grow_the_scratch_and_match_robust() {
        use robust::Coord3D;
        let c3 = |p: [f64; 3]| Coord3D {
            x: p[0],
            y: p[1],
            z: p[2],
        };
        let sgn = |x: f64| (x > 0.0) as i32 - (x < 0.0) as i32;
        let mut rng = Rng(29);
        let mut longest = 0;
        for _ in 0..3000 {
            // Every coordinate at its own scale, 2^-90 .. 2^90: the exact values need long
            // expansions, longer than the first scratch buffer.
            let mut pt = || {
                [0; 3].map(|_| {
                    let (x, _) = rng.dyadic(53, 0, 0);
                    x * 2f64.powi(rng.below(181) as i32 - 90 - 52)
                })
            };
            let [a, b, c, d, e] = [pt(), pt(), pt(), pt(), pt()];
            let want = sgn(robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e)));
            assert_eq!(sgn(insphere_exact(a, b, c, d, e)), want);
            let want = sgn(robust::orient3d(c3(a), c3(b), c3(c), c3(d)));
            assert_eq!(sgn(orient3d_exact(a, b, c, d)), want);
            let c2 = |p: [f64; 3]| robust::Coord { x: p[0], y: p[1] };
            let want = sgn(robust::incircle(c2(a), c2(b), c2(c), c2(d)));
            assert_eq!(
                sgn(incircle_exact(
                    [a[0], a[1]],
                    [b[0], b[1]],
                    [c[0], c[1]],
                    [d[0], d[1]]
                )),
                want
            );
            let v = SCRATCH.take();
            longest = longest.max(v.len());
            SCRATCH.set(v);
        }
        assert!(longest > 512, "the scratch never grew: {longest}");
    }

    /// The stack path of `incircle_exact` (every coordinate difference exact) agrees with
    /// `robust` on points of one dyadic grid at any scale and offset: on circles through grid
    /// points (the cocircular quadruples refinement meets), just off them, and at random.
    #[test]
    fn incircle_exact_on_grids_matches_robust_and_finds_cocircular_points() {
        let sgn = |x: f64| (x > 0.0) as i32 - (x < 0.0) as i32;
        let c2 = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
        // Integer points on the circle of radius 25 about the origin.
        let circle: Vec<[i64; 2]> = (-25i64..=25)
            .flat_map(|x| (-25i64..=25).map(move |y| [x, y]))
            .filter(|&[x, y]| x * x + y * y == 625)
            .collect();
        assert!(circle.len() >= 12);
        let mut rng = Rng(41);
        let (mut zeros, mut exact_diffs) = (0, 0);
        for k in 0..4000 {
            let scale = 2f64.powi(rng.below(200) as i32 - 100);
            let offset = [0; 2].map(|_| (rng.below(1 << 20) as f64 - 524288.0) * scale * 64.0);
            let pick = |rng: &mut Rng| circle[rng.below(circle.len() as u64) as usize];
            let [a, b, c, d] = [0; 4].map(|_| {
                let mut q = pick(&mut rng);
                match k % 3 {
                    0 => {}
                    1 if rng.below(4) == 0 => q[0] += rng.below(3) - 1,
                    _ => q = [0; 2].map(|_| rng.below(61) - 30),
                }
                [
                    offset[0] + q[0] as f64 * scale,
                    offset[1] + q[1] as f64 * scale,
                ]
            });
            if [a, b, c]
                .iter()
                .all(|p| (0..2).all(|i| two_diff(p[i], d[i]).1 == 0.0))
            {
                exact_diffs += 1;
            }
            let got = sgn(incircle_exact(a, b, c, d));
            assert_eq!(
                got,
                sgn(robust::incircle(c2(a), c2(b), c2(c), c2(d))),
                "{a:?} {b:?} {c:?} {d:?}"
            );
            zeros += (got == 0) as usize;
        }
        assert!(zeros > 1000, "only {zeros} cocircular quadruples");
        assert!(exact_diffs > 3000, "the stack path ran {exact_diffs} times");
    }
}
