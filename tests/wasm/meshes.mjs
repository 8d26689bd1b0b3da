// Made-up meshes for the JavaScript tests (tests/wasm and tests/browser), written as
// OBJ text whose numbers parse back exactly (JavaScript prints the shortest
// round-tripping decimal): a playground whose parts are each one primitive kind (a
// slab, a ball, a capsule, a cylinder, a truncated cone and a trapezoidal ramp),
// and a ~100k-face terrain for timings.

class Obj {
  constructor() {
    this.lines = [];
    this.count = 0;
  }
  object(name) {
    this.lines.push(`o ${name}`);
  }
  vertex(x, y, z) {
    this.lines.push(`v ${x} ${y} ${z}`);
    return ++this.count;
  }
  face(...ids) {
    this.lines.push(`f ${ids.join(' ')}`);
  }
  text() {
    return this.lines.join('\n') + '\n';
  }
}

/** A closed surface of revolution about +y through (cx, cz): `profile` is [radius,
 * height] from bottom to top (radius 0 closes a pole); `segments` around. */
function revolve(obj, name, cx, cz, profile, segments) {
  obj.object(name);
  const rings = profile.map(([r, y]) => {
    if (r === 0) return [obj.vertex(cx, y, cz)];
    const ring = [];
    for (let j = 0; j < segments; j++) {
      const a = (2 * Math.PI * j) / segments;
      ring.push(obj.vertex(cx + r * Math.cos(a), y, cz + r * Math.sin(a)));
    }
    return ring;
  });
  const first = rings[0];
  const last = rings[rings.length - 1];
  if (first.length > 1) obj.face(...first); // bottom cap, facing down
  for (let i = 0; i + 1 < rings.length; i++) {
    const a = rings[i];
    const b = rings[i + 1];
    for (let j = 0; j < segments; j++) {
      const j1 = (j + 1) % segments;
      if (a.length === 1) obj.face(a[0], b[j1], b[j]);
      else if (b.length === 1) obj.face(a[j], a[j1], b[0]);
      else obj.face(a[j], a[j1], b[j1], b[j]);
    }
  }
  if (last.length > 1) obj.face(...[...last].reverse()); // top cap, facing up
}

/** A box's six quads, wound outward, over its corners c (bit 0: x, bit 1: y, bit 2:
 * z; set = the high side). */
export const BOX_QUADS = [
  [0, 4, 6, 2],
  [1, 3, 7, 5],
  [0, 1, 5, 4],
  [2, 6, 7, 3],
  [0, 2, 3, 1],
  [4, 5, 7, 6]
];

/** An axis-aligned box from lo to hi as six quads. */
function box(obj, name, lo, hi) {
  obj.object(name);
  const v = [];
  for (let c = 0; c < 8; c++) v.push(obj.vertex(c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]));
  for (const q of BOX_QUADS) obj.face(...q.map((i) => v[i]));
}

/** A hemisphere-capped profile: [radius, height] pairs of a capsule standing on y0. */
function capsuleProfile(r, length, y0, rings) {
  const out = [[0, y0]];
  for (let i = 1; i < rings; i++) {
    const a = -Math.PI / 2 + (Math.PI / 2) * (i / rings);
    out.push([r * Math.cos(a), y0 + r + r * Math.sin(a)]);
  }
  for (let i = 0; i <= rings; i++) {
    const a = (Math.PI / 2) * (i / rings);
    out.push([r * Math.cos(a), y0 + r + length + r * Math.sin(a)]);
  }
  out[out.length - 1] = [0, y0 + 2 * r + length];
  return out;
}

