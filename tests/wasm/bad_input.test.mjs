// Bad input across the WebAssembly boundary, through the npm package as JavaScript
// calls it: mesh files in every format cut short, bit-flipped and made of random
// bytes; typed arrays of the wrong type, length or content; settings of every wrong
// type and range; hostile names for the input and the model. Every failure must be a
// PrimdecompError that is not `internal` (a trap, i.e. a panic, is a bug even though
// the package recovers from it), and what is written must parse. Seeded: the same
// cases on every run.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as primdecomp from 'primdecomp';
import { parseObj, playground } from './meshes.mjs';

/** A seeded generator of numbers in [0, 1) (mulberry32). */
function random(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
const rng = random(0x5eed);
const int = (n) => Math.floor(rng() * n);
const pick = (a) => a[int(a.length)];

let internal = 0;
/** Runs `f`; a thrown error must be a PrimdecompError that is not internal. */
function attempt(what, f) {
  try {
    return { value: f() };
  } catch (e) {
    if (e instanceof primdecomp.PrimdecompError && e.internal) internal++;
    assert.ok(e instanceof primdecomp.PrimdecompError, `${what}: threw ${e && e.constructor && e.constructor.name}: ${e}`);
    assert.ok(!e.internal, `${what}: an internal error (a panic in the engine): ${e.message}`);
    assert.ok(e.message.length > 0, `${what}: an error without a message`);
    return { error: e };
  }
}

/** The playground's OBJ in every format the readers take. */
function seeds() {
  const obj = playground();
  const { vertices: v, faces, triangles: tris } = parseObj(obj);
  const stl = Buffer.alloc(84 + 50 * tris.length);
  stl.writeUInt32LE(tris.length, 80);
  tris.forEach((t, i) => t.forEach((id, k) => v[id].forEach((x, d) => stl.writeFloatLE(x, 84 + 50 * i + 12 + 12 * k + 4 * d))));
  const ply = [
    'ply', 'format ascii 1.0', `element vertex ${v.length}`, 'property float x', 'property float y', 'property float z',
    `element face ${faces.length}`, 'property list uchar int vertex_indices', 'end_header',
    ...v.map((p) => p.join(' ')), ...faces.map((f) => `${f.length} ${f.join(' ')}`)
  ].join('\n');
  const off = ['OFF', `${v.length} ${faces.length} 0`, ...v.map((p) => p.join(' ')), ...faces.map((f) => `${f.length} ${f.join(' ')}`)].join('\n');
  // glTF and GLB as the package writes them, with the colliders' preview meshes.
  const r = primdecomp.decompose(primdecomp.loadMesh(new TextEncoder().encode(obj), 'playground.obj'), { targets: [6] });
  const enc = (s) => new TextEncoder().encode(s);
  return [
    ['part.obj', enc(obj)],
    ['part.stl', new Uint8Array(stl)],
    ['part.ply', enc(ply)],
    ['part.off', enc(off)],
    ['part.gltf', enc(r.toGltf({ binary: false, preview: true }))],
    ['part.glb', r.toGltf({ preview: true })]
  ];
}

/** `bytes` damaged one of several ways. */
function mutate(bytes) {
  let b = Array.from(bytes);
  const at = () => int(b.length);
  switch (int(6)) {
    case 0:
      b = b.slice(0, at());
      break;
    case 1:
      for (let k = 1 + int(7); k > 0; k--) b[at()] ^= 1 << int(8);
      break;
    case 2: {
      const n = pick(['4294967295', '-1', '99999999999999999999', '1e308', 'nan', '0', '"', '\\u0000']);
      b.splice(at(), 3, ...new TextEncoder().encode(n));
      break;
    }
    case 3: {
      const i = at();
      for (let k = i; k < Math.min(i + 4, b.length); k++) b[k] = 0xff;
      break;
    }
    case 4: {
      const i = at();
      const j = i + int(b.length - i);
      b.splice(i, 0, ...b.slice(i, j));
      break;
    }
    default:
      b = Array.from({ length: int(512) }, () => int(256));
  }
  return new Uint8Array(b);
}

/** Reads what a result hands out. */
function drain(r, what) {
  for (let i = 0; i < r.levels.length; i++) {
    const doc = JSON.parse(r.toJSON(i));
    assert.equal(doc.primitives.length, r.levels[i].primitives.length, what);
  }
  r.free();
}

test('damaged files in every format are refused or read, never a panic', () => {
  let read = 0;
  let cases = 0;
  for (const [name, bytes] of seeds()) {
    const m = primdecomp.loadMesh(bytes, name);
    drain(primdecomp.decompose(m, { targets: [3] }), name);
    m.free();
    for (let c = 0; c < 120; c++) {
      cases++;
      const what = `${name}, case ${c}`;
      const { value: mesh } = attempt(what, () => primdecomp.loadMesh(mutate(bytes), name));
      if (!mesh) continue;
      read++;
      const { value: r } = attempt(what, () => primdecomp.decompose(mesh, { targets: [4] }));
      if (r) drain(r, what);
      mesh.free();
    }
  }
  console.log(`${read} of ${cases} damaged files read and decomposed, the rest refused`);
  assert.ok(read > 20, `only ${read} damaged files read`);
  assert.equal(internal, 0);
});

test('typed arrays of the wrong type, length or content are refused', () => {
  const cube = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1];
  const tris = [0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3];
  let made = 0;
  for (let c = 0; c < 300; c++) {
    // A tetrahedron, then one or two of its arguments spoiled (or none).
    let coords = cube.slice();
    let idx = tris.slice();
    let Vertices = pick([Float64Array, Float32Array]);
    let Indices = Uint32Array;
    let faceSizes;
    for (let k = int(3); k > 0; k--) {
      switch (int(6)) {
        case 0: coords = coords.slice(0, pick([11, 9, 3, 0])); break;
        case 1: coords[int(coords.length)] = pick([NaN, Infinity, -Infinity, 1e308, -0]); break;
        case 2: idx = idx.slice(0, pick([11, 3, 0])); break;
        case 3: idx[int(idx.length)] = pick([4, 2 ** 32 - 1, 2 ** 31, -1]); break;
        case 4: faceSizes = pick([[3, 3, 3, 3], [4, 4, 4], [0], [2 ** 32 - 1, 1], [12], [6, 6]]); break;
        default:
          Vertices = pick([Float64Array, Int32Array, Array]);
          Indices = pick([Uint32Array, Int32Array, Uint16Array, Array]);
      }
    }
    const vertices = Vertices.from(coords);
    const indices = Indices.from(idx);
    const settings = pick([{}, { targets: [2] }, '{"targets": [1]}', undefined]);
    const what = `case ${c}: ${vertices.constructor.name}(${coords}) ${indices.constructor.name}(${idx}) ${JSON.stringify(faceSizes)}`;
    const { value: r } = attempt(what, () => primdecomp.decompose(vertices, indices, settings, { faceSizes }));
    if (r) {
      made++;
      drain(r, what);
    }
  }
  console.log(`${made} of 300 array cases decomposed, the rest refused`);
  assert.ok(made > 10 && made < 290, `${made} of 300`);
  assert.equal(internal, 0);
});

