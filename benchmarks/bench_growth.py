"""Growth of the three 2D algorithms on the inputs that were quadratic (issue 15).

Families (``--families``, all by default):

``collinear``
    ``n`` sites evenly spaced on ``y = 0`` in ``[0, 1]`` and one site at ``(0.5, 0.1)``, box
    ``(-0.5, -0.5, 1.5, 1.5)``: the off-line cell has ``n`` neighbours.
``sloped``
    ``n`` sites evenly spaced on ``y = 0.5 x`` for ``x`` in ``[0, 1]`` and one site at
    ``(0.2, 0.9)``, box ``(-1, -1, 2, 2)`` (the independent check's input: the k-d buckets'
    axis-aligned boxes are as wide across a sloped line as along it, which cost
    ``O(sqrt n)`` buckets per cell until each bucket kept its sites' oriented bounds).
``sloped_flat``
    As ``sloped`` on ``y = 0.001 x`` (nearly horizontal: a k-d node's oriented bounds are
    what keeps it flat, not its axis-aligned box).
``sloped_float``
    ``n`` sites at random ``x`` in ``[0, 1000]`` on ``y = 0.3 x + 100`` (rounded: the line is
    straight only to rounding, and random draws put sites a few ulps apart) and one site
    off it, default box: the off-line ring folds where close sites round its vertices
    across each other (the fold test once read the whole ring for every reach it tried).
``comb``
    A polygon domain, a comb of ``n`` teeth (0.6 wide, 1000 high, on a strip 1 high: an
    outline of ``4 n`` vertices meeting every cell), with 4,000 random sites in its box:
    here ``n`` is the boundary's size, not the sites' (only when named: ``--families comb
    --sizes 500,1000,2000``).
``collinear_others``
    ``n`` sites on one line plus ``n / 100`` random ones in the unit box (the README's
    "100,000 on a line plus 1,000 others").
``clustered``
    Three tight Gaussian clusters (sd 1e-3) in a 10 x 9 domain.
``circle``
    ``n`` float sites on the unit circle (cocircular up to rounding), default domain.
``circle_mostly``
    ``0.9 n`` sites on the unit circle and ``0.1 n`` uniform in the unit disc.

``vf.voronoi(p, box, algorithm=a)`` for ``a`` in ``delaunay``, ``fortune``, ``halfplane``,
best of ``--repeat`` wall-clock runs (process CPU with ``--cpu``), the algorithms alternated
within each repeat; a case that took longer than ``--cutoff`` seconds is not run at the next
size. Prints the seconds, the ratio to the default at the same size and the growth exponent
(slope of log t against log n over the sizes measured: n log n shows as about 1.1, n^2 as 2).

Run ``python benchmarks/bench_growth.py --help`` for the options.
"""

from __future__ import annotations

import argparse
import gc
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import voroforge as vf  # noqa: E402

from common import command_line, fmt_ratio, fmt_seconds, machine_info, parse_sizes, print_table  # noqa: E402

ALGORITHMS = ("delaunay", "fortune", "halfplane")


def collinear(n: int):
    x = np.linspace(0.0, 1.0, n)
    pts = np.concatenate((np.column_stack((x, np.zeros(n))), [[0.5, 0.1]]))
    return pts, (-0.5, -0.5, 1.5, 1.5)


def sloped(n: int):
    t = np.linspace(0.0, 1.0, n)
    pts = np.concatenate((np.column_stack((t, 0.5 * t)), [[0.2, 0.9]]))
    return pts, (-1.0, -1.0, 2.0, 2.0)


def sloped_flat(n: int):
    t = np.linspace(0.0, 1.0, n)
    pts = np.concatenate((np.column_stack((t, 1e-3 * t)), [[0.2, 0.9]]))
    return pts, (-1.0, -1.0, 2.0, 2.0)


def sloped_float(n: int):
    x = np.random.default_rng(1).random(n) * 1000.0
    pts = np.concatenate((np.column_stack((x, 0.3 * x + 100.0)), [[500.0, 619.8]]))
    return pts, None


def comb(n: int):
    import shapely

    teeth = []
    for i in range(n):
        teeth += [(i, 1000.0), (i + 0.6, 1000.0), (i + 0.6, 1.0), (i + 1, 1.0)]
    geom = shapely.Polygon([(0, 0), (n, 0), *teeth[::-1]])
    pts = np.random.default_rng(5).random((4000, 2)) * [n, 1000.0]
    return pts, geom


