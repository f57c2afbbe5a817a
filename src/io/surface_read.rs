//! Readers for surface meshes that TetGen accepts as PLCs: Geomview `.off`, `.stl` (ASCII and
//! binary), ASCII `.ply`, Medit `.mesh` and legacy ASCII VTK `.vtk`. Each polygon becomes a
//! one-polygon facet.
//!
//! Numbering, as in TetGen: `.off`, `.ply`, `.vtk` and `.mesh` indices are 0-based when the smallest
//! index in the file is 0 and 1-based when it is 1 (`.off` and `.ply` default to 0, `.mesh`
//! to 1); STL has no indices, its output is numbered from 1 as TetGen does. STL corners are
//! merged into vertices by exact coordinate equality (-0.0 equals 0.0), in order of first
//! appearance.

use std::collections::HashMap;
use std::path::Path;

use super::error::ParseError;
use super::lines::{capacity, parse_f64, parse_int, read_text, Record, Records};
use super::tetgen_input::TetgenInput;
use crate::input3d::{Facet, Plc};
use crate::mesh3d::NONE;

/// Polygons as read (file indices) with their line numbers, turned into facets once the
/// numbering base is known.
struct RawPolygons {
    corners: Vec<i64>,
    start: Vec<usize>,
    lines: Vec<usize>,
    markers: Vec<i32>,
}

impl RawPolygons {
    fn new() -> Self {
        RawPolygons {
            corners: Vec::new(),
            start: vec![0],
            lines: Vec::new(),
            markers: Vec::new(),
        }
    }

    fn push(&mut self, corners: impl IntoIterator<Item = i64>, line: usize, marker: i32) {
        self.corners.extend(corners);
        self.start.push(self.corners.len());
        self.lines.push(line);
        self.markers.push(marker);
    }

    /// Picks the base from the smallest index (0 or 1, else `default`) and checks ranges.
    fn into_input(
        self,
        file: &str,
        points: Vec<[f64; 3]>,
        default: u32,
    ) -> Result<TetgenInput, ParseError> {
        let base = match self.corners.iter().min() {
            Some(0) => 0,
            Some(1) => 1,
            _ => default,
        };
        let n = points.len();
        let mut facets = Vec::with_capacity(self.lines.len());
        for (k, w) in self.start.windows(2).enumerate() {
            let mut poly = Vec::with_capacity(w[1] - w[0]);
            for &v in &self.corners[w[0]..w[1]] {
                let idx = v.saturating_sub(base as i64);
                if idx < 0 || idx >= n as i64 {
                    return Err(ParseError::new(
                        file,
                        self.lines[k],
                        format!(
                            "face {}: corner {v} is out of range: vertices are numbered {base} to {}",
                            k as i64 + base as i64,
                            n as i64 - 1 + base as i64
                        ),
                    ));
                }
                poly.push(idx as u32);
            }
            facets.push(Facet {
                polygons: vec![poly],
                holes: Vec::new(),
                marker: self.markers[k],
            });
        }
        Ok(TetgenInput {
            plc: Plc {
                points,
                facets,
                ..Plc::default()
            },
            base,
            facet_lines: self.lines,
            ..TetgenInput::default()
        })
    }
}

fn too_many(rec: &Record<'_>, n: usize) -> Result<(), ParseError> {
    if n >= NONE as usize {
        Err(rec.error(format!("too many vertices ({n})")))
    } else {
        Ok(())
    }
}

