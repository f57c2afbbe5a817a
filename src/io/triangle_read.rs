//! Readers for Triangle's input formats: `.node`, `.poly` (and `.ele`, to read meshes back).
//!
//! The formats are those of Triangle's documentation. Where the documentation is silent the
//! readers follow Triangle's own reader:
//! * missing optional header fields default to dimension 2, 0 attributes, 0 markers;
//! * missing per-vertex attributes and markers default to 0;
//! * items are numbered by position; the first vertex's number (0 or 1) sets the numbering
//!   base used by segment endpoints (any other first number means base 1);
//! * a region line without a maximum area uses its attribute as the area (Triangle copies the
//!   field); a maximum area that is not positive means "no bound".
//!
//! It is stricter than Triangle where Triangle silently misreads: count lines with extra
//! fields, data after the last section, and out-of-range indices are errors.

use std::path::Path;

use super::error::ParseError;
use super::lines::{capacity, check_attribute_count, read_text, Record, Records, VertexRows};
use crate::input2d::{Pslg, Region};

/// The contents of a Triangle `.node` or `.poly` file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriangleInput {
    /// The PSLG with 0-based indices. `point_markers` / `segment_markers` are empty when the
    /// file declares no markers.
    pub pslg: Pslg,
    /// The numbering base of the file (0 or 1), taken from its first vertex.
    pub base: u32,
    /// Number of attributes per vertex declared in the header.
    pub num_point_attributes: usize,
    /// Vertex attributes, `num_point_attributes` per vertex, vertex by vertex.
    pub point_attributes: Vec<f64>,
}

/// The contents of a Triangle `.ele` file (used to read meshes back).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EleData {
    /// Triangles as 0-based vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Number of attributes per triangle.
    pub num_attributes: usize,
    /// Triangle attributes, `num_attributes` per triangle.
    pub attributes: Vec<f64>,
}

/// Vertices as read from a vertex section, before they are merged into a [`TriangleInput`].
struct Vertices {
    points: Vec<[f64; 2]>,
    markers: Option<Vec<i32>>,
    num_attributes: usize,
    attributes: Vec<f64>,
    base: u32,
}

impl Vertices {
    fn into_input(self) -> TriangleInput {
        TriangleInput {
            pslg: Pslg {
                points: self.points,
                point_markers: self.markers.unwrap_or_default(),
                ..Pslg::default()
            },
            base: self.base,
            num_point_attributes: self.num_attributes,
            point_attributes: self.attributes,
        }
    }
}

/// A header line: `<count> [2] [#attributes] [#markers]`.
struct Header {
    count: usize,
    num_attributes: usize,
    markers: bool,
}

fn parse_header(rec: &Record<'_>, what: &str) -> Result<Header, ParseError> {
    rec.at_most(4, what)?;
    let count = rec.count(0, "vertex count")?;
    if let Some(dim) = rec.opt_int(1, "dimension")? {
        if dim != 2 {
            return Err(rec.error(format!("dimension must be 2, got {dim}")));
        }
    }
    let num_attributes = match rec.get(2) {
        Some(_) => rec.count(2, "attribute count")?,
        None => 0,
    };
    let markers = match rec.opt_int(3, "boundary marker count")? {
        None | Some(0) => false,
        Some(1) => true,
        Some(m) => return Err(rec.error(format!("boundary marker count must be 0 or 1, got {m}"))),
    };
    Ok(Header {
        count,
        num_attributes,
        markers,
    })
}

