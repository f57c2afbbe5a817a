//! Merging exactly coplanar neighbouring facets into one (what TetGen does unless given `-M`).
//!
//! A triangulated surface describes each flat face of the object by triangles, and their
//! shared edges are artefacts of the triangulation, not features: a thin rectangle split along
//! its diagonal has two 1.5° angles that the rectangle does not have (the walls of a
//! tessellated pipe). Kept as
//! input edges they must appear in the mesh, and the small angles they make cost protection
//! zones, skinny tets and many Steiner points. Merged, the face is one polygon facet (the union
//! of its triangles, its holes and isolated points included) and the shared edges are gone.
//!
//! Two facets are merged across an edge when they are the only facets on it, neither is a
//! free segment of the input, both are single loops without hole seeds, they have the same
//! marker, they are exactly coplanar (exact orientation tests), and they lie on opposite sides
//! of the edge (a fold back onto itself is kept).

use crate::hash::FastMap as HashMap;
use crate::input3d::{Facet, Plc};
use crate::predicates::{orient2d, orient3d};

use super::features::{dominant_axis, ekey, proj};

/// The input with each group of mergeable facets replaced by one facet, or `None` when no two
/// facets can be merged (the input is used as it is).
pub(crate) fn merge_coplanar_facets(plc: &Plc) -> Option<Plc> {
    let info: Vec<Option<Loop>> = plc.facets.iter().map(|f| Loop::of(plc, f)).collect();
    let uses = edge_uses(plc);
    let mut groups = UnionFind::new(plc.facets.len());
    let mut merged: crate::hash::FastSet<u64> = Default::default();
    for (&key, u) in &uses {
        if let [(f1, d1), (f2, d2)] = u.as_slice() {
            if mergeable(plc, &info, (*f1, *d1), (*f2, *d2)) {
                merged.insert(key);
                groups.union(*f1, *f2);
            }
        }
    }
    if merged.is_empty() {
        return None;
    }
    let mut members: HashMap<u32, Vec<u32>> = HashMap::default();
    for f in 0..plc.facets.len() as u32 {
        members.entry(groups.find(f)).or_default().push(f);
    }
    let mut out = plc.clone();
    out.facets.clear();
    for (f, facet) in plc.facets.iter().enumerate() {
        let root = groups.find(f as u32);
        let group = &members[&root];
        if group.len() == 1 {
            out.facets.push(facet.clone());
        } else if root == f as u32 {
            match union_facet(plc, &info, group, &merged) {
                Some(u) => out.facets.push(u),
                // Not a consistent boundary (should not happen for a valid PLC): keep the
                // triangles as they are.
                None => out
                    .facets
                    .extend(group.iter().map(|&g| plc.facets[g as usize].clone())),
            }
        }
    }
    Some(out)
}

/// A single-loop facet: its loop, projection axis and the loop's orientation in projection.
struct Loop {
    verts: Vec<u32>,
    axis: usize,
    /// Three non-collinear vertices spanning the facet's plane.
    plane: [u32; 3],
}

impl Loop {
    /// The loop of a facet that may be merged (one polygon of three or more vertices, no hole
    /// seeds), `None` otherwise.
    fn of(plc: &Plc, f: &Facet) -> Option<Loop> {
        if f.polygons.len() != 1 || f.polygons[0].len() < 3 || !f.holes.is_empty() {
            return None;
        }
        let verts = f.polygons[0].clone();
        let p = |v: u32| plc.points[v as usize];
        let a = verts[0];
        for (j, &b) in verts.iter().enumerate().skip(1) {
            for &c in &verts[j + 1..] {
                if let Some(axis) = dominant_axis(p(a), p(b), p(c)) {
                    return Some(Loop {
                        verts,
                        axis,
                        plane: [a, b, c],
                    });
                }
            }
        }
        None
    }

    /// The sign of the loop's signed area projected along `axis` (0 when it is degenerate).
    fn orientation(&self, plc: &Plc, axis: usize) -> f64 {
        let q = |v: u32| proj(plc.points[v as usize], axis);
        let o = q(self.verts[0]);
        let area: f64 = self
            .verts
            .windows(2)
            .skip(1)
            .map(|w| orient2d(o, q(w[0]), q(w[1])))
            .sum();
        if area > 0.0 {
            1.0
        } else if area < 0.0 {
            -1.0
        } else {
            0.0
        }
    }
}