/// Parses a Geomview `.off` file: an optional `OFF` keyword (`COFF`, `NOFF`, ... too; extra
/// per-vertex and per-face fields such as colours are ignored), the counts
/// `<#vertices> <#faces> [<#edges>]`, vertex lines `x y z`, face lines `k v1 .. vk`.
pub fn parse_off(text: &str, file: &str) -> Result<TetgenInput, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || "the OFF header".into())?;
    let mut first = 0;
    if let Some(word) = rec
        .get(0)
        .filter(|w| w.starts_with(|c: char| c.is_ascii_alphabetic()))
    {
        let upper = word.to_ascii_uppercase();
        let kind = upper.strip_suffix("OFF").unwrap_or("?");
        if !kind.chars().all(|c| "STCN".contains(c)) {
            return Err(rec.error(format!(
                "expected an OFF header (OFF, COFF, NOFF, ...), got '{word}'"
            )));
        }
        first = 1;
        if rec.fields.len() == 1 {
            recs.require(&mut rec, || {
                "the counts '<#vertices> <#faces> <#edges>'".into()
            })?;
            first = 0;
        }
    }
    if rec.fields.len() > first + 3 {
        return Err(rec.error("the counts line has more than 3 fields"));
    }
    let nv = rec.count(first, "vertex count")?;
    let nf = rec.count(first + 1, "face count")?;
    too_many(&rec, nv)?;
    let mut points = Vec::with_capacity(capacity(nv, text));
    for k in 0..nv {
        recs.require(&mut rec, || format!("vertex {} of {nv}", k + 1))?;
        rec.item = Some(("vertex", k as i64));
        points.push([
            rec.f64(0, "x coordinate")?,
            rec.f64(1, "y coordinate")?,
            rec.f64(2, "z coordinate")?,
        ]);
    }
    let mut polys = RawPolygons::new();
    for k in 0..nf {
        recs.require(&mut rec, || format!("face {} of {nf}", k + 1))?;
        rec.item = Some(("face", k as i64));
        read_face_line(&rec, &mut polys, 0)?;
    }
    if recs.next_into(&mut rec) {
        return Err(rec.error("unexpected data after the faces declared in the header"));
    }
    polys.into_input(file, points, 0)
}

/// A face line `k v1 .. vk [ignored...]`.
fn read_face_line(
    rec: &Record<'_>,
    polys: &mut RawPolygons,
    marker: i32,
) -> Result<(), ParseError> {
    let k = rec.count(0, "corner count")?;
    if k == 0 {
        return Err(rec.error("a face needs at least one corner"));
    }
    if rec.fields.len() < k + 1 {
        return Err(rec.error(format!(
            "announces {k} corners but lists {}",
            rec.fields.len() - 1
        )));
    }
    let corners = (1..=k)
        .map(|i| rec.int(i, "corner"))
        .collect::<Result<Vec<i64>, ParseError>>()?;
    polys.push(corners, rec.line, marker);
    Ok(())
}

/// Parses an STL file, ASCII or binary (told apart by size: a binary file is exactly
/// `84 + 50 × count` bytes; ASCII files start with `solid`).
pub fn parse_stl(bytes: &[u8], file: &str) -> Result<TetgenInput, ParseError> {
    let binary_size = (bytes.len() >= 84).then(|| {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        84 + 50 * n
    });
    let corners = if binary_size == Some(bytes.len() as u64) {
        stl_binary(bytes, file)?
    } else if bytes.trim_ascii_start().starts_with(b"solid") {
        stl_ascii(&String::from_utf8_lossy(bytes), file)?
    } else {
        return Err(ParseError::new(
            file,
            0,
            "neither an ASCII STL file (starting with 'solid') nor a binary one (84 + 50 × \
             triangles bytes)",
        ));
    };
    if corners.is_empty() {
        return Err(ParseError::new(file, 0, "the STL file has no triangles"));
    }
    // Merge equal corners; adding 0.0 turns -0.0 into 0.0 so that the bits compare as values.
    let mut ids: HashMap<[u64; 3], u32> = HashMap::with_capacity(corners.len() / 2);
    let mut points = Vec::new();
    let mut facets = Vec::with_capacity(corners.len() / 3);
    for tri in corners.chunks(3) {
        let mut poly = Vec::with_capacity(3);
        for &c in tri {
            let key = c.map(|x| (x + 0.0).to_bits());
            let id = *ids.entry(key).or_insert_with(|| {
                points.push(c);
                (points.len() - 1) as u32
            });
            poly.push(id);
        }
        facets.push(Facet {
            polygons: vec![poly],
            ..Facet::default()
        });
    }
    Ok(TetgenInput {
        plc: Plc {
            points,
            facets,
            ..Plc::default()
        },
        base: 1,
        ..TetgenInput::default()
    })
}

