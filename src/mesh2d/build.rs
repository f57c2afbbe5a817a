//! The driver: input validation, insertion of the input points, segment recovery (the
//! conforming stage, paper Fig. 3 step 2), classification of exterior, holes and regions, then
//! refinement (step 3) and output.

use super::refine::{segment_marker, Piece, Refiner, SegmentSteiner};
use super::store::{Cdt, Inserted, Mode, Seg, Start, EXTERIOR, HOLE, NO_REGION};
use super::{Options, TriMesh, NONE};
use crate::error::{Error, InputError};
use crate::geometry::tiny_scale;
use crate::input2d::Pslg;
use crate::predicates::{orient2d, strictly_between};
use crate::progress::{stage, tick, Stage};

/// The largest accepted minimum-angle bound, in degrees.
pub const MAX_MIN_ANGLE: f64 = 34.0;

use crate::error::MAX_COORD;

pub(super) fn run(pslg: &Pslg, opts: &Options) -> Result<TriMesh, Error> {
    let n = pslg.points.len();
    stage(Stage::Reading, || (0, n as u64))?;
    check_options(opts)?;
    check_input(pslg)?;
    let seeds = pslg
        .holes
        .iter()
        .chain(pslg.regions.iter().map(|r| &r.point));
    match tiny_scale(pslg.points.iter().chain(seeds)) {
        Some(s) => run_scaled(pslg, opts, s),
        None => mesh(pslg, opts),
    }
}

/// Meshes an input whose coordinates are all below `2^-64` (see [`tiny_scale`]) scaled up
/// by the power of two `s`: every decision is then the one the exact predicates would make
/// without underflow (a scaling by a power of two changes no sign and no rounding of the
/// constructions), and the mesh is scaled back. Input points are given back as they were;
/// Steiner points are divided by `s`, exactly unless the quotient is subnormal, which is an
/// error rather than a mesh that rounding may have broken. Areas (global, regional, the
/// sizing test's) scale by `s²`.
fn run_scaled(pslg: &Pslg, opts: &Options, s: f64) -> Result<TriMesh, Error> {
    let up = |p: &mut [f64; 2]| *p = [p[0] * s, p[1] * s];
    let mut g = pslg.clone();
    g.points.iter_mut().for_each(up);
    g.holes.iter_mut().for_each(up);
    for r in &mut g.regions {
        up(&mut r.point);
        r.max_area = r.max_area.map(|a| a * s * s);
    }
    let mut o = opts.clone();
    o.max_area = opts.max_area.map(|a| a * s * s);
    if let Some(f) = opts.sizing.clone() {
        let down = move |p: [f64; 2]| [p[0] / s, p[1] / s];
        o.sizing = Some(std::sync::Arc::new(move |a, b, c, area| {
            f(down(a), down(b), down(c), area / s / s)
        }));
    }
    let mut m = mesh(&g, &o)?;
    crate::geometry::scale_back(&mut m.vertices, &pslg.points, s)?;
    Ok(m)
}

/// The mesher proper, on checked input.
///
/// Without segments, nothing names an input point by its index between the insertion and the
/// output, so the whole run, the end-of-run check included, works on the points renamed by
/// their rank in the insertion order ([`brio_order`]) and stored in that order; the names go
/// back on the checked mesh ([`unrank`], a renaming of vertices that changes no triangle, no
/// coordinate and no adjacency), and a fault the check finds is told in the input's names.
/// Neighbouring triangles then have neighbouring vertex names: the check reads the coordinates
/// nearly in memory order, where in input order (random, for scattered points) it missed the
/// cache at nearly every triangle (a third of a 1M-point run).
/// With segments, the points are renamed for the insertion only ([`insert_points`]).
fn mesh(pslg: &Pslg, opts: &Options) -> Result<TriMesh, Error> {
    if !pslg.segments.is_empty() {
        let (m, fixed) = mesh_in_order(pslg, opts, false)?;
        check_output(&m, fixed, opts)?;
        return Ok(m);
    }
    let order = brio_order(&pslg.points);
    let permute = |v: &[i32]| -> Vec<i32> {
        if v.is_empty() {
            Vec::new()
        } else {
            order.iter().map(|&i| v[i as usize]).collect()
        }
    };
    let ranked = Pslg {
        points: order.iter().map(|&i| pslg.points[i as usize]).collect(),
        point_markers: permute(&pslg.point_markers),
        segments: Vec::new(),
        segment_markers: Vec::new(),
        holes: pslg.holes.clone(),
        regions: pslg.regions.clone(),
    };
    let (mut m, fixed) = mesh_in_order(&ranked, opts, true).map_err(|e| match e {
        Error::Input(e) => Error::Input(match e.map_items(&|_, i| order[i] as usize) {
            InputError::DuplicatePoint { first, second } => InputError::DuplicatePoint {
                first: first.min(second),
                second: first.max(second),
            },
            e => e,
        }),
        e => e,
    })?;
    let checked = check_output(&m, fixed, opts);
    unrank(&mut m, &order, &pslg.points);
    match checked {
        Ok(()) => Ok(m),
        // Told in the input's names.
        Err(e) => Err(check_output(&m, fixed, opts).err().unwrap_or(e)),
    }
}

