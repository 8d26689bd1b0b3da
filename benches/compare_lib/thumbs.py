"""Pictures for docs/results/compare.md, as the paper's figures: per mesh a row of
thumbnails, the input, ours and each peer's hulls, each drawn over the input by
`primdecomp view --png` (the viewer page's default three-quarter view, rendered in
software; grey shows where the input pokes out of a collider)."""

import subprocess
from pathlib import Path

# Columns of the row: the input alone, then the colliders over it.
COLUMNS = ["input", "ours", "coacd", "vhacd"]
SIZE = 256
DIR = "thumbs"


def name(mesh, column):
    return f"{Path(mesh).stem}_{column}.png"


def render(binary, mesh, colliders, out_dir, timeout):
    """Renders the row of `mesh` into `out_dir`; `colliders` maps a column (ours,
    coacd, vhacd) to its file (our JSON, a peer's hulls OBJ). Returns {column: file
    name} for the thumbnails drawn and {column: error} for those that failed."""
    out_dir.mkdir(parents=True, exist_ok=True)
    drawn, failed = {}, {}
    for col in COLUMNS:
        if col == "input":
            what = []
        elif col == "ours" and col in colliders:
            what = [str(colliders[col])]
        elif col in colliders:
            what = ["--compare", str(colliders[col])]
        else:
            continue
        dest = out_dir / name(mesh, col)
        cmd = [str(binary), "view", *what, "--input", str(mesh), "--png", str(dest), "--png-size", str(SIZE)]
        try:
            p = subprocess.run(cmd, capture_output=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            failed[col] = f"no picture within {timeout} s"
            continue
        if p.returncode != 0:
            failed[col] = (p.stderr.decode(errors="replace").strip().splitlines() or ["(no message)"])[-1][:300]
            continue
        drawn[col] = dest.name
    return drawn, failed
