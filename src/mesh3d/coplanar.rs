//! Merging exactly coplanar neighbouring facets into one (what TetGen does unless given `-M`),
//! and, on request only, moving nearly coplanar neighbours onto one plane first (TetGen's
//! `-T<tol>`).
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
//!
//! **Remeshing (TetGen's `-r`, [`super::Options3::remesh`]).** The facets are then the
//! boundary faces of a previous mesh, whose Steiner points on a slanted facet were rounded
//! off its plane: the faces of one flat side are coplanar only up to that rounding. Kept
//! apart, the edges between them are input edges that cannot flip as the side is refined:
//! every new point near one forces a split, and a thin wedge remeshed at a quarter of its
//! volume bound made eleven times the tets of meshing it directly. So two faces are merged
//! when every vertex of each lies within 2^-40 times the largest coordinate magnitude
//! involved of the other's plane (the floating-point value of the exact `orient3d`, divided
//! by twice the face's area). Nothing is moved: the merged facet's vertices lie a hair off
//! its plane, as the mesher's own Steiner points on it do, and its facet mesh decides in the
//! plane as it does for them.
//!
//! A group whose boundary runs straight through one of its vertices up to rounding but not
//! exactly (the previous mesh's split points on a straight slanted edge) is merged only where
//! its facets are exactly coplanar (as before merging up to rounding). In one facet mesh such a
//! chain leaves outside triangles thinner than the rounding of a split point on the chain,
//! which then lands beyond them: the subsegment next to it went missing from the facet mesh at
//! every split, down to the precision limit (two CAD-like models remeshed with
//! `-rq1.414a0.0005`). Faces kept apart put the two edges of such a vertex in different facets,
//! where it does no harm.
//!
//! **Tolerance (opt-in, [`snap_nearly_coplanar`]).** Exact conformity to the input is the
//! default: a fold of 10⁻⁹ between two facets is kept, and the flat tetrahedron it may leave is
//! for sliver removal to fix. With a tolerance `tol` (TetGen's `-T`), facets that would be
//! merged but for exact coplanarity are first grouped and snapped onto one plane:
//!
//! * Groups grow from a seed facet, the largest by area first (areas rounded to single
//!   precision; ties: the lower index), across
//!   the edges the exact merge would join (same conditions but coplanarity). A neighbour `g`
//!   joins when every vertex of `g` lies within `tol × L(g)` of the reference plane, `L(g)`
//!   being `g`'s longest edge: a distance relative to the facet's own size, so the rule does
//!   not change under scaling and translation (up to the rounding of the coordinates
//!   themselves). The reference plane is the seed's own plane, or, when the seed lies within
//!   the tolerance of it, the plane parallel to the coordinate plane the seed is closest to,
//!   through the coordinate most of the seed's vertices share (a scanned box face: its noise
//!   does not tilt the reference). Comparing every facet with one plane, not with its
//!   neighbour's, keeps a gently curved surface from being flattened by a chain of small folds.
//! * The group's plane is the first of these (at most 8) on which every member lies within
//!   the tolerance and every move below is exact: the coordinate plane (normal to the seed's
//!   dominant axis) through the value most of the group's vertices share, then the members'
//!   own planes, the seed's first. Each vertex off it (exact `orient3d`) is moved along the
//!   coordinate axis closest to the plane's normal onto a point with floating-point
//!   coordinates lying *exactly* on the plane (the solved coordinate or one of its nearest
//!   floating-point neighbours, checked exactly). It moves by its distance to the plane (for a
//!   plane parallel to a coordinate plane, as a box's faces) or at most √3 times it.
//! * A group is left as it is (counted in [`SnapReport::refused`]) when some vertex has no
//!   such point (common for slanted planes: an exactly planar snap needs representable points
//!   on the plane), or when a move would leave another facet that uses the vertex not exactly
//!   planar. If the moved input is no longer a valid PLC (a move made facets cross), nothing
//!   is moved at all.
//!
//! The exact merge then joins each snapped group. The boundary is then within the tolerance of
//! the input, as TetGen's is; the mesh's vertices are the moved points.