/// Reads the vertex lines announced by `header`. With `rest` they are the rest of the file
/// (a `.node` file), and a big one is read on all threads ([`Records::rest_in_parts`]).
fn read_vertices<'a>(
    recs: &mut Records<'a>,
    rec: &mut Record<'a>,
    header: &Header,
    text: &str,
    rest: bool,
) -> Result<Vertices, ParseError> {
    let n = header.count;
    let na = header.num_attributes;
    let with_markers = header.markers;
    // Triangle numbers from 0 only when the first vertex is numbered 0.
    let (rows, base) =
        VertexRows::<2>::read(recs, rec, n, na, with_markers, text, rest, |first| {
            u32::from(first != 0)
        })?;
    Ok(Vertices {
        points: rows.points,
        markers: with_markers.then_some(rows.markers),
        num_attributes: na,
        attributes: rows.attributes,
        base,
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

/// Parses the text of a `.node` file named `file` (the name is used in errors only).
pub fn parse_node(text: &str, file: &str) -> Result<TriangleInput, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || {
        "the header line '<#vertices> 2 <#attributes> <#markers>'".into()
    })?;
    let header = parse_header(&rec, "the .node header")?;
    let vertices = read_vertices(&mut recs, &mut rec, &header, text, true)?;
    expect_end(&mut recs, &mut rec, "the vertices declared in the header")?;
    Ok(vertices.into_input())
}

/// Parses the text of a `.poly` file named `file`. When its vertex count is 0 the vertices
/// come from `load_node` (normally the `.node` file beside it); it is not called otherwise.
pub fn parse_poly(
    text: &str,
    file: &str,
    load_node: impl FnOnce() -> Result<TriangleInput, ParseError>,
) -> Result<TriangleInput, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || {
        "the header line '<#vertices> 2 <#attributes> <#markers>'".into()
    })?;
    let header = parse_header(&rec, "the .poly header")?;
    let mut input = if header.count == 0 {
        load_node()?
    } else {
        read_vertices(&mut recs, &mut rec, &header, text, false)?.into_input()
    };
    let base = input.base;
    let nv = input.pslg.points.len();

    recs.require(&mut rec, || {
        "the segment header '<#segments> <#markers>'".into()
    })?;
    rec.at_most(2, "the segment header")?;
    let ns = rec.count(0, "segment count")?;
    let seg_markers = match rec.opt_int(1, "boundary marker count")? {
        None | Some(0) => false,
        Some(1) => true,
        Some(m) => return Err(rec.error(format!("boundary marker count must be 0 or 1, got {m}"))),
    };
    let mut segments = Vec::with_capacity(capacity(ns, text));
    let mut markers = Vec::with_capacity(if seg_markers { capacity(ns, text) } else { 0 });
    for k in 0..ns {
        recs.require(&mut rec, || format!("segment {} of {ns}", k + 1))?;
        rec.item = Some(("segment", base as i64 + k as i64));
        let mut ends = [0u32; 2];
        for (j, what) in ["first endpoint", "second endpoint"]
            .into_iter()
            .enumerate()
        {
            let v = rec.int(1 + j, what)?;
            let idx = v.saturating_sub(base as i64);
            if idx < 0 || idx >= nv as i64 {
                return Err(rec.error(if nv == 0 {
                    format!("{what} {v} is out of range: there are no vertices")
                } else {
                    format!(
                        "{what} {v} is out of range: vertices are numbered {base} to {}",
                        nv as i64 - 1 + base as i64
                    )
                }));
            }
            ends[j] = idx as u32;
        }
        segments.push(ends);
        if seg_markers {
            markers.push(rec.marker(3, "boundary marker")?.unwrap_or(0));
        }
    }
    input.pslg.segments = segments;
    input.pslg.segment_markers = markers;

    recs.require(&mut rec, || "the hole count line".into())?;
    rec.at_most(1, "the hole count line")?;
    let nh = rec.count(0, "hole count")?;
    let mut holes = Vec::with_capacity(capacity(nh, text));
    for k in 0..nh {
        recs.require(&mut rec, || format!("hole {} of {nh}", k + 1))?;
        rec.item = Some(("hole", base as i64 + k as i64));
        holes.push([rec.f64(1, "x coordinate")?, rec.f64(2, "y coordinate")?]);
    }
    input.pslg.holes = holes;

    // The regional attribute section is optional.
    if !recs.next_into(&mut rec) {
        return Ok(input);
    }
    rec.at_most(1, "the region count line")?;
    let nr = rec.count(0, "region count")?;
    let mut regions = Vec::with_capacity(capacity(nr, text));
    for k in 0..nr {
        recs.require(&mut rec, || format!("region {} of {nr}", k + 1))?;
        rec.item = Some(("region", base as i64 + k as i64));
        let x = rec.f64(1, "x coordinate")?;
        let y = rec.f64(2, "y coordinate")?;
        let attribute = rec.f64(3, "regional attribute")?;
        let area = rec.opt_f64(4, "maximum area")?.unwrap_or(attribute);
        regions.push(Region {
            point: [x, y],
            attribute,
            max_area: (area > 0.0).then_some(area),
        });
    }
    input.pslg.regions = regions;
    expect_end(&mut recs, &mut rec, "the regions section")?;
    Ok(input)
}

