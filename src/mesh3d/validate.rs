//! Exact checks of the 3D mesh invariants: on an output [`TetMesh`] ([`validate_mesh`]) and on
//! the kernel's [`Tets`] store (`Tets::check_structure` and `Tets::check_locally_delaunay`, in tests).
//!
//! The output check proves that the tets around each interior vertex wind around it exactly
//! once by one exact count per vertex ([`Stars`]), and walks around edges only on the
//! boundary: a pass that streams through the tets instead of chasing neighbours.
//!
//! Every decision is an exact predicate. Floating point only *selects candidates* for the
//! empty-circumsphere check (a uniform grid around each circumsphere, widened by a bound on the
//! circumcenter's rounding error); a vertex is reported only when exact insphere says so.

#[cfg(test)]
use super::store::GHOST;
use super::store::{Tets, FACE};
use super::{TetMesh, NONE};
use crate::error::Error;
use crate::geometry::{dist2_3, tet_circumcenter};
use crate::predicates::{insphere_fast as insphere, orient3d_fast as orient3d};

/// Checks a tet mesh exactly: index ranges and array lengths; every tet positively oriented;
/// neighbours mutual, sharing the right three vertices, on opposite sides of them; no face in
/// more than two tets; every subface a face of some tet; every circumsphere empty of all mesh
/// vertices, or, when the mesh keeps the input surface, no Steiner vertex on a subface (and
/// for an optimised mesh, every subsegment an edge instead of the empty circumspheres). The
/// error names the first offending tet, face or vertex.
pub fn validate_mesh(mesh: &TetMesh) -> Result<(), Error> {
    check_mesh(mesh).map_err(|m| Error::Internal(format!("mesh check failed: {m}")))
}

/// The check every 3D run ends with before it hands back a mesh (issue: never return a broken
/// mesh as a success). Exact and linear in the mesh size: the structure of [`validate_mesh`]
/// (lengths, orientation, neighbours, each face in at most two tets, every subface a face of a
/// tet), the tets around every interior vertex covering the directions around it exactly
/// once ([`Stars`], one count per vertex), and every other edge's tets turning around it less
/// than once (open fan) or exactly once (closed fan): this rules out tets that overlap while
/// each pair of neighbours looks right. It leaves out the empty-sphere test of
/// [`validate_mesh`] (`-C`), which costs about a third of a run and checks a property the
/// kernel keeps by construction. The passes over the tets are split over `threads` threads;
/// what it reports does not depend on how many.
pub(crate) fn check_output(mesh: &TetMesh, threads: usize) -> Result<(), Error> {
    check_output_with(mesh, aim_into, threads)
}

/// [`check_output`] with the aim points of [`Stars`] chosen by `aim` (tests force ties) and
/// the passes over the tets split over `threads` threads.
pub(crate) fn check_output_with(mesh: &TetMesh, aim: Aim, threads: usize) -> Result<(), Error> {
    let run = || -> Result<(), String> {
        let (faces, stars) = check_complex(mesh, aim, threads)?;
        if let Some((i, f)) = mesh.faces.iter().enumerate().find(|(_, f)| {
            f.iter().any(|&v| v as usize >= mesh.vertices.len()) || !faces.contains(**f)
        }) {
            return Err(format!(
                "subface {i} {f:?} is not a face of any tetrahedron"
            ));
        }
        check_edge_winding(mesh, &stars)
    };
    run().map_err(|m| Error::Internal(format!("output check failed: {m}")))
}

/// The structure both checks share, in an order that names the most telling fault first:
/// lengths and index ranges, orientation, neighbours, the vertex stars ([`Stars`]), and the
/// faces in more than two tets. The faces are indexed only where the stars do not already
/// rule that out, and wherever a subface could be.
fn check_complex(m: &TetMesh, aim: Aim, threads: usize) -> Result<(FaceIndex, Stars), String> {
    check_lengths(m)?;
    for (t, tv) in m.tets.iter().enumerate() {
        tick_pass(m, 0, t)?;
        if tv.iter().any(|&v| v as usize >= m.vertices.len()) {
            return Err(format!("tet {t} {tv:?} has a vertex index out of range"));
        }
    }
    let mut stars = Stars::count(m, aim, threads)?;
    check_neighbours(m, threads)?;
    stars.decide()?;
    // A face with a vertex of `Star::Once` lies in exactly two tets or in one with an open
    // side: a third tet would cover the directions near the face twice around that vertex.
    // One byte per vertex (bit 0: `Star::Once`, bit 1: on a subface), read once per tet in
    // place of `stars.of` (a random read through `local`) for every face.
    const ONCE: u8 = 1;
    const SUB: u8 = 2;
    let mut flags: Vec<u8> = (0..m.vertices.len() as u32)
        .map(|v| u8::from(stars.of(v) == Star::Once))
        .collect();
    for &v in m.faces.iter().flatten() {
        if let Some(x) = flags.get_mut(v as usize) {
            *x |= SUB;
        }
    }
    let faces = FaceIndex::new(m, |t| {
        let f = m.tets[t].map(|v| flags[v as usize]);
        let bits = |flag: u8| (0..4).fold(0u8, |b, k| b | (u8::from(f[k] & flag != 0) << k));
        let (once, sub) = (bits(ONCE), bits(SUB));
        (0..4).fold(0u8, |mask, i| {
            let others = 0b1111 & !(1u8 << i);
            let wanted = once & others == 0 || sub & others == others;
            mask | (u8::from(wanted) << i)
        })
    })?;
    Ok((faces, stars))
}

