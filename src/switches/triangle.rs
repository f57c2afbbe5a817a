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
//!
//! `r` (refine a given mesh) is honoured differently from Triangle, by [`refine_input`]: the
//! given triangles are not refined in place but remeshed. Their boundary edges, the edges
//! between triangles of different attribute or area bound, and the given segments (with `p`)
//! become the segments of a PSLG; every given point is kept at its index; each connected
//! group of triangles with one attribute and one area bound becomes a region (its attribute,
//! and its area bound applied with `a` without a number, as Triangle's `.area` file and
//! `trianglearealist` are), seeded strictly inside one of its triangles (exact orientation
//! tests); every area the given triangles enclose but do not cover gets a hole seed. That PSLG
//! is meshed to the `q`/`a` bounds like any other, so the output has the input's boundary,
//! regions and points, but not its triangles. As in Triangle, the holes and regions of a
//! `.poly` file (or `in->holelist`, `in->regionlist`) play no part with `r`, nor does `c`.

use std::collections::HashMap;

use crate::error::Error;
use crate::input2d::{Pslg, Region};
use crate::mesh2d::{triangulate, Options, TriMesh, NONE};
use crate::predicates::orient2d;

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
        // A mesh to refine has regions (its triangles' attributes and area bounds).
        let poly = poly || self.refine;
        Options {
            min_angle: self.min_angle,
            max_area: self.max_area,
            region_max_area: self.region_area && poly,
            region_attributes: self.region_attributes && poly,
            convex_hull: self.convex_hull,
            max_steiner: self.max_steiner,
            no_boundary_steiner: self.no_boundary_steiner,
            no_segment_steiner: self.no_segment_steiner,
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

/// A mesh given for refinement (`r`), numbered 0-based into the input's points.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GivenMesh {
    /// The triangles (their three corners).
    pub triangles: Vec<[u32; 3]>,
    /// One attribute per triangle, or empty (Triangle's first triangle attribute).
    pub attributes: Vec<f64>,
    /// One maximum area per triangle (0 or less: none), or empty (`.area`,
    /// `trianglearealist`).
    pub max_areas: Vec<f64>,
}

/// A point strictly inside triangle `[a, b, c]` (its rounded centroid, checked exactly), or
/// `None` when rounding put the centroid on or outside an edge (a very thin triangle).
fn inside_point(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<[f64; 2]> {
    let p = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
    let side = orient2d(a, b, c);
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|&(u, v)| orient2d(u, v, p) * side > 0.0);
    inside.then_some(p)
}

/// Labels the connected components of `0..n` under `linked(t, k)` (is item `t` joined to
/// its `k`-th neighbour `next(t, k)`), in order of their first item.
fn components(
    n: usize,
    next: impl Fn(usize, usize) -> u32,
    linked: impl Fn(usize, usize) -> bool,
) -> Vec<Vec<usize>> {
    let mut seen = vec![false; n];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for s in 0..n {
        if seen[s] {
            continue;
        }
        seen[s] = true;
        stack.push(s);
        let mut comp = Vec::new();
        while let Some(t) = stack.pop() {
            comp.push(t);
            for k in 0..3 {
                let u = next(t, k);
                if u != NONE && linked(t, k) && !seen[u as usize] {
                    seen[u as usize] = true;
                    stack.push(u as usize);
                }
            }
        }
        out.push(comp);
    }
    out
}

/// A point strictly inside one of the triangles `comp` of `tris` over `pts`.
fn seed_of(pts: &[[f64; 2]], tris: &[[u32; 3]], comp: &[usize]) -> Option<[f64; 2]> {
    comp.iter().find_map(|&t| {
        let [a, b, c] = tris[t].map(|v| pts[v as usize]);
        inside_point(a, b, c)
    })
}

