#!/usr/bin/env python3
"""Tests of the exact rechecks fuzz/recheck2d.py and fuzz/recheck3d.py: each passes a correct
mesh and fails a mesh broken in the way it is there to catch.

    python3 fuzz/test_recheck.py
"""

import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))

CUBE = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)]
CUBE_FACETS = [(1, 2, 4, 3), (5, 6, 8, 7), (1, 2, 6, 5), (3, 4, 8, 7), (1, 3, 7, 5), (2, 4, 8, 6)]


def points_lines(pts):
    """A node section: the count line, then one line a point."""
    dim = len(next(iter(pts.values())))
    return [f"{len(pts)} {dim} 0 0"] + [f"{i} {' '.join(repr(x) for x in p)}"
                                        for i, p in sorted(pts.items())]


def cells_lines(cells, per):
    """An element section (.ele, .face, segments): the count line, then one line a cell."""
    return [f"{len(cells)} {per}"] + [f"{k} {' '.join(map(str, c))}"
                                      for k, c in enumerate(cells, 1)]


def write_case(d, files):
    """Writes each (ending, lines) file of one case into directory `d`; returns their paths."""
    paths = []
    for ending, lines in files:
        paths.append(os.path.join(d, "case" + ending))
        with open(paths[-1], "w") as f:
            f.write("\n".join(lines) + "\n")
    return paths


def run_recheck(script, files):
    """Writes each (ending, lines) file of one case and runs `script` over them."""
    with tempfile.TemporaryDirectory() as d:
        paths = write_case(d, files)
        r = subprocess.run([sys.executable, os.path.join(HERE, script)] + paths,
                           capture_output=True, text=True)
        return r.returncode, r.stdout


def det3(a, b, c, d):
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    w = [d[k] - a[k] for k in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0]))


def positive(pts, t):
    a, b, c, d = t
    return t if det3(*(pts[v] for v in t)) > 0 else (a, c, b, d)


def centred_cube():
    """The unit cube cut into 12 tets around its centre (vertex 9): every corner and edge on
    the boundary, the centre an interior vertex."""
    pts = {i + 1: p for i, p in enumerate(CUBE)}
    pts[9] = (0.5, 0.5, 0.5)
    faces = []
    for a, b, c, d in CUBE_FACETS:
        faces += [(a, b, c), (a, c, d)]
    tets = [positive(pts, f + (9,)) for f in faces]
    return pts, tets, faces


