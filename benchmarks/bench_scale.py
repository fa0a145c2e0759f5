"""Tiled Voronoi on dask.distributed against one process, same cells, same GeoParquet.

Run from the repository root::

    .venv/bin/python benchmarks/bench_scale.py                       # 1e6 uniform
    .venv/bin/python benchmarks/bench_scale.py --n 1e7 --workers 2   # the issue's figure
    .venv/bin/python benchmarks/bench_scale.py --n 1e8 --only tiled  # the 1e8 run
    .venv/bin/python benchmarks/bench_scale.py --identity --tile-size 1000   # 1e6 identity

Each configuration runs in a fresh child process on the same fixed-seed points, saved once
as a ``.npy`` file (memory-mapped by the workers):

``single``  ``vf.voronoi`` on all points + ``io.parquet.write_cells``: one process.
``serial``  ``scale.voronoi`` on a LocalCluster of 1 worker x 1 thread: the same tiles,
            one after another in one process.
``tiled``   ``scale.voronoi`` on a LocalCluster of ``--workers`` workers x 1 thread.

Wall time (end to end: input read, tiles, files, metadata), cells per second, and the peak
of the summed resident memory of the whole process tree (client, nannies, workers), sampled
every 0.2 s. The machine is shared: read the ratios, not the seconds.
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from common import DISTRIBUTIONS, machine_info, print_table  # noqa: E402

CHILD = textwrap.dedent(
    """
    import json, sys, threading, time
    import numpy as np, psutil
    what, pts_path, out, workers, tile_size = sys.argv[1:6]
    workers = int(workers); tile_size = int(tile_size)
    me = psutil.Process()
    peak = [0]
    cpu = {}  # pid -> last (user + system) seconds seen
    stop = threading.Event()
    def sample():
        while not stop.is_set():
            total = 0
            for p in [me, *me.children(recursive=True)]:
                try:
                    total += p.memory_info().rss
                    c = p.cpu_times()
                    cpu[p.pid] = c.user + c.system
                except psutil.Error:
                    pass
            peak[0] = max(peak[0], total)
            time.sleep(0.2)
    def cpu_now():
        sample_once = {}
        for p in [me, *me.children(recursive=True)]:
            try:
                c = p.cpu_times()
                sample_once[p.pid] = c.user + c.system
            except psutil.Error:
                pass
        return sample_once
    threading.Thread(target=sample, daemon=True).start()
    import voroforge as vf
    from voroforge.io.parquet import write_cells
    vf.voronoi(np.random.default_rng(0).random((100, 2)))  # kernels loaded, as in workers
    info = {}
    if what == "single":
        write_cells(vf.voronoi(np.random.default_rng(0).random((100, 2))), out + ".warm")
        c0 = cpu_now()
        t = time.perf_counter()
        pts = np.load(pts_path)
        bounds = (0.0, 0.0, 1.0, 1.0)
        d = vf.voronoi(pts, bounds)
        write_cells(d, out)
        info["seconds"] = time.perf_counter() - t
        c1 = cpu_now()
        info["cpu_driver"] = c1[me.pid] - c0[me.pid]
        info["cpu_workers"] = 0.0
        info["tiles"] = 1
    else:
        from distributed import Client
        from voroforge import scale
        with scale.local_cluster(workers, dashboard_address=":0") as cl, Client(cl) as c:
            # warm: every kernel of a tile loaded in every worker, as in the one-process run
            warm = np.random.default_rng(0).random((4000, 2))
            scale.voronoi(warm, (0.0, 0.0, 1.0, 1.0), out=out + ".warm", client=c,
                          tiles=2 * workers)
            c0 = cpu_now()
            t = time.perf_counter()
            res = scale.voronoi(pts_path, (0.0, 0.0, 1.0, 1.0), out=out, client=c,
                                tile_size=tile_size, overwrite=True)
            info["seconds"] = time.perf_counter() - t
            c1 = cpu_now()
            info["cpu_driver"] = c1[me.pid] - c0[me.pid]
            info["cpu_workers"] = sum(v - c0.get(k, 0.0) for k, v in c1.items() if k != me.pid)
            info.update(tiles=res.tiles, uncertified=res.uncertified, retried=res.retried,
                        cells=res.cells)
            info["phases"] = res.phases
            info["tile_seconds"] = [i["seconds"] for i in res.tile_info]
            info["tile_loaded"] = [i["loaded_sites"] for i in res.tile_info]
            info["tile_owned"] = [i["owned"] for i in res.tile_info]
    stop.set()
    info["peak_rss"] = peak[0]
    print("RESULT " + json.dumps(info))
    """
)


IDENTITY = textwrap.dedent(
    """
    import json, sys, time
    import numpy as np, pyarrow.parquet as pq
    sys.path.insert(0, sys.argv[5])
    from common import polygon_with_holes
    import voroforge as vf
    from distributed import Client
    from voroforge import scale
    from voroforge.io.parquet import write_cells
    pts_path, boundary, out, tile_size, _, workers = sys.argv[1:7]
    pts = np.load(pts_path)
    dom = polygon_with_holes() if boundary == "polygon" else None
    t = time.perf_counter()
    with scale.local_cluster(int(workers)) as cl, Client(cl) as c:
        res = scale.voronoi(pts_path, dom, out=out + ".tiled", client=c,
                            tile_size=int(tile_size), overwrite=True)
    tiled_s = time.perf_counter() - t
    write_cells(vf.voronoi(pts, dom), out + ".single")
    got = pq.read_table(out + ".tiled").sort_by("site_id")
    ref = pq.read_table(out + ".single")
    diff = {}
    for col in ("site_id", "geometry", "neighbors"):
        a, b = got.column(col).combine_chunks(), ref.column(col).combine_chunks()
        diff[col] = 0 if a.equals(b) else sum(
            x != y for x, y in zip(a.to_pylist(), b.to_pylist()))
    def bits(table, col, field=None):
        arr = table.column(col).combine_chunks()
        arr = arr.field(field) if field else arr
        return arr.to_numpy(zero_copy_only=False).view(np.int64)
    diff["area"] = int((bits(got, "area") != bits(ref, "area")).sum())
    diff["bbox"] = int(sum((bits(got, "bbox", f) != bits(ref, "bbox", f)).sum()
                           for f in ("xmin", "ymin", "xmax", "ymax")))
    print("RESULT " + json.dumps({"tiles": res.tiles, "retried": res.retried,
          "uncertified": res.uncertified, "cells": res.cells, "rows": ref.num_rows,
          "seconds": tiled_s, "diff": diff}))
    """
)


def identity(args) -> None:
    """The 1e6 identity checks: uniform, clustered, grid, polygon with holes, bit for bit."""
    import numpy as np

    n = int(args.n)
    print(machine_info())
    rows = []
    for name in ("uniform", "clustered", "grid", "polygon"):
        work = Path(tempfile.mkdtemp(prefix="bench_scale_id_"))
        try:
            pts = DISTRIBUTIONS["uniform" if name == "polygon" else name](n)
            np.save(work / "points.npy", pts)
            boundary = "polygon" if name == "polygon" else "none"
            cmd = [sys.executable, "-c", IDENTITY, str(work / "points.npy"), boundary]
            cmd += [str(work / "out"), str(args.tile_size), str(HERE), str(args.workers)]
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
            line = [x for x in proc.stdout.splitlines() if x.startswith("RESULT ")]
            if not line:
                raise RuntimeError(f"{name} failed:\n{proc.stderr[-3000:]}")
            r = json.loads(line[0][7:])
            same = all(v == 0 for v in r["diff"].values()) and r["cells"] == r["rows"]
            rows.append(
                [
                    name,
                    f"{len(pts):,}",
                    r["tiles"],
                    r["retried"],
                    r["uncertified"],
                    f"{r['seconds']:.1f}",
                    "identical" if same else json.dumps(r["diff"]),
                ]
            )
        finally:
            shutil.rmtree(work, ignore_errors=True)
    print_table(
        ["input", "sites", "tiles", "recomputed", "uncertified", "tiled s", "against one process"],
        rows,
        title=f"scale identity, tile size {args.tile_size}, {args.workers} workers",
    )


def run_child(what, pts_path, out, workers, tile_size, timeout):
    cmd = [sys.executable, "-c", CHILD, what, str(pts_path), str(out), str(workers), str(tile_size)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    for line in proc.stdout.splitlines():
        if line.startswith("RESULT "):
            return json.loads(line[7:])
    raise RuntimeError(f"{what} failed:\n{proc.stderr[-3000:]}")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=float, default=1e6)
    parser.add_argument("--dist", default="uniform", choices=sorted(DISTRIBUTIONS))
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--tile-size", type=int, default=250_000)
    parser.add_argument("--only", default="single,serial,tiled")
    parser.add_argument("--timeout", type=float, default=3600)
    parser.add_argument("--json", help="also write the results here")
    parser.add_argument(
        "--identity",
        action="store_true",
        help="check the tiled output against one process, bit for bit (uniform, clustered, "
        "grid, polygon with holes) instead of timing",
    )
    args = parser.parse_args(argv)
    if args.identity:
        identity(args)
        return
    n = int(args.n)
    print(machine_info())
    work = Path(tempfile.mkdtemp(prefix="bench_scale_"))
    try:
        import numpy as np

        pts_path = work / "points.npy"
        if n <= 2 * 10**7:
            np.save(pts_path, DISTRIBUTIONS[args.dist](n))
        else:  # written in slices: the generator would need the whole array at once
            mm = np.lib.format.open_memmap(pts_path, mode="w+", dtype=np.float64, shape=(n, 2))
            step = 10**7
            for a in range(0, n, step):
                mm[a : a + step] = DISTRIBUTIONS[args.dist](min(step, n - a), seed=a + 1)
            mm.flush()
            del mm
        results = {}
        for what in args.only.split(","):
            workers = 1 if what == "serial" else args.workers
            out = work / f"{what}.parquet"
            t = time.perf_counter()
            results[what] = run_child(what, pts_path, out, workers, args.tile_size, args.timeout)
            results[what]["wall"] = time.perf_counter() - t
            results[what]["workers"] = workers if what != "single" else 1
            for p in (out, Path(f"{out}.warm")):
                shutil.rmtree(p, ignore_errors=True) if p.is_dir() else p.unlink(missing_ok=True)
        single = results.get("single", {}).get("seconds")
        serial = results.get("serial", {}).get("seconds")
        rows = []
        for what, r in results.items():
            rows.append(
                [
                    what,
                    f"{n:.0e}",
                    r.get("tiles", 1),
                    r["workers"],
                    f"{r['seconds']:.1f}",
                    f"{n / r['seconds']:,.0f}",
                    f"{single / r['seconds']:.2f}" if single else "-",
                    f"{serial / r['seconds']:.2f}" if serial else "-",
                    f"{r['peak_rss'] / 2**30:.2f}",
                    f"{r['cpu_driver']:.1f}",
                    f"{r['cpu_workers']:.1f}",
                    r.get("uncertified", "-"),
                    r.get("retried", "-"),
                ]
            )
        print_table(
            [
                "run",
                "n",
                "tiles",
                "workers",
                "s",
                "cells/s",
                "single/run",
                "serial/run",
                "peak GiB",
                "cpu driver",
                "cpu workers",
                "uncertified",
                "retried",
            ],
            rows,
            title=f"scale: {args.dist}, tile size {args.tile_size}",
        )
        for what, r in results.items():
            if "tile_seconds" in r:
                ts = np.array(r["tile_seconds"])
                loaded = np.array(r["tile_loaded"]) / np.maximum(np.array(r["tile_owned"]), 1)
                print(
                    f"{what}: per tile {np.median(ts):.2f} s median, {ts.max():.2f} s max; "
                    f"loaded/owned sites {np.median(loaded):.3f} median; phases "
                    + ", ".join(f"{k} {v:.1f} s" for k, v in r["phases"].items())
                )
        if args.json:
            Path(args.json).write_text(json.dumps(results, indent=1))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
