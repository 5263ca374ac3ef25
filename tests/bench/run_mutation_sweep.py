#!/usr/bin/env python3
"""Robustness sweep: `cbr` on seeded mutations of small shared surfaces.

Each case takes one surface, changes it one way (below), writes it as OFF
and runs `cbr mesh` or `cbr recover` on it (in turn). What the project
promises for any input is one of: a valid mesh (exit 0), a clear rejection
(exit 2: an invalid surface, with a message naming it) or a reported
recovery failure (exit 3). Anything else is a bug and is listed: another
exit code (4 is I/O, 5 an internal error), a signal, a time-out, or a
sanitizer report on stderr (run an ASan/UBSan build of `cbr` for those:
cmake -DCBR_SANITIZE=ON). With --verify, every mesh of an exit-0 run is
also checked by the independent checker ../shared/tools/verify
(`cbr-verify`): a mesh it rejects is a bug too, except where it says its
own volume of the input is approximate (non-manifold input) and only
that volume check fails; those are listed apart.

  tests/bench/run_mutation_sweep.py --cbr PATH [options] [SURFACE...]

  --cbr PATH      the cbr executable to test (required)
  --verify PATH   a built cbr-verify (../shared/tools/verify/build.sh DIR)
  --cases N       number of cases (default 200)
  --seed S        seed of the sweep (default 1; same seed, same cases)
  --timeout S     seconds allowed to each run (default 120)
  --keep DIR      copy every listed case's OFF (bugs and recovery
                  failures) into DIR
  SURFACE...      names in the shared data (default: the 13 small ones of
                  SMALL_SURFACES); the data directory is
                  $CBR_SHARED_DATA_DIR/surfaces or ../shared/data/surfaces
                  next to the repository

Mutations (all seeded; sizes relative to the surface's bounding box):
  jitter-all   every point moved by up to 1e-3 .. 1e-16
  jitter-one   one point moved by up to 1e-1 .. 1e-16
  snap         one point put within 1e-8 .. 1e-17 of another
  scale-shift  scaled by 1e-12 .. 1e12 and shifted by up to 1e9
  swap         two points exchange their coordinates
  flip         one triangle's orientation reversed
  collapse     a triangle's corner moved onto (or next to) its opposite edge
  fold         a corner moved across its opposite edge
  duplicate    one triangle listed twice
  drop         one triangle removed (an open surface)
  bad-value    one coordinate made nan or inf
  bad-index    one corner index made out of range

Exit status: 0 when no case is a bug, 1 otherwise, 2 on a bad command line.
"""

import argparse
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rotate_surface import read_off  # noqa: E402  (the benchmark scripts' OFF reader)

SMALL_SURFACES = [
    "cgal-cube", "cgal-cheese-box", "wildmeshing-csg-x", "thingiverse-mouth", "thingicsg-sprocket-small",
    "thingicsg-openscad-example012", "thingicsg-openscad-example016", "thingi10k-37322",
    "nonmanifold-edge-two-tets", "nonmanifold-vertex-hourglass", "wildmeshing-csg-ball",
    "thingiverse-feeder-guide-arm", "wildmeshing-supershape",
]
MUTATIONS = ["jitter-all", "jitter-one", "snap", "scale-shift", "swap", "flip", "collapse", "fold", "duplicate",
             "drop", "bad-value", "bad-index"]


def read_surface(path):
    """Points (lists of floats) and faces (lists of indices) of an OFF file."""
    points, faces = read_off(path)
    return [list(p) for p in points], [[int(i) for i in f[1:]] for f in faces]


def write_off(path, points, faces):
    with open(path, "w") as out:
        out.write(f"OFF\n{len(points)} {len(faces)} 0\n")
        for p in points:
            out.write(" ".join(repr(x) if math.isfinite(x) else str(x) for x in p) + "\n")
        for f in faces:
            out.write(f"{len(f)} {' '.join(str(i) for i in f)}\n")


def mutate(kind, points, faces, rng):
    """Changes points and faces in place, one way of `kind`."""
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    size = max(hi[k] - lo[k] for k in range(3))
    n = len(points)
    if kind == "jitter-all":
        e = size * 10.0 ** -rng.randint(3, 16)
        for p in points:
            for k in range(3):
                p[k] += rng.uniform(-e, e)
    elif kind == "jitter-one":
        e = size * 10.0 ** -rng.randint(1, 16)
        p = points[rng.randrange(n)]
        for k in range(3):
            p[k] += rng.uniform(-e, e)
    elif kind == "snap":
        i, j = rng.randrange(n), rng.randrange(n)
        e = size * 10.0 ** -rng.randint(8, 17)
        points[i] = [x + rng.uniform(-e, e) for x in points[j]]
    elif kind == "scale-shift":
        s = 10.0 ** rng.uniform(-12, 12)
        d = [rng.uniform(-1, 1) * 10.0 ** rng.uniform(0, 9) for _ in range(3)]
        for p in points:
            for k in range(3):
                p[k] = p[k] * s + d[k]
    elif kind == "swap":
        i, j = rng.randrange(n), rng.randrange(n)
        points[i], points[j] = points[j], points[i]
    elif kind == "flip":
        t = rng.randrange(len(faces))
        faces[t] = faces[t][::-1]
    elif kind == "collapse":
        a, b, c = faces[rng.randrange(len(faces))][:3]
        s = rng.choice([0.5, 1e-9, 1 - 1e-12])
        points[c] = [points[a][k] + s * (points[b][k] - points[a][k]) for k in range(3)]
    elif kind == "fold":
        a, b, c = faces[rng.randrange(len(faces))][:3]
        s = rng.choice([0.9, 0.99, 0.999999, 1.0, 1.000001])
        mid = [(points[a][k] + points[b][k]) / 2 for k in range(3)]
        points[c] = [points[c][k] + 2 * s * (mid[k] - points[c][k]) for k in range(3)]
    elif kind == "duplicate":
        faces.append(list(rng.choice(faces)))
    elif kind == "drop":
        faces.pop(rng.randrange(len(faces)))
    elif kind == "bad-value":
        points[rng.randrange(n)][rng.randrange(3)] = rng.choice([math.nan, math.inf, -math.inf])
    elif kind == "bad-index":
        f = faces[rng.randrange(len(faces))]
        f[rng.randrange(len(f))] = rng.choice([n, n + 1000, -1])
    else:
        raise ValueError(kind)


