//! Floating-point constructions and measures: circumcenters, off-centers, angles, areas.
//! These never decide topology; every decision is made by [`crate::predicates`]. Also the
//! location of a point in a triangle or tetrahedron mesh for interpolation, from the
//! predicates' signs ([`locate_in_simplices`]).

/// The power of two that brings points whose coordinates all lie below `2^-64` in magnitude
/// up to `[1, 4)` (at most `2^500`), or `None` for any other points. Far enough below that
/// the exact predicates are not exact any more: the in-circle test is of degree four in
/// coordinate differences, which can be as small as an ulp of the coordinates, and the
/// smallest terms of its expansions underflow (2D campaign seed 8, run 5389: a square of
/// 1e-67 with four cocircular corners found "inside" each other's circles; in 3D the insphere
/// test, of degree five, on a cube of 1e-54, and a cube of 2^-120 with a facet 10^-6 of its
/// size, which meshed slowly and differently from its copy scaled by 2^120). The products of
/// five differences of an ulp, with the rounding errors of the expansions, reach `2^-1074` for
/// coordinates near `2^-119`; `2^-64` leaves a wide margin. Scaling by a power of two is exact
/// and changes no sign.
pub fn tiny_scale<'a, const N: usize>(points: impl Iterator<Item = &'a [f64; N]>) -> Option<f64> {
    let max = points.fold(0.0f64, |m, p| p.iter().fold(m, |m, x| m.max(x.abs())));
    if !(max > 0.0 && max < 2f64.powi(-64)) {
        return None;
    }
    Some(2f64.powi((-max.log2().floor() as i32).min(500)))
}

/// Scales a mesh made from an input scaled up by [`tiny_scale`]'s `s` back: the input points
/// are put back as they were, and every other vertex divided by `s`, which must be exact (an
/// internal error otherwise: a Steiner point that would fall among the subnormals).
pub fn scale_back<const N: usize>(
    vertices: &mut [[f64; N]],
    input: &[[f64; N]],
    s: f64,
) -> Result<(), crate::Error> {
    let n = input.len();
    vertices[..n].copy_from_slice(input);
    for p in &mut vertices[n..] {
        for x in p.iter_mut() {
            let y = *x / s;
            if y * s != *x {
                return Err(crate::Error::Internal(format!(
                    "Steiner point coordinate {y:e} is too small to represent exactly"
                )));
            }
            *x = y;
        }
    }
    Ok(())
}

/// Twice the signed area of triangle `abc` (positive when counter-clockwise), in floating point.
#[inline]
pub fn area2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Squared distance between two points.
#[inline]
pub fn dist2(a: [f64; 2], b: [f64; 2]) -> f64 {
    let dx = a[0] - b[0];
    let dy = a[1] - b[1];
    dx * dx + dy * dy
}

/// The circumcenter of triangle `abc`, computed relative to `a` for accuracy.
/// Returns `None` when the triangle is degenerate in floating point.
#[inline]
pub fn circumcenter(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<[f64; 2]> {
    let bx = b[0] - a[0];
    let by = b[1] - a[1];
    let cx = c[0] - a[0];
    let cy = c[1] - a[1];
    let d = 2.0 * (bx * cy - by * cx);
    if d == 0.0 || !d.is_finite() {
        return None;
    }
    let b2 = bx * bx + by * by;
    let c2 = cx * cx + cy * cy;
    let ux = (cy * b2 - by * c2) / d;
    let uy = (bx * c2 - cx * b2) / d;
    let p = [a[0] + ux, a[1] + uy];
    (p[0].is_finite() && p[1].is_finite()).then_some(p)
}

/// The three angles of triangle `abc` in degrees, at `a`, `b` and `c`.
pub fn triangle_angles_deg(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> [f64; 3] {
    let ang = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        let u = [q[0] - p[0], q[1] - p[1]];
        let v = [r[0] - p[0], r[1] - p[1]];
        let cross = u[0] * v[1] - u[1] * v[0];
        let dot = u[0] * v[0] + u[1] * v[1];
        cross.abs().atan2(dot).to_degrees()
    };
    [ang(a, b, c), ang(b, c, a), ang(c, a, b)]
}

/// Squared sine of the smallest angle of `abc`, cheaply: for the angle opposite the shortest
/// edge, sin² = (2·area)² / (|e1|²·|e2|²) with e1, e2 the two other edges.
/// Returns 0 for a degenerate triangle.
#[inline]
pub fn min_angle_sin2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let ab = dist2(a, b);
    let bc = dist2(b, c);
    let ca = dist2(c, a);
    let a2 = area2(a, b, c);
    // The smallest angle is opposite the shortest edge; its sides are the other two edges.
    let (s1, s2) = if ab <= bc && ab <= ca {
        (bc, ca)
    } else if bc <= ca {
        (ab, ca)
    } else {
        (ab, bc)
    };
    let den = s1 * s2;
    if den == 0.0 {
        0.0
    } else {
        a2 * a2 / den
    }
}