/// Gives the input points of `m`, meshed renamed by their rank in `order` (input point
/// `order[r]` as vertex `r`), their input names back; Steiner vertices keep theirs.
fn unrank(m: &mut TriMesh, order: &[u32], points: &[[f64; 2]]) {
    let n = points.len();
    let name = |v: u32| {
        if (v as usize) < n {
            order[v as usize]
        } else {
            v
        }
    };
    for t in &mut m.triangles {
        *t = t.map(name);
    }
    for s in &mut m.segments {
        *s = s.map(name);
    }
    m.vertices[..n].copy_from_slice(points);
    let ranked = m.vertex_markers[..n].to_vec();
    for (&i, mk) in order.iter().zip(ranked) {
        m.vertex_markers[i as usize] = mk;
    }
}

/// [`mesh`] without the output check, on `pslg`'s points in insertion order already
/// (`ranked`: point `k` is the `k`-th inserted) or in any order (they are ordered for the
/// insertion); also whether some segments were fixed (no Steiner points on them).
fn mesh_in_order(pslg: &Pslg, opts: &Options, ranked: bool) -> Result<(TriMesh, bool), Error> {
    // Which segments may be split (Triangle's -YY, -Y, neither); one policy serves all three.
    let policy = if opts.no_segment_steiner {
        SegmentSteiner::Nowhere
    } else if opts.no_boundary_steiner {
        SegmentSteiner::NotOnBoundary
    } else {
        SegmentSteiner::Anywhere
    };
    let n = pslg.points.len();
    stage(Stage::Delaunay, || (0, n as u64))?;
    let mut cdt = Cdt::new(&pslg.points);
    cdt.inseg_ends = pslg.segments.clone();
    insert_points(&mut cdt, &pslg.points, ranked)?;
    stage(Stage::Boundary, || (0, 0))?;
    let pieces = segment_pieces(pslg, &mut cdt, opts.split_crossings)?;
    let mut r = Refiner::new(cdt, pslg, opts);
    r.policy = policy;
    // Constrained Delaunay first: every segment becomes an edge without Steiner points (only a
    // segment that cannot be inserted that way is split now).
    r.register_segments(&pieces)?;
    r.drain_splits()?;
    classify(&mut r, pslg, opts)?;
    // Everything after works on the domain only (Triangle's carving): split points on slanted
    // segments can round outside, and the exterior never needs to see them.
    r.cdt.carve();
    r.fix_segments();
    // Conforming stage, then refinement. Cavities stop at segments, so a vertex can encroach a
    // segment across a wall or an exterior notch unseen: every subsegment is swept against
    // every vertex and split until none is encroached, which makes the constrained
    // triangulation truly Delaunay (except at fixed segments, under -Y).
    // Each pass only splits; a spent Steiner budget, or a sweep that keeps finding work (a
    // work budget: features so close that conformity needs more splits than the budget
    // allows), ends the stage with the mesh constrained Delaunay and reported incomplete.
    let mut passes = 0;
    loop {
        while r.sweep_encroached()? > 0 {
            passes += 1;
            if passes > 64 || r.budget_spent() {
                r.complete = false;
                break;
            }
            r.drain_splits()?;
        }
        if !r.refine()? {
            break;
        }
    }
    // A split point rounded beside its edge can leave an edge that is not locally Delaunay
    // (`Cdt::unsettled`): flip such edges now that no point is added any more (flipping at
    // once leaves chain slivers that later splits of the chain cannot be seeded from). The
    // mesh is then constrained Delaunay, and, with no subsegment encroached (the sweep
    // above), Delaunay.
    if r.cdt.unsettled {
        r.cdt.legalize_all();
    }
    stage(Stage::Output, || (0, 0))?;
    let mesh = output(&mut r, n, pslg, opts)?;
    Ok((mesh, r.policy != SegmentSteiner::Anywhere))
}

/// Never hand back a broken mesh as a success: the structure and the local empty-circle rule
/// (exact, linear) always; the global empty-circle search too in debug builds and in
/// `validate()`. With fixed segments (`fixed`), or conformity cut short by the budget, the
/// mesh is only constrained Delaunay, and segments are exempt from the local rule.
fn check_output(mesh: &TriMesh, fixed: bool, opts: &Options) -> Result<(), Error> {
    let threads = crate::threads::resolve(opts.threads)?;
    let check = if fixed || !mesh.complete {
        super::validate::validate_constrained(mesh, threads)
    } else if cfg!(debug_assertions) {
        mesh.validate()
    } else {
        super::validate::validate_final(mesh, threads)
    };
    check.map_err(|e| Error::Internal(format!("output check failed: {e}")))
}

fn check_options(o: &Options) -> Result<(), Error> {
    crate::threads::resolve(o.threads)?;
    if let Some(a) = o.min_angle {
        if !(a > 0.0 && a <= MAX_MIN_ANGLE) {
            return Err(Error::InvalidOption(format!(
                "minimum angle {a} must lie in (0, {MAX_MIN_ANGLE}] degrees (termination is proven \
                 up to 20.7 and observed up to 35; beyond, refinement can run away)"
            )));
        }
    }
    if let Some(a) = o.max_area {
        if !(a > 0.0 && a.is_finite()) {
            return Err(Error::InvalidOption(format!(
                "maximum area {a} must be positive and finite"
            )));
        }
    }
    Ok(())
}