def verify(verify_bin, surface, mesh):
    """'ok', 'approximate' (only the checker's approximate volume failed) or the failure text."""
    r = subprocess.run([verify_bin, surface, mesh, "--threads", "1"], capture_output=True, text=True)
    if r.returncode == 0:
        return "ok"
    report = r.stdout + r.stderr
    failed = [line for line in report.splitlines() if line.startswith("[FAIL]")]
    if "approximate" in report and all("domain coverage" in line for line in failed):
        return "approximate"
    return "cbr-verify: " + " | ".join(failed or report.splitlines()[-3:])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cbr", required=True)
    ap.add_argument("--verify")
    ap.add_argument("--cases", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=120)
    ap.add_argument("--keep")
    ap.add_argument("surfaces", nargs="*")
    args = ap.parse_args()
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    data = os.path.join(os.environ.get("CBR_SHARED_DATA_DIR", os.path.join(repo, "..", "shared", "data")), "surfaces")
    names = [s[:-4] if s.endswith(".off") else s for s in args.surfaces] or SMALL_SURFACES
    for s in names:
        if not os.path.isfile(os.path.join(data, s + ".off")):
            print(f"run_mutation_sweep.py: no surface {s} in {data} (set CBR_SHARED_DATA_DIR)", file=sys.stderr)
            return 2
    for tool in [args.cbr] + ([args.verify] if args.verify else []):
        if not os.access(tool, os.X_OK):
            print(f"run_mutation_sweep.py: {tool} is not an executable", file=sys.stderr)
            return 2
    rng = random.Random(args.seed)
    work = tempfile.mkdtemp(prefix="cbr-mutation-sweep.")
    counts = {kind: {"cases": 0, "ok": 0, "rejected": 0, "failed": 0, "bug": 0} for kind in MUTATIONS}
    bugs, approximate, failures = [], [], []
    try:
        for case in range(args.cases):
            name, kind = rng.choice(names), rng.choice(MUTATIONS)
            command = ("mesh", "recover")[case % 2]
            points, faces = read_surface(os.path.join(data, name + ".off"))
            mutate(kind, points, faces, rng)
            surface = os.path.join(work, f"case{case}-{name}-{kind}.off")
            mesh = os.path.join(work, "out.mesh")
            write_off(surface, points, faces)
            try:
                r = subprocess.run([args.cbr, command, surface, "-o", mesh, "-q"], capture_output=True, text=True,
                                   errors="replace", timeout=args.timeout)
                rc, err = r.returncode, r.stderr
            except subprocess.TimeoutExpired:
                rc, err = "timeout", ""
            c = counts[kind]
            c["cases"] += 1
            problem = None
            if rc == "timeout" or rc not in (0, 2, 3):
                problem = f"exit {rc}: {err.strip()[:300]}"
            elif "Sanitizer" in err or "runtime error" in err:
                problem = "sanitizer: " + err.strip()[:300]
            elif rc == 0 and args.verify:
                verdict = verify(args.verify, surface, mesh)
                if verdict == "approximate":
                    approximate.append(os.path.basename(surface))
                elif verdict != "ok":
                    problem = verdict
            if problem:
                c["bug"] += 1
                bugs.append((os.path.basename(surface), command, problem))
            else:
                c[{0: "ok", 2: "rejected", 3: "failed"}[rc]] += 1
                if rc == 3:  # allowed, but worth a look: TetGen may recover it
                    failures.append((os.path.basename(surface), command, (err.strip().splitlines() or [""])[0][:300]))
            if args.keep and (problem or rc == 3):
                os.makedirs(args.keep, exist_ok=True)
                shutil.copy(surface, args.keep)
            if os.path.exists(mesh):
                os.remove(mesh)
            os.remove(surface)
    finally:
        shutil.rmtree(work, ignore_errors=True)

    print(f"{args.cases} cases (seed {args.seed}) on {len(names)} surfaces, {args.cbr}"
          + (f", meshes checked by {args.verify}" if args.verify else ""))
    print()
    print("| mutation | cases | mesh (exit 0) | rejected (2) | recovery failed (3) | bugs |")
    print("|---|---:|---:|---:|---:|---:|")
    total = {key: 0 for key in ("cases", "ok", "rejected", "failed", "bug")}
    for kind in MUTATIONS:
        c = counts[kind]
        for key in total:
            total[key] += c[key]
        print(f"| {kind} | {c['cases']} | {c['ok']} | {c['rejected']} | {c['failed']} | {c['bug']} |")
    print(f"| **total** | {total['cases']} | {total['ok']} | {total['rejected']} | {total['failed']} | "
          f"**{total['bug']}** |")
    if approximate:
        print(f"\ncbr-verify's volume of the input is approximate (non-manifold) and off for: {', '.join(approximate)}")
    for surface, command, message in failures:
        print(f"\nrecovery failed: {surface} (cbr {command}): {message}")
    for surface, command, problem in bugs:
        print(f"\nBUG {surface} (cbr {command}): {problem}")
    return 1 if bugs else 0


if __name__ == "__main__":
    sys.exit(main())
