#!/usr/bin/env python3
"""Formats the rows that run_recover_bench.sh collected (RAW.csv): prints the
per-mesh table and the totals, and with --csv FILE writes them as CSV.

    recover_bench_table.py RAW.csv [--csv FILE]

Totals are given twice: over every surface (Steiner points summed over the
successful runs only) and over the surfaces both tools succeeded on, which
is the fair comparison of Steiner points and time.
"""
import argparse
import csv
import json
import sys


def num(text, kind=float):
    try:
        return kind(text)
    except (TypeError, ValueError):
        return None


def ratio(a, b):
    return a / b if a is not None and b else None


def fmt_secs(v, digits=3):
    return "-" if v is None else f"{v:.{digits}f}"


def fmt_ratio(v):
    return "-" if v is None else f"{v:.2f}x"


def fmt_int(v):
    return "-" if v is None else str(v)


def first_failure(path):
    """The first failure the checker names in its JSON (or its error)."""
    try:
        with open(path) as f:
            data = json.loads(f.read().strip().splitlines()[-1])
    except (OSError, ValueError, IndexError):
        return "no readable JSON"
    if data.get("error"):
        return str(data["error"])
    failures = data.get("failures") or []
    return str(failures[0]) if failures else "ok is false"


def load(raw_path):
    rows = []
    with open(raw_path, newline="") as f:
        for r in csv.DictReader(f):
            row = {
                "file": r["file"],
                "faces": num(r["faces"], int),
                "points": num(r["points"], int),
                "cbr_status": r["cbr_status"],
                "cbr_exit": r["cbr_exit"],
                "cbr_missing": num(r["cbr_missing"], int),
                "cbr_flips": num(r["cbr_flips"], int),
                "cbr_steiner": num(r["cbr_steiner"], int) if r["cbr_status"] == "ok" else None,
                "cbr_steiner_all": num(r["cbr_steiner_all"], int) if r["cbr_status"] == "ok" else None,
                "cbr_seconds": num(r["cbr_seconds"]),
                "cbr_delaunay_s": num(r["cbr_delaunay_s"]),
                "cbr_recovery_s": num(r["cbr_recovery_s"]),
                "cbr_total_s": num(r["cbr_total_s"]),
                "tetgen_status": r["tetgen_status"] or "n/a",
                "tetgen_exit": r["tetgen_exit"],
                "tetgen_steiner": num(r["tetgen_steiner"], int) if r["tetgen_status"] == "ok" else None,
                "tetgen_seconds": num(r["tetgen_seconds"]),
                "cbr_verify": r["cbr_verify"],
                "tetgen_verify": r["tetgen_verify"],
                "note": r["note"],
            }
            notes = [row["note"]] if row["note"] else []
            for tool in ("cbr", "tetgen"):
                if row[tool + "_verify"] not in ("", "ok"):
                    why = first_failure(r[tool + "_verify_json"]) if r[tool + "_verify_json"] else ""
                    notes.append(f"{tool} output: verification {row[tool + '_verify']}: {why}")
            row["note"] = "; ".join(notes)
            row["ratio"] = ratio(row["cbr_seconds"], row["tetgen_seconds"])
            rows.append(row)
    return rows


def totals(rows, label):
    def total(key, only=None):
        vals = [r[key] for r in rows if r[key] is not None and (only is None or r[only] == "ok")]
        return sum(vals) if vals else None

    n = len(rows)
    cbr_ok = sum(r["cbr_status"] == "ok" for r in rows)
    tg_ok = sum(r["tetgen_status"] == "ok" for r in rows)
    cbr_s, tg_s = total("cbr_seconds"), total("tetgen_seconds")
    verified = [r for r in rows if r["cbr_verify"]]
    tverified = [r for r in rows if r["tetgen_verify"]]
    return {
        "file": label,
        "faces": total("faces"),
        "points": total("points"),
        "cbr_status": f"{cbr_ok}/{n} ok",
        "cbr_exit": "",
        "cbr_missing": total("cbr_missing"),
        "cbr_flips": total("cbr_flips"),
        "cbr_steiner": total("cbr_steiner", "cbr_status"),
        "cbr_steiner_all": total("cbr_steiner_all", "cbr_status"),
        "cbr_seconds": cbr_s,
        "cbr_delaunay_s": total("cbr_delaunay_s"),
        "cbr_recovery_s": total("cbr_recovery_s"),
        "cbr_total_s": total("cbr_total_s"),
        "tetgen_status": f"{tg_ok}/{n} ok",
        "tetgen_exit": "",
        "tetgen_steiner": total("tetgen_steiner", "tetgen_status"),
        "tetgen_seconds": tg_s,
        "ratio": ratio(cbr_s, tg_s),
        "cbr_verify": f"{sum(r['cbr_verify'] == 'ok' for r in verified)}/{len(verified)} ok" if verified else "",
        "tetgen_verify": f"{sum(r['tetgen_verify'] == 'ok' for r in tverified)}/{len(tverified)} ok" if tverified else "",
        "note": "",
        "total": True,
    }