/// The Steiner point for a skinny triangle `abc`: its circumcenter, or, when `off_center` is
/// `Some(k)`, the off-center of Üngör: the point on the bisector of the shortest edge at
/// distance `k · |shortest edge|` from the edge's midpoint, if that is closer than the
/// circumcenter (`k = 0.475 · cot(θ/2)` for a minimum angle θ, as in Triangle).
pub fn steiner_point(
    a: [f64; 2],
    b: [f64; 2],
    c: [f64; 2],
    off_center: Option<f64>,
) -> Option<[f64; 2]> {
    let cc = circumcenter(a, b, c)?;
    let Some(k) = off_center else { return Some(cc) };
    let ab = dist2(a, b);
    let bc = dist2(b, c);
    let ca = dist2(c, a);
    let (p, q, l2) = if ab <= bc && ab <= ca {
        (a, b, ab)
    } else if bc <= ca {
        (b, c, bc)
    } else {
        (c, a, ca)
    };
    let m = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
    let dm2 = dist2(m, cc);
    let want2 = k * k * l2;
    if dm2 <= want2 || dm2 == 0.0 {
        return Some(cc);
    }
    let s = (want2 / dm2).sqrt();
    Some([m[0] + (cc[0] - m[0]) * s, m[1] + (cc[1] - m[1]) * s])
}

// ---------------------------------------------------------------------------------------------
// 3D constructions (floating point; no decision is taken on them).

use glam::DVec3;

#[inline]
fn v3(p: [f64; 3]) -> DVec3 {
    DVec3::from_array(p)
}

/// Signed volume of tetrahedron `abcd`, positive when `det[b − a, c − a, d − a] > 0`
/// (TetGen's positive orientation).
pub fn tet_volume(c: [[f64; 3]; 4]) -> f64 {
    let a = v3(c[0]);
    (v3(c[1]) - a).cross(v3(c[2]) - a).dot(v3(c[3]) - a) / 6.0
}

/// The shape of a tetrahedron in `[0, 1]`: `6√2 |V| / l³` with `l` the root mean square of
/// its six edge lengths; 1 for the regular tetrahedron, near 0 for flat ones of any kind.
pub fn tet_shape(c: [[f64; 3]; 4]) -> f64 {
    let mut l2 = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            l2 += dist2_3(c[i], c[j]);
        }
    }
    let l = (l2 / 6.0).sqrt();
    if l == 0.0 {
        return 0.0;
    }
    6.0 * std::f64::consts::SQRT_2 * tet_volume(c).abs() / (l * l * l)
}

/// Circumcenter of tetrahedron `abcd`, computed relative to `a` for accuracy; `None` when the
/// four points are (numerically) coplanar.
pub fn tet_circumcenter(c: [[f64; 3]; 4]) -> Option<[f64; 3]> {
    let a = v3(c[0]);
    let (b, cc, d) = (v3(c[1]) - a, v3(c[2]) - a, v3(c[3]) - a);
    let det = b.dot(cc.cross(d));
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let num = cc.cross(d) * b.length_squared()
        + d.cross(b) * cc.length_squared()
        + b.cross(cc) * d.length_squared();
    let o = a + num / (2.0 * det);
    o.is_finite().then(|| o.to_array())
}

/// Circumcenter of triangle `abc` in 3D (in its plane); `None` when degenerate.
pub fn tri_circumcenter3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<[f64; 3]> {
    let o = v3(a);
    let (u, w) = (v3(b) - o, v3(c) - o);
    let n = u.cross(w);
    let n2 = n.length_squared();
    if n2 == 0.0 || !n2.is_finite() {
        return None;
    }
    let r = (n.cross(u) * w.length_squared() + w.cross(n) * u.length_squared()) / (2.0 * n2);
    let p = o + r;
    p.is_finite().then(|| p.to_array())
}

