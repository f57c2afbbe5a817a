//! Exact checks of an output mesh's invariants: indices, orientation, adjacency, empty
//! circumcircles against every vertex, and subsegments present as edges.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};

use super::kdtree::PointTree;
use super::{TriMesh, NONE};
use crate::geometry::circumcenter;
use crate::predicates::{incircle, incircle_fast, orient2d};

/// One step of a check's pass over the triangles, for progress reports and cancel (on a
/// 1M-triangle mesh the checks take a noticeable part of a second). `pass` numbers the passes,
/// [`PASSES`] of them; a cancel returns an error text that [`crate::progress::observe`] turns
/// into the run's `Error::Cancelled`.
fn tick_pass(m: &TriMesh, pass: usize, t: usize) -> Result<(), String> {
    let n = m.triangles.len();
    crate::progress::tick(|| ((pass * n + t) as u64, (PASSES * n) as u64))
        .map_err(|e| e.to_string())
}

/// The passes over the triangles a full check makes (for the progress estimate).
const PASSES: usize = 5;

/// `m` with its vertices scaled up by [`crate::geometry::tiny_scale`], when they are that
/// small.
fn scaled_up(m: &TriMesh) -> Option<TriMesh> {
    let s = crate::geometry::tiny_scale(m.vertices.iter())?;
    let mut c = m.clone();
    for p in &mut c.vertices {
        *p = [p[0] * s, p[1] * s];
    }
    Some(c)
}

/// The threads a check of a caller's mesh uses (`IDMESH_THREADS`, else all cores).
fn default_threads() -> usize {
    crate::threads::count().unwrap_or(1)
}

pub(super) fn validate(m: &TriMesh) -> Result<(), String> {
    let scaled = scaled_up(m);
    let m = scaled.as_ref().unwrap_or(m);
    if !m.complete {
        // The budget can stop the splits that make segments conforming: the guarantee of
        // an incomplete mesh is the constrained rule.
        return validate_constrained(m, default_threads());
    }
    validate_structure(m, true, default_threads())?;
    check_empty_circles(m, &Chains::new(m))
}

/// The subsegments grouped into chains along one input segment: two subsegments meeting at
/// a Steiner vertex of no other subsegment belong to one chain.
///
/// Split points of a slanted segment are rounded, so the vertices of one chain are
/// collinear only up to an ulp or so; a chain piece much shorter than its coordinates are
/// large then has a direction off by the rounding over its length, and another vertex of
/// the same chain can fall a hair inside the circumcircle of a long, thin triangle on the
/// piece. With the points exactly on their line (as the input defines them) that is
/// impossible: a line meets a circle twice, at the piece's ends, and no vertex of the chain
/// lies between them. The empty-circle checks forgive exactly that case (the meshes keep
/// the empty-circle rule for every vertex off the chain).
pub(super) struct Chains {
    /// (vertex, chain) for every subsegment endpoint.
    member: std::collections::HashSet<(u32, u32)>,
    /// The chains through each subsegment endpoint.
    at: HashMap<u32, Vec<u32>>,
}

impl Chains {
    pub(super) fn new(m: &TriMesh) -> Chains {
        let ns = m.segments.len();
        let mut parent: Vec<u32> = (0..ns as u32).collect();
        fn find(parent: &mut [u32], mut x: u32) -> u32 {
            while parent[x as usize] != x {
                let g = parent[parent[x as usize] as usize];
                parent[x as usize] = g;
                x = g;
            }
            x
        }
        // Subsegments at each Steiner vertex (the first two, and how many).
        let mut at: HashMap<u32, (u32, u32, u32)> = HashMap::new();
        for (s, e) in m.segments.iter().enumerate() {
            for &v in e {
                if (v as usize) < m.num_input_vertices {
                    continue;
                }
                let x = at.entry(v).or_insert((NONE, NONE, 0));
                if x.2 == 0 {
                    x.0 = s as u32;
                } else if x.2 == 1 {
                    x.1 = s as u32;
                }
                x.2 += 1;
            }
        }
        for &(s, t, n) in at.values() {
            if n == 2 {
                let (a, b) = (find(&mut parent, s), find(&mut parent, t));
                parent[a as usize] = b;
            }
        }
        let mut member = std::collections::HashSet::with_capacity(2 * ns);
        let mut vat: HashMap<u32, Vec<u32>> = HashMap::new();
        for (s, e) in m.segments.iter().enumerate() {
            let c = find(&mut parent, s as u32);
            for v in *e {
                if member.insert((v, c)) {
                    vat.entry(v).or_default().push(c);
                }
            }
        }
        Chains { member, at: vat }
    }

