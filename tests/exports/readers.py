"""Readers that turn each exported file back into world-space shapes (dicts of
contain.py), each through the consumer's own reading where one runs here: MuJoCo's
compiled model (geom poses and sizes, mesh vertices), usd-core's composed
transforms, yourdfpy's parsed URDF and link poses. glTF and Godot scenes are parsed
here from their specifications (node TRS, Transform3D rows then origin).
"""
import base64
import json
import re
import struct
from pathlib import Path

import numpy as np

# ---------------------------------------------------------------- glTF

def load_gltf(path):
    """(document, buffers as bytes) of a .gltf (data URIs) or .glb."""
    raw = Path(path).read_bytes()
    if raw[:4] == b"glTF":
        jlen = struct.unpack_from("<I", raw, 12)[0]
        doc = json.loads(raw[20:20 + jlen])
        at = 20 + jlen
        bufs = []
        if at < len(raw):
            blen = struct.unpack_from("<I", raw, at)[0]
            bufs.append(raw[at + 8:at + 8 + blen])
        return doc, bufs
    doc = json.loads(raw)
    bufs = []
    for b in doc.get("buffers", []):
        uri = b["uri"]
        assert uri.startswith("data:"), uri
        bufs.append(base64.b64decode(uri.split(",", 1)[1]))
    return doc, bufs


def _trs(n):
    if "matrix" in n:
        return np.array(n["matrix"], float).reshape(4, 4).T
    t = np.array(n.get("translation", [0, 0, 0]), float)
    x, y, z, w = n.get("rotation", [0, 0, 0, 1])
    R = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])
    s = np.array(n.get("scale", [1, 1, 1]), float)
    M = np.eye(4)
    M[:3, :3] = R * s
    M[:3, 3] = t
    return M


def gltf_positions(doc, bufs, mesh_index):
    out = []
    for prim in doc["meshes"][mesh_index]["primitives"]:
        acc = doc["accessors"][prim["attributes"]["POSITION"]]
        view = doc["bufferViews"][acc["bufferView"]]
        off = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        data = np.frombuffer(bufs[view["buffer"]], dtype="<f4", count=acc["count"] * 3, offset=off)
        out.append(data.reshape(-1, 3).astype(float))
    return np.concatenate(out)


def _apply(M, p):
    return M[:3, :3] @ np.asarray(p, float) + M[:3, 3]


def _placed(M, local):
    """A shape defined along local +Y at the origin, placed by M (uniform scale)."""
    A = M[:3, :3]
    s = np.linalg.norm(A, axis=0)
    assert np.allclose(s, s[0], rtol=1e-5), f"non-uniform collider scale {s}"
    s = s[0]
    k = local["type"]
    p = local[k]
    if k == "box":
        axes = (A / np.linalg.norm(A, axis=0)).T
        return {"kind": "box", "center": M[:3, 3], "axes": axes, "half": np.array(p["size"]) * np.linalg.norm(A, axis=0) / 2}
    if k == "sphere":
        return {"kind": "sphere", "center": M[:3, 3], "radius": p["radius"] * s}
    h = p["height"] / 2
    a, b = _apply(M, [0, -h, 0]), _apply(M, [0, h, 0])
    if k == "capsule":
        assert p["radiusTop"] == p["radiusBottom"]
        return {"kind": "capsule", "p0": a, "p1": b, "radius": p["radiusTop"] * s}
    if k == "cylinder":
        return {"kind": "round", "p0": a, "p1": b, "r0": p["radiusBottom"] * s, "r1": p["radiusTop"] * s}
    raise ValueError(k)


