// primdecomp live: the page's script. Loads a mesh (the built-in demo scene, or a
// file dropped on the page or chosen), decomposes it in the WebAssembly engine
// (engine.js, in a Worker when one can be made) whenever a target slider moves, and
// draws the mesh and the primitives with WebGL. Exposes its state for tests as
// window.primdecompLive.

// The viewer's palette (crates/primdecomp-view/src/palette.rs; build.mjs checks
// that these are its values).
const KINDS = ['box', 'sphere', 'capsule', 'cylinder', 'frustum', 'prism'];
const KIND_RGB = ['#3d74d6', '#e03c3c', '#2fa84a', '#f08a1c', '#9a4fd0', '#16b0b0'];
const INPUT_RGB = '#a8a8a8';
const BACKGROUND_RGB = '#f7f7f5';

// Slider stops: what a user would type after --tolerance (percent of the diagonal),
// -n (with --cut) and --max-bytes.
const STOPS = {
  tolerance: [0.1, 0.15, 0.2, 0.3, 0.5, 0.75, 1, 1.5, 2, 3, 5, 7.5, 10],
  count: [1, 2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 32, 40, 48, 64, 80, 96, 128, 160, 192, 256, 320, 384, 512, 640, 768, 1024],
  bytes: [64, 128, 256, 384, 512, 768, 1024, 1536, 2048, 3072, 4096, 6144, 8192, 12288, 16384, 24576, 32768, 49152, 65536]
};
const START = { tolerance: 2, count: 64, bytes: 4096 };

const $ = (id) => document.getElementById(id);
const api = (window.primdecompLive = {
  ready: false,
  busy: false,
  error: null,
  worker: false,
  version: null,
  mode: 'tolerance',
  mesh: null,
  result: null,
  runs: 0,
  /** The settings of the last finished run, and those the sliders ask for now. */
  settings: null,
  requested: null,
  cli: ''
});

function fail(message) {
  api.error = String(message);
  $('status').textContent = api.error;
  $('status').className = 'error';
}
function status(text) {
  $('status').textContent = text;
  $('status').className = '';
}

// ---- the engine ---------------------------------------------------------------

function base64Bytes(text) {
  const bin = atob(text.trim());
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

let send = null; // send(message, transfer)
let nextId = 1;
const waiting = new Map();

function onReply(m) {
  if (m.type === 'progress') {
    status(`decomposing: ${m.stage} ${Math.round(100 * m.fraction)}%`);
    return;
  }
  const w = waiting.get(m.id);
  if (w) {
    waiting.delete(m.id);
    if (m.type === 'error') w.reject(new Error(m.message));
    else w.resolve(m);
  }
}

function ask(message, transfer) {
  const id = nextId++;
  return new Promise((resolve, reject) => {
    waiting.set(id, { resolve, reject });
    send({ ...message, id }, transfer);
  });
}

async function startEngine() {
  const source = $('primdecomp-engine').textContent;
  const wasm = base64Bytes($('primdecomp-wasm').textContent);
  const url = URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
  try {
    const worker = new Worker(url);
    worker.onmessage = (e) => onReply(e.data);
    await new Promise((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error('the worker did not start')), 20000);
      worker.onerror = (e) => {
        clearTimeout(timer);
        reject(new Error(e.message || 'worker error'));
      };
      waiting.set(0, {
        resolve: (m) => {
          clearTimeout(timer);
          resolve(m);
        },
        reject
      });
      worker.postMessage({ type: 'init', id: 0, wasm: wasm.buffer }, [wasm.buffer]);
    }).then((m) => (api.version = m.version));
    send = (m, transfer) => worker.postMessage(m, transfer || []);
    api.worker = true;
  } catch (e) {
    api.workerError = String(e && e.message ? e.message : e);
    // No worker here: the same engine on this thread (the page pauses while it
    // works).
    await new Promise((resolve, reject) => {
      const script = document.createElement('script');
      script.src = url;
      script.onload = resolve;
      script.onerror = () => reject(new Error('cannot start the engine'));
      document.head.appendChild(script);
    });
    const engine = window.primdecompEngine;
    send = (m) => setTimeout(() => engine.handle(m, onReply), 0);
    const fresh = base64Bytes($('primdecomp-wasm').textContent);
    const ready = await new Promise((resolve) => engine.handle({ type: 'init', id: 0, wasm: fresh.buffer }, resolve));
    if (ready.type === 'error') throw new Error(ready.message);
    api.version = ready.version;
    api.worker = false;
  }
}

