//! A small dense linear program solver (simplex method with Bland's rule), for the few
//! constructions that need one: the deepest point of a star's kernel, where a vertex taken off
//! the surface goes (`-Y`). Floating point: its answers are constructions, checked afterwards
//! by exact predicates, never decisions.

/// The Chebyshev centre of the polyhedron `{x : n_i · (x - origin) <= d_i}` (the `n_i` need
/// not be unit vectors): the centre `x` and radius `r` of the largest ball inside, with
/// `x` within `box_half` of `origin` in every coordinate (which keeps the program bounded).
/// `origin` must lie in the polyhedron up to rounding (every `d_i >= 0`; negative ones are
/// taken as 0). `None` when the simplex runs out of its pivot budget or nothing is inside.
///
/// With `unit`, the program is solved with unit normals and lengths in units of `box_half`,
/// which keeps every coefficient near 1, so that the pivot tolerances mean the same at any
/// scale and position of the input; without it, with the raw normals and lengths (on a star
/// 1e-9 across the plane rows are then about 1e-18, and the tolerances take them for zeros).
pub fn chebyshev_center(
    origin: [f64; 3],
    planes: &[([f64; 3], f64)],
    box_half: f64,
    unit: bool,
) -> Option<([f64; 3], f64)> {
    if !(box_half > 0.0 && box_half.is_finite()) {
        return None;
    }
    // Variables z = (u+, u-, ρ) >= 0 with x - origin = l (u+ - u-) and r = l ρ, l the length
    // unit; rows f n·u + f |n| ρ <= f d / l (f the row scale) and ±u_k <= box_half / l.
    let l = if unit { box_half } else { 1.0 };
    let mut rows: Vec<([f64; 7], f64)> = Vec::with_capacity(planes.len() + 6);
    for &(n, d) in planes {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if len == 0.0 || !len.is_finite() || !d.is_finite() {
            continue;
        }
        let f = if unit { 1.0 / len } else { 1.0 };
        let u = n.map(|c| c * f);
        let rhs = d.max(0.0) * f / l;
        if !rhs.is_finite() {
            continue;
        }
        rows.push(([u[0], u[1], u[2], -u[0], -u[1], -u[2], len * f], rhs));
    }
    for k in 0..3 {
        let mut a = [0.0; 7];
        a[k] = 1.0;
        a[k + 3] = -1.0;
        rows.push((a, box_half / l));
        let mut b = [0.0; 7];
        b[k] = -1.0;
        b[k + 3] = 1.0;
        rows.push((b, box_half / l));
    }
    let z = maximize(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0], &rows)?;
    let x = [0, 1, 2].map(|k| origin[k] + l * (z[k] - z[k + 3]));
    (z[6] > 0.0).then_some((x, l * z[6]))
}

