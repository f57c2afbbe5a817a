//! Readers for TetGen's formats: `.node`, `.poly`, `.smesh` in; `.ele`, `.face`, `.edge`,
//! `.neigh` to read meshes back.
//!
//! The formats are those of TetGen's manual. Where it is silent the readers follow TetGen's
//! own reader:
//! * missing optional header fields default to dimension 3, 0 attributes, 0 markers;
//! * missing per-vertex attributes and markers default to 0;
//! * items are numbered by position; the first vertex's number (0 or 1) sets the numbering
//!   base of every index in the file (any other first number means base 0, TetGen's default);
//! * a polygon's corner list may continue on the following lines;
//! * a facet's marker is read only when the facet section declares markers (in a `.poly`
//!   file it follows the facet's hole count);
//! * the hole and region sections may be missing at the end of the file; a region line
//!   without a maximum volume uses its attribute as the volume (TetGen copies the field), and
//!   a maximum volume that is not positive means "no bound".
//!
//! It is stricter than TetGen where TetGen silently misreads: count lines with extra fields,
//! polygon lines with more corners than announced, data after the last section, and
//! out-of-range indices are errors naming the line.

use std::path::Path;

use super::error::ParseError;
use super::lines::{capacity, check_attribute_count, read_text, Record, Records, VertexRows};
use super::tetgen_input::TetgenInput;
use crate::input3d::{Facet, Plc, Region3};
use crate::mesh3d::NONE;

/// The contents of an `.ele` file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EleData3 {
    /// Tetrahedra as 0-based vertex indices.
    pub tets: Vec<[u32; 4]>,
    /// Number of attributes per tetrahedron.
    pub num_attributes: usize,
    /// Tetrahedron attributes, `num_attributes` per tetrahedron.
    pub attributes: Vec<f64>,
}

/// The contents of a `.face` or `.edge` file: simplices with optional markers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Simplices<const K: usize> {
    /// The simplices as 0-based vertex indices.
    pub items: Vec<[u32; K]>,
    /// One marker per simplex, or empty when the file has none.
    pub markers: Vec<i32>,
}

/// A marker count field: absent or 0 means no markers, 1 means markers.
fn marker_flag(rec: &Record<'_>, i: usize) -> Result<bool, ParseError> {
    match rec.opt_int(i, "boundary marker count")? {
        None | Some(0) => Ok(false),
        Some(1) => Ok(true),
        Some(m) => Err(rec.error(format!("boundary marker count must be 0 or 1, got {m}"))),
    }
}

/// A vertex header: `<count> [3] [#attributes] [#markers] [0]`.
struct Header {
    count: usize,
    num_attributes: usize,
    markers: bool,
}

fn parse_header(rec: &Record<'_>, what: &str) -> Result<Header, ParseError> {
    rec.at_most(5, what)?;
    let count = rec.count(0, "vertex count")?;
    if let Some(dim) = rec.opt_int(1, "dimension")? {
        if dim != 3 {
            return Err(rec.error(format!("dimension must be 3, got {dim}")));
        }
    }
    let num_attributes = match rec.get(2) {
        Some(_) => rec.count(2, "attribute count")?,
        None => 0,
    };
    let markers = marker_flag(rec, 3)?;
    if let Some(uv) = rec.opt_int(4, "parameter flag")? {
        if uv != 0 {
            return Err(rec.error(
                "vertices with surface parameters (a PSC input) are not supported".to_string(),
            ));
        }
    }
    Ok(Header {
        count,
        num_attributes,
        markers,
    })
}

/// Reads the vertex lines announced by `header` into a fresh input. With `rest` they are the
/// rest of the file (a `.node` file), and a big one is read on all threads
/// ([`Records::rest_in_parts`]).
fn read_vertices<'a>(
    recs: &mut Records<'a>,
    rec: &mut Record<'a>,
    header: &Header,
    text: &str,
    rest: bool,
) -> Result<TetgenInput, ParseError> {
    let n = header.count;
    let na = header.num_attributes;
    // TetGen numbers from 1 only when the first vertex is numbered 1.
    let (rows, base) =
        VertexRows::<3>::read(recs, rec, n, na, header.markers, text, rest, |first| {
            u32::from(first == 1)
        })?;
    Ok(TetgenInput {
        plc: Plc {
            points: rows.points,
            point_markers: rows.markers,
            ..Plc::default()
        },
        base,
        num_point_attributes: na,
        point_attributes: rows.attributes,
        ..TetgenInput::default()
    })
}

