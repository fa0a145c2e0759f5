"""Arc fitting: runs of polygon chords that lie on one circle, folded into DXF bulges.

Shapely draws round buffers and fillets as many short chords. :func:`arc_runs` finds the
runs of equal chords with equal turning whose vertices lie on one circle, and
:func:`bulges_of_rings` folds each run into one vertex *bulge* (``tan(sweep / 4)``), the
form both the DXF writer (LWPOLYLINE bulges) and the SVG layer writer (``A`` arcs) use.
"""

from __future__ import annotations

import math

import numpy as np

from ..config import (
    ARC_CHORD_RTOL,
    ARC_FIT_RTOL,
    ARC_MIN_TURN,
    ARC_STEP_RTOL,
    ARC_SWEEP_ATOL,
    ARC_TOLERANCE,
    ARC_TURN_FLOOR,
    ARC_TURN_RTOL,
)

__all__ = ["arc_runs", "bulges_of_rings", "ring_bulges"]


def _features(xy: np.ndarray, ring_start: np.ndarray, ring_len: np.ndarray, max_step: float):
    """Per-vertex arc features of closed rings stored one after another in ``xy``.

    Returns chord lengths ``L[k] = |p[k+1] - p[k]|``, signed turning angles at each vertex,
    ``ok`` (the vertex can be inside an arc: small turn, equal chords on both sides) and
    ``same_next`` (it turns like its successor, so both belong to one arc).
    """
    n = len(xy)
    idx = np.arange(n)
    owner = np.repeat(np.arange(len(ring_len)), ring_len)
    local = idx - ring_start[owner]
    nxt = ring_start[owner] + (local + 1) % ring_len[owner]
    prv = ring_start[owner] + (local - 1) % ring_len[owner]
    d = xy[nxt] - xy
    length = np.hypot(d[:, 0], d[:, 1])
    prev = d[prv]
    cross = prev[:, 0] * d[:, 1] - prev[:, 1] * d[:, 0]
    dot = prev[:, 0] * d[:, 0] + prev[:, 1] * d[:, 1]
    turn = np.arctan2(cross, dot)
    ok = (np.abs(turn) > ARC_MIN_TURN) & (np.abs(turn) <= max_step * (1.0 + ARC_STEP_RTOL))
    lp = length[prv]
    ok &= np.abs(length - lp) <= ARC_CHORD_RTOL * np.maximum(length, lp)
    same_next = ok & ok[nxt]
    turn_slack = ARC_TURN_RTOL * np.maximum(np.abs(turn), ARC_TURN_FLOOR)
    same_next &= np.abs(turn - turn[nxt]) <= turn_slack
    return length, turn, ok, same_next


def _circle(a, b, c) -> tuple[np.ndarray, float] | None:
    """Centre and radius of the circle through three points (``None`` when collinear)."""
    ax, ay = b[0] - a[0], b[1] - a[1]
    bx, by = c[0] - a[0], c[1] - a[1]
    den = 2.0 * (ax * by - ay * bx)
    if den == 0.0:
        return None
    a2, b2 = ax * ax + ay * ay, bx * bx + by * by
    ux = (by * a2 - ay * b2) / den
    uy = (ax * b2 - bx * a2) / den
    return np.array([a[0] + ux, a[1] + uy]), math.hypot(ux, uy)


def arc_runs(
    xy,
    *,
    tolerance: float = ARC_TOLERANCE,
    max_step: float = math.radians(30.0),
    min_segments: int = 3,
) -> list[tuple[int, int, float]]:
    """Find runs of chords of a closed ring that lie on one circular arc.

    A run is at least ``min_segments`` chords of equal length with equal turning (same sign,
    at most ``max_step`` per vertex) whose vertices all lie within ``tolerance`` of one
    circle. The equal-turning test keeps regular polygons with coarse steps (hexagons,
    squares) as polygons.

    Parameters
    ----------
    xy : (n, 2) float64
        Ring vertices without the closing repeat.
    tolerance : float
        Largest distance of a vertex from the fitted circle, in drawing units.
    max_step : float
        Largest turning angle per chord in radians (shapely's round buffers turn by
        ``90° / quad_segs``: 11.25° by default).
    min_segments : int
        Fewest chords that make an arc.

    Returns
    -------
    list of (start, count, sweep)
        The arc starts at vertex ``start`` and spans ``count`` chords (it ends at vertex
        ``(start + count) % n``); ``sweep`` is its signed angle in radians (positive:
        counter-clockwise). Runs do not overlap and are sorted by ``start``.

    Examples
    --------
    A round buffer's 32 chords are two half circles (a bulge cannot close on itself):

    >>> import shapely
    >>> disc = np.asarray(shapely.Point(0, 0).buffer(1.0, quad_segs=8).exterior.coords)[:-1]
    >>> [count for _, count, _ in arc_runs(disc)]
    [16, 16]
    """
    xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    n = len(xy)
    if n < min_segments + 1:
        return []
    _, turn, ok, same_next = _features(xy, np.array([0]), np.array([n]), max_step)
    return _scan(xy, turn, ok, same_next, _tolerance(xy, tolerance), min_segments)


