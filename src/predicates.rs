//! Exact geometric predicates. Every topological decision of the mesher goes through here.
//!
//! Orientation, in-circle and in-sphere are Shewchuk's predicates ("Adaptive Precision
//! Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997): a floating-point
//! evaluation with his a-priori error bound (stage A) decides whenever it can, and the exact
//! expansion arithmetic of [`crate::exact`] decides the rest. The `_fast` variants are the
//! same predicates with the filter forced inline, for the kernels' hot loops ([`orient3d_fast`],
//! [`insphere_fast`], [`incircle_fast`]); the in-sphere one uses a cheaper bound and a
//! double-double stage before the exact one, because nearly cospherical inputs are common in
//! 3D refinement. Encroachment (a point strictly inside a segment's diametral circle) is the
//! exact sign of a dot product, computed in [`crate::exact`].
//!
//! The 3D facet meshes need "2D-in-3D" decisions without projecting coordinates (a projected
//! circle is an ellipse): [`incircle3d`] for points in a facet plane, [`in_diametral_ball_tri`]
//! and [`in_diametral_ball_seg3`] for encroachment, [`orient2d_proj`] and [`dominant_axis`] for
//! orientation inside a plane.

use crate::exact::{
    fast_two_sum, incircle_exact, insphere_exact, orient2d_exact, orient3d_exact, two_prod, two_sum,
};

/// Error-bound constants of Shewchuk's stage-A filters (ε = 2⁻⁵³).
const EPS: f64 = f64::EPSILON * 0.5;
const CCW_BOUND_A: f64 = (3.0 + 16.0 * EPS) * EPS;
const ICC_BOUND_A: f64 = (10.0 + 96.0 * EPS) * EPS;
const O3D_BOUND_A: f64 = (7.0 + 56.0 * EPS) * EPS;
const ISP_BOUND_A: f64 = (16.0 + 224.0 * EPS) * EPS;

/// Positive when `a, b, c` are counter-clockwise, negative when clockwise, zero when collinear.
/// Only the sign is exact; the magnitude approximates twice the signed area.
#[inline]
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let detleft = (a[0] - c[0]) * (b[1] - c[1]);
    let detright = (a[1] - c[1]) * (b[0] - c[0]);
    let det = detleft - detright;
    // Shewchuk's stage A: when the two products differ in sign (or one is zero) no
    // cancellation can occur and the rounded difference has the exact sign.
    let detsum = if detleft > 0.0 {
        if detright <= 0.0 {
            return det;
        }
        detleft + detright
    } else if detleft < 0.0 {
        if detright >= 0.0 {
            return det;
        }
        -detleft - detright
    } else {
        return det;
    };
    let bound = CCW_BOUND_A * detsum;
    if det >= bound || -det >= bound {
        det
    } else {
        orient2d_exact(a, b, c)
    }
}

/// Positive when `d` lies strictly inside the circle through the counter-clockwise triangle
/// `a, b, c`, negative outside, zero on it (exact sign).
#[inline]
pub fn incircle(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    incircle_fast(a, b, c, d)
}

/// [`incircle`] with its floating-point stage inlined: the determinant (translated to `d`)
/// and the standard a-priori error bound on it, `(10 + 96ε)ε` times the permanent. When the
/// determinant clears the bound its sign is certain; otherwise the exact stage decides. Same
/// sign as [`incircle`] always.
#[inline(always)]
pub fn incircle_fast(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    let (adx, ady) = (a[0] - d[0], a[1] - d[1]);
    let (bdx, bdy) = (b[0] - d[0], b[1] - d[1]);
    let (cdx, cdy) = (c[0] - d[0], c[1] - d[1]);
    let bdxcdy = bdx * cdy;
    let cdxbdy = cdx * bdy;
    let alift = adx * adx + ady * ady;
    let cdxady = cdx * ady;
    let adxcdy = adx * cdy;
    let blift = bdx * bdx + bdy * bdy;
    let adxbdy = adx * bdy;
    let bdxady = bdx * ady;
    let clift = cdx * cdx + cdy * cdy;
    let det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * alift
        + (cdxady.abs() + adxcdy.abs()) * blift
        + (adxbdy.abs() + bdxady.abs()) * clift;
    let bound = ICC_BOUND_A * permanent;
    if det > bound || -det > bound {
        det
    } else {
        incircle_exact(a, b, c, d)
    }
}

/// Shewchuk's orient3d: positive when `d` lies *below* the plane of `a, b, c` seen
/// counter-clockwise from above (the opposite sign of the signed volume of `abcd`). Exact sign.
#[inline]
pub fn orient3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    orient3d_fast(a, b, c, d)
}

/// [`orient3d`] with its floating-point filter inlined: when the rounded determinant clears
/// Shewchuk's stage-A error bound its sign is exact and returned; otherwise the exact stage
/// decides. Only the sign of the result is meaningful.
#[inline(always)]
pub fn orient3d_fast(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let (adx, bdx, cdx) = (a[0] - d[0], b[0] - d[0], c[0] - d[0]);
    let (ady, bdy, cdy) = (a[1] - d[1], b[1] - d[1], c[1] - d[1]);
    let (adz, bdz, cdz) = (a[2] - d[2], b[2] - d[2], c[2] - d[2]);
    let (bdxcdy, cdxbdy) = (bdx * cdy, cdx * bdy);
    let (cdxady, adxcdy) = (cdx * ady, adx * cdy);
    let (adxbdy, bdxady) = (adx * bdy, bdx * ady);
    let det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * adz.abs()
        + (cdxady.abs() + adxcdy.abs()) * bdz.abs()
        + (adxbdy.abs() + bdxady.abs()) * cdz.abs();
    let bound = O3D_BOUND_A * permanent;
    if det > bound || -det > bound {
        det
    } else {
        orient3d_exact(a, b, c, d)
    }
}

/// Shewchuk's insphere: positive when `e` lies inside the sphere through `a, b, c, d`, for
/// `orient3d(a, b, c, d) > 0` (exact sign).
#[inline]
pub fn insphere(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
    insphere_fast(a, b, c, d, e)
}

