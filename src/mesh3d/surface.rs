//! Surface input as users have it: the repairs that turn a polygon surface mesh (`.off`,
//! `.ply`, `.stl`, `.mesh`, `.msh`, or the C API's `surface_input`) into a valid PLC, each
//! reported as a [`SurfaceWarning`] with its count. `.poly` and `.smesh` input is not
//! repaired: there, as in TetGen, the PLC is taken as given and any problem is an error.
//!
//! 1. **Duplicate vertices** (exactly equal coordinates, -0.0 equal to 0.0) are merged into
//!    the first of them; polygons then lose repeated consecutive corners.
//! 2. **Zero-area polygons** (every corner on one line, exact test; after merging, polygons
//!    with fewer than three corners) are dropped. Where a dropped polygon's corners lie inside
//!    an edge of another polygon (the T-junction a collapsed triangle leaves), they are
//!    inserted into that edge, so the surface stays closed.
//! 3. **Non-planar polygons** (a corner off the plane of three others, exact `orient3d`) are
//!    triangulated on their own vertices: projected along a coordinate axis in which the
//!    polygon is simple (tried in the order of the Newell normal's components, largest
//!    first, a floating-point choice that exact tests then confirm), as the constrained
//!    Delaunay triangulation of the polygon by the 2D kernel (exact orientation and
//!    in-circle tests, [`FacetTriangulation::polygon`]; `-Y` uses it too). The triangles are the
//!    graph of a piecewise linear function over a simple polygon, so they do not intersect
//!    each other. A polygon that is simple in no axis projection (or has more than
//!    [`MAX_CLIP`] corners) is refused: [`InputError::UntriangulablePolygon`].
//! 4. **Unreferenced vertices** (on no polygon and no segment) are dropped. TetGen keeps
//!    a `.node` file's points as isolated vertices; a surface file's stray vertices are
//!    usually left over from editing, and a point inside the volume would change the mesh.
//!
//! Output numbering: the repaired PLC's points are the input points that are kept (neither a
//! merged duplicate nor unreferenced), in input order, as TetGen numbers its output for such
//! files; [`SurfaceRepair::vertex_map`] and [`SurfaceRepair::point_origin`] relate the two
//! numberings and [`SurfaceRepair::input_error`] tells an error about the repaired PLC in the
//! input's numbering.
//!
//! Every decision is exact; floating point only orders the projection axes to try.

use std::fmt;

use crate::error::{Error, InputError, Item};
use crate::input3d::{by_coordinates, check_items, Facet, FacetTriangulation, Plc};
use crate::predicates::{collinear3 as collinear, orient2d, orient3d, proj};
use crate::NONE;

/// Non-planar polygons with more corners than this are refused rather than triangulated
/// (finding a projection in which the polygon is simple takes time quadratic in the corners).
pub const MAX_CLIP: usize = 2000;

/// One kind of repair made, with how often and the first item (0-based input numbering).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SurfaceWarning {
    /// Vertices with the coordinates of an earlier vertex were merged into it.
    DuplicateVertices {
        /// How many vertices were merged away.
        count: usize,
        /// The first merged vertex and the earlier vertex it was merged into.
        first: [usize; 2],
    },
    /// Polygons with all corners on one line (zero area) were dropped.
    ZeroAreaPolygons {
        /// How many.
        count: usize,
        /// The first (its facet index).
        first: usize,
    },
    /// Non-planar polygons were triangulated.
    NonPlanarPolygons {
        /// How many.
        count: usize,
        /// The first (its facet index).
        first: usize,
        /// How many triangles they became.
        triangles: usize,
    },
    /// Vertices on no polygon or segment were dropped.
    UnreferencedVertices {
        /// How many.
        count: usize,
        /// The first.
        first: usize,
    },
}

impl SurfaceWarning {
    /// The message, with item numbers shifted by `base` (a file's numbering base).
    pub fn message(&self, base: usize) -> String {
        let s = |n: usize| if n == 1 { "" } else { "s" };
        match *self {
            SurfaceWarning::DuplicateVertices { count, first } => format!(
                "{count} duplicate vertex{} merged (vertices with the coordinates of an earlier \
                 one, e.g. {} = {})",
                if count == 1 { "" } else { "es" },
                first[0] + base,
                first[1] + base
            ),
            SurfaceWarning::ZeroAreaPolygons { count, first } => format!(
                "{count} zero-area face{} (all corners on one line) dropped, e.g. face {}",
                s(count),
                first + base
            ),
            SurfaceWarning::NonPlanarPolygons {
                count,
                first,
                triangles,
            } => format!(
                "{count} non-planar face{} triangulated into {triangles} triangles, e.g. face {}",
                s(count),
                first + base
            ),
            SurfaceWarning::UnreferencedVertices { count, first } => format!(
                "{count} unreferenced vert{} (on no face) dropped, e.g. {}; output vertices are \
                 the kept input vertices in input order",
                if count == 1 { "ex" } else { "ices" },
                first + base
            ),
        }
    }
}

