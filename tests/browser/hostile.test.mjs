// Hostile names in the viewer page (`primdecomp view`), in a real headless Chromium:
// a mesh, a result, a compared hull file and an evaluation whose file and collider
// names hold `<!--<script>`, `</script>`, quotes, ampersands and control characters
// (made here: no corpus needed). No string may change how the page parses: the
// viewer must start (ready, no script error, no network), run no injected script,
// and show each name as it is.
//
// Environment: PRIMDECOMP_BIN (default target/release/primdecomp), CHROMIUM
// (default /usr/bin/chromium), CI (set: a missing browser fails instead of skipping).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..');
const bin = process.env.PRIMDECOMP_BIN || path.join(root, 'target', 'release', 'primdecomp');
const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';
const inCi = !!process.env.CI && process.env.CI !== 'false' && process.env.CI !== '0';

function missing(what) {
  const msg = `${what}: hostile-names browser test cannot run`;
  if (inCi) throw new Error(`${msg} (under CI this is a failure)`);
  console.error(`\n${'!'.repeat(72)}\nSKIPPED: ${msg}\n${'!'.repeat(72)}\n`);
  return msg;
}

let skip = false;
if (!fs.existsSync(chromiumPath)) skip = missing(`no Chromium at ${chromiumPath}`);
else if (!fs.existsSync(bin)) skip = missing(`no primdecomp binary at ${bin} (cargo build --release)`);

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'primdecomp-hostile-view-'));
// File names cannot hold '/': the closing tags come through JSON strings instead.
// The mesh's name also holds U+2028, U+2029 and ESC, and is long (190 bytes); its
// objects' names (`o`, `g`) are 300 characters of the same, decomposed per object.
const MESH = '<!--<script>mesh & "q\'\u2028\u2029\u001b[31m' + 'x'.repeat(150) + '.obj';
const RESULT = 'r<!--<script>\u0007.json';
const HULLS = 'hulls<script>.obj';
const OBJECT = '</script><!--<script>\u2028\u2029\u001b\u0007&"\''.repeat(20).slice(0, 300);
const COLLIDERS = ['</script><script>window.pwned = 1</script>', '<!--<script>', '\u2028</SCRIPT\u001b[31m'];

function run(args) {
  return execFileSync(bin, args, { cwd: work, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

/** Two boxes side by side, as OBJ: two objects with hostile names. */
function twoBoxes() {
  let s = '';
  const quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
  for (let b = 0; b < 2; b++) {
    s += b === 0 ? `o ${OBJECT}\n` : `g ${OBJECT.slice(0, 40)}B\n`;
    for (let i = 0; i < 8; i++) s += `v ${3 * b + (i & 1)} ${(i >> 1) & 1} ${(i >> 2) & 1}\n`;
    for (const q of quads) s += 'f ' + q.map((i) => 8 * b + i + 1).join(' ') + '\n';
  }
  return s;
}

let browser, page;
const errors = [];
const requests = [];

before(async () => {
  if (skip) return;
  fs.writeFileSync(path.join(work, MESH), twoBoxes());
  run(['decompose', MESH, '--per-object', '-n', '4', '-o', RESULT, '--obj', HULLS, '--quiet']);
  const objects = JSON.parse(fs.readFileSync(path.join(work, RESULT), 'utf8')).objects.map((o) => o.name);
  assert.deepEqual(objects, [OBJECT, OBJECT.slice(0, 40) + 'B'], 'the objects keep their names');
  // An evaluation of the result and the hulls, its collider names then made hostile.
  run(['eval', '--input', MESH, RESULT, HULLS, '--samples', '2000', '--json', 'e.json']);
  const ev = JSON.parse(fs.readFileSync(path.join(work, 'e.json'), 'utf8'));
  ev.colliders.forEach((c, i) => (c.collider = COLLIDERS[i % COLLIDERS.length] + c.collider));
  for (const c of COLLIDERS) ev.colliders.push({ collider: c, hausdorff: 0.5, chamfer: 0.1, enclosure: 1 });
  fs.writeFileSync(path.join(work, 'e.json'), JSON.stringify(ev));
  run(['view', RESULT, '--input', MESH, '--compare', HULLS, '--eval', 'e.json', '-o', 'view.html']);

  const { chromium } = await import('playwright-core');
  browser = await chromium.launch({
    executablePath: chromiumPath,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-first-run'],
  });
  const context = await browser.newContext({ viewport: { width: 1024, height: 700 } });
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file://')) return route.continue();
    requests.push(url);
    return route.abort();
  });
  page = await context.newPage();
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  await page.goto(pathToFileURL(path.join(work, 'view.html')).href);
  await page.waitForFunction(() => window.primdecompView && (window.primdecompView.ready || window.primdecompView.error), null, { timeout: 30000 });
});

after(async () => {
  if (browser) await browser.close();
  fs.rmSync(work, { recursive: true, force: true });
});

test('the viewer starts: ready, no error, no network, no injected script', { skip }, async () => {
  const v = await page.evaluate(() => ({ error: window.primdecompView.error, ready: window.primdecompView.ready, pwned: window.pwned }));
  assert.equal(v.error, null);
  assert.equal(v.ready, true);
  assert.equal(v.pwned, undefined, 'an injected script ran');
  assert.deepEqual(errors, [], 'no script errors');
  assert.deepEqual(requests, [], 'no network request');
  // The page's own two scripts, nothing more.
  assert.equal(await page.evaluate(() => document.scripts.length), 2);
});

test('every name is shown as it is', { skip }, async () => {
  const files = await page.evaluate(() => document.getElementById('files').textContent);
  for (const name of [MESH, RESULT, HULLS]) assert.ok(files.includes(name), `${JSON.stringify(name)} not in ${JSON.stringify(files)}`);
  const evalBox = await page.evaluate(() => Array.from(document.querySelectorAll('#eval td[title]')).map((td) => td.title));
  for (const c of COLLIDERS) assert.ok(evalBox.some((t) => t.startsWith(c)), `${JSON.stringify(c)} not in the evaluation table`);
  const levels = await page.evaluate(() => window.primdecompView.levels.length);
  assert.equal(levels, 1);
});
