"""A tiled run in three steps from Python (primdecomp._native.tiles_*, and the driver
primdecomp.ray_tiles without Ray): bad plan and tile bytes are ValueErrors naming
what is wrong, never trusted; the driver's result is the CLI's `--tiles K` file byte
for byte and resumes per tile from its cache, running again a cached tile that was
altered. The two-node Ray cluster run is scripts/test.sh's `ray cluster` section
(crates/primdecomp-py/tests/ray_cluster.py)."""

import subprocess

import pytest

import primdecomp
import primdecomp.ray_tiles
from primdecomp import _native

from conftest import CLI, made_up, need

COUNTS = primdecomp._settings({"targets": [40]})


def flipped(data, at):
    b = bytearray(data)
    b[at] ^= 1
    return bytes(b)


def test_bad_plan_and_tile_bytes_are_refused():
    ply = str(made_up("lumpy.ply"))
    plan = _native.tiles_plan(ply, COUNTS, 3)
    assert _native.tiles_count(plan) == 3
    tile = _native.tiles_run(ply, plan, 1)
    _native.tiles_check(plan, 1, tile)
    # Plans: truncated, altered, another version, not a plan.
    with pytest.raises(ValueError, match="checksum"):
        _native.tiles_count(plan[:-5])
    with pytest.raises(ValueError, match="checksum"):
        _native.tiles_count(flipped(plan, 40))
    with pytest.raises(ValueError, match="version 3"):
        _native.tiles_count(plan[:8] + bytes([3]) + plan[9:])
    with pytest.raises(ValueError, match="not a primdecomp plan"):
        _native.tiles_count(b"PDTPLAN")
    with pytest.raises(ValueError, match="not a primdecomp plan"):
        _native.tiles_count(tile)
    # Tile results: truncated, altered, another tile, another plan, missing.
    with pytest.raises(ValueError, match="checksum"):
        _native.tiles_check(plan, 1, tile[:-1])
    with pytest.raises(ValueError, match="checksum"):
        _native.tiles_check(plan, 1, flipped(tile, len(tile) // 2))
    with pytest.raises(ValueError, match="holds tile 1, not tile 2"):
        _native.tiles_check(plan, 2, tile)
    other = _native.tiles_plan(ply, primdecomp._settings({"targets": [41]}), 3)
    with pytest.raises(ValueError, match="another plan"):
        _native.tiles_check(other, 1, tile)
    with pytest.raises(ValueError, match="3 tiles, 1 tile results"):
        _native.tiles_merge(ply, plan, [tile])
    # The wrong file, a tile out of range, a missing file, a tile count of 0.
    with pytest.raises(ValueError, match="not the file this tile plan was made from"):
        _native.tiles_run(str(made_up("robot.stl")), plan, 0)
    with pytest.raises(ValueError, match="tile 3 out of range"):
        _native.tiles_run(ply, plan, 3)
    with pytest.raises(FileNotFoundError):
        _native.tiles_run(ply + ".missing.ply", plan, 0)
    with pytest.raises(ValueError, match="tiles must be in"):
        _native.tiles_plan(ply, COUNTS, 0)
    with pytest.raises(ValueError, match="tiles: expected a count"):
        primdecomp.ray_tiles.decompose(ply, "3")


@pytest.mark.parametrize("settings,args", [({"targets": [40]}, ["-n", "40"]), ({}, [])])
def test_driver_equals_cli_and_resumes_per_tile(tmp_path, settings, args):
    need(CLI)
    ply = str(made_up("lumpy.ply"))
    out = tmp_path / "cli.json"
    subprocess.run([CLI, "decompose", ply, "--tiles", "3", *args, "-o", out, "-q"], check=True)
    cache = tmp_path / "cache"
    res = primdecomp.ray_tiles.decompose(ply, 3, cache_dir=cache, use_ray=False, **settings)
    assert res.to_json().encode() == out.read_bytes()
    report = res.tile_report
    assert (report["ran"], report["reused"]) == ([0, 1, 2], [])
    # Resumed: every tile from the cache, the same bytes.
    again = primdecomp.ray_tiles.decompose(ply, 3, cache_dir=cache, use_ray=False, **settings)
    assert (again.tile_report["ran"], again.tile_report["reused"]) == ([], [0, 1, 2])
    assert again.to_json() == res.to_json()
    # A cached tile altered is caught by its content and run again.
    file = primdecomp.ray_tiles.tile_file(cache, _native.tiles_plan(ply, primdecomp._settings(settings), 3), 1)
    file.write_bytes(flipped(file.read_bytes(), 50))
    third = primdecomp.ray_tiles.decompose(ply, 3, cache_dir=cache, use_ray=False, **settings)
    assert (third.tile_report["ran"], third.tile_report["reused"]) == ([1], [0, 2])
    assert "checksum" in third.tile_report["rejected"][1]
    assert third.to_json() == res.to_json()