def read_gltf(path):
    doc, bufs = load_gltf(path)
    ext = doc.get("extensions", {})
    khr = ext.get("KHR_implicit_shapes", {}).get("shapes", [])
    omi = ext.get("OMI_physics_shape", {}).get("shapes", [])
    shapes = []
    nodes = doc["nodes"]
    stack = [(i, np.eye(4)) for i in doc["scenes"][doc.get("scene", 0)]["nodes"]]
    while stack:
        i, parent = stack.pop()
        n = nodes[i]
        M = parent @ _trs(n)
        e = n.get("extensions", {})
        if "KHR_physics_rigid_bodies" in e and "collider" in e["KHR_physics_rigid_bodies"]:
            g = e["KHR_physics_rigid_bodies"]["collider"]["geometry"]
            if "shape" in g:
                shapes.append(_placed(M, khr[g["shape"]]))
            else:
                assert g.get("convexHull") is True
                pts = gltf_positions(doc, bufs, nodes[g["node"]]["mesh"])
                shapes.append({"kind": "hull", "points": (M[:3, :3] @ pts.T).T + M[:3, 3]})
        if "OMI_physics_body" in e and "collider" in e["OMI_physics_body"]:
            s = omi[e["OMI_physics_body"]["collider"]["shape"]]
            if s["type"] == "convex":
                pts = gltf_positions(doc, bufs, s["convex"]["mesh"])
                shapes.append({"kind": "hull", "points": (M[:3, :3] @ pts.T).T + M[:3, 3]})
            else:
                shapes.append(_placed(M, s))
        for c in n.get("children", []):
            stack.append((c, M))
    return shapes

# ---------------------------------------------------------------- MJCF (MuJoCo)

def read_mjcf(path):
    import mujoco
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    return mujoco_shapes(m, d)


def mujoco_shapes(m, d, skip_body=None):
    import mujoco
    G = mujoco.mjtGeom
    shapes = []
    for g in range(m.ngeom):
        if skip_body is not None and m.geom_bodyid[g] == skip_body:
            continue
        t = int(m.geom_type[g])
        size = m.geom_size[g]
        c = d.geom_xpos[g].copy()
        R = d.geom_xmat[g].reshape(3, 3)  # world = R @ local
        if t == int(G.mjGEOM_BOX):
            shapes.append({"kind": "box", "center": c, "axes": R.T.copy(), "half": size.copy()})
        elif t == int(G.mjGEOM_SPHERE):
            shapes.append({"kind": "sphere", "center": c, "radius": size[0]})
        elif t in (int(G.mjGEOM_CAPSULE), int(G.mjGEOM_CYLINDER)):
            a = R[:, 2] * size[1]
            if t == int(G.mjGEOM_CAPSULE):
                shapes.append({"kind": "capsule", "p0": c - a, "p1": c + a, "radius": size[0]})
            else:
                shapes.append({"kind": "round", "p0": c - a, "p1": c + a, "r0": size[0], "r1": size[0]})
        elif t == int(G.mjGEOM_MESH):
            i = m.geom_dataid[g]
            v = m.mesh_vert[m.mesh_vertadr[i]:m.mesh_vertadr[i] + m.mesh_vertnum[i]].astype(float)
            shapes.append({"kind": "hull", "points": (R @ v.T).T + c})
        else:
            raise ValueError(f"unexpected geom type {t}")
    return shapes

# ---------------------------------------------------------------- URDF (yourdfpy)

def read_obj_points(path):
    pts = []
    for line in Path(path).read_text().splitlines():
        if line.startswith("v "):
            pts.append([float(x) for x in line.split()[1:4]])
    return np.array(pts)


def read_urdf(path):
    import yourdfpy
    path = Path(path)
    robot = yourdfpy.URDF.load(str(path), load_meshes=False, load_collision_meshes=False,
                               build_scene_graph=True, build_collision_scene_graph=False)
    shapes = []
    for link in robot.robot.links:
        T = robot.get_transform(link.name, robot.base_link)
        for col in link.collisions:
            O = col.origin if col.origin is not None else np.eye(4)
            M = T @ O
            g = col.geometry
            R, c = M[:3, :3], M[:3, 3]
            if g.box is not None:
                shapes.append({"kind": "box", "center": c, "axes": R.T.copy(), "half": np.asarray(g.box.size) / 2})
            elif g.sphere is not None:
                shapes.append({"kind": "sphere", "center": c, "radius": g.sphere.radius})
            elif g.cylinder is not None:
                a = R[:, 2] * g.cylinder.length / 2
                shapes.append({"kind": "round", "p0": c - a, "p1": c + a, "r0": g.cylinder.radius, "r1": g.cylinder.radius})
            elif g.mesh is not None:
                v = read_obj_points(path.parent / g.mesh.filename)
                if g.mesh.scale is not None:
                    v = v * np.asarray(g.mesh.scale)
                shapes.append({"kind": "hull", "points": (R @ v.T).T + c})
            else:
                raise ValueError(f"unexpected URDF geometry in {link.name}")
    return join_capsules(shapes)


