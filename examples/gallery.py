"""Rebuild the README gallery: one small PNG per example in docs/gallery/.

Run from the repository root:  .venv/bin/python examples/gallery.py [NAME ...]
(names of examples to rebuild, e.g. ``leaf-venation``; default: all of them).
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from voroforge.design.build import build

ROOT = Path(__file__).resolve().parent.parent
SIZE = 560
SOLID_SIZE = 640  # 3D previews: a little larger, their struts and webs are fine


def tiled(design: Path):
    """The periodic lamp tile's frame drawn 2 x 2 times side by side."""
    import shapely

    from voroforge.design.compute import compute
    from voroforge.design.designfile import load
    from voroforge.io.png import render_image

    spec, base = load(design)
    result = compute(spec, base)
    xmin, ymin, xmax, ymax = result.boundary.bounds
    w, h = xmax - xmin, ymax - ymin
    holes = [
        shapely.affinity.translate(o, dx, dy)
        for dx in (0.0, w)
        for dy in (0.0, h)
        for o in result.openings
    ]
    sheet = shapely.box(xmin, ymin, xmin + 2 * w, ymin + 2 * h)
    frame = sheet.difference(shapely.union_all(holes))
    return render_image([frame], size=SIZE, colors=[(52, 58, 70)], edge_width=0.0)


def main(names=()) -> None:
    """Build every example (or those named) as a small PNG into docs/gallery/."""
    out = ROOT / "docs" / "gallery"
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for design in sorted((ROOT / "examples").glob("*.toml")):
            if names and design.stem not in names:
                continue
            overrides = {
                "output.formats": '["png"]',
                "output.png_size": SIZE,
                "fabrication.report": "false",
            }
            if design.stem.startswith("solid-"):
                overrides["solid.png_size"] = SOLID_SIZE  # the 3D preview's own size key
            target = out / f"{design.stem}.png"
            if design.stem == "lamp-tile":
                tiled(design).save(target)  # 2 x 2 copies: the seams do not show
            else:
                # solid designs also write their mesh: the preview is the PNG
                (png,) = [p for p in build(design, tmp, overrides=overrides) if p.suffix == ".png"]
                shutil.copyfile(png, target)
            print(target.relative_to(ROOT), f"{target.stat().st_size // 1024} kB")


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
