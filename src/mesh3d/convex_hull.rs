//! TetGen's `-c`: mesh the convex hull of the input points, keeping every input facet and
//! segment inside it as a constraint.
//!
//! The hull's faces are added to the PLC as extra facets (marker 0) before meshing, so the
//! rest of the pipeline is unchanged (paper §4: the hull faces are facets like any other, and
//! the exterior is what lies beyond them). How the faces are made, every decision exact:
//! 1. The hull triangles are the boundary faces of the Delaunay tetrahedralization of the
//!    input points; adjacent ones that are exactly coplanar (`orient3d == 0`) form one hull
//!    face. Every input point in a hull face's plane is a vertex of its triangles.
//! 2. Per hull face, the constrained triangulation of its points (the facet checks' kernel)
//!    takes as constraints the face's outline, every input edge with both ends in the face and every edge of the
//!    region triangles of the input facets lying in it. Its triangles are then either exactly
//!    those input facet triangles or parts of the hull not covered by an input facet; the
//!    latter become the new facets, so no new facet overlaps an input facet and every input
//!    edge or point on the hull is an edge or vertex of the new facets (as the PLC checks
//!    demand).
//!
//! With coplanar merging on, the new triangles of one hull face merge into polygons.

use crate::error::Error;
use crate::hash::{FastMap as HashMap, FastSet as HashSet};
use crate::input3d::{facet_regions, Facet, FacetTriangulation, Plc};
use crate::predicates::orient3d;

use super::features::{dominant_axis, ekey, fkey, proj};

/// The input with the convex hull's faces added as facets (see the module docs).
pub(crate) fn with_hull_facets(plc: &Plc) -> Result<Plc, Error> {
    let hull = hull_triangles(&plc.points)?;
    let group = coplanar_groups(&plc.points, &hull);
    let num_groups = group.iter().max().map_or(0, |&g| g as usize + 1);
    // The points and triangles of each hull face; which faces each point lies in.
    let mut face_points: Vec<Vec<u32>> = vec![Vec::new(); num_groups];
    let mut face_tris: Vec<Vec<[u32; 3]>> = vec![Vec::new(); num_groups];
    let mut faces_of: HashMap<u32, Vec<u32>> = HashMap::default();
    for (t, &g) in hull.iter().zip(&group) {
        face_tris[g as usize].push(*t);
        for &v in t {
            let fs = faces_of.entry(v).or_default();
            if !fs.contains(&g) {
                fs.push(g);
                face_points[g as usize].push(v);
            }
        }
    }
    let common = |vs: &[u32]| -> Vec<u32> {
        let Some(first) = faces_of.get(&vs[0]) else {
            return Vec::new();
        };
        first
            .iter()
            .copied()
            .filter(|g| {
                vs[1..]
                    .iter()
                    .all(|v| faces_of.get(v).is_some_and(|fs| fs.contains(g)))
            })
            .collect()
    };
    // Input edges lying in hull faces.
    let mut face_edges: Vec<Vec<[u32; 2]>> = vec![Vec::new(); num_groups];
    let mut add_edge = |a: u32, b: u32| {
        if a != b {
            for g in common(&[a, b]) {
                face_edges[g as usize].push([a, b]);
            }
        }
    };
    for s in &plc.segments {
        add_edge(s[0], s[1]);
    }
    for f in &plc.facets {
        for poly in &f.polygons {
            let k = poly.len();
            let n = if k >= 3 { k } else { k.saturating_sub(1) };
            for i in 0..n {
                add_edge(poly[i], poly[(i + 1) % k]);
            }
        }
    }
    // Region triangles of input facets lying in hull faces.
    let (tris, _) = facet_regions(plc)?;
    let mut covered: Vec<HashSet<[u32; 3]>> = vec![HashSet::default(); num_groups];
    for t in &tris {
        for g in common(t) {
            covered[g as usize].insert(fkey(*t));
            for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                face_edges[g as usize].push([t[i], t[j]]);
            }
        }
    }
    let mut out = plc.clone();
    let mut cdt = FacetTriangulation::default();
    let mut local: HashMap<u32, u32> = HashMap::default();
    for g in 0..num_groups {
        if face_edges[g].is_empty() {
            // Nothing of the input lies in this face beyond points: its hull triangles are
            // the face.
            out.facets
                .extend(face_tris[g].iter().map(|t| triangle_facet(*t)));
            continue;
        }
        // The face's outline (edges of one of its triangles only) bounds the region that the
        // classification keeps.
        let mut uses: HashMap<u64, ([u32; 2], u32)> = HashMap::default();
        for t in &face_tris[g] {
            for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                uses.entry(ekey(t[i], t[j])).or_insert(([t[i], t[j]], 0)).1 += 1;
            }
        }
        face_edges[g].extend(uses.values().filter(|u| u.1 == 1).map(|u| u.0));
        let t0 = face_tris[g][0].map(|v| plc.points[v as usize]);
        let axis = dominant_axis(t0[0], t0[1], t0[2])
            .ok_or_else(|| Error::Internal("-c: a degenerate hull triangle".into()))?;
        let pts = &face_points[g];
        local.clear();
        local.extend(pts.iter().enumerate().map(|(i, &v)| (v, i as u32)));
        let projected: Vec<[f64; 2]> = pts
            .iter()
            .map(|&v| proj(plc.points[v as usize], axis))
            .collect();
        let fail = |what: &str| Error::Internal(format!("-c: hull face {g}: {what}"));
        cdt.triangulate(&projected)
            .map_err(|e| fail(&format!("{e:?}")))?;
        face_edges[g].sort_unstable_by_key(|e| ekey(e[0], e[1]));
        face_edges[g].dedup_by_key(|e| ekey(e[0], e[1]));
        for (tag, e) in face_edges[g].iter().enumerate() {
            cdt.constrain(local[&e[0]], local[&e[1]], tag as u32)
                .map_err(|e| {
                    fail(&format!(
                        "input edges in the hull's plane cross ({e:?}); is the PLC valid?"
                    ))
                })?;
        }
        cdt.classify(&[]);
        for t in cdt.region() {
            let t = t.map(|v| pts[v as usize]);
            if !covered[g].contains(&fkey(t)) {
                out.facets.push(triangle_facet(t));
            }
        }
    }
    Ok(out)
}

