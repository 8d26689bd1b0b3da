"""--per-object keeps names and transforms: on a multi-node glTF (the made-up
nodes.glb: five named mesh nodes under a moved and turned parent, one scaled, one
turned; and, with the corpus, kenney_character: six) each object has its node's name
and world transform, the glTF export has one node per object with that transform (its
colliders as children), and the target is shared exactly; on a multi-group OBJ (the
made-up groups.obj, and vhacd_lamp: three groups) each group keeps its name in every
format."""
import json

import numpy as np
import pytest

from conftest import BIN, CASE_NAMES, CASES, export, made_up, result, run
from readers import _trs, load_gltf, parse_tscn

# (case, the object names in order) of the multi-node glTF and multi-group OBJ cases.
NODES = [("nodes", ["base", "column", "ball", "arm", "lamp"]),
         ("character", ["leg-left", "leg-right", "torso", "arm-left", "arm-right", "antenna"])]
GROUPS = [("groups", ["table", "lamp", "books"]), ("lamp", ["globes", "arms", "post"])]
# Only the cases collected here (the corpus ones where the corpus is).
NODES = [n for n in NODES if n[0] in CASE_NAMES]
GROUPS = [g for g in GROUPS if g[0] in CASE_NAMES]


def count_of(case):
    args = next(c[2] for c in CASES if c[0] == case)
    return int(args[args.index("-n") + 1])


def node_world(doc):
    """{node name: world matrix} of the mesh nodes of the default scene."""
    out = {}
    stack = [(i, np.eye(4)) for i in doc["scenes"][doc.get("scene", 0)]["nodes"]]
    while stack:
        i, parent = stack.pop()
        n = doc["nodes"][i]
        M = parent @ _trs(n)
        if "mesh" in n:
            out[n.get("name")] = M
        stack += [(c, M) for c in n.get("children", [])]
    return out


def frame_matrix(o):
    from contain import quat_axes
    M = np.eye(4)
    M[:3, :3] = quat_axes(o["rotation"]).T * o["scale"]
    M[:3, 3] = o["translation"]
    return M


@pytest.mark.parametrize("case,names", NODES)
def test_gltf_nodes_keep_names_and_transforms(workdir, case, names):
    res, src, _ = result(workdir, case)
    doc = json.loads(res.read_text())
    inp, _ = load_gltf(src)
    nodes = node_world(inp)
    objs = doc["objects"]
    assert [o["name"] for o in objs] == names
    assert set(nodes) == {o["name"] for o in objs}
    moved = 0
    for o in objs:
        W = nodes[o["name"]]
        assert np.allclose(frame_matrix(o), W, atol=1e-6), o["name"]
        moved += not np.allclose(W, np.eye(4))
        assert o["target"] >= 1
    assert moved > 0, "the case should have transformed nodes"
    assert sum(o["target"] for o in objs) == doc["settings"]["target"] == count_of(case)
    assert "surface area" in doc["settings"]["share_rule"]
    # The glTF export: one node per object, named, with the node's transform, and the
    # colliders as its children (so they move with it).
    out, _ = load_gltf(export(workdir, case, "gltf", "y", 1.0))
    scene = [out["nodes"][i] for i in out["scenes"][0]["nodes"]]
    assert [n["name"] for n in scene] == [o["name"] for o in objs]
    for n, o in zip(scene, objs):
        assert np.allclose(_trs(n), nodes[o["name"]], atol=1e-5), n["name"]
        assert len(n.get("children", [])) == len(o["primitives"])


@pytest.mark.parametrize("case,names", GROUPS)
def test_obj_groups_keep_names_in_every_format(workdir, case, names):
    res, _, _ = result(workdir, case)
    assert [o["name"] for o in json.loads(res.read_text())["objects"]] == names
    urdf = export(workdir, case, "urdf", "y", 1.0).read_text()
    mjcf = export(workdir, case, "xml", "y", 1.0).read_text()
    usda = export(workdir, case, "usda", "y", 1.0).read_text()
    tscn = parse_tscn(export(workdir, case, "tscn", "y", 1.0))
    gltf, _ = load_gltf(export(workdir, case, "glb", "y", 1.0))
    for n in names:
        assert f'<link name="{n}">' in urdf
        assert f'<body name="{n}"' in mjcf
        assert f'def Xform "{n}"' in usda
        assert any(a.get("name") == n and a["type"] == "StaticBody3D" for k, a, _ in tscn if k == "node")
        assert any(x.get("name") == n for x in gltf["nodes"])


