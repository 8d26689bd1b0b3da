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
import math as _math

import numpy as _np

from . import _native

__all__ = ["load", "decompose", "decompose_file", "as_hulls", "Result", "Level", "Primitive", "batch", "ray_tiles"]


def load(path):
    """Load a mesh file (every format the core reads: OBJ, PLY, STL, OFF, glTF, GLB).

    Returns (vertices, faces): vertices an (N,3) float64 array holding the file's
    coordinates exactly; faces an (F,k) uint32 array when every face has k corners,
    else a list of polygons. `decompose(*load(path))` equals the CLI's primitives.

    Raises FileNotFoundError, PermissionError, IsADirectoryError (OSError) for the
    file system, ValueError for a file that is not a mesh we read (naming the line or
    byte where it went wrong)."""
    return _native.load(_path(path))


def _path(path):
    """A str or path-like as str (TypeError otherwise, as open() does)."""
    import os

    p = os.fspath(path)
    return p.decode() if isinstance(p, bytes) else p


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
        def show(v):
            if isinstance(v, (list, tuple)):
                return "(" + ", ".join(f"{x:.4g}" for x in v) + ")"
            return f"{v:.4g}"

        skip = {"kind", "faces", "rotation"}
        if self.kind == "prism" and self.params.get("shift_z") == 0.0:
            skip.add("shift_z")
        fields = ", ".join(f"{k}={show(v)}" for k, v in self.params.items() if k not in skip)
        return f"Primitive({self.kind}: {fields}, volume={self.volume:.4g}, faces={self.params.get('faces')})"


class Level:
    """One level of a result: `target` (the count asked, or the cap of a tolerance or
    byte target), `primitives`, `counts` by kind, `bytes` (the paper's Table 2) and,
    for a cut of the merge tree, `distance` (the farthest a primitive stands from the
    mesh, input units, with what was asked: the JSON's `stats.distance`, else None)
    and `measured_to`: "solid" when that distance is to the mesh's solid (`solid=True`
    on a closed mesh: a primitive's points inside the mesh stand at 0), "mesh" when to
    its surface, None for a greedy level."""

    def __init__(self, native, level):
        self._doc = _json.loads(native.to_json(level))
        vols, tfs = native.volumes(level), native.transforms(level)
        prims = self._doc["primitives"]
        self.primitives = [Primitive(native, level, i, prims[i], tfs[i], vols[i]) for i in range(len(prims))]
        self.target = self._doc["settings"].get("target")
        stats = self._doc["stats"]
        self.counts = {k: n for k, n in stats["counts"].items() if n}
        self.bytes = stats["bytes"]
        self.distance = stats.get("distance")
        # The JSON names the solid; the surface is its absence.
        self.measured_to = None if self.distance is None else self.distance.get("measured_to", "mesh")

    def _asked(self):
        """What the level asked for, in the user's words."""
        d = self.distance or {}
        diag = _diagonal(self._doc)
        if d.get("tolerance") is not None:
            return f"tolerance {_pct(d['tolerance'], diag)}"
        if d.get("max_bytes") is not None:
            return f"bytes {d['max_bytes']}"
        return f"count {self.target}"

    def _summary(self):
        kinds = ", ".join(f"{n} {k}" for k, n in self.counts.items())
        s = f"{self._asked()}: {len(self.primitives)} primitives ({kinds}), {self.bytes} bytes"
        if self.distance:
            where = "outside the solid" if self.measured_to == "solid" else "from the mesh"
            s += f", farthest {_pct(self.distance['worst'], _diagonal(self._doc))} {where}"
        return s

    def __len__(self):
        return len(self.primitives)

    def __repr__(self):
        return f"<primdecomp.Level {self._summary()}>"


class Result:
    """A decomposition: `levels`, `stats`, `to_json(level)`, `export(path, level)`."""

    def __init__(self, native):
        self._native = native
        self.levels = [Level(native, i) for i in range(native.level_count())]
        self.stats = self.levels[0]._doc.get("stats", {}) if self.levels else {}
        self.input = self.levels[0]._doc.get("input", {}) if self.levels else {}

    def __repr__(self):
        inp = self.input
        # A path's line and paragraph separators and control characters would break
        # the line the repr is printed on: shown escaped, as repr() shows them.
        name = "".join(c if c.isprintable() else repr(c)[1:-1] for c in inp.get("path") or "arrays")
        head = f"<primdecomp.Result of {name} ({inp.get('faces')} faces), {len(self.levels)} level"
        head += "s" if len(self.levels) != 1 else ""
        return head + ": " + "; ".join(l._summary() for l in self.levels) + ">"

    def to_json(self, level=0):
        """The CLI's JSON document (`primdecomp decompose`) of one level."""
        return self._native.to_json(level)

    def export(self, path, level=0):
        """Write one level in the format named by the extension (.json, .obj, .gltf,
        .glb, .urdf, .usda, .tscn, .xml = MJCF). Returns the files written."""
        return self._native.export(str(path), level)


def _diagonal(doc):
    inp = doc.get("input", {})
    lo, hi = inp.get("aabb_min"), inp.get("aabb_max")
    if not lo or not hi:
        return None
    return sum((b - a) ** 2 for a, b in zip(lo, hi)) ** 0.5


def _pct(d, diagonal):
    """A distance as a percentage of the diagonal (and in units)."""
    if diagonal:
        return f"{100 * d / diagonal:.3g}% of the diagonal ({d:.4g})"
    return f"{d:.4g}"


