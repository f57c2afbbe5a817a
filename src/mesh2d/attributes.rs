//! Point attributes on the output mesh (Triangle's `numberofpointattributes`, the extra
//! columns of a `.node` file): input vertices keep theirs, Steiner vertices get them
//! interpolated linearly, as Triangle does while it inserts them.
//!
//! The interpolation is done after meshing, from the input alone, so the mesher carries no
//! attributes: a Steiner vertex on a subsegment chain of an input segment is interpolated
//! along that segment between the chain's end vertices; any other Steiner vertex
//! barycentrically in the triangle of the Delaunay triangulation of the input points (made by
//! the 2D mesher itself) that contains it. Both are exact for attributes that are linear
//! functions of the coordinates, which is what Triangle's interpolation guarantees too; for
//! other attributes the values differ from Triangle's (which interpolates in the triangle of
//! the mesh being refined), as both are interpolations.

use crate::error::Error;
use crate::geometry::locate_in_simplices;
use crate::input2d::Pslg;
use crate::predicates::orient2d;

use super::{triangulate, Options, TriMesh};

/// The attributes of every vertex of `mesh`, `per_point` per vertex, vertex by vertex:
/// `values` (`per_point` per input point, `mesh.num_input_vertices` points) for the input
/// vertices, interpolated linearly for Steiner vertices (see the module documentation).
/// A Steiner vertex that lies in no triangle of the input points' triangulation (possible only
/// through rounding at the hull) takes the values of the nearest input point.
pub fn interpolate_point_attributes(
    mesh: &TriMesh,
    per_point: usize,
    values: &[f64],
) -> Result<Vec<f64>, Error> {
    let ni = mesh.num_input_vertices.min(mesh.vertices.len());
    let nv = mesh.vertices.len();
    let k = per_point;
    if values.len() != ni * k {
        return Err(Error::InvalidOption(format!(
            "{} point attribute values given for {ni} points with {k} attributes each",
            values.len()
        )));
    }
    let mut out = vec![0.0; nv * k];
    out[..ni * k].copy_from_slice(values);
    if k == 0 || nv == ni {
        return Ok(out);
    }
    // The subsegment graph: a Steiner vertex with exactly two subsegments lies inside one
    // input segment (crossing points have four).
    let mut seg_nbrs: Vec<Vec<u32>> = vec![Vec::new(); nv - ni];
    for s in &mesh.segments {
        for (a, b) in [(s[0], s[1]), (s[1], s[0])] {
            if a as usize >= ni {
                seg_nbrs[a as usize - ni].push(b);
            }
        }
    }
    let on_chain = |v: usize| v >= ni && seg_nbrs[v - ni].len() == 2;
    // First the vertices off segment chains, barycentrically in the input's triangulation.
    let input = &mesh.vertices[..ni];
    let mut dt: Option<TriMesh> = None;
    let mut hint = 0u32;
    for v in (ni..nv).filter(|&v| !on_chain(v)) {
        if dt.is_none() {
            let pslg = Pslg {
                points: input.to_vec(),
                ..Pslg::default()
            };
            dt = Some(triangulate(&pslg, &Options::default()).map_err(|e| {
                Error::InvalidOption(format!(
                    "point attributes: cannot triangulate the input points: {e}"
                ))
            })?);
        }
        let dt = dt.as_ref().expect("built above");
        let p = mesh.vertices[v];
        let (dst, src) = out.split_at_mut(v * k);
        let dst_row = &mut src[..k];
        match locate_in_simplices(&dt.neighbors, |t| sub_areas(dt, t, p), &mut hint) {
            Some((t, w)) => {
                for (a, o) in dst_row.iter_mut().enumerate() {
                    *o = (0..3)
                        .map(|i| w[i] * dst[dt.triangles[t][i] as usize * k + a])
                        .sum();
                }
            }
            None => {
                let near = nearest(input, p);
                dst_row.copy_from_slice(&dst[near * k..near * k + k]);
            }
        }
    }
    // Then the vertices inside a segment: along the chain to its two ends.
    for v in (ni..nv).filter(|&v| on_chain(v)) {
        let nb = &seg_nbrs[v - ni];
        let (a, b) = (
            walk(&seg_nbrs, ni, v, nb[0]) as usize,
            walk(&seg_nbrs, ni, v, nb[1]) as usize,
        );
        let (pa, pb, p) = (mesh.vertices[a], mesh.vertices[b], mesh.vertices[v]);
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let t = if len2 > 0.0 {
            (((p[0] - pa[0]) * d[0] + (p[1] - pa[1]) * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        for i in 0..k {
            // The ends are input or off-chain vertices, whose values are final.
            out[v * k + i] = (1.0 - t) * out[a * k + i] + t * out[b * k + i];
        }
    }
    Ok(out)
}

/// Follows the subsegment chain from Steiner vertex `from` through `next` until a vertex that
/// is not a two-subsegment Steiner vertex (an input vertex or a crossing), which it returns.
fn walk(seg_nbrs: &[Vec<u32>], ni: usize, from: usize, mut next: u32) -> u32 {
    let mut prev = from as u32;
    // A chain visits each Steiner vertex once; the budget only guards a closed loop of Steiner
    // vertices, which a mesh of input segments cannot have.
    for _ in 0..seg_nbrs.len() + 1 {
        let n = next as usize;
        if n < ni || seg_nbrs[n - ni].len() != 2 {
            return next;
        }
        let nb = &seg_nbrs[n - ni];
        let step = if nb[0] == prev { nb[1] } else { nb[0] };
        prev = next;
        next = step;
    }
    next
}

/// The input point nearest to `p`.
fn nearest(points: &[[f64; 2]], p: [f64; 2]) -> usize {
    let d2 = |q: &[f64; 2]| (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
    (0..points.len())
        .min_by(|&i, &j| d2(&points[i]).total_cmp(&d2(&points[j])))
        .unwrap_or(0)
}

/// The areas (twice, approximate; exact signs) of the triangles `p` makes with each edge of
/// triangle `t`: all non-negative exactly when `p` is in the closed triangle.
fn sub_areas(dt: &TriMesh, t: usize, p: [f64; 2]) -> [f64; 3] {
    let c = dt.triangles[t].map(|v| dt.vertices[v as usize]);
    std::array::from_fn(|i| orient2d(c[(i + 1) % 3], c[(i + 2) % 3], p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input2d::Region;

    /// Two attributes, linear in x and y, at every vertex.
    fn linear(p: [f64; 2]) -> [f64; 2] {
        [2.0 * p[0] - 3.0 * p[1] + 1.0, 0.5 * p[1] - 7.0]
    }

    fn check_linear(mesh: &TriMesh, got: &[f64]) {
        assert_eq!(got.len(), 2 * mesh.vertices.len());
        for (v, p) in mesh.vertices.iter().enumerate() {
            let want = linear(*p);
            for a in 0..2 {
                let err = (got[2 * v + a] - want[a]).abs();
                assert!(
                    err <= 1e-12 * (1.0 + want[a].abs()),
                    "vertex {v} {p:?}: {got:?}"
                );
            }
        }
    }

    #[test]
    fn linear_attributes_are_reproduced_at_steiner_points() {
        // A concave polygon (an L) with an inner segment and a hole: Steiner points land on
        // boundary segments, on the inner segment and inside.
        let points = vec![
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
            [0.2, 0.2],
            [0.8, 2.5],
            [2.0, 0.3],
            [2.2, 0.3],
            [2.2, 0.6],
            [2.0, 0.6],
        ];
        let mut segments: Vec<[u32; 2]> = (0..6).map(|i| [i, (i + 1) % 6]).collect();
        segments.push([6, 7]);
        segments.extend((0..4).map(|i| [8 + i, 8 + (i + 1) % 4]));
        let pslg = Pslg {
            points: points.clone(),
            segments,
            holes: vec![[2.1, 0.45]],
            regions: vec![Region {
                point: [0.5, 0.5],
                attribute: 1.0,
                max_area: None,
            }],
            ..Pslg::default()
        };
        let opts = Options {
            min_angle: Some(30.0),
            max_area: Some(0.01),
            ..Options::default()
        };
        let mesh = triangulate(&pslg, &opts).unwrap();
        assert!(mesh.vertices.len() > points.len() + 100);
        let values: Vec<f64> = points.iter().flat_map(|&p| linear(p)).collect();
        let got = interpolate_point_attributes(&mesh, 2, &values).unwrap();
        assert_eq!(got[..values.len()], values[..], "input values kept exactly");
        check_linear(&mesh, &got);
    }

    #[test]
    fn segment_points_interpolate_along_their_segment_only() {
        // A square whose bottom side is split: the attribute is 0 at every corner but 1 at
        // (1, 0). A split point of the bottom side must get the value along that side (between
        // 0 and 1 by its position), not a triangle's.
        let points = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let segments: Vec<[u32; 2]> = (0..4).map(|i| [i, (i + 1) % 4]).collect();
        let pslg = Pslg {
            points,
            segments,
            ..Pslg::default()
        };
        let opts = Options {
            max_area: Some(0.02),
            ..Options::default()
        };
        let mesh = triangulate(&pslg, &opts).unwrap();
        let got = interpolate_point_attributes(&mesh, 1, &[0.0, 1.0, 0.0, 0.0]).unwrap();
        let mut bottom = 0;
        for (v, p) in mesh.vertices.iter().enumerate().skip(4) {
            if p[1] == 0.0 {
                bottom += 1;
                assert_eq!(got[v], p[0], "bottom side at {p:?}");
            } else if p[0] == 0.0 || p[1] == 1.0 {
                assert_eq!(got[v], 0.0, "side with both ends 0 at {p:?}");
            }
        }
        assert!(bottom > 0, "the bottom side was split");
    }

    #[test]
    fn wrong_value_count_is_an_error() {
        let pslg = Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            ..Pslg::default()
        };
        let mesh = triangulate(&pslg, &Options::default()).unwrap();
        let e = interpolate_point_attributes(&mesh, 2, &[0.0; 5]).unwrap_err();
        assert!(e.to_string().contains("5 point attribute values"), "{e}");
    }
}
