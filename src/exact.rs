//! Exact sign of small polynomial expressions in floating-point inputs, by floating-point
//! expansions (Shewchuk's two-sum / two-product). Used behind a fast filter where `robust`
//! has no ready-made predicate (the dot-product sign of the encroachment test).

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
}
