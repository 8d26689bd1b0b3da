"""Each format loaded by the real thing: MuJoCo compiles the MJCF and a ball dropped
on it comes to rest on top; yourdfpy loads the URDF; usd-core opens the stage with
the collision API on every collider; the Khronos glTF Validator finds no error and
the physics extension objects validate against the extensions' constraints
(physics_schema.json); Godot cannot run here, so the .tscn is parsed back and
checked."""
import json
import subprocess
from pathlib import Path

import jsonschema
import numpy as np
import pytest

from conftest import CASES, ROOT, export, result
from readers import load_gltf, parse_tscn, read_mjcf, read_tscn, read_usd

HERE = Path(__file__).parent
CASE_NAMES = [c[0] for c in CASES]


@pytest.mark.parametrize("up", ["y", "z"])
@pytest.mark.parametrize("case", CASE_NAMES)
def test_mujoco_ball_comes_to_rest_on_top(workdir, case, up):
    """MuJoCo compiles the MJCF; a ball dropped (along MJCF's -z, on a vertical
    slide joint so it cannot roll off a slope) above the input's highest vertex
    lands on the colliders and rests there: at least the mesh's top plus its radius
    (less MuJoCo's contact softness) high, and no higher than the colliders' top
    plus its radius. A wrong up axis or scale puts no collider under it."""
    import mujoco
    import xml.etree.ElementTree as ET

    from conftest import to_format_frame

    path = export(workdir, case, "xml", up, 1.0)
    m0 = mujoco.MjModel.from_xml_path(str(path))  # compiles as written
    assert m0.ngeom > 0
    d0 = mujoco.MjData(m0)
    mujoco.mj_forward(m0, d0)
    from contain import aabb
    from readers import mujoco_shapes

    top_colliders = max(aabb(sh)[1][2] for sh in mujoco_shapes(m0, d0))
    V = to_format_frame("xml", up, 1.0, result(workdir, case)[2]["vertices"])
    size = float(np.linalg.norm(V.max(axis=0) - V.min(axis=0)))
    peak = V[np.argmax(V[:, 2])]
    r = 0.02 * size
    tree = ET.parse(path)
    world = tree.getroot().find("worldbody")
    ball = ET.SubElement(world, "body", name="primdecomp_test_ball",
                         pos=f"{peak[0]} {peak[1]} {top_colliders + 2 * r}")
    ET.SubElement(ball, "joint", type="slide", axis="0 0 1")
    ET.SubElement(ball, "geom", type="sphere", size=str(r), density="1000")
    dropped = path.with_name("dropped.xml")
    tree.write(dropped)
    m = mujoco.MjModel.from_xml_path(str(dropped))
    d = mujoco.MjData(m)
    b = m.body("primdecomp_test_ball").id
    fall = np.sqrt(2 * (top_colliders + 2 * r - V[:, 2].min()) / 9.81)
    for _ in range(int((fall + 2.0) / m.opt.timestep)):
        mujoco.mj_step(m, d)
    z = d.xpos[b][2]
    speed = abs(d.qvel[0])
    touching = [c for c in d.contact[: d.ncon] if b in (m.geom_bodyid[c.geom1], m.geom_bodyid[c.geom2])]
    assert touching, f"ball touches no collider (z={z})"
    assert speed < 0.01 * size, f"ball still moving at {speed}"
    assert z >= peak[2] + 0.9 * r, f"ball at z={z} sank below the mesh's top {peak[2]} + r"
    assert z <= top_colliders + 1.01 * r, f"ball at z={z} above every collider ({top_colliders})"


