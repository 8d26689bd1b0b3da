#!/usr/bin/env python3
"""Summary of benches/corpus_sweep.sh OUT NAME...: each config against the first, over
the meshes every config has results for. `--list` also prints each mesh whose
primitives differ from the first config's."""
import json
import os
import statistics as st
import sys

SLOW = ("samurai_monastery", "japanese_maple_tree", "engine_2cylinder", "happy_buddha_100k",
        "lucy_100k", "armadillo_libigl", "tank")


def load(out, name):
    rows = {}
    d = f"{out}/{name}"
    for f in sorted(os.listdir(d)):
        if not f.endswith(".json.eval.json"):
            continue
        m = f[: -len(".json.eval.json")]
        ev = json.load(open(f"{d}/{f}"))["colliders"][0]
        prims = json.load(open(f"{d}/{m}.json"))["primitives"]
        user = float(open(f"{d}/{m}.json.user").read().split()[-1])
        rows[m] = dict(ev, prims=prims, user=user)
    return rows


def main(argv):
    out, names = argv[1], [a for a in argv[2:] if a != "--list"]
    data = {n: load(out, n) for n in names}
    base = data[names[0]]
    meshes = sorted(set.intersection(*(set(d) for d in data.values())))
    print(f"{len(meshes)} meshes with results for every config; against '{names[0]}':")
    for n in names:
        d = data[n]
        same = sum(d[m]["prims"] == base[m]["prims"] for m in meshes)
        parts = [f"{n}: identical primitives on {same}"]
        for key in ["hausdorff", "chamfer", "reverse_chamfer"]:
            v = [d[m][key] for m in meshes]
            better = sum(d[m][key] < base[m][key] * 0.98 for m in meshes)
            worse = sum(d[m][key] > base[m][key] * 1.02 for m in meshes)
            parts.append(f"{key} mean {st.mean(v):.4g} median {st.median(v):.4g} "
                         f"(better/worse by >2%: {better}/{worse})")
        parts.append(f"least enclosure {min(d[m]['enclosure'] for m in meshes):.6f}")
        slow = [m for m in meshes if m.startswith(SLOW)]
        ratio = lambda ms: sum(d[m]["user"] for m in ms) / max(sum(base[m]["user"] for m in ms), 1e-9)  # noqa: E731
        parts.append(f"user x{ratio(meshes):.3f}, slowest seven x{ratio(slow):.3f}")
        print("; ".join(parts))
        if "--list" in argv and n != names[0]:
            for m in meshes:
                if d[m]["prims"] != base[m]["prims"]:
                    print(f"  {m}: hausdorff {base[m]['hausdorff']:.4f} -> {d[m]['hausdorff']:.4f}, "
                          f"chamfer {base[m]['chamfer']:.3e} -> {d[m]['chamfer']:.3e}")


if __name__ == "__main__":
    main(sys.argv)
