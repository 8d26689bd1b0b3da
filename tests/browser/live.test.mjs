// The live page (crates/primdecomp-wasm/pkg/primdecomp-live.html, built by
// crates/primdecomp-wasm/build.sh) in a real headless Chromium, opened from file://
// with every network request refused: the WebAssembly engine starts (in a Worker)
// and decomposes the built-in demo scene; a made-up mesh given through the file
// input (a knotted tube, as a binary STL) and another dropped on the page (an OBJ
// with a part of every kind) are decomposed; the
// count, tolerance and byte sliders are moved; after each, the page's count and
// counts by kind equal the CLI's on the same file with the flags the page says it
// used, and moving the count slider changes the count. PLY, glTF and GLB files with
// hostile names go through the file input: the name is shown as text, and the
// command line the page shows, run by a shell, reads that file and gives the page's
// count. Then the npm package itself
// (pkg/index.js, an ES module) is imported by a page served from 127.0.0.1 and
// decomposes typed arrays in the browser.
//
// Environment: PRIMDECOMP_BIN (default target/release/primdecomp), PRIMDECOMP_LIVE
// (default crates/primdecomp-wasm/pkg/primdecomp-live.html), CHROMIUM (default
// /usr/bin/chromium), CI (set: a missing piece fails instead of skipping).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { knot, parseObj, playground } from '../wasm/meshes.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..');
const bin = process.env.PRIMDECOMP_BIN || path.join(root, 'target', 'release', 'primdecomp');
const live = process.env.PRIMDECOMP_LIVE || path.join(root, 'crates', 'primdecomp-wasm', 'pkg', 'primdecomp-live.html');
const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';
const inCi = !!process.env.CI && process.env.CI !== 'false' && process.env.CI !== '0';
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'primdecomp-live-test-'));

function missing(what) {
  const msg = `${what}: live page test cannot run`;
  if (inCi) throw new Error(`${msg} (under CI this is a failure)`);
  console.error(`\n${'!'.repeat(72)}\nSKIPPED: ${msg}\n${'!'.repeat(72)}\n`);
  return msg;
}

let skip = false;
if (!fs.existsSync(live)) skip = missing(`no live page at ${live} (crates/primdecomp-wasm/build.sh)`);
else if (!fs.existsSync(chromiumPath)) skip = missing(`no Chromium at ${chromiumPath} (apt-get install chromium)`);
else if (!fs.existsSync(bin)) skip = missing(`no primdecomp binary at ${bin} (cargo build --release)`);

/** The OBJ's polygons fanned into triangles, as a binary STL. */
function stl(obj) {
  const { vertices: v, triangles: tris } = parseObj(obj);
  const buf = Buffer.alloc(84 + 50 * tris.length);
  buf.write('primdecomp live test', 0);
  buf.writeUInt32LE(tris.length, 80);
  tris.forEach((t, i) => {
    const o = 84 + 50 * i;
    t.forEach((id, k) => v[id].forEach((x, d) => buf.writeFloatLE(x, o + 12 + 12 * k + 4 * d)));
  });
  return buf;
}

const stlPath = path.join(work, 'knot.stl');
const objPath = path.join(work, 'playground.obj');
let browser, page;
const requests = [];
const errors = [];

before(async () => {
  if (skip) return;
  fs.writeFileSync(stlPath, stl(knot()));
  fs.writeFileSync(objPath, playground());
  const { chromium } = await import('playwright-core');
  browser = await chromium.launch({
    executablePath: chromiumPath,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync']
  });
  const context = await browser.newContext({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 });
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file://') || url.startsWith('blob:') || url.startsWith('data:')) return route.continue();
    requests.push(url);
    return route.abort();
  });
  page = await context.newPage();
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  await page.goto(pathToFileURL(live).href);
  await settled(0);
});

after(async () => {
  if (browser) await browser.close();
  fs.rmSync(work, { recursive: true, force: true });
});

const state = () => page.evaluate(() => JSON.parse(JSON.stringify(window.primdecompLive)));

/** Waits until more than `runs` runs finished and the last one ran what the sliders ask. */
async function settled(runs) {
  await page.waitForFunction(
    (n) => {
      const a = window.primdecompLive;
      return a && (a.error || (a.runs > n && !a.busy && JSON.stringify(a.settings) === JSON.stringify(a.requested)));
    },
    runs,
    { timeout: 120000 }
  );
  const s = await state();
  assert.equal(s.error, null, `the page reported an error: ${s.error}`);
  return s;
}

