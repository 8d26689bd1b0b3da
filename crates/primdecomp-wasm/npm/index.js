// primdecomp for JavaScript: convex primitive decomposition of 3D meshes, in
// WebAssembly (one thread, no SharedArrayBuffer), for node and browsers.
//
//   import { decompose, loadMesh } from 'primdecomp';
//   const result = decompose(vertices, indices, { targets: [64] });
//   for (const p of result.primitives) if (p.kind === 'box') console.log(p.center, p.half_extents);
//   fs.writeFileSync('colliders.glb', result.toGltf());
//
// The engine is the Rust core built for wasm32-unknown-unknown (primdecomp_wasm.js
// and primdecomp_wasm_bg.wasm, made by wasm-bindgen); this module loads it once (top-
// level await) and gives it a JavaScript face: typed primitives, the CLI's JSON,
// exports, errors as PrimdecompError.
import initEngine, * as engine from './primdecomp_wasm.js';

const wasmUrl = new URL('./primdecomp_wasm_bg.wasm', import.meta.url);
const inNode = typeof process !== 'undefined' && !!process.versions && !!process.versions.node;

if (inNode) {
  // Node's fetch cannot read file: URLs; read the file instead.
  const fsName = 'node:fs/promises';
  const { readFile } = await import(/* @vite-ignore */ /* webpackIgnore: true */ fsName);
  await initEngine({ module_or_path: await readFile(wasmUrl) });
} else {
  await initEngine({ module_or_path: wasmUrl });
}

/** The library's version, "MAJOR.MINOR.PATCH". */
export const version = engine.version();

/** Bad input or settings (the message names the file and line, or the setting), a
 * cancelled run, or an internal error (`internal` true: a bug; the engine is reset). */
export class PrimdecompError extends Error {
  constructor(message, internal = false) {
    super(message);
    this.name = 'PrimdecompError';
    this.internal = internal;
  }
}

// Bumped when the engine is reset after a trap: objects made before refer to memory
// that is gone.
let generation = 0;

function call(f) {
  try {
    return f();
  } catch (e) {
    if (e instanceof WebAssembly.RuntimeError) {
      let why = null;
      try {
        why = engine.takePanic();
      } catch (_) {
        // The trapped instance cannot say more.
      }
      engine.__wbg_reset_state();
      generation++;
      throw new PrimdecompError(
        `internal error in primdecomp (a bug, please report it): ${why || e.message}; the engine was reset`,
        true
      );
    }
    if (e instanceof PrimdecompError) throw e;
    throw new PrimdecompError(e && e.message !== undefined ? e.message : String(e));
  }
}

function live(obj, what) {
  if (obj._generation !== generation)
    throw new PrimdecompError(`this ${what} was made before the engine was reset after an internal error: make it again`);
  if (!obj._raw) throw new PrimdecompError(`this ${what} was freed`);
  return obj._raw;
}

/** A mesh ready to decompose, read by the library's own parsers or built from arrays. */
export class Mesh {
  constructor(raw) {
    this._raw = raw;
    this._generation = generation;
  }
  get faceCount() {
    return live(this, 'mesh').faceCount;
  }
  get vertexCount() {
    return live(this, 'mesh').vertexCount;
  }
  /** The name results record as `input.path`. */
  get path() {
    return live(this, 'mesh').path ?? null;
  }
  /** Every vertex relative to `centre()`, and the faces fanned into triangles (for drawing). */
  triangles() {
    const m = live(this, 'mesh');
    return call(() => ({ positions: m.trianglePositions(), indices: m.triangleIndices(), centre: Array.from(m.centre()) }));
  }
  /** Frees the engine's copy now (otherwise when garbage-collected). */
  free() {
    if (this._raw && this._generation === generation) this._raw.free();
    this._raw = null;
  }
}

/**
 * Reads a mesh file's bytes (OBJ, PLY, STL, OFF, glTF with embedded buffers, GLB);
 * `name`'s extension says the format and results record it as the input's path.
 */