class Recheck3d(unittest.TestCase):
    def run_case(self, pts, tets, faces, facets, input_pts=None, holes=(), facet_holes=None):
        """`facets`: polygons, or lists of polygons; `facet_holes`: facet index -> its hole
        points."""
        poly = points_lines(input_pts or pts) + [f"{len(facets)} 0"]
        for k, q in enumerate(facets):
            loops = q if isinstance(q[0], (tuple, list)) else [q]
            fh = (facet_holes or {}).get(k, [])
            poly += [f"{len(loops)} {len(fh)}"]
            poly += [f"{len(p)} {' '.join(map(str, p))}" for p in loops]
            poly += [f"{j} {h[0]!r} {h[1]!r} {h[2]!r}" for j, h in enumerate(fh, 1)]
        poly += [f"{len(holes)}"] + [f"{k} {h[0]!r} {h[1]!r} {h[2]!r}"
                                     for k, h in enumerate(holes, 1)] + ["0"]
        return run_recheck("recheck3d.py", [(".poly", poly), (".node", points_lines(pts)),
                                            (".ele", cells_lines(tets, "4 0")),
                                            (".face", cells_lines(faces, "0"))])

    def test_correct_cube_passes(self):
        pts, tets, faces = centred_cube()
        code, out = self.run_case(pts, tets, faces, CUBE_FACETS)
        self.assertEqual(code, 0, out)
        self.assertIn("9 vertex stars checked", out)

    def test_inverted_tet_fails(self):
        pts, tets, faces = centred_cube()
        a, b, c, d = tets[0]
        tets[0] = (b, a, c, d)
        code, out = self.run_case(pts, tets, faces, CUBE_FACETS)
        self.assertEqual(code, 1, out)
        self.assertIn("tet orientations", out)

    def test_overlapping_tet_at_a_corner_fails(self):
        # A 13th tet inside the cube's corner at vertex 1, its faces listed as boundary: every
        # tet positive and every face matched or listed, but the tets at vertex 1 overlap.
        pts, tets, faces = centred_cube()
        pts[10], pts[11], pts[12] = (0.2, 0.1, 0.1), (0.1, 0.2, 0.1), (0.1, 0.1, 0.2)
        t = positive(pts, (1, 10, 11, 12))
        tets.append(t)
        faces += [(1, 10, 11), (1, 11, 12), (1, 10, 12), (10, 11, 12)]
        code, out = self.run_case(pts, tets, faces, CUBE_FACETS, centred_cube()[0])
        self.assertEqual(code, 1, out)
        self.assertIn("whose tets overlap", out)
        self.assertIn("vertex 1:", out)

    def test_crossing_cones_fail(self):
        # The same, with the extra tet poking out through the cube's bottom face.
        pts, tets, faces = centred_cube()
        pts[10], pts[11], pts[12] = (0.2, 0.1, -0.1), (0.1, 0.2, 0.1), (0.1, 0.1, 0.2)
        tets.append(positive(pts, (1, 10, 11, 12)))
        faces += [(1, 10, 11), (1, 11, 12), (1, 10, 12), (10, 11, 12)]
        code, out = self.run_case(pts, tets, faces, CUBE_FACETS, centred_cube()[0])
        self.assertEqual(code, 1, out)
        self.assertIn("whose tets overlap", out)

    def test_inner_facet_must_be_listed_subfaces(self):
        # An input facet (1, 2, 9) through the cube: the tets have it as a face; it conforms
        # only if the .face file lists it as a subface.
        pts, tets, faces = centred_cube()
        facets = CUBE_FACETS + [(1, 2, 9)]
        code, out = self.run_case(pts, tets, faces + [(1, 2, 9)], facets)
        self.assertEqual(code, 0, out)
        code, out = self.run_case(pts, tets, faces, facets)
        self.assertEqual(code, 1, out)
        self.assertIn("facets not covered", out)
        self.assertIn("segments are not chains", out)

    def test_facet_outside_passes_and_facet_across_fails(self):
        pts, tets, faces = centred_cube()
        inp = dict(pts)
        inp[10], inp[11], inp[12] = (2.0, 0.0, 0.0), (3.0, 0.0, 0.0), (2.0, 1.0, 0.5)
        code, out = self.run_case(dict(inp), tets, faces, CUBE_FACETS + [(10, 11, 12)], inp)
        self.assertEqual(code, 0, out)
        self.assertIn("1 of them outside the mesh", out)
        inp[10] = (0.75, 0.25, 0.25)
        code, out = self.run_case(dict(inp), tets, faces, CUBE_FACETS + [(10, 11, 12)], inp)
        self.assertEqual(code, 1, out)
        self.assertIn("facets not covered", out)


    def test_hole_point_in_a_tet_fails(self):
        pts, tets, faces = centred_cube()
        code, out = self.run_case(pts, tets, faces, CUBE_FACETS, holes=[(0.5, 0.5, 0.5)])
        self.assertEqual(code, 1, out)
        self.assertIn("hole point", out)

    def test_tet_outside_the_cube_fails(self):
        pts, tets, faces = centred_cube()
        pts[10] = (0.5, 0.5, 1.5)
        tets.append(positive(pts, (5, 6, 8, 10)))
        faces += [(5, 6, 10), (6, 8, 10), (5, 8, 10)]
        code, out = self.run_case(pts, tets, faces, CUBE_FACETS, centred_cube()[0])
        self.assertEqual(code, 1, out)
        self.assertIn("lie on no facet", out)

    def test_enclosed_region_left_out_fails(self):
        # The cube with a tetrahedral surface inside: meshing only the inside of that surface
        # leaves out the region between it and the cube, which nothing carves.
        inp = {i + 1: p for i, p in enumerate(CUBE)}
        inner = [(0.2, 0.2, 0.2), (0.8, 0.2, 0.2), (0.2, 0.8, 0.2), (0.2, 0.2, 0.8)]
        for k, p in enumerate(inner):
            inp[9 + k] = p
        tet_faces = [(9, 10, 11), (9, 10, 12), (9, 11, 12), (10, 11, 12)]
        tets = [positive(inp, (9, 10, 11, 12))]
        code, out = self.run_case(dict(inp), tets, tet_faces, CUBE_FACETS + tet_faces, inp)
        self.assertEqual(code, 1, out)
        self.assertIn("4 boundary faces whose outside is not shown exterior", out)
        # With hole points between the two surfaces, that region is carved: correct. (One in
        # sight of each face: the check does not follow paths around the inner surface.)
        holes = [(0.4, 0.4, 0.1), (0.4, 0.1, 0.4), (0.1, 0.4, 0.4), (0.9, 0.9, 0.9)]
        code, out = self.run_case(dict(inp), tets, tet_faces, CUBE_FACETS + tet_faces, inp,
                                  holes=holes)
        self.assertEqual(code, 0, out)
        code, out = self.run_case(dict(inp), tets, tet_faces, CUBE_FACETS + tet_faces, inp,
                                  holes=holes[1:])
        self.assertEqual(code, 1, out)
        self.assertIn("1 boundary faces whose outside is not shown exterior", out)

    def test_missing_tet_fails(self):
        pts, tets, faces = centred_cube()
        a, b, c = faces[0]
        del tets[0]
        faces = faces[1:] + [(a, b, 9), (b, c, 9), (a, c, 9)]
        code, out = self.run_case(pts, tets, faces, CUBE_FACETS)
        self.assertEqual(code, 1, out)
        self.assertIn("facets not covered", out)
        self.assertIn("lie on no facet", out)


