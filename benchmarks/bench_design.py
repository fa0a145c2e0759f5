"""Parametric design: a 2000-cell laser panel, Poisson-disk seeds and unique edges.

Run from the repository root::

    .venv/bin/python benchmarks/bench_design.py
    .venv/bin/python benchmarks/bench_design.py --figures docs   # only the README figure

Each line times ours and a plain reference in the same process (best of N, warm; wall and
process CPU time, as the machine may be shared) and prints the CPU-time ratio:

- panel: 600 x 400 mm, 2000 Poisson-disk seeds, attractor-graded inset, 2 mm fillet, frame,
  unique edges (and DXF export when ``voroforge.io.write_dxf`` exists). Reference: the same
  cell operations written as a per-cell shapely loop.
- poisson: ``populate.poisson`` against ``scipy.stats.qmc.PoissonDisk.fill_space`` in the
  unit square, same radius: time, point count and the largest empty gap (max distance from
  20000 probes to the nearest point; a maximal sampling has it <= radius).
- explode: ``cellops.explode`` against noding all cell outlines with GEOS
  (``shapely.union_all`` of the boundaries), which also yields every edge once.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import shapely
from scipy.spatial import cKDTree
from scipy.stats import qmc

sys.path.insert(0, str(Path(__file__).parent))
import voroforge as vf  # noqa: E402
from voroforge import io as vio  # noqa: E402
from voroforge.design import attractors, boundary, cellops, populate  # noqa: E402

from common import machine_info, print_table  # noqa: E402

PANEL = boundary.rectangle(600, 400)


def seeds_2000():
    # radius chosen so the panel holds about 2000 Poisson-disk seeds
    return populate.poisson(PANEL, 8.9, seed=1)


def ours_panel(pts, tmp, dxf=False):
    d = vf.voronoi(pts, PANEL)
    field = attractors.PointAttractor([[200, 200]], radius=300.0)
    web = attractors.remap(field(d.centroids), 4.0, 1.5)
    holes = cellops.fillet(cellops.inset(d.cells, web / 2), 2.0)
    part = cellops.frame(PANEL, cellops.openings(holes, cellops.by_area(holes, min=5.0)))
    edges = cellops.explode(d)
    write_dxf = getattr(vio, "write_dxf", None)
    if dxf and write_dxf is not None:
        write_dxf([part], Path(tmp) / "panel.dxf")
    return part, edges


def reference_panel(pts, tmp):
    d = vf.voronoi(pts, PANEL)
    field = attractors.PointAttractor([[200, 200]], radius=300.0)
    web = attractors.remap(field(d.centroids), 4.0, 1.5)
    holes = []
    for cell, w in zip(d.cells, web, strict=True):
        h = cell.buffer(-w / 2, join_style="mitre")
        h = h.buffer(-2.0).buffer(2.0).buffer(2.0).buffer(-2.0)
        if not h.is_empty and h.area >= 5.0:
            holes.append(h)
    part = PANEL.difference(shapely.union_all(holes))
    edges = shapely.union_all(shapely.boundary(d.cells))
    return part, edges


def gap(pts, radius_box=1.0):
    probe = np.random.default_rng(7).random((20000, 2)) * radius_box
    return float(cKDTree(pts).query(probe)[0].max())


def best(fn, repeat):
    """Best wall and best CPU (process) seconds of ``repeat`` calls."""
    wall, cpu = [], []
    for _ in range(repeat):
        w0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - w0)
        cpu.append(time.process_time() - c0)
    return min(wall), min(cpu)


def main():
    print(machine_info())
    rows = []

    def row(name, ours, ref=None):
        cells = [name, f"{ours[0]:.3f}", f"{ours[1]:.3f}"]
        if ref is None:
            cells += ["", "", ""]
        else:
            cells += [f"{ref[0]:.3f}", f"{ref[1]:.3f}", f"{ref[1] / ours[1]:.2f}x"]
        rows.append(cells)

    pts = seeds_2000()
    with tempfile.TemporaryDirectory() as tmp:
        ours_panel(pts, tmp, dxf=True)  # warm-up (numba caches, GEOS)
        reference_panel(pts, tmp)
        row(
            f"panel {len(pts)} cells: geometry",
            best(lambda: ours_panel(pts, tmp), 5),
            best(lambda: reference_panel(pts, tmp), 5),
        )
        if hasattr(vio, "write_dxf"):
            row("panel geometry + write_dxf", best(lambda: ours_panel(pts, tmp, dxf=True), 3))
        part, edges = ours_panel(pts, tmp)
        ref_part, _ = reference_panel(pts, tmp)
        d = vf.voronoi(pts, PANEL)
        field = attractors.PointAttractor([[200, 200]], radius=300.0)
        web = attractors.remap(field(d.centroids), 4.0, 1.5)
        ins = cellops.inset(d.cells, web / 2)
        fil = cellops.fillet(ins, 2.0)
        op = cellops.openings(fil, cellops.by_area(fil, min=5.0))
        fr = cellops.frame(PANEL, op)
        stages = [
            ("  voronoi + cells", lambda: vf.voronoi(pts, PANEL).cells),
            ("  inset (graded web)", lambda: cellops.inset(d.cells, web / 2)),
            ("  fillet 2 mm", lambda: cellops.fillet(ins, 2.0)),
            ("  frame", lambda: cellops.frame(PANEL, op)),
            ("  explode", lambda: cellops.explode(d)),
        ]
        if hasattr(vio, "write_dxf"):
            stages.append(
                ("  write_dxf (design-files)", lambda: vio.write_dxf([fr], Path(tmp) / "p.dxf"))
            )
        for name, fn in stages:
            row(name, best(fn, 5))
    same = abs(part.area - ref_part.area) / ref_part.area
    row(f"seeds: poisson r=8.9 mm ({len(pts)})", best(seeds_2000, 3))

    r = 0.02
    unit = boundary.rectangle(1, 1)
    ours = populate.poisson(unit, r, seed=1)
    ref = qmc.PoissonDisk(d=2, radius=r, seed=1).fill_space()
    row(
        f"poisson r={r}, unit square",
        best(lambda: populate.poisson(unit, r, seed=1), 3),
        best(lambda: qmc.PoissonDisk(d=2, radius=r, seed=1).fill_space(), 3),
    )
    row(
        "explode (unique edges)",
        best(lambda: cellops.explode(d), 5),
        best(lambda: shapely.union_all(shapely.boundary(d.cells)), 5),
    )
    print_table(
        ["case", "ours wall", "ours CPU", "ref wall", "ref CPU", "CPU ratio"],
        rows,
        title="design (seconds, best of N, warm)",
    )
    print(f"\npanel: frame area ours vs per-cell reference differs by {same:.2e} (relative)")
    print(
        f"poisson: ours {len(ours)} points, largest gap {gap(ours):.4f}; "
        f"scipy {len(ref)} points, largest gap {gap(ref):.4f} (radius {r})"
    )
    e_len = np.linalg.norm(edges[:, 1] - edges[:, 0], axis=1).sum()
    noded = shapely.length(shapely.union_all(shapely.boundary(d.cells)))
    print(f"explode: {len(edges)} edges, length {e_len:.3f} mm; GEOS noded {noded:.3f} mm")


def figures(out_dir):
    """The README's figure: the README example's panel and a 3-level recursive pattern."""
    from PIL import Image

    from voroforge.design import recursive, relax

    panel = boundary.rectangle(600, 400).difference(boundary.circle(60, center=(450, 200)))
    seeds = relax.relax(populate.hexgrid(panel, 30.0, angle=15.0), panel, iterations=5)
    d = vf.voronoi(seeds, panel)
    sun = attractors.PointAttractor([[150, 150]], radius=350.0)
    web = attractors.remap(sun(d.centroids), 12.0, 3.0)
    holes = cellops.fillet(cellops.inset(d.cells, web / 2), 3.0)
    keep = cellops.by_area(holes, min=40.0)  # skip holes too small to cut
    part = cellops.frame(panel, cellops.openings(holes, keep))
    leaf = boundary.circle(200, center=(0, 0))
    vein = attractors.CurveAttractor([[-200, -120], [0, 0], [150, 140]], radius=160.0)
    levels = recursive.subdivide(
        leaf,
        14,
        depth=2,
        seed=4,
        web=[10.0, 4.0, 1.6],
        relax=3,
        count=[recursive.count_by_field(vein, 3, 9), recursive.count_by_field(vein, 2, 7)],
    )
    pattern = cellops.frame(leaf, cellops.fillet(recursive.leaves(levels), 1.0))
    left = vio.render_image([part], size=600, colors="#c9a26b")
    right = vio.render_image([pattern], size=400, colors="#7a9a5a")
    sheet = Image.new(
        "RGB", (left.width + right.width + 30, max(left.height, right.height)), "white"
    )
    sheet.paste(left, (0, (sheet.height - left.height) // 2))
    sheet.paste(right, (left.width + 30, (sheet.height - right.height) // 2))
    path = Path(out_dir) / "design_pipeline.png"
    sheet.save(path, format="PNG", optimize=True)
    print(path, f"{path.stat().st_size / 1024:.0f} kB")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--figures":
        figures(sys.argv[2])
    else:
        main()
