//! Pictures of meshes and of their quality, as SVG and PNG (`idmesh show`).
//!
//! A [`Picture`] is a list of flat shapes (filled polygons, lines, text) in pixel coordinates,
//! made once and drawn by two back ends: [`Picture::to_svg`] and [`Picture::to_png`] (an own
//! scan-line rasterizer, so that the same picture gives the same pixels on every machine; the
//! PNG leaves the text out: it carries no fonts).
//!
//! * A 2D mesh: every triangle filled by its smallest angle (red at 0°, yellow at 30°, green
//!   at 60°), subsegments in black, hole seeds as red crosses, and beside it the histogram of
//!   the smallest angles (5° bins).
//! * A 3D mesh: its boundary surface seen along a direction (orthographic, nearer faces drawn
//!   last), or the surface of the tetrahedra on one side of a cut plane seen from the plane;
//!   each face filled by the smallest dihedral angle of its tetrahedron (red at 0°, green at
//!   the regular tetrahedron's 70.5°) and shaded by its slope, and beside it the histogram of
//!   all dihedral angles (10° bins).

use std::fmt::Write as _;

use crate::geometry::{tet_dihedrals, triangle_angles_deg};
use crate::mesh2d::TriMesh;
use crate::mesh3d::{TetMesh, NONE};

/// An RGB colour.
type Rgb = [u8; 3];

const BLACK: Rgb = [0, 0, 0];
const EDGE: Rgb = [60, 60, 60];
const RED: Rgb = [215, 48, 39];
const WHITE: Rgb = [255, 255, 255];

/// Side of the square the mesh is drawn in, and the width of the histogram panel (pixels).
const MESH_PX: f64 = 560.0;
const PANEL_PX: f64 = 260.0;
const MARGIN: f64 = 20.0;

/// Above this many cells, cell edges are not drawn (they would hide the colours).
const MAX_STROKED: usize = 20_000;

/// One shape of a picture, in pixel coordinates (y downwards).
#[derive(Debug, Clone)]
enum Shape {
    Poly {
        pts: Vec<[f64; 2]>,
        fill: Rgb,
        stroke: Option<Rgb>,
    },
    Line {
        a: [f64; 2],
        b: [f64; 2],
        color: Rgb,
        width: f64,
    },
    Text {
        at: [f64; 2],
        size: f64,
        text: String,
        anchor: &'static str,
    },
}

/// How a 3D mesh is seen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum View {
    /// The boundary surface, seen looking along this direction.
    Along([f64; 3]),
    /// The tetrahedra whose centroid has coordinate `axis` at most `at`, seen from the cut
    /// plane (looking along the negative axis).
    Cut {
        /// 0, 1 or 2 for x, y, z.
        axis: usize,
        /// Where the plane cuts that axis.
        at: f64,
    },
}

impl Default for View {
    fn default() -> Self {
        View::Along([-1.0, 2.0, -1.5])
    }
}

impl View {
    /// Parses `--view x,y,z` (a direction) or `--cut x=0.5` style text: `x=0.5`, `y=-1`, `z=2`.
    pub fn parse_cut(text: &str) -> Result<View, String> {
        let (axis, at) = text
            .split_once('=')
            .ok_or_else(|| format!("bad cut '{text}': expected e.g. x=0.5"))?;
        let axis = match axis.trim() {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            a => return Err(format!("bad cut axis '{a}': expected x, y or z")),
        };
        let at: f64 = at
            .trim()
            .parse()
            .map_err(|_| format!("bad cut position '{at}'"))?;
        if !at.is_finite() {
            return Err(format!("bad cut position '{at}'"));
        }
        Ok(View::Cut { axis, at })
    }

    /// Parses a view direction `x,y,z` (not all zero).
    pub fn parse_direction(text: &str) -> Result<View, String> {
        let v: Vec<f64> = text
            .split(',')
            .map(|s| s.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("bad view direction '{text}': expected x,y,z"))?;
        match v[..] {
            [x, y, z]
                if [x, y, z].iter().all(|c| c.is_finite())
                    && (x != 0.0 || y != 0.0 || z != 0.0) =>
            {
                Ok(View::Along([x, y, z]))
            }
            _ => Err(format!(
                "bad view direction '{text}': expected three numbers, not all 0"
            )),
        }
    }
}

/// A picture: shapes on a canvas of `width` × `height` pixels.
#[derive(Debug, Clone)]
pub struct Picture {
    width: f64,
    height: f64,
    shapes: Vec<Shape>,
}

