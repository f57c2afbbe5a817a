//! Unit tests of the Bowyer–Watson kernel ([`super::store`]), the insertion order
//! ([`super::order`]), [`super::delaunay3d`] and the mesh checks ([`super::validate`]).
//! Every mesh is checked exactly (structure, orientation, empty circumspheres).

use std::collections::BTreeSet;

use super::delaunay::build;
use super::order::{brio_hilbert_order, hilbert_index_bits};
use super::store::{in_circumcircle_coplanar, Located, Tets, FACE, GHOST};
use super::{delaunay3d, TetMesh, NONE};
use crate::error::{Error, InputError};
use crate::exact::insphere_exact;
use crate::predicates::{insphere, insphere_dd, insphere_fast, insphere_small_integers, orient3d};

/// SplitMix64, for reproducible test inputs.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn f64(&mut self) -> f64 {
        (self.next() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

fn random_points(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut r = Rng(seed);
    (0..n).map(|_| [r.f64(), r.f64(), r.f64()]).collect()
}

/// Distinct random points with small integer coordinates (exact volumes).
fn random_int_points(n: usize, range: u64, seed: u64) -> Vec<[f64; 3]> {
    let mut r = Rng(seed);
    let mut seen = BTreeSet::new();
    let mut out = Vec::new();
    while out.len() < n {
        let p = [r.below(range), r.below(range), r.below(range)];
        if seen.insert(p) {
            out.push(p.map(|x| x as f64));
        }
    }
    out
}

/// Six times the volume of `abcd` with integer coordinates, exactly.
fn vol6_exact(c: [[f64; 3]; 4]) -> i128 {
    let d = |i: usize, k: usize| c[i][k] as i128 - c[0][k] as i128;
    let (ux, uy, uz) = (d(1, 0), d(1, 1), d(1, 2));
    let (vx, vy, vz) = (d(2, 0), d(2, 1), d(2, 2));
    let (wx, wy, wz) = (d(3, 0), d(3, 1), d(3, 2));
    ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx)
}

/// Six times the volume enclosed by the hull faces (outward), from the divergence theorem.
fn hull_vol6_exact(m: &TetMesh) -> i128 {
    let o = m.vertices[m.faces[0][0] as usize];
    m.faces
        .iter()
        .map(|f| {
            vol6_exact([
                o,
                m.vertices[f[0] as usize],
                m.vertices[f[1] as usize],
                m.vertices[f[2] as usize],
            ])
        })
        .sum()
}

