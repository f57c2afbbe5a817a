//! `idmesh show STEM [-o OUT.svg|OUT.png] [--view X,Y,Z | --cut x=VALUE]`: a picture of a
//! mesh written by `idmesh triangle` or `idmesh tetgen` (or by Triangle and TetGen): `STEM.node`
//! with `STEM.ele` (and `STEM.poly` for a 2D mesh's segments and holes), or a 2D input
//! `STEM.poly` alone (its segments and hole seeds). The dimension comes from the `.node`
//! header. See [`idmesh::io::picture`] for what is drawn.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use idmesh::io::picture::{Picture, View};
use idmesh::io::{tetgen, triangle};
use idmesh::{TetMesh, TriMesh, NONE};

const HELP: &str = "\
Usage: idmesh show STEM [-o OUT.svg|OUT.png] [--view X,Y,Z | --cut x=VALUE]

Draws the mesh STEM.node + STEM.ele (2D: with STEM.poly's segments and holes; 3D: its
boundary surface), coloured by quality, with a histogram of its angles. A 2D input STEM.poly
without .ele is drawn as its segments and hole seeds.
  -o FILE        output (.svg or .png; default STEM.svg)
  --view X,Y,Z   3D: look along this direction (default -1,2,-1.5)
  --cut x=VALUE  3D: keep the tetrahedra whose centroid has x <= VALUE (or y, z) and look at
                 the cut from the plane
";

pub fn main(args: &[String]) -> Result<(), String> {
    let mut stem: Option<String> = None;
    let mut out: Option<String> = None;
    let mut view = View::default();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .cloned()
                .ok_or_else(|| format!("{name} needs a value"))
        };
        match a.as_str() {
            "--help" | "-h" => {
                print!("{HELP}");
                return Ok(());
            }
            "-o" => out = Some(value("-o")?),
            "--view" => view = View::parse_direction(&value("--view")?)?,
            "--cut" => view = View::parse_cut(&value("--cut")?)?,
            s if s.starts_with('-') => {
                return Err(format!("unknown option '{s}'; try 'idmesh show --help'"))
            }
            s if stem.is_none() => stem = Some(s.to_string()),
            s => return Err(format!("unexpected argument '{s}' (one STEM only)")),
        }
    }
    let stem = stem.ok_or("no STEM given; try 'idmesh show --help'")?;
    let stem = ["node", "ele", "poly", "face", "neigh", "edge"]
        .iter()
        .find_map(|e| stem.strip_suffix(&format!(".{e}")))
        .unwrap_or(&stem)
        .to_string();
    let file = |ext: &str| PathBuf::from(format!("{stem}.{ext}"));
    let pic = if file("node").exists() {
        match node_dimension(&file("node"))? {
            2 => picture_2d(&file)?,
            3 => picture_3d(&file, view)?,
            d => {
                return Err(format!(
                    "{}: dimension {d}; expected 2 or 3",
                    file("node").display()
                ))
            }
        }
    } else if file("poly").exists() {
        picture_2d(&file)?
    } else {
        return Err(format!(
            "neither {} nor {} exists",
            file("node").display(),
            file("poly").display()
        ));
    };
    let out = out.unwrap_or_else(|| format!("{stem}.svg"));
    let bytes = if out.ends_with(".png") {
        pic.to_png()?
    } else if out.ends_with(".svg") {
        pic.to_svg().into_bytes()
    } else {
        return Err(format!("output '{out}': the name must end in .svg or .png"));
    };
    std::fs::write(&out, bytes).map_err(|e| format!("cannot write {out}: {e}"))
}

/// The dimension field of a `.node` header (the second number of the first data line).
fn node_dimension(path: &Path) -> Result<usize, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let line = text
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .find(|l| !l.is_empty())
        .ok_or_else(|| format!("{}: empty file", path.display()))?;
    line.split_whitespace()
        .nth(1)
        .and_then(|d| d.parse().ok())
        .ok_or_else(|| format!("{}: the header has no dimension", path.display()))
}

fn read_text(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))
}

fn picture_2d(file: &dyn Fn(&str) -> PathBuf) -> Result<Picture, String> {
    let err = |e: idmesh::io::ParseError| e.to_string();
    // The .poly (when there is one) has the segments and holes, and its vertices or the .node's.
    let input = if file("poly").exists() {
        triangle::read_poly(&file("poly")).map_err(err)?
    } else {
        triangle::read_node(&file("node")).map_err(err)?
    };
    let pslg = input.pslg;
    let n = pslg.points.len();
    let triangles = if file("ele").exists() {
        let e = file("ele");
        triangle::parse_ele(&read_text(&e)?, &e.display().to_string(), input.base, n)
            .map_err(err)?
            .triangles
    } else {
        Vec::new()
    };
    let mesh = TriMesh {
        vertices: pslg.points,
        num_input_vertices: n,
        neighbors: vec![[NONE; 3]; triangles.len()],
        triangles,
        segments: pslg.segments,
        complete: true,
        ..Default::default()
    };
    Ok(Picture::of_tri_mesh(&mesh, &pslg.holes))
}

fn picture_3d(file: &dyn Fn(&str) -> PathBuf, view: View) -> Result<Picture, String> {
    let err = |e: idmesh::io::ParseError| e.to_string();
    let input = tetgen::read_node(&file("node")).map_err(err)?;
    let n = input.plc.points.len();
    let e = file("ele");
    if !e.exists() {
        return Err(format!("{} does not exist: nothing to draw", e.display()));
    }
    let tets = tetgen::parse_ele(&read_text(&e)?, &e.display().to_string(), input.base, n)
        .map_err(err)?
        .tets;
    let neighbors = neighbors(&tets);
    let mesh = TetMesh {
        vertices: input.plc.points,
        num_input_vertices: n,
        tets,
        neighbors,
        complete: true,
        ..Default::default()
    };
    Ok(Picture::of_tet_mesh(&mesh, view))
}

/// The tetrahedron across each face (face `i` opposite corner `i`), or `NONE`.
fn neighbors(tets: &[[u32; 4]]) -> Vec<[u32; 4]> {
    let mut nb = vec![[NONE; 4]; tets.len()];
    let mut open: HashMap<[u32; 3], (u32, usize)> = HashMap::with_capacity(tets.len() * 2);
    for (t, v) in tets.iter().enumerate() {
        for i in 0..4 {
            let mut f = [v[(i + 1) % 4], v[(i + 2) % 4], v[(i + 3) % 4]];
            f.sort_unstable();
            if let Some((u, j)) = open.remove(&f) {
                nb[t][i] = u;
                nb[u as usize][j] = t as u32;
            } else {
                open.insert(f, (t as u32, i));
            }
        }
    }
    nb
}
