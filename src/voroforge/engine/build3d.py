"""The 3D build: sites and a container template in, per-cell polyhedra with shared vertices out.

:func:`build_cells3d` runs the cell kernel in chunks (fixed per-cell slots; cells that do not
fit run again alone with room to spare), then joins the vertices: a vertex is owned by the
lowest site of its name, and every other cell that uses it finds it in that cell's list by
name (:func:`_match`). A vertex not found there (only when two cells' float decisions
disagreed on a nearly degenerate input) becomes its own vertex and is counted.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from ..config import GRID_DEGENERATE_RTOL, GRID_WIDEN_RTOL, NJIT
from ..kernels.cells3d import OK, OVERFLOW, build_cells
from .threads import serial_below

#: cells per call of the kernel (its fixed per-cell slots: ~10 KB a cell while it runs)
CHUNK = 4096
#: mean sites per bucket of the search grid
PER_BUCKET = 2.0
#: buckets visited in distance order before the shell-by-shell search takes over
SEARCH_RADIUS = 3


def grid3d_shape(P: np.ndarray, per_bucket: float) -> np.ndarray:
    """The search grid ``(x0, y0, z0, hx, hy, hz, nx, ny, nz)`` over the sites (kernels/grid3d)."""
    lo = P.min(axis=0)
    ext = P.max(axis=0) - lo
    span = float(ext.max())
    if span == 0.0:
        span = max(float(np.abs(lo).max()), 1.0)
    ext = np.maximum(ext, GRID_DEGENERATE_RTOL * span)
    nb = max(1.0, len(P) / per_bucket)
    side = (float(np.prod(ext)) / nb) ** (1.0 / 3.0)
    counts = np.minimum(np.maximum(ext / side, 1.0), 1024.0).astype(np.int64).astype(np.float64)
    return np.concatenate([lo, ext * (1.0 + GRID_WIDEN_RTOL) / counts, counts])


def bucket_sort3d(P: np.ndarray, g: np.ndarray):
    """Sites by bucket: ``start (nb + 1,)``, ``SP`` in bucket order, ``sidx`` (stable)."""
    n = np.asarray(g[6:9], np.int64)
    key = bucket_keys3d(P, g)
    sidx = np.argsort(key, kind="stable")
    start = np.zeros(int(np.prod(n)) + 1, np.int64)
    np.cumsum(np.bincount(key, minlength=int(np.prod(n))), out=start[1:])
    return start, np.ascontiguousarray(P[sidx]), sidx.astype(np.int64)


def bucket_keys3d(P: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Bucket number of each point of ``P`` in grid ``g`` (clamped into the grid)."""
    n = np.asarray(g[6:9], np.int64)
    idx = np.floor((P - g[:3]) / g[3:6])
    idx = np.clip(np.nan_to_num(idx, nan=0.0), 0, n - 1).astype(np.int64)
    return (idx[:, 2] * n[1] + idx[:, 1]) * n[0] + idx[:, 0]


def _csr_take(lens: np.ndarray, take: np.ndarray) -> np.ndarray:
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
#: copying every packed array; 1e5 uniform cells reach 64 vertices), scratch (vertices, faces, ring
#: entries) and the most edges at a vertex of the cell's graph (kernels/cells3d.build_cells)
CAPS = (96, 48, 320, 1024, 512, 4096, 24)
BIG_CAPS_FACTOR = 16


@dataclass
class Cells3D:
    """Per-cell results in kernel numbering (``cells`` are the site numbers built)."""

    cells: np.ndarray  # (k,) site numbers
    status: np.ndarray  # (k,)
    volume: np.ndarray
    centroid: np.ndarray
    rad2: np.ndarray
    vertices: np.ndarray  # (V, 3)
    foff: np.ndarray  # (k + 1,) per-cell faces
    flabel: np.ndarray  # (Fc,) kernel keys: site >= 0, wall -1 - w
    farea: np.ndarray  # (Fc, 3) area vectors (outward of the cell)
    roff: np.ndarray  # (Fc + 1,) rings
    ring: np.ndarray  # (R,) global vertex ids
    unmatched: int


