#!/usr/bin/env python3
"""Summary of benches/ab_quality.sh's OUTDIR: A -> B per metric over the meshes, and
with --list every mesh whose primitives differ."""
import glob, json, os, statistics as st, sys

d = sys.argv[1]
rows = []
for f in sorted(glob.glob(f"{d}/*.eval.json")):
    m = os.path.basename(f)[: -len(".eval.json")]
    a, b = json.load(open(f))["colliders"][:2]
    same = json.load(open(f"{d}/{m}.a.json"))["primitives"] == json.load(open(f"{d}/{m}.b.json"))["primitives"]
    rows.append((m, a, b, same))
print(f"{len(rows)} meshes; {sum(r[3] for r in rows)} with identical primitives")
for key in ["hausdorff", "chamfer", "reverse_chamfer", "enclosure"]:
    a = [r[1][key] for r in rows]
    b = [r[2][key] for r in rows]
    better = sum(y < x * 0.98 for x, y in zip(a, b))
    worse = sum(y > x * 1.02 for x, y in zip(a, b))
    print(f"{key}: mean {st.mean(a):.4g} -> {st.mean(b):.4g}, median {st.median(a):.4g} -> "
          f"{st.median(b):.4g}; B better by >2% on {better}, worse on {worse}")
if "--list" in sys.argv:
    for m, x, y, same in rows:
        if not same:
            print(f"  {m}: hausdorff {x['hausdorff']:.4f} -> {y['hausdorff']:.4f}, "
                  f"chamfer {x['chamfer']:.3e} -> {y['chamfer']:.3e}")
