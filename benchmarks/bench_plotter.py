"""Plotter paths: pen-up travel and time of ``io.plotter.order_paths`` against NN + full 2-opt.

Run from the repository root::

    .venv/bin/python benchmarks/bench_plotter.py            # 10k paths, 2 distributions
    .venv/bin/python benchmarks/bench_plotter.py --sizes 2000,10000

For each input: our order (greedy nearest neighbour on a bucket grid, then 2-opt on a
10-nearest-ends candidate list, numba), a plain nearest-neighbour tour (ours without 2-opt),
and the reference: the same greedy tour improved by *full* 2-opt (every pair of positions,
best move per position, numpy-vectorised) until no move improves. Travel is pen-up length
from the top-left corner (open tour). Ratios are travel(ours) / travel(reference); times
are best of 3, wall and process CPU seconds (the machine may be shared: on a loaded machine
the CPU time is the cost; compare ratios).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from voroforge.io import plotter  # noqa: E402

from common import machine_info, parse_sizes, print_table  # noqa: E402


def segments(n: int, kind: str, seed: int = 7) -> list:
    """``n`` short strokes in a 1000 x 1000 page: uniform, or in clusters."""
    rng = np.random.default_rng(seed)
    if kind == "uniform":
        a = rng.random((n, 2)) * 1000
    else:
        centres = rng.random((12, 2)) * 1000
        a = centres[rng.integers(0, 12, n)] + rng.normal(size=(n, 2)) * 40
    b = a + rng.normal(size=(n, 2)) * 6
    return [np.array([p, q]) for p, q in zip(a, b, strict=True)]


def full_two_opt(paths, order, flipped, start):
    """Full 2-opt over every pair of positions (reference), in place on copies."""
    heads = np.array([p[0] for p in paths])
    tails = np.array([p[-1] for p in paths])
    order = np.array(order)
    flipped = np.array(flipped, dtype=bool)
    n = len(order)
    start = np.asarray(start, dtype=float)
    while True:
        improved = False
        for i in range(-1, n - 1):
            h = np.where(flipped[:, None], tails[order], heads[order])  # head per position
            t = np.where(flipped[:, None], heads[order], tails[order])
            ti = start if i < 0 else t[i]
            j = np.arange(i + 1, n)
            old = np.hypot(*(ti - h[i + 1]))
            new = np.hypot(*(t[j] - ti).T)
            nxt = np.minimum(j + 1, n - 1)
            has = j + 1 < n
            old = old + np.where(has, np.hypot(*(t[j] - h[nxt]).T), 0.0)
            new = new + np.where(has, np.hypot(*(h[i + 1] - h[nxt]).T), 0.0)
            gain = old - new
            k = int(np.argmax(gain))
            if gain[k] > 1e-9:
                jj = int(j[k])
                order[i + 1 : jj + 1] = order[i + 1 : jj + 1][::-1].copy()
                flipped[i + 1 : jj + 1] = ~flipped[i + 1 : jj + 1][::-1].copy()
                improved = True
        if not improved:
            return order, flipped


def pen_up(paths, order, flipped, start) -> float:
    drawn = [paths[i][::-1] if f else paths[i] for i, f in zip(order, flipped, strict=True)]
    return plotter.travel(drawn, start=start)[0]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="2000,10000")
    parser.add_argument(
        "--ref-max", type=int, default=3000, help="run the O(n^2)-per-pass reference up to this n"
    )
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(machine_info())
    start = (0.0, 1000.0)
    plotter.order_paths(segments(50, "uniform"), start=start)  # compile outside the timing
    rows = []
    for n in parse_sizes(args.sizes):
        for kind in ("uniform", "clustered"):
            paths = segments(n, kind)
            best = cpu = np.inf
            for _ in range(args.repeat):
                t0, c0 = time.perf_counter(), time.process_time()
                order, flipped = plotter.order_paths(paths, start=start)
                best = min(best, time.perf_counter() - t0)
                cpu = min(cpu, time.process_time() - c0)
            ours = pen_up(paths, order, flipped, start)
            nn_o, nn_f = plotter.order_paths(paths, start=start, improve=False)
            nn = pen_up(paths, nn_o, nn_f, start)
            ref = t_ref = None
            if n <= args.ref_max:
                t0 = time.perf_counter()
                ref_o, ref_f = full_two_opt(paths, nn_o, nn_f, start)
                t_ref = time.perf_counter() - t0
                ref = pen_up(paths, ref_o, ref_f, start)
            rows.append(
                [
                    f"{n}",
                    kind,
                    f"{plotter.travel(paths, start=start)[0]:.0f}",
                    f"{nn:.0f}",
                    "-" if ref is None else f"{ref:.0f}",
                    f"{ours:.0f}",
                    "-" if ref is None else f"{ours / ref:.3f}",
                    f"{best:.3f}",
                    f"{cpu:.3f}",
                    "-" if t_ref is None else f"{t_ref:.1f}",
                ]
            )
    print_table(
        [
            "paths",
            "input",
            "file order",
            "NN",
            "NN+2opt (ref)",
            "ours",
            "ours/ref",
            "ours s",
            "ours cpu s",
            "ref s",
        ],
        rows,
        title="pen-up travel (page units) and time",
    )


if __name__ == "__main__":
    main()
