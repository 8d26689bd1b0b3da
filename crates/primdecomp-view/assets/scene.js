/* primdecomp view, the page's script part 1 of 3: the scene's data and the camera.
 *
 * Decodes the JSON that primdecomp-view's html.rs embeds (geometry as base64
 * little-endian arrays, colours and lighting from its palette.rs) into typed arrays,
 * and places the camera over it: the default view fitted as camera.rs fits it, orbit,
 * pan and zoom, the view and projection matrices, and the ray through a point of a pane
 * with the triangle it hits first. No DOM and no WebGL here: gl.js draws, viewer.js
 * runs the page. page.html holds the three in one function scope, in that order.
 */
var viewScene = (function () {
  'use strict';

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

  /* The page's data with its geometry decoded: the colliders (`levels` of ours, then
   * the compared `peers`), the input mesh or null, and the palette's colours as RGB in
   * [0, 1] (`partRgb` indexed by palette.rs's colour index: the kinds, then the hull).
   * `gpu` stays null until gl.js uploads the mesh. */
  function decode(data) {
    var pal = data.palette;
    return {
      data: data,
      palette: pal,
      partRgb: pal.kinds
        .map(function (k) {
          return rgb(k.rgb);
        })
        .concat([rgb(pal.hull)]),
      inputRgb: rgb(pal.input),
      backgroundRgb: rgb(pal.background),
      levels: data.levels.map(function (c, i) {
        return decodeCollider(c, 'level', i);
      }),
      peers: data.peers.map(function (c, i) {
        return decodeCollider(c, 'peer', i);
      }),
      input: data.input
        ? {
            positions: f32(data.input.positions),
            indices: u32(data.input.indices),
            gpu: null
          }
        : null
    };
  }

  /* Part of each triangle and of each vertex of collider `c`, from its part ranges
   * (`c.starts`): what picking and the outline colours look up. */
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

  // ---- vector maths -------------------------------------------------------------

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

  // ---- picking ------------------------------------------------------------------

  /* The nearest triangle of (positions, indices) that the ray from `o` along `d`
   * hits in front of `o` (Möller–Trumbore), as { triangle, distance }, or null. */
  function firstHit(positions, indices, o, d) {
    var P = positions,
      I = indices;
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
    return bestTri < 0 ? null : { triangle: bestTri, distance: best };
  }

  // ---- camera -------------------------------------------------------------------

  /* Every vertex a triangle uses (input, all levels, all peers): what the default
   * view is fitted to, as Scene::points in scene.rs. */
  function fitPoints(scene) {
    var out = [];
    function add(positions, indices) {
      var used = new Uint8Array(positions.length / 3);
      for (var i = 0; i < indices.length; i++) used[indices[i]] = 1;
      for (var v = 0; v < used.length; v++) if (used[v]) out.push(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    }
    if (scene.input) add(scene.input.positions, scene.input.indices);
    scene.levels.concat(scene.peers).forEach(function (c) {
      add(c.positions, c.indices);
    });
    return new Float64Array(out);
  }

  /* The camera over `scene`, set up from the data's `camera` (the default view's
   * direction `back`, the world's `up`, the scene's box `lo`..`hi` about the origin,
   * the field of view and how camera.rs fits). It holds where it looks from (`back`,
   * `target`, `dist`), the pane aspect it was last fitted to (`aspect`), and `moved`:
   * the user has orbited, panned or zoomed since the last fit; until then a change of
   * the panes' shape (a resized window) fits the view again. */
  function camera(scene) {
    var setup = scene.data.camera;
    var worldUp = setup.up;
    var lo = setup.lo,
      hi = setup.hi;
    var radius = 0.5 * Math.sqrt(dot(sub(hi, lo), sub(hi, lo))) || 1;
    var points = fitPoints(scene);
    var halfFov = Math.tan(0.5 * setup.fov_y_deg * DEG);

    /* camera.rs's Camera::three_quarter: look at the points' projected centre from as
     * near as keeps every point within `fill` of a pane of the given aspect. */
    function fitCamera(back, aspect) {
      var b = basis(back, worldUp);
      var ty = halfFov * setup.fill;
      var tx = ty * Math.max(aspect, 1e-3);
      var P = points;
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
      for (var round = 0; round < setup.centring_rounds && P.length; round++) {
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

    var cam = { moved: false, aspect: 0, back: unit(setup.back), target: [0, 0, 0], dist: 1 };

    /* Fits the distance and the target to panes of `aspect`, looking along `back`. */
    cam.refit = function (aspect) {
      cam.aspect = aspect;
      var f = fitCamera(cam.back, aspect);
      cam.target = f.target;
      cam.dist = f.dist;
    };
    /* Back to the default view, fitted to panes of `aspect`. */
    cam.reset = function (aspect) {
      cam.back = unit(setup.back);
      cam.moved = false;
      cam.refit(aspect);
    };
    function eye() {
      return [0, 1, 2].map(function (k) {
        return cam.target[k] + cam.dist * cam.back[k];
      });
    }
    /* The view matrix `m` (column-major) and the normal matrix `n`, with the basis and
     * the eye they come from. */
    cam.view = function () {
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
    };
    /* The perspective projection (column-major) for a pane of `aspect`, its near and
     * far planes around the scene's bounding sphere. */
    cam.projection = function (aspect) {
      var f = 1 / halfFov;
      var near = Math.max(cam.dist - 2 * radius, cam.dist * 1e-3, radius * 1e-4);
      var far = cam.dist + 2 * radius;
      return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, (2 * far * near) / (near - far), 0];
    };
    /* The ray from the eye through a pane's point at (nx, ny) in [-1, 1] (y up), for a
     * pane of `aspect`: { origin, dir } with `dir` of unit length. */
    cam.ray = function (nx, ny, aspect) {
      var v = cam.view();
      var dir = unit([0, 1, 2].map(function (k) {
        return v.basis.right[k] * nx * halfFov * aspect + v.basis.up[k] * ny * halfFov - v.basis.back[k];
      }));
      return { origin: v.eye, dir: dir };
    };
    /* A drag of (dx, dy) pixels: turn about the world's up axis, then tilt about the
     * camera's right axis, keeping away from the poles. */
    cam.orbit = function (dx, dy) {
      cam.moved = true;
      var back = rotate(cam.back, worldUp, -dx * 0.008);
      var right = basis(back, worldUp).right;
      var tilted = rotate(back, right, -dy * 0.008);
      if (Math.abs(dot(tilted, worldUp)) < 0.995) back = tilted;
      cam.back = unit(back);
    };
    /* A drag of (dx, dy) pixels in a pane `paneHeight` pixels high: the target follows
     * the pointer at its depth. */
    cam.pan = function (dx, dy, paneHeight) {
      cam.moved = true;
      var b = basis(cam.back, worldUp);
      var scale = (2 * cam.dist * halfFov) / paneHeight;
      for (var k = 0; k < 3; k++) cam.target[k] += (-dx * b.right[k] + dy * b.up[k]) * scale;
    };
    /* The distance times `factor`, within a thousandth and a thousand radii. */
    cam.zoom = function (factor) {
      cam.moved = true;
      cam.dist = Math.min(Math.max(cam.dist * factor, radius * 1e-3), radius * 1e3);
    };
    return cam;
  }

  return { decode: decode, owners: owners, firstHit: firstHit, camera: camera };
})();
