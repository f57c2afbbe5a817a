//! Delaunay tetrahedralization of a point set ([`super::delaunay3d`]): validate the points,
//! insert them in BRIO + Hilbert order into one [`Tets`] kernel, and write a [`TetMesh`].
//!
//! Internally vertices are numbered in insertion order, so that points inserted one after the
//! other (close along the Hilbert curve) are also close in memory; the output check runs in
//! that numbering too, and the mesh is then renamed back to the input numbering.

use super::order::brio_hilbert_order;
use super::store::{Insertion, TetId, Tets, VertexId, FACE, GHOST};
use super::{TetMesh, NONE};
use crate::error::{Error, InputError, MAX_COORD};
use crate::predicates::{collinear3 as collinear, orient3d};

/// Seed of the insertion-order shuffle (fixed: the output is reproducible).
const ORDER_SEED: u64 = 0x1D3E_5A17_0000_0003;

/// Checks the points: finite, not too large, at least four. Reports the first bad point.
pub(crate) fn check_points(points: &[[f64; 3]]) -> Result<(), Error> {
    for (i, p) in points.iter().enumerate() {
        if !p.iter().all(|x| x.is_finite()) {
            return Err(InputError::NonFinitePoint { point: i }.into());
        }
        if p.iter().any(|x| x.abs() > MAX_COORD) {
            return Err(InputError::CoordinateTooLarge { point: i }.into());
        }
    }
    if points.len() < 4 {
        return Err(InputError::TooFewPoints3 {
            count: points.len(),
        }
        .into());
    }
    Ok(())
}

/// Positions in `order` of the first four vertices that span a tetrahedron: the first vertex,
/// the next one at a different point, the next one off their line, the next one off their
/// plane. Errors (naming input points through `index_of`) when the points are all equal,
/// collinear or coplanar.
fn first_tet(
    tets: &Tets,
    order: &[VertexId],
    index_of: &impl Fn(VertexId) -> usize,
) -> Result<[usize; 4], Error> {
    let p = |i: usize| tets.point(order[i]);
    let n = order.len();
    let i1 = (1..n).find(|&i| p(i) != p(0)).ok_or_else(|| {
        let (a, b) = (index_of(order[0]), index_of(order[1]));
        InputError::DuplicatePoint {
            first: a.min(b),
            second: a.max(b),
        }
    })?;
    let i2 = (i1 + 1..n)
        .find(|&i| !collinear(p(0), p(i1), p(i)))
        .ok_or(InputError::AllCollinear)?;
    let i3 = (i2 + 1..n)
        .find(|&i| orient3d(p(0), p(i1), p(i2), p(i)) != 0.0)
        .ok_or(InputError::AllCoplanar)?;
    Ok([0, i1, i2, i3])
}

/// Inserts the vertices `order` (pushed, none inserted yet, at least two) into the empty
/// kernel `tets`, in that order, except that the first four that span a tetrahedron (see
/// [`first_tet`]) make the first tet. Returns the last tet created (a walking hint).
///
/// Errors name input points through `index_of` (the caller's numbering): a duplicate point
/// (both indices), all points equal, collinear or coplanar, or an internal failure.
pub(crate) fn insert_vertices(
    tets: &mut Tets,
    order: &[VertexId],
    index_of: impl Fn(VertexId) -> usize,
) -> Result<TetId, Error> {
    if order.len() < 4 {
        return Err(InputError::TooFewPoints3 { count: order.len() }.into());
    }
    let first = first_tet(tets, order, &index_of)?;
    let [a, b, c, d] = first.map(|i| order[i]);
    tets.init(a, b, c, d);
    let mut hint = tets.vertex_tet(a);
    for (i, &v) in order.iter().enumerate() {
        crate::progress::tick(|| (i as u64, order.len() as u64))?;
        if first.contains(&i) {
            continue;
        }
        match tets.try_insert(v, hint) {
            Insertion::Inserted(t) => hint = t,
            Insertion::Duplicate(w) => {
                let (a, b) = (index_of(v), index_of(w));
                return Err(InputError::DuplicatePoint {
                    first: a.min(b),
                    second: a.max(b),
                }
                .into());
            }
            Insertion::Lost => {
                return Err(Error::Internal(format!(
                    "3D Delaunay: no tetrahedron in conflict with point {}",
                    index_of(v)
                )))
            }
        }
    }
    Ok(hint)
}

