"""Peak memory (RSS) of clipped Voronoi diagrams, each workload in a fresh child process.

Each workload runs as ``python -c ...`` and prints its own peak resident set size
(``resource.getrusage(RUSAGE_SELF).ru_maxrss``, KiB on Linux), so every number is the high
water mark of one workload alone, interpreter and imports included.

Workloads (``--what``):

``baseline``  import voroforge and generate ``uniform(n)``: the floor the others share.
``kernels``   baseline plus one 100-point ``vf.voronoi(...).cells``: numba kernels loaded
              (from the cache, or compiled), so the rows below minus this one are the
              memory that grows with ``n``.
``diagram``   ``vf.voronoi(points, (0, 0, 1, 1))``, cells not materialised.
``cells``     the same plus ``d.cells`` (n shapely polygons): what most users hold.
``shapely``   reference: GEOS ``voronoi_polygons(extend_to=box)`` + ``intersection``.
``voronoi3d`` ``vf.voronoi3d`` of ``n`` uniform 3D points in the unit box with neighbours.
``faces3d``   the same plus the unique faces (the issue's "per cell with faces" figure).

The 3D rows' points (``n`` x 24 B) are made in the workload, so they count in its peak
(as in ``bench_3d.py``'s B/cell); their B/point is over the ``kernels3d`` row (a 2,000-site
3D call with faces: the 3D kernels loaded), when it was run.

Examples::

    python benchmarks/memory.py                 # n = 1e6: baseline, kernels, cells
    python benchmarks/memory.py --n 1e5 --what baseline,kernels,diagram,cells,shapely
    python benchmarks/memory.py --n 1e7         # slow: minutes and several GiB
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import textwrap
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from common import command_line, machine_info  # noqa: E402

CHILD = textwrap.dedent(
    """
    import json, resource, sys, time
    sys.path.insert(0, {here!r})
    from common import uniform
    import voroforge as vf
    import shapely
    n, what = {n}, {what!r}
    points = uniform(n) if not what.endswith("3d") else None
    if what.endswith("3d"):
        import numpy as np

        small = vf.voronoi3d(np.random.default_rng(0).random((2000, 3)), (0, 0, 0, 1, 1, 1))
        small.neighbors, small.faces
        del small
    t0 = time.perf_counter()
    if what in ("voronoi3d", "faces3d"):
        d = vf.voronoi3d(np.random.default_rng(n).random((n, 3)), (0, 0, 0, 1, 1, 1))
        d.neighbors
        if what == "faces3d":
            d.faces
    elif what == "kernels":
        small = vf.voronoi(uniform(100, seed=1), (0.0, 0.0, 1.0, 1.0)).cells
    elif what == "diagram":
        d = vf.voronoi(points, (0.0, 0.0, 1.0, 1.0))
    elif what == "cells":
        d = vf.voronoi(points, (0.0, 0.0, 1.0, 1.0))
        cells = d.cells
        assert len(cells) == n
    elif what == "shapely":
        box = shapely.box(0.0, 0.0, 1.0, 1.0)
        parts = shapely.get_parts(
            shapely.voronoi_polygons(shapely.multipoints(points), extend_to=box)
        )
        cells = shapely.intersection(parts, box)
        del parts
    seconds = time.perf_counter() - t0
    rss_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(json.dumps({{"maxrss_kib": rss_kib, "seconds": seconds}}))
    """
)

WORKLOADS = (
    "baseline",
    "kernels",
    "diagram",
    "cells",
    "shapely",
    "kernels3d",
    "voronoi3d",
    "faces3d",
)


def run_child(n: int, what: str) -> dict:
    """Run one workload in a fresh interpreter; its JSON line, plus the wall time."""
    code = CHILD.format(here=str(HERE), n=n, what=what)
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        tail = (proc.stderr or proc.stdout).strip().splitlines()[-5:]
        return {"error": f"exit {proc.returncode}: " + " | ".join(tail), "wall": wall}
    result = json.loads(proc.stdout.strip().splitlines()[-1])
    result["wall"] = wall
    return result


def main(argv: list[str] | None = None) -> None:
    """Parse the options, run each workload in its own process and print a table."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", default="1e6", help="number of uniform points (1e7: slow, GiBs)")
    ap.add_argument(
        "--what",
        default="baseline,kernels,cells",
        help="comma-separated workloads: " + ", ".join(WORKLOADS),
    )
    args = ap.parse_args(argv)
    n = int(float(args.n))
    todo = [w.strip() for w in args.what.split(",") if w.strip()]
    bad = [w for w in todo if w not in WORKLOADS]
    if bad:
        ap.error(f"unknown workload(s) {bad}; choose from {list(WORKLOADS)}")

    print("command: " + command_line())
    print(machine_info())
    print(f"\npeak RSS per workload, n = {n:,} uniform points, each in a fresh process")
    print("(the first run of a workload may also compile numba kernels into the cache)")
    base = kern = kern3 = None
    header = (
        f"{'workload':<10} {'peak MiB':>10} {'- baseline':>11} {'- kernels':>10} "
        f"{'B/point':>9} {'run s':>8}"
    )
    print(header)
    print("-" * len(header))
    for what in todo:
        r = run_child(n, what)
        if "error" in r:
            print(f"{what:<10} failed: {r['error']}")
            continue
        mib = r["maxrss_kib"] / 1024.0
        over_base = "-" if base is None or what == "baseline" else f"{mib - base:.1f}"
        uses_vf = what in ("diagram", "cells")
        is3d = what in ("voronoi3d", "faces3d")
        k0 = kern3 if is3d else kern
        over_kern = "-" if k0 is None or not (uses_vf or is3d) else f"{mib - k0:.1f}"
        floor = k0 if k0 is not None and (uses_vf or is3d) else base
        per_point = (
            "-"
            if floor is None or what in ("baseline", "kernels", "kernels3d")
            else f"{(mib - floor) * 2**20 / n:.0f}"
        )
        print(
            f"{what:<10} {mib:>10.1f} {over_base:>11} {over_kern:>10} "
            f"{per_point:>9} {r['seconds']:>8.2f}"
        )
        sys.stdout.flush()
        if what == "baseline":
            base = mib
        elif what == "kernels":
            kern = mib
        elif what == "kernels3d":
            kern3 = mib
    print(
        "B/point = (peak - kernels row) / n for voroforge rows (baseline row when kernels "
        "was not run), (peak - baseline) / n for shapely; run s = the workload alone"
    )


if __name__ == "__main__":
    main()