    /// Whether the rounding of chain points explains vertex `v` inside the circumcircle of
    /// `tri`: two corners of `tri` and `v` lie on one chain (the line through the two meets
    /// the circle only there), or all three corners do (a sliver that rounding made out of
    /// three points of one line; it has no circle in exact terms).
    pub(super) fn forgives(&self, tri: [u32; 3], v: u32) -> bool {
        let on = |x: u32, c: u32| self.member.contains(&(x, c));
        (0..3).any(|i| {
            let (p, q) = (tri[i], tri[(i + 1) % 3]);
            self.of(p)
                .any(|c| on(q, c) && (on(v, c) || on(tri[(i + 2) % 3], c)))
        })
    }

    /// The chains through vertex `v`.
    fn of(&self, v: u32) -> impl Iterator<Item = u32> + '_ {
        self.at.get(&v).into_iter().flatten().copied()
    }
}

/// The structure plus the constrained empty-circle rule: no vertex visible from a triangle's
/// interior (not hidden behind a subsegment) lies strictly inside its circumcircle. Checked in
/// its local form, which is equivalent for a triangulated domain bounded by segments (Lee and
/// Lin; Chew): every edge that is not a subsegment has two triangles, and neither's far vertex
/// lies strictly inside the other's circumcircle.
pub(super) fn validate_constrained(m: &TriMesh, threads: usize) -> Result<(), String> {
    let scaled = scaled_up(m);
    validate_locally(scaled.as_ref().unwrap_or(m), true, threads)
}

/// The structure, and every edge with two triangles locally Delaunay (with `skip_segments`,
/// edges that are subsegments are exempt: the constrained rule above). Without the exemption
/// this is the cheap exact check every conforming run ends with: it catches a kernel that
/// lost the Delaunay property, though not a vertex seen only across a hole or the outside.
pub(super) fn validate_locally(
    m: &TriMesh,
    skip_segments: bool,
    threads: usize,
) -> Result<(), String> {
    locally_forgiving(m, skip_segments, threads).map(|_| ())
}

/// The conforming run's final check: [`validate_locally`], and when it had to forgive the
/// rounding of a chain (see [`Chains`]) the global empty-circle check as well, since the
/// local form no longer implies it then.
pub(super) fn validate_final(m: &TriMesh, threads: usize) -> Result<(), String> {
    if locally_forgiving(m, false, threads)? > 0 {
        check_empty_circles(m, &Chains::new(m))?;
    }
    Ok(())
}

/// [`validate_locally`], returning how many locally non-Delaunay edges the chains forgave.
///
/// The structure checks and the local rule run in one pass over the triangles (on a mesh
/// that passes, as every mesh a run hands back does, each triangle is read once). When that
/// pass finds a fault, the checks run again one after the other, so that the fault reported
/// is the one [`validate_structure`] and then the local rule name first, whatever the thread
/// count.
fn locally_forgiving(m: &TriMesh, skip_segments: bool, threads: usize) -> Result<usize, String> {
    check_lengths(m)?;
    let chains = Chains::new(m);
    let segs = SegmentIndex::new(m);
    let skip = |p: u32, q: u32| skip_segments && segs.wanted.contains_key(&(p.min(q), p.max(q)));
    let fused = in_chunks(m, 0, threads, |t| {
        let links = triangle_structure(m, t, Adjacency::Later)?;
        segs.visit(m, t)?;
        let forgiven = local_rule(m, t, &skip, &chains)?;
        Ok(Tally { forgiven, ..links })
    });
    let fused = fused
        .into_iter()
        .try_fold(Tally::default(), |mut sum, part| {
            sum += part?;
            Ok::<Tally, String>(sum)
        });
    if let (Ok(sum), None) = (&fused, segs.missing(m)) {
        if sum.later == sum.earlier {
            return Ok(sum.forgiven);
        }
    }
    validate_structure(m, true, threads)?;
    let parts = in_chunks(m, 3, threads, |t| local_rule(m, t, &skip, &chains));
    let forgiven = parts.into_iter().sum::<Result<usize, String>>()?;
    // Not reached: a fault of the fused pass is found again by the passes one at a time.
    Ok(forgiven)
}

