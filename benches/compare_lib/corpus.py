"""The mesh list: every corpus mesh (or the names given), smallest first by the
catalogue's triangle count, so a time-limited run covers as many meshes as it can."""

import csv
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
CORPUS = (ROOT / ".." / "shared" / "datasets" / "corpus").resolve()
CATALOG = CORPUS.parent / "CATALOG.tsv"


def catalog():
    """name -> row of CATALOG.tsv (empty when the catalogue is absent)."""
    try:
        with open(CATALOG, newline="") as fh:
            return {r["name"]: r for r in csv.DictReader(fh, delimiter="\t")}
    except OSError:
        return {}


def mesh_list(names):
    """Paths of the meshes to compare, smallest first. `names` are corpus file
    names or paths; empty means the whole corpus."""
    if not CORPUS.is_dir() and not names:
        print(f"CORPUS ABSENT: {CORPUS} does not exist; name meshes with --meshes", file=sys.stderr)
        sys.exit(2)
    cat = catalog()
    if names:
        paths = [Path(n) if Path(n).exists() else CORPUS / n for n in names]
        missing = [str(p) for p in paths if not p.is_file()]
        if missing:
            print(f"no such mesh: {', '.join(missing)}", file=sys.stderr)
            sys.exit(2)
    else:
        paths = sorted(p for p in CORPUS.iterdir() if p.is_file())

    def size(p):
        row = cat.get(p.name)
        return (int(row["triangles"]) if row else p.stat().st_size // 40, p.name)

    return sorted(paths, key=size)


def faces(path):
    """The catalogue's face count (polygons as in the file), or None."""
    row = catalog().get(Path(path).name)
    return int(row["faces_file"]) if row else None
