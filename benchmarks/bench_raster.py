"""Benchmark of vf.rasterize (exact and Jump Flooding) against scipy, side by side.

Usage::

    .venv/bin/python benchmarks/bench_raster.py [--size 2048] [--sites 10000] [--repeat 3]
        [--dist uniform|clustered|grid|circle|two_circles|slanted_line] [--f2] [--no-scipy]

Prints the best-of-``repeat`` wall time (after a warm-up call that also compiles) of each
method, its CPU time summed over threads (steadier on a shared machine), the share of JFA
pixels whose label differs from the exact one, the time and that share for the flood alone
(JFA before its exact check: what a plain Jump Flooding returns), and the same for two scipy
references run in this process on the same pixel centres:

* ``cKDTree.query`` of every pixel centre (exact nearest site; ``workers=-1``);
* ``ndimage.distance_transform_edt(..., return_indices=True)`` on an image with one seed
  pixel per site (a pixel-accurate transform: the nearest *seed pixel*, like JFA).

Ratios are scipy time / our time (> 1: we are faster).
"""

from __future__ import annotations

import argparse
import time

import numba
import numpy as np

from voroforge import rasterize
from voroforge.engine import raster
from voroforge.engine.raster import pixel_centers
from voroforge.kernels.raster import jfa_nearest


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
    if kind in ("circle", "two_circles"):  # crowded: many sites per pixel along the circles
        radii = [0.45] if kind == "circle" else [0.45, 0.2]
        parts = []
        for i, radius in enumerate(radii):
            k = n // len(radii) + (i < n % len(radii))
            t = np.arange(k) * 2 * np.pi / k + 0.1 * i
            parts.append(np.column_stack((np.cos(t), np.sin(t))) * radius + 0.5)
        return np.vstack(parts)
    if kind == "slanted_line":  # crowded: cells are strips thinner than a pixel
        s = np.linspace(0.1, 0.9, n)
        return np.column_stack((s, 0.3 + 0.4 * s))
    raise ValueError(kind)


def flood_only(pts, bounds, shape):
    """Labels of the Jump Flooding pass alone, as ``rasterize`` runs it before its check."""
    h, w = shape
    xmin, ymin, xmax, ymax = bounds
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    px, py = pixel_centers(bounds, shape)
    geom = np.array([xmin, ymax, (xmax - xmin) / w, (ymax - ymin) / h])
    steps = raster._jfa_steps(h, w, raster._jfa_reach(xs, ys, geom, shape))
    return jfa_nearest(xs, ys, px, py, geom, steps, False)[0]


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


def scipy_kdtree(pts, bounds, shape):
    """Exact nearest site of every pixel centre with cKDTree (ties: whichever scipy returns)."""
    from scipy.spatial import cKDTree

    x, y = pixel_centers(bounds, shape)
    xx, yy = np.meshgrid(x, y)
    tree = cKDTree(pts)
    _, idx = tree.query(np.stack((xx.ravel(), yy.ravel()), axis=1), workers=-1)
    return idx.reshape(shape)


def scipy_edt(pts, bounds, shape):
    """Nearest seed pixel by the exact Euclidean distance transform of a seed image."""
    from scipy import ndimage

    h, w = shape
    xmin, ymin, xmax, ymax = bounds
    c = np.clip(((pts[:, 0] - xmin) / (xmax - xmin) * w).astype(np.int64), 0, w - 1)
    r = np.clip(((ymax - pts[:, 1]) / (ymax - ymin) * h).astype(np.int64), 0, h - 1)
    seeds = np.full(shape, -1, dtype=np.int64)
    seeds[r[::-1], c[::-1]] = np.arange(len(pts))[::-1]  # lowest index wins a shared pixel
    _, (ri, ci) = ndimage.distance_transform_edt(seeds < 0, return_indices=True)
    return seeds[ri, ci]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=2048)
    ap.add_argument("--sites", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=3)
    dists = ("uniform", "clustered", "grid", "circle", "two_circles", "slanted_line")
    ap.add_argument("--dist", default="uniform", choices=dists)
    ap.add_argument("--f2", action="store_true")
    ap.add_argument("--no-scipy", action="store_true", help="skip the scipy references")
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
    t_flood, c_flood, fl = best_time(lambda: flood_only(pts, bounds, shape), args.repeat)
    mismatch = float(np.mean(ex.labels != jf.labels))
    flood_bad = float(np.mean(ex.labels != fl))
    derr = float(np.max(jf.distance - ex.distance))
    print(f"{args.dist} sites={args.sites} image={args.size}x{args.size} f2={args.f2}")
    print(f"threads={numba.get_num_threads()}  (cpu = CPU seconds summed over threads)")
    print(f"exact      : wall {t_exact:8.3f} s   cpu {c_exact:8.3f} s")
    print(f"jfa        : wall {t_jfa:8.3f} s   cpu {c_jfa:8.3f} s")
    print(
        f"jfa label mismatch vs exact: {100 * mismatch:.4f} %   "
        f"max F1 excess: {derr:.3g} ({derr * args.size:.2f} px)"
    )
    print(
        f"  flood only: wall {t_flood:8.3f} s   cpu {c_flood:8.3f} s   (label mismatch vs exact: "
        f"{100 * flood_bad:.4f} %)"
    )
    if args.f2:
        print(f"jfa max F2 excess: {float(np.max(jf.f2 - ex.f2)):.3g}")
    if args.no_scipy:
        return
    t_kd, c_kd, kd = best_time(lambda: scipy_kdtree(pts, bounds, shape), args.repeat)
    t_edt, c_edt, edt = best_time(lambda: scipy_edt(pts, bounds, shape), args.repeat)
    # cKDTree breaks exact ties its own way: compare distances, not only labels
    x, y = pixel_centers(bounds, shape)
    xx, yy = np.meshgrid(x, y)
    kd_d = np.sqrt((xx - pts[kd, 0]) ** 2 + (yy - pts[kd, 1]) ** 2)  # as the kernel rounds
    kd_bad = float(np.mean(kd_d != ex.distance))
    edt_bad = float(np.mean(edt != ex.labels))
    print(
        f"scipy kdtree: wall {t_kd:8.3f} s   cpu {c_kd:8.3f} s   (differs from exact: "
        f"{100 * kd_bad:.4f} % of pixels by distance)"
    )
    print(
        f"scipy edt   : wall {t_edt:8.3f} s   cpu {c_edt:8.3f} s   (label mismatch vs exact: "
        f"{100 * edt_bad:.4f} %)"
    )
    print(f"ratio kdtree/exact : {t_kd / t_exact:6.2f}x wall   {c_kd / c_exact:6.2f}x cpu")
    print(f"ratio kdtree/jfa   : {t_kd / t_jfa:6.2f}x wall   {c_kd / c_jfa:6.2f}x cpu")
    print(f"ratio edt/jfa      : {t_edt / t_jfa:6.2f}x wall   {c_edt / c_jfa:6.2f}x cpu")
    print(f"ratio edt/exact    : {t_edt / t_exact:6.2f}x wall   {c_edt / c_exact:6.2f}x cpu")


if __name__ == "__main__":
    main()
