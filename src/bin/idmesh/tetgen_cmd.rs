//! `idmesh tetgen`: TetGen's command line on top of the 3D mesher.

use std::path::Path;
use std::time::{Duration, Instant};

use idmesh::error::Item;
use idmesh::input3d::check_plc;
use idmesh::io::tetgen::{read_input, TetgenInput};
use idmesh::mesh3d::repair_surface;
use idmesh::progress::observe;
use idmesh::switches::tetgen::{self as tetgen_switches, renumber, resolve, say, write_outputs};
use idmesh::switches::tetgen::{Parsed, TetSwitches};
use idmesh::switches::tetgen_extra::{mesh_for, read_extra};
use idmesh::{Error, Plc, TetMesh};

use crate::progress_ui::{catch_interrupt, check_interrupt, Outputs, Progress};

/// The help text of `idmesh tetgen --help`.
pub const HELP: &str = "\
idmesh tetgen: quality conforming Delaunay tetrahedralization, with TetGen's command line.

Usage: idmesh tetgen [-SWITCHES] FILE

FILE is FILE.node (a point set) or, with -p, FILE.poly or FILE.smesh (a piecewise linear
complex); FILE.off, FILE.stl, FILE.ply, FILE.mesh (Medit) and FILE.vtk (legacy ASCII VTK:
its triangles, quads and polygons; 3D cells are skipped) are surfaces read as PLCs, and
those extensions, like .poly and .smesh, imply -p. Surface files are repaired first, with a
warning per kind of repair unless -Q: duplicate vertices merged, zero-area faces and
unreferenced vertices dropped, non-planar faces triangulated (output vertices: the kept input
vertices in input order). Outputs are FILE.1.node, FILE.1.ele and
FILE.1.face (FILE.2.* for FILE.1, ...), FILE.1.edge with -e, FILE.1.neigh with -n. Numbering
follows the input (0 or 1), or starts at 0 with -z.

