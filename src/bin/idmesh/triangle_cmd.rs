//! `idmesh triangle`: Triangle's command line on top of the 2D mesher.

use std::fs::File;
use std::io::{self, Write};
use std::time::{Duration, Instant};

use idmesh::io::triangle::{
    read_node, read_poly, write_edge, write_ele, write_neigh, write_node, write_poly,
    write_poly_segments, TriangleInput,
};
use idmesh::{triangulate, Error, InputError, Options, TriMesh, NONE};

use crate::names::{self, Files};
use crate::switches::{self, Parsed, Switches};

/// The help text of `idmesh triangle --help`.
pub const HELP: &str = "\
idmesh triangle: quality conforming Delaunay triangulation, with Triangle's command line.

Usage: idmesh triangle [-SWITCHES] FILE

FILE is FILE.node (a point set) or, with -p or a .poly extension, FILE.poly (a planar
straight-line graph). Outputs are FILE.1.node and FILE.1.ele (FILE.2.* for FILE.1, ...),
FILE.1.poly with -p (or -c), FILE.1.edge with -e, FILE.1.neigh with -n. Numbering follows the
input (0 or 1), or starts at 0 with -z.

Switches are letters that may be grouped, e.g. -pq30a0.01V:
  -p          read FILE.poly (segments, holes, regional attributes and area bounds)
  -q[ANGLE]   minimum angle in degrees (default 20; above about 34 it may not terminate)
  -a[AREA]    with a number: maximum triangle area; without: the .poly file's regional bounds
  -A          write each triangle's regional attribute to the .ele file
  -c          mesh the convex hull of the input, not only the area enclosed by segments
  -D          conforming Delaunay (accepted; idmesh output always is, except with -Y)
  -Y          no Steiner points on boundary segments (those with the domain on one side):
              the mesh is then constrained Delaunay, and triangles whose new vertex would
              encroach such a segment keep their bad angle or size, as in Triangle
  -S[N]       at most N Steiner points (-S alone: none); a warning is printed if reached
  -z          number output items from 0
  -e          write an .edge file      -n   write a .neigh file
  -N -E -P    do not write the .node / .ele / .poly file
  -Q          quiet: print only errors and warnings
  -V          verbose: print counts, angle range and timings
Numbers take digits and dots only (no exponents), exactly as in Triangle.
";

/// Runs `idmesh triangle ARGS`.
pub fn main(args: &[String]) -> Result<(), String> {
    match switches::parse(args)? {
        Parsed::Help => {
            print!("{HELP}");
            Ok(())
        }
        Parsed::Run { switches, file } => run(&switches, &file),
    }
}

/// Says something unless `-Q`.
fn say(sw: &Switches, text: std::fmt::Arguments<'_>) {
    if !sw.quiet {
        println!("{text}");
    }
}

fn run(sw: &Switches, file: &str) -> Result<(), String> {
    let files = names::resolve(file, sw.poly);
    let start = Instant::now();
    say(sw, format_args!("Opening {}.", files.input));
    let path = std::path::Path::new(&files.input);
    let input = if files.poly {
        read_poly(path)
    } else {
        read_node(path)
    };
    let input = input.map_err(|e| e.to_string())?;
    let read_time = start.elapsed();

    let opts = options(sw, files.poly);
    let mesh_start = Instant::now();
    let mesh = triangulate(&input.pslg, &opts).map_err(|e| describe(&e, &input, &files.input))?;
    let mesh_time = mesh_start.elapsed();
    if !mesh.complete {
        // Printed even with -Q: the files are written but miss the requested bounds.
        eprintln!(
            "idmesh: warning: the Steiner point limit ({}) was reached; some triangles do not \
             meet the quality bounds",
            sw.max_steiner.unwrap_or(0)
        );
    }

    let write_start = Instant::now();
    let base = if sw.zero_based { 0 } else { input.base };
    write_outputs(sw, &files, &input, &mesh, base)?;
    let write_time = write_start.elapsed();
    if sw.verbose && !sw.quiet {
        statistics(&input, &mesh, [read_time, mesh_time, write_time]);
    }
    Ok(())
}

/// Maps the switches to mesher options. Regional switches need a `.poly` file, as in Triangle.
fn options(sw: &Switches, poly: bool) -> Options {
    Options {
        min_angle: sw.min_angle,
        max_area: sw.max_area,
        region_max_area: sw.region_area && poly,
        region_attributes: sw.region_attributes && poly,
        convex_hull: sw.convex_hull,
        max_steiner: sw.max_steiner,
        no_boundary_steiner: sw.no_boundary_steiner,
        verbose: sw.verbose && !sw.quiet,
        ..Options::default()
    }
}

/// A one-line message for a mesher error, with item numbers as in the input file.
fn describe(e: &Error, input: &TriangleInput, file: &str) -> String {
    match e {
        Error::Input(ie) => {
            format!(
                "{file}: invalid input: {}",
                renumber(ie, input.base as usize)
            )
        }
        other => format!("{file}: {other}"),
    }
}

