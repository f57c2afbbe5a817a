//! The structure-aware fuzz campaign of issue 14, as a counted, reproducible run: `runs`
//! cases drawn from a seeded generator, each a seed shape mutated as in
//! `fuzz/fuzz_targets/mutate.rs` (the same code as the cargo-fuzz targets), meshed with a
//! Steiner budget, its result classified: a mesh that validates (complete or with the budget
//! reached), an input error, an internal error (grouped by message), a mesh returned as a
//! success that fails `validate()`, or a hang (no answer within the time limit; the campaign
//! then stops, as the stuck thread cannot be killed). Each failing case is printed so that it
//! can become a regression test.
//!
//! ```text
//! cargo run --release --example fuzz_campaign -- 3d 1 10000 [time-limit-s]
//! ```
//!
//! `RUNS` may also be a range `FIRST..END` (such as `1660..1661`): the cases before `FIRST`
//! are drawn but not run, so one case of a campaign can be rerun alone.
//!
//! With `IDMESH_CAMPAIGN_DUMP=DIR`, every mesh returned as a success (but an empty 2D one:
//! segments enclosing no area give no triangles, as in Triangle) is also written to `DIR` in
//! Triangle's or TetGen's formats (`r<run>.poly` input, `.node`, `.ele`, and `.face` in 3D,
//! plus `.args`: the checker's options), so that an independent checker can read it:
//! `fuzz/verify_campaign.sh DIR` runs `verify2d.py`/`verify3d.py` over them.
//!
//! With `IDMESH_CAMPAIGN_INPUTS=DIR`, the input of every case run is written to `DIR` before it
//! is meshed (`r<run>.poly`), whatever its outcome, so that a failing case (an internal error
//! or a hang, which write no mesh) can be rerun with the command line.

#[path = "../fuzz/fuzz_targets/mutate.rs"]
mod mutate;

use arbitrary::{Arbitrary, Unstructured};
use mutate::{Case2, Case3};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::sync::mpsc;
use std::time::Duration;

/// SplitMix64: a small, well-mixed generator, so a campaign is reproducible from its seed.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
}

/// What one case came to.
fn outcome<M>(
    r: Result<M, idmesh::Error>,
    check: impl Fn(&M) -> Result<(), String>,
    complete: impl Fn(&M) -> bool,
) -> String {
    match r {
        Ok(m) => match check(&m) {
            Ok(()) if complete(&m) => "ok".into(),
            Ok(()) => "ok, Steiner budget reached".into(),
            Err(e) => format!("WRONG MESH returned as a success: {e}"),
        },
        Err(idmesh::Error::Internal(m)) => {
            // Group by the message's words, not its numbers or lists of ids.
            let mut words = String::new();
            let mut depth = 0u32;
            for c in m.chars() {
                match c {
                    '[' | '(' | '{' => depth += 1,
                    ']' | ')' | '}' => depth = depth.saturating_sub(1),
                    _ if depth > 0 => {}
                    c if c.is_ascii_digit()
                        || (matches!(c, '.' | 'e' | '-') && words.ends_with('N')) =>
                    {
                        if !words.ends_with('N') {
                            words.push('N');
                        }
                    }
                    c => words.push(c),
                }
            }
            let words: String = words.chars().take(110).collect();
            format!("INTERNAL: {}", words.trim())
        }
        Err(idmesh::Error::Input(_)) => "input error".into(),
        Err(e) => format!(
            "other error: {}",
            e.to_string().chars().take(60).collect::<String>()
        ),
    }
}

/// Writes a case's input as `r<run>.poly` into the directory of `IDMESH_CAMPAIGN_INPUTS`.
fn write_input(
    dir: &Option<PathBuf>,
    run: u64,
    poly: &dyn Fn(&mut dyn Write) -> std::io::Result<()>,
) {
    if let Some(d) = dir {
        write_files(&d.join(format!("r{run}")), &[("poly", poly)]);
    }
}

/// One writer of a dumped case: the file's extension and what goes into it.
type Writer<'a> = (&'a str, &'a dyn Fn(&mut dyn Write) -> std::io::Result<()>);

