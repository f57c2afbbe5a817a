//! Ctrl-C on the command line: SIGINT during a long run ends it through the mesher's cancel
//! path with exit status 130, promptly, and leaves no output file; a run whose standard error
//! is not a terminal prints no progress bar.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn workdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("idmesh-interrupt-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The unit cube as a TetGen .poly file.
const CUBE_POLY: &str = "\
8 3 0 0
1 0 0 0
2 1 0 0
3 0 1 0
4 1 1 0
5 0 0 1
6 1 0 1
7 0 1 1
8 1 1 1
6 0
1
4 1 2 4 3
1
4 5 6 8 7
1
4 1 2 6 5
1
4 3 4 8 7
1
4 1 3 7 5
1
4 2 4 8 6
0
0
";

/// The unit square as a Triangle .poly file.
const SQUARE_POLY: &str = "\
4 2 0 0
1 0 0
2 1 0
3 1 1
4 0 1
4 0
1 1 2
2 2 3
3 3 4
4 4 1
0
";

/// Starts `idmesh ARGS` in `dir`, sends SIGINT after `after`, and checks it exits with 130
/// within a second, says so, and leaves only `keep` in `dir`.
fn interrupt(dir: &Path, args: &[&str], after: Duration, keep: &str) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_idmesh"))
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(after);
    assert!(
        child.try_wait().unwrap().is_none(),
        "the run ended before the interrupt: make it longer"
    );
    let sent = Instant::now();
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if sent.elapsed() > Duration::from_secs(5) {
            let _ = child.kill();
            panic!("still running 5 s after SIGINT");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let took = sent.elapsed();
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(status.code(), Some(130), "stderr: {stderr}");
    assert!(took < Duration::from_secs(1), "took {took:?} to stop");
    assert!(stderr.contains("interrupted"), "stderr: {stderr}");
    let left: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left, [keep], "files left behind");
}

#[test]
fn ctrl_c_stops_a_long_3d_run_with_status_130_and_no_output() {
    let d = workdir("3d");
    std::fs::write(d.join("cube.poly"), CUBE_POLY).unwrap();
    interrupt(
        &d,
        &["tetgen", "-pq1.5a1e-8", "cube.poly"],
        Duration::from_millis(500),
        "cube.poly",
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn ctrl_c_stops_a_long_2d_run_with_status_130_and_no_output() {
    let d = workdir("2d");
    std::fs::write(d.join("square.poly"), SQUARE_POLY).unwrap();
    interrupt(
        &d,
        &["triangle", "-pq30a0.00000001", "square.poly"],
        Duration::from_millis(500),
        "square.poly",
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn no_progress_bar_when_stderr_is_not_a_terminal() {
    let d = workdir("quiet");
    std::fs::write(d.join("cube.poly"), CUBE_POLY).unwrap();
    // Long enough (over a second) that a terminal would show the bar.
    let out = Command::new(env!("CARGO_BIN_EXE_idmesh"))
        .current_dir(&d)
        .args(["tetgen", "-pq1.5a2e-6", "cube.poly"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.stderr.is_empty(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(d.join("cube.1.ele").exists());
    let _ = std::fs::remove_dir_all(&d);
}
