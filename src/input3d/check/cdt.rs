//! One facet's projected vertices as a constrained triangulation without Steiner points, and
//! the classification of its triangles into the facet's region, its holes and the outside.
//!
//! The facet checks need the facet as a set of triangles on its own vertices, whatever its
//! loops look like (holes, nested loops, loops sharing edges, dangling edges). The
//! triangulation is the 2D mesher's incremental kernel ([`crate::mesh2d::kernel::Cdt`], paper
//! §2): the points go in by Bowyer–Watson, each polygon edge is recovered as a constrained
//! edge (split where a vertex lies inside it), and a flood from infinity and from the hole
//! seeds that stops at polygon edges labels the triangles, as TetGen defines a facet's
//! region. Every decision is an exact `orient2d` or `incircle`.

use crate::mesh2d::kernel::{Cdt, Inserted, Recovery, Seg, EXTERIOR, HOLE, NONE, NO_REGION};

/// Why a facet could not be triangulated.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum CdtError {
    /// Two constraint edges cross; the tags they were inserted with.
    Crossing(u32, u32),
    /// The kernel failed or a loop ran out of its iteration budget (a bug; never expected).
    Budget(&'static str),
}

/// A facet's triangulation: the kernel's store, or nothing when the points are collinear.
#[derive(Default)]
pub(crate) struct FacetTriangulation {
    cdt: Option<Cdt>,
}

impl FacetTriangulation {
    /// Triangulates `pts` (distinct points). Collinear input gives no triangles.
    pub fn triangulate(&mut self, pts: &[[f64; 2]]) -> Result<(), CdtError> {
        self.cdt = None;
        if pts.len() < 3 {
            return Ok(());
        }
        let mut cdt = Cdt::new(pts);
        let Some(c) = (2..pts.len()).find(|&c| cdt.orient_ids(0, 1, c as u32) != 0.0) else {
            return Ok(());
        };
        let c = c as u32;
        if cdt.orient_ids(0, 1, c) > 0.0 {
            cdt.init_triangle(0, 1, c);
        } else {
            cdt.init_triangle(1, 0, c);
        }
        for v in 2..pts.len() as u32 {
            if v == c {
                continue;
            }
            if !matches!(cdt.insert_bulk(v), Inserted::Yes(_)) {
                return Err(CdtError::Budget("point insertion"));
            }
        }
        cdt.sync_aux();
        self.cdt = Some(cdt);
        Ok(())
    }

    /// Makes the edge `ab` part of the triangulation and records it with `tag`. Vertices lying
    /// inside `ab` split it. Fails when `ab` crosses an edge recovered before.
    pub fn constrain(&mut self, a: u32, b: u32, tag: u32) -> Result<(), CdtError> {
        let Some(cdt) = self.cdt.as_mut() else {
            return Ok(());
        };
        let mut a = a;
        for _ in 0..cdt.pts.len() {
            let s = cdt.segs.len() as u32;
            cdt.segs.push(Seg {
                a,
                b,
                input: tag,
                marker: 0,
                fixed: false,
            });
            match cdt.insert_segment(s) {
                Recovery::Edge(_) if cdt.segs[s as usize].b == b => return Ok(()),
                Recovery::Edge(_) => a = cdt.segs[s as usize].b,
                // The piece up to the vertex goes in first; the rest in the next round.
                Recovery::Through(v) => {
                    cdt.segs[s as usize].b = v;
                    match cdt.insert_segment(s) {
                        Recovery::Edge(_) => a = v,
                        Recovery::Blocked(o) => {
                            return Err(CdtError::Crossing(tag, cdt.segs[o as usize].input))
                        }
                        _ => return Err(CdtError::Budget("constraint recovery")),
                    }
                }
                Recovery::Blocked(o) => {
                    return Err(CdtError::Crossing(tag, cdt.segs[o as usize].input))
                }
                Recovery::Failed => return Err(CdtError::Budget("constraint recovery")),
            }
            if a == b {
                return Ok(());
            }
        }
        Err(CdtError::Budget("constraint splits"))
    }

