//! Triangle 1.6's switches: the one parser behind `idmesh triangle` (command line form,
//! [`parse_command_line`]) and behind `triangulate()` of `compat/triangle/triangle.h` (library
//! form, [`parse_library`], reached from C through `idm_triangle_parse_switches`).
//!
//! Switches are letters, concatenated (`pq30a0.1V`) in one or more groups. Numbers after `q`
//! and `a` are read exactly as Triangle reads them: the longest run of digits and dots,
//! converted like `strtod` would (so `a1e-5` means "a1, then switch e, then ..."); `S` takes
//! digits only. Every letter Triangle knows is recorded in [`Switches::given`]; each consumer
//! then refuses, by name, the ones it does not honour ([`Switches::refuse_except`]), so no
//! switch is ever silently ignored. Letters Triangle does not know are errors here.

use crate::mesh2d::{Options, TriMesh, NONE};

/// The parsed switches. Field comments give the letter.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Switches {
    /// `p`: the input is a PSLG (segments, holes, regions); on the command line, read a `.poly`
    /// file (also implied by a `.poly` file name, as in Triangle).
    pub poly: bool,
    /// `r`: refine a previously generated mesh.
    pub refine: bool,
    /// `q[angle]`: minimum angle in degrees (`q` alone is 20; `q0` means no angle bound).
    pub min_angle: Option<f64>,
    /// `a<area>`: global maximum triangle area.
    pub max_area: Option<f64>,
    /// `a` without a number: apply the regional area bounds.
    pub region_area: bool,
    /// `u`: the user's sizing test (`triunsuitable`).
    pub user_test: bool,
    /// `A`: regional attributes on triangles.
    pub region_attributes: bool,
    /// `c`: mesh the convex hull.
    pub convex_hull: bool,
    /// `D`: conforming Delaunay. idmesh output always is (unless `Y`).
    pub conforming_delaunay: bool,
    /// `j`: jettison vertices that are in no triangle.
    pub jettison: bool,
    /// `e`: output the edges.
    pub edges: bool,
    /// `v`: output the Voronoi diagram.
    pub voronoi: bool,
    /// `n`: output the triangle neighbours.
    pub neighbors: bool,
    /// `g`: Geomview `.off` output (a file; Triangle's library writes nothing for it).
    pub geomview: bool,
    /// `B`: no boundary markers in the output.
    pub no_boundary_markers: bool,
    /// `P`: no segments in the output (no `.poly` file).
    pub no_poly: bool,
    /// `N`: no vertices in the output (no `.node` file).
    pub no_node: bool,
    /// `E`: no triangles in the output (no `.ele` file).
    pub no_ele: bool,
    /// `I`: no iteration numbers in output file names.
    pub no_iteration_numbers: bool,
    /// `O`: ignore the holes.
    pub ignore_holes: bool,
    /// `X`: no exact arithmetic (idmesh is always exact).
    pub no_exact: bool,
    /// `z`: number items from 0.
    pub zero_based: bool,
    /// `o2`: second-order (6-node) triangles.
    pub second_order: bool,
    /// `Y` once: no Steiner points on boundary segments (constrained Delaunay output).
    pub no_boundary_steiner: bool,
    /// `YY`: no Steiner points on any segment.
    pub no_segment_steiner: bool,
    /// `S[n]`: at most `n` Steiner points (`S` alone is 0, as in Triangle).
    pub max_steiner: Option<u64>,
    /// `C`: check the consistency of the final mesh.
    pub check: bool,
    /// `Q`: print nothing but errors and warnings.
    pub quiet: bool,
    /// `V`: print statistics (repeat for more).
    pub verbose: bool,
    /// Every switch given, by name (`"o2"` and `"YY"` are names), in order of first appearance.
    pub given: Vec<&'static str>,
    /// `--format NAME` (command line only): further output files in these exchange formats.
    pub formats: Vec<crate::io::exchange::Format>,
}

/// What a command line asks for.
#[derive(Debug, Clone, PartialEq)]
pub enum Parsed {
    /// Print the help text.
    Help,
    /// Mesh `file` with `switches`.
    Run {
        /// The switches.
        switches: Switches,
        /// The input file as given (with or without extension).
        file: String,
    },
}

