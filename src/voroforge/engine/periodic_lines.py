"""The first periodic margins of sites on an axis-parallel line (and a few off it).

:func:`.periodic._periodic` starts from margins of a few typical cells and grows them where
the proof fails (:mod:`.periodic_retry`). Sites on one line across the box make cells that
reach half a period across the line, to the line's copies a period over: the first try,
whose margins hold only the line, fails on every cell and is a whole build thrown away (a
vertical line of 3e4 sites and one off it: two builds, the first ~20% of the time).
:func:`line_start` reads the line from the sites' extent on each axis and gives the first
try the margins it needs: across the line, the line's copies a period over on each side;
along it, room for the cells of the few sites off the line, whose copies go to the caps.
The proof decides as before; where these margins fall short the retries go on from them.
"""

from __future__ import annotations

import numpy as np

from ..config import (
    PERIODIC_LINE_BAND,
    PERIODIC_LINE_MIN_SITES,
    PERIODIC_LINE_OFF_REACH,
    PERIODIC_LINE_OFF_SLACK,
)


def line_start(pts, box, margin, caps, most):
    """First margins and the sites whose copies go to the caps, for sites on a line.

    Parameters
    ----------
    pts : (n, 2) float64
        The sites, in the box.
    box : (xmin, ymin, xmax, ymax)
    margin, caps : (float, float)
        The plain first margins and their caps.
    most : int
        How many sites off the line may have their copies to the caps.

    Returns
    -------
    ((float, float), (n,) bool) or None
        The margins and the sites off the line, where all but at most ``most`` sites lie in
        a band across an axis at most ``PERIODIC_LINE_BAND`` of its period wide (a line
        parallel to the other axis) and the margins stay below their caps; else None.
    """
    n = len(pts)
    if n < PERIODIC_LINE_MIN_SITES:
        return None
    lo = (box[0], box[1])
    hi = (box[2], box[3])
    for k in range(2):
        period = hi[k] - lo[k]
        band = _band(pts[:, k], min(most, n // 16))
        if band is None or band[1] - band[0] > PERIODIC_LINE_BAND * period:
            continue
        a, b = band
        # across: the line's copies a period over on both sides
        across = max(lo[k] - (a - period), (b + period) - hi[k]) + margin[k]
        if across >= caps[k]:
            return None
        off = (pts[:, k] < a) | (pts[:, k] > b)
        j = 1 - k
        along = margin[j]
        if off.any():
            # an off site's cell reaches along the line sqrt(2 D delta - delta^2) from it, D
            # up to half a period (where the line's copies a period over meet it) and delta
            # its distance from the line (plus a quarter of the plain margin)
            s = pts[off]
            gap = np.minimum(
                np.minimum(np.abs(s[:, k] - a), np.abs(s[:, k] - b)),
                np.minimum(np.abs(s[:, k] - (a - period)), np.abs(s[:, k] - (b + period))),
            )
            gap = np.minimum(gap, np.abs(s[:, k] - (a + period)))
            gap = np.minimum(gap, np.abs(s[:, k] - (b - period)))
            half = 0.5 * period
            reach = PERIODIC_LINE_OFF_REACH * np.sqrt(np.maximum(2.0 * half * gap - gap * gap, 0.0))
            past = np.maximum(s[:, j] + reach - hi[j], lo[j] - (s[:, j] - reach))
            along = max(along, float(past.max()) + PERIODIC_LINE_OFF_SLACK * margin[j])
            along = min(along, caps[j])
        out = [0.0, 0.0]
        out[k] = float(across)
        out[j] = float(along)
        return (out[0], out[1]), off
    return None


def _band(x, spare):
    """The narrowest interval ``(a, b)`` holding all but at most ``spare`` of ``x``."""
    if spare < 0 or len(x) <= spare:
        return None
    c = np.sort(x)
    keep = len(c) - spare
    width = c[keep - 1 :] - c[: spare + 1]
    i = int(np.argmin(width))
    return float(c[i]), float(c[i + keep - 1])
