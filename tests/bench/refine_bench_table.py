#!/usr/bin/env python3
"""Measures and formats what run_refine_bench.sh collected (RAW.csv): reads
each successful run's TetGen-format mesh (.node/.ele, both tools), computes
Table II with the formulas of src/cli/quality.hpp (q = 3 r_in / r_circ after
scaling to unit longest edge; dihedral angles by atan2), takes libcbr's
"q < 0.1 touching a Steiner point" from its --json report (column stn;
TetGen's output does not tell its Steiner points from its other points),
prints the per-mesh table and the totals (over the surfaces both tools
meshed), and with --csv FILE writes them as CSV.

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


def table_two(node_path, ele_path):
    xyz, tets = read_mesh(node_path, ele_path)
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


def bad_at_steiner(json_path):
    """Table II's "q < 0.1 touching a Steiner point" from cbr's --json
    report, or None when there is none."""
    try:
        with open(json_path) as f:
            return json.load(f)["table_two"]["bad_touching_steiner"]
    except (OSError, ValueError, KeyError, TypeError):
        return None


def fmt(v, spec):
    return "-" if v is None else format(v, spec)


def ratio(a, b):
    return a / b if a is not None and b else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("raw")
    ap.add_argument("--csv")
    args = ap.parse_args()
    rows = []
    with open(args.raw, newline="") as f:
        for r in csv.DictReader(f):
            row = {"file": r["file"], "cbr_status": r["cbr_status"], "tg_status": r["tetgen_status"]}
            for tool, key in (("cbr", "cbr"), ("tg", "tetgen")):
                row[tool + "_s"] = float(r[key + "_seconds"]) if r[key + "_seconds"] else None
                row[tool] = table_two(r[key + "_node"], r[key + "_ele"]) if r[key + "_status"] == "ok" else None
            if row["cbr"] is not None:
                row["cbr"]["stn"] = bad_at_steiner(r.get("cbr_json") or "")
            rows.append(row)

    head = ("%-30s %7s | %8s %8s | %6s %6s | %6s %6s | %6s %6s | %6s %6s | %5s | %7s %7s | %6s %6s"
            % ("surface", "status", "tets", "tg tets", "q avg", "tg", "q min", "tg", "dihmin", "tg",
               "%q<.1", "tg", "stn", "time s", "tg s", "tets x", "time x"))
    print("Mesh generation: cbr mesh vs tetgen -pYq1.414 (same surfaces, same run; x = cbr / tetgen)")
    print(head)
    print("-" * len(head))
    out = []
    tot = {"stn": 0, "cbr_t": 0, "tg_t": 0, "cbr_s": 0.0, "tg_s": 0.0, "cbr_q": 0.0, "tg_q": 0.0, "cbr_b": 0.0, "tg_b": 0.0,
           "cbr_min": 1.0, "tg_min": 1.0, "cbr_dih": 180.0, "tg_dih": 180.0, "n": 0}
    for r in rows:
        c, t = r["cbr"] or {}, r["tg"] or {}
        status = r["cbr_status"] if r["cbr_status"] != "ok" else ("ok" if r["tg_status"] == "ok" else "tg " + r["tg_status"])
        print("%-30s %7s | %8s %8s | %6s %6s | %6s %6s | %6s %6s | %6s %6s | %5s | %7s %7s | %6s %6s" % (
            r["file"][:30], status, fmt(c.get("tets"), "d"), fmt(t.get("tets"), "d"),
            fmt(c.get("avg"), ".4f"), fmt(t.get("avg"), ".4f"), fmt(c.get("min"), ".4f"), fmt(t.get("min"), ".4f"),
            fmt(c.get("dih"), ".2f"), fmt(t.get("dih"), ".2f"), fmt(c.get("below"), ".3f"), fmt(t.get("below"), ".3f"),
            fmt(c.get("stn"), "d"), fmt(r["cbr_s"], ".3f"), fmt(r["tg_s"], ".3f"),
            fmt(ratio(c.get("tets"), t.get("tets")), ".2f"), fmt(ratio(r["cbr_s"], r["tg_s"]), ".2f")))
        out.append([r["file"], status, c.get("tets"), t.get("tets"), c.get("avg"), t.get("avg"), c.get("min"), t.get("min"),
                    c.get("dih"), t.get("dih"), c.get("below"), t.get("below"), r["cbr_s"], r["tg_s"], c.get("stn")])
        if r["cbr"] and r["tg"]:
            tot["n"] += 1
            # No total once a report lacks the count.
            tot["stn"] = None if tot["stn"] is None or c.get("stn") is None else tot["stn"] + c["stn"]
            for tool, m, s in (("cbr", c, r["cbr_s"]), ("tg", t, r["tg_s"])):
                tot[tool + "_t"] += m["tets"]
                tot[tool + "_s"] += s
                tot[tool + "_q"] += m["avg"] * m["tets"]
                tot[tool + "_b"] += m["below"] * m["tets"] / 100.0
                tot[tool + "_min"] = min(tot[tool + "_min"], m["min"])
                tot[tool + "_dih"] = min(tot[tool + "_dih"], m["dih"])
    print("-" * len(head))
    if tot["n"]:
        ct, tt = tot["cbr_t"], tot["tg_t"]
        total = ["total (%d both ok)" % tot["n"], "", ct, tt, tot["cbr_q"] / ct, tot["tg_q"] / tt, tot["cbr_min"], tot["tg_min"],
                 tot["cbr_dih"], tot["tg_dih"], 100.0 * tot["cbr_b"] / ct, 100.0 * tot["tg_b"] / tt, tot["cbr_s"], tot["tg_s"],
                 tot["stn"]]
        print("%-30s %7s | %8d %8d | %6.4f %6.4f | %6.4f %6.4f | %6.2f %6.2f | %6.3f %6.3f | %5s | %7.3f %7.3f | %6.2f %6.2f" % (
            total[0], "", ct, tt, total[4], total[5], total[6], total[7], total[8], total[9], total[10], total[11],
            fmt(total[14], "d"), total[12], total[13], ct / tt, total[12] / total[13] if total[13] else float("nan")))
        print("(total: q avg and %%q<.1 over all tetrahedra, q min and dihedral min over all meshes; "
              "tetrahedra with q < 0.1: %d cbr, %d tetgen; stn: cbr's tetrahedra with q < 0.1 touching a Steiner point, "
              "Table II's last row)" % (round(tot["cbr_b"]), round(tot["tg_b"])))
        out.append(total)
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["surface", "status", "cbr_tets", "tetgen_tets", "cbr_q_avg", "tetgen_q_avg", "cbr_q_min",
                        "tetgen_q_min", "cbr_dihedral_min", "tetgen_dihedral_min", "cbr_pct_below_0_1",
                        "tetgen_pct_below_0_1", "cbr_seconds", "tetgen_seconds", "cbr_bad_at_steiner"])
            w.writerows(out)


if __name__ == "__main__":
    sys.exit(main())
