// The npm package in node, proven by a real consumer: Rapier.js
// (@dimforge/rapier3d-compat). For the demo scene and a made-up playground (one part
// of each primitive kind), the package's primitives are compared with the native
// CLI's JSON on the same file and settings, then loaded into Rapier one collider each
// (cuboid, ball, capsule, cylinder; frustums and prisms as convex hulls of their
// conservative tessellation); balls dropped on them must come to rest without any
// ball's centre ever entering or crossing a collider.
//
// Environment: PRIMDECOMP_BIN (the release CLI; default target/release/primdecomp).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import RAPIER from '@dimforge/rapier3d-compat';
import * as primdecomp from 'primdecomp';
import { BOX_QUADS, playground } from './meshes.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..');
const bin = process.env.PRIMDECOMP_BIN || path.join(root, 'target', 'release', 'primdecomp');
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'primdecomp-wasm-test-'));
process.on('exit', () => fs.rmSync(work, { recursive: true, force: true }));
await RAPIER.init();

fs.writeFileSync(path.join(work, 'playground.obj'), playground());
const CASES = [
  { name: 'demo scene, -n 150', file: path.join(root, 'datasets', 'demo_scene.obj'), flags: ['-n', '150'], settings: { targets: [150] } },
  { name: 'demo scene, default (2%)', file: path.join(root, 'datasets', 'demo_scene.obj'), flags: [], settings: {} },
  { name: 'playground, --max-bytes 256', file: path.join(work, 'playground.obj'), flags: ['--max-bytes', '256'], settings: { max_bytes: [256] } },
  { name: 'playground, default (2%)', file: path.join(work, 'playground.obj'), flags: [], settings: {} }
];

function cli(c) {
  const out = path.join(work, `cli_${CASES.indexOf(c)}.json`);
  execFileSync(bin, ['decompose', c.file, '-o', out, '--quiet', ...c.flags], { stdio: ['ignore', 'ignore', 'inherit'] });
  return fs.readFileSync(out, 'utf8');
}

/** Every number in two JSON values, pairwise, with the path to it; structure (keys,
 * lengths, strings, booleans) must agree. */
function numbers(a, b, where, out) {
  if (typeof a === 'number' && typeof b === 'number') return out.push({ where, a, b });
  assert.equal(typeof a, typeof b, `${where}: ${JSON.stringify(a)} vs ${JSON.stringify(b)}`);
  if (Array.isArray(a)) {
    assert.equal(a.length, b.length, `${where}: length`);
    a.forEach((x, i) => numbers(x, b[i], `${where}[${i}]`, out));
  } else if (a && typeof a === 'object') {
    assert.deepEqual(Object.keys(a).sort(), Object.keys(b).sort(), `${where}: keys`);
    for (const k of Object.keys(a)) numbers(a[k], b[k], `${where}.${k}`, out);
  } else assert.equal(a, b, where);
  return out;
}

/** q (x, y, z, w) applied to v. */
function rotate(q, v) {
  const [x, y, z, w] = q;
  const t = [2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])];
  return [v[0] + w * t[0] + (y * t[2] - z * t[1]), v[1] + w * t[1] + (z * t[0] - x * t[2]), v[2] + w * t[2] + (x * t[1] - y * t[0])];
}

/** The points that fix a primitive whatever way it is written down: a box's or
 * prism's corners, a ball's centre and radius, a round kind's two ends with their
 * radii. */
function shape(p) {
  const place = (local) => local.map((l) => rotate(p.rotation, l).map((x, k) => x + p.center[k]));
  switch (p.kind) {
    case 'box': {
      const h = p.half_extents;
      return place([...Array(8).keys()].map((c) => [c & 1 ? h[0] : -h[0], c & 2 ? h[1] : -h[1], c & 4 ? h[2] : -h[2]]));
    }
    case 'prism': {
      const s = p.shift_z || 0;
      const sec = [[p.half_y, s - p.half_z_top], [p.half_y, s + p.half_z_top], [-p.half_y, -s - p.half_z_bottom], [-p.half_y, -s + p.half_z_bottom]];
      return place([-p.half_x, p.half_x].flatMap((x) => sec.map(([y, z]) => [x, y, z])));
    }
    case 'sphere':
      return [[...p.center, p.radius]];
    case 'frustum':
      return [[...p.p0, p.radius0], [...p.p1, p.radius1]];
    default:
      return [[...p.p0, p.radius], [...p.p1, p.radius]];
  }
}

