//! Runs the 3D C programs against the crate's static library: `tests/c/test_mesher3d.c` (the
//! 3D C API end to end, using only `include/idmesh.h`) and `examples/c/mesh_box3d.c`, whose
//! output is compared with the same meshing through the Rust API.
//!
//! Built like `tests/c_api.rs`: a nested `cargo build --lib` into `<target>/c_api` (shared with
//! that test, so the library is built once; cargo's lock serialises concurrent builds), then
//! `$CC` (or `cc`) with the strict flags the header promises to survive.
//!
//! While the 3D mesher is being written, the C test accepts `IDM_ERR_UNSUPPORTED` from refine
//! and delaunay. This driver probes the Rust API first and tells the C program (environment
//! variables `IDMESH_REQUIRE_*3D=1`) which calls work, so that acceptance ends by itself the
//! moment the Rust side lands.

#![cfg(target_os = "linux")]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use idmesh::{delaunay3d, tetrahedralize, Error, Facet, Options3, Plc};

/// System libraries the Rust standard library needs in a static link on Linux.
const SYSTEM_LIBS: &[&str] = &["-pthread", "-ldl", "-lm"];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The target directory of this test binary (`<target>/<profile>/deps/c_api3d-<hash>`), so a
/// custom `CARGO_TARGET_DIR` or `--target-dir` is honoured.
fn outer_target_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("current_exe");
    exe.ancestors()
        .nth(3)
        .map(Path::to_path_buf)
        .unwrap_or_else(|| root().join("target"))
}

/// Builds `libidmesh.a` once per test binary and returns (its path, the scratch directory).
fn static_lib() -> &'static (PathBuf, PathBuf) {
    static LIB: OnceLock<(PathBuf, PathBuf)> = OnceLock::new();
    LIB.get_or_init(|| {
        let target = outer_target_dir().join("c_api");
        let release = std::env::current_exe()
            .map(|p| p.components().any(|c| c.as_os_str() == "release"))
            .unwrap_or(false);
        let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
        let mut cmd = Command::new(cargo);
        cmd.current_dir(root())
            .args(["build", "--lib", "--target-dir"])
            .arg(&target);
        if release {
            cmd.arg("--release");
        } else {
            cmd.args(["--profile", "test"]);
        }
        let status = cmd.status().expect("cannot run cargo");
        assert!(status.success(), "cargo build --lib failed: {status}");
        let lib = target
            .join(if release { "release" } else { "debug" })
            .join("libidmesh.a");
        assert!(lib.is_file(), "{} was not built", lib.display());
        (lib, target)
    })
}

/// Fails with the fix when the checked-in header predates the 3D API (it is generated from
/// `src/ffi/` by `tests/header.rs`).
fn assert_header_has_3d() {
    let header = std::fs::read_to_string(root().join("include/idmesh.h")).unwrap_or_default();
    assert!(
        header.contains("idm_mesher3d_new("),
        "include/idmesh.h lacks the 3D API: tests/header.rs must also parse src/ffi/mesh3d.rs; then \
         run IDMESH_UPDATE_HEADER=1 cargo test --test header"
    );
}

