//! Pictures of meshes (`idmesh show`): the SVG is a well-formed XML document with one polygon
//! per triangle or visible face, and the PNG of a fixed mesh matches a small golden image
//! (`tests/data/golden/*.png`) within a tolerance. `IDMESH_UPDATE_GOLDEN=1 cargo test --test
//! picture` rewrites the golden images (look at them before committing).

mod common3d;

use std::path::{Path, PathBuf};
use std::process::Command;

use idmesh::io::picture::{Picture, View};
use idmesh::io::triangle;
use idmesh::{tetrahedralize, triangulate, Options, Options3};

fn golden(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/golden")
        .join(name)
}

fn decode(bytes: &[u8]) -> (usize, usize, Vec<u8>) {
    let dec = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut r = dec.read_info().expect("a PNG header");
    let mut buf = vec![0; r.output_buffer_size().expect("a buffer size")];
    let info = r.next_frame(&mut buf).expect("PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, buf)
}

/// Compares `pic`'s PNG with the golden image `name`: same size, and at most 0.5 % of the
/// pixels differ by more than 24 in a channel (room for rounding in the mesher's floats on
/// another machine, none for a picture drawn differently).
fn check_golden(pic: &Picture, name: &str) {
    let png_bytes = pic.to_png().unwrap();
    let path = golden(name);
    if std::env::var_os("IDMESH_UPDATE_GOLDEN").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &png_bytes).unwrap();
    }
    let (w, h, got) = decode(&png_bytes);
    let want_bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let (gw, gh, want) = decode(&want_bytes);
    assert_eq!((w, h), (gw, gh), "{name}: size");
    let differing = got
        .chunks(3)
        .zip(want.chunks(3))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 24))
        .count();
    assert!(
        differing * 200 <= w * h,
        "{name}: {differing} of {} pixels differ from the golden image",
        w * h
    );
    // The picture is not blank: the mesh and the histogram put colour on the canvas.
    let white = got.chunks(3).filter(|p| p == &[255, 255, 255]).count();
    assert!(white * 10 < w * h * 9, "{name}: nearly blank");
}

/// Checks the SVG is well-formed XML (with Python's parser, when Python is there) and counts
/// its polygons.
fn svg_polygons(svg: &str) -> usize {
    assert!(svg.starts_with("<svg ") && svg.trim_end().ends_with("</svg>"));
    let ok = Command::new("python3")
        .args([
            "-c",
            "import sys, xml.dom.minidom as m; m.parseString(sys.stdin.read())",
        ])
        .stdin(std::process::Stdio::piped())
        .spawn()
        .and_then(|mut c| {
            use std::io::Write;
            c.stdin.take().unwrap().write_all(svg.as_bytes())?;
            c.wait()
        });
    if let Ok(status) = ok {
        assert!(status.success(), "the SVG does not parse as XML");
    }
    svg.matches("<polygon ").count()
}

#[test]
fn a_2d_mesh_and_its_angle_histogram() {
    let input = triangle::read_poly(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/square_hole.poly"),
    )
    .unwrap();
    let opts = Options {
        min_angle: Some(30.0),
        max_area: Some(0.01),
        ..Default::default()
    };
    let mesh = triangulate(&input.pslg, &opts).unwrap();
    let pic = Picture::of_tri_mesh(&mesh, &input.pslg.holes);
    let svg = pic.to_svg();
    // One polygon per triangle, the histogram's frame, and one per non-empty bin (30 to 60
    // degrees: at most 6 bins of 5 degrees).
    let n = svg_polygons(&svg);
    assert!(
        n > mesh.triangles.len() && n <= mesh.triangles.len() + 1 + 6,
        "{n}"
    );
    assert_eq!(
        svg.matches("<line ").count(),
        mesh.segments.len() + 2 * input.pslg.holes.len()
    );
    assert!(svg.contains("smallest angle of each triangle"));
    check_golden(&pic, "square_hole.png");
}

#[test]
fn a_3d_surface_and_a_cut() {
    let plc = common3d::box_plc([0.0; 3], [1.0; 3]);
    let opts = Options3 {
        radius_edge: Some(1.414),
        max_volume: Some(0.002),
        ..Default::default()
    };
    let mesh = tetrahedralize(&plc, &opts).unwrap();
    let pic = Picture::of_tet_mesh(&mesh, View::default());
    let svg = pic.to_svg();
    // Seen along (-1, 2, -1.5) three faces of the box are visible: about half the surface.
    let surface = mesh
        .neighbors
        .iter()
        .flatten()
        .filter(|&&n| n == idmesh::NONE)
        .count();
    let n = svg_polygons(&svg);
    assert!(
        n > surface / 3 && n < surface,
        "{n} polygons for {surface} boundary faces"
    );
    assert!(svg.contains("dihedral angles of all tetrahedra"));
    check_golden(&pic, "box_view.png");
    let cut = Picture::of_tet_mesh(&mesh, View::Cut { axis: 0, at: 0.5 });
    assert!(svg_polygons(&cut.to_svg()) > 0);
    check_golden(&cut, "box_cut.png");
}
