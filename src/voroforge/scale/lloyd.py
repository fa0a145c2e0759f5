"""Lloyd relaxation in tiles on dask.distributed: :func:`lloyd`, the tiled :func:`voroforge.lloyd`.

Every iteration is one tiled Voronoi pass with certified halos (as :func:`.voronoi`), but a
tile returns its sites' cell moments instead of writing cells: each site moves to its cell's
centroid. The sites stay on the workers between iterations. After each step every tile's
moved sites are split by the tile that now owns them and merged again (the halo exchange:
a tile reads its neighbours' moved sites for its halo), so only small summaries (energy,
largest move, recomputations) reach the driver until the end.

A cell's moments come from its cell alone, and a certified cell is the single-process cell,
so every step is that of :func:`voroforge.lloyd` on all sites; the sums over a cell's ring
may start at another vertex, which changes the centroid in its last bits (tested: within
1e-12 of the domain's size after several iterations).
"""

from __future__ import annotations

import math
import operator
import time
from dataclasses import dataclass, field

import numpy as np

from .. import config
from .job import check_counts, client_for, first_halo, tile_count
from .tasks import (
    Piece,
    certified_sites,
    gather_sites,
    group_discs,
    limit_threads,
    open_sides,
    radii,
    split_by_tile,
    take,
)
from .tiling import kd_tiling

__all__ = ["ScaleRelaxation", "lloyd"]


@dataclass
class ScaleRelaxation:
    """What :func:`lloyd` returns.

    Attributes
    ----------
    points : (n, 2) float64
        The relaxed sites, in input order.
    energy : (iterations + 1,) float64
        The CVT energy (sum of the cells' second moments about their sites) before each step
        and after the last.
    shift : (iterations,) float64
        The largest move of a site in each step.
    iterations : int
        Steps made.
    tiles, workers : int
        Tiles per iteration; workers of the cluster.
    retried : int
        Cells recomputed with a grown halo, over all iterations.
    uncertified : int
        Cells whose certificate never held (0 in every run so far; their moments are used
        as computed).
    seconds : float
        Wall time of the call.
    """

    points: np.ndarray
    energy: np.ndarray
    shift: np.ndarray
    iterations: int
    tiles: int
    workers: int
    retried: int = 0
    uncertified: int = 0
    seconds: float = 0.0
    per_iteration: list = field(default_factory=list)


def _moments(ids, xy, dom, loaded, wanted, last):
    """Moments of the ``wanted`` cells among ``xy``; the uncertified ones as pending."""
    from ..engine.diagram import buffers
    from ..engine.inputs import as_points
    from ..engine.integrate import Integrator
    from ..engine.planar import build

    d = build(as_points(xy), dom, "delaunay")
    mass, first, second = Integrator(None, len(xy))(buffers(d), xy)
    r = radii(d, xy)
    ok = certified_sites(xy[wanted], r[wanted], loaded)
    if last:
        ok[:] = True
    keep = wanted[ok]
    bad = wanted[~ok]
    done = (ids[keep], xy[keep], mass[keep].copy(), first[keep].copy(), second[keep].copy())
    return done, (ids[bad], xy[bad], r[bad])


def _step_piece(done, dom):
    """The moved sites of a tile's certified cells (sorted by id) and their summary.

    A site outside the domain whose cell is empty moves to the domain's nearest point, as in
    :func:`voroforge.lloyd` (:func:`~voroforge.engine.lloyd.empty_into_domain`).
    """
    from ..engine.lloyd import empty_into_domain

    if not done:
        return Piece(np.zeros(0, np.int64), np.zeros((0, 2)), None), 0.0, 0.0
    ids, xy, mass, first, second = (np.concatenate(a) for a in zip(*done, strict=True))
    order = np.argsort(ids, kind="stable")
    ids, xy, mass, first, second = ids[order], xy[order], mass[order], first[order], second[order]
    inv = np.divide(1.0, mass, out=np.zeros_like(mass), where=mass > 0.0)
    move = first * inv[:, None]
    new = xy + move
    shift = float(np.sqrt(np.einsum("ij,ij->i", move, move).max())) if len(ids) else 0.0
    shift = max(shift, empty_into_domain(new, ~(mass > 0.0), dom))
    return Piece(ids, np.ascontiguousarray(new), None), float(second.sum()), shift


