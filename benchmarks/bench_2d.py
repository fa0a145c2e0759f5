"""Side-by-side timings of voroforge's 2D engine against the usual references.

Delaunay
    ``vf.delaunay(p)`` vs Shewchuk's Triangle (``triangle.triangulate``) vs
    ``scipy.spatial.Delaunay`` (Qhull).
Voronoi clipped to the unit square (all cells as shapely geometries)
    ``vf.voronoi(p, (0, 0, 1, 1))`` (construction, and construction + ``d.cells``) vs
    (a) shapely/GEOS ``voronoi_polygons(..., extend_to=box)`` + ``intersection`` and
    (b) ``scipy.spatial.Voronoi`` + reconstruction of the unbounded regions + shapely
    polygons + ``intersection``.
Voronoi clipped to a polygon with holes
    ``vf.voronoi(p, polygon_with_holes())``, and its cost relative to the rectangle.

Everything runs in one process, on the same fixed-seed inputs, best of ``--repeat``.
Run ``python benchmarks/bench_2d.py --help`` for the options.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import (  # noqa: E402
    DISTRIBUTIONS,
    best_of,
    command_line,
    fmt_ratio,
    fmt_seconds,
    machine_info,
    parse_sizes,
    polygon_with_holes,
    print_table,
    uniform,
)

BOX = (0.0, 0.0, 1.0, 1.0)
SKIP = float("nan")  # marks a measurement left out by --skip-slow


# --------------------------------------------------------------------------------------
# references
# --------------------------------------------------------------------------------------


def triangle_delaunay(p: np.ndarray) -> np.ndarray:
    """Delaunay triangles from Shewchuk's Triangle.

    The Python wrapper always prepends ``Qz`` (quiet, zero-based indices) to the switches;
    with no ``p``/``q``/``a``/``c`` switch Triangle only triangulates the vertices (the
    Delaunay triangulation of their convex hull, divide-and-conquer, exact predicates).
    """
    import triangle

    return triangle.triangulate({"vertices": p}, "")["triangles"]


def qhull_delaunay(p: np.ndarray) -> np.ndarray:
    """Delaunay triangles from ``scipy.spatial.Delaunay`` (Qhull, default options)."""
    from scipy.spatial import Delaunay

    return Delaunay(p).simplices


def shapely_voronoi(p: np.ndarray, box) -> np.ndarray:
    """GEOS Voronoi cells clipped to ``box``: the two shapely calls (cells in GEOS order)."""
    import shapely

    parts = shapely.get_parts(
        shapely.voronoi_polygons(shapely.multipoints(p), extend_to=box, ordered=False)
    )
    return shapely.intersection(parts, box)


def shapely_voronoi_ordered(p: np.ndarray, box) -> np.ndarray:
    """As :func:`shapely_voronoi`, but cells in input order (GEOS >= 3.12; used for checks)."""
    import shapely

    parts = shapely.get_parts(
        shapely.voronoi_polygons(shapely.multipoints(p), extend_to=box, ordered=True)
    )
    return shapely.intersection(parts, box)


def finite_voronoi_regions(vor, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Close scipy's unbounded Voronoi regions with far points; one ring per input point.

    Each ridge that runs to infinity (one vertex ``-1``) is replaced by a far point at
    ``radius`` from its finite vertex along the outward normal of the two sites. The
    vertices of each region are then sorted by angle around its site (cells are convex and
    contain their site). Returns closed rings as flat ``coords`` and ``offsets`` (ring
    ``i`` is ``coords[offsets[i]:offsets[i + 1]]``; empty for sites without a region,
    e.g. duplicates).
    """
    points = vor.points
    vertices = vor.vertices
    centre = points.mean(axis=0)

    # unbounded ridges of each site: (other site, finite vertex)
    open_ridges: dict[int, list[tuple[int, int]]] = {}
    for (p1, p2), (v1, v2) in zip(vor.ridge_points.tolist(), vor.ridge_vertices, strict=True):
        if v1 >= 0 and v2 >= 0:
            continue
        v = v2 if v1 < 0 else v1
        open_ridges.setdefault(p1, []).append((p2, v))
        open_ridges.setdefault(p2, []).append((p1, v))

    rings: list[np.ndarray] = []
    regions = vor.regions
    for i, region_index in enumerate(vor.point_region.tolist()):
        region = regions[region_index]
        if not region:
            rings.append(np.zeros((0, 2)))
            continue
        if -1 not in region:
            ring = vertices[region]
        else:
            pts = [vertices[v] for v in region if v >= 0]
            for j, v in open_ridges.get(i, ()):
                t = points[j] - points[i]
                normal = np.array([-t[1], t[0]]) / math.hypot(t[0], t[1])
                midpoint = 0.5 * (points[i] + points[j])
                if np.dot(midpoint - centre, normal) < 0:
                    normal = -normal
                pts.append(vertices[v] + radius * normal)
            ring = np.asarray(pts)
            d = ring - points[i]
            ring = ring[np.argsort(np.arctan2(d[:, 1], d[:, 0]))]
        rings.append(np.concatenate((ring, ring[:1])))
    lengths = np.fromiter((len(r) for r in rings), dtype=np.int64, count=len(rings))
    offsets = np.zeros(len(rings) + 1, dtype=np.int64)
    np.cumsum(lengths, out=offsets[1:])
    coords = np.concatenate(rings) if rings else np.zeros((0, 2))
    return coords, offsets


