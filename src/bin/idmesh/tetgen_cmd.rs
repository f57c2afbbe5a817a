//! `idmesh tetgen`: TetGen's command line on top of the 3D mesher.

use std::fs::File;
use std::io::{self, Write};
use std::path::Path;
use std::time::{Duration, Instant};

use idmesh::input3d::check_plc;
use idmesh::io::tetgen::{
    read_input, write_all_faces, write_edge, write_ele, write_face, write_neigh, write_node,
    TetgenInput,
};
use idmesh::{delaunay3d, tetrahedralize, Error, InputError, Options3, TetMesh};

use crate::names;
use crate::tetgen_switches::{self, Parsed, TetSwitches};

/// The help text of `idmesh tetgen --help`.
pub const HELP: &str = "\
idmesh tetgen: quality conforming Delaunay tetrahedralization, with TetGen's command line.

Usage: idmesh tetgen [-SWITCHES] FILE

FILE is FILE.node (a point set) or, with -p, FILE.poly or FILE.smesh (a piecewise linear
complex); FILE.off, FILE.stl, FILE.ply and FILE.mesh (Medit) are surfaces read as PLCs, and
those extensions, like .poly and .smesh, imply -p. Outputs are FILE.1.node, FILE.1.ele and
FILE.1.face (FILE.2.* for FILE.1, ...), FILE.1.edge with -e, FILE.1.neigh with -n. Numbering
follows the input (0 or 1), or starts at 0 with -z.

Switches are letters that may be grouped, e.g. -pq1.414a0.1V:
  -p          read a PLC (facets, facet holes, volume holes, regions)
  -q[RATIO]   radius-edge bound (default 2.0; below about 1.2 it may not terminate); implies -p
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
  -e          write the subsegments to an .edge file
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
              between them need not appear in the mesh); never with -Y
  -D -J       accepted: idmesh output is always conforming Delaunay and never drops unused
              vertices
Numbers after q take digits and dots; after a and S also exponents, exactly as in TetGen
(so -a0.1e reads the volume 0.1e: put e first, -pea0.1).
Not supported: -c, -r, -i, -m, -T, -O, -o2 and the viewer
outputs; they are errors, never ignored.
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

/// Says something unless `-Q`.
fn say(sw: &TetSwitches, text: std::fmt::Arguments<'_>) {
    if !sw.quiet {
        println!("{text}");
    }
}

/// The extensions of PLC files, which imply `-p`.
const PLC_EXTENSIONS: [&str; 6] = ["poly", "smesh", "off", "stl", "ply", "mesh"];

/// Where to read and where to write.
#[derive(Debug, PartialEq)]
struct Files {
    /// The file to read.
    input: String,
    /// Whether the input is read as a PLC.
    plc: bool,
    /// The output name without extension, e.g. `box.1`.
    out_stem: String,
}

impl Files {
    fn output(&self, ext: &str) -> String {
        format!("{}.{ext}", self.out_stem)
    }
}

/// Resolves the file argument as TetGen does: a known extension names the format (PLC
/// extensions imply `-p`); without one, `-p` reads `FILE.poly` (or `FILE.smesh` when there is
/// no `.poly`), else `FILE.node`.
fn resolve(file: &str, sw: &TetSwitches) -> Files {
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
        // Triangle and TetGen form iteration numbers alike.
        names::resolve(&format!("{stem}.node"), false).out_stem
    };
    Files {
        input,
        plc,
        out_stem,
    }
}

fn run(sw: &TetSwitches, file: &str) -> Result<(), String> {
    let files = resolve(file, sw);
    let start = Instant::now();
    say(sw, format_args!("Opening {}.", files.input));
    let path = Path::new(&files.input);
    let input = read_input(path).map_err(|e| e.to_string())?;
    let read_time = start.elapsed();
    let base = input.base;

    if sw.detect {
        check_plc(&input.plc).map_err(|e| describe(&e, base, &files.input))?;
        say(sw, format_args!("No intersections or bad facets found."));
        return Ok(());
    }

    let mesh_start = Instant::now();
    let mesh = if files.plc {
        tetrahedralize(&input.plc, &options(sw))
    } else {
        // A point set has no features to pass markers on: the input's markers are copied.
        delaunay3d(&input.plc.points).map(|mut m| {
            let markers = &input.plc.point_markers;
            if m.vertex_markers.len() >= markers.len() {
                m.vertex_markers[..markers.len()].copy_from_slice(markers);
            }
            m
        })
    };
    let mesh = mesh.map_err(|e| describe(&e, base, &files.input))?;
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
    write_outputs(sw, &files, &input, &mesh, out_base)?;
    let write_time = write_start.elapsed();
    if sw.verbose && !sw.quiet {
        statistics(&input, &mesh, [read_time, mesh_time, write_time]);
    }
    Ok(())
}