def print_table(rows, sums, verified):
    head = ["surface", "faces", "libcbr", "missing", "by flips", "Steiner", "Steiner (all)", "libcbr s",
            "tetgen", "Steiner", "tetgen s", "libcbr/tetgen"]
    if verified:
        head += ["verify libcbr", "verify tetgen"]
    right = {1, 3, 4, 5, 6, 7, 9, 10, 11}

    def cells(r):
        flips = fmt_int(r["cbr_flips"])
        if r.get("total") and r["cbr_missing"]:
            flips += f" ({100.0 * (r['cbr_flips'] or 0) / r['cbr_missing']:.1f}%)"
        c = [r["file"], fmt_int(r["faces"]), r["cbr_status"], fmt_int(r["cbr_missing"]), flips,
             fmt_int(r["cbr_steiner"]), fmt_int(r["cbr_steiner_all"]),
             fmt_secs(r["cbr_seconds"], 2 if r.get("total") else 3),
             r["tetgen_status"], fmt_int(r["tetgen_steiner"]),
             fmt_secs(r["tetgen_seconds"], 2 if r.get("total") else 3), fmt_ratio(r["ratio"])]
        if verified:
            c += [r["cbr_verify"] or "-", r["tetgen_verify"] or "-"]
        return c

    body = [cells(r) for r in rows]
    foot = [cells(r) for r in sums]
    for c in foot:
        c[0] = f"**{c[0]}**"
    widths = [max(len(x) for x in col) for col in zip(head, *body, *foot)]

    def line(c):
        return "| " + " | ".join(x.rjust(w) if i in right else x.ljust(w)
                                 for i, (x, w) in enumerate(zip(c, widths))) + " |"

    print(line(head))
    print("|" + "|".join(("-" * (w + 1) + ":") if i in right else ("-" * (w + 2))
                         for i, w in enumerate(widths)) + "|")
    for c in body + foot:
        print(line(c))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("raw")
    ap.add_argument("--csv")
    args = ap.parse_args()

    rows = load(args.raw)
    if not rows:
        print("no surface was run", file=sys.stderr)
        return 1
    both = [r for r in rows if r["cbr_status"] == "ok" and r["tetgen_status"] == "ok"]
    sums = [totals(rows, f"total ({len(rows)} surfaces)"), totals(both, f"both ok ({len(both)} surfaces)")]
    verified = any(r["cbr_verify"] or r["tetgen_verify"] for r in rows)

    print_table(rows, sums, verified)
    print()
    print("libcbr: `cbr recover` (ok = every face recovered; FAILED = exit 3; ERROR = any other exit);")
    print("missing = faces missing after Delaunay; by flips = of those, recovered by flips;")
    print("Steiner = Steiner points of the domain mesh: libcbr's inside the domain (used by tetrahedra")
    print("of the bounded regions; steiner_inside of `cbr recover --json`) / output nodes minus input")
    print("points (tetgen -pYQ); Steiner (all) = every Steiner point libcbr keeps, those of the")
    print("exterior (region 0, dropped with it) included (Table I's \"Steiner points remaining\");")
    print("summed over successful runs; times are wall seconds of each whole command.")
    notes = [r for r in rows if r["note"]]
    if notes:
        print()
        print("Notes:")
        for r in notes:
            print(f"  {r['file']}: {r['note']}")

    if args.csv:
        cols = ["file", "faces", "points", "cbr_status", "cbr_exit", "cbr_missing", "cbr_flips", "cbr_steiner",
                "cbr_steiner_all", "cbr_seconds", "cbr_delaunay_s", "cbr_recovery_s", "cbr_total_s", "tetgen_status",
                "tetgen_exit", "tetgen_steiner", "tetgen_seconds", "ratio", "cbr_verify", "tetgen_verify", "note"]
        names = {"cbr_missing": "cbr_missing_after_delaunay", "cbr_flips": "cbr_recovered_by_flips",
                 "cbr_total_s": "cbr_reported_total_s", "ratio": "time_ratio_cbr_over_tetgen"}
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow([names.get(c, c) for c in cols])
            for r in rows + sums:
                out = []
                for c in cols:
                    v = r[c]
                    if v is None:
                        v = ""
                    elif isinstance(v, float):
                        v = f"{v:.4f}" if c == "ratio" else f"{v:.3f}"
                    out.append(v)
                w.writerow(out)
        print(f"\nCSV written to {args.csv}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