/// Every switch name Triangle 1.6 knows, with what it does (used in refusals).
pub const ALL: &[(&str, &str)] = &[
    ("p", "PSLG input"),
    ("r", "refining a previous mesh"),
    ("q", "a minimum angle"),
    ("a", "area bounds"),
    ("u", "a user-defined sizing test"),
    ("A", "regional attributes"),
    ("c", "meshing the convex hull"),
    ("D", "conforming Delaunay"),
    ("j", "jettisoning unused vertices"),
    ("e", "edge output"),
    ("v", "Voronoi diagram output"),
    ("n", "neighbour output"),
    ("g", "Geomview output"),
    ("B", "leaving out boundary markers"),
    ("P", "leaving out segments"),
    ("N", "leaving out vertices"),
    ("E", "leaving out triangles"),
    ("I", "leaving out iteration numbers"),
    ("O", "ignoring holes"),
    ("X", "disabling exact arithmetic"),
    ("z", "numbering from zero"),
    ("o2", "second-order triangles"),
    ("Y", "no Steiner points on boundary segments"),
    ("YY", "no Steiner points on any segment"),
    ("S", "a Steiner point limit"),
    ("i", "the incremental algorithm"),
    ("F", "Fortune's sweepline algorithm"),
    ("l", "vertical cuts only in divide-and-conquer"),
    (
        "s",
        "splitting segments instead of constrained Delaunay insertion",
    ),
    ("C", "the consistency check"),
    ("Q", "quiet output"),
    ("V", "verbose output"),
    ("w", "weighted Delaunay triangulations"),
    ("W", "regular triangulations"),
];

impl Switches {
    /// Refuses the first given switch whose name is not in `honoured`, naming it and saying what
    /// it does.
    pub fn refuse_except(&self, honoured: &[&str]) -> Result<(), String> {
        match self.given.iter().find(|g| !honoured.contains(g)) {
            None => Ok(()),
            Some(name) => {
                let what = ALL.iter().find(|(n, _)| n == name).map_or("", |(_, w)| *w);
                Err(format!("switch -{name} ({what}) is not supported"))
            }
        }
    }

    /// The mesher options these switches ask for. `poly` says whether the input is a PSLG:
    /// regional area bounds and attributes need one, as in Triangle.
    pub fn options(&self, poly: bool) -> Options {
        Options {
            min_angle: self.min_angle,
            max_area: self.max_area,
            region_max_area: self.region_area && poly,
            region_attributes: self.region_attributes && poly,
            convex_hull: self.convex_hull,
            max_steiner: self.max_steiner,
            no_boundary_steiner: self.no_boundary_steiner,
            verbose: self.verbose && !self.quiet,
            ..Options::default()
        }
    }

    fn note(&mut self, name: &'static str) {
        if !self.given.contains(&name) {
            self.given.push(name);
        }
    }
}

/// Reads Triangle's number after a switch: the longest run of digits and dots starting at
/// `chars[*j + 1]`, converted like `strtod` (the longest prefix that is a number; none is 0).
/// Advances `*j` past the run. Returns `None` when no digit or dot follows.
fn number_after(chars: &[char], j: &mut usize) -> Option<f64> {
    let start = *j + 1;
    let mut end = start;
    while end < chars.len() && (chars[end].is_ascii_digit() || chars[end] == '.') {
        end += 1;
    }
    if end == start {
        return None;
    }
    *j = end - 1;
    let run: String = chars[start..end].iter().collect();
    let value = (1..=run.len())
        .rev()
        .find_map(|k| run[..k].parse::<f64>().ok());
    Some(value.unwrap_or(0.0))
}

/// Reads the digits after `S`.
fn digits_after(chars: &[char], j: &mut usize) -> Result<u64, String> {
    let mut n: u64 = 0;
    while *j + 1 < chars.len() && chars[*j + 1].is_ascii_digit() {
        *j += 1;
        let d = chars[*j].to_digit(10).unwrap_or(0) as u64;
        n = n
            .checked_mul(10)
            .and_then(|n| n.checked_add(d))
            .ok_or_else(|| "-S: the Steiner point limit is too large".to_string())?;
    }
    Ok(n)
}

