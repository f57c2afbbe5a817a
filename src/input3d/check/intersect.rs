//! Improper intersections between the PLC's features.
//!
//! The features are points, edges and the facets' region triangles. Edges are the segments,
//! the facets' polygon edges and the triangles' inner diagonals, each once with the list of
//! features it belongs to. Two facets (or a segment and a facet) meet properly only in shared
//! vertices and shared polygon edges, and two closed triangles meet improperly exactly when
//! one of these incidences occurs between them (the intersection's extreme points are
//! vertices or edge crossings):
//! * a point inside an edge or in a closed triangle that it is not a vertex of;
//! * two edges crossing at a point interior to both;
//! * an edge passing through a triangle's plane at a point of the triangle;
//! * the same triangle in two facets (all vertices and edges shared, so nothing else shows).
//!
//! So these are the only tests, run on the pairs of features that may touch (see `grid`).

use super::exact3::{
    in_closed_triangle, in_open_segment, segment_pierces_triangle, segments_cross, P3,
};
use super::facets::FacetSet;
use super::grid::{for_each_candidate, Shape};
use crate::error::{Error, InputError};
use crate::input3d::Plc;

/// What an edge belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Owner {
    /// A free segment.
    Segment(u32),
    /// A polygon edge of a facet.
    Polygon(u32),
    /// An inner diagonal of a facet's region.
    Diagonal(u32),
}

impl Owner {
    fn facet(self) -> Option<u32> {
        match self {
            Owner::Segment(_) => None,
            Owner::Polygon(f) | Owner::Diagonal(f) => Some(f),
        }
    }
}

/// The improper meeting of two features, as an error naming both.
fn meeting(a: Owner, b: Owner) -> Error {
    let pair = |x: u32, y: u32| (x.min(y) as usize, x.max(y) as usize);
    let e = match (a.facet(), b.facet()) {
        (None, None) => {
            let (Owner::Segment(s), Owner::Segment(t)) = (a, b) else {
                unreachable!("owners without a facet are segments")
            };
            let (first, second) = pair(s, t);
            InputError::CrossingSegments { first, second }
        }
        (Some(f), Some(g)) => {
            let (first, second) = pair(f, g);
            InputError::FacetsIntersect { first, second }
        }
        (Some(f), None) | (None, Some(f)) => {
            let s = match (a, b) {
                (Owner::Segment(s), _) | (_, Owner::Segment(s)) => s,
                _ => unreachable!("one owner is a segment"),
            };
            InputError::SegmentCrossesFacet {
                segment: s as usize,
                facet: f as usize,
            }
        }
    };
    e.into()
}

/// Distinct edges with their owners.
struct Edges {
    ends: Vec<[u32; 2]>,
    /// `owners[start[e]..start[e + 1]]`, sorted and distinct.
    start: Vec<u32>,
    owners: Vec<Owner>,
}

impl Edges {
    fn owners(&self, e: usize) -> &[Owner] {
        &self.owners[self.start[e] as usize..self.start[e + 1] as usize]
    }
}

/// Gathers the edges; an inner diagonal of a facet that is also any other feature's edge is
/// already an improper meeting.
fn gather_edges(plc: &Plc, fs: &FacetSet) -> Result<Edges, Error> {
    let key = |a: u32, b: u32| if a < b { [a, b] } else { [b, a] };
    let mut all: Vec<([u32; 2], Owner)> = Vec::new();
    for (s, e) in plc.segments.iter().enumerate() {
        all.push((key(e[0], e[1]), Owner::Segment(s as u32)));
    }
    for (f, facet) in plc.facets.iter().enumerate() {
        for poly in &facet.polygons {
            let k = poly.len();
            let edges = match k {
                0 | 1 => 0,
                2 => 1,
                _ => k,
            };
            for i in 0..edges {
                all.push((key(poly[i], poly[(i + 1) % k]), Owner::Polygon(f as u32)));
            }
        }
    }
    for (d, &f) in fs.diags.iter().zip(&fs.diag_facet) {
        all.push((key(d[0], d[1]), Owner::Diagonal(f)));
    }
    all.sort_unstable();
    all.dedup();
    let mut out = Edges {
        ends: Vec::new(),
        start: vec![0],
        owners: Vec::with_capacity(all.len()),
    };
    let mut i = 0;
    while i < all.len() {
        let mut j = i;
        while j < all.len() && all[j].0 == all[i].0 {
            j += 1;
        }
        let group = &all[i..j];
        if let Some(&(_, d)) = group.iter().find(|(_, o)| matches!(o, Owner::Diagonal(_))) {
            if let Some(&(_, other)) = group.iter().find(|(_, o)| *o != d) {
                return Err(meeting(d, other));
            }
        }
        out.ends.push(all[i].0);
        out.owners.extend(group.iter().map(|g| g.1));
        out.start.push(out.owners.len() as u32);
        i = j;
    }
    Ok(out)
}

/// The same triangle (as a vertex set) in two facets.
fn duplicate_triangles(fs: &FacetSet) -> Result<(), Error> {
    let mut keys: Vec<([u32; 3], u32)> = fs
        .tris
        .iter()
        .zip(&fs.tri_facet)
        .map(|(t, &f)| {
            let mut k = *t;
            k.sort_unstable();
            (k, f)
        })
        .collect();
    keys.sort_unstable();
    for w in keys.windows(2) {
        if w[0].0 == w[1].0 {
            return Err(InputError::FacetsIntersect {
                first: w[0].1 as usize,
                second: w[1].1 as usize,
            }
            .into());
        }
    }
    Ok(())
}