fn check_input(p: &Pslg) -> Result<(), Error> {
    let n = p.points.len();
    if n < 3 {
        return Err(InputError::TooFewPoints { count: n }.into());
    }
    if n >= (NONE / 4) as usize {
        return Err(Error::InvalidOption(format!(
            "{n} points is more than this build supports"
        )));
    }
    for (i, q) in p.points.iter().enumerate() {
        if !q[0].is_finite() || !q[1].is_finite() {
            return Err(InputError::NonFinitePoint { point: i }.into());
        }
        if q[0].abs() > MAX_COORD || q[1].abs() > MAX_COORD {
            return Err(InputError::CoordinateTooLarge { point: i }.into());
        }
    }
    if !p.point_markers.is_empty() && p.point_markers.len() != n {
        return Err(InputError::MarkerCountMismatch {
            what: "point",
            expected: n,
            got: p.point_markers.len(),
        }
        .into());
    }
    if !p.segment_markers.is_empty() && p.segment_markers.len() != p.segments.len() {
        return Err(InputError::MarkerCountMismatch {
            what: "segment",
            expected: p.segments.len(),
            got: p.segment_markers.len(),
        }
        .into());
    }
    for (s, e) in p.segments.iter().enumerate() {
        for &i in e {
            if i as usize >= n {
                return Err(InputError::SegmentIndexOutOfRange {
                    segment: s,
                    index: i as u64,
                    num_points: n,
                }
                .into());
            }
        }
        if e[0] == e[1] || p.points[e[0] as usize] == p.points[e[1] as usize] {
            return Err(InputError::ZeroLengthSegment { segment: s }.into());
        }
    }
    for (i, h) in p.holes.iter().enumerate() {
        if !h[0].is_finite() || !h[1].is_finite() {
            return Err(InputError::NonFiniteHole { hole: i }.into());
        }
    }
    for (i, r) in p.regions.iter().enumerate() {
        let bad_area = matches!(r.max_area, Some(a) if a.is_nan() || a <= 0.0);
        if !r.point[0].is_finite()
            || !r.point[1].is_finite()
            || !r.attribute.is_finite()
            || bad_area
        {
            return Err(InputError::NonFiniteRegion { region: i }.into());
        }
    }
    // Duplicate segments: sort the normalised index pairs.
    let mut keys: Vec<(u32, u32, usize)> = p
        .segments
        .iter()
        .enumerate()
        .map(|(s, e)| (e[0].min(e[1]), e[0].max(e[1]), s))
        .collect();
    keys.sort_unstable();
    for w in keys.windows(2) {
        if w[0].0 == w[1].0 && w[0].1 == w[1].1 {
            let (a, b) = (w[0].2.min(w[1].2), w[0].2.max(w[1].2));
            return Err(InputError::DuplicateSegment {
                first: a,
                second: b,
            }
            .into());
        }
    }
    Ok(())
}

/// A spatially coherent insertion order: BRIO rounds (random, geometrically growing) each
/// sorted along a Hilbert curve, so walks stay short and the expected cost is O(n log n).
/// Ties in the Hilbert key go to the lower point index.
pub(super) fn brio_order(points: &[[f64; 2]]) -> Vec<u32> {
    let n = points.len();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
    let scale = 65535.0 / span;
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    // Entries `hilbert << 32 | index`, first in input order with their round's rank, then
    // grouped by rank (a stable counting sort), then each group sorted by key.
    let mut entries: Vec<u64> = Vec::with_capacity(n);
    let mut rank: Vec<u8> = Vec::with_capacity(n);
    let mut count = [0usize; 22];
    for (i, p) in points.iter().enumerate() {
        // xorshift64*: a fixed seed keeps runs reproducible.
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        let r = state.wrapping_mul(0x2545_F491_4F6C_DD1D);
        // Round = number of trailing ones: round k holds ~n/2^(k+1) points; later rounds are
        // larger, so the first rounds form a random sample that makes walks short. Rounds go
        // in the order 20, 19, ..., 0.
        let round = r.trailing_ones().min(20) as usize;
        let x = ((p[0] - lo[0]) * scale) as u32;
        let y = ((p[1] - lo[1]) * scale) as u32;
        let h = hilbert_d(x.min(65535), y.min(65535)) as u64;
        entries.push((h << 32) | i as u64);
        rank.push((20 - round) as u8);
        count[20 - round + 1] += 1;
    }
    for k in 0..21 {
        count[k + 1] += count[k];
    }
    let mut grouped = vec![0u64; n];
    let mut fill = count;
    for (&e, &r) in entries.iter().zip(&rank) {
        grouped[fill[r as usize]] = e;
        fill[r as usize] += 1;
    }
    drop(rank);
    for k in 0..21 {
        let (a, b) = (count[k], count[k + 1]);
        sort_by_high_half(&mut grouped[a..b], &mut entries[a..b]);
    }
    grouped.into_iter().map(|e| e as u32).collect()
}