/// [`insphere`] with a cheaper floating-point filter inlined (see `insphere_filter`); the
/// rare uncertain cases go to `insphere_near_degenerate`. Only the sign of the result is
/// meaningful.
#[inline(always)]
pub fn insphere_fast(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
    match insphere_filter(a, b, c, d, e) {
        Some(det) => det,
        None => insphere_near_degenerate(&a, &b, &c, &d, &e),
    }
}

/// Shewchuk's stage-A evaluation of insphere with a cheaper error bound: the permanent is
/// bounded from the largest coordinate differences (as in CGAL's static filters). Returns the
/// rounded determinant when it clears the bound (then its sign is exact), else `None`.
#[inline(always)]
pub(crate) fn insphere_filter(
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
    d: [f64; 3],
    e: [f64; 3],
) -> Option<f64> {
    let (aex, bex, cex, dex) = (a[0] - e[0], b[0] - e[0], c[0] - e[0], d[0] - e[0]);
    let (aey, bey, cey, dey) = (a[1] - e[1], b[1] - e[1], c[1] - e[1], d[1] - e[1]);
    let (aez, bez, cez, dez) = (a[2] - e[2], b[2] - e[2], c[2] - e[2], d[2] - e[2]);
    let (aexbey, bexaey) = (aex * bey, bex * aey);
    let (bexcey, cexbey) = (bex * cey, cex * bey);
    let (cexdey, dexcey) = (cex * dey, dex * cey);
    let (dexaey, aexdey) = (dex * aey, aex * dey);
    let (aexcey, cexaey) = (aex * cey, cex * aey);
    let (bexdey, dexbey) = (bex * dey, dex * bey);
    let ab = aexbey - bexaey;
    let bc = bexcey - cexbey;
    let cd = cexdey - dexcey;
    let da = dexaey - aexdey;
    let ac = aexcey - cexaey;
    let bd = bexdey - dexbey;
    let abc = aez * bc - bez * ac + cez * ab;
    let bcd = bez * cd - cez * bd + dez * bc;
    let cda = cez * da + dez * ac + aez * cd;
    let dab = dez * ab + aez * bd + bez * da;
    let alift = aex * aex + aey * aey + aez * aez;
    let blift = bex * bex + bey * bey + bez * bez;
    let clift = cex * cex + cey * cey + cez * cez;
    let dlift = dex * dex + dey * dey + dez * dez;
    let det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    // Shewchuk's bound is ISP_BOUND_A times the permanent: the same sum with every product
    // replaced by products of absolute values. Each of its 4 · 3 · 2 = 24 terms is at most
    // mx · my · mz · (mx² + my² + mz²) for the largest absolute coordinate differences, so 24
    // times that (plus a 1e-12 allowance for rounding in this product and in the permanent)
    // bounds it, for a quarter of the work.
    let mx = aex.abs().max(bex.abs()).max(cex.abs().max(dex.abs()));
    let my = aey.abs().max(bey.abs()).max(cey.abs().max(dey.abs()));
    let mz = aez.abs().max(bez.abs()).max(cez.abs().max(dez.abs()));
    let permanent = 24.0 * (1.0 + 1e-12) * (mx * my * mz) * (mx * mx + my * my + mz * mz);
    let bound = ISP_BOUND_A * permanent;
    // A bound that underflowed proves nothing: leave those to the adaptive predicate.
    ((det > bound || -det > bound) && bound > 1e-290).then_some(det)
}

/// The slow path of [`insphere_fast`]: a double-double evaluation with a proven error bound
/// (see [`insphere_dd`]), then Shewchuk's adaptive stages. Nearly cospherical points (a point
/// set on a sphere, say) fail the float filter on almost every test; double-double settles
/// nearly all of them at a fraction of the cost of exact expansion arithmetic.
#[cold]
#[inline(never)]
pub(crate) fn insphere_near_degenerate(
    &a: &[f64; 3],
    &b: &[f64; 3],
    &c: &[f64; 3],
    &d: &[f64; 3],
    &e: &[f64; 3],
) -> f64 {
    if let Some(det) = insphere_dd(a, b, c, d, e) {
        return det;
    }
    if let Some(det) = insphere_small_integers(a, b, c, d, e) {
        return det;
    }
    insphere_exact(a, b, c, d, e)
}

/// The exact insphere determinant when the twelve coordinate differences are exact and, after
/// one common power-of-two scaling, integers below `2^21` (lattices, dyadic grids, cube
/// corners and midpoints: the exactly cospherical inputs where the determinant is 0 and no
/// filter can decide). In `i128` every term is below `2^112`, so nothing overflows. `None`
/// otherwise. Only the sign of the result is meaningful.
pub(crate) fn insphere_small_integers(
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
    d: [f64; 3],
    e: [f64; 3],
) -> Option<f64> {
    let mut diffs = [0.0f64; 12];
    let mut m = 0.0f64;
    for (i, p) in [a, b, c, d].iter().enumerate() {
        for k in 0..3 {
            let t = dd_two_sum(p[k], -e[k]);
            if t.lo != 0.0 {
                return None;
            }
            diffs[3 * i + k] = t.hi;
            m = m.max(t.hi.abs());
        }
    }
    if m == 0.0 || !m.is_finite() {
        return (m == 0.0).then_some(0.0);
    }
    // scale = 2^(21 − ⌈log2 m⌉): m · scale lies in [2^20, 2^21].
    let exp = ((m.to_bits() >> 52) & 0x7ff) as i32 - 1022;
    let shift = 21 - exp;
    if !(-1000..=1000).contains(&shift) {
        return None;
    }
    let scale = 2f64.powi(shift);
    let mut v = [0i128; 12];
    for (x, out) in diffs.iter().zip(&mut v) {
        let y = x * scale;
        if y != y.trunc() || y.abs() > (1u64 << 21) as f64 {
            return None;
        }
        *out = y as i128;
    }
    let [aex, aey, aez, bex, bey, bez, cex, cey, cez, dex, dey, dez] = v;
    let ab = aex * bey - bex * aey;
    let bc = bex * cey - cex * bey;
    let cd = cex * dey - dex * cey;
    let da = dex * aey - aex * dey;
    let ac = aex * cey - cex * aey;
    let bd = bex * dey - dex * bey;
    let abc = aez * bc - bez * ac + cez * ab;
    let bcd = bez * cd - cez * bd + dez * bc;
    let cda = cez * da + dez * ac + aez * cd;
    let dab = dez * ab + aez * bd + bez * da;
    let alift = aex * aex + aey * aey + aez * aez;
    let blift = bex * bex + bey * bey + bez * bez;
    let clift = cex * cex + cey * cey + cez * cez;
    let dlift = dex * dex + dey * dey + dez * dez;
    let det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    Some(det.signum() as f64)
}

