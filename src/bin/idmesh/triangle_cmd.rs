//! `idmesh triangle`: Triangle's command line on top of the 2D mesher.

use idmesh::io::exchange::{self, MeshView};
use std::fs::File;
use std::io::{self, Write};
use std::time::{Duration, Instant};

use idmesh::io::triangle::{
    read_area, read_ele, read_node, read_poly, write_edge, write_ele, write_neigh,
    write_node_attributes, write_poly, write_poly_segments, TriangleInput,
};
use idmesh::mesh2d::interpolate_point_attributes;
use idmesh::switches::triangle::{
    output_segments, parse_command_line, refine_input, GivenMesh, Parsed, Switches,
};
use idmesh::{triangulate, Error, InputError, TriMesh};

use crate::names::{self, Files};
use crate::progress_ui::{catch_interrupt, check_interrupt, Outputs, Progress};

/// The switches `idmesh triangle` honours; the others Triangle knows are refused by name.
const HONOURED: &[&str] = &[
    "p", "r", "q", "a", "A", "c", "D", "Y", "YY", "S", "z", "e", "n", "N", "E", "P", "Q", "V",
];

/// The help text of `idmesh triangle --help`.
pub const HELP: &str = "\
idmesh triangle: quality conforming Delaunay triangulation, with Triangle's command line.

Usage: idmesh triangle [-SWITCHES] FILE

FILE is FILE.node (a point set) or, with -p or a .poly extension, FILE.poly (a planar
straight-line graph). Outputs are FILE.1.node and FILE.1.ele (FILE.2.* for FILE.1, ...),
FILE.1.poly with -p (or -c), FILE.1.edge with -e, FILE.1.neigh with -n. Numbering follows the
input (0 or 1), or starts at 0 with -z. Point attributes of the input are written, kept at
input points and interpolated linearly at Steiner points.

