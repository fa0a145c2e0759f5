"""SurfaceVoronoi.panels() never drops a cell silently (checker7 R4).

A panel is one flat polygon through a cell's corners. A cell whose boundary has fewer than
3 corners (each half of a 2-site sphere, a lune of a 3-site sphere) or several rings (a band
around a torus's tube) has none: it is listed in ``Panels.missing`` with the reason and a
``MissingPanelWarning`` names it. Every other cell keeps its panel.
"""

import warnings

import numpy as np
import pytest

from voroforge import surface


def _panels(S, n, relax):
    vd = surface.voronoi(S, n, relax=relax, seed=0)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        p = vd.panels()
    msgs = [str(x.message) for x in w if issubclass(x.category, surface.MissingPanelWarning)]
    return vd, p, msgs


@pytest.mark.parametrize(
    "S, n, relax, why",
    [
        (surface.torus(3.0, 0.05), 80, 5, "2 boundary rings"),
        (surface.torus(3.0, 1.0), 8, 5, "2 boundary rings"),
        (surface.sphere(1.0, subdivisions=3), 2, 0, "0 corners"),
        (surface.sphere(1.0, subdivisions=3), 3, 0, "2 corners"),
    ],
    ids=["thin-torus-bands", "torus-bands", "sphere-halves", "sphere-lunes"],
)
def test_cells_without_panel_are_reported(S, n, relax, why):
    vd, p, msgs = _panels(S, n, relax)
    live = np.flatnonzero(vd.areas > 0)
    assert sorted(p.missing) == sorted(set(live) - set(p.ids.tolist()))
    assert len(p.missing) == len(live)  # all of these families: no cell is a polygon
    assert all(why in r for r in p.missing.values())
    assert len(msgs) == 1 and f"{len(p.missing)} of {n} cells have no panel" in msgs[0]


@pytest.mark.parametrize(
    "S, n",
    [(surface.cylinder(1.0, 1.0), 3), (surface.sphere(1.0, subdivisions=3), 60)],
    ids=["cylinder-3", "sphere-60"],
)
def test_every_polygon_cell_has_a_panel(S, n):
    vd, p, msgs = _panels(S, n, 3)
    assert not msgs and p.missing == {}
    assert sorted(p.ids.tolist()) == np.flatnonzero(vd.areas > 0).tolist()
    # flat polygons through the corners: near the curved cells' areas
    rel = np.abs(p.areas() - vd.areas[p.ids]) / vd.areas[p.ids]
    assert rel.max() < (0.3 if n == 3 else 0.1)  # chords of a unit sphere: 3-6% at 60 cells
    solids = p.thicken(0.01)
    assert len(solids) == len(p) and all(m.is_watertight for m in solids)


def test_missing_survives_copies():
    _, p, _ = _panels(surface.sphere(1.0, subdivisions=3), 2, 0)
    assert len(p.missing) == 2 and p._with().missing == p.missing
