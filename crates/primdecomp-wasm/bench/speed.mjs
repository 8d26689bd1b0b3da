// WebAssembly against native, one thread each: the time to decompose and whether the
// primitives agree. For each mesh and settings, rounds alternate the native CLI
// (`--threads 1 --timings`: its stages' seconds, the file's loading left out) and
// the package's engine in this node process (the decomposition call alone; the
// first call, which pays for compiling the module's code, is reported apart).
//
//   node crates/primdecomp-wasm/bench/speed.mjs --cli target/release/primdecomp \
//       [--rounds 5] [--musl NATIVE_JSON] [--out docs/results/wasm.md] MESH[=FLAGS] …
//
// --musl: the example native_json built for x86_64-unknown-linux-musl (the native
// code with musl's math library, as WebAssembly has): its JSON is compared with the
// engine's too (docs/decisions/limits-wasm-libm.md).
//
// FLAGS are the CLI's, comma-separated (`demo.obj=-n,150`); the same settings go to
// the engine. Without MESH: the demo scene at `-n 150` and at the default, and the
// made-up 100,352-face terrain of tests/wasm/meshes.mjs at `-n 200`.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..', '..');
const pkg = path.join(here, '..', 'pkg');
const engine = await import(path.join(pkg, 'primdecomp_wasm.js'));
await engine.default({ module_or_path: fs.readFileSync(path.join(pkg, 'primdecomp_wasm_bg.wasm')) });

const args = process.argv.slice(2);
const opt = (name, fallback) => {
  const i = args.indexOf(name);
  if (i < 0) return fallback;
  const v = args[i + 1];
  args.splice(i, 2);
  return v;
};
const cli = opt('--cli', path.join(root, 'target', 'release', 'primdecomp'));
const rounds = +opt('--rounds', '5');
const out = opt('--out', null);
const musl = opt('--musl', null);
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'primdecomp-speed-'));

let cases = args.map((a) => {
  const [file, flags = ''] = a.split('=');
  return { file, flags: flags ? flags.split(',') : [] };
});
if (!cases.length) {
  const { terrain } = await import(path.join(root, 'tests', 'wasm', 'meshes.mjs'));
  const t = path.join(work, 'terrain_100k.obj');
  fs.writeFileSync(t, terrain());
  const demo = path.join(root, 'datasets', 'demo_scene.obj');
  cases = [
    { file: demo, flags: ['-n', '150'] },
    { file: demo, flags: [] },
    { file: t, flags: ['-n', '200'] }
  ];
}

/** The settings the CLI's flags give, read back from the file it writes. */
function native(c) {
  const json = path.join(work, 'native.json');
  execFileSync(cli, ['decompose', c.file, '-o', json, '--quiet', '--timings', '--threads', '1', ...c.flags]);
  const doc = JSON.parse(fs.readFileSync(json, 'utf8'));
  const s = doc.stats.seconds;
  execFileSync(cli, ['decompose', c.file, '-o', json, '--quiet', ...c.flags]);
  return { seconds: s.total - (s.load || 0), settings: doc.settings, json: fs.readFileSync(json, 'utf8') };
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};

const rows = [];
for (const c of cases) {
  const mesh = engine.parseMesh(fs.readFileSync(c.file), c.file);
  const nat = [];
  const wasm = [];
  let first = null;
  let settings = null;
  let same = '';
  for (let r = 0; r < rounds; r++) {
    const n = native(c);
    nat.push(n.seconds);
    settings = JSON.stringify({ ...n.settings, target: undefined });
    const t0 = performance.now();
    const result = engine.decompose(mesh, settings, null);
    const s = (performance.now() - t0) / 1000;
    if (first === null) {
      first = s;
      const j = result.json(0);
      const a = JSON.parse(n.json).primitives;
      const b = JSON.parse(j).primitives;
      same =
        j === n.json
          ? 'byte-identical'
          : a.length !== b.length
            ? `${b.length} vs ${a.length} primitives`
            : `${a.filter((p, i) => JSON.stringify(p) !== JSON.stringify(b[i])).length} of ${a.length} written differently`;
      if (musl) {
        const m = path.join(work, 'musl.json');
        execFileSync(musl, [c.file, settings, m]);
        same += fs.readFileSync(m, 'utf8') === j ? '; the musl build: byte-identical' : '; the musl build: differs';
      }
    } else wasm.push(s);
    result.free();
  }
  const row = {
    mesh: path.basename(c.file),
    faces: mesh.faceCount,
    flags: c.flags.join(' ') || '(default: --tolerance 2%)',
    native: median(nat),
    nativeMin: Math.min(...nat),
    first,
    wasm: median(wasm),
    wasmMin: Math.min(...wasm),
    same
  };
  row.ratio = row.wasm / row.native;
  row.ratioMin = row.wasmMin / row.nativeMin;
  rows.push(row);
  mesh.free();
  console.error(`${row.mesh} ${row.flags}: native ${row.native.toFixed(3)} s, wasm ${row.wasm.toFixed(3)} s (first ${first.toFixed(3)} s), ${row.ratio.toFixed(2)}x (fastest ${row.ratioMin.toFixed(2)}x); ${same}`);
}

const wasmFile = path.join(pkg, 'primdecomp_wasm_bg.wasm');
const bytes = fs.statSync(wasmFile).size;
const gz = zlib.gzipSync(fs.readFileSync(wasmFile), { level: 9 }).length;
const lines = [
  `primdecomp_wasm_bg.wasm: ${bytes.toLocaleString('en-US')} bytes, ${gz.toLocaleString('en-US')} gzipped (-9); node ${process.version}, ${os.cpus()[0].model}, ${rounds} rounds alternating (median and fastest of each; the first wasm call apart)`,
  '',
  '| mesh | faces | settings | native 1 thread (s): median, fastest | wasm (s): median, fastest | wasm / native: medians, fastest | wasm first call (s) | primitives vs native |',
  '|---|---:|---|---:|---:|---:|---:|---|',
  ...rows.map(
    (r) =>
      `| ${r.mesh} | ${r.faces.toLocaleString('en-US')} | \`${r.flags}\` | ${r.native.toFixed(3)}, ${r.nativeMin.toFixed(3)} | ${r.wasm.toFixed(3)}, ${r.wasmMin.toFixed(3)} | ${r.ratio.toFixed(2)}, ${r.ratioMin.toFixed(2)} | ${r.first.toFixed(3)} | ${r.same} |`
  )
];
console.log(lines.join('\n'));
if (out) fs.writeFileSync(out, lines.join('\n') + '\n');
fs.rmSync(work, { recursive: true, force: true });
