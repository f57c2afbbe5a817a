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

/// A fresh directory holding copies of `examples/data/{files}`.
pub fn workdir(name: &str, files: &[&str]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("idmesh-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    for f in files {
        let src = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/data")
            .join(f);
        std::fs::copy(src, d.join(f)).unwrap();
    }
    d
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
