"""One scan across a Ray cluster of two nodes (scripts/test.sh's `ray cluster`
section starts them on this machine with `ray start --head` and `ray start
--address`, one CPU each): primdecomp.ray_tiles.decompose on a binary PLY in K tiles
must give the CLI's `primdecomp decompose INPUT --tiles K` file byte for byte, with
tasks on both nodes; a rerun with the cache present runs no tile; a cached tile
altered on disk is caught and run again, the result unchanged. Exits 1 on any
failure, printing what differed.

    python ray_cluster.py --address 127.0.0.1:PORT --cli primdecomp --input scan.ply --work DIR
"""

import argparse
import subprocess
import sys
import time
from pathlib import Path

import ray

import primdecomp
import primdecomp.ray_tiles
from primdecomp import _native


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--address", required=True)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--tiles", type=int, default=4)
    a = ap.parse_args()
    work = Path(a.work)
    failures = []

    def check(ok, what):
        print(("ok      " if ok else "FAILED  ") + what, flush=True)
        if not ok:
            failures.append(what)

    t0 = time.perf_counter()
    want_file = work / "cli.json"
    subprocess.run([a.cli, "decompose", a.input, "--tiles", str(a.tiles), "-n", "60", "-o", want_file, "-q"],
                   check=True)
    want = want_file.read_bytes()
    cli_s = time.perf_counter() - t0

    ray.init(address=a.address, log_to_driver=False)
    try:
        nodes = [n for n in ray.nodes() if n["Alive"]]
        check(len(nodes) == 2, f"the cluster has 2 live nodes ({len(nodes)}), one CPU each "
              f"({sorted(n['Resources'].get('CPU', 0) for n in nodes)})")
        cache = work / "cache"
        t0 = time.perf_counter()
        res = primdecomp.ray_tiles.decompose(a.input, a.tiles, cache_dir=cache, targets=[60])
        first_s = time.perf_counter() - t0
        r = res.tile_report
        check(res.to_json().encode() == want, f"the result equals the CLI's --tiles {a.tiles} file byte for byte "
              f"({len(want)} bytes, {len(res.levels[0].primitives)} primitives)")
        check(r["ran"] == list(range(a.tiles)) and r["reused"] == [], f"first run: ran tiles {r['ran']}")
        ran_on = {}
        for t, node in r["nodes"].items():
            ran_on.setdefault(node, []).append(t)
        check(len(ran_on) == 2, "tasks ran on both nodes: " +
              "; ".join(f"node {n[:12]}… tiles {sorted(ts)}" for n, ts in ran_on.items()))

        t0 = time.perf_counter()
        again = primdecomp.ray_tiles.decompose(a.input, a.tiles, cache_dir=cache, targets=[60])
        again_s = time.perf_counter() - t0
        r = again.tile_report
        check(r["ran"] == [] and r["reused"] == list(range(a.tiles)),
              f"rerun with the cache: ran {len(r['ran'])} tiles, reused {len(r['reused'])}")
        check(again.to_json().encode() == want, "the resumed result is the same bytes")

        plan = _native.tiles_plan(a.input, primdecomp._settings({"targets": [60]}), a.tiles)
        bad = primdecomp.ray_tiles.tile_file(cache, plan, 2)
        data = bytearray(bad.read_bytes())
        data[len(data) // 2] ^= 0x40
        bad.write_bytes(bytes(data))
        third = primdecomp.ray_tiles.decompose(a.input, a.tiles, cache_dir=cache, targets=[60])
        r = third.tile_report
        check(r["ran"] == [2] and 2 in r["rejected"],
              f"a corrupted cached tile is caught and run again: ran {r['ran']}, "
              f"rejected {r['rejected'].get(2, '-')}")
        check(third.to_json().encode() == want, "and the result is the same bytes")
    finally:
        ray.shutdown()
    print(f"times: CLI --tiles {a.tiles} {cli_s:.2f} s; on the cluster {first_s:.2f} s "
          f"(plan, {a.tiles} tasks, merge); resumed {again_s:.2f} s", flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
