//! TetGen's switches: the one parser behind `idmesh tetgen`, the C ABI's
//! `idm_tetgen_parse_switches` and the TetGen compatibility layer (`compat/tetgen`), with the
//! file naming and output writing that TetGen's command line does.
//!
//! Switches are letters concatenated in one or more arguments starting with `-`
//! (`-pq1.414a0.1V` or `-p -q1.414 -a0.1 -V`), in any order relative to the file name. Numbers
//! are read exactly as TetGen reads them: after `q` (and its `/` part) the longest run of
//! digits and dots; after `a`, `S` and `T` the longest run of digits, dots, `e`, `-` and `+`, so
//! `-a1e-5` is 1e-5 but `-a0.1e` swallows the `e`. The run is converted like `strtod` (`strtol`
//! for `S`): its longest prefix that is a number. Every letter TetGen accepts but idmesh does
//! not implement is an error naming it, never silently ignored.

use std::fs::File;
use std::io::{self, Write};
use std::path::Path;

use super::tetgen_extra::Post;
use crate::error::InputError;
use crate::io::exchange::{self, Format, MeshView};
use crate::io::tetgen::{
    write_all_edges, write_all_faces, write_ele_with, write_face, write_neigh, write_node_with,
};
use crate::mesh3d::{Options3, TetMesh};

/// The parsed switches. Field comments give the letter.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TetSwitches {
    /// `p`: read a PLC (also implied by a PLC file name and by `q`, `a<volume>` and `d`).
    pub plc: bool,
    /// `q[ratio]`: the radius-edge bound (`q` alone, or implied by `a<volume>`: 2.0).
    pub radius_edge: Option<f64>,
    /// `q<ratio>/<angle>`: the minimum dihedral angle target, degrees (`/0`: no sliver
    /// removal; not given: the library's default with `q`).
    pub min_dihedral: Option<f64>,
    /// `a<volume>`: global maximum tetrahedron volume.
    pub max_volume: Option<f64>,
    /// `a` without a number: apply the regional volume bounds of the input.
    pub region_volume: bool,
    /// `A`: write each tetrahedron's regional attribute to the `.ele` file.
    pub region_attributes: bool,
    /// `S<n>`: at most `n` Steiner points (`S` alone: no limit, as in TetGen).
    pub max_steiner: Option<u64>,
    /// `Y`: keep the input surface (no Steiner points on segments or facets).
    pub keep_surface: bool,
    /// `M`: do not merge exactly coplanar neighbouring facets.
    pub no_merge: bool,
    /// `T[tol]`: merge nearly coplanar neighbouring facets too, with this relative tolerance
    /// (`T` alone: TetGen's default 1e-8); `None` (no `T`): exact coplanarity only. No effect
    /// with `M` or `Y`.
    pub coplanar_tolerance: Option<f64>,
    /// `z`: number output items from 0.
    pub zero_based: bool,
    /// `f`: write every face, not only the boundary ones, to the `.face` file.
    pub all_faces: bool,
    /// `e`: write the subsegments to an `.edge` file.
    pub edges: bool,
    /// `n`: write a `.neigh` file.
    pub neighbors: bool,
    /// `nn` (`n` given twice): also the tetrahedra on both sides of each output face (TetGen's
    /// `adjtetlist`).
    pub face_adjacency: bool,
    /// `N`, `E`, `F`: do not write the `.node` / `.ele` / `.face` file.
    pub no_node: bool,
    /// See `no_node`.
    pub no_ele: bool,
    /// See `no_node`.
    pub no_face: bool,
    /// `B`: leave boundary markers out of the output.
    pub no_markers: bool,
    /// `I`: no iteration number in output names (`FILE.node`, not `FILE.1.node`).
    pub no_iteration: bool,
    /// `d`: only check the PLC for self-intersections; write nothing.
    pub detect: bool,
    /// `C`: check the final mesh's consistency.
    pub check: bool,
    /// `Q`: print nothing but errors and warnings.
    pub quiet: bool,
    /// `V`: print statistics.
    pub verbose: bool,
    /// `r`: refine the given mesh (`.node` + `.ele`, with `.face` and `.vol` when present; see
    /// [`super::tetgen_extra`] for what is done).
    pub refine: bool,
    /// `i`: insert the points of `FILE.a.node` (the library's `addin`).
    pub insert_points: bool,
    /// `m`: sizes at points (`FILE.mtr`, or the background mesh `FILE.b.*`; the library's
    /// `pointmtrlist` of `in` or `bgmin`).
    pub metric: bool,
    /// `o2`: second-order (10-node) tetrahedra.
    pub order2: bool,
    /// `c`: mesh the convex hull of the input, keeping the PLC inside it.
    pub convex_hull: bool,
    /// `O[level][/scheme]`: optimise the mesh by flips and smoothing, `level` passes (`O`
    /// alone: 2; implied by `o/<angle>`). `None` without `O`: the mesh stays Delaunay.
    pub optimize_level: Option<u32>,
    /// The `/scheme` of `O` (bits 1 flips, 2 smoothing, 4 vertex insertion/deletion).
    pub optimize_scheme: Option<u32>,
    /// `o/<angle>` (also `o2/<angle>`): the optimisation's maximum dihedral angle target.
    pub optimize_max_dihedral: Option<f64>,
    /// `k` (VTK), `g` (Medit), and on the command line `--format NAME`: further output files
    /// in these exchange formats.
    pub formats: Vec<Format>,
}

