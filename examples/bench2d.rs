//! Benchmark driver for the 2D mesher: builds one input, times only the `idmesh::triangulate`
//! call and prints one JSON line. `bench/bench2d.py` runs it as its own process, so the
//! process's peak memory is the mesher's memory.
//!
//! ```text
//! bench2d random N SEED            uniform points in the unit square (SplitMix64, see below)
//! bench2d hole ANGLE AREA          unit square with a circular hole (r = 0.25, 64 segments),
//!                                  like Triangle's -pq<ANGLE>a<AREA>
//! bench2d file PATH.poly SWITCHES  a Triangle .poly file and a Triangle switch string
//! options: --validate   also run TriMesh::validate() after timing (slow, for smoke runs)
//!          --hash-only  print the input size and hash without meshing
//!          --write STEM write STEM.node and STEM.ele (0-based, round-trip floats) after timing,
//!                       for an independent check with a verifier
//! ```
//!
//! The random points are reproducible outside Rust: x = (next() >> 11) · 2⁻⁵³ then
//! y the same, with SplitMix64 seeded by SEED. `input_hash` in the output lets the benchmark
//! script prove that every tool meshed bit-identical coordinates.

use std::fmt::Write as _;
use std::time::Instant;

use idmesh::{triangulate, Options, Pslg, Region};

/// A named input plus the options that go with it.
struct Case {
    name: String,
    pslg: Pslg,
    opts: Options,
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let validate = args.iter().any(|a| a == "--validate");
    let hash_only = args.iter().any(|a| a == "--hash-only");
    let write_stem = args
        .iter()
        .position(|a| a == "--write")
        .map(|i| args.get(i + 1).cloned().unwrap_or_default());
    let pos: Vec<&str> = args
        .iter()
        .enumerate()
        .filter(|&(i, a)| !a.starts_with("--") && (i == 0 || args[i - 1] != "--write"))
        .map(|(_, a)| a.as_str())
        .collect();
    let result = build_case(&pos).and_then(|case| {
        if hash_only {
            Ok(hash_line(&case))
        } else {
            run(case, validate, write_stem.as_deref())
        }
    });
    match result {
        Ok(line) => println!("{line}"),
        Err(msg) => {
            println!("{{\"tool\":\"idmesh\",\"error\":{}}}", json_str(&msg));
            eprintln!("bench2d: {msg}");
            std::process::exit(1);
        }
    }
}

const USAGE: &str = "usage: bench2d random N SEED | hole ANGLE AREA | file PATH.poly SWITCHES \
                     [--validate] [--hash-only] [--write STEM]";

fn build_case(pos: &[&str]) -> Result<Case, String> {
    match pos {
        ["random", n, seed] => {
            let n: usize = parse_num(n, "N")?;
            let seed: u64 = parse_num(seed, "SEED")?;
            let pslg = Pslg {
                points: random_points(n, seed),
                ..Pslg::default()
            };
            Ok(Case {
                name: format!("random {n} {seed}"),
                pslg,
                opts: Options::default(),
            })
        }
        ["hole", angle, area] => {
            let angle: f64 = parse_num(angle, "ANGLE")?;
            let area: f64 = parse_num(area, "AREA")?;
            let opts = Options {
                min_angle: Some(angle),
                max_area: Some(area),
                ..Options::default()
            };
            Ok(Case {
                name: format!("hole {angle} {area}"),
                pslg: square_with_hole(64),
                opts,
            })
        }
        ["file", path, switches] => {
            let text =
                std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))?;
            let node = path.trim_end_matches(".poly").to_string() + ".node";
            let node_file = || {
                std::fs::read_to_string(&node)
                    .map_err(|e| format!("the .poly has no vertices and {node} is unreadable: {e}"))
            };
            let pslg = parse_poly(&text, node_file).map_err(|e| format!("{path}: {e}"))?;
            let opts = parse_switches(switches)?;
            Ok(Case {
                name: format!("file {path} {switches}"),
                pslg,
                opts,
            })
        }
        _ => Err(USAGE.to_string()),
    }
}

fn parse_num<T: std::str::FromStr>(s: &str, what: &str) -> Result<T, String> {
    s.parse()
        .map_err(|_| format!("{what} must be a number, got {s:?}\n{USAGE}"))
}