fn stl_binary(bytes: &[u8], file: &str) -> Result<Vec<[f64; 3]>, ParseError> {
    let n = (bytes.len() - 84) / 50;
    if n >= (NONE / 3) as usize {
        return Err(ParseError::new(
            file,
            0,
            format!("too many triangles ({n})"),
        ));
    }
    let mut corners = Vec::with_capacity(3 * n);
    for rec in bytes[84..].chunks_exact(50) {
        // 12 bytes of normal, then three corners of three little-endian f32 each.
        for c in 0..3 {
            let at = 12 + 12 * c;
            let f = |k: usize| {
                let b = &rec[at + 4 * k..at + 4 * k + 4];
                f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64
            };
            corners.push([f(0), f(1), f(2)]);
        }
    }
    Ok(corners)
}

fn stl_ascii(text: &str, file: &str) -> Result<Vec<[f64; 3]>, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    let mut corners = Vec::new();
    let mut in_loop = 0usize;
    while recs.next_into(&mut rec) {
        match rec.fields[0].to_ascii_lowercase().as_str() {
            "vertex" => {
                if rec.fields.len() != 4 {
                    return Err(rec.error("a vertex line needs exactly 3 coordinates"));
                }
                rec.item = Some(("triangle", (corners.len() / 3) as i64 + 1));
                corners.push([
                    rec.f64(1, "x coordinate")?,
                    rec.f64(2, "y coordinate")?,
                    rec.f64(3, "z coordinate")?,
                ]);
                in_loop += 1;
            }
            "outer" => in_loop = 0,
            "endloop" => {
                if in_loop != 3 {
                    return Err(rec.error(format!(
                        "a facet loop has {in_loop} vertices; STL facets are triangles"
                    )));
                }
            }
            "solid" | "facet" | "endfacet" | "endsolid" => {}
            other => {
                return Err(rec.error(format!("unexpected keyword '{other}' in an STL file")));
            }
        }
    }
    if corners.len() % 3 != 0 {
        return Err(recs.eof("the rest of the last triangle"));
    }
    Ok(corners)
}

/// A PLY element from the header: name, count and properties (name, whether a list).
struct PlyElement(String, usize, Vec<(String, bool)>);

/// Parses an ASCII `.ply` file with `vertex` (properties `x`, `y`, `z` among others) and
/// `face` (a list property of vertex indices) elements; other elements are skipped.
pub fn parse_ply(text: &str, file: &str) -> Result<TetgenInput, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || "the 'ply' magic line".into())?;
    if rec.fields[0] != "ply" {
        return Err(rec.error("not a PLY file: the first line must be 'ply'"));
    }
    let mut elements: Vec<PlyElement> = Vec::new();
    loop {
        recs.require(&mut rec, || "'end_header'".into())?;
        match rec.fields[0] {
            "format" => {
                if rec.get(1) != Some("ascii") {
                    return Err(rec.error(format!(
                        "only ASCII PLY files are supported (as in TetGen), not '{}'",
                        rec.get(1).unwrap_or("")
                    )));
                }
            }
            "comment" | "obj_info" => {}
            "element" => {
                let name = rec
                    .get(1)
                    .ok_or_else(|| rec.error("missing element name"))?;
                let count = rec.count(2, "element count")?;
                elements.push(PlyElement(name.to_string(), count, Vec::new()));
            }
            "property" => {
                let Some(last) = elements.last_mut() else {
                    return Err(rec.error("a property before any element"));
                };
                let list = rec.get(1) == Some("list");
                let name = rec.fields.last().copied().unwrap_or("");
                last.2.push((name.to_string(), list));
            }
            "end_header" => break,
            other => return Err(rec.error(format!("unexpected header line '{other}'"))),
        }
    }
    let mut points = Vec::new();
    let mut polys = RawPolygons::new();
    let mut saw = (false, false);
    for PlyElement(name, count, props) in &elements {
        let xyz = ["x", "y", "z"].map(|c| props.iter().position(|p| p.0 == c && !p.1));
        let lists = props.iter().filter(|p| p.1).count();
        match name.as_str() {
            "vertex" => {
                let [Some(x), Some(y), Some(z)] = xyz else {
                    return Err(ParseError::new(
                        file,
                        0,
                        "the vertex element lacks x, y or z",
                    ));
                };
                if lists > 0 {
                    return Err(ParseError::new(
                        file,
                        0,
                        "list properties on vertices are not supported",
                    ));
                }
                too_many(&rec, *count)?;
                points.reserve(capacity(*count, text));
                for k in 0..*count {
                    recs.require(&mut rec, || format!("vertex {} of {count}", k + 1))?;
                    rec.item = Some(("vertex", k as i64));
                    points.push([
                        rec.f64(x, "x coordinate")?,
                        rec.f64(y, "y coordinate")?,
                        rec.f64(z, "z coordinate")?,
                    ]);
                }
                saw.0 = true;
            }
            "face" => {
                // The corner list is the only list property (any scalars come before it).
                let at = props.iter().position(|p| p.1);
                let (Some(at), 1) = (at, lists) else {
                    return Err(ParseError::new(
                        file,
                        0,
                        "the face element needs exactly one list property",
                    ));
                };
                for k in 0..*count {
                    recs.require(&mut rec, || format!("face {} of {count}", k + 1))?;
                    rec.item = Some(("face", k as i64));
                    let n = rec.count(at, "corner count")?;
                    if n == 0 || rec.fields.len() < at + 1 + n {
                        return Err(rec.error(format!("a face needs its {n} corners (at least 1)")));
                    }
                    let corners = (at + 1..at + 1 + n)
                        .map(|i| rec.int(i, "corner"))
                        .collect::<Result<Vec<i64>, ParseError>>()?;
                    polys.push(corners, rec.line, 0);
                }
                saw.1 = true;
            }
            _ => {
                for k in 0..*count {
                    recs.require(&mut rec, || format!("{name} {} of {count}", k + 1))?;
                }
            }
        }
    }
    if !saw.0 || !saw.1 {
        return Err(ParseError::new(
            file,
            0,
            "a PLY surface needs vertex and face elements",
        ));
    }
    if recs.next_into(&mut rec) {
        return Err(rec.error("unexpected data after the elements declared in the header"));
    }
    polys.into_input(file, points, 0)
}