def _slots(k, caps):
    """Fixed per-cell output slots for ``k`` cells (reused from chunk to chunk)."""
    cv, cf, cr = caps[:3]
    return (
        np.zeros((k * cv, 4), np.int64),
        np.zeros((k * cv, 3)),
        np.zeros((k * cf, 2), np.int64),
        np.zeros((k * cf, 3)),
        np.zeros(k * cr, np.int64),
    )


def _run(cells, P, W, start, SP, sidx, g, order, t, caps, pool, slots=None):
    """Build ``cells`` into fixed per-cell slots (threads on slices), then pack the slots."""
    k = len(cells)
    cv, cf, cr = caps[:3]
    status = np.zeros(k, np.int64)
    counts = np.zeros((k, 3), np.int64)
    vol = np.zeros(k)
    cen = np.zeros((k, 3))
    rad2 = np.zeros(k)
    onames, ovabs, ofaces, oarea, oring = _slots(k, caps) if slots is None else slots
    capa = np.array(caps, np.int64)

    def part(a, b):
        build_cells(
            cells[a:b],
            P,
            W,
            start,
            SP,
            sidx,
            g,
            order,
            t.TV,
            t.TF,
            t.TR,
            t.WP,
            capa,
            1,
            status[a:b],
            counts[a:b],
            vol[a:b],
            cen[a:b],
            rad2[a:b],
            onames[a * cv : b * cv],
            ovabs[a * cv : b * cv],
            ofaces[a * cf : b * cf],
            oarea[a * cf : b * cf],
            oring[a * cr : b * cr],
        )

    nth = 1 if pool is None else max(1, min(pool._max_workers, k // 512 or 1))
    if nth == 1:
        part(0, k)
    else:  # the kernel releases the GIL: threads take slices of cells as they come free
        # (8 slices a thread: on a loaded machine one descheduled thread with half of the
        # chunk made two threads slower than one, 12.1 s against 7.6 s on 1e5 cells)
        bounds = np.linspace(0, k, 8 * nth + 1).astype(int)
        list(pool.map(part, bounds[:-1], bounds[1:]))
    tot = counts.sum(axis=0)
    names = np.zeros((tot[0], 4), np.int64)
    vabs = np.zeros((tot[0], 3))
    faces = np.zeros((tot[1], 2), np.int64)
    area = np.zeros((tot[1], 3))
    ring = np.zeros(tot[2], np.int64)
    _pack(counts, capa, onames, ovabs, ofaces, oarea, oring, names, vabs, faces, area, ring)
    return dict(
        status=status,
        counts=counts,
        vol=vol,
        cen=cen,
        rad2=rad2,
        names=names,
        vabs=vabs,
        faces=faces,
        area=area,
        ring=ring,
    )


@njit(**NJIT)
def _pack(counts, caps, onames, ovabs, ofaces, oarea, oring, names, vabs, faces, area, ring):
    """Copy the used part of every cell's slots into the packed arrays, cell after cell."""
    cv, cf, cr = caps[0], caps[1], caps[2]
    v = 0
    f = 0
    r = 0
    for c in range(counts.shape[0]):
        for q in range(counts[c, 0]):
            for a in range(4):
                names[v, a] = onames[c * cv + q, a]
            for a in range(3):
                vabs[v, a] = ovabs[c * cv + q, a]
            v += 1
        for q in range(counts[c, 1]):
            faces[f, 0] = ofaces[c * cf + q, 0]
            faces[f, 1] = ofaces[c * cf + q, 1]
            for a in range(3):
                area[f, a] = oarea[c * cf + q, a]
            f += 1
        for q in range(counts[c, 2]):
            ring[r] = oring[c * cr + q]
            r += 1


@njit(**NJIT)
def _in_order(back, counts, faces, area, ring, gid, flabel, farea, flen, gring):
    """Faces of the cells in the caller's order (``back[c]``: where cell ``c`` was built).

    Rings come out in global vertex ids (``gid`` of the cell's vertex records).
    """
    k = counts.shape[0]
    voff = np.zeros(k + 1, np.int64)
    foff = np.zeros(k + 1, np.int64)
    roff = np.zeros(k + 1, np.int64)
    for c in range(k):
        voff[c + 1] = voff[c] + counts[c, 0]
        foff[c + 1] = foff[c] + counts[c, 1]
        roff[c + 1] = roff[c] + counts[c, 2]
    f2 = 0
    r2 = 0
    for c in range(k):
        s = back[c]
        r = roff[s]
        for f in range(foff[s], foff[s + 1]):
            flabel[f2] = faces[f, 0]
            ln = faces[f, 1]
            flen[f2] = ln
            for a in range(3):
                farea[f2, a] = area[f, a]
            for _ in range(ln):
                gring[r2] = gid[voff[s] + ring[r]]
                r += 1
                r2 += 1
            f2 += 1


def build_cells3d(P, W, t, cells=None, progress=None) -> Cells3D:
    """Cells of sites ``cells`` (default all) of ``P (ns, 3)``, weights ``W``, template ``t``."""
    import numba

    ns = len(P)
    cells = np.arange(ns) if cells is None else np.asarray(cells, np.int64)
    if len(cells) == 0:
        return _empty(cells)
    g = grid3d_shape(P, PER_BUCKET)
    start, SP, sidx = bucket_sort3d(P, g)
    order = search_order(g, SEARCH_RADIUS)
    # cells are built in bucket order (neighbouring cells read the same sites: 1.5x less
    # time than input order on 1e5 uniform sites); faces go back to the caller's order below
    sort = np.argsort(bucket_keys3d(P[cells], g), kind="stable")
    built = cells[sort]
    parts = []
    with serial_below(len(cells)):
        nth = numba.get_num_threads()
        pool = None
        if nth > 1 and len(cells) >= 128:
            from concurrent.futures import ThreadPoolExecutor

            pool = ThreadPoolExecutor(nth)
        slots = _slots(min(CHUNK, len(cells)), CAPS)
        try:
            for c0 in range(0, len(cells), CHUNK):
                chunk = built[c0 : c0 + CHUNK]
                parts.append(_run(chunk, P, W, start, SP, sidx, g, order, t, CAPS, pool, slots))
                if progress is not None:
                    progress(min(c0 + CHUNK, len(cells)), len(cells))
        finally:
            if pool is not None:
                pool.shutdown()
    del slots
    out = {}
    for key in list(parts[0]):  # one array at a time, freeing the parts as it goes
        out[key] = np.concatenate([p.pop(key) for p in parts])
    del parts
    status = out["status"]
    counts = out["counts"]
    # cells that did not fit: alone, with big slots
    over = np.flatnonzero(status == OVERFLOW)
    extra = {}
    factor = BIG_CAPS_FACTOR
    while len(over):
        caps = tuple(c * factor for c in CAPS[:6]) + CAPS[6:]
        for c in over:
            extra[int(c)] = _run(built[c : c + 1], P, W, start, SP, sidx, g, order, t, caps, None)
        still = [c for c in over if extra[int(c)]["status"][0] == OVERFLOW]
        if factor >= 256 or not still:
            break
        over = np.array(still)
        factor *= 4
    names, vabs, faces, area, ring = (
        out.pop(k) for k in ("names", "vabs", "faces", "area", "ring")
    )
    if extra:
        names, vabs, faces, area, ring, counts = _splice(
            counts, names, vabs, faces, area, ring, extra
        )
        for c, r in extra.items():
            for key in ("status", "vol", "cen", "rad2"):
                out[key][c] = r[key][0]
    # global vertex ids, by name, in the order the cells were built
    voff = np.concatenate([[0], np.cumsum(counts[:, 0])])
    pos = np.full(ns, -1, np.int64)
    pos[built] = np.arange(len(built))
    vcellpos = np.repeat(np.arange(len(built)), counts[:, 0])
    gid, unmatched = _join(names, vcellpos, built, pos, voff)
    del vcellpos, names
    vertices = np.zeros((int(gid.max()) + 1 if len(gid) else 0, 3))
    vertices[gid] = vabs  # every record of one id holds the same bits (or is its own id)
    del vabs
    # faces in the caller's order
    back = np.zeros(len(cells), np.int64)
    back[sort] = np.arange(len(cells))
    flabel = np.zeros(len(faces), np.int64)
    farea = np.zeros((len(faces), 3))
    flen = np.zeros(len(faces), np.int64)
    gring = np.zeros(len(ring), np.int64)
    _in_order(back, counts, faces, area, ring, gid, flabel, farea, flen, gring)
    del faces, area, ring, gid
    foff = np.concatenate([[0], np.cumsum(counts[back, 1])])
    roff = np.concatenate([[0], np.cumsum(flen)])
    return Cells3D(
        cells,
        out["status"][back],
        out["vol"][back],
        out["cen"][back],
        out["rad2"][back],
        vertices,
        foff,
        flabel,
        farea,
        roff,
        gring,
        unmatched,
    )


def _empty(cells):
    z = np.zeros(0, np.int64)
    k = len(cells)
    return Cells3D(
        cells,
        np.zeros(k, np.int64),
        np.zeros(k),
        np.full((k, 3), np.nan),
        np.zeros(k),
        np.zeros((0, 3)),
        np.zeros(k + 1, np.int64),
        z,
        np.zeros((0, 3)),
        np.zeros(1, np.int64),
        z,
        0,
    )


def _splice(counts, names, vabs, faces, area, ring, extra):
    voff = np.concatenate([[0], np.cumsum(counts[:, 0])])
    foff = np.concatenate([[0], np.cumsum(counts[:, 1])])
    roff = np.concatenate([[0], np.cumsum(counts[:, 2])])
    pieces = {k: [] for k in ("names", "vabs", "faces", "area", "ring")}
    prev = 0
    counts = counts.copy()
    for c in sorted(extra):
        r = extra[c]
        for key, arr, off in (
            ("names", names, voff),
            ("vabs", vabs, voff),
            ("faces", faces, foff),
            ("area", area, foff),
            ("ring", ring, roff),
        ):
            pieces[key].append(arr[off[prev] : off[c]])
            pieces[key].append(r[key if key != "vabs" else "vabs"])
        counts[c] = r["counts"][0]
        prev = c + 1
    for key, arr, off in (
        ("names", names, voff),
        ("vabs", vabs, voff),
        ("faces", faces, foff),
        ("area", area, foff),
        ("ring", ring, roff),
    ):
        pieces[key].append(arr[off[prev] :])
    return (
        *(np.concatenate(pieces[k]) for k in ("names", "vabs", "faces", "area", "ring")),
        counts,
    )


@njit(**NJIT)
def _match(names, vcellpos, cells, pos, voff, gid):
    """Find each vertex record's owner record.

    ``gid[r]``: -2 for a record owned by its own cell (numbered later); else the record index
    in the owner cell with the same name, or -1 when there is none.
    """
    m = names.shape[0]
    for r in range(m):
        c = vcellpos[r]
        owner = names[r, 0]
        if owner == cells[c]:
            gid[r] = -2
            continue
        p = pos[owner] if owner < pos.shape[0] else -1
        gid[r] = -1
        if p < 0:
            continue
        for q in range(voff[p], voff[p + 1]):
            if (
                names[q, 0] == names[r, 0]
                and names[q, 1] == names[r, 1]
                and names[q, 2] == names[r, 2]
                and names[q, 3] == names[r, 3]
            ):
                gid[r] = q
                break


@njit(**NJIT)
def _number(gid):
    """Number owned records, then point matched records at their owner's number."""
    m = gid.shape[0]
    out = np.zeros(m, np.int64)
    k = 0
    for r in range(m):
        if gid[r] == -2:
            out[r] = k
            k += 1
    unmatched = 0
    for r in range(m):
        if gid[r] == -1:
            out[r] = k
            k += 1
            unmatched += 1
    for r in range(m):
        if gid[r] >= 0:
            out[r] = out[gid[r]]
    return out, unmatched


def _join(names, vcellpos, cells, pos, voff):
    gid = np.zeros(len(names), np.int64)
    if len(names) == 0:
        return gid, 0
    _match(names, vcellpos, cells, pos, voff, gid)
    out, unmatched = _number(gid)
    return out, int(unmatched)


__all__ = ["Cells3D", "build_cells3d", "OK"]