impl fmt::Display for SurfaceWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message(0))
    }
}

/// A repaired surface: the PLC to mesh, how its items relate to the input's, and what was
/// repaired.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceRepair {
    /// The repaired PLC (points, facets and segments renumbered; holes and regions as given).
    pub plc: Plc,
    /// Per input point: its index in `plc`, the index of the vertex it was merged into for a
    /// duplicate, or `NONE` when dropped as unreferenced.
    pub vertex_map: Vec<u32>,
    /// Per point of `plc`: its input index.
    pub point_origin: Vec<u32>,
    /// Per facet of `plc`: the input facet it comes from (a triangulated polygon gives
    /// several).
    pub facet_origin: Vec<u32>,
    /// What was repaired (empty when nothing was).
    pub warnings: Vec<SurfaceWarning>,
}

impl SurfaceRepair {
    /// An input error about [`SurfaceRepair::plc`] told in the input's numbering.
    pub fn input_error(&self, e: &InputError) -> InputError {
        e.map_items(&|kind, i| {
            let map = match kind {
                Item::Point => &self.point_origin,
                Item::Facet => &self.facet_origin,
                _ => return i,
            };
            map.get(i).map_or(i, |&o| o as usize)
        })
    }

    /// [`SurfaceRepair::input_error`] for any error (other kinds are kept as they are).
    pub fn error(&self, e: Error) -> Error {
        match e {
            Error::Input(ie) => Error::Input(self.input_error(&ie)),
            other => other,
        }
    }
}

/// Repairs a polygon surface (see the module documentation). Facets with one polygon and no
/// hole seeds are repaired; others only get their vertices renumbered. Fails as
/// [`check_plc`](crate::input3d::check_plc) does on bad items (too few points, non-finite
/// coordinates, indices out of range, empty polygons, a polygon listing an index twice),
/// and on non-planar polygons that cannot be triangulated; the other checks run on the
/// repaired PLC when it is meshed.
pub fn repair_surface(plc: &Plc) -> Result<SurfaceRepair, Error> {
    crate::error::catch_panic("repairing the surface: ", || repair(plc))
}

fn repair(plc: &Plc) -> Result<SurfaceRepair, Error> {
    check_items(plc)?;
    let pts = &plc.points;
    let canon = canonical_points(pts);
    let mut warnings = Vec::new();
    let dups: Vec<usize> = (0..pts.len()).filter(|&i| canon[i] as usize != i).collect();
    if let Some(&d) = dups.first() {
        warnings.push(SurfaceWarning::DuplicateVertices {
            count: dups.len(),
            first: [d, canon[d] as usize],
        });
    }
    let at = |v: u32| pts[v as usize];
    let mut facets: Vec<Facet> = Vec::with_capacity(plc.facets.len());
    let mut origin: Vec<u32> = Vec::with_capacity(plc.facets.len());
    let mut zero_area: Vec<usize> = Vec::new();
    let mut lines: Vec<Vec<u32>> = Vec::new();
    let mut non_planar: Vec<usize> = Vec::new();
    let mut triangles = 0usize;
    for (f, facet) in plc.facets.iter().enumerate() {
        let polygons: Vec<Vec<u32>> = facet
            .polygons
            .iter()
            .map(|p| {
                let q: Vec<u32> = p.iter().map(|&v| canon[v as usize]).collect();
                if p.len() >= 3 {
                    drop_repeats(q)
                } else {
                    q
                }
            })
            .collect();
        let single = facet.polygons.len() == 1 && facet.holes.is_empty();
        if !single || facet.polygons[0].len() < 3 {
            facets.push(Facet {
                polygons,
                ..facet.clone()
            });
            origin.push(f as u32);
            continue;
        }
        let poly = &polygons[0];
        let Some(plane) = plane_of(poly, &at) else {
            zero_area.push(f);
            if poly.len() >= 3 {
                lines.push(poly.clone());
            }
            continue;
        };
        let [a, b, c] = plane.map(at);
        if poly.iter().all(|&v| orient3d(a, b, c, at(v)) == 0.0) {
            facets.push(Facet {
                polygons,
                ..facet.clone()
            });
            origin.push(f as u32);
            continue;
        }
        let tris = triangulate_non_planar(poly, &at)
            .ok_or(Error::Input(InputError::UntriangulablePolygon { facet: f }))?;
        non_planar.push(f);
        triangles += tris.len();
        for t in tris {
            facets.push(Facet {
                polygons: vec![t.to_vec()],
                holes: Vec::new(),
                marker: facet.marker,
            });
            origin.push(f as u32);
        }
    }
    if let Some(&first) = zero_area.first() {
        warnings.push(SurfaceWarning::ZeroAreaPolygons {
            count: zero_area.len(),
            first,
        });
    }
    if let Some(&first) = non_planar.first() {
        warnings.push(SurfaceWarning::NonPlanarPolygons {
            count: non_planar.len(),
            first,
            triangles,
        });
    }
    if !lines.is_empty() {
        close_t_junctions(&mut facets, &lines, pts);
    }
    // Renumber: the kept points in input order.
    let mut used = vec![false; pts.len()];
    for v in facets
        .iter()
        .flat_map(|f| f.polygons.iter().flatten())
        .chain(plc.segments.iter().flatten())
    {
        used[canon[*v as usize] as usize] = true;
    }
    let mut new_id = vec![NONE; pts.len()];
    let mut point_origin = Vec::new();
    let mut unreferenced = Vec::new();
    for i in 0..pts.len() {
        if canon[i] as usize != i {
            continue;
        }
        if used[i] {
            new_id[i] = point_origin.len() as u32;
            point_origin.push(i as u32);
        } else {
            unreferenced.push(i);
        }
    }
    if let Some(&first) = unreferenced.first() {
        warnings.push(SurfaceWarning::UnreferencedVertices {
            count: unreferenced.len(),
            first,
        });
    }
    let vertex_map: Vec<u32> = (0..pts.len()).map(|i| new_id[canon[i] as usize]).collect();
    let renum = |v: &u32| vertex_map[*v as usize];
    for f in &mut facets {
        for p in &mut f.polygons {
            p.iter_mut().for_each(|v| *v = renum(v));
        }
    }
    let out = Plc {
        points: point_origin.iter().map(|&i| pts[i as usize]).collect(),
        point_markers: if plc.point_markers.len() == pts.len() {
            point_origin
                .iter()
                .map(|&i| plc.point_markers[i as usize])
                .collect()
        } else {
            plc.point_markers.clone()
        },
        segments: plc.segments.iter().map(|s| s.map(|v| renum(&v))).collect(),
        segment_markers: plc.segment_markers.clone(),
        facets,
        holes: plc.holes.clone(),
        regions: plc.regions.clone(),
    };
    Ok(SurfaceRepair {
        plc: out,
        vertex_map,
        point_origin,
        facet_origin: origin,
        warnings,
    })
}