Switches are letters that may be grouped, e.g. -pq1.414a0.1V:
  -p          read a PLC (facets, facet holes, volume holes, regions)
  -q[RATIO]   radius-edge bound (default 2.0; below about 1.2 it may not terminate); implies -p
  -qRATIO/ANGLE  also the minimum dihedral angle (default 15 with -q, /0: none): slivers
              are removed by Delaunay refinement, so the mesh stays Delaunay
  -a[VOLUME]  with a number: maximum tetrahedron volume (implies -q); without: the regional
              volume bounds of the input
  -A          write each tetrahedron's regional attribute to the .ele file
  -S[N]       at most N Steiner points (-S alone: no limit); a warning is printed if reached
  -Y          keep the input surface: no Steiner points on segments or facets (the boundary
              faces are the input triangles; interior points are added where the surface
              needs them, and the tets next to the surface are not Delaunay). As in TetGen,
              tets whose circumcenter would encroach the surface are left as they are
  -z          number output items from 0
  -f          write every face to the .face file, not only the boundary and facet faces
  -e          write every edge to an .edge file (marker: the subsegment's, else 0)
  -n          write a .neigh file
  -N -E -F    do not write the .node / .ele / .face file
  -B          leave boundary markers out of the output
  -I          no iteration number in output names (FILE.node, not FILE.1.node)
  -d          only check the PLC for self-intersections and bad facets; write nothing
  -C          check the consistency of the final mesh
  -Q          quiet: print only errors and warnings
  -V          verbose: print counts, volume, quality figures and timings
  -M          do not merge coplanar facets: by default, as in TetGen, exactly coplanar
              neighbouring facets with the same marker are meshed as one facet (the edges
              between them need not appear in the mesh); never with -Y. Duplicate
              vertices of surface files are merged all the same, as in TetGen
  -T[TOL]     also merge nearly coplanar neighbouring facets (off by default: coplanarity is
              decided exactly, and a flat tet at a tiny fold is for sliver removal): facets
              whose vertices lie within TOL (-T alone: 1e-8, TetGen's default; at most 0.01)
              times their longest edge of the plane of their group's largest facet are moved
              exactly onto that plane and merged, so the boundary is within the tolerance of
              the input, as TetGen's. A group with no exactly planar move is kept (-V counts
              them). No effect with -M or -Y
  -k, -g      also write FILE.1.vtk (legacy VTK) / FILE.1.mesh (Medit), as TetGen does
  --format F  also write FILE.1.F: vtk, vtu (VTK XML), msh (Gmsh 4.1) or mesh (Medit)
  -r          refine FILE.node + FILE.ele (+ FILE.face, FILE.vol with -a): the mesh's boundary
              and the faces between its regions (attributes, .vol bounds) are remeshed to the
              -q/-a bounds with every given point kept at its index (not refined in place)
  -i          also insert the points of FILE.a.node
  -m          sizes at points: FILE.mtr (one size per input point), or FILE.b.node +
              FILE.b.ele + FILE.b.mtr (a background mesh); interpolated linearly, a tet is
              split while its longest edge exceeds the size at its centroid
  -o2         10-node tetrahedra: edge midpoints after the vertices in .node, TetGen 1.5's
              node order in .ele
  -O[L][/S]   optimise the mesh (off by default; TetGen runs -O2/7): L passes (0-10, -O
              alone: 2) of flips (scheme bit 1) and smoothing of interior Steiner points
              (bit 2), each kept only when the extreme dihedral angles improve; bit 4 splits
              slivers by new points first (the Delaunay sliver removal of -q, also without
              -q, aiming at 180 minus -o/). After flips or smoothing the mesh is no longer
              Delaunay; facets, segments, regions and input points are kept. With -p or -r only
  -o/ANGLE    the maximum dihedral angle the optimisation aims at (default 165); implies -O
  Point attributes of the input are written, interpolated linearly at Steiner points.
  -D -J -X    accepted: idmesh output is always conforming Delaunay, never drops unused
              vertices, and its arithmetic is always exact
Numbers after q take digits and dots; after a, S and T also exponents, exactly as in TetGen
(so -a0.1e reads the volume 0.1e: put e first, -pea0.1).
Not supported: -w -R -s -l -L -b -v -G -K -j and -p<tol>; they are errors, never ignored.
";

/// Runs `idmesh tetgen ARGS`.
pub fn main(args: &[String]) -> Result<(), String> {
    match tetgen_switches::parse(args)? {
        Parsed::Help => {
            print!("{HELP}");
            Ok(())
        }
        Parsed::Run { switches, file } => run(&switches, &file),
    }
}

fn run(sw: &TetSwitches, file: &str) -> Result<(), String> {
    let files = resolve(file, sw);
    catch_interrupt()?;
    let progress = Progress::new(sw.quiet || sw.verbose);
    let start = Instant::now();
    say(sw, format_args!("Opening {}.", files.input));
    let path = Path::new(&files.input);
    let input = read_input(path).map_err(|e| e.to_string())?;
    check_interrupt()?;
    let base = input.base;
    let repair = if is_surface(&files.input) {
        let r = repair_surface(&input.plc).map_err(|e| describe(&e, &input, &files.input))?;
        if !sw.quiet {
            for w in &r.warnings {
                eprintln!(
                    "idmesh: warning: {}: {}",
                    files.input,
                    w.message(base as usize)
                );
            }
        }
        Some(r)
    } else {
        None
    };
    // The error of a run on the repaired surface, in the file's numbering.
    let told = |e: Error| {
        let e = repair.as_ref().map_or(e.clone(), |r| r.error(e));
        describe(&e, &input, &files.input)
    };
    let plc = repair.as_ref().map_or(&input.plc, |r| &r.plc);
    let read_time = start.elapsed();

    if sw.detect {
        check_plc(plc).map_err(told)?;
        say(sw, format_args!("No intersections or bad facets found."));
        return Ok(());
    }

    let extra = read_extra(sw, &files.input, &input)?;
    let mesh_start = Instant::now();
    // A PLC file name implies -p.
    let sw_run = TetSwitches {
        plc: files.plc,
        ..sw.clone()
    };
    let mut opts = sw.options();
    let f = progress.callback();
    opts.progress = Some(f.clone());
    // observe: the point-set path (delaunay3d) reports too.
    let mesh = observe(Some(&f), || mesh_for(&sw_run, plc, opts, &extra));
    let (mesh, post) = mesh.map_err(told)?;
    let mesh_time = mesh_start.elapsed();
    if !mesh.complete {
        // Printed even with -Q: the files are written but miss the requested bounds.
        eprintln!(
            "idmesh: warning: the Steiner point limit ({}) was reached; some tetrahedra do not \
             meet the quality bounds",
            sw.max_steiner.unwrap_or(0)
        );
    }
    if sw.check {
        mesh.validate()
            .map_err(|e| format!("{}: {e}", files.input))?;
        say(sw, format_args!("The mesh is consistent."));
    }

    let write_start = Instant::now();
    let out_base = if sw.zero_based { 0 } else { base };
    // The bar goes before the file names are printed.
    progress.finish();
    let outputs = Outputs::before_writing(&files.out_stem);
    let written = write_outputs(
        sw,
        &files.out_stem,
        files.plc || sw.refine,
        !plc.point_markers.is_empty(),
        &mesh,
        &post,
        out_base,
    )
    .and_then(|()| check_interrupt());
    if written.is_err() && crate::progress_ui::interrupted() {
        outputs.remove_written();
    }
    written?;
    let write_time = write_start.elapsed();
    if sw.verbose && !sw.quiet {
        statistics(plc, &mesh, [read_time, mesh_time, write_time]);
    }
    Ok(())
}

/// Whether `file` is a surface mesh (repaired as the README's "Surface input" says), not a
/// `.node`, `.poly` or `.smesh` file (taken as given, as in TetGen).
fn is_surface(file: &str) -> bool {
    let ext = Path::new(file)
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    matches!(
        ext.as_deref(),
        Some("off" | "stl" | "ply" | "mesh" | "msh" | "vtk")
    )
}

/// A one-line message for a mesher error, with item numbers as in the input file (and the
/// line of the first facet it names, when the reader kept it).
fn describe(e: &Error, input: &TetgenInput, file: &str) -> String {
    match e {
        Error::Input(ie) => {
            let first = std::cell::Cell::new(None);
            ie.map_items(&|kind, i| {
                if kind == Item::Facet && first.get().is_none() {
                    first.set(Some(i));
                }
                i
            });
            let at = first
                .get()
                .and_then(|f| input.facet_lines.get(f))
                .map_or(String::new(), |l| format!(" (line {l})"));
            format!(
                "{file}: invalid input: {}{at}",
                renumber(ie, input.base as usize)
            )
        }
        other => format!("{file}: {other}"),
    }
}

fn statistics(p: &Plc, mesh: &TetMesh, [read, meshing, write]: [Duration; 3]) {
    let s = mesh.stats();
    println!();
    println!(
        "Input: {} points, {} facets, {} segments, {} holes, {} regions.",
        p.points.len(),
        p.facets.len(),
        p.segments.len(),
        p.holes.len(),
        p.regions.len()
    );
    println!(
        "Mesh: {} vertices ({} Steiner points), {} tetrahedra, {} subfaces, {} subsegments.",
        mesh.vertices.len(),
        mesh.steiner_points,
        mesh.tets.len(),
        mesh.faces.len(),
        mesh.edges.len()
    );
    if mesh.tets.is_empty() {
        println!("Quality: no tetrahedra.");
    } else {
        println!("Radius-edge ratio: largest {:.4}.", s.max_radius_edge);
        println!(
            "Dihedral angles: smallest {:.4} degrees, largest {:.4} degrees.",
            s.min_dihedral, s.max_dihedral
        );
        println!(
            "Tetrahedra with a dihedral angle below 5 / 10 / 15 degrees: {} / {} / {}.",
            s.tets_below[0], s.tets_below[1], s.tets_below[2]
        );
        println!("Dihedral angle histogram (all six angles of every tetrahedron):");
        let h = mesh.dihedral_histogram();
        let bins = idmesh::mesh3d::DIHEDRAL_BINS;
        // Two columns as TetGen prints them: the acute bins left, the obtuse ones right.
        for row in 0..9 {
            let cell =
                |i: usize| format!("{:>5} - {:>3} degrees: {:>10}", bins[i], bins[i + 1], h[i]);
            let right = cell(row + 8);
            let left = if row < 8 { cell(row) } else { " ".repeat(31) };
            println!("  {left}  |  {right}");
        }
    }
    println!("Volume: {}.", s.volume);
    println!(
        "Time: reading {:.3} s, meshing {:.3} s, writing {:.3} s.",
        read.as_secs_f64(),
        meshing.as_secs_f64(),
        write.as_secs_f64()
    );
    if !mesh.complete {
        println!("The Steiner point limit was reached: the mesh is incomplete.");
    }
    if mesh.optimized {
        println!("The mesh was optimised (-O) by flips and smoothing: it is no longer Delaunay.");
    }
}
