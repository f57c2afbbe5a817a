#!/usr/bin/env python3
"""Runs a client of compat/triangle (argv[1]), reads the inputs and meshes it prints, meshes
each input again with Triangle itself (PyPI `triangle`) with the same switches, and checks that
both are valid meshes of the same domain: input vertices kept at their indices, the same area
per regional attribute, the same length of boundary per segment marker, and, for idmesh, the
quality and size bounds, neighbours and edges consistent with the triangles. Not identical
meshes: idmesh's output is conforming Delaunay, Triangle's constrained. A case with given
triangles (T lines) is a refinement (-r): Triangle gets the same triangles, attributes and
area bounds (PyPI triangle's triangle_max_area). Point attributes (A lines in, a lines out)
are given to Triangle too; when the input's are linear functions of x and y, both tools must
output those functions at every vertex (both interpolate linearly at new vertices)."""
import math
import re
import subprocess
import sys

import numpy as np
import triangle


def parse(text):
    cases, cur = [], None
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "case":
            cur = {"sw": f[1], "P": [], "G": [], "H": [], "R": [], "T": [], "p": [], "t": [],
                   "n": [], "s": [], "e": [], "A": [], "a": []}
        elif f[0] == "end":
            cases.append(cur)
            cur = None
        else:
            cur[f[0]].append([float(x) for x in f[1:]])
    return cases


def area(xy, t):
    a, b, c = xy[t[0]], xy[t[1]], xy[t[2]]
    return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))


def min_angle(xy, t):
    best = 180.0
    for i in range(3):
        a, b, c = (np.array(xy[t[(i + k) % 3]]) for k in range(3))
        u, v = b - a, c - a
        cosv = np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v))
        best = min(best, math.degrees(math.acos(max(-1.0, min(1.0, cosv)))))
    return best


def by_attr(xy, tris, attrs):
    out = {}
    for t, a in zip(tris, attrs):
        out[a] = out.get(a, 0.0) + area(xy, t)
    return out


def by_marker(xy, segs, marks):
    out = {}
    for s, m in zip(segs, marks):
        a, b = xy[s[0]], xy[s[1]]
        out[m] = out.get(m, 0.0) + math.hypot(b[0] - a[0], b[1] - a[1])
    return out


def close(d1, d2, what, errors):
    if set(d1) != set(d2) or any(abs(d1[k] - d2[k]) > 1e-9 * max(1.0, abs(d2[k])) for k in d1):
        errors.append(f"{what}: idmesh {d1} vs Triangle {d2}")


def check_linear_attributes(P, A, xy, attrs, who, errors):
    """When the input attributes A are linear in (x, y) (least squares fit exact to 1e-12),
    every output vertex's attributes must be those linear functions at it."""
    X = np.column_stack([np.array(P), np.ones(len(P))])
    coef, *_ = np.linalg.lstsq(X, np.array(A), rcond=None)
    scale = 1.0 + np.abs(np.array(A)).max()
    if np.abs(X @ coef - np.array(A)).max() > 1e-12 * scale:
        return  # not linear: nothing to compare exactly
    if len(attrs) != len(xy):
        errors.append(f"{who}: {len(attrs)} attribute rows for {len(xy)} vertices")
        return
    want = np.column_stack([np.array(xy), np.ones(len(xy))]) @ coef
    err = np.abs(np.array(attrs) - want) / (1.0 + np.abs(want))
    if err.max() > 1e-12:
        v = int(err.max(axis=1).argmax())
        errors.append(f"{who}: vertex {v} at {xy[v]} has attributes {attrs[v]}, "
                      f"linear interpolation gives {want[v].tolist()}")


