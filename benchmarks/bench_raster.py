"""Benchmark of vf.rasterize: exact labels vs Jump Flooding.

Usage::

    .venv/bin/python benchmarks/bench_raster.py [--size 2048] [--sites 10000] [--repeat 3]
        [--dist uniform|clustered|grid] [--f2]

Prints the best-of-``repeat`` wall time (after a warm-up call that also compiles) of each
method, its CPU time summed over threads (a steadier number on a shared machine), and the
share of JFA pixels whose label differs from the exact one.
"""

from __future__ import annotations

import argparse
import time

import numba
import numpy as np

from voroforge.engine.raster import rasterize


def make_sites(kind: str, n: int, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    if kind == "uniform":
        return rng.random((n, 2))
    if kind == "clustered":
        centres = rng.random((max(n // 500, 1), 2))
        pick = rng.integers(0, len(centres), n)
        return centres[pick] + rng.normal(scale=0.02, size=(n, 2))
    if kind == "grid":
        k = int(np.ceil(np.sqrt(n)))
        g = (np.arange(k) + 0.5) / k
        xx, yy = np.meshgrid(g, g)
        return np.stack((xx.ravel(), yy.ravel()), axis=1)[:n]
    raise ValueError(kind)


def best_time(fn, repeat: int) -> tuple[float, float, object]:
    """Best wall time and best CPU time (all threads) of ``repeat`` calls after a warm-up."""
    out = fn()  # warm-up (and JIT compile on first use)
    wall = cpu = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        c0 = time.process_time()
        out = fn()
        cpu = min(cpu, time.process_time() - c0)
        wall = min(wall, time.perf_counter() - t0)
    return wall, cpu, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=2048)
    ap.add_argument("--sites", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--dist", default="uniform", choices=("uniform", "clustered", "grid"))
    ap.add_argument("--f2", action="store_true")
    args = ap.parse_args()
    pts = make_sites(args.dist, args.sites)
    shape = (args.size, args.size)
    bounds = (0.0, 0.0, 1.0, 1.0)
    t_exact, c_exact, ex = best_time(
        lambda: rasterize(pts, shape, bounds, method="exact", f2=args.f2), args.repeat
    )
    t_jfa, c_jfa, jf = best_time(
        lambda: rasterize(pts, shape, bounds, method="jfa", f2=args.f2), args.repeat
    )
    mismatch = float(np.mean(ex.labels != jf.labels))
    derr = float(np.max(jf.distance - ex.distance))
    print(f"{args.dist} sites={args.sites} image={args.size}x{args.size} f2={args.f2}")
    print(f"threads={numba.get_num_threads()}  (cpu = CPU seconds summed over threads)")
    print(f"exact : wall {t_exact:8.3f} s   cpu {c_exact:8.3f} s")
    print(f"jfa   : wall {t_jfa:8.3f} s   cpu {c_jfa:8.3f} s")
    print(f"jfa label mismatch: {100 * mismatch:.4f} %   max F1 excess: {derr:.3g}")
    if args.f2:
        print(f"jfa max F2 excess: {float(np.max(jf.f2 - ex.f2)):.3g}")


if __name__ == "__main__":
    main()
