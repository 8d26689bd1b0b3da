// The WebAssembly package against the native CLI over the corpus: per mesh, whether
// the JSON is byte-identical, the same primitives (kinds and face counts) written a
// last bit apart, or different; with --musl, whether the native code built against
// musl's math library (examples/native_json) gives the package's JSON byte for byte
// (docs/decisions/limits-wasm-libm.md).
//
//   node crates/primdecomp-wasm/bench/corpus.mjs [--cli target/release/primdecomp] \
//       [--musl NATIVE_JSON] [--max-faces 300000] [--corpus ../shared/datasets/corpus] [-- CLI FLAGS…]
//
// The CLI's flags after `--` (none: the default run) give the settings; the engine
// runs the settings the CLI's file records.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..', '..');
const pd = await import(path.join(here, '..', 'pkg', 'index.js'));
const { values: o, positionals: flags } = parseArgs({
  options: {
    cli: { type: 'string', default: path.join(root, 'target', 'release', 'primdecomp') },
    musl: { type: 'string' },
    'max-faces': { type: 'string', default: '300000' },
    corpus: { type: 'string', default: path.join(root, '..', 'shared', 'datasets', 'corpus') }
  },
  allowPositionals: true
});
const { cli, musl, corpus } = o;
const maxFaces = +o['max-faces'];
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'primdecomp-corpus-'));
const tally = { identical: 0, lastBits: 0, different: 0, left: 0, musl: 0 };

for (const f of fs.readdirSync(corpus).filter((f) => /\.(obj|ply|stl|off|glb|gltf)$/i.test(f)).sort()) {
  const file = path.join(corpus, f);
  const mesh = pd.loadMesh(fs.readFileSync(file), file);
  if (mesh.faceCount > maxFaces) {
    tally.left++;
    console.log(`${f}: left out (${mesh.faceCount} faces)`);
    mesh.free();
    continue;
  }
  const out = path.join(work, 'cli.json');
  execFileSync(cli, ['decompose', file, '-o', out, '--quiet', ...flags]);
  const native = fs.readFileSync(out, 'utf8');
  const settings = JSON.parse(native).settings;
  const result = pd.decompose(mesh, settings);
  const mine = result.toJSON();
  result.free();
  mesh.free();
  const a = JSON.parse(native).primitives;
  const b = JSON.parse(mine).primitives;
  let row;
  if (mine === native) {
    tally.identical++;
    row = 'byte-identical';
  } else if (a.length === b.length && a.every((p, i) => p.kind === b[i].kind && p.faces === b[i].faces)) {
    tally.lastBits++;
    row = `the same primitives, ${a.filter((p, i) => JSON.stringify(p) !== JSON.stringify(b[i])).length} of ${a.length} written a last bit apart`;
  } else {
    tally.different++;
    row = `different: ${b.length} primitives against ${a.length}`;
  }
  if (musl) {
    execFileSync(musl, [file, JSON.stringify(settings), path.join(work, 'musl.json')]);
    const same = fs.readFileSync(path.join(work, 'musl.json'), 'utf8') === mine;
    tally.musl += same ? 1 : 0;
    row += same ? '; musl build: byte-identical' : '; musl build: DIFFERS';
  }
  console.log(`${f} (${a.length ? JSON.parse(native).input.faces : 0} faces): ${row}`);
}
console.log(JSON.stringify(tally));
fs.rmSync(work, { recursive: true, force: true });