export function loadMesh(bytes, name) {
  if (typeof name !== 'string') throw new PrimdecompError('loadMesh(bytes, name): name is the file name, e.g. "part.stl"');
  const view = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
  return new Mesh(call(() => engine.parseMesh(view, name)));
}

/** A mesh from vertex coordinates (x, y, z each) and indices: triangles, or polygons
 * of `faceSizes[i]` corners (kept whole, as the file readers keep them). */
export function meshFromArrays(vertices, indices, { faceSizes, name } = {}) {
  if (!(indices instanceof Uint32Array)) throw new PrimdecompError('indices must be a Uint32Array');
  const sizes = faceSizes ? Uint32Array.from(faceSizes) : new Uint32Array(0);
  const path = name ?? undefined;
  if (vertices instanceof Float64Array) return new Mesh(call(() => engine.meshFromF64(vertices, indices, sizes, path)));
  if (vertices instanceof Float32Array) return new Mesh(call(() => engine.meshFromF32(vertices, indices, sizes, path)));
  throw new PrimdecompError('vertices must be a Float32Array or a Float64Array (x, y, z per vertex)');
}

function settingsText(settings) {
  if (settings === undefined || settings === null) return '{}';
  if (typeof settings === 'string') return settings;
  return JSON.stringify(settings);
}

/**
 * Decomposes a mesh into convex primitives.
 *
 *   decompose(vertices, indices, settings?, options?)  // Float32Array | Float64Array, Uint32Array
 *   decompose(mesh, settings?, options?)               // a Mesh from loadMesh or meshFromArrays
 *
 * `settings` is the `settings` object a result file carries, or any part of it
 * (`{ targets: [64] }`, `{ tolerance: [{ diagonal: 0.01 }] }`, `{ max_bytes: [4096] }`),
 * a JSON string of it, or nothing for the default: the fewest primitives within 2%
 * of the mesh's diagonal. `options`: `faceSizes` (polygons), `name` (recorded as
 * `input.path`), `onProgress(stage, fraction)` (return `false` to cancel).
 * The primitives are the CLI's for the same mesh and settings.
 */
export function decompose(...args) {
  let mesh;
  let own = false;
  let rest;
  if (args[0] instanceof Mesh) {
    mesh = args[0];
    rest = args.slice(1);
  } else {
    const [vertices, indices, settings, options = {}] = args;
    mesh = meshFromArrays(vertices, indices, options);
    own = true;
    rest = [settings, options];
  }
  const [settings, options = {}] = rest;
  // What the callback throws stops the run and is thrown from here unchanged.
  let thrown = null;
  const progress = options.onProgress
    ? (stage, fraction) => {
        try {
          return options.onProgress(stage, fraction);
        } catch (e) {
          thrown = { e };
          return false;
        }
      }
    : undefined;
  try {
    const raw = live(mesh, 'mesh');
    return new Result(call(() => engine.decompose(raw, settingsText(settings), progress)));
  } catch (e) {
    throw thrown ? thrown.e : e;
  } finally {
    if (own) mesh.free();
  }
}

function level(doc) {
  const d = doc.stats.distance;
  return {
    target: doc.settings.target,
    primitives: doc.primitives,
    counts: doc.stats.counts,
    bytes: doc.stats.bytes,
    distance: d ? d.worst : null,
    // The JSON says "solid" under `solid: true` on a closed mesh; absent: the surface.
    measuredTo: d ? (d.measured_to === 'solid' ? 'solid' : 'mesh') : null,
    tolerance: d && d.tolerance !== undefined ? d.tolerance : null,
    maxBytes: d && d.max_bytes !== undefined ? d.max_bytes : null,
    limitedBy: d && d.limited_by !== undefined ? d.limited_by : null
  };
}

const TEXT_FORMATS = new Set(['json', 'obj', 'gltf', 'mjcf', 'urdf', 'usda', 'usd', 'tscn']);