/// What the fused pass of [`locally_forgiving`] sums over the triangles.
#[derive(Clone, Copy, Default)]
struct Tally {
    /// Locally non-Delaunay edges the chains forgave.
    forgiven: usize,
    /// Neighbour links [`triangle_structure`] checked with [`Adjacency::Later`] (to a later
    /// triangle), and those it only counted (to an earlier one).
    later: usize,
    earlier: usize,
}

impl std::ops::AddAssign for Tally {
    fn add_assign(&mut self, o: Tally) {
        self.forgiven += o.forgiven;
        self.later += o.later;
        self.earlier += o.earlier;
    }
}

/// How much of the neighbour table [`triangle_structure`] checks.
#[derive(Clone, Copy, PartialEq)]
enum Adjacency {
    /// None of it.
    No,
    /// Every link: the neighbour is in range and links back across the same edge.
    All,
    /// Only links to later triangles, as `All` does; links to earlier ones are counted, not
    /// read. With a triangle's neighbours distinct (checked), every checked link pairs with a
    /// distinct earlier link of its neighbour, so when the two counts agree over the whole
    /// mesh every link is paired and the table is as `All` would find it. Half the random
    /// reads of `All` (the check is bound by them); a mismatch is told by rerunning `All`.
    Later,
}

/// The local empty-circle rule at triangle `t`: across each edge to a later neighbour that
/// `skip` does not exempt, the neighbour's far vertex is not strictly inside `t`'s
/// circumcircle, unless the chains forgive it ([`Chains`]); returns how many they forgave.
/// Indices are checked (the neighbour's structure may not have been checked yet).
fn local_rule(
    m: &TriMesh,
    t: usize,
    skip: &impl Fn(u32, u32) -> bool,
    chains: &Chains,
) -> Result<usize, String> {
    let tri = &m.triangles[t];
    let mut forgiven = 0;
    for i in 0..3 {
        let n = m.neighbors[t][i];
        if n == NONE || (n as usize) < t {
            continue;
        }
        let (p, q) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
        if skip(p, q) {
            continue;
        }
        let Some(other) = m.triangles.get(n as usize) else {
            return Err(format!("triangle {t} has neighbour {n} out of range"));
        };
        let Some(far) = other.iter().copied().find(|&v| v != p && v != q) else {
            return Err(format!("triangles {t} and {n} share all their vertices"));
        };
        let (Some(&d), Some(a), Some(b), Some(c)) = (
            m.vertices.get(far as usize),
            m.vertices.get(tri[0] as usize),
            m.vertices.get(tri[1] as usize),
            m.vertices.get(tri[2] as usize),
        ) else {
            return Err(format!(
                "triangle {t} or {n} has a vertex index out of range"
            ));
        };
        if incircle_fast(*a, *b, *c, d) > 0.0 {
            if !chains.forgives(*tri, far) {
                return Err(format!(
                    "vertex {far} lies inside the circumcircle of triangle {t} across \
                     edge ({p}, {q})"
                ));
            }
            forgiven += 1;
        }
    }
    Ok(forgiven)
}

