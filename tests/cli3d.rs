//! Integration tests of `idmesh tetgen`: switch parsing, TetGen's output files and their
//! names and numbering, one-line errors with exit status 1, and meshes read back and checked.
//!
//! Each test works in its own temporary directory and reads the outputs back with the
//! library's TetGen readers (themselves tested in `io3d.rs`). Tests that need the PLC mesher
//! (`tetrahedralize`) are ignored until it is complete: run them with `--ignored`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use idmesh::io::tetgen::{parse_edge, parse_ele, parse_face, parse_neigh, parse_node, parse_off};
use idmesh::predicates::orient3d;

/// A directory removed when the test ends (pass or fail).
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let p = std::env::temp_dir().join(format!("idmesh-cli3d-{}-{name}", std::process::id()));
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

    /// Copies `examples/data/NAME` in.
    fn example(&self, name: &str) {
        let src = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/data")
            .join(name);
        std::fs::copy(src, self.path(name)).unwrap();
    }

    /// The file names in the directory, sorted.
    fn files(&self) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn idmesh(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_idmesh"))
        .arg("tetgen")
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
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "expected exit 1, stderr: {err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "expected one stderr line, got {err:?}");
    assert!(lines[0].starts_with("idmesh: "), "{err:?}");
    lines[0].to_string()
}

/// A mesh read back from `stem.node` / `stem.ele` (0-based tets).
struct Mesh {
    points: Vec<[f64; 3]>,
    markers: Vec<i32>,
    tets: Vec<[u32; 4]>,
    attributes: Vec<f64>,
}

fn read_mesh(d: &TempDir, stem: &str, base: u32) -> Mesh {
    let node = parse_node(&d.read(&format!("{stem}.node")), "node").unwrap();
    assert_eq!(node.base, base, "numbering of {stem}.node");
    let n = node.plc.points.len();
    let ele = parse_ele(&d.read(&format!("{stem}.ele")), "ele", base, n).unwrap();
    Mesh {
        points: node.plc.points,
        markers: node.plc.point_markers,
        tets: ele.tets,
        attributes: ele.attributes,
    }
}

impl Mesh {
    fn corners(&self, t: [u32; 4]) -> [[f64; 3]; 4] {
        t.map(|v| self.points[v as usize])
    }

    /// Every tetrahedron positively oriented (TetGen's convention; Shewchuk's orient3d is
    /// negative then).
    fn assert_oriented(&self) {
        for &t in &self.tets {
            let [a, b, c, d] = self.corners(t);
            assert!(
                orient3d(a, b, c, d) < 0.0,
                "tet {t:?} is not positively oriented"
            );
        }
    }

    fn volume(&self) -> f64 {
        self.tets.iter().map(|&t| tet_volume(self.corners(t))).sum()
    }
}