use crate::error::{catch_panic, Error};
use crate::geometry::next_float;
use crate::hash::FastMap as HashMap;
use crate::input3d::{Facet, Plc};
use crate::predicates::{orient2d, orient3d};
use crate::NONE;
use glam::DVec3;

use super::features::{dominant_axis, ekey, proj};

/// The input with each group of mergeable facets replaced by one facet, or `None` when no two
/// facets can be merged (the input is used as it is).
pub(crate) fn merge_coplanar_facets(plc: &Plc, rounded: bool) -> Option<Plc> {
    let info: Vec<Option<Loop>> = plc.facets.iter().map(|f| Loop::of(plc, f)).collect();
    let uses = edge_uses(plc);
    // How each facet may merge: 2 up to rounding, 1 exactly coplanar only.
    let mut level = vec![if rounded { 2u8 } else { 1 }; plc.facets.len()];
    let (mut groups, mut merged) = group_facets(plc, &info, &uses, &level);
    // Remeshing, a group whose boundary runs straight through a vertex up to rounding is
    // merged only where exactly coplanar (see the module comment).
    if rounded {
        let mut members: HashMap<u32, Vec<u32>> = HashMap::default();
        for f in 0..plc.facets.len() as u32 {
            members.entry(groups.find(f)).or_default().push(f);
        }
        let mut kinked = false;
        for (&root, group) in &members {
            if group.len() > 1
                && union_facet(plc, &info, group, &merged).is_some_and(|u| {
                    has_rounded_straight_vertex(plc, &u, info[root as usize].as_ref())
                })
            {
                kinked = true;
                for &f in group {
                    level[f as usize] -= 1;
                }
            }
        }
        if kinked {
            (groups, merged) = group_facets(plc, &info, &uses, &level);
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

/// The groups of facets to merge and the edges merged: two facets of `level` 2 merge when
/// coplanar up to rounding, else when exactly coplanar.
fn group_facets(
    plc: &Plc,
    info: &[Option<Loop>],
    uses: &HashMap<u64, Vec<(u32, bool)>>,
    level: &[u8],
) -> (UnionFind, crate::hash::FastSet<u64>) {
    let mut groups = UnionFind::new(plc.facets.len());
    let mut merged: crate::hash::FastSet<u64> = Default::default();
    for (&key, u) in uses {
        if let [(f1, d1), (f2, d2)] = u.as_slice() {
            let lv = |f: u32| level.get(f as usize).copied().unwrap_or(0);
            let l = lv(*f1).min(lv(*f2));
            if l > 0 && mergeable(plc, info, (*f1, *d1), (*f2, *d2), l == 2) {
                merged.insert(key);
                groups.union(*f1, *f2);
            }
        }
    }
    (groups, merged)
}

/// Whether a boundary loop of the merged facet `u` runs straight through one of its vertices
/// up to rounding but not exactly: the vertex lies within [`ROUNDED`] times the largest
/// coordinate magnitude of the line through its two neighbours on the loop, between them, and
/// off it. Lines through the facet's inside are not checked: regular refinement puts split
/// points on the lines of earlier ones, and refusing those merges brought the thin wedge's
/// over-refinement back.
fn has_rounded_straight_vertex(plc: &Plc, u: &Facet, l: Option<&Loop>) -> bool {
    let Some(l) = l else { return false };
    let p = |v: u32| plc.points[v as usize];
    u.polygons.iter().filter(|lp| lp.len() >= 3).any(|lp| {
        let k = lp.len();
        (0..k).any(|i| {
            let (x, y, c) = (p(lp[(i + k - 1) % k]), p(lp[i]), p(lp[(i + 1) % k]));
            let (qx, qy, qc) = (proj(x, l.axis), proj(y, l.axis), proj(c, l.axis));
            let o = orient2d(qx, qy, qc);
            let (dx, dy) = (qc[0] - qx[0], qc[1] - qx[1]);
            let along = (qy[0] - qx[0]) * dx + (qy[1] - qx[1]) * dy;
            let len2 = dx * dx + dy * dy;
            let scale = max_abs([x, y, c, c]);
            o != 0.0 && o.abs() <= ROUNDED * scale * len2.sqrt() && along > 0.0 && along < len2
        })
    })
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

/// Whether the two facet uses of one edge can be merged (see the module comment); with
/// `rounded`, coplanar up to [`ROUNDED`].
fn mergeable(
    plc: &Plc,
    info: &[Option<Loop>],
    u1: (u32, bool),
    u2: (u32, bool),
    rounded: bool,
) -> bool {
    let Some((l1, l2)) = joinable(plc, info, u1, u2) else {
        return false;
    };
    let on_plane = |l: &Loop, other: &Loop| {
        let [a, b, c] = l.plane.map(|v| plc.points[v as usize]);
        let (pa, pb, pc) = (DVec3::from(a), DVec3::from(b), DVec3::from(c));
        let twice_area = (pb - pa).cross(pc - pa).length();
        other.verts.iter().all(|&v| {
            let p = plc.points[v as usize];
            let o = orient3d(a, b, c, p);
            // |orient3d| is the distance from the plane times twice the triangle's area.
            o == 0.0 || rounded && o.abs() <= ROUNDED * max_abs([a, b, c, p]) * twice_area
        })
    };
    on_plane(l1, l2) && (!rounded || on_plane(l2, l1))
}

/// With [`Options3::remesh`](super::Options3::remesh): the largest distance from a facet's
/// plane, relative to the largest coordinate magnitude involved, at which a neighbour's
/// vertex counts as on it. 2^-40 is 4,096 units in the last place of that magnitude: a
/// Steiner point constructed on a plane and rounded lies within a few units of it (the
/// plane is spanned by three such points, which tilts it by as much again across a face),
/// and a fold this flat (an angle of about 1e-12 on a face as large as the model) is no
/// feature a floating-point input can show.
const ROUNDED: f64 = 1.0 / (1u64 << 40) as f64;

/// The largest coordinate magnitude of `ps`.
fn max_abs(ps: [[f64; 3]; 4]) -> f64 {
    ps.iter().flatten().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// The loops of the two facet uses of one edge when they meet every condition of the merge
/// but coplanarity: two distinct facets (no free segment), single loops, the same marker, on
/// opposite sides of the edge in the first loop's projection.
fn joinable<'a>(
    plc: &Plc,
    info: &'a [Option<Loop>],
    u1: (u32, bool),
    u2: (u32, bool),
) -> Option<(&'a Loop, &'a Loop)> {
    let ((f1, d1), (f2, d2)) = (u1, u2);
    if f1 == u32::MAX || f2 == u32::MAX || f1 == f2 {
        return None;
    }
    let (Some(l1), Some(l2)) = (&info[f1 as usize], &info[f2 as usize]) else {
        return None;
    };
    if plc.facets[f1 as usize].marker != plc.facets[f2 as usize].marker {
        return None;
    }
    // Which side of the edge each facet lies on: its orientation in one common projection,
    // flipped when it runs along the edge the other way.
    let side =
        |l: &Loop, forward: bool| l.orientation(plc, l1.axis) * if forward { 1.0 } else { -1.0 };
    let (s1, s2) = (side(l1, d1), side(l2, d2));
    (s1 != 0.0 && s2 != 0.0 && s1 != s2).then_some((l1, l2))
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

/// What [`snap_nearly_coplanar_facets`] (and the tolerance merge of `tetrahedralize`) did.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct SnapReport {
    /// Groups of nearly coplanar facets whose vertices were moved onto one plane.
    pub groups: usize,
    /// Facets in those groups.
    pub facets: usize,
    /// Vertices moved.
    pub moved: usize,
    /// Groups left as they were: a vertex with no floating-point point exactly on the plane
    /// near it, a move that would bend another facet, or (all of them) moves that made the
    /// input invalid.
    pub refused: usize,
}

/// TetGen's `-T<tol>` on its own: `plc` with the vertices of each group of nearly coplanar
/// facets that [`crate::tetrahedralize`] would merge moved exactly onto one plane (the input
/// unchanged when nothing moves), and what moved. Use it to see which facets a tolerance
/// merges; [`crate::mesh3d::Options3::coplanar_tolerance`] applies it when meshing. Errors: an
/// invalid PLC, or `tol` not in `(0, MAX_COPLANAR_TOLERANCE]`.
pub fn snap_nearly_coplanar_facets(plc: &Plc, tol: f64) -> Result<(Plc, SnapReport), Error> {
    crate::input3d::check_plc(plc)?;
    super::check_options(&super::Options3 {
        coplanar_tolerance: Some(tol),
        ..Default::default()
    })?;
    let (out, report) = catch_panic("", || Ok(snap_nearly_coplanar(plc, tol)))?;
    Ok((out.unwrap_or_else(|| plc.clone()), report))
}

/// The input with the vertices of each group of nearly coplanar mergeable facets moved exactly
/// onto the plane of the group's largest facet (see the module docs for the rule), or `None`
/// when nothing moves; `tol` is relative (TetGen's `-T`, default 1e-8) and must be positive.
pub(crate) fn snap_nearly_coplanar(plc: &Plc, tol: f64) -> (Option<Plc>, SnapReport) {
    let mut report = SnapReport::default();
    let nf = plc.facets.len();
    let info: Vec<Option<Loop>> = plc.facets.iter().map(|f| Loop::of(plc, f)).collect();
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); nf];
    for u in edge_uses(plc).values() {
        if let [u1, u2] = u.as_slice() {
            if joinable(plc, &info, *u1, *u2).is_some() {
                neighbours[u1.0 as usize].push(u2.0);
                neighbours[u2.0 as usize].push(u1.0);
            }
        }
    }
    let p = |v: u32| plc.points[v as usize];
    // Size (area, from the Newell normal) and longest edge of each single-loop facet.
    let v3 = |v: u32| DVec3::from_array(p(v));
    let measure = |l: &Loop| {
        let o = v3(l.verts[0]);
        let (mut n, mut longest) = (DVec3::ZERO, 0.0f64);
        for (i, &v) in l.verts.iter().enumerate() {
            let w = l.verts[(i + 1) % l.verts.len()];
            n += (v3(v) - o).cross(v3(w) - o);
            longest = longest.max(v3(w).distance(v3(v)));
        }
        (n.length(), longest)
    };
    let sizes: Vec<(f64, f64)> = info
        .iter()
        .map(|l| l.as_ref().map_or((0.0, 0.0), measure))
        .collect();
    let mut order: Vec<u32> = (0..nf as u32)
        .filter(|&f| info[f as usize].is_some() && !neighbours[f as usize].is_empty())
        .collect();
    // Largest first, areas rounded to single precision: facets of one size (a grid's
    // triangles, whose noise changes their areas only by its square) then keep index order
    // (stable sort), whatever the rounding of their coordinates.
    order.sort_by(|&f, &g| (sizes[g as usize].0 as f32).total_cmp(&(sizes[f as usize].0 as f32)));
    // Groups, grown from the largest facets.
    let mut group_of = vec![NONE; nf];
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for &seed in &order {
        if group_of[seed as usize] != NONE {
            continue;
        }
        group_of[seed as usize] = seed;
        // The reference plane: the coordinate plane through the seed (see `axis_plane`)
        // when the seed is within the tolerance of it, else the seed's own plane, so that
        // the noise of a scanned flat face does not tilt the reference.
        let loop_of = |f: u32| info[f as usize].as_ref();
        let own = loop_of(seed).map_or([[0.0; 3]; 3], |l| l.plane.map(p));
        let within = |t: [[f64; 3]; 3], g: u32| {
            loop_of(g)
                .is_some_and(|l| near_plane(&plc.points, t, &l.verts, tol * sizes[g as usize].1))
        };
        let flat = loop_of(seed).map(|l| axis_plane(&plc.points, own, &l.verts));
        let reference = flat.filter(|&t| within(t, seed)).unwrap_or(own);
        let near = |g: u32| within(reference, g);
        let (mut members, mut queue) = (vec![seed], vec![seed]);
        while let Some(f) = queue.pop() {
            for &g in &neighbours[f as usize] {
                if group_of[g as usize] == NONE && near(g) {
                    group_of[g as usize] = seed;
                    members.push(g);
                    queue.push(g);
                }
            }
        }
        if members.len() > 1 {
            groups.push(members);
        }
    }
    // The facets using each vertex, for the planarity check after a move.
    let mut facets_of: HashMap<u32, Vec<u32>> = HashMap::default();
    for (f, facet) in plc.facets.iter().enumerate() {
        for &v in facet.polygons.iter().flatten() {
            let list = facets_of.entry(v).or_default();
            if list.last() != Some(&(f as u32)) {
                list.push(f as u32);
            }
        }
    }
    let mut points = plc.points.clone();
    for members in &groups {
        let mut verts: Vec<u32> = members
            .iter()
            .filter_map(|&f| info[f as usize].as_ref())
            .flat_map(|l| l.verts.iter().copied())
            .collect();
        verts.sort_unstable();
        verts.dedup();
        let group = Group {
            members,
            verts: &verts,
            info: &info,
            sizes: &sizes,
            tol,
        };
        let planes = group.candidate_planes(&points);
        let moved = planes
            .into_iter()
            .find_map(|t| group.snap(&mut points, t, plc, &facets_of));
        match moved {
            // Exactly coplanar already: the exact merge's business, not counted.
            Some(0) => {}
            Some(n) => {
                report.groups += 1;
                report.facets += members.len();
                report.moved += n;
            }
            None => report.refused += 1,
        }
    }
    if report.moved == 0 {
        return (None, report);
    }
    let out = Plc {
        points,
        ..plc.clone()
    };
    if crate::input3d::check_plc(&out).is_err() {
        report.refused += report.groups;
        (report.groups, report.facets, report.moved) = (0, 0, 0);
        return (None, report);
    }
    (Some(out), report)
}

/// At most this many planes are tried per group (see [`Group::candidate_planes`]).
const MAX_PLANES: usize = 8;

/// A group of nearly coplanar facets to be snapped onto one plane.
struct Group<'a> {
    members: &'a [u32],
    /// The members' vertices, sorted, once each.
    verts: &'a [u32],
    info: &'a [Option<Loop>],
    /// Per facet: (area measure, longest edge).
    sizes: &'a [(f64, f64)],
    tol: f64,
}

impl Group<'_> {
    /// The planes to try, each as three points on it: first the plane parallel to a
    /// coordinate plane (normal: the seed's dominant axis) through the value of that
    /// coordinate most of the group's vertices share (a box face's exact value, where a scan
    /// adds noise to some vertices), then the members' own planes, the seed's first; at most
    /// [`MAX_PLANES`].
    fn candidate_planes(&self, points: &[[f64; 3]]) -> Vec<[[f64; 3]; 3]> {
        let p = |v: u32| points[v as usize];
        let plane_of = |f: u32| self.info[f as usize].as_ref().map(|l| l.plane.map(p));
        let mut planes = Vec::new();
        if let Some(t) = plane_of(self.members[0]) {
            planes.push(axis_plane(points, t, self.verts));
        }
        planes.extend(self.members.iter().filter_map(|&f| plane_of(f)));
        planes.truncate(MAX_PLANES);
        planes
    }

    /// Moves the group's vertices exactly onto the plane through `t` when every member lies
    /// within the tolerance of it, every vertex off it has a floating-point point exactly on
    /// it ([`snap_onto`]), and every facet using a moved vertex stays exactly planar; returns
    /// the number of vertices moved. Otherwise `points` is left as it was and `None` returned.
    fn snap(
        &self,
        points: &mut [[f64; 3]],
        t: [[f64; 3]; 3],
        plc: &Plc,
        facets_of: &HashMap<u32, Vec<u32>>,
    ) -> Option<usize> {
        let within = self.members.iter().all(|&g| {
            self.info[g as usize].as_ref().is_some_and(|l| {
                near_plane(points, t, &l.verts, self.tol * self.sizes[g as usize].1)
            })
        });
        if !within {
            return None;
        }
        let mut undo: Vec<(u32, [f64; 3])> = Vec::new();
        let mut ok = true;
        for &v in self.verts {
            let q = points[v as usize];
            if orient3d(t[0], t[1], t[2], q) == 0.0 {
                continue;
            }
            match snap_onto(t, q) {
                Some(s) => {
                    undo.push((v, q));
                    points[v as usize] = s;
                }
                None => {
                    ok = false;
                    break;
                }
            }
        }
        ok = ok
            && undo.iter().all(|&(v, _)| {
                facets_of.get(&v).map_or(true, |fs| {
                    fs.iter().all(|&f| planar(points, &plc.facets[f as usize]))
                })
            });
        if ok {
            return Some(undo.len());
        }
        for &(v, q) in undo.iter().rev() {
            points[v as usize] = q;
        }
        None
    }
}

