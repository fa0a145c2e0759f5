"""The demo: the flagship design, a 600 x 400 mm laser-cut panel, written as SVG, DXF and PNG.

The design is ``examples/laser-panel.toml`` (kept here too, so the demo runs from an installed
package); ``voroforge demo -o out`` builds it like ``voroforge build``.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["FLAGSHIP", "build_demo"]

#: The flagship design file (identical to ``examples/laser-panel.toml``).
FLAGSHIP = """\
# Laser-cut decorative panel, 600 x 400 mm: 3 mm webs, 2 mm fillets on every opening.
# The flagship example (`voroforge demo` builds it): SVG and DXF ready for a laser cutter.
#   voroforge build examples/laser-panel.toml -o out
#   voroforge check examples/laser-panel.toml

[design]
name = "laser-panel"
description = "600 x 400 mm laser-cut Voronoi panel, 3 mm web, 2 mm fillets"
units = "mm"
seed = 7

[boundary]
shape = "rectangle"
width = 600
height = 400
corner_radius = 12         # rounded panel corners
margin = 15                # solid border all round

[seeds]
method = "poisson"
radius = 38                # about 150 openings

[cells]
web = 3                    # 3 mm of material between openings
fillet = 2                 # 2 mm radius on every corner: true arcs in the DXF

[output]
formats = ["svg", "dxf", "png"]
layers = { CUT = "frame" }
kerf = 0.15                # CO2 laser in 3 mm plywood
png_size = 1000

[fabrication]
min_web = 2.5
min_opening = 10
tool_radius = 1.0
"""


def build_demo(out_dir, *, progress=None) -> list[Path]:
    """Build the flagship design and write ``laser-panel.svg``, ``.dxf`` and ``.png``.

    Parameters
    ----------
    out_dir : str or Path
        Folder for the files; created if missing.
    progress : callable, optional
        Called with the name of each stage.

    Returns
    -------
    list of Path
        The files written (SVG with a CUT layer in mm, DXF with fillets as true arcs, PNG).
    """
    import tomllib

    from .design.build import build

    design = tomllib.loads(FLAGSHIP)
    return build(design, out_dir, progress=progress)