fn tet_volume([a, b, c, d]: [[f64; 3]; 4]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// Five points: a tetrahedron's corners and one inside it; 1-based with markers.
const FIVE: &str = "5 3 0 1\n1 0 0 0 7\n2 3 0 0 7\n3 0 3 0 7\n4 0 0 3 7\n5 0.5 0.5 0.5 9\n";

/// A tetrahedron as a 1-based PLC whose fourth facet is not planar (point 5 is off it).
const BENT: &str = "\
5 3 0 0
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
5 0.5 0.5 0.0000001
4 1
1 0 1
3 1 3 2
1 0 1
3 1 2 4
1 0 1
3 1 4 3
1 0 2
4 2 3 4 5
0
";

// ---------------------------------------------------------------------------------------------
// Command line handling (independent of the mesher).

#[test]
fn help_and_usage_mention_the_3d_switches() {
    let d = TempDir::new("help");
    let out = ok(&idmesh(&d.0, &["--help"]));
    assert!(
        out.contains("-q[RATIO]") && out.contains("-a[VOLUME]"),
        "{out}"
    );
    let out = ok(&Command::new(env!("CARGO_BIN_EXE_idmesh"))
        .arg("--help")
        .output()
        .unwrap());
    assert!(out.contains("idmesh tetgen"), "{out}");
}

#[test]
fn bad_switches_exit_1_with_a_message_naming_them_and_write_nothing() {
    let d = TempDir::new("switches");
    d.example("3d_cube.poly");
    for (args, needle) in [
        (vec!["-pqx", "3d_cube.poly"], "-x"),
        (vec!["-pw", "3d_cube.poly"], "weighted"),
        (vec!["-po3", "3d_cube.poly"], "-o3"),
        (vec!["-rq", "3d_cube"], "3d_cube.node"),
        (vec!["-pa0", "3d_cube.poly"], "greater than zero"),
        (vec!["-pq1.2/15/170", "3d_cube.poly"], "maximum dihedral"),
        (vec!["-p"], "no input file"),
        (vec!["a.poly", "b.poly"], "more than one"),
        (vec!["--frob", "3d_cube.poly"], "--frob"),
    ] {
        let line = fails(&idmesh(&d.0, &args));
        assert!(line.contains(needle), "{args:?}: {line}");
    }
    assert_eq!(d.files(), vec!["3d_cube.poly"], "no output on error");
}

/// The smallest and largest dihedral angles of the `-V` report.
fn dihedral_range(out: &Output) -> (f64, f64) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .find(|l| l.starts_with("Dihedral angles: smallest"))
        .unwrap_or_else(|| panic!("no dihedral line in {text}"));
    let nums: Vec<f64> = line
        .split(' ')
        .filter_map(|w| w.trim_end_matches(',').parse().ok())
        .collect();
    (nums[0], nums[1])
}

#[test]
fn q_slash_angle_sets_the_minimum_dihedral_target() {
    let d = TempDir::new("dihedral");
    d.example("3d_cube.poly");
    let (lo, hi) = dihedral_range(&idmesh(&d.0, &["-pq1.414/20a0.0005V", "3d_cube.poly"]));
    assert!(lo >= 20.0 && hi <= 160.0, "{lo} {hi}");
    let (lo, hi) = dihedral_range(&idmesh(&d.0, &["-pq1.414a0.0005V", "3d_cube.poly"]));
    assert!(lo >= 15.0 && hi <= 165.0, "default target: {lo} {hi}");
    let (lo, _) = dihedral_range(&idmesh(&d.0, &["-pq1.414/0a0.0005V", "3d_cube.poly"]));
    assert!(lo < 15.0, "/0 turns sliver removal off: {lo}");
}

#[test]
fn unreadable_and_malformed_inputs_name_file_and_line() {
    let d = TempDir::new("badfile");
    let line = fails(&idmesh(&d.0, &["-p", "missing.poly"]));
    assert!(line.contains("missing.poly"), "{line}");
    let line = fails(&idmesh(&d.0, &["missing"]));
    assert!(line.contains("missing.node"), "{line}");
    d.write("bad.node", "3 3 0 0\n1 0 0 0\n2 1 zero 0\n3 0 1 0\n");
    let line = fails(&idmesh(&d.0, &["bad"]));
    assert!(
        line.contains("bad.node:3:") && line.contains("zero"),
        "{line}"
    );
    d.write(
        "bad.off",
        "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 4\n",
    );
    let line = fails(&idmesh(&d.0, &["bad.off"]));
    assert!(
        line.contains("bad.off:7:") && line.contains("corner 4"),
        "{line}"
    );
    assert!(!d.exists("bad.1.node"));
}

#[test]
fn detect_checks_the_plc_renumbers_items_and_writes_nothing() {
    let d = TempDir::new("detect");
    d.example("3d_box_hole.poly");
    let out = ok(&idmesh(&d.0, &["-d", "3d_box_hole.poly"]));
    assert!(out.contains("No intersections"), "{out}");
    d.write("bent.poly", BENT);
    let line = fails(&idmesh(&d.0, &["-d", "bent"]));
    // 1-based file: facet 4 and point 5 in the file's numbering.
    assert!(
        line.contains("bent.poly: invalid input: facet 4 is not planar: point 5"),
        "{line}"
    );
    let out = ok(&idmesh(&d.0, &["-dQ", "3d_box_hole.poly"]));
    assert!(out.is_empty(), "-Q: {out}");
    assert_eq!(d.files(), vec!["3d_box_hole.poly", "bent.poly"]);
}