test('settings of every wrong type and range are refused or run', () => {
  const mesh = primdecomp.loadMesh(new TextEncoder().encode(playground()), 'playground.obj');
  const keys = Object.keys(primdecomp.decompose(mesh, { targets: [2] }).settings);
  const values = [null, true, -1, 0, 1, 3, 0.5, 1e308, -1e308, 1e-320, 2 ** 64, '', 'x', [], [0], [1e9], [-1],
    [{ diagonal: 2 }], [{ diagonal: -0.1 }], [{ absolute: 1e300 }], {}, [[1]], '</script>'];
  let ran = 0;
  for (let c = 0; c < 200; c++) {
    const settings = {};
    for (let k = 1 + int(2); k > 0; k--) settings[pick(keys)] = pick(values);
    const what = `case ${c}: ${JSON.stringify(settings)}`;
    const { value: r } = attempt(what, () => primdecomp.decompose(mesh, settings));
    if (r) {
      ran++;
      drain(r, what);
    }
  }
  for (const text of ['', '[', '{"format": "primdecomp-result"}', '{"format": 1, "version": 99}', '\u001b[31m', '{"targets": [3]} x', 'null', '7'])
    attempt(JSON.stringify(text), () => primdecomp.decompose(mesh, text));
  console.log(`${ran} of 200 random settings ran, the rest refused`);
  assert.ok(ran > 5, `only ${ran} ran`);
  assert.equal(internal, 0);
});

test('hostile names come back whole in the JSON and well formed in every export', () => {
  const names = ['</script><script>alert(1)</script>', '<!--', 'a"b\'c<d>&e]]>', '\u0001\u0008\u001b[31mred\u007f',
    'line\nbreak\r\ttab', '../../../etc/passwd', 'con', ' ', '\ufffe\uffff\ud7ff\ue000', '\u2028\u2029',
    '名前 🚀', '$(rm -rf ~)`x`', '\ud800lone surrogate', 'x'.repeat(5000)];
  const obj = new TextEncoder().encode(playground());
  for (const base of names) {
    const name = `${base}.obj`;
    const mesh = primdecomp.loadMesh(obj, name);
    const r = primdecomp.decompose(mesh, { targets: [6] });
    const doc = JSON.parse(r.toJSON());
    // A lone surrogate cannot cross into Rust's UTF-8: it arrives as U+FFFD.
    assert.equal(doc.input.path, name.replace(/\ud800/, '\ufffd'), 'the input path recorded as given');
    for (const format of ['gltf', 'glb', 'mjcf', 'urdf', 'usda', 'tscn', 'obj', 'json']) {
      const what = `${format} of a model named ${JSON.stringify(base.slice(0, 40))}`;
      const { value: out, error } = attempt(what, () => r.export(format, { model: base, preview: true }));
      if (error) {
        assert.ok(format === 'urdf' && /files beside/.test(error.message), `${what}: ${error.message}`);
        continue;
      }
      if (format === 'glb') {
        assert.equal(new TextDecoder().decode(out.subarray(0, 4)), 'glTF', what);
        const len = new DataView(out.buffer, out.byteOffset).getUint32(12, true);
        JSON.parse(new TextDecoder().decode(out.subarray(20, 20 + len)));
      } else if (format === 'gltf' || format === 'json') {
        JSON.parse(out);
      } else {
        // Text formats: no character XML 1.0 or the grammars refuse; the name adds no
        // line, and no markup to the XML formats, to what a plain name gives.
        const plain = r.export(format, { model: 'plain', preview: true });
        const count = (text, re) => (text.match(re) || []).length;
        assert.ok(!/[\u0000-\u0008\u000b\u000c\u000e-\u001f\ufffe\uffff]/.test(out), `${what}: a control character`);
        assert.equal(count(out, /\n/g), count(plain, /\n/g), `${what}: the name added lines`);
        if (format === 'mjcf' || format === 'urdf') assert.equal(count(out, /</g), count(plain, /</g), `${what}: the name added markup`);
      }
    }
    r.free();
    mesh.free();
  }
  assert.equal(internal, 0);
});