/** A decomposition: one level per target, each with its primitives. */
export class Result {
  constructor(raw) {
    this._raw = raw;
    this._generation = generation;
    this._docs = [];
    for (let i = 0; i < raw.levelCount; i++) this._docs.push(call(() => raw.json(i)));
    const parsed = this._docs.map((d) => JSON.parse(d));
    /** One per target, in the order given. */
    this.levels = parsed.map(level);
    /** The input's description (`path`, `faces`, `vertices`, `aabb_min`, `aabb_max`). */
    this.input = parsed[0].input;
    /** Every effective setting of the run (a result file's `settings`). */
    this.settings = parsed[0].settings;
  }
  /** The first level's primitives. */
  get primitives() {
    return this.levels[0].primitives;
  }
  /** The first level's summary values. */
  get count() {
    return this.levels[0].primitives.length;
  }
  get bytes() {
    return this.levels[0].bytes;
  }
  get distance() {
    return this.levels[0].distance;
  }
  get measuredTo() {
    return this.levels[0].measuredTo;
  }
  /**
   * A level's JSON document as a string: byte for byte the file
   * `primdecomp decompose` writes for the same input and settings.
   */
  toJSON(level = 0) {
    const d = this._docs[level];
    if (d === undefined) throw new PrimdecompError(`level ${level} out of range: the result has ${this._docs.length} levels`);
    return d;
  }
  /**
   * A level as glTF 2.0 with physics extensions: a GLB (Uint8Array) by default, the
   * .gltf text with `binary: false`. Options: `level`, `physics` ('khr' or 'omi'),
   * `up` ('y' or 'z': the result's up axis), `scale`, `preview` (coloured meshes of
   * the colliders), `model`.
   */
  toGltf(options = {}) {
    return this.export(options.binary === false ? 'gltf' : 'glb', options);
  }
  /**
   * A level in `format` as `primdecomp decompose --export` writes it: 'json', 'obj',
   * 'gltf', 'glb', 'mjcf', 'urdf', 'usda', 'tscn'; text formats as a string, GLB as a
   * Uint8Array. Options as for toGltf, plus `urdfCapsule` and `detail`.
   */
  export(format, options = {}) {
    const lv = options.level ?? 0;
    const f = String(format).toLowerCase();
    if (f === 'json') return this.toJSON(lv);
    const raw = live(this, 'result');
    const up = String(options.up ?? 'y').toLowerCase();
    if (up !== 'y' && up !== 'z') throw new PrimdecompError(`up: expected 'y' or 'z', got '${options.up}'`);
    const physics = String(options.physics ?? 'khr').toLowerCase();
    if (physics !== 'khr' && physics !== 'omi') throw new PrimdecompError(`physics: expected 'khr' or 'omi', got '${options.physics}'`);
    const bytes = call(() =>
      raw.export(lv, f, options.model ?? 'primdecomp', up === 'z', options.scale ?? 1, physics === 'omi', !!options.preview, !!options.urdfCapsule, options.detail ?? 16)
    );
    return TEXT_FORMATS.has(f) ? new TextDecoder().decode(bytes) : bytes;
  }
  /**
   * The conservative tessellation of a level's primitives (each contains the exact
   * primitive), relative to the mesh's bounding-box centre `centre` ([x, y, z]): `positions`
   * (Float32Array), `indices` (Uint32Array, triangles), `starts` (primitive i's
   * triangles are starts[i]..starts[i+1]) and `kinds` (0 box … 5 prism).
   */
  tessellate(level = 0, detail = 16) {
    const raw = live(this, 'result');
    return call(() => {
      const t = raw.tessellate(level, detail);
      const out = { positions: t.positions(), indices: t.indices(), starts: t.starts(), kinds: t.kinds(), centre: Array.from(raw.centre()) };
      t.free();
      return out;
    });
  }
  /** Frees the engine's copy now (otherwise when garbage-collected). */
  free() {
    if (this._raw && this._generation === generation) this._raw.free();
    this._raw = null;
  }
}

/** The primitive kinds, in the order of `tessellate().kinds` and every count. */
export const KINDS = Object.freeze(['box', 'sphere', 'capsule', 'cylinder', 'frustum', 'prism']);

/** For the package's own tests: makes the engine panic, to show that the panic comes
 * back as a PrimdecompError (internal) and the engine works again after. */
export function _selfTestPanic() {
  return call(() => engine.selfTestPanic());
}