#[test]
fn invalid_plcs_are_reported_before_meshing_with_the_files_numbering() {
    let d = TempDir::new("invalid");
    d.write("bent.poly", BENT);
    let line = fails(&idmesh(&d.0, &["-pq", "bent.poly"]));
    assert!(line.contains("facet 4 is not planar: point 5"), "{line}");
    // A 0-based OFF file whose two triangles cross.
    d.write(
        "x.off",
        "OFF\n6 2 0\n0 0 0\n2 0 0\n0 2 0\n1 1 -1\n1 1 1\n0 0 1\n3 0 1 2\n3 3 4 5\n",
    );
    let line = fails(&idmesh(&d.0, &["x.off"]));
    assert!(
        line.contains("x.off: invalid input: facets 0 and 1 intersect"),
        "{line}"
    );
    assert!(!d.exists("x.1.node") && !d.exists("bent.1.node"));
}

// ---------------------------------------------------------------------------------------------
// Point sets (delaunay3d)

#[test]
fn point_set_gives_node_ele_face_numbered_like_the_input() {
    let d = TempDir::new("points");
    d.write("five.node", FIVE);
    let out = ok(&idmesh(&d.0, &["five"]));
    assert!(out.contains("Writing five.1.ele"), "{out}");
    let m = read_mesh(&d, "five.1", 1);
    assert_eq!(m.points.len(), 5);
    assert_eq!(m.markers, vec![7, 7, 7, 7, 9], "input markers are copied");
    assert_eq!(
        m.tets.len(),
        4,
        "the inner point splits the tetrahedron in four"
    );
    m.assert_oriented();
    assert!(close(m.volume(), 4.5));
    let face = parse_face(&d.read("five.1.face"), "face", 1, 5).unwrap();
    assert_eq!(face.items.len(), 4, "the hull");
    assert!(
        face.markers.is_empty(),
        "no face markers for a point set, as TetGen"
    );
    assert!(m.attributes.is_empty());
}

#[test]
fn switches_choose_files_numbering_and_names() {
    let d = TempDir::new("outputs");
    d.write("five.node", FIVE);
    ok(&idmesh(&d.0, &["-zNEnfQ", "five.node"]));
    assert_eq!(d.files(), vec!["five.1.face", "five.1.neigh", "five.node"]);
    let neigh = parse_neigh(&d.read("five.1.neigh"), "neigh", 0, 4).unwrap();
    // Each of the 4 tets has 3 inner neighbours and one hull face, mutually.
    for (t, row) in neigh.iter().enumerate() {
        let inner: Vec<u32> = row.iter().copied().filter(|&n| n != idmesh::NONE).collect();
        assert_eq!(inner.len(), 3, "{row:?}");
        for n in inner {
            assert!(neigh[n as usize].contains(&(t as u32)));
        }
    }
    let all = parse_face(&d.read("five.1.face"), "face", 0, 5).unwrap();
    assert_eq!(all.items.len(), 10, "-f: 4 hull faces and 6 inner faces");
    // Iteration numbers advance; -I drops them; -B drops markers.
    std::fs::copy(d.path("five.node"), d.path("five.1.node")).unwrap();
    ok(&idmesh(&d.0, &["-Q", "five.1"]));
    assert!(d.exists("five.2.ele"));
    ok(&idmesh(&d.0, &["-QIB", "five.1.node"]));
    assert!(d.exists("five.1.ele"));
    assert!(parse_node(&d.read("five.1.node"), "node")
        .unwrap()
        .plc
        .point_markers
        .is_empty());
}

#[test]
fn verbose_and_check_print_statistics() {
    let d = TempDir::new("verbose");
    d.write("five.node", FIVE);
    let out = ok(&idmesh(&d.0, &["-VC", "five"]));
    for needle in [
        "The mesh is consistent.",
        "Input: 5 points",
        "Mesh: 5 vertices (0 Steiner points), 4 tetrahedra",
        "Radius-edge ratio: largest",
        "Dihedral angles: smallest",
        "Volume: 4.5",
        "Time: reading",
    ] {
        assert!(out.contains(needle), "missing {needle:?} in {out}");
    }
    let out = ok(&idmesh(&d.0, &["-VQ", "five"]));
    assert!(out.is_empty(), "-Q silences -V: {out}");
}

