#!/usr/bin/env python3
"""Writes a copy of an OFF surface turned by a random rotation, scaled by a
random factor in [1e-3, 1e3] and shifted: the same shape, other rounding.
Recovery must not depend on how a surface sits in space; CAD shapes whose
planar faces are no longer exactly planar after the turn are the test.

    rotate_surface.py IN.off OUT.off SEED

The transform depends on SEED only (Python's random.Random), so a run is
reproducible. Faces are copied as they are; comments are dropped."""
import math
import random
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
    faces = []
    for _ in range(nf):
        k = int(tokens[i])
        faces.append(tokens[i:i + 1 + k])
        i += 1 + k
    return points, faces


def write_triangles(path, points, triangles):
    """An OFF file of points (3 floats each, written exactly) and
    triangles (3 indices each)."""
    with open(path, 'w') as f:
        f.write('OFF\n%d %d 0\n' % (len(points), len(triangles)))
        for p in points:
            f.write('%r %r %r\n' % tuple(p))
        for t in triangles:
            f.write('3 %d %d %d\n' % tuple(t))


def transform(seed):
    rng = random.Random(seed)
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(x * x for x in q))
    a, b, c, d = (x / n for x in q)
    rotation = [[a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
                [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
                [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d]]
    scale = 10 ** rng.uniform(-3, 3)
    shift = [rng.uniform(-1000, 1000) * scale for _ in range(3)]
    return rotation, scale, shift


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    points, faces = read_off(sys.argv[1])
    rotation, scale, shift = transform(int(sys.argv[3]))
    with open(sys.argv[2], 'w') as out:
        out.write(f'OFF\n{len(points)} {len(faces)} 0\n')
        for p in points:
            q = [scale * sum(rotation[r][k] * p[k] for k in range(3)) + shift[r] for r in range(3)]
            out.write('%.17g %.17g %.17g\n' % tuple(q))
        for f in faces:
            out.write(' '.join(f) + '\n')


if __name__ == '__main__':
    main()