/// What the command line asks for.
#[derive(Debug, Clone, PartialEq)]
pub enum Parsed {
    /// Print the help text.
    Help,
    /// Mesh `file` with `switches`.
    Run {
        /// The switches.
        switches: TetSwitches,
        /// The input file as given (with or without extension).
        file: String,
    },
}

/// TetGen switches that idmesh recognises but does not implement, with what they do.
fn unsupported(c: char) -> Option<&'static str> {
    Some(match c {
        'w' => "weighted Delaunay triangulations",
        'R' => "reversing tetrahedron orientation",
        's' => "piecewise smooth complexes",
        'l' | 'L' | 'b' => "choosing the insertion algorithm",
        'v' => "Voronoi diagram output",
        'G' | 'K' => "Gid output",
        'j' => "jettisoning unused vertices",
        _ => return None,
    })
}

/// The run of characters starting at `chars[*j + 1]` that `accept`s, when its first
/// character is a digit or a dot (TetGen's test); advances `*j` past it.
fn run_after(chars: &[char], j: &mut usize, accept: impl Fn(char) -> bool) -> Option<String> {
    let start = *j + 1;
    if !chars
        .get(start)
        .is_some_and(|c| c.is_ascii_digit() || *c == '.')
    {
        return None;
    }
    let mut end = start;
    while end < chars.len() && accept(chars[end]) {
        end += 1;
    }
    *j = end - 1;
    Some(chars[start..end].iter().collect())
}

/// `strtod` on a run: its longest prefix that is a number (none: 0).
fn strtod(run: &str) -> f64 {
    (1..=run.len())
        .rev()
        .find_map(|k| run[..k].parse::<f64>().ok())
        .unwrap_or(0.0)
}

fn plain_number(c: char) -> bool {
    c.is_ascii_digit() || c == '.'
}

fn exp_number(c: char) -> bool {
    c.is_ascii_digit() || ".e-+".contains(c)
}