/// Whether every vertex of `verts` lies within `distance` of the plane through `t`
/// (floating point: a tolerance, not a geometric decision).
fn near_plane(points: &[[f64; 3]], t: [[f64; 3]; 3], verts: &[u32], distance: f64) -> bool {
    let [a, b, c] = t.map(DVec3::from_array);
    let n = (b - a).cross(c - a);
    let bound = distance * n.length();
    verts
        .iter()
        .all(|&v| n.dot(DVec3::from_array(points[v as usize]) - a).abs() <= bound)
}

/// Three points spanning the plane parallel to a coordinate plane, normal to the dominant
/// axis of the plane of `t`, through the value of that coordinate most of `verts` share (the
/// smallest of the most common values); `points` gives the coordinates.
fn axis_plane(points: &[[f64; 3]], t: [[f64; 3]; 3], verts: &[u32]) -> [[f64; 3]; 3] {
    let [a, b, c] = t.map(DVec3::from_array);
    let n = (b - a).cross(c - a).abs().to_array();
    let k = (0..3).max_by(|&i, &j| n[i].total_cmp(&n[j])).unwrap_or(2);
    let mut values: Vec<f64> = verts.iter().map(|&v| points[v as usize][k]).collect();
    values.sort_by(f64::total_cmp);
    let mut best = (0, 0.0);
    for run in values.chunk_by(|x, y| x == y) {
        if run.len() > best.0 {
            best = (run.len(), run[0]);
        }
    }
    let mut plane = [[0.0; 3]; 3];
    for (m, corner) in plane.iter_mut().enumerate() {
        corner[k] = best.1;
        if m > 0 {
            corner[(k + m) % 3] = 1.0;
        }
    }
    plane
}

