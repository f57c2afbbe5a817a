//! Integration tests of the `idmesh` command line: switch parsing, Triangle's output files and
//! their numbering, and one-line errors with exit status 1.
//!
//! Each test works in its own temporary directory and reads the outputs back with the
//! library's Triangle readers (themselves unit-tested against hand-written text).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use idmesh::io::triangle::{parse_ele, parse_node, parse_poly};
use idmesh::predicates::orient2d;

/// A directory removed when the test ends (pass or fail).
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let p = std::env::temp_dir().join(format!("idmesh-cli-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(&p).unwrap();
        TempDir(p)
    }

    fn path(&self, file: &str) -> PathBuf {
        self.0.join(file)
    }

    fn write(&self, file: &str, text: &str) {
        std::fs::write(self.path(file), text).unwrap();
    }

    fn read(&self, file: &str) -> String {
        std::fs::read_to_string(self.path(file))
            .unwrap_or_else(|e| panic!("cannot read {file}: {e}"))
    }

    fn exists(&self, file: &str) -> bool {
        self.path(file).exists()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn idmesh(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_idmesh"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("cannot run idmesh")
}

/// Asserts success and returns stdout.
fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "idmesh failed ({:?}): {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Asserts exit status 1 with exactly one `idmesh: ` line on stderr; returns that line.
fn fails(out: &Output) -> String {
    assert_eq!(
        out.status.code(),
        Some(1),
        "expected exit 1, stdout: {:?}",
        out.stdout
    );
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "expected one stderr line, got {err:?}");
    assert!(lines[0].starts_with("idmesh: "), "{err:?}");
    lines[0].to_string()
}

/// Unit square, 1-based, boundary markers 1 (vertices) and 7 (segments).
const SQUARE: &str = "\
# unit square
4 2 0 1
1 0 0 1
2 1 0 1
3 1 1 1
4 0 1 1
4 1
1 1 2 7
2 2 3 7
3 3 4 7
4 4 1 7
0
";

/// The unit square with both diagonals as segments 5 and 6: they cross at the centre.
const CROSSING: &str = "\
4 2 0 0
1 0 0
2 1 0
3 1 1
4 0 1
6 0
1 1 2
2 2 3
3 3 4
4 4 1
5 1 3
6 2 4
0
";

/// First line of a file, split into fields.
fn header(text: &str) -> Vec<String> {
    text.lines()
        .find(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .unwrap_or("")
        .split_whitespace()
        .map(str::to_string)
        .collect()
}

/// Data lines after the header, as fields.
fn rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .map(|l| l.split('#').next().unwrap_or(""))
        .filter(|l| !l.trim().is_empty())
        .skip(1)
        .map(|l| l.split_whitespace().map(str::to_string).collect())
        .collect()
}

/// Reads `stem.node` and `stem.ele` back: vertices and 0-based triangles.
fn read_mesh(dir: &TempDir, stem: &str, base: u32) -> (Vec<[f64; 2]>, Vec<[u32; 3]>) {
    let node = parse_node(&dir.read(&format!("{stem}.node")), "node").unwrap();
    assert_eq!(node.base, base, "numbering of {stem}.node");
    let n = node.pslg.points.len();
    let ele = parse_ele(&dir.read(&format!("{stem}.ele")), "ele", base, n).unwrap();
    (node.pslg.points, ele.triangles)
}

fn tri_area(p: &[[f64; 2]], t: [u32; 3]) -> f64 {
    let [a, b, c] = t.map(|i| p[i as usize]);
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

// ---------------------------------------------------------------------------------------------
// Command line handling (independent of the mesher).

#[test]
fn unknown_switch_exits_1_with_a_message_naming_it() {
    let d = TempDir::new("unknown");
    d.write("sq.poly", SQUARE);
    let line = fails(&idmesh(&d.0, &["triangle", "-pqx", "sq.poly"]));
    assert!(line.contains("-x"), "{line}");
    assert!(!d.exists("sq.1.node"), "no output on error");
    let line = fails(&idmesh(&d.0, &["triangle", "-pw", "sq.poly"]));
    assert!(
        line.contains("-w") && line.contains("not supported"),
        "{line}"
    );
    let line = fails(&idmesh(&d.0, &["triangle", "-pa1e-5", "sq.poly"]));
    assert!(line.contains("exponent"), "{line}");
    let line = fails(&idmesh(&d.0, &["triangle", "-pa0", "sq.poly"]));
    assert!(line.contains("greater than zero"), "{line}");
}

#[test]
fn help_version_and_commands() {
    let d = TempDir::new("help");
    let out = ok(&idmesh(&d.0, &["--help"]));
    assert!(out.contains("idmesh triangle"), "{out}");
    let out = ok(&idmesh(&d.0, &["triangle", "--help"]));
    assert!(out.contains("-q") && out.contains("-a"), "{out}");
    let out = ok(&idmesh(&d.0, &["--version"]));
    assert!(out.contains(env!("CARGO_PKG_VERSION")), "{out}");
    // A missing input for the 3D command: an error naming the file (or, before the 3D mesher
    // landed, saying it is not implemented).
    let line = fails(&idmesh(&d.0, &["tetgen", "-pq", "x.poly"]));
    assert!(
        line.contains("x.poly") || line.contains("not implemented"),
        "{line}"
    );
    let line = fails(&idmesh(&d.0, &[]));
    assert!(line.contains("no command"), "{line}");
    let line = fails(&idmesh(&d.0, &["trinagle", "x"]));
    assert!(line.contains("trinagle"), "{line}");
    let line = fails(&idmesh(&d.0, &["triangle", "-p"]));
    assert!(line.contains("no input file"), "{line}");
}

#[test]
fn unreadable_and_malformed_inputs_exit_1_naming_file_and_line() {
    let d = TempDir::new("badfile");
    let line = fails(&idmesh(&d.0, &["triangle", "-p", "missing.poly"]));
    assert!(line.contains("missing.poly"), "{line}");
    d.write("bad.poly", "3 2 0 0\n1 0 0\n2 1 zero\n3 0 1\n0 0\n0\n");
    let line = fails(&idmesh(&d.0, &["triangle", "-p", "bad.poly"]));
    assert!(
        line.contains("bad.poly:3:") && line.contains("zero"),
        "{line}"
    );
    // Without -p the .node file is read, and here it does not exist.
    d.write("only.poly", SQUARE);
    let line = fails(&idmesh(&d.0, &["triangle", "only"]));
    assert!(line.contains("only.node"), "{line}");
}

// ---------------------------------------------------------------------------------------------
// Meshing runs (need a working `triangulate`).

#[test]
fn outputs_have_triangle_headers_and_consistent_counts() {
    let d = TempDir::new("square");
    d.write("sq.poly", SQUARE);
    ok(&idmesh(&d.0, &["triangle", "-pq30a0.01Q", "sq.poly"]));
    for f in ["sq.1.node", "sq.1.ele", "sq.1.poly"] {
        assert!(d.exists(f), "{f} missing");
    }
    assert!(!d.exists("sq.1.edge") && !d.exists("sq.1.neigh"));

    let node = d.read("sq.1.node");
    let h = header(&node);
    assert_eq!(h[1..], ["2", "0", "1"], "node header {h:?}");
    let nv: usize = h[0].parse().unwrap();
    assert_eq!(rows(&node).len(), nv);
    let ele = d.read("sq.1.ele");
    let h = header(&ele);
    assert_eq!(h[1..], ["3", "0"], "ele header {h:?}");
    let nt: usize = h[0].parse().unwrap();
    assert_eq!(rows(&ele).len(), nt);
    assert!(
        nt >= 100,
        "area bound 0.01 on the unit square needs >= 100 triangles, got {nt}"
    );

    let (pts, tris) = read_mesh(&d, "sq.1", 1);
    assert_eq!(pts[..4], [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    let mut total = 0.0;
    for &t in &tris {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        assert!(
            orient2d(a, b, c) > 0.0,
            "triangle {t:?} is not counter-clockwise"
        );
        let area = tri_area(&pts, t);
        assert!(
            area <= 0.01 * (1.0 + 1e-12),
            "triangle {t:?} has area {area}"
        );
        total += area;
    }
    assert!((total - 1.0).abs() < 1e-12, "total area {total}");

    // The .poly output: vertices in the .node file, subsegments keep marker 7.
    let poly = d.read("sq.1.poly");
    assert_eq!(header(&poly), ["0", "2", "0", "1"]);
    let back = parse_poly(&poly, "sq.1.poly", || parse_node(&node, "sq.1.node")).unwrap();
    assert!(back.pslg.segments.len() >= 4);
    assert!(back.pslg.segment_markers.iter().all(|&m| m == 7), "{poly}");
    let on_boundary = |p: [f64; 2]| p[0] == 0.0 || p[0] == 1.0 || p[1] == 0.0 || p[1] == 1.0;
    for s in &back.pslg.segments {
        assert!(on_boundary(pts[s[0] as usize]) && on_boundary(pts[s[1] as usize]));
    }
}

#[test]
fn numbering_follows_the_input_or_starts_at_zero_with_z() {
    let d = TempDir::new("base");
    d.write("sq.poly", SQUARE);
    ok(&idmesh(&d.0, &["triangle", "-pq30a0.05Q", "sq.poly"]));
    let (pts1, tris1) = read_mesh(&d, "sq.1", 1);
    assert_eq!(rows(&d.read("sq.1.node"))[0][0], "1");
    assert_eq!(rows(&d.read("sq.1.ele"))[0][0], "1");
    let max = tris1.iter().flatten().max().copied().unwrap() as usize;
    assert!(max < pts1.len());

    ok(&idmesh(&d.0, &["triangle", "-pq30a0.05zQ", "sq.poly"]));
    let (pts0, tris0) = read_mesh(&d, "sq.1", 0);
    assert_eq!(rows(&d.read("sq.1.node"))[0][0], "0");
    assert_eq!(rows(&d.read("sq.1.ele"))[0][0], "0");
    assert!(
        tris0.iter().flatten().any(|&v| v == 0),
        "vertex 0 is used in base 0"
    );
    // Same mesh either way: only the numbering differs.
    assert_eq!(pts0, pts1);
    assert_eq!(tris0, tris1);
}

#[test]
fn edge_and_neigh_files_are_consistent() {
    let d = TempDir::new("edges");
    d.write("sq.poly", SQUARE);
    ok(&idmesh(&d.0, &["triangle", "-pq30a0.02enQ", "sq.poly"]));
    let (pts, tris) = read_mesh(&d, "sq.1", 1);
    let nt = tris.len();

    let neigh = d.read("sq.1.neigh");
    assert_eq!(header(&neigh), [nt.to_string(), "3".to_string()]);
    let nrows: Vec<Vec<i64>> = rows(&neigh)
        .iter()
        .map(|r| r.iter().map(|f| f.parse().unwrap()).collect())
        .collect();
    assert_eq!(nrows.len(), nt);
    let mut boundary = 0;
    for (t, r) in nrows.iter().enumerate() {
        assert_eq!(r[0], t as i64 + 1, "neigh rows are numbered from 1");
        for k in 0..3 {
            let n = r[1 + k];
            if n == -1 {
                boundary += 1;
                continue;
            }
            assert!(n >= 1 && n <= nt as i64, "neighbour {n} out of range");
            // Symmetry, and the shared edge is the one opposite corner k.
            let back = &nrows[(n - 1) as usize];
            assert!(
                back[1..].contains(&(t as i64 + 1)),
                "{t} -> {n} is not symmetric"
            );
            let tri = tris[t];
            let (a, b) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let other = tris[(n - 1) as usize];
            assert!(
                other.contains(&a) && other.contains(&b),
                "edge opposite corner {k}"
            );
        }
    }

    let edge = d.read("sq.1.edge");
    assert_eq!(header(&edge)[1], "1");
    let erows = rows(&edge);
    let ne: usize = header(&edge)[0].parse().unwrap();
    assert_eq!(erows.len(), ne);
    assert_eq!(
        2 * ne,
        3 * nt + boundary,
        "each interior edge is shared by two triangles"
    );
    // Boundary edges carry the segment marker 7, interior edges 0; Euler: V - E + F = 1.
    let used: std::collections::BTreeSet<u32> = tris.iter().flatten().copied().collect();
    assert_eq!(used.len() as i64 - ne as i64 + nt as i64, 1);
    let marked = erows.iter().filter(|r| r[3] == "7").count();
    assert_eq!(marked, boundary);
    assert!(erows.iter().all(|r| r[3] == "7" || r[3] == "0"));
    assert!(pts.len() >= used.len());
}

#[test]
fn capital_n_e_p_suppress_outputs() {
    let d = TempDir::new("suppress");
    d.write("sq.poly", SQUARE);
    ok(&idmesh(&d.0, &["triangle", "-pq30NEPeQ", "sq.poly"]));
    assert!(!d.exists("sq.1.node") && !d.exists("sq.1.ele") && !d.exists("sq.1.poly"));
    assert!(d.exists("sq.1.edge"));
}

#[test]
fn crossing_segments_exit_1_naming_both() {
    let d = TempDir::new("crossing");
    d.write("x.poly", CROSSING);
    let line = fails(&idmesh(&d.0, &["triangle", "-pQ", "x.poly"]));
    assert!(
        line.contains("segments 5 and 6") || line.contains("segments 6 and 5"),
        "segments numbered as in the 1-based file: {line}"
    );
    assert!(line.contains("x.poly"), "{line}");
    assert!(!d.exists("x.1.node"));
}

#[test]
fn iteration_numbers_and_poly_extension_imply_p() {
    let d = TempDir::new("iter");
    d.write("sq.1.poly", SQUARE);
    // No -p: the .poly extension implies it, as in Triangle, so a .poly is written too.
    ok(&idmesh(&d.0, &["triangle", "-q", "-Q", "sq.1.poly"]));
    assert!(d.exists("sq.2.node") && d.exists("sq.2.ele") && d.exists("sq.2.poly"));
    // The output .poly can be meshed again (its vertices are in sq.2.node).
    ok(&idmesh(&d.0, &["triangle", "-pq30a0.05Q", "sq.2"]));
    let (pts, tris) = read_mesh(&d, "sq.3", 1);
    let total: f64 = tris.iter().map(|&t| tri_area(&pts, t)).sum();
    assert!((total - 1.0).abs() < 1e-12, "total area {total}");
}

#[test]
fn point_set_without_p_is_a_delaunay_triangulation_of_the_hull() {
    let d = TempDir::new("points");
    let pts: Vec<[f64; 2]> = (0..30)
        .map(|i| {
            [
                ((i * 37) % 101) as f64 / 101.0,
                ((i * 59) % 97) as f64 / 97.0,
            ]
        })
        .collect();
    let mut text = format!("{} 2 0 0\n", pts.len());
    for (i, p) in pts.iter().enumerate() {
        text += &format!("{i} {} {}\n", p[0], p[1]);
    }
    d.write("pts.node", &text);
    ok(&idmesh(&d.0, &["triangle", "-nQ", "pts"]));
    assert!(!d.exists("pts.1.poly"), "no .poly without -p");
    let (out, tris) = read_mesh(&d, "pts.1", 0);
    assert_eq!(out, pts, "a point set gains no vertices");
    let hull_edges: usize = rows(&d.read("pts.1.neigh"))
        .iter()
        .flatten()
        .filter(|f| *f == "-1")
        .count();
    // Triangulation of n points with b boundary vertices (= boundary edges): 2n - 2 - b.
    assert_eq!(tris.len(), 2 * pts.len() - 2 - hull_edges);
}

#[test]
fn poly_with_zero_vertices_reads_the_node_file() {
    let d = TempDir::new("zero");
    d.write("t.node", "3 2 0 0\n0 0 0\n1 2 0\n2 0 2\n");
    d.write("t.poly", "0 2 0 0\n3 0\n0 0 1\n1 1 2\n2 2 0\n0\n");
    ok(&idmesh(&d.0, &["triangle", "-pa0.1Q", "t.poly"]));
    let (pts, tris) = read_mesh(&d, "t.1", 0);
    let total: f64 = tris.iter().map(|&t| tri_area(&pts, t)).sum();
    assert!((total - 2.0).abs() < 1e-12, "total area {total}");
    assert!(tris
        .iter()
        .all(|&t| tri_area(&pts, t) <= 0.1 * (1.0 + 1e-12)));
}

#[test]
fn segments_enclosing_no_area_give_an_empty_mesh_and_a_warning_naming_an_open_end() {
    // The unit square without its left side (as in Triangle's box example): as Triangle, an
    // empty mesh and exit status 0; the warning names an open end, numbered as in the file.
    let d = TempDir::new("open");
    let open = SQUARE.replace("4 1\n", "3 1\n").replace("4 4 1 7\n", "");
    d.write("open.poly", &open);
    let out = idmesh(&d.0, &["triangle", "-pq30Q", "open.poly"]);
    ok(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.lines().count() == 1
            && err.contains("warning: the mesh has no triangles")
            && err.contains("2 of their ends are open, e.g. at point 1"),
        "{err:?}"
    );
    assert!(read_mesh(&d, "open.1", 1).1.is_empty());
    // Closed again: no warning.
    d.write("sq.poly", SQUARE);
    let out = idmesh(&d.0, &["triangle", "-pq30Q", "sq.poly"]);
    ok(&out);
    assert!(
        out.stderr.is_empty(),
        "{:?}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn steiner_cap_warns_but_writes_the_mesh() {
    let d = TempDir::new("steiner");
    d.write("sq.poly", SQUARE);
    let out = idmesh(&d.0, &["triangle", "-pq30a0.0001S5Q", "sq.poly"]);
    ok(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("warning") && err.lines().count() == 1,
        "{err:?}"
    );
    let (pts, tris) = read_mesh(&d, "sq.1", 1);
    assert!(
        pts.len() <= 4 + 5,
        "at most 5 Steiner points, got {} vertices",
        pts.len()
    );
    assert!(!tris.is_empty());
}

#[test]
fn regional_attributes_and_area_bounds() {
    let d = TempDir::new("regions");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/letter_l.poly");
    d.write("l.poly", &std::fs::read_to_string(src).unwrap());
    ok(&idmesh(&d.0, &["triangle", "-pq30aAQ", "l.poly"]));
    let node = parse_node(&d.read("l.1.node"), "l.1.node").unwrap();
    let ele = parse_ele(&d.read("l.1.ele"), "l.1.ele", 0, node.pslg.points.len()).unwrap();
    assert_eq!(ele.num_attributes, 1);
    let mut seen = [false; 2];
    for (t, &a) in ele.triangles.iter().zip(&ele.attributes) {
        let area = tri_area(&node.pslg.points, *t);
        let [p, q, r] = t.map(|i| node.pslg.points[i as usize]);
        let cx = (p[0] + q[0] + r[0]) / 3.0;
        // Region 1 is the bar x < 1 (max area 0.01), region 2 the foot x > 1 (0.05).
        if a == 1.0 {
            assert!(
                cx < 1.0 && area <= 0.01 * (1.0 + 1e-12),
                "attr 1: x {cx}, area {area}"
            );
            seen[0] = true;
        } else {
            assert_eq!(a, 2.0);
            assert!(
                cx > 1.0 && area <= 0.05 * (1.0 + 1e-12),
                "attr 2: x {cx}, area {area}"
            );
            seen[1] = true;
        }
    }
    assert_eq!(seen, [true, true]);
    // The output .poly copies the regions of the input.
    let poly = d.read("l.1.poly");
    let back = parse_poly(&poly, "l.1.poly", || Ok(node.clone())).unwrap();
    assert_eq!(back.pslg.regions.len(), 2);
    assert_eq!(back.pslg.regions[1].max_area, Some(0.05));
}

#[test]
fn readme_main_job_runs_verbosely() {
    let d = TempDir::new("readme");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/square_hole.poly");
    d.write("square_hole.poly", &std::fs::read_to_string(src).unwrap());
    let out = ok(&idmesh(
        &d.0,
        &["triangle", "-pq30a0.01V", "square_hole.poly"],
    ));
    assert!(
        out.contains("triangles") && out.contains("smallest"),
        "{out}"
    );
    let (pts, tris) = read_mesh(&d, "square_hole.1", 1);
    let total: f64 = tris.iter().map(|&t| tri_area(&pts, t)).sum();
    assert!(
        (total - (1.0 - 0.4 * 0.4)).abs() < 1e-12,
        "area minus the hole: {total}"
    );
}

// ---------------------------------------------------------------------------------------------
// -Y: no Steiner points on boundary segments.

/// A thin triangle (0-based) and a point outside it, behind its long side, inside the
/// triangle's circumcircle: a conforming Delaunay mesh must split the long side, `-Y` must
/// leave it whole (the mesh is then only constrained Delaunay).
const SLIVER_AND_POINT: &str = "\
4 2 0 0
0 0 0
1 2 0
2 1 0.1
3 1 -0.2
3 0
0 0 1
1 1 2
2 2 0
0
";

/// The edges used by one triangle only, as 0-based vertex pairs.
fn boundary_of(tris: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let mut count = std::collections::HashMap::new();
    for t in tris {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    count
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|((a, b), _)| [a, b])
        .collect()
}

#[test]
fn y_leaves_boundary_segments_whole() {
    let d = TempDir::new("y-sliver");
    d.write("s.poly", SLIVER_AND_POINT);
    ok(&idmesh(&d.0, &["triangle", "-pYQ", "s.poly"]));
    let (pts, tris) = read_mesh(&d, "s.1", 0);
    assert_eq!((pts.len(), tris.len()), (4, 1), "-pY added a point");
    ok(&idmesh(&d.0, &["triangle", "-pQ", "s.poly"]));
    let (pts, tris) = read_mesh(&d, "s.1", 0);
    assert!(
        pts.len() > 4,
        "the conforming mesh must split the long side"
    );
    let total: f64 = tris.iter().map(|&t| tri_area(&pts, t)).sum();
    assert!((total - 0.1).abs() < 1e-12, "area {total}");
}

#[test]
fn pqy_refines_inside_but_never_splits_the_boundary() {
    let d = TempDir::new("y-letter");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/letter_l.poly");
    d.write("l.poly", &std::fs::read_to_string(src).unwrap());
    // (-pqY needs no new point here, as in Triangle; the area bounds do.)
    for sw in ["-pqYQ", "-pq30aYQ", "-pYq25a0.02Q"] {
        ok(&idmesh(&d.0, &["triangle", sw, "l.poly"]));
        let (pts, tris) = read_mesh(&d, "l.1", 0);
        let boundary = boundary_of(&tris);
        assert_eq!(
            boundary.len(),
            7,
            "{sw}: the 7 boundary segments must stay whole"
        );
        for e in &boundary {
            assert!(
                e[0] < 7 && e[1] < 7,
                "{sw}: boundary edge {e:?} has a Steiner end"
            );
        }
        let total: f64 = tris.iter().map(|&t| tri_area(&pts, t)).sum();
        assert!((total - 3.0).abs() < 1e-12, "{sw}: area {total}");
        assert!(
            sw.contains('a') == (pts.len() > 7),
            "{sw}: {} vertices",
            pts.len()
        );
        // The interior segment (marker 3) is listed, split or not, between vertices 1 and 4.
        let poly = d.read("l.1.poly");
        let node = parse_node(&d.read("l.1.node"), "l.1.node").unwrap();
        let back = parse_poly(&poly, "l.1.poly", || Ok(node.clone())).unwrap();
        let inner: Vec<_> = back
            .pslg
            .segments
            .iter()
            .zip(&back.pslg.segment_markers)
            .filter(|(_, &m)| m == 3)
            .collect();
        assert!(!inner.is_empty(), "{sw}: the interior segment is missing");
        for (s, _) in inner {
            for &v in s {
                assert_eq!(pts[v as usize][0], 1.0, "{sw}: subsegment {s:?} off x = 1");
            }
        }
    }
}

/// The unit square split at x = 0.5 into two regions (attributes 1 and 2), with two interior
/// points; 1-based.
const TWO_REGIONS: &str = "\
8 2 0 1
1 0 0 1
2 1 0 1
3 1 1 1
4 0 1 1
5 0.5 0 1
6 0.5 1 1
7 0.2 0.2 0
8 0.8 0.8 0
7 1
1 1 5 1
2 5 2 1
3 2 3 1
4 3 6 1
5 6 4 1
6 4 1 1
7 5 6 2
0
2
1 0.25 0.5 1 0
2 0.75 0.5 2 0
";

/// A mesh written by `idmesh triangle -e -n` (with `.poly` when `poly`), read back into a
/// `TriMesh` for the exact validity check.
fn read_trimesh(dir: &TempDir, stem: &str, num_input: usize, poly: bool) -> idmesh::TriMesh {
    let node = parse_node(&dir.read(&format!("{stem}.node")), "node").unwrap();
    let base = node.base;
    let n = node.pslg.points.len();
    let ele = parse_ele(&dir.read(&format!("{stem}.ele")), "ele", base, n).unwrap();
    let idx = |s: &str| -> u32 {
        let v: i64 = s.parse().unwrap();
        if v < 0 {
            idmesh::NONE
        } else {
            (v - base as i64) as u32
        }
    };
    let neighbors = rows(&dir.read(&format!("{stem}.neigh")))
        .iter()
        .map(|r| [idx(&r[1]), idx(&r[2]), idx(&r[3])])
        .collect();
    let (segments, segment_markers) = if poly {
        let text = dir.read(&format!("{stem}.poly"));
        let p = parse_poly(&text, "poly", || Ok(node.clone())).unwrap();
        (p.pslg.segments, p.pslg.segment_markers)
    } else {
        (Vec::new(), Vec::new())
    };
    idmesh::TriMesh {
        vertices: node.pslg.points.clone(),
        vertex_markers: node.pslg.point_markers.clone(),
        num_input_vertices: num_input,
        steiner_points: n - num_input,
        triangles: ele.triangles,
        neighbors,
        triangle_attributes: ele.attributes,
        segments,
        segment_markers,
        complete: true,
    }
}

/// Total area per triangle attribute.
fn area_per_attribute(m: &idmesh::TriMesh) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    for (t, &tri) in m.triangles.iter().enumerate() {
        let a = tri_area(&m.vertices, tri);
        let k = m.triangle_attributes[t];
        match out.iter_mut().find(|(x, _)| *x == k) {
            Some((_, s)) => *s += a,
            None => out.push((k, a)),
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

#[test]
fn r_remeshes_a_previous_mesh_keeping_points_regions_and_boundary() {
    let d = TempDir::new("refine");
    d.write("box.poly", TWO_REGIONS);
    ok(&idmesh(&d.0, &["triangle", "-pq30a0.01AenQ", "box.poly"]));
    let m1 = read_trimesh(&d, "box.1", 8, true);
    m1.validate().unwrap();
    let n1 = m1.vertices.len();
    let areas = area_per_attribute(&m1);
    assert_eq!(areas.len(), 2);
    // As Triangle: FILE.1 is refined into FILE.2, attributes carried without -A.
    ok(&idmesh(&d.0, &["triangle", "-rq30a0.001enQ", "box.1"]));
    let m2 = read_trimesh(&d, "box.2", n1, false);
    assert!(m2.triangles.len() > 5 * m1.triangles.len());
    assert_eq!(
        m2.vertices[..n1],
        m1.vertices[..],
        "input points keep their indices"
    );
    assert_eq!(m2.vertex_markers[..n1], m1.vertex_markers[..]);
    for ((k1, a1), (k2, a2)) in areas.iter().zip(area_per_attribute(&m2)) {
        assert_eq!(*k1, k2);
        assert!((a1 - a2).abs() < 1e-12, "region {k1}: area {a2}, was {a1}");
    }
    for &t in &m2.triangles {
        assert!(tri_area(&m2.vertices, t) <= 0.001);
    }
    // With -p the segments of box.1.poly are kept too and box.2.poly is written.
    ok(&idmesh(&d.0, &["triangle", "-rpq30a0.001enQ", "box.1"]));
    let m2 = read_trimesh(&d, "box.2", n1, true);
    m2.validate().unwrap();
    assert_eq!(m2.vertices[..n1], m1.vertices[..]);
    assert_eq!(area_per_attribute(&m2).len(), 2);
}

#[test]
fn ra_applies_the_area_file_per_triangle() {
    let d = TempDir::new("refine-area");
    d.write("box.poly", TWO_REGIONS);
    ok(&idmesh(&d.0, &["triangle", "-pq30a0.01AnQ", "box.poly"]));
    let m1 = read_trimesh(&d, "box.1", 8, false);
    // A small bound on the triangles of region 2 only (-1: none).
    let mut area = format!("{}\n", m1.triangles.len());
    for (t, &k) in m1.triangle_attributes.iter().enumerate() {
        let bound = if k == 2.0 { 0.0005 } else { -1.0 };
        area.push_str(&format!("{} {bound}\n", t + 1));
    }
    d.write("box.1.area", &area);
    ok(&idmesh(&d.0, &["triangle", "-raenQ", "box.1"]));
    let m2 = read_trimesh(&d, "box.2", m1.vertices.len(), false);
    let (mut small, mut other) = (0, 0.0f64);
    for (t, &tri) in m2.triangles.iter().enumerate() {
        let a = tri_area(&m2.vertices, tri);
        if m2.triangle_attributes[t] == 2.0 {
            assert!(a <= 0.0005, "triangle {t}: {a}");
            small += 1;
        } else {
            other = other.max(a);
        }
    }
    assert!(small >= 1000, "{small} triangles in region 2");
    assert!(other > 0.002, "region 1 stays coarse: largest {other}");
    // Bad input: errors naming the file and the item, no output, never a panic.
    d.write("box.1.area", "3\n1 0.5\n2 x\n3 1\n");
    let msg = fails(&idmesh(&d.0, &["triangle", "-raQ", "box.1"]));
    assert!(msg.contains("box.1.area"), "{msg}");
    std::fs::remove_file(d.path("box.1.area")).unwrap();
    let msg = fails(&idmesh(&d.0, &["triangle", "-raQ", "box.1"]));
    assert!(
        msg.contains("box.1.area") && msg.contains("cannot read"),
        "{msg}"
    );
    d.write("lone.node", &d.read("box.1.node"));
    let msg = fails(&idmesh(&d.0, &["triangle", "-rQ", "lone"]));
    assert!(
        msg.contains("lone.ele") && msg.contains("cannot read"),
        "{msg}"
    );
    let ele = d.read("box.1.ele").replacen("\n1 ", "\n1 999 ", 1);
    d.write("bad.node", &d.read("box.1.node"));
    d.write("bad.ele", &ele);
    let msg = fails(&idmesh(&d.0, &["triangle", "-rQ", "bad"]));
    assert!(msg.contains("bad.ele") && msg.contains("999"), "{msg}");
    assert!(!d.exists("bad.1.node") && !d.exists("lone.1.node"));
}

#[test]
fn double_y_keeps_every_segment_whole() {
    let d = TempDir::new("yy");
    d.write("box.poly", TWO_REGIONS);
    ok(&idmesh(&d.0, &["triangle", "-pq30a0.01AQ", "box.poly"]));
    // The points of that mesh (many of them on the segments) with the same segments.
    let node = d.read("box.1.node");
    let n = header(&node)[0].parse::<usize>().unwrap();
    let poly = TWO_REGIONS.replacen("8 2 0 1", "0 2 0 1", 1);
    let poly: String = poly
        .lines()
        .enumerate()
        .filter(|(i, _)| *i == 0 || *i > 8)
        .map(|(_, l)| format!("{l}\n"))
        .collect();
    d.write("pts.node", &node);
    d.write("pts.poly", &poly);
    for sw in ["-pq30a0.002YYenQ", "-pq30a0.002YenQ"] {
        ok(&idmesh(&d.0, &["triangle", sw, "pts.poly"]));
        let m = read_trimesh(&d, "pts.1", n, true);
        m.validate_constrained().unwrap();
        assert!(
            m.steiner_points > 50,
            "{sw}: {} Steiner points",
            m.steiner_points
        );
        let split = m.segments.iter().flatten().any(|&v| v as usize >= n);
        // -Y may split the interior segment x = 0.5, -YY splits none.
        assert_eq!(split, !sw.contains("YY"), "{sw}");
    }
}

#[test]
fn point_attributes_are_written_interpolated_linearly() {
    // A square with a notch, two attributes per point, linear in x and y: every vertex of
    // the output, Steiner points included, must carry the same linear functions.
    let f = |x: f64, y: f64| [3.0 * x - 2.0 * y + 0.5, -x + 4.0 * y];
    let pts = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 1.0], [0.0, 2.0]];
    let mut poly = format!("{} 2 2 0\n", pts.len());
    for (i, p) in pts.iter().enumerate() {
        let a = f(p[0], p[1]);
        poly += &format!("{} {} {} {} {}\n", i + 1, p[0], p[1], a[0], a[1]);
    }
    poly += "5 1\n1 1 2 3\n2 2 3 3\n3 3 4 3\n4 4 5 3\n5 5 1 3\n0\n";
    let d = TempDir::new("pattr");
    d.write("n.poly", &poly);
    ok(&idmesh(&d.0, &["triangle", "-pq30a0.01Q", "n.poly"]));
    let text = d.read("n.1.node");
    assert_eq!(
        header(&text)[1..3],
        ["2", "2"],
        "dimension and attribute count"
    );
    let node = parse_node(&text, "n.1.node").unwrap();
    assert_eq!(node.num_point_attributes, 2);
    let n = node.pslg.points.len();
    assert!(n > 50, "refined: {n} vertices");
    for (v, p) in node.pslg.points.iter().enumerate() {
        let want = f(p[0], p[1]);
        for (a, w) in want.iter().enumerate() {
            let got = node.point_attributes[2 * v + a];
            assert!(
                (got - w).abs() <= 1e-12 * (1.0 + w.abs()),
                "vertex {v} at {p:?}: attribute {a} is {got}, want {w}"
            );
        }
    }
    // Without attributes the header says 0.
    d.write("s.poly", SQUARE);
    ok(&idmesh(&d.0, &["triangle", "-pa0.1Q", "s.poly"]));
    assert_eq!(header(&d.read("s.1.node"))[2], "0");
}