/// Applies one switch group such as `-pq1.414a0.1V` (the leading character, `-` on a command
/// line, is skipped). Implications are applied by [`finish`] once all groups are read.
pub fn parse_group(arg: &str, sw: &mut TetSwitches) -> Result<(), String> {
    let chars: Vec<char> = arg.chars().skip(1).collect();
    if chars.is_empty() {
        return Err("empty switch '-'".into());
    }
    let mut j = 0;
    while j < chars.len() {
        match chars[j] {
            'p' => {
                sw.plc = true;
                if run_after(&chars, &mut j, plain_number).is_some() {
                    return Err(format!(
                        "-p with a number (a facet angle tolerance) is not supported (in '{arg}')"
                    ));
                }
            }
            'q' => {
                let ratio = run_after(&chars, &mut j, plain_number).map(|r| strtod(&r));
                sw.radius_edge = Some(ratio.unwrap_or(2.0));
                for part in 0..2 {
                    if chars.get(j + 1).is_some_and(|c| *c == '/' || *c == ',') {
                        j += 1;
                        let angle = run_after(&chars, &mut j, plain_number).map(|r| strtod(&r));
                        if part == 0 {
                            // `/` alone reads as 0, as TetGen's strtod does: no target.
                            sw.min_dihedral = Some(angle.unwrap_or(0.0));
                        } else if angle.unwrap_or(0.0) != 0.0 {
                            return Err(format!(
                                "-q: a maximum dihedral angle bound is not supported, only the \
                                 radius-edge ratio and the minimum dihedral angle (in '{arg}')"
                            ));
                        }
                    }
                }
            }
            'a' => match run_after(&chars, &mut j, exp_number).map(|r| strtod(&r)) {
                Some(v) if v > 0.0 => sw.max_volume = Some(v),
                Some(_) => return Err("-a: the maximum volume must be greater than zero".into()),
                None => sw.region_volume = true,
            },
            'S' => {
                if let Some(run) = run_after(&chars, &mut j, exp_number) {
                    let digits: String = run.chars().take_while(|c| c.is_ascii_digit()).collect();
                    let n = if digits.is_empty() {
                        0
                    } else {
                        digits
                            .parse::<u64>()
                            .map_err(|_| "-S: the Steiner point limit is too large".to_string())?
                    };
                    sw.max_steiner = Some(n);
                }
            }
            'T' => {
                let tol = run_after(&chars, &mut j, exp_number).map_or(1e-8, |r| strtod(&r));
                if !(tol > 0.0 && tol <= crate::mesh3d::MAX_COPLANAR_TOLERANCE) {
                    return Err(format!(
                        "-T: the coplanarity tolerance must be greater than 0 and at most {} \
                         (in '{arg}')",
                        crate::mesh3d::MAX_COPLANAR_TOLERANCE
                    ));
                }
                sw.coplanar_tolerance = Some(tol);
            }
            'A' => sw.region_attributes = true,
            'Y' => sw.keep_surface = true,
            'z' => sw.zero_based = true,
            'f' => sw.all_faces = true,
            'e' => sw.edges = true,
            'n' => {
                sw.face_adjacency |= sw.neighbors;
                sw.neighbors = true;
            }
            'N' => sw.no_node = true,
            'E' => sw.no_ele = true,
            'F' => sw.no_face = true,
            'B' => sw.no_markers = true,
            'I' => sw.no_iteration = true,
            'd' => sw.detect = true,
            'C' => sw.check = true,
            'Q' => sw.quiet = true,
            'V' => sw.verbose = true,
            'M' => sw.no_merge = true,
            'c' => sw.convex_hull = true,
            'k' => add_format(sw, Format::Vtk),
            'g' => add_format(sw, Format::Medit),
            // What idmesh always does: conforming Delaunay output (D, with TetGen's optional
            // level), no jettisoning (J).
            'D' => {
                if chars.get(j + 1).is_some_and(|c| ('1'..='3').contains(c)) {
                    j += 1;
                }
            }
            // idmesh decides every geometric question exactly; TetGen's X only turns its own
            // exact arithmetic off, so there is nothing to change.
            'J' | 'X' => {}
            'r' => sw.refine = true,
            'i' => sw.insert_points = true,
            'm' => sw.metric = true,
            'o' => {
                match chars.get(j + 1) {
                    Some('2') => {
                        sw.order2 = true;
                        j += 1;
                    }
                    Some('1') => {
                        sw.order2 = false;
                        j += 1;
                    }
                    Some(c) if c.is_ascii_digit() => {
                        return Err(format!(
                            "-o{c}: only -o2 (second-order tetrahedra) is supported (in '{arg}')"
                        ))
                    }
                    _ => {}
                }
                // TetGen 1.5's `o/<angle>`: the optimisation's maximum dihedral angle.
                if chars.get(j + 1).is_some_and(|c| *c == '/' || *c == ',') {
                    j += 1;
                    let run = run_after(&chars, &mut j, plain_number).ok_or_else(|| {
                        format!("-o/ needs a maximum dihedral angle after the '/' (in '{arg}')")
                    })?;
                    let a = strtod(&run);
                    if !(a > 0.0 && a < 180.0) {
                        return Err(format!(
                            "-o/{run}: the optimisation's maximum dihedral angle must be above \
                             0 and below 180 degrees (in '{arg}')"
                        ));
                    }
                    sw.optimize_max_dihedral = Some(a);
                }
            }
            'O' => {
                let digits = |j: &mut usize| run_after(&chars, j, |c| c.is_ascii_digit());
                let level = match digits(&mut j) {
                    Some(d) => d
                        .parse::<u32>()
                        .ok()
                        .filter(|&l| l <= crate::mesh3d::MAX_LEVEL)
                        .ok_or_else(|| {
                            format!(
                                "-O{d}: the optimisation level must be from 0 to {} (in '{arg}')",
                                crate::mesh3d::MAX_LEVEL
                            )
                        })?,
                    None => 2,
                };
                sw.optimize_level = Some(level);
                if chars.get(j + 1).is_some_and(|c| *c == '/' || *c == ',') {
                    j += 1;
                    let bad = |d: &str| {
                        format!(
                            "-O{level}/{d}: the optimisation scheme must be a number from 0 to 7 \
                             (bits: 1 flips, 2 smoothing, 4 vertex insertion/deletion) (in \
                             '{arg}')"
                        )
                    };
                    let d = digits(&mut j).ok_or_else(|| bad(""))?;
                    let scheme = d.parse::<u32>().ok().filter(|&s| s <= 7);
                    sw.optimize_scheme = Some(scheme.ok_or_else(|| bad(&d))?);
                }
            }
            'h' | 'H' | '?' => {
                return Err(format!(
                    "-{} inside a switch group; use 'idmesh tetgen --help'",
                    chars[j]
                ))
            }
            c if c.is_ascii_digit() || "+-./,".contains(c) => {
                return Err(format!(
                    "unexpected '{c}' in '{arg}': only p, q, a, S, T, O and o take numbers, right \
                     after the letter"
                ))
            }
            c => {
                return Err(match unsupported(c) {
                    Some(what) => format!("switch -{c} ({what}) is not supported (in '{arg}')"),
                    None => format!("unknown switch -{c} (in '{arg}'); try 'idmesh tetgen --help'"),
                })
            }
        }
        j += 1;
    }
    Ok(())
}

