"""Benchmark of vf.voronoi3d against voro++ (CLI), freud (periodic) and Qhull, side by side.

Usage::

    .venv/bin/python benchmarks/bench_3d.py [--sizes 10000,100000,1000000] [--repeat 3]
        [--no-freud] [--no-qhull] [--no-periodic] [--single] [--mesh 100000]

For each size (uniform points in the unit box, fixed seed) it prints the best-of-``repeat``
wall time of:

* ``vf.voronoi3d(points, (0, 0, 0, 1, 1, 1))``: volumes, neighbours and faces (after a
  warm-up call that also compiles), with numba's threads and, with ``--single``, on one
  thread (also as user CPU seconds against voro++'s, which a loaded machine disturbs
  less); its peak extra memory per cell (tracemalloc: the arrays numpy allocates, which
  are all the large ones) and the process's peak resident set size at the end;
* the voro++ command-line tool (``voro++ -o 0 1 0 1 0 1 file``: volumes, text I/O included;
  the points file is written once, outside the timing);
* ``vf.voronoi3d(..., periodic=True)`` and freud's ``locality.Voronoi`` (voro++ inside,
  periodic);
* scipy's ``Voronoi`` (Qhull: the raw unbounded diagram, no volumes, no clipping), up to 1e5.

Ours and the reference take turns, ``repeat`` times, and the best of each counts.
Ratios are ours / theirs (< 1: we are faster). With ``--mesh N`` it also times N sites in a
torus container (20k triangles). The machine may be shared: compare ratios from
one run, not absolute times across runs. The cost slope from the smallest to the largest
size is printed (1.0 = linear).
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import tempfile
import time
import tracemalloc

import numba
import numpy as np

import voroforge as vf

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


def best(fn, repeat):
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        t.append(time.perf_counter() - t0)
    return min(t)


def timed(fn):
    """``(wall, cpu)`` seconds of one call: this process's CPU and its children's (voro++)."""
    c0 = resource.getrusage(resource.RUSAGE_SELF)
    k0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    fn()
    wall = time.perf_counter() - t0
    c1 = resource.getrusage(resource.RUSAGE_SELF)
    k1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (c1.ru_utime - c0.ru_utime) + (k1.ru_utime - k0.ru_utime)
    return wall, cpu


def alternated(fns, repeat):
    """Best wall and best CPU time of each function, the functions taking turns."""
    walls = [[] for _ in fns]
    cpus = [[] for _ in fns]
    for _ in range(repeat):
        for k, fn in enumerate(fns):
            if fn is None:
                continue
            w, c = timed(fn)
            walls[k].append(w)
            cpus[k].append(c)
    return [(min(w), min(c)) if w else (None, None) for w, c in zip(walls, cpus, strict=True)]


def ours(p):
    d = vf.voronoi3d(p, BOX)
    d.neighbors  # noqa: B018 - the neighbour CSR and the unique faces are part of the work
    d.faces  # noqa: B018
    return d


def voropp_call(p, tmp):
    """A function running voro++'s CLI on ``p`` (the points file written once, here)."""
    exe = shutil.which("voro++")
    if exe is None:
        return None
    path = os.path.join(tmp, "pts")
    np.savetxt(path, np.column_stack([np.arange(len(p)), p]), fmt=["%d", "%.17g", "%.17g", "%.17g"])
    return lambda: subprocess.run([exe, "-o", "0", "1", "0", "1", "0", "1", path], check=True)


def freud_call(p):
    try:
        import freud
    except ImportError:
        return None
    box = freud.box.Box.cube(1.0)
    q = p - 0.5
    return lambda: freud.locality.Voronoi().compute((box, q))


def qhull_time(p, repeat):
    from scipy.spatial import Voronoi

    return best(lambda: Voronoi(p), repeat)


def peak_per_cell(p):
    tracemalloc.start()
    ours(p)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return peak / len(p)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="10000,100000,1000000")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-freud", action="store_true")
    ap.add_argument("--no-qhull", action="store_true")
    ap.add_argument("--no-periodic", action="store_true")
    ap.add_argument("--single", action="store_true", help="also time ours on one thread")
    ap.add_argument("--mesh", type=int, default=0)
    args = ap.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    rng = np.random.default_rng(20240611)
    ours(rng.random((2000, 3)))  # compile
    vf.voronoi3d(rng.random((2000, 3)), BOX, periodic=True)
    rows = []
    print(
        "wall seconds, best of the repeats with the tools taking turns; ratio = ours / theirs "
        "(CPU: user seconds, voro++ as a child process)"
    )
    print(
        f"{'n':>9} {'ours s':>8} {'1 thr s':>8} {'voro++ s':>9} {'ratio':>6} {'1thr':>6} "
        f"{'CPU r':>6} {'cells/s':>9} {'periodic':>8} {'freud s':>8} {'ratio':>6} "
        f"{'qhull s':>8} {'B/cell':>7}"
    )

    def f(x):
        return f"{x:8.3f}" if x is not None else "       -"

    def ratio(a, b):
        return f"{a / b:6.2f}" if a and b else "     -"

    def single(p):
        before = numba.get_num_threads()
        numba.set_num_threads(1)
        try:
            ours(p)
        finally:
            numba.set_num_threads(before)

    for n in sizes:
        p = np.random.default_rng(n).random((n, 3))
        with tempfile.TemporaryDirectory() as tmp:
            (t, _), (t1, c1), (tv, cv) = alternated(
                [
                    lambda p=p: ours(p),
                    (lambda p=p: single(p)) if args.single else None,
                    voropp_call(p, tmp),
                ],
                args.repeat,
            )
        tp = tf = None
        if not args.no_periodic:
            (tp, _), (tf, _) = alternated(
                [
                    lambda p=p: vf.voronoi3d(p, BOX, periodic=True),
                    None if args.no_freud else freud_call(p),
                ],
                args.repeat,
            )
        tq = None if args.no_qhull or n > 100000 else qhull_time(p, 1 if n > 10000 else args.repeat)
        mem = peak_per_cell(p)
        rows.append((n, t))
        print(
            f"{n:>9} {t:8.3f} {f(t1)} {f(tv):>9} {ratio(t, tv)} {ratio(t1, tv)} "
            f"{ratio(c1, cv)} {n / t:9.0f} {f(tp)} {f(tf)} {ratio(tp, tf)} {f(tq)} {mem:7.0f}",
            flush=True,
        )
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak RSS of this process: {rss:.0f} MiB; load average {os.getloadavg()}")
    if len(rows) >= 2:
        (n0, t0), (n1, t1) = rows[0], rows[-1]
        print(
            f"cost slope {np.log(t1 / t0) / np.log(n1 / n0):.2f} from {n0} to {n1} (1.0 = linear)"
        )
    if args.mesh:
        import trimesh

        knot = trimesh.creation.torus(
            major_radius=1.0, minor_radius=0.35, major_sections=200, minor_sections=50
        )
        lo, hi = knot.bounds
        p = np.random.default_rng(1).uniform(lo, hi, (args.mesh, 3))
        vf.voronoi3d(p[:500], knot)
        t = best(lambda: vf.voronoi3d(p, knot), 1)
        print(
            f"mesh container ({len(knot.faces)} triangles), {args.mesh} sites: {t:.2f} s, "
            f"{args.mesh / t:.0f} cells/s"
        )


if __name__ == "__main__":
    main()