/// Sorts `v` by the upper 32 bits of each entry, stably (so entries that tie keep their
/// order): an LSD radix sort in bytes, with `tmp` (as long as `v`) as the second buffer.
fn sort_by_high_half(v: &mut [u64], tmp: &mut [u64]) {
    if v.len() < 256 {
        v.sort_by_key(|e| e >> 32);
        return;
    }
    let mut hist = [[0usize; 256]; 4];
    for &e in v.iter() {
        for (b, h) in hist.iter_mut().enumerate() {
            h[((e >> (32 + 8 * b)) & 0xff) as usize] += 1;
        }
    }
    let mut in_v = true;
    for (b, h) in hist.iter_mut().enumerate() {
        // A byte shared by every entry does not reorder anything.
        if h.contains(&v.len()) {
            continue;
        }
        let mut sum = 0;
        for c in h.iter_mut() {
            let x = *c;
            *c = sum;
            sum += x;
        }
        let (src, dst): (&[u64], &mut [u64]) = if in_v { (v, tmp) } else { (tmp, v) };
        let shift = 32 + 8 * b;
        for &e in src {
            let d = ((e >> shift) & 0xff) as usize;
            dst[h[d]] = e;
            h[d] += 1;
        }
        in_v = !in_v;
    }
    if !in_v {
        v.copy_from_slice(tmp);
    }
}

/// Hilbert-curve steps four bits at a time: `HILBERT[state][x4 << 4 | y4]` holds the
/// eight-bit curve position of that 16×16 block in its low byte and the next state in the
/// next bits. A state is the symmetry applied to the remaining low bits so far: bit 0 a
/// swap of x and y, bit 1 a complement of both (the two commute).
static HILBERT: [[u16; 256]; 4] = hilbert_table();

const fn hilbert_table() -> [[u16; 256]; 4] {
    let mut t = [[0u16; 256]; 4];
    let mut st = 0;
    while st < 4 {
        let mut xy = 0;
        while xy < 256 {
            let (xb, yb) = ((xy >> 4) as u32, (xy & 15) as u32);
            let (mut sw, mut cp) = (st as u32 & 1, (st as u32 >> 1) & 1);
            let mut d = 0u32;
            let mut k = 4;
            while k > 0 {
                k -= 1;
                let (bx, by) = ((xb >> k) & 1, (yb >> k) & 1);
                let (mut rx, mut ry) = if sw == 1 { (by, bx) } else { (bx, by) };
                rx ^= cp;
                ry ^= cp;
                d = (d << 2) | ((3 * rx) ^ ry);
                if ry == 0 {
                    // The quadrant is reflected: a swap, or a swap and a complement.
                    sw ^= 1;
                    cp ^= rx;
                }
            }
            t[st][xy] = (d | ((sw | (cp << 1)) << 8)) as u16;
            xy += 1;
        }
        st += 1;
    }
    t
}

/// Position of `(x, y)` (both below 2¹⁶) along a Hilbert curve of order 16.
fn hilbert_d(x: u32, y: u32) -> u32 {
    let mut st = 0usize;
    let mut d = 0u32;
    for sh in [12, 8, 4, 0] {
        let xy = ((((x >> sh) & 15) << 4) | ((y >> sh) & 15)) as usize;
        let e = HILBERT[st][xy];
        d = (d << 8) | (e & 0xff) as u32;
        st = (e >> 8) as usize;
    }
    d
}

/// Inserts every input point (Force; no segments are in the mesh yet), in the order of
/// `points` when `ranked`, else in [`brio_order`].
fn insert_points(cdt: &mut Cdt, points: &[[f64; 2]], ranked: bool) -> Result<(), Error> {
    let order: Vec<u32> = if ranked {
        (0..points.len() as u32).collect()
    } else {
        brio_order(points)
    };
    // The first triangle: the first point, the next distinct one, the first non-collinear one.
    let a = order[0];
    let pa = points[a as usize];
    // The second point in order must differ from the first (input has at least 3 points).
    let b_pos = 1;
    let i = order[1];
    if points[i as usize] == pa {
        return Err(InputError::DuplicatePoint {
            first: a.min(i) as usize,
            second: a.max(i) as usize,
        }
        .into());
    }
    let b = order[b_pos];
    let pb = points[b as usize];
    let mut c_pos = None;
    for (k, &i) in order.iter().enumerate().skip(b_pos + 1) {
        if orient2d(pa, pb, points[i as usize]) != 0.0 {
            c_pos = Some(k);
            break;
        }
    }
    let c_pos = c_pos.ok_or(InputError::AllCollinear)?;
    let c = order[c_pos];
    // Triangulate the points renamed by their rank in `order`, stored in that order, so that
    // consecutive insertions touch neighbouring memory; the names go back afterwards.
    let n = points.len();
    let input_pts = (!ranked).then(|| {
        let mut ranked: Vec<[f64; 2]> = Vec::with_capacity(n + 1);
        ranked.extend(order.iter().map(|&i| points[i as usize]));
        ranked.push(cdt.pts[n]);
        std::mem::replace(&mut cdt.pts, ranked)
    });
    let (b_r, c_r) = (b_pos as u32, c_pos as u32);
    if orient2d(pa, pb, points[c as usize]) > 0.0 {
        cdt.init_triangle(0, b_r, c_r);
    } else {
        cdt.init_triangle(0, c_r, b_r);
    }
    let mut result = Ok(());
    for k in 0..n {
        if k == 0 || k == b_pos || k == c_pos {
            continue;
        }
        if let Err(e) = tick(|| (k as u64, n as u64)) {
            result = Err(e);
            break;
        }
        let i = order[k];
        match cdt.insert_bulk(k as u32) {
            Inserted::Yes(_) => {}
            Inserted::Duplicate(u) => {
                let u = order[u as usize];
                result = Err(InputError::DuplicatePoint {
                    first: u.min(i) as usize,
                    second: u.max(i) as usize,
                }
                .into());
                break;
            }
            other => {
                result = Err(Error::Internal(format!(
                    "inserting input point {i}: {other:?}"
                )));
                break;
            }
        }
    }
    if let Some(input_pts) = input_pts {
        cdt.pts = input_pts;
        cdt.rename_vertices(&order);
    }
    cdt.sync_aux();
    result
}

