#!/usr/bin/env python3
"""Exact second look at a 3D campaign case that verify3d.py flags on topology or conformity.

verify3d.py sums solid angles at vertices and dihedral angles around edges in floating point
(tolerance 1e-6), and measures facet areas and segment pieces in floating point too. Where the
fuzzer puts a vertex 1e-9 from another, or adds a facet 1e-8 across, those sums and areas lose
their digits (a facet of area 6e-17 at coordinates near 0.6 is measured with an error of 20%),
and the checker reports overlaps and uncovered facets that are not there. This script decides
the same claims in exact arithmetic: every coordinate as written is a dyadic rational, all of
them are scaled to integers by one power of two, and every sign below is that of an exact
integer expression.

Topology: every tet has the same nonzero orientation; every triangle of the tets lies in one
tet (a boundary face, which the .face file must list) or in two with opposite orientations;
every .face entry is a triangle of the tets; every input vertex is an output vertex.

Local embedding at every vertex v (what the solid-angle sums stand for): the tets at v, seen
from v, are cones over spherical triangles, all positively oriented. Directed edges of these
triangles that meet their reverse cancel; what is left is the boundary of v's link.
* No boundary (interior vertex): the number of cones that contain a direction is the same for
  every direction (the degree of the link onto the sphere), so one generic direction decides
  that they cover the sphere exactly once.
* Boundary (boundary vertex): the count changes only across the boundary arcs. The arcs must
  form disjoint simple closed curves on the sphere (exact great-circle arc intersection tests),
  and at one arc of each curve the count must be 1 just inside and 0 just outside (directions
  perturbed symbolically). Every region of the sphere cut by such curves borders one of them,
  so the count is 0 or 1 everywhere: the tets at v do not overlap.
A point of an edge or face lies in the star of each of its vertices, so this covers the
dihedral sums around edges as well.

Conformity: every input segment (an edge of a facet polygon) is a chain of output edges from
one end to the other, each vertex strictly further along than the one before and no further
from the segment's line than `ULPS` units in the last place of its ends' coordinates (split
points are rounded); every facet is covered: the output triangles whose vertices lie within
the same tolerance of its plane and whose centroid projects into it have, in the projection
along its normal's dominant axis, the facet's area up to what that rounding can move
(perimeter times the tolerance). A facet of several polygons is the region they bound, less
what its hole points take out (see FacetRegion).

    fuzz/recheck3d.py CASE.poly CASE.node CASE.ele CASE.face [ULPS]
"""

import math
import random
import sys
from fractions import Fraction as F

from tetgen_files import read_points, records


def read_plc(poly):
    """Input vertices, facets (each a list of polygons, a polygon a list of vertex ids, and
    the facet's hole points) and the volume's hole points."""
    it = records(poly)
    h = next(it)
    n = int(h[0])
    if n == 0:
        node = poly[: -len(".poly")] + ".node"
        nit = records(node)
        pts = read_points(nit, int(next(nit)[0]), 3)
    else:
        pts = read_points(it, n, 3)
    facets = []
    for _ in range(int(next(it)[0])):
        h = next(it)
        k, nh = int(h[0]), int(h[1]) if len(h) > 1 else 0
        polys = []
        for _ in range(k):
            r = next(it)
            polys.append([int(x) for x in r[1 : 1 + int(r[0])]])
        fholes = [tuple(float(x) for x in next(it)[1:4]) for _ in range(nh)]
        facets.append((polys, fholes))
    holes = []
    r = next(it, None)
    for _ in range(int(r[0]) if r else 0):
        holes.append(tuple(float(x) for x in next(it)[1:4]))
    return pts, facets, holes


def read_mesh(node, ele, face):
    it = records(node)
    pts = read_points(it, int(next(it)[0]), 3)
    it = records(ele)
    tets = [tuple(int(x) for x in next(it)[1:5]) for _ in range(int(next(it)[0]))]
    it = records(face)
    faces = [tuple(int(x) for x in next(it)[1:4]) for _ in range(int(next(it)[0]))]
    return pts, tets, faces


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def det(a, b, c):
    return dot(a, cross(b, c))


def sign(x):
    return (x > 0) - (x < 0)


