/* primdecomp view, the page's script part 3 of 3: the page (WebGL 1, no library, no
 * network).
 *
 * Reads the scene from the JSON in #primdecomp-data, decodes it and places the camera
 * with viewScene (scene.js), draws it with viewGl (gl.js), lays out the panes, fills
 * the side panel (levels, colliders, legend, counts, distances), picks the part under
 * a click and shows its parameters, turns pointer, wheel and key events into camera
 * moves, and exposes its state for tests as window.primdecompView.
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

  var scene = viewScene.decode(data);
  var pal = scene.palette;
  var levels = scene.levels,
    peers = scene.peers,
    input = scene.input;

  api.levels = levels.map(function (l) {
    return { label: l.label, file: l.file, primitives: l.count, counts: l.counts };
  });
  api.peers = peers.map(function (p) {
    return { label: p.label, file: p.file, hulls: p.count };
  });
  api.palette = { kinds: pal.kinds, hull: pal.hull, input: pal.input, background: pal.background };

  var canvas = $('gl');
  var gpu;
  try {
    gpu = viewGl.renderer(canvas, scene);
  } catch (e) {
    fail(e.message);
    return;
  }
  var cam = viewScene.camera(scene);

  // ---- panes ------------------------------------------------------------------

  var ui = {
    level: 0,
    mode: '',
    showInput: !!input,
    inputOpacity: pal.input_opacity,
    partOpacity: pal.part_opacity,
    edges: true
  };
  /* The selected part as { collider, index } with the decoded collider, or null;
   * api.selected says the same for tests, naming the collider by its key. */
  var selected = null;

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
    var ps = layout();
    gpu.draw(ps, cam, window.devicePixelRatio || 1, ui, selected);
    $('labels').innerHTML = ps.length > 1 ? ps.map(function (p) {
      return '<div class="pane" style="left:' + (p.x + 8) + 'px">' + esc(p.label) + '</div>';
    }).join('') : '';
    api.panes = ps.map(function (p) {
      return { label: p.label, x: p.x, y: p.y, w: p.w, h: p.h, collider: p.collider ? key(p.collider) : null };
    });
    api.frames++;
    if (!api.ready && !api.error) {
      var err = gpu.error();
      if (err !== 0) fail('WebGL error ' + err);
      else api.ready = true;
    }
  }

  function refit() {
    cam.refit(paneAspect());
  }
  function resetCamera() {
    cam.reset(paneAspect());
    dirty();
  }

  // ---- picking ----------------------------------------------------------------

  /* The part under client point (x, y): the nearest triangle the ray hits. */
  function hitAt(clientX, clientY) {
    var r = canvas.getBoundingClientRect();
    var x = clientX - r.left,
      y = clientY - r.top;
    var p = layout().filter(function (q) {
      return x >= q.x && x < q.x + q.w && y >= q.y && y < q.y + q.h;
    })[0];
    if (!p || !p.collider) return null;
    var c = p.collider;
    viewScene.owners(c);
    var ray = cam.ray(((x - p.x) / p.w) * 2 - 1, 1 - ((y - p.y) / p.h) * 2, p.w / p.h);
    var hit = viewScene.firstHit(c.positions, c.indices, ray.origin, ray.dir);
    if (!hit) return null;
    return { collider: c, index: c.triOwner[hit.triangle], distance: hit.distance };
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

  /* Selects the part `hit` names (from hitAt; null: none) and shows its kind and
   * parameters in #info; returns what api.selected now holds. */
  function select(hit) {
    var info = $('info');
    if (!hit) {
      selected = null;
      api.selected = null;
      info.style.display = 'none';
      dirty();
      return null;
    }
    var c = hit.collider;
    var part = c.parts[hit.index] || {};
    var sel = { collider: key(c), index: hit.index };
    var colour = scene.partRgb[c.colours[hit.index]];
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
    selected = { collider: c, index: hit.index };
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
    if (drag.pan) cam.pan(dx, dy, canvas.clientHeight);
    else cam.orbit(dx, dy);
    dirty();
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
      cam.zoom(Math.exp(e.deltaY * (e.deltaMode === 1 ? 0.05 : 0.0015)));
      dirty();
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
    return h && { collider: key(h.collider), index: h.index };
  };

  try {
    buildPanel();
    resetCamera();
  } catch (e) {
    fail(e && e.message ? e.message : e);
  }
})();