/** The CLI on `file` with the flags the page shows for its run. */
function cli(file, s) {
  const flags = s.cli.split(' ').slice(3);
  const out = path.join(work, 'cli.json');
  execFileSync(bin, ['decompose', file, '-o', out, '--quiet', ...flags]);
  return JSON.parse(fs.readFileSync(out, 'utf8'));
}

function sameAsCli(file, s, what) {
  const doc = cli(file, s);
  assert.equal(s.result.count, doc.primitives.length, `${what}: the page's count (${s.cli})`);
  assert.deepEqual(s.result.counts, doc.stats.counts, `${what}: counts by kind (${s.cli})`);
  assert.equal(s.result.bytes, doc.stats.bytes, `${what}: bytes`);
  if (doc.stats.distance) assert.ok(Math.abs(s.result.distance - doc.stats.distance.worst) <= 1e-9 * doc.stats.distance.worst, `${what}: farthest distance`);
  console.log(`  ${what}: ${s.result.count} primitives, ${s.result.bytes} bytes in ${(1000 * s.result.seconds).toFixed(0)} ms, as \`${s.cli}\` gives`);
  return doc;
}

/** Presses `key` `times` times on a focused slider, then waits for the last run. */
async function slide(id, key, times) {
  const before = (await state()).runs;
  await page.focus(`#${id}`);
  for (let i = 0; i < times; i++) await page.keyboard.press(key);
  return settled(before);
}

test('the engine starts in a Worker from file://, offline, and decomposes the demo scene as the CLI does', { skip }, async () => {
  const s = await state();
  assert.equal(s.worker, true, `the engine runs in a Worker (${s.workerError || ''})`);
  assert.equal(s.mesh.name, 'demo_scene.obj');
  sameAsCli(path.join(root, 'datasets', 'demo_scene.obj'), s, 'demo scene');
  assert.deepEqual(requests, [], 'no network request');
  assert.deepEqual(errors, [], 'no script errors');
  // Something is drawn: the canvas is not all background.
  const shot = await page.locator('#gl').screenshot();
  assert.ok(shot.length > 5000, `a drawing (${shot.length} bytes of PNG)`);
});

test('a mesh through the file input, then the sliders: the count changes and matches the CLI at each setting', { skip }, async () => {
  let runs = (await state()).runs;
  await page.setInputFiles('#file', stlPath);
  await page.waitForFunction(() => window.primdecompLive.mesh && window.primdecompLive.mesh.name === 'knot.stl');
  let s = await settled(runs);
  sameAsCli(stlPath, s, 'knot.stl, tolerance');

  // The count slider, two stops down from 64: a cut at 40 primitives, then 1 (Home).
  s = await slide('count', 'ArrowLeft', 2);
  assert.equal(s.mode, 'count');
  assert.match(s.cli, / -n 40 --cut$/);
  const atForty = sameAsCli(stlPath, s, 'knot.stl, count slider');
  s = await slide('count', 'Home', 1);
  assert.match(s.cli, / -n 1 --cut$/);
  sameAsCli(stlPath, s, 'knot.stl, count slider at 1');
  assert.notEqual(s.result.count, atForty.primitives.length, 'moving the count slider changes the count');
  assert.equal(s.result.count, 1);

  // The tolerance slider, down to 0.5%, and the byte slider, down to 256 bytes.
  s = await slide('tolerance', 'ArrowLeft', 4);
  assert.match(s.cli, / --tolerance 0\.5%$/);
  sameAsCli(stlPath, s, 'knot.stl, tolerance slider');
  s = await slide('bytes', 'ArrowLeft', 8);
  assert.match(s.cli, / --max-bytes 256$/);
  sameAsCli(stlPath, s, 'knot.stl, byte slider');

  // Without spheres: the kind toggles are settings too.
  runs = s.runs;
  await page.click('#kind-sphere');
  s = await settled(runs);
  assert.match(s.cli, / --kinds box,capsule,cylinder,frustum,prism$/);
  assert.equal(s.result.counts.sphere, 0);
  sameAsCli(stlPath, s, 'knot.stl, no spheres');
  await page.click('#kind-sphere');
  await settled(s.runs);
});