/** The Hausdorff distance between two small point sets (coordinates compared in
 * the max norm). */
function apart(a, b) {
  const d = (x, y) => Math.max(...x.map((v, k) => Math.abs(v - y[k])));
  const one = (x, y) => Math.max(...x.map((p) => Math.min(...y.map((q) => d(p, q)))));
  return Math.max(one(a, b), one(b, a));
}

/** The largest difference between two results' primitives as shapes (the same kind
 * and face count required), and how many are not written identically. */
function compare(a, b) {
  assert.equal(a.length, b.length, 'primitive count');
  let worst = 0;
  let differ = 0;
  a.forEach((p, i) => {
    const q = b[i];
    assert.equal(q.kind, p.kind, `primitive ${i}: kind`);
    assert.equal(q.faces, p.faces, `primitive ${i}: faces`);
    if (JSON.stringify(p) !== JSON.stringify(q)) differ++;
    worst = Math.max(worst, apart(shape(p), shape(q)));
  });
  return { worst, differ };
}
const compared = [];

for (const c of CASES) {
  test(`${c.name}: the package's JSON is the CLI's (same file, same settings)`, () => {
    const expect = cli(c);
    const mesh = primdecomp.loadMesh(fs.readFileSync(c.file), c.file);
    const result = primdecomp.decompose(mesh, c.settings);
    const got = result.toJSON();
    const doc = JSON.parse(expect);
    const mine = JSON.parse(got);
    // Byte for byte, or (where WebAssembly's math library, musl's, and glibc's round
    // a transcendental function a last bit apart: docs/decisions/limits-wasm-libm.md)
    // the same primitives, kinds and face counts, each the same shape within 1e-12 of
    // the diagonal; the same statistics.
    const scale = Math.hypot(...doc.input.aabb_max.map((x, k) => x - doc.input.aabb_min[k]));
    const { worst, differ } = compare(doc.primitives, mine.primitives);
    assert.ok(worst <= 1e-12 * scale, `largest difference between the shapes: ${worst} (diagonal ${scale})`);
    assert.deepEqual({ ...mine.stats, distance: undefined }, { ...doc.stats, distance: undefined }, 'stats');
    assert.deepEqual(mine.settings, doc.settings, 'settings');
    assert.deepEqual(mine.input, doc.input, 'input');
    if (doc.stats.distance) assert.ok(Math.abs(mine.stats.distance.worst - doc.stats.distance.worst) <= 1e-12 * scale, 'distance');
    assert.equal(result.count, doc.primitives.length);
    assert.deepEqual(result.levels[0].counts, doc.stats.counts);
    compared.push({ name: c.name, identical: got === expect, primitives: doc.primitives.length, differ, worst: worst / scale });
    console.log(
      `  ${c.name}: ${doc.primitives.length} primitives; ${got === expect ? 'byte-identical' : `${differ} written differently, the same shapes within ${(worst / scale).toExponential(2)} of the diagonal`}`
    );
    result.free();
    mesh.free();
  });
}

test('every primitive kind becomes a Rapier collider, and dropped balls rest on them without passing through', () => {
  const scenes = [
    // The least share of the balls that must rest on colliders: the playground's parts
    // hold nearly all; on the demo scene most roll off pipes, stairs and the roof.
    { name: 'playground', file: path.join(work, 'playground.obj'), settings: {}, resting: 0.9 },
    { name: 'demo scene', file: path.join(root, 'datasets', 'demo_scene.obj'), settings: { targets: [150] }, resting: 0.2 }
  ];
  const kindsSeen = new Set();
  for (const s of scenes) {
    const result = primdecomp.decompose(primdecomp.loadMesh(fs.readFileSync(s.file), s.file), s.settings);
    const r = drop(result);
    r.kinds.forEach((k) => kindsSeen.add(k));
    console.log(
      `  ${s.name}: ${result.count} colliders (${r.kinds.join(', ')}); ${r.balls} balls after ${r.frames} frames: ${r.onColliders} on colliders, ${r.onGround} on the ground, ${r.through} passed through, ${r.moving} still moving`
    );
    assert.equal(r.through, 0, `${s.name}: balls whose centre entered or crossed a collider: ${r.through} (${r.first})`);
    assert.equal(r.lost, 0, `${s.name}: balls below the ground`);
    assert.ok(r.onColliders >= s.resting * r.balls, `${s.name}: only ${r.onColliders} of ${r.balls} balls rest on the colliders`);
    result.free();
  }
  assert.deepEqual([...kindsSeen].sort(), ['box', 'capsule', 'cylinder', 'frustum', 'prism', 'sphere']);
});

