#!/usr/bin/env python3
"""Compares two output folders of benches/tolerance_check.sh run with TOLS="2%,1%,0.3%"
on the same meshes (OLD then NEW): per tolerance the median and mean primitive counts,
eval's Hausdorff and Chamfer, and how many levels grew or shrank; then the decompose
user seconds summed and per mesh. Usage: benches/tolerance_compare.py OLD NEW"""
import json, glob, os, statistics as st, sys
old, new = sys.argv[1], sys.argv[2]
tols = [("2%","t2pct"),("1%","t1pct"),("0.3%","t0.3pct")]
meshes = sorted(os.path.basename(p)[:-5] for p in glob.glob(f"{new}/*.user"))
print("| tolerance | median prims old → new | mean prims old → new | median eval H old → new | mean eval H old → new | median Chamfer old → new | levels with more prims / fewer / same |")
print("|---|---|---|---|---|---|---|")
for tol, lab in tols:
    rows=[]
    for m in meshes:
        r=[]
        for d in (old,new):
            lv=json.load(open(f"{d}/{m}_{lab}.json")); e=json.load(open(f"{d}/{m}_{lab}.json.eval.json"))["colliders"][0]
            r.append((lv["stats"]["primitives"], e["hausdorff"], e["chamfer"]))
        rows.append(r)
    f=lambda i,k: [r[i][k] for r in rows]
    more=sum(r[1][0]>r[0][0] for r in rows); fewer=sum(r[1][0]<r[0][0] for r in rows)
    print(f"| {tol} | {st.median(f(0,0))} → {st.median(f(1,0))} | {st.mean(f(0,0)):.1f} → {st.mean(f(1,0)):.1f} | {st.median(f(0,1)):.4f} → {st.median(f(1,1)):.4f} | {st.mean(f(0,1)):.4f} → {st.mean(f(1,1)):.4f} | {st.median(f(0,2)):.2e} → {st.median(f(1,2)):.2e} | {more} / {fewer} / {len(rows)-more-fewer} |")
uo=[float(open(f"{old}/{m}.user").read().split()[-1]) for m in meshes]
un=[float(open(f"{new}/{m}.user").read().split()[-1]) for m in meshes]
rat=[b/a for a,b in zip(uo,un) if a>=0.3]
print(f"\ndecompose user s (one pass, three levels), summed over {len(meshes)} meshes: {sum(uo):.1f} → {sum(un):.1f} ({sum(un)/sum(uo):.2f}×); per mesh (those ≥ 0.3 s before, {len(rat)}): median {st.median(rat):.2f}×, range {min(rat):.2f}–{max(rat):.2f}×")
