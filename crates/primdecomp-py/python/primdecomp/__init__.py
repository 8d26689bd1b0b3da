"""primdecomp: decompose meshes into convex primitives (boxes, spheres, capsules,
cylinders, frustums, prisms) from Python. A thin layer over the Rust library; the
decomposition runs with the GIL released, Ctrl-C raises KeyboardInterrupt.

    import primdecomp
    v, f = primdecomp.load("bunny.obj")
    res = primdecomp.decompose(v, f, targets=[64])
    for p in res.levels[0].primitives:
        print(p.kind, p.volume, p.transform)
"""

import json as _json
import inspect as _inspect

import numpy as _np

from . import _native

__all__ = ["load", "decompose", "decompose_file", "as_hulls", "Result", "Level", "Primitive", "batch"]


def load(path):
    """Load a mesh file (every format the core reads: OBJ, PLY, STL, OFF, glTF, GLB).

    Returns (vertices, faces): vertices an (N,3) float64 array holding the file's
    coordinates exactly; faces an (F,k) uint32 array when every face has k corners,
    else a list of polygons. `decompose(*load(path))` equals the CLI's primitives."""
    return _native.load(str(path))


def _vertices(vertices):
    v = _np.asarray(vertices)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vertices must be an (N,3) array, got shape {v.shape}")
    if v.dtype.kind not in "fiu":
        raise ValueError(f"vertices must be float32 or float64, got dtype {v.dtype}")
    # No copy when already C-contiguous float64 (float32 widens exactly).
    return _np.ascontiguousarray(v, dtype=_np.float64)


def _check_range(a):
    if a.size and (a.min() < 0 or a.max() > 0xFFFFFFFF):
        raise ValueError("faces: vertex index out of range (negative or above 2^32-1)")


def _faces(faces):
    """(faces (F,k) C-contiguous uint32, None, None) for an array, or
    (None, offsets, indices) for a list of polygons."""
    if isinstance(faces, _np.ndarray):
        f = faces
        if f.ndim != 2 or f.shape[1] not in (3, 4):
            raise ValueError(f"faces must be an (F,3) or (F,4) integer array or a list of polygons, got shape {f.shape}")
        if f.dtype.kind not in "iu":
            raise ValueError(f"faces must be integers, got dtype {f.dtype}")
        if f.dtype == _np.uint32:
            return _np.ascontiguousarray(f), None, None
        _check_range(f)
        if f.dtype == _np.int32 and f.flags.c_contiguous:
            return f.view(_np.uint32), None, None  # non-negative: the same bits, no copy
        return _np.ascontiguousarray(f, dtype=_np.uint32), None, None
    polys = [list(p) for p in faces]
    lens = [len(p) for p in polys]
    arr = _np.asarray([i for p in polys for i in p], dtype=_np.int64)
    _check_range(arr)
    off = _np.concatenate([[0], _np.cumsum(lens)]).astype(_np.uint32)
    return None, off, arr.astype(_np.uint32)


class Primitive:
    """One primitive: `kind`, its parameters as in the JSON contract (`params`, also
    as attributes; a prism's `shift_z`, which the JSON leaves out when it is zero, is
    always there), a 4x4 `transform` (local frame to world) and `volume`."""

    def __init__(self, native, level, index, data, transform, volume):
        self._native, self._level, self._index = native, level, index
        self.params = dict(data)
        self.kind = self.params.get("kind")
        if self.kind == "prism":
            self.params.setdefault("shift_z", 0.0)
        self.transform = _np.asarray(transform, dtype=_np.float64)
        self.volume = volume

    def __getattr__(self, name):
        try:
            return self.__dict__["params"][name]
        except KeyError:
            raise AttributeError(name) from None

    def to_mesh(self, detail=16):
        """Conservative tessellation (encloses the primitive): (vertices (V,3), polygons)."""
        return self._native.tessellate(self._level, self._index, detail)

    def __repr__(self):
        return f"Primitive(kind={self.kind!r}, volume={self.volume:.6g})"


class Level:
    """One target's result: `target`, `primitives`."""

    def __init__(self, native, level):
        self._doc = _json.loads(native.to_json(level))
        vols, tfs = native.volumes(level), native.transforms(level)
        prims = self._doc["primitives"]
        self.primitives = [Primitive(native, level, i, prims[i], tfs[i], vols[i]) for i in range(len(prims))]
        self.target = self._doc.get("target")

    def __repr__(self):
        return f"Level(primitives={len(self.primitives)})"


