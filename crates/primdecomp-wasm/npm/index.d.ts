// Types of the primdecomp npm package (index.js). Primitives carry the JSON
// contract's names (`half_extents`, `radius0`, …): a primitive here is an entry of
// a result file's `primitives`, numbers exact.

export type Vec3 = [number, number, number];
/** Unit quaternion, scalar last (x, y, z, w), local to world. */
export type Quat = [number, number, number, number];

/** An oriented box. */
export interface Box {
  kind: 'box';
  center: Vec3;
  rotation: Quat;
  half_extents: Vec3;
  /** Input faces it was fitted to. */
  faces: number;
}
/** A ball. */
export interface Sphere {
  kind: 'sphere';
  center: Vec3;
  radius: number;
  faces: number;
}
/** The segment p0–p1 swept by a ball. */
export interface Capsule {
  kind: 'capsule';
  p0: Vec3;
  p1: Vec3;
  radius: number;
  faces: number;
}
/** A capped cylinder between cap centres p0 and p1. */
export interface Cylinder {
  kind: 'cylinder';
  p0: Vec3;
  p1: Vec3;
  radius: number;
  faces: number;
}
/** A truncated cone: radius0 at p0, radius1 at p1. */
export interface Frustum {
  kind: 'frustum';
  p0: Vec3;
  p1: Vec3;
  radius0: number;
  radius1: number;
  faces: number;
}
/** A trapezoidal prism: extruded along local x (half_x), its y–z section a trapezoid
 * 2·half_y high with sides 2·half_z_top (at y = +half_y) and 2·half_z_bottom; the top
 * side's midpoint at z = shift_z (absent: 0), the bottom's at −shift_z. */
export interface Prism {
  kind: 'prism';
  center: Vec3;
  rotation: Quat;
  half_x: number;
  half_y: number;
  half_z_top: number;
  half_z_bottom: number;
  shift_z?: number;
  faces: number;
}
export type Primitive = Box | Sphere | Capsule | Cylinder | Frustum | Prism;
export type Kind = Primitive['kind'];

/** The primitive kinds, in the order of `tessellate().kinds` and every count. */
export const KINDS: readonly Kind[];

/** A tolerance: a distance in the input's units, or a fraction of its diagonal. */
export type Tolerance = { units: number } | { diagonal: number };

/** Settings: a result file's `settings` object or any part of it (README: decompose). */
export interface Settings {
  /** Target counts, one level each; with a tolerance or byte target, each level's cap. */
  targets?: number[];
  /** Each level's primitives within this distance of the input (fewest that are). */
  tolerance?: Tolerance[];
  /** Each level's bytes (paper's Table 2) at most this many. */
  max_bytes?: number[];
  /** Split the merge tree where a primitive stands farthest (implied by tolerance and max_bytes). */
  cut?: boolean;
  /** Allowed kinds. */
  kinds?: Record<Kind, boolean>;
  /** Per-kind cost factors. */
  weights?: Record<Kind, number>;
  /** Every other setting of the JSON contract. */
  [setting: string]: unknown;
}

export interface DecomposeOptions {
  /** Corners of each polygon (indices holds them in order); absent: triangles. */
  faceSizes?: ArrayLike<number>;
  /** Recorded as the result's `input.path`. */
  name?: string;
  /** Called as the run goes; return false to cancel (a PrimdecompError "cancelled"). */
  onProgress?: (stage: 'dedup' | 'adjacency' | 'quadrics' | 'seed' | 'merge' | 'postprocess', fraction: number) => boolean | void;
}

/** One level of a result. */
export interface Level {
  /** The target count (the cap of a tolerance or byte target). */
  target: number;
  primitives: Primitive[];
  counts: Record<Kind, number>;
  /** Storage by the paper's Table 2 (4 bytes a float). */
  bytes: number;
  /** For a cut of the merge tree: an upper bound of the farthest any primitive stands from the input (input units); null for a greedy level. */
  distance: number | null;
  /** What `distance` is measured to: 'solid' with `solid: true` on a closed mesh (a
   * primitive's points inside the mesh stand at 0), else 'mesh' (its surface); null
   * for a greedy level. The JSON's `stats.distance.measured_to`. */
  measuredTo: 'solid' | 'mesh' | null;
  /** The tolerance asked for, input units. */
  tolerance: number | null;
  maxBytes: number | null;
  /** What stopped the level short of its tolerance. */
  limitedBy: 'count' | 'bytes' | 'faces' | null;
}

