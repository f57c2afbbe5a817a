//! `idmesh tetgen` with TetGen's `-r` (refine a previous mesh, with `.vol` bounds), `-i`
//! (`FILE.a.node`), `-m` (`FILE.mtr`), `-o2` (10-node tetrahedra), `-X` and `-e` (every
//! edge), and point attributes carried to the output: each checked on the files written.

mod cli_common;

use cli_common::{idmesh, ok};
use idmesh::io::tetgen::{parse_edge, parse_ele, parse_node};

fn workdir(name: &str) -> cli_common::WorkDir {
    cli_common::workdir(&format!("tetgen-switches-{name}"), &["3d_cube.poly"])
}

fn read(d: &std::path::Path, f: &str) -> String {
    std::fs::read_to_string(d.join(f)).unwrap_or_else(|e| panic!("{f}: {e}"))
}

/// Points and tetrahedra (first four nodes) of `stem.node` / `stem.ele`, 0-based.
fn mesh(d: &std::path::Path, stem: &str) -> (Vec<[f64; 3]>, Vec<[u32; 4]>, usize) {
    let node = parse_node(&read(d, &format!("{stem}.node")), "node").unwrap();
    let pts = node.plc.points;
    let text = read(d, &format!("{stem}.ele"));
    let nodes: usize = text.split_whitespace().nth(1).unwrap().parse().unwrap();
    let ele = parse_ele(&text, "ele", node.base, pts.len()).unwrap();
    (pts, ele.tets, nodes)
}

fn volume(p: &[[f64; 3]], t: &[u32; 4]) -> f64 {
    let c = t.map(|v| p[v as usize]);
    idmesh::geometry::tet_volume(c)
}

#[test]
fn o2_writes_shared_midpoint_nodes_and_e_every_edge() {
    let d = workdir("o2");
    ok(&idmesh(&d, &["tetgen", "-pq1.4a0.05o2eXQ", "3d_cube.poly"]));
    let node = parse_node(&read(&d, "3d_cube.1.node"), "node").unwrap();
    let pts = node.plc.points;
    let text = read(&d, "3d_cube.1.ele");
    let mut lines = text.lines();
    let head: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(head[1], 10, "10 nodes per tetrahedron");
    let order = [(2, 3), (0, 3), (0, 1), (1, 2), (1, 3), (0, 2)];
    let mut node_of = std::collections::HashMap::new();
    let b = node.base as usize;
    for line in lines.filter(|l| !l.trim().is_empty() && !l.starts_with('#')) {
        let v: Vec<usize> = line
            .split_whitespace()
            .skip(1)
            .map(|x| x.parse::<usize>().unwrap() - b)
            .collect();
        for (k, &(i, j)) in order.iter().enumerate() {
            let (p, q, m) = (pts[v[i]], pts[v[j]], pts[v[4 + k]]);
            assert_eq!(m, [0, 1, 2].map(|c| (p[c] + q[c]) / 2.0));
            let e = (v[i].min(v[j]), v[i].max(v[j]));
            assert_eq!(
                *node_of.entry(e).or_insert(v[4 + k]),
                v[4 + k],
                "shared node"
            );
        }
    }
    // -e: every edge once, which here are exactly the edges carrying an o2 node.
    let edges = parse_edge(&read(&d, "3d_cube.1.edge"), "edge", node.base, pts.len()).unwrap();
    let listed: std::collections::HashSet<(usize, usize)> = edges
        .items
        .iter()
        .map(|e| (e[0].min(e[1]) as usize, e[0].max(e[1]) as usize))
        .collect();
    assert_eq!(listed.len(), edges.items.len());
    let all: std::collections::HashSet<(usize, usize)> = node_of.keys().copied().collect();
    assert_eq!(listed, all);
}

#[test]
fn r_refines_a_previous_mesh_to_its_vol_bounds_keeping_points_and_volume() {
    let d = workdir("r");
    ok(&idmesh(&d, &["tetgen", "-pq1.4Q", "3d_cube.poly"]));
    let (p1, t1, _) = mesh(&d, "3d_cube.1");
    let v1: f64 = t1.iter().map(|t| volume(&p1, t)).sum();
    // Bound every tetrahedron by a twentieth of its volume.
    let mut vol = format!("{}\n", t1.len());
    for (i, t) in t1.iter().enumerate() {
        vol += &format!("{} {}\n", i + 1, volume(&p1, t) / 20.0);
    }
    std::fs::write(d.join("3d_cube.1.vol"), vol).unwrap();
    ok(&idmesh(&d, &["tetgen", "-raQ", "3d_cube.1"]));
    let (p2, t2, _) = mesh(&d, "3d_cube.2");
    assert_eq!(
        &p2[..p1.len()],
        &p1[..],
        "the given points keep their indices"
    );
    let v2: f64 = t2.iter().map(|t| volume(&p2, t)).sum();
    assert!((v1 - v2).abs() < 1e-9 * v1, "{v1} vs {v2}");
    assert!(t2.len() > 10 * t1.len(), "{} -> {}", t1.len(), t2.len());
    // Every bound differs, so every given tetrahedron is its own region: each new one lies
    // in one given tetrahedron (the one holding its centroid) and meets that one's bound.
    for t in &t2 {
        let q = t.map(|v| p2[v as usize]);
        let c = [0, 1, 2].map(|k| q.iter().map(|x| x[k]).sum::<f64>() / 4.0);
        let holder = t1
            .iter()
            .find(|g| {
                let whole = volume(&p1, g);
                let parts: f64 = (0..4)
                    .map(|i| {
                        let mut h = g.map(|v| p1[v as usize]);
                        h[i] = c;
                        idmesh::geometry::tet_volume(h).abs()
                    })
                    .sum();
                (parts - whole.abs()).abs() <= 1e-9 * whole.abs()
            })
            .expect("inside a given tetrahedron");
        assert!(volume(&p2, t) <= volume(&p1, holder) / 20.0 * (1.0 + 1e-9));
    }
}