def scipy_voronoi(p: np.ndarray, box) -> np.ndarray:
    """The common recipe: scipy Voronoi, finite regions, shapely polygons, clip to ``box``."""
    import shapely
    from scipy.spatial import Voronoi

    vor = Voronoi(p)
    xmin, ymin, xmax, ymax = box
    extent = max(np.ptp(p, axis=0).max(), xmax - xmin, ymax - ymin)
    coords, offsets = finite_voronoi_regions(vor, radius=100.0 * extent)
    # empty rings -> polygons without a ring (POLYGON EMPTY)
    nonempty = np.diff(offsets) > 0
    ring_offsets = offsets[np.r_[True, nonempty]]
    geom_offsets = np.zeros(len(p) + 1, dtype=np.int64)
    np.cumsum(nonempty, out=geom_offsets[1:])
    polys = shapely.from_ragged_array(
        shapely.GeometryType.POLYGON, coords, (ring_offsets, geom_offsets)
    )
    return shapely.intersection(polys, shapely.box(*box))


# --------------------------------------------------------------------------------------
# voroforge (optional: the script still runs the references when the engine is missing)
# --------------------------------------------------------------------------------------


def load_vf():
    """``voroforge`` module, or None when it cannot be imported."""
    try:
        import voroforge as vf
    except ImportError as exc:
        print(f"voroforge not importable ({exc}); timing the references only")
        return None
    return vf


def warm_up(vf, holes) -> dict[str, bool]:
    """Compile (or load from cache) every numba kernel and import the references.

    Returns which voroforge entry points work (``delaunay``, ``rect``, ``holes``); one
    that is missing or raises on 100 points is reported and left out of the tables.
    """
    p = uniform(100, seed=1)
    works = {"delaunay": False, "rect": False, "holes": False}
    calls = {
        "delaunay": lambda: vf.delaunay(p),
        "rect": lambda: vf.voronoi(p, BOX).cells,
        "holes": lambda: vf.voronoi(p, holes).cells,
    }
    t0 = time.perf_counter()
    for name, call in calls.items():
        if vf is None:
            continue
        try:
            call()
            works[name] = True
        except Exception as exc:  # an engine still being built: time what works
            print(f"voroforge {name} unavailable: {type(exc).__name__}: {exc}")
    t1 = time.perf_counter()
    triangle_delaunay(p)
    qhull_delaunay(p)
    shapely_voronoi(p, _box())
    scipy_voronoi(p, BOX)
    print(f"warm-up (numba compile or cache load, 100 points): {t1 - t0:.2f} s")
    return works


def _box():
    import shapely

    return shapely.box(*BOX)


# --------------------------------------------------------------------------------------
# runner
# --------------------------------------------------------------------------------------