fn hash_line(case: &Case) -> String {
    format!(
        "{{\"tool\":\"idmesh\",\"case\":{},\"input_points\":{},\"input_hash\":\"{:016x}\"}}",
        json_str(&case.name),
        case.pslg.points.len(),
        input_hash(&case.pslg)
    )
}

fn run(case: Case, validate: bool, write_stem: Option<&str>) -> Result<String, String> {
    let hash = input_hash(&case.pslg);
    let before = proc_status();
    // Reset the kernel's peak-RSS mark so that VmHWM afterwards is the peak during meshing
    // alone, not during input generation or parsing.
    let hwm_reset = std::fs::write("/proc/self/clear_refs", "5").is_ok();
    let start = Instant::now();
    let cpu_start = cpu_time();
    let result = triangulate(&case.pslg, &case.opts);
    let time = start.elapsed().as_secs_f64();
    let cpu = cpu_time() - cpu_start;
    let after = proc_status();
    let mesh = result.map_err(|e| format!("triangulate failed on {}: {e}", case.name))?;
    let (min_angle, max_angle) = mesh.angle_range();
    if let Some(stem) = write_stem {
        write_mesh(&mesh, stem).map_err(|e| format!("cannot write {stem}.node/.ele: {e}"))?;
    }
    let valid = if validate {
        Some(mesh.validate())
    } else {
        None
    };

    let mut s = String::new();
    let _ = write!(
        s,
        "{{\"tool\":\"idmesh\",\"case\":{},\"time_s\":{time:.6},\"cpu_s\":{cpu:.6},\"vertices\":{},\
         \"triangles\":{},\"segments\":{},\"min_angle\":{},\"max_angle\":{},\
         \"complete\":{},\"steiner_points\":{},\"input_hash\":\"{hash:016x}\",\
         \"input_points\":{},\"rss_before_kb\":{},\"hwm_before_kb\":{},\"hwm_after_kb\":{},\
         \"rss_after_kb\":{},\"hwm_reset\":{hwm_reset}",
        json_str(&case.name),
        mesh.vertices.len(),
        mesh.triangles.len(),
        mesh.segments.len(),
        json_f64(min_angle),
        json_f64(max_angle),
        mesh.complete,
        mesh.steiner_points,
        case.pslg.points.len(),
        before.rss_kb,
        before.hwm_kb,
        after.hwm_kb,
        after.rss_kb,
    );
    match valid {
        Some(Ok(())) => s.push_str(",\"valid\":true"),
        Some(Err(msg)) => {
            let _ = write!(s, ",\"valid\":false,\"invalid_reason\":{}", json_str(&msg));
        }
        None => {}
    }
    s.push('}');
    Ok(s)
}

