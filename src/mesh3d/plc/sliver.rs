//! Sliver removal that keeps the mesh Delaunay: after radius-edge refinement (paper §4, Fig. 9),
//! tetrahedra inside the domain whose smallest dihedral angle is below a target (or whose
//! largest is above 180° minus it) are removed by Delaunay refinement with a chosen point, as
//! in Chew's and Li and Teng's sliver removal.
//!
//! A sliver can have a good radius-edge ratio (four nearly cocircular vertices on a great
//! circle of its circumsphere), so the radius-edge refinement of `plc.rs` leaves it alone.
//! Here each sliver `t` with circumcentre `o` and circumradius `R` is destroyed by inserting a
//! point `p` of the *picking region*, the ball of radius [`PICK_FRACTION`]` R` around `o`:
//! * candidates are `o` first, then up to [`CANDIDATES`] points of the picking region
//!   (pseudo-random, seeded by the sliver's vertices, so runs are reproducible), up to
//!   [`CANDIDATES_HARD`] while some go in but none meets the target. Each must be inside `t`'s
//!   circumsphere (exact `insphere`), so that its cavity contains `t`;
//! * for each, the would-be Bowyer–Watson cavity is found (exact `insphere`, nothing changes)
//!   and the new tetrahedra inside the domain it would make are measured; a candidate whose
//!   cavity would cross or whose point would encroach a subface or subsegment is skipped;
//! * the first candidate that makes no new tetrahedron below the target and none above the
//!   radius-edge bound (which would be refined in turn, making more points) is taken, else the
//!   best one by those two criteria. When every candidate encroaches, the one demanding the
//!   least splitting goes the way of a bad tetrahedron's circumcentre (`Mesher::take_tet`):
//!   inserted provisionally, refused, and the encroached subsegments and subfaces are split
//!   instead under the lazy rules that protect the features (queued `ForTet`, dropped once the
//!   sliver is gone; the sliver is queued again and, if it survives, its circumcentre is
//!   tried). So slivers at the boundary are removed by refining the boundary, as bad
//!   tetrahedra are, and a point outside the domain is never inserted.
//!
//! Every point goes in through `insert3d`, a Bowyer–Watson insertion with exact predicates:
//! the mesh stays the Delaunay tetrahedralization of its vertices and the features stay
//! conforming, whatever the floating-point constructions of the candidates were. Tetrahedra
//! next to a small input angle (`Sharp::exempts_sliver`: a sharp edge between facets, a thin
//! wedge, a vertex where two input edges meet below the target, or a tet deep inside a sharp
//! vertex's protection ball, where removal would run towards the apex), rounding slivers lying in
//! one facet (the output drops or splits those), and tetrahedra below the size floor are not
//! treated; the exempt ones are counted separately in the `-V` progress lines. The exemption
//! is narrower than the radius-edge bound's (`Sharp::exempts`): two input edges meeting
//! between the target and 60° (at nearly every vertex of a triangulated surface, as fan
//! angles) excuse no sliver; a fan-disk model at `-pq1.414` kept 44 slivers down to 0.05°
//! that way, and has none below 15° without it.
//!
//! What is guaranteed: validity, the Delaunay property, conformity, and termination (the pass
//! stops after [`BUDGET_FACTOR`] attempts per vertex present when it starts, and then marks the
//! result incomplete). What is only empirical: that the target is reached. Each inserted point
//! is at least `(1 − PICK_FRACTION) R` from every vertex (the circumsphere is empty), which
//! keeps new edges long, but Li and Teng's proof that a good point exists in the picking region
//! holds for a tiny angle, not for 15°; on the project's inputs the default target is met
//! everywhere except next to small input angles (see the measurements in the branch report and
//! the property tests in `tests/sliver3d.rs`).

use super::{encroached_in, face_of, Enc, Mesher, UNKNOWN};
use crate::error::Error;
use crate::geometry::{
    dist2_3, tet_circumcenter, tet_dihedral_outside, tet_dihedral_range, tet_radius_edge,
};
use crate::mesh3d::store::{Located, GHOST};
use crate::predicates::{insphere, orient3d};
use crate::progress::tick;
use crate::NONE;