/// Fails if anything but comments follows the last section.
fn expect_end<'a>(
    recs: &mut Records<'a>,
    rec: &mut Record<'a>,
    after: &str,
) -> Result<(), ParseError> {
    if recs.next_into(rec) {
        Err(rec.error(format!("unexpected data after {after} (is a count wrong?)")))
    } else {
        Ok(())
    }
}

/// Converts index `v` of a file numbered from `base` into a 0-based index below `n`.
fn index(rec: &Record<'_>, v: i64, base: u32, n: usize, what: &str) -> Result<u32, ParseError> {
    let idx = v.saturating_sub(base as i64);
    if idx < 0 || idx >= n as i64 {
        return Err(rec.error(if n == 0 {
            format!("{what} {v} is out of range: there are no vertices")
        } else {
            format!(
                "{what} {v} is out of range: vertices are numbered {base} to {}",
                n as i64 - 1 + base as i64
            )
        }));
    }
    Ok(idx as u32)
}

/// Parses the text of a `.node` file named `file` (the name is used in errors only).
pub fn parse_node(text: &str, file: &str) -> Result<TetgenInput, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || {
        "the header line '<#vertices> 3 <#attributes> <#markers>'".into()
    })?;
    let header = parse_header(&rec, "the .node header")?;
    let input = read_vertices(&mut recs, &mut rec, &header, text, true)?;
    expect_end(&mut recs, &mut rec, "the vertices declared in the header")?;
    Ok(input)
}

/// Which facet layout a file uses.
#[derive(Clone, Copy, PartialEq)]
enum Layout {
    /// `.poly`: per facet `<#polygons> [#holes] [marker]`, polygon lines, hole lines.
    Poly,
    /// `.smesh`: per facet one line `<#corners> <corners> [marker]`.
    Smesh,
}

/// Parses the text of a `.poly` file named `file`. When its vertex count is 0 the vertices
/// come from `load_node` (normally the `.node` file beside it); it is not called otherwise.
pub fn parse_poly(
    text: &str,
    file: &str,
    load_node: impl FnOnce() -> Result<TetgenInput, ParseError>,
) -> Result<TetgenInput, ParseError> {
    parse_plc(text, file, load_node, Layout::Poly)
}

/// Parses the text of a `.smesh` file named `file` (TetGen's simple form of `.poly`: one
/// polygon per facet, no facet holes). `load_node` is used as in [`parse_poly`].
pub fn parse_smesh(
    text: &str,
    file: &str,
    load_node: impl FnOnce() -> Result<TetgenInput, ParseError>,
) -> Result<TetgenInput, ParseError> {
    parse_plc(text, file, load_node, Layout::Smesh)
}

fn parse_plc(
    text: &str,
    file: &str,
    load_node: impl FnOnce() -> Result<TetgenInput, ParseError>,
    layout: Layout,
) -> Result<TetgenInput, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || {
        "the header line '<#vertices> 3 <#attributes> <#markers>'".into()
    })?;
    let header = parse_header(&rec, "the vertex header")?;
    let mut input = if header.count == 0 {
        load_node()?
    } else {
        read_vertices(&mut recs, &mut rec, &header, text, false)?
    };
    // TetGen reads a file that stops after the vertices as a bare point set.
    if !recs.next_into(&mut rec) {
        return Ok(input);
    }
    rec.at_most(2, "the facet header")?;
    let nf = rec.count(0, "facet count")?;
    let markers = marker_flag(&rec, 1)?;
    let base = input.base;
    let nv = input.plc.points.len();
    let mut facets = Vec::with_capacity(capacity(nf, text));
    for k in 0..nf {
        recs.require(&mut rec, || format!("facet {} of {nf}", k + 1))?;
        let number = base as i64 + k as i64;
        rec.item = Some(("facet", number));
        let facet = match layout {
            Layout::Smesh => {
                let (poly, next) = read_polygon(&mut recs, &mut rec, base, nv, number, None)?;
                let marker = if markers {
                    rec.marker(next, "boundary marker")?.unwrap_or(0)
                } else {
                    0
                };
                let used = next + markers as usize;
                if rec.fields.len() > used {
                    return Err(rec.error(format!(
                        "unexpected field '{}' after the corners{}",
                        rec.fields[used],
                        if markers { " and the marker" } else { "" }
                    )));
                }
                Facet {
                    polygons: vec![poly],
                    holes: Vec::new(),
                    marker,
                }
            }
            Layout::Poly => read_poly_facet(&mut recs, &mut rec, base, nv, number, markers, text)?,
        };
        facets.push(facet);
    }
    input.plc.facets = facets;

    // The hole and region sections are optional at the end of the file, as in TetGen.
    if !recs.next_into(&mut rec) {
        return Ok(input);
    }
    rec.at_most(1, "the hole count line")?;
    let nh = rec.count(0, "hole count")?;
    let mut holes = Vec::with_capacity(capacity(nh, text));
    for k in 0..nh {
        recs.require(&mut rec, || format!("hole {} of {nh}", k + 1))?;
        rec.item = Some(("hole", base as i64 + k as i64));
        holes.push(read_xyz(&rec, 1)?);
    }
    input.plc.holes = holes;

    if !recs.next_into(&mut rec) {
        return Ok(input);
    }
    rec.at_most(1, "the region count line")?;
    let nr = rec.count(0, "region count")?;
    let mut regions = Vec::with_capacity(capacity(nr, text));
    for k in 0..nr {
        recs.require(&mut rec, || format!("region {} of {nr}", k + 1))?;
        rec.item = Some(("region", base as i64 + k as i64));
        let point = read_xyz(&rec, 1)?;
        let attribute = rec.f64(4, "regional attribute")?;
        let volume = rec.opt_f64(5, "maximum volume")?.unwrap_or(attribute);
        regions.push(Region3 {
            point,
            attribute,
            max_volume: (volume > 0.0).then_some(volume),
        });
    }
    input.plc.regions = regions;
    expect_end(&mut recs, &mut rec, "the regions section")?;
    Ok(input)
}

