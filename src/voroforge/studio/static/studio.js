/* voroforge studio: the page (and the Jupyter widget's view). Plain JavaScript, no build step.
 *
 * The server (or the widget's Python side) sends JSON state and binary geometry messages
 * (see voroforge/studio/wire.py): a JSON header and flat typed arrays, rings as
 * geometry -> ring -> coordinate offsets, decoded by VoroGeom (geom.js). Each cell keeps a
 * reference into its message's buffers; a whole drawing or the boxes of the changed cells
 * are rasterised into pixels by VoroRaster (raster.js; both load first). The page tells the
 * server its pixel size ("view").
 */
var VoroStudio = (function () {
  "use strict";

  var G = VoroGeom;  /* geom.js, loaded first: messages, views, rings */
  var View = G.View, Codes = G.Codes, codeView = G.codeView, unpack = G.unpack;
  var buildPath = G.buildPath, addRings = G.addRings, ringCoords = G.ringCoords;
  var ringBox = G.ringBox, grow = G.grow, colourOf = G.colourOf, marker = G.marker;

  function el(tag, attrs, parent) {
    var e = document.createElement(tag);
    for (var k in attrs || {}) {
      if (k === "text") e.textContent = attrs[k];
      else e.setAttribute(k, attrs[k]);
    }
    if (parent) parent.appendChild(e);
    return e;
  }

  function Studio(root, transport) {
    this.root = root;
    this.transport = transport;
    this.canvas = root.querySelector("[data-role=canvas]");
    this.ctx = this.canvas.getContext("2d");
    // the boundary, handles and check markers: a canvas over the cells, drawn on every repaint
    this.overlay = document.createElement("canvas");
    this.overlay.className = "vf-overlay";
    this.canvas.parentNode.insertBefore(this.overlay, this.canvas.nextSibling);
    this.octx = this.overlay.getContext("2d");
    this.panel = root.querySelector("[data-role=panel]");
    this.statusEl = root.querySelector("[data-role=status]");
    this.messageEl = root.querySelector("[data-role=message]");
    this.legendEl = root.querySelector("[data-role=legend]");
    this.raw = []; this.cells = []; this.boxes = []; this.mask = new Uint8Array(0);
    this.img = null; this.baseValid = false; this.pending = null; this.baseView = null; this.boundaryId = 0;
    this.sites = new Float64Array(0);
    this.boundary = null; this.domain = null; this.bounds = [0, 0, 1, 1];
    this.attractors = []; this.violations = []; this.legend = [];
    this.state = null; this.header = null; this.n = 0;
    this.nextId = 1; this.inflight = null; this.waiting = [];
    this.latencies = []; this.drag = null; this.dirty = false; this.frames = 0;
    this.controlsKey = ""; this.inputs = {}; this.client = null;
    this.lastDraw = 0; this.seq = 0; this.errors = {};
    this.downloads = [];
    // every field the page sets later, here (undefined where "not yet" means something): a
    // field added later changes the object's shape, and V8 throws away the optimised code
    // that reads it (the paint's, at a page's first edits)
    this.bg = undefined; this.bgKey = undefined; this.px = undefined; this.cov = undefined;
    this.dpr = 1; this.handle = undefined; this.moveEvent = undefined;
    this.parseMs = undefined; this.drawMs = undefined; this.roundTrip = undefined;
    this.overlayKey = undefined; this.sentPx = undefined; this.saved = undefined;
    this.violationCounts = undefined; this.violationsId = undefined; this.checkMs = undefined;
    this.violationTotal = undefined; this.violationSeq = undefined;
    this.warmed = false; this.statusText = ""; this.statusAt = -Infinity; this.statusTimer = 0; this.messageColour = undefined;
    this.playing = undefined; this.frameShown = undefined; this.framesPlayed = undefined;
    this.bind();
    this.resize();
  }

  Studio.prototype.send = function (msg, meta) {
    msg.id = this.nextId++;
    this.inflight = { id: msg.id, t0: (meta && meta.t0) || performance.now(), op: msg.op };
    this.transport.send(JSON.stringify(msg));
    this.inflight.tsend = performance.now();
    return msg.id;
  };

  /* One message in flight; the rest wait in order, and a run of the same edit (a drag, a
     slider, the timeline) collapses to its latest value. */
  function collapsible(a, b) {
    if (a.op !== b.op) return false;
    if (a.op === "move") return a.i === b.i;
    if (a.op === "attractor") return a.a === b.a && a.p === b.p;
    if (a.op === "set") return a.key === b.key;
    return a.op === "frame";
  }

  /* `t0`: when the user acted (a pointer event's timeStamp), else now. */
  Studio.prototype.queue = function (msg, t0) {
    var now = performance.now();
    msg._t0 = t0 !== undefined && t0 > 0 && t0 <= now ? t0 : now;
    if (!this.inflight) { var t0 = msg._t0; delete msg._t0; this.send(msg, { t0: t0 }); return; }
    var w = this.waiting, last = w[w.length - 1];
    if (last && collapsible(last, msg)) { if (last.begin) msg.begin = true; w[w.length - 1] = msg; }
    else w.push(msg);
  };

  Studio.prototype.settle = function (replyTo) {
    if (!this.inflight || this.inflight.id !== replyTo) return null;
    var done = this.inflight;
    this.inflight = null;
    var next = this.waiting.shift();
    if (next) { var t0 = next._t0; delete next._t0; this.send(next, { t0: t0 }); }
    return done;
  };

  Studio.prototype.receive = function (data) {
    if (data instanceof ArrayBuffer) {
      var received = performance.now(), m = unpack(data);
      m.received = received; m.bytes = data.byteLength;
      return this.geometry(m);
    }
    var msg = typeof data === "string" ? JSON.parse(data) : data;
    var mine = msg.client === undefined || msg.client === this.client;
    if (msg.op === "state") {
      if (msg.client !== undefined && this.client === null) this.client = msg.client;
      this.state = msg; this.legend = msg.legend || [];
      this.controlsPanel(); this.updateBar(); this.drawLegend(); this.timeline();
      // keys the design's choices do not read (points on a rectangle): said, not refused
      if (msg.warnings && msg.warnings.length && !Object.keys(this.errors).length)
        this.message("warning: " + msg.warnings.map(function (w) { return w.message; }).join("; "), false);
      return;
    }
    if (msg.op === "violations") {
      this.violations = msg.list; this.violationCounts = msg.counts; this.violationsId = (this.violationsId || 0) + 1;
      this.checkMs = msg.check_ms; this.violationTotal = msg.total; this.violationSeq = msg.seq;
      this.drawLegend(); this.status(); this.invalidate();
      return;
    }
    if (mine) this.settle(msg.reply_to);
    if (msg.op === "error") {
      if (!mine) return;
      this.showErrors(msg.issues);
    } else if (msg.op === "file" && mine) {
      this.download(msg);
    } else if (msg.op === "confirm" && mine) {
      var ok = window.confirm("Overwrite " + msg.files.join(" and ") + " in the design's folder?");
      if (ok) this.queue({ op: "save", name: msg.name, overwrite: true });
    } else if (msg.op === "saved" && mine) {
      this.message("saved " + msg.files.join(", "), false);
      this.saved = msg;
    } else if (msg.op === "info" && mine) {
      this.message(msg.note, false);
    }
  };

  /* A geometry message: a full drawing, or a patch of the cells in `idx` (their rings, their
     opening flags `m`, and the sites that moved `si`/`sv`). A patch only marks the box around
     the old and new cells for repainting (see paintNow). */
  Studio.prototype.geometry = function (m) {
    var h = m.header, a = m.arrays, t0 = performance.now();
    var n = h.n, idx = a.idx, k, i, boxes = [], old = this.raw.length;
    // more changed cells than a patch repaints one by one (see renderPending): a whole redraw,
    // without the boxes to repaint
    var full = h.full || old !== n && !a.sites || idx.length > 400;
    this.bounds = h.bounds;
    if (h.full) { this.raw = new Array(n); this.cells = new Array(n); this.boxes = new Array(n); }
    else if (old !== n) {  // cells past the new count are gone: repaint where they were
      for (i = n; i < old; i++) if (this.boxes[i]) boxes.push(this.boxes[i]);
      this.raw.length = n; this.cells.length = n; this.boxes.length = n;
    }
    var codes = h.cq ? new Codes(h.cq) : null;
    for (k = 0; k < idx.length; k++) {
      i = idx[k];
      var was = this.boxes[i];
      // no Path2D per cell: the rings stay in the message's buffers until drawn
      this.raw[i] = a.rg[k + 1] > a.rg[k] ? [a.rg, a.rr, a.rc, k] : null;
      if (h.cells_raw) this.cells[i] = this.raw[i];  // cells without operations: the raw rings
      else this.cells[i] = a.cg[k + 1] > a.cg[k] ? [a.cg, a.cr, a.cc, k, codes] : null;
      this.boxes[i] = ringBox(a.rg, a.rr, a.rc, k);
      if (full) continue;
      var box = grow(was ? was.slice() : null, this.boxes[i]);
      if (box) boxes.push(box);
    }
    var dot = function (x, y) { boxes.push([x, y, x, y]); };
    if (a.sites) {  // all the sites: repaint the dots that moved, came or went
      var before = this.sites, now = a.sites, L = Math.max(before.length, now.length);
      if (!full && !h.full) {
        for (k = 0; k < L; k += 2) {
          if (before[k] === now[k] && before[k + 1] === now[k + 1]) continue;
          if (k < before.length) dot(before[k], before[k + 1]);
          if (k < now.length) dot(now[k], now[k + 1]);
        }
      }
      this.sites = new Float64Array(now);
    } else if (a.si) {
      for (k = 0; k < a.si.length; k++) {
        i = a.si[k];
        dot(this.sites[2 * i], this.sites[2 * i + 1]);
        this.sites[2 * i] = a.sv[2 * k]; this.sites[2 * i + 1] = a.sv[2 * k + 1];
        dot(a.sv[2 * k], a.sv[2 * k + 1]);
      }
    }
    if (a.mask) this.mask = new Uint8Array(a.mask);
    else for (k = 0; k < idx.length; k++) this.mask[idx[k]] = a.m[k];
    this.n = n;
    if (a.bg) {
      this.boundary = buildPath(a.bg, a.br, a.bc, 0); this.domain = buildPath(a.dg, a.dr, a.dc, 0);
      this.boundaryId++; full = true;
    }
    if (h.full || full) { this.baseValid = false; this.pending = null; }
    else if (boxes.length) this.pending = (this.pending || []).concat(boxes);
    this.bounds = h.bounds; this.attractors = h.attractors; this.header = h; this.seq = h.seq;
    this.reportView();
    var t1 = performance.now();
    this.parseMs = t1 - t0;
    var mine = h.client === undefined || h.client === this.client;
    var done = mine ? this.settle(h.reply_to) : null;
    if (done) this.clearErrors();
    this.paintNow();
    if (!this.warmed && this.baseValid) this.warmPatches();
    if (done) {
      var self = this, drawn = performance.now(), recv = m.received || t0;
      requestAnimationFrame(function () {
        var now = performance.now(), ms = now - done.t0;
        self.latencies.push({ op: done.op, ms: ms, drawn: drawn - done.t0, compute_ms: h.compute_ms,
          server_ms: h.server_ms, cpu_ms: h.cpu_ms, others_ms: h.others_ms, wait_ms: h.wait_ms,
          encode_ms: h.encode_ms, bytes: m.bytes,
          draw_ms: drawn - t0, parse_ms: t1 - t0, paint_ms: drawn - t1, frame_ms: now - drawn,
          queue_ms: done.tsend - done.t0, wire_ms: recv - done.tsend - (h.server_ms || 0) - (h.encode_ms || 0),
          // the wire's two ways, by the wall clocks of the page and the server (same machine)
          up_ms: h.received_at - (performance.timeOrigin + done.tsend),
          down_ms: performance.timeOrigin + recv - h.sent_at,
          n: n, changed: idx.length, full: h.full, busy: h.busy, switches: h.switches, ahead: h.ahead });
        self.roundTrip = ms; self.status();
      });
    }
    this.status(); this.updateBar();
  };

  /* --- drawing ------------------------------------------------------------------------ */

  /* The cells, their outlines and the seeds are drawn by VoroRaster (raster.js) into the
     pixels of an ImageData (the "base"), put on the canvas: in full when a whole drawing
     arrives, and after a patch only inside the pixel box around the changed cells (the cells
     meeting that box are drawn again, clipped to it, over the background's own pixels there).
     The boundary, handles and check markers are drawn on a second canvas over it. */
  var BG = "#f4f3ef", MATERIAL = "#d2c4a5", EDGE_RGB = [60, 50, 40], EDGE_ALPHA = 0.42;
  var DOT = VoroRaster.rgba32(29, 35, 48), PALETTE32 = [];
  for (var q2 = 0; q2 < 24; q2++) {
    var rgb = VoroRaster.hslToRgb((q2 * 137.508) % 360, 0.55, 0.72);
    PALETTE32.push(VoroRaster.rgba32(rgb[0], rgb[1], rgb[2]));
  }

  /* The background's pixels (page colour, the boundary's material), kept per view. */
  Studio.prototype.background = function (W, H, v) {
    var key = [W, H, v.s, v.tx, v.ty, this.boundaryId].join(",");
    if (this.bgKey === key) return this.bg;
    var cv = document.createElement("canvas"); cv.width = W; cv.height = H;
    var b = cv.getContext("2d");
    b.fillStyle = BG; b.fillRect(0, 0, W, H);
    if (this.boundary) { b.setTransform(v.s, 0, 0, -v.s, v.tx, v.ty); b.fillStyle = MATERIAL; b.fill(this.boundary, "evenodd"); }
    this.bg = new Uint32Array(b.getImageData(0, 0, W, H).data.buffer);
    this.bgKey = key;
    return this.bg;
  };

  /* Repaint the boxes of changed cells and dots: each box on its own (a few scattered changes
     repaint a few small patches), or everything when they cover much of the canvas. */
  Studio.prototype.renderPending = function (v) {
    var list = this.pending, W = this.canvas.width, H = this.canvas.height, k, rects = [], sum = 0;
    this.pending = null;
    if (!this.img || this.img.width !== W || this.img.height !== H) { this.renderBase(); return; }
    var U = [W, H, 0, 0], pad = (this.dotHalf() + 3) / v.s;
    for (k = 0; k < list.length && k <= 400; k++) {
      var b = list[k], r = [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad];
      var rect = [Math.max(0, Math.floor(r[0] * v.s + v.tx)), Math.max(0, Math.floor(v.ty - r[3] * v.s)),
        Math.min(W, Math.ceil(r[2] * v.s + v.tx)), Math.min(H, Math.ceil(v.ty - r[1] * v.s))];
      if (rect[2] <= rect[0] || rect[3] <= rect[1]) continue;
      rects.push([rect, this.designBox(rect, v)]);
      sum += (rect[2] - rect[0]) * (rect[3] - rect[1]);
      U = [Math.min(U[0], rect[0]), Math.min(U[1], rect[1]), Math.max(U[2], rect[2]), Math.max(U[3], rect[3])];
    }
    if (list.length > 400 || sum > 0.5 * W * H) { this.renderBase(); return; }
    if (!rects.length) return;
    var whole = (U[2] - U[0]) * (U[3] - U[1]);
    if (whole <= 2 * sum + 4096) {  // near one another (a drag): one box around them all
      rects = [[U, this.designBox(U, v)]];
    }
    var grid = rects.length > 3 ? this.buckets(v) : null;
    for (k = 0; k < rects.length; k++) {
      this.paintRect(rects[k][0], rects[k][1], v, grid ? this.near(grid, rects[k][0]) : null);
    }
    this.ctx.putImageData(this.img, 0, 0, U[0], U[1], U[2] - U[0], U[3] - U[1]);
  };

  /* After the first whole drawing, a few patch repaints of the same pixels: the patch path's
     first runs (V8 compiling it: the first took 1.7-3.1 ms, the next 0.1-0.2, with spikes
     of ~2 ms up to the sixth) come here, with the page's first drawing, not in its first
     drag steps. */
  var WARM_PATCHES = 12;
  Studio.prototype.warmPatches = function () {
    this.warmed = true;
    var v = this.view(), n = this.n;
    for (var k = 1; k <= WARM_PATCHES && n; k++) {
      var b = this.boxes[Math.floor(n * k / (WARM_PATCHES + 1))];
      if (b) { this.pending = [b.slice()]; this.renderPending(v); }
    }
    this.pending = null;
  };

  /* Cells and sites by 64-pixel tile, for many small repaints (each looks at its tiles only). */
  var TILE = 64;
  Studio.prototype.buckets = function (v) {
    var gw = Math.ceil(this.canvas.width / TILE), gh = Math.ceil(this.canvas.height / TILE);
    var cells = [], sites = [], i, q, x, y, s = this.sites;
    for (i = 0; i < gw * gh; i++) { cells.push([]); sites.push([]); }
    var tx = function (X) { return Math.max(0, Math.min(gw - 1, Math.floor((X * v.s + v.tx) / TILE))); };
    var ty = function (Y) { return Math.max(0, Math.min(gh - 1, Math.floor((v.ty - Y * v.s) / TILE))); };
    for (i = 0; i < this.n; i++) {
      q = this.boxes[i];
      if (!q) continue;
      for (y = ty(q[3]); y <= ty(q[1]); y++) for (x = tx(q[0]); x <= tx(q[2]); x++) cells[y * gw + x].push(i);
    }
    for (i = 0; 2 * i < s.length; i++) sites[ty(s[2 * i + 1]) * gw + tx(s[2 * i])].push(i);
    return { gw: gw, gh: gh, cells: cells, sites: sites, stamp: new Int32Array(this.n), round: 0 };
  };

  /* The cells (once each) and sites in the tiles that meet pixel rect, sorted. */
  Studio.prototype.near = function (grid, rect) {
    var out = [], pts = [], x, y, k, t, i, gw = grid.gw;
    var x0 = Math.max(0, Math.floor((rect[0] - 8) / TILE)), x1 = Math.min(gw - 1, Math.floor((rect[2] + 8) / TILE));
    var y0 = Math.max(0, Math.floor((rect[1] - 8) / TILE)), y1 = Math.min(grid.gh - 1, Math.floor((rect[3] + 8) / TILE));
    grid.round++;
    for (y = y0; y <= y1; y++) for (x = x0; x <= x1; x++) {
      t = grid.cells[y * gw + x];
      for (k = 0; k < t.length; k++) { i = t[k]; if (grid.stamp[i] !== grid.round) { grid.stamp[i] = grid.round; out.push(i); } }
      t = grid.sites[y * gw + x];
      for (k = 0; k < t.length; k++) pts.push(t[k]);
    }
    out.sort(function (a, b) { return a - b; });  // the same drawing order as a whole redraw
    return { cells: out, sites: pts };
  };

  /* The design box of the cells that can touch pixel rect (their fills and, a pixel and a
     half beyond, their outlines' anti-aliasing). */
  Studio.prototype.designBox = function (rect, v) {
    var m = 1.5;
    return [(rect[0] - m - v.tx) / v.s, (v.ty - rect[3] - m) / v.s, (rect[2] + m - v.tx) / v.s, (v.ty - rect[1] + m) / v.s];
  };

  /* Half the side of a seed's dot, in pixels. */
  Studio.prototype.dotHalf = function () { return Math.max(1, Math.round(1.2 * this.dpr)); };

  /* Everything, into the pixels and onto the canvas. */
  Studio.prototype.renderBase = function () {
    var W = this.canvas.width, H = this.canvas.height, v = this.view();
    if (!this.img || this.img.width !== W || this.img.height !== H) {
      this.img = this.ctx.createImageData(W, H);
      this.px = new Uint32Array(this.img.data.buffer);
      this.cov = new Uint8Array(W * H);
    }
    this.paintRect([0, 0, W, H], null, v);
    this.ctx.putImageData(this.img, 0, 0);
    this.baseValid = true; this.baseView = [v.s, v.tx, v.ty]; this.pending = null;
  };

  /* The pixels of rect = [X0, Y0, X1, Y1): the background, then the cells meeting the design
     box r (null: all), their outlines and the seeds, clipped to rect. */
  Studio.prototype.paintRect = function (rect, r, v, cand) {
    var W = this.canvas.width, px = this.px, cov = this.cov, bg = this.background(W, this.canvas.height, v);
    var h = this.dotHalf(), tol = 0.5 * this.dpr, i, j, bx = this.boxes, R = VoroRaster;
    var n = cand ? cand.cells.length : this.n;
    if (r) for (var y = rect[1]; y < rect[3]; y++) px.set(bg.subarray(y * W + rect[0], y * W + rect[2]), y * W + rect[0]);
    else px.set(bg);
    for (j = 0; j < n; j++) {
      i = cand ? cand.cells[j] : j;
      if (r) {
        var q = bx[i];
        if (!q || q[0] > r[2] || q[2] < r[0] || q[1] > r[3] || q[3] < r[1]) continue;
      }
      var c = this.cells[i], rw = this.raw[i];
      if (c && this.mask[i]) R.fillRings(px, W, rect, c[0], c[1], c[2], c[3], PALETTE32[colourOf(i)], c[4] ? codeView(c[4], v) : v, tol);
      if (rw) R.lineRings(cov, W, rect, rw[0], rw[1], rw[2], rw[3], v);
    }
    R.composite(px, cov, W, rect, EDGE_RGB, EDGE_ALPHA);
    if (!cand) { R.dots(px, W, rect, this.sites, v, h, DOT); return; }
    var s = this.sites, pts = new Float64Array(2 * cand.sites.length);
    for (j = 0; j < cand.sites.length; j++) { pts[2 * j] = s[2 * cand.sites[j]]; pts[2 * j + 1] = s[2 * cand.sites[j] + 1]; }
    R.dots(px, W, rect, pts, v, h, DOT);
  };

  Studio.prototype.resize = function () {
    var r = this.canvas.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
    this.canvas.width = this.overlay.width = Math.max(1, Math.round(r.width * dpr));
    this.canvas.height = this.overlay.height = Math.max(1, Math.round(r.height * dpr));
    this.dpr = dpr; this.invalidate();
    if (this.header) this.reportView();
  };

  /* Tell the server our pixel size in design units (drawn cells need no finer vertices);
     not a queued edit: no reply. */
  Studio.prototype.reportView = function () {
    var px = 1 / this.view().s;
    if (this.sentPx && Math.abs(px - this.sentPx) < 0.05 * this.sentPx) return;
    this.sentPx = px;
    this.transport.send(JSON.stringify({ op: "view", px: px }));
  };

  Studio.prototype.view = function () {
    var b = this.bounds, W = this.canvas.width, H = this.canvas.height;
    var w = Math.max(b[2] - b[0], 1e-9), hh = Math.max(b[3] - b[1], 1e-9), pad = 0.04;
    var s = Math.min(W / (w * (1 + 2 * pad)), H / (hh * (1 + 2 * pad)));
    var tx = (W - w * s) / 2 - b[0] * s, ty = (H + hh * s) / 2 + b[1] * s;
    return new View(s, tx, ty);
  };

  Studio.prototype.toDesign = function (e) {
    var r = this.canvas.getBoundingClientRect(), v = this.view();
    var X = (e.clientX - r.left) * this.dpr, Y = (e.clientY - r.top) * this.dpr;
    return [(X - v.tx) / v.s, (v.ty - Y) / v.s];
  };

  Studio.prototype.invalidate = function () {
    if (this.dirty) return;
    this.dirty = true;
    var self = this;
    requestAnimationFrame(function () { if (self.dirty) self.paintNow(); });
  };

  Studio.prototype.paintNow = function () {
    this.dirty = false;
    var t0 = performance.now(), v = this.view();
    var bv = this.baseView;
    if (!bv || bv[0] !== v.s || bv[1] !== v.tx || bv[2] !== v.ty) this.baseValid = false;
    if (!this.baseValid) this.renderBase();
    else if (this.pending) this.renderPending(v);
    this.placeHandle(v);
    // the overlay is drawn again only when what it shows changed (a canvas that changes is
    // composited again: a frame's cost even when the drawing is the same)
    var key = [v.s, v.tx, v.ty, this.boundaryId, this.violationsId, JSON.stringify(this.attractors)].join("|");
    if (key !== this.overlayKey) { this.overlayKey = key; this.paintOverlay(v); }
    this.drawMs = performance.now() - t0; this.frames++;
  };

  /* The ring around the seed being dragged: an element moved over the canvas. */
  Studio.prototype.placeHandle = function (v) {
    var s = this.sites, d = this.drag, hd = this.handle;
    if (!hd) {
      hd = this.handle = document.createElement("div");
      hd.className = "vf-handle";
      this.overlay.parentNode.appendChild(hd);
    }
    if (!d || d.kind !== "site" || 2 * d.i + 1 >= s.length) { hd.style.display = "none"; return; }
    var x = (s[2 * d.i] * v.s + v.tx) / this.dpr, y = (v.ty - s[2 * d.i + 1] * v.s) / this.dpr;
    hd.style.display = "block";
    hd.style.transform = "translate(" + x.toFixed(1) + "px," + y.toFixed(1) + "px)";
  };

  Studio.prototype.paintOverlay = function (v) {
    var ctx = this.octx, px = 1 / v.s, dpr = this.dpr;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.overlay.width, this.overlay.height);
    ctx.setTransform(v.s, 0, 0, -v.s, v.tx, v.ty);
    if (this.boundary) { ctx.lineWidth = 1.2 * px * dpr; ctx.strokeStyle = "#3a3128"; ctx.stroke(this.boundary); }
    if (this.domain) { ctx.setLineDash([4 * px * dpr, 4 * px * dpr]); ctx.lineWidth = 0.8 * px * dpr;
      ctx.strokeStyle = "rgba(58,49,40,0.6)"; ctx.stroke(this.domain); ctx.setLineDash([]); }
    var self = this;
    (this.attractors || []).forEach(function (a) {
      ctx.strokeStyle = "rgba(220,120,0,0.8)"; ctx.lineWidth = 1.5 * px * dpr;
      if (a.type === "curve" && a.points.length > 1) {
        ctx.beginPath(); a.points.forEach(function (p, k) { k ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]); });
        ctx.stroke();
      }
      a.points.forEach(function (p) {
        if (a.type === "point") { ctx.setLineDash([6 * px * dpr, 5 * px * dpr]); ctx.beginPath();
          ctx.arc(p[0], p[1], a.radius, 0, 7); ctx.stroke(); ctx.setLineDash([]); }
        ctx.beginPath(); ctx.arc(p[0], p[1], 7 * px * dpr, 0, 7);
        ctx.fillStyle = "#ff8c00"; ctx.fill(); ctx.strokeStyle = "#5a3000"; ctx.stroke();
      });
    });
    var styles = {}, kinds = {};
    this.legend.forEach(function (l) { styles[l.kind] = l; });
    ctx.lineWidth = 2.2 * px * dpr;
    var R = 9 * px * dpr;
    (this.violations || []).forEach(function (vi) { (kinds[vi.kind] = kinds[vi.kind] || []).push(vi); });
    Object.keys(kinds).forEach(function (kind) {  // one path per kind
      var st = styles[kind] || { shape: "circle", colour: "#e6194b" };
      ctx.beginPath();
      kinds[kind].forEach(function (vi) { marker(ctx, st.shape, vi.x, vi.y, R); });
      ctx.strokeStyle = st.colour; ctx.stroke();
    });
  };

  Studio.prototype.drawLegend = function () {
    var L = this.legendEl; if (!L) return;
    L.textContent = "";
    var counts = this.violationCounts || {};
    el("span", { text: this.violationTotal === undefined ? "checking… " : "check: " }, L);
    this.legend.forEach(function (l) {
      var item = el("span", { "data-kind": l.kind, "class": "item", title: l.text }, L);
      var sw = el("span", { "class": "sw sw-" + l.shape }, item); sw.style.borderColor = l.colour;
      el("span", { text: l.kind + " " + (counts[l.kind] || 0) }, item);
    });
  };

  /* The status line: its text is written only when it changes, and during a drag at most
     every STATUS_GAP ms (the latest figures then; at once when the drag ends). A text that
     changes lays out and paints the page again: on every drag step that was a frame's main
     thread work beside the step's own (the studio's browser test, issue 13). */
  var STATUS_GAP = 250;
  Studio.prototype.status = function () {
    var h = this.header; if (!h || !this.statusEl) return;
    var parts = [h.n + " cells", (this.sites.length / 2) + " seeds" + (h.sites_edited ? " (edited)" : ""),
      "compute " + h.compute_ms.toFixed(1) + " ms"];
    if (this.roundTrip !== undefined) parts.push("repaint " + this.roundTrip.toFixed(1) + " ms");
    if (this.drawMs !== undefined) parts.push("draw " + this.drawMs.toFixed(1) + " ms");
    if (this.violationTotal !== undefined) parts.push(this.violationTotal + " violations (check " + this.checkMs.toFixed(0) + " ms)");
    this.statusText = parts.join(" · ");
    var wait = this.drag ? STATUS_GAP - (performance.now() - this.statusAt) : 0;
    if (wait <= 0) { this.writeStatus(); return; }
    if (!this.statusTimer) {
      var self = this;
      this.statusTimer = setTimeout(function () { self.statusTimer = 0; self.writeStatus(); }, wait);
    }
  };

  Studio.prototype.writeStatus = function () {
    this.statusAt = performance.now();
    if (this.statusEl.textContent !== this.statusText) this.statusEl.textContent = this.statusText;
  };

  Studio.prototype.message = function (text, bad) {
    if (!this.messageEl) return;
    var colour = bad ? "#b00020" : "#225522";
    if (this.messageEl.textContent !== (text || "")) this.messageEl.textContent = text || "";
    if (this.messageColour !== colour) { this.messageColour = colour; this.messageEl.style.color = colour; }
  };

  Studio.prototype.updateBar = function () {
    var st = this.state; if (!st) return;
    var q = function (sel) { return this.root.querySelector(sel); }.bind(this);
    var u = q("[data-act=undo]"), r = q("[data-act=redo]"), f = q("[data-role=file]");
    var file = st.file + " — " + st.folder;  // each written only when it changes (status)
    if (u && u.disabled !== !st.can_undo) u.disabled = !st.can_undo;
    if (r && r.disabled !== !st.can_redo) r.disabled = !st.can_redo;
    if (f && f.textContent !== file) f.textContent = file;
  };

  /* --- inputs from the schema ------------------------------------------------------------ */

  Studio.prototype.controlsPanel = function () {
    var ctl = this.state.controls, key = ctl.map(function (c) {
      return c.key + ":" + (typeof c.value === "object" ? "g" : "n"); }).join(",");
    var self = this;
    if (key === this.controlsKey) {
      ctl.forEach(function (c) { self.setInputs(c); });
      return;
    }
    this.controlsKey = key; this.inputs = {};
    this.panel.textContent = "";
    var section = null;
    ctl.forEach(function (c) {
      var parts = c.key.split("."), sec = /^\d+$/.test(parts[1] || "") ? parts[0] + " " + parts[1] : parts[0];
      if (sec !== section) { section = sec; el("h3", { text: sec }, self.panel); }
      var box = el("div", { "class": "vf-ctl", "data-key": c.key }, self.panel);
      var label = parts.slice(/^\d+$/.test(parts[1] || "") ? 2 : 1).join(".");
      el("label", { text: label }, box);
      var subs = typeof c.value === "object" && c.value !== null ? ["near", "far"] : [null];
      var rows = subs.map(function (sub) {
        var row = el("div", { "class": "vf-row" }, box);
        if (sub) el("span", { text: sub }, row);
        var range = el("input", { type: "range", min: c.min, max: c.max, step: c.step, "data-key": c.key + (sub ? "." + sub : "") }, row);
        var num = el("input", { type: "number", step: c.step, "data-key": c.key + (sub ? "." + sub : "") }, row);
        var send = function (from, t0) {
          var v = parseFloat(from.value);
          if (!isFinite(v)) {  // typed past float64 ("1e309") or left empty: keep the last value
            var kept = (sub ? rows.filter(function (rw) { return rw.sub === sub; })[0] : rows[0]).num.dataset.last;
            self.showErrors([{ key: c.key, message: "not a finite number; kept " + kept }]);
            from.value = kept; return;
          }
          if (c.kind === "int") v = Math.round(v);
          (from === range ? num : range).value = v;
          var value = v;
          if (sub) { value = {}; rows.forEach(function (rw) { value[rw.sub] = parseFloat(rw.num.value); }); }
          self.queue({ op: "set", key: c.key, value: value }, t0);
        };
        range.addEventListener("input", function (e) { send(range, e.timeStamp); });
        num.addEventListener("change", function (e) { send(num, e.timeStamp); });
        if (!sub) {  // about to be used: the server may compute the step up ahead
          var hint = function () { self.hintAhead(c, num); };
          range.addEventListener("pointerdown", hint); num.addEventListener("focus", hint);
        }
        return { sub: sub, range: range, num: num };
      });
      el("div", { "class": "vf-err" }, box);
      self.inputs[c.key] = { box: box, rows: rows, spec: c };
      self.setInputs(c);
    });
  };

  /* Tell the server which input is about to change, with the value one step up (not an
     edit: no reply; see the server's _Hub.hint). */
  Studio.prototype.hintAhead = function (c, num) {
    var v = parseFloat(num.value), step = parseFloat(c.step) || 1;
    if (!isFinite(v)) return;
    var next = c.kind === "int" ? Math.round(v + step) : v + step;
    this.transport.send(JSON.stringify({ op: "ahead", key: c.key, value: next }));
  };

  Studio.prototype.setInputs = function (c) {
    var ent = this.inputs[c.key]; if (!ent) return;
    ent.rows.forEach(function (rw) {
      var v = rw.sub ? c.value[rw.sub] : c.value;
      rw.num.dataset.last = v;  // the value the server holds: what a bad entry falls back to
      if (document.activeElement !== rw.range && document.activeElement !== rw.num) {
        if (v > parseFloat(rw.range.max)) rw.range.max = v;
        rw.range.value = v; rw.num.value = v;
      }
    });
  };

  Studio.prototype.showErrors = function (issues) {
    var self = this, loose = [];
    issues.forEach(function (it) {
      var ent = self.inputs[it.key];
      if (!ent) {
        var k = Object.keys(self.inputs).filter(function (x) { return it.key && it.key.indexOf(x) === 0; })[0];
        ent = k ? self.inputs[k] : null;
      }
      if (ent) { ent.box.classList.add("vf-bad"); ent.box.querySelector(".vf-err").textContent = it.message;
        self.errors[ent.spec.key] = it.message; }
      loose.push((it.key ? it.key + ": " : "") + it.message);
    });
    this.message(loose.join("; "), true);
  };

  Studio.prototype.clearErrors = function () {
    var self = this;
    Object.keys(this.errors).forEach(function (k) {
      var ent = self.inputs[k]; if (!ent) return;
      ent.box.classList.remove("vf-bad"); ent.box.querySelector(".vf-err").textContent = "";
    });
    this.errors = {}; this.message("", false);
  };

  /* --- pointer and buttons ----------------------------------------------------------------- */

  Studio.prototype.nearestSite = function (p, radiusPx) {
    var s = this.sites, best = -1, bd = Infinity, v = this.view(), lim = radiusPx * this.dpr / v.s;
    for (var i = 0; i < s.length; i += 2) {
      var dx = s[i] - p[0], dy = s[i + 1] - p[1], d = dx * dx + dy * dy;
      if (d < bd) { bd = d; best = i / 2; }
    }
    return bd <= lim * lim ? best : -1;
  };

  Studio.prototype.nearestHandle = function (p, radiusPx) {
    var v = this.view(), lim = radiusPx * this.dpr / v.s, found = null;
    (this.attractors || []).forEach(function (a, ai) {
      a.points.forEach(function (q, pi) {
        var d = Math.hypot(q[0] - p[0], q[1] - p[1]);
        if (d <= lim && (!found || d < found.d)) found = { a: ai, p: pi, d: d };
      });
    });
    return found;
  };

  Studio.prototype.bind = function () {
    var self = this, cv = this.canvas;
    cv.addEventListener("pointerdown", function (e) {
      var p = self.toDesign(e), h = self.nearestHandle(p, 10);
      cv.setPointerCapture && cv.setPointerCapture(e.pointerId);
      if (h) { self.drag = { kind: "attractor", a: h.a, p: h.p, first: true }; return; }
      var i = self.nearestSite(p, 8);
      if (i >= 0 && e.shiftKey) { self.queue({ op: "remove", i: i }); self.drag = null; return; }
      if (i >= 0) { self.drag = { kind: "site", i: i, first: true }; self.invalidate(); return; }
      self.drag = { kind: "click", at: p, x: e.clientX, y: e.clientY };
    });
    // pointerrawupdate (where the browser has it) comes as soon as the pointer moves; a
    // pointermove waits for the next frame, a frame later on the screen
    var moveEvent = "onpointerrawupdate" in window ? "pointerrawupdate" : "pointermove";
    this.moveEvent = moveEvent;
    cv.addEventListener(moveEvent, function (e) {
      var d = self.drag; if (!d) return;
      var p = self.toDesign(e);
      if (d.kind === "site") {
        self.queue({ op: "move", i: d.i, x: p[0], y: p[1], begin: d.first }, e.timeStamp); d.first = false;
      } else if (d.kind === "attractor") {
        self.queue({ op: "attractor", a: d.a, p: d.p, x: p[0], y: p[1], begin: d.first }, e.timeStamp);
        d.first = false;
      } else if (d.kind === "click" && Math.hypot(e.clientX - d.x, e.clientY - d.y) > 4) {
        self.drag = null;
      }
    });
    cv.addEventListener("pointerup", function (e) {
      var d = self.drag; self.drag = null;
      if (self.statusTimer) { clearTimeout(self.statusTimer); self.statusTimer = 0; self.writeStatus(); }
      if (d && d.kind === "click" && !e.shiftKey) self.queue({ op: "add", x: d.at[0], y: d.at[1] });
      self.invalidate();
    });
    window.addEventListener("resize", function () { self.resize(); });
    window.addEventListener("keydown", function (e) {
      if ((e.ctrlKey || e.metaKey) && (e.key === "z" || e.key === "Z")) {
        e.preventDefault(); self.queue({ op: e.shiftKey ? "redo" : "undo" });
      }
    });
    this.root.querySelectorAll("[data-act]").forEach(function (b) {
      b.addEventListener("click", function () { self.action(b.getAttribute("data-act")); });
    });
  };

  Studio.prototype.action = function (act) {
    if (act === "undo" || act === "redo" || act === "reset_sites") return this.queue({ op: act });
    if (act === "play") return this.play();
    if (act === "save") {
      var name = window.prompt("Save as (a .toml file in " + (this.state ? this.state.folder : "the design's folder") + ")",
        this.state ? this.state.file : "design.toml");
      if (name) this.queue({ op: "save", name: name });
      return;
    }
    if (act.indexOf("export-") === 0) return this.queue({ op: "export", format: act.slice(7) });
  };

  /* --- animation: a timeline to scrub and play the design's [animation] frames ---------- */

  Studio.prototype.timeline = function () {
    var bar = this.root.querySelector("[data-role=timeline]"), a = this.state.animation;
    if (!bar) return;
    bar.hidden = !a;
    if (!a) { this.playing = false; return; }
    var scrub = bar.querySelector("[data-role=scrub]"), self = this;
    scrub.max = a.frames - 1;
    if (a.frame !== null && a.frame !== undefined) scrub.value = a.frame;
    bar.querySelector("[data-role=frame]").textContent =
      "frame " + (a.frame === null || a.frame === undefined ? "-" : a.frame + 1) + " / " + a.frames;
    if (!scrub._bound) {
      scrub._bound = true;
      scrub.addEventListener("input", function () { self.playing = false; self.showFrame(parseInt(scrub.value, 10)); });
    }
  };

  Studio.prototype.showFrame = function (k) {
    this.frameShown = k;
    this.queue({ op: "frame", k: k });
  };

  Studio.prototype.play = function () {
    var a = this.state && this.state.animation, self = this;
    if (!a) return;
    this.playing = !this.playing;
    var b = this.root.querySelector("[data-act=play]"); if (b) b.textContent = this.playing ? "Pause" : "Play";
    if (!this.playing) return;
    var k = this.frameShown === undefined ? -1 : this.frameShown;
    this.framesPlayed = 0;
    var step = function () {
      if (!self.playing) return;
      if (self.inflight) { setTimeout(step, 5); return; }
      k = k + 1;
      if (k >= a.frames) { if (!a.loop) { self.playing = false; if (b) b.textContent = "Play"; return; } k = 0; }
      self.showFrame(k); self.framesPlayed++;
      setTimeout(step, 1000 / a.fps);
    };
    step();
  };

  Studio.prototype.download = function (msg) {
    var bin = atob(msg.data), bytes = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    var blob = new Blob([bytes], { type: msg.mime }), url = URL.createObjectURL(blob);
    var a = el("a", { href: url, download: msg.name }, document.body);
    a.click(); a.remove();
    this.downloads.push({ name: msg.name, size: bytes.length });
    setTimeout(function () { URL.revokeObjectURL(url); }, 30000);
    this.message("exported " + msg.name, false);
  };

  /* For tests and scripts: a cell's rings as sent last, and a site's position. */
  Studio.prototype.cellPath = function (i) {
    var w = this.raw[i];
    if (!w) return i < this.n ? [] : null;
    var r = w[1], g = w[0], k = w[3];
    return Array.prototype.slice.call(w[2].subarray(2 * r[g[k]], 2 * r[g[k + 1]]));
  };
  Studio.prototype.site = function (i) { return [this.sites[2 * i], this.sites[2 * i + 1]]; };
  Studio.prototype.toScreen = function (p) {
    var r = this.canvas.getBoundingClientRect(), v = this.view();
    return [r.left + (p[0] * v.s + v.tx) / this.dpr, r.top + (v.ty - p[1] * v.s) / this.dpr];
  };

  function connect(root) {
    var proto = location.protocol === "https:" ? "wss:" : "ws:";
    var ws = null, studio = new Studio(root, { send: function (t) { ws.send(t); } });
    /* the canvas's size in pixels: the first drawing comes at the page's resolution */
    var size = "?w=" + studio.canvas.width + "&h=" + studio.canvas.height;
    ws = new WebSocket(proto + "//" + location.host + "/ws" + size);
    ws.binaryType = "arraybuffer";
    ws.onmessage = function (e) { studio.receive(e.data); };
    ws.onclose = function () { studio.message("disconnected from the studio server", true); };
    window.studio = studio;
    return studio;
  }

  var api = { connect: connect, Studio: Studio, unpack: unpack, buildPath: buildPath, addRings: addRings,
    ringCoords: ringCoords };
  if (typeof document !== "undefined") {
    var auto = document.querySelector("[data-connect=ws]");
    if (auto) api.instance = connect(auto);
  }
  return api;
})();