// ---- targets ------------------------------------------------------------------

function stop(mode) {
  return STOPS[mode][+$(mode).value];
}
function showBytes(b) {
  return b >= 1024 && b % 1024 === 0 ? b / 1024 + 'K' : String(b);
}
function label(mode) {
  const v = stop(mode);
  return mode === 'tolerance' ? v + '%' : mode === 'bytes' ? showBytes(v) : String(v);
}
/** The kinds ticked, or null when all are (the default). */
function kinds() {
  const on = KINDS.filter((k) => $('kind-' + k).checked);
  return on.length === KINDS.length ? null : on;
}
/** The run's settings (a result file's `settings`, in part) and the CLI's words. */
function target() {
  const v = stop(api.mode);
  const t =
    api.mode === 'tolerance'
      ? { settings: { tolerance: [{ diagonal: v / 100 }] }, cli: `--tolerance ${v}%` }
      : api.mode === 'count'
        ? { settings: { targets: [v], cut: true }, cli: `-n ${v} --cut` }
        : { settings: { max_bytes: [v] }, cli: `--max-bytes ${showBytes(v)}` };
  const only = kinds();
  if (only) {
    t.settings.kinds = Object.fromEntries(KINDS.map((k) => [k, only.includes(k)]));
    t.cli += ` --kinds ${only.join(',')}`;
  }
  return t;
}

function setMode(mode) {
  api.mode = mode;
  for (const m of Object.keys(STOPS)) {
    $('row-' + m).classList.toggle('active', m === mode);
    document.querySelector(`input[name=mode][value=${m}]`).checked = m === mode;
  }
  changed();
}

