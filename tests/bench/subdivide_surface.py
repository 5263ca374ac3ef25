#!/usr/bin/env python3
"""Writes a copy of a triangulated OFF surface with every triangle split
into four at its edge midpoints, N times: the same shape with four times
the triangles per step, for measuring how recovery scales with the size
of the input (a surface of a million triangles from igea's 268,686 in one
step). The new points lie in the planes of their triangles up to rounding,
so each old triangle becomes four nearly coplanar ones: many more faces
are missing after Delaunay than on a surface sampled as finely.

    subdivide_surface.py IN.off OUT.off [N]    (N: steps, default 1)

Coordinates are written exactly (Python's repr of each double); comments
are dropped."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rotate_surface import read_off, write_triangles  # noqa: E402  (the benchmark scripts' OFF module)


def read_triangles(path):
    """Points and triangles (tuples of three indices) of an OFF file."""
    points, faces = read_off(path)
    triangles = []
    for f in faces:
        if int(f[0]) != 3:
            sys.exit(f'{path}: a face with {f[0]} corners (triangles only)')
        triangles.append(tuple(int(x) for x in f[1:4]))
    return list(points), triangles


def subdivide(points, triangles):
    middle = {}

    def midpoint(a, b):
        key = (min(a, b), max(a, b))
        if key not in middle:
            points.append(tuple((x + y) / 2 for x, y in zip(points[a], points[b])))
            middle[key] = len(points) - 1
        return middle[key]

    out = []
    for a, b, c in triangles:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return out


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    steps = int(sys.argv[3]) if len(sys.argv) == 4 else 1
    if steps < 0:
        sys.exit('N: a number of steps, 0 or more')
    points, triangles = read_triangles(sys.argv[1])
    for _ in range(steps):
        triangles = subdivide(points, triangles)
    write_triangles(sys.argv[2], points, triangles)


if __name__ == '__main__':
    main()
