// The viewer page (`primdecomp view`) in a real headless Chromium, opened from
// file:// with every network request refused: it must draw a mesh's colliders and say
// what it drew.
//
// On a made-up mesh with all six kinds (kinds.obj from `primdecomp-testkit inputs`, at
// -n 6,3; it runs everywhere) and, where the corpus is present, on a corpus mesh with
// all six kinds (vhacd_lamp.obj at -n 60,20), it checks that the page becomes ready
// with no network, that the primitive count and the counts by kind it reports match
// each level's JSON, that a screenshot is not blank and shows every present kind's
// colour (by hue, as shading darkens it) in the drawing and its exact flat colour in
// the legend swatch, that switching level and showing the compared hulls side by side
// change what is drawn, that a level is labelled by what was asked, that clicking
// a primitive shows its kind, parameters and face count from the JSON, and that a part
// picked after a level switch is highlighted in its own shape.
//
// Environment: PRIMDECOMP_BIN (default $CARGO_TARGET_DIR/release/primdecomp, else
// target/release/primdecomp), PRIMDECOMP_TESTKIT (likewise), PRIMDECOMP_TEST_INPUTS (a
// folder of the made-up inputs; default: written here), CHROMIUM (default
// /usr/bin/chromium), VIEW_SHOTS (a directory to keep the screenshots in), CI (set: a
// missing corpus or browser fails instead of skipping).
import { describe, test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { decodePng, countHue, countNot, countExact } from './png.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..');
const target = process.env.CARGO_TARGET_DIR ? path.resolve(process.env.CARGO_TARGET_DIR) : path.join(root, 'target');
const bin = process.env.PRIMDECOMP_BIN || path.join(target, 'release', 'primdecomp');
const testkit = process.env.PRIMDECOMP_TESTKIT || path.join(target, 'release', 'primdecomp-testkit');
const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';
const corpus = path.resolve(root, '..', 'shared', 'datasets', 'corpus');
const inCi = !!process.env.CI && process.env.CI !== 'false' && process.env.CI !== '0';
const shotsRoot = process.env.VIEW_SHOTS ? path.resolve(process.env.VIEW_SHOTS) : null;

function missing(what) {
  const msg = `${what}: browser test cannot run`;
  if (inCi) throw new Error(`${msg} (under CI this is a failure)`);
  console.error(`\n${'!'.repeat(72)}\nSKIPPED: ${msg}\n${'!'.repeat(72)}\n`);
  return msg;
}

function inputs() {
  if (process.env.PRIMDECOMP_TEST_INPUTS) return path.resolve(process.env.PRIMDECOMP_TEST_INPUTS);
  const d = fs.mkdtempSync(path.join(os.tmpdir(), 'primdecomp-inputs-'));
  execFileSync(testkit, ['inputs', d], { stdio: ['ignore', 'ignore', 'inherit'] });
  return d;
}

// Each case: a name, the mesh, the counts of its two levels, and the first level's label.
const cases = [
  { name: 'made-up kinds.obj', mesh: () => path.join(inputs(), 'kinds.obj'), targets: [6, 3], corpus: false },
  { name: 'corpus vhacd_lamp.obj', mesh: () => path.join(corpus, 'vhacd_lamp.obj'), targets: [60, 20], corpus: true },
];

let common = false;
if (!fs.existsSync(chromiumPath)) common = missing(`no Chromium at ${chromiumPath} (apt-get install chromium)`);
else if (!fs.existsSync(bin)) common = missing(`no primdecomp binary at ${bin} (cargo test --release --workspace builds it)`);
else if (!fs.existsSync(testkit) && !process.env.PRIMDECOMP_TEST_INPUTS) common = missing(`no primdecomp-testkit binary at ${testkit}`);

for (const c of cases) {
  let skip = common;
  if (!skip && c.corpus && !fs.existsSync(corpus)) skip = missing(`CORPUS ABSENT: ${corpus} not found`);
  describe(c.name, { skip }, () => suite(c));
}