def join_capsules(shapes):
    """URDF 1.0 has no capsule: the export writes a cylinder and a sphere of the same
    radius on each end centre. Their union is exactly the capsule, which is convex,
    so a face lies in it iff its vertices do; the three are replaced by that capsule
    where the geometry says so (radii equal, sphere centres on the end centres)."""
    spheres = [i for i, s in enumerate(shapes) if s["kind"] == "sphere"]
    used = set()
    out = []
    for i, s in enumerate(shapes):
        if s["kind"] != "round" or s["r0"] != s["r1"]:
            continue
        ends = []
        for e in (s["p0"], s["p1"]):
            scale = 1e-9 * (np.abs(e).max() + s["r0"])
            j = next((j for j in spheres if j not in used and j not in ends
                      and abs(shapes[j]["radius"] - s["r0"]) <= scale
                      and np.abs(np.asarray(shapes[j]["center"]) - e).max() <= scale), None)
            ends.append(j)
        if None not in ends:
            used.update(ends)
            used.add(i)
            out.append({"kind": "capsule", "p0": s["p0"], "p1": s["p1"], "radius": s["r0"]})
    return out + [s for i, s in enumerate(shapes) if i not in used]

# ---------------------------------------------------------------- USD (usd-core)

def read_usd(path, require_api=True):
    from pxr import Usd, UsdGeom, UsdPhysics
    stage = Usd.Stage.Open(str(path))
    assert stage, f"usd-core cannot open {path}"
    shapes = []
    for prim in stage.Traverse():
        if not prim.IsA(UsdGeom.Gprim):
            continue
        assert prim.HasAPI(UsdPhysics.CollisionAPI), f"{prim.GetPath()} lacks PhysicsCollisionAPI"
        X = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
        M = np.array(X, float).T  # Gf is row-vector: transpose to world = M @ [p, 1]
        A, c = M[:3, :3], M[:3, 3]
        if prim.IsA(UsdGeom.Cube):
            size = UsdGeom.Cube(prim).GetSizeAttr().Get()
            n = np.linalg.norm(A, axis=0)
            shapes.append({"kind": "box", "center": c, "axes": (A / n).T, "half": n * size / 2})
        elif prim.IsA(UsdGeom.Sphere):
            r = UsdGeom.Sphere(prim).GetRadiusAttr().Get()
            shapes.append({"kind": "sphere", "center": c, "radius": r * np.linalg.norm(A[:, 0])})
        elif prim.IsA(UsdGeom.Capsule) or prim.IsA(UsdGeom.Cylinder):
            cap = prim.IsA(UsdGeom.Capsule)
            g = UsdGeom.Capsule(prim) if cap else UsdGeom.Cylinder(prim)
            axis = "XYZ".index(g.GetAxisAttr().Get())
            h = g.GetHeightAttr().Get() / 2
            r = g.GetRadiusAttr().Get() * np.linalg.norm(A[:, 0])
            e = np.zeros(3)
            e[axis] = h
            p0, p1 = A @ -e + c, A @ e + c
            if cap:
                shapes.append({"kind": "capsule", "p0": p0, "p1": p1, "radius": r})
            else:
                shapes.append({"kind": "round", "p0": p0, "p1": p1, "r0": r, "r1": r})
        elif prim.IsA(UsdGeom.Mesh):
            assert prim.HasAPI(UsdPhysics.MeshCollisionAPI), f"{prim.GetPath()} lacks PhysicsMeshCollisionAPI"
            approx = UsdPhysics.MeshCollisionAPI(prim).GetApproximationAttr().Get()
            assert approx == "convexHull", approx
            pts = np.array(UsdGeom.Mesh(prim).GetPointsAttr().Get(), float)
            shapes.append({"kind": "hull", "points": (A @ pts.T).T + c})
        else:
            raise ValueError(f"unexpected prim {prim.GetPath()} {prim.GetTypeName()}")
    return shapes, stage

# ---------------------------------------------------------------- Godot .tscn

