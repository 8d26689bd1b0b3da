/* primdecomp view: the viewer page's script (WebGL 1, no library, no network).
 *
 * Reads the scene from the JSON in #primdecomp-data (written by primdecomp-view's
 * html.rs: geometry as base64 little-endian arrays, colours and lighting from its
 * palette.rs), draws the input mesh and the colliders as the PNG renderer does
 * (input first, the parts blended over it where they are in front, outlines along
 * feature edges), and exposes its state for tests as window.primdecompView.
 */
(function () {
  'use strict';

  var api = (window.primdecompView = {
    ready: false,
    error: null,
    frames: 0,
    level: 0,
    levels: [],
    primitives: 0,
    counts: {},
    mode: '',
    panes: [],
    selected: null
  });

  function $(id) {
    return document.getElementById(id);
  }

  function fail(msg) {
    api.error = String(msg);
    $('error').textContent = 'primdecomp view: ' + api.error;
  }

  var data;
  try {
    data = JSON.parse($('primdecomp-data').textContent);
  } catch (e) {
    fail('cannot read the embedded data: ' + e);
    return;
  }

  // ---- data -------------------------------------------------------------------

  function bytes(b64) {
    var bin = atob(b64 || '');
    var out = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
    return out.buffer;
  }
  function f32(b64) {
    return new Float32Array(bytes(b64));
  }
  function u32(b64) {
    return new Uint32Array(bytes(b64));
  }
  function rgb(hex) {
    return [1, 3, 5].map(function (i) {
      return parseInt(hex.substr(i, 2), 16) / 255;
    });
  }

  var pal = data.palette;
  var kindNames = pal.kinds.map(function (k) {
    return k.name;
  });
  var paletteRgb = pal.kinds
    .map(function (k) {
      return rgb(k.rgb);
    })
    .concat([rgb(pal.hull)]);
  var inputRgb = rgb(pal.input);
  var bgRgb = rgb(pal.background);

  function decodeCollider(c, role, index) {
    var m = c.mesh;
    return {
      role: role,
      index: index,
      label: c.label,
      file: c.file,
      kind: c.kind,
      target: c.target,
      bytes: c.bytes,
      count: c.count,
      counts: c.counts,
      parts: c.parts,
      positions: f32(m.positions),
      indices: u32(m.indices),
      starts: u32(m.starts),
      colours: m.colours,
      edges: u32(m.edges),
      gpu: null
    };
  }

  var levels = data.levels.map(function (c, i) {
    return decodeCollider(c, 'level', i);
  });
  var peers = data.peers.map(function (c, i) {
    return decodeCollider(c, 'peer', i);
  });
  var input = data.input
    ? {
        positions: f32(data.input.positions),
        indices: u32(data.input.indices),
        gpu: null
      }
    : null;

  api.levels = levels.map(function (l) {
    return { label: l.label, file: l.file, primitives: l.count, counts: l.counts };
  });
  api.peers = peers.map(function (p) {
    return { label: p.label, file: p.file, hulls: p.count };
  });
  api.palette = { kinds: pal.kinds, hull: pal.hull, input: pal.input, background: pal.background };

  // ---- WebGL ------------------------------------------------------------------

  var canvas = $('gl');
  var gl =
    canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true, alpha: false }) ||
    canvas.getContext('experimental-webgl', { antialias: true, preserveDrawingBuffer: true, alpha: false });
  if (!gl) {
    fail('WebGL is not available in this browser');
    return;
  }

  var VS = [
    'attribute vec3 aPos;',
    'attribute vec3 aNormal;',
    'attribute vec3 aColour;',
    'uniform mat4 uView;',
    'uniform mat3 uNormalMat;',
    'uniform mat4 uProj;',
    'varying vec3 vPos;',
    'varying vec3 vNormal;',
    'varying vec3 vColour;',
    'void main() {',
    '  vec4 p = uView * vec4(aPos, 1.0);',
    '  vPos = p.xyz;',
    '  vNormal = uNormalMat * aNormal;',
    '  vColour = aColour;',
    '  gl_Position = uProj * p;',
    '}'
  ].join('\n');
  // The same shading as palette.rs's shade(): ambient + key light + headlight, the
  // normal turned towards the viewer; lines (uLines = 1) take their colour unlit.
  var FS = [
    'precision highp float;',
    'uniform vec3 uKey;',
    'uniform vec3 uWeights;',
    'uniform float uAlpha;',
    'uniform float uLines;',
    'uniform float uHighlight;',
    'varying vec3 vPos;',
    'varying vec3 vNormal;',
    'varying vec3 vColour;',
    'void main() {',
    '  vec3 v = normalize(-vPos);',
    '  vec3 n = normalize(vNormal);',
    '  if (dot(n, v) < 0.0) n = -n;',
    '  float s = uWeights.x + uWeights.y * max(dot(n, uKey), 0.0) + uWeights.z * max(dot(n, v), 0.0);',
    '  vec3 c = mix(vColour * s, vColour, uLines);',
    '  c = mix(c, vec3(1.0), uHighlight);',
    '  gl_FragColor = vec4(c, uAlpha);',
    '}'
  ].join('\n');

  function shader(type, src) {
    var s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  var prog;
  try {
    prog = gl.createProgram();
    gl.attachShader(prog, shader(gl.VERTEX_SHADER, VS));
    gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, FS));
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
  } catch (e) {
    fail('shader: ' + e.message);
    return;
  }
  gl.useProgram(prog);
  var loc = {};
  ['aPos', 'aNormal', 'aColour'].forEach(function (n) {
    loc[n] = gl.getAttribLocation(prog, n);
  });
  ['uView', 'uNormalMat', 'uProj', 'uKey', 'uWeights', 'uAlpha', 'uLines', 'uHighlight'].forEach(function (n) {
    loc[n] = gl.getUniformLocation(prog, n);
  });
  gl.uniform3fv(loc.uKey, pal.light.key);
  gl.uniform3f(loc.uWeights, pal.light.ambient, pal.light.key_weight, pal.light.head_weight);

  /* Triangles expanded to one vertex per corner with the face normal, and lines. */
  function buffers(positions, indices, colourOf, edges, edgeColourOf) {
    var nt = indices.length / 3;
    var pos = new Float32Array(nt * 9);
    var nrm = new Float32Array(nt * 9);
    var col = new Float32Array(nt * 9);
    for (var t = 0; t < nt; t++) {
      var a = indices[3 * t] * 3,
        b = indices[3 * t + 1] * 3,
        c = indices[3 * t + 2] * 3;
      var ux = positions[b] - positions[a],
        uy = positions[b + 1] - positions[a + 1],
        uz = positions[b + 2] - positions[a + 2];
      var vx = positions[c] - positions[a],
        vy = positions[c + 1] - positions[a + 1],
        vz = positions[c + 2] - positions[a + 2];
      var nx = uy * vz - uz * vy,
        ny = uz * vx - ux * vz,
        nz = ux * vy - uy * vx;
      var k = colourOf(t);
      var corners = [a, b, c];
      for (var j = 0; j < 3; j++) {
        var o = t * 9 + j * 3,
          p = corners[j];
        pos[o] = positions[p];
        pos[o + 1] = positions[p + 1];
        pos[o + 2] = positions[p + 2];
        nrm[o] = nx;
        nrm[o + 1] = ny;
        nrm[o + 2] = nz;
        col[o] = k[0];
        col[o + 1] = k[1];
        col[o + 2] = k[2];
      }
    }
    var out = { triangles: nt, tri: upload(pos, nrm, col), lines: 0, line: null };
    if (edges && edges.length) {
      var ne = edges.length;
      var lp = new Float32Array(ne * 3),
        ln = new Float32Array(ne * 3),
        lc = new Float32Array(ne * 3);
      for (var e = 0; e < ne; e++) {
        var q = edges[e] * 3;
        lp[3 * e] = positions[q];
        lp[3 * e + 1] = positions[q + 1];
        lp[3 * e + 2] = positions[q + 2];
        ln[3 * e + 2] = 1;
        var ec = edgeColourOf(edges[e]);
        lc[3 * e] = ec[0];
        lc[3 * e + 1] = ec[1];
        lc[3 * e + 2] = ec[2];
      }
      out.lines = ne;
      out.line = upload(lp, ln, lc);
    }
    return out;
  }
  function upload(pos, nrm, col) {
    function buf(a) {
      var b = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, b);
      gl.bufferData(gl.ARRAY_BUFFER, a, gl.STATIC_DRAW);
      return b;
    }
    return { pos: buf(pos), nrm: buf(nrm), col: buf(col) };
  }
  function bind(b) {
    [
      ['aPos', b.pos],
      ['aNormal', b.nrm],
      ['aColour', b.col]
    ].forEach(function (x) {
      gl.bindBuffer(gl.ARRAY_BUFFER, x[1]);
      gl.enableVertexAttribArray(loc[x[0]]);
      gl.vertexAttribPointer(loc[x[0]], 3, gl.FLOAT, false, 0, 0);
    });
  }

  /* Part of each triangle and of each vertex, from the part ranges. */
  function owners(c) {
    if (c.triOwner) return;
    var nt = c.indices.length / 3;
    c.triOwner = new Uint32Array(nt);
    c.vertOwner = new Uint32Array(c.positions.length / 3);
    for (var i = 0; i + 1 < c.starts.length; i++) {
      for (var t = c.starts[i]; t < c.starts[i + 1]; t++) {
        c.triOwner[t] = i;
        c.vertOwner[c.indices[3 * t]] = i;
        c.vertOwner[c.indices[3 * t + 1]] = i;
        c.vertOwner[c.indices[3 * t + 2]] = i;
      }
    }
  }
  function colliderGpu(c) {
    if (!c.gpu) {
      owners(c);
      c.gpu = buffers(
        c.positions,
        c.indices,
        function (t) {
          return paletteRgb[c.colours[c.triOwner[t]]];
        },
        c.edges,
        function (v) {
          return paletteRgb[c.colours[c.vertOwner[v]]].map(function (x) {
            return x * pal.edge_factor;
          });
        }
      );
    }
    return c.gpu;
  }
  function inputGpu() {
    if (!input.gpu)
      input.gpu = buffers(input.positions, input.indices, function () {
        return inputRgb;
      });
    return input.gpu;
  }

  // ---- camera -----------------------------------------------------------------

  var camData = data.camera;
  var DEG = Math.PI / 180;
  function sub(a, b) {
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  }
  function dot(a, b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  }
  function cross(a, b) {
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  }
  function unit(a) {
    var l = Math.sqrt(dot(a, a)) || 1;
    return [a[0] / l, a[1] / l, a[2] / l];
  }
  function basis(back, up) {
    var right = cross(up, back);
    if (dot(right, right) < 1e-24) right = cross([1, 0, 0], back);
    right = unit(right);
    return { right: right, up: cross(back, right), back: back };
  }
  var worldUp = camData.up;
  var lo = camData.lo,
    hi = camData.hi;
  var radius = 0.5 * Math.sqrt(dot(sub(hi, lo), sub(hi, lo))) || 1;

  /* Every vertex a triangle uses (input, all levels, all peers): what the default
   * view is fitted to, as Scene::points in scene.rs. */
  var fitPoints = (function () {
    var out = [];
    function add(positions, indices) {
      var used = new Uint8Array(positions.length / 3);
      for (var i = 0; i < indices.length; i++) used[indices[i]] = 1;
      for (var v = 0; v < used.length; v++) if (used[v]) out.push(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    }
    if (input) add(input.positions, input.indices);
    levels.concat(peers).forEach(function (c) {
      add(c.positions, c.indices);
    });
    return new Float64Array(out);
  })();

  /* camera.rs's Camera::three_quarter: look at the points' projected centre from as
   * near as keeps every point within `fill` of a pane of the given aspect. */
  function fitCamera(back, aspect) {
    var b = basis(back, worldUp);
    var ty = Math.tan(0.5 * camData.fov_y_deg * DEG) * camData.fill;
    var tx = ty * Math.max(aspect, 1e-3);
    var P = fitPoints;
    var target = [0, 1, 2].map(function (k) {
      return 0.5 * (lo[k] + hi[k]);
    });
    var floor = Math.max(2e-3 * radius, 1e-150);
    function fit(t) {
      var d = floor;
      for (var i = 0; i < P.length; i += 3) {
        var r = [P[i] - t[0], P[i + 1] - t[1], P[i + 2] - t[2]];
        var z = dot(r, b.back);
        d = Math.max(d, z + Math.abs(dot(r, b.right)) / tx, z + Math.abs(dot(r, b.up)) / ty);
      }
      return d;
    }
    var dist = fit(target);
    for (var round = 0; round < camData.centring_rounds && P.length; round++) {
      var x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
      for (var i = 0; i < P.length; i += 3) {
        var r = [P[i] - target[0], P[i + 1] - target[1], P[i + 2] - target[2]];
        var depth = dist - dot(r, b.back);
        var x = dot(r, b.right) / depth / tx,
          y = dot(r, b.up) / depth / ty;
        x0 = Math.min(x0, x); x1 = Math.max(x1, x);
        y0 = Math.min(y0, y); y1 = Math.max(y1, y);
      }
      var sx = 0.5 * (x0 + x1) * tx * dist,
        sy = 0.5 * (y0 + y1) * ty * dist;
      target = [0, 1, 2].map(function (k) {
        return target[k] + sx * b.right[k] + sy * b.up[k];
      });
      dist = fit(target);
    }
    return { target: target, dist: dist };
  }

  /* `moved`: the user has orbited, panned or zoomed since the last fit; until then
   * a change of the panes' shape (a resized window) fits the view again. */
  var cam = { moved: false, aspect: 0 };
  function refit() {
    cam.aspect = paneAspect();
    var f = fitCamera(cam.back, cam.aspect);
    cam.target = f.target;
    cam.dist = f.dist;
  }
  function resetCamera() {
    cam.back = unit(camData.back);
    cam.moved = false;
    refit();
    dirty();
  }
  function eye() {
    return [0, 1, 2].map(function (k) {
      return cam.target[k] + cam.dist * cam.back[k];
    });
  }
  function viewMatrix() {
    var b = basis(cam.back, worldUp);
    var e = eye();
    // Column-major: rows right, up, back.
    return {
      m: [
        b.right[0], b.up[0], b.back[0], 0,
        b.right[1], b.up[1], b.back[1], 0,
        b.right[2], b.up[2], b.back[2], 0,
        -dot(b.right, e), -dot(b.up, e), -dot(b.back, e), 1
      ],
      n: [b.right[0], b.up[0], b.back[0], b.right[1], b.up[1], b.back[1], b.right[2], b.up[2], b.back[2]],
      basis: b,
      eye: e
    };
  }
  function projMatrix(aspect) {
    var f = 1 / Math.tan(0.5 * camData.fov_y_deg * DEG);
    var near = Math.max(cam.dist - 2 * radius, cam.dist * 1e-3, radius * 1e-4);
    var far = cam.dist + 2 * radius;
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, (2 * far * near) / (near - far), 0];
  }
  function orbit(dx, dy) {
    cam.moved = true;
    // Turn about the world's up axis, then tilt about the camera's right axis,
    // keeping away from the poles.
    var back = rotate(cam.back, worldUp, -dx * 0.008);
    var right = basis(back, worldUp).right;
    var tilted = rotate(back, right, -dy * 0.008);
    if (Math.abs(dot(tilted, worldUp)) < 0.995) back = tilted;
    cam.back = unit(back);
    dirty();
  }
  function rotate(v, axis, angle) {
    var c = Math.cos(angle),
      s = Math.sin(angle);
    var k = unit(axis);
    var kv = cross(k, v),
      kd = dot(k, v);
    return [0, 1, 2].map(function (i) {
      return v[i] * c + kv[i] * s + k[i] * kd * (1 - c);
    });
  }
  function pan(dx, dy, paneHeight) {
    cam.moved = true;
    var b = basis(cam.back, worldUp);
    var scale = (2 * cam.dist * Math.tan(0.5 * camData.fov_y_deg * DEG)) / paneHeight;
    for (var k = 0; k < 3; k++) cam.target[k] += (-dx * b.right[k] + dy * b.up[k]) * scale;
    dirty();
  }
  function zoom(factor) {
    cam.moved = true;
    cam.dist = Math.min(Math.max(cam.dist * factor, radius * 1e-3), radius * 1e3);
    dirty();
  }

  // ---- panes ------------------------------------------------------------------

  var ui = {
    level: 0,
    mode: '',
    showInput: !!input,
    inputOpacity: pal.input_opacity,
    partOpacity: pal.part_opacity,
    edges: true
  };

  /* Colliders available: the selected level of ours, then each peer. */
  function colliders() {
    var out = [];
    if (levels.length) out.push(levels[ui.level]);
    return out.concat(peers);
  }
  /* Panes as lib.rs's default_panes lays them out: side by side, the input alone
   * first, when two or more colliders are shown. */
  function panes() {
    var cs = colliders();
    var shown = ui.mode === 'side' ? cs : cs.filter(function (c) {
      return key(c) === ui.mode;
    });
    if (!shown.length && cs.length) shown = [cs[0]];
    var out = [];
    if (shown.length !== 1 && input) out.push({ label: 'input', collider: null, inputAlone: true });
    shown.forEach(function (c) {
      out.push({ label: c.role === 'level' ? 'ours, ' + c.label : c.label, collider: c });
    });
    return out;
  }
  /* A collider's key in the mode list: 'level:0' is ours at the selected level. */
  function key(c) {
    return c.role === 'level' ? 'level:0' : 'peer:' + c.index;
  }
  function layout() {
    var ps = panes();
    var w = canvas.clientWidth,
      h = canvas.clientHeight;
    var pw = w / Math.max(ps.length, 1);
    ps.forEach(function (p, i) {
      p.x = i * pw;
      p.y = 0;
      p.w = pw;
      p.h = h;
    });
    return ps;
  }
  function paneAspect() {
    var ps = layout();
    return ps.length ? ps[0].w / Math.max(ps[0].h, 1) : 1;
  }

  // ---- drawing ----------------------------------------------------------------

  var pending = false;
  function dirty() {
    if (!pending) {
      pending = true;
      requestAnimationFrame(draw);
    }
  }

  function draw() {
    pending = false;
    var dpr = window.devicePixelRatio || 1;
    var cw = Math.max(1, Math.round(canvas.clientWidth * dpr)),
      ch = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== cw || canvas.height !== ch) {
      canvas.width = cw;
      canvas.height = ch;
    }
    gl.disable(gl.SCISSOR_TEST);
    gl.viewport(0, 0, cw, ch);
    gl.clearColor(bgRgb[0], bgRgb[1], bgRgb[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    var ps = layout();
    var v = viewMatrix();
    gl.uniformMatrix4fv(loc.uView, false, v.m);
    gl.uniformMatrix3fv(loc.uNormalMat, false, v.n);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    var labels = [];
    ps.forEach(function (p) {
      var x = Math.round(p.x * dpr),
        w = Math.round((p.x + p.w) * dpr) - x;
      gl.enable(gl.SCISSOR_TEST);
      gl.viewport(x, 0, w, ch);
      gl.scissor(x, 0, w, ch);
      gl.uniformMatrix4fv(loc.uProj, false, projMatrix(w / ch));
      gl.uniform1f(loc.uHighlight, 0);
      if (input && (ui.showInput || p.inputAlone)) {
        // The input first, pushed back so flush plates on its faces win ties.
        gl.enable(gl.POLYGON_OFFSET_FILL);
        gl.polygonOffset(2, 2);
        var g = inputGpu();
        bind(g.tri);
        gl.uniform1f(loc.uLines, 0);
        gl.uniform1f(loc.uAlpha, p.inputAlone ? 1 : ui.inputOpacity);
        gl.drawArrays(gl.TRIANGLES, 0, g.triangles * 3);
        gl.disable(gl.POLYGON_OFFSET_FILL);
      }
      if (p.collider) {
        var c = colliderGpu(p.collider);
        gl.enable(gl.POLYGON_OFFSET_FILL);
        gl.polygonOffset(1, 1);
        bind(c.tri);
        gl.uniform1f(loc.uLines, 0);
        gl.uniform1f(loc.uAlpha, ui.partOpacity);
        gl.drawArrays(gl.TRIANGLES, 0, c.triangles * 3);
        gl.disable(gl.POLYGON_OFFSET_FILL);
        if (ui.edges && c.line) {
          bind(c.line);
          gl.uniform1f(loc.uLines, 1);
          gl.uniform1f(loc.uAlpha, Math.min(1, ui.partOpacity + 0.1));
          gl.drawArrays(gl.LINES, 0, c.lines);
        }
        var s = api.selected;
        if (s && s.collider === key(p.collider)) {
          var hg = highlightGpu(p.collider, s.index);
          bind(hg.tri);
          gl.uniform1f(loc.uLines, 0);
          gl.uniform1f(loc.uHighlight, 0.45);
          gl.uniform1f(loc.uAlpha, 1);
          gl.depthFunc(gl.ALWAYS);
          gl.drawArrays(gl.TRIANGLES, 0, hg.triangles * 3);
          gl.depthFunc(gl.LEQUAL);
          gl.uniform1f(loc.uHighlight, 0);
        }
      }
      labels.push('<div class="pane" style="left:' + (p.x + 8) + 'px">' + esc(p.label) + '</div>');
    });
    $('labels').innerHTML = ps.length > 1 ? labels.join('') : '';
    api.panes = ps.map(function (p) {
      return { label: p.label, x: p.x, y: p.y, w: p.w, h: p.h, collider: p.collider ? key(p.collider) : null };
    });
    api.frames++;
    if (!api.ready && !api.error) {
      var err = gl.getError();
      if (err !== gl.NO_ERROR) fail('WebGL error ' + err);
      else api.ready = true;
    }
  }

  var highlightCache = {};
  function highlightGpu(c, part) {
    var k = key(c) + '#' + part;
    if (!highlightCache[k]) {
      var idx = c.indices.subarray(3 * c.starts[part], 3 * c.starts[part + 1]);
      var col = paletteRgb[c.colours[part]];
      highlightCache = {};
      highlightCache[k] = buffers(c.positions, idx, function () {
        return col;
      });
    }
    return highlightCache[k];
  }

  // ---- picking ----------------------------------------------------------------

  /* The part under client point (x, y): the nearest triangle the ray hits. */
  function hitAt(clientX, clientY) {
    var r = canvas.getBoundingClientRect();
    var x = clientX - r.left,
      y = clientY - r.top;
    var ps = layout();
    var p = ps.filter(function (q) {
      return x >= q.x && x < q.x + q.w && y >= q.y && y < q.y + q.h;
    })[0];
    if (!p || !p.collider) return null;
    var c = p.collider;
    owners(c);
    var v = viewMatrix();
    var t = Math.tan(0.5 * camData.fov_y_deg * DEG);
    var nx = ((x - p.x) / p.w) * 2 - 1,
      ny = 1 - ((y - p.y) / p.h) * 2;
    var a = p.w / p.h;
    var d = unit([0, 1, 2].map(function (k) {
      return v.basis.right[k] * nx * t * a + v.basis.up[k] * ny * t - v.basis.back[k];
    }));
    var o = v.eye,
      P = c.positions,
      I = c.indices;
    var best = Infinity,
      bestTri = -1;
    for (var tri = 0; tri < I.length / 3; tri++) {
      var i0 = I[3 * tri] * 3,
        i1 = I[3 * tri + 1] * 3,
        i2 = I[3 * tri + 2] * 3;
      var e1 = [P[i1] - P[i0], P[i1 + 1] - P[i0 + 1], P[i1 + 2] - P[i0 + 2]];
      var e2 = [P[i2] - P[i0], P[i2 + 1] - P[i0 + 1], P[i2 + 2] - P[i0 + 2]];
      var h = cross(d, e2);
      var det = dot(e1, h);
      if (Math.abs(det) < 1e-30) continue;
      var f = 1 / det;
      var s = [o[0] - P[i0], o[1] - P[i0 + 1], o[2] - P[i0 + 2]];
      var u = f * dot(s, h);
      if (u < 0 || u > 1) continue;
      var q = cross(s, e1);
      var w = f * dot(d, q);
      if (w < 0 || u + w > 1) continue;
      var dist = f * dot(e2, q);
      if (dist > 0 && dist < best) {
        best = dist;
        bestTri = tri;
      }
    }
    if (bestTri < 0) return null;
    return { collider: key(c), index: c.triOwner[bestTri], distance: best, collider_ref: c };
  }

  function fmt(x) {
    if (typeof x === 'number') return Number.isInteger(x) ? String(x) : x.toPrecision(6).replace(/\.?0+$/, '');
    if (Array.isArray(x)) return '[' + x.map(fmt).join(', ') + ']';
    return esc(String(x));
  }
  function short(x) {
    return typeof x === 'number' ? x.toPrecision(4) : '–';
  }
  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (ch) {
      return { '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[ch];
    });
  }

  function select(hit) {
    var info = $('info');
    if (!hit) {
      api.selected = null;
      info.style.display = 'none';
      dirty();
      return null;
    }
    var c = hit.collider_ref;
    var part = c.parts[hit.index] || {};
    var sel = { collider: hit.collider, index: hit.index };
    var colour = paletteRgb[c.colours[hit.index]];
    var rows = [];
    var tris = c.starts[hit.index + 1] - c.starts[hit.index];
    var title;
    if (c.kind === 'primitives') {
      sel.kind = part.kind;
      sel.faces = part.faces;
      title = part.kind + ' #' + hit.index;
      Object.keys(part).forEach(function (k) {
        if (k !== 'kind' && k !== 'faces') rows.push([k.replace(/_/g, ' '), fmt(part[k])]);
      });
      rows.push(['input faces', fmt(part.faces)]);
      rows.push(['shown triangles', String(tris)]);
    } else {
      sel.kind = 'hull';
      title = 'hull #' + hit.index + ' of ' + c.label;
      rows.push(['vertices', fmt(part.vertices)]);
      rows.push(['triangles', fmt(part.triangles)]);
    }
    sel.title = title;
    api.selected = sel;
    info.innerHTML =
      '<h3><span class="swatch" style="display:inline-block;width:14px;height:14px;border-radius:2px;background:' +
      hex(colour) +
      '"></span>' +
      esc(title) +
      '</h3><table>' +
      rows
        .map(function (r) {
          return '<tr><td>' + esc(r[0]) + '</td><td>' + r[1] + '</td></tr>';
        })
        .join('') +
      '</table>';
    info.style.display = 'block';
    dirty();
    return sel;
  }
  function hex(c) {
    return (
      '#' +
      c
        .map(function (x) {
          return ('0' + Math.round(x * 255).toString(16)).slice(-2);
        })
        .join('')
    );
  }

  // ---- panel ------------------------------------------------------------------

  function num(x) {
    return typeof x === 'number' ? x.toLocaleString('en-US') : '–';
  }

  function buildPanel() {
    $('title').textContent = data.title;
    var files = [];
    if (data.input) {
      var d = data.input;
      files.push('<div class="file">input: ' + esc(d.file) + ' (' + num(d.faces) + ' faces)</div>');
      if (d.simplified)
        files.push(
          '<div class="note">input shown simplified for display: ' +
            num(d.triangles) +
            ' of its ' +
            num(d.source_triangles) +
            ' triangles</div>'
        );
    }
    levels.forEach(function (l) {
      files.push('<div class="file">ours: ' + esc(l.file) + '</div>');
    });
    peers.forEach(function (p) {
      files.push('<div class="file">' + esc(p.label) + ': ' + esc(p.file) + '</div>');
    });
    $('files').innerHTML = files.join('');

    var sel = $('level');
    levels.forEach(function (l, i) {
      var o = document.createElement('option');
      o.value = String(i);
      o.textContent = l.label + ' (' + l.count + ' primitives)';
      sel.appendChild(o);
    });
    $('level-row').style.display = levels.length ? '' : 'none';
    sel.onchange = function () {
      setLevel(+sel.value);
    };

    var mode = $('mode');
    var cs = colliders();
    var opts = [];
    if (levels.length) opts.push(['level:0', 'ours']);
    peers.forEach(function (p) {
      opts.push([key(p), p.label]);
    });
    if (cs.length > 1) opts.push(['side', 'side by side']);
    opts.forEach(function (o) {
      var e = document.createElement('option');
      e.value = o[0];
      e.textContent = o[1];
      mode.appendChild(e);
    });
    ui.mode = cs.length > 1 ? 'side' : opts.length ? opts[0][0] : '';
    mode.value = ui.mode;
    $('mode-row').style.display = opts.length > 1 ? '' : 'none';
    mode.onchange = function () {
      setMode(mode.value);
    };

    var si = $('show-input'),
      io = $('input-opacity'),
      po = $('part-opacity'),
      se = $('show-edges');
    $('input-row').style.display = input ? '' : 'none';
    si.checked = ui.showInput;
    io.value = String(ui.inputOpacity);
    po.value = String(ui.partOpacity);
    si.onchange = function () {
      ui.showInput = si.checked;
      dirty();
    };
    io.oninput = function () {
      ui.inputOpacity = +io.value;
      dirty();
    };
    po.oninput = function () {
      ui.partOpacity = +po.value;
      dirty();
    };
    se.onchange = function () {
      ui.edges = se.checked;
      dirty();
    };
    updatePanel();
  }

  function swatch(colour) {
    return '<span class="swatch" style="background:' + colour + '"></span>';
  }

  function updatePanel() {
    var l = levels[ui.level];
    var rows = [];
    pal.kinds.forEach(function (k) {
      var n = l ? l.counts[k.name] : 0;
      rows.push(
        '<div class="row' + (n ? '' : ' zero') + '" data-kind="' + k.name + '">' + swatch(k.rgb) + k.name + '<span class="count">' + (l ? n : '') + '</span></div>'
      );
    });
    if (peers.length)
      rows.push('<div class="row" data-kind="hull">' + swatch(pal.hull) + 'peer hull<span class="count"></span></div>');
    if (input) rows.push('<div class="row" data-kind="input">' + swatch(pal.input) + 'input mesh<span class="count"></span></div>');
    $('legend').innerHTML = rows.join('');

    var st = ['<table><tr><th></th><th>parts</th><th>bytes</th></tr>'];
    if (l) st.push('<tr><td>ours, ' + esc(l.label) + '</td><td>' + num(l.count) + '</td><td>' + num(l.bytes) + '</td></tr>');
    peers.forEach(function (p) {
      st.push('<tr><td>' + esc(p.label) + ' hulls</td><td>' + num(p.count) + '</td><td>' + num(p.bytes) + '</td></tr>');
    });
    st.push('</table>');
    $('stats').innerHTML = st.join('') + '<div class="help" style="margin-top:4px">bytes by the paper\'s Table 2: 4 per float, 2 per hull triangle index</div>';

    var ev = data.eval || [];
    $('eval-box').style.display = ev.length ? '' : 'none';
    if (ev.length) {
      var cur = l ? 'level:' + ui.level : null;
      var shownPeers = ui.mode === 'side' ? peers.map(key) : [ui.mode];
      var t = ['<table><tr><th></th><th>Hausdorff</th><th>Chamfer</th><th>encl.</th></tr>'];
      ev.forEach(function (r) {
        var name = r.matches ? (r.matches[0] === 'level' ? 'ours, ' + levels[r.matches[1]].label : peers[r.matches[1]].label) : String(r.collider).split('/').pop();
        var rk = r.matches && r.matches[0] + ':' + r.matches[1];
        var here = rk && (rk === cur || shownPeers.indexOf(rk) >= 0);
        t.push(
          '<tr' + (here ? ' style="font-weight:600"' : '') + '><td title="' + esc(r.collider) + '">' + esc(name) + '</td><td>' + short(r.hausdorff) + '</td><td>' + short(r.chamfer) + '</td><td>' + short(r.enclosure) + '</td></tr>'
        );
      });
      t.push('</table><div class="help" style="margin-top:4px">one-way distances from the collider to the input, over its bounding-box diagonal; enclosure: share of input samples inside</div>');
      $('eval').innerHTML = t.join('');
    }

    api.level = ui.level;
    api.primitives = l ? l.count : 0;
    api.counts = l ? l.counts : {};
    api.mode = ui.mode;
  }

  function setLevel(i) {
    if (!(i >= 0 && i < levels.length)) throw new Error('no level ' + i);
    ui.level = i;
    $('level').value = String(i);
    if (ui.mode.indexOf('level:') === 0) ui.mode = 'level:0';
    select(null);
    updatePanel();
    dirty();
  }
  function setMode(m) {
    ui.mode = m;
    $('mode').value = m;
    select(null);
    updatePanel();
    // The panes' shape changed: fit again, looking from where the user looks now.
    refit();
    dirty();
  }
  // ---- input events ------------------------------------------------------------

  var drag = null;
  canvas.addEventListener('contextmenu', function (e) {
    e.preventDefault();
  });
  canvas.addEventListener('pointerdown', function (e) {
    drag = { x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY, pan: e.button === 2 || e.button === 1 || e.shiftKey };
    canvas.setPointerCapture(e.pointerId);
    canvas.style.cursor = 'grabbing';
  });
  canvas.addEventListener('pointermove', function (e) {
    if (!drag) return;
    var dx = e.clientX - drag.x,
      dy = e.clientY - drag.y;
    drag.x = e.clientX;
    drag.y = e.clientY;
    if (drag.pan) pan(dx, dy, canvas.clientHeight);
    else orbit(dx, dy);
  });
  canvas.addEventListener('pointerup', function (e) {
    var d = drag;
    drag = null;
    canvas.style.cursor = 'grab';
    if (d && Math.abs(e.clientX - d.x0) + Math.abs(e.clientY - d.y0) < 4 && e.button === 0) select(hitAt(e.clientX, e.clientY));
  });
  canvas.addEventListener(
    'wheel',
    function (e) {
      e.preventDefault();
      zoom(Math.exp(e.deltaY * (e.deltaMode === 1 ? 0.05 : 0.0015)));
    },
    { passive: false }
  );
  window.addEventListener('keydown', function (e) {
    if (e.key === 'r' || e.key === 'R') resetCamera();
  });
  window.addEventListener('resize', function () {
    if (!cam.moved && paneAspect() !== cam.aspect) refit();
    dirty();
  });

  // ---- for tests ----------------------------------------------------------------

  api.setLevel = setLevel;
  api.setMode = setMode;
  api.setInput = function (on) {
    ui.showInput = !!on;
    $('show-input').checked = ui.showInput;
    dirty();
  };
  api.resetView = resetCamera;
  /* The part under a client point, without selecting it. */
  api.hitAt = function (x, y) {
    var h = hitAt(x, y);
    return h && { collider: h.collider, index: h.index };
  };

  try {
    buildPanel();
    resetCamera();
  } catch (e) {
    fail(e && e.message ? e.message : e);
  }
})();
