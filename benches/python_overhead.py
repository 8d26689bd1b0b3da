#!/usr/bin/env python3
"""What calling primdecomp from Python costs over the CLI: the same mesh
and target through `primdecomp decompose IN -n N -o OUT.json`, through
`primdecomp.decompose_file(IN, targets=[N]).export(OUT.json)` and through
`primdecomp.decompose(*primdecomp.load(IN), targets=[N]).export(OUT.json)`, each a
fresh process (interpreter start and imports included, as the CLI's start is),
alternating, several rounds; wall-clock medians and ratios to the CLI. The three
outputs' primitives are checked to be byte-identical.

    nice python3 benches/python_overhead.py --python .venv-py/bin/python \\
        --mesh ../shared/datasets/corpus/dragon_vrip_full.ply -n 2000 --rounds 3
"""

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

PY_FILE = """import sys, primdecomp
primdecomp.decompose_file(sys.argv[1], targets=[int(sys.argv[2])]).export(sys.argv[3])"""
PY_ARRAYS = """import sys, primdecomp
v, f = primdecomp.load(sys.argv[1])
primdecomp.decompose(v, f, targets=[int(sys.argv[2])]).export(sys.argv[3])"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--python", default=str(ROOT / ".venv-py" / "bin" / "python"))
    ap.add_argument("--cli", default=str(ROOT / "target" / "release" / "primdecomp"))
    ap.add_argument("--mesh", default=str(ROOT.parent / "shared" / "datasets" / "corpus" / "dragon_vrip_full.ply"))
    ap.add_argument("-n", type=int, default=2000)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    out = Path(tempfile.mkdtemp(prefix="pyoverhead-"))
    variants = {
        "CLI": lambda o: [a.cli, "decompose", a.mesh, "-n", str(a.n), "-o", o],
        "decompose_file": lambda o: [a.python, "-c", PY_FILE, a.mesh, str(a.n), o],
        "decompose(*load())": lambda o: [a.python, "-c", PY_ARRAYS, a.mesh, str(a.n), o],
    }
    times = {k: [] for k in variants}
    for r in range(a.rounds):
        for k, cmd in variants.items():
            o = str(out / f"{len(times[k])}_{k.replace('(', '').replace(')', '').replace('*', '')}.json")
            t0 = time.perf_counter()
            subprocess.run(cmd(o), check=True, capture_output=True)
            times[k].append(time.perf_counter() - t0)
            print(f"round {r + 1} {k}: {times[k][-1]:.2f} s", file=sys.stderr, flush=True)
    prims = {k: json.dumps(json.loads(next(out.glob(f"0_{k.replace('(', '').replace(')', '').replace('*', '')}.json")).read_text())["primitives"]) for k in variants}
    same = len(set(prims.values())) == 1
    cli = statistics.median(times["CLI"])
    print(f"mesh {a.mesh}, -n {a.n}, {a.rounds} rounds, alternating\n")
    print("| variant | runs (s) | median (s) | vs CLI |")
    print("|---|---|---|---|")
    for k, ts in times.items():
        m = statistics.median(ts)
        print(f"| {k} | {', '.join(f'{t:.2f}' for t in ts)} | {m:.2f} | {m / cli - 1:+.1%} |")
    print(f"\nprimitives byte-identical across the three: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    raise SystemExit(main())
