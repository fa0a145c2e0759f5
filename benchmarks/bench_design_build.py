"""Design pipeline benchmark: a 2000-cell laser panel with inset, fillet and DXF export.

Times ``voroforge.design.build.build`` on a 1000 x 700 mm panel with 2000 random seeds,
2 mm webs and 1 mm fillets, written as DXF (closed LWPOLYLINEs, fillets as bulge arcs),
against a plain reference doing the same work with the usual tools: scipy's Voronoi
(mirrored sites for bounded cells) clipped with shapely, the same shapely buffers for inset
and fillet, boundary minus union, and ezdxf with every chord written as a line segment.
Both run in one process, warm, best of N; wall-clock and CPU (process) time are printed,
with the ratio. Run from the repository root:

    NUMBA_NUM_THREADS=1 .venv/bin/python benchmarks/bench_design_build.py [--cells N] [--repeat K]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import shapely

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "src"))

from voroforge.design.build import build  # noqa: E402


def design(cells: int) -> dict:
    return {
        "design": {"name": "bench", "seed": 1},
        "boundary": {"shape": "rectangle", "width": 1000, "height": 700},
        "seeds": {"method": "random", "count": cells},
        "cells": {"web": 2, "fillet": 1},
        "output": {"formats": ["dxf"]},
    }


def reference(cells: int, out: Path) -> Path:
    """The same panel with scipy + shapely + ezdxf, no arc detection."""
    import ezdxf
    from scipy.spatial import Voronoi

    from voroforge.design.populate import random as random_points

    w, h = 1000.0, 700.0
    box = shapely.box(0, 0, w, h)
    pts = random_points(box, cells, seed=1)
    # Mirror the sites in the four sides so every original cell is bounded.
    mirrored = [
        pts,
        pts * [-1, 1],
        pts * [1, -1],
        pts * [-1, 1] + [2 * w, 0],
        pts * [1, -1] + [0, 2 * h],
    ]
    vor = Voronoi(np.concatenate(mirrored))
    polys = []
    for i in range(len(pts)):
        region = vor.regions[vor.point_region[i]]
        polys.append(shapely.Polygon(vor.vertices[region]))
    cells_arr = shapely.intersection(np.asarray(polys, dtype=object), box)
    holes = shapely.buffer(cells_arr, -1.0, join_style="mitre")
    holes = shapely.buffer(shapely.buffer(holes, -1.0, quad_segs=16), 1.0, quad_segs=16)
    holes = holes[~shapely.is_empty(holes)]
    frame = box.difference(shapely.union_all(holes))
    doc = ezdxf.new("R2000", setup=False, units=4)
    msp = doc.modelspace()
    doc.layers.add("CUT", color=1)
    for poly in shapely.get_parts(frame):
        for ring in (poly.exterior, *poly.interiors):
            msp.add_lwpolyline(
                np.asarray(ring.coords)[:-1].tolist(), close=True, dxfattribs={"layer": "CUT"}
            )
    path = out / "reference.dxf"
    doc.saveas(path)
    return path


def timed(fn, repeat: int) -> tuple[float, float]:
    best_wall, best_cpu = float("inf"), float("inf")
    for _ in range(repeat):
        t, c = time.perf_counter(), time.process_time()
        fn()
        best_wall = min(best_wall, time.perf_counter() - t)
        best_cpu = min(best_cpu, time.process_time() - c)
    return best_wall, best_cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cells", type=int, default=2000)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        spec = design(args.cells)
        ours = lambda: build(spec, out)  # noqa: E731
        ref = lambda: reference(args.cells, out)  # noqa: E731
        ours()  # warm: numba kernels compiled, ezdxf imported
        ref()
        ow, oc = timed(ours, args.repeat)
        rw, rc = timed(ref, args.repeat)
        import ezdxf

        doc = ezdxf.readfile(out / "bench.dxf")
        ents = list(doc.modelspace())
        arcs = sum(sum(1 for b in e.get_points("b") if b[0]) for e in ents)
        ref_ents = list(ezdxf.readfile(out / "reference.dxf").modelspace())
        size_ours = (out / "bench.dxf").stat().st_size
        size_ref = (out / "reference.dxf").stat().st_size
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(
        f"{args.cells}-cell panel, inset + fillet + DXF, best of {args.repeat} "
        f"(load average {load:.1f}, {os.cpu_count()} CPUs)"
    )
    print(f"{'':26} {'wall s':>8} {'cpu s':>8} {'entities':>9} {'arcs':>6} {'DXF kB':>7}")
    print(
        f"{'voroforge build':26} {ow:8.3f} {oc:8.3f} {len(ents):9d} {arcs:6d} "
        f"{size_ours // 1024:7d}"
    )
    print(
        f"{'scipy+shapely+ezdxf ref':26} {rw:8.3f} {rc:8.3f} {len(ref_ents):9d} {0:6d} "
        f"{size_ref // 1024:7d}"
    )
    print(
        f"ratio reference / ours: wall {rw / ow:.2f}x, cpu {rc / oc:.2f}x; "
        f"target <= 1 s warm: {'met' if ow <= 1.0 else 'not met'} (wall), "
        f"{'met' if oc <= 1.0 else 'not met'} (cpu)"
    )


if __name__ == "__main__":
    main()