@pytest.mark.parametrize("case", CASE_NAMES)
def test_urdf_loads_in_yourdfpy_and_pybullet(workdir, case):
    """yourdfpy loads and validates the URDF 1.0 file with its collision meshes;
    pybullet loads it too, and the --urdf-capsule variant (which yourdfpy, a URDF
    1.0 reader, refuses) with native capsules of the right size."""
    import pybullet
    import yourdfpy

    from conftest import BIN, run

    res, _, _ = result(workdir, case)
    doc = json.loads(res.read_text())
    objects = doc.get("objects") or [{"primitives": doc["primitives"]}]
    n = sum(len(o["primitives"]) for o in objects)
    caps = [p for o in objects for p in o["primitives"] if p["kind"] == "capsule"]
    path = export(workdir, case, "urdf", "z", 1.0)
    robot = yourdfpy.URDF.load(str(path), load_meshes=True, load_collision_meshes=True,
                               build_collision_scene_graph=True)
    assert robot.validate()
    assert len(robot.robot.links) == len(objects) + 1  # and the root
    cols = sum(len(link.collisions) for link in robot.robot.links)
    assert cols == n + 2 * len(caps)  # a capsule: a cylinder and two spheres
    # yourdfpy builds one collision mesh per link, from the mesh files beside.
    assert len(robot.collision_scene.geometry) == len(objects)

    capsule = path.with_name("capsule.urdf")
    run([BIN, "export", res, "-o", capsule, "--up", "z", "--urdf-capsule"])
    client = pybullet.connect(pybullet.DIRECT)
    try:
        for p, want in ((path, n + 2 * len(caps)), (capsule, n)):
            body = pybullet.loadURDF(str(p), useFixedBase=True, physicsClientId=client)
            data = [d for j in range(-1, pybullet.getNumJoints(body, physicsClientId=client))
                    for d in pybullet.getCollisionShapeData(body, j, physicsClientId=client)]
            assert len(data) == want, (p.name, len(data), want)
            if p == capsule:
                got = sorted(d[3][1] for d in data if d[2] == pybullet.GEOM_CAPSULE)
                # pybullet's capsule dimensions: (length between cap centres, radius).
                assert len(got) == len(caps)
                radii = sorted(c["radius"] for c in caps)
                # Every export grows a shape by 2^-18 of its coordinates' magnitude (the
                # conservative margin, exports-engine-conventions.md): never smaller.
                box = doc["input"]["aabb_min"] + doc["input"]["aabb_max"]
                reach = max(abs(x) for x in box) + max(radii, default=0.0)
                assert all(g >= r for g, r in zip(got, radii)), (got, radii)
                assert np.allclose(got, radii, rtol=1e-4, atol=4 * reach / 262144), (got, radii)
    finally:
        pybullet.disconnect(client)


@pytest.mark.parametrize("up", ["y", "z"])
@pytest.mark.parametrize("case", CASE_NAMES)
def test_usd_stage_opens_with_collision_api(workdir, case, up):
    from pxr import UsdGeom, UsdPhysics

    path = export(workdir, case, "usda", up, 0.01)
    shapes, stage = read_usd(path)  # asserts the API on every Gprim
    assert UsdGeom.GetStageUpAxis(stage) == up.upper()
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
    colliders = [p for p in stage.Traverse() if p.HasAPI(UsdPhysics.CollisionAPI)]
    doc = json.loads(result(workdir, case)[0].read_text())
    assert len(colliders) == len(doc["primitives"]) == len(shapes)


def validator_reports(paths):
    node = subprocess.run(["node", str(HERE / "validate_gltf.js"), *map(str, paths)],
                          capture_output=True, text=True, cwd=HERE)
    assert node.returncode == 0, node.stderr
    return [json.loads(line) for line in node.stdout.splitlines()]