fn read_xyz(rec: &Record<'_>, first: usize) -> Result<[f64; 3], ParseError> {
    Ok([
        rec.f64(first, "x coordinate")?,
        rec.f64(first + 1, "y coordinate")?,
        rec.f64(first + 2, "z coordinate")?,
    ])
}

/// One `.poly` facet: its header line (already in `rec`), polygons and hole seeds.
fn read_poly_facet<'a>(
    recs: &mut Records<'a>,
    rec: &mut Record<'a>,
    base: u32,
    nv: usize,
    number: i64,
    markers: bool,
    text: &str,
) -> Result<Facet, ParseError> {
    rec.at_most(3, "a facet header")?;
    let np = rec.count(0, "polygon count")?;
    if np == 0 {
        return Err(rec.error("a facet needs at least one polygon"));
    }
    let nh = match rec.get(1) {
        Some(_) => rec.count(1, "facet hole count")?,
        None => 0,
    };
    let marker = if markers {
        rec.marker(2, "boundary marker")?.unwrap_or(0)
    } else {
        0
    };
    let mut polygons = Vec::with_capacity(capacity(np, text));
    for j in 0..np {
        recs.require(rec, || {
            format!("polygon {} of {np} of facet {number}", j + 1)
        })?;
        rec.item = Some(("facet", number));
        let pno = base as i64 + j as i64;
        let (poly, next) = read_polygon(recs, rec, base, nv, number, Some(pno))?;
        if rec.fields.len() > next {
            return Err(rec.error(format!(
                "polygon {pno}: unexpected field '{}' after its corners",
                rec.fields[next]
            )));
        }
        polygons.push(poly);
    }
    let mut holes = Vec::with_capacity(capacity(nh, text));
    for j in 0..nh {
        recs.require(rec, || format!("hole {} of {nh} of facet {number}", j + 1))?;
        rec.item = Some(("facet", number));
        holes.push(read_xyz(rec, 1)?);
    }
    Ok(Facet {
        polygons,
        holes,
        marker,
    })
}

/// Reads `<k> v1 .. vk` starting at field 0 of `rec`, continuing on the next lines while
/// corners are missing (as TetGen does). Returns the polygon and the first unread field of
/// the current line.
fn read_polygon<'a>(
    recs: &mut Records<'a>,
    rec: &mut Record<'a>,
    base: u32,
    nv: usize,
    facet: i64,
    polygon: Option<i64>,
) -> Result<(Vec<u32>, usize), ParseError> {
    let label = |what: &str| match polygon {
        Some(p) => format!("polygon {p}: {what}"),
        None => what.to_string(),
    };
    let k = rec.count(0, "corner count")?;
    if k == 0 {
        return Err(rec.error(label("a polygon needs at least one corner")));
    }
    let mut poly = Vec::with_capacity(k.min(rec.fields.len() + 64));
    let mut field = 1;
    while poly.len() < k {
        if field >= rec.fields.len() {
            let got = poly.len();
            recs.require(rec, || {
                format!("corner {} of {k} of facet {facet}", got + 1)
            })?;
            rec.item = Some(("facet", facet));
            field = 0;
        }
        let v = rec.int(field, "corner")?;
        let what = label("corner");
        poly.push(index(rec, v, base, nv, &what)?);
        field += 1;
    }
    Ok((poly, field))
}

