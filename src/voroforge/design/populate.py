"""Seed points inside a boundary: random, grids, Poisson-disk, by density, along curves.

Every function returns a new ``(n, 2)`` float64 array of points strictly inside the
boundary (holes excluded). Randomness comes from ``numpy.random.default_rng(seed)``: the
same arguments and seed give the same points.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from .. import config
from ..io.snap import nearest_to
from .boundary import as_polygonal

__all__ = [
    "along_curves",
    "as_region",
    "by_density",
    "crossing_edges",
    "from_file",
    "grid",
    "hexgrid",
    "jittered",
    "poisson",
    "random",
]

_MAX_ROUNDS = 1000  # rejection-sampling rounds before giving up


def as_region(boundary):
    """A boundary (polygonal geometry or ``(xmin, ymin, xmax, ymax)``) as a prepared region.

    Raises
    ------
    ValueError
        For an empty box or geometry that is not polygonal.
    """
    if isinstance(boundary, tuple | list) and len(boundary) == 4:
        xmin, ymin, xmax, ymax = (float(v) for v in boundary)
        if not (xmin < xmax and ymin < ymax):
            raise ValueError(f"boundary box {boundary!r} needs xmin < xmax and ymin < ymax")
        boundary = shapely.box(xmin, ymin, xmax, ymax)
    geom = as_polygonal(boundary)
    shapely.prepare(geom)
    return geom


def _count(count, name: str = "count") -> int:
    if isinstance(count, bool) or int(count) != count or count < 0:
        raise ValueError(f"{name} must be an integer >= 0, got {count!r}")
    if count > config.SEEDS_MAX_POINTS:
        raise ValueError(f"{name} {int(count):,} is too large: at most {config.SEEDS_MAX_POINTS:,}")
    return int(count)


def _positive(value, name: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return v


def _inside(geom, xy: np.ndarray) -> np.ndarray:
    if len(xy) == 0:
        return np.zeros(0, dtype=bool)
    return shapely.contains_xy(geom, xy[:, 0], xy[:, 1])


def _field_values(field, xy: np.ndarray) -> np.ndarray:
    """Evaluate a user field at points; check the shape and clip to [0, 1]."""
    if len(xy) == 0:
        return np.zeros(0)
    values = np.asarray(field(xy.copy()), dtype=np.float64)
    if values.shape != (len(xy),):
        raise ValueError(
            f"field must return one value per point, shape ({len(xy)},), got {values.shape}"
        )
    if not np.isfinite(values).all():
        raise ValueError("field returned NaN or infinite values")
    return np.clip(values, 0.0, 1.0)


def next_batch(base: int, short: int, drawn: int, kept: int, what: str = "the field") -> int:
    """Candidates to draw in a rejection round: ``base``, unless few are being kept.

    Where under ``config.POPULATE_LOW_ACCEPT`` of the ``drawn`` candidates were ``kept``,
    the ``short`` points still missing are drawn at that rate (capped at
    ``config.POPULATE_MAX_BATCH``): at a fixed multiple of the shortfall a rate of 1e-3
    needed thousands of rounds and was refused as a field or image that misses the
    boundary. Raises ValueError once ``config.POPULATE_MAX_DRAWS`` candidates are drawn.
    """
    if drawn >= config.POPULATE_MAX_DRAWS or (not kept and drawn >= config.POPULATE_EMPTY_DRAWS):
        raise ValueError(
            f"could not place the points: {kept:,} of {drawn:,} candidates fell in the boundary"
            f" where the density allows ({what} hardly meets the boundary)"
        )
    rate = kept / drawn if drawn else 1.0
    if rate >= config.POPULATE_LOW_ACCEPT:
        return base
    want = short / max(rate, 1.0 / drawn) * 1.2 + 16
    return int(min(max(base, want), config.POPULATE_MAX_BATCH))


def _uniform(geom, count: int, rng) -> np.ndarray:
    """Exactly ``count`` uniform points inside ``geom`` by rejection from its bounding box.

    A boundary filling less than ``config.POPULATE_REJECTION_MIN_FILL`` of its box (a thin
    diagonal strip) is sampled from its triangles instead: rejection would draw
    ``count / fill`` points (3 GiB for 50 points in a strip filling 3e-7 of its box).
    """
    xmin, ymin, xmax, ymax = geom.bounds
    ratio = geom.area / ((xmax - xmin) * (ymax - ymin))
    if ratio < config.POPULATE_REJECTION_MIN_FILL or count / ratio > config.POPULATE_MAX_BATCH:
        return _uniform_triangles(geom, count, rng)
    out = []
    have = 0
    for _ in range(_MAX_ROUNDS):
        if have >= count:
            break
        m = int((count - have) / ratio * 1.2) + 16
        xy = rng.uniform((xmin, ymin), (xmax, ymax), size=(m, 2))
        xy = xy[_inside(geom, xy)]
        out.append(xy)
        have += len(xy)
    else:
        raise ValueError("could not place the points: the boundary is too thin for sampling")
    return np.concatenate(out)[:count] if out else np.zeros((0, 2))


def _uniform_triangles(geom, count: int, rng) -> np.ndarray:
    """Exactly ``count`` uniform points strictly inside ``geom``, drawn from its triangles."""
    tris = shapely.get_parts(shapely.constrained_delaunay_triangles(geom))
    corners = shapely.get_coordinates(shapely.get_exterior_ring(tris)).reshape(-1, 4, 2)[:, :3]
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    area = 0.5 * np.abs(
        (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    )
    if not len(area) or not area.sum() > 0:
        raise ValueError("could not place the points: the boundary has no area to sample")
    out, have = [], 0
    for _ in range(_MAX_ROUNDS):
        if have >= count:
            break
        m = count - have + 16
        t = rng.choice(len(area), size=m, p=area / area.sum())
        u, v = rng.random(m), rng.random(m)
        flip = u + v > 1.0
        u[flip], v[flip] = 1.0 - u[flip], 1.0 - v[flip]
        xy = a[t] + u[:, None] * (b[t] - a[t]) + v[:, None] * (c[t] - a[t])
        xy = xy[_inside(geom, xy)]  # rounding can put a point on the outline
        out.append(xy)
        have += len(xy)
    else:
        raise ValueError("could not place the points: the boundary is too thin for sampling")
    return np.concatenate(out)[:count] if out else np.zeros((0, 2))


def random(boundary, count, *, seed) -> np.ndarray:
    """``count`` uniformly random points inside the boundary.

    Parameters
    ----------
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        Where to put the points (holes respected).
    count : int
        Number of points.
    seed : int
        Random seed.

    Returns
    -------
    (count, 2) float64

    Examples
    --------
    >>> import shapely
    >>> random(shapely.box(0, 0, 10, 10), 5, seed=1).shape
    (5, 2)
    """
    geom = as_region(boundary)
    n = _count(count)
    return np.ascontiguousarray(_uniform(geom, n, np.random.default_rng(seed)))


def _lattice(geom, spacing: float, angle: float, offset, hexagonal: bool, margin: float = 0.0):
    """Lattice points (square or hexagonal) covering ``geom``, rotated by ``angle`` degrees.

    The lattice is anchored at the centre of the boundary's bounding box plus ``offset`` (so
    symmetric boundaries get symmetric seeds) and ordered row by row.
    """
    off = np.asarray(offset, dtype=np.float64)
    if off.shape != (2,) or not np.isfinite(off).all():
        raise ValueError(f"offset must be two finite numbers, got {offset!r}")
    ang = float(angle)
    if not math.isfinite(ang):
        raise ValueError(f"angle must be finite, got {angle!r}")
    xmin, ymin, xmax, ymax = geom.bounds
    centre = np.array([(xmin + xmax) / 2, (ymin + ymax) / 2]) + off
    # radius of the bounding box around the anchor, plus one cell
    reach = (
        math.hypot(
            max(abs(xmin - centre[0]), abs(xmax - centre[0])),
            max(abs(ymin - centre[1]), abs(ymax - centre[1])),
        )
        + margin
    )
    dy = spacing * math.sqrt(3) / 2 if hexagonal else spacing
    nx = int(math.ceil(reach / spacing)) + 1
    ny = int(math.ceil(reach / dy)) + 1
    t = math.radians(ang)
    rot = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
    # Only the rows and columns that reach the box (grown by margin) in the lattice's frame:
    # the disc around it held (diagonal / spacing)^2 points, 16M tested for 76k in a
    # 2000 x 10 strip, and a 20000 x 10 one was refused. The points kept are the same.
    box = np.array(
        [[xmin, ymin], [xmax, ymin], [xmax, ymax], [xmin, ymax]], dtype=np.float64
    ) + margin * np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]])
    lx, ly = ((box - centre) @ rot).T
    i0 = max(-nx, math.floor(lx.min() / spacing) - 2)
    i1 = min(nx, math.ceil(lx.max() / spacing) + 2)
    j0 = max(-ny, math.floor(ly.min() / dy) - 2)
    j1 = min(ny, math.ceil(ly.max() / dy) + 2)
    if max(i1 - i0 + 1, 0) * max(j1 - j0 + 1, 0) > config.SEEDS_MAX_POINTS:
        raise ValueError(
            f"spacing {spacing} is too small for this boundary "
            f"(> {config.SEEDS_MAX_POINTS:,} points)"
        )
    j, i = np.meshgrid(np.arange(j0, j1 + 1), np.arange(i0, i1 + 1), indexing="ij")
    x = i * spacing + (0.5 * spacing * (j % 2) if hexagonal else 0.0)
    y = j * dy
    local = np.column_stack((x.ravel(), y.ravel()))
    return local @ rot.T + centre, rot


def grid(boundary, spacing, *, angle=0.0, offset=(0.0, 0.0)) -> np.ndarray:
    """Square-grid points inside the boundary.

    Parameters
    ----------
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        Where to put the points (holes respected).
    spacing : float
        Distance between neighbouring points.
    angle : float
        Rotation of the grid in degrees (counter-clockwise).
    offset : (2,) float
        Shift of the grid from its anchor, the centre of the boundary's bounding box.

    Returns
    -------
    (n, 2) float64
        Row by row.
    """
    geom = as_region(boundary)
    pts, _ = _lattice(geom, _positive(spacing, "spacing"), angle, offset, hexagonal=False)
    return np.ascontiguousarray(pts[_inside(geom, pts)])


def hexgrid(boundary, spacing, *, angle=0.0, offset=(0.0, 0.0)) -> np.ndarray:
    """Hexagonal-grid points inside the boundary (their Voronoi cells are regular hexagons).

    Parameters
    ----------
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        Where to put the points (holes respected).
    spacing : float
        Distance between neighbouring points (rows are ``spacing * sqrt(3) / 2`` apart).
    angle : float
        Rotation in degrees (counter-clockwise).
    offset : (2,) float
        Shift of the grid from its anchor, the centre of the boundary's bounding box.

    Returns
    -------
    (n, 2) float64
        Row by row.
    """
    geom = as_region(boundary)
    pts, _ = _lattice(geom, _positive(spacing, "spacing"), angle, offset, hexagonal=True)
    return np.ascontiguousarray(pts[_inside(geom, pts)])


def jittered(boundary, spacing, *, jitter=0.5, seed, angle=0.0, offset=(0.0, 0.0)) -> np.ndarray:
    """Square-grid points each moved randomly within its own grid cell.

    Parameters
    ----------
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        Where to put the points (holes respected).
    spacing : float
        Grid spacing.
    jitter : float in [0, 1]
        Each point moves uniformly within a square of side ``jitter * spacing`` around its
        grid position (0: the plain grid; 1: stratified sampling, one point per grid cell).
    seed : int
        Random seed.
    angle : float
        Rotation of the grid in degrees.
    offset : (2,) float
        Shift of the grid from the boundary's bounding-box centre (as for :func:`grid`).

    Returns
    -------
    (n, 2) float64
    """
    geom = as_region(boundary)
    s = _positive(spacing, "spacing")
    j = float(jitter)
    if not 0.0 <= j <= 1.0:
        raise ValueError(f"jitter must be in [0, 1], got {jitter!r}")
    pts, rot = _lattice(geom, s, angle, offset, hexagonal=False, margin=s)
    rng = np.random.default_rng(seed)
    shift = rng.uniform(-0.5, 0.5, size=pts.shape) * (j * s)
    pts = pts + shift @ rot.T
    return np.ascontiguousarray(pts[_inside(geom, pts)])


def poisson(boundary, radius, *, seed, field=None, radius_max=None, k: int = 30) -> np.ndarray:
    """Poisson-disk points (Bridson), optionally with a spacing that varies with a field.

    No two points are closer than the local spacing, and the sampling is maximal in
    practice: after Bridson's front stops, random probes look for any remaining gap (also in
    separate parts of the boundary) and restart the front there.

    Parameters
    ----------
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        Where to put the points (holes respected).
    radius : float
        Minimum distance between points (where ``field`` is 1).
    seed : int
        Random seed.
    field : callable, optional
        ``field(xy (m, 2)) -> (m,)`` values in [0, 1] (for example an attractor). The local
        spacing at ``p`` is ``r(p) = radius + (radius_max - radius) * (1 - field(p))``; two
        points ``p, q`` are at least ``max(r(p), r(q))`` apart.
    radius_max : float, optional
        Spacing where ``field`` is 0 (required with ``field``; >= ``radius``).
    k : int
        Candidates tried around each active point before it retires (Bridson's k).

    Returns
    -------
    (n, 2) float64
        In the order they were placed.

    Notes
    -----
    The background grid has cells of ``radius / sqrt(2)`` (the smallest spacing), so each
    cell holds at most one point; a candidate is compared with the points in the grid window
    that the largest spacing can reach.
    """
    geom = as_region(boundary)
    rmin = _positive(radius, "radius")
    if int(k) != k or k < 1:
        raise ValueError(f"k must be an integer >= 1, got {k!r}")
    k = int(k)
    if field is None:
        if radius_max is not None and float(radius_max) != rmin:
            raise ValueError("radius_max needs a field (the spacing varies with the field)")
        rmax = rmin
    else:
        if not callable(field):
            raise ValueError("field must be a callable field(xy) -> values in [0, 1]")
        if radius_max is None:
            raise ValueError("poisson with a field needs radius_max (the spacing where field=0)")
        rmax = _positive(radius_max, "radius_max")
        if rmax < rmin:
            raise ValueError(f"radius_max ({rmax}) must be >= radius ({rmin})")
    # a spacing past the boundary's diagonal keeps one seed whatever its value: capped at
    # twice the diagonal, no comparison changes and huge radii (1e308) do not overflow
    bx0, by0, bx1, by1 = geom.bounds
    cap = 2.0 * math.hypot(bx1 - bx0, by1 - by0)
    if cap > 0:
        rmin, rmax = min(rmin, cap), min(rmax, cap)
    variable = field is not None and rmax > rmin

    def spacing(xy):
        if not variable:
            return np.full(len(xy), rmin)
        return rmin + (rmax - rmin) * (1.0 - _field_values(field, xy))

    xmin, ymin, xmax, ymax = geom.bounds
    cell = rmin / math.sqrt(2.0)
    gw = int((xmax - xmin) / cell) + 1
    gh = int((ymax - ymin) / cell) + 1
    if gw * gh > config.SEEDS_MAX_POINTS:
        raise ValueError(
            f"radius {rmin} is too small for this boundary "
            f"(grid > {config.SEEDS_MAX_POINTS:,} cells)"
        )
    # a maximal Poisson-disk sampling holds about 0.67 points per radius^2 (measured)
    expected = 0.67 * geom.area / (rmin * rmin)
    if expected > config.POISSON_MAX_POINTS:
        raise ValueError(
            f"radius {rmin:g} is too small for this boundary: about {expected:,.0f} points "
            f"expected, at most {config.POISSON_MAX_POINTS:,} (use a larger radius, or "
            "vf.voronoi on points of your own)"
        )
    reach = int(math.ceil(rmax / cell))
    # padded grid of point indices (-1 = free) so windows never leave the array
    owner = np.full((gh + 2 * reach, gw + 2 * reach), -1, dtype=np.int64)
    store = {"p": np.zeros((1024, 2)), "r": np.zeros(1024), "n": 0}
    rng = np.random.default_rng(seed)
    win = np.arange(-reach, reach + 1)
    wy, wx = (w.ravel() for w in np.meshgrid(win, win, indexing="ij"))

    def cells_of(xy):
        gy = ((xy[:, 1] - ymin) / cell).astype(np.int64) + reach
        gx = ((xy[:, 0] - xmin) / cell).astype(np.int64) + reach
        return gy, gx

    def fits(cand: np.ndarray, rc: np.ndarray) -> np.ndarray:
        """For each candidate (c, 2) with spacing rc: no point within the pair spacing."""
        gy, gx = cells_of(cand)
        idx = owner[gy[:, None] + wy, gx[:, None] + wx]  # (c, window)
        taken = idx >= 0
        safe = np.where(taken, idx, 0)
        d2 = ((store["p"][safe] - cand[:, None, :]) ** 2).sum(axis=2)
        need = np.maximum(store["r"][safe], rc[:, None])
        return ~(taken & (d2 < need * need)).any(axis=1)

    def add(p, r):
        n = store["n"]
        if n == len(store["r"]):
            store["p"] = np.concatenate((store["p"], np.zeros_like(store["p"])))
            store["r"] = np.concatenate((store["r"], np.zeros_like(store["r"])))
        gy, gx = cells_of(p[None])
        owner[gy[0], gx[0]] = n
        store["p"][n] = p
        store["r"][n] = r
        store["n"] = n + 1
        return n

    def bridson(active: list[int]):
        while active:
            j = int(rng.integers(len(active)))
            a = store["p"][active[j]]
            ra = store["r"][active[j]]
            # k candidates uniformly by area in the annulus [ra, 2 ra]
            rr = ra * np.sqrt(rng.uniform(1.0, 4.0, size=k))
            th = rng.uniform(0.0, 2.0 * math.pi, size=k)
            cand = a + np.column_stack((rr * np.cos(th), rr * np.sin(th)))
            inside = _inside(geom, cand)
            placed = False
            if inside.any():
                cand = cand[inside]
                rc = spacing(cand)
                # the candidate must also respect the active point's own spacing
                far = ((cand - a) ** 2).sum(axis=1) >= np.maximum(rc, ra) ** 2
                cand, rc = cand[far], rc[far]
                if len(cand):
                    ok = np.flatnonzero(fits(cand, rc))
                    if len(ok):
                        active.append(add(cand[ok[0]], float(rc[ok[0]])))
                        placed = True
            if not placed:
                active[j] = active[-1]
                active.pop()

    # gap filling: random probes; every probe farther than the pair spacing from all points
    # (checked one by one, so new fronts never conflict) starts a new front. The first
    # round has no points yet: its first probe starts the first front.
    def gap_round(region) -> bool:
        """One round of probes in ``region``; False when none started a front."""
        n_probe = int(min(200_000, max(64, 4 * region.area / (rmin * rmin))))
        probes = _uniform(region, n_probe, rng)
        n = store["n"]
        if n:
            # pre-filter: only probes clear of their nearest point's spacing (numpy for a
            # few hundred thousand pairs, so small designs need no scipy; a KD-tree beyond)
            dist, idx = nearest_to(store["p"][:n], probes)
            keep = dist >= np.maximum(spacing(probes), store["r"][:n][idx])
            probes = probes[keep]
        else:
            probes = probes[:1]
        fronts = []
        for probe, r in zip(probes, spacing(probes), strict=True):
            if fits(probe[None], np.array([r]))[0]:
                fronts.append(add(probe, float(r)))
        started = bool(fronts)
        bridson(fronts)  # empties the list
        return started

    for _ in range(_MAX_ROUNDS):
        if not gap_round(geom):
            break
    # A part of a MultiPolygon far smaller than the whole gets a few probes a round by area
    # and could be left empty (a 0.05-wide square 14 radii away: 18 of 20 seeds): probe
    # each part that holds no point on its own, until it does or no probe fits there.
    for part in shapely.get_parts(geom):
        for _ in range(_MAX_ROUNDS):
            if _inside(part, store["p"][: store["n"]]).any() or not gap_round(part):
                break
    return np.ascontiguousarray(store["p"][: store["n"]])


def by_density(boundary, count, field, *, seed) -> np.ndarray:
    """``count`` random points with a density proportional to ``field`` (rejection sampling).

    Parameters
    ----------
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        Where to put the points (holes respected).
    count : int
        Number of points.
    field : callable
        ``field(xy (m, 2)) -> (m,)`` values in [0, 1] (values outside are clipped); the
        density of points is proportional to it.
    seed : int
        Random seed.

    Returns
    -------
    (count, 2) float64

    Notes
    -----
    A uniform point is kept with probability ``field(p) / fmax``, where ``fmax`` is the
    largest field value seen so far (a first batch of 4096 uniform points, then every
    batch), so a field that is small everywhere still samples efficiently. A peak narrower
    than that sampling can find is flattened to the largest value seen.
    """
    geom = as_region(boundary)
    n = _count(count)
    if not callable(field):
        raise ValueError("field must be a callable field(xy) -> values in [0, 1]")
    rng = np.random.default_rng(seed)
    if n == 0:
        return np.zeros((0, 2))
    probe = _uniform(geom, 4096, rng)
    fmax = float(_field_values(field, probe).max())
    if fmax <= 0.0:
        raise ValueError("field is zero everywhere in the boundary: no density to sample")
    out = []
    have = drawn = 0
    for _ in range(_MAX_ROUNDS):
        if have >= n:
            break
        m = next_batch(max(256, int((n - have) * 1.5)), n - have, drawn, have)
        xy = _uniform(geom, m, rng)
        values = _field_values(field, xy)
        keep = rng.uniform(0.0, fmax, size=m) < values
        fmax = max(fmax, float(values.max()))  # a higher peak seen: accept less from now on
        out.append(xy[keep])
        have += int(keep.sum())
        drawn += m
    else:
        raise ValueError("field is too small over the boundary to place the points")
    return np.ascontiguousarray(np.concatenate(out)[:n])


def from_file(path) -> np.ndarray:
    """Read seed points from ``.csv``/``.txt``/``.npy``/``.geojson`` (``io.read_points``).

    Returns
    -------
    (n, 2) float64
    """
    from ..io.readers import read_points

    return read_points(path)


def _as_lines(curves) -> list:
    """Curves as a list of shapely LineStrings (polylines, LineStrings or MultiLineStrings)."""
    if isinstance(curves, shapely.Geometry):
        parts = list(shapely.get_parts(curves))
    else:
        parts = []
        for c in curves:
            if isinstance(c, shapely.Geometry):
                parts += list(shapely.get_parts(c))
                continue
            arr = np.asarray(c, dtype=np.float64)
            if arr.ndim != 2 or arr.shape[1] != 2 or len(arr) < 2:
                raise ValueError(f"a curve must be a (k >= 2, 2) polyline, got shape {arr.shape}")
            if not np.isfinite(arr).all():
                raise ValueError("curve coordinates must be finite")
            parts.append(shapely.LineString(arr))
    lines = []
    for g in parts:
        if g.geom_type == "LinearRing":
            g = shapely.LineString(g.coords)
        if g.geom_type != "LineString":
            raise ValueError(f"curves must be lines, got a {g.geom_type}")
        if g.length > 0:
            lines.append(g)
    if not lines:
        raise ValueError("no curve of positive length")
    return lines


def along_curves(boundary, curves, spacing, *, distance=None, radius=None, seed=0) -> np.ndarray:
    """Sites in mirrored pairs along curves, so that cell edges trace the curves.

    Each curve gets a site on either side every ``spacing`` along it, at ``distance`` from
    it along the normal: the two sites of a pair are mirror images, so the edge between
    their cells lies on the curve's tangent there, and their cells' edges follow the curve
    as a chain (veins in a leaf, a seam, a crease). A site closer than ``distance`` to
    another curve (near a junction) is left out, so curves that meet join in a small knot
    of cells. The rest of the boundary can be filled with Poisson-disk sites of ``radius``,
    none nearer to a curve than ``distance + radius / 2``.

    Parameters
    ----------
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        Where the sites go (sites outside are left out).
    curves : sequence of (k, 2) polylines, or shapely lines
        The curves to trace.
    spacing : float
        Distance between pairs along a curve (> 0).
    distance : float, optional
        Distance of each site from its curve (default ``spacing / 2``).
    radius : float, optional
        Poisson-disk spacing of the sites filling the rest (default: no fill).
    seed : int
        Random seed of the fill.

    Returns
    -------
    (n, 2) float64
        The pairs (curve by curve, in order along each curve), then the fill.

    Examples
    --------
    >>> import voroforge as vf
    >>> pts = along_curves((0, 0, 100, 50), [[(0, 25), (100, 25)]], 10.0, radius=10.0)
    >>> d = vf.voronoi(pts, (0, 0, 100, 50))
    >>> on_line = [bool(abs(c[:, 1] - 25).max() < 1e-9) for c in d.edges.coords]
    >>> sum(on_line) >= 9  # the cells meet along y = 25
    True
    """
    geom = as_region(boundary)
    step = _positive(spacing, "spacing")
    dist = step / 2.0 if distance is None else _positive(distance, "distance")
    lines = _as_lines(curves)
    pairs = []
    for k, line in enumerate(lines):
        n = max(1, int(round(line.length / step)))
        at = (np.arange(n) + 0.5) * (line.length / n)
        eps = min(step, line.length) * 1e-3
        ahead = shapely.get_coordinates(shapely.line_interpolate_point(line, at + eps))
        behind = shapely.get_coordinates(shapely.line_interpolate_point(line, at - eps))
        on = shapely.get_coordinates(shapely.line_interpolate_point(line, at))
        tangent = ahead - behind
        tangent /= np.hypot(tangent[:, 0], tangent[:, 1])[:, None]
        normal = np.column_stack((-tangent[:, 1], tangent[:, 0]))
        sides = np.vstack((on + dist * normal, on - dist * normal))
        if len(lines) > 1:  # a site in another curve's band would pull that curve's edges
            others = shapely.MultiLineString([g for j, g in enumerate(lines) if j != k])
            sides = sides[shapely.distance(others, shapely.points(sides)) >= dist * (1 - 1e-9)]
        pairs.append(sides)
    sites = np.vstack(pairs)
    sites = sites[_inside(geom, sites)]
    if radius is not None:
        fill = poisson(geom, radius, seed=seed)
        network = shapely.MultiLineString(lines)
        far = shapely.distance(network, shapely.points(fill)) >= dist + float(radius) / 2.0
        sites = np.vstack((sites, fill[far]))
    return np.ascontiguousarray(sites, dtype=np.float64)


def crossing_edges(diagram, curves) -> shapely.MultiLineString:
    """The edges of a diagram between two sites on opposite sides of a curve, merged.

    With sites from :func:`along_curves` these edges follow the curves as unbroken chains
    (where pairs were left out near junctions, the edges between the nearest sites on either
    side carry the chain through): the veins of a leaf, drawn from the cells' own edges.

    Parameters
    ----------
    diagram : Diagram
        A diagram (its ``sites`` and ``edges``).
    curves : sequence of polylines or shapely lines
        As for :func:`along_curves`.

    Returns
    -------
    shapely.MultiLineString
        The chains (``shapely.line_merge`` of the edges).
    """
    network = shapely.MultiLineString(_as_lines(curves))
    shapely.prepare(network)
    e = diagram.edges
    if not len(e.pairs):
        return shapely.MultiLineString()
    sites = np.asarray(diagram.sites, dtype=np.float64)
    links = shapely.linestrings(np.stack((sites[e.pairs[:, 0]], sites[e.pairs[:, 1]]), axis=1))
    cross = shapely.intersects(network, links)
    segs = shapely.linestrings(np.asarray(e.coords)[cross])
    merged = shapely.line_merge(shapely.MultiLineString(list(segs)))
    if merged.is_empty:  # no link crosses a curve (it runs along the outline or outside)
        return shapely.MultiLineString()
    return merged if merged.geom_type == "MultiLineString" else shapely.MultiLineString([merged])