def test_without_the_flag_nothing_changes(tmp_path):
    src = made_up("groups.obj")
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    run([BIN, "decompose", src, "-n", "8", "-o", a, "--quiet"])
    run([BIN, "decompose", src, "-n", "8", "-o", b, "--quiet", "--export", tmp_path / "x.glb"])
    doc = json.loads(a.read_text())
    assert "objects" not in doc and "share_rule" not in doc["settings"]
    assert a.read_bytes() == b.read_bytes()


def test_names_with_quotes_and_angle_brackets(tmp_path):
    """A multi-group OBJ made here (not in the corpus), with hostile group names:
    every format stays well-formed and the consumers still load it."""
    import xml.etree.ElementTree as ET

    from readers import read_mjcf, read_tscn, read_urdf, read_usd

    cube = lambda x0: [(x0 + dx, dy, dz) for dx in (0, 1) for dy in (0, 1) for dz in (0, 1)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines = []
    names = ['a "quoted" <part> & co', "a \\ back\nslash", "a \"quoted\" <part> & co"]
    for k, name in enumerate(names):
        lines.append(f"g {name.splitlines()[0]}")
        lines += [f"v {x} {y} {z}" for x, y, z in cube(3 * k)]
        lines += ["f " + " ".join(str(8 * k + i + 1) for i in q) for q in quads]
    obj = tmp_path / "hostile.obj"
    obj.write_text("\n".join(lines) + "\n")
    res = tmp_path / "r.json"
    outs = [tmp_path / f for f in ("h.gltf", "h.urdf", "h.usda", "h.tscn")]
    run([BIN, "decompose", obj, "--per-object", "-n", "3", "-o", res, "--quiet",
         *sum((["--export", o] for o in outs), [])])
    run([BIN, "export", res, "-o", tmp_path / "h.xml", "--format", "mjcf"])
    got = [o["name"] for o in json.loads(res.read_text())["objects"]]
    assert len(got) == 3 and got[0] == names[0]
    ET.parse(tmp_path / "h.xml")
    ET.parse(tmp_path / "h.urdf")
    assert len(read_mjcf(tmp_path / "h.xml")) == 3
    assert len(read_urdf(tmp_path / "h.urdf")) == 3
    assert len(read_usd(tmp_path / "h.usda")[0]) == 3
    assert len(read_tscn(tmp_path / "h.tscn")) == 3
    json.loads((tmp_path / "h.gltf").read_text())


def test_extension_decides_and_format_covers_xml(tmp_path):
    """`--format mjcf` names the format of the .xml only: the other exports of the
    same run keep the format their extension names; an unknown extension without
    --format is refused with exit 2, and so is an export onto the input."""
    import subprocess

    obj = tmp_path / "cube.obj"
    obj.write_text("o cube\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
                   "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n")
    res = tmp_path / "r.json"
    run([BIN, "decompose", obj, "-n", "1", "-o", res, "--quiet", "--export", tmp_path / "a.glb",
         "--export", tmp_path / "b.xml", "--format", "mjcf"])
    assert (tmp_path / "a.glb").read_bytes()[:4] == b"glTF"
    assert "<mujoco" in (tmp_path / "b.xml").read_text()
    bad = subprocess.run([str(BIN), "export", str(res), "-o", str(tmp_path / "c.xml")], capture_output=True, text=True)
    assert bad.returncode == 2 and "--format mjcf" in bad.stderr
    bad = subprocess.run([str(BIN), "export", str(res), "-o", str(res), "--format", "gltf"], capture_output=True, text=True)
    assert bad.returncode == 2 and "refusing to overwrite an input" in bad.stderr
