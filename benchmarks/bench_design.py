"""Parametric design: a 2000-cell laser panel, Poisson-disk seeds and unique edges.

Run from the repository root::

    .venv/bin/python benchmarks/bench_design.py
    .venv/bin/python benchmarks/bench_design.py --figures docs   # only the README figure

Each line times ours and a plain reference in the same process (best of N, warm) and prints
the ratio:

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
from pathlib import Path

import numpy as np
import shapely
from scipy.spatial import cKDTree
from scipy.stats import qmc

sys.path.insert(0, str(Path(__file__).parent))
import voroforge as vf  # noqa: E402
from voroforge import io as vio  # noqa: E402
from voroforge.design import attractors, boundary, cellops, populate  # noqa: E402

from common import best_of, machine_info, print_table  # noqa: E402

PANEL = boundary.rectangle(600, 400)


def seeds_2000():
    # radius chosen so the panel holds about 2000 Poisson-disk seeds
    return populate.poisson(PANEL, 8.9, seed=1)


def ours_panel(pts, tmp):
    d = vf.voronoi(pts, PANEL)
    field = attractors.PointAttractor([[200, 200]], radius=300.0)
    web = attractors.remap(field(d.centroids), 4.0, 1.5)
    holes = cellops.fillet(cellops.inset(d.cells, web / 2), 2.0)
    part = cellops.frame(PANEL, cellops.openings(holes, cellops.by_area(holes, min=5.0)))
    edges = cellops.explode(d)
    write_dxf = getattr(vio, "write_dxf", None)
    if write_dxf is not None:
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


def main():
    print(machine_info())

    pts = seeds_2000()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        ours_panel(pts, tmp)  # warm-up (numba caches, GEOS)
        reference_panel(pts, tmp)
        t_ours = best_of(lambda: ours_panel(pts, tmp), 5)
        t_ref = best_of(lambda: reference_panel(pts, tmp), 5)
        part, edges = ours_panel(pts, tmp)
        ref_part, _ = reference_panel(pts, tmp)
    dxf = "yes" if hasattr(vio, "write_dxf") else "no"
    rows.append(
        [
            f"panel {len(pts)} cells (dxf: {dxf})",
            f"{t_ours:.3f}",
            f"{t_ref:.3f}",
            f"{t_ref / t_ours:.2f}x",
        ]
    )
    same = abs(part.area - ref_part.area) / ref_part.area

    t_seed = best_of(seeds_2000, 3)
    rows.append([f"  seeds: poisson r=8.9 mm ({len(pts)})", f"{t_seed:.3f}", "", ""])

    r = 0.02
    ours = populate.poisson(boundary.rectangle(1, 1), r, seed=1)
    ref = qmc.PoissonDisk(d=2, radius=r, seed=1).fill_space()
    t_p = best_of(lambda: populate.poisson(boundary.rectangle(1, 1), r, seed=1), 3)
    t_q = best_of(lambda: qmc.PoissonDisk(d=2, radius=r, seed=1).fill_space(), 3)
    rows.append([f"poisson r={r} unit square", f"{t_p:.3f}", f"{t_q:.3f}", f"{t_q / t_p:.2f}x"])

    d = vf.voronoi(pts, PANEL)
    t_e = best_of(lambda: cellops.explode(d), 5)
    t_u = best_of(lambda: shapely.union_all(shapely.boundary(d.cells)), 5)
    rows.append(["explode (unique edges)", f"{t_e:.3f}", f"{t_u:.3f}", f"{t_u / t_e:.2f}x"])
    print_table(["case", "ours s", "reference s", "speed-up"], rows, title="design")
    print(f"\npanel: frame area ours vs reference differs by {same:.2e} (relative)")
    print(
        f"poisson: ours {len(ours)} points, largest gap {gap(ours):.4f}; "
        f"scipy {len(ref)} points, largest gap {gap(ref):.4f} (radius {r})"
    )
    e_len = np.linalg.norm(edges[:, 1] - edges[:, 0], axis=1).sum()
    print(
        f"explode: {len(edges)} edges, length {e_len:.3f} mm; GEOS noded length "
        f"{shapely.length(shapely.union_all(shapely.boundary(d.cells))):.3f} mm"
    )


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