function suite(c) {
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'primdecomp-view-test-'));
const shots = shotsRoot ? path.join(shotsRoot, c.targets.join('_')) : work;
if (shotsRoot) fs.mkdirSync(shots, { recursive: true });
const TARGETS = c.targets;
function run(args) {
  return execFileSync(bin, args, { cwd: work, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

const out = path.join(work, 'res.json');
const levelFile = (t) => path.join(work, `res_n${t}.json`);
const levels = [];
let browser, page, mesh;
const requests = [];

before(async () => {
  mesh = c.mesh();
  run(['decompose', mesh, '-n', TARGETS.join(','), '-o', out, '--obj', path.join(work, 'hulls.obj'), '--quiet']);
  for (const t of TARGETS) levels.push(JSON.parse(fs.readFileSync(levelFile(t), 'utf8')));
  // Our own n20 tessellation stands in for a peer's hull file: one convex `o` per part.
  fs.renameSync(path.join(work, `hulls_n${TARGETS[1]}.obj`), path.join(work, 'tessellation.obj'));
  run(['eval', '--input', mesh, levelFile(TARGETS[0]), path.join(work, 'tessellation.obj'), '--samples', '5000', '--json', path.join(work, 'eval.json')]);
  run(['view', out, '--input', mesh, '--compare', path.join(work, 'tessellation.obj'), '--eval', path.join(work, 'eval.json'), '-o', path.join(work, 'view.html')]);

  const { chromium } = await import('playwright-core');
  browser = await chromium.launch({
    executablePath: chromiumPath,
    headless: true,
    args: [
      '--no-sandbox',
      '--disable-gpu',
      '--use-angle=swiftshader',
      '--enable-unsafe-swiftshader',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync'
    ]
  });
  const context = await browser.newContext({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 });
  // Offline: anything but the file itself is refused and recorded.
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file://')) return route.continue();
    requests.push(url);
    return route.abort();
  });
  page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  await page.goto(pathToFileURL(path.join(work, 'view.html')).href);
  await page.waitForFunction(() => window.primdecompView && (window.primdecompView.ready || window.primdecompView.error), null, { timeout: 30000 });
  const err = await page.evaluate(() => window.primdecompView.error);
  assert.equal(err, null, `the page reported an error: ${err}`);
  assert.deepEqual(errors, [], 'no script errors');
});

after(async () => {
  if (browser) await browser.close();
  fs.rmSync(work, { recursive: true, force: true });
});

/** The canvas's rectangle in page pixels. */
async function canvasRect() {
  const r = await page.evaluate(() => {
    const b = document.getElementById('gl').getBoundingClientRect();
    return { x: b.left, y: b.top, w: b.width, h: b.height };
  });
  return { x: Math.round(r.x), y: Math.round(r.y), w: Math.floor(r.w), h: Math.floor(r.h) };
}

async function frame() {
  // Two animation frames: the one drawing the change, and one after it.
  await page.evaluate(() => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res))));
}

async function shot(name) {
  await frame();
  const buf = await page.screenshot({ path: path.join(shots, name) });
  return decodePng(buf);
}

const background = () => page.evaluate(() => window.primdecompView.palette.background);
const kindColours = () => page.evaluate(() => window.primdecompView.palette.kinds);

test('the page opens from file:// with no network and reports every level of the JSON', async () => {
  assert.deepEqual(requests, [], 'no network request');
  const v = await page.evaluate(() => ({ levels: window.primdecompView.levels, level: window.primdecompView.level, primitives: window.primdecompView.primitives }));
  assert.equal(v.levels.length, TARGETS.length);
  levels.forEach((doc, i) => {
    assert.equal(v.levels[i].primitives, doc.primitives.length, `level ${i}: primitive count`);
    assert.equal(v.levels[i].primitives, doc.stats.primitives);
    for (const [kind, n] of Object.entries(doc.stats.counts)) assert.equal(v.levels[i].counts[kind], n, `level ${i}: ${kind}`);
  });
  assert.equal(v.level, 0);
  assert.equal(v.primitives, levels[0].primitives.length);
});

test('ours alone: not blank, and every present kind in its colour in the drawing and the legend', async () => {
  await page.evaluate(() => window.primdecompView.setMode('level:0'));
  const img = await shot('view.png');
  const c = await canvasRect();
  const bg = await background();
  const drawn = countNot(img, c, bg);
  assert.ok(drawn > 0.03 * c.w * c.h, `drawn pixels: ${drawn} of ${c.w * c.h}`);
  const counts = levels[0].stats.counts;
  const present = (await kindColours()).filter((k) => counts[k.name] > 0);
  assert.ok(present.length >= 5, `the test mesh shows several kinds: ${present.map((k) => k.name)}`);
  for (const k of present) {
    const n = countHue(img, c, k.rgb);
    assert.ok(n >= 30, `${k.name} (${k.rgb}): ${n} pixels of its hue in the drawing`);
    const sw = await page.evaluate((name) => {
      const b = document.querySelector(`#legend .row[data-kind="${name}"] .swatch`).getBoundingClientRect();
      return { x: Math.ceil(b.left) + 2, y: Math.ceil(b.top) + 2, w: Math.floor(b.width) - 4, h: Math.floor(b.height) - 4 };
    }, k.name);
    assert.equal(countExact(img, sw, k.rgb), sw.w * sw.h, `${k.name}: legend swatch in ${k.rgb}`);
  }
  // A kind absent from the level is not in the drawing.
  for (const k of (await kindColours()).filter((k) => counts[k.name] === 0)) {
    assert.ok(countHue(img, c, k.rgb) < 30, `${k.name} absent but drawn`);
  }
});

