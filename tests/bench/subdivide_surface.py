#!/usr/bin/env python3
"""Writes a copy of a triangulated OFF surface with every triangle split
into four at its edge midpoints, N times: the same shape with four times
the triangles per step, for measuring how recovery scales with the size
of the input (a surface of a million triangles from igea's 268,686 in one
step). The new points lie in the planes of their triangles up to rounding,
so each old triangle becomes four nearly coplanar ones: many more faces
are missing after Delaunay than on a surface sampled as finely.

    subdivide_surface.py IN.off OUT.off [N]    (N: steps, default 1)

Coordinates are written with 17 significant digits (exact for doubles);
comments are dropped."""
import sys


def read_off(path):
    tokens = []
    with open(path) as f:
        for line in f:
            tokens += line.split('#')[0].split()
    if not tokens or not tokens[0].upper().endswith('OFF'):
        sys.exit(f'{path}: not an OFF file')
    nv, nf = int(tokens[1]), int(tokens[2])
    i = 4
    points = [tuple(float(x) for x in tokens[i + 3 * k:i + 3 * k + 3]) for k in range(nv)]
    i += 3 * nv
    triangles = []
    for _ in range(nf):
        k = int(tokens[i])
        if k != 3:
            sys.exit(f'{path}: a face with {k} corners (triangles only)')
        triangles.append(tuple(int(x) for x in tokens[i + 1:i + 4]))
        i += 1 + k
    return points, triangles


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
    points, triangles = read_off(sys.argv[1])
    for _ in range(steps):
        triangles = subdivide(points, triangles)
    with open(sys.argv[2], 'w') as f:
        f.write(f'OFF\n{len(points)} {len(triangles)} 0\n')
        for p in points:
            f.write('%.17g %.17g %.17g\n' % p)
        for t in triangles:
            f.write('3 %d %d %d\n' % t)


if __name__ == '__main__':
    main()
