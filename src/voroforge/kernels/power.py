"""Power (Laguerre) cells by cutting a box with power bisectors; Voronoi is the equal-weight case.

Cell ``i`` is ``{x : |x - p_i|^2 - w_i <= |x - p_j|^2 - w_j}`` for every neighbour ``j``. With
``u = x - p_i`` and ``d = p_j - p_i`` the constraint reads ``d.u <= (|d|^2 + w_i - w_j) / 2``,
so every test is made relative to the cell's own site and large coordinates keep their
precision. :func:`box_cell` makes that cut (through ``kernels/clip``); with equal weights its
signed values are the Voronoi bisectors' bit for bit, and the Delaunay-dual cell builder
(``kernels/cells``) uses it for the cells it cuts.

After the cut every vertex is replaced by the one computed from its name
(``kernels/vertex``): the power centre of the cell's site and its two edges' owners, or the
power bisector's crossing with a box side. Neighbouring cells therefore share every vertex
bit for bit.

Output contract (the same closed-ring layout the Voronoi assembly consumes):

``coords (K, 2) float64``
    Closed counter-clockwise rings (last vertex repeats the first), in site order.
``lengths (n + 1,) int64``
    Cell ``i`` is ``coords[lengths[i]:lengths[i + 1]]``; empty when the cell misses the box.
``owner (K,) int64``
    ``owner[k] = j`` when the edge from vertex ``k`` to ``k + 1`` lies on the power bisector of
    sites ``i`` and ``j``, -1 on the box, -2 on the closing vertex.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL, POWER_CROWDED_RTOL
from .clip import cut_ring, plane_values
from .vertex import power_box_crossing, power_vertex


@njit(**NJIT)
def box_cell(i, xs, ys, ws, nbrs, nn, box, px, py, pw, qx, qy, qw, ss):
    """Box cut by the power bisectors of site ``i`` with ``nbrs[:nn]``; result in ``p``.

    Returns the vertex count (0 when less than a polygon is left). Edge owners are the
    neighbours, and -1 (left), -2 (bottom), -3 (right), -4 (top) on the box sides. All
    buffers need room for ``nn + 5`` vertices; ``q`` and ``ss`` are scratch.
    """
    px[0] = box[0]
    py[0] = box[1]
    px[1] = box[2]
    py[1] = box[1]
    px[2] = box[2]
    py[2] = box[3]
    px[3] = box[0]
    py[3] = box[3]
    pw[0] = -2  # bottom
    pw[1] = -3  # right
    pw[2] = -4  # top
    pw[3] = -1  # left
    # np.int64, not literals: numba would compile the clip's callees once more for them
    m = np.int64(4)
    zero = np.int64(0)
    sx = xs[i]
    sy = ys[i]
    swapped = False
    for k in range(nn):
        j = nbrs[k]
        dx = xs[j] - sx
        dy = ys[j] - sy
        # the weight difference first: |d|^2 + w_i would round |d|^2 away when the weights
        # are large, and sites i and j would then see two different bisectors (a gap)
        h = 0.5 * (dx * dx + dy * dy + (ws[i] - ws[j]))
        if plane_values(px, py, zero, m, dx, dy, sx, sy, h, ss) <= 0.0:
            continue
        m = cut_ring(px, py, pw, zero, m, ss, qx, qy, qw, zero, j)
        if m < 3:
            return 0
        px, qx = qx, px
        py, qy = qy, py
        pw, qw = qw, pw
        swapped = not swapped
    if swapped:
        for v in range(m):
            qx[v] = px[v]
            qy[v] = py[v]
            qw[v] = pw[v]
    return m


@njit(**NJIT)
def _named_vertices(i, xs, ys, ws, px, py, pw, m, box, qx, qy):
    """Replace each vertex of ring ``p[:m]`` by the one computed from its name (in place).

    A vertex between two bisector edges is the power vertex of ``i`` and their owners; one
    between a bisector and a box side is the bisector's crossing with that side; box
    corners are exact already. Where several cells meet at one point (power-cocircular
    sites) a ring can have two vertices a few ulps apart that named copies could swap, and
    an ill-conditioned name can be far from the cut: those vertices stay as cut.
    """
    near = POWER_CROWDED_RTOL * max(box[2] - box[0], box[3] - box[1])
    for v in range(m):
        vp = v - 1 if v > 0 else m - 1
        vn = v + 1 if v + 1 < m else 0
        x = px[v]
        y = py[v]
        gap = min(max(abs(x - px[vp]), abs(y - py[vp])), max(abs(x - px[vn]), abs(y - py[vn])))
        a = pw[vp]
        b = pw[v]
        if gap <= near or a == b:
            nx = x
            ny = y
        elif a >= 0 and b >= 0:
            nx, ny = power_vertex(i, a, b, xs, ys, ws)
        elif a >= 0 or b >= 0:
            nx, ny = power_box_crossing(i, a if a >= 0 else b, xs, ys, ws, b if a >= 0 else a, box)
        else:
            nx = x
            ny = y
        if not (abs(nx - x) <= near and abs(ny - y) <= near):
            nx = x  # NaN (bisector parallel to the side) or an ill-conditioned name
            ny = y
        qx[v] = nx
        qy[v] = ny
    for v in range(m):
        px[v] = qx[v]
        py[v] = qy[v]


@njit(**NJIT)
def _cell(i, xs, ys, ws, indptr, indices, box, px, py, po, qx, qy, qo, ss):
    """Power cell of site ``i`` clipped to ``box``; returns its vertex count (in ``p``)."""
    nb = indices[indptr[i] : indptr[i + 1]]
    m = box_cell(i, xs, ys, ws, nb, nb.shape[0], box, px, py, po, qx, qy, qo, ss)
    if m == 0:
        return 0
    _named_vertices(i, xs, ys, ws, px, py, po, m, box, qx, qy)
    ox = xs[i]
    oy = ys[i]
    area2 = 0.0
    for k in range(m):
        kn = k + 1 if k + 1 < m else 0
        area2 += (px[k] - ox) * (py[kn] - oy) - (px[kn] - ox) * (py[k] - oy)
        if po[k] < 0:
            po[k] = -1
    if not area2 > 0.0:
        return 0
    return m


@njit(**NJIT_PARALLEL)
def power_cells(xs, ys, ws, indptr, indices, box, active):
    """Closed rings of the power cells of all sites (see the module docstring).

    Parameters
    ----------
    xs, ys, ws : (n,) float64
        Sites and weights.
    indptr, indices : CSR int64
        Candidate neighbours of each site (a superset of its power neighbours).
    box : (4,) float64
        ``(xmin, ymin, xmax, ymax)``.
    active : (n,) bool
        Sites whose cell is computed; the others get an empty cell.

    Returns
    -------
    coords, lengths, owner
        As in the module docstring.
    """
    n = xs.shape[0]
    cap = np.zeros(n + 1, dtype=np.int64)
    for i in range(n):
        cap[i + 1] = cap[i] + 2 * (indptr[i + 1] - indptr[i]) + 9
    slab_x = np.zeros(cap[n])
    slab_y = np.zeros(cap[n])
    slab_o = np.zeros(cap[n], dtype=np.int64)
    counts = np.zeros(n + 1, dtype=np.int64)
    for i in prange(n):
        if not active[i]:
            continue
        size = cap[i + 1] - cap[i]
        px = np.zeros(size)
        py = np.zeros(size)
        po = np.zeros(size, dtype=np.int64)
        qx = np.zeros(size)
        qy = np.zeros(size)
        qo = np.zeros(size, dtype=np.int64)
        ss = np.zeros(size)
        # prange's index is unsigned: as np.int64 the callees are compiled once, not twice
        m = _cell(np.int64(i), xs, ys, ws, indptr, indices, box, px, py, po, qx, qy, qo, ss)
        if m > 0:
            b = cap[i]
            for k in range(m):
                slab_x[b + k] = px[k]
                slab_y[b + k] = py[k]
                slab_o[b + k] = po[k]
            slab_x[b + m] = px[0]
            slab_y[b + m] = py[0]
            slab_o[b + m] = -2
            counts[i + 1] = m + 1
    for i in range(n):
        counts[i + 1] += counts[i]
    coords = np.zeros((counts[n], 2))
    owner = np.zeros(counts[n], dtype=np.int64)
    for i in prange(n):
        b = cap[i]
        o = counts[i]
        for k in range(counts[i + 1] - o):
            coords[o + k, 0] = slab_x[b + k]
            coords[o + k, 1] = slab_y[b + k]
            owner[o + k] = slab_o[b + k]
    return coords, counts, owner
