"""Benchmark of the query functions and periodic diagrams against references, side by side.

Usage::

    .venv/bin/python benchmarks/bench_queries.py [--sites 1e4] [--queries 1e5] [--repeat 3]
        [--periodic 1e4,1e5]

Every row times ours and a reference in this process on the same input (best of
``repeat`` after a warm-up call that also compiles), and prints their ratio:

* ``vf.locate`` (KD-tree + exact lowest-index tie-break) against a bare
  ``scipy.spatial.cKDTree`` build + query (what it is built on);
* ``vf.natural_neighbor`` (Sibson Z0, and Z1 with ``smooth=True``) against
  ``scipy.interpolate.griddata(method="linear")`` and ``method="cubic"`` (Clough-Tocher);
* periodic ``vf.voronoi(..., periodic=True)`` (and ``wrap=True``) against the plain
  ``vf.voronoi`` of the same sites in the box (the cost of the torus).

Then the interpolation error on Franke's function (500 uniform samples in the unit square,
101 x 101 grid of queries, points inside the convex hull of the samples): RMS and maximum
error of Sibson Z0, Z1 and the two griddata methods.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from scipy.interpolate import griddata
from scipy.spatial import cKDTree

sys.path.insert(0, str(Path(__file__).parent))
import voroforge as vf

from common import best_of, fmt_ratio, fmt_seconds, machine_info, parse_sizes, print_table, uniform


def franke(x, y):
    """Franke's test function on the unit square."""
    return (
        0.75 * np.exp(-((9 * x - 2) ** 2) / 4 - (9 * y - 2) ** 2 / 4)
        + 0.75 * np.exp(-((9 * x + 1) ** 2) / 49 - (9 * y + 1) / 10)
        + 0.5 * np.exp(-((9 * x - 7) ** 2) / 4 - (9 * y - 3) ** 2 / 4)
        - 0.2 * np.exp(-((9 * x - 4) ** 2) - (9 * y - 7) ** 2)
    )


def bench_queries(n: int, m: int, repeat: int) -> None:
    sites = uniform(n)
    q = uniform(m, seed=7) * 1.1 - 0.05
    vals = franke(*sites.T)

    def kd():
        return cKDTree(sites).query(q)[1]

    rows = []
    for name, ours, ref_name, ref in [
        ("locate", lambda: vf.locate(sites, q), "cKDTree build+query", kd),
        (
            "natural_neighbor (Z0)",
            lambda: vf.natural_neighbor(sites, vals, q),
            "griddata linear",
            lambda: griddata(sites, vals, q, method="linear"),
        ),
        (
            "natural_neighbor smooth (Z1)",
            lambda: vf.natural_neighbor(sites, vals, q, smooth=True),
            "griddata cubic",
            lambda: griddata(sites, vals, q, method="cubic"),
        ),
    ]:
        ours()
        ref()
        t_ours = best_of(ours, repeat)
        t_ref = best_of(ref, repeat)
        rows.append(
            [name, fmt_seconds(t_ours), ref_name, fmt_seconds(t_ref), fmt_ratio(t_ours, t_ref)]
        )
    print_table(
        ["task", "voroforge s", "reference", "reference s", "ours / reference"],
        rows,
        f"queries: {n} sites, {m} query points (uniform), best of {repeat}",
    )


BOX = (0.0, 0.0, 1.0, 1.0)


def bench_periodic(sizes, repeat: int) -> None:
    rows = []
    box = BOX
    for n in sizes:
        sites = uniform(n)
        vf.voronoi(sites, box, periodic=True)
        vf.voronoi(sites, box, periodic=True, wrap=True)
        calls = {
            "plain": lambda s=sites: vf.voronoi(s, BOX),
            "periodic": lambda s=sites: vf.voronoi(s, BOX, periodic=True),
            "wrap": lambda s=sites: vf.voronoi(s, BOX, periodic=True, wrap=True),
        }
        best = dict.fromkeys(calls, float("inf"))
        for _ in range(repeat):  # interleaved, so load changes hit all three alike
            for name, fn in calls.items():
                best[name] = min(best[name], best_of(fn, 1))
        t_plain, t_per, t_wrap = best["plain"], best["periodic"], best["wrap"]
        rows.append(
            [
                n,
                fmt_seconds(t_plain),
                fmt_seconds(t_per),
                fmt_ratio(t_per, t_plain),
                fmt_seconds(t_wrap),
                fmt_ratio(t_wrap, t_plain),
            ]
        )
    print_table(
        ["n", "plain s", "periodic s", "periodic/plain", "wrap s", "wrap/plain"],
        rows,
        f"periodic diagrams of uniform sites in the unit square, best of {repeat} interleaved",
    )


def franke_errors() -> None:
    rng = np.random.default_rng(1)
    sites = rng.random((500, 2))
    vals = franke(*sites.T)
    g = np.linspace(0.0, 1.0, 101)
    q = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
    results = {
        "Sibson Z0 (vf.natural_neighbor)": vf.natural_neighbor(sites, vals, q),
        "Sibson Z1 (smooth=True)": vf.natural_neighbor(sites, vals, q, smooth=True),
        "griddata linear": griddata(sites, vals, q, method="linear"),
        "griddata cubic (Clough-Tocher)": griddata(sites, vals, q, method="cubic"),
    }
    inside = ~np.isnan(results["griddata linear"])
    exact = franke(*q[inside].T)
    rows = []
    for name, f in results.items():
        err = f[inside] - exact
        rows.append([name, f"{np.sqrt(np.mean(err**2)):.2e}", f"{np.abs(err).max():.2e}"])
    print_table(
        ["method", "RMS error", "max error"],
        rows,
        f"Franke's function, 500 uniform samples (seed 1), {inside.sum()} grid queries in the hull",
    )


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--sites", default="1e4")
    ap.add_argument("--queries", default="1e5")
    ap.add_argument("--periodic", default="1e4,1e5")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(machine_info())
    bench_queries(parse_sizes(args.sites)[0], parse_sizes(args.queries)[0], args.repeat)
    bench_periodic(parse_sizes(args.periodic), args.repeat)
    franke_errors()


if __name__ == "__main__":
    main()