/// Adds an exchange format to the outputs (once).
pub fn add_format(sw: &mut TetSwitches, f: Format) {
    if !sw.formats.contains(&f) {
        sw.formats.push(f);
    }
}

/// The format named by `--format NAME` (`vtk`, `vtu`, `msh`, `mesh`).
pub fn format_option(name: &str) -> Result<Format, String> {
    Format::from_name(name)
        .ok_or_else(|| format!("unknown output format '{name}': expected vtk, vtu, msh or mesh"))
}

/// Applies the implications as TetGen applies them: `a<volume>` turns on `q`; `q` and `d` turn
/// on `p`, unless `r` (a mesh is read, not a PLC); and idmesh's own: `o/<angle>` turns on
/// `O`.
pub fn finish(sw: &mut TetSwitches) {
    if sw.max_volume.is_some() && sw.radius_edge.is_none() {
        sw.radius_edge = Some(2.0);
    }
    if (sw.radius_edge.is_some() || sw.detect) && !sw.refine {
        sw.plc = true;
    }
    // `o/<angle>` sets the target of TetGen's optimisation, on by default there; idmesh's is
    // off unless asked for, and the angle asks for it.
    if sw.optimize_max_dihedral.is_some() && sw.optimize_level.is_none() {
        sw.optimize_level = Some(2);
    }
}

/// Parses a switch string as TetGen's library takes it (`"pq1.414a0.1"`): whitespace separated
/// groups, each with or without a leading `-`. An empty string is no switches.
pub fn parse_string(text: &str) -> Result<TetSwitches, String> {
    let mut sw = TetSwitches::default();
    for group in text.split_whitespace() {
        let body = group.strip_prefix('-').unwrap_or(group);
        parse_group(&format!("-{body}"), &mut sw)?;
    }
    finish(&mut sw);
    Ok(sw)
}

/// Parses the arguments after `idmesh tetgen`, with the implications of [`finish`].
pub fn parse(args: &[String]) -> Result<Parsed, String> {
    let mut sw = TetSwitches::default();
    let mut file: Option<&String> = None;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if arg == "--help" || arg == "-h" {
            return Ok(Parsed::Help);
        } else if let Some(name) = arg.strip_prefix("--format=") {
            add_format(&mut sw, format_option(name)?);
        } else if arg == "--format" {
            let name = it
                .next()
                .ok_or("--format needs a value: vtk, vtu, msh or mesh")?;
            add_format(&mut sw, format_option(name)?);
        } else if arg.starts_with("--") {
            return Err(format!(
                "unknown option '{arg}'; try 'idmesh tetgen --help'"
            ));
        } else if arg.starts_with('-') {
            parse_group(arg, &mut sw)?;
        } else if let Some(first) = file {
            return Err(format!(
                "more than one input file given: '{first}' and '{arg}'"
            ));
        } else {
            file = Some(arg);
        }
    }
    finish(&mut sw);
    match file {
        Some(f) => Ok(Parsed::Run {
            switches: sw,
            file: f.clone(),
        }),
        None => Err("no input file given; try 'idmesh tetgen --help'".into()),
    }
}

/// Says something unless `-Q`.
pub fn say(sw: &TetSwitches, text: std::fmt::Arguments<'_>) {
    if !sw.quiet {
        println!("{text}");
    }
}

/// The extensions of PLC files, which imply `-p`.
pub const PLC_EXTENSIONS: [&str; 8] = ["poly", "smesh", "off", "stl", "ply", "mesh", "msh", "vtk"];

/// Where to read and where to write.
#[derive(Debug, Clone, PartialEq)]
pub struct Files {
    /// The file to read.
    pub input: String,
    /// Whether the input is read as a PLC.
    pub plc: bool,
    /// The output name without extension, e.g. `box.1`.
    pub out_stem: String,
}

impl Files {
    /// The output file with extension `ext` (without dot).
    pub fn output(&self, ext: &str) -> String {
        format!("{}.{ext}", self.out_stem)
    }
}