/** The unit quaternion turning +y onto the unit vector d. */
function fromY(d) {
  const [x, y, z] = d;
  if (y < -1 + 1e-12) return { x: 1, y: 0, z: 0, w: 0 };
  const w = 1 + y;
  const n = Math.hypot(z, -x, w);
  return { x: z / n, y: 0, z: -x / n, w: w / n };
}

/** One fixed collider per primitive; returns the colliders' handles and their kinds. */
function colliders(world, result) {
  const t = result.tessellate(0, 16);
  const handles = new Set();
  const kinds = [];
  result.primitives.forEach((p, i) => {
    let desc;
    if (p.kind === 'box') {
      const [x, y, z, w] = p.rotation;
      desc = RAPIER.ColliderDesc.cuboid(...p.half_extents)
        .setTranslation(...p.center)
        .setRotation({ x, y, z, w });
    } else if (p.kind === 'sphere') {
      desc = RAPIER.ColliderDesc.ball(p.radius).setTranslation(...p.center);
    } else if (p.kind === 'capsule' || p.kind === 'cylinder') {
      const d = [0, 1, 2].map((k) => p.p1[k] - p.p0[k]);
      const len = Math.hypot(...d);
      const mid = [0, 1, 2].map((k) => 0.5 * (p.p0[k] + p.p1[k]));
      const half = 0.5 * len;
      desc = (p.kind === 'capsule' ? RAPIER.ColliderDesc.capsule(half, p.radius) : RAPIER.ColliderDesc.cylinder(half, p.radius))
        .setTranslation(...mid)
        .setRotation(len > 0 ? fromY(d.map((x) => x / len)) : { x: 0, y: 0, z: 0, w: 1 });
    } else {
      // Frustums and prisms: the convex hull of the conservative tessellation (which
      // contains the exact primitive), in world coordinates.
      const pts = [];
      for (let tri = t.starts[i]; tri < t.starts[i + 1]; tri++)
        for (let k = 0; k < 3; k++) {
          const v = t.indices[3 * tri + k];
          pts.push(t.positions[3 * v] + t.centre[0], t.positions[3 * v + 1] + t.centre[1], t.positions[3 * v + 2] + t.centre[2]);
        }
      desc = RAPIER.ColliderDesc.convexHull(new Float32Array(pts));
      assert.ok(desc, `primitive ${i} (${p.kind}): Rapier builds its hull`);
    }
    assert.equal(RAPIER.ColliderDesc.prototype.isPrototypeOf(desc), true);
    handles.add(world.createCollider(desc).handle);
    kinds.push(p.kind);
  });
  return { handles, kinds: [...new Set(kinds)].sort() };
}

/** Drops balls on a grid over the result's primitives, where one lies below (a
 * ground slab under them all), and steps Rapier until they rest. */