/// This thread's CPU time in seconds (less sensitive to other jobs than the wall clock).
fn cpu_time() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// Writes Triangle's .node/.ele (0-based). Rust's `{}` for f64 prints the shortest string that
/// reads back to the same bits, so the verifier sees exactly the mesher's coordinates.
fn write_mesh(mesh: &idmesh::TriMesh, stem: &str) -> std::io::Result<()> {
    use std::io::Write;
    if stem.is_empty() {
        return Err(std::io::Error::other("--write needs a STEM argument"));
    }
    let mut f = std::io::BufWriter::new(std::fs::File::create(format!("{stem}.node"))?);
    writeln!(f, "{} 2 0 1", mesh.vertices.len())?;
    for (i, (p, m)) in mesh.vertices.iter().zip(&mesh.vertex_markers).enumerate() {
        writeln!(f, "{i} {} {} {m}", p[0], p[1])?;
    }
    f.flush()?;
    let mut f = std::io::BufWriter::new(std::fs::File::create(format!("{stem}.ele"))?);
    writeln!(f, "{} 3 0", mesh.triangles.len())?;
    for (i, t) in mesh.triangles.iter().enumerate() {
        writeln!(f, "{i} {} {} {}", t[0], t[1], t[2])?;
    }
    f.flush()
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

fn random_points(n: usize, seed: u64) -> Vec<[f64; 2]> {
    let mut rng = SplitMix64(seed);
    (0..n)
        .map(|_| {
            let x = rng.next_f64();
            let y = rng.next_f64();
            [x, y]
        })
        .collect()
}

/// The unit square with a hole of radius 0.25 at its centre, the circle cut into `n` segments.
fn square_with_hole(n: usize) -> Pslg {
    let mut points = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut segments = vec![[0, 1], [1, 2], [2, 3], [3, 0]];
    for i in 0..n {
        let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        points.push([0.5 + 0.25 * t.cos(), 0.5 + 0.25 * t.sin()]);
        segments.push([(4 + i) as u32, (4 + (i + 1) % n) as u32]);
    }
    Pslg {
        points,
        segments,
        holes: vec![[0.5, 0.5]],
        ..Pslg::default()
    }
}

/// An order-sensitive hash of the coordinates' bit patterns and the segment indices:
/// sum over words i of mix64(word_i ^ (i · φ)), wrapping. Words are x0, y0, x1, y1, … then
/// one word per segment, (a << 32) | b. The same sum is cheap to vectorise in numpy.
fn input_hash(pslg: &Pslg) -> u64 {
    let coords = pslg
        .points
        .iter()
        .flat_map(|p| [p[0].to_bits(), p[1].to_bits()]);
    let segs = pslg
        .segments
        .iter()
        .map(|s| ((s[0] as u64) << 32) | s[1] as u64);
    coords.chain(segs).enumerate().fold(0u64, |h, (i, w)| {
        h.wrapping_add(mix64(w ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)))
    })
}

/// Triangle switches that map onto [`Options`]. Output-only switches (z, Q, V, e, n, …) are
/// accepted and ignored; switches that change the algorithm in ways idmesh cannot follow are
/// rejected so that a benchmark never silently compares different jobs.
fn parse_switches(sw: &str) -> Result<Options, String> {
    let mut opts = Options::default();
    let chars: Vec<char> = sw.trim_start_matches('-').chars().collect();
    let mut i = 0;
    let number = |i: &mut usize| -> String {
        let start = *i;
        while *i < chars.len() && (chars[*i].is_ascii_digit() || chars[*i] == '.') {
            *i += 1;
        }
        chars[start..*i].iter().collect()
    };
    while i < chars.len() {
        let c = chars[i];
        i += 1;
        match c {
            'p' | 'z' | 'Q' | 'V' | 'e' | 'n' | 'P' | 'N' | 'E' | 'B' | 'I' | 'O' | 'j' | 'D'
            | 'C' => {}
            'q' => {
                let num = number(&mut i);
                let angle = if num.is_empty() {
                    20.0
                } else {
                    num.parse()
                        .map_err(|_| format!("bad angle after 'q' in {sw:?}"))?
                };
                opts.min_angle = Some(angle);
            }
            'a' => {
                let num = number(&mut i);
                if num.is_empty() {
                    opts.region_max_area = true;
                } else {
                    let a = num
                        .parse()
                        .map_err(|_| format!("bad area after 'a' in {sw:?}"))?;
                    opts.max_area = Some(a);
                }
            }
            'S' => {
                let num = number(&mut i);
                let n = num
                    .parse()
                    .map_err(|_| format!("bad count after 'S' in {sw:?}"))?;
                opts.max_steiner = Some(n);
            }
            'A' => opts.region_attributes = true,
            'c' => opts.convex_hull = true,
            'Y' => opts.no_boundary_steiner = true,
            other => {
                return Err(format!(
                    "switch '{other}' in {sw:?} is not supported by bench2d (it would change \
                     the job being compared)"
                ))
            }
        }
    }
    Ok(opts)
}

/// Whitespace-separated tokens with `#` comments removed, one line at a time.
fn tokens(text: &str) -> impl Iterator<Item = (usize, Vec<&str>)> {
    text.lines().enumerate().filter_map(|(n, line)| {
        let line = line.split('#').next().unwrap_or("");
        let toks: Vec<&str> = line.split_whitespace().collect();
        (!toks.is_empty()).then_some((n + 1, toks))
    })
}

fn field<T: std::str::FromStr>(toks: &[&str], k: usize, line: usize) -> Result<T, String> {
    let tok = toks
        .get(k)
        .ok_or_else(|| format!("line {line}: expected at least {} fields", k + 1))?;
    tok.parse().map_err(|_| {
        format!(
            "line {line}: field {} ({tok:?}) is not a valid number",
            k + 1
        )
    })
}