Switches are letters that may be grouped, e.g. -pq30a0.01V:
  -p          read FILE.poly (segments, holes, regional attributes and area bounds)
  -r          remesh a previous mesh: read FILE.node and FILE.ele (with -p the segments of
              FILE.poly, with -a without a number the per-triangle bounds of FILE.area);
              its boundary, its points (same numbers), its triangle attributes and area
              bounds (as regions) are kept, its triangles are remeshed, not refined in place
  -q[ANGLE]   minimum angle in degrees (default 20; above about 34 it may not terminate)
  -a[AREA]    with a number: maximum triangle area; without: the .poly file's regional bounds
              (with -r: the .area file's)
  -A          write each triangle's regional attribute to the .ele file
  -c          mesh the convex hull of the input, not only the area enclosed by segments
  -D          conforming Delaunay (accepted; idmesh output always is, except with -Y)
  -Y          no Steiner points on boundary segments (those with the domain on one side):
              the mesh is then constrained Delaunay, and triangles whose new vertex would
              encroach such a segment keep their bad angle or size, as in Triangle
  -YY         no Steiner points on any segment, interior ones too (same consequences)
  -S[N]       at most N Steiner points (-S alone: none); a warning is printed if reached
  -z          number output items from 0
  -e          write an .edge file      -n   write a .neigh file
  -N -E -P    do not write the .node / .ele / .poly file
  -Q          quiet: print only errors and warnings
  -V          verbose: print counts, angle range and timings
  --format F  also write FILE.1.F: vtk (legacy VTK), vtu (VTK XML), msh (Gmsh 4.1), mesh (Medit)
Numbers take digits and dots only (no exponents), exactly as in Triangle.
";

/// Runs `idmesh triangle ARGS`.
pub fn main(args: &[String]) -> Result<(), String> {
    let hint = |e: String| format!("{e}; try 'idmesh triangle --help'");
    match parse_command_line(args).map_err(hint)? {
        Parsed::Help => {
            print!("{HELP}");
            Ok(())
        }
        Parsed::Run { switches, file } => {
            switches.refuse_except(HONOURED)?;
            run(&switches, &file)
        }
    }
}

/// Says something unless `-Q`.
fn say(sw: &Switches, text: std::fmt::Arguments<'_>) {
    if !sw.quiet {
        println!("{text}");
    }
}

fn run(sw: &Switches, file: &str) -> Result<(), String> {
    let mut files = names::resolve(file, sw.poly);
    let refined;
    let sw = if sw.refine {
        // With -r, FILE.node and FILE.ele are read (and FILE.poly's segments with -p); -c
        // does nothing, as in Triangle.
        files.poly = sw.poly;
        if let Some(stem) = files.input.strip_suffix(".poly") {
            files.input = format!("{stem}.node");
        }
        refined = Switches {
            convex_hull: false,
            ..sw.clone()
        };
        &refined
    } else {
        sw
    };
    catch_interrupt()?;
    let progress = Progress::new(sw.quiet || sw.verbose);
    let start = Instant::now();
    say(sw, format_args!("Opening {}.", files.input));
    let path = std::path::Path::new(&files.input);
    let input = if sw.refine {
        read_given(sw, &files)
    } else if files.poly {
        read_poly(path)
            .map(|i| (i, false))
            .map_err(|e| e.to_string())
    } else {
        read_node(path)
            .map(|i| (i, false))
            .map_err(|e| e.to_string())
    };
    let (input, given_attributes) = input?;
    check_interrupt()?;
    let read_time = start.elapsed();

    let mut opts = sw.options(files.poly);
    if sw.refine {
        // The given mesh's attributes are carried over (as Triangle does, -A or not); -c has
        // no effect, the domain being the given triangles.
        opts.region_attributes = given_attributes;
        opts.convex_hull = false;
    }
    opts.progress = Some(progress.callback());
    let mesh_start = Instant::now();
    let mesh = triangulate(&input.pslg, &opts).map_err(|e| describe(&e, &input, &files.input))?;
    let mesh_time = mesh_start.elapsed();
    if !mesh.complete {
        // Printed even with -Q: the files are written but miss the requested bounds.
        // The budget also stops the splits that make segments conforming.
        let what = match sw.max_steiner {
            Some(n) => format!("the Steiner point limit ({n})"),
            None => "the work budget of segment splitting".to_string(),
        };
        eprintln!(
            "idmesh: warning: {what} was reached; some triangles do not meet the quality \
             bounds, or some segments are still encroached (the mesh is constrained Delaunay)"
        );
    }

    if files.poly && mesh.triangles.is_empty() && !input.pslg.points.is_empty() {
        // As Triangle, an input whose segments enclose no area gives an empty mesh; unlike
        // Triangle, the user is told why (printed even with -Q).
        eprintln!(
            "idmesh: warning: the mesh has no triangles: {}",
            why_empty(&input)
        );
    }

    let write_start = Instant::now();
    let base = if sw.zero_based { 0 } else { input.base };
    // The bar goes before the file names are printed.
    progress.finish();
    let outputs = Outputs::before_writing(&files.out_stem);
    let written = write_outputs(sw, &files, &input, &mesh, base).and_then(|()| check_interrupt());
    if written.is_err() && crate::progress_ui::interrupted() {
        outputs.remove_written();
    }
    written?;
    let write_time = write_start.elapsed();
    if sw.verbose && !sw.quiet {
        statistics(&input, &mesh, [read_time, mesh_time, write_time]);
    }
    Ok(())
}

/// Reads what `-r` refines (see `refine_input`): `FILE.node`, `FILE.ele`, with `-p` the
/// segments of `FILE.poly`, with `-a` without a number `FILE.area`. Returns the PSLG to mesh
/// (numbered as `FILE.node`) and whether the triangles have attributes.
fn read_given(sw: &Switches, files: &Files) -> Result<(TriangleInput, bool), String> {
    let node = std::path::Path::new(&files.input);
    let mut input = read_node(node).map_err(|e| e.to_string())?;
    if sw.poly {
        let poly = read_poly(&node.with_extension("poly")).map_err(|e| e.to_string())?;
        input.pslg.segments = poly.pslg.segments;
        input.pslg.segment_markers = poly.pslg.segment_markers;
    }
    let n = input.pslg.points.len();
    let ele_path = node.with_extension("ele");
    let ele_name = ele_path.display().to_string();
    let ele = read_ele(&ele_path, input.base, n).map_err(|e| e.to_string())?;
    if ele.num_attributes > 1 {
        return Err(format!(
            "{ele_name}: {} attributes per triangle; idmesh carries one (-r)",
            ele.num_attributes
        ));
    }
    let max_areas = if sw.region_area {
        read_area(&node.with_extension("area"), ele.triangles.len()).map_err(|e| e.to_string())?
    } else {
        Vec::new()
    };
    let given = GivenMesh {
        triangles: ele.triangles,
        attributes: ele.attributes,
        max_areas,
    };
    input.pslg = refine_input(&input.pslg, &given, sw.region_area, input.base)
        .map_err(|e| format!("{ele_name}: {e}"))?;
    Ok((input, !given.attributes.is_empty()))
}

/// A one-line message for a mesher error, with item numbers as in the input file.
fn describe(e: &Error, input: &TriangleInput, file: &str) -> String {
    match e {
        Error::Input(ie) => {
            format!(
                "{file}: invalid input: {}",
                InputError::renumbered(ie, input.base as usize)
            )
        }
        other => format!("{file}: {other}"),
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
        // The input's point attributes, kept at input points and interpolated linearly at
        // Steiner points, as Triangle writes them.
        let na = input.num_point_attributes;
        let attributes = interpolate_point_attributes(mesh, na, &input.point_attributes)
            .map_err(|e| format!("{}: {e}", files.input))?;
        write_file(sw, &files.output("node"), |f| {
            write_node_attributes(f, mesh, base, na, &attributes)
        })?;
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
            let (hull, markers): (Vec<[u32; 2]>, Vec<i32>) =
                output_segments(mesh).into_iter().unzip();
            write_file(sw, &files.output("poly"), |f| {
                write_poly_segments(f, &hull, &markers, base, holes, regions)
            })?;
        }
    }
    if sw.edges {
        write_file(sw, &files.output("edge"), |f| write_edge(f, mesh, base))?;
    }
    if sw.neighbors {
        write_file(sw, &files.output("neigh"), |f| write_neigh(f, mesh, base))?;
    }
    for &fmt in &sw.formats {
        write_file(sw, &files.output(fmt.extension()), |f| {
            exchange::write(f, MeshView::from(mesh), fmt)
        })?;
    }
    Ok(())
}