/// The PSLG that remeshes `given` (Triangle's `r`; see the module docs): `input`'s points and
/// markers, its segments (with `p`; markers default to 1) followed by the given mesh's
/// boundary edges (marker 1) and the edges between its groups (marker 0), a region per
/// connected group of triangles (when they have attributes, or area bounds and `use_areas`),
/// and hole seeds where the given triangles leave an enclosed area uncovered. Messages number
/// items from `base`, as the caller's input does. Mesh the result with the switches' options,
/// plus `region_attributes` when the given triangles have attributes.
pub fn refine_input(
    input: &Pslg,
    given: &GivenMesh,
    use_areas: bool,
    base: u32,
) -> Result<Pslg, Error> {
    let bad = |m: String| Error::InvalidOption(format!("-r: {m}"));
    let pts = &input.points;
    let (n, nt) = (pts.len(), given.triangles.len());
    if nt == 0 {
        return Err(bad(
            "no triangles given to refine (.ele file or trianglelist)".into(),
        ));
    }
    if nt >= NONE as usize {
        return Err(bad(format!(
            "{nt} triangles is more than this build supports"
        )));
    }
    let b = base as u64;
    for (t, tri) in given.triangles.iter().enumerate() {
        if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
            return Err(bad(format!(
                "triangle {} has corner {}, but the points are numbered {b} to {}",
                t as u64 + b,
                v as u64 + b,
                n as i64 - 1 + b as i64
            )));
        }
        let [p, q, r] = tri.map(|v| pts[v as usize]);
        if orient2d(p, q, r) == 0.0 {
            return Err(bad(format!(
                "triangle {} is degenerate: its corners lie on one line",
                t as u64 + b
            )));
        }
    }
    for (what, len) in [
        ("attributes", given.attributes.len()),
        ("area bounds", given.max_areas.len()),
    ] {
        if len != 0 && len != nt {
            return Err(bad(format!("{len} triangle {what} for {nt} triangles")));
        }
    }
    if let Some(t) = given.attributes.iter().position(|a| !a.is_finite()) {
        return Err(bad(format!(
            "triangle {} has a non-finite attribute",
            t as u64 + b
        )));
    }
    if let Some(t) = given.max_areas.iter().position(|a| a.is_nan()) {
        return Err(bad(format!(
            "triangle {} has a NaN area bound",
            t as u64 + b
        )));
    }
    let attr = |t: usize| given.attributes.get(t).copied().unwrap_or(0.0);
    let area = |t: usize| match given.max_areas.get(t) {
        Some(&a) if use_areas && a > 0.0 => Some(a),
        _ => None,
    };
    let group = |t: usize| ((attr(t) + 0.0).to_bits(), area(t).map(f64::to_bits));
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let edge = |t: usize, i: usize| {
        let tri = given.triangles[t];
        (tri[(i + 1) % 3], tri[(i + 2) % 3])
    };

    // Edge-to-edge adjacency: nb[t][i] is the triangle across the edge opposite corner i.
    let mut nb = vec![[NONE; 3]; nt];
    let mut first: HashMap<(u32, u32), (u32, usize, bool)> = HashMap::with_capacity(2 * nt);
    for t in 0..nt {
        for i in 0..3 {
            let (a, c) = edge(t, i);
            match first.get_mut(&key(a, c)) {
                Some((_, _, true)) => {
                    return Err(bad(format!(
                        "the edge {} {} is shared by more than two triangles",
                        a as u64 + b,
                        c as u64 + b
                    )))
                }
                Some((u, j, paired)) => {
                    *paired = true;
                    nb[*u as usize][*j] = t as u32;
                    nb[t][i] = *u;
                }
                None => {
                    first.insert(key(a, c), (t as u32, i, false));
                }
            }
        }
    }
    drop(first);

    // Segments: the given ones, then the walls the given mesh adds.
    let mut segments = input.segments.clone();
    let mut segment_markers = if input.segment_markers.is_empty() {
        vec![1; segments.len()]
    } else {
        input.segment_markers.clone()
    };
    let known: std::collections::HashSet<(u32, u32)> =
        input.segments.iter().map(|s| key(s[0], s[1])).collect();
    let wall = |t: usize, i: usize| {
        let u = nb[t][i];
        let (a, c) = edge(t, i);
        u == NONE || group(u as usize) != group(t) || known.contains(&key(a, c))
    };
    for (t, across) in nb.iter().enumerate() {
        for (i, &u) in across.iter().enumerate() {
            let (a, c) = edge(t, i);
            // Each edge once: from the triangle with the smaller index (or the only one).
            if wall(t, i) && (u == NONE || u as usize > t) && !known.contains(&key(a, c)) {
                segments.push([a, c]);
                segment_markers.push(i32::from(u == NONE));
            }
        }
    }

    let tris = &given.triangles;
    let no_seed = |t: usize| {
        bad(format!(
            "no point strictly inside triangle {} or its neighbours could be found in floating \
             point",
            t as u64 + b
        ))
    };
    let mut regions = Vec::new();
    if !given.attributes.is_empty() || given.max_areas.iter().any(|&a| use_areas && a > 0.0) {
        for comp in components(nt, |t, k| nb[t][k], |t, k| !wall(t, k)) {
            let t = comp[0];
            regions.push(Region {
                point: seed_of(pts, tris, &comp).ok_or_else(|| no_seed(t))?,
                attribute: attr(t),
                max_area: area(t),
            });
        }
    }

    // Holes: the constrained Delaunay triangulation of the points and the boundary edges
    // (no Steiner point), its triangles covered by the given mesh found by flooding from one
    // seed per connected piece of the given mesh; every uncovered piece that does not reach
    // the convex hull is enclosed, and gets a hole seed.
    let mut cover = Pslg {
        points: pts.clone(),
        ..Pslg::default()
    };
    for (t, across) in nb.iter().enumerate() {
        for (i, &u) in across.iter().enumerate() {
            if u == NONE {
                let (a, c) = edge(t, i);
                cover.segments.push([a, c]);
            }
        }
    }
    for comp in components(nt, |t, k| nb[t][k], |_, _| true) {
        cover.regions.push(Region {
            point: seed_of(pts, tris, &comp).ok_or_else(|| no_seed(comp[0]))?,
            attribute: 1.0,
            max_area: None,
        });
    }
    let opts = Options {
        convex_hull: true,
        no_segment_steiner: true,
        region_attributes: true,
        ..Options::default()
    };
    let cdt = triangulate(&cover, &opts).map_err(|e| {
        bad(format!(
            "the given triangles do not form a valid mesh (their boundary edges: {e})"
        ))
    })?;
    let fixed: std::collections::HashSet<(u32, u32)> =
        cdt.segments.iter().map(|s| key(s[0], s[1])).collect();
    let covered = |t: usize| cdt.triangle_attributes[t] == 1.0;
    let ct = cdt.triangles.len();
    // Uncovered triangles are joined to uncovered neighbours only.
    let cnb = |t: usize, k: usize| {
        let u = cdt.neighbors[t][k];
        if covered(t) || (u != NONE && covered(u as usize)) {
            NONE
        } else {
            u
        }
    };
    let open = |t: usize, k: usize| {
        let tri = cdt.triangles[t];
        !fixed.contains(&key(tri[(k + 1) % 3], tri[(k + 2) % 3]))
    };
    let mut holes = Vec::new();
    for comp in components(ct, cnb, open) {
        let t = comp[0];
        if covered(t) || comp.iter().any(|&u| cdt.neighbors[u].contains(&NONE)) {
            continue;
        }
        holes.push(
            seed_of(&cdt.vertices, &cdt.triangles, &comp).ok_or_else(|| {
                bad("no point strictly inside an uncovered area could be found".into())
            })?,
        );
    }
    Ok(Pslg {
        points: pts.clone(),
        point_markers: input.point_markers.clone(),
        segments,
        segment_markers,
        holes,
        regions,
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

    /// A unit square with a square hole (0.3..0.7) and a segment at x = 0.15 splitting off a
    /// strip, regions with attributes 1 (strip) and 2 (the rest), meshed to `a0.01`.
    fn given_square_with_hole() -> (Pslg, TriMesh) {
        let mut p = Pslg {
            points: vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [1.0, 1.0],
                [0.0, 1.0],
                [0.3, 0.3],
                [0.7, 0.3],
                [0.7, 0.7],
                [0.3, 0.7],
                [0.15, 0.0],
                [0.15, 1.0],
            ],
            holes: vec![[0.5, 0.5]],
            ..Pslg::default()
        };
        p.segments = vec![
            [0, 8],
            [8, 1],
            [1, 2],
            [2, 9],
            [9, 3],
            [3, 0],
            [4, 5],
            [5, 6],
            [6, 7],
            [7, 4],
            [8, 9],
        ];
        p.regions = vec![
            Region {
                point: [0.05, 0.5],
                attribute: 1.0,
                max_area: None,
            },
            Region {
                point: [0.9, 0.5],
                attribute: 2.0,
                max_area: None,
            },
        ];
        let opts = Options {
            min_angle: Some(30.0),
            max_area: Some(0.01),
            region_attributes: true,
            ..Options::default()
        };
        let m = triangulate(&p, &opts).unwrap();
        m.validate().unwrap();
        (p, m)
    }

    fn area_by_attribute(m: &TriMesh) -> HashMap<u64, f64> {
        let mut out = HashMap::new();
        for (t, tri) in m.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|v| m.vertices[v as usize]);
            *out.entry(m.triangle_attributes[t].to_bits()).or_insert(0.0) +=
                0.5 * crate::geometry::area2(a, b, c);
        }
        out
    }

    fn given_of(m: &TriMesh) -> (Pslg, GivenMesh) {
        let input = Pslg {
            points: m.vertices.clone(),
            point_markers: m.vertex_markers.clone(),
            ..Pslg::default()
        };
        let given = GivenMesh {
            triangles: m.triangles.clone(),
            attributes: m.triangle_attributes.clone(),
            max_areas: Vec::new(),
        };
        (input, given)
    }

    #[test]
    fn a_given_mesh_is_remeshed_with_its_boundary_regions_and_points() {
        let (_, m0) = given_square_with_hole();
        let (input, given) = given_of(&m0);
        let p = refine_input(&input, &given, false, 0).unwrap();
        assert_eq!(p.holes.len(), 1, "the uncovered square is a hole");
        assert!(p.holes[0].iter().all(|x| (0.3..0.7).contains(x)));
        assert_eq!(p.regions.len(), 2, "one region per attribute");
        // Boundary edges get marker 1, the edges between the two attributes marker 0.
        let interface = p
            .segments
            .iter()
            .zip(&p.segment_markers)
            .filter(|(_, &k)| k == 0);
        assert!(interface.clone().count() >= 1);
        for (s, _) in interface {
            assert!(s.iter().all(|&v| p.points[v as usize][0] == 0.15));
        }
        let sw = parse_library("rq30a0.001").unwrap();
        let mut opts = sw.options(false);
        opts.region_attributes = true;
        let m1 = triangulate(&p, &opts).unwrap();
        m1.validate().unwrap();
        assert!(m1.triangles.len() > 4 * m0.triangles.len());
        assert_eq!(m1.vertices[..m0.vertices.len()], m0.vertices[..]);
        assert_eq!(
            m1.vertex_markers[..m0.vertices.len()],
            m0.vertex_markers[..]
        );
        let (a0, a1) = (area_by_attribute(&m0), area_by_attribute(&m1));
        assert_eq!(a0.len(), 2);
        for (k, v) in &a0 {
            assert!((a1[k] - v).abs() < 1e-12, "{k}: {} != {v}", a1[k]);
        }
        assert!((a0[&1f64.to_bits()] - 0.15).abs() < 1e-12);
    }

    #[test]
    fn per_triangle_area_bounds_refine_only_where_small() {
        let (_, m0) = given_square_with_hole();
        let (input, mut given) = given_of(&m0);
        let centroid_x = |m: &TriMesh, t: usize| {
            m.triangles[t]
                .iter()
                .map(|&v| m.vertices[v as usize][0])
                .sum::<f64>()
                / 3.0
        };
        let small: Vec<bool> = (0..m0.triangles.len())
            .map(|t| centroid_x(&m0, t) > 0.7)
            .collect();
        given.max_areas = small
            .iter()
            .map(|&s| if s { 0.0005 } else { -1.0 })
            .collect();
        // The attributes tell the two parts apart in the output.
        given.attributes = small.iter().map(|&s| f64::from(u8::from(s))).collect();
        let sw = parse_library("ra").unwrap();
        let p = refine_input(&input, &given, sw.region_area, 0).unwrap();
        let mut opts = sw.options(false);
        opts.region_attributes = true;
        let m1 = triangulate(&p, &opts).unwrap();
        m1.validate().unwrap();
        let area = |m: &TriMesh, t: usize| {
            let [a, b, c] = m.triangles[t].map(|v| m.vertices[v as usize]);
            0.5 * crate::geometry::area2(a, b, c)
        };
        let (mut right, mut right_area, mut left) = (0, 0.0, 0.0f64);
        for t in 0..m1.triangles.len() {
            if m1.triangle_attributes[t] == 1.0 {
                assert!(area(&m1, t) <= 0.0005);
                right += 1;
                right_area += area(&m1, t);
            } else {
                left = left.max(area(&m1, t));
            }
        }
        assert!(
            right as f64 >= right_area / 0.0005 && right_area > 0.1,
            "{right} small triangles"
        );
        assert!(left > 0.002, "the unbounded part stays coarse: {left}");
        given.attributes.clear();
        // Without `a` the bounds play no part: no Steiner point at all.
        let p = refine_input(&input, &given, false, 0).unwrap();
        assert!(p.regions.is_empty());
        let m2 = triangulate(&p, &Options::default()).unwrap();
        assert_eq!(m2.steiner_points, 0);
        assert_eq!(m2.triangles.len(), m0.triangles.len());
    }

    #[test]
    fn bad_given_meshes_are_errors_naming_the_item() {
        let (_, m0) = given_square_with_hole();
        let (input, given) = given_of(&m0);
        let n = input.points.len() as u32;
        let mut g = given.clone();
        g.triangles[3][1] = n;
        let e = refine_input(&input, &g, false, 1).unwrap_err().to_string();
        assert!(
            e.contains("triangle 4") && e.contains(&format!("corner {}", n + 1)),
            "{e}"
        );
        let mut g = given.clone();
        g.triangles.push(g.triangles[0]);
        g.attributes.push(1.0);
        let e = refine_input(&input, &g, false, 0).unwrap_err().to_string();
        assert!(e.contains("more than two triangles"), "{e}");
        let mut g = given.clone();
        g.attributes.pop();
        let e = refine_input(&input, &g, false, 0).unwrap_err().to_string();
        assert!(e.contains("attributes for"), "{e}");
        let mut g = given.clone();
        g.triangles[0] = [0, 8, 1];
        let e = refine_input(&input, &g, false, 0).unwrap_err().to_string();
        assert!(e.contains("triangle 0 is degenerate"), "{e}");
        let e = refine_input(&input, &GivenMesh::default(), false, 0).unwrap_err();
        assert!(e.to_string().contains("no triangles"), "{e}");
    }

    #[test]
    fn yy_keeps_every_segment_whole() {
        // The points of a mesh of the domain (some of them on the segments) with the domain's
        // segments: refinement points away from the segments are possible.
        let (mut p, m0) = given_square_with_hole();
        p.points = m0.vertices.clone();
        let n = p.points.len() as u32;
        let sw = parse_library("pq30a0.002YY").unwrap();
        let m = triangulate(&p, &sw.options(true)).unwrap();
        m.validate_constrained().unwrap();
        assert!(
            m.segments.iter().flatten().all(|&v| v < n),
            "a segment was split"
        );
        assert!(m.steiner_points > 50, "{} Steiner points", m.steiner_points);
        let one_y = triangulate(&p, &parse_library("pq30a0.002Y").unwrap().options(true));
        let one_y = one_y.unwrap();
        one_y.validate_constrained().unwrap();
        assert!(
            one_y.segments.iter().flatten().any(|&v| v >= n),
            "-Y splits the interior segment x = 0.15"
        );
    }
}