/// Writes `base.<ext>` for each writer. A case whose input cannot be written in the format
/// (a PLC with free segments) is left out whole, as the checker could not read it.
fn write_files(base: &std::path::Path, writers: &[Writer]) {
    let mut done = Vec::new();
    for (ext, f) in writers {
        let path = base.with_extension(ext);
        let ok = File::create(&path).is_ok_and(|file| {
            let mut w = BufWriter::new(file);
            f(&mut w).is_ok() && w.flush().is_ok()
        });
        done.push(path);
        if !ok {
            for p in &done {
                let _ = std::fs::remove_file(p);
            }
            return;
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        eprintln!("usage: fuzz_campaign 2d|3d SEED RUNS [TIME-LIMIT-S]");
        std::process::exit(2);
    }
    let mode = args[1].clone();
    let seed: u64 = args[2].parse().expect("SEED");
    let (first, runs): (u64, u64) = match args[3].split_once("..") {
        Some((a, b)) => (a.parse().expect("FIRST"), b.parse().expect("END")),
        None => (0, args[3].parse().expect("RUNS")),
    };
    let limit = Duration::from_secs(args.get(4).map_or(20, |s| s.parse().expect("TIME-LIMIT-S")));
    // IDMESH_CAMPAIGN_ALL=1 lists every run, to compare two builds run by run.
    let all = std::env::var_os("IDMESH_CAMPAIGN_ALL").is_some();
    let dump = std::env::var_os("IDMESH_CAMPAIGN_DUMP").map(PathBuf::from);
    if let Some(d) = &dump {
        std::fs::create_dir_all(d).expect("IDMESH_CAMPAIGN_DUMP: cannot create the directory");
    }
    let inputs = std::env::var_os("IDMESH_CAMPAIGN_INPUTS").map(PathBuf::from);
    if let Some(d) = &inputs {
        std::fs::create_dir_all(d).expect("IDMESH_CAMPAIGN_INPUTS: cannot create the directory");
    }
    let mut rng = Rng(seed);
    let mut counts: BTreeMap<String, u64> = BTreeMap::new();
    let mut bytes = vec![0u8; 256];
    for run in 0..runs {
        for b in bytes.iter_mut() {
            *b = rng.next() as u8;
        }
        if run < first {
            continue;
        }
        let mut u = Unstructured::new(&bytes);
        let (tx, rx) = mpsc::channel();
        let desc;
        if mode == "2d" {
            let Ok(mut case) = Case2::arbitrary(&mut u) else {
                continue;
            };
            case.muts.truncate(6);
            desc = format!("{case:?}");
            write_input(&inputs, run, &|w| {
                idmesh::io::triangle::write_pslg_poly(w, &case.input(), 1)
            });
            let dump = dump.clone();
            std::thread::spawn(move || {
                let check = |m: &idmesh::TriMesh| {
                    if case.no_boundary_steiner {
                        m.validate_constrained()
                    } else {
                        m.validate().map_err(|e| e.to_string())
                    }
                };
                let r = case.run();
                // An input whose segments enclose no area gives an empty mesh, as Triangle
                // does; the checker reads no mesh there.
                if let (Some(d), Some(m)) =
                    (&dump, r.as_ref().ok().filter(|m| !m.triangles.is_empty()))
                {
                    use idmesh::io::triangle as t;
                    let base = d.join(format!("r{run}"));
                    let args = if case.no_boundary_steiner {
                        ""
                    } else {
                        "--require-delaunay"
                    };
                    write_files(
                        &base,
                        &[
                            ("poly", &|w| t::write_pslg_poly(w, &case.input(), 1)),
                            ("node", &|w| t::write_node(w, m, 1)),
                            ("ele", &|w| t::write_ele(w, m, 1)),
                            ("args", &|w: &mut dyn Write| writeln!(w, "{args}")),
                        ],
                    );
                }
                let _ = tx.send(outcome(r, check, |m| m.complete));
            });
        } else {
            let Ok(mut case) = Case3::arbitrary(&mut u) else {
                continue;
            };
            case.muts.truncate(6);
            desc = format!("{case:?}");
            write_input(&inputs, run, &|w| {
                idmesh::io::tetgen::write_plc_poly(w, &case.input(), 1)
            });
            let dump = dump.clone();
            std::thread::spawn(move || {
                let check = |m: &idmesh::TetMesh| m.validate().map_err(|e| e.to_string());
                let r = case.run();
                if let (Some(d), Ok(m)) = (&dump, &r) {
                    use idmesh::io::tetgen as t;
                    let base = d.join(format!("r{run}"));
                    let args = if case.keep_surface {
                        ""
                    } else {
                        "--require-delaunay"
                    };
                    write_files(
                        &base,
                        &[
                            ("poly", &|w| t::write_plc_poly(w, &case.input(), 1)),
                            ("node", &|w| t::write_node(w, m, 1, true)),
                            ("ele", &|w| t::write_ele(w, m, 1)),
                            ("face", &|w| t::write_face(w, m, 1, true)),
                            ("args", &|w: &mut dyn Write| writeln!(w, "{args}")),
                        ],
                    );
                }
                let _ = tx.send(outcome(r, check, |m| m.complete));
            });
        }
        let got = match rx.recv_timeout(limit) {
            Ok(o) => o,
            Err(_) => format!("HANG (no answer in {} s)", limit.as_secs()),
        };
        if all || (!got.starts_with("ok") && got != "input error") {
            println!("run {run}: {got}\n  case: {desc}");
        }
        let hang = got.starts_with("HANG");
        *counts.entry(got).or_default() += 1;
        if hang {
            break;
        }
    }
    println!(
        "\n{mode} campaign, seed {seed}, {} cases:",
        counts.values().sum::<u64>()
    );
    for (k, v) in &counts {
        println!("{v:>8}  {k}");
    }
    std::process::exit(0);
}
