"""CVT relaxation, L-BFGS and capacity fitting, with a plain reference Lloyd side by side.

Run from the repository root::

    .venv/bin/python benchmarks/bench_lloyd.py                 # all figures
    .venv/bin/python benchmarks/bench_lloyd.py --long          # also 1000 Lloyd iterations
    .venv/bin/python benchmarks/bench_lloyd.py --figures docs  # also write the README's PNGs

The reference Lloyd is written here the plain way: ``scipy.spatial.Voronoi`` of the sites
plus four far mirror points, every region clipped to the square with shapely, sites moved
to ``shapely.centroid``. Both run on the same 1000 fixed-seed sites in the unit square.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import shapely
from scipy.spatial import Voronoi

sys.path.insert(0, str(Path(__file__).parent))
import voroforge as vf  # noqa: E402

from common import best_of, machine_info, print_table  # noqa: E402

SQUARE = shapely.box(0.0, 0.0, 1.0, 1.0)


def reference_cells(pts: np.ndarray) -> np.ndarray:
    """Voronoi cells clipped to the unit square, from Qhull regions and a shapely clip."""
    far = np.array([[-10.0, -10.0], [11.0, -10.0], [11.0, 11.0], [-10.0, 11.0]])
    vor = Voronoi(np.vstack((pts, far)))
    polys = []
    for i in range(len(pts)):
        region = vor.regions[vor.point_region[i]]
        polys.append(shapely.Polygon(vor.vertices[region]))
    return shapely.intersection(np.array(polys, dtype=object), SQUARE)


def reference_lloyd(pts: np.ndarray, iterations: int) -> tuple[np.ndarray, np.ndarray]:
    """Plain Lloyd: ``iterations`` steps; returns the sites and the final cells."""
    z = pts.copy()
    for _ in range(iterations):
        cells = reference_cells(z)
        z = shapely.get_coordinates(shapely.centroid(cells))
    return z, reference_cells(z)


def side_counts(cells) -> np.ndarray:
    """Number of edges longer than 1e-9 of each cell (ring vertices that are not repeats)."""
    out = np.zeros(len(cells), dtype=np.int64)
    for i, c in enumerate(cells):
        xy = shapely.get_coordinates(shapely.get_exterior_ring(c))
        seg = np.hypot(*np.diff(xy, axis=0).T)
        out[i] = int((seg > 1e-9).sum())
    return out


def hexagon_share(cells) -> tuple[float, int]:
    """Share of hexagons among cells not touching the square's boundary, and that count."""
    edge = SQUARE.exterior
    inner = np.array([not shapely.dwithin(c, edge, 1e-9) for c in cells])
    sides = side_counts(np.asarray(cells, dtype=object)[inner])
    return float((sides == 6).mean()), int(inner.sum())


def lloyd_vs_reference(pts, long: bool):
    print("\n## Lloyd: hexagon share vs a plain reference Lloyd (scipy Voronoi + shapely)")
    rows = []
    runs = [200, 1000] if long else [200]
    results = {}
    for iters in runs:
        t = time.perf_counter()
        r = vf.lloyd(pts, (0, 0, 1, 1), iterations=iters)
        t_vf = time.perf_counter() - t
        t = time.perf_counter()
        _, ref_cells = reference_lloyd(pts, iters)
        t_ref = time.perf_counter() - t
        share, inner = hexagon_share(r.diagram.cells)
        ref_share, ref_inner = hexagon_share(ref_cells)
        rises = int((np.diff(r.energy) > 0).sum())
        rows.append(
            [
                iters,
                f"{share:.1%} of {inner}",
                f"{ref_share:.1%} of {ref_inner}",
                f"{t_vf:.2f} s",
                f"{t_ref:.2f} s",
                f"{t_ref / t_vf:.1f}x",
                f"{rises} (max rise {max(np.diff(r.energy).max(), 0):.1e})",
            ]
        )
        results[iters] = r
    print_table(
        [
            "iterations",
            "vf hexagons",
            "reference hexagons",
            "vf time",
            "reference time",
            "speed-up",
            "energy increases",
        ],
        rows,
    )
    return results[200]