/// `q` moved along coordinate axis `k` onto the plane of `t` (floating point: its `k`-th
/// coordinate solved from the plane through `t[0]` with the normal of `t`); `None` when the
/// plane is parallel to axis `k` (in floating point) or the result overflows. The other two
/// coordinates are `q`'s own, so the point projects (dropping axis `k`) exactly where `q` does.
pub fn along_axis_onto_plane(t: [[f64; 3]; 3], q: [f64; 3], k: usize) -> Option<[f64; 3]> {
    let [a, b, c] = t;
    let n = (v3(b) - v3(a)).cross(v3(c) - v3(a)).to_array();
    if n[k] == 0.0 {
        return None;
    }
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let mut s = q;
    s[k] = a[k] - (n[i] * (q[i] - a[i]) + n[j] * (q[j] - a[j])) / n[k];
    s[k].is_finite().then_some(s)
}

/// The next floating-point number above (`up`) or below `x`, a finite number (`f64::next_up`
/// and `next_down` are newer than the crate's minimum Rust version).
pub fn next_float(x: f64, up: bool) -> f64 {
    if x == 0.0 {
        let tiny = f64::from_bits(1);
        return if up { tiny } else { -tiny };
    }
    let bits = x.to_bits();
    f64::from_bits(if (x > 0.0) == up { bits + 1 } else { bits - 1 })
}

/// Area of the 3D triangle `abc`.
pub fn tri_area3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    0.5 * (v3(b) - v3(a)).cross(v3(c) - v3(a)).length()
}

/// Squared distance between two points.
pub fn dist2_3(a: [f64; 3], b: [f64; 3]) -> f64 {
    v3(a).distance_squared(v3(b))
}