/// Applies one switch group such as `pq30a0.1V` (without its leading `-`) to `sw`. `shown` is
/// the group as the user wrote it, for messages.
pub fn parse_group(group: &str, shown: &str, sw: &mut Switches) -> Result<(), String> {
    let chars: Vec<char> = group.chars().collect();
    if chars.is_empty() {
        return Err(format!("empty switch group '{shown}'"));
    }
    let mut j = 0;
    while j < chars.len() {
        let name: &'static str = match chars[j] {
            'p' => {
                sw.poly = true;
                "p"
            }
            'r' => {
                sw.refine = true;
                "r"
            }
            'q' => {
                let angle = number_after(&chars, &mut j).unwrap_or(20.0);
                sw.min_angle = (angle != 0.0).then_some(angle);
                "q"
            }
            'a' => {
                match number_after(&chars, &mut j) {
                    Some(area) if area > 0.0 => sw.max_area = Some(area),
                    Some(_) => return Err("-a: the maximum area must be greater than zero".into()),
                    None => sw.region_area = true,
                }
                "a"
            }
            'u' => {
                sw.user_test = true;
                "u"
            }
            'A' => {
                sw.region_attributes = true;
                "A"
            }
            'c' => {
                sw.convex_hull = true;
                "c"
            }
            'D' => {
                sw.conforming_delaunay = true;
                "D"
            }
            'j' => {
                sw.jettison = true;
                "j"
            }
            'e' => {
                sw.edges = true;
                "e"
            }
            'v' => {
                sw.voronoi = true;
                "v"
            }
            'n' => {
                sw.neighbors = true;
                "n"
            }
            'g' => {
                sw.geomview = true;
                "g"
            }
            'B' => {
                sw.no_boundary_markers = true;
                "B"
            }
            'P' => {
                sw.no_poly = true;
                "P"
            }
            'N' => {
                sw.no_node = true;
                "N"
            }
            'E' => {
                sw.no_ele = true;
                "E"
            }
            'I' => {
                sw.no_iteration_numbers = true;
                "I"
            }
            'O' => {
                sw.ignore_holes = true;
                "O"
            }
            'X' => {
                sw.no_exact = true;
                "X"
            }
            'z' => {
                sw.zero_based = true;
                "z"
            }
            'o' if chars.get(j + 1) == Some(&'2') => {
                j += 1;
                sw.second_order = true;
                "o2"
            }
            'o' => return Err(format!("-o must be followed by 2 (-o2), in '{shown}'")),
            'Y' if sw.no_boundary_steiner => {
                sw.no_segment_steiner = true;
                "YY"
            }
            'Y' => {
                sw.no_boundary_steiner = true;
                "Y"
            }
            'S' => {
                sw.max_steiner = Some(digits_after(&chars, &mut j)?);
                "S"
            }
            'i' => "i",
            'F' => "F",
            'l' => "l",
            's' => "s",
            'C' => {
                sw.check = true;
                "C"
            }
            'Q' => {
                sw.quiet = true;
                "Q"
            }
            'V' => {
                sw.verbose = true;
                "V"
            }
            'w' => "w",
            'W' => "W",
            c if c.is_ascii_digit() || "+-.".contains(c) => {
                return Err(format!(
                    "unexpected '{c}' in '{shown}': only q, a and S take numbers, written with \
                     digits and dots (no exponents)"
                ))
            }
            c => return Err(format!("unknown switch -{c} (in '{shown}')")),
        };
        sw.note(name);
        j += 1;
    }
    Ok(())
}

/// Parses the switch string handed to Triangle's library `triangulate()`: letters without a
/// leading dash (`"pzq30"`). A leading dash and spaces between groups are tolerated.
pub fn parse_library(text: &str) -> Result<Switches, String> {
    let mut sw = Switches::default();
    for group in text.split_whitespace() {
        let letters = group.strip_prefix('-').unwrap_or(group);
        if !letters.is_empty() {
            parse_group(letters, group, &mut sw)?;
        }
    }
    Ok(sw)
}

/// Parses the arguments after `idmesh triangle`: switch groups starting with `-` and one file,
/// in any order, or `--help`.
pub fn parse_command_line(args: &[String]) -> Result<Parsed, String> {
    let mut sw = Switches::default();
    let mut file: Option<&String> = None;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let format_name = if arg == "--format" {
            Some(
                it.next()
                    .ok_or("--format needs a value: vtk, vtu, msh or mesh")?
                    .as_str(),
            )
        } else {
            arg.strip_prefix("--format=")
        };
        if let Some(name) = format_name {
            let f = crate::switches::tetgen::format_option(name)?;
            if !sw.formats.contains(&f) {
                sw.formats.push(f);
            }
        } else if arg == "--help" || arg == "-h" {
            return Ok(Parsed::Help);
        } else if arg.starts_with("--") {
            return Err(format!("unknown option '{arg}'"));
        } else if let Some(group) = arg.strip_prefix('-') {
            parse_group(group, arg, &mut sw)?;
        } else if let Some(first) = file {
            return Err(format!(
                "more than one input file given: '{first}' and '{arg}'"
            ));
        } else {
            file = Some(arg);
        }
    }
    match file {
        Some(f) => Ok(Parsed::Run {
            switches: sw,
            file: f.clone(),
        }),
        None => Err("no input file given".into()),
    }
}