    /// Triangulates the counter-clockwise simple polygon `ring` (vertex ids, projected by
    /// `p2`) on its own vertices: the constrained Delaunay triangulation of its corners with
    /// its edges as constraints, the triangles inside appended to `out` (counter-clockwise,
    /// as ids of `ring`). `None`, with `out` unchanged, when `ring` is not a counter-clockwise
    /// simple polygon in this projection: fewer than three corners, all on a line, a repeated
    /// point, an edge through another corner, edges that cross, or clockwise order (then some
    /// edge `a b` of the ring is not an edge `a → b` of a triangle inside). Every decision is
    /// an exact `orient2d` or `incircle`.
    pub fn polygon(
        ring: &[u32],
        p2: &dyn Fn(u32) -> [f64; 2],
        out: &mut Vec<[u32; 3]>,
    ) -> Option<()> {
        let n = ring.len();
        if n < 3 {
            return None;
        }
        let pts: Vec<[f64; 2]> = ring.iter().map(|&v| p2(v)).collect();
        let mut ft = FacetTriangulation::default();
        ft.triangulate(&pts).ok()?;
        for i in 0..n as u32 {
            let j = (i + 1) % n as u32;
            ft.constrain(i, j, i).ok()?;
            // A corner inside the edge splits it: the ring touches itself there.
            let cdt = ft.cdt.as_ref()?;
            if cdt.segs.last().map(|s| (s.a, s.b)) != Some((i, j)) {
                return None;
            }
        }
        ft.classify(&[]);
        let inside: Vec<[u32; 3]> = ft.region().collect();
        let directed: crate::hash::FastSet<(u32, u32)> = inside
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .collect();
        let ccw = (0..n as u32).all(|i| directed.contains(&(i, (i + 1) % n as u32)));
        if inside.len() != n - 2 || !ccw {
            return None;
        }
        out.extend(inside.iter().map(|t| t.map(|k| ring[k as usize])));
        Some(())
    }

    /// Whether edge `ab` was recovered as a constraint (tests only).
    #[cfg(test)]
    pub fn is_constrained(&self, a: u32, b: u32) -> bool {
        self.cdt
            .as_ref()
            .is_some_and(|cdt| cdt.find_edge(a, b).is_some_and(|h| cdt.seg_at(h) != NONE))
    }

    /// Labels the triangles: those reachable from infinity without crossing a constraint are
    /// outside, those reachable from a hole seed are holes, the rest form the region. A seed
    /// on an edge starts from the first unlabelled triangle beside it; seeds outside the
    /// triangulation or in the outside do nothing.
    pub fn classify(&mut self, seeds: &[[f64; 2]]) {
        let Some(cdt) = self.cdt.as_mut() else {
            return;
        };
        let mut stack = Vec::new();
        for t in 0..cdt.num_slots() as u32 {
            if cdt.alive(t) && cdt.is_ghost(t) {
                cdt.aux[t as usize].reg = EXTERIOR;
                stack.push(t);
            }
        }
        cdt.flood(&mut stack, EXTERIOR);
        for &s in seeds {
            let Ok(t) = cdt.locate(cdt.vtri[0], s, false) else {
                continue;
            };
            if cdt.is_ghost(t) {
                continue;
            }
            // `s` lies in `t` or on its boundary: on an edge, the triangle across is a
            // candidate too.
            let mut pick = (cdt.aux[t as usize].reg == NO_REGION).then_some(t);
            for i in 0..3 {
                let h = 3 * t + i;
                let (x, y) = cdt.edge_ends(h);
                let n = cdt.twin(h) / 3;
                if pick.is_none()
                    && cdt.orient_at(x, y, s) == 0.0
                    && !cdt.is_ghost(n)
                    && cdt.aux[n as usize].reg == NO_REGION
                {
                    pick = Some(n);
                }
            }
            if let Some(t) = pick {
                cdt.aux[t as usize].reg = HOLE;
                stack.push(t);
                cdt.flood(&mut stack, HOLE);
            }
        }
    }

    /// Whether slot `t` is a triangle of the region (after [`FacetTriangulation::classify`]).
    fn in_region(cdt: &Cdt, t: u32) -> bool {
        cdt.alive(t) && !cdt.is_ghost(t) && cdt.aux[t as usize].reg == NO_REGION
    }