test('clicking a primitive shows its kind, parameters and face count', async () => {
  const c = await canvasRect();
  // The first point of a coarse grid over the canvas that hits a part.
  let hit = null;
  for (let y = c.y + 20; y < c.y + c.h && !hit; y += 16) {
    for (let x = c.x + 20; x < c.x + c.w && !hit; x += 16) {
      const h = await page.evaluate(([x, y]) => window.primdecompView.hitAt(x, y), [x, y]);
      if (h) hit = { x, y, ...h };
    }
  }
  assert.ok(hit, 'some point of the drawing hits a primitive');
  await page.mouse.click(hit.x, hit.y);
  await frame();
  const sel = await page.evaluate(() => window.primdecompView.selected);
  assert.equal(sel.index, hit.index);
  const prim = levels[0].primitives[sel.index];
  assert.equal(sel.kind, prim.kind);
  assert.equal(sel.faces, prim.faces);
  const info = await page.evaluate(() => {
    const e = document.getElementById('info');
    return { shown: getComputedStyle(e).display !== 'none', text: e.innerText };
  });
  assert.ok(info.shown, 'the info panel is shown');
  assert.match(info.text, new RegExp(`^${prim.kind} #${sel.index}`));
  assert.match(info.text, new RegExp(`input faces\\s+${prim.faces}\\b`));
  const param = Object.keys(prim).find((k) => k !== 'kind' && k !== 'faces');
  assert.ok(info.text.includes(param.replace(/_/g, ' ')), `parameter ${param} listed: ${info.text}`);
  await shot('view_selected.png');
});

test('the level selector switches to the other level', async () => {
  const before = await shot('level0.png');
  await page.selectOption('#level', '1');
  const v = await page.evaluate(() => ({ level: window.primdecompView.level, primitives: window.primdecompView.primitives, selected: window.primdecompView.selected }));
  assert.equal(v.level, 1);
  assert.equal(v.primitives, levels[1].primitives.length);
  assert.equal(v.selected, null);
  const afterImg = await shot('level1.png');
  const c = await canvasRect();
  let differ = 0;
  for (let y = c.y; y < c.y + c.h; y++)
    for (let x = c.x; x < c.x + c.w; x++) {
      const k = 3 * (y * afterImg.width + x);
      if (afterImg.rgb[k] !== before.rgb[k] || afterImg.rgb[k + 1] !== before.rgb[k + 1] || afterImg.rgb[k + 2] !== before.rgb[k + 2]) differ++;
    }
  assert.ok(differ > 500, `the drawing changed: ${differ} pixels`);
  await page.selectOption('#level', '0');
});

/** Pixels that differ between two screenshots inside rectangle r. */
function differing(a, b, r) {
  let n = 0;
  for (let y = r.y; y < r.y + r.h; y++)
    for (let x = r.x; x < r.x + r.w; x++) {
      const k = 3 * (y * a.width + x);
      if (a.rgb[k] !== b.rgb[k] || a.rgb[k + 1] !== b.rgb[k + 1] || a.rgb[k + 2] !== b.rgb[k + 2]) n++;
    }
  return n;
}

