"""How far the periodic margins grow when :func:`.periodic._proved` fails (the next try's ask).

A vertex that fails the proof on an axis used to ask for its disk's whole radius past its
room there (with 1/16 to spare). Where the disk is long and its chord at the margin holds
many sites' coordinates that no copy of theirs is near (a vertical line of sites and one site
off it: the off site's cell, cut by the grown box's top, asked for 1.34 periods of y, 7 n
copies where 3 n are proved), that is far more than the cells need. A failing vertex now asks
for the margins that take in the copies its disk holds (:func:`.periodic_chord.disk_asks`),
measured, no more; where its disk holds none (a cell cut off by the grown box: the cell goes
on past it) the axis doubles, as before.
"""

from __future__ import annotations

import numpy as np

from ..config import PERIODIC_CHORD_SITES, PERIODIC_SHORTFALL_SLACK
from .periodic_chord import chord_clear, disk_asks

# -> config: relative room added to a measured ask (the copies it takes in are rounded sums)
PERIODIC_ASK_RTOL = 2.0**-20
# -> config: the least growth of a margin a measured ask grows (each try takes in more)
PERIODIC_ASK_MIN_GROWTH = 1.25


def shortfall(v, r, sites, box, margin, slack):
    """Per axis, the next margin the failing vertices ask for, or 0.0 where none fails.

    ``v`` the vertices of the kept cells (or pieces), ``r`` each one's distance to its site
    in units of the box's longer side, rounding allowance included; ``slack`` the rounding
    of the copies' coordinates.
    """
    x0, y0, x1, y1 = box
    side = max(x1 - x0, y1 - y0)
    # a vertex on the grown box's side is where a cell was cut off, not a vertex: it asks
    # for that axis only (sites on one line: their cells end there until the copies of the
    # line beside it are in, and asked for half a period along the line too)
    sides = ((x0, x1, margin[0]), (y0, y1, margin[1]))
    edge = np.column_stack(
        [
            (v[:, k] <= a - m + slack) | (v[:, k] >= b + m - slack)
            for k, (a, b, m) in enumerate(sides)
        ]
    )
    bads, rooms = [], []
    for k, (a, b, m) in enumerate(sides):
        room = np.minimum(v[:, k] - (a - m), (b + m) - v[:, k])
        bad = (room < (b - a) + slack) & (room / side < r) & ~edge[:, 1 - k]
        if bad.any():
            rs = np.maximum(room, 0.0) / side
            bad &= ~chord_clear(v, r * r, rs, sites, box, k, m, side, slack, bad)
        bads.append(bad)
        rooms.append(room)
    if edge.any():
        # cells cut off by the grown box: the copies past that side are missing, and a vertex
        # failing on both axes may be one they move (a site off a line: the first margins
        # hold only the line, and the line's cells beside the off site's asked for 1.4
        # periods along the line, 5.9 n copies where the next try proves 3 n): it waits
        both = bads[0] & bads[1]
        bads = [bad & ~both for bad in bads]
    bads = [bad | (room < 0) for bad, room in zip(bads, rooms, strict=True)]
    failing = np.flatnonzero(bads[0] | bads[1])
    if not len(failing):
        return [0.0, 0.0]
    # the copies left out in each failing vertex's disk: a few (a site off a line of
    # sites, cut off by the grown box's side) ask for the margins that take them in; many
    # or none (a line's cells cut off across it: their disks reach over the copies of the
    # line beside it) ask as before, the radius past the room
    count, asks = disk_asks(v, r * side, sites, box, margin, slack, failing, PERIODIC_CHORD_SITES)
    old = np.zeros(len(v), dtype=bool)
    old[failing] = (count > PERIODIC_CHORD_SITES) | ((count == 0) & edge[failing].any(axis=1))
    out = []
    for ask, bad, room, m in zip(asks, bads, rooms, margin, strict=True):
        want = ask * (1.0 + PERIODIC_ASK_RTOL) + 4.0 * slack if ask > 0 else 0.0
        bad = bad & old
        if bad.any():
            need = (r[bad] - np.maximum(room[bad], 0.0) / side).max()
            want = max(want, 2.0 * m, m + PERIODIC_SHORTFALL_SLACK * need * side)
        out.append(float(max(want, PERIODIC_ASK_MIN_GROWTH * m)) if want > m else 0.0)
    return out
