// WebAssembly against native, one thread each: the time to decompose and whether the
// primitives agree. For each mesh and settings, the CLI gives the settings and the
// JSON to compare with; then rounds alternate the native library
// (examples/native_json, RAYON_NUM_THREADS=1, several decompositions in one
// process) and the package's engine in this node process (as many calls, after
// warming up), each timing the decomposition alone. The engine's very first call,
// which pays for compiling the module's code, is reported apart.
//
//   cargo build --release -p primdecomp-wasm --example native_json
//   node crates/primdecomp-wasm/bench/speed.mjs [--cli target/release/primdecomp] \
//       [--native target/release/examples/native_json] [--rounds 5] \
//       [--musl NATIVE_JSON_MUSL] [--out docs/results/wasm.md] [MESH[=FLAGS] …]
//
// FLAGS are the CLI's, comma-separated (`demo.obj=-n,150`). Without MESH: the demo
// scene and the made-up 100,352-face terrain of tests/wasm/meshes.mjs, each at a
// count (`-n 150`, `-n 200`) and at the default. --musl: native_json built for
// x86_64-unknown-linux-musl (the native code on musl's math library, as WebAssembly
// is): its JSON is compared with the engine's too (docs/decisions/limits-wasm-libm.md).
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..', '..');
const pkg = path.join(here, '..', 'pkg');
const engine = await import(path.join(pkg, 'primdecomp_wasm.js'));
await engine.default({ module_or_path: fs.readFileSync(path.join(pkg, 'primdecomp_wasm_bg.wasm')) });

const target = path.join(root, 'target', 'release');
const { values: o, positionals } = parseArgs({
  options: {
    cli: { type: 'string', default: path.join(target, 'primdecomp') },
    native: { type: 'string', default: path.join(target, 'examples', 'native_json') },
    rounds: { type: 'string', default: '5' },
    out: { type: 'string' },
    musl: { type: 'string' }
  },
  allowPositionals: true
});
const { cli, native, out, musl } = o;
const rounds = +o.rounds;
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'primdecomp-speed-'));

let cases = positionals.map((a) => {
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
    { file: t, flags: ['-n', '200'] },
    { file: t, flags: [] }
  ];
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};
const differ = (x, y) => {
  const a = JSON.parse(x).primitives;
  const b = JSON.parse(y).primitives;
  if (a.length !== b.length) return `${b.length} primitives against ${a.length}`;
  const n = a.filter((p, i) => JSON.stringify(p) !== JSON.stringify(b[i])).length;
  return n ? `${n} of ${a.length} written a last bit apart` : 'byte-identical';
};

/** Native decompositions on one thread in one process: their seconds and the JSON. */
function nativeRuns(bin, file, settings, repeat) {
  const json = path.join(work, 'native.json');
  const text = execFileSync(bin, [file, settings, json, ...(repeat > 1 ? [String(repeat)] : [])], { env: { ...process.env, RAYON_NUM_THREADS: '1' }, encoding: 'utf8' });
  return { seconds: text.trim().split('\n').map(Number), json: fs.readFileSync(json, 'utf8') };
}

const rows = [];
for (const c of cases) {
  const cliJson = path.join(work, 'cli.json');
  execFileSync(cli, ['decompose', c.file, '-o', cliJson, '--quiet', ...c.flags]);
  const reference = fs.readFileSync(cliJson, 'utf8');
  const settings = JSON.stringify(JSON.parse(reference).settings);
  const mesh = engine.parseMesh(fs.readFileSync(c.file), c.file);
  const t0 = performance.now();
  const firstResult = engine.decompose(mesh, settings, null);
  const first = (performance.now() - t0) / 1000;
  const same = differ(reference, firstResult.json(0));
  firstResult.free();
  // Warm up: V8 compiles the module's hot code with its optimising tier in the
  // background over the first calls; then as many decompositions a round as fill
  // about a second (at least one).
  let warm = first;
  for (let k = 0, spent = 0; k < 10 && spent < 3; k++) {
    const t = performance.now();
    engine.decompose(mesh, settings, null).free();
    warm = (performance.now() - t) / 1000;
    spent += warm;
  }
  const repeat = Math.max(1, Math.min(20, Math.round(1 / Math.max(warm, 1e-3))));
  const nat = [];
  const wasm = [];
  let nativeSame = '';
  for (let r = 0; r < rounds; r++) {
    const n = nativeRuns(native, c.file, settings, repeat);
    nat.push(...n.seconds);
    if (r === 0) nativeSame = n.json === reference ? 'the CLI' : 'not the CLI';
    for (let k = 0; k < repeat; k++) {
      const t = performance.now();
      engine.decompose(mesh, settings, null).free();
      wasm.push((performance.now() - t) / 1000);
    }
  }
  if (nativeSame !== 'the CLI') console.error(`${c.file}: the native library's JSON is not the CLI's`);
  let muslSame = '';
  if (musl) {
    const result = engine.decompose(mesh, settings, null);
    muslSame = nativeRuns(musl, c.file, settings, 1).json === result.json(0) ? 'byte-identical' : 'DIFFERS';
    result.free();
  }
  const row = {
    mesh: path.basename(c.file),
    faces: mesh.faceCount,
    flags: c.flags.join(' ') || '(default)',
    runs: nat.length,
    native: median(nat),
    wasm: median(wasm),
    first,
    same,
    muslSame
  };
  row.ratio = row.wasm / row.native;
  rows.push(row);
  mesh.free();
  console.error(
    `${row.mesh} ${row.flags}: native ${row.native.toFixed(4)} s, wasm ${row.wasm.toFixed(4)} s (${row.runs} each; first call ${first.toFixed(3)} s): ${row.ratio.toFixed(2)}x; ${same}${musl ? `; musl build vs wasm: ${muslSame}` : ''}`
  );
}

const wasmFile = path.join(pkg, 'primdecomp_wasm_bg.wasm');
const bytes = fs.statSync(wasmFile).size;
// gzip -9 where the tool is there (build.sh prints the same figure), else zlib's.
let gz;
try {
  gz = execFileSync('gzip', ['-9', '-c', wasmFile]).length;
} catch {
  gz = zlib.gzipSync(fs.readFileSync(wasmFile), { level: 9 }).length;
}
const lines = [
  `primdecomp_wasm_bg.wasm: ${bytes.toLocaleString('en-US')} bytes, ${gz.toLocaleString('en-US')} gzipped (gzip -9). node ${process.version}, ${os.cpus()[0].model}; ${rounds} rounds alternating native and WebAssembly, medians of every decomposition (warm); the first WebAssembly call apart.`,
  '',
  `| mesh | faces | CLI flags | native, 1 thread (s) | WebAssembly (s) | WebAssembly / native | first WebAssembly call (s) | primitives against the CLI's${musl ? ' | musl build against WebAssembly' : ''} |`,
  `|---|---:|---|---:|---:|---:|---:|---|${musl ? '---|' : ''}`,
  ...rows.map(
    (r) =>
      `| ${r.mesh} | ${r.faces.toLocaleString('en-US')} | \`${r.flags}\` | ${r.native.toFixed(4)} | ${r.wasm.toFixed(4)} | ${r.ratio.toFixed(2)} | ${r.first.toFixed(3)} | ${r.same}${musl ? ` | ${r.muslSame}` : ''} |`
  )
];
console.log(lines.join('\n'));
if (out) fs.writeFileSync(out, lines.join('\n') + '\n');
fs.rmSync(work, { recursive: true, force: true });