/** A file name as one shell word that the CLI reads as a file (not a flag). */
function shellWord(name) {
  const word = name.startsWith('-') ? `./${name}` : name;
  return /^[\w.\-/]+$/.test(word) ? word : `'${word.replace(/'/g, `'\\''`)}'`;
}

function changed() {
  for (const m of Object.keys(STOPS)) $(m + '-value').textContent = label(m);
  const t = target();
  api.cli = `primdecomp decompose ${api.mesh ? shellWord(api.mesh.name) : 'MESH'} ${t.cli}`;
  $('cli').textContent = api.cli;
  api.requested = t.settings;
  request(t.settings);
}

// ---- runs: the latest settings win --------------------------------------------

let wanted = null;
let running = false;

function request(settings) {
  wanted = settings;
  if (!running && api.mesh) pump();
}

async function pump() {
  running = true;
  api.busy = true;
  while (wanted) {
    const settings = wanted;
    wanted = null;
    status('decomposing…');
    try {
      const r = await ask({ type: 'run', settings });
      api.runs++;
      api.settings = settings;
      show(r);
      status(`done in ${(1000 * r.seconds).toFixed(0)} ms` + (api.worker ? '' : ' (on the page thread)'));
    } catch (e) {
      fail(e.message);
    }
  }
  running = false;
  api.busy = false;
}

function show(r) {
  const diagonal = api.mesh.diagonal;
  const d = r.distance;
  api.result = { count: r.count, bytes: r.bytes, counts: r.counts, distance: d ? d.worst : null, seconds: r.seconds, json: r.json };
  $('out-count').textContent = r.count.toLocaleString('en-US');
  $('out-bytes').textContent = r.bytes.toLocaleString('en-US');
  $('out-distance').textContent = d ? `${d.worst.toPrecision(3)} (${(100 * d.worst / diagonal).toFixed(2)}%)` : '–';
  $('out-time').textContent = `${(1000 * r.seconds).toFixed(0)} ms`;
  $('legend').innerHTML = KINDS.map(
    (k, i) => `<tr class="${r.counts[k] ? '' : 'zero'}" data-kind="${k}"><td><span class="swatch" style="background:${KIND_RGB[i]}"></span>${k}</td><td>${r.counts[k]}</td></tr>`
  ).join('');
  $('save-json').disabled = false;
  $('save-glb').disabled = false;
  scene.parts = geometry(r.positions, r.indices, (t) => KIND_RGB_F[r.kinds[owner(r.starts, t)]]);
  draw();
}

function owner(starts, t) {
  let lo = 0;
  let hi = starts.length - 2;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (starts[mid] <= t) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

// ---- meshes -------------------------------------------------------------------

function escapeText(s) {
  return String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
}

async function load(bytes, name) {
  status(`reading ${name}…`);
  try {
    const m = await ask({ type: 'load', bytes, name }, bytes ? [bytes] : []);
    const diag = Math.hypot(m.hi[0] - m.lo[0], m.hi[1] - m.lo[1], m.hi[2] - m.lo[2]);
    api.mesh = { name: m.name, faces: m.faces, vertices: m.vertices, diagonal: diag };
    api.error = null;
    $('mesh').innerHTML = `${escapeText(m.name)}: ${m.faces.toLocaleString('en-US')} faces, ${m.vertices.toLocaleString('en-US')} vertices`;
    scene.input = geometry(m.positions, m.indices, () => INPUT_RGB_F);
    scene.parts = null;
    scene.radius = 0.5 * diag || 1;
    resetView();
    changed();
  } catch (e) {
    fail(e.message);
  }
}

async function loadFile(file) {
  if (!file) return;
  load(await file.arrayBuffer(), file.name);
}

function save(name, bytes, type) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([bytes], { type }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

/** The mesh's file name without its extension, as a file name on any system: no
 * separators, control or reserved characters, no leading dot, at most 200 characters. */
function stem() {
  const name = (api.mesh ? api.mesh.name : 'mesh').replace(/\.[^.]*$/, '');
  // eslint-disable-next-line no-control-regex
  const safe = name.replace(/[\u0000-\u001f\u007f/\\:*?"<>|]/g, '_').replace(/^[.\s]+/, '').slice(0, 200);
  return safe || 'mesh';
}

// ---- drawing (WebGL 1) ----------------------------------------------------------

const canvas = $('gl');
const gl = canvas.getContext('webgl', { antialias: true, alpha: false, preserveDrawingBuffer: true });
const rgbF = (hex) => [1, 3, 5].map((i) => parseInt(hex.substr(i, 2), 16) / 255);
const KIND_RGB_F = KIND_RGB.map(rgbF);
const INPUT_RGB_F = rgbF(INPUT_RGB);
const scene = { input: null, parts: null, radius: 1, yaw: 0.7, pitch: 0.45, dist: 3 };

const VS = `attribute vec3 aPos; attribute vec3 aNormal; attribute vec3 aColour;
uniform mat4 uView; uniform mat4 uProj; varying vec3 vN; varying vec3 vC; varying vec3 vP;
void main() { vec4 p = uView * vec4(aPos, 1.0); vP = p.xyz; vN = mat3(uView) * aNormal; vC = aColour; gl_Position = uProj * p; }`;
// palette.rs's shade(): ambient + key light + headlight, the normal towards the eye.
const FS = `precision highp float; uniform float uAlpha; varying vec3 vN; varying vec3 vC; varying vec3 vP;
void main() { vec3 v = normalize(-vP); vec3 n = normalize(vN); if (dot(n, v) < 0.0) n = -n;
float s = 0.28 + 0.42 * max(dot(n, normalize(vec3(-1.0, 1.0, 2.0))), 0.0) + 0.30 * max(dot(n, v), 0.0);
gl_FragColor = vec4(vC * s, uAlpha); }`;

function program() {
  const compile = (type, src) => {
    const s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  };
  const p = gl.createProgram();
  gl.attachShader(p, compile(gl.VERTEX_SHADER, VS));
  gl.attachShader(p, compile(gl.FRAGMENT_SHADER, FS));
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
  return p;
}

let prog = null;
const loc = {};

/** Triangles with one vertex per corner and the face's normal, uploaded. */
function geometry(positions, indices, colourOf) {
  const n = indices.length / 3;
  const pos = new Float32Array(9 * n);
  const nrm = new Float32Array(9 * n);
  const col = new Float32Array(9 * n);
  for (let t = 0; t < n; t++) {
    const a = 3 * indices[3 * t];
    const b = 3 * indices[3 * t + 1];
    const c = 3 * indices[3 * t + 2];
    const u = [0, 1, 2].map((k) => positions[b + k] - positions[a + k]);
    const v = [0, 1, 2].map((k) => positions[c + k] - positions[a + k]);
    const nx = u[1] * v[2] - u[2] * v[1];
    const ny = u[2] * v[0] - u[0] * v[2];
    const nz = u[0] * v[1] - u[1] * v[0];
    const k = colourOf(t);
    [a, b, c].forEach((p, j) => {
      const o = 9 * t + 3 * j;
      pos.set([positions[p], positions[p + 1], positions[p + 2]], o);
      nrm.set([nx, ny, nz], o);
      col.set(k, o);
    });
  }
  if (!gl) return null;
  const upload = (a) => {
    const buf = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, buf);
    gl.bufferData(gl.ARRAY_BUFFER, a, gl.STATIC_DRAW);
    return buf;
  };
  return { count: 3 * n, pos: upload(pos), nrm: upload(nrm), col: upload(col) };
}

const FOV_Y = (30 * Math.PI) / 180;

/** The default view: from the front-right, above, near enough that the mesh's
 * bounding sphere just fits the canvas. */
function resetView() {
  scene.yaw = 0.7;
  scene.pitch = 0.45;
  const aspect = canvas.clientWidth / Math.max(1, canvas.clientHeight);
  const half = Math.min(FOV_Y / 2, Math.atan(aspect * Math.tan(FOV_Y / 2)));
  scene.dist = (1.05 * scene.radius) / Math.sin(half);
  draw();
}

function matrices(aspect) {
  const cy = Math.cos(scene.yaw), sy = Math.sin(scene.yaw), cp = Math.cos(scene.pitch), sp = Math.sin(scene.pitch);
  const back = [sy * cp, sp, cy * cp]; // from the target towards the eye (+y up)
  const right = [cy, 0, -sy];
  const up = [-sy * sp, cp, -cy * sp];
  const eye = back.map((x) => x * scene.dist);
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const view = [right[0], up[0], back[0], 0, right[1], up[1], back[1], 0, right[2], up[2], back[2], 0, -dot(right, eye), -dot(up, eye), -dot(back, eye), 1];
  const f = 1 / Math.tan(FOV_Y / 2);
  const near = Math.max(scene.dist - 2 * scene.radius, scene.dist * 1e-3);
  const far = scene.dist + 2 * scene.radius;
  const proj = [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, (2 * far * near) / (near - far), 0];
  return { view, proj };
}

let frame = 0;
function draw() {
  if (frame || !gl) return;
  frame = requestAnimationFrame(() => {
    frame = 0;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(canvas.clientWidth * dpr));
    const h = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== w || canvas.height !== h) {
      canvas.width = w;
      canvas.height = h;
    }
    gl.viewport(0, 0, w, h);
    const bg = rgbF(BACKGROUND_RGB);
    gl.clearColor(bg[0], bg[1], bg[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    const m = matrices(w / h);
    gl.uniformMatrix4fv(loc.uView, false, m.view);
    gl.uniformMatrix4fv(loc.uProj, false, m.proj);
    // The mesh first, opaque and pushed back; the colliders over it, see-through.
    for (const [g, alpha, offset] of [
      [$('show-mesh').checked ? scene.input : null, 1, 2],
      [scene.parts, 0.55, 1]
    ]) {
      if (!g) continue;
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(offset, offset);
      for (const [name, buf] of [
        ['aPos', g.pos],
        ['aNormal', g.nrm],
        ['aColour', g.col]
      ]) {
        gl.bindBuffer(gl.ARRAY_BUFFER, buf);
        gl.enableVertexAttribArray(loc[name]);
        gl.vertexAttribPointer(loc[name], 3, gl.FLOAT, false, 0, 0);
      }
      gl.uniform1f(loc.uAlpha, alpha);
      gl.drawArrays(gl.TRIANGLES, 0, g.count);
    }
    gl.disable(gl.POLYGON_OFFSET_FILL);
    api.frames = (api.frames || 0) + 1;
  });
}

// ---- wiring -------------------------------------------------------------------

function wire() {
  for (const m of Object.keys(STOPS)) {
    const s = $(m);
    s.min = 0;
    s.max = STOPS[m].length - 1;
    s.step = 1;
    s.value = STOPS[m].indexOf(START[m]);
    s.addEventListener('input', () => (api.mode === m ? changed() : setMode(m)));
    document.querySelector(`input[name=mode][value=${m}]`).addEventListener('change', () => setMode(m));
  }
  $('file').addEventListener('change', (e) => loadFile(e.target.files[0]));
  $('kinds').innerHTML = KINDS.map(
    (k, i) => `<label title="${k}"><input type="checkbox" id="kind-${k}" checked><span class="swatch" style="background:${KIND_RGB[i]}"></span>${k}</label>`
  ).join('');
  for (const k of KINDS)
    $('kind-' + k).addEventListener('change', () => {
      // At least one kind: unticking the last one ticks it again.
      if (!KINDS.some((x) => $('kind-' + x).checked)) $('kind-' + k).checked = true;
      changed();
    });
  $('show-mesh').addEventListener('change', draw);
  window.addEventListener('dragover', (e) => {
    e.preventDefault();
    document.body.classList.add('dragging');
  });
  window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
  window.addEventListener('drop', (e) => {
    e.preventDefault();
    document.body.classList.remove('dragging');
    loadFile(e.dataTransfer.files[0]);
  });
  $('save-json').addEventListener('click', () => api.result && save(stem() + '.primdecomp.json', api.result.json, 'application/json'));
  $('save-glb').addEventListener('click', async () => {
    try {
      const f = await ask({ type: 'export', format: 'glb' });
      save(stem() + '.colliders.glb', f.bytes, 'model/gltf-binary');
    } catch (e) {
      fail(e.message);
    }
  });
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => {
    drag = { x: e.clientX, y: e.clientY };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    scene.yaw -= 0.008 * (e.clientX - drag.x);
    scene.pitch = Math.max(-1.5, Math.min(1.5, scene.pitch + 0.008 * (e.clientY - drag.y)));
    drag = { x: e.clientX, y: e.clientY };
    draw();
  });
  canvas.addEventListener('pointerup', () => (drag = null));
  canvas.addEventListener(
    'wheel',
    (e) => {
      e.preventDefault();
      scene.dist *= Math.exp(e.deltaY * 0.0015);
      draw();
    },
    { passive: false }
  );
  window.addEventListener('keydown', (e) => (e.key === 'r' || e.key === 'R') && resetView());
  window.addEventListener('resize', draw);
}

async function main() {
  wire();
  if (!gl) throw new Error('WebGL is not available in this browser');
  prog = program();
  gl.useProgram(prog);
  for (const n of ['aPos', 'aNormal', 'aColour']) loc[n] = gl.getAttribLocation(prog, n);
  for (const n of ['uView', 'uProj', 'uAlpha']) loc[n] = gl.getUniformLocation(prog, n);
  status('starting the engine…');
  await startEngine();
  api.ready = true;
  setMode('tolerance');
  await load(null, 'demo_scene.obj');
}

main().catch((e) => fail(e && e.message ? e.message : e));
