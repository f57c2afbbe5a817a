"""Readers shared by fuzz/recheck2d.py and fuzz/recheck3d.py for the Triangle/TetGen text
formats (.node .poly .ele .face): records without comments, and a node section."""


def records(path):
    """The whitespace-separated fields of each line of `path`, comments (`#` to the end of the
    line) and blank lines left out."""
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                yield line


def read_points(it, n, dim):
    """`n` point records of `dim` coordinates from the record iterator `it`, by their ids."""
    pts = {}
    for _ in range(n):
        r = next(it)
        pts[int(r[0])] = tuple(float(x) for x in r[1 : 1 + dim])
    return pts