test('a part picked after a level switch is highlighted in its own shape, not that of the same index in the level before', async () => {
  const c = await canvasRect();
  // The first point of a grid over the canvas that hits each part, by its index.
  const grid = async () =>
    new Map(
      await page.evaluate((c) => {
        const out = new Map();
        for (let y = c.y + 20; y < c.y + c.h; y += 12)
          for (let x = c.x + 20; x < c.x + c.w; x += 12) {
            const h = window.primdecompView.hitAt(x, y);
            if (h && !out.has(h.index)) out.set(h.index, { x, y });
          }
        return [...out];
      }, c)
    );
  await page.evaluate(() => window.primdecompView.setMode('level:0'));
  await page.evaluate(() => window.primdecompView.setLevel(1));
  const atLevel1 = await grid();
  await page.evaluate(() => window.primdecompView.setLevel(0));
  const atLevel0 = await grid();
  const index = [...atLevel1.keys()].find((i) => atLevel0.has(i));
  assert.ok(index !== undefined, 'some part index is visible in both levels');
  // Pick that index in level 0, then in level 1.
  await page.mouse.click(atLevel0.get(index).x, atLevel0.get(index).y);
  await frame();
  assert.equal((await page.evaluate(() => window.primdecompView.selected)).index, index);
  await page.evaluate(() => window.primdecompView.setLevel(1));
  await page.mouse.click(atLevel1.get(index).x, atLevel1.get(index).y);
  const after = await shot('level1_picked_after_level0.png');
  // The same pick on a page that never picked in level 0.
  const fresh = await page.context().newPage();
  try {
    await fresh.goto(page.url());
    await fresh.waitForFunction(() => window.primdecompView && window.primdecompView.ready);
    await fresh.evaluate(() => window.primdecompView.setMode('level:0'));
    await fresh.evaluate(() => window.primdecompView.setLevel(1));
    await fresh.mouse.click(atLevel1.get(index).x, atLevel1.get(index).y);
    await fresh.evaluate(() => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res))));
    const alone = decodePng(await fresh.screenshot({ path: path.join(shots, 'level1_picked.png') }));
    const n = differing(after, alone, c);
    assert.ok(n < 0.001 * c.w * c.h, `${n} pixels of the view differ from the same pick on a fresh page`);
  } finally {
    await fresh.close();
    await page.evaluate(() => window.primdecompView.setLevel(0));
  }
});

test('side by side: the input, ours and the compared hulls, each in its pane, with distances', async () => {
  await page.evaluate(() => window.primdecompView.setMode('side'));
  const img = await shot('view_side.png');
  const v = await page.evaluate(() => window.primdecompView.panes);
  assert.deepEqual(v.map((p) => p.collider), [null, 'level:0', 'peer:0']);
  const hull = await page.evaluate(() => window.primdecompView.palette.hull);
  const bg = await background();
  const c = await canvasRect();
  const pane = (i) => ({ x: c.x + Math.ceil(v[i].x), y: c.y, w: Math.floor(v[i].w), h: c.h });
  // The input pane: grey, no kind colour.
  assert.ok(countNot(img, pane(0), bg) > 0.01 * c.w * c.h, 'input drawn');
  for (const k of await kindColours()) assert.ok(countHue(img, pane(0), k.rgb) < 30, `no ${k.name} in the input pane`);
  // Ours: kind colours; the hulls: the hull colour and no kind colour.
  assert.ok(countHue(img, pane(1), (await kindColours())[0].rgb) >= 30, 'boxes in our pane');
  const hullsThere = countHue(img, pane(2), hull);
  assert.ok(hullsThere >= 200, `hulls in their pane: ${hullsThere}`);
  // In ours, the hull's hue only where orange meets green at an anti-aliased edge.
  const hullsHere = countHue(img, pane(1), hull);
  assert.ok(hullsHere < hullsThere / 20, `hull colour in our pane: ${hullsHere} vs ${hullsThere}`);
  const evalText = await page.evaluate(() => document.getElementById('eval').innerText);
  const ev = JSON.parse(fs.readFileSync(path.join(work, 'eval.json'), 'utf8'));
  // A level is labelled by what was asked (a count here) and what was reached.
  assert.ok(evalText.includes(`ours, count ${TARGETS[0]}`), evalText);
  assert.ok(evalText.includes('tessellation.obj'), evalText);
  const h = ev.colliders[0].hausdorff;
  assert.ok(evalText.includes(h.toPrecision(4)), `Hausdorff ${h} in ${evalText}`);
});

test('a resized window keeps the whole scene in the default view until the user moves it', async () => {
  await page.evaluate(() => window.primdecompView.setMode('level:0'));
  await page.evaluate(() => window.primdecompView.resetView());
  const bg = await background();
  try {
    // Narrower than the view was fitted for: the scene must be fitted again, not cropped.
    for (const size of [{ width: 640, height: 800 }, { width: 1280, height: 420 }]) {
      await page.setViewportSize(size);
      const img = await shot(`view_${size.width}x${size.height}.png`);
      const c = await canvasRect();
      assert.ok(countNot(img, c, bg) > 0.03 * c.w * c.h, `drawn at ${size.width}x${size.height}`);
      const edges = [
        { x: c.x, y: c.y, w: 2, h: c.h },
        { x: c.x + c.w - 2, y: c.y, w: 2, h: c.h },
        { x: c.x, y: c.y, w: c.w, h: 2 },
        { x: c.x, y: c.y + c.h - 2, w: c.w, h: 2 }
      ];
      for (const e of edges) assert.equal(countNot(img, e, bg), 0, `the scene touches the frame's edge ${JSON.stringify(e)} at ${size.width}x${size.height}`);
    }
  } finally {
    await page.setViewportSize({ width: 1280, height: 800 });
  }
});
}
