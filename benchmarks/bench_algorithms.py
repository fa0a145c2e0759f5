"""Timings of the three 2D construction methods side by side, with their growth exponents.

``vf.voronoi(p, (0, 0, 1, 1), algorithm=a)`` (cells as buffers only, no shapely geometries)
for ``a`` in ``delaunay`` (the default), ``fortune`` and ``halfplane``, on fixed-seed uniform
points at each size; best of ``--repeat``, all in one process, the algorithms alternated
within each repeat so that load changes hit them alike. Prints each time, its ratio to the
default's time at the same size, and the growth exponent fitted over the sizes (slope of
log t against log n: n log n shows as about 1.1, n^2 as 2).

Run ``python benchmarks/bench_algorithms.py --help`` for the options.
"""

from __future__ import annotations

import argparse
import gc
import math
import sys
import time
from pathlib import Path

import numba
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import voroforge as vf  # noqa: E402

from common import (  # noqa: E402
    command_line,
    fmt_ratio,
    fmt_seconds,
    machine_info,
    parse_sizes,
    print_table,
    uniform,
)

ALGORITHMS = ("delaunay", "fortune", "halfplane")
BOX = (0.0, 0.0, 1.0, 1.0)


def growth_exponent(sizes: list[int], times: list[float]) -> float:
    """Least-squares slope of ``log t`` against ``log n``."""
    if len(sizes) < 2:
        return math.nan
    return float(np.polyfit(np.log(sizes), np.log(times), 1)[0])


def time_sizes(sizes: list[int], repeat: int) -> dict[str, list[float]]:
    """Best-of-``repeat`` seconds per algorithm and size, algorithms alternated each repeat."""
    warm = uniform(2000)
    for alg in ALGORITHMS:  # compile (or load from numba's cache) outside the timings
        vf.voronoi(warm, BOX, algorithm=alg)
    out: dict[str, list[float]] = {alg: [] for alg in ALGORITHMS}
    for n in sizes:
        pts = uniform(n)
        best = dict.fromkeys(ALGORITHMS, math.inf)
        for _ in range(repeat):
            for alg in ALGORITHMS:
                gc.collect()
                t0 = time.perf_counter()
                d = vf.voronoi(pts, BOX, algorithm=alg)
                best[alg] = min(best[alg], time.perf_counter() - t0)
                del d
        for alg in ALGORITHMS:
            out[alg].append(best[alg])
        print(
            f"n={n}: " + ", ".join(f"{a} {fmt_seconds(best[a])}" for a in ALGORITHMS),
            flush=True,
        )
    return out


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="1e3,1e4,1e5,1e6", help="comma-separated point counts")
    ap.add_argument("--repeat", type=int, default=3, help="best of this many runs")
    args = ap.parse_args(argv)
    sizes = parse_sizes(args.sizes)
    print(command_line())
    print(machine_info())
    print(f"numba threads: {numba.get_num_threads()}")
    times = time_sizes(sizes, args.repeat)
    rows = []
    for k, n in enumerate(sizes):
        base = times["delaunay"][k]
        row: list[object] = [f"{n:,}"]
        for alg in ALGORITHMS:
            row += [fmt_seconds(times[alg][k]), fmt_ratio(times[alg][k], base)]
        rows.append(row)
    headers = ["n"]
    for alg in ALGORITHMS:
        headers += [alg, "÷ delaunay"]
    print_table(headers, rows, title="vf.voronoi(p, unit square, algorithm=...), buffers only")
    exps = [f"{alg} {growth_exponent(sizes, times[alg]):.2f}" for alg in ALGORITHMS]
    print("growth exponent (slope of log t vs log n): " + ", ".join(exps))


if __name__ == "__main__":
    main()