function drop(result) {
  const lo = result.input.aabb_min;
  const hi = result.input.aabb_max;
  const size = hi.map((x, k) => x - lo[k]);
  const diag = Math.hypot(...size);
  const world = new RAPIER.World({ x: 0, y: -9.81, z: 0 });
  const { handles, kinds } = colliders(world, result);
  const ground = lo[1] - 0.02 * diag;
  world.createCollider(RAPIER.ColliderDesc.cuboid(size[0] + diag, 0.05 * diag, size[2] + diag).setTranslation(0.5 * (lo[0] + hi[0]), ground - 0.05 * diag, 0.5 * (lo[2] + hi[2])));
  const radius = 0.006 * diag;
  const isPrimitive = (c) => handles.has(c.handle);
  // Balls on a grid over the scene 3 radii apart (they must not start overlapping),
  // where a collider lies below the ball.
  world.step();
  const balls = [];
  const nx = Math.max(2, Math.floor(size[0] / (3 * radius)));
  const nz = Math.max(2, Math.floor(size[2] / (3 * radius)));
  for (let i = 0; i < nx; i++)
    for (let j = 0; j < nz; j++) {
      const x = lo[0] + ((i + 0.5) / nx) * size[0];
      const z = lo[2] + ((j + 0.5) / nz) * size[2];
      const y = hi[1] + radius * (2 + 3 * ((i + j) % 4));
      const below = new RAPIER.Ray({ x, y, z }, { x: 0, y: -1, z: 0 });
      if (!world.castRay(below, 2 * diag, true, undefined, undefined, undefined, undefined, isPrimitive)) continue;
      const body = world.createRigidBody(RAPIER.RigidBodyDesc.dynamic().setTranslation(x, y, z));
      body.setLinearDamping(0.2);
      body.setAngularDamping(1.5);
      world.createCollider(RAPIER.ColliderDesc.ball(radius).setRestitution(0).setFriction(0.8), body);
      balls.push(body);
    }
  let through = 0;
  let first = '';
  let frames = 0;
  let prev = balls.map((b) => b.translation());
  for (; frames < 1200; frames++) {
    world.step();
    const now = balls.map((b) => b.translation());
    balls.forEach((b, k) => {
      const a = prev[k];
      const d = { x: now[k].x - a.x, y: now[k].y - a.y, z: now[k].z - a.z };
      const len = Math.hypot(d.x, d.y, d.z);
      // The centre's path this step, against the primitives only (solid: a centre
      // already inside counts at distance 0).
      const ray = new RAPIER.Ray(a, len > 0 ? { x: d.x / len, y: d.y / len, z: d.z / len } : { x: 0, y: -1, z: 0 });
      const hit = world.castRay(ray, len, true, undefined, undefined, undefined, undefined, isPrimitive);
      if (hit) {
        through++;
        if (!first) first = `ball ${k} at frame ${frames}, (${a.x.toFixed(3)}, ${a.y.toFixed(3)}, ${a.z.toFixed(3)})`;
      }
    });
    prev = now;
    if (frames > 60 && balls.every((b) => b.isSleeping() || Math.hypot(...Object.values(b.linvel())) < 1e-3 * diag)) break;
  }
  const ys = balls.map((b) => b.translation().y);
  const onGround = ys.filter((y) => y < ground + 1.5 * radius).length;
  const lost = ys.filter((y) => y < ground).length;
  const moving = balls.filter((b) => !b.isSleeping() && Math.hypot(...Object.values(b.linvel())) >= 1e-3 * diag).length;
  world.free();
  return { balls: balls.length, onGround, onColliders: balls.length - onGround, lost, through, first, frames, moving, kinds };
}

test('the package installed from the repository holds every file it needs', () => {
  const pkg = path.dirname(fileURLToPath(import.meta.resolve('primdecomp')));
  const manifest = JSON.parse(fs.readFileSync(path.join(pkg, 'package.json'), 'utf8'));
  for (const f of manifest.files) assert.ok(fs.existsSync(path.join(pkg, f)), `${f} in ${pkg}`);
  assert.equal(primdecomp.version, manifest.version);
  const types = fs.readFileSync(path.join(pkg, manifest.types), 'utf8');
  for (const name of ['decompose', 'loadMesh', 'meshFromArrays', 'toJSON', 'toGltf', 'PrimdecompError'])
    assert.ok(types.includes(name), `${name} typed in ${manifest.types}`);
});

