//! The exchange formats (VTK, VTU, Gmsh 4.1, Medit) written from real meshes: the Medit file
//! reads back through idmesh's own Medit reader, and, where the Python package `meshio` is
//! installed (the test script installs it), meshio reads every file with the same counts.

mod common3d;

use std::path::{Path, PathBuf};
use std::process::Command;

use idmesh::io::exchange::{write, Format, MeshView};
use idmesh::{tetrahedralize, triangulate, Options, Options3, Plc, Pslg};

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("idmesh-exchange-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A 2 x 1 x 1 box whose six facets carry markers 1 to 6.
fn box_plc() -> Plc {
    let mut plc = common3d::box_plc([0.0; 3], [2.0, 1.0, 1.0]);
    for (i, f) in plc.facets.iter_mut().enumerate() {
        f.marker = i as i32 + 1;
    }
    plc
}

fn square_pslg() -> Pslg {
    Pslg {
        points: vec![[0., 0.], [1., 0.], [1., 1.], [0., 1.]],
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        segment_markers: vec![1, 2, 3, 4],
        ..Default::default()
    }
}

fn write_file<const D: usize, const C: usize, const B: usize>(
    dir: &Path,
    stem: &str,
    view: MeshView<'_, D, C, B>,
    f: Format,
) -> PathBuf {
    let p = dir.join(format!("{stem}.{}", f.extension()));
    write(std::fs::File::create(&p).unwrap(), view, f).unwrap();
    p
}

fn meshio_available() -> bool {
    Command::new("python3")
        .args(["-c", "import meshio"])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// meshio's counts for `path`: points, then (cell type, count) pairs.
fn meshio_counts(path: &Path) -> String {
    let script = "import sys, meshio\n\
                  m = meshio.read(sys.argv[1])\n\
                  c = {}\n\
                  for b in m.cells: c[b.type] = c.get(b.type, 0) + len(b.data)\n\
                  print(len(m.points), *sorted(f'{k}={v}' for k, v in c.items()))";
    let out = Command::new("python3")
        .args(["-c", script])
        .arg(path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "meshio cannot read {}: {}",
        path.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap().trim().to_string()
}

#[test]
fn meshio_reads_every_format_with_the_same_counts() {
    if !meshio_available() {
        eprintln!("meshio not installed: skipping (scripts/test.sh installs it)");
        return;
    }
    let dir = tmpdir("meshio");
    let opts3 = Options3 {
        radius_edge: Some(1.414),
        max_volume: Some(0.05),
        ..Default::default()
    };
    let tets = tetrahedralize(&box_plc(), &opts3).unwrap();
    let opts2 = Options {
        min_angle: Some(30.0),
        max_area: Some(0.01),
        ..Default::default()
    };
    let tris = triangulate(&square_pslg(), &opts2).unwrap();
    for f in [Format::Vtk, Format::Vtu, Format::Msh, Format::Medit] {
        let p = write_file(&dir, "box", MeshView::from(&tets), f);
        let want = format!(
            "{} tetra={} triangle={}",
            tets.vertices.len(),
            tets.tets.len(),
            tets.faces.len()
        );
        assert_eq!(meshio_counts(&p), want, "{f:?}");
        let p = write_file(&dir, "square", MeshView::from(&tris), f);
        let want = format!(
            "{} line={} triangle={}",
            tris.vertices.len(),
            tris.segments.len(),
            tris.triangles.len()
        );
        assert_eq!(meshio_counts(&p), want, "{f:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn medit_output_reads_back_as_a_surface() {
    let dir = tmpdir("medit");
    let opts3 = Options3 {
        radius_edge: Some(2.0),
        ..Default::default()
    };
    let mesh = tetrahedralize(&box_plc(), &opts3).unwrap();
    let p = write_file(&dir, "box", MeshView::from(&mesh), Format::Medit);
    let back = idmesh::io::tetgen::read_medit(&p).unwrap();
    assert_eq!(
        back.plc.points, mesh.vertices,
        "coordinates read back bit for bit"
    );
    assert_eq!(back.plc.facets.len(), mesh.faces.len());
    for (f, (face, marker)) in back
        .plc
        .facets
        .iter()
        .zip(mesh.faces.iter().zip(&mesh.face_markers))
    {
        assert_eq!(f.polygons, vec![face.to_vec()]);
        assert_eq!(f.marker, *marker);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_written_msh_surface_meshes_again() {
    let dir = tmpdir("msh");
    let opts3 = Options3 {
        radius_edge: Some(2.0),
        ..Default::default()
    };
    let mesh = tetrahedralize(&box_plc(), &opts3).unwrap();
    let p = write_file(&dir, "box", MeshView::from(&mesh), Format::Msh);
    let back = idmesh::io::tetgen::read_input(&p).unwrap();
    assert_eq!(back.plc.facets.len(), mesh.faces.len());
    let again = tetrahedralize(&back.plc, &opts3).unwrap();
    again.validate().unwrap();
    let vol = |m: &idmesh::TetMesh| m.stats().volume;
    assert!((vol(&again) - 2.0).abs() < 1e-12 && (vol(&mesh) - 2.0).abs() < 1e-12);
    let mut markers: Vec<i32> = again.face_markers.clone();
    markers.sort_unstable();
    markers.dedup();
    assert_eq!(
        markers,
        [1, 2, 3, 4, 5, 6],
        "the physical tags come back as facet markers"
    );
    std::fs::remove_dir_all(&dir).ok();
}
