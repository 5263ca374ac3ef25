#!/usr/bin/env python3
"""Writes an OFF surface as a Medit .mesh holding only its points and
triangles (for gmsh, which reads Medit but not OFF). Coordinates are copied
as the OFF file spells them, so the points are bit for bit the same; a
polygon with more than three corners is split into a fan, as `cbr` does
with its polygon option. Every triangle gets reference 1 (one discrete
surface).

    off_to_medit.py IN.off OUT.mesh
"""
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        tokens = " ".join(line.split("#", 1)[0] for line in f).split()
    if not tokens or tokens[0] != "OFF":
        sys.exit("%s: not a plain OFF file (no colours or normals)" % sys.argv[1])
    nv, nf = int(tokens[1]), int(tokens[2])
    at = 4
    points = [tokens[at + 3 * i:at + 3 * i + 3] for i in range(nv)]
    at += 3 * nv
    triangles = []
    for _ in range(nf):
        n = int(tokens[at])
        ids = [int(x) for x in tokens[at + 1:at + 1 + n]]
        at += 1 + n
        triangles.extend((ids[0], ids[k], ids[k + 1]) for k in range(1, n - 1))
    with open(sys.argv[2], "w") as out:
        out.write("MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n" % nv)
        out.writelines("%s %s %s 0\n" % tuple(p) for p in points)
        out.write("Triangles\n%d\n" % len(triangles))
        out.writelines("%d %d %d 1\n" % (a + 1, b + 1, c + 1) for a, b, c in triangles)
        out.write("End\n")


if __name__ == "__main__":
    main()