/// Builds the Delaunay tetrahedralization of `points` into a fresh kernel, inserting in BRIO +
/// Hilbert order. Kernel vertex `k` is input point `input_of[k]`: vertices are numbered in
/// insertion order, so that consecutive insertions touch nearby memory. Errors on invalid,
/// duplicate or flat input.
pub(crate) fn build(points: &[[f64; 3]]) -> Result<(Tets, Vec<u32>), Error> {
    check_points(points)?;
    let input_of = brio_hilbert_order(points, ORDER_SEED);
    let mut tets = Tets::with_capacity(points.len());
    for &i in &input_of {
        tets.push_vertex(points[i as usize]);
    }
    let order: Vec<VertexId> = (0..points.len() as VertexId).collect();
    insert_vertices(&mut tets, &order, |v| input_of[v as usize] as usize)?;
    Ok((tets, input_of))
}

/// The Delaunay tetrahedralization of `points` as a [`TetMesh`] (see [`super::delaunay3d`]),
/// passed through `check` first.
///
/// The check runs on the mesh still in the kernel's names (insertion order), where tets made
/// one after the other have vertices close in memory: in input order (random, for scattered
/// points) it missed the cache at nearly every tet. The names go back afterwards (a renaming
/// of vertices, which changes no tet, coordinate or adjacency); a fault is told in the
/// input's names.
pub(crate) fn delaunay(
    points: &[[f64; 3]],
    check: impl Fn(&TetMesh) -> Result<(), Error>,
) -> Result<TetMesh, Error> {
    use crate::progress::{stage, Stage};
    stage(Stage::Delaunay, || (0, points.len() as u64))?;
    let (tets, input_of) = build(points)?;
    stage(Stage::Output, || (0, tets.num_slots() as u64))?;
    let mut mesh = to_mesh(&tets);
    mesh.vertices = tets.into_points();
    let checked = check(&mesh);
    unrank(&mut mesh, &input_of, points);
    match checked {
        Ok(()) => Ok(mesh),
        Err(e) => Err(check(&mesh).err().unwrap_or(e)),
    }
}

/// Gives mesh `m`, made in the kernel's names (input point `input_of[k]` as vertex `k`), the
/// input's names and coordinates.
fn unrank(m: &mut TetMesh, input_of: &[u32], points: &[[f64; 3]]) {
    let name = |v: u32| input_of[v as usize];
    for t in &mut m.tets {
        *t = t.map(name);
    }
    for f in &mut m.faces {
        *f = f.map(name);
    }
    m.vertices = points.to_vec();
}

/// Writes the real tets of `tets` as a [`TetMesh`] in the kernel's vertex names (the caller
/// sets the vertices): positive tets, neighbours (`NONE` on the hull), hull faces oriented
/// outward.
fn to_mesh(tets: &Tets) -> TetMesh {
    let slots = tets.num_slots();
    let mut out_id = vec![NONE; slots];
    let mut count = 0u32;
    let mut hull = 0usize;
    for t in 0..slots as u32 {
        if tets.alive(t) {
            if tets.is_ghost(t) {
                hull += 1;
            } else {
                out_id[t as usize] = count;
                count += 1;
            }
        }
    }
    let mut out_tets = Vec::with_capacity(count as usize);
    let mut neighbors = Vec::with_capacity(count as usize);
    let mut faces = Vec::with_capacity(hull);
    for t in 0..slots as u32 {
        if !tets.alive(t) {
            continue;
        }
        let v = tets.verts(t);
        if let Some(k) = v.iter().position(|&x| x == GHOST) {
            // The real tet across the hull triangle lists it outward (counter-clockwise seen
            // from outside the hull).
            let (r, f) = tets.neighbor(t, k);
            let rv = tets.verts(r);
            faces.push(FACE[f].map(|i| rv[i]));
            continue;
        }
        out_tets.push(v);
        neighbors.push([0, 1, 2, 3].map(|f| out_id[tets.neighbor(t, f).0 as usize]));
    }
    drop(out_id);
    let n = tets.num_vertices();
    TetMesh {
        vertices: Vec::new(),
        vertex_markers: vec![0; n],
        num_input_vertices: n,
        tets: out_tets,
        neighbors,
        tet_attributes: Vec::new(),
        face_markers: vec![0; faces.len()],
        faces,
        edges: Vec::new(),
        edge_markers: Vec::new(),
        complete: true,
        steiner_points: 0,
        surface_kept: false,
        optimized: false,
    }
}