/// Every Steiner point made inside a facet lies within one floating-point step of the
/// facet's plane along the facet's projection axis (exact orientations,
/// [`super::features::within_ulp_of_plane`]): what [`super::features::Features::onto_facet_plane`]
/// guarantees. A point further off makes the boundary faces around it leave the input
/// surface (issue 12, on a scanned model). Points on input edges (in every facet through the
/// edge, on none exactly) are not checked here. Checked before the mesh is moved back to the
/// caller's frame, whose grid rounds the points once more.
pub(crate) fn check_facet_points(
    feat: &super::features::Features,
    pts: &[[f64; 3]],
    num_input: usize,
) -> Result<(), Error> {
    for (&v, fs) in &feat.vert_facets {
        let &[f] = fs.as_slice() else { continue };
        if (v as usize) < num_input || feat.split_edge.contains_key(&v) {
            continue;
        }
        let fi = &feat.facets[f as usize];
        let t = fi.plane.map(|x| pts[x as usize]);
        if !super::features::within_ulp_of_plane(t, pts[v as usize], fi.axis) {
            return Err(Error::Internal(format!(
                "output check failed: Steiner point {v} {:?} is off the plane of facet {f}",
                pts[v as usize]
            )));
        }
    }
    Ok(())
}

/// One step of a check's pass over the tets, for progress reports and cancel (on a 1M-tet
/// mesh the check takes seconds). `pass` numbers the passes over the tets, [`PASSES`] of them;
/// a cancel returns an error text that [`crate::progress::observe`] turns into the run's
/// `Error::Cancelled`.
fn tick_pass(m: &TetMesh, pass: usize, t: usize) -> Result<(), String> {
    let n = m.tets.len();
    crate::progress::tick(|| ((pass * n + t) as u64, (PASSES * n) as u64))
        .map_err(|e| e.to_string())
}

/// The passes over the tets a full check makes (for the progress estimate).
const PASSES: usize = 7;

/// Around every edge, the tets sharing it (walked through neighbours) turn exactly once when
/// they close up, and less than once when the fan is open. Measured exactly: with `c0` the
/// first apex, the signs of `orient3d(a, b, c0, c)` along the fan change at most once, and no
/// later apex lies on `c0`'s half-plane (that would be a second turn). Each fan is walked once
/// (a bit per tet edge marks it done), so the check costs O(1) per tet edge.
///
/// Most fans need no walk: [`Stars`] first proves, vertex by vertex, that the tets
/// around an interior vertex cover the directions around it exactly once, which makes its
/// star an embedded ball and every edge at it turn exactly once. Only edges with no such
/// vertex (on the boundary, or where the proof met a tie) are walked; the walk reads two tet
/// records per step, a dependent cache miss each, where the proof streams through the tets.
fn check_edge_winding(m: &TetMesh, stars: &Stars) -> Result<(), String> {
    // Local edge number of the pair of positions (i, j), i < j.
    const EDGE_BIT: [[u8; 4]; 4] = [[0, 1, 2, 4], [1, 0, 8, 16], [2, 8, 0, 32], [4, 16, 32, 0]];
    const EDGES: [[usize; 4]; 6] = [
        [0, 1, 2, 3],
        [0, 2, 3, 1],
        [0, 3, 1, 2],
        [1, 2, 0, 3],
        [1, 3, 2, 0],
        [2, 3, 0, 1],
    ];
    let Stars {
        local,
        coords,
        tally,
        star,
    } = stars;
    let p = |v: u32| coords[local[v as usize] as usize];
    let mut done = vec![0u8; m.tets.len()];
    let mark = |t: u32, a: u32, b: u32, done: &mut [u8]| {
        let tv = m.tets[t as usize];
        if let (Some(i), Some(j)) = (
            tv.iter().position(|&v| v == a),
            tv.iter().position(|&v| v == b),
        ) {
            done[t as usize] |= EDGE_BIT[i][j];
        }
    };
    // Across the face of tet `t` made of `a`, `b` and `w`: the next tet and its apex there.
    let step = |t: u32, a: u32, b: u32, w: u32| -> Option<(u32, u32)> {
        let tv = m.tets[t as usize];
        let i = tv.iter().position(|&v| v != a && v != b && v != w)?;
        let n = m.neighbors[t as usize][i];
        if n == NONE {
            return None;
        }
        let apex = *m.tets[n as usize].iter().find(|&&v| !tv.contains(&v))?;
        Some((n, apex))
    };
    let budget = m.tets.len() + 1;
    // Per vertex (local numbering): edges walked (fans of tets around an edge).
    let mut edges_at = vec![0u32; coords.len()];
    let at = |v: u32| local[v as usize] as usize;
    let (mut apexes, mut back): (Vec<u32>, Vec<u32>) = (Vec::new(), Vec::new());
    for t0 in 0..m.tets.len() as u32 {
        tick_pass(m, 5, t0 as usize)?;
        let tv = m.tets[t0 as usize];
        // Every edge at a proven vertex turns exactly once. Edges at an unproven interior
        // vertex are all walked: the Euler count below needs them. (A tet with three proven
        // corners and no unproven one, most of them, has no edge to walk.)
        let st = tv.map(|v| star[at(v)]);
        if !st.contains(&Star::Unknown) && st.iter().filter(|&&x| x == Star::Once).count() >= 3 {
            continue;
        }
        for (k, e) in EDGES.iter().enumerate() {
            if done[t0 as usize] & (1 << k) != 0 {
                continue;
            }
            let [a, b, c, d] = e.map(|k| tv[k]);
            let (sa, sb) = (st[e[0]], st[e[1]]);
            if (sa == Star::Once || sb == Star::Once) && sa != Star::Unknown && sb != Star::Unknown
            {
                continue;
            }
            mark(t0, a, b, &mut done);
            edges_at[at(a)] += 1;
            edges_at[at(b)] += 1;
            // Forward from t0 across a-b-c; if the fan opens there, backward across a-b-d.
            apexes.clear();
            back.clear();
            let (mut t, mut w) = (t0, c);
            let mut closed = false;
            while let Some((n, apex)) = step(t, a, b, w) {
                if n == t0 {
                    closed = true;
                    break;
                }
                if apexes.len() > budget {
                    return Err(format!("the tets around edge [{a}, {b}] do not close up"));
                }
                mark(n, a, b, &mut done);
                apexes.push(apex);
                (t, w) = (n, apex);
            }
            if !closed {
                (t, w) = (t0, d);
                while let Some((n, apex)) = step(t, a, b, w) {
                    if back.len() > budget {
                        return Err(format!("the tets around edge [{a}, {b}] do not close up"));
                    }
                    mark(n, a, b, &mut done);
                    back.push(apex);
                    (t, w) = (n, apex);
                }
            }
            // Turning order: the backward apexes reversed, d, c, the forward apexes (closed:
            // the last forward apex is d again and is dropped).
            if closed {
                apexes.pop();
            }
            back.reverse();
            back.extend([d, c]);
            back.extend_from_slice(&apexes);
            if let Err(why) = turns_once(a, b, &back, closed, &p) {
                return Err(format!(
                    "the tets around edge [{a}, {b}] (apexes {back:?}) {why}"
                ));
            }
        }
    }
    // Around a vertex with no open face, the faces opposite it must form one sphere: Euler
    // characteristic V - E + F = 2 with F its tets, E = 3F/2 its faces and V its edges.
    // With every edge turning exactly once, the link then covers the sphere of directions
    // exactly once; tets wrapping twice around a vertex give two spheres (4), which the
    // edges alone do not show.
    if let Some(i) = (0..coords.len())
        .find(|&i| star[i] == Star::Unknown && 2 * edges_at[i] != tally[i].tets + 4)
    {
        let v = local.iter().position(|&l| l as usize == i).unwrap_or(i);
        return Err(format!(
            "the tets around vertex {v} do not wind around it exactly once ({} tets, {} edges)",
            tally[i].tets, edges_at[i]
        ));
    }
    Ok(())
}