/// The minimum dihedral angle target used with a radius-edge bound when none is given
/// (degrees): TetGen's `-q` leaves it at 0 (no target); idmesh removes tetrahedra below 15°
/// (and above 165°), which its Delaunay sliver removal reaches on the usual inputs.
pub const DEFAULT_MIN_DIHEDRAL: f64 = 15.0;

/// The largest minimum dihedral angle target accepted (degrees). The regular tetrahedron's
/// dihedral angle is 70.5°; a target near it cannot be met and only spends the budget.
pub(crate) const MAX_MIN_DIHEDRAL: f64 = 70.0;

/// Radius of the picking region around a sliver's circumcentre, relative to its circumradius.
const PICK_FRACTION: f64 = 0.3;

/// Points tried in the picking region besides the circumcentre.
const CANDIDATES: u32 = 12;

/// Points tried in all when some of the first [`CANDIDATES`] go in but none meets the target.
/// Taking the best of too few makes a new sliver, which the next round treats in turn: a domed
/// 21-gon prism at -pq1.414a0.0013 ran out of rounds that way (9,109 tets, one sliver of 5.9°
/// left); with 48 it is done in 3 rounds with 6,585 tets, and fewer points overall on the
/// benchmark inputs (`bench/quality3d.py`). When none of the first goes in, the boundary is
/// split without trying more: more only lowered the demand a little, at 36 more probes for
/// each such sliver (1,847 of the 4,771 slivers of a scanned animal model at `-pq`).
const CANDIDATES_HARD: u32 = 48;

/// Largest cavity a candidate may have (tets). A sliver's picking region can reach into the
/// big flat tets outside the domain (across a through-hole next to a thin wall, say), where a
/// candidate's cavity runs to tens of thousands of tets; such a candidate destroys far more
/// than the sliver, and probing it cost 93% of a plate's meshing time (17 of 18 s). It counts
/// as unusable; when every candidate is, the sliver goes the way of a bad tet.
const PROBE_CAP: usize = 2048;

/// Sliver removal attempts allowed per vertex present when the pass starts.
const BUDGET_FACTOR: u64 = 2;

/// Rounds of sliver collection (each round treats every sliver found at its start).
const MAX_ROUNDS: u32 = 64;

/// Tetrahedra to treat, with their vertices when found (a tet changed since is skipped).
type Slivers = Vec<(u32, [u32; 4])>;

/// Why a tet is not treated, once judged (see [`Mesher::collect_slivers`]).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Verdict {
    /// It meets the target, or is below the size floor.
    Fine,
    /// A rounding sliver lying in one facet: the output drops or splits it.
    OneFacet,
    /// Next to a small input angle.
    Exempt,
}

/// What the sliver removal pass did, for the `-V` progress lines.
#[derive(Default, Debug)]
struct SliverCounts {
    /// Slivers treated (each by one point, or by the splits its point demanded).
    treated: u64,
    /// Slivers left (non-exempt, below the target) when the pass ended.
    left: u64,
    /// Tetrahedra below the target exempted for a small input angle at the end.
    exempt: u64,
    /// Rounds run.
    rounds: u32,
}

