"""Shared helpers for the benchmarks: fixed-seed inputs, timing and a small table printer.

Every generator returns a C-contiguous ``(n, 2) float64`` array in ``[0, 1]^2`` and is
deterministic (fixed seed), so runs on different machines time the same input.
"""

from __future__ import annotations

import gc
import os
import platform
import sys
import time
from collections.abc import Callable, Sequence

import numpy as np

SEED = 20240611


def uniform(n: int, seed: int = SEED) -> np.ndarray:
    """``n`` points uniformly distributed in the unit square."""
    rng = np.random.default_rng(seed)
    return rng.random((int(n), 2))


def clustered(n: int, seed: int = SEED, n_clusters: int | None = None) -> np.ndarray:
    """``n`` points in gaussian blobs of varying size, clipped into the unit square.

    The number of blobs grows slowly with ``n`` (about ``n ** 0.3``, at least 4); blob
    centres are uniform in ``[0.1, 0.9]^2`` and standard deviations lie in
    ``[0.01, 0.06]``. Points falling outside the square are clipped onto its border, which
    also exercises collinear sites on the domain edges.
    """
    n = int(n)
    rng = np.random.default_rng(seed)
    k = n_clusters if n_clusters is not None else max(4, int(round(n**0.3)))
    centres = 0.1 + 0.8 * rng.random((k, 2))
    sigmas = rng.uniform(0.01, 0.06, size=k)
    weights = rng.random(k) + 0.2
    which = rng.choice(k, size=n, p=weights / weights.sum())
    pts = centres[which] + sigmas[which, None] * rng.standard_normal((n, 2))
    return np.ascontiguousarray(np.clip(pts, 0.0, 1.0))


def grid(n: int) -> np.ndarray:
    """The square grid with about ``n`` points: ``k * k`` of them, ``k = round(sqrt(n))``.

    Coordinates are cell centres ``(i + 0.5) / k``. Every 2x2 block of neighbouring points
    is the corner set of an axis-aligned rectangle built from the same ``k`` float values,
    so the four points are *exactly* cocircular: the worst case for Delaunay codes.
    """
    k = max(2, int(round(np.sqrt(int(n)))))
    axis = (np.arange(k, dtype=np.float64) + 0.5) / k
    xx, yy = np.meshgrid(axis, axis, indexing="xy")
    return np.ascontiguousarray(np.column_stack((xx.ravel(), yy.ravel())))


DISTRIBUTIONS: dict[str, Callable[[int], np.ndarray]] = {
    "uniform": uniform,
    "clustered": clustered,
    "grid": grid,
}


def polygon_with_holes():
    """The unit square with three holes of different shapes (a shapely Polygon).

    Holes: a disc of radius 0.12 around (0.28, 0.7), a triangle in the lower left and a
    thin L-shaped (non-convex) slot on the right. Their total area is about 0.16.
    """
    import shapely

    disc = shapely.Point(0.28, 0.7).buffer(0.12, quad_segs=16)
    triangle = [(0.15, 0.12), (0.45, 0.18), (0.25, 0.38)]
    ell = [(0.6, 0.15), (0.9, 0.15), (0.9, 0.25), (0.7, 0.25), (0.7, 0.75), (0.6, 0.75)]
    holes = [
        list(disc.exterior.coords)[::-1],
        triangle,
        ell,
    ]
    shell = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    poly = shapely.Polygon(shell, holes)
    poly = shapely.normalize(poly)
    assert poly.is_valid, shapely.is_valid_reason(poly)
    return poly


def best_of(fn: Callable[[], object], repeat: int = 3) -> float:
    """Minimum wall time in seconds of ``repeat`` calls of ``fn`` (gc collected before each).

    The result of each call is dropped before the next one starts, so peak memory stays at
    one result.
    """
    best = float("inf")
    for _ in range(max(1, int(repeat))):
        gc.collect()
        t0 = time.perf_counter()
        out = fn()
        t1 = time.perf_counter()
        del out
        best = min(best, t1 - t0)
    gc.collect()
    return best


def parse_sizes(text: str) -> list[int]:
    """``"1e4,1e5,3000"`` -> ``[10000, 100000, 3000]``."""
    return [int(float(s)) for s in text.split(",") if s.strip()]


def fmt_seconds(t: float | None) -> str:
    """Seconds with 3 significant digits, ``-`` for missing, ``skip`` for skipped (NaN)."""
    if t is None:
        return "-"
    if t != t:  # NaN marks a skipped measurement
        return "skip"
    if t >= 100:
        return f"{t:.0f}"
    if t >= 10:
        return f"{t:.1f}"
    if t >= 1:
        return f"{t:.2f}"
    return f"{t:.3g}"


def fmt_ratio(num: float | None, den: float | None) -> str:
    """``num / den`` as ``1.23x``, or ``-`` when either side is missing or skipped."""
    if num is None or den is None or num != num or den != den or den <= 0:
        return "-"
    r = num / den
    return f"{r:.2f}x" if r < 100 else f"{r:.0f}x"


def print_table(headers: Sequence[str], rows: Sequence[Sequence[object]], title: str = "") -> None:
    """Print a plain text table: first column left-aligned, the others right-aligned."""
    cells = [[str(h) for h in headers]] + [[str(c) for c in row] for row in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(headers))]

    def line(r: Sequence[str]) -> str:
        rest = [c.rjust(w) for c, w in zip(r[1:], widths[1:], strict=True)]
        parts = [r[0].ljust(widths[0]), *rest]
        return "  ".join(parts).rstrip()

    if title:
        print(f"\n{title}")
    print(line(cells[0]))
    print("  ".join("-" * w for w in widths))
    for r in cells[1:]:
        print(line(r))
    sys.stdout.flush()


def machine_info() -> str:
    """One block of text: interpreter, platform, CPU count and library versions."""
    import importlib

    lines = [
        f"python   {platform.python_version()} ({platform.python_implementation()})",
        f"platform {platform.platform()}",
        f"cpu      {_cpu_name()}; os.cpu_count()={os.cpu_count()}, "
        f"usable={len(os.sched_getaffinity(0)) if hasattr(os, 'sched_getaffinity') else '?'}",
    ]
    versions = []
    for name in ("numpy", "numba", "scipy", "shapely", "triangle", "voroforge"):
        try:
            mod = importlib.import_module(name)
            ver = getattr(mod, "__version__", None)
            if ver is None and name == "triangle":
                from importlib.metadata import version

                ver = version("triangle")
            versions.append(f"{name} {ver}")
        except Exception as exc:  # report any import failure and go on
            versions.append(f"{name} (unavailable: {type(exc).__name__})")
    try:
        import shapely

        versions.append("GEOS {}.{}.{}".format(*shapely.geos_version))
    except ImportError:
        pass
    try:
        import numba

        versions.append(f"numba threads {numba.config.NUMBA_NUM_THREADS}")
    except ImportError:
        pass
    lines.append("versions " + ", ".join(versions))
    return "\n".join(lines)


def _cpu_name() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def command_line() -> str:
    """The exact command line of this process, shell-quoted."""
    import shlex

    return " ".join(shlex.quote(a) for a in [sys.executable, *sys.argv])
