"""The up axis a result records (input.up: glTF +Y by its specification, STL assumed
+Z, docs/decisions/0053) is the one `export` uses when --up is not given: MuJoCo
(+Z up) gets a z-up STL as it stands and a y-up glTF turned upright; a result made
before the axis was recorded exports as +Y, as it did then."""
import json

import numpy as np

from conftest import BIN, made_up, run
from contain import aabb
from readers import mujoco_shapes


def mjcf_top(path):
    """The highest point (z) of the colliders MuJoCo compiles from an MJCF file."""
    import mujoco

    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    return max(aabb(sh)[1][2] for sh in mujoco_shapes(m, d))


def decompose(tmp_path, name, *args):
    out = tmp_path / f"{name}.json"
    run([BIN, "decompose", made_up(name), "-n", "8", "-o", out, "--quiet", *args])
    return out, json.loads(out.read_text())


def test_each_format_records_its_up_axis(tmp_path):
    _, stl = decompose(tmp_path, "robot.stl")
    _, gltf = decompose(tmp_path, "nodes.glb")
    _, obj = decompose(tmp_path, "groups.obj")
    assert stl["input"]["up"] == "z" and "assumed" in stl["input"]["up_from"]
    assert gltf["input"]["up"] == "y" and "specification" in gltf["input"]["up_from"]
    assert obj["input"]["up"] == "y" and "assumed" in obj["input"]["up_from"]
    _, given = decompose(tmp_path, "robot.stl", "--up", "y")
    assert given["input"]["up"] == "y" and given["input"]["up_from"] == "given with --up"


def test_export_stands_the_result_on_its_recorded_axis(tmp_path):
    res, doc = decompose(tmp_path, "robot.stl")
    top_z = doc["input"]["aabb_max"][2]
    xml = tmp_path / "robot.xml"
    out = run([BIN, "export", res, "-o", xml, "--format", "mjcf"]).stdout
    assert "turned" not in out, out
    assert np.isclose(mjcf_top(xml), top_z, rtol=1e-3, atol=1e-3)

    res, doc = decompose(tmp_path, "nodes.glb")
    top_y = doc["input"]["aabb_max"][1]
    xml = tmp_path / "nodes.xml"
    out = run([BIN, "export", res, "-o", xml, "--format", "mjcf"]).stdout
    assert "turned to the format's z" in out, out
    assert np.isclose(mjcf_top(xml), top_y, rtol=1e-3, atol=1e-3)


def test_a_result_without_an_up_axis_exports_as_y_up(tmp_path):
    """Results written before input.up existed still read, and export as they did
    (+Y up): the z-up robot is turned, as it was then."""
    res, doc = decompose(tmp_path, "robot.stl")
    del doc["input"]["up"], doc["input"]["up_from"]
    old = tmp_path / "old.json"
    old.write_text(json.dumps(doc))
    xml = tmp_path / "old.xml"
    out = run([BIN, "export", old, "-o", xml, "--format", "mjcf"]).stdout
    assert "records none" in out, out
    # +Y turned to +Z: the robot's y extent becomes its height.
    assert np.isclose(mjcf_top(xml), doc["input"]["aabb_max"][1], rtol=1e-3, atol=1e-3)