/// Runs every test; reports the first improper intersection found.
pub(super) fn check_intersections(plc: &Plc, fs: &FacetSet) -> Result<(), Error> {
    duplicate_triangles(fs)?;
    let edges = gather_edges(plc, fs)?;
    let p = |v: u32| plc.points[v as usize];
    let (nv, ne, nf) = (plc.points.len(), edges.ends.len(), plc.facets.len() as u32);
    // Features are numbered: points, then edges, then triangles. Groups: all points share
    // one, each facet's edges and triangles another, each segment its own.
    let group = |o: Owner| match o {
        Owner::Polygon(f) | Owner::Diagonal(f) => 1 + f,
        Owner::Segment(s) => 1 + nf + s,
    };
    let mut shapes: Vec<Shape> = Vec::with_capacity(nv + ne + fs.tris.len());
    let mut groups: Vec<u32> = Vec::with_capacity(shapes.capacity());
    shapes.extend(plc.points.iter().map(|&q| Shape::Point(q)));
    groups.resize(nv, 0);
    for (e, ends) in edges.ends.iter().enumerate() {
        shapes.push(Shape::Segment(p(ends[0]), p(ends[1])));
        groups.push(group(edges.owners(e)[0]));
    }
    for (t, &f) in fs.tris.iter().zip(&fs.tri_facet) {
        shapes.push(Shape::Triangle(t.map(p)));
        groups.push(1 + f);
    }
    let (e0, t0) = (nv as u32, (nv + ne) as u32);
    let kind = |i: u32| {
        if i < e0 {
            0
        } else if i < t0 {
            1
        } else {
            2
        }
    };
    // Triangles are only ever the second of a pair.
    for_each_candidate(&shapes, &groups, t0 as usize, |i, j| {
        match (kind(i), kind(j)) {
            (0, 1) => point_edge(fs, &edges, p, i, (j - e0) as usize),
            (0, 2) => point_triangle(fs, p, i, (j - t0) as usize),
            (1, 1) => edge_edge(&edges, p, (i - e0) as usize, (j - e0) as usize),
            (1, 2) => edge_triangle(fs, &edges, p, (i - e0) as usize, (j - t0) as usize),
            _ => Ok(()),
        }
    })
}

fn point_edge(
    fs: &FacetSet,
    edges: &Edges,
    p: impl Fn(u32) -> P3,
    v: u32,
    e: usize,
) -> Result<(), Error> {
    let [a, b] = edges.ends[e];
    if v == a || v == b || !in_open_segment(p(a), p(b), p(v)) {
        return Ok(());
    }
    for &o in edges.owners(e) {
        match o {
            Owner::Segment(s) => {
                return Err(InputError::VertexOnSegment {
                    vertex: v as usize,
                    segment: s as usize,
                }
                .into())
            }
            // A facet's own vertex may split its polygon edges.
            Owner::Polygon(f) | Owner::Diagonal(f) if !fs.has_vertex(f, v) => {
                return Err(InputError::VertexOnFacet {
                    vertex: v as usize,
                    facet: f as usize,
                }
                .into())
            }
            _ => {}
        }
    }
    Ok(())
}

fn point_triangle(fs: &FacetSet, p: impl Fn(u32) -> P3, v: u32, t: usize) -> Result<(), Error> {
    let f = fs.tri_facet[t];
    if fs.tris[t].contains(&v) {
        return Ok(());
    }
    let [a, b, c] = fs.tris[t].map(&p);
    if !fs.has_vertex(f, v) && in_closed_triangle(a, b, c, p(v)) {
        return Err(InputError::VertexOnFacet {
            vertex: v as usize,
            facet: f as usize,
        }
        .into());
    }
    Ok(())
}

fn edge_edge(edges: &Edges, p: impl Fn(u32) -> P3, e: usize, g: usize) -> Result<(), Error> {
    let ([a, b], [c, d]) = (edges.ends[e], edges.ends[g]);
    if a == c || a == d || b == c || b == d || !segments_cross(p(a), p(b), p(c), p(d)) {
        return Ok(());
    }
    // Two edges of one facet never cross (its triangulation recovered them all), so some
    // pair of owners is a pair of different features.
    for &x in edges.owners(e) {
        for &y in edges.owners(g) {
            let same_facet = x.facet().is_some() && x.facet() == y.facet();
            if !same_facet {
                return Err(meeting(x, y));
            }
        }
    }
    Ok(())
}

fn edge_triangle(
    fs: &FacetSet,
    edges: &Edges,
    p: impl Fn(u32) -> P3,
    e: usize,
    t: usize,
) -> Result<(), Error> {
    let f = fs.tri_facet[t];
    let owners = edges.owners(e);
    if owners.iter().any(|o| o.facet() == Some(f)) {
        return Ok(());
    }
    let [a, b] = edges.ends[e];
    // An edge ending at a corner of the triangle cannot pass strictly through its plane.
    let tv = fs.tris[t];
    if tv.contains(&a) || tv.contains(&b) {
        return Ok(());
    }
    if segment_pierces_triangle(p(a), p(b), tv.map(&p)) {
        return Err(meeting(owners[0], Owner::Polygon(f)));
    }
    Ok(())
}