test('the npm package as an ES module in the browser: import, decompose typed arrays, toJSON, toGltf', { skip }, async () => {
  // Served over HTTP from the package's folder (a module cannot be imported from
  // file://), as a bundler or a static server would.
  const http = await import('node:http');
  const pkg = path.dirname(live);
  const types = { '.js': 'text/javascript', '.wasm': 'application/wasm', '.html': 'text/html' };
  const page_ = `<!DOCTYPE html><script type="module">
    import { decompose, version, KINDS } from './index.js';
    const v = new Float32Array([0,0,0, 2,0,0, 0,1,0, 2,1,0, 0,0,3, 2,0,3, 0,1,3, 2,1,3]);
    const quads = [[0,4,6,2],[1,3,7,5],[0,1,5,4],[2,6,7,3],[0,2,3,1],[4,5,7,6]];
    const tris = new Uint32Array(quads.flatMap((q) => [q[0], q[1], q[2], q[0], q[2], q[3]]));
    const r = decompose(v, tris, { targets: [1] });
    const glb = r.toGltf();
    window.out = { version, kinds: KINDS, primitive: r.primitives[0], json: JSON.parse(r.toJSON()).stats, glb: new TextDecoder().decode(glb.subarray(0, 4)) };
  </script>`;
  const server = http.createServer((req, res) => {
    const name = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    if (name === '/test.html') return res.writeHead(200, { 'content-type': 'text/html' }).end(page_);
    const file = path.join(pkg, path.normalize(name));
    if (!file.startsWith(pkg) || !fs.existsSync(file)) return res.writeHead(404).end();
    res.writeHead(200, { 'content-type': types[path.extname(file)] || 'application/octet-stream' }).end(fs.readFileSync(file));
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  const url = `http://127.0.0.1:${server.address().port}/test.html`;
  try {
    const p = await page.context().newPage();
    await p.route('**/*', (route) => (route.request().url().startsWith('http://127.0.0.1:') ? route.continue() : route.abort()));
    await p.goto(url);
    await p.waitForFunction(() => window.out, null, { timeout: 60000 });
    const out = await p.evaluate(() => window.out);
    assert.match(out.version, /^\d+\.\d+\.\d+$/);
    assert.equal(out.kinds.length, 6);
    assert.equal(out.primitive.kind, 'box');
    assert.deepEqual(out.primitive.half_extents.map((x) => Math.round(x * 1e6) / 1e6).sort(), [0.5, 1, 1.5]);
    assert.equal(out.json.primitives, 1);
    assert.equal(out.glb, 'glTF');
    await p.close();
  } finally {
    server.close();
  }
});

test('a mesh dropped on the page is decomposed', { skip }, async () => {
  const runs = (await state()).runs;
  const text = fs.readFileSync(objPath, 'utf8');
  await page.evaluate((t) => {
    const dt = new DataTransfer();
    dt.items.add(new File([t], 'playground.obj', { type: 'model/obj' }));
    window.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, text);
  await page.waitForFunction(() => window.primdecompLive.mesh && window.primdecompLive.mesh.name === 'playground.obj');
  const s = await settled(runs);
  sameAsCli(objPath, s, 'playground.obj');
  assert.equal(new Set(Object.values(s.result.counts)).size > 0 && Object.values(s.result.counts).every((n) => n === 1), true, 'the playground: one primitive of each kind');
  // A file the engine cannot read: the page says why and keeps working.
  await page.evaluate(() => {
    const dt = new DataTransfer();
    dt.items.add(new File(['v 0 0 0\nf 1 2 x\n'], 'broken.obj'));
    window.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  });
  await page.waitForFunction(() => window.primdecompLive.error);
  const e = await state();
  assert.match(e.error, /broken\.obj:2/);
  assert.deepEqual(requests, [], 'no network request');
});

/** The playground's triangles as glTF (a data: URI buffer), GLB and ASCII PLY. */
function formats(obj) {
  const { vertices: v, faces, triangles: tris } = parseObj(obj);
  const bin = Buffer.alloc(12 * v.length + 12 * tris.length);
  v.forEach((p, i) => p.forEach((x, d) => bin.writeFloatLE(x, 12 * i + 4 * d)));
  tris.flat().forEach((id, i) => bin.writeUInt32LE(id, 12 * v.length + 4 * i));
  const lo = [0, 1, 2].map((d) => Math.min(...v.map((p) => Math.fround(p[d]))));
  const hi = [0, 1, 2].map((d) => Math.max(...v.map((p) => Math.fround(p[d]))));
  const doc = (uri) => ({
    asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0, name: '</script><!--' }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
    buffers: [{ byteLength: bin.length, ...(uri ? { uri } : {}) }],
    bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: 12 * v.length }, { buffer: 0, byteOffset: 12 * v.length, byteLength: 12 * tris.length }],
    accessors: [{ bufferView: 0, componentType: 5126, count: v.length, type: 'VEC3', min: lo, max: hi }, { bufferView: 1, componentType: 5125, count: 3 * tris.length, type: 'SCALAR' }]
  });
  const gltf = Buffer.from(JSON.stringify(doc(`data:application/octet-stream;base64,${bin.toString('base64')}`)));
  let json = Buffer.from(JSON.stringify(doc(null)));
  json = Buffer.concat([json, Buffer.alloc((4 - (json.length % 4)) % 4, 0x20)]);
  const head = Buffer.alloc(20);
  head.write('glTF', 0);
  head.writeUInt32LE(2, 4);
  head.writeUInt32LE(12 + 8 + json.length + 8 + bin.length, 8);
  head.writeUInt32LE(json.length, 12);
  head.write('JSON', 16);
  const binHead = Buffer.alloc(8);
  binHead.writeUInt32LE(bin.length, 0);
  binHead.write('BIN\0', 4);
  const glb = Buffer.concat([head, json, binHead, bin]);
  const ply = Buffer.from([
    'ply', 'format ascii 1.0', `element vertex ${v.length}`, 'property float x', 'property float y', 'property float z',
    `element face ${faces.length}`, 'property list uchar int vertex_indices', 'end_header',
    ...v.map((p) => p.join(' ')), ...faces.map((f) => `${f.length} ${f.join(' ')}`), ''
  ].join('\n'));
  return { gltf, glb, ply };
}