// ---------------------------------------------------------------------------------------------
// PLCs (tetrahedralize)

/// Meshes `name` from examples/data with `switches`; returns the directory and the mesh.
fn mesh_example(name: &str, switches: &str, base: u32) -> (TempDir, Mesh) {
    let d = TempDir::new(&format!("{name}{switches}"));
    d.example(name);
    ok(&idmesh(&d.0, &[switches, name]));
    let stem = format!("{}.1", name.rsplit_once('.').unwrap().0);
    let m = read_mesh(&d, &stem, base);
    m.assert_oriented();
    (d, m)
}

#[test]
fn cube_quality_mesh_fills_the_cube_with_markers_and_bounds() {
    let (d, m) = mesh_example("3d_cube.poly", "-pq1.414ea0.01Q", 1);
    assert!(close(m.volume(), 1.0), "{}", m.volume());
    assert!(m.tets.len() >= 100);
    for &t in &m.tets {
        let v = tet_volume(m.corners(t));
        assert!(v <= 0.01 * (1.0 + 1e-9), "tet {t:?} has volume {v}");
    }
    assert_eq!(&m.markers[..8], &[1, 1, 1, 1, 2, 2, 2, 2]);
    // Every boundary face carries its side's marker, and each side's area is 1.
    let n = m.points.len();
    let face = parse_face(&d.read("3d_cube.1.face"), "face", 1, n).unwrap();
    let mut area = [0.0f64; 7];
    for (f, &mk) in face.items.iter().zip(&face.markers) {
        assert!((1..=6).contains(&mk), "marker {mk}");
        let [a, b, c] = f.map(|v| m.points[v as usize]);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let x = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        area[mk as usize] += 0.5 * (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    }
    for (k, a) in area.iter().enumerate().skip(1) {
        assert!(close(*a, 1.0), "side {k} has area {a}");
    }
    let edges = parse_edge(&d.read("3d_cube.1.edge"), "edge", 1, n).unwrap();
    assert!(edges.items.len() >= 12 && edges.markers.len() == edges.items.len());
}

#[test]
fn box_with_cavity_has_regional_attributes_and_volume_bounds() {
    let (_d, m) = mesh_example("3d_box_hole.poly", "-pq1.5aAQ", 0);
    assert!(close(m.volume(), 32.0 - 4.0), "{}", m.volume());
    assert_eq!(m.attributes.len(), m.tets.len());
    assert!(
        m.attributes.iter().all(|&a| a == 7.0),
        "one region, attribute 7"
    );
    for &t in &m.tets {
        assert!(tet_volume(m.corners(t)) <= 0.05 * (1.0 + 1e-9));
    }
}

#[test]
fn surface_formats_mesh_to_their_volumes_with_tetgen_numbering() {
    for (name, base, volume) in [
        ("3d_pyramid.off", 0, 2.0),
        ("3d_tetra.stl", 1, 1.0 / 6.0),
        ("3d_wedge.ply", 0, 0.5),
        ("3d_octahedron.mesh", 1, 4.0 / 3.0),
        ("3d_lprism.smesh", 0, 3.0),
    ] {
        let (_d, m) = mesh_example(name, "-pqQ", base);
        assert!(close(m.volume(), volume), "{name}: volume {}", m.volume());
    }
}

#[test]
fn all_faces_neighbours_and_consistency_check_agree() {
    let (d, m) = mesh_example("3d_lprism.smesh", "-pq1.414fnCQ", 0);
    let n = m.points.len();
    let faces = parse_face(&d.read("3d_lprism.1.face"), "face", 0, n).unwrap();
    let neigh = parse_neigh(&d.read("3d_lprism.1.neigh"), "neigh", 0, m.tets.len()).unwrap();
    let hull = neigh
        .iter()
        .flatten()
        .filter(|&&x| x == idmesh::NONE)
        .count();
    assert_eq!(faces.items.len(), (4 * m.tets.len() + hull) / 2);
    assert!(faces.markers.contains(&0) && faces.markers.contains(&3));
}

#[test]
fn keep_surface_adds_points_only_inside_and_keeps_every_facet_whole() {
    // The cube's surface is in the Delaunay tetrahedralization of its corners: -Y keeps it
    // (every boundary face has input corners only) and refinement adds interior points only.
    let (d, m) = mesh_example("3d_cube.poly", "-pq1.414a0.01YQ", 1);
    assert!(close(m.volume(), 1.0), "{}", m.volume());
    let n = m.points.len();
    assert!(
        n > 8,
        "the volume bound adds interior points ({n} vertices)"
    );
    for p in &m.points[8..] {
        assert!(
            p.iter().all(|&x| x > 0.0 && x < 1.0),
            "Steiner point {p:?} is not strictly inside the cube"
        );
    }
    let face = parse_face(&d.read("3d_cube.1.face"), "face", 1, n).unwrap();
    assert_eq!(face.items.len(), 12, "two triangles per side");
    for f in &face.items {
        assert!(
            f.iter().all(|&v| v < 8),
            "boundary face {f:?} has a Steiner point"
        );
    }
    // The cavity's square sides are cospherical with the outer box's corners: the Delaunay
    // tetrahedralization does not contain them all, and the conforming mesh puts Steiner
    // points on them; -Y takes every one off the surface again.
    let (d, m) = mesh_example("3d_box_hole.poly", "-pqYV", 0);
    assert!(close(m.volume(), 32.0 - 4.0), "{}", m.volume());
    let face = parse_face(&d.read("3d_box_hole.1.face"), "face", 0, m.points.len()).unwrap();
    for f in &face.items {
        assert!(
            f.iter().all(|&v| v < 20),
            "boundary face {f:?} has a Steiner point"
        );
    }
    // Each square side is two triangles; the top has its window and lid: 2 per square side
    // (5 outer, 6 inner), 8 around the window, 2 for the lid.
    assert_eq!(face.items.len(), 2 * 5 + 2 * 6 + 8 + 2, "{:?}", face.items);
}

/// The unit cube as an OFF surface of twelve triangles (two per face, split along a diagonal).
const CUBE_TRIANGLES: &str = "OFF
8 12 0
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
3 0 2 1
3 0 3 2
3 4 5 6
3 4 6 7
3 0 1 5
3 0 5 4
3 1 2 6
3 1 6 5
3 2 3 7
3 2 7 6
3 3 0 4
3 3 4 7
";

#[test]
fn coplanar_triangles_are_merged_unless_minus_m() {
    // As in TetGen, the two triangles of each face are one facet: no subsegment lies on a
    // face diagonal (a cube edge keeps two coordinates, a diagonal only one). With -M each
    // triangle is a facet and its diagonal is covered by subsegments.
    for (switches, diagonals) in [("-pq1.2eQ", false), ("-pq1.2eMQ", true)] {
        let d = TempDir::new(&format!("cubetri{switches}"));
        d.write("c.off", CUBE_TRIANGLES);
        ok(&idmesh(&d.0, &[switches, "c.off"]));
        let m = read_mesh(&d, "c.1", 0);
        assert!(close(m.volume(), 1.0), "{switches}: volume {}", m.volume());
        // The .edge file lists every edge (TetGen's -e); the subsegments are those with a
        // marker... which a .off input does not give: ask the library for them.
        let _ = parse_edge(&d.read("c.1.edge"), "edge", 0, m.points.len()).unwrap();
        let plc = idmesh::io::tetgen::parse_off(CUBE_TRIANGLES, "c.off")
            .unwrap()
            .plc;
        let opts = idmesh::Options3 {
            radius_edge: Some(1.2),
            merge_coplanar: !switches.contains('M'),
            ..idmesh::Options3::default()
        };
        let mesh = idmesh::tetrahedralize(&plc, &opts).unwrap();
        let on_diagonal = mesh.edges.iter().any(|e| {
            let [a, b] = e.map(|v| mesh.vertices[v as usize]);
            (0..3).filter(|&k| a[k] == b[k]).count() < 2
        });
        assert_eq!(on_diagonal, diagonals, "{switches}");
    }
}

/// A unit cube as exported surfaces have it: vertex 8 repeats vertex 1 (and the right side
/// uses it), vertex 9 is on no face, vertex 10 halves the bottom's edge 0-1 with a zero-area
/// triangle 0-10-1 beside it, and corner 6 is raised so that the top is not planar.
const CUBE_AS_EXPORTED: &str = "OFF
11 7 0
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1.25
0 1 1
1 0 0
5 5 5
0.5 0 0
5 0 3 2 1 10
4 4 5 6 7
4 0 1 5 4
4 8 2 6 5
4 2 3 7 6
4 3 0 4 7
3 0 10 1
";

#[test]
fn surface_input_is_repaired_with_warnings_unless_quiet() {
    let d = TempDir::new("exported");
    d.write("c.off", CUBE_AS_EXPORTED);
    let out = idmesh(&d.0, &["-pC", "c.off"]);
    ok(&out);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    for want in [
        "1 duplicate vertex merged (vertices with the coordinates of an earlier one, e.g. 8 = 1)",
        "1 zero-area face (all corners on one line) dropped, e.g. face 6",
        "1 non-planar face triangulated into 2 triangles, e.g. face 1",
        "1 unreferenced vertex (on no face) dropped, e.g. 9",
    ] {
        assert!(err.contains(want), "missing '{want}' in {err}");
    }
    assert_eq!(err.lines().count(), 4, "{err}");
    // Output vertices: the kept input vertices in input order (0-7, then 10), then Steiner
    // points.
    let m = read_mesh(&d, "c.1", 0);
    let input = parse_off(CUBE_AS_EXPORTED, "c.off").unwrap().plc.points;
    assert_eq!(&m.points[..8], &input[..8]);
    assert_eq!(m.points[8], input[10]);
    m.assert_oriented();
    // The top's diagonal decides the volume: 1 + 1/24 or 1 + 1/12.
    let v = m.volume();
    assert!(
        close(v, 1.0 + 1.0 / 24.0) || close(v, 1.0 + 1.0 / 12.0),
        "{v}"
    );
    // -Q: the same mesh (written over the first), no warnings.
    let first = d.read("c.1.node");
    let out = idmesh(&d.0, &["-pQ", "c.off"]);
    ok(&out);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(d.read("c.1.node"), first);
}

#[test]
fn an_untriangulable_face_is_named_with_its_line() {
    // Face 1 is a non-planar bow tie in every axis projection.
    let d = TempDir::new("bowtie");
    d.write(
        "b.off",
        "OFF\n5 2 0\n0 0 0\n1 1 1\n1 0 0.3\n0 1 0.7\n5 5 5\n3 0 1 4\n4 0 1 2 3\n",
    );
    let line = fails(&idmesh(&d.0, &["-pQ", "b.off"]));
    assert!(
        line.contains("b.off: invalid input: facet 1 is not planar and cannot be triangulated")
            && line.ends_with("(line 9)"),
        "{line}"
    );
}

#[test]
fn a_vtk_mesh_written_with_k_reads_back_as_its_surface_and_meshes() {
    // -k writes the tets and the boundary triangles with their markers; read back, the
    // triangles are the surface (with those markers) of a mesh of the same volume.
    let (d, m) = mesh_example("3d_cube.poly", "-pq1.414kQ", 1);
    assert!(d.exists("3d_cube.1.vtk"));
    let text = d.read("3d_cube.1.vtk");
    d.write("again.vtk", &text);
    ok(&idmesh(&d.0, &["-pqQ", "again.vtk"]));
    let again = read_mesh(&d, "again.1", 0);
    again.assert_oriented();
    assert!(close(again.volume(), m.volume()), "{}", again.volume());
    let face = parse_face(&d.read("again.1.face"), "face", 0, again.points.len()).unwrap();
    let mut seen: Vec<i32> = face.markers.clone();
    seen.sort_unstable();
    seen.dedup();
    assert_eq!(
        seen,
        [1, 2, 3, 4, 5, 6],
        "the cube's side markers come back"
    );
    // A bad file names the file and the line.
    d.write("bad.vtk", &text.replacen("POINTS", "POINTS x", 1));
    let line = fails(&idmesh(&d.0, &["-pQ", "bad.vtk"]));
    assert!(line.contains("bad.vtk:5"), "{line}");
}