/// Runs `check(t)` for every triangle `t`, in blocks dealt to `threads` threads
/// ([`crate::threads::blocks`]; pass `pass` of the progress reports, ticked by the calling
/// thread), and returns each block's sum of results or its first error: the first error in
/// triangle order is then the first error of the returned parts, whatever the thread count.
fn in_chunks<R: Default + std::ops::AddAssign + Send>(
    m: &TriMesh,
    pass: usize,
    threads: usize,
    check: impl Fn(usize) -> Result<R, String> + Sync,
) -> Vec<Result<R, String>> {
    let n = m.triangles.len();
    crate::threads::blocks(n, threads, 1 << 15, |range, block| {
        let mut sum = R::default();
        for t in range {
            if block.on_caller {
                // Blocks are dealt in order: the caller's position is about the work done.
                tick_pass(m, pass, t)?;
            } else if block.stopped(t) {
                break;
            }
            sum += check(t)?;
        }
        Ok(sum)
    })
}

/// The lengths of the per-vertex and per-triangle tables.
fn check_lengths(m: &TriMesh) -> Result<(), String> {
    let nv = m.vertices.len();
    let nt = m.triangles.len();
    if m.neighbors.len() != nt {
        return Err(format!(
            "{} neighbour rows for {nt} triangles",
            m.neighbors.len()
        ));
    }
    if m.vertex_markers.len() != nv {
        return Err(format!(
            "{} vertex markers for {nv} vertices",
            m.vertex_markers.len()
        ));
    }
    if !m.triangle_attributes.is_empty() && m.triangle_attributes.len() != nt {
        return Err(format!(
            "{} attributes for {nt} triangles",
            m.triangle_attributes.len()
        ));
    }
    Ok(())
}

/// Triangle `t`'s indices and orientation, and as `adjacency` says its neighbours: in range,
/// mutual, sharing the edge. Counts the links it checked and those it left (see
/// [`Adjacency::Later`]).
fn triangle_structure(m: &TriMesh, t: usize, adjacency: Adjacency) -> Result<Tally, String> {
    let (nv, nt) = (m.vertices.len(), m.triangles.len());
    let tri = &m.triangles[t];
    if tri.iter().any(|&v| v as usize >= nv) {
        return Err(format!("triangle {t} has a vertex index out of range"));
    }
    let [a, b, c] = tri.map(|v| m.vertices[v as usize]);
    if orient2d(a, b, c) <= 0.0 {
        return Err(format!("triangle {t} is not strictly counter-clockwise"));
    }
    let mut links = Tally::default();
    let nb = m.neighbors[t];
    if adjacency == Adjacency::Later
        && (0..3).any(|i| nb[i] != NONE && (nb[i] == nb[(i + 1) % 3] || nb[i] == t as u32))
    {
        return Err(format!("triangle {t} lists a neighbour twice or itself"));
    }
    for i in 0..3 {
        let n = nb[i];
        if n == NONE || adjacency == Adjacency::No {
            continue;
        }
        if n as usize >= nt {
            return Err(format!("triangle {t} has neighbour {n} out of range"));
        }
        if adjacency == Adjacency::Later && (n as usize) < t {
            links.earlier += 1;
            continue;
        }
        links.later += 1;
        let (p, q) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
        let other = m.triangles[n as usize];
        let back = (0..3).find(|&j| m.neighbors[n as usize][j] == t as u32);
        let Some(j) = back else {
            return Err(format!("triangles {t} and {n} are not mutual neighbours"));
        };
        if other[(j + 1) % 3] != q || other[(j + 2) % 3] != p {
            return Err(format!(
                "triangles {t} and {n} do not share the edge ({p}, {q})"
            ));
        }
    }
    Ok(links)
}

/// The subsegments, hashed (the few, not the many edges), to check that every boundary edge
/// is one and to mark which are edges in one pass over the triangles.
struct SegmentIndex {
    wanted: HashMap<(u32, u32), usize>,
    /// Whether each vertex ends a subsegment: only edges between two such can be one.
    endpoint: Vec<bool>,
    marks: Vec<AtomicBool>,
}

