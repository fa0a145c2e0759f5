"""The 3D build: sites and a container template in, per-cell polyhedra with shared vertices out.

:func:`build_cells3d` runs the cell kernel in chunks (fixed per-cell slots; cells that do not
fit run again alone with room to spare, and after a chunk of such cells the next chunks' slots
grow: :mod:`.slots3d`), then joins the vertices: a vertex is owned by the
lowest site of its name, and every other cell that uses it finds it in that cell's list by
name (:func:`_match`). A vertex not found there (only when two cells' float decisions
disagreed on a nearly degenerate input) becomes its own vertex and is counted.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..config import BUILD3D_RESERVE_PAD, NJIT, TRIM_CELLS, VORONOI3D_CHUNK
from ..kernels.cells3d import EMPTY, OK, OVERFLOW, build_cells, cell_scratch
from ..kernels.grid3d import kd_buckets3d
from ..kernels.reach3d import weight_reach
from .bigvertex3d import BigVertices
from .containers import maybe_outside
from .jointable3d import probe_next, rehash, rows_box, slot
from .lists3d import Lists, chunk_search, chunks, redo_slow
from .sitegrid3d import grid3d_shape
from .slots3d import (
    GROW_CHUNK_LEAST,
    big_cell,
    chunk_room,
    grown_caps,
    minus_ones,
    probe_caps,
    probe_grown,
    slot_arrays,
    small_pages,
)
from .threads import serial_below

_NONE_GONE = np.zeros(0, np.bool_)  # no site's cell known empty (the kernel's gone)
#: mean sites per bucket of the search grid
PER_BUCKET = 2.0
#: buckets visited in distance order before the shell-by-shell search takes over
SEARCH_RADIUS = 3
#: k-d buckets (kernels.grid3d.kd_buckets3d) instead of the grid when a site shares its
#: grid bucket with more than this many others on average (the sum of the buckets' squared
#: counts over the sites; uniform sites at 2 a bucket: 3, lattices at most 8)
KD_CROWDED = 16.0
#: sites per k-d bucket
KD_LEAF = 8


def bucket_sort3d(P: np.ndarray, g: np.ndarray):
    """Sites by bucket: ``start (nb + 1,)``, ``SP`` in bucket order, ``sidx`` (stable)."""
    key = bucket_keys3d(P, g)
    start, sidx = _counting_sort(key, int(np.prod(np.asarray(g[6:9], np.int64))))
    return start, np.ascontiguousarray(P[sidx]), sidx


def bucket_keys3d(P: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Bucket number of each point of ``P`` in grid ``g`` (clamped into the grid; NaN: 0)."""
    return _bucket_keys(np.ascontiguousarray(P, np.float64), np.asarray(g, np.float64))


@njit(**NJIT)
def _bucket_keys(P, g):
    """:func:`bucket_keys3d` in one pass (numpy's floor, NaN to 0 and clip, per point)."""
    key = np.zeros(P.shape[0], np.int64)
    for i in range(P.shape[0]):
        b = 0
        for q in range(2, -1, -1):
            x = np.floor((P[i, q] - g[q]) / g[3 + q])
            top = g[6 + q] - 1.0
            if x != x:
                x = 0.0
            x = min(max(x, 0.0), top)
            b = b * np.int64(g[6 + q]) + np.int64(x)
        key[i] = b
    return key


@njit(**NJIT)
def _counting_sort(key, nb):
    """``start (nb + 1,)`` (cumulative counts) and the stable order of ``key`` (a bucket each)."""
    start = np.zeros(nb + 1, np.int64)
    for i in range(key.shape[0]):
        start[key[i] + 1] += 1
    for b in range(nb):
        start[b + 1] += start[b]
    fill = start[:-1].copy()
    sidx = np.zeros(key.shape[0], np.int64)
    for i in range(key.shape[0]):
        sidx[fill[key[i]]] = i
        fill[key[i]] += 1
    return start, sidx


def csr_take(lens: np.ndarray, take: np.ndarray) -> np.ndarray:
    """Element indices of the runs ``take`` of a run-length layout ``lens``, in that order."""
    off = np.concatenate([[0], np.cumsum(lens)])
    ln = lens[take]
    tot = int(ln.sum())
    if tot == 0:
        return np.zeros(0, np.int64)
    firsts = np.concatenate([[0], np.cumsum(ln)[:-1]])
    return np.repeat(off[take] - firsts, ln) + np.arange(tot)