/// Compiles `source` with the strict flags, links it against the static library and runs it
/// with `env`, returning its output (whatever its exit status).
fn compile_and_run(source: &str, exe_name: &str, env: &[(&str, &str)]) -> Output {
    assert_header_has_3d();
    let (lib, scratch) = static_lib();
    let exe = scratch.join(exe_name);
    let cc = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    let out = Command::new(&cc)
        .current_dir(root())
        .args([
            "-std=c99",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
            "-O1",
        ])
        .arg("-I")
        .arg(root().join("include"))
        .arg(root().join(source))
        .arg(lib)
        .args(SYSTEM_LIBS)
        .arg("-o")
        .arg(&exe)
        .output()
        .unwrap_or_else(|e| panic!("cannot run the C compiler {cc:?}: {e}"));
    assert!(
        out.status.success(),
        "compiling {source} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut run = Command::new(&exe);
    for (k, v) in env {
        run.env(k, v);
    }
    run.output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", exe.display()))
}

/// A unit cube PLC, with one facet index optionally replaced by an out-of-range one.
fn cube(bad_index: bool) -> Plc {
    let points = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let mut loops = vec![
        vec![0, 3, 2, 1],
        vec![4, 5, 6, 7],
        vec![0, 1, 5, 4],
        vec![1, 2, 6, 5],
        vec![2, 3, 7, 6],
        vec![3, 0, 4, 7],
    ];
    if bad_index {
        loops[3][2] = 17;
    }
    Plc {
        points,
        facets: loops
            .into_iter()
            .zip(1..)
            .map(|(l, marker)| Facet {
                polygons: vec![l],
                holes: Vec::new(),
                marker,
            })
            .collect(),
        ..Plc::default()
    }
}

/// Which parts of the 3D Rust API work yet, as the C test's environment: a call counts as
/// working when it no longer answers `Unsupported` (the input check: when it reports a bad
/// facet index as an input error).
fn capabilities() -> Vec<(&'static str, &'static str)> {
    let flag = |b: bool| if b { "1" } else { "0" };
    let refine = !matches!(
        tetrahedralize(&cube(false), &Options3::default()),
        Err(Error::Unsupported(_))
    );
    let mut points = cube(false).points;
    points.push([0.5, 0.5, 0.5]);
    let delaunay = !matches!(delaunay3d(&points), Err(Error::Unsupported(_)));
    let check = matches!(
        tetrahedralize(&cube(true), &Options3::default()),
        Err(Error::Input(_))
    );
    vec![
        ("IDMESH_REQUIRE_REFINE3D", flag(refine)),
        ("IDMESH_REQUIRE_DELAUNAY3D", flag(delaunay)),
        ("IDMESH_REQUIRE_CHECK3D", flag(check)),
    ]
}

#[test]
fn c_api3d_end_to_end() {
    let env = capabilities();
    let out = compile_and_run("tests/c/test_mesher3d.c", "test_mesher3d", &env);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "tests/c/test_mesher3d.c failed ({}) with {env:?}:\n{stdout}\n{stderr}",
        out.status
    );
    // The program counts its checks: "N checks, S skipped, F failed". A run that checked
    // little would be a broken test.
    let last = stdout.lines().last().unwrap_or_default();
    let numbers: Vec<usize> = last
        .split(|c: char| !c.is_ascii_digit())
        .filter_map(|w| w.parse().ok())
        .collect();
    let [checks, skipped, failed] = numbers[..] else {
        panic!("no check counts in the output:\n{stdout}");
    };
    assert_eq!(failed, 0, "{stdout}");
    assert!(checks > 60, "only {checks} checks ran:\n{stdout}");
    if env.iter().all(|(_, v)| *v == "1") {
        assert_eq!(
            skipped, 0,
            "checks skipped with the whole mesher working:\n{stdout}"
        );
        assert!(checks > 1000, "only {checks} checks ran:\n{stdout}");
    }
}

/// The example's input, built through the Rust API.
fn box_with_cavity() -> Plc {
    let cube = cube(false);
    let mut points = cube.points.clone();
    // The cavity's corners as the C literals 0.4 and 0.6 (0.4 + 0.2 would round to
    // 0.6000000000000001 and mesh a different box).
    points.extend(
        cube.points
            .iter()
            .map(|p| p.map(|x| if x == 0.0 { 0.4 } else { 0.6 })),
    );
    let mut facets = Vec::new();
    for (offset, marker) in [(0, 1), (8, 2)] {
        for f in &cube.facets {
            facets.push(Facet {
                polygons: vec![f.polygons[0].iter().map(|&v| v + offset).collect()],
                holes: Vec::new(),
                marker,
            });
        }
    }
    Plc {
        points,
        facets,
        holes: vec![[0.5, 0.5, 0.5]],
        ..Plc::default()
    }
}

#[test]
fn c_example_matches_the_rust_api() {
    let out = compile_and_run("examples/c/mesh_box3d.c", "mesh_box3d", &[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let opts = Options3 {
        radius_edge: Some(2.0),
        max_volume: Some(0.001),
        ..Options3::default()
    };
    match tetrahedralize(&box_with_cavity(), &opts) {
        Ok(mesh) => {
            assert!(out.status.success(), "the example failed:\n{stderr}");
            mesh.validate().expect("the Rust mesh is valid");
            let s = mesh.stats();
            let want = format!(
                "idmesh {}: {} vertices, {} tetrahedra, {} faces, {} edges, volume {:.6}, \
                 radius-edge {:.4}, dihedral {:.4}..{:.4} degrees",
                env!("CARGO_PKG_VERSION"),
                mesh.vertices.len(),
                mesh.tets.len(),
                mesh.faces.len(),
                mesh.edges.len(),
                s.volume,
                s.max_radius_edge,
                s.min_dihedral,
                s.max_dihedral
            );
            assert_eq!(stdout.trim_end(), want);
            assert!((s.volume - 0.992).abs() < 1e-12, "volume {}", s.volume);
            assert!(s.max_radius_edge <= 2.0, "{}", s.max_radius_edge);
        }
        // Not implemented yet: the example must say so and fail, not print a mesh.
        Err(Error::Unsupported(msg)) => {
            assert!(!out.status.success(), "the example succeeded:\n{stdout}");
            assert!(stderr.contains(&msg), "{stderr}");
        }
        Err(e) => panic!("the Rust API fails on the example's input: {e}"),
    }
}