/// A double-word number `hi + lo` with `|lo| <= ulp(hi) / 2`.
#[derive(Clone, Copy)]
struct Dd {
    hi: f64,
    lo: f64,
}

/// [`crate::exact::two_sum`] as a [`Dd`].
#[inline(always)]
fn dd_two_sum(a: f64, b: f64) -> Dd {
    let (hi, lo) = two_sum(a, b);
    Dd { hi, lo }
}

/// [`crate::exact::fast_two_sum`] as a [`Dd`].
#[inline(always)]
fn dd_fast_two_sum(a: f64, b: f64) -> Dd {
    let (hi, lo) = fast_two_sum(a, b);
    Dd { hi, lo }
}

impl Dd {
    /// AccurateDWPlusDW (Joldes, Muller, Popescu, ACM TOMS 2017, Alg. 6): relative error
    /// below `3u²/(1 − 4u)`, `u = 2⁻⁵³`, for all inputs.
    #[inline(always)]
    fn add(self, y: Dd) -> Dd {
        let s = dd_two_sum(self.hi, y.hi);
        let t = dd_two_sum(self.lo, y.lo);
        let v = dd_fast_two_sum(s.hi, s.lo + t.hi);
        dd_fast_two_sum(v.hi, t.lo + v.lo)
    }

    #[inline(always)]
    fn sub(self, y: Dd) -> Dd {
        self.add(Dd {
            hi: -y.hi,
            lo: -y.lo,
        })
    }

    /// DWTimesDW1 (same paper, Alg. 10): relative error below `7u²`.
    #[inline(always)]
    fn mul(self, y: Dd) -> Dd {
        let (hi, lo) = two_prod(self.hi, y.hi);
        let c = Dd { hi, lo };
        let cl2 = self.hi * y.lo + self.lo * y.hi;
        dd_fast_two_sum(c.hi, c.lo + cl2)
    }
}

/// The sign of Shewchuk's insphere determinant evaluated in double-double, or `None` when that
/// evaluation cannot certify it.
///
/// The coordinate differences are exact (TwoSum); every later operation has relative error
/// at most `δ = 7u²` (see [`Dd`]), and no path through the formula (Shewchuk's arrangement)
/// has more than 8 operations, so the computed value is within `γ₈ = 8δ/(1 − 8δ) < 57u²` times
/// the permanent of the exact value (the same formula in absolute values). The permanent is at
/// most `24 · mx · my · mz · (mx² + my² + mz²)` (see [`insphere_fast`]); `1e-28` times that
/// product leaves a factor of six over `24 · 57u²`. Underflow and overflow, which void the
/// error-free transformations, are excluded by requiring every axis' largest difference to lie
/// in `[1e-20, 1e20]`: any underflowed partial product is then below `1e-240`, far beneath the
/// bound, and nothing can overflow.
pub(crate) fn insphere_dd(
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
    d: [f64; 3],
    e: [f64; 3],
) -> Option<f64> {
    let diff = |p: [f64; 3], k: usize| dd_two_sum(p[k], -e[k]);
    let [aex, bex, cex, dex] = [a, b, c, d].map(|p| diff(p, 0));
    let [aey, bey, cey, dey] = [a, b, c, d].map(|p| diff(p, 1));
    let [aez, bez, cez, dez] = [a, b, c, d].map(|p| diff(p, 2));
    let max = |v: [Dd; 4]| v.iter().fold(0.0f64, |m, x| m.max(x.hi.abs()));
    let (mx, my, mz) = (
        max([aex, bex, cex, dex]),
        max([aey, bey, cey, dey]),
        max([aez, bez, cez, dez]),
    );
    if ![mx, my, mz].iter().all(|&m| (1e-20..=1e20).contains(&m)) {
        return None;
    }
    let ab = aex.mul(bey).sub(bex.mul(aey));
    let bc = bex.mul(cey).sub(cex.mul(bey));
    let cd = cex.mul(dey).sub(dex.mul(cey));
    let da = dex.mul(aey).sub(aex.mul(dey));
    let ac = aex.mul(cey).sub(cex.mul(aey));
    let bd = bex.mul(dey).sub(dex.mul(bey));
    let abc = aez.mul(bc).sub(bez.mul(ac)).add(cez.mul(ab));
    let bcd = bez.mul(cd).sub(cez.mul(bd)).add(dez.mul(bc));
    let cda = cez.mul(da).add(dez.mul(ac)).add(aez.mul(cd));
    let dab = dez.mul(ab).add(aez.mul(bd)).add(bez.mul(da));
    let lift = |x: Dd, y: Dd, z: Dd| x.mul(x).add(y.mul(y)).add(z.mul(z));
    let alift = lift(aex, aey, aez);
    let blift = lift(bex, bey, bez);
    let clift = lift(cex, cey, cez);
    let dlift = lift(dex, dey, dez);
    let det = dlift
        .mul(abc)
        .sub(clift.mul(dab))
        .add(blift.mul(cda).sub(alift.mul(bcd)));
    // The differences' low parts add at most a relative u to each maximum (covered by the
    // factor-six margin, as is the rounding of this product).
    let bound = 1e-28 * (mx * my * mz) * (mx * mx + my * my + mz * mz);
    // |lo| <= u |hi|, so |hi| > 2 · bound puts the double-double value beyond the bound too.
    (det.hi.abs() > 2.0 * bound).then_some(det.hi)
}

/// `true` when `p` lies strictly inside the diametral circle of segment `ab`
/// (the angle `apb` is obtuse), decided exactly.
#[inline]
pub fn encroaches(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    crate::exact::dot_sign_2d(a, b, p) < 0
}