test('PLY, glTF and GLB with hostile file names through the file input: shown as text, the command line runs as shown', { skip }, async () => {
  const { gltf, glb, ply } = formats(fs.readFileSync(objPath, 'utf8'));
  const files = [
    ['<img src=x onerror="window.__pwned=1"><script>window.__pwned=2<.ply', ply],
    ["-n 1 $(touch pwned) 'q' `x`.glb", glb],
    ['a"b&c<!--\u202e\u0007 名前.gltf', gltf]
  ];
  for (const [name, buffer] of files) {
    const runs = (await state()).runs;
    await page.setInputFiles('#file', { name, mimeType: 'application/octet-stream', buffer });
    await page.waitForFunction((n) => window.primdecompLive.mesh && window.primdecompLive.mesh.name === n, name);
    const s = await settled(runs);
    const shown = await page.evaluate(() => ({
      text: document.getElementById('mesh').textContent,
      elements: document.getElementById('mesh').children.length,
      images: document.images.length,
      scripts: document.scripts.length,
      pwned: window.__pwned === undefined ? null : window.__pwned,
      cli: document.getElementById('cli').textContent
    }));
    assert.ok(shown.text.startsWith(`${name}: `), `the name as text: ${JSON.stringify(shown.text)}`);
    assert.deepEqual([shown.elements, shown.images, shown.scripts, shown.pwned], [0, 0, 3, null], 'no markup from the name');
    assert.equal(shown.cli, s.cli);
    // The command line the page shows, run by a shell in a folder holding the file
    // under that name: it reads that file (not a flag, nothing substituted) and gives
    // the page's count.
    const dir = fs.mkdtempSync(path.join(work, 'shell-'));
    fs.writeFileSync(path.join(dir, name), buffer);
    const command = `"$PRIMDECOMP" ${s.cli.replace(/^primdecomp /, '')} -o out.json --quiet`;
    execFileSync('/bin/sh', ['-c', command], { cwd: dir, env: { ...process.env, PRIMDECOMP: bin } });
    assert.ok(!fs.existsSync(path.join(dir, 'pwned')), 'the shell substituted nothing');
    const doc = JSON.parse(fs.readFileSync(path.join(dir, 'out.json'), 'utf8'));
    assert.equal(doc.primitives.length, s.result.count, `${JSON.stringify(name)}: the page's count is the CLI's (${s.cli})`);
    assert.deepEqual(doc.stats.counts, s.result.counts, `${JSON.stringify(name)}: counts by kind`);
    console.log(`  ${path.extname(name)}: ${s.result.count} primitives, as \`${s.cli}\` gives in a shell`);
    // Saved under a name any file system takes.
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#save-json')]);
    const saved = download.suggestedFilename();
    assert.ok(saved.endsWith('.primdecomp.json') && !/[\u0000-\u001f/\\:*?"<>|]/.test(saved), `saved as ${JSON.stringify(saved)}`);
  }
  // A broken file with a hostile name: the message is text too.
  await page.setInputFiles('#file', { name: '<b id="bold">x.obj', mimeType: 'text/plain', buffer: Buffer.from('v 0 0 0\nf 1 2 x\n') });
  await page.waitForFunction(() => window.primdecompLive.error);
  const status = await page.evaluate(() => ({ text: document.getElementById('status').textContent, bold: !!document.getElementById('bold') }));
  assert.match(status.text, /<b id="bold">x\.obj:2/);
  assert.equal(status.bold, false);
  assert.deepEqual(errors, [], 'no script errors');
  assert.deepEqual(requests, [], 'no network request');
});