/// Parses an `.ele` file whose vertices are numbered from `base` and number `num_vertices`.
/// 4-node and 10-node (TetGen's `-o2`) tetrahedra are accepted; of the latter only the four
/// corners are read.
pub fn parse_ele(
    text: &str,
    file: &str,
    base: u32,
    num_vertices: usize,
) -> Result<EleData3, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || {
        "the header line '<#tetrahedra> 4 <#attributes>'".into()
    })?;
    rec.at_most(3, "the .ele header")?;
    let nt = rec.count(0, "tetrahedron count")?;
    let nodes = match rec.opt_int(1, "nodes per tetrahedron")? {
        None | Some(4) => 4,
        Some(10) => 10,
        Some(k) => {
            return Err(rec.error(format!(
                "only 4 or 10 nodes per tetrahedron are supported, got {k}"
            )))
        }
    };
    let na = match rec.get(2) {
        Some(_) => rec.count(2, "attribute count")?,
        None => 0,
    };
    check_attribute_count(&rec, nt, na, text)?;
    let mut tets = Vec::with_capacity(capacity(nt, text));
    let mut attributes = Vec::with_capacity(capacity(nt.saturating_mul(na), text));
    for k in 0..nt {
        recs.require(&mut rec, || format!("tetrahedron {} of {nt}", k + 1))?;
        rec.item = Some(("tetrahedron", base as i64 + k as i64));
        let mut tet = [0u32; 4];
        for (c, slot) in tet.iter_mut().enumerate() {
            let v = rec.int(1 + c, "corner")?;
            *slot = index(&rec, v, base, num_vertices, "corner")?;
        }
        tets.push(tet);
        for c in 4..nodes {
            let v = rec.int(1 + c, "node")?;
            index(&rec, v, base, num_vertices, "node")?;
        }
        for a in 0..na {
            attributes.push(rec.f64(1 + nodes + a, "attribute")?);
        }
    }
    expect_end(&mut recs, &mut rec, "the tetrahedra declared in the header")?;
    Ok(EleData3 {
        tets,
        num_attributes: na,
        attributes,
    })
}

/// Reads `<count> <#markers>` and then `<#> v1 .. vK [marker]` lines.
fn parse_simplices<const K: usize>(
    text: &str,
    file: &str,
    base: u32,
    num_vertices: usize,
    what: &'static str,
) -> Result<Simplices<K>, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || {
        format!("the header line '<#{what}s> <#markers>'")
    })?;
    rec.at_most(2, "the header")?;
    let n = rec.count(0, "count")?;
    let markers = marker_flag(&rec, 1)?;
    let mut out = Simplices {
        items: Vec::with_capacity(capacity(n, text)),
        markers: Vec::with_capacity(if markers { capacity(n, text) } else { 0 }),
    };
    for k in 0..n {
        recs.require(&mut rec, || format!("{what} {} of {n}", k + 1))?;
        rec.item = Some((what, base as i64 + k as i64));
        let mut s = [0u32; K];
        for (c, slot) in s.iter_mut().enumerate() {
            let v = rec.int(1 + c, "corner")?;
            *slot = index(&rec, v, base, num_vertices, "corner")?;
        }
        out.items.push(s);
        if markers {
            out.markers
                .push(rec.marker(1 + K, "boundary marker")?.unwrap_or(0));
        }
    }
    expect_end(&mut recs, &mut rec, "the items declared in the header")?;
    Ok(out)
}

/// Parses a `.face` file (triangles with optional markers).
pub fn parse_face(
    text: &str,
    file: &str,
    base: u32,
    num_vertices: usize,
) -> Result<Simplices<3>, ParseError> {
    parse_simplices(text, file, base, num_vertices, "face")
}

/// Parses an `.edge` file (edges with optional markers).
pub fn parse_edge(
    text: &str,
    file: &str,
    base: u32,
    num_vertices: usize,
) -> Result<Simplices<2>, ParseError> {
    parse_simplices(text, file, base, num_vertices, "edge")
}