/// Parses a Medit `.mesh` file: `Vertices` (`x y z ref`), `Triangles` and `Quadrilaterals`
/// (corners and a reference, which becomes the facet marker); other sections are skipped by
/// their counts. The dimension must be 3.
pub fn parse_medit(text: &str, file: &str) -> Result<TetgenInput, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    let mut points: Option<Vec<[f64; 3]>> = None;
    let mut polys = RawPolygons::new();
    while recs.next_into(&mut rec) {
        let word = rec.fields[0];
        if !word.starts_with(|c: char| c.is_ascii_alphabetic()) {
            return Err(rec.error(format!("expected a keyword, got '{word}'")));
        }
        let keyword = word.to_ascii_lowercase();
        if keyword == "end" {
            break;
        }
        // The keyword's value: on the same line or on the next one.
        let value = if rec.fields.len() > 1 {
            rec.int(1, &keyword)?
        } else {
            recs.require(&mut rec, || format!("the value of {word}"))?;
            rec.int(0, &keyword)?
        };
        match keyword.as_str() {
            "meshversionformatted" => {}
            "dimension" => {
                if value != 3 {
                    return Err(rec.error(format!("dimension must be 3, got {value}")));
                }
            }
            "vertices" => {
                let n = usize::try_from(value).map_err(|_| rec.error("negative vertex count"))?;
                too_many(&rec, n)?;
                let mut pts = Vec::with_capacity(capacity(n, text));
                for k in 0..n {
                    recs.require(&mut rec, || format!("vertex {} of {n}", k + 1))?;
                    rec.item = Some(("vertex", k as i64 + 1));
                    pts.push([
                        rec.f64(0, "x coordinate")?,
                        rec.f64(1, "y coordinate")?,
                        rec.f64(2, "z coordinate")?,
                    ]);
                }
                points = Some(pts);
            }
            "triangles" | "quadrilaterals" => {
                let k = if keyword == "triangles" { 3 } else { 4 };
                let n = usize::try_from(value).map_err(|_| rec.error("negative count"))?;
                for j in 0..n {
                    recs.require(&mut rec, || format!("{word} {} of {n}", j + 1))?;
                    rec.item = Some((
                        if k == 3 { "triangle" } else { "quadrilateral" },
                        j as i64 + 1,
                    ));
                    let corners = (0..k)
                        .map(|i| rec.int(i, "corner"))
                        .collect::<Result<Vec<i64>, ParseError>>()?;
                    let marker = rec.marker(k, "reference")?.unwrap_or(0);
                    polys.push(corners, rec.line, marker);
                }
            }
            _ => {
                let n = usize::try_from(value).map_err(|_| rec.error("negative count"))?;
                for j in 0..n {
                    recs.require(&mut rec, || format!("{word} item {} of {n}", j + 1))?;
                }
            }
        }
    }
    let points = points.ok_or_else(|| ParseError::new(file, 0, "no Vertices section"))?;
    polys.into_input(file, points, 1)
}