/// A point with floating-point coordinates exactly on the plane of `t` near `q`: `q` moved
/// along the axis closest to the plane's normal (its solved coordinate, then up to 8 of that
/// coordinate's floating-point neighbours on each side, each checked exactly). `None` when
/// none of them is on the plane.
fn snap_onto(t: [[f64; 3]; 3], q: [f64; 3]) -> Option<[f64; 3]> {
    let [a, b, c] = t;
    let n = (DVec3::from_array(b) - DVec3::from_array(a))
        .cross(DVec3::from_array(c) - DVec3::from_array(a))
        .to_array();
    let k = (0..3).max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))?;
    let mut s = crate::geometry::along_axis_onto_plane(t, q, k)?;
    let solved = s[k];
    let (mut up, mut down) = (solved, solved);
    for step in 0..17 {
        s[k] = match step {
            0 => solved,
            _ if step % 2 == 1 => {
                up = next_float(up, true);
                up
            }
            _ => {
                down = next_float(down, false);
                down
            }
        };
        if orient3d(a, b, c, s) == 0.0 {
            return Some(s);
        }
    }
    None
}

/// Whether every vertex and hole seed of `facet` lies exactly on one plane (`points` as moved).
fn planar(points: &[[f64; 3]], facet: &Facet) -> bool {
    let verts: Vec<[f64; 3]> = facet
        .polygons
        .iter()
        .flatten()
        .map(|&v| points[v as usize])
        .collect();
    let Some(&a) = verts.first() else {
        return true;
    };
    let plane = verts.iter().enumerate().skip(1).find_map(|(j, &b)| {
        verts[j + 1..]
            .iter()
            .find(|&&c| dominant_axis(a, b, c).is_some())
            .map(|&c| [a, b, c])
    });
    let Some([a, b, c]) = plane else {
        return false;
    };
    verts
        .iter()
        .chain(facet.holes.iter())
        .all(|&d| orient3d(a, b, c, d) == 0.0)
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
        let out = merge_coplanar_facets(&plc, false).expect("the square's halves merge");
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
        assert!(merge_coplanar_facets(&square(tri(0, 1, 4, 1), [1, 2]), false).is_none());
        // (0, 1, 5) is coplanar with (0, 1, 2) but on the other side of 0-1: merged; a
        // triangle folded back onto (0, 1, 2) along 0-1 is not.
        let other_side = square(tri(1, 0, 5, 1), [1, 1]);
        let out = merge_coplanar_facets(&other_side, false).unwrap();
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
        assert!(merge_coplanar_facets(&folded, false).is_none());
        // A free segment on the diagonal keeps it.
        let mut seg = square(tri(0, 1, 4, 1), [1, 1]);
        seg.segments.push([2, 0]);
        assert!(merge_coplanar_facets(&seg, false).is_none());
    }

    #[test]
    fn rounded_neighbours_merge_when_remeshing_and_real_folds_never() {
        // The square's corner 3 lifted by a few units in the last place (a rounded Steiner
        // point), then by 1e-9 (a fold).
        let lifted = |dz: f64| {
            let mut plc = square(tri(0, 1, 4, 1), [1, 1]);
            plc.points[3][2] = dz;
            plc
        };
        let rounded = lifted(4.0 * f64::EPSILON);
        assert!(merge_coplanar_facets(&rounded, false).is_none(), "exact");
        let out = merge_coplanar_facets(&rounded, true).expect("coplanar up to rounding");
        assert_eq!(out.facets.len(), 2);
        assert!(merge_coplanar_facets(&lifted(1e-9), true).is_none());
        // The bound follows the coordinates: the same square moved by 1e6 merges a lift of a
        // few units in the last place of 1e6, and the fold stays.
        let moved = |dz: f64| {
            let mut plc = lifted(0.0);
            plc.points.iter_mut().for_each(|p| p[0] += 1e6);
            plc.points[3][2] = dz;
            plc
        };
        assert!(merge_coplanar_facets(&moved(4.0 * 1e6 * f64::EPSILON), true).is_some());
        assert!(merge_coplanar_facets(&moved(1e-3), true).is_none());
    }

    #[test]
    fn a_boundary_straight_up_to_rounding_is_merged_only_where_exactly_coplanar() {
        // The square with its corner 3 lifted a few units in the last place off z = 0, as a
        // rounded Steiner point is, and its left side running through vertex 5, `dx` off the
        // line x = 0. Triangles (0, 1, 2) and (0, 2, 5) lie exactly in z = 0.
        let plc = |dx: f64| Plc {
            points: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 4.0 * f64::EPSILON],
                [0.5, 0.5, 1.0],
                [dx, 0.5, 0.0],
            ],
            facets: vec![tri(0, 1, 2, 1), tri(0, 2, 5, 1), tri(5, 2, 3, 1)],
            ..Plc::default()
        };
        // Exactly straight, or visibly bent: one facet.
        for dx in [0.0, -1e-3] {
            let out = merge_coplanar_facets(&plc(dx), true).unwrap();
            assert_eq!(out.facets.len(), 1, "dx = {dx}");
        }
        // Straight up to rounding: the exactly coplanar triangles merge (their boundary
        // 0-1-2-5 bends visibly at 5), the lifted one stays apart.
        let out = merge_coplanar_facets(&plc(-1e-17), true).unwrap();
        assert_eq!(out.facets.len(), 2);
        let mut quad = out.facets[0].polygons[0].clone();
        quad.sort_unstable();
        assert_eq!(quad, vec![0, 1, 2, 5]);
        assert_eq!(out.facets[1], plc(-1e-17).facets[2]);
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
        let out = merge_coplanar_facets(&plc, false).unwrap();
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
        let out = merge_coplanar_facets(&ring, false).unwrap();
        assert_eq!(out.facets.len(), 1);
        let mut sizes: Vec<usize> = out.facets[0].polygons.iter().map(|p| p.len()).collect();
        sizes.sort_unstable();
        assert_eq!(sizes, vec![4, 4]);
    }
}
