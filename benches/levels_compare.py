#!/usr/bin/env python3
"""benches/levels_compare.py OLD NEW: two folders of level files written by
`primdecomp decompose MESH --tolerance T1,T2,… -o FOLDER/MESH.json` (one
`MESH_tLABEL.json` per level, as benches/tolerance_check.sh writes them), compared by
each level's `stats`: how many are within their tolerance (the declared distance,
docs/decisions/0040), what stopped the others (`limited_by`), and the levels whose
primitives, bytes or declared distance changed, as a markdown table. Levels in only
one folder are skipped. No sampling: `eval` is tolerance_check.sh's part."""
import json
import re
import sys
from pathlib import Path


def levels(folder):
    out = {}
    for p in sorted(Path(folder).glob("*_t*.json")):
        m = re.fullmatch(r"(.+)_(t[^_]+)\.json", p.name)
        if m and not p.name.endswith(".eval.json"):
            s = json.loads(p.read_text())["stats"]
            d = s["distance"]
            out[(m.group(1), m.group(2))] = dict(
                n=s["primitives"], bytes=s["bytes"], dist=d["of_diagonal"],
                within=d["worst"] <= d["tolerance"], by=d.get("limited_by"))
    return out


def main(old, new):
    a, b = levels(old), levels(new)
    keys = [k for k in a if k in b]
    labels = sorted({k[1] for k in keys}, key=lambda t: -float(t[1:].replace("pct", "")))
    rows = []
    for lab in labels:
        ks = [k for k in keys if k[1] == lab]
        within = (sum(a[k]["within"] for k in ks), sum(b[k]["within"] for k in ks))
        by = ({}, {})
        for k in ks:
            for side, lv in zip(by, (a[k], b[k])):
                side[str(lv["by"])] = side.get(str(lv["by"]), 0) + 1
        moved = [k for k in ks if (a[k]["n"], a[k]["bytes"], a[k]["dist"]) != (b[k]["n"], b[k]["bytes"], b[k]["dist"])]
        nearer = sum(b[k]["dist"] < a[k]["dist"] for k in moved)
        farther = sum(b[k]["dist"] > a[k]["dist"] for k in moved)
        print(f"- {lab}: {len(ks)} levels, within {within[0]} → {within[1]}; changed {len(moved)} "
              f"(nearer {nearer}, farther {farther}, same distance {len(moved) - nearer - farther}); "
              f"stopped by {by[0]} → {by[1]}")
        rows += moved
    print("\n| mesh | level | primitives | bytes | declared distance (of the diagonal) | limited by |")
    print("|---|---|---|---|---|---|")
    for k in rows:
        x, y = a[k], b[k]
        print(f"| {k[0]} | {k[1]} | {x['n']} → {y['n']} | {x['bytes']} → {y['bytes']} | "
              f"{100 * x['dist']:.2f}% → {100 * y['dist']:.2f}% | {x['by']} → {y['by']} |")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: benches/levels_compare.py OLD NEW")
    main(sys.argv[1], sys.argv[2])
