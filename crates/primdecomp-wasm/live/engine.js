// The live page's engine: the wasm-bindgen glue (`--target no-modules`: a classic
// script defining `wasm_bindgen`, placed before this text by build.mjs) and a
// message handler that loads meshes and decomposes them. It runs in a Worker made
// from this text, so the page stays responsive while it works (a classic worker: a
// page opened from file:// cannot start a module worker from a blob); where no
// worker can be made, the page runs the same text as a script and calls
// `primdecompEngine.handle` itself.
//
// Messages in: {type: 'init', wasm: ArrayBuffer | WebAssembly.Module},
// {type: 'load', bytes: ArrayBuffer, name} (no bytes: the built-in demo scene),
// {type: 'run', id, settings}, {type: 'export', id, format}.
// Out: {type: 'ready', version}, {type: 'mesh', …}, {type: 'result', id, …},
// {type: 'file', id, bytes}, {type: 'error', id, message}.

(function () {
const { initSync, version, parseMesh, decompose, demoSceneObj } = wasm_bindgen;
let mesh = null;
let last = null;

function box(m) {
  const p = m.trianglePositions();
  let lo = [Infinity, Infinity, Infinity];
  let hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3)
    for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k], p[i + k]);
      hi[k] = Math.max(hi[k], p[i + k]);
    }
  return { lo, hi, positions: p };
}

async function handle(msg, reply) {
  try {
    if (msg.type === 'init') {
      const module = msg.wasm instanceof WebAssembly.Module ? msg.wasm : await WebAssembly.compile(msg.wasm);
      initSync({ module });
      reply({ type: 'ready', id: msg.id, version: version() });
    } else if (msg.type === 'load') {
      const bytes = msg.bytes ? new Uint8Array(msg.bytes) : new TextEncoder().encode(demoSceneObj());
      const next = parseMesh(bytes, msg.name);
      if (mesh) mesh.free();
      if (last) last.free();
      mesh = next;
      last = null;
      const b = box(mesh);
      const indices = mesh.triangleIndices();
      reply(
        {
          type: 'mesh',
          id: msg.id,
          name: msg.name,
          faces: mesh.faceCount,
          vertices: mesh.vertexCount,
          lo: b.lo,
          hi: b.hi,
          positions: b.positions,
          indices
        },
        [b.positions.buffer, indices.buffer]
      );
    } else if (msg.type === 'run') {
      if (!mesh) throw new Error('no mesh loaded');
      const t0 = performance.now();
      let told = -1;
      const progress = (stage, fraction) => {
        // A report every 10% of the merge (the longest stage) and at each stage's start.
        const step = stage === 'merge' ? Math.floor(10 * fraction) : -1;
        if (stage !== 'merge' || step !== told) reply({ type: 'progress', stage, fraction });
        told = step;
      };
      const result = decompose(mesh, JSON.stringify(msg.settings), progress);
      const seconds = (performance.now() - t0) / 1000;
      const json = result.json(0);
      const doc = JSON.parse(json);
      const t = result.tessellate(0, 16);
      const out = {
        type: 'result',
        id: msg.id,
        seconds,
        json,
        count: doc.stats.primitives,
        bytes: doc.stats.bytes,
        counts: doc.stats.counts,
        distance: doc.stats.distance || null,
        positions: t.positions(),
        indices: t.indices(),
        starts: t.starts(),
        kinds: t.kinds()
      };
      t.free();
      if (last) last.free();
      last = result;
      reply(out, [out.positions.buffer, out.indices.buffer, out.starts.buffer, out.kinds.buffer]);
    } else if (msg.type === 'export') {
      if (!last) throw new Error('nothing decomposed yet');
      const bytes = last.export(0, msg.format, 'primdecomp', false, 1, false, false, false, 16);
      reply({ type: 'file', id: msg.id, format: msg.format, bytes }, [bytes.buffer]);
    }
  } catch (e) {
    // A trap is a panic (a bug): the instance cannot be trusted after it.
    const message = e instanceof WebAssembly.RuntimeError
      ? `internal error in primdecomp (a bug, please report it): ${wasm_bindgen.takePanic() || e.message}; reload the page`
      : e && e.message ? e.message : String(e);
    reply({ type: 'error', id: msg.id, message });
  }
}

if (typeof WorkerGlobalScope !== 'undefined' && self instanceof WorkerGlobalScope) {
  self.onmessage = (e) => handle(e.data, (m, transfer) => self.postMessage(m, transfer || []));
} else {
  self.primdecompEngine = { handle };
}
})();