    /// The triangles of the region (after [`FacetTriangulation::classify`]).
    pub fn region(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.cdt.iter().flat_map(|cdt| {
            (0..cdt.num_slots() as u32)
                .filter(|&t| Self::in_region(cdt, t))
                .map(|t| cdt.tv[t as usize])
        })
    }

    /// The edges inside the region that are no constraint (each once).
    pub fn diagonals(&self) -> impl Iterator<Item = [u32; 2]> + '_ {
        self.cdt.iter().flat_map(|cdt| {
            (0..3 * cdt.num_slots() as u32).filter_map(move |h| {
                let n = cdt.twin(h) / 3;
                let inner = Self::in_region(cdt, h / 3)
                    && h / 3 < n
                    && Self::in_region(cdt, n)
                    && cdt.seg_at(h) == NONE;
                inner.then(|| {
                    let (a, b) = cdt.edge_ends(h);
                    [a, b]
                })
            })
        })
    }

    /// Number of finite triangles (all labels).
    #[cfg(test)]
    pub fn num_triangles(&self) -> usize {
        self.cdt.as_ref().map_or(0, |cdt| {
            (0..cdt.num_slots() as u32)
                .filter(|&t| cdt.alive(t) && !cdt.is_ghost(t))
                .count()
        })
    }

    /// The coordinates of vertex `v` (tests only).
    #[cfg(test)]
    fn point(&self, v: u32) -> [f64; 2] {
        self.cdt
            .as_ref()
            .map_or([0.0; 2], |cdt| cdt.pts[v as usize])
    }

    /// Checks adjacency and orientation (tests only).
    #[cfg(test)]
    pub fn check(&self) -> Result<(), String> {
        let Some(cdt) = self.cdt.as_ref() else {
            return Ok(());
        };
        for t in 0..cdt.num_slots() as u32 {
            if !cdt.alive(t) {
                continue;
            }
            let tv = cdt.tv[t as usize];
            if !cdt.is_ghost(t) && cdt.orient_ids(tv[0], tv[1], tv[2]) <= 0.0 {
                return Err(format!("triangle {t} {tv:?} is not counter-clockwise"));
            }
            for i in 0..3 {
                let h = 3 * t + i;
                let tw = cdt.twin(h);
                if tw == NONE || cdt.twin(tw) != h {
                    return Err(format!("half-edge {h} is not linked both ways"));
                }
                let (x, y) = cdt.edge_ends(h);
                if cdt.edge_ends(tw) != (y, x) {
                    return Err(format!("half-edges {h} and {tw} join different vertices"));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::predicates::{incircle, orient2d};

    fn area(cdt: &FacetTriangulation) -> f64 {
        cdt.region()
            .map(|t| {
                let [a, b, c] = t.map(|v| cdt.point(v));
                0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
            })
            .sum()
    }

    fn run(
        pts: &[[f64; 2]],
        loops: &[&[u32]],
        seeds: &[[f64; 2]],
    ) -> Result<FacetTriangulation, CdtError> {
        let mut cdt = FacetTriangulation::default();
        cdt.triangulate(pts)?;
        cdt.check().unwrap();
        for (tag, l) in loops.iter().enumerate() {
            let k = l.len();
            let edges = if k == 2 { 1 } else { k };
            for i in 0..edges {
                cdt.constrain(l[i], l[(i + 1) % k], tag as u32)?;
            }
        }
        cdt.check().unwrap();
        cdt.classify(seeds);
        Ok(cdt)
    }

    #[test]
    fn collinear_prefix_and_grid_points() {
        // Many points on the first vertical line, then a grid: exercises the fan start and
        // cocircular flips.
        let mut pts = Vec::new();
        for i in 0..6 {
            for j in 0..6 {
                pts.push([i as f64, j as f64]);
            }
        }
        let mut cdt = FacetTriangulation::default();
        cdt.triangulate(&pts).unwrap();
        cdt.check().unwrap();
        assert_eq!(
            cdt.num_triangles(),
            50,
            "2n - 2 - hull vertices = 72 - 2 - 20"
        );
        // All collinear: nothing, and no failure.
        cdt.triangulate(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
            .unwrap();
        assert_eq!(cdt.num_triangles(), 0);
    }

    #[test]
    fn square_with_square_hole() {
        let pts = [
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [0.0, 4.0],
            [1.0, 1.0],
            [3.0, 1.0],
            [3.0, 3.0],
            [1.0, 3.0],
        ];
        let outer: &[u32] = &[0, 1, 2, 3];
        let inner: &[u32] = &[4, 5, 6, 7];
        let c = run(&pts, &[outer, inner], &[[2.0, 2.0]]).unwrap();
        assert_eq!(area(&c), 12.0);
        // Without the seed the inner square belongs to the facet too.
        let c = run(&pts, &[outer, inner], &[]).unwrap();
        assert_eq!(area(&c), 16.0);
        // Only the inner loop: the outer ring is outside.
        let c = run(&pts, &[inner], &[]).unwrap();
        assert_eq!(area(&c), 4.0);
    }

    #[test]
    fn nonconvex_loop_recovers_every_edge() {
        // A comb: teeth force constraints across the convex hull triangulation.
        let mut pts = vec![[0.0, 0.0], [10.0, 0.0]];
        for i in (0..10).rev() {
            let x = i as f64;
            pts.push([x + 1.0, 5.0]);
            pts.push([x + 0.5, 0.5]);
        }
        let n = pts.len() as u32;
        let lp: Vec<u32> = (0..n).collect();
        let c = run(&pts, &[&lp], &[]).unwrap();
        for i in 0..n {
            assert!(c.is_constrained(i, (i + 1) % n));
        }
        // Shoelace area of the polygon equals the region's area.
        let mut shoelace = 0.0;
        for i in 0..pts.len() {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            shoelace += a[0] * b[1] - a[1] * b[0];
        }
        assert!((area(&c) - shoelace / 2.0).abs() < 1e-12, "{}", area(&c));
    }

    #[test]
    fn random_star_polygons_with_holes_and_free_points_keep_their_area() {
        let mut state: u64 = 0x853C_49E6_748F_EA9B;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let shoelace = |p: &[[f64; 2]]| {
            (0..p.len())
                .map(|i| {
                    let (a, b) = (p[i], p[(i + 1) % p.len()]);
                    a[0] * b[1] - a[1] * b[0]
                })
                .sum::<f64>()
                / 2.0
        };
        for round in 0..20 {
            let n = 8 + round * 13;
            // A star-shaped outer loop (radii in [2, 4]) around the origin, a star-shaped
            // hole (radii in [0.5, 1]) with its seed at the origin, and free points between.
            let star = |k: usize, lo: f64, hi: f64, rnd: &mut dyn FnMut() -> f64| {
                (0..k)
                    .map(|i| {
                        let t = (i as f64 + 0.5 * rnd()) / k as f64 * std::f64::consts::TAU;
                        let r = lo + (hi - lo) * rnd();
                        [r * t.cos(), r * t.sin()]
                    })
                    .collect::<Vec<_>>()
            };
            let outer = star(n, 2.0, 4.0, &mut rnd);
            let hole = star(n / 2 + 3, 0.5, 1.0, &mut rnd);
            let mut pts = outer.clone();
            pts.extend_from_slice(&hole);
            for i in 0..n {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                pts.push([1.5 * t.cos(), 1.5 * t.sin()]);
            }
            let lo: Vec<u32> = (0..outer.len() as u32).collect();
            let hi: Vec<u32> = (outer.len() as u32..(outer.len() + hole.len()) as u32).collect();
            let c = run(&pts, &[&lo, &hi], &[[0.0, 0.0]]).unwrap();
            let want = shoelace(&outer) - shoelace(&hole);
            assert!((area(&c) - want).abs() < 1e-9 * want, "round {round}");
            for l in [&lo, &hi] {
                for i in 0..l.len() {
                    assert!(c.is_constrained(l[i], l[(i + 1) % l.len()]));
                }
            }
        }
    }

    #[test]
    fn crossing_loops_and_self_crossing_are_reported() {
        let pts = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        // The bow tie 0-2-1-3 crosses itself.
        let e = run(&pts, &[&[0, 2, 1, 3]], &[]).err().unwrap();
        assert_eq!(e, CdtError::Crossing(0, 0));
        // Two segments crossing, from two polygons.
        let e = run(&pts, &[&[0, 2], &[1, 3]], &[]).err().unwrap();
        assert_eq!(e, CdtError::Crossing(1, 0));
    }

    #[test]
    fn vertices_on_a_constraint_split_it() {
        let pts = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 1.0], [1.0, -1.0]];
        let c = run(&pts, &[&[0, 2]], &[]).unwrap();
        assert!(c.is_constrained(0, 1) && c.is_constrained(1, 2));
        assert!(!c.is_constrained(0, 2));
        // A loop with an unlisted vertex inside one of its edges, and one in its interior.
        let c = run(&pts, &[&[0, 2, 3]], &[]).unwrap();
        assert_eq!(area(&c), 1.0);
        assert_eq!(
            c.diagonals().count(),
            1,
            "the edge from vertex 1 to the apex"
        );
        let c = run(&pts, &[&[0, 4, 2, 3]], &[]).unwrap();
        assert_eq!(area(&c), 2.0);
        assert_eq!(c.diagonals().count(), 4, "the four spokes to vertex 1");
    }

    /// `FacetTriangulation::polygon` of `pts` in order, ids shifted by 10 (the ring's ids are
    /// not its positions).
    fn polygon(pts: &[[f64; 2]]) -> Option<Vec<[u32; 3]>> {
        let ring: Vec<u32> = (10..10 + pts.len() as u32).collect();
        let mut out = vec![[0; 3]];
        let got = FacetTriangulation::polygon(&ring, &|v| pts[v as usize - 10], &mut out);
        assert_eq!(out[0], [0; 3], "what `out` held is kept");
        if got.is_none() {
            assert_eq!(out.len(), 1, "nothing appended on failure");
            return None;
        }
        Some(out[1..].to_vec())
    }

    #[test]
    fn polygon_triangulates_a_non_convex_polygon() {
        // An L shape with a collinear run along its bottom.
        let pts = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ];
        let tris = polygon(&pts).unwrap();
        assert_eq!(tris.len(), pts.len() - 2);
        let mut area = 0.0;
        for t in &tris {
            let [a, b, c] = t.map(|v| pts[v as usize - 10]);
            assert!(
                orient2d(a, b, c) > 0.0,
                "triangle {t:?} is not counter-clockwise"
            );
            area += crate::geometry::area2(a, b, c) / 2.0;
        }
        assert!((area - 3.0).abs() < 1e-12, "area {area}");
    }

    #[test]
    fn polygon_is_constrained_delaunay() {
        // A long thin convex hexagon: ear clipping from any corner may leave a fan, the
        // constrained Delaunay triangulation has every inner edge locally Delaunay.
        let pts = [
            [0.0, 0.0],
            [3.0, -0.4],
            [7.0, -0.5],
            [10.0, 0.0],
            [6.0, 0.6],
            [2.0, 0.5],
        ];
        let tris = polygon(&pts).unwrap();
        assert_eq!(tris.len(), 4);
        let at = |v: u32| pts[v as usize - 10];
        for t in &tris {
            for u in &tris {
                for v in *u {
                    if !t.contains(&v) {
                        let [a, b, c] = t.map(at);
                        assert!(
                            incircle(a, b, c, at(v)) <= 0.0,
                            "corner {v} lies inside the circumcircle of {t:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn polygon_refuses_what_is_not_a_counter_clockwise_simple_polygon() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(polygon(&square).is_some());
        let mut clockwise = square;
        clockwise.reverse();
        assert!(polygon(&clockwise).is_none(), "clockwise");
        let bowtie = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
        assert!(polygon(&bowtie).is_none(), "crossing edges");
        // The last edge runs back through corner 1.
        let through = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 0.0]];
        assert!(polygon(&through).is_none(), "repeated point");
        let touching = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 0.0], [0.0, 2.0]];
        assert!(polygon(&touching).is_none(), "a corner inside an edge");
        assert!(
            polygon(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]).is_none(),
            "collinear"
        );
        assert!(polygon(&square[..2]).is_none(), "two corners");
    }
}