#[test]
fn i_inserts_the_a_node_points_and_m_grades_by_the_mtr_sizes() {
    let d = workdir("im");
    // 3d_cube.poly's corners, read back to give each a size growing with x.
    let cube = idmesh::io::tetgen::read_poly(&d.join("3d_cube.poly")).unwrap();
    let pts = &cube.plc.points;
    let (lo, hi) = pts
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p[0]), b.max(p[0])));
    let w = hi - lo;
    let size = |x: f64| w * (0.1 + 0.4 * (x - lo) / w);
    let mut mtr = format!("{} 1\n", pts.len());
    for p in pts {
        mtr += &format!("{}\n", size(p[0]));
    }
    std::fs::write(d.join("3d_cube.mtr"), mtr).unwrap();
    let c = [0, 1, 2].map(|k| pts.iter().map(|p| p[k]).sum::<f64>() / pts.len() as f64);
    std::fs::write(
        d.join("3d_cube.a.node"),
        format!("1 3 0 0\n1 {} {} {}\n", c[0], c[1], c[2]),
    )
    .unwrap();
    ok(&idmesh(&d, &["tetgen", "-pimQ", "3d_cube.poly"]));
    let (p, t, _) = mesh(&d, "3d_cube.1");
    let added = p
        .iter()
        .position(|q| *q == c)
        .expect("the a.node point is a vertex");
    assert!(t.iter().any(|tv| tv.contains(&(added as u32))));
    assert!(t.len() > 100);
    for tv in &t {
        let q = tv.map(|v| p[v as usize]);
        let cx = q.iter().map(|x| x[0]).sum::<f64>() / 4.0;
        let mut longest: f64 = 0.0;
        for i in 0..4 {
            for j in i + 1..4 {
                let d2: f64 = (0..3).map(|k| (q[i][k] - q[j][k]).powi(2)).sum();
                longest = longest.max(d2.sqrt());
            }
        }
        assert!(
            longest <= size(cx) * (1.0 + 1e-9),
            "{longest} > {}",
            size(cx)
        );
    }
    // Without the .mtr file, -m is an error naming it.
    std::fs::remove_file(d.join("3d_cube.mtr")).unwrap();
    let o = idmesh(&d, &["tetgen", "-pmQ", "3d_cube.poly"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("3d_cube.mtr"));
}

#[test]
fn point_attributes_are_interpolated_at_steiner_points() {
    let d = workdir("attr");
    let cube = idmesh::io::tetgen::read_poly(&d.join("3d_cube.poly")).unwrap();
    let f = |p: [f64; 3]| 2.0 * p[0] - p[1] + 0.5 * p[2] + 1.0;
    let mut node = format!("{} 3 1 0\n", cube.plc.points.len());
    for (i, p) in cube.plc.points.iter().enumerate() {
        node += &format!("{} {} {} {} {}\n", i + 1, p[0], p[1], p[2], f(*p));
    }
    std::fs::write(d.join("c.node"), node).unwrap();
    // The .poly with its own points replaced by "0 3 0 0": the .node is read beside it.
    let poly = read(&d, "3d_cube.poly");
    let n = cube.plc.points.len();
    let rest: Vec<&str> = poly
        .lines()
        .filter(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
        .skip(n + 1)
        .collect();
    std::fs::write(d.join("c.poly"), format!("0 3 0 0\n{}\n", rest.join("\n"))).unwrap();
    ok(&idmesh(&d, &["tetgen", "-pq1.4a0.01Q", "c.poly"]));
    let out = parse_node(&read(&d, "c.1.node"), "node").unwrap();
    assert_eq!(out.num_point_attributes, 1);
    assert!(out.plc.points.len() > n);
    for (p, a) in out.plc.points.iter().zip(&out.point_attributes) {
        assert!((a - f(*p)).abs() < 1e-9, "{p:?}: {a} vs {}", f(*p));
    }
}