class Timer:
    """Best-of timing with ``--skip-slow`` extrapolation for the references."""

    def __init__(self, repeat: int, skip_slow: bool, limit: float = 20.0):
        self.repeat = repeat
        self.skip_slow = skip_slow
        self.limit = limit
        self.last: dict[tuple[str, str], tuple[int, float]] = {}

    def estimate(self, key: tuple[str, str], n: int, make, fn) -> float:
        """Predicted seconds of one call at size ``n`` (n log n from the last measured size)."""
        if key not in self.last:
            if n < 100_000:
                return 0.0
            m = n // 10  # probe once at a tenth of the size
            p = make(m)
            t0 = time.perf_counter()
            fn(p)
            self.last[key] = (m, time.perf_counter() - t0)
        m, t = self.last[key]
        return t * (n / m) * math.log(n) / math.log(max(m, 2))

    def time(self, key: tuple[str, str], p: np.ndarray, make, fn, reference: bool) -> float:
        """Best-of seconds of ``fn(p)``, or NaN when skipped as slow."""
        n = len(p)
        if reference and self.skip_slow:
            est = self.estimate(key, n, make, fn)
            if est > self.limit:
                print(f"  {key[0]:<22} {key[1]:<9} n={n:<9} skipped (estimated {est:.0f} s)")
                return SKIP
        t = best_of(lambda: fn(p), self.repeat)
        self.last[key] = (n, t)
        print(f"  {key[0]:<22} {key[1]:<9} n={n:<9} {fmt_seconds(t):>7} s")
        sys.stdout.flush()
        return t


def bench_delaunay(timer: Timer, dist: str, sizes: list[int], vf, works: dict, check: bool):
    """Delaunay table for one distribution."""
    make = DISTRIBUTIONS[dist]
    rows = []
    for n in sizes:
        p = make(n)
        t_vf = (
            timer.time(("delaunay vf", dist), p, make, vf.delaunay, False)
            if works["delaunay"]
            else None
        )
        t_tr = timer.time(("delaunay triangle", dist), p, make, triangle_delaunay, True)
        t_qh = timer.time(("delaunay qhull", dist), p, make, qhull_delaunay, True)
        rows.append(
            [
                f"{len(p):,}",
                fmt_seconds(t_vf),
                fmt_seconds(t_tr),
                fmt_seconds(t_qh),
                fmt_ratio(t_vf, t_tr),
                fmt_ratio(t_vf, t_qh),
            ]
        )
        if check:
            counts = {"triangle": len(triangle_delaunay(p)), "qhull": len(qhull_delaunay(p))}
            if works["delaunay"]:
                counts["vf"] = len(vf.delaunay(p).triangles)
            print(f"  check: triangle counts {counts}")
    print_table(
        ["n", "vf s", "triangle s", "qhull s", "vf/triangle", "vf/qhull"],
        rows,
        title=f"Delaunay, {dist} (seconds, best of {timer.repeat}; ratio < 1: vf faster)",
    )


def _vf_cells(vf, p, boundary):
    d = vf.voronoi(p, boundary)
    return d.cells