/// Parses the text of an `.ele` file whose vertices are numbered from `base` and number
/// `num_vertices`. 3-node and 6-node (`-o2`) triangles are accepted; of the latter the corners
/// (the first three nodes) are kept, the other three checked for range.
pub fn parse_ele(
    text: &str,
    file: &str,
    base: u32,
    num_vertices: usize,
) -> Result<EleData, ParseError> {
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || {
        "the header line '<#triangles> 3 <#attributes>'".into()
    })?;
    rec.at_most(3, "the .ele header")?;
    let nt = rec.count(0, "triangle count")?;
    let nodes = match rec.opt_int(1, "nodes per triangle")? {
        None | Some(3) => 3,
        Some(6) => 6,
        Some(k) => {
            return Err(rec.error(format!("a triangle has 3 or 6 nodes, not {k}")));
        }
    };
    let na = match rec.get(2) {
        Some(_) => rec.count(2, "attribute count")?,
        None => 0,
    };
    check_attribute_count(&rec, nt, na, text)?;
    let mut triangles = Vec::with_capacity(capacity(nt, text));
    let mut attributes = Vec::with_capacity(capacity(nt.saturating_mul(na), text));
    for k in 0..nt {
        recs.require(&mut rec, || format!("triangle {} of {nt}", k + 1))?;
        rec.item = Some(("triangle", base as i64 + k as i64));
        let mut tri = [0u32; 3];
        for c in 0..nodes {
            let what = if c < 3 { "corner" } else { "node" };
            let v = rec.int(1 + c, what)?;
            let idx = v.saturating_sub(base as i64);
            if idx < 0 || idx >= num_vertices as i64 {
                return Err(rec.error(format!(
                    "{what} {v} is out of range: vertices are numbered {base} to {}",
                    num_vertices as i64 - 1 + base as i64
                )));
            }
            if let Some(slot) = tri.get_mut(c) {
                *slot = idx as u32;
            }
        }
        triangles.push(tri);
        for a in 0..na {
            attributes.push(rec.f64(1 + nodes + a, "attribute")?);
        }
    }
    expect_end(&mut recs, &mut rec, "the triangles declared in the header")?;
    Ok(EleData {
        triangles,
        num_attributes: na,
        attributes,
    })
}

/// Parses a `.area` file (Triangle's per-triangle area bounds for `-ra`): `<#triangles>`,
/// then `<#> <maximum area>` per triangle (0 or less: no bound). It must have `num_triangles`
/// lines.
pub fn parse_area(text: &str, file: &str, num_triangles: usize) -> Result<Vec<f64>, ParseError> {
    let kind = super::lines::BoundsFile {
        ext: ".area",
        one: "triangle",
        many: "triangles",
        quantity: "area",
    };
    super::lines::parse_bounds(text, file, num_triangles, &kind)
}

/// Reads a `.node` file.
pub fn read_node(path: &Path) -> Result<TriangleInput, ParseError> {
    let text = read_text(path)?;
    parse_node(&text, &path.display().to_string())
}

/// Reads an `.ele` file whose vertices are numbered from `base` and number `num_vertices`.
pub fn read_ele(path: &Path, base: u32, num_vertices: usize) -> Result<EleData, ParseError> {
    let text = read_text(path)?;
    parse_ele(&text, &path.display().to_string(), base, num_vertices)
}

/// Reads a `.area` file of `num_triangles` bounds.
pub fn read_area(path: &Path, num_triangles: usize) -> Result<Vec<f64>, ParseError> {
    let text = read_text(path)?;
    parse_area(&text, &path.display().to_string(), num_triangles)
}

