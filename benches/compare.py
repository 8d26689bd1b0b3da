"""benches/compare: primdecomp against CoACD and V-HACD on a list of meshes.

Runs the peers (cached under benches/.cache by mesh sha256 + settings, one
thread each, per-run timeout), primdecomp (release binary, one multi-target
pass per mesh), evaluates every collider with `primdecomp eval`, and writes
docs/results/compare.md with PNG plots beside it. `--ours-mode cut` evaluates
our engine a second way, the merge-tree cut of `--max-bytes` at a third of
CoACD's bytes beside the byte rule's level, into docs/results/compare_cut.md
(no pictures). `--sweep` runs our engine over
targets and excess-volume caps on a few meshes and writes
docs/results/tradeoff.md instead. See `benches/compare --help`.
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from compare_lib import corpus, peers  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
CACHE = ROOT / "benches" / ".cache"


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="benches/compare", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshes", nargs="*", default=[], help="corpus file names or paths (default: the whole corpus, smallest first)")
    ap.add_argument("--methods", default=",".join(peers.METHODS), help="peer methods to run (default: %(default)s)")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per peer run and per primdecomp run (default: %(default)s)")
    ap.add_argument("--threads", type=int, default=1, help="threads per peer run (OMP_NUM_THREADS) (default: %(default)s)")
    ap.add_argument("--peers-only", action="store_true", help="only fill the peer cache")
    ap.add_argument("--cached-only", action="store_true", help="never start a peer; a peer result missing from the cache is listed as not run")
    ap.add_argument("--samples", type=int, default=None, help="samples per surface for primdecomp eval (default: eval's own)")
    ap.add_argument("--refresh-sim", action="store_true",
                    help="only replace the simulation section of OUT/compare.md and the `sim` fields of OUT/compare.json "
                         "with the current SIM summaries (after `python3 benches/sim_compare.py`); every other figure "
                         "stays from the run named at the top of the report")
    ap.add_argument("--thumbs-only", action="store_true",
                    help="only draw the pictures (input, ours, CoACD, V-HACD per mesh; `primdecomp view --png`) into "
                         "OUT/thumbs and replace the pictures section of OUT/compare.md: ours decomposed again at the "
                         "report's target, peers' hulls from the cache where present (none is run); --meshes limits it")
    ap.add_argument("--ours-mode", choices=["level", "cut"], default="level",
                    help="level (default): our row is the level of one multi-target pass chosen by the byte rule; cut: our "
                         "row is `decompose --max-bytes B` (the merge-tree cut of least worst distance that fits B = one "
                         "third of CoACD's bytes, -n capped at the byte rule's top count), with the byte rule's level as a "
                         "second row, into OUT/compare_cut.md unless --report-name says otherwise")
    ap.add_argument("--report-name", default=None,
                    help="stem of the report's files: OUT/NAME.md, OUT/NAME.json and the plots OUT/NAME_*.png (default: compare, "
                         "with --ours-mode cut compare_cut); --ours-mode cut draws no pictures (OUT/thumbs belongs to compare.md)")
    ap.add_argument("--note", default="", help="with --ours-mode cut: a line for the report's header (e.g. where the peer cache came from)")
    ap.add_argument("--sweep", action="store_true", help="the speed/accuracy sweep of our engine -> docs/results/tradeoff.md")
    ap.add_argument("--out", default=str(ROOT / "docs" / "results"), help="report directory (default: %(default)s)")
    ap.add_argument("--sim", default=str(CACHE / "sim" / "summary"), help="directory of simulation results, SIM/<mesh file name>.json = {method: {metric: value}}, as benches/sim_compare.py writes them (default: %(default)s)")
    ap.add_argument("--cache", default=str(CACHE), help="peer cache and work directory (default: %(default)s)")
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "primdecomp"), help="primdecomp binary (default: %(default)s)")
    return ap.parse_args(argv)


def fill_peer_cache(a, meshes, methods):
    python = sys.executable
    for m in meshes:
        for method in methods:
            peers.run_peer(python, m, method, Path(a.cache), a.timeout, a.threads)


def main(argv):
    a = parse_args(argv)
    if a.report_name is None:
        a.report_name = "compare_cut" if a.ours_mode == "cut" else "compare"
    methods = [m for m in a.methods.split(",") if m]
    bad = [m for m in methods if m not in peers.METHODS]
    if bad:
        print(f"unknown method(s) {bad}; expected some of {peers.METHODS}", file=sys.stderr)
        return 2
    methods = [m for m in peers.METHODS if m in methods]  # display order: CoACD, paper settings, V-HACD
    meshes = corpus.mesh_list(a.meshes)
    if a.peers_only:
        fill_peer_cache(a, meshes, methods)
        return 0
    if a.refresh_sim:
        from compare_lib import report

        return report.refresh_sim(a)
    if a.thumbs_only:
        from compare_lib import report

        return report.refresh_thumbs(a, Path(a.cache))
    if a.sweep:
        from compare_lib import sweep

        return sweep.main(a, meshes)
    from compare_lib import report

    return report.main(a, meshes, methods, Path(a.cache))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