def bench_voronoi(timer: Timer, dist: str, sizes: list[int], vf, works: dict, check: bool):
    """Voronoi table for one distribution (unit square, then the polygon with holes)."""
    import shapely

    make = DISTRIBUTIONS[dist]
    box = _box()
    holes = polygon_with_holes()
    rows = []
    for n in sizes:
        p = make(n)
        t_build = t_cells = t_hb = t_hc = None
        if works["rect"]:
            t_build = timer.time(("voronoi vf", dist), p, make, lambda q: vf.voronoi(q, BOX), False)
            t_cells = timer.time(
                ("voronoi vf +cells", dist), p, make, lambda q: _vf_cells(vf, q, BOX), False
            )
        t_sh = timer.time(
            ("voronoi shapely", dist), p, make, lambda q: shapely_voronoi(q, box), True
        )
        t_sc = timer.time(("voronoi scipy", dist), p, make, lambda q: scipy_voronoi(q, BOX), True)
        if works["holes"]:
            t_hb = timer.time(
                ("voronoi vf holes", dist), p, make, lambda q: vf.voronoi(q, holes), False
            )
            t_hc = timer.time(
                ("voronoi vf holes +cells", dist),
                p,
                make,
                lambda q: _vf_cells(vf, q, holes),
                False,
            )
        rows.append(
            [
                f"{len(p):,}",
                fmt_seconds(t_build),
                fmt_seconds(t_cells),
                fmt_seconds(t_sh),
                fmt_ratio(t_sh, t_cells),
                fmt_seconds(t_sc),
                fmt_ratio(t_sc, t_cells),
                fmt_seconds(t_hb),
                fmt_seconds(t_hc),
                fmt_ratio(t_hc, t_cells),
            ]
        )
        if check:
            _check_voronoi(vf, works, p, box, holes, shapely)
    print_table(
        [
            "n",
            "vf s",
            "vf+cells s",
            "shapely s",
            "shapely/vf",
            "scipy s",
            "scipy/vf",
            "holes s",
            "holes+cells s",
            "holes/rect",
        ],
        rows,
        title=(
            f"Voronoi clipped, {dist} (seconds, best of {timer.repeat}; "
            "ref/vf = speed-up of vf+cells; holes/rect = cost of the polygon with holes)"
        ),
    )


def _check_voronoi(vf, works: dict, p, box, holes, shapely) -> None:
    """Untimed agreement check: per-site cell areas of every method, in input order."""
    areas = {
        "shapely": shapely.area(shapely_voronoi_ordered(p, box)),
        "scipy": shapely.area(scipy_voronoi(p, BOX)),
    }
    if works["rect"]:
        areas["vf"] = shapely.area(vf.voronoi(p, BOX).cells)
    if works["holes"]:
        hole_area = shapely.area(vf.voronoi(p, holes).cells).sum()
        print(f"  check: holes domain area {holes.area:.12f}, sum of vf cells {hole_area:.12f}")
    ref = areas.get("vf", areas["shapely"])
    for name, a in areas.items():
        print(
            f"  check: {name:<8} sum of areas {a.sum():.12f}, "
            f"max |area - {'vf' if 'vf' in areas else 'shapely'}| {np.abs(a - ref).max():.2e}"
        )


def main(argv: list[str] | None = None) -> None:
    """Parse the options and run the selected benchmarks."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default="1e4,1e5,1e6", help="comma-separated point counts")
    ap.add_argument(
        "--dists",
        default="uniform,clustered,grid",
        help="comma-separated subset of: " + ", ".join(DISTRIBUTIONS),
    )
    ap.add_argument("--repeat", type=int, default=3, help="best of this many runs")
    ap.add_argument("--only", choices=["delaunay", "voronoi", "all"], default="all")
    ap.add_argument(
        "--skip-slow",
        action="store_true",
        help="skip a reference whose single run is estimated to take > 20 s",
    )
    ap.add_argument(
        "--check",
        action="store_true",
        help="also compare outputs (triangle counts, per-cell areas); untimed",
    )
    ap.add_argument("--no-vf", action="store_true", help="time the references only")
    args = ap.parse_args(argv)

    sizes = parse_sizes(args.sizes)
    dists = [d.strip() for d in args.dists.split(",") if d.strip()]
    unknown = [d for d in dists if d not in DISTRIBUTIONS]
    if unknown:
        ap.error(f"unknown distribution(s) {unknown}; choose from {list(DISTRIBUTIONS)}")

    print("command: " + command_line())
    print(machine_info())
    vf = None if args.no_vf else load_vf()
    works = warm_up(vf, polygon_with_holes())

    timer = Timer(args.repeat, args.skip_slow)
    t0 = time.perf_counter()
    for dist in dists:
        print(f"\n=== {dist} ===")
        if args.only in ("delaunay", "all"):
            bench_delaunay(timer, dist, sizes, vf, works, args.check)
        if args.only in ("voronoi", "all"):
            bench_voronoi(timer, dist, sizes, vf, works, args.check)
    print(f"\ntotal wall time {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