/// Per undirected edge: the facets whose loops (or free segments: facet `u32::MAX`) use it,
/// each with the direction of use (`true`: from the smaller vertex id to the larger).
fn edge_uses(plc: &Plc) -> HashMap<u64, Vec<(u32, bool)>> {
    let mut uses: HashMap<u64, Vec<(u32, bool)>> = HashMap::default();
    for s in &plc.segments {
        uses.entry(ekey(s[0], s[1]))
            .or_default()
            .push((u32::MAX, true));
    }
    for (f, facet) in plc.facets.iter().enumerate() {
        for poly in &facet.polygons {
            let k = poly.len();
            let n = match k {
                0 | 1 => 0,
                2 => 1,
                _ => k,
            };
            for i in 0..n {
                let (a, b) = (poly[i], poly[(i + 1) % k]);
                if a != b {
                    uses.entry(ekey(a, b)).or_default().push((f as u32, a < b));
                }
            }
        }
    }
    uses
}

/// Whether the two facet uses of one edge can be merged (see the module comment).
fn mergeable(plc: &Plc, info: &[Option<Loop>], u1: (u32, bool), u2: (u32, bool)) -> bool {
    let ((f1, d1), (f2, d2)) = (u1, u2);
    if f1 == u32::MAX || f2 == u32::MAX || f1 == f2 {
        return false;
    }
    let (Some(l1), Some(l2)) = (&info[f1 as usize], &info[f2 as usize]) else {
        return false;
    };
    if plc.facets[f1 as usize].marker != plc.facets[f2 as usize].marker {
        return false;
    }
    let [a, b, c] = l1.plane.map(|v| plc.points[v as usize]);
    if l2
        .verts
        .iter()
        .any(|&v| orient3d(a, b, c, plc.points[v as usize]) != 0.0)
    {
        return false;
    }
    // Which side of the edge each facet lies on: its orientation in one common projection,
    // flipped when it runs along the edge the other way.
    let side =
        |l: &Loop, forward: bool| l.orientation(plc, l1.axis) * if forward { 1.0 } else { -1.0 };
    let (s1, s2) = (side(l1, d1), side(l2, d2));
    s1 != 0.0 && s2 != 0.0 && s1 != s2
}

/// The facet that is the union of the group's facets: the loops of its boundary, the edges
/// between group members that could not be merged (kept as segments in the facet), and the
/// members' vertices on neither (kept as isolated points). `None` if the boundary does not
/// close into loops.
fn union_facet(
    plc: &Plc,
    info: &[Option<Loop>],
    group: &[u32],
    merged: &crate::hash::FastSet<u64>,
) -> Option<Facet> {
    let axis = info[group[0] as usize].as_ref()?.axis;
    // Directed edges with the facet's interior on the left in the common projection.
    let mut directed: Vec<(u32, u32)> = Vec::new();
    for &f in group {
        let l = info[f as usize].as_ref()?;
        let ccw = l.orientation(plc, axis) > 0.0;
        let k = l.verts.len();
        for i in 0..k {
            let (a, b) = (l.verts[i], l.verts[(i + 1) % k]);
            directed.push(if ccw { (a, b) } else { (b, a) });
        }
    }
    let present: crate::hash::FastSet<(u32, u32)> = directed.iter().copied().collect();
    let mut polygons: Vec<Vec<u32>> = Vec::new();
    let mut boundary: HashMap<u32, Vec<u32>> = HashMap::default();
    let mut edges_left = 0usize;
    for &(a, b) in &directed {
        if present.contains(&(b, a)) {
            // Inside the union: gone if merged, else a segment of the facet (once).
            if !merged.contains(&ekey(a, b)) && a < b {
                polygons.push(vec![a, b]);
            }
            continue;
        }
        boundary.entry(a).or_default().push(b);
        edges_left += 1;
    }
    // Chain the boundary edges into closed loops, from the smallest vertex with an edge left
    // (any pairing at a vertex where loops touch gives the same region under the even-odd
    // rule).
    let mut starts: Vec<u32> = boundary.keys().copied().collect();
    starts.sort_unstable();
    for start in starts {
        while boundary.get(&start).is_some_and(|outs| !outs.is_empty()) {
            let mut lp = vec![start];
            let mut cur = boundary.get_mut(&start)?.pop()?;
            edges_left -= 1;
            while cur != start {
                lp.push(cur);
                cur = boundary.get_mut(&cur)?.pop()?;
                edges_left = edges_left.checked_sub(1)?;
            }
            polygons.push(lp);
        }
    }
    if edges_left != 0 {
        return None;
    }
    let on_polygon: crate::hash::FastSet<u32> = polygons.iter().flatten().copied().collect();
    let mut lone: Vec<u32> = group
        .iter()
        .flat_map(|&f| plc.facets[f as usize].polygons[0].iter().copied())
        .filter(|v| !on_polygon.contains(v))
        .collect();
    lone.sort_unstable();
    lone.dedup();
    polygons.extend(lone.into_iter().map(|v| vec![v]));
    Some(Facet {
        polygons,
        holes: Vec::new(),
        marker: plc.facets[group[0] as usize].marker,
    })
}

