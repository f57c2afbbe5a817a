//! `idmesh show`: pictures of meshes written by `idmesh triangle` and `idmesh tetgen`, and its
//! errors (a missing mesh, an unknown output type, bad view options) as one-line messages with
//! exit status 1.

mod cli_common;

use cli_common::{idmesh, ok};

const FILES: [&str; 2] = ["square_hole.poly", "3d_box_hole.poly"];

fn workdir(name: &str) -> cli_common::WorkDir {
    cli_common::workdir(&format!("show-{name}"), &FILES)
}

#[test]
fn draws_2d_and_3d_meshes_as_svg_and_png() {
    let d = workdir("ok");
    ok(&idmesh(
        &d,
        &["triangle", "-pq30a0.01Q", "square_hole.poly"],
    ));
    ok(&idmesh(&d, &["show", "square_hole.1"]));
    let svg = std::fs::read_to_string(d.join("square_hole.1.svg")).unwrap();
    let ele = std::fs::read_to_string(d.join("square_hole.1.ele")).unwrap();
    let ntri: usize = ele.split_whitespace().next().unwrap().parse().unwrap();
    assert!(
        svg.matches("<polygon ").count() > ntri,
        "one polygon per triangle and the histogram"
    );
    ok(&idmesh(&d, &["show", "square_hole.1.node", "-o", "sq.png"]));
    assert!(std::fs::read(d.join("sq.png"))
        .unwrap()
        .starts_with(b"\x89PNG\r\n\x1a\n"));
    // The input PSLG alone: segments and the hole seed, no triangles.
    ok(&idmesh(&d, &["show", "square_hole.poly", "-o", "in.svg"]));
    let svg = std::fs::read_to_string(d.join("in.svg")).unwrap();
    assert_eq!(
        svg.matches("<line ").count(),
        8 + 2,
        "8 segments and the hole's cross"
    );

    ok(&idmesh(
        &d,
        &["tetgen", "-pq1.414a0.01Q", "3d_box_hole.poly"],
    ));
    ok(&idmesh(&d, &["show", "3d_box_hole.1", "--view", "1,1,-1"]));
    assert!(std::fs::read_to_string(d.join("3d_box_hole.1.svg"))
        .unwrap()
        .contains("dihedral"));
    ok(&idmesh(
        &d,
        &["show", "3d_box_hole.1", "--cut", "z=0.5", "-o", "cut.png"],
    ));
    assert!(d.join("cut.png").exists());
}

#[test]
fn errors_are_one_line_with_status_1() {
    let d = workdir("err");
    ok(&idmesh(&d, &["triangle", "-pQ", "square_hole.poly"]));
    for (args, want) in [
        (
            vec!["show", "missing"],
            "neither missing.node nor missing.poly exists",
        ),
        (
            vec!["show", "square_hole.1", "-o", "x.jpg"],
            "must end in .svg or .png",
        ),
        (
            vec!["show", "square_hole.1", "--cut", "w=1"],
            "bad cut axis 'w'",
        ),
        (
            vec!["show", "square_hole.1", "--view", "0,0,0"],
            "bad view direction",
        ),
        (
            vec!["show", "square_hole.1", "--frobnicate"],
            "unknown option '--frobnicate'",
        ),
        (vec!["show"], "no STEM given"),
    ] {
        let o = idmesh(&d, &args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(want) && err.lines().count() == 1,
            "{args:?}: {err}"
        );
    }
}
