"""Benchmark of vf.voronoi3d against voro++ (CLI), freud (periodic) and Qhull, side by side.

Usage::

    .venv/bin/python benchmarks/bench_3d.py [--sizes 10000,100000,1000000] [--repeat 3]
        [--no-freud] [--no-qhull] [--no-periodic] [--single] [--mesh 100000]
    .venv/bin/python benchmarks/bench_3d.py --huge 10000000   # volumes + neighbours only
    .venv/bin/python benchmarks/bench_3d.py --sizes '' --mesh 100000   # the mesh case only
    .venv/bin/python benchmarks/bench_3d.py --sizes '' --clustered 40000   # clustered inputs
    .venv/bin/python benchmarks/bench_3d.py --sizes '' --padded 200000   # default container

For each size (uniform points in the unit box, fixed seed) it prints the best-of-``repeat``
wall and CPU (user + system seconds of the process, voro++ as a child process) of:

* ``vf.voronoi3d(points, (0, 0, 0, 1, 1, 1))``: volumes, neighbours and faces (after a
  warm-up call that also compiles), with numba's threads and, with ``--single``, on one
  thread; the CPU ratio against voro++ is the figure a loaded machine disturbs least. Its
  peak memory per cell is measured in a fresh process (peak resident set size during the
  call, less the resident size before it, the points included, divided by the cells);
* the voro++ command-line tool (``voro++ -o 0 1 0 1 0 1 file``: volumes, text I/O included;
  the points file is written once, outside the timing);
* ``vf.voronoi3d(..., periodic=True)`` and freud's ``locality.Voronoi`` (voro++ inside,
  periodic);
* scipy's ``Voronoi`` (Qhull: the raw unbounded diagram, no volumes, no clipping), up to 1e5.

Ours and the reference take turns, ``repeat`` times, and the best of each counts.
Ratios are ours / theirs (< 1: we are faster). With ``--mesh N`` it also times N sites,
uniform in its bounding box, in a torus container (20k triangles); with ``--clustered N``,
N sites uniform, in 20 Gaussian clusters (sd 0.02 and 0.003, clipped to the unit box) and
in one cluster (sd 0.001) with 8 sites up to 50 away, default container, against the
uniform cost per cell (the k-d buckets' case, ``engine.build3d.search3d``); with ``--padded
N``, N uniform sites in the default container (their bounding box padded 10%, the call most
users make) against the unit box. The machine may be
shared: compare ratios from one run, not absolute times across runs. The cost slope from
the smallest to the largest size is printed (1.0 = linear).
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

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
    cpu = sum(
        (getattr(c1, a) - getattr(c0, a)) + (getattr(k1, a) - getattr(k0, a))
        for a in ("ru_utime", "ru_stime")
    )
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


def _status_kib(field):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


def peak_per_cell(n, faces=True):
    """Peak extra resident bytes per cell of one call on ``n`` sites, in a fresh process."""
    code = (
        "import sys, numpy as np, voroforge as vf; sys.path.insert(0, sys.argv[1]);"
        "import bench_3d as b; b.child_peak(int(sys.argv[2]), sys.argv[3] == '1')"
    )
    here = os.path.dirname(os.path.abspath(__file__))
    out = subprocess.run(
        [sys.executable, "-c", code, here, str(n), "1" if faces else "0"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return float(out.split()[-1])


def child_peak(n, faces):
    """(In the child) peak resident growth per cell of ``vf.voronoi3d`` on ``n`` sites."""
    ours(np.random.default_rng(0).random((2000, 3)))  # compile or load the kernels
    before = _status_kib("VmRSS")
    p = np.random.default_rng(n).random((n, 3))
    try:  # reset the peak to the present size (Linux)
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass
    d = vf.voronoi3d(p, BOX)
    d.neighbors  # noqa: B018
    if faces:
        d.faces  # noqa: B018
    peak = _status_kib("VmHWM")
    print((peak - before) * 1024 / n)


def huge(n):
    """One call on ``n`` uniform sites, volumes + neighbours: wall, CPU, peak RSS."""
    p = np.random.default_rng(n).random((n, 3))
    w, c = timed(lambda: vf.voronoi3d(p, BOX).neighbors)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(
        f"{n} cells, volumes + neighbours: {w:.1f} s wall, {c:.1f} s CPU, {n / w:.0f} cells/s; "
        f"peak RSS of the process {rss:.0f} MiB ({rss * 2**20 / n:.0f} B/cell); "
        f"load average {os.getloadavg()}",
        flush=True,
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="10000,100000,1000000")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-freud", action="store_true")
    ap.add_argument("--no-qhull", action="store_true")
    ap.add_argument("--no-periodic", action="store_true")
    ap.add_argument("--single", action="store_true", help="also time ours on one thread")
    ap.add_argument("--mesh", type=int, default=0)
    ap.add_argument("--clustered", type=int, default=0, help="clustered inputs of this size")
    ap.add_argument("--huge", type=float, default=0, help="only one call at this size")
    ap.add_argument("--padded", type=int, default=0, help="default container at this size")
    args = ap.parse_args()
    if args.huge:
        ours(np.random.default_rng(0).random((2000, 3)))  # compile
        huge(int(args.huge))
        return
    sizes = [int(s) for s in args.sizes.split(",") if s]  # --sizes '' --mesh N: the mesh only
    if not sizes and (args.mesh or args.clustered or args.padded):
        if args.mesh:
            mesh_case(args)
        if args.clustered:
            clustered_case(args)
        if args.padded:
            padded_case(args)
        return
    rng = np.random.default_rng(20240611)
    ours(rng.random((2000, 3)))  # compile
    vf.voronoi3d(rng.random((2000, 3)), BOX, periodic=True)
    rows = []
    print(
        "wall seconds, best of the repeats with the tools taking turns; ratio = ours / theirs; "
        "CPU: user + system seconds, voro++ as a child process; B/cell: peak RSS growth of a "
        "fresh process"
    )
    print(
        f"{'n':>9} {'ours s':>8} {'CPU s':>8} {'1 thr s':>8} {'voro++ s':>9} {'CPU s':>8} "
        f"{'ratio':>6} {'CPU r':>6} {'1thr r':>6} {'cells/s':>9} {'periodic':>8} {'CPU s':>8} "
        f"{'freud s':>8} {'CPU s':>8} {'CPU r':>6} {'qhull s':>8} {'B/cell':>7}"
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
            (t, c), (t1, c1), (tv, cv) = alternated(
                [
                    lambda p=p: ours(p),
                    (lambda p=p: single(p)) if args.single else None,
                    voropp_call(p, tmp),
                ],
                args.repeat,
            )
        tp = tf = cp = cf = None
        if not args.no_periodic:
            (tp, cp), (tf, cf) = alternated(
                [
                    lambda p=p: vf.voronoi3d(p, BOX, periodic=True),
                    None if args.no_freud else freud_call(p),
                ],
                args.repeat,
            )
        tq = None if args.no_qhull or n > 100000 else qhull_time(p, 1 if n > 10000 else args.repeat)
        mem = peak_per_cell(n)
        rows.append((n, t, c))
        print(
            f"{n:>9} {t:8.3f} {f(c)} {f(t1)} {f(tv):>9} {f(cv)} {ratio(t, tv)} {ratio(c, cv)} "
            f"{ratio(c1, cv)} {n / t:9.0f} {f(tp)} {f(cp)} {f(tf)} {f(cf)} {ratio(cp, cf)} "
            f"{f(tq)} {mem:7.0f}",
            flush=True,
        )
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak RSS of this process: {rss:.0f} MiB; load average {os.getloadavg()}")
    if len(rows) >= 2:
        (n0, t0, c0), (n1, t1, c1) = rows[0], rows[-1]
        print(
            f"cost slope {np.log(t1 / t0) / np.log(n1 / n0):.2f} (wall), "
            f"{np.log(c1 / c0) / np.log(n1 / n0):.2f} (CPU) from {n0} to {n1} (1.0 = linear)"
        )
    if args.mesh:
        mesh_case(args)
    if args.clustered:
        clustered_case(args)
    if args.padded:
        padded_case(args)


def padded_case(args):
    """Best-of-repeats CPU per cell of uniform sites, default container against the unit box."""
    n = args.padded
    p = np.random.default_rng(n).random((n, 3))
    vf.voronoi3d(p[:2000], None)  # compile
    res = alternated([lambda: vf.voronoi3d(p, BOX), lambda: vf.voronoi3d(p, None)], args.repeat)
    (tb, cb), (tp, cp) = res
    print(
        f"uniform n={n}: unit box {tb:.3f} s wall, {cb:.3f} s CPU ({1e6 * cb / n:.1f} us/cell); "
        f"default container (padded 10%) {tp:.3f} s wall, {cp:.3f} s CPU "
        f"({1e6 * cp / n:.1f} us/cell, {cp / cb:.2f}x the box); threads {numba.get_num_threads()}; "
        f"load average {os.getloadavg()}",
        flush=True,
    )


def clustered_points(kind, n, seed=5):
    """``n`` sites: ``uniform``, ``sd0.02`` / ``sd0.003`` (20 clusters), ``far`` (see above)."""
    rng = np.random.default_rng(seed)
    if kind == "uniform":
        return rng.random((n, 3))
    if kind == "far":
        tight = 0.5 + 1e-3 * rng.normal(size=(n - 8, 3))
        return np.vstack([tight, 0.5 + 100 * (rng.random((8, 3)) - 0.5)])
    cen = rng.random((20, 3))
    sd = float(kind[2:])
    return np.clip(cen[rng.integers(0, 20, n)] + sd * rng.normal(size=(n, 3)), 0, 1)


def clustered_case(args):
    """Best-of-repeats CPU per cell on clustered inputs against uniform ones (default box)."""
    n = args.clustered
    kinds = ("uniform", "sd0.02", "sd0.003", "far")
    pts = [clustered_points(k, n) for k in kinds]
    vf.voronoi3d(pts[1][:2000], None)  # compile (the k-d search too)
    res = alternated([lambda p=p: vf.voronoi3d(p, None) for p in pts], args.repeat)
    cu = res[0][1]
    for kind, (t, c) in zip(kinds, res, strict=True):
        print(
            f"clustered {kind:>8} n={n}: {t:.3f} s wall, {c:.3f} s CPU, "
            f"{1e6 * c / n:.1f} us/cell CPU ({c / cu:.2f}x uniform)",
            flush=True,
        )
    print(f"load average {os.getloadavg()}")


def mesh_case(args):
    """``args.mesh`` sites uniform in a 20,000-triangle torus's bounding box, best of repeats."""
    import trimesh

    knot = trimesh.creation.torus(
        major_radius=1.0, minor_radius=0.35, major_sections=200, minor_sections=50
    )
    lo, hi = knot.bounds
    p = np.random.default_rng(1).uniform(lo, hi, (args.mesh, 3))
    vf.voronoi3d(p[:500], knot)
    res = []
    ((t, c),) = alternated([lambda: res.append(vf.voronoi3d(p, knot))], args.repeat)
    d = res[-1]
    inside = int(np.count_nonzero(d.volumes > 0))
    err = abs(d.volumes.sum() - knot.volume) / knot.volume
    print(
        f"mesh container ({len(knot.faces)} triangles), {args.mesh} sites in its bounding "
        f"box ({inside} cells inside, {int(d.cut_cells.sum())} cut; volume sum off by "
        f"{err:.1e}): {t:.2f} s wall, {c:.2f} s CPU, "
        f"{args.mesh / t:.0f} cells/s (wall), {args.mesh / c:.0f} cells/s (CPU); "
        f"load average {os.getloadavg()}"
    )


if __name__ == "__main__":
    main()
