/* voroforge studio: a small scanline rasteriser for the cells (plain JavaScript, no build step).
 *
 * Canvas 2D paths cost far more than the pixels they cover when there are thousands of them
 * (building a Path2D point by point, then Skia's anti-aliased fill and stroke in software: a
 * 2,000-cell redraw took 100+ ms). Cells are simple: polygons with a few rings, filled flat,
 * outlined with one-pixel lines. This draws them straight into an ImageData's pixels:
 *
 * - fillRings: even-odd scanline fill of one geometry's rings (sampled at pixel centres),
 *   clipped to a pixel rectangle, vertices closer than `tol` pixels to the last kept one
 *   skipped (a fillet's arcs have far more vertices than pixels);
 * - lineRings: the rings' outlines as anti-aliased one-pixel lines (Xiaolin Wu), kept as a
 *   coverage mask with max(): an edge shared by two cells and drawn twice is drawn once;
 * - composite: the outline colour blended over the fills by that coverage.
 *
 * Geometry arrives as flat GeoArrow-like buffers (see voroforge/studio/wire.py): geometry k
 * owns rings g[k]..g[k+1], ring j owns coordinates r[j]..r[j+1] of c (x, y interleaved,
 * closed: the last repeats the first). `v` maps design units to pixels: (x * v.s + v.tx,
 * v.ty - y * v.s).
 */