/// Checks segments against each other (crossings, overlaps) and against points (a point inside a
/// segment splits it there), with a uniform grid so typical inputs cost near-linear time.
/// With `split_crossings`, two segments that cross are both split at their intersection point
/// (rounded to floating point, as Triangle does), which is inserted into `cdt`.
fn segment_pieces(p: &Pslg, cdt: &mut Cdt, split_crossings: bool) -> Result<Vec<Piece>, Error> {
    let m = p.segments.len();
    if m == 0 {
        return Ok(Vec::new());
    }
    let pts = &p.points;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in pts {
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    let g = ((m as f64).sqrt().ceil() as usize).clamp(1, 1024);
    let wx = ((hi[0] - lo[0]) / g as f64).max(f64::MIN_POSITIVE);
    let wy = ((hi[1] - lo[1]) / g as f64).max(f64::MIN_POSITIVE);
    let cell = |q: [f64; 2]| -> (usize, usize) {
        let cx = (((q[0] - lo[0]) / wx) as usize).min(g - 1);
        let cy = (((q[1] - lo[1]) / wy) as usize).min(g - 1);
        (cx, cy)
    };
    // Bucket segments by the cells of their bounding boxes (CSR).
    let seg_cells = |s: usize| {
        let [a, b] = p.segments[s];
        let (ax, ay) = cell(pts[a as usize]);
        let (bx, by) = cell(pts[b as usize]);
        (ax.min(bx), ax.max(bx), ay.min(by), ay.max(by))
    };
    let mut count = vec![0u32; g * g + 1];
    for s in 0..m {
        let (x0, x1, y0, y1) = seg_cells(s);
        for y in y0..=y1 {
            for x in x0..=x1 {
                count[y * g + x + 1] += 1;
            }
        }
    }
    for i in 0..g * g {
        count[i + 1] += count[i];
    }
    let mut fill = count.clone();
    let mut items = vec![0u32; count[g * g] as usize];
    for s in 0..m {
        let (x0, x1, y0, y1) = seg_cells(s);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let c = y * g + x;
                items[fill[c] as usize] = s as u32;
                fill[c] += 1;
            }
        }
    }
    // Segment pairs.
    let mut crossings: Vec<(usize, usize)> = Vec::new();
    let mut seen = vec![u32::MAX; m];
    for s in 0..m {
        let (x0, x1, y0, y1) = seg_cells(s);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let c = y * g + x;
                for &t in &items[count[c] as usize..count[c + 1] as usize] {
                    let t = t as usize;
                    if t <= s || seen[t] == s as u32 {
                        continue;
                    }
                    seen[t] = s as u32;
                    match segments_conflict(p, s, t) {
                        Meeting::Fine => {}
                        Meeting::Cross if split_crossings => crossings.push((s, t)),
                        Meeting::Cross | Meeting::Overlap => {
                            return Err(InputError::CrossingSegments {
                                first: s,
                                second: t,
                            }
                            .into())
                        }
                    }
                }
            }
        }
    }
    // Points inside segments.
    let mut on_seg: Vec<(u32, f64, u32)> = Vec::new();
    for (i, q) in pts.iter().enumerate() {
        let (cx, cy) = cell(*q);
        let c = cy * g + cx;
        for &s in &items[count[c] as usize..count[c + 1] as usize] {
            let [a, b] = p.segments[s as usize];
            if a as usize == i || b as usize == i {
                continue;
            }
            let (pa, pb) = (pts[a as usize], pts[b as usize]);
            if orient2d(pa, pb, *q) == 0.0 && strictly_between(pa, pb, *q) {
                let k = if pa[0] != pb[0] { 0 } else { 1 };
                on_seg.push((s, (q[k] - pa[k]).abs(), i as u32));
            }
        }
    }
    // Crossing points become new vertices splitting both segments, unless the two cross
    // exactly at an input point, which splits both already (a computed crossing point would
    // only land next to it).
    let mut on_seg_sorted: Vec<(u32, u32)> = on_seg.iter().map(|&(s, _, i)| (s, i)).collect();
    on_seg_sorted.sort_unstable();
    let points_on = |s: usize| {
        let lo = on_seg_sorted.partition_point(|e| (e.0 as usize) < s);
        let hi = on_seg_sorted.partition_point(|e| (e.0 as usize) <= s);
        &on_seg_sorted[lo..hi]
    };
    // Crossing vertices made so far on each segment: three segments through one point (exact
    // in the reals) give three computed crossings a few ulps apart, which must be one vertex.
    let mut made: std::collections::HashMap<usize, Vec<u32>> = std::collections::HashMap::new();
    for &(s, t) in &crossings {
        if points_on(s)
            .iter()
            .any(|&(_, i)| points_on(t).iter().any(|&(_, j)| i == j))
        {
            continue;
        }
        let [a, b] = p.segments[s];
        let [c, d] = p.segments[t];
        let (pa, pb, pc, pd) = (
            pts[a as usize],
            pts[b as usize],
            pts[c as usize],
            pts[d as usize],
        );
        let e = [pb[0] - pa[0], pb[1] - pa[1]];
        let f = [pd[0] - pc[0], pd[1] - pc[1]];
        let den = e[0] * f[1] - e[1] * f[0];
        let u = ((pc[0] - pa[0]) * f[1] - (pc[1] - pa[1]) * f[0]) / den;
        let x = [pa[0] + e[0] * u, pa[1] + e[1] * u];
        let near = |y: [f64; 2]| {
            let mag = x[0].abs().max(x[1].abs()).max(y[0].abs()).max(y[1].abs());
            (x[0] - y[0]).abs().max((x[1] - y[1]).abs()) <= 4.0 * f64::EPSILON * mag
        };
        let known = [s, t]
            .iter()
            .filter_map(|k| made.get(k))
            .flatten()
            .copied()
            .chain([a, b, c, d])
            .find(|&w| near(cdt.pts[w as usize]));
        let v = match known {
            Some(w) => w,
            None => match cdt.insert(x, Start::Walk(cdt.hint), Mode::Force, NONE, None) {
                Inserted::Yes(v) | Inserted::Duplicate(v) => v,
                other => {
                    return Err(Error::Internal(format!(
                        "inserting the crossing of segments {s} and {t}: {other:?}"
                    )))
                }
            },
        };
        let pv = cdt.pts[v as usize];
        for (seg, q) in [(s, pa), (t, pc)] {
            let [r0, r1] = p.segments[seg];
            let (q0, q1) = (pts[r0 as usize], pts[r1 as usize]);
            let k = if q0[0] != q1[0] { 0 } else { 1 };
            on_seg.push((seg as u32, (pv[k] - q[k]).abs(), v));
            let list = made.entry(seg).or_default();
            if !list.contains(&v) {
                list.push(v);
            }
        }
    }
    on_seg.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)));
    // A crossing that rounds onto an endpoint or onto another split point adds nothing.
    on_seg.dedup_by(|x, y| x.0 == y.0 && x.2 == y.2);
    let mut pieces = Vec::with_capacity(m + on_seg.len());
    let mut j = 0;
    for s in 0..m {
        let [a, b] = p.segments[s];
        let mut from = a;
        while j < on_seg.len() && on_seg[j].0 as usize == s {
            if on_seg[j].2 == from || on_seg[j].2 == b {
                j += 1;
                continue;
            }
            pieces.push(Piece {
                a: from,
                b: on_seg[j].2,
                input: s as u32,
            });
            from = on_seg[j].2;
            j += 1;
        }
        pieces.push(Piece {
            a: from,
            b,
            input: s as u32,
        });
    }
    Ok(pieces)
}