/// What [`Stars`] proved about the tets around a vertex.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Star {
    /// A face through the vertex has no tet behind it: nothing to prove.
    Open,
    /// The tets around the vertex cover the directions around it exactly once.
    Once,
    /// The aimed direction lies on the plane of a face through the vertex (a tie): unproven.
    Unknown,
}

/// Picks a vertex's aim point for [`Stars`] from the corners of the first tet listing it.
pub(crate) type Aim = fn([[f64; 3]; 4]) -> [f64; 3];

/// A point inside the tet with corners `c`, by weights 1, 2, 3, 5 (out of 11): away from every
/// corner, and, unlike the centroid, off the planes through a corner that lattice-like meshes
/// (points on a grid) are full of, so that [`Stars`] rarely meets a tie.
pub(crate) fn aim_into(c: [[f64; 3]; 4]) -> [f64; 3] {
    [0, 1, 2].map(|k| (c[0][k] + 2.0 * c[1][k] + 3.0 * c[2][k] + 5.0 * c[3][k]) / 11.0)
}

/// The vertices renumbered in the order the tets first list them (coordinates copied in that
/// order), and what the tets around each one were proved to do.
///
/// The renumbering is for speed: the passes over the tets read vertices as the tets list them,
/// and tets made in the kernel's spatial insertion order would otherwise hit vertices numbered
/// in the input's order (random for a scattered point set), a cache miss each.
///
/// The proof, per vertex with no open face around it: count exactly the tets whose corner at
/// the vertex contains the direction towards an aim point ([`aim_into`] of the first tet
/// listing the vertex; any point other than the vertex would do). Around such a vertex every
/// face through it has a tet on each side, linked as neighbours on opposite sides of it
/// (checked by [`check_neighbours`]), and every tet is positively oriented: seen from the
/// vertex, the faces opposite it are positively oriented triangles on the sphere of
/// directions, glued in pairs along their sides, each pair on opposite sides of the shared
/// arc. The number of triangles over a direction then
/// stays the same as the direction crosses any arc (one triangle is left, its neighbour is
/// entered), so it is the same for every direction off the arcs: one count decides it.
/// Exactly one means the tets around the vertex fill a ball around it once, every edge at it
/// turning exactly once and every face through it in exactly two tets; more (tets winding
/// twice, two stars sharing the vertex, a face in three tets) is reported. A direction on an
/// arc (a zero orientation where no sign is negative) leaves the vertex [`Star::Unknown`], for
/// the edge walks to decide.
struct Stars {
    /// Local number of each vertex ([`NONE`] for a vertex in no tet).
    local: Vec<u32>,
    /// By local number: coordinates, and what the tets around the vertex showed.
    coords: Vec<[f64; 3]>,
    tally: Vec<Tally>,
    /// By local number, filled by [`Stars::decide`].
    star: Vec<Star>,
}

