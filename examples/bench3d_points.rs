//! Times `idmesh::delaunay3d` on uniform random points in the unit cube; the 3D Delaunay half of
//! `bench/bench3d.py`. Prints one JSON line.
//!
//! ```sh
//! cargo run --release --example bench3d_points -- N SEED [--validate] [--hash-only]
//! ```
//!
//! Points: x, y, z of point i are SplitMix64 draws 3i+1, 3i+2, 3i+3 from `SEED`, each
//! `(u >> 11) · 2⁻⁵³` (exact in f64), the generator of `bench/bench3d.py`; `input_hash` lets the
//! script check that every tool read the same bits. Only the `delaunay3d` call is timed. Peak
//! memory is VmHWM from /proc/self/status, reset through /proc/self/clear_refs just before the
//! call where the kernel allows it. `--validate` runs the exact `TetMesh::validate` afterwards
//! (untimed).

use std::fmt::Write as _;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(line) => println!("{line}"),
        Err(msg) => {
            println!("{{\"tool\":\"idmesh\",\"error\":{}}}", json_str(&msg));
            eprintln!("bench3d_points: {msg}");
            std::process::exit(1);
        }
    }
}

fn run(args: &[String]) -> Result<String, String> {
    let flags: Vec<&str> = args
        .iter()
        .filter(|a| a.starts_with("--"))
        .map(|s| s.as_str())
        .collect();
    let pos: Vec<&String> = args.iter().filter(|a| !a.starts_with("--")).collect();
    if pos.len() != 2 {
        return Err("usage: bench3d_points N SEED [--validate] [--hash-only]".into());
    }
    let n: usize = pos[0]
        .parse()
        .map_err(|_| format!("bad point count {:?}", pos[0]))?;
    let seed: u64 = pos[1]
        .parse()
        .map_err(|_| format!("bad seed {:?}", pos[1]))?;
    for f in &flags {
        if !matches!(*f, "--validate" | "--hash-only") {
            return Err(format!("unknown flag {f}"));
        }
    }
    let points = random_points(n, seed);
    let hash = input_hash(&points);
    if flags.contains(&"--hash-only") {
        return Ok(format!(
            "{{\"tool\":\"idmesh\",\"input_hash\":\"{hash:016x}\",\"input_points\":{n}}}"
        ));
    }

    let before = proc_status();
    let hwm_reset = reset_hwm();
    let t0 = Instant::now();
    let mesh = idmesh::delaunay3d(&points).map_err(|e| e.to_string())?;
    let secs = t0.elapsed().as_secs_f64();
    let after = proc_status();

    let valid = flags.contains(&"--validate").then(|| {
        let t = Instant::now();
        let r = mesh.validate().map_err(|e| e.to_string());
        (r, t.elapsed().as_secs_f64())
    });
    let mut s = format!(
        "{{\"tool\":\"idmesh\",\"time_s\":{secs:.6},\"vertices\":{},\"tets\":{},\
         \"hull_faces\":{},\"input_hash\":\"{hash:016x}\",\"input_points\":{n},\
         \"rss_before_kb\":{},\"hwm_before_kb\":{},\"hwm_after_kb\":{},\"rss_after_kb\":{},\
         \"hwm_reset\":{hwm_reset}",
        mesh.vertices.len(),
        mesh.tets.len(),
        mesh.faces.len(),
        before.rss_kb,
        before.hwm_kb,
        after.hwm_kb,
        after.rss_kb,
    );
    match valid {
        Some((Ok(()), t)) => {
            let _ = write!(s, ",\"valid\":true,\"validate_s\":{t:.3}");
        }
        Some((Err(msg), _)) => {
            let _ = write!(s, ",\"valid\":false,\"invalid_reason\":{}", json_str(&msg));
        }
        None => {}
    }
    s.push('}');
    Ok(s)
}

/// SplitMix64 (Steele, Lea, Flood 2014): tiny, fast and trivially reproducible in numpy.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix64(self.0)
    }

    /// A uniform double in [0, 1) with all 53 mantissa bits random.
    fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// The SplitMix64 finaliser; also used by the input hash.
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

fn random_points(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = SplitMix64(seed);
    (0..n)
        .map(|_| {
            let x = rng.next_f64();
            let y = rng.next_f64();
            let z = rng.next_f64();
            [x, y, z]
        })
        .collect()
}

/// An order-sensitive hash of the coordinates' bit patterns: sum over words i of
/// mix64(word_i ^ (i · φ)), wrapping, with words x0, y0, z0, x1, … (as bench/bench3d.py and
/// bench/cgal_bench3d.cpp compute it).
fn input_hash(points: &[[f64; 3]]) -> u64 {
    points
        .iter()
        .flat_map(|p| p.map(f64::to_bits))
        .enumerate()
        .fold(0u64, |h, (i, w)| {
            h.wrapping_add(mix64(w ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)))
        })
}

/// Resets VmHWM so that the peak read after the call covers the call only.
fn reset_hwm() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// Resident and peak resident memory of this process, from /proc/self/status (0 if absent).
struct Status {
    rss_kb: u64,
    hwm_kb: u64,
}

fn proc_status() -> Status {
    let text = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let get = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|rest| rest.split_whitespace().next())
            .and_then(|v| v.parse().ok())
            .unwrap_or(0)
    };
    Status {
        rss_kb: get("VmRSS:"),
        hwm_kb: get("VmHWM:"),
    }
}

fn json_str(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
