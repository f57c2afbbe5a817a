//! Runs the C programs against the crate's static library: `tests/c/test_mesher2d.c` (the C
//! API end to end, using only `include/idmesh.h`) and `examples/mesh_square.c`.
//!
//! The library is built by a nested `cargo build --lib` into its own target directory
//! (`<target>/c_api`), so the test works from a fresh clone with plain `cargo test`, always
//! links the current sources, and never races the outer build for its artifacts. The C
//! compiler is `$CC`, or `cc`.

#![cfg(target_os = "linux")]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// System libraries the Rust standard library needs in a static link on Linux.
const SYSTEM_LIBS: &[&str] = &["-pthread", "-ldl", "-lm"];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The target directory of this test binary (`<target>/<profile>/deps/c_api-<hash>`), so a
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
        // Same optimisation level as this test run: `cargo test --release` builds release.
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

/// Compiles `source` with the strict flags the header promises to survive, links it against
/// the static library, runs it, and returns its standard output. Panics with the compiler's or
/// the program's output on failure.
fn compile_and_run(source: &str, exe_name: &str) -> String {
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
    let run = Command::new(&exe)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", exe.display()));
    let stdout = String::from_utf8_lossy(&run.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        run.status.success(),
        "{source} failed ({}):\n{stdout}\n{stderr}",
        run.status
    );
    stdout
}

#[test]
fn c_api_end_to_end() {
    let out = compile_and_run("tests/c/test_mesher2d.c", "test_mesher2d");
    // The program counts its checks; a run that checked nothing would be a broken test.
    let last = out.lines().last().unwrap_or_default();
    let checks: usize = last
        .split_whitespace()
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no check count in the output:\n{out}"));
    assert!(checks > 100, "only {checks} checks ran:\n{out}");
    assert!(last.ends_with(" 0 failed"), "{out}");
}

/// C++ must be able to include the header (cbindgen's `cpp_compat`: `extern "C"` linkage).
/// Skipped, with a note, when no C++ compiler is installed: C++ is not a build requirement.
#[test]
fn header_works_from_cpp() {
    let (lib, scratch) = static_lib();
    let src = scratch.join("from_cpp.cpp");
    std::fs::write(
        &src,
        "#include \"idmesh.h\"\n#include <cstring>\n\
         int main() {\n\
           idm_mesher2d *m = nullptr;\n\
           if (idm_mesher2d_new(&m) != IDM_OK) return 1;\n\
           if (idm_mesher2d_refine(m) != IDM_ERR_INVALID_INPUT) return 2;\n\
           if (std::strlen(idm_last_error()) == 0) return 3;\n\
           idm_mesher2d_free(m);\n\
           return 0;\n\
         }\n",
    )
    .unwrap();
    let exe = scratch.join("from_cpp");
    let cxx = std::env::var_os("CXX").unwrap_or_else(|| "c++".into());
    let out = match Command::new(&cxx)
        .args(["-std=c++11", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(root().join("include"))
        .arg(&src)
        .arg(lib)
        .args(SYSTEM_LIBS)
        .arg("-o")
        .arg(&exe)
        .output()
    {
        Ok(out) => out,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            eprintln!("note: no C++ compiler ({cxx:?}); C++ inclusion not checked");
            return;
        }
        Err(e) => panic!("cannot run {cxx:?}: {e}"),
    };
    assert!(
        out.status.success(),
        "compiling the header as C++ failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let status = Command::new(&exe).status().expect("run the C++ program");
    assert!(status.success(), "the C++ program failed: {status}");
}

/// The Rust example, compiled in to compare its output with the C example's.
#[allow(dead_code)]
#[path = "../examples/mesh_square.rs"]
mod rust_example;

#[test]
fn c_example_matches_the_rust_example() {
    let out = compile_and_run("examples/mesh_square.c", "mesh_square_c");
    let rust = rust_example::summary().expect("the Rust example failed");
    assert!(rust.contains(" triangles"), "{rust}");
    assert_eq!(out.trim_end(), rust);
}
