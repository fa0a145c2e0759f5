"""The demo: 300 random sites in an irregular outline with a hole, written as SVG, PNG, GeoJSON."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

__all__ = ["build_demo", "demo_domain", "demo_sites"]


def demo_domain() -> shapely.Polygon:
    """Return an irregular rounded outline inside ``[0, 100]²`` with a rounded-rectangle hole."""
    theta = np.linspace(0.0, 2.0 * np.pi, 240, endpoint=False)
    radius = 42.0 + 4.0 * np.sin(3.0 * theta) + 2.5 * np.cos(5.0 * theta + 0.7)
    outline = np.column_stack((50.0 + radius * np.cos(theta), 50.0 + radius * np.sin(theta)))
    hole = shapely.box(42.0, 40.0, 62.0, 54.0).buffer(5.0, quad_segs=8)
    return shapely.Polygon(outline, [np.asarray(hole.exterior.coords)])


def demo_sites(domain: shapely.Geometry, n: int = 300, seed: int = 7) -> np.ndarray:
    """``n`` uniform random points inside ``domain`` (rejection sampling, reproducible)."""
    rng = np.random.default_rng(seed)
    xmin, ymin, xmax, ymax = domain.bounds
    found = np.zeros((0, 2))
    while len(found) < n:
        cand = rng.uniform((xmin, ymin), (xmax, ymax), size=(2 * n, 2))
        found = np.concatenate((found, cand[shapely.contains_xy(domain, cand[:, 0], cand[:, 1])]))
    return found[:n]


def build_demo(out_dir, *, progress=None) -> list[Path]:
    """Compute the demo diagram and write ``demo.svg``, ``demo.png`` and ``demo.geojson``.

    Parameters
    ----------
    out_dir : str or Path
        Folder for the files; created if missing.
    progress : callable, optional
        Called with the name of each stage (``"computing"``, ``"writing demo.svg"``, ...).

    Returns
    -------
    list of Path
        The files written.
    """
    import voroforge as vf

    from .io import write_geojson, write_png, write_svg

    stage = progress or (lambda name: None)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    domain = demo_domain()
    sites = demo_sites(domain)
    stage(f"computing {len(sites)} Voronoi cells")
    d = vf.voronoi(sites, domain)
    written = []
    for name, writer in (("demo.svg", write_svg), ("demo.png", write_png)):
        stage(f"writing {name}")
        written.append(writer(d.cells, out / name, sites=d.sites, boundary=d.boundary))
    stage("writing demo.geojson")
    written.append(write_geojson(d.cells, out / "demo.geojson", sites=d.sites))
    return written
