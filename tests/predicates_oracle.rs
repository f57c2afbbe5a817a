//! The exact predicates of `idmesh::predicates` (Shewchuk's stage-A filters in front of the
//! expansion arithmetic of `idmesh::exact`) against the `robust` crate's adaptive predicates and
//! exact integer determinants, on random, nearly degenerate (a rounded point of a line, circle,
//! plane or sphere, then moved by one ulp), exactly degenerate (sign 0), integer-grid, mixed-
//! magnitude, huge, tiny and translated inputs. Every input goes through the filtered
//! predicates, their inlined `_fast` forms and the exact stage alone, so the exact stage is
//! checked on all inputs and not only on those the filter leaves to it. Deterministic seeds.

use idmesh::exact::{incircle_exact, insphere_exact, orient2d_exact, orient3d_exact};
use idmesh::predicates::{
    incircle, incircle_fast, insphere, insphere_fast, orient2d, orient3d, orient3d_fast,
};
use robust::{Coord, Coord3D};

type P2 = [f64; 2];
type P3 = [f64; 3];

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

    /// Uniform in `[-1, 1)`, a multiple of `2⁻⁵²`.
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// Uniform in `-r..=r`.
    fn int(&mut self, r: i64) -> i64 {
        (self.next() % (2 * r as u64 + 1)) as i64 - r
    }

    fn p2(&mut self) -> P2 {
        [self.unit(), self.unit()]
    }

    fn p3(&mut self) -> P3 {
        [self.unit(), self.unit(), self.unit()]
    }
}

fn sgn(x: f64) -> i32 {
    assert!(!x.is_nan(), "a predicate returned NaN");
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// `x` moved by `k` units in the last place (towards +∞ for positive `k`).
fn ulps(x: f64, k: i32) -> f64 {
    // `f64::next_up` is newer than the crate's minimum Rust version.
    let up = |x: f64| {
        if x == 0.0 {
            f64::from_bits(1)
        } else if x > 0.0 {
            f64::from_bits(x.to_bits() + 1)
        } else {
            f64::from_bits(x.to_bits() - 1)
        }
    };
    let mut x = x;
    for _ in 0..k.abs() {
        x = if k > 0 { up(x) } else { -up(-x) };
    }
    x
}

fn c2(p: P2) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

fn c3(p: P3) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

/// All of idmesh's forms of orient2d agree with `robust`; returns the sign.
fn check_o2(a: P2, b: P2, c: P2) -> i32 {
    let want = sgn(robust::orient2d(c2(a), c2(b), c2(c)));
    assert_eq!(sgn(orient2d(a, b, c)), want, "orient2d {a:?} {b:?} {c:?}");
    assert_eq!(
        sgn(orient2d_exact(a, b, c)),
        want,
        "exact {a:?} {b:?} {c:?}"
    );
    want
}

fn check_icc(a: P2, b: P2, c: P2, d: P2) -> i32 {
    let want = sgn(robust::incircle(c2(a), c2(b), c2(c), c2(d)));
    let msg = format!("incircle {a:?} {b:?} {c:?} {d:?}");
    assert_eq!(sgn(incircle(a, b, c, d)), want, "{msg}");
    assert_eq!(sgn(incircle_fast(a, b, c, d)), want, "{msg}");
    assert_eq!(sgn(incircle_exact(a, b, c, d)), want, "exact {msg}");
    want
}

fn check_o3(a: P3, b: P3, c: P3, d: P3) -> i32 {
    let want = sgn(robust::orient3d(c3(a), c3(b), c3(c), c3(d)));
    let msg = format!("orient3d {a:?} {b:?} {c:?} {d:?}");
    assert_eq!(sgn(orient3d(a, b, c, d)), want, "{msg}");
    assert_eq!(sgn(orient3d_fast(a, b, c, d)), want, "{msg}");
    assert_eq!(sgn(orient3d_exact(a, b, c, d)), want, "exact {msg}");
    want
}

fn check_isp(a: P3, b: P3, c: P3, d: P3, e: P3) -> i32 {
    let want = sgn(robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e)));
    let msg = format!("insphere {a:?} {b:?} {c:?} {d:?} {e:?}");
    assert_eq!(sgn(insphere(a, b, c, d, e)), want, "{msg}");
    assert_eq!(sgn(insphere_fast(a, b, c, d, e)), want, "{msg}");
    assert_eq!(sgn(insphere_exact(a, b, c, d, e)), want, "exact {msg}");
    want
}

/// Multiplying every coordinate by a power of two is exact and keeps every sign; translating
/// is not exact but is a different input on which the oracle must agree as well. Per
/// predicate, the largest exponents for which neither overflow nor underflow can occur in
/// expansion arithmetic of its degree (2: orient2d, 3: orient3d, 4: incircle, 5: insphere).
#[derive(Clone, Copy)]
struct Range {
    huge: i32,
    tiny: i32,
}