def lex_sign(*xs):
    """Sign of x0 + e x1 + e^2 x2 + ... for an infinitesimal e > 0."""
    for x in xs:
        if x:
            return sign(x)
    return 0


class Case:
    def __init__(self, argv):
        poly, node, ele, face = argv[:4]
        self.ulps = float(argv[4]) if len(argv) > 4 else 16.0
        self.ipts, self.facets, self.holes = read_plc(poly)
        self.opts, self.tets, self.faces = read_mesh(node, ele, face)
        # One power of two makes every coordinate an integer (floats are dyadic).
        den = 1
        fholes = [h for _, hs in self.facets for h in hs]
        for p in list(self.ipts.values()) + list(self.opts.values()) + self.holes + fholes:
            for x in p:
                den = max(den, x.as_integer_ratio()[1])
        self.den = den
        self.P = {i: tuple(int(F(x) * den) for x in p) for i, p in self.opts.items()}
        self.by_xyz = {p: i for i, p in self.opts.items()}
        self.errors = []
        self.notes = []
        self.rng = random.Random(1)

    def fail(self, msg):
        self.errors.append(msg)

    def tol(self, coords):
        """`ulps` units in the last place of the largest of `coords`, in integer units."""
        return F(self.ulps) * F(math.ulp(max(abs(x) for x in coords))) * self.den

    # ---- topology -------------------------------------------------------------------------

    def topology(self):
        P = self.P
        signs = set()
        for t in self.tets:
            a, b, c, d = (P[v] for v in t)
            signs.add(sign(det(sub(b, a), sub(c, a), sub(d, a))))
        if 0 in signs or len(signs) != 1:
            self.fail(f"tet orientations (exact): {sorted(signs)}, not one nonzero sign")
            return False
        self.sigma = signs.pop()
        # Each tet's faces, oriented outward (for sigma > 0: (b,c,d) seen from a is clockwise).
        count = {}
        for ti, t in enumerate(self.tets):
            for k in range(4):
                f = [t[j] for j in range(4) if j != k]
                if k % 2 == 1:
                    f[1], f[2] = f[2], f[1]
                key = tuple(sorted(f))
                # parity of the permutation from key to f decides the face's orientation
                par = perm_parity(f, key)
                count.setdefault(key, []).append((par, ti))
        boundary = set()
        self.boundary = {}
        for key, uses in count.items():
            if len(uses) == 1:
                boundary.add(key)
                self.boundary[key] = uses[0][1]
            elif len(uses) != 2 or uses[0][0] == uses[1][0]:
                self.fail(f"face {key}: in {len(uses)} tets" +
                          ("" if len(uses) != 2 else " with the same orientation"))
        listed = {tuple(sorted(f)) for f in self.faces}
        missing = boundary - listed
        if missing:
            self.fail(f"{len(missing)} boundary faces not in the .face file, e.g. {min(missing)}")
        extra = listed - set(count)
        if extra:
            self.fail(f"{len(extra)} .face entries are not faces of the tets, e.g. {min(extra)}")
        lost = [i for i, p in self.ipts.items() if p not in self.by_xyz]
        if lost:
            self.fail(f"{len(lost)} input vertices are not output vertices, e.g. {lost[0]}")
        return True

    def stars(self):
        P = self.P
        star = {}
        for t in self.tets:
            for k in range(4):
                star.setdefault(t[k], []).append([t[j] for j in range(4) if j != k])
        bad = 0
        first = None
        for v, opp in star.items():
            msg = self.star_embedded(v, P[v], opp)
            if msg:
                bad += 1
                first = first or f"vertex {v}: {msg}"
        if bad:
            self.fail(f"{bad} vertices whose tets overlap (exact), e.g. {first}")
        self.notes.append(f"{len(star)} vertex stars checked")

    def star_embedded(self, v, p, opp):
        P = self.P
        cones = []
        directed = {}
        for x, y, z in opp:
            a, b, c = sub(P[x], p), sub(P[y], p), sub(P[z], p)
            if det(a, b, c) < 0:
                y, z, b, c = z, y, c, b
            cones.append((a, b, c))
            for e, third in (((x, y), z), ((y, z), x), ((z, x), y)):
                directed[e] = directed.get(e, 0) + 1
                directed.setdefault(("third", e), third)
        arcs = []
        for e, n in directed.items():
            if e[0] == "third":
                continue
            if n != 1 or directed.get((e[1], e[0]), 0) > 1:
                return f"link edge {e} used {n} times"
            if (e[1], e[0]) not in directed:
                arcs.append(e)

        def count(d):
            total = 0
            for a, b, c in cones:
                s = (lex_sign(*(det(di, b, c) for di in d)),
                     lex_sign(*(det(a, di, c) for di in d)),
                     lex_sign(*(det(a, b, di) for di in d)))
                if 0 in s:
                    return None
                total += s == (1, 1, 1)
            return total

        def random_dir():
            return tuple(self.rng.randint(-10**9, 10**9) for _ in range(3))

        if not arcs:
            for _ in range(8):
                n = count((random_dir(),))
                if n is not None:
                    return None if n == 1 else f"interior vertex, its tets cover a direction {n} times"
            return "no generic direction found"
        vec = {}
        for e in arcs:
            for w in e:
                vec[w] = sub(P[w], p)
        out_arcs = {}
        for e in arcs:
            if e[0] in out_arcs:
                return "boundary link not a set of disjoint cycles (two arcs leave one vertex)"
            out_arcs[e[0]] = e[1]
        if {e[1] for e in arcs} != set(out_arcs):
            return "boundary arcs do not close"
        for e in arcs:
            if not any(cross(vec[e[0]], vec[e[1]])):
                return f"boundary face ({v}, {e[0]}, {e[1]}) is degenerate"
        for i in range(len(arcs)):
            for j in range(i + 1, len(arcs)):
                if arcs_meet(vec, arcs[i], arcs[j]):
                    return f"boundary arcs {arcs[i]} and {arcs[j]} meet"
        # One arc per cycle: count 1 just inside, 0 just outside.
        seen = set()
        for start in out_arcs:
            if start in seen:
                continue
            w = start
            while w not in seen:
                seen.add(w)
                w = out_arcs[w]
            e = (start, out_arcs[start])
            m = tuple(s + t for s, t in zip(vec[e[0]], vec[e[1]]))
            inward = sub(P[directed[("third", e)]], p)
            for _ in range(8):
                r = random_dir()
                inside = count((m, inward, r))
                outside = count((m, tuple(-c for c in inward), r))
                if inside is not None and outside is not None:
                    break
            else:
                return "no generic direction found at a boundary arc"
            if (inside, outside) != (1, 0):
                return (f"boundary vertex, directions at arc {e} are covered {inside} times "
                        f"inside and {outside} times outside (want 1 and 0)")
        return None

    # ---- conformity ----------------------------------------------------------------------

    def meets_mesh(self, pts):
        """Whether the convex hull of `pts` (a segment or a facet polygon) meets the interior of
        some tet (no plane among the separating-axis candidates, faces of each and edge against
        edge, has the tet's interior on one side and the hull on the other), or its vertices'
        centroid lies in a closed tet: a feature along faces of the tets is in the mesh, not
        outside it (exact)."""
        P = self.P
        k = len(pts)
        cen = tuple(sum(x[i] for x in pts) for i in range(3))  # k times the centroid
        lo = [min(x[k] for x in pts) for k in range(3)]
        hi = [max(x[k] for x in pts) for k in range(3)]
        hull_edges = [sub(pts[(k + 1) % len(pts)], pts[k]) for k in range(len(pts))]
        own = []
        if len(pts) >= 3:
            n = (0, 0, 0)
            for k in range(len(pts)):
                n = tuple(s + t for s, t in zip(n, cross(pts[k], pts[(k + 1) % len(pts)])))
            own.append(n)
        for t in self.tets:
            q = [P[v] for v in t]
            if any(max(x[k] for x in q) <= lo[k] or min(x[k] for x in q) >= hi[k]
                   for k in range(3) if lo[k] != hi[k]):
                continue
            axes = list(own)
            for i in range(4):
                f = [q[j] for j in range(4) if j != i]
                axes.append(cross(sub(f[1], f[0]), sub(f[2], f[0])))
            for i in range(4):
                for j in range(i + 1, 4):
                    e = sub(q[j], q[i])
                    axes.extend(cross(e, h) for h in hull_edges)
            separated = False
            for n in axes:
                if not any(n):
                    continue
                a = [dot(n, x) for x in pts]
                b = [dot(n, x) for x in q]
                if max(a) <= min(b) or max(b) <= min(a):
                    separated = True
                    break
            if not separated:
                return True
            kq = [tuple(k * c for c in x) for x in q]
            if contains(kq, cen):
                return True
        return False

    def segments(self):
        # A facet's edge is covered by edges of subfaces (the .face file, checked against the
        # tets above); a lone segment by any edges.
        sub_edges, edges = {}, {}
        for graph, cells in ((sub_edges, self.faces), (edges, self.tets)):
            for t in cells:
                for i in range(len(t)):
                    for j in range(i + 1, len(t)):
                        graph.setdefault(t[i], set()).add(t[j])
                        graph.setdefault(t[j], set()).add(t[i])
        lone = set()
        segs = set()
        for polys, _ in self.facets:
            for poly in polys:
                if len(poly) == 2:
                    segs.add(tuple(sorted(poly)))
                    lone.add(tuple(sorted(poly)))
                elif len(poly) > 2:
                    for k in range(len(poly)):
                        segs.add(tuple(sorted((poly[k], poly[(k + 1) % len(poly)]))))
        P = self.P
        bad = []
        exterior = 0
        self.on_segment = set()  # edges along a segment: the chains' and their branches
        for ia, ib in sorted(segs):
            a, b = self.by_xyz.get(self.ipts[ia]), self.by_xyz.get(self.ipts[ib])
            if a is None or b is None:
                bad.append((ia, ib))
                continue
            pa, pb = P[a], P[b]
            d = sub(pb, pa)
            len2 = dot(d, d)
            tol = self.tol(self.ipts[ia] + self.ipts[ib])

            def along(w):
                return dot(sub(P[w], pa), d)

            def near(w):
                c = cross(sub(P[w], pa), d)
                return dot(c, c) <= tol * tol * len2

            graph = edges if (ia, ib) in lone else sub_edges
            covered, stack, seen = False, [a], {a}
            while stack and not covered:
                w = stack.pop()
                for u in graph.get(w, ()):
                    if u in seen or along(u) <= along(w) or not near(u):
                        continue
                    self.on_segment.add((min(u, w), max(u, w)))
                    if u == b:
                        covered = True
                        break
                    seen.add(u)
                    stack.append(u)
            if not covered and self.meets_mesh([pa, pb]):
                bad.append((ia, ib))
            elif not covered:
                exterior += 1
        if bad:
            self.fail(f"{len(bad)} input segments are not chains of output edges, e.g. {bad[0]}")
        self.notes.append(f"{len(segs)} segments checked, {exterior} of them outside the mesh")

    def regions(self):
        """Each facet's FacetRegion (None for a facet of no polygon or of zero area), from the
        input coordinates in integer units."""
        if not hasattr(self, "_regions"):
            den = self.den
            ipts = {i: tuple(int(F(x) * den) for x in p) for i, p in self.ipts.items()}
            self._regions = []
            for polys, fholes in self.facets:
                loops = [[ipts[i] for i in q] for q in polys if len(q) >= 3]
                holes = [tuple(int(F(x) * den) for x in h) for h in fholes]
                region = FacetRegion(loops, holes) if loops else None
                self._regions.append(region if region and region.area2 else None)
        return self._regions

    def facet_coverage(self):
        P = self.P
        bad = []
        checked = exterior = 0
        self.on_facet = {}  # face -> the facets (indices) it lies on
        for fi, ((polys, _), region) in enumerate(zip(self.facets, self.regions()), 1):
            ids = [i for q in polys if len(q) >= 3 for i in q]
            if not ids:
                continue
            if any(self.by_xyz.get(self.ipts[i]) is None for i in ids):
                bad.append(f"facet {fi}: a corner is not an output vertex")
                continue
            if region is None:
                bad.append(f"facet {fi}: zero area")
                continue
            normal, u, w, q0 = region.normal, region.u, region.w, region.main[0]
            tol = self.tol([c for i in ids for c in self.ipts[i]])
            n2 = dot(normal, normal)
            lo, hi = region.lo, region.hi
            slack = int(tol) + 1

            def on_plane(v, cache={}):
                key = (fi, v)
                if key not in cache:
                    x = P[v]
                    if any(x[k] < lo[k] - slack or x[k] > hi[k] + slack for k in range(3)):
                        cache[key] = False
                    else:
                        h = dot(sub(x, q0), normal)
                        cache[key] = h * h <= tol * tol * n2
                return cache[key]

            covered2 = 0
            for f in self.faces:
                if not all(on_plane(v) for v in f):
                    continue
                a, b, c = (P[v] for v in f)
                cen = ((a[u] + b[u] + c[u]), (a[w] + b[w] + c[w]))
                if region.classify(cen, 3) <= 0:
                    continue
                covered2 += abs((b[u] - a[u]) * (c[w] - a[w]) - (b[w] - a[w]) * (c[u] - a[u]))
                self.on_facet.setdefault(tuple(sorted(f)), set()).add(fi - 1)
            # Rounded split points move the boundary by at most tol (times the normal's tilt).
            tilt = F(math.sqrt(n2)) / abs(normal[region.axis])
            allowed = 4 * F(region.perimeter()) * tol * (tilt + 1)
            checked += 1
            if covered2 == 0 and not self.meets_mesh(region.main):
                exterior += 1
            elif abs(covered2 - region.area2) > 2 * allowed:
                bad.append(f"facet {fi}: covered {float(F(covered2, region.area2))} of its area")
        if bad:
            self.fail(f"{len(bad)} facets not covered (exact), e.g. {bad[0]}")
        self.notes.append(f"{checked} facets checked, {exterior} of them outside the mesh")

    # ---- domain ---------------------------------------------------------------------------

    def domain(self):
        """The meshed region is the input's: every boundary face lies on a facet (above), no
        hole point lies in a tet, and the outside of every boundary face is exterior: a ray from
        its centroid reaches infinity, or a segment reaches a hole point, crossing no facet
        (the normal first, then 15 random outward directions; exact), or it shares an edge
        along no segment with such a face. As in verify3d.py, a face whose outside sees
        neither is reported although a longer path might exist."""
        P = self.P
        den = self.den
        off = [f for f in self.boundary if f not in self.on_facet]
        if off:
            self.fail(f"{len(off)} boundary faces lie on no facet, e.g. {min(off)}")
        planes = [(i, r.normal, dot(r.normal, r.main[0]), r)
                  for i, r in enumerate(self.regions()) if r]
        holes = [tuple(int(F(x) * den) for x in h) for h in self.holes]
        for h in holes:
            if any(contains([P[v] for v in t], h) for t in self.tets):
                self.fail(f"hole point {h} lies in a tet")

        def blocked(S, k, D, segment, own):
            # The ray (S + t D) / k, t > 0 (t < 1 for a segment), meets a facet (closed) other
            # than the facets `own` of the face it starts from: that face's rounded Steiner
            # points can put its centroid a hair inside its own facet's plane, and a ray
            # leaving a plane does not meet it again.
            for fi, n, c, region in planes:
                if fi in own:
                    continue
                s = dot(n, D)
                num = k * c - dot(n, S)
                if s == 0:
                    if num == 0:
                        return True  # along the facet's plane: undecided, try another ray
                    continue
                if s < 0:
                    s, num = -s, -num
                if num <= 0 or (segment and num >= s):
                    continue
                X = tuple(S[i] * s + num * D[i] for i in range(3))  # scale k * s
                ks = k * s
                if any(X[i] < region.lo[i] * ks or X[i] > region.hi[i] * ks for i in range(3)):
                    continue
                if region.classify((X[region.u], X[region.w]), ks) >= 0:
                    return True
            return False

        # Boundary faces that share an edge along no segment have their outsides in one region
        # (two facets meet only along segments): one proof serves the whole group.
        parent = {f: f for f in self.boundary}

        def root(f):
            while parent[f] != f:
                parent[f] = parent[parent[f]]
                f = parent[f]
            return f

        by_edge = {}
        for f in self.boundary:
            for i in range(3):
                e = (f[i], f[(i + 1) % 3])
                e = (min(e), max(e))
                if e in self.on_segment:
                    continue
                if e in by_edge:
                    parent[root(f)] = root(by_edge[e])
                else:
                    by_edge[e] = f
        proven = set()
        unproven = []
        for f, ti in self.boundary.items():
            if root(f) in proven:
                continue
            a, b, c = (P[v] for v in f)
            d = P[next(v for v in self.tets[ti] if v not in f)]
            n = cross(sub(b, a), sub(c, a))
            if dot(n, sub(d, a)) > 0:
                n = tuple(-x for x in n)
            S = tuple(a[i] + b[i] + c[i] for i in range(3))
            to_holes = [tuple(3 * h[i] - S[i] for i in range(3)) for h in holes]
            own = self.on_facet.get(tuple(sorted(f)), ())
            if any(dot(D, n) > 0 and not blocked(S, 3, D, True, own) for D in to_holes):
                proven.add(root(f))
                continue
            dirs = [n]
            while len(dirs) < 16:
                r = tuple(self.rng.randint(-10**9, 10**9) for _ in range(3))
                if dot(r, n):
                    dirs.append(r if dot(r, n) > 0 else tuple(-x for x in r))
            if not all(blocked(S, 3, D, False, own) for D in dirs):
                proven.add(root(f))
                continue
            unproven.append(f)
        unproven = [f for f in unproven if root(f) not in proven]
        if unproven:
            self.fail(f"{len(unproven)} boundary faces whose outside is not shown exterior (no ray "
                      f"to infinity or a hole point misses the facets), e.g. {min(unproven)}")
        self.notes.append(f"{len(self.boundary)} boundary faces shown to face the exterior")