def search_order(g: np.ndarray, radius: int) -> np.ndarray:
    """Bucket offsets within Chebyshev ``radius`` by least possible squared distance.

    Rows ``(dx, dy, dz, lb, radius)``; ``lb`` is the smallest squared distance between a
    point of a bucket and a point of the bucket ``(dx, dy, dz)`` away.
    """
    r = np.arange(-radius, radius + 1)
    d = np.stack(np.meshgrid(r, r, r, indexing="ij"), -1).reshape(-1, 3)[:, ::-1]
    lb = ((np.maximum(np.abs(d) - 1, 0) * g[3:6]) ** 2).sum(axis=1)
    out = np.column_stack([d, lb, np.full(len(d), radius)]).astype(np.float64)
    return np.ascontiguousarray(out[np.argsort(lb, kind="stable")])


#: per-cell output slots (vertices, faces, ring entries; a cell past them runs again alone,
#: and they grow for the next chunks after a chunk of such cells; 1e5 uniform cells reach 64
#: vertices), scratch (vertices, faces, ring entries) and the most
#: edges at a vertex of the cell's graph (kernels/cells3d.build_cells)
CAPS = (96, 48, 320, 1024, 512, 4096, 24)
BIG_CAPS_FACTOR = 4
#: the vertex table's largest load before it doubles
TABLE_LOAD = 0.7


@dataclass
class Cells3D:
    """Per-cell results of :func:`build_cells3d`.

    Per-cell arrays (``status``, ``volume``, ``centroid``, ``rad2``) follow ``cells`` (the
    caller's order); the face table is in *build* order: cell ``cells[c]``'s faces are
    ``cell_faces[pos[c]]:cell_faces[pos[c] + 1]``, face ``f``'s ring
    ``ring[roff[f]:roff[f + 1]]`` (outward) of indices into the cell's vertices
    ``vid[voff[pos[c]]:voff[pos[c] + 1]]`` (global vertex numbers).
    """

    cells: np.ndarray  # (k,) site numbers
    status: np.ndarray  # (k,)
    volume: np.ndarray
    centroid: np.ndarray
    rad2: np.ndarray
    vertices: np.ndarray  # (V, 3)
    pos: np.ndarray  # (k,) build position of each cell
    cell_faces: np.ndarray  # (k + 1,) face offsets, build order
    flabel: np.ndarray  # (Fc,) int32 kernel keys: site >= 0, wall -1 - w
    roff: np.ndarray  # (Fc + 1,) ring offsets
    ring: np.ndarray  # (R,) uint8/uint16 indices into the cell's vertex list
    voff: np.ndarray  # (k + 1,) vertex-list offsets, build order
    vid: np.ndarray  # (sum of nv,) global vertex ids of each cell's vertices
    unmatched: int
    #: with ``build_cells3d(..., short=True)``: ``(V,) bool``, the vertices referenced by fewer
    #: built cells than they have owner sites (``unmatched`` counts them; in a build of some
    #: cells only, also the vertices shared with cells not built)
    short: np.ndarray | None = None


def search3d(P: np.ndarray):
    """The search structure of the sites: ``(g, start, SP, sidx, order, tree)``.

    The bucket grid ``g`` (``PER_BUCKET`` sites a bucket), its buckets ``start``, the sites
    in bucket order ``SP`` (numbers ``sidx``) and its search ``order``; ``tree`` is empty.
    When the grid crowds its sites (clusters: more than ``KD_CROWDED`` bucket mates a site
    on average) the buckets are k-d buckets instead (``tree``, ``start``, ``SP``, ``sidx``
    from :func:`.grid3d.kd_buckets3d`).
    """
    g = grid3d_shape(P, PER_BUCKET)
    start, SP, sidx = bucket_sort3d(P, g)
    counts = np.diff(start).astype(np.float64)
    if float(counts @ counts) > KD_CROWDED * max(len(P), 1):
        tree, start, SP, sidx = kd_buckets3d(np.ascontiguousarray(P, np.float64), KD_LEAF)
        return g, start, SP, sidx, np.zeros((0, 5)), tree
    return g, start, SP, sidx, search_order(g, SEARCH_RADIUS), np.zeros((0, 8))