def cube_with_a_square_on_its_bottom():
    """centred_cube() with a square (vertices 10 to 13) inside its bottom facet, the bottom
    triangulated through the square's edges: an annulus of 8 triangles and the square's 2."""
    pts = {i + 1: p for i, p in enumerate(CUBE)}
    pts[9] = (0.5, 0.5, 0.5)
    pts.update({10: (0.25, 0.25, 0.0), 11: (0.75, 0.25, 0.0), 12: (0.75, 0.75, 0.0),
                13: (0.25, 0.75, 0.0)})
    faces = [(1, 2, 11), (1, 11, 10), (2, 4, 12), (2, 12, 11), (4, 3, 13), (4, 13, 12),
             (3, 1, 10), (3, 10, 13), (10, 11, 12), (10, 12, 13)]
    for a, b, c, d in CUBE_FACETS[1:]:
        faces += [(a, b, c), (a, c, d)]
    tets = [positive(pts, f + (9,)) for f in faces]
    facets = [[CUBE_FACETS[0], (10, 11, 12, 13)]] + CUBE_FACETS[1:]
    return pts, tets, faces, facets


class FacetsOfSeveralPolygons(unittest.TestCase):
    run_case = Recheck3d.run_case

    def test_square_inside_a_facet_passes(self):
        # The inner square bounds part of the facet: the facet is the whole bottom.
        pts, tets, faces, facets = cube_with_a_square_on_its_bottom()
        code, out = self.run_case(pts, tets, faces, facets)
        self.assertEqual(code, 0, out)
        self.assertIn("6 facets checked", out)

    def test_hole_in_a_facet_covered_fails(self):
        # A hole point inside the square takes the square out of the facet (its 2 triangles
        # are then on no facet); one between the squares takes out the annulus and leaves the
        # inner square, an island (the annulus's 8 triangles are on no facet).
        for hole, off in (((0.5, 0.5, 0.0), 2), ((0.1, 0.5, 0.0), 8)):
            with self.subTest(hole=hole):
                pts, tets, faces, facets = cube_with_a_square_on_its_bottom()
                code, out = self.run_case(pts, tets, faces, facets, facet_holes={0: [hole]})
                self.assertEqual(code, 1, out)
                self.assertIn(f"{off} boundary faces lie on no facet", out)