class Result:
    """A decomposition: `levels`, `stats`, `to_json(level)`, `export(path, level)`."""

    def __init__(self, native):
        self._native = native
        self.levels = [Level(native, i) for i in range(native.level_count())]
        self.stats = self.levels[0]._doc.get("stats", {}) if self.levels else {}

    def to_json(self, level=0):
        """The CLI's JSON document (`primdecomp decompose`) of one level."""
        return self._native.to_json(level)

    def export(self, path, level=0):
        """Write one level in the format named by the extension (.json, .obj, .gltf,
        .glb, .urdf, .usda, .tscn, .xml = MJCF). Returns the files written."""
        return self._native.export(str(path), level)


def decompose(vertices, faces, progress=None, **settings):
    """Decompose a mesh. `vertices`: (N,3) float array (float32/float64, any layout);
    `faces`: (F,3)/(F,4) integer array or list of polygons. `settings`: the library's
    `Params` fields (targets, kinds, weights, min_extent, ...), library defaults
    otherwise: without `targets`, `tolerance` or `max_bytes`, the fewest primitives
    within the default tolerance (as `primdecomp decompose`). `tolerance="1%"` (or a
    distance in input units) gives the fewest primitives all within it,
    `max_bytes=4096` the closest fit in that many bytes (one value, or a list for one
    level each, with `targets` as the count cap); `targets=64` asks for a count.
    `progress(stage, fraction)` is called from the calling thread, or
    `progress(stage, fraction, seconds_left)` when it takes three arguments
    (`seconds_left`: the whole run's estimated time left, None until known)."""
    v = _vertices(vertices)
    arr, off, idx = _faces(faces)
    return Result(_native.decompose(v, arr, off, idx, _settings(settings), _progress(progress)))


def _progress(callback):
    """The callback as the native side calls it, with three arguments (stage, the
    stage's fraction, seconds left): one of two arguments is wrapped."""
    if callback is None:
        return None
    try:
        params = list(_inspect.signature(callback).parameters.values())
    except (TypeError, ValueError):
        return lambda stage, fraction, left: callback(stage, fraction)
    positional = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    if any(p.kind == p.VAR_POSITIONAL for p in params) or len(positional) >= 3:
        return callback
    return lambda stage, fraction, left: callback(stage, fraction)


def _tolerance(t):
    """"1%" (of the bounding-box diagonal) or a distance in input units, as the
    library's Tolerance; a dict ({"units": d} / {"diagonal": f}) is passed on."""
    if isinstance(t, str) and t.strip().endswith("%"):
        try:
            return {"diagonal": float(t.strip()[:-1]) / 100.0}
        except ValueError:
            raise ValueError(f"tolerance: expected a distance or a percentage like '1%', got {t!r}") from None
    if isinstance(t, (int, float)) and not isinstance(t, bool):
        return {"units": float(t)}
    return t


def _settings(settings):
    settings = dict(settings)
    # Targets in the user's terms: one value or a list; tolerances as "1%" or units.
    for key in ("targets", "tolerance", "max_bytes"):
        v = settings.get(key)
        if v is not None and (isinstance(v, (str, int, float, dict)) and not isinstance(v, bool)):
            settings[key] = [v]
    if "tolerance" in settings and isinstance(settings["tolerance"], (list, tuple)):
        settings["tolerance"] = [_tolerance(t) for t in settings["tolerance"]]
    try:
        return _json.dumps(settings, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise ValueError(f"invalid settings: {e}") from None


def decompose_file(path, progress=None, **settings):
    """Decompose the mesh in a file with the CLI's own loader: the primitives equal
    `primdecomp decompose PATH` byte for byte in to_json(), as decompose(*load(path))
    does, without handing the arrays to Python."""
    return Result(_native.decompose_path(str(path), _settings(settings), _progress(progress)))


def as_hulls(vertices, faces, progress=None, **settings):
    """Like coacd.run_coacd: [[vertices (V,3), triangles (T,3)], ...] of the first
    level's primitives, each the conservative tessellation, triangulated."""
    res = decompose(vertices, faces, progress=progress, **settings)
    out = []
    for p in res.levels[0].primitives if res.levels else []:
        pv, polys = p.to_mesh()
        tris = [[poly[0], poly[k], poly[k + 1]] for poly in polys for k in range(1, len(poly) - 1)]
        out.append([pv, _np.asarray(tris, dtype=_np.int64).reshape(-1, 3)])
    return out