/// Union–find over facet ids (path halving; the smaller root wins, so results are
/// deterministic).
struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n as u32).collect(),
        }
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let up = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = up;
            x = up;
        }
        x
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: u32, b: u32, c: u32, marker: i32) -> Facet {
        Facet {
            polygons: vec![vec![a, b, c]],
            holes: vec![],
            marker,
        }
    }

    /// The unit square in z = 0 split along its diagonal 0-2, plus a third triangle.
    fn square(third: Facet, markers: [i32; 2]) -> Plc {
        Plc {
            points: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.5, 0.5, 1.0],
                [0.5, -1.0, 0.0],
            ],
            facets: vec![tri(0, 1, 2, markers[0]), tri(0, 2, 3, markers[1]), third],
            ..Plc::default()
        }
    }

    #[test]
    fn two_coplanar_triangles_become_one_quadrilateral() {
        let plc = square(tri(0, 1, 4, 1), [1, 1]);
        let out = merge_coplanar_facets(&plc).expect("the square's halves merge");
        assert_eq!(out.facets.len(), 2);
        let mut quad = out.facets[0].polygons[0].clone();
        assert_eq!(
            out.facets[0].polygons.len(),
            1,
            "no diagonal, no lone point"
        );
        quad.sort_unstable();
        assert_eq!(quad, vec![0, 1, 2, 3]);
        assert_eq!(out.facets[1], plc.facets[2], "the slanted triangle is kept");
    }

    #[test]
    fn different_markers_folds_and_third_facets_block_merging() {
        assert!(merge_coplanar_facets(&square(tri(0, 1, 4, 1), [1, 2])).is_none());
        // (0, 1, 5) is coplanar with (0, 1, 2) but on the other side of 0-1: merged; a
        // triangle folded back onto (0, 1, 2) along 0-1 is not.
        let other_side = square(tri(1, 0, 5, 1), [1, 1]);
        let out = merge_coplanar_facets(&other_side).unwrap();
        assert_eq!(out.facets.len(), 1);
        let folded = Plc {
            points: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.5, 0.5, 0.0],
            ],
            facets: vec![tri(0, 1, 2, 1), tri(1, 0, 3, 1)],
            ..Plc::default()
        };
        assert!(merge_coplanar_facets(&folded).is_none());
        // A free segment on the diagonal keeps it.
        let mut seg = square(tri(0, 1, 4, 1), [1, 1]);
        seg.segments.push([2, 0]);
        assert!(merge_coplanar_facets(&seg).is_none());
    }

    #[test]
    fn a_fan_keeps_its_centre_and_a_ring_its_hole() {
        // A square fanned from its centre 4: one loop and the centre as a lone point.
        let mut plc = Plc {
            points: vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 2.0, 0.0],
                [0.0, 2.0, 0.0],
                [1.0, 1.0, 0.0],
            ],
            ..Plc::default()
        };
        for i in 0..4 {
            plc.facets.push(tri(i, (i + 1) % 4, 4, 3));
        }
        let out = merge_coplanar_facets(&plc).unwrap();
        assert_eq!(out.facets.len(), 1);
        let f = &out.facets[0];
        assert_eq!(f.marker, 3);
        assert_eq!(f.polygons.len(), 2);
        assert_eq!(f.polygons[0].len(), 4);
        assert_eq!(f.polygons[1], vec![4]);
        // A square ring (outer 0-3, inner 4-7) of eight triangles: two loops.
        let mut ring = Plc {
            points: vec![
                [0.0, 0.0, 0.0],
                [3.0, 0.0, 0.0],
                [3.0, 3.0, 0.0],
                [0.0, 3.0, 0.0],
                [1.0, 1.0, 0.0],
                [2.0, 1.0, 0.0],
                [2.0, 2.0, 0.0],
                [1.0, 2.0, 0.0],
            ],
            ..Plc::default()
        };
        for i in 0..4u32 {
            let j = (i + 1) % 4;
            ring.facets.push(tri(i, j, 4 + j, 1));
            ring.facets.push(tri(i, 4 + j, 4 + i, 1));
        }
        let out = merge_coplanar_facets(&ring).unwrap();
        assert_eq!(out.facets.len(), 1);
        let mut sizes: Vec<usize> = out.facets[0].polygons.iter().map(|p| p.len()).collect();
        sizes.sort_unstable();
        assert_eq!(sizes, vec![4, 4]);
    }
}
