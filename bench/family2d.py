#!/usr/bin/env python3
"""Writes the 2D small-angle and thin-channel family (issue 13, item 5) to tests/data/family2d/.

Each member is a small Triangle `.poly` file (no holes, no regions) on which a quality mesher
has to work around sharp input angles or a long thin gap:

* star-N-T: a star polygon with N spikes of tip angle T degrees around a round body
  (star-12-mixed: tips of 3, 8, 15 and 25 degrees in turn);
* slot-R: a thin rectangular slot of aspect 1:R fed by a wide square chamber at each end
  (a channel between two rooms);
* channel-R: a plain 1 x 1/R rectangle;
* comb-N: a comb with N thin teeth (each 1:20) on a spine;
* wedge-T: a square with one spike of tip angle T degrees (one very sharp input angle);
* fan-N: N segments radiating from one centre vertex inside a square, with small angles
  (a few degrees) between neighbours;
* tee-T: a segment ending on an input point inside another segment at T degrees from it.

Coordinates are written as Python's repr (round-trip exact), so the files are regenerated bit for
bit:

    python3 bench/family2d.py            # writes tests/data/family2d/*.poly
    python3 bench/family2d.py --list     # prints the member names
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench2d import write_poly  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "data", "family2d")


def star(n, tips, body=0.4, arc_deg=10.0):
    """A star of n spikes of length 1 - body around a round body of radius `body` (a polygon
    with a vertex every arc_deg degrees); spike k has the tip angle tips[k % len(tips)] degrees
    (its base is narrowed to fit, never wider than 0.8 of its share of the circle)."""
    pts = []
    share = 2 * math.pi / n
    for k in range(n):
        phi = share * k
        tip = math.radians(tips[k % len(tips)])
        # Half-width d of the base (at radius `body`) for that tip angle, by bisection: the
        # angle at (1, 0) between the base points body * (cos(+-d), sin(+-d)) grows with d.
        lo, hi = 0.0, 0.4 * share
        for _ in range(80):
            d = 0.5 * (lo + hi)
            if 2 * math.atan2(body * math.sin(d), 1 - body * math.cos(d)) < tip:
                lo = d
            else:
                hi = d
        pts.append(polar(body, phi - d))
        pts.append(polar(1.0, phi))
        pts.append(polar(body, phi + d))
        a0, a1 = phi + d, phi + share - 0.4 * share
        m = int(math.degrees(a1 - a0) / arc_deg)
        for j in range(1, m):
            pts.append(polar(body, a0 + (a1 - a0) * j / m))
    return pts, closed(len(pts))


def polar(r, a):
    return (r * math.cos(a), r * math.sin(a))


def slot(ratio):
    """Two unit square rooms joined by a channel of width 1/ratio and length 1 (aspect 1:ratio)."""
    w = 1.0 / ratio
    h = 0.5 * w
    pts = [
        (0.0, -0.5), (1.0, -0.5), (1.0, -h), (2.0, -h), (2.0, -0.5), (3.0, -0.5),
        (3.0, 0.5), (2.0, 0.5), (2.0, h), (1.0, h), (1.0, 0.5), (0.0, 0.5),
    ]
    return pts, closed(len(pts))


def channel(ratio):
    """A rectangle of length 1 and width 1/ratio."""
    w = 1.0 / ratio
    pts = [(0.0, 0.0), (1.0, 0.0), (1.0, w), (0.0, w)]
    return pts, closed(len(pts))


def comb(n):
    """A spine of height 0.2 with n teeth of width 0.02 and length 0.4, gaps of 0.03 between."""
    tooth, gap, length, spine = 0.02, 0.03, 0.4, 0.2
    width = n * tooth + (n + 1) * gap
    pts = [(0.0, 0.0), (width, 0.0), (width, spine)]
    x = width - gap
    for _ in range(n):
        pts += [(x, spine), (x, spine + length), (x - tooth, spine + length), (x - tooth, spine)]
        x -= tooth + gap
    pts.append((0.0, spine))
    # Drop repeated consecutive points (x, spine) of the first tooth's right edge.
    clean = []
    for p in pts:
        if not clean or clean[-1] != p:
            clean.append(p)
    return clean, closed(len(clean))


def wedge(tip_deg):
    """The unit square [1, 2] x [-0.5, 0.5] with a spike of length 1 on its left side, its tip
    at the origin with an angle of tip_deg degrees (one very sharp input angle)."""
    h = math.tan(math.radians(tip_deg) / 2)
    pts = [(0.0, 0.0), (1.0, -h), (1.0, -0.5), (2.0, -0.5), (2.0, 0.5), (1.0, 0.5), (1.0, h)]
    return pts, closed(len(pts))


def fan(n):
    """The square [-1, 1]^2 with n segments from the origin to points on a circle of radius
    0.8, 4 degrees apart, starting at angle 0."""
    pts = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (0.0, 0.0)]
    segs = closed(4)
    for k in range(n):
        a = math.radians(4.0 * k)
        pts.append((0.8 * math.cos(a), 0.8 * math.sin(a)))
        segs.append((4, len(pts) - 1))
    return pts, segs


def tee(deg):
    """The unit square with a segment of slope 2 across it and a second one starting at an
    input point inside the first, deg degrees off it (a T-junction with a sharp angle)."""
    pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.1875, 0.0625), (0.5, 0.6875),
           (0.25, 0.1875)]
    a = math.atan2(2.0, 1.0) + math.radians(deg)
    pts.append((0.25 + 0.6 * math.cos(a), 0.1875 + 0.6 * math.sin(a)))
    return pts, closed(4) + [(4, 5), (6, 7)]


def closed(n):
    return [(i, (i + 1) % n) for i in range(n)]


MEMBERS = {
    "star-5-10": lambda: star(5, [10.0]),
    "star-8-5": lambda: star(8, [5.0]),
    "star-12-mixed": lambda: star(12, [3.0, 8.0, 15.0, 25.0]),
    "slot-50": lambda: slot(50),
    "slot-200": lambda: slot(200),
    "slot-1000": lambda: slot(1000),
    "channel-100": lambda: channel(100),
    "comb-8": lambda: comb(8),
    "wedge-2": lambda: wedge(2.0),
    "wedge-10": lambda: wedge(10.0),
    "fan-6": lambda: fan(6),
    "tee-3": lambda: tee(3.0),
}


def main():
    if "--list" in sys.argv[1:]:
        print("\n".join(MEMBERS))
        return
    os.makedirs(OUT, exist_ok=True)
    for name, make in MEMBERS.items():
        pts, segs = make()
        write_poly(os.path.join(OUT, name + ".poly"), pts, segs, [],
                   title=f"{name}.poly: written by bench/family2d.py")
    print(f"wrote {len(MEMBERS)} files to {os.path.relpath(OUT, ROOT)}/")


if __name__ == "__main__":
    main()
