//! Triangle-style command line parsing for `idmesh triangle`.
//!
//! Switches are letters concatenated in one or more arguments starting with `-` (`-pq30a0.1V`
//! or `-p -q30 -a0.1 -V`), in any order relative to the file name. Numbers after `q`, `a` and
//! `S` are read exactly as Triangle reads them: the longest run of digits and dots (digits only
//! for `S`), converted like `strtod` would, so `-a1e-5` means "a1, then switch e, then ...".
//! Every letter Triangle accepts but idmesh does not implement is an error naming it, never
//! silently ignored.

/// The parsed switches. Field comments give the letter.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Switches {
    /// `p`: read a `.poly` file (also implied by a `.poly` file name, as in Triangle).
    pub poly: bool,
    /// `q[angle]`: minimum angle in degrees (`q` alone is 20; `q0` means no angle bound).
    pub min_angle: Option<f64>,
    /// `a<area>`: global maximum triangle area.
    pub max_area: Option<f64>,
    /// `a` without a number: apply the regional area bounds of the `.poly` file.
    pub region_area: bool,
    /// `A`: write regional attributes to the `.ele` file.
    pub region_attributes: bool,
    /// `D`: conforming Delaunay. Accepted for compatibility; idmesh output always is (unless
    /// `Y` is given).
    pub conforming_delaunay: bool,
    /// `Y`: no Steiner points on boundary segments (constrained Delaunay output).
    pub no_boundary_steiner: bool,
    /// `S[n]`: at most `n` Steiner points (`S` alone is 0, as in Triangle).
    pub max_steiner: Option<u64>,
    /// `c`: mesh the convex hull.
    pub convex_hull: bool,
    /// `z`: number output items from 0.
    pub zero_based: bool,
    /// `e`: write an `.edge` file.
    pub edges: bool,
    /// `n`: write a `.neigh` file.
    pub neighbors: bool,
    /// `N`: do not write the `.node` file.
    pub no_node: bool,
    /// `E`: do not write the `.ele` file.
    pub no_ele: bool,
    /// `P`: do not write the `.poly` file.
    pub no_poly: bool,
    /// `Q`: print nothing but errors and warnings.
    pub quiet: bool,
    /// `V`: print statistics.
    pub verbose: bool,
}

/// What the command line asks for.
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

/// Triangle switches that idmesh recognises but does not implement, with what they do.
fn unsupported(c: char) -> Option<&'static str> {
    Some(match c {
        'r' => "refining a previous mesh",
        'u' => "a user-defined sizing test (use the library's SizingFn)",
        'j' => "jettisoning unused vertices",
        'v' => "Voronoi diagram output",
        'g' => "Geomview output",
        'B' => "leaving out boundary markers",
        'I' => "leaving out iteration numbers",
        'O' => "ignoring holes",
        'X' => "disabling exact arithmetic",
        'o' => "second-order triangles",
        'i' | 'F' | 'l' => "choosing the triangulation algorithm",
        's' => "splitting segments instead of conforming",
        'C' => "the consistency check",
        'w' | 'W' => "weighted Delaunay triangulations",
        'L' => "the old name of -D (use -D)",
        'h' => "help inside a switch group (use --help)",
        _ => return None,
    })
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

/// Applies one switch group such as `-pq30a0.1V`.
fn parse_group(arg: &str, sw: &mut Switches, y_count: &mut u32) -> Result<(), String> {
    let chars: Vec<char> = arg.chars().skip(1).collect();
    if chars.is_empty() {
        return Err("empty switch '-'".into());
    }
    let mut j = 0;
    while j < chars.len() {
        match chars[j] {
            'p' => sw.poly = true,
            'q' => {
                let angle = number_after(&chars, &mut j).unwrap_or(20.0);
                sw.min_angle = (angle != 0.0).then_some(angle);
            }
            'a' => match number_after(&chars, &mut j) {
                Some(area) if area > 0.0 => sw.max_area = Some(area),
                Some(_) => return Err("-a: the maximum area must be greater than zero".into()),
                None => sw.region_area = true,
            },
            'A' => sw.region_attributes = true,
            'D' => sw.conforming_delaunay = true,
            'Y' => {
                *y_count += 1;
                if *y_count > 1 {
                    return Err(
                        "-YY (no Steiner points on any segment) is not supported yet; -Y is".into(),
                    );
                }
                sw.no_boundary_steiner = true;
            }
            'S' => sw.max_steiner = Some(digits_after(&chars, &mut j)?),
            'c' => sw.convex_hull = true,
            'z' => sw.zero_based = true,
            'e' => sw.edges = true,
            'n' => sw.neighbors = true,
            'N' => sw.no_node = true,
            'E' => sw.no_ele = true,
            'P' => sw.no_poly = true,
            'Q' => sw.quiet = true,
            'V' => sw.verbose = true,
            c if c.is_ascii_digit() || "+-.".contains(c) => {
                return Err(format!(
                    "unexpected '{c}' in '{arg}': only q, a and S take numbers, written with \
                     digits and dots (no exponents)"
                ))
            }
            c => {
                return Err(match unsupported(c) {
                    Some(what) => format!("switch -{c} ({what}) is not supported (in '{arg}')"),
                    None => {
                        format!("unknown switch -{c} (in '{arg}'); try 'idmesh triangle --help'")
                    }
                })
            }
        }
        j += 1;
    }
    Ok(())
}

/// Parses the arguments after `idmesh triangle`.
pub fn parse(args: &[String]) -> Result<Parsed, String> {
    let mut sw = Switches::default();
    let mut file: Option<&String> = None;
    let mut y_count = 0;
    for arg in args {
        if arg == "--help" || arg == "-h" {
            return Ok(Parsed::Help);
        } else if arg.starts_with("--") {
            return Err(format!(
                "unknown option '{arg}'; try 'idmesh triangle --help'"
            ));
        } else if arg.starts_with('-') {
            parse_group(arg, &mut sw, &mut y_count)?;
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
        None => Err("no input file given; try 'idmesh triangle --help'".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(args: &[&str]) -> Result<(Switches, String), String> {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        match parse(&args)? {
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
        assert!(s.no_boundary_steiner);
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
        assert!(run(&["-YY", "f"]).unwrap_err().contains("-YY"));
    }

    #[test]
    fn unknown_and_unsupported_switches_are_errors_naming_them() {
        let e = run(&["-pqx", "f"]).unwrap_err();
        assert!(e.contains("-x") && e.contains("-pqx"), "{e}");
        let e = run(&["-pr", "f"]).unwrap_err();
        assert!(e.contains("-r") && e.contains("not supported"), "{e}");
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
        assert_eq!(parse(&args).unwrap(), Parsed::Help);
    }
}