/// The segments Triangle outputs for a mesh: the subsegments, then the boundary edges that are
/// no subsegment (the convex hull of a point set, or hull edges a PSLG leaves open), which
/// Triangle also treats as segments, with marker 1. Each boundary edge is oriented with the
/// mesh on its left.
pub fn output_segments(mesh: &TriMesh) -> Vec<([u32; 2], i32)> {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let known: std::collections::HashSet<(u32, u32)> =
        mesh.segments.iter().map(|s| key(s[0], s[1])).collect();
    let mut out: Vec<([u32; 2], i32)> = mesh
        .segments
        .iter()
        .copied()
        .zip(mesh.segment_markers.iter().copied())
        .collect();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for i in 0..3 {
            if mesh.neighbors.get(t).is_some_and(|n| n[i] == NONE) {
                let (a, b) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                if !known.contains(&key(a, b)) {
                    out.push(([a, b], 1));
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(args: &[&str]) -> Result<(Switches, String), String> {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        match parse_command_line(&args)? {
            Parsed::Run { switches, file } => Ok((switches, file)),
            Parsed::Help => Err("help".into()),
        }
    }

    #[test]
    fn parses_a_typical_group() {
        let (s, f) = run(&["-pq30a0.01V", "box.poly"]).unwrap();
        assert_eq!(f, "box.poly");
        assert!(s.poly && s.verbose);
        assert_eq!(s.min_angle, Some(30.0));
        assert_eq!(s.max_area, Some(0.01));
        assert!(!s.region_area && !s.quiet);
        assert_eq!(s.given, vec!["p", "q", "a", "V"]);
    }

    #[test]
    fn switches_may_be_split_and_follow_the_file() {
        let (s, f) = run(&["-p", "x", "-q", "-zen"]).unwrap();
        assert_eq!(f, "x");
        assert!(s.poly && s.zero_based && s.edges && s.neighbors);
        assert_eq!(s.min_angle, Some(20.0), "q alone is 20 degrees");
    }

    #[test]
    fn numbers_are_read_like_triangle() {
        let (s, _) = run(&["-pq32.5a0.0000012", "f"]).unwrap();
        assert_eq!(s.min_angle, Some(32.5));
        assert_eq!(s.max_area, Some(0.0000012));
        // No exponents: 'e' after the number is the edge switch.
        let e = run(&["-pa1e-5", "f"]).unwrap_err();
        assert!(e.contains("no exponents"), "{e}");
        let (s, _) = run(&["-pa1e", "f"]).unwrap();
        assert_eq!(s.max_area, Some(1.0));
        assert!(s.edges);
        // strtod stops at the second dot.
        let (s, _) = run(&["-q30.5.2", "f"]).unwrap();
        assert_eq!(s.min_angle, Some(30.5));
        // '.5' and '20.' are numbers.
        let (s, _) = run(&["-q20.a.5", "f"]).unwrap();
        assert_eq!((s.min_angle, s.max_area), (Some(20.0), Some(0.5)));
    }

    #[test]
    fn area_with_and_without_number_may_both_appear() {
        let (s, _) = run(&["-pa0.5qa", "f"]).unwrap();
        assert_eq!(s.max_area, Some(0.5));
        assert!(s.region_area);
        assert!(run(&["-pa0", "f"])
            .unwrap_err()
            .contains("greater than zero"));
        assert!(run(&["-pa.", "f"])
            .unwrap_err()
            .contains("greater than zero"));
    }

    #[test]
    fn steiner_limit_and_other_letters() {
        let (s, _) = run(&["-pS120Y", "f"]).unwrap();
        assert_eq!(s.max_steiner, Some(120));
        assert!(s.no_boundary_steiner && !s.no_segment_steiner);
        let (s, _) = run(&["-S", "f"]).unwrap();
        assert_eq!(
            s.max_steiner,
            Some(0),
            "S alone allows no Steiner points, as in Triangle"
        );
        let (s, _) = run(&["-cADNEPQ", "f"]).unwrap();
        assert!(s.convex_hull && s.region_attributes && s.conforming_delaunay);
        assert!(s.no_node && s.no_ele && s.no_poly && s.quiet);
        assert_eq!(s.min_angle, None);
        let (s, _) = run(&["-q0", "f"]).unwrap();
        assert_eq!(s.min_angle, None, "q0 is no angle bound");
        assert!(run(&["-S99999999999999999999999", "f"]).is_err());
        let (s, _) = run(&["-pYY", "f"]).unwrap();
        assert!(s.no_segment_steiner);
        assert_eq!(s.given, vec!["p", "Y", "YY"]);
        assert!(s.refuse_except(&["p", "Y"]).unwrap_err().contains("-YY"));
    }

    #[test]
    fn every_triangle_letter_is_recorded_by_name() {
        let s = parse_library("prq30a0.1auAcDjevngBPNEIOXzo2YYS5iFlsCQVwW").unwrap();
        let names: Vec<&str> = ALL.iter().map(|(n, _)| *n).collect();
        let mut given = s.given.clone();
        given.sort();
        let mut all = names.clone();
        all.sort();
        assert_eq!(given, all);
        assert!(s.refine && s.user_test && s.jettison && s.voronoi && s.geomview);
        assert!(s.no_boundary_markers && s.no_iteration_numbers && s.ignore_holes);
        assert!(s.no_exact && s.second_order && s.check && s.zero_based);
        assert_eq!(s.max_steiner, Some(5));
        assert!(s.refuse_except(&names).is_ok());
        let e = s.refuse_except(&["p", "q"]).unwrap_err();
        assert!(e.contains("-r") && e.contains("refining"), "{e}");
    }

    #[test]
    fn library_form_takes_no_dash_but_tolerates_one() {
        let s = parse_library("pzq30").unwrap();
        assert!(s.poly && s.zero_based);
        assert_eq!(s.min_angle, Some(30.0));
        assert_eq!(parse_library("-pzq30").unwrap(), s);
        assert_eq!(
            parse_library("-p -zq30").unwrap().given,
            vec!["p", "z", "q"]
        );
        assert_eq!(parse_library("").unwrap(), Switches::default());
        assert!(parse_library("pq-").unwrap_err().contains("'-'"));
        assert!(parse_library("po").unwrap_err().contains("o2"));
        assert!(parse_library("px").unwrap_err().contains("-x"));
    }

    #[test]
    fn unknown_switches_are_errors_naming_them() {
        let e = run(&["-pqx", "f"]).unwrap_err();
        assert!(e.contains("-x") && e.contains("-pqx"), "{e}");
        assert!(run(&["-", "f"]).is_err());
        assert!(run(&["--frobnicate", "f"])
            .unwrap_err()
            .contains("--frobnicate"));
    }

    #[test]
    fn file_count_is_checked_and_help_is_recognised() {
        assert!(run(&["-p"]).unwrap_err().contains("no input file"));
        assert!(run(&["a", "b"]).unwrap_err().contains("more than one"));
        let args = vec!["-p".to_string(), "--help".to_string()];
        assert_eq!(parse_command_line(&args).unwrap(), Parsed::Help);
    }

    #[test]
    fn regional_switches_need_a_pslg() {
        let sw = Switches {
            region_area: true,
            region_attributes: true,
            ..Switches::default()
        };
        let o = sw.options(false);
        assert!(!o.region_max_area && !o.region_attributes);
        let o = sw.options(true);
        assert!(o.region_max_area && o.region_attributes);
    }

    #[test]
    fn output_segments_add_the_open_hull_with_marker_1() {
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            neighbors: vec![[NONE, 1, NONE], [NONE, NONE, 0]],
            segments: vec![[0, 1]],
            segment_markers: vec![7],
            ..TriMesh::default()
        };
        let mut e = output_segments(&mesh);
        assert_eq!(e[0], ([0, 1], 7));
        e.sort();
        assert_eq!(e, vec![([0, 1], 7), ([1, 2], 1), ([2, 3], 1), ([3, 0], 1)]);
    }
}