def lbfgs_vs_lloyd(pts, lloyd200):
    print("\n## L-BFGS (method='lbfgs') time to reach the energy of 200 Lloyd iterations")
    target = lloyd200.energy[-1]
    quasi = vf.lloyd(pts, (0, 0, 1, 1), iterations=200, method="lbfgs")
    reached = np.flatnonzero(quasi.energy <= target)
    if not len(reached):
        print(f"L-BFGS did not reach {target:.6e} in 200 iterations ({quasi.energy[-1]:.6e})")
        return quasi
    k = int(reached[0])
    t_lloyd = best_of(lambda: vf.lloyd(pts, (0, 0, 1, 1), iterations=200), 3)
    t_quasi = best_of(lambda: vf.lloyd(pts, (0, 0, 1, 1), iterations=k, method="lbfgs"), 3)
    check = vf.lloyd(pts, (0, 0, 1, 1), iterations=k, method="lbfgs").energy[-1]
    print_table(
        ["solver", "iterations", "energy", "time (best of 3)", "vs Lloyd"],
        [
            ["Lloyd", 200, f"{target:.7e}", f"{t_lloyd:.3f} s", "1"],
            ["L-BFGS", k, f"{check:.7e}", f"{t_quasi:.3f} s", f"{t_quasi / t_lloyd:.2f}x"],
            ["L-BFGS", 200, f"{quasi.energy[-1]:.7e}", "", ""],
        ],
    )
    return quasi


def iteration_cost(n: int, rounds: int = 5):
    print(f"\n## One Lloyd iteration vs one vf.voronoi call, {n} uniform points")
    pts = np.random.default_rng(1).random((n, 2))
    z = vf.lloyd(pts, (0, 0, 1, 1), iterations=1).points  # warm up
    steps, calls = [], []
    for _ in range(rounds):  # interleaved, so both sides see the same machine load
        r = vf.lloyd(z, (0, 0, 1, 1), iterations=3)
        steps.extend(np.diff(r.elapsed).tolist())  # diagram + moments + move, per iteration
        calls.append(best_of(lambda z=r.points: vf.voronoi(z, (0, 0, 1, 1)), 1))
    step_min, call_min = min(steps), min(calls)
    step_med, call_med = float(np.median(steps)), float(np.median(calls))
    print_table(
        ["statistic", f"Lloyd iteration ({len(steps)})", f"vf.voronoi ({len(calls)})", "ratio"],
        [
            ["min", f"{step_min:.3f} s", f"{call_min:.3f} s", f"{step_min / call_min:.2f}x"],
            ["median", f"{step_med:.3f} s", f"{call_med:.3f} s", f"{step_med / call_med:.2f}x"],
        ],
    )


def power_scale(n: int):
    """``vf.power`` against ``vf.voronoi`` and Qhull's 3D hull alone (informational)."""
    from scipy.spatial import ConvexHull

    print(f"\n## vf.power vs vf.voronoi, {n} uniform sites, weights uniform in [0, 1e-6)")
    pts = np.random.default_rng(0).random((n, 2))
    w = np.random.default_rng(1).random(n) * 1e-6
    vf.power(pts[:100], w[:100], (0, 0, 1, 1))  # warm up
    lift = np.column_stack((pts - 0.5, ((pts - 0.5) ** 2).sum(axis=1) - w))
    t_pow = best_of(lambda: vf.power(pts, w, (0, 0, 1, 1)), 3)
    t_vor = best_of(lambda: vf.voronoi(pts, (0, 0, 1, 1)), 3)
    t_hull = best_of(lambda: ConvexHull(lift), 3)
    print_table(
        ["vf.power", "vf.voronoi", "ratio", "Qhull 3D hull alone"],
        [[f"{t_pow:.3f} s", f"{t_vor:.3f} s", f"{t_pow / t_vor:.2f}x", f"{t_hull:.3f} s"]],
    )


def power_fit_bench(n: int):
    print(f"\n## power_fit: {n} cells, equal and 1:4 target areas in the unit square")
    pts = np.random.default_rng(2).random((n, 2))
    rows = []
    for name, raw in [
        ("equal", np.ones(n)),
        ("1:4 by x", 1.0 + 3.0 * (pts[:, 0] > 0.5)),
    ]:
        target = raw / raw.sum()
        vf.power_fit(pts[:100], np.full(100, 0.01), (0, 0, 1, 1))  # warm up
        t = best_of(lambda target=target: vf.power_fit(pts, target, (0, 0, 1, 1)), 3)
        d = vf.power_fit(pts, target, (0, 0, 1, 1))
        err = float(np.max(np.abs(d.areas - target) / target))
        rows.append([name, f"{t:.3f} s", f"{err:.1e}"])
    print_table(["targets", "time (best of 3)", "max relative area error"], rows)