impl Mesher<'_> {
    /// The minimum dihedral angle target in force, if any (degrees): with a radius-edge
    /// bound, `-q`'s (`/angle`, else the default); without one, under TetGen's `-O` with scheme
    /// bit 4 (TetGen splits slivers by new points there), the optimisation's target `o/`
    /// turned into a minimum angle (165 gives 15). The mesh stays Delaunay either way.
    pub(super) fn sliver_target(&self) -> Option<f64> {
        if self.walled {
            return None;
        }
        let o = self.opts;
        let a = if o.radius_edge.is_some() {
            o.min_dihedral.unwrap_or(DEFAULT_MIN_DIHEDRAL)
        } else if o.optimize_level > 0
            && o.optimize_scheme.unwrap_or(crate::mesh3d::DEFAULT_SCHEME) & 4 != 0
        {
            let max = o
                .optimize_max_dihedral
                .unwrap_or(crate::mesh3d::DEFAULT_MAX_DIHEDRAL);
            (180.0 - max).min(MAX_MIN_DIHEDRAL)
        } else {
            return None;
        };
        (a > 0.0).then_some(a)
    }

    /// Whether tet `t` (corners `c`) misses the dihedral target: an angle below `target` or
    /// above `180 − target`.
    fn is_sliver(c: [[f64; 3]; 4], target: f64) -> bool {
        tet_dihedral_outside(c, target)
    }

    /// The tets inside the domain missing the target that the pass treats, and how many others
    /// miss it but are exempt (next to a small input angle). `seen` holds, per tet slot, the
    /// vertices of the tet last judged there with a verdict that cannot change while the tet
    /// lives: it meets the target (or is below the size floor), it is a rounding sliver in one
    /// facet, or it is exempt. Each of those depends on the four vertices alone (their
    /// positions, the features they lie on and the small-angle protection, all fixed once a
    /// vertex is in), so a slot holding the same vertices is not judged again: the pass runs
    /// this every round, and most tets, and on scanned models thousands of exempt ones, would
    /// be measured and tested against the protection zones each time.
    fn collect_slivers(
        &self,
        target: f64,
        seen: &mut Vec<([u32; 4], Verdict)>,
    ) -> Result<(Slivers, u64), Error> {
        let mut out = Vec::new();
        let mut exempt = 0;
        seen.resize(self.tets.num_slots(), ([NONE; 4], Verdict::Fine));
        for t in 0..self.tets.num_slots() as u32 {
            tick(|| (self.steiner, self.steiner))?;
            if !self.tets.alive(t) || self.tets.is_ghost(t) || self.region_of(t) >= UNKNOWN {
                continue;
            }
            let vs = self.tets.verts(t);
            let verdict = match seen[t as usize] {
                (w, verdict) if w == vs => verdict,
                _ => {
                    let c = vs.map(|x| self.pts[x as usize]);
                    let verdict = if !Self::is_sliver(c, target) || self.below_floor(&c) {
                        Verdict::Fine
                    } else if self.feat.in_one_facet(vs) {
                        Verdict::OneFacet
                    } else if self.sharp.exempts_sliver(vs, &self.feat, &self.pts, target) {
                        Verdict::Exempt
                    } else {
                        out.push((t, vs));
                        continue;
                    };
                    seen[t as usize] = (vs, verdict);
                    verdict
                }
            };
            if verdict == Verdict::Exempt {
                exempt += 1;
            }
        }
        Ok((out, exempt))
    }

    /// Removes the slivers (see the module docs); a no-op without a target.
    pub(super) fn remove_slivers(&mut self) -> Result<(), Error> {
        let Some(target) = self.sliver_target() else {
            return Ok(());
        };
        let budget = BUDGET_FACTOR * self.tets.num_vertices() as u64 + 1024;
        let mut counts = SliverCounts::default();

        let mut exhausted = false;
        let mut seen = Vec::new();
        'rounds: for round in 0..MAX_ROUNDS {
            let (list, _) = self.collect_slivers(target, &mut seen)?;
            if list.is_empty() {
                break;
            }
            counts.rounds = round + 1;
            let before = self.steiner;
            for (t, vs) in list {
                if self.cap_reached() {
                    self.complete = false;
                }
                if !self.complete {
                    break 'rounds; // the Steiner cap was reached
                }
                if !self.tets.alive(t) || self.tets.verts(t) != vs {
                    continue;
                }
                if counts.treated >= budget {
                    exhausted = true;
                    break 'rounds;
                }
                counts.treated += 1;
                self.take_sliver(t, vs, target)?;
                // The point's new tets may be bad (radius-edge, volume) and its demands may
                // be queued: the work loop settles them before the next sliver.
                self.run()?;
            }
            if self.steiner == before {
                break; // every demand was dropped (size floor): nothing more to gain
            }
        }
        let (left, exempt) = self.collect_slivers(target, &mut seen)?;
        counts.left = left.len() as u64;
        counts.exempt = exempt;
        if exhausted {
            self.complete = false;
        }
        if self.opts.verbose {
            eprintln!(
                "idmesh: sliver removal (dihedral angles {target}..{}): {} slivers treated in {} \
                 rounds{}; {} left, {} exempt next to small input angles",
                180.0 - target,
                counts.treated,
                counts.rounds,
                if exhausted { " (budget exhausted)" } else { "" },
                counts.left,
                counts.exempt
            );
        }
        Ok(())
    }

    /// Removes sliver `t` (vertices `vs`) by a point of its picking region, or by its
    /// circumcentre and the splits that demands.
    fn take_sliver(&mut self, t: u32, vs: [u32; 4], target: f64) -> Result<(), Error> {
        if self.region_of(t) >= UNKNOWN {
            return Ok(());
        }
        let c = vs.map(|x| self.pts[x as usize]);
        let Some(cc) = tet_circumcenter(c) else {
            return self.take_tet(t, vs);
        };
        let r = dist2_3(cc, c[0]).sqrt();
        let o = orient3d(c[0], c[1], c[2], c[3]);
        let mut rng = Rng::new(vs);
        let mut best: Option<(Rank, [f64; 3])> = None;
        // When every candidate encroaches: the one demanding the least splitting.
        let mut least: Option<(u32, [f64; 3])> = None;
        for k in 0..=CANDIDATES_HARD {
            if k > CANDIDATES && best.map_or(true, |b| b.0 .0) {
                // A candidate meeting the target, with more bad tets than hoped; or none
                // that goes in, and the boundary is split instead (more candidates would
                // only lower the demand a little).
                break;
            }
            let p = if k == 0 {
                cc
            } else {
                let u = rng.in_unit_ball();
                [0, 1, 2].map(|i| cc[i] + PICK_FRACTION * r * u[i])
            };
            if !p.iter().all(|x| x.is_finite())
                || insphere(c[0], c[1], c[2], c[3], p) * o <= 0.0
                || !self.in_box(p)
            {
                continue;
            }
            // Once a candidate goes in, no encroaching one is chosen; before, only one
            // demanding less than the least so far.
            let bound = match (best, least) {
                (Some(_), _) => 1,
                (None, Some((d, _))) => d,
                (None, None) => u32::MAX,
            };
            match self.probe(t, p, bound) {
                Probe::Fits(worst, bad) => {
                    // Rank: meets the target, then fewest new tets above the radius-edge
                    // bound (each would be refined in turn), then the best angle.
                    let key = (worst >= target, std::cmp::Reverse(bad), worst);
                    if best.map_or(true, |b| key > b.0) {
                        best = Some((key, p));
                    }
                    if worst >= target && bad == 0 {
                        break;
                    }
                }
                Probe::Encroaches(d) => {
                    if least.map_or(true, |l| d < l.0) {
                        least = Some((d, p));
                    }
                }
                Probe::Unusable => {}
            }
        }
        match (best, least) {
            (Some((_, p)), _) => self.place_for_tet(t, vs, c, p),
            (None, Some((_, p))) => self.place_for_tet(t, vs, c, p),
            (None, None) => self.take_tet(t, vs),
        }
    }

    /// What inserting `p` (in conflict with tet `t`) would do, found on the would-be cavity
    /// without changing the mesh: refused for encroaching (a subsegment or subface holds `p`
    /// in its diametral ball, or the cavity crosses a subface), unusable (on a vertex, or
    /// outside the hull), or accepted with the worst angle of its new tets inside the domain
    /// (the smallest of each one's smallest dihedral and 180° minus its largest).
    ///
    /// A candidate demanding `bound` or more splitting cannot be chosen (one that goes in, or
    /// one demanding less, was found before it): its search stops there, as unusable. Most
    /// candidates next to the boundary encroach, and their cavities are big (a sliver's
    /// circumsphere is), so this saves most of the probing on surface-heavy models.
    fn probe(&mut self, t: u32, p: [f64; 3], bound: u32) -> Probe {
        let start = match self.tets.locate(p, t) {
            Located::InTet(s) => s,
            Located::Vertex(_) => return Probe::Unusable,
        };
        // How much splitting the point would demand: subfaces it encroaches or whose cavity
        // crosses them count 1, subsegments 3 (a split there changes every facet through
        // the edge). Each is counted once per cavity tet holding it: a rough measure only
        // used to rank candidates. A tet joining the cavity counts its subfaces that `p`
        // encroaches; one whose neighbour across it joined before counts for both sides (the
        // neighbour counted it then only if encroached).
        let mut demand = 0u32;
        let mut outside = false;
        let (feat, pts) = (&self.feat, &self.pts);
        let found = self
            .tets
            .find_cavity_visit(p, start, PROBE_CAP, |vs, joined| {
                if vs.contains(&GHOST) {
                    // Outside the hull, hence outside the domain.
                    outside = true;
                    return false;
                }
                encroached_in(feat, pts, p, vs, joined, |e, crossed, ball| {
                    demand += match e {
                        Enc::Face(..) if crossed => 2 - u32::from(ball),
                        Enc::Face(..) => 1,
                        Enc::Seg(_) => 3,
                    };
                });
                demand < bound
            });
        if found != Some(true) || outside || !self.tets.in_cavity(t) {
            self.tets.cancel_cavity();
            return Probe::Unusable;
        }
        if demand > 0 {
            self.tets.cancel_cavity();
            return Probe::Encroaches(demand);
        }
        let mut worst = 180.0f64;
        let mut bad = 0u32;

        for &h in self.tets.cavity_boundary() {
            let (u, f) = (h / 4, (h % 4) as usize);
            let fv = face_of(self.tets.verts(u), f);
            if fv.contains(&GHOST) || self.region_of(u) >= UNKNOWN {
                continue;
            }
            let [a, b, c] = fv.map(|x| self.pts[x as usize]);
            let (lo, hi) = tet_dihedral_range([a, b, c, p]);
            worst = worst.min(lo).min(180.0 - hi);
            if self
                .opts
                .radius_edge
                .is_some_and(|rho| tet_radius_edge([a, b, c, p]) > rho)
            {
                bad += 1;
            }
        }
        self.tets.cancel_cavity();
        Probe::Fits(worst, bad)
    }
}