/// For `p` known to be collinear with `a` and `b`: `true` when `p` lies strictly between them.
/// Exact: only coordinate comparisons.
#[inline]
pub fn strictly_between(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    let k = if a[0] != b[0] { 0 } else { 1 };
    (a[k] < p[k] && p[k] < b[k]) || (b[k] < p[k] && p[k] < a[k])
}

/// The orient2d of `a, b, c` projected along coordinate `axis` (that coordinate dropped, the
/// other two kept in cyclic order `axis+1, axis+2`), so its sign is exactly the sign of
/// component `axis` of the normal `(b - a) × (c - a)`. `axis` must be 0, 1 or 2.
#[inline]
pub fn orient2d_proj(a: [f64; 3], b: [f64; 3], c: [f64; 3], axis: usize) -> f64 {
    debug_assert!(axis < 3, "axis {axis} is not a coordinate of a 3D point");
    orient2d(proj(a, axis), proj(b, axis), proj(c, axis))
}

/// The projection of `p` that drops coordinate `axis`, keeping the cyclic order of the other
/// two (`(y, z)`, `(z, x)` or `(x, y)`), so a plane's orientation seen from `+axis` is kept.
#[inline(always)]
pub fn proj(p: [f64; 3], axis: usize) -> [f64; 2] {
    match axis {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

/// The coordinate axis along which the triangle `abc` projects best: the largest magnitude
/// among the three exact-sign projected orientations ([`orient2d_proj`], whose magnitudes
/// approximate the normal's components and are zero exactly when they are), ties going to x,
/// then y. Deterministic in `a, b, c`; for a non-degenerate triangle the chosen normal
/// component is exactly non-zero, so projecting along it never flattens the triangle. `None`
/// exactly when the three points are collinear (every component zero). The one projection
/// rule of the crate: facet meshes, the input checks and [`incircle3d`] all use it, so a facet
/// is seen along the same axis everywhere.
pub fn dominant_axis(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<usize> {
    let mut best = (0.0f64, None);
    for axis in 0..3 {
        let v = orient2d_proj(a, b, c, axis).abs();
        if v > best.0 {
            best = (v, Some(axis));
        }
    }
    best.1
}

/// Whether `a`, `b`, `c` lie on one line (exact: every coordinate projection is flat).
#[inline]
pub fn collinear3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> bool {
    dominant_axis(a, b, c).is_none()
}

/// The in-circle test inside a facet plane: for `p` coplanar with `a, b, c`, positive when `p`
/// is strictly inside the circumcircle of `abc`, zero on it, negative outside, whatever the
/// orientation of `abc` (exact sign; only the sign is meaningful). Zero for a degenerate
/// (collinear) triangle, which has no circumcircle.
///
/// Why it works: every sphere through `a, b, c` cuts their plane in their circumcircle, so
/// for coplanar `p` inside-the-sphere is inside-the-circle. The sphere used passes through a
/// fourth point `q`: `a` moved along the [`dominant_axis`] `k` (whose normal component is
/// exactly non-zero, so `q` is off the plane) towards zero by the triangle's extent (its
/// largest coordinate difference), or by `2ε|a_k|` if that is larger, so that the rounded
/// `q_k` really differs from `a_k`. `insphere` is then sign-corrected by
/// `orient3d(a, b, c, q)`.
///
/// Precondition: `p` exactly coplanar with `a, b, c` (e.g. a vertex of the facet). If it is
/// not, the answer is still an exact, consistent decision, but against that sphere through
/// `a, b, c, q`; since `q` is a deterministic function of `a, b, c` alone, the same triangle
/// always gets the same sphere, whatever `p` is asked about. That sphere is about the size of
/// the triangle, so points rounded off a slanted facet's plane are judged nearly as their
/// projections are, and the same at every scale (issue 14: a step of at least 1 made a sphere
/// 10^20 times the triangle's size on an input scaled by 2^-20, where a rounding error off the
/// plane outweighed the in-plane distances and the facet meshes cascaded).
pub fn incircle3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> f64 {
    let k = dominant_axis(a, b, c).unwrap_or(2);
    let mut q = a;
    let span = (0..3)
        .map(|i| (b[i] - a[i]).abs().max((c[i] - a[i]).abs()))
        .fold(0.0, f64::max);
    let step = span.max(2.0 * f64::EPSILON * a[k].abs());
    q[k] = if a[k] >= 0.0 {
        a[k] - step
    } else {
        a[k] + step
    };
    let o = orient3d(a, b, c, q);
    if o == 0.0 {
        return 0.0;
    }
    let s = insphere(a, b, c, q, p);
    if s == 0.0 {
        0.0 // never -0.0, so that `signum` and printing agree with the comparisons
    } else if o > 0.0 {
        s
    } else {
        -s
    }
}

/// `true` when `p` lies strictly inside the diametral ball of segment `ab` in 3D (the angle
/// `apb` is obtuse), decided exactly.
#[inline]
pub fn in_diametral_ball_seg3(a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> bool {
    crate::exact::dot_sign_3d(a, b, p) < 0
}

/// `true` when `p` lies strictly inside the *lens* of triangle `abc` of relative height `h`:
/// the intersection of the two balls whose spheres pass through `a, b, c` and through the
/// points at distance `h·r` above and below the circumcentre (`r` the circumradius) along the
/// triangle's normal. For `h < 1` it is the part of the diametral ball within about `h·r` of
/// the triangle's plane. The two apexes are constructed in floating point; the sphere tests
/// are exact, and each sphere passes exactly through `a, b, c`. `false` for a degenerate
/// triangle.
pub fn in_lens_tri(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3], h: f64) -> bool {
    let Some(o) = crate::geometry::tri_circumcenter3(a, b, c) else {
        return false;
    };
    let (u, w) = (sub3(b, a), sub3(c, a));
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let len = dot3(n, n).sqrt();
    let r = dot3(sub3(a, o), sub3(a, o)).sqrt();
    if len == 0.0 || !(len.is_finite() && r.is_finite()) {
        return false;
    }
    let k = h * r / len;
    [1.0, -1.0].into_iter().all(|side| {
        let x = [0, 1, 2].map(|i| o[i] + side * k * n[i]);
        let s = orient3d(a, b, c, x);
        s != 0.0 && insphere(a, b, c, x, p) * s > 0.0
    })
}

/// `true` when `p` lies strictly inside the diametral ball of triangle `abc`: the smallest
/// sphere through `a, b, c`, centred at their circumcentre in their plane. `p` need not be
/// coplanar. Exact (barring overflow/underflow); `false` for a degenerate triangle, whose
/// diametral ball is empty.
///
/// With `u = b - a`, `w = c - a`, `n = u × w`, `d = p - a`, the circumcentre is
/// `a + m / (2|n|²)` with `m = |w|²(n × u) + |u|²(w × n)`, so `|p - o|² < R²` is the degree-6
/// test `d·m - |d|²|n|² > 0`. Rewritten with the six dot products of `u, w, d` (`uu = u·u`,
/// `uw = u·w`, ...; Binet–Cauchy for the products of cross products) it becomes
/// `E = uu·ww·(ud + wd - dd) - uw·(ww·ud + uu·wd) + dd·uw²`, which needs far fewer
/// operations, so a cheaper filter and a much shorter exact stage. `E` is first evaluated in
/// floats; if that is too close to zero to trust, it is redone in expansion arithmetic.
pub fn in_diametral_ball_tri(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> bool {
    match diametral_tri_filter(a, b, c, p) {
        Some(s) => s > 0,
        None => diametral_tri_exact(a, b, c, p) > 0,
    }
}

#[inline]
fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
fn dot3(u: [f64; 3], w: [f64; 3]) -> f64 {
    u[0] * w[0] + u[1] * w[1] + u[2] * w[2]
}

/// The dot product of the absolute values: what bounds the rounding error of [`dot3`].
#[inline]
fn dot3_abs(u: [f64; 3], w: [f64; 3]) -> f64 {
    (u[0] * w[0]).abs() + (u[1] * w[1]).abs() + (u[2] * w[2]).abs()
}

/// The float stage of [`in_diametral_ball_tri`]: the sign of `E` when it is certain, `None`
/// otherwise.
///
/// Error bound: expanding the float evaluation into monomials of the exact differences, each
/// monomial carries at most 21 rounding factors `(1 + δ)`, `|δ| ≤ ε = 2⁻⁵³`. A dot product
/// contributes 5 (two leaf differences, one product, two sums); the worst monomials, those of
/// `uu·ww·ud`, have three dot products (15), the product `uu·ww` and the outer product (2),
/// the two operations of `ud + wd - dd` (2) and the two final sums (2). So the error is at
/// most `γ₂₁·M ≈ 21ε·M`, where `M` is `E` with absolute values and every subtraction made an
/// addition; `M` computed in floats is low by at most another factor `(1 - ε)²¹`. `32ε·M`
/// (an exact power-of-two scaling) covers both.
fn diametral_tri_filter(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> Option<i32> {
    let (u, w, d) = (sub3(b, a), sub3(c, a), sub3(p, a));
    let (uu, ww, dd) = (dot3(u, u), dot3(w, w), dot3(d, d));
    let (uw, ud, wd) = (dot3(u, w), dot3(u, d), dot3(w, d));
    let (uw_abs, ud_abs, wd_abs) = (dot3_abs(u, w), dot3_abs(u, d), dot3_abs(w, d));
    let uuww = uu * ww;
    let det = uuww * (ud + wd - dd) - uw * (ww * ud + uu * wd) + dd * uw * uw;
    let mag =
        uuww * (ud_abs + wd_abs + dd) + uw_abs * (ww * ud_abs + uu * wd_abs) + dd * uw_abs * uw_abs;
    // 32ε with ε = 2⁻⁵³ (f64::EPSILON is 2⁻⁵²).
    let bound = 16.0 * f64::EPSILON * mag;
    if det > bound {
        Some(1)
    } else if det < -bound {
        Some(-1)
    } else {
        None
    }
}

/// The exact sign of `E` (see [`in_diametral_ball_tri`]) in expansion arithmetic.
fn diametral_tri_exact(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> i32 {
    use crate::exact::DynExpansion as X;
    let diff = |x: [f64; 3], y: [f64; 3]| [0, 1, 2].map(|k| X::from_diff(x[k], y[k]));
    let dot = |u: &[X; 3], w: &[X; 3]| {
        let mut s = u[0].mul(&w[0]).add(&u[1].mul(&w[1])).add(&u[2].mul(&w[2]));
        s.compress();
        s
    };
    let (u, w, d) = (diff(b, a), diff(c, a), diff(p, a));
    let (uu, ww, dd) = (dot(&u, &u), dot(&w, &w), dot(&d, &d));
    let (uw, ud, wd) = (dot(&u, &w), dot(&u, &d), dot(&w, &d));
    let t1 = uu.mul(&ww).mul(&ud.add(&wd).sub(&dd));
    let t2 = uw.mul(&ww.mul(&ud).add(&uu.mul(&wd)));
    let t3 = dd.mul(&uw).mul(&uw);
    t1.sub(&t2).add(&t3).sign()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_signs() {
        assert!(orient2d([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]) > 0.0);
        assert!(orient2d([0.0, 0.0], [0.0, 1.0], [1.0, 0.0]) < 0.0);
        assert_eq!(orient2d([0.0, 0.0], [1.0, 1.0], [3.0, 3.0]), 0.0);
        // Shewchuk's convention: positive when d is below the ccw plane abc.
        assert!(
            orient3d(
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, -1.0]
            ) > 0.0
        );
    }

    #[test]
    fn incircle_and_encroachment() {
        let (a, b, c) = ([0.0, 0.0], [2.0, 0.0], [0.0, 2.0]);
        assert!(incircle(a, b, c, [1.0, 1.0]) > 0.0);
        assert_eq!(incircle(a, b, c, [2.0, 2.0]), 0.0);
        assert!(encroaches([0.0, 0.0], [2.0, 0.0], [1.0, 0.9]));
        assert!(!encroaches([0.0, 0.0], [2.0, 0.0], [1.0, 1.0]));
        assert!(strictly_between([0.0, 0.0], [2.0, 2.0], [1.0, 1.0]));
        assert!(!strictly_between([0.0, 0.0], [2.0, 2.0], [2.0, 2.0]));
    }

    // ---- 3D facet predicates ----

    type P = [i64; 3];

    fn fl(p: P) -> [f64; 3] {
        p.map(|x| x as f64)
    }

    fn add(p: P, q: P) -> P {
        [p[0] + q[0], p[1] + q[1], p[2] + q[2]]
    }

    fn scale(s: i64, p: P) -> P {
        p.map(|x| s * x)
    }

    fn isub(x: P, y: P) -> [i128; 3] {
        [0, 1, 2].map(|k| (x[k] - y[k]) as i128)
    }

    fn icross(u: [i128; 3], w: [i128; 3]) -> [i128; 3] {
        [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ]
    }

    fn idot(u: [i128; 3], w: [i128; 3]) -> i128 {
        u[0] * w[0] + u[1] * w[1] + u[2] * w[2]
    }

    /// Reference for the diametral-ball test in exact integers (coordinates below 2^17):
    /// the sign of `d·m - |d|²|n|²`, positive strictly inside.
    fn ball_ref(a: P, b: P, c: P, p: P) -> i32 {
        let (u, w, d) = (isub(b, a), isub(c, a), isub(p, a));
        let n = icross(u, w);
        let (nxu, wxn) = (icross(n, u), icross(w, n));
        let m = [0, 1, 2].map(|k| idot(w, w) * nxu[k] + idot(u, u) * wxn[k]);
        (idot(d, m) - idot(d, d) * idot(n, n)).signum() as i32
    }

    /// An independent in-circle reference for points of the plane lattice `a + i·e1 + j·e2`:
    /// the 2D lifted determinant in lattice coordinates with the lifting `Q(x) = xᵀGx` (G the
    /// Gram matrix of e1, e2), which is the squared length in space; sign-corrected by the
    /// orientation of the lattice coordinates.
    fn lattice_incircle_ref(e1: P, e2: P, t: [[i64; 2]; 4]) -> i32 {
        let (g11, g12, g22) = (
            idot(isub(e1, [0; 3]), isub(e1, [0; 3])),
            idot(isub(e1, [0; 3]), isub(e2, [0; 3])),
            idot(isub(e2, [0; 3]), isub(e2, [0; 3])),
        );
        let p = t[3];
        let rows = [0, 1, 2].map(|r| {
            let x = (t[r][0] - p[0]) as i128;
            let y = (t[r][1] - p[1]) as i128;
            [x, y, g11 * x * x + 2 * g12 * x * y + g22 * y * y]
        });
        let det = idot(rows[0], icross(rows[1], rows[2]));
        let orient = (t[1][0] - t[0][0]) as i128 * (t[2][1] - t[0][1]) as i128
            - (t[1][1] - t[0][1]) as i128 * (t[2][0] - t[0][0]) as i128;
        (det.signum() * orient.signum()) as i32
    }

    fn sign(x: f64) -> i32 {
        if x > 0.0 {
            1
        } else if x < 0.0 {
            -1
        } else {
            0
        }
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

        /// Uniform in `-r..=r`.
        fn int(&mut self, r: i64) -> i64 {
            (self.next() % (2 * r as u64 + 1)) as i64 - r
        }

        fn point(&mut self, r: i64) -> P {
            [self.int(r), self.int(r), self.int(r)]
        }

        fn unit(&mut self) -> f64 {
            (self.next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    /// All integer vectors of squared length 81 (e.g. (1,4,8), (4,4,7), (3,6,6), (0,0,9) and
    /// their signed permutations): lattice points on a sphere, for exact cospherical inputs.
    fn norm81() -> Vec<P> {
        let mut out = Vec::new();
        for x in -9..=9i64 {
            for y in -9..=9i64 {
                for z in -9..=9i64 {
                    if x * x + y * y + z * z == 81 {
                        out.push([x, y, z]);
                    }
                }
            }
        }
        out
    }

    fn det3(u: P, v: P, w: P) -> i128 {
        idot(isub(u, [0; 3]), icross(isub(v, [0; 3]), isub(w, [0; 3])))
    }

    /// The 48 signed axis permutations and a few integer quaternion similarities
    /// (`|q|²` times a rotation), all exact on integer points.
    fn similarities() -> Vec<[[i64; 3]; 3]> {
        let mut out = Vec::new();
        for perm in [
            [0, 1, 2],
            [1, 2, 0],
            [2, 0, 1],
            [0, 2, 1],
            [2, 1, 0],
            [1, 0, 2],
        ] {
            for signs in 0..8 {
                let mut m = [[0; 3]; 3];
                for (r, &col) in perm.iter().enumerate() {
                    m[r][col] = if signs >> r & 1 == 1 { -1 } else { 1 };
                }
                out.push(m);
            }
        }
        for [w, x, y, z] in [[1, 1, 1, 1], [2, 1, -1, 3], [1, 2, 3, 4], [3, -1, 0, 2]] {
            out.push([
                [
                    w * w + x * x - y * y - z * z,
                    2 * (x * y - w * z),
                    2 * (x * z + w * y),
                ],
                [
                    2 * (x * y + w * z),
                    w * w - x * x + y * y - z * z,
                    2 * (y * z - w * x),
                ],
                [
                    2 * (x * z - w * y),
                    2 * (y * z + w * x),
                    w * w - x * x - y * y + z * z,
                ],
            ]);
        }
        out
    }

    fn apply(m: &[[i64; 3]; 3], p: P) -> P {
        [0, 1, 2].map(|r| m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2])
    }

    #[test]
    fn projected_orientation_and_dominant_axis() {
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        // Normal (0, 0, 1): only the z projection is non-degenerate, and positive.
        assert!(orient2d_proj(a, b, c, 2) > 0.0);
        assert_eq!(orient2d_proj(a, b, c, 0), 0.0);
        assert_eq!(orient2d_proj(a, b, c, 1), 0.0);
        assert_eq!(dominant_axis(a, b, c), Some(2));
        // Normal (u×w) = (-4, 2, 1) for u = (1,2,0), w = (0,1,4)... checked per component.
        let (a, b, c) = ([1.0, 1.0, 1.0], [2.0, 3.0, 1.0], [1.0, 2.0, 5.0]);
        assert!(orient2d_proj(a, b, c, 0) > 0.0); // n_x = 2*4 - 0*1 = 8
        assert!(orient2d_proj(a, b, c, 1) < 0.0); // n_y = 0*0 - 1*4 = -4
        assert!(orient2d_proj(a, b, c, 2) > 0.0); // n_z = 1*1 - 2*0 = 1
        assert_eq!(dominant_axis(a, b, c), Some(0));
        // The projected sign is the normal component's sign on random integer triangles.
        let mut rng = Rng(3);
        for _ in 0..2000 {
            let (a, b, c) = (rng.point(5), rng.point(5), rng.point(5));
            let n = icross(isub(b, a), isub(c, a));
            for (k, nk) in n.iter().enumerate() {
                assert_eq!(
                    sign(orient2d_proj(fl(a), fl(b), fl(c), k)),
                    nk.signum() as i32
                );
            }
            // The first axis of the largest normal component (ties to x, then y), none for a
            // collinear triple.
            let largest = n.iter().map(|v| v.abs()).max().unwrap();
            let first = (0..3).find(|&k| largest > 0 && n[k].abs() == largest);
            assert_eq!(
                dominant_axis(fl(a), fl(b), fl(c)),
                first,
                "{a:?} {b:?} {c:?}"
            );
            assert_eq!(collinear3(fl(a), fl(b), fl(c)), largest == 0);
        }
    }

    #[test]
    fn facet_predicates_on_exact_circles_and_spheres() {
        // a, b antipodal on a sphere of radius 9s about o, so the sphere is the diametral ball
        // of abc for any c on it, and its great circle through a, b, c is abc's circumcircle.
        let (o, s) = ([5, -3, 2], 3);
        let vs = norm81();
        let (v, v2) = ([1, 4, 8], [4, 4, 7]);
        let (a, b, c) = (
            add(o, scale(s, v)),
            add(o, scale(-s, v)),
            add(o, scale(s, v2)),
        );
        let (af, bf, cf) = (fl(a), fl(b), fl(c));
        for &v3 in &vs {
            let on = add(o, scale(s, v3));
            assert!(
                !in_diametral_ball_tri(af, bf, cf, fl(on)),
                "{v3:?} is on the sphere"
            );
            let inside = add(o, scale(s - 1, v3));
            assert!(in_diametral_ball_tri(af, bf, cf, fl(inside)));
            assert!(!in_diametral_ball_tri(
                af,
                bf,
                cf,
                fl(add(o, scale(s + 1, v3)))
            ));
            // The segment ab's diametral ball is the same sphere.
            assert!(!in_diametral_ball_seg3(af, bf, fl(on)));
            assert!(in_diametral_ball_seg3(af, bf, fl(inside)));
            if det3(v, v2, v3) == 0 {
                for (x, y, z) in [(af, bf, cf), (bf, af, cf), (cf, bf, af)] {
                    assert_eq!(incircle3d(x, y, z, fl(on)), 0.0, "{v3:?} is on the circle");
                    assert!(incircle3d(x, y, z, fl(inside)) > 0.0);
                    assert!(incircle3d(x, y, z, fl(add(o, scale(s + 1, v3)))) < 0.0);
                }
            }
        }
        assert!(in_diametral_ball_tri(af, bf, cf, fl(o)));
        // Degenerate triangles have neither circumcircle nor diametral ball.
        let (p, q, r) = ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [3.0, 3.0, 3.0]);
        assert_eq!(incircle3d(p, q, r, [1.0, 2.0, 3.0]), 0.0);
        assert!(!in_diametral_ball_tri(p, q, r, [1.0, 1.0, 1.2]));
        assert!(!in_diametral_ball_tri(p, p, p, p));
    }

    #[test]
    fn diametral_ball_matches_i128_on_random_integers() {
        let mut rng = Rng(5);
        let (mut zeros, mut undecided) = (0, 0);
        for i in 0..40_000 {
            // Tiny ranges give many exactly cospherical inputs, large ones generic ones.
            let r = if i % 2 == 0 { 4 } else { 1 << 16 };
            let (a, b, c, p) = (rng.point(r), rng.point(r), rng.point(r), rng.point(r));
            let want = ball_ref(a, b, c, p);
            let (af, bf, cf, pf) = (fl(a), fl(b), fl(c), fl(p));
            assert_eq!(
                in_diametral_ball_tri(af, bf, cf, pf),
                want > 0,
                "{a:?} {b:?} {c:?} {p:?}"
            );
            assert_eq!(diametral_tri_exact(af, bf, cf, pf), want);
            if let Some(s) = diametral_tri_filter(af, bf, cf, pf) {
                assert_eq!(s, want, "the filter lied on {a:?} {b:?} {c:?} {p:?}");
            } else {
                undecided += 1;
            }
            zeros += usize::from(want == 0);
        }
        assert!(
            zeros > 100 && undecided >= zeros,
            "{zeros} zeros, {undecided} undecided"
        );
    }

    #[test]
    fn incircle3d_matches_lattice_reference_under_rotations() {
        let mut rng = Rng(9);
        let sims = similarities();
        let mut counts = [0usize; 3];
        for _ in 0..3000 {
            let (origin, e1, e2) = (rng.point(200), rng.point(6), rng.point(6));
            if icross(isub(e1, [0; 3]), isub(e2, [0; 3])) == [0; 3] {
                continue;
            }
            let t = [0; 4].map(|_| [rng.int(3), rng.int(3)]);
            let pts = t.map(|[i, j]| add(origin, add(scale(i, e1), scale(j, e2))));
            let want = lattice_incircle_ref(e1, e2, t);
            let [a, b, c, p] = pts;
            // For coplanar p the circle test and the ball test agree.
            let degenerate = icross(isub(b, a), isub(c, a)) == [0; 3];
            if !degenerate {
                assert_eq!(ball_ref(a, b, c, p), want);
            }
            counts[(want + 1) as usize] += 1;
            for m in &sims {
                let [a, b, c, p] = pts.map(|x| fl(apply(m, x)));
                assert_eq!(sign(incircle3d(a, b, c, p)), want, "{pts:?} under {m:?}");
                assert_eq!(sign(incircle3d(b, a, c, p)), want);
            }
        }
        // All three answers occur often, so the test can fail each way.
        assert!(counts.iter().all(|&n| n > 200), "{counts:?}");
    }

    #[test]
    fn near_degenerate_large_coordinates_against_exact_distances() {
        // Coordinates up to 2^51 (still exact integers) with a unit perturbation: the relative
        // gap is ~2^-47, below what the float filter resolves, so the exact stage decides most.
        let mut rng = Rng(13);
        let vs = norm81();
        let mut undecided = 0;
        for _ in 0..3000 {
            let o = rng.point(1 << 50);
            let s = 1 + rng.int(1 << 46).abs();
            let pick = |rng: &mut Rng| vs[rng.next() as usize % vs.len()];
            let v = pick(&mut rng);
            let v2 = loop {
                let x = pick(&mut rng);
                if icross(isub(x, [0; 3]), isub(v, [0; 3])) != [0; 3] {
                    break x;
                }
            };
            let (a, b, c) = (
                add(o, scale(s, v)),
                add(o, scale(-s, v)),
                add(o, scale(s, v2)),
            );
            let (af, bf, cf) = (fl(a), fl(b), fl(c));
            let r2 = (9 * s as i128).pow(2);
            let dist2 = |p: P| isub(p, o).iter().map(|x| x * x).sum::<i128>();
            // Off-plane: the ball test against |p - o|² vs R².
            let v3 = pick(&mut rng);
            let p = add(add(o, scale(s, v3)), rng.point(1));
            let want = (r2 - dist2(p)).signum() as i32;
            assert_eq!(
                in_diametral_ball_tri(af, bf, cf, fl(p)),
                want > 0,
                "{o:?} {s} {p:?}"
            );
            undecided += usize::from(diametral_tri_filter(af, bf, cf, fl(p)).is_none());
            // In-plane: the circle test, perturbing along the plane by a lattice vector.
            let tv = [v, v2, add(v, v2), add(v, scale(-1, v2))][rng.next() as usize % 4];
            let t = scale(rng.int(1), tv);
            let p = add(add(o, scale(s, v2)), t);
            let want = (r2 - dist2(p)).signum() as i32;
            assert_eq!(sign(incircle3d(af, bf, cf, fl(p))), want, "{o:?} {s} {p:?}");
            assert_eq!(sign(incircle3d(cf, bf, af, fl(p))), want);
        }
        assert!(undecided > 1000, "only {undecided} reached the exact stage");
    }

    #[test]
    fn dyadic_similarity_keeps_decisions() {
        // x -> 0.375 + x·2^-40 is exact on these coordinates and preserves every answer.
        let mut rng = Rng(17);
        let map = |p: P| p.map(|x| 0.375 + x as f64 * 2f64.powi(-40));
        for _ in 0..5000 {
            let (a, b, c, p) = (rng.point(5), rng.point(5), rng.point(5), rng.point(5));
            let want = ball_ref(a, b, c, p) > 0;
            assert_eq!(in_diametral_ball_tri(map(a), map(b), map(c), map(p)), want);
            let want_seg = idot(isub(a, p), isub(b, p)) < 0;
            assert_eq!(in_diametral_ball_seg3(map(a), map(b), map(p)), want_seg);
        }
    }

    fn cross3(u: [f64; 3], w: [f64; 3]) -> [f64; 3] {
        [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ]
    }

    /// The circumcentre and squared radius in plain floats (the cross-product formula).
    fn float_circumsphere(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> ([f64; 3], f64) {
        let (u, w) = (sub3(b, a), sub3(c, a));
        let n = cross3(u, w);
        let (uu, ww, nn) = (dot3(u, u), dot3(w, w), dot3(n, n));
        let (nxu, wxn) = (cross3(n, u), cross3(w, n));
        let off = [0, 1, 2].map(|k| (ww * nxu[k] + uu * wxn[k]) / (2.0 * nn));
        let o = [0, 1, 2].map(|k| a[k] + off[k]);
        (o, dot3(off, off))
    }

    #[test]
    fn float_formula_agrees_on_well_conditioned_inputs() {
        let mut rng = Rng(19);
        let mut checked = [0usize; 2];
        for _ in 0..20_000 {
            let [a, b, c, p] = [0; 4].map(|_| [rng.unit(), rng.unit(), rng.unit()]);
            let (o, r2) = float_circumsphere(a, b, c);
            let gap = r2 - dot3(sub3(p, o), sub3(p, o));
            if gap.abs() > 1e-6 * r2 {
                assert_eq!(in_diametral_ball_tri(a, b, c, p), gap > 0.0);
                checked[usize::from(gap > 0.0)] += 1;
            }
            // A point of the plane (up to rounding), judged by its distance to the centre.
            let (s, t) = (rng.unit(), rng.unit());
            let q = [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]));
            let gap = r2 - dot3(sub3(q, o), sub3(q, o));
            if gap.abs() > 1e-6 * r2 {
                assert_eq!(incircle3d(a, b, c, q) > 0.0, gap > 0.0);
            }
        }
        assert!(checked.iter().all(|&n| n > 1000), "{checked:?}");
    }

    #[test]
    fn filter_never_contradicts_exact_stage_near_the_sphere() {
        let mut rng = Rng(23);
        let mut undecided = 0;
        for _ in 0..20_000 {
            let [a, b, c] = [0; 3].map(|_| [rng.unit(), rng.unit(), rng.unit()].map(|x| x * 1e3));
            let (o, r2) = float_circumsphere(a, b, c);
            let dir = [rng.unit(), rng.unit(), rng.unit()];
            let len = dot3(dir, dir).sqrt();
            // On the sphere up to rounding: the sign is decided by the last bits.
            let p = [0, 1, 2].map(|k| o[k] + dir[k] / len * r2.sqrt());
            let exact = diametral_tri_exact(a, b, c, p);
            assert_eq!(in_diametral_ball_tri(a, b, c, p), exact > 0);
            match diametral_tri_filter(a, b, c, p) {
                Some(s) => assert_eq!(s, exact),
                None => undecided += 1,
            }
        }
        assert!(undecided > 1000, "only {undecided} near-degenerate cases");
    }
}