/// Shifts the 0-based indices of an input error to the file's numbering.
fn renumber(e: &InputError, base: usize) -> InputError {
    use InputError::*;
    let b = base;
    match e.clone() {
        NonFinitePoint { point } => NonFinitePoint { point: point + b },
        DuplicatePoint { first, second } => DuplicatePoint {
            first: first + b,
            second: second + b,
        },
        SegmentIndexOutOfRange {
            segment,
            index,
            num_points,
        } => SegmentIndexOutOfRange {
            segment: segment + b,
            index: index + b as u64,
            num_points,
        },
        ZeroLengthSegment { segment } => ZeroLengthSegment {
            segment: segment + b,
        },
        DuplicateSegment { first, second } => DuplicateSegment {
            first: first + b,
            second: second + b,
        },
        CrossingSegments { first, second } => CrossingSegments {
            first: first + b,
            second: second + b,
        },
        NonFiniteHole { hole } => NonFiniteHole { hole: hole + b },
        HoleOutsideDomain { hole } => HoleOutsideDomain { hole: hole + b },
        NonFiniteRegion { region } => NonFiniteRegion { region: region + b },
        RegionOutsideDomain { region } => RegionOutsideDomain { region: region + b },
        CoordinateTooLarge { point } => CoordinateTooLarge { point: point + b },
        other => other,
    }
}

/// Creates `name` and writes it with `write`; errors name the file.
fn write_file(
    sw: &Switches,
    name: &str,
    write: impl FnOnce(&mut File) -> io::Result<()>,
) -> Result<(), String> {
    say(sw, format_args!("Writing {name}."));
    let mut f = File::create(name).map_err(|e| format!("cannot create {name}: {e}"))?;
    write(&mut f)
        .and_then(|()| f.flush())
        .map_err(|e| format!("cannot write {name}: {e}"))
}

fn write_outputs(
    sw: &Switches,
    files: &Files,
    input: &TriangleInput,
    mesh: &TriMesh,
    base: u32,
) -> Result<(), String> {
    if !sw.no_node {
        write_file(sw, &files.output("node"), |f| write_node(f, mesh, base))?;
    }
    if !sw.no_ele {
        write_file(sw, &files.output("ele"), |f| write_ele(f, mesh, base))?;
    }
    if !sw.no_poly && (files.poly || sw.convex_hull) {
        let (holes, regions) = (&input.pslg.holes, &input.pslg.regions);
        if files.poly {
            write_file(sw, &files.output("poly"), |f| {
                write_poly(f, mesh, base, holes, regions)
            })?;
        } else {
            // A point set meshed with -c: Triangle writes its convex hull edges.
            let hull = boundary_edges(mesh);
            write_file(sw, &files.output("poly"), |f| {
                write_poly_segments(f, &hull, &[], base, holes, regions)
            })?;
        }
    }
    if sw.edges {
        write_file(sw, &files.output("edge"), |f| write_edge(f, mesh, base))?;
    }
    if sw.neighbors {
        write_file(sw, &files.output("neigh"), |f| write_neigh(f, mesh, base))?;
    }
    Ok(())
}

/// The edges with no triangle on one side, oriented with the mesh on their left.
fn boundary_edges(mesh: &TriMesh) -> Vec<[u32; 2]> {
    let mut out = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for i in 0..3 {
            if mesh.neighbors.get(t).is_some_and(|n| n[i] == NONE) {
                out.push([tri[(i + 1) % 3], tri[(i + 2) % 3]]);
            }
        }
    }
    out
}

fn statistics(input: &TriangleInput, mesh: &TriMesh, [read, meshing, write]: [Duration; 3]) {
    let p = &input.pslg;
    let (lo, hi) = mesh.angle_range();
    println!();
    println!(
        "Input: {} points, {} segments, {} holes, {} regions.",
        p.points.len(),
        p.segments.len(),
        p.holes.len(),
        p.regions.len()
    );
    println!(
        "Mesh: {} vertices ({} Steiner points), {} triangles, {} subsegments.",
        mesh.vertices.len(),
        mesh.steiner_points,
        mesh.triangles.len(),
        mesh.segments.len()
    );
    if mesh.triangles.is_empty() {
        println!("Angles: no triangles.");
    } else {
        println!("Angles: smallest {lo:.4} degrees, largest {hi:.4} degrees.");
    }
    println!("Area: {}.", mesh.area());
    println!(
        "Time: reading {:.3} s, meshing {:.3} s, writing {:.3} s.",
        read.as_secs_f64(),
        meshing.as_secs_f64(),
        write.as_secs_f64()
    );
    if !mesh.complete {
        println!("The Steiner point limit was reached: the mesh is incomplete.");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renumber_shifts_every_index_but_counts() {
        let e = renumber(
            &InputError::CrossingSegments {
                first: 0,
                second: 4,
            },
            1,
        );
        assert_eq!(
            e,
            InputError::CrossingSegments {
                first: 1,
                second: 5
            }
        );
        let e = renumber(
            &InputError::SegmentIndexOutOfRange {
                segment: 2,
                index: 9,
                num_points: 9,
            },
            1,
        );
        assert_eq!(
            e,
            InputError::SegmentIndexOutOfRange {
                segment: 3,
                index: 10,
                num_points: 9
            }
        );
        let e = renumber(&InputError::TooFewPoints { count: 2 }, 1);
        assert_eq!(e, InputError::TooFewPoints { count: 2 });
    }

    #[test]
    fn regional_switches_need_a_poly_file() {
        let sw = Switches {
            region_area: true,
            region_attributes: true,
            ..Switches::default()
        };
        let o = options(&sw, false);
        assert!(!o.region_max_area && !o.region_attributes);
        let o = options(&sw, true);
        assert!(o.region_max_area && o.region_attributes);
    }

    #[test]
    fn boundary_edges_of_two_triangles() {
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            neighbors: vec![[NONE, 1, NONE], [NONE, NONE, 0]],
            ..TriMesh::default()
        };
        let mut e = boundary_edges(&mesh);
        e.sort();
        assert_eq!(e, vec![[0, 1], [1, 2], [2, 3], [3, 0]]);
    }
}