def decompose(vertices, faces, progress=None, **settings):
    """Decompose a mesh. `vertices`: (N,3) float array (float32/float64, any layout);
    `faces`: (F,3)/(F,4) integer array or list of polygons. `settings`: the library's
    `Params` fields (targets, kinds, weights, min_extent, ...), library defaults
    otherwise: without `targets`, `tolerance` or `max_bytes`, the fewest primitives
    within the default tolerance (as `primdecomp decompose`). `tolerance="1%"` (or a
    distance in input units) gives the fewest primitives all within it,
    `max_bytes=4096` the closest fit in that many bytes (one value, or a list for one
    level each, with `targets` as the count cap); `targets=64` asks for a count,
    `targets="1%"` for one per hundred faces (as `-n 1%`).
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


_KINDS = ("box", "sphere", "capsule", "cylinder", "frustum", "prism")
_NUMBERS = ("tangent_eps", "min_extent", "max_excess_volume", "remove_thin_boxes", "open_holes",
            "rim_weight", "min_thickness")
_FLAGS = ("remove_nested", "flush_plates", "join_coplanar", "solid", "fill", "greedy", "cut")
_OTHER = ("targets", "tolerance", "max_bytes", "kinds", "weights", "dedup", "reprice", "partitions")


def _number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _listed(v):
    return list(v) if isinstance(v, (list, tuple)) else [v]


def _target(t):
    """A count, or a percentage of the faces ("1%"), as -n takes it: a string is read by
    the library's own parser; a percentage becomes its count once the faces are known."""
    if isinstance(t, int) and not isinstance(t, bool) and t > 0:
        return t
    if isinstance(t, str):
        return _spelled("targets", t)
    raise ValueError(f"targets: expected a positive count, got {t!r}")


def _spelled(key, v):
    """A value as the CLI spells it ("1%", "4K", "exact", "auto", "box"), or a number,
    read by the library's own parser; the JSON of the settings it stands for."""
    if isinstance(v, bool) or not isinstance(v, (str, int, float)):
        raise ValueError(f"{key}: expected a word or a number such as the CLI takes, got {v!r}")
    return _json.loads(_native.spelled(key, str(v)))


def _tolerance(t):
    """"1%" (of the bounding-box diagonal) or a distance in input units, as the
    library's Tolerance ({"units": d} / {"diagonal": f}, also accepted as is)."""
    return t if isinstance(t, dict) else _spelled("tolerance", t)


def _kind(k):
    return _spelled("kind", k)


def _kinds(v):
    """Allowed kinds: names (['box', 'sphere']), or a dict of the kinds to turn on or off."""
    if isinstance(v, dict):
        out = dict.fromkeys(_KINDS, True)
        for k, on in v.items():
            out[_kind(k)] = bool(on)
        return out
    names = {_kind(k) for k in _listed(v)}
    return {k: k in names for k in _KINDS}


def _weights(v):
    """Cost factors per kind: a dict of the kinds to change ({'frustum': 3}), read by the
    library's own reader of the CLI's `--weights kind=w,…` (the others keep their
    defaults)."""
    if not isinstance(v, dict):
        raise ValueError(f"weights: expected a dict of kind to factor such as {{'frustum': 3.0}}, got {v!r}")
    for w in v.values():
        if not _number(w):
            raise ValueError(f"weights: {w!r} is not a number")
        if not _math.isfinite(w):
            raise ValueError("settings: numbers must be finite (no NaN or infinity)")
    return _spelled("weights", ",".join(f"{k}={float(w)!r}" for k, w in v.items()))


def _settings(settings, where="decompose"):
    """The keyword arguments as the library's Params JSON, each checked first so that
    a wrong value is a ValueError in the CLI's words and an unknown name a TypeError."""
    for key in settings:
        if key not in _NUMBERS + _FLAGS + _OTHER:
            raise TypeError(f"{where}() got an unexpected keyword argument {key!r}")
    out = {}
    for key, v in settings.items():
        if v is None and key in ("max_excess_volume", "remove_thin_boxes"):
            out[key] = None
        elif key in _NUMBERS:
            if not _number(v):
                raise ValueError(f"{key}: expected a number, got {v!r}")
            out[key] = float(v)
        elif key in _FLAGS:
            if not isinstance(v, bool):
                raise ValueError(f"{key}: expected True or False, got {v!r}")
            out[key] = v
        elif key == "targets":
            out[key] = [_target(t) for t in _listed(v)]
        elif key == "tolerance":
            out[key] = [_tolerance(t) for t in _listed(v)]
        elif key == "max_bytes":
            out[key] = [_spelled(key, b) for b in _listed(v)]
        elif key == "kinds":
            out[key] = _kinds(v)
        elif key == "weights":
            out[key] = _weights(v)
        elif key in ("dedup", "reprice", "partitions"):
            out[key] = _spelled(key, v)
    try:
        return _json.dumps(out, allow_nan=False)
    except ValueError:
        raise ValueError("settings: numbers must be finite (no NaN or infinity)") from None


def decompose_file(path, progress=None, **settings):
    """Decompose the mesh in a file with the CLI's own loader: the primitives equal
    `primdecomp decompose PATH` byte for byte in to_json(), as decompose(*load(path))
    does, without handing the arrays to Python."""
    return _decompose_file(path, progress, settings)


def _decompose_file(path, progress, settings, stop=None):
    """decompose_file, stopped (KeyboardInterrupt) once `stop` (a threading.Event) is
    set: Ctrl-C reaches only the main thread, which stops runs on other threads so."""
    return Result(_native.decompose_path(_path(path), _settings(settings, "decompose_file"), _progress(progress), stop))


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
