"""The periodic margin's next try: which margins grow and which sites' copies come in.

:func:`.periodic._periodic` builds the diagram of the copies in a grown box, proves the
margin (:func:`.periodic._proved`) and, where the proof fails, asks
:func:`.periodic_chord.shortfall` how far each axis falls short and which few sites' copies
are missing. Each failed try is a whole build of every copy, so a try that asks too little
costs as much as the next build. :func:`next_try` turns the shortfall into the next
margins:

- a margin that grows for the first time at least doubles; one that grew before grows by
  at least a quarter (sites on a sloped line: the last ask was 4% past the margin and
  doubling it made the last build of 1e4 sites 124k copies, where 2.24 x 2.14 periods proves
  with 70k);
- the few cells cut off by the grown box on both axes while the others are cut off on one
  (a site off a line: :func:`.periodic_chord.shortfall` lets their vertices wait until the
  line's copies beside them are in) bring their sites' copies in to the caps, and the
  margin doubles on the axes nothing else grows, at once: the next try asked just that, a
  whole build later (a vertical line of 3e4 sites and one off it: three builds, now two).
"""

from __future__ import annotations

import numpy as np

from ..config import PERIODIC_FIRST_GROW, PERIODIC_REGROW, PERIODIC_WAIT_GROW_COST


def cut_off_twice(v, cell, box, margin, slack, most, cut=None):
    """The cells cut off by the grown box on both axes while others are cut off on one.

    ``v`` are the kept cells' vertices, ``cell`` each vertex's cell (a copy index),
    ``margin`` the grown box's margins, ``slack`` the copies' rounding, ``most`` how many
    such cells are few (more: none returned), ``cut`` ((p, 2) bool or None) where the
    vertex's cell is cut off elsewhere (:func:`cut_off`). Returns the cells, sorted (int64).
    """
    x0, y0, x1, y1 = box
    cells = []
    for k, (a, b, m) in enumerate(((x0, x1, margin[0]), (y0, y1, margin[1]))):
        on = (v[:, k] <= a - m + slack) | (v[:, k] >= b + m - slack)
        if cut is not None:
            on |= cut[:, k]
        cells.append(np.unique(cell[on]))
    twice = np.intersect1d(cells[0], cells[1])
    if not len(twice) or len(twice) >= max(len(cells[0]), len(cells[1])) or len(twice) > most:
        return np.zeros(0, dtype=np.int64)
    return twice.astype(np.int64)


def next_try(margin, caps, grow, grew, waiting_sites, extra, most, count=None):
    """The next try's margins, and whether anything changed.

    Parameters
    ----------
    margin, caps : (float, float)
        The margins of the failed try and their caps.
    grow : (float, float)
        What :func:`.periodic_chord.shortfall` asked per axis (0.0: nothing).
    grew : list of two bool
        Whether each axis grew before (updated in place).
    waiting_sites : (k,) int64
        The sites of the cells :func:`cut_off_twice` found (their copies come in to the
        caps, set in ``extra``; the margins they are cut off by double where nothing else
        asks).
    extra : ((n,) bool, caps)
        The sites whose copies are in to the caps (updated in place).
    most : int
        How many sites ``extra`` may hold.
    count : callable or None
        The number of copies a try with given margins builds: the waiting cells' axes
        double only where that adds at most ``PERIODIC_WAIT_GROW_COST`` of the copies.

    Returns
    -------
    ((float, float), bool)
        The margins, and whether they or ``extra`` changed.
    """
    grow = list(grow)
    changed = False
    new = waiting_sites[~extra[0][waiting_sites]]
    if len(new) and int(extra[0].sum()) + len(new) <= most:
        extra[0][new] = True
        changed = True
        both = [g if g else 2.0 * m for g, m in zip(grow, margin, strict=True)]
        if count is not None and both != grow:
            # the doubling only where it is cheap against the next build: a whole build
            # later it may not be needed (n = 2,000: the cell's cut on y was only where the
            # line's copies across it were missing, and 18% more copies were built)
            sizes = [count(_grown(margin, caps, g, grew)) for g in (grow, both)]
            if sizes[1] <= (1.0 + PERIODIC_WAIT_GROW_COST) * sizes[0]:
                grow = both
        else:
            grow = both
    out = _grown(margin, caps, grow, grew)
    changed |= out != tuple(margin)
    for k in range(2):
        grew[k] |= bool(out[k] != margin[k])
    return out, changed


def _grown(margin, caps, grow, grew):
    """The margins grown by the asks ``grow`` (see :func:`next_try`)."""
    out = []
    for k in range(2):
        m, cap = margin[k], caps[k]
        if grow[k] and m < cap:
            factor = PERIODIC_REGROW if grew[k] else PERIODIC_FIRST_GROW
            m = min(max(factor * m, grow[k]), cap)
        out.append(m)
    return (out[0], out[1])


def on_sides(v, box, margin, slack) -> bool:
    """Whether any of the vertices ``v`` lies on the sides of the box grown by ``margin``."""
    x0, y0, x1, y1 = box
    for k, (a, b, m) in enumerate(((x0, x1, margin[0]), (y0, y1, margin[1]))):
        if ((v[:, k] <= a - m + slack) | (v[:, k] >= b + m - slack)).any():
            return True
    return False


def same_copies(last, source, shift) -> bool:
    """Whether the copies ``(source, shift)`` are those of the last try, ``last``.

    A margin that grows past no copy (a sloped line's copies leave gaps: the last growth of
    1e4 sites on a slope 3 took none in) gives the same diagram where no kept cell ended
    at the smaller grown box's sides: it is proved again, not built again.
    """
    if last is None or len(last[0]) != len(source):
        return False
    return bool(np.array_equal(last[0], source) and np.array_equal(last[1], shift))


def cut_off(d, copies, box, margin, slack):
    """Per copy of ``copies``: whether the grown box cuts its whole cell off, per axis.

    ``(len(copies), 2)`` bool. A wrapped piece is its copy's cell cut to the box: where the
    cell is cut off by the grown box past the box's side, the piece's corner on the side is
    no vertex of the cell and its distance to the site says nothing about the other axis
    (sites on a vertical line, wrapped: the line's cells end at the grown box until its
    copies across are in, and their corners asked for a whole period along the line too,
    9 n copies where 3.3 n are proved).
    """
    coords, (ring, poly, geom) = d.to_geoarrow()
    cells, at = np.unique(copies, return_inverse=True)
    lo = ring[poly[geom[cells]]]
    hi = ring[poly[geom[cells + 1]]]
    x0, y0, x1, y1 = box
    out = np.zeros((len(cells), 2), dtype=bool)
    length = hi - lo
    take = np.repeat(lo - np.cumsum(length) + length, length) + np.arange(int(length.sum()))
    which = np.repeat(np.arange(len(cells)), length)
    v = coords[take]
    for k, (a, b, m) in enumerate(((x0, x1, margin[0]), (y0, y1, margin[1]))):
        on = (v[:, k] <= a - m + slack) | (v[:, k] >= b + m - slack)
        out[np.unique(which[on]), k] = True
    return out[at]