def lloyd_tile(t, spec, tiling, own, *neighbours):
    """One Lloyd step of tile ``t``: certified moments, grown halos for the others.

    ``neighbours`` are the owned sites of the tiles ``spec["held"][1:]``. A cell whose
    certificate fails is recomputed here only when every tile its grown box reaches is held
    (then the box holds all the sites in it); the others are escalated to the driver, which
    recomputes them with the sites of every tile their boxes reach (:func:`lloyd_box`).

    Returns ``(summary, Piece of the moved certified sites, escalated (ids, xy, r))``; the
    summary is a small dict.
    """
    t0 = time.perf_counter()
    pieces = [own, *neighbours]
    held = {int(u) for u in spec["held"]}
    done = []
    retried = 0
    uncertified = 0
    escalated = ([], [], [])
    with limit_threads():
        ids, xy = gather_sites(pieces, spec["loaded"])
        wanted = np.flatnonzero(np.isin(ids, own.ids, assume_unique=True))
        loaded = open_sides(spec["loaded"], spec["lo"], spec["hi"])
        part, pending = _moments(ids, xy, spec["domain"], loaded, wanted, False)
        done.append(part)
        rounds = 0
        while len(pending[0]):
            rounds += 1
            retried += len(pending[0])
            last = rounds >= spec["max_rounds"]
            ids_u, xy_u, r_u = pending
            boxes, member = group_discs(xy_u, r_u)
            left = ([], [], [])
            for g, box in enumerate(boxes):
                group = member == g
                if not held.issuperset(int(u) for u in tiling.touching(box)):
                    # the box reaches sites this task never loaded (checker19 F3)
                    for acc, new in zip(escalated, pending, strict=True):
                        acc.append(new[group])
                    continue
                part, more = _box_moments(spec, box, ids_u[group], last, pieces)
                done.append(part)
                for acc, new in zip(left, more, strict=True):
                    acc.append(new)
            pending = _cat(left)
            if last:
                uncertified += len(pending[0])
                break
    escalated = _cat(escalated)
    piece, energy, shift = _step_piece(done, spec["domain"])
    if len(piece.ids) + len(escalated[0]) != len(own.ids):
        raise RuntimeError(f"tile {t}: moments do not match the tile's sites")  # a bug
    summary = {
        "tile": t,
        "energy": energy,
        "shift": shift,
        "retried": retried,
        "uncertified": uncertified,
        "escalated": len(escalated[0]),
        "seconds": time.perf_counter() - t0,
    }
    return summary, piece, escalated


def _cat(parts):
    """``(ids, xy, r)`` lists concatenated (empty arrays for none)."""
    ids, xy, r = parts
    if not ids:
        return np.zeros(0, np.int64), np.zeros((0, 2)), np.zeros(0)
    return np.concatenate(ids), np.concatenate(xy), np.concatenate(r)


def lloyd_box(spec, box, ids_u, last, *pieces):
    """Moments of the cells ``ids_u`` recomputed in ``box`` from ``pieces``.

    ``pieces`` are the owned sites of every tile that ``box`` reaches, so the box holds all
    the sites in it and certifies the cells whose discs it contains. Returns ``(summary,
    Piece of the moved certified sites, still uncertified (ids, xy, r))``.
    """
    with limit_threads():
        part, more = _box_moments(spec, box, ids_u, last, pieces)
    if len(part[0]) + len(more[0]) != len(ids_u):
        raise RuntimeError("a recomputation box misses its own sites")  # a bug
    piece, energy, shift = _step_piece([part], spec["domain"])
    return {"energy": energy, "shift": shift, "n": len(piece.ids)}, piece, more


def _box_moments(spec, box, ids_u, last, pieces):
    """:func:`_moments` of the cells ``ids_u`` in ``box``, from the sites of ``pieces`` in it."""
    ids_b, xy_b = gather_sites(pieces, box)
    wanted = np.flatnonzero(np.isin(ids_b, ids_u, assume_unique=True))
    loaded = open_sides(box, spec["lo"], spec["hi"])
    return _moments(ids_b, xy_b, spec["domain"], loaded, wanted, last)