export interface ExportOptions {
  level?: number;
  /** glTF physics extensions: Khronos (default) or OMI (Godot 4). */
  physics?: 'khr' | 'omi';
  /** The result's up axis. */
  up?: 'y' | 'z';
  /** Length multiplier (input units to metres). */
  scale?: number;
  /** glTF: coloured preview meshes of the colliders. */
  preview?: boolean;
  /** URDF: <capsule> instead of a cylinder and two spheres. */
  urdfCapsule?: boolean;
  /** Segments around circles of shapes written as hulls. */
  detail?: number;
  /** The model's name (MJCF model, URDF robot, USD prim, Godot root, glTF node prefix). */
  model?: string;
}

export interface Tessellation {
  /** Vertices relative to `centre` (x, y, z each). */
  positions: Float32Array;
  /** Three vertex indices per triangle. */
  indices: Uint32Array;
  /** Primitive i's triangles are starts[i]..starts[i+1]. */
  starts: Uint32Array;
  /** Each primitive's kind, an index into KINDS. */
  kinds: Uint8Array;
  /** The mesh's bounding-box centre. */
  centre: Vec3;
}

export class PrimdecompError extends Error {
  /** True for an internal error (a bug): the engine was reset, older meshes and results are gone. */
  readonly internal: boolean;
}

export class Mesh {
  readonly faceCount: number;
  readonly vertexCount: number;
  readonly path: string | null;
  /** Vertices relative to `centre` and the faces fanned into triangles, for drawing. */
  triangles(): { positions: Float32Array; indices: Uint32Array; centre: Vec3 };
  free(): void;
}

export class Result {
  readonly levels: Level[];
  readonly input: { path: string | null; faces: number; vertices: number; aabb_min: Vec3; aabb_max: Vec3 };
  readonly settings: Settings;
  /** The first level's primitives, count, bytes, distance and what it is measured to. */
  readonly primitives: Primitive[];
  readonly count: number;
  readonly bytes: number;
  readonly distance: number | null;
  readonly measuredTo: 'solid' | 'mesh' | null;
  /** A level's JSON document: the CLI's file for the same input and settings, byte for byte. */
  toJSON(level?: number): string;
  /** GLB bytes, or the .gltf text with `binary: false`. */
  toGltf(options?: ExportOptions & { binary?: true }): Uint8Array;
  toGltf(options: ExportOptions & { binary: false }): string;
  /** 'glb' as bytes; 'json', 'obj', 'gltf', 'mjcf', 'urdf', 'usda', 'tscn' as text. */
  export(format: 'glb', options?: ExportOptions): Uint8Array;
  export(format: 'json' | 'obj' | 'gltf' | 'mjcf' | 'urdf' | 'usda' | 'tscn', options?: ExportOptions): string;
  tessellate(level?: number, detail?: number): Tessellation;
  free(): void;
}

export const version: string;

/** A mesh file's bytes (OBJ, PLY, STL, OFF, glTF with embedded buffers, GLB); the name's extension says the format. */
export function loadMesh(bytes: Uint8Array | ArrayBuffer, name: string): Mesh;
/** A mesh from coordinates (x, y, z each) and indices (triangles, or polygons with faceSizes). */
export function meshFromArrays(vertices: Float32Array | Float64Array, indices: Uint32Array, options?: { faceSizes?: ArrayLike<number>; name?: string }): Mesh;
/** Decomposes a mesh into convex primitives (the CLI's primitives for the same mesh and settings). */
export function decompose(vertices: Float32Array | Float64Array, indices: Uint32Array, settings?: Settings | string, options?: DecomposeOptions): Result;
export function decompose(mesh: Mesh, settings?: Settings | string, options?: Omit<DecomposeOptions, 'faceSizes' | 'name'>): Result;
/** For the package's own tests. */
export function _selfTestPanic(): void;