/// How a candidate that goes in ranks: meets the target, fewest new tets above the radius-edge
/// bound, best worst angle (greater is better).
type Rank = (bool, std::cmp::Reverse<u32>, f64);

/// What inserting a candidate point would do (see [`Mesher::probe`]).
enum Probe {
    /// It goes in; the worst angle of the new tets inside the domain, and how many of them
    /// exceed the radius-edge bound (each would be refined in turn).
    Fits(f64, u32),
    /// It would be refused for encroaching, demanding about this much splitting.
    Encroaches(u32),
    /// It lies on a vertex or outside the hull.
    Unusable,
}

/// A small deterministic generator (xorshift64*) for the candidate points.
struct Rng(u64);

impl Rng {
    fn new(vs: [u32; 4]) -> Rng {
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        for v in vs {
            s = (s ^ u64::from(v)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        }
        Rng(s | 1)
    }

    fn next_unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// A point of the unit ball (rejection sampling, at most 16 draws; the last is scaled in).
    fn in_unit_ball(&mut self) -> [f64; 3] {
        let mut u = [0.0; 3];
        for _ in 0..16 {
            u = [self.next_unit(), self.next_unit(), self.next_unit()];
            if u.iter().map(|x| x * x).sum::<f64>() <= 1.0 {
                return u;
            }
        }
        u.map(|x| x / 3f64.sqrt())
    }
}
