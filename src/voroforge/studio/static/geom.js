/* voroforge studio: the geometry messages and drawing helpers (plain JavaScript, no build step).
 *
 * Decodes the server's binary messages (see voroforge/studio/wire.py: a JSON header and flat
 * typed arrays, rings as geometry -> ring -> coordinate offsets), maps design units to pixels,
 * and walks rings: what the page (studio.js, loaded after this file) and the rasteriser's
 * callers share. Loaded after raster.js, before studio.js.
 */
var VoroGeom = (function () {
  "use strict";

  var DTYPES = { f4: Float32Array, f8: Float64Array, i4: Int32Array, u1: Uint8Array, u2: Uint16Array };

  /* A view: design units to pixels, (x * s + tx, ty - y * s). One constructor for every view
     object, so the rasteriser's code sees one object shape. */
  function View(s, tx, ty) { this.s = s; this.tx = tx; this.ty = ty; }

  /* Coordinates sent as uint16 steps (wire.quantize, q = [x0, y0, step]): x0 + code * step in
     design units is code * (step * s) + (x0 * s + tx) in pixels, so the rasteriser draws the
     codes as they came (no copy as floats) through a view of its own, kept per view. One
     object per message, not properties added to the header's array: that array's shape
     changed on every message, and V8 threw away the optimised paint code that read it. */
  function Codes(q) {
    this.x0 = +q[0]; this.y0 = +q[1]; this.step = +q[2];
    this.vs = NaN; this.vtx = NaN; this.vty = NaN; this.v = null;
  }
  function codeView(q, v) {
    if (q.vs !== v.s || q.vtx !== v.tx || q.vty !== v.ty) {
      q.vs = v.s; q.vtx = v.tx; q.vty = v.ty;
      q.v = new View(v.s * q.step, v.tx + q.x0 * v.s, v.ty - q.y0 * v.s);
    }
    return q.v;
  }

  function unpack(buf) {
    var bytes = new Uint8Array(buf);
    var magic = String.fromCharCode(bytes[0], bytes[1], bytes[2], bytes[3]);
    if (magic !== "VFS1") throw new Error("not a studio message");
    var len = new DataView(buf).getUint32(4, true);
    var header = JSON.parse(new TextDecoder().decode(bytes.subarray(8, 8 + len)));
    var off = 8 + len, arrays = {};
    header.arrays.forEach(function (a) {
      var T = DTYPES[a[1]];
      arrays[a[0]] = new T(buf, off, a[2]);
      var size = a[2] * T.BYTES_PER_ELEMENT;
      off += size + ((8 - (size % 8)) % 8);
    });
    return { header: header, arrays: arrays };
  }

  /* One Path2D of geometry k; with `tol`, vertices closer than tol (in x and y) to the last
     one drawn are skipped (a fillet's arcs have far more vertices than pixels). */
  function buildPath(g, r, c, k, tol) {
    if (g[k + 1] <= g[k]) return null;
    var p = new Path2D();
    addRings(p, g, r, c, k, tol);
    return p;
  }

  /* Append the rings of geometry k to path p (see buildPath). */
  function addRings(p, g, r, c, k, tol) {
    var r0 = g[k], r1 = g[k + 1], d = tol || 0;
    for (var j = r0; j < r1; j++) {
      var s = r[j], e = r[j + 1];
      if (e - s < 3) continue;
      var lx = c[2 * s], ly = c[2 * s + 1];
      p.moveTo(lx, ly);
      for (var t = s + 1; t < e - 1; t++) {
        var x = c[2 * t], y = c[2 * t + 1];
        if (Math.abs(x - lx) < d && Math.abs(y - ly) < d) continue;
        p.lineTo(x, y); lx = x; ly = y;
      }
      p.closePath();
    }
  }

  function ringCoords(g, r, c, k) {
    var out = [];
    for (var j = g[k]; j < g[k + 1]; j++) {
      var ring = [];
      for (var t = r[j]; t < r[j + 1]; t++) ring.push([c[2 * t], c[2 * t + 1]]);
      out.push(ring);
    }
    return out;
  }

  /* Stable cell colours: cell i always gets the same one (the golden-angle hue walk). */
  function colourOf(i) { return (i * 7 + (i >> 5)) % 24; }

  /* The marker shapes of `voroforge check`'s overlays (added to the current path). */
  function marker(ctx, shape, x, y, r) {
    if (shape === "square") ctx.rect(x - r * 0.8, y - r * 0.8, 1.6 * r, 1.6 * r);
    else if (shape === "triangle") { ctx.moveTo(x, y + r); ctx.lineTo(x + 0.87 * r, y - 0.5 * r);
      ctx.lineTo(x - 0.87 * r, y - 0.5 * r); ctx.closePath(); }
    else if (shape === "diamond") { ctx.moveTo(x, y + r); ctx.lineTo(x + r, y); ctx.lineTo(x, y - r);
      ctx.lineTo(x - r, y); ctx.closePath(); }
    else { ctx.moveTo(x + r, y); ctx.arc(x, y, r, 0, 7); }
  }


  /* Bounding box (design units) of ring data [g, r, c] geometry k: [x0, y0, x1, y1] or null. */
  function ringBox(g, r, c, k) {
    var s = r[g[k]], e = r[g[k + 1]];
    if (e <= s) return null;
    var x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (var t = s; t < e; t++) {
      var x = c[2 * t], y = c[2 * t + 1];
      if (x < x0) x0 = x; if (x > x1) x1 = x; if (y < y0) y0 = y; if (y > y1) y1 = y;
    }
    return [x0, y0, x1, y1];
  }
  function grow(box, b) {
    if (!b) return box;
    if (!box) return b.slice();
    box[0] = Math.min(box[0], b[0]); box[1] = Math.min(box[1], b[1]);
    box[2] = Math.max(box[2], b[2]); box[3] = Math.max(box[3], b[3]);
    return box;
  }

  return {
    DTYPES: DTYPES,
    View: View,
    Codes: Codes,
    codeView: codeView,
    unpack: unpack,
    buildPath: buildPath,
    addRings: addRings,
    ringCoords: ringCoords,
    ringBox: ringBox,
    grow: grow,
    colourOf: colourOf,
    marker: marker
  };
})();
