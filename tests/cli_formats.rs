//! Exchange-format output from the command line: TetGen's `-k` (VTK) and `-g` (Medit), and
//! `--format NAME` for both `idmesh triangle` and `idmesh tetgen`; `-V` prints TetGen's
//! dihedral-angle histogram.

mod cli_common;

use cli_common::{idmesh, ok};

const FILES: [&str; 2] = ["square_hole.poly", "3d_box_hole.poly"];

fn workdir(name: &str) -> cli_common::WorkDir {
    cli_common::workdir(&format!("formats-{name}"), &FILES)
}

fn first_number(text: &str) -> usize {
    text.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn tetgen_k_g_and_format_write_the_same_mesh() {
    let d = workdir("tet");
    let out = ok(&idmesh(
        &d,
        &[
            "tetgen",
            "-pq1.414a0.05kgV",
            "--format",
            "msh",
            "--format=vtu",
            "3d_box_hole.poly",
        ],
    ));
    let ntet = first_number(&std::fs::read_to_string(d.join("3d_box_hole.1.ele")).unwrap());
    let vtk = std::fs::read_to_string(d.join("3d_box_hole.1.vtk")).unwrap();
    assert_eq!(
        vtk.lines()
            .skip_while(|l| !l.starts_with("CELL_TYPES"))
            .skip(1)
            .filter(|l| *l == "10")
            .count(),
        ntet
    );
    let medit = std::fs::read_to_string(d.join("3d_box_hole.1.mesh")).unwrap();
    assert!(medit.contains(&format!("Tetrahedra\n{ntet}\n")));
    assert!(std::fs::read_to_string(d.join("3d_box_hole.1.msh"))
        .unwrap()
        .starts_with("$MeshFormat\n4.1 0 8"));
    assert!(std::fs::read_to_string(d.join("3d_box_hole.1.vtu"))
        .unwrap()
        .contains("UnstructuredGrid"));
    // The histogram counts all six dihedral angles of every tetrahedron.
    let counts: usize = out
        .lines()
        .filter(|l| l.contains("degrees:") && l.contains(" - "))
        .flat_map(|l| l.split('|'))
        .filter_map(|cell| cell.split("degrees:").nth(1))
        .map(|n| n.trim().parse::<usize>().unwrap())
        .sum();
    assert_eq!(counts, 6 * ntet, "{out}");
}

#[test]
fn triangle_format_and_errors() {
    let d = workdir("tri");
    ok(&idmesh(
        &d,
        &[
            "triangle",
            "-pq30a0.01Q",
            "--format",
            "mesh",
            "square_hole.poly",
        ],
    ));
    let ntri = first_number(&std::fs::read_to_string(d.join("square_hole.1.ele")).unwrap());
    let medit = std::fs::read_to_string(d.join("square_hole.1.mesh")).unwrap();
    assert!(medit.contains("Dimension 2") && medit.contains(&format!("Triangles\n{ntri}\n")));
    for (args, want) in [
        (
            vec!["triangle", "-pQ", "--format", "obj", "square_hole.poly"],
            "unknown output format 'obj'",
        ),
        (vec!["tetgen", "-pQ", "--format"], "--format needs a value"),
        (
            vec!["tetgen", "-pGQ", "3d_box_hole.poly"],
            "switch -G (Gid output) is not supported",
        ),
    ] {
        let o = idmesh(&d, &args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(want),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}