/// Resolves the file argument as TetGen does: a known extension names the format (PLC
/// extensions imply `-p`); without one, `-p` reads `FILE.poly` (or `FILE.smesh` when there is
/// no `.poly`), else `FILE.node`. Outputs get the next iteration number unless `-I`.
pub fn resolve(file: &str, sw: &TetSwitches) -> Files {
    let ext = Path::new(file)
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    let (stem, input, plc) = match ext.as_deref() {
        Some(e) if PLC_EXTENSIONS.contains(&e) => {
            (&file[..file.len() - e.len() - 1], file.to_string(), true)
        }
        Some("node") => (&file[..file.len() - 5], file.to_string(), sw.plc),
        _ if sw.plc => {
            let poly = format!("{file}.poly");
            let smesh = format!("{file}.smesh");
            let input = if !Path::new(&poly).exists() && Path::new(&smesh).exists() {
                smesh
            } else {
                poly
            };
            (file, input, true)
        }
        _ => (file, format!("{file}.node"), false),
    };
    let out_stem = if sw.no_iteration {
        stem.to_string()
    } else {
        super::next_iteration(stem)
    };
    Files {
        input,
        plc,
        out_stem,
    }
}

impl TetSwitches {
    /// The mesher options these switches ask for.
    pub fn options(&self) -> Options3 {
        Options3 {
            radius_edge: self.radius_edge,
            min_dihedral: self.min_dihedral,
            max_volume: self.max_volume,
            region_max_volume: self.region_volume,
            region_attributes: self.region_attributes,
            max_steiner: self.max_steiner,
            keep_surface: self.keep_surface,
            merge_coplanar: !self.no_merge,
            coplanar_tolerance: self.coplanar_tolerance,
            verbose: self.verbose && !self.quiet,
            convex_hull: self.convex_hull,
            optimize_level: self.optimize_level.unwrap_or(0),
            optimize_scheme: self.optimize_scheme,
            optimize_max_dihedral: self.optimize_max_dihedral,
            ..Options3::default()
        }
    }
}

/// Creates `name` and writes it with `write`; errors name the file.
fn write_file(
    sw: &TetSwitches,
    name: &str,
    write: impl FnOnce(&mut File) -> io::Result<()>,
) -> Result<(), String> {
    say(sw, format_args!("Writing {name}."));
    let mut f = File::create(name).map_err(|e| format!("cannot create {name}: {e}"))?;
    write(&mut f)
        .and_then(|()| f.flush())
        .map_err(|e| format!("cannot write {name}: {e}"))
}

/// Writes the output files TetGen's command line writes for these switches: `STEM.node`,
/// `.ele`, `.face` (unless `-N`, `-E`, `-F`), `.edge` with `-e` (every edge, as TetGen),
/// `.neigh` with `-n`, and `.vtk` (`-k`), `.mesh` (`-g`) or any `--format`. As in
/// TetGen, vertex markers are written when the input had them (`node_markers`) and face and
/// edge markers for PLC input, both unless `-B`. `post` adds the `-o2` nodes (after the
/// vertices in `.node`, 10 nodes per line in `.ele`) and point attributes.
pub fn write_outputs(
    sw: &TetSwitches,
    out_stem: &str,
    plc: bool,
    node_markers: bool,
    mesh: &TetMesh,
    post: &Post,
    base: u32,
) -> Result<(), String> {
    let node_markers = !sw.no_markers && node_markers;
    let markers = !sw.no_markers && plc;
    let name = |ext: &str| format!("{out_stem}.{ext}");
    if !sw.no_node {
        let extra = post.order2.as_ref().map_or(&[][..], |(p, _)| p.as_slice());
        write_file(sw, &name("node"), |f| {
            write_node_with(
                f,
                mesh,
                extra,
                post.num_point_attributes,
                &post.point_attributes,
                base,
                node_markers,
            )
        })?;
    }
    if !sw.no_ele {
        let corners: Vec<&[u32]> = match &post.order2 {
            Some((_, t10)) => t10.iter().map(|t| &t[..]).collect(),
            None => mesh.tets.iter().map(|t| &t[..]).collect(),
        };
        write_file(sw, &name("ele"), |f| {
            write_ele_with(f, mesh, &corners, base)
        })?;
    }
    if !sw.no_face {
        write_file(sw, &name("face"), |f| {
            if sw.all_faces {
                write_all_faces(f, mesh, base, markers)
            } else {
                write_face(f, mesh, base, markers)
            }
        })?;
    }
    if sw.edges {
        write_file(sw, &name("edge"), |f| {
            write_all_edges(f, mesh, base, markers)
        })?;
    }
    if sw.neighbors {
        write_file(sw, &name("neigh"), |f| write_neigh(f, mesh, base))?;
    }
    for &f in &sw.formats {
        write_file(sw, &name(f.extension()), |file| {
            exchange::write(file, MeshView::from(mesh), f)
        })?;
    }
    Ok(())
}