/// Maximizes `c · z` subject to `a_i · z <= b_i` (every `b_i >= 0`, so `z = 0` is feasible)
/// and `z >= 0`. Returns an optimal `z`, or `None` when unbounded or out of pivot budget.
fn maximize<const N: usize>(c: &[f64; N], rows: &[([f64; N], f64)]) -> Option<[f64; N]> {
    let m = rows.len();
    let width = N + m + 1;
    // Tableau: m constraint rows (structural, slack, right-hand side), then the objective row
    // holding the reduced costs -c.
    let mut t = vec![0.0f64; (m + 1) * width];
    for (i, (a, b)) in rows.iter().enumerate() {
        t[i * width..i * width + N].copy_from_slice(a);
        t[i * width + N + i] = 1.0;
        t[i * width + width - 1] = *b;
    }
    for (j, &cj) in c.iter().enumerate() {
        t[m * width + j] = -cj;
    }
    let mut basis: Vec<usize> = (N..N + m).collect();
    let scale = rows
        .iter()
        .flat_map(|(a, b)| a.iter().chain(std::iter::once(b)))
        .fold(0.0f64, |s, x| s.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    let eps = 1e-12 * scale;
    for _ in 0..50 * (m + N) {
        // Bland's rule: the lowest-index column with a negative reduced cost enters...
        let Some(col) = (0..N + m).find(|&j| t[m * width + j] < -1e-12) else {
            let mut z = [0.0; N];
            for (i, &bv) in basis.iter().enumerate() {
                if bv < N {
                    z[bv] = t[i * width + width - 1];
                }
            }
            return Some(z);
        };
        // ...and the row with the smallest ratio leaves (lowest basis index on ties).
        let mut pick: Option<(usize, f64)> = None;
        for i in 0..m {
            let a = t[i * width + col];
            if a > eps {
                let ratio = t[i * width + width - 1] / a;
                let better = match pick {
                    None => true,
                    Some((r, best)) => ratio < best || (ratio == best && basis[i] < basis[r]),
                };
                if better {
                    pick = Some((i, ratio));
                }
            }
        }
        let (row, _) = pick?;
        let p = t[row * width + col];
        for x in &mut t[row * width..(row + 1) * width] {
            *x /= p;
        }
        for i in 0..=m {
            if i == row {
                continue;
            }
            let f = t[i * width + col];
            if f != 0.0 {
                for j in 0..width {
                    t[i * width + j] -= f * t[row * width + j];
                }
            }
        }
        basis[row] = col;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::chebyshev_center;

    #[test]
    fn centre_of_a_cube_seen_from_a_corner() {
        // The unit cube as six half-spaces, around its corner at the origin.
        let planes = [
            ([-1.0, 0.0, 0.0], 0.0),
            ([1.0, 0.0, 0.0], 1.0),
            ([0.0, -1.0, 0.0], 0.0),
            ([0.0, 1.0, 0.0], 1.0),
            ([0.0, 0.0, -2.0], 0.0), // normals need not be unit vectors
            ([0.0, 0.0, 1.0], 1.0),
        ];
        let (x, r) = chebyshev_center([0.0; 3], &planes, 10.0, false).unwrap();
        for k in 0..3 {
            assert!((x[k] - 0.5).abs() < 1e-9, "{x:?}");
        }
        assert!((r - 0.5).abs() < 1e-9);
    }

    #[test]
    fn centre_is_scale_and_translation_invariant() {
        // The cube of the test above, scaled and moved: the same centre, scaled and moved
        // (the pivot tolerances once took the plane rows of a 1e-9 cube for zeros).
        for (s, o) in [
            (1e-9, [0.0; 3]),
            (1e-24, [0.0; 3]),
            (1e12, [0.0; 3]),
            (1e-6, [1e3, -2e3, 5e2]),
        ] {
            let planes = [
                ([-s, 0.0, 0.0], 0.0),
                ([s, 0.0, 0.0], s * s),
                ([0.0, -s, 0.0], 0.0),
                ([0.0, s, 0.0], s * s),
                ([0.0, 0.0, -2.0 * s], 0.0),
                ([0.0, 0.0, s], s * s),
            ];
            let (x, r) = chebyshev_center(o, &planes, 10.0 * s, true).unwrap();
            for k in 0..3 {
                assert!((x[k] - o[k] - 0.5 * s).abs() < 1e-6 * s, "{s} {x:?}");
            }
            assert!((r - 0.5 * s).abs() < 1e-6 * s, "{s} {r}");
        }
    }

    #[test]
    fn centre_of_a_thin_wedge() {
        // Above z = 0 and below the plane z = 0.01 x, cut at x <= 1 and |y| <= 1: the largest
        // ball touches z = 0 and the slanted plane near x = 1.
        let planes = [
            ([0.0, 0.0, -1.0], 0.0),
            ([-0.01, 0.0, 1.0], 0.0),
            ([1.0, 0.0, 0.0], 1.0),
            ([0.0, 1.0, 0.0], 1.0),
            ([0.0, -1.0, 0.0], 1.0),
        ];
        let (x, r) = chebyshev_center([0.0; 3], &planes, 10.0, false).unwrap();
        assert!(r > 0.0 && r < 0.01);
        assert!(x[2] > 0.0 && x[2] < 0.01 * x[0], "{x:?}");
    }

    #[test]
    fn empty_interior_gives_none() {
        // z >= 0 and z <= 0: a plane, no ball fits.
        let planes = [([0.0, 0.0, -1.0], 0.0), ([0.0, 0.0, 1.0], 0.0)];
        assert!(chebyshev_center([0.0; 3], &planes, 1.0, true).is_none());
    }
}