/// Per point: the first point with exactly its coordinates (itself if none comes before).
fn canonical_points(pts: &[[f64; 3]]) -> Vec<u32> {
    let order = by_coordinates(pts);
    let mut canon: Vec<u32> = (0..pts.len() as u32).collect();
    let mut k = 0;
    while k < order.len() {
        let first = order[k];
        let mut j = k + 1;
        while j < order.len() && pts[order[j] as usize] == pts[first as usize] {
            canon[order[j] as usize] = first;
            j += 1;
        }
        k = j;
    }
    canon
}

/// A closed loop without consecutive repeated corners (the last and first included).
fn drop_repeats(mut q: Vec<u32>) -> Vec<u32> {
    q.dedup();
    while q.len() > 1 && q.first() == q.last() {
        q.pop();
    }
    q
}

/// Three corners of `poly` spanning its plane, or `None` when all lie on one line.
fn plane_of(poly: &[u32], at: &dyn Fn(u32) -> [f64; 3]) -> Option<[u32; 3]> {
    let a = poly[0];
    let b = *poly.iter().find(|&&v| at(v) != at(a))?;
    let c = *poly.iter().find(|&&v| !collinear(at(a), at(b), at(v)))?;
    Some([a, b, c])
}

/// Triangles covering the non-planar loop `poly`, oriented as the loop, or `None` when no
/// axis projection makes it simple.
fn triangulate_non_planar(poly: &[u32], at: &dyn Fn(u32) -> [f64; 3]) -> Option<Vec<[u32; 3]>> {
    if poly.len() > MAX_CLIP {
        return None;
    }
    // Newell's normal orders the axes to try: the polygon's "average" plane is seen best
    // along its largest component.
    let mut n = [0.0f64; 3];
    for (i, &v) in poly.iter().enumerate() {
        let (p, q) = (at(v), at(poly[(i + 1) % poly.len()]));
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    let mut axes = [2usize, 0, 1];
    axes.sort_by(|&i, &j| n[j].abs().total_cmp(&n[i].abs()));
    for axis in axes {
        let p2 = |v: u32| proj(at(v), axis);
        if !simple(poly, &p2) {
            continue;
        }
        // At the lexicographically smallest corner of a simple polygon the turn is exact and
        // non-zero, and gives the orientation.
        let k = (0..poly.len())
            .min_by(|&i, &j| p2(poly[i]).partial_cmp(&p2(poly[j])).unwrap())
            .unwrap_or(0);
        let m = poly.len();
        let turn = orient2d(
            p2(poly[(k + m - 1) % m]),
            p2(poly[k]),
            p2(poly[(k + 1) % m]),
        );
        let ccw = turn > 0.0;
        let ring: Vec<u32> = if ccw {
            poly.to_vec()
        } else {
            poly.iter().rev().copied().collect()
        };
        let mut tris = Vec::with_capacity(m - 2);
        FacetTriangulation::polygon(&ring, &p2, &mut tris)?;
        if !ccw {
            tris.iter_mut().for_each(|t| t.swap(1, 2));
        }
        return Some(tris);
    }
    None
}

/// Whether the closed loop `poly` is a simple polygon in the projection `p2`: distinct
/// projected corners, adjacent edges meeting only at their shared corner, other edges not
/// meeting at all (exact, `O(n²)`).
fn simple(poly: &[u32], p2: &dyn Fn(u32) -> [f64; 2]) -> bool {
    let n = poly.len();
    let q: Vec<[f64; 2]> = poly.iter().map(|&v| p2(v)).collect();
    for i in 0..n {
        let (a, b) = (q[i], q[(i + 1) % n]);
        if a == b {
            return false;
        }
        for j in i + 1..n {
            let (c, d) = (q[j], q[(j + 1) % n]);
            if j == i + 1 {
                // Shared corner b = c: the edges fold onto each other when a and d lie on one
                // ray from b.
                if orient2d(a, b, d) == 0.0 && same_ray(b, a, d) {
                    return false;
                }
            } else if i == 0 && j == n - 1 {
                // Shared corner a = d.
                if orient2d(c, a, b) == 0.0 && same_ray(a, c, b) {
                    return false;
                }
            } else if segments_meet(a, b, c, d) {
                return false;
            }
        }
    }
    true
}

/// For `x`, `y` collinear with `o` (both different from it): whether they lie on one ray
/// from `o` (exact coordinate comparisons).
fn same_ray(o: [f64; 2], x: [f64; 2], y: [f64; 2]) -> bool {
    let k = if x[0] != o[0] { 0 } else { 1 };
    (x[k] > o[k]) == (y[k] > o[k])
}

/// Whether the closed segments `ab` and `cd` have a point in common (exact).
fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (o1, o2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (o3, o4) = (orient2d(c, d, a), orient2d(c, d, b));
    let within = |p: [f64; 2], q: [f64; 2], x: [f64; 2]| {
        (0..2).all(|k| p[k].min(q[k]) <= x[k] && x[k] <= p[k].max(q[k]))
    };
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    (o1 == 0.0 && within(a, b, c))
        || (o2 == 0.0 && within(a, b, d))
        || (o3 == 0.0 && within(c, d, a))
        || (o4 == 0.0 && within(c, d, b))
}

/// Inserts the corners of each dropped collinear loop (`lines`) into the polygon edges of
/// `facets` they lie strictly inside, in order along the edge.
fn close_t_junctions(facets: &mut [Facet], lines: &[Vec<u32>], pts: &[[f64; 3]]) {
    let mut on_line: crate::hash::FastMap<u32, Vec<usize>> = Default::default();
    for (l, line) in lines.iter().enumerate() {
        for &v in line {
            on_line.entry(v).or_default().push(l);
        }
    }
    let at = |v: u32| pts[v as usize];
    for facet in facets.iter_mut() {
        for poly in facet.polygons.iter_mut().filter(|p| p.len() >= 3) {
            let n = poly.len();
            let mut out = Vec::with_capacity(n);
            for i in 0..n {
                let (u, v) = (poly[i], poly[(i + 1) % n]);
                out.push(u);
                let (Some(lu), Some(lv)) = (on_line.get(&u), on_line.get(&v)) else {
                    continue;
                };
                let Some(&l) = lu.iter().find(|l| lv.contains(l)) else {
                    continue;
                };
                let (a, b) = (at(u), at(v));
                let k = (0..3).find(|&k| a[k] != b[k]).unwrap_or(0);
                let mut inside: Vec<u32> = lines[l]
                    .iter()
                    .copied()
                    .filter(|&w| {
                        let x = at(w)[k];
                        ((a[k] < x && x < b[k]) || (b[k] < x && x < a[k])) && !poly.contains(&w)
                    })
                    .collect();
                // Along the line, coordinate k runs monotonically from u to v.
                inside.sort_by(|&w1, &w2| at(w1)[k].total_cmp(&at(w2)[k]));
                if a[k] > b[k] {
                    inside.reverse();
                }
                inside.dedup();
                out.extend(inside);
            }
            *poly = out;
        }
    }
}

#[cfg(test)]
mod tests;
