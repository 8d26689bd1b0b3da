// Assembles the live page: one HTML file holding the engine (wasm-bindgen's
// `--target no-modules` glue and engine.js as a classic script's text, the .wasm as
// base64: a page opened from file:// cannot fetch anything) and its script
// (page.js). Run by build.sh:
//
//   node live/build.mjs NO_MODULES_DIR PKG_DIR OUT.html
//
// NO_MODULES_DIR holds wasm-bindgen's no-modules output, PKG_DIR the npm package
// (for its version).
//
// Checks that page.js uses the viewer's palette (crates/primdecomp-view/src/palette.rs)
// and that no embedded text can end its <script> element early.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const [classic, pkg, out] = process.argv.slice(2);
if (!classic || !pkg || !out) {
  console.error('usage: node live/build.mjs NO_MODULES_DIR PKG_DIR OUT.html');
  process.exit(2);
}
const read = (p) => fs.readFileSync(p, 'utf8');

const glue = read(path.join(classic, 'primdecomp_wasm.js'));
const engine = `${glue}\n// ---- live/engine.js ----\n${read(path.join(here, 'engine.js'))}`;
const page = read(path.join(here, 'page.js'));
const wasm = fs.readFileSync(path.join(classic, 'primdecomp_wasm_bg.wasm'));
const version = JSON.parse(read(path.join(pkg, 'package.json'))).version;

// The palette: page.js's constants must be palette.rs's.
const palette = read(path.join(here, '..', '..', 'primdecomp-view', 'src', 'palette.rs'));
const hexes = (block) => [...block.matchAll(/\[0x([0-9a-f]{2}), 0x([0-9a-f]{2}), 0x([0-9a-f]{2})\]/g)].map((m) => `#${m[1]}${m[2]}${m[3]}`);
const constant = (name) => {
  const m = palette.match(new RegExp(`pub const ${name}: [^=]+= ([^;]+);`, 's'));
  if (!m) throw new Error(`palette.rs has no ${name}`);
  return hexes(m[1]);
};
const expect = {
  KIND_RGB: JSON.stringify(constant('KIND_RGB')),
  INPUT_RGB: JSON.stringify(constant('INPUT_RGB')[0]),
  BACKGROUND_RGB: JSON.stringify(constant('BACKGROUND_RGB')[0])
};
for (const [name, value] of Object.entries(expect)) {
  const m = page.match(new RegExp(`const ${name} = ([^;]+);`));
  const got = m && JSON.stringify(JSON.parse(m[1].replace(/'/g, '"')));
  if (got !== value) {
    console.error(`live/page.js: ${name} is ${got}, palette.rs says ${value}`);
    process.exit(1);
  }
}

// Script data ends at "</script" (any case); "<!--" changes how it is read.
for (const [name, text] of [
  ['the engine', engine],
  ['page.js', page]
]) {
  if (/<\/script|<!--/i.test(text)) {
    console.error(`${name} holds "</script" or "<!--": it cannot be embedded in a <script> element`);
    process.exit(1);
  }
}

const values = {
  __PRIMDECOMP_VERSION__: version,
  __PRIMDECOMP_ENGINE__: engine,
  __PRIMDECOMP_WASM__: wasm.toString('base64'),
  __PRIMDECOMP_PAGE__: page
};
// Each marker replaced once, in one pass: a value holding a marker's text stays.
const template = read(path.join(here, 'live.html'));
const html = template.replace(/__PRIMDECOMP_[A-Z]+__/g, (m) => (m in values ? values[m] : m));
fs.writeFileSync(out, html);