/// Reads a `.poly` file; when its vertex count is 0, the vertices are read from the `.node`
/// file with the same name beside it, as Triangle does.
pub fn read_poly(path: &Path) -> Result<TriangleInput, ParseError> {
    let text = read_text(path)?;
    parse_poly(&text, &path.display().to_string(), || {
        read_node(&path.with_extension("node"))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `.node` text of `n` vertices with attributes and markers, comments, blank lines and
    /// CRLF line ends mixed in; big enough for the parallel read.
    fn big_node(n: usize) -> String {
        let mut t = format!("{n} 2 1 1\n");
        for i in 0..n {
            let (x, y) = (
                (i as f64 * 0.618).fract(),
                (i as f64 * 0.377).fract() * 1e-3,
            );
            t.push_str(&format!("{i} {x:?} {y:e} {} {}", i % 7, i % 3));
            t.push_str(match i % 5 {
                0 => "  # comment\n",
                1 => "\r\n",
                2 => "\n\n",
                _ => "\n",
            });
        }
        t
    }

    #[test]
    fn a_big_node_file_reads_as_line_by_line() {
        let n = 150_000;
        let text = big_node(n);
        assert!(text.len() > crate::io::lines::PARALLEL_BYTES);
        let got = parse_node(&text, "big.node").unwrap();
        assert_eq!(got.pslg.points.len(), n);
        assert_eq!(got.base, 0);
        for (i, p) in got.pslg.points.iter().enumerate() {
            assert_eq!(p[0], (i as f64 * 0.618).fract());
            assert_eq!(p[1], (i as f64 * 0.377).fract() * 1e-3);
            assert_eq!(got.pslg.point_markers[i], (i % 3) as i32);
            assert_eq!(got.point_attributes[i], (i % 7) as f64);
        }
        // A bad number near the end, a missing line, an extra line: each named with its line
        // and vertex, as the line-by-line reader names them.
        let bad = text.replacen(&format!("\n{} ", n - 3), &format!("\n{} x", n - 3), 1);
        let e = parse_node(&bad, "big.node").unwrap_err();
        assert!(e.message.contains(&format!("vertex {}", n - 3)), "{e}");
        assert_eq!(
            e.line,
            1 + bad[..bad.find(&format!("\n{} x", n - 3)).unwrap()]
                .matches('\n')
                .count()
                + 1
        );
        let short = text.replacen(&format!("{n} 2 1 1"), &format!("{} 2 1 1", n + 1), 1);
        let e = parse_node(&short, "big.node").unwrap_err();
        assert!(e.message.contains("unexpected end of file"), "{e}");
        let long = text.replacen(&format!("{n} 2 1 1"), &format!("{} 2 1 1", n - 1), 1);
        let e = parse_node(&long, "big.node").unwrap_err();
        assert!(e.message.contains("unexpected data"), "{e}");
    }

    fn no_node() -> Result<TriangleInput, ParseError> {
        panic!("the .node loader must not be called for a .poly with vertices")
    }

    fn poly(text: &str) -> Result<TriangleInput, ParseError> {
        parse_poly(text, "t.poly", no_node)
    }

    const SQUARE_HOLE_1BASED: &str = "\
# A unit square with a square hole; 1-based.
8 2 0 1   # header
1 0 0 1
2 1 0 1
3 1 1 1
4 0 1 1

5 0.25 0.25 2
6 0.75 0.25 2
7 0.75 0.75 2
8 0.25 0.75 2
8 1
1 1 2 1
2 2 3 1
3 3 4 1
4 4 1 1
5 5 6 2
6 6 7 2
7 7 8 2
8 8 5 2
1
1 0.5 0.5
";

    #[test]
    fn parses_one_based_poly_with_comments_markers_and_holes() {
        let inp = poly(SQUARE_HOLE_1BASED).unwrap();
        assert_eq!(inp.base, 1);
        let p = &inp.pslg;
        assert_eq!(p.points.len(), 8);
        assert_eq!(p.points[4], [0.25, 0.25]);
        assert_eq!(p.point_markers, vec![1, 1, 1, 1, 2, 2, 2, 2]);
        assert_eq!(p.segments[0], [0, 1]);
        assert_eq!(p.segments[7], [7, 4]);
        assert_eq!(p.segment_markers, vec![1, 1, 1, 1, 2, 2, 2, 2]);
        assert_eq!(p.holes, vec![[0.5, 0.5]]);
        assert!(p.regions.is_empty());
    }

    #[test]
    fn parses_zero_based_poly_with_regions_and_no_markers() {
        let text = "4 2\n0 0 0\n1 2 0\n2 2 1\n3 0 1\n5 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n4 1 3\n\
                    0\n2\n0 1.5 0.2 7 0.01\n1 0.2 0.8 -3 -1\n";
        let inp = poly(text).unwrap();
        assert_eq!(inp.base, 0);
        assert!(inp.pslg.point_markers.is_empty());
        assert!(inp.pslg.segment_markers.is_empty());
        assert_eq!(inp.pslg.segments[4], [1, 3]);
        assert_eq!(
            inp.pslg.regions,
            vec![
                Region {
                    point: [1.5, 0.2],
                    attribute: 7.0,
                    max_area: Some(0.01)
                },
                Region {
                    point: [0.2, 0.8],
                    attribute: -3.0,
                    max_area: None
                },
            ]
        );
    }

    #[test]
    fn region_without_area_copies_the_attribute_like_triangle() {
        let text = "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n0\n1\n1 0.2 0.2 0.5\n";
        let inp = poly(text).unwrap();
        assert_eq!(inp.pslg.regions[0].attribute, 0.5);
        assert_eq!(inp.pslg.regions[0].max_area, Some(0.5));
    }

    #[test]
    fn parses_node_with_attributes_and_defaults() {
        // Missing attributes and markers default to 0, as in Triangle.
        let text = "3 2 2 1\n0 0.5 -1e-3 7 8 4\n1 1 0 9\n2 0 1\n";
        let inp = parse_node(text, "t.node").unwrap();
        assert_eq!(inp.base, 0);
        assert_eq!(inp.pslg.points, vec![[0.5, -0.001], [1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(inp.num_point_attributes, 2);
        assert_eq!(inp.point_attributes, vec![7.0, 8.0, 9.0, 0.0, 0.0, 0.0]);
        assert_eq!(inp.pslg.point_markers, vec![4, 0, 0]);
        assert!(inp.pslg.segments.is_empty());
    }

    #[test]
    fn numbers_round_like_strtod() {
        let text = "3\n1 0.1 0.30000000000000004\n2 1e-320 -0\n3 123456789012345678901 2.5e+2\n";
        let inp = parse_node(text, "t.node").unwrap();
        let p = &inp.pslg.points;
        assert_eq!(p[0], [0.1, 0.30000000000000004]);
        assert_eq!(p[1][0].to_bits(), 1e-320f64.to_bits());
        assert!(p[1][1] == 0.0 && p[1][1].is_sign_negative());
        assert_eq!(p[2], [123456789012345678901.0, 250.0]);
    }

    #[test]
    fn poly_with_zero_vertices_reads_the_node_file_beside_it() {
        let dir = std::env::temp_dir().join(format!("idmesh-io-{}-zero", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("tri.node"), "3 2 0 1\n0 0 0 5\n1 1 0 6\n2 0 1 7\n").unwrap();
        std::fs::write(
            dir.join("tri.poly"),
            "0 2 0 1\n3 1\n0 0 1 3\n1 1 2 3\n2 2 0 4\n0\n",
        )
        .unwrap();
        let inp = read_poly(&dir.join("tri.poly")).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(inp.base, 0);
        assert_eq!(inp.pslg.points.len(), 3);
        assert_eq!(inp.pslg.point_markers, vec![5, 6, 7]);
        assert_eq!(inp.pslg.segments, vec![[0, 1], [1, 2], [2, 0]]);
        assert_eq!(inp.pslg.segment_markers, vec![3, 3, 4]);
    }

    #[test]
    fn missing_node_file_is_an_error_naming_it() {
        let e = read_poly(Path::new("/nonexistent-idmesh/x.poly")).unwrap_err();
        assert!(e.file.ends_with("x.poly"), "{e}");
        assert_eq!(e.line, 0);
        let e = parse_poly("0 2 0 0\n0 0\n0\n", "x.poly", || {
            read_node(Path::new("/nonexistent-idmesh/x.node"))
        })
        .unwrap_err();
        assert!(e.file.ends_with("x.node"), "{e}");
    }

    fn err(text: &str) -> ParseError {
        poly(text).unwrap_err()
    }

    #[test]
    fn empty_file_is_an_error() {
        let e = err("# nothing but a comment\n\n");
        assert!(e.message.contains("unexpected end of file"), "{e}");
    }

    #[test]
    fn missing_coordinate_is_an_error_naming_the_vertex() {
        let e = err("3 2 0 0\n1 0 0\n2 1\n3 0 1\n0 0\n0\n");
        assert_eq!(e.line, 3);
        assert_eq!(e.message, "vertex 2: missing y coordinate");
    }

    #[test]
    fn bad_number_is_an_error() {
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1.0.0\n0 0\n0\n");
        assert_eq!(e.line, 4);
        assert!(
            e.message.contains("vertex 3") && e.message.contains("'1.0.0'"),
            "{e}"
        );
        let e = err("3 2 0 1\n1 0 0 x\n2 1 0 0\n3 0 1 0\n0 0\n0\n");
        assert!(e.message.contains("boundary marker"), "{e}");
        let e = err("3 two 0 0\n");
        assert!(e.message.contains("dimension"), "{e}");
    }

    #[test]
    fn wrong_header_values_are_errors() {
        assert!(err("3 3 0 0\n").message.contains("dimension must be 2"));
        assert!(err("3 2 0 2\n").message.contains("0 or 1"));
        assert!(err("-3 2 0 0\n").message.contains("negative"));
        assert!(err("3 2 0 0 9\n").message.contains("at most 4"));
    }

    #[test]
    fn too_few_vertex_lines_is_an_error() {
        // Two vertex lines for three declared: the segment header is read as vertex 3 and
        // lacks a y coordinate.
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n1 0\n1 1 2\n0\n");
        assert_eq!(e.line, 4);
        assert!(e.message.contains("vertex 3"), "{e}");
    }

    #[test]
    fn too_many_segment_lines_is_an_error() {
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n2 0\n1 1 2\n2 2 3\n3 3 1\n0\n");
        assert_eq!(e.line, 8);
        assert!(e.message.contains("hole count"), "{e}");
    }

    #[test]
    fn segment_index_out_of_range_is_an_error() {
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 1 4\n0\n");
        assert_eq!(e.line, 6);
        assert_eq!(
            e.message,
            "segment 1: second endpoint 4 is out of range: vertices are numbered 1 to 3"
        );
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 -9223372036854775808 2\n0\n");
        assert!(e.message.contains("out of range"), "{e}");
        // Base 1: index 0 is out of range too.
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 0 2\n0\n");
        assert!(
            e.message.contains("first endpoint 0 is out of range"),
            "{e}"
        );
    }

    #[test]
    fn truncated_file_is_an_error() {
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2\n");
        assert_eq!(e.line, 6);
        assert!(
            e.message
                .contains("unexpected end of file: expected segment 2 of 3"),
            "{e}"
        );
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n");
        assert!(e.message.contains("hole count"), "{e}");
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n2\n1 0.5 0.5\n");
        assert!(e.message.contains("hole 2 of 2"), "{e}");
    }

    #[test]
    fn region_without_attribute_is_an_error() {
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n0\n1\n1 0.2 0.2\n");
        assert_eq!(e.message, "region 1: missing regional attribute");
    }

    #[test]
    fn trailing_data_is_an_error() {
        let e = err("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n0\n0\n5 5\n");
        assert_eq!(e.line, 8);
        assert!(e.message.contains("unexpected data"), "{e}");
        let e = parse_node("1\n1 0 0\n2 1 0\n", "t.node").unwrap_err();
        assert_eq!(e.line, 3);
    }

    #[test]
    fn huge_count_in_a_short_file_fails_cleanly() {
        let e = err("4000000000 2 0 0\n1 0 0\n");
        assert!(e.message.contains("unexpected end of file"), "{e}");
        let e = err("9999999999999 2 0 0\n1 0 0\n");
        assert!(e.message.contains("too many vertices"), "{e}");
        // Vertex ids are u32 below NONE (as in 3D): 2^32 - 1 vertices are one too many.
        let e = err("4294967295 2 0 0\n1 0 0\n");
        assert!(
            e.message.contains("at most 4294967294 are supported"),
            "{e}"
        );
    }

    #[test]
    fn mangled_files_give_errors_not_panics() {
        // Deterministic pseudo-random edits of a valid file: every outcome must be Ok or a
        // ParseError with a line inside the file.
        let base = SQUARE_HOLE_1BASED.as_bytes();
        let lines = SQUARE_HOLE_1BASED.lines().count();
        let pieces: [&[u8]; 8] = [b"", b" ", b"\n", b"#", b"-", b"9", b"1e400", b"x"];
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = |m: usize| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            ((state >> 33) as usize) % m
        };
        let mut errors = 0;
        for _ in 0..3000 {
            let mut text = base.to_vec();
            for _ in 0..1 + next(3) {
                let at = next(text.len() + 1);
                let cut = next(4).min(text.len() - at.min(text.len()));
                let piece = pieces[next(pieces.len())];
                text.splice(at..at + cut, piece.iter().copied());
            }
            let text = String::from_utf8_lossy(&text).into_owned();
            if let Err(e) = parse_poly(&text, "m.poly", || Err(ParseError::new("m.node", 0, "x"))) {
                errors += 1;
                assert!(e.line <= lines + 3, "{e}");
            }
        }
        assert!(
            errors > 100,
            "the edits should break many files, broke {errors}"
        );
    }

    #[test]
    fn parses_ele_and_checks_corners() {
        let d = parse_ele("2 3 1\n1 1 2 3 0.5\n2 3 2 4 -1\n", "t.ele", 1, 4).unwrap();
        assert_eq!(d.triangles, vec![[0, 1, 2], [2, 1, 3]]);
        assert_eq!(d.attributes, vec![0.5, -1.0]);
        let e = parse_ele("1 3 0\n1 1 2 5\n", "t.ele", 1, 4).unwrap_err();
        assert!(e.message.contains("corner 5 is out of range"), "{e}");
        let e = parse_ele("1 4 0\n", "t.ele", 1, 4).unwrap_err();
        assert!(e.message.contains("3 or 6 nodes"), "{e}");
    }

    #[test]
    fn area_files_give_one_bound_per_triangle_and_errors_name_file_and_line() {
        let a = parse_area("# bounds\n3\n1 0.5\n2 -1\n3 0.25 # last\n", "m.area", 3).unwrap();
        assert_eq!(a, vec![0.5, -1.0, 0.25]);
        let e = parse_area("3\n1 0.5\n2 x\n3 1\n", "m.area", 3)
            .unwrap_err()
            .to_string();
        assert!(e.contains("m.area:3") && e.contains("maximum area"), "{e}");
        let e = parse_area("2\n1 0.5\n2 1\n", "m.area", 3)
            .unwrap_err()
            .to_string();
        assert!(e.contains("2 area bounds for 3 triangles"), "{e}");
        let e = parse_area("2\n1 0.5\n", "m.area", 2)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("end of file") && e.contains("triangle 2 of 2"),
            "{e}"
        );
        let e = parse_area("1\n1 0.5\n2 1\n", "m.area", 1)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("m.area:3") && e.contains("unexpected data"),
            "{e}"
        );
    }

    #[test]
    fn six_node_triangles_keep_their_corners() {
        let ele = "1 6 1\n1 1 2 3 4 5 6 7.5\n";
        let e = parse_ele(ele, "m.ele", 1, 6).unwrap();
        assert_eq!(e.triangles, vec![[0, 1, 2]]);
        assert_eq!(e.attributes, vec![7.5]);
        let err = parse_ele(ele, "m.ele", 1, 5).unwrap_err().to_string();
        assert!(err.contains("node 6 is out of range"), "{err}");
        let err = parse_ele("1 4\n1 1 2 3 4\n", "m.ele", 1, 6)
            .unwrap_err()
            .to_string();
        assert!(err.contains("3 or 6 nodes"), "{err}");
    }
}