/// Per vertex, side by side so that one read serves a corner: its tets, its faces with no tet
/// behind, the tets whose corner at it holds the aimed direction, and whether a tie left that
/// count undecided.
#[derive(Clone, Copy, Default)]
struct Tally {
    tets: u32,
    open: u32,
    count: u32,
    tie: bool,
}

impl Stars {
    /// Renumbers the vertices (with each one's tets and open faces), then checks that every
    /// tet is positively oriented and counts, on `threads` threads: two passes over the tets.
    /// The counts mean something only once the neighbours are checked.
    fn count(m: &TetMesh, aim: Aim, threads: usize) -> Result<Stars, String> {
        let nv = m.vertices.len();
        let mut local = vec![NONE; nv];
        let mut coords: Vec<[f64; 3]> = Vec::with_capacity(nv);
        let mut aims: Vec<[f64; 3]> = Vec::with_capacity(nv);
        let mut tally: Vec<Tally> = Vec::with_capacity(nv);
        for (t, tv) in m.tets.iter().enumerate() {
            let l = tv.map(|v| {
                let x = &mut local[v as usize];
                if *x == NONE {
                    *x = coords.len() as u32;
                    coords.push(m.vertices[v as usize]);
                    aims.push(aim(tv.map(|w| m.vertices[w as usize])));
                    tally.push(Tally::default());
                }
                *x as usize
            });
            for (i, &li) in l.iter().enumerate() {
                tally[li].tets += 1;
                if m.neighbors[t][i] == NONE {
                    for (j, &lj) in l.iter().enumerate() {
                        if j != i {
                            tally[lj].open += 1;
                        }
                    }
                }
            }
        }
        // The orientations and the counts, in chunks of tets on the run's threads. Each chunk
        // keeps a byte per vertex: the count (saturating) and a tie bit. Open vertices are
        // counted too, and sorted out by `decide`.
        const TIE: u8 = 0x80;
        let parts = crate::threads::chunks(m.tets.len(), threads, 1 << 16, |range, stop| {
            let first = range.start == 0;
            let mut seen = vec![0u8; coords.len()];
            for t in range {
                if first {
                    tick_pass(m, 1, (t * threads).min(m.tets.len()))?;
                } else if crate::threads::stopped(t, stop) {
                    break;
                }
                let tv = m.tets[t];
                let l = tv.map(|v| local[v as usize] as usize);
                let c = l.map(|i| coords[i]);
                if orient3d(c[0], c[1], c[2], c[3]) >= 0.0 {
                    return Err(format!(
                        "tet {t} {tv:?} is not positively oriented (flat or inverted)"
                    ));
                }
                for (i, &li) in l.iter().enumerate() {
                    if seen[li] & TIE != 0 {
                        continue;
                    }
                    let r = aims[li];
                    // `FACE[j]` lists face j outward: the tet lies where orient3d(face, x) > 0,
                    // and its corner at i is bounded by the three faces through i (all but i).
                    let (mut inside, mut zero) = (true, false);
                    for (j, f) in FACE.iter().enumerate() {
                        if j == i {
                            continue;
                        }
                        let s = orient3d(c[f[0]], c[f[1]], c[f[2]], r);
                        if s < 0.0 {
                            inside = false;
                            break;
                        }
                        zero |= s == 0.0;
                    }
                    if inside {
                        if zero {
                            seen[li] |= TIE;
                        } else if seen[li] < TIE - 1 {
                            seen[li] += 1;
                        }
                    }
                }
            }
            Ok(seen)
        });
        // The first fault in tet order, whatever the thread count.
        let parts = parts.into_iter().collect::<Result<Vec<_>, String>>()?;
        for part in &parts {
            for (x, &b) in tally.iter_mut().zip(part) {
                x.count += u32::from(b & !TIE);
                x.tie |= b & TIE != 0;
            }
        }
        Ok(Stars {
            local,
            coords,
            tally,
            star: Vec::new(),
        })
    }

    /// Turns the counts into [`Star`]s; an error names a vertex whose tets cover the
    /// directions around it more than once. Call only once the neighbours are checked.
    fn decide(&mut self) -> Result<(), String> {
        let mut star = Vec::with_capacity(self.coords.len());
        for (i, x) in self.tally.iter().enumerate() {
            star.push(if x.open != 0 {
                Star::Open
            } else if x.tie {
                Star::Unknown
            } else if x.count == 1 {
                Star::Once
            } else {
                let v = self
                    .local
                    .iter()
                    .position(|&l| l as usize == i)
                    .unwrap_or(i);
                return Err(format!(
                    "the tets around vertex {v} do not wind around it exactly once (they \
                     cover a direction {} times)",
                    x.count
                ));
            });
        }
        self.star = star;
        Ok(())
    }

    /// What was proved about vertex `v`'s star (a vertex in no tet is [`Star::Open`]).
    fn of(&self, v: u32) -> Star {
        match self.local.get(v as usize) {
            Some(&l) if l != NONE => self.star[l as usize],
            _ => Star::Open,
        }
    }
}