/// Squared distance from `q` to the segment `ab` (a point when `a == b`).
pub fn dist2_point_segment3(q: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    use glam::DVec3;
    let (q, a, b) = (DVec3::from(q), DVec3::from(a), DVec3::from(b));
    let e = b - a;
    let l2 = e.length_squared();
    let t = if l2 > 0.0 {
        ((q - a).dot(e) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (q - (a + e * t)).length_squared()
}

/// Circumradius over shortest edge (∞ for a flat tetrahedron). 0.61 for the regular one.
pub fn tet_radius_edge(c: [[f64; 3]; 4]) -> f64 {
    let Some(o) = tet_circumcenter(c) else {
        return f64::INFINITY;
    };
    let r2 = dist2_3(o, c[0]);
    let mut e2 = f64::INFINITY;
    for i in 0..4 {
        for j in i + 1..4 {
            e2 = e2.min(dist2_3(c[i], c[j]));
        }
    }
    (r2 / e2).sqrt()
}

/// The six dihedral angles of a tetrahedron, degrees, at edges (0 1), (0 2), (0 3), (1 2),
/// (1 3), (2 3).
pub fn tet_dihedrals(c: [[f64; 3]; 4]) -> [f64; 6] {
    // Face i is opposite corner i; its outward normal is n_i. The dihedral angle at the edge
    // shared by faces i and j is π minus the angle between their outward normals; that edge
    // joins the two other corners.
    let n = outward_normals(c);
    // Edge (a b) lies on faces (k l), the other two corners.
    [(2, 3), (1, 3), (1, 2), (0, 3), (0, 2), (0, 1)]
        .map(|(k, l): (usize, usize)| (-n[k].dot(n[l])).clamp(-1.0, 1.0).acos().to_degrees())
}

/// Smallest and largest dihedral angle of a tetrahedron, degrees.
pub fn tet_dihedral_range(c: [[f64; 3]; 4]) -> (f64, f64) {
    // The same values as the extremes of `tet_dihedrals` (acos is decreasing, so the extreme
    // cosines give them), with two arc cosines instead of six: the sliver pass and the mesh
    // optimisation call this in their inner loops.
    let n = outward_normals(c);
    let (mut dmin, mut dmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for (k, l) in [(2, 3), (1, 3), (1, 2), (0, 3), (0, 2), (0, 1)] {
        let d = (-n[k].dot(n[l])).clamp(-1.0, 1.0);
        dmin = dmin.min(d);
        dmax = dmax.max(d);
    }
    (
        dmax.acos().to_degrees().min(180.0),
        dmin.acos().to_degrees().max(0.0),
    )
}

/// Whether some dihedral angle of the tetrahedron is below `target` degrees or above
/// `180 − target` (`0 < target < 90`): the same question as comparing [`tet_dihedral_range`]
/// with the two bounds, without its square roots and arc cosines. The angle between faces `k`
/// and `l` has cosine `−n̂k·n̂l`; it lies outside `[target, 180 − target]` exactly when that
/// cosine's magnitude exceeds `cos(target)`, i.e. `(nk·nl)² > cos²(target)·|nk|²·|nl|²` for any
/// normals of the faces, whatever their orientation or length. The sliver pass asks this of
/// every tet in each round.
pub fn tet_dihedral_outside(c: [[f64; 3]; 4], target: f64) -> bool {
    // In units of the tet (corner 0 at the origin, largest offset 1): the products below are
    // edge lengths to the eighth power, which would underflow or overflow at other scales.
    let o = v3(c[0]);
    let d = c.map(|q| v3(q) - o);
    let size = d.iter().map(|v| v.abs().max_element()).fold(0.0, f64::max);
    if size == 0.0 || !size.is_finite() {
        return false;
    }
    let p = d.map(|v| v / size);
    let n: [DVec3; 4] = std::array::from_fn(|i| {
        let f = [(i + 1) % 4, (i + 2) % 4, (i + 3) % 4].map(|k| p[k]);
        (f[1] - f[0]).cross(f[2] - f[0])
    });
    let len2 = n.map(|v| v.length_squared());
    let cos2 = target.to_radians().cos().powi(2);
    [(2, 3), (1, 3), (1, 2), (0, 3), (0, 2), (0, 1)]
        .into_iter()
        .any(|(k, l)| n[k].dot(n[l]).powi(2) > cos2 * len2[k] * len2[l])
}

/// The unit outward normals of the faces of a tetrahedron, face `i` opposite corner `i`.
fn outward_normals(c: [[f64; 3]; 4]) -> [DVec3; 4] {
    let p = c.map(v3);
    std::array::from_fn(|i| {
        let f = [(i + 1) % 4, (i + 2) % 4, (i + 3) % 4].map(|k| p[k]);
        let m = (f[1] - f[0]).cross(f[2] - f[0]);
        let m = if m.dot(p[i] - f[0]) > 0.0 { -m } else { m };
        m.normalize_or_zero()
    })
}

/// The simplex of a mesh containing a point, and the point's barycentric weights, for
/// interpolating values given at the vertices (2D triangles, `N = 3`; 3D tetrahedra, `N = 4`).
/// `sub(t)` gives, for simplex `t`, the signed measures (from the exact predicates: exact
/// signs) of the simplices the point makes with each facet, facet `i` being opposite corner
/// `i`: all non-negative exactly when the point is in the closed simplex. `neighbors[t][i]` is
/// the simplex across facet `i`, or [`crate::NONE`]. A visibility walk from `*hint` (updated),
/// then, if the walk leaves the mesh or runs out of steps (it can cycle only in non-Delaunay
/// meshes), a scan. `None` when the point is in no simplex.
pub fn locate_in_simplices<const N: usize>(
    neighbors: &[[u32; N]],
    sub: impl Fn(usize) -> [f64; N],
    hint: &mut u32,
) -> Option<(usize, [f64; N])> {
    let nt = neighbors.len();
    if nt == 0 {
        return None;
    }
    let weights = |s: [f64; N]| {
        let total: f64 = s.iter().sum();
        (total > 0.0).then(|| s.map(|x| x / total))
    };
    let mut t = (*hint as usize).min(nt - 1);
    for _ in 0..nt.min(4096) + 8 {
        let s = sub(t);
        match (0..N).find(|&i| s[i] < 0.0) {
            None => {
                if let Some(w) = weights(s) {
                    *hint = t as u32;
                    return Some((t, w));
                }
                break;
            }
            Some(i) => {
                let n = neighbors[t][i];
                if n == crate::NONE {
                    break;
                }
                t = n as usize;
            }
        }
    }
    (0..nt).find_map(|t| {
        let s = sub(t);
        if s.iter().all(|&x| x >= 0.0) {
            let w = weights(s)?;
            *hint = t as u32;
            Some((t, w))
        } else {
            None
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dihedral_range_is_the_extremes_of_the_six_angles() {
        let tets = [
            [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.3, 0.3, 1e-3],
            ],
            [
                [0.1, 0.2, 0.3],
                [5.0, -1.0, 2.0],
                [0.5, 3.0, 0.1],
                [1.0, 1.0, 7.0],
            ],
            [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        ];
        for c in tets {
            let a = tet_dihedrals(c);
            let lo = a.iter().fold(180.0f64, |m, &x| m.min(x));
            let hi = a.iter().fold(0.0f64, |m, &x| m.max(x));
            assert_eq!(tet_dihedral_range(c), (lo, hi), "{c:?}");
        }
    }

    #[test]
    fn dihedral_outside_agrees_with_the_angles() {
        // Tets from regular to needle-, cap- and sliver-shaped (a vertex pulled towards the
        // opposite face, an edge, another vertex), against targets from 1 to 60 degrees.
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut decided = [0usize; 2];
        for i in 0..4000 {
            let mut c: [[f64; 3]; 4] = std::array::from_fn(|_| [rnd(), rnd(), rnd()]);
            let squash = if i % 2 == 0 {
                1.0
            } else {
                10f64.powi(-(i % 7))
            };
            c[3] = std::array::from_fn(|k| c[0][k] + squash * (c[3][k] - c[0][k]));
            let target = 1.0 + 29.0 * rnd();
            let (lo, hi) = tet_dihedral_range(c);
            // Angles within 1e-6 degrees of a bound are left out: the two computations round
            // differently there.
            if (lo - target).abs() < 1e-6 || (hi - (180.0 - target)).abs() < 1e-6 {
                continue;
            }
            let want = lo < target || hi > 180.0 - target;
            assert_eq!(tet_dihedral_outside(c, target), want, "{c:?} {target}");
            decided[usize::from(want)] += 1;
            // The same answer at any scale (powers of two: exactly the same tet, scaled).
            for k in [-1000, -600, 600, 1000] {
                let m = 2f64.powi(k);
                let scaled = c.map(|q| q.map(|x| x * m));
                assert_eq!(tet_dihedral_outside(scaled, target), want, "{c:?} 2^{k}");
            }
        }
        assert!(decided[0] > 500 && decided[1] > 500, "{decided:?}");
    }

    #[test]
    fn circumcenter_is_equidistant() {
        let (a, b, c) = ([0.0, 0.0], [4.0, 0.0], [1.0, 3.0]);
        let o = circumcenter(a, b, c).unwrap();
        let (ra, rb, rc) = (dist2(o, a), dist2(o, b), dist2(o, c));
        assert!((ra - rb).abs() < 1e-12 && (ra - rc).abs() < 1e-12);
        assert!(circumcenter(a, b, [8.0, 0.0]).is_none());
    }

    #[test]
    fn angles_sum_to_180() {
        let t = triangle_angles_deg([0.0, 0.0], [1.0, 0.0], [0.3, 0.2]);
        assert!((t.iter().sum::<f64>() - 180.0).abs() < 1e-9);
        let s2 = min_angle_sin2([0.0, 0.0], [1.0, 0.0], [0.3, 0.2]);
        let lo = t.iter().cloned().fold(180.0, f64::min).to_radians().sin();
        assert!((s2 - lo * lo).abs() < 1e-12);
    }

    #[test]
    fn off_center_sits_on_the_short_edge_bisector_at_the_set_distance() {
        // A skinny triangle whose shortest edge is bc (length 0.1), apex a far away.
        let (a, b, c) = ([0.0, 0.0], [1.0, 0.0], [1.0, 0.1]);
        let cc = circumcenter(a, b, c).unwrap();
        let k = 0.475 / (15f64.to_radians()).tan();
        let oc = steiner_point(a, b, c, Some(k)).unwrap();
        let m = [1.0, 0.05];
        // On the bisector of bc (the line y = 0.05), k·|bc| from its midpoint, closer than cc.
        assert!((oc[1] - 0.05).abs() < 1e-12);
        assert!((dist2(oc, m).sqrt() - k * 0.1).abs() < 1e-12);
        assert!(dist2(oc, m) < dist2(cc, m));
        // Without an off-center constant the circumcenter comes back.
        assert_eq!(steiner_point(a, b, c, None), Some(cc));
    }
}
