"""DXF output with ezdxf: closed LWPOLYLINEs on named layers, circular arcs as true bulges.

Laser cutters and CNC software read a DXF polyline with *bulges* as straight segments and
circular arcs. Shapely draws round buffers and fillets as many short chords; :func:`write_dxf`
finds the runs of chords that lie on one circle and writes each run as one arc, so a
filleted corner is a real arc in the cutter's software, not a fan of tiny lines.

The file is deterministic: the same geometry gives the same bytes (fixed creation date, zero
GUIDs, handles in writing order).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import shapely

from .render import as_geometries

__all__ = ["LAYER_COLOURS", "UNITS", "arc_runs", "ring_bulges", "write_dxf"]

#: ``$INSUNITS`` codes of the unit names :func:`write_dxf` accepts.
UNITS = {"unitless": 0, "in": 1, "ft": 2, "mm": 4, "cm": 5, "m": 6}

#: AutoCAD colour index of the conventional fabrication layers (others get white/black, 7).
LAYER_COLOURS = {
    "CUT": 1,  # red
    "SCORE": 5,  # blue
    "ENGRAVE": 3,  # green
    "SITES": 8,  # grey
    "BOUNDARY": 6,  # magenta
    "FRAME": 1,
    "OPENINGS": 1,
    "MARK": 2,  # yellow
}


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
    ok = (np.abs(turn) > 1e-9) & (np.abs(turn) <= max_step * (1.0 + 1e-9))
    lp = length[prv]
    ok &= np.abs(length - lp) <= 1e-3 * np.maximum(length, lp)
    same_next = ok & ok[nxt]
    same_next &= np.abs(turn - turn[nxt]) <= 1e-3 * np.maximum(np.abs(turn), 1e-3)
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
    tolerance: float = 1e-6,
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
    """
    xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    n = len(xy)
    if n < min_segments + 1:
        return []
    _, turn, ok, same_next = _features(xy, np.array([0]), np.array([n]), max_step)
    return _scan(xy, turn, ok, same_next, _tolerance(xy, tolerance), min_segments)


def _tolerance(xy: np.ndarray, tolerance: float) -> float:
    scale = float(np.abs(xy).max()) if len(xy) else 1.0
    return max(float(tolerance), 1e-11 * scale)


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
        good &= np.abs(exact - step * count) <= 0.5 * np.abs(step) + 1e-6
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
    if abs(exact - sweep) > 0.5 * abs(step) + 1e-6:
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
    return [tuple(p) for p in _bulges_of_rings([ring], **options)[0].tolist()]


def _bulges_of_rings(
    rings: list[np.ndarray],
    *,
    arcs: bool = True,
    tolerance: float = 1e-6,
    max_step: float = math.radians(30.0),
    min_segments: int = 3,
) -> list[np.ndarray]:
    """:func:`ring_bulges` for many rings (each an ``(k, 3)`` array of x, y, bulge)."""
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


def _rings(geom):
    """Closed rings (exteriors CCW, holes CW) and open lines of a geometry, as arrays."""
    closed, open_ = [], []
    if geom is None or geom.is_empty:
        return closed, open_
    kind = geom.geom_type
    if kind == "Polygon":
        poly = shapely.orient_polygons(geom) if hasattr(shapely, "orient_polygons") else geom
        for ring in (poly.exterior, *poly.interiors):
            xy = np.asarray(ring.coords)[:-1, :2]
            if len(xy) >= 3:
                closed.append(xy)
    elif kind == "LinearRing":
        closed.append(np.asarray(geom.coords)[:-1, :2])
    elif kind == "LineString":
        open_.append(np.asarray(geom.coords)[:, :2])
    elif kind.startswith("Multi") or kind == "GeometryCollection":
        for part in geom.geoms:
            c, o = _rings(part)
            closed += c
            open_ += o
    return closed, open_


