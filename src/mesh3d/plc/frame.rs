//! Meshing in a local frame: a PLC far from the origin (relative to its own size) is moved
//! next to the origin by an exact translation before meshing, and the mesh is moved back.
//!
//! Why: a Steiner point is a floating-point construction (a midpoint, a circumcentre), rounded
//! to the grid of representable numbers at the coordinates' magnitude. For a part 1 across translated
//! by 1e6 that grid is 1.2e-10 while the features are 1e-2: every split point of a wall's
//! edge lands off its line and off the facet's plane, the rectangles of the walls stop being
//! exactly cocircular, the facet meshes and the 3D mesh break those near-ties differently,
//! and recovering the facets never ends (issue 14). Meshed next to the origin, the same points
//! (exactly the same geometry) give the original's mesh in 0.03 s: constructions are then as
//! precise, relative to the input's size, as for the untranslated input (translation
//! invariance, issue 14 item 1).
//!
//! The translation is exact: per axis the shift is an input coordinate `s` chosen so that
//! every input coordinate `x` on that axis has the same sign and lies within a factor of two
//! of it, so `x - s` is exact (Sterbenz's lemma), and so is `(x - s) + s`. An axis whose
//! points do not lie within a factor of two of one another is not shifted (the input is
//! then not far from the origin relative to its size on that axis). Only Steiner points are
//! rounded when moved back, to the nearest representable point, as they would be anyway.

use crate::input3d::Plc;
use crate::mesh3d::{Options3, TetMesh};

/// The exact shift of `plc` (per axis; zero where none applies), or `None` when no axis is
/// shifted.
pub(super) fn shift_of(plc: &Plc) -> Option<[f64; 3]> {
    let mut s = [0.0; 3];
    for (k, sk) in s.iter_mut().enumerate() {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in &plc.points {
            lo = lo.min(p[k]);
            hi = hi.max(p[k]);
        }
        // Sterbenz: y/2 <= x <= 2y gives x - y exact. With the shift at the middle of the
        // span's magnitude, every coordinate of the axis must be within a factor of two of it.
        *sk = if lo > 0.0 && hi <= 2.0 * lo {
            lo
        } else if hi < 0.0 && lo >= 2.0 * hi {
            hi
        } else {
            0.0
        };
    }
    // Not worth it when the input is already near the origin relative to its size: the
    // shift gains fewer than 8 bits of precision for constructions.
    let far = (0..3).any(|k| {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in &plc.points {
            lo = lo.min(p[k]);
            hi = hi.max(p[k]);
        }
        s[k] != 0.0 && (hi - lo) * 256.0 < s[k].abs()
    });
    far.then_some(s)
}

/// `plc` translated by `-s` (input points exactly; seeds rounded, as the seeds only say on
/// which side of the facets they are).
pub(super) fn shifted(plc: &Plc, s: [f64; 3]) -> Plc {
    let mv = |p: [f64; 3]| [p[0] - s[0], p[1] - s[1], p[2] - s[2]];
    let mut out = plc.clone();
    for p in &mut out.points {
        *p = mv(*p);
    }
    for h in &mut out.holes {
        *h = mv(*h);
    }
    for r in &mut out.regions {
        r.point = mv(r.point);
    }
    for f in &mut out.facets {
        for h in &mut f.holes {
            *h = mv(*h);
        }
    }
    out
}

/// The options for meshing in the frame shifted by `-s`: a user sizing test still sees the
/// caller's coordinates.
pub(super) fn shifted_options(opts: &Options3, s: [f64; 3]) -> Options3 {
    let mut o = opts.clone();
    if let Some(f) = opts.sizing.clone() {
        let back = move |p: [f64; 3]| [p[0] + s[0], p[1] + s[1], p[2] + s[2]];
        o.sizing = Some(std::sync::Arc::new(move |a, b, c, d, v| {
            f(back(a), back(b), back(c), back(d), v)
        }));
    }
    o
}

/// Moves a mesh made in the shifted frame back by `+s`; input vertices come back exactly.
pub(super) fn unshift(mesh: &mut TetMesh, s: [f64; 3]) {
    for p in &mut mesh.vertices {
        for k in 0..3 {
            p[k] += s[k];
        }
    }
}

impl super::Mesher<'_> {
    /// Moves every Steiner point onto the grid of the caller's frame (shifted by `s`): the
    /// point `(p + s) - s`, the second step exact. The mesh made in the shifted frame is then
    /// exactly the mesh the caller gets back. The moves are a rounding at the coordinates'
    /// magnitude (1e-10 at 1e6), far below the mesh's sizes; the faces they leave not locally
    /// Delaunay (near ties, as four nearly cocircular points) are flipped. `false` when a tet
    /// that is output turned over; the caller checks the rest on the output
    /// ([`crate::mesh3d::validate::validate_mesh`]).
    pub(super) fn snap_to_frame(&mut self, s: [f64; 3]) -> bool {
        use crate::predicates::orient3d;
        for v in self.num_input..self.pts.len() {
            let p = self.pts[v];
            let q = [0, 1, 2].map(|k| (p[k] + s[k]) - s[k]);
            if q != p {
                self.pts[v] = q;
                if v < self.tets.num_vertices() {
                    self.tets.set_point(v as u32, q);
                }
            }
        }
        let dropped = self.rounding_slivers_on_boundary();
        for t in 0..self.tets.num_slots() as u32 {
            if self.tets.alive(t)
                && !self.tets.is_ghost(t)
                && self.region_of(t) != super::OUTSIDE
                && !dropped.contains(&t)
            {
                let c = self.tets.verts(t).map(|x| self.pts[x as usize]);
                if orient3d(c[0], c[1], c[2], c[3]) >= 0.0 {
                    return false;
                }
            }
        }
        if !self.walled {
            self.flips(false);
        }
        true
    }
}