/// Why a mesh came out empty: open ends of the segments (points where an odd number of
/// segments end; a closed boundary has none), numbered as in the input, or else the holes.
fn why_empty(input: &TriangleInput) -> String {
    let mut ends = vec![0u32; input.pslg.points.len()];
    for s in &input.pslg.segments {
        for &v in s {
            if let Some(e) = ends.get_mut(v as usize) {
                *e += 1;
            }
        }
    }
    let open: Vec<usize> = (0..ends.len()).filter(|&v| ends[v] % 2 == 1).collect();
    if input.pslg.segments.is_empty() {
        "no segment encloses an area (-p without segments; -c meshes the convex hull)".into()
    } else if let Some(&v) = open.first() {
        format!(
            "the segments enclose no area: {} of their ends are open, e.g. at point {} \
             (-c meshes the convex hull)",
            open.len(),
            v + input.base as usize
        )
    } else {
        "every triangle is outside the segments or in a hole".into()
    }
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
        println!("The Steiner point limit or a work budget was reached: the mesh is incomplete.");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renumber_shifts_every_index_but_counts() {
        let e = InputError::renumbered(
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
        let e = InputError::renumbered(
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
        let e = InputError::renumbered(&InputError::TooFewPoints { count: 2 }, 1);
        assert_eq!(e, InputError::TooFewPoints { count: 2 });
    }
}