@pytest.mark.parametrize("case", CASE_NAMES)
def test_gltf_validator_and_physics_schema(workdir, case):
    paths = [export(workdir, case, f, "y", 1.0) for f in ("gltf", "glb", "omi.gltf")]
    res, src, _ = result(workdir, case)
    preview = paths[0].with_name("preview.glb")
    from conftest import BIN, run
    run([BIN, "export", res, "-o", preview, "--preview", "--input", src])
    paths.append(preview)
    for rep in validator_reports(paths):
        assert rep["errors"] == 0, json.dumps(rep, indent=1)[:3000]
    schema = json.loads((HERE / "physics_schema.json").read_text())
    defs = schema["$defs"]

    def check(instance, name):
        jsonschema.validate(instance, {"$ref": f"#/$defs/{name}", "$defs": defs})

    for p in paths:
        doc, _ = load_gltf(p)
        ext = doc.get("extensions", {})
        if "KHR_implicit_shapes" in ext:
            check(ext["KHR_implicit_shapes"], "khrDocument")
            assert doc["extensionsUsed"] == ["KHR_implicit_shapes", "KHR_physics_rigid_bodies"]
        elif "KHR_physics_rigid_bodies" in doc["extensionsUsed"]:
            # Every collider a hull (a mesh): no implicit shape, none listed.
            assert doc["extensionsUsed"] == ["KHR_physics_rigid_bodies"]
        else:
            check(ext["OMI_physics_shape"], "omiDocument")
            assert doc["extensionsUsed"] == ["OMI_physics_shape", "OMI_physics_body"]
        n = 0
        for node in doc["nodes"]:
            e = node.get("extensions", {})
            if "KHR_physics_rigid_bodies" in e:
                check(e["KHR_physics_rigid_bodies"], "khrNode")
                n += 1
            if "OMI_physics_body" in e:
                check(e["OMI_physics_body"], "omiNode")
                n += "collider" in e["OMI_physics_body"]
        assert n == len(json.loads(res.read_text())["primitives"])


def test_schema_rejects_what_the_specs_forbid():
    """The constraints catch the mistakes an exporter makes (so the check can fail)."""
    schema = json.loads((HERE / "physics_schema.json").read_text())
    bad = [
        ("khrShape", {"type": "box", "box": {"size": [1, 0, 1]}}),
        ("khrShape", {"type": "sphere", "sphere": {"radius": -1}}),
        ("khrShape", {"type": "capsule", "capsule": {"height": 0, "radiusTop": 1, "radiusBottom": 1}}),
        ("khrShape", {"type": "box", "box": {"size": [1, 1, 1]}, "sphere": {"radius": 1}}),
        ("khrShape", {"type": "cylinder", "cylinder": {"height": 1, "radiusTop": 0, "radiusBottom": 0}}),
        ("khrNode", {"collider": {"geometry": {"shape": 0, "node": 1}}}),
        ("khrNode", {"collider": {}}),
        ("omiShape", {"type": "cone"}),
        ("omiNode", {"motion": {"type": "fixed"}}),
    ]
    for name, inst in bad:
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(inst, {"$ref": f"#/$defs/{name}", "$defs": schema["$defs"]})


@pytest.mark.parametrize("case", CASE_NAMES)
def test_tscn_parses_back(workdir, case):
    path = export(workdir, case, "tscn", "z", 1.0)
    secs = parse_tscn(path)
    nodes = [(a, p) for k, a, p in secs if k == "node"]
    ids = {a["id"] for k, a, p in secs if k == "sub_resource"}
    bodies = {a["name"] for a, p in nodes if a["type"] == "StaticBody3D"}
    assert nodes[0][0]["type"] == "Node3D" and "parent" not in nodes[0][0]
    used = set()
    for a, p in nodes:
        if a["type"] == "CollisionShape3D":
            assert a["parent"] in bodies, a
            rid = p["shape"].split('"')[1]
            assert rid in ids
            used.add(rid)
        if a["type"] == "StaticBody3D":
            assert a["parent"] == "."
            assert "metadata/primdecomp_name" in p
    assert used == ids
    doc = json.loads(result(workdir, case)[0].read_text())
    assert len(read_tscn(path)) == len(doc["primitives"])
    assert len(bodies) == len(doc.get("objects") or [0])
