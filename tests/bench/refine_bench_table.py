#!/usr/bin/env python3
"""Measures and formats what run_refine_bench.sh collected (RAW.csv): reads
each successful run's mesh (TetGen's .node/.ele for cbr and TetGen, Medit
.mesh for gmsh), computes Table II with the formulas of src/cli/quality.hpp
(q = 3 r_in / r_circ after scaling to unit longest edge; dihedral angles by
atan2), takes libcbr's "q < 0.1 touching a Steiner point" from its --json
report (column stn; the peers' outputs do not tell their Steiner points from
their other points) and the tetrahedra it left over its size bound (their
total under the table), prints per peer (TetGen; gmsh when it ran) the per-mesh
table and the totals (over the surfaces both cbr and the peer meshed), and
with --csv FILE writes them as CSV: the TetGen columns first, as before the
gmsh columns were added at the end of each row, and after the TetGen total
a row of gmsh totals (its cbr columns over the surfaces both meshed).

    refine_bench_table.py RAW.csv [--csv FILE]
"""
import argparse
import csv
import json
import math
import sys


def read_numbers(path):
    rows = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                rows.append(line)
    return rows


def read_mesh(node_path, ele_path):
    nodes = read_numbers(node_path)
    n, dim = int(nodes[0][0]), int(nodes[0][1])
    first = int(nodes[1][0]) if n else 0
    xyz = {}
    for r in nodes[1:1 + n]:
        xyz[int(r[0])] = (float(r[1]), float(r[2]), float(r[3]))
    eles = read_numbers(ele_path)
    m, per = int(eles[0][0]), int(eles[0][1])
    tets = [tuple(int(x) for x in r[1:1 + per]) for r in eles[1:1 + m]]
    return xyz, tets


def read_medit(path):
    """Points (1-based ids) and tetrahedra of a Medit .mesh file."""
    with open(path) as f:
        tokens = " ".join(line.split("#", 1)[0] for line in f).split()
    xyz, tets, at = {}, [], 0
    while at < len(tokens):
        key = tokens[at]
        at += 1
        if key in ("MeshVersionFormatted", "Dimension"):
            at += 1
        elif key == "Vertices":
            n = int(tokens[at])
            for i in range(n):
                xyz[i + 1] = tuple(float(x) for x in tokens[at + 1 + 4 * i:at + 4 + 4 * i])
            at += 1 + 4 * n
        elif key in ("Edges", "Triangles", "Quadrilaterals", "Tetrahedra", "Hexahedra"):
            per = {"Edges": 3, "Triangles": 4, "Quadrilaterals": 5, "Tetrahedra": 5, "Hexahedra": 9}[key]
            n = int(tokens[at])
            if key == "Tetrahedra":
                tets = [tuple(int(x) for x in tokens[at + 1 + per * i:at + per * i + per]) for i in range(n)]
            at += 1 + per * n
        elif key == "End":
            break
        else:
            raise ValueError("%s: unknown Medit keyword %s" % (path, key))
    return xyz, tets


def sub(p, q):
    return (p[0] - q[0], p[1] - q[1], p[2] - q[2])


def dot(p, q):
    return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]


def cross(p, q):
    return (p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])


def norm(p):
    return math.sqrt(dot(p, p))


EDGES = ((0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2), (1, 2, 0, 3), (1, 3, 0, 2), (2, 3, 0, 1))


def measure(a, b, c, d):
    """(q, min dihedral, max dihedral) of one tetrahedron."""
    u, v, w = sub(b, a), sub(c, a), sub(d, a)
    longest = max(norm(u), norm(v), norm(w), norm(sub(v, u)), norm(sub(w, u)), norm(sub(w, v)))
    if not longest > 0:
        return 0.0, 0.0, 0.0
    s = 1 / longest
    u, v, w = tuple(x * s for x in u), tuple(x * s for x in v), tuple(x * s for x in w)
    vw, wu, uv = cross(v, w), cross(w, u), cross(u, v)
    det = dot(u, vw)
    q = 0.0
    if det != 0:
        area = 0.5 * (norm(uv) + norm(wu) + norm(vw) + norm(cross(sub(v, u), sub(w, u))))
        uu, vv, ww = dot(u, u), dot(v, v), dot(w, w)
        nn = tuple(uu * vw[k] + vv * wu[k] + ww * uv[k] for k in range(3))
        q = min(max(3 * det * det / (area * norm(nn)), 0.0), 1.0)
    p = ((0.0, 0.0, 0.0), u, v, w)
    lo, hi = 180.0, 0.0
    for e in EDGES:
        axis = sub(p[e[1]], p[e[0]])
        n1, n2 = cross(axis, sub(p[e[2]], p[e[0]])), cross(axis, sub(p[e[3]], p[e[0]]))
        deg = math.degrees(math.atan2(norm(cross(n1, n2)), dot(n1, n2)))
        lo, hi = min(lo, deg), max(hi, deg)
    return q, lo, hi