def _escalations(cl, tiling, spec, owned, pending):
    """Recompute the escalated cells ``pending`` with every tile their boxes reach.

    Returns ``(energy, shift, retried, uncertified, futures of moved Pieces)``.
    """
    energy = shift = 0.0
    retried = uncertified = rounds = 0
    moved = []
    while len(pending[0]):
        rounds += 1
        retried += len(pending[0])
        last = rounds >= spec["max_rounds"]
        ids_u, xy_u, r_u = pending
        boxes, member = group_discs(xy_u, r_u)
        futures = []
        for g, box in enumerate(boxes):
            reach = [owned[int(u)] for u in tiling.touching(box)]
            box_t = tuple(float(v) for v in box)
            futures.append(cl.submit(lloyd_box, spec, box_t, ids_u[member == g], last, *reach))
        summaries = cl.gather([cl.submit(operator.getitem, f, 0) for f in futures])
        left = cl.gather([cl.submit(operator.getitem, f, 2) for f in futures])
        moved += [cl.submit(operator.getitem, f, 1) for f in futures]
        energy += float(sum(s["energy"] for s in summaries))
        shift = max([shift, *(s["shift"] for s in summaries)])
        pending = _cat(tuple(list(a) for a in zip(*left, strict=True)))
        if last:
            uncertified += len(pending[0])
            break
    return energy, shift, retried, uncertified, moved


def split_piece(piece, tiling):
    """``(counts (t,), pieces)``: a tile's moved sites split by the tile owning them now."""
    return split_by_tile(piece.ids, piece.xy, None, tiling)


def merge_sorted(*pieces):
    """One tile's sites from pieces of several tiles, sorted by input row."""
    pieces = [p for p in pieces if p is not None]
    if not pieces:
        return Piece(np.zeros(0, np.int64), np.zeros((0, 2)), None)
    ids = np.concatenate([p.ids for p in pieces])
    xy = np.concatenate([p.xy for p in pieces])
    order = np.argsort(ids, kind="stable")
    return Piece(ids[order], np.ascontiguousarray(xy[order]), None)