impl SegmentIndex {
    fn new(m: &TriMesh) -> SegmentIndex {
        let mut wanted = HashMap::with_capacity(m.segments.len());
        let mut endpoint = vec![false; m.vertices.len()];
        for (s, e) in m.segments.iter().enumerate() {
            wanted.insert((e[0].min(e[1]), e[0].max(e[1])), s);
            for v in *e {
                if let Some(x) = endpoint.get_mut(v as usize) {
                    *x = true;
                }
            }
        }
        let marks = (0..m.segments.len())
            .map(|_| AtomicBool::new(false))
            .collect();
        SegmentIndex {
            wanted,
            endpoint,
            marks,
        }
    }

    /// Triangle `t`: each edge without a neighbour must be a subsegment (the domain is bounded
    /// by segments); marks the subsegments among its edges. Vertex indices in range.
    fn visit(&self, m: &TriMesh, t: usize) -> Result<usize, String> {
        let tri = &m.triangles[t];
        for i in 0..3 {
            let (p, q) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
            let key = (p.min(q), p.max(q));
            if m.neighbors[t][i] == NONE && !self.wanted.contains_key(&key) {
                return Err(format!(
                    "boundary edge ({p}, {q}) of triangle {t} is on no segment"
                ));
            }
            if !(self.endpoint[p as usize] && self.endpoint[q as usize]) {
                continue;
            }
            if let Some(&s) = self.wanted.get(&key) {
                self.marks[s].store(true, Ordering::Relaxed);
            }
        }
        Ok(0)
    }

    /// The first subsegment no visited triangle had as an edge, as an error.
    fn missing(&self, m: &TriMesh) -> Option<String> {
        let s = self.marks.iter().position(|f| !f.load(Ordering::Relaxed))?;
        let e = m.segments[s];
        Some(format!(
            "subsegment {s} ({}, {}) is not a mesh edge",
            e[0], e[1]
        ))
    }
}

/// Everything but the empty-circle check: indices, orientation, subsegments, and with
/// `adjacency` the neighbour table.
pub(super) fn validate_structure(
    m: &TriMesh,
    adjacency: bool,
    threads: usize,
) -> Result<(), String> {
    check_lengths(m)?;
    let adjacency = if adjacency {
        Adjacency::All
    } else {
        Adjacency::No
    };
    let parts = in_chunks(m, 0, threads, |t| triangle_structure(m, t, adjacency));
    for part in parts {
        part?;
    }
    let segs = SegmentIndex::new(m);
    let parts = in_chunks(m, 1, threads, |t| segs.visit(m, t));
    parts.into_iter().sum::<Result<usize, String>>()?;
    match segs.missing(m) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Every triangle's open circumdisk must hold no vertex. Candidates come from a k-d tree over
/// the vertices; the float circumcircle only selects them (generously padded), the decision
/// is the exact in-circle test.
fn check_empty_circles(m: &TriMesh, chains: &Chains) -> Result<(), String> {
    let nv = m.vertices.len();
    if nv == 0 || m.triangles.is_empty() {
        return Ok(());
    }
    let ids: Vec<u32> = (0..nv as u32).collect();
    let tree = PointTree::new(&m.vertices, &ids).map_err(|e| e.to_string())?;
    for (t, tri) in m.triangles.iter().enumerate() {
        tick_pass(m, 4, t)?;
        let [a, b, c] = tri.map(|v| m.vertices[v as usize]);
        let Some(o) = circumcenter(a, b, c) else {
            return Err(format!("triangle {t} has no finite circumcenter"));
        };
        let r = ((o[0] - a[0]).hypot(o[1] - a[1])) * (1.0 + 1e-9) + 1e-300;
        let mut inside = None;
        tree.for_each_near(o, r, |v| {
            if !tri.contains(&v)
                && incircle(a, b, c, m.vertices[v as usize]) > 0.0
                && !chains.forgives(*tri, v)
            {
                inside = Some(v);
                return false;
            }
            true
        });
        if let Some(v) = inside {
            return Err(format!(
                "vertex {v} lies inside the circumcircle of triangle {t}"
            ));
        }
    }
    Ok(())
}