/// Maps the switches to mesher options.
fn options(sw: &TetSwitches) -> Options3 {
    Options3 {
        radius_edge: sw.radius_edge,
        max_volume: sw.max_volume,
        region_max_volume: sw.region_volume,
        region_attributes: sw.region_attributes,
        max_steiner: sw.max_steiner,
        keep_surface: sw.keep_surface,
        merge_coplanar: !sw.no_merge,
        verbose: sw.verbose && !sw.quiet,
        ..Options3::default()
    }
}

/// A one-line message for a mesher error, with item numbers as in the input file.
fn describe(e: &Error, base: u32, file: &str) -> String {
    match e {
        Error::Input(ie) => format!("{file}: invalid input: {}", renumber(ie, base as usize)),
        other => format!("{file}: {other}"),
    }
}

/// Shifts the 0-based indices of an input error to the file's numbering (counts stay).
fn renumber(e: &InputError, b: usize) -> InputError {
    use InputError::*;
    let i = |x: u64| x + b as u64;
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
            index: i(index),
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
        FacetWithoutPolygons { facet } => FacetWithoutPolygons { facet: facet + b },
        EmptyPolygon { facet, polygon } => EmptyPolygon {
            facet: facet + b,
            polygon: polygon + b,
        },
        FacetIndexOutOfRange {
            facet,
            polygon,
            index,
            num_points,
        } => FacetIndexOutOfRange {
            facet: facet + b,
            polygon: polygon + b,
            index: i(index),
            num_points,
        },
        RepeatedVertexInPolygon {
            facet,
            polygon,
            vertex,
        } => RepeatedVertexInPolygon {
            facet: facet + b,
            polygon: polygon + b,
            vertex: vertex + b,
        },
        DegeneratePolygon { facet, polygon } => DegeneratePolygon {
            facet: facet + b,
            polygon: polygon + b,
        },
        DegenerateFacet { facet } => DegenerateFacet { facet: facet + b },
        NonPlanarFacet { facet, vertex } => NonPlanarFacet {
            facet: facet + b,
            vertex: vertex + b,
        },
        NonFiniteFacetHole { facet, hole } => NonFiniteFacetHole {
            facet: facet + b,
            hole: hole + b,
        },
        FacetHoleOffPlane { facet, hole } => FacetHoleOffPlane {
            facet: facet + b,
            hole: hole + b,
        },
        SelfIntersectingFacet {
            facet,
            first_polygon,
            second_polygon,
        } => SelfIntersectingFacet {
            facet: facet + b,
            first_polygon: first_polygon + b,
            second_polygon: second_polygon + b,
        },
        InvalidRegion3 { region } => InvalidRegion3 { region: region + b },
        SegmentCrossesFacet { segment, facet } => SegmentCrossesFacet {
            segment: segment + b,
            facet: facet + b,
        },
        FacetsIntersect { first, second } => FacetsIntersect {
            first: first + b,
            second: second + b,
        },
        VertexOnFacet { vertex, facet } => VertexOnFacet {
            vertex: vertex + b,
            facet: facet + b,
        },
        VertexOnSegment { vertex, segment } => VertexOnSegment {
            vertex: vertex + b,
            segment: segment + b,
        },
        other => other,
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

fn write_outputs(
    sw: &TetSwitches,
    files: &Files,
    input: &TetgenInput,
    mesh: &TetMesh,
    base: u32,
) -> Result<(), String> {
    // As TetGen: vertex markers when the input had them; face and edge markers for PLCs.
    let node_markers = !sw.no_markers && !input.plc.point_markers.is_empty();
    let markers = !sw.no_markers && files.plc;
    if !sw.no_node {
        write_file(sw, &files.output("node"), |f| {
            write_node(f, mesh, base, node_markers)
        })?;
    }
    if !sw.no_ele {
        write_file(sw, &files.output("ele"), |f| write_ele(f, mesh, base))?;
    }
    if !sw.no_face {
        write_file(sw, &files.output("face"), |f| {
            if sw.all_faces {
                write_all_faces(f, mesh, base, markers)
            } else {
                write_face(f, mesh, base, markers)
            }
        })?;
    }
    if sw.edges {
        write_file(sw, &files.output("edge"), |f| {
            write_edge(f, mesh, base, markers)
        })?;
    }
    if sw.neighbors {
        write_file(sw, &files.output("neigh"), |f| write_neigh(f, mesh, base))?;
    }
    Ok(())
}

fn statistics(input: &TetgenInput, mesh: &TetMesh, [read, meshing, write]: [Duration; 3]) {
    let p = &input.plc;
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
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sw(plc: bool) -> TetSwitches {
        TetSwitches {
            plc,
            ..TetSwitches::default()
        }
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
        let o = options(&s);
        assert_eq!(
            (o.radius_edge, o.max_volume, o.max_steiner),
            (Some(1.5), Some(0.25), Some(7))
        );
        assert!(o.region_max_volume && o.region_attributes && !o.verbose);
    }
}