def write_dxf(
    geoms=None,
    path=None,
    *,
    layers: dict | None = None,
    layer: str = "CUT",
    units: str = "mm",
    arcs: bool = True,
    arc_tolerance: float = 1e-6,
    max_arc_step: float = 30.0,
    colours: dict | None = None,
    version: str = "R2000",
) -> Path:
    """Write polygons as closed LWPOLYLINEs on named layers, with fillets as true arcs.

    Every polygon ring (exterior and each hole) becomes one closed LWPOLYLINE on its layer.
    Runs of at least three chords of equal length and equal turning that lie on one circle
    (what shapely's round buffers and :func:`voroforge.design.cellops.fillet` produce) are
    written as one arc each, through the vertex *bulge*. LineStrings become open
    LWPOLYLINEs and points POINT entities.

    Parameters
    ----------
    geoms : sequence of shapely geometries, optional
        Geometry for the ``layer`` layer (default ``"CUT"``).
    path : str or Path
        Output file.
    layers : dict of str to sequence of shapely geometries, optional
        More layers, by name (``{"CUT": frame, "SCORE": edges, "ENGRAVE": labels}``).
        Layer names are upper-cased; geometry for a name given twice is merged.
    layer : str
        Layer of ``geoms``.
    units : {"mm", "cm", "m", "in", "ft", "unitless"}
        Drawing units, written as ``$INSUNITS`` (1 data unit = 1 unit).
    arcs : bool
        Fold circular runs into arcs (``False`` writes every chord as a line).
    arc_tolerance : float
        Largest distance, in drawing units, of a vertex from the arc that replaces it.
    max_arc_step : float
        Largest turning per chord in degrees that still counts as part of an arc; coarser
        polygons (hexagons turn 60°) stay polygons.
    colours : dict of str to int, optional
        AutoCAD colour index per layer, over :data:`LAYER_COLOURS`.
    version : str
        DXF version, ``"R2000"`` or newer (``"R2004"``, ``"R2007"``, ``"R2010"``, ``"R2013"``,
        ``"R2018"``).

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    ValueError
        For unknown units, an old DXF version, a bad layer name or a non-geometry.

    Examples
    --------
    >>> import shapely, tempfile, pathlib
    >>> part = shapely.box(0, 0, 40, 20).buffer(3, quad_segs=8)
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "part.dxf"
    >>> write_dxf([part], out).name
    'part.dxf'
    """
    import ezdxf

    if path is None:
        raise ValueError("write_dxf needs an output path")
    if units not in UNITS:
        raise ValueError(f"units must be one of {', '.join(UNITS)}; got {units!r}")
    if version not in ("R2000", "R2004", "R2007", "R2010", "R2013", "R2018"):
        raise ValueError(f"version must be R2000 or newer; got {version!r}")
    if not arc_tolerance > 0:
        raise ValueError(f"arc_tolerance must be positive; got {arc_tolerance!r}")
    content: dict[str, list] = {}
    if geoms is not None:
        content.setdefault(_layer_name(layer), []).extend(as_geometries(geoms))
    for name, value in (layers or {}).items():
        content.setdefault(_layer_name(name), []).extend(as_geometries(value))
    palette = {**LAYER_COLOURS, **{k.upper(): int(v) for k, v in (colours or {}).items()}}

    options = {"tolerance": arc_tolerance, "max_step": math.radians(max_arc_step), "arcs": arcs}
    saved = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        doc = ezdxf.new(version, setup=False, units=UNITS[units])
        doc.header["$MEASUREMENT"] = 0 if units in ("in", "ft") else 1
        msp = doc.modelspace()
        for name, items in content.items():
            doc.layers.add(name, color=palette.get(name, 7))
            attribs = {"layer": name}
            closed_all, open_all = [], []
            for geom in items:
                closed, open_ = _rings(geom)
                closed_all += closed
                open_all += open_
            for points in _bulges_of_rings(closed_all, **options):
                _add_closed(msp, points, attribs)
            for xy in open_all:
                msp.add_lwpolyline(xy.tolist(), format="xy", close=False, dxfattribs=attribs)
            for geom in items:
                if "Point" not in geom.geom_type and geom.geom_type != "GeometryCollection":
                    continue
                for pt in shapely.get_parts(geom):
                    if pt.geom_type == "Point":
                        msp.add_point((pt.x, pt.y), dxfattribs=attribs)
        path = Path(path)
        doc.saveas(path)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = saved
    return path


def _add_closed(msp, points: np.ndarray, attribs: dict) -> None:
    """Add a closed LWPOLYLINE of ``(k, 3)`` x, y, bulge rows.

    ezdxf keeps LWPOLYLINE vertices as an ``(k, 5)`` float array (x, y, start width, end
    width, bulge); filling it in one go is several times faster than appending point by
    point. Any other layout (a future ezdxf) takes the public, slower way.
    """
    e = msp.add_lwpolyline([], close=True, dxfattribs=attribs)
    store = getattr(e, "lwpoints", None)
    values = getattr(store, "values", None)
    if isinstance(values, np.ndarray) and values.ndim == 2 and values.shape[1] == 5:
        block = np.zeros((len(points), 5))
        block[:, :2] = points[:, :2]
        block[:, 4] = points[:, 2]
        store.values = block
    else:  # pragma: no cover - depends on ezdxf internals
        e.set_points(points.tolist(), format="xyb")


def _layer_name(name) -> str:
    text = str(name).strip().upper()
    bad = set('<>/\\":;?*|=`')
    if not text or any(c in bad for c in text):
        raise ValueError(f"invalid DXF layer name {name!r}")
    return text