/// The colour of a quality `t` in `[0, 1]`: red, yellow, green.
fn ramp(t: f64) -> Rgb {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (a, b, s) = if t < 0.5 {
        (RED, [254, 224, 139], t / 0.5)
    } else {
        ([254, 224, 139], [26, 152, 80], (t - 0.5) / 0.5)
    };
    [0, 1, 2].map(|k| (a[k] as f64 + (b[k] as f64 - a[k] as f64) * s).round() as u8)
}

fn shade(c: Rgb, f: f64) -> Rgb {
    c.map(|x| (x as f64 * f).round().clamp(0.0, 255.0) as u8)
}

/// Maps points of a bounding box into the mesh square (y up in the mesh, down on screen).
struct Fit {
    lo: [f64; 2],
    scale: f64,
    off: [f64; 2],
}

impl Fit {
    fn new(pts: impl Iterator<Item = [f64; 2]>) -> Fit {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in pts {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if lo[0] > hi[0] {
            (lo, hi) = ([0.0; 2], [1.0; 2]);
        }
        let ext = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let scale = if ext > 0.0 {
            (MESH_PX - 2.0 * MARGIN) / ext
        } else {
            1.0
        };
        let off = [
            MARGIN + 0.5 * ((MESH_PX - 2.0 * MARGIN) - (hi[0] - lo[0]) * scale),
            MARGIN + 0.5 * ((MESH_PX - 2.0 * MARGIN) - (hi[1] - lo[1]) * scale),
        ];
        Fit { lo, scale, off }
    }

    fn map(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.off[0] + (p[0] - self.lo[0]) * self.scale,
            MESH_PX - (self.off[1] + (p[1] - self.lo[1]) * self.scale),
        ]
    }
}

impl Picture {
    fn new() -> Picture {
        Picture {
            width: MESH_PX + PANEL_PX,
            height: MESH_PX,
            shapes: Vec::new(),
        }
    }

    /// A 2D mesh filled by smallest angle, its subsegments, the hole seeds `holes`, and the
    /// histogram of smallest angles.
    pub fn of_tri_mesh(mesh: &TriMesh, holes: &[[f64; 2]]) -> Picture {
        let mut pic = Picture::new();
        let fit = Fit::new(mesh.vertices.iter().copied());
        let stroke = (mesh.triangles.len() <= MAX_STROKED).then_some(EDGE);
        let mut mins = Vec::with_capacity(mesh.triangles.len());
        for t in &mesh.triangles {
            let c = t.map(|v| mesh.vertices[v as usize]);
            let a = triangle_angles_deg(c[0], c[1], c[2]);
            let m = a[0].min(a[1]).min(a[2]);
            mins.push(m);
            pic.shapes.push(Shape::Poly {
                pts: c.iter().map(|&p| fit.map(p)).collect(),
                fill: ramp(m / 60.0),
                stroke,
            });
        }
        for s in &mesh.segments {
            let [a, b] = s.map(|v| fit.map(mesh.vertices[v as usize]));
            pic.shapes.push(Shape::Line {
                a,
                b,
                color: BLACK,
                width: 1.5,
            });
        }
        for &h in holes {
            let c = fit.map(h);
            for (dx, dy) in [(5.0, 5.0), (5.0, -5.0)] {
                let (a, b) = ([c[0] - dx, c[1] - dy], [c[0] + dx, c[1] + dy]);
                pic.shapes.push(Shape::Line {
                    a,
                    b,
                    color: RED,
                    width: 2.0,
                });
            }
        }
        pic.histogram(
            &mins,
            60.0,
            5.0,
            60.0,
            "smallest angle of each triangle (degrees)",
        );
        pic
    }