class FacetRegion:
    """A facet (integer coordinates) in the projection along the dominant axis of its largest
    polygon's normal: its polygons of three or more corners (loops), each solid or void. A loop
    is void when it is the innermost loop around one of the facet's hole points: the hole takes
    out what that loop encloses, except the loops inside it (islands, which segments separate
    from the hole point). The facet is the set of points whose innermost enclosing loop is
    solid; loops either nest or have disjoint insides, as in a valid PLC."""

    def __init__(self, loops, holes):
        normals = []
        for q in loops:
            n = (0, 0, 0)
            for k in range(len(q)):
                n = tuple(s + t for s, t in zip(n, cross(q[k], q[(k + 1) % len(q)])))
            normals.append(n)
        main = max(range(len(loops)), key=lambda i: dot(normals[i], normals[i]))
        self.normal, self.main = normals[main], loops[main]
        self.axis = max(range(3), key=lambda k: abs(self.normal[k]))
        self.u, self.w = (self.axis + 1) % 3, (self.axis + 2) % 3
        self.lo = [min(x[k] for q in loops for x in q) for k in range(3)]
        self.hi = [max(x[k] for q in loops for x in q) for k in range(3)]
        # Twice the projected areas; loops of none (corners on a line) bound nothing.
        area2 = [abs(n[self.axis]) for n in normals]
        keep = [i for i in range(len(loops)) if area2[i]]
        self.loops = [[(x[self.u], x[self.w]) for x in loops[i]] for i in keep]
        self.areas = [area2[i] for i in keep]
        self.parent = [self.innermost_around_loop(i) for i in range(len(self.loops))]
        self.void = [False] * len(self.loops)
        for h in holes:
            i = self.innermost((h[self.u], h[self.w]), 1)
            if i is not None:
                self.void[i] = True
        # A solid loop adds its area where it starts the facet (at the top or inside a void
        # loop); a void loop takes its area out of the solid loop around it.
        self.area2 = 0
        for i, p in enumerate(self.parent):
            outer_solid = p is not None and not self.void[p]
            if not self.void[i] and not outer_solid:
                self.area2 += self.areas[i]
            elif self.void[i] and outer_solid:
                self.area2 -= self.areas[i]

    def innermost_around_loop(self, i):
        """The smallest loop, other than loop i, whose closure holds loop i and whose inside
        holds one of its corners or edge midpoints."""
        best = None
        q = self.loops[i]
        for j, r in enumerate(self.loops):
            if j == i or self.areas[j] <= self.areas[i]:
                continue
            if any(where_in_polygon(x, r, 1) < 0 for x in q):
                continue
            mids = [(q[k][0] + q[k - 1][0], q[k][1] + q[k - 1][1]) for k in range(len(q))]
            if not (any(where_in_polygon(x, r, 1) > 0 for x in q)
                    or any(where_in_polygon(m, r, 2) > 0 for m in mids)):
                continue
            if best is None or self.areas[j] < self.areas[best]:
                best = j
        return best

    def innermost(self, pt, scale):
        """The smallest loop whose inside holds pt / scale (None if there is none)."""
        best = None
        for j, r in enumerate(self.loops):
            if where_in_polygon(pt, r, scale) > 0 and (best is None or self.areas[j] < self.areas[best]):
                best = j
        return best

    def classify(self, pt, scale):
        """1 if pt / scale (projected) lies inside the facet, 0 on a loop, -1 outside."""
        if any(where_in_polygon(pt, r, scale) == 0 for r in self.loops):
            return 0
        i = self.innermost(pt, scale)
        return 1 if i is not None and not self.void[i] else -1

    def perimeter(self):
        return sum(math.dist(r[k], r[k - 1]) for r in self.loops for k in range(len(r)))