def table_two(node_path, ele_path=None):
    """Table II of a .node/.ele pair, or of a Medit .mesh (no ele_path)."""
    xyz, tets = read_mesh(node_path, ele_path) if ele_path else read_medit(node_path)
    total, qmin, dmin, below = 0.0, 1.0, 180.0, 0
    for t in tets:
        q, lo, _ = measure(*(xyz[i] for i in t))
        total += q
        qmin = min(qmin, q)
        dmin = min(dmin, lo)
        below += q < 0.1
    n = len(tets)
    return {"tets": n, "avg": total / n if n else None, "min": qmin if n else None,
            "dih": dmin if n else None, "below": 100.0 * below / n if n else None}


def from_report(json_path, *keys):
    """A value of cbr's --json report (keys: its path), or None when the
    report or the value is missing."""
    try:
        with open(json_path) as f:
            value = json.load(f)
        for key in keys:
            value = value[key]
        return value
    except (OSError, ValueError, KeyError, TypeError):
        return None


def fmt(v, spec):
    return "-" if v is None else format(v, spec)


def ratio(a, b):
    return a / b if a is not None and b else None


# The peers: key (and column label), name, command in the table's title.
PEERS = {"tg": ("tetgen", "tetgen -pYq1.414"), "gm": ("gmsh", "gmsh -3 (Delaunay)")}


