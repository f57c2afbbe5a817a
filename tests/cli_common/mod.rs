//! Running the `idmesh` binary on copies of the shipped examples, for the command-line tests.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `idmesh ARGS` in `dir`.
pub fn idmesh(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_idmesh"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

/// A scratch directory of one test, removed when the test passes; kept (and named on standard
/// error) when it fails, for a look at what the run wrote.
pub struct WorkDir(PathBuf);

impl std::ops::Deref for WorkDir {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for WorkDir {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("kept the test's files in {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// A fresh directory holding copies of `examples/data/{files}`.
pub fn workdir(name: &str, files: &[&str]) -> WorkDir {
    let d = std::env::temp_dir().join(format!("idmesh-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    for f in files {
        let src = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/data")
            .join(f);
        std::fs::copy(src, d.join(f)).unwrap();
    }
    WorkDir(d)
}

/// Asserts success and returns standard output.
pub fn ok(o: &Output) -> String {
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}
