//! Reader for Gmsh `.msh` surface meshes (ASCII, format 4.1 and 2.2) as 3D input: the
//! triangles and quadrangles become facets, lines and volume elements are passed over.
//!
//! * A facet's marker is the first physical tag of its element (format 2.2: the element's
//!   first tag; format 4.1: the first physical tag of its surface entity), or 0 without one.
//! * Only the nodes that some triangle or quadrangle uses are kept, in increasing node tag
//!   order, so that nodes of a volume mesh in the same file do not become interior points.
//! * Binary files are refused by name (write them with `-format msh41` and `Mesh.Binary=0`).
//!
//! Every problem is a [`ParseError`] naming the line.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::error::ParseError;
use super::tetgen_input::TetgenInput;
use crate::input3d::{Facet, Plc};

/// Lines of the file with their 1-based numbers, blank lines skipped.
struct Lines<'a> {
    it: std::iter::Peekable<Box<dyn Iterator<Item = (usize, &'a str)> + 'a>>,
    file: &'a str,
    last: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str, file: &'a str) -> Lines<'a> {
        let it: Box<dyn Iterator<Item = (usize, &'a str)> + 'a> = Box::new(
            text.lines()
                .enumerate()
                .map(|(i, l)| (i + 1, l.trim()))
                .filter(|(_, l)| !l.is_empty()),
        );
        Lines {
            it: it.peekable(),
            file,
            last: 0,
        }
    }

    fn next(&mut self, what: &str) -> Result<(usize, &'a str), ParseError> {
        match self.it.next() {
            Some((n, l)) => {
                self.last = n;
                Ok((n, l))
            }
            None => Err(ParseError::new(
                self.file,
                self.last,
                format!("the file ends before {what}"),
            )),
        }
    }

    fn err(&self, line: usize, msg: impl Into<String>) -> ParseError {
        ParseError::new(self.file, line, msg)
    }

    /// The next line's whitespace-separated numbers, parsed as `T`.
    fn numbers<T: std::str::FromStr>(&mut self, what: &str) -> Result<(usize, Vec<T>), ParseError> {
        let (n, l) = self.next(what)?;
        let v = l
            .split_whitespace()
            .map(|t| {
                t.parse::<T>()
                    .map_err(|_| self.err(n, format!("{what}: bad number '{t}'")))
            })
            .collect::<Result<Vec<T>, _>>()?;
        Ok((n, v))
    }

    /// Skips to the line `$End<name>`.
    fn skip_section(&mut self, name: &str) -> Result<(), ParseError> {
        let end = format!("$End{name}");
        loop {
            let (_, l) = self.next(&end)?;
            if l == end {
                return Ok(());
            }
        }
    }

    fn expect_end(&mut self, name: &str) -> Result<(), ParseError> {
        let end = format!("$End{name}");
        let (n, l) = self.next(&end)?;
        if l != end {
            return Err(self.err(n, format!("expected {end}, got '{l}'")));
        }
        Ok(())
    }
}

/// Number of nodes of the Gmsh element types read as facets.
fn facet_nodes(kind: i64) -> Option<usize> {
    match kind {
        2 => Some(3),
        3 => Some(4),
        _ => None,
    }
}

fn count(line: usize, v: i64, lines: &Lines<'_>, what: &str) -> Result<usize, ParseError> {
    usize::try_from(v).map_err(|_| lines.err(line, format!("negative {what} count {v}")))
}

/// Parses a Gmsh `.msh` file (ASCII 4.1 or 2.2).
pub fn parse_msh(text: &str, file: &str) -> Result<TetgenInput, ParseError> {
    let mut lines = Lines::new(text, file);
    let mut version: Option<f64> = None;
    let mut nodes: BTreeMap<u64, [f64; 3]> = BTreeMap::new();
    // Facets: (node tags, marker, line).
    let mut faces: Vec<(Vec<u64>, i32, usize)> = Vec::new();
    // Format 4.1: surface entity tag -> first physical tag.
    let mut surface_phys: HashMap<i64, i32> = HashMap::new();
    while let Some(&(n, l)) = lines.it.peek() {
        lines.it.next();
        lines.last = n;
        if !l.starts_with('$') {
            return Err(lines.err(n, format!("expected a section such as $Nodes, got '{l}'")));
        }
        let name = &l[1..];
        match name {
            "MeshFormat" => {
                let (n, l) = lines.next("the format line")?;
                let f: Vec<&str> = l.split_whitespace().collect();
                let v: f64 = f
                    .first()
                    .and_then(|v| v.parse().ok())
                    .ok_or_else(|| lines.err(n, "bad format line"))?;
                if f.get(1) != Some(&"0") {
                    return Err(lines.err(
                        n,
                        "binary .msh files are not read; write ASCII (Mesh.Binary = 0)",
                    ));
                }
                if !(v == 2.2 || (4.0..4.2).contains(&v)) {
                    return Err(
                        lines.err(n, format!("format version {v} is not read; use 4.1 or 2.2"))
                    );
                }
                version = Some(v);
                lines.expect_end("MeshFormat")?;
            }
            "Entities" if version.is_some_and(|v| v >= 4.0) => {
                let (n, c) = lines.numbers::<i64>("the entity counts")?;
                if c.len() < 4 {
                    return Err(lines.err(n, "expected 4 entity counts"));
                }
                let counts: Vec<usize> = c[..4]
                    .iter()
                    .map(|&x| count(n, x, &lines, "entity"))
                    .collect::<Result<_, _>>()?;
                for (dim, &k) in counts.iter().enumerate() {
                    for _ in 0..k {
                        let (n, f) = lines.numbers::<f64>("an entity")?;
                        // Points: tag x y z; others: tag and a 6-number box; then the physical
                        // tags with their count.
                        let at = if dim == 0 { 4 } else { 7 };
                        let np = f
                            .get(at)
                            .copied()
                            .ok_or_else(|| lines.err(n, "entity line too short"))?
                            as usize;
                        if dim == 2 && np > 0 {
                            let phys = f
                                .get(at + 1)
                                .copied()
                                .ok_or_else(|| lines.err(n, "entity line too short"))?;
                            surface_phys.insert(f[0] as i64, phys as i32);
                        }
                    }
                }
                lines.expect_end("Entities")?;
            }
            "Nodes" => {
                let v = version.ok_or_else(|| lines.err(n, "$Nodes before $MeshFormat"))?;
                if v >= 4.0 {
                    let (n, c) = lines.numbers::<i64>("the node counts")?;
                    let blocks = count(n, *c.first().unwrap_or(&-1), &lines, "block")?;
                    for _ in 0..blocks {
                        let (n, b) = lines.numbers::<i64>("a node block header")?;
                        if b.len() < 4 {
                            return Err(lines.err(n, "a node block header has 4 numbers"));
                        }
                        let k = count(n, b[3], &lines, "node")?;
                        let mut tags = Vec::with_capacity(k.min(text.len()));
                        for _ in 0..k {
                            let (n, t) = lines.numbers::<u64>("a node tag")?;
                            tags.push(*t.first().ok_or_else(|| lines.err(n, "missing node tag"))?);
                        }
                        for tag in tags {
                            let (n, x) = lines.numbers::<f64>("node coordinates")?;
                            if x.len() < 3 {
                                return Err(lines.err(n, format!("node {tag}: expected x y z")));
                            }
                            nodes.insert(tag, [x[0], x[1], x[2]]);
                        }
                    }
                } else {
                    let (n, c) = lines.numbers::<i64>("the node count")?;
                    let k = count(n, *c.first().unwrap_or(&-1), &lines, "node")?;
                    for _ in 0..k {
                        let (n, l) = lines.next("a node")?;
                        let f: Vec<&str> = l.split_whitespace().collect();
                        let p = (f.len() >= 4)
                            .then(|| {
                                Some((
                                    f[0].parse::<u64>().ok()?,
                                    [f[1].parse().ok()?, f[2].parse().ok()?, f[3].parse().ok()?],
                                ))
                            })
                            .flatten()
                            .ok_or_else(|| lines.err(n, "expected: tag x y z"))?;
                        nodes.insert(p.0, p.1);
                    }
                }
                lines.expect_end("Nodes")?;
            }
            "Elements" => {
                let v = version.ok_or_else(|| lines.err(n, "$Elements before $MeshFormat"))?;
                if v >= 4.0 {
                    let (n, c) = lines.numbers::<i64>("the element counts")?;
                    let blocks = count(n, *c.first().unwrap_or(&-1), &lines, "block")?;
                    for _ in 0..blocks {
                        let (n, b) = lines.numbers::<i64>("an element block header")?;
                        if b.len() < 4 {
                            return Err(lines.err(n, "an element block header has 4 numbers"));
                        }
                        let k = count(n, b[3], &lines, "element")?;
                        let want = if b[0] == 2 { facet_nodes(b[2]) } else { None };
                        let marker = surface_phys.get(&b[1]).copied().unwrap_or(0);
                        for _ in 0..k {
                            let (n, e) = lines.numbers::<u64>("an element")?;
                            if let Some(m) = want {
                                if e.len() != m + 1 {
                                    return Err(lines
                                        .err(n, format!("expected an element tag and {m} nodes")));
                                }
                                faces.push((e[1..].to_vec(), marker, n));
                            }
                        }
                    }
                } else {
                    let (n, c) = lines.numbers::<i64>("the element count")?;
                    let k = count(n, *c.first().unwrap_or(&-1), &lines, "element")?;
                    for _ in 0..k {
                        let (n, e) = lines.numbers::<i64>("an element")?;
                        if e.len() < 3 {
                            return Err(lines.err(n, "expected: tag type number-of-tags ..."));
                        }
                        let nt = count(n, e[2], &lines, "tag")?;
                        if let Some(m) = facet_nodes(e[1]) {
                            if e.len() != 3 + nt + m {
                                return Err(
                                    lines.err(n, format!("expected {nt} tags and {m} nodes"))
                                );
                            }
                            let marker = if nt > 0 { e[3] as i32 } else { 0 };
                            let corners = e[3 + nt..].iter().map(|&x| x as u64).collect();
                            faces.push((corners, marker, n));
                        }
                    }
                }
                lines.expect_end("Elements")?;
            }
            other => lines.skip_section(other)?,
        }
    }
    if version.is_none() {
        return Err(ParseError::new(
            file,
            0,
            "no $MeshFormat section: not a Gmsh file",
        ));
    }
    if faces.is_empty() {
        return Err(ParseError::new(
            file,
            0,
            "no triangles or quadrangles: nothing to mesh",
        ));
    }
    // Keep the nodes that facets use, in tag order.
    let mut index: HashMap<u64, u32> = HashMap::new();
    for (corners, _, line) in &faces {
        for t in corners {
            if !nodes.contains_key(t) {
                return Err(ParseError::new(
                    file,
                    *line,
                    format!("node {t} is not defined"),
                ));
            }
            index.insert(*t, 0);
        }
    }
    let mut points = Vec::with_capacity(index.len());
    for (tag, p) in &nodes {
        if let Some(i) = index.get_mut(tag) {
            *i = points.len() as u32;
            points.push(*p);
        }
    }
    let facet_lines = faces.iter().map(|f| f.2).collect();
    let facets = faces
        .into_iter()
        .map(|(corners, marker, _)| Facet {
            polygons: vec![corners.iter().map(|t| index[t]).collect()],
            holes: vec![],
            marker,
        })
        .collect();
    Ok(TetgenInput {
        plc: Plc {
            points,
            facets,
            ..Default::default()
        },
        base: 0,
        facet_lines,
        ..Default::default()
    })
}

/// Reads a Gmsh `.msh` file.
pub fn read_msh(path: &Path) -> Result<TetgenInput, ParseError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| ParseError::new(&name, 0, format!("cannot read: {e}")))?;
    parse_msh(&text, &name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::exchange::{write, Format, MeshView};
    use crate::mesh3d::TetMesh;

    #[test]
    fn reads_back_what_the_gmsh_writer_writes() {
        let mesh = TetMesh {
            vertices: vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
            vertex_markers: vec![0; 4],
            num_input_vertices: 4,
            tets: vec![[0, 1, 2, 3]],
            neighbors: vec![[u32::MAX; 4]],
            faces: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            face_markers: vec![1, 2, 2, 5],
            ..Default::default()
        };
        let mut out = Vec::new();
        write(&mut out, MeshView::from(&mesh), Format::Msh).unwrap();
        let inp = parse_msh(std::str::from_utf8(&out).unwrap(), "t.msh").unwrap();
        assert_eq!(inp.plc.points, mesh.vertices);
        let mut got: Vec<(Vec<u32>, i32)> = inp
            .plc
            .facets
            .iter()
            .map(|f| (f.polygons[0].clone(), f.marker))
            .collect();
        got.sort();
        let mut want: Vec<(Vec<u32>, i32)> = mesh
            .faces
            .iter()
            .zip(&mesh.face_markers)
            .map(|(f, m)| (f.to_vec(), *m))
            .collect();
        want.sort();
        assert_eq!(got, want);
    }

    #[test]
    fn reads_format_2_2_and_keeps_only_surface_nodes() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n\
                    4 0 0 1\n9 0.2 0.2 0.2\n$EndNodes\n$Elements\n3\n1 1 2 7 1 1 2\n\
                    2 2 2 7 1 1 3 2\n3 4 2 8 1 1 2 3 9\n$EndElements\n";
        let inp = parse_msh(text, "t.msh").unwrap();
        assert_eq!(
            inp.plc.points.len(),
            3,
            "the line's and tet's extra node is dropped"
        );
        assert_eq!(inp.plc.facets.len(), 1);
        assert_eq!(inp.plc.facets[0].polygons, vec![vec![0, 2, 1]]);
        assert_eq!(inp.plc.facets[0].marker, 7);
    }

    #[test]
    fn errors_name_the_line() {
        let bin = "$MeshFormat\n4.1 1 8\n$EndMeshFormat\n";
        assert!(parse_msh(bin, "b.msh")
            .unwrap_err()
            .to_string()
            .contains("b.msh:2: binary"));
        let undefined = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n\
                         $Elements\n1\n1 2 0 1 2 3\n$EndElements\n";
        let e = parse_msh(undefined, "u.msh").unwrap_err();
        assert_eq!(e.line, 10, "{e}");
        assert!(e.message.contains("node 2 is not defined"), "{e}");
        let cut = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n";
        assert!(parse_msh(cut, "c.msh")
            .unwrap_err()
            .message
            .contains("ends before"));
        assert!(parse_msh("hello\n", "h.msh").is_err());
    }
}