/// Parses a `.neigh` file: per tetrahedron the four neighbours (opposite each corner), with
/// -1 read as [`NONE`].
pub fn parse_neigh(
    text: &str,
    file: &str,
    base: u32,
    num_tets: usize,
) -> Result<Vec<[u32; 4]>, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || "the header line '<#tetrahedra> 4'".into())?;
    rec.at_most(2, "the .neigh header")?;
    let n = rec.count(0, "tetrahedron count")?;
    if let Some(k) = rec.opt_int(1, "neighbours per tetrahedron")? {
        if k != 4 {
            return Err(rec.error(format!("expected 4 neighbours per tetrahedron, got {k}")));
        }
    }
    let mut out = Vec::with_capacity(capacity(n, text));
    for k in 0..n {
        recs.require(&mut rec, || format!("tetrahedron {} of {n}", k + 1))?;
        rec.item = Some(("tetrahedron", base as i64 + k as i64));
        let mut row = [NONE; 4];
        for (c, slot) in row.iter_mut().enumerate() {
            let v = rec.int(1 + c, "neighbour")?;
            if v != -1 {
                *slot = index(&rec, v, base, num_tets, "neighbour").map_err(|_| {
                    rec.error(format!(
                        "neighbour {v} is out of range: tetrahedra are numbered {base} to {}",
                        num_tets as i64 - 1 + base as i64
                    ))
                })?;
            }
        }
        out.push(row);
    }
    expect_end(&mut recs, &mut rec, "the tetrahedra declared in the header")?;
    Ok(out)
}

/// Parses a `.vol` file (TetGen's volume bounds for `-ra`): `<#tetrahedra>`, then
/// `<#> <maximum volume>` per tetrahedron (-1 or 0: no bound). It must have `num_tets` lines.
pub fn parse_vol(text: &str, file: &str, num_tets: usize) -> Result<Vec<f64>, ParseError> {
    let kind = super::lines::BoundsFile {
        ext: ".vol",
        one: "tetrahedron",
        many: "tetrahedra",
        quantity: "volume",
    };
    super::lines::parse_bounds(text, file, num_tets, &kind)
}

/// TetGen's `.var` file: facet constraints (marker, maximum area) and segment constraints
/// (0-based endpoints, maximum length).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VarData {
    /// Per facet constraint: the facet marker and the maximum subface area.
    pub facets: Vec<(i32, f64)>,
    /// Per segment constraint: the endpoints (0-based) and the maximum subsegment length.
    pub segments: Vec<([u32; 2], f64)>,
}

/// Parses a `.var` file (TetGen's variant constraints): `<#facet constraints>`, then
/// `<#> <facet marker> <maximum area>` per constraint, then `<#segment constraints>` and
/// `<#> <point> <point> <maximum length>` per constraint, the points numbered from `base`
/// among `num_points`. The segment part may be missing. Bounds must be positive.
pub fn parse_var(
    text: &str,
    file: &str,
    base: u32,
    num_points: usize,
) -> Result<VarData, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    let mut out = VarData::default();
    recs.require(&mut rec, || "the line '<#facet constraints>'".into())?;
    rec.at_most(1, "the facet constraint count")?;
    let n = rec.count(0, "facet constraint count")?;
    let positive = |rec: &Record<'_>, i: usize, what: &str| -> Result<f64, ParseError> {
        let v = rec.f64(i, what)?;
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(rec.error(format!("{what} {v} must be a positive number")))
        }
    };
    for k in 0..n {
        recs.require(&mut rec, || format!("facet constraint {} of {n}", k + 1))?;
        rec.at_most(3, "a facet constraint line")?;
        let marker = rec
            .marker(1, "facet marker")?
            .ok_or_else(|| rec.error("missing facet marker"))?;
        out.facets
            .push((marker, positive(&rec, 2, "maximum area")?));
    }
    if !recs.next_into(&mut rec) {
        return Ok(out);
    }
    rec.at_most(1, "the segment constraint count")?;
    let n = rec.count(0, "segment constraint count")?;
    for k in 0..n {
        recs.require(&mut rec, || format!("segment constraint {} of {n}", k + 1))?;
        rec.at_most(4, "a segment constraint line")?;
        let a = index(&rec, rec.int(1, "endpoint")?, base, num_points, "endpoint")?;
        let b = index(&rec, rec.int(2, "endpoint")?, base, num_points, "endpoint")?;
        out.segments
            .push(([a, b], positive(&rec, 3, "maximum length")?));
    }
    expect_end(&mut recs, &mut rec, "the constraints declared")?;
    Ok(out)
}