/// See [`check_edge_winding`]: `apexes` in turning order around the line a-b.
fn turns_once(
    a: u32,
    b: u32,
    apexes: &[u32],
    closed: bool,
    p: &impl Fn(u32) -> [f64; 3],
) -> Result<(), &'static str> {
    let (pa, pb) = (p(a), p(b));
    let c0 = p(apexes[0]);
    // Any plane through a-b other than c0's separates c0's half-plane from the opposite one;
    // the second apex spans one (its tet with a, b, c0 is not flat).
    let c1 = p(apexes[1]);
    let side0 = orient3d(pa, pb, c1, c0);
    let mut last = 0.0f64;
    let mut changes = 0;
    for &w in &apexes[1..] {
        let q = p(w);
        let s = orient3d(pa, pb, c0, q);
        if s == 0.0 {
            if orient3d(pa, pb, c1, q) * side0 > 0.0 {
                return Err("turn more than once (an apex returns to the first one's side)");
            }
            continue;
        }
        if last != 0.0 && (s > 0.0) != (last > 0.0) {
            changes += 1;
        }
        last = s;
    }
    if changes > 1 {
        return Err("turn more than once");
    }
    if closed && changes == 0 {
        return Err("close up without going around the edge");
    }
    Ok(())
}

fn check_mesh(m: &TetMesh) -> Result<(), String> {
    let (faces, stars) = check_complex(m, aim_into, crate::threads::count().unwrap_or(1))?;
    for (i, f) in m.faces.iter().enumerate() {
        if f.iter().any(|&v| v as usize >= m.vertices.len()) {
            return Err(format!("subface {i} has a vertex index out of range"));
        }
        if f[0] == f[1] || f[1] == f[2] || f[0] == f[2] {
            return Err(format!("subface {i} repeats a vertex"));
        }
        if !faces.contains(*f) {
            return Err(format!(
                "subface {i} {f:?} is not a face of any tetrahedron"
            ));
        }
        if m.surface_kept {
            if let Some(&v) = f.iter().find(|&&v| v as usize >= m.num_input_vertices) {
                return Err(format!(
                    "subface {i} {f:?} has the Steiner vertex {v}, but the surface is kept"
                ));
            }
        }
    }
    check_edge_winding(m, &stars)?;
    if m.optimized {
        // Flips and smoothing give up the Delaunay property (`TetMesh::optimized`); what they
        // must keep is checked instead: every subsegment is still an edge of the mesh.
        check_subsegments(m)?;
    }
    if m.surface_kept || m.optimized {
        // Not Delaunay next to the surface (see `TetMesh::surface_kept`) or anywhere.
        return Ok(());
    }
    check_empty_spheres(m)
}

/// Every subsegment is an edge of some tetrahedron.
fn check_subsegments(m: &TetMesh) -> Result<(), String> {
    let mut edges: crate::hash::FastSet<[u32; 2]> = crate::hash::FastSet::default();
    for (t, tv) in m.tets.iter().enumerate() {
        tick_pass(m, 6, t)?;
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            edges.insert([tv[i].min(tv[j]), tv[i].max(tv[j])]);
        }
    }
    match m
        .edges
        .iter()
        .enumerate()
        .find(|(_, e)| !edges.contains(&[e[0].min(e[1]), e[0].max(e[1])]))
    {
        Some((i, e)) => Err(format!(
            "subsegment {i} {e:?} is not an edge of any tetrahedron"
        )),
        None => Ok(()),
    }
}

fn check_lengths(m: &TetMesh) -> Result<(), String> {
    let (nv, nt) = (m.vertices.len(), m.tets.len());
    let pairs = [
        ("vertex markers", m.vertex_markers.len(), nv),
        ("neighbour rows", m.neighbors.len(), nt),
        ("face markers", m.face_markers.len(), m.faces.len()),
        ("edge markers", m.edge_markers.len(), m.edges.len()),
    ];
    for (what, got, want) in pairs {
        if got != want {
            return Err(format!("{got} {what}, expected {want}"));
        }
    }
    if !m.tet_attributes.is_empty() && m.tet_attributes.len() != nt {
        return Err(format!(
            "{} tet attributes for {nt} tetrahedra",
            m.tet_attributes.len()
        ));
    }
    if m.num_input_vertices > nv {
        return Err(format!(
            "{} input vertices but only {nv} vertices",
            m.num_input_vertices
        ));
    }
    for (i, e) in m.edges.iter().enumerate() {
        if e.iter().any(|&v| v as usize >= nv) || e[0] == e[1] {
            return Err(format!(
                "subsegment {i} {e:?} is not a pair of distinct vertices"
            ));
        }
    }
    Ok(())
}

/// Mutual, geometrically consistent neighbours (vertex indices already checked in range,
/// every tet positively oriented).
fn check_neighbours(m: &TetMesh, threads: usize) -> Result<(), String> {
    let parts = crate::threads::blocks(m.tets.len(), threads, 1 << 15, |range, block| {
        for t in range {
            if block.on_caller {
                // Blocks are dealt in order: the caller's position is about the work done.
                tick_pass(m, 2, t)?;
            } else if block.stopped(t) {
                break;
            }
            neighbours_of(m, t)?;
        }
        Ok(())
    });
    // The first fault in tet order, whatever the thread count.
    parts.into_iter().collect()
}