def contains(q, x):
    """Whether point x lies in the closed tet q (exact)."""
    s = sign(det(sub(q[1], q[0]), sub(q[2], q[0]), sub(q[3], q[0])))
    for j in range(4):
        r = list(q)
        r[j] = x
        if sign(det(sub(r[1], r[0]), sub(r[2], r[0]), sub(r[3], r[0]))) == -s:
            return False
    return True


def perm_parity(f, key):
    f = list(f)
    par = 0
    for i in range(3):
        j = f.index(key[i])
        if j != i:
            f[i], f[j] = f[j], f[i]
            par ^= 1
    return par


def on_arc(vec, e, x):
    """Whether direction x, on the great circle of arc e, lies on the closed minor arc."""
    a, b = vec[e[0]], vec[e[1]]
    n = cross(a, b)
    return dot(cross(a, x), n) >= 0 and dot(cross(x, b), n) >= 0


def arcs_meet(vec, e, g):
    """Whether two boundary arcs of a link (minor great-circle arcs) share a point other than
    a common end."""
    shared = set(e) & set(g)
    a, b = vec[e[0]], vec[e[1]]
    c, d = vec[g[0]], vec[g[1]]
    na, nb = cross(a, b), cross(c, d)
    x = cross(na, nb)
    if not any(x):  # one great circle
        ends = [(e, g[0], c), (e, g[1], d), (g, e[0], a), (g, e[1], b)]
        if shared:
            # consecutive arcs: only the common end, so neither far end lies on the other arc
            return any(on_arc(vec, arc, y) for arc, w, y in ends if w not in shared)
        return any(on_arc(vec, arc, y) for arc, w, y in ends)
    if shared:
        # two great circles meet in +-(common end); the antipode lies on no minor arc through it
        return False
    for y in (x, tuple(-t for t in x)):
        if on_arc(vec, e, y) and on_arc(vec, g, y):
            return True
    return False


def where_in_polygon(pt, poly, scale):
    """1 if pt / scale lies inside the polygon, 0 on its boundary, -1 outside (exact)."""
    x, y = pt
    inside = False
    n = len(poly)
    for k in range(n):
        (x1, y1), (x2, y2) = poly[k], poly[(k + 1) % n]
        x1, y1, x2, y2 = x1 * scale, y1 * scale, x2 * scale, y2 * scale
        if min(x1, x2) <= x <= max(x1, x2) and min(y1, y2) <= y <= max(y1, y2) \
                and (x2 - x1) * (y - y1) == (y2 - y1) * (x - x1):
            return 0
        if (y1 > y) != (y2 > y):
            o = (x2 - x1) * (y - y1) - (y2 - y1) * (x - x1)
            if (o > 0) == (y2 > y1):
                inside = not inside
    return 1 if inside else -1


def main():
    case = Case(sys.argv[1:])
    if case.topology():
        case.stars()
        case.segments()
        case.facet_coverage()
        case.domain()
    for e in case.errors:
        print("FAIL", e)
    print(f"{sys.argv[1]}: {'FAILED' if case.errors else 'OK'} ({', '.join(case.notes)})")
    return 1 if case.errors else 0


if __name__ == "__main__":
    sys.exit(main())