const O2_RANGE: Range = Range {
    huge: 332,
    tiny: -332,
}; // 2^±332 ≈ 1e±100
const O3_RANGE: Range = Range {
    huge: 300,
    tiny: -250,
}; // ≈ 2e90 and 5e-76
const ICC_RANGE: Range = Range {
    huge: 230,
    tiny: -190,
}; // ≈ 2e69 and 6e-58
const ISP_RANGE: Range = Range {
    huge: 180,
    tiny: -120,
}; // ≈ 2e54 and 8e-37

/// The transformed copies of a configuration: scaled to the huge and tiny ends, and
/// translated by 1e6 (the scaled copies must keep the sign exactly).
fn variants<const N: usize>(pts: &[[f64; N]], range: Range) -> [(Vec<[f64; N]>, bool); 3] {
    let scale = |s: i32| {
        let f = 2f64.powi(s);
        pts.iter().map(|p| p.map(|x| x * f)).collect::<Vec<_>>()
    };
    [
        (scale(range.huge), true),
        (scale(range.tiny), true),
        (pts.iter().map(|p| p.map(|x| x + 1e6)).collect(), false),
    ]
}

/// Counts of each sign, to show the inputs really reach all three answers.
#[derive(Default, Debug)]
struct Signs([usize; 3]);

impl Signs {
    fn add(&mut self, s: i32) {
        self.0[(s + 1) as usize] += 1;
    }
}

#[test]
fn random_inputs_agree_with_robust() {
    let mut rng = Rng(1);
    for i in 0..20_000 {
        // Half the cases use mixed magnitudes per coordinate (2^-40 .. 2^40), which makes the
        // exact stage's expansions long.
        let mixed = i % 2 == 1;
        let coord = |rng: &mut Rng| {
            let x = rng.unit();
            if mixed {
                x * 2f64.powi(rng.int(40) as i32)
            } else {
                x
            }
        };
        let p2: [P2; 4] = std::array::from_fn(|_| [coord(&mut rng), coord(&mut rng)]);
        let p3: [P3; 5] =
            std::array::from_fn(|_| [coord(&mut rng), coord(&mut rng), coord(&mut rng)]);
        let [a, b, c, d] = p2;
        check_o2(a, b, c);
        check_icc(a, b, c, d);
        let [a, b, c, d, e] = p3;
        check_o3(a, b, c, d);
        check_isp(a, b, c, d, e);
    }
}

/// Nearly degenerate configurations: the last point is computed on the line, circle, plane or
/// sphere of the others (so it is off it by rounding only) and then moved by -1, 0 or +1 ulp
/// per coordinate; optionally everything lives around a far offset.
#[test]
fn near_degenerate_inputs_agree_with_robust() {
    let mut rng = Rng(2);
    let (mut s_o2, mut s_icc, mut s_o3, mut s_isp) = (
        Signs::default(),
        Signs::default(),
        Signs::default(),
        Signs::default(),
    );
    for i in 0..6_000 {
        let off = if i % 3 == 2 { 1e6 } else { 0.0 };
        let kick = |rng: &mut Rng, x: f64| ulps(x, rng.int(1) as i32);

        // orient2d: c on the line ab.
        let (a, b) = (rng.p2().map(|x| x + off), rng.p2().map(|x| x + off));
        let t = rng.unit() * 2.0;
        let c = [0, 1].map(|k| kick(&mut rng, a[k] + t * (b[k] - a[k])));
        let s = check_o2(a, b, c);
        s_o2.add(s);
        for (v, exact) in variants(&[a, b, c], O2_RANGE) {
            let sv = check_o2(v[0], v[1], v[2]);
            assert!(
                !exact || sv == s,
                "scaling changed orient2d of {a:?} {b:?} {c:?}"
            );
        }

        // incircle: four points on a circle, in counter-clockwise order of angle.
        let o = rng.p2().map(|x| x + off);
        let r = 0.25 + rng.unit().abs();
        let mut ang: [f64; 4] = std::array::from_fn(|_| rng.unit() * std::f64::consts::PI);
        ang[..3].sort_by(f64::total_cmp);
        let on = |t: f64| [o[0] + r * t.cos(), o[1] + r * t.sin()];
        let [a, b, c] = [on(ang[0]), on(ang[1]), on(ang[2])];
        let d = on(ang[3]).map(|x| kick(&mut rng, x));
        let s = check_icc(a, b, c, d);
        s_icc.add(s);
        for (v, exact) in variants(&[a, b, c, d], ICC_RANGE) {
            let sv = check_icc(v[0], v[1], v[2], v[3]);
            assert!(
                !exact || sv == s,
                "scaling changed incircle of {a:?} {b:?} {c:?} {d:?}"
            );
        }

        // orient3d: d on the plane abc.
        let [a, b, c] = [rng.p3(), rng.p3(), rng.p3()].map(|p| p.map(|x| x + off));
        let (u, w) = (rng.unit() * 2.0, rng.unit() * 2.0);
        let d = [0, 1, 2].map(|k| kick(&mut rng, a[k] + u * (b[k] - a[k]) + w * (c[k] - a[k])));
        let s = check_o3(a, b, c, d);
        s_o3.add(s);
        for (v, exact) in variants(&[a, b, c, d], O3_RANGE) {
            let sv = check_o3(v[0], v[1], v[2], v[3]);
            assert!(
                !exact || sv == s,
                "scaling changed orient3d of {a:?} {b:?} {c:?} {d:?}"
            );
        }

        // insphere: five points on a sphere.
        let o = rng.p3().map(|x| x + off);
        let r = 0.25 + rng.unit().abs();
        let on = |rng: &mut Rng| {
            let v = rng.p3();
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
            [0, 1, 2].map(|k| o[k] + r * v[k] / len)
        };
        let [a, b, c, d] = [on(&mut rng), on(&mut rng), on(&mut rng), on(&mut rng)];
        let e = on(&mut rng).map(|x| kick(&mut rng, x));
        let s = check_isp(a, b, c, d, e);
        s_isp.add(s);
        for (v, exact) in variants(&[a, b, c, d, e], ISP_RANGE) {
            let sv = check_isp(v[0], v[1], v[2], v[3], v[4]);
            assert!(
                !exact || sv == s,
                "scaling changed insphere of {a:?} {b:?} {c:?} {d:?} {e:?}"
            );
        }
    }
    // Both signs are common: a rounded point is off the curve either way.
    for (name, s) in [
        ("o2", &s_o2),
        ("icc", &s_icc),
        ("o3", &s_o3),
        ("isp", &s_isp),
    ] {
        assert!(s.0[0] > 1000 && s.0[2] > 1000, "{name}: {s:?}");
    }
}

