//! Per-facet checks (degenerate loops, planarity, hole seeds in the plane, crossing polygon
//! edges) and each facet's region as triangles on its own vertices, for the intersection
//! tests.

use super::cdt::{CdtError, FacetTriangulation};
use super::exact3::{collinear, dominant_axis, proj, P3};
use crate::error::{Error, InputError};
use crate::input3d::{Facet, Plc};
use crate::predicates::orient3d;

/// Every facet's vertices and region triangles, in global point indices.
#[derive(Debug, Default)]
pub(super) struct FacetSet {
    /// `verts[vstart[f]..vstart[f + 1]]`: the distinct vertices of facet `f`, sorted.
    vstart: Vec<u32>,
    verts: Vec<u32>,
    /// The region triangles and the facet of each.
    pub tris: Vec<[u32; 3]>,
    pub tri_facet: Vec<u32>,
    /// Edges of region triangles that lie inside the region (not on a polygon edge), and the
    /// facet of each.
    pub diags: Vec<[u32; 2]>,
    pub diag_facet: Vec<u32>,
}

impl FacetSet {
    /// Whether point `v` is one of facet `f`'s vertices.
    pub fn has_vertex(&self, f: u32, v: u32) -> bool {
        let (s, e) = (
            self.vstart[f as usize] as usize,
            self.vstart[f as usize + 1] as usize,
        );
        self.verts[s..e].binary_search(&v).is_ok()
    }
}

/// Scratch reused from facet to facet.
#[derive(Default)]
struct Scratch {
    /// Global → local index, valid where `stamp` equals the current facet + 1.
    local: Vec<u32>,
    stamp: Vec<u32>,
    /// Local → global, in order of first appearance.
    global: Vec<u32>,
    projected: Vec<[f64; 2]>,
    seeds: Vec<[f64; 2]>,
    cdt: FacetTriangulation,
}

/// Checks every facet on its own and triangulates its region. Polygon indices must already
/// be valid and free of repeats; points must be distinct.
pub(super) fn triangulate_facets(plc: &Plc) -> Result<FacetSet, Error> {
    let n = plc.points.len();
    let mut out = FacetSet {
        vstart: Vec::with_capacity(plc.facets.len() + 1),
        ..FacetSet::default()
    };
    out.vstart.push(0);
    let mut s = Scratch {
        local: vec![0; n],
        stamp: vec![0; n],
        ..Scratch::default()
    };
    for (fi, f) in plc.facets.iter().enumerate() {
        facet(plc, fi, f, &mut s, &mut out)?;
    }
    Ok(out)
}

fn facet(
    plc: &Plc,
    fi: usize,
    f: &Facet,
    s: &mut Scratch,
    out: &mut FacetSet,
) -> Result<(), Error> {
    let pt = |v: u32| plc.points[v as usize];
    for (pi, poly) in f.polygons.iter().enumerate() {
        if poly.len() >= 3 {
            let (a, b) = (pt(poly[0]), pt(poly[1]));
            if poly[2..].iter().all(|&v| collinear(a, b, pt(v))) {
                return Err(InputError::DegeneratePolygon {
                    facet: fi,
                    polygon: pi,
                }
                .into());
            }
        }
    }
    // Local numbering in order of first appearance.
    let stamp = fi as u32 + 1;
    s.global.clear();
    for &v in f.polygons.iter().flatten() {
        if s.stamp[v as usize] != stamp {
            s.stamp[v as usize] = stamp;
            s.local[v as usize] = s.global.len() as u32;
            s.global.push(v);
        }
    }
    let first = s.global.first().copied();
    let second = s.global.get(1).copied();
    let (Some(a), Some(b)) = (first, second) else {
        return Err(InputError::DegenerateFacet { facet: fi }.into());
    };
    let (pa, pb) = (pt(a), pt(b));
    let Some(&c) = s.global[2..].iter().find(|&&c| !collinear(pa, pb, pt(c))) else {
        return Err(InputError::DegenerateFacet { facet: fi }.into());
    };
    let pc = pt(c);
    if let Some(&v) = s
        .global
        .iter()
        .find(|&&v| orient3d(pa, pb, pc, pt(v)) != 0.0)
    {
        return Err(InputError::NonPlanarFacet {
            facet: fi,
            vertex: v as usize,
        }
        .into());
    }
    for (h, seed) in f.holes.iter().enumerate() {
        if !seed.iter().all(|x| x.is_finite()) {
            return Err(InputError::NonFiniteFacetHole { facet: fi, hole: h }.into());
        }
        if orient3d(pa, pb, pc, *seed) != 0.0 {
            return Err(InputError::FacetHoleOffPlane { facet: fi, hole: h }.into());
        }
    }

    let start = out.verts.len();
    out.verts.extend_from_slice(&s.global);
    out.verts[start..].sort_unstable();
    out.vstart.push(out.verts.len() as u32);

    // A lone triangle is its own region: the common case of surface meshes, kept cheap.
    if f.polygons.len() == 1 && f.polygons[0].len() == 3 && f.holes.is_empty() {
        let p = &f.polygons[0];
        out.tris.push([p[0], p[1], p[2]]);
        out.tri_facet.push(fi as u32);
        return Ok(());
    }
    let axis = dominant_axis(pa, pb, pc).unwrap_or(2);
    s.projected.clear();
    s.projected
        .extend(s.global.iter().map(|&v| proj(pt(v), axis)));
    s.seeds.clear();
    s.seeds.extend(f.holes.iter().map(|&h: &P3| proj(h, axis)));
    let fail = |e: CdtError| -> Error {
        match e {
            CdtError::Crossing(x, y) => InputError::SelfIntersectingFacet {
                facet: fi,
                first_polygon: x.min(y) as usize,
                second_polygon: x.max(y) as usize,
            }
            .into(),
            CdtError::Budget(what) => {
                Error::Internal(format!("facet {fi}: triangulating its polygons: {what}"))
            }
        }
    };
    s.cdt.triangulate(&s.projected).map_err(fail)?;
    for (pi, poly) in f.polygons.iter().enumerate() {
        let k = poly.len();
        let edges = match k {
            0 | 1 => 0,
            2 => 1,
            _ => k,
        };
        for i in 0..edges {
            let (u, w) = (
                s.local[poly[i] as usize],
                s.local[poly[(i + 1) % k] as usize],
            );
            s.cdt.constrain(u, w, pi as u32).map_err(fail)?;
        }
    }
    s.cdt.classify(&s.seeds);
    for t in s.cdt.region() {
        out.tris.push(t.map(|v| s.global[v as usize]));
        out.tri_facet.push(fi as u32);
    }
    for d in s.cdt.diagonals() {
        out.diags.push(d.map(|v| s.global[v as usize]));
        out.diag_facet.push(fi as u32);
    }
    Ok(())
}