/// The fields of a file as one stream across lines (legacy VTK lets numbers run on over line
/// breaks); errors point at the line of the last field read.
struct Fields<'a> {
    recs: Records<'a>,
    rec: Record<'a>,
    at: usize,
}

impl<'a> Fields<'a> {
    fn new(text: &'a str, file: &'a str) -> Self {
        let recs = Records::new(text, file);
        let rec = recs.record();
        Fields { recs, rec, at: 0 }
    }

    /// The next field, or `None` at the end of the file.
    fn next(&mut self) -> Option<&'a str> {
        while self.at >= self.rec.fields.len() {
            if !self.recs.next_into(&mut self.rec) {
                return None;
            }
            self.at = 0;
        }
        self.at += 1;
        Some(self.rec.fields[self.at - 1])
    }

    /// The rest of the current line (fields not read yet), consumed.
    fn rest_of_line(&mut self) -> Vec<&'a str> {
        let rest = self.rec.fields[self.at.min(self.rec.fields.len())..].to_vec();
        self.at = self.rec.fields.len();
        rest
    }

    fn error(&self, message: impl Into<String>) -> ParseError {
        self.rec.error(message)
    }

    fn require(&mut self, what: &str) -> Result<&'a str, ParseError> {
        self.next().ok_or_else(|| self.recs.eof(what))
    }

    fn int(&mut self, what: &str) -> Result<i64, ParseError> {
        let s = self.require(what)?;
        parse_int(s).ok_or_else(|| self.error(format!("bad integer '{s}' for {what}")))
    }

    fn count(&mut self, what: &str) -> Result<usize, ParseError> {
        let v = self.int(what)?;
        usize::try_from(v).map_err(|_| self.error(format!("{what} is negative ({v})")))
    }

    fn f64(&mut self, what: &str) -> Result<f64, ParseError> {
        let s = self.require(what)?;
        parse_f64(s).ok_or_else(|| self.error(format!("bad number '{s}' for {what}")))
    }
}

/// Legacy VTK cell types read as facets: triangle, polygon, pixel (corners in raster order) and
/// quad.
const VTK_TRIANGLE: i64 = 5;
const VTK_POLYGON: i64 = 7;
const VTK_PIXEL: i64 = 8;
const VTK_QUAD: i64 = 9;