def _run(
    cells,
    P,
    W,
    start,
    SP,
    SW,
    sidx,
    g,
    order,
    tree,
    t,
    caps,
    pool,
    slots=None,
    scr=None,
    wmax=None,
    big=None,
    gone=None,
):
    """Build ``cells`` into fixed per-cell slots (threads on slices of the cells).

    ``scr`` (a dict, thread id -> :func:`.cells3d.cell_scratch`) keeps each thread's working
    space from call to call on the same inputs and caps; None: made for this call. ``wmax``:
    ``W.max()`` (None: found here; the caller of many chunks finds it once). ``big``: the
    candidate lists' ``(big, star)`` (:mod:`.lists3d`, :func:`.cells3d.build_cells`), or None.
    ``gone``: ``(ns,) bool``, sites whose cells are empty (:func:`build_cells3d`), or None.
    """
    k = len(cells)
    gone = _NONE_GONE if gone is None else gone
    scr = {} if scr is None else scr
    cv, cf, cr = caps[:3]
    status = np.zeros(k, np.int64)
    counts = np.zeros((k, 3), np.int64)
    vol = np.zeros(k)
    cen = np.zeros((k, 3))
    rad2 = np.zeros(k)
    osite, ovabs, ofaces, oring = slot_arrays(k, caps) if slots is None else slots
    capa = np.array(caps, np.int64)
    if wmax is None:  # once per build, not per chunk or slice (an 8 MB scan at 1e6)
        wmax = float(W.max()) if len(W) else 0.0

    def part(a, b):
        me = threading.get_ident()
        work = scr.get(me)
        if work is None:
            work = scr[me] = cell_scratch(len(P), g, tree, t.TV, t.TF, t.TR, capa)
        build_cells(
            cells[a:b],
            P,
            W,
            start,
            SP,
            SW,
            sidx,
            g,
            order,
            tree,
            t.TV,
            t.TF,
            t.TR,
            t.WP,
            capa,
            wmax,
            status[a:b],
            counts[a:b],
            vol[a:b],
            cen[a:b],
            rad2[a:b],
            osite[a * cv : b * cv],
            ovabs[a * cv : b * cv],
            ofaces[a * cf : b * cf],
            oring[a * cr : b * cr],
            work,
            *((None, None) if big is None else big),
            gone,
        )

    nth = 1 if pool is None else max(1, min(pool._max_workers, k // 512 or 1))
    if nth == 1:
        part(0, k)
    else:  # the kernel releases the GIL: threads take slices of cells as they come free
        # (8 slices a thread: on a loaded machine one descheduled thread with half of the
        # chunk made two threads slower than one, 12.1 s against 7.6 s on 1e5 cells)
        bounds = np.linspace(0, k, 8 * nth + 1).astype(int)
        list(pool.map(part, bounds[:-1], bounds[1:]))
    return status, counts, vol, cen, rad2, (osite, ovabs, ofaces, oring), capa


@njit(**NJIT)
def _join(
    c0, status, counts, caps, osite, ovabs, vbits, ofaces, oring, out, table, refs, want, gl, jt
):
    """Append the cells ``c0, c0 + 1, ...`` of a chunk to the outputs (vertices by bits + key).

    ``out = (verts, flabel, roff, ring, vid, sizes)`` with ``sizes = [nvert, nface, nring,
    nvid]``: each vertex record is looked up in ``table`` (open addressing on its
    coordinates' bits; the slots hold vertex numbers, -1 free) and appended when new; the
    cell's list of vertex numbers goes to ``vid`` and its rings stay local. Stops before a
    cell that does not fit (an output or the table is full: returns its number and 1), that
    overflowed its slots (2) or whose local numbers need a wider ring type (3); returns
    ``(k, 0)`` when done. ``jt = (jg, bslot)``: the table's slot layout (:func:`.jointable3d.slot`).
    """
    verts, flabel, roff, ring, vid, sizes = out
    jg, bslot = jt
    cv, cf, cr = caps[0], caps[1], caps[2]
    mask = table.shape[0] - 1
    nvert = sizes[0]
    nface = sizes[1]
    nring = sizes[2]
    nvid = sizes[3]
    k = counts.shape[0]
    widest = np.iinfo(ring.dtype).max
    hs = np.zeros(cv, np.int64)
    why = 0
    c = c0
    while c < k:
        if status[c] == OVERFLOW:
            why = 2
            break
        nv = counts[c, 0]
        nf = counts[c, 1]
        nr = counts[c, 2]
        if nv > widest + 1:
            why = 3
            break
        if (
            nvert + nv > verts.shape[0]
            or (nvert + nv) > TABLE_LOAD * table.shape[0]
            or nface + nf > flabel.shape[0]
            or nring + nr > ring.shape[0]
            or nvid + nv > vid.shape[0]
        ):
            why = 1
            break
        # first every slot the cell's vertices will probe, and the vertex each holds: the
        # loads are independent, so their cache misses overlap (the table is random access)
        # (and its count of references, the next thing a hit reads: another random line)
        touch = 0
        for v in range(nv):
            h = slot(vbits, ovabs, c * cv + v, jg, bslot, mask, osite[c * cv + v] >> 8)
            hs[v] = h
            gv = table[h]
            if gv >= 0 and verts[gv, 0] == ovabs[c * cv + v, 0]:
                touch += refs[gv]
        gl[0] = touch
        for v in range(nv):
            r = c * cv + v
            h = hs[v]
            key_r = osite[r] >> 8
            steps = 0
            while True:
                gv = table[h]
                if gv < 0:
                    table[h] = nvert
                    verts[nvert, 0] = ovabs[r, 0]
                    verts[nvert, 1] = ovabs[r, 1]
                    verts[nvert, 2] = ovabs[r, 2]
                    refs[nvert] = 1
                    want[nvert] = osite[r]
                    vid[nvid + v] = nvert
                    nvert += 1
                    break
                if (
                    verts[gv, 0] == ovabs[r, 0]
                    and verts[gv, 1] == ovabs[r, 1]
                    and verts[gv, 2] == ovabs[r, 2]
                    and want[gv] >> 8 == osite[r] >> 8
                ):
                    if refs[gv] < 255:
                        refs[gv] += 1
                    vid[nvid + v] = gv
                    break
                h = probe_next(h, mask, vbits, r, key_r, steps)
                steps += 1
        nvid += nv
        for f in range(nf):
            flabel[nface] = ofaces[c * cf + f, 0]
            roff[nface + 1] = roff[nface] + ofaces[c * cf + f, 1]
            nface += 1
        for q in range(nr):
            ring[nring] = oring[c * cr + q]
            nring += 1
        c += 1
    sizes[0] = nvert
    sizes[1] = nface
    sizes[2] = nring
    sizes[3] = nvid
    return c, why


def duplicate_owners(P, W):
    """``(n,)``: -1 for a site that owns its cell, else the equal site that owns it.

    Among equal points (``+0.0 == -0.0``) the largest weight owns the cell, ties to the
    lowest index. One pass over a hash table of the coordinates' bits (:func:`_owners`).
    """
    n = P.shape[0]
    it = _itype(n)
    table = np.full(1 << int(np.ceil(np.log2(max(n, 4) / TABLE_LOAD))), -1, it)
    dup = np.full(n, -1, np.int64)
    _owners(P, W, table, np.empty(n, it), dup)  # noqa: TID251 - every slot written first
    return dup


@njit(**NJIT)
def _owners(P, W, table, head, dup):
    """:func:`duplicate_owners` into ``dup``: ``table`` all -1 (a power of two), ``head``."""
    n = P.shape[0]
    mask = table.shape[0] - 1
    row = np.zeros(3)  # the point with one zero (+0.0), and its bits
    bits = row.view(np.int64)
    for i in range(n):
        row[0] = P[i, 0] + 0.0
        row[1] = P[i, 1] + 0.0
        row[2] = P[i, 2] + 0.0
        x = np.uint64(0x9E3779B97F4A7C15)  # the hash of the bits (its slot: h)
        for q in range(3):
            x ^= np.uint64(bits[q])
            x *= np.uint64(0xBF58476D1CE4E5B9)
            x ^= x >> np.uint64(31)
        h = np.int64(x & np.uint64(mask))
        while True:
            o = table[h]
            if o < 0:
                table[h] = i
                break
            if P[o, 0] == P[i, 0] and P[o, 1] == P[i, 1] and P[o, 2] == P[i, 2]:
                if W[i] > W[o]:
                    table[h] = i
                break
            h = (h + 1) & mask
        head[i] = h
    for i in range(n):
        o = table[head[i]]
        if o != i:
            dup[i] = o


class _Out:
    """The growing outputs of the join (numpy arrays, resized in place)."""

    def __init__(self, k, jg, units):
        self.jg, self.units = jg, units  # the table's layout (:func:`.jointable3d.slot`)
        # typical sizes per uniform cell: 6.8 vertices (27 per cell), 15.5 faces, 81 ring entries
        self.verts = np.zeros((max(16, 7 * k), 3))
        self.refs = np.zeros(len(self.verts), np.uint8)
        # each vertex's owner sites and name key (osite: key << 8 | sites), kept while joining
        self.want = np.zeros(len(self.verts), np.int32)
        self.flabel = np.zeros(max(16, 16 * k), np.int32)
        self.roff = np.zeros(len(self.flabel) + 1, _itype(84 * k))
        self.ring = np.zeros(max(64, 84 * k), np.uint8)
        self.vid = np.zeros(max(64, 28 * k), _itype(7 * k))
        self.sizes = np.zeros(4, np.int64)
        # 4 KB pages (first touch of ~0.5 GB in huge pages: 1.2 s of system time at 1e6)
        small_pages(self.verts, self.refs, self.want, self.flabel, self.roff, self.ring, self.vid)
        self.table = minus_ones(_table_size(len(self.verts)), self.vid.dtype)
        self.bslot = self._bslot()

    def _bslot(self):
        """First slot of each join bucket's run in the current table (and the end)."""
        u = self.units
        return (u * len(self.table)) // max(int(u[-1]), 1)

    def tuple(self):
        return (self.verts, self.flabel, self.roff, self.ring, self.vid, self.sizes)

    def grow(self, nv, nf, nr, nref=None):
        """Room for ``nv`` vertices (``nref`` refs), ``nf`` faces, ``nr`` ring entries (by half)."""
        nvert, nface, nring, nvid = (int(x) for x in self.sizes)
        nref = nv if nref is None else nref
        if nvert + nv > len(self.verts):
            m = int(1.5 * len(self.verts)) + nv
            self.verts.resize((m, 3), refcheck=False)
            self.refs.resize(m, refcheck=False)
            self.want.resize(m, refcheck=False)
        if nvert + nv > TABLE_LOAD * len(self.table):
            size = _table_size(int(1.5 * (nvert + nv)))
            if self.vid.dtype == np.int32 and size > 2**31 - 1:
                self.vid = self.vid.astype(np.int64)
            self.table = minus_ones(size, self.vid.dtype)
            self.bslot = self._bslot()
            rehash(self.verts, self.want, nvert, self.table, self.jg, self.bslot)
        if nface + nf > len(self.flabel):
            m = int(1.5 * len(self.flabel)) + nf
            self.flabel.resize(m, refcheck=False)
            self.roff.resize(m + 1, refcheck=False)
        if nring + nr > len(self.ring):
            m = int(1.5 * len(self.ring)) + nr
            if self.roff.dtype == np.int32 and m > 2**31 - 1:
                self.roff = self.roff.astype(np.int64)
            self.ring.resize(m, refcheck=False)
        if nvid + nref > len(self.vid):
            self.vid.resize(int(1.5 * len(self.vid)) + nref, refcheck=False)

    def reserve(self, status, counts):
        """Room for a chunk's cells at once (new vertices: the share so far, padded).

        A helix of 1,500 had 29 grows (5 rehashes) in 35 join calls; the vertex numbers
        follow the join's order, not the room: the same outputs.
        """
        ok = status != OVERFLOW
        nv, nf, nr = (int(x) for x in counts[ok].sum(axis=0))
        nvert, nface, nring, nvid = (int(x) for x in self.sizes)
        new = int(BUILD3D_RESERVE_PAD * nv * (nvert / nvid if nvid else 1.0))
        if (
            nvert + new > min(len(self.verts), TABLE_LOAD * len(self.table))
            or nface + nf > len(self.flabel)
            or nring + nr > len(self.ring)
            or nvid + nv > len(self.vid)
        ):
            self.grow(new, nf, nr, nv)

    def add(self, status, counts, slots, caps, big=None):
        """Join one chunk's cells in order.

        ``big(c)`` builds a cell that overflowed its slots again and joins it in its place.
        """
        osite, ovabs, ofaces, oring = slots
        self.reserve(status, counts)
        gl = np.zeros(1, self.vid.dtype)
        c = 0
        while c < len(counts):
            c, why = _join(
                c,
                status,
                counts,
                caps,
                osite,
                ovabs,
                ovabs.view(np.int64),
                ofaces,
                oring,
                self.tuple(),
                self.table,
                self.refs,
                self.want,
                gl,
                (self.jg, self.bslot),
            )
            if why == 1:
                self.grow(*(int(x) for x in counts[c]))
            elif why == 2:
                if big is None:
                    raise RuntimeError("a 3D cell overflowed its biggest slots")
                big(c)
                c += 1
            elif why == 3:  # a cell of more than 256 vertices: wider local numbers
                self.ring = self.ring.astype(np.uint16 if counts[c, 0] <= 65536 else np.int32)

    def finish(self):
        """Trim every output to its size (in place); returns the arrays and the unmatched."""
        nvert, nface, nring, nvid = (int(x) for x in self.sizes)
        self.table = None
        self.short = self.refs[:nvert] < (self.want[:nvert] & 255)
        unmatched = int(np.count_nonzero(self.short))
        self.refs = self.want = None
        self.verts.resize((nvert, 3), refcheck=False)
        self.flabel.resize(nface, refcheck=False)
        self.roff.resize(nface + 1, refcheck=False)
        self.ring.resize(nring, refcheck=False)
        self.vid.resize(nvid, refcheck=False)
        return self.verts, self.flabel, self.roff, self.ring, self.vid, unmatched


def _join_grid(Pb, bounds, k):
    """The join grid over the built sites and the container (about 2 built cells a bucket).

    Returns ``jg (9,)`` (origin, inverse bucket sizes, counts) and ``units (nb + 1,)``:
    before each bucket, the buckets and built cells of the buckets before it (every bucket
    gets one unit and one per cell built in it, so a run of the table follows the vertices'
    density, and empty space keeps a little room).
    """
    corners = np.vstack([*rows_box(Pb), bounds[0], bounds[1]])
    lo = corners.min(axis=0)
    box = np.vstack([lo, corners.max(axis=0)])
    g = grid3d_shape(box, 2.0 / max(k / PER_BUCKET, 1.0), flat=False)
    keys = bucket_keys3d(Pb, g)
    nb = int(np.prod(g[6:9]))
    units = np.zeros(nb + 1, np.int64)
    np.cumsum(np.bincount(keys, minlength=nb) + 1, out=units[1:])
    jg = np.concatenate([g[:3], 1.0 / g[3:6], g[6:9]])
    return jg, units


def _itype(most):
    """int32 for indices up to ``most`` (with room), else int64."""
    return np.int32 if most < 2**30 else np.int64


def _table_size(nvert):
    return 1 << int(np.ceil(np.log2(max(nvert, 8) / TABLE_LOAD)))


def build_order(P, cells, g, sidx, tree):
    """The order to build ``cells`` in: the positions in ``cells`` sorted by bucket (stable).

    ``g, sidx, tree`` from :func:`search3d`. Cells in bucket order read the same sites as
    their neighbours (1.5x less time than input order on 1e5 uniform sites).
    """
    k = len(cells)
    if len(tree):
        rank = np.zeros(len(P), np.int64)
        rank[sidx] = np.arange(len(P))
        return np.argsort(rank[cells], kind="stable")
    if k and cells[0] == 0 and cells[-1] == k - 1 and (np.diff(cells) == 1).all():
        # the first k sites (all, or those before a periodic build's images): sidx, less others
        return sidx if k == len(P) else sidx[sidx < k]
    return np.argsort(bucket_keys3d(P[cells], g), kind="stable")


def build_cells3d(
    P, W, t, cells=None, progress=None, short=False, lists=True, outside=False
) -> Cells3D:
    """Cells of sites ``cells`` (default all) of ``P (ns, 3)``, weights ``W``, template ``t``.

    Chunks of cells are built in bucket order into per-cell slots (threads), and each chunk
    is joined at once into the growing outputs (:func:`_join`); a cell that overflowed its
    slots is built again alone with big slots and joined in its place. ``short``: keep the
    per-vertex mask behind ``unmatched`` (:attr:`Cells3D.short`). ``lists``: unweighted
    cells past a search budget are built from Delaunay lists (:mod:`.lists3d`); ``"owners"``:
    only those with a vertex of more owners than the cell's table holds (mesh containers).
    ``outside``: the cells of the sites that may lie outside the container
    (:func:`maybe_outside`) are built first, and those found empty own no vertex (a site
    outside a box whose cell shrinks to a corner is on that vertex's sphere, but no cell of
    it references the vertex: it counted as unmatched, and a float hull was built twice).
    """
    import numba

    ns = len(P)
    cells = np.arange(ns) if cells is None else np.asarray(cells, np.int64)
    k = len(cells)
    if k == 0:
        return _empty(cells)
    g, start, SP, sidx, order, tree = search3d(P)
    SW = np.ascontiguousarray(W[sidx])  # the weights in bucket order, read beside SP
    # unweighted: a budget of sites a cell, past it the cell's Delaunay list (engine.lists3d)
    lists = None if W.any() or not lists else Lists(P, W, g, owners_only=lists == "owners")
    # cells are built in bucket order (neighbouring cells read the same sites: 1.5x less
    # time than input order on 1e5 uniform sites); the face table stays in that order
    sort = build_order(P, cells, g, sidx, tree)
    built = cells[sort]
    wmax = float(W.max()) if len(W) else 0.0
    # per-cell results to the caller's order (sort), counts to the build position's offsets
    status = np.empty(k, np.int64)  # noqa: TID251 - every cell written by its chunk's join
    vol = np.empty(k)  # noqa: TID251 - as status
    cen = np.empty((k, 3))  # noqa: TID251 - as status
    rad2 = np.empty(k)  # noqa: TID251 - as status
    cell_faces = np.zeros(k + 1, np.int64)
    voff = np.zeros(k + 1, np.int64)
    # the join's outputs (_Out), made by the first join: with a joining thread, the vertex
    # table (67 MB of -1 at 1e6 cells) is filled while the pool builds the first chunk
    made = []
    with serial_below(k):
        nth, size = numba.get_num_threads(), int(np.clip(k // 128, *VORONOI3D_CHUNK))
        pool = joiner = None
        if nth > 1 and k >= 128:
            from concurrent.futures import ThreadPoolExecutor

            pool = ThreadPoolExecutor(nth)
            # one more thread joins chunk c while the pool builds c + 1 (two sets of slots)
            joiner = ThreadPoolExecutor(1)
        nsl = 2 if joiner else 1
        slots = [slot_arrays(min(size, k), CAPS) for _ in range(nsl)]
        # the chunks' caps and each thread's working space for them, kept from chunk to
        # chunk (_run); grown after a chunk of many-faced cells (.slots3d.grown_caps); the
        # probe's slots are as large as the scratch (.slots3d.probe_caps), chunks as small
        # as grown slots' bytes need (.slots3d.chunk_room)
        probe = lists is not None
        cur = [probe_caps(CAPS) if probe else CAPS, {}]
        bigscr = {}  # the same for cells built alone with big slots (big_cell), by slot size
        pending = []
        grid = (start, SP, SW, sidx, weight_reach(P, W, g, sidx), None)  # (+ local weights)
        gone = None  # the sites whose cells are empty (outside), not counted as owners
        bv = BigVertices(P, W, t.WP) if lists is None else None  # (found where they overflow)

        def run(few, *search, sl=None):  # search: (start, SP, SW, sidx, g, big)
            *s, big = search
            return _run(few, P, W, *s, order, tree, t, cur[0], pool, sl, cur[1], wmax, big, gone)

        if outside:
            far = np.flatnonzero(maybe_outside(P, t))
            if len(far):
                empty = far[run(far, *grid)[0] == EMPTY]
                if len(empty):
                    gone = np.zeros(ns, np.bool_)
                    gone[empty] = True

        def join(c0, chunk, how, st, counts, v, c, r2, sl, capa):
            if not made:
                Pb = P if k == ns else P[cells]  # (k == ns: every site once, in some order)
                made.append(_Out(k, *_join_grid(Pb, t.bounds, k)))
            out = made[0]

            def big(q):
                # a cell past its slots: alone, big slots (its list if built from one), in place
                s = lists.get()[:6] if how is not None and how[q] else grid
                st[q], counts[q], v[q], c[q], r2[q] = big_cell(
                    *(chunk[q], P, W, s, order, tree, t, out, wmax, counts[q], gone, bv),
                    *(bigscr, CAPS, BIG_CAPS_FACTOR, _run),
                )

            out.add(st, counts, sl, capa, big)
            at = sort[c0 : c0 + len(chunk)]
            status[at], vol[at], cen[at], rad2[at] = st, v, c, r2
            cell_faces[c0 + 1 : c0 + 1 + len(chunk)] = counts[:, 1]
            voff[c0 + 1 : c0 + 1 + len(chunk)] = counts[:, 0]
            if progress is not None:
                progress(c0 + len(chunk), k)

        try:
            room = [size]
            for q, (c0, c1) in enumerate(chunks(k, size, probe, room)):
                if len(pending) >= len(slots):
                    pending.pop(0).result()  # the join that used these slots is done
                chunk = built[c0:c1]
                s = grid if lists is None else chunk_search(lists, grid)
                first = probe and q == 0
                sl = slot_arrays(c1 - c0, cur[0]) if first else slots[q % len(slots)]
                res = run(chunk, *s, sl=sl)
                how = None
                if lists is not None:  # cells past the budget, again (from their lists)
                    how = redo_slow(chunk, res, lists, run, grid)
                if first:  # back to CAPS (the same scratch), or grown from the probe's counts
                    grown = probe_grown(res[0], res[1], CAPS, nsl)
                    cur[0] = CAPS
                else:
                    grown = grown_caps(res[0], res[1], cur[0], CAPS, nsl * GROW_CHUNK_LEAST)
                if grown is not None:  # most cells overflowed: the next chunks fit them
                    cur[:] = [grown, {}]
                    room[0] = chunk_room(grown, nsl, size)
                    slots = [slot_arrays(min(room[0], k), grown) for _ in range(nsl)]
                if joiner is None:
                    join(c0, chunk, how, *res)
                else:
                    pending.append(joiner.submit(join, c0, chunk, how, *res))
            for f in pending:
                f.result()
        finally:
            for ex in (pool, joiner):
                if ex is not None:
                    ex.shutdown()
    del slots
    out = made[0]
    vertices, flabel, roff, ring, vid, unmatched = out.finish()
    vshort = out.short if short else None
    out.short = None
    pos = np.empty(k, np.int64)  # noqa: TID251 - a permutation: every slot written
    pos[sort] = np.arange(k)
    np.cumsum(cell_faces, out=cell_faces)
    np.cumsum(voff, out=voff)
    return Cells3D(
        cells,
        status,
        vol,
        cen,
        rad2,
        vertices,
        pos,
        cell_faces,
        flabel,
        roff,
        ring,
        voff,
        vid,
        unmatched,
        vshort,
    )


def release_freed_memory(k):
    """After a build of ``k`` cells: give the heap's free pages back (glibc ``malloc_trim``).

    The build frees ~300 B a cell (the vertex table, the chunks' slots, the search grid,
    per-cell arrays in build order) in blocks below glibc's mmap threshold, which stay
    resident as holes in the heap; the outputs made after it (neighbours, unique faces:
    numba's large arrays, mmapped) do not reuse them, so they stayed in the peak (1e6
    cells: 997 B a cell at the unique faces, against 872 B of live arrays). Elsewhere
    (no glibc) nothing happens.
    """
    if k < TRIM_CELLS:
        return
    global _TRIM
    if _TRIM is None:
        import ctypes
        import ctypes.util

        try:
            _TRIM = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6").malloc_trim
        except (OSError, AttributeError):
            _TRIM = False
    if _TRIM:
        _TRIM(0)


_TRIM = None


def _empty(cells):
    k = len(cells)
    return Cells3D(
        cells,
        np.zeros(k, np.int64),
        np.zeros(k),
        np.full((k, 3), np.nan),
        np.zeros(k),
        np.zeros((0, 3)),
        np.arange(k),
        np.zeros(k + 1, np.int64),
        np.zeros(0, np.int32),
        np.zeros(1, np.int32),
        np.zeros(0, np.uint8),
        np.zeros(k + 1, np.int64),
        np.zeros(0, np.int32),
        0,
    )


__all__ = ["Cells3D", "build_cells3d", "build_order", "duplicate_owners", "OK"]
