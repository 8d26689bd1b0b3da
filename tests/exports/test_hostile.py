"""Hostile names and numbers through the real consumers (made here, not in the
corpus): a per-object result whose objects carry names that broke the writers (a
NUL, ESC and BEL, characters XML 1.0 forbids, the line and paragraph separators
U+2028 and U+2029 (written raw: every reader takes them inside a name or string),
markup, MuJoCo's `world`, duplicates, a 240-character name) and an output file name with control characters, exported in
every format: MuJoCo compiles the MJCF, yourdfpy loads the URDF and its meshes,
usd-core opens the stage, the Khronos glTF Validator finds no error, the .tscn
parses back; every object keeps a unique, readable name. Numbers no format can hold
are refused with exit 2 and nothing written. The full set of cases, with the exact
messages, is docs/bad_input.md (crates/primdecomp-cli/tests/bad_input.rs)."""
import json
import subprocess

import pytest

from conftest import BIN, run
from readers import _unquote, parse_tscn

NAMES = ["world", "a\x00b", "\x1b[31mred\x07", "tab\tnl\ncr\r", "a\ufffeb\uffff", "a\u2028b\u2029c",
         "<!--<script>", "q\"'&<>", "\u202etxt.exe", "dup", "dup", "", "日本語 ok", "x" * 240]

PRISM = {"kind": "prism", "center": [0, 0, 0], "rotation": [0, 0, 0, 1], "half_x": 0.5,
         "half_y": 0.5, "half_z_top": 0.25, "half_z_bottom": 0.5}
SPHERE = {"kind": "sphere", "center": [1, 0, 0], "radius": 0.5}
CAPSULE = {"kind": "capsule", "p0": [0, 0, 0], "p1": [0, 1, 0], "radius": 0.25}


def hostile_result(path):
    objects = [{"name": n, "translation": [3.0 * i, 0, 0], "rotation": [0, 0, 0, 1], "scale": 1,
                "primitives": [PRISM, SPHERE, CAPSULE]} for i, n in enumerate(NAMES)]
    doc = {"format": "primdecomp", "version": 1, "primitives": [PRISM], "objects": objects}
    path.write_text(json.dumps(doc))
    return path


def visible(s):
    """The writers' escape of control characters (`visible`, crates/primdecomp/src/output/visible.rs)."""
    hidden = lambda c: (ord(c) < 0x20 or 0x7f <= ord(c) <= 0x9f or c in "\ufffe\uffff"  # noqa: E731
                        or 0x202a <= ord(c) <= 0x202e or 0x2066 <= ord(c) <= 0x2069)
    return "".join(f"\\u{{{ord(c):x}}}" if hidden(c) else c for c in s)


def expected(reserved=()):
    """The names the writers give the objects: visible, unique, not reserved."""
    used, out = set(reserved), []
    for i, n in enumerate(NAMES):
        base = visible(n) if n else f"object{i}"
        name, k = base, 2
        while name in used:
            name, k = f"{base}_{k}", k + 1
        used.add(name)
        out.append(name)
    return out


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    d = tmp_path_factory.mktemp("hostile")
    res = hostile_result(d / "r.json")
    model = "m\x1b[2J\x07"
    outs = {}
    for key, name, extra in [("gltf", "g.gltf", []), ("glb", "g.glb", []),
                             ("omi", "o.gltf", ["--gltf-physics", "omi"]),
                             ("preview", "p.glb", ["--preview"]),
                             ("mjcf", f"{model}.xml", ["--format", "mjcf"]),
                             ("urdf", f"{model}.urdf", []), ("urdf_capsule", "c.urdf", ["--urdf-capsule"]),
                             ("usda", f"{model}.usda", []), ("tscn", f"{model}.tscn", [])]:
        r = run([BIN, "export", res, "-o", d / name, *extra])
        assert "\x1b" not in r.stdout and "\x07" not in r.stdout, "raw control characters printed"
        outs[key] = d / name
    return outs


def test_mujoco_compiles_the_mjcf(exported):
    import mujoco

    m = mujoco.MjModel.from_xml_path(str(exported["mjcf"]))
    bodies = [m.body(i).name for i in range(1, m.nbody)]
    assert bodies == expected(reserved=["world"])
    assert m.ngeom == 3 * len(NAMES)


def test_yourdfpy_loads_the_urdf_and_its_meshes(exported):
    import yourdfpy

    u = yourdfpy.URDF.load(str(exported["urdf"]), build_collision_scene_graph=True,
                           load_collision_meshes=True)
    links = [name for name in u.link_map if not name.endswith("_root")]
    assert sorted(links) == sorted(expected())
    meshes = [c.geometry.mesh.filename for link in u.link_map.values() for c in link.collisions
              if c.geometry.mesh is not None]
    assert len(meshes) == len(NAMES)
    assert all(len(part.encode()) <= 255 for f in meshes for part in f.split("/"))
    import pybullet
    client = pybullet.connect(pybullet.DIRECT)
    try:
        assert pybullet.loadURDF(str(exported["urdf_capsule"]), physicsClientId=client) >= 0
    finally:
        pybullet.disconnect(client)


def test_usd_stage_opens(exported):
    from pxr import Usd

    stage = Usd.Stage.Open(str(exported["usda"]))
    assert stage, "usd-core cannot open the stage"
    names = [p.GetAttribute("primdecomp:name").Get() for p in stage.Traverse()
             if p.GetAttribute("primdecomp:name")]
    assert names == expected()
    prims = [p.GetName() for p in stage.GetDefaultPrim().GetChildren()]
    assert len(set(prims)) == len(NAMES)


def test_gltf_validator_passes(exported):
    from test_consumers import validator_reports

    paths = [exported[k] for k in ("gltf", "glb", "omi", "preview")]
    for rep in validator_reports(paths):
        assert rep["errors"] == 0, json.dumps(rep, indent=1)[:3000]
    doc = json.loads(exported["gltf"].read_text())
    scene = [doc["nodes"][i]["name"] for i in doc["scenes"][0]["nodes"]]
    assert scene == expected()


def test_tscn_parses_back(exported):
    text = exported["tscn"].read_text()
    assert not any(ord(c) < 32 and c not in "\n\t" for c in text), "raw control character"
    secs = parse_tscn(exported["tscn"])
    bodies = [(a["name"], p) for k, a, p in secs if k == "node" and a.get("type") == "StaticBody3D"]
    assert len(bodies) == len({n for n, _ in bodies}) == len(NAMES)
    # Each body's metadata keeps the object's name whole, U+2028 and U+2029 included.
    kept = [_unquote(p["metadata/primdecomp_name"]) for _, p in bodies]
    assert kept == expected()


@pytest.mark.parametrize("fmt", ["g.glb", "x.xml", "u.urdf", "s.usda", "t.tscn"])
def test_unwritable_numbers_are_refused(tmp_path, fmt):
    """A sphere at 1e60 (readable, but no 32-bit reader can load it): exit 2, one
    sentence naming the file, nothing written."""
    doc = {"format": "primdecomp", "version": 1,
           "primitives": [{"kind": "sphere", "center": [1e60, 0, 0], "radius": 1}]}
    (tmp_path / "r.json").write_text(json.dumps(doc))
    extra = ["--format", "mjcf"] if fmt.endswith(".xml") else []
    r = subprocess.run([str(BIN), "export", str(tmp_path / "r.json"), "-o", str(tmp_path / fmt), *extra],
                       capture_output=True, text=True)
    assert r.returncode == 2 and fmt in r.stderr and "1e18" in r.stderr, r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.json"]