    /// A 3D mesh's surface (or cut) filled by the smallest dihedral angle of each face's
    /// tetrahedron, and the histogram of all dihedral angles.
    pub fn of_tet_mesh(mesh: &TetMesh, view: View) -> Picture {
        let mut pic = Picture::new();
        let corners = |t: usize| mesh.tets[t].map(|v| mesh.vertices[v as usize]);
        let keep: Vec<bool> = match view {
            View::Along(_) => vec![true; mesh.tets.len()],
            View::Cut { axis, at } => (0..mesh.tets.len())
                .map(|t| corners(t).iter().map(|p| p[axis]).sum::<f64>() * 0.25 <= at)
                .collect(),
        };
        let d = match view {
            View::Along(d) => {
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                d.map(|x| x / n)
            }
            View::Cut { axis, .. } => {
                let mut d = [0.0; 3];
                d[axis] = -1.0;
                d
            }
        };
        // Screen axes: u horizontal, v up, both orthogonal to the view direction.
        let up = if d[2].abs() < 0.9 {
            [0.0, 0.0, 1.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let u = normalize(cross(d, up));
        let v = cross(u, d);
        let screen = |p: [f64; 3]| [dot(p, u), dot(p, v)];

        let mut all_angles = Vec::with_capacity(mesh.tets.len() * 6);
        let mut worst = Vec::with_capacity(mesh.tets.len());
        for t in 0..mesh.tets.len() {
            let a = tet_dihedrals(corners(t));
            all_angles.extend(a);
            worst.push(a.iter().copied().fold(180.0, f64::min));
        }
        // Faces on the surface of the kept tets: (depth, screen corners, colour).
        let mut faces: Vec<(f64, [[f64; 2]; 3], Rgb)> = Vec::new();
        for t in (0..mesh.tets.len()).filter(|&t| keep[t]) {
            let c = corners(t);
            for i in 0..4 {
                let n = mesh.neighbors[t][i];
                if n != NONE && keep[n as usize] {
                    continue;
                }
                let f = [0, 1, 2, 3].map(|k| c[k]);
                let tri = [f[(i + 1) % 4], f[(i + 2) % 4], f[(i + 3) % 4]];
                // Outward normal: away from the opposite corner.
                let mut nrm = normalize(cross(sub(tri[1], tri[0]), sub(tri[2], tri[0])));
                if dot(nrm, sub(c[i], tri[0])) > 0.0 {
                    nrm = nrm.map(|x| -x);
                }
                let facing = -dot(nrm, d);
                if facing <= 0.0 {
                    continue; // seen from behind: hidden by the front of the surface
                }
                let depth = tri.iter().map(|&p| dot(p, d)).sum::<f64>();
                let color = shade(ramp(worst[t] / 70.528_779), 0.55 + 0.45 * facing);
                faces.push((depth, tri.map(screen), color));
            }
        }
        // Painter's order: the farthest (largest depth along the view) first.
        faces.sort_by(|a, b| b.0.total_cmp(&a.0));
        let fit = Fit::new(faces.iter().flat_map(|f| f.1));
        let stroke = (faces.len() <= MAX_STROKED).then_some(EDGE);
        for (_, tri, fill) in faces {
            pic.shapes.push(Shape::Poly {
                pts: tri.iter().map(|&p| fit.map(p)).collect(),
                fill,
                stroke,
            });
        }
        pic.histogram(
            &all_angles,
            180.0,
            10.0,
            70.528_779,
            "dihedral angles of all tetrahedra (degrees)",
        );
        pic
    }

    /// A histogram of `values` in `[0, max]` with bins of `bin`, bars coloured by the bin's
    /// quality (`good` is the value coloured green), in the panel right of the mesh.
    fn histogram(&mut self, values: &[f64], max: f64, bin: f64, good: f64, title: &str) {
        let nb = (max / bin).round() as usize;
        let mut counts = vec![0usize; nb];
        for &x in values {
            if x.is_finite() {
                counts[((x / bin).floor().max(0.0) as usize).min(nb - 1)] += 1;
            }
        }
        let top = counts.iter().copied().max().unwrap_or(0).max(1) as f64;
        let (x0, y0, w, h) = (MESH_PX + 20.0, 60.0, PANEL_PX - 40.0, MESH_PX - 120.0);
        self.shapes.push(Shape::Poly {
            pts: vec![[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]],
            fill: WHITE,
            stroke: Some(EDGE),
        });
        let bw = w / nb as f64;
        for (i, &c) in counts.iter().enumerate() {
            if c == 0 {
                continue;
            }
            let bh = h * c as f64 / top;
            let x = x0 + i as f64 * bw;
            let mid = (i as f64 + 0.5) * bin;
            // Angles above the ideal are as bad as their distance to 180 (dihedral) or are
            // impossible (triangle angles above 60 are not smallest angles).
            let q = if mid <= good {
                mid / good
            } else {
                (max - mid) / (max - good)
            };
            self.shapes.push(Shape::Poly {
                pts: vec![
                    [x, y0 + h - bh],
                    [x + bw, y0 + h - bh],
                    [x + bw, y0 + h],
                    [x, y0 + h],
                ],
                fill: ramp(q),
                stroke: Some(EDGE),
            });
        }
        let t = |at: [f64; 2], size: f64, text: String, anchor: &'static str| Shape::Text {
            at,
            size,
            text,
            anchor,
        };
        self.shapes.push(t(
            [x0 + w / 2.0, y0 - 30.0],
            12.0,
            title.to_string(),
            "middle",
        ));
        self.shapes.push(t(
            [x0 + w / 2.0, y0 - 12.0],
            11.0,
            format!("{} values, tallest bar {}", values.len(), top as usize),
            "middle",
        ));
        for k in 0..=4 {
            let v = max * k as f64 / 4.0;
            self.shapes.push(t(
                [x0 + w * k as f64 / 4.0, y0 + h + 16.0],
                11.0,
                format!("{v}"),
                "middle",
            ));
        }
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if lo <= hi {
            self.shapes.push(t(
                [x0, y0 + h + 40.0],
                11.0,
                format!("min {lo:.2}, max {hi:.2}"),
                "start",
            ));
        }
    }

    /// The picture as an SVG document.
    pub fn to_svg(&self) -> String {
        let mut s = String::with_capacity(64 * self.shapes.len() + 256);
        let _ = writeln!(
            s,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">",
            w = self.width,
            h = self.height
        );
        let _ = writeln!(s, "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>");
        let hex = |c: Rgb| format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
        for sh in &self.shapes {
            match sh {
                Shape::Poly { pts, fill, stroke } => {
                    s.push_str("<polygon points=\"");
                    for (i, p) in pts.iter().enumerate() {
                        let _ =
                            write!(s, "{}{:.2},{:.2}", if i > 0 { " " } else { "" }, p[0], p[1]);
                    }
                    let _ = write!(s, "\" fill=\"{}\"", hex(*fill));
                    match stroke {
                        Some(c) => {
                            let _ = writeln!(s, " stroke=\"{}\" stroke-width=\"0.4\"/>", hex(*c));
                        }
                        None => {
                            let _ =
                                writeln!(s, " stroke=\"{}\" stroke-width=\"0.3\"/>", hex(*fill));
                        }
                    }
                }
                Shape::Line { a, b, color, width } => {
                    let _ = writeln!(
                        s,
                        "<line x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\" stroke=\"{}\" stroke-width=\"{width}\"/>",
                        a[0],
                        a[1],
                        b[0],
                        b[1],
                        hex(*color)
                    );
                }
                Shape::Text {
                    at,
                    size,
                    text,
                    anchor,
                } => {
                    let text = text
                        .replace('&', "&amp;")
                        .replace('<', "&lt;")
                        .replace('>', "&gt;");
                    let _ = writeln!(
                        s,
                        "<text x=\"{:.1}\" y=\"{:.1}\" font-family=\"sans-serif\" font-size=\"{size}\" text-anchor=\"{anchor}\">{text}</text>",
                        at[0], at[1]
                    );
                }
            }
        }
        s.push_str("</svg>\n");
        s
    }

    /// The picture rasterized (text left out): width, height and RGB rows.
    pub fn raster(&self) -> (usize, usize, Vec<u8>) {
        let (w, h) = (self.width.ceil() as usize, self.height.ceil() as usize);
        let mut img = vec![255u8; w * h * 3];
        for sh in &self.shapes {
            match sh {
                Shape::Poly { pts, fill, stroke } => {
                    fill_polygon(&mut img, w, h, pts, *fill);
                    if let Some(c) = stroke {
                        for i in 0..pts.len() {
                            draw_line(&mut img, w, h, pts[i], pts[(i + 1) % pts.len()], 0.6, *c);
                        }
                    }
                }
                Shape::Line { a, b, color, width } => {
                    draw_line(&mut img, w, h, *a, *b, *width, *color)
                }
                Shape::Text { .. } => {}
            }
        }
        (w, h, img)
    }

    /// The picture as a PNG file (text left out).
    pub fn to_png(&self) -> Result<Vec<u8>, String> {
        let (w, h, img) = self.raster();
        let mut out = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut out, w as u32, h as u32);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            let mut wr = enc.write_header().map_err(|e| e.to_string())?;
            wr.write_image_data(&img).map_err(|e| e.to_string())?;
        }
        Ok(out)
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn normalize(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    if n > 0.0 {
        a.map(|x| x / n)
    } else {
        a
    }
}

/// Fills a polygon (even-odd rule) sampling pixel centres, row by row.
fn fill_polygon(img: &mut [u8], w: usize, h: usize, pts: &[[f64; 2]], c: Rgb) {
    if pts.len() < 3 {
        return;
    }
    let ymin = pts
        .iter()
        .map(|p| p[1])
        .fold(f64::INFINITY, f64::min)
        .max(0.0);
    let ymax = pts
        .iter()
        .map(|p| p[1])
        .fold(f64::NEG_INFINITY, f64::max)
        .min(h as f64);
    if ymin >= ymax || ymin.is_nan() || ymax.is_nan() {
        return;
    }
    let mut xs: Vec<f64> = Vec::with_capacity(8);
    for row in (ymin.floor() as usize)..(ymax.ceil() as usize).min(h) {
        let y = row as f64 + 0.5;
        xs.clear();
        for i in 0..pts.len() {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            if (a[1] <= y) != (b[1] <= y) {
                xs.push(a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
            }
        }
        xs.sort_by(f64::total_cmp);
        for pair in xs.chunks_exact(2) {
            let x0 = (pair[0] - 0.5).ceil().max(0.0) as usize;
            let x1 = ((pair[1] - 0.5).floor() + 1.0).clamp(0.0, w as f64) as usize;
            for x in x0..x1.min(w) {
                let k = 3 * (row * w + x);
                img[k..k + 3].copy_from_slice(&c);
            }
        }
    }
}

/// Draws a line of `width` pixels as a thin quadrilateral.
fn draw_line(img: &mut [u8], w: usize, h: usize, a: [f64; 2], b: [f64; 2], width: f64, c: Rgb) {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    if len == 0.0 {
        return;
    }
    let half = 0.5 * width.max(1.0);
    let n = [-d[1] / len * half, d[0] / len * half];
    let quad = [
        [a[0] + n[0], a[1] + n[1]],
        [b[0] + n[0], b[1] + n[1]],
        [b[0] - n[0], b[1] - n[1]],
        [a[0] - n[0], a[1] - n[1]],
    ];
    fill_polygon(img, w, h, &quad, c);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_runs_red_yellow_green() {
        assert_eq!(ramp(0.0), RED);
        assert_eq!(ramp(0.5), [254, 224, 139]);
        assert_eq!(ramp(1.0), [26, 152, 80]);
        assert_eq!(ramp(f64::NAN), RED);
    }

    #[test]
    fn dihedrals_of_the_regular_and_corner_tetrahedra() {
        let s = 1.0 / 2f64.sqrt();
        let reg = [
            [1.0, 0.0, -s],
            [-1.0, 0.0, -s],
            [0.0, 1.0, s],
            [0.0, -1.0, s],
        ];
        for a in tet_dihedrals(reg) {
            assert!((a - 70.528_779).abs() < 1e-6, "{a}");
        }
        let corner = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let mut a = tet_dihedrals(corner);
        a.sort_by(f64::total_cmp);
        assert!(
            (a[0] - 54.735_610).abs() < 1e-6 && (a[5] - 90.0).abs() < 1e-9,
            "{a:?}"
        );
        let (lo, hi) = crate::geometry::tet_dihedral_range(corner);
        assert!((lo - a[0]).abs() < 1e-6 && (hi - a[5]).abs() < 1e-6);
    }

    #[test]
    fn fill_covers_pixel_centres_inside_only() {
        let (w, h) = (10, 10);
        let mut img = vec![255u8; w * h * 3];
        fill_polygon(
            &mut img,
            w,
            h,
            &[[2.0, 2.0], [6.0, 2.0], [6.0, 5.0], [2.0, 5.0]],
            BLACK,
        );
        let black = img.chunks(3).filter(|p| p == &BLACK).count();
        assert_eq!(black, 4 * 3);
        assert_eq!(&img[3 * (2 * w + 2)..3 * (2 * w + 2) + 3], &BLACK);
        assert_eq!(&img[3 * (5 * w + 2)..3 * (5 * w + 2) + 3], &WHITE);
    }

    #[test]
    fn views_parse() {
        assert_eq!(View::parse_cut("x=0.5"), Ok(View::Cut { axis: 0, at: 0.5 }));
        assert!(View::parse_cut("w=1").is_err());
        assert!(View::parse_cut("z=nan").is_err());
        assert_eq!(
            View::parse_direction("1,0,-2"),
            Ok(View::Along([1.0, 0.0, -2.0]))
        );
        assert!(View::parse_direction("0,0,0").is_err());
        assert!(View::parse_direction("1,2").is_err());
    }
}