/// How two input segments meet.
enum Meeting {
    /// Disjoint, or sharing an endpoint, or touching at an input point (which splits a segment).
    Fine,
    /// Their interiors cross at a single point.
    Cross,
    /// They are collinear and overlap, or join the same two points.
    Overlap,
}

/// How segments `s` and `t` meet.
fn segments_conflict(p: &Pslg, s: usize, t: usize) -> Meeting {
    let [a, b] = p.segments[s];
    let [c, d] = p.segments[t];
    let (pa, pb, pc, pd) = (
        p.points[a as usize],
        p.points[b as usize],
        p.points[c as usize],
        p.points[d as usize],
    );
    let shared = [a, b].iter().filter(|&&x| x == c || x == d).count();
    if shared == 2 {
        return Meeting::Overlap;
    }
    let o1 = orient2d(pa, pb, pc);
    let o2 = orient2d(pa, pb, pd);
    if o1 == 0.0 && o2 == 0.0 {
        // Collinear: they conflict when their interiors overlap.
        let k = if pa[0] != pb[0] { 0 } else { 1 };
        let (s0, s1) = (pa[k].min(pb[k]), pa[k].max(pb[k]));
        let (t0, t1) = (pc[k].min(pd[k]), pc[k].max(pd[k]));
        return if s0.max(t0) < s1.min(t1) {
            Meeting::Overlap
        } else {
            Meeting::Fine
        };
    }
    if shared == 1 {
        return Meeting::Fine;
    }
    let o3 = orient2d(pc, pd, pa);
    let o4 = orient2d(pc, pd, pb);
    // A proper crossing. Touchings (an endpoint inside the other segment) are handled as points
    // on segments.
    if (o1 > 0.0 && o2 < 0.0 || o1 < 0.0 && o2 > 0.0)
        && (o3 > 0.0 && o4 < 0.0 || o3 < 0.0 && o4 > 0.0)
    {
        Meeting::Cross
    } else {
        Meeting::Fine
    }
}