/// Parses an `.mtr` file (TetGen's sizes at points for `-m`): `<#points> <#values per
/// point>`, then one line of values per point. Only one value per point (an isotropic size)
/// is supported. It must have `num_points` lines.
pub fn parse_mtr(text: &str, file: &str, num_points: usize) -> Result<Vec<f64>, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || "the header line '<#points> 1'".into())?;
    rec.at_most(2, "the .mtr header")?;
    let n = rec.count(0, "point count")?;
    if n != num_points {
        return Err(rec.error(format!("{n} sizes for {num_points} points")));
    }
    if let Some(k) = rec.opt_int(1, "values per point")? {
        if k != 1 {
            return Err(rec.error(format!(
                "{k} values per point: only isotropic sizes (1 per point) are supported"
            )));
        }
    }
    let mut out = Vec::with_capacity(capacity(n, text));
    for k in 0..n {
        recs.require(&mut rec, || format!("point {} of {n}", k + 1))?;
        rec.at_most(1, "an .mtr line")?;
        out.push(rec.f64(0, "size")?);
    }
    expect_end(&mut recs, &mut rec, "the points declared in the header")?;
    Ok(out)
}

/// Reads a `.node` file.
pub fn read_node(path: &Path) -> Result<TetgenInput, ParseError> {
    let text = read_text(path)?;
    parse_node(&text, &path.display().to_string())
}

/// Reads a `.poly` file; when its vertex count is 0, the vertices are read from the `.node`
/// file with the same name beside it, as TetGen does.
pub fn read_poly(path: &Path) -> Result<TetgenInput, ParseError> {
    let text = read_text(path)?;
    parse_poly(&text, &path.display().to_string(), || {
        read_node(&path.with_extension("node"))
    })
}

/// Reads a `.smesh` file (with the `.node` file beside it when its vertex count is 0).
pub fn read_smesh(path: &Path) -> Result<TetgenInput, ParseError> {
    let text = read_text(path)?;
    parse_smesh(&text, &path.display().to_string(), || {
        read_node(&path.with_extension("node"))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_node() -> Result<TetgenInput, ParseError> {
        panic!("the .node loader must not be called for a file with vertices")
    }

    #[test]
    fn polygon_corners_may_continue_on_the_next_line() {
        let text = "4 3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n1 0\n1\n4 1 2\n 3 4\n";
        let inp = parse_poly(text, "t.poly", no_node).unwrap();
        assert_eq!(inp.plc.facets[0].polygons, vec![vec![0, 1, 2, 3]]);
        assert!(inp.plc.holes.is_empty() && inp.plc.regions.is_empty());
    }

    #[test]
    fn an_attribute_count_the_file_cannot_hold_is_refused_at_once() {
        // Found by the read_tetgen fuzz target: every vertex pushed 10^12 default attributes.
        let e = parse_node(
            "8 3 1000000000000
1 0 0 0
",
            "t.node",
        )
        .unwrap_err();
        assert!(e.to_string().contains("attributes cannot fit"), "{e}");
        let e = parse_ele(
            "1 4 99999
1 1 2 3 4
",
            "t.ele",
            1,
            4,
        )
        .unwrap_err();
        assert!(e.to_string().contains("attributes cannot fit"), "{e}");
        // Missing attributes still read as 0 when the count is plausible.
        let inp = parse_node(
            "2 3 2
1 0 0 0 5
2 1 1 1
",
            "t.node",
        )
        .unwrap();
        assert_eq!(inp.point_attributes, vec![5.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn first_number_other_than_0_or_1_means_base_0() {
        let inp = parse_node("2 3\n7 0 0 0\n8 1 1 1\n", "t.node").unwrap();
        assert_eq!(inp.base, 0);
    }

    #[test]
    fn smesh_marker_is_optional_per_line_and_extra_fields_are_errors() {
        let head = "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";
        let inp = parse_smesh(
            &format!("{head}2 1\n3 0 1 2 7\n3 0 1 3\n"),
            "t.smesh",
            no_node,
        )
        .unwrap();
        assert_eq!(inp.plc.facets[0].marker, 7);
        assert_eq!(inp.plc.facets[1].marker, 0);
        let e = parse_smesh(&format!("{head}1 0\n3 0 1 2 7\n"), "t.smesh", no_node).unwrap_err();
        assert_eq!(e.line, 7);
        assert!(e.message.contains("'7'"), "{e}");
    }
}