def check_case(c):
    errors = []
    sw = c["sw"]
    P = [row[:2] for row in c["P"]]
    xy = [row[:2] for row in c["p"]]
    tris = [[int(x) for x in row[:3]] for row in c["t"]]
    attrs = [row[3] for row in c["t"]]
    segs = [[int(x) for x in row[:2]] for row in c["s"]]
    smarks = [int(row[2]) for row in c["s"]]
    # Triangle's own mesh of the same input (PyPI triangle adds Q and z; it has no -u).
    tri_in = {"vertices": np.array(P), "vertex_markers": np.array([[int(r[2])] for r in c["P"]])}
    if c["G"]:
        tri_in["segments"] = np.array([[int(r[0]), int(r[1])] for r in c["G"]])
        tri_in["segment_markers"] = np.array([[int(r[2])] for r in c["G"]])
    if c["H"]:
        tri_in["holes"] = np.array(c["H"])
    if c["R"]:
        tri_in["regions"] = np.array(c["R"])
    if c["T"]:
        # -r: the given mesh, its attribute and its area bound per triangle.
        tri_in["triangles"] = np.array([[int(x) for x in r[:3]] for r in c["T"]])
        tri_in["triangle_attributes"] = np.array([[r[3]] for r in c["T"]])
        tri_in["triangle_max_area"] = np.array([r[4] for r in c["T"]])
    if c["A"]:
        tri_in["vertex_attributes"] = np.array(c["A"])
    ref_sw = re.sub("[QzuenV]", "", sw)
    ref = triangle.triangulate(tri_in, ref_sw)
    rxy = ref["vertices"].tolist()
    rtris = ref["triangles"].tolist()
    rattrs = ref["triangle_attributes"][:, 0].tolist()
    rsegs = ref["segments"].tolist() if "segments" in ref else []
    rmarks = ref["segment_markers"][:, 0].tolist() if "segments" in ref else []

    if xy[: len(P)] != P:
        errors.append("idmesh moved or renumbered input vertices")
    if rxy[: len(P)] != P:
        errors.append("Triangle moved input vertices (unexpected)")
    if c["T"]:
        # -r: Triangle mixes the attributes of triangles it splits across the edges between
        # attributes (without -p they are not segments); idmesh keeps them apart. Compare the
        # total, and idmesh's areas per attribute with the given mesh's.
        close({0: sum(by_attr(xy, tris, attrs).values())},
              {0: sum(by_attr(rxy, rtris, rattrs).values())}, "total area", errors)
        given = [[int(x) for x in r[:3]] for r in c["T"]]
        close(by_attr(xy, tris, attrs), by_attr(P, given, [r[3] for r in c["T"]]),
              "area per attribute (given mesh)", errors)
    else:
        close(by_attr(xy, tris, attrs), by_attr(rxy, rtris, rattrs), "area per attribute",
              errors)
    close(by_marker(xy, segs, smarks), by_marker(rxy, rsegs, rmarks), "boundary per marker",
          errors)
    if c["A"]:
        check_linear_attributes(P, c["A"], xy, c["a"], "idmesh", errors)
        check_linear_attributes(P, c["A"], rxy, ref["vertex_attributes"].tolist(), "Triangle",
                                errors)
    # Quality and size bounds asked for.
    q = re.search(r"q([0-9.]*)", sw)
    qmin = (float(q.group(1)) if q.group(1) else 20.0) if q else 0.0
    a = re.search(r"a([0-9.]+)", sw)
    amax = float(a.group(1)) if a else math.inf
    region_area = {r[2]: r[3] for r in c["R"]} if re.search(r"a(?![0-9.])", sw) else {}
    if c["T"] and re.search(r"a(?![0-9.])", sw):
        # -ra: the bound per attribute, when the given triangles of each attribute share one.
        given = {(r[3], r[4]) for r in c["T"]}
        if len({a for a, _ in given}) == len(given):
            region_area = dict(given)
    for t, at in zip(tris, attrs):
        ar = area(xy, t)
        if ar <= 0:
            errors.append(f"triangle {t} not counter-clockwise")
        bound = min(amax, region_area.get(at, math.inf) if region_area.get(at, -1) > 0 else math.inf)
        if ar > bound * (1 + 1e-12):
            errors.append(f"triangle {t} area {ar} above {bound}")
        if min_angle(xy, t) < qmin - 1e-9:
            errors.append(f"triangle {t} angle {min_angle(xy, t)} below {qmin}")
    # Neighbours: entry i of triangle t shares the edge opposite corner i.
    for t, (tri, nb) in enumerate(zip(tris, c["n"])):
        for i in range(3):
            e = {tri[(i + 1) % 3], tri[(i + 2) % 3]}
            n = int(nb[i])
            if n >= 0 and not e <= set(tris[n]):
                errors.append(f"neighbour {i} of triangle {t} does not share its edge")
    # Edges: every triangle edge once, marked with its segment's marker (else 0).
    tri_edges = {frozenset((t[i], t[(i + 1) % 3])) for t in tris for i in range(3)}
    seg_mark = {frozenset(s): m for s, m in zip(segs, smarks)}
    out_edges = [frozenset((int(r[0]), int(r[1]))) for r in c["e"]]
    if len(out_edges) != len(tri_edges) or set(out_edges) != tri_edges:
        errors.append(f"{len(out_edges)} edges output, {len(tri_edges)} in the triangles")
    # (With -r and no -p the segments idmesh made are not output, but mark the edges.)
    for e, r in zip(out_edges, c["e"] if not c["T"] or c["s"] else []):
        if int(r[2]) != seg_mark.get(e, 0):
            errors.append(f"edge {sorted(e)} marker {int(r[2])}, segment says {seg_mark.get(e, 0)}")
    print(f"{sw}: idmesh {len(xy)} vertices {len(tris)} triangles; Triangle ({ref_sw}) "
          f"{len(rxy)} vertices {len(rtris)} triangles; {'OK' if not errors else 'FAILED'}")
    for e in errors[:10]:
        print("  " + e)
    return not errors


def main():
    run = subprocess.run([sys.argv[1]], capture_output=True, text=True)
    sys.stderr.write(run.stderr)
    if run.returncode != 0:
        print(f"{sys.argv[1]} failed with status {run.returncode}")
        return 1
    cases = parse(run.stdout)
    if not cases:
        print("no mesh printed")
        return 1
    ok = all([check_case(c) for c in cases])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