/// Full exact check of a mesh from `delaunay3d` of `pts`: validate_mesh, every point used, the
/// hull closed (each hull edge in exactly two hull faces).
fn check_dt(pts: &[[f64; 3]]) -> TetMesh {
    let m = delaunay3d(pts).unwrap();
    m.validate().unwrap();
    assert_eq!(m.vertices, pts);
    assert!(m.complete);
    assert_eq!(m.faces.len(), m.face_markers.len());
    let mut used = vec![false; pts.len()];
    for t in &m.tets {
        for &v in t {
            used[v as usize] = true;
        }
    }
    assert!(
        used.iter().all(|&u| u),
        "a point is missing from the tetrahedralization"
    );
    let mut edges = std::collections::HashMap::new();
    for f in &m.faces {
        for i in 0..3 {
            let (a, b) = (f[i], f[(i + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            // Outward-consistent orientation: each directed edge once.
            assert!(
                !m.faces
                    .iter()
                    .any(|g| g != f && (0..3).any(|j| g[j] == a && g[(j + 1) % 3] == b)),
                "hull faces are not consistently oriented at edge {a}-{b}"
            );
        }
    }
    assert!(
        edges.values().all(|&c| c == 2),
        "hull is not a closed surface"
    );
    // Outward: counter-clockwise seen from outside, so no point lies above any hull face.
    for (i, f) in m.faces.iter().enumerate() {
        let [a, b, c] = f.map(|v| pts[v as usize]);
        let above = pts.iter().position(|&q| orient3d(a, b, c, q) < 0.0);
        assert!(above.is_none(), "point {above:?} is outside hull face {i}");
    }
    let boundary = m.neighbors.iter().flatten().filter(|&&n| n == NONE).count();
    assert_eq!(boundary, m.faces.len());
    m
}

fn check_kernel(pts: &[[f64; 3]]) -> Tets {
    let (tets, _) = build(pts).unwrap();
    tets.check_structure().unwrap();
    tets.check_locally_delaunay().unwrap();
    tets
}

#[test]
fn random_points_several_seeds_and_sizes() {
    for (n, seed) in [
        (4, 7),
        (5, 8),
        (10, 1),
        (11, 2),
        (50, 3),
        (200, 4),
        (1000, 5),
        (5000, 6),
    ] {
        let pts = random_points(n, seed);
        check_kernel(&pts);
        let m = check_dt(&pts);
        // General position: hull faces = 2 · hull vertices − 4.
        let hull: BTreeSet<u32> = m.faces.iter().flatten().copied().collect();
        assert_eq!(m.faces.len(), 2 * hull.len() - 4, "n = {n}");
        // Euler for a triangulated ball: V − E + F − T = 1.
        let mut edges = BTreeSet::new();
        let mut faces = BTreeSet::new();
        for t in &m.tets {
            for i in 0..4 {
                for j in i + 1..4 {
                    edges.insert((t[i].min(t[j]), t[i].max(t[j])));
                }
                let mut f = FACE[i].map(|k| t[k]);
                f.sort_unstable();
                faces.insert(f);
            }
        }
        let euler = n as i64 - edges.len() as i64 + faces.len() as i64 - m.tets.len() as i64;
        assert_eq!(euler, 1, "n = {n}");
    }
}

#[test]
fn matches_brute_force_empty_sphere_tets() {
    // In general position the Delaunay tetrahedra are exactly the 4-sets whose open
    // circumsphere holds no other point.
    for seed in 0..4 {
        let pts = random_points(13, 100 + seed);
        let m = check_dt(&pts);
        let mine: BTreeSet<[u32; 4]> = m
            .tets
            .iter()
            .map(|t| {
                let mut s = *t;
                s.sort_unstable();
                s
            })
            .collect();
        let mut brute = BTreeSet::new();
        let n = pts.len() as u32;
        for a in 0..n {
            for b in a + 1..n {
                for c in b + 1..n {
                    for d in c + 1..n {
                        let q = [a, b, c, d].map(|v| pts[v as usize]);
                        let o = orient3d(q[0], q[1], q[2], q[3]);
                        assert_ne!(o, 0.0);
                        let empty = (0..n).filter(|v| ![a, b, c, d].contains(v)).all(|v| {
                            let s = insphere(q[0], q[1], q[2], q[3], pts[v as usize]);
                            // Inside iff s has the sign of o.
                            s * o <= 0.0
                        });
                        if empty {
                            brute.insert([a, b, c, d]);
                        }
                    }
                }
            }
        }
        assert_eq!(mine, brute, "seed {seed}");
    }
}

#[test]
fn integer_lattice_is_cospherical_everywhere() {
    for n in [2usize, 3, 5, 7] {
        let mut pts = Vec::new();
        for x in 0..n {
            for y in 0..n {
                for z in 0..n {
                    pts.push([x as f64, y as f64, z as f64]);
                }
            }
        }
        check_kernel(&pts);
        let m = check_dt(&pts);
        let side = (n - 1) as i128;
        let total: i128 = (0..m.tets.len()).map(|t| vol6_exact(m.corners(t))).sum();
        assert_eq!(total, 6 * side * side * side, "n = {n}");
        assert_eq!(hull_vol6_exact(&m), total);
    }
}

#[test]
fn cube_corners_and_points_on_hull_faces_and_edges() {
    let mut pts = Vec::new();
    for x in [0.0, 4.0] {
        for y in [0.0, 4.0] {
            for z in [0.0, 4.0] {
                pts.push([x, y, z]);
            }
        }
    }
    check_dt(&pts);
    // Points exactly on edges (midpoints, quarter points) and faces of the cube, and inside.
    pts.extend([
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [4.0, 4.0, 3.0],
        [2.0, 2.0, 0.0],
        [1.0, 3.0, 4.0],
        [0.0, 2.5, 1.5],
        [4.0, 0.5, 3.5],
        [2.0, 2.0, 2.0],
        [1.0, 1.0, 1.0],
        [3.0, 0.0, 4.0],
    ]);
    check_kernel(&pts);
    let m = check_dt(&pts);
    let total: i128 = (0..m.tets.len()).map(|t| vol6_exact(m.corners(t))).sum();
    assert_eq!(total, 6 * 64);
}

#[test]
fn exactly_cospherical_integer_points() {
    // All integer points with x² + y² + z² = 425 lie exactly on one sphere; the centre too.
    let mut pts = vec![[0.0, 0.0, 0.0]];
    for x in -21i32..=21 {
        for y in -21i32..=21 {
            for z in -21i32..=21 {
                if x * x + y * y + z * z == 425 {
                    pts.push([x as f64, y as f64, z as f64]);
                }
            }
        }
    }
    assert!(pts.len() > 100, "{} points", pts.len());
    check_kernel(&pts);
    check_dt(&pts);
    check_dt(&pts[1..]);
}

#[test]
fn points_on_a_sphere_in_floating_point() {
    let mut r = Rng(7);
    let pts: Vec<[f64; 3]> = (0..400)
        .map(|_| {
            let (u, v) = (2.0 * r.f64() - 1.0, std::f64::consts::TAU * r.f64());
            let s = (1.0 - u * u).sqrt();
            [s * v.cos(), s * v.sin(), u]
        })
        .collect();
    check_kernel(&pts);
    check_dt(&pts);
}

#[test]
fn points_on_few_planes() {
    // Random points on the planes z = 0, z = 1 and x = 1/2 (exactly representable): flat hull
    // facets full of coplanar points, where the ghosts' in-circle rule decides.
    let mut r = Rng(11);
    let mut pts = Vec::new();
    for i in 0..600 {
        let (a, b) = (r.f64(), r.f64());
        pts.push(match i % 3 {
            0 => [a, b, 0.0],
            1 => [a, b, 1.0],
            _ => [0.5, a, b],
        });
    }
    check_kernel(&pts);
    check_dt(&pts);
    // Integer points on two planes: also cocircular within each plane.
    let mut pts = Vec::new();
    for x in 0..6 {
        for y in 0..6 {
            pts.push([x as f64, y as f64, 0.0]);
            pts.push([x as f64, y as f64, 3.0]);
        }
    }
    check_kernel(&pts);
    let m = check_dt(&pts);
    let total: i128 = (0..m.tets.len()).map(|t| vol6_exact(m.corners(t))).sum();
    assert_eq!(total, 6 * 5 * 5 * 3);
}

#[test]
fn volume_is_the_hull_volume_in_any_insertion_order() {
    let pts = random_int_points(300, 40, 5);
    let mut volumes = Vec::new();
    for seed in 0..4u64 {
        // Insert through the kernel directly, in a shuffled order.
        let mut order: Vec<usize> = (0..pts.len()).collect();
        let mut r = Rng(seed);
        for i in (1..order.len()).rev() {
            order.swap(i, r.below(i as u64 + 1) as usize);
        }
        let mut tets = Tets::with_capacity(pts.len());
        for &i in &order {
            tets.push_vertex(pts[i]);
        }
        let first = first_four(&tets);
        tets.init(first[0], first[1], first[2], first[3]);
        let mut hint = 0;
        for v in 0..pts.len() as u32 {
            if !first.contains(&v) {
                hint = tets.insert(v, hint).unwrap();
            }
        }
        tets.check_structure().unwrap();
        tets.check_locally_delaunay().unwrap();
        let mut vol = 0i128;
        for t in 0..tets.num_slots() as u32 {
            if tets.alive(t) && !tets.is_ghost(t) {
                vol += vol6_exact(tets.verts(t).map(|v| tets.point(v)));
            }
        }
        volumes.push(vol);
    }
    let m = check_dt(&pts);
    let hull = hull_vol6_exact(&m);
    assert!(hull > 0);
    assert!(
        volumes.iter().all(|&v| v == hull),
        "{volumes:?} vs hull {hull}"
    );
}

#[test]
fn generic_points_give_the_same_tets_in_any_order() {
    // The Delaunay tetrahedralization of points in general position is unique.
    let pts = random_points(500, 77);
    let reference: BTreeSet<[u32; 4]> = sorted_tets(&delaunay3d(&pts).unwrap());
    let mut rev = pts.clone();
    rev.reverse();
    let n = pts.len() as u32;
    let reversed: BTreeSet<[u32; 4]> = sorted_tets(&delaunay3d(&rev).unwrap())
        .into_iter()
        .map(|t| {
            let mut s = t.map(|v| n - 1 - v);
            s.sort_unstable();
            s
        })
        .collect();
    assert_eq!(reference, reversed);
}

fn sorted_faces(m: &TetMesh) -> BTreeSet<[u32; 3]> {
    m.tets
        .iter()
        .flat_map(|t| {
            FACE.map(|f| {
                let mut s = f.map(|i| t[i]);
                s.sort_unstable();
                s
            })
        })
        .collect()
}

fn sorted_tets(m: &TetMesh) -> BTreeSet<[u32; 4]> {
    m.tets
        .iter()
        .map(|t| {
            let mut s = *t;
            s.sort_unstable();
            s
        })
        .collect()
}

/// The first four kernel vertices (in id order) that span a tetrahedron.
fn first_four(tets: &Tets) -> [u32; 4] {
    let n = tets.num_vertices() as u32;
    let p = |v: u32| tets.point(v);
    let b = (1..n).find(|&v| p(v) != p(0)).unwrap();
    let c = (b + 1..n)
        .find(|&v| {
            let (u, w) = (sub(p(b), p(0)), sub(p(v), p(0)));
            cross(u, w) != [0.0; 3]
        })
        .unwrap();
    let d = (c + 1..n)
        .find(|&v| orient3d(p(0), p(b), p(c), p(v)) != 0.0)
        .unwrap();
    [0, b, c, d]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(u: [f64; 3], w: [f64; 3]) -> [f64; 3] {
    [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ]
}

/// Everything observable about the store's tets, slot by slot.
/// One tet's vertices and neighbour half-faces.
type TetRecord = ([u32; 4], [(u32, usize); 4]);

fn snapshot(t: &Tets) -> Vec<TetRecord> {
    (0..t.num_slots() as u32)
        .map(|s| {
            if t.alive(s) {
                (t.verts(s), [0, 1, 2, 3].map(|f| t.neighbor(s, f)))
            } else {
                ([NONE; 4], [(NONE, 0); 4])
            }
        })
        .collect()
}

#[test]
fn two_phase_cancel_leaves_the_mesh_identical_and_commit_inserts() {
    let pts = random_points(400, 21);
    let (mut tets, _) = build(&pts[..300]).unwrap();
    let mut hint = 0;
    for (k, &p) in pts[300..].iter().enumerate() {
        let Located::InTet(start) = tets.locate(p, hint) else {
            panic!("random point {k} equals a vertex");
        };
        let before = snapshot(&tets);
        assert!(tets.find_cavity(p, start));
        let cavity = tets.cavity().to_vec();
        assert!(cavity.contains(&start));
        for &t in &cavity {
            assert!(tets.in_cavity(t) && tets.conflict(t, p));
        }
        for &h in tets.cavity_boundary() {
            let (t, f) = (h >> 2, (h & 3) as usize);
            assert!(tets.in_cavity(t));
            let (u, _) = tets.neighbor(t, f);
            assert!(!tets.in_cavity(u) && !tets.conflict(u, p));
        }
        // Boundary of a ball: F = 2 · (boundary vertices) − 4.
        let mut bverts = BTreeSet::new();
        for &h in tets.cavity_boundary() {
            let (t, f) = (h >> 2, (h & 3) as usize);
            for i in FACE[f] {
                bverts.insert(tets.verts(t)[i]);
            }
        }
        assert_eq!(tets.cavity_boundary().len(), 2 * bverts.len() - 4);
        tets.cancel_cavity();
        assert!(cavity.iter().all(|&t| !tets.in_cavity(t)));
        assert!(snapshot(&tets) == before, "cancel changed the mesh");
        // Find again and commit this time.
        let v = tets.push_vertex(p);
        assert!(tets.find_cavity(p, start));
        let nb = tets.cavity_boundary().len();
        let new = tets.commit_cavity(v).to_vec();
        assert_eq!(new.len(), nb);
        assert!(new.iter().all(|&t| tets.alive(t) && tets.verts(t)[0] == v));
        hint = new[0];
        if k % 20 == 0 {
            tets.check_structure().unwrap();
            tets.check_locally_delaunay().unwrap();
        }
    }
    tets.check_structure().unwrap();
    tets.check_locally_delaunay().unwrap();
}

#[test]
fn locate_finds_vertices_inside_and_outside_points() {
    let pts = random_points(200, 31);
    let (tets, _) = build(&pts).unwrap();
    for v in 0..tets.num_vertices() as u32 {
        assert_eq!(tets.locate(tets.point(v), 0), Located::Vertex(v));
    }
    // Outside the hull: a ghost whose hull triangle the point is beyond.
    for p in [[2.0, 0.5, 0.5], [-1.0, -1.0, -1.0], [0.5, 0.5, 7.0]] {
        let Located::InTet(t) = tets.locate(p, 5) else {
            panic!()
        };
        assert!(tets.is_ghost(t) && tets.conflict(t, p));
    }
    // Inside: a real tet containing the point (closed).
    let p = [0.5, 0.5, 0.5];
    let Located::InTet(t) = tets.locate(p, 0) else {
        panic!()
    };
    assert!(!tets.is_ghost(t));
    let v = tets.verts(t);
    for face in FACE {
        let [a, b, c] = face.map(|i| tets.point(v[i]));
        assert!(orient3d(a, b, c, p) >= 0.0);
    }
    // A dead or out-of-range hint is tolerated.
    assert!(matches!(tets.locate(p, NONE - 7), Located::InTet(_)));
}

#[test]
fn star_edge_and_face_queries_agree_with_the_tets() {
    let pts = random_points(300, 41);
    let (tets, _) = build(&pts).unwrap();
    let mut star = Vec::new();
    for v in 0..tets.num_vertices() as u32 {
        tets.star(v, &mut star);
        let brute: BTreeSet<u32> = (0..tets.num_slots() as u32)
            .filter(|&t| tets.alive(t) && tets.verts(t).contains(&v))
            .collect();
        assert_eq!(
            star.iter().copied().collect::<BTreeSet<_>>(),
            brute,
            "vertex {v}"
        );
        assert_eq!(star.len(), brute.len());
        assert!(tets.verts(tets.vertex_tet(v)).contains(&v));
    }
    for t in (0..tets.num_slots() as u32).filter(|&t| tets.alive(t) && !tets.is_ghost(t)) {
        let [a, b, c, d] = tets.verts(t);
        let e = tets.find_edge(a, c).unwrap();
        assert!(tets.verts(e).contains(&a) && tets.verts(e).contains(&c));
        let h = tets.find_face(b, d, c).unwrap();
        let (u, f) = (h >> 2, (h & 3) as usize);
        let mut got = FACE[f].map(|i| tets.verts(u)[i]);
        got.sort_unstable();
        let mut want = [b, c, d];
        want.sort_unstable();
        assert_eq!(got, want);
    }
    // An edge that is not in the mesh: the two farthest-apart vertices of a random cloud are
    // (almost surely) not joined; check the answer against a brute-force scan either way.
    let (a, b) = (0u32, 1u32);
    let brute = (0..tets.num_slots() as u32)
        .any(|t| tets.alive(t) && tets.verts(t).contains(&a) && tets.verts(t).contains(&b));
    assert_eq!(tets.find_edge(a, b).is_some(), brute);
    assert!(
        tets.find_face(a, b, GHOST).is_some()
            == tets.find_edge(a, b).is_some_and(|_| {
                (0..tets.num_slots() as u32).any(|t| {
                    tets.alive(t) && [a, b, GHOST].iter().all(|x| tets.verts(t).contains(x))
                })
            })
    );
}

#[test]
fn duplicates_and_bad_input_are_reported() {
    let mut pts = random_points(50, 51);
    pts[37] = pts[12];
    match delaunay3d(&pts) {
        Err(Error::Input(InputError::DuplicatePoint { first, second })) => {
            assert_eq!((first, second), (12, 37));
        }
        other => panic!("{other:?}"),
    }
    let mut bad = random_points(10, 52);
    bad[6][1] = f64::NAN;
    assert_eq!(
        delaunay3d(&bad).unwrap_err(),
        Error::Input(InputError::NonFinitePoint { point: 6 })
    );
    bad[6][1] = f64::INFINITY;
    assert_eq!(
        delaunay3d(&bad).unwrap_err(),
        Error::Input(InputError::NonFinitePoint { point: 6 })
    );
    bad[6][1] = 1e300;
    assert_eq!(
        delaunay3d(&bad).unwrap_err(),
        Error::Input(InputError::CoordinateTooLarge { point: 6 })
    );
    assert_eq!(
        delaunay3d(&random_points(3, 53)).unwrap_err(),
        Error::Input(InputError::TooFewPoints3 { count: 3 })
    );
    let line: Vec<[f64; 3]> = (0..20)
        .map(|i| [i as f64, 2.0 * i as f64, -(i as f64)])
        .collect();
    assert_eq!(
        delaunay3d(&line).unwrap_err(),
        Error::Input(InputError::AllCollinear)
    );
    // Integer points on the plane x + y + z = 10: exactly coplanar.
    let mut r = Rng(54);
    let plane: Vec<[f64; 3]> = (0..30)
        .map(|i| {
            let (x, y) = (r.below(20) as f64 + i as f64 * 20.0, r.below(20) as f64);
            [x, y, 10.0 - x - y]
        })
        .collect();
    assert_eq!(
        delaunay3d(&plane).unwrap_err(),
        Error::Input(InputError::AllCoplanar)
    );
    let same = vec![[1.0, 2.0, 3.0]; 6];
    assert!(matches!(
        delaunay3d(&same),
        Err(Error::Input(InputError::DuplicatePoint { .. }))
    ));
    // A duplicate among otherwise flat points is still found once the points span space.
    let mut pts = random_points(40, 55);
    pts.push(pts[3]);
    assert!(matches!(
        delaunay3d(&pts),
        Err(Error::Input(InputError::DuplicatePoint {
            first: 3,
            second: 40
        }))
    ));
}

/// Five tets around one short edge, apexes `step` degrees apart on the unit circle: 72 closes
/// the fan once (a Delaunay mesh); 144 winds it twice (a pentagram), although every tet is
/// positive and every pair of neighbours lies on opposite sides of their shared face.
fn edge_fan(step: f64) -> TetMesh {
    let mut vertices = vec![[0.0, 0.0, -0.2], [0.0, 0.0, 0.2]];
    for i in 0..5 {
        let t = (step * i as f64).to_radians();
        vertices.push([t.cos(), t.sin(), 0.0]);
    }
    let p = |v: u32| vertices[v as usize];
    let flip = orient3d(p(0), p(1), p(2), p(3)) > 0.0;
    let tets: Vec<[u32; 4]> = (0..5u32)
        .map(|i| {
            let (c, d) = (2 + i, 2 + (i + 1) % 5);
            if flip {
                [1, 0, c, d]
            } else {
                [0, 1, c, d]
            }
        })
        .collect();
    // Across the face without c_i lies the next tet; without c_{i+1}, the previous one.
    let neighbors = (0..5u32)
        .map(|i| [NONE, NONE, (i + 1) % 5, (i + 4) % 5])
        .collect();
    TetMesh {
        vertex_markers: vec![0; vertices.len()],
        num_input_vertices: vertices.len(),
        vertices,
        tets,
        neighbors,
        complete: true,
        ..TetMesh::default()
    }
}

#[test]
fn validate_catches_tets_winding_twice_around_an_edge() {
    let once = edge_fan(72.0);
    once.validate().unwrap();
    crate::mesh3d::validate::check_output(&once, 2).unwrap();
    let twice = edge_fan(144.0);
    assert!(twice.validate().is_err());
    match crate::mesh3d::validate::check_output(&twice, 2) {
        Err(Error::Internal(s)) => assert!(s.contains("around edge [0, 1]"), "{s}"),
        other => panic!("overlap not caught: {other:?}"),
    }
}

#[test]
fn validate_mesh_catches_corruption() {
    let pts = random_points(60, 61);
    let good = delaunay3d(&pts).unwrap();
    good.validate().unwrap();
    let msg = |m: &TetMesh| match m.validate() {
        Err(Error::Internal(s)) => s,
        other => panic!("corruption not caught: {other:?}"),
    };
    // Inverted tet.
    let mut m = good.clone();
    m.tets[3].swap(0, 1);
    assert!(msg(&m).contains("tet 3"));
    // Broken neighbour link.
    let mut m = good.clone();
    let t = (0..m.tets.len())
        .find(|&t| m.neighbors[t][0] != NONE)
        .unwrap();
    m.neighbors[t][0] = NONE;
    assert!(msg(&m).contains(&format!("{t}")));
    // A point moved inside a circumsphere: the Delaunay check names it.
    let mut m = good.clone();
    let [a, b, c, d] = m.corners(0);
    let inside = [0, 1, 2].map(|k| (a[k] + b[k] + c[k] + d[k]) / 4.0);
    let v = m.tets[1]
        .iter()
        .copied()
        .find(|v| !m.tets[0].contains(v))
        .unwrap();
    m.vertices[v as usize] = inside;
    assert!(m.validate().is_err());
    // A subface that is no face.
    let all = sorted_faces(&good);
    let n = good.vertices.len() as u32;
    let triple = (0..n)
        .flat_map(|a| (a + 1..n).map(move |b| [a, b, (b + 1) % n]))
        .find(|f| {
            let mut s = *f;
            s.sort_unstable();
            f[2] != f[0] && !all.contains(&s)
        })
        .unwrap();
    let mut m = good.clone();
    m.faces[0] = triple;
    assert!(msg(&m).contains("subface 0"));
    // A duplicated tet: its faces then lie in too many tets.
    let mut m = good.clone();
    m.tets.push(m.tets[0]);
    m.neighbors.push([NONE; 4]);
    assert!(m.validate().is_err());
}

#[test]
fn validate_catches_neighbours_on_the_same_side_of_their_face() {
    // Two positively oriented tets on face abc, both apexes above it, linked as neighbours:
    // each tet alone is fine, together they overlap. Both list the face in the same cyclic
    // order, which is what the (coordinate-free) side test looks at.
    let (a, b, c, d) = (
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    );
    let mut m = delaunay3d(&[a, b, c, d]).unwrap();
    m.validate().unwrap();
    let t = m.tets[0];
    let (apex, k) = (0..4).map(|k| (t[k], k)).find(|&(v, _)| v == 3).unwrap();
    assert_eq!(apex, 3);
    m.vertices.push([0.1, 0.1, 2.0]);
    m.vertex_markers.push(0);
    let mut u = t;
    u[k] = 4;
    assert!(
        orient3d(a, b, c, [0.1, 0.1, 2.0]) < 0.0,
        "both apexes above abc"
    );
    m.tets.push(u);
    m.neighbors[0][k] = 1;
    m.neighbors.push([NONE; 4]);
    m.neighbors[1][k] = 0;
    match m.validate() {
        Err(Error::Internal(s)) => assert!(s.contains("same side"), "{s}"),
        other => panic!("overlap not caught: {other:?}"),
    }
}

#[test]
fn coplanar_circumcircle_test_is_exact() {
    // Triangle in the tilted plane x + y + z = 3 (integer points).
    let (a, b, c) = ([3.0, 0.0, 0.0], [0.0, 3.0, 0.0], [0.0, 0.0, 3.0]);
    assert!(in_circumcircle_coplanar(a, b, c, [1.0, 1.0, 1.0]));
    assert!(!in_circumcircle_coplanar(a, b, c, [3.0, 3.0, -3.0]));
    // On the circle: (x−1)²+(y−1)²+(z−1)² = 6 in the plane; (3,0,0) is on it, so is (−1,2,2).
    assert!(!in_circumcircle_coplanar(a, b, c, [-1.0, 2.0, 2.0]));
    // Orientation of the triangle does not matter.
    assert!(in_circumcircle_coplanar(a, c, b, [1.0, 1.0, 1.0]));
    assert!(!in_circumcircle_coplanar(a, c, b, [-1.0, 2.0, 2.0]));
    // Large coordinates: q must really move off the plane.
    let s = 1e17;
    let (a, b, c) = ([s, s, s], [s + 64.0, s, s], [s, s + 64.0, s]);
    assert!(in_circumcircle_coplanar(a, b, c, [s + 16.0, s + 16.0, s]));
    assert!(!in_circumcircle_coplanar(a, b, c, [s + 64.0, s + 64.0, s]));
    assert!(!in_circumcircle_coplanar(a, b, c, [s + 128.0, s + 64.0, s]));
}

#[test]
fn brio_order_is_a_permutation_and_hilbert_steps_are_unit() {
    let pts = random_points(3000, 71);
    let order = brio_hilbert_order(&pts, 9);
    let mut seen = vec![false; pts.len()];
    for &i in &order {
        assert!(!seen[i as usize]);
        seen[i as usize] = true;
    }
    assert!(seen.iter().all(|&s| s));
    assert_eq!(brio_hilbert_order(&pts, 9), order, "not deterministic");
    // The first 4^3 curve positions fill the 4x4x4 corner block, one cell per step.
    let mut by_index = vec![None; 64];
    for x in 0..4u32 {
        for y in 0..4u32 {
            for z in 0..4u32 {
                let h = hilbert_index_bits([x, y, z], 21);
                assert!(h < 64, "cell {x} {y} {z} -> {h}");
                assert!(by_index[h as usize].is_none());
                by_index[h as usize] = Some([x, y, z]);
            }
        }
    }
    for w in by_index.windows(2) {
        let (p, q) = (w[0].unwrap(), w[1].unwrap());
        let d: u32 = (0..3).map(|k| p[k].abs_diff(q[k])).sum();
        assert_eq!(d, 1, "{p:?} -> {q:?}");
    }
}

#[test]
fn coarse_hilbert_curves_visit_every_cell_by_unit_steps() {
    for bits in 1..=3u32 {
        let side = 1u32 << bits;
        let mut by_index = vec![None; (side * side * side) as usize];
        for x in 0..side {
            for y in 0..side {
                for z in 0..side {
                    let h = hilbert_index_bits([x, y, z], bits) as usize;
                    assert!(by_index[h].is_none(), "bits {bits}: index {h} twice");
                    by_index[h] = Some([x, y, z]);
                }
            }
        }
        for w in by_index.windows(2) {
            let (p, q) = (w[0].unwrap(), w[1].unwrap());
            let d: u32 = (0..3).map(|k| p[k].abs_diff(q[k])).sum();
            assert_eq!(d, 1, "bits {bits}: {p:?} -> {q:?}");
        }
    }
}

#[test]
fn kernel_vertices_map_back_to_input_numbering() {
    let pts = random_points(100, 81);
    let (tets, input_of) = build(&pts).unwrap();
    for v in 0..tets.num_vertices() as u32 {
        assert_eq!(tets.point(v), pts[input_of[v as usize] as usize]);
    }
    let m = delaunay3d(&pts).unwrap();
    let live_real = (0..tets.num_slots() as u32)
        .filter(|&t| tets.alive(t) && !tets.is_ghost(t))
        .count();
    assert_eq!(m.tets.len(), live_real);
    assert_eq!(m.faces.len(), tets.num_live() - live_real);
}

#[test]
fn filtered_insphere_agrees_with_the_exact_predicate_near_degeneracy() {
    let sign = |x: f64| (x > 0.0) as i32 - (x < 0.0) as i32;
    let mut r = Rng(91);
    let sphere = |r: &mut Rng, rad: f64, c: [f64; 3]| {
        let (u, t) = (2.0 * r.f64() - 1.0, std::f64::consts::TAU * r.f64());
        let q = (1.0 - u * u).sqrt();
        [
            c[0] + rad * q * t.cos(),
            c[1] + rad * q * t.sin(),
            c[2] + rad * u,
        ]
    };
    let mut decided = 0;
    for i in 0..20000 {
        // Five points on one sphere in floating point: the determinant is rounding noise.
        let (rad, c) = match i % 3 {
            0 => (1.0, [0.0; 3]),
            1 => (1e-3, [0.5, 0.25, 0.125]),
            _ => (7.0, [100.0, -3.0, 12.0]),
        };
        let p: Vec<[f64; 3]> = (0..5).map(|_| sphere(&mut r, rad, c)).collect();
        // The exact stage alone (itself checked against `robust` in tests/predicates_oracle.rs).
        let exact = sign(insphere_exact(p[0], p[1], p[2], p[3], p[4]));
        assert_eq!(
            sign(insphere_fast(p[0], p[1], p[2], p[3], p[4])),
            exact,
            "case {i}"
        );
        if let Some(dd) = insphere_dd(p[0], p[1], p[2], p[3], p[4]) {
            assert_eq!(sign(dd), exact, "double-double, case {i}");
            decided += 1;
        }
    }
    // The double-double stage must settle nearly all of these (that is its purpose).
    assert!(decided > 19000, "double-double decided only {decided}");
    // Exactly cospherical integer points: every stage must say 0 or defer.
    for p in [
        [3.0, 0.0, 4.0],
        [0.0, 5.0, 0.0],
        [-4.0, 3.0, 0.0],
        [0.0, 0.0, -5.0],
    ] {
        let q = [
            [5.0, 0.0, 0.0],
            [0.0, -5.0, 0.0],
            [0.0, 4.0, 3.0],
            [4.0, 0.0, -3.0],
        ];
        assert_eq!(insphere_fast(q[0], q[1], q[2], q[3], p), 0.0);
        assert!(insphere_dd(q[0], q[1], q[2], q[3], p).is_none());
        assert_eq!(
            insphere_small_integers(q[0], q[1], q[2], q[3], p),
            Some(0.0)
        );
    }
    // Small-integer (after scaling) differences: exact, and agrees with the exact predicate.
    let mut r = Rng(92);
    let mut integral = 0;
    for i in 0..20000 {
        let s = [1.0, 0.125, 1024.0, 3.0 / 64.0][i % 4];
        let off = [0.0, 1e6, -37.5, 2.0f64.powi(-30)][(i / 4) % 4];
        let p: Vec<[f64; 3]> = (0..5)
            .map(|_| [0, 1, 2].map(|_| off + s * (r.below(9) as f64 - 4.0)))
            .collect();
        // The exact stage alone (itself checked against `robust` in tests/predicates_oracle.rs).
        let exact = sign(insphere_exact(p[0], p[1], p[2], p[3], p[4]));
        assert_eq!(
            sign(insphere_fast(p[0], p[1], p[2], p[3], p[4])),
            exact,
            "case {i}"
        );
        if let Some(v) = insphere_small_integers(p[0], p[1], p[2], p[3], p[4]) {
            assert_eq!(sign(v), exact, "integer path, case {i}");
            integral += 1;
        }
    }
    assert_eq!(integral, 20000);
    // Differences that are not small integers after scaling are left to the other stages.
    let q = [
        [0.1, 0.0, 0.0],
        [0.0, 0.3, 0.0],
        [0.0, 0.0, 0.7],
        [1.0, 1.0, 1.0],
    ];
    assert!(insphere_small_integers(q[0], q[1], q[2], q[3], [0.2, 0.2, 0.2]).is_none());
}

#[test]
fn tiny_point_sets_give_the_same_tets_as_their_scaled_copy() {
    // Coordinates of 2^-1000: orientation and insphere products underflow, so the points
    // are triangulated scaled up by a power of two (exact) and put back as they were.
    let mut pts = random_points(200, 5);
    for i in 0..3 {
        for j in 0..3 {
            for k in 0..3 {
                pts.push([i as f64, j as f64, k as f64]); // cospherical ties
            }
        }
    }
    let s = 2f64.powi(-1000);
    let tiny: Vec<[f64; 3]> = pts.iter().map(|p| p.map(|x| x * s)).collect();
    let want = sorted_tets(&delaunay3d(&pts).unwrap());
    let m = delaunay3d(&tiny).unwrap();
    assert_eq!(m.vertices, tiny);
    assert_eq!(sorted_tets(&m), want);
}

/// Two octahedra around one vertex, the second turned and twice as large: each star is closed
/// and every edge's tets turn around it exactly once, but the tets wind twice around the
/// centre.
#[test]
fn validate_catches_tets_winding_twice_around_a_vertex() {
    let mut vertices = vec![[0.0; 3]];
    let mut tets = Vec::new();
    let mut neighbors = Vec::new();
    let (c, s) = (0.6f64, 0.8f64);
    let turn = |p: [f64; 3]| {
        // About x, then about z: no axis point of the second star on the first's.
        let q = [p[0], c * p[1] - s * p[2], s * p[1] + c * p[2]];
        [
            2.0 * (c * q[0] - s * q[1]),
            2.0 * (s * q[0] + c * q[1]),
            2.0 * q[2],
        ]
    };
    for star in 0..2u32 {
        let base = vertices.len() as u32;
        for k in 0..6 {
            let mut p = [0.0; 3];
            p[k / 2] = if k % 2 == 0 { 1.0 } else { -1.0 };
            vertices.push(if star == 0 { p } else { turn(p) });
        }
        // Octant o (bit i set: the negative axis i); vertex of axis i there.
        let at = |o: u32, i: u32| base + 2 * i + ((o >> i) & 1);
        for o in 0..8u32 {
            let v = [0, at(o, 0), at(o, 1), at(o, 2)];
            let n = [NONE, o ^ 1, o ^ 2, o ^ 4].map(|x| if x == NONE { x } else { 8 * star + x });
            let p = |v: u32| vertices[v as usize];
            if orient3d(p(v[0]), p(v[1]), p(v[2]), p(v[3])) < 0.0 {
                tets.push(v);
                neighbors.push(n);
            } else {
                tets.push([v[0], v[1], v[3], v[2]]);
                neighbors.push([n[0], n[1], n[3], n[2]]);
            }
        }
    }
    let mesh = |tets: Vec<[u32; 4]>, neighbors: Vec<[u32; 4]>| TetMesh {
        vertex_markers: vec![0; vertices.len()],
        num_input_vertices: vertices.len(),
        vertices: vertices.clone(),
        tets,
        neighbors,
        complete: true,
        ..TetMesh::default()
    };
    // One octahedron alone is fine (its unused second star's vertices are no tet's).
    crate::mesh3d::validate::check_output(&mesh(tets[..8].to_vec(), neighbors[..8].to_vec()), 2)
        .unwrap();
    match crate::mesh3d::validate::check_output(&mesh(tets.clone(), neighbors.clone()), 2) {
        Err(Error::Internal(s)) => assert!(s.contains("around vertex 0"), "{s}"),
        other => panic!("overlap not caught: {other:?}"),
    }
    // The same with every vertex's aimed direction on a face of its first tet, so that no
    // star is proved by counting: the edge walks and the Euler count must catch it.
    let tie = |c: [[f64; 3]; 4]| [0, 1, 2].map(|k| (c[1][k] + c[2][k]) / 2.0);
    let aimed = |m: &TetMesh| crate::mesh3d::validate::check_output_with(m, tie, 1);
    aimed(&mesh(tets[..8].to_vec(), neighbors[..8].to_vec())).unwrap();
    match aimed(&mesh(tets, neighbors)) {
        Err(Error::Internal(s)) => assert!(
            s.contains("around vertex 0 do not wind around it exactly once (16 tets, 12 edges)"),
            "{s}"
        ),
        other => panic!("overlap not caught: {other:?}"),
    }
}

/// The vertex-star proof and its fallback agree on valid meshes: Delaunay meshes of random
/// points and of a grid (cospherical ties everywhere) pass with the usual aim points and with
/// aims that tie on every vertex, which leaves every edge to the walks.
#[test]
fn output_check_passes_valid_meshes_with_and_without_ties() {
    let grid: Vec<[f64; 3]> = (0..64)
        .map(|i| [i / 16, i / 4 % 4, i % 4].map(f64::from))
        .collect();
    let tie = |c: [[f64; 3]; 4]| [0, 1, 2].map(|k| (c[1][k] + c[2][k]) / 2.0);
    let centroid =
        |c: [[f64; 3]; 4]| [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k] + c[3][k]) / 4.0);
    for pts in [random_points(300, 7), grid] {
        let m = delaunay3d(&pts).unwrap();
        crate::mesh3d::validate::check_output(&m, 2).unwrap();
        for aim in [tie as crate::mesh3d::validate::Aim, centroid] {
            crate::mesh3d::validate::check_output_with(&m, aim, 1).unwrap();
        }
    }
}

/// The output check splits its passes over threads; what it reports must not depend on how
/// many: a valid mesh passes, and with faults in both halves of the tets the first one (in tet
/// order) is named for every thread count.
#[test]
fn output_check_reports_the_same_for_any_thread_count() {
    use crate::mesh3d::validate::{aim_into, check_output_with};
    let m = delaunay3d(&random_points(40_000, 3)).unwrap();
    assert!(
        m.tets.len() > 4 << 16,
        "{} tets: too few for four chunks",
        m.tets.len()
    );
    for threads in [1, 2, 3, 4] {
        check_output_with(&m, aim_into, threads).unwrap();
    }
    let n = m.tets.len();
    let message = |m: &TetMesh, threads| match check_output_with(m, aim_into, threads) {
        Err(Error::Internal(s)) => s,
        other => panic!("fault not caught with {threads} threads: {other:?}"),
    };
    // Inverted tets (the counting pass) and a broken link (the neighbour pass).
    let mut bad = m.clone();
    bad.tets[n / 2].swap(0, 1);
    bad.tets[n - 1].swap(0, 1);
    let mut unlinked = m.clone();
    let (t, i) = (3 * n / 4..n)
        .flat_map(|t| (0..4).map(move |i| (t, i)))
        .find(|&(t, i)| m.neighbors[t][i] != NONE && (m.neighbors[t][i] as usize) > t)
        .unwrap();
    unlinked.neighbors[t][i] = unlinked.neighbors[t][(i + 1) % 4];
    let first = message(&bad, 1);
    assert!(first.contains(&format!("tet {} ", n / 2)), "{first}");
    for broken in [bad, unlinked] {
        let one = message(&broken, 1);
        for threads in [2, 3, 4] {
            assert_eq!(message(&broken, threads), one);
        }
    }
}