/// Exactly degenerate inputs built from integers (collinear, cocircular, coplanar and
/// cospherical lattice points), scaled by powers of two and translated by integers, so they
/// stay exactly degenerate: every form must answer 0. Moving the last point by one ulp in any
/// coordinate must give the oracle's non-zero answer.
#[test]
fn exactly_degenerate_inputs_are_zero() {
    let mut rng = Rng(3);
    // Lattice points on the circle x² + y² = 65 and on the sphere |v|² = 81.
    let circle: Vec<[i64; 2]> = (-8..=8i64)
        .flat_map(|x| (-8..=8i64).map(move |y| [x, y]))
        .filter(|[x, y]| x * x + y * y == 65)
        .collect();
    let sphere: Vec<[i64; 3]> = (-9..=9i64)
        .flat_map(|x| (-9..=9i64).flat_map(move |y| (-9..=9i64).map(move |z| [x, y, z])))
        .filter(|[x, y, z]| x * x + y * y + z * z == 81)
        .collect();
    assert_eq!(circle.len(), 16);
    let mut nonzero = 0;
    for i in 0..3_000 {
        let s = [0, 40, -40, 300, -300][i % 5];
        let range = |r: Range| 2f64.powi(s.clamp(r.tiny + 60, r.huge - 10));
        let off = rng.int(1 << 20);
        let fl = |x: i64, f: f64| (x + off) as f64 * f;
        let bump = |p: &mut [f64], k: usize, up: bool| p[k] = ulps(p[k], if up { 1 } else { -1 });
        let up = rng.next() & 1 == 1;

        // Collinear: a + i·v.
        let f = range(O2_RANGE);
        let (a, v) = ([rng.int(50), rng.int(50)], [rng.int(9), rng.int(9)]);
        let pts =
            [rng.int(5), rng.int(5), rng.int(5)].map(|t| [0, 1].map(|k| fl(a[k] + t * v[k], f)));
        assert_eq!(check_o2(pts[0], pts[1], pts[2]), 0, "{pts:?}");
        let mut c = pts[2];
        bump(&mut c, i % 2, up);
        nonzero += usize::from(check_o2(pts[0], pts[1], c) != 0);

        // Cocircular.
        let f = range(ICC_RANGE);
        let o = [rng.int(50), rng.int(50)];
        let q: [P2; 4] = std::array::from_fn(|_| {
            let v = circle[rng.next() as usize % circle.len()];
            [0, 1].map(|k| fl(o[k] + v[k], f))
        });
        assert_eq!(check_icc(q[0], q[1], q[2], q[3]), 0, "{q:?}");
        let mut d = q[3];
        bump(&mut d, i % 2, up);
        check_icc(q[0], q[1], q[2], d);

        // Coplanar: o + i·e1 + j·e2.
        let f = range(O3_RANGE);
        let (o, e1, e2) = (
            [0; 3].map(|_| rng.int(50)),
            [0; 3].map(|_| rng.int(6)),
            [0; 3].map(|_| rng.int(6)),
        );
        let q: [P3; 4] = std::array::from_fn(|_| {
            let (s, t) = (rng.int(4), rng.int(4));
            [0, 1, 2].map(|k| fl(o[k] + s * e1[k] + t * e2[k], f))
        });
        assert_eq!(check_o3(q[0], q[1], q[2], q[3]), 0, "{q:?}");
        let mut d = q[3];
        bump(&mut d, i % 3, up);
        check_o3(q[0], q[1], q[2], d);

        // Cospherical.
        let f = range(ISP_RANGE);
        let o = [0; 3].map(|_| rng.int(50));
        let q: [P3; 5] = std::array::from_fn(|_| {
            let v = sphere[rng.next() as usize % sphere.len()];
            [0, 1, 2].map(|k| fl(o[k] + v[k], f))
        });
        assert_eq!(check_isp(q[0], q[1], q[2], q[3], q[4]), 0, "{q:?}");
        let mut e = q[4];
        bump(&mut e, i % 3, up);
        check_isp(q[0], q[1], q[2], q[3], e);
    }
    // Most one-ulp moves leave the line (a move along it needs a special direction).
    assert!(
        nonzero > 2_000,
        "only {nonzero} non-zero after a one-ulp move"
    );
}