def _tolerance(xy: np.ndarray, tolerance: float) -> float:
    scale = float(np.abs(xy).max()) if len(xy) else 1.0
    return max(float(tolerance), ARC_FIT_RTOL * scale)


def _candidates(ok, same_next, min_segments: int) -> list[tuple[int, int, int]]:
    """Runs of arc vertices of one ring as ``(start, count, first inside vertex)``."""
    n = len(ok)
    ok_l = ok.tolist()
    same_l = same_next.tolist()
    # Start the scan after a vertex that does not continue to its successor.
    first = (same_l.index(False) + 1) % n
    out = []
    k = 0
    while k < n:
        v = (first + k) % n
        if not ok_l[v]:
            k += 1
            continue
        m = 1  # inside vertices in this run: v, v+1, ..., v+m-1
        while k + m < n and same_l[(v + m - 1) % n]:
            m += 1
        if m + 1 >= min_segments:  # chords from vertex v-1 to vertex v+m
            out.append(((v - 1) % n, m + 1, v))
        k += m
    return out


def _fit_many(xy, ring_start, ring_len, ring, start, count, step, tol):
    """Vectorised circle check of many candidate runs; returns (accepted, exact sweeps).

    Each run's circle goes through its first, middle and last vertex; every vertex must lie
    within ``tol`` of it, and the sweep seen from the centre must match ``step * count``.
    """
    ring_start = np.asarray(ring_start)
    ring_len = np.asarray(ring_len)

    def at(r, j):
        return xy[ring_start[r] + j % ring_len[r]]

    p0, pm, p1 = at(ring, start), at(ring, start + count // 2), at(ring, start + count)
    a = pm - p0
    b = p1 - p0
    den = 2.0 * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    a2 = (a * a).sum(axis=1)
    b2 = (b * b).sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (b[:, 1] * a2 - a[:, 1] * b2) / den
        uy = (a[:, 0] * b2 - b[:, 0] * a2) / den
    centre = p0 + np.column_stack((ux, uy))
    radius = np.hypot(ux, uy)
    good = (den != 0) & np.isfinite(radius)
    # Distances of every vertex of every run from its circle.
    sizes = count + 1
    run_of = np.repeat(np.arange(len(count)), sizes)
    firsts = np.concatenate(([0], np.cumsum(sizes)[:-1]))
    local = start[run_of] + np.arange(sizes.sum()) - firsts[run_of]
    pts = at(ring[run_of], local)
    with np.errstate(invalid="ignore"):
        off = np.abs(np.hypot(*(pts - centre[run_of]).T) - radius[run_of])
    worst = np.maximum.reduceat(np.where(np.isfinite(off), off, np.inf), firsts)
    good &= worst <= tol[ring]
    # The sweep from the centre (exact for the end points; direction from the turning).
    a0 = np.arctan2(p0[:, 1] - centre[:, 1], p0[:, 0] - centre[:, 0])
    a1 = np.arctan2(p1[:, 1] - centre[:, 1], p1[:, 0] - centre[:, 0])
    exact = np.mod(a1 - a0, 2.0 * math.pi)
    exact = np.where(step < 0, exact - 2.0 * math.pi, exact)
    with np.errstate(invalid="ignore"):
        good &= np.abs(exact - step * count) <= 0.5 * np.abs(step) + ARC_SWEEP_ATOL
    return good, exact


def _scan(xy, turn, ok, same_next, tol: float, min_segments: int) -> list[tuple[int, int, float]]:
    """Group the arc vertices of one ring into runs and keep those that fit a circle."""
    n = len(xy)
    if ok.all() and same_next.all():
        return _full_circle(xy, turn, tol)
    cand = _candidates(ok, same_next, min_segments)
    if not cand:
        return []
    start, count, v = (np.array(c, dtype=np.int64) for c in zip(*cand, strict=True))
    ring = np.zeros(len(start), dtype=np.int64)
    good, exact = _fit_many(xy, [0], [n], ring, start, count, turn[v], np.array([tol]))
    return [
        (int(s), int(c), float(e))
        for s, c, e, g in zip(start, count, exact, good, strict=True)
        if g
    ]


def _fit(xy, start: int, count: int, step: float, tol: float) -> tuple[int, int, float] | None:
    """Check that the ``count + 1`` vertices from ``start`` lie on one circle; return the run."""
    n = len(xy)
    idx = (start + np.arange(count + 1)) % n
    pts = xy[idx]
    circ = _circle(pts[0], pts[count // 2], pts[-1])
    if circ is None:
        return None
    centre, radius = circ
    if not math.isfinite(radius):
        return None
    dist = np.abs(np.hypot(pts[:, 0] - centre[0], pts[:, 1] - centre[1]) - radius)
    if dist.max() > tol:
        return None
    sweep = float(np.sign(step)) * abs(float(step)) * count
    # Refine the sweep from the centre (exact for the end points, sign from the turning).
    a0 = math.atan2(pts[0, 1] - centre[1], pts[0, 0] - centre[0])
    a1 = math.atan2(pts[-1, 1] - centre[1], pts[-1, 0] - centre[0])
    exact = (a1 - a0) % (2.0 * math.pi)
    if step < 0:
        exact -= 2.0 * math.pi
    if abs(exact - sweep) > 0.5 * abs(step) + ARC_SWEEP_ATOL:
        return None
    return start, count, exact


def _full_circle(xy, turn, tol) -> list[tuple[int, int, float]]:
    """A ring that is all one circle: two half arcs (a bulge cannot close on itself)."""
    n = len(xy)
    half = n // 2
    runs = []
    for start, count in ((0, half), (half, n - half)):
        run = _fit(xy, start, count, turn[(start + 1) % n], tol)
        if run is None:
            return []
        runs.append(run)
    return runs


def ring_bulges(xy, **options) -> list[tuple[float, float, float]]:
    """Vertices of a closed ring as ``(x, y, bulge)`` with arcs folded into bulges.

    Parameters
    ----------
    xy : (n, 2) float64
        Ring vertices without the closing repeat.
    **options
        ``tolerance``, ``max_step``, ``min_segments`` as for :func:`arc_runs`;
        ``arcs=False`` keeps every chord.

    Returns
    -------
    list of (x, y, bulge)
        ``bulge = tan(sweep / 4)`` describes the segment from this vertex to the next
        (0 for a straight segment, positive for a counter-clockwise arc).
    """
    ring = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    return [tuple(p) for p in bulges_of_rings([ring], **options)[0].tolist()]


def bulges_of_rings(
    rings: list[np.ndarray],
    *,
    arcs: bool = True,
    tolerance: float = ARC_TOLERANCE,
    max_step: float = math.radians(30.0),
    min_segments: int = 3,
) -> list[np.ndarray]:
    """Fold the circular runs of many closed rings into bulges in one vectorised pass.

    Parameters
    ----------
    rings : list of (k, 2) float64
        Ring vertices without the closing repeat.
    arcs : bool
        ``False`` keeps every chord (all bulges 0).
    tolerance, max_step, min_segments
        As for :func:`arc_runs`.

    Returns
    -------
    list of (m, 3) float64
        Per ring, the kept vertices as rows ``x, y, bulge`` (see :func:`ring_bulges`).
    """
    out: list = []
    if not rings:
        return out
    lens = np.array([len(r) for r in rings], dtype=np.int64)
    xy = np.concatenate(rings) if len(rings) > 1 else rings[0]
    starts = np.concatenate(([0], np.cumsum(lens)[:-1]))
    if arcs and len(xy):
        _, turn, ok, same_next = _features(xy, starts, lens, max_step)
        candidates = np.add.reduceat(ok.astype(np.int64), starts) >= min_segments - 1
    else:
        candidates = np.zeros(len(rings), dtype=bool)
    # Candidate runs of every ring, then one vectorised circle check for all of them.
    runs_of: list[list] = [[] for _ in rings]
    full: list[int] = []
    cand_ring, cand_start, cand_count, cand_v = [], [], [], []
    for i in np.flatnonzero(candidates).tolist():
        n = len(rings[i])
        if n < min_segments + 1:
            continue
        sl = slice(starts[i], starts[i] + n)
        if ok[sl].all() and same_next[sl].all():
            full.append(i)
            continue
        for start, count, v in _candidates(ok[sl], same_next[sl], min_segments):
            cand_ring.append(i)
            cand_start.append(start)
            cand_count.append(count)
            cand_v.append(starts[i] + v)
    if cand_ring:
        ring_ids = np.asarray(cand_ring, dtype=np.int64)
        tol = np.array([_tolerance(r, tolerance) for r in rings])
        good, exact = _fit_many(
            xy,
            starts,
            lens,
            ring_ids,
            np.asarray(cand_start, dtype=np.int64),
            np.asarray(cand_count, dtype=np.int64),
            turn[np.asarray(cand_v, dtype=np.int64)],
            tol,
        )
        for k in np.flatnonzero(good).tolist():
            runs_of[cand_ring[k]].append((cand_start[k], cand_count[k], float(exact[k])))
    for i in full:
        sl = slice(starts[i], starts[i] + len(rings[i]))
        runs_of[i] = _full_circle(rings[i], turn[sl], _tolerance(rings[i], tolerance))
    for ring, runs in zip(rings, runs_of, strict=True):
        n = len(ring)
        if not runs:
            out.append(np.column_stack((ring, np.zeros(n))))
            continue
        skip = np.zeros(n, dtype=bool)
        bulge = np.zeros(n)
        for start, count, sweep in runs:
            bulge[start] = math.tan(sweep / 4.0)
            skip[(start + 1 + np.arange(count - 1)) % n] = True
        out.append(np.column_stack((ring, bulge))[~skip])
    return out