/// [`check_neighbours`] for tet `t`.
fn neighbours_of(m: &TetMesh, t: usize) -> Result<(), String> {
    let nt = m.tets.len();
    let tv = m.tets[t];
    #[allow(clippy::needless_range_loop)] // i indexes the neighbours and FACE alike
    for i in 0..4 {
        let n = m.neighbors[t][i];
        if n == NONE {
            continue;
        }
        if n as usize >= nt {
            return Err(format!("tet {t} has neighbour {n} out of range"));
        }
        let Some(j) = (0..4).find(|&j| m.neighbors[n as usize][j] == t as u32) else {
            return Err(format!("tets {t} and {n} are not mutual neighbours"));
        };
        let face = FACE[i].map(|k| tv[k]);
        let other = m.tets[n as usize];
        let seen = FACE[j].map(|k| other[k]);
        let Some(k) = seen.iter().position(|&v| v == face[0]) else {
            return Err(format!(
                "tets {t} {tv:?} and {n} {other:?} are neighbours but do not share face {face:?}"
            ));
        };
        let (next, prev) = (seen[(k + 1) % 3], seen[(k + 2) % 3]);
        if !((next == face[1] && prev == face[2]) || (next == face[2] && prev == face[1])) {
            return Err(format!(
                "tets {t} {tv:?} and {n} {other:?} are neighbours but do not share face {face:?}"
            ));
        }
        // `FACE[i]` lists the face outward for its tet: orient3d(face, own apex) > 0 for a
        // positively oriented tet (checked exactly by `Stars::count`). So n's apex lies
        // strictly on the other side of the face exactly when n lists the face in the
        // opposite cyclic order (orient3d changes sign with an odd permutation): a
        // combinatorial test, no coordinates read.
        if next == face[1] {
            return Err(format!(
                "tets {t} and {n} lie on the same side of their shared face {face:?}"
            ));
        }
    }
    Ok(())
}

/// Every distinct face of the mesh that the caller wants indexed (`wanted(t)`: a bit per face
/// of tet `t`, bit i for the face opposite corner i), grouped by smallest vertex
/// (counting sort), each group sorted: detects such faces in more than two tets and answers
/// "is this a face" in O(log) for them.
struct FaceIndex {
    start: Vec<u32>,
    keys: Vec<u64>,
}