def collinear_others(n: int):
    x = np.linspace(0.0, 1.0, n)
    others = np.random.default_rng(1).random((max(n // 100, 1), 2))
    return np.concatenate((np.column_stack((x, np.full(n, 0.5))), others)), (0.0, 0.0, 1.0, 1.0)


def clustered(n: int):
    g = np.random.default_rng(2)
    centres = np.array([[2.0, 2.0], [7.5, 3.0], [4.5, 7.0]])
    pts = centres[g.integers(0, 3, n)] + g.normal(0.0, 1e-3, (n, 2))
    return pts, (0.0, 0.0, 10.0, 9.0)


def circle(n: int):
    t = np.arange(n) * (2.0 * np.pi / n)
    return np.column_stack((np.cos(t), np.sin(t))), None


def circle_mostly(n: int):
    g = np.random.default_rng(3)
    m = n - n // 10
    t = np.arange(m) * (2.0 * np.pi / m)
    r = np.sqrt(g.random(n - m))
    a = g.random(n - m) * 2.0 * np.pi
    inner = np.column_stack((r * np.cos(a), r * np.sin(a)))
    return np.concatenate((np.column_stack((np.cos(t), np.sin(t))), inner)), None


FAMILIES = {
    "collinear": collinear,
    "sloped": sloped,
    "sloped_flat": sloped_flat,
    "sloped_float": sloped_float,
    "comb": comb,
    "collinear_others": collinear_others,
    "clustered": clustered,
    "circle": circle,
    "circle_mostly": circle_mostly,
}


def growth_exponent(sizes: list[int], times: list[float]) -> float:
    """Least-squares slope of ``log t`` against ``log n`` (NaN below two sizes)."""
    ok = [(n, t) for n, t in zip(sizes, times, strict=True) if t is not None and math.isfinite(t)]
    if len(ok) < 2:
        return math.nan
    n, t = np.array(ok).T
    return float(np.polyfit(np.log(n), np.log(t), 1)[0])


def run_family(name: str, sizes: list[int], algorithms, repeat: int, cutoff: float, cpu=False):
    make = FAMILIES[name]
    warm, wbox = make(200)
    for alg in algorithms:  # compile or load numba's cache outside the timings
        vf.voronoi(warm, wbox, algorithm=alg)
    times: dict[str, list[float | None]] = {alg: [] for alg in algorithms}
    live = set(algorithms)
    for n in sizes:
        pts, box = make(n)
        best = dict.fromkeys(algorithms, math.inf)
        for _ in range(repeat):
            for alg in algorithms:
                if alg not in live:
                    continue
                gc.collect()
                clock = time.process_time if cpu else time.perf_counter
                t0 = clock()
                vf.voronoi(pts, box, algorithm=alg)
                best[alg] = min(best[alg], clock() - t0)
        for alg in algorithms:
            if alg in live:
                times[alg].append(best[alg])
                if best[alg] > cutoff:
                    live.discard(alg)
            else:
                times[alg].append(None)
        done = ", ".join(f"{a} {fmt_seconds(times[a][-1])}" for a in algorithms)
        print(f"  {name} n={n}: {done}", flush=True)
    return times


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default="1e4,1e5,1e6", help="comma-separated sizes")
    every = ",".join(f for f in FAMILIES if f != "comb")  # (comb: boundary sizes, on request)
    ap.add_argument("--families", default=every, help="comma-separated families")
    ap.add_argument("--algorithms", default=",".join(ALGORITHMS))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cutoff", type=float, default=60.0, help="skip larger sizes past this")
    ap.add_argument("--cpu", action="store_true", help="time process CPU (all threads), not wall")
    args = ap.parse_args(argv)
    sizes = parse_sizes(args.sizes)
    algorithms = [a for a in args.algorithms.split(",") if a]
    print(command_line())
    print(machine_info())
    for name in args.families.split(","):
        times = run_family(name, sizes, algorithms, args.repeat, args.cutoff, args.cpu)
        rows = []
        for alg in algorithms:
            ts = times[alg]
            row = [alg] + [fmt_seconds(t) for t in ts]
            row += [fmt_ratio(t, d) for t, d in zip(ts, times.get("delaunay", ts), strict=True)]
            row.append(f"{growth_exponent(sizes, ts):.2f}")
            rows.append(row)
        headers = ["algorithm"] + [f"n={n}" for n in sizes] + [f"x{n}" for n in sizes] + ["slope"]
        print_table(headers, rows, title=f"{name} (seconds, ratio to delaunay, growth slope)")


if __name__ == "__main__":
    main()