fn triangle_facet(t: [u32; 3]) -> Facet {
    Facet {
        polygons: vec![t.to_vec()],
        holes: Vec::new(),
        marker: 0,
    }
}

/// The boundary triangles of the Delaunay tetrahedralization of `points`: the convex hull,
/// each of its flat faces triangulated on the points lying in it.
fn hull_triangles(points: &[[f64; 3]]) -> Result<Vec<[u32; 3]>, Error> {
    // Its faces are the hull triangles.
    Ok(super::delaunay::delaunay(points, |_| Ok(()))?.faces)
}

/// Per hull triangle, the id (0, 1, ...) of its group: triangles joined across shared edges
/// when exactly coplanar.
fn coplanar_groups(points: &[[f64; 3]], hull: &[[u32; 3]]) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..hull.len() as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    let mut by_edge: HashMap<u64, u32> = HashMap::default();
    for (t, tri) in hull.iter().enumerate() {
        for (i, j, k) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
            let key = ekey(tri[i], tri[j]);
            match by_edge.get(&key) {
                Some(&u) => {
                    let p = |v: u32| points[v as usize];
                    let other = hull[u as usize];
                    if orient3d(p(other[0]), p(other[1]), p(other[2]), p(tri[k])) == 0.0 {
                        let (a, b) = (find(&mut parent, u), find(&mut parent, t as u32));
                        parent[a as usize] = b;
                    }
                }
                None => {
                    by_edge.insert(key, t as u32);
                }
            }
        }
    }
    let mut id: HashMap<u32, u32> = HashMap::default();
    (0..hull.len() as u32)
        .map(|t| {
            let r = find(&mut parent, t);
            let next = id.len() as u32;
            *id.entry(r).or_insert(next)
        })
        .collect()
}