impl FaceIndex {
    /// Records each face once (interior faces from the tet with the smaller index) and fails
    /// if a face is recorded twice, i.e. it lies in more than two tets or in two tets that are
    /// not linked as neighbours.
    fn new(m: &TetMesh, wanted: impl Fn(usize) -> u8) -> Result<FaceIndex, String> {
        let nv = m.vertices.len();
        let recorded = |t: usize, i: usize, mask: u8| {
            let n = m.neighbors[t][i];
            mask & (1 << i) != 0 && (n == NONE || (t as u32) < n)
        };
        let sorted = |t: usize, i: usize| {
            let mut f = FACE[i].map(|k| m.tets[t][k]);
            f.sort_unstable();
            f
        };
        let mut start = vec![0u32; nv + 1];
        for t in 0..m.tets.len() {
            tick_pass(m, 3, t)?;
            let mask = wanted(t);
            for i in 0..4 {
                if recorded(t, i, mask) {
                    start[sorted(t, i)[0] as usize + 1] += 1;
                }
            }
        }
        for v in 0..nv {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut keys = vec![0u64; start[nv] as usize];
        for t in 0..m.tets.len() {
            tick_pass(m, 4, t)?;
            let mask = wanted(t);
            for i in 0..4 {
                if recorded(t, i, mask) {
                    let f = sorted(t, i);
                    let slot = &mut fill[f[0] as usize];
                    keys[*slot as usize] = ((f[1] as u64) << 32) | f[2] as u64;
                    *slot += 1;
                }
            }
        }
        drop(fill);
        for v in 0..nv {
            tick_pass(m, 4, m.tets.len())?;
            let group = &mut keys[start[v] as usize..start[v + 1] as usize];
            group.sort_unstable();
            if let Some(w) = group.windows(2).find(|w| w[0] == w[1]) {
                return Err(format!(
                    "face [{v}, {}, {}] lies in more than two tets, or in two tets that are not \
                     neighbours",
                    w[0] >> 32,
                    w[0] & 0xffff_ffff
                ));
            }
        }
        Ok(FaceIndex { start, keys })
    }

    fn contains(&self, mut f: [u32; 3]) -> bool {
        f.sort_unstable();
        let group =
            &self.keys[self.start[f[0] as usize] as usize..self.start[f[0] as usize + 1] as usize];
        group
            .binary_search(&(((f[1] as u64) << 32) | f[2] as u64))
            .is_ok()
    }
}

/// Points bucketed into a uniform `g × g × g` grid over their bounding box (compressed cells).
/// It only selects candidates; decisions on them are exact.
struct Grid3 {
    lo: [f64; 3],
    w: [f64; 3],
    /// Per-axis allowance for rounding in the cell arithmetic (cells are treated as this much
    /// wider), so no point is dropped from a query by an ulp.
    tol: [f64; 3],
    g: usize,
    /// Cell `(x, y, z)` is number `(x·g + y)·g + z`, so a column of cells along z is one
    /// contiguous run of items.
    start: Vec<u32>,
    /// Vertex ids, cell by cell, and their coordinates alongside (a query then reads memory
    /// in order instead of chasing ids into the vertex array).
    items: Vec<u32>,
    coords: Vec<[f64; 3]>,
}

impl Grid3 {
    fn new(pts: &[[f64; 3]]) -> Grid3 {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in pts {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        // About half a point per cell: a typical circumsphere then meets a few dozen cells.
        let g = ((2.0 * pts.len() as f64).cbrt().ceil() as usize).clamp(1, 400);
        let w = [0, 1, 2].map(|k| ((hi[k] - lo[k]) / g as f64).max(f64::MIN_POSITIVE));
        let tol = [0, 1, 2].map(|k| 1e-9 * w[k] + 1e-14 * (lo[k].abs() + hi[k].abs()));
        let mut grid = Grid3 {
            lo,
            w,
            tol,
            g,
            start: vec![0; g * g * g + 1],
            items: vec![0; pts.len()],
            coords: vec![[0.0; 3]; pts.len()],
        };
        for p in pts {
            let c = grid.cell_of(*p);
            grid.start[c + 1] += 1;
        }
        for i in 0..g * g * g {
            grid.start[i + 1] += grid.start[i];
        }
        let mut fill = grid.start.clone();
        for (v, p) in pts.iter().enumerate() {
            let c = grid.cell_of(*p);
            grid.items[fill[c] as usize] = v as u32;
            grid.coords[fill[c] as usize] = *p;
            fill[c] += 1;
        }
        grid
    }

    fn cell(&self, x: f64, k: usize) -> usize {
        let c = (x - self.lo[k]) / self.w[k];
        // Truncation is floor for c >= 0; NaN and negatives clamp to cell 0.
        if c >= 0.0 {
            (c as usize).min(self.g - 1)
        } else {
            0
        }
    }

    fn cell_of(&self, p: [f64; 3]) -> usize {
        (self.cell(p[0], 0) * self.g + self.cell(p[1], 1)) * self.g + self.cell(p[2], 2)
    }

    /// Squared distance from `x` to the interval of cell `i` along axis `k` (0 inside).
    fn gap2(&self, x: f64, i: usize, k: usize) -> f64 {
        let lo = self.lo[k] + i as f64 * self.w[k] - self.tol[k];
        let hi = lo + self.w[k] + 2.0 * self.tol[k];
        let d = if x < lo {
            lo - x
        } else if x > hi {
            x - hi
        } else {
            0.0
        };
        d * d
    }

    /// Calls `f` for every point in the cells that meet the ball of radius `r` around `c` (a
    /// superset of the points in the ball: edge cells reach to infinity, as points beyond the
    /// box are clamped into them, and every cell is widened by `tol`). Stops when `f` returns
    /// an error.
    fn for_each_in_ball(
        &self,
        c: [f64; 3],
        r: f64,
        mut f: impl FnMut(u32, [f64; 3]) -> Result<(), String>,
    ) -> Result<(), String> {
        let r2 = r * r;
        let t = self.tol;
        let (x0, x1) = (self.cell(c[0] - r - t[0], 0), self.cell(c[0] + r + t[0], 0));
        let (y0, y1) = (self.cell(c[1] - r - t[1], 1), self.cell(c[1] + r + t[1], 1));
        for x in x0..=x1 {
            let dx = if x == 0 || x == self.g - 1 {
                0.0
            } else {
                self.gap2(c[0], x, 0)
            };
            for y in y0..=y1 {
                let dy = if y == 0 || y == self.g - 1 {
                    0.0
                } else {
                    self.gap2(c[1], y, 1)
                };
                let rest = r2 - dx - dy;
                if rest < 0.0 {
                    continue;
                }
                let h = rest.sqrt() * (1.0 + 1e-12) + t[2];
                let column = (x * self.g + y) * self.g;
                let first = self.start[column + self.cell(c[2] - h, 2)] as usize;
                let end = self.start[column + self.cell(c[2] + h, 2) + 1] as usize;
                for (&v, &q) in self.items[first..end].iter().zip(&self.coords[first..end]) {
                    f(v, q)?;
                }
            }
        }
        Ok(())
    }
}

/// Every tet's open circumsphere is empty of all mesh vertices (exact insphere on the
/// candidates of a grid search; tets whose circumcenter cannot be trusted test every vertex).
fn check_empty_spheres(m: &TetMesh) -> Result<(), String> {
    if m.tets.is_empty() {
        return Ok(());
    }
    let grid = Grid3::new(&m.vertices);
    let p = |v: u32| m.vertices[v as usize];
    for (t, tv) in m.tets.iter().enumerate() {
        tick_pass(m, 6, t)?;
        let c = tv.map(p);
        let [a, b, cc, d] = c;
        let query = sphere_query(c);
        // Points surely outside the widened ball need no exact test.
        let (center, reach2) = match query {
            Some((center, r)) => (center, r * r * (1.0 + 1e-9)),
            None => ([0.0; 3], f64::INFINITY),
        };
        let test = |w: u32, q: [f64; 3]| {
            if dist2_3(center, q) > reach2 {
                return Ok(());
            }
            // Real tets have orient3d < 0, which flips Shewchuk's insphere sign.
            if !tv.contains(&w) && insphere(a, b, cc, d, q) < 0.0 {
                Err(format!(
                    "vertex {w} lies strictly inside the circumsphere of tet {t} {tv:?}"
                ))
            } else {
                Ok(())
            }
        };
        match query {
            Some((center, r)) => grid.for_each_in_ball(center, r, test)?,
            None => (0..m.vertices.len() as u32).try_for_each(|w| test(w, p(w)))?,
        }
    }
    Ok(())
}

/// A ball that surely contains the circumsphere of the tet: the floating-point circumcenter
/// with its radius widened by an error bound that grows with the tet's condition (longest
/// edge cubed over volume). `None` when that bound is meaningless (a nearly flat tet).
fn sphere_query(c: [[f64; 3]; 4]) -> Option<([f64; 3], f64)> {
    let center = tet_circumcenter(c)?;
    let r = c
        .iter()
        .map(|&q| dist2_3(center, q))
        .fold(0.0f64, f64::max)
        .sqrt();
    let mut l2 = 0.0f64;
    for i in 0..4 {
        for j in i + 1..4 {
            l2 = l2.max(dist2_3(c[i], c[j]));
        }
    }
    let l = l2.sqrt();
    let vol6 = crate::geometry::tet_volume(c).abs() * 6.0;
    let cond = l * l * l / vol6;
    // Rounding moves the computed center by about cond · ε · (r + l); 1e-10 leaves a margin of
    // several orders of magnitude over ε = 1.1e-16.
    let slack = 1e-10 * cond * (r + l) + 1e-300;
    if !(slack.is_finite() && center.iter().all(|x| x.is_finite())) || slack > 1e3 * (r + l) {
        return None;
    }
    Some((center, r + 2.0 * slack))
}

impl Tets {
    /// Debug check of the store: live neighbours with mutual links across the same three
    /// vertices; real tets positively oriented and on opposite sides of shared faces; each ghost
    /// has one [`GHOST`] vertex and its hull triangle faces a real tet; the hull is locally
    /// convex; the vertex-to-tet map points at live incident tets. Exact. The message names the
    /// first offending tet or vertex.
    #[cfg(test)]
    pub fn check_structure(&self) -> Result<(), String> {
        let p = |v: u32| self.point(v);
        for t in 0..self.num_slots() as u32 {
            if !self.alive(t) {
                continue;
            }
            let tv = self.verts(t);
            let ghosts = tv.iter().filter(|&&v| v == GHOST).count();
            if ghosts > 1 {
                return Err(format!("tet {t} {tv:?} has {ghosts} ghost vertices"));
            }
            for (i, &v) in tv.iter().enumerate() {
                if v != GHOST && v as usize >= self.num_vertices() {
                    return Err(format!("tet {t} has vertex {v} out of range"));
                }
                if tv[..i].contains(&v) {
                    return Err(format!("tet {t} {tv:?} repeats vertex {v}"));
                }
            }
            if ghosts == 0 {
                let [a, b, c, d] = tv.map(p);
                if orient3d(a, b, c, d) >= 0.0 {
                    return Err(format!("real tet {t} {tv:?} is flat or inverted"));
                }
            }
            for f in 0..4 {
                let (u, g) = self.neighbor(t, f);
                if u == NONE && ghosts == 0 && self.vertex_tet(GHOST) == NONE {
                    continue; // an open face of a carved store
                }
                if u as usize >= self.num_slots() || !self.alive(u) {
                    return Err(format!("tet {t} face {f}: neighbour {u} is not a live tet"));
                }
                if self.neighbor(u, g) != (t, f) {
                    return Err(format!(
                        "tet {t} face {f} -> tet {u} face {g}, which does not link back"
                    ));
                }
                let uv = self.verts(u);
                let face = FACE[f].map(|k| tv[k]);
                let mut fa = face;
                let mut fb = FACE[g].map(|k| uv[k]);
                fa.sort_unstable();
                fb.sort_unstable();
                if fa != fb {
                    return Err(format!(
                        "tets {t} {tv:?} and {u} {uv:?} are linked across different faces"
                    ));
                }
                let real_t = ghosts == 0;
                let real_u = !uv.contains(&GHOST);
                if real_t && real_u {
                    let [x, y, z] = face.map(p);
                    if orient3d(x, y, z, p(uv[g])) >= 0.0 {
                        return Err(format!(
                            "tets {t} and {u} lie on the same side of face {face:?}"
                        ));
                    }
                }
                if !real_t && tv[f] == GHOST && !real_u {
                    return Err(format!("ghost {t}'s hull triangle faces ghost {u}"));
                }
                if !real_t && tv[f] != GHOST && !real_u {
                    // Two hull triangles sharing an edge: the hull must not fold inwards
                    // there, i.e. u's far vertex is not strictly beyond t's hull triangle.
                    let k = tv.iter().position(|&v| v == GHOST).unwrap_or(0);
                    let [x, y, z] = FACE[k].map(|i| p(tv[i]));
                    let w = uv[g];
                    if w != GHOST && orient3d(x, y, z, p(w)) > 0.0 {
                        return Err(format!(
                            "hull is not convex at ghosts {t} and {u} (vertex {w})"
                        ));
                    }
                }
            }
        }
        for v in 0..self.num_vertices() as u32 {
            let t = self.vertex_tet(v);
            if t == NONE {
                continue;
            }
            if t as usize >= self.num_slots() || !self.alive(t) || !self.verts(t).contains(&v) {
                return Err(format!(
                    "vertex {v}'s tet {t} is dead or does not contain it"
                ));
            }
        }
        Ok(())
    }

    /// Debug check that every interior face is locally Delaunay: the apex of the tet across a
    /// face is not strictly inside the circumsphere of the tet, and no vertex is beyond a hull
    /// triangle's circumcircle test (the ghost conflict rule). With a valid structure this
    /// means the whole tetrahedralization is Delaunay. Exact.
    #[cfg(test)]
    pub fn check_locally_delaunay(&self) -> Result<(), String> {
        for t in 0..self.num_slots() as u32 {
            if !self.alive(t) {
                continue;
            }
            for f in 0..4 {
                let (u, g) = self.neighbor(t, f);
                if u == NONE {
                    continue;
                }
                let w = self.verts(u)[g];
                if w == GHOST || self.verts(t).contains(&w) {
                    continue;
                }
                if self.conflict(t, self.point(w)) {
                    return Err(format!(
                        "vertex {w} of tet {u} is in conflict with its neighbour tet {t}"
                    ));
                }
            }
        }
        Ok(())
    }
}