/// Shifts the 0-based indices of an input error to the file's numbering (counts stay); see
/// [`InputError::renumbered`].
pub fn renumber(e: &InputError, b: usize) -> InputError {
    e.renumbered(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(args: &[&str]) -> Result<(TetSwitches, String), String> {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        match parse(&args)? {
            Parsed::Run { switches, file } => Ok((switches, file)),
            Parsed::Help => Err("help".into()),
        }
    }

    #[test]
    fn parses_a_typical_group() {
        let (s, f) = run(&["-pq1.414a0.1V", "box.poly"]).unwrap();
        assert_eq!(f, "box.poly");
        assert!(s.plc && s.verbose && !s.quiet);
        assert_eq!(s.radius_edge, Some(1.414));
        assert_eq!(s.max_volume, Some(0.1));
        assert!(!s.region_volume);
    }

    #[test]
    fn q_alone_is_two_and_implies_p_and_a_implies_q() {
        let (s, _) = run(&["-q", "x"]).unwrap();
        assert_eq!(s.radius_edge, Some(2.0));
        assert!(s.plc);
        let (s, _) = run(&["-a0.5", "x"]).unwrap();
        assert_eq!((s.radius_edge, s.max_volume), (Some(2.0), Some(0.5)));
        assert!(s.plc);
        // 'a' alone (regional bounds) implies neither.
        let (s, _) = run(&["-a", "x"]).unwrap();
        assert!(s.region_volume && !s.plc && s.radius_edge.is_none());
    }

    #[test]
    fn volume_numbers_take_exponents_like_tetgen() {
        let (s, _) = run(&["-pa1e-5", "x"]).unwrap();
        assert_eq!(s.max_volume, Some(1e-5));
        // The 'e' is swallowed by the number: no .edge file.
        let (s, _) = run(&["-pa0.1e", "x"]).unwrap();
        assert_eq!(s.max_volume, Some(0.1));
        assert!(!s.edges);
        let (s, _) = run(&["-pea0.1", "x"]).unwrap();
        assert!(s.edges);
        // The ratio takes no exponent: 'e' after it is the edge switch.
        let (s, _) = run(&["-q1.2e", "x"]).unwrap();
        assert_eq!(s.radius_edge, Some(1.2));
        assert!(s.edges);
        assert!(run(&["-pa0", "x"])
            .unwrap_err()
            .contains("greater than zero"));
        assert!(run(&["-pa.", "x"])
            .unwrap_err()
            .contains("greater than zero"));
    }

    #[test]
    fn dihedral_part_and_steiner_limit() {
        let (s, _) = run(&["-pq1.5/0", "x"]).unwrap();
        assert_eq!((s.radius_edge, s.min_dihedral), (Some(1.5), Some(0.0)));
        assert_eq!(
            s.options().min_dihedral,
            Some(0.0),
            "/0 turns sliver removal off"
        );
        let (s, _) = run(&["-pq1.5", "x"]).unwrap();
        assert_eq!(
            s.min_dihedral, None,
            "q alone: the library's default target"
        );
        let (s, _) = run(&["-pq1.414/12.5a0.1", "x"]).unwrap();
        assert_eq!(
            (s.radius_edge, s.min_dihedral, s.max_volume),
            (Some(1.414), Some(12.5), Some(0.1))
        );
        assert_eq!(s.options().min_dihedral, Some(12.5));
        let (s, _) = run(&["-pq/18", "x"]).unwrap();
        assert_eq!((s.radius_edge, s.min_dihedral), (Some(2.0), Some(18.0)));
        let (s, _) = run(&["-pq1.2,10/0", "x"]).unwrap();
        assert_eq!((s.radius_edge, s.min_dihedral), (Some(1.2), Some(10.0)));
        let e = run(&["-pq1.5/10/170", "x"]).unwrap_err();
        assert!(
            e.contains("maximum dihedral") && e.contains("not supported"),
            "{e}"
        );
        let (s, _) = run(&["-pS120", "x"]).unwrap();
        assert_eq!(s.max_steiner, Some(120));
        let (s, _) = run(&["-pS", "x"]).unwrap();
        assert_eq!(s.max_steiner, None, "S alone sets no limit, as in TetGen");
        let (s, _) = run(&["-pS1e3", "x"]).unwrap();
        assert_eq!(s.max_steiner, Some(1), "strtol stops at the 'e'");
        assert!(run(&["-S99999999999999999999999", "x"]).is_err());
    }

    #[test]
    fn output_and_accepted_letters() {
        let (s, _) = run(&["-pzfenNEFBIACQ", "x"]).unwrap();
        assert!(s.zero_based && s.all_faces && s.edges && s.neighbors);
        assert!(s.no_node && s.no_ele && s.no_face && s.no_markers && s.no_iteration);
        assert!(s.region_attributes && s.check && s.quiet);
        let (s, _) = run(&["-pMJD2", "x"]).unwrap();
        assert_eq!(
            s,
            TetSwitches {
                plc: true,
                no_merge: true,
                ..TetSwitches::default()
            }
        );
        let (s, _) = run(&["-pJD2", "x"]).unwrap();
        assert!(!s.no_merge, "coplanar facets are merged unless -M");
        let (s, _) = run(&["-d", "x"]).unwrap();
        assert!(s.detect && s.plc);
    }

    #[test]
    fn unsupported_and_unknown_switches_are_errors_naming_them() {
        let (s, _) = run(&["-pY", "x"]).unwrap();
        assert!(s.keep_surface && s.plc);
        let (s, _) = run(&["-pc", "x"]).unwrap();
        assert!(s.convex_hull && s.options().convex_hull);
        let e = run(&["-pw", "x"]).unwrap_err();
        assert!(e.contains("-w") && e.contains("weighted"), "{e}");
        let e = run(&["-p1.5", "x"]).unwrap_err();
        assert!(e.contains("-p"), "{e}");
        let e = run(&["-pqx", "x"]).unwrap_err();
        assert!(e.contains("-x") && e.contains("-pqx"), "{e}");
        assert!(run(&["-", "x"]).is_err());
        assert!(run(&["--frobnicate", "x"])
            .unwrap_err()
            .contains("--frobnicate"));
        assert!(run(&["-p/", "x"]).unwrap_err().contains("'/'"));
    }

    #[test]
    fn file_count_is_checked_and_help_is_recognised() {
        assert!(run(&["-p"]).unwrap_err().contains("no input file"));
        assert!(run(&["a", "b"]).unwrap_err().contains("more than one"));
        let args = vec!["-p".to_string(), "--help".to_string()];
        assert_eq!(parse(&args).unwrap(), Parsed::Help);
    }

    fn sw(plc: bool) -> TetSwitches {
        TetSwitches {
            plc,
            ..TetSwitches::default()
        }
    }

    #[test]
    fn nn_asks_for_face_adjacency_and_strings_parse_like_groups() {
        let s = parse_string("pq1.414a0.01nnfAzQ").unwrap();
        assert!(s.plc && s.neighbors && s.face_adjacency && s.all_faces);
        assert!(s.region_attributes && s.zero_based && s.quiet);
        assert_eq!((s.radius_edge, s.max_volume), (Some(1.414), Some(0.01)));
        let s = parse_string("-pn -V").unwrap();
        assert!(s.neighbors && !s.face_adjacency && s.verbose);
        assert_eq!(parse_string("").unwrap(), TetSwitches::default());
        let e = parse_string("pqR").unwrap_err();
        assert!(e.contains("-R"), "{e}");
        assert!(parse_string("pqc").unwrap().convex_hull);
        assert!(parse_string("a1").unwrap().plc, "a<volume> implies q and p");
    }

    #[test]
    fn names_follow_tetgen() {
        let f = resolve("d/box.off", &sw(false));
        assert_eq!(
            f,
            Files {
                input: "d/box.off".into(),
                plc: true,
                out_stem: "d/box.1".into()
            }
        );
        let f = resolve("box.1.smesh", &sw(false));
        assert_eq!((f.plc, f.out_stem.as_str()), (true, "box.2"));
        let f = resolve("pts", &sw(false));
        assert_eq!((f.input.as_str(), f.plc), ("pts.node", false));
        let f = resolve("pts.node", &sw(true));
        assert_eq!((f.input.as_str(), f.plc), ("pts.node", true));
        let f = resolve("/nonexistent-idmesh/x", &sw(true));
        assert_eq!(f.input, "/nonexistent-idmesh/x.poly");
        let f = resolve(
            "a.v2/x.STL",
            &TetSwitches {
                no_iteration: true,
                ..sw(false)
            },
        );
        assert_eq!((f.plc, f.out_stem.as_str()), (true, "a.v2/x"));
    }

    #[test]
    fn options_map_the_switches() {
        let s = TetSwitches {
            radius_edge: Some(1.5),
            max_volume: Some(0.25),
            region_volume: true,
            region_attributes: true,
            max_steiner: Some(7),
            verbose: true,
            quiet: true,
            ..sw(true)
        };
        let o = s.options();
        assert_eq!(
            (o.radius_edge, o.max_volume, o.max_steiner),
            (Some(1.5), Some(0.25), Some(7))
        );
        assert!(o.region_max_volume && o.region_attributes && !o.verbose && o.merge_coplanar);
        assert!(
            !TetSwitches {
                no_merge: true,
                ..sw(true)
            }
            .options()
            .merge_coplanar
        );
    }

    #[test]
    fn renumber_shifts_indices_but_not_counts() {
        let e = renumber(
            &InputError::FacetIndexOutOfRange {
                facet: 0,
                polygon: 1,
                index: 9,
                num_points: 9,
            },
            1,
        );
        assert_eq!(
            e,
            InputError::FacetIndexOutOfRange {
                facet: 1,
                polygon: 2,
                index: 10,
                num_points: 9
            }
        );
        let e = renumber(
            &InputError::VertexOnFacet {
                vertex: 3,
                facet: 4,
            },
            1,
        );
        assert_eq!(
            e,
            InputError::VertexOnFacet {
                vertex: 4,
                facet: 5
            }
        );
        assert_eq!(
            renumber(&InputError::TooFewPoints3 { count: 2 }, 1),
            InputError::TooFewPoints3 { count: 2 }
        );
    }

    #[test]
    fn refine_insert_metric_order2_and_x_are_parsed() {
        let (s, _) = run(&["-rq1.3aimo2X", "box.1"]).unwrap();
        assert!(s.refine && s.insert_points && s.metric && s.order2 && s.region_volume);
        assert!(!s.plc, "-r reads a mesh: q does not imply p");
        assert_eq!(s.radius_edge, Some(1.3));
        let (s, _) = run(&["-pq", "x"]).unwrap();
        assert!(!s.refine && !s.insert_points && !s.metric && !s.order2);
        let (s, _) = run(&["-po1", "x"]).unwrap();
        assert!(!s.order2, "-o1 is first order");
        let e = run(&["-po3", "x"]).unwrap_err();
        assert!(e.contains("-o3") && e.contains("o2"), "{e}");
        let (s, _) = run(&["-po/150", "x"]).unwrap();
        assert_eq!(s.optimize_max_dihedral, Some(150.0));
        assert_eq!(s.optimize_level, Some(2), "o/<angle> implies O");
        let (s, _) = run(&["-po2/150.5e", "x"]).unwrap();
        assert!(s.order2 && s.edges);
        assert_eq!(s.optimize_max_dihedral, Some(150.5));
        // o2 followed by other letters.
        let (s, _) = run(&["-po2e", "x"]).unwrap();
        assert!(s.order2 && s.edges);
        let s = parse_string("pq1.414o2").unwrap();
        assert!(s.order2 && s.plc);
    }

    #[test]
    fn optimisation_level_scheme_and_angle() {
        let (s, _) = run(&["-pq1.414O", "x"]).unwrap();
        assert_eq!((s.optimize_level, s.optimize_scheme), (Some(2), None));
        assert_eq!(s.options().optimize_level, 2);
        let (s, _) = run(&["-pO3/1V", "x"]).unwrap();
        assert_eq!((s.optimize_level, s.optimize_scheme), (Some(3), Some(1)));
        assert!(s.verbose);
        let o = s.options();
        assert_eq!((o.optimize_level, o.optimize_scheme), (3, Some(1)));
        let (s, _) = run(&["-pO10,7", "x"]).unwrap();
        assert_eq!((s.optimize_level, s.optimize_scheme), (Some(10), Some(7)));
        let (s, _) = run(&["-pO0o/150", "x"]).unwrap();
        assert_eq!(s.optimize_level, Some(0), "an explicit O0 stays off");
        let (s, _) = run(&["-pq", "x"]).unwrap();
        assert_eq!(
            s.options().optimize_level,
            0,
            "no O: the mesh stays Delaunay"
        );
        for (bad, words) in [
            ("-pO11", ["-O11", "level"]),
            ("-pO2/9", ["-O2/9", "scheme"]),
            ("-pO2/", ["-O2/", "scheme"]),
            ("-po/0", ["-o/0", "angle"]),
            ("-po/180", ["-o/180", "angle"]),
            ("-po/", ["-o/", "angle"]),
        ] {
            let e = run(&[bad, "x"]).unwrap_err();
            assert!(words.iter().all(|w| e.contains(w)), "{bad}: {e}");
        }
    }

    #[test]
    fn r_reads_the_node_file_of_a_previous_mesh() {
        let sw = TetSwitches {
            refine: true,
            radius_edge: Some(1.5),
            ..TetSwitches::default()
        };
        let f = resolve("/nonexistent-idmesh/box.1", &sw);
        assert_eq!(f.input, "/nonexistent-idmesh/box.1.node");
        assert_eq!(f.out_stem, "/nonexistent-idmesh/box.2");
        assert!(!f.plc);
    }
}