/** The playground: every part a different primitive kind, on a slab, +y up. */
export function playground() {
  const obj = new Obj();
  box(obj, 'slab', [-7, -0.4, -4], [7, 0, 4]);
  const ball = [[0, 0]];
  for (let i = 1; i < 12; i++) {
    const a = -Math.PI / 2 + (Math.PI * i) / 12;
    ball.push([0.9 * Math.cos(a), 0.9 + 0.9 * Math.sin(a)]);
  }
  ball.push([0, 1.8]);
  revolve(obj, 'ball', -4.5, 0, ball, 24);
  revolve(obj, 'capsule', -1.8, 1.6, capsuleProfile(0.45, 1.6, 0, 6), 20);
  revolve(obj, 'cylinder', 1, -1.5, [[0.7, 0], [0.7, 1.4]], 32);
  revolve(obj, 'cone', 4.2, 1.2, [[1.1, 0], [0.35, 1.5]], 32);
  // A ramp: a trapezoidal section (2.4 wide at the bottom, 0.8 at the top, 0.9 high)
  // extruded 2.5 along z.
  obj.object('ramp');
  const sec = [
    [-1.2, 0],
    [1.2, 0],
    [0.4, 0.9],
    [-0.4, 0.9]
  ];
  const near = sec.map(([x, y]) => obj.vertex(1 + x, y, 1.2));
  const far = sec.map(([x, y]) => obj.vertex(1 + x, y, 3.7));
  obj.face(...near);
  obj.face(...[...far].reverse());
  for (let i = 0; i < 4; i++) obj.face(near[(i + 1) % 4], near[i], far[i], far[(i + 1) % 4]);
  return obj.text();
}

/** A trefoil knot's tube: `rings` rings of `around` vertices, quads between them (a
 * curved shape whose count follows the tolerance). */
export function knot(rings = 96, around = 12) {
  const obj = new Obj();
  obj.object('knot');
  const curve = (t) => [Math.sin(t) + 2 * Math.sin(2 * t), Math.cos(t) - 2 * Math.cos(2 * t), -Math.sin(3 * t)];
  for (let i = 0; i < rings; i++) {
    const t = (2 * Math.PI * i) / rings;
    const p = curve(t);
    const q = curve(t + 1e-4);
    const d = q.map((x, k) => x - p[k]);
    const dl = Math.hypot(...d);
    const u = d.map((x) => x / dl);
    const nl = Math.hypot(u[1], u[0]);
    const n = [u[1] / nl, -u[0] / nl, 0];
    const b = [u[1] * n[2] - u[2] * n[1], u[2] * n[0] - u[0] * n[2], u[0] * n[1] - u[1] * n[0]];
    for (let j = 0; j < around; j++) {
      const a = (2 * Math.PI * j) / around;
      obj.vertex(...[0, 1, 2].map((k) => p[k] + 0.45 * (Math.cos(a) * n[k] + Math.sin(a) * b[k])));
    }
  }
  for (let i = 0; i < rings; i++)
    for (let j = 0; j < around; j++) {
      const id = (r, s) => 1 + (r % rings) * around + (s % around);
      obj.face(id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
    }
  return obj.text();
}

/** A rolling terrain of 2·n² triangles (n = 224: 100,352 faces) on an integer grid,
 * heights on a 1/256 grid. */
export function terrain(n = 224) {
  const obj = new Obj();
  obj.object('terrain');
  const id = (x, z) => 1 + z * (n + 1) + x;
  for (let z = 0; z <= n; z++)
    for (let x = 0; x <= n; x++) {
      const h = 6 * Math.sin(x / 17) * Math.cos(z / 23) + 2 * Math.sin((x + 2 * z) / 7) + ((x * 7 + z * 13) % 5) / 10;
      obj.vertex(x / 4, Math.round(256 * h) / 256, z / 4);
    }
  for (let z = 0; z < n; z++)
    for (let x = 0; x < n; x++) {
      obj.face(id(x, z), id(x + 1, z), id(x + 1, z + 1));
      obj.face(id(x, z), id(x + 1, z + 1), id(x, z + 1));
    }
  return obj.text();
}

/** OBJ text's vertices ([x, y, z] each), polygons (0-based ids) and their triangle
 * fans, for the tests that write the same mesh in other formats. */
export function parseObj(text) {
  const vertices = [];
  const faces = [];
  for (const line of text.split('\n')) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'v') vertices.push(w.slice(1, 4).map(Number));
    if (w[0] === 'f') faces.push(w.slice(1).map((x) => parseInt(x, 10) - 1));
  }
  const triangles = faces.flatMap((f) => f.slice(1, -1).map((_, k) => [f[0], f[k + 1], f[k + 2]]));
  return { vertices, faces, triangles };
}