class RecheckIfFloat(unittest.TestCase):
    """fuzz/recheck3d_if_float.sh: a verify3d.py failure is rechecked only when every failed
    claim is one it decides in floating point."""

    def judge(self, verify_output):
        pts, tets, faces = centred_cube()
        poly = points_lines(pts) + [f"{len(CUBE_FACETS)} 0"]
        for q in CUBE_FACETS:
            poly += ["1", f"{len(q)} {' '.join(map(str, q))}"]
        poly += ["0", "0"]
        with tempfile.TemporaryDirectory() as d:
            out, *paths = write_case(d, [
                (".out", [verify_output]), (".poly", poly), (".node", points_lines(pts)),
                (".ele", cells_lines(tets, "4 0")), (".face", cells_lines(faces, "0"))])
            return subprocess.run([os.path.join(HERE, "recheck3d_if_float.sh"), out] + paths,
                                  capture_output=True).returncode

    PARTLY = ("  [FAIL] conformity   facets=6\n"
              "         ! 1 facets only partly covered by output faces, e.g. facet 1\n")

    def test_float_claim_on_a_right_mesh_is_rechecked(self):
        self.assertEqual(self.judge(self.PARTLY + "RESULT: FAILED\n"), 0)

    def test_failed_delaunay_check_stands(self):
        self.assertEqual(self.judge(self.PARTLY + "  [FAIL] delaunay     violating_tets=1\n"), 1)

    def test_other_conformity_claim_stands(self):
        self.assertEqual(self.judge("  [FAIL] conformity   facets=6\n"
                                    "         ! 2 boundary faces lie off the facets\n"), 1)

    def test_passing_output_is_not_a_recheck(self):
        self.assertEqual(self.judge("  [PASS] topology\nRESULT: OK\n"), 1)


class CampaignCases(unittest.TestCase):
    """Meshes of the 3D campaign (seed 1) that verify3d.py fails on its floating-point sums and
    areas (fuzz/recheck_cases: r122, r455 overlaps at a vertex 1e-9 from another, r455 also
    segment pieces, r475 a facet 1e-12 across measured as area 0, r2049 a tiny facet inside a
    cavity shading the floor from the hole point): the exact recheck passes each, and fails
    each with one tet turned inside out."""

    CASES = ["3d-seed1-r122", "3d-seed1-r455", "3d-seed1-r475", "3d-seed1-r2049"]

    def files(self, name):
        base = os.path.join(HERE, "recheck_cases", name)
        files = []
        for e in (".poly", ".node", ".ele", ".face"):
            with open(base + e) as f:
                files.append((e, f.read().rstrip("\n").split("\n")))
        return files

    def test_recheck_passes_them(self):
        for name in self.CASES:
            code, out = run_recheck("recheck3d.py", self.files(name))
            self.assertEqual(code, 0, name + ": " + out)

    def test_recheck_fails_them_with_a_tet_inverted(self):
        for name in self.CASES:
            files = self.files(name)
            ele = files[2][1]
            first = ele[1].split()
            first[1], first[2] = first[2], first[1]
            files[2] = (".ele", [ele[0], " ".join(first)] + ele[2:])
            code, out = run_recheck("recheck3d.py", files)
            self.assertEqual(code, 1, name + ": " + out)
            self.assertIn("tet orientations", out)


class Recheck2d(unittest.TestCase):
    def run_case(self, pts, tris, segs):
        poly = points_lines(pts) + cells_lines(segs, "0") + ["0"]
        return run_recheck("recheck2d.py", [(".poly", poly), (".node", points_lines(pts)),
                                            (".ele", cells_lines(tris, "3 0"))])

    SQUARE = {1: (0.0, 0.0), 2: (1.0, 0.0), 3: (1.0, 1.0), 4: (0.0, 1.0)}
    BORDER = [(1, 2), (2, 3), (3, 4), (4, 1)]

    def test_diagonal_covered_passes(self):
        code, out = self.run_case(self.SQUARE, [(1, 2, 3), (1, 3, 4)], self.BORDER + [(1, 3)])
        self.assertEqual(code, 0, out)

    def test_diagonal_crossed_fails(self):
        code, out = self.run_case(self.SQUARE, [(1, 2, 4), (2, 3, 4)], self.BORDER + [(1, 3)])
        self.assertEqual(code, 1, out)
        self.assertIn("NOT covered", out)


if __name__ == "__main__":
    unittest.main()