/// Vertices, their markers (empty when the file has none) and the first vertex's index.
type NodeList = (Vec<[f64; 2]>, Vec<i32>, i64);

/// Reads a node section (header line plus vertices) and returns the first vertex's index as
/// the numbering base. `header` is passed when the caller has already consumed it.
fn parse_nodes<'t, I: Iterator<Item = (usize, Vec<&'t str>)>>(
    lines: &mut I,
    header: Option<(usize, Vec<&'t str>)>,
) -> Result<NodeList, String> {
    let (hl, h) = match header {
        Some(h) => h,
        None => lines.next().ok_or("missing vertex header")?,
    };
    let n: usize = field(&h, 0, hl)?;
    let nattr: usize = if h.len() > 2 { field(&h, 2, hl)? } else { 0 };
    let has_marker: usize = if h.len() > 3 { field(&h, 3, hl)? } else { 0 };
    let mut points = Vec::with_capacity(n);
    let mut markers = Vec::new();
    let mut base = 0;
    for k in 0..n {
        let (l, t) = lines.next().ok_or("file ends inside the vertex list")?;
        if k == 0 {
            base = field(&t, 0, l)?;
        }
        points.push([field(&t, 1, l)?, field(&t, 2, l)?]);
        if has_marker != 0 {
            markers.push(field(&t, 3 + nattr, l)?);
        }
    }
    Ok((points, markers, base))
}

/// A minimal reader for Triangle's .poly format: vertices, segments, holes, regions.
/// Vertex numbering follows the first vertex's index (0- or 1-based), as Triangle does.
/// `node_file` supplies the vertices when the .poly lists none (Triangle's convention).
fn parse_poly(
    text: &str,
    node_file: impl FnOnce() -> Result<String, String>,
) -> Result<Pslg, String> {
    let mut lines = tokens(text);
    let (hl, header) = lines.next().ok_or("empty file")?;
    let n: usize = field(&header, 0, hl)?;
    let (points, point_markers, base) = if n > 0 {
        parse_nodes(&mut lines, Some((hl, header)))?
    } else {
        let node_text = node_file()?;
        let mut node_lines = tokens(&node_text);
        parse_nodes(&mut node_lines, None)?
    };

    let (sl, sh) = lines.next().ok_or("missing segment header")?;
    let ns: usize = field(&sh, 0, sl)?;
    let seg_marker: usize = if sh.len() > 1 { field(&sh, 1, sl)? } else { 0 };
    let mut segments = Vec::with_capacity(ns);
    let mut segment_markers = Vec::new();
    for _ in 0..ns {
        let (l, t) = lines.next().ok_or("file ends inside the segment list")?;
        let a: i64 = field(&t, 1, l)?;
        let b: i64 = field(&t, 2, l)?;
        let a = u32::try_from(a - base)
            .map_err(|_| format!("line {l}: vertex index {a} is below the base {base}"))?;
        let b = u32::try_from(b - base)
            .map_err(|_| format!("line {l}: vertex index {b} is below the base {base}"))?;
        segments.push([a, b]);
        if seg_marker != 0 {
            segment_markers.push(field(&t, 3, l)?);
        }
    }

    let mut holes = Vec::new();
    if let Some((hl, hh)) = lines.next() {
        let nh: usize = field(&hh, 0, hl)?;
        for _ in 0..nh {
            let (l, t) = lines.next().ok_or("file ends inside the hole list")?;
            holes.push([field(&t, 1, l)?, field(&t, 2, l)?]);
        }
    }
    let mut regions = Vec::new();
    if let Some((rl, rh)) = lines.next() {
        let nr: usize = field(&rh, 0, rl)?;
        for _ in 0..nr {
            let (l, t) = lines.next().ok_or("file ends inside the region list")?;
            let area: f64 = if t.len() > 4 { field(&t, 4, l)? } else { -1.0 };
            regions.push(Region {
                point: [field(&t, 1, l)?, field(&t, 2, l)?],
                attribute: if t.len() > 3 { field(&t, 3, l)? } else { 0.0 },
                max_area: (area > 0.0).then_some(area),
            });
        }
    }
    Ok(Pslg {
        points,
        point_markers,
        segments,
        segment_markers,
        holes,
        regions,
    })
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

/// JSON has no NaN or infinity; an empty mesh's angles become null.
fn json_f64(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.6}")
    } else {
        "null".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix_matches_reference_algorithm() {
        // Independent restatement of SplitMix64 with plain u128 arithmetic mod 2^64.
        let seed = 42u64;
        let pts = random_points(3, seed);
        let mut state = seed as u128;
        let m = 1u128 << 64;
        let mut draw = || {
            state = (state + 0x9E37_79B9_7F4A_7C15) % m;
            let mut z = state;
            z = ((z ^ (z >> 30)) * 0xBF58_476D_1CE4_E5B9) % m;
            z = ((z ^ (z >> 27)) * 0x94D0_49BB_1331_11EB) % m;
            let z = (z ^ (z >> 31)) as u64;
            (z >> 11) as f64 / 9_007_199_254_740_992.0
        };
        for p in pts {
            assert_eq!(p[0].to_bits(), draw().to_bits());
            assert_eq!(p[1].to_bits(), draw().to_bits());
            assert!((0.0..1.0).contains(&p[0]) && (0.0..1.0).contains(&p[1]));
        }
    }

    #[test]
    fn hash_sees_order_and_segments() {
        let a = square_with_hole(8);
        let mut b = a.clone();
        b.points.swap(0, 1);
        let mut c = a.clone();
        c.segments[0] = [1, 0];
        assert_ne!(input_hash(&a), input_hash(&b));
        assert_ne!(input_hash(&a), input_hash(&c));
        assert_eq!(input_hash(&a), input_hash(&a.clone()));
    }

    #[test]
    fn switches_map_to_options() {
        let o = parse_switches("-pq33.5a0.0000012zQ").unwrap();
        assert_eq!(o.min_angle, Some(33.5));
        assert_eq!(o.max_area, Some(0.0000012));
        assert!(!o.region_max_area && !o.convex_hull);
        let o = parse_switches("pqacAS100").unwrap();
        assert_eq!(o.min_angle, Some(20.0));
        assert!(o.region_max_area && o.convex_hull && o.region_attributes);
        assert_eq!(o.max_steiner, Some(100));
        let err = parse_switches("pr").err().unwrap();
        assert!(err.contains("'r'"), "{err}");
        assert!(parse_switches("pS").is_err());
    }

    #[test]
    fn poly_reader_handles_base_markers_holes_regions() {
        let text = "# comment\n4 2 1 1\n1 0 0 7.5 3\n2 2 0 0 3\n3 2 2 0 3\n4 0 2 0 3\n\
                    4 1\n1 1 2 5\n2 2 3 5\n3 3 4 5\n4 4 1 5\n1\n1 9 9\n1\n1 1 1 4.5 0.25\n";
        let p = parse_poly(text, || Err("no .node".into())).unwrap();
        assert_eq!(
            p.points,
            vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]
        );
        assert_eq!(p.point_markers, vec![3; 4]);
        assert_eq!(p.segments, vec![[0, 1], [1, 2], [2, 3], [3, 0]]);
        assert_eq!(p.segment_markers, vec![5; 4]);
        assert_eq!(p.holes, vec![[9.0, 9.0]]);
        assert_eq!(p.regions[0].attribute, 4.5);
        assert_eq!(p.regions[0].max_area, Some(0.25));

        let no_vertices = "0 2 0 0\n1 0\n0 0 1\n";
        let p = parse_poly(no_vertices, || Ok("2 2 0 0\n0 0 0\n1 1 1\n".into())).unwrap();
        assert_eq!(p.points.len(), 2);
        assert_eq!(p.segments, vec![[0, 1]]);

        let err = parse_poly("2 2 0 0\n0 0 0\n", || Err(String::new()))
            .err()
            .unwrap();
        assert!(err.contains("vertex list"), "{err}");
        let err = parse_poly("1 2 0 0\n0 0 x\n", || Err(String::new()))
            .err()
            .unwrap();
        assert!(err.contains("line 2"), "{err}");
    }
}
