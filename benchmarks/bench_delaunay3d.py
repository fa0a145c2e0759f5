"""Benchmark of vf.delaunay3d against scipy's Delaunay (Qhull), side by side in one process.

Usage::

    .venv/bin/python benchmarks/bench_delaunay3d.py [--sizes 10000,100000,1000000] [--repeat 3]

For each size it times, alternating and keeping the best of ``repeat``, our exact
tetrahedralisation and Qhull's (``scipy.spatial.Delaunay``, default options: joggle-free,
``Qbb Qc Qz Q12``, float arithmetic) on uniform points in the unit cube and on a cubic grid
(every cube's 8 corners on one sphere: the degenerate case), and checks that both give the
same number of tetrahedra on the uniform input. Ratios are ours / Qhull's (< 1: faster).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from scipy.spatial import Delaunay

sys.path.insert(0, str(Path(__file__).resolve().parent))
import voroforge as vf  # noqa: E402

from common import SEED, best_of, fmt_ratio, fmt_seconds, machine_info, parse_sizes, print_table  # noqa: E402


def _inputs(n: int) -> dict[str, np.ndarray]:
    k = max(2, round(n ** (1 / 3)))
    axis = np.arange(k, dtype=np.float64)
    grid = np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), axis=-1).reshape(-1, 3)
    return {"uniform": np.random.default_rng(SEED).random((n, 3)), "cubic grid": grid}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", default="10000,100000")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(machine_info())
    vf.delaunay3d(np.random.default_rng(0).random((200, 3)))  # compile (cached after)
    rows = []
    for n in parse_sizes(args.sizes):
        for name, pts in _inputs(n).items():
            ours = theirs = float("inf")
            for _ in range(max(1, args.repeat)):
                ours = min(ours, best_of(lambda p=pts: vf.delaunay3d(p), 1))
                theirs = min(theirs, best_of(lambda p=pts: Delaunay(p), 1))
            m_ours = len(vf.delaunay3d(pts).simplices)
            m_qhull = len(Delaunay(pts).simplices)
            rows.append(
                [name, len(pts), fmt_seconds(ours), fmt_seconds(theirs),
                 fmt_ratio(ours, theirs), m_ours, m_qhull]
            )  # fmt: skip
    print_table(
        ["input", "n", "ours s", "Qhull s", "ratio", "tets (ours)", "tets (Qhull)"],
        rows,
        title="vf.delaunay3d vs scipy.spatial.Delaunay (best of repeat, wall)",
    )


if __name__ == "__main__":
    main()
