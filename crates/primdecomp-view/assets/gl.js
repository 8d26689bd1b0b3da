/* primdecomp view, the page's script part 2 of 3: drawing with WebGL 1.
 *
 * One shader program shades as palette.rs's shade() does; meshes become GPU buffers
 * (one vertex per triangle corner with the face normal, and outline lines) on first
 * use; draw() paints the panes viewer.js lays out as the PNG renderer does: the input
 * first, the parts blended over it where they are in front, outlines along feature
 * edges, the selected part highlighted on top. Uses viewScene (scene.js).
 */
var viewGl = (function () {
  'use strict';

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

  /* The renderer for `scene` (from viewScene.decode) on `canvas`, or throws an Error
   * saying why there is none (no WebGL, or the shaders do not build). */
  function renderer(canvas, scene) {
    var gl =
      canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true, alpha: false }) ||
      canvas.getContext('experimental-webgl', { antialias: true, preserveDrawingBuffer: true, alpha: false });
    if (!gl) throw new Error('WebGL is not available in this browser');

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
      throw new Error('shader: ' + e.message);
    }
    gl.useProgram(prog);
    var pal = scene.palette;
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

    function colliderGpu(c) {
      if (!c.gpu) {
        viewScene.owners(c);
        c.gpu = buffers(
          c.positions,
          c.indices,
          function (t) {
            return scene.partRgb[c.colours[c.triOwner[t]]];
          },
          c.edges,
          function (v) {
            return scene.partRgb[c.colours[c.vertOwner[v]]].map(function (x) {
              return x * pal.edge_factor;
            });
          }
        );
      }
      return c.gpu;
    }
    function inputGpu() {
      var input = scene.input;
      if (!input.gpu)
        input.gpu = buffers(input.positions, input.indices, function () {
          return scene.inputRgb;
        });
      return input.gpu;
    }
    /* The buffers of one part alone, in its flat colour; only the last part asked for
     * is kept. */
    var highlight = null;
    function highlightGpu(c, part) {
      if (!highlight || highlight.collider !== c || highlight.part !== part) {
        var idx = c.indices.subarray(3 * c.starts[part], 3 * c.starts[part + 1]);
        var col = scene.partRgb[c.colours[part]];
        var gpu = buffers(c.positions, idx, function () {
          return col;
        });
        highlight = { collider: c, part: part, gpu: gpu };
      }
      return highlight.gpu;
    }

    /* Paints `panes` (from viewer.js's layout: x and w in CSS pixels, each with its
     * `collider` or null, `inputAlone` for the input's own pane) as seen by `cam`
     * (viewScene.camera), with `dpr` device pixels per CSS pixel. `show`: showInput,
     * inputOpacity, partOpacity and edges as the panel sets them; `selected`: the
     * highlighted part as { collider, index } (collider the decoded collider) or null. */
    function draw(panes, cam, dpr, show, selected) {
      var cw = Math.max(1, Math.round(canvas.clientWidth * dpr)),
        ch = Math.max(1, Math.round(canvas.clientHeight * dpr));
      if (canvas.width !== cw || canvas.height !== ch) {
        canvas.width = cw;
        canvas.height = ch;
      }
      var bg = scene.backgroundRgb;
      gl.disable(gl.SCISSOR_TEST);
      gl.viewport(0, 0, cw, ch);
      gl.clearColor(bg[0], bg[1], bg[2], 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      var v = cam.view();
      gl.uniformMatrix4fv(loc.uView, false, v.m);
      gl.uniformMatrix3fv(loc.uNormalMat, false, v.n);
      gl.enable(gl.DEPTH_TEST);
      gl.depthFunc(gl.LEQUAL);
      gl.enable(gl.BLEND);
      gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
      panes.forEach(function (p) {
        var x = Math.round(p.x * dpr),
          w = Math.round((p.x + p.w) * dpr) - x;
        gl.enable(gl.SCISSOR_TEST);
        gl.viewport(x, 0, w, ch);
        gl.scissor(x, 0, w, ch);
        gl.uniformMatrix4fv(loc.uProj, false, cam.projection(w / ch));
        gl.uniform1f(loc.uHighlight, 0);
        if (scene.input && (show.showInput || p.inputAlone)) {
          // The input first, pushed back so flush plates on its faces win ties.
          gl.enable(gl.POLYGON_OFFSET_FILL);
          gl.polygonOffset(2, 2);
          var g = inputGpu();
          bind(g.tri);
          gl.uniform1f(loc.uLines, 0);
          gl.uniform1f(loc.uAlpha, p.inputAlone ? 1 : show.inputOpacity);
          gl.drawArrays(gl.TRIANGLES, 0, g.triangles * 3);
          gl.disable(gl.POLYGON_OFFSET_FILL);
        }
        if (p.collider) {
          var c = colliderGpu(p.collider);
          gl.enable(gl.POLYGON_OFFSET_FILL);
          gl.polygonOffset(1, 1);
          bind(c.tri);
          gl.uniform1f(loc.uLines, 0);
          gl.uniform1f(loc.uAlpha, show.partOpacity);
          gl.drawArrays(gl.TRIANGLES, 0, c.triangles * 3);
          gl.disable(gl.POLYGON_OFFSET_FILL);
          if (show.edges && c.line) {
            bind(c.line);
            gl.uniform1f(loc.uLines, 1);
            gl.uniform1f(loc.uAlpha, Math.min(1, show.partOpacity + 0.1));
            gl.drawArrays(gl.LINES, 0, c.lines);
          }
          if (selected && selected.collider === p.collider) {
            var hg = highlightGpu(p.collider, selected.index);
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
      });
    }

    /* The first WebGL error since the last call, or 0 (gl.NO_ERROR). */
    function error() {
      return gl.getError();
    }

    return { draw: draw, error: error };
  }

  return { renderer: renderer };
})();