fn i128_det3(m: [[i128; 3]; 3]) -> i128 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// Small integer grids (many exact zeros) against determinants in `i128`, the independent
/// reference: orient2d is `(a-c)×(b-c)`, incircle and insphere are the lifted determinants,
/// orient3d is `det[a-d, b-d, c-d]` (Shewchuk's sign).
#[test]
fn integer_grids_match_exact_integer_determinants() {
    let mut rng = Rng(4);
    let mut zeros = [0usize; 4];
    for i in 0..20_000 {
        let r = if i % 2 == 0 { 2 } else { 1000 };
        let ip2 = |rng: &mut Rng| [rng.int(r), rng.int(r)].map(i128::from);
        let ip3 = |rng: &mut Rng| [rng.int(r), rng.int(r), rng.int(r)].map(i128::from);
        let f2 = |p: [i128; 2]| p.map(|x| x as f64);
        let f3 = |p: [i128; 3]| p.map(|x| x as f64);

        let [a, b, c, d] = [ip2(&mut rng), ip2(&mut rng), ip2(&mut rng), ip2(&mut rng)];
        let o2 = ((a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0])).signum() as i32;
        assert_eq!(check_o2(f2(a), f2(b), f2(c)), o2);
        let row = |p: [i128; 2]| {
            let (x, y) = (p[0] - d[0], p[1] - d[1]);
            [x, y, x * x + y * y]
        };
        let icc = i128_det3([row(a), row(b), row(c)]).signum() as i32;
        assert_eq!(check_icc(f2(a), f2(b), f2(c), f2(d)), icc);

        let [a, b, c, d, e] = [0; 5].map(|_| ip3(&mut rng));
        let rel = |p: [i128; 3], q: [i128; 3]| [0, 1, 2].map(|k| p[k] - q[k]);
        let o3 = i128_det3([rel(a, d), rel(b, d), rel(c, d)]).signum() as i32;
        assert_eq!(check_o3(f3(a), f3(b), f3(c), f3(d)), o3);
        // insphere: the 4×4 determinant of rows (p - e, |p - e|²), expanded along the lift.
        let rows = [a, b, c, d].map(|p| rel(p, e));
        let lift = rows.map(|v| v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        let minor = |skip: usize| {
            let m: Vec<[i128; 3]> = (0..4).filter(|&j| j != skip).map(|j| rows[j]).collect();
            i128_det3([m[0], m[1], m[2]])
        };
        let det4: i128 = (0..4)
            .map(|j| {
                let s = if (j + 3) % 2 == 0 { 1 } else { -1 };
                s * lift[j] * minor(j)
            })
            .sum();
        // Shewchuk's insphere is the 4×4 determinant of the (p - e, |p - e|²) rows.
        let isp = det4.signum() as i32;
        assert_eq!(check_isp(f3(a), f3(b), f3(c), f3(d), f3(e)), isp);
        for (z, s) in zeros.iter_mut().zip([o2, icc, o3, isp]) {
            *z += usize::from(s == 0);
        }
    }
    assert!(zeros.iter().all(|&z| z > 300), "{zeros:?}");
}
