"""One scan across a Ray cluster: a mesh too large for one machine decomposed as
spatial tiles, each tile a Ray task, the tiles' results merged on the driver.

    import ray, primdecomp.ray_tiles
    ray.init(address="auto")           # or RAY_ADDRESS=...; without Ray: local
    res = primdecomp.ray_tiles.decompose("/data/scan.ply", tiles=16,
                                         cache_dir="/data/scan.tiles", targets=[2000])
    res.export("scan.primdecomp.json")

The result is the CLI's `primdecomp decompose PATH --tiles K` with the same settings,
byte for byte in `to_json()`: the driver plans (one pass over the file), each tile runs
as a task of one CPU (`num_cpus=1`, spread over the nodes), and the driver merges.

**The input must be readable at the same path on every node** (a shared file system,
or the same file copied to the same path): a task reads only its tile's part of a
binary PLY from the memory map, where shipping the file through Ray's object store
would copy the whole scan to every node. Each task checks the file's size and
content hash against the plan and refuses another file. Tile results (the tiles'
boxes: kilobytes to a few megabytes) come back to the driver through Ray, so only the
driver needs `cache_dir`.

**Resumable per tile:** with `cache_dir`, each tile's result is written, as soon as it
arrives, to CACHE_DIR/PLAN/tile-NNNNN.bin (a temporary file renamed into place), PLAN
being the hash of the plan's bytes (the input's size and content hash, the settings,
the tile count). A rerun reuses the cached results that check out (magic, version,
checksum, this plan, this tile) and runs the others; a cached file that does not
check out is run again and replaced.
"""

import hashlib as _hashlib
import os as _os
from pathlib import Path as _Path

from . import _native
from . import Result, _path, _progress, _settings
from .batch import _ray_or_none, _ray_results

__all__ = ["decompose", "tile_file"]


def tile_file(cache_dir, plan, tile):
    """Where tile `tile`'s result of the plan (its bytes) is cached."""
    key = _hashlib.sha256(plan).hexdigest()[:32]
    return _Path(cache_dir) / key / f"tile-{tile:05d}.bin"


def _run_tile(path, plan, tile):
    """A Ray task: tile `tile`'s result bytes, and the id of the node that ran it."""
    import ray

    return _native.tiles_run(path, plan, tile), ray.get_runtime_context().get_node_id()


def _write_atomic(file, data):
    file.parent.mkdir(parents=True, exist_ok=True)
    tmp = file.with_name(f".{file.name}.tmp{_os.getpid()}")
    try:
        with open(tmp, "wb") as f:
            f.write(data)
            f.flush()
            _os.fsync(f.fileno())
        _os.replace(tmp, file)
    finally:
        if tmp.exists():
            tmp.unlink()


def _cached(cache_dir, plan, count, report):
    """The cached results that check out, by tile; the others are reported."""
    found = {}
    if cache_dir is None:
        return found
    for t in range(count):
        file = tile_file(cache_dir, plan, t)
        try:
            data = file.read_bytes()
        except FileNotFoundError:
            continue
        try:
            _native.tiles_check(plan, t, data)
        except ValueError as e:
            report["rejected"][t] = f"{file}: {e}"
            continue
        found[t] = data
    return found


def decompose(path, tiles, cache_dir=None, *, use_ray=None, progress=None, **settings):
    """Decompose the mesh in `path` as `tiles` spatial tiles, each a Ray task; returns
    a `primdecomp.Result` equal to `primdecomp decompose PATH --tiles TILES` with the
    same settings (`targets`, `tolerance`, … as for `primdecomp.decompose`).

    `cache_dir`: where tile results are kept between runs (see the module's doc);
    None keeps nothing. `use_ray`: None runs the tiles on Ray when it is initialised
    (or RAY_ADDRESS is set), else one after another here; True requires Ray; False
    never uses it. `progress(stage, fraction)` reports the plan and the merge.

    The result's `tile_report` says what happened: `tiles`, `ran` and `reused` (tile
    indices), `rejected` (cached files that did not check out, with why), `nodes`
    (the node id that ran each tile, under Ray) and `cache` (the plan's folder).

    Raises what `decompose_file` raises for the file and the settings, ValueError for
    a tile count out of range, and the task's error when a tile fails."""
    path = _path(path)
    if isinstance(tiles, bool) or not isinstance(tiles, int):
        raise ValueError(f"tiles: expected a count, got {tiles!r}")
    settings_json = _settings(settings, "ray_tiles.decompose")
    callback = _progress(progress)
    plan = _native.tiles_plan(path, settings_json, tiles, callback)
    count = _native.tiles_count(plan)
    report = {"tiles": count, "ran": [], "reused": [], "rejected": {}, "nodes": {},
              "cache": str(tile_file(cache_dir, plan, 0).parent) if cache_dir is not None else None}
    results = _cached(cache_dir, plan, count, report)
    report["reused"] = sorted(results)
    todo = [t for t in range(count) if t not in results]

    def keep(t, data, node):
        _native.tiles_check(plan, t, data)  # what came back over the network too
        if cache_dir is not None:
            _write_atomic(tile_file(cache_dir, plan, t), data)
        results[t] = data
        report["ran"].append(t)
        if node is not None:
            report["nodes"][t] = node

    ray = _ray_or_none(use_ray) if todo else None
    if ray is not None:
        task = ray.remote(num_cpus=1, max_retries=1)(_run_tile)
        refs = {task.options(scheduling_strategy="SPREAD").remote(path, plan, t): t for t in todo}
        _ray_results(ray, refs, lambda ref: keep(refs[ref], *ray.get(ref)))
    else:
        for t in todo:
            keep(t, _native.tiles_run(path, plan, t), None)
    report["ran"].sort()
    merged = _native.tiles_merge(path, plan, [results[t] for t in range(count)], callback)
    res = Result(merged)
    res.tile_report = report
    return res