test('typed arrays in, typed primitives out; toGltf; errors', () => {
  // A unit cube as 12 triangles, in float and in double.
  const corners = [];
  for (let c = 0; c < 8; c++) corners.push(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  const quads = BOX_QUADS;
  const tris = new Uint32Array(quads.flatMap((q) => [q[0], q[1], q[2], q[0], q[2], q[3]]));
  for (const Arr of [Float32Array, Float64Array]) {
    const r = primdecomp.decompose(new Arr(corners), tris, { targets: [1] });
    assert.equal(r.count, 1);
    const box = r.primitives[0];
    assert.equal(box.kind, 'box');
    assert.deepEqual(box.center.map((x) => Math.round(x * 1e9) / 1e9), [0.5, 0.5, 0.5]);
    const glb = r.toGltf();
    assert.ok(glb instanceof Uint8Array && new TextDecoder().decode(glb.subarray(0, 4)) === 'glTF', 'a GLB');
    const gltf = JSON.parse(r.toGltf({ binary: false }));
    assert.ok(gltf.extensionsUsed.includes('KHR_implicit_shapes'), gltf.extensionsUsed);
    assert.ok(r.export('usda').startsWith('#usda 1.0'));
    assert.ok(r.export('mjcf').includes('<mujoco'));
  }
  // Quads kept as quads: the same as the CLI reads an OBJ of quads.
  const q = primdecomp.decompose(new Float64Array(corners), new Uint32Array(quads.flat()), { targets: [1] }, { faceSizes: quads.map(() => 4), name: 'cube.obj' });
  assert.equal(q.input.faces, 6);
  assert.equal(q.input.path, 'cube.obj');
  // Errors name what is wrong and are PrimdecompErrors.
  const err = (f, re) => assert.throws(f, (e) => e instanceof primdecomp.PrimdecompError && re.test(e.message));
  err(() => primdecomp.decompose(new Float64Array(corners), tris, { targetz: [3] }), /targetz/);
  err(() => primdecomp.decompose(new Float64Array(corners), new Uint32Array([0, 1, 99]), {}), /99|out of range/);
  err(() => primdecomp.loadMesh(new TextEncoder().encode('v 0 0 0\nf 1 2 x\n'), 'bad.obj'), /bad\.obj:2/);
  err(() => primdecomp.decompose([0, 0, 0], tris), /Float32Array or a Float64Array/);
  // Progress: reported, and `false` cancels; what the callback throws comes back.
  const mesh = primdecomp.loadMesh(fs.readFileSync(path.join(root, 'datasets', 'demo_scene.obj')), 'demo.obj');
  const stages = new Set();
  primdecomp.decompose(mesh, { targets: [40] }, { onProgress: (s) => void stages.add(s) });
  assert.ok(stages.has('merge') && stages.has('postprocess'), [...stages].join(' '));
  err(() => primdecomp.decompose(mesh, { targets: [40] }, { onProgress: (s) => s !== 'merge' }), /cancelled/);
  assert.throws(() => primdecomp.decompose(mesh, {}, { onProgress: () => { throw new RangeError('mine'); } }), RangeError);
  // A panic (a bug) comes back as an internal PrimdecompError; the engine works after.
  assert.throws(() => primdecomp._selfTestPanic(), (e) => e instanceof primdecomp.PrimdecompError && e.internal && /self-test panic/.test(e.message));
  assert.throws(() => primdecomp.decompose(mesh), /made before the engine was reset/);
  const again = primdecomp.loadMesh(fs.readFileSync(path.join(root, 'datasets', 'demo_scene.obj')), 'demo.obj');
  assert.ok(primdecomp.decompose(again).count > 0);
});

test('a level says what its distance is measured to: the solid of a closed box under solid, else the surface', () => {
  // A 2 x 1 x 0.5 box; opened, it lacks its last side's two triangles.
  const corners = [];
  for (let c = 0; c < 8; c++) corners.push(2 * (c & 1), (c >> 1) & 1, 0.5 * ((c >> 2) & 1));
  const tris = BOX_QUADS.flatMap((q) => [q[0], q[1], q[2], q[0], q[2], q[3]]);
  const run = (faces, settings) => primdecomp.decompose(new Float64Array(corners), new Uint32Array(tris.slice(0, 3 * faces)), settings);
  const measured = (r) => [r.measuredTo, r.levels[0].measuredTo, JSON.parse(r.toJSON()).stats.distance?.measured_to];
  assert.deepEqual(measured(run(12, { solid: true })), ['solid', 'solid', 'solid'], 'closed, solid');
  assert.deepEqual(measured(run(10, { solid: true })), ['mesh', 'mesh', undefined], 'open, solid');
  assert.deepEqual(measured(run(12, {})), ['mesh', 'mesh', undefined], 'closed, without solid');
  assert.deepEqual(measured(run(12, { targets: [2], solid: true })), [null, null, undefined], 'greedy: nothing measured');
  // Levels of one run each say their own.
  const two = run(12, { solid: true, tolerance: [{ diagonal: 0.02 }, { diagonal: 0.01 }] });
  assert.deepEqual(two.levels.map((l) => l.measuredTo), ['solid', 'solid']);
});