var VoroRaster = (function () {
  "use strict";

  var edges = new Float64Array(4096), xs = new Float64Array(4096), counts = new Int32Array(512), per = 8;

  /* Pixel colour as the little-endian uint32 an ImageData's Uint32Array view holds. */
  function rgba32(r, g, b) { return ((255 << 24) | (b << 16) | (g << 8) | r) >>> 0; }

  function hslToRgb(h, s, l) {
    var a = s * Math.min(l, 1 - l);
    function f(n) { var k = (n + h / 30) % 12; return Math.round(255 * (l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1)))); }
    return [f(0), f(8), f(4)];
  }

  function pushEdge(ne, x0, y0, x1, y1) {
    if (4 * ne + 4 > edges.length) { var e = new Float64Array(edges.length * 2); e.set(edges); edges = e; }
    edges[4 * ne] = x0; edges[4 * ne + 1] = y0; edges[4 * ne + 2] = x1; edges[4 * ne + 3] = y1;
    return ne + 1;
  }

  /* Fill geometry k of (g, r, c) with `colour` into px (width W), inside the pixel rectangle
     rect = [X0, Y0, X1, Y1) (even-odd rule, pixel centres). Edge by edge: each edge puts its
     crossings with the pixel rows it spans into those rows' lists (a few per row), so the
     work is the edges plus the crossings, not every edge for every row. */
  function fillRings(px, W, rect, g, r, c, k, colour, v, tol) {
    var ne = 0, ymin = Infinity, ymax = -Infinity, s = v.s, tx = v.tx, ty = v.ty;
    for (var j = g[k]; j < g[k + 1]; j++) {
      var a = r[j], b = r[j + 1];
      if (b - a < 3) continue;
      var lx = c[2 * a] * s + tx, ly = ty - c[2 * a + 1] * s;
      if (ly < ymin) ymin = ly; if (ly > ymax) ymax = ly;
      for (var t = a + 1; t < b; t++) {
        var x = c[2 * t] * s + tx, y = ty - c[2 * t + 1] * s;
        if (t < b - 1 && Math.abs(x - lx) < tol && Math.abs(y - ly) < tol) continue;
        if (y !== ly) ne = pushEdge(ne, lx, ly, x, y);
        if (y < ymin) ymin = y; if (y > ymax) ymax = y;
        lx = x; ly = y;
      }
    }
    var y0 = Math.max(rect[1], Math.ceil(ymin - 0.5)), y1 = Math.min(rect[3], Math.ceil(ymax - 0.5));
    var rows = y1 - y0;
    if (rows <= 0 || ne === 0) return;
    if (rows > counts.length) counts = new Int32Array(2 * rows);
    for (;;) {  // until every row's crossings fit in `per` slots
      if (rows * per > xs.length) xs = new Float64Array(2 * rows * per);
      counts.fill(0, 0, rows);
      var full = false;
      for (var e = 0; e < ne && !full; e++) {
        var ex0 = edges[4 * e], ey0 = edges[4 * e + 1], ex1 = edges[4 * e + 2], ey1 = edges[4 * e + 3];
        // the rows whose centre yc has (ey0 <= yc) !== (ey1 <= yc)
        var lo = ey0 < ey1 ? ey0 : ey1, hi = ey0 < ey1 ? ey1 : ey0;
        var ra = Math.max(y0, Math.ceil(lo - 0.5)), rb = Math.min(y1, Math.ceil(hi - 0.5));
        for (var row = ra; row < rb; row++) {
          var q = row - y0, n = counts[q];
          if (n === per) { full = true; break; }
          xs[q * per + n] = ex0 + (row + 0.5 - ey0) * (ex1 - ex0) / (ey1 - ey0);
          counts[q] = n + 1;
        }
      }
      if (!full) break;
      per *= 2;
    }
    var X0 = rect[0], X1 = rect[2];
    for (var q2 = 0; q2 < rows; q2++) {
      var nx = counts[q2], o = q2 * per;
      for (var p = o + 1; p < o + nx; p++) {  // insertion sort: a handful of crossings per row
        var z0 = xs[p], m = p - 1;
        while (m >= o && xs[m] > z0) { xs[m + 1] = xs[m]; m--; }
        xs[m + 1] = z0;
      }
      var base = (y0 + q2) * W;
      for (var z = o; z + 1 < o + nx; z += 2) {
        var L = Math.max(X0, Math.ceil(xs[z] - 0.5)), R = Math.min(X1, Math.ceil(xs[z + 1] - 0.5));
        if (R - L > 48) px.fill(colour, base + L, base + R);
        else for (var u = base + L, ue = base + R; u < ue; u++) px[u] = colour;
      }
    }
  }

  /* One anti-aliased line (Xiaolin Wu) into the coverage mask, between pixel-space points:
     each pixel column (row, for steep lines) gets the two pixels around the line, weighted
     by their distance to it. */
  function line(cov, W, X0, Y0, X1, Y1, x0, y0, x1, y1) {
    var t, i, k, c, y, yi, f, a, b, grad;
    if (Math.abs(x1 - x0) >= Math.abs(y1 - y0)) {
      if (x1 === x0) return;
      if (x0 > x1) { t = x0; x0 = x1; x1 = t; t = y0; y0 = y1; y1 = t; }
      grad = (y1 - y0) / (x1 - x0);
      a = Math.max(X0, Math.ceil(x0 - 0.5)) | 0; b = Math.min(X1, Math.ceil(x1 - 0.5)) | 0;
      for (i = a; i < b; i++) {
        y = y0 + grad * (i + 0.5 - x0) - 0.5; yi = Math.floor(y) | 0; f = y - yi;
        if (yi >= Y0 && yi < Y1) { k = yi * W + i; c = ((1 - f) * 255 + 0.5) | 0; if (c > cov[k]) cov[k] = c; }
        if (yi + 1 >= Y0 && yi + 1 < Y1) { k = (yi + 1) * W + i; c = (f * 255 + 0.5) | 0; if (c > cov[k]) cov[k] = c; }
      }
    } else {
      if (y0 > y1) { t = x0; x0 = x1; x1 = t; t = y0; y0 = y1; y1 = t; }
      grad = (x1 - x0) / (y1 - y0);
      a = Math.max(Y0, Math.ceil(y0 - 0.5)) | 0; b = Math.min(Y1, Math.ceil(y1 - 0.5)) | 0;
      for (i = a; i < b; i++) {
        y = x0 + grad * (i + 0.5 - y0) - 0.5; yi = Math.floor(y) | 0; f = y - yi;
        if (yi >= X0 && yi < X1) { k = i * W + yi; c = ((1 - f) * 255 + 0.5) | 0; if (c > cov[k]) cov[k] = c; }
        if (yi + 1 >= X0 && yi + 1 < X1) { k = i * W + yi + 1; c = (f * 255 + 0.5) | 0; if (c > cov[k]) cov[k] = c; }
      }
    }
  }

  /* The outlines of geometry k as coverage (see line). */
  function lineRings(cov, W, rect, g, r, c, k, v) {
    var s = v.s, tx = v.tx, ty = v.ty, X0 = rect[0], Y0 = rect[1], X1 = rect[2], Y1 = rect[3];
    for (var j = g[k]; j < g[k + 1]; j++) {
      var a = r[j], b = r[j + 1];
      if (b - a < 2) continue;
      var lx = c[2 * a] * s + tx, ly = ty - c[2 * a + 1] * s;
      for (var t = a + 1; t < b; t++) {
        var x = c[2 * t] * s + tx, y = ty - c[2 * t + 1] * s;
        line(cov, W, X0, Y0, X1, Y1, lx, ly, x, y);
        lx = x; ly = y;
      }
    }
  }

  /* Blend `rgb` at opacity `alpha` x coverage over px inside rect, and clear the coverage. */
  function composite(px, cov, W, rect, rgb, alpha) {
    var R = rgb[0], G = rgb[1], B = rgb[2], k = alpha / 255;
    for (var y = rect[1]; y < rect[3]; y++) {
      for (var i = y * W + rect[0], e = y * W + rect[2]; i < e; i++) {
        var w = cov[i];
        if (!w) continue;
        cov[i] = 0;
        var p = px[i], a = w * k, r = p & 255, gg = (p >>> 8) & 255, bb = (p >>> 16) & 255;
        px[i] = rgba32((r + (R - r) * a) | 0, (gg + (G - gg) * a) | 0, (bb + (B - bb) * a) | 0);
      }
    }
  }

  /* Square dots (side 2h + 1 pixels) at design points pts (x, y interleaved) inside rect. */
  function dots(px, W, rect, pts, v, h, colour) {
    for (var i = 0; i < pts.length; i += 2) {
      var X = Math.round(pts[i] * v.s + v.tx), Y = Math.round(v.ty - pts[i + 1] * v.s);
      if (X + h < rect[0] || X - h >= rect[2] || Y + h < rect[1] || Y - h >= rect[3]) continue;
      var a = Math.max(rect[0], X - h), b = Math.min(rect[2], X + h + 1);
      for (var y = Math.max(rect[1], Y - h); y < Math.min(rect[3], Y + h + 1); y++) px.fill(colour, y * W + a, y * W + b);
    }
  }

  return { rgba32: rgba32, hslToRgb: hslToRgb, fillRings: fillRings, lineRings: lineRings, line: line,
    composite: composite, dots: dots };
})();
