//! Exact geometric predicates. Every topological decision of the mesher goes through here.
//!
//! Orientation and in-circle come from the `robust` crate (Shewchuk's adaptive predicates).
//! Encroachment (a point strictly inside a segment's diametral circle) is the exact sign of a
//! dot product, computed in [`crate::exact`].

use robust::{Coord, Coord3D};

#[inline]
fn c2(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

#[inline]
fn c3(p: [f64; 3]) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

/// Positive when `a, b, c` are counter-clockwise, negative when clockwise, zero when collinear.
/// Only the sign is meaningful (exact).
#[inline]
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    robust::orient2d(c2(a), c2(b), c2(c))
}

/// Positive when `d` lies strictly inside the circle through the counter-clockwise triangle
/// `a, b, c`, negative outside, zero on it (exact sign).
#[inline]
pub fn incircle(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    robust::incircle(c2(a), c2(b), c2(c), c2(d))
}

/// Shewchuk's orient3d: positive when `d` lies *below* the plane of `a, b, c` seen
/// counter-clockwise from above (the opposite sign of the signed volume of `abcd`).
#[inline]
pub fn orient3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// Shewchuk's insphere: positive when `e` lies inside the sphere through `a, b, c, d`, for
/// `orient3d(a, b, c, d) > 0` (exact sign).
#[inline]
pub fn insphere(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
    robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e))
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
}