def peer_table(rows, peer):
    """Prints the table of cbr against one peer; returns the CSV rows (per
    mesh, then the total when some surface has both meshes)."""
    name, command = PEERS[peer]
    head = ("%-30s %7s | %8s %8s | %6s %6s | %6s %6s | %6s %6s | %6s %6s | %5s | %7s %7s | %6s %6s"
            % ("surface", "status", "tets", peer + " tets", "q avg", peer, "q min", peer, "dihmin", peer, "%q<.1", peer,
               "stn", "time s", peer + " s", "tets x", "time x"))
    print("Mesh generation: cbr mesh vs %s (same surfaces, same run; x = cbr / %s)" % (command, name))
    print(head)
    print("-" * len(head))
    out = []
    tot = {"stn": 0, "over": 0, "cbr_t": 0, "p_t": 0, "cbr_s": 0.0, "p_s": 0.0, "cbr_q": 0.0, "p_q": 0.0, "cbr_b": 0.0, "p_b": 0.0,
           "cbr_min": 1.0, "p_min": 1.0, "cbr_dih": 180.0, "p_dih": 180.0, "n": 0}
    for r in rows:
        c, t = r["cbr"] or {}, r[peer] or {}
        status = r["cbr_status"] if r["cbr_status"] != "ok" else (
            "ok" if r[peer + "_status"] == "ok" else peer + " " + (r[peer + "_status"] or "n/a"))
        print("%-30s %7s | %8s %8s | %6s %6s | %6s %6s | %6s %6s | %6s %6s | %5s | %7s %7s | %6s %6s" % (
            r["file"][:30], status, fmt(c.get("tets"), "d"), fmt(t.get("tets"), "d"),
            fmt(c.get("avg"), ".4f"), fmt(t.get("avg"), ".4f"), fmt(c.get("min"), ".4f"), fmt(t.get("min"), ".4f"),
            fmt(c.get("dih"), ".2f"), fmt(t.get("dih"), ".2f"), fmt(c.get("below"), ".3f"), fmt(t.get("below"), ".3f"),
            fmt(c.get("stn"), "d"), fmt(r["cbr_s"], ".3f"), fmt(r[peer + "_s"], ".3f"),
            fmt(ratio(c.get("tets"), t.get("tets")), ".2f"), fmt(ratio(r["cbr_s"], r[peer + "_s"]), ".2f")))
        out.append([r["file"], status, c.get("tets"), t.get("tets"), c.get("avg"), t.get("avg"), c.get("min"), t.get("min"),
                    c.get("dih"), t.get("dih"), c.get("below"), t.get("below"), r["cbr_s"], r[peer + "_s"], c.get("stn")])
        if r["cbr"] and r[peer]:
            tot["n"] += 1
            # No total once a report lacks the count.
            for key in ("stn", "over"):
                tot[key] = None if tot[key] is None or c.get(key) is None else tot[key] + c[key]
            for tool, m, s in (("cbr", c, r["cbr_s"]), ("p", t, r[peer + "_s"])):
                tot[tool + "_t"] += m["tets"]
                tot[tool + "_s"] += s
                tot[tool + "_q"] += m["avg"] * m["tets"]
                tot[tool + "_b"] += m["below"] * m["tets"] / 100.0
                tot[tool + "_min"] = min(tot[tool + "_min"], m["min"])
                tot[tool + "_dih"] = min(tot[tool + "_dih"], m["dih"])
    print("-" * len(head))
    if tot["n"]:
        ct, pt = tot["cbr_t"], tot["p_t"]
        total = ["%stotal (%d both ok)" % ("" if peer == "tg" else "gmsh ", tot["n"]), "", ct, pt, tot["cbr_q"] / ct,
                 tot["p_q"] / pt, tot["cbr_min"], tot["p_min"], tot["cbr_dih"], tot["p_dih"], 100.0 * tot["cbr_b"] / ct,
                 100.0 * tot["p_b"] / pt, tot["cbr_s"], tot["p_s"], tot["stn"]]
        print("%-30s %7s | %8d %8d | %6.4f %6.4f | %6.4f %6.4f | %6.2f %6.2f | %6.3f %6.3f | %5s | %7.3f %7.3f | %6.2f %6.2f" % (
            total[0], "", ct, pt, total[4], total[5], total[6], total[7], total[8], total[9], total[10], total[11],
            fmt(total[14], "d"), total[12], total[13], ct / pt, total[12] / total[13] if total[13] else float("nan")))
        print("(total: q avg and %%q<.1 over all tetrahedra, q min and dihedral min over all meshes; "
              "tetrahedra with q < 0.1: %d cbr, %d %s; stn: cbr's tetrahedra with q < 0.1 touching a Steiner point, "
              "Table II's last row; cbr's tetrahedra left over its size bound: %s)"
              % (round(tot["cbr_b"]), round(tot["p_b"]), name, fmt(tot["over"], "d")))
        out.append(total)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("raw")
    ap.add_argument("--csv")
    args = ap.parse_args()
    rows = []
    with open(args.raw, newline="") as f:
        for r in csv.DictReader(f):
            row = {"file": r["file"], "cbr_status": r["cbr_status"], "tg_status": r["tetgen_status"],
                   "gm_status": r.get("gmsh_status") or None}
            for tool, key in (("cbr", "cbr"), ("tg", "tetgen")):
                row[tool + "_s"] = float(r[key + "_seconds"]) if r[key + "_seconds"] else None
                row[tool] = table_two(r[key + "_node"], r[key + "_ele"]) if r[key + "_status"] == "ok" else None
            row["gm_s"] = float(r["gmsh_seconds"]) if r.get("gmsh_seconds") else None
            row["gm"] = table_two(r["gmsh_mesh"]) if row["gm_status"] == "ok" else None
            if row["cbr"] is not None:
                report = r.get("cbr_json") or ""
                # Table II's "q < 0.1 touching a Steiner point", and the
                # tetrahedra left over the size bound.
                row["cbr"]["stn"] = from_report(report, "table_two", "bad_touching_steiner")
                row["cbr"]["over"] = from_report(report, "refine", "oversize_tets")
            rows.append(row)

    out = peer_table(rows, "tg")
    gmsh_ran = any(r["gm_status"] for r in rows)
    if gmsh_ran:
        print()
        gm = peer_table(rows, "gm")
        # CSV: the gmsh columns after TetGen's, on the same surface rows;
        # the gmsh total as one more row, its TetGen columns empty. A
        # peer_table row is file, status, then (cbr, peer) pairs of tets,
        # q avg, q min, dihedral min, % below 0.1, seconds, then stn.
        peer = slice(3, 14, 2)
        per_mesh = len(rows)
        for i in range(per_mesh):
            out[i] = out[i] + gm[i][peer]
        if len(out) > per_mesh:
            out[per_mesh] = out[per_mesh] + [None] * 6
        if len(gm) > per_mesh:
            g = gm[per_mesh]
            cbr_only = [x if k % 2 == 0 else None for k, x in enumerate(g[2:14], start=2)]
            out.append(g[:2] + cbr_only + [g[14]] + g[peer])
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["surface", "status", "cbr_tets", "tetgen_tets", "cbr_q_avg", "tetgen_q_avg", "cbr_q_min",
                        "tetgen_q_min", "cbr_dihedral_min", "tetgen_dihedral_min", "cbr_pct_below_0_1",
                        "tetgen_pct_below_0_1", "cbr_seconds", "tetgen_seconds", "cbr_bad_at_steiner"]
                       + (["gmsh_tets", "gmsh_q_avg", "gmsh_q_min", "gmsh_dihedral_min", "gmsh_pct_below_0_1",
                           "gmsh_seconds"] if gmsh_ran else []))
            w.writerows(out)


if __name__ == "__main__":
    sys.exit(main())