/// Marks exterior, holes and regions by flooding from infinity and from seeds, stopping at
/// segments. In convex-hull mode (or without segments) the hull edges become segments instead.
fn classify(r: &mut Refiner, pslg: &Pslg, opts: &Options) -> Result<(), Error> {
    let hull_mode = opts.convex_hull || pslg.segments.is_empty();
    let cdt = &mut r.cdt;
    let nslots = cdt.num_slots();
    let mut stack: Vec<u32> = Vec::new();
    for t in 0..nslots as u32 {
        if !cdt.alive(t) {
            continue;
        }
        if cdt.is_ghost(t) {
            cdt.aux[t as usize].reg = EXTERIOR;
            if hull_mode {
                // The hull edge is the ghost's finite edge; make it a boundary segment.
                let v = cdt.tv[t as usize];
                let k = (0..3).find(|&k| v[k] == cdt.ghost).unwrap_or(0) as u32;
                let h = 3 * t + k;
                if cdt.seg_at(h) == NONE {
                    let (a, b) = cdt.edge_ends(h);
                    let s = cdt.segs.len() as u32;
                    cdt.segs.push(Seg {
                        a,
                        b,
                        input: NONE,
                        marker: 1,
                        fixed: false,
                    });
                    cdt.seg_queued.push(false);
                    cdt.set_seg(h, s);
                }
            } else {
                stack.push(t);
            }
        } else {
            cdt.aux[t as usize].reg = NO_REGION;
        }
    }
    let cdt = &mut r.cdt;
    cdt.flood(&mut stack, EXTERIOR);
    for (i, h) in pslg.holes.iter().enumerate() {
        let t = seed_triangle(cdt, *h).ok_or(InputError::HoleOutsideDomain { hole: i })?;
        match cdt.aux[t as usize].reg {
            EXTERIOR => return Err(InputError::HoleOutsideDomain { hole: i }.into()),
            HOLE => continue,
            _ => {}
        }
        cdt.aux[t as usize].reg = HOLE;
        stack.push(t);
        cdt.flood(&mut stack, HOLE);
    }
    for (i, reg) in pslg.regions.iter().enumerate() {
        let t =
            seed_triangle(cdt, reg.point).ok_or(InputError::RegionOutsideDomain { region: i })?;
        if matches!(cdt.aux[t as usize].reg, EXTERIOR | HOLE) {
            return Err(InputError::RegionOutsideDomain { region: i }.into());
        }
        cdt.aux[t as usize].reg = i as u32;
        stack.push(t);
        cdt.flood(&mut stack, i as u32);
    }
    Ok(())
}

/// The triangle containing seed `p`, or `None` when `p` lies on a segment.
fn seed_triangle(cdt: &Cdt, p: [f64; 2]) -> Option<u32> {
    let t = cdt.locate(cdt.hint, p, false).ok()?;
    if cdt.is_ghost(t) {
        return Some(t);
    }
    let v = cdt.tv[t as usize];
    for i in 0..3 {
        let a = cdt.pts[v[(i + 1) % 3] as usize];
        let b = cdt.pts[v[(i + 2) % 3] as usize];
        if orient2d(a, b, p) == 0.0 && cdt.aux[t as usize].s[i] != NONE {
            return None;
        }
    }
    Some(t)
}