def lloyd(
    points,
    boundary=None,
    *,
    iterations: int = 10,
    tiles: int | None = None,
    tile_size: int | None = None,
    client=None,
    workers: int | None = None,
    progress=None,
) -> ScaleRelaxation:
    """Lloyd relaxation of many sites in tiles on dask.distributed.

    Each step is that of :func:`voroforge.lloyd` (uniform density): every site moves to the
    centroid of its Voronoi cell in the domain (a site outside with an empty cell moves to
    the domain's nearest point; a duplicate inside waits a step). The cells
    are computed in tiles with certified halos (see :func:`voronoi`); between steps each
    tile's moved sites go to the tiles that own them now, on the workers.

    Parameters
    ----------
    points : (n, 2) array_like or dask array
        Starting sites; never modified.
    boundary : None, (xmin, ymin, xmax, ymax) or shapely Polygon/MultiPolygon
        The domain, as for :func:`voroforge.lloyd` (None: the sites' box padded by 10%).
    iterations : int
        Lloyd steps (>= 0).
    tiles, tile_size : int, optional
        Number of tiles, or sites per tile (default as for :func:`voronoi`).
    client : distributed.Client, optional
        Default: the current client, else a LocalCluster started for the call.
    workers : int, optional
        Workers of the LocalCluster started when there is no client.
    progress : callable, optional
        ``progress(done, total)`` after every iteration.

    Returns
    -------
    ScaleRelaxation

    Raises
    ------
    ValueError
        Bad points (shape, non-finite rows with their row numbers), a bad boundary, a
        negative ``iterations``.

    Examples
    --------
    >>> import numpy as np
    >>> from voroforge import scale
    >>> pts = np.random.default_rng(0).random((100_000, 2))
    >>> r = scale.lloyd(pts, (0, 0, 1, 1), iterations=5)  # doctest: +SKIP
    >>> bool(np.all(np.diff(r.energy) <= 0))  # doctest: +SKIP
    True
    """
    from ..engine.domain import make_domain
    from ..engine.inputs import as_points
    from ..engine.lloyd import cell_domain, size_exponent

    t_start = time.perf_counter()
    tiles, tile_size, workers, _ = check_counts(tiles, tile_size, workers)
    try:
        steps = -1 if isinstance(iterations, bool) else operator.index(iterations)
    except TypeError:
        steps = -1
    if steps < 0:
        raise ValueError(f"iterations must be a whole number >= 0; got {iterations!r}")
    iterations = steps
    if hasattr(points, "compute") and hasattr(points, "chunks"):
        points = points.compute()  # a dask array: the driver validates it once
    z = as_points(points)
    if len(z) == 0:
        raise ValueError("no points: the input has no rows")
    dom = make_domain(boundary, z)
    k = size_exponent(dom)
    if k:  # relax scaled by a power of two (exact), as voroforge.lloyd does
        scaled = dom.scaled(k)
        res = lloyd(
            np.ldexp(z, k),
            scaled.bounds if scaled.is_rect else scaled.geometry,
            iterations=iterations,
            tiles=tiles,
            tile_size=tile_size,
            client=client,
            workers=workers,
            progress=progress,
        )
        res.points = np.ldexp(res.points, -k)
        with np.errstate(over="ignore", under="ignore"):
            res.energy = np.ldexp(res.energy, -4 * k)
        res.shift = np.ldexp(res.shift, -k)
        return res
    cell_dom = cell_domain(dom)
    x0, y0, x1, y1 = dom.bounds
    # sites move inside the domain's box (a centroid lies in its cell), so the tiles'
    # outer sides are open: a site never leaves every tile
    lo = np.minimum(z.min(axis=0), [x0, y0])
    hi = np.maximum(z.max(axis=0), [x1, y1])
    rng = np.random.default_rng(0)
    sample = z[rng.choice(len(z), size=min(len(z), config.SCALE_SAMPLE_SITES), replace=False)]
    with client_for(client, workers) as cl:
        nworkers = max(1, len(cl.scheduler_info(n_workers=-1)["workers"]))
        tiling = kd_tiling(sample, tile_count(len(z), tiles, tile_size, nworkers))
        ntiles = len(tiling)
        chunk = max(1, math.ceil(len(z) / max(ntiles, 1)))
        ids = np.arange(len(z), dtype=np.int64)
        current = [
            cl.scatter(
                Piece(ids[s : s + chunk], np.ascontiguousarray(z[s : s + chunk])), hash=False
            )
            for s in range(0, len(z), chunk)
        ]
        energy, shifts, per_iter = [], [], []
        retried = uncertified = 0
        for it in range(iterations + 1):
            splits = [cl.submit(split_piece, p, tiling) for p in current]
            counts = np.array(cl.gather([cl.submit(operator.getitem, s, 0) for s in splits]))
            per_tile = counts.sum(axis=0)
            owned = []
            for t in range(ntiles):
                parts = [cl.submit(take, s, t) for c, s in enumerate(splits) if counts[c, t]]
                owned.append(cl.submit(merge_sorted, *parts))
            results = []
            for t in range(ntiles):
                h = first_halo(tiling.rects[t], per_tile[t], lo, hi)
                rect = tiling.rects[t]
                spec = {
                    "loaded": (rect[0] - h, rect[1] - h, rect[2] + h, rect[3] + h),
                    "lo": lo.tolist(),
                    "hi": hi.tolist(),
                    "domain": cell_dom,
                    "max_rounds": config.SCALE_MAX_ROUNDS,
                }
                near = [int(u) for u in tiling.touching(spec["loaded"]) if u != t]
                spec["held"] = [t, *near]
                results.append(
                    cl.submit(lloyd_tile, t, spec, tiling, owned[t], *[owned[u] for u in near])
                )
            summaries = cl.gather([cl.submit(operator.getitem, r, 0) for r in results])
            up = [r for r, s in zip(results, summaries, strict=True) if s["escalated"]]
            esc = cl.gather([cl.submit(operator.getitem, r, 2) for r in up])
            pending = _cat(tuple(list(a) for a in zip(*esc, strict=True)) if esc else ([],) * 3)
            e_energy, e_shift, e_retried, e_unc, moved = _escalations(
                cl, tiling, {**spec, "held": None}, owned, pending
            )
            energy.append(float(sum(s["energy"] for s in summaries)) + e_energy)
            # an escalated cell was counted once by its tile: count the driver's rounds past it
            step_retried = int(sum(s["retried"] for s in summaries)) + e_retried - len(pending[0])
            retried += step_retried
            uncertified += int(sum(s["uncertified"] for s in summaries)) + e_unc
            per_iter.append(
                {"retried": step_retried, "seconds": max(s["seconds"] for s in summaries)}
            )
            if it == iterations:
                # the moved pieces of the last pass are not a step: keep the sites
                break
            shifts.append(max(float(max(s["shift"] for s in summaries)), e_shift))
            current = [cl.submit(operator.getitem, r, 1) for r in results] + moved
            if progress is not None:
                progress(it + 1, iterations)
        final = cl.gather(owned)
    out = np.zeros_like(z)
    for p in final:
        out[p.ids] = p.xy
    return ScaleRelaxation(
        points=out,
        energy=np.array(energy),
        shift=np.array(shifts),
        iterations=iterations,
        tiles=ntiles,
        workers=nworkers,
        retried=retried,
        uncertified=uncertified,
        seconds=time.perf_counter() - t_start,
        per_iteration=per_iter,
    )
