#!/usr/bin/env python3
"""Writes a regular N-gon prism whose two caps are fanned from one rim
vertex, as CAD exporters write cylinders: long thin cap triangles on
cocircular points. Turned by rotate_surface.py, its caps are no longer
exactly planar, which is what the robustness sweeps of README
("Robustness") measure.

    fan_cap_prism.py N RADIUS HEIGHT OUT.off

The caps are fanned from vertex 0 (bottom, normal -z) and vertex N (top,
normal +z); each side quad is two triangles. Outward orientation."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rotate_surface import write_triangles  # noqa: E402  (the benchmark scripts' OFF writer)


def prism(n, radius, height):
    points = [(radius * math.cos(2 * math.pi * i / n), radius * math.sin(2 * math.pi * i / n), z)
              for z in (0.0, height) for i in range(n)]
    tris = [(0, i + 1, i) for i in range(1, n - 1)]
    tris += [(n, n + i, n + i + 1) for i in range(1, n - 1)]
    for i in range(n):
        j = (i + 1) % n
        tris += [(i, j, n + j), (i, n + j, n + i)]
    return points, tris


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    n, radius, height, out = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
    if n < 3 or not radius > 0 or not height > 0:
        sys.exit('fan_cap_prism.py: N must be at least 3, RADIUS and HEIGHT positive')
    points, tris = prism(n, radius, height)
    write_triangles(out, points, tris)


if __name__ == '__main__':
    main()