def figures(pts, lloyd200, quasi, out: Path):
    """Before/after PNG and the energy history, drawn with pillow."""
    from PIL import Image, ImageDraw

    from voroforge.io.png import render_image

    def colours(cells):
        sides = side_counts(cells)
        table = {5: (120, 160, 220), 6: (236, 236, 230), 7: (240, 170, 110)}
        return [table.get(int(s), (200, 110, 140)) for s in sides]

    before = vf.voronoi(pts, (0, 0, 1, 1))
    panels = []
    for d in (before, lloyd200.diagram):
        cells = d.cells
        img = render_image(
            cells, size=460, colors=colours(cells), sites=d.sites, site_radius=1.2, supersample=2
        )
        panels.append(img.convert("RGB"))
    w, h = panels[0].size
    both = Image.new("RGB", (2 * w + 20, h + 30), "white")
    both.paste(panels[0], (0, 30))
    both.paste(panels[1], (w + 20, 30))
    draw = ImageDraw.Draw(both)
    draw.text((10, 8), "1000 random sites", fill=(0, 0, 0))
    draw.text((w + 30, 8), "after 200 Lloyd iterations (light: hexagons)", fill=(0, 0, 0))
    out.mkdir(parents=True, exist_ok=True)
    both.quantize(colors=32).save(out / "lloyd_before_after.png", optimize=True)

    # energy plot: log energy above the final L-BFGS value, per iteration
    width, height, pad = 640, 360, 50
    img = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(img)
    # relative gap to the lowest energy a long L-BFGS run finds (clamped at 1e-9)
    best = vf.lloyd(pts, (0, 0, 1, 1), iterations=600, method="lbfgs").energy.min()
    floor = min(best, quasi.energy.min(), lloyd200.energy.min())
    series = [
        ("Lloyd", lloyd200.energy, (40, 90, 180)),
        ("L-BFGS", quasi.energy, (200, 80, 40)),
    ]
    gaps = [np.log10(np.maximum((e - floor) / floor, 1e-9)) for _, e, _ in series]
    lo = min(g.min() for g in gaps)
    hi = max(g.max() for g in gaps)
    x_max = max(len(e) for _, e, _ in series) - 1

    def xy(i, v):
        return (
            pad + (width - 2 * pad) * i / x_max,
            height - pad - (height - 2 * pad) * (v - lo) / (hi - lo),
        )

    draw.rectangle([pad, pad, width - pad, height - pad], outline=(0, 0, 0))
    for k, ((name, _, col), g) in enumerate(zip(series, gaps, strict=True)):
        draw.line([xy(i, v) for i, v in enumerate(g)], fill=col, width=2)
        draw.text((width - pad - 90, pad + 10 + 14 * k), name, fill=col)
    for v in range(int(np.ceil(lo)), int(np.floor(hi)) + 1):
        _, y = xy(0, v)
        draw.line([pad - 4, y, pad, y], fill=(0, 0, 0))
        draw.text((4, y - 6), f"1e{v}", fill=(0, 0, 0))
    for i in range(0, x_max + 1, 50):
        x, _ = xy(i, lo)
        draw.line([x, height - pad, x, height - pad + 4], fill=(0, 0, 0))
        draw.text((x - 8, height - pad + 8), str(i), fill=(0, 0, 0))
    draw.text(
        (pad, 12),
        "CVT energy, 1000 sites: (E - E*) / E*, E* = best of 600 L-BFGS iterations",
        fill=(0, 0, 0),
    )
    draw.text((width // 2 - 20, height - 18), "iteration", fill=(0, 0, 0))
    img.quantize(colors=16).save(out / "lloyd_energy.png", optimize=True)
    print(f"\nwrote {out / 'lloyd_before_after.png'} and {out / 'lloyd_energy.png'}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--long", action="store_true", help="also run 1000 Lloyd iterations")
    ap.add_argument("--big", type=int, default=100_000, help="size of the per-iteration test")
    ap.add_argument("--fit", type=int, default=10_000, help="cells in the power_fit test")
    ap.add_argument("--figures", type=Path, default=None, help="write the PNGs here")
    args = ap.parse_args(argv)
    print(machine_info())
    pts = np.random.default_rng(0).random((1000, 2))
    vf.lloyd(pts, (0, 0, 1, 1), iterations=2)
    vf.lloyd(pts, (0, 0, 1, 1), iterations=2, method="lbfgs")
    lloyd200 = lloyd_vs_reference(pts, args.long)
    quasi = lbfgs_vs_lloyd(pts, lloyd200)
    iteration_cost(args.big)
    power_fit_bench(args.fit)
    if args.figures is not None:
        figures(pts, lloyd200, quasi, args.figures)


if __name__ == "__main__":
    main()
