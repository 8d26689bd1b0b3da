#!/usr/bin/env python3
"""benches/sim_view.py: where the balls of a `primdecomp sim` run end, drawn over the
geometry they ended on: one column per run (the mesh, the perturbed mesh, then each
collider in the order given to `primdecomp sim`), top view above, side view below,
balls coloured by height. This is how docs/decisions/sim-gaps-and-the-byte-rule.md ("Where our gaps
were") found roof rims closed into lids.

Usage (y up, as `primdecomp sim`'s default; the peers' Python has trimesh and
matplotlib):
  primdecomp decompose MESH -n N -o ours.json --obj ours.obj
  primdecomp sim --input MESH ours.json peer_hulls.obj --csv DIR
  "$(benches/peers/venv.sh)" benches/sim_view.py MESH DIR/<mesh stem>_ends.csv OUT.png \\
      ours.obj peer_hulls.obj
The OBJ files are the colliders' tessellations, one per collider, in the same order.
"""

import collections
import csv
import sys

import matplotlib
import numpy as np
import trimesh

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def obj_faces(path):
    """Polygons of an OBJ file as arrays of 3D points."""
    verts, faces = [], []
    with open(path, errors="replace") as f:
        for line in f:
            t = line.split()
            if t and t[0] == "v":
                verts.append([float(x) for x in t[1:4]])
            elif t and t[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in t[1:]])
    verts = np.array(verts)
    return [verts[f] for f in faces]


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    mesh_path, ends_path, out, *objs = argv
    mesh = trimesh.load(mesh_path, force="mesh")
    ends = collections.OrderedDict()
    with open(ends_path) as f:
        for r in csv.DictReader(f):
            ends.setdefault(r["collider"], []).append([float(r[k]) for k in "xyz"])
    names = list(ends)
    own = list(mesh.vertices[mesh.faces])
    geometry = [own, own] + [obj_faces(o) for o in objs]
    if len(geometry) < len(names):
        print(f"{len(names) - 2} colliders in {ends_path} but {len(objs)} OBJ files", file=sys.stderr)
        return 2
    lo, hi = mesh.bounds
    pad = 0.1 * float(np.max(hi - lo))
    fig, ax = plt.subplots(2, len(names), figsize=(4.5 * len(names), 9), squeeze=False)
    for j, name in enumerate(names):
        e = np.array(ends[name])
        for i, (a, b) in enumerate([(0, 2), (0, 1)]):  # top: x-z, side: x-y
            axis = ax[i, j]
            polys = [p[:, [a, b]] for p in geometry[j]]
            axis.add_collection(PolyCollection(polys, facecolor=(0.5, 0.5, 0.9, 0.08),
                                               edgecolor=(0, 0, 0.6, 0.4), lw=0.4))
            axis.scatter(e[:, a], e[:, b], s=1, c=e[:, 1], cmap="viridis")
            axis.set_xlim(lo[a] - pad, hi[a] + pad)
            axis.set_ylim(lo[b] - pad, hi[b] + (pad if i == 0 else 4 * pad))
            axis.set_aspect("equal")
            axis.set_title(name[-48:] if i == 0 else "side (x, y)", fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