/// Builds the output: domain triangles, input vertices at their input index, used Steiner
/// vertices after them, subsegments on domain edges. The triangle and neighbour tables are
/// built in place in the store's `tv` and `tn` (compacting forwards: a triangle's output
/// index never exceeds its slot), and the vertex table reuses `pts`, so the store is spent
/// afterwards.
fn output(r: &mut Refiner, n: usize, pslg: &Pslg, opts: &Options) -> Result<TriMesh, Error> {
    let complete = r.complete;
    let cdt = &mut r.cdt;
    let in_domain = |cdt: &Cdt, t: u32| {
        let reg = cdt.aux[t as usize].reg;
        cdt.alive(t) && reg != EXTERIOR && reg != HOLE && !cdt.is_ghost(t)
    };
    let nv = cdt.pts.len();
    let nslots = cdt.num_slots();
    // Input vertices keep their index; `smap` numbers the used Steiner vertices (cdt index
    // `n + 1 + k`, after the ghost) in order of first use.
    let mut smap = vec![NONE; nv - n - 1];
    let vmap = |smap: &[u32], v: u32| {
        match (v as usize).cmp(&n) {
            std::cmp::Ordering::Less => v,
            std::cmp::Ordering::Equal => NONE, // the ghost
            std::cmp::Ordering::Greater => smap[v as usize - n - 1],
        }
    };
    let mut tmap = vec![NONE; nslots];
    let mut ntri = 0u32;
    let mut next_v = n as u32;
    let mut steiner: Vec<[f64; 2]> = Vec::new();
    let mut vertex_markers: Vec<i32> = if pslg.point_markers.is_empty() {
        vec![0; n]
    } else {
        pslg.point_markers.clone()
    };
    // Progress: two passes over the triangle slots.
    for t in 0..nslots as u32 {
        tick(|| (t as u64, 2 * nslots as u64))?;
        if !in_domain(cdt, t) {
            continue;
        }
        tmap[t as usize] = ntri;
        ntri += 1;
        for &v in &cdt.tv[t as usize] {
            if (v as usize) > n && smap[v as usize - n - 1] == NONE {
                smap[v as usize - n - 1] = next_v;
                next_v += 1;
                steiner.push(cdt.pts[v as usize]);
                let s = cdt.vseg[v as usize];
                let marker = if s != NONE {
                    segment_marker(pslg, s as usize)
                } else {
                    0
                };
                vertex_markers.push(marker);
            }
        }
    }
    let mut segments = Vec::new();
    let mut segment_markers = Vec::new();
    // Two input segments that meet within rounding (a vertex of one lies on the other up to
    // an ulp) can share a subsegment: list each edge once.
    let mut listed = std::collections::HashSet::with_capacity(cdt.segs.len());
    for s in &cdt.segs {
        if s.a == NONE || !listed.insert((s.a.min(s.b), s.a.max(s.b))) {
            continue;
        }
        let (a, b) = (vmap(&smap, s.a), vmap(&smap, s.b));
        if a == NONE || b == NONE {
            continue;
        }
        let Some(h) = cdt.find_edge(s.a, s.b) else {
            return Err(Error::Internal(format!(
                "subsegment ({:?}, {:?}) is missing from the mesh",
                cdt.pts[s.a as usize], cdt.pts[s.b as usize]
            )));
        };
        let tw = cdt.twin(h);
        if in_domain(cdt, h / 3) || (tw != NONE && in_domain(cdt, tw / 3)) {
            segments.push([a, b]);
            segment_markers.push(s.marker);
        }
    }
    // As Triangle: a vertex with marker 0 lying on a subsegment takes the subsegment's marker.
    for (e, &mk) in segments.iter().zip(&segment_markers) {
        for &v in e {
            if vertex_markers[v as usize] == 0 {
                vertex_markers[v as usize] = mk;
            }
        }
    }
    let mut attrs = Vec::new();
    if opts.region_attributes {
        attrs.reserve(ntri as usize);
        for (&k, reg) in tmap.iter().zip(cdt.aux.iter().map(|a| a.reg)) {
            if k != NONE {
                attrs.push(if reg == NO_REGION {
                    0.0
                } else {
                    pslg.regions[reg as usize].attribute
                });
            }
        }
    }
    let mut triangles = std::mem::take(&mut cdt.tv);
    let mut neighbors = std::mem::take(&mut cdt.tn);
    for t in 0..nslots {
        tick(|| ((nslots + t) as u64, 2 * nslots as u64))?;
        let k = tmap[t];
        if k == NONE {
            continue;
        }
        let v = triangles[t];
        triangles[k as usize] = v.map(|x| vmap(&smap, x));
        let nb = neighbors[t];
        neighbors[k as usize] = nb.map(|h| {
            if h == NONE {
                NONE
            } else {
                tmap[(h / 3) as usize]
            }
        });
    }
    triangles.truncate(ntri as usize);
    neighbors.truncate(ntri as usize);
    let mut vertices = std::mem::take(&mut cdt.pts);
    vertices.truncate(n);
    vertices.extend_from_slice(&steiner);
    Ok(TriMesh {
        steiner_points: next_v as usize - n,
        vertices,
        vertex_markers,
        num_input_vertices: n,
        triangles,
        neighbors,
        triangle_attributes: attrs,
        segments,
        segment_markers,
        complete,
    })
}

#[cfg(test)]
mod order_tests {
    use super::*;

    /// The bit-serial Hilbert position (the definition the table is built from).
    fn hilbert_ref(mut x: u32, mut y: u32) -> u32 {
        let n: u32 = 1 << 16;
        let mut d: u32 = 0;
        let mut s = n / 2;
        while s > 0 {
            let rx = u32::from((x & s) > 0);
            let ry = u32::from((y & s) > 0);
            d = d.wrapping_add(s.wrapping_mul(s).wrapping_mul((3 * rx) ^ ry));
            if ry == 0 {
                if rx == 1 {
                    x = s.wrapping_sub(1).wrapping_sub(x) & (n - 1);
                    y = s.wrapping_sub(1).wrapping_sub(y) & (n - 1);
                }
                std::mem::swap(&mut x, &mut y);
            }
            s /= 2;
        }
        d
    }

    #[test]
    fn hilbert_table_matches_bit_serial_definition() {
        let mut z: u64 = 12345;
        for i in 0..200_000u32 {
            z = z
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let (x, y) = if i < 65536 {
                (i, 65535 - i)
            } else {
                ((z >> 16) as u32 & 0xffff, (z >> 40) as u32 & 0xffff)
            };
            assert_eq!(hilbert_d(x, y), hilbert_ref(x, y), "({x}, {y})");
        }
    }

    #[test]
    fn brio_order_matches_a_comparison_sort() {
        let mut z: u64 = 99;
        let mut pts = Vec::new();
        for _ in 0..50_000 {
            z = z
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            // Coarse coordinates, so equal Hilbert keys occur.
            pts.push([((z >> 33) % 300) as f64, ((z >> 13) % 300) as f64]);
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &pts {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
        let scale = 65535.0 / span;
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut keys: Vec<(u64, u32)> = Vec::new();
        for (i, p) in pts.iter().enumerate() {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            let r = state.wrapping_mul(0x2545_F491_4F6C_DD1D);
            let round = (r.trailing_ones()).min(20) as u64;
            let x = ((p[0] - lo[0]) * scale) as u32;
            let y = ((p[1] - lo[1]) * scale) as u32;
            let h = hilbert_ref(x.min(65535), y.min(65535)) as u64;
            keys.push((((20 - round) << 32) | h, i as u32));
        }
        keys.sort_unstable();
        let want: Vec<u32> = keys.into_iter().map(|k| k.1).collect();
        assert_eq!(brio_order(&pts), want);
    }
}
