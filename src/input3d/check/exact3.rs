//! Exact incidence tests between points, segments and triangles in 3D.
//!
//! Everything reduces to the signs of `orient3d` and of `orient2d` on coordinate projections:
//! three points are collinear exactly when all three coordinate projections are flat, and
//! points known to be coplanar keep their orientations in any projection along an axis the
//! plane is not parallel to. No constructed point is ever compared.

use crate::predicates::{orient2d, orient3d};

/// A point in space.
pub(super) type P3 = [f64; 3];

pub(super) use crate::predicates::{collinear3 as collinear, dominant_axis, proj};

/// For `p` collinear with distinct `a` and `b`: whether it lies strictly between them. Exact:
/// coordinate comparisons along an axis on which `a` and `b` differ.
pub(super) fn strictly_between(a: P3, b: P3, p: P3) -> bool {
    let k = (0..3).find(|&k| a[k] != b[k]).unwrap_or(0);
    (a[k] < p[k] && p[k] < b[k]) || (b[k] < p[k] && p[k] < a[k])
}

/// Whether `p` lies in the open segment `ab` (`a != b`).
pub(super) fn in_open_segment(a: P3, b: P3, p: P3) -> bool {
    collinear(a, b, p) && strictly_between(a, b, p)
}

/// Whether `p` lies in the closed triangle `abc` (which must not be degenerate).
pub(super) fn in_closed_triangle(a: P3, b: P3, c: P3, p: P3) -> bool {
    if orient3d(a, b, c, p) != 0.0 {
        return false;
    }
    let Some(axis) = dominant_axis(a, b, c) else {
        return false;
    };
    let (a, b, c, p) = (proj(a, axis), proj(b, axis), proj(c, axis), proj(p, axis));
    let o = [orient2d(a, b, p), orient2d(b, c, p), orient2d(c, a, p)];
    if orient2d(a, b, c) > 0.0 {
        o.iter().all(|&x| x >= 0.0)
    } else {
        o.iter().all(|&x| x <= 0.0)
    }
}

/// Strictly opposite signs.
#[inline]
fn opposite(x: f64, y: f64) -> bool {
    (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0)
}

/// Whether the open segments `ab` and `cd` cross at a single point interior to both (they are
/// coplanar and not collinear). Touching at an endpoint and collinear overlaps are not
/// crossings: those always put a vertex inside the other segment, which is tested separately.
pub(super) fn segments_cross(a: P3, b: P3, c: P3, d: P3) -> bool {
    if orient3d(a, b, c, d) != 0.0 {
        return false;
    }
    let Some(axis) = dominant_axis(a, b, c).or_else(|| dominant_axis(a, b, d)) else {
        return false;
    };
    let (a, b, c, d) = (proj(a, axis), proj(b, axis), proj(c, axis), proj(d, axis));
    opposite(orient2d(a, b, c), orient2d(a, b, d)) && opposite(orient2d(c, d, a), orient2d(c, d, b))
}

/// Whether segment `ab` passes through the plane of triangle `t` (endpoints strictly on both
/// sides) at a point of the closed triangle.
pub(super) fn segment_pierces_triangle(a: P3, b: P3, t: [P3; 3]) -> bool {
    if !opposite(orient3d(t[0], t[1], t[2], a), orient3d(t[0], t[1], t[2], b)) {
        return false;
    }
    let s = [
        orient3d(a, b, t[0], t[1]),
        orient3d(a, b, t[1], t[2]),
        orient3d(a, b, t[2], t[0]),
    ];
    s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    const O: P3 = [0.0, 0.0, 0.0];

    #[test]
    fn collinearity_and_betweenness_are_exact() {
        assert!(collinear(O, [1.0, 2.0, 3.0], [0.5, 1.0, 1.5]));
        assert!(!collinear(
            O,
            [1.0, 2.0, 3.0],
            [0.5, 1.0, 1.5000000000000002]
        ));
        assert!(in_open_segment(O, [0.0, 0.0, 2.0], [0.0, 0.0, 1.0]));
        assert!(!in_open_segment(O, [0.0, 0.0, 2.0], [0.0, 0.0, 2.0]));
        assert!(!in_open_segment(O, [0.0, 0.0, 2.0], [0.0, 0.0, 3.0]));
        // 0.1 + 0.2 is not 0.3 in binary: off the line by one ulp.
        assert!(!in_open_segment(O, [0.3, 0.3, 0.3], [0.1 + 0.2, 0.3, 0.3]));
    }

    #[test]
    fn closed_triangle_includes_its_boundary_only_in_plane() {
        let t = [[0.0, 0.0, 1.0], [2.0, 0.0, 1.0], [0.0, 2.0, 1.0]];
        assert!(in_closed_triangle(t[0], t[1], t[2], [0.5, 0.5, 1.0]));
        assert!(in_closed_triangle(t[0], t[1], t[2], [1.0, 1.0, 1.0]));
        assert!(in_closed_triangle(t[0], t[1], t[2], [0.0, 2.0, 1.0]));
        assert!(!in_closed_triangle(
            t[0],
            t[1],
            t[2],
            [1.0, 1.0000000000000002, 1.0]
        ));
        assert!(!in_closed_triangle(
            t[0],
            t[1],
            t[2],
            [0.5, 0.5, 1.0000000000000002]
        ));
        // A vertical triangle (dropping z would flatten it).
        let v = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(in_closed_triangle(v[0], v[1], v[2], [0.25, 0.25, 0.5]));
        assert!(!in_closed_triangle(v[0], v[1], v[2], [0.25, 0.25, 0.8]));
    }

    #[test]
    fn crossings_need_interiors() {
        let (a, b) = ([0.0, 0.0, 0.0], [2.0, 2.0, 2.0]);
        assert!(segments_cross(a, b, [2.0, 0.0, 0.0], [0.0, 2.0, 2.0]));
        // Skew: no crossing.
        assert!(!segments_cross(a, b, [2.0, 0.0, 0.0], [0.0, 2.0, 2.5]));
        // Touching at an endpoint is not a crossing.
        assert!(!segments_cross(a, b, [1.0, 1.0, 1.0], [0.0, 2.0, 2.0]));
        // Collinear overlap is not a crossing either.
        assert!(!segments_cross(a, b, [1.0, 1.0, 1.0], [3.0, 3.0, 3.0]));
    }

    #[test]
    fn piercing_counts_the_closed_triangle() {
        let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        assert!(segment_pierces_triangle(
            [0.5, 0.5, -1.0],
            [0.5, 0.5, 1.0],
            t
        ));
        // Through an edge and through a vertex.
        assert!(segment_pierces_triangle(
            [1.0, 0.0, -1.0],
            [1.0, 0.0, 1.0],
            t
        ));
        assert!(segment_pierces_triangle(
            [0.0, 0.0, -1.0],
            [0.0, 0.0, 1.0],
            t
        ));
        assert!(!segment_pierces_triangle(
            [1.5, 1.5, -1.0],
            [1.5, 1.5, 1.0],
            t
        ));
        // Ending on the plane is not piercing (that is a vertex on the facet).
        assert!(!segment_pierces_triangle(
            [0.5, 0.5, 0.0],
            [0.5, 0.5, 1.0],
            t
        ));
    }
}