/// Parses a legacy ASCII VTK file (`.vtk`) as a surface, as TetGen's `load_vtk` does: `POINTS`,
/// then either `POLYGONS` (a `POLYDATA` dataset) or `CELLS` with `CELL_TYPES` (an
/// `UNSTRUCTURED_GRID`), whose triangles, quads, pixels and polygons become one-polygon
/// facets. Vertices, lines and 3D cells are skipped, so a tetrahedral mesh written with
/// idmesh's `-k` reads back as its boundary triangles; integer cell data named `marker`
/// (what `-k` writes) gives the facet markers. Numbers may run over line breaks; indices are
/// 0-based (1-based when the smallest is 1, as in TetGen). Binary files and the `OFFSETS` /
/// `CONNECTIVITY` cell layout of VTK 5.1 are refused by name.
pub fn parse_vtk(text: &str, file: &str) -> Result<TetgenInput, ParseError> {
    let mut f = Fields::new(text, file);
    // Header: the `# vtk DataFile` line is a comment to the tokenizer; then the title line
    // (any text, possibly blank), then ASCII or BINARY.
    let first = f.require("the title and 'ASCII' lines")?;
    let mode = if first.eq_ignore_ascii_case("ascii") || first.eq_ignore_ascii_case("binary") {
        first
    } else {
        f.rest_of_line();
        f.require("'ASCII'")?
    };
    if !mode.eq_ignore_ascii_case("ascii") {
        return Err(f.error(format!(
            "expected 'ASCII' after the title line, got '{mode}' (binary VTK is not supported)"
        )));
    }
    let mut points: Option<Vec<[f64; 3]>> = None;
    let mut polys = RawPolygons::new();
    // The index of each facet among the CELLS, or among the POLYGONS (for `marker` cell
    // data), and the cells before the polygons in VTK's cell order (vertices, lines,
    // polygons, strips).
    let mut cell_of_facet: Vec<usize> = Vec::new();
    let mut cells_before_polygons = 0usize;
    let mut num_cells = 0usize;
    let mut unstructured = false;
    let mut cell_data = false;
    while let Some(word) = f.next() {
        match word.to_ascii_uppercase().as_str() {
            "DATASET" => {
                let kind = f.require("the dataset type")?;
                match kind.to_ascii_uppercase().as_str() {
                    "POLYDATA" => {}
                    "UNSTRUCTURED_GRID" => unstructured = true,
                    _ => {
                        return Err(f.error(format!(
                            "dataset '{kind}': only POLYDATA and UNSTRUCTURED_GRID are read"
                        )))
                    }
                }
            }
            "POINTS" => {
                let n = f.count("the point count")?;
                f.require("the point data type")?;
                too_many(&f.rec, n)?;
                let mut p = Vec::with_capacity(capacity(n, text));
                for k in 0..n {
                    let what = |c: &str| format!("{c} coordinate of point {k}");
                    p.push([f.f64(&what("x"))?, f.f64(&what("y"))?, f.f64(&what("z"))?]);
                }
                points = Some(p);
            }
            kw @ ("VERTICES" | "LINES" | "POLYGONS" | "TRIANGLE_STRIPS" | "CELLS") => {
                let n = f.count("the cell count")?;
                f.count("the list size")?;
                if kw == "TRIANGLE_STRIPS" && n > 0 {
                    return Err(f.error("TRIANGLE_STRIPS are not supported"));
                }
                let mut types_from = Vec::new();
                for k in 0..n {
                    let m = f.count("the corner count")?;
                    let line = f.rec.line;
                    let mut corners = Vec::with_capacity(m);
                    for _ in 0..m {
                        let s = f.require("a corner")?;
                        if s.eq_ignore_ascii_case("OFFSETS") {
                            return Err(f.error(
                                "the OFFSETS/CONNECTIVITY cell layout (VTK 5.1) is not supported",
                            ));
                        }
                        corners.push(
                            parse_int(s).ok_or_else(|| {
                                f.error(format!("bad integer '{s}' for a corner"))
                            })?,
                        );
                    }
                    match kw {
                        "POLYGONS" => {
                            if m == 0 {
                                return Err(f.error(format!("polygon {k} has no corners")));
                            }
                            cell_of_facet.push(k);
                            polys.push(corners, line, 0);
                        }
                        "CELLS" => types_from.push((corners, line)),
                        _ => {}
                    }
                }
                match kw {
                    "VERTICES" | "LINES" => cells_before_polygons += n,
                    "POLYGONS" => num_cells += n,
                    "CELLS" => {
                        if !unstructured {
                            return Err(f.error("CELLS outside an UNSTRUCTURED_GRID dataset"));
                        }
                        let kw2 = f.require("CELL_TYPES")?;
                        if !kw2.eq_ignore_ascii_case("CELL_TYPES") {
                            return Err(f.error(format!("expected CELL_TYPES, got '{kw2}'")));
                        }
                        let nt = f.count("the cell type count")?;
                        if nt != n {
                            return Err(f.error(format!("{nt} cell types for {n} cells")));
                        }
                        for (k, (mut corners, line)) in types_from.into_iter().enumerate() {
                            let t = f.int("a cell type")?;
                            let need = match t {
                                VTK_TRIANGLE => Some(3),
                                VTK_PIXEL | VTK_QUAD => Some(4),
                                VTK_POLYGON => Some(0),
                                // Vertices and lines (1-4) and 3D cells (10-16, 24-29, 42)
                                // are not part of a surface.
                                1..=4 | 10..=16 | 24..=29 | 42 => None,
                                _ => {
                                    return Err(f.error(format!(
                                        "cell {k} has type {t}, which is neither a surface cell \
                                         (5 triangle, 7 polygon, 8 pixel, 9 quad) nor a vertex, \
                                         line or 3D cell"
                                    )))
                                }
                            };
                            let Some(need) = need else { continue };
                            if (need > 0 && corners.len() != need) || corners.is_empty() {
                                return Err(ParseError::new(
                                    file,
                                    line,
                                    format!("cell {k} (type {t}) has {} corners", corners.len()),
                                ));
                            }
                            if t == VTK_PIXEL {
                                corners.swap(2, 3);
                            }
                            cell_of_facet.push(k);
                            polys.push(corners, line, 0);
                        }
                        num_cells = n;
                    }
                    _ => num_cells += n,
                }
            }
            "CELL_DATA" => {
                let n = f.count("the cell data count")?;
                if unstructured {
                    cells_before_polygons = 0;
                }
                if n != num_cells + cells_before_polygons {
                    return Err(f.error(format!("CELL_DATA {n} for {num_cells} cells")));
                }
                cell_data = true;
            }
            "POINT_DATA" => {
                f.count("the point data count")?;
                cell_data = false;
            }
            "SCALARS" if cell_data => {
                let name = f.require("the scalars' name")?;
                let ty = f.require("the scalars' type")?;
                let rest = f.rest_of_line();
                if name != "marker" || !ty.to_ascii_lowercase().contains("int") || rest.len() > 1 {
                    continue;
                }
                if rest.first().is_some_and(|c| *c != "1") {
                    continue;
                }
                let lut = f.require("LOOKUP_TABLE")?;
                if lut.eq_ignore_ascii_case("LOOKUP_TABLE") {
                    f.require("the lookup table name")?;
                } else {
                    return Err(f.error(format!("expected LOOKUP_TABLE, got '{lut}'")));
                }
                let n = num_cells + cells_before_polygons;
                let mut markers = Vec::with_capacity(capacity(n, text));
                for k in 0..n {
                    let v = f.int(&format!("the marker of cell {k}"))?;
                    markers.push(
                        i32::try_from(v)
                            .map_err(|_| f.error(format!("marker {v} does not fit in 32 bits")))?,
                    );
                }
                for (facet, &cell) in cell_of_facet.iter().enumerate() {
                    polys.markers[facet] = markers[cells_before_polygons + cell];
                }
            }
            _ => {}
        }
    }
    let points = points.ok_or_else(|| ParseError::new(file, 0, "no POINTS section"))?;
    if polys.lines.is_empty() {
        return Err(ParseError::new(
            file,
            0,
            "no surface cells (POLYGONS, or CELLS of type 5, 7, 8 or 9)",
        ));
    }
    polys.into_input(file, points, 0)
}

/// Reads an `.off` file.
pub fn read_off(path: &Path) -> Result<TetgenInput, ParseError> {
    parse_off(&read_text(path)?, &path.display().to_string())
}

/// Reads an `.stl` file (ASCII or binary).
pub fn read_stl(path: &Path) -> Result<TetgenInput, ParseError> {
    let name = path.display().to_string();
    let bytes =
        std::fs::read(path).map_err(|e| ParseError::new(&name, 0, format!("cannot read: {e}")))?;
    parse_stl(&bytes, &name)
}

/// Reads an ASCII `.ply` file.
pub fn read_ply(path: &Path) -> Result<TetgenInput, ParseError> {
    parse_ply(&read_text(path)?, &path.display().to_string())
}

/// Reads a legacy ASCII VTK `.vtk` file as a surface (see [`parse_vtk`]).
pub fn read_vtk(path: &Path) -> Result<TetgenInput, ParseError> {
    parse_vtk(&read_text(path)?, &path.display().to_string())
}

/// Reads a Medit `.mesh` file.
pub fn read_medit(path: &Path) -> Result<TetgenInput, ParseError> {
    parse_medit(&read_text(path)?, &path.display().to_string())
}