_HEADER = re.compile(r'^\[(\w+)((?:\s+[\w/]+=(?:"(?:[^"\\]|\\.)*"|[^\s\]]+))*)\s*\]$')
_ATTR = re.compile(r'([\w/]+)=("(?:[^"\\]|\\.)*"|[^\s\]]+)')


def _unquote(v):
    if v.startswith('"'):
        return re.sub(r"\\(.)", lambda m: {"n": "\n"}.get(m.group(1), m.group(1)), v[1:-1])
    return v


def _numbers(v):
    inner = v[v.index("(") + 1:v.rindex(")")]
    return np.array([float(x) for x in inner.split(",")]) if inner.strip() else np.zeros(0)


def parse_tscn(path):
    """[(section kind, header attrs, properties)] of a text scene; raises on lines it
    does not understand. Lines end at a line feed only, as Godot's tokenizer reads them
    (core/variant/variant_parser.cpp): U+2028 and U+2029, where str.splitlines() would
    also cut, are characters of a string there."""
    sections = []
    for ln, line in enumerate(Path(path).read_text().split("\n"), 1):
        if not line.strip():
            continue
        if line.startswith("["):
            m = _HEADER.match(line)
            assert m, f"{path}:{ln}: bad section header {line!r}"
            attrs = {k: _unquote(v) for k, v in _ATTR.findall(m.group(2))}
            sections.append((m.group(1), attrs, {}))
        else:
            k, sep, v = line.partition(" = ")
            assert sep and sections, f"{path}:{ln}: bad property line {line!r}"
            sections[-1][2][k] = v
    return sections


def read_tscn(path):
    secs = parse_tscn(path)
    assert secs[0][0] == "gd_scene" and secs[0][1].get("format") == "3", secs[0]
    res = {a["id"]: (a["type"], p) for kind, a, p in secs if kind == "sub_resource"}
    assert int(secs[0][1]["load_steps"]) == len(res) + 1
    nodes = [(a, p) for kind, a, p in secs if kind == "node"]
    world = {}
    shapes = []
    for a, p in nodes:
        M = np.eye(4)
        if "transform" in p:
            assert p["transform"].startswith("Transform3D(")
            v = _numbers(p["transform"])
            M[:3, :3] = v[:9].reshape(3, 3)  # rows
            M[:3, 3] = v[9:]
        parent = a.get("parent")
        path_key = a["name"] if parent is None else (a["name"] if parent == "." else f"{parent}/{a['name']}")
        if parent is not None:
            M = world["." if parent == "." else parent] @ M
        world["." if parent is None else path_key] = M
        if a["type"] == "CollisionShape3D":
            rid = re.match(r'SubResource\("([^"]+)"\)', p["shape"]).group(1)
            ty, props = res[rid]
            A, c = M[:3, :3], M[:3, 3]
            if ty == "BoxShape3D":
                shapes.append({"kind": "box", "center": c, "axes": A.T.copy(), "half": _numbers(props["size"]) / 2})
            elif ty == "SphereShape3D":
                shapes.append({"kind": "sphere", "center": c, "radius": float(props["radius"])})
            elif ty == "CapsuleShape3D":
                r, h = float(props["radius"]), float(props["height"])
                e = A[:, 1] * (h / 2 - r)
                shapes.append({"kind": "capsule", "p0": c - e, "p1": c + e, "radius": r})
            elif ty == "CylinderShape3D":
                r, h = float(props["radius"]), float(props["height"])
                e = A[:, 1] * h / 2
                shapes.append({"kind": "round", "p0": c - e, "p1": c + e, "r0": r, "r1": r})
            elif ty == "ConvexPolygonShape3D":
                pts = _numbers(props["points"]).reshape(-1, 3)
                shapes.append({"kind": "hull", "points": (A @ pts.T).T + c})
            else:
                raise ValueError(ty)
        else:
            assert a["type"] in ("Node3D", "StaticBody3D"), a
    return shapes


READERS = {
    "gltf": read_gltf,
    "glb": read_gltf,
    "omi.gltf": read_gltf,
    "xml": read_mjcf,
    "urdf": read_urdf,
    "usda": lambda p: read_usd(p)[0],
    "tscn": read_tscn,
}
